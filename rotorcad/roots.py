"""The one root search of the package: bracket a sign change, then Brent's method.

Brent's method (:func:`scipy.optimize.brentq`; R. P. Brent, *Algorithms for Minimization without
Derivatives*, 1973, ch. 4) needs an interval whose ends have values of opposite sign. The
callers find it in one of three ways, all through :func:`bracket_root`: on a grid evaluated at
once (``values`` given), by stepping out from a start point (``trials`` an iterator, evaluated
one at a time), or as a given interval (two trials).
"""

from __future__ import annotations

import math
from collections.abc import Callable, Iterable

import numpy as np


def bracket_root(
    f: Callable[[float], float],
    trials: Iterable[float],
    *,
    xtol: float = 1e-12,
    values: Iterable[float] | None = None,
    stop_at_nan: bool = False,
) -> float | None:
    """Root of ``f`` in the first interval of ``trials`` where its value changes sign.

    Parameters
    ----------
    f : callable
        Scalar function of one float.
    trials : iterable of float
        Parameters visited in order (increasing, decreasing or stepping out from a start; may
        be a generator, evaluated only as far as needed).
    xtol : float
        Absolute tolerance of the root, in the unit of the parameter.
    values : iterable of float, optional
        ``f`` at every trial, computed by the caller at once (a vectorised grid); then ``f`` is
        called only by Brent's method.
    stop_at_nan : bool
        Give up at the first value that is not finite (else such trials are stepped over: they
        bracket nothing).

    Returns
    -------
    float or None
        The root, within ``xtol``; None where no neighbouring pair of finite values changes sign
        (a value of zero counts as a change).
    """
    if values is not None:
        x = np.asarray(list(trials) if not isinstance(trials, np.ndarray) else trials, dtype=float)
        v = np.asarray(values, dtype=float)
        finite = np.isfinite(v)
        if stop_at_nan and not finite.all():
            cut = int(np.argmin(finite))
            x, v, finite = x[:cut], v[:cut], finite[:cut]
        ok = finite[:-1] & finite[1:] & (np.sign(v[:-1]) * np.sign(v[1:]) <= 0)
        hits = np.flatnonzero(ok)
        if not len(hits):
            return None
        i = int(hits[0])
        return _brent(f, float(x[i]), float(x[i + 1]), float(v[i]), float(v[i + 1]), xtol)
    previous: tuple[float, float] | None = None
    for t in trials:
        ft = float(f(t))
        if not math.isfinite(ft):
            if stop_at_nan:
                return None
            previous = None
            continue
        if previous is not None and np.sign(previous[1]) * np.sign(ft) <= 0:
            return _brent(f, previous[0], float(t), previous[1], ft, xtol)
        previous = (float(t), ft)
    return None


def _brent(f: Callable[[float], float], a: float, b: float, fa: float, fb: float, xtol: float) -> float:
    """Brent's root in [a, b] (either order) with the end values known (a zero end is the root)."""
    if fa == 0.0:
        return a
    if fb == 0.0:
        return b
    from scipy import optimize  # scipy only when a root is searched

    lo, hi = (a, b) if a <= b else (b, a)
    return float(optimize.brentq(f, lo, hi, xtol=xtol))


__all__ = ["bracket_root"]

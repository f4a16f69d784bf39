"""The one root search of the package: bracket a sign change, then Brent's method.

Brent's method (the steps of :func:`scipy.optimize.brentq`, in Python; R. P. Brent, *Algorithms for Minimization without
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
    """Brent's root in [a, b] (either order) with the end values known (a zero end is the root).

    The steps of :func:`scipy.optimize.brentq` (its C routine ``brentq.c``: inverse quadratic or
    secant step when it is short enough, else bisection; Brent 1973, ch. 4), written here so that a
    root search does not import scipy.optimize (0.3 s). It stops when the bracket is narrower than
    ``xtol + 4 eps |x|`` (scipy's default ``rtol``) or after 100 steps.
    """
    if fa == 0.0:
        return a
    if fb == 0.0:
        return b
    lo, hi = (a, b) if a <= b else (b, a)
    flo, fhi = (fa, fb) if a <= b else (fb, fa)
    rtol = 4 * np.finfo(float).eps
    xpre, xcur, fpre, fcur = lo, hi, flo, fhi
    xblk = fblk = spre = scur = 0.0
    for _ in range(100):
        if fpre != 0 and fcur != 0 and (math.copysign(1.0, fpre) != math.copysign(1.0, fcur)):
            xblk, fblk = xpre, fpre
            spre = scur = xcur - xpre
        if abs(fblk) < abs(fcur):
            xpre, xcur, xblk = xcur, xblk, xcur
            fpre, fcur, fblk = fcur, fblk, fcur
        delta = (xtol + rtol * abs(xcur)) / 2
        sbis = (xblk - xcur) / 2
        if fcur == 0 or abs(sbis) < delta:
            return float(xcur)
        if abs(spre) > delta and abs(fcur) < abs(fpre):
            if xpre == xblk:  # secant
                stry = -fcur * (xcur - xpre) / (fcur - fpre)
            else:  # inverse quadratic
                dpre = (fpre - fcur) / (xpre - xcur)
                dblk = (fblk - fcur) / (xblk - xcur)
                stry = -fcur * (fblk * dblk - fpre * dpre) / (dblk * dpre * (fblk - fpre))
            if 2 * abs(stry) < min(abs(spre), 3 * abs(sbis) - delta):
                spre, scur = scur, stry
            else:
                spre = scur = sbis
        else:
            spre = scur = sbis
        xpre, fpre = xcur, fcur
        xcur += scur if abs(scur) > delta else (delta if sbis > 0 else -delta)
        fcur = float(f(xcur))
    return float(xcur)


__all__ = ["bisect_levels", "bisect_many", "bracket_root"]


def bisect_many(f: Callable[[np.ndarray], np.ndarray], lo: np.ndarray, hi: np.ndarray, xtol: float = 1e-12) -> np.ndarray:
    """Roots of a vectorised ``f`` in many brackets at once, by bisection.

    Parameters
    ----------
    f : callable
        Maps an (n,) array of parameters to the (n,) values of n independent functions.
    lo, hi : (n,) float arrays
        Brackets: the values at their ends differ in sign (or one is zero).
    xtol : float
        Width of the final brackets, in the unit of the parameter.

    Returns
    -------
    (n,) float array
        The middle of every final bracket (NaN where ``lo`` or ``hi`` is not finite).
    """
    lo, hi = np.array(lo, dtype=float), np.array(hi, dtype=float)
    flo = f(lo)
    width = float(np.nanmax(np.abs(hi - lo))) if len(lo) else 0.0
    steps = int(np.ceil(np.log2(max(width, xtol) / xtol))) + 1 if width > 0 else 0
    for _ in range(steps):
        mid = 0.5 * (lo + hi)
        fm = f(mid)
        left = np.sign(fm) * np.sign(flo) <= 0
        hi = np.where(left, mid, hi)
        lo, flo = np.where(left, lo, mid), np.where(left, flo, fm)
    return 0.5 * (lo + hi)


def bisect_levels(
    holds: Callable[[np.ndarray], np.ndarray], inside: float, outside: float, steps: int, levels: int = 5
) -> tuple[float, float]:
    """Bisect where a vectorised predicate stops holding, ``levels`` steps of bisection at a time.

    The same midpoints as ``steps`` steps of plain bisection (the middle of the bracket, taken as
    its new ``inside`` where ``holds`` is true there, as its ``outside`` where not), so the same
    final bracket; but ``holds`` is called once per ``levels`` steps, on the 2**levels - 1
    midpoints those steps may visit (a predicate that costs a vectorised evaluation of the
    envelope per call costs about as much on 31 parameters as on one).

    Parameters
    ----------
    holds : callable
        Maps an (n,) float array of parameters to an (n,) bool array.
    inside, outside : float
        The bracket: ``holds`` is taken as true at ``inside`` and false at ``outside``.
    steps : int
        Steps of bisection.
    levels : int
        Steps evaluated per call of ``holds``.

    Returns
    -------
    inside, outside : float
        The final bracket.
    """
    done = 0
    while done < steps:
        k = min(levels, steps - done)
        size = 2**k - 1
        mids = np.empty(size)
        brackets = [(inside, outside)] * size  # heap order: node i's children 2i+1 (holds) and 2i+2 (not)
        for i in range(size):
            a, b = brackets[i]
            mids[i] = 0.5 * (a + b)
            if 2 * i + 2 < size:
                brackets[2 * i + 1], brackets[2 * i + 2] = (mids[i], b), (a, mids[i])
        ok = np.asarray(holds(mids), dtype=bool)
        i = 0
        for _ in range(k):
            if ok[i]:
                inside, i = float(mids[i]), 2 * i + 1
            else:
                outside, i = float(mids[i]), 2 * i + 2
        done += k
    return inside, outside

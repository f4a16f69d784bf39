"""Slopes of the interpolating cubic spline (not-a-knot ends) at its knots, by numpy alone.

The spline is the one :func:`scipy.interpolate.make_interp_spline` (k = 3) and
:class:`scipy.interpolate.CubicSpline` (``bc_type="not-a-knot"``) make: C2, through every point, with
the third derivative continuous across the second and the second-last knot (de Boor, *A Practical
Guide to Splines*, 1978, ch. IV; the slope equations are those of scipy's ``CubicSpline``). Its
slopes solve a tridiagonal system, solved here by parallel cyclic reduction (Hockney 1965; every
step vectorised, log2 n steps) so that judging a meshline does not import scipy.interpolate
(0.35-0.7 s, which pulls scipy.optimize, scipy.linalg and numpy.f2py).
"""

from __future__ import annotations

import numpy as np


def _shifted(v: np.ndarray, k: int, fill: float) -> tuple[np.ndarray, np.ndarray]:
    """Return (v[i - k], v[i + k]) for every i, ``fill`` where the index falls outside."""
    pad = np.full((k, *v.shape[1:]), fill, dtype=float)
    k = min(k, len(v))
    return np.concatenate([pad[:k], v[: len(v) - k]]), np.concatenate([v[k:], pad[:k]])


def solve_tridiagonal(lower: np.ndarray, diagonal: np.ndarray, upper: np.ndarray, rhs: np.ndarray) -> np.ndarray:
    """Solve a tridiagonal system by parallel cyclic reduction (Hockney 1965).

    Row i reads ``lower[i] x[i-1] + diagonal[i] x[i] + upper[i] x[i+1] = rhs[i]``. Each step
    eliminates the neighbours at distance k with rows i - k and i + k and doubles k; after
    ceil(log2 n) steps every row holds one unknown. Without pivoting: for systems that need none
    (diagonally dominant ones, and the spline's, whose two end rows are reduced first by their
    neighbours).

    Parameters
    ----------
    lower, diagonal, upper : (n,) float arrays
        The three diagonals (``lower[0]`` and ``upper[-1]`` are ignored).
    rhs : (n, m) float array
        Right-hand sides, one per column.

    Returns
    -------
    (n, m) float array
    """
    a = np.asarray(lower, dtype=float).copy()
    b = np.asarray(diagonal, dtype=float).copy()
    c = np.asarray(upper, dtype=float).copy()
    d = np.asarray(rhs, dtype=float).copy()
    a[0], c[-1] = 0.0, 0.0
    k = 1
    while k < len(b):
        a_lo, a_hi = _shifted(a, k, 0.0)
        b_lo, b_hi = _shifted(b, k, 1.0)
        c_lo, c_hi = _shifted(c, k, 0.0)
        d_lo, d_hi = _shifted(d, k, 0.0)
        alpha, gamma = -a / b_lo, -c / b_hi
        a, b, c = alpha * a_lo, b + alpha * c_lo + gamma * a_hi, gamma * c_hi
        d = d + alpha[:, None] * d_lo + gamma[:, None] * d_hi
        k *= 2
    return d / b[:, None]


def spline_slopes(x: np.ndarray, y: np.ndarray) -> np.ndarray:
    """Return dy/dx at the knots of the not-a-knot cubic spline through (x, y).

    Parameters
    ----------
    x : (n,) float array
        Strictly increasing knots, n >= 4.
    y : (n, m) float array
        Values (e.g. the two coordinates of points on a curve).

    Returns
    -------
    (n, m) float array
        The spline's first derivative at every knot.
    """
    x = np.asarray(x, dtype=float)
    y = np.asarray(y, dtype=float)
    dx = np.diff(x)
    slope = np.diff(y, axis=0) / dx[:, None]
    n = len(x)
    lower, diagonal, upper = np.zeros(n), np.zeros(n), np.zeros(n)
    rhs = np.zeros_like(y)
    # interior rows: dx[i] s[i-1] + 2 (dx[i-1] + dx[i]) s[i] + dx[i-1] s[i+1] = 3 (dx[i] m[i-1] + dx[i-1] m[i])
    lower[1:-1], diagonal[1:-1], upper[1:-1] = dx[1:], 2.0 * (dx[:-1] + dx[1:]), dx[:-1]
    rhs[1:-1] = 3.0 * (dx[1:, None] * slope[:-1] + dx[:-1, None] * slope[1:])
    # not-a-knot: the third derivative is continuous at x[1] and at x[-2]
    w = x[2] - x[0]
    diagonal[0], upper[0] = dx[1], w
    rhs[0] = ((dx[0] + 2.0 * w) * dx[1] * slope[0] + dx[0] ** 2 * slope[1]) / w
    w = x[-1] - x[-3]
    diagonal[-1], lower[-1] = dx[-2], w
    rhs[-1] = (dx[-1] ** 2 * slope[-2] + (2.0 * w + dx[-1]) * dx[-2] * slope[-1]) / w
    return solve_tridiagonal(lower, diagonal, upper, rhs)


def makima_slopes(x: np.ndarray, y: np.ndarray) -> np.ndarray:
    """Return the slopes at the knots of the modified Akima cubic through (x, y), by numpy alone.

    Akima (J. ACM 17, 1970) takes the slope at knot i as a weighted mean of the chords' slopes
    m_{i-1} and m_i, weighted by how much the slopes change on the far side; the modified weights
    (Moler, "Makima piecewise cubic interpolation", 2019) add half the slopes' mean magnitude, so
    that flat runs and equal slopes give no overshoot:
    w1 = |m_{i+1} - m_i| + |m_{i+1} + m_i|/2, w2 = |m_{i-1} - m_{i-2}| + |m_{i-1} + m_{i-2}|/2,
    t_i = (w1 m_{i-1} + w2 m_i) / (w1 + w2). Two chords are added at each end by linear
    extrapolation of the slopes; where both weights vanish (all four slopes equal, within 1e-9 of
    the largest weight sum) t_i = (m_{i-2} + m_{i+1}) / 2, as in
    :class:`scipy.interpolate.Akima1DInterpolator` with ``method="makima"``, which this equals.

    Parameters
    ----------
    x : (n,) float array
        Strictly increasing knots, n >= 2.
    y : (n, m) float array
        Values at the knots, one column per coordinate.

    Returns
    -------
    (n, m) float array
        dy/dx at the knots.
    """
    x = np.asarray(x, dtype=float)
    y = np.asarray(y, dtype=float)
    chord = np.diff(y, axis=0) / np.diff(x)[:, None]
    if len(x) == 2:
        return np.repeat(chord, 2, axis=0)
    m = np.empty((len(x) + 3, y.shape[1]))
    m[2:-2] = chord
    m[1] = 2.0 * m[2] - m[3]
    m[0] = 2.0 * m[1] - m[2]
    m[-2] = 2.0 * m[-3] - m[-4]
    m[-1] = 2.0 * m[-2] - m[-3]
    t = 0.5 * (m[3:] + m[:-3])
    change = np.abs(np.diff(m, axis=0))
    size = np.abs(m[1:] + m[:-1])
    w1 = change[2:] + 0.5 * size[2:]
    w2 = change[:-2] + 0.5 * size[:-2]
    total = w1 + w2
    defined = total > 1e-9 * total.max(initial=-np.inf)
    with np.errstate(divide="ignore", invalid="ignore"):
        weighted = m[1:-2] + (w2 / total) * (m[2:-1] - m[1:-2])
    return np.where(defined, weighted, t)

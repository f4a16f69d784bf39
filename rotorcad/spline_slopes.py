"""Slopes of the modified Akima cubic at its knots, by numpy alone.

The meshing analysis takes the tangents of a design's exact meshline from this shape-preserving
cubic (an interpolating cubic rings where the meshline turns sharply, a rack rounding about C
meeting a straight flank), computed here so that judging a meshline does not import
scipy.interpolate (0.35-0.7 s, which pulls scipy.optimize, scipy.linalg and numpy.f2py).
"""

from __future__ import annotations

import numpy as np


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
    step = np.diff(x)
    rise = np.diff(y, axis=0)
    chord = np.empty_like(rise)  # rise / step[:, None], the same numbers, by columns
    for k in range(rise.shape[1]):
        np.divide(rise[:, k], step, out=chord[:, k])
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

"""How far points that look exact lie from a smooth outline: the pattern a polygon leaves.

Points resampled along a polygon (a CSV written at a chord tolerance e, read back at a finer
spacing) lie on straight chords: neighbour to neighbour they show no scatter
(:func:`rotorcad.measured.outline.scatter` reads 0) and no sagitta, yet they leave the true outline
by up to e, in a pattern that repeats at the polygon's vertex spacing H = sqrt(8 e rho). Seen only
between neighbours such points are exact; an interpolating fit through them turns its tangent at
every vertex, and the meshing analysis read 4 points of infinite slip and a 33 % smaller blow-hole
of the narrow-tip male given by 2000 points a lobe on its own 1 µm chord CSV.

The pattern shows over a longer reach: a local cubic (least squares, in the chord frame of a window
of the outline about each point) leaves a point of a chord between vertices by
e (1/3 - t^2), t uniform in [0, 1] along the half-chord (the chord's parabolic sag about its mean);
the median of its absolute value is 0.26 e (:data:`PATTERN_MEDIAN`). A smooth outline leaves the
cubic by its fourth-order term only: over a window of 1/40 of a lobe's length the median residual
of exact points of the narrow-tip male is 2-3 nm at 300 a lobe, 13 nm at 80 (at the least window of
five points), against 0.2 µm of its 1 µm chord polygon at 2000 a lobe. The median keeps the few
sharp corners and tip roundings, where the cubic cannot follow, out of it.

Such points are fitted as scattered by the pattern's spread, :data:`PATTERN_RMS` e, when that
exceeds the scatter below which points are exact (:data:`rotorcad.measured.outline.SCATTER_FLOOR`,
0.1 µm; :func:`rotorcad.measured.outline.read_outline`): the polygons of 1 µm chords do (0.24-0.29
µm), a boolean cut's scallops (0.23 µm of pattern on the 5/6 undercut male, 0.07 µm spread) and the
0.01 µm chords' do not.
"""

from __future__ import annotations

import numpy as np

PATTERN_MEDIAN = 0.26
"""Median of |1/3 - t^2| for t uniform in [0, 1]: the median residual of a local smooth fit through
points on a chord of sagitta e, in units of e (the chord's parabola less its mean)."""

PATTERN_RMS = 0.298
"""Root mean square of 1/3 - t^2 for t uniform in [0, 1] (sqrt(4/45)): the standard deviation of
such points about the smooth outline, in units of e."""

WINDOWS_PER_LOBE = 40
"""A lobe's length over the window of the local fit: 2.3 mm of the narrow-tip male (a = 116 mm),
longer than the vertex spacing of its 1 µm chord CSV (0.3-1 mm) and short enough that a smooth
outline's fourth-order term stays in nanometres."""


WINDOW_HALF_POINTS = 16
"""Most points each side of a window's centre that a local cubic takes: denser points take every
k-th (33 points fix a cubic's four coefficients many times over), so that 100 000 points need
tens of megabytes, not the 8 GB a window of 2500 points about each of them took."""

PATTERN_CENTRES = 20_000
"""Most points whose residuals :func:`pattern_deviation` takes the median of (evenly among all)."""


def _local_cubic(
    whole: np.ndarray, half: int, stride: int = 1, centres: np.ndarray | None = None
) -> tuple[np.ndarray, np.ndarray]:
    """Return each point's offset from the local cubic of the ``2 half + 1`` points about it and its leverage.

    The offsets v normal to the window's chord against the positions u along it, the least-squares
    cubic c(u) of them; the residual v_0 - c(0) of the centre point and the hat matrix's diagonal
    entry h_00 there (the residual of independent scatter sigma has standard deviation
    sigma sqrt(1 - h_00), however uneven the points' spacing). The window takes every ``stride``-th
    point about the centre (its span ``2 half stride`` points); ``centres`` (indices, default every
    point) are the points whose residuals are returned: memory (centres x window x 4 floats) stays
    bounded however dense the points.
    """
    p = np.asarray(whole, dtype=float)
    n = len(p)
    at = np.arange(n) if centres is None else np.asarray(centres)
    k = stride * np.arange(-half, half + 1)
    idx = (at[:, None] + k[None, :]) % n
    chord = p[(at + stride * half) % n] - p[(at - stride * half) % n]
    t = chord / np.maximum(np.hypot(*chord.T), 1e-300)[:, None]
    d = p[idx] - p[at][:, None, :]  # (m, w, 2)
    u = d[..., 0] * t[:, None, 0] + d[..., 1] * t[:, None, 1]
    v = d[..., 1] * t[:, None, 0] - d[..., 0] * t[:, None, 1]
    u = u / np.maximum(np.abs(u).max(axis=1, keepdims=True), 1e-300)
    basis = np.empty((*u.shape, 4))  # (n, w, 4): 1, u, u^2, u^3 (products: a power of an array is libm's pow)
    basis[..., 0] = 1.0
    basis[..., 1] = u
    np.multiply(u, u, out=basis[..., 2])
    np.multiply(basis[..., 2], u, out=basis[..., 3])
    gram = np.einsum("nwi,nwj->nij", basis, basis) + 1e-12 * np.eye(4)
    coef = np.linalg.solve(gram, np.einsum("nwi,nw->ni", basis, v)[..., None])[..., 0]
    centre = basis[:, half, :]
    leverage = np.einsum("ni,ni->n", centre, np.linalg.solve(gram, centre[..., None])[..., 0])
    return v[:, half] - np.einsum("ni,ni->n", centre, coef), leverage


def local_fit_residual(whole: np.ndarray, half: int) -> np.ndarray:
    """Return each point's distance from the cubic fitted to the ``2 half + 1`` points about it (mm).

    Parameters
    ----------
    whole : (n, 2) float array, mm
        The closed outline, counter-clockwise, no repeated point.
    half : int
        Points each side of the centre point in the window (at least 2).

    Returns
    -------
    (n,) float array, mm
        |v_0 - c(0)|: the centre point's offset normal to the window's chord from the least-squares
        cubic c(u) of the offsets v against the positions u along that chord.
    """
    return np.abs(_local_cubic(whole, half)[0])


def uneven_scatter(whole: np.ndarray) -> float:
    """Estimate the points' normal scatter from local cubics, whatever their spacing (mm).

    The third differences of :func:`rotorcad.measured.outline.scatter` assume nearly even spacing:
    points exact on the outline but unevenly spaced (a polyline's vertices drawn to a chord
    tolerance e, spaced sqrt(8 e rho) as the radius of curvature rho changes) leave them a
    second-order term of the spacing's change, which read as 0.18 µm of scatter on the N rack male's
    export polyline (2.5 µm chords), and its vertices were smoothed instead of interpolated. The
    cubic through each five consecutive points (:func:`local_fit_residual`) leaves exact points by
    the outline's fourth-order term only; each residual over sqrt(1 - h_00) (its leverage) has the
    scatter's standard deviation, and 1.4826 times their median (a zero-mean normal's MAD) is sigma.
    Reads 0.98-1.1 µm for the samples' males with 1 µm of scatter (the third differences 0.99-1.05),
    0.8-2 nm for their exact CSVs.

    Parameters
    ----------
    whole : (n, 2) float array, mm
        The closed outline (at least 5 points).

    Returns
    -------
    float, mm
    """
    residual, leverage = _local_cubic(whole, 2)
    return float(1.4826 * np.median(np.abs(residual) / np.sqrt(np.maximum(1.0 - leverage, 1e-12))))


def pattern_deviation(whole: np.ndarray, teeth: int) -> float:
    """Estimate how far points that show no scatter lie from the smooth outline (mm).

    The median residual of a local cubic over 1/:data:`WINDOWS_PER_LOBE` of a lobe's length (at
    least five points), over :data:`PATTERN_MEDIAN` (module docstring): the sagitta e of the polygon
    the points were taken from; the nanometres of a smooth outline's own fourth-order term for
    exact points.

    Parameters
    ----------
    whole : (n, 2) float array, mm
        The closed outline.
    teeth : int
        Its lobe count.

    Returns
    -------
    float, mm
        0 for fewer than 16 points.
    """
    p = np.asarray(whole, dtype=float)
    if len(p) < 16:
        return 0.0
    step = np.hypot(*np.diff(np.vstack([p, p[:1]]), axis=0).T)
    window = step.sum() / max(teeth, 1) / WINDOWS_PER_LOBE
    half = int(min(max(2, round(window / 2.0 / max(float(np.median(step)), 1e-300))), (len(p) - 1) // 2))
    stride = -(-half // WINDOW_HALF_POINTS)  # dense points: every stride-th of them spans the same window
    centres = np.arange(0, len(p), max(1, len(p) // PATTERN_CENTRES))
    residual = _local_cubic(p, -(-half // stride), stride, centres)[0]
    return float(np.median(np.abs(residual))) / PATTERN_MEDIAN


__all__ = [
    "PATTERN_CENTRES",
    "PATTERN_MEDIAN",
    "PATTERN_RMS",
    "WINDOWS_PER_LOBE",
    "WINDOW_HALF_POINTS",
    "local_fit_residual",
    "pattern_deviation",
    "uneven_scatter",
]

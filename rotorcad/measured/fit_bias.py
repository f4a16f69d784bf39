"""The bias of a fit of scattered points that its scatter bound leaves out: roundings and folds (issue 22).

A rotor's ``accuracy`` (k_N sigma, :func:`rotorcad.measured.pairs.scatter_bound`) bounds the variance of the
fit of its points, not its bias. Two biases are measured, shared by the rack of a rotor's points
(``hob.rack_accuracy``) and the meshing clearance (:mod:`rotorcad.clearance_bias`):

* **At a rounding.** A smoothing spline by n sigma^2 (Dierckx, *Curve and Surface Fitting with Splines*,
  1993, sec. 5.2) cannot step its curvature: the bias of a smoother of width w at a step kappa of the
  second derivative is ~ kappa w^2, its variance sigma^2 h / w (h the point spacing); their balance gives
  w ~ (sigma^2 h / kappa^2)^(1/5) and an error ~ sigma g^(1/5), g = kappa h^2 / sigma
  (:func:`rounding_bias`, its factor :data:`ROUNDING_BIAS` measured by ``benchmarks/bench_rounding_bias.py``).
* **A fold of a generated rack.** Where a rotor's generation stalls (its point nearly still while its rack
  point runs), the rack follows the fit's curvature, not its position: a curvature error turns the rack
  back along itself, and the middle leg of that fold lies off the legs beside it (:func:`rack_folds`).
"""

from __future__ import annotations

import numpy as np
import shapely

ROUNDING_BIAS = 3.0
"""The largest error of a smoothing fit (n sigma^2) near a rounding, in units of sigma (kappa h^2 /
sigma)^(1/5): ``benchmarks/bench_rounding_bias.py`` (32 seeds on each of 39 synthetic roundings) reads a
median of 1.47, a 95 % quantile of 2.26 and a 98.75 % one (the largest of a lobe's four roundings with
95 % confidence) of 2.65; 3.0 leaves a margin for roundings that are not circles."""


def rounding_bias(sigma: float | np.ndarray, spacing: float, curvature: float | np.ndarray) -> float | np.ndarray:
    """Return the bound (mm) on a smoothing fit's error at a rounding: ROUNDING_BIAS sigma (kappa h^2 / sigma)^(1/5).

    Parameters
    ----------
    sigma : float, mm
        The points' scatter (0: exact points, no bias).
    spacing : float, mm
        The points' spacing h.
    curvature : float or (n,) float array, 1/mm
        The rounding's curvature step kappa (an array: one bound for each).

    Returns
    -------
    float or (n,) float array, mm
        0 where sigma, the spacing or the curvature is not positive.
    """
    kappa = np.asarray(curvature, dtype=float)
    if sigma <= 0 or spacing <= 0:
        out = np.zeros_like(kappa)
    else:
        out = ROUNDING_BIAS * sigma * (np.maximum(kappa, 0.0) * spacing**2 / sigma) ** 0.2
    return float(out) if out.ndim == 0 else out


def rack_folds(points: np.ndarray, tangents: np.ndarray, skip: np.ndarray, piece: np.ndarray) -> list[tuple[int, int, float]]:
    """Return a generated rack's folds: the points they reach over and how far their middle leg lies off.

    A fold: consecutive rack points of one piece that run against the rack's exact tangent (the generation
    turned back; two pieces' ends overlapping at a join are no fold, nor points flagged ``skip``, a corner's
    path). Its width is the largest distance of its points (from the cusp where it starts to the one where
    it ends) from the legs before and after it, each three times as long as the fold (shapely's
    point-to-polyline distance). It reaches over itself and as many points again on either side (the
    legs that overlap it: a swallowtail's three legs span the same stretch of rack); the N-rack sample's
    rows off by a fold of the male rack read it there, and the 5/6 independent pair's rows beside its
    male's undercut fold, which are not off, lie beyond (``benchmarks/bench_clearance_accuracy.py``).

    Parameters
    ----------
    points, tangents : (n, 2) float array
        The rack's points (mm, in order along its chain) and exact unit tangents.
    skip : (n,) bool array
        Points that are no part of a fold (a sharp corner's path).
    piece : (n,) int array
        The fitted piece each point was generated from.

    Returns
    -------
    list of (int, int, float)
        Each fold's first and past-the-last point index of its reach and its width (mm).
    """
    pts = np.asarray(points, dtype=float)
    if len(pts) < 4:
        return []
    back = np.einsum("ij,ij->i", np.diff(pts, axis=0), tangents[:-1]) < 0.0
    back &= ~skip[:-1] & ~skip[1:] & (np.diff(piece) == 0)  # not across a join
    edges = np.diff(np.concatenate([[0], back.astype(int), [0]]))
    out = []
    for a, b in zip(np.flatnonzero(edges == 1), np.flatnonzero(edges == -1), strict=True):
        n = b - a
        middle, width = shapely.points(pts[a : b + 1]), 0.0
        for leg in (pts[max(a - 3 * n - 5, 0) : a + 1], pts[b : b + 3 * n + 6]):
            if len(leg) > 1:
                width = max(width, float(shapely.distance(middle, shapely.LineString(leg)).max()))
        out.append((int(max(a - n - 1, 0)), int(min(b + n + 2, len(pts))), width))
    return out


__all__ = ["ROUNDING_BIAS", "rack_folds", "rounding_bias"]

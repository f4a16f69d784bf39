"""The stated accuracy of each row of a meshing clearance: the fits' bias where they have one (issue 22 item 2).

The scatter bound of :func:`rotorcad.clearance_accuracy.estimated_accuracy` (sqrt(2) k_N sigma, the fits'
variance) leaves out two biases of the two rotors' fits, which act only near where they arise
(:mod:`rotorcad.measured.fit_bias`, as ``hob``'s rack accuracy takes them):

* **A rounding** of either fitted rotor, whose curvature step a smoothing spline by n sigma^2 cannot
  follow: 3 sigma (kappa h^2 / sigma)^(1/5) (:func:`rotorcad.measured.fit_bias.rounding_bias`), kappa the
  largest curvature of the fitted rotor within :data:`ROUNDING_REACH` point spacings of the row's rotor
  point. It takes the place of the scatter bound where it is larger (both bound the same fit's error).
* **A fold of either generated rack**, where that rotor's generation stalls and the rack follows the
  fit's curvature, not its position (the N-rack sample's female at r = 43.5 mm, the end of its 2.07 mm
  sealing tip circle, faced by a fold of the male's rack up to 60 um wide from 300 points a lobe with 2 um
  of scatter): a row whose normal meets a fold or its legs on the male rack, or that lies on one of the
  female rack, is off by up to the fold's width (:func:`rotorcad.measured.fit_bias.rack_folds`) more.

Measured by ``benchmarks/bench_clearance_accuracy.py`` on the N-rack sample's own conjugate outlines
(``N-exact``: 300 exact points a lobe read 12.4 um off at the fold's rows for 4.2 um stated before; their
rows now state 25.6 um) and on the independent 4/6 and 5/6 pairs (README).
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from rotorcad.clearance_normals import normal_crossing
from rotorcad.curves import Curve
from rotorcad.geometry import Array
from rotorcad.measured.fit_bias import rack_folds, rounding_bias

if TYPE_CHECKING:
    from rotorcad.clearance import MeshingClearance

ROUNDING_REACH = 2.0
"""Point spacings about a row's rotor point within which a rounding of the fitted rotor biases it: the
span of the cubic pieces a smoothing spline puts over points h apart (the smoother's own width,
(sigma^2 h / kappa^2)^(1/5), is less: 0.09 mm for the N-rack female's 2.07 mm tip circle from 300 points a
lobe with 2 um)."""


def fitted_curvature(pieces: list[tuple[str, Curve]], spacing: float) -> tuple[Array, Array]:
    """Return points along a rotor's fitted pieces and its curvature there.

    Each piece sampled at a quarter of the point spacing; the curvature the turn of the pieces' exact
    tangents (:meth:`rotorcad.curves.Curve.frame`) between neighbouring samples over their distance.

    Parameters
    ----------
    pieces : list of (str, Curve)
        One lobe of the rotor, in its own frame (mm).
    spacing : float, mm
        The points' spacing.

    Returns
    -------
    points : (k, 2) float array, mm
        Midpoints between neighbouring samples.
    curvature : (k,) float array, 1/mm
    """
    out_p, out_k = [np.zeros((0, 2))], [np.zeros(0)]
    for _, curve in pieces:
        coarse, _ = curve.frame(np.linspace(curve.s0, curve.s1, 65))
        length = float(np.hypot(*np.diff(coarse, axis=0).T).sum())
        count = int(np.clip(np.ceil(length / (0.25 * spacing)), 4, 20000))
        pts, tan = curve.frame(np.linspace(curve.s0, curve.s1, count + 1))
        step = np.maximum(np.hypot(*np.diff(pts, axis=0).T), 1e-12)
        turn = np.arctan2(tan[:-1, 0] * tan[1:, 1] - tan[:-1, 1] * tan[1:, 0], np.einsum("ij,ij->i", tan[:-1], tan[1:]))
        out_p.append(0.5 * (pts[:-1] + pts[1:]))
        out_k.append(np.abs(turn) / step)
    return np.vstack(out_p), np.concatenate(out_k)


def largest_curvature_near(at: Array, pieces: list[tuple[str, Curve]], teeth: int, spacing: float) -> Array:
    """Return the largest curvature (1/mm) of a fitted rotor within :data:`ROUNDING_REACH` spacings of each point.

    Parameters
    ----------
    at : (n, 2) float array, mm
        Points on the rotor, in its own frame (any lobe).
    pieces : list of (str, Curve)
        The rotor's fitted lobe.
    teeth : int
        Its lobe count (the lobe is repeated around the rotor).
    spacing : float, mm
        The points' spacing.

    Returns
    -------
    (n,) float array, 1/mm
        0 where no sample lies within reach (NaN points included).
    """
    from scipy.spatial import cKDTree  # scipy only where the rows are judged

    pts, kappa = fitted_curvature(pieces, spacing)
    out = np.zeros(len(at))
    ok = np.isfinite(at).all(axis=1)
    if not len(pts) or not ok.any():
        return out
    turns = 2 * np.pi * np.arange(teeth) / teeth
    rot = np.stack([np.cos(turns), -np.sin(turns), np.sin(turns), np.cos(turns)], axis=-1).reshape(-1, 2, 2)
    ring = np.einsum("tij,kj->tki", rot, pts).reshape(-1, 2)  # the lobe turned onto every lobe
    near = cKDTree(at[ok]).sparse_distance_matrix(cKDTree(ring), ROUNDING_REACH * spacing, output_type="coo_matrix")
    largest = np.zeros(int(ok.sum()))
    np.maximum.at(largest, near.row, np.tile(kappa, teeth)[near.col])
    out[ok] = largest
    return out


def fold_widths(mc: MeshingClearance) -> Array:
    """Return, for each datum (female) rack point, the widest fold of either rack it reads (mm, 0: none).

    A point on a fold's reach of the female rack (the datum itself), or whose normal meets the male rack
    on a fold's reach (the segment :func:`rotorcad.clearance_normals.normal_crossing` finds, over the male
    rack's three periods).
    """
    out = np.zeros(len(mc.female_rack.points))
    rack = mc.female_rack
    for lo, hi, width in rack_folds(rack.points, rack.tangents, rack.corner_path, rack.piece_index):
        out[lo:hi] = np.maximum(out[lo:hi], width)
    segment = male_segment(mc)
    rack = mc.male_rack
    for lo, hi, width in rack_folds(rack.points, rack.tangents, rack.corner_path, rack.piece_index):
        on = (segment >= lo) & (segment < hi)
        out[on] = np.maximum(out[on], width)
    return out


def male_segment(mc: MeshingClearance) -> Array:
    """Return the male rack point (index in one period) each datum point's normal meets, -1 for none, (n,) int."""
    pts, _, normals = mc._datum
    moved = pts + np.array([mc.shift * np.cos(mc.helix_angle), 0.0])
    compared, compared_tan = mc._compared
    _, segment = normal_crossing(moved, normals, compared, compared_tan)
    return np.where(segment >= 0, segment % len(mc.male_rack.points), -1)


def row_accuracy(mc: MeshingClearance, accuracy: float) -> Array:
    """Return the stated accuracy of each datum rack point's clearance (mm), (n,) float.

    The larger of the scatter bound ``accuracy`` and the rounding bias of either fitted rotor near the
    row (at the female's point that generates it and at the male's point its normal meets), plus the
    widest fold of either rack it reads (:func:`fold_widths`). ``accuracy`` where the fits have no bias:
    of points without scatter (interpolating fits) no rounding term; of exact curves (no points, spacing
    0) neither term.

    Parameters
    ----------
    mc : MeshingClearance
        The clearance (its racks, fitted pieces, scatter and spacing).
    accuracy : float, mm
        The scatter bound (:func:`rotorcad.clearance_accuracy.estimated_accuracy`).

    Returns
    -------
    (n,) float array, mm
    """
    n = len(mc.female_rack.points)
    bias = np.zeros(n)
    if mc.scatter > 0 and mc.spacing > 0:
        female = mc.female_rack.profile if mc.female_rack.profile is not None else np.full((n, 2), np.nan)
        kappa = largest_curvature_near(female, mc.female_pieces, mc.pair.female_teeth, mc.spacing)
        segment = male_segment(mc)
        profile = mc.male_rack.profile
        if profile is not None:
            male = np.where((segment >= 0)[:, None], profile[np.maximum(segment, 0)], np.nan)
            kappa = np.maximum(kappa, largest_curvature_near(male, mc.male_pieces, mc.pair.male_teeth, mc.spacing))
        bias = rounding_bias(mc.scatter, mc.spacing, kappa)
    if mc.spacing <= 0:  # exact curves: no fit, and a fold of their racks is the geometry's own
        return np.full(n, accuracy)
    return np.maximum(accuracy, bias) + fold_widths(mc)


__all__ = ["ROUNDING_REACH", "fitted_curvature", "fold_widths", "largest_curvature_near", "male_segment", "row_accuracy"]

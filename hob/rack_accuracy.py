"""How far the rack a rotor's scattered points give may lie from the rotor's true rack (issue 22 item 3).

A rack point is where the fitted rotor's normal passes the pitch point (Wu & Chi, *Meshing clearance
evaluation*, sec. 2, eq. 4). A wrong normal moves the contact to another roll, but the rotor point's
velocity relative to the rack is normal to its line to the pitch point, which is that normal: the rack
point slides along the rack, and to first order the rack is off by what the fitted rotor is off at the
contact point (measured within 0.1 um on the samples' racks from 300 points a lobe with 2 um of scatter).
Three things make the rack's largest error exceed the profile's ``accuracy`` (k_N sigma, the largest of a
lobe's N point errors with 95 % confidence, :func:`rotorcad.measured.pairs.scatter_bound`), which bounds
the fit's variance but not its bias:

* **The fit's bias at a rounding.** A smoothing spline by n sigma^2 (Dierckx, *Curve and Surface Fitting
  with Splines*, 1993, sec. 5.2) cannot step its curvature: at a tip rounding of ~10 points meeting a
  flank it cuts the rounding by up to 4.5 sigma (the rack-involute female's tip rounding at r = 63.2 mm,
  9.0 um at 2 um). The bias of a smoother of width w at a step kappa of the second derivative is
  ~ kappa w^2, its variance sigma^2 h / w (h the point spacing); their balance gives
  w ~ (sigma^2 h / kappa^2)^(1/5) and an error ~ sigma g^(1/5), g = kappa h^2 / sigma. The factor
  :data:`ROUNDING_BIAS` is measured on synthetic roundings (``benchmarks/bench_rounding_bias.py``: line,
  arc, line, FITPACK's smoothing by n sigma^2, sigma 1-4 um, h 0.1-0.42 mm, R 0.7-16 mm); kappa is the
  largest curvature of the fitted rotor, which a smoothing fit bounds from below (an error of 2 in
  kappa is 15 % in the term).
* **A stall of the generation.** Where the rotor's point stands nearly still while the rack's moves
  (the generation factor near 0: the N-rack female's slip singularity at r = 43-45 mm), the rack
  follows the fit's curvature, not its position: a curvature error turns the rack back along itself (a
  fold, its points running against its exact tangent) and its middle leg lies off the legs beside it
  (N-rack female seeds 12 / 18: folds 12.5 / 9.5 um wide, the rack 12.0 / 8.1 um off for a fit 5.6 / 5.2
  off). The widest such fold off the rotor's corner paths is added.
* **A sharp corner.** Where the points turn by a corner (a root corner of the narrow-tip male, 45 deg),
  the fit puts it where the fits beside it cross, extrapolated over the points next to it; two lines
  each within e of their true ones and turning by theta cross within e / sin(theta / 2) of the true
  corner (the half-diagonal of the rhombus of their offsets), and the flank's fit runs from there: the
  narrow-tip male's corners were found 1-15 um off at 2 um of scatter (seed 17), its rack 7.6-12.9 um
  off beside the 45 deg corner on 8 of seeds 11-30 for an accuracy of 7.3-8.3 um (:func:`corner_error`).

The rack accuracy is the largest of ``accuracy``, the rounding term and the corner term, plus the widest
fold. Of exact points (no scatter) it is ``accuracy``: an interpolating fit has no smoothing bias.
"""

from __future__ import annotations

import numpy as np
import shapely

from rotorcad.curves import Curve, Spline
from rotorcad.envelope import Generated
from rotorcad.inverse_rack import DerivedRack
from rotorcad.measured.pairs import max_factor
from rotorcad.screw_rotors import ScrewRotors

CORNER_DEG = 30.0
"""deg: the smallest turn between two fitted pieces that is a sharp corner (as
:func:`rotorcad.measured.fit.lobe_pieces` cuts the points at)."""
JOIN = 0.05
"""mm: two fitted pieces whose ends lie within this meet (the fits of scattered points leave ends apart by
the join gap :data:`rotorcad.inverse_rack.MEASURED_JOIN_GAP` at most)."""

ROUNDING_BIAS = 3.0
"""The largest error of a smoothing fit (n sigma^2) near a rounding, in units of sigma (kappa h^2 /
sigma)^(1/5): ``benchmarks/bench_rounding_bias.py`` (32 seeds on each of 39 synthetic roundings) reads a
median of 1.47, a 95 % quantile of 2.26 and a 98.75 % one (the largest of a lobe's four roundings with
95 % confidence) of 2.65; 3.0 leaves a margin for roundings that are not circles."""


def _splines(curve: Curve) -> list[Spline]:
    """Return the fitted splines a curve is made from (through its ``parent`` / ``curve`` chain)."""
    out: list[Spline] = []
    seen = 0
    while curve is not None and seen < 16:
        if isinstance(curve, Spline):
            out.append(curve)
            break
        curve = getattr(curve, "parent", None) or getattr(curve, "curve", None)
        seen += 1
    return out


def largest_curvature(rotors: ScrewRotors, spacing: float) -> float:
    """Return the largest curvature (1/mm) of the splines the given rotor was fitted with.

    The curvature from the splines' exact first and second derivatives (scipy's ``splev``), sampled at a
    quarter of the point spacing; the largest over one point spacing's median (a spline's end hooking over
    less than a spacing is no rounding).

    Parameters
    ----------
    rotors : ScrewRotors
        A pair generated from a rotor's points (its rack pieces carry the fitted splines).
    spacing : float, mm
        The points' spacing.

    Returns
    -------
    float, 1/mm
    """
    from scipy import interpolate  # scipy.interpolate only for a spline

    splines = {id(s): s for piece in rotors.rack for s in _splines(piece.curve)}.values()
    largest = 0.0
    for spline in splines:
        lo, hi = sorted((float(spline.s0), float(spline.s1)))
        count = int(np.ceil((hi - lo) / (0.25 * spacing)))
        if count < 8:
            continue
        s = np.linspace(lo, hi, count + 1)
        tck = [spline.knots[0], list(spline.knots[1]), spline.knots[2]]
        d1 = np.stack(interpolate.splev(s, tck, der=1), axis=-1)
        d2 = np.stack(interpolate.splev(s, tck, der=2), axis=-1)
        speed = np.hypot(*d1.T)
        kappa = np.abs(d1[:, 0] * d2[:, 1] - d1[:, 1] * d2[:, 0]) / np.maximum(speed, 1e-12) ** 3
        window = 4  # one point spacing
        kept = np.lib.stride_tricks.sliding_window_view(kappa, window + 1)
        largest = max(largest, float(np.median(kept, axis=1).max()))
    return largest


def rounding_bias(sigma: float, spacing: float, curvature: float) -> float:
    """Return the bound (mm) on a smoothing fit's error at a rounding: ROUNDING_BIAS sigma (kappa h^2 / sigma)^(1/5).

    Parameters
    ----------
    sigma : float, mm
        The points' scatter (0: exact points, no bias).
    spacing : float, mm
        The points' spacing h.
    curvature : float, 1/mm
        The rounding's curvature step kappa.

    Returns
    -------
    float, mm
    """
    if sigma <= 0 or spacing <= 0 or curvature <= 0:
        return 0.0
    return ROUNDING_BIAS * sigma * (curvature * spacing**2 / sigma) ** 0.2


def widest_fold(rack: DerivedRack) -> float:
    """Return the widest fold of a rack off its corner paths (mm): how far a leg run backwards lies off its neighbours.

    A fold: consecutive rack points of one piece that run against the rack's exact tangent (the
    generation turned back; two pieces' ends overlapping at a join are no fold). Its width is the
    largest distance of its points (from the cusp where it starts to the one where it ends) from the
    legs before and after it, each three times as long as the fold (shapely's point-to-polyline distance).

    Parameters
    ----------
    rack : DerivedRack
        A rotor's rack (its points in order along the chain, exact tangents).

    Returns
    -------
    float, mm
    """
    pts, tan = rack.points, rack.tangents
    if len(pts) < 4:
        return 0.0
    back = np.einsum("ij,ij->i", np.diff(pts, axis=0), tan[:-1]) < 0.0
    back &= ~rack.corner_path[:-1] & ~rack.corner_path[1:] & (np.diff(rack.piece_index) == 0)  # not across a join
    edges = np.diff(np.concatenate([[0], back.astype(int), [0]]))
    widest = 0.0
    for a, b in zip(np.flatnonzero(edges == 1), np.flatnonzero(edges == -1), strict=True):
        n = b - a
        middle = pts[a : b + 1]
        for leg in (pts[max(a - 3 * n - 5, 0) : a + 1], pts[b : b + 3 * n + 6]):
            if len(leg) > 1:
                widest = max(widest, float(shapely.distance(shapely.points(middle), shapely.LineString(leg)).max()))
    return widest


def _sources(rotors: ScrewRotors) -> list[Curve]:
    """Return the fitted pieces of the given rotor (pair frame) that its rack pieces were generated from."""
    out: dict[int, Curve] = {}
    for piece in rotors.rack:
        curve, depth = piece.curve, 0
        while curve is not None and not isinstance(curve, Generated) and depth < 16:
            curve, depth = getattr(curve, "parent", None) or getattr(curve, "curve", None), depth + 1
        if isinstance(curve, Generated):
            out[id(curve.parent)] = curve.parent
    return list(out.values())


def concave_corners(rotors: ScrewRotors) -> np.ndarray:
    """Return the turns (rad) at the concave sharp corners between the given rotor's fitted pieces.

    Pieces meet where the end of one lies within :data:`JOIN` of the start of another; the turn is the angle
    between the end tangent and the start tangent (both exact, the pieces counter-clockwise), a right turn
    (a corner below the tip, where the flank beside it touches the mate up to the corner; a convex tip
    corner's own path on the rack is its fan's, not a flank's); turns below :data:`CORNER_DEG` are no
    corners (a land meeting a flank, a fit's kink).
    """
    ends = []
    for curve in _sources(rotors):
        p, t = curve.frame(np.array([curve.s0, curve.s1]))
        ends.append((p, t * (1.0 if curve.s1 >= curve.s0 else -1.0)))
    turns = []
    for pa, ta in ends:
        for pb, tb in ends:
            if pa is pb or np.hypot(*(pa[1] - pb[0])) > JOIN:
                continue
            turn = -float(np.arctan2(ta[1][0] * tb[0][1] - ta[1][1] * tb[0][0], ta[1] @ tb[0]))  # > 0: concave
            if turn >= np.radians(CORNER_DEG):
                turns.append(turn)
    return np.array(turns)


def corner_error(sigma: float, turns: np.ndarray) -> float:
    """Return the bound (mm) on how far the fit puts a lobe's sharp corners: k_2m sigma / sin(theta / 2).

    A corner lies where the fits beside it cross; each fit's end rests on the few points next to it and
    is known to about one point's scatter sigma; the largest of the lobe's 2 m ends' errors with 95 %
    confidence is k_2m sigma (:func:`rotorcad.measured.pairs.max_factor`), and two lines each that far
    off, turning by theta, cross within that over sin(theta / 2) of the true corner (the half-diagonal
    of the rhombus of their offsets). 0 without a corner.

    Parameters
    ----------
    sigma : float, mm
        The points' scatter.
    turns : (m,) float array, rad
        The corners' turns (:func:`concave_corners`).

    Returns
    -------
    float, mm
    """
    if sigma <= 0 or not len(turns):
        return 0.0
    return max_factor(2 * len(turns)) * sigma / float(np.sin(0.5 * np.min(turns)))


def scatter_of(rotors: ScrewRotors, rack: DerivedRack, spacing: float) -> float:
    """Return the points' scatter sigma (mm) that the profile's accuracies were stated from.

    ``point_accuracy`` is one point's (the larger of 2 sigma, the chords' sagitta and the fit's residual)
    and ``accuracy`` the larger of that and k_N sigma over a lobe's N points
    (:func:`rotorcad.measured.pairs.scatter_bound`), N the lobe's length (its rack's profile points, one
    period) over the point spacing: sigma is at most the smaller of point_accuracy / 2 and accuracy / k_N,
    and equals the latter where the scatter sets the accuracy (300 points a lobe with 2 um: 1.99 um); of
    sparse points, whose accuracy the chords' sagitta sets, it is an upper bound.
    """
    profile = rack.profile[~rack.corner_path] if rack.profile is not None else np.zeros((0, 2))
    length = float(np.hypot(*np.diff(profile, axis=0).T).sum()) if len(profile) > 1 else 0.0
    count = max(length / spacing, 1.0)
    return min(0.5 * float(rotors.point_accuracy or rotors.accuracy), float(rotors.accuracy) / max_factor(count))


def rack_accuracy(rotors: ScrewRotors, rack: DerivedRack) -> float:
    """Return how far the rack from a rotor's points may lie from the rotor's true rack (mm, 95 %).

    The largest of the profile's ``accuracy``, the fit's bias at its tightest rounding
    (:func:`rounding_bias` at :func:`largest_curvature`) and the error of its sharp concave corners
    (:func:`corner_error`), plus the widest fold of the rack
    (:func:`widest_fold`); ``accuracy`` for exact points or a design.

    Parameters
    ----------
    rotors : ScrewRotors
        The pair generated from the rotor's points (:func:`rotorcad.measured.pairs.pair_from_rotor_points`).
    rack : DerivedRack
        That rotor's rack (:func:`rotorcad.inverse_rack.rotor_rack`), the one its hob is judged on.

    Returns
    -------
    float, mm
    """
    accuracy = float(rotors.accuracy)
    if not (rotors.tangent_accuracy or 0.0) > 0.0 or not rotors.point_spacing:
        return accuracy
    spacing = float(rotors.point_spacing)
    sigma = scatter_of(rotors, rack, spacing)
    bias = rounding_bias(sigma, spacing, largest_curvature(rotors, spacing))
    corner = corner_error(sigma, concave_corners(rotors))
    return max(accuracy, bias, corner) + widest_fold(rack)


def hob_rack_accuracy(body: object, racks: dict[str, DerivedRack]) -> float:
    """Return the key ``rack_accuracy`` of ``rotorcad hob`` (mm): :func:`rack_accuracy` of the given rotor's rack.

    For a pair from a rotor's points (family ``male-points`` / ``female-points``) the rack of that rotor;
    otherwise the body's ``accuracy`` (0 for a design or a gear; the points' for rack points).

    Parameters
    ----------
    body : ScrewRotors or InvoluteGear
        What ``hob`` judged.
    racks : dict of str to DerivedRack
        Its racks by body name (``male``, ``female`` or ``gear``).

    Returns
    -------
    float, mm
    """
    accuracy = float(getattr(body, "accuracy", 0.0) or 0.0)
    family = getattr(body, "family", "")
    for side in ("male", "female"):
        if isinstance(body, ScrewRotors) and family == f"{side}-points" and side in racks:
            return rack_accuracy(body, racks[side])
    return accuracy


__all__ = [
    "ROUNDING_BIAS",
    "concave_corners",
    "corner_error",
    "hob_rack_accuracy",
    "largest_curvature",
    "rack_accuracy",
    "rounding_bias",
    "scatter_of",
    "widest_fold",
]

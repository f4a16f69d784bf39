"""Rotor pairs from measured points: of the rack, of the male or of the female rotor.

The last stage of the measured-outline pipeline (:mod:`rotorcad.measured`). A rotor's fitted lobe
(:mod:`rotorcad.measured.fit`) is turned into its rack by inverse generation (Wu & Chi sec. 2,
eqs. 4-8, in the transverse section), and the pair is generated from that rack; the rotor given
comes back as its own conjugate's conjugate (a round trip that the tests check). Corner paths, its
own and the mate's (point-generated flanks, Rinder Fig. 1-4), are found and marked as in the
families. Calls go down the pipeline only (fit, then outline).
"""

from __future__ import annotations

import numpy as np

from rotorcad.curves import Curve, Mapped, Spline
from rotorcad.envelope import Generated, from_rack_frame
from rotorcad.errors import DesignError
from rotorcad.inverse_rack import MEASURED_MIN_TURN, with_corner_fans
from rotorcad.measured.fit import fit_residual, lobe_pieces
from rotorcad.measured.outline import read_outline
from rotorcad.roles import PieceRole, Side
from rotorcad.rotor_pair import RotorPair
from rotorcad.screw_rotors import RackPiece, ScrewRotors

CONFIDENCE = 0.95
"""Confidence with which a stated accuracy bounds the largest error over the points it is stated for."""


def max_factor(count: float, confidence: float = CONFIDENCE) -> float:
    """Return k such that the largest |e| of ``count`` independent N(0, 1) errors stays below k with ``confidence``.

    P(max |e_i| > k) <= count P(|e| > k) = 2 count (1 - Phi(k)) (Boole's inequality), so
    k = Phi^-1(1 - (1 - confidence) / (2 count)): 1.96 for one error, 3.42 for 80, 3.76 for 300, 4.21 for 2000
    at 95 %. Not 2: the largest of hundreds of Gaussian errors lies beyond 2 sigma almost surely.

    Parameters
    ----------
    count : float
        Number of independent errors (at least 1).
    confidence : float
        Probability that the bound holds.

    Returns
    -------
    float
    """
    from scipy.stats import norm

    return float(norm.isf((1.0 - confidence) / (2.0 * max(count, 1.0))))


def scatter_bound(sigma: float, count: float) -> float:
    """Return the bound (mm) on the largest deviation of a fitted outline caused by the points' scatter.

    k sigma (:func:`max_factor`, 95 % confidence) for ``count`` points of scatter ``sigma`` (mm): the
    smoothing fit's own error at a point has a standard deviation of at most the scatter's, and the
    largest over the lobe is that of ``count`` of them. 0 for exact points.
    """
    return max_factor(count) * sigma if sigma > 0 else 0.0


def pair_from_rack_points(pair: RotorPair, points: np.ndarray, smoothing: float = 0.0) -> ScrewRotors:
    """Generate a pair from points of one rack period.

    Parameters
    ----------
    pair : RotorPair
        Dimensions of the pair.
    points : (n, 2) float array, mm
        One rack period in the rack frame of CONTRACT.md (x along the motion, y > 0 towards the
        female), in either direction.
    smoothing : float, mm²
        scipy's spline smoothing; 0 interpolates.

    Returns
    -------
    ScrewRotors
        The pair generated from the fitted rack (family ``"rack-points"``).

    Raises
    ------
    DesignError
        Points that do not span one rack period p = 2 pi r1w / z1 in x (within 0.1 %).
    """
    pts = np.asarray(points, dtype=float)
    if pts[-1, 0] < pts[0, 0]:
        pts = pts[::-1]
    span = pts[-1, 0] - pts[0, 0]
    if abs(span - pair.rack_period) > 1e-3 * pair.rack_period:
        raise DesignError("rack points", f"one rack period long in x ({pair.rack_period:.6g} mm)", f"{span:.6g} mm")
    spline = Spline.fit(from_rack_frame(pts, pair.male_pitch_radius), smoothing=smoothing)
    return ScrewRotors(pair, (RackPiece(spline, "flank", "flank"),), "rack-points")


def _mate_corner_runs(
    rack_curve: Curve, mate: Generated, threshold: float = 0.02, tolerance: float = 1e-4
) -> list[tuple[float, float, bool]]:
    """Split a rack curve derived from one rotor into flank-generating parts and the mate's corner paths.

    Along a corner path the mate's generated point stands still: it is the path of a sharp corner of
    the mate (its tip corner sweeping this rotor's point-generated flank), which the mate receives as
    that corner only. Returns (s0, s1, is_corner_path) along the travel.

    Classification (positions only, no tangents): over a stencil of 1/200 of the curve the mate's
    point moves less than ``threshold`` times the rack point; a part stalled so over at least 1/100
    of the curve is a corner path. Its ends are where the mate's point leaves that corner by more
    than ``tolerance`` (mm), found by bisection.
    """
    span = rack_curve.s1 - rack_curve.s0
    s = rack_curve.s0 + span * np.linspace(0.0, 1.0, 801)
    pr, _ = rack_curve.evaluate(s)
    pm, _ = mate.evaluate(s)
    k = 4  # stencil of 4 samples either side (1/200 of the curve)
    dr = np.hypot(*(pr[2 * k :] - pr[: -2 * k]).T)
    dm = np.hypot(*(pm[2 * k :] - pm[: -2 * k]).T)
    with np.errstate(divide="ignore", invalid="ignore"):
        ratio = np.where(dr > 0, dm / dr, np.inf)
    stalled = np.zeros(len(s), dtype=bool)
    stalled[k:-k] = np.nan_to_num(ratio, nan=np.inf) < threshold
    edges = np.flatnonzero(np.diff(stalled.astype(int))) + 1
    bounds = [0, *edges.tolist(), len(s)]
    runs = [(bounds[i], bounds[i + 1]) for i in range(len(bounds) - 1) if stalled[bounds[i]] and bounds[i + 1] - bounds[i] >= 8]
    if not runs:
        return [(rack_curve.s0, rack_curve.s1, False)]

    def leave(corner: np.ndarray, inside: float, outside: float) -> float:
        for _ in range(30):
            mid = 0.5 * (inside + outside)
            q = mate.evaluate(np.array([mid]))[0][0]
            if np.all(np.isfinite(q)) and np.hypot(*(q - corner)) <= tolerance:
                inside = mid
            else:
                outside = mid
        return float(0.5 * (inside + outside))

    out, last = [], rack_curve.s0
    for i, j in runs:
        # the corner is where most of the run's mate points lie; the path extends exactly as far
        # as the mate's point stays within the tolerance of it (a slowly moving flank next to it
        # may pass the stall test without being the corner)
        corner = np.nanmedian(pm[i:j], axis=0)
        near = np.nan_to_num(np.hypot(*(pm - corner).T), nan=np.inf) <= tolerance
        centre = i + int(np.argmin(np.nan_to_num(np.hypot(*(pm[i:j] - corner).T), nan=np.inf)))
        far = np.flatnonzero(~near)
        lo = int(far[far < centre].max(initial=-1)) + 1  # the run of near samples around the centre
        hi = int(far[far > centre].min(initial=len(s))) - 1
        a = rack_curve.s0 if lo == 0 else leave(corner, s[lo], s[lo - 1])
        b = rack_curve.s1 if hi == len(s) - 1 else leave(corner, s[hi], s[hi + 1])
        if (b - a) * span <= 0:
            continue
        if (a - last) * span > 0:  # along the travel, which may run to smaller parameters
            out.append((last, a, False))
        out.append((a, b, True))
        last = b
    if last != rack_curve.s1:
        out.append((last, rack_curve.s1, False))
    parts = []
    for a, b, c in out:
        if abs(b - a) <= 1e-12 * abs(span):
            continue
        tiny = False
        if not c:  # a flank part beside a corner path that gives the mate under 10 um of flank
            ends, _ = mate.evaluate(np.array([a, b]))  # is noise near the path's end: part of it
            tiny = bool(np.all(np.isfinite(ends)) and np.hypot(*(ends[1] - ends[0])) < 10 * tolerance)
        if parts and ((c and (parts[-1][2] or parts[-1][3])) or (parts[-1][2] and tiny)):
            parts[-1] = [parts[-1][0], b, True, False]
        else:
            parts.append([a, b, c, tiny])
    return [(a, b, c) for a, b, c, _ in parts]


def pair_from_rotor_points(
    pair: RotorPair, points: np.ndarray | list[Curve], rotor: Side | str, smoothing: float | None = None, label: str | None = None
) -> ScrewRotors:
    """Generate a pair from points (or curves) of the male or the female rotor.

    The lobe is fitted piecewise between its sharp corners (:func:`lobe_pieces`); each piece and
    each corner's fan of normals gives its part of the rack by inverse generation (Wu & Chi sec. 2,
    eqs. 4-8). A corner's fan is the path of that corner ("male point" / "female point"), and so is
    every part of the rack along which the mate's generated point stands still (the mate's tip
    corner, whose point-generated flank this rotor carries): the mate receives such parts as its
    corner, exactly as in the profile families.

    Parameters
    ----------
    pair : RotorPair
        Dimensions of the pair.
    points : (n, 2) float array, mm, or list of Curve
        One lobe or the whole outline in the rotor's own frame (as for :func:`lobe_pieces`).
    rotor : {"male", "female"}
        Which rotor the points are.
    smoothing : float, mm², optional
        scipy's spline smoothing; None estimates it from the scatter.
    label : str, optional
        How the points are named in errors.

    Returns
    -------
    ScrewRotors
        The pair generated from the derived rack (family ``"male-points"`` or
        ``"female-points"``), with the share of the lobe that has no rack point in ``rack_loss``.

    Raises
    ------
    DesignError
        Points that do not make a lobe, or more than 2 % of the lobe without a rack point (its
        normal misses the pitch circle).
    """
    rotor = Side(rotor)  # "male" / "female" from a script reads as the rotor
    mesh = pair.mesh
    depth = (-pair.male_dedendum - 1e-6, pair.male_addendum + 1e-6)  # the rack lies between these
    side = Side(rotor)
    teeth = side.pick(pair.male_teeth, pair.female_teeth)
    outline = read_outline(points, teeth, label or f"{side.value} points")  # the one reading of the points
    pieces = lobe_pieces(pair, outline, rotor, smoothing)
    # the accuracy bounds the largest deviation over the lobe's points, not one point's (2 sigma)
    per_lobe = (len(outline.whole) if outline.whole is not None else 0) / max(teeth, 1)
    acc = max(outline.accuracy, fit_residual(pair, outline, pieces, rotor), scatter_bound(outline.sigma, per_lobe))
    rotor = side.value
    if side is Side.MALE:
        body, mate_body, centre, teeth = mesh.male, mesh.female, np.zeros(2), pair.male_teeth
    else:
        shift = (pair.center_distance, 0.0)
        pieces = [(name, Mapped(curve, ((1.0, 0.0), (0.0, 1.0)), shift)) for name, curve in pieces]
        body, mate_body, centre, teeth = mesh.female, mesh.male, np.array(shift), pair.female_teeth
    own, other = PieceRole.corner_path_of(side), PieceRole.corner_path_of(side.other)
    parts: list[list[RackPiece]] = []
    lost, total = 0, 0
    for _name, curve in with_corner_fans(pieces, centre, 2 * np.pi / teeth, MEASURED_MIN_TURN):
        gen = Generated(curve, body, mesh.rack, limits=depth)
        rack_curve = gen.reversed() if side is Side.MALE else gen  # travelled in +y (the rack's +x)
        ok = np.isfinite(rack_curve.evaluate(np.linspace(rack_curve.s0, rack_curve.s1, 400))[0]).all(axis=1)
        lost, total = lost + int((~ok).sum()), total + len(ok)
        if curve.is_corner():
            parts.append([RackPiece(rack_curve, f"{rotor} tip corner", f"{rotor} tip corner", kind=own)])
            continue
        mate = Generated(rack_curve, mesh.rack, mate_body)
        runs = _mate_corner_runs(rack_curve, mate, tolerance=1e-4)
        parts.append(
            [RackPiece(rack_curve.trimmed(a, b), "flank", "flank", kind=other if c else PieceRole.CURVE) for a, b, c in runs]
        )
    # the male's counter-clockwise pieces follow the rack's travel, the female's run against it
    rack = [p for group in (parts if side is Side.MALE else reversed(parts)) for p in group]
    lost_share = 100.0 * lost / max(total, 1)
    if lost_share > 2.0:  # a few points at sharp corners may miss their pitch circle; more is not a rotor
        raise DesignError(
            f"{rotor} points",
            "a profile whose every normal meets its pitch circle (it has a rack)",
            None,
            f"{lost_share:.1f} % of the lobe has no rack point",
        )
    return ScrewRotors(pair, tuple(rack), f"{rotor}-points", rack_loss=lost_share, accuracy=acc)


__all__ = ["CONFIDENCE", "max_factor", "pair_from_rack_points", "pair_from_rotor_points", "scatter_bound"]

"""Hobbability verdict, judged through the rack (Rinder sec. 2.1).

"Die Wälzfräsbarkeit ist durch die Beurteilung des zugehörigen Zahnstangenprofils möglich."

A hob is a rack wound into a thread; its tooth in the normal section is the normal rack's tool
material (the region of the rack frame away from the profile). What a hob can make follows from
that tooth:

* every profile point needs a rack point (its normal must cut the pitch circle), else there is no
  generating solution;
* the rack must be single-valued along the pitch line: a loop or an overhang (re-entrant flank)
  would ask the hob to cut under its own tooth, and such parts come out undercut;
* a flank steeper than ``min_flank_angle_deg`` (flank angle from the normal to the pitch line)
  leaves the hob tooth flank no side relief; where it falls to zero the rack flank is
  perpendicular to the pitch line and the contact runs off along it;
* tool tip and root radii below the stated minima cannot be ground and wear at once;
* a hob tooth thinner than ``min_tip_thickness`` near its tip breaks.

Rack pieces that come from sharp corners of the profile (their paths) only bound the clearance of
the hob's root; they are not cutting edges and are left out of the flank checks.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import NamedTuple

import numpy as np
import shapely

from hob.cut_depth import cut_depths
from hob.rack import DerivedRack
from hob.straight_flank import straight_flank_angles
from hob.turn_back import (
    CROSSING_ANGLE,
    FAST,
    FOLD_LENGTH,
    TRANSITION,
    TREND_LENGTH,
    TurnBack,
    crossing_angle,
    fold_length,
    length_scale,
    scaled,
    turn_back,
)
from rotorcad.inverse_rack import MEASURED_MIN_TURN, SHARP_SPAN, stalls
from rotorcad.roles import PieceRole

FOLD_TOLERANCE = 5e-4  # mm: folds and zigzags of a measured rack below this are not loops
CURVATURE_BASE = 0.02  # mm: arc length over which the rack's curvature is taken


class RackFrame(NamedTuple):
    """A rack as :func:`judge` reads it: in its normal section, travelling +x (n points)."""

    points: np.ndarray
    """(n, 2) float array, mm: the rack's points, x scaled by cos(helix angle) into the normal section."""
    tangents: np.ndarray
    """(n, 2) float array: their unit tangents in the normal section, pointing along the travel."""
    piece_index: np.ndarray
    """(n,) int array: each point's rack piece."""
    cutting: np.ndarray
    """(n,) bool array: the point cuts (not a corner fan's)."""
    flank: np.ndarray
    """(n,) bool array: a cutting point of a flank (no corner sliver, not parallel to the pitch line)."""
    arc: np.ndarray
    """(n,) float array, mm: arc length along the rotor's profile (or the rack where there is none), in travel order."""
    order: np.ndarray
    """(n,) int array: the rack's own index of each point here."""


def rack_frame(rack: DerivedRack) -> RackFrame:
    """Return ``rack`` in the frame :func:`judge` reads it (normal section, travelling +x).

    Parameters
    ----------
    rack : DerivedRack
        A rack of a pair, in its own frame.

    Returns
    -------
    RackFrame
    """
    cb = np.cos(rack.helix_angle)
    pts = rack.points * np.array([cb, 1.0])
    tan = rack.tangents * np.array([cb, 1.0])
    tan /= np.linalg.norm(tan, axis=1, keepdims=True)
    n = len(pts)
    back = n > 0 and pts[-1, 0] < pts[0, 0]
    order = np.arange(n)[::-1] if back else np.arange(n)
    pts, tan, idx = pts[order], tan[order] * (-1.0 if back else 1.0), rack.piece_index[order]
    cutting = np.array([role is not PieceRole.CORNER_FAN for role in rack.roles], dtype=bool)[idx]
    flank = cutting & ~_corner_slivers(rack)[idx] & (np.abs(tan[:, 1]) > 1e-9)
    along = (rack.profile if rack.profile is not None else rack.points)[order]
    arc = np.concatenate([[0.0], np.cumsum(np.hypot(*np.diff(along, axis=0).T))])
    return RackFrame(pts, tan, idx, cutting, flank, arc, order)


@dataclass(frozen=True)
class HobLimits:
    """Limits of a producible hob (defaults are workshop values; adjust to the hob maker's).

    Parameters
    ----------
    min_flank_angle_deg : float, deg
        Smallest flank angle of the normal rack (from the normal to the pitch line).
    min_tip_radius : float, mm
        Smallest tool tip rounding.
    min_root_radius : float, mm
        Smallest tool root rounding.
    min_tip_thickness : float, mm
        Smallest hob tooth width at 5 % of the rack depth above its tip.
    """

    min_flank_angle_deg: float = 5.0
    min_tip_radius: float = 0.1  # mm, tool tip rounding
    min_root_radius: float = 0.1  # mm, tool root rounding
    min_tip_thickness: float = 0.3  # mm, hob tooth width at 5 % of the rack depth above its tip


@dataclass(frozen=True)
class Verdict:
    """Whether a hob can make a profile, and why not.

    Parameters
    ----------
    hobbable : bool
        True when there is no reason against it.
    reasons : list of str
        One sentence per problem, with its position on the normal rack.
    normal_pressure_angle_min_deg : float, deg
        Smallest flank angle of the normal rack (from the normal to the pitch line).
    min_tip_radius, min_root_radius : float, mm
        Smallest hob tip and root radius the rack asks for (0 at a sharp corner, inf when straight).
    tip_thickness : float, mm
        Width of the hob tooth at 5 % of the rack depth above its tip.
    notes : tuple of str
        What was judged within the profile's accuracy and so is no reason (an envelope that turns back
        by less than the points can show, or along itself at a slip singularity).
    undercut : bool
        Whether a rotor is undercut by its rack (:func:`undercut_reasons` found a stretch); a gear's
        undercut is :func:`hob.undercut.gear_undercut`'s (a hob makes it: no reason).
    undercut_undecided : bool
        Of a mate generated from scattered points: a turn-back that reads a crossing whose depth lies
        between what the fit's local error can make and the gate ``undercut_accuracy``: it may be an
        undercut the points cannot confirm (:func:`undercut_reasons`); not a reason, named in ``notes``.
    """

    hobbable: bool
    reasons: list[str]
    normal_pressure_angle_min_deg: float
    min_tip_radius: float
    min_root_radius: float
    tip_thickness: float
    notes: tuple[str, ...] = ()
    undercut: bool = False
    undercut_undecided: bool = False


def judge(
    rack: DerivedRack,
    limits: HobLimits | None = None,
    accuracy: float = 0.0,
    measured: bool | None = None,
    undercut_accuracy: float | None = None,
    tangent_accuracy: float = 0.0,
    point_scatter: float = 0.0,
    point_spacing: float = 0.0,
) -> Verdict:
    """Judge a derived rack in its normal section (module docstring).

    Parameters
    ----------
    rack : DerivedRack
        The rack of a rotor or gear (its helix angle gives the normal section).
    limits : HobLimits, optional
        Limits of a producible hob; default the workshop values.
    accuracy : float, mm
        How far the profile the rack was derived from may lie from the true one (a pair from
        measured points: :attr:`rotorcad.screw_rotors.ScrewRotors.accuracy`; 0 for a design). A
        loop of the rack narrower than this (or than :data:`FOLD_TOLERANCE`) is a fold of the fit,
        not an undercut the points can show.
    measured : bool, optional
        Whether the rotor's profile was fitted to its own points (``male-points``, ``female-points``),
        so that a sharp corner below its tip shows as a stall across which the fit turns
        (:func:`undercut_reasons`); default ``accuracy > 0``. A pair generated from a rack's points
        has envelopes for its rotors, whose undercut is their envelope turning back, as a design's.
    undercut_accuracy : float, mm, optional
        Of a rotor generated from points (``accuracy > 0``, not ``measured``): how deep the rack must
        cut into its generated points for an undercut (:func:`undercut_reasons`); default
        :data:`FOLD_TOLERANCE`, and never below it (:func:`undercut_tolerance` gives it for a pair).
    tangent_accuracy : float, rad
        Of points with scatter, how well their tangents are known
        (:attr:`rotorcad.screw_rotors.ScrewRotors.tangent_accuracy`); 0 for exact points, whose mate's
        turn-back is judged by its crossing angle too (:func:`undercut_reasons`).
    point_scatter, point_spacing : float, mm
        Of points with scatter, one point's standard deviation and the points' median spacing
        (:attr:`rotorcad.screw_rotors.ScrewRotors.point_accuracy` / 2 and ``point_spacing``): the
        depth of a mate's turn-back is known to the fit's error averaged over the stretch it removes
        (:func:`depth_accuracy`); 0 where not known (no undecided state).

    Returns
    -------
    Verdict
    """
    lim = limits or HobLimits()
    frame = rack_frame(rack)
    pts, tan, idx, cutting = frame.points, frame.tangents, frame.piece_index, frame.cutting
    reasons: list[str] = []

    def at(i: int) -> str:
        return f"at x = {pts[i, 0]:.3f} mm, y = {pts[i, 1]:.3f} mm of the normal rack"

    if rack.lost_fraction > 0:
        reasons.append(
            f"{100 * rack.lost_fraction:.1f} % of the profile has no rack point: its normal misses the pitch circle, "
            "so no generating position exists there."
        )
    snapped = np.round(pts, 9)  # floating noise (1e-15) on straight pieces must not read as a loop
    keep = np.concatenate([[True], np.any(np.diff(snapped, axis=0) != 0.0, axis=1)])
    line = shapely.LineString(snapped[keep])
    fold = max(FOLD_TOLERANCE, accuracy)
    if not line.is_simple and _crosses_itself(snapped[keep], fold):
        noded = shapely.node(line)
        hits = shapely.get_coordinates(shapely.intersection(line, shapely.MultiLineString(list(noded.geoms)).boundary))
        where = f" near x = {hits[0, 0]:.3f} mm, y = {hits[0, 1]:.3f} mm" if len(hits) else ""
        reasons.append(
            f"the rack crosses itself{where}: the profile is undercut there (two parts of it are generated by crossing "
            "parts of the rack), so a hob makes only the outer envelope and not this profile."
        )
    back = np.nonzero(cutting & (tan[:, 0] < -1e-6))[0]
    if len(back):
        i = back[np.argmin(tan[back, 0])]
        reasons.append(
            f"the rack flank overhangs (re-entrant, running back along the pitch line) {at(i)}: a hob would have to "
            "cut under its own tooth, so this part comes out undercut."
        )
    flank = frame.flank
    angles = np.degrees(np.arctan2(np.abs(tan[:, 0]), np.abs(tan[:, 1])))
    if point_scatter > 0 and point_spacing > 0:  # a straight flank's angle from its line (hob.straight_flank)
        angles = straight_flank_angles(pts, tan, angles, flank, frame.arc, point_scatter, point_spacing, MEASURED_MIN_TURN)
    alpha_min = float(angles[flank].min()) if flank.any() else 90.0
    if alpha_min < lim.min_flank_angle_deg:
        i = np.nonzero(flank)[0][np.argmin(angles[flank])]
        what = (
            "the rack flank stands perpendicular to the pitch line there, so the generating contact runs off along the pitch "
            "line and the hob tooth flank has no side relief"
            if alpha_min < 0.5
            else "the hob tooth flank gets too little side relief"
        )
        reasons.append(
            f"the flank angle falls to {alpha_min:.2f} deg {at(i)}, below the minimum {lim.min_flank_angle_deg:g} deg: {what}."
        )
    # curvature from the exact tangents: turning angle over arc length, travelling +x
    psi = np.unwrap(np.arctan2(tan[:, 1], tan[:, 0]))
    ds = np.hypot(*np.diff(pts, axis=0).T)
    # a sharp corner: pieces meeting with a turn; of a measured profile's rack, a turn above the
    # smallest corner between measured pieces (MEASURED_MIN_TURN, as the rack's corner fans): a
    # spline fitted next to a land of the points meets that land's exact arc with a kink of 1-2 mrad
    # (the rack-involute female's full CSV: 1.6 mrad at its tip land, read as a hob tip radius 0)
    kink = MEASURED_MIN_TURN if accuracy > 0 else 1e-3
    jumps = (idx[:-1] != idx[1:]) & cutting[:-1] & cutting[1:] & (np.abs(np.diff(psi)) > kink) & (ds < 1e-6 * rack.period)
    # the curvature is taken along runs of cutting points that a sharp corner or a corner path does
    # not interrupt: pieces meeting without a corner (a measured rack's fitted pieces, a sliver of
    # spline between a land and a corner) are one run, so that a piece shorter than the base does
    # not read its few samples' kink as a sharp tool radius
    run = np.concatenate([[0], np.cumsum(jumps | (cutting[:-1] != cutting[1:]))])
    same = (idx[:-1] == idx[1:]) & cutting[:-1] & cutting[1:] & (ds > 0)
    kappa = np.where(same, np.diff(psi) / np.where(ds > 0, ds, 1.0), 0.0)
    # the turn over an arc length of CURVATURE_BASE at least, within one cutting piece: sub-micrometre
    # folds of a measured rack (see above) must not read as a sharp tool radius
    arc = np.concatenate([[0.0], np.cumsum(ds)])
    j = np.minimum(np.searchsorted(arc, arc + CURVATURE_BASE), len(arc) - 1)
    piece_ok = (run[j] == run) & cutting & cutting[j] & (arc[j] - arc > 0.5 * CURVATURE_BASE)
    kappa_w = np.where(piece_ok, (psi[j] - psi) / np.where(arc[j] > arc, arc[j] - arc, 1.0), 0.0)[:-1]
    # within the base of a run's end the window looks back instead; a run shorter than half the base
    # (a sliver between corners) keeps its own estimate
    i0 = np.maximum(np.searchsorted(arc, arc - CURVATURE_BASE, side="right") - 1, 0)
    back_ok = (run[i0] == run) & cutting & cutting[i0] & (arc - arc[i0] > 0.5 * CURVATURE_BASE)
    kappa_b = np.where(back_ok, (psi - psi[i0]) / np.where(arc > arc[i0], arc - arc[i0], 1.0), 0.0)[:-1]
    short = np.zeros(len(kappa), dtype=bool)
    last = np.flatnonzero(np.diff(run) != 0)
    short[last] = True
    kappa = np.where(piece_ok[:-1], kappa_w, np.where(back_ok[:-1], kappa_b, np.where(short, 0.0, kappa)))
    # a turn of less than a micro-radian over a rack period is a straight piece (rounding noise of
    # its tangents), whose radius is infinite, not 1e12 mm
    kappa = np.where(np.abs(kappa) * rack.period < 1e-6, 0.0, kappa)
    tip_r = float(1.0 / kappa[kappa > 0].max()) if np.any(kappa > 0) else np.inf
    root_r = float(-1.0 / kappa[kappa < 0].min()) if np.any(kappa < 0) else np.inf
    corners = np.nonzero(jumps)[0]
    turns = np.diff(psi)[corners]
    seam = _seam_turn(pts, tan, cutting, rack.normal_period, kink)
    if seam:  # the corner where one period of the rack meets the next
        corners, turns = np.append(corners, len(pts) - 1), np.append(turns, seam)
    for kind, chosen in (("tip", corners[turns > 0]), ("root", corners[turns < 0])):
        if len(chosen):
            if kind == "tip":
                tip_r = 0.0
            else:
                root_r = 0.0
            more = f" (and {len(chosen) - 1} more)" if len(chosen) > 1 else ""
            reasons.append(f"the rack has a sharp corner (hob {kind} radius 0) {at(int(chosen[0]))}{more}.")
    if 0 < tip_r < lim.min_tip_radius:
        i = int(np.argmax(kappa))
        reasons.append(f"the hob tip radius is {tip_r:.4f} mm {at(i)}, below the minimum {lim.min_tip_radius:g} mm.")
    if 0 < root_r < lim.min_root_radius:
        i = int(np.argmin(kappa))
        reasons.append(f"the hob root radius is {root_r:.4f} mm {at(i)}, below the minimum {lim.min_root_radius:g} mm.")
    fitted = accuracy > 0 if measured is None else measured
    # a rotor fitted to its own scattered points turns back by the fit's ringing too (the N-rack female from its 300
    # points a lobe with 2 um: 0.4-1.7 um deep at r = 42.2-43.3 mm on 8 of seeds 11-30): within the gate it is
    # undecided (undercut_reasons), deeper an undercut as before (the trend is a mate's test, not its own)
    gated = accuracy > 0 and (not fitted or tangent_accuracy > 0)
    depth_tolerance = max(FOLD_TOLERANCE, undercut_accuracy or 0.0) if gated else None
    notes: list[str] = []
    undecided: list[str] = []
    undercut = undercut_reasons(
        rack,
        measured=fitted,
        tolerance=depth_tolerance,
        notes=notes,
        accuracy=accuracy,
        scattered=tangent_accuracy > 0,
        local=(point_scatter, point_spacing),
        undecided=undecided,
    )
    reasons += undercut
    thickness = _tip_thickness(pts[cutting], rack.normal_period, fold)
    if thickness < lim.min_tip_thickness:
        reasons.append(
            f"the hob tooth is {thickness:.3f} mm thick near its tip (5 % of the depth above it), below the minimum "
            f"{lim.min_tip_thickness:g} mm."
        )
    return Verdict(not reasons, reasons, alpha_min, tip_r, root_r, thickness, tuple(notes), bool(undercut), bool(undecided))


def _corner_slivers(rack: DerivedRack) -> np.ndarray:
    """Return which of ``rack``'s pieces are a sliver between two corners, (pieces,) bool: no flank of the rack.

    A cutting piece between two corner fans (:attr:`rotorcad.roles.PieceRole.CORNER_FAN` before and after it) whose
    profile is shorter than :data:`CURVATURE_BASE` at the reference pair's size (scaled with the pair,
    :func:`hob.turn_back.length_scale`) is the fit's junction of the two corners, which a design has as one corner:
    its direction is not measured by any point. The narrow-tip female from its male's 2000 points a lobe, written to
    6 decimals: a piece of 1.6 um of profile (6.5 um of rack) between its tip corner's two fans stood 2.49 deg from
    the perpendicular to the pitch line, read as the rack's smallest flank angle for the design's 6.25 (its own
    flank's minimum, 6.26 deg from the points: tests/test_hob_points_samples.py).
    """
    n = len(rack.roles)
    fan = np.array([role is PieceRole.CORNER_FAN for role in rack.roles])
    if n < 3 or not fan.any():
        return np.zeros(n, dtype=bool)
    along = rack.profile if rack.profile is not None else rack.points
    step = np.hypot(*np.diff(along, axis=0).T)
    same = rack.piece_index[:-1] == rack.piece_index[1:]
    length = np.bincount(rack.piece_index[:-1][same], weights=step[same], minlength=n)[:n]
    between = np.roll(fan, 1) & np.roll(fan, -1) & ~fan
    return between & (length < CURVATURE_BASE * length_scale(rack))


def _seam_turn(pts: np.ndarray, tan: np.ndarray, cutting: np.ndarray, period: float, kink: float) -> float:
    """Return the turn (rad) of the rack where its last point meets its first one period on, 0 for none.

    A rack of one whole period (its last point one normal period after its first) continues into the
    next period there: a corner between two cutting pieces at that seam is a corner of the rack like
    any other. Where the seam falls depends on where the lobe's pieces start: the narrow-tip
    design's rack put its seam exactly on the corner where its root land meets the driving flank
    (the female tip on the pitch circle, Rinder Fig. 5) and read no corner there, the same rack from
    its own points (the lobe starting elsewhere) read one.
    """
    if len(pts) < 2 or not (cutting[0] and cutting[-1]):
        return 0.0
    if np.hypot(pts[-1, 0] - pts[0, 0] - period, pts[-1, 1] - pts[0, 1]) > 1e-6 * period:
        return 0.0
    a, b = tan[-1], tan[0]
    turn = float(np.arctan2(a[0] * b[1] - a[1] * b[0], a @ b))
    return turn if abs(turn) > kink else 0.0


def _say(sentence: str, *lists: list[str] | None) -> None:
    """Append ``sentence`` to each of ``lists`` that is given (the notes, the undecided places)."""
    for out in lists:
        if out is not None:
            out.append(sentence)


def undercut_reasons(
    rack: DerivedRack,
    measured: bool = False,
    tolerance: float | None = None,
    notes: list[str] | None = None,
    accuracy: float = 0.0,
    scattered: bool = False,
    local: tuple[float, float] = (0.0, 0.0),
    undecided: list[str] | None = None,
) -> list[str]:
    """Return the undercut of a rotor by its rack, one sentence per stretch (none for a gear's rack).

    The stretches of :func:`rotorcad.inverse_rack.stalls`: the rotor's envelope turns back there
    (its flank undercut by its rack), or, for a profile given by points (``measured``), its points
    stand still across a sharp corner below its tip (two generated parts of its flank cross: a
    rotor that was undercut when it was cut).

    With ``tolerance`` (a rotor generated from another rotor's points), an envelope that turns back
    is an undercut only where the rack cuts deeper than ``tolerance`` into the rotor's points there
    (:func:`hob.cut_depth.cut_depth`) and the turn-back is a crossing, not a touch
    (:mod:`hob.turn_back`): where the design's generation factor touches 0 (a slip singularity, the
    rack-involute female at r = 56.87 mm, the N rack's at 43.5-44.6 mm) the fit's curvature errors swing
    it below 0 and the envelope turns back along itself, the rack cutting 0.8-314 um "deep" into the
    generated points while removing none of the rotor's material beyond the points' accuracy (brute
    force, tests/test_hob_datum.py); the 5/6 arc-flank male, undercut by its rack
    (tests/independent_pairs.py, brute-force cut), generated from its female's points: 5.0-13.9 um deep
    from exact points (80-2000 a lobe) and 1 um of scatter, a crossing (the generation factor's trend
    starts at -0.06 to -0.14, or of exact points its two sides meet at 3.5-4.7 deg). A shallow stretch or
    a touch goes to ``notes`` instead (``accuracy``, mm, the profile's: the touch's bound; ``scattered``:
    points with scatter, whose crossing angle is not known).

    Of scattered points the gate ``tolerance`` (twice the profile's accuracy, a bound on the largest error
    of one point over the lobe) is far above how well the depth itself is known: the envelope averages
    the fit over the stretch it removes, whose error there is :func:`depth_accuracy` (``local``: one
    point's scatter and the points' spacing, mm). Of scattered points only a trend that reads a touch (f0 from 0 up to
    :data:`hob.turn_back.FAST`: a slow generation's, the N rack's +0.006 to +0.90) lets a turn-back within
    ``tolerance`` be "not judged an undercut"; any other (a crossing's, or below 0 within its bound
    :attr:`hob.turn_back.TurnBack.accuracy`, or in the rack's fast part) leaves it undecided at this accuracy: named in
    ``notes`` and added to ``undecided``, not a reason, however shallow (the sentence says whether deeper than that
    error): the generated points may hide a real undercut entirely (the 5/6 male from its female's 300 points a lobe
    with 2 um turned by 17.3 deg: 1.21 um deep for 1.67 um; from 2000 with 1 um, seed 12: 0.15 um; with 2 um, seed
    12: 0.54 um and f0 -0.065 within its bound 0.080; brute force 39-48 um). A deeper turn-back of scattered points
    is undecided too where its trend stays in the rack's fast part (f0 above :data:`hob.turn_back.FAST`: the fit rang
    past the trend's window, which then measured neither a touch, f0 near 0, nor a crossing) or reads a crossing
    whose standard error (:attr:`hob.turn_back.TurnBack.spread`) exceeds the bound (the generation factor scatters
    more than an accurate rack's would).

    Turn-backs of a mate generated from points that lie less than a trend's reach apart are one place, judged once
    (:func:`one_place`): one sentence, never an undercut and a touch for overlapping radii.
    """
    if rack.side is None or rack.profile is None:
        return []
    radius = np.hypot(*rack.profile.T)
    out = []
    size = length_scale(rack)  # lengths along the rack scale with the pair (hob.turn_back.REFERENCE_PERIOD)
    runs = hob_stalls(rack, measured)
    for a, b, back in one_place(rack, runs) if tolerance is not None else runs:
        r = radius[a:b]
        where = f"r = {r.min():.2f}-{r.max():.2f} mm"
        deep = ""
        if back and tolerance is not None:
            lo, depths = cut_depths(rack, a, b)
            depth = float(depths.max(initial=0.0))
            onset = turn_back(rack, a, b, accuracy, scattered)
            if depth <= tolerance:
                floor = depth_accuracy(rack, lo, depths, *local) if scattered else np.inf
                if scattered and measured:
                    # the rotor's own fit turning back by less than one point is known to (the N-rack female from its
                    # 300 points a lobe with 2 um: 0.4-1.7 um for 14-16 um at r = 42.2-43.3 mm, read "undercut" on 8 of
                    # seeds 11-30; the 5/6 male's real undercut from its 2000 points with 1 um, seed 13: 7.19 um for
                    # 8.24 beside a deeper one): neither confirmed nor ruled out, whatever its trend
                    than = "more than" if depth > floor else "within"
                    sentence = (
                        f"the {rack.side.value}'s own points turn back at {where} and its rack cuts {1000 * depth:.2f} um "
                        f"into their fit there, {than} the {1000 * floor:.2f} um the fit's error over that stretch can "
                        f"make, but within the {1000 * tolerance:.2f} um one point is known to: undecided at this "
                        "accuracy (denser points or less scatter tell it)."
                    )
                    _say(sentence, notes, undecided)
                    continue
                if scattered and not 0.0 <= onset.onset <= FAST:
                    # a trend from scattered points that does not read a touch (f0 within [0, FAST]), however
                    # shallow the generated points show the turn-back: the 5/6 male's real undercut from its female's
                    # 300 points a lobe with 2 um turned by 17.3 deg (1.21 um under a floor of 1.67 um, f0 below the
                    # bound) or 2000 with 2 um, seed 12 (0.54 um, f0 -0.065 within the bound 0.080; a quarter-size
                    # copy +5.28, the fast part): brute force 39-48 um
                    than = "more than" if depth > floor else "within"
                    sentence = (
                        f"the {rack.side.value}'s envelope turns back at {where} and the rack cuts {1000 * depth:.2f} um "
                        f"into it there, {than} the {1000 * floor:.2f} um the fit's error over that stretch can make, "
                        f"{_trend_words(onset)}, but within the {1000 * tolerance:.2f} um one point is known "
                        "to: undecided at this accuracy (denser points or less scatter tell it)."
                    )
                    _say(sentence, notes, undecided)
                    continue
                if notes is not None:
                    notes.append(
                        f"the {rack.side.value}'s envelope turns back at {where}, but the rack cuts only {1000 * depth:.2f} um "
                        f"into it there, within the {1000 * tolerance:.2f} um the points are known to: not judged an undercut."
                    )
                continue
            if scattered and not measured and onset.onset > FAST:
                # the trend beyond the turn-back is the rack's fast part (its fit rings there past the window):
                # it measured neither a touch (f0 near 0) nor a crossing (the 5/6 male, 2000 a lobe with 2 um of
                # scatter: f0 +5.38 where the rack cuts 33.9 um deep, a real undercut by brute force)
                sentence = (
                    f"the {rack.side.value}'s envelope turns back at {where} and the rack cuts {1000 * depth:.1f} um into "
                    f"the generated points, but the generation factor beyond the turn-back stays in the rack's fast part "
                    f"(its trend {onset.onset:+.3f} at the step, above {FAST:g}) in the points' scatter: neither a touch nor "
                    "a crossing is seen, undecided at this accuracy (denser points or less scatter tell it)."
                )
                _say(sentence, notes, undecided)
                continue
            if scattered and not measured and onset.crossing and onset.spread > onset.accuracy:
                # the generation factor scatters about its trend more than an accurate rack's would: its onset is not
                # known to the bound (the N-rack female from its male's 2000 points a lobe with 2 um at a quarter
                # size, seed 12: f0 -3.81 for a bound of 0.71, its standard error 2.66, along a slow generation that
                # only touches 0; brute force 0.3 um)
                sentence = (
                    f"the {rack.side.value}'s envelope turns back at {where} and the rack cuts {1000 * depth:.1f} um into "
                    f"the generated points, {_trend_words(onset)}, but the generation factor scatters about that trend so "
                    f"that its start is known to {onset.spread:.3f} only, more than that bound: undecided at this "
                    "accuracy (denser points or less scatter tell it)."
                )
                _say(sentence, notes, undecided)
                continue
            if scattered and not measured and onset.crossing and onset.onset >= -onset.reach:
                # the trend read far past the step (beyond a fold of the rack from the points, 2 x 1.48 mm: the N-rack
                # female from its male's 300 points a lobe with 2 um, seed 14, f0 -2.87 for a bound of 1.22 at the
                # window, 5.0 back at the step; brute force and the design: a touch at the slip singularity)
                sentence = (
                    f"the {rack.side.value}'s envelope turns back at {where} and the rack cuts {1000 * depth:.1f} um into "
                    f"the generated points, {_trend_words(onset)}, but that trend is read past a fold of the rack from "
                    f"the points and, taken back to the step, is known to {onset.reach:.3f} only: undecided at this "
                    "accuracy (denser points or less scatter tell it)."
                )
                _say(sentence, notes, undecided)
                continue
            # where the rack from the points folds back along itself, the parts the run leaves are the fold's (the
            # N-rack female from its male's exact points, scan phase 0: the removed run reached 0.4 mm into the slow
            # generation, whose points the rack touches 1-3.6 um deep, and its ends met at 2.13 deg): the trend past
            # the fold decides (hob.turn_back)
            folded = max(onset.fold, fold_length(rack, a, b))
            angle = 0.0 if scattered or folded > FOLD_LENGTH * size else crossing_angle(rack, lo, depths, FOLD_TOLERANCE)
            if not measured and not onset.crossing and angle <= CROSSING_ANGLE:
                if notes is not None:
                    seen = "" if scattered else f", and its two sides meet at {np.degrees(angle):.2f} deg"
                    if folded > FOLD_LENGTH * size:
                        seen = f" (read past the {folded:.2f} mm over which the rack from the points folds back along itself)"
                    notes.append(
                        f"the {rack.side.value}'s envelope turns back at {where} (the rack cuts {1000 * depth:.1f} um into "
                        f"the generated points, along the curve), but it only touches, as at a slip singularity, where the "
                        f"generation factor touches 0: its trend beyond the turn-back starts at {onset.onset:+.3f}, not below "
                        f"-{onset.accuracy:.3f}, which the points' accuracy allows{seen}; an undercut's starts below 0 and "
                        "crosses it: not judged an undercut."
                    )
                continue
            deep = f" (the rack cuts {1000 * depth:.1f} um into it, more than the points' {1000 * tolerance:.2f} um)"
        how = "its envelope turns back there" if back else "its points stand still there (a sharp corner)"
        out.append(
            f"the {rack.side.value} is undercut at {where}, {radius.max() - r.max():.2f} mm below "
            f"its tip: {how}{deep} while the rack runs from x = {rack.points[a, 0]:.3f} to {rack.points[b - 1, 0]:.3f} mm, "
            "so two generated parts of its flank cross and a hob makes only their outer envelope."
        )
    return out


def hob_stalls(rack: DerivedRack, measured: bool = False) -> list[tuple[int, int, bool]]:
    """Return :func:`rotorcad.inverse_rack.stalls` of ``rack`` as the hob judges them: its lengths scaled with the pair.

    The stall's shortest run, the generation factor's curvature base and the sharp span
    (:data:`rotorcad.inverse_rack.SHARP_SPAN`) times :func:`hob.turn_back.length_scale` (a quarter-size copy of the
    5/6 arc-flank pair from 2000 points a lobe stalled over 0.1-0.2 mm of rack, under the unscaled 0.25 mm: no
    turn-back found where the full-size pair's is an undercut).

    Parameters
    ----------
    rack : DerivedRack
        A rotor's rack with its ``profile``.
    measured : bool
        Whether the rotor's profile was fitted to its own points (:func:`rotorcad.inverse_rack.stalls`).

    Returns
    -------
    list of (int, int, bool)
        Each run's first and one-past-last point index, and whether the envelope turns back there.
    """
    size = length_scale(rack)
    return stalls(rack, measured, sharp_span=SHARP_SPAN * size, scale=size)


def _trend_words(onset: TurnBack) -> str:
    """Return how the generation factor's trend beyond a turn-back reads, for an undecided sentence."""
    f0, bound = f"{onset.onset:+.3f}", f"{onset.accuracy:.3f}"
    if onset.crossing:
        return f"and as a crossing (an undercut's: its trend beyond the turn-back starts at {f0}, below -{bound})"
    if onset.onset < 0:
        return f"and its trend beyond the turn-back starts at {f0}, below 0 as a crossing's but within the -{bound} allowed"
    return f"and its trend beyond the turn-back starts at {f0}, in the rack's fast part (above {FAST:g}): no touch's"


def one_place(rack: DerivedRack, runs: list[tuple[int, int, bool]]) -> list[tuple[int, int, bool]]:
    """Join the turn-backs of a mate generated from points that are one place: one judgement each.

    Where the fit of the points rounds the step into a slow generation (the N-rack female from its male's 300
    points a lobe, exact or with 2 um of scatter), the generation factor swings to about -4 over the rack's fold
    (:func:`hob.turn_back.turn_back`), comes back above 0 for a few points and falls to the slow part's 0 again:
    :func:`rotorcad.inverse_rack.stalls` finds two or three turn-backs 0.3-0.5 mm of rack apart, whose cut depths
    are the same points', and each was judged alone: an undercut at r = 43.33-44.99 mm and "only touches" at
    r = 43.57-44.22 mm in one answer (newuser issue 22, F3). Turn-backs less than a trend's reach apart
    (:data:`hob.turn_back.TRANSITION` + :data:`hob.turn_back.TREND_LENGTH` of rack between them) are one run:
    the later one lies within the span that judges the earlier, so it cannot be told apart from it.

    Parameters
    ----------
    rack : DerivedRack
        The mate's rack.
    runs : list of (int, int, bool)
        :func:`rotorcad.inverse_rack.stalls`' runs, in order along the rack.

    Returns
    -------
    list of (int, int, bool)
        The runs with each such group of turn-backs joined into one (first of the first, stop of the last).
    """
    reach = scaled(TRANSITION + TREND_LENGTH, rack.period)
    arc = np.concatenate([[0.0], np.cumsum(np.hypot(*np.diff(rack.points, axis=0).T))])
    out: list[tuple[int, int, bool]] = []
    for a, b, back in runs:
        last = out[-1] if out else None
        if back and last is not None and last[2] and arc[a] - arc[last[1] - 1] < reach:
            out[-1] = (last[0], b, True)
        else:
            out.append((a, b, back))
    return out


def depth_accuracy(rack: DerivedRack, first: int, depths: np.ndarray, scatter: float, spacing: float) -> float:
    """Return how deep (mm) the fit's error alone may make a mate's turn-back, 95 %: 2 sigma sqrt(2 / m).

    The depth is the rack's reach past the generated points over the stretch it removes (``depths`` > 0,
    :func:`hob.cut_depth.cut_depths`), both from the same fit of the given points: its error is the fit's
    error averaged over that stretch, of m = its length / ``spacing`` points (a least-squares mean of m
    points of scatter ``scatter`` errs by sigma / sqrt(m); two such, the rack and the generated point:
    sqrt(2)). Of the rack's points along the stretch the length is taken; inf where not known.

    Parameters
    ----------
    rack : DerivedRack
        The mate's rack.
    first : int
        The rack point of ``depths[0]``.
    depths : (m,) float array, mm
    scatter, spacing : float, mm
        One given point's standard deviation and the given points' median spacing.
    """
    if scatter <= 0 or spacing <= 0 or not np.any(depths > 0):
        return np.inf
    k = first + np.flatnonzero(depths > 0)
    pts = rack.points[np.arange(k.min(), k.max() + 1)]
    length = float(np.hypot(*np.diff(pts, axis=0).T).sum())
    m = max(length / spacing, 1.0)
    return max(FOLD_TOLERANCE, 2.0 * scatter * np.sqrt(2.0 / m))


def local_scatter(rotors: object) -> tuple[float, float]:
    """Return one given point's scatter sigma and the points' median spacing (mm) of a pair from scattered points.

    (``point_accuracy`` / 2, ``point_spacing``) of :class:`rotorcad.screw_rotors.ScrewRotors` (one point's accuracy
    is 2 sigma), for :func:`judge`'s ``point_scatter`` and ``point_spacing``; (0, 0) for exact points or a design.
    """
    if not getattr(rotors, "tangent_accuracy", 0.0):
        return 0.0, 0.0
    point = getattr(rotors, "point_accuracy", None) or 0.0
    return 0.5 * float(point), float(getattr(rotors, "point_spacing", None) or 0.0)


def undercut_tolerance(rotors: object) -> float:
    """Return how deep (mm) a rack must cut into a rotor generated from points for an undercut.

    Of scattered points (a tangent accuracy stated), twice the profile's accuracy (the bound on the
    largest deviation over the lobe): the depth compares a generated point of the mate with the rack
    at another position, each known to that accuracy. Measured where the rack-involute design's
    generation factor touches 0 (the female at r = 56.87 mm, from the male's points, 500 a lobe with
    1 um of scatter, accuracy 3.9-4.1 um): the rack cut 0.6-2.3 um into the generated female (one seed of
    eight 19.5 um); the
    undercut 5/6 arc-flank male from its female's points (2000 a lobe, 1 um, accuracy 4.2 um): 13.9 um.
    Of exact points :data:`FOLD_TOLERANCE`: their accuracy is the interpolation's bound between the
    points (17.7 um at 80 a lobe), a smooth error that does not make two nearby generated parts cross;
    the 5/6 male from its female's 80 exact points a lobe is cut 5.2 um deep. Deeper turn-backs that only
    touch (a slip singularity) are told apart by :mod:`hob.turn_back`, whatever their depth.

    Parameters
    ----------
    rotors : ScrewRotors
        The pair (``accuracy``, ``tangent_accuracy``); a design or a gear gives 0.
    """
    accuracy = float(getattr(rotors, "accuracy", 0.0))
    if not accuracy:
        return 0.0
    scattered = getattr(rotors, "tangent_accuracy", 0.0) > 0
    return max(FOLD_TOLERANCE, 2.0 * accuracy if scattered else 0.0)


def _tip_thickness(pts: np.ndarray, period: float, fold: float = FOLD_TOLERANCE) -> float:
    """Return the width (mm) of the hob material (above the rack curve) at 5 % of the depth above its lowest point.

    The material is the polygon of the rack (three periods) closed a depth above it; the line at
    that height crosses its edges at points whose even-odd pairs bound the material (a loop of a
    self-crossing rack is a hole, as shapely's ``make_valid`` makes it: 20 s on a 3 695-point
    measured rack, this O(n log n)). Of the pieces, one period's, whole whatever the rack's phase,
    those wider than ``fold`` count (not a fold's sliver).

    Parameters
    ----------
    pts : (n, 2) float array, mm
        The normal rack's cutting points, travelled in +x.
    period : float, mm
        The normal rack's period.
    fold : float, mm
        Narrowest piece that counts.

    Returns
    -------
    float, mm
        The narrowest piece; 0 when none is wider than ``fold``.
    """
    y0, y1 = pts[:, 1].min(), pts[:, 1].max()
    level = y0 + 0.05 * (y1 - y0)
    chain = np.vstack([pts - [period, 0.0], pts, pts + [period, 0.0]])
    top = y1 + (y1 - y0)
    ring = np.vstack([chain, [[chain[-1, 0], top], [chain[0, 0], top]], chain[:1]])
    a, b = ring[:-1], ring[1:]
    crosses = (a[:, 1] <= level) != (b[:, 1] <= level)  # half-open: a vertex on the line counts once
    u = (level - a[crosses, 1]) / (b[crosses, 1] - a[crosses, 1])
    x = np.sort(a[crosses, 0] + u * (b[crosses, 0] - a[crosses, 0]))
    start, end = x[0::2], x[1::2]  # inside between even-odd pairs
    # each piece once, whole: the one starting within the middle period (a piece cut at the period's
    # ends read half the width or less by the rack's phase: the rack-involute male's hob tooth 13.25 mm
    # from the design, 26.52 mm from the female's points)
    once = (start >= pts[0, 0]) & (start < pts[0, 0] + period)
    widths = (end - start)[once & (end - start > fold)]
    return float(widths.min()) if len(widths) else 0.0


def _crosses_itself(pts: np.ndarray, fold: float = FOLD_TOLERANCE) -> bool:
    """Tell whether the polyline crosses itself so that it encloses a loop wider than ``fold`` (mm).

    The width of a loop is its mean width 2 area / perimeter, for each loop that shapely's noding
    and polygonizing finds: an undercut's swallowtail is tens of micrometres wide, the zigzag of a
    measured rack where its samples fold back along the curve is not.
    """
    segs = shapely.linestrings(np.stack([pts[:-1], pts[1:]], axis=1))
    tree = shapely.STRtree(segs)
    a, b = tree.query(segs, predicate="intersects")
    far = np.abs(a - b) > 1
    if len(pts) > 2 and np.allclose(pts[0], pts[-1]):
        far &= ~(((a == 0) & (b == len(segs) - 1)) | ((b == 0) & (a == len(segs) - 1)))
    if not np.any(far):
        return False
    loops = shapely.get_parts(shapely.polygonize(shapely.get_parts(shapely.node(shapely.LineString(pts)))))
    if len(loops) == 0:
        return False
    width = 2 * shapely.area(loops) / np.maximum(shapely.length(loops), 1e-300)
    return bool(np.any(width > fold))

"""The blow-hole's apex of a given profile where a tip corner's path hands over to a flank.

Rinder (*Sonderverzahnungen für Schraubenverdichterrotoren*, sec. 2.2.2) bounds the blow-hole by the
contact line's end next to the housing cusp. Where a rotor's tip is a sharp corner (the narrow-tip, the
asymmetric SRM, the rack-involute male), the meshline runs along that rotor's tip circle while the
corner is in contact (the corner's path, Rinder's "Radlinien der Punkte") and hands over to the flank's
contacts where the flank's normal at the corner passes through the pitch point C: the apex is that
hand-over, on the tip circle. Of a profile given by points it is placed three ways here, each from
another part of the fit:

* the joint of the corner's path and the flank's meshline piece (:func:`corner_handover`): the fitted
  corner and the flank's end tangent there, the fit's weakest point (its end);
* the flank's meshline extrapolated to the tip circle from beyond one resolution of its end
  (:func:`flank_extrapolation`): the flank where the fit is best, not its end. A smoothing spline through
  scattered points rounds the curvature step where a flank meets the corner's point-generated part
  (the narrow-tip female's straight flank meeting the trochoid of the male tip corner): that rounding
  turned the meshline inside the male tip circle and the blow-hole read +34..+44 % in every seed (300
  points a lobe, 1 um of scatter; 2.69-2.74 mm² extrapolated, design 2.778);
* :func:`rotorcad.meshing.meshline.turn_corner`, a quadratic over 2-8 resolutions of both branches.

The extrapolations hold only where their window is a small part of the flank's meshline
(:data:`LOCAL_EXTRAPOLATION`); at 80 points a lobe the resolution (from the chords' sagitta) is 3-6 mm and
the joint is the better.
"""

from __future__ import annotations

import numpy as np

from rotorcad.meshing.defects import MESHLINE_GAIN, resolution
from rotorcad.meshing.generating_line import line_apex
from rotorcad.meshing.meshline import MeshlinePiece, turn_corner, with_neighbours
from rotorcad.roles import PieceRole
from rotorcad.rotor_pair import RotorPair

TURN_WINDOW = 8.0
"""How many meshline resolutions from the turn :func:`rotorcad.meshing.meshline.turn_corner` fits a branch over."""

FLANK_WINDOW = (1.0, 4.0)
"""Where along the flank's meshline, in resolutions from its end at the tip circle, :func:`flank_extrapolation`
fits its quadratic: beyond the first resolution, which the fit's rounding of the hand-over bends (the
narrow-tip female, 500 points a lobe with 1 um of scatter, five seeds: 2.81 +- 0.30 mm² for the design's
2.778 over 1-4 resolutions, 2.48 +- 0.18 over 2-8, 2.99 +- 0.21 over 0.5-4)."""

LOCAL_EXTRAPOLATION = 0.6
"""Share of a flank's meshline piece beyond which an extrapolation's window (:data:`TURN_WINDOW` or the far
end of :data:`FLANK_WINDOW`, in resolutions) is no local extrapolation of it to the tip circle: exact points
at 300-500 a lobe 0.09 (rack-involute male, 54.6 mm of sealing meshline) and 0.32-0.37 (narrow-tip male,
14.3 mm), the narrow-tip female's points with 1 um of scatter at 300 a lobe 0.52 (10.5 mm), where the
extrapolation is the better; at 80 a lobe 0.83 (rack-involute, the judged accuracy the chords' sagitta,
34 um) and 0.75 (narrow-tip with 1 um of scatter: +18 % extrapolated), where the joint is."""

CORNER_PATHS = (PieceRole.MALE_CORNER_PATH, PieceRole.FEMALE_CORNER_PATH)


def _length(points: np.ndarray) -> float:
    return float(np.hypot(*np.diff(points, axis=0).T).sum())


def corner_handover(
    pieces: list[MeshlinePiece], j: int, local: int, own: PieceRole, gap: float
) -> tuple[np.ndarray, float] | None:
    """Return the joint of a given rotor's own tip corner's path with its flank's meshline piece, or None.

    A sharp corner of the given profile (a male's tip corner from male points, a female's from female
    points) is a fan of normals, and its rack piece a corner's path (:mod:`rotorcad.measured.corner_paths`)
    that ends where the flank's end normal at the corner passes through the pitch point.

    Parameters
    ----------
    pieces : list of MeshlinePiece
        The meshline.
    j, local : int
        The piece and the sample nearest the housing cusp.
    own : PieceRole
        The corner paths of the given rotor's own corners.
    gap : float, mm
        How far apart the two pieces' ends may be.

    Returns
    -------
    ((2,) float array, float) or None
        The joint (mm, fixed frame) and the length of the flank's meshline piece (mm); None where the
        sample is no end of a piece that meets the other there, one of them the given rotor's corner path.
    """
    piece = pieces[j]
    ends = {0: j - 1, len(piece.points) - 1: j + 1}
    if local not in ends or not 0 <= ends[local] < len(pieces):
        return None
    other = pieces[ends[local]]
    if own not in (piece.kind, other.kind) or piece.kind == other.kind or not len(other.points):
        return None
    joint = other.points[-1] if local == 0 else other.points[0]
    if np.hypot(*(joint - piece.points[local])) > gap:
        return None  # the pieces do not meet there
    flank = other if piece.kind == own else piece
    return piece.points[local], _length(flank.points)


ON_CIRCLE = 25.0
"""How many accuracies of the profile the median sample of a meshline branch may lie off a tip circle and still run
on it (a corner's path, :func:`flank_extrapolation`): from the asymmetric SRM's female points with 1 um of
scatter (2 um accuracy) the male tip corner's path ran 30-60 um inside the male tip circle."""


def _on_circle(branch: np.ndarray, tips: tuple[tuple[np.ndarray, float], ...], tolerance: float) -> int | None:
    """Return which tip circle (index into ``tips``) a branch's samples (m, 2) run on (median within ``tolerance``), or None."""
    for k, (centre, radius) in enumerate(tips):
        if len(branch) and float(np.median(np.abs(np.hypot(*(branch - centre).T) - radius))) <= tolerance:
            return k
    return None


def flank_extrapolation(
    pieces: list[MeshlinePiece],
    run: np.ndarray,
    at: int,
    reach: float,
    tips: tuple[tuple[np.ndarray, float], ...],
    accuracy: float,
    degree: int = 2,
) -> tuple[np.ndarray, float] | None:
    """Return where a flank's meshline, extrapolated from beyond one resolution of the turn, meets a tip circle.

    The meshline's samples about the one nearest the cusp (``run[at]``) form two branches; one runs on a tip
    circle (a tip corner's path: its samples 1-4 resolutions from the turn within :data:`ON_CIRCLE` accuracies
    of the male's or the female's tip circle), the other is the flank's. Where the corner's path is no branch
    (1 um of scatter on the narrow-tip female's points at 300 a lobe cut the male tip corner's path 2.2 mm
    short of the flank's piece), the circle is that of a corner's path (a rack piece of kind
    :class:`PieceRole` ``MALE_CORNER_PATH`` or ``FEMALE_CORNER_PATH``) ending within four resolutions of the
    flank's branch's start. The flank's samples from :data:`FLANK_WINDOW` resolutions of the turn are fitted
    by a polynomial in arc length, extended back, and cut with that circle (the cut nearest the turn).

    Parameters
    ----------
    pieces : list of MeshlinePiece
        The meshline (for the corner paths).
    run : (n, 2) float array, mm
        The samples of the piece holding the one nearest the cusp, with the neighbours that continue it
        (:func:`rotorcad.meshing.meshline.with_neighbours`).
    at : int
        The sample nearest the cusp.
    reach : float, mm
        The meshline's resolution (:func:`rotorcad.meshing.defects.resolution`).
    tips : tuple of two ((2,) float array, float)
        Centre and tip radius of the male and of the female (mm).
    accuracy : float, mm
        The profile's (:attr:`rotorcad.meshing.MeshingAnalysis.judged_accuracy`).
    degree : int
        Of the polynomial: 2 (the estimate), 3 (how far the extrapolation depends on its form).

    Returns
    -------
    ((2,) float array, float) or None
        The apex (mm, fixed frame) and the flank branch's length (mm); None where no branch is a flank beside
        a tip circle, the window holds under six samples or is not local (:data:`LOCAL_EXTRAPOLATION`), or
        the extension meets the circle farther than one resolution from the turn: there the meshline's
        nearest approach to the cusp is a smooth one, not a hand-over (the symmetric SRM, 300 points a lobe
        with 1 um of scatter: its lobe arc's meshline, nearest the cusp 1.4 mm before the female tip corner's
        path, extrapolated to the female tip circle 1.35 resolutions away read -12 % in every seed).
    """
    lo, hi = FLANK_WINDOW[0] * reach, FLANK_WINDOW[1] * reach
    branches = []
    for branch in (run[at::-1], run[at:]):
        s = np.concatenate([[0.0], np.cumsum(np.hypot(*np.diff(branch, axis=0).T))])
        window = (s >= lo) & (s <= hi)
        branches.append((branch, s, window, _on_circle(branch[window], tips, ON_CIRCLE * accuracy)))
    circles = [b[3] for b in branches]
    flanks = [b for b in branches if b[3] is None and b[2].sum() >= 6]
    if len(flanks) != 1:
        return None
    branch, s, window, _ = flanks[0]
    circle = next((c for c in circles if c is not None), None)
    if circle is None:  # the corner's path that ends nearest the flank's start (scatter cuts it short)
        nearest = 4.0 * reach
        for path in (p for p in pieces if p.kind in CORNER_PATHS and len(p.points)):
            off = float(np.min(np.hypot(*(path.points[[0, -1]] - branch[0]).T)))
            if off <= nearest:
                circle, nearest = (0 if path.kind is PieceRole.MALE_CORNER_PATH else 1), off
    if circle is None or hi > LOCAL_EXTRAPOLATION * s[-1]:
        return None
    fit = np.polyfit(s[window], branch[window], degree)
    u = np.linspace(-2.0 * reach, hi, 4001)
    ext = np.column_stack([np.polyval(fit[:, 0], u), np.polyval(fit[:, 1], u)])
    centre, radius = tips[circle]
    g = np.hypot(*(ext - centre).T) - radius
    cut = np.flatnonzero(g[:-1] * g[1:] <= 0)
    if len(cut) == 0:
        return None
    k = int(cut[np.argmin(np.abs(u[cut]))])
    w = g[k] / (g[k] - g[k + 1]) if g[k] != g[k + 1] else 0.0
    apex = ext[k] + w * (ext[k + 1] - ext[k])
    apex = centre + (apex - centre) * radius / np.hypot(*(apex - centre))
    if np.hypot(*(apex - run[at])) > reach:  # a smooth nearest approach, not a hand-over (HAND_OVER_REACH)
        return None
    return apex, float(s[-1])


def tip_apex(
    pieces: list[MeshlinePiece],
    j: int,
    local: int,
    tips: tuple[tuple[np.ndarray, float], ...],
    accuracy: float,
    center_distance: float,
    own: PieceRole,
    scattered: bool,
    smoothed: bool,
    pair: RotorPair | None = None,
) -> tuple[np.ndarray | None, list[np.ndarray]]:
    """Return a given profile's apex where the meshline turns or a tip corner's path hands over to a flank.

    Of :func:`rotorcad.meshing.meshline.turn_corner` (both branches extrapolated), the flank's meshline
    extrapolated to the corner path's tip circle (:func:`flank_extrapolation`) and the joint of the given
    rotor's own corner path with the flank (:func:`corner_handover`): of scattered points the flank's
    extrapolation first (it leaves out the fit's rounding of the hand-over), of exact points the turn's;
    either only where its window is local (:data:`LOCAL_EXTRAPOLATION` of the flank's piece, or of the
    turn's shorter branch), else the joint, else None. The turn's quadratics over 8 resolutions of the
    symmetric SRM's meshline at 80 points a lobe (23 mm; 1 um of scatter) read -13..-32 % where the sample
    nearest the cusp read within 5 %. The flank's extrapolation only where the scatter sets the resolution
    (``smoothed``: the accuracy of the points' set above one point's,
    :func:`rotorcad.measured.pairs.scatter_bound`); where the chords' sagitta sets it (80 points a lobe) its
    window reaches into the flank's bend (the narrow-tip male with 1 um of scatter: +16..+22 %
    extrapolated, its joint -8..+1 %).

    Parameters
    ----------
    pieces : list of MeshlinePiece
        The meshline.
    j, local : int
        The piece and the sample nearest the housing cusp.
    tips : tuple of two ((2,) float array, float)
        Centre and tip radius of the male and of the female (mm).
    accuracy : float, mm
        The profile's (:attr:`rotorcad.meshing.MeshingAnalysis.judged_accuracy`).
    center_distance : float, mm
    own : PieceRole
        The corner paths of the given rotor's own corners.
    scattered, smoothed : bool
        The points carry scatter; the scatter sets their resolution.
    pair : RotorPair, optional
        Tooth counts and centre distance: where the flank beside the corner's path is generated by a straight line
        of the male, the female or the rack (:func:`rotorcad.meshing.generating_line.line_apex`), its meshline's cut
        with the tip circle is the apex, before every other place (the narrow-tip, asymmetric SRM, SRM-B and
        rack-involute males with 1 um of scatter, seeds 0-7: -0.6..+0.5 %, where the other places read
        -9.8..+7.7 %; the rack-involute female's DXF polyline -2.3 % -> -0.02 %).

    Returns
    -------
    ((2,) float array or None, list of (2,) float arrays), mm
        The apex and every place of it that holds; where none holds, None and the places that do not (the
        turn and the flank's extrapolation beyond their local windows), for the uncertainty of the sample
        nearest the cusp.
    """
    reach = resolution(accuracy, center_distance)
    run, at = with_neighbours(pieces, j, local, reach)  # a turn at a piece's end too
    arclen = np.concatenate([[0.0], np.cumsum(np.hypot(*np.diff(run, axis=0).T))])
    corner = turn_corner(run, arclen, at, reach, tips, accuracy)
    handover = corner_handover(pieces, j, local, own, MESHLINE_GAIN * accuracy)
    extended = [flank_extrapolation(pieces, run, at, reach, tips, accuracy, deg) if smoothed else None for deg in (2, 3)]
    branches = min(arclen[at], arclen[-1] - arclen[at])  # the turn's two branches, mm
    length = next((c[1] for c in (handover, extended[0]) if c is not None), branches)
    turn = corner if corner is not None and TURN_WINDOW * reach <= LOCAL_EXTRAPOLATION * length else None
    flank = [None if e is None else e[0] for e in extended]
    joint = None if handover is None else handover[0]
    found = [c for c in (*flank, turn, joint) if c is not None]
    line = line_apex(pieces, pieces[j].points[local], tips, accuracy, pair) if pair is not None else None
    if line is not None:
        return line[0], [line[0], *found]
    for apex in (flank[0], turn) if scattered else (turn, flank[0]):
        if apex is not None:
            return apex, found
    if joint is not None:
        return joint, found
    # none holds: the sample nearest the cusp (or an arc's apex) is the apex, and the places that do not hold
    # (the turn and the flank's extrapolation over windows that are not local) say how far it may be off: the
    # asymmetric SRM's male at 80 a lobe with 2 um, its flank's meshline bent 1.9 mm inside the tip circle by
    # the fit's rounding, read 8.96 mm² (design 3.14) stating +-4.2; its turn read 1.76, its extrapolation 3.71
    weak = flank_extrapolation(pieces, run, at, reach, tips, accuracy, 2) if not smoothed else extended[0]
    return None, [c for c in (corner, None if weak is None else weak[0]) if c is not None]


__all__ = ["FLANK_WINDOW", "LOCAL_EXTRAPOLATION", "TURN_WINDOW", "corner_handover", "flank_extrapolation", "tip_apex"]

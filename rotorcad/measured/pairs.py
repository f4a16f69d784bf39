"""Rotor pairs from measured points: of the rack, of the male or of the female rotor.

The last stage of the measured-outline pipeline (:mod:`rotorcad.measured`). A rotor's fitted lobe
(:mod:`rotorcad.measured.fit`) is turned into its rack by inverse generation (Wu & Chi sec. 2,
eqs. 4-8, in the transverse section), and the pair is generated from that rack; the rotor given
comes back as its own conjugate's conjugate (a round trip that the tests check). Corner paths, its
own and the mate's (point-generated flanks, Rinder Fig. 1-4), are found
(:mod:`rotorcad.measured.mate_paths`) and marked as in the families. Calls go down the pipeline only (fit, then outline).
"""

from __future__ import annotations

import numpy as np

from rotorcad.curves import Curve, Mapped, PointPath
from rotorcad.envelope import Generated
from rotorcad.errors import DesignError
from rotorcad.inverse_rack import MEASURED_JOIN_GAP, MEASURED_MIN_TURN, with_corner_fans
from rotorcad.measured.corner_paths import corner_point_path, joined_mate_paths
from rotorcad.measured.fit import fit_residual, lobe_pieces, tangent_spread
from rotorcad.measured.mate_paths import EXACT_CORNER_WANDER, mate_corner_runs
from rotorcad.measured.outline import read_outline
from rotorcad.measured.rack_pieces import tip_corner_path
from rotorcad.measured.tangent import tip_tangent_accuracy
from rotorcad.rack_roles import piece_role
from rotorcad.roles import Flank, PieceRole, Side, tip_corner_name
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
    # Phi^-1 as scipy.stats.norm computes it (isf(q) = -ndtri(q)), without importing scipy.stats (0.3 s)
    from scipy import special

    return float(-special.ndtri((1.0 - confidence) / (2.0 * max(count, 1.0))))


def scatter_bound(sigma: float, count: float) -> float:
    """Return the bound (mm) on the largest deviation of a fitted outline caused by the points' scatter.

    k sigma (:func:`max_factor`, 95 % confidence) for ``count`` points of scatter ``sigma`` (mm): the
    smoothing fit's own error at a point has a standard deviation of at most the scatter's, and the
    largest over the lobe is that of ``count`` of them. 0 for exact points.
    """
    return max_factor(count) * sigma if sigma > 0 else 0.0


PATH_FIT = 10.0
"""Accuracies of the profile within which a mate's tip-corner path found on the rack is taken as that
corner's exact trochoid (:func:`rotorcad.measured.rack_pieces.tip_corner_path`): from the samples' exact
male points the female tip's path lies within 0.1-0.6 um of it (accuracy 0.3-1 um). Exact points only."""

SPARSE_TURN = np.radians(40.0)
"""Largest turn (rad) of the points' outline from one point to the next at which the lobe's roundings are
followed: where the points turn more near the rack points the lobe loses, the refusal says they are too sparse
(:func:`_lost_rack_refusal`). The N-rack female (tip rounding 2.07 mm) from points evenly spaced along its
exact outline, 8 start phases each: 50-62 deg a spacing (30-36 points a lobe) refused on most phases, 45 deg
(40 a lobe) and less on none, exact or with 2 um (a rounding spread over more than two spacings is read as a
rounding, :data:`rotorcad.measured.fit.LONG_ROUNDING`); 40 deg leaves a margin."""


def _lost_rack_refusal(label: str, whole: np.ndarray | None, teeth: int, lost_at: np.ndarray, share: float) -> DesignError:
    """Return the refusal of a lobe whose share ``share`` (per cent) of normals misses the pitch circle.

    Where the given points near the lost rack points turn by more than :data:`SPARSE_TURN` from one
    point to the next, they step over a rounding (the fit reads a sharp corner whose fan of normals misses
    the pitch circle) and the sentence says they are too sparse, with the points a lobe that would follow
    it (the turn a spacing scaled to :data:`SPARSE_TURN`, rounded up to 10); otherwise that the profile
    has no rack there (a drawing in metres, no rotor).

    Parameters
    ----------
    label : str
        How the points are named (``"female points"``).
    whole : (n, 2) float array, mm, or None
        The whole outline's points in the rotor's own frame (None for a drawing's curves).
    teeth : int
        The rotor's lobes.
    lost_at : (m, 2) float array, mm
        Profile points, own frame, whose normals gave no rack point.
    share : float, per cent
        Share of the lobe's samples without a rack point.

    Returns
    -------
    DesignError
    """
    lost = f"{share:.1f} % of the lobe has no rack point"
    if whole is not None and len(lost_at) and len(whole) > 4:
        step = np.roll(whole, -1, axis=0) - whole
        heading = np.arctan2(step[:, 1], step[:, 0])
        vertex_turn = np.abs((heading - np.roll(heading, 1) + np.pi) % (2 * np.pi) - np.pi)  # at each point
        from scipy.spatial import cKDTree

        near = cKDTree(whole).query(lost_at)[1]  # the given point nearest to each lost one
        around = (near[:, None] + np.arange(-2, 3)[None, :]) % len(whole)
        k = around.ravel()[np.argmax(vertex_turn[around.ravel()])]
        turn = float(vertex_turn[k])
        if turn > SPARSE_TURN:
            per_lobe = len(whole) / teeth
            enough = int(np.ceil(per_lobe * turn / SPARSE_TURN / 10.0) * 10)
            spacing = float(np.hypot(*step[k]))
            return DesignError(
                label,
                f"dense enough to follow the lobe's roundings, about {enough} points a lobe or more here",
                f"{per_lobe:.0f} points a lobe",
                f"at r = {np.hypot(*whole[k]):.2f} mm they turn by {np.degrees(turn):.0f} deg from one point to the "
                f"next ({spacing:.2g} mm apart; {np.degrees(SPARSE_TURN):.0f} deg or less follows a rounding), too "
                f"coarse to tell the rounding there from a sharp corner whose normals miss the pitch circle; {lost}",
            )
    return DesignError(label, "a profile whose every normal meets its pitch circle (it has a rack)", None, lost)


def _joints(racks: list[Curve], k: int, side: Side, period: float) -> list[np.ndarray]:
    """Return where the rack pieces beside corner ``k`` end, in the rack's travel: the corner path's targets.

    The male's pieces follow the rack's travel, the female's run against it; a neighbour across the
    lobe's ends (the first or last piece, turned by one pitch) is one rack period away, either way.
    """
    n = len(racks)
    before, after = (k - 1, k + 1) if side is Side.MALE else (k + 1, k - 1)
    shift = np.array([[0.0, 0.0], [0.0, period], [0.0, -period]])
    out = []
    for j, end in ((before, "end"), (after, "start")):
        curve = racks[j % n]
        point = curve.end if end == "end" else curve.start
        out.append(point + shift if not 0 <= j < n else point[None, :])
    return out


def _shifted(curve: Curve, pair: RotorPair, k: int) -> Curve:
    """Return a rack piece moved by -k rack periods along the pitch line (the same rack, one lobe on).

    A corner's point path stays a point path (its mate is cut from it in closed form,
    :mod:`rotorcad.rotor_cut`): the same corner of the lobe k pitches back, observed k male pitches
    later, which is the path moved by -k periods. Any other piece is mapped.
    """
    if k == 0:
        return curve
    if type(curve) is PointPath:
        turn = k * 2.0 * np.pi / pair.male_teeth  # male rotation over k rack periods
        carried = curve.carrier.to_fixed(np.array([curve.carried], dtype=float), -turn)[0]
        return PointPath(
            (float(carried[0]), float(carried[1])), curve.carrier, curve.observer, curve.s0 + turn, curve.s1 + turn, curve.offset
        )
    return Mapped(curve, ((1.0, 0.0), (0.0, 1.0)), (0.0, -k * pair.rack_period))


def _in_design_period(rack: list[RackPiece], pair: RotorPair) -> list[RackPiece]:
    """Return the rack chain with every piece within half a rack period of the male tip's middle, in travel order.

    The design's chain holds the male tip's middle at the pitch line's origin (y = 0, the male tip on
    O1O2 at t = 0, the zero of the angle convention :meth:`rotorcad.meshing.MeshingAnalysis.rinder_angle`);
    a chain derived from a female's points ran its last pieces one period on (the driving flank's
    contacts at -72 deg of male turn on the 5/6 pairs for the design's 0 to -20), and every angle read
    off them (sliding, slip, the contact's place) one male pitch away. A piece whose middle lies
    beyond half a period is moved by whole periods (:func:`_shifted`); the moved pieces end or start
    the chain, which stays continuous.
    """
    period = pair.rack_period
    ks = []
    for piece in rack:  # the median of its rack points' places along the pitch line (a piece may hold gaps)
        y = piece.curve.evaluate(np.linspace(piece.curve.s0, piece.curve.s1, 9))[0][:, 1]
        ks.append(round(float(np.nanmedian(y)) / period) if np.isfinite(y).any() else 0)
    moved = [RackPiece(_shifted(p.curve, pair, k), p.male_name, p.female_name, p.kind) for p, k in zip(rack, ks, strict=True)]
    order = sorted(range(len(rack)), key=lambda i: -ks[i])  # stable: the pieces moved back go first
    return [moved[i] for i in order]


def _at_turns(rack: list[RackPiece], period: float, depth: int = 4) -> list[RackPiece]:
    """Return the chain with each flank piece that holds two lobe parts split where its rack turns.

    A lobe fitted as one closed spline (the N rack's female from 300 exact points a lobe: no sharp
    corner) gives one rack piece over the whole period, from the male tip's middle to the next,
    falling (sealing flank) and then rising (driving flank): named by its ends it read "tip land",
    and no part of it could be placed in the design's period (:func:`_in_design_period`). A piece
    that runs more than half the rack ``period`` (mm) along the pitch line is split at the interior
    extreme of its rack's height (the male root's or tip's middle, where Rinder sec. 1.2's driving and
    sealing flanks meet) when both parts rise or fall by more than 1 % of their chords (neither a
    land); the parts are split so again, ``depth`` times at most. The geometry is unchanged (trims of
    one curve). A shorter piece is left whole: it lies within one period, and its meshline is judged
    as one piece (the symmetric SRM's male from scattered points, its driving flank run on over the
    female tip's lost path, read -9.5 % of blow-hole with that piece split at the male tip).
    """
    out = []
    for piece in rack:
        if piece.kind is not PieceRole.CURVE or depth <= 0:
            out.append(piece)
            continue
        curve = piece.curve
        s = np.linspace(curve.s0, curve.s1, 201)
        pts = curve.evaluate(s)[0]
        x = pts[:, 0]
        if not np.isfinite(pts).all() or np.ptp(pts[:, 1]) <= 0.5 * period:
            out.append(piece)
            continue
        split = None
        for k in (int(np.argmax(x)), int(np.argmin(x))):
            if not 4 <= k <= len(s) - 5:
                continue  # an extreme at an end: no turn inside
            ends = curve.evaluate(np.array([curve.s0, s[k], curve.s1]))[0]
            sides = (ends[[0, 1]], ends[[1, 2]])
            if all(abs(e[1, 0] - e[0, 0]) > 1e-2 * np.hypot(*(e[1] - e[0])) for e in sides):
                split = s[k]
                break
        if split is None:
            out.append(piece)
            continue
        halves = [
            RackPiece(curve.trimmed(a, b), piece.male_name, piece.female_name, piece.kind)
            for a, b in ((curve.s0, split), (split, curve.s1))
        ]
        out.extend(_at_turns(halves, period, depth - 1))
    return out


def _arc_names(x: np.ndarray, chord: float) -> tuple[str, str] | None:
    """Return the male's and the female's names of a flank piece that runs over a whole lobe part, else None.

    Such a piece bulges between its ends, beyond both by more than 1 % of its ``chord`` (mm; ``x``, (n,) mm, its rack
    points' heights along the travel), as the symmetric SRM's rack semicircle does (its ends on the female tip paths
    near the pitch line, 14 mm high in the middle); named by its ends it read "root land" (ends level) or "driving
    flank" (one tip path read shorter, 600 exact points a lobe). Towards the male's tip it is the male's "lobe arc"
    and the female's "flute arc", as the design names them (:mod:`rotorcad.families.srm_symmetric`); towards its
    root, the other way round.
    """
    bulge = 1e-2 * chord
    if x.max() > max(x[0], x[-1]) + bulge:
        return "lobe arc", "flute arc"
    if x.min() < min(x[0], x[-1]) - bulge:
        return "flute arc", "lobe arc"
    return None


def _role_names(rack: list[RackPiece], pair: RotorPair, rotor: Side) -> list[RackPiece]:
    """Return the pieces named by their lobe part (:class:`rotorcad.roles.Flank`), as the design's are.

    The part is read off the rack (:func:`rotorcad.rack_roles.piece_role`) as
    :func:`rotorcad.meshing.meshline.flank_roles` reads it per point (Rinder sec. 1.2): rising towards the male
    tip along the travel, the driving flank; falling, the sealing flank; flat (to 1 % of its chord: fitted points
    leave a land micrometres off flat), the tip land in the male's addendum's outer half, else the root land; a
    flank piece that bulges between its ends runs over a lobe part (the symmetric SRM's "lobe arc",
    :func:`_arc_names`). A corner path is
    named by its corner (:func:`rotorcad.roles.tip_corner_name`: "sealing male tip corner"), a fan's path by the
    rotor whose corner it is; a corner path across O1O2 (its ends a quarter of its chord or more either side)
    takes the role of where it crosses, above the pitch point C the tip, below it the root, and is named "male
    tip corner (both flanks)".
    """
    out = []
    for piece in rack:
        pts = piece.curve.evaluate(np.linspace(piece.curve.s0, piece.curve.s1, 9))[0]
        pts = pts[np.isfinite(pts).all(axis=1)]  # a piece may hold gaps (no rack point)
        pts = pts if len(pts) else np.zeros((2, 2))
        role = piece_role(pts, piece.kind is not PieceRole.CURVE, pair.male_pitch_radius, pair.male_addendum)
        arc = _arc_names(pts[:, 0], float(np.hypot(*(pts[-1] - pts[0])))) if piece.kind is PieceRole.CURVE else None
        if piece.kind is not PieceRole.CURVE:
            name = tip_corner_name(role, Side.MALE if piece.kind is PieceRole.MALE_CORNER_PATH else Side.FEMALE)
            out.append(RackPiece(piece.curve, name, name, piece.kind))
        elif arc is not None:
            out.append(RackPiece(piece.curve, *arc, piece.kind))
        else:
            name = f"{role} flank" if role in (Flank.DRIVING, Flank.SEALING) else f"{role} land"
            out.append(RackPiece(piece.curve, name, name, piece.kind))
    return out


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
    tip_pieces = pieces  # in the rotor's own frame
    # the accuracy bounds the largest deviation over the lobe's points, not one point's (2 sigma)
    per_lobe = (len(outline.whole) if outline.whole is not None else 0) / max(teeth, 1)
    point_acc = max(outline.accuracy, fit_residual(pair, outline, pieces, rotor))  # one point's: 2 sigma
    acc = max(point_acc, scatter_bound(outline.sigma, per_lobe))
    rotor = side.value
    if side is Side.MALE:
        body, mate_body, centre, teeth = mesh.male, mesh.female, np.zeros(2), pair.male_teeth
    else:
        shift = (pair.center_distance, 0.0)
        pieces = [(name, Mapped(curve, ((1.0, 0.0), (0.0, 1.0)), shift)) for name, curve in pieces]
        body, mate_body, centre, teeth = mesh.female, mesh.male, np.array(shift), pair.female_teeth
    own, other = PieceRole.corner_path_of(side), PieceRole.corner_path_of(side.other)
    mate_centre = np.array([pair.center_distance, 0.0]) if side is Side.MALE else np.zeros(2)  # the mate's frame
    mate_tip = (mate_centre, side.pick(pair.female_tip_radius, pair.male_tip_radius), 1e-3 * pair.center_distance)
    # the resolution of the defect tests (rotorcad.meshing.resolution) at the profile's accuracy
    shortest = max(5e-3 * pair.center_distance, float(np.sqrt(8.0 * pair.center_distance * acc)))
    same = EXACT_CORNER_WANDER * acc if outline.sigma <= 0 else 0.0  # of exact points: one corner's path
    # a flank's tangent through points each within point_acc is known to point_acc over one point spacing
    spacing = float(np.median(np.hypot(*np.diff(outline.whole, axis=0).T))) if outline.whole is not None else 0.0
    point_turn = point_acc / spacing if spacing > 0 else 0.0
    spread = (
        tangent_spread(outline, teeth, label or f"{side.value} points")
        if outline.sigma <= 0 and outline.whole is not None
        else None
    )
    parts: list[list[RackPiece]] = []
    lost, total = 0, 0
    lost_at: list[np.ndarray] = []
    gap = MEASURED_JOIN_GAP if outline.sigma > 0 else 2e-3  # scattered points' fits leave a corner's ends apart
    fans = with_corner_fans(pieces, centre, 2 * np.pi / teeth, MEASURED_MIN_TURN, gap)
    racks = []
    for _name, curve in fans:
        gen = Generated(curve, body, mesh.rack, limits=depth)
        rack_curve = gen.reversed() if side is Side.MALE else gen  # travelled in +y (the rack's +x)
        s = np.linspace(rack_curve.s0, rack_curve.s1, 400)
        ok = np.isfinite(rack_curve.evaluate(s)[0]).all(axis=1)
        lost, total = lost + int((~ok).sum()), total + len(ok)
        if not ok.all():  # where, in the rotor's own frame (the parent's parameter is the rack's)
            lost_at.append(curve.evaluate(s[~ok])[0] - centre)
        racks.append(rack_curve)
    for k, (_name, curve) in enumerate(fans):
        rack_curve = racks[k]
        if curve.is_corner():  # its path as the corner's own point path (the mate cut in closed form)
            targets = _joints(racks, k, side, pair.rack_period)
            path = corner_point_path(curve, body, mesh.rack, targets, gap)
            if path is None and np.hypot(*(targets[0][:, None, :] - targets[1][None, :, :]).T).min() <= gap:
                # the racks beside the corner meet: it turns no rack point (a corner on the pitch circle, as
                # the narrow-tip female's tip drawn exactly), and its fan's own rack curve jumps to the far root
                continue
            piece = rack_curve if path is None else path
            parts.append([RackPiece(piece, f"{rotor} tip corner", f"{rotor} tip corner", kind=own)])
            continue
        mate = Generated(rack_curve, mesh.rack, mate_body)
        runs = mate_corner_runs(
            rack_curve,
            mate,
            tolerance=1e-4,
            scattered=outline.sigma > 0,
            tip=mate_tip,
            shortest=shortest,
            same_corner=same,
            accuracy=acc,
            spacing=spacing,
        )
        # of exact points, the mate's tip corner path as its exact trochoid where the part follows one
        # (rack_pieces.tip_corner_path); of scattered points (2 um) the trochoid held within 10 accuracies moved
        # the symmetric SRM's blow-hole by -19 % (test_verdict_invariance), so their path stays as generated
        fitted = outline.sigma <= 0
        exact = [
            tip_corner_path(pair, side.other, rack_curve, a, b, PATH_FIT * acc) if c and fitted else None for a, b, c in runs
        ]
        parts.append(
            [
                RackPiece(rack_curve.trimmed(a, b) if e is None else e, "flank", "flank", kind=other if c else PieceRole.CURVE)
                for (a, b, c), e in zip(runs, exact, strict=True)
            ]
        )
    # the male's counter-clockwise pieces follow the rack's travel, the female's run against it
    rack = [p for group in (parts if side is Side.MALE else reversed(parts)) for p in group]
    # one mate tip corner's path that the fit's pieces leave apart is one path (Krigar's male tip across O1O2)
    joined = joined_mate_paths(
        _in_design_period(_at_turns(rack, pair.rack_period), pair),
        mate_body,
        mesh.rack,
        own,
        same if outline.sigma <= 0 else mate_tip[2],
        gap,
    )
    rack = _role_names(joined, pair, side)
    lost_share = 100.0 * lost / max(total, 1)
    if lost_share > 2.0:  # a few points at sharp corners may miss their pitch circle; more is not a rotor
        raise _lost_rack_refusal(
            label or f"{rotor} points",
            outline.whole,
            teeth,
            np.vstack(lost_at) if lost_at else np.zeros((0, 2)),
            lost_share,
        )
    # scattered points' tangents to point_turn; at a male tip corner, from a parametric bootstrap of its
    # fitted spline (measured.tangent)
    turn = point_turn if outline.sigma > 0 else 0.0
    corner_turn = tip_tangent_accuracy(tip_pieces, outline.whole, outline.sigma) if side is Side.MALE else 0.0
    return ScrewRotors(
        pair,
        tuple(rack),
        f"{rotor}-points",
        rack_loss=lost_share,
        accuracy=acc,
        tangent_accuracy=turn,
        tip_corner_tangent_accuracy=min(corner_turn, turn) if corner_turn > 0.0 else None,
        point_accuracy=point_acc,
        tangent_spread=spread,
        point_spacing=spacing if spacing > 0 else None,
        given_points=outline.whole,
        point_scatter=float(outline.sigma),
    )


__all__ = ["CONFIDENCE", "max_factor", "pair_from_rotor_points", "scatter_bound"]

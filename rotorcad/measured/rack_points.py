"""A rotor pair from points of its rack: its lands and tip-corner paths exact, splines between them.

One rack period as points (``rotor --rack-points``, ``hob --rack-points``, the CSV that
``rotor --rack-csv`` writes). Its lands (straight pieces parallel to the pitch line at its top and
bottom) and its rotors' tip-corner paths (the trochoids of a point of a tip circle, Rinder sec. 2.2.2,
Fig. 1-4) are recognised within the points' accuracy and taken exactly
(:mod:`rotorcad.measured.rack_pieces`): a land as a line, a tip corner's path as the
:class:`rotorcad.curves.PointPath` of that corner, as the profile families build their racks
(:class:`rotorcad.screw_rotors.RackPiece`): the rotor receives the corner only, the mate a
point-generated flank. The points between exact pieces are cubic splines (interpolating exact
points, smoothing scattered ones by n sigma^2, Dierckx sec. 5.2) that start and end on the exact
pieces, tangent to them where the rack runs on smoothly, and split where the curvature of exact
points steps (where two rack curves meet). From each sample's own rack CSV this gives the design's
verdicts, contact ratios within 0.002, blow-hole within 0.02 % and hob verdict; a spline through
the whole period (before) read Krigar and Lysholm as running, a rack deviation of 0.99-9.8 mm and the
rack-involute female as undercut.

Scattered points are fitted by splines between the rack's sharp corners that pay for changes of
curvature, not for a flank's straightness or a rounding's (:mod:`rotorcad.measured.penalized_spline`;
FITPACK's smoothing spline by n sigma^2 read the 4/6 independent rack's flank angle 0.2-1.07 deg low
from 2 um of scatter, 0.01-0.8 now), the parts along
which one rotor's generated point stands still taken as that rotor's corner path
(:func:`rotorcad.measured.mate_paths.mate_corner_runs`, against each rotor in turn): within the 8 um
that 2 um of scatter allows a tip corner's trochoid is not told from a curve near it (the N rack's
tip-circle envelopes passed for them), and lands taken exactly with smoothing splines between them
made the scattered Krigar rack's male take minutes to derive back. A rack without lands or tip-corner
paths is fitted so too.
"""

from __future__ import annotations

import itertools

import numpy as np

from rotorcad.curves import Curve, Spline
from rotorcad.envelope import Generated, from_rack_frame
from rotorcad.errors import DesignError
from rotorcad.measured.fit import _smoothing
from rotorcad.measured.outline import accuracy, corners, scatter
from rotorcad.measured.pairs import mate_corner_runs, scatter_bound
from rotorcad.measured.penalized_spline import penalized_spline
from rotorcad.measured.rack_pieces import (
    EXACT_TOLERANCE,
    ExactPiece,
    clamped_spline,
    curvature_breaks,
    exact_pieces,
    meeting,
    piece_frame,
    piece_parameters,
    rack_curve,
)
from rotorcad.roles import PieceRole, Side
from rotorcad.rotor_pair import RotorPair
from rotorcad.screw_rotors import RackPiece, ScrewRotors

CORNER_DEG = 20.0
"""deg: the smallest turn of the rack between two points' chords that is a corner of the rack (the
narrow-tip rack's CSV turns by 89.6 deg where the female tip corner's path meets the pitch line,
elsewhere by 2.1 deg at most between neighbouring chords; the rack-involute's by 2.3 deg at most)."""


def _period_points(pair: RotorPair, points: np.ndarray) -> np.ndarray:
    """Return the points of one rack period, x ascending, without a last point one period after the first (mm).

    Raises :class:`DesignError` for points that do not span one period in x (within 0.1 %).
    """
    pts = np.asarray(points, dtype=float)
    if pts[-1, 0] < pts[0, 0]:
        pts = pts[::-1]
    span = pts[-1, 0] - pts[0, 0]
    period = pair.rack_period
    if abs(span - period) > 1e-3 * period:
        raise DesignError("rack points", f"one rack period long in x ({period:.6g} mm)", f"{span:.6g} mm")
    if np.hypot(pts[-1, 0] - pts[0, 0] - period, pts[-1, 1] - pts[0, 1]) <= 1e-6:
        pts = pts[:-1]  # the next period's first point
    keep = np.concatenate([[True], np.hypot(*np.diff(pts, axis=0).T) > 1e-9])
    return pts[keep]


def rack_runs(pair: RotorPair, points: np.ndarray, sigma: float) -> list[np.ndarray]:
    """Split one rack period's points at the rack's sharp corners into runs, each from corner to corner.

    The period is tiled three times (x shifted by the period either way) so that the corners near its
    ends are found as in its middle (:func:`rotorcad.measured.outline.corners`, with the tiled chain
    read as a ring whose seam lies a period away); the runs cover exactly one period, from the first
    corner at or after the period's start to the same corner one period later.

    Parameters
    ----------
    pair : RotorPair
        The pair (its rack period).
    points : (n, 2) float array, mm
        One period in the rack frame, x ascending, without the next period's first point.
    sigma : float, mm
        The points' scatter (0: exact).

    Returns
    -------
    list of (m, 2) float arrays, mm
        The runs in order of x, each starting and ending on a corner point; one run of the whole
        period (its last point the first one period on) when the rack has no corner.
    """
    p = pair.rack_period
    n = len(points)
    tiled = np.vstack([points - [p, 0.0], points, points + [p, 0.0]])
    edges, where = corners(tiled, sigma, CORNER_DEG)
    middle = (edges >= n) & (edges < 2 * n)
    edges, where = edges[middle], where[middle]
    if len(edges) == 0:
        return [np.vstack([points, points[:1] + [p, 0.0]])]
    edges = np.append(edges, edges[0] + n)
    where = np.vstack([where, where[:1] + [p, 0.0]])
    runs = []
    for k in range(len(edges) - 1):
        run = np.vstack([where[k], tiled[edges[k] + 1 : edges[k + 1] + 1], where[k + 1]])
        keep = np.concatenate([[True], np.hypot(*np.diff(run, axis=0).T) > 1e-9])
        runs.append(run[keep])
    return runs


def _roles(
    curve: Curve, pair: RotorPair, scattered: bool, shortest: float, tolerance: float
) -> list[tuple[float, float, PieceRole]]:
    """Label the parts of one rack piece: a male corner's path, a female corner's path, or a curve both rotors receive.

    The parts along which the male's (the female's) generated point stands still are the male's
    (the female's) corner path (:func:`rotorcad.measured.mate_paths.mate_corner_runs`, with that rotor
    as the mate), when that point lies on the rotor's tip circle (Rinder sec. 2.2.2: at a tip only
    a corner is possible; the rack-involute female's generated cusp on its base circle, 7 mm inside,
    stalls too and is a flank's end); where both would claim a part (the pitch line, which both
    rotors' corners on their pitch circles touch) the male's is taken.
    """
    mesh = pair.mesh
    a = pair.center_distance
    marks = []
    for body, centre, tip in (
        (mesh.male, np.zeros(2), pair.male_tip_radius),
        (mesh.female, np.array([a, 0.0]), pair.female_tip_radius),
    ):
        mate = Generated(curve, mesh.rack, body)
        tip_circle = (centre, tip, 1e-3 * a)
        runs = mate_corner_runs(curve, mate, tolerance=tolerance, scattered=scattered, tip=tip_circle, shortest=shortest)
        corner_runs = [(s0, s1) for s0, s1, c in runs if c]
        if corner_runs:  # only a tip corner stands so (Rinder sec. 2.2.2); a stall inside is the envelope's cusp
            mid, _ = mate.evaluate(np.array([0.5 * (s0 + s1) for s0, s1 in corner_runs]))
            on_tip = np.abs(np.hypot(*(mid - centre).T) - tip) <= tip_circle[2]
            corner_runs = [run for run, keep in zip(corner_runs, on_tip, strict=True) if keep]
        marks.append(corner_runs)
    cuts = sorted({curve.s0, curve.s1, *(s for m in marks for run in m for s in run)}, reverse=curve.s1 < curve.s0)
    out: list[tuple[float, float, PieceRole]] = []
    for s0, s1 in itertools.pairwise(cuts):
        mid = 0.5 * (s0 + s1)
        role = PieceRole.CURVE
        for side, runs in zip((Side.MALE, Side.FEMALE), marks, strict=True):
            if role is PieceRole.CURVE and any(min(r) <= mid <= max(r) for r in runs):
                role = PieceRole.corner_path_of(side)
        if out and out[-1][2] is role:
            out[-1] = (out[-1][0], s1, role)
        else:
            out.append((s0, s1, role))
    return out


def _land_names(pair: RotorPair, height: float) -> tuple[str, str]:
    """Name what a land at ``height`` (rack frame, mm) generates on the male and on the female."""
    male_r, female_r = pair.male_pitch_radius + height, pair.female_pitch_radius - height
    male = "tip arc" if abs(male_r - pair.male_tip_radius) < abs(male_r - pair.male_root_radius) else "root arc"
    female = "tip arc" if abs(female_r - pair.female_tip_radius) < abs(female_r - pair.female_root_radius) else "root arc"
    return male, female


def _exact_rack_piece(pair: RotorPair, piece: ExactPiece, s0: float, s1: float) -> RackPiece:
    """Make the rack piece of a land or a tip corner's path between parameters ``s0`` and ``s1``."""
    curve = rack_curve(pair, piece, s0, s1)
    if piece.side is Side.MALE:
        return RackPiece(curve, "tip corner", "flank (point-generated by the male tip)", kind=piece.role)
    if piece.side is Side.FEMALE:
        return RackPiece(curve, "flank (point-generated by the female tip)", "tip corner", kind=piece.role)
    return RackPiece(curve, *_land_names(pair, piece.value), kind=PieceRole.CURVE)


def _chain(pair: RotorPair, tiled: np.ndarray, n: int, tol: float, shortest: float, land: float) -> list[ExactPiece] | None:
    """Find the exact pieces of one period of the tiled points, in order, from the first one in the middle period.

    Returns the pieces (their indices into the tiled chain; the last entry the first piece one period
    on), or None when the rack has no land and no tip-corner path.
    """
    found = exact_pieces(pair, tiled, tol, shortest, land)
    start = [p for p in found if n <= p.first < 2 * n]
    if not start:
        return None
    k0 = start[0].first
    chain = [p for p in found if k0 <= p.first < k0 + n]
    nxt = [p for p in found if p.first == k0 + n]
    if not nxt:
        return None
    return [*chain, nxt[0]]


def _travel_tangent(pair: RotorPair, piece: ExactPiece, s0: float, s1: float, at_end: bool) -> np.ndarray:
    """Return the unit tangent (rack frame) of an exact piece along the rack's travel at its start or end."""
    s = s1 if at_end else s0
    _, t = piece_frame(pair, piece, np.array([s]))
    return t[0] * (1.0 if s1 >= s0 else -1.0)


def _smooth_join(tangent: np.ndarray, chord: np.ndarray) -> bool:
    """Whether a spline leaving an exact piece along ``chord`` meets it smoothly (no corner of the rack)."""
    c = chord / max(float(np.hypot(*chord)), 1e-300)
    return bool(np.degrees(np.arccos(np.clip(tangent @ c, -1.0, 1.0))) < CORNER_DEG)


def _exact_rack(
    pair: RotorPair, pts: np.ndarray, sigma: float, tol: float, shortest: float, smoothing: float | None
) -> list[RackPiece] | None:
    """Make the rack of one period with its lands and tip-corner paths exact and splines between them.

    Returns None when the points hold no land and no tip-corner path (the caller fits splines between
    the rack's corners).
    """
    n, p = len(pts), pair.rack_period
    tiled = np.vstack([pts - [p, 0.0], pts, pts + [p, 0.0]])
    chain = _chain(pair, tiled, n, tol, shortest, 0.0)
    if chain is None:
        return None
    spacing = float(np.median(np.hypot(*np.diff(pts, axis=0).T)))
    params = [piece_parameters(pair, e, tiled[[e.first, e.last]]) for e in chain]
    bounds = [[float(s[0]), float(s[1])] for s in params]
    joins: list[np.ndarray | None] = []  # between exact piece k and k + 1: the free points (or None: they meet)
    for k in range(len(chain) - 1):
        a, b = chain[k], chain[k + 1]
        free = tiled[a.last + 1 : b.first]
        reach = 3.0 * spacing + 10 * tol  # where the two pieces' last and first points lie
        met = meeting(pair, a, b, bounds[k][1], bounds[k + 1][0], 10 * tol + 1e-9, reach) if len(free) <= 1 else None
        if met is not None:
            bounds[k][1], bounds[k + 1][0] = met
            joins.append(None)
        else:
            joins.append(free)
    if joins[-1] is None:  # the last piece meets the first one period on: the first starts there
        bounds[0][0] = bounds[-1][0] - (p if chain[0].role is PieceRole.CURVE else 0.0)
    shift = tiled[chain[-1].first] - tiled[chain[0].first]
    rack: list[RackPiece] = []
    for k in range(len(chain) - 1):
        e, (s0, s1) = chain[k], bounds[k]
        rack.append(_exact_rack_piece(pair, e, s0, s1))
        free = joins[k]
        if free is None:
            continue
        nxt, (t0, t1) = chain[k + 1], bounds[k + 1]
        if k + 1 == len(chain) - 1:  # the first piece one period on: its start where the first one starts, shifted
            t0 = bounds[0][0]
            begin = piece_frame(pair, chain[0], np.array([t0]))[0][0] + shift
            t_begin = _travel_tangent(pair, chain[0], bounds[0][0], bounds[0][1], at_end=False)
        else:
            begin = piece_frame(pair, nxt, np.array([t0]))[0][0]
            t_begin = _travel_tangent(pair, nxt, t0, t1, at_end=False)
        end = piece_frame(pair, e, np.array([s1]))[0][0]
        t_end = _travel_tangent(pair, e, s0, s1, at_end=True)
        run = np.vstack([end, free, begin])
        keep = np.concatenate([[True], np.hypot(*np.diff(run, axis=0).T) > 1e-9])
        run = run[keep]
        if len(run) < 2:
            continue
        d0 = t_end if _smooth_join(t_end, run[1] - run[0]) else None
        d1 = t_begin if _smooth_join(t_begin, run[-1] - run[-2]) else None
        rack += _spline_pieces(pair, run, d0, d1, sigma, smoothing)
    return rack


def _spline_pieces(
    pair: RotorPair, run: np.ndarray, start: np.ndarray | None, end: np.ndarray | None, sigma: float, smoothing: float | None
) -> list[RackPiece]:
    """Fit the points between exact pieces (rack frame) as splines, split where their curvature steps.

    ``start`` / ``end`` are the unit tangents (rack frame) the ends must take, or None. At a step of
    the curvature (:func:`rotorcad.measured.rack_pieces.curvature_breaks`) the two splines share the
    mean of the end tangents that splines through the six points either side give.
    """
    r1 = pair.male_pitch_radius
    cuts = [0, *curvature_breaks(run, sigma).tolist(), len(run) - 1]
    tangents: list[np.ndarray | None] = [start]
    for b in cuts[1:-1]:
        left = Spline.fit(run[max(b - 6, 0) : b + 1])
        right = Spline.fit(run[b : b + 7])
        t = left.evaluate(np.array([left.s1]))[1][0] + right.evaluate(np.array([right.s0]))[1][0]
        tangents.append(t / np.hypot(*t))
    tangents.append(end)
    pieces = []
    for k in range(len(cuts) - 1):
        part = run[cuts[k] : cuts[k + 1] + 1]
        d0, d1 = tangents[k], tangents[k + 1]
        spline = clamped_spline(
            from_rack_frame(part, r1),
            None if d0 is None else from_rack_frame(d0[None, :], 0.0)[0],
            None if d1 is None else from_rack_frame(d1[None, :], 0.0)[0],
            _smoothing(part, sigma, smoothing),
        )
        pieces.append(RackPiece(spline, "flank", "flank"))
    return pieces


def pair_from_rack_points(pair: RotorPair, points: np.ndarray, smoothing: float | None = None) -> ScrewRotors:
    """Generate a pair from points of one rack period.

    Its lands and its rotors' tip-corner paths are taken exactly (:mod:`rotorcad.measured.rack_pieces`),
    the rest fitted by splines between them; a rack with neither is fitted by splines between its
    corners, its corner paths found against each rotor.

    Parameters
    ----------
    pair : RotorPair
        Dimensions of the pair.
    points : (n, 2) float array, mm
        One rack period in the rack frame of CONTRACT.md (x along the motion, y > 0 towards the
        female), in either direction; a last point one period after the first may be given.
    smoothing : float, mm², optional
        scipy's spline smoothing of each run between corners; 0 interpolates; None: n sigma^2 from
        the points' estimated scatter (:func:`rotorcad.measured.outline.scatter`), 0 for exact points.

    Returns
    -------
    ScrewRotors
        The pair generated from the fitted rack (family ``"rack-points"``), its accuracy that of the
        points (the chords' sagitta or 2 sigma; over the period, the 95 % bound of
        :func:`rotorcad.measured.pairs.scatter_bound`).

    Raises
    ------
    DesignError
        Points that do not span one rack period p = 2 pi r1w / z1 in x (within 0.1 %).
    """
    pts = _period_points(pair, points)
    sigma = scatter(pts)
    point_acc = accuracy(pts, sigma)
    acc = max(point_acc, scatter_bound(sigma, len(pts)))
    shortest = max(5e-3 * pair.center_distance, float(np.sqrt(8.0 * pair.center_distance * acc)))
    tol = max(EXACT_TOLERANCE * pair.center_distance, scatter_bound(sigma, len(pts)))
    # of scattered points the splines between corners (exact pieces are not told within the scatter)
    rack = _exact_rack(pair, pts, sigma, tol, shortest, smoothing) if sigma <= 0 else None
    if rack is None:
        rack = _spline_rack(pair, pts, sigma, point_acc, shortest, smoothing)
    spacing = float(np.median(np.hypot(*np.diff(pts, axis=0).T)))
    turn = point_acc / spacing if sigma > 0 and spacing > 0 else 0.0
    return ScrewRotors(pair, tuple(rack), "rack-points", accuracy=acc, tangent_accuracy=turn, point_accuracy=point_acc)


def _spline_rack(
    pair: RotorPair, pts: np.ndarray, sigma: float, point_acc: float, shortest: float, smoothing: float | None
) -> list[RackPiece]:
    """Fit the rack as splines between its sharp corners and find its corner paths (a rack with no exact piece).

    Scattered points without a smoothing of the user's: :func:`rotorcad.measured.penalized_spline.penalized_spline`.
    """
    r1 = pair.male_pitch_radius
    rack: list[RackPiece] = []
    for run in rack_runs(pair, pts, sigma):
        fixed, s_fit = from_rack_frame(run, r1), _smoothing(run, sigma, smoothing)
        spline = (penalized_spline(fixed) if s_fit > 0 and smoothing is None else None) or Spline.fit(fixed, smoothing=s_fit)
        # a corner's path reaches as far as the generated point stays within 10 times the points'
        # accuracy of the corner (the narrow-tip rack CSV's sealing contact ratio: 0.233 at 1 time,
        # 0.176 at 10 and 0.172 at 30, the design's 0.175)
        for s0, s1, role in _roles(spline, pair, sigma > 0, shortest, max(1e-4, 10 * point_acc)):
            rack.append(RackPiece(spline.trimmed(s0, s1), "flank", "flank", kind=role))
    return rack


__all__ = ["CORNER_DEG", "pair_from_rack_points", "rack_runs"]

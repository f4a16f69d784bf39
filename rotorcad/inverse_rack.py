"""Inverse rack generation: the transverse rack of any profile on a rotating body.

After Wu & Chi, *Meshing clearance evaluation*, sec. 2, eqs. 4-8. The rack of a rotor or gear is
the envelope of its profile in the frame of a rack rolling on its pitch circle: a profile point's
rack point is where its normal passes the pitch point. The normal rack is the transverse rack with
lengths along the pitch line multiplied by cos(beta) (beta the helix angle at the pitch cylinder:
tan(beta) = 2 pi r_w / h for a screw rotor of lead h).

A sharp corner of the profile (convex, a left turn of the counter-clockwise boundary) is a point
with a fan of normals: it generates its own path on the rack, so a zero-radius arc is inserted
there before the inverse generation (:func:`with_corner_fans`).

Used by the hob (:mod:`hob.rack`: hobbability, hob tooth) and by the meshing clearance
(:mod:`rotorcad.clearance`).
"""

from __future__ import annotations

import weakref
from dataclasses import dataclass, fields, replace
from typing import Any

import numpy as np

from rotorcad.curves import Arc, Curve, Mapped, sample_curve, split_intervals
from rotorcad.envelope import Generated, conjugate, from_rack_frame
from rotorcad.errors import DesignError
from rotorcad.geometry import cross, rotate, wrap_angle
from rotorcad.kinematics import Rotation, Translation, gear_mesh
from rotorcad.lobe_trim import trimmed_lobe
from rotorcad.roles import PieceRole, Side
from rotorcad.roots import bracket_root

MEASURED_MIN_TURN = np.radians(0.5)  # rad: the smallest corner between measured pieces
MEASURED_JOIN_GAP = 0.02  # mm: measured pieces' fits (2 µm scatter) leave their ends this far apart at a corner
GENERATION_BASE = 0.1  # mm: half the arc length over which the curvature of the generation factor is taken
STALL_FACTOR = 0.2
"""Generation factor (:func:`generation_factor`) below which the rotor's generated point stands nearly
still while the rack point moves: a sharp corner of the rotor (or, below 0, its envelope turning back)."""
STALL_LENGTH = 0.25
"""mm: the shortest run of the rack along which a rotor's point stalls for an undercut below its tip:
a corner where two generated parts of the flank cross at 10 deg holds its stall over 0.4-0.9 mm of the
rack (the 5/6 arc-flank male of tests/independent_pairs.py, from 300 to 2000 points a lobe), a
point-generated flank's single slow point a few hundredths of a millimetre."""
STALL_TURN = np.radians(8.0)
"""rad: the smallest turn of the rotor's profile across a stall for it to be a sharp corner (the 5/6
arc-flank male's crossing turns by 10 deg, read 12-14 deg across its stall; the rack-involute 5/6
female's sealing flank, a slow but smooth generation, 6.4 deg from its own points)."""
SMOOTHED_STALL_FACTOR = 0.4
"""Generation factor below which a measured rotor's smoothed corner still stalls: a fit through points
0.9 mm apart (80 a lobe) rounds the 5/6 arc-flank male's 10 deg crossing over a millimetre, which lifts its
stall to f = 0.25 (0.03 from 2000 points a lobe); with the profile turning by :data:`STALL_TURN` across it
(11-12 deg read there at 80 and 300 points a lobe, exact or 2 µm scatter; nothing on the 4/6 pair)."""
SHARP_SPAN = 0.5
"""mm: the longest stretch of a measured profile across which a stall of its generation is a sharp corner
below its tip (:func:`stalls`, ``sharp_span``, as the hob judges it): the 5/6 arc-flank male's crossing
(tests/independent_pairs.py, brute-force cut) turns by 9-13 deg within 0.10-0.30 mm of the fitted
profile (2000 and 300 points a lobe, exact or 1-2 um scatter), the N rack female's tip rounding, a
design's slow generation (generation factor 0.033-0.2), by 28-31 deg over 0.69-0.98 mm (its CSV, 400
points a lobe exact or 300 with 2 um scatter), and its fit's curvature errors swing the factor below
0 there (read "undercut" before)."""
TIP_MARGIN = 0.05
"""Share of the rack depth below the rotor's tip (above its root) within which a stall is the rotor's tip
corner (its root fillet, whose curvature a measured rack gives no better), not an undercut."""


@dataclass(frozen=True, eq=False)
class DerivedRack:
    """A rack derived from a profile, one period: the one rack value of hob and clearance.

    Attributes
    ----------
    points : (n, 2) float array, mm
        Rack points in the rack frame of CONTRACT.md (x along the pitch line); y > 0 away from
        the profile's centre, or, with ``contract_frame``, towards the female for either rotor
        (:meth:`in_contract_frame`).
    tangents : (n, 2) float array
        Unit tangents along the chain, exact (from the envelope).
    names : tuple of str
        The generating pieces' names, one per piece.
    piece_index : (n,) int array
        The piece of each point.
    period : float, mm
        Rack period (transverse).
    lost_fraction : float
        Share of profile points without a rack point (their normal misses the pitch circle); the samples of
        a corner's fan are not counted (one profile point: its directions without a contact are off its path).
    pitch_radius : float, mm
        Pitch radius of the rotor or gear the rack rolls on.
    helix_angle : float, rad
        beta at the pitch cylinder (for the normal rack).
    roles : tuple of PieceRole
        Per piece: a corner fan does not cut (its image is the corner's path).
    side : Side or None
        The rotor the rack was derived from (None for a gear).
    contract_frame : bool
        Whether y > 0 points to the female for either rotor, the chain travelled in +x.
    profile : (n, 2) float array or None, mm
        The profile point that generates each rack point, in the rotor's own frame (its centre at
        the origin): a sharp corner for every point of its fan.
    """

    points: np.ndarray
    tangents: np.ndarray  # unit tangents along the chain, exact (from the envelope)
    names: tuple[str, ...]
    piece_index: np.ndarray
    period: float
    lost_fraction: float
    pitch_radius: float
    helix_angle: float = 0.0
    roles: tuple[PieceRole, ...] = ()
    side: Side | None = None
    contract_frame: bool = False
    profile: np.ndarray | None = None

    def normal(self) -> np.ndarray:
        """Return the normal rack: lengths along the pitch line times cos(beta), (n, 2), mm."""
        return self.points * np.array([np.cos(self.helix_angle), 1.0])

    def normal_section(self, helix_angle: float | None = None) -> tuple[np.ndarray, np.ndarray]:
        """Return the normal rack (Wu & Chi eq. 7) and its unit tangents.

        Parameters
        ----------
        helix_angle : float, rad, optional
            beta (default the rack's own).

        Returns
        -------
        points : (n, 2) float array, mm
            Rack points with x times cos(beta).
        tangents : (n, 2) float array
            Their unit tangents.
        """
        c = np.cos(self.helix_angle if helix_angle is None else helix_angle)
        t = self.tangents * np.array([c, 1.0])
        return self.points * np.array([c, 1.0]), t / np.linalg.norm(t, axis=1, keepdims=True)

    @property
    def corner_path(self) -> np.ndarray:
        """(n,) bool: the point lies on the path of a sharp corner (a corner's fan)."""
        fan = np.array([role is PieceRole.CORNER_FAN for role in self.roles], dtype=bool)
        return fan[self.piece_index] if len(fan) else np.zeros(len(self.points), dtype=bool)

    def in_contract_frame(self) -> DerivedRack:
        """Return the same rack in the CONTRACT.md rack frame.

        y > 0 towards the female for either rotor (a female's rack flipped), the chain travelled in +x.

        Returns
        -------
        DerivedRack
            With ``contract_frame`` set (itself when it already is).
        """
        if self.contract_frame:
            return self
        flip = np.array([1.0, -1.0 if self.side is Side.FEMALE else 1.0])
        pts, tan, idx, prof = self.points * flip, self.tangents * flip, self.piece_index, self.profile
        if pts[-1, 0] < pts[0, 0]:  # travel the chain in +x
            pts, tan, idx = pts[::-1], -tan[::-1], idx[::-1]
            prof = None if prof is None else prof[::-1]
        return replace(self, points=pts, tangents=tan, piece_index=idx, profile=prof, contract_frame=True)

    @property
    def normal_period(self) -> float:
        """Period of the normal rack, mm: the transverse period times cos(beta)."""
        return self.period * np.cos(self.helix_angle)


def generation_factor(rack: DerivedRack, base: float = GENERATION_BASE) -> np.ndarray:
    """Return the generation factor f = ds_rotor / ds_rack of every rack point, (n,) float.

    In the rotor's transverse rack frame (y > 0 away from its centre, x along the pitch line), a rack
    point at height y with unit tangent t and curvature kappa (dpsi/ds, the tangent's turn per arc
    length) touches the rotor when its normal passes the pitch point, u = x - y n_x / n_y; the rotor
    rolls about that point at 1 / r_w rad per mm of travel, so the generated point moves along the
    common tangent at

        f = 1 + y / (r_w t_x^2) + y^2 kappa / (r_w t_x^3)

    mm per mm of the rack (envelope condition, Litvin, *Gear Geometry and Applied Theory*, sec. 6.3 and
    10.4: a straight flank of pressure angle alpha has t_x = sin(alpha) and f = 0 at y = -r_w sin^2(alpha),
    the classical undercut limit). f < 0: the envelope turns back (undercut: the rotor keeps only the
    outer branch); f near 0 over a stretch of the rack: the rotor's point stands still there, a sharp
    corner. f is independent of the direction of travel. The curvature is the tangent's turn over
    ``base`` (mm, default :data:`GENERATION_BASE`; the hob scales it with the pair's size,
    :func:`hob.turn_back.scaled`) either side (exact tangents, not differences of points). NaN where the
    rack runs within 3 deg of perpendicular to the pitch line (|t_x| < 0.05).
    """
    pts, tan = rack.points.copy(), rack.tangents.copy()
    if rack.contract_frame and rack.side is Side.FEMALE:  # back to the rotor's own rack frame
        pts[:, 1] *= -1.0
        tan[:, 1] *= -1.0
    psi = np.unwrap(np.arctan2(tan[:, 1], tan[:, 0]))
    arc = np.concatenate([[0.0], np.cumsum(np.hypot(*np.diff(pts, axis=0).T))])
    # the window stays within the point's piece (pieces meet at corners, where the tangent jumps)
    idx = rack.piece_index
    first = np.searchsorted(idx, idx, side="left") if np.all(np.diff(idx) >= 0) else np.zeros(len(idx), dtype=int)
    last = np.searchsorted(idx, idx, side="right") - 1 if np.all(np.diff(idx) >= 0) else np.full(len(idx), len(idx) - 1)
    hi = np.minimum(np.searchsorted(arc, arc + base), last)
    lo = np.maximum(np.searchsorted(arc, arc - base, side="right") - 1, first)
    kappa = (psi[hi] - psi[lo]) / np.maximum(arc[hi] - arc[lo], 1e-12)
    tx, y, rw = tan[:, 0], pts[:, 1], rack.pitch_radius
    steep = np.abs(tx) < 0.05
    tx = np.where(steep, 1.0, tx)
    f = 1.0 + y / (rw * tx**2) + y**2 * kappa / (rw * tx**3)
    return np.where(steep, np.nan, f)


def _profile_turn(profile: np.ndarray, a: int, b: int) -> float:
    """Angle (rad) between the profile's chords just before point ``a`` and just after point ``b - 1``.

    The chords span the stall's own length of profile either side, so that the turn of a sharp
    corner smoothed by a fit over the stall is measured whole; 0 where a side has no points.
    """
    span = max(float(np.hypot(*(profile[b - 1] - profile[a]))), 1e-3)
    d = np.hypot(*(profile - profile[a]).T)
    before = np.flatnonzero((np.arange(len(profile)) < a) & (d >= span))
    d = np.hypot(*(profile - profile[b - 1]).T)
    after = np.flatnonzero((np.arange(len(profile)) >= b) & (d >= span))
    if not len(before) or not len(after):
        return 0.0
    u = profile[a] - profile[before[-1]]
    v = profile[after[0]] - profile[b - 1]
    return float(abs(np.arctan2(u[0] * v[1] - u[1] * v[0], u @ v)))


def stalls(
    rack: DerivedRack,
    measured: bool = False,
    min_turn: float = STALL_TURN,
    factor: float = STALL_FACTOR,
    max_turn: float = np.pi,
    sharp_span: float = np.inf,
    scale: float = 1.0,
) -> list[tuple[int, int, bool]]:
    """Find where a rotor's generation stalls or turns back: its undercut, or a sharp corner below its tip.

    Runs of rack points at least :data:`STALL_LENGTH` long along which the generation factor
    (:func:`generation_factor`) stays below ``factor`` (:data:`STALL_FACTOR`), where the rotor's generated point
    lies below its tip and above its root by more than :data:`TIP_MARGIN` of the rack depth, not on
    the fan of a sharp corner the profile was given with (a designed point-generating corner,
    whose path the rack carries). A run counts when the envelope turns back in it (f < 0), or, for
    a profile given by points (``measured``, whose fit smooths a sharp corner over the point
    spacing), when the profile turns by ``min_turn`` (rad, :data:`STALL_TURN`) across it: a sharp corner below the tip
    (a design's slowly generated small rounding, the N rack female's tip, stalls too).

    Parameters
    ----------
    rack : DerivedRack
        A rotor's rack with its ``profile`` points.
    measured : bool
        Whether the profile was given by points.
    min_turn : float, rad
        Smallest turn of the profile across a stall of a measured profile.
    factor : float
        Generation factor below which the rotor's point stalls (:data:`STALL_FACTOR`; a fit through
        sparse points lifts a smoothed corner's stall, :data:`SMOOTHED_STALL_FACTOR`).
    max_turn : float, rad
        Largest turn of the profile across a stall that does not turn back (a measured one).
    sharp_span : float, mm
        Of a measured profile, the longest stretch of it across which a stall is a sharp corner (its
        fit's rounding) at all, turning back or not (:data:`SHARP_SPAN`); a longer one is a rounding
        that the points resolve, generated slowly; default no limit.
    scale : float
        The pair's size against the one :data:`STALL_LENGTH` and :data:`GENERATION_BASE` were set on (the hob's
        :func:`hob.turn_back.length_scale`: a geometrically similar pair, k times the size, stalls over k times the
        rack); both lengths are multiplied by it. Default 1 (the clearance's use, unscaled).

    Returns
    -------
    list of (int, int, bool)
        Each run's first and one-past-last point index, and whether the envelope turns back there.
    """
    if rack.profile is None or len(rack.points) < 3:
        return []
    f = generation_factor(rack, GENERATION_BASE * scale)
    radius = np.hypot(*rack.profile.T)
    depth = float(np.ptp(rack.points[:, 1]))
    between = (radius < radius.max() - TIP_MARGIN * depth) & (radius > radius.min() + TIP_MARGIN * depth)
    low = np.isfinite(f) & (f < factor) & between & ~rack.corner_path
    arc = np.concatenate([[0.0], np.cumsum(np.hypot(*np.diff(rack.points, axis=0).T))])
    edges = np.diff(np.concatenate([[0], low.astype(int), [0]]))
    out = []
    for a, b in zip(np.flatnonzero(edges == 1), np.flatnonzero(edges == -1), strict=True):
        if arc[b - 1] - arc[a] < STALL_LENGTH * scale:
            continue
        if measured and np.hypot(*np.diff(rack.profile[a:b], axis=0).T).sum() > sharp_span:
            continue
        back = bool(np.nanmin(f[a:b]) < 0)
        if back or (measured and min_turn <= _profile_turn(rack.profile, a, b) <= max_turn):
            out.append((int(a), int(b), back))
    return out


def contact_of_rack_points(pitch_radius: float, points: np.ndarray, tangents: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Find the contact point and male rotation angle of rack points.

    From the envelope engine (:func:`rotorcad.envelope.conjugate`: the point's normal passes the
    pitch point C).

    Parameters
    ----------
    pitch_radius : float, mm
        Male pitch radius r_w (the rack's pitch line rolls on it).
    points : (n, 2) float array, mm
        Rack points in the rack frame of CONTRACT.md.
    tangents : (n, 2) float array
        Their unit tangents (either direction).

    Returns
    -------
    contact : (n, 2) float array, mm
        Contact point in the fixed transverse frame (male centre at the origin, C at (r_w, 0));
        NaN where the normal runs along the pitch line (no contact).
    angle : (n,) float array, rad
        Male rotation at which the point is in contact.
    """
    mesh = gear_mesh(pitch_radius)
    p = from_rack_frame(points, pitch_radius)
    t = from_rack_frame(tangents, 0.0)  # the axes swapped: a direction in the fixed frame
    contact = conjugate(p, t, mesh.rack, mesh.male)
    return contact.meshline, contact.t


def with_corner_fans(
    pieces: list[tuple[str, Curve]],
    centre: np.ndarray | None = None,
    pitch_angle: float = 0.0,
    min_turn: float = 1e-6,
    join_gap: float = 2e-3,
    piece_ends: list | None = None,
) -> list[tuple[str, Curve]]:
    """Insert zero-radius arcs at the convex corners of a counter-clockwise chain of pieces.

    The corners then generate their paths. With ``centre`` and ``pitch_angle`` (one lobe of a
    patterned rotor) the corner where the previous lobe's last piece meets this lobe's first piece is
    found too, by turning that last piece back by one pitch. Pieces whose ends are more than
    ``join_gap`` apart are not joined by a corner.

    Parameters
    ----------
    pieces : list of (str, Curve)
        The chain, counter-clockwise, mm.
    centre : (2,) float array, mm, optional
        Centre of the rotor.
    pitch_angle : float, rad
        Angular pitch 2 pi / z of the rotor (0: do not close the lobe).
    min_turn : float, rad
        Smaller turns are not corners (measured pieces that meet at a land, where the fits leave a
        kink of a fraction of a degree, pass :data:`MEASURED_MIN_TURN`).
    join_gap : float, mm
        Largest distance between the ends of two pieces that meet at a corner (2 µm; the fits of
        scattered points leave their ends up to :data:`MEASURED_JOIN_GAP` apart).
    piece_ends : list, optional
        Per piece its ends as ``curve.evaluate`` gives them, ((start point, tangent), (end point,
        tangent)), where the caller has them (None entries are evaluated here).

    Returns
    -------
    list of (str, Curve)
        The pieces with ``"<name> corner"`` arcs of radius 0 between them.
    """

    def fan(name: str, end: tuple[np.ndarray, np.ndarray], start: tuple[np.ndarray, np.ndarray]) -> tuple[str, Curve] | None:
        (p_end, t_end), (p_next, t_next) = end, start
        if np.hypot(*(p_end - p_next)) > join_gap:  # measured pieces meet within the fit error
            return None
        turn = float(np.arctan2(cross(t_end, t_next), np.dot(t_end, t_next)))
        if turn <= min_turn:  # only a left turn is a convex corner of a counter-clockwise boundary
            return None
        a0 = np.arctan2(t_end[1], t_end[0]) - np.pi / 2
        return (f"{name} corner", Arc((float(p_end[0]), float(p_end[1])), 0.0, float(a0), float(a0 + turn)))

    def ends(curve: Curve) -> tuple[tuple[np.ndarray, np.ndarray], tuple[np.ndarray, np.ndarray]]:
        p, t = curve.evaluate(np.array([curve.s0, curve.s1]))
        return (p[0], t[0]), (p[1], t[1])

    out: list[tuple[str, Curve]] = []
    n = len(pieces)
    given = piece_ends if piece_ends is not None else [None] * n
    piece_ends = [e if e is not None else ends(curve) for (_, curve), e in zip(pieces, given, strict=True)]  # evaluate once
    if centre is not None and pitch_angle and n:
        (_, _), (p_last, t_last) = piece_ends[-1]
        back = (rotate(p_last, -pitch_angle, centre)[0], rotate(t_last, -pitch_angle)[0])
        first = fan(pieces[-1][0], back, piece_ends[0][0])
        if first is not None:
            out.append(first)
    for i, (name, curve) in enumerate(pieces):
        out.append((name, curve))
        if i + 1 < n:
            corner = fan(name, piece_ends[i][1], piece_ends[i + 1][0])
            if corner is not None:
                out.append(corner)
    return out


def _on_the_corner_path(
    gen: Generated, s: np.ndarray, body: Rotation, pitch_radius: float, depth: tuple[float, float] | None, p: np.ndarray
) -> np.ndarray:
    """Which rack points of a corner's fan lie on the corner's real path.

    The fan's normals reach every direction between the two pieces meeting at the corner, but the
    path exists only inside the rack's depth, and a corner on the pitch circle cuts a cycloid that
    ends in a cusp on the pitch line when the corner passes the pitch point: the fan's normals
    beyond that instant belong to the next arch, which the land behind the corner sweeps away.
    """
    centre = np.asarray(body.center, dtype=float)
    pitch = centre + np.array([np.sign(body.rate) * pitch_radius, 0.0])
    extent = p[:, 0] - pitch[0]  # height of the rack point above its pitch line (the limits' sense)
    ok = np.ones(len(p), dtype=bool)
    if depth is not None:
        ok &= (extent >= depth[0] - 1e-6) & (extent <= depth[1] + 1e-6)
    corner = np.asarray(gen.parent.evaluate(np.array([gen.parent.s0]))[0][0])
    d = corner - centre
    if abs(np.hypot(*d) - pitch_radius) > 1e-9 * pitch_radius:
        return ok
    w = pitch - centre
    theta_f = np.arctan2(w[1], w[0]) - np.arctan2(d[1], d[0])  # the corner at the pitch point
    t = gen.contact(s).t
    half_turn = np.pi / abs(body.rate)
    lag = wrap_angle(t - theta_f / body.rate, 0.0, 2 * half_turn)  # time since the corner passed C, within a turn
    start = 0 if abs(lag[0]) <= abs(lag[-1]) else len(lag) - 1  # the end at the flank, nearer the cusp
    same = np.sign(lag) == np.sign(lag[start])
    run = np.cumprod(same if start == 0 else same[::-1]).astype(bool)
    return ok & (run if start == 0 else run[::-1])


MESHLINE_PERIODS = 20.0
"""Longest meshline of one rack piece refined by contact, in rack periods (a lobe's meshline is
shorter than two)."""


def _refine_by_contact(
    gen: Generated, s: np.ndarray, p: np.ndarray, t: np.ndarray, step: float, longest: float
) -> tuple[np.ndarray, ...]:
    """Split the intervals whose contact points (the meshline) are more than ``step`` apart.

    Only where the contact moves continuously: an interval split into parts is split again only
    while its parts' gaps shrink to less than half the gap it had. A jump of the contact (the
    meshline leaves one branch for another, or the normals of a fit through scattered points swing
    it back and forth) keeps its gap however fine the samples, and was split 64 times on every pass:
    a female fitted through points of 0.5 µm scatter went from 56 666 samples to 2.3 million (120 s,
    1.5 GB in ``rotorcad clearance``). Nor beyond ``longest`` (mm) of meshline: a piece's contacts
    that run farther are a fit's noise, not a meshline, and finer samples would not make them one
    (that female's piece ran 596 m); the samples are then kept as they are.
    """
    before = np.full(len(s) - 1, np.inf)  # the gap of the interval each one was split from
    budget = len(s) + int(np.ceil(longest / step))
    for _ in range(6):
        gap = np.nan_to_num(np.hypot(*np.diff(gen.contact(s).meshline, axis=0).T), nan=0.0)
        n = np.where(gap < 0.5 * before, np.clip(np.ceil(gap / step).astype(int), 1, 64), 1)
        if np.all(n <= 1) or len(s) + int((n - 1).sum()) > budget:
            break
        s, p, t = split_intervals(gen, s, p, t, n)
        before = np.repeat(np.where(n > 1, gap, 0.0), n)  # a part of an interval not split is not split again
    return s, p, t


def derive_rack(
    pieces: list[tuple[str, Curve]],
    body: Rotation,
    pitch_radius: float,
    period: float,
    helix_angle: float = 0.0,
    depth: tuple[float, float] | None = None,
    samples: int = 400,
    pitch_angle: float = 0.0,
    tolerance: float = 1e-4,
    contact_step: float = 0.0,
    min_turn: float = 1e-6,
    join_gap: float = 2e-3,
    piece_ends: list | None = None,
) -> DerivedRack:
    """Derive the rack of a counter-clockwise chain of profile pieces on a rotating body.

    Inverse generation piece by piece (corner fans included, :func:`with_corner_fans`), sampled to
    the chord ``tolerance`` on the rack.

    Parameters
    ----------
    pieces : list of (str, Curve)
        One lobe, counter-clockwise, in the fixed frame about ``body.center``, mm.
    body : Rotation
        The rotor or gear the pieces belong to.
    pitch_radius : float, mm
        Its pitch radius r_w (the rack's pitch line rolls on it).
    period : float, mm
        Rack period (transverse).
    helix_angle : float, rad
        beta at the pitch cylinder (stored, for the normal rack).
    depth : (float, float), mm, optional
        (y_min, y_max) of the rack about its pitch line: where the normal line cuts the pitch
        circle twice, picks the root that lies on the rack (see :mod:`rotorcad.envelope`).
    samples : int
        Fewest samples of each piece.
    pitch_angle : float, rad
        Angular pitch of the lobe, so that the corner at the junction with the previous lobe is
        found too.
    tolerance : float, mm
        Chord tolerance on the rack.
    contact_step : float, mm
        If > 0, samples are added until their contact points (the meshline) are at most that far
        apart: near roundings the contact runs fast along the rack.
    min_turn : float, rad
        Passed to :func:`with_corner_fans`.
    join_gap, piece_ends
        Passed to :func:`with_corner_fans`.

    Returns
    -------
    DerivedRack
        Rack points (n, 2), mm, in the rack frame with y > 0 away from the body's centre.
    """
    centre = np.asarray(body.center, dtype=float)
    # the rack rolls on the pitch circle at the pitch point C = centre + (r, 0) (or - (r, 0) for a
    # body turning clockwise), moving +y per rad of the male / driving gear
    sign = 1.0 if body.rate > 0 else -1.0
    rack = Translation((0.0, abs(body.rate) * pitch_radius))
    pts, tans, idx, names, roles, parents = [], [], [], [], [], []
    lost, total = 0, 0
    # each generated piece runs against its parent, so the rack chain runs the pieces backwards
    for k, (name, curve) in enumerate(reversed(with_corner_fans(pieces, centre, pitch_angle, min_turn, join_gap, piece_ends))):
        recorded = _Recorded(curve)  # the piece's points, kept from the rack's evaluations (no second one)
        gen = Generated(recorded, body, rack, limits=depth)
        s, p, t = sample_curve(gen, tolerance, minimum=samples)  # refined where the rack turns fast (corner paths)
        if contact_step > 0:
            s, p, t = _refine_by_contact(gen, s, p, t, contact_step, MESHLINE_PERIODS * period)
        ok = np.isfinite(p).all(axis=1)
        if not curve.is_corner():  # a fan is one profile point: its directions without contact are off its path
            lost += int((~ok).sum())
            total += len(ok)
        if curve.is_corner():
            ok &= _on_the_corner_path(gen, s, body, pitch_radius, depth, p)
        pts.append(p[ok])
        tans.append(t[ok])
        parents.append(recorded.points_at(s[ok]) - centre)
        idx.append(np.full(int(ok.sum()), k))
        names.append(name)
        roles.append(PieceRole.CORNER_FAN if curve.is_corner() else PieceRole.CURVE)
    p, t = np.vstack(pts), np.vstack(tans)
    c = centre + np.array([sign * pitch_radius, 0.0])
    r = np.stack([p[:, 1], sign * (p[:, 0] - c[0])], axis=1)  # rack frame, y away from the centre
    rt = np.stack([t[:, 1], sign * t[:, 0]], axis=1)
    return DerivedRack(
        r,
        rt,
        tuple(names),
        np.concatenate(idx),
        period,
        lost / max(total, 1),
        pitch_radius,
        helix_angle,
        tuple(roles),
        profile=np.vstack(parents),
    )


class _Recorded(Curve):
    """A curve that keeps the points of its evaluations.

    :func:`derive_rack` reads the profile points of its rack samples from the evaluations that
    made them (the same numbers) instead of evaluating the piece again.
    """

    def __init__(self, curve: Curve) -> None:
        self.curve, self.s0, self.s1 = curve, curve.s0, curve.s1
        self.calls: list[tuple[np.ndarray, np.ndarray]] = []

    def frame(self, s: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """``curve.frame(s)``, its parameters and points kept."""
        p, t = self.curve.frame(s)
        self.calls.append((np.asarray(s, dtype=float), p))
        return p, t

    def arc_center(self) -> np.ndarray | None:
        """``curve.arc_center()``."""
        return self.curve.arc_center()

    def is_corner(self) -> bool:
        """``curve.is_corner()``."""
        return self.curve.is_corner()

    def points_at(self, s: np.ndarray) -> np.ndarray:
        """Points (n, 2), mm, of ``curve`` at parameters ``s``: those kept, else evaluated."""
        if not self.calls:
            return self.curve.evaluate(s)[0]
        known = np.concatenate([c[0] for c in self.calls])
        order = np.argsort(known, kind="stable")
        at = np.minimum(np.searchsorted(known[order], s), len(known) - 1)
        if not (known[order][at] == s).all():
            return self.curve.evaluate(s)[0]
        return np.concatenate([c[1] for c in self.calls])[order[at]]


def rotor_rack(
    rotors: Any,
    side: Side | str,
    pieces: list[tuple[str, Curve]] | None = None,
    *,
    tolerance: float = 1e-4,
    samples: int = 400,
    contact_step: float = 0.0,
    min_turn: float = 1e-6,
    clip_at_tip: bool | None = None,
    join_gap: float = 2e-3,
    cut_loops: bool = False,
) -> DerivedRack:
    """Derive the transverse rack of one lobe of the male or the female of a pair.

    The one function for the rack of a rotor, used by the hob (:mod:`hob.rack`) and the meshing
    clearance (:mod:`rotorcad.clearance`). Inverse generation by :func:`derive_rack`, corner fans
    included.

    Parameters
    ----------
    rotors : ScrewRotors or RotorPair
        The pair (a :class:`~rotorcad.screw_rotors.ScrewRotors` also gives the lobe's pieces).
    side : Side or str
        The rotor.
    pieces : list of (str, Curve), optional
        One lobe, counter-clockwise, in the rotor's own frame (centre at the origin), e.g.
        :func:`rotorcad.measured.fit.lobe_pieces`; default the lobe of ``rotors``.
    tolerance : float, mm
        Chord tolerance of the rack's samples.
    samples : int
        Fewest samples of each piece.
    contact_step : float, mm
        If > 0, samples are added until the contact points (the meshline) of neighbours are at
        most this far apart (the contact runs fast along the rack near roundings).
    min_turn : float, rad
        Smaller turns between pieces are not corners (:data:`MEASURED_MIN_TURN` for measured
        pieces, whose fits leave kinks of a fraction of a degree at the lands).
    clip_at_tip : bool, optional
        Cut the pieces at the rotor's tip circle (generated flanks can overshoot it); default
        for the lobe of ``rotors`` only.
    join_gap : float, mm
        Largest distance between pieces' ends at a corner (:func:`with_corner_fans`;
        :data:`MEASURED_JOIN_GAP` for measured pieces).
    cut_loops : bool
        With ``clip_at_tip``: cut the loops the generated lobe makes beyond its tip circle and join
        its parts cut there by the tip land (:func:`rotorcad.lobe_trim.trimmed_lobe`), as the
        blank leaves them. For a pair generated from a measured rotor, whose rack keeps the
        roundings that cut the measured rotor's root: the mate's images of them overshoot its tip
        and come back onto the land. False keeps each piece's longest part inside the tip circle
        (a design's pieces, which its rack's corner paths keep from overshooting).

    Returns
    -------
    DerivedRack
        Rack points (n, 2), mm, with y > 0 away from this rotor's centre (see
        :meth:`DerivedRack.in_contract_frame`), its ``side`` set and the helix angle at the
        pitch cylinder, tan(beta) = 2 pi r_w / h. Of the pair's own lobe (no ``pieces``) one rack
        per pair and options, derived once and shared: its arrays are read-only.
    """
    options = (tolerance, samples, contact_step, min_turn, clip_at_tip, join_gap, cut_loops)
    if pieces is not None:
        return _rotor_rack(rotors, Side(side), pieces, *options)
    # the lobe of a pair, as its rotors (immutable) give it: derived once per pair and options
    racks = _LOBE_RACKS.setdefault(rotors, {})
    key = (Side(side), *options)
    if key not in racks:
        racks[key] = _read_only(_rotor_rack(rotors, Side(side), None, *options))
    return racks[key]


_LOBE_RACKS: weakref.WeakKeyDictionary = weakref.WeakKeyDictionary()
"""The racks of a pair's own lobes (:func:`rotor_rack` without ``pieces``) per pair and options,
while the pair lives: `rotorcad hob` and :func:`hob.rack.rack_deviation` each derive both."""


def _read_only(rack: DerivedRack) -> DerivedRack:
    """Return ``rack`` with its arrays made read-only (it is shared by every caller asking for it)."""
    for f in fields(rack):
        value = getattr(rack, f.name)
        if isinstance(value, np.ndarray):
            value.flags.writeable = False
    return rack


def _rotor_rack(
    rotors: Any,
    side: Side,
    pieces: list[tuple[str, Curve]] | None,
    tolerance: float,
    samples: int,
    contact_step: float,
    min_turn: float,
    clip_at_tip: bool | None,
    join_gap: float,
    cut_loops: bool,
) -> DerivedRack:
    """:func:`rotor_rack`, derived."""
    pair = getattr(rotors, "pair", rotors)
    if pieces is None:
        lobe = side.pick(rotors.male_pieces, rotors.female_pieces)
        pieces = [(name, curve) for name, curve, *_ in lobe]
        clip_at_tip = True if clip_at_tip is None else clip_at_tip
    mesh, piece_ends = pair.mesh, None
    if side is Side.FEMALE:  # the female's pieces to the fixed frame, its centre at (a, 0)
        shift = (pair.center_distance, 0.0)
        pieces = [(name, Mapped(curve, ((1.0, 0.0), (0.0, 1.0)), shift)) for name, curve in pieces]
    body = side.pick(mesh.male, mesh.female)
    r_w = side.pick(pair.male_pitch_radius, pair.female_pitch_radius)
    if clip_at_tip:
        tip = side.pick(pair.male_tip_radius, pair.female_tip_radius)
        centre = np.asarray(body.center, dtype=float)
        if cut_loops:
            pieces = trimmed_lobe(pieces, centre, tip, 2 * np.pi / side.pick(pair.male_teeth, pair.female_teeth))
        else:
            kept = [p for p in (_inside_tip(name, curve, centre, tip) for name, curve in pieces) if p is not None]
            pieces, piece_ends = [(name, curve) for name, curve, _ in kept], [e for *_, e in kept]
        if not pieces:  # e.g. a mate generated from dense points whose loops beyond the tip cut it whole
            family = str(getattr(rotors, "family", ""))
            raise DesignError(
                f"--{family}" if family.endswith("-points") else f"the {side.value}",
                f"a profile whose {side.value} keeps a part inside its tip circle (r = {tip:g} mm)",
                None,
                f"the {side.value} {'generated from the points ' if family.endswith('-points') else ''}leaves none there "
                "(thin the points to 300-1000 a lobe, or give the other rotor's points)",
            )
    depth = (-pair.male_dedendum - 1e-6, pair.male_addendum + 1e-6)  # the rack lies between these
    rack = derive_rack(
        pieces,
        body,
        r_w,
        pair.rack_period,
        float(np.arctan(2 * np.pi * r_w / side.pick(pair.lead, pair.female_lead))),
        depth=depth,
        samples=samples,
        pitch_angle=2 * np.pi / side.pick(pair.male_teeth, pair.female_teeth),
        tolerance=tolerance,
        contact_step=contact_step,
        min_turn=min_turn,
        join_gap=join_gap,
        piece_ends=piece_ends,
    )
    return replace(rack, side=side)


def _inside_tip(name: str, curve: Curve, centre: np.ndarray, tip: float) -> tuple[str, Curve, tuple | None] | None:
    """Return the longest part of a generated piece inside the rotor's tip circle, or None.

    Generated flanks can overshoot the tip circle; the rotor is cut off there. The third item is
    the piece's ends as :func:`with_corner_fans` takes them where it is kept whole (else None).
    """
    s = np.linspace(curve.s0, curve.s1, 257)  # the ends are refined by root finding below
    p, t = curve.evaluate(s)
    inside = np.hypot(*(p - centre).T) <= tip + 2e-3  # a measured land may wander by the fit error
    if inside.all():
        return name, curve, ((p[0], t[0]), (p[-1], t[-1]))
    if not inside.any():
        return None
    edges = np.diff(np.concatenate([[0], inside.astype(int), [0]]))
    starts, ends = np.nonzero(edges == 1)[0], np.nonzero(edges == -1)[0] - 1
    k = int(np.argmax(ends - starts))
    if ends[k] <= starts[k]:
        return None

    def gap(v: float) -> float:
        return float(np.hypot(*(curve.evaluate(v)[0][0] - centre)) - tip)

    def refine(inner: float, outer: float) -> float:
        root = bracket_root(gap, (inner, outer), xtol=1e-15)
        return inner if root is None else root

    # refine where the piece leaves the tip circle (the map to the rack is steep there)
    a = refine(s[starts[k]], s[starts[k] - 1]) if starts[k] > 0 else s[0]
    b = refine(s[ends[k]], s[ends[k] + 1]) if ends[k] < len(s) - 1 else s[-1]
    return name, curve.trimmed(a, b), None


__all__ = [
    "MEASURED_JOIN_GAP",
    "MEASURED_MIN_TURN",
    "DerivedRack",
    "contact_of_rack_points",
    "derive_rack",
    "rotor_rack",
    "with_corner_fans",
]

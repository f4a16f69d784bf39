"""Inverse rack generation: the transverse rack of any profile on a rotating body (Wu & Chi,
*Meshing clearance evaluation*, sec. 2, eqs. 4-8).

The rack of a rotor or gear is the envelope of its profile in the frame of a rack rolling on its
pitch circle: a profile point's rack point is where its normal passes the pitch point. The normal
rack is the transverse rack with lengths along the pitch line multiplied by cos(beta) (beta the
helix angle at the pitch cylinder: tan(beta) = 2 pi r_w / h for a screw rotor of lead h).

A sharp corner of the profile (convex, a left turn of the counter-clockwise boundary) is a point
with a fan of normals: it generates its own path on the rack, so a zero-radius arc is inserted
there before the inverse generation (:func:`with_corner_fans`).

Used by the hob (:mod:`hob.rack`: hobbability, hob tooth) and by the meshing clearance
(:mod:`rotorcad.clearance`).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from rotorcad.curves import Arc, Curve, sample_curve, split_intervals
from rotorcad.envelope import Generated
from rotorcad.geometry import cross
from rotorcad.kinematics import Rotation, Translation
from rotorcad.roles import PieceRole

MEASURED_MIN_TURN = np.radians(0.5)  # rad: the smallest corner between measured pieces


@dataclass(frozen=True, eq=False)
class DerivedRack:
    """A rack derived from a profile: points in the rack frame of CONTRACT.md (x along the pitch
    line, y > 0 away from the profile's centre), one period, with the generating pieces' names,
    and the share of profile points that have no rack point (their normal misses the pitch circle)."""

    points: np.ndarray
    tangents: np.ndarray  # unit tangents along the chain, exact (from the envelope)
    names: tuple[str, ...]
    piece_index: np.ndarray
    period: float
    lost_fraction: float
    pitch_radius: float
    helix_angle: float = 0.0
    roles: tuple[PieceRole, ...] = ()  # per piece: a corner fan does not cut (its image is the corner's path)

    def normal(self) -> np.ndarray:
        """Normal rack: lengths along the pitch line times cos(beta)."""
        return self.points * np.array([np.cos(self.helix_angle), 1.0])

    @property
    def normal_period(self) -> float:
        return self.period * np.cos(self.helix_angle)


def contact_of_rack_points(pitch_radius: float, points: np.ndarray, tangents: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Contact point (fixed transverse frame, pitch point at (r_w, 0)) and rotation angle of rack
    points (rack frame of CONTRACT.md, unit tangents): where a point's normal meets the pitch
    line, that foot is at the pitch point C (law of gearing)."""
    r1 = pitch_radius
    with np.errstate(divide="ignore", invalid="ignore"):
        offset = points[:, 1] * tangents[:, 1] / tangents[:, 0]  # foot of the normal, along the pitch line
    return np.stack([r1 + points[:, 1], -offset], axis=1), -(points[:, 0] + offset) / r1


def with_corner_fans(
    pieces: list[tuple[str, Curve]], centre: np.ndarray | None = None, pitch_angle: float = 0.0, min_turn: float = 1e-6
) -> list[tuple[str, Curve]]:
    """Insert zero-radius arcs at the convex corners between consecutive pieces of a
    counter-clockwise chain, so that corners generate their paths. With ``centre`` and
    ``pitch_angle`` (one lobe of a patterned rotor) the corner where the previous lobe's last piece
    meets this lobe's first piece is found too, by turning that last piece back by one pitch.
    ``min_turn`` (rad): smaller turns are not corners (measured pieces that meet at a land, where
    the fits leave a kink of a fraction of a degree, pass :data:`MEASURED_MIN_TURN`)."""

    def fan(name: str, end: tuple[np.ndarray, np.ndarray], start: tuple[np.ndarray, np.ndarray]) -> tuple[str, Curve] | None:
        (p_end, t_end), (p_next, t_next) = end, start
        if np.hypot(*(p_end - p_next)) > 2e-3:  # measured pieces meet within the fit error
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
    piece_ends = [ends(curve) for _, curve in pieces]  # generated curves are costly: evaluate once
    if centre is not None and pitch_angle and n:
        (_, _), (p_last, t_last) = piece_ends[-1]
        c, s_ = np.cos(-pitch_angle), np.sin(-pitch_angle)
        rot = np.array([[c, -s_], [s_, c]])
        back = (rot @ (p_last - centre) + centre, rot @ t_last)
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
    beyond that instant belong to the next arch, which the land behind the corner sweeps away."""
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
    lag = np.mod(t - theta_f / body.rate + half_turn, 2 * half_turn) - half_turn
    start = 0 if abs(lag[0]) <= abs(lag[-1]) else len(lag) - 1  # the end at the flank, nearer the cusp
    same = np.sign(lag) == np.sign(lag[start])
    run = np.cumprod(same if start == 0 else same[::-1]).astype(bool)
    return ok & (run if start == 0 else run[::-1])


def _refine_by_contact(gen: Generated, s: np.ndarray, p: np.ndarray, t: np.ndarray, step: float) -> tuple[np.ndarray, ...]:
    """Split the intervals whose contact points (the meshline) are more than ``step`` apart."""
    for _ in range(6):
        gap = np.nan_to_num(np.hypot(*np.diff(gen.contact(s).meshline, axis=0).T), nan=0.0)
        n = np.minimum(np.ceil(gap / step).astype(int), 64)
        if np.all(n <= 1):
            break
        s, p, t = split_intervals(gen, s, p, t, n)
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
) -> DerivedRack:
    """Rack of a counter-clockwise chain of profile pieces on a rotating ``body`` (one lobe of
    ``pitch_angle``, so that the corner at the junction with the previous lobe is found too),
    sampled to the chord ``tolerance`` on the rack.

    ``depth`` = (y_min, y_max) of the rack about its pitch line picks, where the normal line cuts
    the pitch circle twice, the root that lies on the rack (see :mod:`rotorcad.envelope`).
    ``min_turn`` is passed to :func:`with_corner_fans`. ``contact_step`` > 0 refines the samples
    until their contact points (the meshline) are at most that far apart: near roundings the
    contact runs fast along the rack.
    """
    centre = np.asarray(body.center, dtype=float)
    # the rack rolls on the pitch circle at the pitch point C = centre + (r, 0) (or - (r, 0) for a
    # body turning clockwise), moving +y per rad of the male / driving gear
    sign = 1.0 if body.rate > 0 else -1.0
    rack = Translation((0.0, abs(body.rate) * pitch_radius))
    pts, tans, idx, names, roles = [], [], [], [], []
    lost, total = 0, 0
    # each generated piece runs against its parent, so the rack chain runs the pieces backwards
    for k, (name, curve) in enumerate(reversed(with_corner_fans(pieces, centre, pitch_angle, min_turn))):
        gen = Generated(curve, body, rack, limits=depth)
        s, p, t = sample_curve(gen, tolerance, minimum=samples)  # refined where the rack turns fast (corner paths)
        if contact_step > 0:
            s, p, t = _refine_by_contact(gen, s, p, t, contact_step)
        ok = np.isfinite(p).all(axis=1)
        lost += int((~ok).sum())
        total += len(ok)
        if curve.is_corner():
            ok &= _on_the_corner_path(gen, s, body, pitch_radius, depth, p)
        pts.append(p[ok])
        tans.append(t[ok])
        idx.append(np.full(int(ok.sum()), k))
        names.append(name)
        roles.append(PieceRole.CORNER_FAN if curve.is_corner() else PieceRole.CURVE)
    p, t = np.vstack(pts), np.vstack(tans)
    c = centre + np.array([sign * pitch_radius, 0.0])
    r = np.stack([p[:, 1], sign * (p[:, 0] - c[0])], axis=1)  # rack frame, y away from the centre
    rt = np.stack([t[:, 1], sign * t[:, 0]], axis=1)
    return DerivedRack(
        r, rt, tuple(names), np.concatenate(idx), period, lost / max(total, 1), pitch_radius, helix_angle, tuple(roles)
    )


__all__ = ["MEASURED_MIN_TURN", "DerivedRack", "contact_of_rack_points", "derive_rack", "with_corner_fans"]

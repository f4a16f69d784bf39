"""Rack and hob-tooth derivation from any profile (inverse generation).

The transverse rack of a rotor or gear is the envelope of its profile in the frame of a rack
rolling on its pitch circle (Wu & Chi, *Meshing clearance evaluation*, sec. 2, eqs. 4-8; Rinder
sec. 2.1: hobbability is judged through this rack). The normal rack is the transverse rack with
lengths along the pitch line multiplied by cos(beta) (beta the helix angle at the pitch cylinder:
tan(beta) = 2 pi r_w / h for a screw rotor of lead h). The hob tooth is the normal section of the
hob thread: the normal rack's tool material, i.e. the space of the gear, with a clearance added
under its root so that the hob never touches the gear's tip.

A sharp corner of the profile (convex, a left turn of the counter-clockwise boundary) is a point
with a fan of normals: it generates its own path on the rack, so a zero-radius arc is inserted
there before the inverse generation.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy import optimize

from rotorcad.curves import Arc, Curve, Mapped, sample_curve
from rotorcad.envelope import Generated
from rotorcad.gear import InvoluteGear
from rotorcad.geometry import cross, distance_to_polyline
from rotorcad.kinematics import Rotation, Translation, gear_mesh
from rotorcad.screw_rotors import ScrewRotors


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

    def normal(self) -> np.ndarray:
        """Normal rack: lengths along the pitch line times cos(beta)."""
        return self.points * np.array([np.cos(self.helix_angle), 1.0])

    @property
    def normal_period(self) -> float:
        return self.period * np.cos(self.helix_angle)


def _with_corner_fans(
    pieces: list[tuple[str, Curve]], centre: np.ndarray | None = None, pitch_angle: float = 0.0
) -> list[tuple[str, Curve]]:
    """Insert zero-radius arcs at the convex corners between consecutive pieces of a
    counter-clockwise chain, so that corners generate their paths. With ``centre`` and
    ``pitch_angle`` (one lobe of a patterned rotor) the corner where the previous lobe's last piece
    meets this lobe's first piece is found too, by turning that last piece back by one pitch."""

    def fan(name: str, end: tuple[np.ndarray, np.ndarray], start: tuple[np.ndarray, np.ndarray]) -> tuple[str, Curve] | None:
        (p_end, t_end), (p_next, t_next) = end, start
        if np.hypot(*(p_end - p_next)) > 1e-6:
            return None
        turn = float(np.arctan2(cross(t_end, t_next), np.dot(t_end, t_next)))
        if turn <= 1e-6:  # only a left turn is a convex corner of a counter-clockwise boundary
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
) -> DerivedRack:
    """Rack of a counter-clockwise chain of profile pieces on a rotating ``body`` (one lobe of
    ``pitch_angle``, so that the corner at the junction with the previous lobe is found too).

    ``depth`` = (y_min, y_max) of the rack about its pitch line picks, where the normal line cuts
    the pitch circle twice, the root that lies on the rack (see :mod:`rotorcad.envelope`).
    """
    centre = np.asarray(body.center, dtype=float)
    # the rack rolls on the pitch circle at the pitch point C = centre + (r, 0) (or - (r, 0) for a
    # body turning clockwise), moving +y per rad of the male / driving gear
    sign = 1.0 if body.rate > 0 else -1.0
    rack = Translation((0.0, abs(body.rate) * pitch_radius))
    pts, tans, idx, names = [], [], [], []
    lost, total = 0, 0
    # each generated piece runs against its parent, so the rack chain runs the pieces backwards
    for k, (name, curve) in enumerate(reversed(_with_corner_fans(pieces, centre, pitch_angle))):
        gen = Generated(curve, body, rack, limits=depth)
        s, p, t = sample_curve(gen, tolerance, minimum=samples)  # refined where the rack turns fast (corner paths)
        ok = np.isfinite(p).all(axis=1)
        lost += int((~ok).sum())
        total += len(ok)
        if curve.is_corner():
            ok &= _on_the_corner_path(gen, s, body, pitch_radius, depth, p)
        pts.append(p[ok])
        tans.append(t[ok])
        idx.append(np.full(int(ok.sum()), k))
        names.append(name)
    p, t = np.vstack(pts), np.vstack(tans)
    c = centre + np.array([sign * pitch_radius, 0.0])
    r = np.stack([p[:, 1], sign * (p[:, 0] - c[0])], axis=1)  # rack frame, y away from the centre
    rt = np.stack([t[:, 1], sign * t[:, 0]], axis=1)
    return DerivedRack(r, rt, tuple(names), np.concatenate(idx), period, lost / max(total, 1), pitch_radius, helix_angle)


def gear_rack(gear: InvoluteGear, samples: int = 400) -> DerivedRack:
    """Transverse rack of one tooth space of an involute gear (from its generated outline)."""
    mesh = gear_mesh(gear.pitch_radius)
    tooth = gear.tooth_profile()
    pieces = [(seg.name, seg.curve) for seg in tooth.segments]
    return derive_rack(
        pieces,
        mesh.male,
        gear.pitch_radius,
        np.pi * gear.transverse_module,
        gear.helix_angle,
        samples=samples,
        pitch_angle=2 * np.pi / gear.teeth,
    )


def rotor_rack(rotors: ScrewRotors, rotor: str, samples: int = 400) -> DerivedRack:
    """Transverse rack derived from the male or the female of a pair (one lobe)."""
    pair = rotors.pair
    mesh = pair.mesh
    if rotor == "male":
        pieces = [(name, curve) for name, curve, _ in rotors.male_pieces]
        body, r_w = mesh.male, pair.male_pitch_radius
        beta = np.arctan(2 * np.pi * r_w / pair.lead)
    else:
        shift = (pair.center_distance, 0.0)
        pieces = [(name, Mapped(curve, ((1.0, 0.0), (0.0, 1.0)), shift)) for name, curve, _ in rotors.female_pieces]
        body, r_w = mesh.female, pair.female_pitch_radius
        beta = np.arctan(2 * np.pi * r_w / pair.female_lead)
    tip = pair.male_tip_radius if rotor == "male" else pair.female_tip_radius
    centre = np.asarray(body.center, dtype=float)
    pieces = [p for p in (_within(name, curve, centre, tip) for name, curve in pieces) if p is not None]
    depth = (-pair.male_dedendum - 1e-6, pair.male_addendum + 1e-6)
    teeth = pair.male_teeth if rotor == "male" else pair.female_teeth
    return derive_rack(
        pieces,
        body,
        r_w,
        pair.rack_period,
        beta,
        depth=depth,
        samples=samples,
        pitch_angle=2 * np.pi / teeth,
    )


def _within(name: str, curve: Curve, centre: np.ndarray, tip: float) -> tuple[str, Curve] | None:
    """The longest part of a generated piece inside the rotor's tip circle (generated flanks can
    overshoot it; the rotor is cut off there)."""
    s = np.linspace(curve.s0, curve.s1, 257)  # the ends are refined by root finding below
    p, _ = curve.evaluate(s)
    inside = np.hypot(*(p - centre).T) <= tip + 1e-7
    if inside.all():
        return name, curve
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
        fi, fo = gap(inner), gap(outer)
        if np.isfinite(fi) and np.isfinite(fo) and fi * fo < 0:
            return float(optimize.brentq(gap, inner, outer, xtol=1e-15))
        return inner

    # refine where the piece leaves the tip circle (the map to the rack is steep there)
    a = refine(s[starts[k]], s[starts[k] - 1]) if starts[k] > 0 else s[0]
    b = refine(s[ends[k]], s[ends[k] + 1]) if ends[k] < len(s) - 1 else s[-1]
    return name, curve.trimmed(a, b)


def rack_in_contract_frame(rack: DerivedRack, rotor: str) -> np.ndarray:
    """Rack points in the rack frame of CONTRACT.md (y > 0 on the female side)."""
    return rack.points if rotor == "male" else rack.points * np.array([1.0, -1.0])


def rack_deviation(rotors: ScrewRotors, samples: int = 400) -> float:
    """Largest distance of each rotor's rack from the other rotor's rack (mm), over the rack points
    whose contact lies inside both bores (real mesh contacts: a rotor cut off by its tip circle
    generates no rack beyond it), corner paths included: zero up to the sampling (0.1 um) for a
    conjugate pair (Wu & Chi sec. 2: a pair generated by one rack gives that rack back from either
    rotor). The two racks may start at different phases, so each is compared with the other's
    neighbouring periods too."""
    pair = rotors.pair
    racks = []
    for rotor in ("male", "female"):
        rack = rotor_rack(rotors, rotor, samples)
        pts = rack_in_contract_frame(rack, rotor)
        tan = rack.tangents * (np.array([1.0, -1.0]) if rotor == "female" else 1.0)
        # the contact point of each rack point: its normal meets the pitch line at C
        with np.errstate(divide="ignore", invalid="ignore"):
            contact = np.stack([pair.male_pitch_radius + pts[:, 1], -pts[:, 1] * tan[:, 1] / tan[:, 0]], axis=1)
        in_both = (np.hypot(*contact.T) <= pair.male_tip_radius) & (
            np.hypot(contact[:, 0] - pair.center_distance, contact[:, 1]) <= pair.female_tip_radius
        )
        cutting = in_both
        racks.append((pts, cutting))
    (a, ca), (b, cb) = racks

    def periodic(pts: np.ndarray) -> np.ndarray:
        # the two racks need not start at the same phase: compare with the neighbouring periods too
        shift = np.array([pair.rack_period, 0.0])
        return np.vstack([pts - shift, pts, pts + shift])

    d1 = distance_to_polyline(a[ca], periodic(b))
    d2 = distance_to_polyline(b[cb], periodic(a))
    return float(max(d1.max(initial=0.0), d2.max(initial=0.0)))


__all__ = ["DerivedRack", "derive_rack", "gear_rack", "rack_deviation", "rotor_rack"]

"""Rack and hob-tooth derivation from any profile (inverse generation).

The transverse rack of a rotor or gear is the envelope of its profile in the frame of a rack
rolling on its pitch circle (Wu & Chi, *Meshing clearance evaluation*, sec. 2, eqs. 4-8; Rinder
sec. 2.1: hobbability is judged through this rack). The normal rack is the transverse rack with
lengths along the pitch line multiplied by cos(beta) (beta the helix angle at the pitch cylinder:
tan(beta) = 2 pi r_w / h for a screw rotor of lead h). The hob tooth is the normal section of the
hob thread: the normal rack's tool material, i.e. the space of the gear, with a clearance added
under its root so that the hob never touches the gear's tip.

The inverse generation itself, corner fans included, is :mod:`rotorcad.inverse_rack`.
"""

from __future__ import annotations

import numpy as np
from scipy import optimize

from rotorcad.curves import Curve, Mapped
from rotorcad.gear import InvoluteGear
from rotorcad.geometry import distance_to_polyline
from rotorcad.inverse_rack import DerivedRack, contact_of_rack_points, derive_rack
from rotorcad.kinematics import gear_mesh
from rotorcad.roles import Side
from rotorcad.screw_rotors import ScrewRotors


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
    side = Side(rotor)
    if side is Side.MALE:
        pieces = [(name, curve) for name, curve, _ in rotors.male_pieces]
        body, r_w = mesh.male, pair.male_pitch_radius
        beta = np.arctan(2 * np.pi * r_w / pair.lead)
    else:
        shift = (pair.center_distance, 0.0)
        pieces = [(name, Mapped(curve, ((1.0, 0.0), (0.0, 1.0)), shift)) for name, curve, _ in rotors.female_pieces]
        body, r_w = mesh.female, pair.female_pitch_radius
        beta = np.arctan(2 * np.pi * r_w / pair.female_lead)
    tip = side.pick(pair.male_tip_radius, pair.female_tip_radius)
    centre = np.asarray(body.center, dtype=float)
    pieces = [p for p in (_within(name, curve, centre, tip) for name, curve in pieces) if p is not None]
    depth = (-pair.male_dedendum - 1e-6, pair.male_addendum + 1e-6)
    teeth = side.pick(pair.male_teeth, pair.female_teeth)
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
    inside = np.hypot(*(p - centre).T) <= tip + 2e-3  # a measured land may wander by the fit error
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
    return rack.points if Side(rotor) is Side.MALE else rack.points * np.array([1.0, -1.0])


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
        tan = rack.tangents * (np.array([1.0, -1.0]) if Side(rotor) is Side.FEMALE else 1.0)
        contact, _ = contact_of_rack_points(pair.male_pitch_radius, pts, tan)
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

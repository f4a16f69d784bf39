"""Stosic's N rack against brute-force cutting: the N4 rotors as the rack's envelope.

The rack chain of the ``n-rack`` family (its pieces evaluated at equal parameter steps, nothing of
the envelope engine) is rolled over each rotor's blank at some 1500 positions and subtracted from
the tip disc with shapely, as a hob or a planing cutter would cut it. rotorcad's rotors, generated
by the envelope engine from that rack, must lie on the cut outline within the cut's own scallops
and chord errors (a few micrometres), over the whole lobe: the driving generalised arc, the root
rounding, and the sealing tip circles that come back from their rack images.
"""

from __future__ import annotations

import hashlib

import numpy as np
import pytest
import shapely
from independent_pairs import distance_to_line, stored

from rotorcad.rotor_families import build_family
from rotorcad.rotor_pair import RotorPair

N4 = RotorPair(5, 6, 82.0, 57.99, 35.66, 46.34, 24.01, lead=226.156, length=162.079)


def rack_period_points(rotors, spacing: float = 0.03) -> np.ndarray:
    """One rack period in the rack frame (x along the pitch line, y > 0 towards the female), mm.

    Every piece evaluated densely (its parameter, motion t for the rotor circles' images, runs
    very unevenly along them) and thinned to about ``spacing`` mm between points: chords of at most
    spacing^2 / 8 rho, 0.11 um on the 1 mm male tip circle."""
    r1 = rotors.pair.male_pitch_radius
    chain = []
    for piece in rotors.rack:
        c = piece.curve
        p, _ = c.evaluate(np.linspace(c.s0, c.s1, 20000))
        xy = np.column_stack([p[:, 1], p[:, 0] - r1])  # fixed (X, Y) at t = 0 -> rack (Y, X - r1)
        run = np.concatenate([[0.0], np.cumsum(np.hypot(*np.diff(xy, axis=0).T))])
        keep = np.unique(np.searchsorted(run, np.arange(0.0, run[-1], spacing)))
        chain.append(np.vstack([xy[keep], xy[-1:]]))
    return np.vstack(chain)


def brute_force_cut(rotors, rotor: str, positions: int) -> shapely.Polygon:
    """:func:`brute_force_cut_of_rack`, read from tests/reference_data when stored there for this
    very rack chain (its points are part of the key)."""
    pair = rotors.pair
    pts = rack_period_points(rotors)
    key = repr((pair, rotor, positions, hashlib.sha256(pts.tobytes()).hexdigest()))
    return shapely.Polygon(
        stored("n_rack_cut", key, lambda: np.asarray(brute_force_cut_of_rack(pair, pts, rotor, positions).exterior.coords))
    )


def brute_force_cut_of_rack(pair: RotorPair, pts: np.ndarray, rotor: str, positions: int) -> shapely.Polygon:
    """The rotor's tip disc minus the rack (one period ``pts``) rolled over the part of a turn that
    cuts lobe 0 and its neighbours (shapely booleans only)."""
    r1, r2, a, period = pair.male_pitch_radius, pair.female_pitch_radius, pair.center_distance, pair.rack_period
    strip = np.vstack([pts + np.array([k * period, 0.0]) for k in range(-2, 3)])
    strip = strip[np.abs(strip[:, 0]) < 2.2 * period]
    far = 3 * (pair.male_addendum + pair.male_dedendum)
    male = rotor == "male"
    # the male's material lies below the rack curve, so the male is cut by the female side (above)
    tool = np.vstack([strip, [[strip[-1, 0], far if male else -far], [strip[0, 0], far if male else -far]]])
    tip = pair.male_tip_radius if male else pair.female_tip_radius
    shifts = np.linspace(-1.2 * period, 1.2 * period, positions)  # lobe 0 passes the pitch point around s = 0
    polys = []
    for s in shifts:
        fixed = np.column_stack([r1 + tool[:, 1], tool[:, 0] + s])
        ang = -s / r1 if male else s / r2
        q = fixed if male else fixed - np.array([a, 0.0])
        c, si = np.cos(ang), np.sin(ang)
        polys.append(np.column_stack([c * q[:, 0] - si * q[:, 1], si * q[:, 0] + c * q[:, 1]]))
    cut = shapely.Point(0, 0).buffer(tip, quad_segs=4096).difference(shapely.unary_union(shapely.polygons(polys)))
    return max(getattr(cut, "geoms", [cut]), key=lambda g: g.area)


@pytest.mark.parametrize("rotor", ["male", "female"])
def test_n4_rotors_are_what_the_rack_cuts(rotor):
    rotors = build_family(N4, "n-rack", {})
    pair = rotors.pair
    cut = brute_force_cut(rotors, rotor, 1500)
    outline = (rotors.male_outline if rotor == "male" else rotors.female_outline)(1e-4).points
    # lobe 0 (the one centred near polar angle 0 / pi): the brute-force cut is complete there
    polar = np.arctan2(outline[:, 1], outline[:, 0])
    teeth = pair.male_teeth if rotor == "male" else pair.female_teeth
    centre = 0.0 if rotor == "male" else np.pi
    lobe = outline[np.abs(np.angle(np.exp(1j * (polar - centre)))) < np.pi / teeth]  # one lobe pitch
    assert len(lobe) > 300
    d = distance_to_line(lobe, cut.exterior)
    # scallops of 1500 positions over 2.4 periods: (ds)^2 / 8 rho with ds ~ 0.075 mm and rho >= 1 mm:
    # below 1 um; with the rack's own chords and the 0.1 um outline, measured 0.05 um at the worst
    assert d.max() < 5e-4, d.max()
    assert np.median(d) < 1e-4

"""The clearance of a pair whatever the angle its points were measured at (a CMM's angular datum is arbitrary).

Pair (tests/independent_pairs.py, shapely booleans only): the 4/6 trapezoid rack pair, its female's
falling flank cut 20 um deeper by its rack, as CMM-like points (300 a lobe). The same points are
turned about their rotor's centre by a sweep of angles, cut to one lobe or one groove, reversed.

References, not produced by the code under test: the brute-force closest approach of the two cut
outlines over 1500 mesh positions (``independent_pairs.closest_approach``, per female point the
smallest distance to the male) at the unturned points, the designed 20 um flank offset, and the
rolling of the rack on the pitch circle (a rotor turned by theta moves its rack by r_w theta along
the pitch line, Wu & Chi 2013 sec. 2, eqs. 2-6). With a straight rotor (lead 1e5) the normal section
is the transverse one, so the contact zone's normal clearance is that distance.

And the contact alignment at a centre distance other than the one the rotors were cut for (a housing
bored oversize): the 5/6 arc-flank pair against a signed brute-force closest approach.
"""

from __future__ import annotations

import functools
import json

import numpy as np
import pytest
import shapely
from independent_pairs import (
    _rot,
    arc_flank_5_6,
    closest_approach,
    cut_rotor,
    distance_to_line,
    one_lobe,
    resample,
    ring_distance,
    stored_by_inputs,
    trapezoid_4_6,
)

from rotorcad.clearance import ClearanceZone, MeshingClearance, points_quality
from rotorcad.rotor_pair import RotorPair
from rotorcad.rotor_points import lobe_pieces

OFFSET = 0.02  # mm: the female's falling flank cut 20 um deeper by its rack
DEG = np.pi / 180


def per_lobe(ring: np.ndarray, teeth: int, points: int) -> float:
    """Spacing that gives ``points`` points a lobe on the closed ring."""
    return float(np.hypot(*np.diff(np.vstack([ring, ring[:1]]), axis=0).T).sum()) / teeth / points


@functools.cache
def rotors(noise: float = 0.0) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """The cut male and female outlines and their CMM-like points (300 a lobe, ``noise`` mm of scatter)."""
    rack_pair = trapezoid_4_6()
    male, female = cut_rotor(rack_pair, "male"), cut_rotor(trapezoid_4_6(flank_offset=OFFSET), "female")
    m = resample(male, per_lobe(male, 4, 300), noise, seed=11)
    f = resample(female, per_lobe(female, 6, 300), noise, seed=12)
    return male, female, m, f


def evaluate(m: np.ndarray, f: np.ndarray, contact: str = "driving") -> MeshingClearance:
    rack_pair = trapezoid_4_6()
    pair = RotorPair(4, 6, 100.0, **rack_pair.radii(), lead=1e5, length=1e5, strict=False)
    qm, qf = points_quality(m), points_quality(f)
    return MeshingClearance(
        pair,
        lobe_pieces(pair, m, "male"),
        lobe_pieces(pair, f, "female"),
        contact=contact,
        scatter=max(qm[0], qf[0]),
        spacing=max(qm[1], qf[1]),
    )


@functools.cache
def reading(male_turn: float = 0.0, female_turn: float = 0.0, cut: str = "whole", reverse: bool = False, noise: float = 0.0):
    """The clearance (driving contact) of the pair's points, the male turned by ``male_turn`` and the female by
    ``female_turn`` (deg, about their own centres), each cut to one lobe/groove (``cut="one"``) and reversed."""
    _, _, m, f = rotors(noise)
    m, f = _rot(m, np.full(len(m), male_turn * DEG)), _rot(f, np.full(len(f), female_turn * DEG))
    if cut == "one":  # one lobe of the male, one groove of the female (31 deg of its 60), as a CMM measures them
        m, f = one_lobe(m, 4, male_turn + 17.0), one_lobe(f, 6, female_turn + 150.0 + 17.0)
    if reverse:
        m, f = m[::-1], f[::-1]
    mc = evaluate(m, f)
    return mc, mc.summary()


TURNS = [
    (0.0, 10.0, "whole", False),
    (0.0, 180.0, "whole", False),
    (-75.0, 133.0, "whole", False),
    (35.0, -100.0, "one", False),
    (-20.0, 60.0, "one", True),
]


@pytest.mark.parametrize("male_turn,female_turn,cut,reverse", TURNS)
def test_the_reading_does_not_depend_on_the_angle_the_points_were_measured_at(male_turn, female_turn, cut, reverse):
    # Before: the contact search stepped out from the given phase up to a quarter of the rack period
    # and took the first sign change (the N-rack pair, female turned 10 deg: min -7631 um, a false
    # interference; turned farther: refused). Now the contact is found from the phase at which the
    # racks overlap least over the whole period: every turned, cut and reversed input reads the
    # unturned pair's figures within 1 um, the designed 20 um on the falling flank and 0 on the
    # driving one, and at about 40 contact-zone points the brute-force closest approach of the
    # unturned cut outlines within 1.5 um (as tests/test_clearance_zones.py holds the unturned pair).
    _, ref = reading()
    mc, s = reading(male_turn, female_turn, cut, reverse)
    for key in ("max_normal_clearance", "min_normal_clearance", "mean_clearance"):
        assert s[key] == pytest.approx(ref[key], abs=1e-3), key
    assert s["max_normal_clearance"] == pytest.approx(OFFSET, abs=1.5e-3)
    assert s["min_normal_clearance"] == pytest.approx(0.0, abs=1e-3)
    # about 30 contact-zone datum points against the brute force there: the distribution gives the
    # female points where the racks are in contact, in the female's frame at the phase found against
    # the male as given (on the unturned female's outline turned as a male turn turns it, phi2 = -phi1
    # z1 / z2, within 1 um)
    male, female, _, _ = rotors()
    male = _rot(male, np.full(len(male), male_turn * DEG))
    female = _rot(female, np.full(len(female), -male_turn * 4 / 6 * DEG))
    d = mc.distribution()
    on = np.flatnonzero(mc.zones == ClearanceZone.CONTACT)[::12]
    pts = np.column_stack([d["female_x"], d["female_y"]])[on]
    assert distance_to_line(pts, shapely.LinearRing(female)).max() < 1e-3
    truth = closest_approach(trapezoid_4_6(), pts, male, positions=1500)  # stored by its inputs in tests/reference_data
    np.testing.assert_allclose(mc.clearance[on], truth, atol=1.5e-3)


def test_the_contact_shift_follows_the_turn_of_the_female_by_its_pitch_radius():
    # The rack of a female turned by theta is its rack moved by r2w theta along the pitch line (the
    # rolling of the rack on the pitch circle, r2w = a z2 / (z1 + z2) = 60 mm): the shift that brings
    # the driving flanks into contact moves by that, modulo the rack period (20 pi mm), within 1 um.
    base, _ = reading()
    r2w, period = 60.0, 2 * np.pi * 40.0 / 4
    for turn in (10.0, 180.0):
        mc, _ = reading(0.0, turn)
        moved = np.mod(mc.shift - base.shift - r2w * turn * DEG + period / 2, period) - period / 2
        assert abs(moved) < 1e-3, (turn, moved)


def test_scattered_points_turned_read_as_unturned():
    # 1 um of scatter (the new-user session's N-rack case: 300 points a lobe, 1 um): the female turned
    # 10 and 20 deg reads the unturned points' figures within the stated accuracy, no interference.
    _, ref = reading(noise=1e-3)
    for turn in (10.0, 20.0):
        _, s = reading(0.0, turn, noise=1e-3)
        for key in ("max_normal_clearance", "min_normal_clearance", "mean_clearance"):
            assert s[key] == pytest.approx(ref[key], abs=s["accuracy"]), key
        assert s["min_normal_clearance"] > -s["accuracy"]


def test_as_given_keeps_the_points_own_phase(tmp_path, capsys):
    # --contact as-given does not move the racks (female_rack_shift 0): the points' own phase is
    # the measured one, so a turned female reads the turn as interference (CONTRACT.md); driving
    # finds the contact whatever the turn (the CLI, the same figures as the unturned points within 1 um).
    from exports.csv_points import write_points
    from rotorcad.cli.main import main

    _, ref = reading()
    _, _, m, f = rotors()
    write_points(tmp_path / "m.csv", m)
    write_points(tmp_path / "f.csv", _rot(f, np.full(len(f), 10.0 * DEG)))
    base = ["clearance", "--male-points", str(tmp_path / "m.csv"), "--female-points", str(tmp_path / "f.csv")]
    base += ["--male-teeth", "4", "--female-teeth", "6", "--center-distance", "100", "--lead", "1e5", "--length", "1e5", "--json"]
    out = {}
    for contact in ("driving", "as-given"):
        capsys.readouterr()
        assert main([*base, "--contact", contact]) == 0
        out[contact] = json.loads(capsys.readouterr().out)
    assert out["as-given"]["female_rack_shift"] == 0.0
    assert out["as-given"]["min_normal_clearance"] < -1.0  # 10 deg at r2w = 60 mm: the flanks 10 mm into each other
    assert out["driving"]["interference"] is False
    assert out["driving"]["mean_clearance"] == pytest.approx(ref["mean_clearance"], abs=1e-3)


@stored_by_inputs("signed_approach", _rot, ring_distance)
def signed_approach(a: float, female_pts: np.ndarray, male: np.ndarray, positions: int = 1500) -> np.ndarray:
    """Brute force: for each female point (own frame, (n, 2)) the smallest signed distance to the male outline
    over ``positions`` mesh positions at centre distance ``a`` (the 5/6 pair; negative inside the male: an
    interference). The positions, the distance and the window of ``independent_pairs.closest_approach`` (the
    female turned clockwise by phi2 within 40 deg of the line of centres, the male counter-clockwise by
    phi2 z2 / z1); the sign from shapely's point-in-polygon test. Stored in tests/reference_data by its
    inputs and its code (tests/make_reference_data.py)."""
    from scipy.spatial import cKDTree

    ring = np.asarray(shapely.segmentize(shapely.LinearRing(male), 0.005).coords)[:-1]
    body = shapely.Polygon(male)
    shapely.prepare(body)
    theta = np.arctan2(female_pts[:, 1], female_pts[:, 0])
    phi2 = (theta - np.pi)[:, None] + np.radians(40.0) * np.linspace(-1.0, 1.0, positions)[None, :]
    fixed = _rot(np.repeat(female_pts, positions, axis=0), -phi2.ravel()) + np.array([a, 0.0])
    p = _rot(fixed, -(phi2 * 6 / 5).ravel())
    best = ring_distance(ring, cKDTree(ring), p)
    signed = np.where(shapely.contains_xy(body, p[:, 0], p[:, 1]), -best, best)
    return signed.reshape(len(female_pts), positions).min(axis=1)


@pytest.mark.parametrize("a", [100.05, 100.2])
def test_a_housing_bored_oversize_reads_no_interference(a):
    # The 5/6 arc-flank pair, both rotors cut by one rack at a = 100 mm (300 points a lobe, exact),
    # read at a larger centre distance, the racks brought into contact on the sealing flank (its
    # circular arc: unlike an involute, its clearance is no longer uniform along the flank there).
    # Before: the alignment zeroed the running mean of the flank's clearance over twenty spacings,
    # which lies above its minimum where the clearance grows away from the contact: min -1.7 um at
    # 100.05 mm, -6.8 um at 100.2 mm (an interference flag where the rotors only move apart). Now
    # exact points zero the flank's smallest clearance itself (scattered ones that of a local
    # quadratic fit, which keeps the trend). Reference: the brute-force signed closest approach of the
    # cut outlines over 1500 mesh positions at the female points of the contact zone as the clearance
    # placed them: never negative beyond the accuracy (the contact found is where they touch), its
    # smallest value zero within it, and the clearance read within the accuracy of it point by point.
    rack_pair = arc_flank_5_6()
    male, female = cut_rotor(rack_pair, "male"), cut_rotor(rack_pair, "female")
    m, f = resample(male, per_lobe(male, 5, 300)), resample(female, per_lobe(female, 6, 300))
    pair = RotorPair(5, 6, a, **rack_pair.radii(), lead=1e5, length=1e5, strict=False)
    qm, qf = points_quality(m), points_quality(f)
    mc = MeshingClearance(
        pair,
        lobe_pieces(pair, m, "male"),
        lobe_pieces(pair, f, "female"),
        contact="sealing",
        scatter=max(qm[0], qf[0]),
        spacing=max(qm[1], qf[1]),
    )
    s = mc.summary()
    assert s["min_normal_clearance"] > -s["accuracy"]
    d = mc.distribution()
    on = np.flatnonzero(mc.zones == ClearanceZone.CONTACT)
    on = on[np.union1d(np.arange(0, len(on), 12), np.argsort(mc.clearance[on])[:5])]
    truth = signed_approach(a, np.column_stack([d["female_x"], d["female_y"]])[on], male)
    assert truth.min() == pytest.approx(0.0, abs=s["accuracy"])
    np.testing.assert_allclose(mc.clearance[on], truth, atol=s["accuracy"])


def test_the_overlap_areas_are_shapelys_for_overhangs_and_a_chain_that_crosses_itself():
    # rotorcad.clearance_phase sums the racks' overlap over thin columns (each region's section the
    # intervals between alternate crossings of its outline). Reference: shapely's intersection area of
    # the same outlines made valid (GEOS MakeValid: the noded linework, even-odd), on racks whose chains
    # lean back over themselves (an overhang: three crossings in a column) and cross themselves (a loop,
    # as the two generated parts of an undercut flank make), within 1e-4 of the area (1e-6 mm² where
    # they do not overlap).
    from rotorcad.clearance_phase import COLUMNS, overlap_areas, rack_ring

    period = 20.0
    t = np.linspace(0.0, 1.0, 400, endpoint=False)
    # one tooth a period: a sine, leaned so that its flanks hang over (x turns back), plus a loop
    male = np.column_stack([period * t + 4.5 * np.sin(2 * np.pi * t), 3.0 * np.cos(2 * np.pi * t)])
    s = np.linspace(0.0, 1.0, 300, endpoint=False)
    female = np.column_stack([period * s - 2.5 * np.sin(4 * np.pi * s), 3.2 + 2.5 * np.cos(2 * np.pi * s)])
    assert np.any(np.diff(male[:, 0]) < 0) and np.any(np.diff(female[:, 0]) < 0)  # both hang over
    assert not shapely.LineString(female).is_simple  # and the female crosses itself
    low, high = -5.0, 7.0
    m_ring, f_ring = rack_ring(male, period, 3, low), rack_ring(female, period, 1, high)
    shifts = np.linspace(-period / 2, period / 2, 9)
    got = overlap_areas(m_ring, f_ring, shifts, period / COLUMNS)
    m_region, f_region = shapely.make_valid(shapely.Polygon(m_ring)), shapely.make_valid(shapely.Polygon(f_ring))
    want = [shapely.intersection(m_region, shapely.affinity.translate(f_region, xoff=x)).area for x in shifts]
    assert sum(w > 1.0 for w in want) >= 6  # the areas compared are mostly not zeros
    np.testing.assert_allclose(got, want, rtol=1e-4, atol=1e-6)

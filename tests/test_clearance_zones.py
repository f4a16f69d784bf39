"""The meshing clearance's zones and its accuracy from CMM-like points, on pairs rotorcad did not make.

Pairs (tests/independent_pairs.py, shapely booleans only): the 4/6 trapezoid rack pair (sharp tip
corners cut back by the flats, lands), the 5/6 pair of a rack with one straight and one circular-arc
flank (other lobe counts, sharp tips), and a pair cut rotor by rotor (the 4/6 male with its tip
corners rounded, the female cut by it as the tool).

Reference, not produced by the code under test: the brute-force closest approach of the two cut
outlines over 1500 mesh positions (``independent_pairs.closest_approach``: per female point, the
smallest distance to the male over the positions). With a straight rotor (lead 1e5, the largest design lead) the normal
section is the transverse one, so the contact zone's normal clearance is that distance too.
"""

from __future__ import annotations

import functools

import numpy as np
import pytest
from independent_pairs import (
    arc_flank_5_6,
    closest_approach,
    cut_rotor,
    female_cut_by_male,
    resample,
    rounded_male,
    trapezoid_4_6,
    true_gap,
)

from rotorcad.clearance import ClearanceZone, MeshingClearance, points_quality
from rotorcad.rotor_pair import RotorPair
from rotorcad.rotor_points import lobe_pieces

OFFSET = 0.02  # mm: the 4/6 female's falling flank cut 20 um deeper by its rack


@functools.cache
def outlines(name: str) -> tuple[object, np.ndarray, np.ndarray]:
    """The independent pair ``name``: its rack pair and the male and female cut outlines (cached)."""
    if name == "sharp":
        pair = trapezoid_4_6()
        return pair, cut_rotor(pair, "male"), cut_rotor(trapezoid_4_6(flank_offset=OFFSET), "female")
    if name == "arc":
        pair = arc_flank_5_6()
        return pair, cut_rotor(pair, "male"), cut_rotor(pair, "female")
    pair = trapezoid_4_6()
    male = rounded_male(cut_rotor(pair, "male"), 1.5)
    # 3000 positions: the rounded tip (1.5 mm) leaves scallops of about chord^2 / (8 r) = 1.3 um in
    # the female root (the tip moves about 0.13 mm against the female between positions)
    return pair, male, female_cut_by_male(pair, male, positions=3000)


def evaluate(name: str, male: np.ndarray, female: np.ndarray, lead: float = 1e5, contact: str = "as-given") -> MeshingClearance:
    rack_pair, _, _ = outlines(name)
    z1, z2 = rack_pair.male_teeth, rack_pair.female_teeth
    pair = RotorPair(z1, z2, 100.0, **rack_pair.radii(), lead=lead, length=lead, strict=False)
    qm, qf = points_quality(male), points_quality(female)
    return MeshingClearance(
        pair,
        lobe_pieces(pair, male, "male"),
        lobe_pieces(pair, female, "female"),
        contact=contact,
        scatter=max(qm[0], qf[0]),
        spacing=max(qm[1], qf[1]),
    )


@functools.cache
def exact(name: str) -> tuple[MeshingClearance, np.ndarray, np.ndarray, np.ndarray]:
    """The clearance of the cut outlines (straight rotors); about 40 datum points of each zone (and
    each zone's largest value) with the brute-force closest approach at their female points; the
    brute-force closest approach of each sharp female corner (the generating point of its fan)."""
    rack_pair, male, female = outlines(name)
    mc = evaluate(name, male, female)
    d = mc.distribution()
    profile = np.column_stack([d["female_x"], d["female_y"]])
    picks = []
    for zone in (ClearanceZone.CONTACT, ClearanceZone.GAP, ClearanceZone.CORNER):
        idx = np.flatnonzero((mc.zones == zone) & ~mc.female_rack.corner_path)
        if len(idx):  # every 40th, and the largest value (max_normal_clearance, max_gap)
            value = mc.clearance[idx] if zone is ClearanceZone.CONTACT else mc.gap[idx]
            picks.append(np.union1d(idx[:: max(1, len(idx) // 40)], idx[np.nanargmax(value)]))
    pick = np.concatenate(picks)
    fan = mc.female_rack.corner_path & (mc.zones == ClearanceZone.CORNER)
    corners = np.unique(np.round(mc.female_rack.profile[fan], 9), axis=0)
    ref = closest_approach(rack_pair, np.vstack([profile[pick], corners]), male, positions=1500)
    return mc, pick, ref[: len(pick)], ref[len(pick) :]


@pytest.mark.parametrize("name", ["sharp", "arc", "rounded"])
def test_each_zone_reads_the_brute_force_closest_approach(name):
    # The contact zone's normal clearance, the gap of the parts that never touch (the root below a
    # sharp tip) and a sharp female corner's closest approach against the brute force: 1.5 um on the
    # contact zone, 2 um on the gaps (the cut outlines' scallops and chords), the corner's smallest
    # gap along its path within 1.5 um of the corner's own brute-force approach.
    mc, pick, ref, corner_ref = exact(name)
    zone = mc.zones[pick]
    on = zone == ClearanceZone.CONTACT
    assert on.sum() > 20
    # the rounded male's fit leaves 3.2 um where its tip rounding (1.5 mm) meets the flank (the
    # curvature jumps there, measured: the brute force at the same female point reads 0.01 um)
    tol = 3.5e-3 if name == "rounded" else 1.5e-3
    np.testing.assert_allclose(mc.clearance[pick][on], ref[on], atol=tol)
    gap = zone == ClearanceZone.GAP
    np.testing.assert_allclose(mc.gap[pick][gap], ref[gap], atol=2e-3)
    s = mc.summary()
    # max_normal_clearance is the contact zone's: the brute force's largest there, not a corner's gap
    assert s["max_normal_clearance"] == pytest.approx(ref[on].max(), abs=tol)
    assert s["max_normal_clearance"] < (OFFSET + 2e-3 if name == "sharp" else 1e-2)
    if len(corner_ref):
        assert s["min_corner_gap"] == pytest.approx(corner_ref.min(), abs=1.5e-3)
    if name in ("sharp", "arc"):  # a sharp male tip leaves the female root below it untouched
        assert gap.any() and s["max_gap"] == pytest.approx(ref[gap].max(), abs=2e-3)
        assert s["max_gap"] > 0.05


def test_a_designed_flank_offset_is_the_contact_zone_maximum():
    # The 4/6 female's falling flank cut 20 um deeper (transverse, straight rotors): the contact
    # zone reads it (brute force above), and neither the sharp tip corner (0.09 mm of gap under the
    # male tip) nor the corner paths push max_normal_clearance beyond it.
    mc, _, _, _ = exact("sharp")
    s = mc.summary()
    assert s["max_normal_clearance"] == pytest.approx(OFFSET, abs=1.5e-3)
    assert s["min_normal_clearance"] == pytest.approx(0.0, abs=1e-3)


def per_lobe(ring: np.ndarray, teeth: int, points: int) -> float:
    """Spacing that gives ``points`` points a lobe on the closed ring."""
    return float(np.hypot(*np.diff(np.vstack([ring, ring[:1]]), axis=0).T).sum()) / teeth / points


@pytest.mark.parametrize("points", [80, 300, 2000])
@pytest.mark.parametrize("noise", [0.0, 1e-3, 2e-3])
def test_cmm_density_and_scatter_on_a_conjugate_pair(points, noise):
    # Both 4/6 rotors cut by the same rack (no flank offset), lead 300 mm, as a CMM gives them
    # (seeded Gaussian scatter along the normals): on the contact zone the clearance is zero within
    # 5 um (300 and 2000 points a lobe) or 10 um (80), and within the stated accuracy; the contact
    # alignment moves by at most 2 um (0 for the exact pair); no interference beyond the accuracy.
    rack_pair = trapezoid_4_6()
    male, female = cut_rotor(rack_pair, "male"), cut_rotor(rack_pair, "female")
    m = resample(male, per_lobe(male, 4, points), noise, seed=points + 1)
    f = resample(female, per_lobe(female, 6, points), noise, seed=points + 2)
    pair = RotorPair(4, 6, 100.0, **rack_pair.radii(), lead=300.0, length=190.0, strict=False)
    qm, qf = points_quality(m), points_quality(f)
    mc = MeshingClearance(
        pair, lobe_pieces(pair, m, "male"), lobe_pieces(pair, f, "female"), scatter=max(qm[0], qf[0]), spacing=max(qm[1], qf[1])
    )
    s = mc.summary()
    c = mc.clearance[mc.contact_zone]
    assert mc.contact_zone.sum() > 200
    worst = float(np.abs(c).max())
    assert worst < (10e-3 if points == 80 else 5e-3)
    assert worst <= s["accuracy"]
    assert abs(s["female_rack_shift"]) < 2e-3
    assert s["min_normal_clearance"] > -s["accuracy"]  # the CLI's interference flag stays off


@functools.cache
def undercut_pair_from_points(
    points: int, noise: float, seed: int
) -> tuple[MeshingClearance, np.ndarray, np.ndarray, np.ndarray]:
    """The 5/6 arc-flank pair's clearance from CMM-like points (straight rotors), and the brute-force
    truth (independent_pairs.true_gap) at the female points of its contact zone (every 6th row and
    the 20 largest |clearance|) and of its unresolved rows (every 3rd), cached for the tests below."""
    rack_pair = arc_flank_5_6()
    male, female = cut_rotor(rack_pair, "male"), cut_rotor(rack_pair, "female")
    m = resample(male, per_lobe(male, 5, points), noise, seed=seed)
    f = resample(female, per_lobe(female, 6, points), noise, seed=seed + 100)
    pair = RotorPair(5, 6, 100.0, **rack_pair.radii(), lead=1e5, length=1e5, strict=False)
    qm, qf = points_quality(m), points_quality(f)
    mc = MeshingClearance(
        pair, lobe_pieces(pair, m, "male"), lobe_pieces(pair, f, "female"), scatter=max(qm[0], qf[0]), spacing=max(qm[1], qf[1])
    )
    d = mc.distribution()
    on = np.flatnonzero(mc.contact_zone)
    pick = on[np.union1d(np.arange(0, len(on), 6), np.argsort(-np.abs(mc.clearance[on]))[:20])]
    unresolved = np.flatnonzero(mc.zones == ClearanceZone.UNRESOLVED)[::3]
    rows = np.concatenate([pick, unresolved])
    truth = true_gap(rack_pair, female, male, np.column_stack([d["female_x"], d["female_y"]])[rows])
    return mc, rows, np.where(mc.contact_zone[rows], truth, np.nan), np.where(mc.contact_zone[rows], np.nan, truth)


@pytest.mark.parametrize("points,noise,seed", [(80, 0.0, 0), (80, 2e-3, 1), (300, 2e-3, 1), (2000, 1e-3, 3)])
def test_cmm_points_of_the_undercut_pair_against_the_brute_force(points, noise, seed):
    # The 5/6 arc-flank pair (its male undercut at r = 42.3-42.7 mm, a sharp 10 deg corner where
    # the two generated parts of its flank cross), straight rotors so that the normal clearance is
    # the transverse gap: on the contact zone (every 6th row and the 20 largest) the clearance
    # read from CMM-like points within the stated accuracy of the brute-force closest approach of
    # the cut outlines at the same female point (independent_pairs.true_gap), and so are the
    # reported largest and smallest values (measured: 1.5 / 4.6 um at 80 points a lobe with 0 / 2
    # um scatter, stated 6.5 / 19.0 um; 5.7 um at 300 points a lobe with 2 um scatter, stated
    # 12.5 um; 2.0 um at 2000 with 1 um, stated 7.0 um), within the 10 um at 80 points a
    # lobe; the alignment on the driving flank (truth 0: both cut at one rack phase) within 2 um; no
    # interference beyond the accuracy (truth: none).
    mc, rows, truth, _ = undercut_pair_from_points(points, noise, seed)
    s = mc.summary()
    on = np.isfinite(truth)
    c = mc.clearance[rows][on]
    worst = float(np.abs(c - truth[on]).max())
    assert worst <= s["accuracy"], (worst, s["accuracy"])
    if points == 80:
        assert worst < 10e-3
    assert abs(s["max_normal_clearance"] - truth[on][np.argmax(c)]) <= s["accuracy"]
    assert abs(s["min_normal_clearance"] - truth[on][np.argmin(c)]) <= s["accuracy"]
    assert abs(s["female_rack_shift"]) < 2e-3
    assert s["min_normal_clearance"] > -s["accuracy"]


@pytest.mark.parametrize("noise,seed", [(0.0, 0), (2e-3, 1)])
def test_the_contact_that_sparse_points_cannot_resolve_is_left_out(noise, seed):
    # At 80 points a lobe (0.9 mm apart) the 5/6 male's fit rounds its undercut's 0.4 mm crossing
    # off: the female rows facing the flank beside it read up to 25-31 um of clearance where the
    # brute force (independent_pairs.true_gap) gives under 1 um. They are the unresolved zone (4),
    # not the contact zone: a small share of the contact line, and there the error the brute force
    # shows exceeds the 10 um at 80 points a lobe, and for exact points the accuracy stated
    # for the rest (the exclusion is needed, not a guess; measured 25.6 um, stated 6.5 um; 18.9 um
    # with 2 um scatter, stated 19.0 um).
    mc, rows, _, truth = undercut_pair_from_points(80, noise, seed)
    s = mc.summary()
    off = np.isfinite(truth)
    # of the contact line's length, with the flank within two spacings of a sharp corner (0.19 at 80 points
    # a lobe; the undercut's crossing alone 0.085, of the contact line's points under 0.06)
    assert 0.0 < s["unresolved_share"] < 0.25
    assert s["max_unresolved_clearance"] == pytest.approx(np.nanmax(mc.clearance[mc.zones == ClearanceZone.UNRESOLVED]))
    excluded = float(np.abs(mc.clearance[rows][off] - truth[off]).max())
    assert excluded > 10e-3
    if noise == 0:
        assert excluded > s["accuracy"]


def test_cli_states_the_accuracy_and_the_zones(tmp_path, capsys):
    # `rotorcad clearance` on the 4/6 pair at 300 points a lobe with 2 um scatter (CMM-like): the
    # contact zone reads zero within the stated accuracy (both rotors cut by one rack), no false
    # interference, the gap under the sharp male tip (0.1 mm, brute force above) under its own key,
    # and the CSV gives each row's zone and gap.
    import json

    from exports.csv_points import write_points
    from rotorcad.cli.main import main

    rack_pair = trapezoid_4_6()
    male, female = cut_rotor(rack_pair, "male"), cut_rotor(rack_pair, "female")
    write_points(tmp_path / "m.csv", resample(male, per_lobe(male, 4, 300), 2e-3, seed=5))
    write_points(tmp_path / "f.csv", resample(female, per_lobe(female, 6, 300), 2e-3, seed=6))
    args = ["clearance", "--male-points", str(tmp_path / "m.csv"), "--female-points", str(tmp_path / "f.csv")]
    args += ["--male-teeth", "4", "--female-teeth", "6", "--center-distance", "100", "--json", "--csv", str(tmp_path / "c.csv")]
    capsys.readouterr()
    assert main(args) == 0
    data = json.loads(capsys.readouterr().out)
    # 1 um + sqrt(2) k_N sigma + 0.004 h^2 with sigma = 2 um (the scatter made) and k_N the 95 %
    # bound on the largest of N Gaussian errors, Phi^-1(1 - 0.025 / N): 3.29-4.21 for N = 50-2000
    # points along the contact zone, h = 0.25 mm: 10.6-13.2 um
    assert 10.0e-3 < data["accuracy"] < 13.5e-3
    assert abs(data["max_normal_clearance"]) <= data["accuracy"] and abs(data["min_normal_clearance"]) <= data["accuracy"]
    assert data["interference"] is False
    assert data["max_gap"] == pytest.approx(0.1, abs=0.01)
    lines = (tmp_path / "c.csv").read_text().splitlines()
    header = next(line for line in lines if line.startswith("x,y,clearance"))
    # the columns scripts read keep their order; flank (1 driving, 2 sealing, 3/4 lands) is added last
    expected = "x,y,clearance,male_angle_deg,z,contact_x,contact_y,female_x,female_y,male_x,male_y,in_contact,zone,gap"
    assert header == expected + ",flank"
    rows = np.loadtxt([line for line in lines if line[:1].isdigit() or line[:1] == "-"], delimiter=",")
    assert set(np.unique(rows[:, 14])) <= {1.0, 2.0, 3.0, 4.0} and {1.0, 2.0} <= set(np.unique(rows[:, 14]))
    for name in ("driving", "sealing"):  # the conjugate pair: every flank zero within the stated accuracy
        assert abs(data[f"{name}_max_normal_clearance"]) <= data["accuracy"]
        assert abs(data[f"{name}_min_normal_clearance"]) <= data["accuracy"]
    # no --lead / --length: the values taken are said (a new user's finding: they changed the N rack's
    # largest clearance by 8 um, silently); given as those values, the same numbers and nothing taken
    assert set(data["defaults"]) == {"--lead", "--length"} and data["defaults"]["--lead"].startswith("300 mm (default")
    assert main([*args[:-2], "--lead", "300", "--length", "190"]) == 0
    given = json.loads(capsys.readouterr().out)
    assert given["defaults"] == {} and given["max_normal_clearance"] == data["max_normal_clearance"]


def test_a_designed_flank_offset_reads_back_on_its_own_flank():
    # issue 22 (newuser4 N11): a clearance designed on one flank is read back per flank. The 4/6
    # female's trailing rack flank is cut 20 um deeper (its construction, independent_pairs.TrapezoidRack
    # flank_offset), the other flank not at all: one of driving/sealing reads 20 um at most, the other
    # 0, and each flank's largest and smallest value is the brute-force closest approach's (1500 mesh
    # positions) over that flank's rows (picked every 40th and each zone's largest, exact() above)
    mc, pick, ref, _ = exact("sharp")
    s = mc.summary()
    on = mc.zones[pick] == ClearanceZone.CONTACT
    highs = sorted([s["driving_max_normal_clearance"], s["sealing_max_normal_clearance"]])
    assert highs[0] == pytest.approx(0.0, abs=1.5e-3)
    assert highs[1] == pytest.approx(OFFSET, abs=1.5e-3)
    for code, name in ((1, "driving"), (2, "sealing")):
        rows = on & (mc.flanks[pick] == code)
        assert rows.sum() > 5
        assert s[f"{name}_max_normal_clearance"] >= ref[rows].max() - 1.5e-3
        assert s[f"{name}_min_normal_clearance"] == pytest.approx(max(ref[rows].min(), 0.0), abs=1.5e-3)
        assert s[f"{name}_min_normal_clearance"] <= s[f"{name}_mean_clearance"] <= s[f"{name}_max_normal_clearance"]

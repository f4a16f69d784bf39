"""A rotor given as 80-300 points a lobe: its contact ratios, points of infinite slip and defects (issue 21 items 1 and 3).

The transverse contact ratio read from points states an accuracy that covers its error; the points of
infinite slip and the defects at 150-300 points a lobe are the design's.

Reference: each sample's design, its ratios from its exact curves (checked against a brute force over
the two outlines in tests/test_contact_ratio_invariance.py::test_design_ratio_is_the_brute_force). The
inputs are built here from the designs' outlines: a rotor's outline (male or female) as exact points
evenly spaced at 80, 150 and 300 a lobe (a CMM's scan, the corners between the points), and with 1 or
2 µm of scatter along the normals at seeded draws.

The finding (new user 4, "newuser3 #4" and N9): the README said the ratio lies within 2 sqrt(8 a e) /
p_t of the design's (about 0.09 at 80 a lobe), but the narrow-tip male's sealing ratio read 0.000 from
80 exact points a lobe and 0.485 with 1 µm for the design's 0.175, the asymmetric SRM's driving 0.32
for 0, the Lysholm's 0.22 for 0 at 150 and 300 a lobe: 2-3.5 times that bound. An end of the working part
is placed to sqrt(8 a e) along the profile of the rotor whose corner ends it, and where that rotor's
contact moves slowly (the narrow-tip female's sealing flank is 2.9 mm of profile for 12.2 mm of
meshline) that is several times as much male rotation; a stretch the input cannot tell from a tip corner's
path may be one. ``transverse_contact_ratio_accuracy`` (rotorcad.meshing.ratio_accuracy) states it.
"""

from __future__ import annotations

import functools
import tomllib
from collections import Counter
from pathlib import Path

import numpy as np
import pytest
import shapely
from independent_pairs import patterned, scan
from shared_runs import points_summary

from rotorcad.design import rotor_design
from rotorcad.meshing import resolution
from rotorcad.meshing.undecided import compare_defects
from rotorcad.rotor_build import PairSpec, analyse_pair, build_pair, pair_spec

SAMPLES = Path(__file__).resolve().parents[1] / "samples"
NAMES = (
    "krigar_4_6",
    "lysholm_4_6",
    "n_rack_5_6",
    "narrow_tip_5_6",
    "rack_involute_5_6",
    "rinder_deix_5_6",
    "srm_asymmetric_5_6",
    "srm_b_5_6",
    "srm_symmetric_4_6",
)
FLANKS = ("driving", "sealing")
PHASE = 0.37  # where the first point falls, in spacings past the lobe's start


@functools.cache
def _design_pair(name: str) -> tuple[PairSpec, object, dict, dict[str, tuple[np.ndarray, int]]]:
    """A sample's spec, its design's analysis and summary, and each rotor's outline (0.01 um chord) with its lobe count."""
    spec = pair_spec(rotor_design(tomllib.loads((SAMPLES / f"{name}.toml").read_text()), SAMPLES))
    rotors = build_pair(spec)
    outlines = {
        "male": (np.vstack([s.resampled(1e-5).points for s in rotors.male_lobe().segments]), spec.pair.male_teeth),
        "female": (np.vstack([s.resampled(1e-5).points for s in rotors.female_lobe().segments]), spec.pair.female_teeth),
    }
    return spec, *analyse_pair(rotors, spec.speed_rpm), outlines


def _design(name: str) -> tuple[PairSpec, dict, dict[str, tuple[np.ndarray, int]]]:
    spec, _, design, outlines = _design_pair(name)
    return spec, design, outlines


def _points(name: str, side: str, per_lobe: int, sigma: float, seed: int, phase: float = PHASE) -> np.ndarray:
    """One rotor's outline as ``per_lobe`` points a lobe with ``sigma`` mm of scatter along the normals (seeded)."""
    _, _, outlines = _design(name)
    lobe, teeth = outlines[side]
    points = scan(patterned(lobe, teeth), per_lobe * teeth, phase)
    if sigma:
        d = np.roll(points, -1, axis=0) - np.roll(points, 1, axis=0)
        normal = np.column_stack([d[:, 1], -d[:, 0]]) / np.hypot(d[:, 0], d[:, 1])[:, None]
        points = points + np.random.default_rng(seed).normal(0.0, sigma, len(points))[:, None] * normal
    return points


def _given(name: str, side: str, per_lobe: int, sigma: float, seed: int, phase: float = PHASE) -> tuple[dict, dict]:
    """The design's summary and that of one rotor's outline as ``per_lobe`` points a lobe with ``sigma`` mm of scatter."""
    spec, design, _ = _design(name)
    points = _points(name, side, per_lobe, sigma, seed, phase)
    # built and analysed once in the run for these points (this file reads some inputs in several tests, and
    # tests/test_verdict_invariance.py and tests/test_blow_hole_points.py some of the same): tests/shared_runs.py
    given = PairSpec(spec.pair, f"{side}-points", {}, points, None, spec.speed_rpm, 0.0)
    return design, points_summary(given, f"--{side}-points")


# (side, points a lobe, scatter mm, seed): every sample's male at the three densities, exact and scattered
# at two seeds; the females where the male's points are not the only way in
MALE_CASES = [("male", 80, 1e-3, 1), ("male", 150, 2e-3, 2), ("male", 300, 1e-3, 1), ("male", 300, 2e-3, 2)]
FEMALE_CASES = [("female", 80, 0.0, 0), ("female", 150, 1e-3, 1), ("female", 300, 2e-3, 2)]
CASES = [(n, *c) for n in NAMES for c in MALE_CASES] + [
    (n, *c) for n in ("narrow_tip_5_6", "srm_asymmetric_5_6", "lysholm_4_6", "rack_involute_5_6") for c in FEMALE_CASES
]


@pytest.mark.parametrize(("name", "side", "per_lobe", "sigma", "seed"), CASES)
def test_stated_accuracy_covers_the_ratios_error(name, side, per_lobe, sigma, seed):
    # reference: the design's ratio per flank (its exact curves); the stated accuracy covers the departure.
    # Measured over all 9 samples x both rotors x 80/150/300 a lobe x exact, 1 and 2 um at two seeds (268
    # inputs): the largest departure 0.85 of the stated accuracy, the median departure 0.002-0.02
    design, given = _given(name, side, per_lobe, sigma, seed)
    for flank in FLANKS:
        want = design["flanks"][flank]["transverse_contact_ratio"]
        got = given["flanks"][flank]["transverse_contact_ratio"]
        accuracy = given["flanks"][flank]["transverse_contact_ratio_accuracy"]
        assert abs(got - want) <= accuracy, (flank, got, want, accuracy)
        # at least the README's bound: each end placed on the meshline to sqrt(8 a e), over the pitch p_t
        pitch = 2 * np.pi * design["center_distance"] / (design["male_teeth"] + design["female_teeth"])
        assert accuracy >= 2 * np.sqrt(8 * design["center_distance"] * given["defect_accuracy"]) / pitch - 1e-12


@pytest.mark.parametrize("name", NAMES)
def test_exact_points_state_an_accuracy_that_says_something(name):
    # 300 exact points a lobe of the male resolve every sample's ratios to better than half a pitch, and the
    # design states the sampling of its meshline only (reference: the brute force of
    # test_contact_ratio_invariance agrees with the design within 0.01). The N rack's and Rinder-Deix's
    # sealing flanks end on a 0.67 mm tip rounding that holds 2-3 points (their contact on the male moves
    # 0.67 mm for 30.8 mm of meshline), and state 0.44 there: the points do not tell it from a corner
    design, given = _given(name, "male", 300, 0.0, 0)
    for flank in FLANKS:
        assert design["flanks"][flank]["transverse_contact_ratio_accuracy"] <= 0.01, flank
        assert given["flanks"][flank]["transverse_contact_ratio_accuracy"] < 0.5, flank


def test_narrow_tip_from_80_exact_points_a_lobe():
    # the finding: the narrow-tip male as 80 exact points a lobe read a sealing ratio of 0.000 for the design's
    # 0.175: a working stretch whose contact stays near the female tip corner at one end and near the male tip
    # corner at the other was taken for a corner rounded by the fit (within reach of *a* corner step by step,
    # not of one corner all along). Now within the README's bound 2 sqrt(8 a e) / p_t (0.081) of the design's
    design, given = _given("narrow_tip_5_6", "male", 80, 0.0, 0)
    pitch = 2 * np.pi * design["center_distance"] / (design["male_teeth"] + design["female_teeth"])
    bound = 2 * np.sqrt(8 * design["center_distance"] * given["defect_accuracy"]) / pitch
    want = design["flanks"]["sealing"]["transverse_contact_ratio"]
    assert given["flanks"]["sealing"]["transverse_contact_ratio"] == pytest.approx(want, abs=bound)
    assert given["flanks"]["sealing"]["transverse_contact_ratio"] > 0.0


SLIP_CASES = [
    (name, per_lobe, sigma, seed)
    for name in ("krigar_4_6", "lysholm_4_6", "narrow_tip_5_6", "srm_asymmetric_5_6", "srm_b_5_6", "srm_symmetric_4_6")
    for per_lobe, sigma, seed in ((150, 0.0, 0), (150, 1e-3, 1), (300, 2e-3, 2))
]


def key(d: dict) -> tuple[str, str]:
    """A point of infinite slip's rotor and lobe part."""
    return d["rotor"], d["flank"]


@pytest.mark.parametrize(("name", "per_lobe", "sigma", "seed"), SLIP_CASES)
def test_points_of_infinite_slip_from_moderate_densities(name, per_lobe, sigma, seed):
    # reference: the design's points of infinite slip (Rinder eq. 4: where a rotor's v_t vanishes), by rotor and
    # lobe part, each within the input's resolution sqrt(8 a e) (as tests/test_verdict_invariance.py's
    # test_same_points_of_infinite_slip). Before: the males of the samples whose female tip circle is its pitch
    # circle read one more at 150 and 300 a lobe (21 of 72 inputs with 1-2 um at 150 a lobe, 14 of 72 at 300):
    # the female tip corner's path, left by the fit as a curve piece 0.14-0.23 mm inside the tip circle, crossed
    # the Thales circle on O2 C 4-18 deg from C (rotorcad.meshing.slip.TIP_ROUNDING)
    design, given = _given(name, "male", per_lobe, sigma, seed)
    want, got = design["slip_singularities"], given["slip_singularities"]
    assert Counter(map(key, got)) == Counter(map(key, want)), got
    reach = resolution(given["defect_accuracy"], design["center_distance"])
    for d in want:
        near = min((g for g in got if key(g) == key(d)), key=lambda g: np.hypot(g["x"] - d["x"], g["y"] - d["y"]))
        assert np.hypot(near["x"] - d["x"], near["y"] - d["y"]) <= reach, (d, near)


def _defect_keys(summary: dict) -> Counter:
    return Counter((d["kind"], d["rotor"], d["flank_role"], d["tip_corner"]) for d in summary["defects"])


@pytest.mark.parametrize(
    ("side", "per_lobe", "sigma", "seed"),
    [
        ("female", 300, 0.0, 0),
        ("female", 300, 1e-3, 1),
        ("female", 300, 2e-3, 2),
        ("female", 150, 1e-3, 1),
        ("male", 150, 1e-3, 2),
    ],
)
def test_rack_involute_keeps_the_female_tips_slipping(side, per_lobe, sigma, seed):
    # reference: the design's defects (its exact curves): two tip-corner cusps and two slipping points, the male
    # tip on the female root and the female tip on the male root (Rinder sec. 2.2.1: the meshline crosses O1O2
    # away from C). New user 4: the female as exact points at 150 a lobe, and either rotor with 1 um at 500 a lobe
    # in 4 of 10 seeds, lost "slipping, female tip on the male root": the meshline's driving flank began 2 um on
    # the sealing side of O1O2 before crossing it, and the side of a piece's end was taken beyond the profile's
    # accuracy (1.6 um), not the meshline's scatter (rotorcad.meshing.defects.slipping_between_pieces)
    design, given = _given("rack_involute_5_6", side, per_lobe, sigma, seed)
    assert _defect_keys(given) == _defect_keys(design)


# ---- 80 points a lobe: the slipping rule between pieces, and running verdicts the input does not decide ----------


def _slips(summary: dict) -> list[dict]:
    return [d for d in summary["defects"] if d["kind"] == "slipping"]


@pytest.mark.parametrize(
    ("name", "side", "per_lobe", "sigma", "seed", "phase"),
    [
        ("n_rack_5_6", "female", 80, 1e-3, 1, PHASE),
        ("rinder_deix_5_6", "female", 80, 2e-3, 2, PHASE),
        ("rack_involute_5_6", "female", 80, 0.0, 0, PHASE),
        ("rack_involute_5_6", "female", 80, 2e-3, 1, PHASE),
    ],
)
def test_female_tip_slips_on_the_male_root_from_sparse_points(name, side, per_lobe, sigma, seed, phase):
    # reference: the design's slipping points (its exact curves; Rinder sec. 2.2.1: the meshline crosses O1O2 away
    # from C where a tip touches the mate's root), by lobe part and place within the input's resolution. Before: the
    # female as 80 points a lobe lost "female tip on the male root" (13 of the 88 inputs at 80 a lobe): a piece's side
    # of O1O2 was taken beyond three times MESHLINE_GAIN its accuracy (0.5-0.6 mm), and the meshline leaves O1O2 by
    # 0.39-0.48 mm there before it turns back (the design's and the points' alike; rotorcad.meshing.slipping)
    design, given = _given(name, side, per_lobe, sigma, seed, phase)
    assert Counter(d["flank_role"] for d in _slips(given)) == Counter(d["flank_role"] for d in _slips(design))
    reach = resolution(given["defect_accuracy"], design["center_distance"])
    for d in _slips(design):
        assert min(np.hypot(g["x"] - d["x"], g["y"] - d["y"]) for g in _slips(given)) <= reach, (d, _slips(given))


# (sample, rotor, points a lobe, scatter mm, seed): the inputs whose flank ran on contact their accuracy does not
# decide (150 a lobe: Krigar's male exact and with 2 um, the Lysholm female exact, where the designs' flanks have no
# working part) and those that lose a short working part of the design to it (80 a lobe: the narrow-tip's sealing
# flank, 2.9 mm of female flank for 12.2 mm of meshline; the asymmetric SRM's short straight sealing part)
UNDECIDED_RUNNING = [
    ("krigar_4_6", "male", 150, 0.0, 0),
    ("krigar_4_6", "male", 150, 2e-3, 1),
    ("lysholm_4_6", "female", 150, 0.0, 0),
    ("narrow_tip_5_6", "female", 80, 0.0, 0),
    ("srm_asymmetric_5_6", "female", 80, 0.0, 0),
]


@pytest.mark.parametrize(("name", "side", "per_lobe", "sigma", "seed"), UNDECIDED_RUNNING)
def test_running_verdict_is_the_designs_or_undecided(name, side, per_lobe, sigma, seed):
    # reference: the design's running verdict per flank (Rinder sec. 1.2: Krigar's flanks touch nowhere with a common
    # tangent; Lysholm's sealing flank needs timing gears; the narrow-tip and asymmetric SRM sealing flanks run over a
    # small region). A given flank may not say the opposite of the design with running_decided true: where its working
    # part is only contact the input does not tell from a tip corner's path (rotorcad.meshing.contact_ratios.
    # resolved_steps: a transverse ratio of 0 +- 0.17-0.31 here), it is not shown to run and says undecided. Before:
    # Krigar's male at 150 a lobe ran on its driving (exact) or sealing (2 um) flank, the Lysholm female's sealing
    # flank ran, with working lengths 5.5-11.4 mm the design has not
    design, given = _given(name, side, per_lobe, sigma, seed)
    for flank in FLANKS:
        want = design["flanks"][flank]
        got = given["flanks"][flank]
        if got["running_decided"]:
            assert got["runs_without_timing_gears"] == want["runs_without_timing_gears"], flank
        else:
            assert not got["runs_without_timing_gears"], flank
            assert got["transverse_contact_ratio"] <= got["transverse_contact_ratio_accuracy"], flank
            assert any("undecided" in r for r in given["running_reasons"]), given["running_reasons"]
    # the undecided flank's design verdict lies within what the input leaves open: at least one flank here was undecided
    assert not all(given["flanks"][f]["running_decided"] for f in FLANKS)
    assert all(design["flanks"][f]["running_decided"] for f in FLANKS)  # a design decides its own verdict


# ---- tip corners sparse points cannot decide: a corner, or a rounding shorter than two point spacings ------------


def _segment_length(name: str, side: str, segment: str) -> float:
    """Profile length (mm) of a design's named lobe segment, from its own curve (0.01 um chord)."""
    spec = pair_spec(rotor_design(tomllib.loads((SAMPLES / f"{name}.toml").read_text()), SAMPLES))
    rotors = build_pair(spec)
    lobe = rotors.male_lobe() if side == "male" else rotors.female_lobe()
    (seg,) = [g for g in lobe.segments if g.name == segment]
    return float(np.hypot(*np.diff(seg.resampled(1e-5).points, axis=0).T).sum())


def _keys(rows: list[dict]) -> Counter:
    return Counter((d["kind"], d["rotor"], d["flank_role"], d["tip_corner"]) for d in rows)


# (sample, rotor given, points a lobe, scatter mm, seed, the design's tip rounding (rotor, segment)): the N rack's and
# Rinder-Deix's male sealing tip circle (a 0.67 mm rounding, 1-2 points at 80-150 a lobe) is read as a corner; the
# rack-involute female's driving tip rounding (2.64 mm, 2.5 spacings at 80 a lobe) and the N rack female's sealing tip
# circle (4.04 mm, 5 spacings) are longer than two spacings: three points fix their circle, and they are read as
# roundings (rotorcad.measured.fit._long_roundings)
ROUNDINGS = [
    ("n_rack_5_6", "male", 80, 0.0, 0, ("male", "sealing tip circle")),
    ("n_rack_5_6", "male", 150, 2e-3, 1, ("male", "sealing tip circle")),
    ("rinder_deix_5_6", "male", 80, 1e-3, 2, ("male", "sealing tip circle")),
    ("rack_involute_5_6", "female", 80, 0.0, 0, ("female", "driving tip rounding")),
    ("rack_involute_5_6", "female", 80, 1e-3, 2, ("female", "driving tip rounding")),
    ("n_rack_5_6", "female", 80, 0.0, 0, ("female", "sealing tip circle")),
    ("n_rack_5_6", "female", 80, 1e-3, 1, ("female", "sealing tip circle")),
]


@pytest.mark.parametrize(("name", "side", "per_lobe", "sigma", "seed", "rounding"), ROUNDINGS)
def test_a_rounding_reads_as_a_corner_only_below_two_spacings(name, side, per_lobe, sigma, seed, rounding):
    # reference: the design's defects (its exact curves: no cusp at a rounding) and the length of the design's rounding
    # segment (its own curve) against two spacings of the points (three points are the fewest that fix a circle:
    # rotorcad.meshing.undecided). A shorter rounding reads as a tip corner, undecided, that the design's margin allows;
    # a longer one as the design's rounding: no tip corner of that rotor, and what differs from the design's defects
    # is undecided and allowed. Before: the N-rack and Rinder-Deix males at 80 and 150 a lobe (20 of the 178 inputs)
    # reported a male tip corner's path, decided, that the design has not; the rack-involute female at 80 a lobe (exact
    # and 1 um) and the N-rack female with 1 um (seed 1) a female tip corner there, its design's margin 1.4-5.3 mm for
    # a spacing of 0.8-1.06 mm, and the N-rack female as 80 exact points a lobe was refused (5 % of its lobe without a
    # rack point): each of its tip circles' 22 deg vertex turns made two a corner of 44 deg
    spec, analysis, design, _ = _design_pair(name)
    points = _points(name, side, per_lobe, sigma, seed)
    spacing = float(np.median(np.hypot(*np.diff(points, axis=0).T)))
    given = points_summary(PairSpec(spec.pair, f"{side}-points", {}, points, None, spec.speed_rpm, 0.0), f"--{side}-points")
    corner = [d for d in given["defects"] if d["tip_corner"] and d["rotor"] == rounding[0] and d["point_generated"]]
    extra = _keys(given["defects"]) - _keys(design["defects"])
    assert all(d["decided"] for d in design["defects"]) and design["undecided_defects"] == []
    differing, explained = compare_defects(analysis, given)
    assert differing == [], (differing, explained, _segment_length(name, *rounding), spacing)
    assert {k for k, *_ in explained} == set(extra)
    if _segment_length(name, *rounding) >= 2.0 * spacing:
        assert corner == [], corner
        assert not [k for k in extra if k[1] == rounding[0]], extra
    else:
        assert extra and all(k[1] == rounding[0] and k[3] for k in extra), extra  # a tip corner the design has not
        assert corner and all(not d["decided"] and d["margin_accuracy"] == pytest.approx(spacing, rel=1e-6) for d in corner)


@pytest.mark.parametrize("sides", [4, 6, 8])
def test_a_rounding_longer_than_two_spacings_is_no_corner_of_the_fit(sides):
    # reference: closed form, made without rotorcad: a regular polygon (circumradius 20 mm, turning 2 pi / sides at
    # each corner) whose corners shapely's opening rounds with radius rho (each rounding rho 2 pi / sides long),
    # scanned at 1 mm at ten phases of the spacing. A rounding 2.5-4 spacings long holds three points or more: no corner
    # of the fit (rotorcad.measured.fit._long_roundings); a sharp corner and roundings up to 1.9 spacings hold two at
    # most and stay the corners outline.corners finds (a corner between two points and such a rounding are one input)
    from rotorcad.measured.fit import _long_roundings
    from rotorcad.measured.outline import corners

    turn = 2.0 * np.pi / sides
    polygon = shapely.Polygon(20.0 * np.column_stack([np.cos(np.arange(sides) * turn), np.sin(np.arange(sides) * turn)]))
    for length in (0.0, 1.0, 1.5, 1.9, 2.5, 3.0, 4.0):  # the rounding's length in spacings
        rho = length / turn
        shape = polygon.buffer(-rho, quad_segs=256).buffer(rho, quad_segs=256) if rho else polygon
        ring = np.asarray(shape.exterior.coords)[:-1]
        ring = ring if shapely.LinearRing(ring).is_ccw else ring[::-1]
        for phase in np.linspace(0.0, 1.0, 10, endpoint=False):
            points = scan(ring, round(shape.exterior.length), phase)
            edges, at = corners(points, 0.0, 30.0)
            kept, _ = _long_roundings(points, edges, at, 0.0)
            if length <= 1.9:
                assert len(edges) == sides and len(kept) == sides, (length, phase, len(edges), len(kept))
            else:
                assert len(kept) == 0, (length, phase, len(edges), len(kept))


# (sample, rotor given, points a lobe, scatter mm, seed): inputs that lose a tip corner's path of the design (the mate's
# corner, generated from the points, comes out rounded by 0.1-0.4 mm)
LOST_CORNERS = [
    ("srm_symmetric_4_6", "male", 80, 1e-3, 1),
    ("srm_symmetric_4_6", "female", 80, 0.0, 0),
    ("srm_asymmetric_5_6", "male", 150, 2e-3, 1),
]


@pytest.mark.parametrize(("name", "side", "per_lobe", "sigma", "seed"), LOST_CORNERS)
def test_a_lost_tip_corner_is_reported_undecided(name, side, per_lobe, sigma, seed):
    # reference: the design's defects (its exact curves): the female tip corner's path on the male root (Rinder sec.
    # 2.2.2: at a tip only a corner generates) on both flanks of the symmetric SRM, on the driving flank of the asymmetric
    # one. Before: the points lost it (13 of the 88 inputs at 80 a lobe, 1 of 90 at 150), decided. Now the place where the
    # female's contacts stand within a point spacing over the path's meshline is reported undecided, and the decided
    # defects are the design's
    _, analysis, design, _ = _design_pair(name)
    _, given = _given(name, side, per_lobe, sigma, seed)
    lost = _keys(design["defects"]) - _keys(given["defects"])
    assert lost and all(k[0] == "cusp" and k[3] for k in lost), lost
    assert not _keys(given["defects"]) - _keys(design["defects"]) - _keys([d for d in given["defects"] if not d["decided"]])
    assert set(lost) <= set(_keys(given["undecided_defects"]))
    for d in given["undecided_defects"]:
        assert not d["decided"] and d["margin"] <= d["margin_accuracy"], d
    assert max(_keys(given["undecided_defects"]).values(), default=0) == 1, given["undecided_defects"]  # each once
    differing, explained = compare_defects(analysis, given)
    assert differing == [] and {k for k, *_ in explained} >= set(lost), (differing, explained)


@pytest.mark.parametrize("per_lobe", [300, 600])
def test_a_rounding_the_points_resolve_is_no_undecided_corner(per_lobe):
    # issue 21 (a new user's session): the N-rack female from 300 and 600 points a lobe with 2 um listed the male's
    # sealing tip rounding twice in undecided_defects, once on the rounding and once at the tip's middle (a slip
    # singularity: the male's contact stands still as the meshline crosses O1O2). Reference: the design's own rounding,
    # its "sealing tip circle" segment (0.67 mm of profile, from its exact curve), is longer than two of the points'
    # spacings (0.21 and 0.11 mm): three points or more fix its circle (rotorcad.meshing.undecided), so the points
    # decide it, and the design has no tip-corner cusp there
    spec, _, design, _ = _design_pair("n_rack_5_6")
    points = _points("n_rack_5_6", "female", per_lobe, 2e-3, 1)
    rotors = build_pair(PairSpec(spec.pair, "female-points", {}, points, None, spec.speed_rpm, 0.0), label="--female-points")
    given = analyse_pair(rotors, spec.speed_rpm)[1]
    assert _segment_length("n_rack_5_6", "male", "sealing tip circle") >= 2.0 * rotors.point_spacing
    assert not any(d["tip_corner"] for d in design["defects"])
    assert given["undecided_defects"] == [], given["undecided_defects"]
    assert not any(d["tip_corner"] for d in given["defects"]), given["defects"]


def _dented(name: str, per_lobe: int, sigma: float, depth: float = 20e-3, width: float = 2.0) -> dict:
    """The summary of :func:`_dented_analysis`."""
    return _dented_analysis(name, per_lobe, sigma, depth, width)[1]


@functools.cache
def _dented_analysis(name: str, per_lobe: int, sigma: float, depth: float = 20e-3, width: float = 2.0) -> tuple:
    """The analysis and summary of the male as ``per_lobe`` exact points a lobe with each lobe's sealing flank dented
    by ``depth`` mm over ``width`` mm (a cos² bump along the normal at mid-depth of the flank), plus ``sigma`` mm of
    scatter (seed 1)."""
    spec, _, outlines = _design(name)
    lobe, teeth = outlines["male"]
    points = scan(patterned(lobe, teeth), per_lobe * teeth, PHASE)
    d = np.roll(points, -1, axis=0) - np.roll(points, 1, axis=0)
    normal = np.column_stack([d[:, 1], -d[:, 0]]) / np.hypot(d[:, 0], d[:, 1])[:, None]
    s = np.concatenate([[0.0], np.cumsum(np.hypot(*np.diff(points, axis=0).T))])
    r = np.hypot(*points.T)
    mid = 0.5 * (r.min() + r.max())
    k = np.flatnonzero((r[:-1] - mid) * (r[1:] - mid) < 0)[1]  # the first lobe's second flank at mid-depth
    for j in range(teeth):  # every lobe alike (a ground flank)
        u = (s - s[k] - j * s[-1] / teeth) / width
        points = points + (depth * np.where(np.abs(u) < 0.5, np.cos(np.pi * u) ** 2, 0.0))[:, None] * normal
    if sigma:
        points = points + np.random.default_rng(1).normal(0.0, sigma, len(points))[:, None] * normal
    rotors = build_pair(PairSpec(spec.pair, "male-points", {}, points, None, spec.speed_rpm, 0.0), label="--male-points")
    return analyse_pair(rotors, spec.speed_rpm)


def test_dented_flank_keeps_its_defect():
    # an independent modification: the rack-involute male's sealing flank dented by 20 um over 2 mm on every lobe; as
    # 500 exact points a lobe (0.14 um) the female generated from it reverses (cusps on the female inside the sealing
    # working part) and the sealing flank does not run, as 2000 points a lobe read it too; the undented male's points
    # run on both flanks (the design's verdict). The changes of this file's fixes (the slipping side, the undecided
    # working part) must not hide it
    _, design, _ = _design("rack_involute_5_6")
    assert design["flanks"]["sealing"]["runs_without_timing_gears"]
    given = _dented("rack_involute_5_6", 500, 0.0)
    cusps = [d for d in given["defects"] if d["kind"] == "cusp" and not d["tip_corner"]]
    assert cusps and {d["flank_role"] for d in cusps} == {"sealing"}, given["defects"]
    assert not given["flanks"]["sealing"]["runs_without_timing_gears"]
    assert given["flanks"]["sealing"]["running_decided"]


@pytest.mark.parametrize(("per_lobe", "sigma"), [(300, 0.0), (2000, 1e-3), (2000, 2e-3)])
def test_dented_flank_keeps_its_defect_from_scattered_points(per_lobe, sigma):
    # the same dented male where the normal's test cannot resolve the dent: 300 exact points a lobe (meshline resolution
    # 1.9 mm) and 2000 a lobe with 1 and 2 um of scatter (4.3 and 6.1 mm). The meshline runs back over the dent (its
    # normal swings through O2 and C in pairs 1.6-2.1 mm apart along it) and the miss's sign changes cancel within the
    # resolution; before, the sealing flank read "runs", decided. Reference: the independent modification itself (the
    # dent is 10-20 times the points' accuracy) and the 500-exact reading of the test above (the sealing flank does not
    # run). Read now from the male rotation, which turns back and on again along the meshline there by 15-19 mrad where
    # the points' accuracy allows 1.3-5.9 (rotorcad.meshing.rotation_turns): jamming inside the sealing working part
    given = _dented("rack_involute_5_6", per_lobe, sigma)
    sealing = given["flanks"]["sealing"]
    assert not sealing["runs_without_timing_gears"] and sealing["running_decided"], sealing
    assert {d["flank_role"] for d in given["defects"] if not d["tip_corner"] and d["kind"] != "slipping"} == {"sealing"}


@pytest.mark.parametrize("depth", [20e-3, 0.0])
def test_a_dent_below_the_accuracy_leaves_its_flank_undecided_where_it_lies(depth):
    # the same dented male as 300 points a lobe with 2 um of scatter: the rotation turns back by 4.9 mrad over the dent,
    # beyond what the tangent's tolerance alone (the design's test) allows and within the 10.0 the points' accuracy
    # allows, so the input can neither show nor rule out the jamming the 300 exact points read there. Before: "runs",
    # decided. Now undecided at
    # that place (an undecided_defects row, kind jamming), the sealing flank not shown to run. References: the
    # independent modification (where the dent lies: the jamming points of the same 300 points without scatter, within
    # the resolution at 2 um, 6.1 mm) and, for the control (depth 0), the design's verdict, decided
    given = _dented("rack_involute_5_6", 300, 2e-3, depth=depth)
    sealing = given["flanks"]["sealing"]
    possible = [d for d in given["undecided_defects"] if d["kind"] == "jamming"]
    if not depth:
        assert possible == [] and sealing["runs_without_timing_gears"] and sealing["running_decided"], (possible, sealing)
        return
    assert not sealing["runs_without_timing_gears"] and not sealing["running_decided"], sealing
    assert [d["flank_role"] for d in possible] == ["sealing"] and not possible[0]["decided"], possible
    exact = [(d["x"], d["y"]) for d in _dented("rack_involute_5_6", 300, 0.0)["defects"] if d["kind"] == "jamming"]
    assert min(np.hypot(possible[0]["x"] - x, possible[0]["y"] - y) for x, y in exact) < 6.1, (possible, exact)
    assert any("neither show nor rule out" in r for r in given["running_reasons"]), given["running_reasons"]


def test_the_pair_picture_shows_the_undecided_jamming_where_the_json_places_it():
    # issue 21: the pictures show the verdicts at the flank where they are. The dented male of the test above (300 a
    # lobe, 2 um): the pair picture marks the undecided jamming, hollow and labelled with its rotor and flank, at the
    # place `undecided_defects` gives, and writes the sealing flank's verdict as undecided. Reference: the JSON summary
    # (rotorcad rotor --json) of the same analysis
    from rotorcad.rotor_plotting import plot_pair, plot_sliding

    analysis, given = _dented_analysis("rack_involute_5_6", 300, 2e-3)
    (row,) = [d for d in given["undecided_defects"] if d["kind"] == "jamming"]
    ax = plot_pair(analysis).axes[0]
    notes = {t.get_text(): t.xy for t in ax.texts if hasattr(t, "xy")}
    where = notes["undecided jamming on the male, sealing flank"]
    assert np.hypot(where[0] - row["x"], where[1] - row["y"]) < 1e-9, (where, row)
    legend = [t.get_text() for t in ax.get_legend().get_texts()] if ax.get_legend() else []
    legend += [h.get_label() for h in ax.get_lines()]
    assert any(t.startswith("undecided jamming (1)") for t in legend), legend
    assert any(t.startswith("sealing flank: undecided at the input's accuracy") for t in notes), sorted(notes)
    # the sliding picture marks it too, at the angle and sliding velocity of the meshline contact nearest its place
    # (reference: the same analysis' kinematics, the arrays rotor --json's sliding figures come from)
    ax1 = plot_sliding(analysis).axes[0]
    marked = {t.get_text(): t.xy for t in ax1.texts if hasattr(t, "xy")}
    i = int(np.argmin(np.hypot(*(analysis.meshline - (row["x"], row["y"])).T)))
    expected = (analysis.kinematics["angle_deg"][i], abs(analysis.kinematics["sliding"][i]))
    assert np.allclose(marked["undecided jamming on the male, sealing flank"], expected), (marked, expected)


@pytest.mark.parametrize("sigma", [1e-3, 2e-3])
def test_undented_flank_from_scattered_points_runs(sigma):
    # the control of the test above: the same male undented, as the same 2000 points a lobe with the same scatter, reads
    # the design's defects (kind, rotor, lobe part, tip corner) and both flanks run, decided: the rotation's accuracy
    # (rotorcad.meshing.rotation_turns) holds the scatter's turns back of the rotation, and no jamming is read from
    # them. Reference: the design's own analysis (its exact curves)
    _, design, _ = _design("rack_involute_5_6")
    given = _dented("rack_involute_5_6", 2000, sigma, depth=0.0)
    keys = [Counter((d["kind"], d["rotor"], d["flank_role"], d["tip_corner"]) for d in s["defects"]) for s in (given, design)]
    assert keys[0] == keys[1], given["defects"]
    for flank in ("driving", "sealing"):
        assert given["flanks"][flank]["runs_without_timing_gears"] == design["flanks"][flank]["runs_without_timing_gears"]
        assert given["flanks"][flank]["running_decided"]

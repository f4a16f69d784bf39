"""Points that deviate from the outline in a pattern, not at random, are judged to that deviation (issue 21 item 3).

New-user finding 2: 2000 points a lobe resampled evenly along rotorcad's own 1 µm chord CSV lie on the
CSV's chords, up to their sagitta (about 1 µm) inside the outline, in a pattern that repeats at the
chords' length. Neighbour to neighbour they show no scatter and no sagitta, and they were judged as
exact (0.04-0.1 µm): the narrow-tip male read a blow-hole of 1.867 +- 0.0001 mm² against the design's
2.778, meshlines of 47.6 / 180.4 mm against 21.9 / 63.3 and 4 points of infinite slip against 1.

Reference: the design's own verdicts from its exact curves (the same sample built by rotorcad, whose
geometry is checked elsewhere), and for the accuracy the points' distance from the design's outline
at a 0.01 µm chord, measured with shapely (an independent method). The inputs are built here from
the samples' designs.
"""

from __future__ import annotations

import functools
import re
import tomllib
import warnings
from collections import Counter
from pathlib import Path

import numpy as np
import pytest
import shapely
from independent_pairs import scan

from exports.csv_points import read_points, write_points
from rotorcad.design import rotor_design
from rotorcad.errors import DesignError, InputNote
from rotorcad.rotor_build import PairSpec, analyse_pair, build_pair, pair_spec

SAMPLES = Path(__file__).resolve().parents[1] / "samples"
POLYGON_SAMPLES = ("narrow_tip_5_6", "srm_asymmetric_5_6", "rack_involute_5_6")
PER_LOBE = 2000  # the finding's resampling of the 1 µm chord CSV
PHASE = 0.37  # where the first point falls, in spacings past the outline's first point


def _exterior(polygon: shapely.Polygon) -> np.ndarray:
    pts = np.asarray(polygon.exterior.coords)[:-1]
    area = 0.5 * np.sum(pts[:, 0] * np.roll(pts[:, 1], -1) - np.roll(pts[:, 0], -1) * pts[:, 1])
    return pts if area > 0 else pts[::-1]


def _given(spec: PairSpec, data: np.ndarray) -> dict:
    rotors = build_pair(PairSpec(spec.pair, "male-points", {}, data, None, spec.speed_rpm, 0.0), label="--male-points")
    return analyse_pair(rotors, spec.speed_rpm)[1]


@pytest.fixture(scope="module")
def polygon_forms(tmp_path_factory) -> dict:
    """Per sample: the design's summary, the summary of 2000 points a lobe on its own CSV's chords, and
    those points' largest distance from the exact outline (mm)."""
    folder = tmp_path_factory.mktemp("polygon")
    out = {}
    for name in POLYGON_SAMPLES:
        spec = pair_spec(rotor_design(tomllib.loads((SAMPLES / f"{name}.toml").read_text()), SAMPLES))
        rotors = build_pair(spec)
        analysis, design = analyse_pair(rotors, spec.speed_rpm)
        csv = folder / f"{name}.csv"
        write_points(csv, _exterior(analysis.sections[0]))  # what `rotor --male-csv` writes: a 1 µm chord
        on_chords = scan(read_points(csv, "--male-points"), PER_LOBE * spec.pair.male_teeth, PHASE)
        lobe = np.vstack([seg.resampled(1e-5).points for seg in rotors.male_lobe().segments])  # exact, 0.01 µm chord
        turns = 2 * np.pi * np.arange(spec.pair.male_teeth) / spec.pair.male_teeth
        exact = shapely.MultiLineString([lobe @ np.array([[np.cos(t), np.sin(t)], [-np.sin(t), np.cos(t)]]) for t in turns])
        off = float(shapely.distance(shapely.points(on_chords), exact).max())
        out[name] = (design, _given(spec, on_chords), off)
    return out


def _key(d: dict) -> tuple:
    return d["kind"], d["rotor"], d["flank_role"], d["point_generated"]


@pytest.mark.parametrize("name", POLYGON_SAMPLES)
def test_points_on_chords_judged_to_the_chords_sagitta(polygon_forms, name):
    # reference: the points' largest distance from the exact outline (shapely); before: 0.04-0.10 um,
    # 10-25 times below it
    _, given, off = polygon_forms[name]
    assert 0.5 * off <= given["defect_accuracy"] <= 2.0 * off, (given["defect_accuracy"], off)


@pytest.mark.parametrize("name", POLYGON_SAMPLES)
def test_points_on_chords_give_the_design_verdicts(polygon_forms, name):
    # reference: the design's defects (kind, rotor, flank role, point-generated) and running verdicts per flank
    design, given, _ = polygon_forms[name]
    assert Counter(map(_key, given["defects"])) == Counter(map(_key, design["defects"]))
    for flank, report in design["flanks"].items():
        assert given["flanks"][flank]["runs_without_timing_gears"] == report["runs_without_timing_gears"], flank


@pytest.mark.parametrize("name", POLYGON_SAMPLES)
def test_points_on_chords_blow_hole_within_stated_uncertainty(polygon_forms, name):
    # reference: the design's blow-hole from its exact curves; the stated uncertainty bounds the error
    # and stays below the area (the input resolves the blow-hole). Before: the narrow-tip 1.867 +- 0.0001
    # against 2.778 mm²
    design, given, _ = polygon_forms[name]
    gap = abs(given["blow_hole_area"] - design["blow_hole_area"])
    assert gap <= given["blow_hole_uncertainty"] + 0.01 * design["blow_hole_area"], (gap, given["blow_hole_uncertainty"])
    assert given["blow_hole_uncertainty"] < design["blow_hole_area"]
    assert given["blow_hole_resolved"]


@pytest.mark.parametrize("name", POLYGON_SAMPLES)
def test_points_on_chords_meshline_lengths(polygon_forms, name):
    # reference: the design's meshline per flank (before, narrow-tip: 47.6 / 180.4 mm against 21.9 / 63.3)
    design, given, _ = polygon_forms[name]
    for flank, report in design["flanks"].items():
        assert given["flanks"][flank]["meshline_length"] == pytest.approx(report["meshline_length"], rel=0.06), flank


# ---- findings 6 and 15: 1-2 um of scatter, and --smoothing near its default ----------------------
# (name, points a lobe, scatter mm, smoothing mm² or None): the findings' inputs, built from the designs.
# Before: the symmetric SRM "does not run" (driving: cusp on the female), the narrow-tip at 80 a lobe and
# at --smoothing 0.001 / 0.01 "does not run" (sealing: cusp on the female), the Lysholm's meshline open
SCATTERED = [
    ("srm_symmetric_4_6", 300, 1e-3, None),
    ("narrow_tip_5_6", 80, 2e-3, None),
    ("lysholm_4_6", 300, 1e-3, None),
    ("narrow_tip_5_6", 300, 1e-3, 1e-3),
    ("narrow_tip_5_6", 300, 1e-3, 1e-2),
]


@functools.cache
def _design(name: str) -> tuple[PairSpec, dict, np.ndarray]:
    spec = pair_spec(rotor_design(tomllib.loads((SAMPLES / f"{name}.toml").read_text()), SAMPLES))
    analysis, design = analyse_pair(build_pair(spec), spec.speed_rpm)
    return spec, design, _exterior(analysis.sections[0])


def _scattered(name: str, per_lobe: int, sigma: float, smoothing: float | None) -> tuple[dict, dict]:
    return _scattered_noted(name, per_lobe, sigma, smoothing)[:2]


@functools.cache
def _scattered_noted(name: str, per_lobe: int, sigma: float, smoothing: float | None) -> tuple[dict, dict, tuple[str, ...]]:
    """The design's and the scattered points' summaries, and the input notes the build said (built once a case:
    test_smoothing_that_follows_the_scatter_is_refused reads a case of SCATTERED again)."""
    spec, design, male = _design(name)
    points = scan(male, per_lobe * spec.pair.male_teeth, PHASE)
    points = points + np.random.default_rng(0).normal(0.0, sigma, points.shape)  # a CMM's scatter, seed 0
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always", InputNote)
        rotors = build_pair(PairSpec(spec.pair, "male-points", {}, points, smoothing, spec.speed_rpm, 0.0), label="--male-points")
        given = analyse_pair(rotors, spec.speed_rpm)[1]
    return design, given, tuple(str(w.message) for w in caught if issubclass(w.category, InputNote))


@pytest.mark.parametrize(("name", "per_lobe", "sigma", "smoothing"), SCATTERED)
def test_scatter_keeps_the_design_verdicts(name, per_lobe, sigma, smoothing):
    # reference: the design's running verdict per flank, its closed or open meshline and its blow-hole
    # (from its exact curves); the blow-hole within the stated uncertainty, which stays below the female
    # flute's area (a bound that says something)
    design, given = _scattered(name, per_lobe, sigma, smoothing)
    for flank, report in design["flanks"].items():
        assert given["flanks"][flank]["runs_without_timing_gears"] == report["runs_without_timing_gears"], flank
    assert given["runs_without_timing_gears"] == design["runs_without_timing_gears"]
    assert given["meshline_closed"] == design["meshline_closed"]
    gap = abs(given["blow_hole_area"] - design["blow_hole_area"])
    assert gap <= given["blow_hole_uncertainty"] + 0.01 * design["blow_hole_area"], (gap, given["blow_hole_uncertainty"])
    assert given["blow_hole_uncertainty"] < 0.05 * design["female_flute_area"]


def test_smoothing_that_follows_the_scatter_is_refused():
    # finding 15 and issue 21 item 3: a smoothing that lets the fit follow the scatter (below a lobe's n sigma^2)
    # read numbers of the noise (the finding's points: 0.000 +- 0.16 mm² at 0 and 1e-5 mm², design 2.778; the
    # N rack's male from 1 um female points a sealing tip corner it has not at 8e-5 and 1.5e-4), with only a
    # note: now refused, naming the smoothing and the least that works. Reference: the scatter put in here,
    # 1 um: 300 points x (1 um)^2 = 3e-4 mm²
    with pytest.raises(DesignError, match="at least") as refusal:
        _scattered("narrow_tip_5_6", 300, 1e-3, 1e-5)
    assert refusal.value.param == "smoothing" and refusal.value.value == 1e-5
    least = float(re.search(r"at least ([0-9.e+-]+) mm\^2", refusal.value.sentence()).group(1))
    assert least == pytest.approx(300 * 1e-3**2, rel=0.3)
    assert _scattered_noted("narrow_tip_5_6", 300, 1e-3, 1e-3)[2] == ()  # a smoothing above it: taken as given, no note

"""The blow-hole's apex from the straight line that generates the flank beside a tip corner (issue 21 item 3).

References: the design's apex and meshline from its exact curves by the envelope engine
(:class:`rotorcad.meshing.MeshingAnalysis`), which the closed forms of
:mod:`rotorcad.meshing.generating_line` do not use; the foot of the perpendicular from C on a line
(Rinder, *Sonderverzahnungen für Schraubenverdichterrotoren*, sec. 2.1: the contact's normal passes
through the pitch point) checked by hand on a rack's line.
"""

from __future__ import annotations

import tomllib
from pathlib import Path

import numpy as np
import pytest

from rotorcad.design import rotor_design
from rotorcad.meshing import MeshingAnalysis
from rotorcad.meshing.generating_line import body_frames, fit_line, line_apex, line_meshline_cut
from rotorcad.rotor_build import PairSpec, build_pair, pair_spec

SAMPLES = Path(__file__).resolve().parents[1] / "samples"
# the sample, the body whose straight line generates the male's sealing flank (the samples' segment names:
# "envelope of the straight female flank"; the rack-involute's flank an involute of the rack's line)
LINES = {"narrow_tip_5_6": "female", "srm_asymmetric_5_6": "female", "srm_b_5_6": "female", "rack_involute_5_6": "rack"}


@pytest.fixture(scope="module")
def designs() -> dict:
    out = {}
    for name in LINES:
        spec = pair_spec(rotor_design(tomllib.loads((SAMPLES / f"{name}.toml").read_text()), SAMPLES))
        out[name] = (spec, MeshingAnalysis(build_pair(spec), spec.speed_rpm))
    return out


def _flank(analysis: MeshingAnalysis):
    """The design's flank piece that starts at its apex (the tip corner's hand-over)."""
    e = analysis.meshline_end
    return next(p for p in analysis.pieces if p.kind.name == "CURVE" and len(p.points) and np.hypot(*(p.points[0] - e)) < 1e-9)


@pytest.mark.parametrize("name", LINES)
def test_design_flank_is_a_line_of_its_body(designs, name):
    # reference: the envelope engine's contacts of the design's sealing flank lie on a straight line in the
    # frame of the body the sample's construction names (and on none of the other two), to 1e-9 mm
    spec, analysis = designs[name]
    flank = _flank(analysis)
    pair = spec.pair
    frames = body_frames(flank.points, flank.t, pair.male_pitch_radius, 1.0 / pair.ratio, pair.center_distance)
    worst = {body: float(np.abs(fit_line(mapped)[2]).max()) for body, (mapped, _) in frames.items()}
    assert worst[LINES[name]] < 1e-9, worst
    assert min(v for k, v in worst.items() if k != LINES[name]) > 1e-3, worst


@pytest.mark.parametrize("name", LINES)
def test_line_meshline_cut_is_the_design_apex(designs, name):
    # reference: the design's apex (the envelope engine's hand-over of the male tip corner's path to the flank,
    # on the male tip circle); the closed-form meshline of the flank's generating line, cut with that circle,
    # must give it to 1e-7 mm
    spec, analysis = designs[name]
    flank, pair = _flank(analysis), spec.pair
    mapped, centre = body_frames(flank.points, flank.t, pair.male_pitch_radius, 1.0 / pair.ratio, pair.center_distance)[
        LINES[name]
    ]
    centroid, normal, _ = fit_line(mapped)
    distance = None if centre is None else abs(float(centroid @ normal))
    c = np.array([pair.male_pitch_radius, 0.0])
    apex = line_meshline_cut(distance, normal, centre, c, (np.zeros(2), pair.male_tip_radius), flank.points[0])
    assert np.hypot(*(apex - analysis.meshline_end)) < 1e-7


def test_rack_line_meshline_by_hand():
    # a rack line's meshline is the line through C along its normal (Rinder sec. 2.1): C = (3, 0), normal at
    # 45 deg, circle of radius 5 about the origin: (3 + l/sqrt2)^2 + (l/sqrt2)^2 = 25, l^2 + 3 sqrt2 l - 16 = 0,
    # l = (-3 sqrt2 + sqrt(18 + 64)) / 2
    normal = np.array([1.0, 1.0]) / np.sqrt(2.0)
    apex = line_meshline_cut(None, normal, None, np.array([3.0, 0.0]), (np.zeros(2), 5.0), np.array([4.0, 3.0]))
    lam = (-3.0 * np.sqrt(2.0) + np.sqrt(82.0)) / 2.0
    assert apex == pytest.approx([3.0 + lam / np.sqrt(2.0), lam / np.sqrt(2.0)], abs=1e-12)
    assert np.hypot(*apex) == pytest.approx(5.0, abs=1e-12)


def test_turning_line_meshline_by_hand():
    # a line at distance d from O, turning about O: its contact is the foot of the perpendicular from C, so
    # (M - C) is parallel to the line's normal u and (M - O) . u = d; checked at the cut found
    o, c, d = np.array([10.0, 0.0]), np.array([4.0, 0.0]), 2.5
    apex = line_meshline_cut(d, np.zeros(2), o, c, (np.zeros(2), 6.0), np.array([5.0, 3.0]))
    u = (apex - c) / np.hypot(*(apex - c))
    assert abs(float((apex - o) @ u)) == pytest.approx(d, abs=1e-9)
    assert np.hypot(*apex) == pytest.approx(6.0, abs=1e-9)


@pytest.mark.parametrize("name", LINES)
def test_scattered_flank_line_places_the_apex(designs, name):
    # reference: the design's blow-hole from its exact curves. The male's CSV points with 1 um of scatter (seed 3,
    # seed 0 in test_verdict_invariance): the line fitted to the flank's contacts in its body's frame places the
    # apex within 1 % of the design's area (before: the flank's end tangent, -9.8..+7.7 % over seeds 0-7)
    spec, analysis = designs[name]
    ring = np.asarray(analysis.sections[0].exterior.coords)[:-1]
    noisy = ring + np.random.default_rng(3).normal(0.0, 1e-3, ring.shape)
    given = MeshingAnalysis(build_pair(PairSpec(spec.pair, "male-points", {}, noisy, None, spec.speed_rpm, 0.0)), spec.speed_rpm)
    k = int(np.argmin(np.hypot(*(given.meshline - given.cusp).T)))
    tips = ((np.zeros(2), spec.pair.male_tip_radius), (np.array([spec.pair.center_distance, 0.0]), spec.pair.female_tip_radius))
    found = line_apex(given.pieces, given.meshline[k], tips, given.judged_accuracy, spec.pair)
    assert found is not None and found[1] == LINES[name]
    assert np.allclose(given.meshline_end, found[0])  # the apex the analysis states
    assert given.blow_hole_area == pytest.approx(analysis.blow_hole_area, rel=0.01)


@pytest.mark.parametrize("seed", [0, 1])
@pytest.mark.parametrize(("name", "side", "per_lobe"), [("narrow_tip_5_6", "female", 300), ("rack_involute_5_6", "male", 80)])
def test_scanned_points_place_the_apex(designs, name, side, per_lobe, seed):
    # reference: the design's blow-hole from its exact curves. Each rotor's lobe drawn to a 0.01 um chord, scanned
    # evenly round the rotor (the corners between the points, as a CMM scans) with 1 um of normal scatter: within 1 %.
    # Before (the flank's meshline extrapolated, or the joint): the narrow-tip female at 300 a lobe -7.6..-9.5 % over
    # seeds 0-3 (its flank's own straight line, in the female's frame, now), the rack-involute male at 80 a lobe
    # -3.9..+2.8 %
    import warnings

    from independent_pairs import patterned, scan

    from rotorcad.errors import InputNote

    spec, analysis = designs[name]
    rotors = analysis.rotors
    lobe = rotors.male_lobe() if side == "male" else rotors.female_lobe()
    teeth = spec.pair.male_teeth if side == "male" else spec.pair.female_teeth
    points = scan(patterned(np.vstack([seg.resampled(1e-5).points for seg in lobe.segments]), teeth), per_lobe * teeth, 0.37)
    points = points + np.random.default_rng(seed).normal(0.0, 1e-3, points.shape)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", InputNote)
        given = build_pair(PairSpec(spec.pair, f"{side}-points", {}, points, None, spec.speed_rpm, 0.0), label=f"--{side}-points")
    assert MeshingAnalysis(given, spec.speed_rpm).blow_hole_area == pytest.approx(analysis.blow_hole_area, rel=0.01)


@pytest.mark.parametrize("seed", [0, 1, 5, 6])
def test_sparse_points_cut_the_line_with_the_circle_of_the_apex(designs, seed):
    # reference: the design's blow-hole from its exact curves (its apex on the male tip circle). The SRM-B female
    # scanned at 80 exact points a lobe at a new user's phases (their seeds 0, 1, 5, 6): the female's straight flank
    # is found, but sparse points leave the female tip corner's path beside the flank's end, and its meshline was
    # cut with the female tip circle, 13 mm from the design's apex: 60.4 mm² for 3.14, said resolved, outside its
    # uncertainty (4 of 7 phases). The cut nearer the meshline's end is the apex: within 2 % and within the stated
    # uncertainty (Rinder sec. 2.2.2: the blow-hole ends where the contact line comes nearest the housing cusp).
    import warnings

    from independent_pairs import patterned, scan

    from rotorcad.errors import InputNote

    spec, analysis = designs["srm_b_5_6"]
    lobe = analysis.rotors.female_lobe()
    teeth = spec.pair.female_teeth
    phase = float(np.random.default_rng(seed).uniform(0.0, 1.0))
    points = scan(patterned(np.vstack([seg.resampled(1e-5).points for seg in lobe.segments]), teeth), 80 * teeth, phase)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", InputNote)
        given = build_pair(PairSpec(spec.pair, "female-points", {}, points, None, spec.speed_rpm, 0.0), label="--female-points")
    read = MeshingAnalysis(given, spec.speed_rpm)
    assert abs(read.blow_hole_area - analysis.blow_hole_area) <= max(0.02 * analysis.blow_hole_area, read.blow_hole_uncertainty)
    assert read.blow_hole_area == pytest.approx(analysis.blow_hole_area, rel=0.02)

"""The blow-hole read from points is unbiased and its stated uncertainty covers its error (issue 21 item 3).

Reference: the design's blow-hole from its exact curves (``MeshingAnalysis`` of the design: its apex, the
meshline's end nearest the housing cusp, is checked against closed forms in
tests/test_verdict_invariance.py::test_blow_hole_apex_moves_with_tangent_as_stated and
::test_n_rack_tip_round_meshline_from_points, its area by quadrature in
tests/test_families.py::test_spatial_blow_hole_lies_on_the_tips_and_the_cusp_and_its_area_is_independent).
The points are the design's outline (each rotor's lobe drawn to a 0.01 um chord, patterned round the rotor)
resampled evenly at 80, 300 and 500 points a lobe, the corners between the points (as a CMM scans,
tests/independent_pairs.py ``scan``), exact or with 1 or 2 um of normal scatter on each coordinate (seeds
0-2). Whenever ``blow_hole_resolved`` is true the error lies within ``blow_hole_uncertainty``; over the seeds
the mean error lies within the mean uncertainty over sqrt(n) (no bias beyond what the uncertainty allows).

``blow_hole_resolved`` is tested over every sample with a profile of its own, both rotors, 80-300 points a lobe,
exact and with 1-2 um, each at another sampling phase and datum angle (the points turned rigidly): whenever it is
true the design's blow-hole lies within ``blow_hole_uncertainty``.

Before (a new user's findings, newuser3 #5 and N3): the rack-involute male at 80 a lobe read -19 % exact
and -40 % with 1 um (5-6 times the stated uncertainty, resolved), the narrow-tip female with 1 um +34..+44 %
in every seed (300 a lobe, resolved), the asymmetric SRM's female +62..+84 %, the symmetric SRM's male at 80
a lobe with 1 um -29 % (resolved, 1.7 U).
"""

from __future__ import annotations

import functools
import tomllib
import warnings
from pathlib import Path

import numpy as np
import pytest
from independent_pairs import patterned, scan
from shared_runs import points_summary

from exports.dxf_profile import read_profile
from rotorcad.cli.main import main
from rotorcad.design import rotor_design
from rotorcad.errors import DesignError, InputNote
from rotorcad.rotor_build import PairSpec, analyse_pair, build_pair, pair_spec

SAMPLES = Path(__file__).resolve().parents[1] / "samples"
NAMES = ("narrow_tip_5_6", "rack_involute_5_6", "srm_asymmetric_5_6", "srm_symmetric_4_6")
FORMS = ((80, 0.0, (0,)), (300, 1.0, (0, 1, 2)), (500, 2.0, (0, 1, 2)))
"""(points a lobe, scatter um, seeds); 80 a lobe with 1 um in test_findings_resolved_within_a_few_percent."""
# srm_symmetric_4_6's female at 300 a lobe with 1 um read -12.1 % in every seed (each within its 11-12 mm²): the male
# generated from its points had its lobe arc's meshline bent towards the cusp where it meets the female tip corner's
# path, and that joint was the meshline's nearest point, until a male lobe arc's closed-form apex came before a
# hand-over on the female tip circle (MeshingAnalysis._apex): -0.5..0 %
KNOWN: dict[tuple[str, str, int, float], str] = {}
"""Known departures with their cause (strict xfails)."""
PHASE = 0.37  # where the first point falls, in spacings past the lobe's start


@functools.cache
def _design(name: str) -> dict:
    """The sample's spec, its design's blow-hole (the reference) and each rotor's lobe to a 0.01 um chord."""
    spec = pair_spec(rotor_design(tomllib.loads((SAMPLES / f"{name}.toml").read_text()), SAMPLES))
    rotors = build_pair(spec)
    out = {"spec": spec, "area": analyse_pair(rotors, spec.speed_rpm)[1]["blow_hole_area"]}
    for side, lobe in (("male", rotors.male_lobe()), ("female", rotors.female_lobe())):
        out[side] = np.vstack([seg.resampled(1e-5).points for seg in lobe.segments])
    return out


@functools.cache
def _read(
    name: str, side: str, per: int, scatter_um: float, seed: int, phase: float = PHASE, turn_deg: float = 0.0
) -> tuple[float, float, bool]:
    """The blow-hole (mm²), its stated uncertainty (mm²) and ``blow_hole_resolved`` of the rotor's points.

    The points start ``phase`` of a spacing past the lobe's start and are turned rigidly by ``turn_deg`` about the
    rotor's centre after the scatter (the datum angle of a measurement: which lobe faces the mate)."""
    design = _design(name)
    spec = design["spec"]
    teeth = spec.pair.male_teeth if side == "male" else spec.pair.female_teeth
    pts = scan(patterned(design[side], teeth), per * teeth, phase)
    if scatter_um:
        pts = pts + np.random.default_rng(seed).normal(0.0, scatter_um * 1e-3, pts.shape)
    if turn_deg:
        c, s = np.cos(np.radians(turn_deg)), np.sin(np.radians(turn_deg))
        pts = pts @ np.array([[c, s], [-s, c]])
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", InputNote)
        # built and analysed once in the run for these points (tests/test_moderate_densities.py and
        # tests/test_generating_line.py read some of the same): tests/shared_runs.py
        result = points_summary(PairSpec(spec.pair, f"{side}-points", {}, pts, None, spec.speed_rpm, 0.0), f"--{side}-points")
    return result["blow_hole_area"], result["blow_hole_uncertainty"], result["blow_hole_resolved"]


FEMALE_FORMS = {"narrow_tip_5_6": ((500, 1.0, (0, 1, 2)),)}
"""More forms of a female: newuser4's N3 (the narrow-tip female at 500 a lobe with 1 um, +34..+43 % in every seed)."""


def _cases() -> list:
    """Every sample's male in every form; the females at 80 and 300 a lobe (the symmetric SRM's at 300, the
    rack-involute female's pair takes 1.2 s to build: kept to those), with FEMALE_FORMS."""
    out = []
    for name in NAMES:
        females = [FORMS[1]] if name == "srm_symmetric_4_6" else [*FORMS[:2], *FEMALE_FORMS.get(name, ())]
        for side, forms in (("male", FORMS), ("female", females)):
            for per, scatter, seeds in forms:
                reason = KNOWN.get((name, side, per, scatter))
                marks = pytest.mark.xfail(strict=True, reason=reason) if reason else ()
                out.append(pytest.param(name, side, per, scatter, seeds, marks=marks, id=f"{name}-{side}-{per}-{scatter:g}um"))
    return out


@pytest.mark.parametrize(("name", "side", "per", "scatter_um", "seeds"), _cases())
def test_blow_hole_from_points_within_its_uncertainty_and_unbiased(name, side, per, scatter_um, seeds):
    reference = _design(name)["area"]
    reads = [_read(name, side, per, scatter_um, seed) for seed in seeds]
    for seed, (area, stated, resolved) in zip(seeds, reads, strict=True):
        assert stated > 0.0  # points always carry an accuracy
        if resolved:  # resolved: the error within the stated uncertainty
            assert abs(area - reference) <= stated, (seed, area, stated, reference)
    if len(seeds) > 1:  # no bias beyond what the stated uncertainty allows over n seeds
        error = np.mean([area - reference for area, _, _ in reads])
        assert abs(error) <= np.mean([stated for _, stated, _ in reads]) / np.sqrt(len(seeds)), (error, reads)


@pytest.mark.parametrize(
    ("name", "side", "per", "was"),
    [
        ("rack_involute_5_6", "male", 80, "-40 %, 5-6 U"),
        ("narrow_tip_5_6", "female", 300, "+34..+44 %"),
        ("srm_asymmetric_5_6", "female", 300, "+62..+84 %, 0.9-1.2 U"),
        ("srm_symmetric_4_6", "male", 80, "-29 %, 1.7 U"),
    ],
)
def test_findings_resolved_within_a_few_percent(name, side, per, was):
    # the findings' cases with 1 um of scatter (seeds 0-2), each resolved before with the error ``was``: now
    # within 12 % of the reference, the design's blow-hole (a few per cent each: the apex of a tip corner's
    # hand-over from the flank's meshline, the joint of the corner's path, or the turn, where local), and within
    # the stated uncertainty. Resolved where that is at most half the area (RESOLVED_SHARE): the narrow-tip and
    # asymmetric SRM females stated +-1.9-2.7 mm² on 2.5-3.3 (the hand-over's tangent, the other estimates' spread),
    # no figure, until their straight flank's line, which places the apex, stated its own bound (+-0.11-0.18)
    reference = _design(name)["area"]
    for seed in (0, 1, 2):
        area, stated, resolved = _read(name, side, per, 1.0, seed)
        assert resolved
        assert area == pytest.approx(reference, rel=0.12), (seed, area, was)
        assert abs(area - reference) <= stated


def test_sparse_exact_land_corner_within_one_percent():
    # the rack-involute male's exact points at 80 a lobe read -19.4 %: its tip land (3-4 points) extended as a
    # spline crossed the flank's 10 um off the tip circle and bent the flank's end tangent by 27 mrad. Reference:
    # the design's blow-hole, within 1 % (issue 21 item 3)
    area, _, resolved = _read("rack_involute_5_6", "male", 80, 0.0, 0)
    assert resolved
    assert area == pytest.approx(_design("rack_involute_5_6")["area"], rel=0.01)


@pytest.fixture(scope="module")
def exported(tmp_path_factory) -> Path:
    """The rack-involute sample's drawings as ``rotorcad export --format dxf`` writes them."""
    folder = tmp_path_factory.mktemp("export")
    args = ["export", str(SAMPLES / "rack_involute_5_6.toml"), "--format", "dxf", "--out", str(folder), "--no-housing"]
    assert main([*args, "--quiet"]) == 0
    return folder


@pytest.mark.parametrize("side", ["male", "female"])
def test_spline_drawing_states_an_uncertainty_that_covers_its_error(exported, side):
    # newuser4 N5: the export's spline layer read back stated +-0.000 mm² for a blow-hole 0.063 mm² off
    # (+0.28 %, the female). Reference: the design's blow-hole. The drawing's curves lie within their
    # accuracy of the outline, which places the hand-over on the meshline no better than sqrt(8 a e)
    design = _design("rack_involute_5_6")
    spec = design["spec"]
    path = next(exported.glob(f"*_{side}.dxf"))
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", InputNote)
        data = read_profile(path, f"--{side}-points", f"{side.upper()}_SPLINE")
        # made once in the run for this drawing (tests/test_dxf_exact.py reads the same): tests/shared_runs.py
        result = points_summary(PairSpec(spec.pair, f"{side}-points", {}, data, None, spec.speed_rpm, 0.0), f"--{side}-points")
    area, stated = result["blow_hole_area"], result["blow_hole_uncertainty"]
    assert 0.0 < stated < area  # non-zero, and still says something
    assert abs(area - design["area"]) <= stated
    assert area == pytest.approx(design["area"], rel=0.01)


SWEEP_NAMES = (
    "krigar_4_6",
    "lysholm_4_6",
    "n_rack_5_6",
    "narrow_tip_5_6",
    "rack_involute_5_6",
    "srm_asymmetric_5_6",
    "srm_b_5_6",
    "srm_symmetric_4_6",
)
"""Every sample with a profile of its own (rinder_deix_5_6 is the N rack's profile under other parameters' names)."""
SWEEP_FORMS = (
    (80, 0.0, 0, 0.0, 37.0),
    (80, 1.0, 5, 0.25, 24.0),
    (80, 2.0, 2, 0.71, 15.0),
    (150, 0.0, 0, 0.71, 15.0),
    (150, 1.0, 1, 0.37, 0.0),
    (300, 1.0, 1, 0.0, 37.0),
    (300, 2.0, 2, 0.37, 0.0),
)
"""(points a lobe, scatter um, seed, phase in spacings, datum turn in deg): sparse to moderate densities, each with
another sampling phase and datum angle (a new user's findings: the N rack's and SRM-B's males at 80 a lobe exact read
-38 % and +142..+296 % by where the points fell, the asymmetric SRM's male with 2 um +150..+206 % turned by 15-60 deg,
each said resolved and 1.4-4.7 times its uncertainty off)."""


def _sweep_read(name: str, side: str, form: tuple) -> tuple[float, float, bool] | None:
    """:func:`_read` of one form, None where the points are refused (one clear sentence: no verdict to check)."""
    try:
        return _read(name, side, *form)
    except DesignError:
        return None  # the N rack's female at 80 a lobe: 3-7 % of the lobe has no rack point


@pytest.mark.parametrize("side", ["male", "female"])
@pytest.mark.parametrize("name", SWEEP_NAMES)
def test_a_resolved_blow_hole_lies_within_its_uncertainty_at_any_phase_and_datum_angle(name, side):
    # reference: the design's blow-hole from its exact curves (_design). blow_hole_resolved says the area is a figure:
    # then the design's lies within blow_hole_uncertainty, whatever the density, scatter, sampling phase and datum angle
    reference = _design(name)["area"]
    for form in SWEEP_FORMS:
        read = _sweep_read(name, side, form)
        if read is None:
            continue
        area, stated, resolved = read
        assert stated > 0.0  # points always carry an accuracy
        if resolved:
            assert abs(area - reference) <= stated, (form, area, stated, reference)


def test_the_sweep_resolves_blow_holes_at_every_density():
    # the rule is not empty: at each density some of the sweep's blow-holes are resolved (the bound above is no
    # statement on an input that resolves nothing). Counted over test_a_resolved_blow_hole_lies_within_...'s reads
    for per in sorted({form[0] for form in SWEEP_FORMS}):
        reads = [_sweep_read(n, s, f) for n in SWEEP_NAMES for s in ("male", "female") for f in SWEEP_FORMS if f[0] == per]
        resolved = [r for r in reads if r is not None and r[2]]
        assert len(resolved) >= 0.25 * len(reads), (per, len(resolved), len(reads))


def test_the_datum_angle_does_not_move_the_blow_hole():
    # newuser6: the asymmetric SRM male at 80 points a lobe with 2 um of scatter, turned rigidly by 0-10, 15-27 and
    # 36-60 deg, read 2.96, 7.87 and 9.61 mm² (design 3.14), all resolved. A rigid turn of the same points (the same
    # lobe faces the mate up to half a pitch, 36 deg) changes nothing of the profile (reference: the unturned read);
    # and the design's blow-hole lies within the stated uncertainty
    reference = _design("srm_asymmetric_5_6")["area"]
    reads = [_read("srm_asymmetric_5_6", "male", 80, 2.0, 31, PHASE, turn) for turn in (0.0, 15.0, 36.0)]
    for area, stated, _ in reads:
        assert area == pytest.approx(reads[0][0], rel=1e-6)
        assert abs(area - reference) <= stated


def test_a_generating_lines_uncertainty_shrinks_with_the_density():
    # newuser7: where the straight line that generates the flank places the apex (rotorcad.meshing.generating_line),
    # the narrow-tip male with 1 um stated +-0.50 / 0.84 / 1.59 mm² at 80 / 150 / 300 points a lobe for errors within
    # 0.02 mm²: the tangent's bound and the other estimates' spread, growing with the density. The line's own bound
    # (its direction and offset to sigma sqrt(12 / n) / L and sigma / sqrt(n) over the n points under it) shrinks as
    # the points come closer, and still covers the error. Reference: the design's blow-hole from its exact curves
    reference = _design("narrow_tip_5_6")["area"]
    reads = [_read("narrow_tip_5_6", "male", per, 1.0, 0) for per in (80, 150, 300)]
    stated = [u for _, u, _ in reads]
    assert stated[0] > stated[1] > stated[2], stated
    assert stated[1] < 0.84 / 4 and stated[2] < 1.59 / 10, stated
    for area, u, resolved in reads:
        assert resolved
        assert abs(area - reference) <= u, (area, u, reference)


@pytest.mark.parametrize("per", [80, 150])
@pytest.mark.parametrize("name", ["narrow_tip_5_6", "srm_asymmetric_5_6"])
def test_sparse_female_own_line_within_one_percent(name, per):
    # the females whose own straight flank (2.9-3.5 mm: 3-4 places a lobe at 80, 5-7 at 150) places the apex, with
    # 1 um of scatter (seeds 0-2): the line fitted with the male tip's curve beyond it (line_points.own_line) reads
    # within 1 % of the reference, the design's blow-hole, which lies within the stated uncertainty; before, the
    # line of the spline's contacts stood (-9..+4 % along the normals, bench_line_apex.py --normal)
    reference = _design(name)["area"]
    for seed in (0, 1, 2):
        area, stated, _ = _read(name, "female", per, 1.0, seed)
        assert area == pytest.approx(reference, rel=0.01), (seed, area, reference)
        assert abs(area - reference) <= stated, (seed, area, stated, reference)

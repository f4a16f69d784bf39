"""The mate generated from one rotor's points or from the rack's points is the design's mate, with its verdicts.

A new user's findings: ``rotor --female-points`` of a female with sharp tips (narrow-tip, asymmetric
SRM; exact, 300 points a lobe) generated a male 17-21 mm off the design with thin fins and read a
closed meshline with no blow-hole; ``rotor --rack-points`` of the CSV that ``rotor --rack-csv``
writes read "jamming on the male" (narrow-tip) and "cusp on the female" (rack-involute) where the
design runs, a blow-hole of 3.45 mm² for 2.78 and a driving contact ratio of 0.98 for 0.629.

References (not made by the code under test): the male as the brute-force envelope of the given
female's positions (shapely: the male tip disk less the union of the female polygon, placed at 1501
mesh positions over one male pitch, in the male's frame; 1.9 µm from the design's exact male), and
the design's own pair and verdicts from its exact curves. Every rotor sample is checked so from its
female's points, exact and with 1 µm of scatter (issue 21 item 3), and the asymmetric SRM's finding
("does not run: jamming on the male", 4.8 +- 677 mm² for the design's 3.14) with more seeds.
"""

from __future__ import annotations

import json
import tomllib
from collections import Counter
from pathlib import Path

import numpy as np
import pytest
import shapely
from independent_pairs import scan, stored_by_inputs

from exports.csv_points import read_points, write_points
from rotorcad.cli.main import main
from rotorcad.design import rotor_design
from rotorcad.envelope import rack_frame
from rotorcad.profile import Segment
from rotorcad.roles import PieceRole
from rotorcad.rotor_build import PairSpec, analyse_pair, build_pair, pair_spec

SAMPLES = Path(__file__).resolve().parents[1] / "samples"
PER_LOBE = 300  # points a lobe, as a CMM measures
BLOW_HOLE = 0.01  # the blow-hole within 1 % (issue 21 item 3)
CONTACT_RATIO = 0.05  # transverse contact ratios within 0.05 (the asymmetric SRM's driving flank: 0.034 for 0)


def _spec(name: str):
    return pair_spec(rotor_design(tomllib.loads((SAMPLES / f"{name}.toml").read_text()), SAMPLES))


def _exterior(polygon: shapely.Polygon) -> np.ndarray:
    pts = np.asarray(polygon.exterior.coords)[:-1]
    area = 0.5 * np.sum(pts[:, 0] * np.roll(pts[:, 1], -1) - np.roll(pts[:, 0], -1) * pts[:, 1])
    return pts if area > 0 else pts[::-1]


def brute_force_male(pair, female: np.ndarray) -> shapely.Geometry:
    """The male the female cuts: its tip disk less the female at 1501 mesh positions over one male pitch (male frame)."""
    a, z1, z2 = pair.center_distance, pair.male_teeth, pair.female_teeth
    polys = []
    for phi in np.linspace(-np.pi / z1, np.pi / z1, 1501):
        th2 = -phi * z1 / z2  # the female turns the other way at z1/z2 of the male's rate
        f = female @ np.array([[np.cos(th2), np.sin(th2)], [-np.sin(th2), np.cos(th2)]]) + [a, 0.0]
        polys.append(shapely.Polygon(f @ np.array([[np.cos(phi), -np.sin(phi)], [np.sin(phi), np.cos(phi)]])))
    return shapely.Point(0.0, 0.0).buffer(pair.male_tip_radius, quad_segs=2048).difference(shapely.union_all(polys))


@stored_by_inputs("brute_force_male_cut", brute_force_male)
def brute_force_male_cut(pair, female: np.ndarray) -> np.ndarray:
    """The boundary of :func:`brute_force_male` (the cut the male is measured against) as its WKB bytes (uint8):
    the form tests/reference_data stores it in (tests/make_reference_data.py), the coordinates bit for bit."""
    reference = brute_force_male(pair, female)
    cut = (
        reference.boundary if isinstance(reference, shapely.Polygon) else shapely.union_all([g.boundary for g in reference.geoms])
    )
    return np.frombuffer(shapely.to_wkb(cut), dtype=np.uint8)


def _facing(outline: np.ndarray, pair) -> np.ndarray:
    """The outline's points on the male lobe facing the female (0.8 of a half pitch about +x): every female position cut there."""
    return outline[np.abs(np.arctan2(outline[:, 1], outline[:, 0])) <= 0.8 * np.pi / pair.male_teeth]


def _kinds(summary: dict) -> tuple[Counter, set]:
    """The defects that judge a flank (kind, rotor), and the rotors whose tip corner shows as a cusp (not a defect)."""
    flank = Counter((d["kind"], d["rotor"]) for d in summary["defects"] if not d.get("tip_corner"))
    return flank, {d["rotor"] for d in summary["defects"] if d.get("tip_corner")}


def assert_design_verdicts(design: dict, given: dict) -> None:
    """Closed or not, defects (kind, rotor; tip corners by rotor), running per flank and the blow-hole: the design's."""
    assert given["meshline_closed"] == design["meshline_closed"]
    assert _kinds(given) == _kinds(design), (given["defects"], design["defects"])
    assert given["runs_without_timing_gears"] == design["runs_without_timing_gears"]
    for flank, report in design["flanks"].items():
        mine = given["flanks"][flank]
        assert mine["runs_without_timing_gears"] == report["runs_without_timing_gears"], flank
    assert given["blow_hole_area"] == pytest.approx(design["blow_hole_area"], rel=BLOW_HOLE)


# case id -> the cause of a known departure (strict xfail: a fix makes it fail until removed here).
# narrow_tip_5_6 read 0.343 for the design's sealing 0.175 (the male tip corner's path from the female's points
# cut 3.6 mm of rack late by a fixed 0.1 um tolerance, the rest counted as working contact), until the path's
# extent followed the profile's accuracy (rotorcad.measured.mate_paths.mate_wander) and
# rotorcad.meshing.contact_ratios judged the working part to the input's accuracy
KNOWN_RATIOS_FEMALE: dict[str, str] = {}
# srm_asymmetric_5_6 read 0.364 for 0.184 too, until the corners of evenly spaced exact points were placed
# where the fits beside them cross (rotorcad.measured.fit): now the design's ratios. rack_involute_5_6 read 0.683
# and 0.696 for 0.484 and 0.497 (the rack's fitted lands, not flat to the 1e-9 of flank_roles, counted as flank
# contact), until the rack's lands were taken as exact lines (rotorcad.measured.rack_pieces) and
# rotorcad.meshing.contact_ratios counted a land's contact on O1O2 as none
KNOWN_RATIOS_RACK: dict[str, str] = {}


@pytest.fixture(scope="module", params=["narrow_tip_5_6", "srm_asymmetric_5_6"])
def from_female(request) -> tuple:
    """The design, the female's points (300 a lobe, exact) and the pair generated from them, with both summaries."""
    spec = _spec(request.param)
    design = build_pair(spec)
    female = _exterior(design.section("female", tolerance=1e-5))  # exact curves to a 0.01 um chord
    points = scan(female, spec.pair.female_teeth * PER_LOBE, 0.37)  # exact points (no scatter), 300 a lobe
    given = build_pair(PairSpec(spec.pair, "female-points", {}, points, None, spec.speed_rpm, 0.0), label="--female-points")
    return spec, design, points, given, analyse_pair(design, spec.speed_rpm)[1], analyse_pair(given, spec.speed_rpm)[1]


def _known(request, known: dict[str, str]) -> None:
    """Mark the test an expected failure (strict) where ``known`` names its case, with the cause."""
    reason = known.get(request.node.callspec.id)
    if reason:
        request.applymarker(pytest.mark.xfail(strict=True, reason=reason))


def test_male_from_female_points_is_the_envelope_of_the_female(from_female):
    # finding 1: 17-21 mm off with thin fins before; the male the female's own positions cut (brute force)
    spec, design, _, given, _, _ = from_female
    # the female whose points were given, to a 0.01 um chord (300 points a lobe blunt its sharp tips by 37 um)
    cut = shapely.from_wkb(brute_force_male_cut(spec.pair, _exterior(design.section("female", tolerance=1e-5))).tobytes())
    male = _exterior(given.section("male"))
    away = shapely.distance(shapely.points(_facing(male, spec.pair)), cut)
    back = shapely.distance(
        shapely.points(_facing(np.asarray(shapely.get_coordinates(cut)), spec.pair)), given.section("male").boundary
    )
    # the brute force's scallops (1.9 um from the design's exact male) plus the points' stated accuracy and the outline's chord
    bound = 2e-3 + given.accuracy + given.tolerance
    assert max(away.max(), back.max()) <= bound, (away.max(), back.max())


def test_male_from_female_points_is_the_design_male(from_female):
    _, design, _, given, _, _ = from_female
    gap = given.section("male").exterior.hausdorff_distance(design.section("male").exterior)
    assert gap <= given.accuracy + 2 * given.tolerance


def test_verdicts_from_female_points_are_the_design_verdicts(from_female):
    # finding 1: "meshline closed, blow-hole 0, runs" before, for the design's 2.78 mm² (narrow-tip)
    *_, design, given = from_female
    assert_design_verdicts(design, given)


def _rack_csv_points(rotors, tolerance: float = 1e-3) -> np.ndarray:
    """One rack period as ``rotor --rack-csv`` writes it (its pieces sampled to the chord tolerance, rack frame)."""
    pts = np.vstack([Segment.sample("rack", piece.curve, tolerance).points for piece in rotors.rack])
    keep = np.concatenate([[True], np.hypot(*np.diff(pts, axis=0).T) > 1e-9])
    return rack_frame(pts[keep], rotors.pair.male_pitch_radius)


@pytest.fixture(scope="module", params=["narrow_tip_5_6", "rack_involute_5_6"])
def from_rack(request) -> tuple:
    spec = _spec(request.param)
    design = build_pair(spec)
    given = build_pair(PairSpec(spec.pair, "rack-points", {}, _rack_csv_points(design), None, spec.speed_rpm, 0.0))
    return design, given, analyse_pair(design, spec.speed_rpm)[1], analyse_pair(given, spec.speed_rpm)[1]


def test_pair_from_own_rack_csv_is_the_design_pair(from_rack):
    design, given, _, _ = from_rack
    for side in ("male", "female"):
        gap = given.section(side).exterior.hausdorff_distance(design.section(side).exterior)
        assert gap <= given.accuracy + 2 * given.tolerance, (side, gap)


def test_verdicts_from_own_rack_csv_are_the_design_verdicts(from_rack):
    # finding 3: "jamming on the male" (narrow-tip), "cusp on the female" (rack-involute), blow-hole
    # 3.45 for 2.78 mm², driving contact ratio 0.98 for 0.629 before
    *_, design, given = from_rack
    assert_design_verdicts(design, given)


def test_female_drawn_at_the_centre_distance_is_moved_saying_so(tmp_path, capsys):
    # finding 11: rotorcad's pair drawing places the female at (a, 0); read back it was refused as
    # "the points span 0.0004 deg, which fits 8.71e+05 lobes", then as off-centre; now it is recognised
    # (its points lie between its root and tip radii about (a, 0)) and moved. Reference: the shift applied here.
    from exports.csv_points import write_points
    from rotorcad.cli.main import main

    spec = _spec("narrow_tip_5_6")
    points = _exterior(build_pair(spec).section("female"))
    a = spec.pair.center_distance
    path = tmp_path / "female_at_a.csv"
    write_points(path, points + [a, 0.0])
    dims = ["--male-teeth", spec.pair.male_teeth, "--female-teeth", spec.pair.female_teeth, "--center-distance", a]
    radii = ["--male-tip-radius", spec.pair.male_tip_radius, "--male-root-radius", spec.pair.male_root_radius]
    radii += ["--female-tip-radius", spec.pair.female_tip_radius, "--female-root-radius", spec.pair.female_root_radius]
    assert main([str(v) for v in ["rotor", "--female-points", path, *dims, *radii, "--json"]]) == 0
    out = capsys.readouterr()
    assert f"moved by ({-a:g}, 0) mm into its own frame" in out.err, out.err
    assert "lobes" not in out.err and "Traceback" not in out.err
    design = analyse_pair(build_pair(spec), spec.speed_rpm)[1]
    assert json.loads(out.out)["blow_hole_area"] == pytest.approx(design["blow_hole_area"], rel=0.01)


def assert_design_contact_ratios(design: dict, given: dict) -> None:
    for flank, report in design["flanks"].items():
        mine = given["flanks"][flank]["transverse_contact_ratio"]
        assert mine == pytest.approx(report["transverse_contact_ratio"], abs=CONTACT_RATIO), flank


def test_contact_ratios_from_female_points_are_the_design_ratios(from_female, request):
    *_, design, given = from_female
    _known(request, KNOWN_RATIOS_FEMALE)
    assert_design_contact_ratios(design, given)


def test_contact_ratios_from_own_rack_csv_are_the_design_ratios(from_rack, request):
    *_, design, given = from_rack
    _known(request, KNOWN_RATIOS_RACK)
    assert_design_contact_ratios(design, given)


def test_angles_from_female_points_in_the_design_count(from_female):
    # finding 13: from the female's points the male tip's slipping read +72.1 deg (one male pitch on)
    # for the design's +0.2. Reference: the design's slipping angle; every angle within +-180/z1.
    spec, *_, design, given = from_female
    half = 180.0 / spec.pair.male_teeth
    angles = [d["angle_deg"] for d in given["defects"]] + [f["angle_deg"] for f in given["slip_singularities"]]
    assert all(-half <= a < half for a in angles), angles
    slipping = {d["rotor"]: d["angle_deg"] for d in design["defects"] if d["kind"] == "slipping"}
    for d in given["defects"]:
        if d["kind"] == "slipping" and d["rotor"] in slipping:
            assert d["angle_deg"] == pytest.approx(slipping[d["rotor"]], abs=1.0)


# ---- every rotor sample from its female's points (issue 21 item 3) ------------------------------------------
# The design's verdicts from its exact curves are the reference; the female's points are the design's female
# outline (to a 0.01 um chord) scanned at 300 points a lobe, evenly spaced with the corners between the
# points (tests/independent_pairs.py ``scan``, as a CMM scans), exact or with 1 um of Gaussian scatter on
# each coordinate (one seed). Each must give the design's defects (kind, rotor, flank), its running verdict
# per flank, its transverse contact ratios, the blow-hole within 1 % (exact) or within the uncertainty the
# points state, an uncertainty that says something (not above the blow-hole itself, or 1 mm² where that is
# about 0), every angle in the design's count and every piece named by its lobe part.

ROTOR_SAMPLES = [p.stem for p in sorted(SAMPLES.glob("*.toml")) if "profile" in tomllib.loads(p.read_text())]
FEMALE_FORMS = ("exact", "scatter-1um")
SCATTER = 1e-3  # mm: standard deviation of the normal scatter added to each coordinate (a CMM's)
USEFUL_UNCERTAINTY = 1.0  # mm²: an uncertainty below this (or below the area) says something of a blow-hole near 0


def _female_verdicts() -> dict:
    out: dict = {}
    from rotorcad.meshing.meshline import flank_roles

    for name in ROTOR_SAMPLES:
        spec = _spec(name)
        design = build_pair(spec)
        out[(name, "design")] = analyse_pair(design, spec.speed_rpm)[1]
        points = scan(_exterior(design.section("female", tolerance=1e-5)), spec.pair.female_teeth * PER_LOBE, 0.37)
        forms = {"exact": points, "scatter-1um": points + np.random.default_rng(0).normal(0.0, SCATTER, points.shape)}
        for form, data in forms.items():
            given = build_pair(PairSpec(spec.pair, "female-points", {}, data, None, spec.speed_rpm, 0.0), label="--female-points")
            out[(name, form)] = analyse_pair(given, spec.speed_rpm)[1]
            parts = []  # each rack piece's name and its lobe part per point by the meshing analysis's own reading
            for piece in given.rack:
                pts, tangents = piece.curve.evaluate(np.linspace(piece.curve.s0, piece.curve.s1, 41))
                roles = flank_roles(pts, tangents, spec.pair.male_pitch_radius, spec.pair.center_distance)
                flat = bool(np.ptp(pts[:, 0]) <= 1e-2 * np.hypot(*(pts[-1] - pts[0])))
                role = Counter(str(r) for r in roles).most_common(1)[0][0]
                counts = Counter(str(r) for r in roles)
                if (
                    piece.kind in (PieceRole.MALE_CORNER_PATH, PieceRole.FEMALE_CORNER_PATH)
                    and min(counts["driving"], counts["sealing"]) >= 10
                ):
                    # a corner's path with a quarter of its samples on each flank crosses O1O2 at the tip or
                    # root (Rinder sec. 2.2.2: at the tip only a corner): named by the lobe part where it crosses
                    k = int(np.flatnonzero(pts[:-1, 1] * pts[1:, 1] <= 0)[0])
                    role = "tip" if pts[k, 0] > spec.pair.male_pitch_radius else "root"
                parts.append((piece.male_name, role, flat))
            out[(name, form, "parts")] = parts
        out[(name, "teeth")] = spec.pair.male_teeth
    return out


@pytest.fixture(scope="module")
def female_verdicts(built_once) -> dict:
    """The summaries of every rotor sample's design and of the pair from its female's points in each form."""
    return built_once("test_mate_points.female_verdicts", _female_verdicts)


# krigar_4_6 (exact and 1 um scatter) read two male tip-corner cusps, driving and sealing, for the design's one across
# O1O2 (the rack from the female's points split the male tip corner's path on O1O2), and of exact points its sealing
# flank ran on a short curve contact between the two tip corners' paths (sealing contact ratio 0.015 for 0), until a
# corner's path split at O1O2 was made one (rotorcad.meshing.defects._joined_across_o1o2) and such a hand-over
# shorter than the meshline's resolution counted as no working part (rotorcad.meshing.contact_ratios.is_corner_handover)
# n_rack_5_6 and rinder_deix_5_6 from exact female points read a sealing ratio of 1.417 for 0.746 (the rack from
# the female's points held the male's tip rounding and the sealing flank as one piece) until contacts within the
# meshline's accuracy of a tip corner counted as none (rotorcad.meshing.contact_ratios.resolved_steps)
_N_RACK_SPREAD = (
    "exact points: the apex is where the male's tip rounding meets the sealing flank, which 300 points a lobe "
    "resolve with 2-3 points: 1.787 mm² for the design's 1.738 (+2.8 %) with the male generated within 0.65 um "
    "of the design's everywhere (its apex 0.05 mm off: the blow-hole is that ill-conditioned in the fitted "
    "tangent; 600 points a lobe: +0.31 %, the male within 0.29 um), and the fit's tangent spread there "
    "(28-29 mrad) states +-4.4 mm², above the area itself (so did the male's even-300 points until the male tip "
    "rounding's circles stated their own bound, rotorcad.meshing.rounding_apex.model_check)"
)
KNOWN_FEMALE: dict[tuple[str, str, str], str] = {}
_SPACING = (
    "the female's point that hands over at the apex (where its flank meets the part the male tip corner generates, "
    "a curvature step) lies between two of its points 0.3 mm apart, and the apex moved to the contacts of the points "
    "up to one spacing from it changes the area by more than half of it (rotorcad.meshing.blow_hole_accuracy."
    "spacing_uncertainty: +-1.6-2.6 mm² on the narrow-tip, SRM and N-rack pairs' 1.7-3.3, +-20-42 on the "
    "rack-involute's 22.7); exact points still read the design's within 1 %"
)
UNRESOLVED_FEMALE: dict[tuple[str, str], str] = {
    **{(name, "exact"): _N_RACK_SPREAD for name in ("n_rack_5_6", "rinder_deix_5_6")},
    **{(name, "scatter-1um"): _SPACING for name in ("n_rack_5_6", "rinder_deix_5_6")},
}
# the narrow-tip, rack-involute, asymmetric SRM and SRM-B females (exact and 1 um) were here (_SPACING) until the
# straight line that generates the flank beside the tip corner, which places their apex, stated its own bound
# (rotorcad.meshing.blow_hole_accuracy.line_uncertainty): now resolved, and checked as the others below
"""The blow-holes the female's points do not resolve, and say so (``blow_hole_resolved`` false): the area is no
verdict there, and the design's lies within the stated uncertainty (as the male's evenly spaced points in
test_verdict_invariance's UNRESOLVED_BLOW_HOLE)."""


def _female_case(name: str, form: str, what: str):
    reason = KNOWN_FEMALE.get((name, form, what))
    return pytest.param(name, form, marks=pytest.mark.xfail(strict=True, reason=reason)) if reason else (name, form)


def _cases(what: str) -> list:
    return [_female_case(n, f, what) for n in ROTOR_SAMPLES for f in FEMALE_FORMS]


@pytest.mark.parametrize(("name", "form"), _cases("defects"))
def test_female_points_give_the_design_defects_and_running(female_verdicts, name, form):
    design, given = female_verdicts[(name, "design")], female_verdicts[(name, form)]
    key = lambda d: (d["kind"], d["rotor"], d["flank_role"])  # noqa: E731
    assert Counter(map(key, given["defects"])) == Counter(map(key, design["defects"])), (given["defects"], design["defects"])
    assert given["runs_without_timing_gears"] == design["runs_without_timing_gears"]
    for flank, report in design["flanks"].items():
        assert given["flanks"][flank]["runs_without_timing_gears"] == report["runs_without_timing_gears"], flank


@pytest.mark.parametrize(("name", "form"), _cases("ratios"))
def test_female_points_give_the_design_contact_ratios(female_verdicts, name, form):
    assert_design_contact_ratios(female_verdicts[(name, "design")], female_verdicts[(name, form)])


@pytest.mark.parametrize(("name", "form"), _cases("blow_hole"))
def test_female_points_give_the_design_blow_hole(female_verdicts, name, form):
    design, given = female_verdicts[(name, "design")], female_verdicts[(name, form)]
    area, stated = given["blow_hole_area"], given["blow_hole_uncertainty"]
    assert given["blow_hole_resolved"] == ((name, form) not in UNRESOLVED_FEMALE)  # says where it does not resolve
    if (name, form) in UNRESOLVED_FEMALE:  # no verdict: the design's area within the stated uncertainty
        assert abs(area - design["blow_hole_area"]) <= stated, (area, stated, design["blow_hole_area"])
        if form == "exact" and UNRESOLVED_FEMALE[(name, form)] is _SPACING:  # the figure itself still the design's
            assert area == pytest.approx(design["blow_hole_area"], rel=BLOW_HOLE, abs=1e-3)
        return
    if form == "exact":
        assert area == pytest.approx(design["blow_hole_area"], rel=BLOW_HOLE, abs=1e-3)
    else:
        assert abs(area - design["blow_hole_area"]) <= stated, (area, stated, design["blow_hole_area"])
    assert stated <= max(area, USEFUL_UNCERTAINTY), (area, stated)  # an uncertainty that says something


@pytest.mark.parametrize(("name", "form"), _cases("angles"))
def test_female_points_read_angles_and_parts_as_the_design(female_verdicts, name, form):
    # a new user saw +72.0 and 79.8 deg from female points where the design's angles lie within +-180/z1
    # (the rack's last pieces ran one period on), and every piece named just "flank". Reference: the
    # design's convention (every one of its angles lies within +-180/z1) and the lobe part that the meshing
    # analysis reads per point off the rack (rotorcad.meshing.meshline.flank_roles).
    given, half = female_verdicts[(name, form)], 180.0 / female_verdicts[(name, "teeth")]
    angles = [d["angle_deg"] for d in given["defects"] + given["slip_singularities"]]
    angles += [given[k]["angle_deg"] for k in ("max_sliding_at", "max_slip_male", "max_slip_female") if given.get(k)]
    assert all(-half <= a <= half for a in angles), angles
    for piece_name, role, flat in female_verdicts[(name, form, "parts")]:
        # a land fitted through points is not flat to flank_roles' 1e-9 (KNOWN_RATIOS_RACK): flat to 1 % of its chord
        # a corner's path across O1O2 (role tip or root) is named as the corner of both flanks (rotorcad.roles)
        named = piece_name.split()[0] == role or (piece_name.endswith("tip corner (both flanks)") and role in ("tip", "root"))
        assert named or (flat and piece_name.endswith("land")), (piece_name, role)


# seed 2 read jamming on the male's driving arc about C (its meshline's miss of C swung by -0.46..+0.57 mm against
# a band of 0.12 mm) until an arc about C was recognised from the meshline's positions
# (rotorcad.meshing.defects.arcs_about)


@pytest.mark.parametrize("seed", [1, 2])
def test_asymmetric_srm_from_scattered_female_points_runs_as_the_design(seed):
    # the finding: 300 points a lobe of the asymmetric SRM's female with 1 um of scatter read "does not run:
    # driving flank: jamming on the male" and a blow-hole of 4.8 +- 677 mm² (design 3.14, runs). Reference:
    # the design's verdicts from its exact curves; the stated uncertainty must hold the design's blow-hole
    # and stay below the blow-hole itself
    spec = _spec("srm_asymmetric_5_6")
    design = build_pair(spec)
    points = scan(_exterior(design.section("female", tolerance=1e-5)), spec.pair.female_teeth * PER_LOBE, 0.37)
    noisy = points + np.random.default_rng(seed).normal(0.0, SCATTER, points.shape)
    given = analyse_pair(build_pair(PairSpec(spec.pair, "female-points", {}, noisy, None, spec.speed_rpm, 0.0)), spec.speed_rpm)[
        1
    ]
    reference = analyse_pair(design, spec.speed_rpm)[1]
    area, stated = given["blow_hole_area"], given["blow_hole_uncertainty"]
    assert abs(area - reference["blow_hole_area"]) <= stated <= area, (area, stated)
    for flank, report in reference["flanks"].items():
        assert given["flanks"][flank]["runs_without_timing_gears"] == report["runs_without_timing_gears"], flank


# ---- one mate corner's path, and no corner where the mate has none (issue 21 item 3) ---------------------------


def _from_female(name: str, form: str):
    spec = _spec(name)
    design = build_pair(spec)
    points = scan(_exterior(design.section("female", tolerance=1e-5)), spec.pair.female_teeth * PER_LOBE, 0.37)
    if form == "scatter-1um":
        points = points + np.random.default_rng(0).normal(0.0, SCATTER, points.shape)
    return spec, design, build_pair(PairSpec(spec.pair, "female-points", {}, points, None, spec.speed_rpm, 0.0))


def _male_paths(rotors) -> list:
    return [p for p in rotors.rack if p.kind is PieceRole.MALE_CORNER_PATH]


@pytest.mark.parametrize("form", FEMALE_FORMS)
def test_krigar_male_tip_path_from_female_points_is_one_path(form):
    # Krigar's pointed male tip touches the female's root on O1O2, where the female's points were fitted in two
    # pieces: the tip's path came as two rack pieces (14.0 and 13.1 mm, one each side of O1O2) read as a driving
    # and a sealing cusp, and of exact points a 0.94 mm flank between it and the female tip's path ran.
    # Reference: the design's rack (rotorcad.families.krigar: one male tip corner path, a closed-form point
    # path of the corner on the tip circle); its ends within the defect tests' resolution sqrt(8 a e) (the
    # place of a verdict, Rinder's tests resolved to the input's accuracy e), its corner within e.
    spec, design, given = _from_female("krigar_4_6", form)
    (expected,) = _male_paths(design)
    (found,) = _male_paths(given)
    a = spec.pair.center_distance
    reach = max(5e-3 * a, float(np.sqrt(8.0 * a * given.accuracy)))
    ends = lambda c: c.evaluate(np.array([c.s0, c.s1]))[0]  # noqa: E731
    assert np.hypot(*(ends(found.curve) - ends(expected.curve)).T).max() <= reach
    assert np.hypot(*np.subtract(found.curve.carried, expected.curve.carried)) <= given.accuracy
    # across O1O2, above C: the male tip's corner of both flanks (Rinder sec. 2.2.2; the design's family names
    # its piece "tip corner", a defect there reads rotorcad.roles.tip_corner_name from either)
    assert found.male_name == "male tip corner (both flanks)" and expected.male_name == "tip corner"


@pytest.mark.parametrize("form", FEMALE_FORMS)
def test_rounded_male_tip_from_female_points_has_no_corner_path(form):
    # the N rack's male tip is rounded (0.67 mm): the slow part of that rounding, 0.19 mm inside the male tip
    # circle, was read as the male's tip corner from the female's splines, which cut the rounding short where
    # the apex lies (blow-hole +1.7 %). Reference: the design's rack (rotorcad.families.n_rack: a rounded tip
    # has no male corner path) and Rinder sec. 2.2.2 (only a corner at the tip stands still on the tip circle)
    _, design, given = _from_female("n_rack_5_6", form)
    assert not _male_paths(design)
    assert not _male_paths(given), [(p.male_name, p.curve.evaluate(np.array([p.curve.s0]))[0]) for p in _male_paths(given)]


def test_smoothing_that_follows_scattered_female_points_is_refused(capsys, tmp_path):
    # issue 21 item 3: `rotor --female-points` of 1 um scattered points with --smoothing 0 lost the female tip
    # corner's path (the symmetric SRM's driving cusp, blow-hole 0.53 for 70.7 mm²) with only a note; the N
    # rack's male read a tip corner it has not at 8e-5 and 1.5e-4 mm². Now refused in one sentence naming
    # --smoothing and the least that works, exit status 2; that least is taken. Reference: the scatter put in,
    # 300 points a lobe x (1 um)^2 = 3e-4 mm² (scipy's s = n sigma^2, Dierckx sec. 5.2)
    spec = _spec("narrow_tip_5_6")
    female = _exterior(build_pair(spec).section("female", tolerance=1e-5))
    points = scan(female, spec.pair.female_teeth * PER_LOBE, 0.37)
    path = tmp_path / "female.csv"
    write_points(path, points + np.random.default_rng(0).normal(0.0, SCATTER, points.shape))
    args = ["rotor", str(SAMPLES / "narrow_tip_5_6.toml"), "--female-points", str(path), "--quiet"]
    capsys.readouterr()
    assert main([*args, "--smoothing", "0"]) == 2
    lines = [line for line in capsys.readouterr().err.splitlines() if line.strip()]
    assert len(lines) == 1 and "--smoothing must be at least" in lines[0] and "Traceback" not in lines[0], lines
    least = float(lines[0].split("at least ")[1].split()[0])
    assert least == pytest.approx(PER_LOBE * SCATTER**2, rel=0.3)
    assert main([*args, "--smoothing", f"{least:.3g}"]) == 0, capsys.readouterr().err


# ---- the Lysholm female at other phases and starts of the spacing (issue 21 item 3) ----------------------------

# (sample, phase of the spacing, start as a share of the outline, turn in degrees): a new user's Lysholm female
# as 300 exact points a lobe read "sealing flank: runs, transverse contact ratio 0.000 + overlap 2.308" at
# phase 0, at phase 0.5 from 0.37 of the outline and turned by 17.3 deg (12 of his 18 inputs)
SPACINGS = [
    ("lysholm_4_6", 0.0, 0.0, 0.0),
    ("lysholm_4_6", 0.5, 0.37, 0.0),
    ("lysholm_4_6", 0.8, 0.2, 0.0),
    ("lysholm_4_6", 0.0, 0.11, 17.3),
    ("srm_asymmetric_5_6", 0.0, 0.0, 0.0),
    ("srm_asymmetric_5_6", 0.5, 0.37, 0.0),
]


def _spaced(ring: np.ndarray, teeth: int, phase: float, start: float, turn: float) -> np.ndarray:
    """300 exact points a lobe of the closed ``ring``: begun ``start`` of its samples round and ``phase`` of a
    spacing on, then turned by ``turn`` deg about the rotor's centre."""
    points = scan(np.roll(ring, -round(start * len(ring)), axis=0), teeth * PER_LOBE, phase)
    c, s = np.cos(np.radians(turn)), np.sin(np.radians(turn))
    return points @ np.array([[c, s], [-s, c]])


@pytest.fixture(scope="module")
def spaced_verdicts() -> dict:
    """The design's summary per sample, and the summary of the pair from each spacing of its female's points."""
    out: dict = {}
    for name in sorted({case[0] for case in SPACINGS}):
        spec = _spec(name)
        design = build_pair(spec)
        out[name] = analyse_pair(design, spec.speed_rpm)[1]
        ring = _exterior(design.section("female", tolerance=1e-5))  # exact curves to a 0.01 um chord
        for case in SPACINGS:
            if case[0] == name:
                points = _spaced(ring, spec.pair.female_teeth, *case[1:])
                given = build_pair(PairSpec(spec.pair, "female-points", {}, points, None, spec.speed_rpm, 0.0))
                out[case] = analyse_pair(given, spec.speed_rpm)[1]
    return out


@pytest.mark.parametrize("case", SPACINGS, ids=lambda c: f"{c[0]}-phase{c[1]}-start{c[2]}-turn{c[3]}")
def test_female_points_at_any_spacing_give_the_design_defects_and_running(spaced_verdicts, case):
    # reference: the design's own verdicts from its exact curves, and Rinder (Fig. 2, sec. 1.2): the Lysholm
    # profile needs timing gears (its sealing flank has no geometric contact: design working length 0), while
    # the asymmetric SRM's short straight part makes its sealing flank run (Fig. 4: a working part of 13 mm)
    design, given = spaced_verdicts[case[0]], spaced_verdicts[case]
    key = lambda d: (d["kind"], d["rotor"], d["flank_role"], d["tip_corner"])  # noqa: E731
    assert Counter(map(key, given["defects"])) == Counter(map(key, design["defects"])), (given["defects"], design["defects"])
    assert given["runs_without_timing_gears"] == design["runs_without_timing_gears"]
    for flank, report in design["flanks"].items():
        mine = given["flanks"][flank]
        assert mine["runs_without_timing_gears"] == report["runs_without_timing_gears"], (flank, mine)
        assert (mine["working_length"] > 0) == (report["working_length"] > 0), (flank, mine["working_length"])


def _one_lobe_from(ring: np.ndarray, teeth: int, per_lobe: int, at: str) -> np.ndarray:
    """One lobe of ``per_lobe`` + 1 points evenly spaced along the ring (a CMM's scan, tests/independent_pairs.scan),
    from the sharp corner at its tip (``at="tip"``: the vertex of largest turn on the tip circle) or from its lowest
    point (``"root"``) to the same place one lobe on: a point lies there at both ends."""
    step = np.roll(ring, -1, axis=0) - ring
    heading = np.arctan2(step[:, 1], step[:, 0])
    turn = np.abs(np.angle(np.exp(1j * (heading - np.roll(heading, 1)))))
    r = np.hypot(*ring.T)
    near = r >= r.max() - 1e-3
    start = int(np.flatnonzero(near)[np.argmax(turn[near])]) if at == "tip" else int(np.argmin(r))
    return scan(np.roll(ring, -start, axis=0), per_lobe * teeth)[: per_lobe + 1]


@pytest.mark.parametrize(
    ("name", "at"), [("narrow_tip_5_6", "tip"), ("srm_asymmetric_5_6", "tip"), ("srm_asymmetric_5_6", "root")]
)
def test_one_lobe_gives_the_whole_outlines_verdicts(name, at, tmp_path):
    # the finding: one groove of the narrow-tip male, tip to tip, 300 exact points (0-72 deg), was refused "4.3 % of
    # the lobe has no rack point" (its last point, the first one lobe on 0.08 um short of the pitch, kept: a step of
    # 0.08 um at the sharp tip; the asymmetric SRM 5.2 %); the asymmetric SRM male from its lowest point, a root
    # corner, refused "must be a smooth profile ... noise in the points?" (its tip corner, between two points,
    # placed 2.9 um outside the tip circle by the chords' crossing, and a corner on a point left out of the fits
    # that place it). Reference: the design's verdicts (its analytic outline); the lobe resampled by arc length
    # here from the design's CSV at 0.01 um chord (rotor --male-csv --tolerance 0.00001, as the user made it)
    spec = _spec(name)
    rotors = build_pair(spec)
    path = tmp_path / "design.csv"
    assert main(["rotor", str(SAMPLES / f"{name}.toml"), "--male-csv", str(path), "--tolerance", "0.00001", "--quiet"]) == 0
    lobe = _one_lobe_from(read_points(path, "design"), spec.pair.male_teeth, 300, at)
    span = np.degrees(np.ptp(np.unwrap(np.arctan2(lobe[:, 1], lobe[:, 0]))))
    assert span == pytest.approx(72.0, abs=0.01)  # one lobe, a point on the corner at either end
    given = analyse_pair(build_pair(PairSpec(spec.pair, "male-points", {}, lobe, None, spec.speed_rpm, 0.0)), spec.speed_rpm)[1]
    assert_design_verdicts(analyse_pair(rotors, spec.speed_rpm)[1], given)

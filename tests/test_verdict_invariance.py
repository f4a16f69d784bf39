"""Rinder's verdicts do not depend on how the profile is given (issue 21 item 3, issue 22 item 4).

Reference: the design's own verdict, from its exact curves. The same male, given as the CSV and the
DXF drawings rotorcad writes of it (read back by the readers a user's file goes through) and as
dense exact points and as exact points evenly spaced along the outline at 300 a lobe (a CMM's scan:
the sharp corners fall between the points; two phases), must give the same defects (kind, rotor,
flank part, point-generated; each within the resolution of the input,
:func:`rotorcad.meshing.resolution`, of the design's), the same "runs without timing gears" per
flank, and the blow-hole within 1 %. The test is of equality between the forms, not of any sample's
particular verdict (the samples and the criteria may change).

Points with 1 µm of normal scatter (a CMM's, one seed for every sample) must give the same defects and
running verdicts too; the blow-hole is compared within 1 % or the area the meshline's accuracy leaves
open, and the samples whose blow-hole departs by more are named in KNOWN_BLOW_HOLE with the cause;
for every sample the design's blow-hole lies within the uncertainty the points state
(``blow_hole_uncertainty``, from their tangents' accuracy), and so it does for exact points, whose
fit's tangent is off where they do not resolve the outline (a tip rounding with 2-3 points on it);
where that uncertainty exceeds the area the input says it does not resolve the blow-hole
(``blow_hole_resolved``, the forms named in UNRESOLVED_BLOW_HOLE with the cause).

Plus the findings of the issues, with their exact inputs: the rack-involute male's own CSV (94
defects, 78 jamming, before), its own DXF polyline (refused before, whatever ``--smoothing``), an
LWPOLYLINE of arcs within 1.1 µm of the outline (accepted by ``clearance``, refused by ``rotor``
before), a female given as one groove (refused before) and the ``----male-points`` message.
"""

from __future__ import annotations

import functools
import json
import re
import tomllib
from collections import Counter
from pathlib import Path

import ezdxf
import ezdxf.path
import numpy as np
import pytest
import shapely
import shapely.affinity
from independent_pairs import patterned, scan
from shared_runs import points_summary

from exports.csv_points import read_points, write_points
from exports.dxf import Drawing, write_dxf
from exports.dxf_profile import read_profile
from rotorcad.cli.main import main
from rotorcad.design import rotor_design
from rotorcad.meshing import MESHLINE_GAIN, resolution
from rotorcad.roles import tip_corner_name
from rotorcad.rotor_build import PairSpec, analyse_pair, build_pair, pair_spec
from rotorcad.rotor_points import pair_from_rotor_points

SAMPLES = Path(__file__).resolve().parents[1] / "samples"
ROTOR_SAMPLES = [p.stem for p in sorted(SAMPLES.glob("*.toml")) if "profile" in tomllib.loads(p.read_text())]
FORMS = ("csv", "dxf-polyline", "dxf-spline", "dense", "even-300", "even-300-b", "scatter-1um")
EVEN_PER_LOBE = 300  # a CMM's even spacing along the outline: the corners fall between the points
EVEN_PHASES = {"even-300": 0.37, "even-300-b": 0.8}  # where the first point falls, in spacings past the lobe's start
SCATTER = 1e-3  # mm: standard deviation of the normal scatter added to each coordinate of the CSV's points (a CMM's)

# Known departures, each named with its cause (strict: a fix makes them fail until removed here).
# srm_symmetric_4_6 even-300 and even-300-b read a jamming on the lobe arc, until an arc about C was recognised
# from the meshline's positions (rotorcad.meshing.defects.arcs_about) and the female tip path's extent followed
# the profile's accuracy (rotorcad.measured.mate_paths.mate_wander); krigar_4_6 even-300-b named its tip-centre cusp
# by the driving flank until a corner path across O1O2 became the tip of both flanks
KNOWN: dict[tuple[str, str], str] = {}
# krigar_4_6 even-300-b ran on its driving flank (the design's does not): 300 points a lobe at phase 0.8 left
# 1.04 mm of meshline where the male tip corner's path hands over to the female's as a working part, until a
# rack part between the two tips' corner paths along which the mate's point stands nearly still was joined to
# the mate corner's path (rotorcad.measured.corner_paths.joined_mate_paths)
# krigar_4_6 even-300-b ran on its sealing flank (the design's does not): 300 points a lobe at phase 0.8 left 0.96 mm
# of curve contact where the male tip corner's path hands over to the female's, counted as a working part, until
# such a hand-over shorter than the meshline's resolution counted as none
# (rotorcad.meshing.contact_ratios.is_corner_handover)
KNOWN_VERDICTS: dict[tuple[str, str], str] = {}
# n_rack_5_6 and rinder_deix_5_6 even-300 (+0.9 %, +13.7 % before the rounding's circles), even-300-b (-0.0 %, -74.9 %
# before), csv (-0.005 %), scatter-1um (-0.65..+0.37 % over seeds 0-7, +36.8..+65.9 % before) and the two DXF forms
# were here, the area within 1 % but the uncertainty stated the points' spacing along the male's 0.67 mm tip rounding
# (1.39-1.71 mm² of the CSV with 1 um, 26-88 mm² of the even scans) or the fit's tangent at its curvature steps (8 mm²
# of the drawings), over half the area, until the rounding's circle and the female circle whose envelope is the sealing
# flank, fitted to the points themselves (rotorcad.meshing.rounding_apex), stated their own bound where they hold as
# the points' model (rotorcad.meshing.rounding_apex.model_check): 0.03-0.10 mm²
UNRESOLVED_BLOW_HOLE: dict[tuple[str, str], str] = {}
"""The blow-holes the input does not resolve, and says so: the area is no verdict there (the design's lies
within the stated uncertainty, test_exact_points_state_their_blow_hole_uncertainty)."""
KNOWN_BLOW_HOLE: dict[tuple[str, str], str] = {}


def _exterior(polygon: shapely.Polygon) -> np.ndarray:
    pts = np.asarray(polygon.exterior.coords)[:-1]
    area = 0.5 * np.sum(pts[:, 0] * np.roll(pts[:, 1], -1) - np.roll(pts[:, 0], -1) * pts[:, 1])
    return pts if area > 0 else pts[::-1]


def _evenly(lobe: np.ndarray, teeth: int, per_lobe: int, phase: float = 0.37) -> np.ndarray:
    """Points evenly spaced along the whole outline of a dense exact lobe (root to root), ``per_lobe`` a
    lobe, the first ``phase`` of a spacing past the lobe's start: the sharp corners fall between the
    points, as in a CMM's scan (the lobe's own samples hold every corner as a point)."""
    return scan(patterned(lobe, teeth), per_lobe * teeth, phase)


def _given(spec: PairSpec, data, label: str) -> dict:
    # built and analysed once in the run for these points (tests/test_moderate_densities.py reads the even-300
    # form too): tests/shared_runs.py
    return points_summary(PairSpec(spec.pair, "male-points", {}, data, None, spec.speed_rpm, 0.0), label)


@pytest.fixture(scope="module")
def verdicts(tmp_path_factory, built_once) -> dict:
    """The summaries of every sample's design and of its male in every form (built once), its spec and male."""
    return built_once("test_verdict_invariance.verdicts", lambda: _verdicts(tmp_path_factory.mktemp("forms")))


def _verdicts(folder) -> dict:
    out: dict[tuple[str, str], dict] = {}
    for name in ROTOR_SAMPLES:
        spec = pair_spec(rotor_design(tomllib.loads((SAMPLES / f"{name}.toml").read_text()), SAMPLES))
        rotors = build_pair(spec)
        analysis, out[(name, "design")] = analyse_pair(rotors, spec.speed_rpm)
        male = _exterior(analysis.sections[0])  # what `rotor --male-csv` and `--dxf` write
        csv = folder / f"{name}.csv"
        write_points(csv, male)
        out[(name, "csv")] = _given(spec, read_points(csv, "--male-points"), "--male-points")
        drawings = {"dxf-polyline": Drawing(outlines=[("MALE", male)]), "dxf-spline": Drawing(splines=[("MALE", male)])}
        for form, drawing in drawings.items():
            path = folder / f"{name}_{form}.dxf"
            write_dxf(path, drawing)
            out[(name, form)] = _given(spec, read_profile(path, "--male-points", "MALE"), "--male-points")
        dense = np.vstack([seg.resampled(1e-5).points for seg in rotors.male_lobe().segments])  # exact, 0.01 um chord
        out[(name, "dense")] = _given(spec, dense, "--male-points")
        for form, phase in EVEN_PHASES.items():
            out[(name, form)] = _given(spec, _evenly(dense, spec.pair.male_teeth, EVEN_PER_LOBE, phase), "--male-points")
        out[(name, "spec")], out[(name, "male")] = spec, male  # for more seeds (test_blow_hole_within_uncertainty)
        scattered = male + np.random.default_rng(0).normal(0.0, SCATTER, male.shape)  # one seed for every sample
        out[(name, "scatter-1um")] = _given(spec, scattered, "--male-points")
    return out


def _key(d: dict) -> tuple:
    return d["kind"], d["rotor"], d["flank_role"], d["point_generated"]


def assert_same_verdicts(design: dict, given: dict) -> None:
    """The defects, their places and the running verdicts of ``given`` are those of ``design``."""
    assert Counter(map(_key, given["defects"])) == Counter(map(_key, design["defects"]))
    reach = resolution(given["defect_accuracy"], design["center_distance"])
    for d in design["defects"]:
        near = [
            np.hypot(g["x"] - d["x"], g["y"] - d["y"]) - 0.5 * (g["extent"] + d["extent"])
            for g in given["defects"]
            if _key(g) == _key(d)
        ]
        assert min(near) <= reach, (d, given["defects"])
    for flank, report in design["flanks"].items():
        assert given["flanks"][flank]["runs_without_timing_gears"] == report["runs_without_timing_gears"], flank


def _case(name: str, form: str, known: dict):
    reason = known.get((name, form))
    return pytest.param(name, form, marks=pytest.mark.xfail(strict=True, reason=reason)) if reason else (name, form)


@pytest.mark.parametrize(("name", "form"), [_case(n, f, {**KNOWN, **KNOWN_VERDICTS}) for n in ROTOR_SAMPLES for f in FORMS])
def test_same_defects_and_running(verdicts, name, form):
    assert_same_verdicts(verdicts[(name, "design")], verdicts[(name, form)])


@pytest.mark.parametrize(("name", "form"), [_case(n, f, {**KNOWN, **KNOWN_BLOW_HOLE}) for n in ROTOR_SAMPLES for f in FORMS])
def test_same_blow_hole(verdicts, name, form):
    design, given = verdicts[(name, "design")]["blow_hole_area"], verdicts[(name, form)]["blow_hole_area"]
    # the input resolves the blow-hole, or says it does not (only where named, with the cause)
    assert verdicts[(name, form)]["blow_hole_resolved"] == ((name, form) not in UNRESOLVED_BLOW_HOLE)
    assert verdicts[(name, "design")]["blow_hole_resolved"]
    if (name, form) in UNRESOLVED_BLOW_HOLE:  # no verdict: the design's area within the stated uncertainty
        assert abs(given - design) <= verdicts[(name, form)]["blow_hole_uncertainty"]
        assert given == pytest.approx(design, rel=0.01)  # the area within 1 % all the same (even: the rounding's circles)
        return
    floor = 1e-3  # mm², where the meshline closes
    if form.startswith("scatter"):
        # a closed meshline read from scattered points ends within the meshline's accuracy (MESHLINE_GAIN
        # times the points') of the cusp, over the stretch the tests resolve: an area below that is no verdict
        acc = verdicts[(name, form)]["defect_accuracy"]
        floor = max(floor, MESHLINE_GAIN * acc * resolution(acc, verdicts[(name, form)]["center_distance"]))
    assert given == pytest.approx(design, rel=0.01, abs=floor)  # 1 %


@pytest.mark.parametrize(("name", "form"), [(n, f) for n in ROTOR_SAMPLES for f in FORMS])
def test_same_words_for_the_same_defects(verdicts, name, form):
    # issue 21 (a new user's session): the same defect read "sealing tip corner" from the design and "sealing male
    # tip corner" from its own CSV (the narrow-tip's female tip corner "sealing root (female tip path)" and "sealing
    # female tip corner", the symmetric SRM's "trailing root (female tip path)", Krigar's "tip corner" and "tip male
    # tip corner"): one thing, one wording, whatever the form. Reference: the design's own defects; each one's `flank`
    # text is the one of the given form's defect of the same key (test_same_defects_and_running: kind, rotor, flank
    # part, point-generated) nearest to it, and every tip corner is named by its rotor and lobe part alone
    design, given = verdicts[(name, "design")], verdicts[(name, form)]
    for d in design["defects"]:
        same = [g for g in given["defects"] if _key(g) == _key(d)]
        if not same:
            continue  # a different verdict: test_same_defects_and_running's
        near = min(same, key=lambda g: np.hypot(g["x"] - d["x"], g["y"] - d["y"]))
        assert near["flank"] == d["flank"], (d, near)
    for d in design["defects"] + given["defects"]:
        if d["tip_corner"]:
            assert d["flank"] == tip_corner_name(d["flank_role"], d["rotor"]), d


@pytest.mark.parametrize(("name", "form"), [(n, f) for n in ROTOR_SAMPLES for f in FORMS])
def test_same_point_generated_flanks(verdicts, name, form):
    # issue 21 item 3: the flanks a single tip corner of the mate traces are listed once each and in the same words
    # from every form (reference: the design's own list, from its exact rack). Before, the design listed its
    # family's segment names ("sealing flank (point-generated by the female tip)", "trailing root (female tip
    # path)") and points their lobe parts ("sealing female tip corner"), a path in two pieces twice; the narrow-tip and
    # SRM-B designs listed a female tip path of no length; the rack-involute male from its CSV, DXF (polyline, spline)
    # and even-300 listed a "sealing female tip corner" (strict xfail until the female involute's cusp on its base
    # circle, held still over 0.24-0.28 mm of rack, under the resolution, counted as flank: measured.pairs)
    design, given = verdicts[(name, "design")], verdicts[(name, form)]
    rows = [(f["rotor"], f["flank"], f["flank_role"], f["generated_by"]) for f in given["point_generated_flanks"]]
    assert len(set(rows)) == len(rows), rows
    for f in design["point_generated_flanks"] + given["point_generated_flanks"]:
        assert f["flank"] == tip_corner_name(f["flank_role"], f["generated_by"].split()[0]), f
    assert sorted(rows) == sorted(
        (f["rotor"], f["flank"], f["flank_role"], f["generated_by"]) for f in design["point_generated_flanks"]
    )


def _slip_key(d: dict) -> tuple:
    return d["rotor"], d["flank"]


@pytest.mark.parametrize(("name", "form"), [(n, f) for n in ROTOR_SAMPLES for f in FORMS])
def test_same_points_of_infinite_slip(verdicts, name, form):
    # issue 21 item 3: the points of infinite slip (Rinder eq. 4, sec. 3.2: where a rotor's v_t vanishes) are the
    # design's whatever form the male comes in (reference: the design's own, from its exact curves): the same count
    # by rotor and lobe part, each where the design's is within the input's resolution sqrt(8 a e)
    # (rotorcad.meshing.resolution: how far along the meshline the input places a point), and at the male rotation
    # that turns the male's point there by that much (the angle names the instant of that contact). Before: narrow-tip
    # and SRM-B 2 for 1, the asymmetric SRM 3-4 for 2, Krigar, Lysholm and the symmetric SRM 3-5 for 2 (a female tip
    # corner on its pitch circle, placed 16-95 um off it by the fit, moved the zero at C 0.1-3.8 mm away)
    design, given = verdicts[(name, "design")], verdicts[(name, form)]
    want, got = design["slip_singularities"], given["slip_singularities"]
    assert Counter(map(_slip_key, got)) == Counter(map(_slip_key, want)), got
    reach = resolution(given["defect_accuracy"], design["center_distance"])
    for d in want:
        near = min((g for g in got if _slip_key(g) == _slip_key(d)), key=lambda g: np.hypot(g["x"] - d["x"], g["y"] - d["y"]))
        assert np.hypot(near["x"] - d["x"], near["y"] - d["y"]) <= reach, (d, near)
        assert near["angle_deg"] == pytest.approx(d["angle_deg"], abs=np.degrees(reach / d["male_radius"])), (d, near)


def test_scatter_judged_to_its_accuracy(verdicts):
    # the points with 1 um of scatter are judged to twice the scatter estimated from them (2 sigma,
    # rotorcad.measured.outline.accuracy), not to the chords' sagitta of the exact CSV: 2 um within 15 %
    for name in ROTOR_SAMPLES:
        assert verdicts[(name, "scatter-1um")]["defect_accuracy"] == pytest.approx(2 * SCATTER, rel=0.15), name


def test_accuracy_is_reported(verdicts):
    # the design is judged to its chord tolerance, points to their chords' sagitta: the CSV's points
    # are 0.25 mm apart on radii of 7.7 mm and more, h^2 / (8 rho) <= 1 um (an independent bound)
    design, csv = verdicts[("rack_involute_5_6", "design")], verdicts[("rack_involute_5_6", "csv")]
    assert design["defect_accuracy"] == pytest.approx(1e-4)
    assert 1e-4 < csv["defect_accuracy"] < 1e-3


def test_own_csv_has_no_jamming(verdicts):
    # the finding: 94 defects, 78 of them jamming, from the rack-involute male's own CSV
    csv = verdicts[("rack_involute_5_6", "csv")]
    assert not [d for d in csv["defects"] if d["kind"] == "jamming"]
    assert len(csv["defects"]) == len(verdicts[("rack_involute_5_6", "design")]["defects"])


# ---- the drawings and the spans of the findings, through the command line ------------------------

_RI_PAIR = tomllib.loads((SAMPLES / "rack_involute_5_6.toml").read_text())["pair"]  # the sample's own dimensions
DIMS_56 = ["--male-teeth", _RI_PAIR["male_teeth"], "--female-teeth", _RI_PAIR["female_teeth"]]
DIMS_56 += ["--center-distance", repr(_RI_PAIR["center_distance"])]
RADII_56 = [
    f"--{key.replace('_', '-')}" if i % 2 == 0 else repr(_RI_PAIR[key])
    for key in ("male_tip_radius", "male_root_radius", "female_tip_radius", "female_root_radius")
    for i in (0, 1)
]


def run(capsys, *args) -> tuple[int, str, str]:
    rc = main([str(a) for a in args])
    out = capsys.readouterr()
    return rc, out.out, out.err


@pytest.fixture(scope="module")
def written(tmp_path_factory) -> dict[str, Path]:
    """The rack-involute pair as ``rotor`` writes it: JSON, male and female CSV, the pair's DXF."""
    folder = tmp_path_factory.mktemp("written")
    files = {"male": folder / "m.csv", "female": folder / "f.csv", "dxf": folder / "pair.dxf", "json": folder / "design.json"}
    rc = main(
        ["rotor", str(SAMPLES / "rack_involute_5_6.toml"), "--json", "--quiet"]
        + ["--male-csv", str(files["male"]), "--female-csv", str(files["female"]), "--dxf", str(files["dxf"])]
    )
    assert rc == 0
    return files


def test_own_dxf_polyline_accepted_and_smoothing_acts(verdicts, written, capsys):
    # the finding: rotorcad's own DXF polyline was refused ("noise in the points? raise --smoothing"),
    # and --smoothing 0, 0.1 and 10 gave that one refusal
    design = verdicts[("rack_involute_5_6", "design")]
    results = {}
    for smoothing in (None, 0.0, 0.1, 10.0):
        extra = [] if smoothing is None else ["--smoothing", smoothing]
        args = ["--male-points", written["dxf"], "--layer", "MALE", *DIMS_56, *RADII_56, *extra]
        rc, out, err = run(capsys, "rotor", *args, "--json")
        assert rc == 0, err
        results[smoothing] = json.loads(out)
    assert_same_verdicts(design, results[None])
    assert_same_verdicts(design, results[0.0])
    # a smoothing lets the fit leave the points by sqrt(s / n) in the mean (Dierckx sec. 5.2): the
    # accuracy judged to grows with it, and the pair built changes
    accuracies = [results[s]["defect_accuracy"] for s in (0.0, 0.1, 10.0)]
    assert accuracies[0] < accuracies[1] < accuracies[2]
    areas = [results[s]["female_flute_area"] for s in (0.0, 0.1, 10.0)]
    assert len({round(a, 6) for a in areas}) == 3


def _bulged_polyline(points: np.ndarray, every: int) -> np.ndarray:
    """Rows (x, y, bulge) of a closed LWPOLYLINE of arcs, each through three consecutive points."""
    n = len(points)
    start = np.linspace(0, n, n // every, endpoint=False).astype(int)
    end = np.append(start[1:], n)
    p0, pm, p1 = points[start], points[(start + end) // 2 % n], points[end % n]
    # the arc through p0, pm, p1: included angle 2 * (angle at pm between the chords), signed
    a, b = p0 - pm, p1 - pm
    inscribed = np.arctan2(a[:, 0] * b[:, 1] - a[:, 1] * b[:, 0], np.einsum("ij,ij->i", a, b))
    included = 2.0 * (inscribed - np.sign(inscribed) * np.pi)
    return np.column_stack([p0, np.tan(included / 4.0)])


def test_bulged_polyline_accepted_by_rotor_as_by_clearance(verdicts, written, tmp_path, capsys):
    # the finding: an LWPOLYLINE of arcs within 1.1 um of the outline, accepted by clearance, refused by rotor
    lobe = np.vstack([seg.resampled(1e-3).points for seg in _rack_involute().male_lobe().segments])
    lobe = lobe[np.concatenate([[True], np.hypot(*np.diff(lobe, axis=0).T) > 1e-9])][:-1]
    male = np.vstack([lobe @ np.array([[np.cos(a), np.sin(a)], [-np.sin(a), np.cos(a)]]) for a in np.radians(72) * np.arange(5)])
    rows = _bulged_polyline(male, 2)
    doc = ezdxf.new("R2000")
    doc.modelspace().add_lwpolyline(rows.tolist(), format="xyb", close=True)
    path = tmp_path / "bulged.dxf"
    doc.saveas(path)
    # independent check of the drawing: its arcs, sampled by ezdxf, lie within 1.1 um of the outline
    entity = next(iter(ezdxf.readfile(path).modelspace()))
    flat = np.array([(v.x, v.y) for v in ezdxf.path.make_path(entity).flattening(1e-5)])
    exact = shapely.LineString(np.vstack([seg.resampled(1e-5).points for seg in _rack_involute().male_lobe().segments]))
    whole = shapely.MultiLineString([shapely.affinity.rotate(exact, 72 * k, origin=(0, 0)) for k in range(5)])
    assert float(shapely.distance(shapely.points(flat), whole).max()) < 1.1e-3
    rc, out, err = run(capsys, "rotor", "--male-points", path, *DIMS_56, *RADII_56, "--json")
    assert rc == 0, err
    assert_same_verdicts(verdicts[("rack_involute_5_6", "design")], json.loads(out))
    rc, _, err = run(capsys, "clearance", "--male-points", path, "--female-points", written["female"], *DIMS_56, "--json")
    assert rc == 0, err


@functools.cache
def _rack_involute():
    spec = pair_spec(rotor_design(tomllib.loads((SAMPLES / "rack_involute_5_6.toml").read_text()), SAMPLES))
    return build_pair(spec)


def _one_groove(female: np.ndarray) -> np.ndarray:
    """Return the female's points from one tip land to the next (a groove, as a CMM measures it)."""
    r = np.hypot(*female.T)
    tip = np.flatnonzero(r >= r.max() - 1e-4)  # the tip land
    k = int(np.argmax(np.diff(tip)))
    return female[tip[k] : tip[k + 1] + 1]


def test_one_groove_is_enough(verdicts, written, tmp_path, capsys):
    # the finding: a female given as one groove was refused; rotor, clearance and hob take it
    groove = _one_groove(read_points(written["female"], "f"))
    span = np.degrees(np.ptp(np.unwrap(np.arctan2(groove[:, 1], groove[:, 0]))))
    assert 20 < span < 55  # less than the pitch of 60 deg: not one lobe
    path = tmp_path / "groove.csv"
    write_points(path, groove)
    rc, out, err = run(capsys, "rotor", "--female-points", path, *DIMS_56, *RADII_56, "--json")
    assert rc == 0, err
    got, design = json.loads(out), verdicts[("rack_involute_5_6", "design")]
    assert_same_verdicts(design, got)
    rc, _, err = run(capsys, "clearance", "--male-points", written["male"], "--female-points", path, *DIMS_56, "--json")
    assert rc == 0, err
    rc, out, err = run(capsys, "hob", "--female-points", path, *DIMS_56, *RADII_56, "--json")
    assert rc == 0, err
    assert "hobbable" in json.loads(out)


def test_wrong_lobe_count_names_the_option_once(written, capsys):
    # the finding: the lobe-count refusal of clearance printed "----male-points"
    dims = ["--male-teeth", "4", "--female-teeth", "6", "--center-distance", "116"]
    rc, _, err = run(capsys, "clearance", "--male-points", written["male"], "--female-points", written["female"], *dims)
    assert rc == 2
    assert "--male-points" in err and "----" not in err


def test_api_outline_at_one_nanometre_chord():
    # the finding: the API outline at a 1 nm chord gave 107 defects
    rotors = _rack_involute()
    design = analyse_pair(rotors, 3000.0)[1]
    pts = np.vstack([seg.resampled(1e-6).points for seg in rotors.male_lobe().segments])
    given = analyse_pair(pair_from_rotor_points(rotors.pair, pts, "male"), 3000.0)[1]
    assert_same_verdicts(design, given)


@pytest.mark.parametrize("given", ["whole", "groove"])
def test_blow_hole_from_the_female_points(verdicts, written, tmp_path, capsys, given):
    # issue 21 item 3: the blow-hole within 1 % whatever form the profile comes in (here: the female's
    # own CSV, whole or one groove). Before: +5.6 % (whole) and +4.3 % (groove): from the female's
    # points the male sealing tip corner's path left the tip circle in the last millimetre before it
    # meets the female's involute, and the meshline's end (the corner) came out 0.11 mm off
    path = written["female"]
    if given == "groove":
        path = tmp_path / "groove.csv"
        write_points(path, _one_groove(read_points(written["female"], "f")))
    rc, out, err = run(capsys, "rotor", "--female-points", path, *DIMS_56, *RADII_56, "--json")
    assert rc == 0, err
    design = verdicts[("rack_involute_5_6", "design")]
    assert json.loads(out)["blow_hole_area"] == pytest.approx(design["blow_hole_area"], rel=0.01)


def _n_rack_tip_round():
    """The N rack pair, its male sealing tip round (centre, radius; a Kasa fit of the design's segment)."""
    spec = pair_spec(rotor_design(tomllib.loads((SAMPLES / "n_rack_5_6.toml").read_text()), SAMPLES))
    rotors = build_pair(spec)
    pts = next(s for s in rotors.male_lobe().segments if s.name == "sealing tip circle").points
    a = np.column_stack([2 * pts, np.ones(len(pts))])
    cx, cy, c0 = np.linalg.lstsq(a, (pts**2).sum(axis=1), rcond=None)[0]
    rho = float(np.sqrt(c0 + cx**2 + cy**2))
    assert np.abs(np.hypot(*(pts - (cx, cy)).T) - rho).max() < 1e-9  # it is a circle
    return rotors, np.array([cx, cy]), rho


@pytest.mark.parametrize("form", ["csv", "dense"])
def test_n_rack_tip_round_meshline_from_points(form):
    # issue 21 item 3 (a): from points, the meshline of the male's sealing tip round came out with two
    # or three samples over 30 mm (the fit's parameter spends 0.67 mm of profile on it), its tangent
    # 7-9 mrad off, and cusps there. Reference, a closed form: a male circle (centre Q, radius rho)
    # touches where its normal passes through the pitch point C, X(t) = Q_t - rho (C - Q_t) / |C - Q_t|
    # with Q_t = R(t) Q, whose tangent is dX/dt = J Q_t + rho (I - u u^T) J Q_t / |C - Q_t| (u the unit
    # vector to C, J the quarter turn); the design's own meshline follows it to 1e-12 mm.
    from rotorcad.meshing import MeshingAnalysis, meshline_tangents

    rotors, q, rho = _n_rack_tip_round()
    pair = rotors.pair
    c = np.array([pair.male_pitch_radius, 0.0])

    def closed(t):
        qt = np.column_stack([q[0] * np.cos(t) - q[1] * np.sin(t), q[0] * np.sin(t) + q[1] * np.cos(t)])
        jq = np.column_stack([-qt[:, 1], qt[:, 0]])
        d = c - qt
        dist = np.hypot(*d.T)[:, None]
        u = d / dist
        v = jq + rho * (jq - u * np.einsum("ij,ij->i", u, jq)[:, None]) / dist
        return qt - rho * u, v / np.hypot(*v.T)[:, None]

    design = MeshingAnalysis(rotors)
    tip = next(p for p in design.pieces if p.name == "sealing tip circle")
    assert np.hypot(*(tip.points - closed(tip.t)[0]).T).max() < 1e-9
    if form == "csv":
        pts = np.asarray(design.sections[0].exterior.coords)[:-1]  # what `rotor --male-csv` writes
    else:
        pts = np.vstack([seg.resampled(1e-5).points for seg in rotors.male_lobe().segments])
    given = MeshingAnalysis(pair_from_rotor_points(pair, pts, "male"))
    piece = next(p for p in given.pieces if np.sum((p.t > 0.02) & (p.t < 0.49) & (np.hypot(*p.points.T) > q[0])) > 0)
    on = (piece.t > np.radians(1.0)) & (piece.t < np.radians(28.0)) & (np.hypot(*piece.points.T) > q[0])
    assert on.sum() >= 100  # the 1-28 deg of the round's 30 deg sampled along the meshline, not two or three
    arclen = np.concatenate([[0.0], np.cumsum(np.hypot(*np.diff(piece.points, axis=0).T))])
    tau = meshline_tangents(piece, arclen, given.judged_accuracy)[on]
    x, v = closed(piece.t[on])
    assert np.hypot(*(piece.points[on] - x).T).max() < 10 * given.judged_accuracy
    turn = np.abs(np.arcsin(np.clip(v[:, 0] * tau[:, 1] - v[:, 1] * tau[:, 0], -1.0, 1.0)))
    assert turn.max() < given.tolerance  # within the cusp test's tangent tolerance (1 mrad), not 7-9 mrad off


def test_clearance_angles_in_the_one_convention(verdicts, written, tmp_path, capsys):
    # issue 21 item 4: the clearance CSV's male_angle_deg was the engine's male rotation (another zero,
    # the opposite sign, over more than one lobe), not `rotor`'s count. References: (1) the male tip
    # land is on O1O2 exactly while the middle of the tip passes it, phi in +-w/2 with w the land's
    # polar width (the design's tip arc segment): the rows touching at the tip point are symmetric
    # about 0; (2) the design's meshline angle in
    # `rotor`'s count (MeshingAnalysis.kinematics, its own passage) at the same contact point
    from scipy.spatial import cKDTree

    from rotorcad.meshing import MeshingAnalysis

    path = tmp_path / "c.csv"
    given = ["--male-points", written["male"], "--female-points", written["female"]]
    rc, _, err = run(capsys, "clearance", *given, *DIMS_56, "--csv", path)
    assert rc == 0, err
    lines = [line for line in path.read_text().splitlines() if line and not line.startswith("#")]
    header, rows = lines[0].split(","), np.array([[float(v) for v in line.split(",")] for line in lines[1:]])
    col = dict(zip(header, rows.T, strict=True))
    on = col["in_contact"] == 1
    contact, phi = np.column_stack([col["contact_x"], col["contact_y"]])[on], col["male_angle_deg"][on]
    assert np.all(np.abs(phi) <= 180.0 / 5 + 1e-9)  # one lobe's window, root to root
    rotors = _rack_involute()
    pair = rotors.pair
    land = next(s for s in rotors.male_lobe().segments if s.name == "tip arc").points
    half = 0.5 * np.degrees(np.ptp(np.arctan2(land[:, 1], land[:, 0])))
    at_tip = np.hypot(contact[:, 0] - pair.male_tip_radius, contact[:, 1]) < 1e-2
    assert at_tip.sum() > 10
    assert abs(phi[at_tip].min() + phi[at_tip].max()) < 0.05
    assert phi[at_tip].max() <= half + 0.1
    analysis = MeshingAnalysis(rotors)
    dist, idx = cKDTree(analysis.meshline).query(contact)
    c = np.array([pair.male_pitch_radius, 0.0])
    away = (dist < 0.02) & (np.abs(contact[:, 1]) > 0.05) & (np.hypot(*(contact - c).T) > 1.0)  # off the lands and C
    assert away.sum() > 1000
    assert np.abs(phi[away] - analysis.kinematics["angle_deg"][idx[away]]).max() < 0.1


def test_scatter_report_names_its_accuracy(written, tmp_path, capsys):
    # issue 21 item 3: the report says at what accuracy it judged. The rack-involute male's own CSV with
    # 1 um of scatter: the profile's accuracy is twice the scatter (about 2 um), the meshline's normals
    # are judged to 10 times that, over sqrt(8 a e) of meshline (a = 116 mm, e = 20 um: 4.3 mm)
    male = read_points(written["male"], "m")
    path = tmp_path / "scattered.csv"
    write_points(path, male + np.random.default_rng(0).normal(0.0, SCATTER, male.shape))
    rc, out, err = run(capsys, "rotor", "--male-points", path, *DIMS_56, *RADII_56)
    assert rc == 0, err
    line = next(ln for ln in out.splitlines() if "defects judged to an accuracy of" in ln)
    profile, normals = (float(v) for v in re.findall(r"([0-9.]+) µm", line))
    assert profile == pytest.approx(2.0, rel=0.15) and normals == pytest.approx(10 * profile, rel=0.06)
    reach = float(re.search(r"over ([0-9.]+) mm of meshline", line).group(1))
    assert reach == pytest.approx(np.sqrt(8 * 116.0 * normals * 1e-3), rel=0.05)
    # and the blow-hole with the uncertainty its apex has from the points' tangents (blow_hole_uncertainty)
    hole = next(ln for ln in out.splitlines() if ln.strip().startswith("blow-hole") and "±" in ln)
    area, plus = (float(v) for v in re.findall(r"([0-9.]+)", hole)[:2])
    assert 0.0 < plus < area


@pytest.mark.parametrize("name", ROTOR_SAMPLES)
def test_design_blow_hole_within_stated_uncertainty(verdicts, name):
    # reference: the design's blow-hole from its exact curves. Points with 1 um of scatter state how far
    # their blow-hole may be off (blow_hole_uncertainty, from the tangent accuracy over one point spacing);
    # the design's value must lie within it (plus the 1 % or closed-meshline floor of test_same_blow_hole)
    design, given = verdicts[(name, "design")], verdicts[(name, "scatter-1um")]
    floor = 1e-3 if design["blow_hole_area"] <= 1e-9 else 0.01 * design["blow_hole_area"]
    gap = abs(given["blow_hole_area"] - design["blow_hole_area"])
    assert gap <= given["blow_hole_uncertainty"] + floor, (gap, given["blow_hole_uncertainty"])
    assert design["blow_hole_uncertainty"] == 0.0  # exact curves: no input accuracy to propagate


@pytest.mark.parametrize("form", ["csv", "dense", *EVEN_PHASES])
@pytest.mark.parametrize("name", ROTOR_SAMPLES)
def test_exact_points_state_their_blow_hole_uncertainty(verdicts, name, form):
    # reference: the design's blow-hole from its exact curves. Exact points carry no scatter, but their
    # interpolating fit's tangent is off where the points do not resolve the outline (a tip rounding with
    # 2-3 points on it, UNRESOLVED_BLOW_HOLE): the uncertainty they state holds the design's value there and
    # everywhere, and the 0.01 um chord's (which resolves the outline) states less than 300 points a lobe
    design, given = verdicts[(name, "design")], verdicts[(name, form)]
    floor = 1e-3 if design["blow_hole_area"] <= 1e-9 else 0.01 * design["blow_hole_area"]
    gap = abs(given["blow_hole_area"] - design["blow_hole_area"])
    assert gap <= given["blow_hole_uncertainty"] + floor, (gap, given["blow_hole_uncertainty"])
    if form == "dense" and design["blow_hole_area"] > 1e-9:
        assert 0.0 < given["blow_hole_uncertainty"] < min(verdicts[(name, f)]["blow_hole_uncertainty"] for f in EVEN_PHASES)
    departs = (name, form) in KNOWN_BLOW_HOLE  # (the N rack's unresolved even scans are now within 1 %)
    if departs:  # the departure is stated, not hidden
        assert given["blow_hole_uncertainty"] > gap > 0.01 * design["blow_hole_area"]


@pytest.mark.parametrize("seed", [1, 2])
@pytest.mark.parametrize("name", ROTOR_SAMPLES)
def test_blow_hole_within_uncertainty_other_seeds(verdicts, name, seed):
    # every sample at two more seeds of 1 um scatter (seed 0 above): the design's blow-hole (reference: its
    # exact curves) within the points' stated uncertainty plus the floor of test_same_blow_hole, and where
    # the design has a blow-hole the uncertainty is less than the area itself (not vacuous); and within 1 %
    # where seed 0 is (a tip corner's hand-over placed by its flank's generating line, rotorcad.meshing.generating_line:
    # over seeds 0-7 -0.58..+0.50 %, where the flank's end tangent read -9.8..+7.7 %)
    design = verdicts[(name, "design")]
    male = verdicts[(name, "male")]
    noisy = male + np.random.default_rng(seed).normal(0.0, SCATTER, male.shape)
    given = _given(verdicts[(name, "spec")], noisy, "--male-points")
    closed = design["blow_hole_area"] <= 1e-9
    floor = 1e-3 if closed else 0.01 * design["blow_hole_area"]
    gap = abs(given["blow_hole_area"] - design["blow_hole_area"])
    assert gap <= given["blow_hole_uncertainty"] + floor
    assert closed or 0.0 < given["blow_hole_uncertainty"] < design["blow_hole_area"]
    if (name, "scatter-1um") not in KNOWN_BLOW_HOLE:  # issue 21 item 3: within 1 % at these seeds too, not by chance
        acc = given["defect_accuracy"]  # or the closed meshline's floor of test_same_blow_hole
        floor = max(1e-3, MESHLINE_GAIN * acc * resolution(acc, given["center_distance"]))
        assert given["blow_hole_area"] == pytest.approx(design["blow_hole_area"], rel=0.01, abs=floor)


def test_blow_hole_apex_moves_with_tangent_as_stated():
    # independent method: turn the normal of the male point at the design's apex by 1 mrad (in the rotor)
    # and find by bisection the male angle where that normal passes through the pitch point C again; the
    # apex's move along its circle must match r delta / |beta' - 1| used by blow_hole_uncertainty
    # (0.13 mm per mrad measured on the narrow-tip by the verdict-noise benchmark), within 2 %
    from rotorcad.roots import bracket_root

    spec = pair_spec(rotor_design(tomllib.loads((SAMPLES / "narrow_tip_5_6.toml").read_text()), SAMPLES))
    analysis, _ = analyse_pair(build_pair(spec), spec.speed_rpm)
    e = analysis.meshline_end
    r, phi0 = float(np.hypot(*e)), float(np.arctan2(e[1], e[0]))
    c = np.array([spec.pair.male_pitch_radius, 0.0])
    psi0 = float(np.arctan2(*(c - e)[::-1])) - phi0  # the normal through C, in the rotor's frame

    def miss(phi: float, delta: float) -> float:
        x = r * np.array([np.cos(phi), np.sin(phi)])
        n = np.array([np.cos(psi0 + delta + phi), np.sin(psi0 + delta + phi)])
        v = c - x
        return float(n[0] * v[1] - n[1] * v[0])

    phi1 = bracket_root(lambda p: miss(p, 1e-3), (phi0 - 0.02, phi0 + 0.02), xtol=1e-14)
    moved = r * abs(phi1 - phi0)
    v, dx = c - e, r * np.array([-np.sin(phi0), np.cos(phi0)])
    rate = (v[0] * -dx[1] - v[1] * -dx[0]) / (v @ v)
    assert moved == pytest.approx(r * 1e-3 / abs(rate - 1.0), rel=0.02)
    assert moved == pytest.approx(0.13, rel=0.1)  # the benchmark's measured figure (mm per mrad)


# ---- the symmetric SRM's apex from its lobe arc (rotorcad.meshing.apex) ---------------------------


def test_fit_circle_recovers_a_known_circle():
    # reference: the construction. 1 um of normal scatter on 300 points of a 130 deg arc of radius 14 mm
    # about (28.28, 28.28) (the symmetric SRM's lobe arc): the centre within 1 um (over 300 seeds its RMS
    # error is 0.24 um, the largest 0.7 um), the radius too; exact points to 1e-9 mm
    from rotorcad.meshing.apex import fit_circle

    q, rho = np.array([28.28427, 28.28427]), 14.0
    th = np.radians(np.linspace(0.0, 130.0, 300))
    pts = q + rho * np.column_stack([np.cos(th), np.sin(th)])
    centre, radius = fit_circle(pts)
    assert np.hypot(*(centre - q)) < 1e-9 and abs(radius - rho) < 1e-9
    noisy = pts + np.random.default_rng(0).normal(0.0, 1e-3 / np.sqrt(2), pts.shape)
    centre, radius = fit_circle(noisy)
    assert np.hypot(*(centre - q)) < 1e-3 and abs(radius - rho) < 1e-3


def test_circle_bounds_hold_the_refitted_circles():
    # independent method, brute force: every sample of a 60 deg arc moved along its normal by +-e (random
    # signs, and the worst sign pattern of each parameter), the circle refitted: its centre and radius move
    # within circle_bounds (to 1 % for the linearisation), and the worst pattern reaches 90 % of the bound
    from rotorcad.meshing.apex import circle_bounds, fit_circle

    q, rho, e = np.array([3.0, -2.0]), 14.0, 2e-3
    th = np.radians(np.linspace(20.0, 80.0, 120))
    normal = np.column_stack([np.cos(th), np.sin(th)])
    pts = q + rho * normal
    bound = circle_bounds(pts, q, rho, e)
    rng = np.random.default_rng(0)
    d = pts - q
    jac = np.column_stack([-d / np.hypot(*d.T)[:, None], -np.ones(len(pts))])
    worst = np.sign(np.linalg.pinv(jac))  # per parameter, the signs that move it most
    patterns = [rng.choice([-1.0, 1.0], len(pts)) for _ in range(50)] + list(worst) + list(-worst)
    moves = []
    for signs in patterns:
        centre, radius = fit_circle(pts - e * signs[:, None] * normal)  # distance from q changes by -e * sign
        moves.append(np.abs(np.array([*(centre - q), radius - rho])))
    moves = np.array(moves)
    assert np.all(moves <= 1.01 * bound)
    assert np.all(moves.max(axis=0) >= 0.9 * bound)


def test_symmetric_srm_apex_closed_form(verdicts):
    # reference, a closed form (Rinder sec. 2.2.1: the symmetric SRM's arc is centred on the pitch point
    # when it touches): the male lobe arc (radius rho, centre on the pitch circle) touches along its whole
    # length at the instant its centre passes C, so that stretch of meshline is the circle of radius rho
    # about C, and its point nearest the cusp K is C + rho (K - C) / |K - C|. The design's apex (the envelope
    # engine's meshline) and the apex from the arc's closed-form meshline (rotorcad.meshing.apex) both on it
    from rotorcad.meshing.apex import circle_meshline_apex, fit_circle

    spec = verdicts[("srm_symmetric_4_6", "spec")]
    rotors = build_pair(spec)
    pair = rotors.pair
    arc = next(s for s in rotors.male_lobe().segments if s.name == "lobe arc").resampled(1e-4).points
    q, rho = fit_circle(arc)
    assert np.abs(np.hypot(*(arc - q).T) - rho).max() < 1e-9  # it is a circle
    assert np.hypot(*q) == pytest.approx(pair.male_pitch_radius, abs=1e-9)  # centred on the pitch circle
    c = np.array([pair.male_pitch_radius, 0.0])
    k = np.array(pair.housing_cusp)
    closed = c + rho * (k - c) / np.hypot(*(k - c))
    design = verdicts[("srm_symmetric_4_6", "design")]["blow_hole_spatial"]["apex"][:2]
    assert np.hypot(*(np.array(design) - closed)) < 1e-4
    bores = ((np.zeros(2), pair.male_tip_radius), (np.array([pair.center_distance, 0.0]), pair.female_tip_radius))
    apex = circle_meshline_apex(q, rho, c, k, closed, 1.0, bores)
    assert np.hypot(*(apex - closed)) < 1e-4


_LOST_TIP_PATHS = (
    "seed {0} loses a female tip path (defects 2/3, the {1} cusp): on the rack these paths run 1.2-1.6 mm, at "
    "the resolution below which rotorcad.measured.pairs calls a corner path a flank (1.7 mm at 1 um), and the "
    "meshline's nearest point to the cusp is then a contact of the male root: {2}, within the stated {3} "
    "(which seeds lose a path changed with each change of the corner fits: seed 1 read -10.7, +0.1, -9.6 %)"
)


@pytest.mark.parametrize(
    "seed",
    [
        1,  # read -9.6 % (a lost driving tip path); within 1 % since this branch's pairs.py changes (which one: not isolated)
        2,
        # seed 3 lost a female tip path (_LOST_TIP_PATHS: -13.0 %, within the stated 10.1 mm²) until a male lobe arc's
        # closed-form apex came before a hand-over on the female tip circle (MeshingAnalysis._apex)
        3,
    ],
)
def test_symmetric_srm_blow_hole_from_scatter(verdicts, seed):
    # issue 21 item 3: the symmetric SRM's blow-hole from 1 um scattered points within 1 % of the design's
    # (reference: its exact curves). Before: -6.8, -10.7, +0.6, -6.8 % at seeds 0-3 (the nearest meshline point
    # moved 0.2-1.5 mm along a meshline that runs at one distance from the cusp); its apex now comes from the
    # closed form meshline of the fitted lobe arc (seed 0 in test_same_blow_hole). Its stated uncertainty
    # (from how far the arc's centre and radius may move, rotorcad.meshing.apex.circle_bounds) holds the
    # design's value and is below 5 % of the area (the tangent's bound was 4.8-6.8 mm², 7-10 %)
    name = "srm_symmetric_4_6"
    male = verdicts[(name, "male")]
    noisy = male + np.random.default_rng(seed).normal(0.0, SCATTER, male.shape)
    given = _given(verdicts[(name, "spec")], noisy, "--male-points")
    design = verdicts[(name, "design")]["blow_hole_area"]
    assert given["blow_hole_area"] == pytest.approx(design, rel=0.01)
    assert abs(given["blow_hole_area"] - design) <= given["blow_hole_uncertainty"] < 0.05 * design


# ---- an arc about C recognised from positions (rotorcad.meshing.defects.arcs_about) ----------------


def test_arcs_about_finds_the_arc_and_not_a_crossing():
    # reference, a closed form: a meshline that follows a circle of radius rho about q for s in [0, 20] mm
    # (its normal through q all along: Rinder's exception at C) and then a straight tangent line, whose
    # distance from q grows as sqrt(rho^2 + s^2) - rho (about s^2 / (2 rho)), gives one stretch, from the
    # arc's start to where that growth reaches the spread. A normal that passes q at one point only
    # (a meshline of curvature kappa off the circle's) leaves the distance by kappa w^2 / 8 over a window w
    # centred on it: no arc for kappa above 8 spread / span^2, an arc below
    from rotorcad.meshing.defects import arcs_about

    q, rho, span, spread = np.array([40.0, 0.0]), 14.0, 2.0, 5e-3
    th = np.linspace(0.0, 20.0 / rho, 2001)
    arc = q + rho * np.column_stack([np.cos(th), np.sin(th)])
    tangent = np.array([-np.sin(th[-1]), np.cos(th[-1])])
    line = arc[-1] + np.outer(np.linspace(0.01, 10.0, 1000), tangent)
    pts = np.vstack([arc, line])
    arclen = np.concatenate([[0.0], np.cumsum(np.hypot(*np.diff(pts, axis=0).T))])
    stretches = arcs_about(np.hypot(*(pts - q).T), arclen, span, spread)
    assert len(stretches) == 1 and stretches[0][0] == 0
    s_end = np.sqrt((rho + spread) ** 2 - rho**2)  # where the line leaves the circle by the spread
    assert arclen[stretches[0][1]] == pytest.approx(20.0 + s_end, abs=0.02)
    for kappa, expected in ((16 * spread / span**2, 0), (2 * spread / span**2, 1)):
        s = np.linspace(-10.0, 10.0, 2001)
        distance = rho + 0.5 * kappa * s**2  # the distance from q near the point whose normal passes q
        assert len(arcs_about(distance, s + 10.0, span, spread)) == expected, kappa


# ---- a corner's path across O1O2, and a corner between exact points (issue 21 item 3) --------------


def test_tip_corner_across_o1o2_is_the_tip_of_both_flanks(verdicts):
    # reference: Rinder sec. 2.2.2 ("Am Haupt- bzw. Nebenläuferkopf ist demnach nur eine Spitze oder Ecke
    # als Flanke denkbar") and the Krigar profile's symmetry: its male tip corner's path runs along the male
    # tip circle equally far either side of O1O2, so it is the corner of both flanks, named by the lobe part
    # it crosses O1O2 on (the tip), not by the side of O1O2 its middle falls on (y = +0.06 mm in the design,
    # -0.17 mm from 300 exact points a lobe at phase 0.8, which read "driving" before)
    for form in ("design", *EVEN_PHASES):
        s = verdicts[("krigar_4_6", form)]
        (tip,) = [d for d in s["defects"] if d["kind"] == "cusp" and d["rotor"] == "male"]
        assert tip["flank_role"] == "tip" and tip["point_generated"] and tip["tip_corner"], form
        assert tip["extent"] == pytest.approx(2 * 35.14, rel=0.01), form  # both halves of the path
        for flank in ("driving", "sealing"):
            assert s["flanks"][flank]["tip_corners"] == ["female", "male"], (form, flank)


@pytest.mark.parametrize("seed", [3, 4])
def test_tip_corner_across_o1o2_from_scatter(verdicts, seed):
    # the same rule through 1 um of scatter (reference: the design's defects, its exact curves): seeds 3 and 4
    # named Krigar's male tip corner "driving" before (its middle 0.1-0.2 mm below O1O2), the design "sealing"
    male = verdicts[("krigar_4_6", "male")]
    noisy = male + np.random.default_rng(seed).normal(0.0, SCATTER, male.shape)
    given = _given(verdicts[("krigar_4_6", "spec")], noisy, "--male-points")
    assert Counter(map(_key, given["defects"])) == Counter(map(_key, verdicts[("krigar_4_6", "design")]["defects"]))


def test_corner_between_exact_points_is_found_between_them():
    # reference: the design's exact male (shapely distance to its curves). 300 exact points a lobe at phase
    # 0.8 put Krigar's male tip corner 0.2 of a spacing from the nearest point, which turns by over 90 % of
    # the corner: kept as the corner, it left the fit 25 um inside the tip at the tip and 7.8 um at 0.1-0.5 mm
    # below it (and the rounded tip meshed as a flank over 22 mm of meshline). Where the fits beside it cross,
    # the fit follows the design within 0.1 um to the tip
    from rotorcad.curves import sample_curve
    from rotorcad.measured.fit import lobe_pieces

    spec = pair_spec(rotor_design(tomllib.loads((SAMPLES / "krigar_4_6.toml").read_text()), SAMPLES))
    rotors = build_pair(spec)
    dense = np.vstack([seg.resampled(1e-5).points for seg in rotors.male_lobe().segments])
    z = spec.pair.male_teeth
    points = _evenly(dense, z, EVEN_PER_LOBE, EVEN_PHASES["even-300-b"])
    fitted = np.vstack([sample_curve(curve, 1e-5)[1] for _, curve in lobe_pieces(spec.pair, points, "male")])
    exact = shapely.MultiLineString([shapely.LineString(patterned(dense, z))])
    near_tip = np.hypot(*fitted.T) > spec.pair.male_tip_radius - 1.0
    assert near_tip.sum() > 20
    gap = shapely.distance(shapely.points(fitted[near_tip]), exact).max()
    assert gap < 1e-4, gap


def test_unresolved_blow_hole_is_said(verdicts, tmp_path, capsys):
    # issue 21 item 3: where the points do not resolve the blow-hole (the N rack male's tip rounding with 3 of 300
    # points a lobe on it, the first at the lobe's start: its circle through them, radius 1.27 mm for 1.036, and the
    # flank's cross 0.57 mrad apart, for 0.42 that the accuracy allows, so the model does not hold and the points'
    # spacing along the rounding stands, ±73 mm², +7.8 %; reference its exact curves. At phase 0.8, before the
    # circles' own bound, 0.44 mm² read, then 1.737, and it resolves now), the JSON says so and the text names it;
    # the design's value lies within the stated uncertainty
    name = "n_rack_5_6"
    spec = verdicts[(name, "spec")]
    dense = np.vstack([seg.resampled(1e-5).points for seg in build_pair(spec).male_lobe().segments])
    path = tmp_path / "even.csv"
    write_points(path, _evenly(dense, spec.pair.male_teeth, EVEN_PER_LOBE, 0.0))
    pair = tomllib.loads((SAMPLES / f"{name}.toml").read_text())["pair"]
    dims = []
    for key in ("male_teeth", "female_teeth", "center_distance", *(k for k in pair if k.endswith("_radius"))):
        dims += [f"--{key.replace('_', '-')}", repr(pair[key])]
    rc, out, err = run(capsys, "rotor", "--male-points", path, *dims)
    assert rc == 0, err
    line = next(ln for ln in out.splitlines() if ln.strip().startswith("blow-hole") and "±" in ln)
    assert "not resolved" in line and "closer together" in line
    area, plus = (float(v) for v in re.findall(r"([0-9.]+)", line)[:2])
    design = verdicts[(name, "design")]["blow_hole_area"]
    assert abs(area - design) <= plus and plus > area


def test_tip_corner_across_o1o2_from_the_females_points():
    # the same rule from the female's exact points, 300 a lobe (a CMM's scan, as tests/test_mate_points.py builds
    # them): the rack derived from them ends its pieces on O1O2 and split Krigar's male tip corner's path there into
    # two, which read as two cusps (driving and sealing) for the design's one across O1O2 (the tip), until two such
    # paths of one corner (their points turned back into the male within the resolution of each other) were made one.
    # Reference: the design's defects, from its exact curves; its rack-involute male's two tip corners (the ends of
    # its tip land, 0.2 mm apart on the male) stay two (test_same_defects_and_running)
    from independent_pairs import scan

    spec = pair_spec(rotor_design(tomllib.loads((SAMPLES / "krigar_4_6.toml").read_text()), SAMPLES))
    female = _exterior(build_pair(spec).section("female", tolerance=1e-5))
    points = scan(female, spec.pair.female_teeth * EVEN_PER_LOBE, 0.37)
    given = analyse_pair(
        build_pair(PairSpec(spec.pair, "female-points", {}, points, None, spec.speed_rpm, 0.0), label="--female-points"),
        spec.speed_rpm,
    )[1]
    design = analyse_pair(build_pair(spec), spec.speed_rpm)[1]
    assert_same_verdicts(design, given)
    (tip,) = [d for d in given["defects"] if d["kind"] == "cusp" and d["rotor"] == "male"]
    assert tip["flank_role"] == "tip" and tip["extent"] == pytest.approx(2 * 35.14, rel=0.05)


FINE_CHORD = 1e-5  # mm: the finest chord users write the sample at (newuser4 N1)


def _main_json(*args) -> dict:
    """``rotorcad *args --json --quiet`` run in this process; its JSON."""
    import contextlib
    import io

    buffer = io.StringIO()
    with contextlib.redirect_stdout(buffer):
        assert main([str(a) for a in args] + ["--json", "--quiet"]) == 0
    return json.loads(buffer.getvalue())


@pytest.fixture(scope="module")
def fine_csv(tmp_path_factory) -> dict:
    """The rack-involute sample's outlines written at a 0.01 um chord and read back by ``rotor`` and ``hob``.

    References: the design's own analysis and hob verdict from its exact curves (``rotor`` and ``hob`` of
    the sample file), not from any points.
    """
    folder = tmp_path_factory.mktemp("fine_csv")
    design = SAMPLES / "rack_involute_5_6.toml"
    files = {side: folder / f"{side}.csv" for side in ("male", "female")}
    out = {"files": files}
    out["design"] = _main_json(
        "rotor", design, "--tolerance", FINE_CHORD, "--male-csv", files["male"], "--female-csv", files["female"]
    )
    out["design hob"] = _main_json("hob", design)
    pair = tomllib.loads(design.read_text())["pair"]
    given = [f"--{k.replace('_', '-')}={v}" for k, v in pair.items() if k != "hand"]
    # the male as rotor wrote it before: clipped by the 2048-gon inscribed in tip + 1 nm (ScrewRotors.section
    # without exact_tip), its sealing tip corner 72 nm inside the tip, on a chord of the clip
    disk = shapely.Point(0, 0).buffer(pair["male_tip_radius"] + 1e-6, quad_segs=512)
    files["old male"] = folder / "old_male.csv"
    write_points(files["old male"], _exterior(shapely.Polygon(read_points(files["male"])).intersection(disk)))
    for name, path in files.items():
        side = name.split()[-1]
        out[name] = _main_json("rotor", f"--{side}-points", path, *given)
        out[f"{name} hob"] = _main_json("hob", f"--{side}-points", path, *given)
    return out


@pytest.mark.parametrize("side", ["male", "female"])
def test_fine_csv_outline_does_not_cross_itself(fine_csv, side):
    # newuser4 N1 asked whether the written outline crosses itself: it does not, but its tip land was the chords
    # of the section's clip (a 2048-gon), 75-82 nm inside the tip circle at a 10 nm chord. References: shapely
    # (GEOS), an independent reader: the closed ring is simple; the tip circle (the pair's tip radius): no point
    # outside it, and every chord between two points on it within the chord tolerance of it at its middle.
    pts = read_points(fine_csv["files"][side])
    assert shapely.LinearRing(pts).is_simple
    tip = tomllib.loads((SAMPLES / "rack_involute_5_6.toml").read_text())["pair"][f"{side}_tip_radius"]
    r = np.hypot(*pts.T)
    assert r.max() <= tip + FINE_CHORD
    on_tip = np.abs(r - tip) <= FINE_CHORD
    both = on_tip & np.roll(on_tip, -1)
    assert both.sum() >= 10  # the tip lands are there
    middle = 0.5 * (pts + np.roll(pts, -1, axis=0))[both]
    assert np.hypot(*middle.T).min() >= tip - FINE_CHORD, np.sort(np.hypot(*middle.T) - tip)[:5]


@pytest.mark.parametrize("side", ["male", "female", "old male"])
def test_fine_csv_reads_back_as_the_design(fine_csv, side):
    # newuser4 N1: rotorcad's own male outline at a 0.01 um chord read back without its sealing tip-corner
    # cusp, a sealing meshline of 29.20 mm (design 54.56), the slip singularity on both driving flanks, and in
    # `hob` "not hobbable, 3.434 deg" (design hobbable, 18.127 deg): the section's clip (a 2048-gon inscribed in
    # the tip circle) wrote the sealing tip corner 72 nm inside the tip, and the reader moved it past the next
    # point: "old male" is that file, read back since rotorcad.measured.corner_fits._turns_back. Reference: the
    # design's own analysis and hob verdict from its exact curves.
    design, given = fine_csv["design"], fine_csv[side]
    assert_same_verdicts(design, given)
    assert given["runs_without_timing_gears"] == design["runs_without_timing_gears"]
    assert given["blow_hole_area"] == pytest.approx(design["blow_hole_area"], rel=0.01)
    for flank, report in design["flanks"].items():
        assert given["flanks"][flank]["meshline_length"] == pytest.approx(report["meshline_length"], rel=0.01), flank
    want, got = design["slip_singularities"], given["slip_singularities"]
    assert Counter(map(_slip_key, got)) == Counter(map(_slip_key, want)), got
    hob_design, hob_given = fine_csv["design hob"], fine_csv[f"{side} hob"]
    assert hob_given["hobbable"] == hob_design["hobbable"], hob_given["reasons"]
    assert hob_given["normal_pressure_angle_min_deg"] == pytest.approx(hob_design["normal_pressure_angle_min_deg"], abs=0.03)

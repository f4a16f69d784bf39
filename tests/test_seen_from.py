"""A transverse section seen from the discharge end face (a new user's N4): ``--seen-from``.

rotorcad's sections are seen from the suction end (CONTRACT.md, points files): the male turns
counter-clockwise there, the driving flanks lie below the line of centres (y < 0). A CMM that
scans the section from the discharge end gives the mirror image (y -> -y); read as it stands, that
is the mirror-image rotor, whose meshing analysis swaps the design's driving and sealing verdicts
(the finding: exit 0, no note). References: the design's own ``rotor samples/X.toml --json`` (the
per-flank verdicts from its exact curves), and the mirror image made here by numpy (y -> -y of the
outline ``rotor --male-csv`` / ``--female-csv`` writes), not by the code under test.
"""

from __future__ import annotations

import functools
import json
import tomllib
from collections import Counter
from pathlib import Path

import numpy as np
import pytest
from independent_pairs import patterned, scan

from exports.csv_points import read_points, write_points
from exports.dxf import Drawing, write_dxf
from exports.dxf_profile import read_profile
from rotorcad.cli.main import main
from rotorcad.design import rotor_design
from rotorcad.measured.end_face import MIRROR_FIT, design_deviation, mirror_note, mirrored, section_points
from rotorcad.roles import EndFace, Side
from rotorcad.rotor_build import build_pair, pair_spec

SAMPLES = Path(__file__).resolve().parents[1] / "samples"
CASES = [("srm_asymmetric_5_6", "male"), ("lysholm_4_6", "female")]  # asymmetric profiles: the mirror is another rotor


def run(capsys, *args) -> tuple[int, str, str]:
    rc = main([str(a) for a in args])
    out = capsys.readouterr()
    return rc, out.out, out.err


@functools.cache
def _design_run(name: str, rotor: str, folder: str) -> tuple[dict, Path, Path]:
    """The design's JSON, its rotor's outline as ``rotor`` writes it, and that outline's mirror image (y -> -y)."""
    here = Path(folder)
    csv, json_path = here / f"{name}_{rotor}.csv", here / f"{name}.json"
    import contextlib
    import io

    text = io.StringIO()
    with contextlib.redirect_stdout(text):
        assert main(["rotor", str(SAMPLES / f"{name}.toml"), "--json", "--quiet", f"--{rotor}-csv", str(csv)]) == 0
    design = json.loads(text.getvalue())
    pts = read_points(csv, "outline")
    flipped = here / f"{name}_{rotor}_mirror.csv"
    write_points(flipped, np.column_stack([pts[:, 0], -pts[:, 1]]))  # the section seen from the discharge end
    json_path.write_text(json.dumps(design))
    return design, csv, flipped


@pytest.fixture(scope="module")
def folder(tmp_path_factory) -> str:
    return str(tmp_path_factory.mktemp("seen_from"))


def _defects(data: dict) -> Counter:
    return Counter((d["kind"], d["rotor"], d["flank_role"]) for d in data["defects"])


@pytest.fixture(scope="module")
def readings(folder) -> dict:
    """Per case: the design, the mirrored section read with --seen-from discharge, and read as it stands."""
    import contextlib
    import io
    import warnings

    out = {}
    for name, rotor in CASES:
        design, _, flipped = _design_run(name, rotor, folder)
        got = {}
        for face in ("discharge", None):
            extra = [] if face is None else ["--seen-from", face]
            text, err = io.StringIO(), io.StringIO()
            with contextlib.redirect_stdout(text), contextlib.redirect_stderr(err), warnings.catch_warnings():
                args = ["rotor", str(SAMPLES / f"{name}.toml"), f"--{rotor}-points", str(flipped), "--json", "--quiet"]
                assert main(args + extra) == 0
            got[face] = (json.loads(text.getvalue()), err.getvalue())
        out[(name, rotor)] = design, got
    return out


@pytest.mark.parametrize(("name", "rotor"), CASES)
def test_mirrored_section_seen_from_discharge_gives_the_design_flanks(readings, name, rotor):
    # the finding: the srm_asymmetric male mirrored read driving eps 0.184 / sealing 0.002 (the design's
    # sealing / driving); read with --seen-from discharge: the design's per flank, and its defects by flank
    design, got = readings[(name, rotor)]
    data, err = got["discharge"]
    assert data["seen_from"] == "discharge"
    assert _defects(data) == _defects(design)
    for flank in ("driving", "sealing"):
        want, have = design["flanks"][flank], data["flanks"][flank]
        assert have["runs_without_timing_gears"] == want["runs_without_timing_gears"], flank
        assert have["transverse_contact_ratio"] == pytest.approx(want["transverse_contact_ratio"], abs=0.02), flank
    assert data["runs_without_timing_gears"] == design["runs_without_timing_gears"]
    assert "--seen-from" not in err  # read right: no note
    assert data["design_deviation"]["as_read"] < MIRROR_FIT < data["design_deviation"]["mirrored"]


@pytest.mark.parametrize(("name", "rotor"), CASES)
def test_mirrored_section_read_as_it_stands_swaps_the_flanks_and_says_so(readings, name, rotor):
    # the mirror-image rotor, analysed right: the design's driving flank's ratio on its sealing flank and
    # vice versa; a note names --seen-from discharge (was: exit 0, nothing said)
    design, got = readings[(name, rotor)]
    data, err = got[None]
    assert data["seen_from"] == "suction"
    for flank, other in (("driving", "sealing"), ("sealing", "driving")):
        want = design["flanks"][other]["transverse_contact_ratio"]
        assert data["flanks"][flank]["transverse_contact_ratio"] == pytest.approx(want, abs=0.02), flank
    assert "--seen-from discharge" in err and err.count("\n") == 1, err
    assert data["design_deviation"]["mirrored"] < MIRROR_FIT < data["design_deviation"]["as_read"]


# ---- no note on the forms of tests/test_verdict_invariance.py (unmirrored) ---------------------------------

ROTOR_SAMPLES = [p.stem for p in sorted(SAMPLES.glob("*.toml")) if "profile" in tomllib.loads(p.read_text())]


def _forms(name: str, folder: Path) -> tuple[dict[str, np.ndarray], np.ndarray, int]:
    """The male of sample ``name`` in test_verdict_invariance's forms (its own CSV and DXF drawings, dense
    exact points, 300 a lobe evenly along the outline at two phases, 1 µm scatter), the design's whole
    male outline and the lobe count."""
    spec = pair_spec(rotor_design(tomllib.loads((SAMPLES / f"{name}.toml").read_text()), SAMPLES))
    rotors = build_pair(spec)
    pts = np.asarray(rotors.section(Side.MALE, 1e-3, exact_tip=True).exterior.coords)[:-1]  # as `rotor --male-csv`
    forms: dict[str, np.ndarray] = {"csv": pts}
    for form, drawing in (("dxf-polyline", Drawing(outlines=[("MALE", pts)])), ("dxf-spline", Drawing(splines=[("MALE", pts)]))):
        path = folder / f"{name}_{form}.dxf"
        write_dxf(path, drawing)
        forms[form] = read_profile(path, "--male-points", "MALE")  # curves
    dense = np.vstack([seg.resampled(1e-5).points for seg in rotors.male_lobe().segments])
    forms["dense"] = dense
    z = spec.pair.male_teeth
    for form, phase in (("even-300", 0.37), ("even-300-b", 0.8)):
        forms[form] = scan(patterned(dense, z), 300 * z, phase)
    forms["scatter-1um"] = pts + np.random.default_rng(0).normal(0.0, 1e-3, pts.shape)
    return forms, rotors.male_outline(1e-3).points, z


@pytest.mark.parametrize("name", ROTOR_SAMPLES)
def test_no_mirror_note_on_unmirrored_forms(tmp_path, name):
    # every form of the verdict-invariance test lies on the design's outline (within MIRROR_FIT = 10 um RMS
    # after the best turn: 1 um scatter reads ~1 um), so no note at any stated accuracy; its mirror image
    # does get the note when the profile is asymmetric (0.23-3.5 mm RMS off), none when symmetric
    forms, outline, z = _forms(name, tmp_path)
    for form, given in forms.items():
        pts = section_points(given, Side.MALE, z, 100.0, "--male-points")  # as `rotor` reads it
        as_read, mirror = design_deviation(pts, outline, z)
        assert as_read < MIRROR_FIT, (form, as_read)
        assert mirror_note(as_read, mirror, 0.0, EndFace.SUCTION, "--male-points") is None, form
    as_read, mirror = design_deviation(mirrored(forms["csv"]), outline, z)
    symmetric = name in ("krigar_4_6", "srm_symmetric_4_6")
    note = mirror_note(as_read, mirror, 2e-3, EndFace.SUCTION, "--male-points")
    assert (note is None) == symmetric, (name, as_read, mirror)
    if note is not None:
        assert "--seen-from discharge" in note


# ---- the option on every command that reads points; bad values ---------------------------------------------


@pytest.mark.parametrize("value", ["top", "", "suction-end", "1"])
@pytest.mark.parametrize("command", ["rotor", "hob", "clearance"])
def test_bad_seen_from_is_one_sentence_exit_2(capsys, tmp_path, command, value, folder):
    _, csv, _ = _design_run("srm_asymmetric_5_6", "male", folder)
    if command == "clearance":
        args = ["clearance", "--male-points", csv, "--female-points", csv, "--male-teeth", 5, "--female-teeth", 6]
        args += ["--center-distance", 116]
    else:
        args = [command, SAMPLES / "srm_asymmetric_5_6.toml", "--male-points", csv]
    rc, out, err = run(capsys, *args, "--seen-from", value, "--json")
    assert rc == 2 and out == ""
    assert err.count("\n") == 1 and "--seen-from must be suction or discharge" in err and "Traceback" not in err


@pytest.mark.parametrize(
    "args",
    [
        ["rotor", SAMPLES / "srm_asymmetric_5_6.toml"],  # a design's own profile: no section to mirror
        ["hob", SAMPLES / "srm_asymmetric_5_6.toml"],
        ["hob", "--teeth", 20, "--module", 2],  # a gear
    ],
)
def test_seen_from_discharge_without_points_is_refused(capsys, args):
    rc, out, err = run(capsys, *args, "--seen-from", "discharge")
    assert rc == 2 and out == "" and err.count("\n") == 1
    assert "--seen-from discharge needs --male-points or --female-points" in err


def test_hob_of_a_mirrored_male_seen_from_discharge_is_the_unmirrored_males(capsys, folder):
    # the finding: hob --male-points of the mirrored male put the flank-angle minimum at x = -8.017 mm; with
    # --seen-from discharge the racks are those of the male as the design's CSV gives it (reference: the
    # unmirrored points, read by the same command)
    _, csv, flipped = _design_run("srm_asymmetric_5_6", "male", folder)
    sample = SAMPLES / "srm_asymmetric_5_6.toml"
    rc, plain, _ = run(capsys, "hob", sample, "--male-points", csv, "--json")
    assert rc == 0
    rc, fixed, _ = run(capsys, "hob", sample, "--male-points", flipped, "--seen-from", "discharge", "--json")
    assert rc == 0
    plain, fixed = json.loads(plain), json.loads(fixed)
    assert fixed["seen_from"] == "discharge" and plain["seen_from"] == "suction"
    assert fixed["hobbable"] == plain["hobbable"]
    for rotor in ("male", "female"):
        for key in ("hob_tip_thickness", "hob_root_radius"):
            assert fixed["racks"][rotor][key] == pytest.approx(plain["racks"][rotor][key], abs=2e-3), (rotor, key)
    assert sorted(fixed["reasons"]) == sorted(plain["reasons"])


def test_clearance_of_a_mirrored_pair_seen_from_discharge_is_the_unmirrored_pairs(capsys, tmp_path):
    # a pair with a different designed clearance on each flank (driving 10 um, sealing 30 um, rotor --clearance):
    # the mirrored pair read as it stands brings the racks into contact on the design's sealing flank (mean
    # clearance 19 um); --seen-from discharge reads the unmirrored pair's figures (reference: the unmirrored files)
    sample = SAMPLES / "srm_asymmetric_5_6.toml"
    male, female = tmp_path / "m.csv", tmp_path / "f.csv"
    designed = ["--clearance", "driving=0.01,sealing=0.03"]
    rc, _, err = run(capsys, "rotor", sample, *designed, "--male-csv", male, "--female-csv", female)
    assert rc == 0, err
    flipped = {}
    for path in (male, female):
        pts = read_points(path, "outline")
        flipped[path] = tmp_path / f"{path.stem}_mirror.csv"
        write_points(flipped[path], np.column_stack([pts[:, 0], -pts[:, 1]]))
    dims = ["--male-teeth", 5, "--female-teeth", 6, "--center-distance", 116, "--json", "--quiet"]
    readings = {}
    for tag, files, extra in (
        ("plain", (male, female), []),
        ("mirror", (flipped[male], flipped[female]), []),
        ("fixed", (flipped[male], flipped[female]), ["--seen-from", "discharge"]),
    ):
        rc, out, err = run(capsys, "clearance", "--male-points", files[0], "--female-points", files[1], *dims, *extra)
        assert rc == 0, err
        readings[tag] = json.loads(out)
    plain, mirror, fixed = readings["plain"], readings["mirror"], readings["fixed"]
    assert fixed["seen_from"] == "discharge" and plain["seen_from"] == "suction"
    for key in ("max_normal_clearance", "min_normal_clearance", "mean_clearance", "female_rack_shift"):
        assert fixed[key] == pytest.approx(plain[key], abs=1e-6), key
    assert plain["mean_clearance"] == pytest.approx(0.01, abs=2e-3)  # contact on the driving flank: its 10 um
    assert mirror["mean_clearance"] > plain["mean_clearance"] + 5e-3  # the finding: the other flank's contact


def test_unmirrored_section_read_from_discharge_says_so(capsys, folder):
    # the other mistake: --seen-from discharge given for a section seen from the suction end (the design's
    # own CSV): the note names --seen-from suction
    _, csv, _ = _design_run("srm_asymmetric_5_6", "male", folder)
    rc, out, err = run(
        capsys, "rotor", SAMPLES / "srm_asymmetric_5_6.toml", "--male-points", csv, "--seen-from", "discharge", "--json"
    )
    assert rc == 0
    assert json.loads(out)["seen_from"] == "discharge"
    assert "give --seen-from suction" in err and err.count("\n") == 1, err


def test_mirrored_female_off_its_design_by_a_designed_clearance_is_noted(capsys, tmp_path):
    # a made rotor lies off its design (here the female thinned by 10 / 30 um on its flanks, rotor --clearance:
    # 17 um RMS): its mirror image is still noted (the mirror image 4 times nearer than the points as read),
    # the unmirrored one is not
    sample = SAMPLES / "srm_asymmetric_5_6.toml"
    female = tmp_path / "f.csv"
    rc, _, err = run(capsys, "rotor", sample, "--clearance", "driving=0.01,sealing=0.03", "--female-csv", female)
    assert rc == 0, err
    pts = read_points(female, "outline")
    flipped = tmp_path / "f_mirror.csv"
    write_points(flipped, np.column_stack([pts[:, 0], -pts[:, 1]]))
    rc, out, err = run(capsys, "rotor", sample, "--female-points", female, "--json", "--quiet")
    assert rc == 0 and "--seen-from" not in err, err
    assert MIRROR_FIT < json.loads(out)["design_deviation"]["as_read"] < 0.03  # off its design by the clearance
    rc, out, err = run(capsys, "rotor", sample, "--female-points", flipped, "--json", "--quiet")
    assert rc == 0 and "give --seen-from discharge" in err, err


def test_drawing_mirrored_in_cad_seen_from_discharge_reads_as_the_drawing(capsys, tmp_path):
    # export's exact B-spline drawing of the male (MALE_SPLINE), mirrored by ezdxf (Matrix44.scale(1, -1, 1),
    # a third-party transform of the entities): read with --seen-from discharge, the figures of the drawing
    # as exported (reference: the unmirrored drawing through the same reader)
    sample = SAMPLES / "srm_asymmetric_5_6.toml"
    rc, _, err = run(capsys, "export", sample, "--format", "dxf", "--out", tmp_path, "--no-housing", "--quiet")
    assert rc == 0, err
    import ezdxf
    from ezdxf.math import Matrix44

    drawn = tmp_path / "srm_asymmetric_5_6_male.dxf"
    doc = ezdxf.readfile(drawn)
    for entity in doc.modelspace():
        entity.transform(Matrix44.scale(1, -1, 1))
    flipped = tmp_path / "male_mirror.dxf"
    doc.saveas(flipped)
    common = ["--layer", "MALE_SPLINE", "--json", "--quiet"]
    readings = {}
    for tag, path, extra in (("plain", drawn, []), ("fixed", flipped, ["--seen-from", "discharge"])):
        rc, out, err = run(capsys, "rotor", sample, "--male-points", path, *common, *extra)
        assert rc == 0 and "--seen-from" not in err, err
        readings[tag] = json.loads(out)
    plain, fixed = readings["plain"], readings["fixed"]
    assert _defects(fixed) == _defects(plain)
    for flank in ("driving", "sealing"):
        for key in ("transverse_contact_ratio", "working_length", "meshline_length"):
            assert fixed["flanks"][flank][key] == pytest.approx(plain["flanks"][flank][key], rel=1e-6, abs=1e-9), (flank, key)
    assert fixed["blow_hole_area"] == pytest.approx(plain["blow_hole_area"], rel=1e-6)


def test_mirrored_curves_are_the_curves_flipped():
    # each kind of curve a drawing is read into, mirrored, against its own samples flipped y -> -y by numpy
    from rotorcad.curves import Arc, Line, Mapped, Spline, sample_curve

    spline = Spline.fit(np.column_stack([np.linspace(0, 10, 12), np.sin(np.linspace(0, 3, 12))]))
    curves = [
        Line((1.0, 2.0), (3.0, -1.0)),
        Arc((2.0, 1.0), 3.0, 0.2, 1.4),
        spline,
        Mapped(Line((0, 0), (1, 1)), ((2, 0), (0, 1))),
    ]
    flipped = mirrored(curves)
    assert len(flipped) == len(curves)
    for original, mirror in zip(curves, reversed(flipped), strict=True):
        s = np.linspace(original.s0, original.s1, 7)
        p = original.evaluate(s)[0]
        q = mirror.evaluate(np.linspace(mirror.s1, mirror.s0, 7))[0]  # travelled backwards: the same points
        np.testing.assert_allclose(q, p * [1.0, -1.0], atol=1e-12)
    points = sample_curve(curves[1], 1e-3)[1]
    np.testing.assert_allclose(mirrored(points), (points * [1.0, -1.0])[::-1], atol=0)


def test_inspect_of_a_mirrored_section_says_so_and_reads_it_with_seen_from(capsys, folder):
    # rotorcad inspect judges a rotor's points against its outline per flank: the mirrored male was refused as
    # 2.4 mm off with no hint; the refusal names --seen-from discharge, and with it the points read as the
    # unmirrored ones (reference: the design's own CSV, inspected the same way)
    sample = SAMPLES / "srm_asymmetric_5_6.toml"
    _, csv, flipped = _design_run("srm_asymmetric_5_6", "male", folder)
    rc, out, err = run(capsys, "inspect", sample, "--points", flipped, "--json")
    assert rc == 2 and out == "" and err.count("\n") == 1 and "give --seen-from discharge" in err, err
    readings = {}
    for tag, path, extra in (("plain", csv, []), ("fixed", flipped, ["--seen-from", "discharge"])):
        rc, out, err = run(capsys, "inspect", sample, "--points", path, "--json", *extra)
        assert rc == 0 and "--seen-from" not in err, err
        readings[tag] = json.loads(out)
    assert readings["fixed"]["seen_from"] == "discharge"
    for key in ("max_normal_deviation", "min_normal_deviation"):
        assert readings["fixed"][key] == pytest.approx(readings["plain"][key], abs=1e-6), key
    rc, _, err = run(capsys, "inspect", "--teeth", 20, "--module", 2, "--points", csv, "--seen-from", "discharge")
    assert rc == 2 and "--seen-from is for a screw rotor's section" in err

"""``rotorcad gear``, ``cut`` and ``export`` for internal gears (CONTRACT.md): keys, files read back by third-party
readers, and bad input refused with one sentence naming the option or design key (exit 2).

References: OpenCASCADE's volume of the STEP solid and trimesh's of the STL against the closed form
pi R^2 L minus the bore's area x L (shapely's area of the bore polygon sampled to 0.1 um); ezdxf's
reading of the drawing; the polar angles of ISO 21771 for the bore read back from the CSV.
"""

from __future__ import annotations

import json
import math
from pathlib import Path

import ezdxf
import numpy as np
import pytest
import shapely

from exports.csv_points import read_points
from rotorcad.cli.main import main

ROOT = Path(__file__).resolve().parents[1]
SAMPLE = ROOT / "samples" / "internal_gear.toml"
SMALL = ["--internal", "--teeth", 30, "--module", 1, "--shift", 0.4, "--addendum", 0.8]
SMALL += ["--cutter-teeth", 15, "--cutter-shift", 0.3, "--cutter-tip-radius", 0.1]


def run(capsys, *args):
    rc = main([str(a) for a in args])
    out = capsys.readouterr()
    return rc, out.out, out.err


def test_gear_json_of_the_sample(capsys, tmp_path):
    rc, out, err = run(
        capsys, "gear", SAMPLE, "--json", "--quiet", "--csv", tmp_path / "ring.csv", "--dxf", tmp_path / "ring.dxf"
    )
    assert rc == 0, err
    data = json.loads(out)
    assert data["internal"] is True and data["cutter"]["teeth"] == 20 and data["mate"]["pitch_radius"] == 41.0
    # ISO 21771 / DIN 3993: alpha_w = alpha for x1 = x2, a = (z2 - z1) m / 2
    assert data["center_distance"] == pytest.approx(19.0, abs=1e-12)
    assert data["working_pressure_angle_deg"] == pytest.approx(20.0, abs=1e-9)
    assert data["outer_radius"] == 70.0 and data["tip_radius"] == pytest.approx(60.0 - (0.8 - 0.3) * 2.0)
    pts = read_points(tmp_path / "ring.csv")
    r = np.hypot(*pts.T)
    assert r.min() == pytest.approx(data["tip_radius"], abs=1e-9) and r.max() == pytest.approx(data["root_radius"], abs=1e-9)
    assert Path(tmp_path / "ring_mate.csv").exists()
    msp = ezdxf.readfile(tmp_path / "ring.dxf").modelspace()
    layers = {e.dxf.layer for e in msp}
    assert {"GEAR", "OUTER", "MATE", "LINE_OF_ACTION"} <= layers
    outer = [e for e in msp.query("CIRCLE") if e.dxf.layer == "OUTER"]
    assert len(outer) == 1 and outer[0].dxf.radius == pytest.approx(70.0)
    # the line of action runs tangent to both base circles (ISO 21771): T2 on the ring's, T1 on the pinion's
    line = next(e for e in msp.query("LINE") if e.dxf.layer == "LINE_OF_ACTION")
    t2, t1 = np.array(line.dxf.start)[:2], np.array(line.dxf.end)[:2]
    u = (t1 - t2) / np.linalg.norm(t1 - t2)

    def cross(a, b):
        return a[0] * b[1] - a[1] * b[0]

    assert abs(cross(u, t2)) == pytest.approx(data["base_radius"], abs=1e-9)  # distance of the line from O2
    assert abs(cross(u, t1 - [data["center_distance"], 0.0])) == pytest.approx(data["mate"]["base_radius"], abs=1e-9)


@pytest.mark.parametrize(
    ("args", "message"),
    [
        (["--internal", "--teeth", 60, "--module", 2], "--cutter-teeth is required for an internal gear"),
        (["--internal", "--teeth", 60, "--module", 2, "--cutter-teeth", 20], "--teeth must be at least 64 for a 20-tooth cutter"),
        ([*SMALL, "--cutter-tip-radius", 0.5], "--cutter-tip-radius must be from 0 to 0.1252"),
        ([*SMALL, "--outer-diameter", 20], "--outer-diameter must be from"),
        ([*SMALL, "--span-teeth", 3], "--span-teeth must not be given for an internal gear"),
        ([*SMALL, "--mate-teeth", 30], "--mate-teeth must be a whole number from 3 to 29"),
        (["--teeth", 30, "--module", 1, "--cutter-teeth", 15], "--cutter-teeth must be given with --internal"),
        (["--internal", "--teeth", 30, "--module", 1, "--cutter-teeth", 12, "--shift", 0.3, "--addendum", 0.8],
         "--addendum must be at most 0.7013 for a 12-tooth cutter"),
    ],
)  # fmt: skip
def test_bad_input_names_the_option(capsys, args, message):
    rc, out, err = run(capsys, "gear", *args)
    assert rc == 2 and out == ""
    assert message in err and "Traceback" not in err
    assert err.count("\n") == 1  # one sentence


def test_bad_design_key_is_named(capsys, tmp_path):
    design = tmp_path / "ring.toml"
    design.write_text("[gear]\nteeth = 60\nmodule = 2.0\n\n[shaper]\nteeth = 20\n")
    rc, _, err = run(capsys, "gear", design)
    assert rc == 2 and "[gear] teeth must be at least 64 for a 20-tooth cutter" in err
    design.write_text("[gear]\nteeth = 60\nmodule = 2.0\nshift = 0.3\naddendum = 0.8\n\n[shaper]\nteeth = 20\nshift = 9.0\n")
    rc, _, err = run(capsys, "gear", design)
    assert rc == 2 and "[shaper] shift must be between -1 and 1.5 modules (got 9)" in err
    design.write_text("[gear]\nteeth = 60\nmodule = 2.0\n\n[shaper]\nteth = 20\n")
    rc, _, err = run(capsys, "gear", design)
    assert rc == 2 and "teth" in err


def test_interfering_pinion_is_refused_with_its_smallest_tooth_difference(capsys):
    # trochoid interference for a 54-tooth pinion in the sample's 60-tooth ring (x = 0.3, h_aP* = 0.8):
    # the closed form (tests/test_internal_gear.py) allows z2 - z1 >= 7
    rc, _, err = run(capsys, "gear", SAMPLE, "--mate-teeth", 54)
    assert rc == 2 and "[gear] teeth must be at least 61 for a 54-tooth pinion" in err and "trochoid" in err


def test_cut_shapes_the_space_within_the_scallop(capsys, tmp_path):
    rc, out, err = run(capsys, "cut", *SMALL, "--tolerance", 5e-4, "--json", "--quiet", "--dxf", tmp_path / "cut.dxf")
    assert rc == 0, err
    data = json.loads(out)
    assert data["tolerance_met"] and data["max_deviation_from_envelope"] <= 5e-4
    assert data["tooth_thickness_pitch"] == pytest.approx(data["tooth_thickness_pitch_exact"], abs=5e-4)
    layers = {e.dxf.layer for e in ezdxf.readfile(tmp_path / "cut.dxf").modelspace()}
    assert {"GEAR_SIMULATED", "GEAR_ANALYTIC"} <= layers


def test_export_step_stl_dxf_of_a_ring(capsys, tmp_path):
    design = tmp_path / "ring.toml"
    design.write_text(
        "[gear]\nteeth = 30\nmodule = 1.0\nshift = 0.4\naddendum = 0.8\nouter_diameter = 40.0\nface_width = 4.0\n\n"
        "[shaper]\nteeth = 15\nshift = 0.3\ntip_radius = 0.1\n"
    )
    rc, out, err = run(capsys, "export", design, "--out", tmp_path / "out", "--format", "step,stl,dxf", "--json", "--quiet")
    assert rc == 0, err
    rows = {r["format"]: r for r in json.loads(out)["files"]}
    rc, out, _ = run(capsys, "gear", design, "--json", "--quiet", "--tolerance", 1e-6, "--csv", tmp_path / "bore.csv")
    bore = shapely.Polygon(read_points(tmp_path / "bore.csv"))  # chords within 1 nm: its area within some 1e-4 mm^2
    exact = (math.pi * 20.0**2 - bore.area) * 4.0  # mm^3
    from OCP.BRepGProp import BRepGProp
    from OCP.GProp import GProp_GProps
    from OCP.STEPControl import STEPControl_Reader

    reader = STEPControl_Reader()
    reader.ReadFile(rows["step"]["path"])
    reader.TransferRoots()
    props = GProp_GProps()
    BRepGProp.VolumeProperties_s(reader.OneShape(), props, 1e-9)  # adaptive integration to 1e-9
    # the bore's faces lie within the deviation the export measured (some 10 nm): the volume within that band
    band = bore.length * 4.0 * rows["step"]["tolerance"]
    assert rows["step"]["tolerance"] < 1e-4 and abs(props.Mass() - exact) <= 1.5 * band + 1e-4
    import trimesh

    mesh = trimesh.load(rows["stl"]["path"])
    assert mesh.is_watertight and mesh.volume == pytest.approx(exact, rel=2e-3)
    polylines = [e for e in ezdxf.readfile(rows["dxf"]["path"]).modelspace().query("LWPOLYLINE") if e.dxf.layer == "GEAR"]
    radii = sorted(float(np.hypot(*np.array([p[:2] for p in e.get_points()]).T).max()) for e in polylines)
    assert len(polylines) == 2 and radii[1] == pytest.approx(20.0, abs=1e-9)  # the bore and the outer circle
    assert radii[0] == pytest.approx(json.loads(out)["root_radius"], abs=1e-6)


def test_report_of_an_internal_gear(capsys, tmp_path):
    rc, out, err = run(capsys, "report", SAMPLE, "--out", tmp_path / "ring.html", "--json")
    assert rc == 0, err
    data = json.loads(out)
    assert data["kind"] == "gear" and data["hobbable"] is False  # shaped, not hobbed: said as the reason
    page = (tmp_path / "ring.html").read_text(encoding="utf-8")
    assert "cutting_trochoid_margin_deg" in page and "shaper cutter" in page and "<svg" in page


@pytest.mark.parametrize(
    ("args", "message"),
    [
        (["--positions", 100000], "--positions must be at most"),
        (["--tolerance", 1e-9], "--tolerance must be at least"),
        (["--tolerance", 0.5], "--tolerance must be at most 0.2 mm"),
        (["--plot", "x.png"], "--plot must not be given for an internal gear"),
    ],
)
def test_cut_refusals(capsys, args, message):
    rc, out, err = run(capsys, "cut", SAMPLE, *args)
    assert rc == 2 and out == "" and message in err and err.count("\n") == 1

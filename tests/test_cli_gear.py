"""``rotorcad gear`` as CONTRACT.md specifies it: keys, files, and bad input."""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import ezdxf
import numpy as np
import pytest
import shapely
from matplotlib import image

from exports.csv_points import read_points
from rotorcad.cli.main import main
from rotorcad.gear import GearPair, InvoluteGear

ROOT = Path(__file__).resolve().parents[1]
DEG = np.pi / 180
CONTRACT_KEYS = {"pitch_radius", "base_radius", "tip_radius", "root_radius", "tooth_thickness_pitch", "form_radius", "undercut"}
PAIR_KEYS = CONTRACT_KEYS | {"center_distance", "working_pressure_angle_deg", "contact_ratio"}


def run(capsys, *args):
    rc = main([str(a) for a in args])
    out = capsys.readouterr()
    return rc, out.out, out.err


def test_json_keys_and_values(capsys):
    rc, out, err = run(capsys, "gear", "--teeth", 21, "--module", 2.5, "--shift", 0.2, "--json")
    assert rc == 0 and err == ""
    data = json.loads(out)
    assert CONTRACT_KEYS <= set(data)
    m = 2.5
    assert data["pitch_radius"] == pytest.approx(21 * m / 2)
    assert data["base_radius"] == pytest.approx(21 * m / 2 * np.cos(20 * DEG))
    assert data["tooth_thickness_pitch"] == pytest.approx(m * (np.pi / 2 + 2 * 0.2 * np.tan(20 * DEG)), abs=1e-9)
    assert data["undercut"] is False


def test_pair_with_center_distance_derives_the_mate_shift(capsys):
    rc, out, _ = run(capsys, "gear", "--teeth", 20, "--module", 2, "--mate-teeth", 30, "--center-distance", 51, "--json")
    data = json.loads(out)
    assert rc == 0 and PAIR_KEYS <= set(data)
    assert data["center_distance"] == 51
    assert data["working_pressure_angle_deg"] == pytest.approx(np.degrees(np.arccos(50 * np.cos(20 * DEG) / 51)), abs=1e-10)
    assert abs(data["backlash"]) < 1e-8


def test_files_written_and_read_back(tmp_path, capsys):
    dxf, csv, png = tmp_path / "p.dxf", tmp_path / "g.csv", tmp_path / "p.png"
    rc, out, _ = run(
        capsys,
        "gear",
        "--teeth",
        17,
        "--module",
        3,
        "--shift",
        0.3,
        "--mate-teeth",
        29,
        "--mate-shift",
        -0.1,
        "--dxf",
        dxf,
        "--csv",
        csv,
        "--plot",
        png,
        "--json",
    )
    assert rc == 0
    data = json.loads(out)
    g = InvoluteGear(17, 3.0, shift=0.3)
    pair = GearPair(g, InvoluteGear(29, 3.0, shift=-0.1))
    # CSV: the gear outline, and the mate next to it
    pts = read_points(csv)
    np.testing.assert_allclose(pts, g.outline().points, atol=1e-9)
    mate = read_points(tmp_path / "g_mate.csv")
    assert shapely.Polygon(mate).area == pytest.approx(pair.mate.outline().area, rel=1e-9)
    # DXF: audit clean, millimetres, layers, closed polyline with the profile's area
    doc = ezdxf.readfile(dxf)
    assert len(doc.audit().errors) == 0
    assert doc.header["$INSUNITS"] == 4
    layers = {e.dxf.layer for e in doc.modelspace()}
    assert {"GEAR", "MATE", "PITCH", "BASE", "CENTER", "LINE_OF_ACTION"} <= layers
    poly = next(e for e in doc.modelspace().query("LWPOLYLINE") if e.dxf.layer == "GEAR")
    assert poly.closed
    assert shapely.Polygon(np.array(poly.get_points("xy"))).area == pytest.approx(g.outline().area, rel=1e-12)
    # PNG: a real picture
    img = image.imread(png)
    assert img.shape[0] > 300 and img.shape[1] > 300
    assert sorted(data["files"]) == sorted(str(p) for p in (dxf, csv, tmp_path / "g_mate.csv", png))


def test_design_file_and_out_folder(tmp_path, capsys):
    rc, out, _ = run(capsys, "gear", ROOT / "samples" / "gear_pair.toml", "--out", tmp_path / "o", "--json")
    assert rc == 0
    names = sorted(p.name for p in (tmp_path / "o").iterdir())
    assert names == ["gear.csv", "gear.dxf", "gear.png", "mate.csv"]
    data = json.loads(out)
    assert data["undercut"] is False and data["contact_ratio"] > 1.2


@pytest.mark.parametrize(
    "args,option",
    [
        (["--teeth", "2", "--module", "1"], "--teeth"),
        (["--teeth", "20", "--module", "0"], "--module"),
        (["--teeth", "20", "--module", "-2"], "--module"),
        (["--teeth", "20", "--module", "1", "--pressure-angle", "0"], "--pressure-angle"),
        (["--teeth", "20", "--module", "1", "--pressure-angle", "45"], "--pressure-angle"),
        (["--teeth", "20", "--module", "1", "--pressure-angle", "-5"], "--pressure-angle"),
        (["--teeth", "twenty", "--module", "1"], "--teeth"),
        (["--teeth", "20", "--module", "abc"], "--module"),
        (["--teeth", "20", "--module", "nan"], "--module"),
        (["--teeth", "20", "--module", "1", "--mate-teeth", "2"], "--mate-teeth"),
        (["--teeth", "20", "--module", "1", "--mate-teeth", "30", "--center-distance", "20"], "--center-distance"),
        (["--teeth", "20"], "--module"),
    ],
)
def test_bad_input_one_sentence_exit_2_no_file(tmp_path, capsys, args, option):
    target = tmp_path / "g.dxf"
    rc, out, err = run(capsys, "gear", *args, "--dxf", target, "--json")
    assert rc == 2
    assert out == ""
    lines = err.strip().splitlines()
    assert len(lines) == 1 and option in lines[0] and "Traceback" not in err
    assert not target.exists()
    assert list(tmp_path.iterdir()) == []


def test_existing_file_survives_bad_input(tmp_path, capsys):
    target = tmp_path / "keep.csv"
    target.write_text("x,y\n1,2\n")
    rc, _, _ = run(capsys, "gear", "--teeth", "1", "--module", "1", "--csv", target)
    assert rc == 2 and target.read_text() == "x,y\n1,2\n"


def test_unwritable_folder_is_refused_before_work(tmp_path, capsys):
    rc, _, err = run(capsys, "gear", "--teeth", 20, "--module", 1, "--dxf", tmp_path / "missing" / "g.dxf")
    assert rc == 2 and "--dxf" in err and len(err.strip().splitlines()) == 1


def test_unknown_design_key_is_named(tmp_path, capsys):
    design = tmp_path / "d.toml"
    design.write_text("[gear]\nteeth = 20\nmodule = 2\nshfit = 0.1\n")
    rc, _, err = run(capsys, "gear", design)
    assert rc == 2 and "shfit" in err and len(err.strip().splitlines()) == 1


def test_installed_command_runs_as_a_process(tmp_path):
    # The real process: exit status and stderr as a user sees them.
    cmd = [sys.executable, "-m", "rotorcad.cli.main", "gear", "--teeth", "2", "--module", "1"]
    proc = subprocess.run(cmd, capture_output=True, text=True, cwd=tmp_path)
    assert proc.returncode == 2 and proc.stdout == ""
    assert proc.stderr.count("\n") == 1 and "--teeth" in proc.stderr
    ok = subprocess.run([sys.executable, "-m", "rotorcad.cli.main", "gear", "--help"], capture_output=True, text=True)
    assert ok.returncode == 0 and "--pressure-angle" in ok.stdout and "[deg]" in ok.stdout


def test_plot_format_follows_the_suffix_for_every_command(tmp_path, capsys):
    # one mechanism (Outputs.add_figure) for all pictures: SVG read back by the standard XML parser,
    # an unknown suffix refused naming the option, nothing written
    import xml.etree.ElementTree as ET

    from rotorcad.cli.main import main

    svg = tmp_path / "g.svg"
    assert main(["gear", "--teeth", "17", "--module", "2", "--plot", str(svg)]) == 0
    assert ET.parse(svg).getroot().tag.endswith("svg")
    pump = tmp_path / "p.pdf"
    pump_args = ["--teeth", "11", "--module", "4", "--shift", "0.3", "--face-width", "20", "--speed", "1500"]
    assert main(["pump", *pump_args, "--plot", str(pump)]) == 0
    assert pump.read_bytes()[:5] == b"%PDF-"
    capsys.readouterr()
    assert main(["gear", "--teeth", "17", "--module", "2", "--plot", str(tmp_path / "g.jpg")]) == 2
    assert "--plot must name a .png, .svg or .pdf file" in capsys.readouterr().err
    assert not (tmp_path / "g.jpg").exists()


def test_a_pair_that_loses_contact_is_said(capsys):
    # A new user's finding (newuser5 F8): z = 11/11, m = 4, x = 0 printed contact_ratio 0.971 and
    # tip_interference true with exit 0 and no word. Reference: ISO 21771 eq. 5.4 written out here (the
    # tip-to-tip path over the base pitch, 1.396); rotorcad's ratio, on the usable involutes, is below 1.
    import math

    m, z, alpha = 4.0, 11, math.radians(20.0)
    r, ra = m * z / 2, m * z / 2 + m
    rb = r * math.cos(alpha)
    iso = (2 * math.sqrt(ra**2 - rb**2) - 2 * r * math.sin(alpha)) / (math.pi * m * math.cos(alpha))
    assert main(["gear", "--teeth", "11", "--module", "4", "--mate-teeth", "11", "--json"]) == 0
    out = capsys.readouterr()
    data = json.loads(out.out)
    assert data["contact_ratio"] < 1 and data["tip_interference"] is True
    assert out.err.count("\n") == 1 and "warning: the contact ratio is 0.971, below 1" in out.err
    assert f"tip-to-tip path gives {iso:.3f}" in out.err and "tip interference" in out.err
    # a pair in full contact: no word (z = 20/30, m = 2: ISO 1.63)
    assert main(["gear", "--teeth", "20", "--module", "2", "--mate-teeth", "30", "--json"]) == 0
    assert capsys.readouterr().err == ""

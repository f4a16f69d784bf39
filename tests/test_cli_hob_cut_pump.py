"""``rotorcad hob``, ``cut`` and ``pump`` as CONTRACT.md specifies them."""

from __future__ import annotations

import json
from pathlib import Path

import ezdxf
import numpy as np
import pytest

from exports.csv_points import read_points
from rotorcad.cli.main import main

SAMPLES = Path(__file__).resolve().parents[1] / "samples"


def run(capsys, *args):
    rc = main([str(a) for a in args])
    out = capsys.readouterr()
    return rc, out.out, out.err


def test_hob_gear_json_and_files(tmp_path, capsys):
    rc, out, err = run(
        capsys,
        "hob",
        "--teeth",
        24,
        "--module",
        2,
        "--shift",
        0.2,
        "--json",
        "--dxf",
        tmp_path / "h.dxf",
        "--csv",
        tmp_path / "r.csv",
    )
    assert rc == 0, err
    data = json.loads(out)
    assert {"hobbable", "reasons", "rack_deviation", "normal_pressure_angle_min_deg"} <= set(data)
    assert data["hobbable"] and data["reasons"] == []
    assert data["normal_pressure_angle_min_deg"] == pytest.approx(20.0, abs=1e-6)
    assert data["rack_deviation"] < 1e-6  # derived rack = the basic rack the gear was cut with
    doc = ezdxf.readfile(tmp_path / "h.dxf")
    assert len(doc.audit().errors) == 0 and {"RACK_GEAR", "HOB_TOOTH_GEAR"} <= {e.dxf.layer for e in doc.modelspace()}
    assert len(read_points(tmp_path / "r.csv")) > 100


def test_hob_rotor_pairs(capsys):
    rc, out, _ = run(capsys, "hob", SAMPLES / "rack_involute_5_6.toml", "--json")
    data = json.loads(out)
    assert rc == 0 and data["hobbable"] and data["rack_deviation"] < 1e-4
    rc, out, _ = run(capsys, "hob", SAMPLES / "srm_symmetric_4_6.toml", "--json")
    data = json.loads(out)
    assert rc == 0 and not data["hobbable"]
    assert any("perpendicular to the pitch line" in r for r in data["reasons"])


def test_cut_json(tmp_path, capsys):
    rc, out, err = run(
        capsys,
        "cut",
        "--teeth",
        11,
        "--module",
        2,
        "--tolerance",
        0.002,
        "--mate-teeth",
        11,
        "--json",
        "--dxf",
        tmp_path / "c.dxf",
        "--csv",
        tmp_path / "c.csv",
        "--plot",
        tmp_path / "c.png",
    )
    assert rc == 0, err
    data = json.loads(out)
    for key in (
        "undercut",
        "undercut_radius",
        "undercut_radius_model",
        "max_deviation_from_envelope",
        "tooth_thickness_pitch",
        "contact_ratio",
    ):
        assert key in data
    assert data["undercut"] is True and data["max_deviation_from_envelope"] <= 0.002
    # involute and trochoid meet at a shallow angle: the radius of P' is ~5x less sharp than the scallop
    assert data["undercut_radius"] == pytest.approx(data["undercut_radius_exact"], abs=10 * 0.002)
    assert data["tooth_thickness_pitch"] == pytest.approx(np.pi, abs=0.002)  # m pi / 2, x = 0
    doc = ezdxf.readfile(tmp_path / "c.dxf")
    assert {"GEAR_SIMULATED", "GEAR_ANALYTIC", "RACK", "HOB_TOOTH"} <= {e.dxf.layer for e in doc.modelspace()}
    assert len(doc.audit().errors) == 0


def test_pump_json(capsys):
    rc, out, err = run(
        capsys, "pump", "--teeth", 11, "--module", 4, "--shift", 0.3, "--face-width", 20, "--speed", 1500, "--json"
    )
    assert rc == 0, err
    data = json.loads(out)
    assert data["pump_frequency_hz"] == pytest.approx(275.0)
    assert data["mean_flow"] > 0 and 0 < data["flow_irregularity"] < 1 and len(data["harmonics"]) == 8


@pytest.mark.parametrize(
    "args,needle",
    [
        (["pump", "--teeth", "11", "--module", "4", "--face-width", "0", "--speed", "1500"], "--face-width"),
        (["pump", "--teeth", "11", "--module", "4", "--face-width", "20"], "--speed"),
        (["cut", "--teeth", "2", "--module", "4"], "--teeth"),
        (["cut", "--teeth", "11", "--module", "4", "--tolerance", "-1"], "--tolerance"),
        (["hob", "--teeth", "11", "--module", "4", "--min-flank-angle", "-1"], "--min-flank-angle"),
    ],
)
def test_bad_input(capsys, args, needle):
    rc, out, err = run(capsys, *args)
    assert rc == 2 and out == "" and needle in err and len(err.strip().splitlines()) == 1

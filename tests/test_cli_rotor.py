"""``rotorcad rotor`` as CONTRACT.md specifies it: keys, files, points input and bad input."""

from __future__ import annotations

import json
from pathlib import Path

import ezdxf
import numpy as np
import pytest
import shapely

from exports.csv_points import read_points
from rotorcad.cli.main import main

SAMPLES = Path(__file__).resolve().parents[1] / "samples"
KEYS = {
    "male_teeth",
    "female_teeth",
    "center_distance",
    "meshline_closed",
    "blow_hole_area",
    "contact_line_length",
    "male_flute_area",
    "female_flute_area",
    "displacement_per_rev",
    "max_sliding_velocity",
    "defects",
}

# the 5/6 sample pair's dimensions as command-line options
DIMS_56 = [
    "--male-teeth",
    5,
    "--female-teeth",
    6,
    "--center-distance",
    116,
    "--male-tip-radius",
    63,
    "--male-root-radius",
    45,
    "--female-tip-radius",
    71,
    "--female-root-radius",
    53,
]


def run(capsys, *args):
    rc = main([str(a) for a in args])
    out = capsys.readouterr()
    return rc, out.out, out.err


def test_design_file_json_and_files(tmp_path, capsys):
    m, f, r = tmp_path / "m.csv", tmp_path / "f.csv", tmp_path / "r.csv"
    rc, out, err = run(
        capsys,
        "rotor",
        SAMPLES / "lysholm_4_6.toml",
        "--json",
        "--male-csv",
        m,
        "--female-csv",
        f,
        "--rack-csv",
        r,
        "--plot",
        tmp_path / "p.png",
        "--dxf",
        tmp_path / "p.dxf",
    )
    assert rc == 0, err
    data = json.loads(out)
    assert KEYS <= set(data)
    assert data["meshline_closed"] is True and data["blow_hole_area"] == 0.0
    for d in data["defects"]:
        assert d["kind"] in ("cusp", "jamming", "slipping") and d["rotor"] in ("male", "female") and {"x", "y"} <= set(d)
    assert (tmp_path / "p_sliding.png").exists()
    doc = ezdxf.readfile(tmp_path / "p.dxf")
    assert len(doc.audit().errors) == 0 and doc.header["$INSUNITS"] == 4
    assert {"MALE", "FEMALE", "RACK", "PITCH", "HOUSING"} <= {e.dxf.layer for e in doc.modelspace()}
    # male and female outlines put in mesh by the shift (a, 0) touch without overlapping
    male = shapely.Polygon(read_points(m))
    female = shapely.Polygon(read_points(f) + np.array([100.0, 0.0]))
    assert male.is_valid and female.is_valid and male.intersection(female).area < 1e-3
    # flute areas from the written outlines (shapely) agree with the JSON
    import tomllib

    r1t = tomllib.loads((SAMPLES / "lysholm_4_6.toml").read_text())["pair"]["male_tip_radius"]
    a1 = (np.pi * r1t**2 - male.area) / 4
    assert data["male_flute_area"] == pytest.approx(a1, rel=1e-3)


def test_rebuild_from_written_points(tmp_path, capsys):
    # The male written by one run, read back with --male-points, gives the same pair.
    m = tmp_path / "m.csv"
    rc, out, _ = run(capsys, "rotor", SAMPLES / "rack_involute_5_6.toml", "--json", "--male-csv", m)
    first = json.loads(out)
    import tomllib

    pair = tomllib.loads((SAMPLES / "rack_involute_5_6.toml").read_text())["pair"]
    dims = [f"--{k.replace('_', '-')}={pair[k]!r}" for k in ("male_teeth", "female_teeth", "center_distance")]
    dims += [f"--{k.replace('_', '-')}={pair[k]!r}" for k in ("male_tip_radius", "male_root_radius")]
    dims += [f"--{k.replace('_', '-')}={pair[k]!r}" for k in ("female_tip_radius", "female_root_radius")]
    rc, out, err = run(capsys, "rotor", "--male-points", m, *dims, "--json")
    assert rc == 0, err
    second = json.loads(out)
    assert second["male_flute_area"] == pytest.approx(first["male_flute_area"], rel=1e-3)
    assert second["female_flute_area"] == pytest.approx(first["female_flute_area"], rel=1e-3)


@pytest.mark.parametrize(
    "extra,needle",
    [
        (["--male-teeth", "13"], "male_teeth"),
        (["--female-tip-radius", "40"], "female-tip-radius"),
        (["--speed", "-5"], "--speed"),
        (["--male-teeth", "x"], "--male-teeth"),
    ],
)
def test_bad_input_exit_2_one_sentence(tmp_path, capsys, extra, needle):
    target = tmp_path / "m.csv"
    pts = tmp_path / "p.csv"
    pts.write_text("x,y\n1,0\n0,1\n-1,0\n0,-1\n")
    args = [
        "rotor",
        "--male-points",
        pts,
        *DIMS_56,
        *extra,
        "--male-csv",
        target,
    ]
    rc, out, err = run(capsys, *args)
    assert rc == 2 and out == "" and len(err.strip().splitlines()) == 1 and needle.replace("_", "-") in err.replace("_", "-")
    assert not target.exists()


def test_bad_design_files(tmp_path, capsys):
    text = (SAMPLES / "srm_asymmetric_5_6.toml").read_text()
    for bad, needle in (
        (text.replace('family = "srm-asymmetric"', 'family = "spiral"'), "family"),
        (text.replace("seal_stop = 0.9", "seal_stop = 0.9\nsael_stop = 1"), "sael_stop"),
        (text.replace("male_teeth = 5", "male_teeth = 1"), "male_teeth"),
    ):
        design = tmp_path / "d.toml"
        design.write_text(bad)
        rc, _, err = run(capsys, "rotor", design)
        assert rc == 2 and needle in err and len(err.strip().splitlines()) == 1

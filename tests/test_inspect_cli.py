"""``rotorcad inspect`` end to end: points files (CSV, DXF) of teeth made by tests/inspection_teeth.py, a
rotor's points from shapely's offset outline, and the refusals (one sentence naming the option, exit 2).

References: ISO 21771 closed forms (the start of the active profile from the mate's tip, the
working pressure angle of a shifted pair), the base-circle relation of a pressure-angle error
(f_Halpha = L_alpha (r_b' - r_b) / r_b), ezdxf as the third-party writer of a drawing, shapely's
buffer as the offset outline.
"""

from __future__ import annotations

import json
import math
import re
from pathlib import Path

import ezdxf
import numpy as np
import pytest
import shapely
from scipy.optimize import brentq

from exports.csv_points import write_points
from rotorcad import quantities
from rotorcad.cli.main import main
from tests.inspection_teeth import inv, teeth_points

DEG = math.pi / 180.0
SAMPLES = Path(__file__).resolve().parents[1] / "samples"
SCATTER = 1.5e-3


def numbers(value: object, path: str = "") -> dict[str, float]:
    """Every number of a JSON value by its dotted path (list items as ``[]``)."""
    if isinstance(value, dict):
        out: dict[str, float] = {}
        for k, v in value.items():
            out.update(numbers(v, f"{path}.{k}" if path else k))
        return out
    if isinstance(value, list):
        out = {}
        for v in value:
            out.update(numbers(v, f"{path}[]"))
        return out
    if isinstance(value, int | float) and not isinstance(value, bool):
        return {path: value}
    return {}


def run(capsys, args: list[object]) -> tuple[int, dict | None, str]:
    code = main([str(a) for a in args])
    captured = capsys.readouterr()
    return code, (json.loads(captured.out) if code == 0 and "--json" in args else None), captured.err.strip()


@pytest.fixture(scope="module")
def teeth_csv(tmp_path_factory) -> Path:
    """Four teeth of z = 20, m = 4 with a pressure angle 0.1 deg too large, turned by 0.02 rad, shuffled."""
    roll = np.linspace(2.0, 22.8, 150)
    pts = teeth_points(20, 4.0, 20 * DEG, [0, 1, 2, 3], roll, alpha_actual=20.1 * DEG, rotation=0.02, scatter=SCATTER)
    pts = pts[np.random.default_rng(0).permutation(len(pts))]
    path = tmp_path_factory.mktemp("inspect") / "teeth.csv"
    write_points(path, pts, ["four teeth, CMM-like scatter"])
    return path


def test_gear_points_in_json_with_the_chart(teeth_csv, tmp_path, capsys):
    png = tmp_path / "chart.png"
    code, out, err = run(
        capsys, ["inspect", "--teeth", 20, "--module", 4, "--points", teeth_csv, "--class", 6, "--plot", png, "--json"]
    )
    assert code == 0, err
    assert png.stat().st_size > 10_000
    assert out["alignment"]["rotation_deg"] == pytest.approx(math.degrees(0.02), abs=1e-3)
    rb, r = 40 * math.cos(20 * DEG), 40.0
    lo, hi = out["evaluation_range"]["start_roll_length"], out["evaluation_range"]["end_roll_length"]
    expected = (hi - lo) * (r * math.cos(20.1 * DEG) - rb) / rb  # the base-circle relation: about -12.6 µm
    assert len(out["flanks"]) == 8
    for f in out["flanks"]:
        assert f["profile_slope_deviation"] == pytest.approx(expected, abs=SCATTER)
    assert out["within_tolerance"]["profile_slope_deviation"] is False  # 8 µm for class 6 (m 4, d 80)
    assert out["tolerances"]["profile_slope_tolerance"] == pytest.approx(8e-3)  # (1.6 + 0.08 + 4) * sqrt(2) = 8.03 -> 8.0
    undeclared = [k for k in numbers(out) if quantities.lookup(k) is None]
    assert not undeclared, f"keys without a unit in rotorcad.quantities: {undeclared}"


def test_the_mates_tip_starts_the_active_profile(tmp_path, capsys):
    # samples/gear_pair.toml: z1 17, z2 29, m 3, x1 0.3, x2 -0.1, zero backlash (ISO 21771 eq. 4.14)
    z1, z2, m, x1, x2, a = 17, 29, 3.0, 0.3, -0.1, 20 * DEG
    inv_w = inv(a) + 2 * (x1 + x2) * math.tan(a) / (z1 + z2)
    a_w = brentq(lambda t: inv(t) - inv_w, 0.1, 1.0)
    center = (z1 + z2) * m / 2 * math.cos(a) / math.cos(a_w)
    r2, rb1 = z2 * m / 2, z1 * m / 2 * math.cos(a)
    xi = center * math.sin(a_w) - math.sqrt((r2 + (1 + x2) * m) ** 2 - (r2 * math.cos(a)) ** 2)
    roll = np.linspace(xi - 0.3, math.sqrt((z1 * m / 2 + (1 + x1) * m) ** 2 - rb1**2) - 0.02, 120)
    path = tmp_path / "pinion.csv"
    write_points(path, teeth_points(z1, m, a, [0, 1], roll, shift=x1), ["two teeth, exact"])
    code, out, err = run(capsys, ["inspect", SAMPLES / "gear_pair.toml", "--points", path, "--json"])
    assert code == 0, err
    assert out["evaluation_range"]["active_start"] == "mate's tip"
    assert out["evaluation_range"]["start_roll_length"] == pytest.approx(xi, abs=1e-6)
    assert max(abs(f["total_profile_deviation"]) for f in out["flanks"]) < 1e-6
    assert out["thickness_deviation_mean"] == pytest.approx(0.0, abs=1e-6)


def test_a_dxf_drawn_by_ezdxf(tmp_path, capsys):
    # one tooth (right flank root to tip, then the left flank tip to root) as an LWPOLYLINE of ezdxf,
    # moved 5 µm outwards on both flanks: the thickness grows by 2 * 5 µm / cos(alpha) (ISO 21771)
    roll = np.linspace(2.0, 22.6, 300)
    pts = teeth_points(20, 4.0, 20 * DEG, [0], roll, deviation=lambda xi: np.full_like(xi, 5e-3))
    left, right = pts[:300], pts[300:]
    chain = np.vstack([right, left[::-1]])
    doc = ezdxf.new()
    doc.modelspace().add_lwpolyline(chain.tolist())
    path = tmp_path / "tooth.dxf"
    doc.saveas(path)
    code, out, err = run(capsys, ["inspect", "--teeth", 20, "--module", 4, "--points", path, "--json"])
    assert code == 0, err
    assert out["thickness_deviation"][0]["deviation"] == pytest.approx(2 * 5e-3 / math.cos(20 * DEG), abs=1e-4)


def test_rotor_points_against_the_design(tmp_path, capsys):
    from rotorcad.design.files import load_rotor_design
    from rotorcad.design.rotors import build_pair, merge_pair

    design = SAMPLES / "rack_involute_5_6.toml"
    outline = build_pair(merge_pair(load_rotor_design(design), {})).female_outline(1e-4)
    ring = np.asarray(shapely.Polygon(outline.points).buffer(-4e-3, quad_segs=64).exterior.coords)[:-1]
    path = tmp_path / "female.csv"
    write_points(path, ring, ["the female 4 µm under size"])
    png = tmp_path / "rotor.png"
    code, out, err = run(capsys, ["inspect", design, "--rotor", "female", "--points", path, "--plot", png, "--json"])
    assert code == 0, err
    assert png.exists()
    assert out["alignment"]["rotation_deg"] == pytest.approx(0.0, abs=1e-3)
    for side in ("left", "right"):
        assert out[side]["rms_normal_deviation"] == pytest.approx(4e-3, abs=0.3e-3)
    assert out["max_normal_deviation"] < 0.0  # less material everywhere
    assert not [k for k in numbers(out) if quantities.lookup(k) is None]


def refused(capsys, tmp_path, args: list[object]) -> str:
    png = tmp_path / "never.png"
    code, _, err = run(capsys, ["inspect", *args, "--plot", png])
    assert code == 2
    assert not png.exists()
    assert "\n" not in err and err.startswith("rotorcad: error:") and err.endswith(".")
    return err


def test_refusals_name_the_option_and_the_range(teeth_csv, tmp_path, capsys):
    gear = ["--teeth", 20, "--module", 4]
    few = tmp_path / "few.csv"
    write_points(few, np.array([[40, 1], [40.5, 1.2], [41, 1.1], [41.5, 1.5], [42, 1.3]]))
    assert "--points must hold at least 10 points" in refused(capsys, tmp_path, [*gear, "--points", few])
    # points of the tip land only: no flank within the evaluation range
    tip = tmp_path / "tip.csv"
    angle = np.linspace(-0.02, 0.02, 40)
    write_points(tip, 43.99 * np.column_stack([np.cos(angle), np.sin(angle)]))
    err = refused(capsys, tmp_path, [*gear, "--points", tip])
    assert "--points must hold at least 5 points on one tooth flank within the evaluation range (radius" in err
    # a point in the middle of a tooth space, 1 mm from either flank
    pts = np.loadtxt(teeth_csv, delimiter=",", comments="#", skiprows=2)
    space = np.pi / 20 + 0.02
    far = tmp_path / "far.csv"
    write_points(far, np.vstack([pts, [[40 * math.cos(space), 40 * math.sin(space)]]]))
    assert "--points must lie within 0.4 mm (0.1 m) of a nominal tooth flank" in refused(
        capsys, tmp_path, [*gear, "--points", far]
    )
    # a point outside the tip circle
    out = tmp_path / "out.csv"
    write_points(out, np.vstack([pts, [[0.0, 50.0]]]))
    assert "--points must lie between the root circle and the tip circle" in refused(capsys, tmp_path, [*gear, "--points", out])
    assert "--class must be a whole number from 1 to 11" in refused(
        capsys, tmp_path, [*gear, "--points", teeth_csv, "--class", 0]
    )
    err = refused(capsys, tmp_path, [SAMPLES / "rack_involute_5_6.toml", "--points", teeth_csv, "--class", 5])
    assert err.startswith("rotorcad: error: --class is for gears")


def test_declared_units_scale_with_the_gear(teeth_csv, tmp_path, capsys):
    # geometric similarity: the gear and its points scaled by 2 change a quantity by 2^k, k the power
    # of length in its declared unit (mm 1, deg and counts 0); the tolerance class is left out (the
    # standard's formulas are not similar)
    pts = np.loadtxt(teeth_csv, delimiter=",", comments="#", skiprows=2)
    double = tmp_path / "double.csv"
    write_points(double, 2 * pts)
    results = []
    for m, path in ((4, teeth_csv), (8, double)):
        code, out, err = run(capsys, ["inspect", "--teeth", 20, "--module", m, "--points", path, "--json"])
        assert code == 0, err
        results.append(numbers({k: v for k, v in out.items() if k != "classes"}))
    power = {"mm": 1, "1": 0, "deg": 0}
    for key, value in results[0].items():
        unit = quantities.lookup(key).unit
        if abs(value) < 1e-9:
            continue
        assert math.log2(abs(results[1][key] / value)) == pytest.approx(power[unit], abs=0.05), key


@pytest.mark.parametrize(("moved", "within"), [(-15e-3, True), (-5e-3, False)])
def test_the_thickness_against_the_designs_allowances(tmp_path, capsys, moved, within):
    design = tmp_path / "gear.toml"
    design.write_text("[gear]\nteeth = 20\nmodule = 4.0\nthickness_allowance_upper = -0.02\nthickness_allowance_lower = -0.06\n")
    roll = np.linspace(2.0, 22.6, 100)
    path = tmp_path / "teeth.csv"
    write_points(path, teeth_points(20, 4.0, 20 * DEG, [3, 4], roll, deviation=lambda xi: np.full_like(xi, moved)))
    code, out, err = run(capsys, ["inspect", design, "--points", path, "--json"])
    assert code == 0, err
    # both flanks moved by d along their normals: the normal thickness changes by 2 d / cos(alpha) (ISO 21771):
    # -31.9 µm within the allowances -60 ... -20 µm (DIN 3967), -10.6 µm above them
    assert out["thickness_deviation_mean"] == pytest.approx(2 * moved / math.cos(20 * DEG), abs=1e-5)
    assert out["thickness_allowance"] == {"upper": -0.02, "lower": -0.06}
    assert out["thickness_within_allowance"] is within


def test_the_table_gives_every_number_its_unit(teeth_csv, capsys):
    assert main(["inspect", "--teeth", "20", "--module", "4", "--points", str(teeth_csv), "--class", "6"]) == 0
    rows = [line.split("│")[1:4] for line in capsys.readouterr().out.splitlines() if line.count("│") == 4]
    numeric = [r for r in rows if re.fullmatch(r"\s*-?[\d.]+(e-?\d+)?\s*", r[1]) and "." in r[0]]
    assert numeric and all(r[2].strip() in ("mm", "deg", "1") for r in numeric), numeric


def test_cmm_points_as_dxf_point_entities(tmp_path, capsys):
    # a CMM's DXF: one POINT entity per probed point (ezdxf writes it); a crowning of 6 µm on two teeth
    roll = np.linspace(2.0, 22.6, 120)
    lo, hi = 1.985966, 21.828447  # L_alpha of z 20, m 4 (test_gear_points_in_json_with_the_chart reads them back)

    def crowning(xi: np.ndarray) -> np.ndarray:
        return 6e-3 * (1.0 - ((xi - (lo + hi) / 2) / ((hi - lo) / 2)) ** 2)

    doc = ezdxf.new()
    for x, y in teeth_points(20, 4.0, 20 * DEG, [7, 8], roll, deviation=crowning):
        doc.modelspace().add_point((x, y, 5.0), dxfattribs={"layer": "CMM"})
    doc.modelspace().add_line((0, 0), (1, 1), dxfattribs={"layer": "AXES"})
    path = tmp_path / "cmm.dxf"
    doc.saveas(path)
    code, out, err = run(capsys, ["inspect", "--teeth", 20, "--module", 4, "--points", path, "--layer", "cmm", "--json"])
    assert code == 0, err
    assert out["evaluation_range"]["start_roll_length"] == pytest.approx(lo, abs=1e-5)
    for f in out["flanks"]:
        assert f["profile_form_deviation"] == pytest.approx(6e-3, abs=0.1e-3)  # the parabola's height, exact points
        assert abs(f["profile_slope_deviation"]) < 0.1e-3

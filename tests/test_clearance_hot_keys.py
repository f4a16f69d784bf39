"""``rotorcad clearance`` at working temperature says what it used (a new user's finding F6).

The hot pair follows Miao Huijun et al., *Calculation method of mesh clearance of screw steam
compressor under extreme condition*, sec. 1.2: a body grows by dL = L zeta (t_c - t0) (eq. 1), the
rotors' computation temperature is the arithmetic mean of suction and discharge temperature, and the
centre distance is that of the housing, grown from its own temperature. The closed forms below are
written from that rule, not read from the code.
"""

from __future__ import annotations

import json

import numpy as np
import pytest
import shapely

from exports.csv_points import write_points
from rotorcad.cli.main import main
from rotorcad.rotor_families import build_family
from rotorcad.rotor_pair import RotorPair

A = 116.0  # mm, cold centre distance of the pair
HOT_KEYS = {"rotor_temperature", "housing_temperature", "reference_temperature", "rotor_expansion", "housing_expansion"}
HOT_KEYS |= {"center_distance_cold"}
HOT_DEFAULTS = {"--housing-temperature", "--reference-temperature", "--rotor-expansion", "--housing-expansion"}


@pytest.fixture(scope="module")
def argv(tmp_path_factory) -> list[str]:
    """A 5/6 rack-involute pair with the female 30 µm smaller all round (shapely's offset), as points."""
    folder = tmp_path_factory.mktemp("hot")
    rotors = build_family(RotorPair(5, 6, A, 63.0, 45.0, 71.0, 53.0), "rack-involute", {})
    female = shapely.Polygon(rotors.female_outline(1e-3).points).buffer(-0.03, quad_segs=64).exterior.coords
    write_points(folder / "m.csv", rotors.male_outline(1e-3).points)
    write_points(folder / "f.csv", np.asarray(female)[:-1])
    return ["clearance", "--male-points", str(folder / "m.csv"), "--female-points", str(folder / "f.csv")] + [
        "--male-teeth", "5", "--female-teeth", "6", "--center-distance", f"{A:g}", "--lead", "300", "--length", "190", "--quiet",
    ]  # fmt: skip


def run(capsys, args: list[str]) -> str:
    capsys.readouterr()
    assert main(args) == 0
    return capsys.readouterr().out


def test_cold_pair_has_none_of_the_hot_keys(argv, capsys):
    data = json.loads(run(capsys, [*argv, "--json"]))
    assert not HOT_KEYS & set(data)
    assert data["center_distance"] == A and data["defaults"] == {}


def test_hot_pair_with_the_defaults_says_each_one(argv, capsys):
    ts, td = 20.0, 120.0
    data = json.loads(run(capsys, [*argv, "--suction-temperature", f"{ts:g}", "--discharge-temperature", f"{td:g}", "--json"]))
    t_rotor = (ts + td) / 2  # Miao et al. sec. 1.2: the arithmetic mean of suction and discharge
    assert data["rotor_temperature"] == pytest.approx(t_rotor, abs=1e-12)
    assert data["housing_temperature"] == pytest.approx(t_rotor, abs=1e-12)  # housing at the rotors' temperature
    assert data["reference_temperature"] == 20.0
    assert (data["rotor_expansion"], data["housing_expansion"]) == (11.5e-6, 10.5e-6)  # steel, grey cast iron
    # eq. 1 on the housing: a_hot = a (1 + zeta_housing (t_housing - t0)); 82 mm gave the user 82.04305
    assert data["center_distance_cold"] == A
    assert data["center_distance"] == pytest.approx(A * (1 + 10.5e-6 * (t_rotor - 20.0)), abs=1e-9)
    assert set(data["defaults"]) == HOT_DEFAULTS
    for option, value in (("--housing-temperature", "70 degC"), ("--reference-temperature", "20 degC")):
        assert data["defaults"][option].startswith(f"{value} (default: ")
    assert data["defaults"]["--rotor-expansion"].startswith("1.15e-05 1/K (default: steel")
    assert data["defaults"]["--housing-expansion"].startswith("1.05e-05 1/K (default: grey cast iron")


def test_hot_pair_with_every_input_given_takes_no_default_and_prints_the_units(argv, capsys):
    ts, td, th, t0, zr, zh = -10.0, 150.0, 45.0, 25.0, 12e-6, 23e-6
    given = ["--suction-temperature", ts, "--discharge-temperature", td, "--housing-temperature", th]
    given += ["--reference-temperature", t0, "--rotor-expansion", zr, "--housing-expansion", zh]
    hot = [*argv, *(f"{v:g}" if isinstance(v, float) else v for v in given)]
    data = json.loads(run(capsys, [*hot, "--json"]))
    assert data["defaults"] == {}
    assert data["rotor_temperature"] == pytest.approx((ts + td) / 2, abs=1e-12)
    assert data["housing_temperature"] == th and data["reference_temperature"] == t0
    assert (data["rotor_expansion"], data["housing_expansion"]) == (zr, zh)
    assert data["center_distance_cold"] == A
    assert data["center_distance"] == pytest.approx(A * (1 + zh * (th - t0)), abs=1e-9)  # eq. 1 on the housing
    rows, table = {}, run(capsys, hot)
    for line in table.splitlines():
        cells = [c.strip() for c in line.strip().strip("│").split("│")]
        if line.startswith("│") and len(cells) == 3:
            rows[cells[0]] = cells[1:]
    assert rows["rotor_temperature"] == ["70.000000", "degC"] and rows["housing_temperature"] == ["45.000000", "degC"]
    assert rows["housing_expansion"] == ["2.3e-05", "1/K"] and rows["center_distance_cold"] == ["116.000000", "mm"]
    assert "defaults taken" not in table

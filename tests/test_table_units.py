"""Every number a command prints in its table carries its unit (CONTRACT.md conventions): the
tables of gear, cut, pump, rotor, hob and clearance are read back from their output."""

from __future__ import annotations

import re

import pytest

from exports.csv_points import write_points
from rotorcad.cli.common import unit_of
from rotorcad.cli.main import main
from rotorcad.rotor_families import build_family
from rotorcad.rotor_pair import RotorPair

COMMANDS = [
    ["gear", "--teeth", "17", "--module", "3", "--mate-teeth", "29"],
    ["cut", "--teeth", "11", "--module", "2"],
    ["pump", "--teeth", "11", "--module", "4", "--shift", "0.3", "--face-width", "20", "--speed", "1500"],
    ["rotor", "samples/rack_involute_5_6.toml"],
    ["hob", "samples/rack_involute_5_6.toml"],
]


def test_known_units():
    # CONTRACT.md: lengths mm, areas mm², volumes mm³, angles in keys ending _deg, speeds m/s, flows L/min
    assert unit_of("blow_hole_area") == "mm²" and unit_of("displacement_per_rev") == "mm³"
    assert unit_of("working_pressure_angle_deg") == "deg" and unit_of("max_sliding_velocity") == "m/s"
    assert unit_of("mean_flow") == "L/min" and unit_of("tip_radius") == "mm" and unit_of("male_teeth") == "1"


@pytest.mark.parametrize("args", COMMANDS, ids=[c[0] for c in COMMANDS])
def test_every_number_in_a_table_has_a_unit(args, capsys, tmp_path):
    capsys.readouterr()
    assert main(args) == 0
    _check(capsys.readouterr().out)


def test_clearance_table_has_units(capsys, tmp_path):
    pair = RotorPair(5, 6, 116.0, 63.0, 45.0, 71.0, 53.0)
    rotors = build_family(pair, "rack-involute", {})
    write_points(tmp_path / "m.csv", rotors.male_outline(1e-3).points)
    write_points(tmp_path / "f.csv", rotors.female_outline(1e-3).points)
    capsys.readouterr()
    dims = ["--male-teeth", "5", "--female-teeth", "6", "--center-distance", "116"]
    assert main(["clearance", "--male-points", str(tmp_path / "m.csv"), "--female-points", str(tmp_path / "f.csv"), *dims]) == 0
    _check(capsys.readouterr().out)


def _check(out: str) -> None:
    rows = [r for r in out.splitlines() if r.startswith("│")]
    numeric = 0
    for row in rows:
        cells = [c.strip() for c in row.strip("│").split("│")]
        if len(cells) >= 3 and re.fullmatch(r"-?\d+(\.\d+)?(e-?\d+)?", cells[1]):
            numeric += 1
            assert cells[-1], f"no unit for {cells[0]}"
    assert numeric >= 2


def test_the_gear_table_shows_the_mate(capsys):
    # pitch radii z m / 2 (ISO 21771) of both gears, each in its column, with the unit
    capsys.readouterr()
    assert main(["gear", "--teeth", "17", "--module", "3", "--mate-teeth", "29"]) == 0
    row = next(r for r in capsys.readouterr().out.splitlines() if "pitch_radius" in r)
    cells = [c.strip() for c in row.strip("│").split("│")]
    assert cells == ["pitch_radius", "25.500000", "43.500000", "mm"]


def test_keys_the_name_rules_misread_have_their_contract_units():
    # issue 25: max_normal_clearance printed in N ("_n"), max_penetration as a ratio ("penetRATIOn"),
    # touching_threshold without mm³; CONTRACT.md gives clearances and penetrations in mm, volumes in mm³
    from rotorcad.cli.common import unit_of

    expected = {
        "max_normal_clearance": "mm",
        "min_normal_clearance": "mm",
        "max_penetration": "mm",
        "touching_threshold": "mm³",
        "max_gap": "mm",
        "male_gas_force_n": "N",
        "male_gas_force_n_paper": "N",
    }
    assert {key: unit_of(key) for key in expected} == expected

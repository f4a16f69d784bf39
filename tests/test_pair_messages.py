"""Refusals of a rotor pair's values name what the user typed, in digits a user reads (a new user's N9).

References: the sample's own ``[pair]`` values (the limits are sums and differences of them, computed
here), and the order of the checks a user expects (a missing file before a missing radius).
"""

from __future__ import annotations

import tomllib
from pathlib import Path

import pytest

from rotorcad.cli.main import main
from rotorcad.errors import DesignError, value_text

SAMPLES = Path(__file__).resolve().parents[1] / "samples"
RI = SAMPLES / "rack_involute_5_6.toml"
PAIR = tomllib.loads(RI.read_text())["pair"]


def refusal(capsys, *args) -> str:
    rc = main([str(a) for a in args])
    out = capsys.readouterr()
    assert rc == 2 and out.out == "" and out.err.count("\n") == 1 and "Traceback" not in out.err, out
    return out.err


def test_missing_points_file_is_named_before_missing_radii(capsys, tmp_path):
    # was: "--male-tip-radius is required" for a file that does not exist
    err = refusal(
        capsys,
        "rotor",
        "--male-points",
        tmp_path / "nonexist.csv",
        "--male-teeth",
        5,
        "--female-teeth",
        6,
        "--center-distance",
        116,
    )
    assert "--male-points" in err and "no such file" in err and "required" not in err


def test_hob_missing_points_file_is_named_first(capsys, tmp_path):
    err = refusal(capsys, "hob", "--female-points", tmp_path / "nonexist.csv", "--male-teeth", 5, "--female-teeth", 6)
    assert "--female-points" in err and "no such file" in err


def test_conflict_names_the_option_typed_not_the_design_key(capsys):
    # was: "[pair] female_root_radius must be at most 36 mm (centre distance minus male tip radius) (got 46.48933484382849)"
    err = refusal(capsys, "rotor", RI, "--male-tip-radius", 80)
    limit = PAIR["center_distance"] - PAIR["female_root_radius"]
    assert f"--male-tip-radius must be at most {limit:.6g} mm" in err and "(got 80)" in err, err
    assert "[pair]" not in err


def test_conflict_names_the_typed_centre_distance(capsys):
    err = refusal(capsys, "rotor", RI, "--center-distance", 100)
    pitch_limit = PAIR["male_root_radius"] * (PAIR["male_teeth"] + PAIR["female_teeth"]) / PAIR["male_teeth"]
    assert f"--center-distance must be at least {pitch_limit:.6g} mm" in err and "(got 100)" in err, err


def test_conflict_of_the_value_typed_names_it(capsys):
    err = refusal(capsys, "rotor", RI, "--female-root-radius", 60)
    assert err.startswith("rotorcad: error: --female-root-radius must be at most"), err


@pytest.mark.parametrize(
    ("value", "context", "text"),
    [
        (46.48933484382849, "at most 36 mm", "46.4893"),  # 6 significant digits
        (80.0, "at most 69.5107 mm", "80"),
        (36.0000004, "at most 36 mm", "36.0000004"),  # never shown equal to its limit
        (63.2727272, "at least 63.272727 mm", "63.27273"),  # nor on the limit's other side
        (1e-6, "at least 1e-05", "1e-06"),
        (float("nan"), "a number", "nan"),
        (3, "at most 2", "3"),
        ("abc", "a number", "abc"),
    ],
)
def test_refused_value_digits(value, context, text):
    assert value_text(value, context) == text
    assert DesignError("x", context, value).sentence() == f"x must be {context} (got {text})."


def test_clearance_missing_points_file_is_named_first(capsys, tmp_path):
    err = refusal(capsys, "clearance", "--male-points", tmp_path / "nonexist.csv", "--female-points", tmp_path / "f.csv")
    assert "--male-points" in err and "no such file" in err and "required" not in err

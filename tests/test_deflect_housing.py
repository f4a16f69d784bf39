"""`deflect` compares each rotor's deflection with the design's radial housing clearance (newuser5 F15).

References, none of them the comparison under test:

- the new user's run of the previous release on their long design (the sample with length 450 mm,
  40 bar, volume ratio 10; ``[housing] radial_clearance = 0.05``): ``female_max_deflection`` 0.055409 mm
  at 205.79 mm from the discharge bearing, inside the helical part (the female's journals are 24 mm long, the male's 36), and
  ``male_max_deflection`` 0.016184 mm: a key that was there before the check, so the body's deflection
  must equal it and the female's must be refused a silent pass (55 µm > 50 µm);
- Rinder & Deix sec. 1: the deflection matters because it can take the rotors to the housing wall;
  their 5/6 example (0.0075 mm with journals) stays far inside a 0.05 mm clearance.
"""

from __future__ import annotations

import contextlib
import io
import json
import re
from pathlib import Path

import pytest
from shared_runs import command_output

from rotorcad.cli.main import main

ROOT = Path(__file__).resolve().parents[1]
SAMPLE = ROOT / "samples" / "rinder_deix_5_6.toml"
USER_FEMALE, USER_MALE = 0.055409, 0.016184  # mm, the new user's figures (previous release, key female/male_max_deflection)


def _run(path: Path) -> tuple[dict, str]:
    out, err = io.StringIO(), io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
        assert main(["deflect", str(path), "--json", "--quiet"]) == 0
    return json.loads(out.getvalue()), err.getvalue()


def _long_design(tmp: Path, clearance: float) -> Path:
    text = SAMPLE.read_text()
    text = re.sub(r"(?m)^length = .*$", "length = 450.0", text)
    text = re.sub(r"(?m)^discharge_pressure_bar = .*$", "discharge_pressure_bar = 40.0", text)
    text = re.sub(r"(?m)^volume_ratio = .*$", "volume_ratio = 10.0", text)
    text = re.sub(r"(?m)^radial_clearance = .*$", f"radial_clearance = {clearance}", text)
    path = tmp / f"rd_long_{clearance}.toml"
    path.write_text(text)
    return path


@pytest.fixture(scope="module")
def long_run(tmp_path_factory) -> tuple[dict, str]:
    return _run(_long_design(tmp_path_factory.mktemp("housing"), 0.05))


def test_a_deflection_past_the_housing_clearance_is_said(long_run):
    result, err = long_run
    assert result["housing_radial_clearance"] == 0.05
    assert result["female_body_deflection"] == pytest.approx(USER_FEMALE, abs=1e-6)
    assert result["male_body_deflection"] == pytest.approx(USER_MALE, abs=1e-6)
    assert result["female_deflection_to_housing_clearance"] == pytest.approx(USER_FEMALE / 0.05, rel=1e-4)
    assert "female's deflection 55.4 µm reaches the housing's radial clearance 50.0 µm" in err
    assert "male's deflection" not in err.replace("female's deflection", "")


def test_the_body_is_the_helical_part_not_the_journals(long_run):
    # the body's deflection is at most the whole shaft's, and here (largest inside the body) equal to it
    result, _ = long_run
    for rotor, journal in (("male", 36.0), ("female", 24.0)):  # the sample's [deflection] journal lengths
        assert result[f"{rotor}_body_deflection"] <= result[f"{rotor}_max_deflection"] + 1e-12
        assert journal < result[f"{rotor}_max_deflection_position"] < journal + 450.0


def test_the_papers_example_stays_inside_its_clearance(tmp_path):
    # run once in the run (tests/test_report_deflection.py runs the same): tests/shared_runs.py
    code, out, err = command_output("deflect", SAMPLE, "--json", "--quiet")
    assert code == 0
    result = json.loads(out)
    assert result["female_deflection_to_housing_clearance"] < 0.2  # 7.5 µm of 50 (Rinder & Deix: 0.0075 mm)
    assert "housing" not in err


def test_no_clearance_in_the_design_no_keys(tmp_path):
    result, _ = _run(_long_design(tmp_path, 0.0))
    assert "housing_radial_clearance" not in result and "female_body_deflection" not in result

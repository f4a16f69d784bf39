"""`report` of a design with [operating] pressures shows its deflection (newuser5 F14: it had none).

Reference: ``rotorcad deflect DESIGN --json`` on the same design, the command the numbers belong to
(the report computes them by the same code: the page must hold the command's figures, each one).
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


def _json(args: list[str]) -> dict:
    out = io.StringIO()
    with contextlib.redirect_stdout(out):
        assert main(args) == 0
    return json.loads(out.getvalue())


def test_the_report_holds_deflects_numbers(tmp_path):
    page = tmp_path / "rd.html"
    _json(["report", str(SAMPLE), "--out", str(page), "--json", "--quiet"])
    html = page.read_text(encoding="utf-8")
    assert "Deflection under gas load (rotorcad deflect --json)" in html
    code, out, _ = command_output("deflect", SAMPLE, "--json", "--quiet")  # once in the run: tests/shared_runs.py
    assert code == 0
    deflect = json.loads(out)
    for key in ("female_max_deflection", "male_max_deflection", "female_body_deflection", "female_discharge_bearing_load_n"):
        shown = re.search(rf"data-key='(?:[^']*\.)?{key}' data-value='([^']+)'", html)
        assert shown is not None, key
        assert float(shown.group(1)) == pytest.approx(deflect[key], rel=1e-9)


def test_a_design_without_pressures_has_no_deflection_section(tmp_path):
    page = tmp_path / "ri.html"
    _json(["report", str(ROOT / "samples" / "lysholm_4_6.toml"), "--out", str(page), "--json", "--quiet"])
    assert "Deflection under gas load" not in page.read_text(encoding="utf-8")


def test_a_design_deflect_refuses_keeps_its_report(tmp_path):
    # the report's other sections do not depend on deflect: its refusal is said in the section
    design = tmp_path / "p.toml"
    text = (ROOT / "samples" / "lysholm_4_6.toml").read_text()
    extra = "suction_pressure_bar = 1.0\ndischarge_pressure_bar = 8.0\npolytropic_exponent = 3.0\n"
    design.write_text(text.replace("[operating]\n", "[operating]\n" + extra))
    page = tmp_path / "p.html"
    _json(["report", str(design), "--out", str(page), "--json", "--quiet"])
    html = page.read_text(encoding="utf-8")
    assert "rotorcad deflect refuses this design: [operating] polytropic_exponent must be a number from 1 to 2" in html

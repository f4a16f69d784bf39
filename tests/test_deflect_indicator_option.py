"""`deflect --indicator` overrides the design's way of setting the discharge (newuser5 F14).

Before, a design with `[operating] volume_ratio` refused `--indicator` ("give only one of ..."): the
option could not override the design, as every other option does. Reference: the built-in port
model's pressure written as an indicator diagram gives the built-in model's deflection (the check of
tests/test_deflection.py), whatever volume ratio the design names beside it.
"""

from __future__ import annotations

import contextlib
import io
import json
from pathlib import Path

import numpy as np
import pytest

from rotorcad.cli.main import main

ROOT = Path(__file__).resolve().parents[1]
SAMPLE = ROOT / "samples" / "rack_involute_5_6.toml"
ARGS = ["--json", "--angle", "17", "--terms", "5", "--quiet"]


def _run(args: list[str]) -> tuple[dict, str]:
    out, err = io.StringIO(), io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
        assert main(args) == 0
    return json.loads(out.getvalue()), err.getvalue()


def test_the_option_replaces_the_designs_volume_ratio(tmp_path):
    from rotorcad.cli.export_cmd import _rotor_options
    from rotorcad.cli.rotor import _build
    from rotorcad.deflection import GasDeflection

    rotors, _, _ = _build(SAMPLE, _rotor_options(SAMPLE))
    cycle = GasDeflection(rotors, 1.0, 8.0, terms=5).cycle  # the port matched to 8 bar, the sample's own
    csv = tmp_path / "indicator.csv"
    rows = "\n".join(f"{np.degrees(t):.6f},{p * 10:.9f}" for t, p in zip(cycle.angle, cycle.pressure, strict=True))
    csv.write_text("angle_deg,pressure_bar\n" + rows + "\n")
    design = tmp_path / "vr.toml"
    design.write_text(SAMPLE.read_text().replace("[operating]\n", "[operating]\nvolume_ratio = 3.0\n"))
    given, err = _run(["deflect", str(design), *ARGS, "--indicator", str(csv)])
    built_in, _ = _run(["deflect", str(SAMPLE), *ARGS])
    for key in ("male_max_deflection", "female_max_deflection"):
        assert given[key] == pytest.approx(built_in[key], rel=2e-3)
    assert "--indicator replaced the design's [operating] volume_ratio" in err

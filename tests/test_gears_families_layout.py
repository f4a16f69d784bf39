"""The layout of issue 25 item 4: ``rotorcad.gears`` and ``rotorcad.families``, their shims and their types."""

from __future__ import annotations

import re
from pathlib import Path

import numpy as np
import pytest

ROOT = Path(__file__).resolve().parents[1]


def test_the_involute_function_is_written_once():
    # inv(alpha) = tan(alpha) - alpha lives in rotorcad/gears/formulas.py only (issue 25: it was
    # written three times); any other "tan(x) - x" in the core or the hob checks is a copy
    pattern = re.compile(r"tan\(\s*(\w+)\s*\)\s*-\s*\1\b")
    copies = [
        f"{path.relative_to(ROOT)}:{n}"
        for folder in ("rotorcad", "hob")
        for path in sorted((ROOT / folder).rglob("*.py"))
        if path != ROOT / "rotorcad" / "gears" / "formulas.py"
        for n, line in enumerate(path.read_text().splitlines(), 1)
        if pattern.search(line.split("#")[0]) and '"""' not in line
    ]
    assert copies == []


def test_inv_matches_the_involute_function_tables():
    # involute-function tables (7 decimals, e.g. Machinery's Handbook): inv 14.5 deg = 0.0055448, inv 20 deg =
    # 0.0149044, inv 25 deg = 0.0299753 (7 decimals)
    from rotorcad.gears.formulas import inv, inv_inverse

    degrees = np.array([14.5, 20.0, 25.0])
    table = np.array([0.0055448, 0.0149044, 0.0299753])
    assert np.allclose(inv(np.radians(degrees)), table, atol=6e-8)
    assert [round(inv(float(np.radians(d))), 7) for d in degrees] == list(table)  # the scalar path
    assert np.allclose(np.degrees(inv_inverse(table)), degrees, atol=2e-4)


@pytest.mark.parametrize("package", ["gears", "families"])
def test_every_module_is_short(package):
    # issue 25, done when: no module over ~800 lines (counted by lines of the file)
    lengths = {p.name: len(p.read_text().splitlines()) for p in (ROOT / "rotorcad" / package).glob("*.py")}
    assert lengths and max(lengths.values()) <= 800, lengths


def test_the_old_import_paths_give_the_same_objects():
    import importlib

    import rotorcad
    from rotorcad import gear, involute, rotor_families
    from rotorcad.families import checks, krigar, registry
    from rotorcad.families import n_rack as n_rack_module
    from rotorcad.gears import formulas, involute_gear, pair

    assert gear.InvoluteGear is involute_gear.InvoluteGear is rotorcad.InvoluteGear
    assert gear.GearPair is pair.GearPair and gear.mate_shift is pair.mate_shift
    assert gear.tool_tip_radius_limit is formulas.tool_tip_radius_limit
    assert involute.inv is formulas.inv and involute.inv_inverse is formulas.inv_inverse
    assert rotor_families.FAMILIES is registry.FAMILIES is rotorcad.FAMILIES
    assert rotor_families.build_family is registry.build_family and rotor_families.check_tips is checks.check_tips
    assert rotor_families.krigar is krigar.krigar is rotorcad.krigar
    assert importlib.import_module("rotorcad.n_rack").n_rack is n_rack_module.n_rack  # (a module import: see the shim)
    assert rotor_families.FAMILIES["n-rack"][0] is n_rack_module.n_rack  # (builder, parameters) as before


def test_the_public_n_rack_is_the_builder_after_the_families_are_loaded():
    # rotorcad.n_rack (PEP 562 name) was the module rotorcad.n_rack once rotor_families had imported
    # it; the builder now lives in rotorcad.families.n_rack and nothing in the package imports the
    # old module (a fresh interpreter: this session's tests import the shim)
    import subprocess
    import sys

    code = (
        "import rotorcad; rotorcad.FAMILIES; rotorcad.build_family; print(callable(rotorcad.n_rack), rotorcad.n_rack.__module__)"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout.split()
    assert out == ["True", "rotorcad.families.n_rack"]


def test_a_family_builder_without_a_declared_range_is_a_programming_error():
    from rotorcad.families.parameters import parameters_of

    with pytest.raises(TypeError, match="'depth' needs a default and one Allowed range"):
        parameters_of(_builder_without_range)


def _builder_without_range(pair, depth: float = 1.0):
    return pair


def test_the_tool_cut_kind_is_a_line_or_an_arc():
    from rotorcad.gears.tool import ToolCut

    assert ToolCut("arc", 30.0, 1.0, radius=1.0).kind == "arc"
    with pytest.raises(ValueError, match="kind must be 'line' or 'arc'"):
        ToolCut("circle", 30.0, 1.0)  # type: ignore[arg-type]

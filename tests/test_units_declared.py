"""Every number a command reports has its unit declared once, in :mod:`rotorcad.quantities`, and
the tables print that unit.

Each command runs in process on a sample, once with ``--json`` and once for its table: every numeric
JSON key has a declaration, and every unit in the table is the declared one. The declarations
themselves are checked against physics, not against the table: a design scaled by 2 in every
length (geometric similarity at the same speed, pressure and material) must change a quantity by
2^k, k the power of length in its declared unit (mm 1, mm² 2, mm³ 3, mm⁴ 4, a pure number or an
angle 0, m/s 1 at the same rpm, L/min 3, N 2 at the same pressure). The measured exponent
log2(ratio) must lie within 0.25 of k: a wrong unit is off by a whole power, while the points'
sampling and the fits' fixed thresholds move a ratio by a few per cent.
"""

from __future__ import annotations

import contextlib
import io
import json
import math
import os
import re
import tomllib
from pathlib import Path

import numpy as np
import pytest
import shapely
import tomli_w

from exports.csv_points import read_points, write_points
from rotorcad import quantities
from rotorcad.cli.main import main
from rotorcad.rotor_families import build_family
from rotorcad.rotor_pair import RotorPair

ROOT = Path(__file__).resolve().parents[1]
RACK = ROOT / "samples" / "rack_involute_5_6.toml"
DEFLECT = ROOT / "samples" / "rinder_deix_5_6.toml"

# the power of length in each unit under geometric similarity (same rpm, pressure, material)
LENGTH_POWER = {"mm": 1, "mm²": 2, "mm³": 3, "mm⁴": 4, "1": 0, "deg": 0, "%": 0, "m/s": 1, "L/min": 3, "N": 2, "N/mm": 1}
LENGTH_POWER |= {"MPa": 0, "bar": 0, "rpm": 0, "Hz": 0, "mm/mm": 0, "mm/deg": 1}
PAIR_LENGTHS = ("center_distance", "male_tip_radius", "male_root_radius", "female_tip_radius", "female_root_radius")
PAIR_LENGTHS += ("lead", "length")


def run(args: list[object]) -> tuple[int, str]:
    """Run ``rotorcad ARGS`` in process; return the exit status and stdout (tables 250 columns wide)."""
    out = io.StringIO()
    old = os.environ.get("COLUMNS")
    os.environ["COLUMNS"] = "250"  # no wrapped cells in rich's tables
    try:
        with contextlib.redirect_stdout(out):
            code = main([str(a) for a in args])
    finally:
        if old is None:
            del os.environ["COLUMNS"]
        else:
            os.environ["COLUMNS"] = old
    return code, out.getvalue()


def scaled_design(source: Path, folder: Path, k: float) -> Path:
    """Write ``source`` with every length multiplied by ``k`` (pair, housing clearance, shaft ends)."""
    data = tomllib.loads(source.read_text())
    for key in PAIR_LENGTHS:
        data["pair"][key] *= k
    if "housing" in data:
        data["housing"]["radial_clearance"] *= k
    for key, pieces in data.get("deflection", {}).items():
        if key.endswith(("_shaft_discharge", "_shaft_suction")):
            data["deflection"][key] = [[length * k, diameter * k] for length, diameter in pieces]
    path = folder / f"{source.stem}_x{k:g}.toml"
    path.write_text(tomli_w.dumps(data))
    return path


def numbers(value: object, path: str = "") -> dict[str, float]:
    """Every number of a JSON value by its dotted path (list items by their index, ``chambers.0.pressure_bar``)."""
    out: dict[str, float] = {}
    if isinstance(value, dict):
        for key, item in value.items():
            out |= numbers(item, f"{path}.{key}" if path else key)
    elif isinstance(value, list):
        for i, item in enumerate(value):
            out |= numbers(item, f"{path}.{i}")
    elif isinstance(value, int | float) and not isinstance(value, bool):
        out[path] = float(value)
    return out


@pytest.fixture(scope="module")
def work(tmp_path_factory) -> dict[str, list[object]]:
    """The commands of the checks, on samples: name -> argv (and its scaled twin, ``name@2``)."""
    folder = tmp_path_factory.mktemp("units")
    pair = RotorPair(5, 6, 116.0, 63.0, 45.0, 71.0, 53.0)
    rotors = build_family(pair, "rack-involute", {})
    male = rotors.male_outline(1e-3).points
    # the female 30 µm smaller all round (shapely's offset): a pair with a real clearance to measure
    female = np.asarray(shapely.Polygon(rotors.female_outline(1e-3).points).buffer(-0.03, quad_segs=64).exterior.coords)[:-1]
    cases: dict[str, list[object]] = {}
    for k in (1, 2):
        write_points(folder / f"male_{k}.csv", male * k)
        write_points(folder / f"female_{k}.csv", female * k)
        suffix = "" if k == 1 else "@2"
        design = RACK if k == 1 else scaled_design(RACK, folder, k)
        cases["gear" + suffix] = ["gear", "--teeth", 17, "--module", 3 * k, "--mate-teeth", 29]
        cases["gear-internal" + suffix] = ["gear", ROOT / "samples" / "internal_gear.toml", "--module", 2 * k]
        cases["gear-internal" + suffix] += ["--outer-diameter", 140 * k]
        cases["pump" + suffix] = ["pump", "--teeth", 11, "--module", 4 * k, "--shift", 0.3, "--face-width", 20 * k]
        cases["pump" + suffix] += ["--speed", 1500]
        cases["rotor" + suffix] = ["rotor", design]
        cases["hob" + suffix] = ["hob", design]
        cases["interfere" + suffix] = ["interfere", design, "--tolerance", 0.005 * k]  # the tolerance is a length too
        cases["clearance" + suffix] = [
            "clearance", "--male-points", folder / f"male_{k}.csv", "--female-points", folder / f"female_{k}.csv",
            "--male-teeth", 5, "--female-teeth", 6, "--center-distance", 116 * k, "--lead", 300 * k, "--length", 190 * k,
        ]  # fmt: skip
        cases["deflect" + suffix] = ["deflect", DEFLECT if k == 1 else scaled_design(DEFLECT, folder, k), "--terms", 4]
        cases["grind" + suffix] = ["grind", design, "--wheel-radius", 150 * k, "--worn-radius", 130 * k]
    cases["cut"] = ["cut", "--teeth", 11, "--module", 2]
    cases["cut-internal"] = ["cut", ROOT / "samples" / "internal_gear.toml"]
    cases["coupling"] = ["coupling", "--teeth", 40, "--module", 4, "--face-width", 32, "--speed", 8000, "--viscosity", 0.02]
    cases["coupling"] += ["--power", 4000, "--pressure-viscosity", 2e-8, "--misalignment-deg", 0.3]
    cases["export"] = ["export", ROOT / "samples" / "gear_pair.toml", "--format", "stl", "--out", folder / "export"]
    sweep = folder / "sweep.toml"
    sweep.write_text(f'[sweep]\nbase = "{RACK.as_posix()}"\n\n[vary]\n"pair.lead" = [290.0, 310.0]\n')
    cases["sweep"] = ["sweep", sweep, "--out", folder / "sweep.parquet", "--workers", 0]
    return cases


_JSON: dict[str, dict] = {}
_TABLE: dict[str, str] = {}


def json_of(work: dict[str, list[object]], name: str) -> dict:
    """The command's JSON (each case run once per module)."""
    if name not in _JSON:
        code, out = run([*work[name], "--json", "--quiet"])
        assert code == 0, out
        _JSON[name] = json.loads(out)
    return _JSON[name]


def table_of(work: dict[str, list[object]], name: str) -> str:
    """The command's table output (each case run once per module)."""
    if name not in _TABLE:
        code, out = run([*work[name], "--quiet"])
        assert code == 0, out
        _TABLE[name] = out
    return _TABLE[name]


COMMANDS = ["gear", "cut", "pump", "rotor", "hob", "interfere", "clearance", "deflect", "coupling", "export", "sweep", "grind"]
COMMANDS += ["gear-internal", "cut-internal"]  # an internal gear and its shaping ([shaper])
TABLES = [c for c in COMMANDS if c != "export"]  # export lists its files, with the units in the headings


@pytest.mark.parametrize("name", COMMANDS)
def test_every_numeric_json_key_is_declared(work, name):
    data = json_of(work, name)
    keys = numbers(data)
    if name == "sweep":  # best and top hold the sweep file's own names (varied keys, objectives)
        keys = {k: v for k, v in keys.items() if not k.startswith(("best.", "top[]."))}
    missing = sorted(k for k in keys if quantities.lookup(k) is None)
    assert not missing, f"{name}: no declaration in rotorcad.quantities for {missing}"
    assert len(keys) >= 3


def table_rows(out: str) -> list[tuple[str, str, str]]:
    """(quantity, first value, unit) of every row of rich's table whose value is a number."""
    rows = []
    for line in out.splitlines():
        if not line.startswith("│"):
            continue
        cells = [c.strip() for c in line.strip().strip("│").split("│")]
        if len(cells) >= 3 and re.fullmatch(r"-?\d+(\.\d+)?(e[-+]?\d+)?", cells[1]):
            rows.append((cells[0], cells[1], cells[-1]))
    return rows


@pytest.mark.parametrize("name", TABLES)
def test_every_unit_in_the_table_is_the_declared_one(work, name):
    out = table_of(work, name)
    rows = table_rows(out)
    assert len(rows) >= 2, out
    for key, _, unit in rows:
        declared = quantities.unit_of(key)
        assert declared, f"{name}: {key} is printed but not declared"
        assert unit == declared, f"{name}: {key} printed in {unit!r}, declared {declared!r}"


def test_the_keys_the_name_rules_misread_print_their_units(work):
    # the old rules on key names printed max_normal_clearance in N ("_n"), max_penetration as a ratio
    # ("penetRATIOn"), touching_threshold without mm³; the scaling test below checks these units
    printed = {}
    for name in ("clearance", "interfere"):
        printed |= {key: unit for key, _, unit in table_rows(table_of(work, name))}
    assert printed["max_normal_clearance"] == "mm" and printed["max_penetration"] == "mm"
    assert printed["touching_threshold"] == "mm³"


# quantities that are not results of the geometry: settings and thresholds that a scaled design keeps
NOT_SCALED = {
    "rotor": {"defect_accuracy"},  # the defect search's set accuracy, 1e-4 mm whatever the size
    # counts of the rotor outline's samples (chords at a set tolerance: more on a larger rotor), and
    # the check's set tolerance (1 um whatever the size)
    # and the wheel's default bore (a standard 127 mm bore whatever the size)
    "grind": {f"wheels.{w}.{k}" for w in ("new", "worn") for k in ("check_tolerance", "bore_radius")}
    | {
        f"wheels.{w}.{k}_point_count"
        for w in ("new", "worn")
        for k in ("profile", "no_contact", "unreached", "secondary_cutting")
    },
}


@pytest.mark.parametrize("name", ["gear", "gear-internal", "pump", "rotor", "hob", "interfere", "clearance", "grind"])
def test_declared_units_scale_with_the_design(work, name):
    base, twice = numbers(json_of(work, name)), numbers(json_of(work, f"{name}@2"))
    checked = 0
    for key, value in base.items():
        if key in NOT_SCALED.get(name, ()) or abs(value) < 1e-9 or key not in twice:
            continue
        unit = quantities.unit_of(key)
        power = math.log2(twice[key] / value) if twice[key] / value > 0 else math.nan
        assert abs(power - LENGTH_POWER[unit]) < 0.25, (
            f"{name}: {key} declared in {unit} (length power {LENGTH_POWER[unit]}) but scales as length^{power:.2f} "
            f"({value:.6g} -> {twice[key]:.6g} for a design twice the size)"
        )
        checked += 1
    assert checked >= 5


def test_deflect_sections_volumes_and_forces_scale_with_the_design(work):
    # the deflections themselves mix bending (q L^4 / E J, length^1) with the shear of the
    # equivalent bar (q L^2 / G A, length^0), so only the quantities of one similarity law are
    # checked: section values (Rinder & Deix eqs. 2-4), chamber volumes, and the gas forces at the
    # same pressure (force = pressure x area, length^2)
    base, twice = numbers(json_of(work, "deflect")), numbers(json_of(work, "deflect@2"))
    keys = [f"{rotor}_{key}" for rotor in ("male", "female") for key in ("section_area", "second_moment", "gas_force_n")]
    keys += ["chamber_max_volume", "displacement_per_male_rev", "male_kappa_max", "volume_ratio"]
    for key in keys:
        unit = quantities.unit_of(key)
        power = math.log2(twice[key] / base[key])
        assert abs(power - LENGTH_POWER[unit]) < 0.25, f"{key} declared in {unit} but scales as length^{power:.2f}"


def test_lookup_follows_dotted_paths_and_list_items():
    # a nested key takes its own declaration, else that of its name (rotorcad.quantities docstring)
    assert quantities.unit_of("max_sliding_at.value") == "m/s" and quantities.unit_of("max_slip_male.value") == "1"
    assert quantities.unit_of("racks.male.hob_tip_radius") == "mm" and quantities.unit_of("chambers.3.pressure_bar") == "bar"
    assert quantities.unit_of("no_such_key") == "" and quantities.lookup("value") is None
    assert quantities.axis_label("max_normal_clearance") == "largest normal clearance [mm]"
    assert quantities.symbol("deg") == "°" and quantities.column_suffix("mm²") == "mm2"


def test_points_files_carry_their_units_and_old_files_still_read(tmp_path):
    # CONTRACT.md, points files: the header x,y in mm; the units end the last comment line, so the
    # lines above the data stay as many as before (a script's skiprows) and readers skip them
    square = np.array([[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0], [0.5, 1.5]])
    old = tmp_path / "old.csv"
    old.write_text("# male outline\nx,y\n" + "".join(f"{x},{y}\n" for x, y in square))
    new = tmp_path / "new.csv"
    write_points(new, square, ["male outline"])
    assert np.array_equal(read_points(old), read_points(new))
    assert new.read_text().splitlines()[:2] == ["# male outline (units: x mm, y mm)", "x,y"]
    assert np.array_equal(np.loadtxt(new, delimiter=",", skiprows=2), square)  # numpy, as a user's script reads it


def test_the_clearance_csv_names_the_unit_of_every_column(work, tmp_path):
    # the unit line above the header: one declared unit per column, and the file still reads as
    # points (its first two columns x,y in mm; CONTRACT.md)
    csv = tmp_path / "clearance.csv"
    code, _ = run([*work["clearance"], "--csv", csv, "--quiet"])
    assert code == 0
    lines = csv.read_text().splitlines()
    header = next(line for line in lines if not line.startswith("#"))
    units = re.search(r"\(units: (.*)\)$", lines[lines.index(header) - 1]).group(1)
    named = dict(item.rsplit(" ", 1) for item in units.split(", "))
    assert list(named) == header.split(",")
    assert named["clearance"] == "mm" and named["male_angle_deg"] == "deg" and named["zone"] == "1"
    assert len(read_points(csv)) > 100


def test_sweep_columns_name_their_declared_unit():
    # CONTRACT.md, sweep rows: results with their unit at the end of the column's name; each
    # column is declared, its name ends with its unit, and a column copied from `rotor --json`
    # has the unit of that key
    from rotorcad.sweep.plan import Extra
    from rotorcad.sweep.plots import column_label
    from rotorcad.sweep.tasks import RESULT_COLUMNS, result_columns

    for column in result_columns(tuple(Extra)):
        q = quantities.SWEEP_COLUMNS[column]
        suffix = quantities.column_suffix(q.unit)
        assert not suffix or column.endswith("_" + suffix) or column == "seconds", f"{column} is in {q.unit}"
        assert column_label(column).endswith(f"[{quantities.symbol(q.unit)}]")
    for key, column in RESULT_COLUMNS.items():
        if column in quantities.SWEEP_COLUMNS:
            assert quantities.SWEEP_COLUMNS[column].unit == quantities.unit_of(key), column


def test_every_declaration_names_a_module_that_exists():
    # Quantity.source tells a newcomer where the number is computed: a module (or package) of the repository
    sources = {q.source for q in [*quantities.QUANTITIES.values(), *quantities.SWEEP_COLUMNS.values()]}
    missing = [s for s in sorted(sources) if not ((ROOT / f"{s}.py").is_file() or (ROOT / s / "__init__.py").is_file())]
    assert not missing
    assert all(q.unit and q.label for q in quantities.QUANTITIES.values())


def test_the_report_page_shows_the_declared_units(rack_report):
    # the page's result tables (sections numbers and hob; the design's own keys have their table)
    # show each number with its declared unit, ° for degrees and – for a pure number; the page of
    # `report RACK --out report.html --files files --json`, run once in the run (tests/conftest.py)
    _, page = rack_report
    html = page.read_text()
    checked = 0
    for section in ("numbers", "hob"):
        body = re.search(rf"<section id='{section}'.*?</section>", html, re.S).group(0)
        row = r"<tr data-key='([^']*)'[^>]*><td class='key'>[^<]*</td><td class='num'>([^<]*)</td><td>([^<]*)</td></tr>"
        for key, value, unit in re.findall(row, body):
            if not re.fullmatch(r"[−-]?[\d.]+(e[−+-]?\d+)?", value):
                continue
            assert quantities.lookup(key) is not None, f"{key} is on the page but not declared"
            assert unit == quantities.symbol(quantities.unit_of(key)), f"{key}: the page shows {unit!r}"
            checked += 1
    assert checked >= 30

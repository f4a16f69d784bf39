"""Values that look like another unit are warned about; a long export says so first (newuser5 F13).

References: the new user's inch-typed designs (the Rinder & Deix sample with every length / 25.4:
a = 3.228 mm; a module of 4 mm typed as 0.157 in), the standards' module series (DIN 780, ISO 54:
0.05 to 50 mm; 4/25.4 = 0.15748 is none of them), and the user's measured export of a 1000-tooth
helical gear (7 faces a tooth; STEP, STL and DXF: 263 s wall on the loaded 2-core machine, 4 minutes
without a word).
"""

from __future__ import annotations

import contextlib
import io
import json
import re
from pathlib import Path

import pytest

from rotorcad.cli.main import main
from rotorcad.design.plausibility import STANDARD_MODULES, module_warnings, screw_pair_warnings
from rotorcad.work import load_factor

ROOT = Path(__file__).resolve().parents[1]


def _run(args: list[str]) -> tuple[int, str, str]:
    out, err = io.StringIO(), io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
        status = main(args)
    return status, out.getvalue(), err.getvalue()


@pytest.mark.parametrize("module", STANDARD_MODULES)
def test_no_standard_module_is_warned_about(module):
    assert module_warnings(module, "--module") == []


@pytest.mark.parametrize("mm", [1.0, 1.5, 2.0, 2.5, 3.0, 4.0, 5.0, 6.0, 8.0, 10.0, 12.0, 20.0, 25.0])
def test_a_standard_module_typed_in_inches_is_warned_about(mm):
    for typed in (mm / 25.4, float(f"{mm / 25.4:.3g}")):  # as computed, and as a user rounds it (3 digits)
        said = module_warnings(typed, "[gear] module")
        assert len(said) == 1 and f"near the standard {mm:g} mm" in said[0] and "[gear] module" in said[0]


def test_modules_outside_the_series_are_warned_about():
    assert "above the largest standard module, 50 mm" in module_warnings(60.0, "--module")[0]
    assert "below the smallest standard module, 0.05 mm" in module_warnings(0.02, "--module")[0]


def test_an_inch_typed_screw_pair_is_warned_about_and_still_computed(tmp_path):
    design = (ROOT / "samples" / "rinder_deix_5_6.toml").read_text()
    for key in ("center_distance", "male_tip_radius", "male_root_radius", "female_tip_radius", "female_root_radius"):
        design = re.sub(rf"(?m)^({key}) = ([0-9.]+)", lambda m: f"{m.group(1)} = {float(m.group(2)) / 25.4}", design)
    path = tmp_path / "inch.toml"
    path.write_text(re.sub(r"(?m)^(lead|length) = ([0-9.]+)", lambda m: f"{m.group(1)} = {float(m.group(2)) / 25.4}", design))
    status, out, err = _run(["rotor", str(path), "--json", "--quiet"])
    assert status == 0 and out.startswith("{")  # a warning, not a refusal; stdout stays one JSON object
    assert "rotorcad: warning: [pair] center_distance 3.22835 mm is smaller than any screw compressor built" in err
    assert "in inches it would be 82 mm" in err
    assert screw_pair_warnings(82.0, "[pair] center_distance") == []


def test_an_inch_typed_gear_module_is_warned_about_by_gear_and_pump():
    status, _, err = _run(["gear", "--teeth", "20", "--module", "0.157", "--json"])
    assert status == 0 and "--module 0.157 mm is no standard module, but in inches it is 3.988 mm" in err
    status, _, err = _run(
        ["pump", "--teeth", "11", "--module", "0.15748", "--shift", "0.3", "--face-width", "0.79", "--speed", "1500"]
    )
    assert status == 0 and "near the standard 4 mm" in err
    status, _, err = _run(["gear", "--teeth", "20", "--module", "4", "--json"])
    assert status == 0 and "warning" not in err


@pytest.fixture
def idle(monkeypatch):
    """The machine's load left out of the STEP estimate (rotorcad.work.load_factor 1: an idle machine)."""
    from rotorcad import work

    monkeypatch.setattr(work, "load_factor", lambda *a: 1.0)


def test_a_gear_step_of_a_thousand_teeth_says_it_takes_minutes(capsys, idle):
    from rotorcad.cli import progress
    from rotorcad.cli.export_cmd import _say_long_files

    bar = progress.Steps("test", 1, quiet=True)
    noted = len(progress.NOTED)
    _say_long_files([{"format": "stl", "body": "gear"}, {"format": "step", "body": "gear", "faces": 7 * 100 + 2}], False, bar)
    assert len(progress.NOTED) == noted  # z = 100: some 5 s
    _say_long_files([{"format": "stl"}, {"format": "step", "faces": 7 * 1000 + 2}, {"format": "dxf"}], False, bar)
    note = progress.NOTED[-1]
    assert note.startswith("this will take about 4 min")  # the user's 263 s wall (STEP after 20 s, 4 min more)
    assert "--format dxf,stl would make it about" in note
    assert "rotorcad: note: this will take about 4 min" in capsys.readouterr().err
    noted = len(progress.NOTED)
    half = [{"format": "step", "body": "gear", "faces": 7 * 300 + 2}]  # a herringbone gear's plan: one half's faces
    _say_long_files(half, False, bar)
    assert len(progress.NOTED) == noted  # 2102 faces: some 17 s
    _say_long_files(half, False, bar, frozenset({"gear"}))
    assert len(progress.NOTED) == noted + 1  # both halves, 4204 faces: some 58 s


def test_the_step_faces_planned_are_seven_a_tooth(tmp_path):
    from exports.formats import plan_files, table
    from rotorcad.cli.gear_export import design_gear_bodies

    path = tmp_path / "g.toml"
    path.write_text("[gear]\nteeth = 40\nmodule = 1.0\nface_width = 20.0\nhelix_angle_deg = 20.0\n")
    rows = [row for _, row, _ in plan_files([table()["step"]], design_gear_bodies(path, 0.005), 0.005, tmp_path, "g")]
    assert rows[0]["faces"] == 7 * 40 + 2  # per tooth: root arc, 2 fillets, 2 flanks, tip; and the two end faces


def test_a_step_over_the_memory_bound_is_refused_naming_what_would_do(idle):
    # Measured peaks (rotorcad.work.STEP_MEGABYTES): helical z 1000 (7002 faces) 761 MB; herringbone
    # z 300 / 500 (4202 / 7002 faces) 915 / 1306 MB, so z 1000 (14002 faces) some 2.3 GB, over the 2 GB bound
    from rotorcad.cli import progress
    from rotorcad.cli.common import InputError
    from rotorcad.cli.export_cmd import _say_long_files
    from rotorcad.work import step_megabytes

    assert step_megabytes(7002) == pytest.approx(761, rel=0.05)
    assert step_megabytes(7002, True) == pytest.approx(1306, rel=0.05)
    bar = progress.Steps("test", 1, quiet=True)
    rows = [{"format": "stl", "body": "gear"}, {"format": "step", "body": "gear", "faces": 7 * 1000 + 2}]
    with pytest.raises(InputError) as refused:
        _say_long_files(rows, True, bar, frozenset({"gear"}))
    text = refused.value.format_message()
    assert "--format step cannot be written for the gear: its exact STEP of 14004 faces (a herringbone gear)" in text
    assert "about 2.3 GB, more than the 2 GB allowed; --format stl would do" in text
    _say_long_files(rows, True, bar)  # the helical gear of 1000 teeth: 761 MB, written (with its note)


def test_a_600_tooth_step_says_so_below_the_minute_and_scales_with_the_load(capsys, idle):
    # newuser7 F3: a helical gear of 600 teeth (4202 faces; the table's 58 s, under the 60-s
    # LONG_RUN_SECONDS) took 305 s of wall time on a loaded machine without a word. The crossing is
    # computed from the table (rotorcad.work.STEP_FACE_SECONDS), not timed.
    from rotorcad import work
    from rotorcad.cli import progress
    from rotorcad.cli.export_cmd import GEAR_STEP_FACES, _say_long_files

    bar = progress.Steps("test", 1, quiet=True)
    z600, z300 = GEAR_STEP_FACES * 600 + 2, GEAR_STEP_FACES * 300 + 2
    assert work.step_seconds(z300) < work.STEP_NOTE_SECONDS < work.step_seconds(z600) < work.LONG_RUN_SECONDS
    noted = len(progress.NOTED)
    _say_long_files([{"format": "step", "body": "gear", "faces": z600}], False, bar)
    assert progress.NOTED[noted:] == [
        "this will take about 58 s (an estimate from measured runs); --format stl would make it about 5 s"
    ]
    _say_long_files([{"format": "step", "body": "gear", "faces": z300}], False, bar)
    assert len(progress.NOTED) == noted + 1  # 17 s on an idle machine: no note
    # on a machine loaded 3 times over its 2 cores (load average 6): the 300-tooth gear's 17 s become 51 s
    factor = load_factor(6.0, 2)  # the function itself, not the fixture's
    assert factor == 3.0 and load_factor(0.5, 2) == 1.0
    progress.NOTED.clear()
    with pytest.MonkeyPatch.context() as mp:
        mp.setattr(work, "load_factor", lambda *a: factor)
        _say_long_files([{"format": "step", "body": "gear", "faces": z300}], False, bar)
    assert progress.NOTED == [
        f"this will take about {3 * work.step_seconds(z300):.0f} s (an estimate from measured runs, times 3.0 for "
        "this machine's load now); --format stl would make it about 5 s"
    ]


def test_a_herringbone_gear_too_big_for_a_step_is_refused_before_it_is_built(tmp_path, monkeypatch, capsys):
    # newuser7 F4: the herringbone gear of 1000 teeth (toml/g1000hb.toml) was refused after 105 s of
    # building all bodies. Reference: the refusal the built gear's plan gives (14004 faces, 2.3 GB), and the
    # gear builder is never called.
    from rotorcad.cli import gear_export

    def never(*args, **kwargs):
        raise AssertionError("the gear was built before the refusal")

    monkeypatch.setattr(gear_export, "design_gear_bodies", never)
    design = tmp_path / "g1000hb.toml"
    design.write_text("[gear]\nteeth = 1000\nmodule = 2.0\nhelix_angle_deg = 15.0\nface_width = 30.0\nherringbone = true\n")
    out = tmp_path / "exp"
    status, stdout, err = _run(["export", str(design), "--format", "step", "--out", str(out)])
    assert status == 2 and stdout == "" and not out.exists()
    assert err.count("\n") == 1 and err.startswith("rotorcad: error: --format step cannot be written for the gear: ")
    assert "its exact STEP of 14004 faces (a herringbone gear) would need about 2.3 GB" in err


def _inch_n_rack(tmp_path: Path, rounded: bool) -> Path:
    """The n-rack sample (Wu & Chi's N4 pair, a = 82.0 mm, Table 1) typed in inches to 4 decimals.

    ``rounded``: every radius typed as its own rounded number, as newuser7 did (toml/nrack_inch.toml
    before the user linked the female radii): the female root radius 24.01 / 25.4 = 0.94528 -> 0.9453.
    """
    design = (ROOT / "samples" / "n_rack_5_6.toml").read_text()
    keys = ("center_distance", "male_tip_radius", "male_root_radius", "female_tip_radius", "female_root_radius")
    pattern = r"(?m)^(" + "|".join((*keys, "lead", "length")) + r") = ([0-9.]+)"
    design = re.sub(pattern, lambda m: f"{m.group(1)} = {float(m.group(2)) / 25.4:.4f}", design)
    if not rounded:
        design = re.sub(r"(?m)^female_tip_radius = .*$", 'female_tip_radius = "a - male_root_radius"', design)
        design = re.sub(r"(?m)^female_root_radius = .*$", 'female_root_radius = "a - male_tip_radius"', design)
    path = tmp_path / ("nrack_inch_rounded.toml" if rounded else "nrack_inch.toml")
    path.write_text(design)
    return path


def test_a_rounded_inch_design_is_refused_naming_inches_in_the_one_sentence(tmp_path):
    # newuser7 F5: the refusal "[pair] female_root_radius must be at most 0.9452 mm ... (got 0.9453)" said
    # nothing of inches. Reference: a = 82.0 mm (Wu & Chi, Table 1) / 25.4 = 3.2283.
    path = _inch_n_rack(tmp_path, rounded=True)
    assert "center_distance = 3.2283" in path.read_text() and "female_root_radius = 0.9453" in path.read_text()
    for command in ("rotor", "hob"):
        status, out, err = _run([command, str(path), "--json", "--quiet"])
        assert status == 2 and out == "" and err.count("\n") == 1, err
        assert err.startswith("rotorcad: error: [pair] female_root_radius must be at most 0.9452 mm")
        assert err.endswith(
            "(got 0.9453); [pair] center_distance 3.2283 mm looks like a design typed in inches (82 mm): "
            "rotorcad takes every length in mm.\n"
        )
    status, out, err = _run(["rotor", str(_inch_n_rack(tmp_path, rounded=False)), "--json", "--quiet"])
    assert status == 0 and "[pair] center_distance 3.2283 mm is smaller than any screw compressor" in err  # linked: runs


def test_the_inch_hint_is_added_only_to_refusals_about_lengths_of_an_inch_sized_pair():
    from rotorcad.design.plausibility import with_inch_hint

    said = "[pair] male_root_radius must be equal to the male pitch radius 2.07586 mm (got 2.0758)."
    assert with_inch_hint(said, 4.5669, "[pair] center_distance").endswith("inches (116 mm): rotorcad takes every length in mm.")
    assert with_inch_hint(said, 116.0, "[pair] center_distance") == said  # Rinder's narrow-tip pair in mm
    assert with_inch_hint(said, 25.0, "[pair] center_distance") == said  # the 25-mm micro-compressor
    other = "[pair] male_teeth must be a whole number from 2 to 12 (got 1)."
    assert with_inch_hint(other, 3.2283, "[pair] center_distance") == other  # not about lengths


@pytest.mark.parametrize("mm", [315.0, 400.0, 510.0, 630.0, 700.0, 250.0, 160.0])
def test_a_large_machine_typed_in_inches_is_warned_about(mm):
    # newuser7 F5: 315/400/510-mm machines typed in inches (12.4/15.7/20.1) got no warning (the bound was
    # 10 mm). Reference: the value typed is mm / 25.4 to 4 decimals (and to 3), and the warning names mm.
    for digits in (4, 3):
        typed = round(mm / 25.4, digits)
        said = screw_pair_warnings(typed, "[pair] center_distance")
        assert len(said) == 1 and f"{mm:.4g} mm" in said[0] and "rotorcad takes every length in mm" in said[0], typed


def test_no_inch_warning_for_the_samples_or_a_micro_compressor(tmp_path):
    # The samples' centre distances (Rinder's 116 mm and the like; the N4 pair's 82 mm) and the 25-mm
    # micro-compressor of newuser7 (its design typed to 0.1 mm), and round small machines of 20-28 mm.
    import tomllib

    for sample in sorted((ROOT / "samples").glob("*.toml")):
        a = tomllib.loads(sample.read_text()).get("pair", {}).get("center_distance")
        if isinstance(a, (int, float)):
            assert screw_pair_warnings(float(a), "[pair] center_distance") == [], sample.name
    for a in (20.0, 21.5, 22.5, 25.0, 26.3, 27.5, 28.0, 30.0, 45.0):
        assert screw_pair_warnings(a, "[pair] center_distance") == [], a
    design = (ROOT / "samples" / "n_rack_5_6.toml").read_text()
    scale = 25.0 / 82.0
    for key in ("center_distance", "male_tip_radius", "male_root_radius", "female_tip_radius", "female_root_radius"):
        design = re.sub(rf"(?m)^({key}) = ([0-9.]+)", lambda m: f"{m.group(1)} = {float(m.group(2)) * scale:.4f}", design)
    design = re.sub(r"(?m)^(lead|length) = ([0-9.]+)", lambda m: f"{m.group(1)} = {float(m.group(2)) * scale:.4f}", design)
    path = tmp_path / "micro25.toml"
    path.write_text(design)
    status, _, err = _run(["rotor", str(path), "--json", "--quiet"])
    assert status == 0 and "warning" not in err, err


def test_a_gear_step_note_is_said_once_before_the_gear_is_built(tmp_path, monkeypatch, idle):
    # newuser7 F3/F4: the note came after all bodies were built. With the note's threshold at 0 s, a gear
    # of 20 teeth (142 faces, GEAR_STEP_FACES a tooth) says it before design_gear_bodies is called, once.
    from rotorcad import work
    from rotorcad.cli import gear_export, progress

    monkeypatch.setattr(work, "STEP_NOTE_SECONDS", 0.0)
    built = gear_export.design_gear_bodies
    at_build = []
    monkeypatch.setattr(gear_export, "design_gear_bodies", lambda *a: at_build.append(len(progress.NOTED)) or built(*a))
    design = tmp_path / "g20.toml"
    design.write_text("[gear]\nteeth = 20\nmodule = 2.0\nhelix_angle_deg = 15.0\nface_width = 30.0\n")
    noted = len(progress.NOTED)
    status, out, err = _run(["export", str(design), "--format", "step", "--out", str(tmp_path / "o"), "--json"])
    assert status == 0 and at_build == [noted + 1] and len(progress.NOTED) == noted + 1
    assert err.count("rotorcad: note: this will take about") == 1
    assert [f["faces"] for f in json.loads(out)["files"]] == [7 * 20 + 2]  # the estimate's faces, measured on the solid

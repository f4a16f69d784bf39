"""Issue 24, what was left: design lengths bounded above (100 m), the note before a long run, and a
Ctrl-C at start-up. Fast: every refusal comes before any heavy work."""

from __future__ import annotations

import re
import subprocess
import sys
from pathlib import Path

import pytest

from rotorcad.cli.main import main
from rotorcad.errors import DesignError
from rotorcad.rotor_pair import MAX_LENGTH, RotorPair

ROOT = Path(__file__).resolve().parents[1]
SAMPLES = ROOT / "samples"

# the 100 m bound: no rotor, gear or shaft is larger; the DXF reader's extent limit is the same
# (exports.dxf_profile.MAX_EXTENT), so a design the CLI accepts can always be written and read back
RANGE = "a positive length up to 100000 mm (100 m)"


def refused(capsys, *argv: object) -> str:
    capsys.readouterr()
    status = main([str(a) for a in argv])
    _, err = capsys.readouterr()
    lines = [ln for ln in err.splitlines() if ln.strip()]
    assert status == 2 and len(lines) == 1 and "Traceback" not in err, err
    return lines[0]


def design_with(tmp_path: Path, key: str, value: str) -> Path:
    text = (SAMPLES / "lysholm_4_6.toml").read_text()
    text, n = re.subn(rf"^{key} = .*$", f"{key} = {value}", text, flags=re.M)
    assert n == 1
    path = tmp_path / f"{key}.toml"
    path.write_text(text)
    return path


def test_max_length_is_the_dxf_extent_limit():
    from exports.dxf_profile import MAX_EXTENT

    assert MAX_LENGTH == MAX_EXTENT == 1e5


@pytest.mark.parametrize(
    "key", ["length", "lead", "center_distance", "male_tip_radius", "female_tip_radius", "male_root_radius", "female_root_radius"]
)
def test_pair_length_1e30_refused_naming_the_key(capsys, tmp_path, key):
    """`[pair] length = 1e30` was accepted (exit 0): each pair length is refused above 100 m."""
    line = refused(capsys, "rotor", design_with(tmp_path, key, "1e30"), "--json")
    assert line == f"rotorcad: error: [pair] {key} must be {RANGE} (got 1e+30).", line


def test_pair_option_above_100_m_names_the_option(capsys):
    """An option typed over a design's value is named as typed (it was named `[pair] length`)."""
    line = refused(capsys, "rotor", SAMPLES / "lysholm_4_6.toml", "--length", "1e30", "--json")
    assert line.startswith("rotorcad: error: --length must be " + RANGE), line


@pytest.mark.parametrize("key", ["length", "lead"])
def test_pair_length_bound_is_inclusive(key):
    """At 100 m exactly a lead or length is accepted; just above it refused (the bound, not a typo)."""
    base = dict(
        male_teeth=4,
        female_teeth=6,
        center_distance=100.0,
        male_tip_radius=60.0,
        male_root_radius=40.0,
        female_tip_radius=60.0,
        female_root_radius=40.0,
    )
    assert getattr(RotorPair(**base, **{key: 1e5}), key) == 1e5
    with pytest.raises(DesignError, match=re.escape(RANGE)):
        RotorPair(**base, **{key: 1.000001e5})


def test_gear_mate_center_distance_1e30(capsys, tmp_path):
    """`[mate] center_distance = 1e30` was refused naming `--mate-shift` (solved from it, 1e18 modules)."""
    design = tmp_path / "g.toml"
    design.write_text("[gear]\nteeth = 17\nmodule = 3.0\n[mate]\nteeth = 29\ncenter_distance = 1e30\n")
    line = refused(capsys, "gear", design, "--json")
    assert line == f"rotorcad: error: [mate] center_distance must be {RANGE} (got 1e+30).", line
    line = refused(capsys, "cut", "--teeth", 17, "--module", 3, "--mate-teeth", 29, "--center-distance", "1e30", "--json")
    assert line.startswith(f"rotorcad: error: --center-distance must be {RANGE}"), line


@pytest.mark.parametrize(
    ("option", "value", "expected"),
    [("--face-width", "1e30", "up to 10000 mm"), ("--speed", "1e30", "up to 1e+06 rpm")],
)
def test_pump_face_width_and_speed_bounded(capsys, option, value, expected):
    """`pump --face-width 1e30` was accepted: the face width as export's [gear] face_width (10 m), the
    speed as coupling's (1e6 rpm)."""
    argv = {"--face-width": "20", "--speed": "1000", option: value}
    line = refused(capsys, "pump", "--teeth", 12, "--module", 3, *[x for kv in argv.items() for x in kv], "--json")
    assert option in line and expected in line, line


# A Ctrl-C at the moment the command imports `module`: a finder put first on sys.meta_path sends
# SIGINT to the process when `module` is looked up, so Python raises KeyboardInterrupt inside that
# import, as a real Ctrl-C in the first few hundred ms does (found by sending SIGINT 0-60 ms after
# start: 28 of 60 runs printed Python's traceback, from typing, click, rotorcad.cli.main, ...).
_INTERRUPT_AT_IMPORT = """
import os, signal, sys
signal.signal(signal.SIGINT, signal.default_int_handler)  # as from a shell, whatever the test runner's process ignores
class Interrupt:
    def find_spec(self, name, path=None, target=None):
        if name == {module!r}:
            sys.meta_path.remove(self)
            os.kill(os.getpid(), signal.SIGINT)
        return None
sys.meta_path.insert(0, Interrupt())
sys.argv = ["rotorcad", "gear", "--teeth", "17", "--module", "3", "--json"]
from rotorcad.cli.main import main  # as the console script of pyproject [project.scripts]
sys.exit(main())
"""


@pytest.mark.parametrize("module", ["typing", "threading", "click", "rotorcad.errors"])
def test_ctrl_c_while_the_command_loads(module):
    """A Ctrl-C before rotorcad has loaded is one line and exit 130, nothing on stdout (issue 24)."""
    script = _INTERRUPT_AT_IMPORT.format(module=module)
    proc = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True, timeout=60, cwd=ROOT)
    assert proc.returncode == 130, proc.stderr
    assert proc.stderr.strip() == "rotorcad: interrupted." and proc.stdout == "", proc.stderr


# ----- a note before a run of over a minute (issue 24) -----------------------------------------


def sweep_file(tmp_path: Path, samples: int, compute: str) -> Path:
    """The sample sweep with ``samples`` variants and ``compute`` analyses, without its ranking."""
    text = (SAMPLES / "sweep_rack_involute.toml").read_text().split("[constraints]")[0]
    text, n = re.subn(r"^samples = .*$", f"samples = {samples}", text, flags=re.M)
    text, m = re.subn(r"^compute = .*$", f"compute = {compute}", text, flags=re.M)
    assert n == m == 1
    path = tmp_path / f"sweep_{samples}.toml"
    path.write_text(text)
    return path


def test_sweep_estimate_against_a_measured_run(tmp_path, capsys):
    """The estimate (rotorcad.work.SWEEP_SECONDS) against the CPU time of a small sweep run now:
    the estimate is a calibration of the same code, so a change that makes a variant much slower or
    faster shows here. Within a factor 3 either way (the CPU time of 12 variants varies with them)."""
    import json

    from rotorcad.work import sweep_seconds

    design = sweep_file(tmp_path, 12, '["volume"]')
    capsys.readouterr()
    assert main(["sweep", str(design), "--out", str(tmp_path / "s.parquet"), "--workers", "0", "--json", "--quiet"]) == 0
    result = json.loads(capsys.readouterr().out)
    assert result["computed"] == 12
    estimate = sweep_seconds(12, ("volume",), 1)
    assert result["cpu_seconds"] / 3 < estimate < 3 * result["cpu_seconds"], (estimate, result["cpu_seconds"])


def test_long_sweep_says_so_before_it_starts(tmp_path, capsys, monkeypatch):
    """A sweep of 5000 variants with interference, in this process: about 15 min by the estimate
    (5000 x (0.022 + 0.164) s). The note comes on stderr before the first variant is computed (the
    work is replaced by a Ctrl-C, so that nothing runs for a minute); stdout stays empty for --json."""
    import os

    from rotorcad.cli import progress
    from rotorcad.sweep import run as sweep_run
    from rotorcad.work import sweep_seconds

    def no_work(*args, **kwargs):
        raise KeyboardInterrupt

    monkeypatch.setattr(sweep_run, "evaluate_batch", no_work)
    design = sweep_file(tmp_path, 5000, '["interference"]')
    capsys.readouterr()
    status = main(["sweep", str(design), "--out", str(tmp_path / "s.parquet"), "--workers", "0", "--json"])
    out, err = capsys.readouterr()
    assert status == 130 and out == ""
    lines = err.strip().splitlines()
    cores = os.cpu_count() or 1
    minutes = round(5000 * 0.186 / 60)
    expected = f"rotorcad: note: this will take about {minutes} min"
    assert lines[0].startswith(expected), err
    if cores > 1:
        faster = sweep_seconds(5000, ("interference",), cores)
        assert f"; --workers {cores} would make it about " in lines[0], err
        assert faster < 5000 * 0.186 / cores + 6
    assert lines[-1] == "rotorcad: interrupted."
    assert progress.NOTED[-1] in lines[0]


def test_long_sweep_note_silenced_by_quiet_and_absent_for_a_short_one(tmp_path, capsys, monkeypatch):
    """--quiet says nothing; a sweep estimated under a minute (60 variants, 1.3 s) says nothing."""
    from rotorcad.sweep import run as sweep_run

    def no_work(*args, **kwargs):
        raise KeyboardInterrupt

    monkeypatch.setattr(sweep_run, "evaluate_batch", no_work)
    for samples, extra in ((5000, ["--quiet"]), (60, [])):
        design = sweep_file(tmp_path, samples, '["interference"]' if samples > 60 else "[]")
        capsys.readouterr()
        status = main(["sweep", str(design), "--out", str(tmp_path / f"s{samples}.parquet"), "--workers", "0", *extra])
        _, err = capsys.readouterr()
        assert status == 130 and "note" not in err, err


def test_long_run_note_wording():
    """The sentence of CONTRACT.md, in minutes above 90 s, and nothing up to a minute."""
    from rotorcad.work import long_run_note

    assert long_run_note(60.0, ("--workers", 2, 30.0)) is None
    assert long_run_note(930.0, ("--workers", 2, 470.0)) == "this will take about 16 min; --workers 2 would make it about 8 min"
    assert long_run_note(75.0, ("--workers", 2, 40.0)) == "this will take about 75 s; --workers 2 would make it about 40 s"
    assert long_run_note(7200.0, None) == "this will take about 2.0 h"


def test_clearance_with_many_points_says_so_before_the_work(tmp_path, capsys, monkeypatch):
    """`clearance` of 2.6 million points took 67 s: the note comes after the points are read and
    before the work. Here the time a point is set to 1 s, so that the sample's 2 630 points stand
    for a long run, and the work is replaced by a Ctrl-C."""
    import numpy as np

    from rotorcad import work
    from rotorcad.cli import clearance_cmd

    def no_work(*args, **kwargs):
        raise KeyboardInterrupt

    folder = tmp_path
    assert (
        main(
            [
                "rotor",
                str(SAMPLES / "srm_symmetric_4_6.toml"),
                "--male-csv",
                str(folder / "m.csv"),
                "--female-csv",
                str(folder / "f.csv"),
                "--quiet",
            ]
        )
        == 0
    )
    points = sum(len(np.loadtxt(folder / f"{s}.csv", delimiter=",", comments="#", skiprows=2)) for s in "mf")
    monkeypatch.setattr(work, "CLEARANCE_SECONDS", (0.0, 1.0))
    monkeypatch.setattr(clearance_cmd, "MeshingClearance", no_work)
    capsys.readouterr()
    argv = [
        "clearance",
        "--male-points",
        folder / "m.csv",
        "--female-points",
        folder / "f.csv",
        "--male-teeth",
        4,
        "--female-teeth",
        6,
        "--center-distance",
        100,
        "--json",
    ]
    status = main([str(a) for a in argv])
    out, err = capsys.readouterr()
    assert status == 130 and out == ""
    lines = err.strip().splitlines()
    assert lines[0] == f"rotorcad: note: this will take about {points / 60:.0f} min.", err
    assert lines[-1] == "rotorcad: interrupted."

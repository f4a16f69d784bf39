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

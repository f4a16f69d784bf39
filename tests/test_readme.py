"""The README's Python example runs as printed, and its first two lines are the two commands."""

from __future__ import annotations

import re
from pathlib import Path

import numpy as np

README = (Path(__file__).resolve().parents[1] / "README.md").read_text()


def test_python_example_runs_and_generates_an_involute():
    block = re.search(r"```python\n(.*?)```", README, re.S).group(1)
    scope: dict = {}
    exec(compile(block, "README.md", "exec"), scope)
    # the rack flank through C = (30, 0) at angle alpha generates the involute of r_b = 30 cos(alpha)
    pts = scope["points"]
    rb = 30.0 * np.cos(np.arctan2(0.72794, 2.0))
    a = np.arccos(rb / np.hypot(*pts.T))
    th = np.arctan2(pts[:, 1], pts[:, 0]) + np.tan(a) - a
    assert np.ptp(th) < 1e-12


def test_first_two_commands():
    sh = re.search(r"```sh\n(.*?)```", README, re.S).group(1).strip().splitlines()
    assert len(sh) == 2
    assert "rotorcad export samples/rack_involute_5_6.toml" in sh[0]
    ci = (Path(__file__).resolve().parents[1] / ".ci" / "run").read_text()
    assert sh[1] in ci


def test_the_contract_the_readme_links_is_in_the_project_and_names_every_command():
    # CONTRACT.md is the users' interface: the README links it, and every command it lists exists
    # in the command line (click's registry, not this file's text).
    from rotorcad.cli.main import cli

    root = Path(__file__).resolve().parents[1]
    assert "](CONTRACT.md)" in README
    contract = (root / "CONTRACT.md").read_text()
    listed = set(re.findall(r"^### `rotorcad (\w+)`", contract, re.M))
    implemented = {name for name in cli.list_commands(None) if cli.get_command(None, name) is not None}
    assert {"gear", "cut", "rotor", "hob", "export", "interfere", "clearance", "pump"} <= listed & implemented


def test_the_help_lists_every_command_without_loading_them():
    # `rotorcad --help` must start at once: listing the commands imports none of their modules
    # (a fresh interpreter; sys.modules is the reference)
    import subprocess
    import sys

    code = (
        "import sys; from rotorcad.cli.main import main; main(['--help']); "
        "print('HEAVY', sorted(m for m in ('numpy', 'scipy', 'shapely', 'trimesh', 'matplotlib', 'OCP') if m in sys.modules))"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout
    assert "HEAVY []" in out
    for name in ("gear", "rotor", "hob", "cut", "pump", "export", "interfere", "clearance"):
        assert f"  {name} " in out

"""Long stages show a progress bar on a terminal (issue 15: nothing runs longer than a minute
without one), and none with --quiet or off a terminal (CONTRACT.md)."""

from __future__ import annotations

from pathlib import Path

import pytest

from rotorcad.cli import progress
from rotorcad.cli.main import main

SAMPLES = Path(__file__).resolve().parent.parent / "samples"
ASYM = str(SAMPLES / "srm_asymmetric_5_6.toml")


def long_paths(tmp: Path) -> list[tuple[list[str], str]]:
    """Each command whose work can grow past a minute on valid input, on a small input, with the
    words its bar shows."""
    return [
        (["cut", "--teeth", "11", "--module", "2", "--tolerance", "0.01"], "cutting"),
        (["export", ASYM, "--out", str(tmp / "solids"), "--tolerance", "0.2", "--format", "stl"], "sweeping solids"),
        (["interfere", ASYM, "--steps", "4", "--tolerance", "0.1", "--check-3d"], "interference: 2-D sweep"),
        (["deflect", ASYM, "--terms", "8"], "deflection: angle sweep"),
        (["gear", "--teeth", "17", "--module", "2", "--csv", str(tmp / "g.csv")], "gear: writing files"),
    ]


@pytest.mark.parametrize("case", range(5))
def test_long_paths_show_a_bar_on_a_terminal(capsys, monkeypatch, tmp_path, case):
    argv, words = long_paths(tmp_path)[case]
    monkeypatch.setattr(progress, "on_terminal", lambda: True)
    capsys.readouterr()
    assert main(argv) in (0, 1)  # interfere: 1 is its finding
    err = capsys.readouterr().err
    assert words in err
    # --quiet: no bar, but the stage is still opened (what the fuzz suite counts)
    opened = len(progress.OPENED)
    assert main([*argv, "--quiet"]) in (0, 1)
    assert "━" not in capsys.readouterr().err
    assert len(progress.OPENED) > opened


def test_no_bar_off_a_terminal(capsys, tmp_path):
    argv, _ = long_paths(tmp_path)[0]
    capsys.readouterr()
    assert main(argv) == 0
    assert capsys.readouterr().err == ""

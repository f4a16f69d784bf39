"""An output file never replaces a file the same command reads.

A new user ran ``rotor --male-points out/io.csv --male-csv out/io.csv``: the measured points were
replaced by the fitted outline with only a note ("replaced the existing file"). Every command that
writes files through :class:`rotorcad.cli.common.Outputs` refuses an output naming one of its
inputs (by its path, another spelling of it, or a link to it), exit 2, the input untouched.
The reference is the input file's bytes before the run.
"""

from __future__ import annotations

import hashlib
import os
import shutil
from pathlib import Path

import pytest

from rotorcad.cli.main import main

SAMPLES = Path(__file__).resolve().parents[1] / "samples"
SAMPLE = SAMPLES / "rack_involute_5_6.toml"
PAIR = ["--male-teeth", "5", "--female-teeth", "6", "--center-distance", "116"]


def _digest(path: Path) -> str:
    return hashlib.sha256(path.read_bytes()).hexdigest()


@pytest.fixture(scope="module")
def outlines(tmp_path_factory) -> tuple[Path, Path]:
    folder = tmp_path_factory.mktemp("outlines")
    m, f = folder / "m.csv", folder / "f.csv"
    assert main(["rotor", str(SAMPLE), "--male-csv", str(m), "--female-csv", str(f), "--quiet"]) == 0
    return m, f


def _case(tmp_path: Path, outlines, spelling: str) -> tuple[Path, Path]:
    """A copy of the male points and the name an output gives it (``spelling``)."""
    given = tmp_path / "io.csv"
    shutil.copy(outlines[0], given)
    if spelling == "link":
        os.symlink(given, tmp_path / "link.csv")
        return given, tmp_path / "link.csv"
    if spelling == "dotted":
        return given, tmp_path / "." / "io.csv"
    return given, given


@pytest.mark.parametrize("spelling", ["same", "dotted", "link"])
@pytest.mark.parametrize("output", ["--male-csv", "--female-csv", "--dxf"])
def test_rotor_refuses_to_write_over_its_points(tmp_path, outlines, capsys, spelling, output):
    given, named = _case(tmp_path, outlines, spelling)
    before = _digest(given)
    status = main(["rotor", str(SAMPLE), "--male-points", str(given), output, str(named), "--quiet"])
    err = capsys.readouterr().err
    assert status == 2, err
    assert output in err and "--male-points" in err and len(err.strip().splitlines()) == 1, err
    assert _digest(given) == before


def test_rotor_refuses_to_write_over_its_design(tmp_path, capsys):
    design = tmp_path / "d.toml"
    shutil.copy(SAMPLE, design)
    before = _digest(design)
    assert main(["rotor", str(design), "--male-csv", str(design), "--quiet"]) == 2
    err = capsys.readouterr().err
    assert "--male-csv" in err and "design" in err, err
    assert _digest(design) == before


def test_clearance_refuses_its_csv_over_the_female_points(tmp_path, outlines, capsys):
    female = tmp_path / "f.csv"
    shutil.copy(outlines[1], female)
    before = _digest(female)
    argv = ["clearance", "--male-points", str(outlines[0]), "--female-points", str(female), *PAIR, "--csv", str(female)]
    assert main(argv) == 2
    err = capsys.readouterr().err
    assert "--csv" in err and "--female-points" in err, err
    assert _digest(female) == before


def test_an_output_beside_the_input_is_written(tmp_path, outlines, capsys):
    """The refusal is for the input's own file only: another file in its folder is written."""
    given, _ = _case(tmp_path, outlines, "same")
    argv = [
        "clearance",
        "--male-points",
        str(given),
        "--female-points",
        str(outlines[1]),
        *PAIR,
        "--csv",
        str(tmp_path / "c.csv"),
    ]
    assert main(argv) == 0, capsys.readouterr().err
    assert (tmp_path / "c.csv").stat().st_size > 0

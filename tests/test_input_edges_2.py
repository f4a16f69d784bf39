"""Regression tests for the examples of issue 24 ("Every input gets an answer, part 2"): each test
names the example it covers and uses its exact input. Fast: refusals come before any heavy work."""

from __future__ import annotations

import json
import os
import re
import signal
import subprocess
import sys
import textwrap
import time
from pathlib import Path

import numpy as np
import pytest

from rotorcad.cli.main import main

ROOT = Path(__file__).resolve().parents[1]
SAMPLES = ROOT / "samples"


def run(capsys, *argv: object) -> tuple[int, str, str]:
    capsys.readouterr()
    status = main([str(a) for a in argv])
    out, err = capsys.readouterr()
    assert "Traceback" not in err
    return status, out, err


def refused(capsys, needle: str, *argv: object) -> str:
    status, _, err = run(capsys, *argv)
    lines = [ln for ln in err.splitlines() if ln.strip()]
    assert status == 2 and len(lines) == 1 and needle in lines[0], err
    return lines[0]


def _alive(pid: int) -> bool:
    """Whether ``pid`` is a live process (a zombie, dead but not yet reaped, counts as gone)."""
    try:
        with open(f"/proc/{pid}/stat") as f:
            return f.read().rsplit(")", 1)[1].split()[0] != "Z"
    except OSError:
        return False


@pytest.mark.skipif(sys.platform != "linux", reason="the worker process exists on Linux only")
def test_worker_dies_with_a_parent_killed_by_sigkill(tmp_path):
    """An `export` killed at a time limit left its background writer alive for 42 minutes: the
    parent is killed with SIGKILL while its worker waits, and the worker must be gone within 5 s."""
    script = textwrap.dedent(
        f"""
        import os, sys, time
        sys.path.insert(0, {str(ROOT)!r})
        from exports.background import WorkerPool
        pool = WorkerPool()
        assert pool._executor is not None, "no worker"
        pids = list(pool._executor._processes)
        print(" ".join(map(str, pids)), flush=True)
        time.sleep(600)
        """
    )
    env = {**os.environ, "ROTORCAD_WORKERS": "1"}
    parent = subprocess.Popen([sys.executable, "-c", script], stdout=subprocess.PIPE, text=True, env=env)
    workers: list[int] = []
    try:
        line = parent.stdout.readline()
        workers = [int(p) for p in line.split()]
        assert workers and all(_alive(p) for p in workers), line
        parent.send_signal(signal.SIGKILL)
        parent.wait(10)
        deadline = time.monotonic() + 5.0
        while any(_alive(p) for p in workers) and time.monotonic() < deadline:
            time.sleep(0.05)
        assert not any(_alive(p) for p in workers), f"worker {workers} outlived its parent"
    finally:
        if parent.poll() is None:
            parent.kill()
        for pid in workers:  # a worker left by a failure: end it here, not at the end of the run
            if _alive(pid):
                os.kill(pid, signal.SIGKILL)


# ----- DXF points files -----------------------------------------------------------------------
CLEARANCE = ["--male-teeth", "4", "--female-teeth", "6", "--center-distance", "100"]


@pytest.fixture(scope="module")
def outlines(tmp_path_factory) -> dict[str, np.ndarray]:
    """The symmetric sample's male and female outlines as `rotor --male-csv` writes them."""
    folder = tmp_path_factory.mktemp("outlines")
    argv = ["rotor", str(SAMPLES / "srm_symmetric_4_6.toml"), "--male-csv", str(folder / "m.csv")]
    assert main([*argv, "--female-csv", str(folder / "f.csv")]) == 0
    return {s: np.loadtxt(folder / f"{s[0]}.csv", delimiter=",", comments="#", skiprows=2) for s in ("male", "female")}


def polyline_dxf(path: Path, pts: np.ndarray, closed: bool = True) -> Path:
    """One LWPOLYLINE through ``pts`` (drawn with ezdxf, the project's DXF library)."""
    import ezdxf

    doc = ezdxf.new()
    doc.modelspace().add_lwpolyline(np.asarray(pts, dtype=float).tolist(), close=closed)
    doc.saveas(path)
    return path


def test_dxf_points_with_one_nan_coordinate(capsys, tmp_path, outlines):
    """`clearance --male-points male.dxf` with one `nan` coordinate: ZeroDivisionError in `_segment`."""
    male = outlines["male"].copy()
    male[5, 0] = np.nan
    m = polyline_dxf(tmp_path / "male.dxf", male)
    f = polyline_dxf(tmp_path / "female.dxf", outlines["female"])
    line = refused(capsys, "--male-points", "clearance", "--male-points", m, "--female-points", f, *CLEARANCE)
    assert "NaN or infinite" in line and "LWPOLYLINE" in line


def test_male_dxf_scaled_1e9(capsys, tmp_path, outlines):
    """A male DXF scaled x1e9: IndexError in `in_contract_frame`. Its largest radius (54 mm x 1e9,
    the sample's [pair] male_tip_radius) is named against the centre distance."""
    m = polyline_dxf(tmp_path / "male.dxf", outlines["male"] * 1e9)
    f = polyline_dxf(tmp_path / "female.dxf", outlines["female"])
    line = refused(capsys, "--male-points", "clearance", "--male-points", m, "--female-points", f, *CLEARANCE)
    assert "5.4e+10 mm" in line and "--center-distance" in line


def test_clearance_lead_1e9_refused_with_the_longest_lead(capsys, tmp_path, outlines):
    """`clearance --lead 1e9` returned zeros and nulls on exit 0: no segment of the contact line
    lies within the 190 mm rotors. The lead named must be the bound: just below it, a band."""
    m = polyline_dxf(tmp_path / "male.dxf", outlines["male"])
    f = polyline_dxf(tmp_path / "female.dxf", outlines["female"])
    argv = ["clearance", "--male-points", m, "--female-points", f, *CLEARANCE, "--json"]
    line = refused(capsys, "--lead must be at most", *argv, "--lead", "1e9")
    bound = float(re.search(r"at most ([0-9.e+]+) mm", line).group(1))
    status, out, _ = run(capsys, *argv, "--lead", f"{bound * 0.999:.6g}")
    res = json.loads(out)
    assert status == 0 and res["mean_clearance"] is not None and res["band_area"] > 0


@pytest.mark.parametrize("gap", [0.002, 0.05])
def test_open_dxf_outline_refused_naming_the_gap(capsys, tmp_path, outlines, gap):
    """A DXF outline with an open gap was accepted by `rotor` and `interfere` (exit 0): a gap
    wider than the joining accuracy (1 um) is refused, naming its size and place."""
    pts = outlines["male"]
    m = polyline_dxf(tmp_path / "male.dxf", np.vstack([pts, pts[:1] + [gap, 0.0]]), closed=False)
    for argv in (
        ["interfere", SAMPLES / "srm_symmetric_4_6.toml", "--steps", "2"],
        ["rotor", SAMPLES / "srm_symmetric_4_6.toml"],
    ):
        line = refused(capsys, "--male-points", *argv, "--male-points", m)
        assert f"gap of {gap:g} mm" in line and f"({40 + gap:.6f}, 0.000000) mm" in line


def test_dxf_outline_closed_within_the_accuracy_says_so(capsys, tmp_path, outlines):
    """A gap of 0.8 um (within the 1 um joining accuracy) is closed, and the run says so."""
    pts = outlines["male"]
    m = polyline_dxf(tmp_path / "male.dxf", np.vstack([pts, pts[:1] + [0.0008, 0.0]]), closed=False)
    status, _, err = run(capsys, "interfere", SAMPLES / "srm_symmetric_4_6.toml", "--steps", "2", "--male-points", m)
    assert status in (0, 1)
    assert "rotorcad: note: --male-points" in err and "gap of 0.0008 mm" in err and "(40.000800, -0.000000) mm" in err


# ----- designs --------------------------------------------------------------------------------
@pytest.mark.parametrize("command", [["cut"], ["gear"], ["pump", "--face-width", "10", "--speed", "1500"], ["report"]])
def test_shift_10_to_the_30_in_a_design(capsys, tmp_path, command):
    """An integer too large for a float in a design (`shift = 10**30`): TypeError in `gear.py`
    `__post_init__` from cut, gear, pump, report. 10**30 is 1e30 (refused by the range of the shift);
    10**400 is beyond any float (refused as such)."""
    text = (SAMPLES / "gear_pair.toml").read_text()
    extra = ["--out", tmp_path / "r.html"] if command[0] == "report" else []
    for power, needle in ((30, "[gear] shift must be between -2 and 3"), (400, "[gear] shift must be a number within the range")):
        path = tmp_path / f"shift{power}.toml"
        path.write_text(re.sub(r"^shift = 0.3", f"shift = {10**power}", text, flags=re.M))
        refused(capsys, needle, command[0], path, *command[1:], *extra)
    assert not (tmp_path / "r.html").exists()

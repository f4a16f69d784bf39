"""Regression tests for the examples of issue 24 ("Every input gets an answer, part 2"): each test
names the example it covers and uses its exact input. Fast: refusals come before any heavy work."""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import textwrap
import time
from pathlib import Path

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

"""Speed and memory of the README main job (issue "files CAD and CAM trust"): both rotors of
``samples/rack_involute_5_6.toml``, the housing and bores, STL (5 um) + exact STEP (1 um) + DXF.
Targets: under 3 s wall and under 1 GB on this machine; the B-spline STEP of one rotor under 0.5 s.

Run by hand from the project folder: ``python benchmarks/bench_export.py``. Prints the machine's
load, best and median of 7 runs of the command as a user types it (a fresh process each: start-up,
imports and the forked worker included), the peak memory of the process tree (benchmarks/peak_tree.py)
and the exact STEP of the male alone, in process (best and median of 7).
"""

from __future__ import annotations

import os
import shutil
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

from peak_tree import run_with_peak

ROOT = Path(__file__).resolve().parents[1]
SAMPLE = ROOT / "samples" / "rack_involute_5_6.toml"


def _rotorcad() -> list[str]:
    exe = Path(sys.executable).with_name("rotorcad")
    return [str(exe)] if exe.exists() else [sys.executable, "-m", "rotorcad.cli.main"]


def main() -> None:
    print(f"load average {os.getloadavg()[0]:.2f}, {os.cpu_count()} cores")
    walls = []
    with tempfile.TemporaryDirectory() as tmp:
        for _ in range(7):
            out = Path(tmp) / "out"
            shutil.rmtree(out, ignore_errors=True)
            start = time.perf_counter()
            subprocess.run([*_rotorcad(), "export", str(SAMPLE), "--out", str(out)], check=True, stdout=subprocess.DEVNULL)
            walls.append(time.perf_counter() - start)
        shutil.rmtree(Path(tmp) / "out")
        wall, peak, _ = run_with_peak([*_rotorcad(), "export", str(SAMPLE), "--out", str(Path(tmp) / "out")])
    print(f"README main job: best {min(walls):.2f} s, median {statistics.median(walls):.2f} s (target < 3 s)")
    print(f"  peak memory of the process tree {peak:.0f} MB (target < 1 GB; that run {wall:.2f} s with sampling)")
    step_of_one_rotor()


def step_of_one_rotor() -> None:
    from exports.step_exact import section_segments, write_exact_step
    from rotorcad.cli.export_cmd import _rotor_options
    from rotorcad.cli.rotor import _build

    rotors, _, _ = _build(SAMPLE, _rotor_options(SAMPLE))
    pair = rotors.pair
    write_exact_step(Path(os.devnull), section_segments(rotors.male_outline(0.01)), pair.lead, pair.length)  # OCP loaded
    times = []
    with tempfile.TemporaryDirectory() as tmp:
        for _ in range(7):
            start = time.perf_counter()
            segments = section_segments(rotors.male_outline(0.01))
            exact = rotors.male_outline(1e-5).points
            done = write_exact_step(Path(tmp) / "male.step", segments, pair.lead, pair.length, 1e-3, "male", exact=exact)
            times.append(time.perf_counter() - start)
    print(
        f"exact STEP of the male (1 um, checked on every face, {done['deviation'] * 1e3:.3f} um met): "
        f"best {min(times):.2f} s, median {statistics.median(times):.2f} s (target < 0.5 s)"
    )


if __name__ == "__main__":
    main()

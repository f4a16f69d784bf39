"""Speed and memory of the README main job (issue "files CAD and CAM trust"): both rotors of
``samples/rack_involute_5_6.toml``, the housing and bores, STL (5 um) + exact STEP (1 um) + DXF.
Targets: under 3 s wall and under 1 GB on this machine; the B-spline STEP of one rotor under 0.5 s.

Run by hand from the project folder: ``python benchmarks/bench_export.py``. Prints the machine's
load, best and median of 7 runs of the command as a user types it (a fresh process each: start-up,
imports and the forked worker included), the peak memory of the process tree (benchmarks/peak_tree.py)
and the exact STEP of the male alone, in process (best and median of 7).

``python benchmarks/bench_export.py --parts [ROUNDS]`` prints instead where the job's CPU time goes
(issue 26), in an interleaved loop as ``benchmarks/run_all.py`` measures it (medians of ROUNDS, 5 by
default, and their ratio to the baseline ``python -c "import numpy, scipy"``): the command's own
process and its writer process apart, and the imports that bound it from below, each in a fresh
interpreter (OpenCASCADE, ezdxf, the command's own).
"""

from __future__ import annotations

import os
import resource
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


SPLIT = """
import atexit, resource, runpy, sys
def report():
    s, c = resource.getrusage(resource.RUSAGE_SELF), resource.getrusage(resource.RUSAGE_CHILDREN)
    print(s.ru_utime + s.ru_stime, c.ru_utime + c.ru_stime, file=open({record!r}, "w"))
atexit.register(report)
sys.argv = ["rotorcad", *{args!r}]
runpy.run_module("rotorcad.cli.main", run_name="__main__")
"""


def _cpu(cmd: list[str], env: dict[str, str]) -> float:
    """CPU time (s) of a command and the processes it waited for."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    subprocess.run(cmd, env=env, cwd=ROOT, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, check=True)
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    return (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)


def parts(rounds: int) -> None:
    """Print the README job's CPU time by part (module docstring), medians of ``rounds`` interleaved rounds."""
    env = {k: v for k, v in os.environ.items() if k != "PYTHONDONTWRITEBYTECODE"}
    py = sys.executable
    fixed = {
        "baseline: python -c 'import numpy, scipy'": [py, "-c", "import numpy, scipy"],
        "python -c pass (the interpreter's start)": [py, "-c", "pass"],
        "import OCP.STEPControl (OpenCASCADE, one extension module)": [py, "-c", "import OCP.STEPControl"],
        "import numpy, ezdxf": [py, "-c", "import numpy, ezdxf"],
        "the command's imports (rotorcad.cli.main, export_cmd)": [py, "-c", "import rotorcad.cli.main, rotorcad.cli.export_cmd"],
    }
    times: dict[str, list[float]] = {name: [] for name in (*fixed, "README job", "  its own process", "  its writer process")}
    print(f"load average {os.getloadavg()[0]:.2f}, {os.cpu_count()} cores")
    with tempfile.TemporaryDirectory() as tmp:
        record = Path(tmp) / "split.txt"
        job = [py, "-c", SPLIT.format(record=str(record), args=["export", str(SAMPLE), "--out", str(Path(tmp) / "o"), "--quiet"])]
        for _ in range(rounds):
            for name, cmd in fixed.items():
                times[name].append(_cpu(cmd, env))
            times["README job"].append(_cpu(job, env))
            own, writer = map(float, record.read_text().split())
            times["  its own process"].append(own)
            times["  its writer process"].append(writer)
    base = statistics.median(times["baseline: python -c 'import numpy, scipy'"])
    for name, values in times.items():
        median = statistics.median(values)
        print(f"{name:62s} {median * 1e3:6.0f} ms  {median / base:5.2f}x")
    print(f"load average {os.getloadavg()[0]:.2f}")


if __name__ == "__main__":
    if "--parts" in sys.argv:
        rest = sys.argv[sys.argv.index("--parts") + 1 :]
        parts(int(rest[0]) if rest else 5)
    else:
        main()

"""The speed targets of issue 26, measured against a baseline in the same interleaved loop.

Every round runs the baseline ``python -c "import numpy, scipy"`` and then each target once, so
that a change of the machine's load between rounds touches both alike. Times are CPU time (user +
system, the command's worker processes included: ``resource.getrusage(RUSAGE_CHILDREN)`` for the
commands, ``time.process_time`` for the library calls), so that other processes on a shared machine
disturb them less than wall time. Printed per target: the median figure, the median baseline of
the same rounds, their ratio and the goal (a ratio for the commands, milliseconds for the calls).

The test suite's target is wall time on an idle machine (3 min on 2 cores, the suite spread over a
pytest-xdist worker per CPU), so ``--suite`` runs ``python -m pytest -q`` once, in the last round
(its CPU time too, and the load before and after it, since wall time is what a loaded machine
stretches).

Run by hand: ``python benchmarks/run_all.py [--rounds N] [--scripts] [--suite] [--only TEXT]``;
``--scripts`` also runs every other ``benchmarks/bench_*.py`` and says whether each ran to its end;
``--only`` measures the targets whose name contains TEXT (e.g. ``--only "rotor outlines"``). The byte
code of the package is compiled first (``compileall``) so that a first run does not pay for it.
"""

from __future__ import annotations

import argparse
import compileall
import os
import resource
import statistics
import subprocess
import sys
import tempfile
import time
import tomllib
from collections.abc import Callable
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
SAMPLE = ROOT / "samples" / "rack_involute_5_6.toml"
PY = sys.executable
ENV = {k: v for k, v in os.environ.items() if k != "PYTHONDONTWRITEBYTECODE"}  # as a user's shell: byte code cached


def cpu_of(cmd: list[str], cwd: Path) -> float:
    """CPU time (s) of a command and the processes it waited for."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    subprocess.run(cmd, cwd=cwd, env=ENV, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, check=True)
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    return (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)


def cpu_in_process(fn: Callable[[], object], repeat: int) -> float:
    """Median CPU time (s) of ``repeat`` calls of ``fn``."""
    times = []
    for _ in range(repeat):
        t = time.process_time()
        fn()
        times.append(time.process_time() - t)
    return statistics.median(times)


def library_targets() -> dict[str, tuple[Callable[[], object], int, float]]:
    """Name -> (call, repeats, goal in ms) of the in-process targets; every call builds afresh (nothing cached)."""
    import numpy as np

    from rotorcad.design import rotor_design
    from rotorcad.gear import InvoluteGear
    from rotorcad.inverse_rack import rotor_rack as racks_of
    from rotorcad.rotor_build import build_pair, pair_spec

    with SAMPLE.open("rb") as f:
        spec = pair_spec(rotor_design(tomllib.load(f), SAMPLE.parent))
    rotors = build_pair(spec)

    def outlines() -> None:
        fresh = type(rotors)(rotors.pair, rotors.rack, rotors.family, tolerance=1e-4)
        fresh.male_outline(1e-4)
        fresh.female_outline(1e-4)

    def racks() -> None:
        fresh = type(rotors)(rotors.pair, rotors.rack, rotors.family, tolerance=rotors.tolerance)
        racks_of(fresh, "male")
        racks_of(fresh, "female")

    deg = np.pi / 180

    def gear(z: int) -> Callable[[], object]:
        return lambda: InvoluteGear(z, 2.0, 20 * deg, tolerance=1e-4).outline()

    targets = {
        "both rotor outlines, 5/6 README pair, 0.1 um": (outlines, 5, 2.0),
        "racks from both rotors of the README pair": (racks, 3, 20.0),
    }
    # where the undercut barely exists (x = 0, tool tip radius 0.38 m, 0.1 um)
    targets |= {f"gear outline z = {z} near the undercut limit": (gear(z), 5, 1.0) for z in (17, 18, 19, 20, 21)}
    return targets


def command_targets(out: Path) -> dict[str, tuple[list[str], float]]:
    """Name -> (command, goal as a ratio to the baseline)."""
    cli = [PY, "-m", "rotorcad.cli.main"]
    return {
        "README main job: export samples/rack_involute_5_6.toml (stl, step, dxf)": (
            [*cli, "export", str(SAMPLE), "--out", str(out), "--quiet"],
            10.0,
        ),
        "gear --teeth 20 --module 2 --json": ([*cli, "gear", "--teeth", "20", "--module", "2", "--json"], 2.0),
        "rotor samples/rack_involute_5_6.toml --json": ([*cli, "rotor", str(SAMPLE), "--json"], 3.0),
    }


SUITE = "the test suite: python -m pytest -q (wall time)"
SUITE_GOAL = 180.0  # s of wall time


def suite_run() -> tuple[float, float, str]:
    """Wall time (s) and CPU time (s, the workers included) of the whole test suite, and its closing line."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    start = time.perf_counter()
    cmd = [PY, "-m", "pytest", "-q", "-p", "no:cacheprovider"]
    proc = subprocess.run(cmd, cwd=ROOT, env=ENV, capture_output=True, text=True)
    wall = time.perf_counter() - start
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    lines = proc.stdout.strip().splitlines()
    return wall, cpu, (lines[-1] if lines else f"no output (exit {proc.returncode})")


def load() -> str:
    """The machine's load averages (1, 5, 15 min) and its CPU count."""
    return f"{', '.join(f'{x:.2f}' for x in os.getloadavg())} on {os.cpu_count()} cores"


def run_scripts() -> None:
    """Run every other benchmark script and say whether it ran to its end."""
    for script in sorted((ROOT / "benchmarks").glob("bench_*.py")):
        t = time.perf_counter()
        proc = subprocess.run([PY, str(script)], cwd=ROOT, env=ENV, capture_output=True, text=True)
        state = "ran" if proc.returncode == 0 else f"FAILED (exit {proc.returncode}): {proc.stderr.strip().splitlines()[-1:]}"
        print(f"{script.name}: {state} in {time.perf_counter() - t:.0f} s")
        for line in proc.stdout.strip().splitlines():
            print(f"    {line}")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--rounds", type=int, default=5, help="interleaved rounds (medians are printed)")
    parser.add_argument("--scripts", action="store_true", help="also run every benchmarks/bench_*.py")
    parser.add_argument("--suite", action="store_true", help="also run the whole test suite once, in the last round")
    parser.add_argument("--only", default="", help="measure only the targets whose name contains this text")
    args = parser.parse_args()
    for package in ("rotorcad", "exports", "hob"):
        compileall.compile_dir(str(ROOT / package), quiet=1)
    print(f"machine load (1, 5, 15 min): {load()}")
    baseline_cmd = [PY, "-c", "import numpy, scipy"]
    with tempfile.TemporaryDirectory() as tmp:
        commands = {k: v for k, v in command_targets(Path(tmp) / "out").items() if args.only in k}
        library = {k: v for k, v in library_targets().items() if args.only in k}
        base: list[float] = []
        figures: dict[str, list[float]] = {name: [] for name in (*commands, *library)}
        suite: tuple[float, float, str, str, str] | None = None
        for i in range(args.rounds):
            base.append(cpu_of(baseline_cmd, ROOT))
            for name, (cmd, _) in commands.items():
                figures[name].append(cpu_of(cmd, ROOT))
            for name, (fn, repeat, _) in library.items():
                figures[name].append(cpu_in_process(fn, repeat))
            if args.suite and i == args.rounds - 1:
                at_start = load()
                suite = (*suite_run(), at_start, load())
    b = statistics.median(base)
    print(f"baseline python -c 'import numpy, scipy': {b * 1e3:.0f} ms CPU (median of {args.rounds} rounds)")
    print(f"{'target':<75} {'measured':>10} {'baseline':>9} {'ratio':>7} {'goal':>9}  met")
    for name, values in figures.items():
        m = statistics.median(values)
        if name in commands:
            goal = commands[name][1]
            print(f"{name:<75} {m * 1e3:8.0f}ms {b * 1e3:7.0f}ms {m / b:6.2f}x {goal:8.0f}x  {'yes' if m / b <= goal else 'NO'}")
        else:
            goal = library[name][2]
            met = "yes" if m * 1e3 <= goal else "NO"
            print(f"{name:<75} {m * 1e3:8.2f}ms {b * 1e3:7.0f}ms {m / b:6.3f}x {goal:7.1f}ms  {met}")
    if suite is not None:
        wall, cpu, closing, at_start, at_end = suite
        met = "yes" if wall <= SUITE_GOAL else "NO"
        print(f"{SUITE:<75} {wall:9.0f}s {b * 1e3:7.0f}ms {cpu / b:6.0f}x {SUITE_GOAL:8.0f}s  {met}")
        print(f"    {closing}; {cpu:.0f} s CPU (the ratio is CPU to the baseline); load {at_start} before, {at_end} after")
    print(f"machine load (1, 5, 15 min): {load()}")
    if args.scripts:
        run_scripts()


if __name__ == "__main__":
    main()

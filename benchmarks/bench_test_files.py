"""CPU time of test files, each run alone in one process (``pytest -q -n 0``), and the load around it.

The test suite's target (issue 26) is wall time on an idle 2-core machine; on a shared, loaded one the
wall time says little, so a change to the suite or to a library function it calls is measured by the
CPU time (user + system, of the pytest process and what it starts: ``resource.getrusage(RUSAGE_CHILDREN)``)
of the test files it touches, each alone, before and after. The load average is printed before and
after each file, since a loaded machine still stretches CPU time somewhat (caches, frequency).

Run by hand from the repository's root: ``python benchmarks/bench_test_files.py tests/test_foo.py
[tests/test_bar.py ...] [--rounds N] [-k EXPR]``; prints one line per file and round: CPU seconds,
wall seconds, the tests' outcome line and the load.
"""

from __future__ import annotations

import argparse
import os
import resource
import subprocess
import sys
import time


def _cpu_of_children() -> float:
    usage = resource.getrusage(resource.RUSAGE_CHILDREN)
    return usage.ru_utime + usage.ru_stime


def run_file(path: str, keyword: str | None = None) -> tuple[float, float, str]:
    """Run one test file alone; return its CPU seconds, wall seconds and pytest's last line."""
    command = [sys.executable, "-m", "pytest", "-q", "-n", "0", "-p", "no:cacheprovider", path]
    if keyword:
        command += ["-k", keyword]
    cpu, wall = _cpu_of_children(), time.perf_counter()
    done = subprocess.run(command, capture_output=True, text=True)
    cpu, wall = _cpu_of_children() - cpu, time.perf_counter() - wall
    lines = [line for line in done.stdout.splitlines() if line.strip()]
    return cpu, wall, lines[-1] if lines else f"exit {done.returncode}"


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("files", nargs="+")
    parser.add_argument("--rounds", type=int, default=1)
    parser.add_argument("-k", dest="keyword", default=None)
    args = parser.parse_args()
    for _ in range(args.rounds):
        for path in args.files:
            before = os.getloadavg()[0]
            cpu, wall, outcome = run_file(path, args.keyword)
            print(
                f"{cpu:8.2f} s CPU {wall:8.1f} s wall  load {before:.1f}->{os.getloadavg()[0]:.1f}  {path}: {outcome}", flush=True
            )


if __name__ == "__main__":
    main()

"""Run a command and report its wall time and the peak memory of its whole process tree.

GNU time's %M is the largest single process; an export that hands STEP and DXF to a forked
worker process uses two, and what the machine must hold is their sum. The sum is taken of the
proportional set sizes (Pss in /proc/PID/smaps_rollup: a page shared by the two after the fork is
counted half in each), sampled every 10 ms; the sampling itself takes some of a core.

Usage: python benchmarks/peak_tree.py rotorcad export samples/rack_involute_5_6.toml --out out
"""

from __future__ import annotations

import os
import subprocess
import sys
import time


def _tree_rss_kb(root: int) -> int:
    """Summed proportional set size of ``root`` and its descendants (kB), from /proc.

    The tree from every process's ``stat`` (its parent), then ``smaps_rollup`` of the tree's
    processes only: reading it walks a process's page tables, which for every process of a busy
    machine took some 15 ms of CPU a sample.
    """
    children: dict[int, list[int]] = {}
    for entry in os.listdir("/proc"):
        if not entry.isdigit():
            continue
        try:
            with open(f"/proc/{entry}/stat") as fh:
                fields = fh.read().rsplit(")", 1)[1].split()
        except OSError:
            continue
        children.setdefault(int(fields[1]), []).append(int(entry))
    total, todo = 0, [root]
    while todo:
        pid = todo.pop()
        try:
            with open(f"/proc/{pid}/smaps_rollup") as fh:
                total += next(int(line.split()[1]) for line in fh if line.startswith("Pss:"))
        except (OSError, StopIteration):
            pass
        todo.extend(children.get(pid, []))
    return total


def run_with_peak(command: list[str], interval: float = 0.01) -> tuple[float, float, int]:
    """Run ``command``; return (wall time s, peak PSS of its process tree MB, exit status).

    The tree is sampled every ``interval`` seconds: each sample reads every process of /proc, so a
    long run on a loaded machine samples less often (the sampling takes a core's share from the run).
    """
    start = time.perf_counter()
    proc = subprocess.Popen(command, stdout=subprocess.DEVNULL)
    peak = 0
    while proc.poll() is None:
        peak = max(peak, _tree_rss_kb(proc.pid))
        time.sleep(interval)
    return time.perf_counter() - start, peak / 1024, proc.returncode


def main() -> None:
    wall, peak, status = run_with_peak(sys.argv[1:])
    print(f"{wall:.2f} s wall, peak PSS of the process tree {peak:.0f} MB, exit {status}")


if __name__ == "__main__":
    main()

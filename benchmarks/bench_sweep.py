"""Speed and scale of ``rotorcad sweep`` (issue 27): variants per CPU-second per core for the pair
and Rinder's analysis, the memory of the plan from 1 k to 1 M variants, and a whole sweep on every
core with the peak memory of its process tree.

CPU time (``time.process_time``), not wall time: the machine is shared. Two workloads in this
process (``--workers 0``): a Latin hypercube over the profile and the lead (every variant a new
transverse section: nothing to reuse), and a designer's grid over the profile, lead and length
(few sections, many leads and lengths: a worker reuses the section of a pair it built). Target:
>= 100 variants per CPU-second per core; the plan's memory flat in the number of variants. A row
holds the figures of :func:`rotorcad.sweep.figures.sweep_figures` (``rotorcad rotor --json``'s
numbers; the flute areas within a relative 1e-6, tests/test_sweep_fast_path.py).
Run by hand: ``python benchmarks/bench_sweep.py [variants of the whole sweep]``; ``--rates`` prints
the two rates alone; ``--lhs N`` runs ``rotorcad sweep`` of N new profiles (the Latin hypercube
above, every section new) on every core and prints its wall time and the CPU time of its process
tree (issue 27: 10 000 in under 60 s on 2 cores). Note the load average: on a shared machine the
wall time and, less so, the CPU time grow with it.
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

from peak_tree import run_with_peak

from rotorcad.cli.common import load_toml
from rotorcad.sweep.plan import sweep_plan
from rotorcad.sweep.run import run_sweep
from rotorcad.sweep.tasks import clear_cache

ROOT = Path(__file__).resolve().parents[1]
BASE = ROOT / "samples" / "rack_involute_5_6.toml"
LHS = {
    "sweep": {"method": "latin-hypercube", "samples": 200, "seed": 1},
    "vary": {
        "profile.lobe_width": {"min": 0.62, "max": 0.75},
        "profile.driving_angle_deg": {"min": 25.0, "max": 35.0},
        "pair.lead": {"min": 220.0, "max": 380.0},
    },
}
GRID = {
    "vary": {
        "profile.lobe_width": [0.62, 0.66, 0.7, 0.74],
        "pair.lead": {"from": 200.0, "to": 390.0, "step": 10.0},
        "pair.length": [150.0, 170.0, 190.0],
    }
}


def rate(data: dict) -> tuple[float, int, int]:
    """Variants per CPU-second of a sweep run in this process; the count and how many were built."""
    plan = sweep_plan(data, load_toml(BASE))
    clear_cache()
    start = time.process_time()
    outcome = run_sweep(plan, None, workers=0)
    cpu = time.process_time() - start
    return plan.count / cpu, plan.count, int(outcome.table["ok"].sum())


PLAN_CHILD = """
import json, resource, sys, time
from rotorcad.cli.common import load_toml
from rotorcad.sweep.plan import sweep_plan
data, base = json.loads(sys.argv[1]), load_toml(sys.argv[2])
before = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
start = time.perf_counter()
plan = sweep_plan(data, base)
n = sum(1 for _ in plan.iter_variants())
assert n == plan.count
after = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
print(after - before, after, time.perf_counter() - start)
"""


def plan_memory(count: int, method: str) -> tuple[float, float, float]:
    """Plan ``count`` variants and read them all in a fresh process.

    Returns the growth of its peak resident memory over the peak after its imports (MB), that peak
    (MB), and the seconds it takes.
    """
    if method == "grid":
        side = round(count ** (1 / 3))
        data = {
            "vary": {
                "pair.lead": [float(v) for v in range(200, 200 + side)],
                "pair.length": [float(v) for v in range(100, 100 + side)],
                "profile.lobe_width": [0.6 + i * 1e-4 for i in range(count // side**2)],
            }
        }
    else:
        data = {"sweep": {"method": method, "samples": count, "seed": 1}, "vary": LHS["vary"]}
    out = subprocess.run(
        [sys.executable, "-c", PLAN_CHILD, json.dumps(data), str(BASE)], capture_output=True, text=True, check=True
    ).stdout.split()
    return float(out[0]) / 1024, float(out[1]) / 1024, float(out[2])


def lhs_sweep(count: int) -> None:
    """Run ``rotorcad sweep`` of ``count`` new profiles on every core; print wall and CPU time."""
    vary = "".join(f'"{key}" = {{min = {b["min"]}, max = {b["max"]}}}\n' for key, b in LHS["vary"].items())
    load_before = os.getloadavg()[0]
    with tempfile.TemporaryDirectory() as tmp:
        sweep_file = Path(tmp) / "lhs.toml"
        sweep_file.write_text(
            f'[sweep]\nbase = "{BASE.as_posix()}"\nmethod = "latin-hypercube"\nsamples = {count}\nseed = 1\n[vary]\n{vary}'
        )
        cpu0 = os.times()
        command = [sys.executable, "-m", "rotorcad.cli.main", "sweep", str(sweep_file), "--quiet"]
        # memory sampled every 0.25 s: at every 10 ms the sampler took 30 CPU-s of the two cores a
        # 10 000-variant sweep runs on (a sweep's memory does not jump within a quarter second)
        wall, peak, status = run_with_peak([*command, "--out", str(Path(tmp) / "l.parquet")], interval=0.25)
        cpu1 = os.times()
    cpu = (cpu1.children_user + cpu1.children_system) - (cpu0.children_user + cpu0.children_system)
    sampler = (cpu1.user + cpu1.system) - (cpu0.user + cpu0.system)
    print(
        f"{count} new profiles (Latin hypercube) on {os.cpu_count()} workers: {wall:.1f} s wall (target < 60 s for 10 000 "
        f"on 2 cores), {cpu:.1f} CPU-s of the process tree ({1e3 * cpu / count:.1f} ms a variant, cluster start "
        f"included; the memory sampler {sampler:.1f} CPU-s beside it), peak memory {peak:.0f} MB, exit {status}; "
        f"load average {load_before:.2f} before, {os.getloadavg()[0]:.2f} after"
    )


def rates() -> None:
    """Print the variants per CPU-second of the two workloads in this process."""
    rate(GRID | {"vary": {"profile.lobe_width": [0.62], "pair.lead": [300.0]}})  # imports
    for name, data in (("Latin hypercube, every section new", LHS), ("grid: 4 sections x 20 leads x 3 lengths", GRID)):
        per_cpu_s, count, ok = rate(data)
        print(
            f"{name}: {count} variants ({ok} built), {per_cpu_s:.1f} variants per CPU-second "
            f"({1e3 / per_cpu_s:.1f} ms each; target >= 100)"
        )


def main() -> None:
    print(f"load average {os.getloadavg()[0]:.2f}, {os.cpu_count()} cores")
    if "--lhs" in sys.argv:
        lhs_sweep(int(sys.argv[sys.argv.index("--lhs") + 1]))
        return
    rates()
    if "--rates" in sys.argv:
        return
    big = int(sys.argv[1]) if len(sys.argv) > 1 else 2_000
    for method in ("latin-hypercube", "random", "grid"):
        for count in (1_000, 10_000, 100_000, 1_000_000):
            growth, peak, seconds = plan_memory(count, method)
            print(f"plan only, {method}, {count} variants: peak memory +{growth:.1f} MB (to {peak:.0f} MB), {seconds:.1f} s")
    with tempfile.TemporaryDirectory() as tmp:
        sweep_file = Path(tmp) / "big.toml"
        leads = max(1, big // 12)
        sweep_file.write_text(
            f'[sweep]\nbase = "{BASE.as_posix()}"\n[vary]\n"profile.lobe_width" = [0.62, 0.66, 0.7, 0.74]\n'
            '"pair.length" = [150.0, 170.0, 190.0]\n'
            f'"pair.lead" = {{from = 200.0, to = {200.0 + 0.01 * (leads - 1):.2f}, step = 0.01}}\n'
        )
        cpu0 = os.times()
        wall, peak, status = run_with_peak(
            [sys.executable, "-m", "rotorcad.cli.main", "sweep", str(sweep_file), "--out", str(Path(tmp) / "b.parquet")]
            + ["--quiet"]
        )
        cpu1 = os.times()
        cpu = (cpu1.children_user + cpu1.children_system) - (cpu0.children_user + cpu0.children_system)
    n = 12 * leads
    print(
        f"{n} variants (grid) on {os.cpu_count()} workers: {wall:.1f} s wall, {cpu:.1f} CPU-s of the process tree "
        f"({n / cpu:.1f} variants per CPU-second, cluster start included), peak memory {peak:.0f} MB, exit {status}"
    )


if __name__ == "__main__":
    main()

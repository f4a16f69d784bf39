"""Speed and scale of ``rotorcad sweep`` (issue "design sweeps"): variants per second per core
for the pair and Rinder's analysis in a plain loop; the same work through Dask with one worker
(the scheduler's overhead); a 10 000-variant sweep on every core with the peak memory of the
process tree (benchmarks/peak_tree.py). Targets: >= 40 variants/s per core, overhead < 10 %,
10 000 variants < 3 min, < 1 GB. Run by hand: ``python benchmarks/bench_sweep.py [variants]``.
"""

from __future__ import annotations

import os
import sys
import tempfile
import time
from pathlib import Path

from peak_tree import run_with_peak

from rotorcad.cli.common import load_toml
from rotorcad.cli.sweep_run import run_sweep
from rotorcad.cli.sweep_tasks import evaluate
from rotorcad.sweep_plan import sweep_plan

ROOT = Path(__file__).resolve().parents[1]
BASE = ROOT / "samples" / "rack_involute_5_6.toml"
VARY = """
[vary]
"profile.lobe_width" = {min = 0.62, max = 0.75}
"profile.driving_angle_deg" = {min = 25.0, max = 35.0}
"pair.lead" = {min = 220.0, max = 380.0}
"""


def main() -> None:
    big = int(sys.argv[1]) if len(sys.argv) > 1 else 10_000
    print(f"load average {os.getloadavg()[0]:.2f}, {os.cpu_count()} cores")
    data = {
        "sweep": {"method": "latin-hypercube", "samples": 300, "seed": 1},
        "vary": {
            "profile.lobe_width": {"min": 0.62, "max": 0.75},
            "profile.driving_angle_deg": {"min": 25.0, "max": 35.0},
            "pair.lead": {"min": 220.0, "max": 380.0},
        },
    }
    plan = sweep_plan(data, load_toml(BASE))
    variants = plan.variants()
    evaluate(plan.base, None, None, (), variants[0])  # imports
    start = time.perf_counter()
    rows = [evaluate(plan.base, None, None, (), v) for v in variants]
    loop = time.perf_counter() - start
    print(f"plain loop, one core: {len(rows) / loop:.1f} variants/s ({loop / len(rows) * 1e3:.1f} ms each, target >= 40/s)")
    # the scheduler's overhead: Dask with one worker on n and on 2n variants; the difference of the
    # two runs is the marginal cost of n variants (cluster start, imports in the worker and stop cancel)
    walls = []
    for count in (len(variants), 2 * len(variants)):
        data["sweep"]["samples"] = count
        start = time.perf_counter()
        run_sweep(sweep_plan(data, load_toml(BASE)), None, workers=1)
        walls.append(time.perf_counter() - start)
    marginal = walls[1] - walls[0]
    overhead = (marginal - loop) / loop * 100
    print(
        f"Dask, one worker: {walls[0]:.2f} s for {len(variants)}, {walls[1]:.2f} s for {2 * len(variants)} variants; "
        f"{marginal:.2f} s for {len(variants)} more against {loop:.2f} s in the loop: overhead {overhead:.1f} % "
        f"(target < 10 %); fixed cost (cluster start, worker imports, stop) {walls[0] - marginal:.2f} s"
    )
    with tempfile.TemporaryDirectory() as tmp:
        sweep_file = Path(tmp) / "big.toml"
        sweep_file.write_text(
            f'[sweep]\nbase = "{BASE.as_posix()}"\nmethod = "latin-hypercube"\nsamples = {big}\nseed = 2\n' + VARY
        )
        wall, peak, status = run_with_peak(
            [
                sys.executable,
                "-m",
                "rotorcad.cli.main",
                "sweep",
                str(sweep_file),
                "--out",
                str(Path(tmp) / "big.parquet"),
                "--quiet",
            ]
        )
    print(
        f"{big} variants on {os.cpu_count()} workers: {wall:.1f} s ({big / wall:.1f} variants/s; target < 180 s), "
        f"peak memory of the process tree {peak:.0f} MB (target < 1 GB), exit {status}"
    )


if __name__ == "__main__":
    main()

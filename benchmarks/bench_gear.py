"""Speed of the foundation (issues 2 and 14): gear outline and envelope-engine throughput.

Run by hand on an idle machine: ``python benchmarks/bench_gear.py``. Single-threaded BLAS is
forced so that the figures are per core. The machine's load (1, 5 and 15 minute averages) is
printed before and after the runs; best and median of the runs, after one warm-up run.
"""

from __future__ import annotations

import os

os.environ.setdefault("OMP_NUM_THREADS", "1")
os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import time

import numpy as np

from rotorcad.curves import Arc, Line
from rotorcad.envelope import conjugate
from rotorcad.gear import InvoluteGear
from rotorcad.kinematics import rotor_mesh


def load() -> str:
    """The machine's load averages (1, 5, 15 min) and core count, as printed."""
    return f"machine load (1, 5, 15 min): {', '.join(f'{x:.2f}' for x in os.getloadavg())} on {os.cpu_count()} cores"


def best_of(fn, repeat: int = 15) -> tuple[float, float]:
    """Best and median wall time of ``repeat`` runs of ``fn`` (after one warm-up run), s."""
    fn()
    times = []
    for _ in range(repeat):
        t = time.perf_counter()
        fn()
        times.append(time.perf_counter() - t)
    return min(times), float(np.median(times))


def main() -> None:
    deg = np.pi / 180

    print(load())

    # 1. full gear outline, z = 30, one tooth to 0.1 um chord error (target < 1 ms): a new gear every
    # run (nothing cached); half a tooth evaluated in closed form and sampled in one step from its
    # curvature, mirrored, and the tooth patterned
    def outline():
        return InvoluteGear(30, 2.0, 20 * deg, tolerance=1e-4).outline().points

    best, med = best_of(outline, repeat=200)
    n = len(outline())
    print(f"gear outline z=30, 0.1 um chord: best {best * 1e3:.2f} ms, median {med * 1e3:.2f} ms, {n} points (target < 1 ms)")

    # the same with the per-tooth segment objects (exact curves, for STEP and DXF) made too
    def outline_segments():
        return InvoluteGear(30, 2.0, 20 * deg, tolerance=1e-4).outline().segments

    best, med = best_of(outline_segments, repeat=50)
    print(f"gear outline z=30 with its {len(outline_segments())} segments: best {best * 1e3:.2f} ms, median {med * 1e3:.2f} ms")

    # 2. envelope engine throughput, rack -> rotor and rotor -> rotor (target >= 2 M points/s)
    mesh = rotor_mesh(5, 6, 116.0)
    n_pts = 2_000_000
    flank = Line((50.0, 5.0), (54.0, -6.0))
    p, t = flank.evaluate(np.linspace(0.0, flank.s1, n_pts))
    for name, gen, body in (("rack -> male", mesh.rack, mesh.male), ("rack -> female", mesh.rack, mesh.female)):
        best, med = best_of(lambda gen=gen, body=body: conjugate(p, t, gen, body), repeat=5)
        print(f"engine {name}: {n_pts / best / 1e6:.2f} M points/s (best of 5, median {n_pts / med / 1e6:.2f})")
    arc = Arc((60.0, 2.0), 9.0, -1.2, 1.2)
    p, t = arc.evaluate(np.linspace(-1.2, 1.2, n_pts))
    best, med = best_of(lambda: conjugate(p, t, mesh.male, mesh.female), repeat=5)
    print(f"engine male -> female: {n_pts / best / 1e6:.2f} M points/s (best of 5, median {n_pts / med / 1e6:.2f})")
    print(load())


if __name__ == "__main__":
    main()

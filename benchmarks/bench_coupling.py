"""Speed of the gear-coupling film calculation (``rotorcad coupling``; target < 0.2 s a solution).

Run by hand on an idle machine: ``python benchmarks/bench_coupling.py``. Single-threaded BLAS is
forced so that the figures are per core. Prints the best and the median of 9 runs.
"""

from __future__ import annotations

import os

os.environ.setdefault("OMP_NUM_THREADS", "1")
os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import math
import time
from collections.abc import Callable

import numpy as np

from rotorcad.coupling import GearCoupling, analyse
from rotorcad.coupling_film import LineContact, solve_line_contact


def best_of(fn: Callable[[], object], repeat: int = 9) -> tuple[float, float]:
    fn()
    times = []
    for _ in range(repeat):
        t = time.perf_counter()
        fn()
        times.append(time.perf_counter() - t)
    return min(times), float(np.median(times))


def main() -> None:
    coupling = GearCoupling(
        teeth=40,
        module=4.0,
        face_width=32.0,
        speed_rpm=8000.0,
        power_kw=4000.0,
        viscosity=0.02,
        pressure_viscosity=2e-8,
        misalignment=math.radians(0.3),
    )
    r = analyse(coupling)
    best, med = best_of(lambda: analyse(coupling))
    print(
        f"coupling z=40 m=4 b=32 n=8000 P=4000 kW gamma=0.3 deg: h_min {r.min_film_thickness * 1e3:.3f} um, "
        f"Dowson-Higginson ratio {r.ehl_ratio:.3f}; best {best * 1e3:.1f} ms, median {med * 1e3:.1f} ms (target < 200 ms)"
    )
    heavy = LineContact(radius=0.02, load=1e6, speed=2.0, viscosity=0.01, pressure_viscosity=2e-8)
    best, med = best_of(lambda: solve_line_contact(heavy))
    print(f"heavy line contact (Moes M ~ 75): best {best * 1e3:.1f} ms, median {med * 1e3:.1f} ms")
    rigid = LineContact(radius=0.02, load=1e5, speed=5.0, viscosity=0.05, modulus=math.inf)
    best, med = best_of(lambda: solve_line_contact(rigid))
    print(f"rigid isoviscous (Martin): best {best * 1e3:.1f} ms, median {med * 1e3:.1f} ms")


if __name__ == "__main__":
    main()

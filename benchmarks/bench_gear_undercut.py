"""Issue 26, item 3: every gear outline at 0.1 um within 1 ms, near the undercut limit too.

The grid z = 3..200, profile shift x = -0.5..1 (7 values), tool tip radius 0..0.38 m (5 values),
m = 2 mm, alpha = 20 deg; gears refused as pointed or severed are skipped. Each outline is made
three times from a new gear (nothing cached) and its median CPU time kept; printed: the slowest
cases, how many undercut gears there are and the machine's load.
Run by hand: ``python benchmarks/bench_gear_undercut.py``.
"""

from __future__ import annotations

import os

os.environ.setdefault("OMP_NUM_THREADS", "1")
os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import statistics
import time

import numpy as np

from rotorcad.errors import DesignError
from rotorcad.gear import InvoluteGear

DEG = np.pi / 180


def outline_cpu(z: int, x: float, rho: float) -> tuple[float, bool] | None:
    """Median CPU time (s) of three outlines of a new gear, and whether it is undercut; None if refused."""
    times = []
    for _ in range(3):
        t = time.process_time()
        try:
            g = InvoluteGear(z, 2.0, 20 * DEG, shift=x, tip_radius_factor=rho, tolerance=1e-4)
            g.outline()
        except DesignError:
            return None
        times.append(time.process_time() - t)
    return statistics.median(times), g.undercut


def main() -> None:
    print(f"machine load (1, 5, 15 min): {', '.join(f'{v:.2f}' for v in os.getloadavg())} on {os.cpu_count()} cores")
    InvoluteGear(20, 2.0, 20 * DEG, tolerance=1e-4).outline()  # warm-up
    rows = []
    for z in range(3, 201):
        for x in np.linspace(-0.5, 1.0, 7):
            for rho in (0.0, 0.1, 0.2, 0.3, 0.38):
                got = outline_cpu(z, float(x), rho)
                if got is not None:
                    rows.append((got[0], z, float(x), rho, got[1]))
    rows.sort(reverse=True)
    undercut = [r for r in rows if r[4]]
    print(f"{len(rows)} gears ({len(undercut)} undercut); median {statistics.median(r[0] for r in rows) * 1e3:.2f} ms")
    print("slowest (target < 1 ms each):")
    for t, z, x, rho, cut in rows[:8]:
        print(f"  z = {z:3d}, x = {x:+.2f}, tip radius {rho:.2f} m{' (undercut)' if cut else ''}: {t * 1e3:.2f} ms")
    near = [r for r in rows if r[1] in (17, 18, 19, 20, 21) and r[2] == 0.0]
    print(f"z = 17..21 at x = 0 (every tip radius): slowest {max(r[0] for r in near) * 1e3:.2f} ms")
    print(f"machine load (1, 5, 15 min): {', '.join(f'{v:.2f}' for v in os.getloadavg())} on {os.cpu_count()} cores")


if __name__ == "__main__":
    main()

"""Speed of the cutting simulation (issue 4): z = 11 to 1 um scallop (target < 0.5 s) and the
analytic envelope of the same gear (target < 10 ms). Run by hand."""

from __future__ import annotations

import time

import numpy as np

from hob.cutting import simulate_cutting
from rotorcad.gear import InvoluteGear


def main() -> None:
    deg = np.pi / 180
    g = InvoluteGear(11, 2.0, 20 * deg)
    simulate_cutting(g, 1e-3)
    times = []
    for _ in range(5):
        t = time.perf_counter()
        res = simulate_cutting(InvoluteGear(11, 2.0, 20 * deg), 1e-3)
        times.append(time.perf_counter() - t)
    print(
        f"cutting z=11 to 1 um: best {min(times):.3f} s, median {np.median(times):.3f} s, {res.positions} positions, "
        f"deviation {res.max_deviation * 1e3:.3f} um (target < 0.5 s)"
    )
    times = []
    for _ in range(20):
        t = time.perf_counter()
        InvoluteGear(11, 2.0, 20 * deg, tolerance=1e-3).outline()
        times.append(time.perf_counter() - t)
    best, median = min(times) * 1e3, np.median(times) * 1e3
    print(f"analytic envelope z=11 (1 um chords): best {best:.1f} ms, median {median:.1f} ms (target < 10 ms)")


if __name__ == "__main__":
    main()

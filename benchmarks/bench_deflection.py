"""Speed of ``rotorcad deflect`` (issue "rotor deflection and gear-coupling film"): the chamber
table of a pair (one-off per design), a deflection sweep over one male pitch at 100 angles
(target < 1 s), and the convergence of the result with the chamber table's phase step and the
number of Ritz terms. Run by hand: ``python benchmarks/bench_deflection.py``."""

from __future__ import annotations

import os
import statistics
import time
from pathlib import Path

import numpy as np

from rotorcad.cli.export_cmd import _rotor_options
from rotorcad.cli.rotor import _build
from rotorcad.deflection import GasDeflection

SAMPLE = Path(__file__).resolve().parents[1] / "samples" / "rack_involute_5_6.toml"


def main() -> None:
    print(f"load average {os.getloadavg()[0]:.2f}, {os.cpu_count()} cores")
    rotors, _, _ = _build(SAMPLE, _rotor_options(SAMPLE))
    pitch = 2 * np.pi / rotors.pair.male_teeth
    angles = np.linspace(0.0, pitch, 100, endpoint=False)
    for step in (2.0, 1.0, 0.5):
        start = time.perf_counter()
        model = GasDeflection(rotors, 1.0, 8.0, step_deg=step)
        built = time.perf_counter() - start
        times = []
        for _ in range(7):
            start = time.perf_counter()
            swept = model.sweep(angles)
            times.append(time.perf_counter() - start)
        print(
            f"phase step {step:g} deg: model {built:.2f} s; sweep of 100 angles best {min(times):.3f} s, "
            f"median {statistics.median(times):.3f} s (target < 1 s); largest deflection male "
            f"{swept[:, 0].max() * 1e3:.4f} um, female {swept[:, 1].max() * 1e3:.4f} um"
        )
    worst = angles[int(np.argmax(swept[:, 0]))]
    for terms in (2, 5, 10, 40, 120):
        print(f"  {terms:3d} Ritz terms: male {model.at(worst, terms=terms).largest('male')[0] * 1e3:.5f} um")


if __name__ == "__main__":
    main()

"""Issue 14, item 3: both rotor solids of the README sample (samples/rack_involute_5_6.toml) at
5 um surface tolerance in under 1 s. Best and median of 7 runs, with the machine's load.
Run by hand: ``python benchmarks/bench_readme_solids.py``."""

from __future__ import annotations

import os
import statistics
import time
import tomllib
from pathlib import Path

from rotorcad.design import rotor_design
from rotorcad.rotor_build import build_pair, pair_spec
from rotorcad.solids import helical_solid

SAMPLE = Path(__file__).resolve().parents[1] / "samples" / "rack_involute_5_6.toml"


def both_solids(tol: float = 0.005) -> float:
    with SAMPLE.open("rb") as f:
        rotors = build_pair(pair_spec(rotor_design(tomllib.load(f), SAMPLE.parent)))
    pair = rotors.pair
    t = time.perf_counter()
    male_s, female_s = rotors.section("male", tol / 2), rotors.section("female", tol / 2)
    # the triangles the export writes (the manifold is made only for booleans: bench_solids.py)
    meshes = [
        helical_solid(male_s, pair.lead, pair.length, tol).triangle_mesh,
        helical_solid(female_s, -pair.female_lead, pair.length, tol).triangle_mesh,
    ]
    assert all(len(m.faces) for m in meshes)
    return time.perf_counter() - t


def main() -> None:
    runs = [both_solids() for _ in range(7)]
    print(f"load {os.getloadavg()[0]:.2f} on {os.cpu_count()} cores")
    best, median = min(runs), statistics.median(runs)
    print(f"both solids of the README sample at 5 um: best {best:.3f} s, median {median:.3f} s (target < 1 s)")


if __name__ == "__main__":
    main()

"""Speed and memory of issue 3: a 5/6 pair from a rack, both profiles at 1 um chord error, plus
the whole meshing analysis (target < 100 ms on one core, memory < 200 MB).

Run by hand: ``python benchmarks/bench_rotor.py``.
"""

from __future__ import annotations

import os

os.environ.setdefault("OMP_NUM_THREADS", "1")
os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import resource
import time
import tomllib
from pathlib import Path

import numpy as np

from rotorcad.design import rotor_design
from rotorcad.meshing import MeshingAnalysis
from rotorcad.rotor_build import pair_spec
from rotorcad.rotor_families import build_family
from rotorcad.rotor_pair import RotorPair

SAMPLES = Path(__file__).resolve().parents[1] / "samples"


def sample_spec(name: str):
    """The pair and family of a sample design (its own pair: the asymmetric SRM needs its root on the pitch circle)."""
    path = SAMPLES / name
    with path.open("rb") as f:
        return pair_spec(rotor_design(tomllib.load(f), path.parent))


def run(spec) -> tuple[float, int, int]:
    t = time.perf_counter()
    rotors = build_family(spec.pair, spec.family, spec.params)
    rotors = type(rotors)(rotors.pair, rotors.rack, rotors.family, tolerance=1e-3)
    male = rotors.male_outline(1e-3)
    female = rotors.female_outline(1e-3)
    MeshingAnalysis(rotors, samples=400).summary()
    return time.perf_counter() - t, len(male.points), len(female.points)


def main() -> None:
    for sample in ("rack_involute_5_6.toml", "srm_asymmetric_5_6.toml"):
        spec = sample_spec(sample)
        run(spec)
        times = [run(spec)[0] for _ in range(7)]
        _, nm, nf = run(spec)
        print(
            f"{spec.family} {spec.pair.male_teeth}/{spec.pair.female_teeth} from rack, 1 um chords ({nm} + {nf} points)"
            f" + analysis: best {min(times) * 1e3:.0f} ms, median {np.median(times) * 1e3:.0f} ms (target < 100 ms)"
        )
    from hob.rack import rack_deviation

    rotors = build_family(
        RotorPair(5, 6, 116.0, 63.0, 45.0, 71.0, 53.0),
        "rack-involute",
        {"tip_rounding": 1.4, "root_rounding": 1.0, "lobe_width": 0.6},
    )
    rack_deviation(rotors)
    times = []
    for _ in range(7):
        t = time.perf_counter()
        dev = rack_deviation(rotors)
        times.append(time.perf_counter() - t)
    print(
        f"rack derivation from both rotors of the 5/6 pair + deviation ({dev * 1e3:.4f} um): "
        f"best {min(times) * 1e3:.0f} ms, median {np.median(times) * 1e3:.0f} ms (target < 50 ms)"
    )
    peak = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024
    print(f"peak resident memory of this process: {peak:.0f} MB (target < 200 MB)")


if __name__ == "__main__":
    main()

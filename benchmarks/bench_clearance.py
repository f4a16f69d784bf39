"""Speed of the meshing clearance (Wu & Chi) from measured points: the rack-involute sample's
outlines written at 1 um chords (about 1800 points per rotor), both racks, positioning on the
driving flank, clearance and band. No target in an issue yet; figures go to the note.

Run by hand: ``python benchmarks/bench_clearance.py``.
"""

from __future__ import annotations

import os

os.environ.setdefault("OMP_NUM_THREADS", "1")
os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import time

import numpy as np

from rotorcad.clearance import MeshingClearance
from rotorcad.design import load_rotor_design
from rotorcad.rotor_families import build_family
from rotorcad.rotor_pair import RotorPair
from rotorcad.rotor_points import lobe_pieces


def main() -> None:
    d = load_rotor_design("samples/rack_involute_5_6.toml")
    pair = RotorPair(**d["pair"])
    rotors = build_family(pair, d["family"], d["params"])
    male = rotors.male_outline(1e-3).points
    female = rotors.female_outline(1e-3).points
    times = {}
    for contact in ("as-given", "driving"):
        runs = []
        for _ in range(5):
            t = time.perf_counter()
            mc = MeshingClearance(pair, lobe_pieces(pair, male, "male"), lobe_pieces(pair, female, "female"), contact=contact)
            summary = mc.summary()
            runs.append(time.perf_counter() - t)
        times[contact] = runs
        print(
            f"clearance {contact:9s} ({len(male)} + {len(female)} points, {len(mc.female_rack.points)} datum rack points): "
            f"best {min(runs) * 1e3:.0f} ms, median {np.median(runs) * 1e3:.0f} ms; "
            f"max {summary['max_normal_clearance'] * 1e3:.2f} um, contact line {summary['contact_line_length']:.2f} mm"
        )


if __name__ == "__main__":
    main()

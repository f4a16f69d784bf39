"""Accuracy of ``rotorcad clearance`` from CMM-like points, by density and scatter (README).

Pairs that rotorcad did not make (tests/independent_pairs.py, cut by brute force with shapely):
the 4/6 trapezoid rack pair and the 5/6 pair of a rack with one straight and one circular-arc flank,
both with sharp tip corners cut back by the rack's flats. Each rotor's cut outline is resampled at
80, 300 and 2000 points a lobe with 0, 1 and 2 um Gaussian scatter along the normals (3 seeds),
lead 300 mm, racks brought into contact on the driving flank.

Truth on the contact zone: for the 4/6 pair zero (both rotors cut by one rack: the contact zone is
conjugate, tests/test_clearance_zones.py checks it against the brute-force closest approach); for
the 5/6 pair, whose flank near the female tip is left a few um off by the cut, the clearance of the
cut outlines themselves at the same rack point (checked against the brute force to 1.5 um in the
same tests). Printed per case: the largest error on the contact zone over the seeds, the largest
shift of the contact alignment from the exact pair's, the stated accuracy, and how many seeds raise
the interference flag.

Run by hand: ``python benchmarks/bench_clearance_accuracy.py`` (about 2 minutes).
"""

from __future__ import annotations

import os

os.environ.setdefault("OMP_NUM_THREADS", "1")
os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import sys
from pathlib import Path

import numpy as np
from scipy.spatial import cKDTree

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tests"))

from independent_pairs import arc_flank_5_6, cut_rotor, resample, trapezoid_4_6

from rotorcad.clearance import MeshingClearance, points_quality
from rotorcad.cli.clearance_cmd import INTERFERENCE_THRESHOLD
from rotorcad.rotor_pair import RotorPair
from rotorcad.rotor_points import lobe_pieces


def per_lobe(ring: np.ndarray, teeth: int, points: int) -> float:
    return float(np.hypot(*np.diff(np.vstack([ring, ring[:1]]), axis=0).T).sum()) / teeth / points


def evaluate(pair: RotorPair, male: np.ndarray, female: np.ndarray) -> MeshingClearance:
    qm, qf = points_quality(male), points_quality(female)
    return MeshingClearance(
        pair,
        lobe_pieces(pair, male, "male"),
        lobe_pieces(pair, female, "female"),
        scatter=max(qm[0], qf[0]),
        spacing=max(qm[1], qf[1]),
    )


def main() -> None:
    print("| pair | points a lobe | scatter | error on the contact zone | alignment | stated accuracy | interference |")
    print("|---|---|---|---|---|---|---|")
    for label, rack_pair, truth_zero in (("4/6 trapezoid", trapezoid_4_6(), True), ("5/6 arc flank", arc_flank_5_6(), False)):
        male, female = cut_rotor(rack_pair, "male"), cut_rotor(rack_pair, "female")
        z1, z2 = rack_pair.male_teeth, rack_pair.female_teeth
        pair = RotorPair(z1, z2, 100.0, **rack_pair.radii(), lead=300.0, length=190.0, strict=False)
        ref = evaluate(pair, male, female)
        ref_tree = cKDTree(ref.female_rack.points)
        ref_c = ref.clearance
        for points in (2000, 300, 80):
            for noise in (0.0, 1e-3, 2e-3):
                errors, shifts, accuracy, flags = [], [], [], 0
                for seed in (1, 2, 3):
                    m = resample(male, per_lobe(male, z1, points), noise, seed=seed)
                    f = resample(female, per_lobe(female, z2, points), noise, seed=seed + 100)
                    mc = evaluate(pair, m, f)
                    s = mc.summary()
                    on = mc.contact_zone
                    c = mc.clearance[on]
                    if truth_zero:
                        truth = np.zeros(on.sum())
                    else:  # the exact outlines' clearance at the nearest rack point (the racks' own frames)
                        truth = ref_c[ref_tree.query(mc.female_rack.points[on])[1]]
                    errors.append(float(np.nanmax(np.abs(c - truth))))
                    shifts.append(abs(s["female_rack_shift"] - ref.shift))
                    accuracy.append(s["accuracy"])
                    flags += s["min_normal_clearance"] < -max(INTERFERENCE_THRESHOLD, s["accuracy"])
                print(
                    f"| {label} | {points} | {noise * 1e3:.0f} µm | {max(errors) * 1e3:.1f} µm | {max(shifts) * 1e3:.1f} µm "
                    f"| {min(accuracy) * 1e3:.1f}-{max(accuracy) * 1e3:.1f} µm | {flags}/3 |",
                    flush=True,
                )


if __name__ == "__main__":
    main()

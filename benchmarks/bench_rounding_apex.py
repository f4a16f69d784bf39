"""The blow-hole of a male given as its own CSV with scatter, against the design's, over seeds (issue 21 item 3).

Each sample's male as ``rotor --male-csv`` writes it (the section's exterior: 1 um chord, about 284 points a
lobe for the 5/6 N rack), with normal scatter ``sigma`` added to each coordinate, read back as
``--male-points``. Printed per sample and seed: the blow-hole (mm²) and its departure from the design's (%),
the uncertainty the points state and whether they resolve it, the CPU time, and where a male tip rounding's
circles placed the apex (:mod:`rotorcad.meshing.rounding_apex`) their radii. The reference is the design's
blow-hole from its exact curves, which the points did not produce.

Run by hand: ``python benchmarks/bench_rounding_apex.py [samples] [seeds] [sigma]``, e.g.
``python benchmarks/bench_rounding_apex.py n_rack_5_6,rinder_deix_5_6 0-7 1e-3`` (about 1 min CPU),
``python benchmarks/bench_rounding_apex.py all 0`` for every rotor sample at one seed.
"""

from __future__ import annotations

import sys
import time
import tomllib
from pathlib import Path

import numpy as np

from rotorcad.design import rotor_design
from rotorcad.rotor_build import PairSpec, analyse_pair, build_pair, pair_spec

SAMPLES = Path(__file__).resolve().parents[1] / "samples"


def _exterior(polygon) -> np.ndarray:
    pts = np.asarray(polygon.exterior.coords)[:-1]
    area = 0.5 * np.sum(pts[:, 0] * np.roll(pts[:, 1], -1) - np.roll(pts[:, 0], -1) * pts[:, 1])
    return pts if area > 0 else pts[::-1]


def _seeds(text: str) -> list[int]:
    if "-" in text:
        lo, hi = text.split("-")
        return list(range(int(lo), int(hi) + 1))
    return [int(s) for s in text.split(",")]


def main(argv: list[str]) -> None:
    names = argv[0] if argv else "n_rack_5_6,rinder_deix_5_6"
    seeds = _seeds(argv[1]) if len(argv) > 1 else list(range(8))
    sigma = float(argv[2]) if len(argv) > 2 else 1e-3
    if names == "all":
        samples = [p.stem for p in sorted(SAMPLES.glob("*.toml")) if "profile" in tomllib.loads(p.read_text())]
    else:
        samples = names.split(",")
    print(f"{'sample':22s} seed  area mm²  design    change  uncertainty resolved  cpu s  rounding, flank circle (mm)")
    for name in samples:
        spec = pair_spec(rotor_design(tomllib.loads((SAMPLES / f"{name}.toml").read_text()), SAMPLES))
        analysis, design = analyse_pair(build_pair(spec), spec.speed_rpm)
        male = _exterior(analysis.sections[0])
        want = design["blow_hole_area"]
        for seed in seeds:
            noisy = male + np.random.default_rng(seed).normal(0.0, sigma, male.shape)
            start = time.process_time()
            rotors = build_pair(PairSpec(spec.pair, "male-points", {}, noisy, None, spec.speed_rpm, 0.0), label="--male-points")
            given, summary = analyse_pair(rotors, spec.speed_rpm)
            cpu = time.process_time() - start
            got = summary["blow_hole_area"]
            change = 100.0 * (got / want - 1.0) if want > 1e-9 else float("nan")
            model = getattr(given, "apex_rounding", None)  # None before the rounding model
            circles = "" if model is None else f"{model[1]:.4f}, {model[2]} {model[4]:.4f}"
            print(
                f"{name:22s} {seed:4d} {got:9.4f} {want:7.4f} {change:+8.2f} % {summary['blow_hole_uncertainty']:9.3f} "
                f"{summary['blow_hole_resolved']!s:8s} {cpu:6.1f}  {circles}"
            )


if __name__ == "__main__":
    main(sys.argv[1:])

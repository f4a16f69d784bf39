"""Measure the blow-hole apex from a flank's generating line (issue 21 item 3): which reads take a line, their error.

For each sample, rotor, density (points a lobe), scatter (um), seed and sampling phase: the design's lobe drawn to a
0.01 um chord, patterned round the rotor and scanned evenly (tests/independent_pairs.py ``scan``), with normal
scatter on each coordinate; one line per read (TSV): the frame whose line placed the apex (or -), its window (mm),
the radius its normals tell (mm, :func:`bend_radius`), the blow-hole (mm²), its error against the design's (%), the stated
uncertainty U (mm²), resolved, and whether a resolved read lies outside U.
Reference: the design's blow-hole from its exact curves.

usage: python benchmarks/bench_line_apex.py [--samples a,b] [--sides male,female] [--per 80,150,300]
       [--scatter 0,1,2] [--seeds 0-7] [--phases 0.37] [--out file.tsv]
"""

from __future__ import annotations

import argparse
import sys
import time
import tomllib
import warnings
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "tests"))

from independent_pairs import patterned, scan  # noqa: E402

from rotorcad.design import rotor_design  # noqa: E402
from rotorcad.errors import DesignError, InputNote  # noqa: E402
from rotorcad.meshing import MeshingAnalysis  # noqa: E402
from rotorcad.meshing.generating_line import line_apex  # noqa: E402
from rotorcad.rotor_build import PairSpec, build_pair, pair_spec  # noqa: E402

SAMPLES = ROOT / "samples"


def design(name: str) -> dict:
    spec = pair_spec(rotor_design(tomllib.loads((SAMPLES / f"{name}.toml").read_text()), SAMPLES))
    analysis = MeshingAnalysis(build_pair(spec), spec.speed_rpm)
    out = {"spec": spec, "area": analysis.blow_hole_area}
    for side, lobe in (("male", analysis.rotors.male_lobe()), ("female", analysis.rotors.female_lobe())):
        out[side] = np.vstack([seg.resampled(1e-5).points for seg in lobe.segments])
    return out


def read(d: dict, side: str, per: int, scatter_um: float, seed: int, phase: float) -> tuple:
    spec = d["spec"]
    teeth = spec.pair.male_teeth if side == "male" else spec.pair.female_teeth
    pts = scan(patterned(d[side], teeth), per * teeth, phase)
    if scatter_um:
        pts = pts + np.random.default_rng(seed).normal(0.0, scatter_um * 1e-3, pts.shape)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", InputNote)
        given = MeshingAnalysis(
            build_pair(PairSpec(spec.pair, f"{side}-points", {}, pts, None, spec.speed_rpm, 0.0), label=f"--{side}-points"),
            spec.speed_rpm,
        )
    area, u, resolved = given.blow_hole_area, given.blow_hole_uncertainty, given.blow_hole_resolved
    pair = spec.pair
    tips = ((np.zeros(2), pair.male_tip_radius), (np.array([pair.center_distance, 0.0]), pair.female_tip_radius))
    k = int(np.argmin(np.hypot(*(given.meshline - given.cusp).T)))
    found = line_apex(given.pieces, given.meshline[k], tips, given.judged_accuracy, pair)
    if found is None:
        return "-", 0.0, 0.0, area, u, resolved
    return found.frame, found.window, found.bend, area, u, resolved


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument(
        "--samples", default="narrow_tip_5_6,srm_asymmetric_5_6,srm_b_5_6,rack_involute_5_6,n_rack_5_6,rinder_deix_5_6"
    )
    ap.add_argument("--sides", default="male,female")
    ap.add_argument("--per", default="80,150,300")
    ap.add_argument("--scatter", default="0,1,2")
    ap.add_argument("--seeds", default="0-7")
    ap.add_argument("--phases", default="0.37")
    ap.add_argument("--out", default=None)
    a = ap.parse_args()
    lo, _, hi = a.seeds.partition("-")
    seeds = list(range(int(lo), int(hi or lo) + 1))
    out = open(a.out, "a") if a.out else None
    for name in a.samples.split(","):
        d = design(name)
        for side in a.sides.split(","):
            for per in (int(v) for v in a.per.split(",")):
                for scatter in (float(v) for v in a.scatter.split(",")):
                    for phase in (float(v) for v in a.phases.split(",")):
                        for seed in seeds if scatter else seeds[:1]:
                            t0 = time.process_time()
                            try:
                                frame, window, span, area, u, resolved = read(d, side, per, scatter, seed, phase)
                            except DesignError as exc:
                                line = f"{name}\t{side}\t{per}\t{scatter:g}\t{seed}\t{phase:g}\trefused: {exc}"
                            else:
                                err = 100.0 * (area - d["area"]) / d["area"]
                                outside = "OUTSIDE" if resolved and abs(area - d["area"]) > u else ""
                                line = (
                                    f"{name}\t{side}\t{per}\t{scatter:g}\t{seed}\t{phase:g}\t{frame}\t{window:.2f}\t{span:.1f}\t"
                                    f"{area:.4f}\t{d['area']:.4f}\t{err:+.2f}%\t{u:.4f}\t{resolved}\t{outside}\t"
                                    f"{time.process_time() - t0:.1f}s"
                                )
                            print(line, flush=True)
                            if out:
                                out.write(line + "\n")
                                out.flush()


if __name__ == "__main__":
    main()

"""Measure the blow-hole apex from a flank's generating line (issue 21 item 3): which reads take a line, their error.

For each sample, rotor, density (points a lobe), scatter (um), seed and sampling phase: the design's lobe drawn to a
0.01 um chord, patterned round the rotor and scanned evenly (tests/independent_pairs.py ``scan``), with normal
scatter on each coordinate (``--normal``: along the outline's normals, as a CMM's, as the new user's scans of issue
21 had it); one line per read (TSV): the frame whose line placed the apex (or -), its window (mm), the radius its
normals tell (mm, :func:`bend_radius`), the blow-hole (mm²), the design's, the error (%), the stated uncertainty U
(mm²), resolved, OUTSIDE where the design lies outside U (resolved or not), the apex's model (:func:`apex_model`:
line, arc, rounding or tip), OFF1% where a resolved read lies more than 1 % off the design (of a closed
meshline's, Krigar's, more than :data:`BLOW_HOLE_RESOLUTION` of the female flute's area). Last, the counts over all
reads. Reference: the design's blow-hole from its exact curves.

usage: python benchmarks/bench_line_apex.py [--samples a,b|all] [--sides male,female] [--per 80,150,300]
       [--scatter 0,1,2] [--seeds 0-7] [--phases 0.37|0-0.9] [--normal] [--out file.tsv]

Issue 21's F1 (the narrow-tip female at 80 exact points a lobe read 17 times the design's blow-hole, resolved),
every rotor sample at 80 points a lobe, both rotors, phases 0-0.9, exact and 1 um along the normals (seed 1):
``python benchmarks/bench_line_apex.py --samples all --per 80 --scatter 0,1 --seeds 1 --phases 0-0.9 --normal``.
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
from rotorcad.meshing.blow_hole_accuracy import BLOW_HOLE_RESOLUTION, placing_line  # noqa: E402
from rotorcad.meshing.generating_line import line_apex  # noqa: E402
from rotorcad.rotor_build import PairSpec, build_pair, pair_spec  # noqa: E402

SAMPLES = ROOT / "samples"


def design(name: str) -> dict:
    spec = pair_spec(rotor_design(tomllib.loads((SAMPLES / f"{name}.toml").read_text()), SAMPLES))
    analysis = MeshingAnalysis(build_pair(spec), spec.speed_rpm)
    # within 1 % of the design's area; of a closed meshline's (Krigar's: 0), within the resolution that tells it closed
    area = analysis.blow_hole_area
    near = 0.01 * area if area > 0.0 else BLOW_HOLE_RESOLUTION * analysis.female_flute_area
    out = {"spec": spec, "area": area, "near": near}
    for side, lobe in (("male", analysis.rotors.male_lobe()), ("female", analysis.rotors.female_lobe())):
        out[side] = np.vstack([seg.resampled(1e-5).points for seg in lobe.segments])
    return out


def apex_model(given: MeshingAnalysis) -> str:
    """Which model placed the apex: a generating line, a male arc, a male tip rounding's circles, else the tip's."""
    if placing_line(given) is not None:
        return "line"
    if given.apex_arc is not None:
        return "arc"
    return "rounding" if given.apex_rounding is not None else "tip"


def read(d: dict, side: str, per: int, scatter_um: float, seed: int, phase: float, normal: bool = False) -> tuple:
    spec = d["spec"]
    teeth = spec.pair.male_teeth if side == "male" else spec.pair.female_teeth
    pts = scan(patterned(d[side], teeth), per * teeth, phase)
    rng = np.random.default_rng(seed)
    if scatter_um and normal:
        step = np.roll(pts, -1, axis=0) - np.roll(pts, 1, axis=0)
        along = np.column_stack([step[:, 1], -step[:, 0]]) / np.hypot(*step.T)[:, None]
        pts = pts + along * rng.normal(0.0, scatter_um * 1e-3, len(pts))[:, None]
    elif scatter_um:
        pts = pts + rng.normal(0.0, scatter_um * 1e-3, pts.shape)
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
    model = apex_model(given)
    if found is None:
        return "-", 0.0, 0.0, area, u, resolved, model
    return found.frame, found.window, found.bend, area, u, resolved, model


def _values(text: str) -> list[float]:
    """``a,b,c`` or ``lo-hi`` (tenths from lo to hi)."""
    if "-" in text:
        lo, hi = (float(v) for v in text.split("-"))
        return [round(v, 6) for v in np.arange(lo, hi + 1e-9, 0.1)]
    return [float(v) for v in text.split(",")]


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
    ap.add_argument("--normal", action="store_true")
    ap.add_argument("--out", default=None)
    a = ap.parse_args()
    if a.samples == "all":
        a.samples = ",".join(p.stem for p in sorted(SAMPLES.glob("*.toml")) if "profile" in tomllib.loads(p.read_text()))
    counts = {"reads": 0, "refused": 0, "resolved": 0, "resolved off 1 %": 0, "design outside U": 0}
    lo, _, hi = a.seeds.partition("-")
    seeds = list(range(int(lo), int(hi or lo) + 1))
    out = open(a.out, "a") if a.out else None
    for name in a.samples.split(","):
        d = design(name)
        for side in a.sides.split(","):
            for per in (int(v) for v in a.per.split(",")):
                for scatter in (float(v) for v in a.scatter.split(",")):
                    for phase in _values(a.phases):
                        for seed in seeds if scatter else seeds[:1]:
                            t0 = time.process_time()
                            try:
                                frame, window, span, area, u, resolved, model = read(d, side, per, scatter, seed, phase, a.normal)
                            except DesignError as exc:
                                line = f"{name}\t{side}\t{per}\t{scatter:g}\t{seed}\t{phase:g}\trefused: {exc}"
                                counts["refused"] += 1
                            else:
                                err = 100.0 * (area - d["area"]) / d["area"] if d["area"] > 0.0 else np.nan  # closed: none
                                outside = "OUTSIDE" if abs(area - d["area"]) > u else ""
                                off = "OFF1%" if resolved and abs(area - d["area"]) > d["near"] else ""
                                counts["reads"] += 1
                                counts["resolved"] += bool(resolved)
                                counts["resolved off 1 %"] += bool(off)
                                counts["design outside U"] += bool(outside)
                                line = (
                                    f"{name}\t{side}\t{per}\t{scatter:g}\t{seed}\t{phase:g}\t{frame}\t{window:.2f}\t{span:.1f}\t"
                                    f"{area:.4f}\t{d['area']:.4f}\t{err:+.2f}%\t{u:.4f}\t{resolved}\t{outside}\t"
                                    f"{model}\t{off}\t{time.process_time() - t0:.1f}s"
                                )
                            print(line, flush=True)
                            if out:
                                out.write(line + "\n")
                                out.flush()
    print(", ".join(f"{k} {v}" for k, v in counts.items()), flush=True)


if __name__ == "__main__":
    main()

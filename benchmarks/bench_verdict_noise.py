"""Rinder's verdicts from scattered points against the design's, for every sample (issue 21 item 3, README).

Each rotor sample's male as its own CSV writes it (the section's exterior), with normal scatter of
1 and 2 um added to each coordinate (3 seeds), read back as ``--male-points``. Printed per case:
whether the defects (kind, rotor, flank part, point-generated; each within the resolution of the
design's), the per-flank "runs" and the blow-hole (within 1 %, or 1e-3 mm² where the design's
meshline closes) are the design's, the defect counts and the accuracy the points were judged to.

Run by hand: ``python benchmarks/bench_verdict_noise.py [samples] [sigmas] [seeds]``, e.g.
``python benchmarks/bench_verdict_noise.py all 1e-3,2e-3 0,1,2`` (about 2 minutes).
"""

from __future__ import annotations

import sys
import tomllib
from collections import Counter
from pathlib import Path

import numpy as np

from rotorcad.design import rotor_design
from rotorcad.errors import DesignError
from rotorcad.meshing import resolution
from rotorcad.rotor_build import PairSpec, analyse_pair, build_pair, pair_spec

SAMPLES = Path(__file__).resolve().parents[1] / "samples"


def _key(d: dict) -> tuple:
    return d["kind"], d["rotor"], d["flank_role"], d["point_generated"]


def _exterior(polygon) -> np.ndarray:
    pts = np.asarray(polygon.exterior.coords)[:-1]
    area = 0.5 * np.sum(pts[:, 0] * np.roll(pts[:, 1], -1) - np.roll(pts[:, 0], -1) * pts[:, 1])
    return pts if area > 0 else pts[::-1]


def compare(design: dict, given: dict) -> tuple[bool, bool, float]:
    """Same defects and running verdicts; blow-hole change (relative, or mm² when the design's is 0)."""
    same = Counter(map(_key, given["defects"])) == Counter(map(_key, design["defects"]))
    reach = resolution(given["defect_accuracy"], design["center_distance"])
    for d in design["defects"]:
        near = [
            np.hypot(g["x"] - d["x"], g["y"] - d["y"]) - 0.5 * (g["extent"] + d["extent"])
            for g in given["defects"]
            if _key(g) == _key(d)
        ]
        same = same and bool(near) and min(near) <= reach
    runs = all(
        given["flanks"][f]["runs_without_timing_gears"] == r["runs_without_timing_gears"] for f, r in design["flanks"].items()
    )
    area = design["blow_hole_area"]
    change = (given["blow_hole_area"] - area) / area if area > 1e-9 else given["blow_hole_area"]
    return same, runs, change


def main(argv: list[str]) -> None:
    names = [p.stem for p in sorted(SAMPLES.glob("*.toml")) if "profile" in tomllib.loads(p.read_text())]
    if argv and argv[0] != "all":
        names = argv[0].split(",")
    sigmas = [float(s) for s in (argv[1] if len(argv) > 1 else "1e-3,2e-3").split(",")]
    seeds = [int(s) for s in (argv[2] if len(argv) > 2 else "0,1,2").split(",")]
    for name in names:
        spec = pair_spec(rotor_design(tomllib.loads((SAMPLES / f"{name}.toml").read_text()), SAMPLES))
        analysis, design = analyse_pair(build_pair(spec), spec.speed_rpm)
        male = _exterior(analysis.sections[0])
        for sigma in sigmas:
            for seed in seeds:
                noisy = male + np.random.default_rng(seed).normal(0.0, sigma, male.shape)
                head = f"{name:20s} {sigma * 1e3:.0f} um seed {seed}"
                try:
                    rotors = build_pair(
                        PairSpec(spec.pair, "male-points", {}, noisy, None, spec.speed_rpm, 0.0), label="--male-points"
                    )
                except DesignError as exc:
                    print(f"{head}: refused ({exc})")
                    continue
                given = analyse_pair(rotors, spec.speed_rpm)[1]
                same, runs, change = compare(design, given)
                closes = design["blow_hole_area"] <= 1e-9
                hole = f"{change:.4f} mm² (design 0)" if closes else f"{100 * change:+.2f} %"
                within = change <= 1e-3 if closes else abs(change) <= 0.01
                # the design's area within the stated uncertainty of the points' (blow_hole_uncertainty)
                gap = abs(given["blow_hole_area"] - design["blow_hole_area"])
                inside = gap <= given["blow_hole_uncertainty"] + (1e-3 if closes else 0.01 * design["blow_hole_area"])
                hole += f" ± {given['blow_hole_uncertainty']:.3g} mm² ({'holds' if inside else 'MISSES'})"
                print(
                    f"{head}: defects {'same' if same else 'DIFFER'} ({len(given['defects'])}/{len(design['defects'])}), "
                    f"runs {'same' if runs else 'DIFFER'}, blow-hole {hole}{'' if within else ' (off)'}, "
                    f"judged to {1e3 * given['defect_accuracy']:.2f} um",
                    flush=True,
                )


if __name__ == "__main__":
    main(sys.argv[1:])

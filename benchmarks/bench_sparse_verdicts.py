"""Defects and running verdicts of every sample's rotors as 80-300 points a lobe against the design's (issue 21 item 3).

The inputs of ``bench_moderate_densities.py`` (each rotor sample's male and female outline, 0.01 um chord, as points
evenly spaced at 80, 150 and 300 a lobe, phase 0.37 of a spacing; exact, and with 1 and 2 um of scatter along the
normals at seeds 1 and 2), read back as ``--male-points`` / ``--female-points``. Printed per input that differs from
the design: the defects it has more and fewer (kind, rotor, lobe part, tip corner) and the flanks whose running
verdict differs or is undecided at the input's accuracy (``running_decided`` false); then per density the counts,
and the differences by kind. Each difference is then judged by :func:`rotorcad.meshing.undecided.compare_defects`:
explained by an undecided tip corner (a corner or a rounding shorter than two point spacings, the design's too), or
differing; "decided equal" counts the inputs whose defects are the design's key for key.

Run by hand: ``python benchmarks/bench_sparse_verdicts.py [80,150,300]`` (about 2 minutes of CPU for the three).
"""

from __future__ import annotations

import sys
import tomllib
from collections import Counter

import numpy as np
from bench_moderate_densities import NAMES, SAMPLES, _pattern, _scan

from rotorcad.design import rotor_design
from rotorcad.errors import DesignError
from rotorcad.meshing.undecided import compare_defects, corner_margin
from rotorcad.roles import Side
from rotorcad.rotor_build import PairSpec, analyse_pair, build_pair, pair_spec

FLANKS = ("driving", "sealing")
DRAWS = ((0.0, 0), (1e-3, 1), (1e-3, 2), (2e-3, 1), (2e-3, 2))  # (scatter mm, seed)


def _keys(summary: dict) -> Counter:
    return Counter((d["kind"], d["rotor"], d["flank_role"], d["tip_corner"]) for d in summary["defects"])


def main(densities: str = "80,150,300") -> None:
    pers = [int(p) for p in densities.split(",")]
    counts = {per: Counter() for per in pers}
    kinds = {per: Counter() for per in pers}
    for name in NAMES:
        spec = pair_spec(rotor_design(tomllib.loads((SAMPLES / f"{name}.toml").read_text()), SAMPLES))
        rotors = build_pair(spec)
        analysis, design = analyse_pair(rotors, spec.speed_rpm)
        for side, lobe, teeth in (
            ("male", rotors.male_lobe(), spec.pair.male_teeth),
            ("female", rotors.female_lobe(), spec.pair.female_teeth),
        ):
            ring = _pattern(np.vstack([s.resampled(1e-5).points for s in lobe.segments]), teeth)
            for per in pers:
                for sigma, seed in DRAWS:
                    pts = _scan(ring, per * teeth, 0.37)
                    if sigma:
                        d = np.roll(pts, -1, axis=0) - np.roll(pts, 1, axis=0)
                        normal = np.column_stack([d[:, 1], -d[:, 0]]) / np.hypot(d[:, 0], d[:, 1])[:, None]
                        pts = pts + np.random.default_rng(seed).normal(0.0, sigma, len(pts))[:, None] * normal
                    case = f"{name} {side} {per} a lobe {sigma * 1e3:g} um seed {seed}"
                    try:
                        given = build_pair(
                            PairSpec(spec.pair, f"{side}-points", {}, pts, None, spec.speed_rpm, 0.0), label=f"--{side}-points"
                        )
                    except DesignError:
                        print(f"{case}: refused")
                        continue
                    got = analyse_pair(given, spec.speed_rpm)[1]
                    counts[per]["inputs"] += 1
                    extra, lost = _keys(got) - _keys(design), _keys(design) - _keys(got)
                    differing, explained = compare_defects(analysis, got)
                    loose = [d for d in got["defects"] if not d["decided"]] + got["undecided_defects"]
                    pair = analysis.rotors.pair
                    beyond = [  # undecided where the design's own margin is beyond the points' spacing
                        (d["rotor"], d["flank_role"], round(m, 3), round(d["margin_accuracy"], 3))
                        for d in loose
                        if (m := corner_margin(analysis.pieces, pair, Side(d["rotor"]), np.asarray(d["corner"]), d["extent"]))
                        > d["margin_accuracy"]
                    ]
                    counts[per]["undecided marks"] += len(loose)
                    counts[per]["undecided marks the design resolves"] += len(beyond)
                    undecided = [f for f in FLANKS if not got["flanks"][f]["running_decided"]]
                    flips = [
                        f
                        for f in FLANKS
                        if f not in undecided
                        and got["flanks"][f]["runs_without_timing_gears"] != design["flanks"][f]["runs_without_timing_gears"]
                    ]
                    counts[per]["defects differ"] += bool(extra or lost)
                    counts[per]["decided equal"] += not (extra or lost)
                    counts[per]["undecided, explained"] += bool(explained and not differing)
                    counts[per]["differing"] += bool(differing)
                    counts[per]["running differs (decided)"] += bool(flips)
                    counts[per]["running undecided"] += bool(undecided)
                    kinds[per].update({("more", *k): n for k, n in extra.items()})
                    kinds[per].update({("fewer", *k): n for k, n in lost.items()})
                    if beyond:
                        print(f"{case}: undecided where the design's margin is beyond the spacing {beyond}")
                    if extra or lost or flips or undecided:
                        line = f"more {sorted(extra)} fewer {sorted(lost)} runs differ {flips} undecided {undecided}"
                        line += f" | not explained {differing} explained {explained}"
                        print(f"{case}: {line}", flush=True)
    for per in pers:
        print(f"{per} a lobe: " + ", ".join(f"{k} {v}" for k, v in counts[per].items()))
        for k, v in sorted(kinds[per].items()):
            print(f"    {v:3d} x {k[0]}: {k[1]} on the {k[2]}, {k[3]}{', tip corner' if k[4] else ''}")


if __name__ == "__main__":
    main(*sys.argv[1:2])

"""Contact ratios, lengths, points of infinite slip and defects from 80-300 points a lobe (issue 21 items 1 and 3, README).

Each rotor sample's male and female, its outline (0.01 um chord) as points evenly spaced at 80, 150 and 300
a lobe (phase 0.37 of a spacing: the corners fall between the points), exact and with 1 and 2 um of scatter
along the normals (seeds 1 and 2), read back as ``--male-points`` / ``--female-points``. Printed per case:
each flank's transverse contact ratio against the design's with the stated
``transverse_contact_ratio_accuracy`` ("OUT" where the departure exceeds it), working lengths 10 % off,
defects and points of infinite slip that differ from the design's; then per density the counts, and the
largest departure over the stated accuracy.

Run by hand: ``python benchmarks/bench_moderate_densities.py [out.json]`` (about 3 minutes of CPU; the README's
figures: 270 inputs, none refused).
"""

from __future__ import annotations

import json
import sys
import tomllib
from collections import Counter
from pathlib import Path

import numpy as np

from rotorcad.design import rotor_design
from rotorcad.errors import DesignError
from rotorcad.rotor_build import PairSpec, analyse_pair, build_pair, pair_spec

SAMPLES = Path(__file__).resolve().parents[1] / "samples"
NAMES = [p.stem for p in sorted(SAMPLES.glob("*.toml")) if "profile" in tomllib.loads(p.read_text())]
FLANKS = ("driving", "sealing")


def _scan(ring: np.ndarray, count: int, phase: float) -> np.ndarray:
    """``count`` points evenly spaced along the closed ring, the first ``phase`` of a spacing past its first point."""
    closed = np.vstack([ring, ring[:1]])
    u = np.concatenate([[0.0], np.cumsum(np.hypot(*np.diff(closed, axis=0).T))])
    v = (np.arange(count) + phase) * u[-1] / count
    return np.column_stack([np.interp(v, u, closed[:, 0]), np.interp(v, u, closed[:, 1])])


def _pattern(lobe: np.ndarray, teeth: int) -> np.ndarray:
    """One lobe (root to root) turned round the rotor ``teeth`` times."""
    turns = 2 * np.pi * np.arange(teeth) / teeth
    c, s = np.cos(turns), np.sin(turns)
    x, y = lobe[:-1, 0], lobe[:-1, 1]
    return np.column_stack([(np.outer(c, x) - np.outer(s, y)).ravel(), (np.outer(s, x) + np.outer(c, y)).ravel()])


def _defects(summary: dict) -> list[tuple]:
    return sorted((d["kind"], d["rotor"], d["flank_role"], d["tip_corner"]) for d in summary["defects"])


def main(out: str | None = None) -> None:
    rows = []
    for name in NAMES:
        spec = pair_spec(rotor_design(tomllib.loads((SAMPLES / f"{name}.toml").read_text()), SAMPLES))
        rotors = build_pair(spec)
        design = analyse_pair(rotors, spec.speed_rpm)[1]
        for side, lobe, teeth in (
            ("male", rotors.male_lobe(), spec.pair.male_teeth),
            ("female", rotors.female_lobe(), spec.pair.female_teeth),
        ):
            ring = _pattern(np.vstack([s.resampled(1e-5).points for s in lobe.segments]), teeth)
            for per in (80, 150, 300):
                for sigma, seed in ((0.0, 0), (1e-3, 1), (1e-3, 2), (2e-3, 1), (2e-3, 2)):
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
                    except DesignError as err:
                        print(f"{case}: refused ({err.sentence()[:80]})")
                        continue
                    got = analyse_pair(given, spec.speed_rpm)[1]
                    row = {"name": name, "side": side, "per": per, "sigma": sigma, "seed": seed}
                    notes = []
                    for flank in FLANKS:
                        g, w = got["flanks"][flank], design["flanks"][flank]
                        err = abs(g["transverse_contact_ratio"] - w["transverse_contact_ratio"])
                        row[flank] = (err, g["transverse_contact_ratio_accuracy"])
                        if err > g["transverse_contact_ratio_accuracy"]:
                            notes.append(f"OUT {flank} {g['transverse_contact_ratio']:.3f}/{w['transverse_contact_ratio']:.3f}")
                        if abs(g["working_length"] - w["working_length"]) > 0.1 * w["working_length"] + 1.0:
                            notes.append(f"{flank} working {g['working_length']:.2f}/{w['working_length']:.2f} mm")
                    row["defects"] = _defects(got) == _defects(design)
                    row["slips"] = Counter((s["rotor"], s["flank"]) for s in got["slip_singularities"]) == Counter(
                        (s["rotor"], s["flank"]) for s in design["slip_singularities"]
                    )
                    notes += [] if row["defects"] else ["defects differ"]
                    notes += [] if row["slips"] else ["points of infinite slip differ"]
                    rows.append(row)
                    print(f"{case}: " + ("; ".join(notes) or "as the design"), flush=True)
    print(f"{len(rows)} inputs")
    for per in (80, 150, 300):
        mine = [r for r in rows if r["per"] == per]
        worst = max(e / a for r in mine for e, a in (r["driving"], r["sealing"]) if a > 0)
        print(
            f"{per} a lobe: {len(mine)} inputs, defects differ {sum(not r['defects'] for r in mine)}, points of infinite "
            f"slip differ {sum(not r['slips'] for r in mine)}, largest ratio departure {worst:.2f} of the stated accuracy"
        )
    if out:
        Path(out).write_text(json.dumps(rows, indent=1))


if __name__ == "__main__":
    main(*sys.argv[1:2])

"""The blow-hole of a given male against the design's, over forms, densities and seeds (issue 21 item 3).

Each sample's male (every rotor sample, and the arc-flank male of tests/independent_pairs.py, cut by its
rack, whose reference is its own points at 1500 a lobe) given as points: its own CSV as ``rotor
--male-csv`` writes it (1 um chord) with normal scatter ``sigma`` added to each coordinate (seeds), and
points evenly spaced along the outline at 150 / 300 / 600 a lobe (a CMM's scan, :func:`scan` of
tests/independent_pairs.py), exact at phases 0, 0.37 and 0.8 of a spacing and at phase 0.37 with the
scatter (seeds). Printed per read: the blow-hole (mm²) and its departure from the reference (%), the
uncertainty U the points state, whether they resolve it, where a male tip rounding's circles placed the apex
(:mod:`rotorcad.meshing.rounding_apex`) their radii, their own bound and why it does not hold
(``apex_rounding_check``), and at the end, per sample and in all: the reads resolved within 1 % (of a closed
meshline: within :data:`CLOSED_FLOOR`), resolved with the reference outside U, and with the reference outside U
at all. The reference is the design's blow-hole from its exact curves, which the points did not produce.

Run by hand: ``python benchmarks/bench_rounding_apex.py [samples] [seeds] [sigma] [densities]``, e.g.
``python benchmarks/bench_rounding_apex.py all 0-7 1e-3 150,300,600`` (about 10 min CPU, 410 reads),
``python benchmarks/bench_rounding_apex.py n_rack_5_6,rinder_deix_5_6 0-7 1e-3 csv`` for the CSV alone.
"""

from __future__ import annotations

import sys
import time
import tomllib
from collections import Counter
from pathlib import Path

import numpy as np

from rotorcad.design import rotor_design
from rotorcad.rotor_build import PairSpec, analyse_pair, build_pair, pair_spec
from rotorcad.rotor_pair import RotorPair

ROOT = Path(__file__).resolve().parents[1]
SAMPLES = ROOT / "samples"
sys.path.insert(0, str(ROOT / "tests"))
from independent_pairs import arc_flank_5_6, cut_rotor, patterned, resample, scan  # noqa: E402

EXACT_PHASES = (0.0, 0.37, 0.8)
"""Where the first of exact evenly spaced points falls, in spacings past the lobe's start."""

CLOSED_FLOOR = 1e-3
"""mm²: the blow-hole "within 1 %" of a closed meshline's 0 (Krigar's, Lysholm's), as tests/test_verdict_invariance.py."""

SCATTER_PHASE = 0.37
"""The phase of the evenly spaced points that get the scatter."""


def _exterior(polygon) -> np.ndarray:
    pts = np.asarray(polygon.exterior.coords)[:-1]
    area = 0.5 * np.sum(pts[:, 0] * np.roll(pts[:, 1], -1) - np.roll(pts[:, 0], -1) * pts[:, 1])
    return pts if area > 0 else pts[::-1]


def _seeds(text: str) -> list[int]:
    if "-" in text:
        lo, hi = text.split("-")
        return list(range(int(lo), int(hi) + 1))
    return [int(s) for s in text.split(",")]


def _sample(name: str) -> tuple[RotorPair, float, float, np.ndarray, np.ndarray | None]:
    """The pair, speed (rpm), reference blow-hole (mm²), the male's whole outline and its CSV points (None: no design)."""
    if name == "arc_flank_5_6":
        rack = arc_flank_5_6()
        male = cut_rotor(rack, "male")
        pair = RotorPair(rack.male_teeth, rack.female_teeth, rack.center_distance, **rack.radii(), lead=300.0, length=150.0)
        lobe_length = float(np.hypot(*np.diff(np.vstack([male, male[:1]]), axis=0).T).sum()) / rack.male_teeth
        given = build_pair(PairSpec(pair, "male-points", {}, resample(male, lobe_length / 1500), None, 3000.0, 0.0))
        return pair, 3000.0, analyse_pair(given, 3000.0)[1]["blow_hole_area"], male, None
    spec = pair_spec(rotor_design(tomllib.loads((SAMPLES / f"{name}.toml").read_text()), SAMPLES))
    rotors = build_pair(spec)
    analysis, design = analyse_pair(rotors, spec.speed_rpm)
    lobe = np.vstack([seg.resampled(1e-5).points for seg in rotors.male_lobe().segments])  # exact, 0.01 um chord
    ring = patterned(lobe, spec.pair.male_teeth)
    return spec.pair, spec.speed_rpm, design["blow_hole_area"], ring, _exterior(analysis.sections[0])


def _forms(pair: RotorPair, ring: np.ndarray, csv: np.ndarray | None, seeds: list[int], sigma: float, densities: list[str]):
    """Yield (form, points) for every form read."""
    for density in densities:
        if density == "csv":
            for seed in seeds if csv is not None else []:
                yield f"csv s{seed}", csv + np.random.default_rng(seed).normal(0.0, sigma, csv.shape)
            continue
        count = int(density) * pair.male_teeth
        for phase in EXACT_PHASES:
            yield f"{density} exact p{phase}", scan(ring, count, phase)
        base = scan(ring, count, SCATTER_PHASE)
        for seed in seeds:
            yield f"{density} s{seed}", base + np.random.default_rng(seed).normal(0.0, sigma, base.shape)


def main(argv: list[str]) -> None:
    names = argv[0] if argv else "n_rack_5_6,rinder_deix_5_6"
    seeds = _seeds(argv[1]) if len(argv) > 1 else list(range(8))
    sigma = float(argv[2]) if len(argv) > 2 else 1e-3
    densities = (argv[3] if len(argv) > 3 else "csv,150,300,600").split(",")
    if names == "all":
        samples = [p.stem for p in sorted(SAMPLES.glob("*.toml")) if "profile" in tomllib.loads(p.read_text())]
        samples.append("arc_flank_5_6")
    else:
        samples = names.split(",")
    print(f"{'sample':16s} {'form':15s} area mm²  reference change   uncertainty resolved cpu s  rounding, flank (mm), bound")
    counts: dict[str, Counter] = {}
    for name in samples:
        pair, speed, want, ring, csv = _sample(name)
        tally = counts.setdefault(name, Counter())
        for form, points in _forms(pair, ring, csv, seeds, sigma, densities):
            start = time.process_time()
            given, summary = analyse_pair(build_pair(PairSpec(pair, "male-points", {}, points, None, speed, 0.0)), speed)
            cpu = time.process_time() - start
            got, spread, resolved = summary["blow_hole_area"], summary["blow_hole_uncertainty"], summary["blow_hole_resolved"]
            change = 100.0 * (got / want - 1.0) if want > 1e-9 else float("nan")
            outside = abs(got - want) > spread
            tally["reads"] += 1
            tally["resolved"] += bool(resolved)
            within = abs(got - want) <= (0.01 * want if want > 1e-9 else CLOSED_FLOOR)
            tally["resolved within 1 %"] += bool(resolved and within)
            tally["resolved outside U"] += bool(resolved and outside)
            tally["reference outside U"] += bool(outside)
            model = getattr(given, "apex_rounding", None)
            circles = ""
            if model is not None:
                check = getattr(given, "apex_rounding_check", None)
                circles = f"{model.radius:.4f}, {model.body.name.lower()} {model.flank_radius:.4f}, "
                circles += f"{given.apex_rounding_uncertainty:.4f} {'holds' if check is None else '(' + check + ')'}"
            print(
                f"{name:16s} {form:15s} {got:8.4f} {want:8.4f} {change:+8.2f} % {spread:10.4f} "
                f"{resolved!s:8s} {cpu:5.1f}  {circles}",
                flush=True,
            )
    total = sum(counts.values(), Counter())
    print("\nsample            reads resolved  within 1 %  resolved outside U  reference outside U")
    for name, tally in [*counts.items(), ("all", total)]:
        print(
            f"{name:16s} {tally['reads']:6d} {tally['resolved']:8d} {tally['resolved within 1 %']:11d} "
            f"{tally['resolved outside U']:19d} {tally['reference outside U']:20d}"
        )


if __name__ == "__main__":
    main(sys.argv[1:])

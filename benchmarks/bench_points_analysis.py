"""CPU time of the analyses from measured points (issue 26): build the pair from one rotor's points, then its summary.

Each rotor sample (not the gears), male and female: its 1 um-chord outline (what ``rotorcad rotor SAMPLE
--male-csv F`` / ``--female-csv F`` write), resampled evenly along the closed outline at 80, 300 and 600
points a lobe (start phases 0.1, 0.37 and 0.324 of a spacing, so corners fall between points), exact and
with 1 um of normal scatter (seed 1), rounded to 1 nm as a CSV holds them; 108 inputs in all. Each input
is read as ``--male-points`` / ``--female-points`` (``build_pair``) and analysed (``analyse_pair``, the
JSON summary); the CPU seconds (``time.process_time``, this process) of the two together are printed per
input, then the total. The CPU time, not the wall time: the machine is shared.

Run by hand from the repository's root: ``python benchmarks/bench_points_analysis.py [--samples a,b]
[--per 80,300,600] [--json OUT]`` (about a minute of CPU on an idle machine); ``--json`` also writes every
summary (and the CPU per input), to compare the results of two versions of the library input by input.
"""

from __future__ import annotations

import argparse
import json
import time
import tomllib
import warnings
from pathlib import Path

import numpy as np

from rotorcad.design import rotor_design
from rotorcad.errors import DesignError
from rotorcad.roles import Side
from rotorcad.rotor_build import PairSpec, analyse_pair, build_pair, pair_spec

SAMPLES = Path(__file__).resolve().parents[1] / "samples"
NAMES = [p.stem for p in sorted(SAMPLES.glob("*.toml")) if "profile" in tomllib.loads(p.read_text())]
PHASES = {80: 0.1, 300: 0.37, 600: 0.324}
"""Start phase (in spacings) of the scan at each density (points a lobe)."""
SCATTER = (0.0, 1e-3)
"""Normal scatter of the points, mm (seed 1)."""


def scan(ring: np.ndarray, count: int, phase: float, noise: float = 0.0, seed: int = 1) -> np.ndarray:
    """``count`` points evenly spaced along the closed outline (n, 2), ``phase`` of a spacing past its first point.

    With ``noise`` (mm) each point moves along its normal (the chord between its neighbours turned) by a
    normal deviate of that standard deviation.
    """
    closed = np.vstack([ring, ring[:1]])
    u = np.concatenate([[0.0], np.cumsum(np.hypot(*np.diff(closed, axis=0).T))])
    v = (np.arange(count) + phase) * u[-1] / count
    pts = np.column_stack([np.interp(v, u, closed[:, 0]), np.interp(v, u, closed[:, 1])])
    if noise:
        t = np.gradient(pts, axis=0)
        n = np.column_stack([-t[:, 1], t[:, 0]]) / np.hypot(*t.T)[:, None]
        pts = pts + n * np.random.default_rng(seed).normal(0.0, noise, len(pts))[:, None]
    return np.round(pts, 6)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--samples", default=",".join(NAMES), help="comma-separated sample names (samples/NAME.toml)")
    parser.add_argument("--per", default="80,300,600", help="points a lobe, comma-separated (80, 300 or 600)")
    parser.add_argument("--json", default=None, help="write the summaries and CPU seconds per input here")
    args = parser.parse_args()
    summaries, cpu = {}, {}
    warnings.simplefilter("ignore")  # the inputs' notes (InputNote) are not what is measured
    for name in args.samples.split(","):
        spec = pair_spec(rotor_design(tomllib.loads((SAMPLES / f"{name}.toml").read_text()), SAMPLES))
        rotors = build_pair(spec)
        for side in (Side.MALE, Side.FEMALE):
            teeth = spec.pair.male_teeth if side is Side.MALE else spec.pair.female_teeth
            ring = np.asarray(rotors.section(side, 1e-3, exact_tip=True).exterior.coords)[:-1]
            for per in (int(p) for p in args.per.split(",")):
                for sigma in SCATTER:
                    pts = scan(ring, per * teeth, PHASES[per], sigma)
                    key = f"{name} {side} {per} a lobe {sigma * 1e3:g} um"
                    start = time.process_time()
                    try:
                        given = build_pair(PairSpec(spec.pair, f"{side}-points", {}, pts, None, spec.speed_rpm, 0.0))
                        summaries[key] = analyse_pair(given, spec.speed_rpm)[1]
                    except DesignError as err:
                        summaries[key] = {"refused": err.sentence()}
                    cpu[key] = time.process_time() - start
                    print(f"{cpu[key]:7.2f} s CPU  {key}", flush=True)
    print(f"{sum(cpu.values()):7.2f} s CPU  total, {len(cpu)} inputs")
    if args.json:
        Path(args.json).write_text(json.dumps({"summaries": summaries, "cpu": cpu}, default=str, sort_keys=True))


if __name__ == "__main__":
    main()

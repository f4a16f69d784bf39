"""`rack_deviation` where the mate's generation nearly stalls (issue 22: measured on the contact zone only).

The finding (a new user's session): `rotorcad hob --female-points` of the N-rack female, 300-600 points a
lobe with 2 um of scatter, printed `rack_deviation` 1.2-1.9 mm beside `rack_accuracy` 10-20 um, with no word.
It was measured where the male's 0.67 mm sealing tip rounding touches the female flank: the male's contact
moves a few hundredths of the rack's travel there (its generation nearly stalls over some 6 mm of rack), and
the male's rack, re-derived from the male generated from the points, moves along itself by the generated
profile's curvature error; or where the male, cut where it loops, has a corner whose path the female's rack
piece is (the pair's male tip corner path). Both are left out now (hob.rack.MATE_STALL and the pair's
corner-path pieces).

Reference: the truth is 0 (the mate is generated from the given rotor's rack, Wu & Chi sec. 2: either rotor
gives that rack back), the bound max(2 um, the stated accuracy) as in test_hob_points_samples; the inputs
are the design's own female outline (its exact curves) sampled as a CMM does, with seeded normal scatter.
"""

from __future__ import annotations

import functools
import tomllib
from pathlib import Path

import numpy as np
import pytest
from independent_pairs import patterned, scan

from hob.rack import rack_deviation
from rotorcad.design import rotor_design
from rotorcad.inverse_rack import MEASURED_JOIN_GAP, MEASURED_MIN_TURN
from rotorcad.measured.cusp_paths import with_exact_cusp_paths
from rotorcad.measured.pairs import pair_from_rotor_points
from rotorcad.rotor_build import build_pair, pair_spec

SAMPLE = Path(__file__).resolve().parents[1] / "samples" / "n_rack_5_6.toml"
MEASURED = {"min_turn": MEASURED_MIN_TURN, "join_gap": MEASURED_JOIN_GAP, "cut_loops": True}  # as `rotorcad hob`


@functools.cache
def _female() -> tuple[object, np.ndarray]:
    spec = pair_spec(rotor_design(tomllib.loads(SAMPLE.read_text()), SAMPLE.parent))
    lobe = np.vstack([s.resampled(1e-5).points for s in build_pair(spec).female_lobe().segments])
    return spec.pair, patterned(lobe, spec.pair.female_teeth)


def _scan(per_lobe: int, phase: float, sigma: float, seed: int) -> np.ndarray:
    pair, ring = _female()
    points = scan(ring, per_lobe * pair.female_teeth, phase)
    d = np.roll(points, -1, axis=0) - np.roll(points, 1, axis=0)
    normal = np.column_stack([d[:, 1], -d[:, 0]]) / np.hypot(d[:, 0], d[:, 1])[:, None]
    return points + np.random.default_rng(seed).normal(0.0, sigma, len(points))[:, None] * normal


@pytest.mark.parametrize(("per_lobe", "phase", "seed"), [(300, 0.0, 1), (600, 0.37, 1)])
def test_rack_deviation_where_the_male_tip_rounding_stalls(per_lobe, phase, seed):
    pair, _ = _female()
    rotors = with_exact_cusp_paths(pair_from_rotor_points(pair, _scan(per_lobe, phase, 2e-3, seed), "female"))
    assert rack_deviation(rotors, **MEASURED) <= max(2e-3, rotors.accuracy), rotors.accuracy

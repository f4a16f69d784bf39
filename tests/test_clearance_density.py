"""The contact zone does not move with the density and the scatter of the points (issue 22, newuser4).

The zone is where the male's flank really touches the female, a property of the pair: its share of
the contact line (``contact_zone_share``) read from CMM-like points at 80, 300 and 2000 points a lobe
with 0, 1 and 2 um of scatter lies within :data:`SHARE_TOLERANCE` of the share read from the cut
outlines themselves (before: 0.71 dense, 0.60 from 80 points a lobe on the 4/6 pair; 0.59 and 0.46
on the 5/6 pair), as ``rotorcad clearance`` reads them (the closer fit, tip roundings).

Pairs rotorcad did not make (tests/independent_pairs.py, shapely booleans only): the 4/6 trapezoid
rack pair (sharp tips cut back by the flats, lands) and the 5/6 pair of a rack with one straight and
one circular-arc flank (the male undercut). Reference: the share of the dense cut outlines (0.01 mm
chords), which sparse points cannot move beyond the tolerance; the contact zone's clearance itself is
checked against the brute-force closest approach in test_clearance_zones.py and test_clearance_sparse.py.
"""

from __future__ import annotations

import functools

import numpy as np
import pytest
from independent_pairs import arc_flank_5_6, cut_rotor, resample, trapezoid_4_6

from rotorcad.clearance import MeshingClearance, pair_quality
from rotorcad.measured.fit import close_smoothing
from rotorcad.rotor_pair import RotorPair
from rotorcad.rotor_points import lobe_pieces

SHARE_TOLERANCE = 0.05
"""The contact zone's share of the contact line from points against the dense outlines' (measured: 0.02 on
the 4/6 pair, 0.045 on the 5/6 pair, whose dense cut outline reads 0.651 and every resampling 0.686-0.696)."""


@functools.cache
def outlines(name: str):
    pair = trapezoid_4_6() if name == "4/6" else arc_flank_5_6()
    return pair, cut_rotor(pair, "male"), cut_rotor(pair, "female")


def per_lobe(ring: np.ndarray, teeth: int, points: int) -> float:
    """Spacing that gives ``points`` points a lobe on the closed ring."""
    return float(np.hypot(*np.diff(np.vstack([ring, ring[:1]]), axis=0).T).sum()) / teeth / points


@functools.cache
def summary(name: str, points: int, noise: float) -> dict:
    """The figures of the pair ``name`` from ``points`` a lobe with ``noise`` (mm) of scatter (0: the cut outlines)."""
    rack_pair, male, female = outlines(name)
    z1, z2 = rack_pair.male_teeth, rack_pair.female_teeth
    if points:
        male = resample(male, per_lobe(male, z1, points), noise, seed=points + 1)
        female = resample(female, per_lobe(female, z2, points), noise, seed=points + 2)
    pair = RotorPair(z1, z2, 100.0, **rack_pair.radii(), lead=1e5, length=1e5, strict=False)
    mc = MeshingClearance(
        pair,
        lobe_pieces(pair, male, "male", close_smoothing, roundings=True),
        lobe_pieces(pair, female, "female", close_smoothing, roundings=True),
        contact="as-given",
        **pair_quality(male, female, (z1, z2)),
    )
    return mc.summary()


def share(name: str, points: int, noise: float) -> float:
    """``contact_zone_share`` of :func:`summary`."""
    return summary(name, points, noise)["contact_zone_share"]


@pytest.mark.parametrize("name", ["4/6", "5/6"])
@pytest.mark.parametrize("points", [80, 300, 2000])
@pytest.mark.parametrize("noise", [0.0, 1e-3, 2e-3])
def test_the_contact_zone_share_does_not_move_with_the_points(name, points, noise):
    dense = share(name, 0, 0.0)
    assert 0.5 < dense < 0.9  # both pairs leave the female root below the sharp male tip untouched
    assert abs(share(name, points, noise) - dense) <= SHARE_TOLERANCE


@pytest.mark.parametrize("name", ["4/6", "5/6"])
@pytest.mark.parametrize("points", [80, 300, 2000])
@pytest.mark.parametrize("noise", [0.0, 1e-3, 2e-3])
def test_the_gaps_from_points_are_within_their_stated_accuracy_of_the_dense_ones(name, points, noise):
    # the gap of the female root below the sharp male tip (about 0.1 mm at its largest, 0 where it meets
    # the contact zone): the dense cut outlines' values are the brute-force closest approach's within 2 um
    # (test_clearance_zones::test_each_zone_reads_the_brute_force_closest_approach); from points, within
    # gap_accuracy of them (the contact zone's accuracy and the triangle a sharp corner between two points
    # may lie in)
    dense, read = summary(name, 0, 0.0), summary(name, points, noise)
    assert dense["max_gap"] > 0.05
    for key in ("max_gap", "min_gap"):
        assert abs(read[key] - dense[key]) <= read["gap_accuracy"] + 2e-3, key

"""The clearance of a pair whose axes lie farther apart than designed, read as given (issue 22, a new user's finding).

References, not produced by the code under test (closed forms): the rack-involute sample (Rinder's
rack-involute profile, straight rack flanks) with its female thinned by a uniform 30 um normal
clearance (``rotor --clearance 0.03``), its axes moved apart by da = 0.2 mm. Moving one rotor by da
changes every distance between the two by at most da, so no clearance on the contact zone can exceed
30 um + da (the user read 432.6 um from the dense exact outline). Along a straight normal-rack flank
at the normal flank angle alpha_n the normal clearance grows by da sin(alpha_n), the smallest on the
sealing flank: tan(alpha_n) = tan(26 deg) cos(beta), beta the helix angle at the pitch cylinder
(tan(beta) = 2 pi r1w / h, Rinder eq. 1): 30 + 200 sin(18.13 deg) = 92.2 um.
"""

from __future__ import annotations

import tomllib
from pathlib import Path

import numpy as np
import pytest

from rotorcad.clearance import MeshingClearance, pair_quality
from rotorcad.clearance_design import ClearanceDistribution, corrected_female
from rotorcad.design import rotor_design
from rotorcad.measured.fit import close_smoothing
from rotorcad.rotor_build import build_pair, pair_spec
from rotorcad.rotor_pair import RotorPair
from rotorcad.rotor_points import lobe_pieces

SAMPLES = Path(__file__).resolve().parents[1] / "samples"
APART = 0.2  # mm
CLEARANCE = 0.03  # mm


@pytest.fixture(scope="module")
def apart():
    """The rack-involute pair's outlines (0.1 um chords) read as given at the centre distance 116.2 mm for 116."""
    rotors = build_pair(pair_spec(rotor_design(tomllib.loads((SAMPLES / "rack_involute_5_6.toml").read_text()), SAMPLES)))
    male = rotors.male_outline(1e-4).points
    female = corrected_female(rotors, ClearanceDistribution.uniform(CLEARANCE), 1e-4)[:-1]
    rm, rf = np.hypot(*male.T), np.hypot(*female.T)
    p = rotors.pair
    pair = RotorPair(5, 6, p.center_distance + APART, rm.max(), rm.min(), rf.max(), rf.min(), p.lead, p.length, strict=False)
    mc = MeshingClearance(
        pair,
        lobe_pieces(pair, male, "male", close_smoothing, roundings=True),
        lobe_pieces(pair, female, "female", close_smoothing, roundings=True),
        contact="as-given",
        **pair_quality(male, female, (5, 6)),
    )
    return p, mc.summary()


def test_no_clearance_exceeds_the_design_plus_the_axes_moved_apart(apart):
    _, s = apart
    assert s["max_normal_clearance"] <= CLEARANCE + APART + s["accuracy"]  # 230.0 um for 230 (user: 432.6)


def test_the_smallest_clearance_is_the_sealing_flank_moved_apart(apart):
    p, s = apart
    beta = np.arctan(2 * np.pi * p.male_pitch_radius / p.lead)
    alpha_n = np.arctan(np.tan(np.radians(26.0)) * np.cos(beta))  # the sample's sealing_angle_deg, normal section
    assert abs(s["min_normal_clearance"] - (CLEARANCE + APART * np.sin(alpha_n))) <= s["accuracy"]  # 92.45 for 92.2 um

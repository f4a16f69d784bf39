"""The clearance of a pair's own exact conjugate outlines read as CMM points: zero on the contact zone.

The N-rack sample's male and female as ``rotor samples/n_rack_5_6.toml --male-csv --female-csv`` write
them (1 um chords), resampled evenly along each outline (``independent_pairs.resample``), read as
``rotorcad clearance`` reads points. The truth on the contact zone is zero: the outlines are conjugate
(both cut by one rack); it is checked at the worst rows against the brute-force closest approach of the
two outlines over 1500 mesh positions (``independent_pairs.closest_approach``), which the clearance code
did not make. ``benchmarks/bench_clearance_accuracy.py 4 300,80 N-exact`` prints the same seed by seed.
"""

from __future__ import annotations

import numpy as np
import pytest
from independent_pairs import closest_approach, resample
from test_clearance_lands import rotors_of

from rotorcad.clearance import MeshingClearance, pair_quality
from rotorcad.measured.fit import close_smoothing
from rotorcad.roles import Side
from rotorcad.rotor_pair import RotorPair
from rotorcad.rotor_points import lobe_pieces


@pytest.fixture(scope="module")
def outlines():
    """The N-rack sample's rotors and their outlines written at 1 um chords (counter-clockwise rings)."""
    from rotorcad.cli.rotor import _exterior

    rotors = rotors_of("n_rack_5_6")
    male = _exterior(rotors.section(Side.MALE, 1e-3, exact_tip=True))
    female = _exterior(rotors.section(Side.FEMALE, 1e-3, exact_tip=True))
    return rotors, male, female


def per_lobe(ring: np.ndarray, teeth: int, points: int) -> float:
    return float(np.hypot(*np.diff(np.vstack([ring, ring[:1]]), axis=0).T).sum()) / teeth / points


def read(outlines, points: int) -> MeshingClearance:
    """The clearance read from the outlines resampled at ``points`` a lobe (exact: on the 1 um chords)."""
    rotors, male, female = outlines
    m = resample(male, per_lobe(male, 5, points))
    f = resample(female, per_lobe(female, 6, points))
    rm, rf = np.hypot(*m.T), np.hypot(*f.T)
    p = rotors.pair
    pair = RotorPair(5, 6, p.center_distance, rm.max(), rm.min(), rf.max(), rf.min(), p.lead, p.length, strict=False)
    return MeshingClearance(  # as rotorcad clearance reads the points (its default contact alignment)
        pair,
        lobe_pieces(pair, m, "male", close_smoothing, roundings=True),
        lobe_pieces(pair, f, "female", close_smoothing, roundings=True),
        **pair_quality(m, f, (5, 6)),
    )


def worst_rows(outlines, mc: MeshingClearance, count: int = 6) -> tuple[np.ndarray, np.ndarray]:
    """The ``count`` contact-zone rows of largest |clearance| (mm) and their brute-force truth (mm)."""
    rotors, male, female = outlines
    d = mc.distribution()
    on = np.flatnonzero(mc.contact_zone)
    pick = on[np.argsort(-np.abs(mc.clearance[on]))[:count]]
    at = np.column_stack([d["female_x"], d["female_y"]])[pick]
    # reference: the transverse closest approach of the male outline to the female outline's point
    # nearest each fitted one (1500 mesh positions), turned into the normal section by the flank's
    # stretch (clearance_design: delta_t = delta_n sqrt(t_y^2 / cos^2 beta + t_x^2))
    near = female[np.argmin(np.hypot(*(female[None, :, :] - at[:, None, :]).transpose(2, 0, 1)), axis=1)]
    tan = mc.female_rack.tangents[pick]
    stretch = np.sqrt(tan[:, 1] ** 2 / np.cos(mc.helix_angle) ** 2 + tan[:, 0] ** 2)
    truth = closest_approach(rotors.pair, near, male, positions=1500, window_deg=70.0) / stretch
    return mc.clearance[pick], truth


def test_conjugate_outlines_at_600_points_a_lobe_are_within_the_stated_accuracy(outlines):
    mc = read(outlines, 600)
    c, truth = worst_rows(outlines, mc)
    assert np.all(truth < 1.5e-3)  # the brute force: conjugate within the chords' 1 um
    assert np.abs(c - truth).max() <= mc.accuracy  # measured 2.2 um, stated 3.1


def test_conjugate_outlines_at_300_points_a_lobe_are_within_the_stated_accuracy(outlines):
    # 300 exact points a lobe read 0.3 um of scatter; the smoothing spline's curvature error at the
    # female's sealing tip circle's end (r 43.5 mm), where its generation stalls, folds the male's rack
    # facing it (a swallowtail 21 um wide): its first leg's tail, inside the male, read 12.4 um for 4.2 um
    # stated before the rack was cut back to its envelope (clearance_normals.trim_folds)
    mc = read(outlines, 300)
    c, truth = worst_rows(outlines, mc)
    assert np.all(truth < 1.5e-3)  # the brute force: conjugate within the chords' 1 um
    assert np.abs(c - truth).max() <= mc.accuracy  # measured 2.4 um, stated 4.2

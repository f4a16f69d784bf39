"""The jamming test from the male rotation (rotorcad.meshing.rotation_turns) against closed forms.

References: the contact instant of a straight rack flank, solved in closed form for a normal turned by a small
angle (the rotation's accuracy); the extremes of an analytic rotation along a meshline (where its derivative
vanishes); and the identity the test rests on, d|P - C|/dt = c P_y / |P - C|, integrated along the design's exact
meshline (its samples' distance from C against the integral of the right side over the male rotation).
"""

from __future__ import annotations

import tomllib
import warnings
from pathlib import Path

import numpy as np
import pytest

from rotorcad.design import rotor_design
from rotorcad.meshing.rotation_turns import rotation_accuracy, rotation_turns
from rotorcad.rotor_build import analyse_pair, build_pair, pair_spec

SAMPLES = Path(__file__).resolve().parents[1] / "samples"
PITCH_X = 116.0 * 5 / 11  # the 5/6 pairs' pitch point C (mm)


def _contact_instant(rack_point: np.ndarray, angle: float, pitch_x: float) -> float:
    """The male rotation (rad) at which a rack point with its normal at ``angle`` touches: the rack, moved by
    pitch_x t along y, puts that normal through C = (pitch_x, 0)."""
    return ((rack_point[0] - pitch_x) * np.tan(angle) - rack_point[1]) / pitch_x


@pytest.mark.parametrize("where", [(60.0, 13.0), (64.7, 24.3), (55.0, -8.0), (45.0, 10.0)])
def test_rotation_accuracy_is_the_contact_instant_of_a_turned_normal(where):
    # a straight rack flank through P at the instant its normal passes C; turning its normal by d_phi moves that instant
    # by delta t (closed form above): the accuracy is |delta t| to first order
    p = np.array(where)
    angle = np.arctan2(p[1], p[0] - PITCH_X)  # the normal along P - C at t = 0
    d_phi = 1e-6
    moved = abs(_contact_instant(p, angle + d_phi, PITCH_X) - _contact_instant(p, angle, PITCH_X))
    assert rotation_accuracy(p[None, :], PITCH_X, d_phi)[0] == pytest.approx(moved, rel=1e-4)


@pytest.mark.parametrize("amplitude", [0.5, 2.0])
def test_rotation_turns_are_the_analytic_extremes_beyond_the_accuracy(amplitude):
    # t(s) = s + A sin(s) over 0..4 pi: monotone for A = 0.5; for A = 2 it turns back between its maxima at 2 pi / 3 +
    # 2 pi n and its minima at 4 pi / 3 + 2 pi n (where 1 + 2 cos(s) = 0), by 2 sqrt(3) - 2 pi / 3 each time. With the
    # accuracy e the same at every sample, a turn back by more than 2 e, and on again, is reported as the pair of its
    # ends, one by less is none
    s = np.linspace(0.0, 4.0 * np.pi, 4001)
    p = np.array([PITCH_X + 3.0, 4.0])  # |P - C|^2 = 25, c |P_x - c| = 3 c: e = d_phi 25 / (3 c)
    points = np.tile(p, (len(s), 1))
    a = np.arccos(-1.0 / 2.0)  # A = 2: maxima at a + 2 pi n, minima at 2 pi - a + 2 pi n
    top, low = a, 2.0 * np.pi - a
    drop = (top + 2.0 * np.sin(top)) - (low + 2.0 * np.sin(low))  # the turn back of A = 2, rad
    t = s + amplitude * np.sin(s)
    for share, found in ((0.9, amplitude > 1.0), (1.1, False)):
        d_phi = share * drop / 2.0 * (3.0 * PITCH_X) / 25.0  # 2 e = share x the turn back
        # accuracy / resolution = d_phi; the rack points a turn apart lie c x 1.37 rad = 62 mm apart, beyond it
        got = rotation_turns(t, points, PITCH_X, d_phi * 1.0, 1.0, 0.0)
        if not found:
            assert len(got) == 0, s[got]
            continue
        want = np.column_stack([top + 2 * np.pi * np.arange(2), low + 2 * np.pi * np.arange(2)])  # (maximum, minimum)
        assert got.shape == want.shape and np.allclose(s[got], want, atol=s[1] - s[0]), (s[got], want)


def test_a_turn_back_within_the_accuracy_is_found_by_the_tolerance_alone():
    # the band of the undecided jamming (rotorcad.meshing.undecided.possible_rows): t(s) = s + 2 sin(s) turns back by
    # 2 sqrt(3) - 2 pi / 3 (closed form, as above); with the profile's accuracy allowing 1.1 of that there is no
    # excursion, and with the accuracy 0 (the tangent's tolerance alone, the design's test, allowing 0.9 of it) the
    # analytic extremes are the excursions, two normals at one sample (distance 0) bounded by the tolerance too
    s = np.linspace(0.0, 4.0 * np.pi, 4001)
    points = np.tile([PITCH_X + 3.0, 4.0], (len(s), 1))
    a = np.arccos(-0.5)
    drop = (a + 2.0 * np.sin(a)) - (2.0 * np.pi - a + 2.0 * np.sin(2.0 * np.pi - a))
    t = s + 2.0 * np.sin(s)
    per_rad = (3.0 * PITCH_X) / 25.0 / 2.0  # d_phi for a turn back of 1 rad between two ends
    assert len(rotation_turns(t, points, PITCH_X, 1.1 * drop * per_rad, 1.0, 0.0)) == 0
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # 0 / 0 of one normal's own distance is no bound, and no warning
        got = rotation_turns(t, points, PITCH_X, 0.0, 1.0, 0.9 * drop * per_rad)
    want = np.column_stack([a + 2 * np.pi * np.arange(2), 2.0 * np.pi - a + 2 * np.pi * np.arange(2)])
    assert got.shape == want.shape and np.allclose(s[got], want, atol=s[1] - s[0]), (s[got], want)


def test_a_single_turn_back_is_no_excursion():
    # t(s) = sin(s) over 0..pi: one maximum at pi / 2 and no rise after it; the meshline turns back on itself there
    # (the normal's test judges a reversal), so no excursion whatever the accuracy
    s = np.linspace(0.0, np.pi, 2001)
    points = np.tile([PITCH_X + 3.0, 4.0], (len(s), 1))
    assert len(rotation_turns(np.sin(s), points, PITCH_X, 1e-9, 1.0, 0.0)) == 0
    assert len(rotation_turns(np.sin(s) + np.where(s > 2.5, 4.0 * (s - 2.5), 0.0), points, PITCH_X, 1e-9, 1.0, 0.0)) == 1


def test_distance_from_c_changes_with_the_rotation_as_stated():
    # the identity the test rests on, on the rack-involute design's exact meshline: along each piece that keeps 0.25 mm or
    # more from C (its flanks and tip corners' paths; the root fillets pass within 3 um of C, where c P_y / |P - C| is
    # singular), the change of |P - C| equals the integral of c P_y / |P - C| over the male rotation (trapezoid rule:
    # 1e-13 mm on the straight flanks, 6 um on a tip corner's path, a quarter of that on twice the samples)
    spec = pair_spec(rotor_design(tomllib.loads((SAMPLES / "rack_involute_5_6.toml").read_text()), SAMPLES))
    analysis = analyse_pair(build_pair(spec), spec.speed_rpm)[0]
    c = analysis.rotors.pair.male_pitch_radius
    checked = 0
    for piece in analysis.pieces:
        pts, t = piece.points, piece.t
        r = np.hypot(pts[:, 0] - c, pts[:, 1])
        if len(t) < 50 or np.ptp(r) < 1.0 or r.min() < 0.25:
            continue
        rate = c * pts[:, 1] / r
        integral = np.concatenate([[0.0], np.cumsum(0.5 * (rate[1:] + rate[:-1]) * np.diff(t))])
        assert np.abs((r - r[0]) - integral).max() <= 1e-5 * np.ptp(r), piece.name
        checked += 1
    assert checked == 4

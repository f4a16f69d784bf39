"""hob.straight_flank on racks built here in closed form: the flank angle theta(s) is given, the points are its
integral (tangent (sin theta, cos theta), the flank angle measured from the normal to the pitch line).

References: the angle each curve was built with (a straight flank's one angle; a curved flank's least angle), not
anything hob.straight_flank computes.
"""

from __future__ import annotations

import numpy as np
import pytest

from hob.straight_flank import straight_flank_angles

SCATTER, SPACING = 2e-3, 0.28  # mm: 2 um along the normals, 300 points a lobe (as tests/test_hob_points_samples.py)
KINK = 2e-3  # rad: a sharp corner (rotorcad.inverse_rack.MEASURED_MIN_TURN's order)


def rack_from_angles(theta_deg: np.ndarray, step: float = 0.01) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Points (n, 2), unit tangents (n, 2) and arc length (n,) of the curve whose flank angle is ``theta_deg``."""
    t = np.radians(theta_deg)
    tan = np.column_stack([np.sin(t), np.cos(t)])
    pts = np.vstack([[0.0, 0.0], np.cumsum(0.5 * (tan[1:] + tan[:-1]) * step, axis=0)])
    return pts, tan, np.arange(len(t)) * step


def read(theta_deg: np.ndarray, scatter: float = SCATTER) -> np.ndarray:
    pts, tan, along = rack_from_angles(theta_deg)
    angles = np.degrees(np.arctan2(np.abs(tan[:, 0]), np.abs(tan[:, 1])))
    return straight_flank_angles(pts, tan, angles, np.ones(len(pts), dtype=bool), along, scatter, SPACING, KINK)


def test_a_straight_flank_reads_its_line_not_its_wobble_nor_its_bent_end():
    # A straight flank at 18.127 deg over 8 mm, its fitted angle wobbling by 0.18 deg (1 um of position over a 2 mm
    # wavelength, as the rack-involute's from 2 um of scatter) and bent by 1.2 deg over its last 0.6 mm before a
    # sharp corner (the fit's end effect). Pointwise the least angle reads 1.2 deg low; the flank's line is the one
    # the curve was built with.
    s = np.arange(0.0, 8.0, 0.01)
    wobble = np.degrees(2 * np.pi * 1e-3 / 2.0) * np.sin(2 * np.pi * s / 2.0)
    bend = np.where(s > 7.4, -1.2 * ((s - 7.4) / 0.6) ** 2, 0.0)
    theta = 18.127 + wobble + bend
    assert theta.min() < 18.127 - 1.0
    assert read(theta).min() == pytest.approx(18.127, abs=0.02)


def test_exact_points_keep_their_pointwise_angles():
    s = np.arange(0.0, 8.0, 0.01)
    theta = 18.127 + 0.2 * np.sin(2 * np.pi * s / 2.0)
    assert np.array_equal(read(theta, scatter=0.0), np.degrees(np.arctan2(*np.abs(rack_from_angles(theta)[1]).T)))


@pytest.mark.parametrize(
    "theta",
    [
        12.0 + 0.25 * np.arange(0.0, 8.0, 0.01),  # a gently curved flank, its least angle at one end
        12.0 + 0.5 * ((np.arange(0.0, 8.0, 0.01) - 4.0) / 4.0) ** 2,  # its least angle in the middle
    ],
    ids=["monotone", "middle"],
)
def test_a_curved_flank_keeps_its_least_angle(theta):
    # within 2 sigma of a line over its whole length (the sagitta of 0.5 deg over 8 mm is 8.7 um: not all of it),
    # but its angle moves: the least angle is the curve's own, 12.0 deg
    assert read(theta).min() == pytest.approx(12.0, abs=1e-9)

"""Trapezoidal-hob (basic-rack) cutting simulation against the analytic envelope."""

from __future__ import annotations

import numpy as np
import pytest
import shapely

from hob.cutting import simulate_cutting
from rotorcad.gear import InvoluteGear

DEG = np.pi / 180


@pytest.mark.parametrize(
    "z,x,rho",
    [
        (6, 1.0, 0.38),
        (6, -0.5, 0.38),
        (8, -0.3, 0.0),
        (11, 0.0, 0.38),
        (17, 0.2, 0.0),
        (25, -0.5, 0.38),
        (40, 1.0, 0.2),
        (60, 0.0, 0.0),
    ],
)
def test_simulated_gear_agrees_with_the_analytic_envelope(z, x, rho):
    # Issue 4: shapely's blank minus the union of tool positions agrees with the analytic envelope
    # (involute + trochoid from rotorcad's engine) within the requested scallop height.
    scallop = 1e-2
    res = simulate_cutting(InvoluteGear(z, 2.0, 20 * DEG, 0.0, x, tip_radius_factor=rho), scallop)
    assert res.max_deviation <= scallop
    assert res.flank_deviation <= scallop
    # cutting only removes material: the simulated tooth contains the exact one (to the scallop)
    assert res.envelope.difference(res.tooth.buffer(1e-9)).area < 1e-6 * res.envelope.area


def test_one_micrometre_on_the_paper_gear_and_the_undercut_point():
    # Kollek & Osinski's z = 11 (alpha0 = 20 deg, x = 0: undercut). The simulated boundary passes
    # through the analytic undercut point, where involute and trochoid meet.
    g = InvoluteGear(11, 2.0, 20 * DEG)
    assert g.undercut
    res = simulate_cutting(g, 1e-3)
    assert res.max_deviation <= 1e-3
    segs = g.tooth_profile().segments
    inv = [s for s in segs if s.name == "involute"][-1]
    corner = inv.points[-1]  # involute end = fillet start = undercut point P'
    assert res.tooth.exterior.distance(shapely.Point(corner)) <= 1e-3
    assert np.hypot(*corner) == pytest.approx(g.form_radius)

"""Trapezoidal hob and rack tools in the cutting simulation; the contact-ratio nomogram."""

from __future__ import annotations

import numpy as np
import pytest
import shapely

from hob.cutting import simulate_cutting
from hob.nomogram import contact_ratio_grid
from hob.tools import RackTool, TrapezoidalHob
from hob.undercut import real_limit_shift
from rotorcad.errors import DesignError
from rotorcad.gear import GearPair, InvoluteGear

DEG = np.pi / 180


def test_default_hob_cuts_the_basic_rack_gear():
    # A trapezoidal hob with the ISO 53 tool values cuts the analytic envelope of the basic rack.
    g = InvoluteGear(20, 2.0, 20 * DEG, 0.0, 0.2)
    n = simulate_cutting(g, 1e-2).positions  # a custom tool is not refined: take the basic rack's count
    res = simulate_cutting(g, 1e-2, n, tool=TrapezoidalHob(2.0, 20 * DEG, 1.25, 0.38))
    assert res.max_deviation <= 1e-2


def test_protuberance_relieves_the_root_and_chamfer_leaves_material():
    g = InvoluteGear(20, 2.0, 20 * DEG, 0.0, 0.2)
    base = simulate_cutting(g, 2e-3)
    n = base.positions
    relieved = simulate_cutting(g, 2e-3, n, TrapezoidalHob(2.0, protuberance=0.02, protuberance_height=0.35))
    chamfered = simulate_cutting(g, 2e-3, n, TrapezoidalHob(2.0, tip_radius=0.0, tip_chamfer=0.2))
    assert relieved.tooth.area < base.tooth.area - 0.05  # protuberance cuts under the form circle
    assert base.tooth.area < chamfered.tooth.area  # a chamfer cuts less of the root fillet than r = 0.38 m
    # above the relief the tooth is untouched: same thickness half a module above the pitch circle
    ring = shapely.Point(0, 0).buffer(g.pitch_radius + 1.0, quad_segs=4096).exterior
    assert ring.intersection(relieved.tooth).length == pytest.approx(ring.intersection(base.tooth).length, abs=5e-3)


@pytest.mark.parametrize("shift", [0.0, 0.4])
def test_rack_tool_from_points_cuts_the_same_gear_as_the_hob(shift):
    # A rack tool given by points (the hob's tooth read off as a rack-frame polyline) cuts the same
    # gear as the hob itself, and both agree with the analytic envelope of the sharp basic rack
    # (ISO 21771 gear with that shift). With a profile shift x both tools stand x m further out: the
    # shift is in modules for both (m = 2 mm here, so a shift taken as mm would be off by 0.4 mm).
    hob = TrapezoidalHob(2.0, tip_radius=0.0)
    g = InvoluteGear(25, 2.0, 20 * DEG, 0.0, shift, tip_radius_factor=0.0)
    polygon = hob.tooth(g.pitch_radius, 0.0, g.nominal_tip_radius + 4.0)
    n = (len(polygon) - 2) // 2  # [half, 2 top corners, mirrored half]
    chain = np.vstack([polygon[:n][::-1], polygon[n + 2 :][::-1]])  # flank top -> tip -> other flank top
    tool = RackTool(np.column_stack([chain[:, 1], chain[:, 0] - g.pitch_radius]), np.pi * 2.0)
    positions = simulate_cutting(g, 5e-3).positions
    by_hob = simulate_cutting(g, 5e-3, positions, hob)
    by_points = simulate_cutting(g, 5e-3, positions, tool)
    assert by_points.tooth.symmetric_difference(by_hob.tooth).area < 1e-9
    assert by_points.max_deviation <= 5e-3


def test_hob_lead_angle_and_bad_values():
    # gamma0 = asin(starts m0 / d_m0), d_m0 = d_a0 - 2 h_a0 m0
    h = TrapezoidalHob(3.0, starts=2, diameter=100.0)
    assert h.lead_angle == pytest.approx(np.arcsin(2 * 3.0 / (100.0 - 2 * 1.25 * 3.0)))
    with pytest.raises(DesignError):
        TrapezoidalHob(3.0, tip_radius=0.3, tip_chamfer=0.2)
    with pytest.raises(DesignError):
        TrapezoidalHob(3.0, starts=0)


def test_nomogram_falls_below_the_real_limit():
    # Kollek & Osinski Fig. 4: for x < x''_g the contact ratio drops steeply (undercut shortens the
    # path of contact); above it, the ordinary tip-circle contact ratio (ISO 21771) holds.
    xr = real_limit_shift(11, 1.0, 20 * DEG, 1.0)
    xs = np.array([xr - 0.1, xr - 0.05, xr + 0.05])
    eps = contact_ratio_grid(11, 20 * DEG, xs, np.array([1.0]))[0]
    assert eps[0] < eps[1] < eps[2] + 0.05
    assert eps[1] - eps[0] > 0.05
    g = InvoluteGear(11, 1.0, 20 * DEG, 0.0, float(xs[2]))
    assert eps[2] == pytest.approx(GearPair(g, g).contact_ratio)

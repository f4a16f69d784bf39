"""Trapezoidal-hob (basic-rack) cutting simulation against the analytic envelope."""

from __future__ import annotations

import numpy as np
import pytest
import shapely

from hob.cutting import simulate_cutting, simulated_form_radius
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


@pytest.mark.parametrize(
    "m,x,rho,beta,scallop",
    [
        (25.0, 0.0, 0.38, 0.0, 1e-3),  # issue 15: `cut --teeth 3 --module 25` was refused (GEOS lost the tooth)
        (1.0, 0.0, 0.0, 0.0, 1e-2),  # sharp tool corner: a neck of 0.03 mm between the two undercuts
        (2.0, 0.5, 0.38, 15.0, 1e-2),  # helical, pointed tip
        (3.3, 0.0, 0.38, 0.0, 1e-2),
    ],
)
def test_three_teeth_are_cut_as_the_envelope_engine_generates_them(m, x, rho, beta, scallop):
    # z = 3: the tool rolls through more than 400 degrees, so many positions are turned far; the
    # brute-force cut (shapely) must still agree with the analytic involute + trochoid of
    # rotorcad.gear (the envelope engine) to the scallop height, and find its undercut point P'.
    g = InvoluteGear(3, m, 20 * DEG, beta * DEG, x, tip_radius_factor=rho)
    res = simulate_cutting(g, scallop)
    assert res.max_deviation <= scallop
    assert res.flank_deviation <= scallop
    assert res.envelope.difference(res.tooth.buffer(1e-9 * m)).area < 1e-6 * res.envelope.area
    assert abs(res.tooth.area - res.envelope.area) < 1e-2 * res.envelope.area
    assert g.undercut
    # P' from the simulated boundary, within a few scallops of the analytic one (the fillet
    # crosses the involute at a shallow angle; the involute is taken from halfway up the flank,
    # since for z = 3 the pitch circle can lie on the fillet)
    assert simulated_form_radius(g, res, 1.5 * scallop) == pytest.approx(g.form_radius, abs=3 * scallop)


def test_tool_positions_are_valid_polygons():
    # The cause of the z = 3 failures: the pieces of the tool tooth share their end points, and a
    # repeated point a rounding error off became a spike once the tooth was turned to a position.
    from hob.cutting import _tool_tooth_polygon
    from rotorcad.geometry import rotate

    for z, m, x in ((3, 25.0, 0.0), (3, 1.0, 0.0), (4, 3.3, 0.0), (7, 25.0, 0.5)):
        g = InvoluteGear(z, m, 20 * DEG, 0.0, x)
        tooth = _tool_tooth_polygon(g, 1e-3)
        pt, r = np.pi * g.transverse_module, g.pitch_radius
        ts = np.linspace(-3.8, 3.8, 1501)
        polys = shapely.polygons([rotate(tooth + np.array([0.0, pt * j + r * t]), -t) for t in ts for j in (-1, 0)])
        assert shapely.is_valid(polys).all(), (z, m, x)

"""Involute gears against ISO 21771 / DIN 3960 closed forms computed here, not by rotorcad."""

from __future__ import annotations

import pickle

import numpy as np
import pytest
import shapely
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy.optimize import brentq

from rotorcad.curves import PointPath, chord_error
from rotorcad.errors import DesignError
from rotorcad.gear import GearPair, InvoluteGear, mate_shift
from rotorcad.kinematics import gear_mesh

DEG = np.pi / 180


def iso_inv(a):
    return np.tan(a) - a


def iso_inv_inverse(v):
    """Independent inverse involute for the tests: bracketing root finder."""
    return brentq(lambda a: np.tan(a) - a - v, 1e-9, np.pi / 2 - 1e-9, xtol=1e-15)


def iso_alpha_t(alpha_n, beta):
    return np.arctan(np.tan(alpha_n) / np.cos(beta))


@pytest.mark.parametrize("z,m,alpha,beta", [(30, 2.0, 20, 0), (17, 3.0, 20, 0), (40, 1.5, 25, 15), (23, 4.0, 14.5, 30)])
def test_base_and_pitch_radius(z, m, alpha, beta):
    # ISO 21771: d = z m_n / cos(beta), d_b = d cos(alpha_t).
    g = InvoluteGear(z, m, alpha * DEG, beta * DEG, tip_radius_factor=0.25)
    d = z * m / np.cos(beta * DEG)
    assert g.pitch_radius == pytest.approx(d / 2, rel=1e-15)
    assert g.base_radius == pytest.approx(d / 2 * np.cos(iso_alpha_t(alpha * DEG, beta * DEG)), rel=1e-15)


@pytest.mark.parametrize(
    "z,x,beta",
    [(30, 0.0, 0), (30, 0.5, 0), (25, -0.3, 0), (60, 0.9, 0), (17, 0.3, 0), (40, 0.2, 20), (20, 0.6, 35), (100, -0.5, 10)],
)
def test_tooth_thickness_at_the_pitch_circle(z, x, beta):
    # ISO 21771 eq. 2.27: s_t = m_t (pi/2 + 2 x tan(alpha_n)) (arc length, transverse).
    m, a = 2.5, 20 * DEG
    g = InvoluteGear(z, m, a, beta * DEG, x)
    assert g.form_radius < g.pitch_radius  # the pitch circle cuts the involute
    mt = m / np.cos(beta * DEG)
    assert g.tooth_thickness(g.pitch_radius) == pytest.approx(mt * (np.pi / 2 + 2 * x * np.tan(a)), abs=1e-9)


@pytest.mark.parametrize("z,x,beta", [(30, 0.0, 0), (18, 0.4, 0), (45, -0.2, 25)])
def test_tooth_thickness_at_any_radius(z, x, beta):
    # ISO 21771 eq. 2.33: s_yt = d_y (s_t / d + inv(alpha_t) - inv(alpha_yt)), cos(alpha_yt) = d_b / d_y.
    m, a = 3.0, 20 * DEG
    g = InvoluteGear(z, m, a, beta * DEG, x)
    at = iso_alpha_t(a, beta * DEG)
    mt = m / np.cos(beta * DEG)
    d = z * mt
    st_ = mt * (np.pi / 2 + 2 * x * np.tan(a))
    db = d * np.cos(at)
    for ry in np.linspace(g.form_radius + 1e-3, g.tip_radius, 9):
        ay = np.arccos(db / (2 * ry))
        expected = 2 * ry * (st_ / d + iso_inv(at) - iso_inv(ay))
        assert g.tooth_thickness(ry) == pytest.approx(expected, abs=1e-9)


def test_involute_segment_lies_on_the_involute():
    # Every sampled point of the generated flank lies on the involute of r_b (closed-form polar
    # angle), far inside 1e-6 mm.
    g = InvoluteGear(27, 2.0, 20 * DEG, 0.0, 0.25)
    rb = g.base_radius
    for seg in g.tooth_profile().segments:
        if seg.name != "involute":
            continue
        r = np.hypot(*seg.points.T)
        a = np.arccos(np.clip(rb / r, -1, 1))
        ang = np.abs(np.arctan2(seg.points[:, 1], seg.points[:, 0]))
        th = ang + (np.tan(a) - a)  # constant along one flank
        assert (r * np.abs(th - th[0])).max() < 1e-9


def test_root_circle_and_tip_circle():
    # r_f = r + (x - h_fP*) m and r_a = r + (h_aP* + x) m (no tip shortening).
    g = InvoluteGear(33, 2.0, 20 * DEG, 0.0, 0.2)
    for seg in g.tooth_profile().segments:
        r = np.hypot(*seg.points.T)
        if seg.name == "root arc":
            np.testing.assert_allclose(r, 33.0 + (0.2 - 1.25) * 2.0, atol=1e-12)
        if seg.name == "tip arc":
            np.testing.assert_allclose(r, 33.0 + (1.0 + 0.2) * 2.0, atol=1e-12)


@pytest.mark.parametrize("x,rho", [(0.0, 0.38), (0.4, 0.2), (-0.2, 0.38), (0.0, 0.0)])
def test_fillet_is_the_offset_trochoid_of_the_tool_tip_centre(x, rho):
    # Second method: the root fillet equals the path of the tool tip-arc centre offset by rho.
    g = InvoluteGear(40, 2.0, 20 * DEG, 0.0, x, tip_radius_factor=rho)
    fil = [s for s in g.tooth_profile().segments if s.name == "fillet"][-1]
    arc = g.tool["tip arc"].curve
    mesh = gear_mesh(g.pitch_radius)
    path = PointPath(arc.center, mesh.rack, mesh.male, -1.0, 1.0, offset=-arc.radius)
    t = g._generated["tip arc"].contact(fil.s).t
    np.testing.assert_allclose(fil.points, path.evaluate(t)[0], atol=1e-11)


def test_form_radius_without_undercut():
    # DIN 3960 (3.4.x): the tool's flank/fillet joint at height h_FfP = (h_a0* - rho*(1-sin a) - x) m
    # below the datum generates the form circle: r_Ff = sqrt(r_b^2 + (r sin a - h_FfP / sin a)^2).
    for z, x, rho in [(30, 0.0, 0.38), (20, 0.3, 0.25), (50, -0.2, 0.38)]:
        m, a = 2.0, 20 * DEG
        g = InvoluteGear(z, m, a, 0.0, x, tip_radius_factor=rho)
        assert not g.undercut
        r, rb = z * m / 2, z * m / 2 * np.cos(a)
        h = (1.25 - rho * (1 - np.sin(a)) - x) * m
        assert g.form_radius == pytest.approx(np.sqrt(rb**2 + (r * np.sin(a) - h / np.sin(a)) ** 2), abs=1e-10)


@pytest.mark.parametrize("alpha", [14.5, 20.0, 25.0])
def test_undercut_limit_sharp_rack(alpha):
    # Sharp rack of addendum 1 m: undercut below z_min = 2 / sin^2(alpha) (DIN 3960 / textbook).
    a = alpha * DEG
    zmin = 2 / np.sin(a) ** 2
    for z in range(6, 40):
        g = InvoluteGear(z, 1.0, a, 0.0, 0.0, dedendum=1.0, tip_radius_factor=0.0)
        assert g.undercut == (z < zmin - 1e-9), z


@pytest.mark.parametrize("z", [7, 10, 13, 17, 25])
@pytest.mark.parametrize("rho", [0.0, 0.25, 0.38])
def test_undercut_limit_shift_rounded_rack(z, rho):
    # Limit shift x_g = h_a0* - rho*(1 - sin a) - z sin^2(a) / 2 (issue 4 / DIN 3960).
    a = 20 * DEG
    xg = 1.25 - rho * (1 - np.sin(a)) - z * np.sin(a) ** 2 / 2
    assert InvoluteGear(z, 1.0, a, 0.0, xg - 1e-3, tip_radius_factor=rho).undercut
    assert not InvoluteGear(z, 1.0, a, 0.0, xg + 1e-3, tip_radius_factor=rho).undercut


def test_undercut_point_lies_on_involute_and_fillet():
    g = InvoluteGear(9, 2.0, 20 * DEG, 0.0, 0.0)
    assert g.undercut
    segs = g.tooth_profile().segments
    inv = [s for s in segs if s.name == "involute"][-1]
    fil = [s for s in segs if s.name == "fillet"][-1]
    np.testing.assert_allclose(inv.points[-1], fil.points[0], atol=1e-10)
    assert g.form_radius == pytest.approx(np.hypot(*inv.points[-1]), abs=1e-12)
    assert g.form_radius > g.base_radius


def test_working_pressure_angle_and_center_distance_from_shifts():
    # ISO 21771 eqs. 4.14/4.16, with the test's own inverse involute.
    for z1, z2, x1, x2, beta in [(17, 29, 0.3, -0.1, 0), (12, 40, 0.5, 0.2, 0), (20, 31, 0.4, 0.35, 15), (25, 25, -0.2, 0.0, 0)]:
        m, an = 2.0, 20 * DEG
        at = iso_alpha_t(an, beta * DEG)
        g1 = InvoluteGear(z1, m, an, beta * DEG, x1)
        g2 = InvoluteGear(z2, m, an, beta * DEG, x2)
        pair = GearPair(g1, g2)
        awt = iso_inv_inverse(iso_inv(at) + 2 * (x1 + x2) * np.tan(an) / (z1 + z2))
        a = (z1 + z2) * m / np.cos(beta * DEG) / 2
        assert pair.working_pressure_angle == pytest.approx(awt, abs=1e-13)
        assert pair.working_center_distance == pytest.approx(a * np.cos(at) / np.cos(awt), abs=1e-10)
        # the generated flanks agree: zero backlash at that centre distance
        assert abs(pair.backlash) < 1e-8


def test_working_pressure_angle_from_a_given_center_distance():
    g1 = InvoluteGear(20, 2.0, 20 * DEG)
    a_w = 51.0
    x2 = mate_shift(g1, 30, a_w)
    pair = GearPair(g1, InvoluteGear(30, 2.0, 20 * DEG, 0.0, x2), a_w)
    assert pair.working_pressure_angle == pytest.approx(np.arccos(50.0 * np.cos(20 * DEG) / 51.0), abs=1e-14)
    assert abs(pair.backlash) < 1e-8  # round trip: shift from the distance, backlash from the flanks
    # a larger distance with the same teeth shows as backlash: j = 2 a_w (inv a_w' - inv a_w) tan... > 0
    wider = GearPair(g1, InvoluteGear(30, 2.0, 20 * DEG, 0.0, x2), 51.2)
    assert wider.backlash > 0.1
    with pytest.raises(DesignError):
        GearPair(g1, InvoluteGear(30, 2.0, 20 * DEG, 0.0, x2), 50.8)


@pytest.mark.parametrize("z1,z2,x1,x2", [(20, 30, 0.0, 0.0), (17, 29, 0.3, -0.1), (40, 60, 0.2, 0.1), (25, 80, 0.0, 0.0)])
def test_transverse_contact_ratio(z1, z2, x1, x2):
    # ISO 21771 eq. 5.4: eps_a = (sqrt(da1^2-db1^2) + sqrt(da2^2-db2^2) - 2 a_w sin a_w) / (2 p_b).
    m, a = 2.0, 20 * DEG
    pair = GearPair(InvoluteGear(z1, m, a, 0, x1), InvoluteGear(z2, m, a, 0, x2))
    assert not pair.tip_interference
    aw = iso_inv_inverse(iso_inv(a) + 2 * (x1 + x2) * np.tan(a) / (z1 + z2))
    a_w = (z1 + z2) * m / 2 * np.cos(a) / np.cos(aw)
    ra1, ra2 = z1 * m / 2 + (1 + x1) * m, z2 * m / 2 + (1 + x2) * m
    rb1, rb2 = z1 * m / 2 * np.cos(a), z2 * m / 2 * np.cos(a)
    eps = (np.sqrt(ra1**2 - rb1**2) + np.sqrt(ra2**2 - rb2**2) - a_w * np.sin(aw)) / (np.pi * m * np.cos(a))
    assert pair.contact_ratio == pytest.approx(eps, abs=1e-12)


def test_undercut_shortens_the_contact_ratio():
    # An undercut pinion loses the part of the path of contact below its undercut point.
    a = 20 * DEG
    plain = GearPair(InvoluteGear(11, 1.0, a, 0, 0.4), InvoluteGear(11, 1.0, a, 0, 0.4))
    cut = GearPair(InvoluteGear(11, 1.0, a, 0, -0.1), InvoluteGear(11, 1.0, a, 0, -0.1))
    assert cut.gear.undercut and not plain.gear.undercut
    assert cut.tip_interference


def test_chord_tolerance_of_the_outline():
    # Every sampled segment deviates from its exact curve by at most the tolerance (0.1 um),
    # probed between samples on the exact curve.
    g = InvoluteGear(30, 2.0, 20 * DEG, tolerance=1e-4)
    for seg in g.tooth_profile().segments:
        assert chord_error(seg.curve, seg.s, probes=12) <= 1.0001e-4


def iso_involute_point(r_y, psi_p, alpha_t, r_b, side):
    """ISO 21771 involute flank of the tooth centred on +x: the point at radius r_y is
    r_y (cos psi_y, side sin psi_y) with psi_y = psi_p + inv(alpha_t) - inv(alpha_y),
    cos(alpha_y) = r_b / r_y (eq. 2.33: s_yt = 2 r_y psi_y), psi_p = s_t / d the half angle on
    the pitch circle."""
    a_y = np.arccos(r_b / r_y)
    psi = psi_p + iso_inv(alpha_t) - iso_inv(a_y)
    return r_y[..., None] * np.stack([np.cos(psi), side * np.sin(psi)], axis=-1)


@pytest.mark.parametrize(
    "z,m,beta,x,rho,tol",
    [
        (30, 2.0, 0, 0.0, 0.38, 1e-4),  # the benchmark gear
        (8, 2.0, 0, 0.0, 0.38, 1e-4),  # undercut
        (12, 2.0, 0, 0.4, 0.38, 1e-4),  # shifted
        (25, 2.0, 15, 0.1, 0.38, 1e-4),  # helical
        (100, 2.0, 0, 0.0, 0.38, 1e-4),
        (6, 1.0, 0, 1.0, 0.38, 1e-4),  # pointed tip
        (30, 1.0, 30, 0.0, 0.25, 1e-3),  # coarse
        (40, 5.0, 0, 0.3, 0.2, 1e-6),  # fine
    ],
)
def test_involute_samples_on_the_iso_involute_and_chords_within_tolerance(z, m, beta, x, rho, tol):
    # Reference: the involute of ISO 21771 in closed form, computed here (not by rotorcad). Every
    # sample of both involute flanks lies on it (1e-9 mm, far inside the 0.1 um tolerance), and the
    # chord between two neighbouring samples deviates from it by at most the tolerance: the
    # sagitta, measured at 24 radii between the two samples' radii on the ISO curve.
    a = 20 * DEG
    g = InvoluteGear(z, m, a, beta * DEG, x, tip_radius_factor=rho, tolerance=tol)
    at = iso_alpha_t(a, beta * DEG)
    mt = m / np.cos(beta * DEG)
    r = z * mt / 2
    rb = r * np.cos(at)
    psi_p = mt * (np.pi / 2 + 2 * x * np.tan(a)) / (2 * r)  # ISO 21771 eq. 2.27: s_t / d
    flanks = [s for s in g.tooth_profile().segments if s.name == "involute"]
    assert len(flanks) == 2
    for seg in flanks:
        p = seg.points
        side = np.sign(p[:, 1].mean())
        r_y = np.hypot(*p.T)
        assert np.abs(p - iso_involute_point(r_y, psi_p, at, rb, side)).max() < 1e-9
        # chord sagitta against the ISO curve between consecutive samples
        frac = (np.arange(1, 25) / 25)[None, :]
        probes = iso_involute_point(r_y[:-1, None] + (r_y[1:] - r_y[:-1])[:, None] * frac, psi_p, at, rb, side)
        d = (p[1:] - p[:-1])[:, None, :]
        off = probes - p[:-1, None, :]
        sagitta = np.abs(d[..., 0] * off[..., 1] - d[..., 1] * off[..., 0]) / np.hypot(d[..., 0], d[..., 1])
        assert sagitta.max() <= tol
        assert sagitta.max() > 0.5 * tol  # sampled to the tolerance, not far finer


@pytest.mark.parametrize(
    "kwargs",
    [
        {"teeth": 30, "module": 2.0, "tolerance": 1e-4},
        {"teeth": 9, "module": 2.0, "tip_radius_factor": 0.0, "tolerance": 1e-4},  # sharp tool, undercut
        {"teeth": 25, "module": 2.0, "helix_angle": 50 * DEG, "tolerance": 1e-5},  # tip arc of the tool an ellipse
        # the tool's tip-arc centre beyond the pitch line: the fillet has an inflection
        {"teeth": 13, "module": 10.0, "pressure_angle": 5 * DEG, "helix_angle": 15 * DEG, "shift": 1.3, "tolerance": 5e-4},
        {"teeth": 8, "module": 1.0, "pressure_angle": 14.5 * DEG, "shift": 1.46, "tolerance": 1e-6},
        {"teeth": 9, "module": 10.0, "pressure_angle": 5 * DEG, "shift": 1.14, "tip_radius_factor": 0.2, "tolerance": 0.16},
    ],
)
def test_every_piece_is_sampled_within_the_chord_tolerance(kwargs):
    # The samples are placed from the pieces' curvature in one step; the chord error is measured
    # on the envelope engine's exact curves (rotorcad.envelope, not the closed form that placed
    # them), at 24 points between neighbouring samples.
    g = InvoluteGear(**{"pressure_angle": 20 * DEG, **kwargs})
    for seg in g.tooth_profile().segments:
        np.testing.assert_allclose(seg.points, seg.curve.evaluate(seg.s)[0], rtol=0, atol=1e-12 * g.module)
        assert chord_error(seg.curve, seg.s, probes=24) <= g.tolerance


def test_outline_survives_pickling():
    # the tooth's segment objects are made on first use; the outline still pickles (worker processes)
    g = InvoluteGear(20, 2.0, 20 * DEG, 0.0, 0.3)
    outline = pickle.loads(pickle.dumps(g.outline()))
    np.testing.assert_array_equal(outline.points, g.outline().points)
    assert [s.name for s in outline.segments[:7]] == [s.name for s in g.tooth_profile().segments]


@settings(max_examples=40, deadline=None)
@given(
    z=st.integers(min_value=6, max_value=200),
    x=st.floats(min_value=-0.5, max_value=1.0),
    rho=st.sampled_from([0.0, 0.2, 0.38]),
    beta=st.sampled_from([0.0, 12.0, 30.0]),
)
def test_every_outline_is_a_valid_polygon(z, x, rho, beta):
    # Issue 2: valid polygons for z in 6..200 and x in -0.5..1.0; counter-clockwise, z-fold,
    # between root and tip circles.
    g = InvoluteGear(z, 1.0, 20 * DEG, beta * DEG, x, tip_radius_factor=rho, tolerance=1e-3)
    pts = g.outline().points
    poly = shapely.Polygon(pts)
    assert poly.is_valid and shapely.LinearRing(pts).is_simple
    assert poly.exterior.is_ccw
    r = np.hypot(*pts.T)
    assert r.min() >= g.root_radius - 1e-9 and r.max() <= g.nominal_tip_radius + 1e-9
    turned = shapely.affinity.rotate(poly, 360.0 / z, origin=(0, 0))
    assert poly.symmetric_difference(turned).area < 1e-6 * poly.area


def test_pointed_tooth_is_reported_and_closed():
    g = InvoluteGear(6, 1.0, 20 * DEG, 0.0, 1.0)
    assert g.tip_pointed
    assert g.tip_radius < g.nominal_tip_radius
    assert g.tooth_thickness(g.tip_radius) == pytest.approx(0.0, abs=1e-9)


@pytest.mark.parametrize(
    "kwargs,param",
    [
        ({"teeth": 2, "module": 1.0}, "teeth"),
        ({"teeth": 20, "module": 0.0}, "module"),
        ({"teeth": 20, "module": 1.0, "pressure_angle": 0.0}, "pressure_angle"),
        ({"teeth": 20, "module": 1.0, "pressure_angle": 45 * DEG}, "pressure_angle"),
        ({"teeth": 20, "module": 1.0, "tip_radius_factor": 0.6}, "tip_radius_factor"),
        ({"teeth": 4, "module": 1.0, "shift": -1.5}, "shift"),
        ({"teeth": 20, "module": float("nan")}, "module"),
    ],
)
def test_bad_gear_input_names_the_parameter(kwargs, param):
    with pytest.raises(DesignError) as err:
        InvoluteGear(**kwargs)
    assert err.value.param == param

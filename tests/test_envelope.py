"""The envelope (gearing) engine against closed forms and round trips."""

from __future__ import annotations

import numpy as np
import pytest

from rotorcad.curves import Arc, Involute, Line, PointPath, Spline
from rotorcad.envelope import Generated, conjugate, from_rack_frame, rack_frame
from rotorcad.geometry import perp_cw
from rotorcad.kinematics import Rotation, Translation, gear_mesh, pitch_point, rotor_mesh

DEG = np.pi / 180


def involute_distance(points, rb):
    """Distance of points from the involute family of base radius rb, by the closed form:
    the involute point at the same radius has polar angle theta0 +- inv(acos(rb / r))."""
    r = np.hypot(*points.T)
    a = np.arccos(np.clip(rb / r, -1, 1))
    ang = np.arctan2(points[:, 1], points[:, 0])
    th0 = np.unwrap(ang + (np.tan(a) - a))
    return r * np.abs(th0 - np.median(th0))


def rack_flank(alpha, r_w, half_length=4.0):
    """A straight rack flank through the pitch point C = (r_w, 0) at pressure angle alpha,
    travelled so that its outward normal faces the gear."""
    d = np.array([np.cos(alpha), -np.sin(alpha)])
    c = np.array([r_w, 0.0])
    return Line(tuple(c - half_length * d), tuple(c + half_length * d))


@pytest.mark.parametrize("alpha_deg", [14.5, 20.0, 25.0, 30.0])
def test_straight_rack_flank_generates_the_involute(alpha_deg):
    # Issue 2: a straight rack flank of angle alpha generates an involute of base radius
    # r_w cos(alpha); every point within 1e-6 mm (here to ~1e-12).
    r_w, alpha = 30.0, alpha_deg * DEG
    mesh = gear_mesh(r_w)
    # contacts from C up to just short of the interference point T1 (|CT1| = r_w sin(alpha));
    # a flank point at distance l from C touches at l / tan(alpha) along the line of action
    half = 0.95 * r_w * np.sin(alpha) * np.tan(alpha)
    flank = rack_flank(alpha, r_w, half_length=half)
    c = conjugate(*flank.evaluate(np.linspace(0, 2 * half, 400)), mesh.rack, mesh.male)
    rb = r_w * np.cos(alpha)
    # keep the proper branch (contacts between the interference point and beyond C)
    assert np.all(np.hypot(*c.points.T) >= rb - 1e-12)
    assert involute_distance(c.points, rb).max() < 1e-6
    # the meshline is the straight line through C at alpha to the rack's normal
    d = c.meshline - np.array([r_w, 0.0])
    assert np.abs(d[:, 0] * np.cos(alpha) - d[:, 1] * np.sin(alpha)).max() < 1e-12


def test_rack_point_generates_its_trochoid():
    # A corner of the rack (zero-radius arc: one point, a fan of normals) generates the path
    # whose radius satisfies |p|^2 = a_x^2 + (a_y + r_w t)^2 (issue 2).
    r_w, a = 25.0, np.array([23.1, 0.8])
    mesh = gear_mesh(r_w)
    corner = Arc(tuple(a), 0.0, np.pi, 1.5 * np.pi - 20 * DEG)
    c = conjugate(*corner.evaluate(np.linspace(corner.s0, corner.s1, 200)), mesh.rack, mesh.male)
    np.testing.assert_allclose(np.sum(c.points**2, axis=1), a[0] ** 2 + (a[1] + r_w * c.t) ** 2, rtol=1e-13)
    # and it coincides with the point path computed directly by kinematics
    path = PointPath(tuple(a), mesh.rack, mesh.male, 0.0, 1.0)
    np.testing.assert_allclose(c.points, path.evaluate(c.t)[0], atol=1e-12)


def test_rack_arc_generates_the_offset_trochoid():
    # Second method: the envelope of a tool tip arc (radius rho, centre K) equals the trochoid of
    # K offset by rho (Litvin, ch. 6, envelope of a circle family).
    r_w, k, rho = 20.0, np.array([18.4, 3.1]), 0.9
    mesh = gear_mesh(r_w)
    arc = Arc(tuple(k), rho, np.pi, 1.5 * np.pi - 20 * DEG)
    c = conjugate(*arc.evaluate(np.linspace(arc.s0, arc.s1, 300)), mesh.rack, mesh.male)
    path = PointPath(tuple(k), mesh.rack, mesh.male, 0.0, 1.0, offset=-rho)
    np.testing.assert_allclose(c.points, path.evaluate(c.t)[0], atol=1e-11)


def test_rack_rotor_rack_round_trip():
    # rack -> rotor -> rack returns the rack (issue 2), for a flank and a tip arc.
    mesh = gear_mesh(21.0)
    for curve in (rack_flank(20 * DEG, 21.0, 2.0), Arc((19.0, 1.7), 0.6, np.pi, 1.5 * np.pi - 20 * DEG)):
        gear_side = Generated(curve, mesh.rack, mesh.male)
        back = Generated(gear_side, mesh.male, mesh.rack)
        s = np.linspace(min(curve.s0, curve.s1), max(curve.s0, curve.s1), 101)[1:-1]
        p0, t0 = curve.evaluate(s)
        p2, t2 = back.evaluate(s)
        np.testing.assert_allclose(p2, p0, atol=1e-9)
        np.testing.assert_allclose(t2 * back.direction * curve.direction, t0 * 1.0, atol=1e-9)


@pytest.mark.parametrize(
    "curve",
    [
        Involute(28.190778623577252, -0.2, -1.0, 0.55, 0.25),  # upper involute flank, tip to root
        Arc((36.0, 0.0), 8.0, -0.9, 0.9),  # convex circular lobe, centre off the pitch circle
    ],
)
def test_rotor_rotor_round_trip(curve):
    # rotor -> conjugate rotor -> rotor returns the first rotor (issue 2).
    mesh = rotor_mesh(5, 6, 66.0)
    mate = Generated(curve, mesh.male, mesh.female)
    back = Generated(mate, mesh.female, mesh.male)
    s = np.linspace(curve.s0, curve.s1, 61)
    c = mate.contact(s)
    ok = c.in_contact
    assert ok.sum() > 10
    np.testing.assert_allclose(back.evaluate(s[ok])[0], curve.evaluate(s[ok])[0], atol=1e-9)


def test_sliding_velocity_is_omega_sum_times_cp():
    # Rinder eq. 3: v_g = +-CP (w1 + w2); the engine computes v_rel from the bodies' velocities.
    z1, z2, a = 4, 6, 100.0
    mesh = rotor_mesh(z1, z2, a)
    curve = Arc((45.0, 3.0), 9.0, -1.2, 1.2)
    c = conjugate(*curve.evaluate(np.linspace(-1.2, 1.2, 101)), mesh.male, mesh.female)
    ok = c.in_contact
    cp = np.hypot(*(c.meshline[ok] - mesh.pitch_point).T)
    w1, w2 = 1.0, z1 / z2
    np.testing.assert_allclose(c.sliding_speed[ok], (w1 + w2) * cp, rtol=1e-13, atol=1e-13)
    # and the relative velocity is tangent to both flanks (meshing condition n . v_rel = 0)
    assert np.abs(np.einsum("ij,ij->i", c.normal[ok], c.sliding[ok])).max() < 1e-10


def test_circle_centred_on_the_pitch_circle_is_the_degenerate_case():
    # Symmetric SRM (Rinder, Fig. 3): a circle centred on the male pitch circle meshes with the
    # same circle centred on the female pitch circle, every point at the one angle that brings
    # the centre to C.
    # At the arc's ends the normal is tangent to the pitch circle, where the general root is
    # ill-conditioned (2e-8 rad off before the degenerate case was restored for rotors).
    mesh = rotor_mesh(4, 6, 100.0)
    r1w, rho = mesh.pitch_radius_male, 12.0
    for angle in (0.3, 0.7, 2.0):
        k = r1w * np.array([np.cos(angle), np.sin(angle)])
        arc = Arc(tuple(k), rho, angle - np.pi / 2, angle + np.pi / 2)
        c = conjugate(*arc.evaluate(np.linspace(arc.s0, arc.s1, 2001)), mesh.male, mesh.female, arc_center=k)
        assert np.all(c.in_contact)
        np.testing.assert_allclose(c.t, -angle, atol=1e-14)
        k2 = mesh.female.to_body(np.array([[r1w, 0.0]]), -angle)[0]
        np.testing.assert_allclose(np.hypot(*(c.points - k2).T), rho, atol=1e-12)
        np.testing.assert_allclose(np.hypot(*(k2 - [100.0, 0.0])), mesh.pitch_radius_female, atol=1e-12)


def test_no_contact_is_reported_not_invented():
    mesh = gear_mesh(30.0)
    # rack normal parallel to the pitch line (a flank at 90 deg): never meets the pitch line
    flat = Line((30.0, -1.0), (31.0, -1.0))  # normal (0,-1) along the motion... parallel to V
    p, t = flat.evaluate(np.linspace(0, 1, 5))
    assert np.all(np.isnan(conjugate(p, t, mesh.rack, mesh.male).t))
    # rotor point whose normal passes outside the pitch circle: no contact
    p = np.array([[40.0, 0.0]])
    t = np.array([[1.0, 0.0]])  # normal (0,-1) at x = 40: the line x = 40 misses r_w = 30
    c = conjugate(p, t, mesh.male, mesh.female)
    assert not c.in_contact[0] and np.isnan(c.points).all()


def test_limits_pick_the_root_that_lies_on_the_body():
    # An involute flank has two roots; the far one puts the mate's point outside its body.
    z1 = z2 = 20
    mesh = rotor_mesh(z1, z2, 40.0)
    rb = 20.0 * np.cos(20 * DEG)
    flank = Involute(rb, 0.1, -1.0, 0.5, 0.2)  # upper flank travelled tip to root (CCW)
    pts, tan = flank.evaluate(np.linspace(0.5, 0.2, 30))
    a = conjugate(pts, tan, mesh.male, mesh.female, branch="A")
    b = conjugate(pts, tan, mesh.male, mesh.female, branch="B")
    r_a = np.hypot(*(a.points - [40.0, 0.0]).T)
    r_b = np.hypot(*(b.points - [40.0, 0.0]).T)
    lim = (17.5, 21.5)
    assert np.all((r_a > lim[0]) & (r_a < lim[1])) and not np.any((r_b > lim[0]) & (r_b < lim[1]))
    picked = conjugate(pts, tan, mesh.male, mesh.female, branch="B", limits=lim)
    np.testing.assert_allclose(picked.points, a.points, atol=1e-12)


def test_inverse_problem_rack_of_an_involute_is_straight():
    # The rack of an involute rotor is a straight line at alpha (inverse generation).
    r_w, alpha = 40.0, 20 * DEG
    mesh = gear_mesh(r_w)
    rb = r_w * np.cos(alpha)
    inv_curve = Involute(rb, 0.0, -1.0, 0.1, 0.6).reversed()
    rack = Generated(inv_curve, mesh.male, mesh.rack)
    p, _t = rack.evaluate(np.linspace(0.1, 0.6, 50))
    q = rack_frame(p, r_w)
    slope = np.polyfit(q[:, 1], q[:, 0], 1)
    resid = q[:, 0] - np.polyval(slope, q[:, 1])
    assert np.abs(resid).max() < 1e-10
    assert abs(abs(np.arctan(slope[0])) - alpha) < 1e-12
    np.testing.assert_allclose(from_rack_frame(q, r_w), p, atol=1e-14)


def test_pitch_point_of_the_standard_frames():
    mesh = rotor_mesh(5, 6, 116.0)
    np.testing.assert_allclose(pitch_point(mesh.male, mesh.female), [116.0 * 5 / 11, 0.0], atol=1e-12)
    np.testing.assert_allclose(pitch_point(mesh.male, mesh.rack), [116.0 * 5 / 11, 0.0], atol=1e-12)
    np.testing.assert_allclose(pitch_point(mesh.female, mesh.rack), [116.0 * 5 / 11, 0.0], atol=1e-12)
    assert isinstance(mesh.female, Rotation) and isinstance(mesh.rack, Translation)


def test_spline_flank_conjugate_matches_the_analytic_one():
    # points -> spline -> conjugate reproduces the analytic conjugate to the spline's fit error.
    mesh = gear_mesh(30.0)
    flank = rack_flank(20 * DEG, 30.0, 3.0)
    gen = Generated(flank, mesh.rack, mesh.male)
    s = np.linspace(0.5, 5.5, 40)
    pts, _ = gen.evaluate(s)
    sp = Spline.fit(pts[::-1])
    fine = np.linspace(sp.s0, sp.s1, 400)
    back = Generated(sp, mesh.male, mesh.rack)
    rp = back.evaluate(fine)[0]
    # every rack point must lie on the original straight flank: distance to the line
    d = np.array([np.cos(20 * DEG), -np.sin(20 * DEG)])
    n = perp_cw(d)
    dist = (rp - np.array([30.0, 0.0])) @ n
    assert np.abs(dist).max() < 1e-5


def test_corner_on_the_pitch_circle_generates_its_path():
    # A sharp corner (zero-radius arc: one point, a fan of normals) lying on the generating rotor's
    # pitch circle touches trivially at the instant it passes C, for every normal; the curve it cuts
    # on the mate is its path, which the kinematics give independently (PointPath).
    mesh = rotor_mesh(4, 6, 100.0)
    r1w = mesh.pitch_radius_male
    k = r1w * np.array([np.cos(0.4), np.sin(0.4)])
    corner = Arc(tuple(k), 0.0, 0.4 + 0.3, 0.4 + 1.2)
    c = Generated(corner, mesh.male, mesh.female).contact(np.linspace(corner.s0, corner.s1, 50))
    assert np.ptp(c.t) > 0.1  # not all at the trivial instant
    path = PointPath(tuple(k), mesh.male, mesh.female, 0.0, 1.0)
    np.testing.assert_allclose(c.points, path.evaluate(c.t)[0], atol=1e-9)

"""Analytic curves, their tangents, and chord-tolerance sampling."""

from __future__ import annotations

import numpy as np
import pytest

from rotorcad.curves import (
    Arc,
    Involute,
    Line,
    PointPath,
    Spline,
    chord_error,
    mirrored,
    rotated,
    sample_curve,
    sample_parameters,
)
from rotorcad.geometry import distance_to_polyline
from rotorcad.kinematics import Rotation, Translation


def central_difference_tangent(curve, s, h=1e-6):
    """Reference tangent: 4th-order central difference of the *analytic* evaluation (test only)."""
    f = lambda v: curve.frame(np.atleast_1d(v))[0]  # noqa: E731
    d = (-f(s + 2 * h) + 8 * f(s + h) - 8 * f(s - h) + f(s - 2 * h)) / (12 * h)
    return d / np.linalg.norm(d, axis=1, keepdims=True)


@pytest.mark.parametrize(
    "curve",
    [
        Line((1.0, 2.0), (4.0, -2.0)),
        Arc((1.0, -1.0), 3.0, 0.2, 2.5),
        Involute(20.0, 0.3, 1.0, 0.1, 0.9),
        Involute(20.0, 0.3, -1.0, 0.1, 0.9),
        PointPath((27.0, 1.5), Translation((0.0, 30.0)), Rotation((0.0, 0.0), 1.0), -0.4, 0.4),
        PointPath((27.0, 1.5), Translation((0.0, 30.0)), Rotation((0.0, 0.0), 1.0), -0.4, 0.4, offset=-0.7),
        PointPath((60.0, 4.0), Rotation((0.0, 0.0), 1.0), Rotation((116.0, 0.0), -5 / 6), -0.3, 0.3),
    ],
)
def test_tangents_are_the_analytic_derivative(curve):
    # Reference: numerical derivative of the curve's own point formula, which the tangent code
    # does not use (the tangent comes from the derivative written out by hand).
    s = np.linspace(min(curve.s0, curve.s1) + 1e-3, max(curve.s0, curve.s1) - 1e-3, 23)
    _, t = curve.frame(s)
    np.testing.assert_allclose(t, central_difference_tangent(curve, s), atol=1e-7)
    np.testing.assert_allclose(np.linalg.norm(t, axis=1), 1.0, atol=1e-14)


def test_involute_polar_angle_is_the_involute_function():
    # ISO 21771: a point at radius r of the involute of r_b has polar angle theta0 + inv(alpha_r),
    # cos(alpha_r) = r_b / r.
    rb, th0 = 17.5, 0.21
    inv_curve = Involute(rb, th0, 1.0, 0.0, 1.2)
    p, _ = inv_curve.evaluate(np.linspace(0.0, 1.2, 50))
    r = np.hypot(*p.T)
    alpha = np.arccos(rb / r)
    np.testing.assert_allclose(np.arctan2(p[:, 1], p[:, 0]), th0 + np.tan(alpha) - alpha, atol=1e-14)


def test_rack_point_path_radius():
    # Issue 2: a rack point generates the trochoid with |p|^2 = a_x^2 + (a_y + r_w t)^2.
    r_w, a = 30.0, np.array([27.3, -1.2])
    path = PointPath(tuple(a), Translation((0.0, r_w)), Rotation(), -0.5, 0.5)
    t = np.linspace(-0.5, 0.5, 101)
    p, _ = path.evaluate(t)
    np.testing.assert_allclose(np.sum(p**2, axis=1), a[0] ** 2 + (a[1] + r_w * t) ** 2, rtol=1e-14)


def test_arc_chord_error_matches_the_sagitta():
    # Sagitta of a chord over an arc of angle d: R (1 - cos(d/2)).
    arc = Arc((0.0, 0.0), 50.0, 0.0, 1.0)
    s = sample_parameters(arc, 1e-4)
    d = np.diff(s).max()
    assert 50.0 * (1 - np.cos(d / 2)) <= 1e-4
    assert chord_error(arc, s) <= 1e-4
    # not grossly oversampled: halving the count would break the tolerance
    assert 50.0 * (1 - np.cos(2 * d / 2)) > 1e-4


@pytest.mark.parametrize("tol", [1e-3, 1e-4, 1e-5])
def test_sampling_meets_the_chord_tolerance(tol):
    curves = [
        Involute(20.0, 0.0, 1.0, 0.0, 1.0),
        PointPath((26.0, 0.5), Translation((0.0, 30.0)), Rotation(), -0.6, 0.3, offset=-1.2),
        Arc((3.0, 4.0), 0.5, 0.0, 5.0),
    ]
    for curve in curves:
        s = sample_parameters(curve, tol)
        assert chord_error(curve, s, probes=16) <= tol * 1.001


def test_sampling_keeps_the_direction_of_a_falling_parameter():
    # A generated curve runs its parent backwards (s0 > s1): the refined samples must keep that
    # order and be the curve's own points (re-evaluated here), within the chord tolerance.
    arc = Arc((0.0, 0.0), 50.0, 1.0, 0.0)
    s, p, t = sample_curve(arc, 1e-5, minimum=5)
    assert s[0] == 1.0 and s[-1] == 0.0 and np.all(np.diff(s) < 0)
    q, u = arc.evaluate(s)
    np.testing.assert_allclose(p, q, atol=1e-12)
    np.testing.assert_allclose(t, u, atol=1e-12)
    assert chord_error(arc, s, probes=16) <= 1e-5 * 1.001


def test_distance_to_a_polyline_through_a_repeated_vertex():
    # Two pieces meeting at a shared vertex (listed twice): a point beside the second piece near
    # the joint is at its perpendicular distance from it, not at its distance from the vertex.
    line = np.array([[0.0, 0.0], [1.0, 0.0], [1.0, 0.0], [1.0, 1.0]])
    d = distance_to_polyline(np.array([[1.1, 0.3]]), line)
    assert d[0] == pytest.approx(0.1, abs=1e-12)


def test_spline_through_circle_points_has_circle_tangents():
    # Points on a circle of radius 10; the interpolating periodic spline's tangent must match the
    # circle's tangent to the spline's approximation error (~h^4 / R^3).
    th = np.linspace(0, 2 * np.pi, 181)[:-1]
    pts = 10.0 * np.stack([np.cos(th), np.sin(th)], axis=1)
    sp = Spline.fit(pts, periodic=True)
    s = np.linspace(0, sp.s1, 1000)
    p, t = sp.evaluate(s)
    np.testing.assert_allclose(np.hypot(*p.T), 10.0, atol=2e-7)
    ang = np.arctan2(p[:, 1], p[:, 0])
    np.testing.assert_allclose(t, np.stack([-np.sin(ang), np.cos(ang)], axis=1), atol=1e-6)


def test_mirror_and_rotation_keep_geometry():
    arc = Arc((5.0, 1.0), 2.0, 0.0, 1.0)
    m = mirrored(arc, 0.0)
    p, t = m.evaluate(np.array([m.s0, m.s1]))
    q, u = arc.evaluate(np.array([arc.s1, arc.s0]))
    np.testing.assert_allclose(p, q * [1, -1], atol=1e-15)
    np.testing.assert_allclose(t, -u * [1, -1], atol=1e-15)
    r = rotated(arc, np.pi / 2)
    np.testing.assert_allclose(r.arc_center(), [-1.0, 5.0], atol=1e-15)

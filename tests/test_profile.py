"""Profile helpers: polygon conversion, area and second moments, rotate, mirror, pattern, resample."""

from __future__ import annotations

import numpy as np
import pytest
import shapely

from rotorcad.curves import Arc, Line
from rotorcad.gear import InvoluteGear
from rotorcad.profile import Profile, Segment, polygon_moments

DEG = np.pi / 180


def disk(radius=10.0, tol=1e-6):
    return Profile((Segment.sample("circle", Arc((0.0, 0.0), radius, 0.0, 2 * np.pi), tol),))


def test_disk_moments_against_closed_form():
    # Disk: A = pi R^2, Ixx = Iyy = pi R^4 / 4 (chord tolerance 1e-6 mm -> relative error ~1e-7).
    p = disk(10.0)
    assert p.area == pytest.approx(np.pi * 100, rel=2e-7)
    m = p.second_moments()
    assert m["Ixx"] == pytest.approx(np.pi * 1e4 / 4, rel=4e-7)
    assert m["Iyy"] == pytest.approx(np.pi * 1e4 / 4, rel=4e-7)
    assert abs(m["Ixy"]) < 1e-6


def test_rectangle_moments_about_centroid_and_origin():
    # b x h rectangle at (x0, y0): I_c = b h^3 / 12; origin by the parallel-axis theorem.
    b, h, x0, y0 = 6.0, 2.0, 3.0, 5.0
    pts = np.array([[x0, y0], [x0 + b, y0], [x0 + b, y0 + h], [x0, y0 + h]])
    m = polygon_moments(pts)
    cx, cy = x0 + b / 2, y0 + h / 2
    assert (m["cx"], m["cy"]) == pytest.approx((cx, cy))
    assert m["Ixx"] == pytest.approx(b * h**3 / 12 + b * h * cy**2)
    assert m["Iyy"] == pytest.approx(h * b**3 / 12 + b * h * cx**2)
    assert m["Ixy"] == pytest.approx(b * h * cx * cy)


def test_gear_area_and_centroid_agree_with_shapely():
    g = InvoluteGear(19, 2.0, 20 * DEG, 0.0, 0.2)
    o = g.outline()
    poly = shapely.Polygon(o.points)
    assert o.area == pytest.approx(poly.area, rel=1e-12)
    np.testing.assert_allclose(o.centroid, [0.0, 0.0], atol=1e-9)  # z-fold symmetric
    m = o.second_moments()
    assert m["Ixx"] == pytest.approx(m["Iyy"], rel=1e-9)  # polar symmetry of a gear


def test_rotate_mirror_pattern():
    seg = Segment.sample("arc", Arc((5.0, 0.0), 1.0, -np.pi / 2, np.pi / 2), 1e-5)
    prof = Profile((seg,), closed=False)
    turned = prof.rotated(np.pi / 2)
    np.testing.assert_allclose(turned.points, prof.points @ np.array([[0, 1], [-1, 0]]), atol=1e-14)
    mirr = prof.mirrored(0.0)
    np.testing.assert_allclose(mirr.points, (prof.points * [1, -1])[::-1], atol=1e-14)
    # mirrored tangents still point along the travel (and normals outward)
    np.testing.assert_allclose(mirr.normals, (prof.normals * [1, -1])[::-1], atol=1e-14)
    tooth = InvoluteGear(12, 1.0).tooth_profile()
    whole = tooth.patterned(12)
    assert len(whole.points) == 12 * len(tooth.points) - 12  # shared end points joined once
    np.testing.assert_allclose(
        whole.segments[len(tooth.segments)].points, tooth.rotated(2 * np.pi / 12).segments[0].points, atol=1e-13
    )


def test_resample_re_evaluates_the_exact_curves():
    g = InvoluteGear(24, 2.0)
    fine = g.outline(1e-5)
    coarse = fine.resampled(1e-2)
    assert len(coarse.points) < len(fine.points) / 5
    # every coarse vertex lies on the fine outline (both evaluate the exact curves), within the
    # fine outline's chord tolerance
    dist = shapely.distance(shapely.Polygon(fine.points).exterior, shapely.points(coarse.points))
    assert dist.max() < 1e-5


def test_line_segment_normals_point_outward():
    square = Profile(
        tuple(
            Segment.sample(f"side{i}", Line(tuple(a), tuple(b)))
            for i, (a, b) in enumerate(zip([(0, 0), (1, 0), (1, 1), (0, 1)], [(1, 0), (1, 1), (0, 1), (0, 0)], strict=True))
        )
    )
    centre = np.array([0.5, 0.5])
    assert np.all(np.einsum("ij,ij->i", square.normals, square.points - centre) > 0)
    assert square.area == pytest.approx(1.0)

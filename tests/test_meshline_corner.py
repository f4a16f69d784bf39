"""The corner of a meshline that a fit through points rounds (issue 21 item 3, the blow-hole's apex).

Reference: closed forms. Two straight branches meeting at a known point, and a tip circle met by a
straight branch at the circle's intersection with the line, each rounded within 0.3 mm of the corner
by a fillet arc (what a spline through points does to a curvature jump), with 1 um of scatter: the
corner found is the exact intersection within 2 um; a smooth arc (no corner) is left alone.
"""

from __future__ import annotations

import numpy as np

from rotorcad.meshing import resolution, turn_corner


def _polyline(*parts: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    pts = np.vstack(parts)
    arclen = np.concatenate([[0.0], np.cumsum(np.hypot(*np.diff(pts, axis=0).T))])
    return pts, arclen


def _filleted(a: np.ndarray, b: np.ndarray, corner: np.ndarray, cut: float, step: float) -> np.ndarray:
    """Points from a to corner to b with the corner replaced by a quadratic Bezier from cut before to cut after it."""
    da, db = (corner - a) / np.hypot(*(corner - a)), (b - corner) / np.hypot(*(b - corner))
    p0, p2 = corner - cut * da, corner + cut * db
    n0 = int(np.hypot(*(p0 - a)) / step)
    u = np.linspace(0.0, 1.0, max(int(2 * cut / step), 3))[:, None]
    first = a + np.linspace(0.0, 1.0, n0, endpoint=False)[:, None] * (p0 - a)
    fillet = (1 - u) ** 2 * p0 + 2 * u * (1 - u) * corner + u**2 * p2
    n1 = int(np.hypot(*(b - p2)) / step)
    last = p2 + np.linspace(0.0, 1.0, n1)[1:, None] * (b - p2)
    return np.vstack([first, fillet, last])


def test_two_lines_rounded():
    rng = np.random.default_rng(1)
    corner = np.array([50.0, 30.0])
    pts = _filleted(np.array([40.0, 20.0]), np.array([56.0, 20.0]), corner, 0.3, 0.04)
    pts = pts + rng.normal(0.0, 1e-3, pts.shape)
    pts, arclen = _polyline(pts)
    reach = resolution(1e-3, 82.0)
    i = int(np.argmax(pts[:, 1]))  # the rounded turn's tip, nearest a cusp above it
    assert np.hypot(*(pts[i] - corner)) > 0.1  # the rounding misses the corner by a tenth of a millimetre
    found = turn_corner(pts, arclen, i, reach, accuracy=1e-3)
    assert found is not None
    assert np.hypot(*(found - corner)) < 2e-3


def test_tip_circle_met_by_a_line():
    # a tip corner's path on the male tip circle (radius 69.5 about O1), met by a straight branch
    rng = np.random.default_rng(2)
    radius = 69.5
    th = np.radians(21.0)
    corner = radius * np.array([np.cos(th), np.sin(th)])
    arc = radius * np.column_stack([np.cos(np.linspace(0.0, th, 2000)), np.sin(np.linspace(0.0, th, 2000))])
    line_end = corner + 12.0 * np.array([-0.6, -0.8])
    keep = np.hypot(*(arc - corner).T) > 0.3
    tail = _filleted(arc[keep][-1], line_end, corner, 0.3, 0.04)
    pts, arclen = _polyline(arc[keep], tail[1:])
    pts = pts + rng.normal(0.0, 1e-3, pts.shape)
    i = int(np.argmax(np.hypot(*(pts - corner).T) < 0.2)) + 3
    found = turn_corner(pts, arclen, i, resolution(1e-3, 116.0), ((np.zeros(2), radius),), 1e-3)
    assert found is not None
    assert abs(np.hypot(*found) - radius) < 1e-9  # on the tip circle
    assert np.hypot(*(found - corner)) < 2e-3


def test_smooth_arc_is_no_corner():
    th = np.linspace(0.0, np.pi / 2, 3000)
    pts, arclen = _polyline(14.0 * np.column_stack([np.cos(th), np.sin(th)]))
    assert turn_corner(pts, arclen, 1500, resolution(1e-3, 116.0)) is None

"""The spline through sparse points across a curvature step (rotorcad.measured.stepped_spline), issue 22 item 2.

Reference, not produced by the code under test: the closed-form distance to a stadium (two half
circles of radius R joined by straight lines: the distance of p to the outline is |d(p, S) - R|, S
the segment between the circles' centres), whose curvature steps from 0 to 1/R at four points, as a
rotor's tip rounding meets its flank; and an ellipse (no step) densely sampled.
"""

from __future__ import annotations

import numpy as np
import pytest

from rotorcad.curves import Spline, sample_curve
from rotorcad.geometry import distance_to_polyline
from rotorcad.measured.stepped_spline import curvature_steps, stepped_ring_spline

R, L = 2.07, 12.0  # mm: the N-rack female's tip rounding, a flank 12 mm long
SPACING = 0.79  # mm: the N-rack female at 80 points a lobe


def stadium(count: int, phase: float) -> np.ndarray:
    """``count`` points evenly spaced along the stadium's length, the first ``phase`` of a spacing in."""
    per = 2 * L + 2 * np.pi * R
    s = (np.arange(count) + phase) * per / count
    a = np.clip((s - L) / R, 0.0, np.pi) - np.pi / 2
    b = np.clip((s - 2 * L - np.pi * R) / R, 0.0, np.pi) + np.pi / 2
    x = np.select(
        [s < L, s < L + np.pi * R, s < 2 * L + np.pi * R],
        [-L / 2 + s, L / 2 + R * np.cos(a), L / 2 - (s - L - np.pi * R)],
        -L / 2 + R * np.cos(b),
    )
    y = np.select([s < L, s < L + np.pi * R, s < 2 * L + np.pi * R], [-R, R * np.sin(a), R], R * np.sin(b))
    return np.column_stack([x, y])


def off_stadium(points: np.ndarray) -> float:
    """Closed form: the largest distance of points (n, 2) from the stadium, mm."""
    x = np.clip(points[:, 0], -L / 2, L / 2)
    return float(np.abs(np.hypot(points[:, 0] - x, points[:, 1]) - R).max())


@pytest.mark.parametrize("phase", [0.0, 0.37, 0.5, 0.81])
def test_a_spline_across_curvature_steps_between_sparse_points_follows_the_outline(phase):
    # one periodic cubic through points 0.79 mm apart rings across each step of 0.48 /mm: 4.4-9.5 um
    # off the stadium (h^2 dk / 30 = 10 um); with a double knot at each step, placed where the spline's
    # third derivative jumps least beside it: 1.2-4.4 um (measured), and never worse than the cubic
    points = stadium(round((2 * L + 2 * np.pi * R) / SPACING), phase)
    assert off_stadium(points) < 1e-12  # the points lie on the outline
    stepped = stepped_ring_spline(points)
    assert stepped is not None
    assert len(curvature_steps(points, 0.0)) >= 3
    error = off_stadium(sample_curve(stepped, 1e-5)[1])
    periodic = off_stadium(sample_curve(Spline.fit(points, periodic=True), 1e-5)[1])
    assert error < 5e-3
    assert error < periodic


@pytest.mark.parametrize("count", [40, 60, 100])
def test_a_smooth_outline_has_no_step(count):
    # an ellipse 10 x 6 mm (curvature 0.12-0.56 /mm, varying smoothly) from 40-100 points: no step,
    # the periodic cubic as before (a false step there moved the fit 0.08 -> 0.33 um off at 40 points)
    t = np.linspace(0.0, 2 * np.pi, count, endpoint=False) + 0.1
    points = np.column_stack([5 * np.cos(t), 3 * np.sin(t)])
    assert stepped_ring_spline(points) is None
    dense = np.linspace(0.0, 2 * np.pi, 20001)
    fit = sample_curve(Spline.fit(points, periodic=True), 1e-5)[1]
    assert distance_to_polyline(fit, np.column_stack([5 * np.cos(dense), 3 * np.sin(dense)])).max() < 1e-4

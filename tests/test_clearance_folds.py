"""A generated rack's fold cut back to its envelope (``clearance_normals.trim_folds``), against closed forms.

The curve at distance d = 2 on the concave side of the parabola y = x^2 / 2 (radius of curvature 1 at its
vertex) is the envelope of circles of radius 2 along the parabola, as a rack is the envelope of a rotor's
positions: where the radius of curvature is below d it folds into a swallowtail, whose first and last legs
cross on the axis at (0, 2.5) (the point (0, y) lies 2 from the parabola where 2 y - 1 = 4: the distance
squared x^2 + (x^2 / 2 - y)^2 is least at x^2 = 2 (y - 1)). The region within d of the parabola covers
the loop: the cut curve's points lie at d from the parabola (brute force over 200001 of its points), the
points cut away nearer.
"""

from __future__ import annotations

import numpy as np

from rotorcad.clearance_normals import normal_clearance, trim_folds

D = 2.0


def offset_parabola(x: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Points (n, 2) at distance D above y = x^2 / 2 along its normal, and the parabola's unit tangents (n, 2)."""
    s = np.hypot(1.0, x)
    tan = np.column_stack([1.0 / s, x / s])
    return np.column_stack([x - D * x / s, x**2 / 2 + D / s]), tan


def distance_to_parabola(p: np.ndarray) -> np.ndarray:
    """Brute force: the least distance (n,) from each point to the parabola, sampled 1e-4 apart on |x| <= 10."""
    x = np.linspace(-10.0, 10.0, 200001)
    curve = np.column_stack([x, x**2 / 2])
    from scipy.spatial import cKDTree

    return cKDTree(curve).query(p)[0]


def test_a_swallowtail_is_cut_at_its_legs_crossing_and_what_is_left_is_the_envelope():
    pts, tan = offset_parabola(np.linspace(-8.0, 8.0, 1601))
    cut, cut_tan, (index,) = trim_folds(pts, tan, (np.arange(len(pts)),))
    # the crossing, twice: (0, 2.5) closed form, within the chords' sagitta (0.01 mm apart, curvature <= 1/D)
    twice = np.flatnonzero(np.all(np.diff(cut, axis=0) == 0, axis=1))
    assert len(twice) == 1
    kept = np.isin(np.arange(len(pts)), np.delete(index, [twice[0], twice[0] + 1]))  # the copies carry cut points' flags
    assert 0 < (~kept).sum() < len(pts) // 3
    assert np.allclose(cut[twice[0]], [0.0, 2.5], atol=1e-4)
    # its two copies carry the two legs' tangents: the parabola's at x = -sqrt(3) and +sqrt(3)
    x = np.sqrt(3.0)
    assert np.allclose(cut_tan[twice[0]], [1 / 2, -x / 2], atol=1e-3)
    assert np.allclose(cut_tan[twice[0] + 1], [1 / 2, x / 2], atol=1e-3)
    # what is left is the envelope (at D from the parabola); what was cut lies nearer (inside the region)
    assert np.abs(distance_to_parabola(pts[kept]) - D).max() < 1e-4
    assert np.all(distance_to_parabola(pts[~kept]) < D - 1e-3)


def test_a_normal_meets_the_envelope_not_the_swallowtails_tail():
    # the line x = 0.05 meets the first leg's tail (parabola parameter t in (-sqrt 3, -1)) inside the region
    # and the envelope (the last leg, t > sqrt 3) above it, each where t - D t / sqrt(1 + t^2) = 0.05
    # (brentq); a datum 0.03 above the tail with its normal down (into the region) lies inside it: the
    # envelope above it reads the interference, not the tail 0.03 below
    from scipy.optimize import brentq

    def y_at(lo: float, hi: float) -> float:
        t = brentq(lambda t: t - D * t / np.hypot(1.0, t) - 0.05, lo, hi)
        return t**2 / 2 + D / np.hypot(1.0, t)

    tail, envelope = y_at(-np.sqrt(3.0), -1.0), y_at(np.sqrt(3.0), 3.0)
    assert envelope - tail > 0.15
    pts, tan = offset_parabola(np.linspace(-8.0, 8.0, 1601))
    datum, normal = np.array([[0.05, tail + 0.03]]), np.array([[0.0, -1.0]])
    assert np.allclose(normal_clearance(datum, normal, pts, tan), [0.03], atol=1e-5)  # the tail, uncut
    cut, cut_tan, _ = trim_folds(pts, tan)
    assert np.allclose(normal_clearance(datum, normal, cut, cut_tan), [tail + 0.03 - envelope], atol=1e-5)


def test_a_rack_without_a_fold_is_left_as_it_is():
    x = np.linspace(-8.0, 8.0, 1601)
    s = np.hypot(1.0, x)
    pts, tan = np.column_stack([x - 0.5 * x / s, x**2 / 2 + 0.5 / s]), np.column_stack([1.0 / s, x / s])
    cut, cut_tan, _ = trim_folds(pts, tan)
    assert np.array_equal(cut, pts) and np.array_equal(cut_tan, tan)

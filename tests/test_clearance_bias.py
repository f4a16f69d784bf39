"""The fits' bias terms of the clearance's stated accuracy (rotorcad.measured.fit_bias, rotorcad.clearance_bias)."""

from __future__ import annotations

import numpy as np
import pytest

from rotorcad.clearance_bias import fitted_curvature, largest_curvature_near
from rotorcad.curves import Arc, Line
from rotorcad.measured.fit_bias import ROUNDING_BIAS, rack_folds, rounding_bias


def test_a_fold_is_found_with_the_width_its_middle_leg_lies_off():
    # a swallowtail by construction: a run along y = 0 to x = 5, back along y = w to x = 4, forward
    # along y = 2 w: the middle leg (the fold) lies w off each leg beside it (closed form)
    w = 0.01
    out, back, on = np.linspace(0.0, 5.0, 51), np.linspace(5.0, 4.0, 11), np.linspace(4.0, 9.0, 51)
    pts = np.vstack([np.column_stack([x, np.full_like(x, k * w)]) for k, x in enumerate((out, back, on))])
    tangents = np.tile([1.0, 0.0], (len(pts), 1))  # the exact rack runs in +x
    folds = rack_folds(pts, tangents, np.zeros(len(pts), bool), np.zeros(len(pts), int))
    assert len(folds) == 1
    lo, hi, width = folds[0]
    assert width == pytest.approx(w, rel=1e-6)
    assert lo <= len(out) <= len(out) + len(back) <= hi  # it reaches over the fold and its legs
    # no fold across a join of two pieces, nor on a corner's path
    piece = np.r_[np.zeros(len(out), int), np.ones(len(back) + len(on), int)]
    assert len(rack_folds(pts, tangents, np.zeros(len(pts), bool), piece)) == 1  # the fold is within piece 1
    assert rack_folds(pts, tangents, np.ones(len(pts), bool), np.zeros(len(pts), int)) == []


def test_rounding_bias_is_the_measured_law_and_zero_without_scatter():
    # ROUNDING_BIAS sigma (kappa h^2 / sigma)^(1/5) (benchmarks/bench_rounding_bias.py); arrays elementwise
    sigma, h = 2e-3, 0.25
    kappa = np.array([0.0, 0.5, 2.0])
    expected = ROUNDING_BIAS * sigma * (kappa * h**2 / sigma) ** 0.2
    assert rounding_bias(sigma, h, kappa) == pytest.approx(expected)
    assert rounding_bias(sigma, h, 0.5) == pytest.approx(expected[1])
    assert rounding_bias(0.0, h, 0.5) == 0.0


def test_the_fitted_curvature_near_a_point_is_that_of_the_rounding_within_reach():
    # a flank, an arc of radius 2 mm, a flank: the arc's curvature 1/R (closed form) within two
    # spacings of it, 0 beyond, on either of the rotor's lobes (the lobe turned by 2 pi / z)
    r = 2.0
    pieces = [
        ("flank", Line((10.0, -5.0), (10.0, 0.0))),
        ("tip", Arc((8.0, 0.0), r, 0.0, np.pi / 2)),
        ("flank2", Line((8.0, 2.0), (3.0, 2.0))),
    ]
    _, kappa = fitted_curvature(pieces, 0.2)
    # the turn over the chord: 1/R within (h / 4 R)^2 / 24
    assert np.all(np.isclose(kappa, 1 / r, rtol=1e-4) | np.isclose(kappa, 0.0, atol=1e-9))
    at = np.array([[10.0, -0.2], [10.0, -3.0], [5.0, 2.0]])
    turned = at @ np.array([[0.0, 1.0], [-1.0, 0.0]])  # the same points on the next of 4 lobes
    for points in (at, turned):
        assert largest_curvature_near(points, pieces, 4, 0.2) == pytest.approx([1 / r, 0.0, 0.0], abs=1e-4)

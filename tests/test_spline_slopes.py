"""The meshline's spline slopes (rotorcad.spline_slopes) against scipy's interpolating cubic spline.

Reference: scipy.interpolate.make_interp_spline(k=3) (not-a-knot ends), which the meshing analysis
used before, and a cubic polynomial, which the not-a-knot spline reproduces exactly.
"""

from __future__ import annotations

import numpy as np
import pytest
from scipy.interpolate import make_interp_spline

from rotorcad.spline_slopes import solve_tridiagonal, spline_slopes


@pytest.mark.parametrize("n", [4, 5, 7, 16, 17, 600, 601])
def test_slopes_equal_scipys_not_a_knot_spline(n):
    rng = np.random.default_rng(n)
    for x in (np.linspace(-1.0, 2.5, n), np.cumsum(rng.uniform(0.5, 1.5, n))):
        y = np.column_stack([np.sin(x) * 5, np.cos(2 * x) + x**2])
        reference = make_interp_spline(x, y, k=3).derivative()(x)
        np.testing.assert_allclose(spline_slopes(x, y), reference, rtol=0, atol=1e-11 * np.abs(reference).max())


def test_a_cubic_is_reproduced():
    x = np.linspace(0.0, 3.0, 9) ** 1.3
    y = (2 * x**3 - x**2 + 4 * x - 1)[:, None]
    np.testing.assert_allclose(spline_slopes(x, y)[:, 0], 6 * x**2 - 2 * x + 4, atol=1e-11)


def test_tridiagonal_solve_matches_a_dense_solve():
    rng = np.random.default_rng(3)
    n = 37
    lower, upper = rng.uniform(-1, 1, n), rng.uniform(-1, 1, n)
    diagonal = 3 + rng.uniform(0, 1, n)
    rhs = rng.normal(size=(n, 2))
    dense = np.diag(diagonal) + np.diag(lower[1:], -1) + np.diag(upper[:-1], 1)
    np.testing.assert_allclose(solve_tridiagonal(lower, diagonal, upper, rhs), np.linalg.solve(dense, rhs), atol=1e-13)


@pytest.mark.parametrize("n", [2, 3, 4, 7, 600])
def test_makima_slopes_equal_scipys_modified_akima(n):
    # reference: scipy.interpolate.Akima1DInterpolator(method="makima"), which the meshing analysis
    # used for a design's meshline tangents; flat runs and a corner test the weights' fallbacks
    from scipy.interpolate import Akima1DInterpolator

    from rotorcad.spline_slopes import makima_slopes

    rng = np.random.default_rng(n)
    x = np.cumsum(rng.uniform(0.5, 1.5, n))
    y = np.column_stack([np.sin(x) * 5, np.where(x > x[n // 2], 1.0, 0.0), np.abs(x - x[n // 3])])
    reference = Akima1DInterpolator(x, y, axis=0, method="makima").derivative()(x)
    np.testing.assert_allclose(makima_slopes(x, y), reference, rtol=0, atol=1e-12 * max(1.0, np.abs(reference).max()))

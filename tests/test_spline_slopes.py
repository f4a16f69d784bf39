"""The meshline's spline slopes (rotorcad.spline_slopes) against scipy's modified Akima cubic.

Reference: scipy.interpolate.Akima1DInterpolator(method="makima") (Akima 1970, Moler 2019).
"""

from __future__ import annotations

import numpy as np
import pytest


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

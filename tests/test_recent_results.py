"""rotorcad.measured.recent: a memo of the last few results on array arguments.

Reference: the undecorated function itself (a remembered result is that function's own answer for
equal arguments, compared by value; a caller changing its copy changes no other caller's).
"""

from __future__ import annotations

import numpy as np

from rotorcad.measured import fit
from rotorcad.measured.outline import corners
from rotorcad.measured.recent import recent_results


def test_recent_results_are_the_functions_own_by_value_and_copied():
    calls = []

    @recent_results(2)
    def scaled(a, s, t=1.0):
        calls.append(s)
        return a * s * t

    x = np.arange(4.0)
    first = scaled(x, 2.0)
    first[0] = 99.0  # the caller's copy only
    np.testing.assert_array_equal(scaled(x.copy(), 2.0), x * 2.0)
    assert calls == [2.0]
    scaled(x, 3.0)
    scaled(x, 4.0)  # forgets s = 2
    np.testing.assert_array_equal(scaled(x, 2.0), x * 2.0)
    np.testing.assert_array_equal(scaled(x, 2.0, t=3.0), x * 6.0)
    np.testing.assert_array_equal(scaled(x + 1.0, 2.0), (x + 1.0) * 2.0)
    assert calls == [2.0, 3.0, 4.0, 2.0, 2.0, 2.0]


def test_refined_corners_remembered_are_the_computed_ones():
    # a four-lobed outline r = 1 + 0.5 |sin 2t|: four sharp corners (a 90 deg turn) where sin 2t = 0
    t = np.linspace(0, 2 * np.pi, 401)[:-1]
    whole = np.column_stack([np.cos(t), np.sin(t)]) * (1.0 + 0.5 * np.abs(np.sin(2 * t)))[:, None]
    edges, points = corners(whole, 0.0, 30.0)
    assert len(edges) >= 2
    direct = fit._refined_corners.__wrapped__(whole, edges, points, 0.0, None, 1e-4)
    np.testing.assert_array_equal(fit._refined_corners(whole, edges, points, 0.0, None, 1e-4), direct)
    np.testing.assert_array_equal(fit._refined_corners(whole, edges, points, 0.0, None, 1e-4), direct)

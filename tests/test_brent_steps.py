"""rotorcad.roots' Brent steps in Python against scipy.optimize.brentq (the C routine they follow).

Reference: scipy.optimize.brentq on the same brackets and tolerances; the roots agree to the last
bit (the same steps in the same floating-point order), and each is a sign change of f within xtol.
"""

from __future__ import annotations

import math

import numpy as np
from scipy.optimize import brentq

from rotorcad.roots import bracket_root


def test_roots_equal_scipys_brentq():
    rng = np.random.default_rng(7)
    checked = 0
    for _ in range(600):
        c = rng.normal(size=4)

        def f(x, c=c):
            return c[0] + c[1] * x + c[2] * math.sin(3 * x) + c[3] * x**3

        a, b = sorted(rng.uniform(-3, 3, 2))
        if f(a) * f(b) >= 0:
            continue
        for xtol in (1e-12, 1e-15):
            root = bracket_root(f, (a, b), xtol=xtol)
            assert root == brentq(f, a, b, xtol=xtol)
            assert f(root - 2 * xtol - 1e-15 * abs(root)) * f(root + 2 * xtol + 1e-15 * abs(root)) <= 0
        checked += 1
    assert checked > 200

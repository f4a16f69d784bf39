"""The stored brute-force references (tests/reference_data) are what their functions compute.

tests/make_reference_data.py writes them; here one is computed again from scratch (the male of the
4/6 trapezoid pair cut by 3000 rack positions, shapely booleans) and compared with its file.
"""

from __future__ import annotations

import hashlib

import numpy as np
import shapely
from independent_pairs import REFERENCE_DATA, cut_rotor, cut_rotor_brute_force, trapezoid_4_6


def test_a_stored_cut_equals_the_cut_made_again():
    pair = trapezoid_4_6()
    key = repr((pair, "male", 3000))
    path = REFERENCE_DATA / f"cut_rotor_{hashlib.sha256(key.encode()).hexdigest()[:16]}.npy"
    assert path.exists(), "run tests/make_reference_data.py"
    stored = np.load(path)
    again = cut_rotor_brute_force(pair, "male", 3000)
    # the same booleans give the same vertices; 1 nm allows another GEOS build's rounding
    assert shapely.hausdorff_distance(shapely.LinearRing(stored), shapely.LinearRing(again)) < 1e-6
    np.testing.assert_allclose(cut_rotor(pair, "male"), stored, rtol=0, atol=0)  # what the tests read

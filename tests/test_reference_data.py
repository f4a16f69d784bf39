"""The stored brute-force references (tests/reference_data) are what their functions compute.

tests/make_reference_data.py writes them; here one of each kind is computed again from scratch and
compared with its file: the male of the 4/6 trapezoid pair cut by 3000 rack positions (shapely
booleans), and the closest approach of 60 points of the female to that male over the mesh.
"""

from __future__ import annotations

import hashlib

import numpy as np
import pytest
import shapely
from independent_pairs import REFERENCE_DATA, closest_approach, cut_rotor, cut_rotor_brute_force, trapezoid_4_6


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


def test_a_stored_closest_approach_equals_the_one_made_again(recwarn):
    # keyed by its inputs and its code (independent_pairs.stored_by_inputs): read from its file
    # (no warning that it was computed), and the same numbers as the brute force run again
    pair = trapezoid_4_6()
    male, female = cut_rotor(pair, "male"), cut_rotor(pair, "female")
    points = female[:: len(female) // 60][:60]
    stored = closest_approach(pair, points, male, positions=1500)
    assert not [w for w in recwarn if "reference_data" in str(w.message)], "run tests/make_reference_data.py"
    again = closest_approach.brute_force(pair, points, male, positions=1500)
    np.testing.assert_array_equal(stored, again)
    assert stored.min() == pytest.approx(0.0, abs=2e-3)  # the female's contact points: cut by the male's rack

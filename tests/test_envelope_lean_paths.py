"""The envelope engine's lean paths give the full paths' numbers, bit for bit (issue 26: racks faster).

``Generated.frame`` computes only the points and tangents (no normals, no sliding; each body's cosine
and sine once) and ``_contact_times`` solves both roots of a turning generator at once. Reference:
the full evaluation, ``Generated.contact`` (:func:`rotorcad.envelope.conjugate`), and two calls of
:func:`rotorcad.envelope.contact_parameter`, one per branch, on the README pair's lobes and on
the rack derived from them (rotor pieces as generators, their corner fans included).
"""

from __future__ import annotations

import tomllib
from pathlib import Path

import numpy as np
import pytest

from rotorcad.design import rotor_design
from rotorcad.envelope import Generated, _both_branches, contact_parameter
from rotorcad.geometry import perp_cw
from rotorcad.inverse_rack import with_corner_fans
from rotorcad.kinematics import Translation, pitch_point
from rotorcad.rotor_build import build_pair, pair_spec

SAMPLE = Path(__file__).resolve().parents[1] / "samples" / "rack_involute_5_6.toml"


@pytest.fixture(scope="module")
def rotors():
    with SAMPLE.open("rb") as f:
        return build_pair(pair_spec(rotor_design(tomllib.load(f), SAMPLE.parent)))


def generated_curves(rotors):
    """The male's pieces cut by the rack, and the rack cut by the male's pieces and corners (as derive_rack builds it)."""
    pair = rotors.pair
    male = pair.mesh.male
    rack = Translation((0.0, pair.male_pitch_radius))
    depth = (-pair.male_dedendum - 1e-6, pair.male_addendum + 1e-6)
    lobe = [(name, curve) for name, curve, _ in rotors.male_pieces]
    fans = with_corner_fans(lobe, np.zeros(2), 2 * np.pi / pair.male_teeth)
    return [curve for _, curve in lobe] + [Generated(curve, male, rack, limits=depth) for _, curve in fans]


def test_frame_is_the_full_contacts_points_and_tangents(rotors):
    curves = generated_curves(rotors)
    assert any(c.parent.is_corner() for c in curves)  # corner fans are among them
    for gen in curves:
        s = np.linspace(gen.s0, gen.s1, 97)
        p, t = gen.frame(s)
        full = gen.contact(s)
        assert np.array_equal(p, full.points, equal_nan=True)
        assert np.array_equal(t, full.tangents * (-gen.parent_direction), equal_nan=True)


@pytest.mark.parametrize("branch", ["A", "B"])
def test_both_roots_at_once_are_contact_parameters(rotors, branch):
    for gen in generated_curves(rotors)[len(rotors.male_pieces) :]:  # the rotor's pieces generate the rack
        s = np.linspace(gen.s0, gen.s1, 97)
        p, t = gen.parent.frame(s)
        n = perp_cw(t * gen.parent_direction)
        c = pitch_point(gen.generating, gen.generated)
        args = (gen.parent.arc_center(), 0.0, gen.parent.is_corner())
        first, other = _both_branches(p, n, gen.generating, c, branch, *args)
        ref_first = contact_parameter(p, n, gen.generating, c, branch, args[0], 0.0, args[2])
        ref_other = contact_parameter(p, n, gen.generating, c, "B" if branch == "A" else "A", None, 0.0, args[2])
        assert np.array_equal(first, ref_first, equal_nan=True)
        assert np.array_equal(other, ref_other, equal_nan=True)

"""Rotor pieces cut by a rack line, arc or point path in closed form (rotorcad.rotor_cut), held to the generic path.

References: the envelope engine (:class:`rotorcad.envelope.Generated`, the meshing condition
solved point by point in the fixed frame; Litvin, *Gear Geometry and Applied Theory*, eq. 6.1.7)
for the points and tangents, the exact curve at the chords' middles for the sagitta, and the
generic sampler (:func:`rotorcad.curves.sample_curve`) for the outline.
"""

from __future__ import annotations

import math
import tomllib
from pathlib import Path

import numpy as np
import pytest

import rotorcad.screw_rotors as screw_rotors
from rotorcad.curves import Arc, Line, chord_error
from rotorcad.design import rotor_design
from rotorcad.envelope import Generated
from rotorcad.roles import Side
from rotorcad.rotor_build import build_pair, pair_spec
from rotorcad.rotor_cut import cut_segment

SAMPLES = Path(__file__).resolve().parents[1] / "samples"
TOL = 1e-4  # mm: the README's 0.1 um


def _families() -> list[Path]:
    out = []
    for path in sorted(SAMPLES.glob("*.toml")):
        with path.open("rb") as f:
            if "profile" in tomllib.load(f):
                out.append(path)
    return out


@pytest.fixture(scope="module", params=_families(), ids=lambda p: p.stem)
def rotors(request):
    path = request.param
    with path.open("rb") as f:
        return build_pair(pair_spec(rotor_design(tomllib.load(f), path.parent)))


def _closed_form(rotors, side: Side) -> list[tuple[object, object]]:
    """(lobe segment, its closed-form sampling) of every piece cut by a rack line, arc or point path."""
    pieces = rotors.male_pieces if side is Side.MALE else rotors.female_pieces
    lobe = rotors.male_lobe(TOL) if side is Side.MALE else rotors.female_lobe(TOL)
    by_curve = {id(seg.curve): seg for seg in lobe.segments}
    out = []
    for name, curve, piece in pieces:
        rotor = side.pick(rotors.pair.mesh.male, rotors.pair.mesh.female)
        seg = cut_segment(name, curve, piece.curve, side, rotors.pair.male_pitch_radius, rotors.pair.center_distance, TOL, rotor)
        if seg is not None and id(curve) in by_curve:
            out.append((by_curve[id(curve)], seg))
    return out


@pytest.mark.parametrize("side", [Side.MALE, Side.FEMALE])
def test_closed_form_samples_lie_on_the_envelope(rotors, side):
    # reference: Generated.evaluate, the envelope engine's point-by-point solution of the meshing
    # condition (rotorcad.envelope.conjugate), at the same parameters of the same piece
    pairs = _closed_form(rotors, side)
    assert pairs, "every sample family has a rack line or arc"
    for seg, cut in pairs:
        np.testing.assert_array_equal(seg.s, cut.s)  # the lobe took the closed form
        p, t = seg.curve.evaluate(seg.s)
        assert np.abs(p - seg.points).max() <= 1e-9, seg.name
        # the engine solves t from cross(n, p - C) / cross(n, V), ill-conditioned where a corner
        # passes the pitch point (sliding speed 5e-5 mm/rad at the end of srm-b's sealing root:
        # its t is off by 1e-9 rad there, the point by 5e-14 mm); the closed form has t = s exactly
        assert np.abs(t - seg.tangents).max() <= 1e-8, seg.name


@pytest.mark.parametrize("side", [Side.MALE, Side.FEMALE])
def test_closed_form_chords_within_tolerance(rotors, side):
    # reference: the exact curve (Generated.evaluate) at the middle of every chord and at 4 more
    # points inside it, measured against the chord
    for seg, _ in _closed_form(rotors, side):
        assert chord_error(seg.curve, seg.s, probes=1) <= TOL * (1.0 + 1e-9), seg.name
        assert chord_error(seg.curve, seg.s, probes=5) <= TOL * (1.0 + 1e-6), seg.name


@pytest.mark.parametrize("side", [Side.MALE, Side.FEMALE])
def test_outline_equals_the_generic_samplers(rotors, side, monkeypatch):
    # reference: the generic sampler on the same pieces (rotorcad.curves.sample_curve), which the
    # closed form replaces: the same pieces, in the same order, with the same curves and ends
    lobe = rotors.male_lobe(TOL) if side is Side.MALE else rotors.female_lobe(TOL)
    monkeypatch.setattr(screw_rotors, "cut_segment", lambda *args: None)
    generic_rotors = type(rotors)(rotors.pair, rotors.rack, rotors.family, tolerance=rotors.tolerance)
    generic = generic_rotors.male_lobe(TOL) if side is Side.MALE else generic_rotors.female_lobe(TOL)
    assert [s.name for s in lobe.segments] == [s.name for s in generic.segments]
    for seg, ref in zip(lobe.segments, generic.segments, strict=True):
        assert seg.curve.s0 == ref.curve.s0 and seg.curve.s1 == ref.curve.s1, seg.name
        assert np.abs(seg.points[[0, -1]] - ref.points[[0, -1]]).max() <= 1e-9, seg.name
        # tangents to 1e-8: the engine's contact turn is off by 1e-9 rad where a corner passes the
        # pitch point (see test_closed_form_samples_lie_on_the_envelope)
        assert np.abs(seg.tangents[[0, -1]] - ref.tangents[[0, -1]]).max() <= 1e-8, seg.name
    np.testing.assert_allclose(lobe.points[[0, -1]], generic.points[[0, -1]], rtol=0.0, atol=1e-9)


@pytest.fixture(scope="module")
def readme_pair():
    path = SAMPLES / "rack_involute_5_6.toml"
    with path.open("rb") as f:
        return build_pair(pair_spec(rotor_design(tomllib.load(f), path.parent)))


def test_piece_without_contact_goes_to_the_generic_sampler(readme_pair):
    # the envelope engine has no contact where the rack normal lies along the motion (+y):
    # (rotorcad.envelope.contact_parameter, NaN), and the generic sampler drops those points; the
    # closed form hands such pieces over instead of guessing
    r1, a = readme_pair.pair.male_pitch_radius, readme_pair.pair.center_distance
    mesh = readme_pair.pair.mesh
    arc = Arc((r1 + 3.0, 1.0), 2.0, 0.2, math.pi / 2)  # ends where its normal is (0, 1)
    line = Line((r1 - 2.0, 1.0), (r1 + 2.0, 1.0))  # normal (0, +-1) everywhere
    for piece in (arc, line):
        gen = Generated(piece.reversed(), mesh.rack, mesh.male)
        assert not np.isfinite(gen.evaluate(piece.s1 if piece is arc else 1.0)[0]).all()  # the engine's verdict
        assert cut_segment("x", gen, piece, Side.MALE, r1, a, TOL, mesh.male) is None
    inside = Arc((r1 + 3.0, 1.0), 2.0, 0.2, 1.2)  # the same arc short of the no-contact point
    seg = cut_segment("x", Generated(inside.reversed(), mesh.rack, mesh.male), inside, Side.MALE, r1, a, TOL, mesh.male)
    assert seg is not None and np.abs(seg.curve.evaluate(seg.s)[0] - seg.points).max() <= 1e-9

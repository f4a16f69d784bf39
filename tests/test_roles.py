"""Roles are types: renaming the pieces of a rack changes no decision (issue "a core that is easy
to change": the hobbability verdict once depended on a name ending in "corner")."""

from __future__ import annotations

import dataclasses

import numpy as np

from hob.rack import rotor_rack
from hob.verdict import judge
from rotorcad.roles import PieceRole, Side
from rotorcad.rotor_families import build_family
from rotorcad.rotor_pair import RotorPair


def test_renamed_rack_pieces_give_the_same_verdict():
    pair = RotorPair(5, 6, 116.0, 63.0, 116.0 * 5 / 11, 116.0 * 6 / 11, 53.0)
    rotors = build_family(pair, "srm-asymmetric", {})
    for side in Side:
        rack = rotor_rack(rotors, side)
        assert PieceRole.CORNER_FAN in rack.roles  # the sharp corners' fans are there
        renamed = dataclasses.replace(rack, names=tuple(f"piece {i}" for i in range(len(rack.names))))
        a, b = judge(rack), judge(renamed)
        assert (a.hobbable, a.reasons) == (b.hobbable, b.reasons)
        # and the string a caller may still pass is the same rotor
        assert np.array_equal(rotor_rack(rotors, side.value).points, rack.points)


def test_side_reads_text_and_prints_as_text():
    assert Side("female") is Side.FEMALE and Side.MALE.other is Side.FEMALE
    assert f"{Side.MALE} points" == "male points"

"""Old import path of the involute gear: the names now live in :mod:`rotorcad.gears`.

Kept so that ``from rotorcad.gear import InvoluteGear`` goes on working; new code imports from
:mod:`rotorcad.gears` (or its modules).
"""

from __future__ import annotations

from rotorcad.gears.formulas import tool_tip_radius_limit
from rotorcad.gears.involute_gear import DEG, MAX_TEETH, MODULE_RANGE, RELATIVE_TOLERANCE, InvoluteGear
from rotorcad.gears.pair import GearPair, mate_shift

__all__ = [
    "DEG",
    "MAX_TEETH",
    "MODULE_RANGE",
    "RELATIVE_TOLERANCE",
    "GearPair",
    "InvoluteGear",
    "mate_shift",
    "tool_tip_radius_limit",
]

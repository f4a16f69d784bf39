"""Old import path of the involute closed forms: they now live in :mod:`rotorcad.gears.formulas`.

Kept so that ``from rotorcad.involute import inv`` goes on working; new code imports from
:mod:`rotorcad.gears.formulas`.
"""

from __future__ import annotations

from rotorcad.gears.formulas import inv, inv_inverse, shift_sum, transverse_pressure_angle, working_pressure_angle

__all__ = ["inv", "inv_inverse", "shift_sum", "transverse_pressure_angle", "working_pressure_angle"]

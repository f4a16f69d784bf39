"""Inspection from measured points: a gear against its nominal flanks (ISO 1328-1:2013), a screw rotor against its outline.

``rotorcad inspect`` (:mod:`rotorcad.cli.inspect_cmd`) over :func:`inspect_gear` and :func:`inspect_rotor`.
"""

from rotorcad.inspection.gear_inspection import GearInspection, inspect_gear
from rotorcad.inspection.nominal import NominalFlanks, nominal_flanks
from rotorcad.inspection.tolerances import FlankTolerances, flank_tolerances

__all__ = ["FlankTolerances", "GearInspection", "NominalFlanks", "flank_tolerances", "inspect_gear", "nominal_flanks"]

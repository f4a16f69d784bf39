"""Old import path of the profile families: they now live in :mod:`rotorcad.families`.

Kept so that ``from rotorcad.rotor_families import build_family`` goes on working; new code
imports from :mod:`rotorcad.families`.
"""

from __future__ import annotations

from rotorcad.families.checks import check_tips
from rotorcad.families.krigar import krigar
from rotorcad.families.lysholm import lysholm
from rotorcad.families.narrow_tip import narrow_tip
from rotorcad.families.parameters import Param
from rotorcad.families.rack_involute import rack_involute
from rotorcad.families.registry import FAMILIES, build_family
from rotorcad.families.srm_asymmetric import srm_asymmetric
from rotorcad.families.srm_b import srm_b
from rotorcad.families.srm_symmetric import srm_symmetric

__all__ = [
    "FAMILIES",
    "Param",
    "build_family",
    "check_tips",
    "krigar",
    "lysholm",
    "narrow_tip",
    "rack_involute",
    "srm_asymmetric",
    "srm_b",
    "srm_symmetric",
]

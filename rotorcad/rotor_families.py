"""Old import path of the profile families: they now live in :mod:`rotorcad.families`.

Kept so that ``from rotorcad.rotor_families import build_family`` goes on working; new code
imports from :mod:`rotorcad.families`.
"""

from __future__ import annotations

from rotorcad.families.registry import (
    FAMILIES,
    Param,
    build_family,
    check_tips,
    krigar,
    lysholm,
    narrow_tip,
    rack_involute,
    srm_asymmetric,
    srm_b,
    srm_symmetric,
)

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

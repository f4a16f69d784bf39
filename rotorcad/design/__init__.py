"""Designs: how a design file becomes a rotor pair or a gear.

The modules, in the order data flows:

* :mod:`rotorcad.design.reading` -- a user's file read defensively (missing, special, oversized,
  binary files refused in one sentence).
* :mod:`rotorcad.design.files` -- a TOML design (or sweep) file read and checked.
* :mod:`rotorcad.design.schema` -- the tables and keys of a design, checked.
* :mod:`rotorcad.design.labels` -- each parameter's command-line option and design key, so that a
  refusal names what the user typed.
* :mod:`rotorcad.design.rotors` -- a rotor pair's spec (design and given values merged), the pair
  built, Rinder's analysis summarised.
* :mod:`rotorcad.design.gears` -- a gear's spec (:class:`~rotorcad.design.gears.GearSpec`) and the
  gear (and mate) built.

The schema's and the files' names are importable from here too (``from rotorcad.design import
rotor_design, load_rotor_design``), as when this package was the module ``rotorcad/design.py``.
Every refusal is a :class:`rotorcad.errors.DesignError` (a file's: ``InputFileError``).
"""

from rotorcad.design.files import MAX_DESIGN_BYTES, load_gear_design, load_rotor_design, load_toml
from rotorcad.design.schema import (
    DEFLECTION_KEYS,
    EXPORT_KEYS,
    GEAR_KEYS,
    HOUSING_KEYS,
    MATE_KEYS,
    MAX_RADIAL_CLEARANCE,
    NUMBER,
    OPERATING_KEYS,
    PAIR_KEYS,
    POINT_FAMILIES,
    check_table,
    gear_design,
    refuse_huge_integers,
    rotor_design,
)

__all__ = [
    "DEFLECTION_KEYS",
    "EXPORT_KEYS",
    "GEAR_KEYS",
    "HOUSING_KEYS",
    "MATE_KEYS",
    "MAX_DESIGN_BYTES",
    "MAX_RADIAL_CLEARANCE",
    "NUMBER",
    "OPERATING_KEYS",
    "PAIR_KEYS",
    "POINT_FAMILIES",
    "check_table",
    "gear_design",
    "load_gear_design",
    "load_rotor_design",
    "load_toml",
    "refuse_huge_integers",
    "rotor_design",
]

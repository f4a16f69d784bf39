"""Screw-rotor profile families as rack chains.

After Rinder, *Sonderverzahnungen für Schraubenverdichterrotoren*, sec. 1.2 and Figs. 1-6.

Every family returns a :class:`rotorcad.screw_rotors.ScrewRotors`: one rack period travelled in
the direction of motion (+x of the rack frame of CONTRACT.md: x along the pitch line, y > 0 on the
female side). A male lobe is a bulge of the rack to y = h1 (male addendum), a male root a dip to
y = -d1. Of the two flanks of a male lobe, the *sealing* flank (Dichtflanke) is the leading one
(+x side): its meshline runs up to the upper housing cusp; the *driving* flank (Triebflanke) is the
trailing one (-x side).

Modules:

* :mod:`~rotorcad.families.registry` - :data:`FAMILIES` by name (one :func:`register` line each)
  and :func:`build_family`, which checks a design's ``[profile]`` values;
* :mod:`~rotorcad.families.parameters` - how a family declares its parameters (default and range,
  once, in its builder's signature);
* :mod:`~rotorcad.families.corners` - the sharp tip corners' paths the families share;
* :mod:`~rotorcad.families.checks` - :func:`check_tips`, refusing a rack that undercuts its rotor;
* one module per family: ``krigar`` (Fig. 1), ``lysholm`` (Fig. 2), ``srm_symmetric`` (Fig. 3),
  ``srm_asymmetric`` (Fig. 4) and its ``srm_b`` variant, ``narrow_tip`` (Fig. 5),
  ``rack_involute`` (Fig. 6), ``n_rack`` (Stosic's N rack).

The names below are imported on first use (PEP 562).
"""

from __future__ import annotations

from rotorcad.lazy import lazy_names

_API = {
    "FAMILIES": "rotorcad.families.registry",
    "Family": "rotorcad.families.registry",
    "build_family": "rotorcad.families.registry",
    "register": "rotorcad.families.registry",
    "check_tips": "rotorcad.families.checks",
    "Allowed": "rotorcad.families.parameters",
    "Param": "rotorcad.families.parameters",
    "at_least": "rotorcad.families.parameters",
    "between": "rotorcad.families.parameters",
    "parameters_of": "rotorcad.families.parameters",
}

__getattr__, __dir__, __all__ = lazy_names(__name__, _API)

"""Involute gears: closed forms, the rack tool's cut, the sampled outline and the pair in mesh.

Modules, one job each:

* :mod:`rotorcad.gears.formulas` - the closed forms of ISO 21771 (``inv`` and its inverse, the
  transverse and working pressure angles, the shift sum), the one home of the involute function;
* :mod:`rotorcad.gears.tool` - the generating rack tool (:class:`~rotorcad.gears.tool.RackTool`)
  and the closed form of the curve each of its pieces cuts (:class:`~rotorcad.gears.tool.ToolCut`);
* :mod:`rotorcad.gears.tooth` - the generated tooth: its pieces, undercut point, pointed tip,
  and the check that a flank does not sever it;
* :mod:`rotorcad.gears.sampling` - sampling the tooth to a chord tolerance from the curvature;
* :mod:`rotorcad.gears.involute_gear` - :class:`InvoluteGear`: the gear's design values, their
  checks, its dimensions and its outline;
* :mod:`rotorcad.gears.pair` - :class:`GearPair` (centre distance, backlash, contact ratio) and
  :func:`mate_shift`;
* :mod:`rotorcad.gears.allowances` - tooth-thickness allowances (DIN 3967) as the generating rack
  fed in (:func:`~rotorcad.gears.allowances.thinned`) and a pair's backlash from them;
* :mod:`rotorcad.gears.measurements` - span W_k and dimension over pins or balls M_d (ISO 21771);
* :mod:`rotorcad.gears.rack` - :class:`GearRack`, a gear rack part of the ISO 53 basic rack;
* :mod:`rotorcad.gears.features` - the gear as a part (:class:`GearFeatures`: tip chamfer or
  rounding, :mod:`rotorcad.gears.tip_corner`; bore with a DIN 6885-1 keyway,
  :mod:`rotorcad.gears.keys`; hub; herringbone), its meshes :mod:`rotorcad.gears.part_mesh`.

The names below are imported on first use (PEP 562), so that importing the closed forms alone
does not load the envelope engine.
"""

from __future__ import annotations

from rotorcad.lazy import lazy_names

_API = {
    "DEG": "rotorcad.gears.involute_gear",
    "MAX_TEETH": "rotorcad.gears.involute_gear",
    "MODULE_RANGE": "rotorcad.gears.involute_gear",
    "RELATIVE_TOLERANCE": "rotorcad.gears.involute_gear",
    "InvoluteGear": "rotorcad.gears.involute_gear",
    "GearPair": "rotorcad.gears.pair",
    "mate_shift": "rotorcad.gears.pair",
    "tool_tip_radius_limit": "rotorcad.gears.formulas",
    "base_helix_angle": "rotorcad.gears.formulas",
    "ThicknessAllowance": "rotorcad.gears.allowances",
    "thinned": "rotorcad.gears.allowances",
    "pair_backlash": "rotorcad.gears.allowances",
    "GearRack": "rotorcad.gears.rack",
    "GearFeatures": "rotorcad.gears.features",
    "made_features": "rotorcad.gears.features",
    "key_for_bore": "rotorcad.gears.keys",
    "inv": "rotorcad.gears.formulas",
    "inv_inverse": "rotorcad.gears.formulas",
    "shift_sum": "rotorcad.gears.formulas",
    "transverse_pressure_angle": "rotorcad.gears.formulas",
    "working_pressure_angle": "rotorcad.gears.formulas",
}

__getattr__, __dir__, __all__ = lazy_names(__name__, _API)

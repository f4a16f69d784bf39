"""The gear as a part on the command line: its ``[gear]`` features checked, and drawn.

``rotorcad gear`` and ``rotorcad export`` read the features of a gear design (tip chamfer or
rounding, bore, DIN 6885-1 keyway, hub, herringbone; CONTRACT.md) through :func:`part_features`,
which names a refused value by its ``[gear]`` key.
"""

from __future__ import annotations

from typing import Any

from exports.dxf import Drawing
from rotorcad.cli.common import InputError
from rotorcad.design.labels import gear_name
from rotorcad.errors import DesignError
from rotorcad.gears.features import MadeFeatures, made_features


def part_features(params: dict[str, Any], gear: Any) -> MadeFeatures | None:
    """Return the design's features checked against the gear (as made), or None when it asks for none.

    Parameters
    ----------
    params : dict
        From :func:`rotorcad.cli.gear.merge_gear_params` (its spec under ``"_spec"``).
    gear : InvoluteGear
        The gear as made (after its tooth-thickness allowance).

    Raises
    ------
    InputError
        A feature the gear does not allow, naming its ``[gear]`` key and the allowed range.
    """
    spec = params["_spec"]
    asked = spec.features()
    if not asked.any:
        return None
    try:
        return made_features(gear, asked)
    except DesignError as exc:
        raise InputError(exc.sentence(gear_name(exc.param, spec.from_design))) from None


def draw_features(drawing: Drawing, features: MadeFeatures | None) -> Drawing:
    """Add the bore with its keyway (layer ``BORE``) and the hub's circle (layer ``HUB``) to a drawing.

    The gear's outline itself (with its broken tip corners) is the caller's.
    """
    if features is None:
        return drawing
    solid = features.solid
    if solid.bore_radius > 0:
        drawing.outlines.append(("BORE", features.solid.hole_points(features.gear.tolerance)))
    if solid.hub_radius > 0:
        drawing.circles.append(("HUB", (0.0, 0.0), solid.hub_radius))
    return drawing


__all__ = ["draw_features", "part_features"]

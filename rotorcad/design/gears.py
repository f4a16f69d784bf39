"""An involute gear (and its mate) from a design: the spec, and the gear built from it.

A gear design file (``[gear]``, optional ``[mate]``; CONTRACT.md "Design files") and the values
given beside it (the command's options, a script's arguments) merge into one :class:`GearSpec`:
given values override the file, the ISO 53 basic rack's defaults fill the rest. The spec records
which values are the file's, so that a refusal names the ``[table] key`` the user wrote
(:mod:`rotorcad.design.labels`).
"""

from __future__ import annotations

from dataclasses import dataclass, fields
from typing import Any

import numpy as np

from rotorcad.errors import DesignError, GeometryError, MissingValueError

GEAR_DEFAULTS = {"pressure_angle": 20.0, "helix_angle": 0.0, "shift": 0.0, "addendum": 1.0, "dedendum": 1.25, "tip_radius": 0.38}
"""The ISO 53 basic rack (pressure angle in degrees, factors of the module) and no helix, no shift."""

MATE_FIELDS = {
    "teeth": "mate_teeth",
    "shift": "mate_shift",
    "center_distance": "center_distance",
    "thickness_allowance_upper": "mate_thickness_allowance_upper",
    "thickness_allowance_lower": "mate_thickness_allowance_lower",
}
"""``[mate]`` key -> field of :class:`GearSpec`."""
SHAPER_FIELDS = {
    "teeth": "cutter_teeth",
    "shift": "cutter_shift",
    "tip_radius": "cutter_tip_radius",
    "addendum": "cutter_addendum",
}
"""``[shaper]`` key -> field of :class:`GearSpec` (a design with ``[shaper]`` describes an internal gear)."""
CUTTER_TIP_RADIUS = 0.25
"""Default tip rounding rho_a0* of a shaper cutter, factor of the module."""


@dataclass(frozen=True)
class GearSpec:
    """What builds an involute gear and, with ``mate_teeth``, its mate.

    Attributes
    ----------
    teeth : int
        Number of teeth z.
    module : float, mm
        Normal module m.
    pressure_angle, helix_angle : float, deg
        Of the basic rack; of the helix at the pitch cylinder.
    shift : float
        Profile shift coefficient x, modules.
    addendum, dedendum, tip_radius : float
        Factors of the module: h_aP*, h_fP*, the tool's tip radius rho_a0*.
    face_width : float or None, mm
        For solids.
    mate_teeth : int or None
        Teeth of the mate z2 (None: no mate).
    mate_shift : float or None
        Its profile shift x2 (None: 0, or for zero backlash at ``center_distance``, ISO 21771).
    center_distance : float or None, mm
        Working centre distance a_w (None: zero backlash for the shifts).
    thickness_allowance_upper, thickness_allowance_lower : float, mm
        The gear's tooth-thickness allowances A_sne, A_sni (DIN 3967, normal section, <= 0).
    span_teeth : int or None
        Teeth spanned by the span measurement (None: the standard rule).
    pin_diameter : float or None, mm
        Pins or balls of the dimension over pins (None: the standard rule).
    mate_thickness_allowance_upper, mate_thickness_allowance_lower : float, mm
        The mate's allowances.
    rack_length, rack_height : float or None, mm
        A gear rack of the gear's basic rack (None: no rack), and its height from the back to the
        datum line (None: h_fP* m + 2 m).
    internal : bool
        The gear is an internal (ring) gear cut by a pinion-type shaper cutter (the design's
        ``[shaper]``, the option ``--internal``); the mate is then the pinion inside it.
    outer_diameter : float or None, mm
        The ring's outer diameter (None: the root diameter + 6 m).
    cutter_teeth : int or None
        Teeth z0 of the shaper cutter.
    cutter_shift, cutter_tip_radius : float
        Its profile shift x0 (modules) and tip rounding rho_a0* (factor of the module).
    cutter_addendum : float or None
        Its addendum factor h_a0* (None: the gear's dedendum).
    tip_chamfer, tip_rounding, bore_diameter, keyway, hub_diameter, hub_length, herringbone
        The gear as a part (:class:`rotorcad.gears.features.GearFeatures`; None or False: none).
    from_design : frozenset of str
        The fields whose values are the design file's.
    """

    teeth: int
    module: float
    pressure_angle: float = GEAR_DEFAULTS["pressure_angle"]
    helix_angle: float = GEAR_DEFAULTS["helix_angle"]
    shift: float = GEAR_DEFAULTS["shift"]
    addendum: float = GEAR_DEFAULTS["addendum"]
    dedendum: float = GEAR_DEFAULTS["dedendum"]
    tip_radius: float = GEAR_DEFAULTS["tip_radius"]
    face_width: float | None = None
    mate_teeth: int | None = None
    mate_shift: float | None = None
    center_distance: float | None = None
    thickness_allowance_upper: float = 0.0
    thickness_allowance_lower: float = 0.0
    span_teeth: int | None = None
    pin_diameter: float | None = None
    mate_thickness_allowance_upper: float = 0.0
    mate_thickness_allowance_lower: float = 0.0
    rack_length: float | None = None
    rack_height: float | None = None
    internal: bool = False
    outer_diameter: float | None = None
    cutter_teeth: int | None = None
    cutter_shift: float = 0.0
    cutter_tip_radius: float = CUTTER_TIP_RADIUS
    cutter_addendum: float | None = None
    tip_chamfer: float | None = None
    tip_rounding: float | None = None
    bore_diameter: float | None = None
    keyway: bool = False
    hub_diameter: float | None = None
    hub_length: float | None = None
    herringbone: bool = False
    from_design: frozenset[str] = frozenset()

    def features(self) -> Any:
        """Return the gear's features as a part (:class:`rotorcad.gears.features.GearFeatures`)."""
        from rotorcad.gears.features import FEATURE_FIELDS, GearFeatures

        return GearFeatures(**{f: getattr(self, f) for f in FEATURE_FIELDS})


VALUE_FIELDS = tuple(f.name for f in fields(GearSpec) if f.name != "from_design")
"""The fields of :class:`GearSpec` that hold values."""


RACK_FIELDS = {"length": "rack_length", "height": "rack_height"}
"""``[rack]`` key -> field of :class:`GearSpec`."""


def gear_spec(design: dict[str, dict[str, Any]] | None = None, given: dict[str, Any] | None = None) -> GearSpec:
    """Merge a checked gear design with the values given beside it.

    Parameters
    ----------
    design : dict, optional
        ``{"gear": {...}, "mate": {...}}`` as :func:`rotorcad.design.schema.gear_design` returns it
        (with ``"shaper"``: an internal gear).
    given : dict, optional
        Values by field name (None: not given); they override the design's. Angles in degrees.

    Returns
    -------
    GearSpec

    Raises
    ------
    MissingValueError
        No ``teeth`` or ``module`` from either source (its ``param`` names the field).
    """
    values: dict[str, Any] = {}
    from_design: set[str] = set()
    if design is not None:
        for key, value in design["gear"].items():
            values[key.removesuffix("_deg")] = value
            from_design.add(key.removesuffix("_deg"))
        for key, value in design.get("mate", {}).items():
            values[MATE_FIELDS[key]] = value
            from_design.add(MATE_FIELDS[key])
        for key, value in design.get("rack", {}).items():
            values[RACK_FIELDS[key]] = value
            from_design.add(RACK_FIELDS[key])
        for key, value in design.get("shaper", {}).items():
            values[SHAPER_FIELDS[key]] = value
            from_design.add(SHAPER_FIELDS[key])
        if "shaper" in design:
            values["internal"] = True
    for key, value in (given or {}).items():
        if value is not None and key in VALUE_FIELDS:
            values[key] = value
            from_design.discard(key)
    for key in ("teeth", "module"):
        if values.get(key) is None:
            raise MissingValueError(key)
    return GearSpec(**values, from_design=frozenset(from_design))


def build_gear(spec: GearSpec, tolerance: float) -> tuple[Any, Any]:
    """Build the gear of a spec, and its mate when one is described.

    Parameters
    ----------
    spec : GearSpec
        What to build.
    tolerance : float, mm
        Chord tolerance of the outlines.

    Returns
    -------
    gear : InvoluteGear
        The gear.
    pair : GearPair or None
        The gear with its mate (the mate's shift given, zero, or for zero backlash at the centre
        distance, ISO 21771), None without a mate.

    Raises
    ------
    DesignError
        A gear that cannot be made (its parameter as :class:`rotorcad.gear.InvoluteGear` names it);
        a mate or pair that cannot be made (``mate.PARAM``); a centre distance or mate shift
        without mate teeth (:class:`MissingValueError` ``mate.teeth``).
    GeometryError
        Flanks that never meet (``param`` ``contact_ratio``): :func:`check_contact`.
    """
    from rotorcad.gear import DEG, GearPair, InvoluteGear, mate_shift
    from rotorcad.rotor_pair import LENGTH_RANGE, MAX_LENGTH

    common = {
        "module": spec.module,
        "pressure_angle": spec.pressure_angle * DEG,
        "helix_angle": spec.helix_angle * DEG,
        "addendum": spec.addendum,
        "dedendum": spec.dedendum,
        "tip_radius_factor": spec.tip_radius,
        "tolerance": tolerance,
    }
    gear = InvoluteGear(teeth=spec.teeth, shift=spec.shift, **common)
    z2, a = spec.mate_teeth, spec.center_distance
    if z2 is None:
        if a is not None or spec.mate_shift is not None:
            raise MissingValueError("mate.teeth", "given with the centre distance or the mate's shift")
        return gear, None
    try:
        if not isinstance(z2, int) or z2 < 3:
            raise DesignError("teeth", "a whole number of at least 3", z2)
        if a is not None and not (np.isfinite(a) and 0 < a <= MAX_LENGTH):  # before the mate's shift is solved from it
            raise DesignError("center_distance", LENGTH_RANGE, a)
        x2 = spec.mate_shift
        if x2 is None:
            x2 = 0.0 if a is None else mate_shift(gear, z2, a)
        pair = GearPair(gear, InvoluteGear(teeth=z2, shift=x2, **common), a)
    except DesignError as exc:
        raise type(exc)(f"mate.{exc.param}", exc.allowed, exc.value, exc.detail) from None
    check_contact(pair.contact_ratio, "contact_ratio")
    return gear, pair


def shop_values(spec: GearSpec, gear: Any, pair: Any) -> tuple[dict[str, Any], Any, Any]:
    """Return the measurements that check a spec's tooth-thickness allowances, and the gears as made.

    Parameters
    ----------
    spec : GearSpec
        The spec (its allowances, ``span_teeth`` and ``pin_diameter``).
    gear : InvoluteGear
        The nominal gear (:func:`build_gear`).
    pair : GearPair or None
        The nominal pair.

    Returns
    -------
    values : dict
        :func:`rotorcad.gears.measurements.measurements` of the gear, under ``"mate"`` those of the
        mate, and with a pair ``backlash_circumferential`` and ``backlash_normal``
        (:func:`rotorcad.gears.allowances.pair_backlash`).
    made, made_mate : InvoluteGear
        The gear and the mate (None without) cut at the middle of their tolerance fields
        (:func:`rotorcad.gears.allowances.thinned`): the outlines written to files.

    Raises
    ------
    DesignError
        An allowance, span count or pin diameter that cannot be used, naming the spec's field
        (``mate.thickness_allowance_upper`` ... for the mate's).
    """
    from rotorcad.gears.allowances import ThicknessAllowance, pair_backlash, thinned
    from rotorcad.gears.measurements import measurements

    def made(g: Any, allowance: ThicknessAllowance) -> Any:
        for a in (allowance.lower, allowance.mean):  # the thinnest tooth first: it refuses first
            try:
                out = thinned(g, a)
            except DesignError as exc:
                raise DesignError("thickness_allowance_lower", exc.allowed, allowance.lower, exc.detail) from None
        return out

    own = ThicknessAllowance(spec.thickness_allowance_upper, spec.thickness_allowance_lower)
    values = measurements(gear, own, spec.span_teeth, spec.pin_diameter)
    made_gear = made(gear, own)
    if pair is None:
        return values, made_gear, None
    other = ThicknessAllowance(spec.mate_thickness_allowance_upper, spec.mate_thickness_allowance_lower)
    try:
        values["mate"] = measurements(pair.mate, other)
        made_mate = made(pair.mate, other)
    except DesignError as exc:
        raise type(exc)(f"mate.{exc.param}", exc.allowed, exc.value, exc.detail) from None
    backlash = pair_backlash(pair, own, other)
    values["backlash_circumferential"] = backlash["circumferential"]
    values["backlash_normal"] = backlash["normal"]
    return values, made_gear, made_mate


def build_internal(spec: GearSpec, tolerance: float) -> tuple[Any, Any]:
    """Build the internal gear of a spec (cut by its shaper cutter), and the pinion in mesh when one is described.

    Parameters
    ----------
    spec : GearSpec
        An internal spec (``internal``; ``cutter_teeth`` required): the internal gear's teeth, shift,
        addendum and outer diameter, the cutter's; the mate is the pinion (ISO 53 rack-cut, the
        spec's addendum, dedendum and tool tip radius).
    tolerance : float, mm
        Chord tolerance of the outlines.

    Returns
    -------
    ring : InternalGear
    pair : InternalPair or None
        The pinion inside the ring (its shift given, zero, or for zero backlash at the centre
        distance), None without a mate.

    Raises
    ------
    MissingValueError
        No ``cutter_teeth``; a centre distance or mate shift without mate teeth (``mate.teeth``).
    DesignError
        A cutter, ring or pinion that cannot be made (the pinion's parameters as ``mate.PARAM``);
        an interfering pair (:class:`rotorcad.gears.internal_pair.InternalPair`); flanks that never
        meet (``contact_ratio``).
    """
    from rotorcad.gears.internal_gear import InternalGear
    from rotorcad.gears.internal_pair import InternalPair, internal_mate_shift
    from rotorcad.gears.involute_gear import DEG, InvoluteGear
    from rotorcad.gears.shaper import ShaperCutter
    from rotorcad.rotor_pair import LENGTH_RANGE, MAX_LENGTH

    if spec.cutter_teeth is None:
        raise MissingValueError("cutter_teeth", "for an internal gear")
    angles = {"pressure_angle": spec.pressure_angle * DEG, "helix_angle": spec.helix_angle * DEG}
    try:
        cutter = ShaperCutter(
            teeth=spec.cutter_teeth,
            module=spec.module,
            shift=spec.cutter_shift,
            addendum=spec.dedendum if spec.cutter_addendum is None else spec.cutter_addendum,
            tip_radius_factor=spec.cutter_tip_radius,
            **angles,
        )
    except DesignError as exc:
        if exc.param != "cutter_addendum" or spec.cutter_addendum is not None:
            raise
        # the cutter's addendum is the gear's dedendum when not given: name what the user typed
        detail = exc.detail or "the shaper cutter's addendum is the dedendum when not given"
        raise type(exc)("dedendum", exc.allowed, spec.dedendum, detail) from None
    ring = InternalGear(
        spec.teeth,
        spec.module,
        cutter,
        shift=spec.shift,
        addendum=spec.addendum,
        outer_diameter=spec.outer_diameter,
        tolerance=tolerance,
    )
    z1, a = spec.mate_teeth, spec.center_distance
    if z1 is None:
        if a is not None or spec.mate_shift is not None:
            raise MissingValueError("mate.teeth", "given with the centre distance or the mate's shift")
        return ring, None
    try:
        if not isinstance(z1, int) or not 3 <= z1 < spec.teeth:
            raise DesignError("teeth", f"a whole number from 3 to {spec.teeth - 1} (fewer than the internal gear's)", z1)
        if a is not None and not (np.isfinite(a) and 0 < a <= MAX_LENGTH):
            raise DesignError("center_distance", LENGTH_RANGE, a)
        x1 = spec.mate_shift
        if x1 is None:
            x1 = 0.0 if a is None else internal_mate_shift(ring, z1, a)
            if a is not None and not -2.0 <= x1 <= 3.0:  # the pinion's shift the centre distance asks for
                raise DesignError(
                    "center_distance",
                    f"one that a pinion with a shift from -2 to 3 modules meets at zero backlash (this one needs {x1:.4g})",
                    a,
                )
        pinion = InvoluteGear(
            teeth=z1,
            module=spec.module,
            shift=x1,
            addendum=spec.addendum,
            dedendum=spec.dedendum,
            tip_radius_factor=spec.tip_radius,
            tolerance=tolerance,
            **angles,
        )
    except DesignError as exc:
        raise type(exc)(f"mate.{exc.param}", exc.allowed, exc.value, exc.detail) from None
    try:
        pair = InternalPair(pinion, ring, a)
    except DesignError as exc:
        if exc.param != "center_distance":
            raise
        raise type(exc)("mate.center_distance", exc.allowed, exc.value, exc.detail) from None
    check_contact(pair.contact_ratio, "contact_ratio")
    return ring, pair


def build_rack(spec: GearSpec, tolerance: float) -> Any:
    """Build the gear rack of a spec: the gear's basic rack (module, angles, addendum, dedendum, fillet).

    Parameters
    ----------
    spec : GearSpec
        The spec (``rack_length``, ``rack_height``).
    tolerance : float, mm
        Chord tolerance of the outline.

    Returns
    -------
    GearRack or None
        :class:`rotorcad.gears.rack.GearRack`; None without ``rack_length``.

    Raises
    ------
    DesignError
        A rack that cannot be made, naming ``rack_length``, ``rack_height`` or the gear's parameter.
    """
    if spec.rack_length is None:
        if spec.rack_height is not None:
            raise MissingValueError("rack_length", "given with the rack's height")
        return None
    from rotorcad.gears.involute_gear import DEG
    from rotorcad.gears.rack import GearRack

    return GearRack(
        length=spec.rack_length,
        module=spec.module,
        pressure_angle=spec.pressure_angle * DEG,
        helix_angle=spec.helix_angle * DEG,
        addendum=spec.addendum,
        dedendum=spec.dedendum,
        root_radius_factor=spec.tip_radius,
        height=spec.rack_height,
        tolerance=tolerance,
    )


def check_contact(eps: float, label: str) -> None:
    """Refuse a pair whose flanks never meet (contact ratio 0 or undefined) instead of reporting it.

    Parameters
    ----------
    eps : float
        The pair's transverse contact ratio.
    label : str
        The parameter (or the options) that set it, for the sentence.

    Raises
    ------
    GeometryError
        A contact ratio that is not above 0.
    """
    if not (np.isfinite(eps) and eps > 0.0):
        raise GeometryError(
            label,
            f"chosen so that the flanks meet (a contact ratio above 0; got {eps:g})",
            None,
            "the tips do not reach the usable involute of the mate; raise the addendum, the shifts or the pressure angle",
        )

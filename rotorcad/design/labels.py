"""One table: each library parameter of a design, its command-line option and its design-file key.

A refusal raised by the library names its own parameter (:attr:`rotorcad.errors.DesignError.param`,
e.g. ``tip_radius_factor``); the command line names what the user typed: the option if the value
came from one (``--tip-radius``), the design file's ``[table] key`` if it came from the file
(``[gear] tip_radius``). Both names of every parameter are written here once; the commands keep
their option names, the design files their keys (CONTRACT.md).
"""

from __future__ import annotations

from collections.abc import Collection
from dataclasses import dataclass


@dataclass(frozen=True)
class Label:
    """The two names of a design value.

    Attributes
    ----------
    field : str
        The name of the value in the spec (:class:`rotorcad.design.gears.GearSpec`,
        :class:`rotorcad.design.rotors.PairSpec`'s pair), where it has one.
    option : str
        The command-line option that gives it.
    key : str or None
        The design file's ``[table] key`` that gives it (None: an option only).
    """

    field: str
    option: str
    key: str | None


def _pair_label(name: str) -> Label:
    return Label(name, "--" + name.replace("_", "-"), f"[pair] {name}")


PAIR_FIELDS = (
    "male_teeth",
    "female_teeth",
    "center_distance",
    "male_tip_radius",
    "male_root_radius",
    "female_tip_radius",
    "female_root_radius",
    "lead",
    "length",
)
"""The dimensions of a rotor pair given by options or ``[pair]`` keys of the same names."""

PAIR_LABELS: dict[str, Label] = {
    **{name: _pair_label(name) for name in PAIR_FIELDS},
    "hand": Label("hand", "[pair] hand", "[pair] hand"),  # no option: only a design gives it
    "speed_rpm": Label("speed_rpm", "--speed", "[operating] speed_rpm"),
    "smoothing": Label("smoothing", "--smoothing", "[profile] smoothing"),
}
"""Library parameter of a rotor pair's errors -> its names (:class:`rotorcad.rotor_pair.RotorPair`,
:func:`rotorcad.design.rotors.pair_spec`)."""

POINTS_PARAMS = ("male points", "female points", "rack points")
"""How the library names the points of a points family in its errors."""

GEAR_LABELS: dict[str, Label] = {
    "teeth": Label("teeth", "--teeth", "[gear] teeth"),
    "module": Label("module", "--module", "[gear] module"),
    "pressure_angle": Label("pressure_angle", "--pressure-angle", "[gear] pressure_angle_deg"),
    "helix_angle": Label("helix_angle", "--helix-angle", "[gear] helix_angle_deg"),
    "shift": Label("shift", "--shift", "[gear] shift"),
    "addendum": Label("addendum", "--addendum", "[gear] addendum"),
    "dedendum": Label("dedendum", "--dedendum", "[gear] dedendum"),
    "tip_radius_factor": Label("tip_radius", "--tip-radius", "[gear] tip_radius"),
    "face_width": Label("face_width", "--face-width", "[gear] face_width"),
    "tolerance": Label("tolerance", "--tolerance", None),
    "center_distance": Label("center_distance", "--center-distance", None),
    "radius": Label("radius", "radius", None),
    "thickness_allowance_upper": Label(
        "thickness_allowance_upper", "--thickness-allowance-upper", "[gear] thickness_allowance_upper"
    ),
    "thickness_allowance_lower": Label(
        "thickness_allowance_lower", "--thickness-allowance-lower", "[gear] thickness_allowance_lower"
    ),
    "span_teeth": Label("span_teeth", "--span-teeth", "[gear] span_teeth"),
    "pin_diameter": Label("pin_diameter", "--pin-diameter", "[gear] pin_diameter"),
    "rack_length": Label("rack_length", "--rack", "[rack] length"),
    "rack_height": Label("rack_height", "--rack-height", "[rack] height"),
    "outer_diameter": Label("outer_diameter", "--outer-diameter", "[gear] outer_diameter"),
    "cutter_teeth": Label("cutter_teeth", "--cutter-teeth", "[shaper] teeth"),
    "cutter_shift": Label("cutter_shift", "--cutter-shift", "[shaper] shift"),
    "cutter_tip_radius": Label("cutter_tip_radius", "--cutter-tip-radius", "[shaper] tip_radius"),
    "cutter_addendum": Label("cutter_addendum", "--cutter-addendum", "[shaper] addendum"),
    **{f: Label(f, f"[gear] {f}", f"[gear] {f}") for f in ("tip_chamfer", "tip_rounding", "bore_diameter")},
    **{f: Label(f, f"[gear] {f}", f"[gear] {f}") for f in ("keyway", "hub_diameter", "hub_length", "herringbone")},
    "mate.teeth": Label("mate_teeth", "--mate-teeth", "[mate] teeth"),
    "mate.thickness_allowance_upper": Label(
        "mate_thickness_allowance_upper", "--mate-thickness-allowance-upper", "[mate] thickness_allowance_upper"
    ),
    "mate.thickness_allowance_lower": Label(
        "mate_thickness_allowance_lower", "--mate-thickness-allowance-lower", "[mate] thickness_allowance_lower"
    ),
    "mate.shift": Label("mate_shift", "--mate-shift", "[mate] shift"),
    "mate.center_distance": Label("center_distance", "--center-distance", "[mate] center_distance"),
    "mate.shifts": Label("shifts", "--shift and --mate-shift", None),
    "mate.mesh": Label("mesh", "--teeth, --mate-teeth, --shift, --mate-shift, --addendum and --pressure-angle", None),
}
"""Library parameter of a gear's errors -> its names. The errors of the mate (and of the pair) come
qualified ``mate.PARAM`` (:func:`rotorcad.design.gears.build_gear`)."""

GEAR_FIELD_LABELS: dict[str, Label] = {label.field: label for label in GEAR_LABELS.values() if label.key}
"""Field of :class:`rotorcad.design.gears.GearSpec` -> its names (the fields a design file gives)."""

CONTACT_FIELDS = ("teeth", "mate_teeth", "shift", "mate_shift", "addendum", "pressure_angle")
"""The values that set whether a gear pair's flanks meet, in the order a refusal names them (the
centre distance, when given, after the mate's teeth)."""


def name(label: Label | None, param: str, from_design: bool) -> str:
    """Return what the user typed for a parameter: the design key if the file gave it, else the option.

    Parameters
    ----------
    label : Label or None
        The parameter's row of a table (None: not in the table).
    param : str
        The library's name, said when the table has no row (a ``mate.`` qualifier dropped).
    from_design : bool
        Whether the value in force came from the design file.

    Returns
    -------
    str
    """
    if label is None:
        return param.removeprefix("mate.")
    return label.key if from_design and label.key else label.option


def gear_name(param: str, from_design: Collection[str]) -> str:
    """Return the option or design key that gave a gear's (or its mate's) parameter.

    Parameters
    ----------
    param : str
        The library's name (:attr:`rotorcad.errors.DesignError.param`; ``mate.PARAM`` for the mate).
    from_design : collection of str
        The spec's fields whose values came from the design file.

    Returns
    -------
    str
    """
    label = GEAR_LABELS.get(param)
    return name(label, param, label is not None and label.field in from_design)


def contact_names(from_design: Collection[str], center_distance: bool) -> str:
    """Return the values that set whether a gear pair's flanks meet, as the user gave them.

    Parameters
    ----------
    from_design : collection of str
        The spec's fields whose values came from the design file.
    center_distance : bool
        Whether a centre distance was given (it sets the mesh too).

    Returns
    -------
    str
        E.g. ``"--teeth, --mate-teeth, --shift, --mate-shift, --addendum and --pressure-angle"``.
    """
    names = [name(GEAR_FIELD_LABELS[f], f, f in from_design) for f in CONTACT_FIELDS]
    if center_distance:
        names.insert(2, name(GEAR_LABELS["mate.center_distance"], "center_distance", "center_distance" in from_design))
    return ", ".join(names[:-1]) + " and " + names[-1]


def required(label: Label) -> str:
    """Return the sentence for a value given neither as an option nor in the design file.

    Parameters
    ----------
    label : Label

    Returns
    -------
    str
        ``"--teeth is required (or a design file with [gear] teeth)."``
    """
    return f"{label.option} is required (or a design file with {label.key})."


@dataclass(frozen=True)
class PairNames:
    """Where the values of a rotor pair came from, to name them as the user gave them.

    Attributes
    ----------
    design : bool
        Whether a design file was given.
    options : frozenset of str
        The library names of the values given as options (``male_teeth``, ``speed_rpm``, ...).
    source : str or None
        The points family whose points an option gave (``male-points``), or None.
    params : frozenset of str
        The profile family's parameters (the design's ``[profile]`` keys).
    """

    design: bool
    options: frozenset[str] = frozenset()
    source: str | None = None
    params: frozenset[str] = frozenset()

    def __call__(self, param: str, family: str | None = None) -> str | None:
        """Return the option or design key that gave ``param`` (None: say the library's name).

        Parameters
        ----------
        param : str
            The library's name of the parameter in an error.
        family : str, optional
            The profile family (for the points: ``--male-points`` or ``[profile] points``).
        """
        profile = self.design and self.source is None  # the profile is the design file's
        if param in POINTS_PARAMS:
            return "[profile] points" if profile else f"--{family}"
        label = PAIR_LABELS.get(param)
        if label is not None:
            return name(label, param, self.design and param not in self.options)
        if profile and (param in ("family", "points") or param in self.params):
            return f"[profile] {param}"
        return None

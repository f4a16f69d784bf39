"""Design files (TOML, CONTRACT.md "Design files"): checking the mapping a file holds.

This module checks mappings only; :mod:`rotorcad.design.files` opens and reads the files.
Unknown keys are an error naming the key, so a typo never passes silently. Angles are given in
degrees in keys ending in ``_deg``. Every refusal is an :class:`rotorcad.errors.InputFileError`.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

from rotorcad.errors import InputFileError

NUMBER = (int, float)

GEAR_KEYS: dict[str, type | tuple[type, ...]] = {
    "teeth": int,
    "module": NUMBER,
    "pressure_angle_deg": NUMBER,
    "helix_angle_deg": NUMBER,
    "shift": NUMBER,
    "addendum": NUMBER,
    "dedendum": NUMBER,
    "tip_radius": NUMBER,
    "face_width": NUMBER,  # mm, for solids (rotorcad export)
    "thickness_allowance_upper": NUMBER,  # mm, DIN 3967 A_sne (normal section, <= 0)
    "thickness_allowance_lower": NUMBER,  # mm, DIN 3967 A_sni
    "span_teeth": int,  # teeth spanned by the span measurement (default: the standard rule)
    "pin_diameter": NUMBER,  # mm, pins or balls of the dimension over pins (default: the standard rule)
    "outer_diameter": NUMBER,  # mm, outer diameter of an internal gear's ring (with [shaper])
    # the gear as a part (rotorcad/gears/features.py): tip corners, bore, DIN 6885-1 keyway, hub, herringbone
    "tip_chamfer": NUMBER,  # mm, radial height h_K of a chamfer of the tip corners
    "tip_rounding": NUMBER,  # mm, radius r_K of a rounding of the tip corners
    "bore_diameter": NUMBER,  # mm
    "keyway": bool,  # a hub keyway of the bore's DIN 6885-1 key
    "hub_diameter": NUMBER,  # mm
    "hub_length": NUMBER,  # mm, on the face z = 0
    "herringbone": bool,  # two helical halves of opposite hands
}
MATE_KEYS: dict[str, type | tuple[type, ...]] = {
    "teeth": int,
    "shift": NUMBER,
    "center_distance": NUMBER,
    "thickness_allowance_upper": NUMBER,
    "thickness_allowance_lower": NUMBER,
}


RACK_KEYS: dict[str, type | tuple[type, ...]] = {"length": NUMBER, "height": NUMBER}
SHAPER_KEYS: dict[str, type | tuple[type, ...]] = {"teeth": int, "shift": NUMBER, "tip_radius": NUMBER, "addendum": NUMBER}
"""``[shaper]`` of a gear design: the pinion-type shaper cutter that makes ``[gear]`` an internal gear
(teeth z0, shift x0, tip rounding rho_a0* and addendum h_a0*, factors of the module)."""
"""``[rack]`` of a gear design: a gear rack of the gear's basic rack, length and height to the datum line, mm."""


def check_table(
    data: dict[str, Any], table: str, keys: dict[str, type | tuple[type, ...]], required: tuple[str, ...] = ()
) -> dict[str, Any]:
    """Validate one table of a design: known keys, right types, required keys present.

    Parameters
    ----------
    data : dict
        The design as a TOML file holds it.
    table : str
        Name of the table (``"pair"``, ``"gear"``, ...); a missing table is empty.
    keys : dict
        Allowed keys and the type (or types) of each.
    required : tuple of str
        Keys that must be given.

    Returns
    -------
    dict
        A copy of the table.

    Raises
    ------
    InputFileError
        A table that is not a table, an unknown key, a value of the wrong type (a bool is never a
        number) or a missing required key.
    """
    section = data.get(table, {})
    if not isinstance(section, dict):
        raise InputFileError(f"[{table}]", "a table of keys", type(section).__name__)
    for key, value in section.items():
        if key not in keys:
            raise InputFileError(f"key '{key}' in [{table}]", "one of " + ", ".join(sorted(keys)), None, "unknown key")
        expected = keys[key]
        if (isinstance(value, bool) and expected is not bool) or not isinstance(value, expected):
            kinds = {int: "a whole number", list: "a list", str: "a text in quotes", bool: "true or false"}
            kind = kinds.get(expected, "a number")
            raise InputFileError(f"[{table}] {key}", kind, repr(value))
    section = dict(section)
    for key, value in section.items():  # a number as a float: an integer beyond float range is refused
        if isinstance(value, int) and not isinstance(value, bool) and keys[key] in (NUMBER, int):
            try:
                number = float(value)
                if keys[key] == NUMBER:
                    section[key] = number
            except OverflowError:
                raise InputFileError(
                    f"[{table}] {key}",
                    "a number within the range of a float (below 1.8e308)"
                    if keys[key] == NUMBER
                    else "a whole number below 1.8e308",
                    f"an integer of {int(value.bit_length() * 0.30103) + 1} digits",
                ) from None
    for key in required:
        if key not in section:
            raise InputFileError(f"[{table}] {key}", "given", None, "missing key")
    return section


def refuse_huge_integers(data: dict[str, Any]) -> None:
    """Refuse any integer of a design beyond float range, in any table (a family's ``[profile]`` too).

    Parameters
    ----------
    data : dict
        The design as a TOML file holds it.

    Raises
    ------
    InputFileError
        Naming the ``[table] key`` of the first such integer.
    """
    for table, section in data.items():
        for key, value in section.items() if isinstance(section, dict) else ():
            if isinstance(value, int) and not isinstance(value, bool) and abs(value).bit_length() > 1023:
                digits = int(value.bit_length() * 0.30103) + 1
                raise InputFileError(f"[{table}] {key}", "a number below 1.8e308", f"an integer of {digits} digits")


def gear_design(data: dict[str, Any]) -> dict[str, dict[str, Any]]:
    """Check a gear design mapping (CONTRACT.md "Design files").

    Parameters
    ----------
    data : dict
        The design as a TOML file holds it: ``[gear]`` (required keys teeth, module), an
        optional ``[mate]``, ``[rack]`` and ``[shaper]`` (an internal gear's cutter).

    Returns
    -------
    dict
        ``{"gear": {...}, "mate": {...}}`` (the mate empty if not given), with ``"rack"`` and
        ``"shaper"`` when given; lengths in mm, angles in degrees as given.

    Raises
    ------
    InputFileError
        Naming the table or key that is wrong.
    """
    refuse_huge_integers(data)
    for table in data:
        if table not in ("gear", "mate", "rack", "shaper"):
            raise InputFileError(
                f"table [{table}]", "one of [gear], [mate], [rack], [shaper] in a gear design", None, "unknown table"
            )
    gear = check_table(data, "gear", GEAR_KEYS, required=("teeth", "module"))
    mate = check_table(data, "mate", MATE_KEYS) if "mate" in data else {}
    out = {"gear": gear, "mate": mate}
    if "rack" in data:  # a gear rack of the gear's basic rack
        out["rack"] = check_table(data, "rack", RACK_KEYS, required=("length",))
    if "shaper" in data:  # [gear] is an internal gear cut by this shaper cutter
        out["shaper"] = check_table(data, "shaper", SHAPER_KEYS, required=("teeth",))
    return out


PAIR_KEYS: dict[str, type | tuple[type, ...]] = {
    "male_teeth": int,
    "female_teeth": int,
    "center_distance": NUMBER,
    "male_tip_radius": NUMBER,
    "male_root_radius": NUMBER,
    "female_tip_radius": NUMBER,
    "female_root_radius": NUMBER,
    "lead": NUMBER,
    "length": NUMBER,
    "hand": str,
}
MAX_RADIAL_CLEARANCE = 10.0
"""Largest radial clearance of the housing bores, mm (rotor clearances are tenths of a mm)."""
HOUSING_KEYS: dict[str, type | tuple[type, ...]] = {"radial_clearance": NUMBER}
OPERATING_KEYS: dict[str, type | tuple[type, ...]] = {
    "speed_rpm": NUMBER,
    "suction_pressure_bar": NUMBER,
    "discharge_pressure_bar": NUMBER,
    "polytropic_exponent": NUMBER,  # rotorcad deflect: compression p V^n = const
    "volume_ratio": NUMBER,  # built-in volume ratio V_i fixing the discharge port's control edge
    "discharge_edge_deg": NUMBER,  # or the control edge as a chamber angle (male rotation since it opened)
    "indicator": str,  # or an indicator diagram: CSV "angle_deg,pressure_bar" over the chamber angle
}
DEFLECTION_KEYS: dict[str, type | tuple[type, ...]] = {
    "young_modulus": NUMBER,  # N/mm^2
    "poisson_ratio": NUMBER,
    "terms": int,  # sine terms of the Ritz-Galerkin series
    "male_shaft_discharge": list,  # [[length, diameter], ...] mm, from the end face to the bearing
    "male_shaft_suction": list,
    "female_shaft_discharge": list,
    "female_shaft_suction": list,
}
EXPORT_KEYS: dict[str, type | tuple[type, ...]] = {"tolerance": NUMBER, "formats": list}
POINT_FAMILIES = ("rack-points", "male-points", "female-points")


def rotor_design(data: dict[str, Any], folder: Path | str | None = None) -> dict[str, Any]:
    """Check a screw-rotor design mapping (CONTRACT.md "Design files").

    Tables: [pair], [profile] (family and its parameters, or a points file), optional [housing],
    [operating], [deflection], [export]. Numbers of [pair], [profile] and [housing] may be stated
    as expressions of the centre distance and tooth counts (:mod:`rotorcad.linked_values`).

    Parameters
    ----------
    data : dict
        The design as a TOML file holds it.
    folder : path, optional
        Where a relative points file name is found (the design file's folder); default the
        current folder.

    Returns
    -------
    dict
        ``pair``, ``family``, ``params`` (the family's parameters), ``points`` (the resolved path
        of a points file, or None), ``smoothing`` (mm², or None), ``housing``, ``operating``,
        ``deflection``, ``export``; lengths in mm, angles in degrees as given.

    Raises
    ------
    InputFileError
        Naming the table or key that is wrong (unknown, of the wrong type, missing or out of
        range).
    """
    refuse_huge_integers(data)

    from rotorcad.linked_values import resolve_expressions

    data = resolve_expressions(data)  # values stated as expressions of a, z1, z2 (rotorcad.linked_values)
    for table in data:
        if table not in ("pair", "profile", "housing", "operating", "deflection", "export"):
            allowed = "one of [pair], [profile], [housing], [operating], [deflection], [export]"
            raise InputFileError(f"table [{table}]", allowed, None, "unknown table")
    pair = check_table(data, "pair", PAIR_KEYS, required=tuple(k for k in PAIR_KEYS if k not in ("lead", "length", "hand")))
    profile = dict(data.get("profile", {}))
    if "family" not in profile or not isinstance(profile["family"], str):
        raise InputFileError("[profile] family", "given as a name", None, "missing key")
    family = profile.pop("family")
    points = None
    smoothing = None  # estimated from the points' scatter
    if family in POINT_FAMILIES:
        if not isinstance(profile.get("points"), str):
            raise InputFileError("[profile] points", "a CSV file name for the family " + family, None, "missing key")
        points = (Path(folder or ".") / profile.pop("points")).resolve()
        smoothing = profile.pop("smoothing", None)
        bad = isinstance(smoothing, bool) or not isinstance(smoothing, NUMBER) or not 0 <= smoothing < float("inf")
        if smoothing is not None and bad:
            raise InputFileError("[profile] smoothing", "a number of at least 0 mm^2", repr(smoothing))
        smoothing = None if smoothing is None else float(smoothing)
        if profile:
            raise InputFileError(
                f"key '{next(iter(profile))}' in [profile]", "points or smoothing for a points family", None, "unknown key"
            )
    else:
        for key, value in profile.items():
            if isinstance(value, bool) or not isinstance(value, NUMBER):
                raise InputFileError(f"[profile] {key}", "a number", repr(value))
    housing = check_table(data, "housing", HOUSING_KEYS)
    gap = housing.get("radial_clearance", 0.0)
    if not (0.0 <= gap <= MAX_RADIAL_CLEARANCE):  # also NaN
        raise InputFileError("[housing] radial_clearance", f"a clearance from 0 to {MAX_RADIAL_CLEARANCE:g} mm", gap)
    return {
        "pair": pair,
        "family": family,
        "params": profile,
        "points": points,
        "smoothing": smoothing,
        "housing": housing,
        "operating": check_table(data, "operating", OPERATING_KEYS),
        "deflection": check_table(data, "deflection", DEFLECTION_KEYS),
        "export": check_table(data, "export", EXPORT_KEYS),
    }

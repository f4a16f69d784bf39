"""Values that are legal but look like another unit (an inch design typed as mm, a length in µm).

A new user's design typed in inches (a 5/6 screw pair at a = 3.228 "mm", a gear of module 0.157 mm
for 4 mm) was accepted without a word and computed as a 3-mm compressor. These checks do not refuse:
each returns sentences the command line says on stderr as warnings after a successful run
(:class:`UnitWarning`; CONTRACT.md, "Plausibility"),
naming the option or design key and what the value would be in mm if it was typed in inches.

The ranges are the standards' and the trade's, not rotorcad's limits (those refuse, elsewhere):

- modules: DIN 780 / ISO 54 series I and II, 0.05 to 50 mm (:data:`STANDARD_MODULES`);
- screw compressors: centre distances of the built machines from some 20 mm (small refrigeration
  and automotive superchargers) to some 1000 mm (:data:`SCREW_CENTER_DISTANCE`); from 20 to 28 mm
  (711 mm in inches) only a value whose mm in inches is a whole mm (:func:`inch_center_distance`).
"""

from __future__ import annotations

import numpy as np

from rotorcad.errors import InputNote


class UnitWarning(InputNote):
    """A legal value that looks like another unit: said as ``rotorcad: warning: ...`` after a successful run.

    An :class:`~rotorcad.errors.InputNote` (so that a refusal stays one sentence: a run that ends in
    a refusal says no warning), whose ``label`` the command line prints instead of "note".
    """

    label = "warning"


INCH = 25.4
"""mm per inch."""

STANDARD_MODULES = (
    # DIN 780 below 1 mm, ISO 54 (series I and II) from 1 to 50 mm
    0.05, 0.055, 0.06, 0.07, 0.08, 0.09, 0.1, 0.11, 0.12, 0.14, 0.15, 0.18, 0.2, 0.22, 0.25, 0.28, 0.3, 0.35,
    0.4, 0.45, 0.5, 0.55, 0.6, 0.65, 0.7, 0.75, 0.8, 0.85, 0.9, 0.95, 1.0, 1.125, 1.25, 1.375, 1.5, 1.75, 2.0,
    2.25, 2.5, 2.75, 3.0, 3.5, 4.0, 4.5, 5.0, 5.5, 6.0, 7.0, 8.0, 9.0, 10.0, 11.0, 12.0, 14.0, 16.0, 18.0,
    20.0, 22.0, 25.0, 28.0, 32.0, 36.0, 40.0, 45.0, 50.0,
)  # fmt: skip
"""Standard modules, mm (DIN 780 below 1 mm; ISO 54:1996 series I and II from 1 to 50 mm)."""

INCH_MATCH = 0.005
"""Relative distance within which a value times 25.4 "is" a standard module (0.157 in -> 3.988 mm)."""

SCREW_CENTER_DISTANCE = (20.0, 1500.0)
"""Centre distances of screw-rotor pairs below or above which a warning is said, mm (built
machines: some 20 mm to some 1000 mm; a 5/6 pair of a = 82 mm typed in inches is 3.23). Below
20 mm a machine typed in inches is one of up to 508 mm (it was 10 mm, 254 mm: a new user's 315-510 mm
machines typed in inches, 12.4-20.1, were not warned about)."""

INCH_SIZED = 28.0
"""From the lower bound of :data:`SCREW_CENTER_DISTANCE` to this, mm, a centre distance is taken as
typed in inches only when its value in inches is a whole number of mm (:data:`WHOLE_MM`) and it is not
itself a round 0.1 mm: 28 in is 711 mm, about the largest machines (the trade's oil-flooded and
process compressors reach centre distances of some 500-700 mm); a micro-compressor of a = 25 mm
stays a 25-mm machine."""

WHOLE_MM = 0.02
"""mm: a value in inches whose mm value lies this near a whole mm was converted from a whole mm (a
value typed to 3 decimals in inches is off by at most 0.0127 mm; a random value lands this near by a
chance of 4 %)."""


def inch_center_distance(center_distance: float) -> float | None:
    """Return the centre distance in mm if ``center_distance`` looks typed in inches, else None.

    Parameters
    ----------
    center_distance : float, mm
        The pair's centre distance a as given.

    Returns
    -------
    float or None
        ``a x 25.4`` when a is below :data:`SCREW_CENTER_DISTANCE`'s lower bound (no machine that
        small is built), or below :data:`INCH_SIZED` with ``a x 25.4`` a whole mm (:data:`WHOLE_MM`)
        and a not a round 0.1 mm; None otherwise.
    """
    a = float(center_distance)
    if not (np.isfinite(a) and a > 0):
        return None
    in_mm = a * INCH
    if a < SCREW_CENTER_DISTANCE[0]:
        return in_mm
    round_itself = abs(a * 10 - round(a * 10)) < 1e-9
    if a < INCH_SIZED and abs(in_mm - round(in_mm)) <= WHOLE_MM and not round_itself:
        return in_mm
    return None


def with_inch_hint(sentence: str, center_distance: float, label: str) -> str:
    """Return a refusal about lengths with the inch hint added, still one sentence (newuser7 F5).

    A design typed in inches is usually rounded, and then refused by the pair's own checks (``[pair]
    female_root_radius must be at most 0.9452 mm ...``) before the warning of a successful run.

    Parameters
    ----------
    sentence : str
        The refusal, ending with its stop.
    center_distance : float, mm
        The pair's centre distance as given.
    label : str
        The option or design key that gave it.

    Returns
    -------
    str
        ``sentence`` unchanged unless it names a length in mm and :func:`inch_center_distance`
        takes a as inches; then ``...; LABEL A mm looks like inches (N mm): rotorcad takes every
        length in mm.``
    """
    in_mm = inch_center_distance(center_distance) if isinstance(center_distance, (int, float)) else None
    if in_mm is None or " mm" not in sentence:
        return sentence
    hint = (
        f"{label} {center_distance:g} mm looks like a design typed in inches ({in_mm:.4g} mm): rotorcad takes every length in mm"
    )
    return f"{sentence.rstrip('.')}; {hint}."


def _nearest_standard(value: float) -> tuple[float, float]:
    """Return the standard module nearest ``value`` (mm) and its relative distance."""
    table = np.asarray(STANDARD_MODULES)
    i = int(np.argmin(np.abs(np.log(table / value))))
    return float(table[i]), float(abs(value / table[i] - 1.0))


def module_warnings(module: float, label: str) -> list[str]:
    """Return warnings for a module that looks like another unit (empty: plausible).

    Parameters
    ----------
    module : float, mm
        The normal module as given.
    label : str
        The option or design key that gave it (``--module``, ``[gear] module``).

    Returns
    -------
    list of str
        Sentences without the final stop: a module that is not standard but whose value in inches
        is a standard module of 1 mm or more; one below DIN 780's smallest (0.05 mm) or above
        ISO 54's largest (50 mm).
    """
    if not (np.isfinite(module) and module > 0):
        return []
    out = []
    in_mm, off = _nearest_standard(module * INCH)
    if module < STANDARD_MODULES[-1] / INCH and in_mm >= 1.0 and off <= INCH_MATCH and _nearest_standard(module)[1] > INCH_MATCH:
        out.append(
            f"{label} {module:g} mm is no standard module, but in inches it is {module * INCH:.4g} mm, "
            f"near the standard {in_mm:g} mm: rotorcad takes every length in mm (a design typed in inches?)"
        )
    elif module < STANDARD_MODULES[0]:
        out.append(f"{label} {module:g} mm is below the smallest standard module, 0.05 mm (DIN 780): rotorcad takes mm")
    elif module > STANDARD_MODULES[-1]:
        out.append(f"{label} {module:g} mm is above the largest standard module, 50 mm (ISO 54): rotorcad takes mm, not µm")
    return out


def screw_pair_warnings(center_distance: float, label: str) -> list[str]:
    """Return warnings for a screw-rotor pair whose size looks like another unit (empty: plausible).

    Parameters
    ----------
    center_distance : float, mm
        The pair's centre distance a.
    label : str
        The option or design key that gave it (``[pair] center_distance``, ``--center-distance``).

    Returns
    -------
    list of str
        One sentence without the final stop when a is outside :data:`SCREW_CENTER_DISTANCE` or
        looks typed in inches (:func:`inch_center_distance`).
    """
    lo, hi = SCREW_CENTER_DISTANCE
    if not np.isfinite(center_distance):
        return []
    in_mm = inch_center_distance(center_distance)
    if in_mm is not None and center_distance < lo:
        return [
            f"{label} {center_distance:g} mm is smaller than any screw compressor built (some 20 mm and up); "
            f"in inches it would be {in_mm:.4g} mm: rotorcad takes every length in mm"
        ]
    if in_mm is not None:
        return [
            f"{label} {center_distance:g} mm in inches would be {in_mm:.4g} mm, a whole number of mm as a design "
            "typed in inches gives: rotorcad takes every length in mm"
        ]
    if center_distance > hi:
        return [
            f"{label} {center_distance:g} mm is larger than any screw compressor built (up to some 1000 mm): "
            "rotorcad takes every length in mm (not µm or hundredths)"
        ]
    return []


__all__ = [
    "INCH",
    "SCREW_CENTER_DISTANCE",
    "STANDARD_MODULES",
    "UnitWarning",
    "inch_center_distance",
    "module_warnings",
    "screw_pair_warnings",
    "with_inch_hint",
]

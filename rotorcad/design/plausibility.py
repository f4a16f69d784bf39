"""Values that are legal but look like another unit (an inch design typed as mm, a length in µm).

A new user's design typed in inches (a 5/6 screw pair at a = 3.228 "mm", a gear of module 0.157 mm
for 4 mm) was accepted without a word and computed as a 3-mm compressor. These checks do not refuse:
each returns sentences the command line says on stderr as warnings after a successful run
(:class:`UnitWarning`; CONTRACT.md, "Plausibility"),
naming the option or design key and what the value would be in mm if it was typed in inches.

The ranges are the standards' and the trade's, not rotorcad's limits (those refuse, elsewhere):

- modules: DIN 780 / ISO 54 series I and II, 0.05 to 50 mm (:data:`STANDARD_MODULES`);
- screw compressors: centre distances of the built machines from some 20 mm (small refrigeration
  and automotive superchargers) to some 1000 mm (:data:`SCREW_CENTER_DISTANCE`).
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

SCREW_CENTER_DISTANCE = (10.0, 1500.0)
"""Centre distances of screw-rotor pairs below or above which a warning is said, mm (built
machines: some 20 mm to some 1000 mm; a 5/6 pair of a = 82 mm typed in inches is 3.23)."""


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
        One sentence without the final stop when a is outside :data:`SCREW_CENTER_DISTANCE`.
    """
    lo, hi = SCREW_CENTER_DISTANCE
    if not np.isfinite(center_distance):
        return []
    if center_distance < lo:
        return [
            f"{label} {center_distance:g} mm is smaller than any screw compressor built (some 20 mm and up); "
            f"in inches it would be {center_distance * INCH:.4g} mm: rotorcad takes every length in mm"
        ]
    if center_distance > hi:
        return [
            f"{label} {center_distance:g} mm is larger than any screw compressor built (up to some 1000 mm): "
            "rotorcad takes every length in mm (not µm or hundredths)"
        ]
    return []


__all__ = ["INCH", "SCREW_CENTER_DISTANCE", "STANDARD_MODULES", "UnitWarning", "module_warnings", "screw_pair_warnings"]

"""Flank tolerances of ISO 1328-1:2013, clause 5: the values for a tolerance class from the standard's formulas.

The standard has eleven flank tolerance classes A = 1 (finest) ... 11; the tolerance of class A
is the class-5 value times sqrt(2)^(A - 5), and every value is rounded: above
10 µm to a whole µm, from 5 to 10 µm to 0.5 µm, below 5 µm to 0.1 µm. The totals F_alpha and
F_beta are the root sum of squares of the *unrounded* slope and form values, then rounded.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from rotorcad.errors import DesignError

CLASSES = (1, 11)
"""The flank tolerance classes of ISO 1328-1:2013."""
SCOPE = {"module": (0.5, 70.0), "diameter": (5.0, 15000.0)}
"""ISO 1328-1:2013, clause 1: normal module and reference diameter (mm) the formulas hold for."""


def round_tolerance(value_um: float) -> float:
    """Round a tolerance as ISO 1328-1:2013, clause 5, does.

    Parameters
    ----------
    value_um : float, µm
        The unrounded tolerance.

    Returns
    -------
    float, µm
        Above 10 µm: to a whole µm; from 5 to 10 µm: to 0.5 µm; below 5 µm: to 0.1 µm (halves away
        from zero).
    """

    def half_up(x: float) -> float:
        return math.floor(x + 0.5)

    if value_um > 10.0:
        return float(half_up(value_um))
    if value_um >= 5.0:
        return half_up(value_um * 2.0) / 2.0
    return half_up(value_um * 10.0) / 10.0


@dataclass(frozen=True)
class FlankTolerances:
    """The flank tolerances of one gear for one class (ISO 1328-1:2013, eqs. 5 to 9), mm, rounded.

    Attributes
    ----------
    tolerance_class : int
        A, from 1 to 11.
    single_pitch, cumulative_pitch : float, mm
        f_pT (eq. 5), F_pT (eq. 6).
    profile_slope, profile_form, total_profile : float, mm
        f_HalphaT (eq. 7, a +- limit), f_falphaT (eq. 8), F_alphaT (eq. 9).
    in_scope : bool
        Whether module and diameter lie within :data:`SCOPE` (outside, the standard says the
        values are to be agreed, not extrapolated).
    """

    tolerance_class: int
    single_pitch: float
    cumulative_pitch: float
    profile_slope: float
    profile_form: float
    total_profile: float
    in_scope: bool

    def summary(self) -> dict[str, object]:
        """Return the tolerances as the JSON of ``rotorcad inspect`` gives them (``tolerance_class`` ... mm)."""
        return {
            "tolerance_class": self.tolerance_class,
            "single_pitch_tolerance": self.single_pitch,
            "cumulative_pitch_tolerance": self.cumulative_pitch,
            "profile_slope_tolerance": self.profile_slope,
            "profile_form_tolerance": self.profile_form,
            "total_profile_tolerance": self.total_profile,
            "in_scope": self.in_scope,
        }


def flank_tolerances(tolerance_class: int, module: float, diameter: float) -> FlankTolerances:
    """Return the ISO 1328-1:2013 flank tolerances of a gear for a class.

    Parameters
    ----------
    tolerance_class : int
        A, from 1 to 11.
    module : float, mm
        Normal module m_n.
    diameter : float, mm
        Reference diameter d.

    Returns
    -------
    FlankTolerances
        In mm (the standard's µm / 1000), rounded by :func:`round_tolerance`.

    Raises
    ------
    DesignError
        A class that is not a whole number from 1 to 11 (``tolerance_class``).
    """
    if (
        isinstance(tolerance_class, bool)
        or not isinstance(tolerance_class, int)
        or not (CLASSES[0] <= tolerance_class <= CLASSES[1])
    ):
        raise DesignError(
            "tolerance_class", f"a whole number from {CLASSES[0]} to {CLASSES[1]} (ISO 1328-1:2013)", tolerance_class
        )
    step = math.sqrt(2.0) ** (tolerance_class - 5)
    d, m = diameter, module
    f_pt = (0.001 * d + 0.4 * m + 5.0) * step  # eq. (5)
    f_p = (0.002 * d + 0.55 * math.sqrt(d) + 0.7 * m + 12.0) * step  # eq. (6)
    f_h = (0.4 * m + 0.001 * d + 4.0) * step  # eq. (7)
    f_f = (0.55 * m + 5.0) * step  # eq. (8)
    f_total = math.hypot(f_h, f_f)  # eq. (9), of the unrounded values
    in_scope = SCOPE["module"][0] <= m <= SCOPE["module"][1] and SCOPE["diameter"][0] <= d <= SCOPE["diameter"][1]
    return FlankTolerances(
        tolerance_class,
        *(round_tolerance(v) / 1000.0 for v in (f_pt, f_p, f_h, f_f, f_total)),
        in_scope=in_scope,
    )


__all__ = ["CLASSES", "SCOPE", "FlankTolerances", "flank_tolerances", "round_tolerance"]

"""Tooth-thickness allowances of an involute gear and the backlash of a pair from them.

A tooth-thickness allowance A_sn (DIN 3967, ISO 21771; the upper A_sne and the lower
A_sni) thins the tooth in the normal section on the reference circle: s_n + A_sn, A_sn <= 0. The
gear shop makes it by feeding the generating rack deeper, by A_sn / (2 tan alpha_n): the gear is
generated with the generating profile shift x_E = x + A_sn / (2 m_n tan alpha_n) (ISO 21771,
the generating profile shift) while its blank, and so its tip circle, stays the nominal one. :func:`thinned` builds that gear,
so that its outline is the thinned tooth itself (flanks and root), and every measurement made on it
is the measurement of the thinned gear.

The backlash of a pair follows from both gears' allowances and the centre distance
(:func:`pair_backlash`): the largest with both lower allowances, the smallest with both upper ones.
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np

from rotorcad.errors import DesignError
from rotorcad.gears.formulas import base_helix_angle
from rotorcad.gears.involute_gear import InvoluteGear
from rotorcad.gears.pair import GearPair

THINNING_LIMIT = 0.5
"""Largest thinning |A_sn| as a factor of the module: DIN 3967's largest allowances (series a, the
largest diameters) stay well within half a module; beyond, the generating rack would move the root
by more than 0.7 modules."""


@dataclass(frozen=True)
class ThicknessAllowance:
    """The upper and lower tooth-thickness allowances of one gear (DIN 3967), mm.

    Normal section, on the reference circle; negative numbers thin the tooth (DIN 3967's A_sne,
    A_sni), 0 is the nominal tooth.

    Parameters
    ----------
    upper : float, mm
        A_sne, the allowance nearer the nominal tooth (the thickest tooth allowed), <= 0.
    lower : float, mm
        A_sni, the thinnest tooth allowed, <= ``upper``.
    """

    upper: float = 0.0
    lower: float = 0.0

    def check(self, module: float) -> None:
        """Refuse allowances that are not 0 >= upper >= lower >= -0.5 m.

        Parameters
        ----------
        module : float, mm
            Normal module m_n of the gear.

        Raises
        ------
        DesignError
            ``thickness_allowance_upper`` or ``thickness_allowance_lower`` out of range.
        """
        lowest = -THINNING_LIMIT * module
        if not (np.isfinite(self.upper) and lowest <= self.upper <= 0.0):
            raise DesignError(
                "thickness_allowance_upper",
                f"from {lowest:.6g} to 0 mm (half a module thinner than nominal to nominal)",
                self.upper,
            )
        if not (np.isfinite(self.lower) and lowest <= self.lower <= self.upper):
            raise DesignError(
                "thickness_allowance_lower", f"from {lowest:.6g} mm to the upper allowance {self.upper:.6g} mm", self.lower
            )

    @property
    def mean(self) -> float:
        """The middle of the tolerance field, (A_sne + A_sni) / 2, mm: what a machine is set to cut."""
        return 0.5 * (self.upper + self.lower)

    def limits(self) -> dict[str, float]:
        """Return the allowances by name: ``{"nominal": 0, "upper": A_sne, "lower": A_sni}``, mm."""
        return {"nominal": 0.0, "upper": float(self.upper), "lower": float(self.lower)}


def generating_shift(gear: InvoluteGear, allowance: float) -> float:
    """Return the generating profile shift x_E = x + A_sn / (2 m_n tan alpha_n) (ISO 21771, the generating profile shift).

    Parameters
    ----------
    gear : InvoluteGear
        The nominal gear (shift x, normal module m_n, normal pressure angle alpha_n).
    allowance : float, mm
        Tooth-thickness allowance A_sn, normal section.

    Returns
    -------
    float
        x_E, in normal modules.
    """
    return float(gear.shift + allowance / (2.0 * gear.module * np.tan(gear.pressure_angle)))


def thinned(gear: InvoluteGear, allowance: float) -> InvoluteGear:
    """Return the gear generated with the rack fed in for a tooth-thickness allowance.

    The generating shift is x_E (:func:`generating_shift`); the addendum factor grows by x - x_E so
    that the tip circle, the blank's, stays r + (h_aP* + x) m_n.

    Parameters
    ----------
    gear : InvoluteGear
        The nominal gear.
    allowance : float, mm
        Tooth-thickness allowance A_sn (<= 0), normal section.

    Returns
    -------
    InvoluteGear
        ``gear`` itself for a zero allowance; else the thinned gear (its ``shift`` is x_E).

    Raises
    ------
    DesignError
        ``thickness_allowance``: the fed-in rack severs the tooth or moves the root circle onto the
        centre (the message of the gear's own refusal as the detail).
    """
    if allowance == 0.0:
        return gear
    x_e = generating_shift(gear, allowance)
    try:
        return replace(gear, shift=x_e, addendum=gear.addendum + gear.shift - x_e)
    except DesignError as exc:
        raise DesignError(
            "thickness_allowance", "a thinning the gear's tooth survives", allowance, exc.sentence().rstrip(".")
        ) from None


def thinned_pair(pair: GearPair, gear_allowance: float, mate_allowance: float) -> GearPair:
    """Return the pair of both gears thinned by their allowances, at the pair's working centre distance.

    Parameters
    ----------
    pair : GearPair
        The nominal pair.
    gear_allowance, mate_allowance : float, mm
        A_sn of the gear and of the mate.

    Returns
    -------
    GearPair
        The thinned gears (:func:`thinned`) at ``pair.working_center_distance``.
    """
    return GearPair(thinned(pair.gear, gear_allowance), thinned(pair.mate, mate_allowance), pair.working_center_distance)


def pair_backlash(pair: GearPair, gear: ThicknessAllowance, mate: ThicknessAllowance) -> dict[str, dict[str, float]]:
    """Return the backlash of a pair from both gears' allowances at its working centre distance.

    The circumferential backlash j_wt on the working pitch circles is measured on the generated
    flanks of the thinned gears (:meth:`GearPair.backlash`); the normal backlash is
    j_bn = j_wt cos(alpha_wt) cos(beta_b) (ISO 21771, DIN 3967), the gap along the
    line of action in the normal section.

    Parameters
    ----------
    pair : GearPair
        The nominal pair (its centre distance is kept).
    gear, mate : ThicknessAllowance
        The allowances of the gear and of the mate.

    Returns
    -------
    dict
        ``{"circumferential": {"nominal", "max", "min"}, "normal": {...}}``, mm: the nominal gears,
        both lower allowances (the largest backlash) and both upper ones (the smallest).
    """
    out: dict[str, dict[str, float]] = {"circumferential": {}, "normal": {}}
    beta_b = base_helix_angle(pair.gear.pressure_angle, pair.gear.helix_angle)
    factor = float(np.cos(pair.working_pressure_angle) * np.cos(beta_b))
    for name, a1, a2 in (("nominal", 0.0, 0.0), ("max", gear.lower, mate.lower), ("min", gear.upper, mate.upper)):
        j = thinned_pair(pair, a1, a2).backlash
        out["circumferential"][name] = float(j)
        out["normal"][name] = float(j * factor)
    return out


__all__ = [
    "THINNING_LIMIT",
    "ThicknessAllowance",
    "generating_shift",
    "pair_backlash",
    "thinned",
    "thinned_pair",
]

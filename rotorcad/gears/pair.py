"""Two external involute gears in mesh: centre distance, working pressure angle, backlash, contact ratio.

The closed forms of ISO 21771 (eqs. 4.14, 4.16, 5.4) on the gears' generated flanks
(:class:`~rotorcad.gears.involute_gear.InvoluteGear`).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from rotorcad.errors import DesignError
from rotorcad.gears.formulas import shift_sum, working_pressure_angle
from rotorcad.gears.involute_gear import DEG, InvoluteGear
from rotorcad.rotor_pair import MAX_LENGTH


@dataclass(frozen=True, eq=False)
class GearPair:
    """Two external involute gears in mesh at centre distance a_w.

    Without ``center_distance`` the pair runs without backlash at the centre distance of the
    shifts: inv(alpha_wt) = inv(alpha_t) + 2 (x1 + x2) tan(alpha_n) / (z1 + z2) and
    a_w = a cos(alpha_t) / cos(alpha_wt) (ISO 21771 eqs. 4.14, 4.16). With it, alpha_wt follows
    from cos(alpha_wt) = a cos(alpha_t) / a_w and the difference shows as circumferential
    backlash; a centre distance too small for the teeth is refused.

    Parameters
    ----------
    gear, mate : InvoluteGear
        The two gears, of the same module and pressure angle and helix angles equal in size.
    center_distance : float, optional
        Working centre distance a_w, mm (default: the zero-backlash distance of the shifts).

    Raises
    ------
    DesignError
        Gears of different module, pressure angle or size of helix angle; a centre distance not
        greater than a cos(alpha_t), or smaller than the zero-backlash distance (negative backlash).
    """

    gear: InvoluteGear
    mate: InvoluteGear
    center_distance: float | None = None

    def __post_init__(self) -> None:
        g, m = self.gear, self.mate
        if abs(g.module - m.module) > 1e-12 or abs(g.pressure_angle - m.pressure_angle) > 1e-12:
            raise DesignError("mate", "of the same module and pressure angle as the gear", None)
        if abs(abs(g.helix_angle) - abs(m.helix_angle)) > 1e-12:
            raise DesignError("mate helix angle", "equal in size to the gear's", round(m.helix_angle / DEG, 6))
        if self.center_distance is not None:
            a0 = self.reference_center_distance
            at = g.transverse_pressure_angle
            lo = a0 * np.cos(at)
            if not (self.center_distance > lo):
                raise DesignError("center_distance", f"greater than {lo:.6g} mm", self.center_distance)
            if not self.center_distance <= MAX_LENGTH:
                raise DesignError("center_distance", f"from {lo:.6g} to {MAX_LENGTH:.0f} mm (100 m)", self.center_distance)
            if self.backlash < -1e-9:
                need = self._zero_backlash_distance
                raise DesignError(
                    "center_distance", f"at least {need:.6g} mm for these teeth and shifts (zero backlash)", self.center_distance
                )

    @property
    def reference_center_distance(self) -> float:
        """Reference centre distance a = r1 + r2, mm: the centre distance of unshifted gears."""
        return self.gear.pitch_radius + self.mate.pitch_radius

    @property
    def _zero_backlash_angle(self) -> float:
        g, m = self.gear, self.mate
        return working_pressure_angle(g.teeth, m.teeth, g.shift, m.shift, g.transverse_pressure_angle, g.pressure_angle)

    @property
    def _zero_backlash_distance(self) -> float:
        at = self.gear.transverse_pressure_angle
        return self.reference_center_distance * np.cos(at) / np.cos(self._zero_backlash_angle)

    @property
    def working_center_distance(self) -> float:
        """Working centre distance a_w, mm: ``center_distance``, or without it the zero-backlash one.

        The zero-backlash distance is a cos(alpha_t) / cos(alpha_wt) with alpha_wt from the shifts
        (ISO 21771 eqs. 4.14, 4.16).
        """
        return self._zero_backlash_distance if self.center_distance is None else float(self.center_distance)

    @property
    def working_pressure_angle(self) -> float:
        """alpha_wt (transverse)."""
        if self.center_distance is None:
            return self._zero_backlash_angle
        at = self.gear.transverse_pressure_angle
        return float(np.arccos(self.reference_center_distance * np.cos(at) / self.center_distance))

    @property
    def backlash(self) -> float:
        """Circumferential backlash j_wt = p_wt - s_w1 - s_w2 on the working pitch circles, mm.

        The two circles roll on each other, so their arc lengths compare directly; s_w from the
        generated flanks (:meth:`InvoluteGear.tooth_thickness`). Infinite where a working pitch
        circle lies outside its gear's tip circle.
        """
        aw = self.working_pressure_angle
        g, m = self.gear, self.mate
        rw1 = g.base_radius / np.cos(aw)
        rw2 = m.base_radius / np.cos(aw)
        if rw1 > g.tip_radius or rw2 > m.tip_radius:
            return float("inf")
        s1 = g.tooth_thickness(rw1)
        s2 = m.tooth_thickness(rw2)
        return float(2.0 * np.pi * rw1 / g.teeth - s1 - s2)

    def contact_interval(self) -> tuple[float, float, float, float]:
        """Return the roll distances from T1 along the line of action that bound the contact.

        Where contact starts and ends on the usable flanks (form to tip of each gear), and the
        standard tip-to-tip limits. T1 is the gear's base tangency point; the mate's, T2, lies at
        a_w sin(alpha_wt) from it.

        Returns
        -------
        lo1, hi1 : float
            The gear's usable flank, mm: its form circle and its tip circle.
        lo2, hi2 : float
            The mate's usable flank, mm: its tip circle and its form circle.
        """
        g, m = self.gear, self.mate
        aw = self.working_pressure_angle
        length = self.working_center_distance * np.sin(aw)
        lo1 = np.sqrt(max(g.form_radius**2 - g.base_radius**2, 0.0))
        hi1 = np.sqrt(g.tip_radius**2 - g.base_radius**2)
        lo2 = length - np.sqrt(m.tip_radius**2 - m.base_radius**2)
        hi2 = length - np.sqrt(max(m.form_radius**2 - m.base_radius**2, 0.0))
        return lo1, hi1, lo2, hi2

    @property
    def contact_ratio(self) -> float:
        """Transverse contact ratio epsilon_alpha = g_alpha / p_bt.

        The path of contact g_alpha is limited by the tip circles and by the usable involute of
        each gear (form circle, :meth:`contact_interval`), so that an undercut flank shortens it
        (Kollek & Osinski; ISO 21771 eq. 5.4 without undercut); 0 where the flanks' intervals do
        not overlap.
        """
        lo1, hi1, lo2, hi2 = self.contact_interval()
        g_alpha = max(0.0, min(hi1, hi2) - max(lo1, lo2))
        return float(g_alpha / self.gear.base_pitch)

    @property
    def tip_interference(self) -> bool:
        """True when a tip reaches below the mate's usable involute (tip meets fillet)."""
        lo1, hi1, lo2, hi2 = self.contact_interval()
        return bool(lo2 < lo1 - 1e-9 or hi1 > hi2 + 1e-9)

    def summary(self) -> dict[str, object]:
        """Return the CONTRACT.md keys of ``rotorcad gear`` for the pair.

        Returns
        -------
        dict of str to object
            :meth:`InvoluteGear.summary` of ``gear`` and ``center_distance`` (mm),
            ``working_pressure_angle_deg`` (degrees), ``contact_ratio``, ``backlash`` (mm),
            ``tip_interference`` (bool) and ``mate`` (the mate's :meth:`InvoluteGear.summary`).
        """
        out = self.gear.summary()
        out.update(
            {
                "center_distance": self.working_center_distance,
                "working_pressure_angle_deg": self.working_pressure_angle / DEG,
                "contact_ratio": self.contact_ratio,
                "backlash": self.backlash,
                "tip_interference": self.tip_interference,
                "mate": self.mate.summary(),
            }
        )
        return out


def mate_shift(gear: InvoluteGear, mate_teeth: int, center_distance: float) -> float:
    """Return the mate's shift x2 giving zero backlash with ``gear`` at ``center_distance`` (ISO 21771 eq. 4.14).

    Parameters
    ----------
    gear : InvoluteGear
        The gear, with its shift x1.
    mate_teeth : int
        Number of teeth z2 of the mate (same module, pressure angle and size of helix angle).
    center_distance : float
        Working centre distance a_w, mm.

    Returns
    -------
    float
        x2, in normal modules.

    Raises
    ------
    DesignError
        A centre distance not greater than a cos(alpha_t).
    """
    at = gear.transverse_pressure_angle
    r2 = mate_teeth * gear.transverse_module / 2.0
    a0 = gear.pitch_radius + r2
    c = a0 * np.cos(at) / center_distance
    if not (0.0 < c < 1.0):
        raise DesignError("center_distance", f"greater than {a0 * np.cos(at):.6g} mm", center_distance)
    return shift_sum(gear.teeth, mate_teeth, float(np.arccos(c)), at, gear.pressure_angle) - gear.shift

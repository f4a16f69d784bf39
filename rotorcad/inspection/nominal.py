"""The nominal involute flanks an inspection compares with, and the ranges ISO 1328-1 evaluates over.

All in the transverse section, where ISO 1328-1:2013 defines the profile deviations. A flank of
tooth k (centred at k 2 pi / z) lies at the polar angle k 2 pi / z + s psi(R), s = +1 on the left
(counter-clockwise) and -1 on the right flank (:class:`rotorcad.roles.ToothFlank`), with the
half angle of the tooth psi(R) = psi_b - inv(alpha_R), cos(alpha_R) = r_b / R and
psi_b = (pi / 2 + 2 x tan(alpha_n)) / z + inv(alpha_t) (ISO 21771 eqs. 2.21, 5.12: the arc
thickness on the reference circle s_t = m_t (pi / 2 + 2 x tan(alpha_n))). Two involutes of one
base circle are parallel curves: a flank turned by an angle e lies r_b e from the nominal one
along their common normal (the base tangent), which makes r_b times the polar-angle difference
at one radius the exact normal deviation in the transverse section.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np

from rotorcad.gears.formulas import inv
from rotorcad.geometry import Array

EVALUATED_SHARE = 0.95
"""ISO 1328-1:2013: the profile evaluation range L_alpha runs from the start of the active
profile over 95 % of the way to the tip form diameter."""


@dataclass(frozen=True)
class NominalFlanks:
    """The nominal involute flanks of a gear and the evaluation range of ISO 1328-1:2013.

    Attributes
    ----------
    teeth : int
        z.
    module : float, mm
        Normal module m_n.
    helix_angle, transverse_pressure_angle : float, rad
        beta; alpha_t.
    base_radius, reference_radius : float, mm
        r_b, r.
    base_half_angle : float, rad
        psi_b, half the tooth's angle on the base circle.
    root_radius, tip_radius : float, mm
        Of the gear as cut (the tip form circle is the tip circle: no chamfer).
    active_start : float, mm
        Radius of the start of the active profile: the form circle, or where the mate's tip
        reaches (the larger).
    active_start_by : str
        ``"form circle"`` or ``"mate's tip"``.
    """

    teeth: int
    module: float
    helix_angle: float
    transverse_pressure_angle: float
    base_radius: float
    reference_radius: float
    base_half_angle: float
    root_radius: float
    tip_radius: float
    active_start: float
    active_start_by: str

    @property
    def pitch_angle(self) -> float:
        """2 pi / z, rad."""
        return 2.0 * math.pi / self.teeth

    def roll_length(self, radius: Array) -> Array:
        """Roll length xi = sqrt(R^2 - r_b^2) of the involute at radius R, mm (any shape; 0 inside the base circle)."""
        r = np.asarray(radius, dtype=float)
        return np.sqrt(np.maximum(r * r - self.base_radius**2, 0.0))

    def radius_at(self, roll_length: Array) -> Array:
        """Radius sqrt(r_b^2 + xi^2) at roll length xi, mm."""
        xi = np.asarray(roll_length, dtype=float)
        return np.sqrt(self.base_radius**2 + xi * xi)

    def half_angle(self, radius: Array) -> Array:
        """Return the tooth's polar half angle psi(R) = psi_b - inv(alpha_R) on the involute, rad (R >= r_b)."""
        r = np.maximum(np.asarray(radius, dtype=float), self.base_radius)
        return self.base_half_angle - inv(np.arccos(self.base_radius / r))

    @property
    def evaluation_range(self) -> tuple[float, float]:
        """(xi_start, xi_end), mm: L_alpha from the start of the active profile over :data:`EVALUATED_SHARE` to the tip form."""
        start = float(self.roll_length(self.active_start))
        end = float(self.roll_length(self.tip_radius))
        return start, start + EVALUATED_SHARE * (end - start)

    @property
    def measuring_radius(self) -> float:
        """Radius of the measuring circle of pitch deviations, mm: the middle of the evaluation range (mid tooth depth)."""
        lo, hi = self.evaluation_range
        return float(self.radius_at(0.5 * (lo + hi)))

    def summary(self) -> dict[str, Any]:
        """Return the evaluation range as ``rotorcad inspect`` reports it (radii, roll lengths mm; roll angles xi / r_b deg)."""
        lo, hi = self.evaluation_range
        return {
            "start_radius": float(self.radius_at(lo)),
            "end_radius": float(self.radius_at(hi)),
            "start_roll_length": lo,
            "end_roll_length": hi,
            "evaluation_length": hi - lo,
            "start_roll_angle_deg": math.degrees(lo / self.base_radius),
            "end_roll_angle_deg": math.degrees(hi / self.base_radius),
            "tip_form_radius": self.tip_radius,
            "active_start": self.active_start_by,
            "measuring_radius": self.measuring_radius,
        }


def nominal_flanks(gear: Any, pair: Any = None) -> NominalFlanks:
    """Return the nominal flanks of an involute gear, and its active profile with its mate.

    Parameters
    ----------
    gear : InvoluteGear
        The nominal gear (:class:`rotorcad.gears.involute_gear.InvoluteGear`).
    pair : GearPair, optional
        The gear in mesh with its mate: the active profile then starts where the mate's tip
        reaches, xi = a_w sin(alpha_wt) - sqrt(r_a2^2 - r_b2^2) (ISO 21771), if that lies above
        the form circle.

    Returns
    -------
    NominalFlanks
    """
    alpha_t = gear.transverse_pressure_angle
    rb = gear.base_radius
    psi_b = (math.pi / 2.0 + 2.0 * gear.shift * math.tan(gear.pressure_angle)) / gear.teeth + float(inv(alpha_t))
    start, by = max(gear.form_radius, rb), "form circle"
    if pair is not None:
        mate = pair.mate
        xi = pair.working_center_distance * math.sin(pair.working_pressure_angle) - math.sqrt(
            max(mate.tip_radius**2 - mate.base_radius**2, 0.0)
        )
        r_mate = math.sqrt(rb * rb + max(xi, 0.0) ** 2)
        if r_mate > start:
            start, by = r_mate, "mate's tip"
    return NominalFlanks(
        teeth=gear.teeth,
        module=gear.module,
        helix_angle=gear.helix_angle,
        transverse_pressure_angle=alpha_t,
        base_radius=rb,
        reference_radius=gear.pitch_radius,
        base_half_angle=psi_b,
        root_radius=gear.root_radius,
        tip_radius=gear.tip_radius,
        active_start=start,
        active_start_by=by,
    )


__all__ = ["EVALUATED_SHARE", "NominalFlanks", "nominal_flanks"]

"""An external pinion in mesh with an internal gear: working pressure angle, centre distance, contact ratio, interference.

The closed forms of ISO 21771 and DIN 3993 for internal pairs
(:mod:`rotorcad.gears.internal_formulas`) on the generated gears: the pinion
(:class:`~rotorcad.gears.involute_gear.InvoluteGear`) and the internal gear
(:class:`~rotorcad.gears.internal_gear.InternalGear`). Frame: internal gear about the origin, pinion
about (a_w, 0), tooth space 0 of the internal gear and tooth 0 of the pinion on the +x axis.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from rotorcad.errors import DesignError, GeometryError
from rotorcad.gears.formulas import inv
from rotorcad.gears.internal_formulas import (
    internal_center_distance,
    internal_working_pressure_angle,
    involute_interference_margin,
    radial_margin,
    roll_length,
    trochoid_margin,
)
from rotorcad.gears.internal_gear import InternalGear
from rotorcad.gears.involute_gear import DEG, MAX_TEETH, InvoluteGear


@dataclass(frozen=True, eq=False)
class InternalPair:
    """A pinion meshing inside an internal gear at centre distance a_w.

    Without ``center_distance`` the pair runs without backlash at the centre distance of the shifts
    (:func:`~rotorcad.gears.internal_formulas.internal_working_pressure_angle`,
    :func:`~rotorcad.gears.internal_formulas.internal_center_distance`); with it, cos(alpha_wt) =
    (r2 - r1) cos(alpha_t) / a_w.

    Parameters
    ----------
    pinion : InvoluteGear
        The external pinion (same module, pressure angle and helix angle as the internal gear).
    ring : InternalGear
        The internal gear.
    center_distance : float or None
        Working centre distance a_w, mm.
    check : bool
        Refuse an interfering pair (default): involute interference, the pinion's tip in the
        internal gear's root fillet, trochoid interference.

    Raises
    ------
    DesignError
        Pinion and internal gear of different module or angles (``mate.module``); a pinion with as
        many teeth or more (``mate.teeth``); a centre distance giving negative backlash
        (``center_distance``); with ``check``, an interfering pair (:class:`GeometryError`,
        ``teeth``, naming the smallest tooth-count difference that meshes).
    """

    pinion: InvoluteGear
    ring: InternalGear
    center_distance: float | None = None
    check: bool = True

    def __post_init__(self) -> None:
        p, r = self.pinion, self.ring
        same = (p.module, p.pressure_angle, p.helix_angle) == (r.module, r.pressure_angle, r.helix_angle)
        if not same:
            raise DesignError("mate.module", "the internal gear's module, pressure angle and helix angle", p.module)
        if p.teeth >= r.teeth:
            raise DesignError("mate.teeth", f"fewer than the internal gear's {r.teeth} teeth", p.teeth)
        if self.center_distance is not None:
            least = self._zero_backlash_distance
            a = self.center_distance
            if not (math.isfinite(a) and least - 1e-9 <= a < r.pitch_radius - p.pitch_radius + 2.0 * p.module):
                raise DesignError(
                    "center_distance",
                    f"from {least:.6g} mm (zero backlash) to below {r.pitch_radius - p.pitch_radius + 2.0 * p.module:.6g} mm",
                    a,
                )
        if self.check:
            self._refuse_interference()

    def _refuse_interference(self) -> None:
        """Raise :class:`GeometryError` for involute, tip-fillet or trochoid interference, naming the remedy.

        Involute interference names the internal gear's ``addendum`` and its largest value (the
        tip circle that touches the pinion's form circle on the line of action); the pinion's tip
        in the root fillet and trochoid interference name ``teeth`` and the smallest count
        (:attr:`min_teeth_difference`).
        """
        p, r = self.pinion, self.ring
        if self.involute_interference_margin < -1e-9 * r.module:
            along = self.working_center_distance * math.sin(self.working_pressure_angle) + roll_length(
                p.form_radius, p.base_radius
            )
            largest = (r.pitch_radius + r.shift * r.module - math.hypot(r.base_radius, along)) / r.module
            raise GeometryError(
                "addendum",
                f"at most {math.floor(largest * 1e4) / 1e4:.4f} for this pinion and these shifts",
                r.addendum,
                "the internal gear's tips reach below the pinion's usable involute, into its root fillet "
                "(involute interference, DIN 3993)",
            )
        why = ""
        if self.root_interference_margin < -1e-9 * r.module:
            why = "the pinion's tips reach into the internal gear's root fillets (tip interference)"
        elif self.trochoid_margin < 0.0:
            why = "the pinion's tips strike the internal gear's tooth tips as they leave mesh (trochoid interference)"
        if why:
            least = self.min_teeth_difference
            allowed = f"at least {p.teeth + least} for a {p.teeth}-tooth pinion with these shifts (z2 - z1 >= {least})"
            raise GeometryError("teeth", allowed if least is not None else "larger", r.teeth, why)

    @property
    def _zero_backlash_angle(self) -> float:
        p, r = self.pinion, self.ring
        return internal_working_pressure_angle(p.teeth, r.teeth, p.shift, r.shift, r.transverse_pressure_angle, r.pressure_angle)

    @property
    def _zero_backlash_distance(self) -> float:
        return internal_center_distance(
            self.pinion.pitch_radius, self.ring.pitch_radius, self.ring.transverse_pressure_angle, self._zero_backlash_angle
        )

    @property
    def working_center_distance(self) -> float:
        """a_w, mm: ``center_distance`` or the zero-backlash one."""
        return self._zero_backlash_distance if self.center_distance is None else float(self.center_distance)

    @property
    def working_pressure_angle(self) -> float:
        """alpha_wt, rad (transverse)."""
        if self.center_distance is None:
            return self._zero_backlash_angle
        ref = self.ring.pitch_radius - self.pinion.pitch_radius
        return math.acos(ref * math.cos(self.ring.transverse_pressure_angle) / self.center_distance)

    @property
    def backlash(self) -> float:
        """Circumferential backlash j_wt = e_w2 - s_w1 on the working pitch circles, mm.

        The space width of the internal gear on r_w2 minus the pinion's tooth thickness on r_w1
        (the circles roll on each other, so their arc lengths compare). Each flank's involute
        constant (polar angle + inv(alpha_R), ISO 21771 eq. 2.21) is read from the generated flank
        in the middle of its involute, so that a working circle beyond the teeth is allowed.
        """
        aw = self.working_pressure_angle
        p, r = self.pinion, self.ring
        mid1 = 0.5 * (p.form_radius + p.tip_radius)
        mid2 = 0.5 * (r.form_radius + r.tip_radius)
        psi_b1 = p.half_angle(mid1) + float(inv(math.acos(p.base_radius / mid1)))
        eta_b2 = r.space_half_angle(mid2) + float(inv(math.acos(r.base_radius / mid2)))
        rw1, rw2 = p.base_radius / math.cos(aw), r.base_radius / math.cos(aw)
        inv_w = float(inv(aw))
        return 2.0 * rw2 * (eta_b2 - inv_w) - 2.0 * rw1 * (psi_b1 - inv_w)

    def contact_interval(self) -> tuple[float, float, float, float]:
        """Roll lengths from T2 (the internal gear's base tangency point) bounding the contact, mm.

        Returns
        -------
        tip2, form1 : float
            Where the internal gear's tip circle and the pinion's form circle cross the line of
            action: sqrt(r_a2^2 - r_b2^2) and a_w sin(alpha_wt) + sqrt(r_Ff1^2 - r_b1^2).
        tip1, form2 : float
            The pinion's tip circle and the internal gear's form circle:
            a_w sin(alpha_wt) + sqrt(r_a1^2 - r_b1^2) and sqrt(r_Ff2^2 - r_b2^2).
        """
        p, r = self.pinion, self.ring
        t1 = self.working_center_distance * math.sin(self.working_pressure_angle)
        return (
            roll_length(r.tip_radius, r.base_radius),
            t1 + roll_length(p.form_radius, p.base_radius),
            t1 + roll_length(p.tip_radius, p.base_radius),
            roll_length(r.form_radius, r.base_radius),
        )

    @property
    def contact_ratio(self) -> float:
        """Transverse contact ratio epsilon_alpha = g_alpha / p_bt.

        g_alpha = sqrt(r_a1^2 - r_b1^2) - sqrt(r_a2^2 - r_b2^2) + a_w sin(alpha_wt) for an internal
        pair (ISO 21771 eq. 5.4 with z2 < 0; DIN 3993), limited by the usable involutes (form
        circles); 0 where they do not overlap.
        """
        tip2, form1, tip1, form2 = self.contact_interval()
        g_alpha = max(0.0, min(tip1, form2) - max(tip2, form1))
        return g_alpha / self.ring.base_pitch

    @property
    def involute_interference_margin(self) -> float:
        """How far the internal gear's tip contact lies above the pinion's form circle on the line of action, mm."""
        p, r = self.pinion, self.ring
        return involute_interference_margin(
            r.tip_radius, r.base_radius, self.working_center_distance, self.working_pressure_angle, p.form_radius, p.base_radius
        )

    @property
    def root_interference_margin(self) -> float:
        """How far the pinion's tip contact stays inside the internal gear's usable involute, mm (form2 - tip1)."""
        _, _, tip1, form2 = self.contact_interval()
        return form2 - tip1

    @property
    def trochoid_margin(self) -> float:
        """Trochoid-interference margin, rad (:func:`~rotorcad.gears.internal_formulas.trochoid_margin`)."""
        p, r = self.pinion, self.ring
        return trochoid_margin(
            p.teeth, r.teeth, p.tip_radius, r.tip_radius, self.working_center_distance, self.working_pressure_angle, p.base_radius
        )

    @property
    def radial_margin(self) -> float:
        """Margin against radial (trimming) interference, rad of the pinion (:func:`internal_formulas.radial_margin`).

        Negative: the pinion cannot be moved radially into mesh (it is assembled axially).
        """
        p, r = self.pinion, self.ring
        return radial_margin(p.teeth, r.teeth, p.tip_radius, r.tip_radius, p.base_radius, self.working_pressure_angle)

    @property
    def min_teeth_difference(self) -> int | None:
        """Smallest z2 - z1 for which the pair passes the closed-form checks, the pinion and shifts kept.

        Involute interference (:func:`involute_interference_margin`, with the pinion's form circle)
        and trochoid interference (:func:`trochoid_margin`) at zero backlash, scanned from
        :data:`MAX_TEETH` down: the smallest count of the passing run that reaches it; None if none.
        """
        p, r = self.pinion, self.ring
        at, an = r.transverse_pressure_angle, r.pressure_angle
        rb1 = p.base_radius
        least = None
        for z2 in range(MAX_TEETH, p.teeth, -1):
            r2 = z2 * r.transverse_module / 2.0
            ra2 = r2 - (r.addendum - r.shift) * r.module
            rb2 = r2 * math.cos(at)
            if ra2 <= rb2:
                break
            aw = internal_working_pressure_angle(p.teeth, z2, p.shift, r.shift, at, an)
            a = internal_center_distance(p.pitch_radius, r2, at, aw)
            inv_ok = involute_interference_margin(ra2, rb2, a, aw, p.form_radius, rb1) >= -1e-9 * r.module
            if not (inv_ok and trochoid_margin(p.teeth, z2, p.tip_radius, ra2, a, aw, rb1) >= 0.0):
                break
            least = z2 - p.teeth
        return least

    def summary(self) -> dict[str, object]:
        """Return the CONTRACT.md keys of ``rotorcad gear --internal`` for the pair.

        Returns
        -------
        dict
            :meth:`InternalGear.summary` of the internal gear and ``center_distance`` (mm),
            ``working_pressure_angle_deg``, ``contact_ratio``, ``backlash`` (mm),
            ``involute_interference_margin`` and ``root_interference_margin`` (mm),
            ``trochoid_margin_deg`` and ``radial_assembly_margin_deg`` (degrees),
            ``min_teeth_difference`` and ``mate`` (the pinion's :meth:`InvoluteGear.summary`).
        """
        out = self.ring.summary()
        out.update(
            {
                "center_distance": float(self.working_center_distance),
                "working_pressure_angle_deg": self.working_pressure_angle / DEG,
                "contact_ratio": float(self.contact_ratio),
                "backlash": float(self.backlash),
                "involute_interference_margin": float(self.involute_interference_margin),
                "root_interference_margin": float(self.root_interference_margin),
                "trochoid_margin_deg": self.trochoid_margin / DEG,
                "radial_assembly_margin_deg": self.radial_margin / DEG,
                "min_teeth_difference": self.min_teeth_difference,
                "mate": self.pinion.summary(),
            }
        )
        return out


def internal_mate_shift(ring: InternalGear, pinion_teeth: int, center_distance: float) -> float:
    """Return the pinion's shift x1 giving zero backlash inside ``ring`` at ``center_distance``.

    x1 = x2 - (inv(alpha_wt) - inv(alpha_t)) (z2 - z1) / (2 tan(alpha_n)), cos(alpha_wt) =
    (r2 - r1) cos(alpha_t) / a_w (:func:`~rotorcad.gears.internal_formulas.internal_working_pressure_angle`
    solved for x1).

    Parameters
    ----------
    ring : InternalGear
        The internal gear, with its shift x2.
    pinion_teeth : int
        Teeth z1 of the pinion.
    center_distance : float
        a_w, mm.

    Returns
    -------
    float
        x1, normal modules.

    Raises
    ------
    DesignError
        A centre distance not above (r2 - r1) cos(alpha_t) (``center_distance``).
    """
    at = ring.transverse_pressure_angle
    ref = ring.pitch_radius - pinion_teeth * ring.transverse_module / 2.0
    c = ref * math.cos(at) / center_distance
    if not (0.0 < c < 1.0):
        raise DesignError("center_distance", f"greater than {ref * math.cos(at):.6g} mm", center_distance)
    aw = math.acos(c)
    return ring.shift - (float(inv(aw)) - float(inv(at))) * (ring.teeth - pinion_teeth) / (2.0 * math.tan(ring.pressure_angle))

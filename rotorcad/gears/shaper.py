"""The pinion-type shaper cutter that generates an internal gear: its tooth as exact curves.

A shaper cutter is an external involute gear (z0 teeth, profile shift x0) whose tooth tip is
rounded by an arc of radius rho_a0 tangent to the tip circle and to the involute flank (DIN 1825;
ISO 21771 sec. 2.3 for the involute). Its flank is the involute of its base circle; the tip
rounding cuts the internal gear's root fillet, the tip circle its root circle
(:mod:`rotorcad.gears.internal_gear`).

Frame: cutter centre at the origin, tooth 0 centred on the +x axis, transverse section; lengths
in mm, angles in radians.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import cached_property

import numpy as np

from rotorcad.curves import Arc, Curve, Involute
from rotorcad.errors import DesignError
from rotorcad.gears.dimensions import ReferenceDimensions
from rotorcad.gears.formulas import inv
from rotorcad.gears.involute_gear import DEG, MAX_TEETH, MODULE_RANGE

CUTTER_TEETH_RANGE = (5, MAX_TEETH)
"""Teeth of a shaper cutter: from a 5-tooth cutter to the largest."""


@dataclass(frozen=True, eq=False)
class ShaperCutter(ReferenceDimensions):
    """A pinion-type shaper cutter (Schneidrad) with a rounded tooth tip.

    Parameters
    ----------
    teeth : int
        Number of teeth z0, within :data:`CUTTER_TEETH_RANGE`.
    module : float
        Normal module m, mm.
    pressure_angle : float
        Normal pressure angle alpha_n, rad.
    helix_angle : float
        Helix angle beta, rad (a helical cutter with the helical guide of the gear it cuts).
    shift : float
        Profile shift coefficient x0 of the cutter (in normal modules), from -1 to 1.5.
    addendum : float
        Cutter addendum factor h_a0* (the internal gear's dedendum), from 0.5 to 2.
    tip_radius_factor : float
        Tip rounding rho_a0* (radius / m), from 0 to :attr:`tip_radius_limit`.

    Raises
    ------
    DesignError
        A value out of its range, or a tooth pointed at its tip (naming ``cutter_shift``).
    """

    teeth: int
    module: float
    pressure_angle: float = 20.0 * DEG
    helix_angle: float = 0.0
    shift: float = 0.0
    addendum: float = 1.25
    tip_radius_factor: float = 0.25

    def __post_init__(self) -> None:
        lo, hi = CUTTER_TEETH_RANGE
        if not isinstance(self.teeth, (int, np.integer)) or not lo <= self.teeth <= hi:
            raise DesignError("cutter_teeth", f"a whole number from {lo} to {hi}", self.teeth)
        if not (np.isfinite(self.module) and MODULE_RANGE[0] <= self.module <= MODULE_RANGE[1]):
            raise DesignError("module", f"a length from {MODULE_RANGE[0]:g} to {MODULE_RANGE[1]:g} mm", self.module)
        if not np.isfinite(self.shift) or not -1.0 <= self.shift <= 1.5:
            raise DesignError("cutter_shift", "between -1 and 1.5 modules", self.shift)
        if not (1.0 * DEG <= self.pressure_angle < 45.0 * DEG):
            raise DesignError("pressure_angle", "from 1 to below 45 degrees", float(self.pressure_angle / DEG))
        if not (-60.0 * DEG < self.helix_angle < 60.0 * DEG):
            raise DesignError("helix_angle", "between -60 and 60 degrees (exclusive)", round(self.helix_angle / DEG, 6))
        if not (np.isfinite(self.addendum) and 0.5 <= self.addendum <= 2.0):
            raise DesignError("cutter_addendum", "from 0.5 to 2 (factor of the module)", self.addendum)
        if self.tip_half_angle_sharp <= 0.0:
            largest = self._largest_unpointed_shift()
            if largest is None:
                raise DesignError(
                    "cutter_addendum", "smaller: the cutter's teeth are pointed at the tip for every shift from -1", self.addendum
                )
            allowed = f"at most {largest:.3f} so that the cutter's teeth are not pointed below the tip circle"
            raise DesignError("cutter_shift", allowed, self.shift)
        limit = self.tip_radius_limit
        if not (np.isfinite(self.tip_radius_factor) and 0.0 <= self.tip_radius_factor <= limit):
            raise DesignError(
                "cutter_tip_radius", f"from 0 to {limit:.4f} for this cutter (the tip roundings meet)", self.tip_radius_factor
            )

    def _largest_unpointed_shift(self) -> float | None:
        """Largest shift from -1 whose tooth keeps a tip land (bisection to 1e-4, rounded down to 0.001), or None."""

        def land(x: float) -> float:
            g = object.__new__(ShaperCutter)
            for name in ("teeth", "module", "pressure_angle", "helix_angle", "addendum", "tip_radius_factor"):
                object.__setattr__(g, name, getattr(self, name))
            object.__setattr__(g, "shift", x)
            return g.tip_half_angle_sharp

        lo, hi = -1.0, float(self.shift)
        if land(lo) <= 0.0:
            return None
        while hi - lo > 1e-4:
            mid = 0.5 * (lo + hi)
            lo, hi = (mid, hi) if land(mid) > 0.0 else (lo, mid)
        return math.floor(lo * 1000.0) / 1000.0

    # ----- closed forms (ISO 21771) ---------------------------------------------------------
    @property
    def tip_radius(self) -> float:
        """r_a0 = r0 + (h_a0* + x0) m, mm."""
        return self.pitch_radius + (self.addendum + self.shift) * self.module

    @property
    def base_half_angle(self) -> float:
        """Polar angle of the upper flank's involute on the base circle, rad.

        psi_b = (pi/2 + 2 x0 tan(alpha_n)) / z0 + inv(alpha_t): the half tooth angle at radius R is
        psi_b - inv(alpha_R) (ISO 21771 eq. 2.21 with s_t = m_t (pi/2 + 2 x tan(alpha_n))).
        """
        return (math.pi / 2.0 + 2.0 * self.shift * math.tan(self.pressure_angle)) / self.teeth + float(
            inv(self.transverse_pressure_angle)
        )

    def half_angle(self, radius: float) -> float:
        """Polar half-angle of the (unrounded) involute tooth at ``radius`` >= r_b0, rad."""
        return self.base_half_angle - float(inv(math.acos(min(self.base_radius / radius, 1.0))))

    @property
    def tip_half_angle_sharp(self) -> float:
        """Half-angle of the unrounded tooth on the tip circle, rad (<= 0: pointed)."""
        if self.tip_radius <= self.base_radius:
            return -1.0
        return self.half_angle(self.tip_radius)

    # ----- the tip rounding ------------------------------------------------------------------
    def _rounding(self, rho: float) -> tuple[float, tuple[float, float]]:
        """Roll angle u_K of the tangency with the involute and the centre K of a rounding of radius ``rho``.

        The involute's normal at roll angle u is tangent to the base circle at T(u) =
        r_b (cos g, sin g), g = psi_b - u; the centre lies on it at K = T + (r_b u - rho) (-sin g, cos g),
        and |K| = r_a0 - rho (tangent to the tip circle) gives r_b u_K = rho + sqrt((r_a0 - rho)^2 - r_b^2).
        """
        rb, ra = self.base_radius, self.tip_radius
        u = (rho + math.sqrt(max((ra - rho) ** 2 - rb * rb, 0.0))) / rb
        g = self.base_half_angle - u
        c, s = math.cos(g), math.sin(g)
        w = rb * u - rho
        return u, (rb * c - w * s, rb * s + w * c)

    @cached_property
    def tip_radius_limit(self) -> float:
        """Largest tip rounding factor rho_a0*: the two roundings meet on the tooth's centre line.

        By bisection of the polar angle of the rounding's centre (which falls as rho grows), also
        keeping r_a0 - rho >= r_b0.
        """
        m = self.module
        hi = min(self.tip_radius - self.base_radius, 1.0 * m)
        if self._rounding(hi)[1][1] >= 0.0:
            return hi / m
        lo = 0.0
        for _ in range(60):
            mid = 0.5 * (lo + hi)
            lo, hi = (mid, hi) if self._rounding(mid)[1][1] >= 0.0 else (lo, mid)
        return lo / m

    @property
    def tip_rounding(self) -> float:
        """rho_a0 = rho_a0* m, mm."""
        return self.tip_radius_factor * self.module

    @cached_property
    def rounding_roll(self) -> float:
        """Roll angle u_K of the involute where the tip rounding starts, rad."""
        return self._rounding(self.tip_rounding)[0]

    @cached_property
    def rounding_center(self) -> tuple[float, float]:
        """Centre K of the upper flank's tip rounding, mm."""
        return self._rounding(self.tip_rounding)[1]

    @property
    def tip_corner_angle(self) -> float:
        """Polar angle where the rounding meets the tip circle (the polar angle of K), rad."""
        kx, ky = self.rounding_center
        return math.atan2(ky, kx)

    def curves(self, low_roll: float = 0.0) -> dict[str, Curve]:
        """Return the upper half of tooth 0 as exact curves, counter-clockwise about the cutter.

        Parameters
        ----------
        low_roll : float
            Roll angle (rad) where the involute piece ends towards the root.

        Returns
        -------
        dict of str to Curve
            ``"tip"`` (:class:`~rotorcad.curves.Arc` on the tip circle, polar angle 0 to the
            rounding), ``"rounding"`` (Arc about K, from the tip circle to the involute; a corner for
            rho = 0) and ``"involute"`` (:class:`~rotorcad.curves.Involute`, roll angle from u_K down
            to ``low_roll``); mm.
        """
        kx, ky = self.rounding_center
        u_k = self.rounding_roll
        g = self.base_half_angle - u_k
        out: dict[str, Curve] = {"tip": Arc((0.0, 0.0), self.tip_radius, 0.0, self.tip_corner_angle)}
        out["rounding"] = Arc((kx, ky), self.tip_rounding, self.tip_corner_angle, g + math.pi / 2.0)
        out["involute"] = Involute(self.base_radius, self.base_half_angle, -1.0, u_k, low_roll)
        return out

    def summary(self) -> dict[str, object]:
        """Return the CONTRACT.md keys of the cutter (``cutter`` of ``rotorcad gear --internal``).

        Returns
        -------
        dict
            ``teeth``, ``shift``, ``pitch_radius``, ``base_radius``, ``tip_radius`` (mm),
            ``tip_rounding`` (mm).
        """
        return {
            "teeth": int(self.teeth),
            "shift": float(self.shift),
            "pitch_radius": self.pitch_radius,
            "base_radius": self.base_radius,
            "tip_radius": self.tip_radius,
            "tip_rounding": self.tip_rounding,
        }

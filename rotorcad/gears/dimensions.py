"""The reference dimensions every involute gear shares (ISO 21771).

One home for an external gear, an internal gear and a shaper cutter.
"""

from __future__ import annotations

import numpy as np

from rotorcad.gears.formulas import transverse_pressure_angle


class ReferenceDimensions:
    """Transverse module, transverse pressure angle, reference and base radius (ISO 21771, sec. 2).

    A mixin for a class with ``teeth`` (z), ``module`` (m_n, mm), ``pressure_angle`` (alpha_n,
    rad) and ``helix_angle`` (beta, rad): an external gear, an internal gear (its ``helix_angle``
    the cutter's) and a pinion-type shaper cutter.
    """

    teeth: int
    module: float
    pressure_angle: float
    helix_angle: float

    @property
    def transverse_module(self) -> float:
        """Transverse module m_t = m_n / cos(beta), mm (ISO 21771 eq. 2.3)."""
        return self.module / np.cos(self.helix_angle)

    @property
    def transverse_pressure_angle(self) -> float:
        """Transverse pressure angle alpha_t = atan(tan(alpha_n) / cos(beta)), rad (ISO 21771 eq. 2.5)."""
        return transverse_pressure_angle(self.pressure_angle, self.helix_angle)

    @property
    def pitch_radius(self) -> float:
        """Reference (pitch) radius r = z m_t / 2, mm (ISO 21771 eq. 2.6)."""
        return self.teeth * self.transverse_module / 2.0

    @property
    def base_radius(self) -> float:
        """Base radius r_b = r cos(alpha_t), mm (ISO 21771 eq. 2.8)."""
        return self.pitch_radius * np.cos(self.transverse_pressure_angle)


__all__ = ["ReferenceDimensions"]

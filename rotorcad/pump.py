"""External gear pump of two equal gears: instantaneous delivery, its irregularity and Fourier
series, trapped volume and pump frequency (Kollek & Osiński, *Innovative gear pump*, eqs. 2-9;
standard gear-pump theory).

The flow delivered at the meshing point depends on where the contact that separates suction from
discharge lies on the line of action: q = b w (r_a^2 - r_w^2 - u^2), u its distance from the pitch
point C. Each pair governs the delivery for one base pitch p_b from the start of its contact
(u = -g_a/2 for two equal gears, g_a = eps p_b): with s = u + g_a/2 in [0, p_b) this is Kollek's
eq. (2), q = Q_min + b w (s l - s^2) with l = eps p_b = g_a. Its mean is
b w (r_a^2 - r_w^2 - p_b^2 (eps^2/4 - eps/2 + 1/3)), which for eps = 1 is the textbook
b w (r_a^2 - r_w^2 - p_b^2/12). While two pairs touch, the volume between them (trapped volume)
changes at b w (u_2^2 - u_1^2): it shrinks until the two contacts lie symmetrically about C and
grows back. The pump (meshing) frequency is f = n z / 60 (eq. 9).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from rotorcad.gear import GearPair, InvoluteGear


@dataclass(frozen=True, eq=False)
class GearPump:
    gear: InvoluteGear
    face_width: float  # b, mm
    speed_rpm: float

    @property
    def pair(self) -> GearPair:
        return GearPair(self.gear, self.gear)

    @property
    def omega(self) -> float:
        return self.speed_rpm * 2.0 * np.pi / 60.0

    @property
    def contact_ratio(self) -> float:
        return self.pair.contact_ratio

    def delivery(self, samples: int = 4096, phi: np.ndarray | None = None) -> tuple[np.ndarray, np.ndarray]:
        """Rotation angle within one tooth period (rad; midpoints of ``samples`` equal steps unless
        ``phi`` is given) and the instantaneous delivery q (mm^3/s).
        """
        g = self.gear
        eps = self.contact_ratio
        pb = g.base_pitch
        rw = g.base_radius / np.cos(self.pair.working_pressure_angle)
        if phi is None:
            phi = (np.arange(samples) + 0.5) * (2.0 * np.pi / g.teeth) / samples
        s = g.base_radius * phi  # the contact moves r_b per rad along the line of action
        u = s - eps * pb / 2.0
        q = self.face_width * self.omega * (g.tip_radius**2 - rw**2 - u**2)
        return phi, q

    @property
    def mean_flow(self) -> float:
        """Mean delivery (mm^3/s)."""
        return float(self.delivery()[1].mean())

    @property
    def irregularity(self) -> float:
        """delta = (q_max - q_min) / q_mean."""
        q = self.delivery()[1]
        return float((q.max() - q.min()) / q.mean())

    @property
    def pump_frequency(self) -> float:
        """f = n z / 60 (Hz), eq. 9."""
        return self.speed_rpm * self.gear.teeth / 60.0

    def harmonics(self, count: int = 8) -> np.ndarray:
        """Amplitudes of the first ``count`` harmonics of the delivery over one tooth period,
        relative to the mean flow (numerical Fourier series).
        """
        q = self.delivery()[1]
        c = np.fft.rfft(q) / len(q)
        return 2.0 * np.abs(c[1 : count + 1]) / c[0].real

    def cosine_series(self, count: int = 8) -> np.ndarray:
        """a0 and |a_n| of q - Q_min in the even-extension series of Kollek & Osiński (eq. 3) over
        one base pitch, by numerical integration (trapezoid, 4096 samples), divided by b w t_z^2.
        """
        g = self.gear
        phi, q = self.delivery(phi=np.linspace(0.0, 2.0 * np.pi / g.teeth, 8193))
        s = g.base_radius * phi
        tz = g.base_pitch
        # Q_min is the delivery at s = 0, where s (l - s) of eq. (2) vanishes
        shape = (q - q[0]) / (self.face_width * self.omega)
        a0 = np.trapezoid(shape, s) / tz
        an = [2.0 / tz * np.trapezoid(shape * np.cos(k * np.pi * s / tz), s) for k in range(1, count + 1)]
        return np.concatenate([[a0], np.abs(an)]) / tz**2

    def trapped_volume(self, samples: int = 1024) -> tuple[np.ndarray, np.ndarray]:
        """Rotation angle over the double contact and the volume trapped between the two contacts
        (mm^3, relative to its value when the second contact begins).
        """
        g = self.gear
        eps = self.contact_ratio
        pb = g.base_pitch
        if eps <= 1.0:
            return np.zeros(0), np.zeros(0)
        duration = (eps - 1.0) * pb / g.base_radius
        phi = np.linspace(0.0, duration, samples)
        u1 = -eps * pb / 2.0 + g.base_radius * phi  # the new contact
        u2 = u1 + pb  # the old one, a base pitch ahead
        rate = self.face_width * (u2**2 - u1**2)  # dV/dphi = (q(u1) - q(u2)) / w: shrinks, then grows
        vol = np.concatenate([[0.0], np.cumsum(0.5 * (rate[1:] + rate[:-1]) * np.diff(phi))])
        return phi, vol


def kollek_coefficients(eps: float, count: int) -> np.ndarray:
    """Eqs. (4)-(6) of Kollek & Osiński divided by b w t_z^2: the even-extension cosine series
    q - Q_min = a0 + sum a_n cos(n pi s / t_z) over one base pitch t_z, with a0 = eps/2 - 1/3,
    a_n = -4/(pi n)^2 for even n and -4 (eps - 1)/(pi n)^2 for odd n (the printed a_2n / a_2n+1
    are these with the OCR's index garbled; the odd terms vanish as eps -> 1). Returned: a0 and the
    amplitudes |a_n|, n = 1..count.
    """
    n = np.arange(1, count + 1)
    amps = 4.0 / (np.pi * n) ** 2 * np.where(n % 2 == 0, 1.0, abs(eps - 1.0))
    return np.concatenate([[eps / 2.0 - 1.0 / 3.0], amps])

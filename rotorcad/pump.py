"""External gear pump of two equal gears (Kollek & Osiński, *Innovative gear pump*, eqs. 2-9).

Instantaneous delivery, its irregularity and Fourier series, trapped volume and pump frequency
(Kollek & Osiński; standard gear-pump theory).

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

from rotorcad.gears.involute_gear import InvoluteGear
from rotorcad.gears.pair import GearPair


@dataclass(frozen=True, eq=False)
class GearPump:
    """A pump of two equal external gears in mesh.

    Parameters
    ----------
    gear : InvoluteGear
        Either gear (both are the same).
    face_width : float, mm
        Face width b.
    speed_rpm : float, rpm
        Speed n of the gears.
    """

    gear: InvoluteGear
    face_width: float  # b, mm
    speed_rpm: float

    @property
    def pair(self) -> GearPair:
        """The two gears in mesh (:class:`rotorcad.gears.pair.GearPair` of the gear with itself)."""
        return GearPair(self.gear, self.gear)

    @property
    def omega(self) -> float:
        """Angular speed w = 2 pi n / 60, rad/s."""
        return self.speed_rpm * 2.0 * np.pi / 60.0

    @property
    def contact_ratio(self) -> float:
        """Transverse contact ratio eps of the pair."""
        return self.pair.contact_ratio

    def delivery(self, samples: int = 4096, phi: np.ndarray | None = None) -> tuple[np.ndarray, np.ndarray]:
        """Return the instantaneous delivery over one tooth period (Kollek & Osiński eq. 2).

        Parameters
        ----------
        samples : int
            Equal steps over the tooth period 2 pi / z (their midpoints), unless ``phi`` is given.
        phi : (k,) float array, rad, optional
            Rotation angles within the tooth period, from the start of a contact.

        Returns
        -------
        phi : (k,) float array, rad
            Rotation angles.
        q : (k,) float array, mm³/s
            Delivery q = b w (r_a^2 - r_w^2 - u^2).
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
    def swept_volume_flow(self) -> float:
        """Mean delivery by the textbook displacement of two equal gears, 2 pi b m_t^2 z n / 60 (mm^3/s).

        Per revolution each gear carries the annulus between its tip and pitch circles,
        pi b (r_a^2 - r^2), from suction to discharge; for a standard gear (ISO 21771: r = z m_t / 2,
        r_a = r + m_t) the pair's is 2 pi b m_t^2 (z + 1), and the textbook drops the "+ 1" for the oil
        carried back by the meshing teeth: V = 2 pi b m_t^2 z. It ignores the shift, the addendum and the
        contact ratio; :attr:`mean_flow` (Kollek & Osinski eq. 2) does not.

        Returns
        -------
        float, mm^3/s
        """
        g = self.gear
        return float(2.0 * np.pi * self.face_width * g.transverse_module**2 * g.teeth * self.speed_rpm / 60.0)

    @property
    def irregularity(self) -> float:
        """Delivery irregularity delta = (q_max - q_min) / q_mean (dimensionless)."""
        q = self.delivery()[1]
        return float((q.max() - q.min()) / q.mean())

    @property
    def pump_frequency(self) -> float:
        """Pump (meshing) frequency f = n z / 60, Hz (Kollek & Osiński eq. 9)."""
        return self.speed_rpm * self.gear.teeth / 60.0

    def harmonics(self, count: int = 8) -> np.ndarray:
        """Return the amplitudes of the first harmonics of the delivery over one tooth period.

        A numerical Fourier series of :meth:`delivery`.

        Parameters
        ----------
        count : int
            Number of harmonics.

        Returns
        -------
        (count,) float array
            Amplitudes relative to the mean flow.
        """
        q = self.delivery()[1]
        c = np.fft.rfft(q) / len(q)
        return 2.0 * np.abs(c[1 : count + 1]) / c[0].real

    def cosine_series(self, count: int = 8) -> np.ndarray:
        """Return the even-extension cosine series of q - Q_min (Kollek & Osiński eq. 3).

        Over one base pitch t_z, by numerical integration (trapezoid, 8193 samples), divided by
        b w t_z^2; compare :func:`kollek_coefficients`.

        Parameters
        ----------
        count : int
            Number of terms a_n.

        Returns
        -------
        (count + 1,) float array
            a0 and |a_1| ... |a_count|, dimensionless.
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
        """Return the volume trapped between the two contacts over the double contact.

        Parameters
        ----------
        samples : int
            Angles over the double contact.

        Returns
        -------
        phi : (samples,) float array, rad
            Rotation angle from the moment the second contact begins; empty when eps <= 1.
        volume : (samples,) float array, mm³
            Trapped volume relative to its value when the second contact begins.
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
    """Return the cosine series coefficients of Kollek & Osiński eqs. (4)-(6), divided by b w t_z^2.

    The even-extension cosine series q - Q_min = a0 + sum a_n cos(n pi s / t_z) over one base pitch
    t_z, with a0 = eps/2 - 1/3, a_n = -4/(pi n)^2 for even n and -4 (eps - 1)/(pi n)^2 for odd n (the
    printed a_2n / a_2n+1 are these with the OCR's index garbled; the odd terms vanish as eps -> 1).

    Parameters
    ----------
    eps : float
        Transverse contact ratio.
    count : int
        Number of terms a_n.

    Returns
    -------
    (count + 1,) float array
        a0 and the amplitudes |a_n|, n = 1..count, dimensionless.
    """
    n = np.arange(1, count + 1)
    amps = 4.0 / (np.pi * n) ** 2 * np.where(n % 2 == 0, 1.0, abs(eps - 1.0))
    return np.concatenate([[eps / 2.0 - 1.0 / 3.0], amps])

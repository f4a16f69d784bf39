"""External gear pump of two external gears (Kollek & Osiński, *Innovative gear pump*, eqs. 2-9).

Instantaneous delivery, its irregularity and Fourier series, trapped volume and pump frequency
(Kollek & Osiński; standard gear-pump theory).

The flow delivered at the meshing point depends on where the contact that separates suction from
discharge lies on the line of action. Each gear carries the oil between its tip circle and the
contact point's radius rho_i: per unit face width the delivery is
q' = w1/2 (r_a1^2 - rho_1^2) + w2/2 (r_a2^2 - rho_2^2), w2 = w1 z1/z2. With u the contact's
distance from the pitch point C along the line of action, rho_1^2 = r_w1^2 + 2 u r_w1 sin a_w + u^2
and rho_2^2 = r_w2^2 - 2 u r_w2 sin a_w + u^2, so the terms in u cancel:
q' = w1/2 [r_a1^2 - r_w1^2 + (z1/z2)(r_a2^2 - r_w2^2) - (1 + z1/z2) u^2]
(derived here; for two equal gears it is Kollek & Osiński's eq. 2 written about C,
q' = w (r_a^2 - r_w^2 - u^2); the scanned text of their eqs. 2-8 is damaged, so this is derived,
not copied). The gear (z1) drives: its contact runs from the mate's tip circle (or the usable
flank's end) towards its own tip, and each pair governs the delivery for one base pitch p_b from
the start of its contact (the new contact closes the discharge). For two equal gears the start is
u = -g_a/2, g_a = eps p_b, and with s = u + g_a/2 in [0, p_b) this is Kollek's eq. (2),
q = Q_min + b w (s l - s^2), l = eps p_b, of mean b w (r_a^2 - r_w^2 - p_b^2 (eps^2/4 - eps/2 + 1/3)).
For unequal gears the same parabola reads q = Q_min + b w1 (1 + z1/z2)/2 (s l - s^2) with s from the
start of contact u = -g_f (g_f the path of approach, from the mate's tip circle to C) and l = 2 g_f.

A helical pair's transverse sections mesh with their phases shifted along the face: at axial
position zeta the contact lies zeta tan(beta_b) further along the line of action, so the delivery
is the integral of q' over a window eps_beta p_b of the contact's travel (eps_beta = b sin(beta) /
(pi m_n), the overlap ratio); it is taken in closed form from the antiderivative of q'. With
eps_beta a whole number the window holds every phase alike and the delivery is steady.

While two pairs touch, the volume between them (trapped volume) changes at b (q'(u_new) -
q'(u_old)) / w1: it shrinks until the two contacts lie symmetrically about C and grows back. The
pump (meshing) frequency is f = n z / 60 (eq. 9).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from rotorcad.gears.involute_gear import InvoluteGear
from rotorcad.gears.pair import GearPair


@dataclass(frozen=True, eq=False)
class GearPump:
    """A pump of two external gears in mesh; the gear drives.

    Parameters
    ----------
    gear : InvoluteGear
        The driving gear z1 (and the mate too when ``mate`` is None: two equal gears).
    face_width : float, mm
        Face width b.
    speed_rpm : float, rpm
        Speed n of the gear.
    mate : InvoluteGear, optional
        The driven gear z2 (default: a copy of ``gear``).
    center_distance : float, mm, optional
        Working centre distance a_w (default: the zero-backlash distance of the shifts).
    """

    gear: InvoluteGear
    face_width: float  # b, mm
    speed_rpm: float
    mate: InvoluteGear | None = None
    center_distance: float | None = None

    @property
    def pair(self) -> GearPair:
        """The two gears in mesh (:class:`rotorcad.gears.pair.GearPair`; the gear with itself without a mate)."""
        return GearPair(self.gear, self.mate if self.mate is not None else self.gear, self.center_distance)

    @property
    def omega(self) -> float:
        """Angular speed of the gear w1 = 2 pi n / 60, rad/s."""
        return self.speed_rpm * 2.0 * np.pi / 60.0

    @property
    def contact_ratio(self) -> float:
        """Transverse contact ratio eps_alpha of the pair."""
        return self.pair.contact_ratio

    @property
    def overlap_ratio(self) -> float:
        """Overlap ratio eps_beta = b |sin(beta)| / (pi m_n) (ISO 21771 eq. 5.5); 0 for spur gears."""
        g = self.gear
        return float(self.face_width * abs(np.sin(g.helix_angle)) / (np.pi * g.module))

    @property
    def total_contact_ratio(self) -> float:
        """Total contact ratio eps_gamma = eps_alpha + eps_beta."""
        return self.contact_ratio + self.overlap_ratio

    def line_of_action(self) -> tuple[float, float, float, float]:
        """Return the line of action's figures, rolls in mm from T1 (the gear's base tangency point).

        Returns
        -------
        tuple of float
            (start of the governing contact, T1T2 length, the pitch point C, speed ratio z1/z2).
        """
        return self._line()

    def _line(self) -> tuple[float, float, float, float]:
        """Return (start of the governing contact, T1T2 length, C, speed ratio z1/z2), rolls in mm from T1."""
        pair = self.pair
        lo1, _, lo2, _ = pair.contact_interval()
        aw = pair.working_pressure_angle
        length = pair.working_center_distance * np.sin(aw)
        return max(lo1, lo2), float(length), self.gear.base_radius * np.tan(aw), self.gear.teeth / pair.mate.teeth

    def transverse_delivery(self, roll: np.ndarray) -> np.ndarray:
        """Return the delivery per unit face width with the governing contact at ``roll``.

        Parameters
        ----------
        roll : (k,) float array, mm
            The contact's distance from T1 (the gear's base tangency point) along the line of action.

        Returns
        -------
        (k,) float array, mm²/s
            q' = w1/2 (r_a1^2 - rho_1^2) + w2/2 (r_a2^2 - rho_2^2) (module docstring).
        """
        g, m = self.gear, self.pair.mate
        _, length, _, k = self._line()
        rho1 = g.base_radius**2 + roll**2
        rho2 = m.base_radius**2 + (length - roll) ** 2
        return 0.5 * self.omega * (g.tip_radius**2 - rho1 + k * (m.tip_radius**2 - rho2))

    def _antiderivative(self, s: np.ndarray) -> np.ndarray:
        """Integral of q' over the governing contact's travel from the start of one contact, s in mm (any size)."""
        g, m = self.gear, self.pair.mate
        start, length, _, k = self._line()
        c = g.tip_radius**2 - g.base_radius**2 + k * (m.tip_radius**2 - m.base_radius**2)

        def prim(x: np.ndarray) -> np.ndarray:
            return 0.5 * self.omega * (c * x - x**3 / 3.0 + k * (length - x) ** 3 / 3.0)

        pb = g.base_pitch
        turns, rest = np.divmod(s, pb)
        return turns * (prim(start + pb) - prim(start)) + prim(start + rest) - prim(start)

    def delivery(self, samples: int = 4096, phi: np.ndarray | None = None) -> tuple[np.ndarray, np.ndarray]:
        """Return the instantaneous delivery over one tooth period (Kollek & Osiński eq. 2, all of the face).

        Parameters
        ----------
        samples : int
            Equal steps over the tooth period 2 pi / z1 (their midpoints), unless ``phi`` is given.
        phi : (k,) float array, rad, optional
            Rotation angles of the gear within the tooth period, from the start of a contact (in the
            transverse section at one end of the face).

        Returns
        -------
        phi : (k,) float array, rad
            Rotation angles.
        q : (k,) float array, mm³/s
            Delivery: b q'(u) for spur gears, the integral of q' over the face for helical ones.
        """
        g = self.gear
        if phi is None:
            phi = (np.arange(samples) + 0.5) * (2.0 * np.pi / g.teeth) / samples
        s = g.base_radius * phi  # the contact moves r_b1 per rad along the line of action
        if self.overlap_ratio == 0.0:
            start = self._line()[0]
            return phi, self.face_width * self.transverse_delivery(start + np.mod(s, g.base_pitch))
        window = self.overlap_ratio * g.base_pitch  # b tan(beta_b)
        return phi, self.face_width * (self._antiderivative(s + window) - self._antiderivative(s)) / window

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
        carried back by the meshing teeth: V = 2 pi b m_t^2 z (z of the driving gear; for a mate of
        other teeth the annuli per revolution of the gear are the same to the "+ 1"). It ignores the
        shift, the addendum and the contact ratio; :attr:`mean_flow` (Kollek & Osinski eq. 2) does not.

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

        Of one transverse section's delivery over one base pitch t_z, by numerical integration
        (trapezoid, 8193 samples), divided by b w t_z^2; compare :func:`kollek_coefficients` (two
        equal gears).

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
        tz = g.base_pitch
        s = np.linspace(0.0, tz, 8193)
        q = self.transverse_delivery(self._line()[0] + s)  # one transverse section, as eq. 2
        # Q_min is the delivery at s = 0, where s (l - s) of eq. (2) vanishes
        shape = (q - q[0]) / self.omega
        a0 = np.trapezoid(shape, s) / tz
        an = [2.0 / tz * np.trapezoid(shape * np.cos(k * np.pi * s / tz), s) for k in range(1, count + 1)]
        return np.concatenate([[a0], np.abs(an)]) / tz**2

    def trapped_volume(self, samples: int = 1024) -> tuple[np.ndarray, np.ndarray]:
        """Return the volume trapped between the two contacts of one transverse section over the double contact.

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
        roll1 = self._line()[0] + g.base_radius * phi  # the new contact
        roll2 = roll1 + pb  # the old one, a base pitch ahead
        # dV/dphi = b (q'(new) - q'(old)) / w1: shrinks, then grows
        rate = self.face_width * (self.transverse_delivery(roll1) - self.transverse_delivery(roll2)) / self.omega
        vol = np.concatenate([[0.0], np.cumsum(0.5 * (rate[1:] + rate[:-1]) * np.diff(phi))])
        return phi, vol

    def trapped_area(self, samples: int = 64, tolerance: float = 2e-4) -> tuple[np.ndarray, np.ndarray]:
        """Return the trapped transverse area over the double contact, from the gears' outlines (shapely).

        :func:`rotorcad.pump_trapped.trapped_areas`: the loop between the two contacts along both
        outlines, per unit face width; :meth:`trapped_volume` is its change by the flow kinematics.

        Parameters
        ----------
        samples : int
            Phases over the double contact, both ends in.
        tolerance : float, mm
            Chord tolerance of the outlines.

        Returns
        -------
        phi : (samples,) float array, rad
            Rotation of the gear from the moment the second contact begins; empty when eps <= 1.
        area : (samples,) float array, mm²
            The trapped area of the transverse section.
        """
        from rotorcad.pump_trapped import trapped_areas

        phi, _ = self.trapped_volume(samples)
        return phi, (trapped_areas(self, phi, tolerance) if len(phi) else np.zeros(0))

    def trapped_flow_max(self, samples: int = 1025) -> float:
        """Return the largest rate at which the trapped space shrinks or grows, |dV/dt| = b |q'(u_new) - q'(u_old)|, mm³/s.

        The flow a relief groove must pass (Kollek & Osinski sec. 3.1); from the flow kinematics of
        :meth:`trapped_volume`, at its largest at the ends of the double contact. 0 when eps <= 1.
        """
        phi, _ = self.trapped_volume(samples)
        if not len(phi):
            return 0.0
        g = self.gear
        roll = self._line()[0] + g.base_radius * phi
        return float(
            self.face_width * np.abs(self.transverse_delivery(roll) - self.transverse_delivery(roll + g.base_pitch)).max()
        )


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

"""Gas pressure over the working cycle and the line loads it puts on the rotors (Rinder & Deix).

Rinder & Deix sec. 3.1: "the indicator diagram and the volume curve must be known". The chamber
angle theta is the male rotation since the chamber opened at the suction end
(:attr:`ChamberTable.cycle`); the cycle ends at 2 pi + wrap + (the female flute's overlap).

Built-in pressure (an ideal port model): suction pressure while the volume grows (the chamber is
open to the suction port until it is largest); then polytropic compression p = p_s (V_max / V)^n
until the chamber reaches the discharge port's control edge, given as a chamber angle or following
from a built-in volume ratio V_i (the edge is where V = V_max / V_i; by default V_i matches the
pressure ratio, (p_d / p_s)^(1/n)); from there discharge pressure. Or the pressure from an indicator
diagram the user gives (chamber angle, pressure).

Line loads (eq. 6): a chamber at overpressure p - p_s loads each rotor, per unit length, with
(p - p_s) times the chamber table's force of a unit overpressure at the section's phase, which
turns with the helix. That force is the real chamber's boundary
(:func:`rotorcad.working_chamber.chamber_table`) or eq. 5's tip-to-tip chord
(:func:`rotorcad.working_chamber.chord_table`), whichever table is given. The sections beyond the contact line belong to the
next chamber; beyond the chamber at the suction end the gas is at suction pressure and adds nothing.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from rotorcad.errors import DesignError
from rotorcad.roles import Side
from rotorcad.working_chamber import ChamberTable

BAR = 0.1  # N/mm^2


@dataclass(frozen=True)
class PressureCycle:
    """Pressure over the chamber angle of one working cycle.

    Attributes
    ----------
    angle : (n,) float, rad
        Chamber angle theta (male rotation since the chamber opened), increasing.
    volume : (n,) float, mm^3
        V(theta).
    pressure : (n,) float, N/mm^2 (absolute)
        p(theta).
    suction, discharge : float, N/mm^2
        p_s and p_d.
    closing, opening : float, rad
        Chamber angles at which the suction closes and the discharge opens (nan for a given
        indicator diagram).
    """

    angle: np.ndarray
    volume: np.ndarray
    pressure: np.ndarray
    suction: float
    discharge: float
    closing: float
    opening: float

    def overpressure(self, theta: np.ndarray) -> np.ndarray:
        """Return the overpressure p - p_s at chamber angles.

        Parameters
        ----------
        theta : float array, rad
            Chamber angles, any shape.

        Returns
        -------
        float array, N/mm²
            p - p_s, of the shape of ``theta``; 0 outside the cycle.
        """
        theta = np.asarray(theta, dtype=float)
        inside = (theta >= self.angle[0]) & (theta <= self.angle[-1])
        return np.where(inside, np.interp(theta, self.angle, self.pressure) - self.suction, 0.0)

    @property
    def volume_ratio(self) -> float:
        """Built-in volume ratio V_max / V(opening) (nan for an indicator diagram)."""
        if not np.isfinite(self.opening):
            return float("nan")
        return float(self.volume.max() / self.volume[np.searchsorted(self.angle, self.opening)])


def pressure_cycle(
    table: ChamberTable,
    suction_bar: float,
    discharge_bar: float,
    exponent: float = 1.4,
    volume_ratio: float | None = None,
    discharge_edge: float | None = None,
    indicator: np.ndarray | None = None,
    samples: int = 2001,
) -> PressureCycle:
    """Compute the pressure of a chamber over its cycle (module docstring).

    Parameters
    ----------
    table : ChamberTable
        The pair's chamber (for V(theta)).
    suction_bar, discharge_bar : float, bar (absolute)
        p_s < p_d.
    exponent : float
        Polytropic exponent n (1 <= n <= 2; 1.4 for air).
    volume_ratio : float, optional
        Built-in volume ratio V_i > 1 fixing the control edge; default (p_d/p_s)^(1/n).
    discharge_edge : float, rad, optional
        The control edge as a chamber angle (overrides ``volume_ratio``).
    indicator : (k, 2) float array, optional
        Indicator diagram: chamber angle (rad), absolute pressure (bar); replaces the built-in model.
    samples : int
        Points over the cycle.

    Returns
    -------
    PressureCycle
        Pressures in N/mm² (absolute); the control edge appears twice among the angles (the end of
        compression and the start of discharge).

    Raises
    ------
    DesignError
        Pressures that are not positive or not rising, an exponent outside [1, 2], a volume ratio
        or control edge the chamber does not reach, or a malformed indicator diagram.
    """
    for name, value in (("suction_pressure_bar", suction_bar), ("discharge_pressure_bar", discharge_bar)):
        if not (np.isfinite(value) and value > 0):
            raise DesignError(name, "a positive absolute pressure in bar", value)
    if not discharge_bar > suction_bar:
        raise DesignError("discharge_pressure_bar", f"above the suction pressure {suction_bar:g} bar", discharge_bar)
    if not (np.isfinite(exponent) and 1.0 <= exponent <= 2.0):
        raise DesignError("polytropic_exponent", "from 1 to 2", exponent)
    start, stop = table.cycle
    theta = np.linspace(0.0, stop - start, samples)
    volume = table.volume(start + theta)
    ps, pd = suction_bar * BAR, discharge_bar * BAR
    if indicator is not None:
        ind = np.asarray(indicator, dtype=float)
        if ind.ndim != 2 or ind.shape[1] != 2 or len(ind) < 2 or not np.all(np.diff(ind[:, 0]) >= 0):
            raise DesignError(
                "indicator diagram", "rows of (chamber angle, pressure) with angles that do not decrease", ind.shape
            )
        if not np.all(ind[:, 1] > 0):
            raise DesignError("indicator diagram", "positive absolute pressures in bar", float(ind[:, 1].min()))
        p = np.interp(theta, ind[:, 0], ind[:, 1] * BAR, left=ind[0, 1] * BAR, right=ind[-1, 1] * BAR)
        return PressureCycle(theta, volume, p, ps, pd, float("nan"), float("nan"))
    closing = int(np.argmax(volume))
    vmax = volume[closing]
    if discharge_edge is not None:
        if not (np.isfinite(discharge_edge) and theta[closing] < discharge_edge < theta[-1]):
            raise DesignError(
                "discharge_edge_deg",
                f"a chamber angle between the suction closing {np.degrees(theta[closing]):.1f} and the cycle's end "
                f"{np.degrees(theta[-1]):.1f} deg",
                None if discharge_edge is None else float(np.degrees(discharge_edge)),
            )
        edge = float(discharge_edge)
    else:
        vi = (pd / ps) ** (1.0 / exponent) if volume_ratio is None else float(volume_ratio)
        if not (np.isfinite(vi) and vi > 1.0):
            raise DesignError("volume_ratio", "a built-in volume ratio above 1", vi)
        after = np.nonzero(volume[closing:] <= vmax / vi)[0]
        if len(after) == 0:
            raise DesignError("volume_ratio", "one the chamber reaches (its smallest volume is near 0)", vi)
        i = closing + int(after[0])  # V crosses V_max / V_i between samples i - 1 and i: the edge exactly there
        v0, v1 = volume[i - 1], volume[i]
        edge = float(theta[i - 1] + (v0 - vmax / vi) / (v0 - v1) * (theta[i] - theta[i - 1]))
    # the edge as a node of its own, twice: the end of compression and the start of discharge
    j = int(np.searchsorted(theta, edge))
    v_edge = float(np.interp(edge, theta, volume))
    theta = np.concatenate([theta[:j], [edge, edge], theta[j:]])
    volume = np.concatenate([volume[:j], [v_edge, v_edge], volume[j:]])
    p = np.full(len(theta), ps)
    compress = np.arange(closing, j + 1)
    p[compress] = ps * (vmax / np.maximum(volume[compress], 1e-12)) ** exponent
    p[j + 1 :] = pd
    return PressureCycle(theta, volume, p, ps, pd, float(theta[closing]), edge)


def line_loads(
    table: ChamberTable, cycle: PressureCycle, male_teeth: int, male_angle: float, z: np.ndarray, rotor: Side
) -> np.ndarray:
    """Line load on a rotor along its length at one male angle (Rinder & Deix eq. 6 with the table's flute load).

    Parameters
    ----------
    table : ChamberTable
    cycle : PressureCycle
    male_teeth : int
        z1.
    male_angle : float, rad
        The male's angle (rotors' frame) in the discharge end section.
    z : (n,) float, mm
        Distances from the discharge end face, 0 <= z <= L.
    rotor : Side
        Which rotor.

    Returns
    -------
    (n, 2) float, N/mm
        q_x(z), q_y(z) in the rotors' frame, summed over the chambers under pressure.
    """
    start, stop = table.cycle
    pitch = 2 * np.pi / male_teeth
    # every chamber alive: discharge-end phases psi0 = angle + k pitch (+ whole turns) within the cycle
    first = int(np.floor((start - male_angle) / pitch))
    psi0 = male_angle + pitch * np.arange(first, int(np.ceil((stop - male_angle) / pitch)) + 1)
    psi0 = psi0[(psi0 >= start) & (psi0 < stop)]
    dp = cycle.overpressure(psi0 - start)  # (c,)
    psi = psi0[:, None] + 2 * np.pi * np.asarray(z, dtype=float)[None, :] / table.lead  # (c, n)
    return np.einsum("c,cnk->nk", dp, table.force_at(psi, rotor))

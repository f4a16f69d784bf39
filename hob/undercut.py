"""The undercut model of Kollek & Osiński (*Innovative gear pump*, eq. 1), and the limit shifts.

For gears cut by a hob with a trapezoidal profile. Eq. (1) as the paper prints it (OCR repaired;
r_z base radius, r_p pitch radius, y the effective tool addendum factor, x the profile shift, m0
the module, alpha0 the tool pressure angle)::

    p       = r_z - (r_p - (y - x) m0) / cos(alpha0)
    psi^2   = 2 p / r_z - (p / r_z)^2
    (1/45) v^4 - (1/3) v^2 + psi^2 = 0          (the smaller root v^2)
    phi     = (sin v - v cos v) / (1 - cos v)
    gamma   = v - phi                           (undercut angle)
    r'_z    = r_z sqrt(1 + phi^2)               (active base radius: |O P'|)

The effective tool addendum is the tool's addendum less the tip clearance l_w by which the tip
rounding or chamfer shifts the decisive tip line towards the tool root (the paper's sec. 2):
y = h_a0* - rho_a0* (1 - sin alpha0) for a rounded tip. The quartic is a truncated series, so the
model is exact only at the onset of undercut (p = 0); the exact envelope of
:class:`rotorcad.gears.involute_gear.InvoluteGear` is the reference it is reported against.

Limit shifts: x_g = y - z sin^2(alpha0) / 2 (theoretical: the tool's effective tip line passes the
interference point); the practical x'_g = (5/6) y - z sin^2(alpha0) / 2 of the customary rule that
tolerates a slight, ineffective undercut (z'_min = 5/6 z_min; for alpha0 = 20 deg, y = 1 this is
Niemann's (14 - z) / 17 within 0.015); the real limit x''_g, below which the contact ratio of a
pair starts to fall, follows from the exact envelope (:func:`real_limit_shift`).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from rotorcad.gears.involute_gear import InvoluteGear
from rotorcad.gears.pair import GearPair
from rotorcad.roots import bracket_root


@dataclass(frozen=True)
class UndercutModel:
    """The quantities of Kollek & Osiński's eq. (1) for one gear (module docstring).

    Parameters
    ----------
    p : float, mm
        p = r_z - (r_p - (y - x) m0) / cos(alpha0); > 0 when the effective tool tip line passes
        the interference point (undercut), <= 0 otherwise.
    psi : float
        sqrt(psi^2) of eq. (1).
    v : float, rad
        The smaller root of the quartic (NaN beyond the series' range).
    phi : float
        (sin v - v cos v) / (1 - cos v).
    gamma : float, rad
        Undercut angle v - phi.
    active_base_radius : float, mm
        r'_z = |O P'|, the radius of the undercut point (r_z without undercut).
    undercut : bool
        Whether the gear is undercut (p > 0).
    """

    p: float
    psi: float
    v: float
    phi: float
    gamma: float
    active_base_radius: float
    undercut: bool


def effective_addendum(tool_addendum: float, tip_radius: float, alpha0: float) -> float:
    """Return the effective tool addendum factor y = h_a0* - l_w* (Kollek & Osiński sec. 2).

    The tip clearance of a rounded tip is l_w* = rho_a0* (1 - sin alpha0).

    Parameters
    ----------
    tool_addendum : float
        Tool addendum factor h_a0*.
    tip_radius : float
        Tool tip radius factor rho_a0*.
    alpha0 : float, rad
        Tool pressure angle.

    Returns
    -------
    float
    """
    return tool_addendum - tip_radius * (1.0 - np.sin(alpha0))


def kollek_model(z: int, m0: float, alpha0: float, x: float, y: float) -> UndercutModel:
    """Evaluate eq. (1) of Kollek & Osiński as printed (see the module docstring).

    Parameters
    ----------
    z : int
        Teeth.
    m0 : float, mm
        Module.
    alpha0 : float, rad
        Tool pressure angle.
    x : float
        Profile shift (in modules).
    y : float
        Effective tool addendum factor (:func:`effective_addendum`).

    Returns
    -------
    UndercutModel
    """
    r_p = z * m0 / 2.0
    r_z = r_p * np.cos(alpha0)
    p = r_z - (r_p - (y - x) * m0) / np.cos(alpha0)
    if p <= 0.0:
        return UndercutModel(p, 0.0, 0.0, 0.0, 0.0, r_z, False)
    psi2 = 2.0 * p / r_z - (p / r_z) ** 2
    disc = 1.0 / 9.0 - 4.0 * psi2 / 45.0
    if disc < 0.0:  # beyond the series' range: no real root
        return UndercutModel(p, float(np.sqrt(psi2)), float("nan"), float("nan"), float("nan"), float("nan"), True)
    v2 = (1.0 / 3.0 - np.sqrt(disc)) / (2.0 / 45.0)
    v = float(np.sqrt(v2))
    phi = (np.sin(v) - v * np.cos(v)) / (1.0 - np.cos(v))
    return UndercutModel(p, float(np.sqrt(psi2)), v, float(phi), float(v - phi), float(r_z * np.sqrt(1.0 + phi * phi)), True)


def limit_shift(z: int, alpha0: float, y: float) -> float:
    """Return the theoretical limit shift x_g = y - z sin^2(alpha0) / 2 (no undercut for x >= x_g).

    Parameters
    ----------
    z : int
        Teeth.
    alpha0 : float, rad
        Tool pressure angle.
    y : float
        Effective tool addendum factor.

    Returns
    -------
    float
    """
    return y - z * np.sin(alpha0) ** 2 / 2.0


def practical_limit_shift(z: int, alpha0: float, y: float) -> float:
    """Return the practical limit shift x'_g = (5/6) y - z sin^2(alpha0) / 2 (z'_min = 5/6 z_min).

    Parameters
    ----------
    z : int
        Teeth.
    alpha0 : float, rad
        Tool pressure angle.
    y : float
        Effective tool addendum factor.

    Returns
    -------
    float
    """
    return 5.0 / 6.0 * y - z * np.sin(alpha0) ** 2 / 2.0


def real_limit_shift(
    z: int, m0: float, alpha0: float, y_addendum: float, tool_addendum: float = 1.25, tip_radius: float = 0.38
) -> float:
    """Find x''_g: the shift below which the undercut shortens the contact ratio of two equal gears.

    The mate's tip then reaches below the undercut point; found on the exact envelope by a root
    search between x_g - 1 and x_g + 0.2.

    Parameters
    ----------
    z : int
        Teeth of each gear.
    m0 : float, mm
        Module.
    alpha0 : float, rad
        Tool pressure angle.
    y_addendum : float
        Addendum factor of the gears.
    tool_addendum : float
        Tool addendum factor h_a0*.
    tip_radius : float
        Tool tip radius factor rho_a0*.

    Returns
    -------
    float
        x''_g; NaN when the contact is not shortened at one end of that range or is at the other.
    """

    def shortened(x: float) -> float:
        g = InvoluteGear(z, m0, alpha0, 0.0, x, addendum=y_addendum, dedendum=tool_addendum, tip_radius_factor=tip_radius)
        pair = GearPair(g, g)
        lo1, _, lo2, _ = pair.contact_interval()
        return lo1 - lo2  # > 0: the mate's tip contact starts below the usable involute

    xg = limit_shift(z, alpha0, effective_addendum(tool_addendum, tip_radius, alpha0))
    a, b = xg - 1.0, xg + 0.2
    if shortened(b) > 0 or shortened(a) < 0:
        return float("nan")
    root = bracket_root(shortened, (a, b), xtol=1e-10)
    return float("nan") if root is None else root

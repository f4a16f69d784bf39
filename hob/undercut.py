"""The undercut model of Kollek & Osiński (*Innovative gear pump*, eq. 1), and the limit shifts.

For gears cut by a hob with a trapezoidal profile. Eq. (1), OCR repaired (r_z base radius, r_p pitch
radius, y the effective tool addendum factor, x the profile shift, m0 the module, alpha0 the tool
pressure angle)::

    p       = r_z - (r_p - (y - x) m0) / cos(alpha0)
    psi^2   = 2 p / r_z - (p / r_z)^2
    (1/45) v^4 - (1/3) v^2 + psi^2 = 0          (the smaller root v^2)
    gamma   = (sin v - v cos v) / (1 - cos v)
    phi     = v - gamma                         (undercut angle)
    r'_z    = r_z sqrt(1 + phi^2)               (active base radius: |O P'|)

The OCR prints phi twice ("phi = (sin v - v cos v)/(1 - cos v)" and "phi = v - gamma"); the first
is gamma. Derivation (checked numerically, tests/test_cut_undercut_model.py): the model takes the
path of the tool's effective tip corner A for an extended involute of the base circle, the point
at the constant distance p from the line of action as that line rolls on the base circle (p is
A's distance from the line of action when the contact is at the interference point T1; p > 0
when the tip line passes T1, the undercut condition (y - x) m0 > r_p sin^2(alpha0)). In units of
r_z that point lies at radius sqrt((1 - p/r_z)^2 + gamma^2) = sqrt(1 - psi^2 + gamma^2) at its roll
angle gamma, the involute at sqrt(1 + phi^2) at its roll angle phi: the radii are equal where
gamma^2 = phi^2 + psi^2 and the polar angles where gamma - atan(gamma / (1 - p/r_z)) = -(phi - atan(phi));
v = gamma + phi, and the quartic is the series of these in v to fourth order. Solved exactly
instead, this model gives r'_z within 2 um of eq. (1) (module 4, z = 8 to 17); so the reading is
right, and eq. (1)'s error is the model's: the rack also slides along the flank relative to the
rolling line of action (A's distance from it is p + r_z tan(alpha0) gamma, not p), which the
model leaves out. Exact at the onset of undercut (p = 0), it puts the undercut point above the
exact envelope's by 0.25 p to 0.34 p (module 4, x = 0: +0.58 mm for z = 8, +0.43 for 11, +0.09 for 16,
+0.008 for 17), and :func:`transverse_model` evaluates it in the transverse section of a helical
gear. The effective tool addendum is the tool's addendum less the tip clearance l_w by which the
tip rounding or chamfer shifts the decisive tip line towards the tool root (the paper's sec. 2):
y = h_a0* - rho_a0* (1 - sin alpha0) for a rounded tip. The exact envelope of
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
    phi : float, rad
        Undercut angle v - gamma: the involute's roll angle at the undercut point.
    gamma : float, rad
        (sin v - v cos v) / (1 - cos v): the roll angle of the extended involute there.
    active_base_radius : float, mm
        r'_z = r_z sqrt(1 + phi^2) = |O P'|, the radius of the undercut point (r_z without undercut).
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
    """Evaluate eq. (1) of Kollek & Osiński (the module docstring: its reading and derivation).

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
    gamma = float((np.sin(v) - v * np.cos(v)) / (1.0 - np.cos(v)))
    phi = v - gamma
    return UndercutModel(p, float(np.sqrt(psi2)), v, phi, gamma, float(r_z * np.sqrt(1.0 + phi * phi)), True)


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


@dataclass(frozen=True)
class GearUndercut:
    """The undercut of a gear cut by its basic rack, as ``rotorcad hob`` states it.

    Parameters
    ----------
    undercut : bool
        Whether the tool's tip cuts into the involute it generated (the exact envelope,
        :attr:`rotorcad.gears.involute_gear.InvoluteGear.undercut`).
    radius : float or None, mm
        The undercut point r'_z: the flank is undercut from the root up to this radius, where the
        involute begins (the envelope's form radius); None without undercut.
    limit_shift : float
        The profile shift (in normal modules) from which the gear is not undercut
        (:func:`transverse_limit_shift`).
    min_teeth : float
        The fewest teeth without undercut at the gear's own shift, z_min = 2 (y - x) cos(beta) / sin^2(alpha_t).
    note : str or None
        The sentence of ``hob``'s ``notes``; None without undercut.
    """

    undercut: bool
    radius: float | None
    limit_shift: float
    min_teeth: float
    note: str | None


def transverse_limit_shift(z: int, alpha_n: float, beta: float, y: float) -> float:
    """Return the limit shift x_g = y - z sin^2(alpha_t) / (2 cos beta) of a helical gear (no undercut for x >= x_g).

    The tool's effective tip line, (y - x) m_n inside the pitch circle in every section, passes the
    interference point T1 of the transverse section, r sin^2(alpha_t) inside the pitch circle
    (ISO 21771 sec. 5; Niemann & Winter vol. II sec. 21): (y - x) m_n = z m_n sin^2(alpha_t) / (2 cos beta).
    For a spur gear the usual x_g = y - z sin^2(alpha) / 2 (:func:`limit_shift`).

    Parameters
    ----------
    z : int
        Teeth.
    alpha_n : float, rad
        Normal pressure angle of the tool.
    beta : float, rad
        Helix angle.
    y : float
        Effective tool addendum factor (:func:`effective_addendum`).

    Returns
    -------
    float
    """
    alpha_t = np.arctan(np.tan(alpha_n) / np.cos(beta))
    return float(y - z * np.sin(alpha_t) ** 2 / (2.0 * np.cos(beta)))


def transverse_model(g: InvoluteGear) -> UndercutModel:
    """Evaluate :func:`kollek_model` in the transverse section of a (helical) gear.

    The generating rack of the transverse section has the transverse module m_t = m_n / cos(beta)
    and pressure angle alpha_t = atan(tan(alpha_n) / cos(beta)); its heights are the normal rack's,
    so that (y - x) m_n = (y - x) cos(beta) m_t: the model takes y cos(beta) and x cos(beta). A new
    user's finding: at beta = 30 deg the normal-section model put z = 11's undercut point below
    the base circle and gave one for z = 12, which is not undercut.
    """
    cb = float(np.cos(g.helix_angle))
    y = effective_addendum(g.dedendum, g.tip_radius_factor, g.pressure_angle)
    return kollek_model(g.teeth, g.transverse_module, g.transverse_pressure_angle, g.shift * cb, y * cb)


def gear_undercut(g: InvoluteGear) -> GearUndercut:
    """Say whether and how far a gear is undercut by its basic rack, and the shift that avoids it.

    A hob makes an undercut gear (its tip makes the undercut), so the undercut is no reason against
    hobbing, but a tool engineer is told of it as of a rotor's undercut (:func:`hob.verdict.undercut_reasons`):
    where, how deep below the tip, and what avoids it. The undercut point is the exact envelope's
    (where the fillet generated by the tool's tip rounding meets the involute).

    Parameters
    ----------
    g : InvoluteGear
        The gear.

    Returns
    -------
    GearUndercut
    """
    y = effective_addendum(g.dedendum, g.tip_radius_factor, g.pressure_angle)
    x_min = transverse_limit_shift(g.teeth, g.pressure_angle, g.helix_angle, y)
    s2 = np.sin(g.transverse_pressure_angle) ** 2
    z_min = float(2.0 * (y - g.shift) * np.cos(g.helix_angle) / s2)
    if not g.undercut:
        return GearUndercut(False, None, x_min, z_min, None)
    r_f = float(g.form_radius)
    note = (
        f"the gear is undercut up to r = {r_f:.3f} mm, {g.tip_radius - r_f:.2f} mm below its tip "
        f"(its involute begins there, {r_f - g.base_radius:.3f} mm above the base circle r_b = {g.base_radius:.3f} mm): "
        f"the tool's tip runs past the interference point and cuts into the flank it generated; the hob makes this "
        f"undercut, so it is no reason against hobbing, but it thins the root and shortens the contact; "
        f"a profile shift x >= {x_min:.3f} avoids it (x = {g.shift:g}; at this shift z_min = {z_min:.1f} teeth)."
    )
    return GearUndercut(True, r_f, x_min, z_min, note)


def model_keys(g: InvoluteGear) -> dict[str, object]:
    """Return ``cut``'s keys of Kollek & Osiński's eq. (1) for a gear, with what the model is good for.

    ``undercut_radius_model`` (mm): r'_z of :func:`transverse_model`, None where the exact envelope
    has no undercut, where the quartic has no root, or where r'_z falls outside the flank between the
    base and the pitch circle (a new user's finding: 22.57 mm for z = 11, m = 4 above the 22 mm pitch
    circle, read as printed; 24.16 mm for z = 12 at beta = 30 deg, which is not undercut).
    ``undercut_radius_model_deviation`` (mm): r'_z less the exact envelope's undercut point.
    ``undercut_model_note``: the model's validity in one sentence (the module docstring).
    """
    model = transverse_model(g)
    radius = model.active_base_radius if model.undercut and g.undercut else None
    if radius is not None and not (g.base_radius <= radius <= g.pitch_radius):
        radius = None
    if not g.undercut:
        note = "no undercut: eq. (1) is not evaluated."
    elif radius is None:
        note = (
            f"eq. (1) has no undercut point on the flank for this gear (its series holds for psi^2 <= 5/16, here "
            f"{model.psi**2:.3f}): see undercut_radius_exact."
        )
    else:
        note = (
            "Kollek & Osinski eq. (1) takes the tool's effective tip corner for an extended involute of the base circle "
            f"at the constant distance p = {model.p:.3f} mm from the line of action, leaving out the rack's slide along "
            f"the flank: exact at the onset of undercut (p = 0), it lies {radius - g.form_radius:+.3f} mm from the exact "
            "undercut point here (0.25-0.34 p above it); undercut_radius_exact is the exact envelope's."
        )
    return {
        "undercut_radius_model": radius,
        "undercut_radius_model_deviation": None if radius is None else radius - g.form_radius,
        "undercut_model_note": note,
    }

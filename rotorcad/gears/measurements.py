"""The measurements that check an involute gear's tooth thickness: span W_k and dimension over balls M_d.

Both are closed forms of ISO 21771 (DIN 3960) on the generating profile shift x_E
(:func:`rotorcad.gears.allowances.generating_shift`), so that they hold for the nominal tooth and for
the tooth thinned by an allowance alike:

* the span (base tangent length) over k teeth, normal section,
  W_k = m_n cos(alpha_n) [pi (k - 0.5) + z inv(alpha_t)] + 2 x_E m_n sin(alpha_n),
  with k by the standard rule (:func:`span_teeth`);
* the dimension over two pins (spur) or balls (helical) of diameter D_M in opposite spaces,
  inv(alpha_Kt) = inv(alpha_t) + D_M / (z m_n cos(alpha_n)) - pi / (2 z) + 2 x_E tan(alpha_n) / z,
  d_K = d_b / cos(alpha_Kt), M_d = d_K + D_M (even z) or d_K cos(pi / (2 z)) + D_M (odd z, both balls
  in one transverse plane), with D_M by the standard rule (:func:`ball_diameter`).
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from rotorcad.errors import DesignError
from rotorcad.gears.allowances import ThicknessAllowance, generating_shift
from rotorcad.gears.formulas import base_helix_angle, inv, inv_inverse
from rotorcad.gears.involute_gear import InvoluteGear


def measuring_pressure_angle(gear: InvoluteGear, shift: float | None = None) -> float:
    """Return alpha_Mt, the transverse pressure angle on the measuring circle d_M = d + 2 x m_n.

    Parameters
    ----------
    gear : InvoluteGear
        The gear.
    shift : float, optional
        The profile shift x (default the gear's).

    Returns
    -------
    float, rad
        arccos(d_b / d_M) (ISO 21771, the measuring circle of the span); 0 where d_M <= d_b.
    """
    x = gear.shift if shift is None else shift
    r_m = gear.pitch_radius + x * gear.module
    return float(np.arccos(min(gear.base_radius / r_m, 1.0)))


def span_teeth(gear: InvoluteGear) -> int:
    """Return the number of teeth k the span is measured over, by the standard rule.

    k = z / pi [tan(alpha_Mt) / cos^2(beta_b) - 2 x tan(alpha_n) / z - inv(alpha_t)] + 0.5,
    rounded to the nearest whole number (a half upwards) and at least 1 (ISO 21771, DIN 3960): the caliper touches
    the flanks near the measuring circle d + 2 x m_n (k = z / 9 + 0.5 for an unshifted 20 degree
    spur gear).

    Parameters
    ----------
    gear : InvoluteGear
        The gear (nominal shift x).

    Returns
    -------
    int
        k, from 1 to z - 1.
    """
    z, an = gear.teeth, gear.pressure_angle
    bb = base_helix_angle(an, gear.helix_angle)
    a_m = measuring_pressure_angle(gear)
    at = gear.transverse_pressure_angle
    k = z / np.pi * (np.tan(a_m) / np.cos(bb) ** 2 - 2.0 * gear.shift * np.tan(an) / z - inv(at)) + 0.5
    # to the nearest, a half upwards (z = 99: 11.5 -> 12; 1e-9 against the rounding of the floats)
    return int(min(max(math.floor(float(k) + 0.5 + 1e-9), 1), z - 1))


def span(gear: InvoluteGear, k: int, allowance: float = 0.0) -> float:
    """Return the span W_k over k teeth in the normal section, mm (ISO 21771, DIN 3960).

    W_k = m_n cos(alpha_n) [pi (k - 0.5) + z inv(alpha_t)] + 2 x_E m_n sin(alpha_n); the allowance
    enters through x_E, as A_sn cos(alpha_n).

    Parameters
    ----------
    gear : InvoluteGear
        The nominal gear.
    k : int
        Teeth spanned, 1 to z - 1.
    allowance : float, mm
        Tooth-thickness allowance A_sn (normal section).

    Returns
    -------
    float, mm
        W_k; the transverse span along the base tangent is W_k / cos(beta_b).
    """
    m, an, z = gear.module, gear.pressure_angle, gear.teeth
    x_e = generating_shift(gear, allowance)
    return float(m * np.cos(an) * (np.pi * (k - 0.5) + z * inv(gear.transverse_pressure_angle)) + 2.0 * x_e * m * np.sin(an))


def span_contact_radius(gear: InvoluteGear, span_normal: float) -> float:
    """Return the radius where the caliper touches the flanks for a span (transverse section), mm.

    The contact points lie on a base tangent, half the transverse span W_k / cos(beta_b) from its
    point of tangency: r = sqrt(r_b^2 + (W_k / (2 cos(beta_b)))^2).

    Parameters
    ----------
    gear : InvoluteGear
        The gear.
    span_normal : float, mm
        W_k in the normal section.

    Returns
    -------
    float, mm
    """
    bb = base_helix_angle(gear.pressure_angle, gear.helix_angle)
    half = span_normal / (2.0 * np.cos(bb))
    return float(np.hypot(gear.base_radius, half))


def ball_center_angle(gear: InvoluteGear, diameter: float, allowance: float = 0.0) -> float:
    """Return alpha_Kt, the transverse pressure angle on the circle of the ball (pin) centres, rad.

    inv(alpha_Kt) = inv(alpha_t) + D_M / (z m_n cos(alpha_n)) - pi / (2 z) + 2 x_E tan(alpha_n) / z
    (ISO 21771, DIN 3960): a ball of radius rho touching both flanks of a space has its centre on the
    involute helicoid offset by rho, the same helicoid turned by rho / (r_b cos(beta_b)).

    Parameters
    ----------
    gear : InvoluteGear
        The nominal gear.
    diameter : float, mm
        Ball or pin diameter D_M.
    allowance : float, mm
        Tooth-thickness allowance A_sn.

    Returns
    -------
    float, rad
    """
    z, m, an = gear.teeth, gear.module, gear.pressure_angle
    x_e = generating_shift(gear, allowance)
    value = inv(gear.transverse_pressure_angle) + diameter / (z * m * np.cos(an)) - np.pi / (2.0 * z) + 2.0 * x_e * np.tan(an) / z
    return float(inv_inverse(value))


def over_balls(gear: InvoluteGear, diameter: float, allowance: float = 0.0) -> float:
    """Return the dimension over two balls (or pins) M_d in opposite spaces, mm (ISO 21771, DIN 3960).

    d_K = d_b / cos(alpha_Kt) (:func:`ball_center_angle`); M_d = d_K + D_M for an even number of
    teeth, d_K cos(pi / (2 z)) + D_M for an odd one (the two balls in one transverse plane, in the
    spaces nearest to opposite). For a spur gear pins and balls read the same.

    Parameters
    ----------
    gear : InvoluteGear
        The nominal gear.
    diameter : float, mm
        D_M.
    allowance : float, mm
        Tooth-thickness allowance A_sn.

    Returns
    -------
    float, mm
    """
    d_k = 2.0 * gear.base_radius / np.cos(ball_center_angle(gear, diameter, allowance))
    if gear.teeth % 2:
        d_k *= np.cos(np.pi / (2.0 * gear.teeth))
    return float(d_k + diameter)


def ball_diameter(gear: InvoluteGear) -> float:
    """Return the ball (pin) diameter D_M by the standard rule, rounded to 1 um.

    The ball that touches the flanks on the measuring circle d_M = d + 2 x m_n (the span's,
    :func:`measuring_pressure_angle`; ISO 21771, DIN 3960): its centre lies on the same base
    tangent, rho / cos(beta_b) further, and on the space's centre line, so that
    alpha_Kt = tan(alpha_Mt) - inv(alpha_t) - 2 x tan(alpha_n) / z + pi / (2 z) and
    D_M = 2 r_b cos(beta_b) (tan(alpha_Kt) - tan(alpha_Mt)). For an unshifted 20 degree gear of
    many teeth, D_M -> pi m_n / (2 cos(alpha_n)) = 1.672 m_n, the familiar 1.68 m.

    Parameters
    ----------
    gear : InvoluteGear
        The gear (nominal shift).

    Returns
    -------
    float, mm
        D_M; 0 or less where no ball touches there (few teeth and a large shift: the base tangent
        through the contact point leaves the space before it meets the space's centre line).
    """
    z, an = gear.teeth, gear.pressure_angle
    a_m = measuring_pressure_angle(gear)
    a_k = np.tan(a_m) - inv(gear.transverse_pressure_angle) - 2.0 * gear.shift * np.tan(an) / z + np.pi / (2.0 * z)
    bb = base_helix_angle(an, gear.helix_angle)
    d = 2.0 * gear.base_radius * np.cos(bb) * (np.tan(a_k) - np.tan(a_m))
    return float(round(d, 6))


def ball_contact_radius(gear: InvoluteGear, diameter: float, allowance: float = 0.0) -> float:
    """Return the transverse radius where a ball (pin) touches the flanks, mm.

    The contact lies on the base tangent through the centre, rho / cos(beta_b) before it:
    r = sqrt(r_b^2 + (r_b tan(alpha_Kt) - D_M / (2 cos(beta_b)))^2).

    Parameters
    ----------
    gear : InvoluteGear
        The nominal gear.
    diameter : float, mm
        D_M.
    allowance : float, mm
        A_sn.

    Returns
    -------
    float, mm
    """
    bb = base_helix_angle(gear.pressure_angle, gear.helix_angle)
    roll = gear.base_radius * np.tan(ball_center_angle(gear, diameter, allowance)) - diameter / (2.0 * np.cos(bb))
    return float(np.hypot(gear.base_radius, roll))


def measurements(
    gear: InvoluteGear, allowance: ThicknessAllowance | None = None, k: int | None = None, diameter: float | None = None
) -> dict[str, Any]:
    """Return the span and the dimension over balls of a gear, nominal and for its allowances.

    Parameters
    ----------
    gear : InvoluteGear
        The nominal gear.
    allowance : ThicknessAllowance, optional
        Its allowances (default none: upper = lower = nominal).
    k : int, optional
        Teeth spanned (default :func:`span_teeth`).
    diameter : float, optional
        Ball or pin diameter, mm (default :func:`ball_diameter`).

    Returns
    -------
    dict
        The CONTRACT.md keys: ``thickness_allowance`` ({upper, lower}, mm), ``span_teeth`` (k),
        ``span`` ({nominal, upper, lower}, mm, normal section), ``span_contact_radius`` (mm,
        nominal), ``span_touches_flank`` (bool: that contact lies on the usable involute, between
        the form and the tip circle), ``pin_diameter`` (mm), ``over_pins`` ({nominal, upper,
        lower}, mm; balls for a helical gear), ``pin_contact_radius`` (mm, nominal),
        ``pin_touches_flank`` (bool, likewise). Where the standard rule finds no ball
        (:func:`ball_diameter` not above 0) and none is given, the pin's values are None.

    Raises
    ------
    DesignError
        ``span_teeth`` not from 1 to z - 1; ``pin_diameter`` not positive or so large that the
        pin's centre would lie beyond the involute's reach (no solution).
    """
    allowance = allowance or ThicknessAllowance()
    allowance.check(gear.module)
    if k is None:
        k = span_teeth(gear)
    elif not (isinstance(k, (int, np.integer)) and 1 <= k <= gear.teeth - 1):
        raise DesignError("span_teeth", f"a whole number from 1 to {gear.teeth - 1} (the teeth less one)", k)
    if diameter is None:
        diameter = ball_diameter(gear)
        if not diameter > 0.0:
            diameter = None
    elif not (np.isfinite(diameter) and 0.0 < diameter <= 5.0 * gear.module):
        raise DesignError("pin_diameter", f"a diameter above 0 and at most {5.0 * gear.module:.6g} mm (5 modules)", diameter)
    limits = allowance.limits()

    def on_flank(r: float | None) -> bool:
        return r is not None and math.isfinite(r) and gear.form_radius - 1e-9 <= r <= gear.tip_radius + 1e-9

    w = {name: span(gear, int(k), a) for name, a in limits.items()}
    w_contact = span_contact_radius(gear, w["nominal"])
    m_d: dict[str, float | None] = dict.fromkeys(limits)
    contact = None
    if diameter is not None:
        m_d = {name: over_balls(gear, diameter, a) for name, a in limits.items()}
        contact = ball_contact_radius(gear, diameter)
    return {
        "thickness_allowance": {"upper": float(allowance.upper), "lower": float(allowance.lower)},
        "span_teeth": int(k),
        "span": w,
        "span_contact_radius": w_contact,
        "span_touches_flank": on_flank(w_contact),
        "pin_diameter": None if diameter is None else float(diameter),
        "over_pins": m_d,
        "pin_contact_radius": contact,
        "pin_touches_flank": on_flank(contact),
    }


__all__ = [
    "ball_center_angle",
    "ball_contact_radius",
    "ball_diameter",
    "measurements",
    "measuring_pressure_angle",
    "over_balls",
    "span",
    "span_contact_radius",
    "span_teeth",
]

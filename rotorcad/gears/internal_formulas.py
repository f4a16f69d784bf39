"""Closed forms of an internal gear pair (ISO 21771, DIN 3993): working pressure angle, centre distance, interference.

Conventions: tooth counts z1 < z2 are positive (z2 the internal gear's), and the internal gear's
profile shift x2 is positive where it widens the tooth spaces (moves the profile away from the
gear's axis, as a deeper-fed shaper cutter does). ISO 21771 and DIN 3960 write the same relations
with a negative z2 and x2 of the opposite sign: their inv(alpha_w) = inv(alpha) + 2 tan(alpha)
(x1 + x2) / (z1 + z2) is the form used here with z2 -> -z2, x2 -> -x2. The pinion of the pair may
also be the shaper cutter that generates the internal gear (z1 = z0, x1 = x0).

Frame of the pair (ARCHITECTURE.md conventions, for an internal mesh): internal gear about the
origin, pinion about O1 = (a, 0), both turning the same way; pitch point C = (r_w2, 0).
"""

from __future__ import annotations

import math

from rotorcad.gears.formulas import inv, inv_inverse


def internal_working_pressure_angle(z1: int, z2: int, x1: float, x2: float, alpha_t: float, alpha_n: float) -> float:
    """Return the working transverse pressure angle of an internal pair without backlash.

    inv(alpha_wt) = inv(alpha_t) + 2 tan(alpha_n) (x2 - x1) / (z2 - z1) (ISO 21771 eq. 4.14 with
    the signs of the module docstring; DIN 3993).

    Parameters
    ----------
    z1, z2 : int
        Teeth of the pinion (or cutter) and of the internal gear, z2 > z1.
    x1, x2 : float
        Their profile shifts, normal modules.
    alpha_t, alpha_n : float, rad
        Transverse and normal pressure angles.

    Returns
    -------
    float, rad
        alpha_wt.
    """
    return float(inv_inverse(float(inv(alpha_t)) + 2.0 * math.tan(alpha_n) * (x2 - x1) / (z2 - z1)))


def internal_center_distance(r1: float, r2: float, alpha_t: float, alpha_wt: float) -> float:
    """Return the centre distance a_w = (r2 - r1) cos(alpha_t) / cos(alpha_wt), mm (ISO 21771 eq. 4.16, DIN 3993).

    Parameters
    ----------
    r1, r2 : float, mm
        Reference radii of the pinion and the internal gear (z m_t / 2).
    alpha_t, alpha_wt : float, rad
        Transverse and working transverse pressure angles.

    Returns
    -------
    float, mm
    """
    return (r2 - r1) * math.cos(alpha_t) / math.cos(alpha_wt)


def roll_length(radius: float, base_radius: float) -> float:
    """Return the roll length sqrt(R^2 - r_b^2) of the point of radius R on its line of action, mm (0 inside r_b)."""
    return math.sqrt(max(radius * radius - base_radius * base_radius, 0.0))


def involute_interference_margin(
    tip_radius2: float, base_radius2: float, center_distance: float, alpha_wt: float, form_radius1: float, base_radius1: float
) -> float:
    """Return how far the internal gear's tip contact lies inside the pinion's usable involute, mm.

    Along the line of action, measured from T2 (the internal gear's base tangency point, the far
    end), the pinion's base tangency point T1 lies at a_w sin(alpha_wt) and the internal gear's
    tip touches at sqrt(r_a2^2 - r_b2^2). The tip must touch the pinion's involute at or above its
    form circle: margin = sqrt(r_a2^2 - r_b2^2) - a_w sin(alpha_wt) - sqrt(r_Ff1^2 - r_b1^2) >= 0.
    With the form circle at the base circle this is DIN 3993's involute interference
    (KHK: z1 / z2 >= 1 - tan(alpha_a2) / tan(alpha_w)).

    Parameters
    ----------
    tip_radius2, base_radius2 : float, mm
        r_a2 and r_b2 of the internal gear.
    center_distance : float, mm
        a_w.
    alpha_wt : float, rad
        Working transverse pressure angle.
    form_radius1, base_radius1 : float, mm
        The pinion's (or cutter's) form radius r_Ff1 and base radius r_b1.

    Returns
    -------
    float, mm
        The margin along the line of action; negative: involute interference.
    """
    along = roll_length(tip_radius2, base_radius2) - center_distance * math.sin(alpha_wt)
    return along - roll_length(form_radius1, base_radius1)


def trochoid_margin(
    z1: int, z2: int, tip_radius1: float, tip_radius2: float, center_distance: float, alpha_wt: float, base_radius1: float
) -> float:
    """Return the trochoid-interference margin of an internal pair, rad of the internal gear (DIN 3993; KHK).

    As a pinion tooth leaves the space, its tip corner passes the point P where the two tip circles
    cross, at polar angle theta1 about O1 (from the line of centres, away from O2) and theta2 about
    the internal gear's centre: cos(theta1) = (r_a2^2 - r_a1^2 - a^2) / (2 a r_a1),
    cos(theta2) = (a^2 + r_a2^2 - r_a1^2) / (2 a r_a2). The internal gear's tooth tip must then
    lie past P: z1/z2 (theta1 + inv(alpha_a1) - inv(alpha_wt)) + inv(alpha_wt) - inv(alpha_a2)
    - theta2 >= 0, with the flanks in contact on the leading side (the tooth thicknesses drop out
    through alpha_wt). The pinion's tip corner is taken sharp (conservative for a rounded tip).

    Parameters
    ----------
    z1, z2 : int
        Teeth of the pinion (cutter) and the internal gear.
    tip_radius1, tip_radius2 : float, mm
        r_a1 and r_a2.
    center_distance : float, mm
        a_w.
    alpha_wt : float, rad
        Working transverse pressure angle.
    base_radius1 : float, mm
        r_b1; r_b2 = r_b1 z2 / z1.

    Returns
    -------
    float, rad
        The margin (angle about the internal gear's centre); negative: trochoid interference.
        Where the tip circles do not cross: +inf when the pinion's tip circle stays inside the
        internal gear's (the tips never meet), -inf when it stays outside (the pinion's tips lie
        in the internal gear's teeth all round).
    """
    a, ra1, ra2 = center_distance, tip_radius1, tip_radius2
    c1 = (ra2 * ra2 - ra1 * ra1 - a * a) / (2.0 * a * ra1)
    c2 = (a * a + ra2 * ra2 - ra1 * ra1) / (2.0 * a * ra2)
    if not (-1.0 <= c1 <= 1.0 and -1.0 <= c2 <= 1.0):
        return math.inf if a + ra1 <= ra2 else -math.inf
    rb2 = base_radius1 * z2 / z1
    alpha_a1 = math.acos(min(base_radius1 / ra1, 1.0))
    alpha_a2 = math.acos(min(rb2 / ra2, 1.0))
    inv_w = float(inv(alpha_wt))
    theta1 = math.acos(c1) + float(inv(alpha_a1)) - inv_w
    return z1 / z2 * theta1 + inv_w - float(inv(alpha_a2)) - math.acos(c2)


def radial_margin(z1: int, z2: int, tip_radius1: float, tip_radius2: float, base_radius1: float, alpha_wt: float) -> float:
    """Return the margin against radial (trimming) interference of an internal pair, rad of the pinion (KHK).

    Moved radially out of mesh (assembly, or a shaper cutter fed radially at one position), the
    pinion's teeth must clear the internal gear's: theta1 + inv(alpha_a1) - inv(alpha_wt) >=
    (z2/z1) (theta2 + inv(alpha_a2) - inv(alpha_wt)), sin^2(theta1) = (1 - (cos(alpha_a1) /
    cos(alpha_a2))^2) / (1 - (z1/z2)^2), sin^2(theta2) = ((cos(alpha_a2) / cos(alpha_a1))^2 - 1) /
    ((z2/z1)^2 - 1) (KHK Technical Reference, internal gears, trimming interference; checked against
    a brute-force radial withdrawal with shapely in ``tests/test_internal_gear.py``).

    Parameters
    ----------
    z1, z2 : int
        Teeth of the pinion (cutter) and the internal gear.
    tip_radius1, tip_radius2 : float, mm
        r_a1 and r_a2.
    base_radius1 : float, mm
        r_b1; r_b2 = r_b1 z2 / z1.
    alpha_wt : float, rad
        Working transverse pressure angle.

    Returns
    -------
    float, rad
        The margin (left side minus right side); negative: the teeth collide when moved radially.
        +inf where the sines fall outside [0, 1] (the tip circles' pressure angles admit no collision point).
    """
    rb2 = base_radius1 * z2 / z1
    ca1, ca2 = base_radius1 / tip_radius1, rb2 / tip_radius2
    s1 = (1.0 - (ca1 / ca2) ** 2) / (1.0 - (z1 / z2) ** 2)
    s2 = ((ca2 / ca1) ** 2 - 1.0) / ((z2 / z1) ** 2 - 1.0)
    if not (0.0 <= s1 <= 1.0 and 0.0 <= s2 <= 1.0):
        return math.inf
    inv_w = float(inv(alpha_wt))
    left = math.asin(math.sqrt(s1)) + float(inv(math.acos(min(ca1, 1.0)))) - inv_w
    return left - z2 / z1 * (math.asin(math.sqrt(s2)) + float(inv(math.acos(min(ca2, 1.0)))) - inv_w)

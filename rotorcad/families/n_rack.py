"""The N rack: Stosic's rack-generated screw-rotor profile ("N" rotors, measured by Wu & Chi as N4).

Sources: N. Stosic and K. Hanjalic, *Development and optimization of screw machines with a
simulation model, Part I: Profile generation*, ASME J. Fluids Eng. 119 (1997) 659-663; N. Stosic,
I. K. Smith and A. Kovacevic, *Screw Compressors: Mathematical Modelling and Performance
Calculation*, Springer 2005, sec. 2.4 (the "N" rotor profile); Wu & Chi Table 1 for the
N4 pair's dimensions. The published construction names its features; what those sources leave to
the designer, and so what was chosen here, is said at each item.

The rack (one period, travelled in +x of the rack frame of CONTRACT.md, the male lobe a bulge to
y = h1, the rack bottom at y = -d1) is made of:

1. **Root land** on y = -d1: the female tip land and the male root circle.
2. **Driving root rounding**: a concave rack circle tangent to the rack bottom and to the driving
   flank (the male's root fillet and the rounded female tip on the driving side). Chosen: its radius
   ``driving_root_rounding`` x h1.
3. **Driving flank**: Stosic's generalised arc (x/a)^p + (y/b)^q = 1 (:class:`GeneralisedArc`), a
   quarter ending at the male tip with its tangent along the tip line. Chosen: its centre lies
   ``driving_center_depth`` x h1 = e below the pitch line under the male tip, b = h1 + e,
   a = ``driving_width`` x h1, exponents p (along the rack) and q (across it). p = q = 2, a = h1 and
   e = 0 is Lysholm's circle centred on the pitch line, whose flank stands perpendicular to the pitch
   line there (no side relief for a hob: Rinder's "schlecht wälzfräsbar"); a centre below the pitch
   line tilts the flank where it crosses the pitch line and moves the contact off C (a driving
   meshline of finite length, a transverse contact ratio above zero).
4. **Male tip land** on y = h1, ``tip_land`` mm long (0 by default).
5. **Sealing side, rotor-generated**: Stosic's rack carries two pieces that are not given on the
   rack but generated on it by circles given on the rotors: the male's sealing tip is a circle of
   radius r_m tangent to the male tip circle, the female's sealing tip a circle of radius r_f tangent
   to the female tip circle, and their rack images are the envelopes of those circles (each an
   offset trochoid, :class:`rotorcad.curves.PointPath`). Chosen: the two circles touch each other at
   one instant, at a point K whose common normal runs through the pitch point C, so that both rack
   images pass through K's rack point H with one tangent (no rack corner). In the limit r_m = r_f = 0
   the circles are the sharp tip corners and K is the housing cusp: Lysholm's point-generated
   sealing flank and a closed meshline; rounded tips open a small blow-hole. The male circle may be
   0 (a sharp male tip); the female's must be centred inside the female pitch circle (r_f > d1),
   or part of it has no generating position.
6. **Root land** again, closing the period.

Male tip and female tip land, roundings and the driving arc are rack pieces; each generates both
rotors by the envelope engine, and the male and female sealing tip circles come back from their
rack images, so the pair is rack-generated throughout (the racks derived back from either rotor
are this rack).
"""

from __future__ import annotations

from typing import Annotated

import numpy as np

from rotorcad.curves import Arc, GeneralisedArc, PointPath
from rotorcad.envelope import from_rack_frame
from rotorcad.errors import DesignError
from rotorcad.families.parameters import TipLand, between
from rotorcad.geometry import rotate, wrap_angle
from rotorcad.kinematics import Rotation
from rotorcad.roles import PieceRole
from rotorcad.roots import bracket_root
from rotorcad.rotor_pair import RotorPair
from rotorcad.screw_rotors import RackPiece, ScrewRotors, rack_arc, rack_line

Exponent = Annotated[float, between(1.5, 6.0, "between 1.5 and 6")]
"""An exponent of the driving flank's generalised arc."""


def sealing_contact(pair: RotorPair, male_radius: float, female_radius: float) -> np.ndarray:
    """Point K (fixed frame, mm) where the male and female sealing tip circles touch.

    The circles (radii ``male_radius`` r_m and ``female_radius`` r_f, mm) are tangent inside the
    male tip circle R1 and the female tip circle R2 and touch each other at K with their common
    normal through the pitch point C: with u = (K - C)/|K - C|, the male circle's centre is K - r_m u
    at |K - r_m u| = R1 - r_m and the female's is K + r_f u at |K + r_f u - O2| = R2 - r_f. Solved
    from the housing cusp (the solution for r_m = r_f = 0) by continuation in the radii.

    Returns
    -------
    (2,) float
        K in the fixed frame (male centre at the origin, female at (a, 0)), y > 0.
    """
    a, r1, r2 = pair.center_distance, pair.male_tip_radius, pair.female_tip_radius
    c = np.array([pair.male_pitch_radius, 0.0])
    o2 = np.array([a, 0.0])

    def residual(k: np.ndarray, rm: float, rf: float) -> np.ndarray:
        u = (k - c) / np.hypot(*(k - c))
        return np.array([np.hypot(*(k - rm * u)) - (r1 - rm), np.hypot(*(k + rf * u - o2)) - (r2 - rf)])

    from scipy import optimize  # only here: 0.3 s to import

    k = np.asarray(pair.housing_cusp, dtype=float)
    for share in np.linspace(0.1, 1.0, 10):
        args = (share * male_radius, share * female_radius)
        sol = optimize.root(residual, k, args=args, tol=1e-13)
        if not np.all(np.isfinite(sol.x)) or sol.x[1] <= 0 or np.abs(residual(sol.x, *args)).max() > 1e-9:
            raise DesignError(
                "[profile] male_tip_rounding",
                "small enough that the male and female sealing tip circles can touch with their normal through C",
                male_radius / pair.male_addendum,
            )
        k = sol.x
    return k


def n_rack(
    pair: RotorPair,
    driving_width: Annotated[float, between(0.3, 1.5, "between 0.3 and 1.5 (fraction of the male addendum)")] = 1.25,
    driving_exponent_along: Exponent = 2.0,
    driving_exponent_across: Exponent = 2.0,
    driving_center_depth: Annotated[float, between(0.0, 1.0, "between 0 and 1 (fraction of the male addendum)")] = 0.5,
    driving_root_rounding: Annotated[float, between(0.01, 1.0, "between 0.01 and 1 (fraction of the male addendum)")] = 0.3,
    tip_land: TipLand = 0.0,
    male_tip_rounding: Annotated[float, between(0.0, 0.5, "between 0 and 0.5 (fraction of the male addendum)")] = 0.05,
    female_tip_rounding: Annotated[
        float, between(0.0, 0.5, "between 0 and 0.5 (fraction of the male addendum) and above the female addendum over h1")
    ] = 0.1,
) -> ScrewRotors:
    """Stosic's N rack (see the module docstring for the construction and the choices made).

    Parameters
    ----------
    pair : RotorPair
        Tooth counts, centre distance and radii (mm); a male dedendum d1 >= 0 (the N4 pair has a
        female addendum of 1.61 mm).
    driving_width : float
        Semi-axis of the driving flank's generalised arc along the rack, as a fraction of h1.
    driving_exponent_along, driving_exponent_across : float
        Its exponents p (along the rack) and q (across it), from 1.5 to 6.
    driving_center_depth : float
        Depth e of the arc's centre below the pitch line, as a fraction of h1 (its semi-axis across
        the rack is h1 + e): the flank crosses the pitch line at an angle, which a hob needs.
    driving_root_rounding : float
        Radius of the concave rack circle joining the arc to the rack bottom, as a fraction of h1
        (the male's driving root fillet and the female's driving tip rounding).
    tip_land : float
        Male tip land along the rack, mm.
    male_tip_rounding, female_tip_rounding : float
        Radii of the male and female sealing tip circles, as fractions of h1.

    Returns
    -------
    ScrewRotors
        The pair with its rack chain, the male tip (end of the driving arc) at rack x = 0.
    """
    p_rack, h1, d1 = pair.rack_period, pair.male_addendum, pair.male_dedendum
    mesh = pair.mesh
    if d1 < -1e-9:
        raise DesignError(
            "male_root_radius",
            f"at most the male pitch radius {pair.male_pitch_radius:.6g} mm for the N rack",
            pair.male_root_radius,
        )
    d1 = max(d1, 0.0)
    a_drive = driving_width * h1
    rm, rf = male_tip_rounding * h1, female_tip_rounding * h1
    if not rf > d1:
        # the female circle's centre must lie inside the female pitch circle: then every normal of
        # the circle crosses the pitch circle and the whole circle meshes with the rack; with a
        # smaller radius its part nearest the tip has no generating position and the rotors overlap
        raise DesignError(
            "[profile] female_tip_rounding",
            f"above {d1 / h1:.4g} (the female addendum {d1:.4g} mm over h1) so that the female sealing tip circle is centred "
            "inside the female pitch circle",
            female_tip_rounding,
        )
    for key, radius, depth, value in (
        ("female_tip_rounding", rf, pair.female_tip_radius - pair.female_root_radius, female_tip_rounding),
        ("male_tip_rounding", rm, pair.male_tip_radius - pair.male_root_radius, male_tip_rounding),
    ):
        if radius > depth:
            raise DesignError(f"[profile] {key}", f"at most {depth / h1:.4g} (the tooth depth over h1)", value)

    # --- sealing side: the male and female tip circles touching at K at male angle t_h ---
    k = sealing_contact(pair, rm, rf)
    u = (k - mesh.pitch_point) / np.hypot(*(k - mesh.pitch_point))
    c_m, c_f = k - rm * u, k + rf * u  # circle centres in the fixed frame at t_h
    x_b = tip_land
    t_q = -x_b / pair.male_pitch_radius  # the male tip circle's point (x_b, h1) crosses O1O2
    t_h = t_q + float(np.arctan2(c_m[1], c_m[0]))
    c_m_body = rotate(c_m[None, :], -t_h)[0]
    c_f_body = mesh.female.to_body(c_f[None, :], t_h)[0]
    ang = float(np.arctan2(c_f[1], c_f[0] - pair.center_distance))  # about O2, in (pi/2, pi)
    t_g = t_h + wrap_angle(ang - np.pi) * pair.female_teeth / pair.male_teeth  # female tip point on O1O2
    male_circle = _envelope(pair, c_m_body, mesh.male, rm, t_q, t_h, k, t_h)
    female_circle = _envelope(pair, c_f_body, mesh.female, rf, t_h, t_g, k, t_h)
    x_g = float(_rack_point(pair, female_circle, t_g)[0])

    # --- driving side: the generalised arc and the root rounding tangent to it and the bottom ---
    arc, rounding = _driving_side(
        pair, a_drive, driving_center_depth * h1, driving_root_rounding * h1, driving_exponent_along, driving_exponent_across
    )
    x_start = float(rounding.center[1])  # rack x of the rounding's bottom
    if not x_g < x_start + p_rack - 1e-9:
        _refuse_overfull_lobe(
            pair,
            x_g,
            driving_width,
            (driving_center_depth, driving_root_rounding),
            (driving_exponent_along, driving_exponent_across),
        )
    rack: tuple[RackPiece, ...] = (
        RackPiece(rounding, "driving root fillet", "driving tip rounding"),
        RackPiece(arc, "driving flank (generalised arc)", "driving flank (generalised arc)"),
    )
    if tip_land > 0:
        rack += (RackPiece(rack_line(pair, (0.0, h1), (x_b, h1)), "tip arc", "root arc"),)
    # a male circle of radius 0 is a sharp tip corner: its rack image is the corner's path (Lysholm);
    # the female's is always a circle (r_f > d1 >= 0, checked above)
    male_role = PieceRole.MALE_CORNER_PATH if rm == 0 else PieceRole.CURVE
    rack += (
        RackPiece(male_circle, "sealing tip circle", "sealing flank (envelope of the male tip circle)", kind=male_role),
        RackPiece(female_circle, "sealing flank (envelope of the female tip circle)", "sealing tip circle"),
        RackPiece(rack_line(pair, (x_g, -d1), (x_start + p_rack, -d1)), "root arc", "tip arc"),
    )
    return ScrewRotors(pair, rack, "n-rack")


def _refuse_overfull_lobe(
    pair: RotorPair, x_g: float, width: float, depth_rounding: tuple[float, float], exponents: tuple[float, float]
) -> None:
    """Refuse a lobe that does not fit the rack period, naming the widest driving arc that fits.

    The sealing side ends at rack x = ``x_g`` (mm); the next lobe's driving foot must lie beyond
    it. The foot moves back as the driving arc widens, so the widest ``driving_width`` that fits
    with the other parameters as given is found by bisection (none from 0.3 up: the sealing side
    itself is too long, set by ``tip_land`` and the tip roundings).

    Raises
    ------
    DesignError
        Always: naming ``[profile] driving_width`` and its largest value that fits, or the keys
        that lengthen the sealing side.
    """
    h1, p_rack = pair.male_addendum, pair.rack_period

    def fits(w: float) -> bool:
        try:
            _, rounding = _driving_side(pair, w * h1, depth_rounding[0] * h1, depth_rounding[1] * h1, *exponents)
        except DesignError:
            return False
        return x_g < float(rounding.center[1]) + p_rack - 1e-9

    low, high = 0.3, width
    if not fits(low):
        raise DesignError(
            "[profile] tip_land",
            "small enough, with male_tip_rounding and female_tip_rounding, that the lobe fits the rack period",
            None,
            f"the sealing side alone ends at rack x = {x_g:.4g} mm, so no driving_width from 0.3 leaves room for the next lobe",
        )
    for _ in range(40):
        mid = 0.5 * (low + high)
        low, high = (mid, high) if fits(mid) else (low, mid)
    raise DesignError(
        "[profile] driving_width",
        f"at most {low:.4g} with the other [profile] values as given, so that the lobe fits the rack period",
        width,
    )


def _rack_xy(pair: RotorPair, p: np.ndarray) -> np.ndarray:
    """Rack-frame (x, y) of a fixed-frame point at t = 0, mm."""
    return np.array([p[1], p[0] - pair.male_pitch_radius])


def _driving_side(pair: RotorPair, a: float, depth: float, rounding: float, p: float, q: float) -> tuple[GeneralisedArc, Arc]:
    """Build the driving flank (generalised arc) and the root rounding that joins it to the rack bottom.

    The arc is the quarter (x/a)^p + ((y + e)/b)^q = 1 centred at rack (0, -e), e = ``depth``
    (mm), b = h1 + e, from its foot (-a, -e) to the male tip (0, h1). Its foot stands across the
    pitch line, which a rack flank may not below it (no generating position), so a concave rack
    circle of radius ``rounding`` (mm) tangent to the arc and to the rack bottom y = -d1 takes
    over before the foot: its centre P(s) + rho n(s) (n the normal into the gap) lies at
    y = -d1 + rho, solved for s. That needs rho > d1 - e. With e = 0 and rho = d1 the rounding
    is centred on the pitch line and meets the arc at its foot (the limit, which the strict check
    below refuses).

    Parameters
    ----------
    pair : RotorPair
        The pair (male addendum h1, dedendum d1 and pitch radius r1w), mm.
    a : float, mm
        Semi-axis of the arc along the rack.
    depth : float, mm
        Depth e of the arc's centre below the pitch line.
    rounding : float, mm
        Radius rho of the root rounding.
    p, q : float
        Exponents of the arc along and across the rack.

    Returns
    -------
    arc : GeneralisedArc
        The trimmed arc, fixed frame, travelled foot -> tip.
    rounding : Arc
        The root rounding, fixed frame, from the rack bottom to the arc.

    Raises
    ------
    DesignError
        ``[profile] driving_root_rounding`` unless rho > max(d1 - e, 0).
    """
    h1, d1 = pair.male_addendum, max(pair.male_dedendum, 0.0)
    r = pair.male_pitch_radius
    centre = from_rack_frame(np.array([[0.0, -depth]]), r)[0]
    e1 = from_rack_frame(np.array([[-a, 0.0]]), 0.0)[0]  # rack x -> fixed y, rack y -> fixed x
    e2 = from_rack_frame(np.array([[0.0, h1 + depth]]), 0.0)[0]
    arc = GeneralisedArc(tuple(centre), tuple(e1), tuple(e2), p, q)
    if not rounding > max(d1 - depth, 0.0):
        raise DesignError(
            "[profile] driving_root_rounding",
            f"above {max(d1 - depth, 0.0) / h1:.4g} (the male dedendum less the driving arc's centre depth, over h1) so that "
            "it meets the driving arc above its foot",
            rounding / h1,
        )

    def centre_height(s: float) -> float:
        pt, t = arc.evaluate(np.array([s]))
        xy, tr = _rack_xy(pair, pt[0]), np.array([t[0, 1], t[0, 0]])  # rack-frame point and tangent
        n = np.array([-tr[1], tr[0]])  # into the gap: the tangent turned counter-clockwise in the rack frame
        return float(xy[1] + rounding * n[1] - (-d1 + rounding))

    s_t = 0.0 if centre_height(0.0) >= -1e-12 else bracket_root(centre_height, (0.0, np.pi / 2), xtol=1e-15)
    pt, t = arc.evaluate(np.array([s_t]))
    xy, tr = _rack_xy(pair, pt[0]), np.array([t[0, 1], t[0, 0]])
    c_round = xy + rounding * np.array([-tr[1], tr[0]])
    psi_t = float(np.arctan2(xy[1] - c_round[1], xy[0] - c_round[0]))
    return arc.trimmed(s_t, np.pi / 2), rack_arc(pair, (float(c_round[0]), float(c_round[1])), rounding, -np.pi / 2, psi_t)


def _rack_point(pair: RotorPair, path: PointPath, t: float) -> np.ndarray:
    """Rack-frame (x, y) of ``path`` at motion parameter ``t``, mm."""
    p = path.frame(np.array([t]))[0][0]
    return np.array([p[1], p[0] - pair.male_pitch_radius])


def _envelope(
    pair: RotorPair, centre_body: np.ndarray, body: Rotation, radius: float, t0: float, t1: float, k: np.ndarray, t_k: float
) -> PointPath:
    """Build the rack image of a rotor circle over the motion t0 -> t1.

    The image is the path of the circle's centre offset by the radius to the side of the contact
    K, which it reaches at ``t_k``.

    Parameters
    ----------
    pair : RotorPair
        The pair (its mesh gives the rack's motion).
    centre_body : (2,) float array, mm
        Centre of the circle in the rotor's frame at t = 0.
    body : Rotation
        The rotor carrying the circle.
    radius : float, mm
        Radius of the circle.
    t0, t1 : float, rad
        Range of the motion parameter.
    k : (2,) float array, mm
        The contact K, fixed frame.
    t_k : float, rad
        Motion parameter at which the image passes through K.

    Returns
    -------
    PointPath
        The offset path in the rack's frame, with the offset (+radius or -radius) that passes
        through K at ``t_k``.

    Raises
    ------
    DesignError
        ``[profile] male_tip_rounding`` when neither offset reaches K (within 1e-6 max(1, radius) mm).
    """
    mesh = pair.mesh
    for side in (1.0, -1.0):
        path = PointPath(tuple(centre_body), body, mesh.rack, t0, t1, offset=side * radius)
        p_k = mesh.rack.to_fixed(path.frame(np.array([t_k]))[0], t_k)[0]
        if np.hypot(*(p_k - k)) < 1e-6 * max(1.0, radius):
            return path
    key = "male_tip_rounding" if body is mesh.male else "female_tip_rounding"
    raise DesignError(f"[profile] {key}", "such that the sealing tip circles touch at one point", radius / pair.male_addendum)


__all__ = ["n_rack", "sealing_contact"]

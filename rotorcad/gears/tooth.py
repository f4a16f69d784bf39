"""The generated tooth of an involute gear: which pieces of the tool cut it, and where they meet.

The tool's straight flank generates the involute, its tip arc the root fillet (the trochoid
family of the arc centre, offset by rho_a0), its tip line the root circle; the blank's tip circle
closes the tooth. Where the fillet cuts into the involute (undercut, DIN 3960 sec. 3.4) the two
generated curves are intersected and the outline follows the one nearer the tooth centre
(:func:`undercut_point`). Where the two flanks meet below the tip circle the tooth is pointed and
the tip circle is dropped. A flank that crosses the tooth's centre line severs the tooth
(:func:`severed`, :func:`severed_allowed`).
"""

from __future__ import annotations

import cmath
import math
from collections.abc import Callable
from dataclasses import dataclass, fields
from typing import TYPE_CHECKING, Literal

import numpy as np

from rotorcad.curves import Arc, Curve
from rotorcad.errors import DesignError
from rotorcad.gears.formulas import inv, inv_inverse
from rotorcad.gears.sampling import CROWDED, FILLET_GRID, chord_counts, span
from rotorcad.gears.tool import ToolCut
from rotorcad.geometry import Array, polar_angle, radius
from rotorcad.roots import bracket_root

if TYPE_CHECKING:
    from rotorcad.gears.involute_gear import InvoluteGear

ToothPiece = Literal["tip arc", "involute", "fillet", "root arc"]
"""A piece of the generated half tooth, from the tip towards the space centre."""


@dataclass(frozen=True)
class HalfTooth:
    """Upper half of tooth 0, from the tip centre line to the space centre (:func:`half_tooth`).

    Parameters
    ----------
    cuts : list of (ToothPiece, float, float, ToolCut or None)
        The pieces as (name, s_start, s_end, cutter): the tool parameters (the blank's tip arc:
        polar angles, rad) where the piece starts and ends along the counter-clockwise travel and
        the :class:`~rotorcad.gears.tool.ToolCut` that cuts it (None for the tip arc).
    roll : (float, float)
        (a0 mm, a1): the flank contact's roll distance L = a0 + a1 s.
    fillet_points : (m, 2) float array, mm
        The fillet at :data:`~rotorcad.gears.sampling.FILLET_GRID` parameters.
    fillet_counts : two (m,) float arrays
        Their :func:`~rotorcad.gears.sampling.chord_counts`.
    undercut, tip_pointed : bool
        Whether the fillet cuts into the involute; whether the flanks meet below the tip circle.
    tip_radius, form_radius : float, mm
        The cut gear's tip radius and the radius where the usable involute starts.
    undercut_radius : float or None, mm
        Radius of the undercut point P' (None without undercut).
    """

    cuts: list[tuple[ToothPiece, float, float, ToolCut | None]]
    roll: tuple[float, float]
    fillet_points: Array
    fillet_counts: tuple[Array, Array]
    undercut: bool
    tip_pointed: bool
    tip_radius: float
    form_radius: float
    undercut_radius: float | None


def half_tooth(gear: InvoluteGear) -> HalfTooth:
    """Upper half of tooth 0, from the tip centre line to the space centre.

    The roll distance of the flank's contact, L = a0 + a1 s, gives the undercut (a0 < 0: the
    tool's flank/fillet joint cuts below the interference point T1), the flank's ends on the
    tip circle and the form circle (R = sqrt(r_b^2 + L^2)); the involute's polar angle
    theta_c - inv(alpha_R) (ISO 21771 eq. 2.21) gives the pointed tip (inv(alpha) = theta_c on
    the centre line); the undercut point P' is where the fillet crosses the involute.

    Parameters
    ----------
    gear : InvoluteGear
        The gear (its tool's cutters, ``gear._cuts``, and its dimensions).

    Returns
    -------
    HalfTooth
        The pieces, roll, fillet samples and radii; :func:`tooth_pieces` gives the pieces as curves.
    """
    cuts = gear._cuts
    flank, fillet = cuts["flank"], cuts["tip arc"]
    rb, ra = float(gear.base_radius), float(gear.nominal_tip_radius)
    # flank parameter s runs from the tool's fillet tangency (s = 0) up to the top;
    # the interference point (contact at the base tangency T1) is where the roll vanishes.
    # a straight flank touches along the line of action, linearly in s: along = a0 + a1 s is the
    # roll distance from T1, and the generated radius is R = sqrt(r_b^2 + along^2)
    a0, a1 = flank.roll()
    undercut = bool(a0 < 0.0)
    s_a = (math.sqrt(ra * ra - rb * rb) - a0) / a1
    # the flank is an involute: polar angle + inv(alpha_R) is constant along it; taken at its top
    # (generated above the tip circle, well clear of the base circle where alpha_R is ill-conditioned)
    top = flank.point(flank.length)
    theta_c = cmath.phase(top) + inv(math.acos(rb / abs(top)))

    def flank_angle(r: Array) -> Array:
        return theta_c - inv(np.arccos(np.clip(rb / r, -1.0, 1.0)))

    tip_angle = theta_c - inv(math.acos(min(rb / ra, 1.0)))  # the flank's polar angle on the tip circle
    tip_pointed = bool(tip_angle <= 0.0)
    tip_radius = ra
    if tip_pointed:  # the flank meets the tooth centre line below the tip circle
        r_pt = rb / math.cos(inv_inverse(theta_c))
        s_a = (math.sqrt(r_pt * r_pt - rb * rb) - a0) / a1
        tip_radius = float(r_pt)
    fil_s0, fil_s1 = fillet_range = (gear._tool.arc_end, math.pi)  # fillet/flank joint to root
    s_low = 0.0
    if undercut:
        r_p, fil_s0 = undercut_point(fillet, fillet_range, flank_angle, rb)
        s_low = (math.sqrt(max(r_p * r_p - rb * rb, 0.0)) - a0) / a1
    form_radius = math.sqrt(rb * rb + (a0 + a1 * s_low) ** 2)
    pieces: list[tuple[ToothPiece, float, float, ToolCut | None]] = []
    if not tip_pointed:
        pieces.append(("tip arc", 0.0, tip_angle, None))
    pieces.append(("involute", float(s_a), float(s_low), flank))
    pieces.append(("fillet", float(fil_s0), float(fil_s1), fillet))
    if "tip line" in cuts:
        pieces.append(("root arc", cuts["tip line"].length, 0.0, cuts["tip line"]))  # the whole tip line
    # the fillet on a fine grid: checked for crossing the tooth centre line (severed), and its
    # curvature places the samples (grid_parameters)
    fillet_points, _, turning, speed = fillet.cut(span(fil_s0, fil_s1, FILLET_GRID), curvature=True)
    return HalfTooth(
        cuts=pieces,
        roll=(a0, a1),
        fillet_points=fillet_points,
        fillet_counts=chord_counts(turning, speed, abs(fil_s1 - fil_s0) / (FILLET_GRID - 1)),
        undercut=undercut,
        tip_pointed=tip_pointed,
        tip_radius=tip_radius,
        form_radius=form_radius,
        undercut_radius=form_radius if undercut else None,
    )


def tooth_pieces(gear: InvoluteGear) -> list[tuple[ToothPiece, Curve]]:
    """Return the pieces of the gear's :class:`HalfTooth` as exact curves.

    Parameters
    ----------
    gear : InvoluteGear
        The gear (its half tooth and the curves its tool pieces generate).

    Returns
    -------
    list of (str, Curve)
        The blank's tip arc (:class:`~rotorcad.curves.Arc`, polar angle from 0 to the flank's)
        and the :class:`~rotorcad.envelope.Generated` involute, fillet and root arc, trimmed to
        the tooth, with the tool parameters of the cutters.
    """
    gen = gear._generated
    source = {"involute": "flank", "fillet": "tip arc"}
    out: list[tuple[ToothPiece, Curve]] = []
    for name, s0, s1, _ in gear._half_tooth.cuts:
        if name == "tip arc":
            out.append((name, Arc((0.0, 0.0), gear.nominal_tip_radius, s0, s1)))
        elif name == "root arc":
            out.append((name, gen["tip line"]))  # untrimmed, as the whole tip line cuts it
        else:
            out.append((name, gen[source[name]].trimmed(s0, s1)))
    return out


def undercut_point(
    fillet: ToolCut, s_range: tuple[float, float], flank_angle: Callable[[Array], Array], rb: float
) -> tuple[float, float]:
    """Return the radius and fillet parameter of the undercut point P'.

    P' is where the fillet (trochoid) cuts the involute: the outermost sign change of the
    polar-angle gap between the fillet and the involute at the same radius, bracketed on a
    vectorised grid of 513 parameters (the whole fillet) and solved in its cell by Brent's method
    (:func:`rotorcad.roots.bracket_root`) on the gap of single points (:meth:`ToolCut.point`).
    Near the undercut limit P' lies just outside the base circle, in a grid cell with one end
    inside it, micro-radians from the fillet's start; a second pass, on a grid crowded towards that
    start (spacing growing like the square of the distance), takes the involute's polar angle
    inside the base circle as its start's, so that the gap stays continuous and the cell is
    bracketed. Where the fillet crosses the involute nowhere, the two are joined at the base circle.

    Parameters
    ----------
    fillet : ToolCut
        The tool's tip arc, which cuts the fillet.
    s_range : (float, float)
        Tool parameters (polar angles about the tip-arc centre, rad) of the fillet's ends, from
        its joint with the involute to the root.
    flank_angle : callable
        Polar angle of the involute at radii R (n,), mm: theta_c - inv(arccos(r_b / R)).
    rb : float
        Base radius, mm.

    Returns
    -------
    (float, float)
        Radius of P', mm, and the tool parameter of P' on the fillet; ``rb`` and the fillet's
        start where the fillet does not cross the involute (joined at the base circle).
    """

    def gap(s: Array) -> tuple[Array, Array]:
        p = fillet.cut(s)[0]
        r = radius(p)
        return polar_angle(p) - flank_angle(r), r

    def point_gap(s: float) -> float:
        p = fillet.point(s)
        return cmath.phase(p) - float(flank_angle(abs(p)))

    for near_base in (False, True):
        lo, hi = s_range
        # near the limit P' lies within micro-radians of the fillet's start (the tool's
        # flank/tip joint cuts next to T1): the second pass's grid crowds there
        s = lo + (hi - lo) * CROWDED if near_base else span(lo, hi, 513)
        g, r = gap(s)
        # near the undercut limit P' lies so close to the base circle that the grid cell
        # holding it has an end inside it: there the gap is taken to the involute's start
        # (flank_angle is constant below r_b), continuous across the base circle
        ok = np.isfinite(g) & ((r > rb) | near_base)
        change = np.nonzero(ok[:-1] & ok[1:] & (np.sign(g[:-1]) != np.sign(g[1:])))[0]
        if len(change) == 0:
            continue
        i = change[np.argmax(r[change])]
        s_star = bracket_root(point_gap, (s[i], s[i + 1]), xtol=0.0, values=(g[i], g[i + 1]))
        if s_star is None:
            continue
        r_star = abs(fillet.point(s_star))
        if r_star >= rb:  # else the fillet passed below the involute's start: no crossing
            return r_star, float(s_star)
    return rb, s_range[0]


def severed(gear: InvoluteGear) -> str:
    """Return why the generated flank (involute or root fillet) crosses the tooth's centre line.

    Crossing it, the flank meets its mirror image from the other flank and the outline crosses
    itself; "" when it does not. With few teeth and a negative shift the fillets meet low in the tooth and cut its head off
    (z = 3, x = -0.2); with a large positive shift the tooth is pointed before its involute starts
    (z = 12, x = 2.8).

    Parameters
    ----------
    gear : InvoluteGear
        The gear (possibly made without the check, see :func:`severed_allowed`).

    Returns
    -------
    str
        The reason, or "": the least product polar angle x radius (mm) over the involute (its
        ends) and the fillet (:data:`FILLET_GRID` points) is below -1e-9 m (m the module).
    """
    worst, at = 0.0, 0.0
    half = gear._half_tooth
    for name, s0, s1, cut in half.cuts:
        if name == "involute":
            # along the involute (above the base circle) the polar angle falls as the radius grows:
            # where it is negative, its product with the radius falls too, so the least product
            # (on a grid of the piece too, whose ends are grid points) is at an end
            for s in (s0, s1):
                p = cut.point(s)
                d = cmath.phase(p) * abs(p)
                if d < worst:
                    worst, at = d, abs(p)
        elif name == "fillet":
            pts = half.fillet_points
            d = polar_angle(pts) * radius(pts)
            i = int(np.argmin(d))
            if d[i] < worst:
                worst, at = float(d[i]), float(radius(pts[i : i + 1])[0])
    if worst >= -1e-9 * gear.module:
        return ""
    if at < gear.pitch_radius:
        return "the root fillets of the two flanks meet inside the tooth and cut its head off"
    return "the tooth is pointed below the start of its involute (no involute flank is left)"


def severed_allowed(gear: InvoluteGear) -> str:
    """Return the shifts nearest to ``gear.shift`` whose tooth holds together, to 0.001.

    They come from a scan of the allowed shift range (101 shifts up to 3) and bisection of its
    ends, on gears built without the check (:func:`severed`).

    Parameters
    ----------
    gear : InvoluteGear
        The gear whose shift severs the tooth (possibly made without the check).

    Returns
    -------
    str
        The allowed shifts for :class:`~rotorcad.errors.DesignError`, phrased to follow "must be":
        "from lo to hi", "at least lo" or "at most hi" for these teeth and this tool, the ends
        rounded inwards to 0.001; or a sentence that no shift from -2 to 3 leaves a tooth.
    """

    def whole(shift: float) -> bool:
        g = object.__new__(type(gear))
        for f in fields(gear):
            object.__setattr__(g, f.name, shift if f.name == "shift" else getattr(gear, f.name))
        try:
            return not severed(g)
        except (DesignError, ValueError, ArithmeticError):
            return False

    lowest = max(-2.0, -gear.addendum, gear.dedendum - gear.teeth / (2.0 * np.cos(gear.helix_angle))) + 1e-6
    grid = np.linspace(lowest, 3.0, 101)
    ok = np.array([whole(x) for x in grid])
    if not ok.any():
        return f"a value that leaves a tooth for {gear.teeth} teeth and this tool (none from -2 to 3 does)"

    def edge(good: float, bad: float) -> float:
        while abs(good - bad) > 2e-4:
            mid = 0.5 * (good + bad)
            good, bad = (mid, bad) if whole(mid) else (good, mid)
        return good

    k = int(np.argmin(np.where(ok, np.abs(grid - gear.shift), np.inf)))  # the nearest good grid shift
    lo_i, hi_i = k, k
    while lo_i > 0 and ok[lo_i - 1]:
        lo_i -= 1
    while hi_i < len(grid) - 1 and ok[hi_i + 1]:
        hi_i += 1
    lo = np.ceil(edge(grid[lo_i], grid[lo_i - 1]) * 1000.0) / 1000.0 if lo_i > 0 else None
    hi = np.floor(edge(grid[hi_i], grid[hi_i + 1]) * 1000.0) / 1000.0 if hi_i < len(grid) - 1 else None
    where = f"for {gear.teeth} teeth and this tool"
    if lo is not None and hi is not None:
        return f"from {lo:.3f} to {hi:.3f} {where}"
    return f"at least {lo:.3f} {where}" if lo is not None else f"at most {hi:.3f} {where}"

"""The tooth's tip corner broken by a chamfer or rounded, in the transverse section.

The corner where the involute flank meets the tip circle is replaced by

* a **tip chamfer** (ISO 21771 "tip chamfer", DIN 3960 *Kopfkantenbruch*) of radial height h_K: a
  straight line from the flank at the radius r_a - h_K to the tip circle, its two legs equal (the
  chord from the sharp corner to either end of the chamfer has one length), or
* a **tip rounding** (*Kopfkantenrundung*) of radius r_K: a circular arc tangent to the flank and to
  the tip circle, its centre at r_a - r_K from the gear axis and r_K from the flank along the flank's
  normal (the involute's normal is tangent to the base circle, ISO 21771 sec. 2.3).

Both keep the outline a chain of exact curves (the chamfer a :class:`~rotorcad.curves.Line`, the
rounding an :class:`~rotorcad.curves.Arc`), so the exact STEP makes one face of each (a plane or a
cylinder for a spur gear, a helicoid for a helical one) and the meshes and drawings follow the
sampled outline. The two flanks of a tooth are broken alike (mirrored in the tooth's centre line).
A break is refused where it would leave no tip land (the two flanks' breaks meet) or run below the
form circle (off the usable involute).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from rotorcad.curves import Arc, Curve, Line
from rotorcad.errors import DesignError
from rotorcad.geometry import perp_cw
from rotorcad.profile import Profile, Segment
from rotorcad.roots import bracket_root

BREAK_NAMES = {"chamfer": "tip chamfer", "rounding": "tip rounding"}
"""The segment names of the two kinds of break."""


@dataclass(frozen=True)
class TipBreak:
    """The upper flank's break of tooth 0 (the lower one is its mirror image in the x axis).

    Attributes
    ----------
    kind : {"chamfer", "rounding"}
        What breaks the corner.
    size : float, mm
        The chamfer's radial height h_K or the rounding's radius r_K.
    curve : Curve
        The break, travelled from the tip circle to the flank (counter-clockwise about the tooth).
    flank_parameter : float
        The flank curve's parameter where the break ends.
    tip_angle : float, rad
        Polar angle where the break leaves the tip circle (the tip land is +-tip_angle).
    flank_radius : float, mm
        Radius where the break meets the flank.
    """

    kind: str
    size: float
    curve: Curve
    flank_parameter: float
    tip_angle: float
    flank_radius: float


def _flank(gear) -> tuple[Curve, float, float]:
    """Return the upper involute as an exact curve, and its parameters at the tip and the form circle."""
    curve = dict(gear._pieces)["involute"]
    return curve, float(curve.s0), float(curve.s1)


def _parameter_at(gear, r: float) -> float:
    """Return the flank's tool parameter at radius r: R = sqrt(r_b^2 + (a0 + a1 s)^2) (the roll of the contact)."""
    a0, a1 = gear._half_tooth.roll
    return (math.sqrt(max(r * r - gear.base_radius**2, 0.0)) - a0) / a1


def _chamfer(gear, height: float) -> TipBreak | None:
    """Return the chamfer of radial height ``height``, or None where it leaves no tip land or no involute."""
    ra = float(gear.nominal_tip_radius)
    r1 = ra - height
    if r1 <= gear.form_radius:
        return None
    curve, _, _ = _flank(gear)
    s1 = _parameter_at(gear, r1)
    p1 = curve.point(s1)
    corner = curve.start
    leg = float(np.hypot(*(p1 - corner)))
    phi_corner = math.atan2(corner[1], corner[0])
    phi2 = phi_corner - 2.0 * math.asin(min(leg / (2.0 * ra), 1.0))  # equal legs: a chord of the tip circle
    if phi2 <= 0.0:
        return None
    p2 = (ra * math.cos(phi2), ra * math.sin(phi2))
    return TipBreak("chamfer", height, Line(p2, (float(p1[0]), float(p1[1]))), s1, phi2, r1)


def _rounding(gear, rho: float) -> TipBreak | None:
    """Return the rounding of radius ``rho``, or None where it leaves no tip land or no involute."""
    ra = float(gear.nominal_tip_radius)
    curve, s_tip, s_form = _flank(gear)
    s = np.linspace(s_tip, s_form, 257)

    def gap(v: np.ndarray | float) -> np.ndarray:
        p, t = curve.evaluate(v)
        q = p - rho * perp_cw(t)  # the centre, rho inside the flank along its normal
        return np.hypot(q[:, 0], q[:, 1]) - (ra - rho)

    root = bracket_root(lambda v: float(gap(v)[0]), s, values=gap(s), xtol=1e-14)
    if root is None:
        return None
    p, t = curve.evaluate(root)
    centre = p[0] - rho * perp_cw(t)[0]
    on_tip = centre * ra / np.hypot(*centre)
    phi2 = math.atan2(on_tip[1], on_tip[0])
    if phi2 <= 0.0:
        return None
    a_tip = math.atan2(on_tip[1] - centre[1], on_tip[0] - centre[0])
    a_flank = math.atan2(p[0, 1] - centre[1], p[0, 0] - centre[0])
    a_flank += 2 * math.pi * math.floor((a_tip - a_flank) / (2 * math.pi) + 1.0)  # counter-clockwise from the tip
    arc = Arc((float(centre[0]), float(centre[1])), float(rho), a_tip, a_flank)
    return TipBreak("rounding", rho, arc, float(root), phi2, float(np.hypot(*p[0])))


def tip_break(gear, kind: str, size: float) -> TipBreak:
    """Return the break of the upper tip corner of tooth 0.

    Parameters
    ----------
    gear : InvoluteGear
        The gear (its flank, tip and form circles).
    kind : {"chamfer", "rounding"}
        A chamfer of radial height ``size`` or a rounding of radius ``size``.
    size : float, mm
        Above 0 and below :func:`largest_break`.

    Returns
    -------
    TipBreak

    Raises
    ------
    DesignError
        ``tip_chamfer`` or ``tip_rounding``: a size that is not above 0, or one the tooth does not
        allow (naming the largest that it does).
    """
    param = f"tip_{kind}"
    if gear.tip_pointed:
        raise DesignError(param, "left out for a pointed tooth (it has no tip land to break)", size)
    if not (np.isfinite(size) and size > 0):
        raise DesignError(param, "a length above 0 mm", size)
    made = (_chamfer if kind == "chamfer" else _rounding)(gear, float(size))
    if made is None:
        most = largest_break(gear, kind)
        raise DesignError(
            param,
            f"below {most:.4g} mm for this tooth",
            size,
            "the breaks of a tooth's two flanks would meet on the tip, or run below the form circle",
        )
    return made


def largest_break(gear, kind: str) -> float:
    """Return the largest chamfer height or rounding radius the tooth allows, mm (bisected to 1e-9 relative).

    The break must leave some tip land and end on the usable involute (above the form radius).
    """
    make = _chamfer if kind == "chamfer" else _rounding
    lo, hi = 0.0, float(gear.nominal_tip_radius - gear.form_radius)
    if make(gear, hi) is not None:
        return hi
    for _ in range(60):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if make(gear, mid) is not None else (lo, mid)
        if hi - lo <= 1e-9 * hi:
            break
    return lo


def broken_tooth(gear, brk: TipBreak, tolerance: float) -> Profile:
    """Return one tooth (space centre to space centre, counter-clockwise) with both tip corners broken.

    Parameters
    ----------
    gear : InvoluteGear
        The gear.
    brk : TipBreak
        The upper corner's break (:func:`tip_break`); the lower corner gets its mirror image.
    tolerance : float, mm
        Chord tolerance of the samples.

    Returns
    -------
    Profile
        The open chain root arc, fillet, involute, break, tip arc, break, involute, fillet, root
        arc, each segment with its exact curve.
    """
    base = gear.tooth_profile(tolerance).segments
    names = [s.name for s in base]
    upper_inv = names.index("involute", names.index("tip arc"))
    flank = base[upper_inv]
    curve = flank.curve.trimmed(brk.flank_parameter, flank.curve.s1)
    involute = Segment.sample("involute", curve, tolerance)
    corner = Segment.sample(BREAK_NAMES[brk.kind], brk.curve, tolerance)
    tip = Segment.sample("tip arc", Arc((0.0, 0.0), float(gear.nominal_tip_radius), -brk.tip_angle, brk.tip_angle), tolerance)
    lower = [s.mirrored(0.0) for s in (involute, corner)]  # the lower involute (travelled upwards), then its break
    return Profile((*base[: upper_inv - 2], *lower, tip, corner, involute, *base[upper_inv + 1 :]), closed=False)


def broken_outline(gear, brk: TipBreak, tolerance: float) -> Profile:
    """Return the whole gear with every tip corner broken, closed and counter-clockwise (:func:`broken_tooth` patterned)."""
    return broken_tooth(gear, brk, tolerance).patterned(gear.teeth)


__all__ = ["BREAK_NAMES", "TipBreak", "broken_outline", "broken_tooth", "largest_break", "tip_break"]

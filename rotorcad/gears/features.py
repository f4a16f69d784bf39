"""A gear as a part: tip chamfer or rounding, bore, keyway (DIN 6885-1), hub, herringbone.

:class:`GearFeatures` holds what a design asks for (the ``[gear]`` keys of CONTRACT.md);
:func:`made_features` checks it against the gear and returns :class:`MadeFeatures`: the broken
tip corner (:mod:`rotorcad.gears.tip_corner`), the DIN 6885-1 key of the bore
(:mod:`rotorcad.gears.keys`), the closed forms of the bore's and hub's areas and of the solid's
volume, and :class:`SolidFeatures`, the plain numbers the solids' makers take (the meshes:
:mod:`rotorcad.gears.part_mesh`; the exact STEP: :mod:`exports.gear_step`).

Frames: the gear about the origin, tooth 0 centred on +x, the face from z = 0 to the face width b;
the keyway centred on +x (under tooth 0), the hub from z = -hub_length to 0. A herringbone gear's
halves are helical of opposite hands, the second the mirror image of the first in the mid plane
z = b/2 (its section at b/2 + t is that at b/2 - t).

Limits: the rim under the keyway (or the bore) must be at least half the tooth height,
s_R >= 0.5 h_t, below which ISO 6336-3 (rim thickness factor Y_B, sec. 8) gives no tooth-root
strength and calls the rim to be avoided; the hub lies between the bore's keyway and the root circle.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import cached_property

import numpy as np

from rotorcad.errors import DesignError
from rotorcad.gears.keys import DIN_6885_1, ParallelKey, key_for_bore
from rotorcad.gears.tip_corner import TipBreak, broken_outline, tip_break
from rotorcad.geometry import rotate
from rotorcad.profile import Profile

RIM_SHARE = 0.5
"""Least rim thickness under the bore or keyway as a share of the tooth height h_t (ISO 6336-3, Y_B)."""
FEATURE_FIELDS = ("tip_chamfer", "tip_rounding", "bore_diameter", "keyway", "hub_diameter", "hub_length", "herringbone")
"""The fields of :class:`GearFeatures`, also the ``[gear]`` keys that give them."""
MAX_HUB_LENGTH = 1e4
"""Longest hub, mm (the face width's bound)."""


@dataclass(frozen=True)
class GearFeatures:
    """What a design asks of the gear as a part (every field optional).

    Attributes
    ----------
    tip_chamfer : float or None, mm
        Radial height h_K of a chamfer of every tip corner.
    tip_rounding : float or None, mm
        Radius r_K of a rounding of every tip corner (not with a chamfer).
    bore_diameter : float or None, mm
        The bore d.
    keyway : bool
        A hub keyway of the DIN 6885-1 key of the bore.
    hub_diameter, hub_length : float or None, mm
        A hub on the face z = 0 (both or neither).
    herringbone : bool
        Two helical halves of opposite hands (a helical gear only).
    """

    tip_chamfer: float | None = None
    tip_rounding: float | None = None
    bore_diameter: float | None = None
    keyway: bool = False
    hub_diameter: float | None = None
    hub_length: float | None = None
    herringbone: bool = False

    @property
    def any(self) -> bool:
        """True when any feature is asked for."""
        return self != GearFeatures()


@dataclass(frozen=True)
class SolidFeatures:
    """The numbers the solids' makers take (picklable, for the STEP writer's process).

    Attributes
    ----------
    bore_radius : float, mm
        0: no bore.
    key_width : float, mm
        The keyway's width b (0: no keyway).
    key_bottom : float, mm
        Distance of the keyway's bottom from the axis, d/2 + t2.
    hub_radius, hub_length : float, mm
        0: no hub.
    herringbone : bool
        Two mirrored helical halves.
    turn : float, rad
        The turn of the body in mesh (the keyway turns with it).
    """

    bore_radius: float = 0.0
    key_width: float = 0.0
    key_bottom: float = 0.0
    hub_radius: float = 0.0
    hub_length: float = 0.0
    herringbone: bool = False
    turn: float = 0.0

    @property
    def keyway_corner_x(self) -> float:
        """Return the x where the keyway's sides meet the bore circle, sqrt(R^2 - b^2/4), mm."""
        return math.sqrt(self.bore_radius**2 - 0.25 * self.key_width**2)

    @property
    def hole_area(self) -> float:
        """Area of the bore with its keyway, mm².

        pi R^2 + b B - A_in, with B = d/2 + t2 the keyway's reach and A_in the part of the keyway's
        rectangle inside the circle, (b/2) sqrt(R^2 - b^2/4) + R^2 asin(b / 2R).
        """
        r, b = self.bore_radius, self.key_width
        if r <= 0:
            return 0.0
        inside = 0.5 * b * math.sqrt(r * r - 0.25 * b * b) + r * r * math.asin(0.5 * b / r) if b > 0 else 0.0
        return math.pi * r * r + b * self.key_bottom - inside

    def hole_points(self, tolerance: float) -> np.ndarray:
        """Return the bore and keyway as a closed counter-clockwise ring (n, 2), mm, turned into mesh.

        The bore's arc is sampled to the chord ``tolerance`` (mm); the keyway is three straight lines.
        """
        r, b = self.bore_radius, self.key_width
        start = math.asin(0.5 * b / r) if b > 0 else 0.0
        sweep = 2 * math.pi - 2 * start
        n = max(16, math.ceil(sweep / (2 * math.acos(max(1 - tolerance / r, -1.0)))))
        a = np.linspace(start, start + sweep, n + 1)
        ring = np.column_stack([r * np.cos(a), r * np.sin(a)])
        if b > 0:
            ring = np.vstack([ring, [[self.key_bottom, -0.5 * b], [self.key_bottom, 0.5 * b]]])
        else:
            ring = ring[:-1]
        return rotate(ring, self.turn)

    def volume(self, section_area: float, face_width: float) -> float:
        """Return the solid's volume, mm³: (section - hole) x face width + (hub disc - hole) x hub length.

        A helical (or herringbone) solid's volume is its transverse section's area times the face
        width, as a straight prism's (Cavalieri: every transverse slice is the section turned).
        """
        hub = (math.pi * self.hub_radius**2 - self.hole_area) * self.hub_length if self.hub_radius > 0 else 0.0
        return (section_area - self.hole_area) * face_width + hub


def largest_bore(gear, keyway: bool) -> float:
    """Return the largest bore diameter whose rim (under the keyway) is at least :data:`RIM_SHARE` h_t, mm."""
    limit = gear.root_radius - RIM_SHARE * (gear.tip_radius - gear.root_radius)
    if not keyway:
        return max(2.0 * limit, 0.0)
    best = 0.0
    for row in DIN_6885_1:  # d/2 + t2 <= limit within the row's bores
        d = min(row.bore_to, 2.0 * (limit - row.hub_depth))
        if d > row.bore_over:
            best = max(best, d)
    return best


@dataclass(frozen=True, eq=False)
class MadeFeatures:
    """The features checked against their gear (:func:`made_features`).

    Attributes
    ----------
    gear : InvoluteGear
        The gear.
    asked : GearFeatures
        What the design asked.
    tip : TipBreak or None
        The break of the tip corners.
    key : ParallelKey or None
        The DIN 6885-1 key of the bore.
    """

    gear: object
    asked: GearFeatures
    tip: TipBreak | None
    key: ParallelKey | None

    def outline(self, tolerance: float | None = None) -> Profile:
        """Return the gear's outline with its tip corners broken (the plain outline without a break)."""
        tol = self.gear.tolerance if tolerance is None else tolerance
        return self.gear.outline(tol) if self.tip is None else broken_outline(self.gear, self.tip, tol)

    @cached_property
    def solid(self) -> SolidFeatures:
        """The numbers of :class:`SolidFeatures` (not turned)."""
        a, key = self.asked, self.key
        return SolidFeatures(
            bore_radius=0.5 * (a.bore_diameter or 0.0),
            key_width=key.width if key else 0.0,
            key_bottom=0.5 * a.bore_diameter + key.hub_depth if key else 0.0,
            hub_radius=0.5 * (a.hub_diameter or 0.0),
            hub_length=a.hub_length or 0.0,
            herringbone=a.herringbone,
        )

    @property
    def rim_thickness(self) -> float | None:
        """The rim s_R between the root circle and the keyway's bottom (or the bore), mm; None without a bore."""
        if not self.asked.bore_diameter:
            return None
        inner = self.solid.key_bottom if self.key else 0.5 * self.asked.bore_diameter
        return float(self.gear.root_radius - inner)

    def summary(self) -> dict[str, object]:
        """Return the CONTRACT.md keys of the features (under ``features`` of ``rotorcad gear --json``)."""
        a = self.asked
        out: dict[str, object] = {
            "tip_chamfer": a.tip_chamfer,
            "tip_rounding": a.tip_rounding,
            "tip_land_half_angle_deg": None if self.tip is None else math.degrees(self.tip.tip_angle),
            "tip_break_radius": None if self.tip is None else self.tip.flank_radius,
            "bore_diameter": a.bore_diameter,
            "rim_thickness": self.rim_thickness,
            "hub_diameter": a.hub_diameter,
            "hub_length": a.hub_length,
            "herringbone": a.herringbone,
        }
        k = self.key
        for name in ("width", "height", "shaft_depth", "hub_depth"):  # DIN 6885-1: b, h, t1, t2
            out[f"keyway_{name}"] = None if k is None else getattr(k, name)
        return out


def made_features(gear, asked: GearFeatures) -> MadeFeatures:
    """Check a design's features against the gear and make them.

    Parameters
    ----------
    gear : InvoluteGear
        The gear (as made: after its tooth-thickness allowance).
    asked : GearFeatures
        What the design asks.

    Returns
    -------
    MadeFeatures

    Raises
    ------
    DesignError
        Naming the field: ``tip_chamfer``/``tip_rounding`` (not above 0, both given, larger than the
        tooth allows), ``bore_diameter`` (not above 0, or a rim under half the tooth height),
        ``keyway`` (without a bore, or a bore DIN 6885-1 has no key for), ``hub_diameter`` /
        ``hub_length`` (one without the other; the hub not between the keyway and the root circle;
        a length not from 0 to 10 000 mm), ``herringbone`` (a spur gear).
    """
    tip = None
    if asked.tip_chamfer is not None and asked.tip_rounding is not None:
        raise DesignError("tip_rounding", "left out when a tip chamfer is given (one break per corner)", asked.tip_rounding)
    for kind, size in (("chamfer", asked.tip_chamfer), ("rounding", asked.tip_rounding)):
        if size is not None:
            tip = tip_break(gear, kind, size)
    key = _bore_key(gear, asked)
    made = MadeFeatures(gear, asked, tip, key)
    _check_hub(gear, asked, made.solid)
    if asked.herringbone and abs(gear.helix_angle) < 1e-12:
        raise DesignError("herringbone", "false for a spur gear (a herringbone gear has a helix angle)", "true")
    return made


def _bore_key(gear, asked: GearFeatures) -> ParallelKey | None:
    d = asked.bore_diameter
    if d is None:
        if asked.keyway:
            raise DesignError("keyway", "false without a bore (give the bore diameter too)", "true")
        return None
    if not (np.isfinite(d) and d > 0):
        raise DesignError("bore_diameter", "a diameter above 0 mm", d)
    key = key_for_bore(d) if asked.keyway else None
    inner = 0.5 * d + (key.hub_depth if key else 0.0)
    rim = gear.root_radius - inner
    h_t = gear.tip_radius - gear.root_radius
    if rim < RIM_SHARE * h_t:
        most = largest_bore(gear, asked.keyway)
        what = "the keyway's bottom" if key else "the bore"
        raise DesignError(
            "bore_diameter",
            f"at most {most:.4g} mm for this gear" if most > 0 else "left out for this gear (no bore leaves a rim)",
            d,
            f"the rim between the root circle and {what} would be {rim:.4g} mm, "
            f"less than half the tooth height {RIM_SHARE * h_t:.4g} mm (ISO 6336-3)",
        )
    return key


def _check_hub(gear, asked: GearFeatures, solid: SolidFeatures) -> None:
    dh, lh = asked.hub_diameter, asked.hub_length
    if dh is None and lh is None:
        return
    if dh is None or lh is None:
        missing = "hub_diameter" if dh is None else "hub_length"
        raise DesignError(missing, "given too: a hub needs both its diameter and its length")
    inner = max(solid.key_bottom, solid.bore_radius)
    lo, hi = 2.0 * inner, 2.0 * gear.root_radius
    if not (np.isfinite(dh) and lo < dh <= hi):
        below = f"above {lo:.4g} mm (the bore and keyway)" if lo > 0 else "above 0 mm"
        raise DesignError("hub_diameter", f"{below} and at most the root diameter {hi:.4g} mm", dh)
    if not (np.isfinite(lh) and 0 < lh <= MAX_HUB_LENGTH):
        raise DesignError("hub_length", f"a length above 0 and at most {MAX_HUB_LENGTH:g} mm", lh)


__all__ = ["FEATURE_FIELDS", "RIM_SHARE", "GearFeatures", "MadeFeatures", "SolidFeatures", "largest_bore", "made_features"]

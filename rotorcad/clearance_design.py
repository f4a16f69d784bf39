"""Designed meshing clearance: a pair's female thinned by a clearance distribution.

The corrected rotors measure that clearance back (Wu & Chi, *Meshing clearance evaluation*,
eqs. 7 and 10: the clearance is the distance along the normal of the datum normal rack).

A clearance delta_n given in the normal section at a rack point of transverse flank angle alpha
(angle of the rack flank to the normal of the pitch line) is, in the transverse section, the
offset delta_t = delta_n sqrt(cos^2(alpha) / cos^2(beta) + sin^2(alpha)) of the female along its
transverse normal, beta the helix angle at the pitch cylinder: the normal rack is the transverse
rack with lengths along the pitch line times cos(beta), so its unit normal (cos alpha / cos beta,
sin alpha) / norm is the transverse one (cos alpha, sin alpha) stretched, and a transverse offset
delta_t moves the normal rack by delta_t / norm along its own normal.

The distribution is uniform, per flank (the driving flank where the rack rises, the sealing flank
where it falls, and the lands where the rack is flatter than 30 degrees to the pitch line, each
with its own value; where two values meet, the smaller rises smoothly to the larger over
``blend`` mm of the female outline, so that no point gets less than its flank's clearance), or a
table of clearance over the datum rack's x (one rack period, interpolated periodically).

The offset is the erosion of the female by delta_t (:mod:`rotorcad.outline_offset`): each analytic
piece moves along its own normal and sharp corners are re-cut where the moved pieces cross, so the
thinned female lies inside the designed one by at least the clearance, corners included.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from rotorcad.envelope import conjugate, rack_frame
from rotorcad.errors import DesignError
from rotorcad.geometry import rotate
from rotorcad.outline_offset import offset_inward
from rotorcad.profile import Segment
from rotorcad.screw_rotors import ScrewRotors

BLEND = 1.0  # mm along the female outline: a per-flank clearance step becomes a smooth rise this long
BLEND_CELLS = 2_000_000  # (step, sample) pairs weighed at once by blended(): some 16 MB an array
LAND_SLOPE = 0.5  # |sin| of the rack tangent's angle to the pitch line below which a point is a land's image


@dataclass(frozen=True)
class ClearanceDistribution:
    """Normal clearance to design, per flank or as a table over the rack.

    Parameters
    ----------
    driving, sealing, lands : float, mm
        Clearance (0 to 1 mm) on the driving flank (rack rising), the sealing flank (rack falling)
        and the lands (rack flatter than 30 degrees to the pitch line).
    table : tuple of (float, float), optional
        Rows (x, clearance), mm: x along the pitch line of the transverse rack in the rack frame of
        CONTRACT.md, over one rack period (interpolated periodically). When given, it replaces the
        per-flank values.
    blend : float, mm
        Length along the female outline over which a smaller per-flank clearance rises to a
        neighbouring larger one (0 to 10 mm; 0: a step).

    Raises
    ------
    DesignError
        A clearance outside [0, 1] mm, a blend outside [0, 10] mm, or a table with fewer than two
        finite rows.
    """

    driving: float = 0.0
    sealing: float = 0.0
    lands: float = 0.0
    table: tuple[tuple[float, float], ...] | None = None
    blend: float = BLEND

    def __post_init__(self) -> None:
        if not (np.isfinite(self.blend) and 0.0 <= self.blend <= 10.0):
            raise DesignError("clearance blend", "a blend length from 0 to 10 mm", self.blend)
        for name in ("driving", "sealing", "lands"):
            v = getattr(self, name)
            if not (np.isfinite(v) and 0.0 <= v <= 1.0):
                raise DesignError(f"clearance {name}", "a clearance from 0 to 1 mm", v)
        if self.table is not None:
            rows = np.asarray(self.table, dtype=float)
            if rows.ndim != 2 or rows.shape[1] != 2 or len(rows) < 2 or not np.all(np.isfinite(rows)):
                raise DesignError("clearance table", "at least two finite rows x,clearance", None)
            if np.any(rows[:, 1] < 0) or np.any(rows[:, 1] > 1.0):
                raise DesignError("clearance table", "clearances from 0 to 1 mm", None)

    @staticmethod
    def uniform(value: float) -> ClearanceDistribution:
        """Make a distribution with the same clearance everywhere.

        Parameters
        ----------
        value : float, mm
            The clearance on both flanks and the lands.

        Returns
        -------
        ClearanceDistribution
        """
        return ClearanceDistribution(value, value, value)

    @staticmethod
    def parse(text: str) -> ClearanceDistribution:
        """Read a distribution from its command-line text.

        Parameters
        ----------
        text : str
            ``0.05`` (uniform) or ``driving=0.03,sealing=0.05,lands=0.04`` (a missing flank 0, missing
            lands the smaller of the two flank values), mm; either may add ``blend=`` (mm, default
            :data:`BLEND`).

        Returns
        -------
        ClearanceDistribution

        Raises
        ------
        DesignError
            Text that is neither form, or a value out of range.
        """
        text = text.strip()
        try:
            if "=" not in text:
                return ClearanceDistribution.uniform(float(text))
            values = {}
            for part in text.split(","):
                key, _, value = part.partition("=")
                key = key.strip()
                if key not in ("driving", "sealing", "lands", "blend"):
                    raise DesignError("clearance", "a value or driving=, sealing=, lands= (and blend=) values in mm", text)
                values[key] = float(value)
            if set(values) == {"blend"}:
                raise DesignError("clearance", "a value or driving=, sealing=, lands= (and blend=) values in mm", text)
            if "lands" not in values:  # the lands take the smaller flank value: no point of the female left at 0
                values["lands"] = min(values.get("driving", 0.0), values.get("sealing", 0.0))
            return ClearanceDistribution(**values)
        except DesignError:
            raise
        except ValueError:
            raise DesignError("clearance", "a value or driving=, sealing=, lands= (and blend=) values in mm", text) from None

    def at(self, x: np.ndarray, tangents: np.ndarray, period: float) -> np.ndarray:
        """Return the normal clearance at datum rack points.

        Parameters
        ----------
        x : (n,) float array, mm
            Positions along the pitch line, rack frame of CONTRACT.md.
        tangents : (n, 2) float array
            Unit tangents of the rack there, travelled in +x (their y part is the rise).
        period : float, mm
            Rack period p, for the table's periodic interpolation.

        Returns
        -------
        (n,) float array, mm
            The designed normal clearance delta_n.
        """
        if self.table is not None:
            rows = np.asarray(self.table, dtype=float)
            order = np.argsort(rows[:, 0])
            return np.interp(np.mod(x, period), rows[order, 0], rows[order, 1], period=period)
        rising = tangents[:, 1]
        return np.where(np.abs(rising) < LAND_SLOPE, self.lands, np.where(rising > 0, self.driving, self.sealing))


def corrected_female(rotors: ScrewRotors, clearance: ClearanceDistribution, tolerance: float = 1e-3) -> np.ndarray:
    """Thin the female outline by the designed normal clearance (module docstring).

    Each sample of each analytic piece of the female outline gets its rack point (inverse
    generation by the envelope engine), hence its flank, its transverse flank angle alpha and its x
    on the datum rack, and moves into the female by delta_t along its piece's exact normal. Where
    per-flank clearances differ they are blended (:func:`blended`) along the outline; at sharp
    corners the moved pieces are joined as the erosion of the female by delta_t joins them
    (:func:`rotorcad.outline_offset.offset_inward`): the thinned female lies inside the designed
    one by at least the clearance everywhere, corners included. Points without a rack point keep
    the clearance 0.

    Parameters
    ----------
    rotors : ScrewRotors
        The pair as designed (without clearance).
    clearance : ClearanceDistribution
        The normal clearance to give.
    tolerance : float, mm
        Chord tolerance of the female outline.

    Returns
    -------
    (n, 2) float array, mm
        The thinned female outline, own frame at the mesh position, closed counter-clockwise.
    """
    pair, blend = rotors.pair, clearance.blend
    lobe = [s for s in rotors.female_lobe(tolerance).segments if len(s.points) > 1]
    pts, tan, delta_n, factor, rise = _lobe_clearance(rotors, clearance, lobe, blend)
    if rise.max() > 0:  # the rises of the blends bend the outline: finer chords there
        bend = 6.0 * float(rise.max()) * float(factor.max()) / blend**2  # curvature of the quintic rise, 1/mm
        owner = np.repeat(np.arange(len(lobe)), [len(s.points) for s in lobe])
        spacing = np.sqrt(8.0 * tolerance / bend)
        lobe = [_refined(s, spacing) if np.any(rise[owner == k] > 0) else s for k, s in enumerate(lobe)]
        pts, tan, delta_n, factor, _ = _lobe_clearance(rotors, clearance, lobe, blend)
    delta_t = delta_n * factor
    sizes = np.cumsum([len(s.points) for s in lobe])[:-1]
    turns = 2 * np.pi * np.arange(pair.female_teeth) / pair.female_teeth
    points = [rotate(p, t) for t in turns for p in np.split(pts, sizes)]
    tangents = [rotate(v, t) for t in turns for v in np.split(tan, sizes)]
    moved = np.split(np.tile(delta_t, len(turns)), np.cumsum([len(p) for p in points])[:-1])
    return offset_inward(points, tangents, moved, tolerance)


def _refined(segment: Segment, spacing: float) -> Segment:
    """Return a piece re-evaluated on its exact curve with samples at most ``spacing`` (mm) apart."""
    chord = np.hypot(*np.diff(segment.points, axis=0).T)
    parts = np.maximum(1, np.ceil(chord / spacing).astype(int))
    start = np.repeat(segment.s[:-1], parts)
    step = np.repeat(np.diff(segment.s) / parts, parts)
    k = np.arange(parts.sum()) - np.repeat(np.cumsum(parts) - parts, parts)
    return Segment.at(segment.name, segment.curve, np.append(start + k * step, segment.s[-1]))


def _lobe_clearance(
    rotors: ScrewRotors, clearance: ClearanceDistribution, lobe: list[Segment], blend: float
) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """Return one female lobe's samples and their designed clearance, per-flank steps blended over ``blend`` mm.

    The lobe repeats around the female, so the outline's arc length is taken around one lobe's
    length (its end is the next lobe's start).

    Returns
    -------
    points, tangents : (n, 2) float arrays
        The lobe's samples (mm) and exact unit tangents, pieces end to end.
    delta_n : (n,) float array, mm
        The normal clearance there (0 where a point has no rack point).
    factor : (n,) float array
        delta_t / delta_n (module docstring; 1 where a point has no rack point).
    rise : (n,) float array, mm
        What the blends add to the designed clearance (>= 0).
    """
    pts = np.vstack([s.points for s in lobe])
    tan = np.vstack([s.tangents for s in lobe])
    designed, factor = _normal_clearance(rotors, clearance, pts, tan)
    delta_n = designed
    if clearance.table is None:
        chord = np.hypot(*np.diff(pts, axis=0).T)
        delta_n = blended(designed, np.concatenate([[0.0], np.cumsum(chord)]), float(chord.sum()), blend)
    return pts, tan, delta_n, factor, delta_n - designed


def _normal_clearance(
    rotors: ScrewRotors, clearance: ClearanceDistribution, pts: np.ndarray, tan: np.ndarray
) -> tuple[np.ndarray, np.ndarray]:
    """Return the designed normal clearance at female points and its transverse factor (module docstring).

    Parameters
    ----------
    rotors : ScrewRotors
        The pair as designed.
    clearance : ClearanceDistribution
        The normal clearance to give.
    pts, tan : (n, 2) float arrays
        Female points (own frame, mm) and their exact unit tangents.

    Returns
    -------
    delta_n : (n,) float array, mm
        The normal clearance (0 where a point has no rack point).
    factor : (n,) float array
        delta_t / delta_n = sqrt(cos^2(alpha) / cos^2(beta) + sin^2(alpha)) (1 where no rack point).
    """
    pair = rotors.pair
    mesh = pair.mesh
    shift = np.array([pair.center_distance, 0.0])
    contact = conjugate(pts + shift, tan, mesh.female, mesh.rack, limits=(-pair.male_dedendum - 1e-6, pair.male_addendum + 1e-6))
    rack_pts = rack_frame(contact.points, pair.male_pitch_radius)
    rack_tan = np.stack([contact.tangents[:, 1], contact.tangents[:, 0]], axis=1)  # (y, x) of the fixed frame
    flip = np.where(rack_tan[:, 0] < 0, -1.0, 1.0)[:, None]  # travelled in +x
    rack_tan = rack_tan * flip
    beta = np.arctan(2 * np.pi * pair.male_pitch_radius / pair.lead)
    sin_a = np.abs(rack_tan[:, 0])  # the flank's angle to the normal of the pitch line: sin = |t_x|
    cos_a = np.abs(rack_tan[:, 1])
    delta_n = clearance.at(rack_pts[:, 0], rack_tan, pair.rack_period)
    factor = np.sqrt(cos_a**2 / np.cos(beta) ** 2 + sin_a**2)
    found = np.isfinite(delta_n) & np.isfinite(factor)  # no rack point: left as it is
    return np.where(found, delta_n, 0.0), np.where(found, factor, 1.0)


def blended(delta: np.ndarray, s: np.ndarray, perimeter: float, length: float) -> np.ndarray:
    """Blend the steps of a piecewise-constant clearance smoothly, on the side of the smaller one.

    At a step between delta_lo and delta_hi at arc length s_k, a point on the smaller side at a
    distance d along the outline gets delta_lo + (delta_hi - delta_lo) w(d / length), with the
    quintic fall w(u) = 1 - (10 u^3 - 15 u^4 + 6 u^5) for u < 1, else 0 (w(0) = 1 and w' = w'' = 0 at
    both ends: the outline's tangent and curvature stay continuous). Of several steps within reach
    the largest rise counts. No point gets less than its designed clearance, so the blend only
    removes material; the larger clearance keeps its value up to the step.

    Parameters
    ----------
    delta : (n,) float array, mm
        Clearance at the outline's points, in travel order (a closed outline).
    s : (n,) float array, mm
        Arc length of the points along the outline.
    perimeter : float, mm
        The closed outline's length (distances are taken around it).
    length : float, mm
        Length of the blend (> 0); 0 leaves the steps as they are.

    Returns
    -------
    (n,) float array, mm
        The blended clearance, >= ``delta`` everywhere.
    """
    if length <= 0:
        return delta
    nxt = np.roll(np.arange(len(delta)), -1)
    steps = np.flatnonzero(np.abs(delta[nxt] - delta) > 1e-12)
    if steps.size == 0:
        return delta
    ds = np.mod(s[nxt[steps]] - s[steps], perimeter)
    # the step sits between two samples (or at a corner's two samples), taken back onto [0, perimeter)
    where = np.mod(s[steps] + 0.5 * ds, perimeter)
    high = np.maximum(delta[steps], delta[nxt[steps]])
    rise = np.zeros_like(delta)
    chunk = max(1, BLEND_CELLS // len(delta))  # steps at a time: a few (chunk, n) arrays, not (steps, n)
    for k in range(0, len(steps), chunk):
        d = np.mod(s[None, :] - where[k : k + chunk, None], perimeter)
        # distance around the closed outline, in [0, perimeter / 2] whatever the rounding of s and perimeter
        u = np.clip(np.minimum(d, perimeter - d) / length, 0.0, 1.0)
        w = 1.0 - u**3 * (10.0 - 15.0 * u + 6.0 * u**2)
        rise = np.maximum(rise, (np.clip(high[k : k + chunk, None] - delta[None, :], 0.0, None) * w).max(axis=0))
    return delta + rise


def thinned_female_fault(
    rotors: ScrewRotors, thinned: np.ndarray, clearance: ClearanceDistribution, tolerance: float
) -> str | None:
    """Say what is wrong with a thinned female outline before it is written, or None.

    An outline check independent of how the female was thinned: every point lies inside the design
    female (at the same chord tolerance) by no more than the largest transverse clearance
    delta_n / cos(beta) (module docstring: the factor is at most 1 / cos(beta)), so within the
    annulus from the root radius less that clearance to the tip radius; and no two consecutive
    points lie farther apart than the design female's own longest chord (5 % and the tolerance
    over it: a concave piece's chords grow by (R + delta) / R).

    Parameters
    ----------
    rotors : ScrewRotors
        The pair as designed.
    thinned : (n, 2) float array, mm
        The thinned female outline, own frame, closed without a repeated end point.
    clearance : ClearanceDistribution
        The normal clearance designed into it.
    tolerance : float, mm
        The chord tolerance it was made to.

    Returns
    -------
    str or None
        What is wrong, in words and mm; None when the outline passes.
    """
    import shapely

    pair = rotors.pair
    beta = np.arctan(2 * np.pi * pair.male_pitch_radius / pair.lead)
    values = [clearance.driving, clearance.sealing, clearance.lands]
    if clearance.table is not None:
        values = list(np.asarray(clearance.table, dtype=float)[:, 1])
    reach = max(values) / np.cos(beta) + tolerance  # mm: the most a point may lie inside the design
    if len(thinned) < 3 or not np.all(np.isfinite(thinned)):
        return "the thinned female has fewer than three finite points"
    design = rotors.female_outline(tolerance).points
    r = np.hypot(*thinned.T)
    low, high = pair.female_root_radius - reach, pair.female_tip_radius + tolerance
    if r.min() < low or r.max() > high:
        return f"the thinned female reaches r = {r.min():.4f}-{r.max():.4f} mm, off the annulus {low:.4f}-{high:.4f} mm"
    body = shapely.Polygon(design)
    depth = shapely.distance(shapely.points(thinned), body.exterior)
    outside = ~shapely.contains_xy(body.buffer(tolerance), thinned[:, 0], thinned[:, 1])
    if outside.any() or depth.max() > reach:
        return f"the thinned female lies up to {depth.max():.4f} mm from the design female (at most {reach:.4f} mm inside it)"
    chord = np.hypot(*(np.roll(thinned, -1, axis=0) - thinned).T).max()
    own = np.hypot(*(np.roll(design, -1, axis=0) - design).T).max()
    if chord > 1.05 * own + tolerance:
        return f"the thinned female has a chord of {chord:.4f} mm, the design female's longest is {own:.4f} mm"
    return None


__all__ = ["BLEND", "ClearanceDistribution", "blended", "corrected_female", "thinned_female_fault"]

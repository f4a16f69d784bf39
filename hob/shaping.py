"""Shaping simulation of an internal gear: the shaper cutter's teeth subtracted from the ring blank by polygon booleans.

Independent of the envelope engine: the cutter's tooth (:class:`rotorcad.gears.shaper.ShaperCutter`,
its involute, tip rounding and tip circle sampled as a polygon) is placed at many positions of the
generating motion (the ring turning by t about its centre, the cutter by (z2/z0) t about (a0, 0))
and the union of the placed teeth is cut from a sector of the blank around tooth space 0. The
simulated space is then compared with the analytic envelope
(:meth:`rotorcad.gears.internal_gear.InternalGear.space_profile`), both ways.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import shapely

from hob.cutting import MAX_UNION_VERTICES
from rotorcad.errors import DesignError
from rotorcad.gears.internal_gear import InternalGear
from rotorcad.profile import Segment


@dataclass(frozen=True)
class ShapingResult:
    """Result of :func:`simulate_shaping`.

    Parameters
    ----------
    ring : shapely.Polygon
        The simulated blank sector around tooth space 0 (three pitches), mm.
    max_deviation : float, mm
        Largest distance between the simulated boundary and the envelope over space 0 (root,
        fillets, involutes; off the bore circle), both ways.
    flank_deviation : float, mm
        The same over the involutes alone (from the tip circle to the form circle).
    positions : int
        Cutter positions.
    """

    ring: shapely.Polygon
    max_deviation: float
    flank_deviation: float
    positions: int


def cutter_teeth(ring: InternalGear, tolerance: float) -> np.ndarray:
    """Return three cutter teeth (-1, 0, 1) about the cutter's centre at the origin, tooth 0 on +x, as a polygon.

    The upper half of tooth 0 (tip circle, tip rounding, involute down to the base circle,
    :meth:`~rotorcad.gears.shaper.ShaperCutter.curves`) sampled to ``tolerance`` and mirrored; the
    teeth stand on a core circle that stays inside the ring's bore in every position
    (a0 + r_core < r_a2).

    Returns
    -------
    (n, 2) float array, mm
        The closed outline, counter-clockwise, no repeated end point.
    """
    c = ring.cutter
    half = [Segment.sample(name, curve, tolerance).points for name, curve in c.curves(0.0).items()]
    upper = np.vstack(half)  # from the tooth's centre line on the tip down to the base circle
    lower = upper[::-1] * np.array([1.0, -1.0])
    tooth = np.vstack([lower[:-1], upper[1:]])  # counter-clockwise: lower flank up, tip, upper flank down
    core = min(c.base_radius, ring.tip_radius - ring.cutting_center_distance) - 0.05 * ring.module
    pitch = 2.0 * math.pi / c.teeth
    poly = shapely.Point(0.0, 0.0).buffer(core, quad_segs=64)
    for k in (-1, 0, 1):
        ang = k * pitch
        rot = np.array([[math.cos(ang), -math.sin(ang)], [math.sin(ang), math.cos(ang)]])
        body = np.vstack([tooth @ rot.T, [[0.0, 0.0]]])
        poly = poly.union(shapely.Polygon(body).buffer(0))
    return np.asarray(shapely.geometry.polygon.orient(poly, 1.0).exterior.coords)[:-1]


def shaping_plan(ring: InternalGear, scallop: float, positions: int | None = None) -> tuple[int, float]:
    """Return the cutter positions and the ring's turn either side of the line of centres.

    The turn reaches past the point where the tip circles cross (the cutter's tip leaves the
    spaces there), cos(theta2) = (a0^2 + r_a2^2 - r_a0^2) / (2 a0 r_a2), plus a pitch. The step
    keeps the scallop d^2 / (8 rho) within ``scallop``: d = (z2/z0 - 1) L dt, the relative turn
    about the pitch point times L = sqrt(r_a0^2 - r_b0^2) + m (the reach of the cutter's contact
    points from it), rho the tip rounding (at least m / 20).

    Returns
    -------
    (int, float)
        Positions and the turn T (rad): t from -T to T.
    """
    c, a0 = ring.cutter, ring.cutting_center_distance
    ra0, ra2 = c.tip_radius, ring.tip_radius
    cos2 = (a0 * a0 + ra2 * ra2 - ra0 * ra0) / (2.0 * a0 * ra2)
    theta2 = math.acos(min(max(cos2, -1.0), 1.0))
    turn = min(theta2 + 2.0 * math.pi / ring.teeth, math.pi)
    if positions is None:
        reach = math.sqrt(ra0 * ra0 - c.base_radius**2) + ring.module
        rho = max(c.tip_rounding, 0.05 * ring.module)
        step = math.sqrt(8.0 * rho * scallop) / ((ring.teeth / c.teeth - 1.0) * reach)
        positions = math.ceil(2.0 * turn / step) + 1
    return positions, turn


def coarsest_scallop(ring: InternalGear, scallop: float) -> float:
    """Return a scallop height (mm, from ``scallop`` up by factors of 1.25, two digits up) whose simulation fits one union.

    Its positions (:func:`shaping_plan`) times the vertices of the cutter's teeth sampled to a quarter
    of it stay within :data:`hob.cutting.MAX_UNION_VERTICES`.
    """
    # positions and the cutter's vertices each grow like 1 / sqrt(scallop): their product like 1 / scallop
    work = shaping_plan(ring, scallop)[0] * len(cutter_teeth(ring, scallop / 4.0))
    t = scallop * max(1.0, 0.9 * work / MAX_UNION_VERTICES)
    for _ in range(200):
        if shaping_plan(ring, t)[0] * len(cutter_teeth(ring, t / 4.0)) <= MAX_UNION_VERTICES:
            break
        t *= 1.25
    digits = 1 - math.floor(math.log10(t))
    return math.ceil(t * 10**digits) / 10**digits  # two significant digits, rounded up


def simulate_shaping(ring: InternalGear, scallop: float = 1e-3, positions: int | None = None) -> ShapingResult:
    """Shape tooth space 0 of an internal gear by polygon booleans and compare it with the envelope.

    Parameters
    ----------
    ring : InternalGear
        The internal gear and its cutter.
    scallop : float, mm
        Scallop height between positions (:func:`shaping_plan`); the cutter is sampled to a quarter of it.
    positions : int, optional
        Cutter positions (default from ``scallop``).

    Returns
    -------
    ShapingResult

    Raises
    ------
    DesignError
        A union beyond :data:`hob.cutting.MAX_UNION_VERTICES` vertices (``positions`` or ``tolerance``).
    """
    teeth = cutter_teeth(ring, scallop / 4.0)
    n, turn = shaping_plan(ring, scallop, positions)
    if n * len(teeth) > MAX_UNION_VERTICES:
        most = MAX_UNION_VERTICES // len(teeth)
        if positions is not None:
            raise DesignError("positions", f"at most {most} for this gear (each cutter position has {len(teeth)} vertices)", n)
        raise DesignError(
            "tolerance",
            f"at least {coarsest_scallop(ring, scallop):.2g} mm for this gear",
            scallop,
            f"{n} cutter positions of {len(teeth)} vertices, more than one union of {MAX_UNION_VERTICES} vertices",
        )
    z2, z0, a0 = ring.teeth, ring.cutter.teeth, ring.cutting_center_distance
    t = np.linspace(-turn, turn, n)
    zc = teeth[:, 0] + 1j * teeth[:, 1]
    placed = (np.exp(1j * (z2 / z0) * t)[:, None] * zc[None, :] + a0) * np.exp(-1j * t)[:, None]
    swept = shapely.union_all(shapely.polygons(np.stack([placed.real, placed.imag], axis=-1)))
    pitch = 2.0 * math.pi / z2
    wedge = np.linspace(-1.5 * pitch, 1.5 * pitch, 721)
    outer = ring.root_radius + ring.module
    blank = shapely.Polygon(np.vstack([np.column_stack([outer * np.cos(wedge), outer * np.sin(wedge)]), [[0.0, 0.0]]]))
    blank = blank.difference(shapely.Point(0.0, 0.0).buffer(ring.tip_radius, quad_segs=2048))
    shaped = blank.difference(swept)
    shaped = max(getattr(shaped, "geoms", [shaped]), key=lambda g: g.area)
    return ShapingResult(shaped, *_deviations(ring, shaped, scallop), n)


def _deviations(ring: InternalGear, shaped: shapely.Polygon, scallop: float) -> tuple[float, float]:
    """Return the largest distances between the simulated boundary and the envelope over space 0, both ways, mm.

    Over the whole space (off the bore circle) and over the involutes alone.
    """
    pts = ring.space_profile(scallop / 10.0).points  # polar angle 0 to 2 pi / z2
    pts = np.vstack([(pts * np.array([1.0, -1.0]))[::-1], pts])  # and its mirror: -2 pi / z2 to 2 pi / z2
    line = shapely.LineString(pts)
    sim = shapely.get_coordinates(shaped.exterior)
    bore_off = ring.tip_radius + 1e-3 * ring.module
    half = math.pi / ring.teeth

    def both_ways(r_lo: float, r_hi: float) -> float:
        r, a = np.hypot(*pts.T), np.abs(np.arctan2(pts[:, 1], pts[:, 0]))
        env = pts[(r > r_lo) & (r < r_hi) & (a < half)]
        sr, sa = np.hypot(*sim.T), np.abs(np.arctan2(sim[:, 1], sim[:, 0]))
        near = sim[(sr > r_lo) & (sr < r_hi) & (sa < half)]
        d1 = shapely.distance(shapely.points(env), shaped.exterior).max() if len(env) else 0.0
        d2 = shapely.distance(shapely.points(near), line).max() if len(near) else 0.0
        return float(max(d1, d2))

    whole = both_ways(bore_off, ring.root_radius + 1e-6 * ring.module)
    flank = both_ways(bore_off, ring.form_radius)
    return whole, flank

"""Generating-cutting simulation: the rack tool rolls on the blank's pitch circle and cuts the gear.

The blank minus the union of the tool positions (shapely) is the cut gear, undercut and all.
This is the numerical envelope; it must agree with the analytic one of
:class:`rotorcad.gears.involute_gear.InvoluteGear` (two independent methods
for one envelope). The number of positions follows from the requested
scallop height h: consecutive straight flank positions turn by dt in the blank's frame and leave
cusps of height rho (1/cos(dt/2) - 1) ~ rho dt^2 / 8 above an involute of radius of curvature
rho, so dt = sqrt(8 h / rho_max) with rho_max = sqrt(r_a^2 - r_b^2) at the tip. The root fillet
(trochoid) converges only like 1/N (measured); its deviation is reported, not hidden.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
import shapely

from rotorcad.curves import Curve, PointPath
from rotorcad.errors import DesignError
from rotorcad.gears.formulas import inv
from rotorcad.gears.involute_gear import InvoluteGear
from rotorcad.geometry import rotate
from rotorcad.kinematics import Rotation, Translation
from rotorcad.profile import Segment


@dataclass(frozen=True)
class CutResult:
    """The simulated tooth (polygon, gear frame), its analytic counterpart and how far apart.

    Parameters
    ----------
    tooth : shapely.Polygon
        The simulated tooth 0 in its sector (from space centre to space centre), mm.
    envelope : shapely.Polygon
        The analytic tooth 0 in the same sector, mm.
    positions : int
        Tool positions of the last pass.
    step : float, rad
        Blank rotation between tool positions.
    max_deviation : float, mm
        Largest distance of the analytic boundary from the simulated one inside the tooth sector.
    flank_deviation : float, mm
        The same restricted to the involute.
    """

    tooth: shapely.Polygon
    envelope: shapely.Polygon
    positions: int
    step: float  # rad of blank rotation between tool positions
    max_deviation: float  # mm, simulated boundary vs analytic boundary inside the tooth sector
    flank_deviation: float  # mm, the same restricted to the involute


def _tool_tooth_polygon(gear: InvoluteGear, tolerance: float) -> np.ndarray:
    """Return one tool tooth as a closed polygon (m, 2), mm, in the fixed frame at t = 0.

    Tip line, tip arcs and flanks, closed high above the blank, centred on the line y = p/2 (the
    space of tooth 0's upper neighbour).
    """
    half: list[np.ndarray] = []
    for name in ("tip line", "tip arc", "flank"):
        curve: Curve | None = gear.tool.get(name)
        if curve is not None:
            half.append(Segment.sample(name, curve, tolerance).points)
    upper = np.vstack(half)  # from the tooth centre line y = p_t/2 down the lower side of the tool tooth
    pt = np.pi * gear.transverse_module
    centre = pt / 2.0
    mirrored = upper[::-1] * np.array([1.0, -1.0]) + np.array([0.0, 2 * centre])
    top = gear.nominal_tip_radius + 2.0 * gear.module
    pts = np.vstack([upper, [[top, upper[-1, 1]], [top, mirrored[0, 1]]], mirrored])
    return _drop_repeats(pts, 1e-9 * gear.module)


def _drop_repeats(pts: np.ndarray, eps: float) -> np.ndarray:
    """Drop the points of the ring ``pts`` within ``eps`` of their predecessor (and a last point on the first).

    The pieces of the tool tooth (tip line, tip arc, flank) share their end points; turned to a tool
    position, such a pair a rounding error apart is a spike that makes the position an invalid
    polygon, and GEOS then unites the positions wrongly (found by the fuzz suite: z = 3 lost up to all of the tooth,
    z = 4 and 7 some positions too).
    """
    keep = np.r_[True, np.hypot(*np.diff(pts, axis=0).T) > eps]
    pts = pts[keep]
    if len(pts) > 1 and np.hypot(*(pts[-1] - pts[0])) <= eps:
        pts = pts[:-1]
    return pts


def _cut_blank(
    blank: shapely.Polygon, tooth: np.ndarray, ts: np.ndarray, pt: float, r: float, eps: float
) -> shapely.Polygon | None:
    """Subtract the union of the tool teeth j = -1, 0 at the rolling angles ``ts`` from the blank.

    A position that is still not a valid polygon is repaired first, and a failing union is redone on
    a grid of ``eps`` (snap rounding, robust, well below the scallop). Returns the largest polygon,
    or None when the polygon booleans fail.
    """
    polys = shapely.polygons([rotate(tooth + np.array([0.0, pt * j + r * t]), -t) for t in ts for j in (-1, 0)])
    bad = ~shapely.is_valid(polys)
    if bad.any():
        polys[bad] = shapely.make_valid(polys[bad])
    for grid in (0.0, eps, 1e3 * eps):
        try:
            simulated = blank.difference(shapely.unary_union(polys, grid_size=grid or None), grid_size=grid or None)
        except shapely.errors.GEOSException:
            continue
        if isinstance(simulated, shapely.MultiPolygon | shapely.GeometryCollection):
            parts = [g for g in getattr(simulated, "geoms", []) if isinstance(g, shapely.Polygon)]
            simulated = max(parts, key=lambda g: g.area) if parts else None
        if isinstance(simulated, shapely.Polygon) and not simulated.is_empty:
            return simulated
    return None


MAX_UNION_VERTICES = 3_000_000
"""Most tool-polygon vertices in one union (positions x vertices of a tool tooth x 2 teeth): some
3 s and a few hundred MB. The refinement stops there and reports the deviation it reached."""


def cutting_work(gear: InvoluteGear, scallop: float = 1e-3, positions: int | None = None) -> tuple[int, int]:
    """Estimate the work of a first cutting pass before it starts.

    Parameters
    ----------
    gear : InvoluteGear
        The gear to be cut by its basic-rack tool.
    scallop : float, mm
        Requested scallop height.
    positions : int, optional
        A fixed number of tool positions instead of the one the scallop asks for.

    Returns
    -------
    tuple of int
        The tool positions of the first pass and the vertices of one tool tooth; their product
        times 2 (two tool teeth) is what :data:`MAX_UNION_VERTICES` bounds.
    """
    if positions is None:
        rho_max = np.sqrt(max(gear.nominal_tip_radius**2 - gear.base_radius**2, 1e-12))
        step = min(np.sqrt(8.0 * scallop / rho_max), _fillet_step(gear, scallop))
        pt = np.pi * gear.transverse_module
        reach = (np.sqrt(gear.nominal_tip_radius**2 - gear.root_radius**2) + pt) / gear.pitch_radius
        positions = int(np.ceil(2.0 * reach / step)) + 1
    return int(positions), len(_tool_tooth_polygon(gear, min(scallop / 4.0, 1e-3)))


def simulate_cutting(
    gear: InvoluteGear,
    scallop: float = 1e-3,
    positions: int | None = None,
    tool: object | None = None,
    progress: Callable[[int, float], None] | None = None,
) -> CutResult:
    """Cut a gear by simulation and measure it against the analytic envelope (module docstring).

    Passes are refined (deviation ~ step^2) until the deviation meets ``scallop`` or the union would
    exceed :data:`MAX_UNION_VERTICES` vertices; the deviation reached is reported either way.

    Parameters
    ----------
    gear : InvoluteGear
        The gear (its basic-rack tool, unless ``tool`` is given).
    scallop : float, mm
        Requested scallop height.
    positions : int, optional
        A fixed number of tool positions (one pass, no refinement).
    tool : TrapezoidalHob or RackTool, optional
        A tool that replaces the basic-rack tool (one pass); the deviation is then still measured
        against the basic-rack envelope of ``gear``, so it shows what the tool changes (protuberance
        relief, chamfer).
    progress : callable, optional
        Called as ``progress(positions, deviation)`` after each pass (deviation in mm).

    Returns
    -------
    CutResult

    Raises
    ------
    DesignError
        When the polygon booleans fail, or the refined simulated tooth differs from the analytic one
        by more than 5 % of its area.
    """
    pt = np.pi * gear.transverse_module
    r = gear.pitch_radius
    rho_max = np.sqrt(max(gear.nominal_tip_radius**2 - gear.base_radius**2, 1e-12))
    step = min(np.sqrt(8.0 * scallop / rho_max), _fillet_step(gear, scallop))
    if tool is None:
        tooth = _tool_tooth_polygon(gear, min(scallop / 4.0, 1e-3))
    else:
        stretch = np.array([1.0, 1.0 / np.cos(gear.helix_angle)])
        tooth = tool.tooth(r, gear.shift, gear.nominal_tip_radius + 2.0 * gear.module) * stretch
        tooth = _drop_repeats(tooth, 1e-9 * gear.module)
    # rolling keeps each tool tooth near a fixed polar angle (j + 1/2) 2 pi / z of the blank: teeth
    # j = -1 and 0 cut the two flanks of tooth 0, over the time the tool needs to cross the blank
    reach = (np.sqrt(gear.nominal_tip_radius**2 - gear.root_radius**2) + pt) / r
    sector = _sector(gear, 1.0)
    blank = shapely.Point(0, 0).buffer(gear.nominal_tip_radius, quad_segs=2048).intersection(sector)
    exact = _exact_tooth(gear, min(scallop / 4.0, 1e-4)).intersection(sector)
    if positions is not None:
        step = 2.0 * reach / max(int(positions) - 1, 1)
    for _ in range(1 if positions is not None else 8):  # deviation ~ step^2: refine to the scallop
        ts = np.arange(-reach, reach + step, step)
        simulated = _cut_blank(blank, tooth, ts, pt, r, gear.module * 1e-9)
        if simulated is None:
            raise DesignError("teeth", "a number the cutting simulation can handle", gear.teeth, "the polygon booleans fail")
        dev, flank_dev = _deviation(gear, simulated, exact, scallop)
        if progress is not None:
            progress(len(ts), dev)
        if dev <= scallop or tool is not None:
            break
        finer = step * 0.95 * np.sqrt(scallop / dev)
        if 2 * (2.0 * reach / finer) * len(tooth) > MAX_UNION_VERTICES:
            break  # the root fillet converges like 1/N: report the deviation reached within the budget
        step = finer
    if positions is None and tool is None and abs(simulated.area - exact.area) > 0.05 * exact.area:
        raise DesignError(  # refined to the scallop and still far off: a wrong tooth is refused, never reported
            "teeth",
            "a number the cutting simulation can handle",
            gear.teeth,
            "the simulated tooth differs from the analytic one by more than 5 % of its area",
        )
    return CutResult(simulated, exact, len(ts), float(step), dev, flank_dev)


def _exact_tooth(gear: InvoluteGear, tolerance: float) -> shapely.Polygon:
    """Return the analytic tooth 0 closed at the centre: its profile from space centre to space centre.

    Not the whole gear: a thousand teeth at a fine tolerance were a million points.
    """
    chain = gear.tooth_profile(tolerance).points
    return shapely.Polygon(np.vstack([[0.0, 0.0], chain]))


def _fillet_step(gear: InvoluteGear, scallop: float) -> float:
    """Blank rotation between tool positions that keeps the root-fillet scallop below ``scallop``.

    Consecutive positions of the tool tip arc (radius rho) lie d = |KC| dt apart along the path of
    its centre K (speed |KC| about the instantaneous centre C); the cusp between two circles of
    radius rho on a path of radius of curvature R is about d^2 / (8 (rho + R)). R comes from the
    path's exact tangents (turning angle over arc length).
    """
    arc = gear.tool["tip arc"]
    inner = arc.curve if hasattr(arc, "curve") else arc
    rho = float(getattr(inner, "radius", 0.0))
    fillet = gear._generated["tip arc"]
    s = np.linspace(fillet.s0, fillet.s1, 257)
    t = fillet.contact(s).t
    t = np.linspace(np.nanmin(t), np.nanmax(t), 257)
    centre = np.asarray(inner.center)
    mesh_c = np.array([gear.pitch_radius, 0.0])
    k_fixed = centre[None, :] + np.multiply.outer(t, [0.0, gear.pitch_radius])
    speed = np.hypot(*(k_fixed - mesh_c).T)
    path = rotate(k_fixed, -t)  # the centre's path in the blank frame
    _, tangents = PointPath(tuple(centre), Translation((0.0, gear.pitch_radius)), Rotation(), float(t[0]), float(t[-1])).evaluate(
        t
    )
    psi = np.unwrap(np.arctan2(tangents[:, 1], tangents[:, 0]))
    ds = np.hypot(*np.diff(path, axis=0).T)
    with np.errstate(divide="ignore", invalid="ignore"):
        radius_of_curvature = np.where(np.abs(np.diff(psi)) > 1e-15, ds / np.abs(np.diff(psi)), np.inf)
    need = np.sqrt(8.0 * scallop * (rho + radius_of_curvature)) / np.maximum(speed[:-1], 1e-12)
    return float(np.min(need))


def _sector(gear: InvoluteGear, half_pitches: float) -> shapely.Polygon:
    """Return the wedge of tooth 0 (from space centre to space centre), slightly enlarged radially."""
    a = half_pitches * np.pi / gear.teeth
    big = 2.0 * gear.nominal_tip_radius
    th = np.linspace(-a, a, 64)
    return shapely.Polygon(np.vstack([[0.0, 0.0], big * np.stack([np.cos(th), np.sin(th)], axis=1)]))


def _deviation(gear: InvoluteGear, simulated: shapely.Polygon, exact: shapely.Polygon, scallop: float) -> tuple[float, float]:
    """Return the largest distance from the analytic tooth boundary to the simulated one, mm.

    Also on the involute alone; both away from the sector's straight cut edges.
    """
    inner = _sector(gear, 0.98)
    boundary = np.asarray(exact.exterior.coords)
    pts = boundary[shapely.contains_xy(inner, boundary[:, 0], boundary[:, 1])]
    ring = simulated.exterior
    d = shapely.distance(ring, shapely.points(pts))
    r = np.hypot(*pts.T)
    on_flank = (r > gear.form_radius + 0.02 * gear.module) & (r < gear.tip_radius - 0.02 * gear.module)
    return float(d.max()), float(d[on_flank].max()) if on_flank.any() else 0.0


def simulated_form_radius(gear: InvoluteGear, result: CutResult, tolerance: float) -> float:
    """Return the radius where the simulated flank leaves the involute.

    The undercut point P' when undercut (Kollek & Osiński's active base radius r'_z), else the start
    of the usable involute: the lowest boundary point of the simulated tooth that lies on the
    involute of r_b within ``tolerance`` (closed-form involute polar angle).

    Parameters
    ----------
    gear : InvoluteGear
        The gear that was cut.
    result : CutResult
        The simulation.
    tolerance : float, mm
        Distance from the involute that still counts as on it.

    Returns
    -------
    float, mm
        The radius; NaN when no boundary point lies on the involute.
    """
    pts = np.asarray(result.tooth.exterior.coords)
    r = np.hypot(*pts.T)
    rb = gear.base_radius
    ok = r > rb
    a = np.arccos(np.clip(rb / r[ok], -1.0, 1.0))
    ang = np.abs(np.arctan2(pts[ok, 1], pts[ok, 0]))
    # the flank's polar angle + inv(alpha) is the constant of its involute: take it halfway up the
    # analytic involute (the pitch circle can lie on the fillet: z = 3, x = 0)
    theta = ang + inv(a)
    r_ref = 0.5 * (gear.form_radius + gear.tip_radius)
    a_ref = np.arccos(rb / r_ref)
    ref = gear.half_angle(r_ref) + inv(a_ref)
    gap = (theta - ref) * r[ok]  # > 0 outside the involute (scallops), < 0 inside it (undercut)
    on = np.abs(gap) <= tolerance
    inner = r[ok] < gear.tip_radius - tolerance
    # the flank from the tip down to the first point cut inside the involute: a deep fillet (z = 3)
    # crosses the involute's extension a second time, lower down, and that point is not P'
    cut_in = r[ok][inner & (gap < -tolerance)]
    below = float(cut_in.max()) if len(cut_in) else -np.inf
    flank = on & inner & (r[ok] > below)
    return float(r[ok][flank].min()) if np.any(flank) else float("nan")

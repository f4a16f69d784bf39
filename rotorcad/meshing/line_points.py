"""A flank's generating line fitted to the given points themselves, not to the smoothing spline through them.

:mod:`rotorcad.meshing.generating_line` finds the straight line of the male, the female or the rack whose
envelope is the flank beside a tip corner from the contacts of the fitted profile. Through scattered points
that profile is a smoothing spline (n sigma² from the estimated scatter, :mod:`rotorcad.measured.fit`), and a
smoothing spline cuts a curvature step or a corner over a few point spacings: its contacts bow off the line at
the window's ends by a few scatters, the same way on every read, and the line's distance d moves by tens of um.
Measured over the samples whose flank is a line's envelope (narrow-tip, asymmetric SRM, SRM-B, rack-involute;
both rotors, 80/150/300 points a lobe, 1-2 um along the normals, seeds 0-3, ``python
benchmarks/bench_line_apex.py``): the males' blow-holes read -2.9..+1.2 %, the females' -8.4..+4.3 %, 155 of 216
reads resolved within 1 %. Here the line is fitted again, by least squares, to the given points whose part of the
profile the window's contacts cover (every lobe turned onto one, as :mod:`rotorcad.meshing.rounding_apex` fits its
circles): each point's signed distance from the line's envelope on the given rotor (the law of gearing, Rinder
sec. 2.1: at male rotation t the contact is the foot of the perpendicular from the pitch point C on the line,
mapped into the given rotor's frame). The points at either end must lie on the line to their scatter
(:func:`rotorcad.meshing.rounding_apex.holds` over the :data:`rotorcad.meshing.rounding_apex.END_POINTS` at that
end, the outermost within :data:`END_SCATTERS` scatters); else the outermost of the worse end is left out and the
line fitted again. The standard errors of the fit (sigma² (J^T J)^-1) then state the blow-hole's uncertainty
(:func:`rotorcad.meshing.blow_hole_accuracy.line_uncertainty`). Where the points left cover fewer than
:data:`MIN_SPACINGS` point spacings along the profile the model cannot be told from its ends and the contacts'
line stands, with its own bound. The same reads now: males -0.75..+0.72 % (all 96 within 1 %), 175 of 216 resolved
within 1 %, the design within the stated uncertainty in every read.

A line of the given rotor itself (the females' own straight flank, 2.9-3.5 mm: 3-4 places a lobe at 80 points a
lobe, the same on every lobe of an even scan) is fitted with the curve beside it as one model instead
(:func:`own_line`): the line, and beyond a junction searched along it the curve the mate's tip corner generates,
leaving it tangentially. The females of the narrow-tip, asymmetric SRM and SRM-B (80/150/300 points a lobe, exact
and 1-2 um along the normals, seeds 0-3, 81 reads): 45 -> 80 within 1 % (-9.09..+4.37 % -> -1.03..+0.75 %), the
stated uncertainty 27-135 % -> 2.2-5.7 % of the area at 80 a lobe with scatter, the design within it in every read.
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np
import shapely

from rotorcad.geometry import rotate
from rotorcad.meshing.rounding_apex import END_POINTS, holds
from rotorcad.roles import Body
from rotorcad.rotor_pair import RotorPair

END_SCATTERS = 3.0
"""Scatters (the given points' estimated sigma) beyond which a point at a window's end is no point of the line: a
normal error exceeds it once in 370."""

ENVELOPE_SAMPLES = 1500
"""Samples of the line's envelope over the window's rotations (and a fifth of their range beyond each end)."""

MIN_SPACINGS = 6.0
"""Fewest point spacings along the profile the points a line is fitted to must cover: the ends' tests read
:data:`rotorcad.meshing.rounding_apex.END_POINTS` (6) points each, and on fewer places along the profile (the
lobes of an even scan repeat them) a curvature step beside the line passes them (the narrow-tip female at 80
points a lobe with 2 um, seed 3: four places, +6.4 % for an uncertainty of 5.7 %; the asymmetric SRM's female with
1 um, seeds 0-2: +7.2..+14.5 %; those, the given rotor's own lines, are now :func:`own_line`'s)."""

FEWEST = 4
"""Fewest given points on which the line is fitted again (two parameters; fewer leave it as the contacts gave it)."""

TRIM_BLOCK = 64
"""While fewer than twice this many points are kept, a line's ends are trimmed a point at a time; beyond, a
1/TRIM_BLOCK share at a time (a dense outline's window holds hundreds: the rack-involute male's 1 um-chord CSV
at 600 a lobe, 665 points, took 12 minutes one at a time; the scans of 80-300 points a lobe trim fewer)."""


STEP_REACH = 1.0
"""How far past the window's far end :func:`own_line` takes the curve beyond a line, in the window's lengths."""

STEP_SPACINGS = 5.0
"""And at least this many point spacings (three places of the curve beyond the junction, and two to spare). Farther,
a cubic no longer follows the samples' curves (0.65-1.1 um off over 6 mm): with 1.5 windows and 6 spacings the
asymmetric SRM female at 80 a lobe with 1 um (isotropic, seeds 0-5) read a mean of -0.37 % (rms 0.66 %), with these
-0.10 % (0.47 %)."""

STEP_BAND = 0.25
"""Slope of the band about the line within which :func:`own_line` takes points, from ``reach`` at the corner: the
curve beyond leaves the line by c u² (c = 0.02 /mm on the samples, 0.35 mm at 4 mm), the tip arc across the
corner by 6 times its distance along the line."""

STEP_GRID = 200
"""Junctions :func:`own_line` tries between the first place but one and the last but two."""


class PointLine(NamedTuple):
    """The generating line fitted to the given points (:func:`refit_line`)."""

    distance: float
    """d, mm: the line's distance from its body's centre (of the rack's line, from the rack frame's origin)."""
    normal: np.ndarray
    """(2,) float: the line's unit normal in its body's frame."""
    count: int
    """How many given points it was fitted to (every lobe turned onto one)."""
    rms: float
    """mm: their rms distance from its envelope."""
    errors: np.ndarray
    """(2,) float: the standard errors of the normal's direction (rad) and of d (mm, at the foot of the perpendicular
    from the body's centre), sigma² (J^T J)^-1 of the fit with sigma the larger of the estimated scatter and ``rms``."""


def given_of(rotors: object) -> tuple[np.ndarray, float, Body, float] | None:
    """Return a given profile's points, their scatter (mm), its rotor (:class:`rotorcad.roles.Body`) and spacing (mm), or None.

    None for a design, a drawing or exact points (:attr:`rotorcad.screw_rotors.ScrewRotors.given_points`,
    ``point_scatter`` 0): the fitted profile's contacts stand.
    """
    points, sigma = getattr(rotors, "given_points", None), float(getattr(rotors, "point_scatter", 0.0) or 0.0)
    if points is None or sigma <= 0.0:
        return None
    rotor = Body.FEMALE if str(getattr(rotors, "family", "")).startswith("female") else Body.MALE
    return points, sigma, rotor, float(getattr(rotors, "point_spacing", None) or 0.0)


def _on_body(points: np.ndarray, t: np.ndarray, body: Body, pair: RotorPair) -> np.ndarray:
    """Fixed-frame points in a body's frame at male rotation t (as :func:`rotorcad.meshing.generating_line.body_frames`)."""
    if body is Body.MALE:
        return rotate(points, -t)
    if body is Body.FEMALE:
        return rotate(points - np.array([pair.center_distance, 0.0]), t * pair.male_teeth / pair.female_teeth)
    return points - np.column_stack([np.zeros_like(t), pair.male_pitch_radius * t])


def _envelope(angle: float, distance: float, frame: Body, given: Body, t: np.ndarray, pair: RotorPair) -> np.ndarray:
    """Return the envelope of a line {x . n = d} of body ``frame`` on the given rotor, (m, 2) float, mm, its frame."""
    n = np.array([np.cos(angle), np.sin(angle)])
    c = np.array([pair.male_pitch_radius, 0.0])
    if frame is Body.MALE:
        u, p0 = rotate(np.tile(n, (len(t), 1)), t), rotate(np.tile(distance * n, (len(t), 1)), t)
    elif frame is Body.FEMALE:
        turn = -t * pair.male_teeth / pair.female_teeth
        u = rotate(np.tile(n, (len(t), 1)), turn)
        p0 = rotate(np.tile(distance * n, (len(t), 1)), turn) + np.array([pair.center_distance, 0.0])
    else:
        u = np.tile(n, (len(t), 1))
        p0 = distance * n + np.column_stack([np.zeros_like(t), pair.male_pitch_radius * t])
    return _on_body(c - ((c - p0) * u).sum(axis=1)[:, None] * u, t, given, pair)


def _signed_gaps(points: np.ndarray, curve: np.ndarray) -> np.ndarray:
    """Return the signed distances (mm) of points from a densely sampled curve (left of its direction positive)."""
    from scipy.spatial import cKDTree

    k = np.clip(cKDTree(curve).query(points)[1], 0, len(curve) - 2)  # the nearest sample (an (n, m) matrix was O(nm))
    a, b = curve[k], curve[k + 1]
    tangent = (b - a) / np.maximum(np.hypot(*(b - a).T), 1e-15)[:, None]
    v = points - a
    return tangent[:, 0] * v[:, 1] - tangent[:, 1] * v[:, 0]


def refit_line(
    frame: str | Body,
    normal: np.ndarray,
    distance: float,
    contacts: np.ndarray,
    t: np.ndarray,
    given: tuple[np.ndarray, float, str, float],
    reach: float,
    pair: RotorPair,
    corner: Body | None = None,
) -> PointLine | None:
    """Return a body's generating line fitted to the given points its window's contacts cover, or None.

    Parameters
    ----------
    frame : str or Body
        ``"male"``, ``"female"`` or ``"rack"`` (:class:`rotorcad.roles.Body`): the body whose line it is.
    normal : (2,) float array
        The line's unit normal in that body's frame, as the contacts gave it (the start).
    distance : float, mm
        Its distance from the body's centre along ``normal`` (the rack's: from the rack frame's origin).
    contacts : (n, 2) float array, mm
        The window's contacts (fixed frame), in the meshline's order from the corner.
    t : (n,) float array, rad
        The male's rotation at each.
    given : ((m, 2) float array, float, Body, float)
        The given rotor's points (every lobe, its own frame, mm), their estimated scatter sigma (mm), which
        rotor they are (:class:`rotorcad.roles.Body`) and their spacing h (mm).
    reach : float, mm
        How far off the window's part of the fitted profile a given point may lie and still be taken (the
        profile's accuracy).
    pair : RotorPair
    corner : Body or None
        Whose tip corner's path the window starts at (None: the mate's): on the given rotor's own line
        (:func:`own_line`) the curve the mate's corner generates lies beyond that end, else beyond the far one.

    Returns
    -------
    PointLine or None
        None for exact points (sigma 0: their spline is the outline) or where fewer than :data:`FEWEST` points
        stay on the line.
    """
    from scipy.optimize import least_squares

    points, sigma, rotor, spacing = given
    frame = Body(frame)
    if sigma <= 0.0 or points is None or len(contacts) < 2:
        return None
    teeth = pair.male_teeth if rotor is Body.MALE else pair.female_teeth
    pitch = 2.0 * np.pi / teeth
    path = _on_body(contacts, t, rotor, pair)  # the window's part of the given rotor's fitted profile
    middle = np.arctan2(*path[len(path) // 2][::-1])
    k = np.round((np.arctan2(points[:, 1], points[:, 0]) - middle) / pitch)
    folded = rotate(points, -k * pitch)
    if frame is rotor:  # the given rotor's own straight flank: the line beside the curvature step (two pieces)
        return own_line(normal, distance, path, folded, sigma, spacing, reach, corner is not rotor)
    line = shapely.LineString(path)
    where = shapely.line_locate_point(line, shapely.points(folded))
    near = (shapely.distance(line, shapely.points(folded)) <= reach) & (where > 0.0) & (where < line.length)
    pts, where = folded[near], where[near]
    if len(pts) < FEWEST:
        return None
    order = np.argsort(where)
    pts, where = pts[order], where[order]
    span = float(np.ptp(t))
    grid = np.linspace(t.min() - 0.2 * span, t.max() + 0.2 * span, ENVELOPE_SAMPLES)
    angle0 = float(np.arctan2(normal[1], normal[0]))

    def gaps(x: np.ndarray, use: np.ndarray) -> np.ndarray:
        return _signed_gaps(use, _envelope(angle0 + x[0], distance + x[1], frame, rotor, grid, pair))

    keep = np.ones(len(pts), dtype=bool)
    x = np.zeros(2)
    while keep.sum() >= FEWEST:
        use = pts[keep]
        found = least_squares(lambda v, use=use: gaps(v, use), x, x_scale=np.array([1e-3, 1e-3]), diff_step=1e-7)
        x = found.x
        g = gaps(x, use)
        m = min(END_POINTS, len(g) // 2)
        index = np.arange(len(g))
        # each end: its outermost point within END_SCATTERS scatters, its END_POINTS on the line (holds: their mean
        # within three standard errors, the rms within the scatter's)
        off = [
            abs(g[k]) > END_SCATTERS * sigma or not holds(g, end, sigma, 2)
            for k, end in ((0, index < m), (-1, index >= len(g) - m))
        ]
        cover = float(np.ptp(where[keep])) / spacing + 1.0 if spacing > 0.0 else np.inf
        if not any(off) and cover < MIN_SPACINGS:
            return None
        if not any(off):
            rms = float(np.sqrt(np.mean(g**2)))
            info = found.jac.T @ found.jac
            if abs(np.linalg.det(info)) <= 0.0:
                return None
            errors = max(sigma, rms) * np.sqrt(np.abs(np.diag(np.linalg.inv(info))))
            n = np.array([np.cos(angle0 + x[0]), np.sin(angle0 + x[0])])
            return PointLine(distance + float(x[1]), n, int(keep.sum()), rms, errors)
        means = [abs(float(g[:m].mean())) if off[0] else -1.0, abs(float(g[-m:].mean())) if off[1] else -1.0]
        inside = np.flatnonzero(keep)
        block = max(1, len(inside) // TRIM_BLOCK)  # a point at a time up to TRIM_BLOCK points, a share beyond
        keep[inside[:block] if means[0] >= means[1] else inside[-block:]] = False
    return None


def _step_fit(x: np.ndarray, y: np.ndarray, x0: float) -> tuple[np.ndarray, np.ndarray, float]:
    """Fit y = a + b x + c (x - x0)_+² + e (x - x0)_+³ by least squares; return (a, b, c, e), the design matrix, the RSS."""
    u = np.maximum(x - x0, 0.0)
    a = np.column_stack([np.ones_like(x), x, u**2, u**3])
    coef = np.linalg.lstsq(a, y, rcond=None)[0]
    return coef, a, float(((y - a @ coef) ** 2).sum())


def _step_candidates(x: np.ndarray, spacing: float) -> np.ndarray:
    """Junctions x0 (mm) that leave the line two places and the curve three (:data:`STEP_GRID` of them)."""
    lo, hi = x.min() + spacing, x.max() - 2.0 * spacing
    return np.linspace(lo, hi, STEP_GRID) if hi > lo else np.empty(0)


def own_line(
    normal: np.ndarray,
    distance: float,
    path: np.ndarray,
    folded: np.ndarray,
    sigma: float,
    spacing: float,
    reach: float,
    step_at_start: bool = True,
) -> PointLine | None:
    """Return the given rotor's own straight flank fitted with the curve beyond its far end, or None.

    A female's own straight flank (the narrow-tip's, the asymmetric SRM's and the SRM-B's: 2.9-3.5 mm) holds 3-4
    places a lobe at 80 points a lobe, the same on every lobe of an even scan; beyond its far end the flank point
    generated by the male tip leaves it tangentially (a curvature step), and a line alone cannot be told from the
    first places of that curve (:data:`MIN_SPACINGS`). Here both pieces are fitted at once, in the line's frame
    (x along it from the foot of the perpendicular from the body's centre, y off it):

        y = a + b x + c (x - x0)_+² + e (x - x0)_+³,

    tangent continuous at the junction x0, which is searched over :data:`STEP_GRID` places (each a linear least
    squares; the least residual). The curve beyond is any smooth one: a cubic from the junction follows the
    samples' point-generated flanks within 0.11 um over 4 mm (narrow-tip, asymmetric SRM; the design's curves). The
    points taken run from the window's corner end to :data:`STEP_REACH` times its length (at least
    :data:`STEP_SPACINGS` point spacings) past its far end, within a band that opens from ``reach`` at the corner;
    at either end the outermost points must lie on the model as :func:`refit_line`'s ends (:data:`END_SCATTERS`,
    :func:`rotorcad.meshing.rounding_apex.holds`), else the outermost of the worse end is left out (the near end: a
    point of the tip arc, across the corner). The standard errors are those of the linear fit at the junction found,
    widened by the spread of (a, b) over the junctions whose residual lies within one sigma² of the least.

    Parameters
    ----------
    normal : (2,) float array
        The line's unit normal in the given rotor's frame (the contacts' line, the start).
    distance : float, mm
        Its distance from the rotor's centre along ``normal``.
    path : (n, 2) float array, mm
        The window's contacts in the given rotor's frame, from the corner.
    folded : (m, 2) float array, mm
        The given points, every lobe turned onto the window's.
    sigma, spacing, reach : float, mm
        The points' estimated scatter, their spacing, and the profile's accuracy.
    step_at_start : bool
        Whether the curve lies beyond the window's first contact (the window starts at the mate's tip corner's
        path: that corner generates it) or beyond its last (the window starts at the rotor's own tip corner).

    Returns
    -------
    PointLine or None
        None where fewer than two places lie on the line or three on the curve, or the ends never hold.
    """
    if spacing <= 0.0 or len(path) < 2:
        return None
    n = np.asarray(normal, dtype=float)
    tangent = np.array([-n[1], n[0]])
    if float((path[-1] - path[0]) @ tangent) < 0.0:
        tangent = -tangent
    if step_at_start:  # x runs from the sharp end to the curve's
        tangent, path = -tangent, path[::-1]
    x, y = folded @ tangent, folded @ n - distance
    first, last = float(path[0] @ tangent), float(path[-1] @ tangent)
    extra = max(STEP_REACH * (last - first), STEP_SPACINGS * spacing)
    band = reach + END_SCATTERS * sigma + STEP_BAND * np.maximum(x - last, 0.0)  # opens beyond the window's curve end
    take = (x >= first - extra) & (x <= last + extra) & (np.abs(y) <= band)
    order = np.argsort(x[take])
    x, y = x[take][order], y[take][order]
    keep = np.ones(len(x), dtype=bool)
    while keep.sum() >= FEWEST + 3:
        xs, ys = x[keep], y[keep]
        junctions = _step_candidates(xs, spacing)
        if not len(junctions):
            return None
        fits = [_step_fit(xs, ys, x0) for x0 in junctions]
        rss = np.array([f[2] for f in fits])
        best = int(np.argmin(rss))
        coef, design, _ = fits[best]
        g = ys - design @ coef
        m = min(END_POINTS, len(g) // 2)
        index = np.arange(len(g))
        off = [
            abs(g[k]) > END_SCATTERS * sigma or not holds(g, end, sigma, 5)
            for k, end in ((0, index < m), (-1, index >= len(g) - m))
        ]
        if not any(off):
            rms = float(np.sqrt(np.mean(g**2)))
            scale = max(sigma, rms)
            cov = scale**2 * np.linalg.pinv(design.T @ design)
            near = rss <= rss[best] + scale**2  # the junctions the points cannot tell from the best
            spread = np.array([f[0][:2] for f in fits])[near] - coef[:2]
            a_err = float(np.hypot(np.sqrt(abs(cov[0, 0])), np.abs(spread[:, 0]).max()))
            b_err = float(np.hypot(np.sqrt(abs(cov[1, 1])), np.abs(spread[:, 1]).max()))
            root = float(np.hypot(1.0, coef[1]))
            line_normal = (n - coef[1] * tangent) / root
            return PointLine((distance + float(coef[0])) / root, line_normal, int(keep.sum()), rms, np.array([b_err, a_err]))
        means = [abs(float(g[:m].mean())) if off[0] else -1.0, abs(float(g[-m:].mean())) if off[1] else -1.0]
        inside = np.flatnonzero(keep)
        block = max(1, len(inside) // TRIM_BLOCK)
        keep[inside[:block] if means[0] >= means[1] else inside[-block:]] = False
    return None


__all__ = ["END_SCATTERS", "ENVELOPE_SAMPLES", "FEWEST", "PointLine", "given_of", "own_line", "refit_line"]

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
:data:`MIN_SPACINGS` point spacings along the profile the model cannot be told from its ends (a female's straight
flank at 80 points a lobe holds 3-4 points a lobe, the same on every lobe of an even scan) and the contacts' line
stands, with its own bound. The same reads now: males -0.75..+0.72 % (all 96 within 1 %), 175 of 216 resolved
within 1 %, the design within the stated uncertainty in every read.
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
1 um, seeds 0-2: +7.2..+14.5 %)."""

FEWEST = 4
"""Fewest given points on which the line is fitted again (two parameters; fewer leave it as the contacts gave it)."""

TRIM_BLOCK = 64
"""While fewer than twice this many points are kept, a line's ends are trimmed a point at a time; beyond, a
1/TRIM_BLOCK share at a time (a dense outline's window holds hundreds: the rack-involute male's 1 um-chord CSV
at 600 a lobe, 665 points, took 12 minutes one at a time; the scans of 80-300 points a lobe trim fewer)."""


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


__all__ = ["END_SCATTERS", "ENVELOPE_SAMPLES", "FEWEST", "PointLine", "given_of", "refit_line"]

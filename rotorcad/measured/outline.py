"""Rotor outlines as users bring them: measured (CMM), drawn, or cut by a boolean simulation.

The first stage of the measured-outline pipeline (:mod:`rotorcad.measured`): reading the geometry
that was given. A drawing's curves stay curves when they are the outline's own, or are read as the
points they were drawn through; points of one lobe, one groove or tooth, or the whole outline, in
any order and from any start, become one clean whole outline (counter-clockwise, no repeated or
duplicated points), with the lobe count checked against the design, the scatter of the points
estimated, the accuracy they carry stated, and the sharp corners and lands found at a scale above
that scatter. The fit that follows (:mod:`rotorcad.measured.fit`) relies on it; nothing here calls
back into it.

Scatter. A smooth curve sampled at nearly even spacing h has third differences
p[i+2] - 3 p[i+1] + 3 p[i] - p[i-1] of order h^3 / rho^2; independent normal scatter of standard
deviation sigma adds a term of standard deviation sigma sqrt(20). The median of the third
differences' normal component (a robust estimate, untouched by the few corners) gives sigma; the
smoothing spline that follows allows a mean squared residual of sigma^2 (scipy's s = n sigma^2,
Dierckx, *Curve and Surface Fitting with Splines*, sec. 5.2).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from rotorcad.curves import Curve, Spline
from rotorcad.errors import DesignError
from rotorcad.geometry import cross, rotate, wrap_angle
from rotorcad.measured.drawing import (
    DRAWN_SPANS,
    SMOOTH_JOINT,
    as_given,
    carries_tangents,
    drawing_points,
    hermite_accuracy,
    own_frame,
    profile_points,
)
from rotorcad.measured.pattern import PATTERN_RMS, pattern_deviation, uneven_scatter
from rotorcad.measured.point_checks import file_lines, refuse_bad_points
from rotorcad.roles import Side
from rotorcad.rotor_pair import RotorPair

SCATTER_FLOOR = 1e-4  # mm: below this the points are taken as exact (interpolated)

UNEVEN_SPACING = 1.5
"""Ratio of the 90th to the 10th percentile of the points' spacing above which the spacing is
uneven (a polyline's vertices drawn to a chord tolerance: 2.4-11 on the samples' export polylines;
points resampled evenly along the outline, as a CMM's: 1.0), and :func:`scatter` asks local cubics
(:func:`rotorcad.measured.pattern.uneven_scatter`) whether the points are exact."""


def _drop_repeats(points: np.ndarray) -> np.ndarray:
    """Points without consecutive duplicates (within 1e-9 mm) and without a repeated end point."""
    pts = np.asarray(points, dtype=float)
    step = np.hypot(*np.diff(pts, axis=0).T)
    pts = pts[np.concatenate([[True], step > 1e-9])]
    while len(pts) > 1 and np.hypot(*(pts[0] - pts[-1])) <= 1e-9:
        pts = pts[:-1]
    return pts


def lobe_count(whole: np.ndarray) -> int:
    """Count the lobes of a closed outline about the origin.

    The lobes are the cycles of its radius between the lower and the upper third of its range (a
    hysteresis that noise cannot trip).

    Parameters
    ----------
    whole : (n, 2) float array, mm
        The closed outline (without a repeated end point).

    Returns
    -------
    int
        Number of lobes (0 for a circle).
    """
    r = np.hypot(*whole.T)
    lo, hi = r.min() + (r.max() - r.min()) / 3, r.max() - (r.max() - r.min()) / 3
    state = np.where(r >= hi, 1, np.where(r <= lo, -1, 0))
    state = state[state != 0]
    if len(state) == 0:
        return 0
    changes = np.count_nonzero(np.diff(np.concatenate([state, state[:1]])) > 0)  # low -> high, around the ring
    return int(changes)


def whole_outline(points: np.ndarray, teeth: int, label: str) -> np.ndarray:
    """Make the whole outline from the points of one lobe, one groove or tooth, or of the whole outline.

    The result runs counter-clockwise about the rotor's centre (the origin), without repeated or
    duplicated points; the points may come in either direction and from any start, and one lobe is
    patterned ``teeth`` times. One groove (tip to tip) or one tooth (root to root), which holds
    both flanks but spans less than the lobe pitch, is patterned too, the unmeasured tip or root
    land between the copies filled along its arc (:func:`_patterned_groove`); so is one lobe that
    stops a little short of the pitch (up to 2 % of it) on its land, whose copies were joined by a
    chord across the land before (1.3 deg of the rack-involute male's root land: 3.9 µm inside it).

    Parameters
    ----------
    points : (n, 2) float array, mm
        One lobe or the whole outline in the rotor's own frame.
    teeth : int
        Lobe count of the rotor.
    label : str
        How the points are named in errors.

    Returns
    -------
    (m, 2) float array, mm
        The whole outline, counter-clockwise.

    Raises
    ------
    DesignError
        Naming ``label``: fewer than 4 distinct points, points that wind around the centre but
        have another number of lobes than ``teeth``, or points of one lobe that span another angle
        than the lobe pitch.
    """
    pts = _drop_repeats(points)
    if len(pts) < 4:
        raise DesignError(label, "at least 4 distinct points", None, f"{len(pts)} found")
    ang = np.unwrap(np.arctan2(pts[:, 1], pts[:, 0]))
    pitch = 2 * np.pi / teeth
    closing = np.arctan2(cross(pts[-1], pts[0]), np.dot(pts[-1], pts[0]))  # the step from the last point back to the first
    winding = (ang[-1] - ang[0] + closing) / (2 * np.pi)
    if abs(abs(winding) - 1.0) < 0.25:  # a closed outline around the centre
        whole = pts if winding > 0 else pts[::-1]
        found = lobe_count(whole)
        if found != teeth:
            raise DesignError(label, f"an outline of {teeth} lobes as the tooth count says", None, f"it has {found} lobes")
        return whole
    span = ang[-1] - ang[0]
    if span < 0:
        pts, span = pts[::-1], -span
    spacing = np.median(np.abs(np.diff(ang)))
    if span < pitch - max(3 * spacing, 0.02 * pitch) and _one_groove(pts, span, pitch):
        return _patterned_groove(pts, teeth, label)
    if pitch - 1.5 * spacing > span and _one_groove(pts, span, pitch) and _on_land(pts):
        return _patterned_groove(pts, teeth, label)  # a lobe a little short at its land: the gap along the land's arc
    if abs(span - pitch) > max(3 * spacing, 0.02 * pitch):
        _refuse_off_centre(pts, label)
        share = "less than one lobe's" if span < pitch else f"{span / pitch:.3g} times the lobe's"
        raise DesignError(
            label,
            f"one lobe spanning the lobe pitch 360/{teeth} = {np.degrees(pitch):.4g} deg (or one groove or tooth from tip "
            "to tip or root to root), or the whole outline",
            None,
            f"its {len(pts)} points span {np.degrees(span):.4g} deg about the centre, {share} span",
        )
    # one lobe: keep one pitch of it (the last point may repeat the first one lobe on) and pattern it
    ang = ang - ang[0]
    keep = ang < pitch - 1e-9 * pitch
    lobe = pts[keep]
    # a last point within half a spacing of the first one lobe on is that point again (a scan from tip to tip
    # ending 0.08 µm short of the pitch): kept, it made a step of 0.08 µm at a sharp tip corner, and the
    # narrow-tip male was refused ("4.3 % of the lobe has no rack point")
    again = rotate(lobe[:1], pitch)[0]
    half = 0.5 * float(np.median(np.hypot(*np.diff(lobe, axis=0).T)))
    while len(lobe) > 4 and np.hypot(*(lobe[-1] - again)) < half:
        lobe = lobe[:-1]
    return np.vstack([rotate(lobe, pitch * k) for k in range(teeth)])


def _refuse_off_centre(pts: np.ndarray, label: str) -> None:
    """Refuse a whole outline that winds around another point than the origin, saying where it lies.

    rotorcad's pair drawing (``rotor --dxf``) places the female at the centre distance (a, 0); read
    back as the female's points it does not wind around the origin, and was refused as a lobe
    spanning 0.0004 deg (a new user's finding). Raises :class:`DesignError` naming ``label`` when
    the points close around their own centroid (winding once) and that lies away from the origin.
    """
    step = np.hypot(*np.diff(pts, axis=0).T)
    if np.hypot(*(pts[-1] - pts[0])) > 3 * step.max():  # an open run of points (too few, part of a lobe), not an outline
        return
    c = pts.mean(axis=0)
    rel = pts - c
    ang = np.unwrap(np.arctan2(rel[:, 1], rel[:, 0]))
    closing = np.arctan2(cross(rel[-1], rel[0]), np.dot(rel[-1], rel[0]))
    winding = (ang[-1] - ang[0] + closing) / (2 * np.pi)
    if abs(abs(winding) - 1.0) < 0.25 and np.hypot(*c) > np.hypot(*rel.T).min():
        raise DesignError(
            label,
            "points in the rotor's own frame, its centre at the origin",
            None,
            f"the outline winds around ({c[0]:.4g}, {c[1]:.4g}) mm, {np.hypot(*c):.4g} mm off the origin "
            "(rotorcad's pair drawing places the female at the centre distance (a, 0): move it by (-a, 0))",
        )


GROOVE_ENDS = 0.5
"""Share of the radial range within which both ends of a span shorter than the pitch lie from the
same extreme radius (tip or root) for the span to be taken as one groove or one tooth (and refused
by :func:`_groove_land`, saying why, when an end falls short of that tip or root)."""


def _one_groove(pts: np.ndarray, span: float, pitch: float) -> bool:
    """Tell whether points spanning less than the pitch are one groove or one tooth of a rotor.

    That is a span from tip to tip (a groove, as a CMM measures a female) or from root to root (a
    tooth), which holds both flanks: both ends within :data:`GROOVE_ENDS` of the radial range from
    the same extreme radius, a span of at least a quarter of the pitch and radii over 1 % of the
    largest apart (a lobe's depth, not a land alone). Whether the ends reach
    that tip or root is judged when it is patterned (:func:`_groove_land`).
    """
    r = np.hypot(*pts.T)
    lo, hi = float(r.min()), float(r.max())
    near = GROOVE_ENDS * (hi - lo)
    ends = r[[0, -1]]
    at_tip, at_root = np.all(ends >= hi - near), np.all(ends <= lo + near)
    return bool(span >= 0.25 * pitch and hi - lo > 0.01 * hi and (at_tip or at_root))  # a lobe's depth, not a land


GROOVE_END_FLOOR = 1e-3
"""mm: the ends of one groove or tooth lie on its tip or root land when their radii are within this
of the land's, or within six times the points' scatter when that is more."""

GROOVE_END_SLOPE = np.radians(6.0)
"""rad: the most the outline may turn away from the land's circle over the first
:data:`GROOVE_END_REACH` from an end of one groove or tooth for that end to lie on the land (a root
fillet of 0.1 mm radius tangent to it turns 6 deg over 0.01 mm; a flank 2 deg short of the land
turns by tens of degrees)."""

GROOVE_END_REACH = 0.01
"""mm: the length from an end of one groove or tooth over which its turn from the land is judged
(40 scatters when that is more)."""


def _land_ends(pts: np.ndarray) -> tuple[float, np.ndarray, np.ndarray, float, bool]:
    """Measure how the ends of a span shorter than the pitch lie on its tip or root land (:func:`_groove_land`).

    Returns the land's radius (mm), each end's distance from it (mm) and turn from its circle (rad,
    0 within the tolerance), the tolerance (mm) and whether it is the tip.
    """
    r = np.hypot(*pts.T)
    lo, hi = float(r.min()), float(r.max())
    at_tip = bool(abs(r[0] - hi) + abs(r[-1] - hi) <= abs(r[0] - lo) + abs(r[-1] - lo))
    sigma = scatter(pts)
    tol = max(GROOVE_END_FLOOR, 6.0 * sigma)
    land = float(np.median(r[r >= hi - tol] if at_tip else r[r <= lo + tol]))
    off = np.abs(r[[0, -1]] - land)
    reach = max(GROOVE_END_REACH, 40.0 * sigma)
    turn = np.zeros(2)
    for k, run in enumerate((pts, pts[::-1])):  # from either end inwards
        far = np.hypot(*(run - run[0]).T)
        j = int(np.argmax(far >= reach)) if np.any(far >= reach) else len(run) - 1
        radial = np.dot(run[j] - run[0], run[0]) / max(float(np.hypot(*run[0])), 1e-300)
        turn[k] = np.arcsin(np.clip(abs(radial) / max(float(far[j]), 1e-300), 0.0, 1.0))
    turn = np.where(turn * reach > tol, turn, 0.0)  # a rise within the tolerance is no turn
    return land, off, turn, tol, at_tip


def _on_land(pts: np.ndarray) -> bool:
    """Tell whether both ends of a span shorter than the pitch lie on its tip or root land (:func:`_groove_land`)."""
    _, off, turn, tol, _ = _land_ends(pts)
    return bool(np.all(off <= tol) and np.all(turn <= GROOVE_END_SLOPE))


def _groove_land(pts: np.ndarray, label: str) -> float:
    """Return the radius of the land both ends of one groove or tooth lie on (mm), or refuse.

    Points that span less than the lobe pitch from tip to tip (a groove) or root to root (a tooth)
    leave part of the lobe unmeasured between one copy and the next; for the outline to be known
    there, that part is a land (an arc about the centre: without one, tip to tip or root to root spans
    the pitch) and both ends lie on it: at the land's radius (the median radius of the points within
    the tolerance, :data:`GROOVE_END_FLOOR` or 6 sigma, of the extreme one, sigma the points'
    :func:`scatter`) and running along its circle, turned from it by less than
    :data:`GROOVE_END_SLOPE` over :data:`GROOVE_END_REACH` (a root fillet or tip rounding tangent to
    the land). An end short of the land lies on a flank or rounding, and what lies between it and the
    land was not measured: a rack-involute male tooth cut 2-3 deg short of its root land was filled
    by a straight line from the one flank to the other.

    Raises
    ------
    DesignError
        Naming ``label``, how far from the land's radius each end lies and how steeply the outline
        leaves its circle there.
    """
    land, off, turn, tol, at_tip = _land_ends(pts)
    if np.all(off <= tol) and np.all(turn <= GROOVE_END_SLOPE):
        return land
    where, part = ("below", "tip") if at_tip else ("above", "root")
    raise DesignError(
        label,
        f"one groove or tooth whose both ends lie on its {part} land (within {tol * 1e3:.3g} µm of the {part} radius "
        f"{land:.4f} mm its points reach, running along that circle), one lobe spanning the lobe pitch, or the whole "
        "outline",
        None,
        f"its first and last points lie {off[0]:.4g} and {off[1]:.4g} mm {where} it, leaving its circle at "
        f"{np.degrees(turn[0]):.3g} and {np.degrees(turn[1]):.3g} deg: short of the {part} land, on a flank or "
        f"rounding, and the part between them and the land was not measured (it would be guessed); give the points "
        f"up to the {part} land on both sides",
    )


def _patterned_groove(pts: np.ndarray, teeth: int, label: str = "points") -> np.ndarray:
    """Make the whole outline from one groove or tooth, counter-clockwise.

    The span is patterned ``teeth`` times; the part between the end of one copy and the start of
    the next, which was not measured (the tip or the root between two grooves), is filled with
    points at the polar angle's own spacing on the arc about the centre at the radius both ends
    lie on (:func:`_groove_land`, which refuses ends short of the tip or root land), the ends' own
    radii blended into it over the gap (within the tolerance of that land).
    """
    pitch = 2 * np.pi / teeth
    land = _groove_land(pts, label)
    theta = np.unwrap(np.arctan2(pts[:, 1], pts[:, 0]))
    r = np.hypot(*pts.T)
    gap = theta[0] + pitch - theta[-1]
    step = float(np.median(np.abs(np.diff(theta))))
    n = max(int(np.ceil(gap / max(step, 1e-6))), 2)
    u = np.linspace(0.0, 1.0, n + 1)[1:-1]
    fill_t = theta[-1] + gap * u
    fill_r = land + (r[-1] - land) * (1.0 - u) ** 2 + (r[0] - land) * u**2  # on the land, meeting either end
    fill = np.column_stack([fill_r * np.cos(fill_t), fill_r * np.sin(fill_t)])
    lobe = np.vstack([pts, fill])
    return np.vstack([rotate(lobe, pitch * k) for k in range(teeth)])


def raw_scatter(whole: np.ndarray) -> float:
    """Estimate the points' scatter normal to the outline from their third differences, without a floor.

    The estimate of :func:`scatter` (module docstring) before it is taken as 0 below
    :data:`SCATTER_FLOOR`: the error that points taken as exact still carry (a polyline's chords they
    were resampled from, the decimals they were written to), which an interpolating spline's
    curvature reads as noise once the points are dense (:func:`rotorcad.measured.fit.fine_knot_spacing`).

    Parameters
    ----------
    whole : (n, 2) float array, mm
        The closed outline (8 points at least).

    Returns
    -------
    float, mm
    """
    p = np.asarray(whole, dtype=float)
    d3 = np.roll(p, -2, axis=0) - 3 * np.roll(p, -1, axis=0) + 3 * p - np.roll(p, 1, axis=0)
    chord = np.roll(p, -2, axis=0) - np.roll(p, 1, axis=0)
    length = np.hypot(*chord.T)
    ok = length > 0
    normal = np.abs(cross(chord[ok], d3[ok])) / length[ok]
    return float(1.4826 * np.median(normal) / np.sqrt(20.0))  # MAD of a zero-mean normal, sqrt(20): the difference's gain


def scatter(whole: np.ndarray) -> float:
    """Estimate the standard deviation of the points' scatter normal to the outline.

    From the median of the third differences (module docstring).

    Parameters
    ----------
    whole : (n, 2) float array, mm
        The closed outline.

    Returns
    -------
    float, mm
        sigma; 0 for exact points (below :data:`SCATTER_FLOOR`) or fewer than 8 points, and for
        unevenly spaced points (:data:`UNEVEN_SPACING`) that local cubics, which do not assume an
        even spacing, find exact (:func:`rotorcad.measured.pattern.uneven_scatter`: a polyline's
        vertices drawn to a chord tolerance, which the third differences read as scattered).
    """
    p = np.asarray(whole, dtype=float)
    if len(p) < 8:
        return 0.0
    sigma = raw_scatter(p)
    if sigma <= SCATTER_FLOOR:
        return 0.0
    step = np.hypot(*(np.roll(p, -1, axis=0) - p).T)
    uneven = np.quantile(step, 0.9) > UNEVEN_SPACING * np.quantile(step, 0.1)
    if uneven and uneven_scatter(p) <= SCATTER_FLOOR:  # exact points on an uneven spacing (a polyline's vertices)
        return 0.0
    return float(sigma)


def accuracy(whole: np.ndarray, sigma: float) -> float:
    """Estimate how far the outline the points give may lie from the true one.

    The larger of two scatters (2 sigma) and the chords' sagitta: between points spaced h on a
    curve of curvature k the curve leaves the chord by h^2 k / 8, which is a quarter of the distance
    of a point from the chord of its two neighbours; the 90th percentile of that over the outline
    (the corners, a few points, stay above it).

    Parameters
    ----------
    whole : (n, 2) float array, mm
        The closed outline.
    sigma : float, mm
        Its scatter (:func:`scatter`).

    Returns
    -------
    float, mm
    """
    p = np.asarray(whole, dtype=float)
    before, after = np.roll(p, 1, axis=0), np.roll(p, -1, axis=0)
    chord = after - before
    length = np.hypot(*chord.T)
    ok = length > 0
    off = np.abs(cross(chord[ok], (p - before)[ok])) / length[ok]
    sagitta = float(np.quantile(off, 0.9)) / 4.0 if ok.any() else 0.0
    return max(2.0 * sigma, sagitta)


def _chord_reach(p: np.ndarray, length: float) -> tuple[np.ndarray, np.ndarray]:
    """Return, for each edge (i, i + 1) of a closed outline, where the chords beside it start and end.

    The chord before the edge runs from point ``back[i]`` to point i, the one after it from point
    i + 1 to point ``ahead[i]`` (indices into the outline repeated three times, the edge's own
    copy the middle one): each the fewest points (one at least) that span ``length`` of outline.
    By length, not by a count of points: a measured outline's spacing is not even (a CMM's points
    in pairs 0.3 µm apart at a land, among points 0.3 mm apart), and a chord across two points
    closer than the scatter points anywhere.
    """
    n = len(p)
    step = np.hypot(*(np.roll(p, -1, axis=0) - p).T)
    s = np.concatenate([[0.0], np.cumsum(np.tile(step, 3))])  # arc length at the points of three copies
    i = np.arange(n) + n
    back = np.minimum(np.searchsorted(s, s[i] - length, side="right") - 1, i - 1)
    ahead = np.maximum(np.searchsorted(s, s[i + 1] + length, side="left"), i + 2)
    return back, np.minimum(ahead, 3 * n - 1)


def corners(whole: np.ndarray, sigma: float, angle_deg: float = 30.0) -> tuple[np.ndarray, np.ndarray]:
    """Find the sharp corners of a closed outline: the edges across which it turns by more than ``angle_deg``.

    The turn across edge i (from point i to point i + 1) is the angle between the chord that ends
    at point i and the chord that starts at point i + 1, so a corner shows in full whether it falls
    on a point or between two (a resampled or measured outline). Each chord spans the fewest points
    whose outline is 40 scatters long at least (its direction then wanders by 2 deg at most,
    however dense or uneven the points), but at most 0.1 mm (:func:`_chord_reach`); of exact points
    it is the one neighbouring edge. Of the edges within the chords' reach of each other only the
    one of largest turn is kept, and the corner's point is where the lines of its two chords cross
    (on the points for an exact corner vertex, between them otherwise).

    Parameters
    ----------
    whole : (n, 2) float array, mm
        The closed outline.
    sigma : float, mm
        Its scatter (:func:`scatter`); 0 for exact points.
    angle_deg : float, deg
        Smallest turn of a corner.

    Returns
    -------
    edges : (m,) int array
        Index i of the edge (i, i + 1) of each corner, ascending.
    points : (m, 2) float array, mm
        Each corner's point.
    """
    p = np.asarray(whole, dtype=float)
    n = len(p)
    ring = np.vstack([p, p, p])
    back, ahead = _chord_reach(p, min(40.0 * sigma, 0.1) if sigma > 0 else 0.0)
    i = np.arange(n)
    a0, a1 = ring[back], p  # chord before the edge
    b0, b1 = np.roll(p, -1, axis=0), ring[ahead]  # chord after it
    before, after = a1 - a0, b1 - b0
    signed = np.arctan2(cross(before, after), np.einsum("ij,ij->i", before, after))
    turn = np.abs(signed)
    reach_before, reach_after = i + n - back, ahead - (i + n + 1)  # points each chord spans
    d = np.roll(p, -1, axis=0) - p
    heading = np.arctan2(d[:, 1], d[:, 0])
    vertex_turn = np.abs(wrap_angle(heading - np.roll(heading, 1)))  # turn at each vertex
    # a concave turn (to the right of the counter-clockwise outline) across one edge between chords
    # of one edge each is a corner when it happens at the edge alone: where two generated flanks meet
    # at a root (Lysholm, Krigar, SRM-B males: 58-88 deg, the vertices beside it turn by 2.4 % of that
    # at most). A root fillet that sparse points do not resolve turns as much over the edge, but the
    # vertices beside it turn too (the independent females at 80 points a lobe: 42-46 deg, 19-43 %
    # beside); the spline keeps it smooth (a kink there would send the rack's normals anywhere)
    beside = np.maximum(np.roll(vertex_turn, 1), np.roll(vertex_turn, -2))  # at the vertices before and after the edge's two
    single = (reach_before == 1) & (reach_after == 1)
    turn = np.where(single & (signed < 0) & (beside > 0.1 * turn), 0.0, turn)
    # a peak: no larger turn across the edges within its chords' reach (a corner shows on each of them)
    reach = np.maximum(reach_before, reach_after)
    peak = turn.copy()
    for off in range(1, int(reach.max()) + 1):
        within = reach >= off
        peak = np.where(within, np.maximum(peak, np.maximum(np.roll(turn, off), np.roll(turn, -off))), peak)
    idx = np.flatnonzero((turn > np.radians(angle_deg)) & (turn >= peak))
    if len(idx) > 1:  # a plateau of equal turns: its first edge (also across the ring's seam)
        gaps = np.diff(np.concatenate([idx, [idx[0] + n]]))
        idx = idx[np.roll(gaps, 1) > reach[idx]] if np.any(gaps > reach[idx]) else idx[:1]
    den = cross(before[idx], after[idx])
    u = cross(b0[idx] - a0[idx], after[idx]) / np.where(np.abs(den) > 0, den, 1.0)
    point = a0[idx] + u[:, None] * before[idx]
    # a crossing far from the edge (nearly parallel chords): the edge's middle
    mid = 0.5 * (a1[idx] + b0[idx])
    span = np.maximum(np.hypot(*before[idx].T), np.hypot(*after[idx].T))
    far = np.hypot(*(point - mid).T) > 2 * span
    point[far] = mid[far]
    # a corner on a point of exact data is that point (the chords' lines of curved pieces cross
    # a little off it): the end of the edge that turns by more than the threshold on its own
    if sigma <= 0:  # on a point when that point turns by (nearly) the whole corner; between two points (a
        # resampled outline: the corner's chord) it turns by a share of it, and the pieces' crossing is the corner
        whole = np.maximum(turn[idx], np.radians(angle_deg))
        at_start = vertex_turn[idx] > 0.9 * whole
        at_end = vertex_turn[(idx + 1) % n] > 0.9 * whole
        met, crossing = _circles_crossing(p, idx, point)
        between = met & ~far & ~at_start & ~at_end
        point[between] = crossing[between]
        point[at_start] = p[idx[at_start]]
        point[at_end & ~at_start] = p[(idx[at_end & ~at_start] + 1) % n]
        # a crossing within a thousandth of its edge of one of the edge's ends is that point: kept apart, it
        # began a run with a step of 10 nm (the asymmetric SRM male from its tip corner: refused as noise);
        # within 1 nm it is that point already (rotorcad.measured.fit._runs_between_corners leaves it out)
        ends = np.stack([p[idx], p[(idx + 1) % n]], axis=1)
        off = np.linalg.norm(point[:, None, :] - ends, axis=2)
        snap = (off.min(axis=1) > 1e-6) & (off.min(axis=1) < 1e-3 * np.hypot(*(ends[:, 1] - ends[:, 0]).T))
        point[snap] = ends[snap, np.argmin(off[snap], axis=1)]
    return idx, point


def _circles_crossing(p: np.ndarray, edges: np.ndarray, near: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Return where the pieces either side of corners of exact points cross (mm), and whether they do.

    Each piece is the circle through its three points nearest the corner (the corner edge's end
    and the two before it, its start and the two after it); their crossing nearest the chords'
    crossing ``near`` is the corner, to the circles' third-order error, where the chords' lines
    miss a corner between curved pieces by their sagitta (the asymmetric SRM male at 300 points a
    lobe, one lobe from root to root: its tip corner 2.9 µm outside the tip circle with the chords,
    on it with the circles; the male was refused as noise). Not met (False) where the circles do not cross within a tenth
    of the edge of ``near`` (points nearly in a line, or a piece shorter than three points).

    Parameters
    ----------
    p : (n, 2) float array, mm
        The closed outline.
    edges : (m,) int array
        The corners' edges (i, i + 1).
    near : (m, 2) float array, mm
        The corners' points as the chords give them.

    Returns
    -------
    met : (m,) bool array
    points : (m, 2) float array, mm
    """
    out = np.array(near, dtype=float)
    met = np.zeros(len(out), dtype=bool)
    n = len(p)
    for k, (i, q) in enumerate(zip(edges, near, strict=True)):
        a = p[np.arange(i - 2, i + 1) % n]
        b = p[np.arange(i + 1, i + 4) % n]
        hits = _circle_meets(_circle(a), _circle(b))
        if len(hits):
            best = hits[np.argmin(np.hypot(*(hits - q).T))]
            if np.hypot(*(best - q)) < 0.1 * np.hypot(*(p[(i + 1) % n] - p[i])):
                out[k], met[k] = best, True
    return met, out


def _circle(t: np.ndarray) -> tuple[np.ndarray, float] | None:
    """Return the circle through three points (centre (2,) mm, radius mm), None when they lie (nearly) in a line."""
    (ax, ay), (bx, by), (cx, cy) = t
    d = 2.0 * (ax * (by - cy) + bx * (cy - ay) + cx * (ay - by))
    scale = float(np.ptp(t, axis=0).max())
    if abs(d) <= 1e-9 * scale**2:
        return None
    sa, sb, sc = ax * ax + ay * ay, bx * bx + by * by, cx * cx + cy * cy
    centre = np.array([sa * (by - cy) + sb * (cy - ay) + sc * (ay - by), sa * (cx - bx) + sb * (ax - cx) + sc * (bx - ax)]) / d
    radius = float(np.hypot(*(t[0] - centre)))
    return (centre, radius) if radius < 1e3 * scale else None


def _circle_meets(one: tuple[np.ndarray, float] | None, other: tuple[np.ndarray, float] | None) -> np.ndarray:
    """Return where two circles meet, (m, 2) float, mm (none, one or two points; none when either is None)."""
    if one is None or other is None:
        return np.zeros((0, 2))
    (c0, r0), (c1, r1) = one, other
    d = float(np.hypot(*(c1 - c0)))
    if d == 0.0 or d > r0 + r1 or d < abs(r0 - r1):
        return np.zeros((0, 2))
    a = (r0 * r0 - r1 * r1 + d * d) / (2.0 * d)
    h = np.sqrt(max(r0 * r0 - a * a, 0.0))
    u = (c1 - c0) / d
    m = c0 + a * u
    v = np.array([-u[1], u[0]])
    return np.array([m + h * v, m - h * v])


def lands(run: np.ndarray, sigma: float, min_angle_deg: float = 0.5, min_points: int = 6) -> list[tuple[int, int, float]]:
    """Find the lands of a run of outline points: arcs about the rotor's own centre within the scatter.

    Lands are the images of the rack's flats at the tip and root lines. A point belongs to a land when
    the radii of the points within 0.05 mm either side of it differ by at most 2 tol,
    tol = max(4 sigma, 0.3 µm) (the scallops of a boolean cut, the chords of a drawing); runs of such
    points, trimmed at both ends to the points within max(2 sigma, 0.01 µm) of the run's median radius
    (the window reaches past a land's ends), spanning ``min_angle_deg`` and ``min_points`` at least
    are lands.

    Parameters
    ----------
    run : (n, 2) float array, mm
        Consecutive outline points about the origin.
    sigma : float, mm
        Their scatter.
    min_angle_deg : float, deg
        Smallest angle a land spans about the origin.
    min_points : int
        Fewest points of a land.

    Returns
    -------
    list of (first, last, radius)
        Indices of the land's first and last point in ``run`` and its radius (mm, the median
        of its points' radii).
    """
    p = np.asarray(run, dtype=float)
    if len(p) < min_points:
        return []
    r = np.hypot(*p.T)
    h = float(np.median(np.hypot(*np.diff(p, axis=0).T)))
    w = int(np.clip(np.ceil(0.05 / max(h, 1e-9)), 1, 50))
    tol = max(4 * sigma, 3e-4)
    from scipy.ndimage import maximum_filter1d, minimum_filter1d

    spread = maximum_filter1d(r, size=2 * w + 1, mode="nearest") - minimum_filter1d(r, size=2 * w + 1, mode="nearest")
    flat = spread <= 2 * tol
    edges = np.flatnonzero(np.diff(np.concatenate([[0], flat.astype(int), [0]])))
    out = []
    theta = np.unwrap(np.arctan2(p[:, 1], p[:, 0]))
    end_tol = max(2 * sigma, 1e-5)
    for a, b in zip(edges[::2], edges[1::2] - 1, strict=True):
        radius = float(np.median(r[a : b + 1]))
        on = np.flatnonzero(np.abs(r[a : b + 1] - radius) <= end_tol)  # the window reaches past the ends:
        if len(on) == 0:  # trim them to the points on the circle
            continue
        a, b = a + int(on[0]), a + int(on[-1])
        if b - a + 1 >= min_points and abs(theta[b] - theta[a]) >= np.radians(min_angle_deg):
            out.append((int(a), int(b), float(np.median(r[a : b + 1]))))
    return out


@dataclass(frozen=True, eq=False)
class Outline:
    """A rotor outline as given, read once: what the fit and the accuracy statements start from.

    Attributes
    ----------
    given : (n, 2) float array or list of Curve, mm
        Points, or a drawing's exact curves (:func:`as_given`).
    whole : (m, 2) float array or None, mm
        The whole outline of the points (:func:`whole_outline`); None for exact curves.
    sigma : float, mm
        Estimated scatter of the points (:func:`scatter`; 0 for curves).
    accuracy : float, mm
        How far the outline the points give may lie from the true one (:func:`points_accuracy`).
    teeth : int
        Lobe count.
    label : str
        How the profile is named in errors.
    """

    given: np.ndarray | list[Curve]
    whole: np.ndarray | None
    sigma: float
    accuracy: float
    teeth: int
    label: str


def read_outline(
    points: np.ndarray | list[Curve] | Outline,
    teeth: int,
    label: str,
    corner_angle_deg: float = 30.0,
    drawn_as_points: bool = True,
) -> Outline:
    """Read a rotor profile once: the geometry to fit, its whole outline, scatter and accuracy.

    Parameters
    ----------
    points : (n, 2) float array, list of Curve or Outline, mm
        One lobe, one groove or tooth, or the whole outline in the rotor's own frame, or a
        drawing's curves (an Outline is returned as it is).
    teeth : int
        Lobe count of the rotor.
    label : str
        How the profile is named in errors.
    corner_angle_deg : float, deg
        Turn above which a drawing's joint is a sharp corner (:func:`as_given`).
    drawn_as_points : bool
        Read a drawing that approximates the outline as its points (:func:`drawing_points`).

    Returns
    -------
    Outline

    Raises
    ------
    DesignError
        Naming ``label``: points that do not make a rotor of ``teeth`` lobes (:func:`whole_outline`).
    """
    if isinstance(points, Outline):
        return points
    given = as_given(points, teeth, corner_angle_deg, drawn_as_points)
    if isinstance(given, list):
        # a drawing's splines are as accurate as the points they were drawn through: their knots; a
        # spline that carries its tangents (a Hermite interpolant of an exact curve) is exact as given
        splines = [c for c in given if isinstance(c, Spline)]
        knots = [c.evaluate(np.unique(np.clip(c.knots[0], *sorted((c.s0, c.s1)))))[0] for c in splines if not carries_tangents(c)]
        pts = np.vstack(knots) if knots else np.zeros((0, 2))
        acc = max(accuracy(pts, 0.0), 1e-9) if len(pts) >= 8 else 1e-9
        acc = max([acc, *(hermite_accuracy(c) for c in splines if carries_tangents(c))])
        return Outline(given, None, 0.0, acc, teeth, label)
    whole = whole_outline(given, teeth, label)
    refuse_too_many(whole, teeth, label)
    sigma = scatter(whole)
    acc = accuracy(whole, sigma)
    if sigma <= 0.0:  # points that show no scatter between neighbours may still lie on a polygon's chords
        chords = pattern_deviation(whole, teeth)
        if chords > acc and PATTERN_RMS * chords > SCATTER_FLOOR:  # they do: fitted as scattered by the pattern's spread
            sigma, acc = PATTERN_RMS * chords, chords  # (rotorcad.measured.pattern; below the floor they are exact)
    refuse_bad_points(whole, sigma, teeth, label, given, file_lines(points))
    return Outline(given, whole, sigma, acc, teeth, label)


MAX_OUTLINE_POINTS = 50_000
"""Most points of a whole measured outline that are fitted. More take time and memory without
resolving more (a CMM scan of 300-2000 points a lobe is read to its scatter): the narrow-tip male
of 50 000 points took 3.6 s of CPU; of 100 000, 10.6 s and 5.1 GB, its blow-hole 5.5 % off; of
200 000, over 14 GB; of 2 000 000, 1.5 GB and 69 s of CPU without a result (2 cores at a load of 6-10)."""


def refuse_too_many(whole: np.ndarray, teeth: int, label: str) -> None:
    """Refuse a whole outline of more than :data:`MAX_OUTLINE_POINTS` points, saying how to thin it.

    Raises
    ------
    DesignError
        Naming ``label``, the count, and which share of the points to keep.
    """
    n = len(whole)
    if n <= MAX_OUTLINE_POINTS:
        return
    keep = int(np.ceil(n / MAX_OUTLINE_POINTS))
    raise DesignError(
        label,
        f"an outline of at most {MAX_OUTLINE_POINTS} points ({MAX_OUTLINE_POINTS // teeth} a lobe)",
        None,
        f"the whole outline has {n}; keep one point in {keep} (300-2000 points a lobe are read to their scatter, "
        "more take time and memory without resolving more)",
    )


def points_accuracy(pair: RotorPair, points: np.ndarray | list[Curve], rotor: Side, label: str | None = None) -> float:
    """Estimate the accuracy of a rotor profile given by points or by a drawing's curves (mm).

    :func:`rotorcad.measured.outline.accuracy` of the whole outline: twice the estimated scatter, or
    the sagitta of the chords between the points, whichever is larger. A drawing's splines are
    judged by the points at their knots (what they were drawn through); lines and arcs are exact
    (1e-9 mm: given, not designed). :attr:`Outline.accuracy` of :func:`read_outline`.
    """
    rotor = Side(rotor)  # "male" / "female" from a script reads as the rotor
    side = Side(rotor)
    return read_outline(points, side.pick(pair.male_teeth, pair.female_teeth), label or f"{side.value} points").accuracy


__all__ = [
    "DRAWN_SPANS",
    "MAX_OUTLINE_POINTS",
    "SCATTER_FLOOR",
    "SMOOTH_JOINT",
    "UNEVEN_SPACING",
    "Outline",
    "accuracy",
    "as_given",
    "carries_tangents",
    "corners",
    "drawing_points",
    "hermite_accuracy",
    "lands",
    "lobe_count",
    "own_frame",
    "points_accuracy",
    "profile_points",
    "raw_scatter",
    "read_outline",
    "refuse_too_many",
    "scatter",
    "whole_outline",
]

"""A drawing's curves as given: exact where they are the outline's own, else the points they were drawn through.

Part of the first stage of the measured-outline pipeline (:mod:`rotorcad.measured.outline` reads
the geometry once through it). A drawing (:func:`exports.dxf_profile.read_profile_dxf`) is kept as
its curves when they meet smoothly or at sharp corners, its lands made exact arcs about the rotor's
centre; a drawing that approximates the outline (a polyline, arcs fitted to points, a spline drawn
through points) is read as its points. A spline that carries its tangents (double knots: a
Hermite interpolant of an exact curve, as ``export`` writes one per exact piece) is an exact
curve, whatever its number of pieces, and its accuracy is estimated (:func:`hermite_accuracy`). A
female drawn at its place in the pair is moved into its own frame (:func:`own_frame`).
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np

from rotorcad.curve_points import curve_points
from rotorcad.curves import Arc, Curve, Line, Mapped, Spline, sample_curve
from rotorcad.roles import Side


def _translated(curve: Curve, shift: np.ndarray) -> Curve:
    """Return ``curve`` moved by ``shift`` (mm), of the same kind.

    A line's ends, an arc's centre, a spline's control points (a B-spline's basis sums to one, so
    moving every control point moves the curve).
    """
    dx, dy = float(shift[0]), float(shift[1])
    if isinstance(curve, Line):
        return Line((curve.a[0] + dx, curve.a[1] + dy), (curve.b[0] + dx, curve.b[1] + dy))
    if isinstance(curve, Spline):
        t, (cx, cy), k = curve.knots
        return replace(curve, knots=(t, (np.asarray(cx) + dx, np.asarray(cy) + dy), k))
    if isinstance(curve, Arc):
        return replace(curve, center=(curve.center[0] + dx, curve.center[1] + dy))
    return Mapped(curve, ((1.0, 0.0), (0.0, 1.0)), (dx, dy))


def own_frame(
    profile: np.ndarray | list[Curve],
    rotor: Side,
    center_distance: float,
    label: str,
    radii: tuple[float, float] | None = None,
) -> np.ndarray | list[Curve]:
    """Move a female drawn at its place in the pair (its axis at (a, 0)) into its own frame.

    ``rotor --dxf`` and ``export`` draw the female at the centre distance (a, 0), as the pair
    stands in mesh (CONTRACT.md, points files). A rotor lies within the centre distance of its own
    axis (its tip radius is less than a); points or curves of the female that reach a or farther from
    the origin but lie within a of (a, 0) (its whole outline, one lobe or one groove) are that
    drawing: they are moved by (-a, 0), and an :class:`rotorcad.errors.InputNote` says so. Anything
    else (the male, a female in its own frame, an outline off both centres) is returned as it is
    (an outline off both is refused later, naming where it winds).

    Parameters
    ----------
    profile : (n, 2) float array or list of Curve, mm
        The profile as given.
    rotor : Side
        Which rotor it is.
    center_distance : float, mm
        The pair's centre distance a.
    label : str
        How the profile is named in the note.
    radii : (float, float) or None, mm
        The female's root and tip radii, when known: the profile is moved only when its points lie
        between them about (a, 0), within a tenth of the lobe depth (a female drawn a few mm beside
        its place is refused later, naming where it winds, not moved by a).

    Returns
    -------
    (n, 2) float array or list of Curve, mm
        The profile in the rotor's own frame.
    """
    rotor = Side(rotor)
    a = float(center_distance)
    if rotor is Side.MALE or not (np.isfinite(a) and a > 0):
        return profile
    pts = profile_points(profile, 1e-2)
    if len(pts) == 0:
        return profile
    here = np.hypot(*pts.T).max()
    there = np.hypot(*(pts - (a, 0.0)).T).max()
    if not (here >= a > there):
        return profile
    if radii is not None:
        root, tip = sorted(radii)
        r = np.hypot(*(pts - (a, 0.0)).T)
        if r.min() < root - 0.1 * (tip - root) or r.max() > tip + 0.1 * (tip - root):
            return profile
    import warnings

    from rotorcad.errors import InputNote

    warnings.warn(
        f"{label}: the female is drawn at its place in the pair, about ({a:g}, 0) mm (the centre distance), "
        f"as rotor --dxf and export draw it; it was moved by ({-a:g}, 0) mm into its own frame",
        InputNote,
        stacklevel=2,
    )
    shift = np.array([-a, 0.0])
    if isinstance(profile, list | tuple):
        return [_translated(c, shift) for c in profile]
    moved = np.asarray(profile, dtype=float) + shift
    lines = getattr(profile, "lines", None)  # a points file's lines (exports.csv_points.FilePoints) stay named
    return type(profile).of(moved, lines) if lines is not None else moved


def profile_points(profile: np.ndarray | list[Curve], tolerance: float = 1e-4) -> np.ndarray:
    """Return the points of a profile given by points or by exact curves.

    Parameters
    ----------
    profile : (n, 2) float array or list of Curve, mm
        Points (returned as they are) or exact curves.
    tolerance : float, mm
        Chord tolerance for sampling curves.

    Returns
    -------
    (n, 2) float array, mm
    """
    if isinstance(profile, list | tuple):
        return curve_points(profile, tolerance)  # sample_curve's points of each curve, a polyline's lines at once
    return np.asarray(profile, dtype=float)


def as_given(
    points: np.ndarray | list[Curve], teeth: int, corner_angle_deg: float = 30.0, drawn_as_points: bool = True
) -> np.ndarray | list[Curve]:
    """Return a profile as it is to be fitted: a drawing's exact curves, or points.

    A drawing stays its curves when they are the outline's own (:func:`drawing_points` finds no
    approximation) and span one lobe or more, its splines of a land made exact arcs about the
    centre (:func:`_land_arc`); a drawing that approximates the outline is read as
    its points (with ``drawn_as_points``: the rack generation needs them), and one of a single
    groove or tooth (less than the lobe pitch) as points sampled at 0.1 µm chord, which
    :func:`rotorcad.measured.outline.whole_outline` patterns.

    Parameters
    ----------
    points : (n, 2) float array or list of Curve, mm
        The profile.
    teeth : int
        Lobe count of the rotor.
    corner_angle_deg : float, deg
        Turn above which a joint is a sharp corner.
    drawn_as_points : bool
        Read a drawing that approximates the outline as its points (:func:`drawing_points`);
        False keeps its curves (the clearance measures distances between them as drawn).

    Returns
    -------
    (n, 2) float array or list of Curve
    """
    if not (isinstance(points, list | tuple) and points and isinstance(points[0], Curve)):
        return np.asarray(points, dtype=float)
    curves = list(points)
    drawn = drawing_points(curves, corner_angle_deg) if drawn_as_points or _polygonal(curves, corner_angle_deg) else None
    if drawn is not None:
        return drawn
    pts = curve_points(curves, 1e-4)
    ang = np.unwrap(np.arctan2(pts[:, 1], pts[:, 0]))
    if abs(ang[-1] - ang[0]) < 0.98 * 2 * np.pi / teeth:  # one groove or tooth: patterned as points
        return pts
    return [_land_arc(c) for c in curves]


LAND_SPREAD = 1e-4
"""mm: a drawing's spline whose radii about the rotor's centre differ by no more than this (over at
least :data:`LAND_ANGLE`) is a land, read as that exact arc about the centre (export's splines of a
tip or root land lie within 4 nm of their circle)."""

LAND_ANGLE = np.radians(0.5)
"""rad: smallest angle about the centre of a land (as :func:`lands` of points)."""


def _land_arc(curve: Curve) -> Curve:
    """Return a drawing's spline of a land as the exact arc about the rotor's centre; any other curve as it is.

    The lands of measured points are fitted as exact arcs about the centre (:mod:`rotorcad.measured.fit`):
    their normals are radial, and the rack image of a land is the exact flat at the tip or root line. A
    spline that only approximates the arc (to nanometres, as ``export`` writes it) has normals that miss
    the centre by a little: on the narrow-tip female's tip land, which lies on the pitch circle, its rack
    image ran to 179 mm, and the male generated from it was refused as noise.
    """
    if not isinstance(curve, Spline):
        return curve
    _, p, _ = sample_curve(curve, 1e-5)
    r = np.hypot(*p.T)
    theta = np.unwrap(np.arctan2(p[:, 1], p[:, 0]))
    turn = float(theta[-1] - theta[0])
    if np.ptp(r) > LAND_SPREAD or abs(turn) < LAND_ANGLE or np.any(np.diff(theta) * np.sign(turn) <= 0):
        return curve
    return Arc((0.0, 0.0), float(np.median(r)), float(theta[0]), float(theta[0]) + turn)


SMOOTH_JOINT = 1e-3
"""rad: consecutive curves of a drawing whose tangents differ by more than this (and less than a
corner's angle) meet at a kink: the drawing approximates the outline (a polyline, a chain of arcs
fitted to points) and is read as its points."""


def drawing_points(curves: list[Curve], corner_angle_deg: float = 30.0) -> np.ndarray | None:
    """Return the points of a drawing that approximates an outline, or None for an exact drawing.

    A drawing is read as the points it was drawn through when its curves meet at kinks (tangents
    turning by more than :data:`SMOOTH_JOINT` and less than ``corner_angle_deg``: a polyline, arcs
    fitted to points), or when it holds a spline of more than :data:`DRAWN_SPANS` polynomial pieces
    that does not carry its tangents (:func:`carries_tangents`: a spline through points, as CAD
    draws one on measured points; export's Hermite splines of 16-25 pieces are exact curves): the rack of a
    straight piece would be a single point, a kink a gap, and a spline drawn across a sharp corner
    rings. The points are each line's start, each arc's start and middle (the points it was drawn
    through, :func:`_arc_points`) and a spline's points at its knots; they are then
    fitted, smoothed and cut at corners as measured points are, to the accuracy they carry
    (:func:`rotorcad.measured.outline.points_accuracy`).

    Parameters
    ----------
    curves : list of Curve
        The drawing's curves, chained (:func:`exports.dxf_profile.read_profile_dxf`).
    corner_angle_deg : float, deg
        Turn above which a joint is a sharp corner (kept as a corner by the points' fit).

    Returns
    -------
    (n, 2) float array, mm, or None
    """
    kinks = _kinks(curves, corner_angle_deg)
    drawn = [c for c in curves if isinstance(c, Spline) and _drawn_through_points(c)]
    if not kinks[:-1].any() and not drawn:  # the last joint closes a lobe (a corner or nothing)
        return None
    spacing = _drawn_spacing(curves)
    with_arcs = sum(isinstance(c, Arc) for c in curves) >= ARCS_THROUGH_POINTS  # arcs fitted to points
    after = _joint_turns(curves)
    before = np.roll(after, 1)  # the turns at each curve's start and end
    pts = []
    for i, (c, joint_before, joint_after) in enumerate(zip(curves, before, after, strict=True)):
        if isinstance(c, Spline):
            u = _knot_parameters(c)
            pts.append(c.evaluate(u[:-1])[0])
        elif isinstance(c, Line):  # its start; among arcs drawn through points, at their spacing (three in a line)
            pieces = max(1, round(abs(c.s1 - c.s0) / spacing)) if with_arcs and spacing > 0 else 1
            pts.append(c.evaluate(c.s0 + (c.s1 - c.s0) * np.arange(pieces) / pieces)[0])
        elif isinstance(c, Arc) and with_arcs:
            beside = (curves[i - 1], curves[(i + 1) % len(curves)])
            pts.append(_arc_points(c, spacing, np.radians(corner_angle_deg), (joint_before, joint_after), beside))
        else:  # a designed drawing's few arcs, another curve: to 0.1 um chord, at least its middle
            pts.append(sample_curve(c, 1e-4, minimum=3)[1][:-1])
    return np.vstack(pts)


ARCS_THROUGH_POINTS = 40
"""A drawing read as points that holds at least this many arcs is arcs fitted to points (one lobe of
80 CMM points drawn as 3-point arcs holds 40): each arc is read as the points it was drawn through
(:func:`_arc_points`). A designed drawing's few arcs are sampled at 0.1 µm chord, as before."""


def _drawn_spacing(curves: list[Curve]) -> float:
    """Return the spacing of the points a drawing was drawn through (mm).

    The median over its pieces of the length each spans per point: a line was drawn from one point
    (its start), an arc through three (its start, one point between and its end): half its length.
    """
    keep = [c for c in curves if isinstance(c, Line | Arc)]
    length = np.array([abs(c.s1 - c.s0) * (c.radius if isinstance(c, Arc) else 1.0) for c in keep])
    per = np.array([2.0 if isinstance(c, Arc) else 1.0 for c in keep])
    return float(np.median(length / per)) if keep else 0.0


def _arc_points(
    arc: Arc, spacing: float, corner_angle: float, joints: tuple[float, float], beside: tuple[Curve, Curve]
) -> np.ndarray:
    """Return the points an arc of a drawing stands for, its end left to the next piece.

    An arc was drawn through three points (CAD's 3-point arc, a polyline's bulge through a point
    between its ends): its start, one point between and its end. Where the outline is smooth the
    one between is its middle, the point equidistant from both ends, to within the arc's
    third-order deviation (the circle through three points of a curve leaves it by O(h^3 k'), h
    the spacing). Not densely sampled: the arc's own rounding between the points is no part of the
    outline (the arc through the three points around a sharp tip rounds it to r = 0.3-0.9 mm, which
    read the blow-hole of three samples as 0.01-0.02 mm² against 2.8-22.7, the meshline closed).

    An arc that turns, with the larger turn at its ends, by more than a corner's angle holds a
    corner between its points (its middle lies inside the corner, 4-17 µm on the asymmetric SRM's
    tip). Two of its three points lie on one side of the corner, one spacing apart (the points are
    evenly spaced along the outline): the point between is the one on the arc one spacing's chord
    from its start or from its end, whichever lies on the neighbouring piece on that side extended
    (:func:`_off_extension`; on the samples' drawings the right one lies within 0.2 µm of it, the
    other 33-300 µm off, and it is the point drawn through to 0.05 µm). A longer arc (a land drawn
    as one arc among lines) is read at the drawing's spacing, a land of many points.

    Parameters
    ----------
    arc : Arc
        The drawing's arc.
    spacing : float, mm
        The spacing of the points the drawing was drawn through (:func:`_drawn_spacing`).
    corner_angle : float, rad
        Turn above which a joint is a sharp corner.
    joints : (float, float), rad
        The turns at the joints at the arc's start and at its end (:func:`_joint_turns`).
    beside : (Curve, Curve)
        The drawing's pieces before and after the arc.

    Returns
    -------
    (m, 2) float array, mm
    """
    sweep = arc.s1 - arc.s0
    pieces = max(2, round(abs(sweep) * arc.radius / spacing)) if spacing > 0 else 2
    if pieces > 2 or abs(sweep) + max(joints) <= corner_angle:
        return arc.evaluate(arc.s0 + sweep * np.arange(pieces) / pieces)[0]
    step = 2.0 * np.arcsin(min(1.0, spacing / (2.0 * arc.radius))) * np.sign(sweep)  # one spacing's chord
    if not abs(step) < abs(sweep):  # no room for a point between: its start only
        return arc.evaluate(np.array([arc.s0]))[0]
    after_start, before_end = arc.evaluate(np.array([arc.s0 + step, arc.s1 - step]))[0]
    start_side = _off_extension(after_start, beside[0], True) <= _off_extension(before_end, beside[1], False)
    return np.vstack([arc.start, after_start if start_side else before_end])


def _off_extension(point: np.ndarray, curve: Curve, at_end: bool) -> float:
    """Distance (mm) of a point from a drawing's piece extended past a joint.

    An arc's circle; another piece's tangent line at its end (``at_end``) or its start.
    """
    if isinstance(curve, Arc):
        return abs(float(np.hypot(*(point - np.asarray(curve.center)))) - curve.radius)
    p, t = curve.evaluate(np.array([curve.s1 if at_end else curve.s0]))
    d = point - p[0]
    return abs(float(t[0, 0] * d[1] - t[0, 1] * d[0]))


def _joint_turns(curves: list[Curve]) -> np.ndarray:
    """(n,) float, rad: how far the tangent turns at the joint after each curve (the last: back to the first)."""
    ends = np.array([c.evaluate(np.array([c.s1]))[1][0] for c in curves])
    starts = np.array([c.evaluate(np.array([c.s0]))[1][0] for c in curves])
    following = np.roll(starts, -1, axis=0)
    return np.abs(np.arctan2(ends[:, 0] * following[:, 1] - ends[:, 1] * following[:, 0], np.einsum("ij,ij->i", ends, following)))


def _kinks(curves: list[Curve], corner_angle_deg: float) -> np.ndarray:
    """(n,) bool: the joint after each curve turns by more than :data:`SMOOTH_JOINT` and less than a corner."""
    turn = _joint_turns(curves)
    return (turn > SMOOTH_JOINT) & (turn < np.radians(corner_angle_deg))


def _polygonal(curves: list[Curve], corner_angle_deg: float) -> bool:
    """Tell whether a drawing is a polyline through points: straight lines meeting at kinks.

    Such a drawing (``rotor --dxf`` writes one) is read as its points even where curves are kept as
    drawn (the clearance): as drawn, the rack of a straight piece is a single point and each kink
    a corner's fan, which leave no flank to bring into contact (``clearance`` refused rotorcad's
    own male drawing naming ``--contact``, after 29 s and 1.6 GB).
    """
    straight = np.array([isinstance(c, Line) for c in curves])
    between_lines = straight & np.roll(straight, -1)
    return bool((_kinks(curves, corner_angle_deg) & between_lines)[:-1].any())


DRAWN_SPANS = 16
"""A drawing's spline of more polynomial pieces than this was drawn through points (a designed curve
needs a few), unless it carries its tangents (:func:`carries_tangents`)."""


def carries_tangents(spline: Spline) -> bool:
    """Tell whether a spline was made from a curve's points and tangents (a Hermite interpolant), not through points.

    Each interior knot of multiplicity degree - 1 or more (double knots of a cubic): the spline is
    C1 there and its tangent at the knot is free, given with the point (Piegl and Tiller, *The
    NURBS Book*, sec. 2.2 and eq. 3.9). ``export`` and ``rotor --dxf`` write such splines, one per
    exact piece of the outline, each knot a point of the exact curve with its exact tangent
    (de Boor, *A Practical Guide to Splines*, ch. IV); a spline that CAD draws through points
    (global interpolation, a control frame) has simple knots and is C2.
    """
    t, _, k = spline.knots
    lo, hi = sorted((spline.s0, spline.s1))
    inner = np.asarray(t, dtype=float)[k + 1 : len(t) - k - 1]
    inner = inner[(inner > lo) & (inner < hi)]
    if inner.size == 0 or k < 2:
        return False
    _, counts = np.unique(inner, return_counts=True)
    return bool(np.all(counts >= k - 1))


def hermite_accuracy(spline: Spline) -> float:
    """Estimate how far a spline that carries its tangents (:func:`carries_tangents`) lies from the curve it stands for (mm).

    Twice the largest distance, at the quarter points of its spans, between it and the clamped C2
    cubic interpolant of the same knot points with the same end tangents (scipy's
    ``make_interp_spline``): two interpolants of different form agree to the order of their errors
    (as :func:`rotorcad.measured.fit.tangent_spread` uses it). On the samples' export drawings this
    reads 0.15-0.85 µm where the exact outline lies 0.16-0.88 µm from them (``spline_deviation``).
    """
    from scipy.interpolate import BSpline, make_interp_spline

    t, (cx, cy), k = spline.knots
    lo, hi = sorted((spline.s0, spline.s1))
    b = BSpline(np.asarray(t, dtype=float), np.column_stack([cx, cy]), k)
    u = np.unique(np.clip(np.asarray(t, dtype=float), lo, hi))
    if len(u) < 3:
        return 0.0
    ends = [[(1, b(u[0], nu=1))], [(1, b(u[-1], nu=1))]]
    reference = make_interp_spline(u, b(u), k=3, bc_type=(ends[0], ends[1]))
    m = (u[:-1, None] + np.diff(u)[:, None] * np.array([0.25, 0.5, 0.75])).ravel()
    return 2.0 * float(np.hypot(*(b(m) - reference(m)).T).max())


def _drawn_through_points(spline: Spline) -> bool:
    """Tell whether a drawing's spline was drawn through points.

    More than :data:`DRAWN_SPANS` pieces and no tangents of its own (:func:`carries_tangents`).
    """
    return _knot_parameters(spline).size > DRAWN_SPANS + 1 and not carries_tangents(spline)


def _knot_parameters(spline: Spline) -> np.ndarray:
    """Return the spline's distinct knots within its range, in the direction of travel (both ends included)."""
    lo, hi = sorted((spline.s0, spline.s1))
    knots = np.unique(spline.knots[0])
    u = np.concatenate([[lo], knots[(knots > lo) & (knots < hi)], [hi]])
    return u if spline.s1 >= spline.s0 else u[::-1]


__all__ = [
    "ARCS_THROUGH_POINTS",
    "DRAWN_SPANS",
    "LAND_ANGLE",
    "LAND_SPREAD",
    "SMOOTH_JOINT",
    "as_given",
    "carries_tangents",
    "drawing_points",
    "hermite_accuracy",
    "own_frame",
    "profile_points",
]

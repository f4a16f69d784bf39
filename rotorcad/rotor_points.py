"""Rotor pairs from measured points: of the rack, of the male or of the female rotor.

The points (CONTRACT.md "Points files") are fitted with cubic splines (interpolating, or
smoothing with ``smoothing`` > 0), piecewise between sharp corners, so that tangents are exact. A
rotor's lobe is turned into its rack by inverse generation (Wu & Chi sec. 2, eqs. 4-8, in the
transverse section), and the pair is generated from that rack; the rotor given comes back as its
own conjugate's conjugate (a round trip that the tests check). Corner paths, its own and the
mate's (point-generated flanks, Rinder Fig. 1-4), are found and marked as in the families.
"""

from __future__ import annotations

import numpy as np

from rotorcad.curves import Arc, Curve, Line, Mapped, Spline, rotated, sample_curve
from rotorcad.envelope import Generated, from_rack_frame
from rotorcad.errors import DesignError
from rotorcad.geometry import rotate, wrap_angle
from rotorcad.inverse_rack import MEASURED_MIN_TURN, with_corner_fans
from rotorcad.measured_outline import accuracy, corners, lands, scatter, whole_outline
from rotorcad.roles import PieceRole, Side
from rotorcad.roots import bracket_root
from rotorcad.rotor_pair import RotorPair
from rotorcad.screw_rotors import RackPiece, ScrewRotors


def pair_from_rack_points(pair: RotorPair, points: np.ndarray, smoothing: float = 0.0) -> ScrewRotors:
    """Generate a pair from points of one rack period.

    Parameters
    ----------
    pair : RotorPair
        Dimensions of the pair.
    points : (n, 2) float array, mm
        One rack period in the rack frame of CONTRACT.md (x along the motion, y > 0 towards the
        female), in either direction.
    smoothing : float, mm²
        scipy's spline smoothing; 0 interpolates.

    Returns
    -------
    ScrewRotors
        The pair generated from the fitted rack (family ``"rack-points"``).

    Raises
    ------
    DesignError
        Points that do not span one rack period p = 2 pi r1w / z1 in x (within 0.1 %).
    """
    pts = np.asarray(points, dtype=float)
    if pts[-1, 0] < pts[0, 0]:
        pts = pts[::-1]
    span = pts[-1, 0] - pts[0, 0]
    if abs(span - pair.rack_period) > 1e-3 * pair.rack_period:
        raise DesignError("rack points", f"one rack period long in x ({pair.rack_period:.6g} mm)", f"{span:.6g} mm")
    spline = Spline.fit(from_rack_frame(pts, pair.male_pitch_radius), smoothing=smoothing)
    return ScrewRotors(pair, (RackPiece(spline, "flank", "flank"),), "rack-points")


def _smoothing(run: np.ndarray, sigma: float, smoothing: float | None) -> float:
    """Return scipy's smoothing value for a run of points.

    The user's value, or n sigma^2 from the estimated scatter (:mod:`rotorcad.measured_outline`); a
    run too short for a smoothing cubic (8 points or fewer) interpolates.
    """
    if smoothing is not None:
        return smoothing
    return len(run) * sigma**2 if len(run) > 8 else 0.0


def _facing_root_angle(whole: np.ndarray, teeth: int, facing: float) -> float:
    """Polar angle of the root that starts the lobe containing the polar angle ``facing``."""
    root = whole[np.argmin(np.hypot(*whole.T))]
    pitch = 2 * np.pi / teeth
    theta0 = np.arctan2(root[1], root[0])
    return float(theta0 + np.floor((facing - theta0) / pitch) * pitch)


def _lobe_spline(whole: np.ndarray, teeth: int, smoothing: float, facing: float) -> tuple[Spline, float, float]:
    """Fit a periodic spline to the whole outline and find the lobe facing the mate.

    Returns the spline and the parameters of the lobe between two consecutive roots that contains
    the polar angle ``facing`` (towards the mate, so that its contacts lie within half a turn of the
    mesh position).
    """
    spline = Spline.fit(whole, smoothing=smoothing, periodic=True)
    s = np.linspace(0.0, spline.s1, 20 * len(whole) + 1)
    p, _ = spline.evaluate(s)
    pitch = 2 * np.pi / teeth
    theta = _facing_root_angle(p, teeth, facing)

    s_a = _polar_crossing(spline, p, s, theta)
    s_b = _polar_crossing(spline, p, s, theta + pitch)
    if s_a is None or s_b is None:
        raise DesignError("points", "an outline that every ray from its centre crosses once", None)
    if s_b <= s_a:
        s_b += spline.s1
    return spline, s_a, s_b


def lobe_curve(pair: RotorPair, points: np.ndarray, rotor: str, smoothing: float | None = None) -> Curve:
    """Fit the spline of one lobe of the male or the female, the lobe facing the mate.

    Parameters
    ----------
    pair : RotorPair
        Tooth counts and centre distance (mm).
    points : (n, 2) float array, mm
        One lobe or the whole outline in the rotor's own frame.
    rotor : {"male", "female"}
        Which rotor the points are.
    smoothing : float, mm², optional
        scipy's spline smoothing; None estimates it from the points' scatter.

    Returns
    -------
    Curve
        The lobe from root to root, own frame, counter-clockwise.

    Raises
    ------
    DesignError
        An outline that a ray from its centre crosses more than once, or a wrong lobe count.
    """
    side = Side(rotor)
    teeth = side.pick(pair.male_teeth, pair.female_teeth)
    whole = whole_outline(points, teeth, f"{side.value} points")
    s_fit = _smoothing(whole, scatter(whole), smoothing)
    spline, s_a, s_b = _lobe_spline(whole, teeth, s_fit, side.pick(0.0, np.pi))
    if s_b > spline.s1:  # the lobe wraps past the spline's seam: shift the seam
        p, _ = spline.evaluate(np.linspace(s_a, s_b, 4000) % spline.s1)
        spline = Spline.fit(p, smoothing=0.0)
        s_a, s_b = 0.0, spline.s1
    return spline.trimmed(s_a, s_b)


def _polar_crossing(curve: Curve, points: np.ndarray, u: np.ndarray, theta: float) -> float | None:
    """Find the parameter where ``curve`` crosses the polar ray at ``theta`` counter-clockwise.

    ``points`` are the curve's samples at parameters ``u``; the crossing is bracketed between them
    and refined on the curve. Returns None when the samples do not cross the ray.
    """
    rel = wrap_angle(np.arctan2(points[:, 1], points[:, 0]) - theta)
    i = np.nonzero((rel[:-1] < 0) & (rel[1:] >= 0) & (np.abs(rel[:-1]) < np.pi / 2) & (np.abs(rel[1:]) < np.pi / 2))[0]
    if len(i) == 0:
        return None

    def f(v: float) -> float:
        q = curve.evaluate(v)[0][0]
        return float(wrap_angle(np.arctan2(q[1], q[0]) - theta))

    a, b = u[i[0]], u[i[0] + 1]
    root = bracket_root(f, (a, b), xtol=1e-13)
    return float(a) if root is None else root  # no sign change on the spline: the chord's crossing


def _runs_between_corners(whole: np.ndarray, edges: np.ndarray, points: np.ndarray) -> list[np.ndarray]:
    """Cut the outline at its corners.

    For each corner (on edge i, at a point) to the next: the corner's point, the outline's points in
    between and the next corner's point; points within 1e-6 mm of a corner point are left out (the
    corner is that point).
    """
    n = len(whole)
    ring = np.vstack([whole, whole])
    out = []
    for j, (i, c) in enumerate(zip(edges, points, strict=True)):
        i_next = edges[(j + 1) % len(edges)] + (n if j + 1 == len(edges) else 0)
        c_next = points[(j + 1) % len(edges)]
        inner = ring[i + 1 : i_next + 1]
        inner = inner[(np.hypot(*(inner - c).T) > 1e-6) & (np.hypot(*(inner - c_next).T) > 1e-6)]
        out.append(np.vstack([c, inner, c_next]))
    return out


def _refined_corners(
    whole: np.ndarray, edges: np.ndarray, points: np.ndarray, sigma: float, smoothing: float | None
) -> np.ndarray:
    """Locate the corners of scattered points where the splines beside each corner cross.

    The smoothing splines of the two runs beside a corner, extended past their ends, are crossed by
    Newton on both parameters: the chords' crossing is off by a sample spacing when the corner falls
    between scattered points, which moves the corner's path on the rack by as much. A crossing not
    found within two spacings keeps the chords' one.
    """
    n = len(whole)
    ring = np.vstack([whole, whole, whole])
    fits = []
    for j, i in enumerate(edges):
        i_next = edges[(j + 1) % len(edges)] + (n if j + 1 == len(edges) else 0)
        inner = ring[i + 1 : i_next + 1]
        fits.append(Spline.fit(inner, smoothing=_smoothing(inner, sigma, smoothing)) if len(inner) >= 4 else None)
    h = float(np.median(np.hypot(*np.diff(whole, axis=0).T)))
    out = np.array(points, dtype=float)
    for j in range(len(edges)):
        before, after = fits[j - 1], fits[j]  # the run ending at corner j, and the one starting there
        if before is None or after is None:
            continue
        with np.errstate(all="ignore"):  # a diverging Newton step is refused below, not reported
            p = _cross_ends(before, after, before.s1, after.s0)
        if p is not None and np.hypot(*(p - out[j])) < 2 * h:
            out[j] = p
    return out


def _cross_ends(before: Curve, after: Curve, u: float, v: float) -> np.ndarray | None:
    """Where two curves extended past their ends cross (Newton on both parameters from u, v)."""
    for _ in range(8):
        (pa,), (ta,) = before.frame(np.array([u]))
        (pb,), (tb,) = after.frame(np.array([v]))
        jac = np.column_stack([ta, -tb])
        if not np.all(np.isfinite(jac)) or abs(np.linalg.det(jac)) < 1e-6:
            return None
        du, dv = np.linalg.solve(jac, pb - pa)
        u, v = u + du, v + dv
    p, q = before.frame(np.array([u]))[0][0], after.frame(np.array([v]))[0][0]
    return p if np.all(np.isfinite(p)) and np.hypot(*(p - q)) < 1e-7 else None


def lobe_pieces(
    pair: RotorPair,
    points: np.ndarray | list[Curve],
    rotor: str,
    smoothing: float | None = None,
    corner_angle_deg: float = 30.0,
    label: str | None = None,
    drawn_as_points: bool = False,
) -> list[tuple[str, Curve]]:
    """Fit one lobe of the male or the female as pieces between the sharp corners of its points.

    A measured outline may have sharp corners (a female tip without rounding, a tip land cut by
    the rack's flat): a spline through one rings. The outline is fitted piecewise between corners
    (each piece a cubic spline with exact tangents; lands as exact arcs about the centre), and the
    corners stay corners (their fans of normals are added where racks are derived). An outline
    without corners is one periodic spline (:func:`lobe_curve`).

    Parameters
    ----------
    pair : RotorPair
        Tooth counts and centre distance (mm).
    points : (n, 2) float array, mm, or list of Curve
        One lobe or the whole outline in the rotor's own frame, either direction, any start;
        exact, measured (scatter of a few µm) or polygonal (boolean cutting, with scallops). Or
        the exact curves of a drawing, chained counter-clockwise (lines, arcs, splines), which are
        used as they are.
    rotor : {"male", "female"}
        Which rotor the points are.
    smoothing : float, mm², optional
        scipy's spline smoothing for every piece; None: n sigma^2 from the estimated scatter sigma
        (:func:`rotorcad.measured_outline.scatter`), 0 for exact points.
    corner_angle_deg : float, deg
        Turn above which a vertex is a sharp corner (:func:`rotorcad.measured_outline.corners`).
    label : str, optional
        How the points are named in errors (default "<rotor> points").
    drawn_as_points : bool
        Read a drawing that approximates the outline as the points it was drawn through
        (:func:`drawing_points`), as the rack generation needs; False (the clearance) uses its
        curves as drawn. A drawing of one groove or tooth is read as points either way.

    Returns
    -------
    list of (str, Curve)
        The lobe facing the mate, root to root, own frame, counter-clockwise, as named pieces
        (``"lobe part 1"``, ...; ``"flank"`` for one periodic spline).

    Raises
    ------
    DesignError
        An outline that a ray from its centre crosses more than once, or a wrong lobe count.
    """
    side = Side(rotor)
    rotor = side.value
    teeth = side.pick(pair.male_teeth, pair.female_teeth)
    label = label or f"{rotor} points"
    points = as_given(points, teeth, corner_angle_deg, drawn_as_points)
    if isinstance(points, list):
        return _lobe_from_curves(points, teeth, rotor, label)
    whole = whole_outline(points, teeth, label)
    sigma = scatter(whole) if smoothing is None else 0.0
    edges, corner_points = corners(whole, sigma, corner_angle_deg)
    if len(edges):
        if sigma > 0:
            corner_points = _refined_corners(whole, edges, corner_points, sigma, smoothing)
        runs = _runs_between_corners(whole, edges, corner_points)
    else:  # no corners: cut the ring in the middle of a land, if it has one
        found = lands(np.vstack([whole, whole[:1]]), sigma)
        if not found:
            return [("flank", lobe_curve(pair, whole, rotor, smoothing))]
        a, b, _ = found[0]
        start = (a + b) // 2
        ring = np.roll(whole, -start, axis=0)
        runs = [np.vstack([ring, ring[:1]])]
    fitted = [piece for run in runs for piece in _fit_run(run, sigma, smoothing)]
    return _cut_lobe(fitted, whole, teeth, rotor, label)


def _cut_lobe(
    fitted: list[tuple[Curve, np.ndarray, np.ndarray]], whole: np.ndarray, teeth: int, rotor: str, label: str
) -> list[tuple[str, Curve]]:
    """Cut the lobe facing the mate, root to root, out of the whole outline's curves.

    Each curve comes with its sample points and their parameters; the lobe is trimmed at the two
    roots' polar angles and its pieces are named ``"lobe part i"``.
    """
    theta = _facing_root_angle(whole, teeth, Side(rotor).pick(0.0, np.pi))

    def locate(th: float) -> tuple[int, float]:
        for k, (curve, pts, u) in enumerate(fitted):
            s = _polar_crossing(curve, pts, u, th)
            if s is not None:
                return k, s
        raise DesignError(label, "an outline that every ray from its centre crosses once", None)

    (k_a, s_a), (k_b, s_b) = locate(theta), locate(theta + 2 * np.pi / teeth)
    first, last = fitted[k_a][0], fitted[k_b][0]
    if k_a == k_b and (s_b - s_a) * first.direction > 0:
        curves = [first.trimmed(s_a, s_b)]
    else:
        curves = [first.trimmed(s_a, first.s1)]
        k = (k_a + 1) % len(fitted)
        while k != k_b:
            curves.append(fitted[k][0])
            k = (k + 1) % len(fitted)
        curves.append(last.trimmed(last.s0, s_b))
    return [(f"lobe part {i + 1}", c) for i, c in enumerate(curves) if abs(c.s1 - c.s0) > 1e-9]


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
        return np.vstack([sample_curve(c, tolerance)[1] for c in profile])
    return np.asarray(profile, dtype=float)


def as_given(
    points: np.ndarray | list[Curve], teeth: int, corner_angle_deg: float = 30.0, drawn_as_points: bool = True
) -> np.ndarray | list[Curve]:
    """Return a profile as it is to be fitted: a drawing's exact curves, or points.

    A drawing stays its curves when they are the outline's own (:func:`drawing_points` finds no
    approximation) and span one lobe or more; a drawing that approximates the outline is read as
    its points (with ``drawn_as_points``: the rack generation needs them), and one of a single
    groove or tooth (less than the lobe pitch) as points sampled at 0.1 µm chord, which
    :func:`rotorcad.measured_outline.whole_outline` patterns.

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
    pts = np.vstack([sample_curve(c, 1e-4)[1] for c in curves])
    ang = np.unwrap(np.arctan2(pts[:, 1], pts[:, 0]))
    if abs(ang[-1] - ang[0]) < 0.98 * 2 * np.pi / teeth:  # one groove or tooth: patterned as points
        return pts
    return curves


SMOOTH_JOINT = 1e-3
"""rad: consecutive curves of a drawing whose tangents differ by more than this (and less than a
corner's angle) meet at a kink: the drawing approximates the outline (a polyline, a chain of arcs
fitted to points) and is read as its points."""


def drawing_points(curves: list[Curve], corner_angle_deg: float = 30.0) -> np.ndarray | None:
    """Return the points of a drawing that approximates an outline, or None for an exact drawing.

    A drawing is read as the points it was drawn through when its curves meet at kinks (tangents
    turning by more than :data:`SMOOTH_JOINT` and less than ``corner_angle_deg``: a polyline, arcs
    fitted to points), or when it holds a spline of more than :data:`DRAWN_SPANS` polynomial pieces
    (a spline through points, as CAD and rotorcad's own export draw an outline): the rack of a
    straight piece would be a single point, a kink a gap, and a spline drawn across a sharp corner
    rings. The points are each line's start, each arc sampled to 0.1 µm chord (at least its
    start and middle, the bulge's point) and a spline's points at its knots; they are then
    fitted, smoothed and cut at corners as measured points are, to the accuracy they carry
    (:func:`points_accuracy`).

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
    drawn = [c for c in curves if isinstance(c, Spline) and _knot_parameters(c).size > DRAWN_SPANS + 1]
    if not kinks[:-1].any() and not drawn:  # the last joint closes a lobe (a corner or nothing)
        return None
    pts = []
    for c in curves:
        if isinstance(c, Spline):
            u = _knot_parameters(c)
            pts.append(c.evaluate(u[:-1])[0])
        elif isinstance(c, Line):
            pts.append(c.start[None, :])
        else:  # an arc to 0.1 um chord, at least its middle (a land stays a land of many points)
            pts.append(sample_curve(c, 1e-4, minimum=3)[1][:-1])
    return np.vstack(pts)


def _kinks(curves: list[Curve], corner_angle_deg: float) -> np.ndarray:
    """(n,) bool: the joint after each curve turns by more than :data:`SMOOTH_JOINT` and less than a corner."""
    ends = np.array([c.evaluate(np.array([c.s1]))[1][0] for c in curves])
    starts = np.array([c.evaluate(np.array([c.s0]))[1][0] for c in curves])
    following = np.roll(starts, -1, axis=0)
    turn = np.abs(np.arctan2(ends[:, 0] * following[:, 1] - ends[:, 1] * following[:, 0], np.einsum("ij,ij->i", ends, following)))
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
needs a few)."""


def _knot_parameters(spline: Spline) -> np.ndarray:
    """Return the spline's distinct knots within its range, in the direction of travel (both ends included)."""
    lo, hi = sorted((spline.s0, spline.s1))
    knots = np.unique(spline.knots[0])
    u = np.concatenate([[lo], knots[(knots > lo) & (knots < hi)], [hi]])
    return u if spline.s1 >= spline.s0 else u[::-1]


def _lobe_from_curves(curves: list[Curve], teeth: int, rotor: str, label: str) -> list[tuple[str, Curve]]:
    """Cut the lobe facing the mate from the exact curves of a drawing.

    The curves are one lobe (patterned here), or the whole outline, counter-clockwise
    (:func:`exports.dxf_profile.read_profile_dxf`): arcs stay arcs, splines stay the drawing's
    splines, and the lobe is cut from them at the roots.
    """
    samples = [sample_curve(c, 1e-4) for c in curves]
    pts = np.vstack([p for _, p, _ in samples])
    whole = whole_outline(pts, teeth, label)  # checks the lobe count or the span of one lobe
    ang = np.unwrap(np.arctan2(pts[:, 1], pts[:, 0]))
    pitch = 2 * np.pi / teeth
    if abs(ang[-1] - ang[0]) < 2 * np.pi - 0.5 * pitch:  # one lobe: pattern the curves
        curves = [rotated(c, k * pitch) for k in range(teeth) for c in curves]
        samples = [sample_curve(c, 1e-4) for c in curves]
    fitted = [(c, p, s) for c, (s, p, _) in zip(curves, samples, strict=True)]
    return _cut_lobe(fitted, whole, teeth, rotor, label)


def _fit_run(run: np.ndarray, sigma: float, smoothing: float | None) -> list[tuple[Curve, np.ndarray, np.ndarray]]:
    """Fit a run of outline points between corners as curves.

    Every land (an arc about the rotor's centre within the scatter,
    :func:`rotorcad.measured_outline.lands`) becomes that exact arc, whose normals are radial, so that
    its rack image is the exact flat at the tip or root line; the rest cubic splines. Each curve comes
    with sample points and their parameters (for locating polar crossings).
    """
    out: list[tuple[Curve, np.ndarray, np.ndarray]] = []

    def spline(i0: int, i1: int, lead_in: int, lead_out: int) -> None:
        """Fit the spline of run[i0 : i1 + 1] and append it.

        It is fitted with ``lead_in`` / ``lead_out`` points of the neighbouring lands (so that its ends
        see the land it runs into) and trimmed back.
        """
        if i1 - i0 < 1 or np.hypot(*(run[i1] - run[i0])) <= 1e-9:
            return
        j0, j1 = max(i0 - lead_in, 0), min(i1 + lead_out, len(run) - 1)
        part = run[j0 : j1 + 1]
        u = np.concatenate([[0.0], np.cumsum(np.hypot(*np.diff(part, axis=0).T))])
        curve = Spline.fit(part, smoothing=_smoothing(part, sigma, smoothing)).trimmed(u[i0 - j0], u[i1 - j0])
        out.append((curve, run[i0 : i1 + 1], u[i0 - j0 : i1 - j0 + 1]))

    pos, lead = 0, 0
    for a, b, radius in lands(run, sigma):
        spline(pos, a, lead, 3)
        t0 = float(np.arctan2(run[a, 1], run[a, 0]))
        t1 = t0 + float(np.unwrap(np.arctan2(run[a : b + 1, 1], run[a : b + 1, 0]))[-1] - t0)
        arc = Arc((0.0, 0.0), radius, t0, t1)
        u = np.linspace(t0, t1, b - a + 1)
        out.append((arc, arc.evaluate(u)[0], u))
        pos, lead = b, 3
    spline(pos, len(run) - 1, lead, 0)
    return out


def _mate_corner_runs(
    rack_curve: Curve, mate: Generated, threshold: float = 0.02, tolerance: float = 1e-4
) -> list[tuple[float, float, bool]]:
    """Split a rack curve derived from one rotor into flank-generating parts and the mate's corner paths.

    Along a corner path the mate's generated point stands still: it is the path of a sharp corner of
    the mate (its tip corner sweeping this rotor's point-generated flank), which the mate receives as
    that corner only. Returns (s0, s1, is_corner_path) along the travel.

    Classification (positions only, no tangents): over a stencil of 1/200 of the curve the mate's
    point moves less than ``threshold`` times the rack point; a part stalled so over at least 1/100
    of the curve is a corner path. Its ends are where the mate's point leaves that corner by more
    than ``tolerance`` (mm), found by bisection.
    """
    span = rack_curve.s1 - rack_curve.s0
    s = rack_curve.s0 + span * np.linspace(0.0, 1.0, 801)
    pr, _ = rack_curve.evaluate(s)
    pm, _ = mate.evaluate(s)
    k = 4  # stencil of 4 samples either side (1/200 of the curve)
    dr = np.hypot(*(pr[2 * k :] - pr[: -2 * k]).T)
    dm = np.hypot(*(pm[2 * k :] - pm[: -2 * k]).T)
    with np.errstate(divide="ignore", invalid="ignore"):
        ratio = np.where(dr > 0, dm / dr, np.inf)
    stalled = np.zeros(len(s), dtype=bool)
    stalled[k:-k] = np.nan_to_num(ratio, nan=np.inf) < threshold
    edges = np.flatnonzero(np.diff(stalled.astype(int))) + 1
    bounds = [0, *edges.tolist(), len(s)]
    runs = [(bounds[i], bounds[i + 1]) for i in range(len(bounds) - 1) if stalled[bounds[i]] and bounds[i + 1] - bounds[i] >= 8]
    if not runs:
        return [(rack_curve.s0, rack_curve.s1, False)]

    def leave(corner: np.ndarray, inside: float, outside: float) -> float:
        for _ in range(30):
            mid = 0.5 * (inside + outside)
            q = mate.evaluate(np.array([mid]))[0][0]
            if np.all(np.isfinite(q)) and np.hypot(*(q - corner)) <= tolerance:
                inside = mid
            else:
                outside = mid
        return float(0.5 * (inside + outside))

    out, last = [], rack_curve.s0
    for i, j in runs:
        # the corner is where most of the run's mate points lie; the path extends exactly as far
        # as the mate's point stays within the tolerance of it (a slowly moving flank next to it
        # may pass the stall test without being the corner)
        corner = np.nanmedian(pm[i:j], axis=0)
        near = np.nan_to_num(np.hypot(*(pm - corner).T), nan=np.inf) <= tolerance
        centre = i + int(np.argmin(np.nan_to_num(np.hypot(*(pm[i:j] - corner).T), nan=np.inf)))
        far = np.flatnonzero(~near)
        lo = int(far[far < centre].max(initial=-1)) + 1  # the run of near samples around the centre
        hi = int(far[far > centre].min(initial=len(s))) - 1
        a = rack_curve.s0 if lo == 0 else leave(corner, s[lo], s[lo - 1])
        b = rack_curve.s1 if hi == len(s) - 1 else leave(corner, s[hi], s[hi + 1])
        if (b - a) * span <= 0:
            continue
        if (a - last) * span > 0:  # along the travel, which may run to smaller parameters
            out.append((last, a, False))
        out.append((a, b, True))
        last = b
    if last != rack_curve.s1:
        out.append((last, rack_curve.s1, False))
    parts = []
    for a, b, c in out:
        if abs(b - a) <= 1e-12 * abs(span):
            continue
        tiny = False
        if not c:  # a flank part beside a corner path that gives the mate under 10 um of flank
            ends, _ = mate.evaluate(np.array([a, b]))  # is noise near the path's end: part of it
            tiny = bool(np.all(np.isfinite(ends)) and np.hypot(*(ends[1] - ends[0])) < 10 * tolerance)
        if parts and ((c and (parts[-1][2] or parts[-1][3])) or (parts[-1][2] and tiny)):
            parts[-1] = [parts[-1][0], b, True, False]
        else:
            parts.append([a, b, c, tiny])
    return [(a, b, c) for a, b, c, _ in parts]


def pair_from_rotor_points(
    pair: RotorPair, points: np.ndarray | list[Curve], rotor: str, smoothing: float | None = None, label: str | None = None
) -> ScrewRotors:
    """Generate a pair from points (or curves) of the male or the female rotor.

    The lobe is fitted piecewise between its sharp corners (:func:`lobe_pieces`); each piece and
    each corner's fan of normals gives its part of the rack by inverse generation (Wu & Chi sec. 2,
    eqs. 4-8). A corner's fan is the path of that corner ("male point" / "female point"), and so is
    every part of the rack along which the mate's generated point stands still (the mate's tip
    corner, whose point-generated flank this rotor carries): the mate receives such parts as its
    corner, exactly as in the profile families.

    Parameters
    ----------
    pair : RotorPair
        Dimensions of the pair.
    points : (n, 2) float array, mm, or list of Curve
        One lobe or the whole outline in the rotor's own frame (as for :func:`lobe_pieces`).
    rotor : {"male", "female"}
        Which rotor the points are.
    smoothing : float, mm², optional
        scipy's spline smoothing; None estimates it from the scatter.
    label : str, optional
        How the points are named in errors.

    Returns
    -------
    ScrewRotors
        The pair generated from the derived rack (family ``"male-points"`` or
        ``"female-points"``), with the share of the lobe that has no rack point in ``rack_loss``.

    Raises
    ------
    DesignError
        Points that do not make a lobe, or more than 2 % of the lobe without a rack point (its
        normal misses the pitch circle).
    """
    mesh = pair.mesh
    depth = (-pair.male_dedendum - 1e-6, pair.male_addendum + 1e-6)  # the rack lies between these
    pieces = lobe_pieces(pair, points, rotor, smoothing, label=label, drawn_as_points=True)
    side = Side(rotor)
    acc = max(points_accuracy(pair, points, rotor, label), fit_residual(pair, points, pieces, rotor))
    rotor = side.value
    if side is Side.MALE:
        body, mate_body, centre, teeth = mesh.male, mesh.female, np.zeros(2), pair.male_teeth
    else:
        shift = (pair.center_distance, 0.0)
        pieces = [(name, Mapped(curve, ((1.0, 0.0), (0.0, 1.0)), shift)) for name, curve in pieces]
        body, mate_body, centre, teeth = mesh.female, mesh.male, np.array(shift), pair.female_teeth
    own, other = PieceRole.corner_path_of(side), PieceRole.corner_path_of(side.other)
    parts: list[list[RackPiece]] = []
    lost, total = 0, 0
    for _name, curve in with_corner_fans(pieces, centre, 2 * np.pi / teeth, MEASURED_MIN_TURN):
        gen = Generated(curve, body, mesh.rack, limits=depth)
        rack_curve = gen.reversed() if side is Side.MALE else gen  # travelled in +y (the rack's +x)
        ok = np.isfinite(rack_curve.evaluate(np.linspace(rack_curve.s0, rack_curve.s1, 400))[0]).all(axis=1)
        lost, total = lost + int((~ok).sum()), total + len(ok)
        if curve.is_corner():
            parts.append([RackPiece(rack_curve, f"{rotor} tip corner", f"{rotor} tip corner", kind=own)])
            continue
        mate = Generated(rack_curve, mesh.rack, mate_body)
        runs = _mate_corner_runs(rack_curve, mate, tolerance=1e-4)
        parts.append(
            [RackPiece(rack_curve.trimmed(a, b), "flank", "flank", kind=other if c else PieceRole.CURVE) for a, b, c in runs]
        )
    # the male's counter-clockwise pieces follow the rack's travel, the female's run against it
    rack = [p for group in (parts if side is Side.MALE else reversed(parts)) for p in group]
    lost_share = 100.0 * lost / max(total, 1)
    if lost_share > 2.0:  # a few points at sharp corners may miss their pitch circle; more is not a rotor
        raise DesignError(
            f"{rotor} points",
            "a profile whose every normal meets its pitch circle (it has a rack)",
            None,
            f"{lost_share:.1f} % of the lobe has no rack point",
        )
    return ScrewRotors(pair, tuple(rack), f"{rotor}-points", rack_loss=lost_share, accuracy=acc)


def points_accuracy(pair: RotorPair, points: np.ndarray | list[Curve], rotor: str, label: str | None = None) -> float:
    """Estimate the accuracy of a rotor profile given by points or by a drawing's curves (mm).

    :func:`rotorcad.measured_outline.accuracy` of the whole outline: twice the estimated scatter, or
    the sagitta of the chords between the points, whichever is larger. A drawing's splines are
    judged by the points at their knots (what they were drawn through); lines and arcs are exact
    (1e-9 mm: given, not designed).
    """
    side = Side(rotor)
    points = as_given(points, side.pick(pair.male_teeth, pair.female_teeth))
    if isinstance(points, list):
        # a drawing's splines are as accurate as the points they were drawn through: their knots
        knots = [c.evaluate(np.unique(np.clip(c.knots[0], *sorted((c.s0, c.s1)))))[0] for c in points if isinstance(c, Spline)]
        pts = np.vstack(knots) if knots else np.zeros((0, 2))
        return max(accuracy(pts, 0.0), 1e-9) if len(pts) >= 8 else 1e-9
    whole = whole_outline(points, side.pick(pair.male_teeth, pair.female_teeth), label or f"{side.value} points")
    return accuracy(whole, scatter(whole))


def fit_residual(pair: RotorPair, points: np.ndarray | list[Curve], pieces: list[tuple[str, Curve]], rotor: str) -> float:
    """Return how far the fitted lobe leaves the given points, mm (90th percentile; 0 for exact curves).

    The distance of every point of the whole outline from the fitted lobe patterned around the
    rotor (sampled to 0.1 µm chord): the smoothing the user chose (``--smoothing``) or the one
    estimated from the scatter lets the fit leave the points, and the verdicts are judged to that.

    Parameters
    ----------
    pair : RotorPair
        Tooth counts.
    points : (n, 2) float array or list of Curve, mm
        The profile as given.
    pieces : list of (str, Curve)
        The fitted lobe (:func:`lobe_pieces`), own frame.
    rotor : {"male", "female"}
        Which rotor.
    """
    side = Side(rotor)
    teeth = side.pick(pair.male_teeth, pair.female_teeth)
    given = as_given(points, teeth)
    if isinstance(given, list):
        return 0.0
    import shapely  # here: the points path only

    whole = whole_outline(given, teeth, f"{side.value} points")
    lobe = np.vstack([sample_curve(c, 1e-4)[1] for _, c in pieces])
    line = shapely.MultiLineString([rotate(lobe, k * 2 * np.pi / teeth) for k in range(teeth)])
    gaps = shapely.distance(shapely.points(whole), line)
    return float(np.quantile(gaps, 0.9))

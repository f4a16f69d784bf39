"""The fit of a measured or drawn rotor outline: one lobe as curves with exact tangents.

The second stage of the measured-outline pipeline (:mod:`rotorcad.measured`). The whole outline
(:mod:`rotorcad.measured.outline`) is fitted with cubic splines (interpolating, or smoothing with
n sigma^2 from the estimated scatter), piecewise between its sharp corners, lands as exact arcs
about the centre, so that tangents are exact; the lobe facing the mate is cut from it at two roots.
Calls go to :mod:`rotorcad.measured.outline` only.
"""

from __future__ import annotations

import numpy as np

from rotorcad.curves import Arc, Curve, Spline, rotated, sample_curve
from rotorcad.errors import DesignError
from rotorcad.geometry import distance_to_polylines, rotate, wrap_angle
from rotorcad.measured.corner_fits import Smoothing, _refined_corners, _smoothing
from rotorcad.measured.outline import UNEVEN_SPACING, Outline, corners, lands, raw_scatter, read_outline, scatter, whole_outline
from rotorcad.measured.rack_pieces import step_splines
from rotorcad.measured.stepped_spline import stepped_ring_fit
from rotorcad.roles import Side
from rotorcad.roots import bracket_root
from rotorcad.rotor_pair import RotorPair


def close_smoothing(count: int, sigma: float) -> float:
    """Return the smoothing (n - sqrt(2 n)) sigma^2 of ``count`` points of scatter ``sigma`` (mm²).

    The lower end of the range in which the residual sum of squares of n points of standard deviation
    sigma falls (n +- sqrt(2 n) sigma^2: Dierckx, *Curve and Surface Fitting with Splines*, 1993, sec.
    5.2.4; scipy's ``splrep``): the closer fit, which follows a flank's curvature beside a root
    rounding that n sigma^2 smooths over. The clearance's rule (``rotorcad clearance`` without
    ``--smoothing``): the 5/6 arc-flank pair at 300 points a lobe with 2 um scatter, seeds 1-3, the
    contact zone 5.71 / 2.53 / 4.29 um off the brute force with n sigma^2, 4.28 / 2.30 / 3.40 um with it.
    Pass it as ``smoothing`` to :func:`lobe_pieces`.
    """
    return max(count - np.sqrt(2.0 * count), 0.0) * sigma**2


CURVATURE_NOISE = 2e-3
"""1/mm: the curvature error, from the residual error of points taken as exact, above which their
splines are least-squares cubics (:func:`fine_knot_spacing`). The narrow-tip male resampled evenly
from its outline drawn to a 0.01 um chord, interpolated: 1.9e-4 /mm at 300 a lobe (the design's
verdicts), 5.0e-2 at 4000 (the sealing meshline 72.6 mm for 63.3); from a 1 pm chord the design's.
The 4/6 female's CSV (0.046 mm apart: 7e-4 /mm) stays interpolated (knots 0.25 mm apart: its hob
rack 23.79 deg for 23.87; the N-rack male's 0.67 mm tip rounding a cusp, none at 0.08 mm)."""


KNOT_SPACING = 0.25
"""mm: the widest knot spacing of :func:`fine_knot_spacing` (the evenly spaced points of the samples'
males at 300 a lobe, 0.26-0.32 mm apart, read the design's verdicts through interpolating cubics)."""


def fine_knot_spacing(whole: np.ndarray) -> float | None:
    """Return the knot spacing of least-squares cubics through dense points taken as exact, mm (None: interpolate).

    Points whose scatter is below :data:`rotorcad.measured.outline.SCATTER_FLOOR` are interpolated,
    yet still carry an error e (the chords of the polyline they were resampled from, their decimals):
    the curvature of a cubic through points spaced h apart then errs by about 2 sqrt(6) e / h^2 (the
    second difference of independent errors over h^2), which grows as the points get denser (e = 10
    nm: 2e-4 /mm at h = 0.3 mm, 5e-2 /mm at h = 0.023 mm, more than the flank's own curvature), and
    the meshing analysis, which follows the curvature, reads other defects. Where that exceeds
    :data:`CURVATURE_NOISE`, the splines are least-squares cubics with knots evenly spaced in chord
    length (Dierckx, *Curve and Surface Fitting with Splines*, 1993, sec. 4.1) at the spacing whose
    error is that bound (two point spacings at least, :data:`KNOT_SPACING` at most): what they
    resolve is then a length, not a point count. e is estimated without a floor
    (:func:`rotorcad.measured.outline.raw_scatter`) from evenly spaced points only (a CMM's scan;
    the third differences of uneven ones read their spacing, :data:`rotorcad.measured.outline.UNEVEN_SPACING`).

    Parameters
    ----------
    whole : (n, 2) float array, mm
        The closed outline of points taken as exact.

    Returns
    -------
    float or None, mm
        The knot spacing; None where the points' own spacing keeps the curvature's error within bound.
    """
    step = np.hypot(*np.diff(whole, axis=0).T) if len(whole) >= 64 else np.zeros(1)
    spacing, uneven = float(np.median(step)), np.quantile(step, 0.9) > UNEVEN_SPACING * np.quantile(step, 0.1)
    if spacing <= 0 or uneven or 2.0 * spacing > KNOT_SPACING:  # uneven: a polyline's exact vertices
        return None
    gain = 2.0 * np.sqrt(6.0) * raw_scatter(whole)
    if gain / spacing**2 <= CURVATURE_NOISE:
        return None
    return min(max(float(np.sqrt(gain / CURVATURE_NOISE)), 2.0 * spacing), KNOT_SPACING)


def _least_squares_spline(part: np.ndarray, u: np.ndarray, knot_spacing: float) -> Spline:
    """Fit the least-squares cubic of points ``part`` (n, 2) at chord lengths ``u``, knots about ``knot_spacing`` apart (mm).

    Interior knots evenly spaced, two points a span at least (Schoenberg-Whitney), the ends' fourfold (Dierckx sec. 4.1).
    """
    from scipy.interpolate import make_lsq_spline  # scipy.interpolate only for a spline

    keep = np.concatenate([[True], np.diff(u) > 0.0])
    part, u = part[keep], u[keep]
    spans = max(int(np.floor(u[-1] / knot_spacing)), 1)
    if len(part) < 2 * spans + 4:
        return Spline.fit(part)
    inner = np.linspace(0.0, u[-1], spans + 1)[1:-1]
    t = np.r_[[0.0] * 4, inner, [u[-1]] * 4]
    bs = make_lsq_spline(u, part, t, k=3)
    return Spline(knots=(bs.t, (bs.c[:, 0], bs.c[:, 1]), 3), s0=0.0, s1=float(u[-1]))


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


def lobe_curve(pair: RotorPair, points: np.ndarray, rotor: Side, smoothing: Smoothing = None) -> Curve:
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
    side = Side(rotor)  # "male" / "female" from a script reads as the rotor
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


ROUNDING_SHARE = 0.1
"""A convex turn across one edge of sparse points is a rounding, not a sharp corner, when a vertex
beside the edge's two turns by more than this share of it (:func:`_resolved_corners`)."""


def _corner_turns(whole: np.ndarray, i: np.ndarray, sigma: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Return the turns about each corner's edge and what the scatter allows there.

    Parameters
    ----------
    whole : (n, 2) float array, mm
        The closed outline.
    i : (m,) int array
        Each corner's edge (:func:`rotorcad.measured.outline.corners`).
    sigma : float, mm
        The points' scatter.

    Returns
    -------
    four : (4, m) float array, rad
        The signed turns (counter-clockwise: convex > 0) at the vertex before the edge, the edge's two and the
        vertex after it.
    single : (m,) bool array
        Whether each chord beside the edge spans one edge (the points sparser than the chords' reach).
    noise : (m,) float array, rad
        Three standard deviations of a vertex's turn from the scatter, sqrt(6) sigma / h.
    """
    n = len(whole)
    d = np.roll(whole, -1, axis=0) - whole
    step = np.hypot(*d.T)
    heading = np.arctan2(d[:, 1], d[:, 0])
    vertex_turn = wrap_angle(heading - np.roll(heading, 1))
    four = np.stack([vertex_turn[(i + k) % n] for k in (-1, 0, 1, 2)])
    reach = min(40.0 * sigma, 0.1) if sigma > 0 else 0.0
    single = (step[(i - 1) % n] >= reach) & (step[(i + 1) % n] >= reach)
    noise = 3.0 * np.sqrt(6.0) * sigma / np.maximum(np.minimum(step[(i - 1) % n], step[(i + 1) % n]), 1e-12)
    return four, single, noise


def _resolved_corners(whole: np.ndarray, edges: np.ndarray, points: np.ndarray, sigma: float) -> tuple[np.ndarray, np.ndarray]:
    """Drop the corners of sparse points that are tip roundings the points step over.

    Points about a spacing apart on a rounding of radius rho turn by h / rho at every vertex: a
    rounding of 2 mm at 80 points a lobe (h = 1 mm, the N-rack female's tip) turns by 22 deg at each of
    its three vertices, 44 deg across the edge between two of them, and read as a sharp corner (its
    fan of normals sent the female's tip flanks to corner paths, half the contact line of the
    N-rack sample out of the contact zone). A sharp corner turns at the edge's two vertices alone:
    the vertices beside them turn by the flanks' curvature over a spacing (the narrow-tip male's tip
    at 80 a lobe: 2 %, the independent pairs' tips beside their lands: under 5 % of the corner). The
    rule :func:`rotorcad.measured.outline.corners` applies to concave turns, applied to convex ones:
    where each chord of the turn spans one edge (the points sparser than the chords' reach), a
    corner whose vertices beside it turn by more than :data:`ROUNDING_SHARE` of its turn, and by more than
    three standard deviations of a vertex's turn from the scatter (sqrt(6) sigma / h), is a rounding (the spline runs
    through it): the 4/6 female's sharp tips at 2000 points a lobe with 1 um (seeds 3-5) were roundings of noise.

    Parameters
    ----------
    whole : (n, 2) float array, mm
        The closed outline.
    edges : (m,) int array
        Each corner's edge (:func:`rotorcad.measured.outline.corners`).
    points : (m, 2) float array, mm
        Each corner's point.
    sigma : float, mm
        The points' scatter.

    Returns
    -------
    edges, points
        The corners kept.
    """
    if not len(edges):
        return edges, points
    i = np.asarray(edges)
    four, single, noise = _corner_turns(whole, i, sigma)
    turn = four[1] + four[2]  # the edge's turn between its one-edge chords
    beside = np.maximum(np.abs(four[0]), np.abs(four[3]))
    rounding = single & (turn > 0) & (beside > np.maximum(ROUNDING_SHARE * np.abs(turn), noise))
    return i[~rounding], np.asarray(points)[~rounding]


LONG_ROUNDING = 2.25
"""A convex turn across one edge of sparse points is a rounding the points resolve, not a sharp corner,
when the four vertices about the edge turn by more than this many times the larger of the edge's two
(:func:`_long_roundings`). That ratio measures the rounding's length in spacings: a circle between two
lines at 40-90 deg, its points at 20 phases of the spacing, gave 1.14-2.00 up to one spacing long,
1.90-2.24 at 1.9, 2.10-2.34 at 2.1, 2.47-2.58 at 2.5 and 2.88-3.00 at 3; a sharp corner between two
points 2.0 at most, plus the flanks' turn at the vertices beside it (under 5 % of the corner each on
the samples, :func:`_resolved_corners`)."""


def _long_roundings(whole: np.ndarray, edges: np.ndarray, points: np.ndarray, sigma: float) -> tuple[np.ndarray, np.ndarray]:
    """Drop the corners of sparse points that are roundings longer than two point spacings.

    Points h apart on a rounding of radius rho turn by h / rho at each vertex on it, and the turns of
    the vertices about the rounding add up to its whole turn: their sum over the largest one is about
    the rounding's length in spacings (:data:`LONG_ROUNDING`). A rounding more than two spacings long has
    three points on it, the fewest that fix a circle (:mod:`rotorcad.meshing.undecided`), and the spline
    through them follows it. Read as a corner (two of its vertices turn by more than the corner angle
    together) its fan of normals made a tip-corner cusp the design does not have: the rack-involute
    female's driving tip rounding (2.5 mm radius, 2.64 mm long) at 80 points a lobe, 1.06 mm apart, 17-25
    deg at three vertices, and the N-rack female's sealing tip circle (4.04 mm long) 0.8 mm apart, 22 deg
    at four or five (as 80 exact points a lobe it was refused: 5 % of its lobe without a rack point).
    A turn held by two points (a sharp corner between them, or a rounding shorter than 2h: the same
    input) stays a corner, as :func:`lobe_pieces` reads it for the racks; so does one whose vertices
    beside it turn within the scatter's three standard deviations (sqrt(6) sigma / h).

    Parameters
    ----------
    whole : (n, 2) float array, mm
        The closed outline.
    edges : (m,) int array
        Each corner's edge (:func:`rotorcad.measured.outline.corners`).
    points : (m, 2) float array, mm
        Each corner's point.
    sigma : float, mm
        The points' scatter.

    Returns
    -------
    edges, points
        The corners kept.
    """
    if not len(edges):
        return edges, points
    i = np.asarray(edges)
    four, single, noise = _corner_turns(whole, i, sigma)
    top = np.maximum(four[1], four[2])
    spread = np.maximum(four[0], four[3]) > noise
    rounding = single & (top > 0) & spread & (four.sum(axis=0) > LONG_ROUNDING * top)
    return i[~rounding], np.asarray(points)[~rounding]


def corner_uncertainty(whole: np.ndarray, sigma: float, corner_angle_deg: float = 30.0) -> float:
    """Return how far a sharp corner of the points may lie from where it is found, mm.

    A corner between two points (the corner's edge, :func:`rotorcad.measured.outline.corners`) is
    found where the chords (or fits) beside it cross; the outline between the two points is known
    only to lie in the triangle of the edge and that crossing: a sharp corner at the crossing, or a
    rounding shorter than the spacing anywhere inside (the N-rack male's 1.04 mm tip rounding at 80
    points a lobe, 1 mm apart, read as a corner whose path passes its mate 30 um nearer than the
    rounding). The bound is the triangle's height over the edge, the largest over the corners kept
    by the fit (:func:`_resolved_corners`); 0 for a corner on a point (exact points of a sharp
    corner) and for an outline without corners.

    Parameters
    ----------
    whole : (n, 2) float array, mm
        The closed outline.
    sigma : float, mm
        Its scatter (0 for exact points).
    corner_angle_deg : float, deg
        Turn above which a vertex is a sharp corner.

    Returns
    -------
    float, mm
    """
    edges, points = _resolved_corners(whole, *corners(whole, sigma, corner_angle_deg), sigma)
    if not len(edges):
        return 0.0
    a, b = whole[edges], whole[(edges + 1) % len(whole)]
    chord = b - a
    height = np.abs(chord[:, 0] * (points - a)[:, 1] - chord[:, 1] * (points - a)[:, 0]) / np.maximum(np.hypot(*chord.T), 1e-300)
    return float(height.max())


def curvature_jump(whole: np.ndarray, sigma: float, corner_angle_deg: float = 30.0) -> float:
    """Return the largest jump of the outline's curvature between neighbouring points, 1/mm, corners left out.

    The curvature at each point is its vertex's turn over the mean of its two spacings; the jump the
    difference between neighbours. Where a rounding meets a flank the curvature jumps, and a cubic
    through points h apart misses the outline there by a share of h^2 dk (the fit's own error,
    :func:`rotorcad.clearance_accuracy.estimated_accuracy`). Points within two of a sharp corner's
    edge (:func:`_resolved_corners`) are left out (a corner is no curvature). Scatter adds about
    4 sigma / h^2 to each curvature: h^2 dk then by 4 sigma at most, a share of the scatter's own term.

    Parameters
    ----------
    whole : (n, 2) float array, mm
        The closed outline.
    sigma : float, mm
        Its scatter (0 for exact points).
    corner_angle_deg : float, deg
        Turn above which a vertex is a sharp corner.

    Returns
    -------
    float, 1/mm
    """
    n = len(whole)
    d = np.roll(whole, -1, axis=0) - whole
    step = np.maximum(np.hypot(*d.T), 1e-300)
    heading = np.arctan2(d[:, 1], d[:, 0])
    kappa = wrap_angle(heading - np.roll(heading, 1)) / (0.5 * (step + np.roll(step, 1)))
    jump = np.abs(kappa - np.roll(kappa, 1))  # between points i - 1 and i
    edges, _ = _resolved_corners(whole, *corners(whole, sigma, corner_angle_deg), sigma)
    near = np.zeros(n, dtype=bool)
    for off in range(-2, 4):
        near[(np.asarray(edges, dtype=int) + off) % n] = True
    return float(jump[~near].max()) if (~near).any() else 0.0


def _runs_between_corners(whole: np.ndarray, edges: np.ndarray, points: np.ndarray, sigma: float = 0.0) -> list[np.ndarray]:
    """Cut the outline at its corners.

    For each corner (on edge i, at a point) to the next: the corner's point, the outline's points in
    between and the next corner's point; points within 1e-6 mm (of scattered points: 40 sigma, the
    chord over which :func:`rotorcad.measured.outline.corners` judges a turn) of a corner point are
    left out (the corner is that point). A scattered point 1 µm from the corner found between the
    points bent the spline's end by 100 deg within 0.3 µm (the SRM-B male's tip corner at 1 µm of
    scatter), one 15 µm from it by 45 deg (the narrow-tip male's root), and that corner's fan of
    normals by as much.
    """
    near = max(1e-6, 40.0 * sigma)
    n = len(whole)
    ring = np.vstack([whole, whole])
    out = []
    for j, (i, c) in enumerate(zip(edges, points, strict=True)):
        i_next = edges[(j + 1) % len(edges)] + (n if j + 1 == len(edges) else 0)
        c_next = points[(j + 1) % len(edges)]
        inner = ring[i + 1 : i_next + 1]
        inner = inner[(np.hypot(*(inner - c).T) > near) & (np.hypot(*(inner - c_next).T) > near)]
        out.append(np.vstack([c, inner, c_next]))
    return out


def lobe_pieces(
    pair: RotorPair,
    points: np.ndarray | list[Curve] | Outline,
    rotor: Side | str,
    smoothing: Smoothing = None,
    corner_angle_deg: float = 30.0,
    label: str | None = None,
    drawn_as_points: bool = False,
    roundings: bool = False,
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
    points : (n, 2) float array, mm, list of Curve, or Outline
        One lobe or the whole outline in the rotor's own frame, either direction, any start
        (or the profile read already, :func:`rotorcad.measured.outline.read_outline`);
        exact, measured (scatter of a few µm) or polygonal (boolean cutting, with scallops). Or
        the exact curves of a drawing, chained counter-clockwise (lines, arcs, splines), which are
        used as they are.
    rotor : {"male", "female"}
        Which rotor the points are.
    smoothing : float, mm², or callable, optional
        scipy's spline smoothing for every piece, or its rule of a piece's point count and the scatter
        (:func:`close_smoothing`); None: n sigma^2 from the estimated scatter sigma
        (:func:`rotorcad.measured.outline.scatter`), 0 for exact points.
    corner_angle_deg : float, deg
        Turn above which a vertex is a sharp corner (:func:`rotorcad.measured.outline.corners`).
    label : str, optional
        How the points are named in errors (default "<rotor> points").
    drawn_as_points : bool
        Read a drawing that approximates the outline as the points it was drawn through
        (:func:`drawing_points`), as the rack generation needs; False (the clearance) uses its
        curves as drawn. A drawing of one groove or tooth is read as points either way.
    roundings : bool
        Read a corner of sparse points that the vertices beside it share as a rounding the points
        step over (:func:`_resolved_corners`): the clearance's reading (its zones: no corner paths
        on a rounded tip; a ring's curvature steps between sparse points get knots, :func:`stepped_ring_fit`). False
        keeps it a corner, whose fan of normals gives the rack of a small rounding closer (the 4/6 independent
        female's 1.5 mm root roundings from scattered points: its rack 1.2 um off the generating one as corners),
        unless it is a rounding more than two spacings long, which the points resolve (:func:`_long_roundings`).

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
    side = Side(rotor)  # "male" / "female" from a script reads as the rotor
    rotor = side.value
    teeth = side.pick(pair.male_teeth, pair.female_teeth)
    label = label or f"{rotor} points"
    outline = read_outline(points, teeth, label, corner_angle_deg, drawn_as_points)  # read once (or already)
    points = outline.given
    if isinstance(points, list):
        return _lobe_from_curves(points, teeth, rotor, label)
    whole = outline.whole
    sigma = outline.sigma  # the points read as they are; --smoothing sets only the splines' smoothing
    edges, corner_points = corners(whole, sigma, corner_angle_deg)
    if roundings:
        edges, corner_points = _resolved_corners(whole, edges, corner_points, sigma)
    else:  # the roundings the points resolve are roundings whatever the reading
        edges, corner_points = _long_roundings(whole, edges, corner_points, sigma)
    if len(edges):
        corner_points = _refined_corners(whole, edges, corner_points, sigma, smoothing, outline.accuracy)
        runs = _runs_between_corners(whole, edges, corner_points, sigma)
    else:  # no corners: cut the ring in the middle of a land, if it has one
        found = _lands(np.vstack([whole, whole[:1]]), sigma)
        fitted = stepped_ring_fit(whole, sigma, side.pick(0.0, np.pi)) if roundings and not found else None
        if not found and fitted is None:
            return [("flank", lobe_curve(pair, whole, rotor, smoothing))]
        if fitted is not None:
            return _cut_lobe(fitted, whole, teeth, rotor, label)
        a, b, _ = found[0]
        ring = np.roll(whole, -((a + b) // 2), axis=0)
        if not _lands(np.vstack([ring, ring[:1]]), sigma):
            # the land's halves too short to read as lands (a land of 6 exact points ending at the
            # ring's seam, the N-rack male's root at 300 a lobe): the ring as read, in which the land was
            # found, else the closed run's ends coincide and nothing was fitted ("every ray ... crosses once")
            ring = whole
        runs = [np.vstack([ring, ring[:1]])]
    knots = fine_knot_spacing(whole) if sigma <= 0 and smoothing is None else None
    fitted = [piece for run in runs for piece in _fit_run(run, sigma, smoothing, knots)]
    return _cut_lobe(fitted, whole, teeth, rotor, label)


def _cut_lobe(
    fitted: list[tuple[Curve, np.ndarray, np.ndarray]], whole: np.ndarray, teeth: int, rotor: Side, label: str
) -> list[tuple[str, Curve]]:
    """Cut the lobe facing the mate, root to root, out of the whole outline's curves.

    Each curve comes with its sample points and their parameters; the lobe is trimmed at the two
    roots' polar angles and its pieces are named ``"lobe part i"``.
    """
    rotor = Side(rotor)  # "male" / "female" from a script reads as the rotor
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


def _lobe_from_curves(curves: list[Curve], teeth: int, rotor: Side, label: str) -> list[tuple[str, Curve]]:
    """Cut the lobe facing the mate from the exact curves of a drawing.

    The curves are one lobe (patterned here), or the whole outline, counter-clockwise
    (:func:`exports.dxf_profile.read_profile_dxf`): arcs stay arcs, splines stay the drawing's
    splines, and the lobe is cut from them at the roots.
    """
    rotor = Side(rotor)  # "male" / "female" from a script reads as the rotor
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


def _lands(run: np.ndarray, sigma: float) -> list[tuple[int, int, float]]:
    """Find the lands of a run (:func:`rotorcad.measured.outline.lands`) whose radius is constant within the scatter.

    Scattered points of a flank about its tip or root (a female root rounded by the male tip, its
    radius of curvature some millimetres) stay within the lands' window of 8 sigma over 0.1 mm, yet
    their radius about the centre still rises either side: fitted as a land, their normals turn
    radial and the clearance there reads 10 um off at 1 um scatter (the N-rack female's root, 2000
    points a lobe). A land is kept when a quadratic in the polar angle fitted to its points' radii
    has its slope and curvature within three standard errors (sigma) of zero: the least-squares test
    that the radius is constant; exact points (sigma 0) keep the window's test.

    Parameters
    ----------
    run : (n, 2) float array, mm
        Consecutive outline points about the origin.
    sigma : float, mm
        Their scatter (0 for exact points).

    Returns
    -------
    list of (first, last, radius)
        As :func:`rotorcad.measured.outline.lands`.
    """
    found = lands(run, sigma)
    if sigma <= 0:
        return found
    kept = []
    for a, b, radius in found:
        if b - a + 1 >= 6 and _constant_radius(run[a : b + 1], sigma):
            kept.append((a, b, radius))
    return kept


def _constant_radius(points: np.ndarray, sigma: float) -> bool:
    """Tell whether the radii of points (n, 2) about the origin are constant within their scatter sigma (mm).

    Slope and curvature of a least-squares quadratic in the polar angle each within three standard
    errors of zero.
    """
    theta = np.unwrap(np.arctan2(points[:, 1], points[:, 0]))
    half = 0.5 * (theta.max() - theta.min())
    t = (theta - 0.5 * (theta.max() + theta.min())) / half
    design = np.column_stack([np.ones_like(t), t, t * t])
    coef, *_ = np.linalg.lstsq(design, np.hypot(*points.T), rcond=None)
    error = sigma * np.sqrt(np.diag(np.linalg.inv(design.T @ design)))
    return bool(np.all(np.abs(coef[1:]) <= 3.0 * error[1:]))


def _fit_run(
    run: np.ndarray, sigma: float, smoothing: Smoothing, knot_spacing: float | None = None
) -> list[tuple[Curve, np.ndarray, np.ndarray]]:
    """Fit a run of outline points between corners as curves.

    Every land (an arc about the rotor's centre within the scatter,
    :func:`rotorcad.measured.outline.lands`) becomes that exact arc, whose normals are radial, so that
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
        s = _smoothing(part, sigma, smoothing)
        if knot_spacing is not None and len(part) > 8:  # dense points taken as exact (fine_knot_spacing)
            curve = _least_squares_spline(part, u, knot_spacing).trimmed(u[i0 - j0], u[i1 - j0])
            out.append((curve, run[i0 : i1 + 1], u[i0 - j0 : i1 - j0 + 1]))
            return
        steps = step_splines(part, i0 - j0, i1 - j0, s) if sigma <= 0 else None  # split where the curvature steps
        for curve, a, b in steps or ():
            out.append((curve, part[a : b + 1], u[a : b + 1] - u[a] + curve.s0))
        if steps is None:
            curve = Spline.fit(part, smoothing=s).trimmed(u[i0 - j0], u[i1 - j0])
            out.append((curve, run[i0 : i1 + 1], u[i0 - j0 : i1 - j0 + 1]))

    pos, lead = 0, 0
    for a, b, radius in _lands(run, sigma):
        spline(pos, a, lead, 3)
        t0 = float(np.arctan2(run[a, 1], run[a, 0]))
        t1 = t0 + float(np.unwrap(np.arctan2(run[a : b + 1, 1], run[a : b + 1, 0]))[-1] - t0)
        arc = Arc((0.0, 0.0), radius, t0, t1)
        u = np.linspace(t0, t1, b - a + 1)
        out.append((arc, arc.evaluate(u)[0], u))
        pos, lead = b, 3
    spline(pos, len(run) - 1, lead, 0)
    return out


def tangent_spread(
    points: np.ndarray | Outline, teeth: int, label: str, corner_angle_deg: float = 30.0
) -> tuple[np.ndarray, np.ndarray]:
    """Estimate how far the fit's tangent may turn from the true one at each point of exact points (rad).

    Between its sharp corners the outline is fitted with interpolating cubics (:func:`lobe_pieces`),
    whose tangent is accurate to O(h^3) along a smooth flank but only to O(h k) where the curvature
    jumps by k between two points h apart (a tip rounding meeting a flank): evenly spaced exact
    points of the N rack male (a tip rounding of about 1.04 mm radius, 0.67 mm long, 2-3 points on it at 300 a lobe)
    turn the fit's tangent there by 28-29 mrad, and the blow-hole's apex with it. The estimate is the
    angle between the cubic's tangent and that of the shape-preserving (modified Akima) cubic through
    the same points over the same chord-length parameter: two interpolants of different form agree to
    the smaller of their errors where the points resolve the outline and part where they do not
    (there 65-70 mrad at the N rack's tip, above the cubic's own error).

    Parameters
    ----------
    points : (n, 2) float array, mm, or Outline
        The profile's points (one lobe or the whole outline), own frame.
    teeth : int
        Its lobe count.
    label : str
        How the points are named in errors.
    corner_angle_deg : float, deg
        Turn above which a vertex is a sharp corner (:func:`rotorcad.measured.outline.corners`).

    Returns
    -------
    radii : (m,) float array, mm
        The radius of each point of the whole outline about the rotor's centre.
    spread : (m,) float array, rad
        The estimate at each point (0 at a corner's own point and on runs too short for both cubics).
    """
    from scipy.interpolate import Akima1DInterpolator  # here: exact points only

    outline = read_outline(points, teeth, label, corner_angle_deg, False)
    whole = outline.whole
    if whole is None:
        return np.zeros(0), np.zeros(0)
    edges, corner_points = _long_roundings(whole, *corners(whole, 0.0, corner_angle_deg), 0.0)  # as lobe_pieces cuts it
    if len(edges):
        corner_points = _refined_corners(whole, edges, corner_points, 0.0, None, outline.accuracy)
        runs = _runs_between_corners(whole, edges, corner_points, 0.0)
    else:
        runs = [np.vstack([whole, whole[:3]])]  # closed: the seam's points see both sides
    pts, spread = [], []
    for run in runs:
        u = np.concatenate([[0.0], np.cumsum(np.hypot(*np.diff(run, axis=0).T))])
        keep = np.concatenate([[True], np.diff(u) > 1e-12])
        run, u = run[keep], u[keep]
        if len(run) < 5:
            continue
        _, cubic = Spline.fit(run, smoothing=0.0).frame(u)
        akima = Akima1DInterpolator(u, run, method="makima")(u, 1)
        turn = np.abs(np.arctan2(cubic[:, 0] * akima[:, 1] - cubic[:, 1] * akima[:, 0], np.einsum("ij,ij->i", cubic, akima)))
        pts.append(run)
        spread.append(turn)
    if not pts:
        return np.zeros(0), np.zeros(0)
    return np.hypot(*np.vstack(pts).T), np.concatenate(spread)


def fit_residual(
    pair: RotorPair, points: np.ndarray | list[Curve] | Outline, pieces: list[tuple[str, Curve]], rotor: Side
) -> float:
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
    side = Side(rotor)  # "male" / "female" from a script reads as the rotor
    teeth = side.pick(pair.male_teeth, pair.female_teeth)
    outline = read_outline(points, teeth, f"{side.value} points")
    if outline.whole is None:
        return 0.0
    whole = outline.whole
    lobe = np.vstack([sample_curve(c, 1e-4)[1] for _, c in pieces])
    # each point's exact distance to the nearest segment of the lobes (an R-tree: shapely.distance to
    # the whole MultiLineString scans every segment for every point, 2-3 times the CPU)
    gaps = distance_to_polylines(whole, [rotate(lobe, k * 2 * np.pi / teeth) for k in range(teeth)])
    return float(np.quantile(gaps, 0.9))


__all__ = [
    "CURVATURE_NOISE",
    "KNOT_SPACING",
    "Smoothing",
    "close_smoothing",
    "fine_knot_spacing",
    "fit_residual",
    "lobe_curve",
    "lobe_pieces",
    "tangent_spread",
]

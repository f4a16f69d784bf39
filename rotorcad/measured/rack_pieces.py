"""The exact pieces of a rack read from its points: its lands and its rotors' tip-corner paths.

A rack period given by points (``rotor --rack-points``, ``hob --rack-points``) holds two kinds of
piece that a spline through the points does not give back exactly, and on which the verdicts turn:

* a **land**, a straight piece parallel to the pitch line (the images of the rotors' tip and root
  arcs, Rinder sec. 1.2). Its contacts lie on the line of centres and it is neither flank: fitted
  inside a spline, it rose by 1e-7..1e-4 mm over its length and counted as flank contact (the
  rack-involute sample's transverse contact ratios 0.683/0.696 for the design's 0.484/0.497);
* a **tip-corner path**, the path that a sharp corner on a rotor's tip circle describes in the rack
  frame (Rinder sec. 2.2.2, Fig. 1-4: at a tip only a corner is possible; Litvin, *Gear Geometry and
  Applied Theory*, sec. 6.1). With the rotor's pitch radius r_w, its tip radius R and
  sigma = +1 for the male, -1 for the female (rack frame of CONTRACT.md, y > 0 towards the female)
  it is the trochoid

      r_w + sigma y = R cos u,     x = sigma (R sin u - r_w u) + dx,

  one curve of the rotor's tip radius for every corner position dx. Along it the rotor's generated
  point stands still: the rotor receives the corner only, the mate a point-generated flank. A spline
  through its points (0.3 mm apart) let the generated corner wander by up to 0.1 mm; the male's
  flanks then no longer met at the corner, its corner's own path was lost from its rack and
  ``hob --rack-points`` read a rack deviation of 0.99 mm (rack-involute) where there is none.

Each point of one period is tested against both: a land where at least :data:`LAND_POINTS`
consecutive points lie within the points' tolerance of the rack's top or bottom height; a corner path
where consecutive points give one corner position dx within the tolerance, over at least
:data:`PATH_POINTS` points and the profile's resolution (exact points only: within the 8 um that
2 um of scatter allows, the N rack's tip-circle envelopes passed for tip corners' trochoids).
Adjacent exact pieces meet where they cross (or touch); the points between exact pieces are splines
whose ends are clamped to the exact piece's tangent where the two meet smoothly (the flank that runs
into a tip corner's path is tangent to it).
"""

from __future__ import annotations

import itertools
from dataclasses import dataclass

import numpy as np

from rotorcad.curves import Curve, Line, PointPath, Spline
from rotorcad.envelope import from_rack_frame, rack_frame
from rotorcad.roles import PieceRole, Side
from rotorcad.rotor_pair import RotorPair

LAND_POINTS = 3
"""Fewest consecutive points of exact data at one height that make a land (rotorcad's own rack CSV
samples a land with a point every 1.1 mm; the N rack's 1.8 mm root land holds 3 points of it)."""
PATH_POINTS = 5
"""Fewest consecutive points on one tip-corner trochoid that make that corner's path (the shortest
path of the samples, the narrow-tip female's, holds 9 points of rotorcad's own rack CSV)."""
EXACT_TOLERANCE = 1e-6
"""Share of the centre distance within which exact points lie on a land or a corner path (0.1 um for
a = 116 mm; a CSV written with 12 significant digits holds the points to 1e-10 of that)."""


@dataclass(frozen=True)
class ExactPiece:
    """A land or a tip-corner path recognised in the rack's points.

    Attributes
    ----------
    role : PieceRole
        CURVE for a land, the corner path of the male or the female otherwise.
    value : float, mm
        The land's height y, or the corner position dx of the path (module docstring).
    first, last : int
        Indices of its first and last point in the tiled chain of points.
    """

    role: PieceRole
    value: float
    first: int
    last: int

    @property
    def side(self) -> Side | None:
        """The rotor whose tip corner this path is (None for a land)."""
        return {PieceRole.MALE_CORNER_PATH: Side.MALE, PieceRole.FEMALE_CORNER_PATH: Side.FEMALE}.get(self.role)


def _trochoid(pair: RotorPair, side: Side) -> tuple[float, float, float]:
    """Return (sigma, r_w, R) of a rotor's tip-corner trochoid (module docstring)."""
    if side is Side.MALE:
        return 1.0, pair.male_pitch_radius, pair.male_tip_radius
    return -1.0, pair.female_pitch_radius, pair.female_tip_radius


def path_points(pair: RotorPair, side: Side, dx: float, u: np.ndarray) -> np.ndarray:
    """Return points (rack frame, mm) of the tip-corner trochoid at corner position ``dx``, (n, 2).

    ``u`` (rad) is the corner's polar angle from the line of centres (module docstring).
    """
    sigma, rw, big_r = _trochoid(pair, side)
    u = np.asarray(u, dtype=float)
    return np.column_stack([sigma * (big_r * np.sin(u) - rw * u) + dx, sigma * (big_r * np.cos(u) - rw)])


def corner_positions(pair: RotorPair, side: Side, points: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Return, for each rack point, the corner positions dx of the two trochoid branches through it.

    Returns
    -------
    dx : (n, 2) float array, mm
        Branch u >= 0 and branch u <= 0; NaN where the point lies beyond the tip circle's reach.
    u : (n, 2) float array, rad
        The corner's angle on each branch.
    gain : (n, 2) float array
        The normal distance from the trochoid per mm of dx (|dy/du| / |dp/du|), for a tolerance.
    """
    sigma, rw, big_r = _trochoid(pair, side)
    c = (rw + sigma * points[:, 1]) / big_r
    reach = np.abs(c) <= 1.0 + 1e-12
    base = np.arccos(np.clip(c, -1.0, 1.0))
    u = np.column_stack([base, -base])
    dx = points[:, :1] - sigma * (big_r * np.sin(u) - rw * u)
    dx[~reach] = np.nan
    dy, dxu = big_r * np.sin(u), big_r * np.cos(u) - rw
    gain = np.abs(dy) / np.maximum(np.hypot(dy, dxu), 1e-300)
    return dx, u, gain


GAP_POINTS = 2
"""Points of a run beyond the tolerance that do not end it when the run goes on after them: the
tolerance of scattered points bounds their largest error over the period with 95 % confidence only."""


def _close_gaps(mask: np.ndarray, gap: int = GAP_POINTS) -> np.ndarray:
    """Return ``mask`` with runs of at most ``gap`` False entries between True entries set True."""
    out = mask.copy()
    idx = np.flatnonzero(mask)
    if len(idx) < 2:
        return out
    jumps = np.flatnonzero((np.diff(idx) > 1) & (np.diff(idx) <= gap + 1))
    for j in jumps:
        out[idx[j] + 1 : idx[j + 1]] = True
    return out


def find_lands(points: np.ndarray, tol: float, shortest: float) -> list[tuple[int, int, float]]:
    """Find the lands: runs of consecutive points at the rack's top or bottom height within ``tol`` (mm).

    The lands of a rack are the images of the rotors' tip and root arcs, at its top (the male
    addendum) and its bottom (the dedendum) line (Rinder sec. 1.2). Each height is the median of the
    points within 3 ``tol`` of the extreme one; a land is a run of at least :data:`LAND_POINTS`
    points within ``tol`` of it, ``shortest`` (mm) long at least in x, its height their mean.

    Returns (first, last, height) of each, in the chain's order.
    """
    y = points[:, 1]
    out = []
    for extreme in (y.max(), y.min()):
        near = np.abs(y - extreme) <= 3 * tol
        level = float(np.median(y[near]))
        on = _close_gaps(np.abs(y - level) <= tol)
        edges = np.flatnonzero(np.diff(np.concatenate([[0], on.astype(int), [0]])))
        for a, b in zip(edges[::2], edges[1::2] - 1, strict=True):
            if b - a + 1 >= LAND_POINTS and points[b, 0] - points[a, 0] >= shortest:
                out.append((int(a), int(b), float(np.mean(y[a : b + 1]))))
    return sorted(out)


def find_paths(
    pair: RotorPair, side: Side, points: np.ndarray, free: np.ndarray, tol: float, shortest: float
) -> list[tuple[int, int, float]]:
    """Find runs of consecutive free points on one tip-corner trochoid of ``side`` within ``tol`` (mm).

    A window of :data:`PATH_POINTS` points whose corner positions agree (on one branch) proposes a
    trochoid; it is grown over every neighbouring free point within ``tol`` of it (either branch) and
    kept when it spans ``shortest`` (mm) of rack at least.

    Returns (first, last, dx) of each.
    """
    dx, _, gain = corner_positions(pair, side, points)
    n = len(points)
    m = PATH_POINTS
    out: list[tuple[int, int, float]] = []
    covered = ~free.copy()
    if n < m:
        return out
    # every window's proposal on each branch at once: its corners' median, and whether all agree with it
    windows = np.lib.stride_tricks.sliding_window_view(dx, m, axis=0)  # (n - m + 1, 2, m)
    steep = np.lib.stride_tricks.sliding_window_view(gain, m, axis=0)
    finite = np.isfinite(windows).all(axis=2)
    with np.errstate(invalid="ignore"):
        centres = np.median(windows, axis=2)
        agree = finite & np.all(np.abs(windows - centres[:, :, None]) * steep <= tol, axis=2)
    start = 0  # the first window not yet passed (the one after the last run found)
    for i in np.flatnonzero(agree.any(axis=1)).tolist():
        if i < start or covered[i : i + m].any():
            continue
        found = float(centres[i, 0] if agree[i, 0] else centres[i, 1])
        # refine the position on the window's steepest points and grow the run
        on = _close_gaps(np.nanmin(np.nan_to_num(np.abs(dx - found) * gain, nan=np.inf), axis=1) <= tol) & free
        a, z = i, i + m - 1
        while a > 0 and free[a - 1] and on[a - 1]:
            a -= 1
        while z + 1 < n and free[z + 1] and on[z + 1]:
            z += 1
        if np.hypot(*(points[z] - points[a])) >= shortest:
            # the run's own best corner position: the median over its steepest half
            # the run's own corner position: least squares of the normal distances (weights gain^2)
            rows = np.arange(a, z + 1)
            k = np.nanargmin(np.nan_to_num(np.abs(dx[rows] - found), nan=np.inf), axis=1)
            vals, g = dx[rows, k], gain[rows, k]
            out.append((a, z, float(np.sum(g**2 * vals) / max(float(np.sum(g**2)), 1e-300))))
            covered[a : z + 1] = True
            start = z + 1
    return out


def exact_pieces(
    pair: RotorPair, points: np.ndarray, tol: float, shortest: float, land: float = 0.0, paths: bool = True
) -> list[ExactPiece]:
    """Find the lands and tip-corner paths of a chain of rack points, in the chain's order.

    Parameters
    ----------
    pair : RotorPair
        The pair (pitch and tip radii).
    points : (n, 2) float array, mm
        Consecutive rack points, rack frame of CONTRACT.md, x ascending.
    tol : float, mm
        How far a point may lie from an exact piece it belongs to.
    shortest : float, mm
        The shortest corner path recognised (the profile's resolution).
    land : float, mm
        The shortest land recognised.
    paths : bool
        Whether to look for tip-corner paths too (of exact points only: 2 um of scatter let a stretch
        of 2.7 mm of the N rack's tip-circle envelopes pass for a tip corner's trochoid within the
        8 um the scatter allows).
    """
    pieces = [ExactPiece(PieceRole.CURVE, y0, a, b) for a, b, y0 in find_lands(points, tol, land)]
    free = np.ones(len(points), dtype=bool)
    for p in pieces:
        free[p.first : p.last + 1] = False
    for side in (Side.MALE, Side.FEMALE) if paths else ():
        for a, b, dx in find_paths(pair, side, points, free, tol, shortest):
            pieces.append(ExactPiece(PieceRole.corner_path_of(side), dx, a, b))
            free[a : b + 1] = False
    return sorted(pieces, key=lambda p: p.first)


def piece_parameters(pair: RotorPair, piece: ExactPiece, points: np.ndarray) -> np.ndarray:
    """Return the parameter (x of a land, u of a path) of the exact piece's point nearest each point."""
    if piece.role is PieceRole.CURVE:
        return points[:, 0].astype(float)
    dx, u, _ = corner_positions(pair, piece.side, points)
    k = np.nanargmin(np.nan_to_num(np.abs(dx - piece.value), nan=np.inf), axis=1)
    out = u[np.arange(len(points)), k]
    sigma, rw, _ = _trochoid(pair, piece.side)
    beyond = ~np.isfinite(dx).any(axis=1)  # beyond the tip circle's reach: the path's top or bottom
    out[beyond] = np.where(sigma * points[beyond, 1] + rw > 0, 0.0, np.pi)
    return out


def piece_frame(pair: RotorPair, piece: ExactPiece, s: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Return points (rack frame, mm) and unit tangents (towards larger s) of an exact piece."""
    s = np.atleast_1d(np.asarray(s, dtype=float))
    if piece.role is PieceRole.CURVE:
        return np.column_stack([s, np.full_like(s, piece.value)]), np.tile([1.0, 0.0], (len(s), 1))
    sigma, rw, big_r = _trochoid(pair, piece.side)
    d = np.column_stack([sigma * (big_r * np.cos(s) - rw), -sigma * big_r * np.sin(s)])
    return path_points(pair, piece.side, piece.value, s), d / np.maximum(np.hypot(*d.T), 1e-300)[:, None]


def meeting(
    pair: RotorPair, a: ExactPiece, b: ExactPiece, sa: float, sb: float, tol: float, reach: float = np.inf
) -> tuple[float, float] | None:
    """Return the parameters where two exact pieces cross or touch, near ``sa`` on ``a`` and ``sb`` on ``b``.

    None where they come no nearer than ``tol`` (mm), or meet farther than ``reach`` (mm) from the
    points at ``sa`` and ``sb``: a spline joins them.
    """
    from scipy.optimize import least_squares

    def gap(v: np.ndarray) -> np.ndarray:
        return piece_frame(pair, a, v[:1])[0][0] - piece_frame(pair, b, v[1:])[0][0]

    start = np.array([sa, sb])
    if not np.all(np.isfinite(gap(start))):
        return None
    scale = np.array([1.0 if a.role is PieceRole.CURVE else 0.05, 1.0 if b.role is PieceRole.CURVE else 0.05])
    fit = least_squares(gap, start, x_scale=scale, xtol=1e-15, ftol=1e-15, gtol=1e-15)
    if not fit.success or not np.all(np.isfinite(gap(fit.x))) or np.hypot(*gap(fit.x)) > tol:
        return None
    met = piece_frame(pair, a, fit.x[:1])[0][0]
    ends = np.vstack([piece_frame(pair, a, start[:1])[0], piece_frame(pair, b, start[1:])[0]])
    if np.hypot(*(ends - met).T).max() > reach:
        return None
    return float(fit.x[0]), float(fit.x[1])


def rack_curve(pair: RotorPair, piece: ExactPiece, s0: float, s1: float) -> Curve:
    """Return the exact piece between parameters ``s0`` and ``s1`` as a rack curve in the fixed frame (pitch line x = r1w).

    A land is a :class:`Line`; a corner path the :class:`PointPath` of the corner on the tip circle
    (``s`` the male's turn, as the profile families give it).
    """
    r1 = pair.male_pitch_radius
    if piece.role is PieceRole.CURVE:
        ends = from_rack_frame(np.array([[s0, piece.value], [s1, piece.value]]), r1)
        return Line(tuple(ends[0]), tuple(ends[1]))
    mesh = pair.mesh
    if piece.side is Side.MALE:
        theta = piece.value / r1
        big_r = pair.male_tip_radius
        carried = (big_r * np.cos(theta), big_r * np.sin(theta))
        t0, t1 = s0 - theta, s1 - theta
        return PointPath((float(carried[0]), float(carried[1])), mesh.male, mesh.rack, float(t0), float(t1))
    r2 = pair.female_pitch_radius
    phi = np.pi - piece.value / r2
    big_r = pair.female_tip_radius
    carried = (pair.center_distance + big_r * np.cos(phi), big_r * np.sin(phi))
    t0, t1 = -(piece.value + r2 * s0) / r1, -(piece.value + r2 * s1) / r1
    return PointPath((float(carried[0]), float(carried[1])), mesh.female, mesh.rack, float(t0), float(t1))


def clamped_spline(points: np.ndarray, start: np.ndarray | None, end: np.ndarray | None, smoothing: float) -> Spline:
    """Fit a cubic spline through (or near) rack points (fixed frame), its end tangents ``start`` / ``end`` where given.

    An interpolating spline (``smoothing`` 0) takes the given unit tangents as its end derivatives
    along the chord length (scipy's ``make_interp_spline``, clamped ends). A smoothing spline takes
    the knots of scipy's ``splprep`` for that smoothing (Dierckx sec. 5.2) and is the least-squares
    spline on them that passes through the first and last point (the exact pieces' ends) with the
    given end tangents (the equality-constrained least squares solved by its KKT system, Golub & Van
    Loan sec. 6.2), so that it meets the exact pieces as the interpolating one does.
    """
    pts = np.asarray(points, dtype=float)
    keep = np.concatenate([[True], np.hypot(*np.diff(pts, axis=0).T) > 1e-9])
    pts = pts[keep]
    if len(pts) < 3:
        return Spline.fit(pts)
    u = np.concatenate([[0.0], np.cumsum(np.hypot(*np.diff(pts, axis=0).T))])
    if smoothing > 0:
        return _constrained_smoothing(pts, u, start, end, smoothing)
    if start is None and end is None:
        return Spline.fit(pts)
    from scipy.interpolate import make_interp_spline

    left = [(1, np.asarray(start, dtype=float))] if start is not None else [(2, np.zeros(2))]
    right = [(1, np.asarray(end, dtype=float))] if end is not None else [(2, np.zeros(2))]
    spline = make_interp_spline(u, pts, k=3, bc_type=(left, right))
    knots, coef = spline.t, spline.c
    return Spline(knots=(knots, (coef[:, 0], coef[:, 1]), 3), s0=0.0, s1=float(u[-1]))


def _constrained_smoothing(
    pts: np.ndarray, u: np.ndarray, start: np.ndarray | None, end: np.ndarray | None, smoothing: float
) -> Spline:
    """Fit the least-squares cubic spline on ``splprep``'s knots through the end points, with the given end tangents.

    (:func:`clamped_spline`.)
    """
    from scipy.interpolate import BSpline, splprep

    knots = np.asarray(splprep(pts.T, u=u, s=smoothing, k=3, quiet=2)[0][0], dtype=float)
    inner = knots[4:-4]
    if len(inner) < 4:  # room for the data beside the four end conditions
        inner = np.linspace(u[0], u[-1], 6)[1:-1]
    knots = np.concatenate([[u[0]] * 4, inner, [u[-1]] * 4])
    nc = len(knots) - 4
    basis = BSpline(knots, np.eye(nc), 3)
    design = basis(u)
    ends = np.array([u[0], u[-1]])
    rows, rhs = list(basis(ends)), [pts[0], pts[-1]]
    slope = basis.derivative()(ends)
    for k, t in ((0, start), (1, end)):
        if t is not None:
            rows.append(slope[k])
            rhs.append(np.asarray(t, dtype=float))
    c, d = np.array(rows), np.array(rhs)
    kkt = np.block([[2 * design.T @ design, c.T], [c, np.zeros((len(c), len(c)))]])
    sol = np.linalg.lstsq(kkt, np.vstack([2 * design.T @ pts, d]), rcond=None)[0]
    coef = sol[:nc]
    return Spline(knots=(knots, (coef[:, 0], coef[:, 1]), 3), s0=0.0, s1=float(u[-1]))


PATH_SHARE = 0.9
"""Share of a mate's corner path's points on the rack derived from points that must lie within the
tolerance of the trochoid fitted to them (:func:`tip_corner_path`)."""


def tip_corner_path(pair: RotorPair, side: Side, curve: Curve, s0: float, s1: float, tol: float) -> Curve | None:
    """Return the exact path of ``side``'s tip corner that a part of a rack curve derived from points follows.

    A rack derived from one rotor's points (:func:`rotorcad.measured.pairs.pair_from_rotor_points`)
    carries the path of the mate's tip corner where the mate's generated point stands still; that
    path is the trochoid of a point of the mate's tip circle (module docstring; Rinder sec. 2.2.2),
    one curve for one corner position dx. Generated from a fitted flank it follows the fit's tangent
    errors, which grow without bound where the path ends in its cusp on the pitch line (the corner on
    the mate's pitch circle, the SRM and Lysholm females): the male's rack turned 0.7-0.9 deg off the
    perpendicular there, from exact points of 400 a lobe, for the design's 0. Of a corner on the mate's
    pitch circle (its tip radius its pitch radius, the path a cycloid with its cusp on the pitch line),
    the trochoid whose dx
    fits the part's points best (least squares of their normal distances) is taken instead, as for a
    rack's own points (:func:`find_paths`), when :data:`PATH_SHARE` of the part's points lie within
    ``tol`` (mm) of it.

    Parameters
    ----------
    pair : RotorPair
        The pair (pitch and tip radii).
    side : Side
        The rotor whose tip corner the path is (the mate of the rotor given by points).
    curve : Curve
        The rack curve, fixed frame (pitch line x = r1w, travel +y).
    s0, s1 : float
        The part's parameters on ``curve``, in the order of travel.
    tol : float, mm
        How far the part's points may lie from the trochoid.

    Returns
    -------
    Curve or None
        The :class:`rotorcad.curves.PointPath` from the point nearest the part's start to the one
        nearest its end; None when no trochoid holds the part within ``tol``, or when the mate's tip
        circle is not its pitch circle (elsewhere the generated path is kept: the exact one, met by the
        fitted flanks beside it within ``tol``, gave the male from the N rack female's exact points a
        cusp its design does not have).
    """
    sigma, rw, big_r = _trochoid(pair, side)
    if abs(big_r - rw) > 1e-6 * rw:
        return None  # no cusp on the pitch line: the path generated from the fit is kept
    s = np.linspace(s0, s1, 201)
    fixed = curve.evaluate(s)[0]
    ok = np.isfinite(fixed).all(axis=1)
    if ok.sum() < PATH_POINTS or not (ok[0] and ok[-1]):
        return None
    pts = rack_frame(fixed[ok], pair.male_pitch_radius)
    # points within ``tol`` beyond the tip circle's reach (a path ending on the pitch line of a corner on
    # the pitch circle, 0.01 um past it) are taken at the reach
    reach = np.clip(rw + sigma * pts[:, 1], -big_r, big_r)
    excess = np.abs(rw + sigma * pts[:, 1] - reach)
    pts[excess <= tol, 1] = sigma * (reach[excess <= tol] - rw)
    # farther beyond it: where the path ends in its cusp the rack runs along its tangent there, and
    # the fit's errors carry it past the pitch line by several micrometres (6 um from exact points of
    # the SRM-B male, 400 a lobe): those points are left out of the fit, their end taken at the reach
    inside = excess <= tol
    if inside.sum() < 0.8 * len(pts):
        return None
    ends_given = pts[[0, -1]]
    pts = pts[inside]
    dx, _, gain = corner_positions(pair, side, pts)
    if not np.isfinite(dx).any(axis=1).all():
        return None
    candidates = dx[np.isfinite(dx)]
    err = np.abs(dx[:, :, None] - candidates[None, None, :]) * gain[:, :, None]
    cost = np.nanmax(np.nanmin(np.nan_to_num(err, nan=np.inf), axis=1), axis=0)
    guess = float(candidates[int(np.argmin(cost))])
    # least squares of the normal distances on the branch nearest the guess (weights gain^2)
    k = np.argmin(np.nan_to_num(np.abs(dx - guess), nan=np.inf), axis=1)
    rows = np.arange(len(pts))
    vals, g = dx[rows, k], gain[rows, k]
    value = float(np.sum(g**2 * vals) / max(float(np.sum(g**2)), 1e-300))
    # once more without the points off it by more than ``tol``: next to the cusp the fit's rack strays
    # (1.2-4.5 um over the last 0.2 mm of the SRM-B male's, 0.17 um elsewhere); 90 % of them must hold
    held = np.abs(vals - value) * g <= tol
    if held.sum() < PATH_SHARE * len(vals):
        return None
    value = float(np.sum(g[held] ** 2 * vals[held]) / max(float(np.sum(g[held] ** 2)), 1e-300))
    if np.mean(np.abs(vals - value) * g <= tol) < PATH_SHARE:
        return None
    piece = ExactPiece(PieceRole.corner_path_of(side), value, 0, 0)
    u = piece_parameters(pair, piece, np.vstack([ends_given[0], pts[1], pts[-2], ends_given[1]]))
    # not on the cusp itself (u = 0, the corner on the line of centres), whose normal runs along the
    # pitch line and generates no point: as the design's paths, 1e-11 mm off it
    u = [float(np.copysign(max(abs(u[0]), 1e-7), u[1])), float(np.copysign(max(abs(u[3]), 1e-7), u[2]))]
    path = rack_curve(pair, piece, u[0], u[1])
    ends = path.evaluate(np.array([path.s0, path.s1]))[0]
    if not np.all(np.isfinite(ends)) or np.hypot(*(ends - fixed[ok][[0, -1]]).T).max() > tol + excess.max():
        return None
    return path


CURVATURE_STEP = 8.0
"""A point of exact data where the curvature of the points' circles steps by more than this many times
its change between neighbouring points on either side is a junction of two rack curves (the N rack's
two tip-circle envelopes meet at 9.885 mm with their curvatures 0.046 and 0.015 /mm: a step 25 times
the change beside it; a spline carried across smeared it and the female's generation factor, 0.033
in the design, swung to -0.07: an undercut that is not there)."""


def step_splines(part: np.ndarray, first: int, last: int, smoothing: float) -> list[tuple[Spline, int, int]] | None:
    """Fit exact points of one smooth stretch as interpolating splines split where their curvature steps.

    A rotor's outline is a chain of curves generated by the rack's pieces (Rinder sec. 1.2), which meet
    with a step of their curvature; one cubic through the points across such a step rings over a few
    spacings, and the rack derived from it turns by as much: the rack-involute male's CSV, through its
    root rounding and its flank, gave 17.96 deg for the design's 18.13. The steps are those of
    :func:`curvature_breaks` by at least :data:`STEP_SHARE` of the curvature beside them, where the
    step lies on one of the points: the two splines either side, each with its own end tangent, meet
    there within :data:`STEP_KINK` (the curves are tangent at their junction). A step between two points
    (evenly spaced points) is left inside one spline: the spline starting on the straddled spacing
    turns its end tangent (18 mrad; 17.2-17.4 deg for 18.13, against 18.07-18.08 from one spline).

    Parameters
    ----------
    part : (n, 2) float array, mm
        Consecutive exact points (any frame).
    first, last : int
        The stretch's first and last point in ``part`` (the points beyond them lead the end splines in
        and are trimmed off).
    smoothing : float, mm²
        The splines' smoothing: only 0 (interpolation of exact points) is split.

    Returns
    -------
    list of (Spline, int, int) or None
        Each spline between consecutive steps with its first and last point index in ``part``,
        trimmed to them; None when the stretch has no step on a point (the caller fits one spline).
    """
    if smoothing > 0:
        return None
    steps = (curvature_breaks(part[first : last + 1], 0.0, STEP_SHARE) + first).tolist()
    u = np.concatenate([[0.0], np.cumsum(np.hypot(*np.diff(part, axis=0).T))])

    def fitted(bounds: list[int]) -> list[tuple[Spline, int, int]]:
        out = []
        for k in range(len(bounds) - 1):
            j0 = 0 if k == 0 else bounds[k]
            j1 = len(part) - 1 if k == len(bounds) - 2 else bounds[k + 1]
            spline = Spline.fit(part[j0 : j1 + 1])
            out.append((spline.trimmed(u[bounds[k]] - u[j0], u[bounds[k + 1]] - u[j0]), bounds[k], bounds[k + 1]))
        return out

    while steps:
        out = fitted([first, *steps, last])
        ends = [
            (a.evaluate(np.array([a.s1]))[1][0], b.evaluate(np.array([b.s0]))[1][0])
            for (a, _, _), (b, _, _) in itertools.pairwise(out)
        ]
        kinks = np.array([abs(np.arctan2(ta[0] * tb[1] - ta[1] * tb[0], ta @ tb)) for ta, tb in ends])
        if kinks.max() <= STEP_KINK:
            return out
        steps.pop(int(np.argmax(kinks)))  # a step between two points: one spline across it
    return None


STEP_KINK = 2e-4
"""rad: the largest turn between the splines either side of a curvature step on one of the points
(:func:`step_splines`): 0.04-0.08 mrad at the rack-involute rotors' pieces' ends among the points of
their own CSVs, 17.6-18.5 mrad where the step falls between two evenly spaced points; evenly spaced
points of the N rack female (300 a lobe) whose step fell near a point turned by 0.8-1.0 mrad there, and
the male generated from them read a cusp on its sealing flank that the design does not have."""


STEP_SHARE = 0.25
"""Share of the larger curvature beside it by which the curvature of a rotor's exact points steps at a
junction of two generated curves (:func:`step_splines`): the rack-involute male's root rounding meets
its flank with -0.36 and 0.04 /mm; along its flank the circles of evenly spaced points (400 a lobe)
passed :data:`CURVATURE_STEP` with steps of 3 % of the curvature, where a split only adds ends."""


def curvature_breaks(run: np.ndarray, sigma: float, share: float = 0.0, ratio: float = CURVATURE_STEP) -> np.ndarray:
    """Return the interior points of exact rack points where the curvature steps (:data:`CURVATURE_STEP`).

    The curvature at a point is that of the circle through it and its two neighbours; the step at
    point j compares the circles before (j - 2, j - 1, j) and after (j, j + 1, j + 2) with the change
    between neighbouring circles on either side; of steps within two points of each other only the
    largest is kept. None for scattered points (``sigma`` > 0), whose circles are noise. With ``share``
    the step must be that share of the larger of the two circles' curvatures at least; ``ratio`` is
    the step's least multiple of the change beside it (default :data:`CURVATURE_STEP`).
    """
    p = np.asarray(run, dtype=float)
    n = len(p)
    if sigma > 0 or n < 7:
        return np.zeros(0, dtype=int)
    a, b, c = p[:-2], p[1:-1], p[2:]
    u, v = b - a, c - b
    den = np.hypot(*u.T) * np.hypot(*v.T) * np.hypot(*(c - a).T)
    k = np.full(n, np.nan)
    k[1:-1] = 2 * (u[:, 0] * v[:, 1] - u[:, 1] * v[:, 0]) / np.maximum(den, 1e-300)
    step = np.zeros(n)
    step[2:-2] = np.abs(k[3:-1] - k[1:-3])
    change = np.abs(np.diff(k))  # change[i] = |k[i + 1] - k[i]|
    beside = np.full(n, np.inf)
    beside[3:-3] = np.maximum(change[1:-4], change[4:-1])
    peak = step.copy()
    for off in (1, 2):
        peak = np.maximum(peak, np.maximum(np.roll(step, off), np.roll(step, -off)))
    big = np.zeros(n)
    big[2:-2] = np.maximum(np.abs(k[3:-1]), np.abs(k[1:-3]))
    idx = np.flatnonzero((step > ratio * beside) & (step > 1e-4) & (step >= peak) & (step >= share * big))
    return idx[(idx >= 2) & (idx <= n - 3)]


__all__ = [
    "EXACT_TOLERANCE",
    "GAP_POINTS",
    "LAND_POINTS",
    "PATH_POINTS",
    "ExactPiece",
    "clamped_spline",
    "corner_positions",
    "curvature_breaks",
    "exact_pieces",
    "meeting",
    "path_points",
    "piece_frame",
    "piece_parameters",
    "rack_curve",
    "step_splines",
    "tip_corner_path",
]

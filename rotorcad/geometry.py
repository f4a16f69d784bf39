"""Small vectorised plane-geometry helpers shared by curves, profiles and the envelope engine.

Points and vectors are numpy arrays of shape (n, 2); angles are radians, counter-clockwise
positive. Nothing here loops over points.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import numpy as np

Array = np.ndarray
ORIGIN = (0.0, 0.0)
"""The origin, mm: the default centre of a turn."""


def as_points(points: object) -> Array:
    """Return ``points`` as a float64 array of shape (n, 2) (a single point (2,) becomes (1, 2)).

    Parameters
    ----------
    points : array-like
        Points, or one point.

    Returns
    -------
    (n, 2) float array
        The input itself when it already is a float64 array.
    """
    arr = points if type(points) is np.ndarray and points.dtype == np.float64 else np.asarray(points, dtype=float)
    if arr.ndim == 1:
        arr = arr.reshape(1, 2)
    return arr


def rotate(points: Array, angle: float | Array, center: object = ORIGIN) -> Array:
    """Turn points about ``center``: the one rotation of the package.

    Parameters
    ----------
    points : (n, 2) float array, mm
        Points (or vectors, with the default ``center``).
    angle : float or array, rad
        Counter-clockwise turn. A scalar; one angle per point, shape (n,); or a stack of angles
        that broadcasts against the points, e.g. shape (k, 1) for ``k`` turned copies of all
        points (a pattern), giving shape (k, n, 2).
    center : (2,) float, mm
        Centre of the turn.

    Returns
    -------
    (..., n, 2) float array, mm
        The turned points: x' = c x - s y, y' = s x + c y about ``center``.
    """
    return turned(points, np.cos(angle), np.sin(angle), center)


def turned(points: Array, c: float | Array, s: float | Array, center: object = ORIGIN) -> Array:
    """Turn points about ``center`` by the angle whose cosine and sine are given: :func:`rotate`'s numbers.

    For several arrays turned by the same angles (a body's points and vectors), the cosine and
    sine computed once.

    Parameters
    ----------
    points : (n, 2) float array, mm
        Points (or vectors, with the default ``center``).
    c, s : float or array
        Cosine and sine of the counter-clockwise turn, shaped as :func:`rotate`'s ``angle``.
    center : (2,) float, mm
        Centre of the turn.

    Returns
    -------
    (..., n, 2) float array, mm
        The turned points: x' = c x - s y, y' = s x + c y about ``center``.
    """
    p = as_points(points)
    about_origin = center is ORIGIN or (type(center) is tuple and center == ORIGIN)
    if not about_origin:
        ctr = np.asarray(center, dtype=float)
        p = shifted(p, ctr, -1.0)
    x, y = p[:, 0], p[:, 1]
    if np.ndim(c) <= 1:
        out = np.empty_like(p)
        np.subtract(c * x, s * y, out=out[:, 0])
        np.add(s * x, c * y, out=out[:, 1])
    else:
        out = np.stack([c * x - s * y, s * x + c * y], axis=-1)
    return out if about_origin else shifted(out, ctr) if out.ndim == 2 else out + ctr


def row_norms(v: Array) -> Array:
    """Return the lengths of vectors: ``np.linalg.norm(v, axis=1)``, the same numbers, faster.

    numpy's norm sums a row's squares left to right, ``(x^2 + y^2) + z^2``, as a reduction over
    the short axis; here the same sum runs over the columns.

    Parameters
    ----------
    v : (n, 2) or (n, 3) float array
        Vectors.

    Returns
    -------
    (n,) float array
        Their Euclidean lengths.
    """
    sq = v * v
    total = sq[:, 0] + sq[:, 1]
    if v.shape[1] == 3:
        total += sq[:, 2]
    return np.sqrt(total)


def shifted(points: Array, by: object, sign: float = 1.0) -> Array:
    """Return ``points + by`` (``sign`` 1) or ``points - by`` (``sign`` -1) for one vector ``by``.

    The numbers of numpy's broadcast ``points + by``, taken column by column: numpy 2 broadcasts
    a (2,) row over an (n, 2) array a row at a time, ten times slower than the two columns.

    Parameters
    ----------
    points : (n, 2) float array
        Points or vectors (any other shape takes numpy's broadcast).
    by : (2,) float
        The vector added (or subtracted).
    sign : {1.0, -1.0}
        Add or subtract.

    Returns
    -------
    (n, 2) float array
        A new array.
    """
    p = np.asarray(points, dtype=float)
    if p.ndim != 2 or p.shape[1] != 2 or np.shape(by) != (2,):  # not one vector over (n, 2): numpy's broadcast
        return p + np.asarray(by, dtype=float) if sign > 0 else p - np.asarray(by, dtype=float)
    bx, by_ = float(by[0]), float(by[1])  # type: ignore[index]
    out = np.empty(p.shape)
    if sign > 0:
        np.add(p[:, 0], bx, out=out[:, 0])
        np.add(p[:, 1], by_, out=out[:, 1])
    else:
        np.subtract(p[:, 0], bx, out=out[:, 0])
        np.subtract(p[:, 1], by_, out=out[:, 1])
    return out


def to_point(points: Array, q: object) -> Array:
    """Return ``q - points``, the vectors from (n, 2) points to one point ``q`` ((2,) float), by columns.

    The numbers of numpy's broadcast (see :func:`shifted`).
    """
    p = np.asarray(points, dtype=float)
    if p.ndim != 2 or p.shape[1] != 2 or np.shape(q) != (2,):  # not one point and (n, 2) points: numpy's broadcast
        return np.asarray(q, dtype=float) - p
    out = np.empty(p.shape)
    np.subtract(float(q[0]), p[:, 0], out=out[:, 0])  # type: ignore[index]
    np.subtract(float(q[1]), p[:, 1], out=out[:, 1])  # type: ignore[index]
    return out


def filled(n: int, vector: object) -> Array:
    """Return an (n, 2) float array whose every row is ``vector`` ((2,) float), column by column."""
    out = np.empty((n, 2))
    out[:, 0] = float(vector[0])  # type: ignore[index]
    out[:, 1] = float(vector[1])  # type: ignore[index]
    return out


def dots(a: Array, b: Array) -> Array:
    """Return the row-wise dot products of (n, 2) arrays: ``np.einsum("ij,ij->i", a, b)``, the same numbers.

    ``a_x b_x + a_y b_y`` by columns, plus 0: einsum adds the products to a sum that starts at +0
    (without fusing them), so that a sum of two -0 products is +0.

    Parameters
    ----------
    a, b : (n, 2) float arrays
        Vectors.

    Returns
    -------
    (n,) float array
    """
    out = a[:, 0] * b[:, 0]
    out += a[:, 1] * b[:, 1]
    out += 0.0  # -0 -> +0, every other value as it is
    return out


def take_rows(a: Array, keep: Array) -> Array:
    """Return ``a[keep]`` for a boolean ``keep`` over the rows of an (n, 2) array, the same rows.

    By :func:`numpy.compress`: numpy 2 indexes the rows of a 2-d array by a mask an order of
    magnitude slower.
    """
    return np.compress(keep, a, axis=0)


_SURE = 1e-9
"""Relative margin of a squared length beyond which its hypot's side of a bound is certain: hypot is
within an ulp of the true length and the sum of squares within two, far inside 1e-9."""


def hypot_within(x: Array, y: Array, bound: float | Array) -> Array:
    """Return ``np.hypot(x, y) <= bound``, the same answer, computing hypot only near the bound.

    Where the sum of squares lies beyond the square of the bound by more than :data:`_SURE`
    (relative), the answer is certain; only the rest (a point within 1e-9 of the bound, a NaN)
    takes numpy's hypot, which costs as much as ten multiplications.

    Parameters
    ----------
    x, y : (n,) float arrays
        Coordinates (mm).
    bound : float or (n,) float array
        The largest length (mm), at least 0.

    Returns
    -------
    (n,) bool array
    """
    square = x * x
    square += y * y
    limit = np.square(bound)
    if np.min(limit) < 1e-290:  # a bound near underflow, where squares lose their relative accuracy
        return np.hypot(x, y) <= bound
    inside = square <= limit * (1.0 - _SURE)
    unsure = ~inside & ~(square > limit * (1.0 + _SURE))
    if unsure.any():
        k = np.flatnonzero(unsure)
        b = bound if np.ndim(bound) == 0 else np.asarray(bound)[k]
        inside[k] = np.hypot(x[k], y[k]) <= b
    return inside


def nearest_hypot(x: Array, y: Array) -> tuple[int, float]:
    """Return the index and value of the smallest ``np.hypot(x, y)``: ``argmin`` and ``min``, the same numbers.

    The smallest sum of squares picks the candidates (those within :data:`_SURE` of it, relative:
    any point farther has a larger hypot); numpy's hypot is taken of these only, and the first of
    its minima is returned, as ``np.argmin`` does. Non-finite sums take hypot everywhere.

    Parameters
    ----------
    x, y : (n,) float arrays, n >= 1
        Coordinates of vectors (mm).

    Returns
    -------
    index : int
    length : float
    """
    square = x * x
    square += y * y
    least = square.min()
    if not np.isfinite(least) or least < 1e-290:  # a NaN, or squares near underflow: hypot everywhere
        h = np.hypot(x, y)
        i = int(np.argmin(h))
        return i, float(h[i])
    k = np.flatnonzero(square <= least * (1.0 + _SURE))
    h = np.hypot(x[k], y[k])
    j = int(np.argmin(h))
    return int(k[j]), float(h[j])


def wrap_angle(angle: float | Array, reference: float | Array = 0.0, period: float = 2.0 * np.pi) -> float | Array:
    """Angle brought into the turn centred on ``reference``: the one angle wrap of the package.

    Parameters
    ----------
    angle : float or array, rad
        Angles, any shape.
    reference : float or array, rad
        Centre of the interval; broadcasts against ``angle``.
    period : float
        Length of the turn: 2 pi for an angle, or 2 pi / rate for a time of a body turning at
        ``rate``.

    Returns
    -------
    float or array
        ``reference + mod(angle - reference + period / 2, period) - period / 2``, in
        [reference - period / 2, reference + period / 2).
    """
    half = period / 2.0
    return reference + np.mod(angle - reference + half, period) - half


def cross(a: Array, b: Array) -> Array:
    """Return the z-component of the cross product a × b of plane vectors.

    Parameters
    ----------
    a, b : (..., 2) float array
        Vectors, broadcastable against each other (typically (n, 2)).

    Returns
    -------
    (...,) float array
        ``a_x b_y - a_y b_x``.
    """
    a = np.asarray(a, dtype=float)
    b = np.asarray(b, dtype=float)
    out = a[..., 0] * b[..., 1]
    out -= a[..., 1] * b[..., 0]
    return out


def perp_cw(t: Array) -> Array:
    """Turn vectors clockwise by 90 degrees: the outward normal of a counter-clockwise boundary.

    Parameters
    ----------
    t : (..., 2) float array
        Vectors, e.g. unit tangents (n, 2).

    Returns
    -------
    (..., 2) float array
        ``(t_y, -t_x)``.
    """
    t = np.asarray(t, dtype=float)
    out = np.empty_like(t)
    out[..., 0] = t[..., 1]
    out[..., 1] = -t[..., 0]
    return out


def normalize(v: Array) -> Array:
    """Return unit vectors along ``v`` (rows of zero length stay zero).

    Parameters
    ----------
    v : (..., d) float array
        Vectors along the last axis (d = 2 takes a shorter path).

    Returns
    -------
    (..., d) float array
        ``v / |v|``, zero where ``|v| = 0``.
    """
    v = np.asarray(v, dtype=float)
    if v.ndim == 2 and v.shape[1] == 2:
        x, y = v[:, 0], v[:, 1]
        length = np.sqrt(x * x + y * y)  # the sum np.linalg.norm forms, without its overhead
        if length.min(initial=np.inf) > 0.0:  # no zero (nor NaN) length: a plain division, by columns
            out = np.empty(v.shape)
            np.divide(x, length, out=out[:, 0])
            np.divide(y, length, out=out[:, 1])
            return out
        norm = length[:, None]
    elif v.shape[-1] == 2:
        x, y = v[..., 0], v[..., 1]
        norm = np.sqrt(x * x + y * y)[..., None]  # the sum np.linalg.norm forms, without its overhead
    else:
        norm = np.linalg.norm(v, axis=-1, keepdims=True)
    if norm.min(initial=np.inf) > 0.0:  # no zero (nor NaN) length: a plain division
        return v / norm
    positive = norm > 0.0
    with np.errstate(invalid="ignore", divide="ignore"):
        return np.where(positive, v / np.where(positive, norm, 1.0), 0.0)


def polar_angle(points: Array) -> Array:
    """Return the polar angle of each point about the origin.

    Parameters
    ----------
    points : (n, 2) float array, mm
        Points (a single (2,) point is read as (1, 2)).

    Returns
    -------
    (n,) float array, rad
        ``arctan2(y, x)``, in (-pi, pi].
    """
    p = as_points(points)
    return np.arctan2(p[:, 1], p[:, 0])


def radius(points: Array) -> Array:
    """Return the distance of each point from the origin.

    Parameters
    ----------
    points : (n, 2) float array, mm
        Points (a single (2,) point is read as (1, 2)).

    Returns
    -------
    (n,) float array, mm
        ``hypot(x, y)``.
    """
    return np.hypot(*as_points(points).T)


def distance_to_polyline(points: Array, polyline: Array, max_distance: float | None = None) -> Array:
    """Return the exact distance of each point to an open polyline.

    The nearest of the polyline's segments is found by shapely's STRtree (a packed R-tree), so that
    long segments beside dense clusters of vertices (a rack's flat beside a corner's path) are
    measured right. Repeated vertices (closer than 1e-12 mm) are dropped first.

    Parameters
    ----------
    points : (n, 2) float array, mm
        The points to measure.
    polyline : (m, 2) float array, mm
        Vertices of the open polyline, in order; a single distinct vertex is a point.
    max_distance : float, optional, mm
        Search no farther: a point farther than this from every segment gets ``inf`` (the R-tree
        then leaves the far branches alone, which is what makes many far points fast).

    Returns
    -------
    (n,) float array, mm
        Unsigned distance of each point to the polyline (``inf`` beyond ``max_distance``).
    """
    pts = as_points(points)
    line = as_points(polyline)
    keep = np.concatenate([[True], np.hypot(*np.diff(line, axis=0).T) > 1e-12])
    line = line[keep]
    if len(line) < 2:
        return np.hypot(*(pts - line[0]).T)
    return _nearest_segment_distance(pts, np.stack([line[:-1], line[1:]], axis=1), max_distance)


def polyline_distance(polyline: Array) -> Callable[..., Array]:
    """Return ``f(points, max_distance=None)``: :func:`distance_to_polyline` to ``polyline``, its R-tree built once.

    The same numbers, for a caller that measures many sets of points against one polyline (a search
    over the turns of a rotor's points, :mod:`rotorcad.measured.end_face`): building the R-tree of a
    whole outline's segments took as long as a search of it for 160 points.

    Parameters
    ----------
    polyline : (m, 2) float array, mm
        Vertices of the open polyline, in order.

    Returns
    -------
    callable
        Points (n, 2) mm and an optional ``max_distance`` (mm, as :func:`distance_to_polyline`'s) -> their
        unsigned distances (n,) mm to the polyline.
    """
    line = as_points(polyline)
    line = line[np.concatenate([[True], np.hypot(*np.diff(line, axis=0).T) > 1e-12])]
    if len(line) < 2:
        return lambda points, max_distance=None: np.hypot(*(as_points(points) - line[0]).T)
    import shapely

    tree = shapely.STRtree(shapely.linestrings(np.stack([line[:-1], line[1:]], axis=1)))
    return lambda points, max_distance=None: _nearest_in_tree(tree, as_points(points), max_distance)


def distance_to_polylines(points: Array, polylines: list[Array], near: float = 0.01) -> Array:
    """Return the exact distance of each point to the nearest of several open polylines.

    ``min(distance_to_polyline(points, p) for p in polylines)``, the same numbers, from one R-tree of
    all their segments, searched first within ``near`` of each point (a bounded search of the
    R-tree is many times faster) and then, for the points with no segment that near, without bound.

    Parameters
    ----------
    points : (n, 2) float array, mm
        The points to measure.
    polylines : list of (m_k, 2) float arrays, mm
        Vertices of each open polyline, in order; each has at least two distinct vertices.

    Returns
    -------
    (n,) float array, mm
        Unsigned distance of each point to the nearest polyline.
    """
    segments = []
    for polyline in polylines:
        line = as_points(polyline)
        line = line[np.concatenate([[True], np.hypot(*np.diff(line, axis=0).T) > 1e-12])]
        segments.append(np.stack([line[:-1], line[1:]], axis=1))
    pts = as_points(points)
    import shapely

    tree = shapely.STRtree(shapely.linestrings(np.concatenate(segments)))
    out = _nearest_in_tree(tree, pts, near)
    far = ~np.isfinite(out)
    if far.any():
        out[far] = _nearest_in_tree(tree, pts[far], None)
    return out


def _nearest_segment_distance(pts: Array, segments: Array, max_distance: float | None) -> Array:
    """Distance of each point (n, 2) to the nearest of ``segments`` (m, 2, 2), by shapely's STRtree; mm."""
    import shapely

    return _nearest_in_tree(shapely.STRtree(shapely.linestrings(segments)), pts, max_distance)


def _nearest_in_tree(tree: Any, pts: Array, max_distance: float | None) -> Array:
    """Distance of each point (n, 2) to the nearest geometry of a shapely STRtree (inf beyond ``max_distance``); mm."""
    import shapely

    (which, _seg), dist = tree.query_nearest(
        shapely.points(pts), max_distance=max_distance, return_distance=True, all_matches=False
    )
    out = np.full(len(pts), np.inf)
    np.minimum.at(out, which, dist)
    return out


def closest_pair(p: Array, q: Array, block: int = 16) -> tuple[int, int, float]:
    """Return the indices and distance of the closest pair of points of ``p`` and ``q``.

    The same pair as ``np.argmin`` over the whole distance matrix
    ``hypot(p[:, None] - q[None])`` (the first of equal distances in row-major order) and the same
    distance, without forming that matrix: the points are taken in blocks of ``block`` consecutive
    ones, the blocks' first points measured against each other, and only the block pairs whose
    distance less both blocks' radii (about those first points; the triangle inequality) can undercut
    the closest first points are measured in full. For two sampled curves crossing or passing each
    other that is a few block pairs out of thousands. (scipy's ``cKDTree(q).query(p)`` finds the same
    pair, but `rotor --json` judges meshlines without importing scipy.spatial: tests/test_import_cost.py.)

    Parameters
    ----------
    p : (n, 2) float array, mm
    q : (m, 2) float array, mm
        The points (of non-finite ones, the whole matrix is formed).
    block : int
        Points per block.

    Returns
    -------
    i, j : int
        The pair ``p[i]``, ``q[j]``.
    gap : float, mm
        Their distance.
    """
    p, q = as_points(p), as_points(q)
    n, m = len(p), len(q)
    if n * m <= 16 * block * block or not (np.isfinite(p).all() and np.isfinite(q).all()):
        gap = np.hypot(*(p[:, None, :] - q[None, :, :]).transpose(2, 0, 1))
        i, j = np.unravel_index(int(np.argmin(gap)), gap.shape)
        return int(i), int(j), float(gap[i, j])
    first_p, first_q = np.arange(0, n, block), np.arange(0, m, block)
    radius_p = np.maximum.reduceat(np.hypot(*(p - p[first_p].repeat(block, axis=0)[:n]).T), first_p)
    radius_q = np.maximum.reduceat(np.hypot(*(q - q[first_q].repeat(block, axis=0)[:m]).T), first_q)
    coarse = np.hypot(*(p[first_p][:, None, :] - q[first_q][None, :, :]).transpose(2, 0, 1))
    best = float(coarse.min())
    slack = 1e-9 * (best + float(radius_p.max()) + float(radius_q.max()))  # rounding of the bound: a few more blocks
    bp, bq = np.nonzero(coarse - radius_p[:, None] - radius_q[None, :] <= best + slack)
    offsets = np.arange(block)
    rows = first_p[bp][:, None] + offsets  # (k, block) each candidate block pair's indices
    cols = first_q[bq][:, None] + offsets
    valid = (rows < n)[:, :, None] & (cols < m)[:, None, :]
    rows, cols = np.minimum(rows, n - 1), np.minimum(cols, m - 1)
    gap = np.hypot(*(p[rows][:, :, None, :] - q[cols][:, None, :, :]).transpose(3, 0, 1, 2))
    gap = np.where(valid, gap, np.inf)
    flat = rows[:, :, None] * m + cols[:, None, :]  # the index in the whole matrix: the first of equal gaps wins
    least = gap.min()
    k = int(flat[gap == least].min())
    return k // m, k % m, float(least)

"""Small vectorised plane-geometry helpers shared by curves, profiles and the envelope engine.

Points and vectors are numpy arrays of shape (n, 2); angles are radians, counter-clockwise
positive. Nothing here loops over points.
"""

from __future__ import annotations

import numpy as np

Array = np.ndarray


def as_points(points: object) -> Array:
    """Return ``points`` as a float64 array of shape (n, 2)."""
    arr = np.asarray(points, dtype=float)
    if arr.ndim == 1:
        arr = arr.reshape(1, 2)
    return arr


def rotate(points: Array, angle: float | Array, center: object = (0.0, 0.0)) -> Array:
    """Turn points about ``center`` by ``angle`` (a scalar, or one angle per point)."""
    p = as_points(points) - np.asarray(center, dtype=float)
    c, s = np.cos(angle), np.sin(angle)
    out = np.empty_like(p)
    out[:, 0] = c * p[:, 0] - s * p[:, 1]
    out[:, 1] = s * p[:, 0] + c * p[:, 1]
    return out + np.asarray(center, dtype=float)


def cross(a: Array, b: Array) -> Array:
    """z-component of the cross product of two (n, 2) arrays (or broadcastable)."""
    a = np.asarray(a, dtype=float)
    b = np.asarray(b, dtype=float)
    return a[..., 0] * b[..., 1] - a[..., 1] * b[..., 0]


def perp_cw(t: Array) -> Array:
    """Turn vectors clockwise by 90 degrees: the outward normal of a counter-clockwise boundary."""
    t = np.asarray(t, dtype=float)
    return np.stack([t[..., 1], -t[..., 0]], axis=-1)


def normalize(v: Array) -> Array:
    """Unit vectors along ``v`` (rows of zero length stay zero)."""
    v = np.asarray(v, dtype=float)
    norm = np.linalg.norm(v, axis=-1, keepdims=True)
    with np.errstate(invalid="ignore", divide="ignore"):
        return np.where(norm > 0.0, v / np.where(norm > 0.0, norm, 1.0), 0.0)


def polar_angle(points: Array) -> Array:
    """Polar angle of each point about the origin, in (-pi, pi]."""
    p = as_points(points)
    return np.arctan2(p[:, 1], p[:, 0])


def radius(points: Array) -> Array:
    """Distance of each point from the origin."""
    return np.hypot(*as_points(points).T)


def distance_to_polyline(points: Array, polyline: Array) -> Array:
    """Exact distance of each point (n, 2) to an open polyline (m, 2), mm: the nearest of its
    segments found by shapely's STRtree (a packed R-tree), so that long segments beside dense
    clusters of vertices (a rack's flat beside a corner's path) are measured right."""
    import shapely

    pts = as_points(points)
    line = as_points(polyline)
    keep = np.concatenate([[True], np.hypot(*np.diff(line, axis=0).T) > 1e-12])
    line = line[keep]
    if len(line) < 2:
        return np.hypot(*(pts - line[0]).T)
    segments = shapely.linestrings(np.stack([line[:-1], line[1:]], axis=1))
    tree = shapely.STRtree(segments)
    (which, _seg), dist = tree.query_nearest(shapely.points(pts), return_distance=True, all_matches=False)
    out = np.full(len(pts), np.inf)
    np.minimum.at(out, which, dist)
    return out

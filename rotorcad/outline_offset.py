"""An outline moved into its body by a distance that varies along it, sharp corners included.

Each piece of a closed counter-clockwise outline (an analytic curve between corners) moves along
its own exact unit normal: q = p - delta(p) n(p). Where two pieces meet at a sharp corner the two
moved pieces are joined as the inner parallel set of the body (the erosion by delta, the set of
points at distance delta or more from the outside) joins them:

- at a convex corner (the travel turns left) the moved pieces cross: both are cut at their
  crossing, so the corner stays sharp and moves along the bisector, by delta / sin(theta / 2) for a
  turn of the tangent by pi - theta (theta the corner's inner angle);
- at a concave corner (the travel turns right) the moved pieces part: an arc of radius delta about
  the corner joins them.

Every loop that the moved outline makes (at a convex corner, or where delta exceeds a concave
piece's radius of curvature) lies outside the eroded body and is dropped: the moved chain is noded
and the largest face it bounds is kept (Serra, *Image analysis and mathematical morphology*, 1982,
ch. II: the erosion of a set by a disc; for a uniform delta this is the negative buffer of the body,
which the tests use as the independent reference).
"""

from __future__ import annotations

import numpy as np
import shapely

from rotorcad.geometry import Array, cross, perp_cw

CORNER_TURN = 1e-6  # rad: a turn of the tangent between two pieces above this is a sharp corner


def offset_inward(points: list[Array], tangents: list[Array], delta: list[Array], tolerance: float) -> Array:
    """Move a closed outline into its body by ``delta`` along the pieces' normals (module docstring).

    Parameters
    ----------
    points : list of (n_k, 2) float arrays, mm
        The pieces of a closed counter-clockwise outline in travel order, each with its samples
        (a piece's last point is the next piece's first point; the last piece ends at the first
        piece's start).
    tangents : list of (n_k, 2) float arrays
        Exact unit tangents along the travel at those points (from the analytic pieces).
    delta : list of (n_k,) float arrays, mm
        The distance to move each point into the body (>= 0).
    tolerance : float, mm
        Chord tolerance of the arcs that join the pieces at concave corners.

    Returns
    -------
    (m, 2) float array, mm
        The moved outline, closed counter-clockwise without a repeated end point.
    """
    moved = [p - d[:, None] * perp_cw(t) for p, t, d in zip(points, tangents, delta, strict=True)]
    chain = []
    for k, piece in enumerate(moved):
        chain.append(piece)
        nxt = (k + 1) % len(moved)
        t_end, t_start = tangents[k][-1], tangents[nxt][0]
        turn = float(np.arctan2(cross(t_end, t_start), np.dot(t_end, t_start)))
        if turn < -CORNER_TURN:  # concave corner: the arc of the erosion about the corner
            radius = 0.5 * (delta[k][-1] + delta[nxt][0])
            chain.append(_corner_arc(points[k][-1], t_end, turn, radius, tolerance))
    ring = np.vstack(chain)
    faces = shapely.polygonize(shapely.node(shapely.LineString(np.vstack([ring, ring[:1]]))).geoms)
    body = max(faces.geoms, key=lambda g: g.area)
    out = np.asarray(body.exterior.coords)[:-1]
    out = out[np.hypot(*(np.roll(out, -1, axis=0) - out).T) > 1e-9]  # the noding repeats a point now and then
    area2 = np.sum(out[:, 0] * np.roll(out[:, 1], -1) - np.roll(out[:, 0], -1) * out[:, 1])
    return out if area2 > 0 else out[::-1].copy()


def _corner_arc(corner: Array, t_end: Array, turn: float, radius: float, tolerance: float) -> Array:
    """Points of the arc of ``radius`` about a concave ``corner`` from one piece's moved end to the next's moved start.

    Parameters
    ----------
    corner : (2,) float array, mm
        The corner point.
    t_end : (2,) float array
        Unit tangent of the piece that ends at the corner.
    turn : float, rad
        The tangent's turn at the corner (negative: concave).
    radius : float, mm
        The arc's radius (the distance moved there).
    tolerance : float, mm
        Chord tolerance of the arc.

    Returns
    -------
    (k, 2) float array, mm
        Inner points of the arc (its ends are the moved pieces' ends).
    """
    if radius <= 0:
        return np.empty((0, 2))
    step = 2.0 * np.arccos(max(-1.0, 1.0 - tolerance / radius)) if tolerance < radius else np.pi / 2
    count = int(np.ceil(abs(turn) / step))
    start = np.arctan2(*(-perp_cw(t_end))[::-1])  # direction from the corner to the moved end: the inward normal
    angles = start + turn * np.arange(1, count) / count
    return corner + radius * np.stack([np.cos(angles), np.sin(angles)], axis=1)


__all__ = ["offset_inward"]

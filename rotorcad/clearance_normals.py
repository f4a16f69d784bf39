"""The normal clearance between two racks: the distance from each datum point to the compared rack along its own normal.

Wu & Chi, *A numerical method for the evaluation of the meshing clearance for twin screw rotors
with discrete tooth profile points*, sec. 4, eq. 10: r_n2 + delta n_n2 = r_n1(u), the compared rack
evaluated between its samples by cubic Hermite interpolation with its exact tangents. Used by
:class:`rotorcad.clearance.MeshingClearance`.
"""

from __future__ import annotations

import numpy as np

from rotorcad.geometry import Array, cross


def _hermite(p0: Array, t0: Array, p1: Array, t1: Array, tau: Array) -> tuple[Array, Array]:
    """Evaluate the cubic Hermite point and derivative between samples with exact unit tangents.

    The tangents are scaled by the chord. ``p0``, ``t0``, ``p1``, ``t1`` are (n, 2), ``tau`` (n,) in
    [0, 1]; returns the points and the derivatives d/dtau, both (n, 2).
    """
    h = np.hypot(*(p1 - p0).T)[:, None]
    m0, m1 = t0 * h, t1 * h
    u = tau[:, None]
    p = (2 * u**3 - 3 * u**2 + 1) * p0 + (u**3 - 2 * u**2 + u) * m0 + (-2 * u**3 + 3 * u**2) * p1 + (u**3 - u**2) * m1
    d = (6 * u**2 - 6 * u) * p0 + (3 * u**2 - 4 * u + 1) * m0 + (-6 * u**2 + 6 * u) * p1 + (3 * u**2 - 2 * u) * m1
    return p, d


def normal_clearance(datum: Array, normals: Array, compared: Array, compared_tangents: Array, window: int = 8) -> Array:
    """Measure from each datum point along its unit normal to the compared polyline (Wu & Chi eq. 10).

    The crossing nearest the datum point is taken among the ``window`` segments either side of the
    nearest compared point, then refined on the Hermite cubic of that segment (Newton).

    Parameters
    ----------
    datum : (n, 2) float array, mm
        Points of the datum rack.
    normals : (n, 2) float array
        Their unit normals (positive clearance along them).
    compared : (m, 2) float array, mm
        The compared rack as a polyline.
    compared_tangents : (m, 2) float array
        Its exact unit tangents at the vertices.
    window : int
        Segments searched either side of the nearest compared vertex.

    Returns
    -------
    (n,) float array, mm
        Signed distance delta with datum + delta normal on the compared rack (positive a gap,
        negative an interference); NaN where the normal line does not cut it nearby.
    """
    return normal_crossing(datum, normals, compared, compared_tangents, window)[0]


def normal_crossing(
    datum: Array, normals: Array, compared: Array, compared_tangents: Array, window: int = 8
) -> tuple[Array, Array]:
    """Return :func:`normal_clearance` and the compared segment each normal cuts.

    Parameters as :func:`normal_clearance`.

    Returns
    -------
    delta : (n,) float array, mm
        As :func:`normal_clearance`.
    segment : (n,) int array
        The compared polyline's segment (joining points i, i + 1) that the normal cuts, -1 for none.
    """
    from scipy.spatial import cKDTree

    k = cKDTree(compared).query(datum)[1]
    n_seg = len(compared) - 1
    offsets = np.arange(-window, window)
    seg = np.clip(k[:, None] + offsets[None, :], 0, n_seg - 1)  # segment i joins points i, i+1
    a, b = compared[seg], compared[seg + 1]
    g_a = cross(normals[:, None, :], a - datum[:, None, :])
    g_b = cross(normals[:, None, :], b - datum[:, None, :])
    with np.errstate(divide="ignore", invalid="ignore"):
        tau = g_a / (g_a - g_b)
    # a segment that runs against the tangents at both its ends is no piece of the rack: the seam where
    # one period's copy of a rack longer than its period overlaps the next (the N-rack male at 80
    # points a lobe: 0.7 mm back along the pitch line at its root, cut by the female's normals 57 um
    # nearer than the rack, -30 um read for +30 um)
    forward = np.einsum("ijk,ijk->ij", b - a, compared_tangents[seg] + compared_tangents[seg + 1]) > 0
    hit = (g_a * g_b <= 0) & np.isfinite(tau) & forward
    cut = a + np.nan_to_num(tau)[..., None] * (b - a)
    delta = np.einsum("ijk,ik->ij", cut - datum[:, None, :], normals)
    delta = np.where(hit, delta, np.inf)
    j = np.argmin(np.abs(delta), axis=1)
    rows = np.arange(len(datum))
    found = np.isfinite(delta[rows, j])
    s = seg[rows, j]
    u = np.clip(np.nan_to_num(tau[rows, j]), 0.0, 1.0)
    p0, p1, t0, t1 = compared[s], compared[s + 1], compared_tangents[s], compared_tangents[s + 1]
    for _ in range(4):  # Newton on cross(n, H(u) - datum) = 0
        p, d = _hermite(p0, t0, p1, t1, u)
        f = cross(normals, p - datum)
        df = cross(normals, d)
        with np.errstate(divide="ignore", invalid="ignore"):
            step = np.where(np.abs(df) > 1e-300, f / df, 0.0)
        u = np.clip(u - step, 0.0, 1.0)
    p, _ = _hermite(p0, t0, p1, t1, u)
    return np.where(found, np.einsum("ij,ij->i", p - datum, normals), np.nan), np.where(found, s, -1)


def trim_folds(
    points: Array, tangents: Array, flags: tuple[Array, ...] = (), span: int | None = None
) -> tuple[Array, Array, tuple[Array, ...]]:
    """Return a generated rack with each fold cut back to its envelope (the swallowtail's loop removed).

    Where a rotor's generation nearly stalls (its point still while its rack point runs), the rack follows
    the fit's curvature, not its position: a curvature error turns it back along itself, a swallowtail of
    three legs whose first and last cross (the N-rack sample's male rack facing the female's point r =
    43.5 mm from 300 exact points a lobe: 21 um wide, 60 um from 2 um of scatter). The rotor's material
    covers the loop (the envelope of its positions is the first leg up to the crossing, then the last):
    a normal that met the first leg's tail beyond the crossing read 6.7-12.4 um of clearance for a truth
    of 0 there. Each crossing of two non-adjacent segments i < j whose loop holds a segment running against
    the rack's exact tangents (a fold, not a rack that merely winds) and spans at most ``span`` points is
    cut: the points i + 1 .. j are replaced by the crossing twice, with the first leg's and the last leg's
    tangent there (a zero-length segment between, which no normal cuts). Nested loops: the outer one.

    Parameters
    ----------
    points : (m, 2) float array, mm
        The rack as a polyline, in order along it.
    tangents : (m, 2) float array
        Its exact unit tangents at the points.
    flags : tuple of (m,) arrays
        Per-point values carried along (the crossing's copies take those of points i + 1 and j).
    span : int, optional
        The most points a loop may span (default a third of ``m``).

    Returns
    -------
    points : (k, 2) float array, mm
    tangents : (k, 2) float array
    flags : tuple of (k,) arrays
    """
    import shapely  # only where the racks are compared

    pts = np.asarray(points, dtype=float)
    m = len(pts)
    span = m // 3 if span is None else span
    if m < 4:
        return pts, tangents, flags
    a, b = pts[:-1], pts[1:]
    back = np.einsum("ij,ij->i", b - a, tangents[:-1] + tangents[1:]) < 0
    if not back.any():
        return pts, tangents, flags
    lines = shapely.linestrings(np.stack([a, b], axis=1))
    i, j = shapely.STRtree(lines).query(lines, predicate="intersects")
    keep = (j - i >= 2) & (j - i <= span)
    i, j = i[keep], j[keep]
    n_back = np.concatenate([[0], np.cumsum(back)])
    keep = n_back[j] - n_back[i + 1] > 0  # a segment between them runs back: a fold
    i, j = i[keep], j[keep]
    if not len(i):
        return pts, tangents, flags
    order = np.lexsort((-j, i))
    out_p, out_t, out_f, start, end = [], [], [[] for _ in flags], 0, -1
    for s, e in zip(i[order], j[order], strict=True):  # one pass over the folds (a few), outermost first
        if s < end:  # nested in (or overlapping) a loop already cut
            continue
        d1, d2 = b[s] - a[s], b[e] - a[e]
        den = d1[0] * d2[1] - d1[1] * d2[0]
        if abs(den) < 1e-300:
            continue
        r = a[e] - a[s]
        u = (r[0] * d2[1] - r[1] * d2[0]) / den
        w = (r[0] * d1[1] - r[1] * d1[0]) / den
        x = a[s] + u * d1
        t1 = (1 - u) * tangents[s] + u * tangents[s + 1]
        t2 = (1 - w) * tangents[e] + w * tangents[e + 1]
        out_p += [pts[start : s + 1], x[None, :], x[None, :]]
        out_t += [tangents[start : s + 1], (t1 / np.hypot(*t1))[None, :], (t2 / np.hypot(*t2))[None, :]]
        for k, f in enumerate(flags):
            out_f[k].append(np.concatenate([f[start : s + 1], f[[s + 1, e]]]))
        start, end = e + 1, e + 1
    out_p.append(pts[start:])
    out_t.append(tangents[start:])
    for k, f in enumerate(flags):
        out_f[k].append(f[start:])
    return np.vstack(out_p), np.vstack(out_t), tuple(np.concatenate(f) for f in out_f)


__all__ = ["normal_clearance", "normal_crossing", "trim_folds"]

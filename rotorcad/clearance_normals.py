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


__all__ = ["normal_clearance", "normal_crossing"]

"""The cubic Hermite interpolant of exact samples, shared by the STEP and DXF writers.

Between samples p0, p1 with exact unit tangents t0, t1 on chord-length parameters, the cubic is the
Bézier curve of poles p0, p0 + L t0 / 3, p1 - L t1 / 3, p1 (L = |p1 - p0|): the Hermite interpolant
H(u) = h00 p0 + h10 L t0 + h01 p1 + h11 L t1 in Bernstein form (de Boor, *A Practical Guide to
Splines*, ch. IV). OpenCASCADE's ``GeomAPI_Interpolate`` makes it for the exact STEP
(:mod:`exports.step_exact`), the DXF SPLINE holds it as a B-spline (:mod:`exports.dxf_spline`).
"""

from __future__ import annotations

import numpy as np


def hermite_cubic(points: np.ndarray, tangents: np.ndarray, u: np.ndarray) -> np.ndarray:
    """Evaluate the cubic of every interval at the fractions ``u`` of its parameter.

    Parameters
    ----------
    points, tangents : (n + 1, 2) float arrays
        Samples (mm) and their exact unit tangents.
    u : (k,) float array
        Fractions of each interval, 0 to 1.

    Returns
    -------
    (n, k, 2) float array, mm
    """
    p, t = points, tangents
    chord = np.hypot(*(p[1:] - p[:-1]).T)[:, None]
    poles = np.stack([p[:-1], p[:-1] + chord * t[:-1] / 3.0, p[1:] - chord * t[1:] / 3.0, p[1:]], axis=1)  # (n, 4, 2)
    v = 1.0 - u
    basis = np.stack([v**3, 3 * u * v**2, 3 * u**2 * v, u**3])  # Bernstein, (4, k)
    return np.einsum("ku,nkd->nud", basis, poles)


def distance_to_chains(points: np.ndarray, chains: np.ndarray) -> np.ndarray:
    """Largest distance of each interval's points to its own chain of chords, (n,) mm.

    Parameters
    ----------
    points : (n, m, 2) float array, mm
        m points per interval (rows with NaN are left out).
    chains : (n, k, 2) float array, mm
        The vertices of each interval's chain (no NaN).
    """
    a, b = chains[:, None, :-1], chains[:, None, 1:]  # (n, 1, k - 1, 2)
    d = b - a
    w = points[:, :, None] - a  # (n, m, k - 1, 2)
    length2 = np.maximum((d * d).sum(-1), 1e-300)
    foot = np.clip((w * d).sum(-1) / length2, 0.0, 1.0)
    gap = w - foot[..., None] * d
    near = np.sqrt((gap * gap).sum(-1)).min(axis=2)
    return np.nan_to_num(near, nan=0.0).max(axis=1)

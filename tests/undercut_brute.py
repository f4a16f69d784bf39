"""Brute-force undercut point of a gear cut by the ISO 53 basic rack: a test reference independent of the envelope engine.

The gear's centre at the origin, the rack's pitch line y = r rolling on the pitch circle: a rack
point (u, v) at the roll phi lies at Rot(phi) (u + r phi, v) in the gear. The involute point of a
roll is the foot of the normal from the pitch point on the rack's straight flank (the envelope
of the flank); it is cut when a position of the tool's tip rounding (its centre's path) lies
nearer than the rounding's radius. The undercut point is the largest radius of a cut involute point.
"""

from __future__ import annotations

import numpy as np
from scipy.optimize import brentq, minimize_scalar

ALPHA = np.radians(20.0)
H_A0, RHO = 1.25, 0.38  # ISO 53 profile A tool: addendum and tip radius factors
Y = H_A0 - RHO * (1 - np.sin(ALPHA))  # effective tool addendum (Kollek & Osinski sec. 2): 0.99997
M = 4.0  # mm, the new user's module


def _rot(phi, p):
    c, s = np.cos(phi), np.sin(phi)
    return np.stack([c * p[..., 0] - s * p[..., 1], s * p[..., 0] + c * p[..., 1]], axis=-1)


def brute_undercut_radius(z: int, m: float, x: float = 0.0) -> float | None:
    """Largest radius (mm) of the rack-generated involute that the tool's tip rounding cuts; None for none (module docstring)."""
    r = z * m / 2
    radius = RHO * m
    d_c = (H_A0 - RHO) * m  # the rounding's centre below the datum line
    u_c = np.pi * m / 4 - d_c * np.tan(ALPHA) - radius / np.cos(ALPHA)
    y_c = r + x * m - d_c
    t = np.array([-np.sin(ALPHA), -np.cos(ALPHA)])  # along the flank, towards the tool tip
    pitch = np.array([0.0, r])

    def involute(phi):
        q0 = np.array([np.pi * m / 4 + r * phi, r + x * m])
        return _rot(phi, q0 + ((pitch - q0) @ t) * t)

    def centre(phi):
        phi = np.asarray(phi, float)
        return _rot(phi, np.stack([u_c + r * phi, np.full_like(phi, y_c)], axis=-1))

    grid = -u_c / r + np.linspace(-4 * m / r, 4 * m / r, 20001)
    path = centre(grid)

    def gap(phi1):
        p = involute(phi1)
        k = int(np.argmin(np.hypot(*(path - p).T)))
        lo, hi = grid[max(k - 1, 0)], grid[min(k + 1, len(grid) - 1)]
        near = minimize_scalar(lambda f: np.hypot(*(centre(f) - p)), bounds=(lo, hi), method="bounded", options={"xatol": 1e-13})
        return near.fun - radius

    phi_p = x * m * np.tan(ALPHA) / r - np.pi * m / (4 * r)  # contact at the pitch point
    phis = np.linspace(phi_p, phi_p + np.tan(ALPHA) - 1e-9, 200)  # ... down to the interference point T1
    gaps = np.array([gap(f) for f in phis])
    cut = np.flatnonzero(gaps < 0)
    if len(cut) == 0:
        return None
    k = int(cut[0])
    return float(np.hypot(*involute(brentq(gap, phis[k - 1], phis[k], xtol=1e-14))))

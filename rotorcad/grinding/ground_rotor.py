"""The rotor a given wheel grinds: the envelope of the wheel in helical motion, and the check.

The rotor is still and the wheel moves along the rotor's helix (rotation ``k dz`` about the rotor
axis with the advance ``dz``); the relative velocity of a wheel point ``Q`` per unit advance is
``v = k (e_z x Q) + e_z``. A wheel point of axial profile point ``(t, rho)`` with outward meridian
normal ``(n_t, n_rho)`` at the angle ``psi`` about the wheel axis is

    Q = W0 + t a + rho u(psi),  n = n_t a + n_rho u(psi),  u = cos psi e1 + sin psi e2,

``e1 = (-1, 0, 0)`` (from the wheel axis towards the rotor axis), ``e2 = a x e1 = (0, sin S, cos S)``.
The meshing condition ``n . v = 0`` (Litvin & Fuentes, *Gear Geometry and Applied Theory*, 2004,
the equation of meshing of an envelope to a family of surfaces) comes out linear in
``cos psi, sin psi`` (derived here; the ``sin psi cos psi`` terms cancel):

    alpha cos psi + beta sin psi + gamma = 0,
    alpha = k cos S (n_rho t - n_t rho),  beta = n_rho (k A sin S + cos S),
    gamma = n_t (k A cos S - sin S),

so every wheel circle touches the rotor at ``psi = atan2(beta, alpha) +- acos(-gamma / R)``,
``R = hypot(alpha, beta)``, in closed form; the root nearer ``psi = 0`` (the side facing the
rotor) is the contact. The contact point screwed back to the plane z = 0 along the helix is a
point of the ground transverse profile.

Secondary cutting and flank parts the wheel cannot reach are found by the stock the wheel leaves at
every point of the rotor outline: the least, over the wheel's positions along the helix through
the point, of the point's distance from the wheel axis minus the wheel's radius at its axial
coordinate (the wheel's upper envelope where its profile folds). Below zero the wheel cuts into the
rotor there (secondary cutting where that is not the flute's ground contact); above zero inside the
flute it leaves material (a flank part the wheel does not reach).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from rotorcad.geometry import Array
from rotorcad.grinding.setting import GrindingSetting


def rotor_from_wheel(axial: Array, radius: Array, normals: Array, setting: GrindingSetting) -> tuple[Array, Array]:
    """Return the transverse rotor profile points the wheel's profile points grind (module docstring).

    Parameters
    ----------
    axial, radius : (n,) float arrays, mm
        The wheel's axial profile.
    normals : (n, 2) float array
        Its outward unit normals in ``(t, rho)`` (from the analytic curve or a fitted spline).
    setting : GrindingSetting

    Returns
    -------
    points : (n, 2) float array, mm
        The ground transverse profile in the plane z = 0 (NaN where the wheel circle does not touch
        the rotor).
    contact : (n, 3) float array, mm
        The contact points with the wheel in its place (before screwing back to z = 0).
    """
    t, rho = np.asarray(axial, dtype=float), np.asarray(radius, dtype=float)
    nt, nr = normals[:, 0], normals[:, 1]
    k, a_ = setting.twist, setting.center_distance
    cs, sn = np.cos(setting.crossing_angle), np.sin(setting.crossing_angle)
    alpha = k * cs * (nr * t - nt * rho)
    beta = nr * (k * a_ * sn + cs)
    gamma = nt * (k * a_ * cs - sn)
    big_r = np.hypot(alpha, beta)
    with np.errstate(invalid="ignore", divide="ignore"):
        spread = np.arccos(-gamma / big_r)  # NaN where |gamma| > R: no contact
    centre = np.arctan2(beta, alpha)
    psi_a = np.angle(np.exp(1j * (centre + spread)))
    psi_b = np.angle(np.exp(1j * (centre - spread)))
    psi = np.where(np.abs(psi_a) <= np.abs(psi_b), psi_a, psi_b)
    c, s = np.cos(psi), np.sin(psi)
    contact = np.column_stack([a_ - rho * c, t * cs + rho * sn * s, -t * sn + rho * cs * s])
    turn = -k * contact[:, 2]
    ct, st = np.cos(turn), np.sin(turn)
    pts = np.column_stack([contact[:, 0] * ct - contact[:, 1] * st, contact[:, 0] * st + contact[:, 1] * ct])
    return pts, contact


@dataclass(frozen=True)
class WheelEnvelope:
    """The wheel as a radius over its axial coordinate: the upper envelope of its profile.

    Attributes
    ----------
    axial, radius : (m,) float arrays, mm
        A fine increasing grid of the axial coordinate and the wheel's largest radius there.
    """

    axial: Array
    radius: Array

    @staticmethod
    def of(axial: Array, radius: Array, step: float = 0.002) -> WheelEnvelope:
        """Make the upper envelope of a profile polyline on a grid of ``step`` (mm).

        Parameters
        ----------
        axial, radius : (n,) float arrays, mm
            The profile in order (NaNs dropped); runs where ``axial`` goes back are folds.
        step : float, mm
            Grid step; the profile's own points are added to it, so that no vertex is cut.

        Returns
        -------
        WheelEnvelope
        """
        ok = np.isfinite(axial) & np.isfinite(radius)
        t, r = np.asarray(axial, dtype=float)[ok], np.asarray(radius, dtype=float)[ok]
        grid = np.union1d(np.arange(t.min(), t.max(), step), t)
        best = np.full(len(grid), -np.inf)
        d = np.sign(np.diff(t))
        cuts = np.flatnonzero(d[1:] != d[:-1]) + 1  # where the direction of the axial coordinate turns
        for a, b in zip(np.r_[0, cuts], np.r_[cuts, len(t) - 1], strict=True):  # one pass per monotone run (few)
            tt, rr = t[a : b + 1], r[a : b + 1]
            if tt[0] > tt[-1]:
                tt, rr = tt[::-1], rr[::-1]
            inside = (grid >= tt[0]) & (grid <= tt[-1])
            best[inside] = np.maximum(best[inside], np.interp(grid[inside], tt, rr))
        return WheelEnvelope(grid, best)

    def __call__(self, t: Array) -> Array:
        """Return the wheel's radius at axial coordinates ``t``, mm (-inf beyond its profile's ends)."""
        r = np.interp(t, self.axial, self.radius)
        return np.where((t >= self.axial[0]) & (t <= self.axial[-1]), r, -np.inf)


def stock(points: Array, wheel: WheelEnvelope, setting: GrindingSetting, reach: float, steps: int = 1024) -> Array:
    """Return the material the wheel leaves at rotor points: least distance from the wheel surface.

    For each transverse point the helix through it, ``(Rz(k z) P, z)`` for ``|z| <= reach``, is
    searched for the least ``d(z) = distance from the wheel axis - wheel radius there``: a grid of
    ``steps`` intervals, then a finer grid of 64 about the best one and a parabola through the
    three best values (vectorised over points).

    Parameters
    ----------
    points : (n, 2) float array, mm
        Rotor points (transverse, the rotor as in the setting's frame).
    wheel : WheelEnvelope
    setting : GrindingSetting
    reach : float, mm
        Half the axial range searched.
    steps : int
        Intervals of the coarse grid.

    Returns
    -------
    (n,) float array, mm
        The least ``d``: about 0 where the wheel grinds the point, below 0 where it cuts into the
        rotor, above where it leaves material (inf where it never comes near).
    """
    p = np.asarray(points, dtype=float)

    def d(z: Array) -> Array:
        c, s = np.cos(setting.twist * z), np.sin(setting.twist * z)
        x = p[:, 0, None] * c - p[:, 1, None] * s
        y = p[:, 0, None] * s + p[:, 1, None] * c
        q = np.stack([x, y, np.broadcast_to(z, x.shape)], axis=-1)
        t, rho = setting.meridian(q)
        return rho - wheel(t)

    grid = np.linspace(-reach, reach, steps + 1)
    coarse = d(grid[None, :])
    j = np.clip(np.argmin(coarse, axis=1), 1, steps - 1)
    h = grid[1] - grid[0]
    fine = grid[j][:, None] + np.linspace(-h, h, 65)[None, :]
    v = d(fine)
    i = np.clip(np.argmin(v, axis=1), 1, 63)
    rows = np.arange(len(p))
    v0, v1, v2 = v[rows, i - 1], v[rows, i], v[rows, i + 1]
    curv = v0 - 2 * v1 + v2
    with np.errstate(invalid="ignore", divide="ignore"):
        best = np.where(curv > 0, v1 - (v2 - v0) ** 2 / (8 * curv), v1)
    return np.where(np.isfinite(best), np.minimum(best, v1), np.inf)


__all__ = ["WheelEnvelope", "rotor_from_wheel", "stock"]

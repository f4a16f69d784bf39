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

from rotorcad.geometry import Array, rotate
from rotorcad.grinding.setting import GrindingSetting
from rotorcad.grinding.wheel_profile import WheelProfile, reach

CHECK_TOLERANCE = 1e-3
"""Stock (mm) beyond which a rotor point counts as cut into (secondary cutting) or not reached: 1 um,
the accuracy the brute-force grinding simulation confirms (tests/test_grinding.py)."""


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
        ends = 1e-9  # mm: the profile's end points themselves (the flute's tip points) are on the wheel
        return np.where((t >= self.axial[0] - ends) & (t <= self.axial[-1] + ends), r, -np.inf)


def stock(points: Array, wheel: WheelEnvelope, setting: GrindingSetting, reach: float, steps: int = 256) -> Array:
    """Return the material the wheel leaves at rotor points: least distance from the wheel surface.

    For each transverse point the helix through it, ``(Rz(k z) P, z)`` for ``|z| <= reach``, is
    searched for the least ``d(z) = distance from the wheel axis - wheel radius there``: a grid of
    ``steps`` intervals, then twice a finer grid of 32 about the best one and a parabola through
    the three best values (vectorised over points).

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

    cs, sn = np.cos(setting.crossing_angle), np.sin(setting.crossing_angle)

    def d(z: Array) -> Array:
        # the point (x, y, z) about the wheel axis W0 + t a, a = (0, cos S, -sin S): axial
        # t = y cos S - z sin S, radius^2 = (x - A)^2 + (y sin S + z cos S)^2
        c, s = np.cos(setting.twist * z), np.sin(setting.twist * z)
        x = p[:, 0, None] * c - p[:, 1, None] * s
        y = p[:, 0, None] * s + p[:, 1, None] * c
        rho = np.hypot(x - setting.center_distance, y * sn + z * cs)
        return rho - wheel(y * cs - z * sn)

    grid = np.linspace(-reach, reach, steps + 1)
    best_z = grid[np.argmin(d(grid[None, :]), axis=1)]
    h = grid[1] - grid[0]
    rows = np.arange(len(p))
    for _ in range(2):  # two finer grids about the best so far, each 1/16 of the last step
        fine = best_z[:, None] + np.linspace(-h, h, 33)[None, :]
        v = d(fine)
        i = np.clip(np.argmin(v, axis=1), 1, 31)
        best_z, h = fine[rows, i], h / 16.0
    v0, v1, v2 = v[rows, i - 1], v[rows, i], v[rows, i + 1]
    with np.errstate(invalid="ignore", divide="ignore"):  # inf - inf where the wheel never comes near
        curv = v0 - 2 * v1 + v2
        best = np.where(curv > 0, v1 - (v2 - v0) ** 2 / (8 * curv), v1)
    return np.where(np.isfinite(best), np.minimum(best, v1), np.inf)


@dataclass(frozen=True, eq=False)
class GrindingCheck:
    """What a wheel does to the rotor it was made for.

    Attributes
    ----------
    flute_stock : (n,) float array, mm
        :func:`stock` at the flute's points (the wheel profile's own rotor points).
    neighbour_points : (m, 2) float array, mm
        The outline's points outside the flute within one lobe pitch of its middle, turned like the
        flute, and ``neighbour_stock`` (m,) their stock: the lobes either side, which a wheel that
        is too wide or set wrongly cuts into.
    unreached : (n,) bool array
        Flute points the wheel does not grind: no contact, or stock above :data:`CHECK_TOLERANCE`.
    round_trip : float, mm
        Largest distance between the flute's points and the rotor the wheel grinds
        (:func:`rotor_from_wheel` of the wheel's profile and analytic normals), over the points
        with contact.
    """

    flute_stock: Array
    neighbour_points: Array
    neighbour_stock: Array
    unreached: Array
    round_trip: float

    @property
    def secondary_cutting_deviation(self) -> float:
        """Deepest cut into the rotor beyond :data:`CHECK_TOLERANCE`, mm (0 when there is none)."""
        least = min(float(np.min(self.flute_stock, initial=np.inf)), float(np.min(self.neighbour_stock, initial=np.inf)))
        return max(0.0, -least) if least < -CHECK_TOLERANCE else 0.0

    @property
    def secondary_cutting_points(self) -> int:
        """Rotor points the wheel cuts into by more than :data:`CHECK_TOLERANCE`."""
        return int((self.flute_stock < -CHECK_TOLERANCE).sum() + (self.neighbour_stock < -CHECK_TOLERANCE).sum())


def check_grinding(wheel: WheelProfile, outline: Array, lobes: int) -> GrindingCheck:
    """Check a wheel against the rotor it was made for: stock, secondary cutting, round trip.

    Parameters
    ----------
    wheel : WheelProfile
        The wheel (:func:`rotorcad.grinding.wheel_profile`).
    outline : (k, 2) float array, mm
        The whole rotor outline in its own frame (not turned).
    lobes : int
        The rotor's lobes (teeth), for the neighbouring lobes' window.

    Returns
    -------
    GrindingCheck
    """
    setting, flute = wheel.setting, wheel.flute
    envelope = WheelEnvelope.of(wheel.axial, wheel.radius)
    zmax = reach(setting, flute.tip_radius)
    turned = rotate(np.asarray(outline, dtype=float), flute.turn)
    angle = np.arctan2(turned[:, 1], turned[:, 0])
    ends = np.arctan2(flute.points[[0, -1], 1], flute.points[[0, -1], 0])
    outside = (angle < ends[0] - 1e-9) | (angle > ends[1] + 1e-9)  # the flute itself is checked on its dense points
    near = turned[outside & (np.abs(angle) <= 2 * np.pi / lobes)]
    flute_stock = stock(flute.points, envelope, setting, zmax)
    near_stock = stock(near, envelope, setting, zmax) if len(near) else np.zeros(0)
    valid = wheel.valid
    ground, _ = rotor_from_wheel(wheel.axial[valid], wheel.radius[valid], wheel.normals[valid], setting)
    trip = np.hypot(*(ground - flute.points[valid]).T)
    round_trip = float(np.nanmax(trip)) if len(trip) and np.isfinite(trip).any() else float("nan")
    unreached = ~valid | (np.isfinite(flute_stock) & (flute_stock > CHECK_TOLERANCE))  # inf: a tip point at the wheel's end
    return GrindingCheck(flute_stock, near, near_stock, unreached, round_trip)


__all__ = ["CHECK_TOLERANCE", "GrindingCheck", "WheelEnvelope", "check_grinding", "rotor_from_wheel", "stock"]

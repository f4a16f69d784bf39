"""The axial profile of the form-grinding wheel that grinds a given rotor.

A surface of revolution touches a surface where their common normal meets the axis of revolution
(Litvin & Fuentes, *Gear Geometry and Applied Theory*, 2nd ed., Cambridge 2004, the tangency of a
surface of revolution with a given surface; Litvin, *Theory of Gearing*, NASA RP-1212, 1989; the
forming-tool condition of Stosic, Smith & Kovacevic, *Screw Compressors*, Springer 2005, on rotor
manufacture). For every point ``P = (x, y)`` of the rotor's transverse profile, with its unit
tangent ``T`` from the analytic segment and outward normal ``n = (T_y, -T_x)``, the helicoid
(:mod:`rotorcad.grinding.setting`) carries ``P`` to ``(X, Y, z) = (Rz(kz) P, z)`` with the normal
``N = (Rz(kz) n, k q)``, ``q = P . T`` (derived here: ``N = r_u x r_theta / p`` of the helicoid
``r = Rz(theta) P + p theta e_z``, ``p = 1/k``). The normal line meets the wheel axis
``W0 + s a`` where ``det[r - W0, N, a] = 0``; divided by ``p``, with ``a = (0, cos S, -sin S)`` and
``n' = Rz(kz) n``,

    g(z) = -(X - A)(n'_y sin S + k q cos S) + Y n'_x sin S + z n'_x cos S = 0,
    g'(z) = cos S (k^2 q Y + n'_x - k z n'_y) + k A sin S n'_x,

which holds for the spur gear (``k = 0``, ``S = 0``: ``g = z n_x``, contact in the plane z = 0)
as well. ``g`` is transcendental in ``z``; every profile point's root is bracketed on one grid
(vectorised) and closed by bisection (:func:`rotorcad.roots.bisect_many`). Of several roots the
one nearest the transverse plane z = 0 (which holds the common perpendicular of the axes) whose
normal points at the wheel axis from the rotor's side is kept.
The wheel's profile point is the contact point's axial coordinate and distance from the axis.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from rotorcad.errors import GeometryError
from rotorcad.geometry import Array, perp_cw, rotate
from rotorcad.grinding.setting import GrindingSetting
from rotorcad.profile import Profile
from rotorcad.roots import bisect_many

GRID_STEPS = 256
"""Grid intervals over the wheel's reach along the rotor axis on which every contact is bracketed."""


@dataclass(frozen=True, eq=False)
class Flute:
    """The flute (inter-lobe groove) the wheel grinds: a run of the rotor outline, turned to face +x.

    Attributes
    ----------
    points, tangents : (n, 2) float arrays
        The outline's samples from one lobe tip to the next (counter-clockwise travel), turned by
        ``turn``: points (mm), unit tangents from the analytic segments.
    turn : float, rad
        The turn that brings the flute's middle (the bisector of its two tip points) onto +x.
    tip_radius, root_radius : float, mm
        Largest and least radius of the outline.
    """

    points: Array
    tangents: Array
    turn: float
    tip_radius: float
    root_radius: float


def flute_of(profile: Profile) -> Flute:
    """Pick the flute around the outline's least radius and turn it to face the wheel (+x).

    Parameters
    ----------
    profile : Profile
        The rotor's closed transverse outline about the origin (counter-clockwise).

    Returns
    -------
    Flute
        The points from the last point at the tip radius before the root to the first one after it
        (within 1e-6 of the tip radius, relative).

    Raises
    ------
    GeometryError
        An outline with no lobe tip on both sides of its root (not a rotor).
    """
    p, t = profile.points, profile.tangents
    r = np.hypot(p[:, 0], p[:, 1])
    r_tip, r_root = float(r.max()), float(r.min())
    n = len(p)
    order = np.roll(np.arange(n), -int(np.argmin(r)))  # start at the root
    at_tip = r[order] >= r_tip * (1.0 - 1e-6)
    if not at_tip.any():
        raise GeometryError("profile", "a rotor outline with lobe tips")  # pragma: no cover - r_tip is reached
    after = int(np.argmax(at_tip))  # first tip point after the root
    before = n - 1 - int(np.argmax(at_tip[::-1]))  # last tip point before the root (going round)
    idx = np.concatenate([order[before:], order[: after + 1]])
    if len(idx) < 3 or before <= after:
        raise GeometryError("profile", "a rotor outline with a lobe tip on each side of its root")
    a0, a1 = np.arctan2(p[idx[0], 1], p[idx[0], 0]), np.arctan2(p[idx[-1], 1], p[idx[-1], 0])
    a1 = a0 + np.mod(a1 - a0, 2 * np.pi)
    turn = -0.5 * (a0 + a1)
    return Flute(rotate(p[idx], turn), rotate(t[idx], turn), float(turn), r_tip, r_root)


@dataclass(frozen=True, eq=False)
class WheelProfile:
    """The wheel's axial profile and where it touches the rotor.

    Attributes
    ----------
    axial, radius : (n,) float arrays, mm
        Axial coordinate ``t`` along the wheel axis from its mid-plane and radius ``rho`` of every
        profile point (NaN where the rotor point has no contact with the wheel).
    normals : (n, 2) float array
        Outward unit normals of the wheel's profile in ``(t, rho)`` (from the rotor's analytic
        normal, not from the points).
    contact : (n, 3) float array, mm
        The contact points in the rotor's frame (the rotor turned by ``flute.turn``).
    flute : Flute
        The rotor points ground, in the same order.
    setting : GrindingSetting
    """

    axial: Array
    radius: Array
    normals: Array
    contact: Array
    flute: Flute
    setting: GrindingSetting

    @property
    def valid(self) -> Array:
        """Points with a contact, (n,) bool."""
        return np.isfinite(self.axial) & np.isfinite(self.radius)

    @property
    def folds(self) -> bool:
        """True when the axial coordinate runs back along the profile (a wheel with an undercut)."""
        t = self.axial[self.valid]
        dt = np.diff(t)
        return bool(len(dt) and (dt > 1e-9).any() and (dt < -1e-9).any())


def contact_function(p: Array, n: Array, q: Array, z: Array, s: GrindingSetting) -> tuple[Array, Array]:
    """``g(z)`` and ``g'(z)`` of the module docstring for points ``p`` at axial positions ``z``.

    Parameters
    ----------
    p, n : (..., 2) float arrays
        Transverse points (mm) and their outward unit normals.
    q : (...) float array, mm
        ``P . T``.
    z : (...) float array, mm
        Axial positions (broadcast against ``q``).
    s : GrindingSetting

    Returns
    -------
    g, dg : (...) float arrays
        The contact function (mm) and its derivative along ``z``.
    """
    k, a_ = s.twist, s.center_distance
    cs, sn = np.cos(s.crossing_angle), np.sin(s.crossing_angle)
    c, si = np.cos(k * z), np.sin(k * z)
    x, y = p[..., 0], p[..., 1]
    big_x, big_y = x * c - y * si, x * si + y * c
    nx, ny = n[..., 0] * c - n[..., 1] * si, n[..., 0] * si + n[..., 1] * c
    g = -(big_x - a_) * (ny * sn + k * q * cs) + big_y * nx * sn + z * nx * cs
    dg = cs * (k * k * q * big_y + nx - k * z * ny) + k * a_ * sn * nx
    return g, dg


def reach(s: GrindingSetting, tip_radius: float) -> float:
    """Half the axial range searched for contacts, mm: a sphere about ``W0`` holding wheel and flute."""
    return float(np.hypot(s.center_distance + tip_radius, tip_radius))


def wheel_profile(flute: Flute, setting: GrindingSetting) -> WheelProfile:
    """Compute the wheel's axial profile that grinds ``flute`` in ``setting`` (module docstring).

    Parameters
    ----------
    flute : Flute
        The flute (:func:`flute_of`).
    setting : GrindingSetting

    Returns
    -------
    WheelProfile
        One wheel point per flute point.
    """
    p, t = flute.points, flute.tangents
    n = perp_cw(t)
    q = np.einsum("ij,ij->i", p, t)
    zmax = reach(setting, flute.tip_radius)
    grid = np.linspace(-zmax, zmax, GRID_STEPS + 1)
    g, _ = contact_function(p[:, None, :], n[:, None, :], q[:, None], grid[None, :], setting)
    change = (np.sign(g[:, :-1]) * np.sign(g[:, 1:]) <= 0) & np.isfinite(g[:, :-1]) & np.isfinite(g[:, 1:])
    # a linear estimate of every bracketed root, to choose among them
    g0, g1 = g[:, :-1], g[:, 1:]
    with np.errstate(divide="ignore", invalid="ignore"):
        frac = np.where(g0 != g1, g0 / (g0 - g1), 0.0)
    z_est = grid[:-1][None, :] + frac * (grid[1] - grid[0])
    rows, cols = np.nonzero(change)  # a few brackets per point: the side test only there
    facing = _facing(p[rows], n[rows], q[rows], z_est[rows, cols], setting)
    cost = np.full(change.shape, np.inf)
    cost[rows[facing], cols[facing]] = np.abs(z_est[rows[facing], cols[facing]])
    j = np.argmin(cost, axis=1)
    found = np.isfinite(cost[np.arange(len(p)), j])
    lo, hi = grid[j], grid[j + 1]

    def f(z: Array) -> Array:
        return contact_function(p, n, q, z, setting)[0]

    z = bisect_many(f, lo, hi)
    z = np.where(found, z, np.nan)
    contact, normal3 = _helicoid(p, n, q, z, setting.twist)
    axial, radius = setting.meridian(contact)
    radial = contact - setting.axis_point - axial[:, None] * setting.axis
    with np.errstate(invalid="ignore", divide="ignore"):
        radial /= radius[:, None]
        nt, nr = normal3 @ setting.axis, np.einsum("ij,ij->i", normal3, radial)
        length = np.hypot(nt, nr)
        wheel_n = -np.column_stack([nt, nr]) / length[:, None]  # the rotor's normal points into the wheel
    return WheelProfile(axial, radius, wheel_n, contact, flute, setting)


def _helicoid(p: Array, n: Array, q: Array, z: Array, k: float) -> tuple[Array, Array]:
    """Points ``(Rz(kz) P, z)`` and normals ``(Rz(kz) n, k q)`` of the helicoid, each (..., 3)."""
    c, si = np.cos(k * z), np.sin(k * z)
    x, y = p[..., 0], p[..., 1]
    pts = np.stack([x * c - y * si, x * si + y * c, z], axis=-1)
    nrm = np.stack([n[..., 0] * c - n[..., 1] * si, n[..., 0] * si + n[..., 1] * c, k * q * np.ones_like(z)], axis=-1)
    return pts, nrm


def _facing(p: Array, n: Array, q: Array, z: Array, s: GrindingSetting) -> Array:
    """Tell where the helicoid's normal at ``z`` points from the rotor towards the wheel axis.

    The contact point lies on the wheel's side (``X > 0``) and the foot of its perpendicular on
    the wheel axis is ahead along the outward normal.
    """
    pts, nrm = _helicoid(p, n, q, z, s.twist)
    d = pts - s.axis_point
    foot = d - (d @ s.axis)[..., None] * s.axis  # from the axis to the point, perpendicular
    return (pts[..., 0] > 0.0) & (np.einsum("...i,...i->...", foot, nrm) < 0.0)


__all__ = ["Flute", "WheelProfile", "contact_function", "flute_of", "wheel_profile"]

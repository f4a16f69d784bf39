"""Measured points of gear teeth assigned to the nominal flanks, turned onto them by a least-squares fit.

A CMM measures a gear in its own axis frame but at an arbitrary angular position: the points are
turned by the one angle delta that minimises the sum of the squared normal deviations of the
involute points (those within the radii of the evaluation range L_alpha) from their nearest
nominal flank.
With the flank of each point fixed, the normal deviation is linear in delta (left flank
r_b (u - delta), right flank r_b (delta - u'), :mod:`rotorcad.inspection.nominal`), so the fit is
the mean of u and u' over all points; flanks are reassigned and the fit repeated until no point
changes flank. A coarse scan over one pitch starts it.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from rotorcad.geometry import Array
from rotorcad.inspection.nominal import NominalFlanks

SCAN_STEPS = 720
"""Angles tried over one pitch by the coarse scan."""
SCAN_POINTS = 2000
"""Most points the coarse scan uses (evenly strided): its cost is points x steps."""


@dataclass(frozen=True)
class FlankPoints:
    """Points assigned to the nominal flanks after the best-fit rotation.

    Attributes
    ----------
    rotation : float, rad
        delta, within half a pitch: the measured points turned by -delta lie on the nominal gear.
    tooth : (n,) int array
        Tooth index 0 ... z - 1 of each involute point: tooth k lies near the polar angle
        k 2 pi / z in the frame of the points given.
    sign : (n,) int array
        +1 left flank, -1 right flank (:attr:`rotorcad.roles.ToothFlank.sign`).
    radius : (n,) float array, mm
        Radius of each point.
    deviation : (n,) float array, mm
        Normal deviation from the nominal flank in the transverse section, + more material.
    index : (n,) int array
        The points' rows in the points given.
    """

    rotation: float
    tooth: Array
    sign: Array
    radius: Array
    deviation: Array
    index: Array


def _nearest(theta: Array, psi: Array, pitch: float, delta: float) -> tuple[Array, Array, Array]:
    """Return (tooth, sign, angular error e) of each point's nearest flank for rotation ``delta``.

    e is u - k p with u = theta - delta - s psi: the left flank's polar offset (the right flank's
    with the opposite sign of the normal).
    """
    u_left = theta - delta - psi
    u_right = theta - delta + psi
    k_left = np.round(u_left / pitch)
    k_right = np.round(u_right / pitch)
    e_left = u_left - k_left * pitch
    e_right = u_right - k_right * pitch
    left = np.abs(e_left) <= np.abs(e_right)
    return (
        np.where(left, k_left, k_right).astype(int),
        np.where(left, 1, -1),
        np.where(left, e_left, e_right),
    )


def _scan(theta: Array, psi: Array, pitch: float, cap: float) -> float:
    """Coarse best rotation over one pitch: the least sum of capped squared angular errors."""
    step = max(1, len(theta) // SCAN_POINTS)
    t, p = theta[::step], psi[::step]
    deltas = np.linspace(0.0, pitch, SCAN_STEPS, endpoint=False)
    u = t[None, :] - deltas[:, None]
    e_left = np.remainder(u - p + pitch / 2.0, pitch) - pitch / 2.0
    e_right = np.remainder(u + p + pitch / 2.0, pitch) - pitch / 2.0
    e = np.minimum(np.abs(e_left), np.abs(e_right))
    cost = np.minimum(e * e, cap * cap).sum(axis=1)
    return float(deltas[int(np.argmin(cost))])


def align(points: Array, nominal: NominalFlanks, iterations: int = 20) -> FlankPoints:
    """Assign the involute points to their nominal flanks and fit the rotation (least squares).

    Parameters
    ----------
    points : (n, 2) float array, mm
        Measured points in the gear's axis frame (the centre at the origin).
    nominal : NominalFlanks
        The nominal gear.
    iterations : int
        Most reassignments.

    Returns
    -------
    FlankPoints
        The points within the evaluation range's radii (from the start of the active profile to
        the end of L_alpha: no point of the root or the tip land); empty arrays when there are none.
    """
    pts = np.asarray(points, dtype=float)
    r = np.hypot(pts[:, 0], pts[:, 1])
    top = float(nominal.radius_at(nominal.evaluation_range[1]))  # the tip land and the last 5 % stay out
    on_involute = np.nonzero((r >= max(nominal.active_start, nominal.base_radius)) & (r <= top))[0]
    theta = np.arctan2(pts[on_involute, 1], pts[on_involute, 0])
    psi = nominal.half_angle(r[on_involute])
    pitch = nominal.pitch_angle
    if len(on_involute) == 0:
        empty = np.zeros(0)
        return FlankPoints(0.0, empty.astype(int), empty.astype(int), empty, empty, on_involute)
    delta = _scan(theta, psi, pitch, cap=0.25 * psi.mean())
    tooth, sign, e = _nearest(theta, psi, pitch, delta)
    for _ in range(iterations):
        delta += float(np.mean(e))  # u_left - delta and delta - u_right summed to zero
        new_tooth, new_sign, e = _nearest(theta, psi, pitch, delta)
        same = np.array_equal(new_tooth, tooth) and np.array_equal(new_sign, sign)
        tooth, sign = new_tooth, new_sign
        if same and abs(float(np.mean(e))) < 1e-15:
            break
    turns = round(delta / pitch)  # delta within half a pitch: tooth k lies near k 2 pi / z in the points' frame
    delta -= turns * pitch
    deviation = nominal.base_radius * sign * e
    return FlankPoints(delta, np.mod(tooth + turns, nominal.teeth), sign, r[on_involute], deviation, on_involute)


__all__ = ["FlankPoints", "align"]

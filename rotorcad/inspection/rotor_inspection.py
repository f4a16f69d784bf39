"""A screw rotor's transverse section inspected from measured points: the normal deviation from the nominal outline.

Each point's deviation is its distance from the nominal outline (sampled to a chord tolerance: the
distance is exact to that tolerance), + outside the material (more material: the side of the
analytic normal of the outline's segment, :attr:`rotorcad.profile.Profile.normals`). The points are
turned onto the outline by the rotation that minimises the sum of the squared deviations (a coarse
scan over one lobe pitch, then Brent's method). Along the profile a point is placed by the arc
length of its nearest sample from its lobe's tip (the outline's farthest point, patterned to every
lobe): + towards the left flank (counter-clockwise, :class:`rotorcad.roles.ToothFlank`), - towards
the right one.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np
from scipy.optimize import minimize_scalar
from scipy.spatial import cKDTree

from rotorcad.geometry import Array
from rotorcad.roles import ToothFlank

SCAN_STEPS = 180
"""Rotations tried over one lobe pitch by the coarse scan."""
SCAN_POINTS = 500
"""Most points the coarse scan uses (evenly strided)."""


@dataclass(frozen=True)
class RotorInspection:
    """The normal deviations of a rotor's measured points from its nominal outline.

    Attributes
    ----------
    lobes : int
        Lobes (teeth) of the rotor.
    rotation : float, rad
        The points turned by -rotation lie on the outline (within half a lobe pitch).
    deviation : (n,) float array, mm
        Normal deviation of each point, + more material.
    along : (n,) float array, mm
        Arc length of its nearest nominal point from the lobe's tip, + towards the left flank.
    lobe : (n,) int array
        Lobe index of each point (lobe 0 the one nearest the +x axis of the outline).
    points_given : int
        All points read.
    """

    lobes: int
    rotation: float
    deviation: Array
    along: Array
    lobe: Array
    points_given: int

    def flank(self, flank: ToothFlank) -> Array:
        """Return the mask of the points on ``flank`` (the tip itself counts as left)."""
        return self.along >= 0.0 if flank is ToothFlank.LEFT else self.along < 0.0

    def summary(self) -> dict[str, Any]:
        """Return the CONTRACT.md keys of ``rotorcad inspect`` for a rotor (mm, deg)."""
        sides: dict[str, Any] = {}
        for side in ToothFlank:
            d = self.deviation[self.flank(side)]
            sides[side.value] = {
                "points": len(d),
                "max_normal_deviation": float(d.max()) if len(d) else None,
                "min_normal_deviation": float(d.min()) if len(d) else None,
                "rms_normal_deviation": float(np.sqrt(np.mean(d * d))) if len(d) else None,
                "normal_deviation_range": float(np.ptp(d)) if len(d) else None,
            }
        return {
            "lobes": self.lobes,
            "points_read": self.points_given,
            "lobes_measured": sorted({int(k) for k in self.lobe}),
            "alignment": {
                "rotation_deg": math.degrees(self.rotation),
                "method": "least squares: the rotation minimising the squared normal deviations from the outline",
                "rms_deviation": float(np.sqrt(np.mean(self.deviation**2))),
            },
            "max_normal_deviation": float(self.deviation.max()),
            "min_normal_deviation": float(self.deviation.min()),
            "left": sides["left"],
            "right": sides["right"],
        }


def _rotate(points: Array, angle: float) -> Array:
    c, s = math.cos(angle), math.sin(angle)
    return points @ np.array([[c, s], [-s, c]])


def _signed_distance(points: Array, nominal: Array, normals: Array, nearest: Array) -> Array:
    """Distance of each point from the closed polyline through ``nominal``, + on the side of the normals.

    The foot lies on one of the two chords at the nearest sample; the polyline lies within the
    outline's chord tolerance of the curve, so the distance is the curve's to that tolerance. The
    side is read off the analytic normal at the nearest sample.
    """
    n = len(nominal)
    best = np.full(len(points), np.inf)
    for step in (-1, 1):  # the chord before and the chord after the nearest sample
        a = nominal[nearest]
        b = nominal[(nearest + step) % n]
        ab = b - a
        t = np.clip(np.einsum("ij,ij->i", points - a, ab) / np.einsum("ij,ij->i", ab, ab), 0.0, 1.0)
        best = np.minimum(best, np.hypot(*(points - a - t[:, None] * ab).T))
    side = np.where(np.einsum("ij,ij->i", points - nominal[nearest], normals[nearest]) >= 0.0, 1.0, -1.0)
    return side * best


def inspect_rotor(points: Array, outline: Any, lobes: int) -> RotorInspection:
    """Inspect a rotor's transverse section from measured points against its nominal outline.

    Parameters
    ----------
    points : (n, 2) float array, mm
        Points of the rotor's section in its own axis frame, any order.
    outline : Profile
        The nominal outline, closed and counter-clockwise (:meth:`rotorcad.screw_rotors.ScrewRotors.male_outline`).
    lobes : int
        Its lobe count.

    Returns
    -------
    RotorInspection
    """
    pts = np.asarray(points, dtype=float)
    nominal, normals = outline.points, outline.normals
    tree = cKDTree(nominal)
    pitch = 2.0 * math.pi / lobes

    def deviations(angle: float, sample: Array) -> tuple[Array, Array]:
        turned = _rotate(sample, -angle)
        _, nearest = tree.query(turned)
        return _signed_distance(turned, nominal, normals, nearest), nearest

    sample = pts[:: max(1, len(pts) // SCAN_POINTS)]
    angles = np.linspace(-pitch / 2.0, pitch / 2.0, SCAN_STEPS, endpoint=False)
    costs = [float(np.sum(deviations(a, sample)[0] ** 2)) for a in angles]
    best = float(angles[int(np.argmin(costs))])
    step = pitch / SCAN_STEPS
    fit = minimize_scalar(
        lambda a: float(np.sum(deviations(a, pts)[0] ** 2)),
        bounds=(best - step, best + step),
        method="bounded",
        options={"xatol": 1e-12},
    )
    rotation = float(fit.x)
    deviation, nearest = deviations(rotation, pts)
    chord = np.hypot(*np.diff(np.vstack([nominal, nominal[:1]]), axis=0).T)
    length = np.concatenate([[0.0], np.cumsum(chord)[:-1]])
    lobe_length = float(chord.sum()) / lobes
    r = np.hypot(nominal[:, 0], nominal[:, 1])
    tip = int(np.argmax(r))
    offset = length[nearest] - length[tip]
    lobe = np.round(offset / lobe_length)
    along = offset - lobe * lobe_length
    first = math.atan2(nominal[tip, 1], nominal[tip, 0])
    lobe = np.mod(lobe + round(first / pitch), lobes).astype(int)
    return RotorInspection(lobes, rotation, deviation, along, lobe, len(pts))


__all__ = ["RotorInspection", "inspect_rotor"]

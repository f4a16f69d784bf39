"""Closed planar profiles made of named, densely sampled segments.

A :class:`Segment` is a named piece of a curve ("involute", "tip arc", "trochoid", ...) sampled
with exact unit tangents; a :class:`Profile` is a chain of segments travelled counter-clockwise
around the body (outward normal = tangent turned clockwise). Profiles leave the library as
closed counter-clockwise polygons without a repeated end point (DESIGN.md conventions).

Area and second moments of area follow from Green's theorem over the polygon
(A = 1/2 sum x_i y_{i+1} - x_{i+1} y_i, and the matching closed forms for the first and second
moments; e.g. Bourke, *Calculating the area and centroid of a polygon*, 1988).
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property

import numpy as np
import shapely

from rotorcad.curves import Curve, Mapped, mirrored, rotated, sample_curve
from rotorcad.geometry import Array, perp_cw

DEFAULT_TOLERANCE = 1e-4  # mm chord error: 0.1 micrometre


@dataclass(frozen=True, eq=False)
class Segment:
    """A named curve piece with its samples: parameters ``s``, ``points``, unit ``tangents``."""

    name: str
    curve: Curve
    s: Array
    points: Array
    tangents: Array

    @staticmethod
    def sample(name: str, curve: Curve, tolerance: float = DEFAULT_TOLERANCE) -> Segment:
        """Sample ``curve`` so that chords deviate from it by at most ``tolerance`` (mm)."""
        s, p, t = sample_curve(curve, tolerance)
        ok = np.all(np.isfinite(p), axis=1) & np.all(np.isfinite(t), axis=1)  # no-contact points are dropped
        return Segment(name, curve, s[ok], p[ok], t[ok])

    @staticmethod
    def at(name: str, curve: Curve, s: Array) -> Segment:
        """Sample ``curve`` at the given parameters."""
        p, t = curve.evaluate(np.asarray(s, dtype=float))
        return Segment(name, curve, np.asarray(s, dtype=float), p, t)

    @property
    def normals(self) -> Array:
        """Outward unit normals (tangent turned clockwise)."""
        return perp_cw(self.tangents)

    def resampled(self, tolerance: float) -> Segment:
        return Segment.sample(self.name, self.curve, tolerance)

    def rotated(self, angle: float, center: object = (0.0, 0.0)) -> Segment:
        curve = rotated(self.curve, angle, center)
        c, s = np.cos(angle), np.sin(angle)
        m = np.array([[c, -s], [s, c]])
        ctr = np.asarray(center, dtype=float)
        return Segment(self.name, curve, self.s, (self.points - ctr) @ m.T + ctr, self.tangents @ m.T)

    def mirrored(self, angle: float = 0.0) -> Segment:
        """Mirror in the line through the origin at ``angle``; travel is reversed so a boundary
        stays counter-clockwise."""
        c, s = np.cos(2 * angle), np.sin(2 * angle)
        m = np.array([[c, s], [s, -c]])
        return Segment(
            self.name,
            mirrored(self.curve, angle),
            self.s[::-1].copy(),
            (self.points @ m.T)[::-1].copy(),
            -(self.tangents @ m.T)[::-1].copy(),
        )


@dataclass(frozen=True, eq=False)
class Profile:
    """A chain of segments; ``closed`` profiles bound a body counter-clockwise."""

    segments: tuple[Segment, ...]
    closed: bool = True

    @cached_property
    def _joined(self) -> tuple[Array, Array, Array]:
        """Concatenated samples; a segment's first point is dropped where it repeats the
        previous segment's last point (and the closing point of a closed chain)."""
        segs = self.segments
        p = np.concatenate([s.points for s in segs])
        t = np.concatenate([s.tangents for s in segs])
        lengths = np.array([len(s.points) for s in segs])
        idx = np.repeat(np.arange(len(segs)), lengths)
        keep = np.ones(len(p), dtype=bool)
        starts = np.cumsum(lengths) - lengths
        if len(segs) > 1:
            gap = np.hypot(*(p[starts[1:]] - p[starts[1:] - 1]).T)
            keep[starts[1:][gap < 1e-9]] = False
        p, t, idx = p[keep], t[keep], idx[keep]
        if self.closed and len(p) > 1 and np.hypot(*(p[0] - p[-1])) < 1e-9:
            p, t, idx = p[:-1], t[:-1], idx[:-1]
        return p, t, idx

    @property
    def points(self) -> Array:
        """All sample points in order; closed profiles have no repeated end point."""
        return self._joined[0]

    @property
    def tangents(self) -> Array:
        return self._joined[1]

    @property
    def normals(self) -> Array:
        return perp_cw(self._joined[1])

    @property
    def segment_index(self) -> Array:
        """For every point, the index of the segment it belongs to."""
        return self._joined[2]

    def segment(self, name: str) -> list[Segment]:
        return [s for s in self.segments if s.name == name]

    def rotated(self, angle: float, center: object = (0.0, 0.0)) -> Profile:
        return Profile(tuple(s.rotated(angle, center) for s in self.segments), self.closed)

    def mirrored(self, angle: float = 0.0) -> Profile:
        return Profile(tuple(s.mirrored(angle) for s in reversed(self.segments)), self.closed)

    def __add__(self, other: Profile) -> Profile:
        return Profile(self.segments + other.segments, self.closed and other.closed)

    def patterned(self, count: int, center: object = (0.0, 0.0)) -> Profile:
        """``count`` copies turned by 2*pi/count about ``center`` (one tooth -> the whole gear).

        The sample arrays of all copies are rotated in one vectorised step.
        """
        ctr = np.asarray(center, dtype=float)
        ang = 2.0 * np.pi * np.arange(count) / count
        c, s = np.cos(ang)[:, None], np.sin(ang)[:, None]
        segs: list[Segment] = []
        arrays = []
        for seg in self.segments:
            x, y = (seg.points - ctr).T
            tx, ty = seg.tangents.T
            pts = np.stack([c * x - s * y, s * x + c * y], axis=-1) + ctr
            tan = np.stack([c * tx - s * ty, s * tx + c * ty], axis=-1)
            arrays.append((pts, tan))
        for k in range(count):
            m = ((float(c[k, 0]), float(-s[k, 0])), (float(s[k, 0]), float(c[k, 0])))
            shift = ctr - np.asarray(m) @ ctr
            for seg, (pts, tan) in zip(self.segments, arrays, strict=True):
                curve = (
                    seg.curve if k == 0 else Mapped(seg.curve, m, (float(shift[0]), float(shift[1])), seg.curve.s0, seg.curve.s1)
                )
                segs.append(Segment(seg.name, curve, seg.s, pts[k], tan[k]))
        return Profile(tuple(segs), True)

    def resampled(self, tolerance: float) -> Profile:
        """Every segment re-evaluated on its exact curve to the chord ``tolerance`` (mm)."""
        return Profile(tuple(s.resampled(tolerance) for s in self.segments), self.closed)

    def to_polygon(self) -> shapely.Polygon:
        return shapely.Polygon(self.points)

    @property
    def area(self) -> float:
        return polygon_moments(self.points)["area"]

    @property
    def centroid(self) -> Array:
        m = polygon_moments(self.points)
        return np.array([m["cx"], m["cy"]])

    def second_moments(self, about: str = "centroid") -> dict[str, float]:
        """Second moments of area Ixx, Iyy, Ixy (mm^4) about the ``centroid`` or the ``origin``."""
        m = polygon_moments(self.points)
        if about == "origin":
            return {"Ixx": m["Ixx"], "Iyy": m["Iyy"], "Ixy": m["Ixy"]}
        a, cx, cy = m["area"], m["cx"], m["cy"]
        return {"Ixx": m["Ixx"] - a * cy * cy, "Iyy": m["Iyy"] - a * cx * cx, "Ixy": m["Ixy"] - a * cx * cy}


def polygon_moments(points: Array) -> dict[str, float]:
    """Area, centroid and second moments about the origin of a simple polygon (Green's theorem).

    Ixx = integral y^2 dA, Iyy = integral x^2 dA, Ixy = integral x y dA. Positive area for a
    counter-clockwise polygon.
    """
    p = np.asarray(points, dtype=float)
    x0, y0 = p[:, 0], p[:, 1]
    x1, y1 = np.roll(x0, -1), np.roll(y0, -1)
    c = x0 * y1 - x1 * y0
    area = c.sum() / 2.0
    cx = ((x0 + x1) * c).sum() / (6.0 * area)
    cy = ((y0 + y1) * c).sum() / (6.0 * area)
    ixx = ((y0 * y0 + y0 * y1 + y1 * y1) * c).sum() / 12.0
    iyy = ((x0 * x0 + x0 * x1 + x1 * x1) * c).sum() / 12.0
    ixy = ((x0 * y1 + 2 * x0 * y0 + 2 * x1 * y1 + x1 * y0) * c).sum() / 24.0
    return {"area": float(area), "cx": float(cx), "cy": float(cy), "Ixx": float(ixx), "Iyy": float(iyy), "Ixy": float(ixy)}

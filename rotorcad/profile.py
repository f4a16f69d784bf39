"""Closed planar profiles made of named, densely sampled segments.

A :class:`Segment` is a named piece of a curve ("involute", "tip arc", "trochoid", ...) sampled
with exact unit tangents; a :class:`Profile` is a chain of segments travelled counter-clockwise
around the body (outward normal = tangent turned clockwise). Profiles leave the library as
closed counter-clockwise polygons without a repeated end point (ARCHITECTURE.md, conventions).

Area and second moments of area follow from Green's theorem over the polygon
(A = 1/2 sum x_i y_{i+1} - x_{i+1} y_i, and the matching closed forms for the first and second
moments; e.g. Bourke, *Calculating the area and centroid of a polygon*, 1988).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import cached_property

import numpy as np
import shapely

from rotorcad.curves import Curve, mirrored, rotated, sample_curve
from rotorcad.geometry import Array, perp_cw, rotate

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
        # no-contact points are dropped (the rows' test by columns, the rows by compress: faster)
        ok = np.isfinite(p[:, 0]) & np.isfinite(p[:, 1]) & np.isfinite(t[:, 0]) & np.isfinite(t[:, 1])
        if ok.all():
            return Segment(name, curve, s, p, t)
        return Segment(name, curve, s[ok], np.compress(ok, p, axis=0), np.compress(ok, t, axis=0))

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
        """Return the segment re-evaluated on its exact curve to the chord ``tolerance`` (mm).

        Parameters
        ----------
        tolerance : float
            Largest chord error, mm (:meth:`sample`).

        Returns
        -------
        Segment
            A new segment of the same name and curve.
        """
        return Segment.sample(self.name, self.curve, tolerance)

    def rotated(self, angle: float, center: object = (0.0, 0.0)) -> Segment:
        """Return the segment turned by ``angle`` (rad) about ``center`` (mm), its curve too.

        Parameters
        ----------
        angle : float
            Counter-clockwise turn, rad.
        center : (2,) float, mm
            Centre of the turn.

        Returns
        -------
        Segment
            The same parameters ``s``; points turned about ``center``, tangents turned.
        """
        return Segment(
            self.name,
            rotated(self.curve, angle, center),
            self.s,
            rotate(self.points, angle, center),
            rotate(self.tangents, angle),
        )

    def mirrored(self, angle: float = 0.0) -> Segment:
        """Return the segment mirrored in the line through the origin at ``angle``, its curve too.

        Travel is reversed so a boundary stays counter-clockwise.

        Parameters
        ----------
        angle : float
            Direction of the mirror line, rad.

        Returns
        -------
        Segment
            Parameters, points and tangents in reverse order; the tangents mirrored and negated
            so that they point along the reversed travel.
        """
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
    def _samples(self) -> tuple[Array, Array, Array]:
        """The segments' samples end to end, as three arrays.

        Points (n, 2) float, mm; unit tangents (n, 2) float; and the number of samples of each
        segment, (k,) int.
        """
        segs = self.segments
        lengths = np.array([len(s.points) for s in segs])
        return np.concatenate([s.points for s in segs]), np.concatenate([s.tangents for s in segs]), lengths

    @cached_property
    def _joined(self) -> tuple[Array, Array, Array]:
        """Concatenated samples: points (m, 2), mm; unit tangents (m, 2); segment index (m,).

        A segment's first point is dropped where it repeats the previous segment's last point
        (and the closing point of a closed chain); see :func:`_join`.
        """
        return _join(*self._samples, self.closed)

    @property
    def points(self) -> Array:
        """All sample points in order; closed profiles have no repeated end point."""
        return self._joined[0]

    @property
    def tangents(self) -> Array:
        """Unit tangents along the travel at :attr:`points`, (n, 2) float."""
        return self._joined[1]

    @property
    def normals(self) -> Array:
        """Outward unit normals at :attr:`points` (tangent turned clockwise), (n, 2) float."""
        return perp_cw(self._joined[1])

    @property
    def segment_index(self) -> Array:
        """For every point, the index of the segment it belongs to."""
        return self._joined[2]

    def segment(self, name: str) -> list[Segment]:
        """Return the segments called ``name``.

        Parameters
        ----------
        name : str
            Segment name, e.g. "involute".

        Returns
        -------
        list of Segment
            The segments of that name, in order (empty when there is none).
        """
        return [s for s in self.segments if s.name == name]

    def rotated(self, angle: float, center: object = (0.0, 0.0)) -> Profile:
        """Return the profile turned by ``angle`` about ``center``, every segment with its curve.

        Parameters
        ----------
        angle : float
            Counter-clockwise turn, rad.
        center : (2,) float, mm
            Centre of the turn.

        Returns
        -------
        Profile
            The turned segments (:meth:`Segment.rotated`), closed like this profile.
        """
        return Profile(tuple(s.rotated(angle, center) for s in self.segments), self.closed)

    def mirrored(self, angle: float = 0.0) -> Profile:
        """Return the profile mirrored in the line through the origin at ``angle``.

        Parameters
        ----------
        angle : float
            Direction of the mirror line, rad.

        Returns
        -------
        Profile
            The mirrored segments (:meth:`Segment.mirrored`) in reverse order, so that a closed
            profile stays counter-clockwise.
        """
        return Profile(tuple(s.mirrored(angle) for s in reversed(self.segments)), self.closed)

    def __add__(self, other: Profile) -> Profile:
        return Profile(self.segments + other.segments, self.closed and other.closed)

    def patterned(self, count: int, center: object = (0.0, 0.0)) -> Profile:
        """``count`` copies turned by 2 pi / count about ``center`` (one tooth -> the whole gear).

        Parameters
        ----------
        count : int
            Number of copies (teeth or lobes), the first one this profile itself.
        center : (2,) float, mm
            Centre of the pattern.

        Returns
        -------
        Profile
            A closed profile of ``count * len(self.segments)`` segments. Its points and tangents
            are this profile's samples turned in one vectorised step (a stack of ``count``
            rotations, :func:`rotorcad.geometry.rotate`); the segment objects, each with its
            exact curve under the turn, are only made when :attr:`segments` is first read.
        """
        return _Patterned(self, int(count), (float(center[0]), float(center[1])))

    def resampled(self, tolerance: float) -> Profile:
        """Every segment re-evaluated on its exact curve to the chord ``tolerance`` (mm)."""
        return Profile(tuple(s.resampled(tolerance) for s in self.segments), self.closed)

    def to_polygon(self) -> shapely.Polygon:
        """Return the profile as a shapely polygon of its :attr:`points`, mm."""
        return shapely.Polygon(self.points)

    @property
    def area(self) -> float:
        """Area of the polygon of :attr:`points`, mm² (positive for a counter-clockwise profile)."""
        return polygon_moments(self.points)["area"]

    @property
    def centroid(self) -> Array:
        """Centroid of the polygon of :attr:`points`, (2,) float, mm."""
        m = polygon_moments(self.points)
        return np.array([m["cx"], m["cy"]])

    def second_moments(self, about: str = "centroid") -> dict[str, float]:
        """Second moments of area Ixx, Iyy, Ixy (mm^4) about the ``centroid`` or the ``origin``."""
        m = polygon_moments(self.points)
        if about == "origin":
            return {"Ixx": m["Ixx"], "Iyy": m["Iyy"], "Ixy": m["Ixy"]}
        a, cx, cy = m["area"], m["cx"], m["cy"]
        return {"Ixx": m["Ixx"] - a * cy * cy, "Iyy": m["Iyy"] - a * cx * cx, "Ixy": m["Ixy"] - a * cx * cy}


class _Sampled(Profile):
    """A chain given by its samples, its segment objects made on first use.

    Points, tangents and the segment lengths are arrays from the start (what :attr:`points`, a
    pattern and a polygon need); :attr:`segments`, each with its exact curve, is made by
    ``make_segments`` only when it is read, so that a caller who wants the polygon pays for no
    per-piece objects.

    Parameters
    ----------
    points, tangents : (n, 2) float arrays
        The samples of all segments end to end: points (mm) and unit tangents along the travel.
    lengths : (k,) int array
        Samples of each segment, in order (summing to n).
    make_segments : callable
        Returns the k :class:`Segment` objects holding these samples (in order).
    closed : bool
        Whether the chain is closed.
    """

    def __init__(self, points: Array, tangents: Array, lengths: Array, make_segments: object, closed: bool = False) -> None:
        object.__setattr__(self, "closed", closed)
        object.__setattr__(self, "_make_segments", make_segments)
        self.__dict__["_samples"] = (points, tangents, lengths)

    @cached_property
    def segments(self) -> tuple[Segment, ...]:  # type: ignore[override]
        """The segments, made on first use (see the class docstring)."""
        return tuple(self._make_segments())


class _Patterned(Profile):
    """A closed profile made of ``count`` turned copies of ``unit`` (see :meth:`Profile.patterned`).

    Points, tangents and segment indices come from one vectorised rotation of the unit's samples;
    :attr:`segments` (one :class:`Segment` per piece and copy, with its exact curve) is built on
    first use, so that a caller who wants the polygon pays for no per-piece objects.
    """

    def __init__(self, unit: Profile, count: int, center: tuple[float, float]) -> None:
        object.__setattr__(self, "closed", True)
        object.__setattr__(self, "unit", unit)
        object.__setattr__(self, "count", count)
        object.__setattr__(self, "center", center)

    @cached_property
    def _angles(self) -> Array:
        """The turn of every copy, (count, 1), rad."""
        return (2.0 * np.pi * np.arange(self.count) / self.count)[:, None]

    @cached_property
    def _turned(self) -> tuple[Array, Array]:
        """Points and tangents of every copy, each (count, m, 2): the unit's samples turned."""
        pts, tan, _ = self.unit._samples
        return rotate(pts, self._angles, self.center), rotate(tan, self._angles)

    @cached_property
    def _samples(self) -> tuple[Array, Array, Array]:
        pts, tan = self._turned
        return pts.reshape(-1, 2), tan.reshape(-1, 2), np.tile(self.unit._samples[2], self.count)

    @property
    def points(self) -> Array:
        """All sample points in order, (n, 2), mm (no repeated end point); see :meth:`Profile.points`."""
        if "_joined" in self.__dict__:
            return self._joined[0]
        return self._points_only

    @cached_property
    def _points_only(self) -> Array:
        """The joined points without turning the tangents (what a polygon needs).

        Where every copy ends on the next copy's first point (a gear's teeth), the unit is joined
        once (:func:`_join`, open), its joined points but the first are turned to every copy in one
        step and the first point is put in front; the last point, the first one turned by a full
        turn, is left off. These are the points :func:`_join` keeps from all copies at once.
        """
        unit_pts, _, lengths = self.unit._samples
        ang = self._angles
        if self.count > 1:
            joined = _join(unit_pts, None, lengths, False)[0]
            (x0, y0), (x1, y1), (cx, cy) = joined[0], joined[-1], self.center
            c, s = math.cos(ang[1, 0]), math.sin(ang[1, 0])
            gap = math.hypot(cx + c * (x0 - cx) - s * (y0 - cy) - x1, cy + s * (x0 - cx) + c * (y0 - cy) - y1)
            if len(joined) > 2 and gap < 0.5e-9:  # the unit's last point is the next copy's first one
                centre = complex(cx, cy)
                z = np.ascontiguousarray(joined[1:]).view(np.complex128).reshape(-1)
                if centre:
                    z = z - centre
                turned = np.multiply.outer(np.exp(1j * ang[:, 0]), z)  # x + i y turned: a product
                if centre:
                    turned += centre
                out = np.empty(((len(joined) - 1) * self.count, 2))
                out[0] = joined[0]
                out[1:] = turned.view(np.float64).reshape(-1, 2)[:-1]
                return out
        pts = rotate(unit_pts, ang, self.center).reshape(-1, 2)
        return _join(pts, None, np.tile(lengths, self.count), True)[0]

    @cached_property
    def segments(self) -> tuple[Segment, ...]:  # type: ignore[override]
        """The segments of all copies, the copies' curves as :class:`~rotorcad.curves.Mapped`."""
        pts, tan = self._turned
        unit = self.unit.segments
        bounds = np.cumsum([0] + [len(s.points) for s in unit])
        segs: list[Segment] = []
        for k in range(self.count):
            turn = 2.0 * np.pi * k / self.count
            for j, seg in enumerate(unit):
                curve = seg.curve if k == 0 else rotated(seg.curve, turn, self.center)
                a, b = bounds[j], bounds[j + 1]
                segs.append(Segment(seg.name, curve, seg.s, pts[k, a:b], tan[k, a:b]))
        return tuple(segs)


def _join(p: Array, t: Array | None, lengths: Array, closed: bool) -> tuple[Array, Array | None, Array]:
    """Join a chain's samples.

    The first point of a segment is dropped where it repeats (within 1e-9 mm) the previous
    segment's last point, and so is a closed chain's repeated end point.

    Parameters
    ----------
    p, t : (n, 2) float arrays
        Points (mm) and unit tangents of all segments, in order (``t`` may be None: points only).
    lengths : (k,) int array
        Number of samples of each segment (summing to n).
    closed : bool
        Whether the chain is closed.

    Returns
    -------
    points, tangents : (m, 2) float arrays
        The joined samples.
    index : (m,) int array
        The segment of every sample.
    """
    idx = np.repeat(np.arange(len(lengths)), lengths)
    keep = np.ones(len(p), dtype=bool)
    starts = np.cumsum(lengths) - lengths
    if len(lengths) > 1:
        gap = np.hypot(*(p[starts[1:]] - p[starts[1:] - 1]).T)
        keep[starts[1:][gap < 1e-9]] = False
    if not keep.all():  # compress: not the slow path of a boolean mask on a 2-D array
        p, idx = np.compress(keep, p, axis=0), idx[keep]
        t = None if t is None else np.compress(keep, t, axis=0)
    if closed and len(p) > 1 and np.hypot(*(p[0] - p[-1])) < 1e-9:
        p, t, idx = p[:-1], None if t is None else t[:-1], idx[:-1]
    return p, t, idx


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

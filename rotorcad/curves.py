"""Analytic plane curves with exact unit tangents, and sampling to a chord tolerance.

Every curve maps a parameter ``s`` to points and unit tangents computed from its definition
(never from differences of sampled points). ``s0`` and ``s1`` give the part of the curve in use
and the direction of travel: ``evaluate`` returns the tangent along the travel from ``s0`` to
``s1``. Curves that bound a body are travelled counter-clockwise around it, so the outward
normal is the tangent turned clockwise (:func:`rotorcad.geometry.perp_cw`).

Curve types: :class:`Line`, :class:`Arc`, :class:`Involute` (ordinary involute),
:class:`PointPath` (trochoid / extended involute: the path of a point of one moving body seen
from another, optionally offset, which is the envelope of a circle), :class:`Spline` (cubic
spline through measured points), :class:`Mapped` (a curve under an affine map) and, in
:mod:`rotorcad.envelope`, the generated (conjugate) curve.
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass, field
from functools import cached_property

import numpy as np

from rotorcad.geometry import Array, as_points, cross, dots, filled, normalize, perp_cw
from rotorcad.kinematics import Body


class Curve:
    """Base of all curves: subclasses define ``s0``, ``s1`` and :meth:`frame`."""

    s0: float
    s1: float

    def frame(self, s: Array) -> tuple[Array, Array]:
        """Return points and unit tangents at parameters ``s``, tangents along increasing ``s``.

        Parameters
        ----------
        s : (n,) float array
            Curve parameters (their meaning and unit depend on the curve type).

        Returns
        -------
        points : (n, 2) float array, mm
            Points on the curve.
        tangents : (n, 2) float array
            Unit tangents along increasing ``s``.
        """
        raise NotImplementedError  # pragma: no cover - abstract

    @property
    def direction(self) -> float:
        """Sign of the travel: 1.0 when ``s1 >= s0`` (towards larger ``s``), else -1.0."""
        return 1.0 if self.s1 >= self.s0 else -1.0

    def evaluate(self, s: Array | float) -> tuple[Array, Array]:
        """Return points and unit tangents at ``s``, tangents along the direction of travel (``s0`` to ``s1``).

        Parameters
        ----------
        s : float or (n,) float array
            Curve parameters (a scalar is read as one parameter).

        Returns
        -------
        points : (n, 2) float array, mm
            Points on the curve.
        tangents : (n, 2) float array
            Unit tangents along the travel: those of :meth:`frame` times :attr:`direction`.
        """
        s = np.atleast_1d(np.asarray(s, dtype=float))
        p, t = self.frame(s)
        return p, t * self.direction

    def point(self, s: float) -> Array:
        """Return the point at parameter ``s``.

        Parameters
        ----------
        s : float
            Curve parameter.

        Returns
        -------
        (2,) float array, mm
            The point.
        """
        return self.evaluate(s)[0][0]

    @property
    def start(self) -> Array:
        """Point where the travel starts (at ``s0``), (2,) float array, mm."""
        return self._start.copy()

    @property
    def end(self) -> Array:
        """Point where the travel ends (at ``s1``), (2,) float array, mm."""
        return self._end.copy()

    @cached_property
    def _start(self) -> Array:
        """:attr:`start`, evaluated once (a curve does not change; readers ask for its ends many times)."""
        return self.point(self.s0)

    @cached_property
    def _end(self) -> Array:
        """:attr:`end`, evaluated once."""
        return self.point(self.s1)

    def trimmed(self, s0: float, s1: float) -> Curve:
        """Return the same geometry travelled from ``s0`` to ``s1``.

        Parameters
        ----------
        s0, s1 : float
            New start and end parameters; ``s1 < s0`` travels towards smaller ``s``.

        Returns
        -------
        Curve
            A copy of the curve with the new range (all other fields kept).
        """
        return dataclasses.replace(self, s0=float(s0), s1=float(s1))

    def reversed(self) -> Curve:
        """Return the same geometry travelled backwards, from ``s1`` to ``s0``.

        Returns
        -------
        Curve
            :meth:`trimmed` with the ends swapped.
        """
        return self.trimmed(self.s1, self.s0)

    def arc_center(self) -> Array | None:
        """Centre of curvature if the curve is a circular arc, else None."""
        return None

    def is_corner(self) -> bool:
        """Return True for a zero-radius arc: a sharp corner, one point with a fan of normals."""
        return False


@dataclass(frozen=True)
class Line(Curve):
    """Straight segment from ``a`` to ``b``; ``s`` is the length from ``a``."""

    a: tuple[float, float]
    b: tuple[float, float]
    s0: float = 0.0
    s1: float = field(default=float("nan"))

    def __post_init__(self) -> None:
        if np.isnan(self.s1):
            object.__setattr__(self, "s1", float(np.hypot(*np.subtract(self.b, self.a))))

    @cached_property
    def _start_and_direction(self) -> tuple[Array, Array]:
        """The start point ``a`` (2,) and the unit direction from ``a`` to ``b`` (2,)."""
        return np.asarray(self.a, dtype=float), normalize(np.subtract(self.b, self.a, dtype=float))

    def frame(self, s: Array) -> tuple[Array, Array]:
        """Return points and unit tangents at parameters ``s``.

        Parameters
        ----------
        s : (n,) float array, mm
            Length from ``a`` along the line.

        Returns
        -------
        points : (n, 2) float array, mm
            ``a + s d`` with ``d`` the unit direction from ``a`` to ``b``.
        tangents : (n, 2) float array
            ``d`` at every point.
        """
        a, d = self._start_and_direction
        if np.ndim(s) != 1:
            p = a + np.multiply.outer(s, d)
            t = np.empty_like(p)
            t[...] = d
            return p, t
        p = np.empty((len(s), 2))  # a + outer(s, d), the same numbers, by columns
        np.add(a[0], s * d[0], out=p[:, 0])
        np.add(a[1], s * d[1], out=p[:, 1])
        return p, filled(len(s), d)


@dataclass(frozen=True)
class Arc(Curve):
    """Circular arc about ``center``; ``s`` is the polar angle about the centre."""

    center: tuple[float, float]
    radius: float
    s0: float
    s1: float

    def frame(self, s: Array) -> tuple[Array, Array]:
        """Return points and unit tangents at parameters ``s``.

        Parameters
        ----------
        s : (n,) float array, rad
            Polar angle about ``center``.

        Returns
        -------
        points : (n, 2) float array, mm
            ``center + radius (cos s, sin s)``.
        tangents : (n, 2) float array
            ``(-sin s, cos s)``: counter-clockwise, along increasing ``s``.
        """
        c, si = np.cos(s), np.sin(s)
        t = np.empty((*np.shape(s), 2))
        t[..., 0] = -si
        t[..., 1] = c
        p = np.empty_like(t)
        p[..., 0] = c
        p[..., 1] = si
        return np.asarray(self.center, dtype=float) + self.radius * p, t

    def arc_center(self) -> Array | None:
        """Return the centre of the arc, (2,) float array, mm."""
        return np.asarray(self.center, dtype=float)

    def is_corner(self) -> bool:
        """Return True when the radius is zero: a sharp corner, one point with a fan of normals."""
        return self.radius == 0.0


@dataclass(frozen=True)
class GeneralisedArc(Curve):
    """A quarter of Stosic's generalised arc (x/a)^p + (y/b)^q = 1 between its two axis points.

    Points are ``center + e1 cos^(2/p) s + e2 sin^(2/q) s`` for s in [0, pi/2]: the end on ``e1``
    (s = 0) has its tangent along ``e2`` and the end on ``e2`` (s = pi/2) along ``e1`` for
    exponents above 1, so the arc joins a line or circle tangentially at both ends. p = q = 2 with
    |e1| = |e2| is a circular quarter, with |e1| != |e2| an elliptic one (Stosic & Hanjalic 1997; Stosic,
    Smith & Kovacevic, *Screw Compressors*, 2005, sec. 2.4, where the N rack uses it).

    Parameters
    ----------
    center : tuple of float
        Centre of the generalised ellipse, mm.
    e1, e2 : tuple of float
        Its two semi-axes as vectors (mm); |e1| = a, |e2| = b.
    p, q : float
        Exponents on the ``e1`` and ``e2`` coordinates, at least 1.
    s0, s1 : float
        Parameter range in use and its direction of travel, within [0, pi/2].
    """

    center: tuple[float, float]
    e1: tuple[float, float]
    e2: tuple[float, float]
    p: float = 2.0
    q: float = 2.0
    s0: float = 0.0
    s1: float = np.pi / 2

    def frame(self, s: Array) -> tuple[Array, Array]:
        """Return points and unit tangents at parameters ``s``.

        Parameters
        ----------
        s : (n,) float array, rad
            Parameter of the generalised arc; values outside [0, pi/2] are clipped to it.

        Returns
        -------
        points : (n, 2) float array, mm
            ``center + e1 cos^(2/p) s + e2 sin^(2/q) s``.
        tangents : (n, 2) float array
            Unit tangents along increasing ``s``, from the derivative times the positive factor
            ``sin^(1-2/q) s cos^(1-2/p) s`` (finite and non-zero at both ends).
        """
        s = np.clip(np.asarray(s, dtype=float), 0.0, np.pi / 2)
        c, si = np.cos(s), np.sin(s)
        e1, e2 = np.asarray(self.e1, dtype=float), np.asarray(self.e2, dtype=float)
        p = np.asarray(self.center, dtype=float) + np.multiply.outer(c ** (2 / self.p), e1)
        p = p + np.multiply.outer(si ** (2 / self.q), e2)
        # d/ds times the positive factor sin^(1-2/q) cos^(1-2/p): finite and non-zero at both ends
        t = np.multiply.outer(-(2 / self.p) * si ** (2 - 2 / self.q), e1)
        t = t + np.multiply.outer((2 / self.q) * c ** (2 - 2 / self.p), e2)
        return p, normalize(t)


@dataclass(frozen=True)
class Involute(Curve):
    """Ordinary involute of the base circle ``base_radius`` about the origin.

    p(u) = r_b R(theta0 + h u) (1, -h u), with roll angle u >= 0 and hand h = +1 (unwinding
    counter-clockwise) or -1. Its polar angle is theta0 + h inv(alpha) with tan(alpha) = u
    (ISO 21771 involute function); the tangent is (cos(theta0 + h u), sin(theta0 + h u)).
    """

    base_radius: float
    theta0: float
    hand: float
    s0: float
    s1: float

    def frame(self, s: Array) -> tuple[Array, Array]:
        """Return points and unit tangents at parameters ``s``.

        Parameters
        ----------
        s : (n,) float array, rad
            Roll angle u.

        Returns
        -------
        points : (n, 2) float array, mm
            ``r_b R(theta0 + h u) (1, -h u)``.
        tangents : (n, 2) float array
            Unit tangents along increasing ``s``: ``(cos(theta0 + h u), sin(theta0 + h u))`` for
            u >= 0, its opposite for u < 0.
        """
        ang = self.theta0 + self.hand * s
        c, si = np.cos(ang), np.sin(ang)
        hu = self.hand * s
        p = self.base_radius * np.stack([c + hu * si, si - hu * c], axis=-1)
        t = np.stack([c, si], axis=-1) * np.sign(s + 1e-300)[..., None]
        return p, t


@dataclass(frozen=True)
class PointPath(Curve):
    """Path of a point carried by one body seen from another: a trochoid (extended involute).

    ``carried`` is a point fixed in the ``carrier`` body (given in the fixed frame at t = 0), the path is
    expressed in the ``observer`` body's frame, and ``s`` is the motion parameter t. For a rack
    point and a rotor of pitch radius r_w this is the extended involute with
    |p|^2 = a_x^2 + (a_y + r_w t)^2. ``offset`` moves every point by that distance along the
    normal turned clockwise from the tangent of increasing t: the envelope of a circle of that
    radius centred on the carried point (tool tip fillet, Litvin ch. 6). Where the offset exceeds
    the path's radius of curvature the offset curve has cusps and runs backwards there; the
    tangent returned is still the path's (the envelope tangent), so such parts are trimmed by
    the caller (undercut).
    """

    carried: tuple[float, float]
    carrier: Body
    observer: Body
    s0: float
    s1: float
    offset: float = 0.0

    def frame(self, s: Array) -> tuple[Array, Array]:
        """Return points and unit tangents at parameters ``s``.

        Parameters
        ----------
        s : (n,) float array, rad
            Motion parameter t (male rotation angle).

        Returns
        -------
        points : (n, 2) float array, mm
            The carried point in the observer's frame, moved by ``offset`` along the tangent turned
            clockwise.
        tangents : (n, 2) float array
            Unit tangents of the path (not of the offset curve) along increasing ``s``: the
            relative velocity of the carried point, in the observer's frame.
        """
        a = np.broadcast_to(np.asarray(self.carried, dtype=float), (len(s), 2))
        x = self.carrier.to_fixed(a, s)
        rel = self.carrier.velocity_at(x) - self.observer.velocity_at(x)
        t = normalize(self.observer.vectors_to_body(rel, s))
        p = self.observer.to_body(x, s)
        if self.offset:
            p = p + self.offset * perp_cw(t)
        return p, t


@dataclass(frozen=True)
class Mapped(Curve):
    """``curve`` under the affine map p -> A p + b (rotation, mirror, scaling).

    A map with negative determinant reverses orientation; pass such curves through
    :meth:`Curve.reversed` if they must keep bounding a body counter-clockwise.
    """

    curve: Curve
    matrix: tuple[tuple[float, float], tuple[float, float]]
    shift: tuple[float, float] = (0.0, 0.0)
    s0: float = float("nan")
    s1: float = float("nan")

    def __post_init__(self) -> None:
        if np.isnan(self.s0):
            object.__setattr__(self, "s0", self.curve.s0)
            object.__setattr__(self, "s1", self.curve.s1)

    @cached_property
    def _map(self) -> tuple[Array, Array]:
        """The transposed matrix (2, 2) and the shift (2,), mm, as arrays (made once)."""
        return np.asarray(self.matrix, dtype=float).T.copy(), np.asarray(self.shift, dtype=float)

    @cached_property
    def _similar(self) -> bool:
        """Whether the map keeps circles circles: A A^T = |det A| I (to numpy's ``allclose``)."""
        (a, b), (c, d) = self.matrix
        det = abs(a * d - b * c)
        aat = ((a * a + b * b, a * c + b * d), (a * c + b * d, c * c + d * d))
        eye = ((det, 0.0), (0.0, det))
        return all(abs(aat[i][j] - eye[i][j]) <= 1e-14 + 1e-5 * abs(eye[i][j]) for i in (0, 1) for j in (0, 1))

    def frame(self, s: Array) -> tuple[Array, Array]:
        """Return points and unit tangents at parameters ``s``.

        Parameters
        ----------
        s : (n,) float array
            Parameters of the mapped ``curve``.

        Returns
        -------
        points : (n, 2) float array, mm
            ``A p + b`` for the points p of ``curve``.
        tangents : (n, 2) float array
            ``A t`` for the tangents t of ``curve``, normalised: along increasing ``s``.
        """
        p, t = self.curve.frame(s)
        if self._identity:  # A p = p exactly for finite points: skip the products
            return p + self._map[1], normalize(t)
        mt, shift = self._map
        return p @ mt + shift, normalize(t @ mt)

    @cached_property
    def _identity(self) -> bool:
        """Whether the matrix is the identity (an unstretched tool, a shifted female piece)."""
        return tuple(map(tuple, self.matrix)) == ((1.0, 0.0), (0.0, 1.0))

    def is_corner(self) -> bool:
        """Return whether ``curve`` is a corner (a point stays a point under the map)."""
        return self.curve.is_corner()

    def arc_center(self) -> Array | None:
        """Return the mapped centre of a circular arc, or None.

        None when ``curve`` is no circular arc, or when the map does not keep circles circles
        (A A^T != |det A| I, e.g. a stretch).

        Returns
        -------
        (2,) float array, mm, or None
            ``A c + b`` for the centre c of ``curve``.
        """
        c = self.curve.arc_center()
        if c is None:
            return None
        if not self._similar:
            return None
        mt, shift = self._map
        return mt.T @ c + shift


def rotated(curve: Curve, angle: float, center: object = (0.0, 0.0)) -> Mapped:
    """``curve`` turned by ``angle`` about ``center``."""
    c, s = np.cos(angle), np.sin(angle)
    m = ((c, -s), (s, c))
    ctr = np.asarray(center, dtype=float)
    shift = ctr - np.asarray(m) @ ctr
    return Mapped(curve, m, (float(shift[0]), float(shift[1])))


def mirrored(curve: Curve, angle: float = 0.0) -> Curve:
    """Mirror ``curve`` in the line through the origin at ``angle``, travelled backwards.

    Travelled backwards so that a boundary stays counter-clockwise.

    Parameters
    ----------
    curve : Curve
        The curve to mirror.
    angle : float, rad
        Direction of the mirror line through the origin.

    Returns
    -------
    Curve
        The mirrored curve, reversed.
    """
    c, s = np.cos(2 * angle), np.sin(2 * angle)
    return Mapped(curve, ((c, s), (s, -c))).reversed()


@dataclass(frozen=True)
class Spline(Curve):
    """Cubic spline through (or, with ``smoothing`` > 0, near) measured points.

    Parameterised by cumulative chord length; tangents are the spline's exact derivative.
    ``periodic`` closes the curve with continuous tangent and curvature. The smoothing value
    is scipy's ``s`` (sum of squared residuals allowed, mm^2).
    """

    knots: tuple
    s0: float
    s1: float
    periodic: bool = False

    @staticmethod
    def fit(points: Array, smoothing: float = 0.0, periodic: bool = False) -> Spline:
        """Fit a cubic spline through (or near) measured points.

        Repeated consecutive points are dropped; two or three points give a spline of degree 1 or
        2 (a line or a parabola). With ``periodic`` a last point equal to the first is dropped and
        the curve is closed.

        Parameters
        ----------
        points : (n, 2) float array, mm
            Measured points, in order.
        smoothing : float, mm^2
            scipy's ``s``: sum of squared residuals allowed (0: through the points).
        periodic : bool
            Close the curve with continuous tangent and curvature.

        Returns
        -------
        Spline
            Parameterised by cumulative chord length, from 0 to the total chord length (mm).
        """
        pts = as_points(points)
        if periodic and np.allclose(pts[0], pts[-1]):
            pts = pts[:-1]
        if periodic:
            pts = np.vstack([pts, pts[:1]])
        keep = np.concatenate([[True], np.hypot(*np.diff(pts, axis=0).T) > 0.0])
        pts = pts[keep]
        u = np.concatenate([[0.0], np.cumsum(np.hypot(*np.diff(pts, axis=0).T))])
        k = 3 if periodic else min(3, len(pts) - 1)  # a run of two or three points: a line or a parabola
        from scipy import interpolate  # scipy.interpolate only for a spline (0.4 s to import)

        tck, _ = interpolate.splprep(pts.T, u=u, s=smoothing, k=k, per=int(periodic), quiet=2)
        return Spline(knots=(tck[0], tuple(tck[1]), tck[2]), s0=0.0, s1=float(u[-1]), periodic=periodic)

    def frame(self, s: Array) -> tuple[Array, Array]:
        """Return points and unit tangents at parameters ``s``.

        Parameters
        ----------
        s : (n,) float array, mm
            Cumulative chord length parameter.

        Returns
        -------
        points : (n, 2) float array, mm
            Points of the spline.
        tangents : (n, 2) float array
            The spline's exact derivative, normalised: along increasing ``s``.
        """
        from scipy import interpolate

        tck = [self.knots[0], list(self.knots[1]), self.knots[2]]
        p = np.stack(interpolate.splev(s, tck), axis=-1)
        d = np.stack(interpolate.splev(s, tck, der=1), axis=-1)
        return p, normalize(d)


def turning_angle(t0: Array, t1: Array) -> Array:
    """Signed angle from unit tangents ``t0`` to ``t1``."""
    return np.arctan2(cross(t0, t1), dots(t0, t1))


def sample_curve(curve: Curve, tolerance: float, minimum: int = 2, passes: int = 5) -> tuple[Array, Array, Array]:
    """Sample ``curve`` so that straight chords deviate from it by at most ``tolerance``.

    Returns the parameters, points and unit tangents of the samples; every parameter is evaluated
    once.

    The sagitta of a chord of length L whose end tangents turn by d(psi) is L*|d(psi)|/8 for a
    circular arc; each interval is split uniformly in ``s`` until every estimate is within the
    tolerance (a few vectorised passes, evaluating only the new parameters). The middle of every
    interval is then checked against its chord (an inflection). Each pass evaluates the curve
    once: the new parameters together with the middles of the intervals they make, which the
    check needs should the pass be the last.

    Parameters
    ----------
    curve : Curve
        The curve, sampled from ``curve.s0`` to ``curve.s1``.
    tolerance : float, mm
        Largest chord error.
    minimum : int
        Fewest samples (at least 17 are taken).
    passes : int
        Most refinement passes of each kind.

    Returns
    -------
    s : (n,) float array
        Parameters along the travel.
    points : (n, 2) float array, mm
        Points at ``s``.
    tangents : (n, 2) float array
        Unit tangents along the travel at ``s``.
    """
    s = np.linspace(curve.s0, curve.s1, max(minimum, 17))
    p, t, q = _evaluate_with_middles(curve, s)
    for _ in range(passes):
        d = p[1:] - p[:-1]
        chord = np.hypot(d[:, 0], d[:, 1])
        sag = _finite(chord * np.abs(turning_angle(t[:-1], t[1:])) / 8.0)
        parts = np.sqrt(sag / tolerance) * 1.05
        if (parts <= 1.0).all():  # n = 1 everywhere
            break
        n = np.maximum(np.ceil(parts).astype(int), 1)
        s, p, t, q = _split(curve, s, p, t, n)
    # the end tangents of an interval around an inflection are parallel although the curve bulges
    # between them: check the middle of every interval against its chord and split where needed
    for _ in range(passes):
        d = p[1:] - p[:-1]
        length = np.hypot(d[:, 0], d[:, 1])
        off = _finite(np.abs(cross(d, q - p[:-1])) / np.where(length > 0, length, 1.0))
        n = np.where(off > tolerance, 2, 1) * np.maximum(np.ceil(np.sqrt(off / tolerance)).astype(int), 1)
        if (n == 1).all():
            break
        s, p, t, q = _split(curve, s, p, t, n)
    return s, p, t


def _finite(values: Array) -> Array:
    """``np.nan_to_num(values, nan=0.0)``, skipped where every value is finite (the usual case)."""
    return values if np.isfinite(values).all() else np.nan_to_num(values, nan=0.0)


def _evaluate_with_middles(curve: Curve, s: Array, extra: Array | None = None) -> tuple[Array, Array, Array]:
    """Return points and tangents at ``extra`` and the points at the middles of the intervals of ``s``.

    ``extra`` defaults to ``s``. Points and tangents are (m, 2) each, the middles (len(s) - 1, 2):
    one evaluation of the curve.
    """
    at = s if extra is None else extra
    p, t = curve.evaluate(np.concatenate([at, 0.5 * (s[:-1] + s[1:])]))
    return p[: len(at)], t[: len(at)], p[len(at) :]


def _split(
    curve: Curve, s: Array, p: Array, t: Array, n: Array, middles: bool = True
) -> tuple[Array, Array, Array, Array | None]:
    """Split intervals as :func:`split_intervals` does, optionally with the middles of the new intervals.

    With ``middles``, the fourth result is the points at the middles of the new intervals,
    (len - 1, 2), from the same evaluation (else None).
    """
    parts = np.maximum(np.asarray(n, dtype=int), 1)  # interval i becomes parts[i] intervals
    if (parts == 1).all():
        return s, p, t, (_evaluate_with_middles(curve, s, s[:0])[2] if middles else None)
    # every sample of the refined chain but the last lies in an old interval j, k steps of
    # (s[j+1] - s[j]) / parts[j] after its start (k = 0: the old sample itself)
    j = np.repeat(np.arange(len(parts)), parts)
    k = np.arange(len(j)) - np.repeat(np.cumsum(parts) - parts, parts)
    new = k > 0
    jn = j[new]
    s_new = s[jn] + (s[1:] - s[:-1])[jn] * k[new] / parts[jn]
    # the refined chain as the old samples followed by the new ones, reordered
    order = np.empty(len(j) + 1, dtype=np.intp)
    order[:-1] = np.where(new, len(s) - 1 + np.cumsum(new), j)
    order[-1] = len(s) - 1
    s_all = np.concatenate([s, s_new]).take(order)
    if middles:
        p_new, t_new, q = _evaluate_with_middles(curve, s_all, s_new)
    else:
        (p_new, t_new), q = curve.evaluate(s_new), None
    return s_all, np.concatenate([p, p_new]).take(order, axis=0), np.concatenate([t, t_new]).take(order, axis=0), q


def split_intervals(curve: Curve, s: Array, p: Array, t: Array, n: Array) -> tuple[Array, Array, Array]:
    """Split interval i of the samples into ``n[i]`` equal parts in ``s``.

    Only the new parameters are evaluated, and the order of travel is kept (a generated curve runs
    to smaller parameters).

    Parameters
    ----------
    curve : Curve
        The sampled curve.
    s : (m,) float array
        Parameters along the travel.
    p, t : (m, 2) float arrays
        Points (mm) and unit tangents at ``s``.
    n : (m - 1,) int array
        Parts of each interval (1: kept as it is).

    Returns
    -------
    s, p, t : arrays
        The refined samples, (m', ) and (m', 2).
    """
    return _split(curve, s, p, t, n, middles=False)[:3]


def sample_parameters(curve: Curve, tolerance: float, minimum: int = 2, passes: int = 5) -> Array:
    """Return parameters at which straight chords deviate from ``curve`` by at most ``tolerance``.

    See :func:`sample_curve`, whose first result this is.

    Parameters
    ----------
    curve : Curve
        The curve, sampled from ``curve.s0`` to ``curve.s1``.
    tolerance : float, mm
        Largest chord error.
    minimum : int
        Fewest samples (at least 17 are taken).
    passes : int
        Most refinement passes of each kind.

    Returns
    -------
    (n,) float array
        Parameters along the travel.
    """
    return sample_curve(curve, tolerance, minimum, passes)[0]


def chord_error(curve: Curve, s: Array, probes: int = 8) -> float:
    """Return the largest distance from the curve to the chords between the samples at ``s``.

    Measured at ``probes`` points inside every interval; used to check :func:`sample_parameters`.

    Parameters
    ----------
    curve : Curve
        The sampled curve.
    s : (m,) float array
        Parameters of the samples, in order.
    probes : int
        Points measured inside every interval.

    Returns
    -------
    float, mm
        The largest distance (0.0 when there is no interval).
    """
    p, _ = curve.evaluate(s)
    frac = (np.arange(1, probes + 1) / (probes + 1))[None, :]
    sm = s[:-1, None] + np.diff(s)[:, None] * frac
    q, _ = curve.evaluate(sm.ravel())
    q = q.reshape(len(s) - 1, probes, 2)
    a = p[:-1, None, :]
    d = (p[1:] - p[:-1])[:, None, :]
    length = np.linalg.norm(d, axis=-1)
    dist = np.abs(cross(d, q - a)) / np.where(length > 0, length, 1.0)
    return float(dist.max()) if dist.size else 0.0


__all__ = [
    "Arc",
    "Curve",
    "GeneralisedArc",
    "Involute",
    "Line",
    "Mapped",
    "PointPath",
    "Spline",
    "chord_error",
    "mirrored",
    "rotated",
    "sample_curve",
    "sample_parameters",
    "split_intervals",
]

"""DXF splines of an exact outline: one C1 cubic B-spline per profile segment, its deviation measured.

A rotor outline is a chain of segments (:class:`rotorcad.profile.Profile`), each an exact curve
(line, arc, involute, trochoid, generated conjugate, spline) with analytic unit tangents; where two
segments meet at a sharp corner (a rotor's tip, a rack's corner) the tangent jumps. One spline
through the whole outline smooths every corner over (a global interpolation through the samples
swung 0.2 mm past the sharp tip of the rack-involute sample's male). Here each segment gets its own
spline, so a corner stays a corner, and the spline of a segment is the C1 piecewise cubic Hermite
interpolant of samples of its exact curve with their exact tangents: between samples p0, p1 with
unit tangents t0, t1 and chord L = |p1 - p0|, the cubic Bezier with control points
p0, p0 + L t0 / 3, p1 - L t1 / 3, p1 (de Boor, *A Practical Guide to Splines*, ch. IV, cubic
Hermite interpolation on chord-length parameters). The pieces are one B-spline of degree 3 with
double interior knots at the cumulative chord lengths: the tangents on both sides of a knot are
the same exact unit tangent, so the curve is C1 there (Piegl and Tiller, *The NURBS Book*, sec.
2.2 and eq. 3.9: a knot of multiplicity 2 leaves a cubic C1), and its 2 n + 2 control points are
the Bezier points without the samples (each sample lies on the segment between its neighbours).

The deviation from the exact curve is measured, not assumed (:func:`interval_deviation`), and the
samples are refined where it is over the tolerance (:func:`segment_spline`); what is written is
what was measured.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from exports.hermite import distance_to_chains, hermite_cubic
from rotorcad.curves import Curve
from rotorcad.geometry import rotate

if TYPE_CHECKING:
    from rotorcad.profile import Profile

PROBES = 16
"""Steps per Hermite interval at which the cubic and the exact curve are compared (both ways)."""

PASSES = 12
"""Most refinement passes of :func:`segment_spline`."""


class SplineToleranceError(ValueError):
    """The spline of a segment stays farther from its exact curve than the tolerance.

    Parameters
    ----------
    segment : str
        The segment's name.
    deviation : float, mm
        The deviation reached.
    tolerance : float, mm
        The tolerance asked.
    """

    def __init__(self, segment: str, deviation: float, tolerance: float) -> None:
        super().__init__(
            f"the spline of the segment '{segment}' stays {deviation * 1e3:.3g} um from its exact curve, "
            f"more than the tolerance {tolerance * 1e3:.3g} um"
        )
        self.segment = segment
        self.deviation = deviation


@dataclass(frozen=True)
class SplinePiece:
    """A non-rational B-spline of one profile segment, as a DXF SPLINE entity holds it.

    Parameters
    ----------
    name : str
        The segment's name (e.g. "tip arc").
    control_points : (m, 2) float array, mm
        Control points.
    knots : (m + degree + 1,) float array, mm
        Knot vector, clamped (the first and last knot degree + 1 times), in chord length.
    degree : int
        Degree (3).
    deviation : float, mm
        Largest distance between the spline and the exact curve, measured (:func:`interval_deviation`).
    """

    name: str
    control_points: np.ndarray
    knots: np.ndarray
    degree: int
    deviation: float

    def placed(self, turn: float = 0.0, shift: tuple[float, float] = (0.0, 0.0)) -> SplinePiece:
        """Return the piece turned by ``turn`` (rad, about the origin) and moved by ``shift`` (mm).

        A B-spline is affine invariant: its control points are moved, its knots kept.
        """
        moved = rotate(self.control_points, turn) + np.asarray(shift, dtype=float)
        return SplinePiece(self.name, moved, self.knots, self.degree, self.deviation)

    @property
    def start(self) -> np.ndarray:
        """First point, (2,) mm (the clamped spline starts on its first control point)."""
        return self.control_points[0]

    @property
    def end(self) -> np.ndarray:
        """Last point, (2,) mm."""
        return self.control_points[-1]


def hermite_spline(points: np.ndarray, tangents: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Return the control points and knots of the C1 cubic Hermite B-spline through samples.

    Parameters
    ----------
    points : (n + 1, 2) float array, mm
        Samples, distinct and in order.
    tangents : (n + 1, 2) float array
        Their exact unit tangents, along the travel.

    Returns
    -------
    control_points : (2 n + 2, 2) float array, mm
        p0, then for every interval i: p_i + L_i t_i / 3, p_(i+1) - L_i t_(i+1) / 3; then p_n.
    knots : (2 n + 6,) float array, mm
        Cumulative chord u: u_0 four times, every interior u_i twice, u_n four times.
    """
    p, t = np.asarray(points, dtype=float), np.asarray(tangents, dtype=float)
    chord = np.hypot(*(p[1:] - p[:-1]).T)[:, None]  # (n, 1)
    inner = np.empty((len(chord), 2, 2))
    inner[:, 0] = p[:-1] + chord * t[:-1] / 3.0
    inner[:, 1] = p[1:] - chord * t[1:] / 3.0
    control = np.vstack([p[:1], inner.reshape(-1, 2), p[-1:]])
    u = np.r_[0.0, np.cumsum(chord[:, 0])]
    knots = np.r_[[u[0]] * 4, np.repeat(u[1:-1], 2), [u[-1]] * 4]
    return control, knots


def _sag(points: np.ndarray, middles: np.ndarray) -> np.ndarray:
    """Largest distance of the middles of a chain's steps to their chords, (n,) mm (NaN left out).

    Parameters
    ----------
    points : (n, k + 1, 2) float array, mm
        The chain of each interval.
    middles : (n, k, 2) float array, mm
        The curve at the middle of every step.
    """
    a, b = points[:, :-1], points[:, 1:]
    d = b - a
    w = middles - a
    length2 = np.maximum((d * d).sum(-1), 1e-300)
    foot = np.clip((w * d).sum(-1) / length2, 0.0, 1.0)
    gap = w - foot[..., None] * d
    return np.nan_to_num(np.sqrt((gap * gap).sum(-1)), nan=0.0).max(axis=1)


def interval_deviation(curve: Curve, s: np.ndarray, points: np.ndarray, tangents: np.ndarray) -> np.ndarray:
    """Measure how far the Hermite cubic of every interval strays from the exact curve, both ways.

    In each interval [s_i, s_(i+1)] the exact curve is evaluated at :data:`PROBES` equal steps of
    its parameter (and the middles of the steps), the cubic at as many equal steps of its own.
    The deviation is the larger of (a) the distance of the cubic's points to the exact curve's chain
    plus that chain's sag (the distance of the exact middles to their chords: a point of the chain
    is within it of the curve) and (b) the distance of the exact points to the cubic's chain plus
    the cubic chain's own sag. Both are upper estimates of the one-sided Hausdorff distances
    between the cubic and the exact curve on the interval.

    Parameters
    ----------
    curve : Curve
        The exact curve.
    s : (n + 1,) float array
        Parameters of the samples.
    points, tangents : (n + 1, 2) float arrays
        The samples (mm) and their exact unit tangents.

    Returns
    -------
    (n,) float array, mm
        The deviation of every interval (exact points without contact are left out).
    """
    k = PROBES
    frac = np.arange(k + 1) / k
    half = (np.arange(k) + 0.5) / k
    ds = (s[1:] - s[:-1])[:, None]
    exact, _ = curve.evaluate((s[:-1, None] + ds * frac).ravel())
    exact = exact.reshape(len(ds), k + 1, 2)
    exact[:, 0], exact[:, -1] = points[:-1], points[1:]
    mid, _ = curve.evaluate((s[:-1, None] + ds * half).ravel())
    mid = mid.reshape(len(ds), k, 2)
    cubic = hermite_cubic(points, tangents, frac)
    cubic_mid = hermite_cubic(points, tangents, half)
    chain = np.where(np.isfinite(exact), exact, cubic)  # a missing exact point: the chain skips through the cubic
    sag_exact = _sag(chain, mid)
    sag_cubic = _sag(cubic, cubic_mid)
    out = distance_to_chains(cubic, chain) + sag_exact
    back = distance_to_chains(np.concatenate([exact, mid], axis=1), cubic) + sag_cubic
    return np.maximum(out, back)


def segment_spline(segment, tolerance: float, passes: int = PASSES) -> SplinePiece | None:
    """Return the spline of one profile segment within ``tolerance`` of its exact curve.

    Starts from the segment's own samples; an interval whose measured deviation e is over 0.9 times
    the tolerance is split into ceil((e / (0.9 tolerance))^(1/4)) + 1 equal parameter parts (the
    Hermite cubic's error falls with the fourth power of the spacing where the curve is smooth),
    the new samples evaluated on the exact curve (points without contact dropped), until every
    interval is within it.

    Parameters
    ----------
    segment : rotorcad.profile.Segment
        Samples ``s``, ``points``, ``tangents`` of its exact ``curve``.
    tolerance : float, mm
        Largest deviation of the spline from the curve.
    passes : int
        Most refinement passes.

    Returns
    -------
    SplinePiece or None
        None for a segment of no length (a sharp corner of zero radius, one point).

    Raises
    ------
    SplineToleranceError
        When the spline is still off by more than ``tolerance`` after ``passes`` passes.
    """
    curve = segment.curve
    s, p, t = (np.asarray(a, dtype=float) for a in (segment.s, segment.points, segment.tangents))
    if len(s) < 2 or curve.is_corner() or float(np.hypot(*(p[-1] - p[0]))) + float(np.ptp(p, axis=0).max()) < 1e-12:
        return None
    target = 0.9 * tolerance
    err = interval_deviation(curve, s, p, t)
    for _ in range(passes):
        if err.max() <= target:
            break
        parts = np.where(err > target, np.ceil((err / target) ** 0.25) + 1, 1).astype(int)
        j = np.repeat(np.arange(len(err)), parts)
        k = np.arange(len(j)) - np.repeat(np.cumsum(parts) - parts, parts)
        s_new = np.append(s[j] + (s[j + 1] - s[j]) * (k / parts[j]), s[-1])
        fresh = np.append(k > 0, False)
        p_new, t_new = np.empty((len(s_new), 2)), np.empty((len(s_new), 2))
        p_new[~fresh], t_new[~fresh] = p, t
        p_new[fresh], t_new[fresh] = curve.evaluate(s_new[fresh])
        keep = np.isfinite(p_new).all(axis=1) & np.isfinite(t_new).all(axis=1)
        s, p, t = s_new[keep], p_new[keep], t_new[keep]
        err = interval_deviation(curve, s, p, t)
    deviation = float(err.max())
    if deviation > tolerance:
        raise SplineToleranceError(segment.name, deviation, tolerance)
    distinct = np.r_[True, np.hypot(*(p[1:] - p[:-1]).T) > 0]  # a repeated sample has no chord to carry a tangent
    control, knots = hermite_spline(p[distinct], t[distinct])
    return SplinePiece(segment.name, control, knots, 3, deviation)


def profile_splines(profile, tolerance: float) -> list[SplinePiece]:
    """Return one spline per segment of a closed profile, each within ``tolerance`` of its curve.

    Parameters
    ----------
    profile : rotorcad.profile.Profile
        The outline (its segments with their exact curves), sampled at any chord tolerance: the
        samples are refined where the spline needs them.
    tolerance : float, mm
        Largest deviation of every spline from its exact curve.

    Returns
    -------
    list of SplinePiece
        In the profile's order; segments of no length (sharp corners) are left out, so that one
        piece ends where the next starts.
    """
    pieces = (segment_spline(seg, tolerance) for seg in profile.segments)
    return [piece for piece in pieces if piece is not None]


def placed_splines(
    outline: Callable[[float], Profile], tolerance: float, turn: float = 0.0, shift: tuple[float, float] = (0.0, 0.0)
) -> list[SplinePiece]:
    """Return the DXF splines of a rotor outline, placed, each within ``tolerance`` of its exact segment.

    The outline's segments sampled to ten times the tolerance in chord are the start (as the exact
    STEP's); the samples are refined on the exact curves until the measured deviation is within it.

    Parameters
    ----------
    outline : callable
        ``outline(chord)``: the exact outline sampled to a chord tolerance (mm), own frame.
    tolerance : float, mm
        Largest deviation of every spline from its exact curve.
    turn : float, rad
        Counter-clockwise turn about the body's own axis.
    shift : (float, float), mm
        Where the body's axis is placed.

    Returns
    -------
    list of SplinePiece

    Raises
    ------
    SplineToleranceError
        Where a segment's spline cannot be brought within ``tolerance``.
    """
    return [piece.placed(turn, shift) for piece in profile_splines(outline(10 * tolerance), tolerance)]

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

from exports.hermite import refine_curves
from rotorcad.geometry import rotate

if TYPE_CHECKING:
    from rotorcad.profile import Profile

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


def segment_spline(segment, tolerance: float, passes: int = PASSES) -> SplinePiece | None:
    """Return the spline of one profile segment within ``tolerance`` of its exact curve.

    Starts from the segment's own samples, refined (:func:`exports.hermite.refine_samples`) until
    every interval's measured deviation is within 0.9 times the tolerance.

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
    return segment_splines([segment], tolerance, passes)[0]


def _has_length(segment) -> bool:
    """Tell whether a segment has a spline: two samples or more, not a sharp corner, some length."""
    s, p = np.asarray(segment.s, dtype=float), np.asarray(segment.points, dtype=float)
    if len(s) < 2 or segment.curve.is_corner():
        return False
    return float(np.hypot(*(p[-1] - p[0]))) + float(np.ptp(p, axis=0).max()) >= 1e-12


def segment_splines(segments, tolerance: float, passes: int = PASSES) -> list[SplinePiece | None]:
    """Return the spline of every segment (:func:`segment_spline`), their samples refined all at once.

    The refinement (:func:`exports.hermite.refine_curves`) measures the intervals of every segment
    together; each segment gets the samples and the spline :func:`segment_spline` gives it alone.

    Parameters
    ----------
    segments : sequence of rotorcad.profile.Segment
        The segments.
    tolerance : float, mm
        Largest deviation of every spline from its curve.
    passes : int
        Most refinement passes.

    Returns
    -------
    list of SplinePiece or None
        In order; None for a segment of no length.

    Raises
    ------
    SplineToleranceError
        For the first segment (in order) still off by more than ``tolerance`` after ``passes`` passes.
    """
    out: list[SplinePiece | None] = [None] * len(segments)
    spans = [i for i, seg in enumerate(segments) if _has_length(seg)]
    pieces = [(segments[i].curve, segments[i].s, segments[i].points, segments[i].tangents) for i in spans]
    for i, (_, p, t, err) in zip(spans, refine_curves(pieces, 0.9 * tolerance, passes), strict=True):
        deviation = float(err.max())
        if deviation > tolerance:
            raise SplineToleranceError(segments[i].name, deviation, tolerance)
        distinct = np.r_[True, np.hypot(*(p[1:] - p[:-1]).T) > 0]  # a repeated sample has no chord to carry a tangent
        control, knots = hermite_spline(p[distinct], t[distinct])
        out[i] = SplinePiece(segments[i].name, control, knots, 3, deviation)
    return out


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
    return [piece for piece in segment_splines(profile.segments, tolerance) if piece is not None]


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

"""Sampling an involute gear's tooth to a chord tolerance, in one step, from the curvature of each piece.

The involute's from its roll distance (ISO 21771 sec. 2.3), the fillet's from its exact tangent
turning rate and speed (:meth:`rotorcad.gears.tool.ToolCut.cut`), the two circles' from their
radii: every chord stays within the tolerance of the exact curve (sagitta L^2 / (8 rho)). Half a
tooth is sampled, mirrored, and the tooth patterned (:meth:`rotorcad.profile.Profile.patterned`);
the segment objects with their exact curves are made only when asked for.
"""

from __future__ import annotations

import functools
import math
from typing import TYPE_CHECKING

import numpy as np

from rotorcad.curves import Arc
from rotorcad.gears.tool import as_complex, as_pairs
from rotorcad.geometry import Array
from rotorcad.profile import Profile, Segment, _Sampled

if TYPE_CHECKING:
    from rotorcad.gears.involute_gear import InvoluteGear

CROWDED = np.linspace(0.0, 1.0, 513) ** 3  # grid crowded towards its start, a share of the interval


def span(a: float, b: float, n: int) -> Array:
    """Return ``np.linspace(a, b, n)`` (the same numbers, n >= 2) without its checks.

    The checks cost more than the few samples of a piece.

    Parameters
    ----------
    a, b : float
        First and last value (``b`` exactly).
    n : int
        Number of values, at least 2.

    Returns
    -------
    (n,) float array
        Equally spaced values from ``a`` to ``b``.
    """
    out = np.arange(n) * ((b - a) / (n - 1)) + a
    out[-1] = b
    return out


SAMPLING_MARGIN = 1.05
"""Extra samples over the count the curvature asks for: the sagitta L^2 / (8 rho) holds for a
chord over constant curvature, and the curvature of the involute and the fillet changes along a
chord."""
FILLET_GRID = 513
"""Parameters at which the fillet is evaluated when the gear is made: to check that it stays off
the tooth's centre line and to place its samples from its curvature."""


def arc_intervals(angle: float, radius: float, tolerance: float) -> int:
    """Fewest equal chords of a circular arc within ``tolerance`` of it.

    Parameters
    ----------
    angle : float
        Angle the arc spans, rad.
    radius : float
        Its radius, mm.
    tolerance : float
        Largest chord error, mm.

    Returns
    -------
    int
        ceil(angle / d), at least 1, with d = 4 asin(sqrt(tol / (2 R))) the largest angle of a
        chord whose sagitta R (1 - cos(d / 2)) is the tolerance.
    """
    step = 4.0 * math.asin(math.sqrt(min(tolerance / (2.0 * radius), 0.5)))
    return max(1, math.ceil(abs(angle) / step * (1.0 - 1e-12)))


def involute_parameters(s0: float, s1: float, roll: tuple[float, float], rb: float, tolerance: float) -> Array:
    """Tool-flank parameters that sample the involute to a chord tolerance, in one step.

    The involute's radius of curvature at a point is its roll distance L from the base circle's
    tangency point (ISO 21771 sec. 2.3; L = r_b tan(alpha_y)), and its tangent turns by dL / r_b.
    A chord turning by d(phi) on radius rho has the sagitta rho d(phi)^2 / 8, so the chords of
    equal sagitta are spaced by d(phi) = sqrt(8 tol / L): the number of chords up to L grows as
    (2 / 3) L^(3/2) / (r_b sqrt(8 tol)), and equal steps of L^(3/2) give equal sagittas.

    Parameters
    ----------
    s0, s1 : float
        Tool-flank parameters (mm along the tool's flank) of the piece's start and end.
    roll : (float, float)
        (a0, a1): L = a0 + a1 s, mm and mm per mm.
    rb : float
        Base radius, mm.
    tolerance : float
        Largest chord error, mm.

    Returns
    -------
    (n,) float array
        Parameters from ``s0`` to ``s1`` (both exactly), n >= 2.
    """
    a0, a1 = roll
    w0 = max(a0 + a1 * s0, 0.0) ** 1.5
    w1 = max(a0 + a1 * s1, 0.0) ** 1.5
    n = max(1, math.ceil(2.0 / 3.0 * abs(w1 - w0) / (rb * math.sqrt(8.0 * tolerance)) * SAMPLING_MARGIN))
    s = (span(w0, w1, n + 1) ** (2.0 / 3.0) - a0) / a1
    s[0], s[-1] = s0, s1
    return s


def chord_counts(turning: Array, speed: Array, step: float) -> tuple[Array, Array]:
    """How many chords a cut curve needs up to each parameter of a grid, per unit of tolerance.

    A chord of arc length L over a curve of curvature kappa deviates from it by kappa L^2 / 8 (the
    sagitta L^2 / (8 rho)); where kappa changes sign (an inflection) by the cubic term
    |dkappa/dS| L^3 / (72 sqrt 3) instead (the largest gap between y = a x^3 and its chord over
    an interval centred on the inflection). Chords within a tolerance tol are therefore spaced by
    at most 1 / n(S), n = sqrt(|kappa| / (8 tol)) + (|dkappa/dS| / (72 sqrt(3) tol))^(1/3) (either
    term alone keeps its deviation within the tolerance; their sum keeps the two together within
    it). Over a grid cell of arc length A, turn B = |kappa| A and change C = |dkappa/dS| A of the
    curvature, n integrates to sqrt(A B / (8 tol)) + (A^2 C / (72 sqrt(3) tol))^(1/3): the two
    sums returned, times 1 / sqrt(8 tol) and 1 / (72 sqrt(3) tol)^(1/3).

    Parameters
    ----------
    turning, speed : (m,) float arrays
        dphi/ds (rad per unit of s) and |dP/ds| (mm per unit of s) of the cut curve at m equally
        spaced parameters (:meth:`ToolCut.cut`).
    step : float
        Their spacing, in units of s.

    Returns
    -------
    quadratic, cubic : (m,) float arrays
        Cumulative sums of sqrt(A B) (mm) and (A^2 C)^(1/3) (mm) from the first parameter, 0 there.
    """
    arc = (speed[1:] + speed[:-1]) * (0.5 * step)
    bend = np.abs(turning[1:] + turning[:-1]) * (0.5 * step)
    m = len(turning)
    quadratic, cubic = np.zeros(m), np.zeros(m)
    np.cumsum(np.sqrt(bend * arc), out=quadratic[1:])
    if speed.min() > 0.0:  # no cusp: the curvature is finite everywhere
        np.cumsum(np.cbrt(np.abs(np.diff(turning / speed)) * arc * arc), out=cubic[1:])
    if not (np.isfinite(quadratic[-1]) and np.isfinite(cubic[-1])):
        quadratic, cubic = np.nan_to_num(quadratic), np.nan_to_num(cubic)
    return quadratic, cubic


def grid_parameters(counts: tuple[Array, Array], s0: float, s1: float, tolerance: float) -> Array:
    """Return tool parameters that sample a cut curve to a chord tolerance, in one step, from its curvature.

    The chord count at the grid parameters, N(s) (:func:`chord_counts`), is inverted by linear
    interpolation at equal steps.

    Parameters
    ----------
    counts : two (m,) float arrays
        :func:`chord_counts` on m equally spaced parameters from ``s0`` to ``s1``.
    s0, s1 : float
        Tool parameters of the piece's start and end.
    tolerance : float
        Largest chord error, mm.

    Returns
    -------
    (n,) float array
        Parameters from ``s0`` to ``s1`` (both exactly), n >= 2.
    """
    quadratic, cubic = counts
    total = quadratic * (1.0 / math.sqrt(8.0 * tolerance)) + cubic * (1.0 / math.cbrt(72.0 * math.sqrt(3.0) * tolerance))
    n = max(1, math.ceil(total[-1] * SAMPLING_MARGIN))
    s = np.interp(span(0.0, total[-1], n + 1), total, span(s0, s1, len(total)))
    s[0], s[-1] = s0, s1
    return s


def chords_beyond(z: Array, w: Array, lengths: Array, tolerance: float) -> Array | None:
    """Which pieces of a chain have a chord whose sagitta estimate exceeds ``tolerance``.

    Parameters
    ----------
    z, w : (n,) complex arrays
        Samples of the pieces end to end as x + i y: points (mm) and unit tangents along the travel.
    lengths : (k,) int array
        Samples of each piece.
    tolerance : float
        Largest chord error, mm.

    Returns
    -------
    (k,) bool array or None
        True for a piece with a chord of length L whose exact end tangents turn by d(psi) and
        L |d(psi)| / 8 > tolerance (a circular arc's sagitta; the chords between pieces are not
        checked); None where every chord is within.
    """
    sag = np.abs(z[1:] - z[:-1]) * np.abs(np.angle(w[1:] * np.conj(w[:-1])))
    ends = np.cumsum(lengths)[:-1] - 1  # the chords from one piece's last sample to the next one's first
    sag[ends] = 0.0
    over = ~(sag <= 8.0 * tolerance)
    if not over.any():
        return None
    piece = np.searchsorted(np.cumsum(lengths) - 1, np.nonzero(over)[0], side="right")
    bad = np.zeros(len(lengths), dtype=bool)
    bad[piece] = True
    return bad


def sample_tooth(gear: InvoluteGear, tolerance: float) -> Profile:
    """Sample one tooth from space centre to space centre, counter-clockwise (open chain).

    The upper half's flank pieces (involute, fillet, root arc) are sampled once and mirrored
    in the tooth's centre line for the lower half; the tip arc, which the centre line cuts, is
    sampled whole. Each piece is sampled in one step from its curvature, so that every chord
    stays within the tolerance of the exact curve (sagitta L^2 / (8 rho)):

    * the involute at equal steps of L^(3/2), L its roll distance and radius of curvature
      (ISO 21771 sec. 2.3; :func:`involute_parameters`),
    * the fillet from the exact turning rate and speed of the cut curve on a grid
      (:func:`chord_counts`, :func:`grid_parameters`; with the cubic term of an inflection),
    * the root and tip circles at equal angles (:func:`arc_intervals`),

    each with :data:`SAMPLING_MARGIN` more chords than the estimate asks for. Points and
    tangents come from the closed form (:meth:`~rotorcad.gears.tool.ToolCut.cut`), never from differences of
    points. Should a chord's estimate L |d(psi)| / 8 from the exact end tangents still exceed
    the tolerance (:func:`chords_beyond`), that piece is sampled by the generic sampler
    (:meth:`rotorcad.profile.Segment.sample`).

    Parameters
    ----------
    gear : InvoluteGear
        The gear (its half tooth, :func:`rotorcad.gears.tooth.half_tooth`).
    tolerance : float
        Chord error of the samples, mm.

    Returns
    -------
    Profile
        The open chain lower root arc, fillet, involute, tip arc (unless pointed), upper
        involute, fillet, root arc; points (n, 2), mm. Its segment objects, with their exact
        curves, are made when :attr:`~rotorcad.profile.Profile.segments` is first read.
    """
    tol = tolerance
    half = gear._half_tooth
    names: list[str] = []
    samples: list[tuple[Array, Array, Array]] = []  # parameters, points and tangents as x + i y
    tip = None
    for name, s0, s1, cut in half.cuts:
        if cut is None:
            tip = s1
            continue
        if name == "involute":
            s = involute_parameters(s0, s1, half.roll, gear.base_radius, tol)
        elif name == "fillet":
            s = grid_parameters(half.fillet_counts, s0, s1, tol)
        else:  # the root circle, cut by the tool's tip line: its polar angle is the tool's y / r
            s = span(s0, s1, arc_intervals(cut.k * abs(s1 - s0) / cut.r, cut.start[0], tol) + 1)
        z, w = cut.cut(s, pairs=False)
        names.append(name)
        samples.append((s, z, -w if s1 < s0 else w))  # tangents along the travel
    lengths = np.array([len(s) for s, _, _ in samples])
    z_up = np.concatenate([z for _, z, _ in samples])
    w_up = np.concatenate([w for _, _, w in samples])
    bad = chords_beyond(z_up, w_up, lengths, tol)
    if bad is not None:  # the curvature estimate failed somewhere: the generic sampler there
        curves = dict(gear._pieces)
        for i in np.nonzero(bad)[0]:
            seg = Segment.sample(names[i], curves[names[i]], tol)
            samples[i] = (seg.s, as_complex(seg.points), as_complex(seg.tangents))
        lengths = np.array([len(s) for s, _, _ in samples])
        z_up = np.concatenate([z for _, z, _ in samples])
        w_up = np.concatenate([w for _, _, w in samples])
    # the lower half: the upper one mirrored in the tooth's centre line (the x axis), travelled back
    parts_z, parts_w, counts = [np.conj(z_up[::-1])], [-np.conj(w_up[::-1])], [lengths[::-1]]
    if tip is not None:  # the two halves of the tip arc as one segment
        s_tip = span(-tip, tip, arc_intervals(2.0 * tip, gear.nominal_tip_radius, tol) + 1)
        e = np.exp(1j * s_tip)
        parts_z.append(gear.nominal_tip_radius * e)
        parts_w.append(1j * e)
        counts.append([len(s_tip)])
    parts_z.append(z_up)
    parts_w.append(w_up)
    counts.append(lengths)

    tip_samples = (s_tip, parts_z[1], parts_w[1]) if tip is not None else None
    make_segments = functools.partial(tooth_segments, gear, tuple(names), tuple(samples), tip_samples)
    return _Sampled(as_pairs(np.concatenate(parts_z)), as_pairs(np.concatenate(parts_w)), np.concatenate(counts), make_segments)


def tooth_segments(
    gear: InvoluteGear,
    names: tuple[str, ...],
    samples: tuple[tuple[Array, Array, Array], ...],
    tip: tuple[Array, Array, Array] | None,
) -> list[Segment]:
    """Build the segments of :meth:`InvoluteGear.tooth_profile`, with their exact curves.

    Parameters
    ----------
    gear : InvoluteGear
        The gear (its :attr:`~InvoluteGear._pieces` give the curves).
    names : tuple of str
        The upper half's pieces, from the tip towards the space centre.
    samples : tuple of (s, z, w)
        Their tool parameters (n,), points (n,) complex x + i y, mm, and unit tangents (n,) complex.
    tip : (s, z, w) or None
        The whole tip arc's polar angles (rad), points and tangents; None for a pointed tooth.

    Returns
    -------
    list of Segment
        The lower half (the upper one mirrored, :meth:`~rotorcad.profile.Segment.mirrored`), the
        tip arc, the upper half: the samples of the tooth profile, in order.
    """
    curves = dict(gear._pieces)
    upper = [Segment(n, curves[n], s, as_pairs(z), as_pairs(w)) for n, (s, z, w) in zip(names, samples, strict=True)]
    lower = [seg.mirrored(0.0) for seg in reversed(upper)]
    if tip is not None:
        s_tip, z_tip, w_tip = tip
        arc = Arc((0.0, 0.0), gear.nominal_tip_radius, float(s_tip[0]), float(s_tip[-1]))
        upper.insert(0, Segment("tip arc", arc, s_tip, as_pairs(z_tip), as_pairs(w_tip)))
    return [*lower, *upper]

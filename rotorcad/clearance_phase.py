"""The phase at which the racks of a measured pair are complementary, over the whole rack period.

A CMM's angular datum is arbitrary: the points of a rotor come turned by any angle about its
centre, one lobe or groove of it starting anywhere, in either order. Turning a rotor by theta
slides its rack along the pitch line by r_w theta (the rack point of a profile point is where its
normal passes the pitch point, Wu & Chi, *A numerical method for the evaluation of the meshing
clearance for twin screw rotors with discrete tooth profile points*, Mech. Mach. Theory 70, 2013,
sec. 2, eqs. 2-6), so the phase of the given points is any shift modulo the rack period. Wu &
Chi position the racks from "an initial contact point" (sec. 4); this module finds the
neighbourhood of that contact for any input phase: the shift of the female rack at which the two
racks overlap least (the male's rack tooth sits in the female's rack space), on a grid over one
whole period, then on a finer grid about the best. :class:`rotorcad.clearance.MeshingClearance`
brings the flank into contact from there (``shift``).
"""

from __future__ import annotations

import numpy as np

from rotorcad.geometry import Array
from rotorcad.inverse_rack import DerivedRack

COARSE_COUNT = 32
"""Shifts of the female rack over one rack period on the coarse grid (the least overlap is a basin
as wide as a rack tooth, so a thirty-second of the period finds it)."""

FINE_COUNT = 33
"""Shifts on the fine grid, over one coarse step either side of the coarse grid's best."""

COLUMNS = 8192
"""Columns a rack period is cut into for the overlap areas (the fine grid's step is 16 of them)."""


def rack_ring(points: Array, period: float, copies: int, bound: float) -> Array:
    """Return the closed outline of the region on one side of a rack chain repeated along the pitch line.

    Parameters
    ----------
    points : (n, 2) float array, mm
        One period of the rack chain in the CONTRACT.md rack frame (x along the pitch line,
        travelled in +x).
    period : float, mm
        The rack period (transverse).
    copies : int
        Periods taken, centred on the given one (odd).
    bound : float, mm
        The height at which the region is closed: below the chain's lowest point for the male's
        material (y < chain), above its highest for the female's (y > chain).

    Returns
    -------
    (m, 2) float array, mm
        The ring, its first point repeated at its end. A chain that crosses itself (the two
        generated parts of an undercut flank, a corner's path) bounds the region by the even-odd
        rule, as the noded linework of the ring does (GEOS ``MakeValid``).
    """
    half = copies // 2
    chain = np.vstack([points + np.array([k * period, 0.0]) for k in range(-half, half + 1)])
    return np.vstack([chain, [[chain[-1, 0], bound], [chain[0, 0], bound]], chain[:1]])


def column_crossings(ring: Array, x0: float, width: float, count: int) -> tuple[Array, Array]:
    """Return where a closed ring crosses the vertical lines x = x0 + (i + 1/2) ``width``, i < ``count``.

    A segment counts on the lines from its smaller end's x (included) to its larger's (excluded), so
    that a vertex on a line is crossed once where the ring passes it and twice or not at all where it
    turns back: every line meets the closed ring an even number of times.

    Parameters
    ----------
    ring : (m, 2) float array, mm
        Closed ring, its first point repeated at its end.
    x0, width : float, mm
        The columns' start and width.
    count : int
        Columns.

    Returns
    -------
    column : (k,) int array
        The column of each crossing.
    y : (k,) float array, mm
        Its height (linear along the segment).
    """
    a, b = ring[:-1], ring[1:]
    lo_x, hi_x = np.minimum(a[:, 0], b[:, 0]), np.maximum(a[:, 0], b[:, 0])
    # the first column whose line lies at or past each end: (x - x0) / width - 1/2, rounded up
    first = np.clip(np.ceil((lo_x - x0) / width - 0.5), 0, count).astype(np.intp)
    last = np.clip(np.ceil((hi_x - x0) / width - 0.5), 0, count).astype(np.intp)
    n = last - first
    seg = np.repeat(np.arange(len(a)), n)
    column = np.repeat(first, n) + np.arange(n.sum()) - np.repeat(np.cumsum(n) - n, n)
    x = x0 + (column + 0.5) * width
    dx = b[seg, 0] - a[seg, 0]  # not 0: a vertical segment spans no line
    y = a[seg, 1] + (x - a[seg, 0]) * (b[seg, 1] - a[seg, 1]) / dx
    return column, y


def _column_spans(column: Array, y: Array, count: int) -> tuple[Array, Array, Array]:
    """Return each column's number of crossings (count,) int, and their lowest and highest heights (count,), mm."""
    low, high = np.full(count, np.inf), np.full(count, -np.inf)
    np.minimum.at(low, column, y)
    np.maximum.at(high, column, y)
    return np.bincount(column, minlength=count), low, high


def overlap_areas(male_ring: Array, female_ring: Array, shifts: Array, width: float) -> Array:
    """Return the area of the overlap of the male region and the female region moved by each shift.

    Summed over vertical columns ``width`` wide (the midpoint rule along the pitch line): in each
    column the two regions are the intervals between alternate crossings of their rings (even-odd),
    and the overlap the length where both are inside.

    Parameters
    ----------
    male_ring, female_ring : (m, 2) float arrays, mm
        The racks' material regions' outlines (:func:`rack_ring`).
    shifts : (k,) float array, mm
        Shifts of the female region along the pitch line (+x).
    width : float, mm
        The columns' width.

    Returns
    -------
    (k,) float array, mm²
    """
    shifts = np.asarray(shifts, dtype=float)
    x0 = float(female_ring[:, 0].min() + shifts.min()) - width
    count = int(np.ceil((female_ring[:, 0].max() + shifts.max() - x0) / width)) + 2
    male_column, male_y = column_crossings(male_ring, x0, width, count)
    male_count, male_low, male_high = _column_spans(male_column, male_y, count)
    areas = np.empty(len(shifts))
    for k, shift in enumerate(shifts):
        female_column, female_y = column_crossings(female_ring + np.array([shift, 0.0]), x0, width, count)
        female_count, female_low, female_high = _column_spans(female_column, female_y, count)
        # a column each ring crosses twice holds one interval of each region (nearly all of them)
        simple = (male_count == 2) & (female_count == 2)
        spans = np.minimum(male_high[simple], female_high[simple]) - np.maximum(male_low[simple], female_low[simple])
        area = float(np.sum(np.maximum(spans, 0.0)))
        other = (male_count > 0) & (female_count > 0) & ~simple
        if other.any():  # more crossings (an overhang, a chain crossing itself): even-odd, as below
            keep_male, keep_female = other[male_column], other[female_column]
            column = np.concatenate([male_column[keep_male], female_column[keep_female]])
            y = np.concatenate([male_y[keep_male], female_y[keep_female]])
            is_male = np.concatenate([np.ones(keep_male.sum(), dtype=np.intp), np.zeros(keep_female.sum(), dtype=np.intp)])
            order = np.lexsort((y, column))
            y, is_male = y[order], is_male[order]
            # inside each region above each crossing: the parity of its crossings so far (each column's
            # count is even, so the parity is 0 again at the next column's first crossing)
            in_male = np.cumsum(is_male) % 2
            in_female = np.cumsum(1 - is_male) % 2
            both = (in_male[:-1] == 1) & (in_female[:-1] == 1)
            area += float(np.sum(np.diff(y)[both]))
        areas[k] = width * area
    return areas


def _least(shifts: Array, areas: Array) -> float:
    """Return the middle of the run of grid shifts (k,) at the smallest overlap (k,), mm.

    Where the racks do not overlap at all (a clearance: the backlash), the middle of that run.
    """
    k = int(np.argmin(areas))
    high = np.flatnonzero(areas > areas[k] + 1e-9)
    a = int(high[high < k].max()) + 1 if (high < k).any() else 0
    b = int(high[high > k].min()) - 1 if (high > k).any() else len(areas) - 1
    return float(0.5 * (shifts[a] + shifts[b]))


def complementary_shift(male: DerivedRack, female: DerivedRack) -> float:
    """Return the shift of the female rack at which the two racks are complementary, mm.

    The shift along the pitch line (transverse, as :meth:`rotorcad.clearance.MeshingClearance.clearance_at`
    takes it) at which the male's rack tooth overlaps the female's rack least: on a grid of
    :data:`COARSE_COUNT` shifts over one whole rack period, then of :data:`FINE_COUNT` over one
    coarse step either side of the best (the middle of a run without overlap, a clearance's
    backlash). Independent of the phase the points were given in: the shifts are taken about the
    one that lays the female's rack period over the male's, so the female stays within the male's
    three periods that the clearance compares it with.

    Parameters
    ----------
    male, female : DerivedRack
        The two racks in the CONTRACT.md rack frame (:meth:`DerivedRack.in_contract_frame`), one
        period each.

    Returns
    -------
    float, mm
        The shift, of those a whole number of periods apart the nearest 0 (the points' own phase)
        that keeps the female rack inside the male's three periods.
    """
    period = float(male.period)
    m, f = male.points, female.points
    low = min(m[:, 1].min(), f[:, 1].min()) - 1.0
    high = max(m[:, 1].max(), f[:, 1].max()) + 1.0
    male_ring = rack_ring(m, period, 3, low)
    female_ring = rack_ring(f, period, 1, high)
    width = period / COLUMNS
    centre = 0.5 * (m[:, 0].min() + m[:, 0].max()) - 0.5 * (f[:, 0].min() + f[:, 0].max())
    coarse = centre + period * (np.arange(COARSE_COUNT) / COARSE_COUNT - 0.5)
    best = _least(coarse, overlap_areas(male_ring, female_ring, coarse, width))
    step = period / COARSE_COUNT
    fine = best + np.linspace(-step, step, FINE_COUNT)
    shift = _least(fine, overlap_areas(male_ring, female_ring, fine, width))
    # the same phase nearest the given one (0: the points' own), where the female stays inside the
    # male's three periods with an eighth of a period to spare (the clearance's normals find the male there)
    same = shift + period * np.arange(-3, 4)
    inside = (f[:, 0].min() + same >= m[:, 0].min() - period * 7 / 8) & (f[:, 0].max() + same <= m[:, 0].max() + period * 7 / 8)
    return float(same[inside][np.argmin(np.abs(same[inside]))]) if inside.any() else shift


def running_quadratic(values: Array, arc: Array, width: float) -> Array:
    """Return the local quadratic least-squares fit of ``values`` at each point over a window of arc length.

    The contact alignment's smoothing of the flank's clearance (Cleveland's local regression, *J.
    Am. Stat. Assoc.* 74, 1979, degree 2, uniform weights): like a running mean it averages the
    points' scatter out over the window, but it keeps a trend of the clearance along the flank
    (the rotors at another centre distance than the one they were cut for, where the clearance
    grows away from the contact by tens of µm over the window) instead of lifting its minimum by
    the window's mean. NaN where the window runs past either end or holds fewer than five points.

    Parameters
    ----------
    values : (n,) float array, mm
        The clearance along the flank.
    arc : (n,) float array, mm
        Arc length of each point along the rack, increasing.
    width : float, mm
        Width of the window centred on each point (0: the values themselves).

    Returns
    -------
    (n,) float array, mm
    """
    values = np.asarray(values, dtype=float)
    if len(values) < 5:
        return np.full(len(values), np.nan)
    s = (arc - 0.5 * (arc[0] + arc[-1])) / max(width, 1e-12)  # about 1 over the window: well conditioned
    lo = np.searchsorted(arc, arc - width / 2, side="left")
    hi = np.searchsorted(arc, arc + width / 2, side="right")
    # window sums of s^k and values s^k, then moments about each point (u = s - s_i) binomially
    sums = [np.concatenate([[0.0], np.cumsum(s**k)]) for k in range(5)]
    vsums = [np.concatenate([[0.0], np.cumsum(values * s**k)]) for k in range(3)]
    raw = [c[hi] - c[lo] for c in sums]
    vraw = [c[hi] - c[lo] for c in vsums]
    binom = ((1,), (1, 1), (1, 2, 1), (1, 3, 3, 1), (1, 4, 6, 4, 1))
    su = [sum(binom[k][j] * raw[j] * (-s) ** (k - j) for j in range(k + 1)) for k in range(5)]
    tu = [sum(binom[k][j] * vraw[j] * (-s) ** (k - j) for j in range(k + 1)) for k in range(3)]
    normal = np.stack([np.stack([su[i + j] for j in range(3)], axis=-1) for i in range(3)], axis=-2)
    rhs = np.stack(tu, axis=-1)[..., None]
    # the fit where its window lies on the flank (at the flank's ends a one-sided quadratic's value
    # is four times as scattered as there)
    full = ((hi - lo) >= 5) & (arc - width / 2 >= arc[0]) & (arc + width / 2 <= arc[-1])
    out = np.full(len(values), np.nan)
    if full.any():
        out[full] = np.linalg.solve(normal[full], rhs[full])[:, 0, 0]
    return out


def alignment_curve(values: Array, arc: Array, window: float, scatter: float) -> Array:
    """Return the flank's clearance as the contact alignment zeroes its minimum, mm.

    The clearance itself for exact points (``scatter`` 0: its smallest value is the contact). For
    scattered points a local quadratic fit (:func:`running_quadratic`) over 9/4 of ``window`` (the
    variance of its centre value over n evenly spaced points is 9/(4n) of the scatter's, Cleveland
    1979, the mean's 1/n: as stable under the scatter as the running mean over ``window``, without
    its lift of the minimum where the clearance has a trend along the flank), and the running mean
    over ``window`` where that fit's window runs past the flank's ends (the flank's ends and sparse
    points: as before).

    Parameters
    ----------
    values : (n,) float array, mm
        The clearance along the flank.
    arc : (n,) float array, mm
        Arc length of each point along the rack, increasing.
    window : float, mm
        The running mean's window (:attr:`rotorcad.clearance.MeshingClearance.alignment_window`).
    scatter : float, mm
        The points' scatter (0 for exact points).

    Returns
    -------
    (n,) float array, mm
    """
    values = np.asarray(values, dtype=float)
    if scatter <= 0 or window <= 0 or len(values) < 2:
        return values
    total = np.concatenate([[0.0], np.cumsum(values)])
    lo = np.searchsorted(arc, arc - window / 2, side="left")
    hi = np.searchsorted(arc, arc + window / 2, side="right")
    fit = running_quadratic(values, arc, 2.25 * window)
    return np.where(np.isfinite(fit), fit, (total[hi] - total[lo]) / (hi - lo))


def search_steps(start: float, value: float, period: float) -> list[float]:
    """Return the trials of the contact search: out from ``start``, doubling, up to a quarter period.

    Parameters
    ----------
    start : float, mm
        The search's start (the complementary phase, :func:`complementary_shift`, on the flank's side).
    value : float, mm
        The flank's smallest clearance there (NaN: none): a gap steps on in +, an interference in -.
    period : float, mm
        The rack period.

    Returns
    -------
    list of float, mm
        ``start``, then ``start`` +- 1 µm (or the value's size), doubling, below ``period`` / 4 away.
    """
    step = max(abs(value), 1e-3) if np.isfinite(value) else 1e-3
    direction = 1.0 if not np.isfinite(value) or value >= 0 else -1.0
    steps = [start]
    while step < period / 4:
        steps.append(start + direction * step)
        step *= 2
    return steps


__all__ = [
    "COARSE_COUNT",
    "COLUMNS",
    "FINE_COUNT",
    "alignment_curve",
    "column_crossings",
    "complementary_shift",
    "overlap_areas",
    "rack_ring",
    "running_quadratic",
    "search_steps",
]

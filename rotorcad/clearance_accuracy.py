"""The stated accuracy of a meshing clearance read from profile points (:mod:`rotorcad.clearance`).

From what the points themselves show: their scatter normal to the outline, their spacing, and, for
points that lie on straight runs (resampled from a polyline, a drawing's or an export's chords),
the sagitta of that polygon, by which they leave the true outline wherever it is curved.
Measured on independent pairs cut by brute force (``benchmarks/bench_clearance_accuracy.py``,
README) and on the N-rack sample's thinned female (``tests/test_clearance_lands.py``).
"""

from __future__ import annotations

import numpy as np

from rotorcad.geometry import Array, wrap_angle
from rotorcad.measured.pairs import max_factor

ACCURACY_FLOOR = 1e-3
"""mm: the accuracy stated for exact points (the fits' and the racks' sampling, README)."""

STRAIGHT_TURN = 1e-6
"""mm: a vertex turns by less than this over its spacing (rad x mm) where points lie on one chord.

Points written to 0.1 nm (seven decimals of a millimetre) turn by about 1e-7 mm / h rad on a chord;
a smooth outline of 1 m radius turns by h / 1000 rad, above this from h = 0.03 mm."""


def points_quality(points: Array) -> tuple[float, float]:
    """Estimate the scatter and the spacing of measured profile points.

    Parameters
    ----------
    points : (n, 2) float array, mm
        The points, in order along the outline (one lobe or the whole rotor).

    Returns
    -------
    sigma : float, mm
        Scatter normal to the outline (:func:`rotorcad.measured.outline.scatter`; 0 for exact points).
    spacing : float, mm
        Median distance between neighbouring points.
    """
    from rotorcad.measured.outline import scatter

    p = np.asarray(points, dtype=float)
    return scatter(p), float(np.median(np.hypot(*np.diff(p, axis=0).T)))


def polygon_sagitta(points: Array) -> float:
    """Estimate how far points resampled from a polygon may lie from the curve the polygon stands for.

    Points taken along a polyline's chords (an outline exported at a chord tolerance, then resampled
    or scanned along it) lie on straight runs between the polyline's vertices, where the outline
    turns at once: a chord of length c across which the outline turns by alpha leaves the curve by
    its sagitta c alpha / 8. The runs are the vertices that turn by less than
    :data:`STRAIGHT_TURN` over their spacing; a turn of one or two vertices between two runs is a
    vertex of the polygon, its chord the longer run beside it. Returns the largest sagitta when most
    vertices lie on runs (points of a smooth outline, or scattered ones, turn at every vertex:
    0 then).

    Parameters
    ----------
    points : (n, 2) float array, mm
        The closed outline's points in order.

    Returns
    -------
    float, mm
        The largest sagitta of the polygon (the N-rack sample's outlines written at 1 µm: 1.1-1.2 µm),
        0 when the points do not lie on a polygon's chords.
    """
    p = np.asarray(points, dtype=float)
    if len(p) < 8:
        return 0.0
    d = np.roll(p, -1, axis=0) - p
    step = np.hypot(*d.T)
    turn = wrap_angle(np.arctan2(d[:, 1], d[:, 0]) - np.roll(np.arctan2(d[:, 1], d[:, 0]), 1))  # at each vertex
    straight = np.abs(turn) * np.maximum(step, np.roll(step, 1)) < STRAIGHT_TURN
    if straight.mean() < 0.5 or straight.all():
        return 0.0
    # runs of straight vertices and the bends between them, around the ring (start at a bend's first vertex)
    start = int(np.flatnonzero(~straight & np.roll(straight, 1))[0])
    flag = np.roll(straight, -start)
    t, s = np.roll(turn, -start), np.roll(step, -start)
    change = np.flatnonzero(np.diff(np.concatenate([flag, flag[:1]]).astype(int))) + 1  # first index of each next part
    bounds = np.concatenate([[0], change[change < len(flag)], [len(flag)]])
    total_turn = np.add.reduceat(t, bounds[:-1])
    length = np.add.reduceat(s, bounds[:-1])
    is_run = flag[bounds[:-1]]
    count = np.diff(bounds)
    # the parts alternate bend, run, bend, run, ...: a polygon's vertex turns one vertex of the points
    # (on it) or two (between them); a longer bend is a stretch of short chords, as smooth as the points
    bends = np.flatnonzero(~is_run & (count <= 2))
    before = length[bends - 1] if len(bends) else np.zeros(0)  # bend 0's run before is the ring's last part
    after = length[(bends + 1) % len(length)]
    chord = np.maximum(before, after) + length[bends]
    return float(np.max(chord * np.abs(total_turn[bends]) / 8.0)) if len(bends) else 0.0


def estimated_accuracy(sigma: float, spacing: float, count: float = 1.0, sagitta: float = 0.0) -> float:
    """Return the stated accuracy of the contact-zone clearance from the points' scatter and spacing.

    A bound on the largest error of the normal clearance over the contact zone, which holds with
    95 % confidence (:data:`rotorcad.measured.pairs.CONFIDENCE`): 1 µm for exact points (the fits' and
    the racks' sampling), plus sqrt(2) k sigma for the scatter (the female's and the male's fitted
    outlines each off by at most the scatter's own standard deviation sigma, independently; k from
    :func:`rotorcad.measured.pairs.max_factor` for the ``count`` independent points the contact zone
    is measured by), plus 0.004 h^2 / mm (a cubic through points h apart misses the outline's
    curvature jumps, where a rounding meets a flank, by about h^2 dk / 8), plus the sagittas of the
    polygons the points lie on (:func:`polygon_sagitta`, both rotors': each rotor's points are off
    its outline by up to its own). Measured on independent pairs cut by brute force
    (``benchmarks/bench_clearance_accuracy.py``, README).

    Parameters
    ----------
    sigma : float, mm
        The larger scatter of the two rotors' points (0 for exact curves).
    spacing : float, mm
        The larger point spacing of the two rotors (0 for exact curves).
    count : float
        Number of measured points along the contact zone (its length over the spacing).
    sagitta : float, mm
        The two rotors' polygon sagittas added (0 for points off a smooth outline or exact curves).

    Returns
    -------
    float, mm
        The stated accuracy.
    """
    scatter = np.sqrt(2.0) * max_factor(count) * sigma if sigma > 0 else 0.0
    return float(ACCURACY_FLOOR + scatter + 0.004 * spacing**2 + sagitta)


def pair_quality(male: Array | list, female: Array | list) -> dict[str, float]:
    """Return the ``scatter``, ``spacing`` and ``sagitta`` of a pair's points, as ``MeshingClearance`` takes them.

    Parameters
    ----------
    male, female : (n, 2) float array, mm, or list of Curve
        Each rotor's points (exact curves, a list, count as exact: 0 each).

    Returns
    -------
    dict of float, mm
        The larger scatter and spacing of the two (:func:`points_quality`) and the sum of their
        polygon sagittas (:func:`polygon_sagitta`).
    """
    points = [p for p in (male, female) if not isinstance(p, list | tuple)]
    quality = [points_quality(p) for p in points]
    return {
        "scatter": max((q[0] for q in quality), default=0.0),
        "spacing": max((q[1] for q in quality), default=0.0),
        "sagitta": float(sum(polygon_sagitta(p) for p in points)),
    }


__all__ = ["ACCURACY_FLOOR", "estimated_accuracy", "pair_quality", "points_quality", "polygon_sagitta"]

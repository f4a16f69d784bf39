"""Jamming read from the male rotation along a given profile's meshline, where the normal's tangent cannot resolve it.

Rinder's jamming rule (sec. 2.2.1): the meshline normal passes through the pitch point C. At a contact P
the common normal passes through C, and the male contact point turns with the male about O1, so along the
meshline the distance from C changes with the male rotation t as

    d|P - C| / dt = c P_y / |P - C|        (c = |O1 C|, the male pitch radius; O1 at the origin, C on the x axis)

whatever the profile: the term of the contact's motion along the flank is normal to P - C. Away from O1O2
(P_y not 0) the distance from C is therefore stationary along the meshline, the normal through C, exactly
where the male rotation turns back along it. That is a test of the rotation at each sample, neither of the
meshline's tangent (which a given profile resolves only over the resolution sqrt(8 a e),
:func:`rotorcad.meshing.defect_record.resolution`) nor of its positions (placed to ten times the
profile's accuracy, :data:`rotorcad.meshing.defect_record.MESHLINE_GAIN`).

The rotation of a contact is set by the direction of the profile's normal alone (a point moved along its
own normal keeps its normal line, and so its instant): the normal at P makes the angle psi with P - C, and
d psi / dt = -c (P_x - c) / |P - C|^2 at a fixed profile point, so a normal known to delta phi (rad) puts the
rotation within

    delta t = delta phi |P - C|^2 / (c |P_x - c|)

(:func:`rotation_accuracy`; unbounded where P lies on the normal to O1O2 through C). The normals of the
rack (:func:`rack_points`), which carries the profile's and its accuracy e, are each resolved over no more
than the resolution L and, two of them nearer each other than that along the rack, only over their distance
d: delta phi = e / min(d, L), at least the analysis' tangent tolerance (:func:`normal_accuracy`). A turn back
of the rotation by more than the two ends' delta t together, and on again, is no error of the profile: a
jamming point at each end (:func:`rotation_turns`).

Measured (issue 21 item 3). A 20 µm dent over 2 mm on the rack-involute male's sealing flank, as 2000 points
a lobe with 1 µm of scatter: the rotation turns back by 16.9 mrad between contacts 0.97 mm apart on the rack,
where the accuracy (2.0 µm) allows 2.7; the normal's tangent, resolved over 4.3 mm of meshline, never swings
through C there, and the sign changes of its misses cancel within the resolution. The shapely-cut arc-flank
male as 600 exact points a lobe (tests/independent_pairs.py, phase 0.25): a turn back by 1.5 mrad between
contacts 0.04 mm apart on the rack, where 8.5 are allowed (the cut's facets, no jamming).

Below the accuracy (issue 21): an excursion beyond what the tangent's tolerance alone allows (delta phi the
analysis' tolerance, the design's own test: ``accuracy`` 0) and within the profile's accuracy is a jamming the
input can neither show nor rule out: the flank is undecided there
(:func:`rotorcad.meshing.undecided.possible_rows`). The same dent as 300 points a lobe with 2 µm of scatter: the
rotation turns back by 4.9 mrad where 10.0 are allowed; the flank read "runs", decided, and now reads undecided at
that place.
"""

from __future__ import annotations

import numpy as np


def rotation_accuracy(points: np.ndarray, pitch_x: float, normal_accuracy: float) -> np.ndarray:
    """Return how far the male rotation at each meshline sample may be off, (n,) float, rad.

    Parameters
    ----------
    points : (n, 2) float array, mm
        The meshline samples, fixed frame (O1 at the origin, O2 on the positive x axis).
    pitch_x : float, mm
        The pitch point C's x (the male pitch radius c).
    normal_accuracy : float, rad
        How far the profile's normal direction may be off (delta phi).

    Returns
    -------
    (n,) float array, rad
        delta phi |P - C|^2 / (c |P_x - c|); infinite where P_x = c.
    """
    dx = points[:, 0] - pitch_x
    square = dx * dx + points[:, 1] * points[:, 1]
    with np.errstate(divide="ignore"):
        return normal_accuracy * square / (pitch_x * np.abs(dx))


def rack_points(points: np.ndarray, t: np.ndarray, pitch_x: float) -> np.ndarray:
    """Return the generating rack's point touching at each meshline sample, (n, 2) mm, in the rack's frame at t = 0.

    The rack rolls on the male pitch circle: it moves by c t along y (c = ``pitch_x``, the male pitch radius) while
    the male turns by t, so its point at a contact P is P - (0, c t).
    """
    return points - np.column_stack([np.zeros(len(t)), pitch_x * t])


def normal_accuracy(length: np.ndarray, accuracy: float, longest: float, tolerance: float) -> np.ndarray:
    """Return how far the directions of two normals of a profile known to ``accuracy`` (mm) may be off, each, (m,) rad.

    The two touch ``length`` (mm, (m,)) apart along the rack, which carries the profile's normals (a point moved
    along its own normal keeps its normal line) and its accuracy. Each direction is resolved over no more than the
    resolution ``longest`` (mm, :func:`rotorcad.meshing.defect_record.resolution`) and, between two normals nearer
    each other than that, only over their distance: accuracy / min(length, longest), at least ``tolerance`` (rad).
    """
    with np.errstate(divide="ignore", invalid="ignore"):  # 0 / 0 of an exact profile's one normal: no bound
        return np.maximum(tolerance, accuracy / np.minimum(length, longest))


def _excursions(v: np.ndarray, allowed) -> list[tuple[int, int]]:
    """Return the pairs of samples between which ``v`` (its overall trend rising) turns back and forth beyond ``allowed``.

    ``allowed(i, j)`` is how far ``v`` may be off between samples ``i`` and ``j`` (index arrays). A drop below the
    running maximum by more than that is a turn back; it is an excursion when ``v`` rises again from the drop's
    deepest sample by more than allowed: the maximum and that deepest sample. A drop that ends the piece is one
    turn, not an excursion.
    """
    n = len(v)
    index = np.arange(n)
    top = np.maximum.accumulate(v)
    peak = np.maximum.accumulate(np.where(v >= top, index, 0))  # the sample of the running maximum
    drop = top - v
    deep = drop > allowed(peak, index)
    if not deep.any():
        return []
    rows = index[deep]
    peaks, first = np.unique(peak[rows], return_index=True)  # a drop's samples share its maximum, in one run
    out: list[tuple[int, int]] = []
    for p, a, b in zip(peaks, first, np.append(first[1:], len(rows)), strict=True):  # one pass a turn back
        low = int(rows[a + int(np.argmax(drop[rows[a:b]]))])
        later = index[low:]
        if (v[later] - v[low] > allowed(np.full(len(later), low), later)).any():
            out.append((int(p), low))
    return out


def rotation_turns(
    t: np.ndarray, points: np.ndarray, pitch_x: float, accuracy: float, longest: float, tolerance: float
) -> np.ndarray:
    """Return the pairs of samples of a meshline piece between which the male rotation turns back and forth.

    Each pair are two extremes of the rotation along the piece (its samples in order), a maximum and the minimum
    after it or the reverse, whose rotations differ by more than both their :func:`rotation_accuracy`, with the
    normals' accuracy of their distance along the rack (:func:`normal_accuracy`, :func:`rack_points`), and after
    which the rotation runs on by more than that again: at each, the distance from C is stationary along the
    meshline, its normal through C (jamming, the module's note), unless it lies on O1O2, where that distance is
    stationary in the rotation itself. A single turn back (the N-rack male's meshline, given by its dense CSV
    with 1 um of scatter, runs back on itself where the design's tip-rounding piece hands over to its envelope
    piece: the rotation turns there once, by 0.51 rad) is the meshline's reversal, which the normal's test judges.

    Parameters
    ----------
    t : (n,) float array, rad
        The male rotation at each sample.
    points : (n, 2) float array, mm
        The samples, fixed frame.
    pitch_x : float, mm
        The pitch point C's x.
    accuracy : float, mm
        The profile's accuracy.
    longest : float, mm
        Its resolution (:func:`rotorcad.meshing.defect_record.resolution`).
    tolerance : float, rad
        The least uncertainty of a normal's direction.

    Returns
    -------
    (m, 2) int array
        Sample indices of each pair, in order.
    """
    if len(t) < 3:
        return np.zeros((0, 2), dtype=int)
    gain = rotation_accuracy(points, pitch_x, 1.0)
    rack = rack_points(points, t, pitch_x)

    def allowed(i: np.ndarray, j: np.ndarray) -> np.ndarray:
        apart = np.hypot(rack[i, 0] - rack[j, 0], rack[i, 1] - rack[j, 1])
        return (gain[i] + gain[j]) * normal_accuracy(apart, accuracy, longest, tolerance)

    v = t if t[-1] >= t[0] else -t
    return np.array(_excursions(v, allowed), dtype=int).reshape(-1, 2)

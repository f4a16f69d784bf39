"""The points of many curves sampled to a chord tolerance, a drawing's straight lines all at once.

A drawing read as curves (:func:`exports.dxf_profile.read_profile`) holds a polyline as hundreds or
thousands of :class:`~rotorcad.curves.Line` pieces (the rack-involute sample's female: 1280), and
sampling them one by one (:func:`~rotorcad.curves.sample_curve`) spends its time on the calls, not the
numbers. :func:`curve_points` gives the same points, bit for bit: a line's samples are its first 17
parameters and ``a + s d`` there (its first pass finds no turn and its check of the middles no bulge
beyond rounding), formed here for every line at once with the same operations; a line whose middles
stray from its chords by more than the tolerance (never, short of rounding on a line of 1e14 mm), one
of no length, or one with a coordinate that is not finite is sampled by :func:`~rotorcad.curves.sample_curve`
as before, and so is every other kind of curve.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from rotorcad.curves import Curve, Line, sample_curve
from rotorcad.geometry import Array, cross, normalize

LINE_SAMPLES = 17
"""The samples :func:`~rotorcad.curves.sample_curve` starts from (``max(minimum, 17)``), all a line keeps."""


def curve_points(curves: Sequence[Curve], tolerance: float) -> Array:
    """Return ``np.vstack([sample_curve(c, tolerance)[1] for c in curves])``, the lines among them at once.

    Parameters
    ----------
    curves : sequence of Curve
        The curves, in order (at least one).
    tolerance : float, mm
        Largest chord error (> 0).

    Returns
    -------
    (n, 2) float array, mm
        The points of each curve's samples, one curve after the other.
    """
    pieces: list[Array | None] = [None] * len(curves)
    lines = [i for i, c in enumerate(curves) if type(c) is Line]
    if lines and tolerance > 0:
        for i, points in zip(lines, _line_samples([curves[i] for i in lines], tolerance), strict=True):
            pieces[i] = points
    return np.vstack([p if p is not None else sample_curve(c, tolerance)[1] for p, c in zip(pieces, curves, strict=True)])


def _line_samples(lines: list[Line], tolerance: float) -> list[Array | None]:
    """Return each line's samples as :func:`~rotorcad.curves.sample_curve` forms them, (17, 2) mm; None where it refines."""
    s0 = np.array([c.s0 for c in lines])
    s1 = np.array([c.s1 for c in lines])
    a = np.array([c.a for c in lines], dtype=float)
    d = normalize(np.subtract(np.array([c.b for c in lines], dtype=float), a))  # Line._start_and_direction, by rows
    step = (s1 - s0) / (LINE_SAMPLES - 1)
    # np.linspace(s0, s1, 17) of each line: arange * step + start, the last set to the stop
    s = np.arange(LINE_SAMPLES, dtype=float)[None, :] * step[:, None] + s0[:, None]
    s[:, -1] = s1
    middle = 0.5 * (s[:, :-1] + s[:, 1:])
    p = np.empty((len(lines), LINE_SAMPLES, 2))  # Line.frame: a + s d, by columns
    p[..., 0] = a[:, 0, None] + s * d[:, 0, None]
    p[..., 1] = a[:, 1, None] + s * d[:, 1, None]
    q = np.empty((len(lines), LINE_SAMPLES - 1, 2))
    q[..., 0] = a[:, 0, None] + middle * d[:, 0, None]
    q[..., 1] = a[:, 1, None] + middle * d[:, 1, None]
    # sample_curve's check of the middles against the chords (its first pass finds no turn: a line's tangents are equal)
    chord = p[:, 1:] - p[:, :-1]
    length = np.hypot(chord[..., 0], chord[..., 1])
    off = np.abs(cross(chord, q - p[:, :-1])) / np.where(length > 0, length, 1.0)
    plain = (step != 0) & (off <= tolerance).all(axis=1) & np.isfinite(p).all(axis=(1, 2)) & np.isfinite(q).all(axis=(1, 2))
    plain &= np.abs(d).sum(axis=1) > 0
    return [p[k] if plain[k] else None for k in range(len(lines))]

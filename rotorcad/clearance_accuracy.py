"""The stated accuracy of a meshing clearance read from profile points (:mod:`rotorcad.clearance`).

From what the points themselves show: their scatter normal to the outline, their spacing, and, for
points that lie on straight runs (resampled from a polyline, a drawing's or an export's chords),
the sagitta of that polygon, by which they leave the true outline wherever it is curved: the one
estimate :func:`rotorcad.measured.pattern.pattern_deviation` that :func:`rotorcad.measured.outline.read_outline`
judges such points by (their fit's scatter), counted here once, as a bound, not as scatter too.
The gaps of the parts that never touch state their own accuracy: a sharp corner between sparse
points may lie anywhere in the triangle of its edge and the chords beside it
(:func:`rotorcad.measured.fit.corner_uncertainty`).
Measured on independent pairs cut by brute force (``benchmarks/bench_clearance_accuracy.py``,
README) and on the N-rack sample's thinned female (``tests/test_clearance_lands.py``).
"""

from __future__ import annotations

import numpy as np

from rotorcad.geometry import Array
from rotorcad.measured.pairs import max_factor

ACCURACY_FLOOR = 1e-3
"""mm: the accuracy stated for exact points (the fits' and the racks' sampling, README)."""


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


SPLINE_GAIN = 1.0 / 30.0
"""A cubic through points h apart misses an outline whose curvature jumps by dk between two of them
by up to SPLINE_GAIN h^2 dk (the clearance, both rotors' fits: measured, not the interpolation
bound h^2 dk / 8). Calibrated on the N-rack sample thinned by 30 um, exact points at 80 a lobe
(the female's 2.07 mm tip roundings, read dk 0.29/mm, 1 mm apart): 12.2 um off the brute force
(``benchmarks/bench_clearance_accuracy.py``)."""

DEFAULT_CURVATURE_JUMP = 0.12
"""1/mm: the curvature jump taken where the points' own is not given (:func:`estimated_accuracy`):
0.004 h^2 / mm with :data:`SPLINE_GAIN`, the term measured on 1.5 mm roundings."""


def estimated_accuracy(
    sigma: float, spacing: float, count: float = 1.0, sagitta: float = 0.0, curvature_jump: float | None = None
) -> float:
    """Return the stated accuracy of the contact-zone clearance from the points' scatter and spacing.

    A bound on the largest error of the normal clearance over the contact zone, which holds with
    95 % confidence (:data:`rotorcad.measured.pairs.CONFIDENCE`): 1 µm for exact points (the fits' and
    the racks' sampling), plus sqrt(2) k sigma for the scatter (the female's and the male's fitted
    outlines each off by at most the scatter's own standard deviation sigma, independently; k from
    :func:`rotorcad.measured.pairs.max_factor` for the ``count`` independent points the contact zone
    is measured by), plus :data:`SPLINE_GAIN` h^2 dk (a cubic through points h apart misses the
    outline where its curvature jumps by dk, a rounding meeting a flank: dk read from the points,
    :func:`rotorcad.measured.fit.curvature_jump`), plus the sagittas of the
    polygons the points lie on (:func:`rotorcad.measured.pattern.pattern_deviation`, both rotors':
    each rotor's points are off its outline by up to its own). Measured on independent pairs cut by brute force
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
    curvature_jump : float, 1/mm, optional
        The larger of the two rotors' largest curvature jumps between neighbouring points
        (:func:`rotorcad.measured.fit.curvature_jump`); None: :data:`DEFAULT_CURVATURE_JUMP`.

    Returns
    -------
    float, mm
        The stated accuracy.
    """
    scatter = np.sqrt(2.0) * max_factor(count) * sigma if sigma > 0 else 0.0
    dk = DEFAULT_CURVATURE_JUMP if curvature_jump is None else curvature_jump
    return float(ACCURACY_FLOOR + scatter + SPLINE_GAIN * spacing**2 * dk + sagitta)


def trends(flank: Array, sigma: float, spacing: float, sagitta: float = 0.0, curvature_jump: float | None = None) -> bool:
    """Tell whether the clearance along an aligned flank spans more than twice the points' accuracy.

    Then it trends (a housing bored oversize) rather than scatters about the contact, and the
    contact alignment's running mean over most of the flank (twenty spacings of sparse points) lifts
    its minimum: :attr:`rotorcad.clearance.MeshingClearance.shift` cuts the window to
    :data:`rotorcad.clearance.ALIGNMENT_WINDOW_MAX`. The 4/6 independent pair's conjugate flanks
    from 80 points a lobe with 2 um scatter span 15 um against 25 um stated and keep their window
    (the shift within 2 um of the truth over five seeds, 3 um with the short one); the N-rack's at
    82.2 mm for 82 span 0.14 mm.

    Parameters
    ----------
    flank : (n,) float array, mm
        The clearance along the flank (NaN where undefined).
    sigma, spacing, sagitta, curvature_jump
        As :func:`estimated_accuracy` (mm, mm, mm, 1/mm).

    Returns
    -------
    bool
    """
    ok = np.asarray(flank, dtype=float)
    ok = ok[np.isfinite(ok)]
    if len(ok) < 2:
        return False
    return float(np.ptp(ok)) > 2.0 * estimated_accuracy(sigma, spacing, len(ok), sagitta, curvature_jump)


POLYGON_LARGEST = 1.3
"""The largest chord's sagitta over the polygon's typical one that
:func:`rotorcad.measured.pattern.pattern_deviation` estimates (a median): the N-rack sample's outlines
written at a chord tolerance of 1 um (every chord's sagitta at most 1 um, most near it) read 0.79 um."""


def pair_quality(male: Array | list, female: Array | list, teeth: tuple[int, int]) -> dict[str, float]:
    """Return the quality of a pair's points as ``MeshingClearance`` takes it (its accuracy's inputs).

    Each rotor's points are read as :func:`rotorcad.measured.outline.read_outline` reads them for the
    fit: points that show no scatter between neighbours but lie on a polygon's chords (the pattern a
    polygon leaves, :func:`rotorcad.measured.pattern.pattern_deviation`) are off the outline by that
    polygon's sagitta e, a systematic error bounded by e itself (their fit is smoothed by the
    pattern's spread, but that spread is not a random scatter a second time): they count with
    their sagitta and no scatter.

    Parameters
    ----------
    male, female : (n, 2) float array, mm, or list of Curve
        Each rotor's points (exact curves, a list, count as exact: 0 each).
    teeth : (int, int)
        The male's and the female's lobe counts.

    Returns
    -------
    dict of float, mm
        ``scatter`` and ``spacing``: the larger of the two rotors' (:func:`points_quality`; 0 for
        points on a polygon's chords); ``sagitta``: the two polygons' sagittas added;
        ``curvature_jump`` (1/mm): the larger of the two rotors'
        (:func:`rotorcad.measured.fit.curvature_jump`); ``corner_error``: the largest distance a
        sharp corner found between sparse points may lie from where its fits cross
        (:func:`rotorcad.measured.fit.corner_uncertainty`, either rotor).
    """
    from rotorcad.measured.fit import corner_uncertainty, curvature_jump
    from rotorcad.measured.outline import read_outline, scatter
    from rotorcad.measured.pattern import PATTERN_RMS, pattern_deviation

    out = {"scatter": 0.0, "spacing": 0.0, "sagitta": 0.0, "corner_error": 0.0, "curvature_jump": 0.0}
    for points, z in zip((male, female), teeth, strict=True):
        if isinstance(points, list | tuple):
            continue
        outline = read_outline(np.asarray(points, dtype=float), z, "points", drawn_as_points=False)
        whole = outline.whole
        sigma = scatter(whole)
        chords = pattern_deviation(whole, z)
        polygon = PATTERN_RMS * chords > sigma  # the polygon's pattern, not a scatter, sets how far they lie off
        out["sagitta"] += POLYGON_LARGEST * chords if polygon else 0.0
        out["scatter"] = max(out["scatter"], 0.0 if polygon else outline.sigma)
        out["spacing"] = max(out["spacing"], float(np.median(np.hypot(*np.diff(whole, axis=0).T))))
        out["corner_error"] = max(out["corner_error"], corner_uncertainty(whole, outline.sigma))
        out["curvature_jump"] = max(out["curvature_jump"], curvature_jump(whole, outline.sigma))
    return out


__all__ = ["ACCURACY_FLOOR", "estimated_accuracy", "pair_quality", "points_quality", "trends"]

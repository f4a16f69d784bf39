"""The flank angle of a straight part of a rack fitted to scattered points: a line fit, not the least of its angles.

A rack flank that is straight (the rack-involute's: 18.127 deg over hundreds of rack points) has one angle. Read
pointwise off a rack derived from scattered points, its angle wobbles by the fit's tangent error (0.1-0.3 deg at
300 points a lobe with 2 um of scatter), and the least of those angles picks the most negative wobble: 17.98 for
18.13 from the rack-involute female, seed 11. Where the flank ends at a sharp corner of the profile the fitted spline
bends over its last few points (an end effect: 16.80 for 18.13 over the last 0.8 mm of the rack-involute male's
flank, the corner's fan starting from that bent tangent), below what the points resolve.

So, of scattered points only, each run of flank points between sharp corners is searched for its straight part,
decided from the fitted rack itself and the input's stated scatter, never from a design:

* candidate lines are the chords of the run over :data:`CHORD_SPACINGS` point spacings of profile (each averages
  the fit over several points); a candidate's straight part is the contiguous stretch about its chord whose rack
  points lie within ``2 sigma`` (one point's 95 % scatter, :attr:`rotorcad.screw_rotors.ScrewRotors.point_accuracy`)
  of its line; the longest stretch wins and is refined by a least-squares line over it (twice);
* the stretch is a straight flank when it spans at least :data:`MIN_SPACINGS` spacings of profile and its angle
  carries no trend: inside it by half a chord (its ends are where a curve leaves the line by 2 sigma), the line
  angles of its halves, and of its outer thirds and middle third (by rack arc length), agree within
  :data:`TREND_DEG` (a gently curved flank, whose least angle lies below its line's, keeps its pointwise angles);
* its angle is the least-squares line's over that inner part; the run's points beyond the stretch within
  :data:`END_SPACINGS` spacings of profile of the run's end (a sharp corner) read the same angle: the fit's end
  effect there is not resolved by the points. Elsewhere the pointwise angles stand.

A minimum at a V (two curves meeting, or a quickly changing curvature) is not a straight part and keeps its
pointwise angle: the fitted spline overshoots there (the N rack's male, 5.37 for 5.73 deg), which no reading of the
fitted rack undoes (tests/test_hob_points_samples.py, KNOWN_VERDICTS).
"""

from __future__ import annotations

import itertools

import numpy as np

CHORD_SPACINGS = 3.0
"""Point spacings of profile a candidate chord spans."""
MIN_SPACINGS = 8.0
"""Point spacings of profile a straight part spans at least."""
END_SPACINGS = 4.0
"""Point spacings of profile from a run's end within which the fit's end effect is not resolved."""
TREND_DEG = 0.1
"""deg: how far a straight part's angle may move along it (:func:`_trend`)."""
SEEDS = 48
"""Candidate chords a run (at most)."""
COVERAGE = 2.0
"""How many standard errors of a straight part's line its stated accuracy counts (about 95 %, :func:`line_accuracy`)."""


def _runs(flank: np.ndarray, tan: np.ndarray, kink: float) -> list[tuple[int, int]]:
    """Return the runs of consecutive flank points not broken by a turn above ``kink`` (rad), as (start, stop)."""
    cross = tan[:-1, 0] * tan[1:, 1] - tan[:-1, 1] * tan[1:, 0]
    turn = np.abs(np.arctan2(cross, np.einsum("ij,ij->i", tan[:-1], tan[1:])))
    joined = flank[:-1] & flank[1:] & (turn <= kink)
    edges = np.flatnonzero(np.diff(np.concatenate([[False], flank, [False]]).astype(int)))
    out = []
    for start, stop in zip(edges[::2], edges[1::2], strict=True):
        cuts = start + 1 + np.flatnonzero(~joined[start : stop - 1])
        bounds = np.concatenate([[start], cuts, [stop]])
        out += [(int(a), int(b)) for a, b in itertools.pairwise(bounds) if b > a]
    return out


def _stretch(pts: np.ndarray, origin: np.ndarray, direction: np.ndarray, at: np.ndarray, tol: float) -> tuple:
    """Return the contiguous stretch (first, last index) about each of ``at`` within ``tol`` of its line.

    ``origin`` and ``direction`` (m, 2) give m lines (unit directions); ``at`` (m,) the index each stretch holds.
    """
    rel = pts[None, :, :] - origin[:, None, :]
    off = np.abs(rel[..., 0] * direction[:, None, 1] - rel[..., 1] * direction[:, None, 0]) > tol
    idx = np.arange(len(pts))
    left = np.where(off & (idx[None, :] < at[:, None]), idx[None, :], -1).max(axis=1) + 1
    right = np.where(off & (idx[None, :] > at[:, None]), idx[None, :], len(pts)).min(axis=1) - 1
    return left, right


def _line(pts: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Return the least-squares (total) line through ``pts``: its centroid and unit direction."""
    centre = pts.mean(axis=0)
    direction = np.linalg.svd(pts - centre, full_matrices=False)[2][0]
    return centre, direction


def _angle(pts: np.ndarray) -> float:
    """Return the flank angle (deg, from the normal to the pitch line) of the least-squares line through ``pts``."""
    direction = _line(pts)[1]
    return float(np.degrees(np.arctan2(abs(direction[0]), abs(direction[1]))))


def _trend(pts: np.ndarray) -> float:
    """Return how far the angle moves along a stretch of rack (deg): halves apart, outer thirds from the middle third.

    A linear trend of the angle (slope g over length L) sets the halves g L / 2 apart, which is how far the stretch's
    line lies above its least angle (at one end); a quadratic one (k u^2 about the middle) sets the outer thirds
    0.11 k L^2 from the middle, the line lying 0.083 k L^2 above the least angle. A straight flank's wobble averages
    out over each part.
    """
    along = np.concatenate([[0.0], np.cumsum(np.hypot(*np.diff(pts, axis=0).T))])
    u = along / along[-1]
    parts = [(u >= a) & (u <= b) for a, b in ((0.0, 0.5), (0.5, 1.0), (0.0, 1 / 3), (1 / 3, 2 / 3), (2 / 3, 1.0))]
    if min(part.sum() for part in parts) < 3:
        return np.inf
    halves = [_angle(pts[part]) for part in parts[:2]]
    thirds = [_angle(pts[part]) for part in parts[2:]]
    return max(abs(halves[0] - halves[1]), abs(0.5 * (thirds[0] + thirds[2]) - thirds[1]))


def straight_flank_angles(
    pts: np.ndarray,
    tan: np.ndarray,
    angles: np.ndarray,
    flank: np.ndarray,
    along: np.ndarray,
    scatter: float,
    spacing: float,
    kink: float,
) -> np.ndarray:
    """Return the flank angles with each straight part (and its unresolved run ends) at its fitted line's angle.

    Parameters
    ----------
    pts : (n, 2) float array, mm
        The rack's points in its normal section (travelling +x).
    tan : (n, 2) float array
        Their unit tangents.
    angles : (n,) float array, deg
        Each point's normal flank angle (from the normal to the pitch line).
    flank : (n,) bool array
        Which points are flank points (cutting, not a corner's sliver, not parallel to the pitch line).
    along : (n,) float array, mm
        Arc length along the profile the points come from (the rack's where it has no profile).
    scatter, spacing : float, mm
        One given point's standard deviation and the points' median spacing; either 0 (exact points, a design):
        ``angles`` returned unchanged.
    kink : float, rad
        A turn between neighbouring points above this is a sharp corner, which ends a run.

    Returns
    -------
    (n,) float array, deg
        ``angles``, with the straight parts' points and their run ends' read as the part's line (module docstring).
    """
    return straight_flank_reading(pts, tan, angles, flank, along, scatter, spacing, kink)[0]


def line_accuracy(inner: np.ndarray, profile_length: float, scatter: float, spacing: float) -> float:
    """Return how far a straight part's line angle may lie above the least true angle along it (deg).

    The given points along the part, ``m = profile_length / spacing`` of them, each off by one point's normal
    scatter ``sigma`` (the rack's normal offset is the profile's where they touch, Wu & Chi sec. 2; the normal
    section shortens no offset), set the least-squares line's direction to ``sigma sqrt(12 / m) / L`` rad (the
    slope's standard error of m points spread evenly over the part's length L), counted :data:`COVERAGE` times; a
    trend of the true angle along the part that :func:`_trend` measures (at most :data:`TREND_DEG`, or the part
    is no straight one) puts the line at most that far above the part's least angle, added.

    Parameters
    ----------
    inner : (k, 2) float array, mm
        The rack points the line was fitted to, in the normal section.
    profile_length : float, mm
        The profile's arc length those rack points come from.
    scatter, spacing : float, mm
        One given point's standard deviation and the points' median spacing.

    Returns
    -------
    float, deg
    """
    length = float(np.hypot(*(inner[-1] - inner[0])))
    m = max(profile_length / spacing, 2.0)
    return float(np.degrees(COVERAGE * scatter * np.sqrt(12.0 / m) / length)) + _trend(inner)


def straight_flank_reading(
    pts: np.ndarray,
    tan: np.ndarray,
    angles: np.ndarray,
    flank: np.ndarray,
    along: np.ndarray,
    scatter: float,
    spacing: float,
    kink: float,
    given_along: np.ndarray | None = None,
) -> tuple[np.ndarray, np.ndarray]:
    """Return the flank angles as :func:`straight_flank_angles` reads them, and the accuracy of the line-read ones.

    Parameters are those of :func:`straight_flank_angles`, and:

    given_along : (n,) float array, mm, optional
        Arc length along the given points' profile at each point (a mate's rack: at the given rack's point where the
        two touch). A line's accuracy counts the given points of the shorter of the two spans; default ``along``.

    Returns
    -------
    angles : (n,) float array, deg
        As :func:`straight_flank_angles`.
    line : (n,) float array, deg
        Of a point read as its straight part's line, the line's accuracy (:func:`line_accuracy`); NaN where the
        pointwise angle stands.
    """
    out = np.array(angles, dtype=float)
    line = np.full(len(out), np.nan)
    if scatter <= 0 or spacing <= 0 or not flank.any():
        return out, line
    tol = 2.0 * scatter
    for start, stop in _runs(flank, tan, kink):
        s = along[start:stop] - along[start]
        if s[-1] < MIN_SPACINGS * spacing:
            continue
        p = pts[start:stop]
        half = 0.5 * CHORD_SPACINGS * spacing
        seeds = np.unique(np.linspace(0, len(p) - 1, min(SEEDS, len(p))).astype(int))
        seeds = seeds[(s[seeds] >= half) & (s[seeds] <= s[-1] - half)]
        if not len(seeds):
            continue
        lo = np.searchsorted(s, s[seeds] - half)
        hi = np.minimum(np.searchsorted(s, s[seeds] + half), len(p) - 1)
        chord = p[hi] - p[lo]
        chord /= np.linalg.norm(chord, axis=1, keepdims=True)
        first, last = _stretch(p, p[seeds], chord, seeds, tol)
        k = int(np.argmax(s[last] - s[first]))
        first, last = int(first[k]), int(last[k])
        for _ in range(2):  # refine by the least-squares line over the stretch
            centre, direction = _line(p[first : last + 1])
            middle = np.array([(first + last) // 2])
            f, g = _stretch(p, centre[None, :], direction[None, :], middle, tol)
            first, last = int(f[0]), int(g[0])
        if s[last] - s[first] < MIN_SPACINGS * spacing:
            continue
        # judged and read inside the stretch by half a chord: its ends are where a curve leaves the line by 2 sigma
        inner = slice(first + int(np.searchsorted(s[first:], s[first] + half)), int(np.searchsorted(s, s[last] - half)) + 1)
        if _trend(p[inner]) > TREND_DEG:
            continue
        level = _angle(p[inner])
        a = 0 if s[first] <= END_SPACINGS * spacing else first
        b = len(p) - 1 if s[-1] - s[last] <= END_SPACINGS * spacing else last
        out[start + a : start + b + 1] = level
        span = float(s[inner][-1] - s[inner][0])
        if given_along is not None:
            span = min(span, float(np.ptp(given_along[start:stop][inner])))
        line[start + a : start + b + 1] = line_accuracy(p[inner], span, scatter, spacing)
    return out, line


__all__ = ["line_accuracy", "straight_flank_angles", "straight_flank_reading"]

"""Where the fits beside a sharp corner of an outline's points put that corner.

Part of the fit stage of the measured-outline pipeline (:mod:`rotorcad.measured.fit`, which cuts the
outline at these corners): the splines of the runs beside each corner, extended past their ends, are
crossed, and the corner moves there unless it is one of exact points on both fits, or the crossing lies
past a point of a run beside it (a hook). The spline smoothing of a run is here too, as both use it.
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np

from rotorcad.curves import Curve, Spline
from rotorcad.measured.recent import recent_results

Smoothing = float | Callable[[int, float], float] | None
"""A spline smoothing: a value (mm²), a rule of a run's point count and scatter (mm²), or None (n sigma^2)."""


def _smoothing(run: np.ndarray, sigma: float, smoothing: Smoothing) -> float:
    """Return scipy's smoothing value for a run of points.

    The user's value (or rule of the count and the scatter, :func:`close_smoothing`), or n sigma^2
    from the estimated scatter (:mod:`rotorcad.measured.outline`); a run too short for a smoothing
    cubic (8 points or fewer) interpolates.
    """
    if callable(smoothing):
        return smoothing(len(run), sigma) if len(run) > 8 else 0.0
    if smoothing is not None:
        return smoothing
    return len(run) * sigma**2 if len(run) > 8 else 0.0


NEAR_CORNER = 10.0
"""Scatters within which a point of a corner's neighbourhood is left out of the fits crossed there
(:func:`_refined_corners`): the narrow-tip male's tip corner at 1 µm of scatter, a land point 5.9 µm
from it on the flank's side of the corner's edge, bent that fit's end (its mate then reached 127 mm
against a 63 mm tip)."""


@recent_results()  # lobe_pieces and tangent_spread locate the same exact outline's corners
def _refined_corners(
    whole: np.ndarray, edges: np.ndarray, points: np.ndarray, sigma: float, smoothing: Smoothing, accuracy: float = 0.0
) -> np.ndarray:
    """Locate the corners of an outline's points where the splines beside each corner cross.

    The splines of the two runs beside a corner (smoothing splines of scattered points,
    interpolating ones of exact points), extended past their ends, are crossed by Newton on both
    parameters. The chords' crossing is off by a sample spacing when the corner falls between
    scattered points, which moves the corner's path on the rack by as much; of exact points it is off
    by the chords' angle to the flank (half the flank's turn over a spacing), and the tip corner's
    tangent sets the blow-hole's apex (a corner found on a point of exact points stays it when that
    point lies within :data:`ON_POINT_GAP` times ``accuracy``, mm, of both splines): exact points of
    the narrow-tip male at 300 a lobe, whose corner fell between two points, gave a blow-hole of
    0.69-2.81 mm² by where the points fell (design 2.778), 2.7777-2.7779 with the splines'
    crossing. A crossing not found within two spacings keeps the chords' one.
    """
    ring = np.vstack([whole, whole, whole])
    near = NEAR_CORNER * sigma
    fits, circles = [], []
    for j, i in enumerate(edges):
        i_next = edges[(j + 1) % len(edges)] + (len(whole) if j + 1 == len(edges) else 0)
        inner = ring[i + 1 : i_next + 1]
        # without the points within a few scatters of either corner: which side of it they fall is the scatter's choice
        inner = inner[(np.hypot(*(inner - points[j]).T) >= near) & (np.hypot(*(inner - points[(j + 1) % len(edges)]).T) >= near)]
        fits.append(Spline.fit(inner, smoothing=_smoothing(inner, sigma, smoothing)) if len(inner) >= 4 else None)
        circles.append(_land_radius(inner, sigma))
    h = float(np.median(np.hypot(*np.diff(whole, axis=0).T)))
    out = np.array(points, dtype=float)
    # an exact outline's corner that is one of its points (a design's CSV) stays that point, when on both fits
    # beside it (ON_POINT_GAP; not the nearest point of a corner that falls between two)
    ends = np.stack([whole[edges], whole[(edges + 1) % len(whole)]], axis=1)  # (m, 2, 2): each corner edge's points
    on_point = np.min(np.linalg.norm(out[:, None, :] - ends, axis=2), axis=1) < 1e-9
    for j in range(len(edges)):
        before, after = fits[j - 1], fits[j]  # the run ending at corner j, and the one starting there
        land = circles[j - 1] if circles[j - 1] is not None else circles[j]
        flank = after if circles[j - 1] is not None else before
        with np.errstate(all="ignore"):  # a diverging Newton step is refused below, not reported
            if land is not None and flank is not None and (circles[j - 1] is None or circles[j] is None):
                # a corner of a land: where the flank's extension meets the land's circle (LAND_CORNER)
                p = _cross_circle(flank, flank.s0 if flank is after else flank.s1, land)
            elif before is None or after is None:
                continue
            else:
                p = _cross_ends(before, after, before.s1, after.s0)
        if p is None:
            continue
        moved = np.hypot(*(p - out[j]))
        if sigma <= 0 and on_point[j] and _off_fits(before, after, out[j]) <= ON_POINT_GAP * accuracy:
            continue  # the corner is that point: the splines' extensions cross off it by their own error
        if moved < 2 * h and not _turns_back(whole, int(edges[j]), p, max(1e-6, 40.0 * sigma)):
            out[j] = p
    return out


LAND_POINTS = 3
"""Fewest points of a run between two corners that make it a land (:func:`_land_radius`)."""


def _land_radius(run: np.ndarray, sigma: float) -> float | None:
    """Return the radius (mm) of a run of points between two corners that lies on a circle about the centre, or None.

    A land (a tip or root arc about the rotor's centre, Rinder's "Kopfkreis") between two sharp corners:
    its points' radii all within 4 sigma (1 nm for exact points) of their mean, :data:`LAND_POINTS` of them
    at least, and the run turning about the centre (its polar angles spanning more than its radii).
    The corner beside it is where the neighbouring flank's extension meets that circle
    (:func:`_refined_corners`), not the land's own spline extended: a tip land of 3-4 points (80 points a
    lobe of the rack-involute male) extended as a spline crossed the flank's 10 um off the tip circle, the
    flank's end tangent bent by 27 mrad, and the blow-hole read -19 %.
    """
    if len(run) < LAND_POINTS:
        return None
    r = np.hypot(*run.T)
    if float(np.ptp(r)) > max(8.0 * sigma, 1e-6):
        return None
    return float(np.mean(r))


def _cross_circle(curve: Curve, u: float, radius: float) -> np.ndarray | None:
    """Where a curve extended past its end ``u`` meets the circle of ``radius`` (mm) about the origin (Newton)."""
    for _ in range(12):
        (p,), (t,) = curve.frame(np.array([u]))
        slope = 2.0 * float(p @ t)
        if not np.all(np.isfinite(p)) or abs(slope) < 1e-9:
            return None
        u -= (float(p @ p) - radius**2) / slope
    p = curve.frame(np.array([u]))[0][0]
    return p if np.all(np.isfinite(p)) and abs(np.hypot(*p) - radius) < 1e-7 else None


def _turns_back(whole: np.ndarray, i: int, corner: np.ndarray, near: float) -> bool:
    """Tell whether a corner on edge ``i`` moved to ``corner`` (mm) lies past the first point of a run beside it.

    The runs (:func:`_runs_between_corners`) go from the corner through the points after edge ``i``, and
    end at it from the points up to ``i``, leaving out those within ``near`` of it. A corner beyond the
    run's first point (or its last) makes the run's spline go back to that point and turn round: a hook
    whose end tangent is reversed, and the corner's fan of normals is lost (rotorcad's own rack-involute
    male at a 0.01 um chord, its sealing tip corner written 72 nm inside the tip on a clip chord, moved
    0.17 um onto the flank: its fan dropped, the sealing meshline read 29.2 mm for 54.6).
    """
    n = len(whole)
    for ahead in (whole[[(i + 1 + k) % n for k in range(4)]], whole[[(i - k) % n for k in range(4)]]):
        kept = ahead[np.hypot(*(ahead - corner).T) > near]
        if len(kept) >= 2 and float((kept[0] - corner) @ (kept[1] - kept[0])) <= 0.0:
            return True
    return False


ON_POINT_GAP = 10.0
"""A corner of exact points found on one of them (:func:`rotorcad.measured.outline.corners`) is that point
when it lies within this many times the points' accuracy of both fits beside it, extended
(:func:`_refined_corners`); else it is where the fits cross. Measured against the designs' corners on
eight samples: rotorcad's own CSVs and 1 µm chord outlines, whose corners are points, 0.001-1.4 µm
off the fits at an accuracy of 0.8-1 µm (at most 1.4 accuracies), and Krigar's root corner at 300
points a lobe, 3.3 µm (5 accuracies; the point 1.2 µm from the corner, the crossing 4.5 µm); evenly
spaced exact points whose corner falls between two, the nearer turning by over 90 % of the corner,
7.7-40 µm (16-84 accuracies), those points 11-43 µm from the corner and the crossing 0.01-4.2 µm.
Krigar's male tip, kept 35 µm off at 300 a lobe, meshed as a flank over 22 mm of meshline, and the
driving flank read "runs" where the design's does not."""


def _off_fits(before: Curve, after: Curve, p: np.ndarray) -> float:
    """Return the larger distance (mm) of ``p`` from two curves extended past their ends (Newton on each)."""
    gaps = []
    for curve, u in ((before, before.s1), (after, after.s0)):
        for _ in range(8):
            (q,), (t,) = curve.frame(np.array([u]))
            u = u + float((p - q) @ t) / max(float(t @ t), 1e-300)
        q = curve.frame(np.array([u]))[0][0]
        gaps.append(float(np.hypot(*(p - q))) if np.all(np.isfinite(q)) else np.inf)
    return max(gaps)


def _cross_ends(before: Curve, after: Curve, u: float, v: float) -> np.ndarray | None:
    """Where two curves extended past their ends cross (Newton on both parameters from u, v)."""
    for _ in range(8):
        (pa,), (ta,) = before.frame(np.array([u]))
        (pb,), (tb,) = after.frame(np.array([v]))
        jac = np.column_stack([ta, -tb])
        if not np.all(np.isfinite(jac)) or abs(np.linalg.det(jac)) < 1e-6:
            return None
        du, dv = np.linalg.solve(jac, pb - pa)
        u, v = u + du, v + dv
    p, q = before.frame(np.array([u]))[0][0], after.frame(np.array([v]))[0][0]
    return p if np.all(np.isfinite(p)) and np.hypot(*(p - q)) < 1e-7 else None

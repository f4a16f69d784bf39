"""Checks of a rotor's points as given: an outline that crosses or runs along itself, outliers, other units.

Part of the first stage of the measured-outline pipeline (:mod:`rotorcad.measured.outline` reads the
points once and calls these on the whole outline it makes). Each check refuses in one sentence
(:class:`rotorcad.errors.DesignError`) naming the option the points came from, the fault, and where
it is: the point's line in the file when the points carry their lines (:func:`file_lines`, as
:func:`exports.csv_points.read_points` returns them), its position in mm, and by how much.

Outliers. A CMM point far off the smooth curve of its neighbours is refused, not smoothed in nor
dropped: a metrologist flags such a point and re-measures it (CMM evaluation software lists the
points its outlier filter rejects rather than fitting through them; a silently smoothed spike moves
the fitted outline, and a silently dropped one hides a probe fault, a chip or a burr). A point is an
outlier when it lies off three predictions from its neighbours alone, each by more than many times
the estimated scatter: the cubic through the two points on either side of it (Lagrange, chord-length
parameter), and the quadratic extrapolations from the three points before and the three after it.
A sharp corner lies on one of its flanks' extrapolations, so only a point off all three is an
outlier; points at a turn of more than :data:`CORNER_TURN` between the neighbours' chords are not
judged (an outlier there cannot be told from a corner).
"""

from __future__ import annotations

import numpy as np

from rotorcad.errors import DesignError
from rotorcad.geometry import cross

OUTLIER_SIGMAS = 12.0
"""A point off its neighbours' curve by more than this many scatters (the cubic prediction's residual has a
standard deviation of 1.28 sigma for evenly spaced points: 9 of its standard deviations) is an outlier."""

OUTLIER_LOCAL = 6.0
"""...and by more than this many times the same residual at the points 3 and 4 away (the curve's own
departure from a cubic there, at sparse points, and the scatter's)."""

OUTLIER_FLOOR = 1e-3
"""mm: and by more than this (exact points: the floor of what is told from a curve's own shape)."""

OUTLIER_SPACING = 0.1
"""...and by more than this share of the spacing of its neighbours (a curve sampled sparsely departs from
their cubic by up to 3 % of it where its curvature changes: the females of 80 points a lobe)."""

ALONG_ANGLE = np.radians(10.0)
"""rad: two chords that touch within this of parallel: the outline runs along itself there."""

CROSSING_LOOP = 0.1
"""A crossing at an angle whose loop is longer than this share of a lobe's outline is a figure of eight."""

CORNER_TURN = np.radians(30.0)
"""rad: a point between neighbours' chords that turn by more than this is at a corner and not judged."""

UNIT_FACTORS = {25.4: "inches", 10.0: "cm", 1000.0: "m", 1e-3: "µm"}
"""Scale factors between a profile's radii and the design's that name a unit mistake."""


def file_lines(points: object) -> np.ndarray | None:
    """Return the line in its file of each of the points, or None when they carry none (1-based)."""
    lines = getattr(points, "lines", None)
    n = len(points) if hasattr(points, "__len__") else -1
    return np.asarray(lines) if lines is not None and len(lines) == n else None


def _where(whole: np.ndarray, k: int, given: np.ndarray | None, lines: np.ndarray | None) -> str:
    """Describe point ``k`` of the whole outline: its line in the file when it is a given point, and its position."""
    x, y = whole[k]
    if given is not None and lines is not None:
        row = np.flatnonzero(np.all(given == whole[k], axis=1))
        if len(row):
            return f"line {int(lines[row[0]])} ({x:.4f}, {y:.4f}) mm"
    return f"({x:.4f}, {y:.4f}) mm"


def _thinned(p: np.ndarray, sigma: float) -> np.ndarray:
    """Return the indices of a closed outline's points thinned to one in each max(5 sigma, h / 4, 1 nm) of its length.

    h is the median spacing. Two points closer than the scatter (a CMM's pairs 0.3-3 µm apart with
    0.5 µm of scatter) would make any curve through them point anywhere; one point in each such
    stretch of outline (the first) keeps the rest evenly enough spaced, however the points bunch.
    """
    step = np.hypot(*(np.roll(p, -1, axis=0) - p).T)
    width = max(5.0 * sigma, 0.25 * float(np.median(step)), 1e-6)
    s = np.concatenate([[0.0], np.cumsum(step[:-1])])
    stretch = np.floor(s / width)
    return np.flatnonzero(np.concatenate([[True], np.diff(stretch) > 0]))


def _lagrange(nodes: np.ndarray, at: np.ndarray) -> np.ndarray:
    """Lagrange weights (n, k) of k nodes (n, k) for the value at ``at`` (n,)."""
    k = nodes.shape[1]
    w = np.ones_like(nodes)
    for j in range(k):  # over the few nodes, not the points
        for m in range(k):
            if m != j:
                w[:, j] *= (at - nodes[:, m]) / (nodes[:, j] - nodes[:, m])
    return w


def _residuals(p: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """Each point's distance from the cubic of its two neighbours either side and from the extrapolations of either side.

    Returns the central, left and right residuals (n,) in mm (normal to the predicting curve) and the
    turn (n,) in rad between the chords (i-2, i-1) and (i+1, i+2) of a closed outline ``p`` (n, 2).
    """

    def at(k: int) -> np.ndarray:
        return np.roll(p, -k, axis=0)

    def dist(a: np.ndarray, b: np.ndarray) -> np.ndarray:
        return np.maximum(np.hypot(*(b - a).T), 1e-12)

    # central: the chord (i-1, i+1) of length c, its middle at 0; the point projected on it
    c = dist(at(-1), at(1))
    u = (at(1) - at(-1)) / c[:, None]
    s = np.einsum("ij,ij->i", p - 0.5 * (at(-1) + at(1)), u)
    nodes = np.column_stack([-0.5 * c - dist(at(-2), at(-1)), -0.5 * c, 0.5 * c, 0.5 * c + dist(at(1), at(2))])
    w = _lagrange(nodes, s)
    pred = w[:, :1] * at(-2) + w[:, 1:2] * at(-1) + w[:, 2:3] * at(1) + w[:, 3:] * at(2)
    central = np.abs(cross(u, p - pred))

    def side(k: int) -> np.ndarray:  # k = -1: from the three before; 1: from the three after
        a, b, d = at(k), at(2 * k), at(3 * k)
        t = np.column_stack([np.zeros(len(p)), dist(a, b), dist(a, b) + dist(b, d)])
        direction = (a - b) / dist(a, b)[:, None]
        s = np.einsum("ij,ij->i", p - a, direction)
        w = _lagrange(t, -s)
        pred = w[:, :1] * a + w[:, 1:2] * b + w[:, 2:] * d
        tangent = pred - a
        norm = np.hypot(*tangent.T)
        tangent = np.where(norm[:, None] > 1e-12, tangent / np.maximum(norm, 1e-12)[:, None], direction)
        return np.abs(cross(tangent, p - pred))

    before, after = at(-1) - at(-2), at(2) - at(1)
    turn = np.abs(np.arctan2(cross(before, after), np.einsum("ij,ij->i", before, after)))
    return central, side(-1), side(1), turn


def outliers(whole: np.ndarray, sigma: float) -> tuple[np.ndarray, np.ndarray]:
    """Find the points of a closed outline far off the smooth curve of their neighbours (module docstring).

    Parameters
    ----------
    whole : (n, 2) float array, mm
        The closed outline, without a repeated end point.
    sigma : float, mm
        Its estimated scatter (:func:`rotorcad.measured.outline.scatter`).

    Returns
    -------
    index : (m,) int array
        The outliers' indices into ``whole``, the farthest off first.
    offset : (m,) float array, mm
        How far each lies off its neighbours' curve (the least of the three residuals).
    """
    p = np.asarray(whole, dtype=float)
    keep = _thinned(p, sigma)
    if len(keep) < 12:
        return np.zeros(0, int), np.zeros(0)
    q = p[keep]
    central, left, right, turn = _residuals(q)
    off = np.minimum(central, np.minimum(left, right))
    local = np.max([np.roll(central, k) for k in (-4, -3, 3, 4)], axis=0)
    spacing = 0.5 * np.hypot(*(np.roll(q, -1, axis=0) - np.roll(q, 1, axis=0)).T)
    limit = np.maximum(
        np.maximum(OUTLIER_SIGMAS * sigma, OUTLIER_LOCAL * local), np.maximum(OUTLIER_SPACING * spacing, OUTLIER_FLOOR)
    )
    bad = np.flatnonzero((off > limit) & (turn < CORNER_TURN))
    order = np.argsort(-off[bad])
    return keep[bad[order]], off[bad[order]]


def refuse_outliers(
    whole: np.ndarray, sigma: float, label: str, given: np.ndarray | None = None, lines: np.ndarray | None = None
) -> None:
    """Refuse an outline with outliers (:func:`outliers`), naming the farthest off: its line, position and offset.

    Raises
    ------
    DesignError
        Naming ``label``.
    """
    index, offset = outliers(whole, sigma)
    if len(index) == 0:
        return
    # name a point as given (the copies of a patterned lobe are not in the file)
    named = [k for k in index if given is not None and np.all(given == whole[k], axis=1).any()] or list(index)
    k = named[0]
    off = float(offset[list(index).index(k)])
    more = f"; {len(index) - 1} more points lie so far off" if len(index) > 1 else ""
    raise DesignError(
        label,
        "points on a smooth outline (a point many times the scatter off its neighbours' curve is an outlier: "
        "remove or re-measure it)",
        None,
        f"the point at {_where(whole, k, given, lines)} lies {off:.4g} mm off the curve of its neighbours, "
        f"{off / max(sigma, 1e-300):.3g} times the estimated scatter {sigma * 1e3:.3g} µm{more}"
        if sigma > 0
        else f"the point at {_where(whole, k, given, lines)} lies {off:.4g} mm off the curve of its neighbours "
        f"(the points' scatter is below 0.1 µm){more}",
    )


def crossing(whole: np.ndarray, sigma: float, teeth: int) -> tuple[int, int, np.ndarray] | None:
    """Find where a closed outline crosses or runs along itself, beyond its scatter.

    Two chords that are not neighbours and touch, cross or overlap (shapely's STRtree, GEOS), with
    the loop between them (the outline from the one to the other, the shorter way round): the
    outline runs along itself when the chords lie within :data:`ALONG_ANGLE` of parallel and the loop
    is longer than max(40 sigma, 0.05 mm) (a run of points reversed or measured twice; a shorter loop
    is the scatter's: points 0.3 µm apart with a µm of scatter zigzag); it crosses itself when the
    loop is longer than :data:`CROSSING_LOOP` of a lobe's outline (a figure of eight). A shorter
    crossing at an angle is a generated envelope's swallowtail (the rack-involute family's male:
    its tip-corner path and flank cross at 30 deg, a loop of 1.2 mm), which the fit smooths over as
    before.

    Parameters
    ----------
    whole : (n, 2) float array, mm
        The closed outline, without a repeated end point.
    sigma : float, mm
        Its estimated scatter.
    teeth : int
        Its lobe count.

    Returns
    -------
    (i, j, point) or None
        The two chords (i, i + 1) and (j, j + 1) of the longest loop and a point where they meet (mm).
    """
    import shapely

    p = np.asarray(whole, dtype=float)
    n = len(p)
    ring = shapely.linearrings(np.vstack([p, p[:1]]))
    if shapely.is_simple(ring):
        return None
    chords = shapely.linestrings(np.stack([p, np.roll(p, -1, axis=0)], axis=1))
    a, b = shapely.STRtree(chords).query(chords, predicate="intersects")
    apart = (b - a) % n
    pairs = (apart > 1) & (apart < n - 1)
    a, b = a[pairs], b[pairs]
    if len(a) == 0:
        return None
    a, b = np.minimum(a, b), np.maximum(a, b)
    step = np.hypot(*(np.roll(p, -1, axis=0) - p).T)
    s = np.concatenate([[0.0], np.cumsum(step)])
    # the outline between the two chords, either way round (chords meeting at a repeated point: none)
    loop = np.minimum(s[b] - s[a + 1], s[-1] - (s[b + 1] - s[a]))
    da, db = np.roll(p, -1, axis=0)[a] - p[a], np.roll(p, -1, axis=0)[b] - p[b]
    sine = np.abs(cross(da, db)) / np.maximum(np.hypot(*da.T) * np.hypot(*db.T), 1e-300)
    along = (sine < np.sin(ALONG_ANGLE)) & (loop > max(40.0 * sigma, 0.05))  # runs back or again along itself
    across = loop > CROSSING_LOOP * s[-1] / max(teeth, 1)  # a figure of eight
    fault = np.flatnonzero(along | across)
    if len(fault) == 0:
        return None
    k = int(fault[np.argmax(loop[fault])])
    where = shapely.get_coordinates(shapely.centroid(shapely.intersection(chords[a[k]], chords[b[k]])))[0]
    return int(a[k]), int(b[k]), np.asarray(where)


def refuse_crossing(
    whole: np.ndarray, sigma: float, teeth: int, label: str, given: np.ndarray | None = None, lines: np.ndarray | None = None
) -> None:
    """Refuse an outline that crosses or runs along itself (:func:`crossing`), naming where and between which points.

    Raises
    ------
    DesignError
        Naming ``label``.
    """
    found = crossing(whole, sigma, teeth)
    if found is None:
        return
    i, j, (x, y) = found
    n = len(whole)
    raise DesignError(
        label,
        "an outline that does not cross or run along itself",
        None,
        f"it crosses or runs along itself at ({x:.4f}, {y:.4f}) mm, between the points at "
        f"{_where(whole, i, given, lines)} and {_where(whole, (j + 1) % n, given, lines)}",
    )


def refuse_other_units(whole: np.ndarray, root: float, tip: float, label: str) -> None:
    """Refuse a profile whose size is the design's by a unit's factor (inches, cm, m), saying so.

    Its largest and smallest radius about the centre against the design's tip and root radii: both
    within 5 % of one factor of :data:`UNIT_FACTORS`.

    Raises
    ------
    DesignError
        Naming ``label``.
    """
    r = np.hypot(*np.asarray(whole, dtype=float).T)
    big, small = float(r.max()), float(r.min())
    if not (big > 0 and small > 0 and tip > 0 and root > 0):
        return
    for factor, unit in UNIT_FACTORS.items():
        if abs(tip / big / factor - 1) < 0.05 and abs(root / small / factor - 1) < 0.05:
            size = f"{factor:.4g} times smaller" if factor > 1 else f"{1 / factor:.4g} times larger"
            raise DesignError(
                label,
                "points in mm, of the design's size",
                None,
                f"its tip and root radii {big:.4g} and {small:.4g} mm are {size} than the design's {tip:.4g} and "
                f"{root:.4g} mm ({unit}? write the points in mm)",
            )


PITCH_MARGIN = 0.05
"""Share of the lobe depth by which a rotor's pitch circle may lie outside its points' radii (a
profile thinned by a clearance, or measured hot, whose root or tip lies on the pitch circle)."""


def refuse_pitch_off_profile(points: np.ndarray, teeth: int, pitch_radius: float, option: str) -> None:
    """Refuse a lobe count whose pitch circle misses the rotor's points, naming the count their span implies.

    The rack that generates a pair rolls on each rotor's pitch circle, r_w = a z / (z1 + z2), and each
    rotor's profile reaches it (the pitch circles roll on each other; a screw rotor's male addendum
    lies outside its pitch circle, the female's dedendum inside hers). One lobe of a 5-lobe male with
    ``--male-teeth 4`` (a span of 0.8 of the pitch 4 lobes imply, read as one tooth and its root land)
    put the pitch circle 6 mm inside the root, and ``clearance`` read -4865 µm and interference.

    Parameters
    ----------
    points : (n, 2) float array, mm
        The rotor's points (one lobe, groove or tooth, or the whole outline) in its own frame.
    teeth : int
        The lobe count given.
    pitch_radius : float, mm
        The pitch radius that count gives.
    option : str
        The option that gave the count (``--male-teeth``).

    Raises
    ------
    DesignError
        Naming ``option``, the pitch radius against the points' radii, and the lobe count the points'
        span implies (one lobe of a rotor of 360 deg / span lobes, when the span is that within 2 %).
        A whole outline is left to the count of its lobes when it is read
        (:func:`rotorcad.measured.outline.whole_outline`).
    """
    pts = np.asarray(points, dtype=float)
    r = np.hypot(*pts.T)
    low, high = float(r.min()), float(r.max())
    margin = PITCH_MARGIN * (high - low)
    if not (np.isfinite(pitch_radius) and pitch_radius > 0) or low - margin <= pitch_radius <= high + margin:
        return
    for factor, unit in UNIT_FACTORS.items():  # the pitch circle a unit's factor off the points: the units
        if low > 0 and low * factor * (1 - 0.1) <= pitch_radius <= high * factor * (1 + 0.1):
            size = f"{factor:.4g} times smaller" if factor > 1 else f"{1 / factor:.4g} times larger"
            raise DesignError(
                option.replace("-teeth", "-points"),
                "points in mm",
                None,
                f"its radii {low:.4g}-{high:.4g} mm are about {size} than its pitch circle r = {pitch_radius:.4g} mm "
                f"that the centre distance and the lobe counts give ({unit}? write the points in mm)",
            )
    ang = np.unwrap(np.arctan2(pts[:, 1], pts[:, 0]))
    span = float(abs(ang[-1] - ang[0]))
    if span > 1.5 * np.pi:  # a whole outline: its lobes are counted when it is read (it has 5 lobes)
        return
    implied = round(2 * np.pi / span) if span > 0 else 0
    if implied >= 2 and abs(span * implied / (2 * np.pi) - 1.0) < 0.02:
        hint = f"its points span {np.degrees(span):.4g} deg, one lobe of a {implied}-lobe rotor (give {option} {implied})"
    else:
        share = span / (2 * np.pi / teeth)
        hint = f"its points span {np.degrees(span):.4g} deg, {share:.3g} times the lobe pitch {teeth} lobes imply"
    raise DesignError(
        option,
        "the rotor's lobe count, whose pitch circle crosses its points",
        teeth,
        f"{teeth} lobes put the pitch circle at r = {pitch_radius:.4g} mm, off the points' radii {low:.4g}-{high:.4g} mm; {hint}",
    )


__all__ = [
    "ALONG_ANGLE",
    "CORNER_TURN",
    "CROSSING_LOOP",
    "OUTLIER_FLOOR",
    "OUTLIER_LOCAL",
    "OUTLIER_SIGMAS",
    "OUTLIER_SPACING",
    "PITCH_MARGIN",
    "UNIT_FACTORS",
    "crossing",
    "file_lines",
    "outliers",
    "refuse_bad_points",
    "refuse_crossing",
    "refuse_other_units",
    "refuse_outliers",
    "refuse_pitch_off_profile",
]


def refuse_bad_points(
    whole: np.ndarray, sigma: float, teeth: int, label: str, given: np.ndarray | None = None, lines: np.ndarray | None = None
) -> None:
    """Refuse a whole outline that crosses or runs along itself, then one with outliers (one sentence naming ``label``)."""
    given = None if given is None or isinstance(given, list) else np.asarray(given, dtype=float)
    refuse_crossing(whole, sigma, teeth, label, given, lines)
    refuse_outliers(whole, sigma, label, given, lines)

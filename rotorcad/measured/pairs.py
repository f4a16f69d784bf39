"""Rotor pairs from measured points: of the rack, of the male or of the female rotor.

The last stage of the measured-outline pipeline (:mod:`rotorcad.measured`). A rotor's fitted lobe
(:mod:`rotorcad.measured.fit`) is turned into its rack by inverse generation (Wu & Chi sec. 2,
eqs. 4-8, in the transverse section), and the pair is generated from that rack; the rotor given
comes back as its own conjugate's conjugate (a round trip that the tests check). Corner paths, its
own and the mate's (point-generated flanks, Rinder Fig. 1-4), are found and marked as in the
families. Calls go down the pipeline only (fit, then outline).
"""

from __future__ import annotations

import numpy as np

from rotorcad.curves import Curve, Mapped, PointPath
from rotorcad.envelope import Generated, conjugate
from rotorcad.errors import DesignError
from rotorcad.inverse_rack import MEASURED_JOIN_GAP, MEASURED_MIN_TURN, with_corner_fans
from rotorcad.measured.corner_paths import corner_point_path, joined_mate_paths
from rotorcad.measured.corner_stall import point_jitter, sampled_below_nyquist, stalled_samples
from rotorcad.measured.fit import fit_residual, lobe_pieces, tangent_spread
from rotorcad.measured.outline import read_outline
from rotorcad.measured.rack_pieces import tip_corner_path
from rotorcad.measured.tangent import tip_tangent_accuracy
from rotorcad.rack_roles import piece_role
from rotorcad.roles import Flank, PieceRole, Side, tip_corner_name
from rotorcad.roots import bisect_levels
from rotorcad.rotor_pair import RotorPair
from rotorcad.screw_rotors import RackPiece, ScrewRotors

CONFIDENCE = 0.95
"""Confidence with which a stated accuracy bounds the largest error over the points it is stated for."""


def max_factor(count: float, confidence: float = CONFIDENCE) -> float:
    """Return k such that the largest |e| of ``count`` independent N(0, 1) errors stays below k with ``confidence``.

    P(max |e_i| > k) <= count P(|e| > k) = 2 count (1 - Phi(k)) (Boole's inequality), so
    k = Phi^-1(1 - (1 - confidence) / (2 count)): 1.96 for one error, 3.42 for 80, 3.76 for 300, 4.21 for 2000
    at 95 %. Not 2: the largest of hundreds of Gaussian errors lies beyond 2 sigma almost surely.

    Parameters
    ----------
    count : float
        Number of independent errors (at least 1).
    confidence : float
        Probability that the bound holds.

    Returns
    -------
    float
    """
    # Phi^-1 as scipy.stats.norm computes it (isf(q) = -ndtri(q)), without importing scipy.stats (0.3 s)
    from scipy import special

    return float(-special.ndtri((1.0 - confidence) / (2.0 * max(count, 1.0))))


def scatter_bound(sigma: float, count: float) -> float:
    """Return the bound (mm) on the largest deviation of a fitted outline caused by the points' scatter.

    k sigma (:func:`max_factor`, 95 % confidence) for ``count`` points of scatter ``sigma`` (mm): the
    smoothing fit's own error at a point has a standard deviation of at most the scatter's, and the
    largest over the lobe is that of ``count`` of them. 0 for exact points.
    """
    return max_factor(count) * sigma if sigma > 0 else 0.0


SCATTERED_STALL = 0.15
"""Of scattered points: the mate's point moving less than this share of the rack point's motion over
1/40 of a rack curve stands still (:func:`_mate_corner_runs`): 0.01-0.11 along the samples' mate
tip corner paths at 1-2 µm of scatter, 0.35-1 along the flanks their racks generate."""


PATH_FIT = 10.0
"""Accuracies of the profile within which a mate's tip-corner path found on the rack is taken as that
corner's exact trochoid (:func:`rotorcad.measured.rack_pieces.tip_corner_path`): from the samples' exact
male points the female tip's path lies within 0.1-0.6 um of it (accuracy 0.3-1 um). Exact points only."""

EXACT_CORNER_WANDER = 10.0
"""Of exact points, how far (in multiples of the profile's accuracy) the mate's point generated along
one tip corner's path may wander (:func:`_mate_corner_runs`). The interpolating fit of points 0.3 mm
apart (Krigar, Lysholm males, 300 points a lobe evenly spaced) lets it leave the corner by more than
0.1 µm: the path fell apart into 4-11 stalled parts with flanks between them, each a cusp, and the
flanks' geometric contact ran without timing gears where the design does not. The parts' corners lie
0.1-3.3 µm apart at an accuracy of 0.66 µm; ten times the accuracy is the meshline's own
(:data:`rotorcad.meshing.MESHLINE_GAIN`)."""


SPARSE_TURN = np.radians(40.0)
"""Largest turn (rad) of the points' outline from one point to the next at which the lobe's roundings are
followed: where the points turn more near the rack points the lobe loses, the refusal says they are too sparse
(:func:`_lost_rack_refusal`). The N-rack female (tip rounding 2.07 mm) from points evenly spaced along its
exact outline, 8 start phases each: 50-62 deg a spacing (30-36 points a lobe) refused on most phases, 45 deg
(40 a lobe) and less on none, exact or with 2 um (a rounding spread over more than two spacings is read as a
rounding, :data:`rotorcad.measured.fit.LONG_ROUNDING`); 40 deg leaves a margin."""


def _lost_rack_refusal(label: str, whole: np.ndarray | None, teeth: int, lost_at: np.ndarray, share: float) -> DesignError:
    """Return the refusal of a lobe whose share ``share`` (per cent) of normals misses the pitch circle.

    Where the given points near the lost rack points turn by more than :data:`SPARSE_TURN` from one
    point to the next, they step over a rounding (the fit reads a sharp corner whose fan of normals misses
    the pitch circle) and the sentence says they are too sparse, with the points a lobe that would follow
    it (the turn a spacing scaled to :data:`SPARSE_TURN`, rounded up to 10); otherwise that the profile
    has no rack there (a drawing in metres, no rotor).

    Parameters
    ----------
    label : str
        How the points are named (``"female points"``).
    whole : (n, 2) float array, mm, or None
        The whole outline's points in the rotor's own frame (None for a drawing's curves).
    teeth : int
        The rotor's lobes.
    lost_at : (m, 2) float array, mm
        Profile points, own frame, whose normals gave no rack point.
    share : float, per cent
        Share of the lobe's samples without a rack point.

    Returns
    -------
    DesignError
    """
    lost = f"{share:.1f} % of the lobe has no rack point"
    if whole is not None and len(lost_at) and len(whole) > 4:
        step = np.roll(whole, -1, axis=0) - whole
        heading = np.arctan2(step[:, 1], step[:, 0])
        vertex_turn = np.abs((heading - np.roll(heading, 1) + np.pi) % (2 * np.pi) - np.pi)  # at each point
        from scipy.spatial import cKDTree

        near = cKDTree(whole).query(lost_at)[1]  # the given point nearest to each lost one
        around = (near[:, None] + np.arange(-2, 3)[None, :]) % len(whole)
        k = around.ravel()[np.argmax(vertex_turn[around.ravel()])]
        turn = float(vertex_turn[k])
        if turn > SPARSE_TURN:
            per_lobe = len(whole) / teeth
            enough = int(np.ceil(per_lobe * turn / SPARSE_TURN / 10.0) * 10)
            spacing = float(np.hypot(*step[k]))
            return DesignError(
                label,
                f"dense enough to follow the lobe's roundings, about {enough} points a lobe or more here",
                f"{per_lobe:.0f} points a lobe",
                f"at r = {np.hypot(*whole[k]):.2f} mm they turn by {np.degrees(turn):.0f} deg from one point to the "
                f"next ({spacing:.2g} mm apart; {np.degrees(SPARSE_TURN):.0f} deg or less follows a rounding), too "
                f"coarse to tell the rounding there from a sharp corner whose normals miss the pitch circle; {lost}",
            )
    return DesignError(label, "a profile whose every normal meets its pitch circle (it has a rack)", None, lost)


def mate_wander(
    rack_curve: Curve,
    mate: Generated,
    s: np.ndarray,
    accuracy: float,
    turn: float | np.ndarray,
    known: tuple[np.ndarray, np.ndarray, np.ndarray] | None = None,
) -> np.ndarray:
    """Return how far (mm) the mate's point generated at rack parameters ``s`` may lie from the true one.

    A rack derived from a rotor's points carries that profile's errors: a position error of up to
    ``accuracy`` (mm) and a normal turned by up to ``turn`` (rad, the fitted tangent's accuracy). A
    moved or turned normal meets the pitch line elsewhere, so the rack point touches the mate at
    another instant and generates another mate point (Wu & Chi sec. 2, eq. 4: the contact where the
    normal passes the pitch point C): the bound is ``accuracy`` plus the largest displacement of the
    mate's point with the rack point moved by +-``accuracy`` along its normal and the normal turned
    by +-``turn``, computed by the same contact condition (:func:`rotorcad.envelope.conjugate`). Where
    the rack's normal runs nearly along the pitch line (a female tip path ending on it) the position
    alone moves the mate's point by tens of micrometres. Along a mate tip corner's path that displacement grows
    roughly as |P - C|^2 / r_w per radian (measured: 1 um of scatter on the asymmetric SRM female,
    6.9 mrad, lets the male's tip corner wander by 1 um at O1O2 and by 0.1 mm near the apex).

    Parameters
    ----------
    rack_curve : Curve
        The rack piece (fixed frame at t = 0).
    mate : Generated
        The mate generated by it.
    s : (n,) float array
        Parameters of ``rack_curve``.
    accuracy : float, mm
        Position accuracy of the profile the rack comes from.
    turn : float or (n,) float array, rad
        Accuracy of its tangent direction (at each parameter).
    known : tuple of three (n, 2) float arrays, optional
        ``rack_curve.evaluate(s)`` (points, mm, and tangents) and ``mate.evaluate(s)[0]`` (mm),
        where the caller has them already.

    Returns
    -------
    (n,) float array, mm
    """
    s = np.atleast_1d(np.asarray(s, dtype=float))
    p, tg, base = known if known is not None else (*rack_curve.evaluate(s), mate.evaluate(s)[0])
    normal = np.column_stack([tg[:, 1], -tg[:, 0]])
    moved = np.zeros(len(s))
    turn = np.broadcast_to(np.asarray(turn, dtype=float), len(s))
    for angle, offset in ((-turn, -accuracy), (-turn, accuracy), (turn, -accuracy), (turn, accuracy)):
        c, n = np.cos(angle), np.sin(angle)
        turned = np.column_stack([c * tg[:, 0] - n * tg[:, 1], n * tg[:, 0] + c * tg[:, 1]])
        q = conjugate(p + offset * normal, turned, mate.generating, mate.generated).points
        moved = np.maximum(moved, np.nan_to_num(np.hypot(*(q - base).T), nan=np.inf))
    return accuracy + moved


def _wander_run(pm: np.ndarray, i: int, j: int) -> tuple[int, int, float]:
    """Return the samples around a stalled run ``pm[i:j]`` of the mate's point that stay as near its corner.

    The corner is the median of the run's points, the wander three times the 90th percentile of
    their distances from it; the result is the first and last sample of the contiguous stretch
    within that wander (a scattered profile's corner path, :func:`_mate_corner_runs`), and the
    wander (mm).
    """
    corner = np.nanmedian(pm[i:j], axis=0)
    dist = np.nan_to_num(np.hypot(*(pm - corner).T), nan=np.inf)
    wander = 3.0 * float(np.quantile(dist[i:j][np.isfinite(dist[i:j])], 0.9)) if np.isfinite(dist[i:j]).any() else 0.0
    far = np.flatnonzero(dist > wander)
    centre = i + int(np.argmin(dist[i:j]))
    return int(far[far < centre].max(initial=-1)) + 1, int(far[far > centre].min(initial=len(pm))) - 1, wander


def departure(mate: Generated, corner: np.ndarray, edge: float, inside: float, span: float) -> float:
    """Return where the mate's point leaves its corner, from where it is first seen beyond its wander.

    Beyond the hand-over the mate's point runs away from the corner about linearly in the rack
    parameter (speed v), so by ``edge`` (where it leaves the wander w) it has run w already: the
    hand-over lies dist(edge) / v before ``edge``, v fitted over five steps of 1/400 of the curve's
    ``span`` beyond it, and no further back than ``inside`` (the last sample within the wander).
    Without it each end of a path ran w / v long (the narrow-tip male 5 µm off its brute-force
    envelope, from exact female points).
    """
    direction = 1.0 if edge >= inside else -1.0
    x = edge + direction * 2.5e-3 * span * np.arange(5)
    q = mate.evaluate(x)[0]
    if not np.all(np.isfinite(q)):
        return edge
    dist = np.hypot(*(q - corner).T)
    slope = float(np.polyfit(direction * (x - edge), dist, 1)[0])
    back = dist[0] / slope if slope > 0 else 0.0
    return float(np.clip(edge - direction * back, min(edge, inside), max(edge, inside)))


def _to_piece_ends(
    pr: np.ndarray, dist: np.ndarray, near: np.ndarray, lo: int, hi: int, same: float, shortest: float
) -> tuple[int, int]:
    """Return a mate tip corner's path of exact points ``lo..hi`` (sample indices) run on to the rack piece's ends.

    The piece ends where the rotor given has a corner, and the fit's end leaves the mate's point off its corner
    there (the symmetric SRM male's root corners, 600 exact points a lobe: 5-94 um over the last 10 of 801 samples,
    the female tip's path reaching the pitch line, where the rack's normal runs along it): its last stretch read
    as a flank of a few tenths of a millimetre, whose mate was a female cusp, and the flank "did not run" at two of
    8 start phases. Towards each end the path runs on as far as the mate's point stays within ``same`` (mm, the
    wander of one corner's path, :data:`EXACT_CORNER_WANDER`) of its corner, and on to the end where the rest
    of the rack (``pr``, (n, 2) mm, the samples) to it is shorter than ``shortest`` (mm, the resolution of
    the defect tests: no verdict is read off it). ``dist`` (n,) are the mate's points' distances (mm) from the corner.
    Within that stretch it runs to the farthest samples back within the mate point's own bound (``near``, (n,) bool),
    which the fit's tangent jitter leaves and regains once a point spacing (narrow-tip female, 700 exact points a lobe:
    9.90 mm of path for the design's 9.93, not 6.79); the ends are bisected to it (to the wide one: 7-8 um of flank lost).
    """
    loose = np.flatnonzero(dist > same)
    start = int(loose[loose < lo].max(initial=-1)) + 1  # as far as the mate's point stays within one corner's wander
    stop = int(loose[loose > hi].min(initial=len(dist))) - 1
    held = np.flatnonzero(near[start : stop + 1]) + start  # back within its own bound there: the path goes on
    lo, hi = (min(lo, int(held[0])), max(hi, int(held[-1]))) if len(held) else (lo, hi)
    if 0 < lo and np.hypot(*(pr[start] - pr[0])) < shortest:
        lo = 0
    if hi < len(dist) - 1 and np.hypot(*(pr[-1] - pr[stop])) < shortest:
        hi = len(dist) - 1
    return lo, hi


def _one_corner(same_corner: float, pm: np.ndarray, runs: list[tuple[int, int]], tip: tuple | None) -> float:
    """Return how far apart (mm) the corners of two stalled runs of exact points may lie and be one corner's path.

    ``same_corner`` (mm, :data:`EXACT_CORNER_WANDER` times the profile's accuracy; 0: scattered points, returned as
    it is) plus :data:`EXACT_CORNER_WANDER` times the jitter of the mate's point about its corner along the
    ``runs`` (sample ranges): the 90th percentile of the distances of the runs' mate points ``pm`` ((n, 2), mm) from
    their run's corner (the median), over the runs whose corner lies on the mate's tip circle (``tip``: centre,
    radius, tolerance, mm; every run without it). Exact points carry no position error to speak of, but the cubic
    through them turns its tangent by tens of microradians between the points (Krigar's male at 600 points a lobe:
    50-170 urad on the rack against the design's cycloid, the points 0.02 um off it), and the mate's point
    generated along a tip corner's path follows the normal: it jittered by 1-7 um from sample to sample, where the
    profile's accuracy (0.16 um) allowed 1.6 um, and one female tip corner's path fell apart into 2-4 parts with
    flanks between them, each a female cusp.
    """
    if same_corner <= 0:
        return same_corner
    dists = []
    for i, j in runs:
        corner = np.nanmedian(pm[i:j], axis=0)
        if tip is not None and abs(np.hypot(*(corner - tip[0])) - tip[1]) > tip[2]:
            continue
        d = np.hypot(*(pm[i:j] - corner).T)
        dists.append(d[np.isfinite(d)])
    pooled = np.concatenate(dists) if dists else np.zeros(0)
    return same_corner + EXACT_CORNER_WANDER * (float(np.quantile(pooled, 0.9)) if len(pooled) else 0.0)


def _mate_corner_runs(
    rack_curve: Curve,
    mate: Generated,
    threshold: float = 0.02,
    tolerance: float = 1e-4,
    scattered: bool = False,
    tip: tuple[np.ndarray, float, float] | None = None,
    shortest: float = 0.0,
    same_corner: float = 0.0,
    accuracy: float = 0.0,
    turn: float = 0.0,
    spacing: float = 0.0,
) -> list[tuple[float, float, bool]]:
    """Split a rack curve derived from one rotor into flank-generating parts and the mate's corner paths.

    Along a corner path the mate's generated point stands still: it is the path of a sharp corner of
    the mate (its tip corner sweeping this rotor's point-generated flank), which the mate receives as
    that corner only. Returns (s0, s1, is_corner_path) along the travel.

    Classification (positions only, no tangents): over a stencil of 1/200 of the curve the mate's
    point moves less than ``threshold`` times the rack point; a part stalled so over at least 1/100
    of the curve is a corner path. Its ends are where the mate's point leaves that corner by more
    than ``tolerance`` (mm), found by bisection.

    Of ``scattered`` points (a scatter estimated, :func:`rotorcad.measured.outline.scatter`), the
    mate's point does not stand still: 1 µm of scatter on a male flank that the female tip corner
    generates lets the female's generated point wander by 0.1-0.4 mm while the rack runs 10-14 mm
    (4-6 % of its speed, against 35-100 % along a flank the rack generates; measured on the
    Krigar, Lysholm and asymmetric SRM samples), and the path fell apart into corners 0.1 µm long
    and flanks between them, each a cusp. There the stall is judged over a stencil of 1/40 of the
    curve, below :data:`SCATTERED_STALL` of the rack point's motion, and a stalled part ends where
    the stall does (the mate's point never stays within ``tolerance``). And only the mate's tip
    corner stands so (Rinder sec. 2.2.2: at a tip only a corner is possible): ``tip`` (the mate's
    centre, tip radius and a tolerance, mm) keeps the runs whose corner lies on the tip circle. The
    samples' tip corner paths lie within 0.02 mm of it at 1 µm of scatter; flanks the rack generates
    slowly (the N rack's female sealing flank, 4-15 % of the rack's speed) 2.5-7.3 mm inside it.
    A path along which the rack runs less than ``shortest`` (mm, the profile's resolution) is a
    flank: the independent 4/6 and 5/6 pairs' females with 2 µm of scatter stall the male's point
    over 0.5-0.8 mm of rack near its tip, which has no corner (their real tip paths: 3-10 mm).

    Of exact points, two stalled parts whose corners lie within ``same_corner`` (mm) of each other, widened by
    the mate point's jitter along the stalled parts (:func:`_one_corner`), are one corner's path, with what lies
    between them (:data:`EXACT_CORNER_WANDER`). The stall, and the path where the given points' ``spacing`` (mm) spans
    under two samples, allow its jitter from one sample to the next (:mod:`rotorcad.measured.corner_stall`).

    Of exact points, a run inside the rack piece (reaching neither of its ends) is a corner path only
    where its corner lies on the mate's tip circle (``tip``): the male's 0.67 mm tip rounding of the N
    rack and Rinder-Deix pairs, generated from the female's splines or 300 exact points a lobe, moves
    the male's point at 2-5 % of the rack's speed, and its slowest stretch (0.35-2.25 mm of rack, its
    corner 0.19 mm inside the tip circle) was read as the male's tip corner, which cut the rounding
    short where the apex lies (blow-hole +1.7 % from the splines and +7.2 % from the polyline, now
    -0.28 % and +0.42 %). A run from an end of the piece stays a corner path wherever its corner lies, unless the rack runs
    less than ``shortest`` along it off the mate's tip circle: her cusp (the rack-involute male's sealing flank, CSV, DXF,
    300 exact a lobe: her involute's cusp N2 on her base circle, 7.4 mm inside her tip circle, within 1-2 um over 0.24-0.28
    mm of rack as on the design's rack, was her tip path; ``hob`` reads no undercut there). A run inside the piece along
    which the rack runs less than ``shortest`` (the resolution, as of scattered points) is the mate's point standing
    still for an instant, its cusp, not its tip corner's path (judged on the parts, after the path is run on over a
    flank part too short to count: the narrow-tip male's female tip path, 1000 exact points a lobe, is seen within its
    wander at one sample and reaches the piece's end so): the stall test's stencil is a share of the piece, so
    that whether a cusp's quadratic stall passes for a run depended on where the fit cut its pieces (the shapely-cut
    5/6 arc-flank male, 600 exact points a lobe: at one start phase of eight a driving flank piece 1.6 mm of rack
    long, against 14.6 at the others, stalled the female's cusp 34.7 um inside its tip circle over 11 samples, and
    0.05 mm of rack read as the female tip corner's path: "driving runs without timing gears" where the others, and
    the female cusp they read, say not).

    Of exact points, how far the mate's point may stray from its corner and still be that corner
    follows the profile's accuracy: ``tolerance`` plus :func:`mate_wander` of the profile's
    ``accuracy`` (mm) and tangent ``turn`` (rad) at each rack point; the pair from exact points passes
    its accuracy alone (a tangent bound from the fit's spread, 3-4.6 mrad along 1 µm-chord outlines,
    let the paths swallow flank: the racks derived back from the two rotors 1.7 mm apart). A fixed
    0.1 µm cut the narrow-tip male's tip path from exact female points (300 a lobe;
    the male's point within 0.3 µm of its corner all along, at an accuracy of 0.77 µm) 3.6 mm of rack
    after the piece begins, and that part counted as working contact: sealing transverse contact
    ratio 0.343 for the design's 0.175 (SRM-B 0.330 for 0.184, asymmetric SRM 0.231 for 0.184). Of scattered points the wander
    bound (up to 0.15 mm near the N rack's male tip rounding at 1 µm) would take a rounding 0.67 mm
    long for a corner, so their paths keep the stall test above.
    """
    span = rack_curve.s1 - rack_curve.s0
    s = rack_curve.s0 + span * np.linspace(0.0, 1.0, 801)
    pr, tr = rack_curve.evaluate(s)
    pm, _ = mate.evaluate(s)
    k = 20 if scattered else 4  # stencil of k samples either side (1/40, 1/200 of the curve)
    threshold = SCATTERED_STALL if scattered else threshold
    stalled = stalled_samples(pr, pm, k, threshold, not scattered)  # of exact points, less their jitter
    edges = np.flatnonzero(np.diff(stalled.astype(int))) + 1
    bounds = [0, *edges.tolist(), len(s)]
    runs = [(bounds[i], bounds[i + 1]) for i in range(len(bounds) - 1) if stalled[bounds[i]] and bounds[i + 1] - bounds[i] >= 8]
    if not runs:
        return [(rack_curve.s0, rack_curve.s1, False)]

    wander = tolerance + mate_wander(rack_curve, mate, s, accuracy, turn, (pr, tr, pm))  # how far the mate's point may stray

    def within(corner: np.ndarray, x: np.ndarray) -> np.ndarray:
        q = mate.evaluate(x)[0]
        bound = tolerance + mate_wander(rack_curve, mate, x, accuracy, turn, (*rack_curve.evaluate(x), q))
        with np.errstate(invalid="ignore"):
            return np.isfinite(q).all(axis=1) & (np.hypot(*(q - corner).T) <= bound)

    def leave(corner: np.ndarray, inside: float, outside: float) -> float:
        start = inside  # the last sample inside: the hand-over lies no further back
        inside, outside = bisect_levels(lambda x: within(corner, x), inside, outside, 30, levels=6)
        return departure(mate, corner, float(0.5 * (inside + outside)), start, abs(span))

    out, last, tip_paths = [], rack_curve.s0, []  # tip_paths: rack parameters of paths of the mate's tip corner
    same_corner = _one_corner(same_corner, pm, runs, tip)  # of exact points: with the jitter of the fit's tangents
    jitter = point_jitter(pm, k) if not scattered and sampled_below_nyquist(rack_curve, s, spacing) else 0.0  # mm
    noise = max(10 * tolerance, same_corner)  # how much mate flank beside a corner path is noise near the path's end
    # the last corner's corner (mate, mm), rack point (mm) and where its path was last seen (rack parameter)
    previous = (np.full(2, np.nan), np.full(2, np.nan), rack_curve.s0)
    for i, j in runs:
        # the corner is where most of the run's mate points lie; the path extends exactly as far as the
        # mate's point stays within its wander of it (a slowly moving flank next to it may pass the
        # stall test without being the corner)
        corner = np.nanmedian(pm[i:j], axis=0)
        dist = np.nan_to_num(np.hypot(*(pm - corner).T), nan=np.inf)
        near = dist <= wander + jitter  # of exact points, as far as the fit's jitter of the mate's point
        centre = i + int(np.argmin(dist[i:j] / wander[i:j]))
        far = np.flatnonzero(~near)
        lo = int(far[far < centre].max(initial=-1)) + 1  # the run of near samples around the centre
        hi = int(far[far > centre].min(initial=len(s))) - 1
        off_tip = tip is not None and abs(np.hypot(*(corner - tip[0])) - tip[1]) > tip[2]
        if off_tip and (scattered or (0 < lo and hi < len(s) - 1)):
            continue  # not the mate's tip corner: a flank generated slowly (of exact points, inside the piece)
        if scattered:  # as far as the mate's point stays within its own wander of the corner
            lo, hi, spread = _wander_run(pm, i, j)
            noise = max(noise, spread)
            a, b = max(s[lo], last) if span > 0 else min(s[lo], last), s[hi]
        else:
            if not off_tip and shortest > 0:
                lo, hi = _to_piece_ends(pr, dist, near, lo, hi, same_corner, shortest)
            a = rack_curve.s0 if lo == 0 else leave(corner, s[lo], s[lo - 1])
            b = rack_curve.s1 if hi == len(s) - 1 else leave(corner, s[hi], s[hi + 1])
        middle = pr[(i + j) // 2]
        same = SCATTERED_STALL * np.hypot(*(middle - previous[1])) if scattered else same_corner
        again = bool(np.hypot(*(corner - previous[0])) <= same)
        if again:  # the same corner again, stalled since the path was last seen: what lies between is its path too
            a = previous[2] if (previous[2] - last) * span >= 0 else last
        else:
            previous = (corner, middle, a)
        if (b - a) * span <= 0:
            # no path (the mate's point within its wander at one sample only): the corner is still seen there, so
            # that a run of it further on takes its path from here, and the last path is not run on to it (the
            # symmetric SRM male's whole lobe arc, 600 points a lobe, read as the near female tip's path)
            continue
        previous = (previous[0], previous[1], b)
        if (a - last) * span > 0:  # along the travel, which may run to smaller parameters
            out.append((last, a, False))
        out.append((a, b, True))
        tip_paths += [] if off_tip else [(min(a, b), max(a, b))]
        last = b
    if last != rack_curve.s1:
        out.append((last, rack_curve.s1, False))
    parts = []
    for a, b, c in out:
        if abs(b - a) <= 1e-12 * abs(span):
            continue
        tiny = False
        if not c:  # a flank part beside a corner path that gives the mate under 10 um of flank (of
            ends, _ = mate.evaluate(np.array([a, b]))  # scattered points: the wander) is noise near the path's end
            # of exact points: or within the wander where it is (near the pitch line the mate's point strays
            # by tens of micrometres: Krigar's male, 300 points a lobe, left 0.07 mm of rack as flank there)
            order = np.argsort(s)
            local = float(np.interp([a, b], s[order], wander[order]).max()) if not scattered else 0.0
            tiny = bool(np.all(np.isfinite(ends)) and np.hypot(*(ends[1] - ends[0])) < max(noise, local))
        if parts and ((c and (parts[-1][2] or parts[-1][3])) or (parts[-1][2] and tiny)):
            parts[-1] = [parts[-1][0], b, True, False]
        else:
            parts.append([a, b, c, tiny])
    if shortest > 0 and parts:  # a corner path shorter than the resolution is no verdict: a flank (of exact
        # points, one inside the piece or from an end off the mate's tip circle: a tip path run on to an end stays)
        ends, _ = rack_curve.evaluate(np.array([x for a, b, _, _ in parts for x in (a, b)]))
        for k, part in enumerate(parts):
            on_tip = any(x < max(part[:2]) and y > min(part[:2]) for x, y in tip_paths)
            judged = scattered or (rack_curve.s0 != part[0] and part[1] != rack_curve.s1) or not on_tip
            part[2] = part[2] and not (judged and bool(np.hypot(*(ends[2 * k + 1] - ends[2 * k])) < shortest))
        merged: list[list] = []
        for part in parts:
            if merged and not part[2] and not merged[-1][2]:
                merged[-1][1] = part[1]
            else:
                merged.append(part)
        parts = merged
    return [(a, b, c) for a, b, c, _ in parts]


def _joints(racks: list[Curve], k: int, side: Side, period: float) -> list[np.ndarray]:
    """Return where the rack pieces beside corner ``k`` end, in the rack's travel: the corner path's targets.

    The male's pieces follow the rack's travel, the female's run against it; a neighbour across the
    lobe's ends (the first or last piece, turned by one pitch) is one rack period away, either way.
    """
    n = len(racks)
    before, after = (k - 1, k + 1) if side is Side.MALE else (k + 1, k - 1)
    shift = np.array([[0.0, 0.0], [0.0, period], [0.0, -period]])
    out = []
    for j, end in ((before, "end"), (after, "start")):
        curve = racks[j % n]
        point = curve.end if end == "end" else curve.start
        out.append(point + shift if not 0 <= j < n else point[None, :])
    return out


def _shifted(curve: Curve, pair: RotorPair, k: int) -> Curve:
    """Return a rack piece moved by -k rack periods along the pitch line (the same rack, one lobe on).

    A corner's point path stays a point path (its mate is cut from it in closed form,
    :mod:`rotorcad.rotor_cut`): the same corner of the lobe k pitches back, observed k male pitches
    later, which is the path moved by -k periods. Any other piece is mapped.
    """
    if k == 0:
        return curve
    if type(curve) is PointPath:
        turn = k * 2.0 * np.pi / pair.male_teeth  # male rotation over k rack periods
        carried = curve.carrier.to_fixed(np.array([curve.carried], dtype=float), -turn)[0]
        return PointPath(
            (float(carried[0]), float(carried[1])), curve.carrier, curve.observer, curve.s0 + turn, curve.s1 + turn, curve.offset
        )
    return Mapped(curve, ((1.0, 0.0), (0.0, 1.0)), (0.0, -k * pair.rack_period))


def _in_design_period(rack: list[RackPiece], pair: RotorPair) -> list[RackPiece]:
    """Return the rack chain with every piece within half a rack period of the male tip's middle, in travel order.

    The design's chain holds the male tip's middle at the pitch line's origin (y = 0, the male tip on
    O1O2 at t = 0, the zero of the angle convention :meth:`rotorcad.meshing.MeshingAnalysis.rinder_angle`);
    a chain derived from a female's points ran its last pieces one period on (the driving flank's
    contacts at -72 deg of male turn on the 5/6 pairs for the design's 0 to -20), and every angle read
    off them (sliding, slip, the contact's place) one male pitch away. A piece whose middle lies
    beyond half a period is moved by whole periods (:func:`_shifted`); the moved pieces end or start
    the chain, which stays continuous.
    """
    period = pair.rack_period
    ks = []
    for piece in rack:  # the median of its rack points' places along the pitch line (a piece may hold gaps)
        y = piece.curve.evaluate(np.linspace(piece.curve.s0, piece.curve.s1, 9))[0][:, 1]
        ks.append(round(float(np.nanmedian(y)) / period) if np.isfinite(y).any() else 0)
    moved = [RackPiece(_shifted(p.curve, pair, k), p.male_name, p.female_name, p.kind) for p, k in zip(rack, ks, strict=True)]
    order = sorted(range(len(rack)), key=lambda i: -ks[i])  # stable: the pieces moved back go first
    return [moved[i] for i in order]


def _at_turns(rack: list[RackPiece], period: float, depth: int = 4) -> list[RackPiece]:
    """Return the chain with each flank piece that holds two lobe parts split where its rack turns.

    A lobe fitted as one closed spline (the N rack's female from 300 exact points a lobe: no sharp
    corner) gives one rack piece over the whole period, from the male tip's middle to the next,
    falling (sealing flank) and then rising (driving flank): named by its ends it read "tip land",
    and no part of it could be placed in the design's period (:func:`_in_design_period`). A piece
    that runs more than half the rack ``period`` (mm) along the pitch line is split at the interior
    extreme of its rack's height (the male root's or tip's middle, where Rinder sec. 1.2's driving and
    sealing flanks meet) when both parts rise or fall by more than 1 % of their chords (neither a
    land); the parts are split so again, ``depth`` times at most. The geometry is unchanged (trims of
    one curve). A shorter piece is left whole: it lies within one period, and its meshline is judged
    as one piece (the symmetric SRM's male from scattered points, its driving flank run on over the
    female tip's lost path, read -9.5 % of blow-hole with that piece split at the male tip).
    """
    out = []
    for piece in rack:
        if piece.kind is not PieceRole.CURVE or depth <= 0:
            out.append(piece)
            continue
        curve = piece.curve
        s = np.linspace(curve.s0, curve.s1, 201)
        pts = curve.evaluate(s)[0]
        x = pts[:, 0]
        if not np.isfinite(pts).all() or np.ptp(pts[:, 1]) <= 0.5 * period:
            out.append(piece)
            continue
        split = None
        for k in (int(np.argmax(x)), int(np.argmin(x))):
            if not 4 <= k <= len(s) - 5:
                continue  # an extreme at an end: no turn inside
            ends = curve.evaluate(np.array([curve.s0, s[k], curve.s1]))[0]
            sides = (ends[[0, 1]], ends[[1, 2]])
            if all(abs(e[1, 0] - e[0, 0]) > 1e-2 * np.hypot(*(e[1] - e[0])) for e in sides):
                split = s[k]
                break
        if split is None:
            out.append(piece)
            continue
        halves = [
            RackPiece(curve.trimmed(a, b), piece.male_name, piece.female_name, piece.kind)
            for a, b in ((curve.s0, split), (split, curve.s1))
        ]
        out.extend(_at_turns(halves, period, depth - 1))
    return out


def _arc_names(x: np.ndarray, chord: float) -> tuple[str, str] | None:
    """Return the male's and the female's names of a flank piece that runs over a whole lobe part, else None.

    Such a piece bulges between its ends, beyond both by more than 1 % of its ``chord`` (mm; ``x``, (n,) mm, its rack
    points' heights along the travel), as the symmetric SRM's rack semicircle does (its ends on the female tip paths
    near the pitch line, 14 mm high in the middle); named by its ends it read "root land" (ends level) or "driving
    flank" (one tip path read shorter, 600 exact points a lobe). Towards the male's tip it is the male's "lobe arc"
    and the female's "flute arc", as the design names them (:mod:`rotorcad.families.srm_symmetric`); towards its
    root, the other way round.
    """
    bulge = 1e-2 * chord
    if x.max() > max(x[0], x[-1]) + bulge:
        return "lobe arc", "flute arc"
    if x.min() < min(x[0], x[-1]) - bulge:
        return "flute arc", "lobe arc"
    return None


def _role_names(rack: list[RackPiece], pair: RotorPair, rotor: Side) -> list[RackPiece]:
    """Return the pieces named by their lobe part (:class:`rotorcad.roles.Flank`), as the design's are.

    The part is read off the rack (:func:`rotorcad.rack_roles.piece_role`) as
    :func:`rotorcad.meshing.meshline.flank_roles` reads it per point (Rinder sec. 1.2): rising towards the male
    tip along the travel, the driving flank; falling, the sealing flank; flat (to 1 % of its chord: fitted points
    leave a land micrometres off flat), the tip land in the male's addendum's outer half, else the root land; a
    flank piece that bulges between its ends runs over a lobe part (the symmetric SRM's "lobe arc",
    :func:`_arc_names`). A corner path is
    named by its corner (:func:`rotorcad.roles.tip_corner_name`: "sealing male tip corner"), a fan's path by the
    rotor whose corner it is; a corner path across O1O2 (its ends a quarter of its chord or more either side)
    takes the role of where it crosses, above the pitch point C the tip, below it the root, and is named "male
    tip corner (both flanks)".
    """
    out = []
    for piece in rack:
        pts = piece.curve.evaluate(np.linspace(piece.curve.s0, piece.curve.s1, 9))[0]
        pts = pts[np.isfinite(pts).all(axis=1)]  # a piece may hold gaps (no rack point)
        pts = pts if len(pts) else np.zeros((2, 2))
        role = piece_role(pts, piece.kind is not PieceRole.CURVE, pair.male_pitch_radius, pair.male_addendum)
        arc = _arc_names(pts[:, 0], float(np.hypot(*(pts[-1] - pts[0])))) if piece.kind is PieceRole.CURVE else None
        if piece.kind is not PieceRole.CURVE:
            name = tip_corner_name(role, Side.MALE if piece.kind is PieceRole.MALE_CORNER_PATH else Side.FEMALE)
            out.append(RackPiece(piece.curve, name, name, piece.kind))
        elif arc is not None:
            out.append(RackPiece(piece.curve, *arc, piece.kind))
        else:
            name = f"{role} flank" if role in (Flank.DRIVING, Flank.SEALING) else f"{role} land"
            out.append(RackPiece(piece.curve, name, name, piece.kind))
    return out


def pair_from_rotor_points(
    pair: RotorPair, points: np.ndarray | list[Curve], rotor: Side | str, smoothing: float | None = None, label: str | None = None
) -> ScrewRotors:
    """Generate a pair from points (or curves) of the male or the female rotor.

    The lobe is fitted piecewise between its sharp corners (:func:`lobe_pieces`); each piece and
    each corner's fan of normals gives its part of the rack by inverse generation (Wu & Chi sec. 2,
    eqs. 4-8). A corner's fan is the path of that corner ("male point" / "female point"), and so is
    every part of the rack along which the mate's generated point stands still (the mate's tip
    corner, whose point-generated flank this rotor carries): the mate receives such parts as its
    corner, exactly as in the profile families.

    Parameters
    ----------
    pair : RotorPair
        Dimensions of the pair.
    points : (n, 2) float array, mm, or list of Curve
        One lobe or the whole outline in the rotor's own frame (as for :func:`lobe_pieces`).
    rotor : {"male", "female"}
        Which rotor the points are.
    smoothing : float, mm², optional
        scipy's spline smoothing; None estimates it from the scatter.
    label : str, optional
        How the points are named in errors.

    Returns
    -------
    ScrewRotors
        The pair generated from the derived rack (family ``"male-points"`` or
        ``"female-points"``), with the share of the lobe that has no rack point in ``rack_loss``.

    Raises
    ------
    DesignError
        Points that do not make a lobe, or more than 2 % of the lobe without a rack point (its
        normal misses the pitch circle).
    """
    rotor = Side(rotor)  # "male" / "female" from a script reads as the rotor
    mesh = pair.mesh
    depth = (-pair.male_dedendum - 1e-6, pair.male_addendum + 1e-6)  # the rack lies between these
    side = Side(rotor)
    teeth = side.pick(pair.male_teeth, pair.female_teeth)
    outline = read_outline(points, teeth, label or f"{side.value} points")  # the one reading of the points
    pieces = lobe_pieces(pair, outline, rotor, smoothing)
    tip_pieces = pieces  # in the rotor's own frame
    # the accuracy bounds the largest deviation over the lobe's points, not one point's (2 sigma)
    per_lobe = (len(outline.whole) if outline.whole is not None else 0) / max(teeth, 1)
    point_acc = max(outline.accuracy, fit_residual(pair, outline, pieces, rotor))  # one point's: 2 sigma
    acc = max(point_acc, scatter_bound(outline.sigma, per_lobe))
    rotor = side.value
    if side is Side.MALE:
        body, mate_body, centre, teeth = mesh.male, mesh.female, np.zeros(2), pair.male_teeth
    else:
        shift = (pair.center_distance, 0.0)
        pieces = [(name, Mapped(curve, ((1.0, 0.0), (0.0, 1.0)), shift)) for name, curve in pieces]
        body, mate_body, centre, teeth = mesh.female, mesh.male, np.array(shift), pair.female_teeth
    own, other = PieceRole.corner_path_of(side), PieceRole.corner_path_of(side.other)
    mate_centre = np.array([pair.center_distance, 0.0]) if side is Side.MALE else np.zeros(2)  # the mate's frame
    mate_tip = (mate_centre, side.pick(pair.female_tip_radius, pair.male_tip_radius), 1e-3 * pair.center_distance)
    # the resolution of the defect tests (rotorcad.meshing.resolution) at the profile's accuracy
    shortest = max(5e-3 * pair.center_distance, float(np.sqrt(8.0 * pair.center_distance * acc)))
    same = EXACT_CORNER_WANDER * acc if outline.sigma <= 0 else 0.0  # of exact points: one corner's path
    # a flank's tangent through points each within point_acc is known to point_acc over one point spacing
    spacing = float(np.median(np.hypot(*np.diff(outline.whole, axis=0).T))) if outline.whole is not None else 0.0
    point_turn = point_acc / spacing if spacing > 0 else 0.0
    spread = (
        tangent_spread(outline, teeth, label or f"{side.value} points")
        if outline.sigma <= 0 and outline.whole is not None
        else None
    )
    parts: list[list[RackPiece]] = []
    lost, total = 0, 0
    lost_at: list[np.ndarray] = []
    gap = MEASURED_JOIN_GAP if outline.sigma > 0 else 2e-3  # scattered points' fits leave a corner's ends apart
    fans = with_corner_fans(pieces, centre, 2 * np.pi / teeth, MEASURED_MIN_TURN, gap)
    racks = []
    for _name, curve in fans:
        gen = Generated(curve, body, mesh.rack, limits=depth)
        rack_curve = gen.reversed() if side is Side.MALE else gen  # travelled in +y (the rack's +x)
        s = np.linspace(rack_curve.s0, rack_curve.s1, 400)
        ok = np.isfinite(rack_curve.evaluate(s)[0]).all(axis=1)
        lost, total = lost + int((~ok).sum()), total + len(ok)
        if not ok.all():  # where, in the rotor's own frame (the parent's parameter is the rack's)
            lost_at.append(curve.evaluate(s[~ok])[0] - centre)
        racks.append(rack_curve)
    for k, (_name, curve) in enumerate(fans):
        rack_curve = racks[k]
        if curve.is_corner():  # its path as the corner's own point path (the mate cut in closed form)
            targets = _joints(racks, k, side, pair.rack_period)
            path = corner_point_path(curve, body, mesh.rack, targets, gap)
            if path is None and np.hypot(*(targets[0][:, None, :] - targets[1][None, :, :]).T).min() <= gap:
                # the racks beside the corner meet: it turns no rack point (a corner on the pitch circle, as
                # the narrow-tip female's tip drawn exactly), and its fan's own rack curve jumps to the far root
                continue
            piece = rack_curve if path is None else path
            parts.append([RackPiece(piece, f"{rotor} tip corner", f"{rotor} tip corner", kind=own)])
            continue
        mate = Generated(rack_curve, mesh.rack, mate_body)
        runs = _mate_corner_runs(
            rack_curve,
            mate,
            tolerance=1e-4,
            scattered=outline.sigma > 0,
            tip=mate_tip,
            shortest=shortest,
            same_corner=same,
            accuracy=acc,
            spacing=spacing,
        )
        # of exact points, the mate's tip corner path as its exact trochoid where the part follows one
        # (rack_pieces.tip_corner_path); of scattered points (2 um) the trochoid held within 10 accuracies moved
        # the symmetric SRM's blow-hole by -19 % (test_verdict_invariance), so their path stays as generated
        fitted = outline.sigma <= 0
        exact = [
            tip_corner_path(pair, side.other, rack_curve, a, b, PATH_FIT * acc) if c and fitted else None for a, b, c in runs
        ]
        parts.append(
            [
                RackPiece(rack_curve.trimmed(a, b) if e is None else e, "flank", "flank", kind=other if c else PieceRole.CURVE)
                for (a, b, c), e in zip(runs, exact, strict=True)
            ]
        )
    # the male's counter-clockwise pieces follow the rack's travel, the female's run against it
    rack = [p for group in (parts if side is Side.MALE else reversed(parts)) for p in group]
    # one mate tip corner's path that the fit's pieces leave apart is one path (Krigar's male tip across O1O2)
    joined = joined_mate_paths(
        _in_design_period(_at_turns(rack, pair.rack_period), pair),
        mate_body,
        mesh.rack,
        own,
        same if outline.sigma <= 0 else mate_tip[2],
        gap,
    )
    rack = _role_names(joined, pair, side)
    lost_share = 100.0 * lost / max(total, 1)
    if lost_share > 2.0:  # a few points at sharp corners may miss their pitch circle; more is not a rotor
        raise _lost_rack_refusal(
            label or f"{rotor} points",
            outline.whole,
            teeth,
            np.vstack(lost_at) if lost_at else np.zeros((0, 2)),
            lost_share,
        )
    # scattered points' tangents to point_turn; at a male tip corner, from a parametric bootstrap of its
    # fitted spline (measured.tangent)
    turn = point_turn if outline.sigma > 0 else 0.0
    corner_turn = tip_tangent_accuracy(tip_pieces, outline.whole, outline.sigma) if side is Side.MALE else 0.0
    return ScrewRotors(
        pair,
        tuple(rack),
        f"{rotor}-points",
        rack_loss=lost_share,
        accuracy=acc,
        tangent_accuracy=turn,
        tip_corner_tangent_accuracy=min(corner_turn, turn) if corner_turn > 0.0 else None,
        point_accuracy=point_acc,
        tangent_spread=spread,
        point_spacing=spacing if spacing > 0 else None,
        given_points=outline.whole,
        point_scatter=float(outline.sigma),
    )


__all__ = ["CONFIDENCE", "max_factor", "pair_from_rotor_points", "scatter_bound"]

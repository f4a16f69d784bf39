"""How well a given profile places the blow-hole, and whether it resolves it (Rinder sec. 2.2.2).

Rinder (*Sonderverzahnungen für Schraubenverdichterrotoren*, sec. 2.2.2) bounds the blow-hole by the
contact line's end next to the housing cusp, the apex E (:attr:`MeshingAnalysis.meshline_end`). Of a
design it is exact. Of a profile given by points or a drawing the apex is placed no better than the
input's accuracy lets the law of gearing place it: :func:`blow_hole_uncertainty` states by how much the
area may be off (mm²), :func:`blow_hole_resolved` whether that makes the area a verdict.
"""

from __future__ import annotations

import itertools
from typing import TYPE_CHECKING

import numpy as np

from rotorcad.geometry import rotate
from rotorcad.meshing.apex import circle_bounds, circle_meshline_apex
from rotorcad.meshing.defects import MESHLINE_GAIN, resolution
from rotorcad.meshing.generating_line import GeneratingLine, line_apex, line_meshline_cut
from rotorcad.meshing.line_points import given_of
from rotorcad.roles import PieceRole

if TYPE_CHECKING:
    from rotorcad.meshing.analysis import MeshingAnalysis

APEX_POINTS = 4
"""How many of exact points, nearest the blow-hole apex's radius about their rotor's centre, set its
tangent's accuracy (:func:`blow_hole_uncertainty`): near a tip the radius changes slowly, and these are
the two points either side of the apex's radius on each flank."""

BLOW_HOLE_RESOLUTION = 1e-3
"""Share of the female flute's area below which a blow-hole's uncertainty resolves it whatever its area
(:func:`blow_hole_resolved`): Rinder ranks the blow-holes of his families, closed (Krigar, Lysholm's
sealing flank) below the smallest open ones (the samples' N rack, 0.29 % of its female flute;
narrow-tip 0.48 %), so an uncertainty of 0.1 % tells a closed meshline from them."""


RESOLVED_SHARE = 0.5
"""Largest uncertainty, as a share of the area, at which a blow-hole is resolved (:func:`blow_hole_resolved`): the
area is then known to a factor of 3 at worst (Rinder ranks his families' blow-holes by factors of 2-50). Measured
over 788 reads (9 samples, both rotors, 80/150/300 points a lobe, exact and with 1-2 um of scatter, each at
several sampling phases, seeds and datum angles): 319 resolved, every one within its uncertainty (the largest
error 0.95 of it); at the share 1 (U below the area, the rule before) 438 resolved, also all within, on those
reads alone. tests/test_blow_hole_points.py checks the coverage."""


def blow_hole_uncertainty(analysis: MeshingAnalysis) -> float:
    """Return how far the blow-hole area may lie from the true profile's, from the input's accuracy (mm²).

    The largest of what places the apex E (:attr:`MeshingAnalysis.meshline_end`) and what the input leaves
    open there, each the change of the area (:meth:`MeshingAnalysis.blow_hole_at`) with the apex moved:

    * where a male tip rounding's circle and the flank's generating circle place it and hold as the points'
      model (:func:`rounding_uncertainty`), their own bound alone: the apex then depends on the two circles,
      not on the fitted profile's tangent, its other estimates or where the hand-over falls between points;
    * where a straight line of the male, the female or the rack generates the flank beside the apex and its
      closed-form meshline places it (:func:`placing_line`), that line's own bound alone
      (:func:`line_uncertainty`): the apex then depends on the line, not on the flank's end tangent, the
      other estimates of it or where the hand-over falls between two points;
    * else the estimator's own bound: where the apex comes from a male arc's closed-form meshline
      (:attr:`MeshingAnalysis.apex_arc`), the arc's (:func:`arc_uncertainty`); else the tangent's
      (:func:`tangent_uncertainty`): E is where the normal of a male point passes through the pitch point
      C (Rinder sec. 2.1, the law of gearing), and a normal turned by the tangent's accuracy moves it;
    * the spread of the apex's other places (:func:`candidates_spread`), each from another part of the fit;
    * the points' spacing (:func:`spacing_uncertainty`): the point that hands over is placed no better than
      half a spacing along the profile.

    Of a drawing's exact curves, the meshline's resolution at the drawing's accuracy
    (:func:`drawing_uncertainty`) and the candidates' spread. 0 for a design.

    Parameters
    ----------
    analysis : MeshingAnalysis
        The pair's meshing analysis.

    Returns
    -------
    float, mm²
    """
    rotors = analysis.rotors
    delta = float(getattr(rotors, "tangent_accuracy", 0.0))
    spread = getattr(rotors, "tangent_spread", None)
    if delta <= 0.0 and spread is None:  # a design (0), or a drawing's exact curves
        return max(drawing_uncertainty(analysis), candidates_spread(analysis)) if analysis.is_given else 0.0
    rounding = rounding_uncertainty(analysis)
    if np.isfinite(rounding):
        return rounding
    line = line_uncertainty(analysis)
    if np.isfinite(line):
        return line
    arc_bound = arc_uncertainty(analysis) if delta > 0.0 else np.inf
    # the arc's bound where the arc placed the apex: the tangent's bound is of the hand-over's own estimate, and
    # stated for an arc's apex it missed the error (the asymmetric SRM's female at 150 a lobe with 1 um: +77 %,
    # +-2.2 mm² from the tangent; the symmetric SRM's female: -17 %, +-7.7 for +-28.8 from the arc)
    bound = arc_bound if np.isfinite(arc_bound) else tangent_uncertainty(analysis, delta, spread)
    return max(bound, candidates_spread(analysis), spacing_uncertainty(analysis))


def rounding_uncertainty(analysis: MeshingAnalysis) -> float:
    """Return the blow-hole's uncertainty (mm²) where a tip rounding's two circles place the apex and hold, else inf.

    :attr:`MeshingAnalysis.apex_rounding_uncertainty` (the two fits' worst-case response to every point within
    the accuracy) where :attr:`MeshingAnalysis.apex_rounding_check` finds the model holds. Before, the points'
    spacing along the rounding (:func:`spacing_uncertainty`, 1.39-1.71 mm² for the N rack male's CSV with 1 um
    of scatter, and 2-88 mm² at 300-600 exact points a lobe, by where the points fell) was stated for errors
    within 0.011 mm²; the model's bound there is 0.04-0.10 mm². Where the check fails (the Lysholm male's flank
    is a female corner's envelope, the arc-flank male's tip rounding a rack circle's) that bound is not the
    model's error, and the other estimates stand (:func:`blow_hole_uncertainty`).

    Parameters
    ----------
    analysis : MeshingAnalysis
        The pair's meshing analysis.

    Returns
    -------
    float, mm² (inf: no rounding placed the apex, or its model does not hold)
    """
    if analysis.apex_rounding is None or analysis.apex_rounding_check is not None:
        return np.inf
    return float(analysis.apex_rounding_uncertainty)


def arc_uncertainty(analysis: MeshingAnalysis) -> float:
    """Return the blow-hole's uncertainty (mm²) where the apex comes from a male arc's closed-form meshline, else inf.

    The arc's centre and radius move by at most :func:`rotorcad.meshing.apex.circle_bounds` when its
    samples may each be :attr:`MeshingAnalysis.judged_accuracy` off; the uncertainty is the largest change
    of the area over the eight corners of that box, inf where a corner's meshline has no contact within
    reach of the apex (the arc does not place it).

    Parameters
    ----------
    analysis : MeshingAnalysis
        The pair's meshing analysis.

    Returns
    -------
    float, mm² (inf: no arc, or one that does not place the apex)
    """
    arc = analysis.apex_arc
    if arc is None:
        return np.inf
    centre, radius, window, near, reach, bores = arc
    bound = circle_bounds(window, centre, radius, analysis.judged_accuracy)
    c = np.array([analysis.rotors.pair.male_pitch_radius, 0.0])
    moved, seen = [], {}
    for sign in itertools.product((-1.0, 1.0), repeat=3):
        step = np.asarray(sign) * bound
        moved_centre, moved_radius = centre + step[:2], radius + step[2]
        key = (moved_centre.tobytes(), float(moved_radius).hex())  # a zero bound repeats a corner: searched once
        if key not in seen:
            apex = circle_meshline_apex(moved_centre, moved_radius, c, analysis.cusp, near, reach, bores, window)
            seen[key] = np.inf if apex is None else analysis.blow_hole_at(apex).area
        moved.append(seen[key])
    return float(max(abs(m - analysis.blow_hole_area) for m in moved))


LINE_COVERAGE = 3.0
"""Standard errors of the fitted line by which :func:`line_uncertainty` moves it (three: 99.7 % of a normal
error). Measured over the samples whose flank beside a tip corner is a line's envelope (narrow-tip, asymmetric
SRM, SRM-B, rack-involute; both rotors, 80/150/300 points a lobe, exact and with 1-2 um, seeds 0-3, 216 reads,
``python benchmarks/bench_line_apex.py``): 202 resolved (65 before, with the tangent's bound and the other
estimates' spread), none outside its uncertainty, the largest error 0.61 of it; the errors themselves unchanged."""


def placing_line(analysis: MeshingAnalysis) -> GeneratingLine | None:
    """Return the generating line whose closed-form meshline placed the blow-hole's apex, else None.

    :func:`rotorcad.meshing.generating_line.line_apex` at the meshline's sample nearest the housing cusp,
    as :meth:`MeshingAnalysis._tip_apex` calls it, where its apex is :attr:`MeshingAnalysis.meshline_end`
    (a male arc's apex may come first there). None for a design or a drawing's exact curves.

    Parameters
    ----------
    analysis : MeshingAnalysis
        The pair's meshing analysis.

    Returns
    -------
    GeneratingLine or None
    """
    cached = analysis.__dict__.get("_placing_line", False)
    if cached is not False:
        return cached
    line = None
    rotors = analysis.rotors
    if analysis.is_given and getattr(rotors, "point_spacing", None) and analysis.apex_arc is None:
        pair = rotors.pair
        tips = ((np.zeros(2), pair.male_tip_radius), (np.array([pair.center_distance, 0.0]), pair.female_tip_radius))
        pts = analysis.meshline
        k = int(np.argmin(np.hypot(*(pts - analysis.cusp).T)))
        found = line_apex(analysis.pieces, pts[k], tips, analysis.judged_accuracy, pair, given_of(rotors))
        if found is not None and np.hypot(*(found.apex - analysis.meshline_end)) <= 1e-9:
            line = found
    analysis.__dict__["_placing_line"] = line
    return line


def line_uncertainty(analysis: MeshingAnalysis) -> float:
    """Return the blow-hole's uncertainty (mm²) where a generating line places the apex, else inf.

    A line fitted to n points spread evenly over a length L with normal errors sigma is off in direction by
    sigma / L sqrt(12 / n) and, at a distance x from the points' centroid along it, in offset by
    sigma sqrt(1 / n + 12 x² / (n L²)) (least squares: the slope's variance sigma² / S_xx, S_xx = n L² / 12).
    The meshline of a turning body's line depends on its distance d from the body's centre alone, the rack
    line's on its direction alone (:func:`rotorcad.meshing.generating_line.line_meshline_cut`): d, at the foot
    of the perpendicular from the centre, or the direction is moved by :data:`LINE_COVERAGE` of its standard
    error, and the tip circle's radius by the profile's accuracy (the given corner lies on its tip circle no
    better); the uncertainty is the largest change of the area over those four cuts. n is the number of given
    points over the window (the contacts' path on the given rotor over its point spacing), sigma the accuracy
    of one point (:attr:`rotorcad.screw_rotors.ScrewRotors.point_accuracy`, twice its scatter: the fitted
    outline's error is smooth, no independent scatter a point) or the contacts' rms distance from the line if
    larger, L how far the contacts travel along the line in its body. It
    shrinks as the points come closer (n grows): the narrow-tip male with 1 um of scatter at 80 / 150 / 300
    points a lobe stated 0.50 / 0.84 / 1.59 mm² from the tangent and the other estimates' spread, for errors
    within 0.02 mm² (``python benchmarks/bench_line_apex.py``). Where the line was fitted again to scattered
    points themselves (:func:`rotorcad.meshing.line_points.refit_line`), the larger of these standard errors and
    that fit's own (sigma² (J^T J)^-1): its own alone, over every lobe's points, missed the error of lines whose
    points' model held at their ends but not between (the SRM-B female at 300 a lobe with 2 um, seed 2: +1.17 %
    stating 0.5 %). A given rotor's own line fitted with the curve beyond it
    (:func:`rotorcad.meshing.line_points.own_line`) states that model's errors alone, their spread over the
    junctions its points cannot tell apart included: the females of the narrow-tip, asymmetric SRM and SRM-B at
    80-300 a lobe with 1-2 um along the normals (72 reads) stated 0.8-8.5 % of the area for errors up to 0.42 of it
    (the contacts' floor had stated 3-135 %).

    Parameters
    ----------
    analysis : MeshingAnalysis
        The pair's meshing analysis.

    Returns
    -------
    float, mm² (inf: no line placed the apex)
    """
    line = placing_line(analysis)
    if line is None:
        return np.inf
    rotors = analysis.rotors
    pair = rotors.pair
    if rotors.family.startswith("female"):
        given = rotate(line.contacts - np.array([pair.center_distance, 0.0]), line.t * pair.male_teeth / pair.female_teeth)
    else:
        given = rotate(line.contacts, -line.t)
    count = max(float(np.hypot(*np.diff(given, axis=0).T).sum()) / float(rotors.point_spacing), 2.0)
    point = getattr(rotors, "point_accuracy", None)
    # one point's accuracy (2 sigma), not its scatter: the fitted outline's error is smooth along it and no independent
    # sigma a point (half of it left the SRM-B female's own straight flank at 150 a lobe with 2 um and at 300 with
    # 1 um 1.15 and 1.22 times its bound off, -8.7 and -6.4 %; the samples' other lines up to 0.67 of it)
    sigma = max(float(rotors.accuracy if point is None else point), line.rms)
    sxx = count * line.span**2 / 12.0
    turn_error = sigma / np.sqrt(sxx)
    distance_error = sigma * np.sqrt(1.0 / count + line.along**2 / sxx)
    own = line.errors is not None and line.frame == ("female" if rotors.family.startswith("female") else "male")
    if own:  # the rotor's own line fitted with the curve beyond it (line_points.own_line): that model's errors
        turn_error, distance_error = float(line.errors[0]), float(line.errors[1])
    elif line.errors is not None:  # fitted to the scattered points themselves: their fit's own standard errors, if larger
        turn_error, distance_error = max(turn_error, float(line.errors[0])), max(distance_error, float(line.errors[1]))
    c = np.array([pair.male_pitch_radius, 0.0])
    (o, r), accuracy = line.circle, analysis.judged_accuracy
    area, moved = analysis.blow_hole_area, []
    for side, grow in itertools.product((-1.0, 1.0), repeat=2):
        circle = (o, r + grow * accuracy)
        if line.centre is None:  # the rack's line: its direction
            turn = side * LINE_COVERAGE * turn_error
            normal = _turned(line.normal, turn)
            apex = line_meshline_cut(None, normal, None, c, circle, line.near)
        else:  # a turning body's line: its distance from the centre, at the foot of the perpendicular
            step = side * LINE_COVERAGE * distance_error
            apex = line_meshline_cut(line.distance + step, line.normal, line.centre, c, circle, line.near)
        moved.append(np.inf if apex is None else abs(analysis.blow_hole_at(apex).area - area))
    return float(max(moved))


def _turned(vector: np.ndarray, angle: float) -> np.ndarray:
    """Return a (2,) vector turned counter-clockwise by ``angle`` (rad)."""
    ca, sa = np.cos(angle), np.sin(angle)
    return np.array([ca * vector[0] - sa * vector[1], sa * vector[0] + ca * vector[1]])


def _turned_apex_change(analysis: MeshingAnalysis, turn: float) -> float:
    """Return the larger change of the blow-hole area (mm²) with the apex turned by ``turn`` (rad) either way about O1."""
    e = analysis.meshline_end
    r = float(np.hypot(*e))
    phi, area = float(np.arctan2(e[1], e[0])), analysis.blow_hole_area
    moved = [analysis.blow_hole_at(r * np.array([np.cos(phi + t), np.sin(phi + t)])).area for t in (turn, -turn)]
    return float(max(abs(m - area) for m in moved))


def drawing_uncertainty(analysis: MeshingAnalysis) -> float:
    """Return the blow-hole's uncertainty (mm²) of a profile drawn as exact curves (no points, no tangent bound).

    A drawing within e (:attr:`MeshingAnalysis.judged_accuracy`, its curves' deviation) of the outline places
    a point of the meshline no better than the resolution sqrt(8 a e)
    (:func:`rotorcad.meshing.defects.resolution`): where a flank meets a corner's point-generated part with a
    common tangent (a curvature step alone) the drawing cannot tell where within that length the hand-over
    lies. The apex moved by it either way along its circle about O1. The rack-involute female's export
    splines (0.85 um) read the blow-hole +0.28 % (22.800 mm² for 22.737) and stated +-0.000 before.

    Parameters
    ----------
    analysis : MeshingAnalysis
        The pair's meshing analysis.

    Returns
    -------
    float, mm²
    """
    r = float(np.hypot(*analysis.meshline_end))
    if r < 1e-9:
        return 0.0
    return _turned_apex_change(analysis, resolution(analysis.judged_accuracy, analysis.rotors.pair.center_distance) / r)


def candidates_spread(analysis: MeshingAnalysis) -> float:
    """Return the largest change of the blow-hole area (mm²) between the apex and its other places.

    The apex of a tip corner's hand-over is placed from several parts of the fit
    (:attr:`MeshingAnalysis.apex_candidates`: the joint of the corner's path and the flank, the flank's
    meshline extrapolated by a quadratic and by a cubic, the turn of both branches); where they part by
    more than the tangent's bound the points do not place the apex that well: the narrow-tip male at 80
    points a lobe with 1 um of scatter read +16..+22 % extrapolated over a window of 0.33 of its flank's
    meshline, stating +-0.32..0.43 mm²; its joint read 2.56-2.81 mm² (design 2.778).

    Parameters
    ----------
    analysis : MeshingAnalysis
        The pair's meshing analysis.

    Returns
    -------
    float, mm²
    """
    area = analysis.blow_hole_area
    return float(max((abs(analysis.blow_hole_at(c).area - area) for c in analysis.apex_candidates), default=0.0))


def tangent_uncertainty(analysis: MeshingAnalysis, delta: float, spread: tuple | None) -> float:
    """Return the blow-hole's uncertainty (mm²) from the tangent's accuracy ``delta`` (rad) (:func:`blow_hole_uncertainty`).

    Of the apex a hand-over or the sampled meshline gives (where a male arc gives it, the arc's bound holds
    instead, :func:`arc_uncertainty`; an arc that does not place the apex, as one of 38 mm radius fitted to a
    male generated from a female's points, narrow-tip, 1 um of scatter, whose corners' apexes fell 58 mm
    away, leaves the apex to this bound and the blow-hole unresolved). The apex moves at most
    by the meshline's resolution (:func:`rotorcad.meshing.defects.resolution` at
    :data:`rotorcad.meshing.defects.MESHLINE_GAIN` times the accuracy) along the tip circle: at
    beta' = 1 the linear step r delta / |beta' - 1| has no bound (+-677 mm² on 4.8, the asymmetric SRM
    from a female's points). It moves at least by the meshline's accuracy (:data:`MESHLINE_GAIN` times
    the profile's), to which the meshline places the apex whatever the tangent: exact points 1000 and
    10 000 a lobe (the rack-involute and the narrow-tip males) stated +-0.0012 and +-0.0006 mm² for
    errors of 0.0059 and 0.0011 mm² (0.03 % and 0.04 %).

    Parameters
    ----------
    analysis : MeshingAnalysis
        The pair's meshing analysis.
    delta : float, rad
        The profile's tangent accuracy.
    spread : tuple of two (n,) float arrays or None
        Of exact points, the radii (mm) about their rotor's centre and their fit's tangent turns (rad).

    Returns
    -------
    float, mm²
    """
    rotors = analysis.rotors
    pair = rotors.pair
    e = analysis.meshline_end
    r = float(np.hypot(*e))
    if spread is not None and len(spread[0]) >= APEX_POINTS:  # exact points: their fit's tangent at the apex's radius
        female = rotors.family.startswith("female")
        r_own = float(np.hypot(*(e - np.array([pair.center_distance if female else 0.0, 0.0]))))
        nearest = np.argpartition(np.abs(spread[0] - r_own), APEX_POINTS - 1)[:APEX_POINTS]
        beyond = spread[1][spread[0] >= r_own]  # up to the tip, whose fit hands the flank over at the apex
        delta = max(delta, float(spread[1][nearest].max()), float(beyond.max(initial=0.0)))
    if delta <= 0.0 or r < 1e-9:
        return 0.0
    corner = getattr(rotors, "tip_corner_tangent_accuracy", None)
    if corner is not None and r >= pair.male_tip_radius - 1e-3 * pair.center_distance:
        delta = float(corner)  # the apex on the male tip circle: where the tip corner's path hands over
    c = np.array([pair.male_pitch_radius, 0.0])
    v = c - e
    if np.hypot(*v) < 1e-6:
        return 0.0
    phi = float(np.arctan2(e[1], e[0]))
    dx = r * np.array([-np.sin(phi), np.cos(phi)])
    rate = float((v[0] * -dx[1] - v[1] * -dx[0]) / (v @ v))  # beta'
    reach = resolution(MESHLINE_GAIN * analysis.judged_accuracy, pair.center_distance)
    turn = min(delta / max(abs(rate - 1.0), 1e-9), reach / r)  # dphi, rad, at most the meshline's resolution
    # at least the meshline's accuracy along the tip circle: the apex is a meshline point, placed no better
    turn = max(turn, MESHLINE_GAIN * analysis.judged_accuracy / r)
    return _turned_apex_change(analysis, turn)


SPACING_SAMPLES = 16
"""How many meshline samples within reach of the apex :func:`spacing_uncertainty` moves the apex to (the
farthest from it, along the meshline): the blow-hole's area changes steadily along the meshline."""


def given_points_on_lobe(analysis: MeshingAnalysis) -> tuple[np.ndarray, float]:
    """Return the point of the given rotor that touches at every meshline sample, in its own frame, and its lobe pitch.

    The contact P at male rotation t is the male point R(-t) P; a female point, the female turning the other
    way by t z1 / z2 about O2, is R(t z1 / z2) (P - O2). Of a design, the male's.

    Parameters
    ----------
    analysis : MeshingAnalysis
        The pair's meshing analysis.

    Returns
    -------
    ((n, 2) float array, mm; float, rad)
        The points, row by row as :attr:`MeshingAnalysis.meshline`, and 2 pi over the rotor's lobe count.
    """
    pair = analysis.rotors.pair
    pts, t = analysis.meshline, analysis.contact_angles
    if analysis.rotors.family.startswith("female"):
        ratio = pair.male_teeth / pair.female_teeth
        return rotate(pts - np.array([pair.center_distance, 0.0]), t * ratio), 2.0 * np.pi / pair.female_teeth
    return rotate(pts, -t), 2.0 * np.pi / pair.male_teeth


def spacing_uncertainty(analysis: MeshingAnalysis, spacings: float = 1.0) -> float:
    """Return the blow-hole's uncertainty (mm²) from the spacing of the given points.

    The given profile's point that hands over at the apex (a tip corner, the end of a tip rounding, where a
    flank meets the part a mate's corner generates) is a corner or a curvature step, and the fit places it
    between points h apart (:attr:`rotorcad.screw_rotors.ScrewRotors.point_spacing`): it lies somewhere
    between the two points either side of it, up to h from where the fit took it, along the profile. The
    apex is then the contact of that point (the law of gearing: where its normal passes through C): a
    sample of a flank's meshline (a curve's contacts, no corner's path), reached along the meshline from
    the apex (from a corner path's nearer end where the apex lies on one), whose point of the given rotor
    lies within h of the apex's (turned by whole lobe pitches). The uncertainty is the largest change of
    the area with the apex moved to those samples (the :data:`SPACING_SAMPLES` farthest from it). Before,
    at 80 points a lobe (about 1.0-1.5 mm apart), exact points of the N rack male (its 0.67 mm tip
    rounding between two points) read 1.08-1.34 mm² for the design's 1.74 stating +-0.14-0.16 and
    resolved; now +-1.7-1.8, not resolved. A design's or a drawing's: 0.

    Parameters
    ----------
    analysis : MeshingAnalysis
        The pair's meshing analysis.
    spacings : float
        How many point spacings along the profile the point that hands over may lie from the fit's.

    Returns
    -------
    float, mm²
    """
    h = getattr(analysis.rotors, "point_spacing", None)
    pts = analysis.meshline
    if not h or len(pts) < 2:
        return 0.0
    sizes = np.array([len(p.points) for p in analysis.pieces])
    starts = np.cumsum(sizes) - sizes
    piece = np.repeat(np.arange(len(sizes)), sizes)
    free = np.array([p.kind is PieceRole.CURVE for p in analysis.pieces])[piece]  # a flank's contacts, no corner's path
    x, pitch = given_points_on_lobe(analysis)
    e = analysis.meshline_end
    i = int(np.argmin(np.hypot(*(pts - e).T)))  # the apex's sample
    turn = np.arctan2(x[:, 1], x[:, 0]) - np.arctan2(x[i, 1], x[i, 0])
    x = rotate(x, -pitch * np.round(turn / pitch))  # onto the apex point's lobe
    ok = free & (np.hypot(*(x - x[i]).T) <= spacings * h)
    n = len(pts)
    joined = np.hypot(*(np.roll(pts, -1, axis=0) - pts).T) <= h  # sample k to k + 1 (the meshline is closed)
    if free[i]:
        ways = [(i, 1), (i, -1)]
    else:  # on a corner's path: from its end at the hand-over (the nearer), away from it
        lo, hi = int(starts[piece[i]]), int(starts[piece[i]] + sizes[piece[i]] - 1)
        ways = [(lo, -1)] if i - lo < hi - i else [(hi, 1)]
    reach = []
    for start, way in ways:  # along the meshline while the point stays within reach and the meshline runs on
        order = (start + way * np.arange(1, n)) % n
        run = ok[order] & joined[(order - 1) % n if way > 0 else order]
        reach.extend(order[: int(np.argmin(run)) if not run.all() else n - 1])
    if not reach:
        return 0.0
    cand = pts[np.asarray(reach)]
    far = np.argsort(np.hypot(*(cand - e).T))[-SPACING_SAMPLES:]
    area = analysis.blow_hole_area
    return float(max(abs(analysis.blow_hole_at(p).area - area) for p in cand[far]))


def blow_hole_resolved(analysis: MeshingAnalysis) -> bool:
    """Tell whether the input resolves the blow-hole (always for a design).

    It does when the apex is placed (a male arc's apex only where the arc's bound holds,
    :func:`arc_uncertainty` finite) and :func:`blow_hole_uncertainty` is at most :data:`RESOLVED_SHARE` of the
    area, or below :data:`BLOW_HOLE_RESOLUTION` of the female flute's area (a closed meshline's).

    Where it is not, the area is no verdict: 300 exact points a lobe of the N rack male put 2-3 points on
    its 0.67 mm tip rounding, whose end is the apex, and read 1.98 and 0.44 mm² (design 1.74) by
    where the points fell, stating ±31 and ±25 mm² (:func:`blow_hole_uncertainty`). The rounding meets
    the sealing flank with a common tangent, only the curvature steps there, and that point, the
    apex's male point, moves the apex 46 times as far along the meshline (30.8 mm of meshline for
    0.67 mm of rounding): points that do not resolve the curvature step do not place it. Points
    closer together there do (the dense forms, within 1 %), and so do the rounding's and the flank's circles
    fitted to the points where they hold as the points' model (:func:`rounding_uncertainty`: those two
    forms now +0.9 % and -0.0 %, ±0.05 and ±0.04 mm², resolved).

    Parameters
    ----------
    analysis : MeshingAnalysis
        The pair's meshing analysis.

    Returns
    -------
    bool
    """
    if not analysis.is_given:
        return True
    placed = analysis.apex_arc is None or float(getattr(analysis.rotors, "tangent_accuracy", 0.0)) <= 0.0
    placed = placed or bool(np.isfinite(arc_uncertainty(analysis)))
    area, spread = analysis.blow_hole_area, analysis.blow_hole_uncertainty
    return placed and spread <= max(RESOLVED_SHARE * area, BLOW_HOLE_RESOLUTION * analysis.female_flute_area)

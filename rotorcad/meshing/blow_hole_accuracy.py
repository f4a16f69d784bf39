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

from rotorcad.meshing.apex import circle_bounds, circle_meshline_apex
from rotorcad.meshing.defects import MESHLINE_GAIN, resolution

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


def blow_hole_uncertainty(analysis: MeshingAnalysis) -> float:
    """Return how far the blow-hole area may lie from the true profile's, from the input's accuracy (mm²).

    The apex E (:attr:`MeshingAnalysis.meshline_end`) is where the normal of a male point at radius
    r = |E| passes through the pitch point C (Rinder sec. 2.1, the law of gearing). With the male turned
    by phi the point is X = r (cos phi, sin phi) and its normal, fixed in the rotor, turns with it: the
    contact holds where beta(phi) - phi = psi, beta the direction of C - X. A normal turned by
    delta moves the contact along that circle by ds = r delta / |beta' - 1|, with
    beta' = ((C - X) x (-X')) / |C - X|², X' = dX/dphi. The profile's tangents are known to
    :attr:`rotorcad.screw_rotors.ScrewRotors.tangent_accuracy` (its accuracy over one point
    spacing; at a given male's tip corner, when the apex lies on the male tip circle,
    :attr:`rotorcad.screw_rotors.ScrewRotors.tip_corner_tangent_accuracy` from the fitted spline);
    of exact points, the largest turn of their fit's tangent
    (:attr:`rotorcad.screw_rotors.ScrewRotors.tangent_spread`) at the :data:`APEX_POINTS` points
    nearest the apex's radius and above it, up to the tip, whose fit sets where the flank hands over
    (the N rack male's tip rounding with 2-3 of 300 points a lobe on it: the apex 78 µm off in
    radius). The uncertainty is the larger change of the blow-hole area
    (:meth:`MeshingAnalysis.blow_hole_at`) with the apex moved by ds either way. 0 for a design.

    Where the apex comes from a male arc's closed-form meshline (:attr:`MeshingAnalysis.apex_arc`) no
    tangent enters: the arc's centre and radius move by at most
    :func:`rotorcad.meshing.apex.circle_bounds` when its samples may each be
    :attr:`MeshingAnalysis.judged_accuracy` off, and the uncertainty is the largest change of the area
    over the eight corners of that box.

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
    arc = analysis.apex_arc
    arc_bound = np.inf
    if arc is not None and delta > 0.0:
        centre, radius, window, near, reach, bores = arc
        bound = circle_bounds(window, centre, radius, analysis.judged_accuracy)
        c = np.array([rotors.pair.male_pitch_radius, 0.0])
        moved = []
        for sign in itertools.product((-1.0, 1.0), repeat=3):
            step = np.asarray(sign) * bound
            apex = circle_meshline_apex(centre + step[:2], radius + step[2], c, analysis.cusp, near, reach, bores, window)
            moved.append(np.inf if apex is None else analysis.blow_hole_at(apex).area)
        arc_bound = float(max(abs(m - analysis.blow_hole_area) for m in moved))
    bound = min(arc_bound, tangent_uncertainty(analysis, delta, spread))
    return max(bound, candidates_spread(analysis))


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

    Both it and the arc's bound hold (each from the input's accuracy), so the smaller is stated: an arc
    of 38 mm radius fitted to a male generated from a female's points (narrow-tip, 1 um of scatter) is
    poorly fixed, and its corners' apexes fell 58 mm away (+-1920 mm² on 4.1). The apex moves at most
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


def blow_hole_resolved(analysis: MeshingAnalysis) -> bool:
    """Tell whether the input resolves the blow-hole (always for a design).

    It does when :func:`blow_hole_uncertainty` is below the area or below :data:`BLOW_HOLE_RESOLUTION` of
    the female flute's area.

    Where it is not, the area is no verdict: 300 exact points a lobe of the N rack male put 2-3 points on
    its 0.67 mm tip rounding, whose end is the apex, and read 1.98 and 0.44 mm² (design 1.74) by
    where the points fell, stating ±31 and ±25 mm² (:func:`blow_hole_uncertainty`). The rounding meets
    the sealing flank with a common tangent, only the curvature steps there, and that point, the
    apex's male point, moves the apex 46 times as far along the meshline (30.8 mm of meshline for
    0.67 mm of rounding): points that do not resolve the curvature step do not place it. Points
    closer together there do (the dense forms, within 1 %).

    Parameters
    ----------
    analysis : MeshingAnalysis
        The pair's meshing analysis.

    Returns
    -------
    bool
    """
    area, spread = analysis.blow_hole_area, analysis.blow_hole_uncertainty
    return spread <= max(area, BLOW_HOLE_RESOLUTION * analysis.female_flute_area)

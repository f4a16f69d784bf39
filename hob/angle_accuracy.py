"""How well a rotor's points give the smallest flank angle of its hob (the normal rack's).

A rack point and its rotor point share their normal at contact, where that normal passes the
pitch point C (Wu & Chi, *Meshing clearance evaluation*, sec. 2, eq. 4). Turn the rotor's normal by
d theta about its point: the normal meets the pitch circle elsewhere, by d theta |P - C| / sin(gamma)
along it (gamma the angle between the normal and the pitch line), so the rotor touches at another
roll and the rack tangent turns by

    d psi = d theta (1 + y / (r_w t_x^2)),

y the rack point's height (away from the rotor's centre) and t_x its unit tangent's component
along the pitch line (|P - C| = |y / t_x|, sin(gamma) = |t_x|): the generation factor of
:func:`rotorcad.inverse_rack.generation_factor` without its curvature term. The normal section
(Wu & Chi eq. 7, tan(alpha_n) = tan(alpha_t) cos(beta)) scales it by
cos(beta) / (cos^2(alpha_t) + cos^2(beta) sin^2(alpha_t)).

The rotor's tangent is known to the profile's tangent accuracy: of scattered points, one point's
accuracy over one spacing (:attr:`rotorcad.screw_rotors.ScrewRotors.tangent_accuracy`); of exact
points, the spread of two interpolants' tangents at the points
(:func:`rotorcad.measured.fit.tangent_spread`), which is largest where the points do not resolve the
outline (a land meeting a flank). The smallest angle read from the points may then lie anywhere
within the smallest of the angles less their errors and the smallest of the angles plus their
errors.

The read smallest angle is the minimum of many scattered angles: min(a_i + e_i) lies between
min(a_i) - max |e_i| and min(a_i) + |e_j| (j where a_i is least), so it reads low by up to the
largest of the lobe's errors, and high by one point's at most. Along a straight rack flank (the
rack-involute's) the angle is the same over hundreds of points and the minimum picks the most
negative error: 300 points a lobe with 1 um of scatter read the rack-involute's 18.127 deg 0.04-0.59
deg low over seeds 71-78 of both rotors, never high, outside one point's bound (0.29-0.46 deg) on 8
of the 12 of seeds 71-76. So the truth lies above the read minimum by at most the error at the point that reads it (the point
the minimum chose for its error) counted at the lobe's largest: that point's tangent accuracy times
the ratio of the profile's accuracy (the largest of a lobe's N errors with 95 % confidence, k_N sigma,
:func:`rotorcad.measured.pairs.scatter_bound`) to one point's (2 sigma), k_N / 2: 1.9 at 300 points a
lobe, 1 for exact points; below it by at most one point's error at the true minimum's point (a fixed
point, whatever the scatter), within the smallest of the angles less their errors. The accuracy
stated is the larger of the two: 0.54-0.68 deg on those sixteen, all covered.

Where :func:`hob.verdict.judge` reads a straight part of a rack flank as its fitted line
(:mod:`hob.straight_flank`), that reading is one line's, not a minimum of scattered angles: its points take the
line's angle and the line's accuracy (:func:`hob.straight_flank.line_accuracy`: twice its standard error from the
scatter, the given points along the stretch and its length, plus the trend measured along it) in both bounds. The
rack-involute (300 points a lobe): stated 0.009-0.040 deg at 1 um (seeds 71-78, errors within 0.0095), 0.017-0.090
at 2 um (seeds 11-16, errors within 0.0105), for 0.54-2.74 by the pointwise bound. Other points keep the pointwise
bounds, so a lower pointwise angle elsewhere still counts.

The samples whose smallest angle is 0 deg have it where the male's flank leaves its root land radially on the pitch
circle, turning 6 deg within 0.2 mm of radius (under one point spacing at 300 a lobe). On some seeds the fit starts the
flank about 6 deg off radial there, and the rack reads a dip 1-2.3 deg high 0.3-0.4 mm above the pitch line (25 of
144 male rows of seeds 17-40 with 2 um). The steep points' 3 deg bound covers them, narrowly (1.903 for 1.926 stated);
it does not model that end effect.
"""

from __future__ import annotations

import numpy as np

from rotorcad.inverse_rack import DerivedRack
from rotorcad.roles import PieceRole, Side

STEEP = 0.05
"""|t_x| below which the rack runs within 3 deg of perpendicular to the pitch line (as
:func:`rotorcad.inverse_rack.generation_factor`): the gain is taken there."""
RADIUS_WINDOW = 0.3
"""mm: a rack point takes the largest tangent spread of the given points within this radius of its rotor point."""


def _spread_at(radii: np.ndarray, spread: np.ndarray, at: np.ndarray) -> np.ndarray:
    """Return the largest ``spread`` (rad) of the points whose radius lies within :data:`RADIUS_WINDOW` of each of ``at``."""
    if not len(radii):
        return np.zeros(len(at))
    order = np.argsort(radii)
    r, s = radii[order], spread[order]
    lo = np.searchsorted(r, at - RADIUS_WINDOW)
    hi = np.searchsorted(r, at + RADIUS_WINDOW, side="right")
    # the largest over each window from a sparse table of maxima (no loop over the points)
    levels = [s]
    while 2 ** len(levels) <= len(s):
        prev, step = levels[-1], 2 ** (len(levels) - 1)
        levels.append(np.maximum(prev[:-step], prev[step:]))
    out = np.zeros(len(at))
    has = hi > lo
    width = np.where(has, hi - lo, 1)
    k = np.floor(np.log2(width)).astype(int)
    for level in np.unique(k[has]):
        pick = has & (k == level)
        table = levels[level]
        out[pick] = np.maximum(table[lo[pick]], table[hi[pick] - 2**level])
    return out


def flank_angle_errors(rack: DerivedRack, tangent_accuracy: np.ndarray | float) -> tuple[np.ndarray, np.ndarray]:
    """Return each rack point's normal flank angle and how far the profile's tangent accuracy may move it (deg).

    Parameters
    ----------
    rack : DerivedRack
        The rack of the rotor given by points, in its own frame, with its ``profile``.
    tangent_accuracy : float or (n,) float array, rad
        The profile's tangent accuracy at each rack point's rotor point.

    Returns
    -------
    angle : (n,) float array, deg
        The normal flank angle (from the normal to the pitch line) of each cutting flank point; inf elsewhere.
    error : (n,) float array, deg
        Its bound from the tangent accuracy (module docstring).
    """
    cb = np.cos(rack.helix_angle)
    t = rack.tangents
    normal = t * np.array([cb, 1.0])
    normal /= np.linalg.norm(normal, axis=1, keepdims=True)
    cutting = np.array([role is not PieceRole.CORNER_FAN for role in rack.roles], dtype=bool)[rack.piece_index]
    flank = cutting & (np.abs(normal[:, 1]) > 1e-9)
    angle = np.where(flank, np.degrees(np.arctan2(np.abs(normal[:, 0]), np.abs(normal[:, 1]))), np.inf)
    y = rack.points[:, 1] * (-1.0 if rack.contract_frame and rack.side is Side.FEMALE else 1.0)  # own frame
    # within 3 deg of perpendicular to the pitch line the normal runs along it and the contact is far off
    # (a cusp on the pitch line makes the rack perpendicular there whatever the tangent): there the angle is
    # stated to those 3 deg
    steep = np.abs(t[:, 0]) < STEEP
    tx = np.where(steep, 1.0, t[:, 0])
    gain = np.abs(1.0 + y / (rack.pitch_radius * tx**2))
    alpha_t = np.arctan2(np.abs(t[:, 0]), np.abs(t[:, 1]))
    section = cb / (np.cos(alpha_t) ** 2 + cb**2 * np.sin(alpha_t) ** 2)
    error = gain * np.broadcast_to(np.asarray(tangent_accuracy, dtype=float), len(t))
    error = np.degrees(section * np.where(steep, np.arcsin(STEEP), error))
    return angle, np.where(flank, error, 0.0)


def line_read(
    rack: DerivedRack, scatter: float, spacing: float, given: DerivedRack | None = None
) -> tuple[np.ndarray, np.ndarray]:
    """Return each rack point's angle as :func:`hob.verdict.judge` reads a straight flank, and that line's accuracy.

    Parameters
    ----------
    rack : DerivedRack
        A rack of the pair from the points, in its own frame.
    scatter, spacing : float, mm
        One given point's standard deviation and the points' median spacing (:func:`hob.verdict.local_scatter`).
    given : DerivedRack, optional
        Of a mate's rack, the given rotor's: a line counts the given points along the given rack's nearest points
        too, the fewer of the two (rack frame of CONTRACT.md); default ``rack`` itself.

    Returns
    -------
    angle : (n,) float array, deg
        The line's angle (:func:`hob.straight_flank.straight_flank_reading`) at the points read as a straight
        part's line, NaN elsewhere.
    accuracy : (n,) float array, deg
        Its accuracy there (:func:`hob.straight_flank.line_accuracy`), NaN elsewhere.
    """
    from hob.straight_flank import straight_flank_reading
    from hob.verdict import rack_frame
    from rotorcad.inverse_rack import MEASURED_MIN_TURN

    n = len(rack.points)
    if scatter <= 0 or spacing <= 0:
        return np.full(n, np.nan), np.full(n, np.nan)
    frame = rack_frame(rack)
    pts, tan, flank, arc, order = frame.points, frame.tangents, frame.flank, frame.arc, frame.order
    pointwise = np.degrees(np.arctan2(np.abs(tan[:, 0]), np.abs(tan[:, 1])))
    given_arc = None
    if given is not None and given is not rack and given.profile is not None:
        from scipy.spatial import cKDTree

        own, mine = given.in_contract_frame(), rack.in_contract_frame()
        span = np.concatenate([[0.0], np.cumsum(np.hypot(*np.diff(given.profile, axis=0).T))])
        span = span[::-1] if own.points[0, 0] != given.points[0, 0] else span
        period = np.array([given.period, 0.0])
        tree = cKDTree(np.vstack([own.points - period, own.points, own.points + period]))
        near = tree.query(mine.points)[1] % len(own.points)
        given_arc = span[near]
        given_arc = (given_arc[::-1] if mine.points[0, 0] != rack.points[0, 0] else given_arc)[order]
    angle, line = straight_flank_reading(
        pts, tan, pointwise, flank, arc, scatter, spacing, MEASURED_MIN_TURN, given_along=given_arc
    )
    angle = np.where(np.isfinite(line), angle, np.nan)
    out_angle, out_line = np.empty(n), np.empty(n)
    out_angle[order], out_line[order] = angle, line
    return out_angle, out_line


def lobe_factor(rotors: object) -> float:
    """Return the ratio of the largest of a lobe's errors to one point's (module docstring), at least 1.

    Parameters
    ----------
    rotors : ScrewRotors
        A pair generated from a rotor's points: ``accuracy`` (the lobe's largest error, k_N sigma with 95 %
        confidence) and ``point_accuracy`` (one point's, 2 sigma), mm.

    Returns
    -------
    float
        ``accuracy / point_accuracy``; 1 when either is missing or 0 (a design, exact points).
    """
    whole = float(getattr(rotors, "accuracy", 0.0) or 0.0)
    point = getattr(rotors, "point_accuracy", None)
    return max(whole / point, 1.0) if point and whole > 0 else 1.0


def smallest_angle_accuracy(rotors: object, racks: dict[str, DerivedRack], given: str, smallest: float) -> float:
    """Return the accuracy (deg) of the smallest normal flank angle read from a rotor's points.

    Parameters
    ----------
    rotors : ScrewRotors
        A pair generated from a rotor's points (``accuracy``, ``tangent_accuracy``, ``tangent_spread``);
        a design, a rack's points or a gear give 0.
    racks : dict of DerivedRack
        ``male`` and ``female`` racks of the pair (:func:`rotorcad.inverse_rack.rotor_rack`), own frames.
    given : {"male", "female"}
        The rotor given by points. The mate's rack is the same rack where the two touch: each of its
        points takes the error of the given rack's nearest point (rack frame of CONTRACT.md).
    smallest : float, deg
        The smallest angle read (of both racks).

    Returns
    -------
    float, deg
        How far the smallest angle may lie from the true one either way (module docstring).
    """
    rack = racks.get(given)
    if not getattr(rotors, "accuracy", 0.0) or rack is None or rack.profile is None:
        return 0.0
    turn = float(getattr(rotors, "tangent_accuracy", 0.0))
    spread = getattr(rotors, "tangent_spread", None)
    if turn > 0:
        accuracy: np.ndarray | float = turn
    elif spread is not None:
        accuracy = _spread_at(np.asarray(spread[0]), np.asarray(spread[1]), np.hypot(*rack.profile.T))
    else:
        return 0.0
    # below the read minimum by one point's error (at the true minimum's point, a fixed one); above it by the
    # lobe's largest at the point whose error made it the minimum (module docstring)
    from hob.verdict import local_scatter

    lines = {side: line_read(each, *local_scatter(rotors), given=rack) for side, each in racks.items()}
    low, _ = _bounds(rack, racks, given, accuracy, lines)
    _, at_minimum = _bounds(rack, racks, given, lobe_factor(rotors) * accuracy, lines)  # the steep points' 3 deg unscaled
    if low is None or at_minimum is None:
        return 0.0
    return max(smallest - low, at_minimum, 0.0)


def _bounds(
    rack: DerivedRack,
    racks: dict[str, DerivedRack],
    given: str,
    accuracy: np.ndarray | float,
    lines: dict[str, tuple[np.ndarray, np.ndarray]] | None = None,
) -> tuple[float | None, float | None]:
    """Return the smallest of the angles less their errors, and the error at the smallest angle (deg), both racks.

    The mate's rack is the same rack where the two touch: each of its points takes the error of the
    given rack's nearest point (rack frame of CONTRACT.md). None, None where no rack point is a flank's.
    """
    from scipy.spatial import cKDTree

    angle, error = flank_angle_errors(rack, accuracy)
    angles, errors = [angle], [error]
    own = rack.in_contract_frame()
    if own.points[0, 0] != rack.points[0, 0]:  # travelled the other way: the errors follow the points
        error = error[::-1]
    period = np.array([rack.period, 0.0])
    tree = cKDTree(np.vstack([own.points - period, own.points, own.points + period]))
    for side, mate in racks.items():
        if side == given:
            continue
        mate_angle, mate_error = flank_angle_errors(mate, 0.0)  # its steep points' bound only
        near = tree.query(mate.in_contract_frame().points)[1] % len(own.points)
        flipped = mate.in_contract_frame().points[0, 0] != mate.points[0, 0]
        borrowed = error[near][::-1] if flipped else error[near]
        angles.append(mate_angle)
        errors.append(np.maximum(mate_error, borrowed))
    if lines:  # the straight parts as judge reads them: the line's angle and its own accuracy
        sides = [given] + [side for side in racks if side != given]
        read = np.concatenate([lines[side][0] for side in sides])
        read_error = np.concatenate([lines[side][1] for side in sides])
        by_line = np.isfinite(read) & np.isfinite(np.concatenate(angles))
        angles = [np.where(by_line, read, np.concatenate(angles))]
        errors = [np.where(by_line, read_error, np.concatenate(errors))]
    angle, error = np.concatenate(angles), np.concatenate(errors)
    finite = np.isfinite(angle)
    if not finite.any():
        return None, None
    low = max(float(np.min(angle[finite] - error[finite])), 0.0)  # a flank angle is 0-90 deg
    return low, float(error[finite][np.argmin(angle[finite])])


__all__ = ["flank_angle_errors", "line_read", "lobe_factor", "smallest_angle_accuracy"]

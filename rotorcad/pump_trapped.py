"""The trapped space of an external gear pump, from the two gears' outlines (shapely).

While two pairs of teeth are in contact (contact ratio eps > 1, for (eps - 1) of each base pitch)
the oil between the two contacts is cut off from both suction and discharge (Kollek & Osiński,
*Innovative gear pump*, sec. 3.1: the trapped space, whose squeezing raises the pressure Δp_z). Here
its transverse area is measured on the gears themselves: the gear and its mate are placed in mesh at
the gear's rotation phi, the two contact points P_new and P_old are where their driving flanks meet on
the line of action, and the space is the loop along the gear's outline from P_new to P_old and back
along the mate's outline, one pitch of each; its area (shoelace, the signed area of the loop) is the
trapped area per unit face width. At zero backlash the back flanks touch inside the loop and split it
in two; the area is then their sum (the volume between the two driving contacts).

Placement (rotorcad's pump frame: gear about O1 = (0, 0) turning counter-clockwise, mate about
O2 = (a_w, 0)): the line of action runs from the gear's base tangency T1 = r_b1 (cos a_w, -sin a_w)
in the direction (sin a_w, cos a_w); a contact at roll u from T1 lies on the upper (leading) flank of a
gear tooth, whose polar angle is the tooth's centre + psi1(rho1), and on the mate tooth's flank at polar
angle (about O2) the tooth's centre + psi2(rho2), psi the half angle of the generated tooth
(:meth:`rotorcad.gears.involute_gear.InvoluteGear.half_angle`).

The independent check (tests/test_pump_trapped.py) is the kinematic one of :mod:`rotorcad.pump`: the
space changes at b (q'(u_new) - q'(u_old)) / w1, from the tip radii and the contact positions alone.
"""

from __future__ import annotations

import numpy as np
import shapely

from rotorcad.geometry import rotate


def _arc(ring: shapely.LinearRing, start: np.ndarray, end: np.ndarray) -> np.ndarray:
    """Return the shorter way along ``ring`` from the point nearest ``start`` to the one nearest ``end``, (n, 2)."""
    length = ring.length
    a, b = ring.project(shapely.Point(start)), ring.project(shapely.Point(end))
    coords = np.asarray(ring.coords)[:-1]
    along = np.concatenate([[0.0], np.cumsum(np.hypot(*np.diff(np.vstack([coords, coords[:1]]), axis=0).T))])[:-1]
    forward = (b - a) % length
    lo, span = (a, forward) if forward <= length / 2 else (b, length - forward)
    inside = (along - lo) % length < span
    order = np.argsort((along[inside] - lo) % length)
    pts = np.vstack([ring.interpolate(lo).coords[0], coords[inside][order], ring.interpolate((lo + span) % length).coords[0]])
    return pts if lo == a else pts[::-1]


def trapped_areas(pump, phi: np.ndarray, tolerance: float = 2e-4) -> np.ndarray:
    """Return the trapped transverse area at the gear's rotations ``phi`` over the double contact, mm².

    Parameters
    ----------
    pump : rotorcad.pump.GearPump
        A spur pump (the transverse section; eps > 1).
    phi : (k,) float array, rad
        Rotation of the gear from the moment the second contact begins (the new contact at the
        start of the governing contact's travel), within the double contact (0 to (eps - 1) p_b / r_b1).
    tolerance : float, mm
        Chord tolerance of the outlines (the area's error is of the order of the outline's length
        times it).

    Returns
    -------
    (k,) float array, mm²
        The area of the loop between the two contacts (module docstring).
    """
    pair = pump.pair
    gear, mate = pair.gear, pair.mate
    aw = pair.working_pressure_angle
    a = pair.working_center_distance
    t1 = gear.base_radius * np.array([np.cos(aw), -np.sin(aw)])
    direction = np.array([np.sin(aw), np.cos(aw)])
    start = pump.line_of_action()[0]
    pb = gear.base_pitch
    ring1 = np.asarray(gear.outline(tolerance).points)
    ring2 = np.asarray(mate.outline(tolerance).points)
    out = np.empty(len(phi))
    for i, turn in enumerate(np.asarray(phi, dtype=float)):  # one placement per phase: a loop over phases, not points
        new = t1 + (start + gear.base_radius * turn) * direction
        old = new + pb * direction
        rho1 = float(np.hypot(*new))
        centre1 = np.arctan2(new[1], new[0]) - gear.half_angle(rho1)  # the gear tooth whose upper flank holds P_new
        rel = new - np.array([a, 0.0])
        rho2 = float(np.hypot(*rel))
        centre2 = np.arctan2(rel[1], rel[0]) - mate.half_angle(rho2)  # the mate tooth whose flank holds P_new
        g = shapely.LinearRing(rotate(ring1, centre1))
        m = shapely.LinearRing(rotate(ring2, centre2) + np.array([a, 0.0]))
        loop = np.vstack([_arc(g, new, old), _arc(m, old, new)])
        x, y = loop.T
        out[i] = abs(0.5 * float(np.dot(x, np.roll(y, -1)) - np.dot(y, np.roll(x, -1))))
    return out


__all__ = ["trapped_areas"]

"""Sharp tip corners and their paths on the rack, shared by the profile families.

A sharp tip corner of one rotor generates the other rotor's flank by its own path
(point-generated, Rinder's "Radlinien"): on the rack chain that path is a piece of its own
(:class:`rotorcad.curves.PointPath`, role :class:`rotorcad.roles.PieceRole` ``*_CORNER_PATH``).
These functions trim a rack flank where its conjugate leaves a tip circle and continue the chain
with the corner's path.
"""

from __future__ import annotations

import numpy as np

from rotorcad.curves import Curve, PointPath
from rotorcad.envelope import Generated, rack_line_meshline_point
from rotorcad.geometry import rotate, wrap_angle
from rotorcad.roles import PieceRole
from rotorcad.roots import bracket_root
from rotorcad.rotor_pair import RotorPair
from rotorcad.screw_rotors import RackPiece, rack_arc

# A corner on the pitch circle (d1 = 0) cuts a cycloid whose cusp on the pitch line has its normal
# along the pitch line: no contact exists there, and within about 1e-7 rad of it the normal is lost
# in rounding. Its path stops this far (rad of the male) short of the cusp, 1e-11 mm from it.
CUSP_MARGIN = 1e-6


def fixed_to_rack(pair: RotorPair, p: np.ndarray, t: float) -> np.ndarray:
    """Return the rack-frame coordinates of fixed point ``p`` (mm) at motion parameter ``t`` (rad of the male), mm."""
    r = pair.male_pitch_radius
    return np.array([p[1] - r * t, p[0] - r])


def female_tip_corner(pair: RotorPair, flank: Curve, at_end: bool) -> tuple[Curve, PointPath, float] | None:
    """Trim a rack flank at the female tip circle and add the female tip corner's path to the rack bottom.

    The flank is trimmed where its generated female point reaches the female tip circle, and the
    path of that female tip corner down to the rack bottom is added. The female's flank generated
    by ``flank`` ends at a sharp corner P_N on its tip circle. Beyond that instant P_N itself sweeps
    the male (point-generated male flank), so the rack continues with P_N's path until P_N is
    nearest O1, where the path touches the rack bottom y = -d1 tangentially (the female tip circle
    is generated there).

    Parameters
    ----------
    pair : RotorPair
        The pair.
    flank : Curve
        The rack flank, fixed frame at t = 0.
    at_end : bool
        The flank runs down to the bottom at its end (sealing side), else it rises from it at its
        start (driving side).

    Returns
    -------
    tuple of (Curve, PointPath, float) or None
        The trimmed flank, the corner path (travelled with the chain) and the rack-frame x of its
        foot (mm), or None where the flank's conjugate stays within the female tip circle (a rack
        bottom on the pitch line, d1 = 0: the rack corner is then the female's corner itself).
    """
    mesh = pair.mesh
    o2 = np.array([pair.center_distance, 0.0])
    gen = Generated(flank, mesh.rack, mesh.female)
    s = np.linspace(flank.s0, flank.s1, 801)
    meshline = gen.meshline_contact(s)[1]  # where the contacts lie (the generated points are not needed)
    r = np.hypot(*(meshline - o2).T) - pair.female_tip_radius
    beyond = r > 1e-9 * pair.female_tip_radius
    k = np.nonzero(beyond[:-1] != beyond[1:])[0]
    if len(k) == 0:
        return None
    i = k[-1] if at_end else k[0]
    line = rack_line_meshline_point(gen)  # the same numbers as meshline_contact, without its arrays
    if line is not None:
        s_n = bracket_root(lambda v: np.hypot(*np.subtract(line(v), o2)) - pair.female_tip_radius, (s[i], s[i + 1]), xtol=1e-14)
    else:
        s_n = bracket_root(
            lambda v: np.hypot(*(gen.meshline_contact(v)[1][0] - o2)) - pair.female_tip_radius, (s[i], s[i + 1]), xtol=1e-14
        )
    t_n, x_n = gen.meshline_contact(s_n)[:2]
    path, x_foot = female_corner_path(pair, x_n[0], float(t_n[0]), at_end)
    trimmed = flank.trimmed(flank.s0, s_n) if at_end else flank.trimmed(s_n, flank.s1)
    return trimmed, path, x_foot


def female_corner_path(pair: RotorPair, contact: np.ndarray, t_n: float, at_end: bool) -> tuple[PointPath, float]:
    """Return the path of a female tip corner from a contact to its passage nearest O1, and its foot.

    The corner is the one in contact at ``contact`` (fixed frame) at male angle ``t_n``; its path
    runs from then to its passage nearest O1 (travelled that way if ``at_end``, else the other way).
    With a male dedendum of zero the path stops ``CUSP_MARGIN`` short of that passage.

    Parameters
    ----------
    pair : RotorPair
        The pair.
    contact : (2,) float array, mm
        The contact point, fixed frame.
    t_n : float, rad
        Male angle at that contact.
    at_end : bool
        Travel from the contact to the foot (else from the foot to the contact).

    Returns
    -------
    path : PointPath
        The corner's path in the rack's frame.
    x_foot : float, mm
        Rack-frame x of the foot.
    """
    mesh = pair.mesh
    corner = mesh.female.to_body(contact[None, :], t_n)[0]  # female corner, fixed placement at t = 0
    # polar angle about O2 at t_n; the female turns clockwise at z1/z2 rad per male rad and the
    # corner is nearest O1 at polar angle pi
    ang = np.arctan2(contact[1], contact[0] - pair.center_distance)
    ratio = pair.female_teeth / pair.male_teeth
    t_f = t_n + wrap_angle(ang - np.pi) * ratio  # the nearest passage, before or after t_n
    if abs(pair.male_dedendum) < 1e-9:
        t_f += CUSP_MARGIN * np.sign(t_n - t_f)
    path = (
        PointPath(tuple(corner), mesh.female, mesh.rack, t_n, t_f)
        if at_end
        else PointPath(tuple(corner), mesh.female, mesh.rack, t_f, t_n)
    )
    return path, float(path.point(t_f)[1])


def flank_to_female_tip(
    pair: RotorPair, flank: Curve, at_end: bool, flank_names: tuple[str, str], label: str
) -> tuple[tuple[RackPiece, ...], float]:
    """Build a rack flank ending on the rack bottom at a sharp female tip corner, in chain order.

    The pieces are the flank trimmed at the female tip circle plus the corner's path
    (:func:`female_tip_corner`), or, where the flank's conjugate stays inside the tip circle, the
    flank and a rack corner at its foot (the female's corner, whose path the male receives).

    Parameters
    ----------
    pair : RotorPair
        The pair.
    flank : Curve
        The rack flank, fixed frame at t = 0.
    at_end : bool
        The flank comes down to the bottom (sealing side), else it rises from it.
    flank_names : tuple of str
        Names of the segments the flank generates on the male and on the female.
    label : str
        Which flank, for the corner's segment names (e.g. "leading", "driving").

    Returns
    -------
    pieces : tuple of RackPiece
        The flank and the corner piece, in chain order.
    x_foot : float, mm
        Rack-frame x of the foot on the bottom line.
    """
    names = (f"{label} root (female tip path)", f"{label} tip corner")
    cut = female_tip_corner(pair, flank, at_end)
    if cut is not None:
        trimmed, path, x_foot = cut
        corner = RackPiece(path, *names, kind=PieceRole.FEMALE_CORNER_PATH)
        flank_piece = RackPiece(trimmed, *flank_names)
    else:
        p, t = flank.evaluate(np.array([flank.s1 if at_end else flank.s0]))
        foot = fixed_to_rack(pair, p[0], 0.0)
        psi = float(np.arctan2(t[0, 0], t[0, 1])) - np.pi / 2  # rack-frame tangent (t_y, t_x)
        fan = (psi, 1.5 * np.pi) if at_end else (-np.pi / 2, psi)
        fan = (fan[0] + 2 * np.pi * (fan[0] < fan[1] - 2 * np.pi), fan[1])
        x_foot = float(foot[0])
        corner = RackPiece(rack_arc(pair, (x_foot, float(foot[1])), 0.0, *fan), *names, kind=PieceRole.FEMALE_CORNER_PATH)
        flank_piece = RackPiece(flank, *flank_names)
    return ((flank_piece, corner) if at_end else (corner, flank_piece)), x_foot


def male_tip_corner(pair: RotorPair, flank: Curve, rising: bool = False) -> tuple[Curve, PointPath, float] | None:
    """Trim a falling rack flank at the male tip circle and trace the male tip corner it leaves.

    Where the flank's contacts leave the male bore (its generated male point beyond the male tip
    circle), the male ends in a sharp tip corner on its tip circle. Beyond that instant the rack
    flank is no longer a male flank, so the female must be generated by that corner, the male's
    own point (its path, point-generated), not by the rest of the rack flank: else the female is cut
    where the male never goes. The corner's path runs from its passage of O1O2 (the end of the male
    tip land, on the rack top) to the contact where the flank reaches the tip circle.

    Parameters
    ----------
    pair : RotorPair
        The pair.
    flank : Curve
        The rack flank, fixed frame at t = 0, travelled from the rack top down (the sealing side) or,
        if ``rising``, up to the rack top (the driving side: the corner's path then follows it).
    rising : bool
        The flank rises to the rack top at its end.

    Returns
    -------
    tuple of (Curve, PointPath, float) or None
        The flank trimmed at the male tip circle, the corner's path (travelled with the chain) and the
        rack-frame x where it leaves the rack top (mm); None where the flank's contacts stay inside
        the male tip circle.
    """
    mesh = pair.mesh
    r1t = pair.male_tip_radius
    gen = Generated(flank, mesh.rack, mesh.female)
    s = np.linspace(flank.s0, flank.s1, 801)
    meshline = gen.meshline_contact(s)[1]  # where the contacts lie (the generated points are not needed)
    beyond = np.hypot(*meshline.T) - r1t > 1e-9 * r1t
    k = np.nonzero(~beyond[:-1] & beyond[1:])[0] if rising else np.nonzero(beyond[:-1] & ~beyond[1:])[0]
    if len(k) == 0:
        return None
    i = k[0] if rising else k[-1]
    line = rack_line_meshline_point(gen)  # the same numbers as meshline_contact, without its arrays
    if line is not None:
        s_m = bracket_root(lambda v: float(np.hypot(*line(v)) - r1t), (float(s[i]), float(s[i + 1])), xtol=1e-14)
    else:
        s_m = bracket_root(
            lambda v: float(np.hypot(*gen.meshline_contact(v)[1][0]) - r1t), (float(s[i]), float(s[i + 1])), xtol=1e-14
        )
    if s_m is None:  # the sample before lies within 1e-9 r1t outside the tip circle: it is the root
        s_m = float(s[i] if rising else s[i + 1])
    t_c, x_c = gen.meshline_contact(s_m)[:2]
    p, t_m = x_c[0], float(t_c[0])
    t_q = t_m - float(np.arctan2(p[1], p[0]))  # the corner on O1O2 (polar angle 0) at t_q
    x_corner = -t_q * pair.male_pitch_radius
    if rising:
        return flank.trimmed(flank.s0, s_m), male_corner_path(pair, x_corner, t_m, t_q), x_corner
    return flank.trimmed(s_m, flank.s1), male_corner_path(pair, x_corner, t_q, t_m), x_corner


def point_generated_sealing(pair: RotorPair, x_corner: float) -> tuple[PointPath, float, float, float]:
    """Return the path of the male tip corner at rack point (x_corner, h1) up to the housing cusp, and its times.

    Parameters
    ----------
    pair : RotorPair
        The pair.
    x_corner : float, mm
        Rack-frame x of the corner on the rack top.

    Returns
    -------
    path : PointPath
        The corner's path in the rack frame, from its passage of O1O2 to the housing cusp.
    t_q, t_k : float, rad
        Male angles at those two passages.
    cusp_angle : float, rad
        Polar angle of the housing cusp about O1.
    """
    mesh = pair.mesh
    t_q = -x_corner / pair.male_pitch_radius
    q_male = rotate(np.array([[pair.male_tip_radius, 0.0]]), -t_q)[0]
    k = pair.housing_cusp
    t_k = t_q + np.arctan2(k[1], k[0])
    path = PointPath(tuple(q_male), mesh.male, mesh.rack, t_q, t_k)
    return path, t_q, t_k, float(np.arctan2(k[1], k[0]))


def male_corner_path(pair: RotorPair, x_corner: float, t_from: float, t_to: float) -> PointPath:
    """Return the rack-frame path of the male tip corner at rack point (x_corner, h1) over male angles t_from -> t_to.

    Parameters
    ----------
    pair : RotorPair
        The pair.
    x_corner : float, mm
        Rack-frame x of the corner on the rack top.
    t_from, t_to : float, rad
        Male angles where the path starts and ends.

    Returns
    -------
    PointPath
    """
    t_q = -x_corner / pair.male_pitch_radius
    q_male = rotate(np.array([[pair.male_tip_radius, 0.0]]), -t_q)[0]
    return PointPath(tuple(q_male), pair.mesh.male, pair.mesh.rack, t_from, t_to)

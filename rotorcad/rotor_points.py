"""Rotor pairs from measured points: of the rack, of the male or of the female rotor.

The points (CONTRACT.md "Points files") are fitted with a cubic spline (interpolating, or
smoothing with ``smoothing`` > 0) so that tangents are exact. A rotor's lobe is turned into its
rack by inverse generation (Wu & Chi sec. 2, eqs. 4-8, in the transverse section), and the pair
is generated from that rack; the rotor given comes back as its own conjugate's conjugate (a
round trip that the tests check).
"""

from __future__ import annotations

import numpy as np
from scipy import optimize

from rotorcad.curves import Curve, Mapped, Spline
from rotorcad.envelope import Generated, from_rack_frame
from rotorcad.errors import DesignError
from rotorcad.geometry import rotate
from rotorcad.rotor_pair import RotorPair
from rotorcad.screw_rotors import RackPiece, ScrewRotors


def pair_from_rack_points(pair: RotorPair, points: np.ndarray, smoothing: float = 0.0) -> ScrewRotors:
    """One rack period given in the rack frame (x along the motion, y > 0 towards the female)."""
    pts = np.asarray(points, dtype=float)
    if pts[-1, 0] < pts[0, 0]:
        pts = pts[::-1]
    span = pts[-1, 0] - pts[0, 0]
    if abs(span - pair.rack_period) > 1e-3 * pair.rack_period:
        raise DesignError("rack points", f"one rack period long in x ({pair.rack_period:.6g} mm)", f"{span:.6g} mm")
    spline = Spline.fit(from_rack_frame(pts, pair.male_pitch_radius), smoothing=smoothing)
    return ScrewRotors(pair, (RackPiece(spline, "flank", "flank"),), "rack-points")


def _whole_outline(points: np.ndarray, teeth: int) -> np.ndarray:
    """The whole outline, counter-clockwise, from points of one lobe (patterned) or of all."""
    pts = np.asarray(points, dtype=float)
    ang = np.unwrap(np.arctan2(pts[:, 1], pts[:, 0]))
    if abs(ang[-1] - ang[0]) < 2 * np.pi * (1 - 0.5 / teeth):  # one lobe: pattern it
        if ang[-1] < ang[0]:
            pts, ang = pts[::-1], ang[::-1]
        return np.vstack([rotate(pts[:-1], 2 * np.pi * k / teeth) for k in range(teeth)])
    whole = pts if ang[-1] > ang[0] else pts[::-1]
    return whole[:-1] if np.allclose(whole[0], whole[-1]) else whole


def _facing_root_angle(whole: np.ndarray, teeth: int, facing: float) -> float:
    """Polar angle of the root that starts the lobe containing the polar angle ``facing``."""
    root = whole[np.argmin(np.hypot(*whole.T))]
    pitch = 2 * np.pi / teeth
    theta0 = np.arctan2(root[1], root[0])
    return float(theta0 + np.floor((facing - theta0) / pitch) * pitch)


def _lobe_spline(points: np.ndarray, teeth: int, smoothing: float, facing: float) -> tuple[Spline, float, float]:
    """Periodic spline of the whole outline (one lobe is patterned) and the parameters of the lobe
    between two consecutive roots that contains the polar angle ``facing`` (towards the mate, so
    that its contacts lie within half a turn of the mesh position)."""
    whole = _whole_outline(points, teeth)
    spline = Spline.fit(whole, smoothing=smoothing, periodic=True)
    s = np.linspace(0.0, spline.s1, 20 * len(whole) + 1)
    p, _ = spline.evaluate(s)
    pitch = 2 * np.pi / teeth
    theta = _facing_root_angle(p, teeth, facing)

    def crossing(th: float) -> float:
        rel = np.mod(np.arctan2(p[:, 1], p[:, 0]) - th + np.pi, 2 * np.pi) - np.pi
        i = np.nonzero((rel[:-1] < 0) & (rel[1:] >= 0))[0][0]
        f = lambda v: np.mod(np.arctan2(*spline.evaluate(v)[0][0][::-1]) - th + np.pi, 2 * np.pi) - np.pi  # noqa: E731
        return optimize.brentq(f, s[i], s[i + 1], xtol=1e-13)

    s_a = crossing(theta)
    s_b = crossing(theta + pitch)
    if s_b <= s_a:
        s_b += spline.s1
    return spline, s_a, s_b


def lobe_curve(pair: RotorPair, points: np.ndarray, rotor: str, smoothing: float = 0.0) -> Curve:
    """The spline of one lobe of the male or the female (own frame, counter-clockwise, from root to
    root), the lobe facing the mate, from points of one lobe or of the whole outline."""
    teeth = pair.male_teeth if rotor == "male" else pair.female_teeth
    spline, s_a, s_b = _lobe_spline(points, teeth, smoothing, 0.0 if rotor == "male" else np.pi)
    if s_b > spline.s1:  # the lobe wraps past the spline's seam: shift the seam
        p, _ = spline.evaluate(np.linspace(s_a, s_b, 4000) % spline.s1)
        spline = Spline.fit(p, smoothing=0.0)
        s_a, s_b = 0.0, spline.s1
    return spline.trimmed(s_a, s_b)


def _polar_crossing(curve: Curve, points: np.ndarray, u: np.ndarray, theta: float) -> float | None:
    """Parameter where ``curve`` (through ``points`` at parameters ``u``) crosses the polar ray at
    ``theta`` counter-clockwise, or None."""
    rel = np.mod(np.arctan2(points[:, 1], points[:, 0]) - theta + np.pi, 2 * np.pi) - np.pi
    i = np.nonzero((rel[:-1] < 0) & (rel[1:] >= 0) & (np.abs(rel[:-1]) < np.pi / 2) & (np.abs(rel[1:]) < np.pi / 2))[0]
    if len(i) == 0:
        return None

    def f(v: float) -> float:
        q = curve.evaluate(v)[0][0]
        return float(np.mod(np.arctan2(q[1], q[0]) - theta + np.pi, 2 * np.pi) - np.pi)

    a, b = u[i[0]], u[i[0] + 1]
    if f(a) * f(b) > 0:  # the spline between the points: take the chord's crossing
        return float(a)
    return float(optimize.brentq(f, a, b, xtol=1e-13))


def lobe_pieces(
    pair: RotorPair, points: np.ndarray, rotor: str, smoothing: float = 0.0, corner_angle_deg: float = 30.0
) -> list[tuple[str, Curve]]:
    """One lobe of the male or the female (own frame, counter-clockwise, from root to root, the
    lobe facing the mate) as spline pieces between the sharp corners of the points.

    A measured outline may have sharp corners (a female tip without rounding): a spline through one
    rings. A vertex where the polygon turns by more than ``corner_angle_deg`` is a corner; the
    outline is fitted piecewise between corners (each piece a cubic spline with exact tangents),
    and the corners stay corners (their fans of normals are added where racks are derived). An
    outline without corners is one periodic spline (:func:`lobe_curve`).
    """
    teeth = pair.male_teeth if rotor == "male" else pair.female_teeth
    whole = _whole_outline(points, teeth)
    d = np.diff(np.vstack([whole, whole[:1]]), axis=0)
    heading = np.arctan2(d[:, 1], d[:, 0])
    turn = np.mod(heading - np.roll(heading, 1) + np.pi, 2 * np.pi) - np.pi  # at each vertex
    corners = np.nonzero(np.abs(turn) > np.radians(corner_angle_deg))[0]
    if len(corners) == 0:
        return [("flank", lobe_curve(pair, points, rotor, smoothing))]
    n = len(whole)
    ring = np.vstack([whole, whole])
    runs = [ring[a : b + 1] for a, b in zip(corners, np.append(corners[1:], corners[0] + n), strict=True)]
    splines = [Spline.fit(run, smoothing=smoothing) for run in runs]
    params = [np.concatenate([[0.0], np.cumsum(np.hypot(*np.diff(run, axis=0).T))]) for run in runs]
    theta = _facing_root_angle(whole, teeth, 0.0 if rotor == "male" else np.pi)

    def locate(th: float) -> tuple[int, float]:
        for k, (sp, run, u) in enumerate(zip(splines, runs, params, strict=True)):
            s = _polar_crossing(sp, run, u, th)
            if s is not None:
                return k, s
        raise DesignError(f"{rotor} points", "an outline that every ray from its centre crosses once", None)

    (k_a, s_a), (k_b, s_b) = locate(theta), locate(theta + 2 * np.pi / teeth)
    if k_a == k_b and s_b > s_a:
        curves = [splines[k_a].trimmed(s_a, s_b)]
    else:
        curves = [splines[k_a].trimmed(s_a, splines[k_a].s1)]
        k = (k_a + 1) % len(splines)
        while k != k_b:
            curves.append(splines[k])
            k = (k + 1) % len(splines)
        curves.append(splines[k_b].trimmed(0.0, s_b))
    return [(f"lobe part {i + 1}", c) for i, c in enumerate(curves) if abs(c.s1 - c.s0) > 1e-9]


def pair_from_rotor_points(pair: RotorPair, points: np.ndarray, rotor: str, smoothing: float = 0.0) -> ScrewRotors:
    """Points of the male or the female rotor in its own frame (one lobe or the whole outline)."""
    mesh = pair.mesh
    lobe = lobe_curve(pair, points, rotor, smoothing)
    depth = (-pair.male_dedendum - 1e-6, pair.male_addendum + 1e-6)  # the rack lies between these
    if rotor == "male":
        rack_curve = Generated(lobe, mesh.male, mesh.rack, limits=depth).reversed()
    else:
        placed = Mapped(lobe, ((1.0, 0.0), (0.0, 1.0)), (pair.center_distance, 0.0))
        rack_curve = Generated(placed, mesh.female, mesh.rack, limits=depth)
    s = np.linspace(rack_curve.s0, rack_curve.s1, 400)
    ok = np.isfinite(rack_curve.evaluate(s)[0]).all(axis=1)
    lost = 100.0 * (1 - ok.mean())
    if lost > 2.0:  # a few points at sharp corners may miss their pitch circle; more is not a rotor
        raise DesignError(
            f"{rotor} points",
            "a profile whose every normal meets its pitch circle (it has a rack)",
            None,
            f"{lost:.1f} % of the lobe has no rack point",
        )
    return ScrewRotors(pair, (RackPiece(rack_curve, "flank", "flank"),), f"{rotor}-points", rack_loss=lost)

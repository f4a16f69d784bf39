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

from rotorcad.curves import Mapped, Spline
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


def _lobe_spline(points: np.ndarray, teeth: int, smoothing: float, facing: float) -> tuple[Spline, float, float]:
    """Periodic spline of the whole outline (one lobe is patterned) and the parameters of the lobe
    between two consecutive roots that contains the polar angle ``facing`` (towards the mate, so
    that its contacts lie within half a turn of the mesh position)."""
    pts = np.asarray(points, dtype=float)
    ang = np.unwrap(np.arctan2(pts[:, 1], pts[:, 0]))
    if abs(ang[-1] - ang[0]) < 2 * np.pi * (1 - 0.5 / teeth):  # one lobe: pattern it
        if ang[-1] < ang[0]:
            pts, ang = pts[::-1], ang[::-1]
        whole = np.vstack([rotate(pts[:-1], 2 * np.pi * k / teeth) for k in range(teeth)])
    else:
        whole = pts if ang[-1] > ang[0] else pts[::-1]
    spline = Spline.fit(whole, smoothing=smoothing, periodic=True)
    s = np.linspace(0.0, spline.s1, 20 * len(whole) + 1)
    p, _ = spline.evaluate(s)
    root = p[np.argmin(np.hypot(*p.T))]
    pitch = 2 * np.pi / teeth
    theta0 = np.arctan2(root[1], root[0])
    theta = theta0 + np.floor((facing - theta0) / pitch) * pitch

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


def pair_from_rotor_points(pair: RotorPair, points: np.ndarray, rotor: str, smoothing: float = 0.0) -> ScrewRotors:
    """Points of the male or the female rotor in its own frame (one lobe or the whole outline)."""
    mesh = pair.mesh
    teeth = pair.male_teeth if rotor == "male" else pair.female_teeth
    spline, s_a, s_b = _lobe_spline(points, teeth, smoothing, 0.0 if rotor == "male" else np.pi)
    if s_b > spline.s1:  # the lobe wraps past the spline's seam: shift the seam
        p, _ = spline.evaluate(np.linspace(s_a, s_b, 4000) % spline.s1)
        spline = Spline.fit(p, smoothing=0.0)
        s_a, s_b = 0.0, spline.s1
    lobe = spline.trimmed(s_a, s_b)
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

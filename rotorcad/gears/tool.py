"""The generating rack tool of an involute gear and the gear curve each of its pieces cuts.

The tool is the counterpart of the ISO 53 basic rack (:class:`RackTool`: tip line, tip arc and
straight flank of the tooth facing the upper flank of tooth 0), and :class:`ToolCut` is the
closed form of the curve one piece cuts into the gear as the rack rolls on the pitch circle: the
envelope engine's meshing condition written out for this one motion (Litvin, *Gear Geometry and
Applied Theory*, eq. 6.1.7).
"""

from __future__ import annotations

import cmath
import math
from dataclasses import dataclass
from typing import Literal

import numpy as np

from rotorcad.curves import Arc, Curve, Line, Mapped
from rotorcad.geometry import Array

CutKind = Literal["line", "arc"]
"""The shape of a tool piece: a straight ``"line"`` (tip line, flank) or an ``"arc"`` (tip arc)."""
ToolPiece = Literal["tip line", "tip arc", "flank"]
"""A piece of the tool tooth, in its counter-clockwise travel (:meth:`RackTool.curves`)."""


def as_pairs(z: Array) -> Array:
    """Complex numbers x + i y, (n,), as points (n, 2) float (a view of the same memory)."""
    return z.view(np.float64).reshape(-1, 2)


def as_complex(p: Array) -> Array:
    """Points (n, 2) float as complex numbers x + i y, (n,)."""
    return np.ascontiguousarray(p, dtype=np.float64).view(np.complex128).reshape(-1)


class ToolCut:
    """One piece of the rack tool and the piece of gear outline it cuts, both in closed form.

    The tool piece lies in the fixed frame at t = 0 (gear centre O at the origin, pitch point
    C = (r, 0), the rack moving with V = (0, r) per radian of the gear) and is stretched by
    S = diag(1, k), k = 1 / cos(beta), along the pitch line (the transverse section of a helical
    tool). It is either a straight line, p(s) = S (a + s d) with ``s`` the length along the
    unstretched line, or an arc, p(s) = S (K + rho (cos s, sin s)) with ``s`` the polar angle about
    K (rho = 0: a sharp corner, one point with a fan of normals). These are the parameters of the
    tool curves of :meth:`RackTool.curves`, so that a cut piece is evaluated at the parameters of
    the matching :class:`~rotorcad.envelope.Generated` curve.

    The law of gearing (Litvin, *Gear Geometry and Applied Theory*, eq. 6.1.7) makes the tool's
    outward normal n at the contact point pass through C: cross(n, p + V t - C) = 0, linear in the
    gear's turn t, so t = -cross(n, p - C) / (r n_x). The cut point is R(-t) (p + V t), its tangent
    R(-t) tau (tau the tool's unit tangent). For the line t is linear in s and the cut curve is an
    involute of the base circle (ISO 21771 sec. 2.3); for the arc, with n = S^-T (cos s, sin s)
    normalised, t = -k K_y / r + tan(s) (K_x - r) / (r k) + rho sin(s) (1 / k - k) / r and the cut
    curve is the trochoidal root fillet (for k = 1 the path of K offset by rho, Litvin ch. 6); the
    tip line cuts the root circle. This is the envelope engine's evaluation
    (:func:`rotorcad.envelope.conjugate`) written out for this one motion, in complex numbers
    (x + i y; R(-t) is a product with exp(-i t)) and with no per-call objects, plus the derivatives
    that give the cut curve's curvature for sampling.

    Parameters
    ----------
    kind : {"line", "arc"}
        The tool piece's shape (:data:`CutKind`).
    r : float
        Pitch radius of the gear, mm.
    k : float
        Stretch along the pitch line, 1 / cos(beta).
    start, direction : (2,) float
        A line's start a (mm) and unit direction d, unstretched.
    center, radius : (2,) float and float, mm
        An arc's centre K (unstretched) and radius rho.
    length : float
        A line's length, mm (its parameter at the far end).
    """

    __slots__ = ("arc", "center", "direction", "k", "kind", "length", "r", "radius", "start", "tangent", "turn")

    def __init__(
        self,
        kind: CutKind,
        r: float,
        k: float,
        start: tuple[float, float] = (0.0, 0.0),
        direction: tuple[float, float] = (1.0, 0.0),
        center: tuple[float, float] = (0.0, 0.0),
        radius: float = 0.0,
        length: float = 0.0,
    ) -> None:
        if kind not in ("line", "arc"):
            raise ValueError(f"kind must be 'line' or 'arc', not {kind!r}")
        self.kind: CutKind = kind
        self.r = r = float(r)
        self.k = k = float(k)
        self.start = (float(start[0]), float(k * start[1]))  # S a, mm
        self.direction = dx, dy = (float(direction[0]), float(k * direction[1]))  # S d
        self.center = kx, ky = (float(center[0]), float(center[1]))
        self.radius = rho = float(radius)
        self.length = float(length)
        speed = math.hypot(dx, dy)
        self.tangent = complex(dx / speed, dy / speed)  # a line's unit tangent tau
        # a line's contact turn t = t0 + t1 s; an arc's t = A + B tan(s) + D sin(s)
        ax, ay = self.start
        tx, ty = dx / speed, dy / speed
        self.turn = (-(ty * ay + tx * (ax - r)) / (r * ty), -speed / (r * ty)) if kind == "line" else None
        self.arc = (-k * ky / r, (kx - r) / (r * k), rho * (1.0 / k - k) / r) if kind == "arc" else None

    def roll(self) -> tuple[float, float]:
        """Return a line's roll distance, along = a0 + a1 s, mm.

        The roll distance is where the line's contact point X(s) lies on the line of action,
        measured from T1, the foot of the perpendicular from O (the base circle's tangency point),
        towards C.

        The contact points of a straight tool flank run along the line of action, which passes
        through C along the tool's normal n: X - T1 = (X . n) n and C - T1 = (C . n) n, so the
        roll distance is sign(C . n) (X . n), linear in s through X(s) = p(s) + V t(s). It is also
        the radius of curvature of the involute at the cut point (ISO 21771 sec. 2.3).

        Returns
        -------
        (float, float)
            a0 (mm) and a1 (mm per mm of s).
        """
        (ax, ay), (dx, dy) = self.start, self.direction
        t0, t1 = self.turn
        tau = self.tangent
        nx, ny = tau.imag, -tau.real
        sign = 1.0 if self.r * nx >= 0.0 else -1.0
        a0 = sign * (nx * ax + ny * (ay + self.r * t0))
        a1 = sign * (nx * dx + ny * (dy + self.r * t1))
        return a0, a1

    def point(self, s: float) -> complex:
        """Return the cut point at one tool parameter (the steps of :meth:`cut`, for one point, in Python floats).

        Parameters
        ----------
        s : float
            Tool parameter: mm along the unstretched line, or the polar angle about an arc's centre
            (rad; a single point).

        Returns
        -------
        complex
            The cut point in the gear frame as x + i y, mm.
        """
        if self.kind == "arc":
            a, b, d = self.arc
            e = cmath.exp(1j * s)
            c, sn = e.real, e.imag
            t = a + b * (sn / c)
            if d:
                t += d * sn
            rho, (kx, ky) = self.radius, self.center
            z = rho * e + complex(kx, ky) if self.k == 1.0 else complex(kx + rho * c, self.k * (ky + rho * sn))
            return complex(z.real, z.imag + self.r * t) * cmath.exp(-1j * t)
        (ax, ay), (dx, dy) = self.start, self.direction
        t0, t1 = self.turn
        t = t0 + t1 * s
        return complex(ax + s * dx, ay + s * dy + self.r * t) * cmath.exp(-1j * t)

    def cut(self, s: Array, curvature: bool = False, pairs: bool = True) -> tuple[Array, ...]:
        """Return the cut gear curve at tool parameters ``s``.

        Parameters
        ----------
        s : (n,) float array
            Tool parameters (see the class docstring).
        curvature : bool
            Also return dphi/ds, the turning rate of the cut curve's tangent (phi = psi - t, psi
            the tool tangent's angle), and its speed |dP/ds| = |dp/ds + dt/ds (V - J X) . tau|
            (J X the gear's velocity at the contact point X; the meshing condition makes
            dP/ds parallel to the tangent); the radius of curvature is |dP/ds| / |dphi/ds|.
        pairs : bool
            Points and tangents as (n, 2) float arrays (else as complex x + i y, (n,)).

        Returns
        -------
        points : (n, 2) float array, mm (or (n,) complex)
            Points of the cut curve in the gear frame.
        tangents : (n, 2) float array (or (n,) complex)
            Unit tangents along increasing ``s`` (the tool's tangent turned by -t).
        turning : (n,) float array, rad per unit of s
            dphi/ds, signed; only with ``curvature``.
        speed : (n,) float array, mm per unit of s
            |dP/ds|; only with ``curvature``.
        """
        r, k = self.r, self.k
        if self.kind == "line":
            (ax, ay), (dx, dy) = self.start, self.direction
            t0, t1 = self.turn
            t = t0 + t1 * s
            z = complex(ax, ay + r * t0) + complex(dx, dy + r * t1) * s  # the contact point X = p + V t
            tau = self.tangent
            turn, dt = 0.0, t1
        else:
            a, b, d = self.arc
            e = np.exp(1j * s)
            c, sn = e.real, e.imag
            t = a + b * (sn / c)
            if d:
                t += d * sn
            rho, (kx, ky) = self.radius, self.center
            if k == 1.0:
                z = rho * e + complex(kx, ky)
                tau = 1j * e
            else:
                z = kx + rho * c + 1j * (k * (ky + rho * sn))
                norm = np.sqrt(sn * sn + (k * k) * (c * c))
                tau = (1j * k * c - sn) / norm
            z.imag += r * t
        rot = np.exp(-1j * t)
        pts, tan = z * rot, tau * rot
        if pairs:
            pts, tan = as_pairs(pts), as_pairs(tan)
        if not curvature:
            return pts, tan
        if self.kind == "arc":
            norm = np.sqrt(sn * sn + (k * k) * (c * c))  # |S (-sin s, cos s)|
            speed = self.radius * norm
            turn = k / (norm * norm)
            dt = b / (c * c) + (d * c if d else 0.0)
        else:
            speed = math.hypot(dx, dy)
        along = (np.conj(tau) * (1j * (r - z))).real  # (V - J X) . tau
        return pts, tan, turn - dt, np.abs(speed + dt * along)


@dataclass(frozen=True)
class RackTool:
    """The tool tooth facing the upper flank of tooth 0 (ISO 53 rack, shifted by x m), as numbers.

    In the fixed frame at t = 0 (gear centre at the origin, pitch point C = (r, 0), the rack moving
    +y), unstretched, mm.

    Parameters
    ----------
    pitch_radius : float
        Pitch radius r of the gear, mm.
    tip_line_start : (2,) float or None
        Start of the tool's tip line (None when the two tip arcs meet).
    tip_line_end : (2,) float
        End of the tip line, the tip arc's start.
    arc_center : (2,) float
        Centre of the tip arc.
    arc_radius : float
        Its radius rho_a0, mm.
    arc_end : float
        Polar angle where the tip arc meets the flank, 3 pi / 2 - alpha_n, rad (it starts at pi).
    flank_start, flank_end : (2,) float
        The straight flank from its tangency with the tip arc to past the rack point that cuts the
        tip circle.
    stretch : float
        k = 1 / cos(beta), the transverse section's scale along the pitch line.
    """

    pitch_radius: float
    tip_line_start: tuple[float, float] | None
    tip_line_end: tuple[float, float]
    arc_center: tuple[float, float]
    arc_radius: float
    arc_end: float
    flank_start: tuple[float, float]
    flank_end: tuple[float, float]
    stretch: float

    @classmethod
    def for_gear(
        cls,
        module: float,
        pressure_angle: float,
        helix_angle: float,
        shift: float,
        dedendum: float,
        tip_radius_factor: float,
        pitch_radius: float,
        tip_radius: float,
        base_radius: float,
        transverse_pressure_angle: float,
    ) -> RackTool:
        """Return the tool that cuts a gear of these design values (ISO 53 basic rack, shifted by x m).

        Parameters
        ----------
        module, pressure_angle, helix_angle : float
            Normal module m (mm), normal pressure angle alpha_n and helix angle beta (rad).
        shift, dedendum, tip_radius_factor : float
            Profile shift x, tool addendum h_a0* = h_fP* and tool tip radius rho_a0*, in modules.
        pitch_radius, tip_radius, base_radius : float
            The gear's r, nominal r_a and r_b, mm.
        transverse_pressure_angle : float
            alpha_t, rad.

        Returns
        -------
        RackTool
        """
        m, a = module, pressure_angle
        r = pitch_radius
        rho = tip_radius_factor * m
        pn = np.pi * m
        v_tip = (shift - dedendum) * m
        v_c = v_tip + rho
        k_u = pn / 4.0 + dedendum * m * np.tan(a) + rho * (1.0 - np.sin(a)) / np.cos(a)
        tf = (r + v_c - rho * np.sin(a), k_u - rho * np.cos(a))
        # the flank must reach the rack point that generates the tip circle (plus margin)
        at = transverse_pressure_angle
        v_top = (np.sqrt(tip_radius**2 - base_radius**2) - r * np.sin(at)) * np.sin(at) + 0.5 * m
        top = (r + v_top, pn / 4.0 + (shift * m - v_top) * np.tan(a))
        has_line = bool(pn / 2.0 - k_u > 1e-12 * m)
        return cls(
            pitch_radius=float(r),
            tip_line_start=(r + v_tip, pn / 2.0) if has_line else None,
            tip_line_end=(r + v_tip, k_u),
            arc_center=(r + v_c, k_u),
            arc_radius=rho,
            arc_end=1.5 * np.pi - a,
            flank_start=tf,
            flank_end=top,
            stretch=1.0 / np.cos(helix_angle),
        )

    def curves(self) -> dict[ToolPiece, Curve]:
        """Return the tool's pieces as exact curves, in the fixed frame at t = 0.

        Travelled counter-clockwise around the tool material (outward normal towards the gear):
        ``tip line`` -> ``tip arc`` -> ``flank``.

        Returns
        -------
        dict of ToolPiece to Curve
            :class:`~rotorcad.curves.Mapped` lines and arc (stretched by 1 / cos(beta) along the
            pitch line), mm.
        """
        stretch = ((1.0, 0.0), (0.0, self.stretch))
        curves: dict[ToolPiece, Curve] = {}
        if self.tip_line_start is not None:
            curves["tip line"] = Mapped(Line(self.tip_line_start, self.tip_line_end), stretch)
        curves["tip arc"] = Mapped(Arc(self.arc_center, self.arc_radius, np.pi, self.arc_end), stretch)
        curves["flank"] = Mapped(Line(self.flank_start, self.flank_end), stretch)
        return curves

    def cuts(self) -> dict[ToolPiece, ToolCut]:
        """Return the pieces of :meth:`curves` as closed-form cutters.

        Returns
        -------
        dict of ToolPiece to ToolCut
            Keyed like :meth:`curves`, with the parameters of its curves (length along a line, mm;
            polar angle about the arc centre, rad).
        """
        r, k = self.pitch_radius, self.stretch
        cuts: dict[ToolPiece, ToolCut] = {}
        lines: tuple[tuple[ToolPiece, tuple[float, float] | None, tuple[float, float]], ...] = (
            ("tip line", self.tip_line_start, self.tip_line_end),
            ("flank", self.flank_start, self.flank_end),
        )
        for name, a, b in lines:
            if a is not None:
                dx, dy = float(b[0]) - float(a[0]), float(b[1]) - float(a[1])
                length = math.hypot(dx, dy)
                cuts[name] = ToolCut("line", r, k, a, (dx / length, dy / length), length=length)
        cuts["tip arc"] = ToolCut("arc", r, k, center=self.arc_center, radius=self.arc_radius)
        return cuts

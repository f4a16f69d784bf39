"""Cutting tools: a trapezoidal hob (straight-sided rack in its normal section) and a rack tool by points.

A tool is described by one tool tooth in the fixed frame of :mod:`rotorcad.kinematics` at t = 0
(pitch line x = r, motion +y), centred on y = p/2 and pointing towards the blank's centre: the
form :func:`hob.cutting.simulate_cutting` rolls over the blank.

The trapezoidal hob (Kollek & Osiński: "frez ślimakowy o zarysie trapezowym") has module m0,
pressure angle alpha0, addendum h_a0* m0 below its datum line, and at its tip either a radius
rho_a0* m0 or a chamfer (a straight cut of the corner, height c* m0 at angle ``chamfer_angle``
to the tip line). A protuberance q* m0 moves the lower flank outwards by q (relief of the root
for a later finishing cut), starting at height h_pr* m0 above the tip. The hob's thread has
``starts`` and outside diameter d_a0: its lead angle is gamma0 = asin(starts m0 / d_m0) at the
datum diameter d_m0 = d_a0 - 2 h_a0 m0.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from rotorcad.errors import DesignError


@dataclass(frozen=True)
class TrapezoidalHob:
    """A hob with a trapezoidal (straight-sided) profile in its normal section (module docstring).

    Parameters
    ----------
    module : float, mm
        Module m0.
    pressure_angle : float, rad
        Pressure angle alpha0 (0 to 45 degrees).
    addendum : float
        Addendum factor h_a0* (the gear's dedendum).
    tip_radius : float
        Tip radius factor rho_a0* (0 with a chamfer).
    tip_chamfer : float
        Chamfer height factor c* instead of a radius (then ``tip_radius`` must be 0).
    chamfer_angle : float, rad
        Angle of the chamfer to the tip line.
    protuberance : float
        Protuberance factor q*.
    protuberance_height : float
        Height factor h_pr* above the tip where the protuberance ends.
    starts : int
        Thread starts.
    diameter : float, mm, optional
        Outside diameter d_a0 (for the lead angle).

    Raises
    ------
    DesignError
        A module that is not positive, a pressure angle out of range, a radius and a chamfer
        together, or fewer than 1 start.
    """

    module: float
    pressure_angle: float = 20.0 * np.pi / 180.0
    addendum: float = 1.25  # h_a0*
    tip_radius: float = 0.38  # rho_a0*
    tip_chamfer: float = 0.0  # c*: chamfer height instead of a radius (then tip_radius must be 0)
    chamfer_angle: float = 30.0 * np.pi / 180.0  # of the chamfer to the tip line
    protuberance: float = 0.0  # q*
    protuberance_height: float = 0.5  # h_pr*, above the tip
    starts: int = 1
    diameter: float | None = None  # d_a0 (mm)

    def __post_init__(self) -> None:
        if not (self.module > 0):
            raise DesignError("module", "a positive length in mm", self.module)
        if not (0.0 < self.pressure_angle < np.pi / 4):
            raise DesignError("pressure_angle", "between 0 and 45 degrees", np.degrees(self.pressure_angle))
        if self.tip_radius > 0 and self.tip_chamfer > 0:
            raise DesignError("tip_chamfer", "0 when a tip radius is given (one or the other)", self.tip_chamfer)
        if not isinstance(self.starts, (int, np.integer)) or self.starts < 1:
            raise DesignError("starts", "a whole number of at least 1", self.starts)

    @property
    def lead_angle(self) -> float | None:
        """Lead angle gamma0 = asin(starts m0 / d_m0) of the hob thread, rad (None without a diameter).

        Raises :class:`DesignError` when the diameter is too small for the datum diameter.
        """
        if self.diameter is None:
            return None
        dm = self.diameter - 2.0 * self.addendum * self.module
        if not dm > self.starts * self.module:
            raise DesignError(
                "diameter", f"greater than {2 * self.addendum * self.module + self.starts * self.module:.4g} mm", self.diameter
            )
        return float(np.arcsin(self.starts * self.module / dm))

    def tooth(self, pitch_radius: float, shift: float, top: float, samples: int = 64) -> np.ndarray:
        """Return one tool tooth as a closed polygon in the fixed frame at t = 0.

        The datum line is shifted by x m0 outwards, the tooth centred on y = p/2 and reaching up to
        x = ``top``. Built in the rack coordinates (u along the pitch line, v towards the blank's
        outside): its half facing tooth 0 runs from the tooth centre u = p/2 along the tip line, over the
        tip radius / chamfer / corner, up the flank u(v) = p/4 + (x m0 - v) tan(alpha0).

        Parameters
        ----------
        pitch_radius : float, mm
            Pitch radius r of the blank (the tool's pitch line is x = r).
        shift : float
            Profile shift x, in modules.
        top : float, mm
            x at which the tooth is closed, above the blank.
        samples : int
            Points of the tip radius.

        Returns
        -------
        (n, 2) float array, mm
            The polygon: one half, two top corners, the mirrored half.

        Raises
        ------
        DesignError
            A tip radius, chamfer or addendum that does not fit the tool tooth.
        """
        m, a = self.module, self.pressure_angle
        pn = np.pi * m
        u_c = pn / 2.0
        v_tip = (shift - self.addendum) * m

        def flank_u(v: float) -> float:
            return float(pn / 4.0 + (shift * m - v) * np.tan(a))

        if self.tip_radius > 0:
            rho = self.tip_radius * m
            k_u = pn / 4.0 + self.addendum * m * np.tan(a) + rho * (1.0 - np.sin(a)) / np.cos(a)
            if k_u > u_c:
                raise DesignError("tip_radius", "small enough to fit the tool tooth", self.tip_radius)
            v_c = v_tip + rho
            th = np.linspace(0.0, np.pi / 2.0 - a, samples)  # from the tip line round to the flank
            tip = [(u_c, v_tip)] + [(k_u - rho * np.sin(t), v_c - rho * np.cos(t)) for t in th]
        elif self.tip_chamfer > 0:
            c = self.tip_chamfer * m
            up = v_tip + c
            run = c / np.tan(self.chamfer_angle)
            if not run > c * np.tan(a):
                raise DesignError("chamfer_angle", f"less than {90 - np.degrees(a):.1f} degrees", np.degrees(self.chamfer_angle))
            tip = [(u_c, v_tip), (flank_u(up) + run, v_tip), (flank_u(up), up)]
        else:
            tip = [(u_c, v_tip), (flank_u(v_tip), v_tip)]
        if tip[1][0] > u_c:
            raise DesignError("addendum", "small enough that the tool tooth keeps a tip land", self.addendum)
        pts = list(tip)
        if self.protuberance > 0:  # the flank near the tip stands out by q (relief cut in the root)
            q = self.protuberance * m
            v_pr = v_tip + self.protuberance_height * m
            pts = [pts[0]] + [(u - q, v) for u, v in pts[1:] if v < v_pr]
            pts += [(flank_u(v_pr) - q, v_pr), (flank_u(v_pr + 2.0 * q), v_pr + 2.0 * q)]
        v_top = top - pitch_radius
        pts.append((flank_u(v_top), v_top))
        half = np.array(pts)  # (u, v)
        upper = np.column_stack([pitch_radius + half[:, 1], half[:, 0]])  # fixed frame: X = r + v, Y = u
        mirrored = upper[::-1] * np.array([1.0, -1.0]) + np.array([0.0, pn])
        return np.vstack([upper, [[top, upper[-1, 1]], [top, mirrored[0, 1]]], mirrored])


@dataclass(frozen=True)
class RackTool:
    """A general rack tool: one tool tooth given as points in the rack frame of CONTRACT.md.

    Parameters
    ----------
    points : (n, 2) float array, mm
        The tooth: x along the pitch line, y = 0 on the pitch line, y < 0 towards the blank; from its
        one side's top over the tip to the other side's top, spanning one pitch.
    pitch : float, mm
        The tool's pitch.
    """

    points: np.ndarray
    pitch: float

    def tooth(self, pitch_radius: float, shift: float, top: float) -> np.ndarray:
        """Return the tool tooth as a closed polygon in the fixed frame at t = 0.

        Parameters
        ----------
        pitch_radius : float, mm
            Pitch radius r of the blank (the tool's pitch line is x = r).
        shift : float
            Profile shift x of the gear, in modules of the tool (m = pitch / pi), as for
            :meth:`TrapezoidalHob.tooth`: the tool stands x m further out.
        top : float, mm
            x at which the tooth is closed, above the blank.

        Returns
        -------
        (n + 2, 2) float array, mm
            The points at X = r + y + x m, Y = x, closed by two corners at X = ``top``.
        """
        pts = np.asarray(self.points, dtype=float)
        upper = np.column_stack([pitch_radius + pts[:, 1] + shift * self.pitch / np.pi, pts[:, 0]])
        return np.vstack([upper, [[top, upper[-1, 1]], [top, upper[0, 1]]]])

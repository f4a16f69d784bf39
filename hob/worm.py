"""The hob's basic worm (Grundschnecke): the thread whose normal section is the normal rack.

A hob is a worm gashed into cutting teeth; the worm it is made from, the basic worm, carries the
tool's rack in its thread. Its figures follow from the normal rack (:class:`hob.rack.DerivedRack`,
period the normal pitch ``p_n``), the number of starts ``z0`` and the outside diameter ``d_a0``
(DIN 3975 / ISO 1122-1 worm terms; Kollek & Osiński on the hob's thread; the relations of
:class:`hob.tools.TrapezoidalHob`):

* the reference radius ``r_m`` is where the rack's datum line ``y = y_d`` lies (a gear's basic
  rack: its datum line, ``y_d = x m_n`` from the gear's pitch circle for a profile shift ``x``; a
  rotor's rack: its pitch line, ``y_d = 0``): the rack's tooth tip (its least ``y``, towards the
  body's centre) is the worm's outside radius, ``r_m = r_a0 + y_min - y_d`` (DIN 3968:
  ``d_m0 = d_a0 - 2 h_a0``);
* lead angle ``gamma`` at the reference cylinder: ``sin(gamma) = z0 p_n / (2 pi r_m)``, so that
  ``tan(gamma) = h / (2 pi r_m)`` with the lead ``h = z0 p_x`` and the axial pitch
  ``p_x = p_n / cos(gamma)``;
* the thread's axial section is the normal rack with its lengths along the pitch line divided by
  ``cos(gamma)`` (the rack turned into the worm's axial plane by the lead angle), ``w = x / cos(gamma)``,
  and the radius the helicoid of that section,
  ``r = r_m - (y - y_d)``: the helicoid of that section,
  ``(r cos(phi), r sin(phi), w + h phi / (2 pi))``, ``h`` signed (> 0 right hand).

Its transverse section at z = 0 is then ``phi = -2 pi w / h``: each point of the rack goes to
``(r cos(phi), r sin(phi))``, and the helical solid of that section (:mod:`exports.step_exact`) is
the worm. Between its samples the rack is its cubic Hermite interpolant (the derived rack's exact
tangents at every sample, chord-length parameters: de Boor, *A Practical Guide to Splines*, ch. IV),
mapped to the transverse plane in closed form with its tangents (:class:`WormThreadCurve`), so that
the section is a :class:`rotorcad.profile.Profile` of exact curves.

The gashes (the flutes that cut the worm into the hob's teeth) are given by their number and depth;
they are reported for the hob's order, the solid is the basic worm.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from rotorcad.curves import Curve
from rotorcad.errors import DesignError
from rotorcad.geometry import Array
from rotorcad.inverse_rack import DerivedRack
from rotorcad.profile import Profile, Segment

MAX_STARTS = 12
"""Most thread starts accepted."""
MAX_LEAD_ANGLE = math.radians(45.0)
"""Largest lead angle accepted at the reference cylinder."""


@dataclass(frozen=True, eq=False)
class WormThreadCurve(Curve):
    """One piece of the normal rack carried into the worm's transverse section (module docstring).

    Parameters
    ----------
    points, tangents : (n, 2) float arrays
        The rack piece's samples (mm) and exact unit tangents, normal-rack frame (x along the pitch
        line, y away from the body's centre).
    reference_radius : float, mm
        The worm radius of the rack's line ``y = 0``: ``r_m + y_d``.
    axial_scale : float
        ``1 / cos(gamma)``.
    twist : float, rad/mm
        ``2 pi / h`` of the signed lead.
    turn : float, rad
        Extra turn of the section (``2 pi j / z0`` for the thread start ``j``).
    s0, s1 : float
        Parameter range: ``s = i + u`` on the interval ``i`` between samples ``i`` and ``i + 1``.
    """

    points: Array = field(repr=False)
    tangents: Array = field(repr=False)
    reference_radius: float = 0.0
    axial_scale: float = 1.0
    twist: float = 0.0
    turn: float = 0.0
    s0: float = 0.0
    s1: float = 0.0

    def rack_frame(self, s: Array) -> tuple[Array, Array]:
        """Return the rack's Hermite cubic and its derivative along ``s`` at ``s``, each (n, 2).

        Parameters
        ----------
        s : (n,) float array
            Parameters in ``[0, len(points) - 1]``.

        Returns
        -------
        points : (n, 2) float array, mm
        derivative : (n, 2) float array, mm per unit of ``s``
        """
        p, t = self.points, self.tangents
        s = np.asarray(s, dtype=float)
        i = np.clip(np.floor(s).astype(int), 0, len(p) - 2)
        u = (s - i)[:, None]
        chord = np.hypot(*(p[i + 1] - p[i]).T)[:, None]
        b0, b1, b2, b3 = p[i], p[i] + chord * t[i] / 3.0, p[i + 1] - chord * t[i + 1] / 3.0, p[i + 1]
        v = 1.0 - u
        point = v**3 * b0 + 3 * u * v**2 * b1 + 3 * u**2 * v * b2 + u**3 * b3
        deriv = 3 * (v**2 * (b1 - b0) + 2 * u * v * (b2 - b1) + u**2 * (b3 - b2))
        return point, deriv

    def frame(self, s: Array) -> tuple[Array, Array]:
        """Points and unit tangents of the transverse section (module docstring), each (n, 2)."""
        q, dq = self.rack_frame(s)
        r = self.reference_radius - q[:, 1]
        phi = self.turn - self.twist * self.axial_scale * q[:, 0]
        dr = -dq[:, 1]
        dphi = -self.twist * self.axial_scale * dq[:, 0]
        c, si = np.cos(phi), np.sin(phi)
        pts = np.column_stack([r * c, r * si])
        d = np.column_stack([dr * c - r * dphi * si, dr * si + r * dphi * c])
        return pts, d / np.hypot(d[:, 0], d[:, 1])[:, None]


@dataclass(frozen=True, eq=False)
class BasicWorm:
    """The hob's basic worm (module docstring).

    Parameters
    ----------
    rack : DerivedRack
        The body's rack (``y`` away from its centre, not the contract frame); its normal section is
        the thread's.
    starts : int
        Thread starts ``z0``.
    outside_diameter : float, mm
        ``d_a0``.
    right_hand : bool
        Hand of the thread.
    length : float, mm
        Length of the worm along its axis.
    gashes : int
        Number of gashes (flutes), 0 when not stated.
    gash_depth : float, mm
        Their depth below the outside diameter (0 when not stated).
    datum : float, mm
        ``y_d``: the rack's datum line, where the reference cylinder lies (module docstring).
    """

    rack: DerivedRack
    starts: int
    outside_diameter: float
    right_hand: bool
    length: float
    gashes: int = 0
    gash_depth: float = 0.0
    datum: float = 0.0

    @property
    def normal_rack(self) -> tuple[Array, Array]:
        """The normal rack's points (mm) and unit tangents, (n, 2) each (Wu & Chi eq. 7)."""
        return self.rack.normal_section()

    @property
    def normal_pitch(self) -> float:
        """``p_n``, mm."""
        return float(self.rack.normal_period)

    @property
    def reference_radius(self) -> float:
        """``r_m = r_a0 + y_min - y_d``, mm: the rack's datum line on the worm."""
        return 0.5 * self.outside_diameter + float(self.normal_rack[0][:, 1].min()) - self.datum

    @property
    def root_diameter(self) -> float:
        """Diameter of the thread's root (the rack's largest ``y``), mm."""
        return 2.0 * (self.reference_radius + self.datum - float(self.normal_rack[0][:, 1].max()))

    @property
    def thread_depth(self) -> float:
        """Depth of the thread, outside radius less root radius, mm."""
        return float(np.ptp(self.normal_rack[0][:, 1]))

    @property
    def lead_angle(self) -> float:
        """``gamma``, rad: ``sin(gamma) = z0 p_n / (2 pi r_m)``."""
        return math.asin(self.starts * self.normal_pitch / (2 * math.pi * self.reference_radius))

    @property
    def axial_pitch(self) -> float:
        """``p_x = p_n / cos(gamma)``, mm."""
        return self.normal_pitch / math.cos(self.lead_angle)

    @property
    def lead(self) -> float:
        """``h = z0 p_x``, mm (unsigned)."""
        return self.starts * self.axial_pitch

    @property
    def signed_lead(self) -> float:
        """The lead signed by the hand (> 0 right hand), mm."""
        return self.lead if self.right_hand else -self.lead

    def section(self, tolerance: float = 1e-4) -> Profile:
        """Return the worm's transverse section at z = 0, closed and counter-clockwise.

        One segment per rack piece and start (the rack's piece names), sampled to the chord
        ``tolerance`` (mm) on the exact curves (:class:`WormThreadCurve`).

        Raises
        ------
        DesignError
            A rack whose chain does not repeat after one period within :data:`JOIN_GAP` (``rack``).
        """
        pts, tan = self.normal_rack
        idx = self.rack.piece_index
        period = math.copysign(self.normal_pitch, pts[-1, 0] - pts[0, 0])  # the chain's travel along the pitch line
        twist = 2 * math.pi / self.signed_lead
        scale = 1.0 / math.cos(self.lead_angle)
        # the copies of the chain follow each other: the next start's chain begins where this one ends
        step = -twist * scale * period
        pieces = rack_pieces(pts, tan, idx, self.rack.names, pts[0] + [period, 0.0])
        segments = []
        for j in range(self.starts):
            for name, piece, piece_tangents in pieces:
                curve = WormThreadCurve(
                    piece, piece_tangents, self.reference_radius + self.datum, scale, twist, j * step, 0.0, len(piece) - 1.0
                )
                segments.append((name, curve))
        first = Profile(tuple(Segment.sample(n, c, tolerance) for n, c in segments))
        if shoelace(first.points) > 0:
            return first
        return Profile(tuple(Segment.sample(n, c.reversed(), tolerance) for n, c in reversed(segments)))

    def summary(self) -> dict[str, float | int | str]:
        """Return the figures a hob maker orders by (CONTRACT.md, ``rotorcad hob --json``, ``worms``).

        Returns
        -------
        dict
            Lengths in mm, the lead angle in degrees, counts as int, the hand as text.
        """
        return {
            "starts": self.starts,
            "hand": "right" if self.right_hand else "left",
            "outside_diameter": self.outside_diameter,
            "reference_diameter": 2.0 * self.reference_radius,
            "root_diameter": self.root_diameter,
            "thread_depth": self.thread_depth,
            "normal_pitch": self.normal_pitch,
            "axial_pitch": self.axial_pitch,
            "lead": self.lead,
            "lead_angle_deg": math.degrees(self.lead_angle),
            "worm_length": self.length,
            "gash_count": self.gashes,
            "gash_depth": self.gash_depth,
            "rack_join_max": self.largest_join,
        }

    @property
    def largest_join(self) -> float:
        """Largest gap of the rack chain bridged by a straight join (:func:`rack_pieces`), mm (0 without one)."""
        pts, tan = self.normal_rack
        period = math.copysign(self.normal_pitch, pts[-1, 0] - pts[0, 0])
        pieces = rack_pieces(pts, tan, self.rack.piece_index, self.rack.names, pts[0] + [period, 0.0])
        return max((float(np.hypot(*(p[1] - p[0]))) for name, p, _ in pieces if name == JOIN), default=0.0)


JOIN = "straight join"
"""Name of a piece that bridges a gap of the rack chain."""
JOIN_GAP = 0.1
"""Largest gap (mm) between two pieces of a rack chain, or between its end and its start moved by
one period, that a straight join bridges (reported as ``rack_join_max``): the derived rack's pieces
of a design's rotor meet to about 1 um where a corner's path meets a land; the mate's rack of a
measured rotor, cut where its loops overshoot the tip circle, leaves gaps of some 30 um."""


def rack_pieces(
    points: Array, tangents: Array, piece_index: Array, names: tuple[str, ...], closing: Array
) -> list[tuple[str, Array, Array]]:
    """Split a rack chain into its pieces, bridging small gaps between them by straight joins.

    Parameters
    ----------
    points, tangents : (n, 2) float arrays
        The chain (mm) and its unit tangents.
    piece_index : (n,) int array
        The piece of each point.
    names : tuple of str
        The pieces' names.
    closing : (2,) float array, mm
        Where the chain must end: its start moved by one period (the next period's start).

    Returns
    -------
    list of (name, points, tangents)
        Pieces of two samples or more in chain order, with a piece :data:`JOIN` of two samples
        wherever one piece ends more than 1 nm from where the next starts, and after the last one
        if it ends more than 1 nm from ``closing``.

    Raises
    ------
    DesignError
        A gap wider than :data:`JOIN_GAP` (``rack``).
    """
    out: list[tuple[str, Array, Array]] = []

    def join(target: Array) -> None:
        last = out[-1][1][-1]
        gap = float(np.hypot(*(target - last)))
        if gap > JOIN_GAP:
            raise DesignError("rack", f"a chain whose pieces meet within {JOIN_GAP:g} mm (a gap of {gap:.3g} mm)", None)
        if gap > 1e-9:
            chord = (target - last) / gap
            out.append((JOIN, np.array([last, target]), np.array([chord, chord])))

    for k, name in enumerate(names):
        sel = piece_index == k
        if sel.sum() < 2:
            continue
        p, t = points[sel], tangents[sel]
        if out:
            join(p[0])
        out.append((name, p, t))
    join(np.asarray(closing, dtype=float))
    return out


def shoelace(points: Array) -> float:
    """Signed area of a closed polygon, mm² (> 0 counter-clockwise)."""
    x, y = points[:, 0], points[:, 1]
    return 0.5 * float(np.dot(x, np.roll(y, -1)) - np.dot(y, np.roll(x, -1)))


def basic_worm(
    rack: DerivedRack,
    starts: int,
    outside_diameter: float,
    right_hand: bool = True,
    length: float | None = None,
    gashes: int = 0,
    gash_depth: float | None = None,
    datum: float = 0.0,
) -> BasicWorm:
    """Make the basic worm of a rack, checking its figures.

    Parameters
    ----------
    rack : DerivedRack
        The rack of a gear or rotor (:func:`hob.rack.gear_rack`, :func:`hob.rack.rotor_rack`).
    starts : int
        Thread starts, 1 to :data:`MAX_STARTS`.
    outside_diameter : float, mm
        The worm's outside diameter: its root must stay above the axis and the lead angle at the
        reference cylinder at most :data:`MAX_LEAD_ANGLE`.
    right_hand : bool
        Hand of the thread.
    length : float, mm, optional
        Worm length (default: the outside diameter).
    gashes : int
        Number of gashes, 0 (not stated) or 2 to 40.
    gash_depth : float, mm, optional
        Gash depth below the outside diameter, above the thread depth and below the outside radius
        (default with gashes: the thread depth plus a quarter of it).
    datum : float, mm
        The rack's datum line ``y_d`` (a gear's profile shift x m_n; 0 for a rotor's rack).

    Returns
    -------
    BasicWorm

    Raises
    ------
    DesignError
        A figure out of range, naming it (``starts``, ``outside_diameter``, ``length``, ``gashes``,
        ``gash_depth``).
    """
    if isinstance(starts, bool) or not isinstance(starts, int | np.integer) or not 1 <= starts <= MAX_STARTS:
        raise DesignError("starts", f"a whole number from 1 to {MAX_STARTS}", starts)
    worm = BasicWorm(rack, int(starts), float(outside_diameter), bool(right_hand), 0.0, datum=float(datum))
    y = worm.normal_rack[0][:, 1]
    least = max(
        2.0 * (float(y.max()) - float(y.min())),  # the root above the axis
        2.0 * (starts * worm.normal_pitch / (2 * math.pi * math.sin(MAX_LEAD_ANGLE)) - float(y.min()) + datum),
    )
    if not (math.isfinite(outside_diameter) and least < outside_diameter <= 1e4):
        raise DesignError(
            "outside_diameter",
            f"more than {least:.6g} mm (the root above the axis, the lead angle at most 45 deg) and at most 10000 mm",
            outside_diameter,
        )
    length = float(outside_diameter) if length is None else length
    if not (math.isfinite(length) and 0.0 < length <= 1e4):
        raise DesignError("length", "a length above 0 and at most 10000 mm", length)
    if isinstance(gashes, bool) or not isinstance(gashes, int | np.integer) or not (gashes == 0 or 2 <= gashes <= 40):
        raise DesignError("gashes", "0 (not stated) or a whole number from 2 to 40", gashes)
    depth = 0.0
    if gashes:
        depth = 1.25 * worm.thread_depth if gash_depth is None else gash_depth
        if not (math.isfinite(depth) and worm.thread_depth < depth < 0.5 * outside_diameter):
            raise DesignError(
                "gash_depth",
                f"more than the thread depth {worm.thread_depth:.6g} mm and less than the outside radius "
                f"{0.5 * outside_diameter:.6g} mm",
                depth,
            )
    elif gash_depth is not None:
        raise DesignError("gash_depth", "given with a number of gashes", gash_depth)
    return BasicWorm(
        rack, int(starts), float(outside_diameter), bool(right_hand), length, int(gashes), float(depth), float(datum)
    )


__all__ = ["MAX_STARTS", "BasicWorm", "WormThreadCurve", "basic_worm"]

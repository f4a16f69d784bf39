"""A conjugate screw-rotor pair generated from one rack period by the envelope engine.

Every profile family is written as a *rack chain*: one period p = 2 pi r1w / z1 of the rack,
made of ordinary curves (lines, arcs, ...) and of point paths (the path, seen from the rack, of a
sharp tip corner of one rotor: the point-generated flanks of Krigar and Lysholm, Rinder Fig. 1-4).
The male and the female are both generated from that rack, so they are conjugate to each other
by construction (Rinder sec. 2.1: the rack defines the toothing). A point path of a male corner
generates just that corner on the male and the point-generated flank on the female, and vice
versa.

Frames: the rack chain lives in the fixed frame at t = 0 (pitch line x = r1w, motion +y) and is
travelled in +y. The male lobe comes out centred on the +x axis side of O1, the female in its own
frame (centre at the origin); ``female_in_mesh`` shifts it by (a, 0) (CONTRACT.md, points files).
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property

import numpy as np
import shapely

from rotorcad.curves import Arc, Curve, Line, Mapped
from rotorcad.envelope import Generated, from_rack_frame
from rotorcad.profile import Profile, Segment
from rotorcad.roles import PieceRole, Side
from rotorcad.rotor_pair import RotorPair


@dataclass(frozen=True)
class RackPiece:
    """One piece of the rack chain with the names of what it generates on each rotor.

    ``kind`` is :attr:`PieceRole.CURVE`, or the corner path of a rotor (it generates only that
    corner on its own rotor).
    """

    curve: Curve
    male_name: str
    female_name: str
    kind: PieceRole = PieceRole.CURVE


def rack_line(pair: RotorPair, a: tuple[float, float], b: tuple[float, float]) -> Line:
    """A straight rack piece between two points given in the rack frame of CONTRACT.md."""
    r = pair.male_pitch_radius
    pa, pb = from_rack_frame(np.array([a, b], dtype=float), r)
    return Line(tuple(pa), tuple(pb))


def rack_arc(pair: RotorPair, center: tuple[float, float], radius: float, psi0: float, psi1: float) -> Arc:
    """A circular rack piece given in the rack frame (centre, radius, polar angles psi0 -> psi1
    about the centre, measured in the rack frame). The rack frame is the mirror image of the fixed
    frame, so an angle psi there is pi/2 - psi here.
    """
    c = from_rack_frame(np.array([center], dtype=float), pair.male_pitch_radius)[0]
    return Arc((float(c[0]), float(c[1])), radius, np.pi / 2 - psi0, np.pi / 2 - psi1)


@dataclass(frozen=True, eq=False)
class ScrewRotors:
    """A rotor pair with its rack chain and the generated male and female profiles."""

    pair: RotorPair
    rack: tuple[RackPiece, ...]
    family: str = "rack"
    tolerance: float = 1e-3
    rack_loss: float = 0.0  # per cent of a measured lobe without a rack point (normal misses the pitch circle)

    @cached_property
    def male_pieces(self) -> list[tuple[str, Curve, RackPiece]]:
        """Generated male pieces of one lobe in counter-clockwise order (the male's polar angle
        grows with the rack position, so the order is the rack's).
        """
        mesh = self.pair.mesh
        out = []
        for piece in self.rack:
            if piece.kind is PieceRole.MALE_CORNER_PATH:
                continue
            out.append((piece.male_name, Generated(piece.curve.reversed(), mesh.rack, mesh.male), piece))
        return out

    @cached_property
    def female_pieces(self) -> list[tuple[str, Curve, RackPiece]]:
        """Generated female pieces of one lobe in counter-clockwise order, in the female's own frame
        (the female turns the other way, so the order is the rack's reversed).
        """
        mesh = self.pair.mesh
        shift = (-self.pair.center_distance, 0.0)
        out = []
        for piece in reversed(self.rack):
            if piece.kind is PieceRole.FEMALE_CORNER_PATH:
                continue
            gen = Generated(piece.curve, mesh.rack, mesh.female)
            out.append((piece.female_name, Mapped(gen, ((1.0, 0.0), (0.0, 1.0)), shift), piece))
        return out

    def _lobe(self, pieces: list[tuple[str, Curve, RackPiece]], tolerance: float | None) -> Profile:
        tol = self.tolerance if tolerance is None else tolerance
        segs = []
        for name, curve, _ in pieces:
            if abs(curve.s1 - curve.s0) < 1e-15:
                continue
            seg = Segment.sample(name, curve, tol)
            if len(seg.points) == 0 or np.ptp(seg.points, axis=0).max() < 1e-9:  # degenerate piece (none or one point)
                continue
            segs.append(seg)
        return Profile(tuple(segs), closed=False)

    def male_lobe(self, tolerance: float | None = None) -> Profile:
        return self._lobe(self.male_pieces, tolerance)

    def female_lobe(self, tolerance: float | None = None) -> Profile:
        return self._lobe(self.female_pieces, tolerance)

    def male_outline(self, tolerance: float | None = None) -> Profile:
        """Whole male outline, closed and counter-clockwise, at male angle 0."""
        return self.male_lobe(tolerance).patterned(self.pair.male_teeth)

    def female_outline(self, tolerance: float | None = None) -> Profile:
        """Whole female outline in its own frame (centre at the origin) at the mesh position."""
        return self.female_lobe(tolerance).patterned(self.pair.female_teeth)

    def female_in_mesh(self, points: np.ndarray) -> np.ndarray:
        return np.asarray(points) + np.array([self.pair.center_distance, 0.0])

    def section(self, rotor: str, tolerance: float | None = None) -> shapely.Polygon:
        """The rotor's transverse section as a valid polygon in its own frame, clipped to its tip
        circle (generated curves may overshoot it by the rounding of the rack's corners).
        """
        side = Side(rotor)
        outline = self.male_outline(tolerance) if side is Side.MALE else self.female_outline(tolerance)
        tip = side.pick(self.pair.male_tip_radius, self.pair.female_tip_radius)
        poly = shapely.make_valid(shapely.Polygon(outline.points))
        disk = shapely.Point(0.0, 0.0).buffer(tip + 1e-6, quad_segs=512)
        clipped = poly.intersection(disk)
        if isinstance(clipped, shapely.MultiPolygon | shapely.GeometryCollection):
            clipped = max((g for g in clipped.geoms if isinstance(g, shapely.Polygon)), key=lambda g: g.area)
        return clipped

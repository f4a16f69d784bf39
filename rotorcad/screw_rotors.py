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
from rotorcad.rotor_cut import cut_segment
from rotorcad.rotor_pair import RotorPair


@dataclass(frozen=True)
class RackPiece:
    """One piece of the rack chain with the names of what it generates on each rotor.

    Parameters
    ----------
    curve : Curve
        The piece in the fixed frame at t = 0 (pitch line x = r1w), travelled in +y.
    male_name, female_name : str
        Names of the segments it generates on the male and on the female (e.g. "tip arc").
    kind : PieceRole
        :attr:`PieceRole.CURVE` (it generates a curve on both rotors), or the corner path of a
        rotor (it generates only that corner on its own rotor, and a point-generated flank on the
        other).
    """

    curve: Curve
    male_name: str
    female_name: str
    kind: PieceRole = PieceRole.CURVE


def rack_line(pair: RotorPair, a: tuple[float, float], b: tuple[float, float]) -> Line:
    """Make a straight rack piece between two points given in the rack frame of CONTRACT.md.

    Parameters
    ----------
    pair : RotorPair
        The pair (its male pitch radius r1w places the pitch line).
    a, b : (float, float), mm
        End points in the rack frame: x along the pitch line in the direction of motion, y = 0 on
        the pitch line, y > 0 towards the female.

    Returns
    -------
    Line
        The piece in the fixed frame (pitch line x = r1w), from ``a`` to ``b``.
    """
    r = pair.male_pitch_radius
    pa, pb = from_rack_frame(np.array([a, b], dtype=float), r)
    return Line(tuple(pa), tuple(pb))


def rack_arc(pair: RotorPair, center: tuple[float, float], radius: float, psi0: float, psi1: float) -> Arc:
    """Make a circular rack piece given in the rack frame of CONTRACT.md.

    The rack frame is the mirror image of the fixed frame, so a polar angle psi there is pi/2 - psi
    here; the arc keeps its direction from ``psi0`` to ``psi1`` as seen in the rack frame.

    Parameters
    ----------
    pair : RotorPair
        The pair (its male pitch radius r1w places the pitch line).
    center : (float, float), mm
        Centre of the arc in the rack frame.
    radius : float, mm
        Radius of the arc.
    psi0, psi1 : float, rad
        Polar angles of the start and the end about the centre, measured in the rack frame.

    Returns
    -------
    Arc
        The piece in the fixed frame.
    """
    c = from_rack_frame(np.array([center], dtype=float), pair.male_pitch_radius)[0]
    return Arc((float(c[0]), float(c[1])), radius, np.pi / 2 - psi0, np.pi / 2 - psi1)


@dataclass(frozen=True, eq=False)
class ScrewRotors:
    """A rotor pair with its rack chain and the generated male and female profiles.

    Both rotors are generated from the same rack chain by the envelope engine, so they are conjugate
    to each other (Rinder sec. 2.1).

    Parameters
    ----------
    pair : RotorPair
        Dimensions of the pair.
    rack : tuple of RackPiece
        One rack period p = 2 pi r1w / z1, in order of travel (+y in the fixed frame).
    family : str
        Name of the profile family (``"lysholm"``, ``"rack-involute"``, ...) or ``"rack"``.
    tolerance : float, mm
        Default chord tolerance of the sampled profiles.
    rack_loss : float, per cent
        Share of a measured lobe that has no rack point (its normal misses the pitch circle).
    accuracy : float, mm
        How far the profile the pair was generated from may lie from the true one: 0 for a design
        (exact curves), the estimated scatter and fit error for a profile given by points
        (:func:`rotorcad.rotor_points.pair_from_rotor_points`). The meshing analysis judges its
        defects to this accuracy (:attr:`rotorcad.meshing.MeshingAnalysis.accuracy`).
    tangent_accuracy : float, rad
        How far the tangent of the given profile's fit may turn from the true one: 0 for a design or
        exact points; for scattered points the accuracy over one point spacing (a flank's end tangent
        is fitted through points that each lie within that accuracy). The blow-hole's uncertainty
        follows from it (:attr:`rotorcad.meshing.MeshingAnalysis.blow_hole_uncertainty`).
    tip_corner_tangent_accuracy : float or None, rad
        How far a given male's fitted flank may turn at its tip corners, from the fitted spline's
        parametric bootstrap (:func:`rotorcad.measured.tangent.tip_tangent_accuracy`);
        the blow-hole's apex on the male tip circle moves with it. None: ``tangent_accuracy``.
    tangent_spread : (radii, turns) of two (m,) float arrays (mm, rad), optional
        Of exact points: each point's radius about its rotor's centre and how far the fit's tangent
        may turn there (:func:`rotorcad.measured.fit.tangent_spread`); the blow-hole's uncertainty
        takes it at its apex's radius. None for a design or scattered points.
    point_accuracy : float or None, mm
        The accuracy of one point of the given profile (2 sigma of its scatter, or the fit's
        residual): the meshing analysis judges the defects to it, since a defect is a local feature
        of the meshline. ``accuracy`` is the bound on the largest error over a whole lobe (95 %
        confidence), which the racks, the hob and the clearance state. None: ``accuracy``.
    point_spacing : float or None, mm
        The median spacing of the given points: a corner, a rounding or a curvature step between two
        of them is placed no better than that along the profile (the blow-hole's uncertainty,
        :func:`rotorcad.meshing.blow_hole_accuracy.spacing_uncertainty`). None for a design or a drawing.
    given_points : (n, 2) float array or None, mm
        The given rotor's points (every lobe, its own frame) and ``point_scatter`` (mm) their estimated
        scatter sigma: a model fitted to the points themselves, not to the smoothing spline, places the
        blow-hole's apex at a male tip rounding (:mod:`rotorcad.meshing.rounding_apex`). None for a design
        or a drawing.
    """

    pair: RotorPair
    rack: tuple[RackPiece, ...]
    family: str = "rack"
    tolerance: float = 1e-3
    rack_loss: float = 0.0  # per cent of a measured lobe without a rack point (normal misses the pitch circle)
    accuracy: float = 0.0  # mm: of the given profile (0 for a design's exact curves)
    tangent_accuracy: float = 0.0  # rad: of the given profile's tangents (0 for a design or exact points)
    tip_corner_tangent_accuracy: float | None = None  # rad: of a given male's tangent at its tip corners
    point_accuracy: float | None = None  # mm: of one point of the given profile (None: ``accuracy``)
    tangent_spread: tuple[np.ndarray, np.ndarray] | None = None  # exact points: (radii mm, turns rad) per point
    point_spacing: float | None = None  # mm: median spacing of the given points (None: a design or a drawing)
    given_points: np.ndarray | None = None  # mm: the given rotor's points, its own frame (None: a design or a drawing)
    point_scatter: float = 0.0  # mm: their estimated scatter sigma (0: exact points)

    @cached_property
    def male_pieces(self) -> list[tuple[str, Curve, RackPiece]]:
        """Generated male pieces of one lobe in counter-clockwise order.

        The male's polar angle grows with the rack position, so the order is the rack's. Each entry is
        (segment name, generated curve, rack piece); male corner paths are left out (they generate only
        the corner itself).
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
        """Generated female pieces of one lobe in counter-clockwise order, in the female's own frame.

        The female turns the other way, so the order is the rack's reversed. Each entry is (segment
        name, generated curve shifted by (-a, 0), rack piece); female corner paths are left out.
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
        cache = self.__dict__.setdefault("_lobes", {})  # one sampling per rotor and tolerance
        key = (id(pieces), tol)
        if key not in cache:
            side = Side.MALE if pieces is self.male_pieces else Side.FEMALE
            cache[key] = self._sample_lobe(pieces, tol, side)
        return cache[key]

    def _sample_lobe(self, pieces: list[tuple[str, Curve, RackPiece]], tol: float, side: Side) -> Profile:
        """Sample a lobe's pieces: those cut by a rack line, arc or point path in closed form, the others by the generic sampler.

        Parameters
        ----------
        pieces : list of (str, Curve, RackPiece)
            :attr:`male_pieces` or :attr:`female_pieces`.
        tol : float
            Largest chord error, mm.
        side : Side
            The rotor the pieces belong to.

        Returns
        -------
        Profile
            The open lobe; degenerate pieces (no or one point) are left out.
        """
        r1, a = self.pair.male_pitch_radius, self.pair.center_distance
        rotor = side.pick(self.pair.mesh.male, self.pair.mesh.female)
        segs = []
        for name, curve, piece in pieces:
            if abs(curve.s1 - curve.s0) < 1e-15:
                continue
            seg = cut_segment(name, curve, piece.curve, side, r1, a, tol, rotor)  # closed form (rotorcad.rotor_cut)
            if seg is None:
                seg = Segment.sample(name, curve, tol)
            if _degenerate(seg.points):  # none or one point
                continue
            segs.append(seg)
        return Profile(tuple(segs), closed=False)

    def male_lobe(self, tolerance: float | None = None) -> Profile:
        """Sample one male lobe (an open profile, counter-clockwise).

        Parameters
        ----------
        tolerance : float, mm, optional
            Chord tolerance; default the pair's ``tolerance``.

        Returns
        -------
        Profile
            The lobe's segments at male angle 0; degenerate (zero-length) pieces are left out.
        """
        return self._lobe(self.male_pieces, tolerance)

    def female_lobe(self, tolerance: float | None = None) -> Profile:
        """Sample one female lobe (an open profile, counter-clockwise, centre at the origin).

        Parameters
        ----------
        tolerance : float, mm, optional
            Chord tolerance; default the pair's ``tolerance``.

        Returns
        -------
        Profile
            The lobe's segments in the female's own frame; degenerate pieces are left out.
        """
        return self._lobe(self.female_pieces, tolerance)

    def male_outline(self, tolerance: float | None = None) -> Profile:
        """Sample the whole male outline, closed and counter-clockwise, at male angle 0.

        Parameters
        ----------
        tolerance : float, mm, optional
            Chord tolerance; default the pair's ``tolerance``.

        Returns
        -------
        Profile
            The lobe patterned z1 times about the origin.
        """
        return self.male_lobe(tolerance).patterned(self.pair.male_teeth)

    def female_outline(self, tolerance: float | None = None) -> Profile:
        """Sample the whole female outline in its own frame (centre at the origin) at the mesh position.

        Parameters
        ----------
        tolerance : float, mm, optional
            Chord tolerance; default the pair's ``tolerance``.

        Returns
        -------
        Profile
            The lobe patterned z2 times about the origin; shift by (a, 0) with :meth:`female_in_mesh`.
        """
        return self.female_lobe(tolerance).patterned(self.pair.female_teeth)

    def female_in_mesh(self, points: np.ndarray) -> np.ndarray:
        """Move female points from the female's own frame to the mesh frame.

        Parameters
        ----------
        points : (n, 2) float array, mm
            Points about the female centre at the origin.

        Returns
        -------
        (n, 2) float array, mm
            ``points + (a, 0)``: about O2 = (a, 0).
        """
        return np.asarray(points) + np.array([self.pair.center_distance, 0.0])

    def section(self, rotor: Side | str, tolerance: float | None = None, exact_tip: bool = False) -> shapely.Polygon:
        """Return a rotor's transverse section as a valid polygon in its own frame.

        The outline is clipped to the rotor's tip circle (generated curves may overshoot it by the
        rounding of the rack's corners); of several pieces the largest is kept. The clip is a 2048-gon
        inscribed in tip + 1 nm, whose chords sag 82 nm inside a 69.5 mm tip and replace the tip land;
        with ``exact_tip`` (the outlines ``rotor`` writes) a polygon within tip + 1 nm whose chords sag
        0.5 nm (:func:`_tip_clip`), so that the tip land stays as sampled at any chord tolerance (at a
        0.01 um chord the rack-involute male's sealing tip corner was written 72 nm inside the tip).

        Parameters
        ----------
        rotor : Side or {"male", "female"}
            Which rotor (the text is read as ``Side(rotor)``).
        tolerance : float, mm, optional
            Chord tolerance; default the pair's ``tolerance``.
        exact_tip : bool
            Clip within 0.5 nm of the tip circle instead of the 2048-gon.

        Returns
        -------
        shapely.Polygon
            The section, mm, centred at the origin.
        """
        side = Side(rotor)
        outline = self.male_outline(tolerance) if side is Side.MALE else self.female_outline(tolerance)
        tip = side.pick(self.pair.male_tip_radius, self.pair.female_tip_radius)
        poly = shapely.make_valid(shapely.Polygon(outline.points))
        disk = _tip_clip(tip) if exact_tip else shapely.Point(0.0, 0.0).buffer(tip + 1e-6, quad_segs=512)
        clipped = poly.intersection(disk)
        if isinstance(clipped, shapely.MultiPolygon | shapely.GeometryCollection):
            clipped = max((g for g in clipped.geoms if isinstance(g, shapely.Polygon)), key=lambda g: g.area)
        return clipped


def _tip_clip(tip: float) -> shapely.Polygon:
    """Return a polygon inside tip + 1 nm that holds every point within tip + 0.5 nm of the centre.

    A regular polygon of circumradius R = tip + 1 nm whose chords sag at most 0.5 nm: n = ceil(pi / acos(1 -
    0.5 nm / R)) corners (26 200 for a 69.5 mm tip; 5 ms of CPU for a section).

    Parameters
    ----------
    tip : float, mm
        Tip radius of the rotor.

    Returns
    -------
    shapely.Polygon
        Centred at the origin.
    """
    radius = tip + 1e-6
    n = max(64, int(np.ceil(np.pi / np.arccos(1.0 - 0.5e-6 / radius))))
    t = np.arange(n) * (2.0 * np.pi / n)
    return shapely.Polygon(np.column_stack([np.cos(t), np.sin(t)]) * radius)


def _degenerate(points: np.ndarray) -> bool:
    """Tell whether sampled points are none or one: ``np.ptp(points, axis=0).max() < 1e-9`` (mm).

    A piece whose ends lie 1e-9 mm apart or more in x or y spans at least that much: its range is not
    computed (the usual case).
    """
    if len(points) == 0:
        return True
    if abs(points[-1, 0] - points[0, 0]) >= 1e-9 or abs(points[-1, 1] - points[0, 1]) >= 1e-9:
        return False
    return bool(np.ptp(points, axis=0).max() < 1e-9)

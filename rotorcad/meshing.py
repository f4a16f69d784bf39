"""Meshing analysis of a screw-rotor pair after Rinder (*Sonderverzahnungen für Schraubenverdichterrotoren*).

Meshline, contact line (eq. 1), the kinematic rules of sec. 2.2.1 (cusp, jamming, slipping),
tightness and blow-hole (sec. 2.2.2), flute areas and displacement, sliding velocity and slip
(eqs. 2-4).

The meshline is the set of contact points in the fixed transverse frame: for a rack-generated
pair the rack touches both rotors at the same point, so it is the rack's contact locus. Only
contacts inside both bores (tip circles) count. Its tangent comes from an interpolating spline of
each piece over the generating parameter (never from point differences).

Blow-hole (projected definition, stated because the paper gives no formula): the curvilinear
triangle in the transverse plane between the meshline's end E nearest the housing cusp K and K
itself, bounded by the arc of the female tip circle from K to the radial projection of E on it, the
arc of the male tip circle from K to the radial projection of E on it, and the two radial pieces
to E. It is zero when the meshline runs into the cusp. The spatial (curvilinear) blow-hole is
:class:`rotorcad.blow_hole.SpatialBlowHole` (:attr:`MeshingAnalysis.spatial_blow_hole`).
"""

from __future__ import annotations

import itertools
from dataclasses import dataclass, field
from functools import cached_property

import numpy as np
import shapely

from rotorcad.blow_hole import SpatialBlowHole
from rotorcad.envelope import Generated
from rotorcad.geometry import cross, wrap_angle
from rotorcad.roles import Flank, PieceRole
from rotorcad.screw_rotors import ScrewRotors
from rotorcad.spline_slopes import spline_slopes


@dataclass(frozen=True, eq=False)
class MeshlinePiece:
    """Contact points of one rack piece, ordered along the piece.

    Parameters
    ----------
    name : str
        Name of the segment the piece generates on the male.
    kind : PieceRole
        What the rack piece does (a curve, or a corner's path).
    s : (n,) float array
        Parameter of the rack piece at each contact.
    t : (n,) float array, rad
        Male rotation angle at contact.
    points : (n, 2) float array, mm
        Contact points in the fixed frame (the meshline).
    tangents : (n, 2) float array
        Unit common tangent of the flanks at contact, fixed frame.
    male_name, female_name : str
        Names of the segments the piece generates on the male and on the female.
    roles : (n,) object array of Flank
        The lobe part of each point, read off the rack (:func:`flank_roles`).
    """

    name: str
    kind: PieceRole
    s: np.ndarray
    t: np.ndarray  # male rotation angle at contact (rad)
    points: np.ndarray  # fixed frame
    tangents: np.ndarray  # common tangent of the flanks at contact (unit)
    male_name: str = ""
    female_name: str = ""
    roles: np.ndarray = field(
        default_factory=lambda: np.zeros(0, dtype=object)
    )  # (n,) Flank per point: the lobe part (read off the rack)


_FLANKS = np.array(list(Flank), dtype=object)


def flank_roles(points: np.ndarray, tangents: np.ndarray, pitch_radius: float, scale: float) -> np.ndarray:
    """Return the lobe part of rack points (fixed frame at t = 0, pitch line x = r1w, motion +y).

    Parameters
    ----------
    points, tangents : (n, 2) float array
        Rack points (mm) and unit tangents along the chain (the direction of motion).
    pitch_radius : float, mm
        Male pitch radius r1w: the rack's pitch line.
    scale : float, mm
        A length of the pair for the flatness tolerance.

    Returns
    -------
    (n,) object array of Flank
        DRIVING where the rack rises towards the male tip (x grows along the chain), SEALING
        where it falls, TIP / ROOT on a land above / below the pitch line (Rinder sec. 1.2).
    """
    rise = tangents[:, 0]
    flat = np.abs(rise) <= 1e-9
    above = points[:, 0] > pitch_radius + 1e-9 * scale
    order = list(Flank)
    code = np.where(
        flat,
        np.where(above, order.index(Flank.TIP), order.index(Flank.ROOT)),
        np.where(rise > 0, order.index(Flank.DRIVING), order.index(Flank.SEALING)),
    )
    return _FLANKS[code]


@dataclass(frozen=True)
class FlankReport:
    """How one flank of the lobes meshes (Rinder sec. 1.2 and 2.2.1).

    Parameters
    ----------
    flank : Flank
        DRIVING or SEALING.
    meshline_length : float, mm
        Length of the flank's meshline inside both bores.
    geometric_share : float
        Part of that length (0 to 1) where the flanks touch with a common tangent (not a corner
        against a flank).
    defects : tuple of str
        Kinds of defect on the flank (``"cusp"``, ``"jamming"``); slipping is not counted.
    transverse_contact_ratio : float
        Male rotation over which the flank is in geometric contact, per angular pitch 2 pi / z1 (0
        where a circular flank centred on the pitch point touches at one instant only: Lysholm's
        "nur infinitesimale Stirnüberdeckung").
    """

    flank: Flank
    meshline_length: float
    geometric_share: float
    defects: tuple[str, ...]
    transverse_contact_ratio: float

    @property
    def runs_without_timing_gears(self) -> bool:
        """True when the flank has geometric contact everywhere and no cusp or jamming.

        Slipping is allowed: the helix carries the drive past it (Rinder sec. 2.2.1).
        """
        return self.meshline_length > 0 and self.geometric_share >= 1.0 - 1e-6 and not self.defects

    def as_dict(self) -> dict[str, object]:
        """Return the report as plain values (an entry of ``flanks`` in :meth:`MeshingAnalysis.summary`).

        Returns
        -------
        dict
            ``meshline_length`` (mm), ``geometric_contact`` (bool), ``geometric_share`` (0 to 1),
            ``defects`` (list of str), ``runs_without_timing_gears`` (bool),
            ``transverse_contact_ratio``.
        """
        return {
            "meshline_length": self.meshline_length,
            "geometric_contact": self.geometric_share >= 1.0 - 1e-6,
            "geometric_share": self.geometric_share,
            "defects": list(self.defects),
            "runs_without_timing_gears": self.runs_without_timing_gears,
            "transverse_contact_ratio": self.transverse_contact_ratio,
        }


def _covered(intervals: list[np.ndarray]) -> float:
    """Measure the union of the ranges of the given sets of angles (rad).

    The result is the rotation over which at least one of them is in contact. A piece touching at one
    instant adds nothing.
    """
    spans = sorted((float(t.min()), float(t.max())) for t in intervals if len(t))
    total, reach = 0.0, -np.inf
    for lo, hi in spans:
        lo = max(lo, reach)
        if hi > lo:
            total += hi - lo
            reach = hi
    return total


@dataclass(frozen=True)
class Defect:
    """A point (or stretch) of the meshline that breaks one of Rinder's rules (sec. 2.2.1).

    Parameters
    ----------
    kind : {"cusp", "jamming", "slipping"}
        Cusp: the meshline normal passes through O1 (male) or O2 (female); jamming: through the pitch
        point C; slipping: the meshline crosses O1O2 away from C.
    rotor : {"male", "female"}
        The rotor the rule names.
    x, y : float, mm
        Where it occurs, fixed frame.
    angle_deg : float, deg
        Male rotation angle at that contact.
    flank : str
        Name of the meshline piece (or, for slipping between pieces, which tip touches which root).
    point_generated : bool
        True when the whole piece has its normal through the centre (a point-generated flank).
    extent : float, mm
        Meshline length over which it holds (0: a single point).
    role : Flank, optional
        The lobe part where it occurs.
    """

    kind: str  # cusp, jamming, slipping
    rotor: str  # male, female
    x: float
    y: float
    angle_deg: float
    flank: str
    point_generated: bool = False
    extent: float = 0.0  # meshline length over which it holds (0: a single point)
    role: Flank | None = None  # the lobe part where it occurs

    def as_dict(self) -> dict[str, object]:
        """Return the defect as plain values (an entry of ``defects`` in :meth:`MeshingAnalysis.summary`).

        Returns
        -------
        dict
            The fields by name, ``role`` as ``flank_role`` (its text, or None).
        """
        return {
            "kind": self.kind,
            "rotor": self.rotor,
            "x": self.x,
            "y": self.y,
            "angle_deg": self.angle_deg,
            "flank": self.flank,
            "point_generated": self.point_generated,
            "extent": self.extent,
            "flank_role": None if self.role is None else str(self.role),
        }


@dataclass(frozen=True, eq=False)
class MeshingAnalysis:
    """Everything Rinder reads off a toothing, for one pair at a design speed.

    Parameters
    ----------
    rotors : ScrewRotors
        The generated pair.
    speed_rpm : float, rpm
        Male speed, for the sliding velocities (m/s).
    samples : int
        Samples along each rack piece.
    tolerance : float
        Relative tolerance of the cusp/jamming test of a whole piece (a point-generated flank).
    """

    rotors: ScrewRotors
    speed_rpm: float = 3000.0
    samples: int = 600
    tolerance: float = 1e-3

    # ---- meshline ------------------------------------------------------------------------
    @cached_property
    def pieces(self) -> list[MeshlinePiece]:
        """The meshline, piece by piece: the contacts of every rack piece inside both bores.

        A list of :class:`MeshlinePiece`; pieces with fewer than two contacts are left out.
        """
        pair = self.rotors.pair
        mesh = pair.mesh
        o2 = np.array([pair.center_distance, 0.0])
        out = []
        for piece in self.rotors.rack:
            gen = Generated(piece.curve, mesh.rack, mesh.female)
            s = np.linspace(piece.curve.s0, piece.curve.s1, self.samples)
            c = gen.contact(s)
            x = c.meshline
            inside = (np.hypot(*x.T) <= pair.male_tip_radius + 1e-3) & (np.hypot(*(x - o2).T) <= pair.female_tip_radius + 1e-3)
            ok = c.in_contact & inside & np.all(np.isfinite(x), axis=1)
            if ok.sum() < 2:
                continue
            rack_pts, tan = piece.curve.evaluate(s)
            tan_fixed = mesh.rack.vectors_to_fixed(tan, c.t)
            roles = flank_roles(rack_pts[ok], tan[ok], pair.male_pitch_radius, pair.center_distance)
            out.append(
                MeshlinePiece(
                    piece.male_name,
                    piece.kind,
                    s[ok],
                    c.t[ok],
                    x[ok],
                    tan_fixed[ok],
                    piece.male_name,
                    piece.female_name,
                    roles,
                )
            )
        return out

    @property
    def meshline(self) -> np.ndarray:
        """All contact points in the fixed frame, (n, 2) float, mm (piece after piece)."""
        return np.concatenate([p.points for p in self.pieces]) if self.pieces else np.zeros((0, 2))

    @property
    def contact_angles(self) -> np.ndarray:
        """Male rotation angle at every point of :attr:`meshline`, (n,) float, rad."""
        return np.concatenate([p.t for p in self.pieces]) if self.pieces else np.zeros(0)

    # ---- the rules of sec. 2.2.1 -----------------------------------------------------------
    @cached_property
    def defects(self) -> list[Defect]:
        """Cusps, jamming and slipping points on the meshline (Rinder sec. 2.2.1), a list of :class:`Defect`.

        The meshline normal (from a spline over each piece) through O1 or O2 is a cusp, through C
        jamming (except on a meshline arc about C, Rinder's exception); a crossing of O1O2 away from C
        is slipping, inside a piece or between two pieces.
        """
        pair = self.rotors.pair
        o1, o2 = np.zeros(2), np.array([pair.center_distance, 0.0])
        c = np.array([pair.male_pitch_radius, 0.0])
        tol = self.tolerance
        found: list[Defect] = []
        scale = pair.center_distance
        for piece in self.pieces:
            pts = piece.points
            length = float(np.hypot(*np.diff(pts, axis=0).T).sum())
            if len(pts) < 4 or length < 1e-6 * scale:
                continue  # the piece touches at a single point (a tip or root land): no meshline
            order = np.argsort(piece.s)
            tau = np.empty_like(pts)
            tau[order] = spline_slopes(piece.s[order], pts[order])  # the not-a-knot cubic spline's derivative
            tau /= np.linalg.norm(tau, axis=1, keepdims=True)
            # points on O1O2 are judged by the slipping rule alone (their normal along O1O2 passes
            # through O1, O2 and C at once), and C itself lies on every meshline
            judged = (np.abs(pts[:, 1]) > 1e-6 * scale) & (np.hypot(*(pts - c).T) > 1e-6 * scale)
            for q, kind, rotor in ((o1, "cusp", "male"), (o2, "cusp", "female"), (c, "jamming", "male")):
                f = np.einsum("ij,ij->i", q - pts, tau)  # zero: the meshline normal passes through q
                if np.median(np.abs(f)) < tol * max(1.0, np.abs(q - pts).max()):
                    if kind == "jamming":
                        continue  # meshline arc about C: both curvature centres in C (Rinder's exception)
                    mid = len(pts) // 2
                    found.append(
                        Defect(
                            kind,
                            rotor,
                            *map(float, pts[mid]),
                            float(np.degrees(piece.t[mid])),
                            piece.name,
                            True,
                            length,
                            piece.roles[mid],
                        )
                    )
                    continue
                for i in np.nonzero((np.sign(f[:-1]) * np.sign(f[1:]) < 0) & judged[:-1] & judged[1:])[0]:
                    w = f[i] / (f[i] - f[i + 1])
                    p = pts[i] + w * (pts[i + 1] - pts[i])
                    if np.hypot(*(p - q)) < 1e-3 * scale or abs(p[1]) < 1e-3 * scale:
                        continue  # through q itself (C lies on every meshline), or on O1O2 (slipping rule)
                    ang = piece.t[i] + w * (piece.t[i + 1] - piece.t[i])
                    role = piece.roles[i if w < 0.5 else i + 1]
                    found.append(Defect(kind, rotor, float(p[0]), float(p[1]), float(np.degrees(ang)), piece.name, role=role))
            # crossings of O1O2 inside the piece; a piece that only reaches O1O2 at an end is judged
            # with its neighbour (_slipping_between_pieces)
            y = pts[:, 1]
            side = np.nonzero(np.abs(y) > 1e-9 * scale)[0]
            for i, j in itertools.pairwise(side):
                if y[i] * y[j] < 0:
                    w = y[i] / (y[i] - y[j])
                    p = pts[i] + w * (pts[j] - pts[i])
                    if abs(p[0] - c[0]) > 1e-6 * scale:
                        ang = piece.t[i] + w * (piece.t[j] - piece.t[i])
                        role = piece.roles[i] if piece.roles[i] == piece.roles[j] else (Flank.TIP if p[0] > c[0] else Flank.ROOT)
                        found.append(
                            Defect("slipping", "male", float(p[0]), float(p[1]), float(np.degrees(ang)), piece.name, role=role)
                        )
        found.extend(self._slipping_between_pieces())
        return found

    def _slipping_between_pieces(self) -> list[Defect]:
        """Apply Rinder's slipping rule where the meshline crosses O1O2 between two pieces.

        That is where a tip touches the mate's root on O1O2 (a tip corner's path or a flank handing over
        to the next one), e.g. the female tip on the male root. The pieces are the meshline in order, and
        the next lobe's first piece follows the last; pieces lying on O1O2 (tip lands) hand over.
        """
        pair = self.rotors.pair
        scale = pair.center_distance
        c_x = pair.male_pitch_radius
        ends = []  # per piece: sign of y leaving its start, reaching its end, its end point, its angle
        for piece in self.pieces:
            y = piece.points[:, 1]
            side = np.nonzero(np.abs(y) > 1e-9 * scale)[0]
            if len(side) == 0:
                continue
            ends.append((np.sign(y[side[0]]), np.sign(y[side[-1]]), piece.points[-1], float(piece.t[-1])))
        found = []
        for (_, out_sign, p, t), (in_sign, _, _, _) in zip(ends, ends[1:] + ends[:1], strict=True):
            if abs(p[1]) <= 1e-6 * scale and out_sign * in_sign < 0 and abs(p[0] - c_x) > 1e-6 * scale:
                tip = p[0] > c_x
                land = "male tip on the female root" if tip else "female tip on the male root"
                role = Flank.TIP if tip else Flank.ROOT
                found.append(Defect("slipping", "male", float(p[0]), float(p[1]), float(np.degrees(t)), land, role=role))
        return found

    @property
    def point_generated_flanks(self) -> list[dict[str, str]]:
        """Flanks traced by a single corner of the mate (punkterzeugt).

        A list of dicts with ``rotor``, ``flank`` (segment name) and ``generated_by``.
        """
        out = []
        for piece in self.rotors.rack:
            if piece.kind is PieceRole.MALE_CORNER_PATH:
                out.append({"rotor": "female", "flank": piece.female_name, "generated_by": "male tip corner"})
            elif piece.kind is PieceRole.FEMALE_CORNER_PATH:
                out.append({"rotor": "male", "flank": piece.male_name, "generated_by": "female tip corner"})
        return out

    # ---- running without timing gears (1.2, 2.2.1) -----------------------------------------
    @cached_property
    def flanks(self) -> dict[Flank, FlankReport]:
        """Per flank (driving, sealing): geometric contact, defects, and the transverse contact ratio.

        A contact is geometric where a rack curve touches both rotors (a common tangent); a corner
        path's contacts are a corner against a flank (Rinder sec. 1.2: "eine Berührung ... im
        geometrischen Sinn mit gemeinsamen Tangenten ... ist in keinem Flankenteil gegeben").
        Contact pieces shorter than 1e-6 of the centre distance (a corner touching only at C) do not
        count. A dict Flank -> :class:`FlankReport`.
        """
        pair = self.rotors.pair
        pitch_angle = 2 * np.pi / pair.male_teeth
        out = {}
        for flank in (Flank.DRIVING, Flank.SEALING):
            total = geometric = 0.0
            t_geo: list[np.ndarray] = []
            for piece in self.pieces:
                mask = piece.roles == flank
                if mask.sum() < 2:
                    continue
                seg = np.hypot(*np.diff(piece.points, axis=0).T)
                length = float(seg[mask[:-1] & mask[1:]].sum())
                if length < 1e-6 * pair.center_distance:
                    continue
                total += length
                if piece.kind is PieceRole.CURVE:
                    geometric += length
                    t_geo.append(piece.t[mask])
            defects = tuple(sorted({d.kind for d in self.defects if d.role is flank and d.kind != "slipping"}))
            ratio = _covered(t_geo) / pitch_angle
            out[flank] = FlankReport(flank, total, geometric / total if total > 0 else 0.0, defects, ratio)
        return out

    @property
    def running_reasons(self) -> list[str]:
        """Why the pair does not run without timing gears, one sentence per flank (empty: it runs)."""
        out = []
        for flank, report in self.flanks.items():
            if report.runs_without_timing_gears:
                continue
            if report.meshline_length == 0:
                out.append(f"the {flank} flank has no contact inside the bores.")
                continue
            parts = []
            if report.geometric_share < 1e-6:
                parts.append("no geometric contact anywhere (a tip corner against the mate's flank, no common tangent)")
            elif report.geometric_share < 1.0 - 1e-6:
                parts.append(
                    f"geometric contact on {100 * report.geometric_share:.0f} % of its meshline only, the rest a tip "
                    "corner against the mate's flank"
                )
            for kind in report.defects:
                rotors = sorted({d.rotor for d in self.defects if d.role is flank and d.kind == kind})
                parts.append(f"{kind} on the {' and '.join(rotors)}")
            out.append(f"the {flank} flank: " + "; ".join(parts) + ".")
        return out

    # ---- tightness (2.2.2) -----------------------------------------------------------------
    @cached_property
    def cusp(self) -> np.ndarray:
        """The housing cusp that the meshline comes nearest, (2,) float, mm.

        The intersection of the tip circles above O1O2, or its mirror image below.
        """
        k = self.rotors.pair.housing_cusp
        pts = self.meshline
        lower = k * np.array([1.0, -1.0])
        return k if np.hypot(*(pts - k).T).min() <= np.hypot(*(pts - lower).T).min() else lower

    @cached_property
    def meshline_end(self) -> np.ndarray:
        """Meshline point nearest the housing cusp :attr:`cusp`, (2,) float, mm."""
        pts = self.meshline
        return pts[np.argmin(np.hypot(*(pts - self.cusp).T))]

    @property
    def meshline_closed(self) -> bool:
        """The meshline runs into the housing cusp (Rinder 2.2.2), within 1 micrometre."""
        return bool(np.hypot(*(self.meshline_end - self.cusp)) < 1e-3)

    @cached_property
    def blow_hole(self) -> shapely.Geometry:
        """Projected blow-hole polygon (see the module docstring)."""
        pair = self.rotors.pair
        k, e = self.cusp, self.meshline_end
        if np.hypot(*(e - k)) < 1e-3:
            return shapely.Polygon()
        o2 = np.array([pair.center_distance, 0.0])
        r1, r2 = pair.male_tip_radius, pair.female_tip_radius
        em = e / np.hypot(*e) * r1
        ef = o2 + (e - o2) / np.hypot(*(e - o2)) * r2

        def arc(center: np.ndarray, r: float, a: np.ndarray, b: np.ndarray) -> np.ndarray:
            t0 = np.arctan2(*(a - center)[::-1])
            t1 = np.arctan2(*(b - center)[::-1])
            t1 = wrap_angle(t1, t0)
            th = np.linspace(t0, t1, 200)
            return center + r * np.stack([np.cos(th), np.sin(th)], axis=1)

        ring = np.vstack([[e], arc(o2, r2, ef, k), arc(np.zeros(2), r1, k, em), [e]])
        return shapely.make_valid(shapely.Polygon(ring))

    @property
    def blow_hole_area(self) -> float:
        """Area of the projected blow-hole :attr:`blow_hole`, mm²."""
        return float(self.blow_hole.area)

    @cached_property
    def spatial_blow_hole(self) -> SpatialBlowHole:
        """The blow-hole triangle in 3D (:mod:`rotorcad.blow_hole`).

        Its apex is the meshline end nearest the cusp, at that point's height on the contact line (z
        measured as in :attr:`contact_line`, from the contact line's start).
        """
        pts = self.meshline
        i = int(np.argmin(np.hypot(*(pts - self.cusp).T)))
        z = self.rotors.pair.lead * self.contact_angles / (2 * np.pi)
        return SpatialBlowHole(self.rotors.pair, pts[i], float(z[i] - z.min()), self.cusp)

    # ---- contact line (eq. 1) ------------------------------------------------------------
    @cached_property
    def contact_line(self) -> np.ndarray:
        """3D contact (sealing) line, (n, 3) float, mm.

        Meshline points with z = h1 alpha / 2 pi (Rinder eq. 1, alpha the male rotation angle), shifted
        to start at z = 0 and cut at the rotor length.
        """
        pair = self.rotors.pair
        pts = self.meshline
        z = pair.lead * self.contact_angles / (2 * np.pi)
        line = np.column_stack([pts, z - z.min()])
        return line[line[:, 2] <= pair.length + 1e-9]

    @property
    def contact_line_length(self) -> float:
        """Length of the polyline :attr:`contact_line`, mm."""
        line = self.contact_line
        return float(np.linalg.norm(np.diff(line, axis=0), axis=1).sum())

    # ---- areas and displacement ------------------------------------------------------------
    @cached_property
    def sections(self) -> tuple[shapely.Polygon, shapely.Polygon]:
        """Transverse sections of the male and the female, each in its own frame (shapely polygons, mm)."""
        return self.rotors.section("male"), self.rotors.section("female")

    @property
    def male_flute_area(self) -> float:
        """Male flute area A1 = (bore area - rotor section) / z1, mm² (bore = male tip circle)."""
        pair = self.rotors.pair
        return float((np.pi * pair.male_tip_radius**2 - self.sections[0].area) / pair.male_teeth)

    @property
    def female_flute_area(self) -> float:
        """Female flute area A2 = (bore area - rotor section) / z2, mm² (bore = female tip circle)."""
        pair = self.rotors.pair
        return float((np.pi * pair.female_tip_radius**2 - self.sections[1].area) / pair.female_teeth)

    @property
    def displacement_per_rev(self) -> float:
        """Displacement per male revolution V = z1 L (A1 + A2), mm³."""
        pair = self.rotors.pair
        return pair.male_teeth * pair.length * (self.male_flute_area + self.female_flute_area)

    @property
    def area_utilisation(self) -> float:
        """Share of the two bores' area that is flute: (z1 A1 + z2 A2) / (pi r1t^2 + pi r2t^2)."""
        pair = self.rotors.pair
        flutes = pair.male_teeth * self.male_flute_area + pair.female_teeth * self.female_flute_area
        return float(flutes / (np.pi * (pair.male_tip_radius**2 + pair.female_tip_radius**2)))

    # ---- sliding velocity and slip (eqs. 2-4) ----------------------------------------------
    @cached_property
    def kinematics(self) -> dict[str, np.ndarray]:
        """Velocities and slips at every contact of :attr:`meshline` (Rinder eqs. 2-4).

        A dict of (n,) float arrays: ``v1t`` and ``v2t``, the rotors' velocities along the common
        tangent (m/s, eq. 2); ``sliding``, the sliding velocity v_g = v1t - v2t (m/s, eq. 3); ``slip_male`` and
        ``slip_female``, the slips v_g / v1t and v_g / v2t (eq. 4; infinite where a tangential velocity
        vanishes); ``angle_deg``, the male angle (deg); ``normal_check``, the cross product of the
        tangent with the relative velocity (zero: the law of gearing holds).
        """
        pair = self.rotors.pair
        w1 = self.speed_rpm * 2 * np.pi / 60.0
        w2 = -w1 * pair.male_teeth / pair.female_teeth
        pts = self.meshline
        tau = np.concatenate([p.tangents for p in self.pieces])
        o2 = np.array([pair.center_distance, 0.0])
        v1 = w1 * np.stack([-pts[:, 1], pts[:, 0]], axis=1)
        d2 = pts - o2
        v2 = w2 * np.stack([-d2[:, 1], d2[:, 0]], axis=1)
        v1t = np.einsum("ij,ij->i", v1, tau) * 1e-3
        v2t = np.einsum("ij,ij->i", v2, tau) * 1e-3
        vg = v1t - v2t
        with np.errstate(divide="ignore", invalid="ignore"):
            z1 = vg / v1t
            z2 = vg / v2t
        return {
            "v1t": v1t,
            "v2t": v2t,
            "sliding": vg,
            "slip_male": z1,
            "slip_female": z2,
            "angle_deg": np.degrees(self.contact_angles),
            "normal_check": cross(tau, v1 - v2),
        }

    def _max(self, key: str) -> dict[str, float]:
        """Return the largest magnitude of a :attr:`kinematics` entry and where it occurs.

        A dict with ``value``, ``x``, ``y`` (mm), ``angle_deg``, ``flank`` and both radii (mm).
        """
        k = self.kinematics
        v = np.abs(k[key])
        v = np.where(np.isfinite(v), v, -1.0)
        i = int(np.argmax(v))
        p = self.meshline[i]
        pair = self.rotors.pair
        roles = np.concatenate([piece.roles for piece in self.pieces])
        return {
            "value": float(v[i]),
            "x": float(p[0]),
            "y": float(p[1]),
            "angle_deg": float(k["angle_deg"][i]),
            "flank": str(roles[i]),
            "male_radius": float(np.hypot(*p)),
            "female_radius": float(np.hypot(p[0] - pair.center_distance, p[1])),
        }

    def summary(self) -> dict[str, object]:
        """Return the analysis as plain values (the figures of ``rotorcad rotor --json``).

        Returns
        -------
        dict
            Tooth counts, centre distance (mm), family, ``meshline_closed``, blow-hole areas (mm²)
            and the spatial blow-hole, contact-line length (mm), flute areas (mm²), displacement per
            revolution (mm³), area utilisation, the largest sliding velocity (m/s) and slips with where
            they occur, speed (rpm), defects, point-generated flanks, per-flank reports, whether the pair
            runs without timing gears and why not, wrap angle (deg).
        """
        pair = self.rotors.pair
        return {
            "male_teeth": pair.male_teeth,
            "female_teeth": pair.female_teeth,
            "center_distance": pair.center_distance,
            "family": self.rotors.family,
            "meshline_closed": self.meshline_closed,
            "blow_hole_area": self.blow_hole_area,
            "blow_hole_spatial": self.spatial_blow_hole.as_dict(),
            "contact_line_length": self.contact_line_length,
            "male_flute_area": self.male_flute_area,
            "female_flute_area": self.female_flute_area,
            "displacement_per_rev": self.displacement_per_rev,
            "area_utilisation": self.area_utilisation,
            "max_sliding_velocity": self._max("sliding")["value"],
            "max_sliding_at": self._max("sliding"),
            "max_slip_male": self._max("slip_male"),
            "max_slip_female": self._max("slip_female"),
            "speed_rpm": self.speed_rpm,
            "defects": [d.as_dict() for d in self.defects],
            "point_generated_flanks": self.point_generated_flanks,
            "flanks": {str(f): r.as_dict() for f, r in self.flanks.items()},
            "runs_without_timing_gears": all(r.runs_without_timing_gears for r in self.flanks.values()),
            "running_reasons": self.running_reasons,
            "wrap_angle_deg": float(np.degrees(pair.wrap_angle)),
        }

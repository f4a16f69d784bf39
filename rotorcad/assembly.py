"""Placed bodies: the rotors, gears and housing of an assembly in mesh, and the work their solids imply.

A :class:`PlacedBody` is one body as a file writer needs it: its transverse section turned to its
place in mesh (about its own axis), its helix (signed lead, length), the shift of its axis, and
the solid swept from it, made once, when a writer first asks for it (:meth:`PlacedBody.mesh`).
The writers (:mod:`exports.formats`) take bodies and know nothing of rotor pairs or gears.

Frames (ARCHITECTURE.md): the male (or the gear) about O1 = (0, 0), the female (or the mate) about
O2 = (a, 0); the female turned by -phi z1/z2 when the male is at phi, plus the assembly's phase.
The housing is a block minus the two bores of radii r_tip + radial clearance, and the bores alone.

The work limits (:mod:`rotorcad.work`) refuse a request before anything is swept:
:func:`check_solid_work` (the triangles of the two solids), :func:`check_section_work` (the points
of the sections an interference sweep turns). Refusals are :class:`rotorcad.errors.DesignError`
naming the parameter as the caller labels it.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field, replace
from enum import Enum
from typing import TYPE_CHECKING, NamedTuple

import numpy as np
import shapely
import shapely.affinity

from rotorcad.errors import DesignError
from rotorcad.geometry import rotate
from rotorcad.roles import Side
from rotorcad.triangle_mesh import TriangleMesh

if TYPE_CHECKING:
    from rotorcad.gear import GearPair, InvoluteGear
    from rotorcad.gears.features import MadeFeatures, SolidFeatures
    from rotorcad.gears.internal_gear import InternalGear
    from rotorcad.gears.internal_pair import InternalPair
    from rotorcad.profile import Profile
    from rotorcad.rotor_pair import RotorPair
    from rotorcad.screw_rotors import ScrewRotors


class BodyKind(Enum):
    """What a placed body is: a screw rotor, an involute gear, or the housing (block or bores)."""

    ROTOR = "rotor"
    GEAR = "gear"
    HOUSING = "housing"


class MeshedBody(NamedTuple):
    """A body's solid as meshed: what the mesh writers need."""

    mesh: TriangleMesh  # float64, placed (the female at the centre distance)
    volume: float  # mm^3, of the mesh
    tolerance: float  # mm, the surface tolerance it was made to


@dataclass(eq=False)
class PlacedBody:
    """One body of an assembly, placed in mesh.

    Parameters
    ----------
    name : str
        Its name in file names and in the rows of ``export --json`` (``male``, ``female``,
        ``gear``, ``mate``, ``housing``, ``bores``).
    kind : BodyKind
        A rotor, a gear or the housing.
    length : float, mm
        Length along the axis (the face width of a gear).
    shift : (float, float), mm
        Where its axis is: (0, 0) or (a, 0).
    section : shapely.Polygon, optional
        The transverse section, turned into mesh about its own axis (not shifted), sampled to
        ``section_tolerance``; None for the housing.
    section_tolerance : float, mm
        The chord tolerance of ``section`` (the tolerance of a drawing or points file of it).
    lead : float, mm
        Signed lead of the helix (> 0 right hand); inf for a straight (spur) body.
    turn : float, rad
        The turn that placed ``section`` (the exact outline is turned by it too).
    pitch_radius : float, mm
        Radius of its pitch circle (drawings); 0 for the housing.
    mark_size : float, mm
        Size of the drawings' marks.
    section_of : callable, optional
        ``section_of(chord)``: the section in its own frame (not turned) sampled to a chord
        tolerance (mm), for the work estimates.
    outline : callable, optional
        ``outline(chord)``: the exact outline sampled to a chord tolerance (mm), in its own frame,
        not turned (a :class:`rotorcad.profile.Profile`, for the exact STEP).
    step_chords : tuple of float
        Chords, in multiples of the STEP tolerance, at which the exact STEP's B-splines are
        sampled, tried in order until the faces are within the tolerance.
    solid : MeshedBody, optional
        The solid when it is made beforehand (the housing); else swept from ``section``.
    exact_volume : float, mm^3, optional
        The exact volume when known in closed form (the housing).
    housing : tuple, optional
        ``(center_distance, male bore radius, female bore radius, length, wall)`` of the housing
        (its exact STEP is made of a box and cylinders).
    outer_radius : float, mm, optional
        An internal gear (ring): ``outline`` is its toothed bore and the material lies between it
        and this circle; ``section`` holds the bore as its hole.
    on_swept : callable, optional
        Called when the solid has been swept (a progress bar's step).
    features : SolidFeatures, optional
        A gear's bore, keyway, hub and herringbone (:mod:`rotorcad.gears.features`): its meshes are
        :func:`rotorcad.gears.part_mesh.part_solid`, its exact STEP :mod:`exports.gear_step`.
    """

    name: str
    kind: BodyKind
    length: float
    shift: tuple[float, float] = (0.0, 0.0)
    section: shapely.Polygon | None = None
    section_tolerance: float = 0.0
    lead: float = float("inf")
    turn: float = 0.0
    pitch_radius: float = 0.0
    mark_size: float = 1.0
    section_of: Callable[[float], shapely.Polygon] | None = None
    outline: Callable[[float], Profile] | None = None
    step_chords: tuple[float, ...] = (10.0,)
    solid: MeshedBody | None = None
    exact_volume: float | None = None
    housing: tuple[float, float, float, float, float] | None = None
    outer_radius: float | None = None
    on_swept: Callable[[], None] | None = field(default=None, repr=False)
    features: SolidFeatures | None = None
    _swept: dict[float, MeshedBody] = field(default_factory=dict, repr=False)

    @property
    def swept(self) -> bool:
        """True when the body's solid is swept from its section (a rotor or a gear)."""
        return self.section is not None

    @property
    def section_volume(self) -> float:
        """Volume of the section times the length, mm³ (the helical solid's exact volume)."""
        if self.exact_volume is not None:
            return self.exact_volume
        return float(self.section.area * self.length) if self.section is not None else 0.0

    def placed_points(self) -> np.ndarray:
        """Return the section's outline placed in mesh, (n, 2) mm, without a repeated end point."""
        return np.asarray(self.section.exterior.coords)[:-1] + np.asarray(self.shift)

    def own_points(self) -> np.ndarray:
        """Return the section's outline about its own axis (turned, not shifted), (n, 2) mm."""
        return np.asarray(self.section.exterior.coords)[:-1]

    def _sweep(self, section: shapely.Polygon, tolerance: float):
        """Sweep ``section`` along the body's helix (a spur body as a helix of a very long lead)."""
        from rotorcad.solids import helical_solid  # manifold3d: only when a solid is swept

        if self.features is not None:  # a gear as a part: bore, keyway, hub, herringbone
            from rotorcad.gears.part_mesh import part_solid

            return part_solid(section, self.lead, self.length, tolerance, self.features)
        lead = self.lead if np.isfinite(self.lead) else 1e12 * self.length
        return helical_solid(section, lead, self.length, tolerance)

    def mesh(self, tolerance: float) -> MeshedBody:
        """Return the body's solid meshed to ``tolerance`` (mm) and placed; swept once, when first asked.

        The manifold is let go once meshed (some 150 MB a rotor).
        """
        if self.solid is not None:
            return self.solid
        if tolerance not in self._swept:
            made = self._sweep(self.section, tolerance)
            mesh = made.triangle_mesh
            mesh.apply_translation([*self.shift, 0.0])  # the mesh is the solid's own: moved, not copied
            self._swept[tolerance] = MeshedBody(mesh, made.volume, made.tolerance)
            if self.on_swept is not None:
                self.on_swept()
        return self._swept[tolerance]

    def estimated_triangles(self, tolerance: float) -> float:
        """Triangles of the body's mesh at ``tolerance`` (mm), estimated without sweeping it (:mod:`rotorcad.work`)."""
        from rotorcad.work import points_at, solid_triangles

        coarse = max(tolerance / 2, 0.05)
        section = self.section_of(coarse)
        r_max = float(np.hypot(*np.asarray(section.exterior.coords).T).max())
        return solid_triangles(points_at(section, coarse, tolerance / 2), self.lead, self.length, r_max, tolerance)

    def coarser_tolerance(self, tolerance: float, limit: int) -> float:
        """Return a tolerance, mm (3 digits, rounded up), whose mesh of the body has at most ``limit`` triangles.

        Found on the estimate (:func:`rotorcad.work.solid_triangles`, bisected from ``tolerance``),
        then checked by sweeping the body at it (coarse, so quick), coarsened until it does fit.
        """
        lo, hi = np.log(tolerance), np.log(max(tolerance, 1.0))
        for _ in range(30):
            mid = 0.5 * (lo + hi)
            lo, hi = (lo, mid) if self.estimated_triangles(float(np.exp(mid))) <= limit else (mid, hi)
        need = float(np.exp(hi))
        share = self.section_tolerance / tolerance  # the export at `need` samples its section so (a half, a quarter)
        for _ in range(20):
            digits = 10 ** (2 - np.floor(np.log10(need)))
            need = float(np.ceil(need * digits) / digits)
            if len(self._sweep(self.section_of(need * share), need).mesh.faces) <= limit:
                break
            need *= 1.2
        return need


def assemble(pair: RotorPair, center_distance: float | None, phase_deg: float, clearance: float) -> tuple[RotorPair, float]:
    """Return the pair as assembled and the female's extra turn (rad).

    The design's rotors at another centre distance (the bores follow).

    Parameters
    ----------
    pair : RotorPair
        The pair as designed.
    center_distance : float or None, mm
        Assembly centre distance; None: the design's.
    phase_deg : float, deg
        The female turned by this angle from its mesh position.
    clearance : float, mm
        The housing's radial clearance.

    Raises
    ------
    DesignError
        ``radial_clearance`` below 0, ``phase_deg`` beyond ±360, or a ``center_distance`` at which
        the rotors do not fit (at most the larger tip radius, or beyond the sum of the tip radii).
    """
    if not (np.isfinite(clearance) and clearance >= 0):
        raise DesignError("radial_clearance", "a clearance of at least 0 mm", clearance)
    if not np.isfinite(phase_deg) or abs(phase_deg) > 360:
        raise DesignError("phase_deg", "an angle from -360 to 360 deg", phase_deg)
    if center_distance is None:
        return pair, float(np.radians(phase_deg))
    low = max(pair.male_tip_radius, pair.female_tip_radius)
    high = pair.male_tip_radius + pair.female_tip_radius
    if not (np.isfinite(center_distance) and low < center_distance <= high):
        raise DesignError(
            "center_distance",
            f"more than the larger tip radius {low:g} mm and at most the sum of the tip radii {high:g} mm",
            center_distance,
        )
    return replace(pair, center_distance=float(center_distance), strict=False), float(np.radians(phase_deg))


def rotor_bodies(rotors: ScrewRotors, pair: RotorPair, angle: float, phase: float, tolerance: float) -> list[PlacedBody]:
    """Return the male and the female placed in mesh.

    Parameters
    ----------
    rotors : ScrewRotors
        The rotors as designed.
    pair : RotorPair
        The pair as assembled (:func:`assemble`).
    angle : float, rad
        Male angle; the female at ``-angle z1/z2 + phase``.
    phase : float, rad
        The female's extra turn.
    tolerance : float, mm
        Surface tolerance; the sections are sampled to half of it.
    """
    lead = pair.lead if pair.hand == "right" else -pair.lead
    turn = {Side.MALE: angle, Side.FEMALE: -angle * pair.male_teeth / pair.female_teeth + phase}
    return [
        PlacedBody(
            name=side.value,
            kind=BodyKind.ROTOR,
            length=float(pair.length),
            shift=side.pick((0.0, 0.0), (float(pair.center_distance), 0.0)),
            section=shapely.affinity.rotate(rotors.section(side, tolerance / 2), turn[side], origin=(0, 0), use_radians=True),
            section_tolerance=tolerance / 2,
            lead=float(side.pick(lead, -np.sign(lead) * pair.female_lead)),
            turn=float(turn[side]),
            pitch_radius=float(side.pick(pair.male_pitch_radius, pair.female_pitch_radius)),
            mark_size=0.05 * pair.male_tip_radius,
            section_of=lambda chord, s=side: rotors.section(s, chord),
            outline=side.pick(rotors.male_outline, rotors.female_outline),
        )
        for side in Side
    ]


def gear_lead(g: InvoluteGear) -> float:
    """Return the lead of the gear's helix: 2 pi r / tan(beta) at the pitch radius.

    Parameters
    ----------
    g : InvoluteGear
        The gear.

    Returns
    -------
    float, mm
        Signed lead (> 0 right hand); inf for a spur gear.
    """
    beta = g.helix_angle
    return float("inf") if abs(beta) < 1e-12 else float(2 * np.pi * g.pitch_radius / np.tan(beta))


def gear_bodies(
    gear: InvoluteGear, pair: GearPair | None, width: float, tolerance: float, features: MadeFeatures | None = None
) -> list[PlacedBody]:
    """Return the gear (and its mate in mesh at the working centre distance) as placed bodies.

    ``features`` (the gear's tip corners, bore, keyway, hub, herringbone) make the gear a part: its
    section the outline with broken tip corners, its volume the closed form of
    :meth:`rotorcad.gears.features.SolidFeatures.volume`; a herringbone gear's mate is one too.

    The mate is turned by pi + pi/z2 (a tooth space of the mate faces the gear's tooth on the line
    of centres) and swept with the opposite hand and its own lead, -h1 z2/z1. The sections are
    sampled to a quarter of ``tolerance``; the exact STEP tries its B-splines at 10, 1 and 0.1
    times its tolerance in chord (a large gear's slowly curved flanks need the finer ones).
    """
    lead = gear_lead(gear)
    bodies = [("gear", gear, lead, (0.0, 0.0), 0.0)]
    if pair is not None:
        mate = pair.mate
        lead2 = -lead * mate.teeth / gear.teeth if np.isfinite(lead) else float("inf")
        bodies.append(("mate", mate, lead2, (float(pair.working_center_distance), 0.0), np.pi + np.pi / mate.teeth))
    placed = [
        PlacedBody(
            name=name,
            kind=BodyKind.GEAR,
            length=float(width),
            shift=shift,
            section=shapely.Polygon(rotate(g.outline(tolerance / 4).points, turn)),
            section_tolerance=tolerance / 4,
            lead=float(lead),
            turn=float(turn),
            pitch_radius=float(g.pitch_radius),
            mark_size=float(g.module),
            section_of=lambda chord, g=g: shapely.Polygon(g.outline(chord).points),
            outline=g.outline,
            step_chords=(10.0, 1.0, 0.1),
        )
        for name, g, lead, shift, turn in bodies
    ]
    if features is not None:
        placed = [_as_part(placed[0], features), *(_as_part(b, None, features.solid.herringbone) for b in placed[1:])]
    return placed


def _as_part(body: PlacedBody, features: MadeFeatures | None, herringbone: bool = False) -> PlacedBody:
    """Return a gear body as a part: the gear with its features, or the mate of a herringbone gear."""
    from rotorcad.gears.features import SolidFeatures

    if features is None:
        if not herringbone:
            return body
        solid = SolidFeatures(herringbone=True, turn=body.turn)
        return replace(body, features=solid, exact_volume=solid.volume(body.section.area, body.length))
    tol = body.section_tolerance
    section = shapely.Polygon(rotate(features.outline(tol).points, body.turn))
    solid = replace(features.solid, turn=body.turn)
    return replace(
        body,
        section=section,
        section_of=lambda chord: shapely.Polygon(features.outline(chord).points),
        outline=features.outline,
        features=solid,
        exact_volume=solid.volume(shapely.Polygon(features.outline(tol / 10).points).area, body.length),
    )


def internal_gear_bodies(ring: InternalGear, pair: InternalPair | None, width: float, tolerance: float) -> list[PlacedBody]:
    """Return an internal gear (a ring with its toothed bore) and its pinion in mesh as placed bodies.

    The ring about the origin, its section the circle of the outer radius with the bore as a hole;
    the pinion about (a_w, 0), not turned (its tooth 0 stands in the ring's space 0 on the +x axis),
    swept with the same hand as the ring (an internal pair) and the lead h2 z1 / z2.
    """
    lead = gear_lead(ring)
    # chords of the outer circle within a quarter of the tolerance: sagitta R (1 - cos(pi / n))
    n = max(720, int(np.ceil(np.pi / np.arccos(1.0 - tolerance / 4 / ring.outer_radius))))
    angles = 2 * np.pi * np.arange(n) / n
    outer = ring.outer_radius * np.column_stack([np.cos(angles), np.sin(angles)])

    def ring_section(chord: float) -> shapely.Polygon:
        return shapely.Polygon(outer, [ring.outline(chord).points[::-1]])

    bodies = [
        PlacedBody(
            name="gear",
            kind=BodyKind.GEAR,
            length=float(width),
            section=ring_section(tolerance / 4),
            section_tolerance=tolerance / 4,
            lead=float(lead),
            pitch_radius=float(ring.pitch_radius),
            mark_size=float(ring.module),
            section_of=ring_section,
            outline=ring.outline,
            step_chords=(10.0, 1.0, 0.1),
            outer_radius=float(ring.outer_radius),
        )
    ]
    if pair is not None:
        p = pair.pinion
        (pinion,) = gear_bodies(p, None, width, tolerance)  # its lead 2 pi r1 / tan(beta) = h2 z1 / z2, the same hand
        bodies.append(replace(pinion, name="mate", shift=(float(pair.working_center_distance), 0.0)))
    return bodies


def housing_volumes(pair: RotorPair, clearance: float, wall: float | None = None) -> dict[str, float]:
    """Return the closed-form volumes (mm³) of the bores and of the block minus the bores.

    The bores are two intersecting circles (the union's area from the lens of their overlap), times
    the length; ``wall`` (mm) defaults to :data:`rotorcad.solids.HOUSING_WALL`.
    """
    from rotorcad.solids import HOUSING_WALL

    wall = HOUSING_WALL if wall is None else wall
    a, r1, r2 = pair.center_distance, pair.male_tip_radius + clearance, pair.female_tip_radius + clearance
    lens = r1**2 * np.arccos((a**2 + r1**2 - r2**2) / (2 * a * r1)) + r2**2 * np.arccos((a**2 + r2**2 - r1**2) / (2 * a * r2))
    lens -= 0.5 * np.sqrt((-a + r1 + r2) * (a + r1 - r2) * (a - r1 + r2) * (a + r1 + r2))
    bores = (np.pi * (r1**2 + r2**2) - lens) * pair.length
    half = max(r1, r2) + wall
    block = (a + r1 + r2 + 2 * wall) * 2 * half * pair.length
    return {"bores": float(bores), "housing": float(block - bores)}


def housing_bodies(pair: RotorPair, clearance: float, tolerance: float) -> list[PlacedBody]:
    """Return the housing (block minus the bores) and the bores as placed bodies.

    Their meshes are made here (manifold3d), with enough segments on the bores for their chords to
    sag at most ``tolerance`` (at least 360); each mesh's tolerance is that sag.
    """
    from rotorcad.solids import HOUSING_WALL, housing_solids

    r1, r2 = pair.male_tip_radius + clearance, pair.female_tip_radius + clearance
    segments = max(360, int(2 * np.pi / np.sqrt(8 * tolerance / pair.female_tip_radius)))
    block, bores = housing_solids(pair.center_distance, r1, r2, pair.length, wall=HOUSING_WALL, segments=segments)
    sag = float(r2 * (1 - np.cos(np.pi / segments)))  # chords of the bores
    exact = housing_volumes(pair, clearance)
    bodies = []
    for name, manifold in (("housing", block), ("bores", bores)):
        m = manifold.to_mesh64()
        mesh = TriangleMesh(np.asarray(m.vert_properties)[:, :3], np.asarray(m.tri_verts))
        bodies.append(
            PlacedBody(
                name=name,
                kind=BodyKind.HOUSING,
                length=float(pair.length),
                solid=MeshedBody(mesh, float(manifold.volume()), sag),
                exact_volume=exact[name],
                housing=(float(pair.center_distance), float(r1), float(r2), float(pair.length), HOUSING_WALL),
            )
        )
    return bodies


def check_solid_work(rotors: ScrewRotors, tolerance: float, label: str) -> None:
    """Refuse a request whose two solids would have more than :data:`rotorcad.work.MAX_TRIANGLES` triangles.

    Refused before any solid is swept, naming the smallest tolerance that fits (or the lead or the
    size when no tolerance up to 1 mm does).

    Parameters
    ----------
    rotors : ScrewRotors
        The rotors.
    tolerance : float, mm
        Surface tolerance asked.
    label : str
        How the tolerance was given (``--tolerance``, ``[export] tolerance``), for the sentence.

    Raises
    ------
    DesignError
        Naming ``label``, ``[pair] lead`` or ``[pair] center_distance``.
    """
    from rotorcad.work import MAX_TRIANGLES, points_at, solid_triangles

    pair = rotors.pair
    coarse = max(tolerance / 2, 0.05)
    total = 0.0
    for side, lead in ((Side.MALE, pair.lead), (Side.FEMALE, pair.female_lead)):
        section = rotors.section(side, coarse)
        r_max = float(np.hypot(*np.asarray(section.exterior.coords).T).max())
        total += solid_triangles(points_at(section, coarse, tolerance / 2), lead, pair.length, r_max, tolerance)
    if total <= MAX_TRIANGLES:
        return
    need = tolerance * total / MAX_TRIANGLES * 1.05  # triangles grow like 1/tolerance
    what = f"the solids would have {total / 1e6:.3g} million triangles, at most {MAX_TRIANGLES / 1e6:g} million fit in memory"
    if need <= 1.0:
        raise DesignError(label, f"at least {need:.2g} mm for this design", f"{tolerance:g}: {what}")
    if pair.length / pair.lead > 2:
        lead = pair.lead * total * tolerance / MAX_TRIANGLES * 1.05
        raise DesignError(
            "[pair] lead",
            f"at least {lead:.3g} mm for solids of this length",
            f"{pair.lead:g}: {what} even at a tolerance of 1 mm",
        )
    raise DesignError(
        "[pair] center_distance and the radii",
        "smaller for solids",
        f"{pair.center_distance:g} mm: {what} even at a tolerance of 1 mm",
    )


def check_section_work(rotors: ScrewRotors, tolerance: float, label: str) -> None:
    """Refuse an interference sweep whose sections would have more than :data:`rotorcad.work.MAX_SECTION_POINTS` points.

    Raises
    ------
    DesignError
        Naming ``label`` and the smallest tolerance that fits (points grow like 1/sqrt(tolerance)).
    """
    from rotorcad.work import MAX_SECTION_POINTS, points_at

    coarse = max(tolerance / 2, 0.05)
    points = sum(points_at(rotors.section(side, coarse), coarse, tolerance / 2) for side in Side)
    if points > MAX_SECTION_POINTS:
        need = tolerance * (points / MAX_SECTION_POINTS) ** 2 * 1.05
        raise DesignError(
            label,
            f"at least {need:.2g} mm for this design",
            f"{tolerance:g}: the sections would have {points:.3g} points, at most {MAX_SECTION_POINTS} can be turned "
            "through the sweep",
        )


__all__ = [
    "BodyKind",
    "MeshedBody",
    "PlacedBody",
    "assemble",
    "check_section_work",
    "check_solid_work",
    "gear_bodies",
    "gear_lead",
    "housing_bodies",
    "housing_volumes",
    "rotor_bodies",
]

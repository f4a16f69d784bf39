"""The working chamber of a screw compressor from the rotors themselves.

Its transverse area and the pressure force it puts on each rotor, over one working cycle; its
volume curve.

Conventions (documented choices; Rinder & Deix do not fix them in the text that survives):

- The male turns counter-clockwise in the rotors' frame (male at the origin, female at (a, 0)),
  the female clockwise (phi2 = -phi1 z1/z2, CONTRACT.md). The lobes then pass the mesh from y < 0 to
  y > 0: below the line of centres the lobes enter each other's flutes (the closing side, joined to
  the discharge), above it they leave them (the opening side, joined to the suction).
- A male flute's *phase* psi is the male angle of its bisector (psi = 0: the flute points at O2,
  the female lobe fully inside it). One working cycle of the flute runs psi from 0 (it leaves the
  mesh) to 2 pi (it is filled again by the next female lobe).
- z is measured from the discharge end face. Along z the flute is turned ahead in the direction of
  rotation by 2 pi z / h (h the male lead), so a chamber's sections at the suction end are further
  in their cycle: the suction end opens first and closes first. With a right-hand male that puts
  the discharge end at Z = 0 of the solids (``rotorcad.solids``), with a left-hand one at Z = L.

In a transverse section at phase psi the gas space is the two bores (tip circles) minus both
rotors, shrunk by ``GAP`` so that parts that touch only at a contact point or along a tip land come
apart. The chamber's part of it is what lies in the flute's sector (between its two bounding tips,
inside the male tip circle) or in the sector of the female flute that meshes with it, in pieces
not joined to the cusp on the other side of the mesh (the upper cusp while the flute closes,
psi > pi; the lower one while it opens). Its area is a(psi); the force of a unit overpressure on the
male is the integral of the outward normal of that gas space over its edges on the male's outline.
For a flute open from tip to tip that integral is the chord P1P2 turned by 90 degrees, the load of
Rinder & Deix eq. (5); where the chamber ends at the contact line or a lobe of the mate fills part of
the flute it is shorter (eq. 5's full chord puts a gas force 1.35 (male) and 1.46 (female) times the
real chamber's on the rotors of samples/srm_asymmetric_5_6.toml at their worst angle; the female's force
there moves by several per cent within 0.01 deg, where a chamber opens to discharge). Eq. (5) as
printed, the full chord in every section, is :func:`chord_table`.

The chamber whose flute is at phase psi0 at the discharge end holds the sections with phases
psi0 + 2 pi z / h inside [0, 2 pi): its volume is V(psi0) = h / (2 pi) * integral of a over that
window. It opens at the suction end (psi0 = -wrap) and ends at psi0 = 2 pi; the cycle lasts
2 pi + wrap of male rotation.
"""

from __future__ import annotations

import dataclasses
import threading
from collections import OrderedDict
from dataclasses import dataclass

import numpy as np
import shapely

from rotorcad.errors import DesignError
from rotorcad.roles import Side

GAP = 1e-3  # mm: the gas space is shrunk by this to part pieces that touch at a point or along a tip land (area ~0.03 % less)
SEAL = 0.01  # mm: a gap narrower than twice this seals (the sections' chords and a contact's neighbourhood)
RECENT_TABLES = 4  # chamber tables kept for the same sections asked again (a second model, another command in a process)


@dataclass(frozen=True)
class ChamberTable:
    """The chamber of one male flute over its working cycle, in transverse sections.

    Attributes
    ----------
    phase : (m,) float, rad
        Flute phases psi, equally spaced; each row holds for [psi, psi + step).
    area : (m,) float, mm^2
        a(psi): the chamber's area in a section at that phase.
    male_force, female_force : (m, 2) float, mm
        Force per unit length and unit overpressure (N/mm per N/mm^2) on each rotor, in the
        rotors' frame at that phase.
    male_flute_area, female_flute_area : float, mm^2
        Area between a rotor and its tip circle over one flute (pi r_tip^2 - A) / z.
    lead : float, mm
        Male lead h.
    length : float, mm
        Rotor length L.
    """

    phase: np.ndarray
    area: np.ndarray
    male_force: np.ndarray
    female_force: np.ndarray
    male_flute_area: float
    female_flute_area: float
    lead: float
    length: float

    @property
    def wrap(self) -> float:
        """Male wrap angle 2 pi L / h (rad)."""
        return 2 * np.pi * self.length / self.lead

    @property
    def step(self) -> float:
        """Phase step (rad)."""
        return float(self.phase[1] - self.phase[0])

    @property
    def span(self) -> tuple[float, float]:
        """First and last phase (rad) at which the chamber has gas in a section: [start, stop)."""
        return float(self.phase[0]), float(self.phase[-1] + self.step)

    @property
    def cycle(self) -> tuple[float, float]:
        """Discharge-end phases psi0 (rad) from the chamber's opening at the suction end to its end."""
        start, stop = self.span
        return start - self.wrap, stop

    def volume(self, psi0: np.ndarray) -> np.ndarray:
        """V(psi0): the chamber's volume (mm^3) with its flute at phase psi0 at the discharge end.

        Parameters
        ----------
        psi0 : (k,) float, rad
            Over :attr:`cycle` (before and after it the volume is 0).

        Returns
        -------
        (k,) float, mm^3
            h / (2 pi) times the integral of a(psi) over [psi0, psi0 + wrap] within the span (each
            table value holds over [phase, phase + step)).
        """
        nodes = np.append(self.phase, self.phase[-1] + self.step)
        cum = np.concatenate([[0.0], np.cumsum(self.area * self.step)])
        start, stop = self.span
        psi0 = np.asarray(psi0, dtype=float)
        lo = np.clip(psi0, start, stop)
        hi = np.clip(psi0 + self.wrap, start, stop)
        return self.lead / (2 * np.pi) * (np.interp(hi, nodes, cum) - np.interp(lo, nodes, cum))

    def force_at(self, psi: np.ndarray, rotor: Side) -> np.ndarray:
        """Return the force of a unit overpressure per unit length on a rotor at flute phases.

        Linear between the table's phases; zero outside :attr:`span` (those sections belong to other
        chambers).

        Parameters
        ----------
        psi : float array, rad
            Flute phases, any shape.
        rotor : Side
            Which rotor.

        Returns
        -------
        (..., 2) float array, mm
            Force per unit length and unit overpressure (N/mm per N/mm²), x and y.
        """
        table = rotor.pick(self.male_force, self.female_force)
        psi = np.asarray(psi, dtype=float)
        start, stop = self.span
        inside = (psi >= start) & (psi < stop)
        x = np.clip((psi - start) / self.step, 0.0, len(self.phase) - 1.0)
        i = np.minimum(x.astype(int), len(self.phase) - 2)
        t = (x - i)[..., None]
        return np.where(inside[..., None], (1.0 - t) * table[i] + t * table[i + 1], 0.0)


def _sector(center: tuple[float, float], radius: float, start: float, stop: float) -> shapely.Polygon:
    """Return the wedge about ``center`` from angle ``start`` to ``stop`` (rad), reaching beyond the tip circle ``radius``.

    Cut to the gas of a bore (:attr:`_Section.male_gas`, :attr:`_Section.female_gas`) it is the
    flute's circular sector of that gas.
    """
    t = np.linspace(start, stop, 9)
    r = 1.5 * radius / np.cos((stop - start) / 16)  # beyond the tip circle between the 9 rays
    pts = np.vstack([[center], np.c_[center[0] + r * np.cos(t), center[1] + r * np.sin(t)]])
    return shapely.Polygon(pts)


def flute_cycles(male_teeth: int, female_teeth: int) -> tuple[tuple[float, float], tuple[float, float]]:
    """Return the phase windows (rad) over which the male flute and its female flute belong to the chamber.

    Parameters
    ----------
    male_teeth, female_teeth : int
        z1, z2.

    Returns
    -------
    male, female : tuple of (float, float), rad
        [start, stop) in male flute phase psi: the male flute's cycle is [0, 2 pi); the female flute's
        lasts 2 pi z2 / z1 of male rotation and ends half a male pitch after the male flute's.
    """
    pitch1 = 2 * np.pi / male_teeth
    return (0.0, 2 * np.pi), (2 * np.pi + pitch1 / 2 - 2 * np.pi * female_teeth / male_teeth, 2 * np.pi + pitch1 / 2)


def female_flute_angle(male_teeth: int, female_teeth: int, psi: np.ndarray) -> np.ndarray:
    """Return the direction (rad, about O2 in the rotors' frame) of the bisector of the female flute of phase psi.

    The female flute that closes with the male flute at phase psi (see :func:`_female_sector`).

    Parameters
    ----------
    male_teeth, female_teeth : int
        z1, z2.
    psi : float array, rad
        Male flute phases, any shape.

    Returns
    -------
    float array, rad
        Of the shape of ``psi``.
    """
    pitch2 = 2 * np.pi / female_teeth
    return np.pi + (male_teeth + 0.5) * pitch2 - np.asarray(psi, dtype=float) * male_teeth / female_teeth


def chord_table(
    table: ChamberTable, male_teeth: int, female_teeth: int, male_tip_radius: float, female_tip_radius: float
) -> ChamberTable:
    """Return the chamber table with the forces of Rinder & Deix eq. (5): the flute's chord instead of its boundary.

    Rinder & Deix sec. 3.1, eq. (5): the resultant of the overpressure p in a flute is
    q = l_s p with the chord l_s = d_K sin(pi / z_L) between the two tips P1, P2 bounding the flute
    (d_K the rotor's tip diameter, z_L its number of lobes), normal to the chord through its middle,
    pushing the rotor away from the flute; eq. (6) turns it with the helix. "Deviations from the chord
    length in the meshing region remain unconsidered": the full chord acts in every section in which the
    flute belongs to the chamber (its cycle, :func:`flute_cycles`), also where a lobe of the mate fills
    part of it. Volume and area (hence the pressure curve) are the real chamber's.

    Parameters
    ----------
    table : ChamberTable
        The chamber of the real rotors (:func:`chamber_table`).
    male_teeth, female_teeth : int
        z1, z2.
    male_tip_radius, female_tip_radius : float, mm
        d_K / 2 of each rotor.

    Returns
    -------
    ChamberTable
        The same phases, areas and volumes; ``male_force`` = -l_s1 (cos psi, sin psi) over the male
        flute's cycle, ``female_force`` = -l_s2 (cos c, sin c) over the female flute's, c the female
        flute's bisector (:func:`female_flute_angle`); 0 elsewhere. mm (N/mm per N/mm^2).
    """
    (m0, m1), (f0, f1) = flute_cycles(male_teeth, female_teeth)
    psi = table.phase
    chord1 = 2 * male_tip_radius * np.sin(np.pi / male_teeth)
    chord2 = 2 * female_tip_radius * np.sin(np.pi / female_teeth)
    inside1 = ((psi >= m0) & (psi < m1))[:, None]
    inside2 = ((psi >= f0) & (psi < f1))[:, None]
    c = female_flute_angle(male_teeth, female_teeth, psi)
    male = np.where(inside1, -chord1 * np.c_[np.cos(psi), np.sin(psi)], 0.0)
    female = np.where(inside2, -chord2 * np.c_[np.cos(c), np.sin(c)], 0.0)
    return dataclasses.replace(table, male_force=male, female_force=female)


def _female_sector(a: float, r2: float, z1: int, z2: int, psi: float) -> shapely.Polygon:
    """Wedge of the female flute that closes with the male flute at phase ``psi`` (:func:`_sector`).

    At psi = 2 pi the male flute holds the female lobe at angle pi about O2; the female flute that
    reaches the mesh with it lies just below that lobe (it is filled half a male pitch later).
    """
    pitch2 = 2 * np.pi / z2
    centre = float(female_flute_angle(z1, z2, np.asarray(psi)))
    return _sector((a, 0.0), r2, centre - pitch2 / 2, centre + pitch2 / 2)


def _band(rotor: shapely.Polygon) -> shapely.Geometry:
    """Return a thin band about a rotor's outline, from GAP inside it to 3 GAP outside (the gas edges on it lie GAP out)."""
    return shapely.difference(rotor.buffer(3 * GAP, quad_segs=2), rotor.buffer(-GAP, quad_segs=2))


@dataclass(frozen=True)
class _Section:
    """The gas space of one transverse section, split by bore, and what it touches."""

    male_gas: shapely.Geometry  # the gas in the male bore
    female_gas: shapely.Geometry  # the gas in the female bore outside the male's (the lens counts with the male)
    to_upper: shapely.Geometry  # the gas joined to the upper (opening-side) cusp
    to_lower: shapely.Geometry
    male_near: shapely.Geometry  # a thin band about the male's outline (prepared)
    female_near: shapely.Geometry

    @classmethod
    def at(
        cls,
        rotors: tuple[shapely.Polygon, shapely.Polygon],
        bands: tuple[shapely.Geometry, shapely.Geometry],
        z1: int,
        z2: int,
        a: float,
        bores: tuple[shapely.Geometry, shapely.Geometry, shapely.Geometry],
        cusps: tuple[shapely.Point, shapely.Point],
        psi: float,
    ) -> _Section:
        """Build the section at male angle ``psi`` (rad).

        ``rotors`` and their ``bands`` (:func:`_band`) in their own frames, as the male and the female;
        ``bores``: both bores, the male's and the female's outside the male's; ``cusps``: upper, lower.
        """

        def turned(male: shapely.Geometry, female: shapely.Geometry) -> tuple[shapely.Geometry, shapely.Geometry]:
            m = shapely.affinity.rotate(male, psi, origin=(0, 0), use_radians=True)
            f = shapely.affinity.rotate(female, -psi * z1 / z2, origin=(0, 0), use_radians=True)
            return m, shapely.affinity.translate(f, a, 0)

        m, f = turned(*rotors)
        both, male_only, female_only = bores
        parts = shapely.get_parts(shapely.difference(both, shapely.union(m, f)).buffer(-GAP, quad_segs=2))
        parts = parts[shapely.area(parts) > 100 * GAP**2]  # slivers between a tip land and the bore's polygon
        gas = shapely.union_all(parts)
        # which gas is joined to a cusp: through gaps wider than 2 SEAL only (a morphological opening:
        # shrink, keep the pieces at the cusp, grow back), so that a contact drawn with chords of a
        # few micrometres still seals
        cores = shapely.get_parts(gas.buffer(-SEAL, quad_segs=4))
        joined = []
        for cusp in cusps:
            core = shapely.union_all(cores[shapely.dwithin(cores, cusp, 3 * SEAL)])
            joined.append(shapely.intersection(core.buffer(SEAL + GAP, quad_segs=4), gas))
        to_upper, to_lower = joined
        # the bands turned with the rotors (a band made once: turning the outline and then buffering it
        # gives the same edges' classification, the gas edges on a rotor lying GAP inside the band's 4 GAP)
        near = turned(*bands)
        for band in near:
            shapely.prepare(band)
        male_gas, female_gas = shapely.intersection(gas, male_only), shapely.intersection(gas, female_only)
        return cls(male_gas, female_gas, to_upper, to_lower, near[0], near[1])

    @staticmethod
    def edges(gas: shapely.Geometry) -> tuple[np.ndarray, np.ndarray]:
        """Return the edges of the polygons of ``gas``, each ring run with the gas on its left.

        Returns
        -------
        vectors, middles : (k, 2) float arrays, mm
            Each edge's vector and middle (exteriors counter-clockwise, holes clockwise).
        """
        polygons = shapely.get_parts(gas)
        polygons = shapely.orient_polygons(polygons[(shapely.get_type_id(polygons) == 3) & ~shapely.is_empty(polygons)])
        points, ring = shapely.get_coordinates(shapely.get_rings(polygons), return_index=True)
        same = ring[1:] == ring[:-1]  # not from one ring's last point to the next ring's first
        return np.diff(points, axis=0)[same], (0.5 * (points[1:] + points[:-1]))[same]

    @staticmethod
    def force(edges: tuple[np.ndarray, np.ndarray], near: shapely.Geometry) -> np.ndarray:
        """Sum the outward normal times length over the ``edges`` (:meth:`edges`) that lie in the band ``near``.

        The band lies about a rotor, so the sum is the force of a unit overpressure on that rotor: a (2,)
        float array, mm (N per N/mm² of overpressure, per mm of length).
        """
        e, mid = edges
        on = shapely.contains_xy(near, mid[:, 0], mid[:, 1])
        return np.array([e[on, 1].sum(), -e[on, 0].sum()])  # outward normal (holes run clockwise)


def chamber_table(
    male: shapely.Polygon,
    female: shapely.Polygon,
    male_teeth: int,
    female_teeth: int,
    center_distance: float,
    lead: float,
    length: float,
    step_deg: float = 1.0,
) -> ChamberTable:
    """Build the chamber table of a pair from its transverse sections.

    Parameters
    ----------
    male, female : shapely.Polygon
        Sections in their own frames at the mesh position of male angle 0 (a male flute pointing
        at +x, as rotorcad's outlines are).
    male_teeth, female_teeth : int
        z1, z2.
    center_distance, lead, length : float, mm
        a, male lead h, length L.
    step_deg : float
        Phase step (deg); the gas space is computed over one male pitch (it repeats) and the
        chamber's sectors are cut from it at every phase of the cycle.

    Returns
    -------
    ChamberTable
        Over the chamber's phases: the male flute's part for psi in [0, 2 pi), the female flute's
        part over its own cycle of 2 pi z2/z1 of male rotation, which ends half a male pitch after the
        male flute's (the female flute is filled by the male lobe that follows the male flute).
        The same sections and numbers asked again give the same table (the last
        ``RECENT_TABLES`` are kept; their arrays are read-only).
    """
    if not (0.05 <= step_deg <= 5.0):
        raise DesignError("phase step", "from 0.05 to 5 degrees", step_deg)
    numbers = (int(male_teeth), int(female_teeth), float(center_distance), float(lead), float(length), float(step_deg))
    key = (shapely.to_wkb(male), shapely.to_wkb(female), numbers)  # WKB: every coordinate's bits
    with _RECENT_LOCK:
        table = _RECENT.get(key)
    if table is None:
        table = _chamber_table(male, female, *numbers)
        for values in (table.phase, table.area, table.male_force, table.female_force):
            values.flags.writeable = False  # shared by every caller that asks for these sections
        with _RECENT_LOCK:
            _RECENT[key] = table
            while len(_RECENT) > RECENT_TABLES:
                _RECENT.popitem(last=False)
    return table


_RECENT: OrderedDict[tuple, ChamberTable] = OrderedDict()
_RECENT_LOCK = threading.Lock()  # a sweep's threads may build models at once


def table_phases(male_teeth: int, female_teeth: int, step_deg: float = 1.0) -> tuple[np.ndarray, int, int]:
    """Return the flute phases of the chamber table (:func:`chamber_table`), which depend on the tooth counts only.

    Parameters
    ----------
    male_teeth, female_teeth : int
        z1, z2.
    step_deg : float
        Phase step asked (deg); the step taken divides the male pitch into whole steps.

    Returns
    -------
    psi : (m,) float, rad
        The phases, equally spaced: from a male pitch before the earlier of the two flutes' cycles
        (:func:`flute_cycles`) to a male pitch after the later one's end.
    first : int
        ``psi[0]`` in steps.
    per_pitch : int
        Steps per male pitch.
    """
    pitch1 = 2 * np.pi / male_teeth
    per_pitch = max(1, round(pitch1 / np.radians(step_deg)))
    step = pitch1 / per_pitch  # a whole number of steps per pitch: the gas space is reused exactly
    # cycles (phase windows) of the two flutes; gas still joined to the chamber's cusp just beyond
    # them (a pocket closing after the flute is filled, one opening before) counts as well
    male_cycle, female_cycle = flute_cycles(male_teeth, female_teeth)
    first = int(np.floor((min(male_cycle[0], female_cycle[0]) - pitch1) / step))
    last = int(np.ceil((max(male_cycle[1], female_cycle[1]) + pitch1) / step))
    return np.arange(first, last) * step, first, per_pitch


def cycle_angle(male_teeth: int, female_teeth: int, lead: float, length: float, step_deg: float = 1.0) -> float:
    """Return the male rotation (rad) from a chamber's opening at the suction end to its end: the cycle of :func:`chamber_table`.

    Known before the table is built (its phases depend on the tooth counts only): the table's
    ``cycle`` is its ``span`` widened by the wrap 2 pi L / h.

    Parameters
    ----------
    male_teeth, female_teeth : int
        z1, z2.
    lead, length : float, mm
        Male lead h and rotor length L.
    step_deg : float
        Phase step asked (deg).

    Returns
    -------
    float, rad
    """
    psi, _, _ = table_phases(male_teeth, female_teeth, step_deg)
    return float(psi[-1] + (psi[1] - psi[0]) - psi[0] + 2 * np.pi * length / lead)


def _chamber_table(
    male: shapely.Polygon,
    female: shapely.Polygon,
    z1: int,
    z2: int,
    a: float,
    lead: float,
    length: float,
    step_deg: float,
) -> ChamberTable:
    """:func:`chamber_table`, built."""
    r1 = float(np.hypot(*np.asarray(male.exterior.coords).T).max())
    r2 = float(np.hypot(*np.asarray(female.exterior.coords).T).max())
    if not r1 + r2 > a:
        raise DesignError("tip radii", f"adding up to more than the centre distance {a:g} mm", r1 + r2)
    disc1, disc2 = shapely.Point(0, 0).buffer(r1, quad_segs=256), shapely.Point(a, 0).buffer(r2, quad_segs=256)
    bores = shapely.union(disc1, disc2)
    cusp_x = (a**2 + r1**2 - r2**2) / (2 * a)
    cusp_y = np.sqrt(max(r1**2 - cusp_x**2, 0.0))
    upper, lower = shapely.Point(cusp_x, cusp_y), shapely.Point(cusp_x, -cusp_y)
    pitch1 = 2 * np.pi / z1
    psi, first, per_pitch = table_phases(z1, z2, step_deg)
    step = pitch1 / per_pitch
    male_cycle, female_cycle = flute_cycles(z1, z2)
    male_only = shapely.intersection(disc1, bores)
    female_only = shapely.difference(disc2, disc1)  # the lens between the bores counts with the male flute
    rotors, bands = (male, female), (_band(male), _band(female))
    cusps = (upper, lower)
    sections = [_Section.at(rotors, bands, z1, z2, a, (bores, male_only, female_only), cusps, j * step) for j in range(per_pitch)]
    area = np.zeros(len(psi))
    male_force = np.zeros((len(psi), 2))
    female_force = np.zeros((len(psi), 2))
    for i, p in enumerate(psi):  # a few hundred sections; shapely does the geometry of each
        section = sections[(first + i) % per_pitch]  # the rotors turned by whole pitches are themselves
        parts = []
        for (lo, hi), flute in ((male_cycle, Side.MALE), (female_cycle, Side.FEMALE)):
            if not lo - pitch1 <= p < hi + pitch1:
                continue
            opening = p < 0.5 * (lo + hi)
            if flute is Side.MALE:  # the flute's sector of its bore's gas
                gas = shapely.intersection(section.male_gas, _sector((0.0, 0.0), r1, p - pitch1 / 2, p + pitch1 / 2))
            else:
                gas = shapely.intersection(section.female_gas, _female_sector(a, r2, z1, z2, p))
            if p < lo:  # before the cycle: only gas already open to the suction side
                parts.append(shapely.intersection(gas, section.to_upper))
            elif p >= hi:  # after it: only gas still closing towards the discharge
                parts.append(shapely.intersection(gas, section.to_lower))
            else:  # in it: all but what the other side's chamber holds
                parts.append(shapely.difference(gas, section.to_lower if opening else section.to_upper))
        for part in parts:
            area[i] += part.area
            edges = section.edges(part)
            male_force[i] += section.force(edges, section.male_near)
            female_force[i] += section.force(edges, section.female_near)
    flute1 = (np.pi * r1**2 - male.area) / z1
    flute2 = (np.pi * r2**2 - female.area) / z2
    return ChamberTable(psi, area, male_force, female_force, float(flute1), float(flute2), float(lead), float(length))

"""Interference of a helical rotor pair and of each rotor with the housing.

Fast method (2D sections): the slice of the pair at height z is the transverse pair at male angle
phi1 + 2 pi z / h1, so the intersection volume at male angle phi1 is

    V(phi1) = (h1 / 2 pi) * integral over theta from phi1 to phi1 + wrap of A(theta) d(theta),

A(theta) the intersection area of the two sections at male angle theta. A is periodic over one male
lobe pitch 2 pi / z1, so one table of A over a pitch (shapely booleans) gives V at every angle at
once. The 3D check intersects the manifold3d solids directly (``intersection_3d``).

Touching conjugate surfaces are not interference. Sections sampled to chords of tol/2 overlap at a
contact by at most tol/2 deep over a width of about 2 sqrt(2 R tol) (R the larger flank radius,
bounded by the tip radius), so with at most n_c = z1 + z2 contacts in a section the touching
overlap stays below A_t = n_c tol sqrt(2 R tol) per section and V_t = A_t L in volume. Results
below V_t count as touching (zero interference).
"""

from __future__ import annotations

from dataclasses import dataclass

import manifold3d as m3
import numpy as np
import shapely

from rotorcad.geometry import rotate
from rotorcad.rotor_pair import RotorPair
from rotorcad.solids import HelicalSolid


@dataclass(frozen=True)
class Interference:
    """Interference of a pair over one male lobe pitch, from the 2D-section integral.

    Parameters
    ----------
    angles : (k,) float array, rad
        Male angles over one lobe pitch 2 pi / z1.
    volumes : (k,) float array, mm³
        Intersection volume of the two rotors at each angle.
    threshold : float, mm³
        Volumes below this are touching, not interference (:func:`touching_threshold`).
    housing_volume : float, mm³
        Volume of the rotors outside the housing bores.
    area_table : (m,) float array, mm²
        A(theta), the sections' intersection area over one pitch.
    depth_table : (m,) float array, mm, optional
        The sections' deepest penetration over the same angles (:func:`section_overlaps`).
    tolerance : float, mm
        Chord tolerance of the sections: a deeper penetration is interference.
    """

    angles: np.ndarray  # male angles (rad) over one lobe pitch
    volumes: np.ndarray  # intersection volume at each angle (mm^3)
    threshold: float  # touching below this (mm^3)
    housing_volume: float  # rotors outside the housing bores (mm^3)
    area_table: np.ndarray  # A(theta) over one pitch (mm^2)
    depth_table: np.ndarray | None = None  # deepest penetration of the sections over one pitch (mm)
    tolerance: float = 0.0  # chord tolerance of the sections (mm)

    @property
    def max_penetration(self) -> float:
        """Deepest penetration of one rotor into the other in any transverse section, mm.

        The largest over the intersection's vertices of their distances to the two rotors'
        boundaries added (a vertex on one boundary lies that deep inside the other rotor).
        """
        return float(self.depth_table.max()) if self.depth_table is not None and len(self.depth_table) else 0.0

    @property
    def max_volume(self) -> float:
        """Largest intersection volume over the pitch, mm³."""
        return float(self.volumes.max())

    @property
    def angle_of_max(self) -> float:
        """Male angle of the largest intersection volume, rad."""
        return float(self.angles[int(np.argmax(self.volumes))])

    @property
    def interferes(self) -> bool:
        """True when the rotors interfere beyond touching.

        The largest intersection volume exceeds the touching threshold, or a section penetrates
        deeper than the sections' chord tolerance (touching sections sampled to tol/2 overlap at
        most tol/2 deep, module docstring): a thin interference along the rotors, 20 µm deep at a
        centre distance 0.02 mm short, has little volume but is one all the same.
        """
        return bool(self.max_volume > self.threshold or self.max_penetration > self.tolerance)


def _rotate_coords(pts: np.ndarray, angles: np.ndarray, centre: tuple[float, float] = (0.0, 0.0)) -> np.ndarray:
    """Points (n, 2), mm, turned by each of ``angles`` (k,), rad, about ``centre``: (k, n, 2)."""
    return rotate(pts, np.asarray(angles, dtype=float)[:, None], centre)


def touching_threshold(pair: RotorPair, tolerance: float) -> float:
    """Return the volume V_t below which the rotors only touch (module docstring).

    V_t = (z1 + z2) tol sqrt(2 R tol) L, R the larger tip radius.

    Parameters
    ----------
    pair : RotorPair
        Tooth counts, tip radii and length (mm).
    tolerance : float, mm
        Chord tolerance of the sections.

    Returns
    -------
    float, mm³
    """
    r = max(pair.male_tip_radius, pair.female_tip_radius)
    return float((pair.male_teeth + pair.female_teeth) * tolerance * np.sqrt(2.0 * r * tolerance) * pair.length)


def section_overlap_areas(
    pair: RotorPair, male: shapely.Polygon, female: shapely.Polygon, thetas: np.ndarray, female_phase: float = 0.0
) -> np.ndarray:
    """Return A(theta), the intersection area of the two sections, for all male angles at once.

    The male is turned by theta, the female (own frame, placed at (a, 0)) by -theta z1/z2 +
    ``female_phase``.

    Parameters
    ----------
    pair : RotorPair
        Tooth counts and centre distance (mm).
    male, female : shapely.Polygon
        The transverse sections in their own frames, mm.
    thetas : (k,) float array, rad
        Male angles.
    female_phase : float, rad
        Extra turn of the female.

    Returns
    -------
    (k,) float array, mm²
    """
    return section_overlaps(pair, male, female, thetas, female_phase)[0]


def section_overlaps(
    pair: RotorPair, male: shapely.Polygon, female: shapely.Polygon, thetas: np.ndarray, female_phase: float = 0.0
) -> tuple[np.ndarray, np.ndarray]:
    """Return the intersection area and the penetration depth of the two sections at each male angle.

    Placed as in :func:`section_overlap_areas`. The depth at an angle is the largest, over the
    intersection's vertices, of the vertex's distance to the male boundary plus its distance to
    the female boundary: a vertex on one boundary lies that deep inside the other rotor, so this is
    the deepest penetration (0 where the sections only touch at a point).

    Parameters
    ----------
    pair : RotorPair
        Tooth counts and centre distance (mm).
    male, female : shapely.Polygon
        The transverse sections in their own frames, mm.
    thetas : (k,) float array, rad
        Male angles.
    female_phase : float, rad
        Extra turn of the female.

    Returns
    -------
    area : (k,) float array, mm²
    depth : (k,) float array, mm
    """
    mp = np.asarray(shapely.geometry.polygon.orient(male, 1.0).exterior.coords)
    fp = np.asarray(shapely.geometry.polygon.orient(female, 1.0).exterior.coords) + np.array([pair.center_distance, 0.0])
    ratio = pair.male_teeth / pair.female_teeth
    female_turn = -np.asarray(thetas, dtype=float) * ratio + female_phase
    males = shapely.polygons(_rotate_coords(mp, thetas))
    females = shapely.polygons(_rotate_coords(fp, female_turn, (pair.center_distance, 0.0)))
    cuts = shapely.intersection(males, females)
    area = shapely.area(cuts)
    depth = np.zeros(len(area))
    verts, which = shapely.get_coordinates(cuts, return_index=True)
    if len(verts):
        # each vertex back in the male's and the female's own frames, measured against the fixed rings
        own_male = rotate(verts, -np.asarray(thetas, dtype=float)[which])
        own_female = rotate(verts, -female_turn[which], (pair.center_distance, 0.0))
        d = shapely.distance(shapely.points(own_male), shapely.LinearRing(mp)) + shapely.distance(
            shapely.points(own_female), shapely.LinearRing(fp)
        )
        np.maximum.at(depth, which, d)
    return area, depth


def interference_2d(
    pair: RotorPair,
    male: shapely.Polygon,
    female: shapely.Polygon,
    steps: int,
    tolerance: float,
    samples_per_pitch: int = 360,
    female_phase: float = 0.0,
    clearance: float = 0.0,
) -> Interference:
    """Compute the intersection volume at male angles over one lobe pitch by the 2D-section integral.

    V(phi1) = (h1 / 2 pi) integral of A(theta) over [phi1, phi1 + wrap] (module docstring), with A
    tabulated over one pitch and integrated by the trapezoidal rule.

    Parameters
    ----------
    pair : RotorPair
        Dimensions of the pair (lead and length set the wrap).
    male, female : shapely.Polygon
        The transverse sections in their own frames, mm.
    steps : int
        Male angles over one lobe pitch.
    tolerance : float, mm
        Chord tolerance of the sections (for the touching threshold).
    samples_per_pitch : int
        Samples of A(theta) over one pitch.
    female_phase : float, rad
        Extra turn of the female.
    clearance : float, mm
        Radial clearance of the housing bores (tip radius + clearance).

    Returns
    -------
    Interference
    """
    pitch = 2.0 * np.pi / pair.male_teeth
    theta = np.arange(samples_per_pitch) * pitch / samples_per_pitch
    area, depth = section_overlaps(pair, male, female, theta, female_phase)
    # cumulative integral of the periodic A over any interval, exact for the piecewise-linear A
    closed = np.append(area, area[0])
    cum = np.concatenate([[0.0], np.cumsum(0.5 * (closed[1:] + closed[:-1]) * (pitch / samples_per_pitch))])
    per_pitch = cum[-1]

    def primitive(x: np.ndarray) -> np.ndarray:
        k = np.floor(x / pitch)
        rem = x - k * pitch
        grid = np.arange(samples_per_pitch + 1) * pitch / samples_per_pitch
        return k * per_pitch + np.interp(rem, grid, cum)

    wrap = 2.0 * np.pi * pair.length / pair.lead
    angles = np.arange(steps) * pitch / steps
    volumes = pair.lead / (2.0 * np.pi) * (primitive(angles + wrap) - primitive(angles))
    housing = housing_overlap(pair, male, female, clearance)
    return Interference(angles, volumes, touching_threshold(pair, tolerance), housing, area, depth, tolerance)


def housing_overlap(pair: RotorPair, male: shapely.Polygon, female: shapely.Polygon, clearance: float) -> float:
    """Return the volume of the rotors outside the housing bores.

    Each bore is a circle of tip radius + ``clearance`` about its rotor's axis, so turning the rotor
    does not change it.

    Parameters
    ----------
    pair : RotorPair
        Tip radii, centre distance and length (mm).
    male, female : shapely.Polygon
        The transverse sections in their own frames, mm.
    clearance : float, mm
        Radial clearance of the bores.

    Returns
    -------
    float, mm³
    """
    bores = shapely.union(
        shapely.Point(0, 0).buffer(pair.male_tip_radius + clearance, quad_segs=2048),
        shapely.Point(pair.center_distance, 0).buffer(pair.female_tip_radius + clearance, quad_segs=2048),
    )
    placed = shapely.affinity.translate(female, pair.center_distance, 0.0)
    outside = male.difference(bores).area + placed.difference(bores).area
    return float(outside * pair.length)


def intersection_3d(
    pair: RotorPair, male: HelicalSolid, female: HelicalSolid, angle: float, threshold: float = 0.0
) -> dict[str, object]:
    """Intersect the two solids at a male angle by a 3D boolean (manifold3d).

    The female is turned by -angle z1/z2 and placed at (a, 0).

    Parameters
    ----------
    pair : RotorPair
        Tooth counts and centre distance (mm).
    male, female : HelicalSolid
        The solids in their own frames.
    angle : float, rad
        Male angle.
    threshold : float, mm³
        Parts of the intersection smaller than threshold / (number of parts) are left out of the
        box.

    Returns
    -------
    dict
        ``volume`` (mm³, all parts), ``parts`` (their number), ``centroid`` (the mass centroid of
        the larger parts, [x, y, z] mm) and ``bbox``
        ([lower, upper] corners, mm); the last two None when no part is large enough.
    """
    m = male.manifold.rotate([0.0, 0.0, float(np.degrees(angle))])
    f = female.manifold.rotate([0.0, 0.0, float(-np.degrees(angle) * pair.male_teeth / pair.female_teeth)]).translate(
        [pair.center_distance, 0.0, 0.0]
    )
    inter = m ^ f
    parts = [p for p in inter.decompose() if p.volume() > 0.0]
    volume = float(sum(p.volume() for p in parts))
    big = [p for p in parts if p.volume() > threshold / max(len(parts), 1)]
    if not big:
        return {"volume": volume, "parts": len(parts), "centroid": None, "bbox": None}
    import trimesh

    mesh = m3.Manifold.batch_boolean(big, m3.OpType.Add).to_mesh64()
    verts = np.asarray(mesh.vert_properties)[:, :3]
    lo, hi = verts.min(axis=0), verts.max(axis=0)
    # the mass centroid of the closed mesh (trimesh: divergence theorem over its triangles)
    centroid = trimesh.Trimesh(verts, np.asarray(mesh.tri_verts), process=False).center_mass
    return {"volume": volume, "parts": len(parts), "centroid": np.asarray(centroid).tolist(), "bbox": [lo.tolist(), hi.tolist()]}

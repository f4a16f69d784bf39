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
    angles: np.ndarray  # male angles (rad) over one lobe pitch
    volumes: np.ndarray  # intersection volume at each angle (mm^3)
    threshold: float  # touching below this (mm^3)
    housing_volume: float  # rotors outside the housing bores (mm^3)
    area_table: np.ndarray  # A(theta) over one pitch (mm^2)

    @property
    def max_volume(self) -> float:
        return float(self.volumes.max())

    @property
    def angle_of_max(self) -> float:
        return float(self.angles[int(np.argmax(self.volumes))])

    @property
    def interferes(self) -> bool:
        return bool(self.max_volume > self.threshold)


def _rotate_coords(pts: np.ndarray, angles: np.ndarray, centre: tuple[float, float] = (0.0, 0.0)) -> np.ndarray:
    """Points (n, 2), mm, turned by each of ``angles`` (k,), rad, about ``centre``: (k, n, 2)."""
    return rotate(pts, np.asarray(angles, dtype=float)[:, None], centre)


def touching_threshold(pair: RotorPair, tolerance: float) -> float:
    r = max(pair.male_tip_radius, pair.female_tip_radius)
    return float((pair.male_teeth + pair.female_teeth) * tolerance * np.sqrt(2.0 * r * tolerance) * pair.length)


def section_overlap_areas(
    pair: RotorPair, male: shapely.Polygon, female: shapely.Polygon, thetas: np.ndarray, female_phase: float = 0.0
) -> np.ndarray:
    """A(theta): intersection area of the male turned by theta and the female (own frame, placed at
    (a, 0)) turned by -theta z1/z2 + ``female_phase``, for all theta at once.
    """
    mp = np.asarray(shapely.geometry.polygon.orient(male, 1.0).exterior.coords)
    fp = np.asarray(shapely.geometry.polygon.orient(female, 1.0).exterior.coords) + np.array([pair.center_distance, 0.0])
    ratio = pair.male_teeth / pair.female_teeth
    males = shapely.polygons(_rotate_coords(mp, thetas))
    females = shapely.polygons(_rotate_coords(fp, -thetas * ratio + female_phase, (pair.center_distance, 0.0)))
    return shapely.area(shapely.intersection(males, females))


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
    """Intersection volume at ``steps`` male angles over one lobe pitch by the 2D-section integral."""
    pitch = 2.0 * np.pi / pair.male_teeth
    theta = np.arange(samples_per_pitch) * pitch / samples_per_pitch
    area = section_overlap_areas(pair, male, female, theta, female_phase)
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
    return Interference(angles, volumes, touching_threshold(pair, tolerance), housing, area)


def housing_overlap(pair: RotorPair, male: shapely.Polygon, female: shapely.Polygon, clearance: float) -> float:
    """Volume of the rotors outside the housing bores (tip radius + clearance about each centre);
    each bore is a circle about its rotor's axis, so turning the rotor does not change it.
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
    """3D boolean of the two solids at male angle ``angle`` (female turned by -angle z1/z2, placed at
    (a, 0)): total volume, and centroid and bounding box of the parts above ``threshold``.
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
    mesh = m3.Manifold.batch_boolean(big, m3.OpType.Add).to_mesh64()
    verts = np.asarray(mesh.vert_properties)[:, :3]
    lo, hi = verts.min(axis=0), verts.max(axis=0)
    return {"volume": volume, "parts": len(parts), "centroid": ((lo + hi) / 2).tolist(), "bbox": [lo.tolist(), hi.tolist()]}

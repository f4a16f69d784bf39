"""Helical solids of rotors and gears: a transverse section extruded with twist by manifold3d.

The surface between two consecutive layers is ruled (straight lines between corresponding section
vertices); a point at radius R of a section turned by d(theta) per layer sags from the true helicoid
by about R d(theta)^2 / 8, the sagitta of a chord of the helix seen along the axis (measured here:
300 deg wrap, R = 48 mm: 50 layers 63 um, 200 layers 4 um). With a surface tolerance
``tol`` the section is sampled to chords of tol/2 and the layers are chosen so that the sag stays
below tol/2: n = ceil(wrap sqrt(R_max / (4 tol))). The bound that holds: every point of the
triangulated surface lies within ``tol`` of the exact helical surface, hence
|V - A L| <= P L tol (A, P area and perimeter of the sampled section, L the length).

Right hand turns the section counter-clockwise going up (positive ``twist_degrees`` in manifold3d);
a contour is passed counter-clockwise with the positive fill rule (measured: a clockwise contour
gives an empty section without error).
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property
from typing import TYPE_CHECKING

import manifold3d as m3
import numpy as np
import shapely

from rotorcad.errors import DesignError
from rotorcad.triangle_mesh import TriangleMesh, face_normals

if TYPE_CHECKING:
    import trimesh


@dataclass(frozen=True, eq=False)
class HelicalSolid:
    """A swept solid with what it was made from.

    The triangle mesh is made by numpy (:func:`twisted_extrusion`, the triangles manifold3d's
    ``extrude`` makes) and the :class:`manifold3d.Manifold` only when asked for (a boolean, a slice,
    the genus): a mesh file needs no manifold, and making one costs about 0.5 s for a rotor at 5 µm.

    Parameters
    ----------
    contours : tuple of (n, 2) float arrays, mm
        The section's rings as manifold3d cleans them (outer rings counter-clockwise), at z = 0.
    section : shapely.Polygon
        The swept section at z = 0 in the body's own frame, counter-clockwise, mm.
    length : float, mm
        Axial length.
    lead : float, mm
        Signed lead: > 0 right hand, < 0 left hand, ``inf`` for a straight extrusion.
    layers : int
        Number of ruled layers along z.
    tolerance : float, mm
        The surface tolerance the layers were chosen for.
    """

    contours: tuple[np.ndarray, ...]
    section: shapely.Polygon  # at z = 0, in the body's own frame
    length: float
    lead: float  # signed: > 0 right hand
    layers: int
    tolerance: float

    @property
    def wrap(self) -> float:
        """Turn of the section from z = 0 to z = length, rad (counter-clockwise for a right hand)."""
        return 0.0 if np.isinf(self.lead) else 2.0 * np.pi * self.length / self.lead

    @cached_property
    def manifold(self) -> m3.Manifold:
        """The solid as a :class:`manifold3d.Manifold`, mm, axis along z from 0 to ``length`` (made on first use)."""
        cs = m3.CrossSection(list(self.contours), m3.FillRule.Positive)
        if self.wrap == 0.0:
            return m3.Manifold.extrude(cs, self.length)
        return m3.Manifold.extrude(cs, self.length, n_divisions=self.layers - 1, twist_degrees=float(np.degrees(self.wrap)))

    @cached_property
    def volume(self) -> float:
        """Volume of the triangulated solid, mm³ (:func:`twisted_volume`: one layer's, times the layers)."""
        return twisted_volume(self.contours, self.length, self.layers, self.wrap)

    @property
    def nominal_volume(self) -> float:
        """Section area times length, mm³: what the exact solid holds."""
        return float(self.section.area * self.length)

    @property
    def volume_bound(self) -> float:
        """Bound |V - A L| <= P L tol, mm³ (see the module docstring)."""
        return float(self.section.exterior.length * self.length * self.tolerance)

    @property
    def genus(self) -> int:
        """Topological genus of the solid (0 for a solid without through holes)."""
        return int(self.manifold.genus())

    @cached_property
    def triangle_mesh(self) -> TriangleMesh:
        """Float64 triangle mesh of the solid as numpy arrays, mm (no trimesh and no manifold needed).

        :func:`twisted_extrusion` of the contours, with its face normals computed once here so that
        writers need not.
        """
        return twisted_extrusion(self.contours, self.length, self.layers, self.wrap)

    @cached_property
    def mesh(self) -> trimesh.Trimesh:
        """The same mesh as :attr:`triangle_mesh`, as a :class:`trimesh.Trimesh` (imports trimesh)."""
        return self.triangle_mesh.to_trimesh()

    def section_at(self, z: float) -> shapely.Geometry:
        """Slice the solid at a height.

        Parameters
        ----------
        z : float, mm
            Height along the axis.

        Returns
        -------
        shapely.Geometry
            The slice (the union of its rings, made valid), mm; empty when z misses the solid.
        """
        polys = self.manifold.slice(z).to_polygons()
        rings = [shapely.Polygon(p) for p in polys if len(p) >= 3]
        return shapely.make_valid(shapely.union_all(rings)) if rings else shapely.Polygon()

    def rotation_at(self, z: float) -> float:
        """Return the angle by which the section at height z is turned from the one at z = 0.

        Parameters
        ----------
        z : float, mm
            Height along the axis.

        Returns
        -------
        float, rad
            2 pi z / lead (0 for a straight extrusion).
        """
        return 0.0 if np.isinf(self.lead) else 2.0 * np.pi * z / self.lead


def layers_for(tolerance: float, wrap: float, r_max: float) -> int:
    """Count the layers that keep the ruled-surface sag r_max dtheta^2 / 8 below tolerance / 2.

    Parameters
    ----------
    tolerance : float, mm
        Surface tolerance.
    wrap : float, rad
        Total turn of the section over the length (its sign is ignored).
    r_max : float, mm
        Largest radius of the section.

    Returns
    -------
    int
        n = ceil(|wrap| sqrt(r_max / (4 tol))), at least 1.
    """
    return max(1, int(np.ceil(abs(wrap) * np.sqrt(r_max / (4.0 * tolerance)))))


def helical_solid(section: shapely.Polygon, lead: float, length: float, tolerance: float, phase: float = 0.0) -> HelicalSolid:
    """Sweep a section helically into a solid (module docstring for the tolerance it meets).

    Parameters
    ----------
    section : shapely.Polygon
        Transverse section in its own frame (turned counter-clockwise here if it is not), mm; only
        its exterior ring is swept.
    lead : float, mm
        Signed lead: > 0 right hand, < 0 left hand.
    length : float, mm
        Axial length.
    tolerance : float, mm
        Surface tolerance: sets the number of layers (:func:`layers_for`).
    phase : float, rad
        Turn of the section at z = 0, counter-clockwise.

    Returns
    -------
    HelicalSolid

    Raises
    ------
    DesignError
        A tolerance or length that is not positive, or a lead that is zero or not finite.
    """
    if not (np.isfinite(tolerance) and tolerance > 0):
        raise DesignError("tolerance", "a positive length in mm", tolerance)
    if not (np.isfinite(length) and length > 0):
        raise DesignError("length", "a positive length in mm", length)
    if not (np.isfinite(lead) and lead != 0):
        raise DesignError("lead", "a non-zero length in mm", lead)
    poly = shapely.geometry.polygon.orient(section, 1.0)
    if phase:
        poly = shapely.affinity.rotate(poly, phase, origin=(0, 0), use_radians=True)
    pts = np.asarray(poly.exterior.coords)[:-1]
    holes = [np.asarray(h.coords)[:-1] for h in poly.interiors]  # clockwise (oriented above): an internal gear's bore
    contours = tuple(np.asarray(c, dtype=float) for c in m3.CrossSection([pts, *holes], m3.FillRule.Positive).to_polygons())
    wrap = 2.0 * np.pi * length / lead
    r_max = float(np.hypot(*pts.T).max())
    n = layers_for(tolerance, wrap, r_max)
    return HelicalSolid(contours, poly, float(length), float(lead), n, float(tolerance))


def twisted_extrusion(contours: tuple[np.ndarray, ...], length: float, layers: int, wrap: float) -> TriangleMesh:
    """Triangulate a section extruded along z with a uniform twist, as manifold3d's ``extrude`` does.

    Vertex ring k (k = 0..n) is the section turned by ``wrap`` k / n at z = ``length`` k / n; each
    side quad between rings k and k + 1 over the edge i -> i + 1 is split along the diagonal from
    vertex i + 1 of ring k to vertex i of ring k + 1 (manifold3d's choice, so that the triangles are
    its own); the end caps are :func:`manifold3d.triangulate` of the section, the bottom one
    reversed. The face normals point out of the solid.

    Parameters
    ----------
    contours : tuple of (m_j, 2) float arrays, mm
        The section's rings, outer ones counter-clockwise and holes clockwise.
    length : float, mm
        Length along z.
    layers : int
        Number n of layers (n + 1 rings).
    wrap : float, rad
        Turn of the top ring from the bottom one, counter-clockwise seen from +z.

    Returns
    -------
    TriangleMesh
        (n + 1) m vertices and 2 n m + 2 (m - 2) triangles for one ring of m vertices.
    """
    pts = np.concatenate(contours)
    m = len(pts)
    k = np.arange(layers + 1)
    phi = wrap * k / layers
    c, s = np.cos(phi)[:, None], np.sin(phi)[:, None]
    # every array of a rotor's size is made once and filled in place (each product, sum and index
    # as the plain expressions make it): a fresh one is some 10 MB of pages to fault in
    vertices = np.empty((layers + 1, m, 3))
    x, y, vx, vy = pts[:, 0], pts[:, 1], vertices[..., 0], vertices[..., 1]
    np.multiply(c, x, out=vx)
    vx -= s * y  # c x - s y
    np.multiply(s, x, out=vy)
    vy += c * y  # s x + c y
    vertices[..., 2] = (length * k / layers)[:, None]
    starts = np.cumsum([0] + [len(ring) for ring in contours])
    i = np.arange(m)
    j = i + 1
    j[starts[1:] - 1] = starts[:-1]  # each ring closes on its own first vertex
    base = (np.arange(layers) * m)[:, None]
    cap = np.asarray(m3.triangulate(list(contours)), dtype=np.int64)
    # the faces filled in place (layer, edge, its two triangles, their corners), then the caps:
    # no stacked copies of the 0.5 million side triangles of a rotor; corners a = base + i,
    # b = base + j and the ones above them, up_a = a + m, up_b = b + m
    faces = np.empty((2 * layers * m + 2 * len(cap), 3), dtype=np.int64)
    side = faces[: 2 * layers * m].reshape(layers, m, 2, 3)
    np.add(base, i, out=side[:, :, 0, 0])
    np.add(base, j, out=side[:, :, 0, 1])
    np.add(base + m, i, out=side[:, :, 0, 2])
    side[:, :, 1, 0] = side[:, :, 0, 1]
    np.add(base + m, j, out=side[:, :, 1, 1])
    side[:, :, 1, 2] = side[:, :, 0, 2]
    side = faces[: 2 * layers * m]
    faces[2 * layers * m : 2 * layers * m + len(cap)] = cap[:, ::-1]
    faces[2 * layers * m + len(cap) :] = cap + layers * m
    vertices = vertices.reshape(-1, 3)
    # the side triangles of layer k are those of layer 0 turned by phi_k about z, and so are their
    # normals: computed on layer 0 and turned, without gathering the corners of every triangle
    first = face_normals(vertices, side[: 2 * m]).reshape(1, 2 * m, 3)
    normals = np.empty((2 * layers * m + 2 * len(cap), 3))
    turned = normals[: 2 * layers * m].reshape(layers, 2 * m, 3)
    cos, sin = np.cos(phi[:-1])[:, None], np.sin(phi[:-1])[:, None]
    nx, ny = turned[..., 0], turned[..., 1]
    np.multiply(cos, first[..., 0], out=nx)
    nx -= sin * first[..., 1]
    np.multiply(sin, first[..., 0], out=ny)
    ny += cos * first[..., 1]
    turned[..., 2] = first[..., 2]
    caps = normals[2 * layers * m :]
    caps[:, :2] = 0.0
    caps[: len(cap), 2], caps[len(cap) :, 2] = -1.0, 1.0  # the bottom cap faces down, the top one up
    return TriangleMesh(vertices, faces, normals)


def twisted_volume(contours: tuple[np.ndarray, ...], length: float, layers: int, wrap: float) -> float:
    """Volume of the :func:`twisted_extrusion` mesh, mm³, from its first layer alone.

    Every layer is the first one turned by phi_k about z and raised by k h (h = length / n): the
    layers are congruent, so the solid holds n times the first layer's volume. That one is the sum
    of a . (b x c) / 6 over its closed surface (divergence theorem, the origin on the axis): the 2 m
    side triangles as :func:`twisted_extrusion` makes them; the bottom cap at z = 0 adds nothing;
    the top cap at z = h adds h A / 3, A the section's area (shoelace over its rings, holes
    clockwise), which its triangles cover.

    Parameters
    ----------
    contours : tuple of (m_j, 2) float arrays, mm
        The section's rings, outer ones counter-clockwise and holes clockwise.
    length : float, mm
        Length along z.
    layers : int
        Number n of layers.
    wrap : float, rad
        Turn of the top ring from the bottom one, counter-clockwise seen from +z.

    Returns
    -------
    float, mm³
    """
    h, dphi = length / layers, wrap / layers
    pts = np.concatenate(contours)
    starts = np.cumsum([0] + [len(ring) for ring in contours])
    j = np.arange(1, len(pts) + 1)
    j[starts[1:] - 1] = starts[:-1]  # each ring closes on its own first vertex
    c, s = np.cos(dphi), np.sin(dphi)
    a = np.column_stack([pts, np.zeros(len(pts))])
    b = a[j]
    up = np.column_stack([c * pts[:, 0] - s * pts[:, 1], s * pts[:, 0] + c * pts[:, 1], np.full(len(pts), h)])
    up_a, up_b = up, up[j]
    side = np.einsum("ij,ij->i", a, np.cross(b, up_a)) + np.einsum("ij,ij->i", b, np.cross(up_b, up_a))
    area = 0.5 * float(np.sum(pts[:, 0] * b[:, 1] - b[:, 0] * pts[:, 1]))
    return float(layers * (side.sum() / 6.0 + h * area / 3.0))


HOUSING_WALL = 10.0  # mm: the housing block stands this far beyond the bores


def housing_solids(
    center_distance: float,
    male_bore: float,
    female_bore: float,
    length: float,
    wall: float = HOUSING_WALL,
    segments: int = 720,
) -> tuple[m3.Manifold, m3.Manifold]:
    """Make the housing of a pair: the block minus the bores, and the bores alone.

    The bores are the two intersecting cylinders of radii ``male_bore`` and ``female_bore`` (tip
    radius + radial clearance) about O1 = (0, 0) and O2 = (a, 0); where they cross stand the
    housing cusps. The block stands ``wall`` beyond the bores.

    Parameters
    ----------
    center_distance : float, mm
        Centre distance a.
    male_bore, female_bore : float, mm
        Bore radii.
    length : float, mm
        Length along z, from 0.
    wall : float, mm
        Wall beyond the bores.
    segments : int
        Segments that polygonise a full circle.

    Returns
    -------
    tuple of (manifold3d.Manifold, manifold3d.Manifold)
        (block minus bores, bores).

    Raises
    ------
    DesignError
        A bore radius that is not positive, or bores that do not overlap.
    """
    for name, r in (("male bore", male_bore), ("female bore", female_bore)):
        if not (np.isfinite(r) and r > 0):
            raise DesignError(name, "a positive radius in mm", r)
    if not male_bore + female_bore > center_distance:
        raise DesignError("bores", f"overlapping (radii adding up to more than {center_distance:g} mm)", male_bore + female_bore)
    male = m3.Manifold.cylinder(length, male_bore, male_bore, segments)
    female = m3.Manifold.cylinder(length, female_bore, female_bore, segments).translate([center_distance, 0.0, 0.0])
    bores = male + female
    x0, x1 = -male_bore - wall, center_distance + female_bore + wall
    half = max(male_bore, female_bore) + wall
    block = m3.Manifold.cube([x1 - x0, 2 * half, length]).translate([x0, -half, 0.0])
    return block - bores, bores


def helical_gear_solid(
    outline: np.ndarray, pitch_radius: float, helix_angle: float, face_width: float, tolerance: float
) -> HelicalSolid:
    """Sweep a gear's transverse outline into a helical (or spur) gear.

    The lead is h = 2 pi r / tan(beta), right hand for beta > 0; a spur gear (beta = 0) is a
    straight extrusion.

    Parameters
    ----------
    outline : (n, 2) float array, mm
        Closed transverse outline about the origin.
    pitch_radius : float, mm
        Pitch radius r (the lead is taken there).
    helix_angle : float, rad
        Helix angle beta at the pitch circle.
    face_width : float, mm
        Axial length.
    tolerance : float, mm
        Surface tolerance (:func:`helical_solid`).

    Returns
    -------
    HelicalSolid
    """
    section = shapely.Polygon(outline)
    if abs(helix_angle) < 1e-12:
        poly = shapely.geometry.polygon.orient(section, 1.0)
        pts = np.asarray(poly.exterior.coords)[:-1]
        contours = tuple(np.asarray(c, dtype=float) for c in m3.CrossSection([pts], m3.FillRule.Positive).to_polygons())
        return HelicalSolid(contours, poly, face_width, float("inf"), 1, tolerance)
    lead = 2.0 * np.pi * pitch_radius / np.tan(helix_angle)
    return helical_solid(section, lead, face_width, tolerance)

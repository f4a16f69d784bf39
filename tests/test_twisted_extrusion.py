"""The swept solids' triangles, made by numpy (rotorcad.solids.twisted_extrusion), against manifold3d.

Reference: manifold3d's own ``Manifold.extrude`` with the same layers and twist (what
``HelicalSolid.manifold`` makes, and what the meshes were before): the same triangles (as sets of
corner coordinates, to 1e-7 mm) and the same volume; trimesh (a third-party reader) finds the numpy
mesh watertight and consistently wound, with its normals pointing out.
"""

from __future__ import annotations

import numpy as np
import pytest
import shapely

from rotorcad.rotor_families import build_family
from rotorcad.rotor_pair import RotorPair
from rotorcad.solids import helical_gear_solid, helical_solid
from rotorcad.triangle_mesh import face_normals

PAIR = RotorPair(5, 6, 116.0, 63.0, 45.0, 71.0, 53.0, lead=300.0, length=40.0)


def triangle_set(corners: np.ndarray) -> set:
    return {tuple(sorted(map(tuple, np.round(c, 7)))) for c in corners}


@pytest.fixture(scope="module")
def rotors():
    return build_family(PAIR, "rack-involute", {"tip_rounding": 1.4, "root_rounding": 1.0, "lobe_width": 0.6})


@pytest.mark.parametrize("body,lead", [("male", 300.0), ("female", -360.0)])
def test_numpy_triangles_are_manifold3ds(rotors, body, lead):
    solid = helical_solid(rotors.section(body, 0.1), lead, PAIR.length, 0.2)
    mine = solid.triangle_mesh
    ref = solid.manifold.to_mesh64()
    v, f = np.asarray(ref.vert_properties)[:, :3], np.asarray(ref.tri_verts)
    assert len(mine.faces) == len(f)
    assert triangle_set(mine.vertices[mine.faces]) == triangle_set(v[f])
    assert mine.volume == pytest.approx(solid.manifold.volume(), rel=1e-12)
    # the solid's volume from its first layer (rotorcad.solids.twisted_volume) and the side normals
    # turned from the first layer's: manifold3d's volume, and the cross product of every triangle
    assert solid.volume == pytest.approx(solid.manifold.volume(), rel=1e-12)
    assert np.abs(mine.face_normals - face_normals(mine.vertices, mine.faces)).max() < 1e-9
    t = mine.to_trimesh()
    assert t.is_watertight and t.is_winding_consistent and t.volume > 0
    # normals point out: the mean of normal . (centroid - axis) over the side faces is positive
    c = t.triangles_center
    assert np.mean(np.einsum("ij,ij->i", mine.face_normals[:, :2], c[:, :2])) > 0


def test_a_spur_gear_is_a_straight_extrusion():
    outline = np.column_stack(
        [np.cos(np.linspace(0, 2 * np.pi, 50, endpoint=False)), np.sin(np.linspace(0, 2 * np.pi, 50, endpoint=False))]
    )
    solid = helical_gear_solid(10 * outline, 10.0, 0.0, 5.0, 0.01)
    assert solid.layers == 1 and solid.wrap == 0.0
    assert solid.volume == pytest.approx(solid.manifold.volume(), rel=1e-12)
    # a prism: area times width (manifold3d's cross-section rounds the contour's coordinates to ~1e-8 mm)
    assert solid.volume == pytest.approx(solid.nominal_volume, rel=1e-9)


def test_a_ring_section_with_its_hole_keeps_manifold3ds_volume_and_normals():
    # an internal gear's section is a ring: the hole is swept too (clockwise), its layers' volume
    # counts it out; reference: manifold3d's volume and the cross products of the triangles
    t = np.linspace(0, 2 * np.pi, 90, endpoint=False)
    wobble = 30 + 2 * np.cos(7 * t)
    ring = shapely.Polygon(
        np.column_stack([40 * np.cos(t), 40 * np.sin(t)]), [np.column_stack([wobble * np.cos(t), wobble * np.sin(t)])]
    )
    solid = helical_solid(ring, -150.0, 25.0, 0.05)
    assert len(solid.contours) == 2 and solid.layers > 1
    mesh = solid.triangle_mesh
    assert solid.volume == pytest.approx(solid.manifold.volume(), rel=1e-12)
    assert solid.volume == pytest.approx(mesh.volume, rel=1e-12)
    assert np.abs(mesh.face_normals - face_normals(mesh.vertices, mesh.faces)).max() < 1e-9

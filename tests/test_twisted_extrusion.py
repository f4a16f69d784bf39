"""The swept solids' triangles, made by numpy (rotorcad.solids.twisted_extrusion), against manifold3d.

Reference: manifold3d's own ``Manifold.extrude`` with the same layers and twist (what
``HelicalSolid.manifold`` makes, and what the meshes were before): the same triangles (as sets of
corner coordinates, to 1e-7 mm) and the same volume; trimesh (a third-party reader) finds the numpy
mesh watertight and consistently wound, with its normals pointing out.
"""

from __future__ import annotations

import numpy as np
import pytest

from rotorcad.rotor_families import build_family
from rotorcad.rotor_pair import RotorPair
from rotorcad.solids import helical_gear_solid, helical_solid

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

"""A triangle mesh as plain numpy arrays: what the mesh writers need, without trimesh.

Importing trimesh costs about a second (it pulls scipy.spatial and networkx); STL, OBJ and PLY are
written from these arrays by numpy alone (:mod:`exports.meshes`). :meth:`TriangleMesh.to_trimesh`
gives a :class:`trimesh.Trimesh` for what trimesh is good at (3MF, GLB, checks).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

if TYPE_CHECKING:
    import trimesh


def face_normals(vertices: np.ndarray, faces: np.ndarray) -> np.ndarray:
    """Return the unit normals of the triangles (right-hand rule on the vertex order).

    Parameters
    ----------
    vertices : (n, 3) float array, mm
        Vertices.
    faces : (m, 3) int array
        Vertex indices of each triangle.

    Returns
    -------
    (m, 3) float array
        (b - a) x (c - a) normalised, by components (a few times faster than ``np.cross``).
    """
    a, b, c = vertices[faces[:, 0]], vertices[faces[:, 1]], vertices[faces[:, 2]]
    u, w = b - a, c - a
    n = np.empty_like(u)
    n[:, 0] = u[:, 1] * w[:, 2] - u[:, 2] * w[:, 1]
    n[:, 1] = u[:, 2] * w[:, 0] - u[:, 0] * w[:, 2]
    n[:, 2] = u[:, 0] * w[:, 1] - u[:, 1] * w[:, 0]
    n /= np.sqrt(np.einsum("ij,ij->i", n, n))[:, None]
    return n


@dataclass(eq=False)
class TriangleMesh:
    """A closed triangle mesh, float64.

    Parameters
    ----------
    vertices : (n, 3) float array, mm
        Vertices.
    faces : (m, 3) int array
        Vertex indices of each triangle, counter-clockwise seen from outside.
    face_normals : (m, 3) float array, optional
        Unit outward normals (computed when not given).
    """

    vertices: np.ndarray
    faces: np.ndarray
    face_normals: np.ndarray | None = None

    def __post_init__(self) -> None:
        self.vertices = np.require(self.vertices, dtype=float, requirements="W")  # moved in place (manifold3d's are read-only)
        self.faces = np.asarray(self.faces)
        if self.face_normals is None:
            self.face_normals = face_normals(self.vertices, self.faces)

    @property
    def triangles(self) -> np.ndarray:
        """(m, 3, 3) float array, mm: the corners of every triangle."""
        return self.vertices[self.faces]

    @property
    def volume(self) -> float:
        """Enclosed volume, mm³: the sum of a . (b x c) / 6 over the triangles (divergence theorem)."""
        a, b, c = (self.vertices[self.faces[:, q]] for q in range(3))
        # relative to the centroid of the vertices, so that a far placement loses no digits
        o = self.vertices.mean(axis=0)
        a, b, c = a - o, b - o, c - o
        cx = b[:, 1] * c[:, 2] - b[:, 2] * c[:, 1]
        cy = b[:, 2] * c[:, 0] - b[:, 0] * c[:, 2]
        cz = b[:, 0] * c[:, 1] - b[:, 1] * c[:, 0]
        return float((a[:, 0] * cx + a[:, 1] * cy + a[:, 2] * cz).sum() / 6.0)

    def apply_translation(self, offset) -> TriangleMesh:
        """Move the mesh in place by ``offset`` (3 floats, mm) and return it (as trimesh does)."""
        self.vertices += np.asarray(offset, dtype=float)
        return self

    def copy(self) -> TriangleMesh:
        """Return a copy with its own arrays."""
        return TriangleMesh(self.vertices.copy(), self.faces.copy(), self.face_normals.copy())

    def to_trimesh(self) -> trimesh.Trimesh:
        """Return the mesh as a :class:`trimesh.Trimesh` (imports trimesh, about a second the first time)."""
        import trimesh

        return trimesh.Trimesh(self.vertices, self.faces, face_normals=self.face_normals, process=False)

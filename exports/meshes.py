"""Mesh files: STL (binary and ASCII), OBJ and PLY by numpy; 3MF and GLB with trimesh; VTU and XDMF with meshio.

Every writer takes a float64 mesh: a :class:`rotorcad.triangle_mesh.TriangleMesh` or a
:class:`trimesh.Trimesh` (anything with ``vertices`` and ``faces``). STL, OBJ and PLY are written
from the arrays here, so that an export of those formats never imports trimesh (about a second) or
meshio; their layout is trimesh's own (binary STL: an 80-byte header, a little-endian uint32 count,
then per triangle 12 float32 and a uint16 0; PLY: binary little endian, float32 vertices, uchar/int
faces). Binary STL, PLY and GLB store float32 coordinates (measured), so their volumes read back
to about 1e-7 relative.
"""

from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from rotorcad.triangle_mesh import TriangleMesh, face_normals

if TYPE_CHECKING:
    import trimesh

    from exports.formats import ExportFormat, Writer
    from rotorcad.assembly import PlacedBody

TRIMESH_FORMATS = {"stl": "stl", "stl-ascii": "stl_ascii", "3mf": "3mf", "obj": "obj", "ply": "ply", "glb": "glb"}
MESHIO_FORMATS = {"vtu": "vtu", "xdmf": "xdmf"}
MESH_FORMATS = tuple(TRIMESH_FORMATS) + tuple(MESHIO_FORMATS)
NUMPY_FORMATS = ("stl", "stl-ascii", "obj", "ply")  # written here from the arrays, without trimesh
EXTENSIONS = {
    "stl": ".stl",
    "stl-ascii": "_ascii.stl",  # not the binary STL's name: both may be written at once
    "3mf": ".3mf",
    "obj": ".obj",
    "ply": ".ply",
    "glb": ".glb",
    "vtu": ".vtu",
    "xdmf": ".xdmf",
}
_STL_TRIANGLE = np.dtype([("normals", "<f4", (3,)), ("vertices", "<f4", (3, 3)), ("attributes", "<u2")])
_PLY_FACE = np.dtype([("count", "u1"), ("indices", "<i4", (3,))])


def _normals(mesh) -> np.ndarray:
    """Return the mesh's unit face normals (its own when it has them)."""
    n = getattr(mesh, "face_normals", None)
    return np.asarray(n, dtype=float) if n is not None else face_normals(np.asarray(mesh.vertices, dtype=float), mesh.faces)


STL_CHUNK = 1 << 16
"""Triangles packed and written at a time by :func:`write_stl` (3.3 MB, one buffer used again)."""


def write_stl(path: Path, mesh) -> None:
    """Write a binary STL: 80-byte header, uint32 triangle count, 50 bytes per triangle (float32).

    The vertices are rounded to float32 once and gathered straight into the packed triangles (the
    same bytes as gathering the float64 corners and rounding them), :data:`STL_CHUNK` triangles at
    a time into one buffer, each part written from it without a copy: a rotor's 24 MB file is not
    held in memory a second time.
    """
    faces = np.asarray(mesh.faces)
    normals = _normals(mesh)
    vertices = np.asarray(mesh.vertices, dtype="<f4")
    packed = np.empty(min(len(faces), STL_CHUNK), dtype=_STL_TRIANGLE)
    packed["attributes"] = 0
    with open(path, "wb") as f:
        f.write(bytes(80))
        f.write(np.uint32(len(faces)).astype("<u4").tobytes())
        for start in range(0, len(faces), STL_CHUNK):
            part = packed[: min(STL_CHUNK, len(faces) - start)]
            part["normals"] = normals[start : start + len(part)]
            np.take(vertices, faces[start : start + len(part)], axis=0, out=part["vertices"])  # a bad index raises
            f.write(memoryview(part).cast("B"))


def _rows(fmt: str, values: np.ndarray) -> str:
    """Format the rows of a 2-D array with one %-format line each, in one string operation."""
    return (fmt * len(values)) % tuple(values.ravel().tolist())


def write_stl_ascii(path: Path, mesh) -> None:
    """Write an ASCII STL, full float64 precision (``repr`` of every coordinate)."""
    faces = np.asarray(mesh.faces)
    blob = np.empty((len(faces), 4, 3))
    blob[:, 0] = _normals(mesh)
    blob[:, 1:] = np.asarray(mesh.vertices, dtype=float)[faces]
    facet = "facet normal %r %r %r\nouter loop\nvertex %r %r %r\nvertex %r %r %r\nvertex %r %r %r\nendloop\nendfacet\n"
    with open(path, "w") as f:
        f.write("solid \n")
        f.write(_rows(facet, blob.reshape(len(faces), 12)))
        f.write("endsolid\n")


def write_obj(path: Path, mesh) -> None:
    """Write a Wavefront OBJ: ``v`` lines (8 decimals, as trimesh) and 1-based ``f`` lines."""
    with open(path, "w") as f:
        f.write("# rotorcad\n")
        f.write(_rows("v %.8f %.8f %.8f\n", np.asarray(mesh.vertices, dtype=float)))
        f.write(_rows("f %d %d %d\n", np.asarray(mesh.faces, dtype=np.int64) + 1))


def write_ply(path: Path, mesh) -> None:
    """Write a binary little-endian PLY with float32 vertices and triangle faces."""
    vertices = np.asarray(mesh.vertices, dtype="<f4")
    faces = np.asarray(mesh.faces)
    packed = np.empty(len(faces), dtype=_PLY_FACE)
    packed["count"] = 3
    packed["indices"] = faces
    header = (
        "ply\nformat binary_little_endian 1.0\ncomment rotorcad\n"
        f"element vertex {len(vertices)}\nproperty float x\nproperty float y\nproperty float z\n"
        f"element face {len(faces)}\nproperty list uchar int vertex_indices\nend_header\n"
    )
    with open(path, "wb") as f:
        f.write(header.encode("ascii"))
        f.write(np.ascontiguousarray(vertices).tobytes())
        f.write(packed.tobytes())


_NUMPY_WRITERS = {"stl": write_stl, "stl-ascii": write_stl_ascii, "obj": write_obj, "ply": write_ply}


def write_mesh(path: Path, mesh: TriangleMesh | trimesh.Trimesh, fmt: str) -> None:
    """Write a mesh in one of :data:`MESH_FORMATS`.

    Parameters
    ----------
    path : Path
        The file.
    mesh : TriangleMesh or trimesh.Trimesh
        The mesh, float64, mm.
    fmt : str
        One of :data:`MESH_FORMATS`: STL, OBJ and PLY by numpy, 3MF and GLB by trimesh, VTU and
        XDMF by meshio (XDMF with its data inline, no HDF5 file beside it).

    Raises
    ------
    ValueError
        An unknown format.
    """
    if fmt in _NUMPY_WRITERS:
        _NUMPY_WRITERS[fmt](path, mesh)
    elif fmt in TRIMESH_FORMATS:
        if isinstance(mesh, TriangleMesh):
            mesh = mesh.to_trimesh()
        data = mesh.export(file_type=TRIMESH_FORMATS[fmt])
        mode = "w" if isinstance(data, str) else "wb"
        with open(path, mode) as f:
            f.write(data)
    elif fmt in MESHIO_FORMATS:
        import meshio

        m = meshio.Mesh(np.asarray(mesh.vertices, dtype=float), [("triangle", np.asarray(mesh.faces, dtype=np.int64))])
        # XDMF with its data inline (XML), so that no HDF5 file is left beside it under the
        # temporary name it was written to
        extra = {"data_format": "XML"} if fmt == "xdmf" else {}
        meshio.write(str(path), m, file_format=MESHIO_FORMATS[fmt], **extra)
    else:
        raise ValueError(f"unknown mesh format {fmt}")


def read_mesh(path: Path, fmt: str) -> trimesh.Trimesh:
    """Read a mesh back (trimesh or meshio), merging duplicate vertices for a watertight check.

    Parameters
    ----------
    path : Path
        The file.
    fmt : str
        One of :data:`MESH_FORMATS`.

    Returns
    -------
    trimesh.Trimesh
    """
    import trimesh

    if fmt in MESHIO_FORMATS:
        import meshio

        m = meshio.read(str(path))
        faces = np.vstack([c.data for c in m.cells if c.type == "triangle"])
        mesh = trimesh.Trimesh(m.points[:, :3], faces, process=True)
    else:
        loaded = trimesh.load(str(path), file_type=TRIMESH_FORMATS[fmt].split("_")[0], force="mesh", process=True)
        mesh = loaded
    mesh.merge_vertices()
    return mesh


def _plan_mesh(fmt: ExportFormat, body: PlacedBody, tolerance: float, row: dict[str, Any]) -> Writer:
    """Plan a mesh file: the solid is swept when first written (:meth:`rotorcad.assembly.PlacedBody.mesh`)."""
    from exports.formats import meshed

    row.update(triangles=0, volume=body.section_volume)

    def write(path: Path) -> None:
        write_mesh(path, meshed(fmt, body, tolerance, row).mesh, fmt.name)

    return write


def _register() -> None:
    from exports.formats import ExportFormat, register

    for name in MESH_FORMATS:
        register(
            ExportFormat(
                name,
                EXTENSIONS[name],
                _plan_mesh,
                "the surface tolerance asked: the swept solid's layers and the section's chords (the row gives the "
                "solid's own); the housing's, the sag of the bores' chords",
            )
        )


_register()

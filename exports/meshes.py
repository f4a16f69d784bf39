"""Mesh files: STL (binary and ASCII), 3MF, OBJ, PLY, GLB with trimesh; VTU and XDMF with meshio.

Every writer takes a float64 :class:`trimesh.Trimesh`. PLY and GLB store float32 coordinates
(measured), so their volumes read back to about 1e-7 relative.
"""

from __future__ import annotations

from pathlib import Path

import meshio
import numpy as np
import trimesh

TRIMESH_FORMATS = {"stl": "stl", "stl-ascii": "stl_ascii", "3mf": "3mf", "obj": "obj", "ply": "ply", "glb": "glb"}
MESHIO_FORMATS = {"vtu": "vtu", "xdmf": "xdmf"}
MESH_FORMATS = tuple(TRIMESH_FORMATS) + tuple(MESHIO_FORMATS)
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


def write_mesh(path: Path, mesh: trimesh.Trimesh, fmt: str) -> None:
    """Write a mesh in one of :data:`MESH_FORMATS`.

    Parameters
    ----------
    path : Path
        The file.
    mesh : trimesh.Trimesh
        The mesh, float64, mm.
    fmt : str
        One of :data:`MESH_FORMATS` (XDMF is written with its data inline, no HDF5 file beside it).

    Raises
    ------
    ValueError
        An unknown format.
    """
    if fmt in TRIMESH_FORMATS:
        data = mesh.export(file_type=TRIMESH_FORMATS[fmt])
        mode = "w" if isinstance(data, str) else "wb"
        with open(path, mode) as f:
            f.write(data)
    elif fmt in MESHIO_FORMATS:
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
    if fmt in MESHIO_FORMATS:
        m = meshio.read(str(path))
        faces = np.vstack([c.data for c in m.cells if c.type == "triangle"])
        mesh = trimesh.Trimesh(m.points[:, :3], faces, process=True)
    else:
        loaded = trimesh.load(str(path), file_type=TRIMESH_FORMATS[fmt].split("_")[0], force="mesh", process=True)
        mesh = loaded
    mesh.merge_vertices()
    return mesh

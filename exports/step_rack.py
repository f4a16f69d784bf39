"""Exact STEP of a gear rack (:class:`rotorcad.gears.rack.GearRack`): planes and elliptic cylinders.

The section is built from the rack's exact pieces (:meth:`~rotorcad.gears.rack.GearRack.pieces`:
straight edges and the root fillets as arcs of ellipses, circles for a spur rack) and extruded by
OpenCASCADE along the oblique vector (b tan(beta), 0, b): a prism whose section at z is shifted by
z tan(beta), the helical rack exactly (its flanks planes, its fillets elliptic cylinders cut
obliquely, i.e. circular cylinders along the teeth). The periods are extruded a pitch beyond both
ends and cut by the prism of the box 0 <= x <= L on the same vector, as the meshes are.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

import numpy as np

from exports.ocp_messages import quiet_ocp


def rack_shape(rack: Any, face_width: float) -> Any:
    """Return the rack's solid as an OpenCASCADE shape, mm (frame of :mod:`rotorcad.gears.rack`).

    Parameters
    ----------
    rack : GearRack
        The rack.
    face_width : float, mm
        Across the face (z).

    Returns
    -------
    OCP.TopoDS.TopoDS_Shape
        One solid.
    """
    from OCP.BRepAlgoAPI import BRepAlgoAPI_Common
    from OCP.BRepBuilderAPI import BRepBuilderAPI_MakeEdge, BRepBuilderAPI_MakeFace, BRepBuilderAPI_MakeWire
    from OCP.BRepPrimAPI import BRepPrimAPI_MakePrism
    from OCP.gp import gp_Ax2, gp_Circ, gp_Dir, gp_Elips, gp_Pnt, gp_Vec

    quiet_ocp()

    def point(x: float, y: float) -> gp_Pnt:
        return gp_Pnt(float(x), float(y), 0.0)

    def polygon_face(edges: list) -> Any:
        wire = BRepBuilderAPI_MakeWire()
        for e in edges:
            wire.Add(e)
        return BRepBuilderAPI_MakeFace(wire.Wire(), True).Face()

    def line(a: tuple[float, float], b: tuple[float, float]) -> Any:
        return BRepBuilderAPI_MakeEdge(point(*a), point(*b)).Edge()

    edges = []
    for piece in rack.pieces():
        if piece[0] == "line":
            edges.append(line(piece[1], piece[2]))
            continue
        _, (cx, cy), major, minor, t0, t1 = piece
        axes = gp_Ax2(point(cx, cy), gp_Dir(0.0, 0.0, 1.0), gp_Dir(1.0, 0.0, 0.0))
        curve = gp_Circ(axes, float(minor)) if abs(major - minor) <= 1e-12 * major else gp_Elips(axes, float(major), float(minor))
        edges.append(BRepBuilderAPI_MakeEdge(curve, float(t0), float(t1)).Edge())
    first, last = rack.pieces()[0][1], rack.pieces()[-1][2]
    bottom = -rack.back_height - 1.0
    edges += [line(last, (last[0], bottom)), line((last[0], bottom), (first[0], bottom)), line((first[0], bottom), first)]
    top = rack.addendum * rack.module + 1.0
    corners = [(0.0, -rack.back_height), (rack.length, -rack.back_height), (rack.length, top), (0.0, top)]
    box = [line(corners[i], corners[(i + 1) % 4]) for i in range(4)]
    along = gp_Vec(float(face_width * np.tan(rack.helix_angle)), 0.0, float(face_width))
    teeth = BRepPrimAPI_MakePrism(polygon_face(edges), along).Shape()
    ends = BRepPrimAPI_MakePrism(polygon_face(box), along).Shape()
    common = BRepAlgoAPI_Common(teeth, ends)
    common.Build()
    if not common.IsDone():
        raise ValueError("OpenCASCADE could not cut the rack to its length")
    return common.Shape()


def write_rack_step(path: Path, rack: Any, face_width: float, body: str = "rack") -> dict[str, float]:
    """Write the rack's exact solid as STEP AP214, mm.

    Parameters
    ----------
    path : Path
        The file.
    rack : GearRack
        The rack.
    face_width : float, mm
        Across the face.
    body : str
        The product name in the file.

    Returns
    -------
    dict
        ``faces`` (their number).

    Raises
    ------
    OSError
        When OpenCASCADE cannot write the file.
    """
    from exports.step_exact import faces, write_shape

    shape = rack_shape(rack, face_width)
    write_shape(path, shape, body)
    count = len(faces(shape))
    return {"faces": float(count)}


__all__ = ["rack_shape", "write_rack_step"]

"""Exact STEP of a gear as a part: helical or herringbone teeth, bore, DIN 6885-1 keyway, hub.

The teeth are the section swept along its helix (:func:`exports.step_exact.helical_solid`, one face
per piece of the section: involute, fillet, root arc, tip arc and the tip chamfer or rounding).
A herringbone gear is made of two halves without a boolean: the faces of the half from z = 0 to
b/2, and the same faces mirrored in the plane z = b/2 (an exact transformation), are sewn into one
shell with the two end faces, the mid plane's faces left out (a boolean fuse of the two halves took
138 s for 17 teeth, sewing 0.2 s, measured). The hub (a cylinder from z = -hub_length to 0) is
joined and the bore with its keyway (a circular arc and three lines, extruded straight along the
axis) cut by OpenCASCADE's booleans, whose faces are planes and cylinders: one face each.

Before the bore and hub are added, the teeth's faces are checked against the exact helicoid
(:func:`exports.step_exact.helicoid_deviation`; for a herringbone gear on the first half, of which
the second is an exact mirror image) and refused beyond the tolerance.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

import numpy as np

from exports.ocp_messages import quiet_ocp
from exports.step_exact import SectionSegment, StepDeviationError, faces, helical_solid, helicoid_deviation
from rotorcad.gears.features import SolidFeatures


def _is_cap(face: Any, z: float) -> bool:
    """Whether a face lies in the plane z (samples of its surface over its parameter range)."""
    from OCP.BRep import BRep_Tool
    from OCP.BRepTools import BRepTools

    u0, u1, v0, v1 = BRepTools.UVBounds_s(face)
    surface = BRep_Tool.Surface_s(face)
    zs = [surface.Value(u, v).Z() for u in np.linspace(u0, u1, 3) for v in np.linspace(v0, v1, 3)]
    return max(abs(q - z) for q in zs) <= 1e-9 * max(abs(z), 1.0)


def as_solid(shape: Any) -> Any:
    """Return the one solid of a shape as ``TopoDS_Solid`` (a compound of one solid unwrapped).

    Raises
    ------
    ValueError
        A shape of no solid or of several.
    """
    from OCP.TopAbs import TopAbs_SOLID
    from OCP.TopExp import TopExp_Explorer
    from OCP.TopoDS import TopoDS

    found, explorer = [], TopExp_Explorer(shape, TopAbs_SOLID)
    while explorer.More():
        found.append(explorer.Current())
        explorer.Next()
    if len(found) != 1:
        raise ValueError(f"OpenCASCADE made {len(found)} solids where one was expected")
    return TopoDS.Solid(found[0])


def herringbone_solid(half: Any, face_width: float) -> Any:
    """Sew the half from z = 0 to b/2 and its mirror image in z = b/2 into one solid.

    Parameters
    ----------
    half : OCP.TopoDS.TopoDS_Shape
        The helical half, z from 0 to ``face_width / 2``.
    face_width : float, mm
        b.

    Returns
    -------
    OCP.TopoDS.TopoDS_Solid
    """
    from OCP.BRepBuilderAPI import BRepBuilderAPI_MakeSolid, BRepBuilderAPI_Sewing, BRepBuilderAPI_Transform
    from OCP.BRepLib import BRepLib
    from OCP.gp import gp_Ax2, gp_Dir, gp_Pnt, gp_Trsf
    from OCP.TopoDS import TopoDS

    mirror = gp_Trsf()
    mirror.SetMirror(gp_Ax2(gp_Pnt(0.0, 0.0, 0.5 * face_width), gp_Dir(0.0, 0.0, 1.0)))
    other = BRepBuilderAPI_Transform(half, mirror, True).Shape()
    sewing = BRepBuilderAPI_Sewing(1e-7)
    for shape in (half, other):
        for face in faces(shape):
            if not _is_cap(face, 0.5 * face_width):
                sewing.Add(face)
    sewing.Perform()
    solid = BRepBuilderAPI_MakeSolid(TopoDS.Shell(sewing.SewedShape())).Solid()
    BRepLib.OrientClosedSolid_s(solid)
    return solid


def _hole_prism(features: SolidFeatures, z0: float, z1: float) -> Any:
    """Return the bore with its keyway as a straight prism from z0 to z1 (exact: an arc and three lines)."""
    from OCP.BRepBuilderAPI import BRepBuilderAPI_MakeEdge, BRepBuilderAPI_MakeFace, BRepBuilderAPI_MakeWire
    from OCP.BRepPrimAPI import BRepPrimAPI_MakeCylinder, BRepPrimAPI_MakePrism
    from OCP.GC import GC_MakeArcOfCircle, GC_MakeSegment
    from OCP.gp import gp_Ax2, gp_Dir, gp_Pnt, gp_Vec

    r, b = features.bore_radius, features.key_width
    if b <= 0:
        return BRepPrimAPI_MakeCylinder(gp_Ax2(gp_Pnt(0.0, 0.0, z0), gp_Dir(0.0, 0.0, 1.0)), r, z1 - z0).Shape()
    c, s = np.cos(features.turn), np.sin(features.turn)

    def point(x: float, y: float) -> gp_Pnt:
        return gp_Pnt(float(c * x - s * y), float(s * x + c * y), float(z0))

    xc, bottom = features.keyway_corner_x, features.key_bottom
    start, end, far = point(xc, 0.5 * b), point(xc, -0.5 * b), point(-r, 0.0)
    edges = [
        GC_MakeArcOfCircle(start, far, end).Value(),  # the bore, counter-clockwise round the back
        GC_MakeSegment(end, point(bottom, -0.5 * b)).Value(),
        GC_MakeSegment(point(bottom, -0.5 * b), point(bottom, 0.5 * b)).Value(),
        GC_MakeSegment(point(bottom, 0.5 * b), start).Value(),
    ]
    wire = BRepBuilderAPI_MakeWire()
    for curve in edges:
        wire.Add(BRepBuilderAPI_MakeEdge(curve).Edge())
    face = BRepBuilderAPI_MakeFace(wire.Wire(), True).Face()
    return BRepPrimAPI_MakePrism(face, gp_Vec(0.0, 0.0, float(z1 - z0))).Shape()


def add_features(teeth: Any, face_width: float, features: SolidFeatures) -> Any:
    """Join the hub to the teeth and cut the bore with its keyway (OpenCASCADE booleans).

    Parameters
    ----------
    teeth : OCP.TopoDS.TopoDS_Shape
        The toothed solid, z from 0 to ``face_width``.
    face_width : float, mm
        b.
    features : SolidFeatures
        Hub and bore.

    Returns
    -------
    OCP.TopoDS.TopoDS_Solid
    """
    from OCP.BRepAlgoAPI import BRepAlgoAPI_Cut, BRepAlgoAPI_Fuse
    from OCP.BRepPrimAPI import BRepPrimAPI_MakeCylinder
    from OCP.gp import gp_Ax2, gp_Dir, gp_Pnt

    shape = teeth
    if features.hub_radius > 0:
        axes = gp_Ax2(gp_Pnt(0.0, 0.0, -features.hub_length), gp_Dir(0.0, 0.0, 1.0))
        hub = BRepPrimAPI_MakeCylinder(axes, features.hub_radius, features.hub_length).Shape()
        shape = _boolean(BRepAlgoAPI_Fuse(shape, hub), "join the hub")
    if features.bore_radius > 0:
        hole = _hole_prism(features, -features.hub_length - 1.0, face_width + 1.0)
        shape = _boolean(BRepAlgoAPI_Cut(shape, hole), "cut the bore")
    return as_solid(shape)


def _boolean(op: Any, what: str) -> Any:
    op.Build()
    if not op.IsDone():
        raise ValueError(f"OpenCASCADE could not {what}")
    return op.Shape()


def gear_part_shape(
    segments: list[SectionSegment],
    lead: float,
    face_width: float,
    tolerance: float,
    features: SolidFeatures,
    exact: np.ndarray | None = None,
) -> tuple[Any, float | None]:
    """Make the gear part's exact solid; measure its teeth's faces against the helicoid.

    Parameters
    ----------
    segments : list of SectionSegment
        The section (:func:`exports.step_exact.section_segments`), turned into mesh.
    lead : float, mm
        Signed lead; inf for a spur gear (a herringbone gear is never spur).
    face_width : float, mm
        b.
    tolerance : float, mm
        Largest deviation of the teeth's faces from the helicoid accepted (with ``exact``).
    features : SolidFeatures
        Bore, keyway, hub, herringbone.
    exact : (n, 2) float array, mm, optional
        The section as a fine closed polyline, for the check.

    Returns
    -------
    solid : OCP.TopoDS.TopoDS_Solid
    deviation : float or None, mm
        The largest distance of the teeth's faces from the helicoid (None without ``exact``).

    Raises
    ------
    StepDeviationError
        Faces farther than ``tolerance`` from the helicoid.
    """
    quiet_ocp()
    half = face_width / 2 if features.herringbone else face_width
    teeth = helical_solid(segments, lead, half, tolerance)
    deviation = None
    if exact is not None:
        deviation = helicoid_deviation(teeth, exact, lead, half)
        if deviation > tolerance:
            raise StepDeviationError(
                f"the STEP surface is {deviation * 1e3:.2f} um from the helicoid, more than the tolerance {tolerance * 1e3:g} um"
            )
    if features.herringbone:
        teeth = herringbone_solid(teeth, face_width)
    return add_features(teeth, face_width, features), deviation


def write_gear_part_step(
    path: Path,
    sections: list[list[SectionSegment]],
    lead: float,
    face_width: float,
    tolerance: float,
    body: str,
    offset: tuple[float, float],
    exact: np.ndarray,
    features: SolidFeatures,
) -> dict[str, float]:
    """Write the gear part as STEP from the first of ``sections`` whose faces are within the tolerance.

    As :func:`exports.step.write_exact_step_refined` (sections sampled ever finer), with the part's
    features (:func:`gear_part_shape`). Module level, so that the worker process can run it.

    Returns
    -------
    dict
        ``faces`` (their number) and ``deviation`` (mm).
    """
    from exports.step_exact import write_shape

    for i, segments in enumerate(sections):
        try:
            solid, deviation = gear_part_shape(segments, lead, face_width, tolerance, features, exact)
            break
        except StepDeviationError:
            if i == len(sections) - 1:
                raise
    write_shape(path, solid, body, offset)
    return {"faces": float(len(faces(solid))), "deviation": float(deviation)}


__all__ = ["add_features", "as_solid", "gear_part_shape", "herringbone_solid", "write_gear_part_step"]

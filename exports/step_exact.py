"""Exact STEP of a helical rotor or gear: the section swept along its helix by OpenCASCADE.

One face per profile segment. Each segment of the transverse section becomes one edge: a straight
segment a line, a circular arc a circle (through its ends and its middle), every other curve
(involute, trochoid, generated conjugate, spline) a B-spline interpolating its samples with their
exact unit tangents (``GeomAPI_Interpolate`` with a tangent at every point: a C1 Hermite-type fit
whose error falls with the fourth power of the spacing). The edges meet at the segments' ends, so
a sharp corner stays a corner. The wire is swept along the axis with an auxiliary helix on a
cylinder (``BRepOffsetAPI_MakePipeShell``, measured), so that every point turns by 2 pi z / h
at height z, and closed into a solid: each segment gives one face, the faces a grinding or CMM
program names.

The samples are the caller's (the export samples the section to ten times the tolerance in chord);
given the tolerance, :func:`section_segments` adds samples on the exact curve where the Hermite
cubic between two of them would be off by more than a quarter of it (a chord tolerance does not
bound that cubic where the curve bends sharply, at an involute's cusp). :func:`helicoid_deviation`
checks the result: it samples every face's surface, at the middle of every knot span too, turns
each point back by -2 pi z / h and measures its distance to the exact section, and
:func:`write_exact_step` refuses a solid off by more than the tolerance.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import numpy as np

from exports.hermite import refine_curves
from exports.ocp_messages import quiet_ocp
from rotorcad.geometry import rotate


class StepDeviationError(ValueError):
    """The swept faces lie farther from the exact helicoid than the tolerance.

    The samples of the section are too sparse for the B-spline fit.
    """


@dataclass(frozen=True)
class SectionSegment:
    """One segment of a closed counter-clockwise section.

    Parameters
    ----------
    name : str
        The segment's name (e.g. "tip arc").
    points : (n, 2) float array, mm
        Samples.
    tangents : (n, 2) float array
        Their exact unit tangents.
    kind : {"line", "arc", "curve"}
        What the segment is.
    center : (float, float), mm, optional
        Centre of an arc.
    """

    name: str
    points: np.ndarray
    tangents: np.ndarray
    kind: str = "curve"
    center: tuple[float, float] | None = None


def section_segments(profile, turn: float = 0.0, tolerance: float | None = None) -> list[SectionSegment]:
    """Return the segments of a :class:`rotorcad.profile.Profile` turned by ``turn``.

    A straight segment is a line and a circular arc (its curve has a centre, and is not a corner of
    zero radius) an arc, the rest curves. With ``tolerance``, the samples of a curve are refined on
    its exact curve until the Hermite cubic between every two neighbours (the B-spline
    :func:`helical_solid` makes) lies within :data:`HERMITE_SHARE` of it (:func:`_hermite_samples`):
    a chord tolerance alone does not bound that cubic where the curve bends sharply.

    Parameters
    ----------
    profile : Profile
        A closed counter-clockwise section.
    turn : float, rad
        Counter-clockwise turn about the origin.
    tolerance : float, mm, optional
        The STEP tolerance; None keeps the profile's samples as they are.

    Returns
    -------
    list of SectionSegment
    """
    from rotorcad.curves import Line

    kinds, centres = [], []
    for seg in profile.segments:
        centre = seg.curve.arc_center()
        arc = centre is not None and not seg.curve.is_corner()
        kinds.append("line" if isinstance(seg.curve, Line) else "arc" if arc else "curve")
        centres.append(centre)
    samples = [(seg.points, seg.tangents) for seg in profile.segments]
    if tolerance is not None:  # every curve's samples refined at once (exports.hermite.refine_curves)
        refined = [i for i, seg in enumerate(profile.segments) if kinds[i] == "curve" and len(seg.points) >= 2]
        found = _hermite_samples([profile.segments[i] for i in refined], HERMITE_SHARE * tolerance)
        for i, refined_samples in zip(refined, found, strict=True):
            samples[i] = refined_samples
    out = []
    for seg, kind, centre, (points, tangents) in zip(profile.segments, kinds, centres, samples, strict=True):
        out.append(
            SectionSegment(
                seg.name,
                rotate(points, turn),
                rotate(tangents, turn),
                kind,
                None if centre is None else tuple(rotate(centre, turn)[0]),
            )
        )
    return out


HERMITE_SHARE = 0.25
"""Share of the STEP tolerance left to the Hermite cubic between two samples of a curve; the rest is
the sweep's and the check's own (its exact polyline is sampled to a hundredth of the tolerance)."""


def _hermite_samples(segments: list, budget: float, passes: int = 8) -> list[tuple[np.ndarray, np.ndarray]]:
    """Refine segments' samples until the Hermite cubic between neighbours is within ``budget`` of their curves.

    Between samples p0, p1 with unit tangents t0, t1, ``GeomAPI_Interpolate`` (chord-length
    parameters, tangents scaled to them) makes the cubic Hermite interpolant of
    :func:`exports.hermite.hermite_cubic`; the samples are refined by the DXF spline's rule and
    measure (:func:`exports.hermite.refine_curves`, all the segments at once), so that both files
    hold the same cubic to the same check.

    Parameters
    ----------
    segments : list of rotorcad.profile.Segment
        Each with samples ``s``, ``points``, ``tangents`` (unit, along the travel) of its exact ``curve``.
    budget : float, mm
        Largest error of the cubic between two samples.
    passes : int
        Most refinement passes.

    Returns
    -------
    list of (points, tangents) : (n, 2) float arrays
        Every segment's refined samples (the old ones among them), in order; a segment of fewer
        than two samples as it is.
    """
    out = [(np.asarray(seg.points, dtype=float), np.asarray(seg.tangents, dtype=float)) for seg in segments]
    refined = [i for i, seg in enumerate(segments) if len(seg.s) >= 2]
    pieces = [(segments[i].curve, segments[i].s, segments[i].points, segments[i].tangents) for i in refined]
    for i, (_, p, t, _) in zip(refined, refine_curves(pieces, budget, passes, exact=False), strict=True):
        out[i] = (p, t)
    return out


def _edge(segment: SectionSegment, tolerance: float):
    """Make the OpenCASCADE edge of one segment (see the module docstring).

    ``tolerance`` is not used: the samples are interpolated as they are. A curve of two samples is
    the Hermite cubic of its ends, not their chord.
    """
    from OCP.BRepBuilderAPI import BRepBuilderAPI_MakeEdge
    from OCP.collections import Array1_gp_Vec, HArray1_bool, HArray1_gp_Pnt
    from OCP.GC import GC_MakeArcOfCircle, GC_MakeSegment
    from OCP.GeomAPI import GeomAPI_Interpolate
    from OCP.gp import gp_Pnt, gp_Vec

    p, t = segment.points, segment.tangents
    first, last = gp_Pnt(float(p[0, 0]), float(p[0, 1]), 0.0), gp_Pnt(float(p[-1, 0]), float(p[-1, 1]), 0.0)
    if segment.kind == "line":  # a curve of two samples is not straight: the Hermite cubic below takes it
        return BRepBuilderAPI_MakeEdge(GC_MakeSegment(first, last).Value()).Edge()
    if segment.kind == "arc" and len(p) == 2:  # through its ends, tangent to the first one's exact tangent
        start = gp_Vec(float(t[0, 0]), float(t[0, 1]), 0.0)
        return BRepBuilderAPI_MakeEdge(GC_MakeArcOfCircle(first, start, last).Value()).Edge()
    if segment.kind == "arc":
        m = p[len(p) // 2]
        return BRepBuilderAPI_MakeEdge(GC_MakeArcOfCircle(first, gp_Pnt(float(m[0]), float(m[1]), 0.0), last).Value()).Edge()
    pts = HArray1_gp_Pnt(1, len(p))
    tans = Array1_gp_Vec(1, len(p))
    flags = HArray1_bool(1, len(p))
    for i in range(len(p)):  # OCP's arrays take one item at a time
        pts.SetValue(i + 1, gp_Pnt(float(p[i, 0]), float(p[i, 1]), 0.0))
        tans.SetValue(i + 1, gp_Vec(float(t[i, 0]), float(t[i, 1]), 0.0))
        flags.SetValue(i + 1, True)
    interp = GeomAPI_Interpolate(pts, False, 1e-12)
    interp.Load(tans, flags, False)  # unit tangents on chord-length parameters: the cubic of _hermite_samples
    interp.Perform()
    if not interp.IsDone():
        raise ValueError(f"OpenCASCADE could not interpolate the segment '{segment.name}'")
    return BRepBuilderAPI_MakeEdge(interp.Curve()).Edge()


def helical_solid(segments: list[SectionSegment], lead: float, length: float, tolerance: float):
    """Sweep a closed section of segments into a solid (an OpenCASCADE ``TopoDS_Shape``).

    Parameters
    ----------
    segments : list of SectionSegment
        The section, counter-clockwise, its segments end to end.
    lead : float, mm
        Signed lead (> 0 right hand); infinite for a straight prism (a spur gear).
    length : float, mm
        Axial length, from z = 0.
    tolerance : float, mm
        Not used in the sweep itself (kept for the callers' signature).

    Returns
    -------
    OCP.TopoDS.TopoDS_Shape

    Raises
    ------
    ValueError
        A segment that does not continue the previous one, or a sweep OpenCASCADE cannot make.
    """
    from OCP.BRepBuilderAPI import BRepBuilderAPI_MakeEdge, BRepBuilderAPI_MakeWire
    from OCP.BRepFill import BRepFill_TypeOfContact
    from OCP.BRepLib import BRepLib
    from OCP.BRepOffsetAPI import BRepOffsetAPI_MakePipeShell
    from OCP.Geom import Geom_CylindricalSurface
    from OCP.Geom2d import Geom2d_Line
    from OCP.gp import gp_Ax3, gp_Dir, gp_Dir2d, gp_Pnt, gp_Pnt2d

    quiet_ocp()
    wire = BRepBuilderAPI_MakeWire()
    for seg in segments:
        wire.Add(_edge(seg, tolerance))
        if not wire.IsDone():
            raise ValueError(f"the section's segment '{seg.name}' does not continue the previous one")
    profile = wire.Wire()
    if not np.isfinite(lead):  # a straight prism (a spur gear)
        from OCP.BRepBuilderAPI import BRepBuilderAPI_MakeFace
        from OCP.BRepPrimAPI import BRepPrimAPI_MakePrism
        from OCP.gp import gp_Vec

        return BRepPrimAPI_MakePrism(BRepBuilderAPI_MakeFace(profile).Face(), gp_Vec(0.0, 0.0, float(length))).Shape()
    spine = BRepBuilderAPI_MakeWire(BRepBuilderAPI_MakeEdge(gp_Pnt(0, 0, 0), gp_Pnt(0, 0, length)).Edge()).Wire()
    radius = max(float(np.hypot(*s.points.T).max()) for s in segments)
    cyl = Geom_CylindricalSurface(gp_Ax3(gp_Pnt(0, 0, 0), gp_Dir(0, 0, 1)), radius)
    line = Geom2d_Line(gp_Pnt2d(0.0, 0.0), gp_Dir2d(float(np.sign(lead) * 2 * np.pi), float(abs(lead))))
    helix_len = float(np.hypot(2 * np.pi * length / abs(lead), length))
    helix = BRepBuilderAPI_MakeWire(BRepBuilderAPI_MakeEdge(line, cyl, 0.0, helix_len).Edge()).Wire()
    BRepLib.BuildCurves3d_s(helix)
    pipe = BRepOffsetAPI_MakePipeShell(spine)
    pipe.SetMode(helix, False, BRepFill_TypeOfContact.BRepFill_NoContact)
    pipe.Add(profile)
    pipe.Build()
    if not pipe.IsDone():
        raise ValueError("OpenCASCADE could not sweep the section along its helix")
    solid = _capped_solid(pipe)
    if solid is None:  # not two plane ends to close it with: OpenCASCADE's own closing
        pipe.MakeSolid()
        return pipe.Shape()
    return solid


def _capped_solid(pipe):
    """Close a swept shell with its two plane end faces into a solid, outward; None when it cannot.

    What ``BRepOffsetAPI_MakePipeShell.MakeSolid`` does (OpenCASCADE's ``BRepFill_PipeShell::MakeSolid``:
    a plane face on the first and on the last section's wire, each oriented against the side face
    that shares its first edge, all in one closed shell), without its last step: the classification
    of a point at infinity against the solid (``BRepClass3d_SolidClassifier``), which intersects a
    ray with every B-spline face and took 30-40 ms of the 35-50 ms per rotor (README sample,
    measured). The solid lies between the planes of its ends, so whether it is inside out is read
    off the end at the smaller z: its face, as it lies in the solid, must face -z (a plane face
    made on +z is FORWARD when its normal is +z, REVERSED when -z); else the shell is reversed.
    Measured on the README sample (both hands): the same volume as ``MakeSolid``'s, valid (BRepCheck),
    3-7 ms.

    Parameters
    ----------
    pipe : OCP.BRepOffsetAPI.BRepOffsetAPI_MakePipeShell
        Built, not yet made a solid.

    Returns
    -------
    OCP.TopoDS.TopoDS_Solid or None
        None when the shell is closed already, an end is missing or not a wire, or a face cannot
        be made (the caller then uses ``MakeSolid``).
    """
    from OCP.BRep import BRep_Builder, BRep_Tool
    from OCP.BRepBuilderAPI import BRepBuilderAPI_MakeFace
    from OCP.gp import gp_Dir, gp_Pln, gp_Pnt
    from OCP.TopAbs import TopAbs_FACE, TopAbs_FORWARD, TopAbs_SHELL, TopAbs_VERTEX, TopAbs_WIRE
    from OCP.TopExp import TopExp_Explorer
    from OCP.TopoDS import TopoDS, TopoDS_Solid

    shell = pipe.Shape()
    ends = (pipe.FirstShape(), pipe.LastShape())
    if shell.IsNull() or shell.ShapeType() != TopAbs_SHELL or shell.Closed():
        return None
    if any(end.IsNull() or end.ShapeType() != TopAbs_WIRE for end in ends):
        return None
    builder = BRep_Builder()
    caps = []
    for end in ends:
        wire = TopoDS.Wire(end)
        vertex = TopExp_Explorer(wire, TopAbs_VERTEX)
        if not vertex.More():
            return None
        z = BRep_Tool.Pnt_s(TopoDS.Vertex(vertex.Current())).Z()
        made = BRepBuilderAPI_MakeFace(gp_Pln(gp_Pnt(0.0, 0.0, z), gp_Dir(0.0, 0.0, 1.0)), wire, True)
        if not made.IsDone():
            return None
        face = made.Face()
        opposed = _opposed_on_shared_edge(face, shell)
        if opposed is None:
            return None
        if not opposed:  # as OpenCASCADE's IsSameOriented: a shared edge runs both ways in a closed shell
            face.Reverse()
        caps.append((z, face))
    for _, face in caps:
        builder.Add(shell, face)
    shell.Closed(True)
    solid = TopoDS_Solid()
    builder.MakeSolid(solid)
    builder.Add(solid, shell)
    bottom = min(caps, key=lambda cap: cap[0])[1]
    explorer = TopExp_Explorer(solid, TopAbs_FACE)
    while explorer.More() and not explorer.Current().IsSame(bottom):
        explorer.Next()
    if not explorer.More():
        return None
    if explorer.Current().Orientation() == TopAbs_FORWARD:  # the bottom faces +z: inside out
        solid = TopoDS_Solid()
        builder.MakeSolid(solid)
        builder.Add(solid, shell.Reversed())
    return solid


def _opposed_on_shared_edge(face, shell) -> bool | None:
    """Tell whether the face's first edge runs the other way in the shell (None: the shell lacks it)."""
    from OCP.TopAbs import TopAbs_EDGE
    from OCP.TopExp import TopExp_Explorer

    first = TopExp_Explorer(face, TopAbs_EDGE)
    if not first.More():
        return None
    edge = first.Current()
    explorer = TopExp_Explorer(shell, TopAbs_EDGE)
    while explorer.More():
        if explorer.Current().IsSame(edge):
            return explorer.Current().Orientation() != edge.Orientation()
        explorer.Next()
    return None


def faces(shape) -> list:
    """List the faces of an OpenCASCADE shape.

    Parameters
    ----------
    shape : OCP.TopoDS.TopoDS_Shape
        The shape.

    Returns
    -------
    list of OCP.TopoDS.TopoDS_Face
    """
    from OCP.TopAbs import TopAbs_FACE
    from OCP.TopExp import TopExp_Explorer
    from OCP.TopoDS import TopoDS

    out, explorer = [], TopExp_Explorer(shape, TopAbs_FACE)
    while explorer.More():
        out.append(TopoDS.Face(explorer.Current()))
        explorer.Next()
    return out


def helicoid_deviation(shape, exact: np.ndarray, lead: float, length: float, per_face: int = 10) -> float:
    """Measure how far the side faces of a swept solid lie from the exact helicoid.

    Points are sampled on a grid of ``per_face`` x ``per_face`` in each face's parameter range (edges
    included) and, on a B-spline face, at every knot and the middle of every knot span too (where a
    piecewise cubic between two samples errs most: a fixed grid of 10 saw 0.09 um of a face 2 um
    off), turned back by -2 pi z / h and measured against the exact section. End faces (planes at
    z = 0 and z = length) are left out.

    Parameters
    ----------
    shape : OCP.TopoDS.TopoDS_Shape
        The solid.
    exact : (n, 2) float array, mm
        The exact section as a closed polyline, sampled finer than the tolerance checked.
    lead : float, mm
        Signed lead.
    length : float, mm
        Axial length.
    per_face : int
        Grid size per face.

    Returns
    -------
    float, mm
        The largest distance (0 when there is no side face).
    """
    from OCP.BRep import BRep_Tool
    from OCP.BRepTools import BRepTools
    from OCP.gp import gp_Pnt

    ring = np.vstack([exact, exact[:1]])
    batches = []
    at = gp_Pnt()
    coord = at.Coord
    for face in faces(shape):
        surface = BRep_Tool.Surface_s(face)
        u0, u1, v0, v1 = BRepTools.UVBounds_s(face)
        us, vs = _face_parameters(surface, u0, u1, v0, v1, per_face)
        d0, values = surface.D0, []
        for u in us.tolist():  # each point written into one gp_Pnt (what Value does, without a new one per point)
            for v in vs.tolist():
                d0(u, v, at)
                values.append(coord())
        pts = np.array(values)
        if np.ptp(pts[:, 2]) < 1e-9 * max(length, 1.0):  # an end cap
            continue
        batches.append(rotate(pts[:, :2], -2 * np.pi * pts[:, 2] / lead))  # each point by its own turn
    if not batches:
        return 0.0
    return farthest_distance(np.vstack(batches), ring)


def farthest_distance(points: np.ndarray, polyline: np.ndarray) -> float:
    """Return the largest distance of ``points`` to a polyline: ``distance_to_polyline(points, polyline).max()``.

    The same number, bit for bit, with the exact R-tree query (:func:`rotorcad.geometry.distance_to_polyline`)
    made only for the points that may be the farthest. For every point an upper bound of its
    distance is the distance to a few segments about the vertex nearest to it in polar angle
    (numpy; exact for a section star-shaped about its axis, larger elsewhere, never smaller).
    The points of the largest bounds are measured exactly, their largest distance ``L`` is a lower
    bound of the answer, and every point whose bound is at least ``L`` less a margin far above the
    rounding of either computation is measured too: a point left out lies nearer than ``L``.

    Parameters
    ----------
    points : (n, 2) float array, mm
        The points.
    polyline : (m, 2) float array, mm
        Vertices of the open polyline (a closed section with its first vertex repeated at the end).

    Returns
    -------
    float, mm
        The largest distance.
    """
    from rotorcad.geometry import as_points, distance_to_polyline

    pts, line = as_points(points), as_points(polyline)
    if len(pts) <= FIRST_MEASURED or len(line) < 3:
        return float(distance_to_polyline(pts, line).max())
    bound = _distance_bound(pts, line)
    first = np.argpartition(bound, -FIRST_MEASURED)[-FIRST_MEASURED:]
    lower = float(distance_to_polyline(pts[first], line).max())
    margin = 1e-9 * (1.0 + float(np.abs(line).max()) + float(np.abs(pts).max()))  # mm; the rounding is some 1e-13 of it
    rest = np.flatnonzero(bound >= lower - margin)
    rest = rest[~np.isin(rest, first)]
    if len(rest) == 0:
        return lower
    return max(lower, float(distance_to_polyline(pts[rest], line).max()))


FIRST_MEASURED = 64
"""Points of the largest bounds measured exactly first by :func:`farthest_distance`."""


def _distance_bound(pts: np.ndarray, line: np.ndarray, reach: int = 2, chunk: int = 2048) -> np.ndarray:
    """Upper bound of each point's distance to the polyline, (n,) mm (see :func:`farthest_distance`).

    The least distance to the ``2 reach`` segments about the vertex next in polar angle after the
    point (each a segment of the polyline, so never less than the distance). Made ``chunk`` points
    at a time: small temporaries, no fresh pages to fault in for each.
    """
    angle = np.arctan2(line[:, 1], line[:, 0])
    order = np.argsort(angle)
    at = np.searchsorted(angle[order], np.arctan2(pts[:, 1], pts[:, 0])) % len(order)
    start = np.clip(order[at][:, None] + np.arange(-reach, reach), 0, len(line) - 2)  # (n, 2 reach) segments (j, j + 1)
    out = np.empty(len(pts))
    for k in range(0, len(pts), chunk):
        j = start[k : k + chunk]
        ax, ay = line[j, 0], line[j, 1]
        dx, dy = line[j + 1, 0] - ax, line[j + 1, 1] - ay
        wx, wy = pts[k : k + chunk, :1] - ax, pts[k : k + chunk, 1:] - ay
        foot = np.clip((wx * dx + wy * dy) / np.maximum(dx * dx + dy * dy, 1e-300), 0.0, 1.0)
        wx -= foot * dx
        wy -= foot * dy
        out[k : k + chunk] = (wx * wx + wy * wy).min(axis=1)
    return np.sqrt(out)


def _face_parameters(surface, u0: float, u1: float, v0: float, v1: float, count: int) -> tuple[np.ndarray, np.ndarray]:
    """Return the u and v at which :func:`helicoid_deviation` samples a face.

    ``count`` equally spaced values in each range and, on a B-spline surface, its knots in the range
    and the middles of the knot spans.

    Parameters
    ----------
    surface : OCP.Geom.Geom_Surface
        The face's surface.
    u0, u1, v0, v1 : float
        The face's parameter bounds.
    count : int
        Equally spaced values per direction.

    Returns
    -------
    us, vs : (m,) float arrays
        Sorted, without repeats.
    """
    from OCP.GeomAbs import GeomAbs_SurfaceType
    from OCP.GeomAdaptor import GeomAdaptor_Surface

    us, vs = np.linspace(u0, u1, count), np.linspace(v0, v1, count)
    adaptor = GeomAdaptor_Surface(surface)
    if adaptor.GetType() != GeomAbs_SurfaceType.GeomAbs_BSplineSurface:
        return us, vs
    spline = adaptor.BSpline()

    def spans(knots, lo: float, hi: float) -> np.ndarray:
        k = np.array([knots.Value(i) for i in range(knots.Lower(), knots.Upper() + 1)])
        k = np.clip(k, lo, hi)
        return np.concatenate([k, 0.5 * (k[1:] + k[:-1])])

    return np.unique(np.concatenate([us, spans(spline.UKnots(), u0, u1)])), np.unique(
        np.concatenate([vs, spans(spline.VKnots(), v0, v1)])
    )


def write_exact_step(
    path: Path,
    segments: list[SectionSegment],
    lead: float,
    length: float,
    tolerance: float = 1e-3,
    body: str = "rotor",
    offset: tuple[float, float] = (0.0, 0.0),
    exact: np.ndarray | None = None,
) -> dict[str, float]:
    """Write the helical solid of ``segments`` as STEP (AP214, product named ``body``).

    Parameters
    ----------
    path : Path
        The file.
    segments : list of SectionSegment
        The section (:func:`section_segments`).
    lead : float, mm
        Signed lead (> 0 right hand; infinite for a spur gear).
    length : float, mm
        Axial length.
    tolerance : float, mm
        Largest deviation of the faces from the helicoid accepted.
    body : str
        Product name in the file.
    offset : (float, float), mm
        Translation of the solid in x and y (e.g. the female to (a, 0)).
    exact : (n, 2) float array, mm, optional
        The section as a fine closed polyline: the deviation of the faces from the helicoid is
        then measured.

    Returns
    -------
    dict of float
        ``faces`` (their number) and, with ``exact``, ``deviation`` (mm).

    Raises
    ------
    ValueError
        A solid off by more than ``tolerance`` (saying what was reached), or a sweep that fails.
    OSError
        When OpenCASCADE cannot write the file.
    """
    shape = helical_solid(segments, lead, length, tolerance)
    result = {"faces": float(len(faces(shape)))}
    if exact is not None:
        dev = helicoid_deviation(shape, exact, lead, length)
        result["deviation"] = dev
        if dev > tolerance:
            raise StepDeviationError(
                f"the STEP surface is {dev * 1e3:.2f} um from the helicoid, more than the tolerance {tolerance * 1e3:g} um"
            )
    write_shape(path, shape, body, offset)
    return result


def write_shape(path: Path, shape, body: str, offset: tuple[float, float] = (0.0, 0.0)) -> None:
    """Write an OpenCASCADE shape as STEP AP214 (product named ``body``), moved by ``offset``.

    Parameters
    ----------
    path : Path
        The file.
    shape : OCP.TopoDS.TopoDS_Shape
        What to write.
    body : str
        Product name in the file.
    offset : (float, float), mm
        Translation in x and y (e.g. the mate to (a, 0)).

    Raises
    ------
    OSError
        When OpenCASCADE cannot write the file.
    """
    from OCP.BRepBuilderAPI import BRepBuilderAPI_Transform
    from OCP.gp import gp_Trsf, gp_Vec
    from OCP.IFSelect import IFSelect_RetDone
    from OCP.Interface import Interface_Static
    from OCP.STEPControl import STEPControl_AsIs, STEPControl_Writer

    if offset != (0.0, 0.0):
        tr = gp_Trsf()
        tr.SetTranslation(gp_Vec(float(offset[0]), float(offset[1]), 0.0))
        shape = BRepBuilderAPI_Transform(shape, tr, True).Shape()
    writer = STEPControl_Writer()
    Interface_Static.SetCVal_s("write.step.schema", "AP214")
    Interface_Static.SetCVal_s("write.step.product.name", body)
    writer.Transfer(shape, STEPControl_AsIs)
    if writer.Write(str(path)) != IFSelect_RetDone:
        raise OSError(f"OpenCASCADE could not write {path}")


def housing_shape(
    center_distance: float, male_bore: float, female_bore: float, length: float, wall: float = 10.0, body: str = "housing"
):
    """Return the housing as an exact OpenCASCADE solid: box and cylinders.

    The block (as :func:`rotorcad.solids.housing_solids` sizes it) minus the two bore cylinders about
    O1 = (0, 0) and O2 = (a, 0) (``body`` "housing"), or the bores alone ("bores").

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
    body : {"housing", "bores"}
        Which solid.

    Returns
    -------
    OCP.TopoDS.TopoDS_Shape
    """
    from OCP.BRepAlgoAPI import BRepAlgoAPI_Cut, BRepAlgoAPI_Fuse
    from OCP.BRepPrimAPI import BRepPrimAPI_MakeBox, BRepPrimAPI_MakeCylinder
    from OCP.gp import gp_Ax2, gp_Dir, gp_Pnt

    quiet_ocp()
    axis = gp_Dir(0.0, 0.0, 1.0)
    male = BRepPrimAPI_MakeCylinder(gp_Ax2(gp_Pnt(0.0, 0.0, 0.0), axis), male_bore, length).Shape()
    female = BRepPrimAPI_MakeCylinder(gp_Ax2(gp_Pnt(center_distance, 0.0, 0.0), axis), female_bore, length).Shape()
    bores = BRepAlgoAPI_Fuse(male, female).Shape()
    if body == "bores":
        return bores
    x0, x1 = -male_bore - wall, center_distance + female_bore + wall
    half = max(male_bore, female_bore) + wall
    block = BRepPrimAPI_MakeBox(gp_Pnt(x0, -half, 0.0), gp_Pnt(x1, half, length)).Shape()
    return BRepAlgoAPI_Cut(block, bores).Shape()


def write_housing_step(
    path: Path,
    center_distance: float,
    male_bore: float,
    female_bore: float,
    length: float,
    wall: float = 10.0,
    body: str = "housing",
) -> float:
    """Write the housing as exact STEP (:func:`housing_shape`).

    Parameters
    ----------
    path : Path
        The file.
    center_distance : float, mm
        Centre distance a.
    male_bore, female_bore : float, mm
        Bore radii.
    length : float, mm
        Length along z, from 0.
    wall : float, mm
        Wall beyond the bores.
    body : {"housing", "bores"}
        What to write (also the product name).

    Returns
    -------
    float, mm³
        The volume of what was written.

    Raises
    ------
    OSError
        When OpenCASCADE cannot write the file.
    """
    from OCP.BRepGProp import BRepGProp
    from OCP.GProp import GProp_GProps

    shape = housing_shape(center_distance, male_bore, female_bore, length, wall, body)
    props = GProp_GProps()
    BRepGProp.VolumeProperties_s(shape, props)
    write_shape(path, shape, body)
    return float(props.Mass())


__all__ = [
    "SectionSegment",
    "faces",
    "helical_solid",
    "helicoid_deviation",
    "housing_shape",
    "section_segments",
    "write_exact_step",
    "write_housing_step",
    "write_shape",
]

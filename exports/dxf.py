"""DXF drawings of profiles with ezdxf, true scale in millimetres ($INSUNITS = 4).

Closed polylines on named layers, reference circles and centre marks on their own layers, labels
as TEXT on theirs.

ezdxf is imported by the writers (0.15 s): the export command hands DXF writing to its worker
process and need not load it (see :mod:`exports.background`).
"""

from __future__ import annotations

import logging
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

if TYPE_CHECKING:
    import ezdxf.document

    from exports.dxf_spline import SplinePiece
    from exports.formats import ExportFormat, Writer
    from rotorcad.assembly import PlacedBody

LAYER_COLOURS = {
    "GEAR": 5,
    "MATE": 1,
    "MALE": 5,
    "FEMALE": 1,
    "RACK": 4,
    "HOUSING": 8,
    "PITCH": 3,
    "BASE": 8,
    "CENTER": 2,
    "LINE_OF_ACTION": 6,
    "LABELS": 7,
}


@dataclass
class Drawing:
    """What goes into a 2D profile drawing (all coordinates in mm).

    Parameters
    ----------
    outlines : list of (str, (n, 2) float array)
        (layer, closed points): closed polylines.
    circles : list of (str, (float, float), float)
        (layer, centre, radius): reference circles.
    lines : list of (str, (float, float), (float, float))
        (layer, start, end).
    centers : list of (float, float)
        Centre marks, drawn as crosses on the layer CENTER.
    polylines : list of (str, (n, 2) float array)
        (layer, open points).
    splines : list of (str, SplinePiece or (n, 2) float array)
        (layer, piece): one non-rational B-spline per profile segment, each ending where the next
        starts (:func:`exports.dxf_spline.profile_splines`, R2000+ only); or (layer, closed points):
        one closed cubic spline through them, chord-length parameters (a drawing made on points).
    texts : list of (str, (float, float), str, float)
        (layer, insertion point, text, height in mm): one-line TEXT labels.
    mark_size : float, mm
        Half the size of a centre mark.
    """

    outlines: list[tuple[str, np.ndarray]] = field(default_factory=list)  # (layer, closed points)
    circles: list[tuple[str, tuple[float, float], float]] = field(default_factory=list)  # (layer, centre, radius)
    lines: list[tuple[str, tuple[float, float], tuple[float, float]]] = field(default_factory=list)
    centers: list[tuple[float, float]] = field(default_factory=list)
    polylines: list[tuple[str, np.ndarray]] = field(default_factory=list)  # (layer, open points)
    splines: list[tuple[str, SplinePiece | np.ndarray]] = field(default_factory=list)  # (layer, B-spline or points)
    texts: list[tuple[str, tuple[float, float], str, float]] = field(default_factory=list)  # (layer, insert, text, height mm)
    mark_size: float = 2.0


def write_dxf(path: Path, drawing: Drawing, version: str = "R2000") -> None:
    """Write a drawing as DXF.

    Outlines become closed LWPOLYLINEs (R2000+) or POLYLINEs (R12); splines are left out in R12.

    Parameters
    ----------
    path : Path
        The file.
    drawing : Drawing
        What to draw.
    version : str
        DXF version, e.g. ``"R2000"`` or ``"R12"``.
    """
    doc = _new(version)
    if version != "R12":  # R12 has no units variable
        doc.header["$INSUNITS"] = 4  # millimetres
        doc.header["$MEASUREMENT"] = 1  # metric
    layers = (
        {name for name, _ in drawing.outlines + drawing.polylines}
        | ({name for name, _ in drawing.splines} if version != "R12" else set())
        | {c[0] for c in drawing.circles}
        | {ln[0] for ln in drawing.lines}
        | {t[0] for t in drawing.texts}
    )
    if drawing.centers:
        layers.add("CENTER")
    for name in sorted(layers):
        doc.layers.add(name, color=LAYER_COLOURS.get(name, 7))
    msp = doc.modelspace()
    for layer, pts in drawing.outlines:
        if version == "R12":
            xy = [(float(x), float(y)) for x, y in np.asarray(pts, dtype=float)]
            msp.add_polyline2d(xy, close=True, dxfattribs={"layer": layer})
        else:
            _lwpolyline(msp, pts, True, layer)
    for layer, pts in drawing.polylines:
        if version == "R12":
            xy = [(float(x), float(y)) for x, y in np.asarray(pts, dtype=float)]
            msp.add_polyline2d(xy, dxfattribs={"layer": layer})
        else:
            _lwpolyline(msp, pts, False, layer)
    if version != "R12":  # SPLINE needs R2000+: its control points and knots as they are (no fit points to re-interpolate)
        for layer, piece in drawing.splines:
            if isinstance(piece, np.ndarray):  # closed points: one cubic through them (as a CAD user draws a spline on points)
                closed = np.vstack([piece, piece[:1]])
                spline = msp.add_spline_control_frame([(float(x), float(y), 0.0) for x, y in closed], degree=3, method="chord")
                spline.dxf.layer = layer
                continue
            control = np.column_stack([piece.control_points, np.zeros(len(piece.control_points))])
            msp.add_open_spline(control, degree=piece.degree, knots=piece.knots.tolist(), dxfattribs={"layer": layer})
    for layer, centre, r in drawing.circles:
        msp.add_circle(centre, r, dxfattribs={"layer": layer})
    for layer, a, b in drawing.lines:
        msp.add_line(a, b, dxfattribs={"layer": layer})
    for layer, insert, text, height in drawing.texts:  # one line each: TEXT is in R12 too (MTEXT is not)
        msp.add_text(text, height=height, dxfattribs={"layer": layer, "insert": (float(insert[0]), float(insert[1]))})
    h = drawing.mark_size
    for cx, cy in drawing.centers:
        msp.add_line((cx - h, cy), (cx + h, cy), dxfattribs={"layer": "CENTER"})
        msp.add_line((cx, cy - h), (cx, cy + h), dxfattribs={"layer": "CENTER"})
    _save(doc, path, version)


def _lwpolyline(msp, pts: np.ndarray, close: bool, layer: str) -> None:
    """Add an LWPOLYLINE of ``pts`` set in one piece.

    ezdxf appends points one by one, copying the whole array each time (a 126 000-point gear outline
    took minutes).
    """
    pts = np.asarray(pts, dtype=float)
    poly = msp.add_lwpolyline([], close=close, dxfattribs={"layer": layer})
    poly.lwpoints.set(np.column_stack([pts[:, :2], np.zeros((len(pts), 3))]))


def write_dxf_mesh(path: Path, vertices: np.ndarray, faces: np.ndarray, layer: str = "MESH", version: str = "R2000") -> None:
    """Write a 3D triangle mesh as a MESH entity (R2000+) or a POLYFACE (R12).

    Meant for small meshes: a POLYFACE of 0.1 M triangles takes ezdxf ~10 s to build (measured).

    Parameters
    ----------
    path : Path
        The file.
    vertices : (n, 3) float array, mm
        Vertices.
    faces : (m, 3) int array
        Triangles as vertex indices.
    layer : str
        Layer of the mesh.
    version : str
        DXF version.
    """
    doc = _new(version)
    if version != "R12":
        doc.header["$INSUNITS"] = 4
    doc.layers.add(layer, color=7)
    msp = doc.modelspace()
    v = [tuple(map(float, p)) for p in np.asarray(vertices, dtype=float)]
    f = [tuple(map(int, t)) for t in np.asarray(faces, dtype=np.int64)]
    if version == "R12":
        poly = msp.add_polyface(dxfattribs={"layer": layer})
        poly.append_faces([[v[i] for i in tri] for tri in f])
        poly.optimize()
    else:
        mesh = msp.add_mesh(dxfattribs={"layer": layer})
        with mesh.edit_data() as data:
            data.vertices = v
            data.faces = f
    _save(doc, path, version)


def _new(version: str) -> ezdxf.document.Drawing:
    """Start a new drawing, quietly.

    ezdxf warns on stderr that R12 has no units variable when it sets its default units - keep a
    successful run's stderr clean.
    """
    import ezdxf

    logger = logging.getLogger("ezdxf")
    level = logger.level
    logger.setLevel(logging.ERROR)
    try:
        return ezdxf.new(version)
    finally:
        logger.setLevel(level)


def _save(doc: ezdxf.document.Drawing, path: Path, version: str) -> None:
    """Save as ``doc.saveas(path)`` does; ezdxf logs that R12 has no units variable on every R12 save - keep that quiet.

    The drawing is written to a string first (``Drawing.write`` to a ``StringIO``, as ezdxf's
    documentation of it says) and the file gets it in one piece, with the encoding, error handler
    and newlines of ``saveas``: the same bytes, without an encoder call for each of the 15 000
    tags of a rotor's drawing.
    """
    import io

    logger = logging.getLogger("ezdxf")
    level = logger.level
    if version == "R12":
        logger.setLevel(logging.ERROR)
    try:
        doc.filename = str(path)
        text = io.StringIO()
        doc.write(text)
    finally:
        logger.setLevel(level)
    with open(path, "w", encoding=doc.output_encoding, errors="dxfreplace") as f:
        f.write(text.getvalue())


DXF_MESH_MAX = 50_000
"""Most triangles of a DXF mesh: a DXF mesh is for small meshes (measured)."""


def _plan_drawing(fmt: ExportFormat, body: PlacedBody, tolerance: float, row: dict[str, Any]) -> Writer:
    """Plan a body's drawing: its section placed in mesh, pitch circle; a rotor's also its centre and spline.

    Written by the worker process (ezdxf); the section's chords are its tolerance. A rotor's
    splines, one per profile segment (:func:`exports.dxf_spline.placed_splines`), are made here
    and their measured deviation goes into the row (``spline_deviation``); where the section's
    tolerance cannot be met by them the export is refused naming it.
    """
    from exports.background import BackgroundWriter
    from exports.dxf_spline import SplineToleranceError, placed_splines
    from exports.formats import RefusalError
    from rotorcad.assembly import BodyKind

    row.update(triangles=0, volume=body.section_volume, tolerance=body.section_tolerance)
    placed = body.placed_points()
    drawing = Drawing(mark_size=body.mark_size)
    drawing.outlines.append((body.name.upper(), placed))
    for hole in body.section.interiors:  # an internal gear's toothed bore
        drawing.outlines.append((body.name.upper(), np.asarray(hole.coords)[:-1][::-1] + np.asarray(body.shift)))
    drawing.circles.append(("PITCH", body.shift, body.pitch_radius))
    features = body.features  # a gear as a part: its bore with the keyway, its hub (rotorcad/gears/features.py)
    if features is not None and features.bore_radius > 0:
        drawing.outlines.append(("BORE", features.hole_points(body.section_tolerance) + np.asarray(body.shift)))
    if features is not None and features.hub_radius > 0:
        drawing.circles.append(("HUB", body.shift, features.hub_radius))
    r12 = fmt.name.endswith("r12")
    if body.kind is BodyKind.ROTOR:
        drawing.centers.append(body.shift)
        if not r12:  # one spline per profile segment, its deviation from the exact curve measured
            try:
                pieces = placed_splines(body.outline, body.section_tolerance, body.turn, body.shift)
            except SplineToleranceError as exc:
                raise RefusalError(
                    f"--tolerance {2 * body.section_tolerance:g} mm cannot be met by the DXF spline of the {body.name}: "
                    f"{exc} (the DXF is drawn to half the tolerance; --format dxf-r12 writes the polyline alone)."
                ) from None
            row.update(spline_deviation=max(piece.deviation for piece in pieces))
            drawing.splines.extend((f"{body.name.upper()}_SPLINE", piece) for piece in pieces)
    return BackgroundWriter(write_dxf, (drawing, "R12" if r12 else "R2000"))


def _plan_mesh_dxf(fmt: ExportFormat, body: PlacedBody, tolerance: float, row: dict[str, Any]) -> Writer:
    """Plan a body's DXF mesh (a POLYFACE in R12, a MESH in R2000), at most :data:`DXF_MESH_MAX` triangles."""
    from exports.formats import meshed

    row.update(triangles=0, volume=body.section_volume)

    def write(path: Path) -> None:
        made = meshed(fmt, body, tolerance, row)
        version = "R12" if fmt.name.endswith("r12") else "R2000"
        write_dxf_mesh(path, made.mesh.vertices, made.mesh.faces, body.name.upper(), version)

    return write


def _register() -> None:
    from exports.formats import SWEPT_BODIES, ExportFormat, Limit, register

    chords = "the section's chords: half the surface tolerance asked (a quarter for a gear)"
    for name, extension in (("dxf", ".dxf"), ("dxf-r12", "_r12.dxf")):
        register(
            ExportFormat(name, extension, _plan_drawing, chords, SWEPT_BODIES, background=True, preload=("ezdxf",), meshes=False)
        )
    for name, extension in (("dxf-mesh", "_mesh.dxf"), ("dxf-mesh-r12", "_mesh_r12.dxf")):
        register(
            ExportFormat(
                name,
                extension,
                _plan_mesh_dxf,
                "as the meshes (stl ...); refused when the mesh would have more triangles than the limit",
                SWEPT_BODIES,
                limit=Limit(DXF_MESH_MAX, "a DXF mesh"),
            )
        )


_register()

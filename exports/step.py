"""STEP (ISO 10303-21) writers.

``write_faceted_step`` writes, without OpenCASCADE, a closed faceted B-rep in AP214
(AUTOMOTIVE_DESIGN): one FACETED_BREP whose CLOSED_SHELL has a FACE_SURFACE on a PLANE bounded by a
POLY_LOOP per triangle - the form OpenCASCADE reads as one valid solid (measured: a plain FACE
with POLY_LOOP reads as an empty shell). It suits coarse meshes: OpenCASCADE needs seconds per
10 000 facets to read it.

The exact STEP (one face per profile segment) is :mod:`exports.step_exact`; ``read_step`` reads
any STEP back with OpenCASCADE.
"""

from __future__ import annotations

import importlib.util
import io
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from exports.ocp_messages import quiet_ocp

if TYPE_CHECKING:
    from exports.formats import ExportFormat, Writer
    from rotorcad.assembly import PlacedBody

HEADER = """ISO-10303-21;
HEADER;
FILE_DESCRIPTION(('{description}'),'2;1');
FILE_NAME('{name}','2026-01-01T00:00:00',('rotorcad'),('rotorcad'),'rotorcad','rotorcad','');
FILE_SCHEMA(('AUTOMOTIVE_DESIGN {{ 1 0 10303 214 1 1 1 1 }}'));
ENDSEC;
DATA;
#1=APPLICATION_CONTEXT('automotive design');
#2=APPLICATION_PROTOCOL_DEFINITION('international standard','automotive_design',2000,#1);
#3=PRODUCT_CONTEXT('',#1,'mechanical');
#4=PRODUCT('{body}','{body}','',(#3));
#5=PRODUCT_DEFINITION_FORMATION('','',#4);
#6=PRODUCT_DEFINITION_CONTEXT('part definition',#1,'design');
#7=PRODUCT_DEFINITION('design','',#5,#6);
#8=PRODUCT_DEFINITION_SHAPE('','',#7);
#9=(LENGTH_UNIT()NAMED_UNIT(*)SI_UNIT(.MILLI.,.METRE.));
#10=(NAMED_UNIT(*)PLANE_ANGLE_UNIT()SI_UNIT($,.RADIAN.));
#11=(NAMED_UNIT(*)SI_UNIT($,.STERADIAN.)SOLID_ANGLE_UNIT());
#12=UNCERTAINTY_MEASURE_WITH_UNIT(LENGTH_MEASURE(1.E-07),#9,'distance_accuracy_value','confusion accuracy');
#13=(GEOMETRIC_REPRESENTATION_CONTEXT(3)GLOBAL_UNCERTAINTY_ASSIGNED_CONTEXT((#12))GLOBAL_UNIT_ASSIGNED_CONTEXT((#9,#10,#11))REPRESENTATION_CONTEXT('Context3D','3D'));
#14=CARTESIAN_POINT('',(0.,0.,0.));
#15=DIRECTION('',(0.,0.,1.));
#16=DIRECTION('',(1.,0.,0.));
#17=AXIS2_PLACEMENT_3D('',#14,#15,#16);
#18=FACETED_BREP_SHAPE_REPRESENTATION('',(#17,#{brep}),#13);
#19=SHAPE_DEFINITION_REPRESENTATION(#8,#18);
"""


def _lines(fmt: str, columns: list[np.ndarray]) -> str:
    """Format entity lines for whole arrays at once (numpy's savetxt over stacked columns)."""
    buf = io.StringIO()
    np.savetxt(buf, np.column_stack(columns), fmt=fmt)
    return buf.getvalue()


def write_faceted_step(path: Path, vertices: np.ndarray, faces: np.ndarray, body: str = "rotor") -> None:
    """Write a closed triangle mesh as one faceted solid (AP214), without OpenCASCADE (module docstring).

    Parameters
    ----------
    path : Path
        The file.
    vertices : (n, 3) float array, mm
        Vertices.
    faces : (m, 3) int array
        Triangles as vertex indices.
    body : str
        Product name in the file.
    """
    v = np.asarray(vertices, dtype=float)
    f = np.asarray(faces, dtype=np.int64)
    nv, nf = len(v), len(f)
    a, b, c = v[f[:, 0]], v[f[:, 1]], v[f[:, 2]]
    normal = np.cross(b - a, c - a)
    normal /= np.linalg.norm(normal, axis=1, keepdims=True)
    ref = (b - a) / np.linalg.norm(b - a, axis=1, keepdims=True)
    first = 20
    pid = first + np.arange(nv)  # CARTESIAN_POINT ids of the vertices
    base = first + nv
    k = np.arange(nf)
    loop, bound, ndir, rdir, axis, plane, face = (base + 7 * k + j for j in range(7))
    shell = base + 7 * nf
    brep = shell + 1
    text = [HEADER.format(description="rotorcad faceted solid", name=Path(path).name, body=body, brep=brep)]
    text.append(_lines("#%d=CARTESIAN_POINT('',(%.12g,%.12g,%.12g));", [pid, v[:, 0], v[:, 1], v[:, 2]]))
    ids = pid[f]
    entity = np.empty(nf * 7, dtype=object)
    parts = [
        _lines("#%d=POLY_LOOP('',(#%d,#%d,#%d));", [loop, ids[:, 0], ids[:, 1], ids[:, 2]]).splitlines(),
        _lines("#%d=FACE_OUTER_BOUND('',#%d,.T.);", [bound, loop]).splitlines(),
        _lines("#%d=DIRECTION('',(%.15g,%.15g,%.15g));", [ndir, normal[:, 0], normal[:, 1], normal[:, 2]]).splitlines(),
        _lines("#%d=DIRECTION('',(%.15g,%.15g,%.15g));", [rdir, ref[:, 0], ref[:, 1], ref[:, 2]]).splitlines(),
        _lines("#%d=AXIS2_PLACEMENT_3D('',#%d,#%d,#%d);", [axis, ids[:, 0], ndir, rdir]).splitlines(),
        _lines("#%d=PLANE('',#%d);", [plane, axis]).splitlines(),
        _lines("#%d=FACE_SURFACE('',(#%d),#%d,.T.);", [face, bound, plane]).splitlines(),
    ]
    for j, lines in enumerate(parts):
        entity[j::7] = lines
    text.append("\n".join(entity) + "\n")
    face_list = ",".join(f"#{i}" for i in face)
    text.append(f"#{shell}=CLOSED_SHELL('',({face_list}));\n#{brep}=FACETED_BREP('',#{shell});\nENDSEC;\nEND-ISO-10303-21;\n")
    with open(path, "w", encoding="ascii") as fh:
        fh.write("".join(text))


def ocp_available() -> bool:
    """Tell whether OpenCASCADE (the ``OCP`` package) is installed.

    Found without importing it (0.6 s), which the export leaves to its worker process.
    """
    return importlib.util.find_spec("OCP") is not None


def read_step(path: Path) -> dict[str, object]:
    """Read a STEP file with OpenCASCADE and check it.

    The volume is integrated by Gauss-Kronrod (the plain integration was 0.9 % off on a B-spline
    rotor).

    Parameters
    ----------
    path : Path
        The STEP file.

    Returns
    -------
    dict
        ``solids`` (their number), ``valid`` (BRepCheck) and ``volume`` (mm³).

    Raises
    ------
    FileNotFoundError
        A missing file (OpenCASCADE's reader would crash on it).
    """
    from OCP.BRepCheck import BRepCheck_Analyzer
    from OCP.BRepGProp import BRepGProp
    from OCP.GProp import GProp_GProps
    from OCP.STEPControl import STEPControl_Reader
    from OCP.TopAbs import TopAbs_SOLID
    from OCP.TopExp import TopExp_Explorer

    quiet_ocp()
    if not Path(path).is_file():  # OpenCASCADE's reader crashes on a missing file
        raise FileNotFoundError(str(path))
    reader = STEPControl_Reader()
    reader.ReadFile(str(path))
    reader.TransferRoots()
    shape = reader.OneShape()
    props = GProp_GProps()
    BRepGProp.VolumePropertiesGK_s(shape, props, 1e-9, False, True)
    solids = 0
    explorer = TopExp_Explorer(shape, TopAbs_SOLID)
    while explorer.More():
        solids += 1
        explorer.Next()
    return {"solids": solids, "valid": bool(BRepCheck_Analyzer(shape).IsValid()), "volume": float(props.Mass())}


FACETED_STEP_MAX = 20_000
"""Most facets of a faceted STEP: OpenCASCADE reads a 20 000-facet faceted B-rep in 5-7 s (measured)."""

STEP_TOLERANCE = 1e-3
"""mm: the exact STEP is checked against the helicoid to 1 µm unless the tolerance asked is finer."""


def write_exact_step_refined(
    path: Path, sections: list, lead: float, length: float, tolerance: float, body: str, offset, exact: np.ndarray
) -> dict[str, float]:
    """Write the exact STEP from the first of ``sections`` whose faces are within ``tolerance`` of the helicoid.

    Each section is a list of :class:`exports.step_exact.SectionSegment`, sampled finer than the one
    before: the B-splines interpolate samples with their exact tangents (Hermite), and a large
    gear's slowly curved flanks, sampled sparsely at 10 x the tolerance in chord, stray from the
    helicoid (5.3 µm at module 100); ten times finer in chord (a third of the spacing) divides the
    error by about 100. Module level, so that the worker process can run it.

    Raises
    ------
    exports.step_exact.StepDeviationError
        When even the last section's faces are not within the tolerance.
    """
    from exports.step_exact import StepDeviationError, write_exact_step

    for i, segments in enumerate(sections):
        try:
            return write_exact_step(path, segments, lead, length, tolerance, body, offset, exact=exact)
        except StepDeviationError:
            if i == len(sections) - 1:
                raise
    raise ValueError("no section to write")


def _plan_exact_step(fmt: ExportFormat, body: PlacedBody, tolerance: float, row: dict[str, Any]) -> Writer:
    """Plan a body's exact STEP: B-spline faces for a rotor or gear, box and cylinders for the housing.

    Made to min(tolerance, :data:`STEP_TOLERANCE`); the row's tolerance is then the deviation
    measured on the solid's faces. Without OpenCASCADE the faceted STEP is written instead.
    """
    import shapely

    from exports.background import BackgroundWriter
    from exports.formats import RefusalError, table
    from exports.step_exact import section_segments, write_housing_step
    from rotorcad.geometry import rotate

    if not ocp_available():
        return _plan_faceted_step(table()["step-faceted"], body, tolerance, row)
    if body.housing is not None:
        row.update(triangles=0, volume=body.exact_volume, tolerance=0.0)
        return BackgroundWriter(write_housing_step, (*body.housing, body.name))
    step_tol = min(tolerance, STEP_TOLERANCE)
    # the B-splines interpolate points and exact tangents (Hermite): points at `chord` x the tolerance,
    # with samples added where the cubic between two would be off by more than a share of the tolerance
    # (section_segments); the face check of the writer refuses any solid that would not be
    sections = [section_segments(body.outline(chord * step_tol), body.turn, step_tol) for chord in body.step_chords]
    exact = rotate(body.outline(step_tol / 100).points, body.turn)
    if body.outer_radius is not None:  # an internal gear: the outer cylinder minus the swept bore
        from exports.step_ring import write_ring_step

        area = np.pi * body.outer_radius**2 - shapely.Polygon(exact).area
        row.update(triangles=0, volume=float(area * body.length), faces=len(sections[0]) + 3, tolerance=step_tol)
        return BackgroundWriter(
            write_ring_step,
            (sections, body.lead, body.length, body.outer_radius, step_tol, body.name, body.shift, exact),
            done=lambda done: row.update(tolerance=done["deviation"], faces=int(done["faces"])),
            failed=lambda exc: RefusalError(f"--tolerance {step_tol:g} mm cannot be met by the STEP of the {body.name}: {exc}."),
        )
    row.update(
        triangles=0,
        volume=float(shapely.Polygon(exact).area * body.length),
        faces=len(sections[0]) + 2,
        tolerance=step_tol,
    )
    writer, args = write_exact_step_refined, (sections, body.lead, body.length, step_tol, body.name, body.shift, exact)
    if body.features is not None:  # a gear as a part: bore, keyway, hub, herringbone (exports/gear_step.py)
        from exports.gear_step import write_gear_part_step

        row.update(volume=body.features.volume(shapely.Polygon(exact).area, body.length))
        writer, args = write_gear_part_step, (*args, body.features)
    return BackgroundWriter(
        writer,
        args,
        done=lambda done: row.update(tolerance=done["deviation"], faces=int(done["faces"])),  # measured on the solid
        failed=lambda exc: RefusalError(f"--tolerance {step_tol:g} mm cannot be met by the STEP of the {body.name}: {exc}."),
    )


def _plan_faceted_step(fmt: ExportFormat, body: PlacedBody, tolerance: float, row: dict[str, Any]) -> Writer:
    """Plan a body's faceted STEP: its mesh's triangles as planar faces, at most :data:`FACETED_STEP_MAX`."""
    from exports.formats import meshed

    row.update(triangles=0, volume=body.section_volume)

    def write(path: Path) -> None:
        made = meshed(fmt, body, tolerance, row)
        write_faceted_step(path, made.mesh.vertices, made.mesh.faces, body.name)

    return write


def _register() -> None:
    from exports.formats import ExportFormat, Limit, register

    register(
        ExportFormat(
            "step",
            ".step",
            _plan_exact_step,
            "min(tolerance, 1 µm), measured on the solid's faces against the helicoid and refused when not met "
            "(the housing: exact box and cylinders)",
            background=True,
            preload=("OCP.STEPControl",),
            meshes=False,
        )
    )
    register(
        ExportFormat(
            "step-faceted",
            "_faceted.step",
            _plan_faceted_step,
            "as the meshes (stl ...); refused when the mesh would have more facets than the limit",
            limit=Limit(
                FACETED_STEP_MAX, "a faceted STEP, which OpenCASCADE reads in seconds,", "; --format step writes the exact solid"
            ),
        )
    )


_register()

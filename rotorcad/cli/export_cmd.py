"""``rotorcad export`` and ``rotorcad interfere``: helical solids, files, interference (CONTRACT.md)."""

from __future__ import annotations

import sys
from dataclasses import replace
from pathlib import Path
from typing import Any, NamedTuple

import click
import numpy as np
import shapely
import shapely.validation
from rich.console import Console
from rich.table import Table

from exports.background import BackgroundWriter, WorkerPool
from exports.csv_points import write_points
from exports.dxf import Drawing, write_dxf, write_dxf_mesh
from exports.dxf_profile import read_profile_points
from exports.meshes import EXTENSIONS, MESH_FORMATS, write_mesh
from exports.step import ocp_available, write_faceted_step
from exports.step_exact import SectionSegment, section_segments, write_exact_step, write_housing_step
from rotorcad.cli.common import InputError, Outputs, emit_json, load_rotor_design, load_toml, output_folder
from rotorcad.cli.gear_export import GEAR_FORMATS, export_gear, is_gear_design
from rotorcad.cli.progress import Steps
from rotorcad.cli.rotor import PAIR_OPTIONS
from rotorcad.cli.rotor import _build as build_rotors
from rotorcad.errors import DesignError
from rotorcad.geometry import rotate
from rotorcad.interference import interference_2d, intersection_3d
from rotorcad.measured_outline import whole_outline
from rotorcad.rotor_pair import RotorPair
from rotorcad.solids import HOUSING_WALL, helical_solid, housing_solids
from rotorcad.triangle_mesh import TriangleMesh
from rotorcad.work import MAX_SECTION_POINTS, MAX_TRIANGLES, points_at, solid_triangles

FORMATS = (*MESH_FORMATS, "dxf", "dxf-r12", "dxf-mesh", "dxf-mesh-r12", "step", "step-faceted", "csv")
DXF_MESH_MAX = 50_000  # triangles: a DXF mesh is for small meshes (measured)
FACETED_STEP_MAX = 20_000  # facets: OpenCASCADE reads a 20 000-facet faceted B-rep in 5-7 s (measured)


def _rotor_options(design: Path) -> dict[str, Any]:
    """No command-line overrides: the design file gives the pair."""
    opts: dict[str, Any] = dict.fromkeys((*PAIR_OPTIONS, "male_points", "female_points", "rack_points", "speed"))
    opts["smoothing"] = None
    return opts


def _design_settings(design: Path, data: dict[str, Any] | None = None) -> dict[str, Any]:
    """Check the rotor design (from its mapping ``data`` if the file was read already).

    A bad design is refused in one sentence (:class:`InputError`).
    """
    try:
        return load_rotor_design(design, data)
    except DesignError as exc:
        raise InputError(exc.sentence()) from None


def _read_design(design: Path) -> dict[str, Any]:
    """Read the design file's mapping, once; a file that cannot be read is refused in one sentence."""
    try:
        return load_toml(design)
    except DesignError as exc:
        raise InputError(exc.sentence()) from None


ASSEMBLY_OPTIONS = (
    click.option(
        "--center-distance",
        type=float,
        help="Assembly centre distance [mm] at which the rotors (built at the design's) are placed. Default: the design's.",
    ),
    click.option(
        "--phase-deg",
        type=float,
        default=0.0,
        show_default=True,
        help="Female turned by this angle [deg] (counter-clockwise seen from the suction end) from its mesh position.",
    ),
)


@click.command()
@click.argument("design", type=click.Path(path_type=Path, dir_okay=False))
@click.option(
    "--format",
    "formats",
    help="Comma-separated formats: " + ", ".join(FORMATS) + ". Default: the design's [export] formats, else stl.",
)
@click.option(
    "--out", type=click.Path(path_type=Path, file_okay=False), required=True, help="Output folder (created if missing)."
)
@click.option(
    "--tolerance", type=float, help="Surface tolerance of the meshes [mm]. Default: the design's [export] tolerance, else 0.005."
)
@click.option(
    "--angle", type=float, default=0.0, show_default=True, help="Male angle of the pair in mesh [deg] (female at -angle z1/z2)."
)
@click.option(
    "--housing/--no-housing",
    default=None,
    help="Also write the housing (block minus bores) and the bores. Default: when the design has [housing].",
)
@ASSEMBLY_OPTIONS[0]
@ASSEMBLY_OPTIONS[1]
@click.option("--json", "as_json", is_flag=True, help="Print one JSON object on stdout.")
@click.option("--quiet", is_flag=True, help="No progress bar.")
def export(
    design: Path,
    formats: str | None,
    out: Path,
    tolerance: float | None,
    angle: float,
    housing: bool | None,
    center_distance: float | None,
    phase_deg: float,
    as_json: bool,
    quiet: bool,
) -> None:
    """Helical male and female rotor solids of a design, written in each format.

    One file per body and format; the female is placed in mesh at (a, 0) at the male angle --angle.
    With a housing, the block minus the two bores and the bores alone are written as meshes and STEP
    too. A gear design ([gear], optional [mate] and face_width) gives the gear and its mate in mesh.
    """
    data = _read_design(design)
    if is_gear_design(data):
        _export_gear(design, formats, out, tolerance, as_json, data)
        return
    settings = _design_settings(design, data)
    fmts = (
        [f.strip().lower() for f in formats.split(",")]
        if formats
        else [str(f).lower() for f in settings["export"].get("formats", ["stl"])]
    )
    fmts = list(dict.fromkeys(fmts))  # a format given twice is one file, one row
    for f in fmts:
        if f not in FORMATS:
            raise InputError(f"--format must be a comma-separated list of {', '.join(FORMATS)} (got {f!r}).")
    tol = tolerance if tolerance is not None else float(settings["export"].get("tolerance", 0.005))
    if not (np.isfinite(tol) and 0 < tol <= 1.0):
        raise InputError(f"--tolerance must be a surface tolerance between 0 and 1 mm (got {tol}).")
    # STEP and DXF are written by a worker process (exports.background), forked before the
    # progress bar's thread, while this one sweeps and meshes
    preload = ("OCP.STEPControl",) if "step" in fmts and ocp_available() else ()
    preload += ("ezdxf",) if {"dxf", "dxf-r12"} & set(fmts) else ()
    with WorkerPool(background=bool(preload), preload=preload) as pool:
        rotors, _, clearance = build_rotors(design, _rotor_options(design), settings)
        pair, phase = _assembly(rotors.pair, center_distance, phase_deg, clearance)
        _check_solid_work(rotors, tol, "--tolerance" if tolerance is not None else "[export] tolerance")
        folder = output_folder(out)
        stem = Path(design).stem
        if not np.isfinite(angle):
            raise InputError(f"--angle must be a number of degrees (got {angle}).")
        phi = np.radians(angle)
        turn = {"male": phi, "female": -phi * pair.male_teeth / pair.female_teeth + phase}
        sections = {
            b: shapely.affinity.rotate(rotors.section(b, tol / 2), turn[b], origin=(0, 0), use_radians=True)
            for b in ("male", "female")
        }
        leads = {"male": pair.lead if pair.hand == "right" else -pair.lead}
        leads["female"] = -np.sign(leads["male"]) * pair.female_lead
        shift = {"male": (0.0, 0.0), "female": (pair.center_distance, 0.0)}
        swept: dict[str, _SweptBody] = {}
        progress = Steps("sweeping solids", 2, quiet).start()

        def body_mesh(body: str) -> _SweptBody:
            """Sweep and mesh the body in place when a writer first needs it (while the worker writes STEP and DXF).

            The manifold is let go once meshed (some 150 MB a rotor).
            """
            if body not in swept:
                made = helical_solid(sections[body], leads[body], pair.length, tol)
                mesh = made.triangle_mesh
                mesh.apply_translation([*shift[body], 0.0])  # the mesh is the solid's own: moved, not copied
                swept[body] = _SweptBody(mesh, made.volume, made.tolerance)
                progress.advance()
            return swept[body]

        def write_placed_mesh(p: Path, body: str, fmt: str, row: dict[str, Any]) -> None:
            made = body_mesh(body)
            row.update(triangles=len(made.mesh.faces), volume=made.volume, tolerance=made.tolerance)
            write_mesh(p, made.mesh, fmt)

        def write_mesh_dxf(p: Path, body: str, fmt: str, row: dict[str, Any]) -> None:
            made = body_mesh(body)
            if len(made.mesh.faces) > DXF_MESH_MAX:
                _refuse_mesh_size(fmt, body, len(made.mesh.faces), DXF_MESH_MAX, coarser_tolerance(body, DXF_MESH_MAX))
            row.update(triangles=len(made.mesh.faces), volume=made.volume, tolerance=made.tolerance)
            write_dxf_mesh(p, made.mesh.vertices, made.mesh.faces, body.upper(), "R12" if fmt.endswith("r12") else "R2000")

        def estimated_triangles(body: str, t: float) -> float:
            """Triangles of the body's mesh at the tolerance ``t`` (mm), estimated without sweeping it."""
            coarse = max(t / 2, 0.05)
            section = rotors.section(body, coarse)
            r_max = float(np.hypot(*np.asarray(section.exterior.coords).T).max())
            return solid_triangles(points_at(section, coarse, t / 2), leads[body], pair.length, r_max, t)

        def coarser_tolerance(body: str, limit: int) -> float:
            """Return a tolerance, mm (3 digits, rounded up), whose mesh of ``body`` has at most ``limit`` triangles.

            Found on the estimate (:func:`rotorcad.work.solid_triangles`, bisected), then checked
            by sweeping the body at it (coarse, so quick), coarsened until it does fit.
            """
            lo, hi = np.log(tol), np.log(max(tol, 1.0))
            for _ in range(30):
                mid = 0.5 * (lo + hi)
                lo, hi = (lo, mid) if estimated_triangles(body, float(np.exp(mid))) <= limit else (mid, hi)
            need = float(np.exp(hi))
            for _ in range(20):
                need = float(np.ceil(need * 10 ** (2 - np.floor(np.log10(need)))) / 10 ** (2 - np.floor(np.log10(need))))
                made = helical_solid(rotors.section(body, need / 2), leads[body], pair.length, need)
                if len(made.mesh.faces) <= limit:
                    break
                need *= 1.2
            return need

        def write_faceted(p: Path, body: str, row: dict[str, Any]) -> None:
            made = body_mesh(body)
            faces = len(made.mesh.faces)
            if faces > FACETED_STEP_MAX:  # a file coarser than asked is never written: the tolerance that can be met
                _refuse_mesh_size("step-faceted", body, faces, FACETED_STEP_MAX, coarser_tolerance(body, FACETED_STEP_MAX))
            row.update(triangles=faces, volume=made.volume, tolerance=made.tolerance)
            write_faceted_step(p, made.mesh.vertices, made.mesh.faces, body)

        for fmt, limit in (("dxf-mesh", DXF_MESH_MAX), ("dxf-mesh-r12", DXF_MESH_MAX), ("step-faceted", FACETED_STEP_MAX)):
            for body in ("male", "female") if fmt in fmts else ():  # far over on the estimate: refused before any sweep
                if estimated_triangles(body, tol) > 2 * limit:
                    needed = coarser_tolerance(body, limit)
                    _refuse_mesh_size(fmt, body, estimated_triangles(body, tol), limit, needed)
        outputs = Outputs()
        rows: list[dict[str, Any]] = []
        for body in ("male", "female"):
            placed = np.asarray(sections[body].exterior.coords)[:-1] + np.array(shift[body])
            for fmt in fmts:
                path = folder / f"{stem}_{body}{_extension(fmt)}"
                row: dict[str, Any] = {
                    "path": str(path),
                    "format": fmt,
                    "body": body,
                    "triangles": 0,
                    "volume": float(sections[body].area * pair.length),
                }
                if fmt in MESH_FORMATS:
                    outputs.add(path, lambda p, b=body, f=fmt, r=row: write_placed_mesh(p, b, f, r), "--out")
                elif fmt in ("dxf", "dxf-r12"):
                    row.update(tolerance=tol / 2)  # the section's chords
                    drawing = Drawing(mark_size=0.05 * pair.male_tip_radius)
                    drawing.outlines.append((body.upper(), placed))
                    drawing.circles.append(
                        ("PITCH", shift[body], pair.male_pitch_radius if body == "male" else pair.female_pitch_radius)
                    )
                    drawing.centers.append(shift[body])
                    if fmt == "dxf":
                        drawing.splines.append((f"{body.upper()}_SPLINE", placed))
                    outputs.add(path, BackgroundWriter(write_dxf, (drawing, "R12" if fmt == "dxf-r12" else "R2000")), "--out")
                elif fmt in ("dxf-mesh", "dxf-mesh-r12"):
                    outputs.add(path, lambda p, b=body, f=fmt, r=row: write_mesh_dxf(p, b, f, r), "--out")
                elif fmt == "csv":
                    row.update(tolerance=tol / 2)
                    own = np.asarray(sections[body].exterior.coords)[:-1]
                    outputs.add(path, lambda p, pts=own: write_points(p, pts), "--out")
                elif fmt == "step" and ocp_available():
                    step_tol = min(tol, STEP_TOLERANCE)
                    segments, exact = _step_section(rotors, body, turn[body], step_tol)
                    row.update(
                        faces=len(segments) + 2, tolerance=step_tol, volume=float(shapely.Polygon(exact).area * pair.length)
                    )
                    job = BackgroundWriter(
                        write_exact_step,
                        (segments, leads[body], pair.length, step_tol, body, shift[body], exact),
                        done=lambda done, r=row: r.update(tolerance=done["deviation"]),  # measured on the solid's faces
                        failed=lambda exc, b=body, t=step_tol: InputError(
                            f"--tolerance {t:g} mm cannot be met by the STEP of the {b}: {exc}."
                        ),
                    )
                    outputs.add(path, job, "--out")
                else:  # faceted STEP: coarse enough for OpenCASCADE to read
                    outputs.add(path, lambda p, b=body, r=row: write_faceted(p, b, r), "--out")
                rows.append(row)
        with_housing = housing if housing is not None else bool(settings["housing"])
        if with_housing:
            segments = max(360, int(2 * np.pi / np.sqrt(8 * tol / pair.female_tip_radius)))
            block, bores = housing_solids(
                pair.center_distance,
                pair.male_tip_radius + clearance,
                pair.female_tip_radius + clearance,
                pair.length,
                wall=HOUSING_WALL,
                segments=segments,
            )
            housing_sag = float((pair.female_tip_radius + clearance) * (1 - np.cos(np.pi / segments)))  # chords of the bores
            exact_volume = _housing_volumes(pair, clearance)
            for body, manifold in (("housing", block), ("bores", bores)):
                m = manifold.to_mesh64()
                mesh = TriangleMesh(np.asarray(m.vert_properties)[:, :3], np.asarray(m.tri_verts))
                for fmt in fmts:
                    if fmt in MESH_FORMATS or fmt in ("step", "step-faceted"):
                        ext = _extension(fmt) if fmt in MESH_FORMATS else ("_faceted.step" if fmt == "step-faceted" else ".step")
                        path = folder / f"{stem}_{body}{ext}"
                        rows.append(
                            {
                                "path": str(path),
                                "format": fmt,
                                "body": body,
                                "triangles": len(mesh.faces),
                                "volume": float(manifold.volume()),
                            }
                        )
                        if fmt in MESH_FORMATS:
                            rows[-1]["tolerance"] = housing_sag
                            outputs.add(path, lambda p, mm=mesh, f=fmt: write_mesh(p, mm, f), "--out")
                        elif fmt == "step":  # exact: box and cylinders by OpenCASCADE
                            rows[-1].update(tolerance=0.0, triangles=0, volume=exact_volume[body])
                            bores_at = (pair.male_tip_radius + clearance, pair.female_tip_radius + clearance)
                            job = BackgroundWriter(
                                write_housing_step, (pair.center_distance, *bores_at, pair.length, HOUSING_WALL, body)
                            )
                            outputs.add(path, job, "--out")
                        else:
                            rows[-1]["tolerance"] = housing_sag
                            outputs.add(path, lambda p, mm=mesh, b=body: write_faceted_step(p, mm.vertices, mm.faces, b), "--out")
        written = outputs.write(pool)
    progress.stop()
    for row in rows:
        row["size"] = Path(row["path"]).stat().st_size if Path(row["path"]).exists() else 0
        row["replaced"] = Path(row["path"]) in outputs.replaced  # a file that was there, replaced whole
    result = {"files": rows, "tolerance": tol, "clearance": clearance}
    if as_json:
        emit_json(result)
    else:
        table = Table(title=f"{len(written)} files {stem}_<file> in {folder}", header_style="bold")
        table.add_column("file", overflow="fold")  # the whole name after the stem, folded, never cut
        table.add_column("format")
        for col in ("tolerance µm", "volume mm³", "size MB"):
            table.add_column(col, justify="right")
        for row in rows:
            met = row.get("tolerance")
            table.add_row(
                Path(row["path"]).name.removeprefix(f"{stem}_"),
                row["format"],
                "-" if met is None else f"{met * 1e3:.3g}",
                f"{row['volume']:.1f}",
                f"{row['size'] / 1e6:.2f}",
            )
        Console(file=sys.stdout, highlight=False).print(table)


def _refuse_mesh_size(fmt: str, body: str, triangles: float, limit: int, needed: float) -> None:
    """Refuse a DXF mesh or faceted STEP of too many triangles, naming the tolerance that would do.

    A file coarser than the tolerance asked is never written (issue 24: a faceted STEP was written at
    3.1 mm where 5 um were asked).
    """
    what = "a DXF mesh" if fmt.startswith("dxf-mesh") else "a faceted STEP, which OpenCASCADE reads in seconds,"
    can = f"{needed:.3g} mm or coarser would do" if needed <= 1.0 else f"only {needed:.3g} mm would, above the 1 mm allowed"
    alternative = "; --format step writes the exact solid" if fmt == "step-faceted" else ""
    raise InputError(
        f"--tolerance must be coarser for {what} of the {body} (about {triangles:.3g} triangles; at most {limit}): "
        f"{can}{alternative}."
    )


STEP_TOLERANCE = 1e-3  # mm: the exact STEP is checked against the helicoid to 1 um unless --tolerance is finer


class _SweptBody(NamedTuple):
    """What the mesh writers need of a swept rotor: its mesh in place and what it was made to."""

    mesh: TriangleMesh  # float64, placed (the female at the centre distance)
    volume: float  # mm^3, of the mesh
    tolerance: float  # mm, surface tolerance it was made to


def _step_section(rotors, body: str, turn: float, tolerance: float) -> tuple[list[SectionSegment], np.ndarray]:
    """Return the section of one rotor as segments and as a fine polyline for the deviation check.

    The segments are its exact pieces, sampled to ten times the tolerance with their tangents; the
    polyline is sampled to a hundredth of it; both turned by ``turn`` (rad).
    """
    # the B-splines interpolate points and exact tangents (Hermite): points at 10 x the tolerance in
    # chord, with samples added where the cubic between two would be off by more than a quarter of
    # the tolerance (section_segments), and the face check refuses any solid that would not be
    outline = rotors.male_outline(10 * tolerance) if body == "male" else rotors.female_outline(10 * tolerance)
    fine = rotors.male_outline(tolerance / 100) if body == "male" else rotors.female_outline(tolerance / 100)
    return section_segments(outline, turn, tolerance), rotate(fine.points, turn)


def _export_gear(
    design: Path, formats: str | None, out: Path, tolerance: float | None, as_json: bool, data: dict[str, Any] | None = None
) -> None:
    """Run the gear branch of ``export``: formats default to stl, step and dxf, tolerance to 5 µm."""
    fmts = list(dict.fromkeys(f.strip().lower() for f in (formats or "stl,step,dxf").split(",")))  # each once
    tol = 0.005 if tolerance is None else tolerance
    if not (np.isfinite(tol) and 0 < tol <= 1.0):
        raise InputError(f"--tolerance must be a surface tolerance between 0 and 1 mm (got {tol}).")
    for f in fmts:  # before the folder is made: a failed run leaves none behind
        if f not in GEAR_FORMATS:
            raise InputError(
                f"--format for a gear design must be a comma-separated list of {', '.join(GEAR_FORMATS)} (got {f!r})."
            )
    folder = output_folder(out)
    rows = export_gear(design, fmts, folder, tol, data)
    if as_json:
        emit_json({"files": rows, "tolerance": tol})
        return
    table = Table(title=f"{len(rows)} files {design.stem}_<file> in {folder}", header_style="bold")
    table.add_column("file", overflow="fold")
    table.add_column("format")
    for col in ("tolerance µm", "volume mm³", "size MB"):
        table.add_column(col, justify="right")
    for row in rows:
        table.add_row(
            Path(row["path"]).name.removeprefix(f"{design.stem}_"),
            row["format"],
            f"{row['tolerance'] * 1e3:.3g}",
            f"{row['volume']:.1f}",
            f"{row['size'] / 1e6:.2f}",
        )
    Console(file=sys.stdout, highlight=False).print(table)


def _check_solid_work(rotors, tol: float, label: str) -> None:
    """Refuse a request whose two solids would have more than :data:`rotorcad.work.MAX_TRIANGLES` triangles.

    Refused before any solid is swept, naming the smallest tolerance that fits (or the lead or the
    size when no tolerance up to 1 mm does).
    """
    pair = rotors.pair
    coarse = max(tol / 2, 0.05)
    total = 0.0
    for body, lead in (("male", pair.lead), ("female", pair.female_lead)):
        section = rotors.section(body, coarse)
        r_max = float(np.hypot(*np.asarray(section.exterior.coords).T).max())
        total += solid_triangles(points_at(section, coarse, tol / 2), lead, pair.length, r_max, tol)
    if total <= MAX_TRIANGLES:
        return
    need = tol * total / MAX_TRIANGLES * 1.05  # triangles grow like 1/tolerance
    what = f"the solids would have {total / 1e6:.3g} million triangles, at most {MAX_TRIANGLES / 1e6:g} million fit in memory"
    if need <= 1.0:
        raise InputError(f"{label} must be at least {need:.2g} mm for this design (got {tol:g}: {what}).")
    at_1mm = total * tol
    wrap_turns = pair.length / pair.lead
    if wrap_turns > 2:
        lead = pair.lead * at_1mm / MAX_TRIANGLES * 1.05
        raise InputError(
            f"[pair] lead must be at least {lead:.3g} mm for solids of this length (got {pair.lead:g}: {what} even at a "
            "tolerance of 1 mm)."
        )
    raise InputError(
        f"[pair] center_distance and the radii must be smaller for solids (got {pair.center_distance:g} mm: {what} even "
        "at a tolerance of 1 mm)."
    )


def _assembly(pair: RotorPair, center_distance: float | None, phase_deg: float, clearance: float) -> tuple[RotorPair, float]:
    """Return the pair as assembled and the female's extra turn (rad).

    The design's rotors at another centre distance (the bores follow); bad values are refused in one
    sentence.
    """
    if not (np.isfinite(clearance) and clearance >= 0):
        raise InputError(f"[housing] radial_clearance must be a clearance of at least 0 mm (got {clearance}).")
    if not np.isfinite(phase_deg) or abs(phase_deg) > 360:
        raise InputError(f"--phase-deg must be an angle from -360 to 360 deg (got {phase_deg}).")
    if center_distance is None:
        return pair, float(np.radians(phase_deg))
    low = max(pair.male_tip_radius, pair.female_tip_radius)
    high = pair.male_tip_radius + pair.female_tip_radius
    if not (np.isfinite(center_distance) and low < center_distance <= high):
        raise InputError(
            f"--center-distance must be more than the larger tip radius {low:g} mm and at most the sum of the tip radii "
            f"{high:g} mm (got {center_distance})."
        )
    return replace(pair, center_distance=float(center_distance), strict=False), float(np.radians(phase_deg))


def _housing_volumes(pair: RotorPair, clearance: float, wall: float = HOUSING_WALL) -> dict[str, float]:
    """Return the closed-form volumes (mm³) of the bores and of the block minus the bores.

    The bores are two intersecting circles (the union's area from the lens of their overlap), times
    the length.
    """
    a, r1, r2 = pair.center_distance, pair.male_tip_radius + clearance, pair.female_tip_radius + clearance
    lens = r1**2 * np.arccos((a**2 + r1**2 - r2**2) / (2 * a * r1)) + r2**2 * np.arccos((a**2 + r2**2 - r1**2) / (2 * a * r2))
    lens -= 0.5 * np.sqrt((-a + r1 + r2) * (a + r1 - r2) * (a - r1 + r2) * (a + r1 + r2))
    bores = (np.pi * (r1**2 + r2**2) - lens) * pair.length
    half = max(r1, r2) + wall
    block = (a + r1 + r2 + 2 * wall) * 2 * half * pair.length
    return {"bores": float(bores), "housing": float(block - bores)}


def _extension(fmt: str) -> str:
    return EXTENSIONS.get(
        fmt,
        {
            "dxf": ".dxf",
            "dxf-r12": "_r12.dxf",
            "dxf-mesh": "_mesh.dxf",
            "dxf-mesh-r12": "_mesh_r12.dxf",
            "step": ".step",
            "step-faceted": "_faceted.step",
            "csv": "_own_frame.csv",  # the section in the body's own frame, unlike the placed solids
        }.get(fmt, ""),
    )


@click.command()
@click.argument("design", type=click.Path(path_type=Path, dir_okay=False))
@click.option("--steps", type=int, default=72, show_default=True, help="Male angles over one lobe pitch.")
@click.option(
    "--tolerance", type=float, default=0.005, show_default=True, help="Section tolerance [mm]; sets the touching threshold."
)
@click.option(
    "--check-3d", is_flag=True, help="Also intersect the 3D solids at the angle of the maximum (slow at fine tolerance)."
)
@ASSEMBLY_OPTIONS[0]
@ASSEMBLY_OPTIONS[1]
@click.option(
    "--male-points",
    type=click.Path(path_type=Path, dir_okay=False),
    help="The male as built: measured outline (CSV or DXF, own frame, one lobe or whole) in place of the design's.",
)
@click.option(
    "--female-points",
    type=click.Path(path_type=Path, dir_okay=False),
    help="The female as built: measured outline (CSV or DXF, own frame, one lobe or whole) in place of the design's.",
)
@click.option("--layer", help="Layer of the outline in DXF points files.")
@click.option("--json", "as_json", is_flag=True, help="Print one JSON object on stdout.")
@click.option("--quiet", is_flag=True, help="No progress bar.")
def interfere(
    design: Path,
    steps: int,
    tolerance: float,
    check_3d: bool,
    center_distance: float | None,
    phase_deg: float,
    male_points: Path | None,
    female_points: Path | None,
    layer: str | None,
    as_json: bool,
    quiet: bool,
) -> None:
    """Interference of the rotor pair over one lobe pitch and of the rotors with the housing bores.

    The pair's interference is the integral of 2D section intersections along the helix. As
    assembled: at --center-distance and with the female turned by --phase-deg from its mesh position
    (the rotors keep their profiles; the bores follow the centre distance).

    Exit status: 0 when clean, 1 when the rotors interfere with each other or with the housing by
    more than the touching threshold (key touching_threshold, mm³, set by --tolerance), 2 on bad
    input.
    """
    if not 1 <= steps <= 100_000:
        raise InputError(f"--steps must be a whole number from 1 to 100000 (got {steps}).")
    if not (np.isfinite(tolerance) and 0 < tolerance <= 1.0):
        raise InputError(f"--tolerance must be between 0 and 1 mm (got {tolerance}).")
    rotors, _, clearance = build_rotors(design, _rotor_options(design))
    coarse = max(tolerance / 2, 0.05)
    points = sum(points_at(rotors.section(b, coarse), coarse, tolerance / 2) for b in ("male", "female"))
    if points > MAX_SECTION_POINTS:
        need = tolerance * (points / MAX_SECTION_POINTS) ** 2 * 1.05  # points grow like 1/sqrt(tolerance)
        raise InputError(
            f"--tolerance must be at least {need:.2g} mm for this design (got {tolerance:g}: the sections would have "
            f"{points:.3g} points, at most {MAX_SECTION_POINTS} can be turned through the sweep)."
        )
    if check_3d:
        _check_solid_work(rotors, tolerance, "--tolerance")
    male, female = rotors.section("male", tolerance / 2), rotors.section("female", tolerance / 2)
    for option, path, teeth in (
        ("--male-points", male_points, rotors.pair.male_teeth),
        ("--female-points", female_points, rotors.pair.female_teeth),
    ):
        if path is not None:
            try:
                outline = shapely.Polygon(whole_outline(read_profile_points(path, option, layer), teeth, option))
            except DesignError as exc:
                raise InputError(exc.sentence()) from None
            if not outline.is_valid:  # a self-crossing outline: GEOS fails on it in the sweep (exit 70)
                why = shapely.validation.explain_validity(outline)
                raise InputError(f"{option} must be an outline that does not cross itself (got {path}): {why}.")
            if option == "--male-points":
                male = outline
            else:
                female = outline
    pair, phase = _assembly(rotors.pair, center_distance, phase_deg, clearance)
    progress = Steps("interference: 2-D sweep", 4 if check_3d else 1, quiet).start()
    result_2d = interference_2d(pair, male, female, steps, tolerance, female_phase=phase, clearance=clearance)
    progress.advance(description="interference: male solid")
    result: dict[str, Any] = {
        "center_distance": pair.center_distance,
        "phase_deg": float(np.degrees(phase)),
        "max_intersection_volume": result_2d.max_volume if result_2d.interferes else 0.0,
        "max_intersection_volume_raw": result_2d.max_volume,
        "angle_deg": float(np.degrees(result_2d.angle_of_max)),
        "housing_intersection_volume": result_2d.housing_volume,
        "steps": steps,
        "touching_threshold": result_2d.threshold,
        "max_penetration": result_2d.max_penetration,
        "interferes": result_2d.interferes or result_2d.housing_volume > result_2d.threshold,
    }
    if check_3d:
        lead = pair.lead if pair.hand == "right" else -pair.lead
        m = helical_solid(male, lead, pair.length, tolerance)
        progress.advance(description="interference: female solid")
        f = helical_solid(female, -np.sign(lead) * pair.female_lead, pair.length, tolerance)
        progress.advance(description="interference: 3-D intersection")
        result["check_3d"] = intersection_3d(pair, m, f, result_2d.angle_of_max, result_2d.threshold)
        progress.advance()
    progress.stop()
    if as_json:
        emit_json(result)
    else:
        from rotorcad.cli.common import print_table

        print_table(f"interference of {Path(design).stem}", {k: v for k, v in result.items() if k != "check_3d"})
    if result["interferes"]:
        click.get_current_context().exit(1)  # a finding, not an error: pipelines test the status


__all__ = ["export", "interfere"]

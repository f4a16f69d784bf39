"""``rotorcad export`` and ``rotorcad interfere``: helical solids, files, interference (CONTRACT.md)."""

from __future__ import annotations

import sys
from pathlib import Path
from typing import Any

import click
import numpy as np
import shapely
import shapely.validation
from rich.console import Console
from rich.table import Table

from exports.background import WorkerPool
from exports.dxf_profile import read_profile_points
from exports.formats import ExportFormat, check_limits, names, plan_files, preload, table
from rotorcad.assembly import BodyKind, PlacedBody, assemble, check_section_work, check_solid_work, housing_bodies, rotor_bodies
from rotorcad.cli.common import InputError, Outputs, emit_json, load_rotor_design, load_toml, output_folder
from rotorcad.cli.progress import Steps
from rotorcad.cli.rotor import PAIR_OPTIONS
from rotorcad.cli.rotor import _build as build_rotors
from rotorcad.design.files import is_gear_design
from rotorcad.errors import DesignError
from rotorcad.interference import interference_2d, intersection_3d
from rotorcad.measured_outline import whole_outline
from rotorcad.rotor_pair import RotorPair
from rotorcad.screw_rotors import ScrewRotors
from rotorcad.solids import helical_solid

FORMATS = names()
"""The formats of the built-in table (:mod:`exports.formats`); ``--help`` and the check read the table itself."""


class _FormatOption(click.Option):
    """``--format``, whose help lists the formats of the table when it is shown (a row added later too)."""

    def get_help_record(self, ctx: click.Context) -> tuple[str, str] | None:
        self.help = "Comma-separated formats: " + ", ".join(names()) + ". Default: the design's [export] formats, else stl."
        return super().get_help_record(ctx)


LABELS = {
    "radial_clearance": "[housing] radial_clearance",
    "phase_deg": "--phase-deg",
    "center_distance": "--center-distance",
}
"""The options and design keys of the assembly's parameters (:func:`rotorcad.assembly.assemble`)."""


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
@click.option("--format", "formats", cls=_FormatOption, help="Comma-separated formats (the table of exports.formats).")
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
    if is_gear_design(data):  # formats default to stl, step and dxf, the tolerance to 5 µm
        from rotorcad.cli.gear_export import design_gear_bodies  # the gear commands' modules, for a gear only

        fmts = _asked_formats(formats, ["stl", "step", "dxf"], BodyKind.GEAR)
        tol = _surface_tolerance(0.005 if tolerance is None else tolerance)
        result: dict[str, Any] = {"tolerance": tol}

        def make_bodies() -> list[PlacedBody]:
            return design_gear_bodies(design, tol, data)

    else:
        settings = _design_settings(design, data)
        fmts = _asked_formats(formats, settings["export"].get("formats", ["stl"]), BodyKind.ROTOR)
        tol = _surface_tolerance(tolerance if tolerance is not None else float(settings["export"].get("tolerance", 0.005)))
        if not np.isfinite(angle):
            raise InputError(f"--angle must be a number of degrees (got {angle}).")
        result = {"tolerance": tol}
        label = "--tolerance" if tolerance is not None else "[export] tolerance"

        def make_bodies() -> list[PlacedBody]:
            return _rotor_bodies(design, settings, tol, label, angle, (center_distance, phase_deg, housing), result)

    # STEP and DXF are written by a worker process (exports.background), forked before the
    # progress bar's thread, while this one sweeps and meshes
    modules = preload(fmts)
    with WorkerPool(background=bool(modules), preload=modules) as pool:
        bodies = make_bodies()
        check_limits(fmts, bodies, tol)  # far over on the estimate: refused before any sweep
        folder = output_folder(out)
        progress = Steps("sweeping solids", sum(b.swept for b in bodies), quiet).start()
        outputs, rows = Outputs(), []
        for body in bodies:
            body.on_swept = progress.advance  # each solid is swept when a writer first needs it
        for path, row, writer in plan_files(fmts, bodies, tol, folder, design.stem):
            outputs.add(path, writer, "--out")
            rows.append(row)
        if is_gear_design(data):  # a gear design's rack ([rack]), in its own frame
            from rotorcad.cli.gear_export import design_rack_files

            rows += design_rack_files(design, [f.name for f in fmts], folder, tol, outputs, data)
        outputs.write(pool)
    progress.stop()
    for row in rows:
        row["size"] = Path(row["path"]).stat().st_size if Path(row["path"]).exists() else 0
        row["replaced"] = Path(row["path"]) in outputs.replaced  # a file that was there, replaced whole
    result = {"files": rows, **result}
    if as_json:
        emit_json(result)
    else:
        _print_files(rows, design.stem, folder)


def _asked_formats(asked: str | None, default: list[Any], kind: BodyKind) -> list[ExportFormat]:
    """Return the rows of the formats asked (``--format``, else ``default``), each once, in order.

    Refused in one sentence naming the formats of the table that write bodies of ``kind``.
    """
    given = asked.split(",") if asked else [str(f) for f in default]
    fmts = list(dict.fromkeys(f.strip().lower() for f in given))  # a format given twice is one file, one row
    allowed = names(kind)
    for f in fmts:  # before any folder is made: a failed run leaves none behind
        if f not in allowed:
            option = "--format for a gear design" if kind is BodyKind.GEAR else "--format"
            raise InputError(f"{option} must be a comma-separated list of {', '.join(allowed)} (got {f!r}).")
    return [table()[f] for f in fmts]


def _surface_tolerance(tol: float) -> float:
    """Return the surface tolerance (mm), refused unless between 0 and 1 mm."""
    if not (np.isfinite(tol) and 0 < tol <= 1.0):
        raise InputError(f"--tolerance must be a surface tolerance between 0 and 1 mm (got {tol}).")
    return tol


def _rotor_bodies(
    design: Path,
    settings: dict[str, Any],
    tol: float,
    label: str,
    angle: float,
    assembly: tuple[float | None, float, bool | None],
    result: dict[str, Any],
) -> list[PlacedBody]:
    """Build the rotors of a design and return them placed as assembled, with the housing when asked.

    ``assembly`` is (--center-distance, --phase-deg, --housing); the housing's radial clearance is
    put in ``result`` (key ``clearance``). A request whose solids would not fit in memory is
    refused naming ``label`` (:func:`rotorcad.assembly.check_solid_work`).
    """
    center_distance, phase_deg, housing = assembly
    rotors, _, clearance = build_rotors(design, _rotor_options(design), settings)
    pair, phase = _assemble(rotors.pair, center_distance, phase_deg, clearance)
    _check_solid_work(rotors, tol, label)
    result["clearance"] = clearance
    bodies = rotor_bodies(rotors, pair, float(np.radians(angle)), phase, tol)
    if housing if housing is not None else bool(settings["housing"]):
        bodies += housing_bodies(pair, clearance, tol)
    return bodies


def _print_files(rows: list[dict[str, Any]], stem: str, folder: Path) -> None:
    """Print the table of the files written: name after the stem, format, tolerance, volume, size."""
    table_ = Table(title=f"{len(rows)} files {stem}_<file> in {folder}", header_style="bold")
    table_.add_column("file", overflow="fold")  # the whole name after the stem, folded, never cut
    table_.add_column("format")
    for col in ("tolerance µm", "volume mm³", "size MB"):
        table_.add_column(col, justify="right")
    for row in rows:
        met = row.get("tolerance")
        table_.add_row(
            Path(row["path"]).name.removeprefix(f"{stem}_"),
            row["format"],
            "-" if met is None else f"{met * 1e3:.3g}",
            f"{row['volume']:.1f}",
            f"{row['size'] / 1e6:.2f}",
        )
    Console(file=sys.stdout, highlight=False).print(table_)


def _check_solid_work(rotors: ScrewRotors, tol: float, label: str) -> None:
    """Refuse a request whose two solids would not fit in memory (:func:`rotorcad.assembly.check_solid_work`)."""
    try:
        check_solid_work(rotors, tol, label)
    except DesignError as exc:
        raise InputError(exc.sentence()) from None


def _assemble(pair: RotorPair, center_distance: float | None, phase_deg: float, clearance: float) -> tuple[RotorPair, float]:
    """Return the pair as assembled and the female's extra turn (rad); bad values refused naming the option."""
    try:
        return assemble(pair, center_distance, phase_deg, clearance)
    except DesignError as exc:
        raise InputError(exc.sentence(LABELS.get(exc.param, exc.param))) from None


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
    try:
        check_section_work(rotors, tolerance, "--tolerance")
    except DesignError as exc:
        raise InputError(exc.sentence()) from None
    if check_3d:
        _check_solid_work(rotors, tolerance, "--tolerance")
    male = _as_built(rotors.section("male", tolerance / 2), "--male-points", male_points, layer, rotors.pair.male_teeth)
    female = _as_built(rotors.section("female", tolerance / 2), "--female-points", female_points, layer, rotors.pair.female_teeth)
    pair, phase = _assemble(rotors.pair, center_distance, phase_deg, clearance)
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
        result["check_3d"] = _intersection_3d(pair, male, female, tolerance, result_2d, progress)
    progress.stop()
    if as_json:
        emit_json(result)
    else:
        from rotorcad.cli.common import print_table

        print_table(f"interference of {Path(design).stem}", {k: v for k, v in result.items() if k != "check_3d"})
    if result["interferes"]:
        click.get_current_context().exit(1)  # a finding, not an error: pipelines test the status


def _as_built(section: shapely.Polygon, option: str, path: Path | None, layer: str | None, teeth: int) -> shapely.Polygon:
    """Return the rotor's section as built: the measured outline of ``path`` (own frame) or else ``section``.

    A file that cannot be read, or an outline that crosses itself (GEOS fails on it in the sweep,
    exit 70), is refused in one sentence naming ``option``.
    """
    if path is None:
        return section
    try:
        outline = shapely.Polygon(whole_outline(read_profile_points(path, option, layer), teeth, option))
    except DesignError as exc:
        raise InputError(exc.sentence()) from None
    if not outline.is_valid:
        why = shapely.validation.explain_validity(outline)
        raise InputError(f"{option} must be an outline that does not cross itself (got {path}): {why}.")
    return outline


def _intersection_3d(
    pair: RotorPair, male: shapely.Polygon, female: shapely.Polygon, tolerance: float, result_2d: Any, progress: Steps
) -> dict[str, Any]:
    """Sweep both solids and intersect them at the male angle of the 2-D maximum (``--check-3d``)."""
    lead = pair.lead if pair.hand == "right" else -pair.lead
    m = helical_solid(male, lead, pair.length, tolerance)
    progress.advance(description="interference: female solid")
    f = helical_solid(female, -np.sign(lead) * pair.female_lead, pair.length, tolerance)
    progress.advance(description="interference: 3-D intersection")
    found = intersection_3d(pair, m, f, result_2d.angle_of_max, result_2d.threshold)
    progress.advance()
    return found


__all__ = ["export", "interfere"]

"""``rotorcad export``: helical solids and files (CONTRACT.md); ``rotorcad interfere`` is :mod:`rotorcad.cli.interfere_cmd`."""

from __future__ import annotations

import sys
from pathlib import Path
from typing import Any

import click
import numpy as np
from rich.console import Console
from rich.table import Table

from exports.background import WorkerPool
from exports.formats import ExportFormat, check_limits, makes_meshes, names, plan_files, preload, table
from rotorcad.assembly import BodyKind, PlacedBody, assemble, check_solid_work, housing_bodies, rotor_bodies
from rotorcad.cli.common import InputError, Outputs, emit_json, load_rotor_design, load_toml, output_folder
from rotorcad.cli.progress import Steps
from rotorcad.cli.rotor import PAIR_OPTIONS
from rotorcad.cli.rotor import _build as build_rotors
from rotorcad.design.files import is_gear_design
from rotorcad.errors import DesignError
from rotorcad.rotor_pair import RotorPair
from rotorcad.screw_rotors import ScrewRotors

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
        noted = _say_gear_files(data, fmts, quiet)  # refused or noted from the teeth, before any gear is built

        def make_bodies() -> list[PlacedBody]:
            return design_gear_bodies(design, tol, data)

    else:
        settings = _design_settings(design, data)
        fmts = _asked_formats(formats, settings["export"].get("formats", ["stl"]), BodyKind.ROTOR)
        tol = _surface_tolerance(tolerance if tolerance is not None else float(settings["export"].get("tolerance", 0.005)))
        if not np.isfinite(angle):
            raise InputError(f"--angle must be a number of degrees (got {angle}).")
        result, noted = {"tolerance": tol}, False
        label = "--tolerance" if tolerance is not None else "[export] tolerance"

        def make_bodies() -> list[PlacedBody]:
            return _rotor_bodies(design, settings, (tol, fmts), label, angle, (center_distance, phase_deg, housing), result)

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
        _say_long_files(rows, quiet, progress, _herringbones(bodies), note=not noted)
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


def _herringbones(bodies: list[PlacedBody]) -> frozenset[str]:
    """Return the names of the bodies that are herringbone gears (their STEP has both halves' faces)."""
    return frozenset(b.name for b in bodies if b.features is not None and b.features.herringbone)


def _say_long_files(
    rows: list[dict[str, Any]], quiet: bool, progress: Steps | None, doubled: frozenset[str] = frozenset(), note: bool = True
) -> bool:
    """Refuse an exact STEP that would not fit in memory; say before writing when the STEP files take long.

    The STEP's faces are known once planned (a gear of 1000 teeth: 7002 faces, some 48 s of CPU
    and 4 minutes of wall time on a loaded 2-core machine, which a new user waited through without
    a word; a herringbone gear's plan counts one half's faces, ``doubled`` names those bodies); the
    meshes, drawings and points take seconds (:mod:`rotorcad.work`; that gear's STL and DXF: 3.2 s
    wall, 1 s of CPU, so "about 5 s" is named for ``--format`` without ``step``). A gear design's
    rows are first estimated from its teeth, before any gear is built (:func:`_say_gear_files`);
    ``note`` False then leaves the note, said already, unsaid. Returns whether a note was said.

    The note is said above :data:`rotorcad.work.STEP_NOTE_SECONDS` of the table's estimate times
    :func:`rotorcad.work.load_factor` (the machine's load now).

    Raises
    ------
    InputError
        A STEP estimated over :data:`rotorcad.work.MAX_STEP_MEGABYTES` (a herringbone gear of some
        850 teeth and more), naming ``--format`` and the most faces that would do.
    """
    from rotorcad.cli.progress import say_long_run
    from rotorcad.work import (
        MAX_STEP_MEGABYTES,
        STEP_NOTE_SECONDS,
        load_factor,
        long_run_note,
        step_faces_within,
        step_megabytes,
        step_seconds,
    )

    steps = [(row, row.get("faces", 0) * (2 if row.get("body") in doubled else 1), row.get("body") in doubled) for row in rows]
    steps = [(row, faces, both) for row, faces, both in steps if row["format"] == "step"]
    others = sorted({row["format"] for row in rows if row["format"] != "step"}) or ["stl"]
    for row, faces, both in steps:
        need = step_megabytes(faces, both)
        if need > MAX_STEP_MEGABYTES:
            what = "herringbone gear" if both else "solid"
            raise InputError(
                f"--format step cannot be written for the {row.get('body')}: its exact STEP of {faces:.0f} faces (a {what}) "
                f"would need about {need / 1000:.1f} GB, more than the {MAX_STEP_MEGABYTES / 1000:g} GB allowed; "
                f"--format {','.join(others)} would do, or one of at most about "
                f"{step_faces_within(MAX_STEP_MEGABYTES, both):.0f} faces (fewer teeth)."
            )
    load = load_factor()
    caveat = " (an estimate from measured runs" + (f", times {load:.1f} for this machine's load now" if load > 1 else "")
    seconds = load * sum(step_seconds(faces) for _, faces, _ in steps)
    said = long_run_note(seconds, ("--format", ",".join(others), 5.0), STEP_NOTE_SECONDS, caveat + ")")
    if said is not None and note:
        if progress is not None:
            progress.stop()  # the note on a line of its own, not through the bar
        say_long_run(said, quiet)
        if progress is not None:
            progress.start()
    return said is not None and note


GEAR_STEP_FACES = 7
"""Faces a tooth of an involute gear's exact STEP (two flanks, two fillets, tip, root and a joint), and 2 end faces.

Measured on the planned rows of ``export --format step``: z = 17, 20 give 121, 142 faces; a new
user's z = 1000: 7002."""


def _say_gear_files(data: dict[str, Any], fmts: list[ExportFormat], quiet: bool) -> bool:
    """Refuse or note a gear design's exact STEP from its teeth, before the gears are built; tell if a note was said.

    A herringbone gear of 1000 teeth was refused only after 105 s of building (newuser7 F4). The
    teeth and ``herringbone`` are read from the design (``[gear]``, ``[mate] teeth``) and the faces
    estimated as :data:`GEAR_STEP_FACES` a tooth; a value that is not a whole number is left to the
    design's own check.
    """
    if "step" not in {f.name for f in fmts} or "shaper" in data:  # an internal gear's ring: left to its plan
        return False
    gear, mate = data.get("gear", {}), data.get("mate", {})
    herringbone = gear.get("herringbone") is True
    rows = []
    for body, teeth in (("gear", gear.get("teeth")), ("mate", mate.get("teeth") if isinstance(mate, dict) else None)):
        if isinstance(teeth, int) and not isinstance(teeth, bool) and 0 < teeth <= 100_000:
            rows.append({"format": "step", "body": body, "faces": GEAR_STEP_FACES * teeth + 2})
    rows += [{"format": f.name, "body": "gear"} for f in fmts if f.name != "step"]
    return _say_long_files(rows, quiet, None, frozenset(("gear", "mate")) if herringbone else frozenset())


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
    asked: tuple[float, list[ExportFormat]],
    label: str,
    angle: float,
    assembly: tuple[float | None, float, bool | None],
    result: dict[str, Any],
) -> list[PlacedBody]:
    """Build the rotors of a design and return them placed as assembled, with the housing when asked.

    ``asked`` is the surface tolerance (mm) and the formats; ``assembly`` is (--center-distance,
    --phase-deg, --housing); the housing's radial clearance is put in ``result`` (key ``clearance``). A
    request for a mesh format whose solids would not fit in memory is refused naming ``label``
    (:func:`rotorcad.assembly.check_solid_work`), one whose exact formats would follow a looping outline
    too (:func:`_check_outlines`).
    """
    tol, fmts = asked
    center_distance, phase_deg, housing = assembly
    rotors, _, clearance = build_rotors(design, _rotor_options(design), settings)
    pair, phase = _assemble(rotors.pair, center_distance, phase_deg, clearance)
    if makes_meshes(fmts):  # the exact STEP, the drawings and the points hold no triangles
        _check_solid_work(rotors, tol, label)
    result["clearance"] = clearance
    bodies = rotor_bodies(rotors, pair, float(np.radians(angle)), phase, tol)
    _check_outlines(rotors, min(tol / 2, LOOP_CHORD), fmts)
    if housing if housing is not None else bool(settings["housing"]):
        bodies += housing_bodies(pair, clearance, tol)
    return bodies


LOOP_CHORD = 1e-4  # mm: outlines checked for loops at least this finely (the exact STEP follows the curves to 0.5 µm)
CURVE_FORMATS = ("step", "dxf")  # the formats that sweep or draw the outline's generated curves, not the section


def _check_outlines(rotors: ScrewRotors, chord: float, fmts: list[ExportFormat]) -> None:
    """Refuse the exact formats of a rotor whose outline crosses itself or leaves its tip circle; else a note.

    The meshes and the DXF polyline are made from the section (the outline made valid and clipped to the
    tip circle: loops and overshoot left out); the STEP solid and the DXF splines follow the generated
    curves themselves, and would be swept or drawn through the loop.
    """
    import warnings

    from rotorcad.errors import InputNote
    from rotorcad.families.checks import OUTLINE_FAULT_WHY, outline_faults

    said = outline_faults(rotors, chord)  # the words `hob` names them in too
    if not said:
        return
    why = OUTLINE_FAULT_WHY
    curves = [f.name for f in fmts if f.name in CURVE_FORMATS]
    if curves:
        raise InputError(
            f"--format {','.join(curves)} cannot be written for this design: {said}: {why}, and the exact curves "
            "would be swept or drawn through it; the meshes and dxf-r12 are written from the section trimmed to the "
            "tip circle (e.g. --format stl,dxf-r12), or give [profile] roundings the rotor can follow."
        )
    warnings.warn(f"{said}: {why}; the meshes are made from the section trimmed to the tip circle", InputNote, stacklevel=2)


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


__all__ = ["export"]

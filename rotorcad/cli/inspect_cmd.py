"""``rotorcad inspect``: measured points of a gear or a screw rotor against the nominal part (CONTRACT.md)."""

from __future__ import annotations

import math
from pathlib import Path
from typing import Any

import click
import numpy as np

from exports.dxf_points import read_measured_points
from rotorcad.cli.common import InputError, Outputs, emit_json, end_face, load_toml, print_table, seen_from_option
from rotorcad.cli.gear import build_gear, gear_options, merge_gear_params
from rotorcad.cli.rotor import rotors_of
from rotorcad.errors import DesignError, InputNote
from rotorcad.inspection.gear_inspection import GearInspection, inspect_gear
from rotorcad.inspection.nominal import nominal_flanks
from rotorcad.inspection.profile_deviations import MIN_POINTS
from rotorcad.inspection.rotor_inspection import RotorInspection, inspect_rotor
from rotorcad.inspection.tolerances import CLASSES
from rotorcad.measured.end_face import design_deviation, mirror_note, seen_from_suction
from rotorcad.roles import EndFace

MIN_POINTS_READ = 10
"""Fewest points an inspection takes."""
FAR_MODULES = 0.1
"""Gear: a point farther than this many modules from every nominal flank (or outside the root and
tip circles by as much) is no point of the teeth."""
FAR_DEPTH = 0.05
"""Rotor: a point farther from the outline than this share of the profile depth (tip less root
radius) is no point of the rotor."""


@click.command()
@click.argument("design", required=False, type=click.Path(path_type=Path, dir_okay=False))
@gear_options
@click.option(
    "--points",
    "points_files",
    multiple=True,
    type=click.Path(path_type=Path, dir_okay=False),
    help="Measured points (CSV x,y or DXF, mm, the part's axis frame, transverse section); repeat for several files.",
)
@click.option("--layer", help="Layer of the points in DXF files (default: their only layer).")
@click.option(
    "--rotor", "body", type=click.Choice(["male", "female"]), help="Rotor of a pair design (default: male); not for a gear."
)
@seen_from_option
@click.option(
    "--class",
    "tolerance_class",
    type=int,
    help=f"ISO 1328-1:2013 flank tolerance class to judge by ({CLASSES[0]}..{CLASSES[1]}).",
)
@click.option("--plot", type=click.Path(path_type=Path, dir_okay=False), help="Profile chart (PNG, SVG or PDF by the suffix).")
@click.option("--json", "as_json", is_flag=True, help="Print one JSON object on stdout.")
@click.option("--quiet", is_flag=True, help="No progress output.")
def inspect(design: Path | None, **opts: Any) -> None:
    """Judge measured points of a gear's teeth (ISO 1328-1) or of a screw rotor against the nominal part.

    DESIGN is a gear design ([gear]; or the gear options) or a rotor pair design ([pair], with
    --rotor). Gear: profile deviations F_alpha, f_falpha, f_Halpha over the evaluation range,
    single and cumulative pitch deviations over the teeth measured, tooth thickness deviation,
    per flank (left, right), after the best-fit rotation of the points. Rotor: the normal
    deviation from the nominal outline along the profile, per flank.
    """
    data = None
    if design is not None:
        try:
            data = load_toml(design)
        except DesignError as exc:
            raise InputError(exc.sentence()) from None
    points = _read_points(opts)
    face = end_face(opts.pop("seen_from", None))  # a rotor's section seen from the discharge end: mirrored first
    out = Outputs()
    rotors = rotors_of(design, data, opts)
    if rotors is not None:
        if opts["tolerance_class"] is not None:
            raise InputError("--class is for gears (ISO 1328-1); a rotor is judged by its normal deviation only.")
        opts["body"] = opts["body"] or "male"
        rotor = _inspect_rotor(rotors, opts["body"], seen_from_suction(points, face), face)
        result = {"body": opts["body"], "seen_from": str(face), **rotor.summary()}
        if opts["plot"] is not None:
            from rotorcad.inspection.charts import rotor_chart

            case = f"{opts['body']} rotor against its outline: {rotor.points_given} points"
            out.add_figure(opts["plot"], lambda: rotor_chart(rotor, case), "--plot")
    else:
        if opts["body"] is not None:
            raise InputError(f"--rotor is for a screw-rotor pair design ([pair]); a gear has no {opts['body']} rotor.")
        if face is not EndFace.SUCTION:
            raise InputError("--seen-from is for a screw rotor's section; a gear's flanks are named from its reference face.")
        gear, result = _inspect_gear(design, data, opts, points)
        if opts["plot"] is not None:
            from rotorcad.inspection.charts import profile_chart

            case = f"profile chart: gear z={gear.nominal.teeth}, m={gear.nominal.module:g} mm"
            out.add_figure(opts["plot"], lambda: profile_chart(gear, case), "--plot")
    result["files"] = [str(p) for p in out.write()]
    if opts["as_json"]:
        emit_json(result)
    else:
        _print(result)


def _read_points(opts: dict[str, Any]) -> np.ndarray:
    """Read every ``--points`` file (CSV or DXF) into one (n, 2) array, mm."""
    if not opts["points_files"]:
        raise InputError("--points must be given: a CSV (x,y) or DXF file of the measured points in mm.")
    try:
        parts = [read_measured_points(p, "--points", opts["layer"]) for p in opts["points_files"]]
    except DesignError as exc:
        raise InputError(exc.sentence()) from None
    points = np.vstack(parts)
    if len(points) < MIN_POINTS_READ:
        raise InputError(f"--points must hold at least {MIN_POINTS_READ} points of the teeth (got {len(points)}).")
    return points


def _inspect_gear(
    design: Path | None, data: dict[str, Any] | None, opts: dict[str, Any], points: np.ndarray
) -> tuple[GearInspection, dict[str, Any]]:
    """Build the nominal gear (with its mate, if any), check the points' place and inspect them.

    Returns the inspection and its JSON; with tooth-thickness allowances in the design (DIN 3967)
    the JSON also has ``thickness_allowance`` and ``thickness_within_allowance``.
    """
    params = merge_gear_params(design, opts, data)
    gear, pair = build_gear(params, 1e-4)
    nominal = nominal_flanks(gear, pair)
    far = FAR_MODULES * gear.module
    r = np.hypot(points[:, 0], points[:, 1])
    worst = int(np.argmax(np.maximum(gear.root_radius - far - r, r - gear.tip_radius - far)))
    if not gear.root_radius - far <= r[worst] <= gear.tip_radius + far:
        x, y = points[worst]
        raise InputError(
            f"--points must lie between the root circle and the tip circle (radius {gear.root_radius - far:.4f} to "
            f"{gear.tip_radius + far:.4f} mm with {FAR_MODULES:g} m to spare; got the point ({x:.4f}, {y:.4f}) "
            f"at {r[worst]:.4f} mm)."
        )
    try:
        result = inspect_gear(points, nominal, opts["tolerance_class"])
    except DesignError as exc:
        raise InputError(exc.sentence("--class")) from None
    lo, hi = (float(v) for v in nominal.radius_at(np.array(nominal.evaluation_range)))
    if not result.flanks:
        raise InputError(
            f"--points must hold at least {MIN_POINTS} points on one tooth flank within the evaluation range "
            f"(radius {lo:.4f} to {hi:.4f} mm); no flank has that many of the {len(points)} points."
        )
    off = np.abs(result.fit.deviation)
    if off.size and off.max() > far:
        x, y = points[result.fit.index[int(np.argmax(off))]]
        raise InputError(
            f"--points must lie within {far:.4g} mm ({FAR_MODULES:g} m) of a nominal tooth flank after the best-fit rotation "
            f"of {math.degrees(result.fit.rotation):.4f} deg; the point ({x:.4f}, {y:.4f}) lies {off.max():.4f} mm off."
        )
    summary = result.summary()
    upper, lower = params.get("thickness_allowance_upper") or 0.0, params.get("thickness_allowance_lower") or 0.0
    if (upper or lower) and result.thickness:
        summary["thickness_allowance"] = {"upper": upper, "lower": lower}
        summary["thickness_within_allowance"] = all(lower <= d <= upper for d in result.thickness.values())
    return result, summary


def _inspect_rotor(rotors: Any, body: str, points: np.ndarray, face: EndFace = EndFace.SUCTION) -> RotorInspection:
    """Inspect the points against the male's or the female's outline; refuse points far from it.

    Points whose mirror image lies on the outline and they do not (a section seen from the other end
    face, :func:`rotorcad.measured.end_face.mirror_note`) are said so: in the refusal, or in a note.
    """
    import warnings

    pair = rotors.pair
    if body == "male":
        outline, lobes = rotors.male_outline(1e-4), pair.male_teeth
    else:
        outline, lobes = rotors.female_outline(1e-4), pair.female_teeth
    result = inspect_rotor(points, outline, lobes)
    note = mirror_note(*design_deviation(points, outline.points, lobes), 0.0, face, "--points")
    r = np.hypot(*outline.points.T)
    far = FAR_DEPTH * float(r.max() - r.min())
    off = np.abs(result.deviation)
    if off.max() > far:
        x, y = points[int(np.argmax(off))]
        raise InputError(
            f"--points must lie within {far:.4g} mm ({FAR_DEPTH:g} of the profile depth) of the {body}'s outline after "
            f"the best-fit rotation of {math.degrees(result.rotation):.4f} deg; the point ({x:.4f}, {y:.4f}) lies "
            f"{off.max():.4f} mm off" + ("" if note is None else f" ({note})") + "."
        )
    if note is not None:
        warnings.warn(note, InputNote, stacklevel=2)
    return result


def _print(result: dict[str, Any]) -> None:
    """Print the result as tables: the figures, each side's largest deviations and, for a gear, every flank in µm."""
    flat = {k: v for k, v in result.items() if not isinstance(v, dict | list)}
    for key in ("alignment", "evaluation_range", "tolerances", "within_tolerance", "classes", "thickness_allowance"):
        flat.update({f"{key}.{k}": v for k, v in result.get(key, {}).items()})
    print_table(f"inspection of the {result['body']}", flat)
    for side in ("left", "right"):
        print_table(f"{side} flanks", {f"{side}.{k}": v for k, v in result[side].items()})
    if "flanks" in result:
        from rich.console import Console
        from rich.table import Table

        table = Table(title="flanks [µm]", header_style="bold")
        for column in ("tooth", "flank", "F_alpha", "f_f_alpha", "f_H_alpha", "f_pt"):
            table.add_column(column, justify="right")
        for f in result["flanks"]:
            um = [f[k] for k in ("total_profile_deviation", "profile_form_deviation", "profile_slope_deviation")]
            pitch = f["single_pitch_deviation"]
            table.add_row(
                str(f["tooth"]), f["flank"], *(f"{v * 1e3:.2f}" for v in um), "" if pitch is None else f"{pitch * 1e3:.2f}"
            )
        Console(highlight=False).print(table)
    for p in result["files"]:
        click.echo(f"wrote {p}")

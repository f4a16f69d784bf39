"""``rotorcad grind``: the form-grinding wheel of a rotor or gear, checked, and the dresser's files."""

from __future__ import annotations

import math
from pathlib import Path
from typing import Any

import click
import numpy as np

from exports.csv_points import write_points
from exports.dresser import write_wheel_csv, write_wheel_dxf
from rotorcad.cli.common import InputError, Outputs, emit_json, load_toml, output_folder, print_table
from rotorcad.cli.gear import build_gear, gear_options, merge_gear_params
from rotorcad.cli.rotor import rotor_input_options, rotors_of
from rotorcad.errors import DesignError
from rotorcad.geometry import rotate
from rotorcad.grinding.job import GrindingJob, cut_depth, grind, least_cutting_angle
from rotorcad.grinding.sensitivity import ERRORS, UNITS, Sensitivity, compensate, normal_deviation, sensitivities
from rotorcad.grinding.setting import MAX_WHEEL_RADIUS
from rotorcad.grinding.wheel_profile import WheelProfile as GrindingWheel
from rotorcad.grinding.wheel_section import STANDARD_BORE_RADIUS, WheelSection, wheel_section

OPTION_NAMES = {
    "wheel_radius": "--wheel-radius",
    "center_distance": "--wheel-center-distance",
    "crossing_angle": "--crossing-angle",
    "setting_radius": "--setting-radius",
    "wheel_width": "--wheel-width",
    "bore_radius": "--wheel-bore-radius",
}
"""The grinding library's parameters as this command's options, for refusals."""


@click.command()
@click.argument("design", required=False, type=click.Path(path_type=Path, dir_okay=False))
@gear_options
@rotor_input_options
@click.option(
    "--rotor",
    "body",
    type=click.Choice(["male", "female", "gear", "mate"]),
    help="Body to grind: male or female of a rotor pair (default male); gear or mate of a gear design (default gear).",
)
@click.option("--wheel-radius", type=float, help=f"Outside radius of the new wheel [mm], above 0, at most {MAX_WHEEL_RADIUS:g}.")
@click.option(
    "--worn-radius", type=float, help="Outside radius of the worn wheel [mm], above 0, below --wheel-radius: its profile too."
)
@click.option(
    "--crossing-angle",
    type=float,
    help="Angle between the wheel's mid-plane and the rotor axis [deg], |angle| < 80. "
    "Default: the helix angle at --setting-radius.",
)
@click.option(
    "--setting-radius", type=float, help="Radius whose helix angle is the default crossing angle [mm]. Default: the pitch radius."
)
@click.option(
    "--wheel-center-distance",
    type=float,
    help="Distance of the wheel axis from the rotor axis [mm], above the root radius. Default: root radius + wheel radius "
    "(the worn wheel's: this minus the wear).",
)
@click.option(
    "--wheel-width",
    type=float,
    help="Width of the wheel between its side faces [mm], at least the profile's. Default: the profile's plus 1 mm "
    "each side, rounded up to a whole mm.",
)
@click.option(
    "--wheel-bore-radius",
    type=float,
    help=f"Radius of the wheel's bore [mm], below the shoulder radius. Default {STANDARD_BORE_RADIUS:g} (a 127 mm bore), "
    "or half the shoulder radius on a smaller wheel.",
)
@click.option(
    "--out", type=click.Path(path_type=Path, file_okay=False), help="Folder for the dresser's CSV and DXF (R12, R2000) files."
)
@click.option(
    "--plot",
    type=click.Path(path_type=Path, dir_okay=False),
    help="Chart (PNG, SVG or PDF by the suffix): the wheel profiles and the rotor's deviation for each setting error.",
)
@click.option(
    "--least-cutting-angle",
    is_flag=True,
    help="Also find the crossing angle at which the new wheel cuts least into the rotor (a scan: some seconds).",
)
@click.option("--json", "as_json", is_flag=True, help="Print one JSON object on stdout.")
@click.option("--quiet", is_flag=True, help="No progress output.")
def grind_cmd(design: Path | None, **opts: Any) -> None:
    """Give the form-grinding wheel's axial profile for a rotor of a pair or a helical gear.

    The wheel's axis crosses the rotor's at the crossing angle; its profile follows from the contact
    condition (the common normal meets the wheel axis). The wheel is checked against the rotor:
    secondary cutting, flank parts it does not reach, and the rotor it grinds back.
    """
    wheel_radius, worn = _check_numbers(opts)
    body = _body(design, opts)
    setting_radius, angle = _setting(body, opts)
    radii = {"new": wheel_radius} | ({"worn": worn} if worn is not None else {})
    jobs: dict[str, GrindingJob] = {}
    for state, radius in radii.items():
        a = opts["wheel_center_distance"]
        if a is not None:
            a -= wheel_radius - radius  # the worn wheel plunges by its wear
        try:
            jobs[state] = grind(body["outline"], body["twist"], body["lobes"], radius, setting_radius, angle, a)
        except DesignError as exc:
            label = OPTION_NAMES.get(exc.param)
            if state == "worn":  # the worn wheel's values follow from --worn-radius
                label = {"wheel_radius": "--worn-radius", "center_distance": "--wheel-center-distance less the wear"}.get(
                    exc.param, label
                )
            raise InputError(exc.sentence(label)) from None
    sections = _sections(jobs, opts)
    result: dict[str, Any] = {
        "body": body["name"],
        "lobe_count": body["lobes"],
        "lead": body["lead"],
        "tip_radius": jobs["new"].wheel.flute.tip_radius,
        "root_radius": jobs["new"].wheel.flute.root_radius,
        "setting_radius": setting_radius,
        "crossing_angle_deg": math.degrees(jobs["new"].wheel.setting.crossing_angle),
        "wheels": {state: job.summary() | _section_summary(sections[state]) for state, job in jobs.items()},
    }
    sens = sensitivities(jobs["new"].wheel)
    result["sensitivity"] = {
        name: {"unit": UNITS[name], "max_normal_deviation_per_unit": value} for name, value in sens.largest().items()
    }
    if opts["least_cutting_angle"]:
        a = opts["wheel_center_distance"]
        best, job = least_cutting_angle(body["outline"], body["twist"], body["lobes"], wheel_radius, setting_radius, a)
        numbers = job.summary()
        result["least_cutting"] = {
            "crossing_angle_deg": math.degrees(best),
            "deepest_cut_deviation": cut_depth(job),
            **{k: numbers[k] for k in ("secondary_cutting_point_count", "secondary_cutting_deviation", "no_contact_point_count")},
        }
    if "worn" in jobs:
        result["worn_with_new_profile"] = _worn_with_new_profile(jobs["new"].wheel, wheel_radius - worn)
    result["files"] = _write_files(opts, jobs, sections, body, sens)
    if opts["as_json"]:
        emit_json(result)
        return
    print_table(f"grinding wheel for the {body['name']}", {k: v for k, v in result.items() if k not in ("wheels", "files")})
    for state, numbers in result["wheels"].items():
        print_table(f"{state} wheel", numbers)
    _print_sensitivity(result["sensitivity"])
    if "least_cutting" in result:
        print_table("crossing angle of the least secondary cutting (new wheel)", result["least_cutting"])
    if "worn_with_new_profile" in result:
        print_table("worn wheel left at the new wheel's profile", result["worn_with_new_profile"])
    for p in result["files"]:
        click.echo(f"wrote {p}")


def _sections(jobs: dict[str, GrindingJob], opts: dict[str, Any]) -> dict[str, WheelSection]:
    """Close each wheel's profile into its section: one width and bore for new and worn wheel.

    By default the widest profile's width and the least default bore of the wheels (the worn wheel's
    shoulder is lower).
    """
    width, bore = opts["wheel_width"], opts["wheel_bore_radius"]
    try:
        if width is None or bore is None:
            defaults = [wheel_section(job.wheel, width, bore) for job in jobs.values()]
            width = max(d.width for d in defaults) if width is None else width
            bore = min(d.bore_radius for d in defaults) if bore is None else bore
        return {state: wheel_section(job.wheel, width, bore) for state, job in jobs.items()}
    except DesignError as exc:
        raise InputError(exc.sentence(OPTION_NAMES.get(exc.param))) from None


def _section_summary(section: WheelSection) -> dict[str, float]:
    """Return the section's keys of a wheel in ``rotorcad grind --json`` (mm)."""
    return {"wheel_width": section.width, "bore_radius": section.bore_radius, "shoulder_radius": section.shoulder_radius}


def _write_files(
    opts: dict[str, Any], jobs: dict[str, GrindingJob], sections: dict[str, WheelSection], body: dict[str, Any], sens: Sensitivity
) -> list[str]:
    """Write the dresser's files (``--out``) and the chart (``--plot``), all or none; return their paths."""
    out = Outputs()
    if opts["out"] is not None:
        folder = output_folder(opts["out"])
        for state, job in jobs.items():
            _add_files(out, folder, f"wheel_{body['name']}_{state}", job, sections[state], body["name"])
        rows = _sensitivity_rows(jobs["new"].wheel, sens)
        header = "rotor_x,rotor_y,flute_arc_length," + ",".join(ERRORS)
        notes = [
            f"the {body['name']}'s normal deviation (mm, + thicker) per unit error of the new wheel's setting: "
            + ", ".join(f"{n} per {UNITS[n]}" for n in ERRORS),
            "rotor_x, rotor_y: the rotor point in its own frame [mm]; flute_arc_length: from the flute's first tip [mm]",
        ]
        out.add(folder / f"wheel_{body['name']}_sensitivity.csv", lambda p: write_points(p, rows, notes, header=header), "--out")
    if opts["plot"] is not None:
        from rotorcad.grinding.plotting import grinding_chart  # matplotlib only for a picture

        case = f"form-grinding wheel for the {body['name']}"
        out.add_figure(opts["plot"], lambda: grinding_chart({k: j.wheel for k, j in jobs.items()}, sens, case), "--plot")
    return [str(p) for p in out.write()]


def _check_numbers(opts: dict[str, Any]) -> tuple[float, float | None]:
    """Return the new and the worn wheel radius (mm) after checking every number given."""
    wheel_radius, worn = opts["wheel_radius"], opts["worn_radius"]
    if wheel_radius is None:
        raise InputError(
            f"--wheel-radius must be given: the new wheel's outside radius in mm (above 0, at most {MAX_WHEEL_RADIUS:g})."
        )
    if not (math.isfinite(wheel_radius) and 0 < wheel_radius <= MAX_WHEEL_RADIUS):
        raise InputError(f"--wheel-radius must be above 0 and at most {MAX_WHEEL_RADIUS:g} mm (got {wheel_radius}).")
    if worn is not None and not (math.isfinite(worn) and 0 < worn < wheel_radius):
        raise InputError(f"--worn-radius must be above 0 and below --wheel-radius {wheel_radius:g} mm (got {worn}).")
    for key in ("crossing_angle", "setting_radius", "wheel_center_distance"):
        v = opts[key]
        if v is not None and not math.isfinite(v):
            raise InputError(f"--{key.replace('_', '-')} must be a finite number (got {v}).")
    return wheel_radius, worn


def _setting(body: dict[str, Any], opts: dict[str, Any]) -> tuple[float, float | None]:
    """Return the setting radius (mm) and the crossing angle given (rad, or None for the helix angle there)."""
    setting_radius = body["pitch_radius"] if opts["setting_radius"] is None else opts["setting_radius"]
    angle = None if opts["crossing_angle"] is None else math.radians(opts["crossing_angle"])
    if angle is None and opts["setting_radius"] is not None and body["twist"] != 0.0:
        most = math.tan(math.radians(80.0)) / abs(body["twist"])  # the helix angle there reaches 80 deg
        if not 0 < setting_radius <= most:
            raise InputError(
                f"--setting-radius must be above 0 and at most {most:.6g} mm, where the helix angle reaches 80 deg "
                f"(got {setting_radius})."
            )
    return setting_radius, angle


def _print_sensitivity(sensitivity: dict[str, dict[str, Any]]) -> None:
    """Print the largest normal deviation per unit error, with its unit (mm/mm or mm/deg)."""
    from rich.console import Console
    from rich.table import Table

    table = Table(title="largest normal deviation of the rotor per unit error (new wheel)", header_style="bold")
    for column, justify in (("error", "left"), ("value", "right"), ("unit", "left")):
        table.add_column(column, justify=justify)
    from rotorcad.quantities import unit_of

    for name, row in sensitivity.items():  # the row's unit, mm/mm or mm/deg, as rotorcad.quantities declares it
        table.add_row(f"sensitivity.{name}", f"{row['max_normal_deviation_per_unit']:.6f}", unit_of(f"sensitivity.{name}"))
    Console(highlight=False).print(table)


def _worn_with_new_profile(wheel: GrindingWheel, wear: float) -> dict[str, float]:
    """Judge the worn wheel dressed to the new one's profile: its deviation, and the crossing angle that helps most."""
    errors = {"wheel_radius": wear}
    before = normal_deviation(wheel, errors)
    fix = compensate(wheel, errors, ("crossing_angle",))
    after = normal_deviation(wheel, {**errors, **fix})
    return {  # over the points where the wheel still touches the rotor
        "wheel_radius_change": -wear,
        "max_normal_deviation": float(np.nanmax(np.abs(before))),
        "rms_normal_deviation": float(np.sqrt(np.nanmean(before**2))),
        "best_crossing_angle_change_deg": fix["crossing_angle"],
        "max_normal_deviation_compensated": float(np.nanmax(np.abs(after))),
        "rms_normal_deviation_compensated": float(np.sqrt(np.nanmean(after**2))),
    }


def _sensitivity_rows(wheel: GrindingWheel, sens: Sensitivity) -> np.ndarray:
    """Rows of the sensitivity CSV: rotor point (own frame), arc length along the flute, per-unit deviations."""
    own = rotate(sens.points, -wheel.flute.turn)
    arc = np.concatenate([[0.0], np.cumsum(np.hypot(*np.diff(sens.points, axis=0).T))])
    return np.column_stack([own, arc, sens.per_unit.T])


def _add_files(out: Outputs, folder: Path, stem: str, job: GrindingJob, section: WheelSection, name: str) -> None:
    """Add the profile's CSV, the section's CSV and the two DXF of one wheel to ``out``."""
    s = job.wheel.setting
    rows = job.rows()
    label = (
        f"{name}: wheel radius {s.wheel_radius:g} mm, centre distance {s.center_distance:.6g} mm, "
        f"crossing angle {math.degrees(s.crossing_angle):.6g} deg"
    )
    comments = [
        f"form-grinding wheel axial profile for the {label}",
        "axial: from the wheel's mid-plane along its axis [mm]; radius: from the wheel axis [mm]; "
        "normal: outward unit normal; rotor_x, rotor_y: the rotor point ground [mm]",
    ]
    out.add(folder / f"{stem}.csv", lambda p: write_wheel_csv(p, rows, comments), "--out")
    ring = section.outline()
    notes = [
        f"form-grinding wheel section for the {label}: width {section.width:g} mm, bore radius {section.bore_radius:g} mm",
        "the closed outline counter-clockwise: the profile, the shoulders, the side faces, the bore; axial, radius [mm]",
    ]
    out.add(folder / f"{stem}_section.csv", lambda p: write_points(p, ring, notes, header="axial,radius"), "--out")
    for version in ("R12", "R2000"):
        out.add(
            folder / f"{stem}_{version.lower()}.dxf",
            lambda p, v=version: write_wheel_dxf(p, rows[:, 0], rows[:, 1], label, v, section.sides()),
            "--out",
        )


def _body(design: Path | None, opts: dict[str, Any]) -> dict[str, Any]:
    """Build the rotor or gear to grind: outline, twist (rad/mm), lobes, signed lead (mm, None spur), pitch radius."""
    data = None
    if design is not None:
        try:
            data = load_toml(design)
        except DesignError as exc:
            raise InputError(exc.sentence()) from None
    rotors = rotors_of(design, data, opts)
    if rotors is not None:
        if opts["body"] in ("gear", "mate"):
            raise InputError(f"--rotor must be male or female for a rotor pair (got {opts['body']}: that names a gear).")
        pair = rotors.pair
        hand = 1.0 if pair.hand == "right" else -1.0
        if opts["body"] in (None, "male"):
            lead, outline, lobes, pitch = hand * pair.lead, rotors.male_outline(), pair.male_teeth, pair.male_pitch_radius
        else:  # the female's helix is of the other hand
            lead, outline, lobes, pitch = (
                -hand * pair.female_lead,
                rotors.female_outline(),
                pair.female_teeth,
                pair.female_pitch_radius,
            )
        return {
            "name": opts["body"] or "male",
            "outline": outline,
            "twist": 2 * np.pi / lead,
            "lobes": lobes,
            "lead": lead,
            "pitch_radius": pitch,
        }
    return _gear_body(design, data, opts)


def _gear_body(design: Path | None, data: dict[str, Any] | None, opts: dict[str, Any]) -> dict[str, Any]:
    """Build the gear or its mate (``--rotor gear|mate``) to grind, as :func:`_body` returns it.

    The mate of an external pair has the helix of the other hand (:func:`rotorcad.assembly.gear_lead`).
    """
    which = opts["body"] or "gear"
    if which in ("male", "female"):
        raise InputError(f"--rotor must be gear or mate for a gear design (got {which}: that names a screw rotor).")
    gear, pair = build_gear(merge_gear_params(design, opts, data), 1e-4)
    hand = 1.0
    if which == "mate":
        if pair is None:
            raise InputError("--rotor mate needs a mating gear: give --mate-teeth (or [mate] teeth in the design).")
        gear, hand = pair.mate, -1.0
    twist = hand * float(np.tan(gear.helix_angle) / gear.pitch_radius)  # right hand for beta > 0 (rotorcad.solids)
    lead = 2 * np.pi / twist if twist != 0.0 else None
    return {
        "name": which,
        "outline": gear.outline(),
        "twist": twist,
        "lobes": gear.teeth,
        "lead": lead,
        "pitch_radius": gear.pitch_radius,
    }

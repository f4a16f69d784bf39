"""``rotorcad clearance``: meshing clearance from discrete profile points (CONTRACT.md)."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import click
import numpy as np

from exports.csv_points import write_points
from exports.dxf_profile import read_profile
from exports.reading import check_regular_file
from rotorcad.clearance import CONTACT_SIDES, MeshingClearance, ThermalState, pair_quality
from rotorcad.clearance_thermal import GREY_CAST_IRON_EXPANSION, REFERENCE_TEMPERATURE, STEEL_EXPANSION
from rotorcad.cli.common import InputError, Outputs, emit_json, end_face, print_table, seen_from_option
from rotorcad.cli.progress import say_long_run
from rotorcad.errors import DesignError
from rotorcad.measured.end_face import seen_from_suction
from rotorcad.measured.fit import close_smoothing
from rotorcad.measured.outline import own_frame
from rotorcad.measured.point_checks import refuse_pitch_off_profile
from rotorcad.roles import Side
from rotorcad.rotor_pair import RotorPair
from rotorcad.rotor_points import as_given, lobe_pieces, profile_points
from rotorcad.work import clearance_seconds, long_run_note

INTERFERENCE_THRESHOLD = 2e-3
"""mm: a clearance below minus this (or minus the stated accuracy, the larger) is an interference.
A conjugate pair given by exact points measures 0 within 1 µm (README), so less is no finding."""
DEFAULT_LEAD, DEFAULT_LENGTH = 300.0, 190.0  # mm: taken when --lead / --length are not given, and said so (result's defaults)


@click.command()
@click.option(
    "--male-points", type=click.Path(path_type=Path, dir_okay=False), help="Male profile points (CSV x,y in mm, own frame)."
)
@click.option(
    "--female-points", type=click.Path(path_type=Path, dir_okay=False), help="Female profile points (CSV x,y in mm, own frame)."
)
@seen_from_option
@click.option("--male-teeth", type=int, help="Male lobes z1 (2..12). Required.")
@click.option("--female-teeth", type=int, help="Female lobes z2 (2..12). Required.")
@click.option("--center-distance", type=float, help="Centre distance a [mm] at which the pair runs. Required.")
@click.option(
    "--lead",
    type=float,
    help=f"Male lead h1 [mm]: the normal section and the contact line follow from it. Default {DEFAULT_LEAD:g} (said so).",
)
@click.option("--length", type=float, help=f"Rotor length L [mm] (the contact line's). Default {DEFAULT_LENGTH:g} (said so).")
@click.option(
    "--contact",
    type=click.Choice(CONTACT_SIDES),
    default="driving",
    show_default=True,
    help="Where the racks are brought into contact: the driving or the sealing flank, or as the points were given.",
)
@click.option(
    "--smoothing",
    type=float,
    help="Spline smoothing of the points [mm^2], 0 interpolates. Default: n sigma^2 from the points' estimated scatter.",
)
@click.option("--layer", help="Layer of the profile in DXF points files (default: their only layer).")
@click.option("--male-layer", help="Layer of the male in its DXF file, e.g. MALE_SPLINE as export writes it (default: --layer).")
@click.option(
    "--female-layer", help="Layer of the female in its DXF file, e.g. FEMALE_SPLINE as export writes it (default: --layer)."
)
@click.option(
    "--suction-temperature", type=float, help="Suction temperature [degC]: evaluate the pair hot (with --discharge-temperature)."
)
@click.option("--discharge-temperature", type=float, help="Discharge temperature [degC]; the rotors take the mean of the two.")
@click.option("--housing-temperature", type=float, help="Housing temperature [degC]. Default: the rotors' temperature.")
@click.option(
    "--reference-temperature",
    type=float,
    help=f"Temperature of the points [degC]. Default {REFERENCE_TEMPERATURE:g} (said so, with temperatures).",
)
@click.option(
    "--rotor-expansion", type=float, help=f"Rotors' linear expansion coefficient [1/K]. Default {STEEL_EXPANSION:g} (steel)."
)
@click.option(
    "--housing-expansion",
    type=float,
    help=f"Housing's linear expansion coefficient [1/K]: sets the hot centre distance. Default {GREY_CAST_IRON_EXPANSION:g} "
    "(grey cast iron).",
)
@click.option("--json", "as_json", is_flag=True, help="Print one JSON object on stdout.")
@click.option("--plot", type=click.Path(path_type=Path, dir_okay=False), help="PNG of the clearance along the datum rack.")
@click.option(
    "--csv",
    "csv_path",
    type=click.Path(path_type=Path, dir_okay=False),
    help="Write the clearance distribution: datum (female) normal rack x, y, clearance [mm], male angle [deg], z, "
    "contact point, female and male profile points [mm], in_contact, zone, gap [mm], flank (1 driving, 2 sealing, 3/4 lands).",
)
@click.option("--quiet", is_flag=True, help="No progress output.")
def clearance(**opts: Any) -> None:
    """Meshing clearance of a screw-rotor pair from measured profile points (Wu & Chi).

    The normal racks of both rotors, brought into contact, the normal clearance along the female's
    rack, and the clearance band on the 3D contact line (area, equal clearance, wetted perimeter).
    """
    from rotorcad.cli.defaults import print_defaults, taken
    from rotorcad.cli.progress import Steps

    defaults = {
        f"--{key}": taken(f"{value:g} mm", "not given: give the rotors' own, the normal clearance and the band change with it")
        for key, value in (("lead", DEFAULT_LEAD), ("length", DEFAULT_LENGTH))
        if opts[key] is None
    }
    opts = {**opts, **{key: value for key, value in (("lead", DEFAULT_LEAD), ("length", DEFAULT_LENGTH)) if opts[key] is None}}
    with Steps("clearance: racks, contact and band", None, opts["quiet"]):  # seconds of work: a bar on a terminal
        mc = _evaluate(opts)
    thermal = _thermal(opts)
    try:
        result = {
            **mc.summary(),
            "male_teeth": mc.pair.male_teeth,
            "female_teeth": mc.pair.female_teeth,
            "center_distance": mc.pair.center_distance,  # the one the pair runs at: hot, with temperatures
            **({} if thermal is None else thermal.keys(opts["center_distance"])),
            "seen_from": str(end_face(opts.get("seen_from"))),
            "defaults": {**defaults, **_thermal_defaults(opts, thermal)},
        }
    except DesignError as exc:
        raise InputError(exc.sentence()) from None
    # only a contact zone negative beyond what the points can tell is a finding
    result["interference"] = bool(result["min_normal_clearance"] < -max(INTERFERENCE_THRESHOLD, result["accuracy"]))
    if result["interference"]:  # never silent: a hot pair can run into interference
        click.echo(
            f"rotorcad: warning: the rotors interfere: the normal clearance goes down to "
            f"{result['min_normal_clearance'] * 1e3:.1f} µm (negative) on the contact zone, "
            f"beyond the accuracy of {result['accuracy'] * 1e3:.1f} µm.",
            err=True,
        )
    out = Outputs()
    if opts["plot"]:
        out.add_figure(opts["plot"], lambda: _plot(mc, opts), "--plot")
    if opts["csv_path"]:
        dist = mc.distribution()
        rows = np.column_stack(list(dist.values()))
        ok = np.isfinite(np.column_stack([v for k, v in dist.items() if k != "gap"])).all(axis=1)
        notes = [
            "meshing clearance (Wu & Chi) per female normal rack point (datum): x, y [mm], clearance along its normal [mm],",
            "male angle [deg, rotation to go until the nearest male tip's middle reaches O1O2, within +-180/z1] and z [mm] of",
            "the contact (0: first inside both bores), contact point (fixed frame), female and male profile points there [mm,",
            "own frames], in_contact 1 in both bores and length; zone 1 contact, 2 never touches (root below a sharp tip),",
            "3 a sharp female corner's path, 4 not resolved, 0 outside; gap [mm] of 2, 3; flank 1 driving, 2 sealing, 3/4 lands",
        ]
        out.add(opts["csv_path"], lambda p: write_points(p, rows[ok], notes, header=",".join(dist)), "--csv")
    result["files"] = [str(p) for p in out.write()]
    if opts["as_json"]:
        emit_json(result)
    else:
        print_table(f"meshing clearance {result['male_teeth']}/{result['female_teeth']}", result)
        print_defaults(result["defaults"])
        for p in result["files"]:
            click.echo(f"wrote {p}")


def _read_rotors(opts: dict[str, Any]) -> tuple[Any, Any]:
    """Read both rotors' points as seen from the suction end (``--seen-from``), refusing a missing file first."""
    for key in ("male_points", "female_points"):  # a missing file before what else the pair needs (as rotor)
        if opts.get(key) is not None:
            try:
                check_regular_file(opts[key], f"--{key.replace('_', '-')}", "points file or DXF drawing")
            except DesignError as exc:
                raise InputError(exc.sentence()) from None
    for key in ("male_points", "female_points", "male_teeth", "female_teeth", "center_distance"):
        if opts.get(key) is None:
            raise InputError(f"--{key.replace('_', '-')} is required.")
    if opts["smoothing"] is not None and not (np.isfinite(opts["smoothing"]) and opts["smoothing"] >= 0):
        raise InputError(f"--smoothing must be at least 0 mm^2 (got {opts['smoothing']}).")
    face = end_face(opts.get("seen_from"))  # a section seen from the discharge end: mirrored before anything else
    try:
        male = read_profile(opts["male_points"], "--male-points", opts.get("male_layer") or opts["layer"])
        female = read_profile(opts["female_points"], "--female-points", opts.get("female_layer") or opts["layer"])
    except DesignError as exc:
        raise InputError(exc.sentence()) from None
    return seen_from_suction(male, face), seen_from_suction(female, face)


def _evaluate(opts: dict[str, Any]) -> MeshingClearance:
    male, female = _read_rotors(opts)
    female = own_frame(female, Side.FEMALE, opts["center_distance"], "--female-points")  # drawn at (a, 0), as export does
    rm, rf = np.hypot(*profile_points(male).T), np.hypot(*profile_points(female).T)
    # a note before the work when the points would take over a minute (no option makes it faster: fewer points would)
    say_long_run(long_run_note(clearance_seconds(len(rm) + len(rf)), None), opts["quiet"])
    a = opts["center_distance"]
    for option, radii in (("--male-points", rm), ("--female-points", rf)):
        if np.isfinite(a) and a > 0 and not radii.max() < a:  # e.g. a drawing in other units
            raise InputError(
                f"{option} must be a lobe within the --center-distance of {a:g} mm, but its largest radius is "
                f"{radii.max():.6g} mm (a drawing in other units?)."
            )
    z1, z2 = opts["male_teeth"], opts["female_teeth"]
    try:  # the lobe count against the points (one lobe of a 5-lobe male read with 4 lobes: -4865 µm)
        for option, z, points in (("--male-teeth", z1, male), ("--female-teeth", z2, female)):
            refuse_pitch_off_profile(profile_points(points), z, a * z / (z1 + z2), option)
    except DesignError as exc:
        raise InputError(exc.sentence()) from None
    names = {
        "male points": "--male-points",
        "female points": "--female-points",
        "male_tip_radius": "--male-points (its largest radius)",
        "male_root_radius": "--male-points (its smallest radius)",
        "female_tip_radius": "--female-points (its largest radius)",
        "female_root_radius": "--female-points (its smallest radius)",
        "suction_temperature": "--suction-temperature",
        "discharge_temperature": "--discharge-temperature",
        "reference_temperature": "--reference-temperature",
        "rotor_expansion": "--rotor-expansion",
        "housing_expansion": "--housing-expansion",
    }
    try:
        pair = RotorPair(
            opts["male_teeth"],
            opts["female_teeth"],
            opts["center_distance"],
            float(rm.max()),
            float(rm.min()),
            float(rf.max()),
            float(rf.min()),
            opts["lead"],
            opts["length"],
            strict=False,
        )
        # a drawing read as its points (a polyline through them) is judged by their scatter and spacing, as a CSV is
        male = as_given(male, pair.male_teeth, drawn_as_points=False)
        female = as_given(female, pair.female_teeth, drawn_as_points=False)
        thermal = _thermal(opts)
        smoothing = close_smoothing if opts["smoothing"] is None else opts["smoothing"]  # the closer fit (fit.py)
        if thermal is not None:
            pair, male, female = thermal.apply(pair, male, female)
        mc = MeshingClearance(
            pair,
            lobe_pieces(pair, male, "male", smoothing, label="--male-points", roundings=True),
            lobe_pieces(pair, female, "female", smoothing, label="--female-points", roundings=True),
            contact=opts["contact"],
            **pair_quality(male, female, (pair.male_teeth, pair.female_teeth)),
        )
        mc.summary()  # evaluate here (the clearance and its band) so that its errors are reported as bad input
    except DesignError as exc:
        bare = " " not in exc.param and not exc.param.startswith("--")  # an option's name, not already "--male-points"
        label = names.get(exc.param, f"--{exc.param.replace('_', '-')}" if bare else exc.param)
        raise InputError(exc.sentence(label)) from None
    return mc


def _thermal(opts: dict[str, Any]) -> ThermalState | None:
    given = [opts.get(k) is not None for k in ("suction_temperature", "discharge_temperature")]
    if not any(given):
        if opts.get("housing_temperature") is not None:
            raise InputError("--housing-temperature needs --suction-temperature and --discharge-temperature.")
        return None
    if not all(given):
        raise InputError("give both --suction-temperature and --discharge-temperature for the hot pair.")
    given = {k: opts[k] for k in ("reference_temperature", "rotor_expansion", "housing_expansion") if opts.get(k) is not None}
    return ThermalState(
        opts["suction_temperature"], opts["discharge_temperature"], housing_temperature=opts["housing_temperature"], **given
    )


def _thermal_defaults(opts: dict[str, Any], thermal: ThermalState | None) -> dict[str, str]:
    """Return the hot pair's inputs taken by default, "value (default: how it was chosen)" (none for a cold pair)."""
    from rotorcad.cli.defaults import taken

    if thermal is None:
        return {}
    how = {
        "--housing-temperature": (
            f"{thermal.housing_temperature_used:g} degC",
            "the rotors' temperature, the mean of suction and discharge (Miao et al., sec. 1.2): "
            "a cooler housing closes the clearance",
        ),
        "--reference-temperature": (f"{thermal.reference_temperature:g} degC", "the points' temperature, ISO 1's 20 degC"),
        "--rotor-expansion": (f"{thermal.rotor_expansion:g} 1/K", "steel"),
        "--housing-expansion": (f"{thermal.housing_expansion:g} 1/K", "grey cast iron"),
    }
    return {key: taken(*text) for key, text in how.items() if opts.get(key[2:].replace("-", "_")) is None}


def _plot(mc: MeshingClearance, opts: dict[str, Any]):
    """Draw the clearance pictures (:func:`rotorcad.clearance_plotting.plot_clearance`).

    Titled with the state (cold or hot, temperatures, contact flank).
    """
    from rotorcad.clearance_plotting import clearance_state, plot_clearance

    given = opts.get("reference_temperature")
    return plot_clearance(mc, clearance_state(mc, _thermal(opts), REFERENCE_TEMPERATURE if given is None else given))

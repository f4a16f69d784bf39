"""``rotorcad gear``: one involute gear, optionally with its mate (CONTRACT.md)."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import click
import numpy as np

from exports.csv_points import write_points
from exports.dxf import Drawing, write_dxf
from rotorcad.cli.common import (
    InputError,
    Outputs,
    emit_json,
    load_gear_design,
    output_folder,
    print_pair_table,
    print_table,
    reraise,
)
from rotorcad.cli.progress import Steps
from rotorcad.errors import DesignError
from rotorcad.gear import DEG, GearPair, InvoluteGear, mate_shift
from rotorcad.plotting import line_of_action, mate_in_mesh, plot_gears
from rotorcad.rotor_pair import LENGTH_RANGE, MAX_LENGTH

GEAR_OPTION = {
    "teeth": "--teeth",
    "module": "--module",
    "pressure_angle": "--pressure-angle",
    "helix_angle": "--helix-angle",
    "shift": "--shift",
    "addendum": "--addendum",
    "dedendum": "--dedendum",
    "tip_radius_factor": "--tip-radius",
    "tolerance": "--tolerance",
    "center_distance": "--center-distance",
    "radius": "radius",
}
MATE_OPTION = {
    "teeth": "--mate-teeth",
    "shift": "--mate-shift",
    "center_distance": "--center-distance",
    "shifts": "--shift and --mate-shift",
    "mesh": "--teeth, --mate-teeth, --shift, --mate-shift, --addendum and --pressure-angle",
}
# design-file keys ([gear], without _deg) by the parameter names of the gear's errors, where they differ
DESIGN_PARAM = {"tip_radius": "tip_radius_factor"}
FROM_DESIGN = "_named_in_design"
DEFAULTS = {"pressure_angle": 20.0, "helix_angle": 0.0, "shift": 0.0, "addendum": 1.0, "dedendum": 1.25, "tip_radius": 0.38}


GEAR_DECORATORS = [
    click.option("--teeth", type=int, help="Number of teeth z (at least 3)."),
    click.option("--module", type=float, help="Normal module m [mm], > 0."),
    click.option(
        "--pressure-angle", type=float, help="Normal pressure angle of the basic rack [deg], 1 <= alpha < 45. Default 20."
    ),
    click.option("--helix-angle", type=float, help="Helix angle beta at the pitch cylinder [deg], |beta| < 60. Default 0."),
    click.option("--shift", type=float, help="Profile shift coefficient x [modules]. Default 0."),
    click.option("--addendum", type=float, help="Addendum factor h_aP* of the basic rack. Default 1.0."),
    click.option("--dedendum", type=float, help="Dedendum factor h_fP* (tool addendum). Default 1.25."),
    click.option("--tip-radius", type=float, help="Tool tip radius factor rho_a0* (root fillet of the rack). Default 0.38."),
    click.option("--mate-teeth", type=int, help="Teeth of the mating gear z2 (at least 3)."),
    click.option(
        "--mate-shift", type=float, help="Profile shift x2 of the mate [modules]. Default: 0, or from --center-distance."
    ),
    click.option(
        "--center-distance", type=float, help="Working centre distance a_w [mm]. Default: zero backlash for the shifts."
    ),
]


def gear_options(fn):
    """Add the options of ``rotorcad gear`` that describe the gear (and mate) to another command.

    A decorator: ``fn`` comes back with the options applied.
    """
    for deco in reversed(GEAR_DECORATORS):
        fn = deco(fn)
    return fn


@click.command()
@click.argument("design", required=False, type=click.Path(path_type=Path, dir_okay=False))
@gear_options
@click.option("--tolerance", type=float, default=1e-4, show_default=True, help="Chord tolerance of the outline [mm].")
@click.option("--json", "as_json", is_flag=True, help="Print one JSON object on stdout.")
@click.option("--dxf", type=click.Path(path_type=Path, dir_okay=False), help="Write a DXF of the gear (and mate in mesh) [mm].")
@click.option(
    "--csv",
    type=click.Path(path_type=Path, dir_okay=False),
    help="Write the gear outline as x,y points; the mate goes to NAME_mate.csv.",
)
@click.option(
    "--plot",
    type=click.Path(path_type=Path, dir_okay=False),
    help="Write a PNG of the gear pair with pitch and base circles and the line of action.",
)
@click.option(
    "--out", type=click.Path(path_type=Path, file_okay=False), help="Folder for gear.dxf, gear.csv, mate.csv and gear.png."
)
@click.option("--quiet", is_flag=True, help="No progress output.")
def gear(design: Path | None, **opts: Any) -> None:
    """One involute gear cut by the ISO 53 basic rack, optionally with its mate.

    DESIGN is an optional TOML design file with a [gear] table (teeth, module,
    pressure_angle_deg, helix_angle_deg, shift, addendum, dedendum, tip_radius) and an
    optional [mate] table (teeth, shift, center_distance); options given on the command
    line override it.
    """
    params = merge_gear_params(design, opts)
    g, pair = build_gear(params, opts["tolerance"])
    result: dict[str, Any] = pair.summary() if pair is not None else g.summary()

    outputs = Outputs()
    out = output_folder(opts["out"])
    dxf_paths = [p for p in (opts["dxf"], out and out / "gear.dxf") if p]
    csv_paths = [p for p in (opts["csv"], out and out / "gear.csv") if p]
    png_paths = [p for p in (opts["plot"], out and out / "gear.png") if p]
    for p in dxf_paths:
        outputs.add(p, lambda path: write_dxf(path, _drawing(g, pair)), "--dxf")
    for p in csv_paths:
        outputs.add(p, lambda path: write_points(path, g.outline().points, _comments(g, "gear")), "--csv")
        if pair is not None:
            mate_path = p.with_name("mate.csv") if out and p == out / "gear.csv" else p.with_name(p.stem + "_mate.csv")
            outputs.add(
                mate_path, lambda path: write_points(path, pair.mate.outline().points, _comments(pair.mate, "mate")), "--csv"
            )
    for p in png_paths:
        outputs.add_figure(p, lambda: plot_gears(g, pair), "--plot")
    with Steps("gear: writing files", None, opts["quiet"] or not (dxf_paths or csv_paths or png_paths)):
        written = outputs.write()  # 1000 teeth at the finest tolerance: some 20 s
    result["files"] = [str(p) for p in written]

    if opts["as_json"]:
        emit_json(result)
    else:
        title = f"gear z={g.teeth}, m={g.module:g} mm" + (f" with mate z={pair.mate.teeth}" if pair else "")
        if pair is not None and isinstance(result.get("mate"), dict):
            print_pair_table(title, result, result["mate"])
        else:
            print_table(title, result)
        for p in written:
            click.echo(f"wrote {p}")


def merge_gear_params(design: Path | None, opts: dict[str, Any], data: dict[str, Any] | None = None) -> dict[str, Any]:
    """Merge a gear design's values with the options given: options override the file, defaults last.

    Parameters
    ----------
    design : Path or None
        The design file, if any.
    opts : dict
        The command's options (None for an option not given); angles in degrees.
    data : dict, optional
        The design file's mapping if it was read already (the file is read once).

    Returns
    -------
    dict
        Gear (and mate) parameters by name, with the design keys still in force recorded so that
        errors name them.

    Raises
    ------
    InputError
        A bad design file, or no teeth or module from either source.
    """
    params: dict[str, Any] = {}
    if design is not None:
        try:
            d = load_gear_design(design, data)
        except DesignError as exc:
            raise InputError(exc.sentence()) from None
        gd, md = d["gear"], d["mate"]
        params.update({k.removesuffix("_deg"): v for k, v in gd.items()})
        # what the design file gave, by the names the gear's errors use, to name its key in them
        named = {DESIGN_PARAM.get(k.removesuffix("_deg"), k.removesuffix("_deg")): f"[gear] {k}" for k in gd}
        if md:
            params["mate_teeth"] = md.get("teeth")
            params["mate_shift"] = md.get("shift")
            params["center_distance"] = md.get("center_distance")
            named.update({f"mate {k}": f"[mate] {k}" for k in md})
        params[FROM_DESIGN] = named
    for key in (
        "teeth",
        "module",
        "pressure_angle",
        "helix_angle",
        "shift",
        "addendum",
        "dedendum",
        "tip_radius",
        "mate_teeth",
        "mate_shift",
        "center_distance",
    ):
        if opts.get(key) is not None:
            params[key] = opts[key]
            params.get(FROM_DESIGN, {}).pop(DESIGN_PARAM.get(key, key), None)  # the option overrides the file
            params.get(FROM_DESIGN, {}).pop(f"mate {key.removeprefix('mate_')}", None)
    for key, value in DEFAULTS.items():
        params.setdefault(key, value)
    for key in ("teeth", "module"):
        if params.get(key) is None:
            raise InputError(f"--{key} is required (or a design file with [gear] {key}).")
    return params


def build_gear(p: dict[str, Any], tolerance: float) -> tuple[InvoluteGear, GearPair | None]:
    """Build the gear, and its mate when one is described.

    Parameters
    ----------
    p : dict
        Parameters from :func:`merge_gear_params` (angles in degrees, lengths in mm).
    tolerance : float, mm
        Chord tolerance of the outlines.

    Returns
    -------
    gear : InvoluteGear
        The gear.
    pair : GearPair or None
        The gear with its mate (the mate's shift given, zero, or for zero backlash at the centre
        distance, ISO 21771), None without a mate.

    Raises
    ------
    InputError
        A gear or mate that cannot be made, a centre distance or mate shift without mate teeth, or
        flanks that never meet; naming the options (or design keys) given.
    """
    common = {
        "module": p["module"],
        "pressure_angle": p["pressure_angle"] * DEG,
        "helix_angle": p["helix_angle"] * DEG,
        "addendum": p["addendum"],
        "dedendum": p["dedendum"],
        "tip_radius_factor": p["tip_radius"],
        "tolerance": tolerance,
    }
    named = p.get(FROM_DESIGN, {})
    try:
        g = InvoluteGear(teeth=p["teeth"], shift=p["shift"], **common)
    except DesignError as exc:
        raise reraise(exc, {**GEAR_OPTION, **{k: v for k, v in named.items() if not k.startswith("mate ")}}) from None
    z2, a = p.get("mate_teeth"), p.get("center_distance")
    if z2 is None:
        if a is not None or p.get("mate_shift") is not None:
            raise InputError("--mate-teeth must be given with --center-distance or --mate-shift.")
        return g, None
    try:
        if not isinstance(z2, int) or z2 < 3:
            raise DesignError("teeth", "a whole number of at least 3", z2)
        if a is not None and not (np.isfinite(a) and 0 < a <= MAX_LENGTH):  # before the mate's shift is solved from it
            raise DesignError("center_distance", LENGTH_RANGE, a)
        x2 = p.get("mate_shift")
        if x2 is None:
            x2 = 0.0 if a is None else mate_shift(g, z2, a)
        mate = InvoluteGear(teeth=z2, shift=x2, **common)
        pair = GearPair(g, mate, a)
    except DesignError as exc:
        mate_named = {k.removeprefix("mate "): v for k, v in named.items() if k.startswith("mate ")}
        raise reraise(exc, {**MATE_OPTION, **mate_named}) from None
    given = set(named.values())  # the design's keys still in force are named as the user wrote them
    names = [
        key if key in given else option
        for option, key in (
            ("--teeth", "[gear] teeth"),
            ("--mate-teeth", "[mate] teeth"),
            ("--shift", "[gear] shift"),
            ("--mate-shift", "[mate] shift"),
            ("--addendum", "[gear] addendum"),
            ("--pressure-angle", "[gear] pressure_angle_deg"),
        )
    ]
    if a is not None:  # a centre distance given sets the mesh too
        names.insert(2, "[mate] center_distance" if "[mate] center_distance" in given else "--center-distance")
    check_contact(pair.contact_ratio, ", ".join(names[:-1]) + " and " + names[-1])
    return g, pair


def check_contact(eps: float, label: str) -> None:
    """Refuse a pair whose flanks never meet (contact ratio 0 or undefined) instead of reporting it.

    Parameters
    ----------
    eps : float
        The pair's transverse contact ratio.
    label : str
        The options that set it, for the sentence.
    """
    if not (np.isfinite(eps) and eps > 0.0):
        raise InputError(
            f"{label} must be chosen so that the flanks meet (a contact ratio above 0; got {eps:g}): the tips do not reach "
            "the usable involute of the mate; raise the addendum, the shifts or the pressure angle."
        )


def _comments(g: InvoluteGear, body: str) -> list[str]:
    return [
        f"rotorcad {body}: z={g.teeth} m={g.module:g} mm alpha={np.degrees(g.pressure_angle):g} deg x={g.shift:g}",
        "whole outline, counter-clockwise, gear centre at the origin, tooth 0 on the +x axis",
    ]


def _drawing(g: InvoluteGear, pair: GearPair | None) -> Drawing:
    d = Drawing(mark_size=g.module)
    d.outlines.append(("GEAR", g.outline().points))
    d.circles += [("PITCH", (0.0, 0.0), g.pitch_radius), ("BASE", (0.0, 0.0), g.base_radius)]
    d.centers.append((0.0, 0.0))
    if pair is not None:
        o2 = (pair.working_center_distance, 0.0)
        d.outlines.append(("MATE", mate_in_mesh(pair, pair.mate.outline().points)))
        d.circles += [("PITCH", o2, pair.mate.pitch_radius), ("BASE", o2, pair.mate.base_radius)]
        d.centers.append(o2)
        t1, t2, _ = line_of_action(pair)
        d.lines.append(("LINE_OF_ACTION", tuple(t1), tuple(t2)))
    return d

"""``rotorcad gear``: one involute gear, optionally with its mate (CONTRACT.md)."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import click
import numpy as np

from exports.csv_points import write_points
from exports.dxf import Drawing, write_dxf
from exports.svg import write_svg
from rotorcad.cli.common import (
    InputError,
    Outputs,
    emit_json,
    load_gear_design,
    output_folder,
    print_pair_table,
    print_table,
)
from rotorcad.cli.gear_internal import INTERNAL_FIELDS, internal_options, refuse_internal_options, run_internal_gear
from rotorcad.cli.gear_part import draw_features, part_features
from rotorcad.cli.progress import Steps
from rotorcad.design.gears import GEAR_DEFAULTS, VALUE_FIELDS, GearSpec, gear_spec
from rotorcad.design.gears import build_gear as core_build_gear
from rotorcad.design.gears import build_rack as core_build_rack
from rotorcad.design.gears import check_contact as core_check_contact
from rotorcad.design.gears import shop_values as core_shop_values
from rotorcad.design.labels import GEAR_FIELD_LABELS, GEAR_LABELS, contact_names, gear_name, required
from rotorcad.errors import DesignError, GeometryError, MissingValueError
from rotorcad.gear import GearPair, InvoluteGear
from rotorcad.gears.features import MadeFeatures
from rotorcad.gears.rack import GearRack
from rotorcad.plotting import line_of_action, mate_in_mesh, plot_gears

GEAR_OPTION = {
    param: label.option for param, label in GEAR_LABELS.items() if not param.startswith("mate.") and label.option != label.key
}
"""Library parameter of a gear's errors -> option (:data:`rotorcad.design.labels.GEAR_LABELS`; design keys
without an option, the gear-as-a-part keys, left out)."""
MATE_OPTION = {param.removeprefix("mate."): label.option for param, label in GEAR_LABELS.items() if param.startswith("mate.")}
"""Library parameter of the mate's errors -> option."""
DESIGN_PARAM = {"tip_radius": "tip_radius_factor"}
"""Design-file keys ([gear], without _deg) by the parameter names of the gear's errors, where they differ."""
FROM_DESIGN = "_named_in_design"
SPEC = "_spec"
DEFAULTS = GEAR_DEFAULTS
OPTION_FIELDS = (
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
    "thickness_allowance_upper",
    "thickness_allowance_lower",
    "span_teeth",
    "pin_diameter",
    "mate_thickness_allowance_upper",
    "mate_thickness_allowance_lower",
    "rack_length",
    "rack_height",
    *INTERNAL_FIELDS,
)
"""The fields of :class:`rotorcad.design.gears.GearSpec` that the options of :func:`gear_options` (and
:func:`rotorcad.cli.gear_internal.internal_options`) give."""


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


SHOP_DECORATORS = [
    click.option(
        "--thickness-allowance-upper",
        type=float,
        help="Upper tooth-thickness allowance A_sne [mm], normal section, DIN 3967 (<= 0). Default 0.",
    ),
    click.option(
        "--thickness-allowance-lower",
        type=float,
        help="Lower tooth-thickness allowance A_sni [mm] (<= the upper one). Default 0. Files get the middle of the field.",
    ),
    click.option("--span-teeth", type=int, help="Teeth k of the span measurement W_k. Default: the standard rule."),
    click.option(
        "--pin-diameter",
        type=float,
        help="Pin (ball, helical) diameter D_M of the dimension over pins [mm]. Default: the standard rule.",
    ),
    click.option("--mate-thickness-allowance-upper", type=float, help="The mate's upper allowance A_sne [mm]. Default 0."),
    click.option("--mate-thickness-allowance-lower", type=float, help="The mate's lower allowance A_sni [mm]. Default 0."),
    click.option(
        "--rack",
        "rack_length",
        type=float,
        help="Also a gear rack of this length [mm] with the gear's basic rack (rack.csv, rack.dxf; JSON key rack).",
    ),
    click.option(
        "--rack-height", type=float, help="The rack's height from its back to the datum line [mm]. Default h_fP* m + 2 m."
    ),
]
"""The options of ``rotorcad gear`` alone: the tooth-thickness allowances and their measurements."""


def gear_options(fn):
    """Add the options of ``rotorcad gear`` that describe the gear (and mate) to another command.

    A decorator: ``fn`` comes back with the options applied.
    """
    for deco in reversed(GEAR_DECORATORS):
        fn = deco(fn)
    return fn


def shop_options(fn):
    """Add :data:`SHOP_DECORATORS` to a command (a decorator)."""
    for deco in reversed(SHOP_DECORATORS):
        fn = deco(fn)
    return fn


@click.command()
@click.argument("design", required=False, type=click.Path(path_type=Path, dir_okay=False))
@gear_options
@shop_options
@internal_options
@click.option("--tolerance", type=float, default=1e-4, show_default=True, help="Chord tolerance of the outline [mm].")
@click.option("--json", "as_json", is_flag=True, help="Print one JSON object on stdout.")
@click.option("--dxf", type=click.Path(path_type=Path, dir_okay=False), help="Write a DXF of the gear (and mate in mesh) [mm].")
@click.option(
    "--svg",
    type=click.Path(path_type=Path, dir_okay=False),
    help="Write an SVG of the drawing of --dxf [mm, y up]; the rack goes to NAME_rack.svg.",
)
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
    line override it. With a [shaper] table (or --internal) the gear is an internal gear cut by
    that shaper cutter and the mate is the pinion inside it.
    """
    params = merge_gear_params(design, opts)
    if params["internal"]:
        run_internal_gear(params[SPEC], opts)
        return
    refuse_internal_options(opts)
    g, pair = build_gear(params, opts["tolerance"])
    result: dict[str, Any] = pair.summary() if pair is not None else g.summary()
    if pair is not None:
        _warn_lost_contact(pair)
    shop, g, pair = shop_gears(params, g, pair)
    if pair is not None:
        result["mate"].update(shop.pop("mate"))
    result.update(shop)
    part = part_features(params, g)  # tip corners, bore, keyway, hub, herringbone: the [gear] keys
    if part is not None:
        result["features"] = part.summary()
    rack = make_rack(params, opts["tolerance"])
    if rack is not None:
        result["rack"] = rack.summary()

    outputs = Outputs()
    out = output_folder(opts["out"])
    dxf_paths = [p for p in (opts["dxf"], out and out / "gear.dxf") if p]
    csv_paths = [p for p in (opts["csv"], out and out / "gear.csv") if p]
    png_paths = [p for p in (opts["plot"], out and out / "gear.png") if p]
    for p in dxf_paths:
        outputs.add(p, lambda path: write_dxf(path, _drawing(g, pair, part)), "--dxf")
    if opts["svg"]:
        outputs.add(opts["svg"], lambda path: write_svg(path, _drawing(g, pair, part)), "--svg")
        if rack is not None:
            rack_svg = opts["svg"].with_name(opts["svg"].stem + "_rack.svg")
            outputs.add(rack_svg, lambda path: write_svg(path, _rack_drawing(rack)), "--svg")
    for p in csv_paths:
        outline = (part or g).outline().points
        outputs.add(p, lambda path, o=outline: write_points(path, o, _comments(g, "gear")), "--csv")
        if pair is not None:
            mate_path = p.with_name("mate.csv") if out and p == out / "gear.csv" else p.with_name(p.stem + "_mate.csv")
            outputs.add(
                mate_path, lambda path: write_points(path, pair.mate.outline().points, _comments(pair.mate, "mate")), "--csv"
            )
    if rack is not None:
        comments = [f"rotorcad rack: L={rack.length:g} mm m={rack.module:g} mm", "x along the rack, datum line y = 0"]
        for p in dxf_paths:
            rack_path = p.with_name("rack.dxf") if out and p == out / "gear.dxf" else p.with_name(p.stem + "_rack.dxf")
            outputs.add(rack_path, lambda path: write_dxf(path, _rack_drawing(rack)), "--dxf")
        for p in csv_paths:
            rack_path = p.with_name("rack.csv") if out and p == out / "gear.csv" else p.with_name(p.stem + "_rack.csv")
            outputs.add(rack_path, lambda path: write_points(path, rack.outline(), comments), "--csv")
    for p in png_paths:
        outputs.add_figure(p, lambda: plot_gears(g, pair), "--plot")
    with Steps("gear: writing files", None, opts["quiet"] or not (dxf_paths or csv_paths or png_paths or opts["svg"])):
        written = outputs.write()  # 1000 teeth at the finest tolerance: some 20 s
    result["files"] = [str(p) for p in written]

    if opts["as_json"]:
        emit_json(result)
    else:
        title = f"gear z={g.teeth}, m={g.module:g} mm" + (f" with mate z={pair.mate.teeth}" if pair else "")
        shown = _flat(result)
        if pair is not None and isinstance(result.get("mate"), dict):
            print_pair_table(title, shown, _flat(result["mate"]))
        else:
            print_table(title, shown)
        for p in written:
            click.echo(f"wrote {p}")


def merge_gear_params(design: Path | None, opts: dict[str, Any], data: dict[str, Any] | None = None) -> dict[str, Any]:
    """Merge a gear design's values with the options given: options override the file, defaults last.

    The merging is the core's (:func:`rotorcad.design.gears.gear_spec`); this reads the file and
    names the option or key of a refusal.

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
        The values of the :class:`~rotorcad.design.gears.GearSpec` by field (None: not given), the
        spec under ``SPEC`` and, for a design, the keys still in force by the gear's parameter names
        under ``FROM_DESIGN`` (``{"tip_radius_factor": "[gear] tip_radius", "mate teeth": ...}``).

    Raises
    ------
    InputError
        A bad design file, or no teeth or module from either source.
    """
    try:
        checked = None if design is None else load_gear_design(design, data)
    except DesignError as exc:
        raise InputError(exc.sentence()) from None
    try:
        spec = gear_spec(checked, {k: opts.get(k) for k in OPTION_FIELDS})
    except MissingValueError as exc:
        raise InputError(required(GEAR_FIELD_LABELS[exc.param])) from None
    params: dict[str, Any] = {f: getattr(spec, f) for f in VALUE_FIELDS}
    params[SPEC] = spec
    if design is not None:
        by_param = {label.field: p.replace(".", " ") for p, label in GEAR_LABELS.items() if label.key}
        params[FROM_DESIGN] = {by_param[f]: GEAR_FIELD_LABELS[f].key for f in spec.from_design}
    return params


def build_gear(p: dict[str, Any], tolerance: float) -> tuple[InvoluteGear, GearPair | None]:
    """Build the gear, and its mate when one is described (:func:`rotorcad.design.gears.build_gear`).

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
        The gear with its mate, None without a mate.

    Raises
    ------
    InputError
        A gear or mate that cannot be made, a centre distance or mate shift without mate teeth, or
        flanks that never meet; naming the options (or design keys) given
        (:data:`rotorcad.design.labels.GEAR_LABELS`).
    """
    from_design = p[SPEC].from_design if SPEC in p else frozenset()
    spec = GearSpec(**{f: p[f] for f in VALUE_FIELDS if p.get(f) is not None}, from_design=from_design)
    if spec.internal:
        what = "[shaper]" if "cutter_teeth" in spec.from_design else "--internal"
        raise InputError(f"{what} must not be given here: an internal gear is made by rotorcad gear, cut, export and report.")
    try:
        built = core_build_gear(spec, tolerance)
    except MissingValueError as exc:
        if exc.param != "mate.teeth":
            raise
        raise InputError("--mate-teeth must be given with --center-distance or --mate-shift.") from None
    except DesignError as exc:
        if isinstance(exc, GeometryError) and exc.param == "contact_ratio":  # named by the values that set it
            label = contact_names(spec.from_design, spec.center_distance is not None)
        else:
            label = gear_name(exc.param, spec.from_design)
        raise InputError(exc.sentence(label)) from None
    from rotorcad.cli.plausible import say_warnings
    from rotorcad.design.plausibility import module_warnings

    say_warnings(module_warnings(spec.module, gear_name("module", spec.from_design)))  # an inch design, a module in µm
    return built


def shop_gears(
    p: dict[str, Any], gear: InvoluteGear, pair: GearPair | None
) -> tuple[dict[str, Any], InvoluteGear, GearPair | None]:
    """Return the allowances' measurements and backlash, and the gears as made (:func:`rotorcad.design.gears.shop_values`).

    Parameters
    ----------
    p : dict
        Parameters from :func:`merge_gear_params`.
    gear : InvoluteGear
        The nominal gear.
    pair : GearPair or None
        The nominal pair.

    Returns
    -------
    values : dict
        The CONTRACT.md keys of the measurements (the mate's under ``"mate"``) and the backlash.
    made : InvoluteGear
        The gear cut at the middle of its tolerance field (the nominal gear without allowances).
    made_pair : GearPair or None
        The two gears as made at the pair's centre distance.

    Raises
    ------
    InputError
        A value that cannot be used, naming the option or design key given.
    """
    spec = GearSpec(**{f: p[f] for f in VALUE_FIELDS if p.get(f) is not None}, from_design=p[SPEC].from_design)
    try:
        values, made, made_mate = core_shop_values(spec, gear, pair)
    except DesignError as exc:
        raise InputError(exc.sentence(gear_name(exc.param, spec.from_design))) from None
    if pair is None:
        return values, made, None
    if made is pair.gear and made_mate is pair.mate:
        return values, made, pair
    return values, made, GearPair(made, made_mate, pair.working_center_distance)


def make_rack(p: dict[str, Any], tolerance: float) -> GearRack | None:
    """Build the gear rack the options or the design's ``[rack]`` describe (:func:`rotorcad.design.gears.build_rack`).

    Parameters
    ----------
    p : dict
        Parameters from :func:`merge_gear_params`.
    tolerance : float, mm
        Chord tolerance of the outline.

    Returns
    -------
    GearRack or None
        None without ``--rack`` (or ``[rack] length``).

    Raises
    ------
    InputError
        A rack that cannot be made, naming the option or design key given.
    """
    spec = GearSpec(**{f: p[f] for f in VALUE_FIELDS if p.get(f) is not None}, from_design=p[SPEC].from_design)
    try:
        return core_build_rack(spec, tolerance)
    except MissingValueError:
        raise InputError("--rack must be given with --rack-height.") from None
    except DesignError as exc:
        raise InputError(exc.sentence(gear_name(exc.param, spec.from_design))) from None


FLAT_KEYS = ("thickness_allowance", "span", "over_pins", "backlash_circumferential", "backlash_normal", "rack", "features")
"""Nested result keys shown in the text table as one row per value (``span_nominal``, ``rack_pitch``, ...)."""


def _flat(result: dict[str, Any]) -> dict[str, Any]:
    """Return the result with the values of :data:`FLAT_KEYS` as rows of their own, for the text table."""
    out: dict[str, Any] = {}
    for key, value in result.items():
        if key in FLAT_KEYS and isinstance(value, dict):
            out.update({f"{key}_{sub}": v for sub, v in value.items() if not (key == "rack" and sub == "length")})
        else:
            out[key] = value
    return out


def _rack_drawing(rack: GearRack) -> Drawing:
    d = Drawing(mark_size=rack.module)
    d.outlines.append(("RACK", rack.outline()))
    d.lines.append(("PITCH", (0.0, 0.0), (float(rack.length), 0.0)))
    return d


def check_contact(eps: float, label: str) -> None:
    """Refuse a pair whose flanks never meet (:func:`rotorcad.design.gears.check_contact`) as a CLI error.

    Parameters
    ----------
    eps : float
        The pair's transverse contact ratio.
    label : str
        The options that set it, for the sentence.
    """
    try:
        core_check_contact(eps, label)
    except GeometryError as exc:
        raise InputError(exc.sentence()) from None


def _comments(g: InvoluteGear, body: str) -> list[str]:
    return [
        f"rotorcad {body}: z={g.teeth} m={g.module:g} mm alpha={np.degrees(g.pressure_angle):g} deg x={g.shift:g}",
        "whole outline, counter-clockwise, gear centre at the origin, tooth 0 on the +x axis",
    ]


def _drawing(g: InvoluteGear, pair: GearPair | None, part: MadeFeatures | None = None) -> Drawing:
    d = Drawing(mark_size=g.module)
    d.outlines.append(("GEAR", (part or g).outline().points))
    draw_features(d, part)
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


def _warn_lost_contact(pair: Any) -> None:
    """Say on stderr when a pair's gears lose contact once a pitch or a tip meets the mate's fillet.

    ``contact_ratio`` is the path of contact on the usable involutes (form to tip circle) over the base
    pitch; ISO 21771 eq. 5.4's tip-to-tip path (hi1 - lo2 of :meth:`GearPair.contact_interval`) is given
    beside it, so that the undercut's share is seen (z = 11/11, m = 4: 0.971 against 1.396).
    """
    _, hi1, lo2, _ = pair.contact_interval()
    said = []
    if pair.contact_ratio < 1.0:
        iso = (hi1 - lo2) / pair.gear.base_pitch
        said.append(
            f"the contact ratio is {pair.contact_ratio:.3f}, below 1: the gears lose contact once a pitch "
            f"(ISO 21771's tip-to-tip path gives {iso:.3f}; the undercut flanks below the form circles shorten it)"
        )
    if pair.tip_interference:
        said.append("a tip reaches below the mate's form circle (tip interference: it meets the undercut fillet)")
    if said:
        click.echo(f"rotorcad: warning: {'; '.join(said)}; a profile shift (--shift, --mate-shift) avoids it.", err=True)

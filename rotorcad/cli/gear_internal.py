"""``rotorcad gear --internal``: an internal (ring) gear cut by a shaper cutter, optionally with its pinion (CONTRACT.md).

The options of the internal gear and its cutter (:data:`INTERNAL_DECORATORS`), its build from the
merged spec (:func:`build_internal_gear`, refusals naming the option or ``[table] key`` given), the
JSON and table of ``rotorcad gear`` for it and its files (outline points, drawing, picture).
"""

from __future__ import annotations

from typing import Any

import click
import numpy as np

from exports.csv_points import write_points
from exports.dxf import Drawing, write_dxf
from exports.svg import write_svg
from rotorcad.cli.common import InputError, Outputs, emit_json, output_folder, print_pair_table, print_table
from rotorcad.cli.progress import Steps
from rotorcad.design.gears import GearSpec, build_internal
from rotorcad.design.labels import GEAR_FIELD_LABELS, contact_names, gear_name, required
from rotorcad.errors import DesignError, GeometryError, MissingValueError

INTERNAL_FIELDS = ("internal", "outer_diameter", "cutter_teeth", "cutter_shift", "cutter_tip_radius", "cutter_addendum")
"""The fields of :class:`rotorcad.design.gears.GearSpec` that :data:`INTERNAL_DECORATORS` give."""

INTERNAL_DECORATORS = [
    click.option(
        "--internal",
        is_flag=True,
        default=None,
        help="The gear is an internal (ring) gear cut by a shaper cutter (--cutter-teeth); the mate is the pinion inside it. "
        "A design with a [shaper] table is internal.",
    ),
    click.option("--outer-diameter", type=float, help="Outer diameter of the ring [mm]. Default: root diameter + 6 m."),
    click.option("--cutter-teeth", type=int, help="Teeth z0 of the pinion-type shaper cutter (an internal gear: required)."),
    click.option("--cutter-shift", type=float, help="Profile shift x0 of the shaper cutter [modules], -1 to 1.5. Default 0."),
    click.option("--cutter-tip-radius", type=float, help="Tip rounding rho_a0* of the shaper cutter (radius / m). Default 0.25."),
    click.option(
        "--cutter-addendum", type=float, help="Addendum factor h_a0* of the shaper cutter, 0.5 to 2. Default: --dedendum."
    ),
]
"""The options of an internal gear and its cutter (``rotorcad gear``, ``rotorcad cut``)."""

SHOP_ONLY_EXTERNAL = (
    "thickness_allowance_upper",
    "thickness_allowance_lower",
    "span_teeth",
    "pin_diameter",
    "mate_thickness_allowance_upper",
    "mate_thickness_allowance_lower",
    "rack_length",
    "rack_height",
)
"""Values of an external gear only (allowances, span, pins, the rack): refused with an internal gear."""


def internal_options(fn):
    """Add :data:`INTERNAL_DECORATORS` to a command (a decorator)."""
    for deco in reversed(INTERNAL_DECORATORS):
        fn = deco(fn)
    return fn


def refuse_internal_options(opts: dict[str, Any]) -> None:
    """Refuse the options of an internal gear's cutter and ring given for an external gear.

    Parameters
    ----------
    opts : dict
        The command's options (None: not given).

    Raises
    ------
    InputError
        Naming the first such option.
    """
    for field in INTERNAL_FIELDS[1:]:
        if opts.get(field) is not None:
            option = "--" + field.replace("_", "-")
            raise InputError(f"{option} must be given with --internal (or a design with a [shaper] table).")


def build_internal_gear(spec: GearSpec, tolerance: float) -> tuple[Any, Any]:
    """Build the internal gear and its pinion (:func:`rotorcad.design.gears.build_internal`), refusals as CLI errors.

    Parameters
    ----------
    spec : GearSpec
        The merged spec (``internal``).
    tolerance : float, mm
        Chord tolerance of the outlines.

    Returns
    -------
    ring : InternalGear
    pair : InternalPair or None

    Raises
    ------
    InputError
        One sentence naming the option or design key given and the allowed range.
    """
    for f in SHOP_ONLY_EXTERNAL:
        if getattr(spec, f) not in (None, 0.0):
            label = gear_name(f if not f.startswith("mate_") else "mate." + f.removeprefix("mate_"), spec.from_design)
            raise InputError(
                f"{label} must not be given for an internal gear (allowances, span, pins and the rack are of external gears)."
            )
    try:
        return build_internal(spec, tolerance)
    except MissingValueError as exc:
        if exc.param == "cutter_teeth":
            raise InputError(required(GEAR_FIELD_LABELS["cutter_teeth"]).replace("(or", "for an internal gear (or")) from None
        raise InputError("--mate-teeth must be given with --center-distance or --mate-shift.") from None
    except DesignError as exc:
        if isinstance(exc, GeometryError) and exc.param == "contact_ratio":
            label = contact_names(spec.from_design, spec.center_distance is not None)
        else:
            label = gear_name(exc.param, spec.from_design)
        raise InputError(exc.sentence(label)) from None


def internal_result(ring: Any, pair: Any) -> dict[str, Any]:
    """Return the JSON of ``rotorcad gear`` for an internal gear (and its pinion): CONTRACT.md keys."""
    return _plain(pair.summary() if pair is not None else ring.summary())


def _plain(d: dict[str, Any]) -> dict[str, Any]:
    out: dict[str, Any] = {}
    for k, v in d.items():
        if isinstance(v, dict):
            out[k] = _plain(v)
        elif isinstance(v, (bool, np.bool_)):
            out[k] = bool(v)
        elif isinstance(v, (int, np.integer)) or v is None:
            out[k] = v if v is None else int(v)
        else:
            out[k] = float(v)
    return out


def run_internal_gear(spec: GearSpec, opts: dict[str, Any]) -> None:
    """Run ``rotorcad gear`` for an internal gear: build, print (table or JSON), write the files asked for.

    Parameters
    ----------
    spec : GearSpec
        The merged spec.
    opts : dict
        The command's options (``tolerance``, ``as_json``, ``dxf``, ``svg``, ``csv``, ``plot``, ``out``, ``quiet``).
    """
    ring, pair = build_internal_gear(spec, opts["tolerance"])
    result = internal_result(ring, pair)
    outputs = Outputs()
    out = output_folder(opts["out"])
    dxf_paths = [p for p in (opts["dxf"], out and out / "gear.dxf") if p]
    csv_paths = [p for p in (opts["csv"], out and out / "gear.csv") if p]
    png_paths = [p for p in (opts["plot"], out and out / "gear.png") if p]
    for p in dxf_paths:
        outputs.add(p, lambda path: write_dxf(path, ring_drawing(ring, pair)), "--dxf")
    if opts["svg"]:
        outputs.add(opts["svg"], lambda path: write_svg(path, ring_drawing(ring, pair)), "--svg")
    for p in csv_paths:
        outputs.add(p, lambda path: write_points(path, ring.outline().points, _comments(ring)), "--csv")
        if pair is not None:
            mate_path = p.with_name("mate.csv") if out and p == out / "gear.csv" else p.with_name(p.stem + "_mate.csv")
            notes = [f"rotorcad mate (pinion): z={pair.pinion.teeth} x={pair.pinion.shift:g}", "pinion centre at the origin"]
            outputs.add(mate_path, lambda path, c=notes: write_points(path, pair.pinion.outline().points, c), "--csv")
    for p in png_paths:
        from rotorcad.gears.internal_plotting import plot_internal

        outputs.add_figure(p, lambda: plot_internal(ring, pair), "--plot")
    with Steps("gear: writing files", None, opts["quiet"] or not (dxf_paths or csv_paths or png_paths or opts["svg"])):
        written = outputs.write()
    result["files"] = [str(p) for p in written]
    if opts["as_json"]:
        emit_json(result)
        return
    title = f"internal gear z={ring.teeth}, m={ring.module:g} mm, cutter z0={ring.cutter.teeth}"
    shown = {k: v for k, v in result.items() if k not in ("mate", "cutter")}
    shown.update({f"cutter_{k}": v for k, v in result["cutter"].items()})
    if pair is not None:
        print_pair_table(title + f" with pinion z={pair.pinion.teeth}", shown, result["mate"], ("internal gear", "pinion"))
    else:
        print_table(title, shown)
    for p in written:
        click.echo(f"wrote {p}")


def _comments(ring: Any) -> list[str]:
    return [
        f"rotorcad internal gear: z={ring.teeth} m={ring.module:g} mm x={ring.shift:g}, cutter z0={ring.cutter.teeth}",
        "toothed bore, counter-clockwise, gear centre at the origin, tooth space 0 on the +x axis; "
        f"outer diameter {2.0 * ring.outer_radius:.6g} mm",
    ]


def ring_drawing(ring: Any, pair: Any) -> Drawing:
    """Return the drawing of an internal gear: its bore (GEAR), outer circle (OUTER), and the pinion in mesh (MATE).

    Parameters
    ----------
    ring : InternalGear
    pair : InternalPair or None

    Returns
    -------
    Drawing
        Layers GEAR, OUTER, PITCH, BASE (and MATE, the pinion's pitch and base circles about
        (a_w, 0), LINE_OF_ACTION from T2 to T1), mm.
    """
    d = Drawing(mark_size=ring.module)
    d.outlines.append(("GEAR", ring.outline().points))
    d.circles += [
        ("OUTER", (0.0, 0.0), ring.outer_radius),
        ("PITCH", (0.0, 0.0), ring.pitch_radius),
        ("BASE", (0.0, 0.0), ring.base_radius),
    ]
    d.centers.append((0.0, 0.0))
    if pair is not None:
        a = pair.working_center_distance
        p = pair.pinion
        d.outlines.append(("MATE", p.outline().points + np.array([a, 0.0])))
        d.circles += [("PITCH", (a, 0.0), p.pitch_radius), ("BASE", (a, 0.0), p.base_radius)]
        d.centers.append((a, 0.0))
        t1, t2 = line_of_action(pair)
        d.lines.append(("LINE_OF_ACTION", t2, t1))
    return d


def line_of_action(pair: Any) -> tuple[tuple[float, float], tuple[float, float]]:
    """Return the base tangency points T1 (pinion) and T2 (internal gear) of the line of action, mm.

    Both lie on the same side of the line of centres, in the direction (sin alpha_wt, cos alpha_wt)
    turned so that the line passes through the pitch point C = (r_w2, 0) at the working pressure angle.
    """
    aw = pair.working_pressure_angle
    r = pair.ring
    u = np.array([np.cos(aw), np.sin(aw)])  # from the gear centre to T2
    t2 = r.base_radius * u
    t1 = np.array([pair.working_center_distance, 0.0]) + pair.pinion.base_radius * u
    return (float(t1[0]), float(t1[1])), (float(t2[0]), float(t2[1]))


__all__ = [
    "INTERNAL_FIELDS",
    "build_internal_gear",
    "internal_options",
    "refuse_internal_options",
    "ring_drawing",
    "run_internal_gear",
]

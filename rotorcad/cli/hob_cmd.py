"""``rotorcad hob``: rack and hob tooth derived from a profile, and the hobbability verdict."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import click
import numpy as np
import shapely

from exports.csv_points import write_points
from exports.dxf import Drawing, write_dxf
from hob.rack import DerivedRack, gear_rack, hob_tooth, rack_deviation, rotor_rack
from hob.undercut import gear_undercut
from hob.verdict import FOLD_TOLERANCE, HobLimits, judge, local_scatter, undercut_tolerance
from rotorcad.cli.common import InputError, Outputs, emit_json, end_face, load_toml, print_table
from rotorcad.cli.gear import build_gear, gear_options, merge_gear_params
from rotorcad.cli.hob_worm import add_worm_steps, body_hands, rack_datum, worm_options, worm_summaries, worms_of
from rotorcad.cli.rotor import rotor_input_options, rotors_of
from rotorcad.envelope import rack_frame
from rotorcad.errors import DesignError
from rotorcad.gear import InvoluteGear
from rotorcad.inverse_rack import MEASURED_JOIN_GAP, MEASURED_MIN_TURN
from rotorcad.measured.cusp_paths import with_exact_cusp_paths


@click.command()
@click.argument("design", required=False, type=click.Path(path_type=Path, dir_okay=False))
@gear_options
@rotor_input_options
@click.option("--min-flank-angle", type=float, default=5.0, show_default=True, help="Smallest hob flank angle [deg].")
@click.option("--min-tip-radius-mm", type=float, default=0.1, show_default=True, help="Smallest hob tip radius [mm].")
@click.option("--min-root-radius-mm", type=float, default=0.1, show_default=True, help="Smallest hob root radius [mm].")
@click.option("--min-tip-thickness", type=float, default=0.3, show_default=True, help="Thinnest hob tooth near its tip [mm].")
@click.option(
    "--root-clearance", type=float, default=0.25, show_default=True, help="Hob root clearance over the rack [modules or x h1]."
)
@click.option("--json", "as_json", is_flag=True, help="Print one JSON object on stdout.")
@click.option("--dxf", type=click.Path(path_type=Path, dir_okay=False), help="DXF of the normal rack and the hob tooth [mm].")
@click.option("--csv", type=click.Path(path_type=Path, dir_okay=False), help="Normal rack points (x,y).")
@click.option(
    "--plot",
    type=click.Path(path_type=Path, dir_okay=False),
    help="Picture (PNG, SVG or PDF by the suffix): the racks compared, their deviation magnified along the normal, "
    "and the hob teeth.",
)
@worm_options
@click.option("--quiet", is_flag=True, help="No progress output.")
def hob(design: Path | None, **opts: Any) -> None:
    """Derive the transverse and normal rack of a gear or of both rotors of a pair, and judge them.

    Judge whether a hob can make the profile (with reasons and positions) and give the hob tooth.
    """
    for key, flag in (
        ("min_flank_angle", "--min-flank-angle"),
        ("min_tip_radius_mm", "--min-tip-radius-mm"),
        ("min_root_radius_mm", "--min-root-radius-mm"),
        ("min_tip_thickness", "--min-tip-thickness"),
        ("root_clearance", "--root-clearance"),
    ):
        if not (np.isfinite(opts[key]) and opts[key] >= 0):
            raise InputError(f"{flag} must be a number of at least 0 (got {opts[key]}).")
    limits = HobLimits(opts["min_flank_angle"], opts["min_tip_radius_mm"], opts["min_root_radius_mm"], opts["min_tip_thickness"])
    racks: dict[str, DerivedRack] = {}
    data = _read_design(design)  # the one reading of the design file
    rotors = rotors_of(design, data, opts)
    if rotors is not None:
        try:
            # measured pieces: their fits leave kinks of a fraction of a degree and gaps of a few µm
            # at the lands, which are no corners (the meshing clearance judges them alike); the mate generated
            # from their rack overshoots its tip where the rack's rounding meets its flat (its loops are cut)
            measured = {"min_turn": MEASURED_MIN_TURN, "join_gap": MEASURED_JOIN_GAP, "cut_loops": True}
            measured = measured if _measured(rotors) else {}
            rotors = with_exact_cusp_paths(rotors)  # the mate's tip-corner cycloids of scattered points, for the hob
            racks = {"male": rotor_rack(rotors, "male", **measured), "female": rotor_rack(rotors, "female", **measured)}
            deviation = rack_deviation(rotors, **measured)
        except DesignError as exc:
            raise InputError(exc.sentence()) from None
        scale = rotors.pair.male_addendum
        body: Any = rotors
    else:
        spec = merge_gear_params(design, opts, data)
        g, _ = build_gear(spec, 1e-4)
        notes = _not_hobbed(spec)
        racks = {"gear": gear_rack(g)}
        deviation = _basic_rack_deviation(g, racks["gear"])
        scale = g.module
        body = g
    verdicts, result = judge_racks(
        racks,
        deviation,
        limits,
        getattr(body, "accuracy", 0.0),
        _fitted_sides(body),
        undercut_tolerance(body),
        body if rotors is None else None,
        tangent_accuracy=getattr(body, "tangent_accuracy", 0.0) or 0.0,
        local=local_scatter(body),
    )
    result["smallest_flank_angle_accuracy_deg"] = _angle_accuracy(body, racks, result["normal_pressure_angle_min_deg"])
    result["rack_accuracy"] = _rack_accuracy(body, racks)
    result["notes"] = (notes if rotors is None else _outline_notes(rotors)) + result["notes"]
    if opts.get("male_points") or opts.get("female_points"):  # the end face the section was read as seen from
        result["seen_from"] = str(end_face(opts.get("seen_from")))
    worms = worms_of(racks, body_hands(body), opts, rack_datum(body))
    first = next(iter(racks))
    normal = racks[first].normal()
    clearance = opts["root_clearance"] * scale
    out = Outputs()
    out.add(opts["csv"], lambda p: write_points(p, normal, [f"normal rack derived from the {first}, rack frame"]), "--csv")
    out.add(opts["dxf"], lambda p: write_dxf(p, _drawing(racks, clearance)), "--dxf")
    if opts["plot"]:
        out.add_figure(opts["plot"], lambda: _plot(racks, verdicts, clearance, deviation, body), "--plot")
    steps = add_worm_steps(out, worms, opts["step"])
    result["files"] = [str(p) for p in out.write()]
    if worms:
        result["worms"] = worm_summaries(worms, steps)
    if opts["as_json"]:
        emit_json(result)
    else:
        print_table("hobbability", {k: v for k, v in result.items() if k not in ("reasons", "racks", "worms")})
        for name, figures in result.get("worms", {}).items():
            print_table(f"basic worm of the hob for the {name}", figures)
        for r in result["reasons"] + result["notes"]:
            click.echo(f"  - {r}")


def _not_hobbed(spec: dict[str, Any]) -> list[str]:
    """Say what of a gear design's part features the hob of its basic rack does not make.

    A new user's finding: the rack, and so the hob, of a gear with a tip chamfer was the plain
    gear's, without a word.
    """
    notes = []
    for key, what in (("tip_chamfer", "tip chamfer"), ("tip_rounding", "tip rounding")):
        value = spec.get(key)
        if value:
            notes.append(
                f"the {what} ([gear] {key} = {value:g} mm) is not made by this hob (the basic rack's): "
                "a semi-topping hob or a separate chamfering operation makes it"
            )
    return notes


def judge_racks(
    racks: dict[str, DerivedRack],
    deviation: float,
    limits: HobLimits,
    accuracy: float = 0.0,
    measured: dict[str, bool] | None = None,
    undercut_accuracy: float = 0.0,
    gear: InvoluteGear | None = None,
    tangent_accuracy: float = 0.0,
    local: tuple[float, float] = (0.0, 0.0),
) -> tuple[dict[str, Any], dict[str, Any]]:
    """Judge each rack and collect the keys of ``rotorcad hob --json`` (``files`` aside).

    For this command and ``rotorcad report``.

    Parameters
    ----------
    racks : dict of DerivedRack
        ``male`` and ``female``, or ``gear``.
    deviation : float, mm
        The largest distance between the racks (or from the basic rack).
    limits : HobLimits
        Limits of a producible hob.
    accuracy : float, mm
        Accuracy of a profile given by points (:func:`hob.verdict.judge`; 0 for a design).
    measured : dict of bool, optional
        Per rack, whether that rotor's profile was fitted to its own points (:func:`hob.verdict.judge`);
        default ``accuracy > 0`` for every rack. False for the mate generated from a rotor's points and
        for both rotors of a pair generated from a rack's points: they are envelopes, undercut only
        where they turn back, as a design's.
    undercut_accuracy : float, mm
        How deep the rack must cut into a mate generated from points for an undercut
        (:func:`hob.verdict.undercut_tolerance`); 0 for a design.
    gear : InvoluteGear, optional
        The gear of the rack ``gear``: its undercut (:func:`hob.undercut.gear_undercut`), which a hob
        makes, is stated in ``notes`` and the keys below, not in ``reasons``.
    tangent_accuracy : float, rad
        Of points with scatter, how well their tangents are known (0 for exact points and designs):
        :func:`hob.verdict.judge` tells a touch from a crossing by the generation factor alone then.
    local : (float, float), mm
        Of points with scatter, one point's scatter and the points' spacing (:func:`hob.verdict.local_scatter`):
        how well a mate's undercut depth is known, below which a crossing is undecided.

    Returns
    -------
    verdicts : dict of Verdict
        The verdict on each rack.
    result : dict
        ``hobbable``, ``reasons``, ``rack_deviation`` (mm), ``normal_pressure_angle_min_deg``,
        ``accuracy`` (mm), ``undercut_accuracy`` (mm), ``smallest_flank_angle_accuracy_deg`` (0 here),
        ``notes`` (what was judged within the accuracy), ``undercut`` (bool: a rotor undercut by its
        rack, or the gear's undercut), ``undercut_undecided`` (bool: a mate's turn-back the points
        cannot decide, :func:`hob.verdict.undercut_reasons`), for a gear ``undercut_radius`` (mm) and ``undercut_limit_shift``,
        and per rack its figures (radii and tip thickness in mm, angles in deg).
    """
    fitted = {name: None if measured is None else measured.get(name, False) for name in racks}
    verdicts = {
        name: judge(rack, limits, accuracy, fitted[name], undercut_accuracy, tangent_accuracy, *local)
        for name, rack in racks.items()
    }
    result: dict[str, Any] = {
        "hobbable": all(v.hobbable for v in verdicts.values()),
        "reasons": [f"{name}: {r}" if len(verdicts) > 1 else r for name, v in verdicts.items() for r in v.reasons],
        "rack_deviation": deviation,
        "normal_pressure_angle_min_deg": min(v.normal_pressure_angle_min_deg for v in verdicts.values()),
        "accuracy": float(accuracy),
        "undercut_accuracy": float(max(undercut_accuracy, FOLD_TOLERANCE)) if accuracy > 0 else 0.0,
        "smallest_flank_angle_accuracy_deg": 0.0,  # of a design; `hob` states it for points (_angle_accuracy)
        "rack_accuracy": float(accuracy),  # of a design; `hob` states it for points (_rack_accuracy)
        "notes": [f"{name}: {n}" if len(verdicts) > 1 else n for name, v in verdicts.items() for n in v.notes],
        "racks": {name: _rack_figures(v, racks[name]) for name, v in verdicts.items()},
    }
    result["undercut"] = any(v.undercut for v in verdicts.values())
    result["undercut_undecided"] = any(v.undercut_undecided for v in verdicts.values())
    if gear is not None:  # a hob makes a gear's undercut: a note and its figures, not a reason
        cut = gear_undercut(gear)
        result.update(undercut=cut.undercut, undercut_radius=cut.radius, undercut_limit_shift=cut.limit_shift)
        result["notes"] += [cut.note] if cut.note else []
    return verdicts, result


def _rack_figures(v: Any, rack: DerivedRack) -> dict[str, Any]:
    """Return one rack's figures of ``hob --json`` (radii and tip thickness in mm, angles in deg)."""
    return {
        "hobbable": v.hobbable,
        "normal_pressure_angle_min_deg": v.normal_pressure_angle_min_deg,
        "hob_tip_radius": v.min_tip_radius,
        "hob_root_radius": v.min_root_radius,
        "hob_tip_radius_infinite": bool(np.isinf(v.min_tip_radius)),  # straight: JSON null and this flag
        "hob_root_radius_infinite": bool(np.isinf(v.min_root_radius)),
        "hob_tip_thickness": v.tip_thickness,
        "helix_angle_deg": float(np.degrees(rack.helix_angle)),
        "no_rack_share": rack.lost_fraction,
    }


def _outline_notes(rotors: Any) -> list[str]:
    """Name a design's generated outline that crosses itself or runs past its tip, in ``export``'s words.

    A new user's finding (the rack-involute family at its default roundings): ``rotor`` and ``export``
    named the male's loop at r = 70.9 mm, ``hob`` did not. The hob cuts the outer envelope (the loop and
    the overshoot cut away), so it is a note, not a reason. Of a pair from points (whose mate's turn-backs
    :func:`hob.verdict.undercut_reasons` judges within the points' accuracy) none. The outlines are checked
    at 0.1 um chords, as ``export`` checks them.
    """
    if str(getattr(rotors, "family", "")) in ("male-points", "female-points", "rack-points"):
        return []
    from rotorcad.families.checks import OUTLINE_FAULT_WHY, outline_faults

    said = outline_faults(rotors, 1e-4)
    return [f"{said}: {OUTLINE_FAULT_WHY}; a hob cuts the rotor without the loop (as `rotorcad export` says)."] if said else []


def _angle_accuracy(body: Any, racks: dict[str, DerivedRack], smallest: float) -> float:
    """Return the accuracy (deg) of the smallest flank angle read from a rotor's points; 0 for a design or a gear."""
    from hob.angle_accuracy import smallest_angle_accuracy

    given = [side for side, fitted in _fitted_sides(body).items() if fitted]
    return smallest_angle_accuracy(body, racks, given[0], smallest) if given and "male" in racks else 0.0


def _rack_accuracy(body: Any, racks: dict[str, DerivedRack]) -> float:
    """Return how far the given rotor's rack may lie from its true one (mm, hob.rack_accuracy); ``accuracy`` otherwise."""
    from hob.rack_accuracy import hob_rack_accuracy

    return hob_rack_accuracy(body, racks)


def _fitted_sides(body: Any) -> dict[str, bool]:
    """Tell per rack whether its rotor's profile was fitted to its own points.

    The ``male-points`` or ``female-points`` rotor; none of a design, of a rack's points or of a gear.
    """
    family = str(getattr(body, "family", ""))
    return {"male": family == "male-points", "female": family == "female-points", "gear": False}


def _measured(rotors: Any) -> bool:
    """Whether the pair was derived from measured points of a rotor or of its rack with scatter.

    Family ``male-points``/``female-points``, or ``rack-points`` with a tangent accuracy (scattered points):
    its lands are fitted, and the mates generated from them overshoot their tips as from a rotor's points;
    without the measured-piece options the 4/6 independent rack with 2 um of scatter read a rack deviation
    of 7.7 mm, 0.002 um with them.
    """
    family = str(getattr(rotors, "family", ""))
    scattered_rack = family == "rack-points" and (getattr(rotors, "tangent_accuracy", 0.0) or 0.0) > 0.0
    return family in ("male-points", "female-points") or scattered_rack


def _read_design(design: Path | None) -> dict[str, Any] | None:
    """Read the design file's mapping (None without a file); a file that cannot be read is refused in one sentence."""
    if design is None:
        return None
    try:
        return load_toml(design)
    except DesignError as exc:
        raise InputError(exc.sentence()) from None


def _basic_rack_deviation(g: InvoluteGear, rack: DerivedRack) -> float:
    """Return the largest distance (mm) of the derived rack's cutting points from the gear's basic-rack tool.

    Measured against both flanks of the tool teeth either side of the tooth space.
    """
    half = np.vstack([c.evaluate(np.linspace(c.s0, c.s1, 2000))[0] for c in g.tool.values()])
    half = rack_frame(half, g.pitch_radius)
    pt = np.pi * g.transverse_module
    tooth = np.vstack([half, (half * [-1.0, 1.0] + [pt, 0.0])[::-1]])  # both sides of the tool tooth at x = p/2
    lines = shapely.MultiLineString([tooth, tooth - [pt, 0.0]])
    # the gear's tip circle and tip corners face the tool's root clearance, not its cutting edges
    cutting = np.array([n in ("involute", "fillet", "root arc") for n in rack.names])[rack.piece_index]
    return float(shapely.distance(lines, shapely.points(rack.points[cutting])).max())


def _plot(racks: dict[str, DerivedRack], verdicts: dict[str, Any], clearance: float, deviation: float, body: Any):
    """Draw the racks compared (deviation magnified along the normal) and the hob teeth side by side."""
    from hob.plotting import gear_rack_comparison, plot_hob, rotor_rack_comparison

    if "male" in racks:
        pair = body.pair
        case = f"the {body.family} {pair.male_teeth}/{pair.female_teeth} rotor pair (a = {pair.center_distance:g} mm)"
        comparison = rotor_rack_comparison(body, racks)
    else:
        case = f"the gear z = {body.teeth}, m = {body.module:g} mm, x = {body.shift:g}"
        comparison = gear_rack_comparison(body, racks["gear"])
    return plot_hob(racks, verdicts, comparison, clearance, case, deviation)


def _drawing(racks: dict[str, DerivedRack], clearance: float) -> Drawing:
    """Draw the normal racks and hob teeth side by side, labelled on the layer LABELS.

    Each is in its own rack frame, the next one shifted along the pitch line by its width and a gap.
    """
    d = Drawing()
    offset = 0.0
    for name, rack in racks.items():
        # normal rack; the female's is flipped into the rack frame of CONTRACT.md (y > 0 to the female)
        pts, tooth = hob_tooth(rack, clearance)
        pts, tooth = pts + np.array([offset, 0.0]), tooth + np.array([offset, 0.0])
        d.polylines.append((f"RACK_{name.upper()}", pts))
        d.outlines.append((f"HOB_TOOTH_{name.upper()}", tooth))
        width = float(np.ptp(tooth[:, 0]))
        height = max(0.04 * max(width, float(np.ptp(tooth[:, 1]))), 0.05)
        left, high = float(tooth[:, 0].min()), float(tooth[:, 1].max())
        d.texts.append(("LABELS", (left, high + 1.0 * height), f"normal rack and hob tooth from the {name}", height))
        d.texts.append(("LABELS", (left, high + 2.4 * height), f"shifted {offset:.4f} mm along the pitch line", 0.7 * height))
        offset += width * 1.25
    return d

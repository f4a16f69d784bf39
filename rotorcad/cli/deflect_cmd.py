"""``rotorcad deflect``: deflection of the rotors under gas load (Rinder & Deix; CONTRACT.md)."""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path
from typing import Any

import click
import numpy as np
from matplotlib.figure import Figure

from exports.csv_points import read_points
from rotorcad import plot_style as ps
from rotorcad.cli.common import InputError, Outputs, emit_json, load_rotor_design, print_table
from rotorcad.cli.defaults import print_defaults, taken
from rotorcad.cli.export_cmd import _rotor_options
from rotorcad.cli.progress import Steps
from rotorcad.cli.rotor import _build as build_rotors
from rotorcad.deflection import AIR_EXPONENT, MAX_WRAP_DEG, STEEL, GasDeflection, LoadModel, Shaft
from rotorcad.errors import DesignError
from rotorcad.plot_style import styled
from rotorcad.working_chamber import cycle_angle

SWEEP_ANGLES = 100  # male angles over one male pitch
STEP_DEG = 1.0  # deg: the chamber table's phase step (GasDeflection's default)
# Rinder & Deix sec. 3.5 (text under Figs. 9 and 10): the largest deflections of their 5/6 pair at 12 bar,
# mm: (helical part, with the journals of their Fig. 8); the curves of Figs. 9/10 are not in the text
PAPER_MAX = {"male": (0.0005, 0.0022), "female": (0.002, 0.0075)}


def _shaft(value: Any, key: str) -> tuple[tuple[float, float], ...]:
    """Read a shaft end from the design: [[length, diameter], ...] in mm.

    Returns the pieces as a tuple of (length, diameter) pairs (empty when ``value`` is None); anything
    else is refused with :class:`InputError` naming ``[deflection] key``.
    """
    if value is None:
        return ()
    ok = isinstance(value, list) and all(
        isinstance(p, list) and len(p) == 2 and all(isinstance(x, (int, float)) and not isinstance(x, bool) for x in p)
        for p in value
    )
    if not ok:
        raise InputError(f"[deflection] {key} must be a list of [length, diameter] pairs in mm (got {value!r}).")
    for length, diameter in value:
        if not (np.isfinite(length) and np.isfinite(diameter) and 0 < length <= 1e4 and 0 < diameter <= 1e4):
            raise InputError(f"[deflection] {key} must have lengths and diameters above 0 and up to 10000 mm (got {value!r}).")
    return tuple((float(a), float(b)) for a, b in value)


@click.command()
@click.argument("design", type=click.Path(path_type=Path, dir_okay=False))
@click.option("--angle", type=float, help="Male angle [deg] to evaluate. Default: the worst over one male pitch (swept).")
@click.option(
    "--terms",
    type=int,
    help=(
        "Sine terms of the Ritz-Galerkin series of the helical part (1..400; the rotor on its bearings "
        "with journals is integrated along its length instead). Default: the design's, else 40."
    ),
)
@click.option(
    "--indicator",
    type=click.Path(path_type=Path, dir_okay=False),
    help="Indicator diagram: CSV 'angle_deg,pressure_bar' (chamber angle since it opened at the suction end, absolute bar).",
)
@click.option(
    "--method",
    type=click.Choice([m.value for m in LoadModel]),
    default=LoadModel.CHAMBER.value,
    show_default=True,
    help="Flute load of the reported keys: 'rotorcad' the overpressure on the real chamber's boundary, 'paper' "
    "Rinder & Deix eq. (5), the tip-to-tip chord d_K sin(pi/z) in every section. Both are computed and compared.",
)
@click.option("--json", "as_json", is_flag=True, help="Print one JSON object on stdout.")
@click.option(
    "--plot",
    type=click.Path(path_type=Path, dir_okay=False),
    help="Picture of the deflection lines (Rinder & Deix Fig. 9/10): PNG, SVG or PDF by the name's suffix.",
)
@click.option("--quiet", is_flag=True, help="No progress output.")
def deflect(
    design: Path,
    angle: float | None,
    terms: int | None,
    indicator: Path | None,
    method: str,
    as_json: bool,
    plot: Path | None,
    quiet: bool,
) -> None:
    """Deflection of the male and female under the pressure of the working chambers (Rinder & Deix).

    Section values of the real profiles, the equivalent round bar (eqs. 2-4), the chambers' volume
    curve and pressure ([operating]: suction and discharge pressure, polytropic exponent, volume
    ratio or control edge, or an indicator diagram), the line loads (eqs. 5-6) and the deflection
    lines by Ritz-Galerkin (eqs. 7-9), swept over one male pitch for the worst angle (eq. 10); with
    shaft ends in [deflection] also the whole shafts on their bearings. The flute load is the real
    chamber's (--method rotorcad) or eq. (5)'s chord (--method paper); the other method's largest
    deflections and their ratio are reported beside. Every default taken is printed.
    """
    try:
        settings = load_rotor_design(design)
    except DesignError as exc:
        raise InputError(exc.sentence()) from None
    given = _gather(design, settings, angle, terms, indicator)
    out = Outputs()  # the picture's file checked before the work (a FIFO --plot was refused after 2.5 s of it)
    out.add_figure(
        plot,
        lambda: _plot(
            model,
            solved.lines,
            sweep_angles,
            solved.swept,
            given.shafts,
            f"{Path(design).name}: {rotors.family}",
            solved.other_lines,
            solved.other_swept,
        ),
        "--plot",
    )
    rotors, _, _ = build_rotors(design, _rotor_options(design), settings)  # the design as read above
    _check_indicator_covers(rotors.pair, given)  # before the chamber table (2 s of CPU), not after it
    model = _model(rotors, given, LoadModel(method))
    sweep_angles = np.linspace(0.0, 2 * np.pi / rotors.pair.male_teeth, SWEEP_ANGLES, endpoint=False)
    solved = _solve(model, sweep_angles, given, quiet)
    result = _result(model, solved, given, rotors.pair.male_teeth, sweep_angles)
    result.update(housing_check(model, solved.lines, given.shafts, settings["housing"].get("radial_clearance", 0.0)))
    result["defaults"] = _defaults(given.op, given.de, model, given.exponent, given.terms_label, given.terms)
    result["files"] = [str(x) for x in out.write()]
    if as_json:
        emit_json(result)
    else:
        print_table(
            f"deflection under gas load, {Path(design).name}, flute load '{model.load.value}', "
            f"male angle {np.degrees(solved.at):.2f} deg",
            result,
        )
        print_defaults(result["defaults"])


def body_deflection(model: GasDeflection, lines, rotor: str, shafts: bool) -> float:
    """Return the largest deflection of a rotor's body (its helical part) as it is supported, mm.

    With shaft ends, the line of the whole shaft on its bearings between the body's end faces (the
    journals do not face the bore); without, the helical part simply supported at its end faces.
    Either is the body's displacement from the bearings' axis, which is the housing bore's.
    """
    shaft_z = getattr(lines, f"{rotor}_shaft_z")
    if shafts and len(shaft_z):
        start = model.journal_length(rotor)
        inside = (shaft_z >= start - 1e-9) & (shaft_z <= start + model.pair.length + 1e-9)
        w = getattr(lines, f"{rotor}_shaft")[inside]
    else:
        w = getattr(lines, rotor)
    return float(np.hypot(w[:, 0], w[:, 1]).max())


def housing_check(model: GasDeflection, lines, shafts: bool, clearance: float) -> dict[str, float]:
    """Compare each rotor body's deflection with the design's radial housing clearance (``[housing] radial_clearance``).

    Rinder & Deix (sec. 1) compute the deflection because it can take the rotors "bis zum
    Anlaufen an die Gehäusewand": a body deflected by more than the radial clearance touches its
    bore. No clearance in the design (0): no keys. A ratio of 1 or more is also said as a note on
    stderr after the result.

    Returns
    -------
    dict
        ``housing_radial_clearance`` (mm), ``{rotor}_body_deflection`` (mm, :func:`body_deflection`)
        and ``{rotor}_deflection_to_housing_clearance`` (1) for male and female.
    """
    if not clearance > 0.0:
        return {}
    import warnings

    from rotorcad.errors import InputNote

    out: dict[str, float] = {"housing_radial_clearance": float(clearance)}
    for rotor in ("male", "female"):
        w = body_deflection(model, lines, rotor, shafts)
        out[f"{rotor}_body_deflection"] = w
        out[f"{rotor}_deflection_to_housing_clearance"] = w / clearance
        if w >= clearance:
            warnings.warn(
                f"the {rotor}'s deflection {w * 1e3:.1f} µm reaches the housing's radial clearance {clearance * 1e3:.1f} µm "
                "([housing] radial_clearance): its tips touch the bore under this gas load",
                InputNote,
                stacklevel=2,
            )
    return out


def design_deflection(design: Path, settings: dict[str, Any], rotors) -> dict[str, Any] | None:
    """Return ``deflect --json``'s keys for a design at its ``[operating]`` pressures (None without them).

    For ``report``: the same sweep, worst angle, flute load (``rotorcad``) and housing check as
    ``deflect`` with no options; a design ``deflect`` refuses is refused alike (:class:`InputError`).
    """
    if not {"suction_pressure_bar", "discharge_pressure_bar"} <= set(settings["operating"]):
        return None
    given = _gather(design, settings, None, None, None)
    _check_indicator_covers(rotors.pair, given)
    model = _model(rotors, given, LoadModel.CHAMBER)
    sweep_angles = np.linspace(0.0, 2 * np.pi / rotors.pair.male_teeth, SWEEP_ANGLES, endpoint=False)
    solved = _solve(model, sweep_angles, given, True)
    result = _result(model, solved, given, rotors.pair.male_teeth, sweep_angles)
    result.update(housing_check(model, solved.lines, given.shafts, settings["housing"].get("radial_clearance", 0.0)))
    result["defaults"] = _defaults(given.op, given.de, model, given.exponent, given.terms_label, given.terms)
    return result


@dataclass(frozen=True)
class _Given:
    """The inputs of ``deflect`` after every check: the design's tables and what they set.

    Attributes
    ----------
    op, de : dict
        The design's ``[operating]`` and ``[deflection]`` tables.
    angle : float or None
        ``--angle`` [deg]; None: the worst angle over one male pitch.
    terms : int
        Sine terms of the Ritz-Galerkin series; ``terms_label`` names where they came from.
    curve : (n, 2) array or None
        The indicator diagram: chamber angle [rad], absolute pressure [bar]; ``curve_label`` names it.
    exponent : float
        Polytropic exponent.
    male_shaft, female_shaft : Shaft
        The shaft ends of each rotor.
    """

    op: dict[str, Any]
    de: dict[str, Any]
    angle: float | None
    terms: int
    terms_label: str
    curve: np.ndarray | None
    curve_label: str
    exponent: float
    male_shaft: Shaft
    female_shaft: Shaft

    @property
    def shafts(self) -> bool:
        """Whether any shaft end is given (then the whole shafts on their bearings)."""
        return bool(self.male_shaft.given or self.female_shaft.given)


def _gather(design: Path, settings: dict[str, Any], angle: float | None, terms: int | None, indicator: Path | None) -> _Given:
    """Check the options and the design's ``[operating]`` and ``[deflection]`` tables.

    Every refusal is one sentence naming the option or ``[table] key`` (:class:`InputError`).
    """
    op, de = dict(settings["operating"]), settings["deflection"]
    if indicator is not None:  # the option wins over the design's way of setting the discharge, as every option does
        overridden = [k for k in ("volume_ratio", "discharge_edge_deg", "indicator") if op.pop(k, None) is not None]
        if overridden:
            import warnings

            from rotorcad.errors import InputNote

            said = ", ".join(f"[operating] {k}" for k in overridden)
            warnings.warn(
                f"--indicator replaced the design's {said} (each sets where the discharge opens)", InputNote, stacklevel=2
            )
    for key in ("suction_pressure_bar", "discharge_pressure_bar"):
        if key not in op:
            raise InputError(f"[operating] {key} is needed for the gas load (an absolute pressure in bar).")
    terms_label = "--terms" if terms is not None else "[deflection] terms"
    terms = terms if terms is not None else int(de.get("terms", 40))
    if not 1 <= terms <= 400:
        raise InputError(f"{terms_label} must be a whole number from 1 to 400 (got {terms}).")
    if angle is not None and not (np.isfinite(angle) and abs(angle) <= 3600):
        raise InputError(f"--angle must be a male angle from -3600 to 3600 degrees (got {angle}).")
    _check_operating(op, indicator)
    source = indicator or (Path(design).parent / op["indicator"] if "indicator" in op else None)
    label = "--indicator" if indicator else "[operating] indicator"
    curve = None if source is None else _indicator(Path(source), label)
    male_shaft = Shaft(
        _shaft(de.get("male_shaft_discharge"), "male_shaft_discharge"), _shaft(de.get("male_shaft_suction"), "male_shaft_suction")
    )
    female_shaft = Shaft(
        _shaft(de.get("female_shaft_discharge"), "female_shaft_discharge"),
        _shaft(de.get("female_shaft_suction"), "female_shaft_suction"),
    )
    if "speed_rpm" in op and not (np.isfinite(op["speed_rpm"]) and op["speed_rpm"] > 0):
        # deflect has no --speed: the speed only reaches the shared rotor build, which would name --speed
        raise InputError(f"[operating] speed_rpm must be a positive speed in rpm (got {op['speed_rpm']}).")
    exponent = float(op.get("polytropic_exponent", AIR_EXPONENT))
    return _Given(op, de, angle, terms, terms_label, curve, label, exponent, male_shaft, female_shaft)


def _check_operating(op: dict[str, Any], indicator: Path | None) -> None:
    """Refuse pressures, volume ratio, exponent and control edge out of range, and two ways of setting the discharge."""
    for key in ("suction_pressure_bar", "discharge_pressure_bar"):
        if not (np.isfinite(op[key]) and 0 < op[key] <= 1000):
            raise InputError(f"[operating] {key} must be an absolute pressure above 0 and up to 1000 bar (got {op[key]}).")
    if "volume_ratio" in op and not (np.isfinite(op["volume_ratio"]) and 1 < op["volume_ratio"] <= 50):
        raise InputError(f"[operating] volume_ratio must be above 1 and up to 50 (got {op['volume_ratio']}).")
    given = [f"[operating] {k}" for k in ("volume_ratio", "discharge_edge_deg", "indicator") if k in op]
    given += ["--indicator"] if indicator else []
    if len(given) > 1:
        raise InputError(f"give only one of {', '.join(given)}: each sets where the discharge opens (got {len(given)}).")
    for key, lo, hi in (("polytropic_exponent", 1.0, 2.0), ("discharge_edge_deg", 0.0, 3600.0)):
        if key in op and not (np.isfinite(op[key]) and lo <= op[key] <= hi):
            raise InputError(f"[operating] {key} must be a number from {lo:g} to {hi:g} (got {op[key]}).")


def _indicator(source: Path, label: str) -> np.ndarray:
    """Read an indicator diagram (CSV ``angle_deg,pressure_bar``); return chamber angle [rad] and pressure [bar], (n, 2)."""
    try:
        rows = read_points(source, label, columns=("angle_deg", "pressure_bar"))
    except DesignError as exc:
        raise InputError(exc.sentence()) from None
    if not (np.all(np.diff(rows[:, 0]) >= 0) and rows[-1, 0] > rows[0, 0]):
        line = int(np.argmin(np.diff(rows[:, 0]) >= 0)) + 2
        raise InputError(
            f"{label} must have chamber angles that do not decrease (a pressure jump: one angle twice; data row {line} "
            f"goes back): {source}."
        )
    if not np.all((rows[:, 1] > 0) & (rows[:, 1] <= 1000)):
        raise InputError(f"{label} must have absolute pressures above 0 and up to 1000 bar: {source}.")
    return np.c_[np.radians(rows[:, 0]), rows[:, 1]]


def _model(rotors, given: _Given, load: LoadModel) -> GasDeflection:
    """Build the gas-load model of the pair; a model the design cannot make is refused."""
    op, de, edge = given.op, given.de, given.op.get("discharge_edge_deg")
    try:
        model = GasDeflection(
            rotors,
            float(op["suction_pressure_bar"]),
            float(op["discharge_pressure_bar"]),
            exponent=given.exponent,
            volume_ratio=op.get("volume_ratio"),
            discharge_edge=None if edge is None else float(np.radians(edge)),
            indicator=given.curve,
            young=float(de.get("young_modulus", STEEL[0])),
            poisson=float(de.get("poisson_ratio", STEEL[1])),
            male_shaft=given.male_shaft,
            female_shaft=given.female_shaft,
            terms=given.terms,
            step_deg=STEP_DEG,
            load=load,
        )
    except DesignError as exc:
        raise InputError(exc.sentence()) from None
    return model


def _check_indicator_covers(pair, given: _Given) -> None:
    """Refuse an indicator diagram that does not cover the chamber's cycle (known from the pair before its chamber table)."""
    if given.curve is None or not 360.0 * pair.length / pair.lead <= MAX_WRAP_DEG:  # a wrap the model refuses itself
        return
    end = float(np.degrees(cycle_angle(pair.male_teeth, pair.female_teeth, pair.lead, pair.length, STEP_DEG)))
    first, last = np.degrees(given.curve[0, 0]), np.degrees(given.curve[-1, 0])
    if first > 1.0 or last < end - 1.0:
        raise InputError(
            f"{given.curve_label} must cover the chamber's cycle from 0 to {end:.1f} deg (male rotation since the chamber "
            f"opened at the suction end; it covers {first:.1f} to {last:.1f} deg)."
        )


@dataclass(frozen=True)
class _Solved:
    """The deflection lines of both flute loads: the chosen one's and the other's (for comparison)."""

    at: float  # male angle shown [rad]
    swept: np.ndarray  # (angles, 2) largest |w| of male and female over one male pitch [mm]
    lines: Any  # the lines at ``at``
    two: Any  # the same with two sine terms (Rinder & Deix's own approximation)
    other: GasDeflection  # the model with the other flute load
    other_at: float
    other_swept: np.ndarray
    other_lines: Any


def _solve(model: GasDeflection, sweep_angles: np.ndarray, given: _Given, quiet: bool) -> _Solved:
    """Sweep one male pitch, find the worst angle (or take --angle), and the lines of both flute loads there."""
    shafts = given.shafts
    other = model.with_load(LoadModel.CHORD if model.load is LoadModel.CHAMBER else LoadModel.CHAMBER)
    with Steps("deflection: angle sweep", 4, quiet) as progress:
        swept = model.sweep(sweep_angles, shaft=shafts)
        progress.advance(description="deflection: worst angle")
        if given.angle is None:
            at = model.refine_worst(sweep_angles, swept.max(axis=1), shaft=shafts)
        else:
            at = float(np.radians(given.angle))
        progress.advance(description="deflection: lines")
        lines = model.at(at)
        two = model.at(at, terms=2)
        progress.advance(description="deflection: the other flute load")
        other_swept = other.sweep(sweep_angles, shaft=shafts)
        other_at = at if given.angle is not None else other.refine_worst(sweep_angles, other_swept.max(axis=1), shaft=shafts)
        other_lines = other.at(other_at)
        progress.advance()
    return _Solved(at, swept, lines, two, other, other_at, other_swept, other_lines)


def _own_worst_angle(model: GasDeflection, solved: _Solved, given: _Given, sweep_angles: np.ndarray, column: int) -> float:
    """Return one rotor's worst male angle [deg] over the sweep, refined as ``angle_deg`` is (whatever --angle)."""
    swept = solved.swept[:, column]
    if given.angle is None and swept.max() >= solved.swept.max():  # this rotor's maximum is angle_deg's
        return float(np.degrees(solved.at))
    from rotorcad.roles import Side

    side = (Side.MALE, Side.FEMALE)[column]
    return float(np.degrees(model.refine_worst(sweep_angles, swept, shaft=given.shafts, side=side)))


def _result(model: GasDeflection, solved: _Solved, given: _Given, male_teeth: int, sweep_angles: np.ndarray) -> dict[str, Any]:
    """Return the result keys (CONTRACT.md, ``deflect``; units declared in :mod:`rotorcad.quantities`)."""
    lines, at = solved.lines, solved.at
    result: dict[str, Any] = {}
    for column, (rotor, beam) in enumerate((("male", model.male), ("female", model.female))):
        helical = lines.largest(rotor)
        whole = lines.largest(rotor, shaft=True)
        result[f"{rotor}_max_deflection"] = whole[0]
        result[f"{rotor}_max_deflection_position"] = whole[1]  # from the discharge bearing (or end face)
        result[f"{rotor}_deflection_direction_deg"] = whole[2]
        result[f"{rotor}_max_deflection_helical"] = helical[0]
        result[f"{rotor}_max_deflection_helical_ritz2"] = solved.two.largest(rotor)[0]
        result[f"{rotor}_equivalent_diameter"] = beam.diameter
        result[f"{rotor}_root_diameter"] = beam.root_diameter
        result[f"{rotor}_section_area"] = beam.area
        result[f"{rotor}_second_moment"] = beam.j_total
        result[f"{rotor}_second_moment_core"] = beam.j_core
        result[f"{rotor}_second_moment_reduced"] = beam.j_reduced
        result[f"{rotor}_kappa_min"], result[f"{rotor}_kappa_max"] = beam.kappa_range
        result[f"{rotor}_worst_angle_deg"] = _own_worst_angle(model, solved, given, sweep_angles, column)
    result["angle_deg"] = float(np.degrees(at))
    cycle = model.cycle
    if np.isfinite(cycle.opening):
        result["angle_eq10_deg"] = float(np.degrees(model.worst_angle_eq10()))
        result["suction_closing_deg"] = float(np.degrees(cycle.closing))
        result["discharge_opening_deg"] = float(np.degrees(cycle.opening))
        result["volume_ratio"] = cycle.volume_ratio
    result["chamber_max_volume"] = float(cycle.volume.max())
    result["displacement_per_male_rev"] = float(cycle.volume.max() * male_teeth)
    result["chambers"] = model.chambers(at)  # at the angle shown: pressure and reach of each chamber
    result.update(_bearing_loads(model, at, sweep_angles))
    result["terms"] = given.terms
    result["shaft_ends"] = given.shafts
    result["method"] = model.load.value
    result.update(_both_loads(model, solved))
    return result


def _bearing_loads(model: GasDeflection, at: float, sweep_angles: np.ndarray) -> dict[str, float]:
    """Gas force and bearing loads at the angle shown, and each bearing's largest load over one male pitch."""
    result: dict[str, float] = {}
    loads = model.bearing_loads(at)
    peak = [loads] + [model.bearing_loads(a) for a in sweep_angles[::4]]  # and 25 angles over the pitch
    for rotor in ("male", "female"):
        result[f"{rotor}_gas_force_n"] = loads[rotor]["force"]
        result[f"{rotor}_gas_force_direction_deg"] = loads[rotor]["direction_deg"]
        for end in ("discharge", "suction"):
            result[f"{rotor}_{end}_bearing_load_n"] = loads[rotor][f"{end}_bearing"]
            result[f"{rotor}_{end}_bearing_load_max_n"] = max(p[rotor][f"{end}_bearing"] for p in peak)
    return result


def _both_loads(model: GasDeflection, solved: _Solved) -> dict[str, float]:
    """Return the largest deflections and gas forces of both flute loads, and the paper's over rotorcad's."""
    result: dict[str, float] = {}
    both = {
        model.load.value: (solved.lines, solved.at, model),
        solved.other.load.value: (solved.other_lines, solved.other_at, solved.other),
    }
    for name in ("rotorcad", "paper"):
        ls, a, m = both[name]
        forces = m.bearing_loads(a)
        for rotor in ("male", "female"):
            result[f"{rotor}_max_deflection_helical_{name}"] = ls.largest(rotor)[0]
            result[f"{rotor}_max_deflection_{name}"] = ls.largest(rotor, shaft=True)[0]
            result[f"{rotor}_gas_force_n_{name}"] = forces[rotor]["force"]
        result[f"angle_deg_{name}"] = float(np.degrees(a))
    for rotor in ("male", "female"):
        for key in (f"{rotor}_max_deflection_helical", f"{rotor}_max_deflection", f"{rotor}_gas_force_n"):
            result[f"{key}_paper_to_rotorcad"] = result[f"{key}_paper"] / result[f"{key}_rotorcad"]
    return result


def _defaults(
    op: dict[str, Any],
    de: dict[str, Any],
    model: GasDeflection,
    exponent: float,
    terms_label: str,
    terms: int,
) -> dict[str, str]:
    """Return the inputs that changed the result and were not given, each as "value (default: how)"."""
    out: dict[str, str] = {}
    ratio = op["discharge_pressure_bar"] / op["suction_pressure_bar"]
    port = any(k in op for k in ("volume_ratio", "discharge_edge_deg", "indicator"))
    if "polytropic_exponent" not in op and np.isfinite(model.cycle.opening):
        out["[operating] polytropic_exponent"] = taken(f"{exponent:g}", "isentropic air")
    if not port and np.isfinite(model.cycle.opening):
        out["[operating] volume_ratio"] = taken(
            f"{model.cycle.volume_ratio:.4g}",
            f"matched to the pressure ratio, (p_d/p_s)^(1/n) = {ratio:.4g}^(1/{exponent:g}); it fixes the control edge, "
            "the worst angle (eq. 10) and the loads: give the machine's built-in volume ratio",
        )
    if "young_modulus" not in de:
        out["[deflection] young_modulus"] = taken(f"{STEEL[0]:g} N/mm^2", "steel")
    if "poisson_ratio" not in de:
        out["[deflection] poisson_ratio"] = taken(f"{STEEL[1]:g}", "steel")
    for rotor in ("male", "female"):
        for end in ("discharge", "suction"):
            key = f"{rotor}_shaft_{end}"
            if key not in de:
                out[f"[deflection] {key}"] = taken("none", "the bearing at the end face: the helical part alone")
    if terms_label != "--terms" and "terms" not in de:
        out["[deflection] terms"] = taken(f"{terms}", "sine terms of the Ritz-Galerkin series, converged to < 0.1 %")
    return out


@styled
def _plot(
    model: GasDeflection,
    lines,
    angles: np.ndarray,
    swept: np.ndarray,
    shafts: bool,
    case: str = "",
    other_lines=None,
    other_swept: np.ndarray | None = None,
) -> Figure:
    """Draw the deflection lines of both rotors and the largest deflection over one male pitch.

    The lines at the chosen angle (w_x, w_y in the rotors' frame: x from O1 to O2, y turned 90 deg
    counter-clockwise; |w|), the other flute load's |w| dashed, the helical part's end faces marked on
    a shaft, and the largest deflection over one male pitch with the chosen angle marked (Rinder &
    Deix Figs. 9 and 10). Rinder & Deix's largest deflections of their 5/6 example (sec. 3.5, the
    values in the text; the curves of Figs. 9/10 are not) are drawn as dotted levels on the same axes.
    """
    fig = ps.new_figure(12.0, 7.6)
    axes = fig.subplots(2, 2)
    length = model.pair.length
    for col, rotor in enumerate(("male", "female")):
        ax = axes[0, col]
        shaft_z = getattr(lines, f"{rotor}_shaft_z")
        if shafts and len(shaft_z):
            z, w = shaft_z, getattr(lines, f"{rotor}_shaft")
            ax.set_xlabel(ps.label("z from the discharge bearing", "mm"))
            start = model.journal_length(rotor)
            for end in (start, start + length):
                ax.axvline(end, color=ps.GREY, lw=0.8, ls=":")
            ax.axvspan(start, start + length, color="#EEEEEE", zorder=0, label="helical part")
        else:
            z, w = lines.z, getattr(lines, rotor)
            ax.set_xlabel(ps.label("z from the discharge end face", "mm"))
        ax.plot(z, w[:, 0] * 1e3, color=ps.BLUE, label="w_x (x from O1 to O2)")
        ax.plot(z, w[:, 1] * 1e3, color=ps.ORANGE, label="w_y (x turned 90° ccw)")
        ax.plot(z, np.hypot(w[:, 0], w[:, 1]) * 1e3, color=ps.BLACK, lw=1.6, label=f"|w| ({model.load.value} load)")
        if other_lines is not None:
            oz = getattr(other_lines, f"{rotor}_shaft_z") if shafts and len(shaft_z) else other_lines.z
            ow = getattr(other_lines, f"{rotor}_shaft") if shafts and len(shaft_z) else getattr(other_lines, rotor)
            other_name = "paper" if model.load.value == "rotorcad" else "rotorcad"
            ax.plot(oz, np.hypot(ow[:, 0], ow[:, 1]) * 1e3, "--", color=ps.GREY, lw=1.2, label=f"|w| ({other_name} load)")
        paper = PAPER_MAX[rotor][1 if shafts else 0] * 1e3
        ax.axhline(paper, color=ps.VERMILLION, lw=1.0, ls=":", label=f"Rinder & Deix 5/6 at 12 bar: {paper:g} µm")
        ax.axhline(0.0, color=ps.GREY, lw=0.5)
        ax.set_ylabel(ps.label("deflection w", "µm"))
        ax.set_title(f"{rotor} deflection line at male angle {np.degrees(lines.angle):.2f}°")
        ps.legend_below(ax, ncol=2, bbox_to_anchor=(0.5, -0.2))
        ax2 = axes[1, col]
        ax2.plot(np.degrees(angles), swept[:, col] * 1e3, "-", color=ps.BLACK, label=f"largest |w| ({model.load.value} load)")
        if other_swept is not None:
            ax2.plot(np.degrees(angles), other_swept[:, col] * 1e3, "--", color=ps.GREY, label="the other flute load")
        ax2.axvline(
            np.degrees(lines.angle) % np.degrees(angles[-1] + angles[1] - angles[0]),
            color=ps.VERMILLION,
            lw=1.2,
            label="angle shown above",
        )
        ax2.set_xlabel(ps.label("male rotation angle φ1", "°"))
        ax2.set_ylabel(ps.label("largest deflection |w|", "µm"))
        ax2.set_title(f"{rotor}: largest deflection over one male pitch")
        ps.legend_below(ax2, ncol=2)
    cycle = model.cycle
    pair = model.pair
    ps.title(
        fig,
        f"deflection under gas load, {case or 'rotor pair'} {pair.male_teeth}/{pair.female_teeth}",
        f"{cycle.suction * 10:g} → {cycle.discharge * 10:g} bar, "
        + (f"built-in volume ratio {cycle.volume_ratio:.2f}" if np.isfinite(cycle.opening) else "indicator diagram")
        + (", shafts on their bearings" if shafts else ", helical part simply supported at its end faces"),
    )
    return fig

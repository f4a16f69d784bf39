"""``rotorcad coupling``: lubricant film of a gear coupling with barrel-shaped teeth.

CONTRACT.md; after Belkov, Maksimov & Shitikov (:mod:`rotorcad.coupling`).
"""

from __future__ import annotations

import math
import sys
from dataclasses import replace
from pathlib import Path
from typing import Any

import click
import numpy as np
from matplotlib.figure import Figure
from rich.console import Console
from rich.table import Table

from rotorcad import plot_style as ps
from rotorcad import quantities
from rotorcad.cli.common import InputError, Outputs, emit_json, plain, reraise
from rotorcad.cli.defaults import print_defaults, taken
from rotorcad.coupling import (
    DEFAULT_ROUGHNESS,
    STEEL_POISSON,
    STEEL_YOUNG,
    CouplingResult,
    Eq7Reading,
    GearCoupling,
    Hold,
    Regime,
    Verdict,
    analyse,
    reduced_modulus_of,
    sweep_teeth,
)
from rotorcad.errors import DesignError
from rotorcad.plot_style import styled

OPTION_OF = {
    "teeth": "--teeth",
    "module": "--module",
    "barrel_radius": "--barrel-radius",
    "pressure_angle": "--pressure-angle",
    "addendum": "--addendum",
    "face_width": "--face-width",
    "speed_rpm": "--speed",
    "viscosity": "--viscosity",
    "power_kw": "--power",
    "pressure_viscosity": "--pressure-viscosity",
    "misalignment": "--misalignment-deg",
    "load_factor": "--load-factor",
    "young_modulus": "--young-modulus",
    "poisson_ratio": "--poisson-ratio",
    "roughness": "--roughness",
}

# option key -> (flag, low, high, low included, the allowed range as words); None = required option absent.
# The lower ends keep the film thicknesses above underflow: `--speed 1e-308` or `--module 1e-300`
# made the EHL film 0 and its ratio a division by zero (found by the fuzz suite, tests/test_fuzz_cli.py)
RANGES: dict[str, tuple[str, float, float, bool, str]] = {
    "teeth": ("--teeth", 6, 1000, True, "a whole number from 6 to 1000"),
    "module": ("--module", 0.1, 100.0, True, "a number from 0.1 to 100 (mm)"),
    "face_width": ("--face-width", 0.1, 2000.0, True, "a number from 0.1 to 2000 (mm)"),
    "speed": ("--speed", 0.1, 1e6, True, "a number from 0.1 to 1e6 (rpm)"),
    "viscosity": ("--viscosity", 1e-5, 100.0, True, "a number from 1e-5 (a gas) to 100 (Pa s)"),
    "power": ("--power", 1e-3, 1e7, True, "a number from 0.001 to 1e7 (kW)"),
    "pressure_viscosity": ("--pressure-viscosity", 0.0, 1e-6, True, "a number from 0 to 1e-6 (1/Pa)"),
    "misalignment_deg": ("--misalignment-deg", 0.0, 10.0, True, "a number from 0 to 10 (degrees)"),
    "pressure_angle": ("--pressure-angle", 10.0, 40.0, True, "a number from 10 to 40 (degrees)"),
    "addendum": ("--addendum", 0.0, 2.0, False, "a positive number up to 2"),
    "load_factor": ("--load-factor", 1.0, 10.0, True, "a number from 1 to 10"),
    "barrel_radius": ("--barrel-radius", 0.0, 1e7, False, "a positive number up to 1e7 (mm)"),
    "young_modulus": ("--young-modulus", 1e3, 1e7, True, "a number from 1000 to 1e7 (N/mm^2)"),
    "poisson_ratio": ("--poisson-ratio", 0.0, 0.499, True, "a number from 0 to 0.499"),
    "roughness": ("--roughness", 0.0, 100.0, False, "a positive number up to 100 (um)"),
}
OPTIONAL = {"pressure_angle", "addendum", "load_factor", "barrel_radius", "young_modulus", "poisson_ratio", "roughness"}
PAPER_PRESSURE_SHARE = 0.5  # Belkov et al., text under Fig. 4: p_max about 50 % below the Hertz stress
MIN_DERIVED_MISALIGNMENT = 0.01  # deg: below it the derived crowning radius exceeds ~100 b

HELP = """Lubricant film of a gear coupling with barrel-shaped (crowned) hub teeth: the contact-hydrodynamic
calculation of Belkov, Maksimov & Shitikov (Reynolds equation with Barus viscosity and the elastic gap of a
cylinder of the flank crown radius on a plane, minimum film where the film carries the tooth load). Steel
teeth by default, E = 200 GPa and nu = 0.3 (the paper's values; --young-modulus, --poisson-ratio). Inputs
outside the model (no rolling of the contact: R_b <= r (1 + sin alpha); a film thicker than a tenth of the
module) exit 2 naming the option and its range. hydrodynamic is true when the film separates the flanks
(lambda = h_min / roughness >= 3, on the face); the regime is one word by a stated rule (no_solution,
edge_contact, boundary, mixed, starved, full_film: README), starved (a short inlet, a rule of thumb) beside a
hydrodynamic film; no_solution exits 1 with its reason. Both readings of eq. 7 are computed
(--method rotorcad: eq. 7 is the mean entraining speed; paper: it is the sum of the surface speeds, u half of
it). Every default taken is printed.

\b
Keys (JSON and table): hydrodynamic (bool: lambda >= 3), min_film_thickness [mm], load_capacity [N, one tooth],
max_pressure [MPa, in the film], hertz_stress [MPa, dry Hertz line contact], message; further:
central_film_thickness [mm], ehl_film_thickness [mm, Dowson-Higginson], ehl_ratio [1, h_min / Dowson-Higginson],
pressure_to_hertz_ratio [1], tooth_load [N, normal], load_per_length [N/mm], pitch_radius, barrel_radius (R0),
flank_crown_radius (R_b = R0 / sin alpha), crowning_depth, contact_length, hertz_half_width, contact_excursion [mm],
edge_contact (bool), inlet_length [mm, where the gap is within ten central films], inlet_room [mm, from the
contact's farthest position to the face edge], inlet_off_face (bool: the film may be starved),
mean_sliding_velocity, mean_entraining_velocity, max_rolling_velocity, max_axial_sliding_velocity [m/s], regime,
regime_reason, film_parameter [1, h_min / roughness], roughness [mm], line_contact_holds (bool), method,
eq7_velocity [m/s, eq. 7 as printed], min_film_thickness_rotorcad / _paper [mm] and _paper_to_rotorcad [1],
ehl_film_thickness_rotorcad / _paper [mm] and _paper_to_rotorcad [1], defaults, files.
"""


@click.command(help=HELP)
@click.option("--teeth", type=int, help="Number of teeth z of hub and sleeve.")
@click.option("--module", type=float, help="Module m [mm].")
@click.option(
    "--barrel-radius",
    type=float,
    help="Crowning radius R0 of the hub teeth [mm] (arc of the hob centre); default b sin(alpha) / (4 tan(gamma)).",
)
@click.option("--pressure-angle", type=float, default=20.0, show_default=True, help="Pressure angle alpha [deg].")
@click.option("--addendum", type=float, default=0.8, show_default=True, help="Addendum factor h_a*.")
@click.option("--face-width", type=float, help="Face width b [mm] (the paper: 6...10 m).")
@click.option("--speed", type=float, help="Speed n [rpm].")
@click.option("--viscosity", type=float, help="Mean oil viscosity mu_0 [Pa s].")
@click.option("--power", type=float, help="Power P on the shaft [kW].")
@click.option("--pressure-viscosity", type=float, help="Barus pressure-viscosity coefficient alpha_0 [1/Pa], e.g. 2e-8.")
@click.option("--misalignment-deg", type=float, help="Shaft misalignment gamma [deg] (the paper: 0.17...0.4).")
@click.option("--load-factor", type=float, default=1.0, show_default=True, help="Load distribution factor K_H.")
@click.option("--young-modulus", type=float, help="Young's modulus E of hub and sleeve [N/mm^2]. Default 200000 (steel).")
@click.option("--poisson-ratio", type=float, help="Poisson's ratio nu of hub and sleeve. Default 0.3 (steel).")
@click.option(
    "--roughness",
    type=float,
    help="Composite roughness sigma = sqrt(Rq1^2 + Rq2^2) of the flanks [um], for the film parameter. Default 1.0.",
)
@click.option(
    "--method",
    type=click.Choice([r.value for r in Eq7Reading]),
    default=Eq7Reading.MEAN.value,
    show_default=True,
    help="Reading of eq. 7 for the reported film: 'rotorcad' eq. 7 is the mean entraining speed u, 'paper' it is "
    "the sum of the surface speeds (u half of it). Both are computed and compared.",
)
@click.option("--json", "as_json", is_flag=True, help="Print one JSON object on stdout.")
@click.option(
    "--plot",
    type=click.Path(path_type=Path, dir_okay=False),
    help="Picture (PNG, SVG or PDF by the suffix): speeds over one revolution, film pressure and shape, "
    "h_min over the number of teeth.",
)
@click.option("--quiet", is_flag=True, help="No progress output (there is none).")
def coupling(**opts: Any) -> None:
    """Run ``rotorcad coupling``: check the options, analyse the coupling, print and write the results.

    The help text the user sees is :data:`HELP` (given to click), not this docstring.
    """
    _check_inputs(opts)
    c = _build(opts)
    r = analyse(c)
    if r.verdict is Verdict.NO_ENTRAINMENT:  # the paper's "error in the input data"
        raise InputError(_no_entrainment(opts, c))
    if r.verdict is Verdict.THICK_FILM:
        raise InputError(_thick_film(opts, r))
    other_reading = Eq7Reading.SUM if c.reading is Eq7Reading.MEAN else Eq7Reading.MEAN
    other = analyse(replace(c, reading=other_reading))
    result = _result(r)
    films = {c.reading.value: r, other_reading.value: other}
    for key in ("min_film_thickness", "ehl_film_thickness"):
        for name in ("rotorcad", "paper"):
            result[f"{key}_{name}"] = getattr(films[name], key)
        result[f"{key}_paper_to_rotorcad"] = result[f"{key}_paper"] / result[f"{key}_rotorcad"]
    result["defaults"] = _defaults(opts, c)
    out = Outputs()
    out.add_figure(opts["plot"], lambda: _plot(r), "--plot")
    result["files"] = [str(x) for x in out.write()]
    if opts["as_json"]:
        emit_json(result)
    else:
        _print_table(f"gear coupling z={c.teeth}, m={c.module:g} mm, n={c.speed_rpm:g} rpm, P={c.power_kw:g} kW", result)
        print_defaults(result["defaults"])
    if r.regime is Regime.NO_SOLUTION:  # a finding, not an error: the coupling has no film to report (CONTRACT.md)
        click.get_current_context().exit(1)


def _no_entrainment(opts: dict[str, Any], c: GearCoupling) -> str:
    """One sentence for eq. 7 giving no rolling: the parameter, its allowed range and why (R_b <= r (1 + sin alpha))."""
    arm = c.pitch_radius * (1.0 + math.sin(c.pressure_angle))  # mm: R_b must exceed it (eq. 7)
    got = opts["misalignment_deg"]
    if got <= 0.0:
        return (
            "--misalignment-deg must be above 0 (the paper's range is 0.17-0.4 deg): eq. 7 gives the contact no rolling "
            f"without it (got {got:g})."
        )
    if opts["barrel_radius"] is None:  # R_b = R0 / sin(alpha) = b / (4 tan(gamma))
        top = math.degrees(math.atan(c.face_width / (4.0 * arm)))
        least_b = 4.0 * math.tan(c.misalignment) * arm
        return (
            f"--misalignment-deg must be below {top:.3g} deg at --face-width {c.face_width:g} (or --face-width above "
            f"{least_b:.3g} mm at {got:g} deg; the paper's ranges are 0.17-0.4 deg and b = 6-10 m): the crowning they "
            f"derive, R_b = b / (4 tan(gamma)) = {c.flank_radius:.4g} mm, must exceed r (1 + sin(alpha)) = {arm:.4g} mm "
            f"for eq. 7 to give the contact a rolling speed (got {got:g})."
        )
    least = arm * math.sin(c.pressure_angle)
    return (
        f"--barrel-radius must be above {least:.4g} mm for this --teeth, --module and --pressure-angle: the flank crown "
        f"radius R0 / sin(alpha) = {c.flank_radius:.4g} mm must exceed r (1 + sin(alpha)) = {arm:.4g} mm for eq. 7 to give "
        f"the contact a rolling speed (got {opts['barrel_radius']:g})."
    )


def _thick_film(opts: dict[str, Any], r: CouplingResult) -> str:
    """One sentence for a film thicker than m / 10: the model's limit, with the power that reaches it.

    Below the limit the film is the rigid-isoviscous one, h proportional to 1 / load (Martin), so the
    power at which h_min falls to m / 10 is about P h_min / (m / 10).
    """
    c = r.coupling
    limit = 0.1 * c.module
    least = opts["power"] * r.min_film_thickness / limit
    return (
        f"--power must be above about {least:.3g} kW at this --speed, --viscosity and crowning radius "
        f"(got {opts['power']:g}): the film h_min = {r.min_film_thickness:.3g} mm is thicker than a tenth of the module, "
        f"m / 10 = {limit:.3g} mm, where the paper's thin-film model ends (the film falls as 1 / load there)."
    )


def _defaults(opts: dict[str, Any], c: GearCoupling) -> dict[str, str]:
    """Return the inputs that changed the result and were not given, each as "value (default: how)"."""
    out: dict[str, str] = {}
    if opts["barrel_radius"] is None:
        out["--barrel-radius"] = taken(
            f"{c.crown_radius:.6g} mm", "the paper's crowning for the misalignment, R0 = b sin(alpha) / (4 tan(gamma))"
        )
    src = click.get_current_context()
    for key, flag, how in (
        ("pressure_angle", "--pressure-angle", "the paper's alpha"),
        ("addendum", "--addendum", "the paper's h_a*"),
        ("load_factor", "--load-factor", "equal sharing by all z teeth"),
    ):
        if src.get_parameter_source(key) is click.core.ParameterSource.DEFAULT:
            out[flag] = taken(f"{opts[key]:g}" + (" deg" if key == "pressure_angle" else ""), how)
    if opts["young_modulus"] is None:
        out["--young-modulus"] = taken(f"{STEEL_YOUNG:g} N/mm^2", "steel, the paper's")
    if opts["poisson_ratio"] is None:
        out["--poisson-ratio"] = taken(f"{STEEL_POISSON:g}", "steel, the paper's")
    if opts["roughness"] is None:
        out["--roughness"] = taken(
            f"{DEFAULT_ROUGHNESS * 1e3:g} um", "hobbed or shaped coupling flanks, Rq 0.7 um each, composite sqrt(2) 0.7"
        )
    out["viscosity model"] = taken(
        "Barus mu_0 exp(alpha_0 p), isothermal", "the paper's eq. 6; mu_0 the inlet viscosity, no thermal correction"
    )
    out["teeth in contact"] = taken("z", "all teeth share the load; --load-factor carries the unequal sharing")
    return out


def _check_inputs(opts: dict[str, Any]) -> None:
    """Every option present (unless optional), finite and in its range; misalignment > 0 without a barrel radius."""
    for key, (flag, lo, hi, closed, allowed) in RANGES.items():
        v = opts.get(key)
        if v is None:
            if key in OPTIONAL:
                continue
            raise InputError(f"{flag} is required ({allowed}).")
        ok = (v.bit_length() < 64 if isinstance(v, int) else math.isfinite(v)) and (v >= lo if closed else v > lo) and v <= hi
        if not ok:  # an integer beyond float range (`--teeth 10**400`) is compared as it is, never converted
            shown = (
                v
                if not isinstance(v, int) or v.bit_length() < 64
                else f"an integer of {int(v.bit_length() * 0.30103) + 1} digits"
            )
            raise InputError(f"{flag} must be {allowed} (got {shown}).")
    from rotorcad.cli.plausible import say_warnings
    from rotorcad.design.plausibility import module_warnings

    say_warnings(module_warnings(opts["module"], "--module"))  # an inch-typed coupling: 8 s to end in no_solution
    if opts["barrel_radius"] is None and opts["misalignment_deg"] < MIN_DERIVED_MISALIGNMENT:
        raise InputError(
            f"--misalignment-deg must be at least {MIN_DERIVED_MISALIGNMENT} when --barrel-radius is not given "
            f"(R0 = b sin(alpha) / (4 tan(gamma)) grows without bound as gamma -> 0; give --barrel-radius) "
            f"(got {opts['misalignment_deg']})."
        )


def _build(opts: dict[str, Any]) -> GearCoupling:
    try:
        return GearCoupling(
            teeth=opts["teeth"],
            module=opts["module"],
            face_width=opts["face_width"],
            speed_rpm=opts["speed"],
            power_kw=opts["power"],
            viscosity=opts["viscosity"],
            pressure_viscosity=opts["pressure_viscosity"],
            misalignment=math.radians(opts["misalignment_deg"]),
            pressure_angle=math.radians(opts["pressure_angle"]),
            addendum=opts["addendum"],
            barrel_radius=opts["barrel_radius"],
            load_factor=opts["load_factor"],
            modulus=reduced_modulus_of(
                STEEL_YOUNG if opts["young_modulus"] is None else opts["young_modulus"],
                STEEL_POISSON if opts["poisson_ratio"] is None else opts["poisson_ratio"],
            ),
            roughness=(DEFAULT_ROUGHNESS * 1e3 if opts["roughness"] is None else opts["roughness"]) * 1e-3,
            reading=Eq7Reading(opts["method"]),
        )
    except DesignError as exc:
        raise reraise(exc, OPTION_OF) from None


def _result(r: CouplingResult) -> dict[str, Any]:
    c = r.coupling
    _, rolling, axial, _ = c.speeds()
    return {
        "hydrodynamic": r.hydrodynamic,
        "min_film_thickness": r.min_film_thickness,
        "load_capacity": r.load_capacity,
        "max_pressure": r.max_pressure,
        "hertz_stress": r.hertz_stress,
        "message": r.message,
        "central_film_thickness": r.central_film_thickness,
        "ehl_film_thickness": r.ehl_film_thickness,
        "ehl_ratio": r.ehl_ratio,
        "pressure_to_hertz_ratio": r.max_pressure / r.hertz_stress,
        "tooth_load": c.tooth_load,
        "load_per_length": c.load_per_length * 1e-3,
        "pitch_radius": c.pitch_radius,
        "barrel_radius": c.crown_radius,
        "flank_crown_radius": c.flank_radius,
        "crowning_depth": c.crowning_depth,
        "contact_length": c.contact_length,
        "hertz_half_width": r.hertz_half_width,
        "contact_excursion": c.contact_excursion,
        "edge_contact": r.edge_contact,
        "inlet_length": r.inlet_length,
        "inlet_room": r.inlet_room,
        "inlet_off_face": r.inlet_off_face,
        "mean_sliding_velocity": c.mean_sliding_speed,
        "mean_entraining_velocity": c.entraining_speed,
        "max_rolling_velocity": float(np.abs(rolling).max()),
        "max_axial_sliding_velocity": float(np.abs(axial).max()),
        "regime": r.regime.value,
        "regime_reason": r.regime_reason,
        "film_parameter": r.film_parameter,
        "roughness": c.roughness,
        "line_contact_holds": r.line_contact_holds,
        "method": c.reading.value,
        "eq7_velocity": c.eq7_speed,
    }


def _print_table(title: str, rows: dict[str, Any]) -> None:
    """Quantity, value and unit of every key (units declared in :mod:`rotorcad.quantities`)."""
    table = Table(title=title, show_header=True, header_style="bold")
    for name, justify in (("quantity", "left"), ("value", "right"), ("unit", "left")):
        table.add_column(name, justify=justify)
    for key, value in plain(rows).items():
        if isinstance(value, (list, dict)):
            continue
        if isinstance(value, bool) or value is None or isinstance(value, str):
            table.add_row(key, "-" if value is None else str(value), "")
        else:
            table.add_row(key, f"{value:.6g}" if abs(value) < 1e-3 else f"{value:.6f}", quantities.unit_of(key))
    Console(file=sys.stdout, highlight=False, width=110).print(table)


PLOT_NODES = 101
"""Grid nodes of each film solution of the --plot's h_min-over-z panel (the result's own film: 201).
Measured on the README coupling (z 40, m 4, 8000 rpm, 4 MW): the 36 solutions 20.4 s -> 4.2 s of CPU,
h_min within 0.5 % of the 201-node solutions (3.979 vs 3.990 µm), a trend the picture shows alike."""


@styled
def _plot(r: CouplingResult) -> Figure:
    """Fig. 2 (speeds over one revolution), Fig. 3 (film pressure and shape), Fig. 4 (h_min over z) of the paper."""
    c = r.coupling
    fig = ps.new_figure(10.0, 10.0)
    ax1, ax2, ax4 = fig.subplots(3, 1)
    psi, rolling, axial, radial = c.speeds()
    deg = np.degrees(psi)
    ax1.plot(deg, rolling, label="rolling V_k", color=ps.BLUE)
    ax1.plot(deg, axial, label="axial sliding V_os", color=ps.ORANGE)
    ax1.plot(deg, radial, label="radial sliding V_r", color=ps.GREEN)
    ax1.set_xlabel(ps.label("rotation angle ψ", "°"))
    ax1.set_ylabel(ps.label("speed", "m/s"))
    ax1.set_title("speeds at the tooth contact over one revolution (Fig. 2)")
    ps.legend_outside(ax1)
    if r.film is not None:
        x = r.film.x * 1e3
        ax2.plot(x, r.film.pressure / 1e6, color=ps.BLUE, label="film pressure")
        b = r.hertz_half_width
        xs = np.linspace(-b, b, 201)
        ax2.plot(xs, r.hertz_stress * np.sqrt(1.0 - (xs / b) ** 2), "--", color=ps.GREY, label="Hertz pressure (dry)")
        # Belkov et al., text under Fig. 4: "the largest film pressure is about 50 % below the contact stress"
        ax2.axhline(PAPER_PRESSURE_SHARE * r.hertz_stress, color=ps.VERMILLION, ls=":", lw=1.0, label="paper: p_max ≈ 0.5 σ_H")
        ax2.set_xlim(-3.0 * b, 2.0 * b)
        ax2.set_xlabel(ps.label("x along the face width", "mm"))
        ax2.set_ylabel(ps.label("pressure p", "MPa"))
        ax3 = ax2.twinx()
        ax3.plot(x, r.film.film * 1e6, color=ps.VERMILLION, label="film thickness h")
        ax3.set_ylim(0.0, 6.0 * r.min_film_thickness * 1e3)
        ax3.set_ylabel(ps.label("film thickness h", "µm"), color=ps.VERMILLION)
        ax3.grid(False)
        handles = ax2.get_legend_handles_labels()[0] + ax3.get_legend_handles_labels()[0]
        ps.legend_outside(ax2, handles, bbox_to_anchor=(1.1, 1.0))
    else:
        ax2.set_axis_off()
    ax2.set_title("pressure and film shape in the contact (Fig. 3)")
    teeth = np.unique(np.round(np.linspace(max(6, c.teeth // 2), 2 * c.teeth, 12)).astype(int))
    nodes = PLOT_NODES  # 36 film solutions: the trend at half the grid (--plot cost 5x the command without it)
    ax4.plot(teeth, sweep_teeth(c, teeth, nodes=nodes) * 1e3, "o-", color=ps.BLUE, label=f"module {c.module:g} mm and power kept")
    ax4.plot(
        teeth,
        sweep_teeth(c, teeth, nodes=nodes, hold=Hold.DIAMETER) * 1e3,
        "s--",
        color=ps.ORANGE,
        label="pitch diameter and power kept",
    )
    shown = sweep_teeth(c, teeth, nodes=nodes, hold=Hold.TOOTH_LOAD) * 1e3
    ax4.plot(teeth, shown, "^-", color=ps.GREEN, label="module and tooth load kept (the paper's trend)")
    # Belkov et al. give Fig. 4's trend in words only ("h_min falls slightly as z grows"): drawn as that
    # trend through this coupling's h_min, the curve's values are not in the text
    ax4.annotate(
        "paper, Fig. 4: h_min falls slightly as z grows\n(other conditions and geometry kept; values not printed)",
        xy=(0.02, 0.95),
        xycoords="axes fraction",
        va="top",
        fontsize=8,
        color=ps.VERMILLION,
    )
    ax4.axvline(c.teeth, color=ps.GREY, lw=0.8, label=f"this coupling, z = {c.teeth}")
    ax4.set_xlabel(ps.label("number of teeth z", "1"))
    ax4.set_ylabel(ps.label("minimum film thickness h_min", "µm"))
    ax4.set_title("h_min over the number of teeth (Fig. 4)")
    ps.legend_outside(ax4)
    ps.title(
        fig,
        f"gear coupling z = {c.teeth}, m = {c.module:g} mm, b = {c.face_width:g} mm: {r.regime.value.replace('_', ' ')}",
        f"n = {c.speed_rpm:g} rpm, P = {c.power_kw:g} kW, misalignment γ = {math.degrees(c.misalignment):g}°, "
        f"η0 = {c.viscosity:g} Pa·s, α0 = {c.pressure_viscosity:g} 1/Pa; h_min = {r.min_film_thickness * 1e3:.3g} µm",
    )
    return fig

"""``rotorcad pump``: external gear pump of two gears in mesh (CONTRACT.md)."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import click
import numpy as np
from matplotlib.figure import Figure

from hob.nomogram import plot_nomogram
from rotorcad import plot_style as ps
from rotorcad.cli.common import InputError, Outputs, emit_json, print_table, reraise
from rotorcad.cli.defaults import print_defaults, taken
from rotorcad.cli.gear import (
    DEFAULTS,
    DESIGN_PARAM,
    FROM_DESIGN,
    SPEC,
    build_gear,
    check_contact,
    gear_options,
    merge_gear_params,
)
from rotorcad.design.labels import contact_names
from rotorcad.errors import DesignError
from rotorcad.plot_style import styled
from rotorcad.pump import GearPump, kollek_coefficients

MM3_PER_S_TO_L_PER_MIN = 60.0 / 1e6
PUMP_OPTION = {
    "shifts": "--shift and --mate-shift",
    "mesh": "--teeth, --shift, --addendum and --pressure-angle",
}


@click.command()
@click.argument("design", required=False, type=click.Path(path_type=Path, dir_okay=False))
@gear_options
@click.option("--face-width", type=float, help="Face width b [mm].")
@click.option("--speed", type=float, help="Speed n [rpm].")
@click.option(
    "--harmonics",
    "count",
    type=int,
    default=8,
    show_default=True,
    help="Number of harmonics listed (table rows at k x the pump frequency, JSON 'harmonics', the --plot's bars).",
)
@click.option(
    "--method",
    type=click.Choice(["paper", "swept-volume"]),
    default="paper",
    show_default=True,
    help="Mean flow of 'mean_flow': 'paper' Kollek & Osinski eq. 2 (the delivery of these gears), 'swept-volume' the "
    "textbook 2 pi b m^2 z n. Both are reported with their ratio.",
)
@click.option("--json", "as_json", is_flag=True, help="Print one JSON object on stdout.")
@click.option("--plot", type=click.Path(path_type=Path, dir_okay=False), help="PNG of the delivery and its spectrum.")
@click.option(
    "--nomogram",
    type=click.Path(path_type=Path, dir_okay=False),
    help="PNG of the contact ratio over shift x and addendum factor y for this z and pressure angle (Kollek Fig. 4).",
)
@click.option("--quiet", is_flag=True, help="No progress output.")
def pump(design: Path | None, **opts: Any) -> None:
    """Delivery of an external gear pump: the gear drives its mate (Kollek & Osinski eqs. 2-9).

    Mean flow (eq. 2 for the pair given, and the textbook swept volume 2 pi b m^2 z n beside it),
    irregularity, harmonics and pump frequency f = n z / 60. Without --mate-teeth (or a [mate]
    table) the mate equals the gear. Helical gears: the delivery of the whole face (each transverse
    section's, shifted along the helix). Every default taken is printed.
    """
    # the face width up to 10 m as [gear] face_width of `export`, the speed up to 1e6 rpm as `coupling`'s
    for key, flag, top, unit in (("face_width", "--face-width", 10_000.0, "mm"), ("speed", "--speed", 1e6, "rpm")):
        v = opts.get(key)
        if v is None:
            raise InputError(f"{flag} is required (a positive number).")
        if not (np.isfinite(v) and 0 < v <= top):
            raise InputError(f"{flag} must be a positive number up to {top:g} {unit} (got {v}).")
    if not 1 <= opts["count"] <= 64:
        raise InputError(f"--harmonics must be a whole number from 1 to 64 (got {opts['count']}).")
    params = merge_gear_params(design, opts)
    named = params.get(FROM_DESIGN, {})
    defaulted = [
        k
        for k in ("pressure_angle", "helix_angle", "shift", "addendum")
        if opts.get(k) is None and DESIGN_PARAM.get(k, k) not in named
    ]
    g, pair = build_gear(params, 1e-4)
    mate = None if pair is None else (pair.mate, pair.center_distance)
    p = GearPump(g, opts["face_width"], opts["speed"], *(mate or ()))
    try:
        eps = p.contact_ratio
    except DesignError as exc:
        raise reraise(exc, PUMP_OPTION) from None
    names = "--teeth, --shift, --addendum and --pressure-angle"
    if pair is not None:  # the mate's values too, named as the user gave them (options or [mate] keys)
        names = contact_names(params[SPEC].from_design, pair.center_distance is not None)
    check_contact(eps, names)
    _check_in_mesh(p, names)
    if not (np.isfinite(p.mean_flow) and p.mean_flow > 0 and np.isfinite(p.irregularity) and p.irregularity >= 0):
        raise InputError(
            f"{names} must give a pump that delivers (a positive mean flow; got "
            f"{p.mean_flow * MM3_PER_S_TO_L_PER_MIN:.4g} L/min): the tips reach too little beyond the working pitch circle."
        )
    paper, swept = p.mean_flow * MM3_PER_S_TO_L_PER_MIN, p.swept_volume_flow * MM3_PER_S_TO_L_PER_MIN
    unit = {"pressure_angle": " deg", "helix_angle": " deg", "shift": "", "addendum": ""}
    how = {
        "pressure_angle": "ISO 53 basic rack",
        "helix_angle": "spur gears",
        "shift": "no profile shift",
        "addendum": "ISO 53 basic rack; it sets the tip radius r + m (h_a* + x), hence the flow, with no tip shortening",
    }
    result = {
        "mean_flow": paper if opts["method"] == "paper" else swept,
        "method": opts["method"],
        "mean_flow_paper": paper,
        "mean_flow_swept_volume": swept,
        "mean_flow_paper_to_swept_volume": paper / swept,
        "flow_irregularity": p.irregularity,
        "pump_frequency_hz": p.pump_frequency,
        "contact_ratio": eps,
        "overlap_contact_ratio": p.overlap_ratio,
        "total_contact_ratio": p.total_contact_ratio,
        "mate_teeth": p.pair.mate.teeth,
        "center_distance": p.pair.working_center_distance,
        "harmonics": p.harmonics(opts["count"]).tolist(),
        "kollek_series": {
            "numerical": p.cosine_series(opts["count"]).tolist(),
            "eqs_4_6": kollek_coefficients(eps, opts["count"]).tolist(),
        },
    }
    result.update(_trapped(p))
    out = Outputs()
    out.add_figure(opts["plot"], lambda: _plot(p, opts["count"]), "--plot")
    out.add_figure(opts["nomogram"], lambda: plot_nomogram(g.teeth, g.pressure_angle), "--nomogram")
    result["defaults"] = {f"--{k.replace('_', '-')}": taken(f"{DEFAULTS[k]:g}{unit[k]}", how[k]) for k in defaulted}
    if mate is None:
        result["defaults"]["--mate-teeth"] = taken(f"{g.teeth} and --mate-shift {g.shift:g}", "two equal gears")
    result["files"] = [str(x) for x in out.write()]
    if opts["as_json"]:
        emit_json(result)
    else:
        _print(result, p)


def _print(result: dict[str, Any], p: GearPump) -> None:
    """Print the table, the harmonics as rows ``harmonics.k`` (at k x the pump frequency, over the mean flow), the defaults."""
    shown = dict(result)
    shown.update({f"harmonics.{k}": h for k, h in enumerate(result["harmonics"], 1)})
    print_table(
        f"gear pump z={p.gear.teeth}/{p.pair.mate.teeth}, b={p.face_width:g} mm, n={p.speed_rpm:g} rpm; "
        f"harmonics.k at k x {p.pump_frequency:g} Hz, over the mean flow",
        shown,
    )
    print_defaults(result["defaults"])


def _trapped(p: GearPump) -> dict[str, float]:
    """Return the trapped-space keys of a spur pump (CONTRACT.md); none for a helical one or eps <= 1.

    The area from the gears' outlines (:meth:`rotorcad.pump.GearPump.trapped_area`, shapely), the
    volume that area times the face width, the change max - min squeezed out and refilled each pitch,
    and the largest flow of the squeeze (:meth:`rotorcad.pump.GearPump.trapped_flow_max`). In a helical
    pump the transverse sections' spaces join along the face: no closed space to report.
    """
    if p.overlap_ratio or p.contact_ratio <= 1.0:
        return {}
    _, area = p.trapped_area()
    b = p.face_width
    return {
        "trapped_double_contact_deg": float(np.degrees((p.contact_ratio - 1.0) * 2.0 * np.pi / p.gear.teeth)),
        "trapped_area_max": float(area.max()),
        "trapped_area_min": float(area.min()),
        "trapped_volume_max": float(area.max() * b),
        "trapped_volume_min": float(area.min() * b),
        "trapped_volume_change": float((area.max() - area.min()) * b),
        "trapped_flow_max": p.trapped_flow_max() * MM3_PER_S_TO_L_PER_MIN,
    }


def _check_in_mesh(p: GearPump, names: str) -> None:
    """Refuse a pump whose teeth leave the discharge open to the suction, or whose delivery is not modelled.

    Kollek & Osinski (sec. 2, Fig. 4): the meshing teeth separate the discharge from the suction side
    only while a pair is in contact: a spur pair needs eps_alpha >= 1, a helical one eps_gamma =
    eps_alpha + eps_beta >= 1 (the contact line then always crosses the face somewhere).
    """
    eps, total = p.contact_ratio, p.total_contact_ratio
    if total < 1.0:
        what = "contact ratio" if p.overlap_ratio == 0.0 else "total contact ratio (transverse + overlap)"
        raise InputError(
            f"{names} must give a gear pump a {what} of at least 1 (got {total:.4g}): below it no pair of teeth is in mesh "
            "for part of each pitch and the discharge opens to the suction; raise --shift or --addendum (see --nomogram)"
            + (" or --face-width." if p.overlap_ratio else ".")
        )
    if eps < 1.0:
        raise InputError(
            f"{names} must give a transverse contact ratio of at least 1 (got {eps:.4g}; total contact ratio {total:.4g}): "
            "a pair stays in mesh along the face, but the delivery of the transverse sections left without a contact is not "
            "modelled by rotorcad pump; raise --shift or --addendum (see --nomogram)."
        )


@styled
def _plot(p: GearPump, count: int = 12) -> Figure:
    """Delivery over one tooth pitch with its mean, and the harmonics of the delivery."""
    g = p.gear
    fig = ps.new_figure(10.0, 7.0)
    ax1, ax2 = fig.subplots(2, 1)
    phi, q = p.delivery()
    mean = p.mean_flow * MM3_PER_S_TO_L_PER_MIN
    ax1.plot(np.degrees(phi), q * MM3_PER_S_TO_L_PER_MIN, "-", color=ps.BLUE, lw=1.4, label="instantaneous delivery Q(φ)")
    ax1.axhline(mean, ls="--", color=ps.VERMILLION, lw=1.0, label=f"mean flow {mean:.4g} L/min")
    ax1.set_xlabel(ps.label("rotation angle within one tooth pitch φ", "°"))
    ax1.set_ylabel(ps.label("delivery Q", "L/min"))
    ax1.set_title(f"delivery (Kollek & Osiński eqs. 2-3): irregularity δ_Q = {p.irregularity:.3f}")
    ps.legend_outside(ax1)
    h = p.harmonics(count)  # as many as --harmonics lists
    ax2.bar(
        np.arange(1, len(h) + 1) * p.pump_frequency, h, width=0.6 * p.pump_frequency, color=ps.ORANGE, label="harmonic amplitude"
    )
    ax2.set_xlabel(ps.label("frequency f", "Hz"))
    ax2.set_ylabel(ps.label("amplitude / mean flow", "1"))
    ax2.set_title(f"harmonics of the delivery at k × the pump frequency {p.pump_frequency:.4g} Hz")
    ps.legend_outside(ax2)
    mate = p.pair.mate
    helix = (
        f", β = {np.degrees(g.helix_angle):g}°, ε_β = {p.overlap_ratio:.3f} (delivery of the whole face)"
        if p.overlap_ratio
        else ""
    )
    ps.title(
        fig,
        f"external gear pump z = {g.teeth}/{mate.teeth}, m = {g.module:g} mm, x = {g.shift:g}/{mate.shift:.4g}",
        f"α = {np.degrees(g.pressure_angle):g}°, b = {p.face_width:g} mm, n = {p.speed_rpm:g} rpm; ε = {p.contact_ratio:.3f}"
        f"{helix}, f = {p.pump_frequency:.4g} Hz",
    )
    return fig

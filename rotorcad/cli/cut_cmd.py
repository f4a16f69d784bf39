"""``rotorcad cut``: trapezoidal-hob (basic-rack) cutting simulation of a gear (CONTRACT.md)."""

from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING, Any

import click
import numpy as np
import shapely

from exports.csv_points import write_points
from exports.dxf import Drawing, write_dxf
from hob.cutting import MAX_UNION_VERTICES, cutting_work, simulate_cutting, simulated_form_radius
from hob.tools import TrapezoidalHob
from hob.undercut import model_keys
from rotorcad.cli.common import InputError, Outputs, emit_json, print_table, reraise
from rotorcad.cli.gear import GEAR_OPTION, SPEC, build_gear, gear_options, merge_gear_params
from rotorcad.cli.gear_internal import internal_options, refuse_internal_options
from rotorcad.cli.progress import Steps
from rotorcad.errors import DesignError
from rotorcad.gear import RELATIVE_TOLERANCE

if TYPE_CHECKING:
    from matplotlib.figure import Figure


@click.command()
@click.argument("design", required=False, type=click.Path(path_type=Path, dir_okay=False))
@gear_options
@internal_options
@click.option("--hob-addendum", type=float, help="Hob (tool) addendum factor h_a0* = the gear's dedendum. Default 1.25.")
@click.option("--positions", type=int, help="Number of tool positions (default: from --tolerance).")
@click.option("--tolerance", type=float, default=1e-3, show_default=True, help="Scallop height of the simulated profile [mm].")
@click.option("--json", "as_json", is_flag=True, help="Print one JSON object on stdout.")
@click.option(
    "--dxf", type=click.Path(path_type=Path, dir_okay=False), help="DXF: simulated gear, analytic gear, tool rack [mm]."
)
@click.option("--csv", type=click.Path(path_type=Path, dir_okay=False), help="Simulated gear outline as x,y points.")
@click.option("--plot", type=click.Path(path_type=Path, dir_okay=False), help="PNG of the simulated tooth over the analytic one.")
@click.option("--quiet", is_flag=True, help="No progress output.")
def cut(design: Path | None, **opts: Any) -> None:
    """Cut a gear with the ISO 53 basic-rack tool (a trapezoidal hob) by polygon booleans.

    The simulated gear is compared with the analytic envelope; the undercut radius comes from the
    simulation, the exact envelope and Kollek & Osiński's model (eq. 1, exact at the onset of
    undercut, above the exact point deeper in: its deviation and a note are given). An internal gear
    ([shaper] or --internal) is shaped instead by its shaper cutter, and compared with its envelope.
    """
    if opts.get("hob_addendum") is not None:
        if not (np.isfinite(opts["hob_addendum"]) and 0.1 <= opts["hob_addendum"] <= 3.0):
            raise InputError(f"--hob-addendum must be from 0.1 to 3 (factor of the module) (got {opts['hob_addendum']}).")
        opts["dedendum"] = opts["hob_addendum"]
    tol = opts["tolerance"]
    if not (tol and np.isfinite(tol) and 0 < tol <= 1.0):
        raise InputError(f"--tolerance must be a scallop height between 0 and 1 mm (got {tol}).")
    if opts["positions"] is not None and not 3 <= opts["positions"] <= 100000:
        raise InputError(f"--positions must be a whole number from 3 to 100000 (got {opts['positions']}).")
    params = merge_gear_params(design, opts)
    if params["internal"]:
        from rotorcad.cli.cut_internal import run_internal_cut

        run_internal_cut(params[SPEC], opts)
        return
    refuse_internal_options(opts)
    module = params["module"] if np.isfinite(params["module"]) else 1.0
    if 0 < module and tol > RELATIVE_TOLERANCE[1] * module:
        raise InputError(
            f"--tolerance must be at most {RELATIVE_TOLERANCE[1] * module:.3g} mm (a tenth of the module; got {tol:g})."
        )
    g, pair = build_gear(params, max(min(tol / 4, 1e-4), RELATIVE_TOLERANCE[0] * module))
    _check_work(g, tol, opts["positions"])
    try:
        with Steps("cutting", None, opts["quiet"]) as steps:
            res = simulate_cutting(
                g,
                tol,
                opts["positions"],
                progress=lambda n, dev: steps.advance(description=f"cutting: pass {steps.done + 1}, {n} positions, {dev:.2g} mm"),
            )
    except DesignError as exc:
        raise reraise(exc, GEAR_OPTION) from None
    exact = g.pitch_thickness()  # None: the reference circle lies below the root circle
    result: dict[str, Any] = {
        "undercut": g.undercut,
        "undercut_radius": _undercut_radius(g, res, tol),
        "undercut_radius_exact": g.form_radius if g.undercut else None,
        **model_keys(g),
        "max_deviation_from_envelope": res.max_deviation,
        "flank_deviation_from_envelope": res.flank_deviation,
        "tooth_thickness_pitch": None if exact is None else 2 * g.pitch_radius * _half_angle(res.tooth, g.pitch_radius),
        "tooth_thickness_pitch_exact": exact,
        "positions": res.positions,
        "tolerance_met": bool(res.max_deviation <= tol),
    }
    if pair is not None:
        result["contact_ratio"] = pair.contact_ratio
    whole = _whole_gear(res.tooth, g.teeth, g.module)
    out = Outputs()
    out.add(opts["csv"], lambda p: write_points(p, _ccw(whole), ["simulated gear, basic-rack cutting"]), "--csv")
    out.add(opts["dxf"], lambda p: write_dxf(p, _drawing(g, whole)), "--dxf")
    out.add_figure(opts["plot"], lambda: _plot(g, res, tol), "--plot")
    result["files"] = [str(p) for p in out.write()]
    if opts["as_json"]:
        emit_json(result)
    else:
        note = result.pop("undercut_model_note")
        print_table(f"cutting simulation z={g.teeth}, m={g.module:g} mm, x={g.shift:g}", result)
        click.echo(f"  - {note}")


def _undercut_radius(g, res, tol: float) -> float | None:
    """Return r'_z of the simulated profile, mm; None without undercut.

    The point where the simulated flank leaves the involute is searched within 1.5 x the scallop,
    then within the flank deviation the simulation reached (a budget-limited run); a profile with no
    involute left is refused (:class:`InputError`).
    """
    if not g.undercut:
        return None
    for within in (1.5 * tol, 1.5 * max(tol, res.flank_deviation), 0.02 * g.module):
        found = simulated_form_radius(g, res, within)
        if np.isfinite(found):
            return found
    raise InputError(
        "--teeth, --shift and --tip-radius must leave an involute flank on the simulated gear (it is undercut up to its tip)."
    )


def _work(g, tol: float, positions: int | None) -> tuple[int, int] | None:
    """Return :func:`hob.cutting.cutting_work`, or None for a scallop too small to estimate.

    None below a billionth of the module, where even sampling the tool would not fit
    (`--tolerance 3e-198` was an internal error).
    """
    if tol < 1e-9 * g.module:
        return None
    try:
        return cutting_work(g, tol, positions)
    except (MemoryError, ValueError, OverflowError):
        return None


def _check_work(g, tol: float, positions: int | None) -> None:
    """Refuse a simulation whose first pass alone would exceed :data:`hob.cutting.MAX_UNION_VERTICES`.

    Refused before it starts, with an :class:`InputError` naming the coarsest setting that fits.
    """
    work = _work(g, tol, positions)
    if work is not None and 2 * work[0] * work[1] <= MAX_UNION_VERTICES:
        return
    if work is not None and positions is not None and 2 * 3 * work[1] <= MAX_UNION_VERTICES:
        raise InputError(
            f"--positions must be at most {MAX_UNION_VERTICES // (2 * work[1])} for this gear and tolerance "
            f"(got {positions}; each tool tooth has {work[1]} vertices)."
        )
    what = "far more tool positions and vertices" if work is None else f"{work[0]} tool positions of {work[1]} vertices"
    raise InputError(
        f"--tolerance must be at least {_coarsest_needed(g, tol):.2g} mm for this gear (got {tol:g}: {what}, more than "
        "this machine simulates in a minute)."
    )


def _coarsest_needed(g, tol: float) -> float:
    """Return the finest scallop height (mm, two significant digits, rounded up) whose first pass fits.

    It must fit :data:`hob.cutting.MAX_UNION_VERTICES`; found by bisection on the estimate (positions
    and tool vertices each grow like 1/sqrt(tolerance), but the vertices in steps).
    """

    def fits(t: float) -> bool:
        work = _work(g, t, None)
        return work is not None and 2 * work[0] * work[1] <= MAX_UNION_VERTICES

    lo, hi = np.log(tol), np.log(max(tol, RELATIVE_TOLERANCE[1] * g.module))
    if not fits(np.exp(hi)):
        return float(np.exp(hi))
    for _ in range(40):
        mid = 0.5 * (lo + hi)
        lo, hi = (lo, mid) if fits(np.exp(mid)) else (mid, hi)
    need = float(np.exp(hi))
    digits = 1 - int(np.floor(np.log10(need)))
    up = float(np.ceil(need * 10**digits) / 10**digits)
    return up if fits(up) else need


def _half_angle(tooth: shapely.Polygon, radius: float) -> float:
    ring = shapely.Point(0, 0).buffer(radius, quad_segs=4096).exterior
    arc = ring.intersection(tooth)
    pts = shapely.get_coordinates(arc)
    return float(np.abs(np.arctan2(pts[:, 1], pts[:, 0])).max())


def _whole_gear(tooth: shapely.Polygon, z: int, module: float = 1.0) -> shapely.Polygon:
    """Make the whole simulated gear from tooth 0's sector, as one closed outline.

    The sector's outline without its two radii, turned z times and chained. Failing that, a union of
    the turned sectors, which meet along radial lines only up to rounding, so the slivers between
    them (which took the outline through the centre) are closed by a mitred closing of a millionth of
    the module.
    """
    ring = np.asarray(shapely.geometry.polygon.orient(tooth, 1.0).exterior.coords)[:-1]
    apex = np.flatnonzero(np.hypot(*ring.T) <= 1e-12 * max(1.0, float(np.abs(ring).max())))
    if len(apex) == 1:  # tooth 0's outline without the two radii to the centre, turned z times and chained
        chain = np.roll(ring, -int(apex[0]), axis=0)[1:]  # from the radius at -pi/z round to the one at +pi/z
        turns = 2.0 * np.pi * np.arange(z) / z
        c, s = np.cos(turns)[:, None], np.sin(turns)[:, None]
        pts = np.stack([c * chain[:, 0] - s * chain[:, 1], s * chain[:, 0] + c * chain[:, 1]], axis=-1)
        whole = shapely.Polygon(pts[:, :-1].reshape(-1, 2))  # a chain's end is the next one's start
        if whole.is_valid:
            return whole  # 1000 teeth: 20 ms (the union and closing below took 30 s and 1.5 GB)
    parts = [shapely.affinity.rotate(tooth, 360.0 * k / z, origin=(0, 0)) for k in range(z)]
    eps = 1e-6 * module
    whole = shapely.unary_union(parts).buffer(eps, join_style="mitre").buffer(-eps, join_style="mitre")
    return max(getattr(whole, "geoms", [whole]), key=lambda g: g.area)


def _ccw(poly: shapely.Polygon) -> np.ndarray:
    return np.asarray(shapely.geometry.polygon.orient(poly, 1.0).exterior.coords)[:-1]


def _drawing(g, whole: shapely.Polygon) -> Drawing:
    d = Drawing(mark_size=g.module)
    d.outlines.append(("GEAR_SIMULATED", _ccw(whole)))
    d.outlines.append(("GEAR_ANALYTIC", g.outline(1e-3).points))
    rack = np.vstack([c.evaluate(np.linspace(c.s0, c.s1, 200))[0] for c in g.tool.values()])
    d.polylines.append(("RACK", rack))
    d.outlines.append(
        (
            "HOB_TOOTH",
            TrapezoidalHob(g.module, g.pressure_angle, g.dedendum, g.tip_radius_factor).tooth(
                g.pitch_radius, g.shift, g.nominal_tip_radius + 0.25 * g.module
            )
            * np.array([1.0, 1.0 / np.cos(g.helix_angle)]),
        )
    )
    d.circles += [("PITCH", (0.0, 0.0), g.pitch_radius), ("BASE", (0.0, 0.0), g.base_radius)]
    d.centers.append((0.0, 0.0))
    return d


def _plot(g, res, tolerance: float) -> Figure:
    """Draw the simulated tooth over the analytic one (:func:`hob.plotting.plot_cut`).

    The deviation is magnified along the normal and shown over the radius.
    """
    from hob.plotting import plot_cut

    return plot_cut(g, res, tolerance)

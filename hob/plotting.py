"""Pictures of the hob side in the style of :mod:`rotorcad.plot_style`.

The racks derived from a pair's two rotors (or from a gear, against its basic rack) with their
deviation drawn along the normal, magnified, beside the hob teeth; and the cutting simulation of a
gear tooth against the analytic envelope, with the deviation drawn the same way.
"""

from __future__ import annotations

from typing import Any

import numpy as np
import shapely
from matplotlib.figure import Figure
from matplotlib.lines import Line2D

from hob.rack import ZONE_MARGIN, DerivedRack, hob_tooth, rack_in_contract_frame
from rotorcad import plot_style as ps
from rotorcad.envelope import rack_frame
from rotorcad.gears.involute_gear import InvoluteGear
from rotorcad.geometry import perp_cw
from rotorcad.inverse_rack import contact_of_rack_points
from rotorcad.plot_style import styled
from rotorcad.roles import Side
from rotorcad.screw_rotors import ScrewRotors


def signed_distance(points: np.ndarray, normals: np.ndarray, other: np.ndarray | shapely.Geometry) -> np.ndarray:
    """Measure the distance from each point to a curve, signed by the point's normal.

    Parameters
    ----------
    points : (n, 2) float array, mm
        The points.
    normals : (n, 2) float array
        Unit normals at ``points``.
    other : (m, 2) float array or shapely geometry
        The curve: a polyline, a shapely line or ring, or a polygon (its exterior), mm.

    Returns
    -------
    (n,) float array, mm
        Distance, positive where the nearest point of ``other`` lies on the side of the point's
        normal.
    """
    line = other if isinstance(other, shapely.Geometry) else shapely.LineString(np.asarray(other, dtype=float))
    if isinstance(line, shapely.Polygon):
        line = line.exterior
    points = np.asarray(points, dtype=float).reshape(-1, 2)
    if not len(points):
        return np.zeros(0)
    shortest = shapely.shortest_line(shapely.points(points), line)
    nearest = shapely.get_coordinates(shortest).reshape(-1, 2, 2)[:, 1]
    gap = nearest - points
    d = np.hypot(*gap.T)
    side = np.einsum("ij,ij->i", gap, normals)
    return np.where(side >= 0, d, -d)


def _upward_normals(tangents: np.ndarray, points: np.ndarray) -> np.ndarray:
    """Return the normals of a rack chain (tangent turned clockwise), all flipped if need be.

    They are flipped together so that the highest point's normal points to +y (away from the
    profile's centre).
    """
    n = perp_cw(np.asarray(tangents, dtype=float))
    return n if n[int(np.argmax(points[:, 1])), 1] >= 0 else -n


def rotor_rack_comparison(rotors: ScrewRotors, racks: dict[str, DerivedRack]) -> dict[str, Any]:
    """Compare the female's rack with the male's (transverse section, CONTRACT.md rack frame).

    Parameters
    ----------
    rotors : ScrewRotors
        The pair.
    racks : dict of DerivedRack
        Keyed by :class:`rotorcad.roles.Side` (or its text, "male" and "female"), each from
        :func:`rotorcad.inverse_rack.rotor_rack`.

    Returns
    -------
    dict
        ``reference`` (n, 2) the male rack's points (mm) and ``normals`` (n, 2); ``deviation`` (n,)
        the signed distance (mm) of the female rack (its neighbouring periods too) from each, NaN
        where the contact lies off the contact zone (as :func:`hob.rack.rack_deviation` judges);
        ``compared`` the female rack's points; ``names`` of the two racks; ``period`` (mm).
    """
    pair = rotors.pair
    male = racks[Side.MALE]
    pts = rack_in_contract_frame(male, Side.MALE)
    other = rack_in_contract_frame(racks[Side.FEMALE], Side.FEMALE)
    shift = np.array([pair.rack_period, 0.0])
    contact, _ = contact_of_rack_points(pair.male_pitch_radius, pts, male.tangents)
    margin = ZONE_MARGIN * pair.center_distance  # the contact zone, as rack_deviation judges it
    inside = (np.hypot(*contact.T) <= pair.male_tip_radius - margin) & (
        np.hypot(contact[:, 0] - pair.center_distance, contact[:, 1]) <= pair.female_tip_radius - margin
    )
    normals = _upward_normals(male.tangents, pts)
    lines = shapely.MultiLineString([other - shift, other, other + shift])
    d = signed_distance(pts, normals, lines)
    return {
        "reference": pts,
        "normals": normals,
        "deviation": np.where(inside, d, np.nan),
        "compared": other,
        "names": ("rack from the male", "rack from the female"),
        "period": pair.rack_period,
    }


def gear_rack_comparison(gear: InvoluteGear, rack: DerivedRack) -> dict[str, Any]:
    """Compare the rack derived from a gear with the basic-rack tool it was cut with (transverse section).

    Parameters
    ----------
    gear : InvoluteGear
        The gear (its tool).
    rack : DerivedRack
        The rack derived from the gear.

    Returns
    -------
    dict
        ``reference`` (n, 2) the derived rack's points (mm) and ``normals`` (n, 2); ``deviation``
        (n,) their signed distance (mm) from the tool's flanks, on the cutting pieces (involute,
        fillet, root arc) only, NaN elsewhere; ``compared`` the tool tooth; ``names``; ``period``
        (transverse pitch, mm).
    """
    half = np.vstack([c.evaluate(np.linspace(c.s0, c.s1, 2000))[0] for c in gear.tool.values()])
    half = rack_frame(half, gear.pitch_radius)
    pt = np.pi * gear.transverse_module
    tooth = np.vstack([half, (half * [-1.0, 1.0] + [pt, 0.0])[::-1]])
    pts = rack.points
    cutting = np.array([n in ("involute", "fillet", "root arc") for n in rack.names])[rack.piece_index]
    normals = _upward_normals(rack.tangents, pts)
    d = signed_distance(pts, normals, shapely.MultiLineString([tooth, tooth - [pt, 0.0]]))
    return {
        "reference": pts,
        "normals": normals,
        "deviation": np.where(cutting, d, np.nan),
        "compared": tooth,
        "names": ("rack derived from the gear", "ISO 53 basic rack (tool)"),
        "period": pt,
    }


@styled
def plot_hob(
    racks: dict[str, DerivedRack],
    verdicts: dict[str, Any],
    comparison: dict[str, Any],
    clearance: float,
    case: str,
    deviation: float,
) -> Figure:
    """Draw the racks compared and the hob teeth, each with its verdict.

    Two panels: the racks compared in the transverse section with their deviation along the normal,
    magnified (scale stated); the hob teeth in the normal section side by side, each with its
    verdict.

    Parameters
    ----------
    racks : dict of DerivedRack
        ``male`` and ``female``, or ``gear``.
    verdicts : dict of hob.verdict.Verdict
        The verdict on each rack.
    comparison : dict
        From :func:`rotor_rack_comparison` or :func:`gear_rack_comparison`.
    clearance : float, mm
        Hob root clearance over the rack.
    case : str
        What the racks belong to (title).
    deviation : float, mm
        The largest rack deviation the command reports (``rack_deviation``).

    Returns
    -------
    matplotlib.figure.Figure
    """
    if len(racks) > 1:
        fig = ps.new_figure(11.0, 6.6)
        ax, bx = fig.subplots(2, 1)
    else:
        fig = ps.new_figure(13.0, 5.0)
        ax, bx = fig.subplots(1, 2)
    ref, normals, d = comparison["reference"], comparison["normals"], comparison["deviation"]
    period = comparison["period"]
    ok = np.isfinite(d)
    largest = float(np.nanmax(np.abs(d))) if ok.any() else 0.0
    height = float(np.ptp(ref[:, 1]))
    scale = ps.magnification(largest, height, 0.1)
    ax.plot(*ref.T, "-", color=ps.BLUE, lw=1.4, label=comparison["names"][0])
    compared = comparison["compared"]
    for k in (-1, 0, 1):
        ax.plot(
            *(compared + [k * period, 0.0]).T, "--", color=ps.ORANGE, lw=1.2, label=comparison["names"][1] if k == 0 else None
        )
    ax.axhline(0.0, color=ps.PITCH, lw=0.8, ls="-.", label="pitch line")
    handles, _ = ax.get_legend_handles_labels()
    handles += ps.draw_deviation(ax, ref, normals, d, scale, "deviation")
    x0, x1 = float(ref[:, 0].min()), float(ref[:, 0].max())
    y0, y1 = float(ref[:, 1].min()), float(ref[:, 1].max())
    pad = 0.05 * max(x1 - x0, y1 - y0)
    ax.set_xlim(x0 - pad, x1 + pad)
    ax.set_ylim(y0 - pad, y1 + pad)
    ax.set_aspect("equal", adjustable="box")
    ps.scale_bar(ax, scale, max(largest, 1e-7))
    ax.set_xlabel(ps.label("x along the pitch line (transverse section)", "mm"))
    ax.set_ylabel(ps.label("y", "mm"))
    ax.set_title(f"racks compared: largest deviation {deviation * 1e3:.3g} µm (drawn ×{scale:g} along the normal)")
    ps.legend_outside(ax, handles)
    # the hob teeth in the normal section, side by side
    offset = 0.0
    drawn = []
    for (name, rack), colour in zip(racks.items(), (ps.BLUE, ps.ORANGE, ps.GREEN), strict=False):
        pts, tooth = hob_tooth(rack, clearance)
        shift = np.array([offset - pts[:, 0].min(), 0.0])
        pts, tooth = pts + shift, tooth + shift
        v = verdicts[name]
        state = "hobbable" if v.hobbable else "not hobbable"
        bx.fill(*tooth.T, facecolor=colour, alpha=0.25, edgecolor=colour, lw=1.0, label=f"hob tooth from the {name}: {state}")
        bx.plot(*pts.T, "-", color=colour, lw=1.4)
        bx.annotate(
            f"{name}\nα_n,min = {v.normal_pressure_angle_min_deg:.2f}°",
            (float(pts[:, 0].mean()), float(np.mean([pts[:, 1].min(), pts[:, 1].max()]))),
            ha="center",
            va="center",
            fontsize=8,
        )
        drawn.append(tooth)
        offset = float(tooth[:, 0].max()) + 0.15 * float(np.ptp(tooth[:, 0]))
    bx.axhline(0.0, color=ps.PITCH, lw=0.8, ls="-.")
    handles, _ = bx.get_legend_handles_labels()
    handles.append(Line2D([], [], color=ps.PITCH, lw=0.8, ls="-.", label="pitch line"))
    ps.frame(bx, drawn, margin=0.04)
    bx.set_xlabel(ps.label("x along the pitch line (normal section), the teeth side by side", "mm"))
    bx.set_ylabel(ps.label("y", "mm"))
    bx.set_title(f"hob teeth in the normal section, root clearance {clearance:.3g} mm")
    ps.legend_outside(bx, handles)
    verdict = "hobbable" if all(v.hobbable for v in verdicts.values()) else "NOT hobbable"
    beta = np.degrees(next(iter(racks.values())).helix_angle)
    ps.title(fig, f"rack and hob of {case}: {verdict}", f"helix angle at the pitch cylinder β = {beta:.3f}°")
    return fig


def cut_deviation(gear: InvoluteGear, result: Any, tolerance: float) -> dict[str, np.ndarray]:
    """Measure the simulated tooth against the analytic one.

    Parameters
    ----------
    gear : InvoluteGear
        The gear that was cut.
    result : hob.cutting.CutResult
        The simulation.
    tolerance : float, mm
        The scallop height asked for (the profile is sampled to a quarter of it, at most 0.1 µm).

    Returns
    -------
    dict
        ``points`` (n, 2) of the analytic tooth profile inside the tooth sector (away from its
        straight cut edges, mm), their outward ``normals`` (n, 2), segment ``names`` (n,) and the
        signed ``deviation`` (n,) of the simulated boundary (mm; positive: material left standing).
    """
    prof = gear.tooth_profile(min(tolerance / 4.0, 1e-4))  # sampled as hob.cutting measures it
    pts, normals = prof.points, prof.normals
    names = np.array([prof.segments[i].name for i in prof.segment_index])
    keep = np.abs(np.arctan2(pts[:, 1], pts[:, 0])) <= 0.98 * np.pi / gear.teeth
    pts, normals, names = pts[keep], normals[keep], names[keep]
    return {"points": pts, "normals": normals, "names": names, "deviation": signed_distance(pts, normals, result.tooth)}


@styled
def plot_cut(gear: InvoluteGear, result: Any, tolerance: float) -> Figure:
    """Draw the simulated tooth over the analytic one with the deviation along the normal, magnified.

    And the deviation along the profile over the radius.

    Parameters
    ----------
    gear : InvoluteGear
        The gear that was cut.
    result : hob.cutting.CutResult
        The simulation.
    tolerance : float, mm
        The scallop height asked for.

    Returns
    -------
    matplotlib.figure.Figure
    """
    dev = cut_deviation(gear, result, tolerance)
    pts, d = dev["points"], dev["deviation"]
    fig = ps.new_figure(12.0, 5.6)
    ax, bx = fig.subplots(1, 2, width_ratios=[1.0, 1.1])
    ax.plot(*pts.T, "-", color=ps.BLACK, lw=1.3, label="analytic envelope (reference)")
    sim = np.asarray(result.tooth.exterior.coords)
    r_sim = np.hypot(*sim.T)
    sim = np.where((r_sim > 0.5 * gear.root_radius)[:, None], sim, np.nan)  # the sector's sides, not the profile
    ax.plot(*sim.T, "--", color=ps.VERMILLION, lw=1.0, label=f"simulated ({result.positions} tool positions)")
    largest = float(np.nanmax(np.abs(d))) if len(d) else 0.0
    scale = ps.magnification(largest, gear.tip_radius - gear.root_radius, 0.15)
    handles, _ = ax.get_legend_handles_labels()
    handles += ps.draw_deviation(ax, pts, dev["normals"], d, scale, "deviation", every=2)
    half = np.pi / gear.teeth
    th = np.linspace(-half, half, 200)
    for r, style, colour, name in (
        (gear.base_radius, ":", ps.GREY, "base circle"),
        (gear.pitch_radius, "--", ps.PITCH, "pitch circle"),
        (gear.form_radius, "-.", ps.BLUE, "form circle (undercut point)" if gear.undercut else "form circle"),
    ):
        line = ax.plot(r * np.cos(th), r * np.sin(th), style, color=colour, lw=0.8, label=name)[0]
        handles.append(line)
    ps.frame(ax, [pts, pts + (scale * np.nan_to_num(d))[:, None] * dev["normals"]], margin=0.05)
    ps.scale_bar(ax, scale, max(largest, 1e-7))
    ax.set_xlabel(ps.label("x (gear frame, tooth on +x)", "mm"))
    ax.set_ylabel(ps.label("y", "mm"))
    ax.set_title("tooth 0: simulated against analytic")
    ps.legend_below(ax, handles=handles, ncol=2)
    r = np.hypot(*pts.T)
    upper = pts[:, 1] >= 0
    names = dev["names"]
    colours = {}
    for side, marker in ((upper, "-"), (~upper, "--")):
        for name in dict.fromkeys(names):
            sel = side & (names == name)
            if not sel.any():
                continue
            colour = colours.setdefault(name, ps.CYCLE[len(colours) % len(ps.CYCLE)])
            order = np.argsort(r[sel])
            bx.plot(r[sel][order], 1e3 * d[sel][order], marker, color=colour, lw=1.2)
    for sign in (-1.0, 1.0):
        bx.axhline(sign * tolerance * 1e3, color=ps.GREY, lw=0.9, ls=":")
    bx.axhline(0.0, color=ps.GREY, lw=0.6)
    bx.axvline(gear.form_radius, color=ps.BLUE, lw=0.8, ls="-.")
    legend = [Line2D([], [], color=c, lw=1.2, label=n) for n, c in colours.items()]
    legend += [
        Line2D([], [], color=ps.GREY, ls="-", label="upper flank (y > 0)"),
        Line2D([], [], color=ps.GREY, ls="--", label="lower flank (y < 0)"),
        Line2D([], [], color=ps.GREY, lw=0.9, ls=":", label=f"scallop tolerance ±{tolerance * 1e3:g} µm"),
        Line2D([], [], color=ps.BLUE, ls="-.", label=f"form radius {gear.form_radius:.4g} mm"),
    ]
    bx.set_xlabel(ps.label("radius r", "mm"))
    bx.set_ylabel(ps.label("deviation along the normal (+: material left)", "µm"))
    bx.set_title("deviation of the simulated profile from the envelope")
    ps.legend_below(bx, handles=legend, ncol=2)
    ps.title(
        fig,
        f"hob cutting simulation of gear z = {gear.teeth}, m = {gear.module:g} mm, x = {gear.shift:g}",
        f"α = {np.degrees(gear.pressure_angle):g}°, tool addendum h_a0* = {gear.dedendum:g}, ρ_a0* = {gear.tip_radius_factor:g}; "
        f"largest deviation {result.max_deviation * 1e3:.3g} µm, scallop tolerance {tolerance * 1e3:g} µm"
        + ("; undercut" if gear.undercut else ""),
    )
    return fig

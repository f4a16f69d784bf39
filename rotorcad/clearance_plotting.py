"""Pictures of the meshing clearance (Wu & Chi) in the style of :mod:`rotorcad.plot_style`.

The datum rack with the clearance drawn along its normal, magnified (Wu & Chi Fig. 4f); the
clearance along the rack and over the male rotation (Fig. 9), interference (negative clearance)
shaded; and the clearance band on the 3D contact line.
"""

from __future__ import annotations

import numpy as np
from matplotlib.figure import Figure
from matplotlib.lines import Line2D
from matplotlib.patches import Patch

from rotorcad import plot_style as ps
from rotorcad.clearance import ClearanceZone, MeshingClearance, ThermalState
from rotorcad.plot_style import styled


def clearance_state(mc: MeshingClearance, thermal: ThermalState | None, reference_temperature: float = 20.0) -> str:
    """Describe how the pair is evaluated, for a title.

    Cold or hot with its temperatures, and the flank the racks are brought into contact on.

    Parameters
    ----------
    mc : MeshingClearance
        The evaluation (its contact flank).
    thermal : ThermalState, optional
        The working temperatures (None: cold, as measured).
    reference_temperature : float, °C
        Temperature of the points.

    Returns
    -------
    str
    """
    contact = {"driving": "in contact on the driving flank", "sealing": "in contact on the sealing flank"}.get(
        mc.contact, "as the points were given"
    )
    if thermal is None:
        state = f"cold (points at {reference_temperature:g} °C)"
    else:
        housing = thermal.rotor_temperature if thermal.housing_temperature is None else thermal.housing_temperature
        state = (
            f"hot: suction {thermal.suction_temperature:g} °C, discharge {thermal.discharge_temperature:g} °C, "
            f"rotors {thermal.rotor_temperature:g} °C, housing {housing:g} °C (points at {thermal.reference_temperature:g} °C)"
        )
    return f"{state}; racks {contact}"


def _band_normals(mc: MeshingClearance, contact: np.ndarray) -> np.ndarray:
    """Return the unit normals (n, 3) of the helical flank at the contact points.

    Transverse from the rack, axial from the helicoid (as the band of :class:`MeshingClearance` is
    built).
    """
    tan = mc.female_rack.tangents
    n_t = np.stack([-tan[:, 0], tan[:, 1]], axis=1)
    n_z = 2 * np.pi * (contact[:, 1] * n_t[:, 0] - contact[:, 0] * n_t[:, 1]) / mc.pair.lead
    normal = np.column_stack([n_t, n_z])
    return normal / np.linalg.norm(normal, axis=1, keepdims=True)


@styled
def plot_clearance(mc: MeshingClearance, state: str) -> Figure:
    """Draw the meshing clearance of a pair in four panels (Wu & Chi Figs. 4f and 9).

    The datum rack with the clearance magnified along its normal; the 3D contact line with its
    clearance band (magnified); the clearance along the rack; the clearance over the male rotation
    angle. Interference (negative clearance) is vermillion and shaded.

    Parameters
    ----------
    mc : MeshingClearance
        The evaluated pair.
    state : str
        Cold or hot, temperatures and contact flank (:func:`clearance_state`), for the title.

    Returns
    -------
    matplotlib.figure.Figure
    """
    pts, delta, n = mc.datum_rack, mc.clearance, mc.datum_normals
    ok = np.isfinite(delta)
    dist = mc.distribution()
    inside = dist["in_contact"] > 0
    contact_zone = mc.contact_zone
    worst = float(np.nanmin(delta[contact_zone])) if contact_zone.any() else float(np.nanmin(delta))
    largest = float(np.nanmax(np.abs(delta))) if ok.any() else 0.0
    fig = ps.new_figure(13.0, 9.0)
    grid = fig.add_gridspec(2, 2)
    ax = fig.add_subplot(grid[0, 0])
    scale = ps.magnification(largest, float(np.ptp(pts[:, 1])), 0.1)
    ax.plot(*pts.T, "-", color=ps.BLACK, lw=1.0, label="female normal rack (datum)")
    handles, _ = ax.get_legend_handles_labels()
    handles += ps.draw_deviation(ax, pts, n, np.where(ok, delta, np.nan), scale, "clearance", every=3)
    ps.frame(ax, [pts, pts + (scale * np.nan_to_num(delta))[:, None] * n], margin=0.04)
    ps.scale_bar(ax, scale, max(largest, 1e-6))
    ax.set_xlabel(ps.label("x along the pitch line (normal section)", "mm"))
    ax.set_ylabel(ps.label("y", "mm"))
    ax.set_title(f"normal clearance drawn ×{scale:g} along the datum rack's normal")
    ps.legend_below(ax, handles=handles, ncol=2, bbox_to_anchor=(0.5, -0.2))

    cx = fig.add_subplot(grid[0, 1], projection="3d")
    contact = np.column_stack([dist["contact_x"], dist["contact_y"]])
    line = np.column_stack([contact, dist["z"]])
    normal = _band_normals(mc, contact)
    band_scale = ps.magnification(largest, mc.pair.length, 0.04, most=1e3)
    offset = line + (band_scale * np.nan_to_num(delta))[:, None] * normal
    use = inside & np.isfinite(delta) & np.all(np.isfinite(line), axis=1)
    seg = np.nonzero(use[:-1] & use[1:])[0]
    step = max(1, len(seg) // 600)
    seg = seg[::step]
    from mpl_toolkits.mplot3d.art3d import Poly3DCollection

    quads = [
        np.array([line[i], line[min(i + step, len(line) - 1)], offset[min(i + step, len(line) - 1)], offset[i]]) for i in seg
    ]
    colours = [ps.SKY_BLUE if delta[i] >= 0 else ps.VERMILLION for i in seg]
    if quads:
        cx.add_collection3d(Poly3DCollection(quads, facecolors=colours, edgecolors="none", alpha=0.85))
    ln = np.where(use[:, None], line, np.nan)
    cx.plot(ln[:, 0], ln[:, 1], ln[:, 2], "-", color=ps.BLACK, lw=0.9)
    if use.any():
        lo, hi = line[use].min(axis=0), line[use].max(axis=0)
        cx.set_xlim(lo[0], hi[0])
        cx.set_ylim(lo[1], hi[1])
        cx.set_zlim(lo[2], hi[2])
    cx.set_xlabel(ps.label("x", "mm"))
    cx.set_ylabel(ps.label("y", "mm"))
    cx.set_zlabel(ps.label("z (suction → discharge)", "mm"))
    cx.set_title(f"clearance band on the contact line, width ×{band_scale:g}")
    cx.legend(
        handles=[
            Line2D([], [], color=ps.BLACK, lw=0.9, label="contact line (sealing line)"),
            Patch(color=ps.SKY_BLUE, label=f"clearance > 0 (×{band_scale:g})"),
            Patch(color=ps.VERMILLION, label=f"interference (×{band_scale:g})"),
        ],
        loc="upper left",
        bbox_to_anchor=(0.0, 1.0),
        fontsize=7,
    )

    bx = fig.add_subplot(grid[1, 0])
    length = np.concatenate([[0.0], np.cumsum(np.hypot(*np.diff(pts, axis=0).T))])
    um = 1e3 * delta
    zone = mc.zones
    on = zone == ClearanceZone.CONTACT
    gap_um = 1e3 * mc.gap
    bx.plot(length, np.where(on, um, np.nan), "-", color=ps.BLUE, lw=1.1, label="normal clearance δ (contact zone)")
    for code, colour, text, value in (
        (ClearanceZone.GAP, ps.ORANGE, "gap where the male never touches (root below a sharp tip)", gap_um),
        (ClearanceZone.CORNER, ps.GREEN, "gap of a sharp female corner's path", gap_um),
        (ClearanceZone.UNRESOLVED, ps.PURPLE, "δ the points cannot resolve (beside a rounded-over corner)", um),
    ):
        if (zone == code).any():
            bx.plot(length, np.where(zone == code, value, np.nan), "-", color=colour, lw=1.1, label=text)
    bx.fill_between(length, um, 0.0, where=ok & (um < 0), color=ps.VERMILLION, alpha=0.35, lw=0, label="interference (δ < 0)")
    bx.axhline(0.0, color=ps.BLACK, lw=0.6)
    bx.set_xlabel(ps.label("arc length along the datum rack", "mm"))
    bx.set_ylabel(ps.label("normal clearance δ", "µm"))
    bx.set_title("clearance along the rack")
    ps.legend_below(bx, ncol=2)

    dx = fig.add_subplot(grid[1, 1])
    angle = dist["male_angle_deg"]
    c_um = 1e3 * dist["clearance"]
    dx.plot(angle[on], c_um[on], ".", color=ps.BLUE, ms=1.8, label="normal clearance δ (contact zone)")
    for code, colour, text, value in (
        (ClearanceZone.GAP, ps.ORANGE, "gap, never touched", gap_um),
        (ClearanceZone.CORNER, ps.GREEN, "corner path gap", gap_um),
        (ClearanceZone.UNRESOLVED, ps.PURPLE, "δ, unresolved", c_um),
    ):
        if (zone == code).any():
            dx.plot(angle[zone == code], value[zone == code], ".", color=colour, ms=1.8, label=text)
    neg = on & (c_um < 0)
    if neg.any():
        dx.plot(angle[neg], c_um[neg], ".", color=ps.VERMILLION, ms=2.2, label="interference (δ < 0)")
        dx.axhspan(min(float(c_um[neg].min()) * 1.05, 0.0), 0.0, color=ps.VERMILLION, alpha=0.12, lw=0)
    dx.axhline(0.0, color=ps.BLACK, lw=0.6)
    dx.set_xlabel(ps.label("male angle φ of the contact, to go until a male tip's middle is on O1O2 (the rotation runs →)", "°"))
    dx.invert_xaxis()  # φ falls as the male turns (the one angle convention, as `rotor` counts it)
    dx.set_ylabel(ps.label("normal clearance δ", "µm"))
    dx.set_title("clearance over the rotation (Wu & Chi Fig. 9)")
    ps.legend_below(dx, ncol=2, markerscale=4)
    if worst < -max(2e-3, mc.accuracy):  # beyond the stated accuracy (rotorcad clearance: interference)
        for axis in (bx, dx):
            axis.annotate(
                f"INTERFERENCE: δ down to {worst * 1e3:.1f} µm",
                xy=(0.01, 0.03),
                xycoords="axes fraction",
                color=ps.VERMILLION,
                fontsize=8,
                fontweight="bold",
            )
    pair = mc.pair
    s = mc.summary()
    ps.title(
        fig,
        f"meshing clearance of the {pair.male_teeth}/{pair.female_teeth} pair from points, {state}",
        f"a = {pair.center_distance:.6g} mm, h1 = {pair.lead:.6g} mm, L = {pair.length:.6g} mm, "
        f"helix angle {s['helix_angle_deg']:.3f}°; "
        f"δ on the contact zone from {s['min_normal_clearance'] * 1e3:.1f} to {s['max_normal_clearance'] * 1e3:.1f} µm "
        f"(accuracy ±{s['accuracy'] * 1e3:.1f} µm), "
        f"equal clearance {s['equal_clearance'] * 1e3:.1f} µm",
    )
    return fig

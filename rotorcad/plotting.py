"""Pictures of gears (matplotlib, no global pyplot state: each function returns a Figure)."""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from rotorcad import plot_style as ps
from rotorcad.gears.involute_gear import InvoluteGear
from rotorcad.gears.pair import GearPair
from rotorcad.geometry import rotate
from rotorcad.plot_style import styled

if TYPE_CHECKING:
    from matplotlib.figure import Figure


def mate_in_mesh(pair: GearPair, points: np.ndarray) -> np.ndarray:
    """Place mate outline points in mesh: turned so a tooth space faces the gear's tooth 0, centred at (a_w, 0).

    Parameters
    ----------
    pair : GearPair
        The pair (mate tooth count and working centre distance a_w).
    points : (n, 2) float array, mm
        The mate's outline in its own frame.

    Returns
    -------
    (n, 2) float array, mm
    """
    z2 = pair.mate.teeth
    return rotate(points, np.pi + np.pi / z2) + np.array([pair.working_center_distance, 0.0])


def line_of_action(pair: GearPair) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Return the ends of the line of action on the base circles and the working pitch point.

    The upper flanks of the gear's tooth 0 are in contact (ISO 21771: the line of action is tangent
    to both base circles at the working pressure angle).

    Parameters
    ----------
    pair : GearPair
        The pair.

    Returns
    -------
    t1, t2, c : (2,) float arrays, mm
        Tangency points T1 (gear) and T2 (mate) and the pitch point C.
    """
    aw = pair.working_pressure_angle
    a = pair.working_center_distance
    rb1, rb2 = pair.gear.base_radius, pair.mate.base_radius
    t1 = rb1 * np.array([np.cos(aw), -np.sin(aw)])
    t2 = np.array([a, 0.0]) + rb2 * np.array([-np.cos(aw), np.sin(aw)])
    c = np.array([rb1 / np.cos(aw), 0.0])
    return t1, t2, c


def path_of_contact(pair: GearPair) -> np.ndarray:
    """Return the end points of the path of contact on the line of action.

    Where the flanks meet between the tip circles and the usable involutes
    (:meth:`GearPair.contact_interval`).

    Parameters
    ----------
    pair : GearPair
        The pair.

    Returns
    -------
    (2, 2) float array, mm
        Start and end point.
    """
    t1, t2, _ = line_of_action(pair)
    lo1, hi1, lo2, hi2 = pair.contact_interval()
    u = (t2 - t1) / np.hypot(*(t2 - t1))
    return np.array([t1 + max(lo1, lo2) * u, t1 + min(hi1, hi2) * u])


@styled
def plot_gears(gear: InvoluteGear, pair: GearPair | None = None) -> Figure:
    """Draw the gear (and its mate in mesh) with pitch, base and tip circles and the line of action.

    With a pair also the path of contact and the pitch point C; the title states the gear data, the
    legend stands beside the drawing.

    Parameters
    ----------
    gear : InvoluteGear
        The gear (z1).
    pair : GearPair, optional
        The gear with its mate.

    Returns
    -------
    matplotlib.figure.Figure
    """
    from matplotlib.lines import Line2D

    ra1 = gear.tip_radius
    if pair is None:
        fig = ps.new_figure(7.5, 5.6)
    else:
        a = pair.working_center_distance
        ra2 = pair.mate.tip_radius
        aspect = (ra1 + a + ra2) / (2 * max(ra1, ra2))
        fig = ps.new_figure(min(3.0 + 5.0 * aspect, 13.0), 5.6)
    ax = fig.add_subplot()
    pts = gear.outline().points
    ax.fill(*pts.T, facecolor=ps.MALE_FILL, edgecolor=ps.MALE_EDGE, lw=0.7, label=f"gear z1 = {gear.teeth}")
    circles = [((0.0, 0.0), gear.pitch_radius, "--", ps.PITCH), ((0.0, 0.0), gear.base_radius, ":", ps.GREY)]
    seen = [pts]
    if pair is not None:
        mp = mate_in_mesh(pair, pair.mate.outline().points)
        ax.fill(*mp.T, facecolor=ps.FEMALE_FILL, edgecolor=ps.FEMALE_EDGE, lw=0.7, label=f"mate z2 = {pair.mate.teeth}")
        seen.append(mp)
        o2 = (pair.working_center_distance, 0.0)
        circles += [(o2, pair.mate.pitch_radius, "--", ps.PITCH), (o2, pair.mate.base_radius, ":", ps.GREY)]
        t1, t2, c = line_of_action(pair)
        ax.plot(*np.array([t1, t2]).T, "-", color=ps.PURPLE, lw=0.9, label="line of action T1T2")
        ax.plot(*path_of_contact(pair).T, "-", color=ps.BLACK, lw=2.4, solid_capstyle="butt", label="path of contact")
        ax.plot(*np.array([t1, t2]).T, "o", color=ps.PURPLE, ms=3)
        ax.plot(*c, "o", color=ps.BLACK, ms=4)
        ax.annotate("C", c, textcoords="offset points", xytext=(5, 5), fontsize=8)
    for centre, r, style, colour in circles:
        ax.plot(*ps.circle_points(centre, r).T, style, color=colour, lw=0.8)
    handles, _ = ax.get_legend_handles_labels()
    handles += [
        Line2D([], [], ls="--", color=ps.PITCH, lw=0.8, label="pitch circles"),
        Line2D([], [], ls=":", color=ps.GREY, lw=0.8, label="base circles"),
    ]
    ps.frame(ax, seen, margin=0.03)
    ax.set_xlabel(ps.label("x", "mm"))
    ax.set_ylabel(ps.label("y", "mm"))
    ps.legend_outside(ax, handles)
    ps.title(fig, _gear_case(gear, pair), _gear_settings(gear, pair))
    return fig


def _gear_case(gear: InvoluteGear, pair: GearPair | None) -> str:
    return f"involute gear z1 = {gear.teeth}" + (f" with mate z2 = {pair.mate.teeth}" if pair is not None else "")


def _gear_settings(gear: InvoluteGear, pair: GearPair | None) -> str:
    text = (
        f"m = {gear.module:g} mm, α = {np.degrees(gear.pressure_angle):g}°, β = {np.degrees(gear.helix_angle):g}°, "
        f"x1 = {gear.shift:g}"
    )
    if pair is not None:
        text += (
            f", x2 = {pair.mate.shift:.4g}; a_w = {pair.working_center_distance:.4f} mm, "
            f"α_wt = {np.degrees(pair.working_pressure_angle):.3f}°, ε_α = {pair.contact_ratio:.3f}"
        )
    else:
        text += f"; d = {2 * gear.pitch_radius:.4g} mm, d_a = {2 * gear.tip_radius:.4g} mm" + (
            ", undercut" if gear.undercut else ""
        )
    return text

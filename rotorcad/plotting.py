"""Pictures of gears (matplotlib, no global pyplot state: each function returns a Figure)."""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from rotorcad.gear import GearPair, InvoluteGear
from rotorcad.geometry import rotate

if TYPE_CHECKING:
    from matplotlib.figure import Figure


def mate_in_mesh(pair: GearPair, points: np.ndarray) -> np.ndarray:
    """Mate outline points placed in mesh: turned so a tooth space faces the gear's tooth 0,
    centred at (a_w, 0)."""
    z2 = pair.mate.teeth
    return rotate(points, np.pi + np.pi / z2) + np.array([pair.working_center_distance, 0.0])


def line_of_action(pair: GearPair) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Tangency points T1, T2 of the line of action on the base circles and the working pitch
    point C (upper flanks of the gear's tooth 0 in contact)."""
    aw = pair.working_pressure_angle
    a = pair.working_center_distance
    rb1, rb2 = pair.gear.base_radius, pair.mate.base_radius
    t1 = rb1 * np.array([np.cos(aw), -np.sin(aw)])
    t2 = np.array([a, 0.0]) + rb2 * np.array([-np.cos(aw), np.sin(aw)])
    c = np.array([rb1 / np.cos(aw), 0.0])
    return t1, t2, c


def plot_gears(gear: InvoluteGear, pair: GearPair | None = None) -> Figure:
    """The gear (and its mate in mesh) with pitch, base, tip circles and the line of action."""
    from matplotlib.figure import Figure  # matplotlib only when a picture is drawn

    fig = Figure(figsize=(8, 6), dpi=120)
    ax = fig.add_subplot()
    pts = gear.outline().points
    ax.fill(*pts.T, facecolor="#9ecae1", edgecolor="#08519c", lw=0.6, label=f"gear z={gear.teeth}")
    circles = [((0.0, 0.0), gear.pitch_radius, "--", "#31a354"), ((0.0, 0.0), gear.base_radius, ":", "#636363")]
    if pair is not None:
        mp = mate_in_mesh(pair, pair.mate.outline().points)
        ax.fill(*mp.T, facecolor="#fcbba1", edgecolor="#a50f15", lw=0.6, alpha=0.9, label=f"mate z={pair.mate.teeth}")
        o2 = (pair.working_center_distance, 0.0)
        circles += [(o2, pair.mate.pitch_radius, "--", "#31a354"), (o2, pair.mate.base_radius, ":", "#636363")]
        t1, t2, c = line_of_action(pair)
        ax.plot(*np.array([t1, t2]).T, "-", color="#756bb1", lw=1.0, label="line of action")
        ax.plot(*c, "o", color="k", ms=3)
        ax.annotate("C", c, textcoords="offset points", xytext=(4, 4))
    for centre, r, style, colour in circles:
        th = np.linspace(0.0, 2.0 * np.pi, 721)
        ax.plot(centre[0] + r * np.cos(th), centre[1] + r * np.sin(th), style, color=colour, lw=0.7)
    ax.plot([], [], "--", color="#31a354", lw=0.7, label="pitch circles")
    ax.plot([], [], ":", color="#636363", lw=0.7, label="base circles")
    ax.set_aspect("equal")
    ax.set_xlabel("x [mm]")
    ax.set_ylabel("y [mm]")
    title = f"m={gear.module:g} mm, alpha={np.degrees(gear.pressure_angle):g} deg"
    if pair is not None:
        title += f", a_w={pair.working_center_distance:.4f} mm, eps_alpha={pair.contact_ratio:.3f}"
    ax.set_title(title, fontsize=9)
    ax.legend(loc="upper right", fontsize=7)
    ax.grid(True, lw=0.3)
    return fig

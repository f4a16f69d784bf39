"""Picture of an internal gear (ring with its toothed bore) and its pinion in mesh (matplotlib, returns a Figure)."""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from rotorcad import plot_style as ps
from rotorcad.plot_style import styled

if TYPE_CHECKING:
    from matplotlib.figure import Figure

    from rotorcad.gears.internal_gear import InternalGear
    from rotorcad.gears.internal_pair import InternalPair


@styled
def plot_internal(ring: InternalGear, pair: InternalPair | None = None) -> Figure:
    """Draw the ring (outer circle and toothed bore), its pitch and base circles, and the pinion in mesh.

    Parameters
    ----------
    ring : InternalGear
        The internal gear, about the origin.
    pair : InternalPair, optional
        With the pinion about (a_w, 0) and the line of action between the base tangency points.

    Returns
    -------
    matplotlib.figure.Figure
    """
    from matplotlib.patches import PathPatch
    from matplotlib.path import Path

    fig = ps.new_figure(7.5, 6.4)
    ax = fig.add_subplot()
    bore = ring.outline().points
    outer = ps.circle_points((0.0, 0.0), ring.outer_radius)[::-1]  # clockwise: the ring's material between
    verts = np.vstack([outer, outer[:1], bore, bore[:1]])
    codes = np.full(len(verts), Path.LINETO)
    codes[0], codes[len(outer)] = Path.MOVETO, Path.CLOSEPOLY
    codes[len(outer) + 1], codes[-1] = Path.MOVETO, Path.CLOSEPOLY
    patch = PathPatch(Path(verts, codes), facecolor=ps.FEMALE_FILL, edgecolor=ps.FEMALE_EDGE, lw=0.7)
    ax.add_patch(patch)
    ax.plot([], [], color=ps.FEMALE_EDGE, lw=4, label=f"internal gear z2 = {ring.teeth}")
    seen = [outer]
    for radius, style, colour, name in ((ring.pitch_radius, "--", ps.PITCH, "pitch"), (ring.base_radius, ":", ps.GREY, "base")):
        ax.plot(*ps.circle_points((0.0, 0.0), radius).T, style, color=colour, lw=0.7, label=f"{name} circles")
    if pair is not None:
        a = pair.working_center_distance
        pts = pair.pinion.outline().points + np.array([a, 0.0])
        ax.fill(*pts.T, facecolor=ps.MALE_FILL, edgecolor=ps.MALE_EDGE, lw=0.7, label=f"pinion z1 = {pair.pinion.teeth}")
        ax.plot(*ps.circle_points((a, 0.0), pair.pinion.pitch_radius).T, "--", color=ps.PITCH, lw=0.7)
        aw = pair.working_pressure_angle
        u = np.array([np.cos(aw), np.sin(aw)])
        t2, t1 = ring.base_radius * u, np.array([a, 0.0]) + pair.pinion.base_radius * u
        ax.plot(*np.array([t1, t2]).T, "-", color=ps.PURPLE, lw=0.9, label="line of action T1T2")
        seen.append(pts)
    ps.frame(ax, seen)
    ps.legend_outside(ax)
    case = f"internal gear z2 = {ring.teeth}, m = {ring.module:g} mm, x2 = {ring.shift:g}, cutter z0 = {ring.cutter.teeth}"
    ps.title(fig, case + (f", pinion z1 = {pair.pinion.teeth}" if pair is not None else ""))
    return fig

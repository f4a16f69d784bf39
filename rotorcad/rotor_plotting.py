"""Pictures of a screw-rotor pair: the pair in mesh with its meshline, defects and blow-hole, and
sliding velocity and slip over the rotation angle in the manner of Rinder's Figs. 10-13."""

from __future__ import annotations

import numpy as np
from matplotlib.figure import Figure

from rotorcad.meshing import MeshingAnalysis

MARKERS = {"cusp": ("v", "#d62728"), "jamming": ("s", "#9467bd"), "slipping": ("D", "#ff7f0e")}


def _circle(ax, centre, r, style, colour, lw=0.7):
    th = np.linspace(0.0, 2.0 * np.pi, 721)
    ax.plot(centre[0] + r * np.cos(th), centre[1] + r * np.sin(th), style, color=colour, lw=lw)


def plot_pair(analysis: MeshingAnalysis, clearance: float = 0.0) -> Figure:
    """Male and female in mesh at male angle 0, pitch circles, housing bores, meshline with the
    flagged points, the housing cusp and the (projected) blow-hole."""
    rotors = analysis.rotors
    pair = rotors.pair
    a = pair.center_distance
    fig = Figure(figsize=(9, 7), dpi=120)
    ax = fig.add_subplot()
    male, female = analysis.sections
    ax.fill(*male.exterior.xy, facecolor="#9ecae1", edgecolor="#08519c", lw=0.6, label=f"male z1={pair.male_teeth}")
    fx, fy = female.exterior.xy
    ax.fill(np.asarray(fx) + a, fy, facecolor="#fcbba1", edgecolor="#a50f15", lw=0.6, label=f"female z2={pair.female_teeth}")
    _circle(ax, (0, 0), pair.male_pitch_radius, "--", "#31a354")
    _circle(ax, (a, 0), pair.female_pitch_radius, "--", "#31a354")
    _circle(ax, (0, 0), pair.male_tip_radius + clearance, "-", "#444444", 0.9)
    _circle(ax, (a, 0), pair.female_tip_radius + clearance, "-", "#444444", 0.9)
    ax.plot([], [], "--", color="#31a354", lw=0.7, label="pitch circles")
    ax.plot([], [], "-", color="#444444", lw=0.9, label="housing bores")
    for k, piece in enumerate(analysis.pieces):
        ax.plot(*piece.points.T, "-", color="k", lw=1.4, label="meshline" if k == 0 else None)
    for kind, (marker, colour) in MARKERS.items():
        pts = [(d.x, d.y) for d in analysis.defects if d.kind == kind]
        if pts:
            ax.plot(*np.array(pts).T, marker, color=colour, ms=6, ls="none", label=kind)
    bh = analysis.blow_hole
    for g in getattr(bh, "geoms", [bh]):
        if hasattr(g, "exterior") and not g.is_empty:
            ax.fill(*g.exterior.xy, color="#e31a1c", alpha=0.7)
    ax.plot(*analysis.cusp, "k*", ms=9, label=f"cusp, blow-hole {analysis.blow_hole_area:.2f} mm²")
    ax.plot(pair.male_pitch_radius, 0.0, "ko", ms=3)
    ax.set_aspect("equal")
    ax.set_xlabel("x [mm]")
    ax.set_ylabel("y [mm]")
    ax.set_title(
        f"{rotors.family} {pair.male_teeth}/{pair.female_teeth}, a = {a:g} mm, meshline "
        + ("closed" if analysis.meshline_closed else "open"),
        fontsize=9,
    )
    ax.legend(loc="upper left", fontsize=7)
    ax.grid(True, lw=0.3)
    return fig


def plot_sliding(analysis: MeshingAnalysis) -> Figure:
    """Sliding velocity v_g (eq. 3) and slip of male and female (eq. 4) over the male rotation
    angle at contact; slip is clipped to +-10 where it runs to infinity (v_t = 0)."""
    k = analysis.kinematics
    ang = k["angle_deg"]
    order = np.argsort(ang)
    fig = Figure(figsize=(9, 7), dpi=120)
    ax1, ax2 = fig.subplots(2, 1, sharex=True)
    ax1.plot(ang[order], np.abs(k["sliding"][order]), ".", ms=2, color="#08519c")
    ax1.set_ylabel("sliding velocity |v_g| [m/s]")
    ax1.set_title(f"{analysis.rotors.family}: sliding and slip at {analysis.speed_rpm:g} rpm (Rinder eqs. 3-4)", fontsize=9)
    ax1.grid(True, lw=0.3)
    ax2.plot(ang[order], np.clip(k["slip_male"][order], -10, 10), ".", ms=2, color="#08519c", label="male slip ζ1")
    ax2.plot(ang[order], np.clip(k["slip_female"][order], -10, 10), ".", ms=2, color="#a50f15", label="female slip ζ2")
    ax2.set_ylabel("slip [-] (clipped to ±10)")
    ax2.set_xlabel("male rotation angle at contact [deg]")
    ax2.legend(fontsize=7)
    ax2.grid(True, lw=0.3)
    return fig

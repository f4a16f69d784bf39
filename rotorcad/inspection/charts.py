"""The charts a gear inspector reads: the profile chart of each flank, and a rotor's deviation along its profile."""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from rotorcad import plot_style as ps

if TYPE_CHECKING:
    from matplotlib.figure import Figure

    from rotorcad.inspection.gear_inspection import GearInspection
    from rotorcad.inspection.rotor_inspection import RotorInspection

MOST_FLANKS = 12
"""Flanks drawn in one profile chart (the first ones by tooth; the JSON has them all)."""


@ps.styled
def profile_chart(result: GearInspection, case: str) -> Figure:
    """Draw the profile chart of each measured flank (ISO 1328-1:2013).

    Parameters
    ----------
    result : GearInspection
        The inspection (:func:`rotorcad.inspection.inspect_gear`).
    case : str
        The title's first line.

    Returns
    -------
    matplotlib.figure.Figure
        One panel per flank: the deviation [µm] across, the roll length [mm] up (start of the
        active profile at the bottom, the tip at the top), the evaluation range L_alpha between
        two grey lines, the mean profile line, and with a tolerance class the band of F_alphaT
        about the middle of the measured deviations over L_alpha; F_alpha, f_falpha, f_Halpha
        written under each panel.
    """
    flanks = result.flanks[:MOST_FLANKS]
    fig = ps.new_figure(max(4.0, 1.9 * len(flanks)), 6.0)
    axes = np.atleast_1d(fig.subplots(1, len(flanks), sharey=True))
    lo, hi = result.nominal.evaluation_range
    tol = result.tolerances
    for ax, f in zip(axes, flanks, strict=True):
        ax.plot(f.deviation * 1e3, f.roll_length, ".", ms=2, color=ps.BLUE)
        xi = np.array([lo, hi])
        ax.plot([f.profile.at(v) * 1e3 for v in xi], xi, color=ps.VERMILLION, lw=1.0)
        for v in xi:
            ax.axhline(v, color=ps.GREY, lw=0.6, ls="--")
        ax.axvline(0.0, color=ps.BLACK, lw=0.8)
        inside = (f.roll_length >= lo) & (f.roll_length <= hi)
        if tol is not None and inside.any():
            mid = 0.5 * (f.deviation[inside].max() + f.deviation[inside].min()) * 1e3
            for side in (-0.5, 0.5):
                ax.plot([mid + side * tol.total_profile * 1e3] * 2, xi, color=ps.GREEN, lw=1.0)
        p = f.profile
        ax.set_title(f"tooth {f.tooth} {f.flank.value}")
        ax.set_xlabel(f"{ps.label('deviation', 'µm')}\nFα {p.total * 1e3:.1f}  ffα {p.form * 1e3:.1f}\nfHα {p.slope * 1e3:+.1f}")
    axes[0].set_ylabel(ps.label("roll length", "mm"))
    settings = f"L_alpha {hi - lo:.3f} mm from roll length {lo:.3f} mm; + more material"
    if len(result.flanks) > len(flanks):
        settings += f"; the first {len(flanks)} of {len(result.flanks)} flanks"
    if tol is not None:
        settings += f"; class {tol.tolerance_class}: F_alphaT {tol.total_profile * 1e3:g} µm (green)"
    ps.title(fig, case, settings)
    return fig


@ps.styled
def rotor_chart(result: RotorInspection, case: str) -> Figure:
    """Draw a rotor's normal deviation along its profile, per flank.

    Parameters
    ----------
    result : RotorInspection
        The inspection (:func:`rotorcad.inspection.rotor_inspection.inspect_rotor`).
    case : str
        The title's first line.

    Returns
    -------
    matplotlib.figure.Figure
        The deviation [µm] over the arc length from the lobe's tip [mm] (+ the left flank), every
        lobe's points together.
    """
    from rotorcad.roles import ToothFlank

    fig = ps.new_figure(8.0, 4.5)
    ax = fig.subplots()
    for side, colour in zip(ToothFlank, (ps.BLUE, ps.ORANGE), strict=True):
        mask = result.flank(side)
        ax.plot(result.along[mask], result.deviation[mask] * 1e3, ".", ms=2, color=colour, label=f"{side.value} flank")
    ax.axhline(0.0, color=ps.BLACK, lw=0.8)
    ax.set_xlabel(ps.label("along the profile from the lobe's tip", "mm"))
    ax.set_ylabel(ps.label("normal deviation (+ more material)", "µm"))
    ps.legend_below(ax, ncol=2)
    ps.title(fig, case, f"rotation {np.degrees(result.rotation):.5f}° (least squares)")
    return fig


__all__ = ["profile_chart", "rotor_chart"]

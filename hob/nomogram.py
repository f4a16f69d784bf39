"""Contact-ratio nomogram in the manner of Kollek & Osiński's Fig. 4.

The transverse contact ratio of two equal gears over the profile shift x and the addendum factor
y, with the undercut limits x_g (theoretical), x'_g (practical) and x''_g (where undercut starts to
shorten the path of contact, from the exact envelope).
"""

from __future__ import annotations

import numpy as np
from matplotlib.figure import Figure
from matplotlib.lines import Line2D

from hob.undercut import effective_addendum, limit_shift, practical_limit_shift, real_limit_shift
from rotorcad import plot_style as ps
from rotorcad.errors import DesignError
from rotorcad.gears.involute_gear import InvoluteGear
from rotorcad.gears.pair import GearPair
from rotorcad.plot_style import styled


def contact_ratio_grid(
    z: int,
    alpha0: float,
    xs: np.ndarray,
    ys: np.ndarray,
    module: float = 1.0,
    tool_addendum: float = 1.25,
    tip_radius: float = 0.38,
) -> np.ndarray:
    """Compute the transverse contact ratio of two equal gears over addendum factors and shifts.

    Parameters
    ----------
    z : int
        Teeth of each gear.
    alpha0 : float, rad
        Tool pressure angle.
    xs : (k,) float array
        Profile shifts x (in modules).
    ys : (m,) float array
        Addendum factors y of the gears (addendum y m).
    module : float, mm
        Module m0.
    tool_addendum : float
        Tool addendum factor h_a0* (the gears' dedendum factor).
    tip_radius : float
        Tool tip radius factor rho_a0*.

    Returns
    -------
    (m, k) float array
        eps_alpha[i, j] for ys[i] and xs[j]; NaN where the gear cannot be made (pointed or refused).
    """
    eps = np.full((len(ys), len(xs)), np.nan)
    for i, y in enumerate(ys):
        for j, x in enumerate(xs):
            try:
                g = InvoluteGear(
                    z,
                    module,
                    alpha0,
                    0.0,
                    float(x),
                    addendum=float(y),
                    dedendum=tool_addendum,
                    tip_radius_factor=tip_radius,
                    tolerance=1e-3,
                )
                if g.tip_pointed:
                    continue
                eps[i, j] = GearPair(g, g).contact_ratio
            except DesignError:
                continue
    return eps


def pointed_limits(xs: np.ndarray, eps: np.ndarray) -> np.ndarray:
    """Find, for each row of ``eps`` (an addendum factor), the first shift where the tip turned pointed.

    Parameters
    ----------
    xs : (k,) float array
        The shifts of the columns.
    eps : (m, k) float array
        Contact ratios, NaN where the gear could not be made (:func:`contact_ratio_grid`).

    Returns
    -------
    (m,) float array
        The first shift after the last computed one; NaN when every shift to the end was made.
    """
    out = np.full(len(eps), np.nan)
    for i, row in enumerate(eps):
        ok = np.nonzero(np.isfinite(row))[0]
        if len(ok) and ok[-1] + 1 < len(xs):
            out[i] = xs[ok[-1] + 1]
    return out


@styled
def plot_nomogram(
    z: int = 11, alpha0: float = 20.0 * np.pi / 180.0, xs: np.ndarray | None = None, ys: np.ndarray | None = None
) -> Figure:
    """Draw the contact ratio of two equal gears over the shift x, one curve per addendum factor y.

    With the line epsilon = 1, the undercut limits x_g, x'_g (for the effective addendum of the
    basic rack tool h_a0* = 1.25, rho_a0* = 0.38) and x''_g (y = 1), and the undercut and
    pointed-tooth regions shaded; the legend, outside the plot, says what each limit means.

    Parameters
    ----------
    z : int
        Teeth of each gear (Kollek & Osiński: 11).
    alpha0 : float, rad
        Tool pressure angle.
    xs : (k,) float array, optional
        Shifts; default -0.2 to 1.0 in 25 steps.
    ys : (m,) float array, optional
        Addendum factors; default 0.8 to 1.2 in 9 steps.

    Returns
    -------
    matplotlib.figure.Figure
    """
    from matplotlib.patches import Patch

    xs = np.linspace(-0.2, 1.0, 25) if xs is None else xs
    ys = np.linspace(0.8, 1.2, 9) if ys is None else ys
    eps = contact_ratio_grid(z, alpha0, xs, ys)
    fig = ps.new_figure(11.0, 6.2)
    ax = fig.add_subplot()
    handles = []
    for i, y in enumerate(ys):
        colour = ps.CYCLE[i % 7]
        style = "-" if i < 7 else "--"
        handles.append(ax.plot(xs, eps[i], style, color=colour, lw=1.2, label=f"y = {y:.2f}")[0])
        ok = np.nonzero(np.isfinite(eps[i]))[0]
        if len(ok) and ok[-1] + 1 < len(xs):
            ax.plot(xs[ok[-1]], eps[i][ok[-1]], "x", color=colour, ms=7, mew=1.6)
    y_eff = effective_addendum(1.25, 0.38, alpha0)
    limits = {
        "x_g": limit_shift(z, alpha0, y_eff),
        "x'_g": practical_limit_shift(z, alpha0, y_eff),
        "x''_g": real_limit_shift(z, 1.0, alpha0, 1.0),
    }
    meaning = {
        "x_g": "x_g = {v:.3f}: theoretical undercut limit (no undercut for x ≥ x_g)",
        "x'_g": "x′_g = {v:.3f}: practical limit (a slight undercut accepted)",
        "x''_g": "x″_g = {v:.3f} (y = 1): below it the undercut shortens the path of contact",
    }
    x_lo, x_hi = float(xs.min()), float(xs.max())
    if np.isfinite(limits["x_g"]):
        ax.axvspan(x_lo, limits["x_g"], color=ps.SKY_BLUE, alpha=0.15, lw=0)
        handles.append(Patch(color=ps.SKY_BLUE, alpha=0.3, label="undercut (x < x_g)"))
    if np.isfinite(limits["x''_g"]):
        ax.axvspan(x_lo, limits["x''_g"], color=ps.BLUE, alpha=0.15, lw=0)
        handles.append(Patch(color=ps.BLUE, alpha=0.35, label="undercut shortens the contact (x < x″_g)"))
    pointed = pointed_limits(xs, eps)
    if np.isfinite(pointed).any():
        first, last = float(np.nanmin(pointed)), float(np.nanmax(pointed))
        ax.axvspan(first, x_hi, facecolor="none", edgecolor=ps.GREY, hatch="//", lw=0, alpha=0.5)
        handles.append(
            Patch(facecolor="none", edgecolor=ps.GREY, hatch="//", label=f"pointed tooth tip for the larger y (x ≥ {first:.2f})")
        )
        if np.isfinite(pointed).all():
            ax.axvspan(last, x_hi, color=ps.GREY, alpha=0.25, lw=0)
            handles.append(Patch(color=ps.GREY, alpha=0.4, label=f"pointed for every y shown (x ≥ {last:.2f})"))
        handles.append(Line2D([], [], ls="none", marker="x", color=ps.GREY, mew=1.6, label="curve ends: the tip turns pointed"))
    for (name, value), style in zip(limits.items(), ("--", ":", "-."), strict=True):
        if np.isfinite(value):
            handles.append(ax.axvline(value, ls=style, color=ps.BLACK, lw=1.0, label=meaning[name].format(v=value)))
    handles.append(ax.axhline(1.0, color="#999999", lw=3.0, zorder=1, label="ε = 1: below it the delivery is interrupted"))
    ax.set_xlim(x_lo, x_hi)
    ax.set_xlabel(ps.label("profile shift x", "1"))
    ax.set_ylabel(ps.label("transverse contact ratio ε_α", "1"))
    ps.legend_outside(ax, handles, title="addendum factor y and limits", alignment="left")
    ps.title(
        fig,
        f"contact-ratio nomogram of two equal gears, z = {z}, α0 = {np.degrees(alpha0):g}°",
        "after Kollek & Osiński Fig. 4; basic rack tool h_a0* = 1.25, ρ_a0* = 0.38",
    )
    return fig

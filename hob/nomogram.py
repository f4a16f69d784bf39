"""Contact-ratio nomogram in the manner of Kollek & Osiński's Fig. 4: the transverse contact ratio
of two equal gears over the profile shift x and the addendum factor y, with the undercut limits
x_g (theoretical), x'_g (practical) and x''_g (where undercut starts to shorten the path of
contact, from the exact envelope)."""

from __future__ import annotations

import numpy as np
from matplotlib.figure import Figure

from hob.undercut import effective_addendum, limit_shift, practical_limit_shift, real_limit_shift
from rotorcad.errors import DesignError
from rotorcad.gear import GearPair, InvoluteGear


def contact_ratio_grid(
    z: int,
    alpha0: float,
    xs: np.ndarray,
    ys: np.ndarray,
    module: float = 1.0,
    tool_addendum: float = 1.25,
    tip_radius: float = 0.38,
) -> np.ndarray:
    """eps_alpha[i, j] for addendum factor ys[i] and shift xs[j] (NaN where the gear cannot be made:
    pointed or refused)."""
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


def plot_nomogram(
    z: int = 11, alpha0: float = 20.0 * np.pi / 180.0, xs: np.ndarray | None = None, ys: np.ndarray | None = None
) -> Figure:
    xs = np.linspace(-0.2, 1.0, 25) if xs is None else xs
    ys = np.linspace(0.8, 1.2, 9) if ys is None else ys
    eps = contact_ratio_grid(z, alpha0, xs, ys)
    fig = Figure(figsize=(8, 6), dpi=120)
    ax = fig.add_subplot()
    for i, y in enumerate(ys):
        ax.plot(xs, eps[i], "-", lw=1.0, label=f"y = {y:.2f}")
    y_eff = effective_addendum(1.25, 0.38, alpha0)
    for value, style, name in (
        (limit_shift(z, alpha0, y_eff), "--", "x_g"),
        (practical_limit_shift(z, alpha0, y_eff), ":", "x'_g"),
        (real_limit_shift(z, 1.0, alpha0, 1.0), "-.", "x''_g (y = 1)"),
    ):
        if np.isfinite(value):
            ax.axvline(value, ls=style, color="k", lw=0.8, label=f"{name} = {value:.3f}")
    ax.set_xlabel("profile shift x")
    ax.set_ylabel("contact ratio ε")
    ax.set_title(
        f"contact ratio of two equal gears, z = {z}, α0 = {np.degrees(alpha0):g}° (after Kollek & Osiński Fig. 4)", fontsize=9
    )
    ax.grid(True, lw=0.3)
    ax.legend(fontsize=7, ncol=2)
    return fig

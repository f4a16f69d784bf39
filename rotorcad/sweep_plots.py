"""Pictures of a design sweep: the Pareto front of two objectives and the effect of each varied
parameter on an objective (matplotlib figures from plain arrays)."""

from __future__ import annotations

import numpy as np
from matplotlib.figure import Figure


def pareto_mask(x: np.ndarray, y: np.ndarray, smaller_x: bool = True, smaller_y: bool = True) -> np.ndarray:
    """The variants no other beats in both objectives (the Pareto front).

    Parameters
    ----------
    x, y : (n,) float
        Two objectives (NaN rows are never on the front).
    smaller_x, smaller_y : bool
        Whether smaller is better for each.

    Returns
    -------
    (n,) bool
    """
    x = np.where(np.isfinite(x), x if smaller_x else -x, np.inf)
    y = np.where(np.isfinite(y), y if smaller_y else -y, np.inf)
    order = np.lexsort((y, x))  # by x, then y
    best_y = np.minimum.accumulate(y[order])
    previous = np.concatenate([[np.inf], best_y[:-1]])
    front = np.zeros(len(x), dtype=bool)
    front[order] = (y[order] < previous) & np.isfinite(x[order]) & np.isfinite(y[order])
    return front


def plot_pareto(
    x: np.ndarray,
    y: np.ndarray,
    colour: np.ndarray | None,
    names: tuple[str, str, str | None],
    smaller: tuple[bool, bool] = (True, True),
) -> Figure:
    """Every variant in the plane of two objectives, coloured by a third, the front drawn."""
    fig = Figure(figsize=(8, 6), dpi=120)
    ax = fig.subplots()
    front = pareto_mask(x, y, *smaller)
    sc = ax.scatter(x, y, c=colour if colour is not None else "#1f77b4", s=12, cmap="viridis", alpha=0.8)
    if colour is not None:
        fig.colorbar(sc, ax=ax, label=names[2])
    order = np.argsort(x[front])
    ax.plot(x[front][order], y[front][order], "-o", color="#d62728", ms=4, label=f"Pareto front ({front.sum()} variants)")
    ax.set_xlabel(names[0])
    ax.set_ylabel(names[1])
    ax.set_title(f"{len(x)} variants: {names[1]} against {names[0]}", fontsize=10)
    ax.legend(loc="best", fontsize=8)
    ax.grid(alpha=0.3)
    fig.tight_layout()
    return fig


def plot_effects(parameters: dict[str, np.ndarray], objective: np.ndarray, name: str) -> Figure:
    """One panel per varied parameter: the objective over the parameter's values (every variant
    as a point, the mean per value as a line)."""
    n = max(1, len(parameters))
    cols = min(3, n)
    rows = int(np.ceil(n / cols))
    fig = Figure(figsize=(4.2 * cols, 3.4 * rows), dpi=110)
    axes = np.atleast_1d(fig.subplots(rows, cols)).ravel()
    for ax, (pname, values) in zip(axes, parameters.items(), strict=False):
        v = np.asarray(values, dtype=float)
        ok = np.isfinite(v) & np.isfinite(objective)
        ax.scatter(v[ok], objective[ok], s=8, alpha=0.5, color="#1f77b4")
        levels = np.unique(v[ok])
        if 1 < len(levels) <= 50:
            means = [objective[ok][v[ok] == level].mean() for level in levels]
            ax.plot(levels, means, "-", color="#d62728", label="mean")
            ax.legend(fontsize=7)
        ax.set_xlabel(pname)
        ax.set_ylabel(name)
        ax.grid(alpha=0.3)
    for ax in axes[n:]:
        ax.set_visible(False)
    fig.suptitle(f"effect of each varied value on {name}", fontsize=10)
    fig.tight_layout()
    return fig

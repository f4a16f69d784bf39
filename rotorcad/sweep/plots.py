"""Pictures of a design sweep (matplotlib figures from plain arrays).

The Pareto front of two objectives and the effect of each varied parameter on an objective.
"""

from __future__ import annotations

import numpy as np
from matplotlib.figure import Figure

from rotorcad import plot_style as ps
from rotorcad import quantities
from rotorcad.plot_style import styled


def pareto_mask(x: np.ndarray, y: np.ndarray, smaller_x: bool = True, smaller_y: bool = True) -> np.ndarray:
    """Select the variants no other beats in both objectives (the Pareto front).

    Parameters
    ----------
    x, y : (n,) float array
        Two objectives (NaN rows are never on the front).
    smaller_x, smaller_y : bool
        Whether smaller is better for each.

    Returns
    -------
    (n,) bool array
    """
    x = np.where(np.isfinite(x), x if smaller_x else -x, np.inf)
    y = np.where(np.isfinite(y), y if smaller_y else -y, np.inf)
    order = np.lexsort((y, x))  # by x, then y
    best_y = np.minimum.accumulate(y[order])
    previous = np.concatenate([[np.inf], best_y[:-1]])
    front = np.zeros(len(x), dtype=bool)
    front[order] = (y[order] < previous) & np.isfinite(x[order]) & np.isfinite(y[order])
    return front


NAMES: dict[str, tuple[str, str]] = {
    # result columns (CONTRACT.md, sweep rows): label and unit declared in rotorcad.quantities
    **{name: (q.label, q.unit) for name, q in quantities.SWEEP_COLUMNS.items()},
    # varied design values ("table.key"): name and unit
    "pair.male_teeth": ("male teeth z1", "1"),
    "pair.female_teeth": ("female teeth z2", "1"),
    "pair.center_distance": ("centre distance a", "mm"),
    "pair.male_tip_radius": ("male tip radius", "mm"),
    "pair.male_root_radius": ("male root radius", "mm"),
    "pair.female_tip_radius": ("female tip radius", "mm"),
    "pair.female_root_radius": ("female root radius", "mm"),
    "pair.lead": ("male lead", "mm"),
    "pair.length": ("rotor length", "mm"),
    "housing.radial_clearance": ("radial clearance of the bores", "mm"),
    "operating.speed_rpm": ("male speed", "rpm"),
    "operating.suction_pressure_bar": ("suction pressure", "bar"),
    "operating.discharge_pressure_bar": ("discharge pressure", "bar"),
    "profile.family": ("profile family", "1"),
    "profile.tip_land": ("tip land", "mm"),
    "profile.driving_center_depth": ("driving arc centre depth", "1"),
}
"""What a plot calls a sweep column, and its unit."""


def column_label(name: str) -> str:
    """Return an axis label with its unit for a sweep column: its name in words, not the column's.

    Known columns by :data:`NAMES` (``blow_hole_area_mm2`` -> ``blow-hole area [mm²]``,
    ``pair.lead`` -> ``male lead [mm]``); a family parameter ``profile.KEY`` in words, angles
    (``_deg``) in degrees, the others shares and factors ``[–]``; an objective's expression
    ``objective.NAME`` by its name.

    Parameters
    ----------
    name : str
        The column's name.

    Returns
    -------
    str
    """
    if name in NAMES:
        words, unit = NAMES[name]
        return ps.label(words, quantities.symbol(unit))
    key = name.split(".", 1)[1] if "." in name else name
    if key.endswith("_deg"):
        return ps.label(key[:-4].replace("_", " ") + " angle" * ("angle" not in key), "°")
    if name.startswith("objective."):
        return ps.label(key.replace("_", " "), "1")
    return ps.label(key.replace("_", " "), "1")  # the families' shares and factors (lobe_width, tip_rounding, ...)


def _words(name: str) -> str:
    """Return a column's name in words (the label without its unit)."""
    return column_label(name).rsplit(" [", 1)[0]


@styled
def plot_pareto(
    x: np.ndarray,
    y: np.ndarray,
    colour: np.ndarray | None,
    names: tuple[str, str, str | None],
    smaller: tuple[bool, bool] = (True, True),
    case: str = "",
) -> Figure:
    """Draw every variant in the plane of two objectives, coloured by a third, the front drawn.

    Parameters
    ----------
    x, y : (n,) float array
        The two objectives of every variant.
    colour : (n,) float array, optional
        A third column that colours the points.
    names : tuple of str
        The columns' names (their units follow from them, :func:`column_label`).
    smaller : tuple of bool
        Whether smaller is better for x and y.
    case : str
        The sweep (its file name), for the title.

    Returns
    -------
    matplotlib.figure.Figure
    """
    fig = ps.new_figure(9.0, 6.0)
    ax = fig.subplots()
    front = pareto_mask(x, y, *smaller)
    if colour is not None:
        sc = ax.scatter(x, y, c=colour, s=14, cmap="viridis", alpha=0.8, label="variant")
    else:
        sc = ax.scatter(x, y, color=ps.SKY_BLUE, s=14, alpha=0.8, label="variant")
    if colour is not None:
        fig.colorbar(sc, ax=ax, label=column_label(names[2]))
    order = np.argsort(x[front])
    ax.plot(x[front][order], y[front][order], "-o", color=ps.VERMILLION, ms=4, label=f"Pareto front ({front.sum()} variants)")
    ax.set_xlabel(column_label(names[0]))
    ax.set_ylabel(column_label(names[1]))
    better = ", ".join(f"{_words(n)}: {'smaller' if s else 'larger'} is better" for n, s in zip(names[:2], smaller, strict=True))
    ax.set_title(better)
    ps.legend_outside(ax)
    ps.title(fig, f"design sweep {case}: {len(x)} variants".replace("  ", " "), f"{_words(names[1])} against {_words(names[0])}")
    return fig


@styled
def plot_effects(parameters: dict[str, np.ndarray], objective: np.ndarray, name: str, case: str = "") -> Figure:
    """Draw one panel per varied parameter: the objective over the parameter's values.

    Every variant as a point, and (for 2 to 50 distinct values) the mean per value as a line.

    Parameters
    ----------
    parameters : dict of (n,) float arrays
        The varied values by column name.
    objective : (n,) float array
        The objective of every variant.
    name : str
        The objective's column name.
    case : str
        The sweep (its file name), for the title.

    Returns
    -------
    matplotlib.figure.Figure
    """
    n = max(1, len(parameters))
    cols = min(3, n)
    rows = int(np.ceil(n / cols))
    fig = ps.new_figure(4.4 * cols, 3.6 * rows + 0.6)
    axes = np.atleast_1d(fig.subplots(rows, cols)).ravel()
    for ax, (pname, values) in zip(axes, parameters.items(), strict=False):
        v = np.asarray(values, dtype=float)
        ok = np.isfinite(v) & np.isfinite(objective)
        ax.scatter(v[ok], objective[ok], s=8, alpha=0.5, color=ps.SKY_BLUE, label="variant")
        levels = np.unique(v[ok])
        if 1 < len(levels) <= 50:
            means = [objective[ok][v[ok] == level].mean() for level in levels]
            ax.plot(levels, means, "-", color=ps.VERMILLION, label="mean per value")
        ax.legend(loc="best")
        ax.set_xlabel(column_label(pname))
        ax.set_ylabel(column_label(name))
    for ax in axes[n:]:
        ax.set_visible(False)
    ps.title(fig, f"design sweep {case}: effect of each varied value".replace("  ", " "), f"on {column_label(name)}")
    return fig

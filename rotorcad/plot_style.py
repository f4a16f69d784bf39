"""One look for every picture rotorcad draws (matplotlib, no pyplot state).

What an engineer reads at a glance: every axis label ends with its unit in brackets and proper
symbols (``x [mm]``, ``clearance [µm]``, ``angle [°]``, ``[–]`` for a pure number); the figure
title states the case and its settings; legends stand outside the geometry; colours are the
colour-blind-safe palette of Okabe & Ito (*Color Universal Design*, 2008); frames are cut to what
is drawn. A deviation from a reference is drawn along the reference's normal, magnified by a
round factor that the picture states (:func:`draw_deviation`).

Plotting functions are wrapped in :func:`styled` so that the style applies to the artists they
make; :func:`save` writes PNG, SVG (text kept as text) or PDF and tags the title and the axis
labels (SVG ids ``title``, ``axes-N-xlabel``, ...) so that a reader of the SVG finds them.
"""

from __future__ import annotations

import functools
from collections.abc import Callable, Iterable, Sequence
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

if TYPE_CHECKING:
    from matplotlib.axes import Axes
    from matplotlib.figure import Figure

# Okabe & Ito's eight colours (colour-blind safe)
BLACK = "#000000"
ORANGE = "#E69F00"
SKY_BLUE = "#56B4E9"
GREEN = "#009E73"
YELLOW = "#F0E442"
BLUE = "#0072B2"
VERMILLION = "#D55E00"
PURPLE = "#CC79A7"
GREY = "#555555"
LIGHT_GREY = "#DDDDDD"

CYCLE = (BLUE, ORANGE, GREEN, VERMILLION, PURPLE, SKY_BLUE, BLACK, YELLOW)
"""Line colours in order (the light yellow last)."""

MALE_FILL, MALE_EDGE = "#A6D4F2", BLUE  # sky blue, lightened
FEMALE_FILL, FEMALE_EDGE = "#F5D38A", VERMILLION  # orange, lightened
PITCH = GREEN
BORE = GREY
REFERENCE = BLACK
RESULT = VERMILLION
INTERFERENCE = VERMILLION
POSITIVE = BLUE

STYLE: dict[str, Any] = {
    "font.size": 9,
    "axes.titlesize": 9,
    "axes.labelsize": 9,
    "figure.titlesize": 10,
    "legend.fontsize": 8,
    "legend.frameon": False,
    "xtick.labelsize": 8,
    "ytick.labelsize": 8,
    "axes.grid": True,
    "grid.linewidth": 0.4,
    "grid.alpha": 0.45,
    "lines.linewidth": 1.2,
    "lines.markersize": 5,
    "axes.spines.top": True,
    "axes.spines.right": True,
    "figure.dpi": 120,
    "savefig.dpi": 120,
    "svg.fonttype": "none",  # text stays text in an SVG: searchable, and small inside an HTML report
    "svg.hashsalt": "rotorcad",  # the same picture gives the same SVG
    "pdf.fonttype": 42,
}


def _rc() -> Any:
    import matplotlib
    from cycler import cycler

    return matplotlib.rc_context({**STYLE, "axes.prop_cycle": cycler(color=list(CYCLE))})


def styled(fn: Callable[..., Figure]) -> Callable[..., Figure]:
    """Wrap a plotting function so that it runs with rotorcad's style (a decorator).

    The artists it creates keep the style.

    Parameters
    ----------
    fn : callable
        A function that makes and returns a matplotlib Figure.

    Returns
    -------
    callable
        The same function, run inside rotorcad's rc context.
    """

    @functools.wraps(fn)
    def wrapper(*args: Any, **kwargs: Any) -> Figure:
        with _rc():
            return fn(*args, **kwargs)

    return wrapper


def new_figure(width: float, height: float) -> Figure:
    """Make a figure with constrained layout (legends outside the axes are given room).

    Call it inside a :func:`styled` function.

    Parameters
    ----------
    width, height : float, inch
        Size of the figure.

    Returns
    -------
    matplotlib.figure.Figure
    """
    from matplotlib.figure import Figure

    return Figure(figsize=(width, height), layout="constrained")


def label(name: str, unit: str) -> str:
    """Format an axis label: ``name [unit]``; ``unit`` "1" or "" for a pure number gives ``[–]``.

    Parameters
    ----------
    name : str
        The quantity, e.g. ``"normal clearance δ"``.
    unit : str
        Its unit with proper symbols: ``mm``, ``µm``, ``°``, ``m/s``, ``mm²``, ``L/min`` ...

    Returns
    -------
    str
    """
    return f"{name} [{unit if unit not in ('', '1') else '–'}]"


def title(fig: Figure, case: str, settings: str = "") -> None:
    """Set the figure's title: the case on the first line, its settings on the second.

    Parameters
    ----------
    fig : Figure
        The figure.
    case : str
        What is drawn, e.g. ``"rotor pair lysholm 4/6"``.
    settings : str
        The settings that made it, e.g. ``"a = 100 mm, 3000 rpm"``.
    """
    fig.suptitle(case + (f"\n{settings}" if settings else ""), fontsize=10)


def legend_outside(ax: Axes, handles: Sequence[Any] | None = None, labels: Sequence[str] | None = None, **kwargs: Any) -> Any:
    """Put a legend to the right of ``ax``, outside the drawing (constrained layout makes room).

    Parameters
    ----------
    ax : Axes
        The axes.
    handles : sequence of artists, optional
        What to list; default the labelled artists of ``ax``.
    labels : sequence of str, optional
        Their labels; default each handle's own.
    **kwargs
        Further options of ``Axes.legend`` (they override the placement).

    Returns
    -------
    matplotlib.legend.Legend
    """
    options: dict[str, Any] = {"loc": "upper left", "bbox_to_anchor": (1.02, 1.0), "borderaxespad": 0.0}
    options.update(kwargs)
    if handles is not None:
        return ax.legend(handles, labels if labels is not None else [h.get_label() for h in handles], **options)
    return ax.legend(**options)


def legend_below(ax: Axes, ncol: int = 3, **kwargs: Any) -> Any:
    """Put a legend under ``ax``, outside the drawing.

    Parameters
    ----------
    ax : Axes
        The axes.
    ncol : int
        Number of columns.
    **kwargs
        Further options of ``Axes.legend``.

    Returns
    -------
    matplotlib.legend.Legend
    """
    options: dict[str, Any] = {"loc": "upper center", "bbox_to_anchor": (0.5, -0.16), "ncol": ncol, "borderaxespad": 0.0}
    options.update(kwargs)
    return ax.legend(**options)


def frame(ax: Axes, points: Iterable[np.ndarray] | np.ndarray, margin: float = 0.04, equal: bool = True) -> None:
    """Cut the frame to the drawn points plus a margin, so that no part of the frame is left empty.

    Parameters
    ----------
    ax : Axes
        The axes.
    points : (n, 2) float array or iterable of them, mm
        What must be seen (non-finite points are ignored).
    margin : float
        Room around it, as a share of the larger extent.
    equal : bool
        Equal scale on both axes (geometry).
    """
    arrays = [points] if isinstance(points, np.ndarray) else list(points)
    pts = np.vstack([np.asarray(p, dtype=float).reshape(-1, 2) for p in arrays if len(p)])
    pts = pts[np.all(np.isfinite(pts), axis=1)]
    lo, hi = pts.min(axis=0), pts.max(axis=0)
    pad = margin * max(float(np.max(hi - lo)), 1e-9)
    ax.set_xlim(lo[0] - pad, hi[0] + pad)
    ax.set_ylim(lo[1] - pad, hi[1] + pad)
    if equal:
        ax.set_aspect("equal", adjustable="box")


def circle_points(centre: Sequence[float], radius: float, n: int = 721) -> np.ndarray:
    """Return the points of a circle, closed (the last point repeats the first).

    Parameters
    ----------
    centre : (float, float), mm
        Centre.
    radius : float, mm
        Radius.
    n : int
        Number of points.

    Returns
    -------
    (n, 2) float array, mm
    """
    th = np.linspace(0.0, 2.0 * np.pi, n)
    return np.column_stack([centre[0] + radius * np.cos(th), centre[1] + radius * np.sin(th)])


def nice(value: float) -> float:
    """Return the largest of 1, 2, 5 x 10^k not above ``value``.

    Parameters
    ----------
    value : float
        A positive number (anything else gives 1).

    Returns
    -------
    float
    """
    if not (np.isfinite(value) and value > 0):
        return 1.0
    k = np.floor(np.log10(value))
    for m in (5.0, 2.0, 1.0):
        if m * 10**k <= value * (1 + 1e-12):
            return float(m * 10**k)
    return float(10**k)


def magnification(largest: float, extent: float, share: float = 0.08, most: float = 1e4) -> float:
    """Choose a round factor that draws the largest deviation as about ``share`` of the drawing.

    The factor is 1, 2 or 5 x 10^k, from 1 to ``most``; the cap keeps numerical noise (nanometres)
    from being blown up into a shape.

    Parameters
    ----------
    largest : float, mm
        The largest deviation.
    extent : float, mm
        Size of the drawing.
    share : float
        Share of ``extent`` the largest deviation should take.
    most : float
        Largest factor.

    Returns
    -------
    float
        The factor; 1 when there is no deviation.
    """
    if not (np.isfinite(largest) and largest > 0):
        return 1.0
    return min(max(nice(share * extent / largest), 1.0), most)


def micrometres(value_mm: float) -> str:
    """Write a length given in mm in µm with a sign and sensible digits.

    Parameters
    ----------
    value_mm : float, mm
        The length.

    Returns
    -------
    str
        E.g. ``"+12.3 µm"``; three significant digits below 100 µm, whole micrometres above.
    """
    v = value_mm * 1e3
    return f"{v:+.3g} µm" if abs(v) < 100 else f"{v:+.0f} µm"


def draw_deviation(
    ax: Axes,
    points: np.ndarray,
    normals: np.ndarray,
    deviation: np.ndarray,
    scale: float,
    what: str = "deviation",
    every: int = 1,
) -> list[Any]:
    """Draw a deviation from a reference curve along its normals, magnified ``scale`` times.

    The magnified curve, and needles from the reference to it (blue where the deviation is
    positive, vermillion where negative). The legend entries state the factor.

    Parameters
    ----------
    ax : Axes
        The axes.
    points : (n, 2) float array, mm
        The reference curve.
    normals : (n, 2) float array
        Unit normals of the reference, the direction of a positive deviation.
    deviation : (n,) float array, mm
        NaN where there is none.
    scale : float
        Magnification of the deviation.
    what : str
        The name of the deviation in the legend.
    every : int
        Draw a needle at every ``every``-th point.

    Returns
    -------
    list of artists
        Handles for a legend.
    """
    from matplotlib.collections import LineCollection
    from matplotlib.lines import Line2D

    p = np.asarray(points, dtype=float)
    d = np.asarray(deviation, dtype=float)
    tip = p + (scale * np.nan_to_num(d))[:, None] * np.asarray(normals, dtype=float)
    ok = np.isfinite(d)
    curve = np.where(ok[:, None], tip, np.nan)
    ax.plot(*curve.T, "-", color=PURPLE, lw=1.0, zorder=4)
    idx = np.nonzero(ok)[0][:: max(1, every)]
    segs = np.stack([p[idx], tip[idx]], axis=1)
    colours = [POSITIVE if v >= 0 else INTERFERENCE for v in d[idx]]
    ax.add_collection(LineCollection(segs, colors=colours, linewidths=0.5, zorder=3))
    largest = float(np.nanmax(np.abs(d))) if ok.any() else 0.0
    return [
        Line2D([], [], color=PURPLE, lw=1.0, label=f"{what} ×{scale:g} along the normal (largest {largest * 1e3:.3g} µm)"),
        Line2D([], [], color=POSITIVE, lw=0.8, label=f"{what} > 0 (×{scale:g})"),
        Line2D([], [], color=INTERFERENCE, lw=0.8, label=f"{what} < 0 (×{scale:g})"),
    ]


def scale_bar(ax: Axes, scale: float, largest: float) -> None:
    """Add a bar in the lower right corner of ``ax`` that shows a round deviation at the drawn magnification.

    Parameters
    ----------
    ax : Axes
        The axes.
    scale : float
        Magnification of the drawn deviation.
    largest : float, mm
        The deviation's largest value; sets the bar's size (a round number of µm).
    """
    from mpl_toolkits.axes_grid1.anchored_artists import AnchoredSizeBar

    step = nice(max(largest, 1e-9))
    bar = AnchoredSizeBar(
        ax.transData,
        step * scale,
        f"{step * 1e3:g} µm of deviation (×{scale:g})",
        "lower right",
        pad=0.4,
        color=PURPLE,
        frameon=True,
        size_vertical=0,
        fontproperties={"size": 7},
    )
    bar.patch.set_alpha(0.85)
    ax.add_artist(bar)


def _tag(fig: Figure) -> None:
    """Give ids to the title and the axes' labels for an SVG.

    ``title``, ``axes-N-xlabel`` within the group ``axes-N-xaxis``, ...
    """
    if getattr(fig, "_suptitle", None) is not None:
        fig._suptitle.set_gid("title")
    for i, ax in enumerate(fig.axes):
        ax.title.set_gid(f"axes-{i}-title")
        for name in ("x", "y", "z"):
            axis = getattr(ax, f"{name}axis", None)
            if axis is None:
                continue
            axis.set_gid(f"axes-{i}-{name}axis")
            axis.label.set_gid(f"axes-{i}-{name}label")


def save(fig: Figure, path: Path, fmt: str | None = None) -> None:
    """Write ``fig`` as PNG, SVG or PDF, cut to what is drawn, with the title and axis labels tagged.

    SVG and PDF carry no date, so the same picture gives the same file.

    Parameters
    ----------
    fig : Figure
        The figure.
    path : Path
        The file (or a temporary name: give ``fmt`` then).
    fmt : str, optional
        ``png``, ``svg`` or ``pdf``; default by the suffix of ``path`` (``png`` without one).
    """
    fmt = fmt or (Path(path).suffix.lower().lstrip(".") or "png")
    _tag(fig)
    metadata = {"Date": None} if fmt == "svg" else ({"CreationDate": None} if fmt == "pdf" else None)
    with _rc():
        fig.savefig(path, format=fmt, bbox_inches="tight", pad_inches=0.08, metadata=metadata)


def svg_text(fig: Figure, salt: str = "rotorcad") -> str:
    """Return ``fig`` as an SVG document (text), for embedding in an HTML page.

    Parameters
    ----------
    fig : Figure
        The figure.
    salt : str
        Seeds the SVG's internal ids (clip paths, markers): give each picture of one page its own,
        so that no two pictures share an id.

    Returns
    -------
    str
        The SVG document.
    """
    import io

    buffer = io.StringIO()
    _tag(fig)
    with _rc():
        import matplotlib

        with matplotlib.rc_context({"svg.hashsalt": salt}):
            fig.savefig(buffer, format="svg", bbox_inches="tight", pad_inches=0.08, metadata={"Date": None})
    return buffer.getvalue()


__all__ = [
    "BLUE",
    "CYCLE",
    "GREEN",
    "ORANGE",
    "PURPLE",
    "SKY_BLUE",
    "VERMILLION",
    "circle_points",
    "draw_deviation",
    "frame",
    "label",
    "legend_below",
    "legend_outside",
    "magnification",
    "new_figure",
    "nice",
    "save",
    "scale_bar",
    "styled",
    "svg_text",
    "title",
]

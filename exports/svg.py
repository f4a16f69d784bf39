"""SVG of a 2D drawing (the :class:`exports.dxf.Drawing` the DXF writer takes), in millimetres.

One ``<g>`` per layer (its ``id`` the layer's name); outlines as closed paths of straight segments
through their points (``M x y L ... Z``, 1 nm resolution), open polylines as open paths, circles,
lines, centre marks and texts as their SVG elements. The drawing's y axis points up: the content is
drawn in a group mirrored by ``scale(1, -1)`` and the ``viewBox`` spans its bounds (2 % margin), so
that one user unit is one millimetre (``width``/``height`` in mm): a user coordinate (x, y') of the
file is the drawing's point (x, -y').
"""

from __future__ import annotations

from pathlib import Path
from xml.sax.saxutils import escape, quoteattr

import numpy as np

from exports.dxf import Drawing

LAYER_COLOURS = {"GEAR": "#1f4e9c", "MATE": "#b03a2e", "RACK": "#1e7b4f", "PITCH": "#7f7f7f", "BASE": "#bfbfbf"}
"""Stroke colour by layer; others are black."""


def _number(v: float) -> str:
    text = f"{v:.6f}".rstrip("0").rstrip(".")
    return "0" if text in ("-0", "") else text


def _path(points: np.ndarray, closed: bool) -> str:
    pts = np.asarray(points, dtype=float)
    parts = [f"M {_number(pts[0, 0])} {_number(pts[0, 1])}"]
    parts += [f"L {_number(x)} {_number(y)}" for x, y in pts[1:]]
    if closed:
        parts.append("Z")
    return " ".join(parts)


def _bounds(drawing: Drawing) -> tuple[float, float, float, float]:
    xs: list[float] = []
    ys: list[float] = []
    for _, pts in drawing.outlines + drawing.polylines + drawing.splines:
        p = np.asarray(pts, dtype=float)
        xs += [float(p[:, 0].min()), float(p[:, 0].max())]
        ys += [float(p[:, 1].min()), float(p[:, 1].max())]
    for _, (cx, cy), r in drawing.circles:
        xs += [cx - r, cx + r]
        ys += [cy - r, cy + r]
    for _, a, b in drawing.lines:
        xs += [a[0], b[0]]
        ys += [a[1], b[1]]
    for cx, cy in drawing.centers:
        xs += [cx - drawing.mark_size, cx + drawing.mark_size]
        ys += [cy - drawing.mark_size, cy + drawing.mark_size]
    if not xs:
        return 0.0, 0.0, 1.0, 1.0
    return min(xs), min(ys), max(xs), max(ys)


def svg_text(drawing: Drawing) -> str:
    """Return the drawing as the text of an SVG 1.1 document, mm.

    Parameters
    ----------
    drawing : Drawing
        What to draw (splines are drawn through their points as closed paths).

    Returns
    -------
    str
        The document.
    """
    x0, y0, x1, y1 = _bounds(drawing)
    margin = 0.02 * max(x1 - x0, y1 - y0, 1e-3)
    x0, y0, x1, y1 = x0 - margin, y0 - margin, x1 + margin, y1 + margin
    w, h = x1 - x0, y1 - y0
    stroke = _number(max(w, h) / 1000.0)
    layers: dict[str, list[str]] = {}

    def add(layer: str, element: str) -> None:
        layers.setdefault(layer, []).append(element)

    for layer, pts in drawing.outlines + drawing.splines:
        add(layer, f'<path d="{_path(pts, True)}"/>')
    for layer, pts in drawing.polylines:
        add(layer, f'<path d="{_path(pts, False)}"/>')
    for layer, (cx, cy), r in drawing.circles:
        add(layer, f'<circle cx="{_number(cx)}" cy="{_number(cy)}" r="{_number(r)}"/>')
    for layer, a, b in drawing.lines:
        add(layer, f'<line x1="{_number(a[0])}" y1="{_number(a[1])}" x2="{_number(b[0])}" y2="{_number(b[1])}"/>')
    s = drawing.mark_size
    for cx, cy in drawing.centers:
        add("CENTER", f'<line x1="{_number(cx - s)}" y1="{_number(cy)}" x2="{_number(cx + s)}" y2="{_number(cy)}"/>')
        add("CENTER", f'<line x1="{_number(cx)}" y1="{_number(cy - s)}" x2="{_number(cx)}" y2="{_number(cy + s)}"/>')
    lines = [
        '<?xml version="1.0" encoding="UTF-8"?>',
        f'<svg xmlns="http://www.w3.org/2000/svg" version="1.1" width="{_number(w)}mm" height="{_number(h)}mm" '
        f'viewBox="{_number(x0)} {_number(-y1)} {_number(w)} {_number(h)}">',
        f'<g transform="scale(1,-1)" fill="none" stroke-width="{stroke}">',
    ]
    for layer in sorted(layers):
        colour = LAYER_COLOURS.get(layer, "#000000")
        lines.append(f"<g id={quoteattr(layer)} stroke={quoteattr(colour)}>")
        lines += layers[layer]
        lines.append("</g>")
    lines.append("</g>")
    for layer, (x, y), text, height in drawing.texts:  # upright text outside the mirrored group
        where = f'x="{_number(x)}" y="{_number(-y)}" font-size="{_number(height)}"'
        lines.append(f"<text class={quoteattr(layer)} {where}>{escape(text)}</text>")
    lines.append("</svg>")
    return "\n".join(lines) + "\n"


def write_svg(path: Path, drawing: Drawing) -> None:
    """Write a drawing as SVG (:func:`svg_text`), mm.

    Parameters
    ----------
    path : Path
        The file (written whole by the caller's :class:`exports.atomic` staging).
    drawing : Drawing
        What to draw.
    """
    Path(path).write_text(svg_text(drawing), encoding="utf-8")


__all__ = ["svg_text", "write_svg"]

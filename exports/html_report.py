"""One self-contained HTML page per design (``rotorcad report``).

Tables of numbers with their units, the verdicts, and the pictures inline as SVG. The page loads
nothing: no scripts, no style sheets, no fonts or images from elsewhere, and a
Content-Security-Policy that forbids any load, so that it opens the same on a machine without
network and can be attached to a review.

Pure text building: the caller computes the numbers and the pictures (:mod:`rotorcad.cli.report_cmd`).
"""

from __future__ import annotations

import html
import math
import re
from collections.abc import Callable, Iterable, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

CSP = "default-src 'none'; style-src 'unsafe-inline'; img-src data:; base-uri 'none'; form-action 'none'"
"""Content-Security-Policy of the page: nothing may be loaded, inline style alone is allowed."""

STYLE = """
body { font-family: 'DejaVu Sans', Arial, Helvetica, sans-serif; font-size: 14px; color: #111; margin: 1.5em auto;
       max-width: 1180px; padding: 0 1em; line-height: 1.4; }
h1 { font-size: 1.6em; margin-bottom: 0.2em; }
h2 { font-size: 1.25em; border-bottom: 2px solid #0072B2; padding-bottom: 0.15em; margin-top: 1.8em; }
h3 { font-size: 1.05em; margin-bottom: 0.3em; }
table { border-collapse: collapse; margin: 0.5em 0 1em 0; }
th, td { border: 1px solid #ccc; padding: 0.2em 0.6em; vertical-align: top; }
th { background: #eef4fa; text-align: left; }
td.num { text-align: right; font-variant-numeric: tabular-nums; white-space: nowrap; }
td.key { font-family: 'DejaVu Sans Mono', monospace; }
.meta td { border: none; padding: 0.05em 0.8em 0.05em 0; }
.verdict { font-size: 1.15em; font-weight: bold; padding: 0.4em 0.8em; display: inline-block; border-radius: 4px; }
.ok { background: #d9f2e6; color: #00553b; border: 1px solid #009E73; }
.bad { background: #fbe3d4; color: #8a3a00; border: 1px solid #D55E00; }
figure.plot { margin: 1em 0 2em 0; }
figure.plot svg { max-width: 100%; height: auto; }
figcaption { font-size: 0.92em; color: #333; margin-top: 0.3em; }
nav ol { columns: 2; }
@media print { h2 { page-break-after: avoid; } figure.plot { page-break-inside: avoid; } }
"""


@dataclass(frozen=True)
class Section:
    """A part of the page: an anchor id, a heading and its body (HTML text).

    Parameters
    ----------
    id : str
        Anchor id (the contents link to it).
    heading : str
        Heading text (escaped).
    body : str
        HTML text of the section (not escaped).
    """

    id: str
    heading: str
    body: str


def esc(text: Any) -> str:
    """Escape text for HTML (``&``, ``<``, ``>`` and quotes).

    Parameters
    ----------
    text : object
        Anything; its ``str`` is escaped.

    Returns
    -------
    str
    """
    return html.escape(str(text), quote=True)


def number_text(value: Any) -> str:
    """Write a value as the page shows it.

    Floats to 6 significant digits, booleans as yes / no, None and NaN as a dash, infinities as ∞.

    Parameters
    ----------
    value : object
        The value.

    Returns
    -------
    str
    """
    if value is None:
        return "—"
    if isinstance(value, bool):
        return "yes" if value else "no"
    if isinstance(value, int):
        return str(value)
    if isinstance(value, float):
        if math.isinf(value):
            return "∞" if value > 0 else "−∞"
        if math.isnan(value):
            return "—"
        return f"{value:.6g}"
    return str(value)


def is_number(value: Any) -> bool:
    """Tell whether ``value`` is an int or a float (a bool is not)."""
    return isinstance(value, int | float) and not isinstance(value, bool)


def flatten(mapping: dict[str, Any], prefix: str = "") -> list[tuple[str, Any]]:
    """List ``(dotted key, value)`` for every scalar of a nested mapping, in its order.

    Lists are left to their own tables.

    Parameters
    ----------
    mapping : dict
        The nested mapping (e.g. the JSON of ``rotor --json``).
    prefix : str
        Put before every key.

    Returns
    -------
    list of (str, object)
    """
    out: list[tuple[str, Any]] = []
    for key, value in mapping.items():
        name = f"{prefix}{key}"
        if isinstance(value, dict):
            out.extend(flatten(value, name + "."))
        elif not isinstance(value, list | tuple):
            out.append((name, value))
    return out


def quantity_table(rows: Iterable[tuple[str, Any]], unit: Callable[[str], str], label: str = "quantity") -> str:
    """Build a table of quantity, value and unit.

    Each row carries ``data-key`` (its dotted key) and, for numbers, ``data-value`` (the full value)
    so that a reader can check the page.

    Parameters
    ----------
    rows : iterable of (str, object)
        Dotted keys and values.
    unit : callable
        The unit of a key (shown for numbers only).
    label : str
        Heading of the first column.

    Returns
    -------
    str
        The HTML table.
    """
    lines = [f"<table class='quantities'><tr><th>{esc(label)}</th><th>value</th><th>unit</th></tr>"]
    for key, value in rows:
        numeric = is_number(value)
        attr = f" data-value='{esc(repr(float(value)))}'" if numeric else ""
        unit_text = unit(key) if numeric else ""
        lines.append(
            f"<tr data-key='{esc(key)}'{attr}><td class='key'>{esc(key)}</td>"
            f"<td class='num'>{esc(number_text(value))}</td><td>{esc(unit_text)}</td></tr>"
        )
    lines.append("</table>")
    return "\n".join(lines)


def record_table(records: Sequence[dict[str, Any]], columns: Sequence[tuple[str, str]], empty: str) -> str:
    """Build a table of records, one row each.

    Parameters
    ----------
    records : sequence of dict
        The rows.
    columns : sequence of (str, str)
        ``(key, heading with unit)`` of each column.
    empty : str
        Said instead of the table when there are no records.

    Returns
    -------
    str
        The HTML table (or paragraph).
    """
    if not records:
        return f"<p>{esc(empty)}</p>"
    head = "".join(f"<th>{esc(h)}</th>" for _, h in columns)
    rows = []
    for r in records:
        cells = "".join(
            f"<td class='{'num' if is_number(r.get(k)) else 'text'}'>{esc(number_text(r.get(k)))}</td>" for k, _ in columns
        )
        rows.append(f"<tr>{cells}</tr>")
    return f"<table class='records'><tr>{head}</tr>\n" + "\n".join(rows) + "</table>"


_PROLOGUE = re.compile(r"<\?xml.*?\?>|<!DOCTYPE.*?>", re.S)
_METADATA = re.compile(r"<metadata>.*?</metadata>", re.S)


def inline_svg(svg: str) -> str:
    """Turn an SVG document into an element for the page.

    Without the XML declaration, the DOCTYPE and the metadata (they name web addresses, though
    nothing loads them).

    Parameters
    ----------
    svg : str
        The SVG document.

    Returns
    -------
    str
    """
    return _METADATA.sub("", _PROLOGUE.sub("", svg)).strip()


def figure(svg: str, caption: str, fid: str) -> str:
    """Build a picture (SVG text) with its caption.

    Parameters
    ----------
    svg : str
        The SVG document.
    caption : str
        The caption.
    fid : str
        Id of the figure element.

    Returns
    -------
    str
    """
    return f"<figure class='plot' id='{esc(fid)}'>{inline_svg(svg)}<figcaption>{esc(caption)}</figcaption></figure>"


def verdict_box(ok: bool, text: str) -> str:
    """Build a verdict in a green (``ok``) or vermillion box.

    Parameters
    ----------
    ok : bool
        Whether the verdict is good.
    text : str
        The verdict.

    Returns
    -------
    str
    """
    return f"<p class='verdict {'ok' if ok else 'bad'}'>{esc(text)}</p>"


def bullet_list(items: Sequence[str], empty: str) -> str:
    """Build a list of sentences, or ``empty`` when there are none.

    Parameters
    ----------
    items : sequence of str
        The sentences.
    empty : str
        Said instead when there are none.

    Returns
    -------
    str
    """
    if not items:
        return f"<p>{esc(empty)}</p>"
    return "<ul>" + "".join(f"<li>{esc(i)}</li>" for i in items) + "</ul>"


def page(title: str, meta: Sequence[tuple[str, str]], sections: Sequence[Section]) -> str:
    """Build the whole page: a header (title, the facts in ``meta``), the contents, the sections.

    Parameters
    ----------
    title : str
        Title of the page.
    meta : sequence of (str, str)
        Facts shown under the title.
    sections : sequence of Section
        The sections, in order (each listed in the contents).

    Returns
    -------
    str
        The HTML document.
    """
    head = "".join(f"<tr><td>{esc(k)}</td><td>{esc(v)}</td></tr>" for k, v in meta)
    nav = "".join(f"<li><a href='#{esc(s.id)}'>{esc(s.heading)}</a></li>" for s in sections)
    body = "\n".join(f"<section id='{esc(s.id)}'><h2>{esc(s.heading)}</h2>\n{s.body}\n</section>" for s in sections)
    return (
        "<!DOCTYPE html>\n<html lang='en'>\n<head>\n<meta charset='utf-8'>\n"
        f"<meta http-equiv='Content-Security-Policy' content=\"{CSP}\">\n"
        "<meta name='viewport' content='width=device-width, initial-scale=1'>\n"
        f"<title>{esc(title)}</title>\n<style>{STYLE}</style>\n</head>\n<body>\n"
        f"<header><h1>{esc(title)}</h1><table class='meta'>{head}</table></header>\n"
        f"<nav><h3>Contents</h3><ol>{nav}</ol></nav>\n{body}\n</body>\n</html>\n"
    )


def write_page(path: Path, text: str) -> None:
    """Write the page as UTF-8 (to a temporary name given by :mod:`exports.atomic`).

    Parameters
    ----------
    path : Path
        The file.
    text : str
        The HTML document (:func:`page`).
    """
    Path(path).write_text(text, encoding="utf-8")


__all__ = [
    "CSP",
    "Section",
    "bullet_list",
    "figure",
    "flatten",
    "inline_svg",
    "number_text",
    "page",
    "quantity_table",
    "record_table",
    "verdict_box",
    "write_page",
]

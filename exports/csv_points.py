"""Points files (CONTRACT.md, "Points files"): CSV with the header ``x,y`` in mm, one point a line.

Points are in order along the curve; comment lines start with ``#``.

The reader takes files from users and measuring machines, so it refuses anything it cannot read
as a profile with one sentence naming the file's option (``label``): a path that is not a regular
file (checked with ``os.stat`` before opening, so a FIFO or a device never blocks it), a file over
:data:`exports.reading.MAX_BYTES`, binary data, a missing header, a malformed or non-finite value (naming the
line), fewer than 4 distinct points, more than :data:`MAX_POINTS`, and points that are all the
same or all on one straight line. Accepted variants: UTF-8 (with or without a byte-order mark) or
Latin-1 text; the separators ``,``, ``;``, tab or blanks, as the header line uses them; more
columns than two (``x,y,z,...``), of which the first two are read.
"""

from __future__ import annotations

import re
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from exports.reading import read_bytes
from rotorcad.errors import DesignError
from rotorcad.quantities import csv_units_line

if TYPE_CHECKING:
    from exports.formats import ExportFormat, Writer
    from rotorcad.assembly import PlacedBody

MAX_POINTS = 2_000_000
"""Largest number of points in a profile."""

COLLINEAR = 1e-9
"""Points within this fraction of their extent of one straight line are not a profile."""

_MAGIC = (
    (b"\x89PNG\r\n\x1a\n", "a PNG image"),
    (b"\xff\xd8\xff", "a JPEG image"),
    (b"GIF8", "a GIF image"),
    (b"%PDF-", "a PDF document"),
    (b"PK\x03\x04", "a ZIP archive (or an .xlsx or .docx document)"),
    (b"PK\x05\x06", "an empty ZIP archive"),
    (b"\x1f\x8b", "gzip-compressed data"),
    (b"\xd0\xcf\x11\xe0\xa1\xb1\x1a\xe1", "an OLE2 document (such as an .xls workbook)"),
    (b"AutoCAD Binary DXF", "a binary DXF drawing"),
)
_CONTROL = re.compile(r"[\x00-\x08\x0e-\x1f\x7f]")  # C0 controls other than tab, line feed, VT, FF, CR
_DXF_TEXT = re.compile(rb"\A(?:\xef\xbb\xbf)?\s*(?:999[ \t]*\r?\n[^\r\n]*\r?\n\s*)*0[ \t]*\r?\n[ \t]*SECTION\b")


def write_points(path: Path, points: np.ndarray, comments: list[str] | None = None, header: str = "x,y") -> None:
    """Write points, or rows with the columns ``header`` names, to a CSV file with full double precision.

    Parameters
    ----------
    path : Path
        The file.
    points : (n, k) float array
        The rows (points (n, 2) in mm for a points file).
    comments : list of str, optional
        Lines written first, each after ``# ``.
    header : str
        The header line, e.g. ``x,y``. When every column's unit is declared
        (:func:`rotorcad.quantities.csv_units_line`), the last comment line ends with them,
        ``(units: x mm, y mm)``: readers skip comments, and the file keeps its number of lines
        before the data (scripts that skip a fixed number of lines read it as before).
    """
    units = csv_units_line(header.split(","))
    lines = list(comments or [])
    if units and lines:
        lines[-1] = f"{lines[-1]} ({units})"
    with open(path, "w", encoding="utf-8", newline="\n") as f:
        for line in lines:
            f.write(f"# {line}\n")
        f.write(f"{header}\n")
        np.savetxt(f, np.asarray(points, dtype=float), delimiter=",", fmt="%.12g")


def looks_like_dxf(head: bytes) -> bool:
    """Tell whether the first bytes of a file are those of a DXF drawing.

    The binary sentinel ``AutoCAD Binary DXF``, or (after optional blanks and ``999`` comments) the
    group code ``0`` followed by ``SECTION``.

    Parameters
    ----------
    head : bytes
        The first bytes of the file.

    Returns
    -------
    bool
    """
    return head.startswith(b"AutoCAD Binary DXF") or _DXF_TEXT.match(head) is not None


def _decode(data: bytes, label: str, path: Path) -> str:
    """Return the text of a points file: UTF-8 (a byte-order mark is dropped), else Latin-1.

    Binary data (known file signatures, NUL or control bytes, mostly high bytes) is refused with
    :class:`DesignError`.
    """
    allowed = "a CSV points file (text with the header x,y)"
    for magic, name in _MAGIC:
        if data.startswith(magic):
            raise DesignError(label, allowed, str(path), f"it is {name}, not a CSV points file")
    if b"\x00" in data:
        raise DesignError(label, allowed, str(path), "it holds NUL bytes (binary data), not a CSV points file")
    try:
        text = data.decode("utf-8-sig")
    except UnicodeDecodeError:
        text = data.decode("latin-1")
        if sum(b >= 0x80 for b in data[:4096]) > 0.3 * min(len(data), 4096):
            raise DesignError(label, allowed, str(path), "it is binary data, not a CSV points file") from None
    bad = _CONTROL.search(text)
    if bad:
        code = ord(bad.group())
        raise DesignError(
            label, allowed, str(path), f"it holds the control byte 0x{code:02x} (binary data), not a CSV points file"
        )
    return text


def _quote(line: str, limit: int = 60) -> str:
    return repr(line if len(line) <= limit else line[:limit] + "...")


def _is_number(text: str) -> bool:
    try:
        float(text)
    except ValueError:
        return False
    return "_" not in text


def read_points(path: Path, label: str = "points file", columns: tuple[str, str] = ("x", "y")) -> np.ndarray:
    """Read a points file; anything that is not a readable profile is refused.

    With other ``columns`` than ``("x", "y")`` the file is a table of two numbers a row under that
    header (e.g. ``x,clearance``): it is read the same way but not checked as a profile (at least
    two rows).

    Parameters
    ----------
    path : Path
        CSV file: a header line ``x,y`` (case-insensitive, blanks allowed; further columns such
        as ``x,y,z`` are allowed and ignored), then one point per line in mm, in order along
        the curve. Lines starting with ``#`` and blank lines are skipped. The separator is the
        one the header uses: ``,``, ``;``, tab, or blanks. UTF-8 or Latin-1.
    label : str
        The option or key that named the file; it leads the error sentence.

    Returns
    -------
    numpy.ndarray
        Points (n, 2) in mm, n >= 4, with consecutive repeated points dropped.

    Raises
    ------
    DesignError
        With one sentence naming ``label``: not a regular file, over 64 MiB, binary data, no
        header ``x,y``, a line without the header's number of values or with a value that is
        not a finite number (naming the line), fewer than 4 distinct points, more than
        2 000 000 points, all points identical or on one straight line.
    """
    path = Path(path)
    text = _decode(read_bytes(path, label, "CSV points file"), label, path)
    lines = text.replace("\r\n", "\n").replace("\r", "\n").split("\n")
    header_at = next((i for i, raw in enumerate(lines) if raw.strip() and not raw.strip().startswith("#")), None)
    if header_at is None:
        raise DesignError(label, "a CSV points file with the header x,y and at least 4 points", str(path), "it holds no data")
    header = lines[header_at].strip()
    sep = "," if "," in header else ";" if ";" in header else "\t" if "\t" in header else None
    want = [c.lower() for c in columns]
    head = ",".join(columns)
    columns = [c.strip().strip("\"'").lower() for c in header.split(sep)]
    if len(columns) < 2 or columns[:2] != want:
        if looks_like_dxf(text[:256].encode("latin-1", "replace")):
            detail = "it is a DXF drawing, not a CSV points file"
        else:
            detail = f"line {header_at + 1} reads {_quote(header)}"
            if all(_is_number(c) for c in header.split(sep)):
                detail += " (the header line x,y is missing)"
        raise DesignError(label, f"a CSV file whose first line is the header {head}", str(path), detail)
    width = len(columns)
    sep_name = {",": "','", ";": "';'", "\t": "tabs", None: "blanks"}[sep]
    xs: list[float] = []
    ys: list[float] = []
    numbers: list[int] = []
    for i in range(header_at + 1, len(lines)):
        line = lines[i].strip()
        if not line or line[0] == "#":
            continue
        parts = line.split(sep)
        try:
            if len(parts) != width or "_" in parts[0] or "_" in parts[1]:
                raise ValueError
            x, y = float(parts[0]), float(parts[1])
        except ValueError:
            allowed = f"two numbers x,y separated by {sep_name} on every line"
            if width > 2:
                allowed = f"{width} values separated by {sep_name} on every line as in its header, the first two numbers x,y"
            detail = f"line {i + 1} reads {_quote(line)}"
            if sep != "," and "," in line and all(_is_number(p.replace(",", ".")) for p in parts[:2]):
                detail += " (write decimal points, not decimal commas)"
            raise DesignError(label, allowed, str(path), detail) from None
        xs.append(x)
        ys.append(y)
        numbers.append(i + 1)
        if len(xs) > MAX_POINTS:
            raise DesignError(
                label, f"a profile of at most {MAX_POINTS} points", str(path), f"line {i + 1} holds a point beyond that"
            )
    pts = np.column_stack([np.asarray(xs, dtype=float), np.asarray(ys, dtype=float)])
    finite = np.isfinite(pts).all(axis=1)
    if not finite.all():
        number = numbers[int(np.argmin(finite))]
        raise DesignError(
            label, f"finite numbers {head} on every line", str(path), f"line {number} reads {_quote(lines[number - 1].strip())}"
        )
    if want != ["x", "y"]:
        if len(pts) < 2:
            raise DesignError(label, f"a table of at least two rows {head}", str(path), f"{len(pts)} read")
        return pts
    distinct = check_profile(pts, label, str(path))
    kept = np.concatenate([[True], np.any(np.diff(pts, axis=0) != 0.0, axis=1)])  # as check_profile keeps them
    return FilePoints.of(distinct, np.asarray(numbers)[kept])


class FilePoints(np.ndarray):
    """Points (n, 2) read from a file, carrying the line of each in it (``lines``, (n,) int, 1-based).

    A plain array everywhere else; ``lines`` is kept by this array only (not by its views or by
    arrays made from it), so that a point's line is named in an error (an outlier's) and never a
    wrong one.
    """

    lines: np.ndarray | None

    @classmethod
    def of(cls, points: np.ndarray, lines: np.ndarray) -> FilePoints:
        """Return ``points`` carrying ``lines`` (one a point), or as plain points when they do not match."""
        out = np.asarray(points, dtype=float).view(cls)
        out.lines = np.asarray(lines, dtype=int) if len(lines) == len(points) else None
        return out

    def __array_finalize__(self, obj: object) -> None:
        self.lines = None


def check_profile(points: np.ndarray, label: str, value: object = None) -> np.ndarray:
    """Drop consecutive repeated points and refuse what cannot be a profile.

    Parameters
    ----------
    points : numpy.ndarray
        Points (n, 2) in mm along a curve.
    label : str
        The option or key the points came from; it leads the error sentence.
    value : object
        What to show as the value given (the file name).

    Returns
    -------
    numpy.ndarray
        The points (m, 2) without consecutive repeats.

    Raises
    ------
    DesignError
        Non-finite coordinates, more than :data:`MAX_POINTS` points, all points identical,
        fewer than 4 distinct points, or all points on one straight line (within
        :data:`COLLINEAR` of their extent).
    """
    pts = np.asarray(points, dtype=float).reshape(-1, 2)
    if not np.isfinite(pts).all():
        raise DesignError(label, "a profile of finite coordinates", value, "a coordinate is NaN or infinite")
    if len(pts) > MAX_POINTS:
        raise DesignError(label, f"a profile of at most {MAX_POINTS} points", value, f"{len(pts)} points")
    keep = np.concatenate([[True], np.any(np.diff(pts, axis=0) != 0.0, axis=1)]) if len(pts) else np.zeros(0, bool)
    distinct = pts[keep]
    if len(pts) > 1 and len(distinct) == 1:
        x, y = distinct[0]
        raise DesignError(
            label, "a profile (points along a curve)", value, f"all {len(pts)} points are the same point ({x:g}, {y:g})"
        )
    if len(distinct) < 4:
        raise DesignError(label, "a profile of at least 4 distinct points", value, f"{len(distinct)} distinct points read")
    centred = distinct - distinct.mean(axis=0)
    extent = float(np.hypot(*np.ptp(distinct, axis=0)))
    _, vectors = np.linalg.eigh(centred.T @ centred)
    off_line = float(np.abs(centred @ vectors[:, 0]).max())  # distance from the principal line
    if off_line <= COLLINEAR * extent:
        raise DesignError(
            label,
            "a profile (points along a curve)",
            value,
            f"all {len(distinct)} points lie on one straight line (within {off_line:.3g} mm over {extent:.6g} mm)",
        )
    return distinct


def _plan_points(fmt: ExportFormat, body: PlacedBody, tolerance: float, row: dict[str, Any]) -> Writer:
    """Plan a body's section as points, in its own frame (turned into mesh, not shifted)."""
    row.update(triangles=0, volume=body.section_volume, tolerance=body.section_tolerance)
    own = body.own_points()
    return lambda path: write_points(path, own)


def _register() -> None:
    from exports.formats import SWEPT_BODIES, ExportFormat, register
    from rotorcad.assembly import BodyKind

    register(
        ExportFormat(
            "csv",
            "_own_frame.csv",  # the section about its own axis, unlike the placed solids
            _plan_points,
            "the section's chords: half the surface tolerance asked (a quarter for a gear)",
            SWEPT_BODIES,
            kind_extensions=((BodyKind.GEAR, ".csv"),),  # a gear's points file: <design>_<body>.csv, as before
            meshes=False,
        )
    )


_register()

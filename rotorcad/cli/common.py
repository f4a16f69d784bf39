"""Helpers shared by the commands: JSON output, summary tables, output-file groups.

The design files are read by the core (:mod:`rotorcad.design.files`); its readers are importable
from here under their old names.
"""

from __future__ import annotations

import json
import math
import sys
from collections.abc import Callable
from pathlib import Path
from typing import Any

import click
import numpy as np
from rich.console import Console
from rich.table import Table

from exports.atomic import Writer, check_writable, staging_prefix, write_all
from exports.background import WorkerPool
from rotorcad.design.files import MAX_DESIGN_BYTES, load_gear_design, load_rotor_design, load_toml  # noqa: F401 - the commands' names
from rotorcad.errors import DesignError, InputNote
from rotorcad.roles import EndFace


class InputError(click.ClickException):
    """Bad input: one sentence on stderr, exit status 2."""

    exit_code = 2


def reraise(exc: DesignError, names: dict[str, str]) -> InputError:
    """Turn a library :class:`DesignError` into a CLI error naming the option the user typed.

    Parameters
    ----------
    exc : DesignError
        The library's error.
    names : dict of str to str
        Library parameter name -> option name (e.g. ``"teeth"`` -> ``"--teeth"``).

    Returns
    -------
    InputError
        To be raised by the caller.
    """
    return InputError(exc.sentence(names.get(exc.param, exc.param)))


SEEN_FROM_HELP = (
    "End face the points' transverse section is seen from: suction (rotorcad's convention: the male turns "
    "counter-clockwise, the driving flanks below the line of centres, y < 0, with a male tip on +x) or discharge "
    "(a CMM's scan from the other end: the mirror image, mirrored y -> -y before anything else). Default suction."
)


def seen_from_option(fn):
    """Add ``--seen-from suction|discharge`` to a command that reads a rotor's points (a decorator).

    Read by :func:`end_face`; the points are mirrored by
    :func:`rotorcad.measured.end_face.seen_from_suction` before anything else reads them.
    """
    return click.option("--seen-from", "seen_from", metavar="suction|discharge", help=SEEN_FROM_HELP)(fn)


def end_face(value: str | None) -> EndFace:
    """Return the end face of ``--seen-from`` (suction when not given).

    Parameters
    ----------
    value : str or None
        The option's text as typed (any case), or None.

    Returns
    -------
    EndFace

    Raises
    ------
    InputError
        Any other text: one sentence naming the option and its two values.
    """
    if value is None:
        return EndFace.SUCTION
    try:
        return EndFace(str(value).strip().lower())
    except ValueError:
        raise InputError(
            f"--seen-from must be suction or discharge, the end face the points' section is seen from (got {value!r})."
        ) from None


def plain(value: Any) -> Any:
    """Convert numpy scalars and arrays to JSON-ready Python values; non-finite numbers to None.

    Parameters
    ----------
    value : object
        A value, or dicts, lists and tuples of them (converted throughout).

    Returns
    -------
    object
    """
    if isinstance(value, dict):
        return {k: plain(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [plain(v) for v in value]
    if isinstance(value, np.ndarray):
        return plain(value.tolist())
    if isinstance(value, (bool, np.bool_)):
        return bool(value)
    if isinstance(value, (int, np.integer)):
        return int(value)
    if isinstance(value, (float, np.floating)):
        v = float(value)
        return v if math.isfinite(v) else None
    return value


def emit_json(data: dict[str, Any]) -> None:
    """Print ``data`` as indented JSON on stdout (numpy values converted by :func:`plain`)."""
    click.echo(json.dumps(plain(data), indent=2))


def unit_of(key: str) -> str:
    """Return the unit of a result key as the tables print it: its declaration in :mod:`rotorcad.quantities`.

    Parameters
    ----------
    key : str
        A result key or dotted path, e.g. ``max_normal_clearance``.

    Returns
    -------
    str
        ``mm``, ``mm²``, ``deg``, ...; ``"1"`` for a pure number; ``""`` for a key without a declaration.
    """
    from rotorcad.quantities import unit_of as declared

    return declared(key)


def print_table(title: str, rows: dict[str, Any]) -> None:
    """Print the result as a table of quantity, value and unit (mm unless the unit column says else).

    Nested values (dicts, lists) are left out.

    Parameters
    ----------
    title : str
        Title of the table.
    rows : dict
        Result keys and values.
    """
    table = Table(title=title, show_header=True, header_style="bold")
    table.add_column("quantity")
    table.add_column("value", justify="right")
    table.add_column("unit")
    for key, value in plain(rows).items():
        if isinstance(value, bool):
            text, unit = str(value), ""
        elif isinstance(value, float):
            text = f"{value:.4g}" if 0 < abs(value) < 0.01 else f"{value:.6f}"  # micrometres keep their digits
            unit = unit_of(key)
        elif isinstance(value, int):
            text, unit = str(value), unit_of(key)
        elif isinstance(value, (dict, list)):
            continue
        else:
            text, unit = str(value), ""
        table.add_row(key, text, unit)
    Console(file=sys.stdout, highlight=False).print(table)


def print_pair_table(title: str, rows: dict[str, Any], mate: dict[str, Any], names: tuple[str, str] = ("gear", "mate")) -> None:
    """Print a table of quantity, the value of each of two bodies and unit.

    The mate's value stands where it has one; the quantities of the pair alone (centre distance,
    contact ratio, ...) fill the first column only.

    Parameters
    ----------
    title : str
        Title of the table.
    rows : dict
        Result keys and values of the first body and of the pair.
    mate : dict
        Result keys and values of the second body.
    names : (str, str)
        Headings of the two value columns.
    """
    table = Table(title=title, show_header=True, header_style="bold")
    table.add_column("quantity")
    table.add_column(names[0], justify="right")
    table.add_column(names[1], justify="right")
    table.add_column("unit")

    def text(value: Any) -> str:
        return f"{value:.6f}" if isinstance(value, float) and not isinstance(value, bool) else str(value)

    for key, value in plain(rows).items():
        if isinstance(value, (dict, list)):
            continue
        other = plain(mate).get(key)
        unit = "" if isinstance(value, bool) else unit_of(key)
        table.add_row(key, text(value), "" if other is None else text(other), unit)
    Console(file=sys.stdout, highlight=False).print(table)


class Outputs:
    """Collect the files a command will write, check their folders up front, write them all or none.

    See :mod:`exports.atomic`.
    """

    def __init__(self) -> None:
        self._items: list[tuple[Path, Writer]] = []
        self._options: dict[Path, str] = {}
        self.replaced: list[Path] = []
        """The files that were there before :meth:`write` and were replaced whole."""

    def add(self, path: Path | None, writer: Writer, option: str) -> None:
        """Add a file to write, checked at once.

        Parameters
        ----------
        path : Path or None
            The file (None: nothing to add).
        writer : Writer
            Writes the file given the (temporary) path.
        option : str
            The option that named the file, for error sentences.

        Raises
        ------
        InputError
            A target that cannot be written (:func:`exports.atomic.check_writable`).
        """
        if path is None:
            return
        try:
            check_writable(Path(path), option)
        except DesignError as exc:
            raise InputError(exc.sentence()) from None
        self._items.append((Path(path), writer))
        self._options[Path(path)] = option

    def add_figure(self, path: Path | None, figure: Callable[[], Any], option: str) -> None:
        """Add a picture to write.

        ``figure()`` makes the matplotlib figure, saved as PNG, SVG or PDF by the suffix of ``path``
        (PNG without one; any other suffix is refused naming ``option``), in the style of
        :mod:`rotorcad.plot_style` (cut to what is drawn, labels tagged in SVG).

        Parameters
        ----------
        path : Path or None
            The file (None: nothing to add).
        figure : callable
            Makes the figure when the file is written.
        option : str
            The option that named the file.
        """
        if path is None:
            return
        fmt = plot_format(path, option)

        def write(p: Path) -> None:
            from rotorcad.plot_style import save  # matplotlib only when a picture is drawn

            save(figure(), p, fmt)

        self.add(path, write, option)

    def write(self, pool: WorkerPool | None = None) -> list[Path]:
        """Write every file or none; background writers run in ``pool``'s worker if given.

        Parameters
        ----------
        pool : WorkerPool, optional
            Worker for the background writers.

        Returns
        -------
        list of Path
            The files written.

        Raises
        ------
        InputError
            A write that failed, naming the option and its file.
        """
        self._refuse_inputs()
        there = [(p, self._options[p]) for p, _ in self._items if p.is_file()]  # a link: the file it points to
        try:
            written = write_all(self._items, pool)
        except OSError as exc:
            raise InputError(self._failure(exc)) from None
        self.replaced = [p for p, _ in there]
        if there:  # one policy for every command: an existing file is replaced whole, and named
            import warnings

            by_option: dict[str, list[str]] = {}
            for path, option in there:
                by_option.setdefault(option, []).append(str(path))
            named = "; ".join(f"{', '.join(paths)} ({option})" for option, paths in by_option.items())
            warnings.warn(f"replaced the existing {'file' if len(there) == 1 else 'files'} {named}", InputNote, stacklevel=2)
        return written

    def _refuse_inputs(self) -> None:
        """Refuse an output that is a file the command reads (``--male-csv`` naming the ``--male-points`` file).

        The inputs are the command's file parameters that are not among the outputs' options; the same
        file also through another name or a link (:func:`os.path.samefile`).

        Raises
        ------
        InputError
            Naming the output's option, the input's and the file.
        """
        import os

        ctx = click.get_current_context(silent=True)
        if ctx is None:
            return
        outputs = set(self._options.values())
        inputs = []
        for param in ctx.command.params:
            value = ctx.params.get(param.name or "")
            name = param.opts[0] if param.opts[0].startswith("-") else f"the {param.name} file"
            if isinstance(value, Path) and name not in outputs and value.is_file():
                inputs.append((name, value))
        for path, option in self._options.items():
            for name, value in inputs:
                if path.is_file() and os.path.samefile(path, value):
                    raise InputError(f"{option} names the file {name} reads ({path}): write it to another file.")

    def _failure(self, exc: OSError) -> str:
        """Return the sentence for a failed write, naming the option and its file (never the temporary)."""
        failed = Path(str(exc.filename)) if exc.filename else None
        for path, option in self._options.items():
            if failed is not None and (
                failed == path or (failed.parent == path.parent and failed.name.startswith(staging_prefix(path)))
            ):
                return f"{option} must be a file that can be written ({exc.strerror}): {path}."
        names = ", ".join(dict.fromkeys(self._options.values()))
        return f"{names} must be files that can be written ({exc.strerror})."


PLOT_FORMATS = ("png", "svg", "pdf")


def plot_format(path: Path, option: str = "--plot") -> str:
    """Return the picture format of ``path`` from its suffix (PNG, SVG or PDF; PNG without one).

    Parameters
    ----------
    path : Path
        The picture's file.
    option : str
        The option that named it.

    Returns
    -------
    str
        ``"png"``, ``"svg"`` or ``"pdf"``.

    Raises
    ------
    InputError
        Any other suffix.
    """
    suffix = Path(path).suffix.lower().lstrip(".")
    if not suffix:
        return "png"
    if suffix not in PLOT_FORMATS:
        raise InputError(f"{option} must name a .png, .svg or .pdf file (got {path}).")
    return suffix


def output_folder(path: Path | None) -> Path | None:
    """Create the ``--out`` folder if needed; refuse a path that is a file or cannot be created.

    Folders made here are recorded in :data:`CREATED_FOLDERS`, so that a failed run removes them.

    Parameters
    ----------
    path : Path or None
        The folder (None: no folder).

    Returns
    -------
    Path or None
        The folder.

    Raises
    ------
    InputError
        A path that is a file, or a folder that cannot be created.
    """
    if path is None:
        return None
    path = Path(path)
    try:  # Path.exists raises for a name too long (ENAMETOOLONG) rather than saying False
        if path.exists() and not path.is_dir():
            raise InputError(f"--out must be a folder, but {path} is a file.")
        missing = [p for p in (path, *path.parents) if not p.exists()]  # deepest first
        path.mkdir(parents=True, exist_ok=True)
    except OSError as exc:
        raise InputError(f"--out must be a folder that can be created ({exc.strerror}): {path}.") from None
    CREATED_FOLDERS.extend(missing)
    return path


CREATED_FOLDERS: list[Path] = []
"""Folders made by :func:`output_folder` in this run; a failed run removes those still empty."""


def remove_created_folders() -> None:
    """Remove the folders this run created that are still empty, deepest first; forget them all.

    A failed run leaves no folder behind.
    """
    while CREATED_FOLDERS:
        folder = CREATED_FOLDERS.pop(0)
        try:
            folder.rmdir()
        except OSError:
            pass

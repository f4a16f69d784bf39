"""Reading design files (TOML): the one place that opens a design or sweep file.

The text is read defensively (:mod:`rotorcad.design.reading`), parsed by :mod:`tomllib` and
checked by :mod:`rotorcad.design.schema`. A file that cannot be read, or a design that is wrong,
is an :class:`rotorcad.errors.InputFileError` naming the option or ``[table] key`` that gave it.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

from rotorcad.errors import InputFileError

MAX_DESIGN_BYTES = 2**20
"""Largest design or sweep file read, bytes (1 MiB; a design is a few hundred bytes)."""


def load_toml(path: Path, label: str = "design file") -> dict[str, Any]:
    """Read the mapping a TOML design (or sweep) file holds.

    Parameters
    ----------
    path : Path
        The file (UTF-8 or Latin-1 text of at most :data:`MAX_DESIGN_BYTES`).
    label : str
        The option or key that named the file; it leads the error sentence.

    Returns
    -------
    dict
        The tables and keys as TOML reads them (not checked: see :mod:`rotorcad.design.schema`).

    Raises
    ------
    InputFileError
        A missing, special (FIFO, device, folder), oversized, binary or malformed file, in one
        sentence naming ``label`` (NUL bytes by their line).
    """
    import tomllib

    from rotorcad.design.reading import read_text

    text = read_text(Path(path), label, "TOML design file", MAX_DESIGN_BYTES)
    try:
        return tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise InputFileError(label, "valid TOML", str(path), str(exc)) from None


def is_gear_design(data: dict[str, Any]) -> bool:
    """Tell whether a design mapping is a gear design (it has a ``[gear]`` table)."""
    return "gear" in data


def load_gear_design(path: Path, data: dict[str, Any] | None = None) -> dict[str, dict[str, Any]]:
    """Read a gear design file and check it (:func:`rotorcad.design.schema.gear_design`).

    Parameters
    ----------
    path : Path
        The design file.
    data : dict, optional
        Its mapping, if the file was read already (it is then not read again).

    Returns
    -------
    dict
        ``{"gear": {...}, "mate": {...}}``.

    Raises
    ------
    InputFileError
        A file that cannot be read, or a bad design.
    """
    from rotorcad.design.schema import gear_design

    return gear_design(load_toml(path) if data is None else data)


def load_rotor_design(path: Path, data: dict[str, Any] | None = None) -> dict[str, Any]:
    """Read a screw-rotor design file and check it (:func:`rotorcad.design.schema.rotor_design`).

    A points file named in the design is found beside the design file (it is not read here).

    Parameters
    ----------
    path : Path
        The design file.
    data : dict, optional
        Its mapping, if the file was read already (it is then not read again).

    Returns
    -------
    dict
        The checked design (:func:`rotorcad.design.schema.rotor_design`).

    Raises
    ------
    DesignError
        A file that cannot be read, or a bad design.
    """
    from rotorcad.design.schema import rotor_design

    return rotor_design(load_toml(path) if data is None else data, Path(path).parent)

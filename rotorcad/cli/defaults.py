"""Defaults a command took: "value (default: how it was chosen)", for the JSON and the table (CONTRACT.md, "defaults")."""

from __future__ import annotations

import sys

from rich.console import Console
from rich.markup import escape
from rich.table import Table


def taken(value: str, how: str) -> str:
    """Return the text of a default: ``"value (default: how)"``.

    Parameters
    ----------
    value : str
        The value as the user would type it, with its unit.
    how : str
        How it was chosen (a formula, a standard value and its source).

    Returns
    -------
    str
    """
    return f"{value} (default: {how})"


def print_defaults(defaults: dict[str, str]) -> None:
    """Print the defaults a command took, one row each (nothing when there are none).

    Parameters
    ----------
    defaults : dict of str to str
        Input name (the ``[table] key`` or option) to the text of :func:`taken`.
    """
    if not defaults:
        return
    table = Table(title="defaults taken (give them in the design or as options to change them)", header_style="bold")
    table.add_column("input")
    table.add_column("value (default: how it was chosen)")
    for key, text in defaults.items():
        table.add_row(escape(key), escape(text))
    Console(file=sys.stdout, highlight=False, width=140).print(table)

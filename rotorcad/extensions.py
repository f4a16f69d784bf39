"""Extension points: what the packages beside the core add to it, without the core importing them.

The core never imports ``hob``, ``exports`` or ``rotorcad.cli`` (ARCHITECTURE.md). Where it runs
work that belongs to them -- a design sweep asks for the hobbability verdict of ``hob``; a sweep
file's base design names a points file or drawing that ``exports`` reads -- it looks the work up
here. The tables are filled:

* by the packages themselves when imported (:mod:`hob.sweep_check` registers the verdict,
  :mod:`exports.extensions` the profile readers); the command line imports them;
* for a script that imports neither, by :func:`load_extensions`: the distribution declares them as
  entry points of the group ``rotorcad.extensions`` (``pyproject.toml``), each a module that
  registers what it adds when imported (the ordinary plugin mechanism of Python packages,
  :mod:`importlib.metadata`).

Passing the work in explicitly (``analyses=``, ``read_points=``) always works and wins.
"""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path
from typing import Any

GROUP = "rotorcad.extensions"
"""The entry-point group of the modules that fill these tables."""

SWEEP_ANALYSES: dict[Any, Callable[[Any, Any, float], dict[str, Any]]] = {}
"""Optional analyses of a sweep's variant by :class:`rotorcad.sweep.plan.Extra`: (rotors, spec,
designed clearance in mm) -> the columns (:data:`rotorcad.sweep.tasks.Analysis`)."""

PROFILE_READERS: dict[str, Callable[[Path, str], Any]] = {}
"""Readers of a points family's file by family (``rack-points``, ``male-points``,
``female-points``): (path, label naming it in errors) -> ``(n, 2)`` points or curves, mm."""

_loaded = False


def register_sweep_analysis(extra: Any, analysis: Callable[[Any, Any, float], dict[str, Any]]) -> None:
    """Add an optional analysis a sweep file may ask for (``[sweep] compute``).

    Parameters
    ----------
    extra : rotorcad.sweep.plan.Extra
        What the sweep file names.
    analysis : callable
        (rotors, spec, designed clearance in mm) -> its columns.
    """
    SWEEP_ANALYSES[extra] = analysis


def register_profile_reader(family: str, reader: Callable[[Path, str], Any]) -> None:
    """Add the reader of a points family's file.

    Parameters
    ----------
    family : str
        ``rack-points``, ``male-points`` or ``female-points``.
    reader : callable
        (path, label) -> the profile, mm; refusing a bad file with a
        :class:`rotorcad.errors.DesignError` naming ``label``.
    """
    PROFILE_READERS[family] = reader


def load_extensions() -> None:
    """Import, once, the modules the installed distributions declare in the group :data:`GROUP`.

    A module that cannot be imported is skipped (its work is then refused where it is asked for,
    naming what to pass instead).
    """
    global _loaded
    if _loaded:
        return
    _loaded = True
    from importlib.metadata import entry_points

    for point in entry_points(group=GROUP):
        try:
            point.load()
        except ImportError:
            continue

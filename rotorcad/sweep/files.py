"""A sweep file from disk to its table: reading it, its base design and the base's points; the public run.

The sweep file (TOML, :mod:`rotorcad.sweep.plan`) is read by the core's design reader
(:mod:`rotorcad.design.files`). What belongs to the packages beside the core comes through its
extension points (:mod:`rotorcad.extensions`), or is passed in: the points file of a points
family's base (read by ``exports``) and the hobbability verdict (``hob``). :func:`sweep` is the
public ``rotorcad.sweep(...)``.
"""

from __future__ import annotations

import os
from collections.abc import Callable, Mapping
from pathlib import Path
from typing import Any

from rotorcad.design.files import load_toml
from rotorcad.errors import DesignError, InputFileError
from rotorcad.sweep.plan import Extra, SweepPlan

PointsReader = Callable[[Path, str], Any]
"""Reads a points family's file: (path, label naming it in errors) -> the profile, mm."""


def sweep_columns(plan: SweepPlan) -> tuple[list[str], list[str]]:
    """Return the number and true/false columns of a plan's table (for constraints, objectives, plots).

    Parameters
    ----------
    plan : SweepPlan

    Returns
    -------
    numeric, boolean : list of str
    """
    from rotorcad.sweep.tasks import boolean_columns, result_columns

    varied = [p.name for p in plan.parameters if p.name != "profile.family"]
    return [*result_columns(plan.extras), *varied], boolean_columns(plan.extras)


def load_steering(path: Path, plan: SweepPlan):
    """Read the ``[constraints]`` and ``[objectives]`` of a sweep file (:func:`rotorcad.sweep.ranking.steering`).

    Parameters
    ----------
    path : Path
        The sweep file.
    plan : SweepPlan
        Its plan (for the columns it makes).

    Returns
    -------
    rotorcad.sweep.ranking.Steering
    """
    from rotorcad.sweep.ranking import steering

    numeric, boolean = sweep_columns(plan)
    return steering(load_toml(path, "sweep file"), numeric, boolean)


def load_sweep(path: Path, read_points: Mapping[str, PointsReader] | None = None) -> tuple[SweepPlan, Path, Any]:
    """Read a sweep file, its base design and the base's points (if a points family).

    Parameters
    ----------
    path : Path
        The sweep file (TOML): a ``[sweep]`` table naming the base design file, or a ``[base]``
        table holding it.
    read_points : mapping of str to callable, optional
        Readers of a points family's file by family; default those registered
        (:data:`rotorcad.extensions.PROFILE_READERS`: ``exports``' readers of CSV points and DXF
        drawings).

    Returns
    -------
    plan : SweepPlan
        The checked sweep.
    folder : Path
        The base design's folder.
    points : (n, 2) float array, list of Curve or None
        The base's profile points (mm), for a points family.

    Raises
    ------
    DesignError
        A bad or missing base, or a bad sweep (:class:`rotorcad.errors.InputFileError` for the
        files).
    """
    from rotorcad.design.schema import POINT_FAMILIES, rotor_design
    from rotorcad.sweep.plan import sweep_plan

    data = load_toml(path, "sweep file")
    section = data.get("sweep", {})
    if "base" in data and "base" in section:
        raise InputFileError("[sweep] base", "either a design file or a [base] table, not both", section["base"])
    if "base" in data:
        base, folder = data["base"], path.parent
    elif isinstance(section.get("base"), str):
        base_path = (path.parent / section["base"]).resolve()
        base, folder = load_toml(base_path, "[sweep] base"), base_path.parent
    else:
        raise InputFileError("[sweep] base", "a design file name (or a [base] table)", None, "missing key")
    plan = sweep_plan(data, base)
    settings = rotor_design(base, folder)  # the base must be a valid design
    points = None
    if settings["family"] in POINT_FAMILIES:
        readers = _points_readers(read_points)
        if settings["family"] not in readers:
            raise InputFileError(
                "[profile] points",
                "a file this run can read",
                str(settings["points"]),
                "pass read_points= (exports.extensions registers the readers of CSV points and DXF drawings)",
            )
        points = readers[settings["family"]](settings["points"], "[profile] points")
    return plan, folder, points


def _points_readers(given: Mapping[str, PointsReader] | None) -> Mapping[str, PointsReader]:
    """Return the readers given, else those registered (the entry points loaded first)."""
    if given is not None:
        return given
    from rotorcad.extensions import PROFILE_READERS, load_extensions

    load_extensions()
    return PROFILE_READERS


def registered_analyses() -> dict[Extra, Callable[..., dict[str, Any]]]:
    """Return the optional analyses registered (:data:`rotorcad.extensions.SWEEP_ANALYSES`), entry points loaded.

    Returns
    -------
    dict
        :class:`Extra` -> analysis: the hobbability verdict of ``hob`` when installed.
    """
    from rotorcad.extensions import SWEEP_ANALYSES, load_extensions

    load_extensions()
    return dict(SWEEP_ANALYSES)


def sweep(
    sweep_file: str | os.PathLike,
    out: str | os.PathLike | None = None,
    scheduler: str | None = None,
    workers: int | None = None,
    analyses: Mapping[Extra, Callable[..., dict[str, Any]]] | None = None,
    read_points: Mapping[str, PointsReader] | None = None,
):
    """Run a design sweep file (see :mod:`rotorcad.sweep.plan`) and return its table.

    Parameters
    ----------
    sweep_file : path
        The sweep (TOML).
    out : path, optional
        Parquet file to stream to and resume from.
    scheduler : str, optional
        Address of a running ``dask.distributed`` scheduler (default: a local cluster).
    workers : int, optional
        Local worker processes; 0 runs the variants in this process. Default: in this process for
        fewer than 200 variants to compute, else one worker per core.
    analyses : mapping, optional
        Optional analyses (:class:`Extra` -> analysis); default those registered
        (:func:`registered_analyses`: the hobbability verdict of ``hob``).
    read_points : mapping, optional
        Readers of a points family's base file; default those registered (:func:`load_sweep`).

    Returns
    -------
    pandas.DataFrame
        One row per variant: its number and key, the varied values (``table.key`` columns), ``ok``,
        ``reason``, ``seconds`` and the results with their unit in the column name; with
        ``[constraints]`` or ``[objectives]`` also ``feasible``, ``pareto`` and ``rank``
        (:mod:`rotorcad.sweep.ranking`).

    Raises
    ------
    DesignError
        A bad sweep file or base design, ``workers`` below 0, or ``out`` in a folder that does not
        exist.
    """
    from rotorcad.sweep.run import run_sweep

    if workers is not None and not (isinstance(workers, int) and not isinstance(workers, bool) and workers >= 0):
        raise DesignError("workers", "a whole number of at least 0 (0: in this process)", workers)
    if out is not None and not Path(out).parent.is_dir():
        raise DesignError("out", "a file in an existing folder", str(out))
    plan, folder, points = load_sweep(Path(sweep_file), read_points)
    steer = load_steering(Path(sweep_file), plan)
    chosen = registered_analyses() if analyses is None else analyses
    table = run_sweep(plan, folder, points, None if out is None else Path(out), scheduler, workers, analyses=chosen).table
    return steer.apply(table) if steer.constraints or steer.objectives else table

"""A sweep file from disk to its table: the application's edge of :mod:`rotorcad.sweep`.

Reading the sweep file, its base design and the base's points file (``exports``), and the
hobbability verdict (``hob``), are the command line's: the core package :mod:`rotorcad.sweep`
imports neither. :func:`sweep` is the public ``rotorcad.sweep(...)``. The names of the core that
lived here before (``run_sweep``, ``parts_folder``, ``SweepOutcome``, ``variant_design``) are
re-exported.
"""

from __future__ import annotations

import os
from collections.abc import Callable, Mapping
from pathlib import Path
from typing import Any

import pandas as pd

from rotorcad.errors import DesignError
from rotorcad.sweep.plan import Extra, SweepPlan
from rotorcad.sweep.run import SweepOutcome, parts_folder, variant_design  # noqa: F401 - re-exported
from rotorcad.sweep.run import run_sweep as _run_sweep


def edge_analyses() -> dict[Extra, Callable[..., dict[str, Any]]]:
    """Return the sweep analyses of the packages beside the core: the hobbability verdict of ``hob``."""
    from hob.sweep_check import ANALYSES

    return dict(ANALYSES)


def run_sweep(
    plan: SweepPlan,
    folder: Path | None,
    points: Any = None,
    out: Path | None = None,
    scheduler: str | None = None,
    workers: int | None = None,
    batch: int | None = None,
    progress: Callable[[int, int, int], None] | None = None,
    analyses: Mapping[Extra, Callable[..., dict[str, Any]]] | None = None,
    before: Callable[[int, bool], None] | None = None,
) -> SweepOutcome:
    """Run a plan with every analysis, the hobbability verdict included (:func:`rotorcad.sweep.run.run_sweep`).

    Parameters
    ----------
    plan, folder, points, out, scheduler, workers, batch, progress, before
        As for :func:`rotorcad.sweep.run.run_sweep`.
    analyses : mapping, optional
        Default :func:`edge_analyses`.

    Returns
    -------
    SweepOutcome
    """
    return _run_sweep(plan, folder, points, out, scheduler, workers, batch, progress, analyses or edge_analyses(), before=before)


def sweep(
    sweep_file: str | os.PathLike,
    out: str | os.PathLike | None = None,
    scheduler: str | None = None,
    workers: int | None = None,
) -> pd.DataFrame:
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
    if workers is not None and not (isinstance(workers, int) and not isinstance(workers, bool) and workers >= 0):
        raise DesignError("workers", "a whole number of at least 0 (0: in this process)", workers)
    if out is not None and not Path(out).parent.is_dir():
        raise DesignError("out", "a file in an existing folder", str(out))
    plan, folder, points = load_sweep(Path(sweep_file))
    steer = load_steering(Path(sweep_file), plan)
    table = run_sweep(plan, folder, points, None if out is None else Path(out), scheduler, workers).table
    return steer.apply(table) if steer.constraints or steer.objectives else table


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
    from rotorcad.cli.common import load_toml
    from rotorcad.sweep.ranking import steering

    numeric, boolean = sweep_columns(plan)
    return steering(load_toml(path, "sweep file"), numeric, boolean)


def load_sweep(path: Path) -> tuple[SweepPlan, Path, Any]:
    """Read a sweep file, its base design and the base's points (if a points family).

    Parameters
    ----------
    path : Path
        The sweep file (TOML): a ``[sweep]`` table naming the base design file, or a ``[base]``
        table holding it.

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
        A bad or missing base, or a bad sweep.
    """
    from exports.dxf_profile import read_profile, read_profile_points
    from rotorcad.cli.common import load_toml
    from rotorcad.design import rotor_design
    from rotorcad.sweep.plan import sweep_plan

    data = load_toml(path, "sweep file")
    section = data.get("sweep", {})
    if "base" in data and "base" in section:
        raise DesignError("[sweep] base", "either a design file or a [base] table, not both", section["base"])
    if "base" in data:
        base, folder = data["base"], path.parent
    elif isinstance(section.get("base"), str):
        base_path = (path.parent / section["base"]).resolve()
        base, folder = load_toml(base_path, "[sweep] base"), base_path.parent
    else:
        raise DesignError("[sweep] base", "a design file name (or a [base] table)", None, "missing key")
    plan = sweep_plan(data, base)
    settings = rotor_design(base, folder)  # the base must be a valid design
    points = None
    if settings["family"] == "rack-points":
        points = read_profile_points(settings["points"], "[profile] points")
    elif settings["family"] in ("male-points", "female-points"):
        points = read_profile(settings["points"], "[profile] points")
    return plan, folder, points

"""``rotorcad sweep``: thousands of rotor variants built and judged on Dask (CONTRACT.md)."""

from __future__ import annotations

import os
import sys
import time
from dataclasses import replace
from pathlib import Path
from typing import Any

import click
import numpy as np
from rich.console import Console

from rotorcad.cli.common import InputError, Outputs, emit_json, print_table
from rotorcad.cli.progress import Steps, say_long_run
from rotorcad.errors import DesignError
from rotorcad.work import long_run_note, sweep_seconds


@click.command()
@click.argument("sweep_file", type=click.Path(path_type=Path, dir_okay=False))
@click.option(
    "--out",
    type=click.Path(path_type=Path, dir_okay=False),
    required=True,
    help="Parquet file of the results, one row per variant (resumed when it or OUT.parts exists).",
)
@click.option("--csv", type=click.Path(path_type=Path, dir_okay=False), help="Also write the table as CSV.")
@click.option("--scheduler", help="Address of a running dask.distributed scheduler (default: a local cluster).")
@click.option(
    "--workers",
    type=int,
    help="Worker processes of the local cluster; 0 runs every variant in this process, without a cluster. "
    "Default: in this process for fewer than 200 variants to compute (a cluster costs about 5 CPU-s to start), "
    "else one worker per core.",
)
@click.option(
    "--batch",
    type=int,
    help="Variants per Dask task (1..10000). Default: about 8 tasks per worker, at most 50 variants a task; "
    "raise it on a large cluster so that the scheduler handles fewer tasks.",
)
@click.option("--pareto", type=click.Path(path_type=Path, dir_okay=False), help="PNG of the Pareto front of two objectives.")
@click.option(
    "--objectives",
    help="Columns of the Pareto plot: x,y[,colour] (smaller is better, displacement larger). Default: the first two "
    "[objectives] of the sweep file, else blow_hole_area_mm2,contact_line_length_mm,displacement_per_rev_mm3.",
)
@click.option(
    "--top",
    type=int,
    default=10,
    show_default=True,
    help="Feasible variants listed by rank (0..10000; [constraints] and [objectives] of the sweep file).",
)
@click.option(
    "--pareto-csv",
    type=click.Path(path_type=Path, dir_okay=False),
    help="CSV of the variants on the Pareto front of the [objectives] (needs [objectives]).",
)
@click.option(
    "--effects", type=click.Path(path_type=Path, dir_okay=False), help="PNG of each varied value's effect on an objective."
)
@click.option("--objective", default="blow_hole_area_mm2", show_default=True, help="Column of the --effects plot.")
@click.option(
    "--best-designs",
    type=click.Path(path_type=Path, file_okay=False),
    help="Folder to write the design file of the best variant per objective (best_<objective>.toml).",
)
@click.option("--json", "as_json", is_flag=True, help="Print one JSON object on stdout.")
@click.option("--quiet", is_flag=True, help="No progress bar.")
def sweep(
    sweep_file: Path,
    out: Path,
    csv: Path | None,
    scheduler: str | None,
    workers: int | None,
    batch: int | None,
    pareto: Path | None,
    objectives: str | None,
    top: int,
    pareto_csv: Path | None,
    effects: Path | None,
    objective: str,
    best_designs: Path | None,
    as_json: bool,
    quiet: bool,
) -> None:
    """Build and judge every variant of a sweep file as tasks on Dask, streaming one row per variant to Parquet.

    A sweep file holds a base design and the values to vary: lists, ranges, or bounds drawn at random
    or by Latin hypercube. A variant that cannot be built is a row with its reason. Interrupted and
    run again, the sweep computes only what is missing. [constraints] and [objectives] of the file
    mark the feasible variants, the Pareto front and a ranking (columns feasible, pareto, rank).
    """
    from rotorcad.cli.sweep_run import load_steering, load_sweep, run_sweep
    from rotorcad.sweep.run import write_table

    targets = {"--out": out, "--csv": csv, "--pareto": pareto, "--effects": effects, "--pareto-csv": pareto_csv}
    _check_options(workers, scheduler, batch, top, out, targets)
    try:
        plan, folder, points = load_sweep(sweep_file)
        steer = load_steering(sweep_file, plan)
    except DesignError as exc:
        raise InputError(exc.sentence()) from None
    if pareto_csv is not None and not steer.objectives:
        raise InputError("--pareto-csv needs [objectives] in the sweep file (the front of what?).")
    named_objectives = [o.name if o.expression == o.name else f"objective.{o.name}" for o in steer.objectives]
    axes = _axes(plan, steer, named_objectives, objectives, pareto is not None, objective if effects else None)
    bar = Steps("sweep", plan.count, quiet, ("{task.fields[failed]} failed, {task.fields[rate]}/s",), failed=0, rate="-")
    started = time.perf_counter()

    def report(done: int, failed: int, _total: int) -> None:
        rate = done / max(time.perf_counter() - started, 1e-9)
        bar.update(done, failed=failed, rate=f"{rate:.1f}")

    try:
        with bar:
            long_run = _long_run(plan, scheduler, workers, quiet)
            outcome = run_sweep(plan, folder, points, out, scheduler, workers, batch, progress=report, before=long_run)
    except DesignError as exc:
        raise InputError(exc.sentence()) from None
    steered = bool(steer.constraints or steer.objectives)
    if steered:
        outcome = replace(outcome, table=steer.apply(outcome.table))
        write_table(out, outcome.table)  # the Parquet file holds feasible, pareto and rank too
    directions = {n: o.smaller for n, o in zip(named_objectives, steer.objectives, strict=True)}
    pictures = {"--pareto": pareto, "--effects": effects, "axes": axes, "objective": objective, "directions": directions}
    best = outcome.best()
    files = [str(out), *_write_outputs(sweep_file, plan, folder, outcome.table, best, csv, pareto_csv, best_designs, pictures)]
    result = _result(outcome, best, files)
    if steered:
        result["feasible"] = int(outcome.table["feasible"].sum())
        result["pareto_front"] = int(outcome.table["pareto"].sum())
        result["top"] = _top(outcome.table, top, named_objectives)
    if as_json:
        emit_json(result)
    else:
        _print_result(result, outcome)


def _axes(plan, steer, named_objectives: list[str], objectives: str | None, pareto: bool, effects: str | None) -> list[str]:
    """Return the columns of the Pareto plot; refuse --objectives / --objective naming no result column.

    Default: the first two [objectives] of the sweep file, else :data:`DEFAULT_AXES`.
    """
    from rotorcad.sweep.files import sweep_columns

    if objectives is None:
        objectives = ",".join(named_objectives[:2]) if len(named_objectives) >= 2 else DEFAULT_AXES
    axes = [c.strip() for c in objectives.split(",") if c.strip()]
    if pareto and len(axes) not in (2, 3):
        raise InputError(f"--objectives must name 2 or 3 columns (got {objectives!r}).")
    columns = sweep_columns(plan)[0] + [f"objective.{o.name}" for o in steer.objectives if o.expression != o.name]
    for option, wanted in (("--objectives", axes if pareto else []), ("--objective", [effects] if effects is not None else [])):
        unknown = [c for c in wanted if c not in columns]
        if unknown:
            raise InputError(f"{option} must name result columns: {', '.join(columns)} (got {unknown[0]!r}).")
    return axes


def _result(outcome, best: dict, files: list[str]) -> dict[str, Any]:
    """Return the JSON of a sweep (CONTRACT.md): counts, times, failures, the best variants, the files."""
    return {
        "variants": len(outcome.table),
        "computed": outcome.computed,
        "resumed": outcome.resumed,
        "failed": outcome.failed,
        "seconds": outcome.seconds,
        "variants_per_second": outcome.computed / outcome.seconds if outcome.computed else 0.0,
        "cpu_seconds": outcome.cpu_seconds,
        "failures": outcome.failures(),
        "best": best,
        "files": files,
    }


def _long_run(plan, scheduler: str | None, workers: int | None, quiet: bool):
    """Return the callback that says a sweep will take over a minute (:func:`rotorcad.work.sweep_seconds`).

    Called by :func:`rotorcad.sweep.run.run_sweep` with the variants left to compute; the faster
    option is ``--workers`` with one per core when fewer run. Nothing for a ``--scheduler`` (the
    cluster's size is not known here).
    """

    def before(count: int, in_process: bool) -> None:
        if scheduler:
            return
        cores = os.cpu_count() or 1
        used = 1 if in_process else min(workers or cores, cores)
        extras = tuple(e.value for e in plan.extras)
        seconds = sweep_seconds(count, extras, used)
        faster = ("--workers", cores, sweep_seconds(count, extras, cores)) if used < cores else None
        say_long_run(long_run_note(seconds, faster), quiet)

    return before


def _check_options(workers: int | None, scheduler: str | None, batch: int | None, top: int, out: Path, targets: dict) -> None:
    """Refuse bad options and unwritable outputs before any work, naming the option."""
    from exports.atomic import check_writable

    if workers is not None and not 0 <= workers <= 256:
        raise InputError(f"--workers must be a whole number from 0 to 256 (got {workers}; 0 runs in this process).")
    if workers == 0 and scheduler:
        raise InputError("--workers 0 runs in this process: give it or --scheduler, not both.")
    if batch is not None and not 1 <= batch <= 10_000:
        raise InputError(f"--batch must be a whole number from 1 to 10000 (got {batch}).")
    if not 0 <= top <= 10_000:
        raise InputError(f"--top must be a whole number from 0 to 10000 (got {top}).")
    if out.exists() and out.is_dir():
        raise InputError(f"--out must be a file name, but {out} is a folder.")
    if out.suffix.lower() != ".parquet":
        raise InputError(f"--out must name a .parquet file (got {out}); --csv writes CSV beside it.")
    for option, path in targets.items():  # every output checked before hours of work
        if path is not None:
            try:
                check_writable(Path(path), option)
            except DesignError as exc:
                raise InputError(exc.sentence()) from None
    named = [Path(p).resolve() for p in targets.values() if p is not None]
    if len(set(named)) < len(named):
        raise InputError("--out, --csv, --pareto, --effects and --pareto-csv must name different files.")


def _write_outputs(
    sweep_file: Path, plan, folder: Path, table, best: dict, csv, pareto_csv, best_designs, pictures: dict
) -> list[str]:
    """Write the CSV, the pictures, the Pareto CSV and the best designs; return the files written."""
    from rotorcad.sweep.tasks import OBJECTIVES

    writers = Outputs()
    if csv is not None:
        writers.add(csv, lambda p: table.to_csv(p, index=False), "--csv")
    shown = table[table["feasible" if "feasible" in table else "ok"].astype(bool)]  # the feasible variants, or those built
    params = [c for c in table.columns if "." in c and not c.startswith("objective.")]
    axes, case = pictures["axes"], Path(sweep_file).name
    if pictures["--pareto"] is not None:
        from rotorcad.sweep.plots import plot_pareto

        x, y = (shown[c].to_numpy(float) for c in axes[:2])
        colour = shown[axes[2]].to_numpy(float) if len(axes) == 3 else None
        directions = {**OBJECTIVES, **pictures["directions"]}
        smaller = (directions.get(axes[0], True), directions.get(axes[1], True))
        names = (axes[0], axes[1], axes[2] if len(axes) == 3 else None)
        writers.add_figure(pictures["--pareto"], lambda: plot_pareto(x, y, colour, names, smaller, case=case), "--pareto")
    if pictures["--effects"] is not None:
        from rotorcad.sweep.plots import plot_effects

        values = {p: _numeric(shown[p]) for p in params}
        name = pictures["objective"]
        target = shown[name].to_numpy(float)
        writers.add_figure(pictures["--effects"], lambda: plot_effects(values, target, name, case=case), "--effects")
    if pareto_csv is not None:
        front = table[table["pareto"].astype(bool)].sort_values("rank")
        writers.add(pareto_csv, lambda p: front.to_csv(p, index=False), "--pareto-csv")
    if best_designs is not None:
        import tomli_w

        from rotorcad.cli.common import output_folder

        output_folder(best_designs)
        wanted = {chosen["variant"] for chosen in best.values()}
        by_index = {v.index: v for v in plan.iter_variants() if v.index in wanted}  # one pass over the stream
        for column, chosen in best.items():
            design = plan.design(by_index[chosen["variant"]])
            if isinstance(design.get("profile", {}).get("points"), str):  # the points file from anywhere
                design["profile"]["points"] = str((folder / design["profile"]["points"]).resolve())
            path = best_designs / f"best_{column}.toml"
            writers.add(path, lambda p, d=design: Path(p).write_text(tomli_w.dumps(d)), "--best-designs")
    return [str(p) for p in writers.write()]


def _print_result(result: dict[str, Any], outcome) -> None:
    """Print the summary table, the best variants, the top ranks, the failures and the files."""
    shown = {k: v for k, v in result.items() if k != "top"}
    print_table(f"sweep of {result['variants']} variants ({outcome.computed} computed, {outcome.resumed} resumed)", shown)
    console = Console(file=sys.stdout, highlight=False)
    for column, best in result["best"].items():
        values = ", ".join(f"{k} = {v}" for k, v in best.items() if k not in ("variant", "value"))
        console.print(f"best {column}: {best['value']:.6g} (variant {best['variant']}: {values})", markup=False)
    for row in result.get("top", []):
        values = ", ".join(f"{k} = {v:.6g}" if isinstance(v, float) else f"{k} = {v}" for k, v in row.items() if k != "rank")
        console.print(f"rank {row['rank']}: {values}", markup=False)
    for reason, count in result["failures"].items():
        console.print(f"{count} failed: {reason}", markup=False)
    for p in result["files"]:
        console.print(f"wrote {p}", markup=False)


DEFAULT_AXES = "blow_hole_area_mm2,contact_line_length_mm,displacement_per_rev_mm3"


def _top(table, count: int, objective_columns: list[str]) -> list[dict[str, Any]]:
    """Return the ``count`` best feasible variants: rank, variant, on the front, varied values, objectives."""
    ranked = table[table["rank"] > 0].sort_values("rank").head(count)
    params = [c for c in table.columns if "." in c and not c.startswith("objective.")]
    keep = ["rank", "variant", "pareto", *params, *objective_columns]
    return [{k: _plain(row[k]) for k in keep if k in row} for _, row in ranked.iterrows()]


def _plain(value: Any) -> Any:
    return value.item() if hasattr(value, "item") else value


def _numeric(column) -> np.ndarray:
    try:
        return column.to_numpy(float)
    except (TypeError, ValueError):  # a varied name (e.g. the family): its values in order of appearance
        codes = {v: i for i, v in enumerate(dict.fromkeys(column))}
        return np.array([codes[v] for v in column], dtype=float)

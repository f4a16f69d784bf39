"""Running a design sweep on Dask and streaming its rows to Parquet, resumably.

Every batch of variants is one Dask task (:func:`rotorcad.cli.sweep_tasks.evaluate_batch`). By
default a ``dask.distributed.LocalCluster`` of worker processes sized to the machine runs them;
given a scheduler address, the same tasks go to that cluster. Each finished batch is written at
once as a Parquet part file (complete or absent: written to a temporary name and renamed) in the
folder ``OUT.parts`` beside the output; at the end the parts are joined into ``OUT`` in variant
order and the folder is removed. Run again after an interruption, a sweep reads what the parts (and
an earlier ``OUT``) hold and computes only the variants missing, so none is computed twice and none
is lost.

Like any Dask program, a script that starts a sweep with the local cluster needs the
``if __name__ == "__main__":`` guard (the worker processes are spawned and import the script).
"""

from __future__ import annotations

import itertools
import logging
import os
import re
import shutil
import signal
import tempfile
import threading
import time
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import pandas as pd

from rotorcad.cli.sweep_tasks import OBJECTIVES, evaluate_batch
from rotorcad.errors import DesignError
from rotorcad.sweep_plan import SweepPlan, Variant


@dataclass(frozen=True)
class SweepOutcome:
    """What a sweep run did: its table and the counts.

    Parameters
    ----------
    table : pandas.DataFrame
        One row per variant of the plan, in variant order.
    computed : int
        Variants computed in this run.
    resumed : int
        Variants taken from an earlier, interrupted run.
    seconds : float, s
        Wall time of the run.
    """

    table: pd.DataFrame
    computed: int
    resumed: int
    seconds: float

    @property
    def failed(self) -> int:
        """Number of variants that failed (``ok`` false)."""
        return int((~self.table["ok"].astype(bool)).sum()) if len(self.table) else 0

    def failures(self) -> dict[str, int]:
        """Count the failed variants by reason, most frequent first.

        Numbers in a reason stand as '#' so that the same cause with other values counts once.

        Returns
        -------
        dict of str to int
            Reason (with numbers as '#') -> number of variants.
        """
        bad = self.table.loc[~self.table["ok"].astype(bool), "reason"]
        causes = bad.map(lambda r: re.sub(r"-?\d+(\.\d+)?(e[-+]?\d+)?", "#", str(r)))
        return {str(k): int(v) for k, v in causes.value_counts().items()}

    def best(self) -> dict[str, dict[str, Any]]:
        """Return the best variant of every objective column present.

        Only variants that succeeded count, and of those only the ones a hob can make and that do not
        interfere, where those columns exist.

        Returns
        -------
        dict
            Objective column -> ``variant`` (its number), ``value`` and the varied values.
        """
        ok = self.table[self.table["ok"].astype(bool)]
        if "hobbable" in ok:  # best among the variants a hob can make, and that do not interfere
            ok = ok[ok["hobbable"].astype(bool)]
        if "interferes" in ok:
            ok = ok[~ok["interferes"].astype(bool)]
        params = [c for c in self.table.columns if "." in c]
        out = {}
        for column, smaller in OBJECTIVES.items():
            if column not in ok or ok[column].isna().all():
                continue
            row = ok.loc[ok[column].idxmin() if smaller else ok[column].idxmax()]
            out[column] = {"variant": int(row["variant"]), "value": float(row[column]), **{p: _plain(row[p]) for p in params}}
        return out


def _plain(value: Any) -> Any:
    return value.item() if hasattr(value, "item") else value


EARLIER = "a Parquet file of an earlier sweep (or a new name)"


def parts_folder(out: Path) -> Path:
    """Return the folder where the finished batches of a sweep writing ``out`` are kept until it ends.

    Parameters
    ----------
    out : Path
        The sweep's Parquet file.

    Returns
    -------
    Path
        ``OUT.parts`` beside it.
    """
    return out.with_name(out.name + ".parts")


def _done(out: Path | None, keys: dict[str, int]) -> pd.DataFrame:
    """Read the rows already computed for this plan from ``out`` and its parts folder.

    The rows are numbered as the plan numbers them. Rows of another sweep (another base design, other
    analyses, other values) are refused with :class:`DesignError`, not dropped: ``out`` would lose
    them.
    """
    frames = []
    if out is not None:
        sources = [out] if out.is_file() else []
        folder = parts_folder(out)
        if folder.is_dir():
            sources += sorted(folder.glob("part-*.parquet"))
        for path in sources:
            try:
                frame = pd.read_parquet(path)
            except Exception as exc:  # not a Parquet table we wrote: refuse rather than overwrite it
                reason = " ".join(str(exc).split())[:160]
                raise DesignError("--out", EARLIER, str(path), reason) from None
            if "key" not in frame:
                raise DesignError("--out", EARLIER, str(path), "it has no key column")
            foreign = int((~frame["key"].isin(keys)).sum())
            if foreign:
                raise DesignError(
                    "--out",
                    "a new file name, or the results of this same sweep",
                    str(path),
                    f"{foreign} of its rows are of another sweep (its base design, analyses or values differ)",
                )
            frames.append(frame)
    if not frames:
        return pd.DataFrame()
    done = pd.concat(frames, ignore_index=True).drop_duplicates("key")
    done["variant"] = done["key"].map(keys)
    return done


def _write_part(folder: Path, rows: list[dict[str, Any]]) -> None:
    fd, tmp = tempfile.mkstemp(prefix=".part-", suffix=".tmp", dir=folder)
    os.close(fd)
    try:
        pd.DataFrame(rows).to_parquet(tmp, index=False)
        os.chmod(tmp, 0o666 & ~_umask())
        os.replace(tmp, folder / f"part-{rows[0]['variant']:09d}.parquet")
    except BaseException:
        Path(tmp).unlink(missing_ok=True)
        raise


def _client(scheduler: str | None, workers: int | None):
    """Start a Dask client: of the cluster at ``scheduler``, or of a local cluster of worker processes.

    Returns the client and the local cluster (None for a scheduler's).
    """
    # the worker processes read their log levels from the environment when they start
    os.environ.setdefault("DASK_LOGGING__DISTRIBUTED", "error")
    from dask.distributed import Client, LocalCluster

    # distributed logs INFO lines (connections closed, workers retired) on stderr: only errors are the user's business
    for name in ["distributed", *(n for n in logging.root.manager.loggerDict if n.startswith("distributed."))]:
        logging.getLogger(name).setLevel(logging.ERROR)

    if scheduler:
        try:
            return Client(scheduler, timeout="10s"), None
        except (OSError, TimeoutError) as exc:
            raise DesignError(
                "--scheduler", "the address of a running dask.distributed scheduler", scheduler, str(exc)[:80]
            ) from None
    n = workers or os.cpu_count() or 1
    # the workers start with Ctrl-C ignored (they inherit it): the sweep stops them itself, and
    # their tracebacks would bury the one line a user is owed
    main = threading.current_thread() is threading.main_thread()
    previous = signal.signal(signal.SIGINT, signal.SIG_IGN) if main else None
    try:
        cluster = LocalCluster(
            n_workers=n,
            threads_per_worker=1,
            processes=True,
            dashboard_address=None,
            silence_logs=logging.CRITICAL,
            memory_limit=0,
        )
    finally:
        if main:
            signal.signal(signal.SIGINT, previous)
    return Client(cluster), cluster


def run_sweep(
    plan: SweepPlan,
    folder: Path | None,
    points: Any = None,
    out: Path | None = None,
    scheduler: str | None = None,
    workers: int | None = None,
    batch: int | None = None,
    progress: Callable[[int, int, int], None] | None = None,
) -> SweepOutcome:
    """Compute every variant of ``plan`` not yet in ``out``; return the whole table.

    Parameters
    ----------
    plan : SweepPlan
        The sweep.
    folder : Path, optional
        The base design's folder (for a relative points file).
    points : (n, 2) float array or list of Curve, optional
        The base design's profile points, already read (mm).
    out : Path, optional
        Parquet file to write (resumed if it or its parts folder exists); None keeps all in memory.
    scheduler : str, optional
        Address of a running ``dask.distributed`` scheduler; default a local cluster.
    workers : int, optional
        Worker processes of the local cluster (default: one per core).
    batch : int, optional
        Variants per task (default: about eight tasks per worker, at most 50 variants a task).
    progress : callable, optional
        Called with (done, failed, total) after every batch.

    Returns
    -------
    SweepOutcome
        The table of all variants (earlier and new) and the counts.

    Raises
    ------
    DesignError
        An ``out`` that holds something other than this sweep's rows, or a scheduler that cannot be
        reached.
    """
    start = time.perf_counter()
    variants = plan.variants()
    keys = {v.key: v.index for v in variants}
    earlier = _done(out, keys)
    done_keys = set(earlier["key"]) if len(earlier) else set()
    todo = [v for v in variants if v.key not in done_keys]
    rows: list[dict[str, Any]] = []
    failed = int((~earlier["ok"].astype(bool)).sum()) if len(earlier) else 0
    if todo:
        parts = parts_folder(out) if out is not None else None
        if parts is not None:
            parts.mkdir(exist_ok=True)
        client, cluster = _client(scheduler, workers)
        try:
            n_workers = max(1, len(client.scheduler_info().get("workers", {})) or (workers or os.cpu_count() or 1))
            size = batch or max(1, min(50, len(todo) // (8 * n_workers)))
            batches = [todo[i : i + size] for i in range(0, len(todo), size)]
            from dask.distributed import as_completed

            # at most four tasks a worker in flight: a small graph however large the sweep
            pending = iter(batches)
            submit = dict(
                base=plan.base,
                folder=None if folder is None else str(folder),
                points=points,
                extras=plan.extras,
                clearance=plan.clearance,
                pure=False,
            )
            queue = as_completed([client.submit(evaluate_batch, b, **submit) for b in itertools.islice(pending, 4 * n_workers)])
            done = len(earlier)
            for future in queue:
                batch_rows = future.result()
                future.release()
                following = next(pending, None)
                if following is not None:
                    queue.add(client.submit(evaluate_batch, following, **submit))
                if parts is not None:
                    _write_part(parts, batch_rows)
                else:
                    rows.extend(batch_rows)
                done += len(batch_rows)
                failed += sum(not r["ok"] for r in batch_rows)
                if progress:
                    progress(done, failed, len(variants))
        finally:
            if cluster is not None:
                client.retire_workers(close_workers=True)  # workers first: no heartbeat to a closed scheduler
            client.close()
            if cluster is not None:
                cluster.close()
    table = _done(out, keys) if out is not None else pd.concat([earlier, pd.DataFrame(rows)], ignore_index=True)
    if len(table):
        table = table.sort_values("variant", kind="stable").reset_index(drop=True)
    if out is not None:
        _replace(out, table)
        shutil.rmtree(parts_folder(out), ignore_errors=True)
    return SweepOutcome(table, len(todo), len(variants) - len(todo), time.perf_counter() - start)


def _replace(out: Path, table: pd.DataFrame) -> None:
    """Write ``out`` whole (a temporary name renamed over it)."""
    fd, tmp = tempfile.mkstemp(prefix=f".{out.name}.", suffix=".tmp", dir=out.parent)
    os.close(fd)
    try:
        table.to_parquet(tmp, index=False)
        os.chmod(tmp, 0o666 & ~_umask())
        os.replace(tmp, out)
    except BaseException:
        Path(tmp).unlink(missing_ok=True)
        raise


def _umask() -> int:
    mask = os.umask(0)
    os.umask(mask)
    return mask


def sweep(
    sweep_file: str | os.PathLike,
    out: str | os.PathLike | None = None,
    scheduler: str | None = None,
    workers: int | None = None,
) -> pd.DataFrame:
    """Run a design sweep file (see :mod:`rotorcad.sweep_plan`) and return its table.

    Parameters
    ----------
    sweep_file : path
        The sweep (TOML).
    out : path, optional
        Parquet file to stream to and resume from.
    scheduler : str, optional
        Address of a running ``dask.distributed`` scheduler (default: a local cluster).
    workers : int, optional
        Local worker processes (default: one per core).

    Returns
    -------
    pandas.DataFrame
        One row per variant: its number and key, the varied values (``table.key`` columns), ``ok``,
        ``reason``, ``seconds`` and the results with their unit in the column name.

    Raises
    ------
    DesignError
        A bad sweep file or base design, ``workers`` below 1, or ``out`` in a folder that does not
        exist.
    """
    if workers is not None and not (isinstance(workers, int) and workers >= 1):
        raise DesignError("workers", "a whole number of at least 1", workers)
    if out is not None and not Path(out).parent.is_dir():
        raise DesignError("out", "a file in an existing folder", str(out))
    plan, folder, points = load_sweep(Path(sweep_file))
    return run_sweep(plan, folder, points, None if out is None else Path(out), scheduler, workers).table


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
    from rotorcad.sweep_plan import sweep_plan

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


def variant_design(plan: SweepPlan, variant: Variant) -> dict[str, Any]:
    """Return the design mapping of one variant (to write it as a design file).

    Parameters
    ----------
    plan : SweepPlan
        The sweep.
    variant : Variant
        One of its variants.

    Returns
    -------
    dict
        The base design with the variant's values put in.
    """
    from rotorcad.sweep_plan import apply

    return apply(plan.base, variant.values)

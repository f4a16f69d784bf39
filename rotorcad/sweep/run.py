"""Running a design sweep, in this process or on Dask, and streaming its rows to Parquet, resumably.

Every batch of variants is one task (:func:`rotorcad.sweep.tasks.evaluate_batch`). With
``workers=0`` the batches run one after the other in this process (no cluster to start: the
choice for a small sweep or a script). Otherwise a ``dask.distributed.LocalCluster`` of worker
processes sized to the machine runs them; given a scheduler address, the same tasks go to that
cluster. Each finished batch is written at once as a Parquet part file (complete or absent:
written to a temporary name and renamed) in the folder ``OUT.parts`` beside the output; at the end
the parts are joined into ``OUT`` in variant order and the folder is removed. Run again after an
interruption, a sweep reads what the parts (and an earlier ``OUT``) hold and computes only the
variants missing, so none is computed twice and none is lost.

The plan is read as a stream (:meth:`rotorcad.sweep.plan.SweepPlan.variants`): what the run holds
grows with the batches in flight and the rows done, not with the variants planned.

Like any Dask program, a script that starts a sweep with the local cluster needs the
``if __name__ == "__main__":`` guard (the worker processes are spawned and import the script).
"""

from __future__ import annotations

import contextlib
import itertools
import logging
import os
import re
import shutil
import signal
import socket
import tempfile
import threading
import time
import warnings
from collections.abc import Callable, Iterator, Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any
from urllib.parse import urlsplit

import pandas as pd

from rotorcad.errors import DesignError, InputFileError
from rotorcad.sweep.plan import Extra, SweepPlan, Variant
from rotorcad.sweep.tasks import OBJECTIVES, Analysis, evaluate_batch


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
    cpu_seconds : float, s
        CPU time of the variants computed in this run (the sum of their ``seconds`` column is
        their wall time inside the workers; this is the process CPU time of an in-process run and
        the workers' wall time otherwise).
    """

    table: pd.DataFrame
    computed: int
    resumed: int
    seconds: float
    cpu_seconds: float = 0.0

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
        if not len(self.table):
            return {}
        bad = self.table.loc[~self.table["ok"].astype(bool), "reason"]
        causes = bad.map(lambda r: re.sub(r"-?\d+(\.\d+)?(e[-+]?\d+)?", "#", str(r)))
        return {str(k): int(v) for k, v in causes.value_counts().items()}

    def best(self) -> dict[str, dict[str, Any]]:
        """Return the best variant of every objective column present.

        Only variants that succeeded count, and of those only the ones a hob can make and that do not
        interfere, where those columns exist, and that meet the constraints (a ``feasible`` column,
        :mod:`rotorcad.sweep.ranking`), where they were stated.

        Returns
        -------
        dict
            Objective column -> ``variant`` (its number), ``value`` and the varied values.
        """
        if not len(self.table):
            return {}
        ok = self.table[self.table["ok"].astype(bool)]
        if "hobbable" in ok:  # best among the variants a hob can make, and that do not interfere
            ok = ok[ok["hobbable"].fillna(False).astype(bool)]
        if "interferes" in ok:
            ok = ok[~ok["interferes"].fillna(True).astype(bool)]
        if "feasible" in ok:
            ok = ok[ok["feasible"].astype(bool)]
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

IN_PROCESS_BELOW = 200
"""Fewer variants to compute than this run in this process when no worker count is given: starting
a local cluster costs about 5 CPU-seconds, the time of some 200 variants."""


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


def _read_earlier(out: Path | None) -> pd.DataFrame:
    """Read the rows already computed from ``out`` and its parts folder (any sweep's: checked later)."""
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
                raise InputFileError("--out", EARLIER, str(path), reason) from None
            if "key" not in frame:
                raise InputFileError("--out", EARLIER, str(path), "it has no key column")
            frames.append(frame)
    if not frames:
        return pd.DataFrame()
    return pd.concat(frames, ignore_index=True).drop_duplicates("key")


def _number_earlier(plan: SweepPlan, earlier: pd.DataFrame) -> pd.DataFrame:
    """Give the earlier rows their numbers in the plan; refuse rows of another sweep.

    One pass over the plan's stream; what is held is the earlier rows' keys only. Rows of another
    sweep (another base design, other analyses, other values) are refused with
    :class:`DesignError`, not dropped: ``out`` would lose them.
    """
    if not len(earlier):
        return earlier
    wanted = set(earlier["key"])
    index: dict[str, int] = {}
    for v in plan.iter_variants():
        if v.key in wanted:
            index[v.key] = v.index
            if len(index) == len(wanted):
                break
    foreign = len(wanted) - len(index)
    if foreign:
        raise InputFileError(
            "--out",
            "a new file name, or the results of this same sweep",
            None,
            f"{foreign} of its rows are of another sweep (its base design, analyses or values differ)",
        )
    earlier = earlier.copy()
    earlier["variant"] = earlier["key"].map(index)
    return earlier


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


def check_scheduler(address: str, timeout: float = 2.0) -> None:
    """Refuse at once a scheduler address that is malformed or where nothing listens.

    Parameters
    ----------
    address : str
        ``tcp://HOST:PORT`` (or ``HOST:PORT``).
    timeout : float, s
        How long to wait for the connection.

    Raises
    ------
    DesignError
        Naming ``--scheduler``: the address cannot be parsed, or no connection within ``timeout``.
    """
    allowed = "the address of a running dask.distributed scheduler, tcp://HOST:PORT"
    text = address if "://" in address else "tcp://" + address
    try:
        parts = urlsplit(text)
        host, port = parts.hostname, parts.port
    except ValueError:
        host, port = None, None
    if parts.scheme not in ("tcp", "tls") or not host or port is None:
        raise DesignError("--scheduler", allowed, address)
    try:
        with socket.create_connection((host, port), timeout=timeout):
            pass
    except OSError as exc:
        raise DesignError("--scheduler", allowed, address, f"nothing answers there ({exc.strerror or exc})") from None


def _quiet_dask() -> None:
    """Keep Dask's and multiprocessing's chatter off stderr: only errors are the user's business."""
    # the worker processes read their log levels from the environment when they start
    os.environ.setdefault("DASK_LOGGING__DISTRIBUTED", "error")
    # the worker processes' resource tracker unlinks the semaphores of a killed sweep itself; its
    # warning that it does so ("leaked semaphore objects to clean up") is not the user's business
    quiet = "ignore:resource_tracker:UserWarning"
    current = os.environ.get("PYTHONWARNINGS", "")
    if quiet not in current:
        os.environ["PYTHONWARNINGS"] = ",".join(w for w in (current, quiet) if w)
    for name in ["distributed", *(n for n in logging.root.manager.loggerDict if n.startswith("distributed."))]:
        logging.getLogger(name).setLevel(logging.ERROR)


def _client(scheduler: str | None, workers: int | None):
    """Start a Dask client: of the cluster at ``scheduler``, or of a local cluster of worker processes.

    Returns the client and the local cluster (None for a scheduler's).
    """
    _quiet_dask()
    from dask.distributed import Client, LocalCluster

    if scheduler:
        check_scheduler(scheduler)
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
        with warnings.catch_warnings(), _lean_workers():
            # without a dashboard the scheduler still serves its health check over HTTP, on port 8787
            # or, when another dashboard holds it, any free port: its 4-line warning about the port
            # is not the user's business (nothing of the sweep listens there)
            warnings.filterwarnings("ignore", message="Port .* is already in use", category=UserWarning)
            cluster = LocalCluster(
                n_workers=n,
                threads_per_worker=1,
                processes=True,
                dashboard_address=None,  # no dashboard
                worker_dashboard_address=None,
                silence_logs=logging.CRITICAL,
                memory_limit=0,
            )
    finally:
        if main:
            signal.signal(signal.SIGINT, previous)
    return Client(cluster), cluster


LEAN_WORKERS = {
    "distributed.worker.profile.enabled": False,
    "distributed.admin.tick.interval": "1s",
}
"""Dask settings of the local cluster's workers (dask.config keys): no statistical profiler sampling
the task's stack every 10 ms (a sweep's tasks are its own code, profiled by cProfile when needed),
the event loop's health tick every second instead of every 20 ms; and the workers started without
the nanny's ``MALLOC_TRIM_THRESHOLD_=65536`` (:func:`_lean_workers`), which returns every freed
64 kB to the system: a variant allocates and frees arrays of that size by the hundred (8 % more CPU
measured in one process). Inside the workers, 1000 new profiles at load 12: the worker processes
took 12.18 ms of CPU a variant with dask's settings (its compute thread 10.30), 9.89 with these (9.56)."""


@contextlib.contextmanager
def _lean_workers() -> Iterator[None]:
    """Start the local cluster's workers with :data:`LEAN_WORKERS` (the user's own dask settings otherwise kept)."""
    import dask

    spawn = dict(dask.config.get("distributed.nanny.pre-spawn-environ", {}) or {})
    spawn.pop("MALLOC_TRIM_THRESHOLD_", None)
    with dask.config.set({**LEAN_WORKERS, "distributed.nanny.pre-spawn-environ": spawn}):
        yield


def _batches(plan: SweepPlan, done: set[str], size: int) -> Iterator[list[Variant]]:
    """Yield the variants not in ``done``, ``size`` at a time, reading the plan as a stream."""
    todo = (v for v in plan.iter_variants() if v.key not in done)
    while batch := list(itertools.islice(todo, size)):
        yield batch


def run_sweep(
    plan: SweepPlan,
    folder: Path | None,
    points: Any = None,
    out: Path | None = None,
    scheduler: str | None = None,
    workers: int | None = None,
    batch: int | None = None,
    progress: Callable[[int, int, int], None] | None = None,
    analyses: Mapping[Extra, Analysis] | None = None,
    before: Callable[[int, bool], None] | None = None,
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
        Worker processes of the local cluster; 0 runs every variant in this process, without Dask.
        Default: in this process for fewer than :data:`IN_PROCESS_BELOW` variants to compute, else
        one worker per core.
    batch : int, optional
        Variants per task (default: about eight tasks per worker, at most 50 variants a task).
    progress : callable, optional
        Called with (done, failed, total) after every batch.
    analyses : mapping of Extra to callable, optional
        Optional analyses the core does not make itself (the hobbability verdict of
        ``hob.sweep_check``): required when the plan asks for them.
    before : callable, optional
        Called with (variants to compute, whether they run in this process) once the earlier rows
        are counted, before any cluster starts or variant is computed (the command's note of a
        long run).

    Returns
    -------
    SweepOutcome
        The table of all variants (earlier and new) and the counts.

    Raises
    ------
    DesignError
        An ``out`` that holds something other than this sweep's rows, a scheduler that cannot be
        reached, or an analysis the plan asks for that was not given.
    """
    from rotorcad.sweep.tasks import ANALYSES

    start, cpu_start = time.perf_counter(), time.process_time()
    missing = [e.value for e in plan.extras if e not in {**ANALYSES, **(analyses or {})}]
    if missing:
        raise DesignError("[sweep] compute", "analyses this run can make", missing[0], "pass analyses=hob.sweep_check.ANALYSES")
    earlier = _number_earlier(plan, _read_earlier(out))
    done_keys = set(earlier["key"]) if len(earlier) else set()
    todo_count = plan.count - len(done_keys)
    tally = _Tally(done=len(earlier), failed=int((~earlier["ok"].astype(bool)).sum()) if len(earlier) else 0)
    in_process = not scheduler and (workers == 0 or (workers is None and todo_count < IN_PROCESS_BELOW))
    if before is not None and todo_count:
        before(todo_count, in_process)
    if todo_count:
        submit = _task_arguments(plan, folder, points, analyses)
        pending = lambda size: _batches(plan, done_keys, size)  # noqa: E731 - the stream, once the batch size is known
        parts = parts_folder(out) if out is not None else None
        _compute(pending, todo_count, submit, _Where(parts, scheduler, workers, batch, in_process), tally, progress, plan.count)
    table = _whole_table(out, earlier, tally.rows)
    cpu = time.process_time() - cpu_start if in_process else tally.worker_seconds
    return SweepOutcome(table, todo_count, len(done_keys), time.perf_counter() - start, cpu)


def _task_arguments(plan: SweepPlan, folder: Path | None, points: Any, analyses: Mapping[Extra, Analysis] | None) -> dict:
    """Return what every batch's task gets beside its variants (:func:`rotorcad.sweep.tasks.evaluate_batch`)."""
    return dict(
        base=plan.base,
        folder=None if folder is None else str(folder),
        points=points,
        extras=plan.extras,
        clearance=plan.clearance,
        analyses=dict(analyses or {}),
        families=plan.families,
    )


@dataclass
class _Tally:
    """What a run has done so far.

    Variants done (earlier ones included) and failed, the workers' seconds, and the rows kept in
    memory when there is no output file.
    """

    done: int = 0
    failed: int = 0
    worker_seconds: float = 0.0
    rows: list[dict[str, Any]] = field(default_factory=list)


@dataclass(frozen=True)
class _Where:
    """Where and how the variants run.

    The parts folder (None: rows in memory), the scheduler or the local workers, the batch size,
    whether in this process.
    """

    parts: Path | None
    scheduler: str | None
    workers: int | None
    batch: int | None
    in_process: bool


def _compute(
    pending: Callable[[int], Iterator[list[Variant]]],
    todo_count: int,
    submit: dict[str, Any],
    where: _Where,
    tally: _Tally,
    progress: Callable[[int, int, int], None] | None,
    total: int,
) -> None:
    """Compute the variants not done, in batches, in this process or on Dask; each batch's rows to a part file."""
    client = cluster = None
    made_parts = False
    parts = where.parts

    def finished(batch_rows: list[dict[str, Any]]) -> None:
        if parts is not None:
            _write_part(parts, batch_rows)
        else:
            tally.rows.extend(batch_rows)
        tally.done += len(batch_rows)
        tally.failed += sum(not r["ok"] for r in batch_rows)
        tally.worker_seconds += sum(r["seconds"] for r in batch_rows)
        if progress:
            progress(tally.done, tally.failed, total)

    try:
        n_workers = 1
        if not where.in_process:
            client, cluster = _client(where.scheduler, where.workers)  # a bad scheduler is refused before any file
            n_workers = max(1, len(client.scheduler_info().get("workers", {})) or (where.workers or os.cpu_count() or 1))
        if parts is not None and not parts.is_dir():
            parts.mkdir()
            made_parts = True
        batches = pending(where.batch or max(1, min(50, todo_count // (8 * n_workers))))
        if where.in_process:
            for variants in batches:
                finished(evaluate_batch(variants, **submit))
        else:
            _on_dask(client, batches, submit, n_workers, finished)
    except BaseException:
        if made_parts and parts is not None and not any(parts.iterdir()):
            shutil.rmtree(parts, ignore_errors=True)  # nothing computed: no folder left behind
        raise
    finally:
        if client is not None:
            if cluster is not None:
                client.retire_workers(close_workers=True)  # workers first: no heartbeat to a closed scheduler
            client.close()
        if cluster is not None:
            cluster.close()


def _on_dask(client, batches: Iterator[list[Variant]], submit: dict[str, Any], n_workers: int, finished) -> None:
    """Run the batches as Dask tasks, at most four a worker in flight (a small graph however large the sweep)."""
    from dask.distributed import as_completed

    first = itertools.islice(batches, 4 * n_workers)
    queue = as_completed([client.submit(evaluate_batch, b, **submit, pure=False) for b in first])
    for future in queue:
        batch_rows = future.result()
        future.release()
        following = next(batches, None)
        if following is not None:
            queue.add(client.submit(evaluate_batch, following, **submit, pure=False))
        finished(batch_rows)


def _whole_table(out: Path | None, earlier: pd.DataFrame, rows: list[dict[str, Any]]) -> pd.DataFrame:
    """Join the earlier rows and this run's in variant order; write ``out`` whole and remove its parts folder."""
    if out is not None:
        table = _read_earlier(out)  # this run's rows carry their number; earlier rows are renumbered
        if len(earlier) and len(table):
            renumbered = table["key"].map(dict(zip(earlier["key"], earlier["variant"], strict=True)))
            table["variant"] = renumbered.fillna(table["variant"]).astype("int64")
    else:
        table = pd.concat([earlier, pd.DataFrame(rows)], ignore_index=True) if len(earlier) else pd.DataFrame(rows)
    if len(table):
        table = table.sort_values("variant", kind="stable").reset_index(drop=True)
    if out is not None:
        write_table(out, table)
        shutil.rmtree(parts_folder(out), ignore_errors=True)
    return table


def write_table(out: Path, table: pd.DataFrame) -> None:
    """Write a sweep's table to the Parquet file ``out`` whole (a temporary name renamed over it).

    Parameters
    ----------
    out : Path
        The Parquet file.
    table : pandas.DataFrame
        The table.
    """
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
    return plan.design(variant)

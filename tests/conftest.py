"""What every test file shares: how many processes run the suite, one BLAS thread in each.

The suite runs on pytest-xdist's worker processes (``-n auto`` in pyproject's pytest options, with
``--dist worksteal``: each worker starts on its own contiguous half of the tests, so that a module's
fixtures are mostly built once, and takes tests from the other's end when it runs out). ``auto`` is
decided here: one worker per CPU this process may use, none (the tests in this process) on one CPU,
and none in a pytest started by a test inside a worker (tests/test_fuzz_cli.py runs one), which
would otherwise start workers of its own. ``PYTEST_XDIST_AUTO_NUM_WORKERS`` overrides it, as in
pytest-xdist; ``-n 0`` runs everything in this process.

Each test process (and each command a test starts, which inherits the environment) does its linear
algebra on one thread: the workers already take every CPU, and OpenBLAS's threads waiting for work
on top of them cost more than they save on this suite's small systems (the coupling film test
tests/test_coupling.py::test_ehl_capacity_rises_with_viscosity_and_speed took 32 s of CPU with
OpenBLAS's default threads on a loaded 2-core machine, 0.5 s with one). The benchmarks set the same
variables. Set before numpy is imported (this file is read before any test module); a variable the
user set is kept.

An expensive fixture that a module's tests need on both workers (a module split between them, as
the last one is when a worker takes the other's last tests) is built once per run through
``built_once``: the first worker builds it and leaves it pickled in the run's temporary folder, the
other waits for it and reads it; within a process it is kept for the other modules that ask (in one
process, ``-n 0``, too). The pairs from points that several modules analyse are shared the same way
(tests/shared_runs.py). Nothing is kept from one run to the next.

Python's cyclic garbage collector runs a tenth as often in the test processes (a collection of the
youngest generation after 10000 net allocations of container objects instead of 700), and what the
collection of the tests leaves (the test modules, their tables and functions) is moved out of its
reach (``gc.freeze``): the module fixtures keep large heaps alive (every sample's pairs, fits and
analyses), and the collector walked them again and again without finding anything to free (measured
on tests/test_hob_points_samples.py alone, one process, loaded machine: 3.15 s of 14.7 s of CPU in
7389 collections, 0.20 s of 11.0 s in 380 after). Garbage is still collected, only in larger batches;
the commands the tests start run with Python's own setting.

Where Python is told not to write bytecode beside the sources (``PYTHONDONTWRITEBYTECODE``, as on
the project's CI machine), every test process would compile the project's modules and rewrite the
test modules' asserts (pytest) anew: 4 s of CPU a worker of the suite's 7.4 s collection. The
bytecode is then kept in pytest's own cache folder instead (``.pytest_cache/bytecode``, through
``sys.pycache_prefix``; ``PYTHONPYCACHEPREFIX`` for the commands the tests start), never beside a
source file; a prefix the user set is used as it is.
"""

from __future__ import annotations

import gc
import os
import sys
from collections.abc import Callable
from pathlib import Path
from typing import Any

import pytest

for _variable in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_variable, "1")

gc.set_threshold(10_000, 10, 10)  # Python's default (700, 10, 10): see the module's docstring

if sys.dont_write_bytecode:  # set before any test module is imported (and rewritten)
    sys.pycache_prefix = os.environ.setdefault(
        "PYTHONPYCACHEPREFIX", str(Path(__file__).resolve().parents[1] / ".pytest_cache" / "bytecode")
    )
    sys.dont_write_bytecode = False


def pytest_collection_finish(session: pytest.Session) -> None:
    """Move what the collection made (test modules, parameter tables) out of the garbage collector's reach."""
    gc.collect()
    gc.freeze()


def _usable_cpus() -> int:
    """The CPUs this process may run on (its affinity, e.g. a container's limit), else all."""
    try:
        return len(os.sched_getaffinity(0))
    except AttributeError:  # not on Linux
        return os.cpu_count() or 1


@pytest.hookimpl(tryfirst=True, optionalhook=True)
def pytest_xdist_auto_num_workers(config: pytest.Config) -> int:
    """The number of workers for ``-n auto`` (pytest-xdist's hook; 0 runs the tests in this process)."""
    given = os.environ.get("PYTEST_XDIST_AUTO_NUM_WORKERS")
    if given:
        return int(given)
    if os.environ.get("PYTEST_XDIST_WORKER"):  # a pytest run by a test inside a worker
        return 0
    cpus = _usable_cpus()
    return cpus if cpus > 1 else 0


@pytest.hookimpl(optionalhook=True)
def pytest_xdist_make_scheduler(config: pytest.Config, log: Any) -> Any:
    """pytest-xdist's ``worksteal``, its first halves cut where one test module ends (else None: xdist's own).

    The first share of each worker ends at the module boundary nearest to an even split, so that no
    module is cut there and its module fixtures and cached cases (tests/test_hob_points_samples.py's
    pairs from points, 9-10 s of CPU on each worker when it was the module cut) are made by one worker;
    the tests taken from the other's end at the close are xdist's own steals.
    """
    if config.getvalue("dist") != "worksteal":
        return None
    from xdist.scheduler import WorkStealingScheduling

    if not callable(getattr(WorkStealingScheduling, "_send_tests", None)):  # a private method: xdist's own if it goes
        return None

    class ModuleWholeWorkStealing(WorkStealingScheduling):
        def _send_tests(self, node: Any, num: int) -> None:
            if 0 < num < len(self.pending) and self.collection is not None:
                files = [self.collection[i].split("::", 1)[0] for i in self.pending]
                ends = [i for i in range(1, len(files)) if files[i] != files[i - 1]]
                if ends:
                    num = min(ends, key=lambda i: abs(i - num))
            super()._send_tests(node, num)

    return ModuleWholeWorkStealing(config, log)


@pytest.fixture(scope="session", autouse=True)
def shared_root(tmp_path_factory: pytest.TempPathFactory) -> Path | None:
    """The run's folder that the workers share (above each worker's own), for ``built_once`` and
    tests/shared_runs.py; None without workers or without POSIX file locks (this process only)."""
    import shared_runs  # here, not above: it imports numpy and rotorcad (the settings above come first)

    if shared_runs.fcntl is None or not os.environ.get("PYTEST_XDIST_WORKER"):
        return None
    shared_runs.ROOT = tmp_path_factory.getbasetemp().parent
    return shared_runs.ROOT


@pytest.fixture(scope="session")
def built_once(shared_root: Path | None) -> Callable[[str, Callable[[], Any]], Any]:
    """``built_once(name, build)``: ``build()`` made once in this run for all the test modules and all the
    workers (pickled in the run's temporary folder, kept in each process; tests/shared_runs.py's ``once``)."""
    import shared_runs

    return shared_runs.once


@pytest.fixture(scope="session")
def rack_report(tmp_path_factory: pytest.TempPathFactory, built_once) -> tuple[dict, Path]:
    """``rotorcad report samples/rack_involute_5_6.toml --out report.html --files files --json``, run
    once in this run (some 2.5 s of CPU) for the tests that read its page: tests/test_report.py (the
    page in Chromium, the files) and tests/test_units_declared.py (the units on the page). Returns
    the command's JSON and the page's path."""

    def build() -> tuple[dict, Path]:
        import contextlib
        import io
        import json

        from rotorcad.cli.main import main

        folder = tmp_path_factory.mktemp("rack-report")
        page = folder / "report.html"
        design = Path(__file__).resolve().parents[1] / "samples" / "rack_involute_5_6.toml"
        out = io.StringIO()
        with contextlib.redirect_stdout(out):
            code = main(["report", str(design), "--out", str(page), "--files", str(folder / "files"), "--json"])
        assert code == 0, out.getvalue()
        return json.loads(out.getvalue()), page

    return built_once("conftest.rack_report", build)

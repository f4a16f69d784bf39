"""The command line's side of a sweep: ``hob``'s verdict and ``exports``' readers passed to the core.

Reading a sweep file and running it are the core's (:mod:`rotorcad.sweep.files`,
:mod:`rotorcad.sweep.run`); the command passes in what the packages beside the core add: the
hobbability verdict (:data:`hob.sweep_check.ANALYSES`) and the readers of points files and
drawings (:mod:`exports.extensions`). The names that lived here before are re-exported.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from pathlib import Path
from typing import Any

from rotorcad.sweep.files import load_steering, sweep_columns  # noqa: F401 - re-exported
from rotorcad.sweep.files import load_sweep as _load_sweep
from rotorcad.sweep.files import sweep as _sweep
from rotorcad.sweep.plan import Extra, SweepPlan
from rotorcad.sweep.run import SweepOutcome, parts_folder, variant_design  # noqa: F401 - re-exported
from rotorcad.sweep.run import run_sweep as _run_sweep


def edge_analyses() -> dict[Extra, Callable[..., dict[str, Any]]]:
    """Return the sweep analyses of the packages beside the core: the hobbability verdict of ``hob``."""
    from hob.sweep_check import ANALYSES

    return dict(ANALYSES)


def edge_readers() -> dict[str, Callable[[Path, str], Any]]:
    """Return the readers of a points family's file: ``exports``' CSV points and DXF drawings."""
    import exports.extensions  # noqa: F401 - registers the readers
    from rotorcad.extensions import PROFILE_READERS

    return dict(PROFILE_READERS)


def load_sweep(path: Path) -> tuple[SweepPlan, Path, Any]:
    """Read a sweep file, its base design and the base's points (:func:`rotorcad.sweep.files.load_sweep`)."""
    return _load_sweep(path, edge_readers())


def sweep(sweep_file: Any, out: Any = None, scheduler: str | None = None, workers: int | None = None) -> Any:
    """Run a sweep file with ``hob``'s verdict and ``exports``' readers (:func:`rotorcad.sweep.files.sweep`)."""
    return _sweep(sweep_file, out, scheduler, workers, analyses=edge_analyses(), read_points=edge_readers())


def run_sweep(
    plan: SweepPlan, *args: Any, analyses: Mapping[Extra, Callable[..., dict[str, Any]]] | None = None, **kwargs: Any
) -> SweepOutcome:
    """Run a plan as :func:`rotorcad.sweep.run.run_sweep` does, every analysis by default (:func:`edge_analyses`)."""
    return _run_sweep(plan, *args, analyses=analyses or edge_analyses(), **kwargs)

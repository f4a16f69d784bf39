"""Design sweeps: a base design, the values to vary, thousands of variants built and judged.

The modules, in the order data flows:

* :mod:`rotorcad.sweep.plan` -- the sweep file's mapping turned into a plan; variants streamed.
* :mod:`rotorcad.sweep.tasks` -- one variant built and judged (the commands' analyses).
* :mod:`rotorcad.sweep.run` -- the variants run in this process or on Dask, rows streamed to
  Parquet, resumable.
* :mod:`rotorcad.sweep.ranking` -- constraints, objectives, the Pareto front and the ranking.
* :mod:`rotorcad.sweep.plots` -- the Pareto and effects pictures.

The package imports the core only (never :mod:`rotorcad.cli`, ``hob`` or ``exports``): reading a
sweep file and its points, and the hobbability verdict of ``hob``, are the command line's
(:mod:`rotorcad.cli.sweep_run`), which passes the verdict in as an analysis
(:data:`hob.sweep_check.ANALYSES`).

``rotorcad.sweep(...)`` stays the function that runs a sweep file (the public API since the first
sweep): the package is callable, and the call is that of :func:`rotorcad.cli.sweep_run.sweep`,
reached through the facade's table of public names (``rotorcad._API``), as ``rotorcad.sweep`` was
before this package existed.
"""

from __future__ import annotations

import importlib
import sys
import types
from typing import Any

from rotorcad.sweep.plan import Extra, Parameter, Sampling, SweepPlan, Variant, apply, sweep_plan


class _CallableSweep(types.ModuleType):
    """The package, callable as the public function ``rotorcad.sweep(sweep_file, ...)``."""

    def __call__(self, *args: Any, **kwargs: Any) -> Any:
        import rotorcad

        return importlib.import_module(rotorcad._ENTRY["sweep"]).sweep(*args, **kwargs)


sys.modules[__name__].__class__ = _CallableSweep

__all__ = ["Extra", "Parameter", "Sampling", "SweepPlan", "Variant", "apply", "sweep_plan"]

"""Design sweeps: a base design, the values to vary, thousands of variants built and judged.

The modules, in the order data flows:

* :mod:`rotorcad.sweep.plan` -- the sweep file's mapping turned into a plan; variants streamed.
* :mod:`rotorcad.sweep.tasks` -- one variant built and judged (the commands' analyses).
* :mod:`rotorcad.sweep.run` -- the variants run in this process or on Dask, rows streamed to
  Parquet, resumable.
* :mod:`rotorcad.sweep.ranking` -- constraints, objectives, the Pareto front and the ranking.
* :mod:`rotorcad.sweep.plots` -- the Pareto and effects pictures.
* :mod:`rotorcad.sweep.files` -- a sweep file read (with its base design and the base's points)
  and run: the public ``rotorcad.sweep(...)``.

The package imports the core only (never :mod:`rotorcad.cli`, ``hob`` or ``exports``): the
hobbability verdict of ``hob`` and the readers of ``exports`` come through the core's extension
points (:mod:`rotorcad.extensions`), or are passed in (``analyses=``, ``read_points=``).

``rotorcad.sweep(...)`` stays the function that runs a sweep file (the public API since the first
sweep): the package is callable, and the call is that of :func:`rotorcad.sweep.files.sweep`.
"""

from __future__ import annotations

import sys
import types
from typing import Any

from rotorcad.sweep.plan import Extra, Parameter, Sampling, SweepPlan, Variant, apply, sweep_plan


class _CallableSweep(types.ModuleType):
    """The package, callable as the public function ``rotorcad.sweep(sweep_file, ...)``."""

    def __call__(self, *args: Any, **kwargs: Any) -> Any:
        from rotorcad.sweep.files import sweep

        return sweep(*args, **kwargs)


sys.modules[__name__].__class__ = _CallableSweep

__all__ = ["Extra", "Parameter", "Sampling", "SweepPlan", "Variant", "apply", "sweep_plan"]

"""Old import path of the sweep plan: it moved to :mod:`rotorcad.sweep.plan` (kept for a while)."""

from rotorcad.sweep.plan import (  # noqa: F401 - re-exported
    MAX_VARIANTS,
    TABLES,
    Extra,
    Parameter,
    Sampling,
    SweepPlan,
    Variant,
    apply,
    sweep_plan,
)

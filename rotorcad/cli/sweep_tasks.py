"""Old import path of a sweep's tasks: they moved to :mod:`rotorcad.sweep.tasks` (kept for a while)."""

from rotorcad.sweep.tasks import (  # noqa: F401 - re-exported
    EXTRA_COLUMNS,
    OBJECTIVES,
    RESULT_COLUMNS,
    evaluate,
    evaluate_batch,
    result_columns,
)

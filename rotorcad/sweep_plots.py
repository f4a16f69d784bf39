"""Old import path of the sweep pictures: they moved to :mod:`rotorcad.sweep.plots` (kept for a while)."""

from rotorcad.sweep.plots import column_label, pareto_mask, plot_effects, plot_pareto  # noqa: F401 - re-exported

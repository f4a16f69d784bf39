"""Rotor outlines as users bring them (old import path).

Reading the geometry of measured or drawn outlines is :mod:`rotorcad.measured.outline`, the first
stage of the measured-outline pipeline :mod:`rotorcad.measured`; this module re-exports its names
for code that imports them from here.
"""

from rotorcad.measured.outline import SCATTER_FLOOR, accuracy, corners, lands, lobe_count, scatter, whole_outline

__all__ = ["SCATTER_FLOOR", "accuracy", "corners", "lands", "lobe_count", "scatter", "whole_outline"]

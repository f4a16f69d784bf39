"""Rotor pairs from measured points (old import path).

The measured-outline pipeline is :mod:`rotorcad.measured` (outline, fit, pairs); this module
re-exports its names for code that imports them from here.
"""

from rotorcad.measured.fit import fit_residual, lobe_curve, lobe_pieces
from rotorcad.measured.outline import DRAWN_SPANS, SMOOTH_JOINT, as_given, drawing_points, points_accuracy, profile_points
from rotorcad.measured.pairs import pair_from_rotor_points
from rotorcad.measured.rack_points import pair_from_rack_points

__all__ = [
    "DRAWN_SPANS",
    "SMOOTH_JOINT",
    "as_given",
    "drawing_points",
    "fit_residual",
    "lobe_curve",
    "lobe_pieces",
    "pair_from_rack_points",
    "pair_from_rotor_points",
    "points_accuracy",
    "profile_points",
]

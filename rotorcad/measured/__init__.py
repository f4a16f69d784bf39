"""Rotor outlines as users bring them, measured or drawn, through one pipeline to a rotor pair.

The calls run one way, each stage using only the ones before it:

1. :mod:`rotorcad.measured.outline` -- reading the geometry given: a drawing's curves or points of
   a lobe, a groove or the whole outline become one whole outline, with its scatter, the accuracy
   it carries, its sharp corners and lands;
2. :mod:`rotorcad.measured.fit` -- the lobe facing the mate as fitted curves with exact tangents
   (splines between corners, lands as arcs), and how far the fit leaves the points;
3. :mod:`rotorcad.measured.pairs` -- the rack of that lobe by inverse generation and the pair
   generated from it; :mod:`rotorcad.measured.rack_points` -- a pair from rack points, whose lands
   and tip-corner paths :mod:`rotorcad.measured.rack_pieces` recognises and takes exactly.

``rotorcad.rotor_points`` and ``rotorcad.measured_outline`` re-export these names for code that
imports them from there.
"""

from rotorcad.measured.fit import fit_residual, lobe_curve, lobe_pieces
from rotorcad.measured.outline import (
    DRAWN_SPANS,
    SCATTER_FLOOR,
    SMOOTH_JOINT,
    Outline,
    accuracy,
    as_given,
    corners,
    drawing_points,
    lands,
    lobe_count,
    points_accuracy,
    profile_points,
    read_outline,
    scatter,
    whole_outline,
)
from rotorcad.measured.pairs import pair_from_rotor_points
from rotorcad.measured.rack_points import pair_from_rack_points

__all__ = [
    "DRAWN_SPANS",
    "SCATTER_FLOOR",
    "SMOOTH_JOINT",
    "Outline",
    "accuracy",
    "as_given",
    "corners",
    "drawing_points",
    "fit_residual",
    "lands",
    "lobe_count",
    "lobe_curve",
    "lobe_pieces",
    "pair_from_rack_points",
    "pair_from_rotor_points",
    "points_accuracy",
    "profile_points",
    "read_outline",
    "scatter",
    "whole_outline",
]

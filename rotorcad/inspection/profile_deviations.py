"""Profile deviations of one flank over the evaluation range, as ISO 1328-1:2013 (clause 3) defines them.

The measured deviation is charted along the roll length xi of the nominal involute (the profile
chart: the design profile is the horizontal line 0). Over the evaluation range L_alpha:

- the *mean profile line* is the least-squares line fitted to the deviations;
- the *total profile deviation* F_alpha is the distance between two design profile lines (here:
  horizontal lines) enclosing the measured profile;
- the *profile form deviation* f_falpha is the distance between two lines parallel to the mean
  profile line enclosing the measured profile;
- the *profile slope deviation* f_Halpha is the distance between two design profile lines through
  the mean profile line's ends over L_alpha, + when the mean line rises towards the tip
  (more material at the tip).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from rotorcad.geometry import Array

MIN_POINTS = 5
"""Fewest points within the evaluation range that make a flank's profile evaluated."""


@dataclass(frozen=True)
class ProfileDeviation:
    """The profile deviations of one flank over L_alpha, mm.

    Attributes
    ----------
    total, form, slope : float, mm
        F_alpha, f_falpha, f_Halpha (signed).
    mean_line : (float, float)
        (c0 mm, c1): the mean profile line c0 + c1 (xi - xi_start), mm.
    start, length : float, mm
        xi_start and L_alpha.
    points : int
        Points within L_alpha.
    """

    total: float
    form: float
    slope: float
    mean_line: tuple[float, float]
    start: float
    length: float
    points: int

    def at(self, roll_length: float) -> float:
        """Return the mean profile line's deviation at roll length ``roll_length`` (mm), extended beyond L_alpha if need be."""
        c0, c1 = self.mean_line
        return float(c0 + c1 * (roll_length - self.start))


def profile_deviation(roll_length: Array, deviation: Array, evaluation_range: tuple[float, float]) -> ProfileDeviation | None:
    """Evaluate one flank's profile over the evaluation range.

    Parameters
    ----------
    roll_length : (n,) float array, mm
        Roll length of each point's foot on the nominal involute.
    deviation : (n,) float array, mm
        Its normal deviation (+ more material).
    evaluation_range : (float, float), mm
        (xi_start, xi_end) of L_alpha.

    Returns
    -------
    ProfileDeviation or None
        None with fewer than :data:`MIN_POINTS` points in L_alpha or all at one roll length.
    """
    lo, hi = evaluation_range
    xi = np.asarray(roll_length, dtype=float)
    dev = np.asarray(deviation, dtype=float)
    inside = (xi >= lo) & (xi <= hi)
    x, y = xi[inside] - lo, dev[inside]
    if len(x) < MIN_POINTS or np.ptp(x) <= 0.0:
        return None
    c1, c0 = np.polyfit(x, y, 1)
    residual = y - (c0 + c1 * x)
    return ProfileDeviation(
        total=float(np.ptp(y)),
        form=float(np.ptp(residual)),
        slope=float(c1 * (hi - lo)),
        mean_line=(float(c0), float(c1)),
        start=float(lo),
        length=float(hi - lo),
        points=len(x),
    )


__all__ = ["MIN_POINTS", "ProfileDeviation", "profile_deviation"]

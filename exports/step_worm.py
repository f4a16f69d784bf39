"""Exact STEP of a hob's basic worm: its transverse section swept along the thread's helix.

The worm's transverse section (:meth:`hob.worm.BasicWorm.section`, one segment per rack piece and
start) is written as the rotors are (:mod:`exports.step_exact`): each segment a B-spline through
samples refined on its exact curve with their exact tangents, swept along the helix of the worm's
signed lead, one face per segment and start, and the faces checked against the exact helicoid
(:func:`exports.step_exact.helicoid_deviation`): a solid off by more than the tolerance is refused.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from exports.step_exact import section_segments, write_exact_step


def write_worm_step(
    path: Path, section, exact: np.ndarray, lead: float, length: float, tolerance: float = 1e-3
) -> dict[str, float]:
    """Write the basic worm as STEP (AP214, product ``basic worm``).

    Parameters
    ----------
    path : Path
        The file.
    section : rotorcad.profile.Profile
        The worm's transverse section at z = 0, closed, counter-clockwise, of exact curves.
    exact : (n, 2) float array, mm
        The same section as a fine closed polyline (a hundredth of the tolerance in chord), for the
        check.
    lead : float, mm
        Signed lead of the thread (> 0 right hand).
    length : float, mm
        Length along the axis, from z = 0.
    tolerance : float, mm
        Largest distance of the faces from the helicoid accepted.

    Returns
    -------
    dict of float
        ``faces`` (their number) and ``deviation`` (mm), as :func:`exports.step_exact.write_exact_step`.

    Raises
    ------
    exports.step_exact.StepDeviationError
        Faces farther from the helicoid than ``tolerance``.
    OSError
        When OpenCASCADE cannot write the file.
    """
    segments = section_segments(section, 0.0, tolerance)
    return write_exact_step(Path(path), segments, lead, length, tolerance, "basic worm", exact=exact)


__all__ = ["write_worm_step"]

"""The stall test of a mate's generated point along a rack derived from a rotor's points.

Along a mate tip corner's path the mate's generated point stands still (Rinder sec. 2.2.2: the path of
a sharp corner); along a flank the rack generates it moves with the rack. The test compares the mate
point's motion with the rack point's over a stencil of samples (:func:`stalled_samples`), and is used by
:func:`rotorcad.measured.mate_paths.mate_corner_runs`.
"""

from __future__ import annotations

import numpy as np
from numpy.lib.stride_tricks import sliding_window_view

from rotorcad.curves import Curve


def point_jitter(pm: np.ndarray, k: int) -> np.ndarray:
    """Return the jitter (mm) of the mate's points about a smooth path at each sample.

    The largest second difference of the points ``pm`` ((n, 2), mm) centred within ``k - 1`` samples of each
    sample (the first and last sample take their neighbour's): noise of amplitude e gives second differences of
    up to 4 e, a smooth path its change of motion over one sample. It sees jitter from one sample to the next,
    which the interpolating fit of dense exact points gives (below): jitter whose period spans many samples,
    as at 700 points a lobe (7 samples), it hardly sees, and the path runs on through that from one return to
    its corner to the next (:func:`rotorcad.measured.mate_paths._to_piece_ends`). Non-finite points count as no jitter.

    Parameters
    ----------
    pm : (n, 2) float array, mm
        The mate's points at the samples.
    k : int
        Stencil half-width (samples), ``n > 2 k``.

    Returns
    -------
    (n,) float array, mm
    """
    second = np.nan_to_num(np.hypot(*(pm[2:] - 2.0 * pm[1:-1] + pm[:-2]).T), nan=0.0)  # at samples 1..n-2
    padded = np.concatenate([np.full(k - 1, second[0]), second, np.full(k - 1, second[-1])])
    inner = sliding_window_view(padded, 2 * k - 1).max(axis=1)  # at samples 1..n-2
    return np.concatenate([inner[:1], inner, inner[-1:]])


def sampled_below_nyquist(rack_curve: Curve, s: np.ndarray, spacing: float) -> bool:
    """Return whether samples ``s`` of a rack piece see the fit's jitter only aliased, under two samples a period.

    The jitter's period is one given point spacing (``spacing``, mm) along the rotor, whose curve is the rack
    piece's parent (the parent's parameter is the rack's). Sampled twice a period or more, the mate's point is seen
    back on its corner once a period, and a path runs on to the last such sample
    (:func:`rotorcad.measured.mate_paths._to_piece_ends`); sampled less, it is seen there seldom (the symmetric SRM male at
    2000 exact points a lobe: 0.9 points a sample, its female tip corner's path cut to 0.78 mm of the design's 1.64).
    """
    parent = getattr(rack_curve, "parent", None)
    if parent is None or spacing <= 0:
        return False
    q = parent.evaluate(s)[0]
    step = np.hypot(*np.diff(q[np.isfinite(q).all(axis=1)], axis=0).T)
    return bool(len(step) and spacing < 2.0 * float(np.median(step)))


def stalled_samples(pr: np.ndarray, pm: np.ndarray, k: int, threshold: float, jitter: bool) -> np.ndarray:
    """Return where the mate's point stands still: it moves less than ``threshold`` times the rack point.

    Both motions are taken over a stencil of ``k`` samples either side. Of exact points (``jitter``) the mate's
    point also jitters about its corner from one sample to the next. The interpolating fit turns its tangent by
    tens of microradians between the given points, and along a tip corner's path the mate's point follows the
    normal. The symmetric SRM male at 2000 exact points a lobe: 1-14 um from sample to sample, with rack samples
    55 um apart. Over the stencil (0.44 mm of rack) that is up to 0.1 of the rack's motion, where the test allows
    0.02. The path fell apart into runs of 2-4 samples; none was long enough to count, and a female tip corner's
    path was lost. So the mate's motion over the stencil is first reduced by the jitter seen within it. That is
    the largest second difference of the mate's points between the stencil's ends. It is the jitter's own scale:
    a second difference of noise of amplitude e is up to 4 e, a stencil's difference up to 2 e. Along a flank
    the rack generates, it is the motion's change over one sample, which is far below its motion over the
    stencil. The allowance thus follows the jitter the input's spacing gives, not a fixed bound.

    Parameters
    ----------
    pr : (n, 2) float array, mm
        Rack points at the samples.
    pm : (n, 2) float array, mm
        The mate's points generated there (non-finite where none is).
    k : int
        Stencil half-width (samples), ``n > 2 k``.
    threshold : float
        Largest ratio of the mate's motion to the rack's that is a stall.
    jitter : bool
        Reduce the mate's motion by its jitter (exact points).

    Returns
    -------
    (n,) bool array
        True where stalled; the first and last ``k`` samples are False.
    """
    dr = np.hypot(*(pr[2 * k :] - pr[: -2 * k]).T)
    dm = np.hypot(*(pm[2 * k :] - pm[: -2 * k]).T)
    if jitter:  # the largest second difference centred within the stencil, its ends excluded
        dm = np.maximum(dm - point_jitter(pm, k)[k:-k], 0.0)  # NaN stays NaN
    with np.errstate(divide="ignore", invalid="ignore"):
        ratio = np.where(dr > 0, dm / dr, np.inf)
    stalled = np.zeros(len(pr), dtype=bool)
    stalled[k:-k] = np.nan_to_num(ratio, nan=np.inf) < threshold
    return stalled


__all__ = ["point_jitter", "sampled_below_nyquist", "stalled_samples"]

"""The cubic Hermite interpolant of exact samples, shared by the STEP and DXF writers.

Between samples p0, p1 with exact unit tangents t0, t1 on chord-length parameters, the cubic is the
Bézier curve of poles p0, p0 + L t0 / 3, p1 - L t1 / 3, p1 (L = |p1 - p0|): the Hermite interpolant
H(u) = h00 p0 + h10 L t0 + h01 p1 + h11 L t1 in Bernstein form (de Boor, *A Practical Guide to
Splines*, ch. IV). OpenCASCADE's ``GeomAPI_Interpolate`` makes it for the exact STEP
(:mod:`exports.step_exact`), the DXF SPLINE holds it as a B-spline (:mod:`exports.dxf_spline`).
"""

from __future__ import annotations

import numpy as np

from rotorcad.curves import Curve

PROBES = 16
"""Steps per Hermite interval at which the cubic and the exact curve are compared (both ways)."""


def hermite_cubic(points: np.ndarray, tangents: np.ndarray, u: np.ndarray) -> np.ndarray:
    """Evaluate the cubic of every interval at the fractions ``u`` of its parameter.

    Parameters
    ----------
    points, tangents : (n + 1, 2) float arrays
        Samples (mm) and their exact unit tangents.
    u : (k,) float array
        Fractions of each interval, 0 to 1.

    Returns
    -------
    (n, k, 2) float array, mm
    """
    p, t = points, tangents
    chord = np.hypot(*(p[1:] - p[:-1]).T)[:, None]
    poles = np.stack([p[:-1], p[:-1] + chord * t[:-1] / 3.0, p[1:] - chord * t[1:] / 3.0, p[1:]], axis=1)  # (n, 4, 2)
    v = 1.0 - u
    basis = np.stack([v**3, 3 * u * v**2, 3 * u**2 * v, u**3])  # Bernstein, (4, k)
    return np.einsum("ku,nkd->nud", basis, poles)


def _squared_gap(px: np.ndarray, py: np.ndarray, ax: np.ndarray, ay: np.ndarray, dx: np.ndarray, dy: np.ndarray) -> np.ndarray:
    """Squared distance of points p to the chords from a along d, by components (broadcast arrays), mm².

    The foot of p on each chord is clipped to its ends. By x and y arrays rather than a last axis of
    2, whose sums numpy makes as many tiny reductions (the same sums, a few times slower); the
    products and sums are made in place in four arrays of the broadcast shape, the same values as
    the plain expressions (each step the same rounding) without a dozen fresh ones.
    """
    wx, wy = np.subtract(px, ax), np.subtract(py, ay)
    foot = wx * dx
    part = wy * dy
    foot += part
    foot /= np.maximum(dx * dx + dy * dy, 1e-300)
    np.clip(foot, 0.0, 1.0, out=foot)
    np.multiply(foot, dx, out=part)
    wx -= part
    np.multiply(foot, dy, out=part)
    wy -= part
    wx *= wx
    wy *= wy
    wx += wy
    return wx


def _gap_to_chords(px: np.ndarray, py: np.ndarray, ax: np.ndarray, ay: np.ndarray, dx: np.ndarray, dy: np.ndarray) -> np.ndarray:
    """Distance of points p to the chords from a along d, by components (broadcast arrays), mm (:func:`_squared_gap`)."""
    return np.sqrt(_squared_gap(px, py, ax, ay, dx, dy))


def distance_to_chains(points: np.ndarray, chains: np.ndarray) -> np.ndarray:
    """Largest distance of each interval's points to its own chain of chords, (n,) mm.

    The root is taken of the least squared distance (the root rises with its argument: the same
    number as the least of the roots).

    Parameters
    ----------
    points : (n, m, 2) float array, mm
        m points per interval (rows with NaN are left out).
    chains : (n, k, 2) float array, mm
        The vertices of each interval's chain (no NaN).
    """
    ax, ay = chains[:, None, :-1, 0], chains[:, None, :-1, 1]  # (n, 1, k - 1)
    dx, dy = chains[:, None, 1:, 0] - ax, chains[:, None, 1:, 1] - ay
    near = np.sqrt(_squared_gap(points[:, :, None, 0], points[:, :, None, 1], ax, ay, dx, dy).min(axis=2))
    return np.fmax.reduce(near, axis=1, initial=0.0)  # NaN rows left out (fmax); distances are >= 0


def _sag(points: np.ndarray, middles: np.ndarray) -> np.ndarray:
    """Largest distance of the middles of a chain's steps to their chords, (n,) mm (NaN left out).

    Parameters
    ----------
    points : (n, k + 1, 2) float array, mm
        The chain of each interval.
    middles : (n, k, 2) float array, mm
        The curve at the middle of every step.
    """
    ax, ay = points[:, :-1, 0], points[:, :-1, 1]
    dx, dy = points[:, 1:, 0] - ax, points[:, 1:, 1] - ay
    return np.fmax.reduce(_gap_to_chords(middles[..., 0], middles[..., 1], ax, ay, dx, dy), axis=1, initial=0.0)  # NaN left out


def _near_chains(points: np.ndarray, chains: np.ndarray, chords: np.ndarray) -> np.ndarray:
    """Upper bound of :func:`distance_to_chains`: each point's distance to the chords ``chords`` of its chain only, (n,) mm.

    Each distance is the one :func:`distance_to_chains` makes for that chord, bit for bit (the same
    differences and steps), and the least over fewer chords is never the smaller.

    Parameters
    ----------
    points : (n, m, 2) float array, mm
        m points per interval (rows with NaN are left out).
    chains : (n, k, 2) float array, mm
        The vertices of each interval's chain (no NaN).
    chords : (m, c) int array
        The chords (a chord j runs from vertex j to j + 1) measured for each point.
    """
    a = chains[:, chords]  # (n, m, c, 2)
    d = chains[:, chords + 1] - a
    gap = _squared_gap(points[:, :, None, 0], points[:, :, None, 1], a[..., 0], a[..., 1], d[..., 0], d[..., 1])
    return np.fmax.reduce(np.sqrt(gap.min(axis=2)), axis=1, initial=0.0)  # NaN left out


_STEP_CHORDS = np.clip(np.arange(PROBES + 1)[:, None] + [-1, 0], 0, PROBES - 1)
"""The chords either side of each step's end (the cubic's points on the exact chain and back)."""
_MIDDLE_CHORDS = np.repeat(np.arange(PROBES)[:, None], 2, axis=1)
"""The chord of each step's middle (the exact middles on the cubic's chain)."""


def interval_deviation(
    curve: Curve, s: np.ndarray, points: np.ndarray, tangents: np.ndarray, below: float | None = None
) -> np.ndarray:
    """Measure how far the Hermite cubic of every interval strays from the exact curve, both ways.

    In each interval [s_i, s_(i+1)] the exact curve is evaluated at :data:`PROBES` equal steps of
    its parameter (and the middles of the steps), the cubic at as many equal steps of its own.
    The deviation is the larger of (a) the distance of the cubic's points to the exact curve's chain
    plus that chain's sag (the distance of the exact middles to their chords: a point of the chain
    is within it of the curve) and (b) the distance of the exact points to the cubic's chain plus
    the cubic chain's own sag. Both are upper estimates of the one-sided Hausdorff distances
    between the cubic and the exact curve on the interval.

    Parameters
    ----------
    curve : Curve
        The exact curve.
    s : (n + 1,) float array
        Parameters of the samples.
    points, tangents : (n + 1, 2) float arrays
        The samples (mm) and their exact unit tangents.
    below : float, mm, optional
        Where only whether a deviation exceeds ``below`` matters: every point is first measured
        against the chords beside it alone (:func:`_near_chains`: an upper bound of the
        deviation; the nearest chords unless the chain folds back), and the intervals whose
        bound exceeds ``below`` are measured against all their chords.

    Returns
    -------
    (n,) float array, mm
        The deviation of every interval (exact points without contact are left out); with
        ``below``, an upper bound of it where that is at most ``below``.
    """
    k = PROBES
    # the steps' ends (k + 1) and their middles (k) of every interval, evaluated in one call each
    # on the exact curve and on the cubic (the same values as two calls: both act point by point)
    steps = np.concatenate([np.arange(k + 1) / k, (np.arange(k) + 0.5) / k])
    ds = (s[1:] - s[:-1])[:, None]
    both, _ = curve.evaluate((s[:-1, None] + ds * steps).ravel())
    both = both.reshape(len(ds), 2 * k + 1, 2)
    exact, mid = both[:, : k + 1], both[:, k + 1 :]
    exact[:, 0], exact[:, -1] = points[:-1], points[1:]
    cubic_both = hermite_cubic(points, tangents, steps)
    cubic, cubic_mid = cubic_both[:, : k + 1], cubic_both[:, k + 1 :]
    chain = np.where(np.isfinite(exact), exact, cubic)  # a missing exact point: the chain skips through the cubic
    sag_exact = _sag(chain, mid)
    sag_cubic = _sag(cubic, cubic_mid)
    if below is None:
        out = distance_to_chains(cubic, chain) + sag_exact
        back = distance_to_chains(both, cubic) + sag_cubic  # the exact points: the steps' ends and middles
        return np.maximum(out, back)
    err = np.maximum(
        _near_chains(cubic, chain, _STEP_CHORDS) + sag_exact,
        _near_chains(both, cubic, np.vstack([_STEP_CHORDS, _MIDDLE_CHORDS])) + sag_cubic,
    )
    over = err > below
    if over.any():
        out = distance_to_chains(cubic[over], chain[over]) + sag_exact[over]
        err[over] = np.maximum(out, distance_to_chains(both[over], cubic[over]) + sag_cubic[over])
    return err


def refine_samples(
    curve: Curve, s: np.ndarray, points: np.ndarray, tangents: np.ndarray, target: float, passes: int, exact: bool = True
) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """Add samples of the exact curve until the Hermite cubic of every interval is within ``target`` of it.

    An interval whose deviation e (:func:`interval_deviation`) exceeds the target is split into
    ceil((e / target)^(1/4)) + 1 equal parameter parts (the cubic's error falls with the fourth
    power of the spacing where the curve is smooth; on an arc of radius rho it is about
    sag^2 / (2 rho), so a chord tolerance alone does not bound it where the curve bends sharply, as
    near an involute's cusp), the new samples evaluated on the exact curve (points without contact
    dropped). Both writers use it: the DXF spline (:mod:`exports.dxf_spline`) and the exact STEP
    (:mod:`exports.step_exact`).

    Parameters
    ----------
    curve : Curve
        The exact curve.
    s : (n + 1,) float array
        Parameters of the samples.
    points, tangents : (n + 1, 2) float arrays
        The samples (mm) and their exact unit tangents.
    target : float, mm
        Largest deviation of the cubic of an interval.
    passes : int
        Most refinement passes.
    exact : bool
        False when the caller keeps the samples alone: an interval within the target may then be
        given an upper bound of its deviation (``interval_deviation(..., below=target)``), which
        splits the same intervals into the same parts.

    Returns
    -------
    s, points, tangents : arrays as above, refined (the old samples among them)
    deviation : (n',) float array, mm
        The measured deviation of every interval after the last pass (it may still exceed the
        target after ``passes`` passes: the caller decides); without ``exact``, where it is
        within the target, an upper bound of it that is.
    """
    s, p, t = (np.asarray(a, dtype=float) for a in (s, points, tangents))
    below = None if exact else target
    err = interval_deviation(curve, s, p, t, below)
    for _ in range(passes):
        if err.max() <= target:
            break
        parts = np.where(err > target, np.ceil((err / target) ** 0.25) + 1, 1).astype(int)
        j = np.repeat(np.arange(len(err)), parts)  # interval of each new parameter
        k = np.arange(len(j)) - np.repeat(np.cumsum(parts) - parts, parts)  # its part of the interval
        s_new = np.append(s[j] + (s[j + 1] - s[j]) * (k / parts[j]), s[-1])
        fresh = np.append(k > 0, False)
        p_new, t_new = np.empty((len(s_new), 2)), np.empty((len(s_new), 2))
        p_new[~fresh], t_new[~fresh] = p, t
        p_new[fresh], t_new[fresh] = curve.evaluate(s_new[fresh])
        keep = np.isfinite(p_new).all(axis=1) & np.isfinite(t_new).all(axis=1)
        s, p, t = s_new[keep], p_new[keep], t_new[keep]
        err = interval_deviation(curve, s, p, t, below)
    return s, p, t, err

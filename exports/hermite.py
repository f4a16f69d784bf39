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
    return _interval_cubic(points[:-1], points[1:], tangents[:-1], tangents[1:], u)


def _interval_cubic(p0: np.ndarray, p1: np.ndarray, t0: np.ndarray, t1: np.ndarray, u: np.ndarray) -> np.ndarray:
    """Evaluate the Hermite cubic of every interval from its ends, (n, k, 2) mm (:func:`hermite_cubic`).

    The intervals need not follow one another (those of several curves, stacked).

    Parameters
    ----------
    p0, p1 : (n, 2) float arrays, mm
        The start and end of every interval.
    t0, t1 : (n, 2) float arrays
        Their exact unit tangents.
    u : (k,) float array
        Fractions of each interval, 0 to 1.
    """
    chord = np.hypot(*(p1 - p0).T)[:, None]
    poles = np.stack([p0, p0 + chord * t0 / 3.0, p1 - chord * t1 / 3.0, p1], axis=1)  # (n, 4, 2)
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
    both = _probe(curve, s, points)
    return _measured(both, points[:-1], points[1:], tangents[:-1], tangents[1:], below)


_STEPS = np.concatenate([np.arange(PROBES + 1) / PROBES, (np.arange(PROBES) + 0.5) / PROBES])
"""The fractions of an interval probed: the :data:`PROBES` steps' ends, then their middles."""


def _probe(curve: Curve, s: np.ndarray, points: np.ndarray) -> np.ndarray:
    """Evaluate the exact curve at every interval's steps' ends and middles, (n, 2 PROBES + 1, 2) mm.

    One call of the curve for all (it acts point by point); the ends of every interval are the
    samples themselves.
    """
    k = PROBES
    ds = (s[1:] - s[:-1])[:, None]
    both, _ = curve.evaluate((s[:-1, None] + ds * _STEPS).ravel())
    both = both.reshape(len(ds), 2 * k + 1, 2)
    both[:, 0], both[:, k] = points[:-1], points[1:]
    return both


def _measured(
    both: np.ndarray, p0: np.ndarray, p1: np.ndarray, t0: np.ndarray, t1: np.ndarray, below: float | None = None
) -> np.ndarray:
    """Measure the deviation of every interval's cubic from its probed exact points, (n,) mm (:func:`interval_deviation`).

    Row by row: the intervals of several curves may be stacked (each row the numbers it gives alone).

    Parameters
    ----------
    both : (n, 2 PROBES + 1, 2) float array, mm
        The exact points at the steps' ends and middles (:func:`_probe`).
    p0, p1, t0, t1 : (n, 2) float arrays
        The ends of every interval (mm) and their exact unit tangents.
    below : float, mm, optional
        As :func:`interval_deviation`'s.
    """
    k = PROBES
    exact, mid = both[:, : k + 1], both[:, k + 1 :]
    cubic_both = _interval_cubic(p0, p1, t0, t1, _STEPS)
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
    return refine_curves([(curve, s, points, tangents)], target, passes, exact)[0]


Samples = tuple[np.ndarray, np.ndarray, np.ndarray]
"""The samples of one curve: parameters s (n + 1,), points (n + 1, 2) mm, exact unit tangents (n + 1, 2)."""


def refine_curves(
    pieces: list[tuple[Curve, np.ndarray, np.ndarray, np.ndarray]], target: float, passes: int, exact: bool = True
) -> list[tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]]:
    """Refine the samples of several curves at once, each as :func:`refine_samples` refines it alone.

    Each curve is evaluated on its own (one call a pass); the deviations of the intervals of all
    the curves still being refined are measured together, row by row (:func:`_measured`), in one
    set of array operations instead of one set per curve: a rotor's 35-55 segments measured in
    one go. Every curve gets the samples, bit for bit, that :func:`refine_samples` gives it alone.

    Parameters
    ----------
    pieces : list of (Curve, s, points, tangents)
        Each exact curve with its samples (arrays as :func:`refine_samples` takes them, at least 2).
    target, passes, exact
        As :func:`refine_samples`'s.

    Returns
    -------
    list of (s, points, tangents, deviation)
        For every piece, in order, what :func:`refine_samples` returns for it.
    """
    curves = [piece[0] for piece in pieces]
    state: list[Samples] = [tuple(np.asarray(a, dtype=float) for a in piece[1:]) for piece in pieces]
    below = None if exact else target
    errs = _deviations(curves, state, below)
    for _ in range(passes):
        todo = [i for i, err in enumerate(errs) if not err.max() <= target]  # as `if err.max() <= target: break`
        if not todo:
            break
        for i in todo:
            state[i] = _split(curves[i], *state[i], errs[i], target)
        for i, err in zip(todo, _deviations([curves[i] for i in todo], [state[i] for i in todo], below), strict=True):
            errs[i] = err
    return [(*samples, err) for samples, err in zip(state, errs, strict=True)]


def _deviations(curves: list[Curve], state: list[Samples], below: float | None) -> list[np.ndarray]:
    """:func:`interval_deviation` of every curve's samples, the intervals of all measured together."""
    both = [_probe(curve, s, p) for curve, (s, p, _) in zip(curves, state, strict=True)]
    ends = [np.concatenate(a) for a in zip(*((p[:-1], p[1:], t[:-1], t[1:]) for _, p, t in state), strict=True)]
    err = _measured(np.concatenate(both), *ends, below)
    return np.split(err, np.cumsum([len(b) for b in both])[:-1])


def _split(curve: Curve, s: np.ndarray, p: np.ndarray, t: np.ndarray, err: np.ndarray, target: float) -> Samples:
    """Split every interval whose deviation exceeds ``target`` (:func:`refine_samples`' rule); new samples on the curve."""
    parts = np.where(err > target, np.ceil((err / target) ** 0.25) + 1, 1).astype(int)
    j = np.repeat(np.arange(len(err)), parts)  # interval of each new parameter
    k = np.arange(len(j)) - np.repeat(np.cumsum(parts) - parts, parts)  # its part of the interval
    s_new = np.append(s[j] + (s[j + 1] - s[j]) * (k / parts[j]), s[-1])
    fresh = np.append(k > 0, False)
    p_new, t_new = np.empty((len(s_new), 2)), np.empty((len(s_new), 2))
    p_new[~fresh], t_new[~fresh] = p, t
    p_new[fresh], t_new[fresh] = curve.evaluate(s_new[fresh])
    keep = np.isfinite(p_new).all(axis=1) & np.isfinite(t_new).all(axis=1)
    return s_new[keep], p_new[keep], t_new[keep]

"""A closed spline through sparse outline points whose curvature steps between two of them.

A rotor's outline is a chain of generated curves that meet with a step of their curvature (a tip
rounding meeting its flank or land, Rinder sec. 1.2). One cubic spline through points spaced h apart
across a step dk rings over a few spacings by about h^2 dk / 30: the N-rack female (2.07 mm tip
roundings, 80 points a lobe, 0.79 mm apart) 10 um off its outline, the clearance read from it 12 um
off. Here the spline gets a double knot at each step (continuous tangent, free curvature: the two
curves meet tangent there), placed where the circles of the three points either side come closest
(their curves are tangent at the junction), and the two extra conditions each such knot needs are
that the third derivative is continuous at the data points either side of it (de Boor's not-a-knot
condition, *A Practical Guide to Splines*, 2001, ch. IV): each side of a step is then one cubic up to
the step, as a smooth curve is between two points.
"""

from __future__ import annotations

import numpy as np

from rotorcad.curves import Spline

STEP_ERROR = 1e-3
"""mm: the spline error h^2 dk / 30 of a curvature step dk between points h apart above which it gets
its own knot (:func:`curvature_steps`); 300 points a lobe of the N-rack female (0.21 mm, dk 0.47 /mm):
0.7 um, 80 a lobe (0.79 mm): 10 um."""

STEP_RATIO = 6.0
"""The least ratio of a step's jump of curvature to the change of the circles beside it on either side."""


def _circles(ring: np.ndarray) -> np.ndarray:
    """Signed curvature (1/mm, positive turning left) of the circle through each point of a closed ring and its neighbours."""
    a, b, c = np.roll(ring, 1, axis=0), ring, np.roll(ring, -1, axis=0)
    u, v = b - a, c - b
    den = np.hypot(*u.T) * np.hypot(*v.T) * np.hypot(*(c - a).T)
    return 2.0 * (u[:, 0] * v[:, 1] - u[:, 1] * v[:, 0]) / np.maximum(den, 1e-300)


def curvature_steps(ring: np.ndarray, sigma: float) -> np.ndarray:
    """Return the spacings (i, i + 1) of a closed ring of points across which the curvature steps.

    The step of spacing i compares the circles at points i - 1 and i + 2 (each through three points of
    one side); it counts where it is :data:`STEP_RATIO` times the change of the circles beside it,
    the largest within two spacings, above the circles' noise (5 x 2 sqrt(6) sigma / h^2) and large
    enough for the spline to miss the outline by :data:`STEP_ERROR` (h^2 dk / 30).

    Parameters
    ----------
    ring : (n, 2) float array, mm
        The closed outline's points, in order (the last not repeating the first).
    sigma : float, mm
        Their scatter (0 for exact points).

    Returns
    -------
    (m,) int array
        The first point i of each stepped spacing.
    """
    k = _circles(ring)
    h = float(np.median(np.hypot(*np.diff(ring, axis=0).T)))
    jump = np.abs(np.roll(k, -2) - np.roll(k, 1))
    beside = np.maximum(np.abs(np.roll(k, 1) - np.roll(k, 2)), np.abs(np.roll(k, -3) - np.roll(k, -2)))
    floor = max(30.0 * STEP_ERROR / h**2, 5.0 * 2.0 * np.sqrt(6.0) * sigma / h**2)
    jump = np.where((jump > STEP_RATIO * beside) & (jump > floor), jump, 0.0)
    peak = jump.copy()
    for off in (1, 2):
        peak = np.maximum(peak, np.maximum(np.roll(jump, off), np.roll(jump, -off)))
    return np.flatnonzero((jump > 0) & (jump >= peak))


def _end_frame(a: np.ndarray, b: np.ndarray, c: np.ndarray, at_end: bool) -> tuple[np.ndarray, np.ndarray, float]:
    """Point, unit tangent (along a -> c) and signed curvature of the circle through a, b, c at c (or at a)."""
    k = float(_circles(np.array([a, b, c]))[1])
    p, q = (b, c) if at_end else (a, b)
    chord = (q - p) / np.hypot(*(q - p))
    half = np.arcsin(np.clip(0.5 * k * np.hypot(*(q - p)), -1.0, 1.0)) * (1.0 if at_end else -1.0)
    t = np.array([chord[0] * np.cos(half) - chord[1] * np.sin(half), chord[0] * np.sin(half) + chord[1] * np.cos(half)])
    return (c if at_end else a), t, k


def _junction(ring: np.ndarray, i: int) -> float:
    """Return where along the spacing (i, i + 1) the curves of the points either side meet tangent, a share of it in (0, 1).

    The circle of points i - 2, i - 1, i continued past i, against the circle of i + 1, i + 2, i + 3:
    their signed distance along the first is a parabola about the tangent point (Rinder's generated
    curves meet tangent), whose vertex is taken.
    """
    n = len(ring)
    p = ring[[(i - 2) % n, (i - 1) % n, i % n, (i + 1) % n, (i + 2) % n, (i + 3) % n]]
    p0, t0, k0 = _end_frame(p[0], p[1], p[2], True)
    p1, t1, k1 = _end_frame(p[3], p[4], p[5], False)
    h = float(np.hypot(*(p[3] - p[2])))
    s = np.linspace(-0.9 * h, 1.9 * h, 113)  # the junction may lie a spacing off the step found
    n0 = np.array([-t0[1], t0[0]])
    x = k0 * s
    sinc = np.where(np.abs(x) > 1e-12, np.sin(x) / np.where(x == 0, 1, x), 1.0)
    versine = np.where(np.abs(x) > 1e-12, (1 - np.cos(x)) / np.where(x == 0, 1, x), 0.5 * x)
    q = p0 + s[:, None] * (sinc[:, None] * t0 + versine[:, None] * n0)
    d = q - p1
    n1 = np.array([-t1[1], t1[0]])
    dn, dd = d @ n1, np.einsum("ij,ij->i", d, d)
    dist = (2 * dn - k1 * dd) / (1 + np.sqrt(np.maximum(1 - 2 * k1 * dn + k1 * k1 * dd, 0.0)))
    c2, c1, _ = np.polyfit(s / h, dist, 2)
    share = -c1 / (2 * c2) if c2 != 0 else 0.5
    return float(np.clip(share, -0.9, 1.9)) if np.isfinite(share) else 0.5


def _solve(u: np.ndarray, pts: np.ndarray, junctions: list[tuple[int, float]]) -> tuple[np.ndarray, np.ndarray] | None:
    """Interpolate points (n, 2) at chord lengths ``u`` with a cubic spline, a double knot at each junction.

    ``junctions`` holds (j, x): a junction at ``x`` between ``u[j]`` and ``u[j + 1]``, whose two extra
    conditions are a continuous third derivative at ``u[j]`` and ``u[j + 1]``; not-a-knot ends.
    Returns the knots and the coefficients (m, 2), or None where the system is singular.
    """
    from scipy.interpolate import BSpline

    inner = np.sort(np.concatenate([u[2:-2], np.repeat([x for _, x in junctions], 2)]))
    t = np.r_[[u[0]] * 4, inner, [u[-1]] * 4]
    count = len(t) - 4
    basis = BSpline(t, np.eye(count), 3, extrapolate=False)
    a = np.nan_to_num(basis(u))
    a[-1] = np.nan_to_num(basis(u[-1] - 1e-12 * max(1.0, abs(u[-1]))))  # the last point closes the base interval
    rows = [a]
    for j, _ in junctions:
        for m in (j, j + 1):  # the third derivative continuous at the data points either side of the step
            jumps = np.nan_to_num(basis(np.array([_knot_below(t, u[m]), _knot_above(t, u[m])]), 3))
            rows.append((jumps[1] - jumps[0])[None, :])
    a = np.vstack(rows)
    if a.shape[0] != count:
        return None
    try:
        coef = np.linalg.solve(a, np.vstack([pts, np.zeros((a.shape[0] - len(pts), 2))]))
    except np.linalg.LinAlgError:
        return None
    return t, coef


def _third_jumps(t: np.ndarray, coef: np.ndarray, at: np.ndarray) -> np.ndarray:
    """Length of the jump of the spline's third derivative (vector) at each knot of ``at`` (k,)."""
    from scipy.interpolate import BSpline

    spline = BSpline(t, coef, 3)
    lo = np.array([_knot_below(t, x) for x in at])
    hi = np.array([_knot_above(t, x) for x in at])
    return np.hypot(*(spline(hi, 3) - spline(lo, 3)).T)


def _placed(u: np.ndarray, pts: np.ndarray, junctions: list[tuple[int, float]], sweeps: int = 2) -> list[tuple[int, float]]:
    """Move each junction over its spacing and the two beside it to where the spline's third derivative jumps least.

    A smooth curve interpolated by a cubic has nearly the same third derivative either side of a data
    point; a junction placed off the curvature step leaves jumps at the points beside it. The jumps at
    the data points within three spacings (other than those the junctions hold) are added in squares,
    over a local run of sixteen points, each junction in turn with the others where they are.
    """
    junctions = sorted(junctions)
    for _ in range(sweeps):
        for k in range(len(junctions)):
            j0, _ = junctions[k]
            lo, hi = max(j0 - 8, 0), min(j0 + 10, len(u) - 1)
            best, pick = np.inf, junctions[k]
            for j in (j0 - 1, j0, j0 + 1):
                if j - lo < 3 or hi - j < 4:
                    continue
                others = [(a, x) for i, (a, x) in enumerate(junctions) if i != k and lo + 3 <= a <= hi - 4]
                held = {m for a, _ in others for m in (a, a + 1)}
                if {j, j + 1} & held:
                    continue
                probe = np.array([m for m in range(max(j - 3, lo + 2), min(j + 5, hi - 1)) if m not in held | {j, j + 1}])
                for share in np.linspace(0.05, 0.95, 19):
                    x = u[j] + share * (u[j + 1] - u[j])
                    fit = _solve(u[lo : hi + 1], pts[lo : hi + 1], [(a - lo, y) for a, y in [*others, (j, x)]])
                    if fit is None:
                        continue
                    cost = float(np.sum(_third_jumps(*fit, u[probe]) ** 2))
                    if cost < best:
                        best, pick = cost, (j, x)
            junctions[k] = pick
    return junctions


def stepped_ring_spline(ring: np.ndarray, sigma: float = 0.0, lead: int = 8) -> Spline | None:
    """Fit the closed ring of points with a cubic spline that has a double knot at each curvature step.

    Parameters
    ----------
    ring : (n, 2) float array, mm
        The closed outline's points, in order (the last not repeating the first), exact or of scatter
        ``sigma`` (interpolated either way).
    sigma : float, mm
        Their scatter, for :func:`curvature_steps`.
    lead : int
        Points of the ring repeated before and after it, so that the spline trimmed to one turn has no
        end of its own.

    Returns
    -------
    Spline or None
        Parameterised by the cumulative chord length of the ring repeated, trimmed to one turn from the
        ring's first point back to it; None where the ring has no step (a periodic cubic serves) or is
        too dense for it to matter.
    """
    n = len(ring)
    if n < 4 * lead or n > 4000:
        return None
    steps = curvature_steps(ring, sigma)
    if not len(steps):
        return None
    idx = np.arange(-lead, n + lead + 1)
    pts = ring[idx % n]
    u = np.concatenate([[0.0], np.cumsum(np.hypot(*np.diff(pts, axis=0).T))])
    at: list[tuple[int, float]] = []
    for i in steps:
        share = _junction(ring, i)
        whole = int(np.floor(share))
        for j in np.flatnonzero(idx[:-1] % n == i) + whole:
            if 3 <= j <= len(u) - 5:
                at.append((int(j), u[j] + float(np.clip(share - whole, 0.05, 0.95)) * (u[j + 1] - u[j])))
    # steps a spacing apart (a rounding of one point): no knot, the spline through them as before
    at = sorted(at)
    close = {k for k in range(len(at) - 1) if at[k + 1][0] - at[k][0] < 2}
    at = [a for k, a in enumerate(at) if k not in close and k - 1 not in close]
    if not at:
        return None
    at = _placed(u, pts, at)
    fit = _solve(u, pts, at)
    if fit is None:
        return None
    t, coef = fit
    return Spline(knots=(t, (coef[:, 0], coef[:, 1]), 3), s0=float(u[lead]), s1=float(u[lead + n]))


def _knot_below(t: np.ndarray, x: float) -> float:
    """Return a point inside the knot span just below ``x`` (a knot)."""
    below = t[t < x - 1e-12]
    return 0.5 * (below[-1] + x) if len(below) else x - 1e-9


def _knot_above(t: np.ndarray, x: float) -> float:
    """Return a point inside the knot span just above ``x`` (a knot)."""
    above = t[t > x + 1e-12]
    return 0.5 * (above[0] + x) if len(above) else x + 1e-9


def stepped_ring_fit(
    ring: np.ndarray, sigma: float = 0.0, facing: float = 0.0
) -> list[tuple[Spline, np.ndarray, np.ndarray]] | None:
    """Return :func:`stepped_ring_spline` with the ring's points closed and their parameters (for cutting a lobe), or None.

    The ring starts opposite the polar angle ``facing`` (rad), so that the lobe facing the mate lies
    inside the spline's one turn, not across its ends.
    """
    start = int(np.argmin(np.abs(np.angle(np.exp(1j * (np.arctan2(ring[:, 1], ring[:, 0]) - facing - np.pi))))))
    ring = np.roll(ring, -start, axis=0)
    spline = stepped_ring_spline(ring, sigma)
    if spline is None:
        return None
    closed = np.vstack([ring, ring[:1]])
    return [(spline, closed, spline.s0 + np.concatenate([[0.0], np.cumsum(np.hypot(*np.diff(closed, axis=0).T))]))]


__all__ = ["STEP_ERROR", "STEP_RATIO", "curvature_steps", "stepped_ring_fit", "stepped_ring_spline"]

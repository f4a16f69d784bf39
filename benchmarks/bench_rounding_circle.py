"""Would a least-squares circle at a tip rounding beat the smoothing spline there? (issue 22 item 3; not a test).

For each case, 300 points a lobe with 2 um of scatter (``test_hob_points_samples.outline``, seed by seed), the rotor
fitted as ``rotorcad`` fits it (:func:`rotorcad.measured.fit.lobe_pieces`: smoothing splines by n sigma^2). The
roundings are the runs of points where the fit's curvature exceeds half its largest (at least 5 points); each is
fitted by a least-squares circle (Kasa's algebraic fit, then Gauss-Newton on the geometric distances) and kept when
its residuals are the scatter's (chi^2 below m - 3 + 3 sqrt(2 (m - 3))). Printed per case and seed: the largest
distance from the design's outline (its exact curves at a 0.1 um chord) of the spline and of the circle at the
rounding's points' feet, over the rounding's middle (its points but the two at either end, where the circle meets
the flanks) and over all of it. The bound of a known arc fitted to m points is sigma sqrt(3 / m) at a point (the
variance of 3 parameters). Run from the repository: ``python benchmarks/bench_rounding_circle.py 11 20`` (16 s of CPU).

Measured, seeds 11-20, the worst rounding of each (largest spline error over its points -> the circle's; the
radius found / the design's): rack-involute female (9-10 points, R 2.40-2.46 mm / 2.44) 3.96-8.16 -> 1.25-3.95 um;
N-rack female (19 points, R 2.07 / 2.07) 2.06-7.69 -> 0.71-2.71 um; rack-involute male (7-9 points, R 2.54-2.61)
2.69-5.41 -> 0.45-3.00 um; narrow-tip female: no rounding (its tips are sharp corners). Not yet in the fit: these
roundings meet the tip land directly (the fitted run's lead-in points are the land's). Tried in the fit and not
kept: the circle tangent to the tip land (2 parameters, the land ending at the tangent point), smoothing splines
leaning on 3 points of the circle either side (as on a land's): the rotor's fit at the rack-involute female's
tip rounding 4.95-5.17 -> 0.97-1.17 um (seed 13), its rack over seeds 11-16 9.07/5.41/5.19/5.98/5.36/5.10 ->
5.83/5.88/8.20/8.66/4.20/5.15 um (the spline beside the circle is still 4.6 um off where the circle ends before the
rounding does), but the N-rack female's rack 7.76 -> 112.6 um on seed 11 (99-100 um on 13-15): its sealing tip
circle ends at r = 43.5 mm, where the female's generation stalls (slip singularity), and the curvature step
the circle leaves there sends the rack 100 um off (the rack follows the fit's curvature where generation
stalls); the rack-involute male 6.28 -> 6.27, 3.5-6.7 um on seeds 12-16. A circle in the fit needs its
curvature blended into the flank's where the generation stalls.
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np
import shapely
from scipy import interpolate
from scipy.spatial import cKDTree

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tests"))

import test_hob_points_samples as samples
from independent_pairs import distance_to_line

from rotorcad.curves import Spline
from rotorcad.measured.fit import lobe_pieces
from rotorcad.measured.outline import read_outline

CASES = [("rack_involute_5_6", "female"), ("n_rack_5_6", "female"), ("rack_involute_5_6", "male"), ("narrow_tip_5_6", "female")]


def circle(points: np.ndarray) -> tuple[np.ndarray, float, np.ndarray]:
    """Least-squares circle: centre, radius and the signed residuals (mm); Kasa's fit refined by Gauss-Newton."""
    x, y = points.T
    a = np.column_stack([x, y, np.ones_like(x)])
    b, c, d = np.linalg.lstsq(a, x**2 + y**2, rcond=None)[0]
    centre = np.array([b / 2, c / 2])
    radius = float(np.sqrt(d + centre @ centre))
    for _ in range(10):
        v = points - centre
        dist = np.hypot(*v.T)
        jac = np.column_stack([-v / dist[:, None], -np.ones(len(v))])
        step = np.linalg.lstsq(jac, -(dist - radius), rcond=None)[0]
        centre, radius = centre + step[:2], radius + float(step[2])
    return centre, radius, np.hypot(*(points - centre).T) - radius


def dense_fit(pieces: list) -> tuple[np.ndarray, np.ndarray]:
    """The fitted splines' points 1 um apart and their curvature from the exact derivatives (1/mm)."""
    pts, kap = [], []
    for _, curve in pieces:
        if not isinstance(curve, Spline):
            continue
        lo, hi = sorted((curve.s0, curve.s1))
        s = np.linspace(lo, hi, max(int((hi - lo) / 1e-3), 2))
        tck = [curve.knots[0], list(curve.knots[1]), curve.knots[2]]
        p = np.stack(interpolate.splev(s, tck), axis=-1)
        d1 = np.stack(interpolate.splev(s, tck, der=1), axis=-1)
        d2 = np.stack(interpolate.splev(s, tck, der=2), axis=-1)
        kap.append(np.abs(d1[:, 0] * d2[:, 1] - d1[:, 1] * d2[:, 0]) / np.hypot(*d1.T) ** 3)
        pts.append(p)
    return np.vstack(pts), np.concatenate(kap)


def measure(name: str, rotor: str, seed: int) -> list[tuple[float, float, float, float, int, float]]:
    spec, design = samples.design(name)
    pair = spec.pair
    teeth = pair.male_teeth if rotor == "male" else pair.female_teeth
    pts = samples.outline(name, rotor, "scatter", seed)
    outline = read_outline(pts, teeth, "points")
    sigma = outline.sigma
    fit, kappa = dense_fit(lobe_pieces(pair, outline, rotor))
    lobe = design.male_outline(1e-4) if rotor == "male" else design.female_outline(1e-4)
    truth = shapely.LineString(np.vstack([seg.points for seg in lobe.segments]))
    near, foot = cKDTree(fit).query(pts)
    on_fit = near < 50 * sigma  # the points beside the fitted lobe
    high = on_fit & (kappa[foot] > 0.5 * kappa.max())
    edges = np.diff(np.concatenate([[0], high.astype(int), [0]]))
    out = []
    for a, b in zip(np.flatnonzero(edges == 1), np.flatnonzero(edges == -1), strict=True):
        if b - a < 5:
            continue
        window = pts[a:b]
        centre, radius, residual = circle(window)
        m = len(window)
        if (residual**2).sum() / sigma**2 > m - 3 + 3 * np.sqrt(2 * (m - 3)):
            continue  # the points do not say it is a circle
        spline_feet = fit[foot[a:b]]
        v = window - centre
        circle_feet = centre + radius * v / np.hypot(*v.T)[:, None]
        e_spline = distance_to_line(spline_feet, truth)
        e_circle = distance_to_line(circle_feet, truth)
        mid = slice(2, m - 2)
        out.append((e_spline[mid].max(), e_circle[mid].max(), e_spline.max(), e_circle.max(), m, radius))
    return out


def main(first: int, last: int) -> None:
    for name, rotor in CASES:
        print(f"{name} {rotor}")
        for seed in range(first, last + 1):
            rows = measure(name, rotor, seed)
            worst = max(rows, key=lambda r: r[2]) if rows else None
            if worst is None:
                print(f"  seed {seed}: no rounding read as a circle", flush=True)
                continue
            s_mid, c_mid, s_all, c_all, m, radius = worst
            print(
                f"  seed {seed}: {len(rows)} roundings; worst (m = {m}, R = {radius:.2f} mm): middle spline {1e3 * s_mid:5.2f} "
                f"circle {1e3 * c_mid:5.2f} um, whole spline {1e3 * s_all:5.2f} circle {1e3 * c_all:5.2f} um",
                flush=True,
            )


if __name__ == "__main__":
    main(*(int(a) for a in sys.argv[1:3])) if len(sys.argv) > 2 else main(11, 20)

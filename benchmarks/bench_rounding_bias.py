"""The smoothing spline's bias at a rounding, measured on synthetic roundings (issue 22 item 3; not a test).

A straight run, a circular rounding of radius R turning by 1 rad, a straight run (the shape of a rotor's tip
rounding between flanks), sampled every h mm along the arc and scattered by sigma along the normals, fitted as
``rotorcad`` fits a run of scattered points (FITPACK's smoothing spline by n sigma^2, Dierckx sec. 5.2,
:meth:`rotorcad.curves.Spline.fit`). The largest distance of the fit from the true shape within 2 mm of the
rounding, over seeds, in units of sigma g^(1/5), g = kappa h^2 / sigma (kappa = 1 / R the curvature step): the
bias of a smoothing fit at a step of its curvature grows as (kappa h^2 / sigma)^(1/5) sigma (the bias-variance
balance of a kernel of width w at a step of the second derivative: kappa^2 w^4 ~ sigma^2 h / w). Prints the
statistic's quantiles over all cases, the constant of :data:`hob.rack_accuracy.ROUNDING_BIAS` (its 98.75 %
quantile: a lobe's four roundings at 95 %). Run from the repository: ``python benchmarks/bench_rounding_bias.py``
(about 1 min of CPU).
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np
import shapely

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tests"))

from independent_pairs import distance_to_line

from rotorcad.curves import Spline, sample_curve


def rounding(radius: float, turn: float = 1.0, flank: float = 6.0) -> np.ndarray:
    """The true shape: flank, rounding, flank (points 1 um apart, mm)."""
    s = np.arange(0.0, 2 * flank + radius * turn, 1e-3)
    kappa = np.where((s > flank) & (s < flank + radius * turn), 1.0 / radius, 0.0)
    theta = np.cumsum(kappa) * 1e-3
    return np.column_stack([np.cumsum(np.cos(theta)), np.cumsum(np.sin(theta))]) * 1e-3


def largest_error(radius: float, sigma: float, spacing: float, seed: int) -> float:
    """The fit's largest distance from the true shape within 2 mm of the rounding (mm)."""
    dense = rounding(radius)
    s = np.concatenate([[0.0], np.cumsum(np.hypot(*np.diff(dense, axis=0).T))])
    u = np.arange(0.37 * spacing, s[-1], spacing)
    q = np.column_stack([np.interp(u, s, dense[:, 0]), np.interp(u, s, dense[:, 1])])
    d = np.gradient(q, axis=0)  # the scatter's direction only
    normal = np.column_stack([d[:, 1], -d[:, 0]]) / np.hypot(*d.T)[:, None]
    q = q + np.random.default_rng(seed).normal(0.0, sigma, len(q))[:, None] * normal
    _, p, _ = sample_curve(Spline.fit(q, smoothing=len(q) * sigma**2), 1e-5)
    near = np.hypot(*(p - dense[len(dense) // 2]).T) < 0.5 * radius + 2.0
    return float(distance_to_line(p[near], shapely.LineString(dense)).max())


def main(seeds: int = 32) -> None:
    stats = []
    for sigma in (1e-3, 2e-3, 4e-3):
        for spacing in (0.1, 0.21, 0.42):
            for radius in (0.7, 1.0, 2.0, 4.0, 16.0):
                if radius / spacing < 3.0:  # a rounding of fewer than 3 points: not resolved
                    continue
                g = spacing**2 / (radius * sigma)
                z = np.array([largest_error(radius, sigma, spacing, k) for k in range(seeds)]) / (sigma * g**0.2)
                stats.append(z)
                print(
                    f"sigma {sigma * 1e3:.0f} um, h {spacing:.2f} mm, R {radius:5.1f} mm, g {g:7.2f}: "
                    f"error / (sigma g^0.2) median {np.median(z):.2f}, 95 % {np.quantile(z, 0.95):.2f}, max {z.max():.2f}"
                )
    z = np.concatenate(stats)
    print(f"all {len(z)}: median {np.median(z):.2f}, 95 % {np.quantile(z, 0.95):.2f}, 98.75 % {np.quantile(z, 0.9875):.2f}")


if __name__ == "__main__":
    main(int(sys.argv[1]) if len(sys.argv) > 1 else 32)

"""The rack accuracy's terms against closed forms (hob.rack_accuracy; issue 22 item 3).

The rack from a rotor's scattered points is stated to the larger of the profile's accuracy, the
smoothing fit's bias at a rounding and the fit's error at a sharp concave corner, plus the widest fold
of the rack. The terms are checked here on shapes whose truth is known in closed form; the statement
against the design racks of the rotor samples is in ``tests/test_hob_points_samples.py``.
"""

from __future__ import annotations

import numpy as np
import pytest
import shapely
from independent_pairs import distance_to_line

from hob.rack_accuracy import corner_error, rounding_bias, widest_fold
from rotorcad.curves import Spline, sample_curve
from rotorcad.inverse_rack import DerivedRack
from rotorcad.roles import PieceRole


def rounding(radius: float, turn: float, flank: float = 5.0) -> np.ndarray:
    """Closed form: a straight flank, a circular rounding of ``radius`` turning by ``turn`` rad, a straight flank (1 um apart)."""
    s = np.arange(0.0, 2 * flank + radius * turn, 1e-3)
    kappa = np.where((s > flank) & (s < flank + radius * turn), 1.0 / radius, 0.0)
    theta = np.cumsum(kappa) * 1e-3
    return np.column_stack([np.cumsum(np.cos(theta)), np.cumsum(np.sin(theta))]) * 1e-3


@pytest.mark.parametrize("radius,turn,spacing,sigma", [(3.0, 1.5, 0.25, 1.5e-3), (1.2, 0.8, 0.18, 2.5e-3)])
def test_the_rounding_bias_bounds_a_smoothing_fit_of_a_scattered_rounding(radius, turn, spacing, sigma):
    # A rounding (not one of benchmarks/bench_rounding_bias.py's, from which the factor comes) sampled every
    # `spacing` mm with `sigma` of Gaussian scatter along the normals, fitted as rotorcad fits scattered points
    # (FITPACK's smoothing spline by n sigma^2, Dierckx sec. 5.2). Reference: the closed-form shape (shapely's
    # point-to-polyline distance). Over 24 seeds the fit's largest error near the rounding stays within the bound,
    # and the bound is no shrug: the median error is more than a third of it (it is a bias, not k_N sigma).
    truth = rounding(radius, turn)
    line = shapely.LineString(truth)
    s = np.concatenate([[0.0], np.cumsum(np.hypot(*np.diff(truth, axis=0).T))])
    u = np.arange(0.37 * spacing, s[-1], spacing)
    q0 = np.column_stack([np.interp(u, s, truth[:, 0]), np.interp(u, s, truth[:, 1])])
    d = np.gradient(q0, axis=0)
    normal = np.column_stack([d[:, 1], -d[:, 0]]) / np.hypot(*d.T)[:, None]
    errors = []
    for seed in range(24):
        q = q0 + np.random.default_rng(seed).normal(0.0, sigma, len(q0))[:, None] * normal
        _, p, _ = sample_curve(Spline.fit(q, smoothing=len(q) * sigma**2), 1e-5)
        near = np.hypot(*(p - truth[len(truth) // 2]).T) < 0.5 * radius * turn + 2.0
        errors.append(distance_to_line(p[near], line).max())
    bound = rounding_bias(sigma, spacing, 1.0 / radius)
    assert max(errors) <= bound, (max(errors), bound)
    assert np.median(errors) >= bound / 3.0, (np.median(errors), bound)


def test_rounding_bias_of_exact_points_is_nil():
    assert rounding_bias(0.0, 0.2, 0.5) == 0.0


def test_the_widest_fold_is_the_middle_legs_offset():
    # Closed form: a rack along x that runs forward to x = 1 at y = 0, back to x = 0.6 at 10 um above, forward
    # again at 20 um (a fold of the generation: its middle leg against the exact tangent +x, from the first leg's
    # end); the fold's width, its points' largest distance from the legs beside it, is 20 um (the first leg's end
    # from the last leg). A reversal across two pieces' join (their ends overlapping by 3 um) is no fold.
    first = np.column_stack([np.linspace(0.0, 1.0, 21), np.zeros(21)])
    middle = np.column_stack([np.linspace(1.0, 0.6, 9)[1:], np.full(8, 0.01)])
    last = np.column_stack([np.linspace(0.6, 2.0, 29)[1:], np.full(28, 0.02)])
    pts = np.vstack([first, middle, last])
    n = len(pts)
    rack = DerivedRack(
        points=pts,
        tangents=np.tile([1.0, 0.0], (n, 1)),
        names=("flank",),
        piece_index=np.zeros(n, dtype=int),
        period=10.0,
        lost_fraction=0.0,
        pitch_radius=50.0,
        roles=(PieceRole.CURVE,),
    )
    assert widest_fold(rack) == pytest.approx(0.02, abs=1e-9)
    on = np.vstack([first[-1:] - [0.003, 0.0], np.column_stack([np.linspace(1.0, 2.0, 21)[1:], np.zeros(20)])])
    joined = DerivedRack(
        points=np.vstack([first, on]),
        tangents=np.tile([1.0, 0.0], (len(first) + len(on), 1)),
        names=("flank", "flank"),
        piece_index=np.repeat([0, 1], [len(first), len(on)]),
        period=10.0,
        lost_fraction=0.0,
        pitch_radius=50.0,
        roles=(PieceRole.CURVE, PieceRole.CURVE),
    )
    assert widest_fold(joined) == 0.0


def test_the_corner_error_is_the_crossing_of_two_offset_lines():
    # Closed form: two lines turning by theta, each offset by e along its normal, cross e / sin(theta / 2) from the
    # true corner at most (offsets of opposite sense across the bisector); the bound counts k_2m e for m corners.
    theta, e = np.radians(45.0), 1.0
    a = np.array([1.0, 0.0])
    b = np.array([np.cos(theta), -np.sin(theta)])
    na, nb = np.array([-a[1], a[0]]), np.array([-b[1], b[0]])
    worst = 0.0
    for sa in (-1.0, 1.0):
        for sb in (-1.0, 1.0):
            # crossing of p = sa e na + t a and q = sb e nb + u b
            t, _ = np.linalg.solve(np.column_stack([a, -b]), sb * e * nb - sa * e * na)
            worst = max(worst, float(np.hypot(*(sa * e * na + t * a))))
    assert worst == pytest.approx(e / np.sin(theta / 2), rel=1e-12)
    from rotorcad.measured.pairs import max_factor

    assert corner_error(2e-3, np.array([theta, np.radians(89.0)])) == pytest.approx(
        max_factor(4) * 2e-3 / np.sin(theta / 2), rel=1e-12
    )
    assert corner_error(2e-3, np.array([])) == 0.0

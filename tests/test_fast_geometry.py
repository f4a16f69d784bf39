"""The per-variant fast path's array helpers against numpy's own expressions, bit for bit.

numpy 2 broadcasts a (2,) row over an (n, 2) array, divides by an (n, 1) column and selects rows
by a boolean mask a row at a time, ten to thirty times slower than the same operations on the two
columns; np.hypot costs as much as ten multiplications. The helpers of :mod:`rotorcad.geometry`
(and the rewritten Line, Translation, Rotation and normalize) do the same arithmetic by columns,
or test a sum of squares first. The reference of every test is the numpy expression they replace
(``points + by``, ``np.einsum("ij,ij->i", a, b)``, ``a[mask]``, ``np.hypot(x, y) <= bound``,
``np.argmin(np.hypot(x, y))``, ``a + np.multiply.outer(s, d)``), which the helpers do not call,
on values chosen to be hard: NaN, infinities, signed zeros, ties, and points within an ulp of a
bound.
"""

from __future__ import annotations

import numpy as np
import pytest

from rotorcad.curves import Line
from rotorcad.geometry import dots, filled, hypot_within, nearest_hypot, normalize, shifted, take_rows, to_point
from rotorcad.kinematics import Rotation, Translation
from rotorcad.meshing.meshline import FLANK_CODE, flank_codes, flank_roles

RNG = np.random.default_rng(2026)


def _hard_points(n: int) -> np.ndarray:
    """Points over magnitudes 1e-9..1e3 with NaN, +-inf and signed zeros among them, (n, 2)."""
    p = RNG.normal(size=(n, 2)) * 10.0 ** RNG.integers(-9, 4, size=(n, 1))
    p[:5] = [[np.nan, 1.0], [np.inf, 2.0], [-np.inf, np.nan], [0.0, -0.0], [-0.0, 0.0]]
    return p


def _same(a: np.ndarray, b: np.ndarray) -> None:
    """Equal bit for bit: the values, NaN where NaN, and the sign of every zero."""
    assert a.shape == b.shape and a.dtype == b.dtype
    assert np.array_equal(a, b, equal_nan=True)
    number = ~np.isnan(a)
    assert np.array_equal(np.signbit(a[number]), np.signbit(b[number]))


def test_shifted_and_to_point_are_numpys_broadcast():
    # reference: numpy's broadcast of a (2,) row, points + by, points - by and q - points
    p = _hard_points(5000)
    for by in ([3.5, -1e-7], [0.0, -0.0], [1e300, 2.0]):
        q = np.array(by)
        _same(shifted(p, q), p + q)
        _same(shifted(p, tuple(by), -1.0), p - q)
        _same(to_point(p, q), q - p)
    stack = RNG.normal(size=(3, 10, 2))  # any other shape keeps the broadcast
    _same(shifted(stack, np.array([1.0, 2.0])), stack + np.array([1.0, 2.0]))
    centres = RNG.normal(size=(5000, 2))  # a centre per point
    _same(shifted(p, centres, -1.0), p - centres)
    _same(to_point(p, centres), centres - p)


def test_dots_filled_and_take_rows_are_numpys():
    # references: np.einsum's row dot products, a broadcast assignment, a boolean row mask
    a, b = _hard_points(5000), _hard_points(5000)[::-1].copy()
    b[:200:2] = -0.0  # products of signed zeros: einsum's sum starts at +0
    with np.errstate(invalid="ignore", over="ignore"):
        _same(dots(a, b), np.einsum("ij,ij->i", a, b))
    out = np.empty((7, 2))
    out[...] = np.array([1.5, -0.0])
    _same(filled(7, (1.5, -0.0)), out)
    for mask in (RNG.random(5000) < 0.3, np.ones(5000, bool), np.zeros(5000, bool)):
        _same(take_rows(a, mask), a[mask])


@pytest.mark.parametrize("scale", [1e-6, 1.0, 80.0])
def test_hypot_within_is_numpys_answer_at_the_bound(scale):
    # reference: np.hypot(x, y) <= bound, with points placed on the bound and one ulp either side
    # of its hypot, scalar and per-point bounds, NaN and infinities
    n = 4000
    angle = RNG.uniform(0.0, 2.0 * np.pi, n)
    r = scale * RNG.uniform(0.5, 1.5, n)
    x, y = r * np.cos(angle), r * np.sin(angle)
    h = np.hypot(x, y)
    x[:3], y[:3] = [np.nan, np.inf, 0.0], [1.0, np.nan, 0.0]
    for bound in (scale, h[n // 2], np.nextafter(h[n // 2], 0.0), np.nextafter(h[n // 2], np.inf)):
        assert np.array_equal(hypot_within(x, y, bound), np.hypot(x, y) <= bound)
    per_point = np.where(RNG.random(n) < 0.5, h, np.nextafter(h, 0.0))  # every point on or just off its bound
    assert np.array_equal(hypot_within(x, y, per_point), np.hypot(x, y) <= per_point)
    assert np.array_equal(hypot_within(x, y, 1e-300), np.hypot(x, y) <= 1e-300)  # near underflow: hypot itself


def test_nearest_hypot_is_numpys_argmin_and_min():
    # reference: np.argmin(np.hypot(x, y)) and its value: ties (the first wins), points on one
    # circle (hypot decides among sums of squares within an ulp), NaN (numpy's argmin returns it)
    for _ in range(200):
        n = int(RNG.integers(1, 400))
        angle = RNG.uniform(0.0, 2.0 * np.pi, n)
        r = RNG.choice([1.0, 57.99, 1e-3]) * (1.0 + RNG.integers(0, 3, n) * 1e-16)
        x, y = r * np.cos(angle) + RNG.choice([0.0, 1e-12]), r * np.sin(angle)
        if RNG.random() < 0.3:
            x[RNG.integers(n, size=2)] = x[0]  # ties with the first
            y[RNG.integers(n, size=2)] = y[0]
        if RNG.random() < 0.1:
            x[RNG.integers(n)] = np.nan
        h = np.hypot(x, y)
        i, value = nearest_hypot(x, y)
        assert i == int(np.argmin(h))
        assert value == h[i] or (np.isnan(value) and np.isnan(h[i]))


def test_normalize_line_and_motions_are_the_broadcast_formulas():
    # references: v / norm[:, None] (norm the sum of squares' root), a + outer(s, d) of a line,
    # p + outer(t, V) of a rack, rate * (-(y - yO), x - xO) of a rotor, numpy's broadcast all
    v = RNG.normal(size=(3000, 2)) * 10.0 ** RNG.integers(-6, 4, size=(3000, 1))
    norm = np.sqrt(v[:, 0] * v[:, 0] + v[:, 1] * v[:, 1])[:, None]
    _same(normalize(v), v / norm)
    v[7] = 0.0
    assert np.array_equal(normalize(v)[7], [0.0, 0.0]) and np.array_equal(normalize(v)[8], v[8] / norm[8])
    line = Line((3.25, -7.5), (11.0, 40.0))
    s = RNG.uniform(-5.0, 60.0, 999)
    a, d = np.asarray(line.a, float), line._start_and_direction[1]
    p, t = line.frame(s)
    _same(p, a + np.multiply.outer(s, d))
    _same(t, np.broadcast_to(d, (999, 2)).copy())
    rack = Translation((0.0, 37.27))
    pts = _hard_points(999)
    with np.errstate(invalid="ignore"):
        _same(rack.to_fixed(pts, s), pts + np.multiply.outer(s, rack.velocity_array))
        _same(rack.to_body(pts, s), pts - np.multiply.outer(s, rack.velocity_array))
    _same(rack.velocity_at(pts), np.broadcast_to(rack.velocity_array, (999, 2)).copy())
    rotor = Rotation((82.0, 0.0), -5.0 / 6.0)
    d2 = pts - np.array([82.0, 0.0])
    with np.errstate(invalid="ignore"):
        _same(rotor.velocity_at(pts), -5.0 / 6.0 * np.stack([-d2[:, 1], d2[:, 0]], axis=1))


def test_flank_codes_name_the_flank_roles():
    # reference: flank_roles' object array compared with each lobe part (the comparison the flank
    # reports made before they read the codes)
    pts = RNG.normal(size=(2000, 2)) * 5.0 + [40.0, 0.0]
    tan = normalize(RNG.normal(size=(2000, 2)))
    tan[::7, 0] = 0.0  # lands
    roles, codes = flank_roles(pts, tan, 40.0, 116.0), flank_codes(pts, tan, 40.0, 116.0)
    for flank, code in FLANK_CODE.items():
        assert np.array_equal(codes == code, roles == flank)

"""Kollek & Osinski: undercut model eq. (1), limit shifts, the gear pump (eqs. 2-9)."""

from __future__ import annotations

import numpy as np
import pytest

from hob.undercut import effective_addendum, kollek_model, limit_shift, practical_limit_shift, real_limit_shift
from rotorcad.gear import GearPair, InvoluteGear
from rotorcad.pump import GearPump, kollek_coefficients

DEG = np.pi / 180
A20 = 20 * DEG


def test_effective_addendum_and_limit_shift_match_the_tool_geometry():
    # Issue 4: x_g = h_a0* - rho_a0* (1 - sin a) - z sin^2(a) / 2, computed here from the tool.
    y = effective_addendum(1.25, 0.38, A20)
    assert y == pytest.approx(1.25 - 0.38 * (1 - np.sin(A20)))
    for z in (8, 11, 14):
        xg = 1.25 - 0.38 * (1 - np.sin(A20)) - z * np.sin(A20) ** 2 / 2
        assert limit_shift(z, A20, y) == pytest.approx(xg)
        # and the exact envelope's undercut switches there
        assert InvoluteGear(z, 1.0, A20, 0.0, xg - 1e-3).undercut and not InvoluteGear(z, 1.0, A20, 0.0, xg + 1e-3).undercut
    # practical limit: Niemann's (14 - z) / 17 for alpha = 20 deg and y = 1
    for z in (8, 11, 13):
        assert practical_limit_shift(z, A20, 1.0) == pytest.approx((14 - z) / 17, abs=0.02)


def test_model_agrees_with_the_exact_envelope_only_at_the_onset():
    # The quartic of eq. (1) is a truncated series: at the onset of undercut (p -> 0) the model's
    # active base radius tends to the exact one (both to r_b); deeper in, it departs. Stated here
    # as measured, the exact envelope being the reference.
    z, m = 11, 1.0
    y = effective_addendum(1.25, 0.38, A20)
    xg = limit_shift(z, A20, y)
    gaps = []
    for below in (5e-3, 5e-4, 5e-5):
        x = xg - below
        gaps.append(abs(kollek_model(z, m, A20, x, y).active_base_radius - InvoluteGear(z, m, A20, 0.0, x).form_radius))
    assert gaps[0] < 1e-2 * m and gaps[2] < gaps[1] < gaps[0] and gaps[2] < 1e-3 * m  # converges at the onset
    deep = 0.0
    exact_deep = InvoluteGear(z, m, A20, 0.0, deep).form_radius
    model = kollek_model(z, m, A20, deep, y)
    # far from the onset the model (an extended involute at the constant offset p, hob/undercut.py)
    # puts r'_z above the exact point by 0.25-0.34 p: 0.108 m for z = 11 (read as the OCR printed it,
    # 0.47 m, above the pitch circle)
    assert 0.25 * model.p < model.active_base_radius - exact_deep < 0.34 * model.p
    assert model.active_base_radius < z * m / 2
    assert not kollek_model(z, m, A20, xg + 0.01, y).undercut


def test_real_limit_lies_below_the_theoretical_one():
    # x''_g: a slight undercut does not cut the contact ratio yet (ineffective undercut).
    y = effective_addendum(1.25, 0.38, A20)
    xr = real_limit_shift(11, 1.0, A20, 1.0)
    assert xr < limit_shift(11, A20, y)
    g_above = InvoluteGear(11, 1.0, A20, 0.0, xr + 0.01)
    g_below = InvoluteGear(11, 1.0, A20, 0.0, xr - 0.01)
    assert not GearPair(g_above, g_above).tip_interference and GearPair(g_below, g_below).tip_interference


def test_pump_frequency():
    # Eq. (9): f = n z / 60; Kollek's 250 Hz is n z = 15 000; z = 11 at 1500 rpm gives 275 Hz.
    assert GearPump(InvoluteGear(11, 4.0, A20, 0.0, 0.3), 20.0, 1500).pump_frequency == pytest.approx(275.0)
    assert GearPump(InvoluteGear(10, 4.0, A20, 0.0, 0.3), 20.0, 1500).pump_frequency == pytest.approx(250.0)


@pytest.mark.parametrize("x", [0.3, 0.6])
def test_mean_delivery_closed_form(x):
    # Standard gear-pump theory: mean delivery b w (r_a^2 - r_w^2 - p_b^2 (eps^2/4 - eps/2 + 1/3)),
    # b w (r_a^2 - r_w^2 - p_b^2/12) for eps = 1 (the closed form of the issue).
    g = InvoluteGear(11, 4.0, A20, 0.0, x)
    p = GearPump(g, 20.0, 1500)
    eps = p.contact_ratio
    rw = g.base_radius / np.cos(GearPair(g, g).working_pressure_angle)
    w = 1500 * 2 * np.pi / 60
    closed = 20.0 * w * (g.tip_radius**2 - rw**2 - g.base_pitch**2 * (eps**2 / 4 - eps / 2 + 1 / 3))
    assert p.mean_flow == pytest.approx(closed, rel=1e-7)
    assert eps**2 / 4 - eps / 2 + 1 / 3 == pytest.approx(1 / 12 + (eps - 1) ** 2 / 4)  # = p_b^2/12 at eps = 1


@pytest.mark.parametrize("x", [0.2, 0.5, 0.9])
def test_fourier_series_matches_eqs_4_to_6(x):
    # Numerical cosine coefficients of the simulated delivery against eqs. (4)-(6): a0 = eps/2 - 1/3,
    # even a_n = 4/(pi n)^2, odd a_n = 4 (eps - 1)/(pi n)^2 (all / b w t_z^2).
    p = GearPump(InvoluteGear(11, 4.0, A20, 0.0, x), 20.0, 1500)
    np.testing.assert_allclose(p.cosine_series(8), kollek_coefficients(p.contact_ratio, 8), atol=5e-4)
    # the odd terms vanish as eps -> 1
    assert kollek_coefficients(1.0, 5)[1::2].max() == 0.0


def test_trapped_volume_is_symmetric_about_the_pitch_point():
    # Two contacts a base pitch apart move together along the line of action; the volume between
    # them shrinks until they lie symmetrically about C (u1 + u2 = 0) and grows back: it returns to
    # its start value with its minimum halfway (d/dphi V = b (u1^2 - u2^2), zero at u1 = -u2).
    g = InvoluteGear(11, 4.0, A20, 0.0, 0.3)
    p = GearPump(g, 20.0, 1500)
    phi, vol = p.trapped_volume(2001)
    assert len(phi) and abs(vol[-1] - vol[0]) < 1e-6 * np.abs(vol).max()
    i = int(np.argmin(vol))
    assert phi[i] == pytest.approx(phi[-1] / 2, abs=2 * (phi[1] - phi[0]))
    # depth of the dip: b p_b r_b (phi/2)^2 from the closed-form integral of -2 b p_b r_b (phi - phi_mid)
    half = phi[-1] / 2
    assert -vol[i] == pytest.approx(20.0 * g.base_pitch * g.base_radius * half**2, rel=1e-5)

"""Gear inspection from points against teeth made with known deviations (tests/inspection_teeth.py).

References: the involute and ISO 21771 closed forms (the teeth are written from the involute's
definition, not by rotorcad.inspection), the definitions of ISO 1328-1:2013 (clause 3: profile
evaluation range L_alpha, mean profile line, F_alpha, f_falpha, f_Halpha, f_pt, F_p) and the
standard's tolerance formulas (clause 5), evaluated by hand in the comments.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from rotorcad.gear import InvoluteGear
from rotorcad.inspection import flank_tolerances, inspect_gear, nominal_flanks
from rotorcad.inspection.tolerances import round_tolerance
from rotorcad.roles import ToothFlank
from tests.inspection_teeth import inv, teeth_points, transverse

DEG = math.pi / 180.0
SCATTER = 1.5e-3
"""mm: the CMM-like scatter added to every point, uniform in +-SCATTER (1.5 µm)."""
Z, M, ALPHA = 20, 4.0, 20.0 * DEG


@pytest.fixture(scope="module")
def spur():
    gear = InvoluteGear(teeth=Z, module=M)
    nominal = nominal_flanks(gear)
    # ISO 1328-1:2013: L_alpha from the start of the active profile (no mate: the form circle) over
    # 95 % of the way to the tip form circle (the tip circle); roll length xi = sqrt(R^2 - r_b^2)
    rb = M * Z / 2 * math.cos(ALPHA)
    lo = math.sqrt(gear.form_radius**2 - rb**2)
    hi = lo + 0.95 * (math.sqrt(gear.tip_radius**2 - rb**2) - lo)
    roll = np.linspace(lo - 0.5, math.sqrt(gear.tip_radius**2 - rb**2) - 0.01, 240)
    return gear, nominal, (lo, hi), roll


def test_the_evaluation_range_is_the_standards(spur):
    _gear, nominal, (lo, hi), _ = spur
    assert nominal.evaluation_range == pytest.approx((lo, hi), abs=1e-9)
    # the measuring circle of the pitch deviations: the middle of L_alpha
    rb = M * Z / 2 * math.cos(ALPHA)
    assert nominal.measuring_radius == pytest.approx(math.hypot(rb, (lo + hi) / 2), abs=1e-9)


def test_exact_teeth_turned_by_an_angle_give_that_angle_and_no_deviation(spur):
    _, nominal, _, roll = spur
    turn = 0.05  # rad, the points' frame against the gear's
    result = inspect_gear(teeth_points(Z, M, ALPHA, [0, 1, 2, 3], roll, rotation=turn), nominal)
    assert result.fit.rotation == pytest.approx(turn, abs=1e-12)
    assert sorted({f.tooth for f in result.flanks}) == [0, 1, 2, 3]
    for f in result.flanks:
        assert max(f.profile.total, f.profile.form, abs(f.profile.slope)) < 1e-9


def test_a_pressure_angle_error_is_a_slope_deviation_of_the_base_circle_relation(spur):
    gear, nominal, (lo, hi), roll = spur
    d_alpha = 0.15 * DEG
    pts = teeth_points(Z, M, ALPHA, [0, 1, 2], roll, alpha_actual=ALPHA + d_alpha, rotation=0.3, scatter=SCATTER)
    result = inspect_gear(pts, nominal)
    # closed form: an involute of base radius r_b' against one of r_b deviates along the roll length
    # with the slope (r_b' - r_b) / r_b (d(r_b (psi' - psi)) / d(xi) to first order), so
    # f_Halpha = L_alpha (r_b' - r_b) / r_b: -19.0 µm here, the same on both flanks
    rb = gear.pitch_radius * math.cos(ALPHA)
    rb_actual = gear.pitch_radius * math.cos(transverse(ALPHA + d_alpha, 0.0))
    expected = (hi - lo) * (rb_actual - rb) / rb
    # the exact deviation r_b (psi'(R) - psi(R)) bends a little near the base circle (the first-order
    # form's remainder): its form deviation about its own least-squares line, from the closed forms
    xi = np.linspace(lo, hi, 2001)
    radius = np.hypot(rb, xi)
    exact = rb * (
        inv(np.arccos(rb / radius)) - inv(np.arccos(rb_actual / radius)) + inv(transverse(ALPHA + d_alpha, 0)) - inv(ALPHA)
    )
    bow = np.ptp(exact - np.polyval(np.polyfit(xi, exact, 1), xi))
    assert bow < 0.05 * abs(expected)
    assert len(result.flanks) == 6
    for f in result.flanks:
        # the scatter's range 2 SCATTER, and the fitted line's own error at the ends of L_alpha: the
        # end value of a least-squares line through n points of standard deviation SCATTER / sqrt(3)
        # (uniform) has the standard deviation 2 SCATTER / sqrt(3 n); allowed twice over, on both lines
        line = 4 * SCATTER / math.sqrt(3 * f.profile.points) * 2
        assert f.profile.slope == pytest.approx(expected, abs=SCATTER)
        assert f.profile.form <= 2 * SCATTER + bow + line  # a straight line in the chart, but for the scatter
        assert f.profile.total == pytest.approx(abs(expected), abs=2 * SCATTER + bow)


def test_a_crowning_is_a_form_deviation_of_its_height(spur):
    _, nominal, (lo, hi), roll = spur
    height = 8e-3  # mm: a parabola over L_alpha, its vertex in the middle, 0 at both ends

    def crowning(xi: np.ndarray) -> np.ndarray:
        return height * (1.0 - ((xi - (lo + hi) / 2) / ((hi - lo) / 2)) ** 2)

    pts = teeth_points(Z, M, ALPHA, [5, 6], roll, deviation=crowning, scatter=SCATTER)
    result = inspect_gear(pts, nominal)
    # a symmetric parabola sampled evenly has a horizontal least-squares line: f_falpha = F_alpha =
    # its height, f_Halpha = 0 (ISO 1328-1:2013 definitions), within the scatter's range 2 SCATTER
    assert len(result.flanks) == 4
    for f in result.flanks:
        assert f.profile.form == pytest.approx(height, abs=2 * SCATTER)
        assert f.profile.total == pytest.approx(height, abs=2 * SCATTER)
        assert abs(f.profile.slope) <= SCATTER


def test_pitch_errors_imposed_on_chosen_teeth(spur):
    _, nominal, (lo, hi), roll = spur
    rb = M * Z / 2 * math.cos(ALPHA)
    r_m = math.hypot(rb, (lo + hi) / 2)  # the measuring circle (the middle of L_alpha)
    arcs = {1: 0.0, 2: 12e-3, 3: -5e-3, 4: 0.0, 5: 20e-3}  # mm on the measuring circle, + counter-clockwise
    turns = {k: a / r_m for k, a in arcs.items()}
    pts = teeth_points(Z, M, ALPHA, list(arcs), roll, tooth_turns=turns, rotation=-0.02, scatter=SCATTER)
    result = inspect_gear(pts, nominal)
    for f in result.flanks:
        if f.tooth == 1:
            assert f.single_pitch is None  # tooth 0 was not measured
            continue
        # f_pt: actual minus theoretical pitch from tooth k - 1 to tooth k, the same on both flanks
        assert f.single_pitch == pytest.approx(arcs[f.tooth] - arcs[f.tooth - 1], abs=SCATTER)
    for side in ToothFlank:
        worst = result.worst(side)
        assert worst["single_pitch_deviation"] == pytest.approx(20e-3, abs=SCATTER)  # |f_pt|: 12, -17, 5, 20 µm
        assert worst["cumulative_pitch_deviation"] == pytest.approx(25e-3, abs=SCATTER)  # 20 - (-5) µm


@pytest.mark.parametrize("beta_deg", [0.0, 15.0])
def test_a_tooth_thickness_change_is_the_shifts(beta_deg):
    beta = beta_deg * DEG
    gear = InvoluteGear(teeth=23, module=3.0, helix_angle=beta)
    nominal = nominal_flanks(gear)
    at = transverse(ALPHA, beta)
    rb = gear.pitch_radius * math.cos(at)
    roll = np.linspace(math.sqrt(gear.form_radius**2 - rb**2), math.sqrt(gear.tip_radius**2 - rb**2), 200)
    d_x = 0.01  # teeth cut with the shift 0.01 instead of 0
    pts = teeth_points(23, 3.0, ALPHA, [0, 7, 15], roll, beta=beta, shift=d_x, scatter=SCATTER)
    result = inspect_gear(pts, nominal)
    # ISO 21771: the normal tooth thickness on the reference circle grows by 2 x m_n tan(alpha_n)
    expected = 2 * d_x * 3.0 * math.tan(ALPHA)
    assert sorted(result.thickness) == [0, 7, 15]
    for value in result.thickness.values():
        assert value == pytest.approx(expected, abs=SCATTER)


def test_iso_1328_tolerances_against_values_worked_by_hand():
    # ISO 1328-1:2013 eqs. 5 to 9, class 5, m_n = 2 mm, d = 40 mm:
    # f_pT = 0.001*40 + 0.4*2 + 5 = 5.84 -> 6.0 (5 to 10 µm: to 0.5 µm)
    # F_pT = 0.002*40 + 0.55*sqrt(40) + 0.7*2 + 12 = 16.958 -> 17 (above 10 µm: whole µm)
    # f_HaT = 0.4*2 + 0.001*40 + 4 = 4.84 -> 4.8 (below 5 µm: to 0.1 µm)
    # f_faT = 0.55*2 + 5 = 6.1 -> 6.0; F_aT = sqrt(4.84^2 + 6.1^2) = 7.787 -> 8.0
    t = flank_tolerances(5, 2.0, 40.0)
    assert (t.single_pitch, t.cumulative_pitch, t.profile_slope, t.profile_form, t.total_profile) == pytest.approx(
        (6.0e-3, 17e-3, 4.8e-3, 6.0e-3, 8.0e-3)
    )
    # class 7 is class 5 times sqrt(2)^2 = 2: f_faT 12.2 -> 12, f_HaT 9.68 -> 9.5, F_aT 15.57 -> 16,
    # f_pT 11.68 -> 12, F_pT 33.92 -> 34
    t = flank_tolerances(7, 2.0, 40.0)
    assert (t.single_pitch, t.cumulative_pitch, t.profile_slope, t.profile_form, t.total_profile) == pytest.approx(
        (12e-3, 34e-3, 9.5e-3, 12e-3, 16e-3)
    )
    assert round_tolerance(4.84) == 4.8 and round_tolerance(7.25) == 7.5 and round_tolerance(10.5) == 11.0


def test_the_class_is_judged_from_the_worst_flank(spur):
    _gear, nominal, _, roll = spur
    pts = teeth_points(Z, M, ALPHA, [0, 1], roll, alpha_actual=ALPHA + 0.15 * DEG)
    summary = inspect_gear(pts, nominal, tolerance_class=5).summary()
    # f_Halpha ~ -19 µm against f_HaT of class 5 for m = 4, d = 80: 0.4*4 + 0.08 + 4 = 5.68 -> 5.5 µm
    assert summary["tolerances"]["profile_slope_tolerance"] == pytest.approx(5.5e-3)
    assert summary["within_tolerance"]["profile_slope_deviation"] is False
    # the finest class it meets: 5.68 * sqrt(2)^(A - 5) >= 19 first for A = 9 (22.72 -> 23 µm)
    assert summary["classes"]["profile_slope_deviation"] == 9

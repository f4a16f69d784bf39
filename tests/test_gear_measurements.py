"""Tooth-thickness allowances, span W_k, dimension over pins/balls M_d and the pair's backlash.

References, none of them the code under test:
* ISO 21771 / DIN 3960 closed forms, written out here in their own form (the involute function
  and its inverse here too, by scipy's brentq);
* a published worked example (MachineCalcs, "Span Measurement Over Teeth Calculator", worked
  example: z = 20, m = 2 mm, 20 deg, x = 0: k = 3, W = 15.321 mm, contact diameter 40.59 mm);
* brute force on the generated outline itself: the span between two parallel lines tangent to the
  sampled outline of k teeth (numpy), and a pin placed in the gap with shapely (the pin circle
  touching both flanks, found by bisection on its centre radius). Required within 1 um.
"""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np
import pytest
import shapely
import shapely.ops
from scipy.optimize import brentq

from exports.csv_points import read_points
from rotorcad.cli.main import main
from rotorcad.errors import DesignError
from rotorcad.gears.allowances import ThicknessAllowance, pair_backlash, thinned
from rotorcad.gears.involute_gear import InvoluteGear
from rotorcad.gears.measurements import ball_diameter, measurements, over_balls, span, span_teeth
from rotorcad.gears.pair import GearPair

DEG = math.pi / 180.0
BRUTE_TOL = 1e-4  # mm: 0.1 um asserted, 1 um required

# (teeth, module, shift, helix deg): even and odd, spur and helical, shifted both ways
GEARS = [(20, 2.0, 0.0, 0.0), (17, 3.0, 0.3, 0.0), (23, 3.0, -0.2, 15.0), (24, 3.0, 0.4, 25.0), (40, 1.5, 0.1, -20.0)]
ALLOWANCES = (0.0, -0.035, -0.12)


def inv_ref(a: float) -> float:
    return math.tan(a) - a


def inv_inverse_ref(v: float) -> float:
    return brentq(lambda a: inv_ref(a) - v, 1e-9, math.pi / 2 - 1e-6, xtol=1e-15, rtol=1e-15)


def iso_span(z, m, x, beta, k, a_sn, alpha=20 * DEG):
    """ISO 21771 / DIN 3960: W_k = m_n cos(a_n) [pi (k - 0.5) + z inv(a_t)] + 2 x m_n sin(a_n) + A_sn cos(a_n)."""
    at = math.atan(math.tan(alpha) / math.cos(beta))
    return m * math.cos(alpha) * (math.pi * (k - 0.5) + z * inv_ref(at)) + 2 * x * m * math.sin(alpha) + a_sn * math.cos(alpha)


def iso_over_balls(z, m, x, beta, d_m, a_sn, alpha=20 * DEG):
    """ISO 21771 / DIN 3960 dimension over balls with the generating shift x_E = x + A_sn / (2 m tan a_n)."""
    at = math.atan(math.tan(alpha) / math.cos(beta))
    x_e = x + a_sn / (2 * m * math.tan(alpha))
    a_k = inv_inverse_ref(inv_ref(at) + d_m / (z * m * math.cos(alpha)) - math.pi / (2 * z) + 2 * x_e * math.tan(alpha) / z)
    d_b = z * m / math.cos(beta) * math.cos(at)
    d_k = d_b / math.cos(a_k)
    return (d_k if z % 2 == 0 else d_k * math.cos(math.pi / (2 * z))) + d_m


def make(z, m, x, beta_deg, tol=1e-4):
    return InvoluteGear(z, m, shift=x, helix_angle=beta_deg * DEG, tolerance=tol)


# ---------------------------------------------------------------- closed forms and worked example
def test_span_worked_example():
    # MachineCalcs worked example: z = 20, m = 2, 20 deg, x = 0 -> k = 3, W = 15.321 mm, d_c = 40.59 mm
    g = make(20, 2.0, 0.0, 0.0)
    out = measurements(g)
    assert out["span_teeth"] == 3
    assert out["span"]["nominal"] == pytest.approx(15.321, abs=5e-4)
    assert 2 * out["span_contact_radius"] == pytest.approx(40.59, abs=5e-3)


@pytest.mark.parametrize("z", [8, 12, 17, 20, 26, 35, 47, 60, 90, 99, 150])
def test_span_teeth_rule_spur(z):
    # the rule for an unshifted 20 degree spur gear: k = z alpha / 180 deg + 0.5 = z / 9 + 0.5, rounded to
    # the nearest, a half upwards (z = 90, 99 give exact halves)
    assert span_teeth(make(z, 2.0, 0.0, 0.0)) == math.floor(z / 9 + 1.0)


@pytest.mark.parametrize(("z", "m", "x", "beta"), GEARS)
def test_span_teeth_rule_helical_shifted(z, m, x, beta):
    # ISO 21771 / DIN 3960: k = z/pi [tan(a_Mt) / cos^2(b_b) - 2 x tan(a_n) / z - inv(a_t)] + 0.5, d_M = d + 2 x m_n
    a = 20 * DEG
    b = beta * DEG
    at = math.atan(math.tan(a) / math.cos(b))
    bb = math.asin(math.sin(b) * math.cos(a))
    d = z * m / math.cos(b)
    a_m = math.acos(d * math.cos(at) / (d + 2 * x * m))
    k = z / math.pi * (math.tan(a_m) / math.cos(bb) ** 2 - 2 * x * math.tan(a) / z - inv_ref(at)) + 0.5
    assert span_teeth(make(z, m, x, beta)) == math.floor(k + 0.5)


@pytest.mark.parametrize(("z", "m", "x", "beta"), GEARS)
@pytest.mark.parametrize("a_sn", ALLOWANCES)
def test_span_and_over_balls_closed_forms(z, m, x, beta, a_sn):
    g = make(z, m, x, beta)
    k = span_teeth(g)
    assert span(g, k, a_sn) == pytest.approx(iso_span(z, m, x, beta * DEG, k, a_sn), abs=1e-10)
    d_m = ball_diameter(g)
    assert over_balls(g, d_m, a_sn) == pytest.approx(iso_over_balls(z, m, x, beta * DEG, d_m, a_sn), abs=1e-9)


def test_ball_diameter_rule():
    # an unshifted 20 degree gear of many teeth: D_M -> pi m / (2 cos 20 deg) = 1.672 m, the
    # "about 1.68 m" of the shop tables (the pin touching at the pitch circle)
    # (1000 teeth: the rest of order 1 / z)
    g = make(1000, 1.0, 0.0, 0.0)
    assert ball_diameter(g) == pytest.approx(math.pi / (2 * math.cos(20 * DEG)), abs=1.5e-3)
    # for every gear the rule's ball touches the flanks on the measuring circle d + 2 x m_n
    for z, m, x, beta in GEARS:
        g = make(z, m, x, beta)
        out = measurements(g)
        assert out["pin_contact_radius"] == pytest.approx(g.pitch_radius + x * m, abs=1e-5)  # D_M rounded to 1 um
        assert out["pin_touches_flank"]


def test_allowance_changes_follow_din_3960_approximations():
    # DIN 3960: the span changes by A_sn cos(a_n); the dimension over balls by about
    # A_sn cos(a_t) / (sin(a_Kt) cos(b)) (even z, first order in A_sn)
    z, m, x, beta = 24, 3.0, 0.4, 25.0
    g = make(z, m, x, beta)
    a = 20 * DEG
    b = beta * DEG
    at = math.atan(math.tan(a) / math.cos(b))
    out = measurements(g, ThicknessAllowance(-0.01, -0.02))
    assert out["span"]["lower"] - out["span"]["nominal"] == pytest.approx(-0.02 * math.cos(a), abs=1e-12)
    d_m = out["pin_diameter"]
    d_b = z * m / math.cos(b) * math.cos(at)
    a_k = math.acos(d_b / (out["over_pins"]["nominal"] - d_m))
    expected = -0.02 * math.cos(at) / (math.sin(a_k) * math.cos(b))
    assert out["over_pins"]["lower"] - out["over_pins"]["nominal"] == pytest.approx(expected, rel=2e-3)


# ---------------------------------------------------------------- the thinned outline
@pytest.mark.parametrize(("z", "m", "x", "beta"), GEARS)
def test_thinned_gear_keeps_tip_and_thins_tooth(z, m, x, beta):
    g = make(z, m, x, beta)
    a_sn = -0.12
    t = thinned(g, a_sn)
    assert t.tip_radius == pytest.approx(g.tip_radius, abs=1e-12)
    # ISO 21771: transverse tooth thickness on the reference circle s_t = m_t (pi/2 + 2 x tan a_n) + A_sn / cos(beta)
    m_t = m / math.cos(beta * DEG)
    s_t = m_t * (math.pi / 2 + 2 * x * math.tan(20 * DEG)) + a_sn / math.cos(beta * DEG)
    assert t.tooth_thickness(t.pitch_radius) == pytest.approx(s_t, abs=1e-9)
    # the rack fed in by A_sn / (2 tan a_n) deepens the root by as much
    assert t.root_radius == pytest.approx(g.root_radius + a_sn / (2 * math.tan(20 * DEG)), abs=1e-12)


def brute_span(gear: InvoluteGear, k: int, tol: float = 1e-6) -> float:
    """Span over teeth 0..k-1 between two parallel lines tangent to the sampled outline (transverse)."""
    pts = gear.outline(tol).points
    z = gear.teeth
    axis = (k - 1) * np.pi / z  # the symmetry line of the k teeth
    rel = np.angle(np.exp(1j * (np.arctan2(pts[:, 1], pts[:, 0]) - axis)))
    keep = (np.abs(rel) < k * np.pi / z) & (np.hypot(pts[:, 0], pts[:, 1]) >= gear.form_radius)
    across = pts[keep] @ np.array([-np.sin(axis), np.cos(axis)])
    return float(across.max() - across.min())


def brute_over_pins(gear: InvoluteGear, d_m: float, tol: float = 1e-6) -> tuple[float, float]:
    """Pin of diameter d_m (transverse) in space 0 touching both flanks: bisection on its centre radius.

    Returns the dimension over two such pins and the radius of the outline point nearest the pin's centre.
    """
    poly = shapely.Polygon(gear.outline(tol).points)
    boundary = poly.exterior
    z = gear.teeth
    c, s = math.cos(math.pi / z), math.sin(math.pi / z)

    def clear(r: float) -> bool:  # the pin of centre radius r stays clear of the gear
        p = shapely.Point(r * c, r * s)
        return not poly.contains(p) and boundary.distance(p) >= d_m / 2

    lo, hi = gear.root_radius, gear.tip_radius + 2 * d_m
    assert clear(hi) and not clear(lo)
    for _ in range(60):
        mid = 0.5 * (lo + hi)
        lo, hi = (lo, mid) if clear(mid) else (mid, hi)
    r = 0.5 * (lo + hi)
    touch = shapely.ops.nearest_points(boundary, shapely.Point(r * c, r * s))[0]
    return 2 * r * (1.0 if z % 2 == 0 else math.cos(math.pi / (2 * z))) + d_m, math.hypot(touch.x, touch.y)


@pytest.mark.parametrize(("z", "m", "x", "beta"), GEARS)
@pytest.mark.parametrize("a_sn", [0.0, -0.12])
def test_span_brute_force_on_outline(z, m, x, beta, a_sn):
    g = make(z, m, x, beta)
    k = span_teeth(g)
    t = thinned(g, a_sn)
    # the normal-section span of an involute helicoid is the transverse one times cos(beta_b) (ISO 21771)
    bb = math.asin(math.sin(beta * DEG) * math.cos(20 * DEG))
    assert brute_span(t, k) * math.cos(bb) == pytest.approx(span(g, k, a_sn), abs=BRUTE_TOL)


@pytest.mark.parametrize(("z", "m", "x", "beta"), GEARS)
@pytest.mark.parametrize("a_sn", [0.0, -0.12])
def test_over_pins_brute_force_on_outline(z, m, x, beta, a_sn):
    g = make(z, m, x, beta)
    d_m = ball_diameter(g)
    t = thinned(g, a_sn)
    # a ball of radius rho touching two involute helicoids has its centre where a transverse circle of
    # radius rho / cos(beta_b) touching the transverse flanks has it (the helicoid offset by rho is
    # the same helicoid turned by rho / (r_b cos beta_b)); for a spur gear the pin itself
    bb = math.asin(math.sin(beta * DEG) * math.cos(20 * DEG))
    transverse, touch = brute_over_pins(t, d_m / math.cos(bb))
    measured = transverse - d_m / math.cos(bb) + d_m
    assert measured == pytest.approx(over_balls(g, d_m, a_sn), abs=BRUTE_TOL)
    if a_sn == 0.0:  # the standard ball touches the nominal flanks on the measuring circle d + 2 x m_n
        assert touch == pytest.approx(g.pitch_radius + x * m, abs=1e-3)


# ---------------------------------------------------------------- backlash of a pair
def test_pair_backlash_closed_form():
    # ISO 21771: on the working pitch circles j_wt = d_w/z [(z1 + z2)(inv a_wt - inv a_t) - 2 (x1E + x2E) tan a_n],
    # normal backlash j_bn = j_wt cos(a_wt) cos(b_b)
    a, b = 20 * DEG, 12 * DEG
    g, mate = InvoluteGear(17, 3.0, shift=0.3, helix_angle=b), InvoluteGear(29, 3.0, shift=-0.1, helix_angle=-b)
    aw_given = 71.2
    pair = GearPair(g, mate, aw_given)
    a1, a2 = ThicknessAllowance(-0.05, -0.12), ThicknessAllowance(-0.07, -0.15)
    out = pair_backlash(pair, a1, a2)
    at = math.atan(math.tan(a) / math.cos(b))
    m_t = 3.0 / math.cos(b)
    aw = math.acos((17 + 29) * m_t / 2 * math.cos(at) / aw_given)
    bb = math.asin(math.sin(b) * math.cos(a))
    for name, s1, s2 in (("nominal", 0.0, 0.0), ("max", -0.12, -0.15), ("min", -0.05, -0.07)):
        x1 = 0.3 + s1 / (2 * 3.0 * math.tan(a))
        x2 = -0.1 + s2 / (2 * 3.0 * math.tan(a))
        j = m_t * math.cos(at) / math.cos(aw) * ((17 + 29) * (inv_ref(aw) - inv_ref(at)) - 2 * (x1 + x2) * math.tan(a))
        assert out["circumferential"][name] == pytest.approx(j, abs=1e-9)
        assert out["normal"][name] == pytest.approx(j * math.cos(aw) * math.cos(bb), abs=1e-9)


def test_pair_backlash_at_reference_distance_spur():
    # unshifted spur gears at a = r1 + r2: the backlash is the thinning itself, j_t = -(A_sn1 + A_sn2)
    pair = GearPair(InvoluteGear(20, 2.0), InvoluteGear(31, 2.0))
    out = pair_backlash(pair, ThicknessAllowance(-0.02, -0.06), ThicknessAllowance(-0.03, -0.04))
    assert out["circumferential"]["max"] == pytest.approx(0.10, abs=1e-9)
    assert out["circumferential"]["min"] == pytest.approx(0.05, abs=1e-9)
    assert out["normal"]["max"] == pytest.approx(0.10 * math.cos(20 * DEG), abs=1e-9)


# ---------------------------------------------------------------- bad input
@pytest.mark.parametrize(
    ("upper", "lower", "param"),
    [
        (0.01, -0.1, "thickness_allowance_upper"),
        (-0.1, -0.05, "thickness_allowance_lower"),
        (-0.01, -5.0, "thickness_allowance_lower"),
    ],
)
def test_bad_allowances_are_named(upper, lower, param):
    with pytest.raises(DesignError) as err:
        measurements(make(20, 2.0, 0.0, 0.0), ThicknessAllowance(upper, lower))
    assert err.value.param == param


def test_bad_span_teeth_and_pin():
    g = make(20, 2.0, 0.0, 0.0)
    with pytest.raises(DesignError, match="span_teeth"):
        measurements(g, k=20)
    with pytest.raises(DesignError, match="pin_diameter"):
        measurements(g, diameter=-1.0)


# ---------------------------------------------------------------- the command
def run(capsys, *args):
    rc = main([str(a) for a in args])
    out = capsys.readouterr()
    return rc, out.out, out.err


def test_cli_keys_and_mid_tolerance_outline(tmp_path, capsys):
    csv = tmp_path / "g.csv"
    rc, out, err = run(
        capsys,
        "gear",
        "--teeth", 21, "--module", 2.5, "--shift", 0.2,
        "--thickness-allowance-upper", -0.04, "--thickness-allowance-lower", -0.1,
        "--mate-teeth", 34, "--mate-thickness-allowance-upper", -0.05, "--mate-thickness-allowance-lower", -0.09,
        "--csv", csv, "--json",
    )  # fmt: skip
    assert rc == 0, err
    data = json.loads(out)
    assert data["thickness_allowance"] == {"upper": -0.04, "lower": -0.1}
    k = data["span_teeth"]
    for name, a_sn in (("nominal", 0.0), ("upper", -0.04), ("lower", -0.1)):
        assert data["span"][name] == pytest.approx(iso_span(21, 2.5, 0.2, 0.0, k, a_sn), abs=1e-10)
        assert data["over_pins"][name] == pytest.approx(iso_over_balls(21, 2.5, 0.2, 0.0, data["pin_diameter"], a_sn), abs=1e-9)
    assert {"span", "over_pins", "pin_diameter", "span_teeth"} <= set(data["mate"])
    assert data["backlash_circumferential"]["max"] > data["backlash_circumferential"]["min"] > 0
    # the CSV holds the tooth at the middle of the field, A_sn = -0.07: its span by brute force
    pts = read_points(csv)
    g = InvoluteGear(21, 2.5, shift=0.2)
    poly = shapely.Polygon(pts)
    made = thinned(g, -0.07)
    assert shapely.Polygon(made.outline().points).symmetric_difference(poly).area < 1e-6
    assert abs(poly.area - shapely.Polygon(g.outline().points).area) > 1e-3  # not the nominal gear


def test_cli_options_given(capsys):
    rc, out, _ = run(capsys, "gear", "--teeth", 30, "--module", 2, "--span-teeth", 5, "--pin-diameter", 3.5, "--json")
    data = json.loads(out)
    assert rc == 0 and data["span_teeth"] == 5 and data["pin_diameter"] == 3.5
    assert data["span"]["nominal"] == pytest.approx(iso_span(30, 2.0, 0.0, 0.0, 5, 0.0), abs=1e-10)


@pytest.mark.parametrize(
    ("args", "named"),
    [
        (["--thickness-allowance-upper", 0.1], "--thickness-allowance-upper"),
        (["--thickness-allowance-upper", -0.1, "--thickness-allowance-lower", -0.05], "--thickness-allowance-lower"),
        (["--span-teeth", 0], "--span-teeth"),
        (["--pin-diameter", 0], "--pin-diameter"),
        (["--mate-teeth", 30, "--mate-thickness-allowance-lower", 0.2], "--mate-thickness-allowance-lower"),
    ],
)
def test_cli_bad_values_one_sentence(tmp_path, capsys, args, named):
    csv = tmp_path / "g.csv"
    rc, out, err = run(capsys, "gear", "--teeth", 20, "--module", 2, "--csv", csv, *args)
    assert rc == 2 and out == ""
    assert named in err and "Traceback" not in err and err.count("\n") == 1
    assert not csv.exists()


def test_design_keys_are_named(tmp_path, capsys):
    design = tmp_path / "g.toml"
    design.write_text("[gear]\nteeth = 20\nmodule = 2\nthickness_allowance_upper = -0.02\nthickness_allowance_lower = -0.01\n")
    rc, _, err = run(capsys, "gear", design, "--json")
    assert rc == 2 and "[gear] thickness_allowance_lower" in err
    design.write_text("[gear]\nteeth = 20\nmodule = 2\nthickness_allowance_upper = -0.02\nthickness_allowance_lower = -0.05\n")
    rc, out, _ = run(capsys, "gear", design, "--json")
    assert rc == 0 and json.loads(out)["span"]["lower"] == pytest.approx(iso_span(20, 2.0, 0, 0, 3, -0.05), abs=1e-10)


def test_export_writes_the_mid_tolerance_tooth(tmp_path, capsys):
    # rotorcad export: the gear's section as made at A_sn = (upper + lower) / 2 = -0.06; its tooth
    # thickness on the reference circle is ISO 21771's s = m (pi/2 + 2 x tan a) + A_sn (spur), measured
    # on the written CSV with shapely (a circle cut by the section)
    design = tmp_path / "g.toml"
    design.write_text(
        "[gear]\nteeth = 17\nmodule = 3.0\nshift = 0.3\nthickness_allowance_upper = -0.04\nthickness_allowance_lower = -0.08\n"
    )
    out = tmp_path / "o"
    assert main(["export", str(design), "--out", str(out), "--format", "csv", "--tolerance", "0.0001", "--json"]) == 0
    files = json.loads(capsys.readouterr().out)["files"]
    section = shapely.Polygon(read_points(next(Path(f["path"]) for f in files if f["body"] == "gear")))
    r = 17 * 3.0 / 2
    t = np.linspace(0, 2 * np.pi, 400_001)
    circle = shapely.LineString(r * np.column_stack([np.cos(t), np.sin(t)]))
    expected = 3.0 * (np.pi / 2 + 2 * 0.3 * np.tan(20 * DEG)) - 0.06
    arcs = [a.length for a in shapely.get_parts(circle.intersection(section)) if a.length > 0.75 * expected]
    assert len(arcs) >= 16
    np.testing.assert_allclose(arcs, expected, atol=1e-4)


def test_no_standard_ball_for_few_teeth_and_a_large_shift():
    # 5 teeth shifted by 2.15 modules: the base tangent through the point on d + 2 x m_n leaves the
    # space before it meets the space's centre line, so no ball touches there (the rule's D_M <= 0):
    # the pin's values are null, and a given pin is measured over
    g = InvoluteGear(
        5,
        2.0,
        pressure_angle=22.86 * DEG,
        helix_angle=-16.73 * DEG,
        shift=2.149,
        addendum=0.573,
        dedendum=0.978,
        tip_radius_factor=0.1,
    )
    assert ball_diameter(g) <= 0.0
    out = measurements(g)
    assert out["pin_diameter"] is None and set(out["over_pins"].values()) == {None} and out["pin_touches_flank"] is False
    assert out["span"]["nominal"] == pytest.approx(
        iso_span(5, 2.0, 2.149, -16.73 * DEG, out["span_teeth"], 0.0, 22.86 * DEG), abs=1e-10
    )
    given = measurements(g, diameter=1.0)
    assert given["over_pins"]["nominal"] == pytest.approx(
        iso_over_balls(5, 2.0, 2.149, -16.73 * DEG, 1.0, 0.0, 22.86 * DEG), abs=1e-9
    )

"""Gear coupling film (Belkov, Maksimov & Shitikov) and ``rotorcad coupling`` (CONTRACT.md).

References, each computed here and not by the code under test: Hertz line contact (Johnson,
*Contact Mechanics*, 4.3), Martin (1916) rigid isoviscous cylinder h_min = 4.9 mu u R / w',
Dowson & Higginson (1977) H_min = 2.65 U^0.7 G^0.54 W^-0.13 and Pan & Hamrock (1989)
H_min = 1.714 U^0.694 G^0.568 W^-0.128 for the elastohydrodynamic line contact, the paper's own
closed forms (b_0 = 0.34e-5 sqrt(w R); V_cp from the quarter-turn mean of V_s).
"""

from __future__ import annotations

import json
import math

import numpy as np
import pytest

from rotorcad.cli.main import main
from rotorcad.coupling import GearCoupling, Verdict, analyse, load_capacity_at
from rotorcad.coupling_film import LineContact, solve_line_contact

E_STEEL, NU_STEEL = 2.0e11, 0.3
E_PRIME = E_STEEL / (1.0 - NU_STEEL**2)  # Hamrock's E' of two equal steel bodies

BASE = dict(
    teeth=40,
    module=4.0,
    face_width=32.0,
    speed_rpm=8000.0,
    power_kw=4000.0,
    viscosity=0.02,
    pressure_viscosity=2e-8,
    misalignment=math.radians(0.3),
)
ARGS = ["--teeth", "40", "--module", "4", "--face-width", "32", "--speed", "8000", "--viscosity", "0.02", "--power", "4000"]
ARGS += ["--pressure-viscosity", "2e-8", "--misalignment-deg", "0.3"]


def dowson_higginson(c: LineContact) -> float:
    """Dowson & Higginson (1977) minimum film of a line contact [m]."""
    r = c.radius
    return (
        2.65
        * (c.viscosity * c.speed / (E_PRIME * r)) ** 0.7
        * (c.pressure_viscosity * E_PRIME) ** 0.54
        * (c.load / (E_PRIME * r)) ** -0.13
        * r
    )


def pan_hamrock(c: LineContact) -> float:
    """Pan & Hamrock (1989) minimum film of a line contact [m]."""
    r = c.radius
    u, g, w = c.viscosity * c.speed / (E_PRIME * r), c.pressure_viscosity * E_PRIME, c.load / (E_PRIME * r)
    return 1.714 * u**0.694 * g**0.568 * w**-0.128 * r


def run(capsys, *args):
    rc = main([str(a) for a in args])
    out = capsys.readouterr()
    return rc, out.out, out.err


# --- film solver against closed forms ---------------------------------------------------------


def test_rigid_isoviscous_film_is_martins():
    # Martin (1916), Reynolds outlet condition: w' = 4.9 mu u R / h_min for a rigid cylinder on a plane,
    # u the mean entraining speed; elasticity (E' = inf) and pressure-viscosity (alpha_0 = 0) off
    for radius, load, speed, mu in ((0.02, 1e5, 5.0, 0.05), (1.5, 3e5, 3.0, 0.02)):
        c = LineContact(radius=radius, load=load, speed=speed, viscosity=mu, pressure_viscosity=0.0, modulus=math.inf)
        s = solve_line_contact(c)
        assert s.converged
        martin = 4.9 * mu * speed * radius / load
        assert s.min_film == pytest.approx(martin, rel=0.02)


def test_rigid_isoviscous_capacity_is_proportional_to_viscosity_and_speed():
    # Martin: at a given film the capacity is w' = 4.9 mu u R / h, linear in mu and in u
    c = LineContact(radius=0.05, load=2e5, speed=2.0, viscosity=0.03, pressure_viscosity=0.0, modulus=math.inf)
    h = 4.9 * c.viscosity * c.speed * c.radius / c.load
    w1 = load_capacity_at(c, h)
    assert w1 == pytest.approx(c.load, rel=0.02)
    assert load_capacity_at(LineContact(0.05, 2e5, 2.0, 0.06, 0.0, math.inf), h) == pytest.approx(2.0 * w1, rel=0.01)
    assert load_capacity_at(LineContact(0.05, 2e5, 6.0, 0.03, 0.0, math.inf), h) == pytest.approx(3.0 * w1, rel=0.01)


def test_hertz_half_width_and_pressure():
    # Hertz line contact: b = sqrt(4 w R / (pi E*)), p_H = 2 w / (pi b), 1/E* = 2 (1 - nu^2) / E;
    # the paper's b_0 = 0.34e-5 sqrt(w R) (SI) is that half-width for steel
    c = LineContact(radius=0.8, load=5e5, speed=1.0, viscosity=0.02, pressure_viscosity=2e-8)
    e_star = E_STEEL / (2.0 * (1.0 - NU_STEEL**2))
    b = math.sqrt(4.0 * c.load * c.radius / (math.pi * e_star))
    assert c.hertz_half_width == pytest.approx(b, rel=1e-9)
    assert c.hertz_pressure == pytest.approx(2.0 * c.load / (math.pi * b), rel=1e-9)
    assert c.hertz_half_width == pytest.approx(0.34e-5 * math.sqrt(c.load * c.radius), rel=0.01)


def test_heavy_load_film_pressure_tends_to_hertz():
    # Under a heavy load (Moes M ~ 100) the EHL pressure is the dry Hertz semi-ellipse inside the
    # contact except near the outlet, and the film carries the load: int p dx = w'
    c = LineContact(radius=0.02, load=1e6, speed=2.0, viscosity=0.01, pressure_viscosity=1e-8)
    s = solve_line_contact(c)
    b, p_h = c.hertz_half_width, c.hertz_pressure
    inside = np.abs(s.x) < 0.6 * b
    hertz = p_h * np.sqrt(1.0 - (s.x[inside] / b) ** 2)
    assert np.abs(s.pressure[inside] - hertz).max() < 0.05 * p_h
    assert s.load_capacity == pytest.approx(c.load, rel=1e-3)


@pytest.mark.parametrize(
    "radius, load, speed",
    [(1.53, 2.3e5, 4.0), (1.53, 1e6, 4.0), (0.5, 1e6, 2.0), (0.05, 1e6, 5.0)],
)
def test_film_against_dowson_higginson_and_pan_hamrock(radius, load, speed):
    # same load, speed and materials: within a factor 0.7...1.4 of both standard formulas
    c = LineContact(radius=radius, load=load, speed=speed, viscosity=0.02, pressure_viscosity=2e-8)
    h = solve_line_contact(c).min_film
    assert 0.7 < h / dowson_higginson(c) < 1.4
    assert 0.7 < h / pan_hamrock(c) < 1.4


def test_film_trends_match_ehl_theory():
    # Dowson-Higginson: h ~ u^0.70 and h ~ w'^-0.13; the solver's exponents over a factor 4 in
    # speed and in load are within 0.15 of these
    base = dict(radius=0.5, viscosity=0.02, pressure_viscosity=2e-8)
    h = {
        (w, u): solve_line_contact(LineContact(load=w, speed=u, **base)).min_film for w, u in ((1e6, 1.0), (1e6, 4.0), (4e6, 1.0))
    }
    speed_exponent = math.log(h[1e6, 4.0] / h[1e6, 1.0]) / math.log(4.0)
    load_exponent = math.log(h[4e6, 1.0] / h[1e6, 1.0]) / math.log(4.0)
    assert abs(speed_exponent - 0.70) < 0.15
    assert abs(load_exponent - -0.13) < 0.15 and load_exponent < 0


def test_ehl_capacity_rises_with_viscosity_and_speed():
    # at a fixed minimum film the film carries more load with a thicker oil or a faster contact
    c = LineContact(radius=0.5, load=1e6, speed=2.0, viscosity=0.02, pressure_viscosity=2e-8)
    h = 0.8 * solve_line_contact(c).min_film
    w = load_capacity_at(c, h)
    assert w > c.load  # a thinner film than the load's own needs a larger load
    assert load_capacity_at(LineContact(0.5, 1e6, 2.0, 0.04, 2e-8), h) > 1.5 * w
    assert load_capacity_at(LineContact(0.5, 1e6, 4.0, 0.02, 2e-8), h) > 1.5 * w


# --- coupling model ----------------------------------------------------------------------------


def test_coupling_kinematics_closed_forms():
    c = GearCoupling(**BASE)
    n, z, m, gamma = BASE["speed_rpm"], BASE["teeth"], BASE["module"], BASE["misalignment"]
    # paper: V_cp = (2/pi) int_0^pi/2 R omega sin(gamma) cos(phi) dphi = z m n sin(gamma) / 30 [mm/s, m in mm]
    assert c.mean_sliding_speed == pytest.approx(z * m * n * math.sin(gamma) / 30.0 / 1000.0, rel=1e-12)
    # the mean of |V_os| and |V_k| over one revolution is 2/pi of their amplitudes (trapezoidal rule here)
    psi, rolling, axial, _ = c.speeds(20001)
    omega = 2.0 * math.pi * n / 60.0
    assert np.trapezoid(np.abs(axial), psi) / (2 * math.pi) == pytest.approx(c.mean_sliding_speed, rel=1e-6)
    rb = BASE["face_width"] / (4.0 * math.tan(gamma))  # R_b = R0 / sin(alpha), R0 = b sin(alpha) / (4 tan(gamma))
    assert np.trapezoid(np.abs(rolling), psi) / (2 * math.pi) == pytest.approx(2 / math.pi * rb * 1e-3 * omega * math.sin(gamma))
    # eq. 7: u = (2 omega gamma / pi) [R_b - r (1 + sin alpha)]
    u = 2 / math.pi * omega * math.sin(gamma) * (rb - z * m / 2 * (1 + math.sin(math.radians(20)))) * 1e-3
    assert c.entraining_speed == pytest.approx(u, rel=1e-12)
    # the derived crown radius keeps the contact within b/4 of the middle of the face width
    assert c.contact_excursion == pytest.approx(BASE["face_width"] / 4.0, rel=1e-12)


def test_coupling_tooth_load_and_hertz_stress():
    c = GearCoupling(**BASE)
    r = analyse(c)
    # T = P / omega, F_n = T / (r z cos alpha), l = 2 h_a* m / cos alpha, p_H = sqrt(w' E* / (pi R_b))
    alpha = math.radians(20)
    torque = BASE["power_kw"] * 1e3 / (2 * math.pi * BASE["speed_rpm"] / 60)
    f_n = torque / (0.08 * 40 * math.cos(alpha))
    w = f_n / (2 * 0.8 * 4e-3 / math.cos(alpha))
    rb = 32e-3 / (4 * math.tan(BASE["misalignment"]))
    e_star = E_STEEL / (2 * (1 - NU_STEEL**2))
    assert r.hertz_stress * 1e6 == pytest.approx(math.sqrt(w * e_star / (math.pi * rb)), rel=1e-9)
    assert r.load_capacity == pytest.approx(f_n, rel=1e-3)  # the film carries the tooth load
    # the paper's verdict; the regime is starved (the inlet runs off the face, test_paper_coupling.py)
    assert r.verdict is Verdict.HYDRODYNAMIC and r.regime.value == "starved"
    assert 0.7 < r.min_film_thickness * 1e-3 / dowson_higginson(c.line_contact()) < 1.4


def test_coupling_film_falls_with_power():
    films = [analyse(GearCoupling(**{**BASE, "power_kw": p})).min_film_thickness for p in (1000.0, 4000.0, 16000.0)]
    assert films[0] > films[1] > films[2]


def test_coupling_messages():
    # a crown radius far above b/(4 tan gamma) walks the contact off the face width: edge contact
    r = analyse(GearCoupling(**BASE, barrel_radius=5000.0))
    assert not r.hydrodynamic and r.verdict is Verdict.EDGE_CONTACT and "edge contact" in r.message
    # R_b <= r (1 + sin alpha): eq. 7 gives no entrainment, the paper's "error in the input data"
    r = analyse(GearCoupling(**BASE, barrel_radius=30.0))
    assert not r.hydrodynamic and r.verdict is Verdict.NO_ENTRAINMENT and math.isnan(r.min_film_thickness)
    # a vanishing load gives Martin's rigid film 4.9 mu u R_b / w' of metres: not a thin film
    r = analyse(GearCoupling(**{**BASE, "power_kw": 1e-3}))
    assert not r.hydrodynamic and r.verdict is Verdict.THICK_FILM and r.min_film_thickness > 0.1 * BASE["module"]


# --- command line ------------------------------------------------------------------------------


def test_cli_json_keys(capsys):
    rc, out, err = run(capsys, "coupling", *ARGS, "--json")
    assert rc == 0, err
    data = json.loads(out)
    assert {"hydrodynamic", "min_film_thickness", "load_capacity", "max_pressure", "hertz_stress", "message"} <= set(data)
    # the film separates the flanks (lambda 3.99 >= 3): hydrodynamic; the inlet it needs runs off the face: starved
    assert data["hydrodynamic"] is True and data["regime"] == "starved" and isinstance(data["message"], str)
    # the paper: the film pressure stays well below the Hertz stress
    assert data["max_pressure"] < data["hertz_stress"]
    assert data["ehl_ratio"] == pytest.approx(data["min_film_thickness"] / data["ehl_film_thickness"])


def test_cli_table_has_units(capsys):
    rc, out, _ = run(capsys, "coupling", *ARGS)
    assert rc == 0
    rows = {r.split("│")[1].strip(): r.split("│")[3].strip() for r in out.splitlines() if r.startswith("│")}
    assert rows["min_film_thickness"] == "mm" and rows["max_pressure"] == "MPa" and rows["load_capacity"] == "N"


def test_cli_plot_writes_a_picture_that_reads_at_a_glance(capsys, tmp_path):
    from test_pictures import check_picture  # units on every axis, the case in the title (issue 16)

    path = tmp_path / "c.svg"
    rc, _, err = run(capsys, "coupling", *ARGS, "--plot", path)
    assert rc == 0, err
    drawn = check_picture(path, ["gear coupling z = ", " rpm", " kW"])
    # the paper's words beside rotorcad's curves (issue 23): Fig. 4's trend and p_max ~ 0.5 sigma_H
    assert "paper, Fig. 4: h_min falls slightly as z grows" in drawn["text"]
    assert "module and tooth load kept (the paper's trend)" in drawn["text"] and "p_max ≈ 0.5 σ_H" in drawn["text"]


@pytest.mark.parametrize(
    "change, option",
    [
        (("--teeth", "3"), "--teeth"),
        (("--module", "-1"), "--module"),
        (("--viscosity", "nan"), "--viscosity"),
        (("--speed", "inf"), "--speed"),
        (("--power", "0"), "--power"),
        (("--pressure-viscosity", "-1e-8"), "--pressure-viscosity"),
        (("--misalignment-deg", "0"), "--misalignment-deg"),
        (("--pressure-angle", "60"), "--pressure-angle"),
        (("--load-factor", "0.5"), "--load-factor"),
        (("--barrel-radius", "-5"), "--barrel-radius"),
        (("--addendum", "0"), "--addendum"),
    ],
)
def test_cli_bad_input(capsys, tmp_path, change, option):
    args = list(ARGS)
    if change[0] in args:
        args[args.index(change[0]) + 1] = change[1]
    else:
        args += list(change)
    rc, out, err = run(capsys, "coupling", *args, "--plot", tmp_path / "x.png")
    assert rc == 2 and out == ""
    assert option in err and "Traceback" not in err and len(err.strip().splitlines()) == 1
    assert not (tmp_path / "x.png").exists()


def test_cli_missing_option(capsys):
    rc, _, err = run(capsys, "coupling", "--teeth", "40", "--module", "4")
    assert rc == 2 and "--face-width is required" in err


def test_cli_inputs_that_make_no_sense_exit_2(capsys):
    # a new user's check: a vanishing misalignment made the derived crowning radius 1.6e11 mm and a
    # film of 0.8 m; a film thicker than a tenth of the module is the paper's "error in the input data"
    base = ["coupling", "--teeth", "40", "--module", "4", "--speed", "8000", "--power", "4000", "--viscosity", "0.02"]
    base += ["--pressure-viscosity", "2e-8"]
    assert main([*base, "--face-width", "32", "--misalignment-deg", "1e-9"]) == 2
    assert "--misalignment-deg must be at least" in capsys.readouterr().err
    assert main([*base, "--face-width", "500", "--misalignment-deg", "0.3"]) == 2
    assert "--power must be above about" in capsys.readouterr().err


def test_inlet_zone_against_the_face_closed_form(capsys):
    # the inlet zone is where the crowned flank's gap x^2 / (2 R_b) stays within ten central films:
    # x = sqrt(20 R_b h_c), computed here from the reported R_b and h_c; the room is b/2 - R_b tan(gamma)
    args = ["coupling", "--teeth", "40", "--module", "4", "--face-width", "32", "--speed", "8000", "--power", "4000"]
    args += ["--viscosity", "0.02", "--pressure-viscosity", "2e-8", "--misalignment-deg", "0.3", "--json"]
    assert main(args) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["inlet_length"] == pytest.approx(math.sqrt(20 * out["flank_crown_radius"] * out["central_film_thickness"]))
    room = 16.0 - out["flank_crown_radius"] * math.tan(math.radians(0.3))
    assert out["inlet_room"] == pytest.approx(room)
    assert out["inlet_off_face"] == (out["inlet_length"] > room)

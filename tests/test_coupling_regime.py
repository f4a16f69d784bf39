"""`coupling`'s verdict says whether the film separates the flanks; a short inlet is said beside it.

A new user's couplings inside Belkov, Maksimov & Shitikov's ranges (b = 6-10 m, gamma = 0.003-0.007 rad
= 0.17-0.4 deg) read `hydrodynamic: false` beside 3-7 um films (lambda 3-7) because the paper's crowning
puts the contact's excursion at b / 4, so the inlet room is always b / 4 and rotorcad's inlet rule of
thumb called them starved. `hydrodynamic` is now the film separating the surfaces (lambda >= 3).

References, computed here from the inputs (not from rotorcad): the tooth load F_n = P / (omega r z cos alpha)
over the contact line l = 2 h_a* m / cos alpha; the flank crown radius R_b = b / (4 tan gamma) (the paper's
R0 = b sin alpha / (4 tan gamma), R_b = R0 / sin alpha); eq. 7's entraining speed
u = (2 / pi) omega sin(gamma) [R_b - r (1 + sin alpha)]; Dowson & Higginson's line-contact film
h = 2.65 U^0.7 G^0.54 W^-0.13 R (Hamrock, *Fundamentals of Fluid Film Lubrication*, ch. 21) and
Martin's rigid-isoviscous film h = 4.9 mu u R / w' (Martin 1916), the film being about the larger of the
two (Johnson's regime map: these couplings sit near the rigid-isoviscous corner, the README's in the
piezoviscous-elastic one); lambda = h / sigma >= 3 the full-film limit (Hamrock ch. 1).
"""

from __future__ import annotations

import json
import math

import pytest
from test_coupling import ARGS, run

E_PRIME = 2e11 / (1 - 0.3**2)  # Pa: two steel flanks, 2 / E' = 2 (1 - nu^2) / E
SIGMA = 1e-6  # m: the default composite roughness


def _films(z, m, b, n, p_kw, gamma_deg, mu=0.02, alpha0=2e-8, r0=None):
    """Dowson-Higginson and Martin minimum films [m] of the coupling's contact, from the inputs."""
    al, g = math.radians(20), math.radians(gamma_deg)
    w, r = 2 * math.pi * n / 60, m * z / 2e3
    rb = (r0 * 1e-3 / math.sin(al)) if r0 else b * 1e-3 / (4 * math.tan(g))
    u = 2 / math.pi * w * math.sin(g) * (rb - r * (1 + math.sin(al)))
    load = p_kw * 1e3 / w / (r * z * math.cos(al)) / (2 * 0.8 * m * 1e-3 / math.cos(al))  # w', N/m
    big_u, big_g, big_w = mu * u / (E_PRIME * rb), alpha0 * E_PRIME, load / (E_PRIME * rb)
    return 2.65 * big_u**0.7 * big_g**0.54 * big_w**-0.13 * rb, 4.9 * mu * u * rb / load


def _args(z, m, b, n, p_kw, gamma_deg):
    args = ["--teeth", z, "--module", m, "--face-width", b, "--speed", n, "--power", p_kw, "--misalignment-deg", gamma_deg]
    return [str(a) for a in args] + ["--viscosity", "0.02", "--pressure-viscosity", "2e-8"]


# the README coupling and two of the new user's (coupling_regimes.txt): lambda 3.99, 3.89, 7.32, all "starved"
SEPARATED = {
    "readme": (40, 4, 32, 8000, 4000, 0.3),
    "user_b40_gamma0.4": (40, 4, 40, 3000, 500, 0.4),
    "user_z60_10000rpm": (60, 3, 24, 10000, 2000, 0.25),
}


@pytest.mark.parametrize("case", SEPARATED)
def test_film_above_three_roughnesses_reads_hydrodynamic(capsys, case):
    inputs = SEPARATED[case]
    rc, out, err = run(capsys, "coupling", *_args(*inputs), "--json")
    assert rc == 0, err
    r = json.loads(out)
    dh, martin = _films(*inputs)
    reference = max(dh, martin)
    assert reference / SIGMA >= 3  # the closed forms alone say the film separates the flanks
    assert 1.0 <= r["min_film_thickness"] * 1e-3 / reference <= 1.3
    assert r["film_parameter"] == pytest.approx(r["min_film_thickness"] / r["roughness"]) and r["film_parameter"] >= 3
    assert r["hydrodynamic"] is True
    # the inlet is judged separately: the paper's crowning leaves b / 4 beyond the contact's farthest position
    assert r["inlet_room"] == pytest.approx(inputs[2] / 4) and r["inlet_length"] > r["inlet_room"]
    assert r["regime"] == "starved" and r["inlet_off_face"] is True
    assert r["message"].startswith("hydrodynamic regime") and "starved inlet" in r["message"]
    assert f"{r['film_parameter']:.3g} times the composite roughness" in r["regime_reason"]
    assert "rule of thumb" in r["regime_reason"]


def test_thin_film_reads_not_hydrodynamic(capsys):
    # the README coupling with a crowning radius of 200 mm: Dowson-Higginson 1.06 um, lambda 1.06 < 3
    rc, out, err = run(capsys, "coupling", *ARGS, "--barrel-radius", "200", "--json")
    assert rc == 0, err
    r = json.loads(out)
    dh, martin = _films(40, 4, 32, 8000, 4000, 0.3, r0=200)
    reference = max(dh, martin)
    assert 1 <= reference / SIGMA < 3
    assert 1.0 <= r["min_film_thickness"] * 1e-3 / reference <= 1.3
    assert r["hydrodynamic"] is False and r["regime"] == "mixed" and 1 <= r["film_parameter"] < 3


def test_misalignment_beyond_rolling_names_its_range(capsys):
    # R_b = b / (4 tan gamma) must exceed r (1 + sin alpha): gamma < atan(b / (4 r (1 + sin alpha))) = 4.26 deg
    args = [a if a != "0.3" else "5" for a in ARGS]
    rc, out, err = run(capsys, "coupling", *args)
    top = math.degrees(math.atan(32 / (4 * 80 * (1 + math.sin(math.radians(20))))))
    least_b = 4 * math.tan(math.radians(5)) * 80 * (1 + math.sin(math.radians(20)))
    assert rc == 2 and out == "" and len(err.strip().splitlines()) == 1 and "Traceback" not in err
    assert f"--misalignment-deg must be below {top:.3g} deg" in err and f"--face-width above {least_b:.3g} mm" in err
    assert "0.17-0.4 deg" in err and "no misalignment" not in err and "(got 5)" in err


def test_light_load_names_the_models_limit(capsys):
    # 4 kW: Martin's rigid-isoviscous film (h ~ 1 / load) of 2.5 mm; it reaches m / 10 = 0.4 mm near 25.5 kW
    args = [a if a != "4000" else "4" for a in ARGS]
    rc, out, err = run(capsys, "coupling", *args)
    _, martin = _films(40, 4, 32, 8000, 4, 0.3)
    assert rc == 2 and out == "" and len(err.strip().splitlines()) == 1 and "Traceback" not in err
    assert "make no sense" not in err and "m / 10 = 0.4 mm" in err and "(got 4)" in err
    least = float(err.split("--power must be above about ")[1].split(" kW")[0])
    assert least == pytest.approx(4 * martin / 0.4e-3, rel=0.03)

"""``rotorcad pump`` uses the pair it is given: unequal gears, a centre distance, helical gears.

References (none produced by rotorcad.pump):

- The delivery of two external gears, derived from the flux of each gear's rotation through its
  flank between the tip circle and the contact point (Kollek & Osinski eq. 2 is its equal-gears
  case): q = b w1/2 [r_a1^2 - r_w1^2 + (z1/z2)(r_a2^2 - r_w2^2) - (1 + z1/z2) u^2], u the governing
  contact's distance from the pitch point along the line of action, from -g_f (the start of
  contact, on the mate's tip circle) for one base pitch. Geometry by ISO 21771 closed forms
  (eqs. 4.14, 4.16: inv a_w, a_w; 5.4: the contact ratio), written out here.
- A new user's figures: the 17/29 pair's contact ratio 1.5033 (ISO 21771), and the 17/17 pair at
  a = 51 mm (mate shift -0.3) 1.4086 by ``rotorcad gear``; the equal-gears answer all of these used
  to give: 30.6298 L/min, irregularity 0.2339, contact ratio 1.3925.
- Helical pumps: the delivery is the sum of thin transverse slices, each the spur-section delivery
  above with its contact shifted by zeta tan(beta_b) along the line of action (summed here over
  20000 slices, against the pump's closed-form integral); with overlap ratio 1 every phase is in the
  face once and the delivery is steady.
"""

from __future__ import annotations

import json

import numpy as np
import pytest

from rotorcad.cli.main import main
from rotorcad.gear import InvoluteGear
from rotorcad.pump import GearPump

A20 = np.radians(20.0)
L_PER_MIN = 60.0 / 1e6


def inv(a):
    return np.tan(a) - a


def iso_pair(z1, z2, m, x1, x2, beta=0.0, aw=None):
    """ISO 21771 transverse geometry of a pair (radii, base pitch, working angle, approach length)."""
    mt = m / np.cos(beta)
    at = np.arctan(np.tan(A20) / np.cos(beta))
    r1, r2 = z1 * mt / 2, z2 * mt / 2
    if aw is None:  # zero backlash: inv a_wt = inv a_t + 2 (x1 + x2) tan a_n / (z1 + z2)
        target = inv(at) + 2 * (x1 + x2) * np.tan(A20) / (z1 + z2)
        awt = at
        for _ in range(60):  # Newton on inv(a) - target, d inv / da = tan^2 a
            awt -= (inv(awt) - target) / np.tan(awt) ** 2
        aw = (r1 + r2) * np.cos(at) / np.cos(awt)
    awt = np.arccos((r1 + r2) * np.cos(at) / aw)
    ra1, ra2 = r1 + (1 + x1) * m, r2 + (1 + x2) * m
    rb1, rb2 = r1 * np.cos(at), r2 * np.cos(at)
    rw1, rw2 = rb1 / np.cos(awt), rb2 / np.cos(awt)
    pb = np.pi * mt * np.cos(at)
    g_f = np.sqrt(ra2**2 - rb2**2) - rw2 * np.sin(awt)  # approach: from the mate's tip circle to C
    g_a = np.sqrt(ra1**2 - rb1**2) - rw1 * np.sin(awt)
    return dict(ra1=ra1, ra2=ra2, rb1=rb1, rw1=rw1, rw2=rw2, pb=pb, g_f=g_f, eps=(g_f + g_a) / pb, k=z1 / z2, aw=aw)


def section_delivery(geo, s, w):
    """Delivery per unit face width with the governing contact at s from the start of contact, mm^2/s."""
    u = np.mod(s, geo["pb"]) - geo["g_f"]
    k = geo["k"]
    return w / 2 * (geo["ra1"] ** 2 - geo["rw1"] ** 2 + k * (geo["ra2"] ** 2 - geo["rw2"] ** 2) - (1 + k) * u**2)


def mate_shift_for(aw, z1, z2, m, x1):
    """x2 from the centre distance (ISO 21771 eqs. 4.14, 4.16 solved for x1 + x2)."""
    a = (z1 + z2) * m / 2
    awt = np.arccos(a * np.cos(A20) / aw)
    return (inv(awt) - inv(A20)) * (z1 + z2) / (2 * np.tan(A20)) - x1


def pump_json(capsys, *args):
    assert main(["pump", *map(str, args), "--face-width", "20", "--speed", "1500", "--json"]) == 0
    return json.loads(capsys.readouterr().out)


@pytest.mark.parametrize(
    "z2,x2,aw",
    [
        (29, -0.1, None),  # samples/gear_pair.toml
        (17, 0.3, None),  # two equal gears: Kollek & Osinski eq. 2 itself
        (17, None, 51.0),  # the mate's shift from the centre distance: -0.3 (an undercut mate)
        (17, None, 53.5),  # a positive one
    ],
)
def test_delivery_of_the_pair_is_the_closed_form(z2, x2, aw):
    z1, m, x1, b, n = 17, 3.0, 0.3, 20.0, 1500.0
    if x2 is None:
        x2 = mate_shift_for(aw, z1, z2, m, x1)
    geo = iso_pair(z1, z2, m, x1, x2, aw=aw)
    p = GearPump(InvoluteGear(z1, m, A20, 0.0, x1), b, n, InvoluteGear(z2, m, A20, 0.0, x2), aw)
    if aw == 51.0:  # the mate's undercut ends the contact before the gear's tip: 1.4086 by `rotorcad gear` (new user)
        assert x2 == pytest.approx(-0.3, abs=2e-3) and p.contact_ratio == pytest.approx(1.4086, abs=1e-4)
    else:
        assert p.contact_ratio == pytest.approx(geo["eps"], rel=1e-9)
    w = 2 * np.pi * n / 60
    s = np.linspace(0.0, geo["pb"], 301, endpoint=False)
    _, q = p.delivery(phi=s / geo["rb1"])
    np.testing.assert_allclose(q, b * section_delivery(geo, s, w), rtol=1e-9)
    # the mean in closed form: the mean of u^2 over [-g_f, p_b - g_f] is ((p_b - g_f)^3 + g_f^3) / (3 p_b)
    pb, gf, k = geo["pb"], geo["g_f"], geo["k"]
    u2 = ((pb - gf) ** 3 + gf**3) / (3 * pb)
    mean = b * w / 2 * (geo["ra1"] ** 2 - geo["rw1"] ** 2 + k * (geo["ra2"] ** 2 - geo["rw2"] ** 2) - (1 + k) * u2)
    assert p.mean_flow == pytest.approx(mean, rel=1e-6)


def test_the_cli_uses_the_mate(capsys):
    equal = pump_json(capsys, "--teeth", 17, "--module", 3, "--shift", 0.3)
    # before: every mate below gave these, the values of two equal x = 0.3 gears
    assert equal["mean_flow"] == pytest.approx(30.6298, abs=1e-4)
    assert equal["contact_ratio"] == pytest.approx(1.3925, abs=1e-4)
    assert equal["mate_teeth"] == 17 and "--mate-teeth" in equal["defaults"]
    pair = pump_json(capsys, "--teeth", 17, "--module", 3, "--shift", 0.3, "--mate-teeth", 29, "--mate-shift", -0.1)
    geo = iso_pair(17, 29, 3.0, 0.3, -0.1)
    assert pair["contact_ratio"] == pytest.approx(1.5033, abs=1e-4) == geo["eps"]
    assert pair["mate_teeth"] == 29 and pair["center_distance"] == pytest.approx(geo["aw"], rel=1e-9)
    assert "--mate-teeth" not in pair["defaults"]
    w = 2 * np.pi * 1500 / 60
    s = (np.arange(20000) + 0.5) / 20000 * geo["pb"]
    assert pair["mean_flow"] == pytest.approx(20 * section_delivery(geo, s, w).mean() * L_PER_MIN, rel=1e-6)
    assert abs(pair["mean_flow"] - equal["mean_flow"]) > 0.5  # the pair's own flow (28.2-29.6 by the new user's hand)
    design = ["samples/gear_pair.toml"]  # [mate] teeth = 29, shift = -0.1
    assert main(["pump", *design, "--face-width", "20", "--speed", "1500", "--json"]) == 0
    sample = json.loads(capsys.readouterr().out)
    assert sample["mean_flow"] == pytest.approx(pair["mean_flow"], rel=1e-12)
    a51 = pump_json(capsys, "--teeth", 17, "--module", 3, "--shift", 0.3, "--mate-teeth", 17, "--center-distance", 51)
    assert a51["contact_ratio"] == pytest.approx(1.4086, abs=2e-4)  # `rotorcad gear`, same options (new user)
    assert a51["center_distance"] == 51.0


def helical_geometry(z, m, x, beta_deg, b):
    beta = np.radians(beta_deg)
    geo = iso_pair(z, z, m, x, x, beta=beta)
    at = np.arctan(np.tan(A20) / np.cos(beta))
    window = b * np.tan(beta) * np.cos(at)  # b tan(beta_b): the contact's shift along the face
    return geo, window


@pytest.mark.parametrize("overlap", [1.0, 0.5, 2.0])
def test_helical_delivery_is_the_sum_of_its_transverse_slices(overlap):
    z, m, x, beta_deg, n = 11, 4.0, 0.3, 15.0, 1500.0
    b = overlap * np.pi * m / np.sin(np.radians(beta_deg))  # eps_beta = b sin(beta) / (pi m_n)
    g = InvoluteGear(z, m, A20, np.radians(beta_deg), x)
    p = GearPump(g, b, n)
    assert p.overlap_ratio == pytest.approx(overlap, rel=1e-12)
    geo, window = helical_geometry(z, m, x, beta_deg, b)
    w = 2 * np.pi * n / 60
    s = np.linspace(0.0, geo["pb"], 97, endpoint=False)
    slices = (np.arange(20000) + 0.5) / 20000  # midpoints of 20000 slices of the face
    summed = b * section_delivery(geo, s[:, None] + slices[None, :] * window, w).mean(axis=1)
    _, q = p.delivery(phi=s / geo["rb1"])
    np.testing.assert_allclose(q, summed, rtol=2e-5)  # the slices miss the jump by 1/20000
    spur = GearPump(InvoluteGear(z, m, A20, 0.0, x), b, n)
    if overlap == 0.5:  # half the face's phases: the pulsation drops, not to zero
        assert 0.05 < p.irregularity < 0.6 * spur.irregularity
    else:  # every phase equally often: steady (the new user's integration: 0.0005; before: 0.278)
        assert p.irregularity < 1e-9 and np.all(p.harmonics(8) < 1e-9)
    assert p.mean_flow == pytest.approx(b * section_delivery(geo, s, w).mean(), rel=1e-3)


def test_helical_cli_face_width_changes_the_pulsation(capsys):
    args = ["--teeth", 11, "--module", 4, "--shift", 0.3, "--helix-angle", 15]
    r = json.loads(_run(capsys, *args, "--face-width", f"{np.pi * 4 / np.sin(np.radians(15)):.12g}"))
    assert r["overlap_contact_ratio"] == pytest.approx(1.0, rel=1e-9)
    assert r["total_contact_ratio"] == pytest.approx(r["contact_ratio"] + 1.0, rel=1e-9)
    assert r["flow_irregularity"] < 1e-6  # before: 0.278


def _run(capsys, *args):
    assert main(["pump", *map(str, args), "--speed", "1500", "--json"]) == 0
    return capsys.readouterr().out


def test_helical_pump_below_transverse_contact_ratio_1_refused_for_the_true_reason(capsys):
    base = ["pump", "--teeth", "11", "--module", "4", "--shift", "0.3", "--helix-angle", "45", "--speed", "1500"]
    # eps_alpha 0.8814, eps_beta = 20 sin 45 / (4 pi) = 1.125: a pair is always in mesh along the face
    assert main([*base, "--face-width", "20"]) == 2
    err = capsys.readouterr().err
    assert "no pair of teeth is in mesh" not in err and "not modelled" in err and "0.8814" in err
    # eps_beta = 2 sin 45 / (4 pi) = 0.113: eps_gamma = 0.99 < 1, the discharge opens to the suction
    assert main([*base, "--face-width", "2"]) == 2
    err = capsys.readouterr().err
    assert "total contact ratio" in err and "no pair of teeth is in mesh" in err and len(err.strip().splitlines()) == 1

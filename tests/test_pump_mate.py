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
- An independent integration: the area of the discharge chamber (housing, port, both gears' generated
  outlines) by shapely as the gears turn; its rate of fall is the delivery. It also tells which
  contact governs: the newest one, from the mate's tip circle (the other start fits 77 % of the
  phases, the model 47 of 48; the one left is next to the jump where a new contact closes the discharge).
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


# --- an independent integration: the discharge chamber's area, by shapely, as the gears turn ------------------------


def discharge_chamber_area(g1, g2, aw):
    """Return A(phi): the area of the discharge chamber when the gear has turned by phi (rad, anticlockwise).

    The gears' generated outlines (1e-4 mm chords) at centres (0, 0) and (aw, 0) with backlash, the
    mate turned clockwise by phi z1/z2 with its flank on the gear's driving flank; the housing is
    the two tip circles (1e-4 mm inside, so that the tips seal each tooth space) and a port below the
    mesh on the side where the teeth come into mesh (y < 0), reaching below both gears. The chamber
    is the part of the housing outside both gears (each grown by 5e-4 mm, so that a contact seals)
    that is connected to the port. Its area falls by the delivery per unit face width and angle.
    """
    from shapely import affinity, union_all
    from shapely.geometry import Point, Polygon, box

    z1, z2, m = g1.teeth, g2.teeth, g1.module
    gear, mate = Polygon(g1.outline(1e-4).points), Polygon(g2.outline(1e-4).points)  # a tooth on +x
    ra1, ra2 = g1.tip_radius, g2.tip_radius
    xi = (aw**2 + ra1**2 - ra2**2) / (2 * aw)  # where the tip circles cross
    deep = max(ra1, ra2) + 2 * m
    window = box(xi - 4 * m - 0.3 * ra1, -deep, xi + 4 * m + 0.3 * ra2, 0.6 * ra1)
    housing = union_all([Point(0, 0).buffer(ra1 - 1e-4, 2048), Point(aw, 0).buffer(ra2 - 1e-4, 2048)])
    housing = union_all([housing, box(xi - m, -deep, xi + m, 0.0)]).intersection(window)
    probe = Point(xi, -deep + m)

    def placed(phi, turn):
        a = affinity.rotate(gear, phi, origin=(0, 0), use_radians=True)
        b = affinity.rotate(mate, np.pi - np.pi / z2 + turn - phi * z1 / z2, origin=(0, 0), use_radians=True)
        return a, affinity.translate(b, aw, 0.0)  # a space of the mate faces the gear's tooth 0

    lo, hi = 0.0, 0.2  # turn the mate back until its flank meets the gear's driving flank
    for _ in range(50):
        mid = (lo + hi) / 2
        a, b = placed(0.0, mid)
        lo, hi = (lo, mid) if a.intersection(b).area > 0 else (mid, hi)

    def area(phi):
        a, b = placed(phi, hi)
        fluid = housing.difference(a.buffer(5e-4, 2)).difference(b.buffer(5e-4, 2))
        return next(part.area for part in getattr(fluid, "geoms", [fluid]) if part.contains(probe))

    return area


@pytest.mark.parametrize("z2,x2", [(29, -0.1), (17, 0.3)])
def test_delivery_is_the_shrinking_of_the_discharge_chamber(z2, x2):
    z1, m, x1 = 17, 3.0, 0.3
    g1, g2 = InvoluteGear(z1, m, A20, 0.0, x1), InvoluteGear(z2, m, A20, 0.0, x2)
    aw = iso_pair(z1, z2, m, x1, x2)["aw"] + 0.2  # backlash: only the driving flanks seal
    geo = iso_pair(z1, z2, m, x1, x2, aw=aw)
    p = GearPump(g1, 1.0, 60 / (2 * np.pi), g2, aw)  # b = 1 mm, w1 = 1 rad/s: q in mm^2 per rad
    area = discharge_chamber_area(g1, g2, aw)
    h = 2e-4
    phis = np.linspace(0.0, 2 * np.pi / z1, 48, endpoint=False)
    q = np.array([(area(f - h / 2) - area(f + h / 2)) / h for f in phis])
    # the phase of the start of contact, fitted (median error over a grid of 4000 phases)
    rb1, pb = geo["rb1"], geo["pb"]
    s0 = np.linspace(0.0, pb, 4000, endpoint=False)[:, None]

    def fit(geo_):
        err = np.abs(section_delivery(geo_, rb1 * phis[None, :] + s0, 1.0) - q[None, :])
        best = np.argmin(np.median(err, axis=1))
        return err[best] / q.mean(), s0[best, 0]

    err, start = fit(geo)
    _, closed = p.delivery(phi=np.mod(phis + start / rb1, 2 * np.pi / z1))
    # all but the samples next to the jump where a new contact closes the discharge: 1.3e-4 measured
    assert np.mean(np.abs(closed - q) / q.mean() < 3e-4) > 0.9
    assert np.mean(err < 3e-4) > 0.95  # 47 of 48 measured
    assert q.mean() == pytest.approx(p.mean_flow, rel=5e-3)
    if z2 != z1:  # the other start (the contact from the gear's own tip) does not fit this pair
        mirrored = dict(geo, g_f=geo["eps"] * pb - geo["g_f"])  # u from g_a down: u^2 as from -g_a up
        assert np.mean(fit(mirrored)[0] < 3e-4) < 0.85  # 0.77 measured: 1 - (g_a - g_f) / p_b of the phases

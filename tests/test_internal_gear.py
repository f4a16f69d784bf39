"""Internal gears cut by a shaper cutter: closed forms of ISO 21771 / DIN 3993 and a brute-force shaping simulation.

References, none of them rotorcad's output:
- the involute of the base circle and the space width on the reference circle, ISO 21771 sec. 2.3
  and eq. 2.21 (the tooth-space half-angle eta(R) = (pi/2 + 2 x2 tan alpha)/z2 + inv(alpha_t) - inv(alpha_R),
  internal gear with its shift positive where the space widens);
- the working pressure angle, centre distance, tip and root diameters and the contact ratio of an
  internal pair (ISO 21771 eqs. 4.14, 4.16, 5.4 with z2 < 0; DIN 3993), evaluated here with scipy's
  brentq for the inverse involute;
- a brute-force shaping simulation with shapely: the cutter's teeth, built here from the involute
  and rounded by an opening (buffer -rho, +rho: the arc tangent to the tip circle and the flank),
  placed at 1000 positions of the generating motion and subtracted from a ring blank.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
import shapely
from scipy.optimize import brentq

from rotorcad.errors import DesignError, GeometryError
from rotorcad.gears.internal_gear import InternalGear
from rotorcad.gears.internal_pair import InternalPair
from rotorcad.gears.involute_gear import InvoluteGear
from rotorcad.gears.shaper import ShaperCutter

DEG = math.pi / 180.0


def inv(a):
    return np.tan(a) - a


def inv_inverse(v: float) -> float:
    return brentq(lambda a: math.tan(a) - a - v, 1e-9, 1.5)


def internal_alpha_w(z1, z2, x1, x2, alpha_t, alpha_n):
    """ISO 21771 eq. 4.14 with z2 -> -z2, x2 -> -x2 (internal gear, DIN 3993)."""
    return inv_inverse(float(inv(alpha_t)) + 2.0 * math.tan(alpha_n) * (x2 - x1) / (z2 - z1))


@pytest.fixture(scope="module")
def spur():
    cutter = ShaperCutter(teeth=20, module=2.0, shift=0.1, tip_radius_factor=0.3)
    return InternalGear(teeth=60, module=2.0, cutter=cutter, shift=0.3, addendum=0.8)


@pytest.fixture(scope="module")
def helical():
    cutter = ShaperCutter(teeth=17, module=1.5, helix_angle=15.0 * DEG, shift=0.0)
    return InternalGear(teeth=53, module=1.5, cutter=cutter, shift=0.4, addendum=0.8)


@pytest.mark.parametrize("name", ["spur", "helical"])
def test_generated_flank_is_the_involute_of_iso_21771(name, request):
    # ISO 21771 eq. 2.21: the space's flank at radius R lies at polar angle eta_p + inv(alpha_t) - inv(alpha_R),
    # eta_p = (pi/2 + 2 x2 tan(alpha_n)) / z2; its tangent makes the angle alpha_R with the radius
    g = request.getfixturevalue(name)
    m, z, x = g.module, g.teeth, g.shift
    beta = g.helix_angle
    alpha_t = math.atan(math.tan(20.0 * DEG) / math.cos(beta))
    rb = z * m / math.cos(beta) / 2.0 * math.cos(alpha_t)
    seg = next(s for s in g.space_profile().segments if s.name == "involute")
    p, t = seg.points, seg.tangents
    r = np.hypot(*p.T)
    eta = (math.pi / 2.0 + 2.0 * x * math.tan(20.0 * DEG)) / z + inv(alpha_t) - inv(np.arccos(rb / r))
    assert np.max(np.abs(np.arctan2(p[:, 1], p[:, 0]) - eta) * r) < 1e-7  # mm, along the circle
    sin_alpha = np.abs(p[:, 0] * t[:, 1] - p[:, 1] * t[:, 0]) / r  # |cross(radial, tangent)|
    assert np.max(np.abs(sin_alpha - np.sqrt(1.0 - (rb / r) ** 2))) < 1e-9
    # the involute runs from the tip circle r_a2 = r2 - (h_aP* - x2) m (DIN 3993) to the form circle
    r2 = z * m / math.cos(beta) / 2.0
    assert r.min() == pytest.approx(r2 - (g.addendum - x) * m, abs=1e-9)


@pytest.mark.parametrize("name", ["spur", "helical"])
def test_diameters_and_cutting_centre_distance(name, request):
    g = request.getfixturevalue(name)
    c = g.cutter
    m, beta = g.module, g.helix_angle
    mt = m / math.cos(beta)
    alpha_t = math.atan(math.tan(20.0 * DEG) / math.cos(beta))
    aw0 = internal_alpha_w(c.teeth, g.teeth, c.shift, g.shift, alpha_t, 20.0 * DEG)
    a0 = (g.teeth - c.teeth) * mt / 2.0 * math.cos(alpha_t) / math.cos(aw0)  # ISO 21771 eq. 4.16, DIN 3993
    assert g.cutting_center_distance == pytest.approx(a0, rel=1e-12)
    assert g.base_radius == pytest.approx(g.teeth * mt / 2.0 * math.cos(alpha_t), rel=1e-14)
    # the root circle is where the cutter's tip circle d_a0 = d0 + 2 (h_a0* + x0) m reaches: d_f2 = 2 a0 + d_a0
    d_a0 = c.teeth * mt + 2.0 * (c.addendum + c.shift) * m
    assert 2.0 * g.root_radius == pytest.approx(2.0 * a0 + d_a0, rel=1e-12)
    pts = g.outline().points
    r = np.hypot(*pts.T)
    assert r.max() == pytest.approx(g.root_radius, abs=1e-9)
    assert r.min() == pytest.approx(g.teeth * mt / 2.0 - (g.addendum - g.shift) * m, abs=1e-9)
    # the space width on the reference circle: e2 = m_t (pi/2 + 2 x2 tan(alpha_t)) (ISO 21771, internal)
    e2 = 2.0 * math.pi * g.pitch_radius / g.teeth - g.tooth_thickness(g.pitch_radius)
    assert e2 == pytest.approx(mt * math.pi / 2.0 + 2.0 * g.shift * m * math.tan(alpha_t), abs=1e-9)


def test_outline_is_a_simple_counter_clockwise_bore(spur):
    pts = spur.outline().points
    ring = shapely.LinearRing(pts)
    assert ring.is_simple and ring.is_ccw
    # area of the bore: between the tip and root circles
    area = shapely.Polygon(pts).area
    assert math.pi * spur.tip_radius**2 < area < math.pi * spur.root_radius**2


@pytest.mark.parametrize(("z1", "x1"), [(20, 0.3), (41, 0.5)])
def test_pair_working_angle_centre_distance_contact_ratio(spur, z1, x1):
    g = spur
    pinion = InvoluteGear(teeth=z1, module=2.0, shift=x1, addendum=0.8)
    pair = InternalPair(pinion, g)
    alpha = 20.0 * DEG
    aw = internal_alpha_w(z1, g.teeth, x1, g.shift, alpha, alpha)
    a = (g.teeth - z1) * 2.0 / 2.0 * math.cos(alpha) / math.cos(aw)
    assert pair.working_pressure_angle == pytest.approx(aw, abs=1e-12)
    assert pair.working_center_distance == pytest.approx(a, rel=1e-12)
    # ISO 21771 eq. 5.4 for an internal pair (DIN 3993): the form circles do not limit here
    rb1, rb2 = z1 * math.cos(alpha), g.teeth * math.cos(alpha)
    ra1 = z1 + (0.8 + x1) * 2.0
    ra2 = g.teeth - (0.8 - g.shift) * 2.0
    eps = (math.sqrt(ra1**2 - rb1**2) - math.sqrt(ra2**2 - rb2**2) + a * math.sin(aw)) / (math.pi * 2.0 * math.cos(alpha))
    assert pair.contact_ratio == pytest.approx(eps, rel=1e-12)
    # zero backlash at the centre distance of the shifts
    assert abs(pair.backlash) < 1e-7


def test_involute_interference_is_refused_at_the_closed_form_addendum(spur):
    # DIN 3993 involute interference: the internal gear's tip contact sqrt(r_a2^2 - r_b2^2) must lie at
    # least a sin(alpha_w) + sqrt(r_Ff1^2 - r_b1^2) from T2; the pinion's form circle from its rack tool's
    # straight flank end (ISO 53 tool, rho = 0.38: flank up to h_fP* - rho (1 - sin alpha) above the datum)
    z1, x1 = 20, 0.3
    alpha = 20.0 * DEG
    rho = 0.38
    h_lin = 1.25 - rho * (1.0 - math.sin(alpha))  # tool flank height above the pitch line, modules
    l_form = z1 * math.sin(alpha) - (h_lin - x1) * 2.0 / math.sin(alpha)  # roll length of the form point, mm
    a = (60 - z1) * math.cos(alpha) / math.cos(internal_alpha_w(z1, 60, x1, 0.3, alpha, alpha))
    aw = internal_alpha_w(z1, 60, x1, 0.3, alpha, alpha)
    ra2_least = math.hypot(60 * math.cos(alpha), a * math.sin(aw) + l_form)
    h_max = (60.0 + 0.3 * 2.0 - ra2_least) / 2.0
    cutter = spur.cutter
    ok = InternalGear(60, 2.0, cutter, shift=0.3, addendum=h_max - 0.002)
    InternalPair(InvoluteGear(z1, 2.0, shift=x1, addendum=0.8), ok)
    bad = InternalGear(60, 2.0, cutter, shift=0.3, addendum=h_max + 0.002)
    with pytest.raises(GeometryError, match=r"addendum must be at most (\d\.\d+)") as info:
        InternalPair(InvoluteGear(z1, 2.0, shift=x1, addendum=0.8), bad)
    assert float(info.value.allowed.split()[2]) == pytest.approx(h_max, abs=1e-4)


def trochoid_by_khk(z1, z2, ra1, ra2, a, aw, rb1):
    """KHK Technical Reference (internal gears, trochoid interference), written out independently."""
    t1 = math.acos((ra2**2 - ra1**2 - a**2) / (2 * a * ra1))
    t2 = math.acos((a**2 + ra2**2 - ra1**2) / (2 * a * ra2))
    a_a1, a_a2 = math.acos(rb1 / ra1), math.acos(rb1 * z2 / z1 / ra2)
    return (t1 + inv(a_a1) - inv(aw)) * z1 / z2 + inv(aw) - inv(a_a2) - t2


def test_smallest_tooth_difference_against_the_trochoid_closed_form(spur):
    # the first ring tooth count that passes KHK's trochoid condition (and the involute one) for a
    # 50-tooth pinion: the pair is refused one tooth below it and accepted at it
    z1, x1, alpha = 50, 0.3, 20.0 * DEG
    rb1 = z1 * math.cos(alpha)
    ra1 = z1 + (0.8 + x1) * 2.0

    def margin(z2):
        aw = internal_alpha_w(z1, z2, x1, 0.3, alpha, alpha)
        if (z2 - z1) * math.cos(alpha) / math.cos(aw) + z2 - (0.8 - 0.3) * 2.0 < ra1:  # pinion tips in the ring's teeth
            return -1.0
        a = (z2 - z1) * math.cos(alpha) / math.cos(aw)
        return trochoid_by_khk(z1, z2, ra1, z2 - (0.8 - 0.3) * 2.0, a, aw, rb1)

    least = next(z2 for z2 in range(z1 + 1, 200) if margin(z2) >= 0.0)
    cutter = spur.cutter
    pinion = InvoluteGear(z1, 2.0, shift=x1, addendum=0.8)
    pair = InternalPair(pinion, InternalGear(least, 2.0, cutter, shift=0.3, addendum=0.8))
    assert pair.min_teeth_difference == least - z1
    with pytest.raises(GeometryError, match=rf"teeth must be at least {least} .*trochoid interference"):
        InternalPair(pinion, InternalGear(least - 1, 2.0, cutter, shift=0.3, addendum=0.8))


def test_cutter_too_large_for_the_ring_is_refused():
    # the cutting's involute interference (DIN 3993 with the cutter's base circle): a ring of z2 teeth
    # needs sqrt(r_a2^2 - r_b2^2) >= a0 sin(alpha_w0); the first z2 that passes, from the closed form
    alpha = 20.0 * DEG
    cutter = ShaperCutter(teeth=20, module=2.0)

    def ok(z2):
        aw = internal_alpha_w(20, z2, 0.0, 0.0, alpha, alpha)
        a0 = (z2 - 20) * math.cos(alpha) / math.cos(aw)
        ra2, rb2 = z2 - 2.0, z2 * math.cos(alpha)
        return ra2 > rb2 and math.sqrt(ra2**2 - rb2**2) >= a0 * math.sin(aw)

    least = next(z2 for z2 in range(21, 400) if ok(z2))
    InternalGear(least, 2.0, cutter)
    with pytest.raises(GeometryError, match=rf"teeth must be at least {least} for a 20-tooth cutter"):
        InternalGear(least - 1, 2.0, cutter)


@pytest.mark.parametrize(
    ("kwargs", "param"),
    [
        ({"teeth": 20}, "teeth"),
        ({"shift": 3.0}, "shift"),
        ({"addendum": 0.0}, "addendum"),
        ({"outer_diameter": 100.0}, "outer_diameter"),
    ],
)
def test_bad_values_name_their_parameter(kwargs, param):
    values = {"teeth": 60, "module": 2.0, "cutter": ShaperCutter(teeth=20, module=2.0), "shift": 0.3, "addendum": 0.8}
    values.update(kwargs)
    with pytest.raises(DesignError) as info:
        InternalGear(**values)
    assert info.value.param == param


def test_cutter_rounding_limit():
    c = ShaperCutter(teeth=20, module=2.0)
    with pytest.raises(DesignError, match="cutter_tip_radius must be from 0 to"):
        ShaperCutter(teeth=20, module=2.0, tip_radius_factor=c.tip_radius_limit + 0.01)


# ----- brute-force shaping simulation -----------------------------------------------------------


def cutter_teeth_polygon(z0, m, x0, h_a0, rho_star, alpha, n=400, beta=0.0):
    """Three teeth (-1, 0, 1) of a shaper cutter about the origin, tooth 0 on +x, from closed forms.

    Transverse section of a cutter of normal module m, normal pressure angle alpha and helix angle
    beta (ISO 21771: m_t = m / cos(beta), tan(alpha_t) = tan(alpha) / cos(beta)). Involute flanks (eq.
    2.21, sampled in equal roll angles) from the base or root circle to the tip circle, tip arcs,
    radial flanks below the base circle, then the tip rounded by an opening of radius rho (buffer
    -rho, +rho: the arc tangent to the tip circle and to the flank).
    """
    alpha_t = math.atan(math.tan(alpha) / math.cos(beta))
    r0 = z0 * m / math.cos(beta) / 2.0
    rb = r0 * math.cos(alpha_t)
    ra = r0 + (h_a0 + x0) * m
    rf = r0 + (x0 - 1.25) * m
    psi_b = (math.pi / 2.0 + 2.0 * x0 * math.tan(alpha)) / z0 + inv(alpha_t)
    u = np.linspace(math.sqrt(max(rf * rf - rb * rb, 0.0)) / rb, math.sqrt(ra * ra - rb * rb) / rb, n)
    r = rb * np.sqrt(1.0 + u * u)
    psi = psi_b - (u - np.arctan(u))
    pts = []
    for k in (-1, 0, 1):
        c = 2.0 * math.pi * k / z0
        if rf < rb:  # radial flank below the base circle
            pts.append([[rf * math.cos(c - psi_b), rf * math.sin(c - psi_b)]])
        pts.append(np.column_stack([r * np.cos(c - psi), r * np.sin(c - psi)]))
        tip_a = np.linspace(c - psi[-1], c + psi[-1], n // 2)[1:-1]
        pts.append(np.column_stack([ra * np.cos(tip_a), ra * np.sin(tip_a)]))
        pts.append(np.column_stack([r * np.cos(c + psi), r * np.sin(c + psi)])[::-1])
        if rf < rb:
            pts.append([[rf * math.cos(c + psi_b), rf * math.sin(c + psi_b)]])
    poly = shapely.Polygon(np.vstack([*pts, [[0.0, 0.0]]]))
    assert poly.is_valid
    rho = rho_star * m
    if rho > 0:
        poly = poly.buffer(-rho, quad_segs=128).buffer(rho, quad_segs=128)
    return poly


def shaped_ring(g: InternalGear, positions=1000, turn=None, n=300):
    """The ring blank (bore r_a2) minus the cutter's three teeth at ``positions`` steps of the generating motion.

    The ring turns by t about the origin and the cutter by (z2/z0) t about (a0, 0) (an internal pair:
    the same sense, pitch circles rolling); seen from the ring, a cutter point p is at R(-t) (a0 + R(z2 t / z0) p).
    """
    c = g.cutter
    alpha = c.pressure_angle
    teeth = cutter_teeth_polygon(c.teeth, c.module, c.shift, c.addendum, c.tip_radius_factor, alpha, n, c.helix_angle)
    xy = shapely.get_coordinates(teeth)
    z0, z2, a0 = c.teeth, g.teeth, g.cutting_center_distance
    span = turn if turn is not None else 2.5 * 2.0 * math.pi / z2
    ts = np.linspace(-span, span, positions)
    own = z2 / z0 * ts
    zc = xy[:, 0] + 1j * xy[:, 1]
    moved = (np.exp(1j * own)[:, None] * zc[None, :] + a0) * np.exp(-1j * ts)[:, None]
    polys = shapely.polygons(np.stack([moved.real, moved.imag], axis=-1))
    swept = shapely.union_all(polys)
    wedge_a = np.linspace(-1.5, 1.5, 400) * 2.0 * math.pi / z2
    outer = g.root_radius + g.module
    blank = shapely.Polygon(
        np.vstack([np.column_stack([outer * np.cos(wedge_a), outer * np.sin(wedge_a)]), [[0.0, 0.0]]])
    ).difference(shapely.Point(0, 0).buffer(g.tip_radius, quad_segs=4096))
    return blank.difference(swept)


@pytest.mark.parametrize("name", ["spur", "helical"])
def test_shaping_simulation_matches_the_envelope(name, request):
    # brute force: the ring blank minus the cutter at 1000 positions; the envelope's space 0 (root arc,
    # fillet, involute; both flanks) lies on the simulated boundary within 1 um, and back (a helical
    # gear in its transverse section, shaped by a helical cutter)
    g = request.getfixturevalue(name)
    sim = shaped_ring(g)
    boundary = sim.boundary
    prof = g.outline()
    pts = prof.points
    ang = np.arctan2(pts[:, 1], pts[:, 0])
    r = np.hypot(*pts.T)
    flank = (np.abs(ang) < math.pi / g.teeth) & (r > g.tip_radius + 1e-3)  # space 0, off the bore circle
    env = pts[flank]
    assert len(env) > 100
    d_env = shapely.distance(shapely.points(env), boundary)
    assert d_env.max() < 1e-3, f"envelope to simulation {d_env.max() * 1e3:.3f} um"
    # and the simulated boundary's vertices in space 0 against the envelope polyline
    ring = shapely.LinearRing(pts)
    sv = shapely.get_coordinates(boundary)
    sa, sr = np.arctan2(sv[:, 1], sv[:, 0]), np.hypot(*sv.T)
    inside = (np.abs(sa) < 0.8 * math.pi / g.teeth) & (sr > g.tip_radius + 1e-3) & (sr < g.root_radius + 1e-4)
    d_sim = shapely.distance(shapely.points(sv[inside]), ring)
    assert inside.sum() > 100
    assert d_sim.max() < 1e-3, f"simulation to envelope {d_sim.max() * 1e3:.3f} um"


def test_shaping_simulation_trims_tips_where_the_cutter_trochoid_check_refuses():
    # the cutter's trochoid interference (secondary cutting) predicted by the closed form shows in the
    # brute-force simulation as tooth tips cut back from the bore circle; a passing ring keeps them
    cutter = ShaperCutter(teeth=40, module=2.0, tip_radius_factor=0.0)
    passing = InternalGear(50, 2.0, cutter)
    assert passing.trochoid_margin_cutting > 0.0
    with pytest.raises(GeometryError, match=r"at least 49 .*trochoid interference of the shaper cutter"):
        InternalGear(46, 2.0, cutter)

    def tip_width(g):
        # the cutter's tip leaves the spaces where the tip circles cross, some 9 pitches from the line of centres
        sim = shaped_ring(g, positions=700, turn=1.6, n=200)
        band = (
            shapely.Point(0, 0)
            .buffer(g.tip_radius + 2e-3, quad_segs=4096)
            .difference(shapely.Point(0, 0).buffer(g.tip_radius, quad_segs=4096))
        )
        tooth = sim.intersection(band)
        part = min(shapely.get_parts(tooth), key=lambda p: abs(math.atan2(p.centroid.y, p.centroid.x) - math.pi / g.teeth))
        return part.area / 2e-3 / g.tip_radius  # angular width of the tip, rad

    expected = 2.0 * passing.tip_half_angle
    assert tip_width(passing) == pytest.approx(expected, abs=2e-4)
    bad = object.__new__(InternalGear)  # the refused ring, its closed forms only
    for f, v in {"teeth": 46, "module": 2.0, "cutter": cutter, "shift": 0.0, "addendum": 1.0}.items():
        object.__setattr__(bad, f, v)
    object.__setattr__(bad, "outer_diameter", None)
    object.__setattr__(bad, "tolerance", 1e-4)
    assert bad.trochoid_margin_cutting < 0.0
    assert tip_width(bad) < 2.0 * bad.tip_half_angle - 5e-3  # margin -0.010 rad: tips cut back


def radial_overlap(pair: InternalPair, steps: int = 150) -> float:
    """Brute force: the pinion pulled from its working centre distance towards the ring's centre by up to 3 m;
    the largest overlap area (mm^2) of its outline with the ring's teeth (shapely)."""
    ring, p = pair.ring, pair.pinion
    a = pair.working_center_distance
    outer = shapely.Point(0, 0).buffer(ring.root_radius + 2.0, quad_segs=256)
    teeth = shapely.Polygon(outer.exterior.coords, [ring.outline(1e-3).points[::-1]])
    pin = p.outline(1e-3).points
    moved = [shapely.Polygon(pin + [a - s, 0.0]) for s in np.linspace(0.0, 3.0 * ring.module, steps)[1:]]
    return float(shapely.area(shapely.intersection(teeth, moved)).max())


def test_radial_assembly_margin_against_a_brute_force_withdrawal(spur):
    # KHK's trimming-interference condition (the code's closed form) against pulling the pinion out of
    # mesh radially: a 44-tooth pinion clears the 60-tooth ring, a 50-tooth one collides with its teeth
    clear = InternalPair(InvoluteGear(44, 2.0, shift=0.3, addendum=0.8), spur)
    assert clear.radial_margin > 0.0
    assert radial_overlap(clear) == 0.0
    collides = InternalPair(InvoluteGear(50, 2.0, shift=0.3, addendum=0.8), spur)
    assert collides.radial_margin < 0.0
    assert radial_overlap(collides) > 0.01  # mm^2


def test_reference_thickness_when_the_reference_circle_lies_in_the_bore():
    # shift 0.9 and addendum 0.8: the tip circle r2 + 0.1 m lies outside the reference circle; the
    # thickness on it is the involutes' (ISO 21771: s2 = m (pi/2 - 2 x2 tan(alpha)) with the space-widening sign)
    g = InternalGear(60, 2.0, ShaperCutter(teeth=20, module=2.0, tip_radius_factor=0.2), shift=0.9, addendum=0.8)
    assert g.tip_radius > g.pitch_radius
    s = g.summary()["tooth_thickness_pitch"]
    assert s == pytest.approx(2.0 * (math.pi / 2.0 - 2.0 * 0.9 * math.tan(20.0 * DEG)), abs=1e-9)


def test_pointed_cutter_names_the_largest_shift():
    # ISO 21771 eq. 2.21: the tip land's half-angle (pi/2 + 2 x tan(alpha))/z + inv(alpha) - inv(alpha_a) vanishes at x*
    z, m, alpha = 5, 2.0, 20.0 * DEG

    def land(x):
        ra = z * m / 2.0 + (1.25 + x) * m
        return (math.pi / 2.0 + 2.0 * x * math.tan(alpha)) / z + inv(alpha) - inv(math.acos(z * m / 2.0 * math.cos(alpha) / ra))

    x_star = brentq(land, -1.0, 1.0)
    with pytest.raises(DesignError, match=r"cutter_shift must be at most (-?\d\.\d+)") as info:
        ShaperCutter(teeth=z, module=m)
    assert float(info.value.allowed.split()[2]) == pytest.approx(math.floor(x_star * 1000.0) / 1000.0, abs=1e-12)


def mesh_overlap(pair: InternalPair, turn: float = 0.9, positions: int = 400) -> float:
    """Brute force: the pinion turned in mesh (ring by t, pinion by t z2/z1 about (a_w, 0)) for |t| <= turn;
    the largest overlap area (mm^2) of its outline with the ring's teeth (shapely), both sampled to 1 um."""
    ring, p = pair.ring, pair.pinion
    outer = shapely.Point(0, 0).buffer(ring.root_radius + 2.0, quad_segs=256)
    teeth = shapely.Polygon(outer.exterior.coords, [ring.outline(1e-3).points[::-1]])
    pin = p.outline(1e-3).points
    t = np.linspace(-turn, turn, positions)[:, None]
    own = np.exp(1j * t * ring.teeth / p.teeth) * (pin[:, 0] + 1j * pin[:, 1])
    placed = (own + pair.working_center_distance) * np.exp(-1j * t)  # seen from the ring
    polys = shapely.polygons(np.stack([placed.real, placed.imag], axis=-1))
    return float(shapely.area(shapely.intersection(teeth, polys)).max())


def test_trochoid_margin_of_the_pair_against_a_brute_force_mesh(spur):
    # the pair's trochoid check against turning the pinion through the whole mesh: with a margin the
    # outlines only touch along the conjugate flanks (overlap at the 1 um sampling's level), without one
    # the pinion's tips cut into the ring's tooth tips as they leave the spaces
    clear = InternalPair(InvoluteGear(50, 2.0, shift=0.3, addendum=0.8), spur)
    assert clear.trochoid_margin > 0.0
    assert mesh_overlap(clear) < 1e-4  # mm^2
    strikes = InternalPair(InvoluteGear(56, 2.0, shift=0.3, addendum=0.8), spur, check=False)
    assert strikes.trochoid_margin < 0.0
    assert mesh_overlap(strikes) > 0.05  # mm^2 (0.31 measured)

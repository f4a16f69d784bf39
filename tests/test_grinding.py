"""Form grinding: the wheel from the rotor, the rotor from the wheel, checked by means rotorcad did not use.

References:

* a brute-force grinding simulation (the issue's check): the wheel, a solid of revolution of the
  computed axial profile, screwed along the rotor's helix to 1201 positions; each position's section
  in the plane z = 0 is the set of points whose distance from the wheel axis is below the wheel's
  radius at their axial coordinate (found in closed form per line of the plane, as polygons), and
  the rotor is the tip-circle blank minus all of them (shapely). Neither the contact condition nor
  the envelope formula of rotorcad.grinding is used there;
* the round trip wheel -> rotor through a spline fitted to the wheel points (scipy), evaluated
  between the points the wheel came from;
* for involute gears, the involute itself (ISO 21771: polar angle of a flank point = constant +-
  inv(arccos(r_b / r))), which the spur gear's form wheel must reproduce as its profile (the wheel
  axis lies in the transverse plane), and the symmetry of the helical gear's wheel: turning the whole
  setting by 180 deg about the common perpendicular maps the rotor's helicoid with a symmetric tooth
  space and the wheel axis onto themselves and the wheel's axial coordinate t onto -t, so the wheel's
  profile of a symmetric space is symmetric, rho(t) = rho(-t).
"""

from __future__ import annotations

import tomllib
from pathlib import Path

import numpy as np
import pytest
import shapely
from scipy.interpolate import CubicSpline

from rotorcad.design.rotors import build_pair, pair_spec
from rotorcad.design.schema import rotor_design
from rotorcad.gears import InvoluteGear
from rotorcad.gears.formulas import inv
from rotorcad.geometry import perp_cw
from rotorcad.grinding import WheelEnvelope, default_setting, flute_of, rotor_from_wheel, sensitivities, stock, wheel_profile

SAMPLES = Path(__file__).resolve().parents[1] / "samples"
WHEEL_RADIUS = 100.0


@pytest.fixture(scope="module")
def n_rack_male():
    """The N-rack 5/6 male (Wu & Chi's N4 pair), its flute and the wheel of radius 100 mm."""
    design = tomllib.loads((SAMPLES / "n_rack_5_6.toml").read_text())
    rotors = build_pair(pair_spec(rotor_design(design)))
    pair = rotors.pair
    flute = flute_of(rotors.male_outline().resampled(2e-5))  # 20 nm chords: wheel points 0.2 mm apart at most
    setting = default_setting(2 * np.pi / pair.lead, flute.root_radius, WHEEL_RADIUS, pair.male_pitch_radius)
    return flute, setting, wheel_profile(flute, setting)


def _brute_force_section(flute, setting, wheel, positions=1201, lines=2500):
    """The blank (tip circle) minus the wheel at ``positions`` places along the helix (module docstring).

    The wheel at the advance ``-zc`` along the helix, cut by z = 0, is the fixed wheel cut by the plane
    z = zc, turned by -k zc about the rotor axis. In that plane a point (x, y, zc) has the axial
    coordinate t = y cos S - zc sin S and lies at the distance sqrt((x - A)^2 + w^2),
    w = y sin S + zc cos S, from the wheel axis: inside for |x - A| < sqrt(rho(t)^2 - w^2).
    """
    t_w, r_w = wheel.axial, wheel.radius
    assert np.all(np.diff(t_w) > 0)  # a wheel without folds: rho(t) by interpolation
    k, a_ = setting.twist, setting.center_distance
    cs, sn = np.cos(setting.crossing_angle), np.sin(setting.crossing_angle)
    zmax = 1.2 * np.abs(wheel.contact[:, 2]).max() + 2.0
    polys = []
    for zc in np.linspace(-zmax, zmax, positions):
        y = np.linspace((t_w[0] + zc * sn) / cs, (t_w[-1] + zc * sn) / cs, lines)
        t = y * cs - zc * sn
        half2 = np.interp(t, t_w, r_w) ** 2 - (y * sn + zc * cs) ** 2
        inside = half2 > 0
        if inside.sum() < 2:
            continue
        yy, hw = y[inside], np.sqrt(half2[inside])  # one run: the wheel's section is convex across y here
        ring = np.vstack([np.column_stack([a_ - hw, yy]), np.column_stack([a_ + hw, yy])[::-1]])
        c, s = np.cos(-k * zc), np.sin(-k * zc)
        polys.append(shapely.Polygon(np.column_stack([ring[:, 0] * c - ring[:, 1] * s, ring[:, 0] * s + ring[:, 1] * c])))
    assert len(polys) >= 1000
    cut = shapely.union_all(polys)
    blank = shapely.Point(0.0, 0.0).buffer(flute.tip_radius + 1.0, 2048)
    return blank.difference(cut)


@pytest.fixture(scope="module")
def simulated(n_rack_male):
    flute, setting, wheel = n_rack_male
    return _brute_force_section(flute, setting, wheel)


def test_brute_force_grinding_matches_the_rotor(n_rack_male, simulated):
    """The simulated ground section runs through the rotor's flute within 1 um where the wheel reaches it.

    Reference: the brute-force simulation (module docstring). Reachable: where rotorcad's own stock
    check finds neither secondary cutting nor stock left (|stock| < 0.5 um).
    """
    flute, setting, wheel = n_rack_male
    pts = shapely.points(flute.points)
    gap = shapely.distance(pts, simulated.boundary)
    envelope = WheelEnvelope.of(wheel.axial, wheel.radius)
    left = stock(flute.points, envelope, setting, reach=150.0)
    reach = np.abs(left) < 5e-4
    assert reach.mean() > 0.99  # the N rack's male is ground whole: no secondary cutting
    assert gap[reach].max() < 1e-3, gap[reach].max()


def test_round_trip_through_a_spline(n_rack_male):
    """Wheel from rotor, rotor from wheel: within 0.5 um of the rotor outline between the wheel's points.

    The wheel points are fitted with a cubic spline in their chord length (scipy), its normals taken
    from the spline's derivative and evaluated half-way between the points; the ground points must lie
    on the rotor's flute (distance to its polyline, sampled to 0.1 um chord, shapely).
    """
    flute, setting, wheel = n_rack_male
    t, r = wheel.axial, wheel.radius
    u = np.concatenate([[0.0], np.cumsum(np.hypot(np.diff(t), np.diff(r)))])
    spline = CubicSpline(u, np.column_stack([t, r]))
    um = 0.5 * (u[1:] + u[:-1])
    tr, d = spline(um), spline(um, 1)
    normals = np.column_stack([d[:, 1], -d[:, 0]]) / np.hypot(d[:, 0], d[:, 1])[:, None]
    normals *= np.sign(np.einsum("ij,ij->i", normals, 0.5 * (wheel.normals[1:] + wheel.normals[:-1])))[:, None]
    ground, _ = rotor_from_wheel(tr[:, 0], tr[:, 1], normals, setting)
    exact, _ = rotor_from_wheel(t, r, wheel.normals, setting)
    assert np.abs(exact - flute.points).max() < 1e-9  # the analytic normals give the points back
    dist = shapely.distance(shapely.points(ground), shapely.LineString(flute.points))
    assert np.isfinite(dist).all() and dist.max() < 5e-4, dist.max()


def _gear_wheel(helix_deg):
    gear = InvoluteGear(teeth=23, module=4.0, helix_angle=np.radians(helix_deg), shift=0.2, tolerance=1e-4)
    flute = flute_of(gear.outline())
    k = np.tan(gear.helix_angle) / gear.pitch_radius
    setting = default_setting(k, flute.root_radius, 80.0, gear.pitch_radius)
    return gear, flute, setting, wheel_profile(flute, setting)


def test_spur_gear_wheel_is_the_involute_space():
    """A spur gear's form wheel has the tooth space's involute as its profile (ISO 21771 involute)."""
    gear, _, setting, wheel = _gear_wheel(0.0)
    assert setting.crossing_angle == 0.0
    x, y = setting.center_distance - wheel.radius, wheel.axial  # the wheel's profile laid in the transverse plane
    r = np.hypot(x, y)
    rb = gear.base_radius
    on = (r > gear.form_radius + 0.05) & (r < gear.tip_radius - 0.05)
    for sign in (1.0, -1.0):  # each flank: polar angle - sign * inv(alpha(r)) is constant
        sel = on & (sign * y > 0)
        assert sel.sum() > 20
        c = np.arctan2(y[sel], x[sel]) - sign * inv(np.arccos(rb / r[sel]))
        assert np.ptp(c) * r[sel].max() < 1e-6, np.ptp(c) * r[sel].max()


def test_helical_gear_wheel_is_symmetric():
    """A helical gear's form wheel grinds a symmetric space with a symmetric profile (module docstring)."""
    _, _, setting, wheel = _gear_wheel(20.0)
    assert np.isclose(setting.crossing_angle, np.radians(20.0))
    assert not wheel.folds and wheel.valid.all()
    t, r = wheel.axial, wheel.radius
    pos = t > 0
    neg = (t < 0) & (-t < t[pos].max())
    mirrored = np.interp(-t[neg], t[pos], r[pos])
    assert neg.sum() > 50 and np.abs(mirrored - r[neg]).max() < 5e-4
    # and it is not the spur wheel: the helix changes the profile by more than the tolerance
    _, _, _, spur = _gear_wheel(0.0)
    assert np.abs(np.interp(t, spur.axial, spur.radius) - r).max() > 1e-2


def test_helical_gear_tip_edge_cut_as_the_brute_force_finds():
    """Secondary cutting found by the stock check is where and about as deep as the simulation cuts.

    A helical gear (z = 17, m = 3 mm, beta = 15 deg, x = 0.3, wheel radius 60 mm): the wheel's ends
    cut the sharp tip edges (the helicoid's tip corners) by some 20 um; the brute-force simulation
    (module docstring) must remove those points, by a normal distance between 0.6 and 1 times the
    stock (stock is measured along the wheel's radius, the simulation's gap along the rotor's
    normal), and keep every other flute point within 1 um of its boundary.
    """
    from rotorcad.grinding import grind

    gear = InvoluteGear(teeth=17, module=3.0, helix_angle=np.radians(15.0), shift=0.3, tolerance=1e-4)
    job = grind(gear.outline(), np.tan(gear.helix_angle) / gear.pitch_radius, 17, 60.0, gear.pitch_radius)
    wheel, check = job.wheel, job.check
    sim = _brute_force_section(wheel.flute, wheel.setting, wheel)
    pts = shapely.points(wheel.flute.points)
    gap = shapely.distance(pts, sim.boundary)
    kept = shapely.contains(sim, pts) | (gap < 1e-9)
    cut = check.flute_stock < -1e-3
    assert 1 <= cut.sum() <= 4 and check.secondary_cutting_deviation > 0.01
    assert not kept[cut].any()
    ratio = gap[cut] / -check.flute_stock[cut]
    assert ((ratio > 0.6) & (ratio <= 1.0 + 1e-3)).all(), ratio
    assert gap[~cut].max() < 1e-3, gap[~cut].max()


def test_grind_command_writes_the_dresser_files(tmp_path, capsys):
    """``rotorcad grind --json`` and its files, read back by ezdxf (a third-party reader) and numpy.

    The DXF polylines hold the CSV's profile (R12 as AC1009, R2000 as AC1015 with $INSUNITS = 4, mm);
    the worn wheel's outside radius follows the worn radius (root + worn radius: the wheel plunges).
    """
    import json

    import ezdxf

    from rotorcad.cli.main import main

    out = tmp_path / "wheel"
    args = ["grind", str(SAMPLES / "n_rack_5_6.toml"), "--wheel-radius", "100", "--worn-radius", "80"]
    args += ["--out", str(out), "--plot", str(tmp_path / "chart.svg"), "--json"]
    assert main(args) == 0
    result = json.loads(capsys.readouterr().out)
    new, worn = result["wheels"]["new"], result["wheels"]["worn"]
    assert result["body"] == "male" and np.isclose(result["crossing_angle_deg"], 46.0, atol=1e-4)  # the N4 pair's 46 deg
    assert np.isclose(new["center_distance"] - worn["center_distance"], 20.0)
    assert new["secondary_cutting_point_count"] == 0 and new["round_trip_deviation"] < 1e-9
    assert len(result["files"]) == 10 and (tmp_path / "chart.svg").read_text().lstrip().startswith("<?xml")
    sens = np.loadtxt(out / "wheel_male_sensitivity.csv", delimiter=",", comments="#", skiprows=3)
    for k, name in enumerate(("center_distance", "crossing_angle", "axial_position", "wheel_radius", "wheel_profile")):
        assert result["sensitivity"][name]["unit"] == ("deg" if name == "crossing_angle" else "mm")
        assert np.isclose(np.abs(sens[:, 3 + k]).max(), result["sensitivity"][name]["max_normal_deviation_per_unit"])
    worn_use = result["worn_with_new_profile"]
    assert worn_use["wheel_radius_change"] == -20.0
    assert worn_use["rms_normal_deviation_compensated"] < worn_use["rms_normal_deviation"]
    for state, numbers in (("new", new), ("worn", worn)):
        rows = np.loadtxt(out / f"wheel_male_{state}.csv", delimiter=",", comments="#", skiprows=3)
        assert rows.shape == (numbers["profile_point_count"], 6)
        assert np.isclose(rows[:, 1].max(), numbers["wheel_max_radius"])
        for version, acad in (("r12", "AC1009"), ("r2000", "AC1015")):
            doc = ezdxf.readfile(out / f"wheel_male_{state}_{version}.dxf")
            assert doc.dxfversion == acad
            if version == "r2000":
                assert doc.header["$INSUNITS"] == 4
            poly = [e for e in doc.modelspace() if e.dxf.layer == "WHEEL"]
            assert len(poly) == 1
            xy = np.array([tuple(p)[:2] for p in poly[0].points()]) if version == "r12" else np.array(poly[0].get_points("xy"))
            assert np.abs(xy - rows[:, :2]).max() < 1e-9


@pytest.mark.parametrize(
    ("extra", "option"),
    [
        ([], "--wheel-radius"),
        (["--wheel-radius", "0"], "--wheel-radius"),
        (["--wheel-radius", "100", "--worn-radius", "100"], "--worn-radius"),
        (["--wheel-radius", "100", "--crossing-angle", "85"], "--crossing-angle"),
        (["--wheel-radius", "100", "--wheel-center-distance", "50"], "--wheel-center-distance"),
        (["--wheel-radius", "100", "--wheel-center-distance", "1e9"], "--wheel-center-distance"),
        (["--wheel-radius", "10"], "--wheel-radius"),
        (["--wheel-radius", "100", "--setting-radius", "5000"], "--setting-radius"),
    ],
)
def test_grind_command_refuses_bad_settings(tmp_path, capsys, extra, option):
    """A setting out of range: one sentence naming the option, exit 2, no folder or file made."""
    from rotorcad.cli.main import main

    out = tmp_path / "never"
    assert main(["grind", str(SAMPLES / "n_rack_5_6.toml"), *extra, "--out", str(out)]) == 2
    err = capsys.readouterr().err.strip()
    assert err.startswith(f"rotorcad: error: {option} must") and err.count("\n") == 0 and "Traceback" not in err
    assert not out.exists()


def test_spur_gear_sensitivities_are_translations():
    """Spur gear: a wheel moved along x or along its axis (y) grinds the space translated (a rigid
    motion: normal deviation = the step's component along the normal); a wheel worn and set to plunge
    again grinds the same space (its section in z = 0 is the space); a wheel dressed thicker by d
    grinds the rotor thinner by d."""
    _, flute, _, wheel = _gear_wheel(0.0)
    sens = sensitivities(wheel)
    n = perp_cw(flute.tangents[wheel.valid])
    assert np.abs(sens.per_unit[0] - n[:, 0]).max() < 1e-8  # centre distance: along +x
    assert np.abs(sens.per_unit[2] - n[:, 1]).max() < 1e-8  # axial position: the wheel axis is +y
    assert np.abs(sens.per_unit[3]).max() < 1e-8
    assert np.abs(sens.per_unit[4] + 1.0).max() < 1e-8


def test_helical_profile_sensitivity_is_the_normals_inclination(n_rack_male):
    """A wheel dressed thicker by d along its normal takes d off the helicoid along the common normal
    N = (n, k q) (q = P . T): in the transverse section that is d sqrt(1 + (k q)^2) along n (the
    helicoid's normal derived in rotorcad.grinding.wheel_profile's docstring, by hand: r_u x r_theta)."""
    flute, setting, wheel = n_rack_male
    sens = sensitivities(wheel)
    q = np.einsum("ij,ij->i", flute.points, flute.tangents)[wheel.valid]
    expected = -np.sqrt(1.0 + (setting.twist * q) ** 2)
    assert np.abs(sens.per_unit[4] - expected).max() < 1e-6
    assert expected.min() < -1.3  # the inclination matters on this rotor


def test_setting_errors_as_the_brute_force_grinds_them(n_rack_male):
    """Centre distance +20 um, axial position +20 um and crossing angle +0.02 deg at once: the linear
    prediction of the sensitivities against the brute-force simulation of the wheel so set (the
    simulated section's signed distance from each design point: + where material is left), 1 um."""
    import dataclasses
    import types

    flute, setting, wheel = n_rack_male
    errors = {"center_distance": 0.02, "axial_position": 0.02, "crossing_angle": 0.02}
    predicted = sensitivities(wheel).deviation(errors)
    wrong = dataclasses.replace(
        setting,
        center_distance=setting.center_distance + 0.02,
        crossing_angle=setting.crossing_angle + np.radians(0.02),
    )
    moved = types.SimpleNamespace(axial=wheel.axial + 0.02, radius=wheel.radius, contact=wheel.contact)
    sim = _brute_force_section(flute, wrong, moved)
    pts = shapely.points(flute.points[wheel.valid])
    gap = shapely.distance(pts, sim.boundary)
    signed = np.where(shapely.contains(sim, pts), gap, -gap)
    inner = np.hypot(*flute.points[wheel.valid].T) < flute.tip_radius - 0.5  # the tip edges aside
    assert np.abs(predicted).max() > 0.02  # the errors matter
    assert np.abs(signed - predicted)[inner].max() < 1e-3, np.abs(signed - predicted)[inner].max()


def test_compensation_finds_a_planted_setting_error(n_rack_male):
    """A wheel swivelled 0.05 deg too far and set 30 um too far out: the corrections that minimise the
    rms deviation are the planted errors undone (the planted values are the reference), and the rotor
    is then ground back to its design (the closed-form envelope, not linearised)."""
    from rotorcad.grinding.sensitivity import compensate, normal_deviation

    _, _, wheel = n_rack_male
    planted = {"crossing_angle": 0.05, "center_distance": 0.03}
    assert np.abs(normal_deviation(wheel, planted)).max() > 0.02  # the errors matter
    fix = compensate(wheel, planted, ("crossing_angle", "center_distance"))
    assert abs(fix["crossing_angle"] + 0.05) < 1e-6 and abs(fix["center_distance"] + 0.03) < 1e-6
    undone = {k: planted[k] + fix[k] for k in planted}
    assert np.abs(normal_deviation(wheel, undone)).max() < 1e-7


def test_grind_from_measured_points_matches_the_design(n_rack_male, tmp_path, capsys):
    """The male given as points (its outline at 1 um chords, CSV, read and fitted by rotorcad's points
    readers) gives the design's wheel: the same shape within 5 um once the axial zero is matched (the
    zero is the bisector of the flute's tip points, which a fitted outline puts a few ten um along the
    helix elsewhere); reference: the wheel of the analytic design (its own round trip and brute-force
    checks above)."""
    from exports.csv_points import write_points
    from rotorcad.cli.main import main

    _, _, wheel = n_rack_male
    design = tomllib.loads((SAMPLES / "n_rack_5_6.toml").read_text())
    rotors = build_pair(pair_spec(rotor_design(design)))
    write_points(tmp_path / "male.csv", rotors.male_outline().resampled(1e-3).points)
    pair = design["pair"]
    args = ["grind", "--male-points", str(tmp_path / "male.csv"), "--wheel-radius", "100", "--out", str(tmp_path)]
    args += [
        x
        for k in (
            "male_teeth",
            "female_teeth",
            "center_distance",
            "male_tip_radius",
            "male_root_radius",
            "female_tip_radius",
            "female_root_radius",
            "lead",
        )
        for x in (f"--{k.replace('_', '-')}", str(pair[k]))
    ]
    assert main([*args, "--quiet"]) == 0
    capsys.readouterr()
    rows = np.loadtxt(tmp_path / "wheel_male_new.csv", delimiter=",", comments="#", skiprows=3)
    from scipy.spatial import cKDTree

    # signed distance along the design wheel's normal at the nearest design point (tangential offsets
    # cancel to first order), then the axial shift that fits best (least squares) and what is left
    inner = rows[20:-20, :2]
    j = cKDTree(np.column_stack([wheel.axial, wheel.radius])).query(inner)[1]
    n = wheel.normals[j]
    signed = np.einsum("ij,ij->i", inner - np.column_stack([wheel.axial[j], wheel.radius[j]]), n)
    shift = -np.sum(signed * n[:, 0]) / np.sum(n[:, 0] ** 2)
    left = signed + shift * n[:, 0]
    assert abs(shift) < 0.1 and np.abs(left).max() < 5e-3, (shift, np.abs(left).max())


def test_worn_wheel_compensation_where_some_wheel_points_lose_contact():
    """The Lysholm male's wheel worn by 10 mm, left at its profile: swivelled by the correction, some
    wheel points no longer touch the rotor (NaN); the correction is found over the others and lowers
    the rms deviation (the rms before and after, both from the closed-form envelope, are the reference)."""
    from rotorcad.grinding import grind
    from rotorcad.grinding.sensitivity import compensate, normal_deviation

    design = tomllib.loads((SAMPLES / "lysholm_4_6.toml").read_text())
    rotors = build_pair(pair_spec(rotor_design(design)))
    pair = rotors.pair
    wheel = grind(rotors.male_outline(), 2 * np.pi / pair.lead, 4, 100.0, pair.male_pitch_radius).wheel
    before = normal_deviation(wheel, {"wheel_radius": 10.0})
    fix = compensate(wheel, {"wheel_radius": 10.0})
    after = normal_deviation(wheel, {"wheel_radius": 10.0, **fix})
    assert np.isnan(after).any() and not np.isnan(before).any()
    assert np.isfinite(fix["crossing_angle"]) and np.sqrt(np.nanmean(after**2)) < 0.8 * np.sqrt(np.nanmean(before**2))


def test_least_cutting_angle_cuts_less_than_its_neighbours():
    """The helical gear's tip edges cut by 20 um at the helix angle: the crossing angle found cuts less
    than the default and than 0.5 deg either side of it (each judged by the stock check, which the
    brute-force simulation confirms above)."""
    from rotorcad.grinding.job import cut_depth, grind, least_cutting_angle

    gear = InvoluteGear(teeth=17, module=3.0, helix_angle=np.radians(15.0), shift=0.3, tolerance=1e-4)
    args = (gear.outline(), np.tan(gear.helix_angle) / gear.pitch_radius, 17, 60.0, gear.pitch_radius)
    angle, job = least_cutting_angle(*args)
    found = cut_depth(job)
    assert found < 0.5 * cut_depth(grind(*args))
    for step in (-0.5, 0.5):
        assert found <= cut_depth(grind(*args, angle + np.radians(step)))


def test_left_hand_rotor_wheel_is_the_mirror_image(n_rack_male):
    """A left-hand rotor is the right-hand one mirrored in the plane y = 0 (profile mirrored, twist and
    crossing angle negated); the mirror takes the wheel axis to the new one with t -> -t, so its wheel
    is the same profile mirrored about the mid-plane: rho(t) = rho_right(-t) (a symmetry, not a
    computed reference)."""
    _, setting, wheel = n_rack_male
    design = tomllib.loads((SAMPLES / "n_rack_5_6.toml").read_text())
    rotors = build_pair(pair_spec(rotor_design(design)))
    left = flute_of(rotors.male_outline().mirrored(0.0).resampled(2e-5))
    mirrored = default_setting(-setting.twist, left.root_radius, WHEEL_RADIUS, rotors.pair.male_pitch_radius)
    assert np.isclose(mirrored.crossing_angle, -setting.crossing_angle)
    other = wheel_profile(left, mirrored)
    t, r = -other.axial[::-1], other.radius[::-1]
    inside = (t > wheel.axial.min() + 0.01) & (t < wheel.axial.max() - 0.01)
    assert inside.sum() > 1000
    assert np.abs(np.interp(t[inside], wheel.axial, wheel.radius) - r[inside]).max() < 1e-6

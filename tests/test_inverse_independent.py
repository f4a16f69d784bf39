"""The inverse path (points -> spline -> rack -> clearance, conjugate, hob) on rotors that rotorcad
did not make: a 4/6 pair cut by brute force from a trapezoid rack with flats and rounded corners
(tests/independent_pairs.py, shapely booleans only), as a CMM or a drawing gives it.

References, none produced by the code under test:
* the generating rack itself (closed form: lines and arcs);
* the closed form of a straight rack flank's image, the involute of r_w cos(alpha) (Litvin, *Gear
  Geometry and Applied Theory*, sec. 10), which checks the generator;
* a designed flank offset in the normal section, delta_n = delta_t / sqrt(cos^2 a / cos^2 b + sin^2 a)
  for a transverse offset delta_t of a rack flank of transverse angle a at the helix angle b
  (Wu & Chi, eq. 7: the normal rack is the transverse rack with lengths along the pitch line times
  cos b);
* the female cut by brute force with the male outline as the tool (rotor-rotor generation).

Where the rack's flat cuts back a rotor's tip (a sharp tip corner), the mate's root rounding, cut
by the full rack rounding, is deeper than the corner's path: the brute-force pair has a real gap
there (up to 0.1 mm on this pair). The comparisons below therefore select the flanks where both
rotors touch them and the flats (the lands' images) away from the roundings (``regions``).
"""

from __future__ import annotations

import json

import numpy as np
import pytest
import shapely
from independent_pairs import (
    cut_rotor,
    distance_to_line,
    female_cut_by_male,
    one_lobe,
    resample,
    trapezoid_4_6,
    write_drawing,
)

from exports.csv_points import write_points
from exports.dxf_profile import read_profile_dxf
from rotorcad.clearance import MeshingClearance
from rotorcad.cli.main import main
from rotorcad.curves import Arc, Spline
from rotorcad.inverse_rack import MEASURED_MIN_TURN, rotor_rack
from rotorcad.rotor_pair import RotorPair
from rotorcad.rotor_points import lobe_pieces, pair_from_rotor_points

PAIR = trapezoid_4_6()
OFFSET = 0.05  # mm: the female's falling flank cut 50 um deeper (the rack flank moved along its normal)
ALPHA = np.radians(30.0)
LEAD = 300.0


def rotor_pair(lead: float = LEAD) -> RotorPair:
    return RotorPair(4, 6, 100.0, **PAIR.radii(), lead=lead, length=190.0, strict=False)


def male() -> np.ndarray:
    return cut_rotor(PAIR, "male")


def female(offset: float = 0.0) -> np.ndarray:
    return cut_rotor(trapezoid_4_6(flank_offset=offset) if offset else PAIR, "female")


def noisy(ring: np.ndarray, seed: int) -> np.ndarray:
    """CMM-like: about 200 points a flank (0.1 mm apart), 1 um Gaussian scatter along the normals."""
    return resample(ring, 0.1, noise=1e-3, seed=seed)


def clearance(m: np.ndarray, f: np.ndarray, contact: str = "driving", lead: float = LEAD) -> MeshingClearance:
    pair = rotor_pair(lead)
    return MeshingClearance(pair, lobe_pieces(pair, m, "male"), lobe_pieces(pair, f, "female"), contact=contact)


def on_flats(x: np.ndarray, margin: float = 0.2) -> np.ndarray:
    """Rack x positions on the generating rack's flats, ``margin`` mm away from their roundings."""
    period = PAIR.rack.period
    flats = [g for kind, g in PAIR.rack.pieces() if kind == "line" and abs(g[0][1] - g[1][1]) < 1e-12]
    u = np.mod(x, period)
    inside = np.zeros(len(x), dtype=bool)
    for (x0, _), (x1, _) in flats:
        lo, hi = min(x0, x1), max(x0, x1)
        if lo <= 0.0 + 1e-9 or hi >= period - 1e-9:  # the bottom flat is split at the period's ends
            inside |= (u >= (lo + margin if lo > 1e-9 else -1.0)) & (u <= (hi - margin if hi < period - 1e-9 else period + 1.0))
        else:
            inside |= (u >= lo + margin) & (u <= hi - margin)
    return inside


def regions(mc: MeshingClearance) -> dict[str, np.ndarray]:
    """Datum (female rack) points in contact, by what they are on the generating rack: the rising
    and falling flanks where both rotors touch them (rack heights -6.9 to 6.6 mm: above 6.73 mm the
    rack's flat has cut the male's tip back, below -7.10 mm the female's) and the flats (the
    lands' images) 0.2 mm away from the roundings; the roundings are left out (module docstring)."""
    pts, tan = mc.female_rack.points, mc.female_rack.tangents
    used = mc._in_both_bores(mc.clearance) & np.isfinite(mc.clearance)
    flank = (pts[:, 1] >= -6.9) & (pts[:, 1] <= 6.6)
    return {
        "rising": used & flank & (tan[:, 1] > 0),
        "falling": used & flank & (tan[:, 1] < 0),
        "lands": used & (np.abs(pts[:, 1]) > 7.9) & on_flats(pts[:, 0] - mc.shift),
    }


def normal_offset(delta_t: float, lead: float = LEAD) -> float:
    beta = np.arctan(2 * np.pi * PAIR.male_pitch_radius / lead)
    return delta_t / np.sqrt(np.cos(ALPHA) ** 2 / np.cos(beta) ** 2 + np.sin(ALPHA) ** 2)


def test_the_generator_cuts_involute_flanks_and_lands():
    # Closed form (Litvin sec. 10): the rack's straight flank generates the involute of the base
    # circle r_b = r_w cos(alpha), whose polar angle is theta0 +- inv(arccos(r_b / r)); the flats
    # generate lands at r_w +- h. The brute-force cut must follow both within 0.5 um.
    ring = male()
    r, theta = np.hypot(*ring.T), np.unwrap(np.arctan2(ring[:, 1], ring[:, 0]))
    rb = PAIR.male_pitch_radius * np.cos(ALPHA)
    assert np.abs(r.max() - 48.0) < 1e-6 and np.abs(r.min() - 32.0) < 1e-6
    flank = (r > 35.2) & (r < 47.9)  # the straight flank generates r from 35.07 to the tip
    runs = np.split(np.flatnonzero(flank), np.flatnonzero(np.diff(np.flatnonzero(flank)) > 1) + 1)
    assert len(runs) == 8  # two flanks a lobe
    for run in runs:
        a = np.arccos(rb / r[run])
        inv = np.tan(a) - a
        sign = np.sign(np.polyfit(r[run], theta[run], 1)[0])
        theta0 = np.median(theta[run] - sign * inv)
        assert np.abs(r[run] * (theta[run] - theta0 - sign * inv)).max() < 5e-4


@pytest.mark.parametrize("kind", ["exact", "noisy"])
def test_a_conjugate_pair_measures_no_clearance_on_flanks_and_lands(kind):
    # Both rotors cut by the same rack: on the flanks and lands the normal clearance is zero
    # within 2 um (exact cut outlines) and 5 um (CMM-like points, whole male, one clockwise
    # female lobe starting mid-flank).
    if kind == "exact":
        m, f = male(), female()
    else:
        m, f = noisy(male(), 1), one_lobe(noisy(female(), 2), 6, start_deg=17.0)[::-1]
    mc = clearance(m, f)
    for name, sel in regions(mc).items():
        assert sel.sum() > 100, name
        assert np.abs(mc.clearance[sel]).max() < (2e-3 if kind == "exact" else 5e-3), name


@pytest.mark.parametrize("kind", ["exact", "noisy"])
def test_a_designed_flank_offset_comes_back_in_the_normal_section(kind):
    # The female's falling flank cut 50 um deeper by the rack: with contact on the driving
    # (rising) flank, the falling flank reads delta_n (closed form above) within 3 um, the
    # driving flank and the lands zero within 2 um (5 um noisy).
    m, f = male(), female(OFFSET)
    if kind == "noisy":
        m, f = noisy(m, 3), noisy(f, 4)
    mc = clearance(m, f)
    sel = regions(mc)
    expected = normal_offset(OFFSET)
    np.testing.assert_allclose(mc.clearance[sel["falling"]], expected, atol=3e-3)
    tol = 2e-3 if kind == "exact" else 5e-3
    assert np.abs(mc.clearance[sel["rising"]]).max() < tol
    assert np.abs(mc.clearance[sel["lands"]]).max() < tol


def test_the_offset_holds_for_a_straight_rotor_too():
    # lead -> infinity: the normal section is the transverse one, delta_n = delta_t exactly.
    mc = clearance(male(), female(OFFSET), contact="as-given", lead=1e5)  # 100 m, the largest design lead
    sel = regions(mc)
    np.testing.assert_allclose(mc.clearance[sel["falling"]], OFFSET, atol=2e-3)
    assert np.abs(mc.clearance[sel["rising"]]).max() < 1e-3


@pytest.mark.parametrize("rotor", ["male", "female"])
def test_racks_from_points_of_either_rotor_follow_the_generating_rack(rotor):
    # Inverse generation of the cut rotor, exact and noisy, against the closed-form rack (lines
    # and arcs): within 2 um wherever the rotor touches it (flanks and lands).
    pair = rotor_pair()
    chain = PAIR.rack.polygon_chain(1e-7)
    period = PAIR.rack.period
    rack_line = shapely.LineString(np.vstack([chain + [k * period, 0.0] for k in range(-3, 4)]))
    ring = male() if rotor == "male" else female()
    for pts in (ring, noisy(ring, 5)):
        # the rack as the meshing clearance derives it (measured pieces, rack frame of CONTRACT.md)
        rack = rotor_rack(pair, rotor, lobe_pieces(pair, pts, rotor), samples=800, min_turn=MEASURED_MIN_TURN).in_contract_frame()
        y = rack.points[:, 1]
        sel = ((y >= -6.9) & (y <= 6.6)) | ((np.abs(y) > 7.9) & on_flats(rack.points[:, 0]))
        d = distance_to_line(rack.points[sel], rack_line)
        assert d.max() < 2e-3


def test_the_female_from_male_points_is_the_female_the_male_cuts():
    # rotor -> rack -> mate against brute force: the female cut with the male outline as the tool
    # (rotor-rotor generation, 3000 positions; its own scallops and the sharp tip corner's path
    # between positions reach 13 um against 6000 positions). Mean distance within 2 um, exact and noisy.
    # The rebuilt section at a 0.5 um chord (its sagitta a quarter of the 2 um bound) for speed: at
    # 0.1 um the exact male's section spent 17-20 s in shapely.make_valid (its outline noded has
    # ~28000 sliver faces) for the same reading (mean / max distance, exact male: 0.36 / 9.03 um at
    # 0.1 um, 0.48 / 9.13 um at 0.5 um; noisy: 0.48 / 8.98 um and 0.54 / 8.91 um).
    pair = rotor_pair()
    reference = shapely.LinearRing(female_cut_by_male(PAIR, male(), positions=3000))
    for pts in (male(), noisy(male(), 6)):
        rebuilt = pair_from_rotor_points(pair, pts, "male").section("female", 5e-4).exterior
        dense = np.asarray(shapely.segmentize(rebuilt, 0.01).coords)
        d = distance_to_line(dense, reference)
        assert d.mean() < 2e-3
        assert d.max() < 15e-3


def test_outline_forms_give_the_same_clearance():
    # one lobe or the whole outline, either direction, any start, with or without a repeated end
    # point: the same pieces, hence the same clearance (1 um).
    m, f = male(), female(OFFSET)
    reference = clearance(m, f)  # built once: its clearance and summary serve every form below
    ref, ref_mean = reference.clearance, reference.summary()["mean_clearance"]
    forms = [
        (m[::-1], np.vstack([f, f[:1]])),
        (np.roll(m, 1234, axis=0), one_lobe(f, 6, start_deg=40.0)),
        (one_lobe(m, 4, start_deg=-20.0)[::-1], np.roll(f[::-1], 77, axis=0)),
    ]
    for mm, ff in forms:
        c = clearance(mm, ff)
        a, b = np.nanmax(np.abs(ref)), np.nanmax(np.abs(c.clearance))
        assert abs(a - b) < 1e-3
        assert c.summary()["mean_clearance"] == pytest.approx(ref_mean, abs=1e-3)


def test_cli_refuses_a_wrong_lobe_count_and_a_binary_file(tmp_path, capsys):
    write_points(tmp_path / "m.csv", male())
    write_points(tmp_path / "f.csv", female())
    (tmp_path / "b.csv").write_bytes(b"\x89PNG\r\n\x1a\n" + bytes(range(256)) * 4)
    base = ["clearance", "--female-points", str(tmp_path / "f.csv"), "--female-teeth", "6", "--center-distance", "100"]
    capsys.readouterr()
    assert main([*base, "--male-points", str(tmp_path / "m.csv"), "--male-teeth", "5"]) == 2
    err = capsys.readouterr().err.strip()
    assert "--male-points" in err and "4 lobes" in err and "Traceback" not in err and len(err.splitlines()) == 1
    assert main([*base, "--male-points", str(tmp_path / "b.csv"), "--male-teeth", "4"]) == 2
    err = capsys.readouterr().err.strip()
    assert "--male-points" in err and "Traceback" not in err and len(err.splitlines()) == 1
    assert main([*base, "--male-points", str(tmp_path / "m.csv"), "--male-teeth", "4", "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert abs(data["min_normal_clearance"]) < 2e-3


@pytest.mark.parametrize("rotor", ["male", "female"])
def test_a_plain_trapezoid_rotor_is_hobbable(tmp_path, capsys, rotor):
    # A rotor cut by a trapezoid rack (30 deg flanks, 1.5 mm roundings) is what any hob makes: the
    # verdict from its points (exact, and CMM-like) is "hobbable" with no reasons, and the normal
    # rack's flank angle is the closed form atan(tan(30 deg) cos(beta)) (Wu & Chi eq. 7).
    ring = male() if rotor == "male" else female()
    beta = np.arctan(2 * np.pi * PAIR.male_pitch_radius / LEAD)
    alpha_n = np.degrees(np.arctan(np.tan(ALPHA) * np.cos(beta)))
    dims = ["--male-teeth", "4", "--female-teeth", "6", "--center-distance", "100", "--lead", str(LEAD)]
    dims += [f"--{k.replace('_', '-')}={v}" for k, v in PAIR.radii().items()]
    for k, pts in enumerate((ring, noisy(ring, 7))):
        write_points(tmp_path / f"p{k}.csv", pts)
        capsys.readouterr()
        assert main(["hob", f"--{rotor}-points", str(tmp_path / f"p{k}.csv"), *dims, "--json"]) == 0
        data = json.loads(capsys.readouterr().out)
        assert data["hobbable"] and data["reasons"] == []
        # the smallest flank angle is a minimum over the flank: with 1 um scatter the smoothed
        # spline's slope wanders by a few mrad, so 0.3 deg there, 0.02 deg for the exact cut
        assert data["racks"][rotor]["normal_pressure_angle_min_deg"] == pytest.approx(alpha_n, abs=0.3 if k else 0.02)


def test_a_drawing_with_arcs_splines_and_polylines_gives_the_csv_result(tmp_path, capsys):
    # The same cut pair as CSV points and as DXF drawings made with ezdxf (lands as ARCs, flanks
    # as fit-point SPLINEs, the rest as LWPOLYLINEs), read as exact curves: the clearance on the
    # flanks and lands agrees within 1 um (median; 2 um at the extremes), and so do the command's
    # minimum and positioning
    # (points 0.1 mm apart, as a drawing's spline would be laid through them).
    m, f = resample(male(), 0.1), resample(female(OFFSET), 0.1)
    write_points(tmp_path / "m.csv", m)
    write_points(tmp_path / "f.csv", f)
    write_drawing(str(tmp_path / "m.dxf"), m, (48.0, 32.0), (35.2, 47.9))
    write_drawing(str(tmp_path / "f.dxf"), f, (68.0, 52.0), (53.0, 67.9))
    pair = rotor_pair()
    drawn = [read_profile_dxf(tmp_path / "m.dxf", "m"), read_profile_dxf(tmp_path / "f.dxf", "f")]
    assert any(isinstance(c, Arc) for c in drawn[0]) and any(isinstance(c, Spline) for c in drawn[0])
    via_dxf = MeshingClearance(pair, lobe_pieces(pair, drawn[0], "male"), lobe_pieces(pair, drawn[1], "female"))
    via_csv = clearance(m, f)
    for name, sel in regions(via_csv).items():
        ref = via_csv.clearance[sel]
        other = regions(via_dxf)[name]
        assert abs(np.median(via_dxf.clearance[other]) - np.median(ref)) < 1e-3, name
        # at the flanks' ends the spline through points 0.1 mm apart leaves 1.2 um where the
        # drawing's exact curves read the closed form
        assert abs(via_dxf.clearance[other].max() - ref.max()) < 2e-3, name
    dims = ["--male-teeth", "4", "--female-teeth", "6", "--center-distance", "100", "--json"]
    results = []
    for ext in ("csv", "dxf"):
        capsys.readouterr()
        args = ["clearance", "--male-points", str(tmp_path / f"m.{ext}"), "--female-points", str(tmp_path / f"f.{ext}"), *dims]
        assert main(args) == 0, capsys.readouterr().err
        results.append(json.loads(capsys.readouterr().out))
    for key in ("min_normal_clearance", "female_rack_shift"):
        assert results[1][key] == pytest.approx(results[0][key], abs=1e-3), key


def test_a_designed_clearance_is_made_and_measured_back(tmp_path, capsys):
    # Make: the trapezoid rack given to `rotor --rack-points` with --clearance sealing=0.04 writes
    # a female thinned on its sealing (falling) flank. Independent check: on that flank it lies on
    # the female that the rack with its falling flank moved by delta_t (the transverse offset of
    # the closed form, inverted) cuts by brute force, within 3 um (0.1 um typical). Round trip: `clearance
    # --contact as-given` reads 40 um there within 3 um and zero on the driving flank within 2 um.
    delta_n = 0.04
    beta = np.arctan(2 * np.pi * PAIR.male_pitch_radius / LEAD)
    delta_t = delta_n * np.sqrt(np.cos(ALPHA) ** 2 / np.cos(beta) ** 2 + np.sin(ALPHA) ** 2)
    rack, _ = PAIR.rack.sample(0.01)
    write_points(tmp_path / "rack.csv", np.vstack([rack, rack[:1] + [PAIR.rack.period, 0.0]]))
    dims = ["--male-teeth", "4", "--female-teeth", "6", "--center-distance", "100", "--lead", str(LEAD)]
    dims += [f"--{k.replace('_', '-')}={v}" for k, v in PAIR.radii().items()]
    out = ["--male-csv", str(tmp_path / "m.csv"), "--female-csv", str(tmp_path / "f.csv"), "--json"]
    capsys.readouterr()
    assert main(["rotor", "--rack-points", str(tmp_path / "rack.csv"), *dims, "--clearance", "sealing=0.04", *out]) == 0
    designed = json.loads(capsys.readouterr().out)["designed_clearance"]
    assert designed == {"driving": 0.0, "sealing": 0.04, "lands": 0.0, "blend": 1.0}
    made = np.loadtxt(tmp_path / "f.csv", delimiter=",", comments="#", skiprows=2)
    reference = shapely.LinearRing(female(delta_t))
    r = np.hypot(*made.T)
    flank = (r > 53.5) & (r < 66.5)
    d = distance_to_line(made[flank], reference)
    assert np.median(d) < 1e-4 and d.max() < 3e-3  # 2.1 um at the flank's foot, 0.01 um typical
    mc = clearance(np.loadtxt(tmp_path / "m.csv", delimiter=",", comments="#", skiprows=2), made, contact="as-given")
    sel = regions(mc)
    np.testing.assert_allclose(mc.clearance[sel["falling"]], delta_n, atol=3e-3)
    assert np.abs(mc.clearance[sel["rising"]]).max() < 2e-3


@pytest.mark.parametrize("offset", [0.0, OFFSET])
def test_the_distribution_lands_on_both_rotor_profiles(offset):
    # Wu & Chi Fig. 9: each datum point's clearance placed on the female profile (its contact
    # point turned into the female frame) and on the male (across the transverse gap, turned into
    # the male frame). Both must lie on the cut outlines given as input: female within 1 um, male
    # within 1.5 um (which checks the normal-to-transverse conversion on the offset flank: 50 um
    # transverse there), over a contact line from z = 0 to the rotor length.
    mc = clearance(male(), female(offset))
    dist = mc.distribution()
    sel = np.zeros(len(mc.clearance), dtype=bool)
    for part in regions(mc).values():
        sel |= part
    sel &= dist["in_contact"] > 0
    f = np.column_stack([dist["female_x"], dist["female_y"]])[sel]
    m = np.column_stack([dist["male_x"], dist["male_y"]])[sel]
    assert distance_to_line(f, shapely.LinearRing(female(offset))).max() < 1e-3
    assert distance_to_line(m, shapely.LinearRing(male())).max() < 1.5e-3
    z = dist["z"][dist["in_contact"] > 0]
    assert z.min() == pytest.approx(0.0, abs=1e-9) and z.max() <= 190.0 + 1e-9


def test_a_smooth_one_flank_clearance_from_a_table_comes_back(tmp_path, capsys):
    # A smooth correction of the sealing flank only: 30 um sin^2 over the falling flank's rack x
    # (rack heights -6.9 .. 6.6 mm), zero elsewhere, given as --clearance-table and measured back by
    # `clearance --contact as-given` at each datum point within 3 um of the table's value there.
    rack, _ = PAIR.rack.sample(0.01)
    write_points(tmp_path / "rack.csv", np.vstack([rack, rack[:1] + [PAIR.rack.period, 0.0]]))
    falling = next(g for kind, g in PAIR.rack.pieces() if kind == "line" and g[1][1] < g[0][1])
    x0, x1 = falling[0][0], falling[1][0]  # the falling flank's straight part, in rack x

    def table(x: np.ndarray) -> np.ndarray:
        u = np.clip((np.mod(x, PAIR.rack.period) - x0) / (x1 - x0), 0.0, 1.0)
        return 0.03 * np.sin(np.pi * u) ** 2

    xs = np.linspace(0.0, PAIR.rack.period, 2001)
    rows = "x,clearance\n" + "".join(f"{x:.9f},{c:.9f}\n" for x, c in zip(xs, table(xs), strict=True))
    (tmp_path / "t.csv").write_text(rows)
    dims = ["--male-teeth", "4", "--female-teeth", "6", "--center-distance", "100", "--lead", str(LEAD)]
    dims += [f"--{k.replace('_', '-')}={v}" for k, v in PAIR.radii().items()]
    out = ["--male-csv", str(tmp_path / "m.csv"), "--female-csv", str(tmp_path / "f.csv")]
    capsys.readouterr()
    assert (
        main(["rotor", "--rack-points", str(tmp_path / "rack.csv"), *dims, "--clearance-table", str(tmp_path / "t.csv"), *out])
        == 0
    )
    load = lambda name: np.loadtxt(tmp_path / name, delimiter=",", comments="#", skiprows=2)  # noqa: E731
    mc = clearance(load("m.csv"), load("f.csv"), contact="as-given")
    sel = regions(mc)
    x_transverse = mc.female_rack.points[:, 0]
    for name in ("falling", "rising"):
        np.testing.assert_allclose(mc.clearance[sel[name]], table(x_transverse[sel[name]]), atol=3e-3)
    assert mc.clearance[sel["falling"]].max() > 0.025  # the bump is there

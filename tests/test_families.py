"""The profile families of Rinder's paper (sec. 1.2, Figs. 1-6), each checked against what the
paper says of it and against methods outside the engine: shapely booleans for conjugacy, the racks
derived back from both rotors, closed forms for the contact ratio, and an independent quadrature
of the spatial blow-hole."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
import shapely
from scipy import integrate
from shapely import affinity

from hob.rack import rack_deviation, rotor_rack
from hob.verdict import judge
from rotorcad.cli.common import load_rotor_design
from rotorcad.errors import DesignError
from rotorcad.meshing import MeshingAnalysis
from rotorcad.roles import Flank, PieceRole
from rotorcad.rotor_build import design_summary
from rotorcad.rotor_families import FAMILIES, build_family
from rotorcad.rotor_pair import RotorPair

SAMPLES = Path(__file__).resolve().parents[1] / "samples"
A = 116.0
R1W, R2W = A * 5 / 11, A * 6 / 11
# 5/6, a = 116 mm, male all addendum and female all dedendum (Lysholm, SRM)
PAIR_SRM = RotorPair(5, 6, A, 63.0, R1W, R2W, A - 63.0)
PAIR_NARROW = RotorPair(5, 6, A, 70.0, R1W, R2W, A - 70.0)
PAIR_56 = RotorPair(5, 6, A, 63.0, 45.0, 71.0, 53.0)
PAIR_46 = RotorPair(4, 6, 100.0, 54.0, 40.0, 60.0, 46.0)
# Wu & Chi Table 1, the N4 pair: 5/6, a = 82 mm, outer/inner radii 57.99/35.66 (male) and
# 46.34/24.01 mm (female), pitch helix angle 46 deg, screw length 162.079 mm
N4_LEAD = 2 * np.pi * (82.0 * 5 / 11) / np.tan(np.radians(46.0))
PAIR_N4 = RotorPair(5, 6, 82.0, 57.99, 35.66, 46.34, 24.01, lead=N4_LEAD, length=162.079)

EVERY_FAMILY = [
    ("krigar", PAIR_46, {}),
    ("krigar", PAIR_SRM, {"tip_land": 2.0}),
    ("lysholm", PAIR_SRM, {}),
    ("srm-symmetric", PAIR_SRM, {}),
    ("srm-asymmetric", PAIR_SRM, {}),
    ("srm-asymmetric", PAIR_46, {"seal_stop": 0.8, "tip_land": 1.0}),
    ("srm-b", PAIR_SRM, {}),
    ("srm-b", PAIR_SRM, {"driving_rounding": 0.3}),
    ("narrow-tip", PAIR_NARROW, {}),
    ("rack-involute", PAIR_56, {"tip_rounding": 1.4, "root_rounding": 1.0, "lobe_width": 0.6}),
    ("n-rack", PAIR_N4, {}),
    ("n-rack", PAIR_N4, {"driving_width": 1.1, "driving_exponent_along": 2.5, "tip_land": 1.5, "male_tip_rounding": 0.0}),
    ("n-rack", PAIR_46, {"driving_exponent_across": 3.0, "female_tip_rounding": 0.2}),
]


def overlap(rotors, phase_deg: float = 0.0, steps: int = 13) -> float:
    """Largest intersection area (mm^2) of the male and female sections turned together over one
    male lobe pitch, the female turned ``phase_deg`` off its mesh phase: shapely booleans only."""
    pair = rotors.pair
    male, female = rotors.section("male"), rotors.section("female")
    worst = 0.0
    for phi in np.linspace(0.0, 2 * np.pi / pair.male_teeth, steps)[:-1]:
        m = affinity.rotate(male, phi, origin=(0, 0), use_radians=True)
        f = affinity.rotate(female, -np.degrees(phi) * pair.male_teeth / pair.female_teeth + phase_deg, origin=(0, 0))
        worst = max(worst, m.intersection(affinity.translate(f, pair.center_distance, 0)).area)
    return worst


def test_every_family_has_a_builder():
    assert {f for f, _, _ in EVERY_FAMILY} == set(FAMILIES)


@pytest.mark.parametrize("family,pair,params", EVERY_FAMILY)
def test_every_family_is_conjugate_and_gives_its_rack_back_from_both_rotors(family, pair, params):
    # Conjugate: the sections touch but never overlap over a lobe pitch (shapely, 1 um chords on
    # 60 mm rotors: below 1e-3 mm^2), while a female one degree off its phase overlaps clearly.
    # The racks derived back from the male and from the female agree within 0.1 um (Wu & Chi
    # sec. 2: the rack of either rotor of a rack-generated pair is that rack).
    rotors = build_family(pair, family, params)
    assert overlap(rotors) < 1e-3
    assert max(overlap(rotors, -1.0, 7), overlap(rotors, 1.0, 7)) > 0.5
    assert rack_deviation(rotors) < 1e-4


@pytest.mark.parametrize("family,pair,params", EVERY_FAMILY)
def test_flute_areas_match_shapely_on_a_finer_outline(family, pair, params):
    # A1 = (pi r1t^2 - section) / z1: the analysis at its 1 um outline against shapely's
    # difference of a 4096-segment bore disk and the outline resampled at 0.2 um. Chords of at most
    # 1 um sagitta move the area by at most perimeter x 1 um.
    rotors = build_family(pair, family, params)
    ma = MeshingAnalysis(rotors)
    for rotor, teeth, tip, value in (
        ("male", pair.male_teeth, pair.male_tip_radius, ma.male_flute_area),
        ("female", pair.female_teeth, pair.female_tip_radius, ma.female_flute_area),
    ):
        fine = rotors.section(rotor, tolerance=2e-4)
        bore = shapely.Point(0, 0).buffer(tip, quad_segs=4096)
        assert value == pytest.approx(bore.difference(fine).area / teeth, abs=fine.length * 1e-3 / teeth)


# ---- Krigar (Fig. 1) ------------------------------------------------------------------------


def test_krigar_is_tight_but_has_no_geometric_contact_anywhere():
    # Rinder Fig. 1: only point-generated flanks, closed meshline up to the tip circles' crossing,
    # no blow-hole; no flank part with a common tangent, so not runnable: cusps on both rotors.
    ma = MeshingAnalysis(build_family(PAIR_46, "krigar", {}))
    assert ma.meshline_closed and ma.blow_hole_area == 0.0 and ma.spatial_blow_hole.area == 0.0
    # both ends of the meshline reach the cusps: the upper and the lower one within 1 um
    k = PAIR_46.housing_cusp
    for cusp in (k, k * [1, -1]):
        assert np.hypot(*(ma.meshline - cusp).T).min() < 1e-3
    assert {d.rotor for d in ma.defects if d.kind == "cusp"} == {"male", "female"}
    for report in ma.flanks.values():
        assert report.meshline_length > 10.0 and report.geometric_share == 0.0
        assert not report.runs_without_timing_gears
    reasons = ma.running_reasons
    assert len(reasons) == 2 and all("no geometric contact" in r for r in reasons)
    # every rack piece is a corner's path but the root land (a line on the pitch line, d1 = 0)
    curves = [p for p in ma.rotors.rack if p.kind is PieceRole.CURVE]
    assert len(curves) == 1
    pts, _ = curves[0].curve.evaluate(np.linspace(curves[0].curve.s0, curves[0].curve.s1, 5))
    np.testing.assert_allclose(pts[:, 0], PAIR_46.male_pitch_radius, atol=1e-9)


def test_krigar_is_symmetric():
    # Mirror symmetry of the male lobe about its axis (Rinder: "die Verzahnung ist symmetrisch"):
    # the section equals its mirror image about the x axis (shapely symmetric difference).
    rotors = build_family(PAIR_46, "krigar", {})
    male = rotors.section("male")
    mirrored = affinity.scale(male, 1.0, -1.0, origin=(0, 0))
    assert male.symmetric_difference(mirrored).area < 1e-3


# ---- the asymmetric SRM profile (Fig. 4) and SRM-B ------------------------------------------------


def test_asymmetric_srm_has_a_small_blow_hole_against_the_symmetric_one():
    # Rinder Fig. 3 "relativ großes Blasloch" against Fig. 4 "ein kleines Blasloch", at the same
    # tooth counts, centre distance and radii; and the two samples as shipped.
    sym = MeshingAnalysis(build_family(PAIR_SRM, "srm-symmetric", {}))
    asym = MeshingAnalysis(build_family(PAIR_SRM, "srm-asymmetric", {}))
    assert not asym.meshline_closed
    assert 0.0 < asym.blow_hole_area < sym.blow_hole_area / 10
    samples = {
        name: design_summary(_toml(SAMPLES / f"{name}.toml"), SAMPLES)["blow_hole_area"]
        for name in ("srm_symmetric_4_6", "srm_asymmetric_5_6", "srm_b_5_6")
    }
    assert samples["srm_asymmetric_5_6"] < samples["srm_symmetric_4_6"] / 3
    assert samples["srm_b_5_6"] < samples["srm_symmetric_4_6"] / 3


def test_asymmetric_srm_sealing_flank_has_a_short_part_of_geometric_contact():
    # The straight female flank gives the sealing flank geometric contact over a short part; the
    # rest stays point-generated (Lysholm's sealing flank has none).
    lysholm = MeshingAnalysis(build_family(PAIR_SRM, "lysholm", {}))
    asym = MeshingAnalysis(build_family(PAIR_SRM, "srm-asymmetric", {}))
    assert lysholm.flanks[Flank.SEALING].geometric_share == 0.0
    assert 0.05 < asym.flanks[Flank.SEALING].geometric_share < 0.5


def test_srm_b_driving_flank_runs_and_its_contact_ratio_is_the_closed_form():
    # SRM-B: the driving arc (radius R = h1 + e, centre e below the pitch line) touches the point
    # whose normal makes the angle theta with the pitch-line normal at the rack shift e tan(theta);
    # from its top (theta = 0) to its foot on the pitch line (cos theta = e / R) that is
    # sqrt(R^2 - e^2), so eps = sqrt(R^2 - e^2) / p. SRM-A's arc centred on C touches at one instant:
    # eps = 0 (Rinder on Lysholm's flank: "nur infinitesimale Stirnüberdeckung").
    a_deg = 30.0
    b = MeshingAnalysis(build_family(PAIR_SRM, "srm-b", {"driving_foot_angle_deg": a_deg}))
    a = MeshingAnalysis(build_family(PAIR_SRM, "srm-asymmetric", {}))
    h1 = PAIR_SRM.male_addendum
    sa = np.sin(np.radians(a_deg))
    e = h1 * sa / (1 - sa)
    r = h1 + e
    expected = np.sqrt(r * r - e * e) / PAIR_SRM.rack_period
    drive = b.flanks[Flank.DRIVING]
    assert drive.transverse_contact_ratio == pytest.approx(expected, rel=2e-3)
    assert a.flanks[Flank.DRIVING].transverse_contact_ratio == 0.0
    # no cusp, jamming or slipping on SRM-B's driving flank; geometric contact on all of it
    assert drive.geometric_share == 1.0 and drive.runs_without_timing_gears
    assert not [d for d in b.defects if d.role is Flank.DRIVING]
    # a shorter meshline than SRM-A's (Rinder: "weitere Verkürzung der Eingriffslinienlänge")
    assert b.contact_line_length < a.contact_line_length
    assert drive.meshline_length < a.flanks[Flank.DRIVING].meshline_length


def test_srm_b_hobs_badly_and_says_why():
    # Rinder: SRM-B "ist gut ohne Koppelgetriebe lauffähig ..., hat aber den Nachteil, daß es
    # schlecht wälzfräsbar ist". The verdict through the rack names the reasons.
    rotors = build_family(PAIR_SRM, "srm-b", {})
    verdicts = {side: judge(rotor_rack(rotors, side)) for side in ("male", "female")}
    assert not any(v.hobbable for v in verdicts.values())
    text = " ".join(r for v in verdicts.values() for r in v.reasons)
    assert "flank angle" in text and "side relief" in text


@pytest.mark.parametrize("family", ["srm-asymmetric", "srm-b", "narrow-tip", "krigar"])
def test_point_generated_families_refuse_a_female_addendum(family):
    with pytest.raises(DesignError, match="male_root_radius"):
        build_family(PAIR_56, family, {})


# ---- narrow-tip (Fig. 5) ----------------------------------------------------------------------


def _female_share_on_pitch_circle(rotors) -> float:
    """Share of the female pitch circle (0.3 mm inside it) that is female material (shapely)."""
    ring = shapely.Point(0, 0).buffer(rotors.pair.female_pitch_radius - 0.3, quad_segs=2048).exterior
    return rotors.section("female").intersection(ring).length / ring.length


def test_narrow_tip_has_thin_female_teeth_and_a_short_driving_meshline():
    narrow = build_family(PAIR_NARROW, "narrow-tip", {})
    srm = build_family(PAIR_SRM, "srm-asymmetric", {})
    assert _female_share_on_pitch_circle(narrow) < 0.3 < _female_share_on_pitch_circle(srm)
    # deep flutes: the female flute is deeper than SRM's (female root radius from the section)
    female = narrow.section("female")
    depth = narrow.pair.female_tip_radius - female.exterior.distance(shapely.Point(0, 0))
    assert depth > 17.0
    ma = MeshingAnalysis(narrow)
    drive, seal = ma.flanks[Flank.DRIVING], ma.flanks[Flank.SEALING]
    assert drive.runs_without_timing_gears and drive.meshline_length < seal.meshline_length / 2
    assert 0.0 < seal.geometric_share < 0.5  # long point-generated sealing parts
    assert 0.0 < ma.blow_hole_area < 5.0


@pytest.mark.parametrize("teeth", [2, 8])
def test_narrow_tip_lobe_counts_are_those_rinder_names(teeth):
    pair = RotorPair(teeth, teeth + 1, A, 63.0, A * teeth / (2 * teeth + 1), A * (teeth + 1) / (2 * teeth + 1), A - 63.0)
    with pytest.raises(DesignError, match="male_teeth"):
        build_family(pair, "narrow-tip", {})


# ---- the spatial blow-hole ------------------------------------------------------------------------


@pytest.mark.parametrize(
    "family,pair,params", [("srm-symmetric", PAIR_46, {}), ("srm-asymmetric", PAIR_SRM, {}), ("n-rack", PAIR_N4, {})]
)
def test_spatial_blow_hole_lies_on_the_tips_and_the_cusp_and_its_area_is_independent(family, pair, params):
    ma = MeshingAnalysis(build_family(pair, family, params))
    hole = ma.spatial_blow_hole
    k = ma.cusp
    o2 = np.array([pair.center_distance, 0.0])
    # its three bounding curves: on the male tip cylinder, the female tip cylinder, the cusp line
    np.testing.assert_allclose(np.hypot(*hole.male_tip[:, :2].T), pair.male_tip_radius, atol=1e-9)
    np.testing.assert_allclose(np.hypot(*(hole.female_tip[:, :2] - o2).T), pair.female_tip_radius, atol=1e-9)
    np.testing.assert_allclose(hole.cusp_line[:, :2], np.broadcast_to(k, hole.cusp_line[:, :2].shape), atol=1e-12)
    # its projection is the projected blow-hole
    assert hole.projected_area == pytest.approx(ma.blow_hole_area, rel=1e-3)
    # the tips turn along the rotors with their leads: each tip curve's angle is linear in z with
    # slope 2 pi / h1 (male) and -2 pi / h2 (female)
    for pts, centre, lead in ((hole.male_tip, np.zeros(2), pair.lead), (hole.female_tip, o2, -pair.female_lead)):
        ang = np.unwrap(np.arctan2(pts[:, 1] - centre[1], pts[:, 0] - centre[0]))
        slope = np.polyfit(pts[:, 2], ang, 1)[0]
        assert slope == pytest.approx(2 * np.pi / lead, rel=1e-9)
    # area: the cone from the apex, by adaptive quadrature of |(B - A) x B'| / 2 over the exact
    # boundary (helices with their analytic derivatives), against the code's triangle fan
    apex = hole.boundary[0]
    total = 0.0
    for pts, centre, radius, lead in (
        (hole.male_tip, np.zeros(2), pair.male_tip_radius, pair.lead),
        (hole.female_tip, o2, pair.female_tip_radius, -pair.female_lead),
    ):
        z0, z1 = pts[0, 2], pts[-1, 2]
        phi0 = np.arctan2(pts[0, 1] - centre[1], pts[0, 0] - centre[0])
        w = 2 * np.pi / lead

        def helix(z, centre=centre, radius=radius, w=w, phi0=phi0, z0=z0):
            ang = phi0 + w * (z - z0)
            return np.array([centre[0] + radius * np.cos(ang), centre[1] + radius * np.sin(ang), z])

        def d_helix(z, radius=radius, w=w, phi0=phi0, z0=z0):
            ang = phi0 + w * (z - z0)
            return np.array([-radius * w * np.sin(ang), radius * w * np.cos(ang), 1.0])

        total += integrate.quad(
            lambda z: 0.5 * np.linalg.norm(np.cross(helix(z) - apex, d_helix(z))), min(z0, z1), max(z0, z1), limit=200
        )[0]
        # the radial piece from the apex to the helix start lies in the plane z = z_apex: a triangle
        # with the apex of zero area (collinear), nothing to add
    zc = hole.cusp_line[:, 2]
    kk = np.array([k[0], k[1], 0.0])
    d = kk - apex
    total += integrate.quad(
        lambda z: 0.5 * np.linalg.norm(np.cross(d + [0, 0, z], [0, 0, 1.0])), min(zc[0], zc[-1]), max(zc[0], zc[-1])
    )[0]
    assert hole.area == pytest.approx(total, rel=1e-2)
    assert hole.area > hole.projected_area


# ---- Stosic's N rack -------------------------------------------------------------------------------


def test_n_rack_sealing_tips_are_circles_on_the_rotors_touching_with_their_normal_through_c():
    # Stosic's N rack carries two rotor-generated pieces: the rack images of a male and a female
    # sealing tip circle. The engine generates the rotors back from those rack pieces; the result
    # must be the circles themselves (closed form: centre at R - r on the tip circle's radius,
    # radius r), tangent to the tip circles, and the two circles must touch at one point K whose
    # common normal runs through the pitch point C (the construction's defining property).
    pair = PAIR_N4
    h1 = pair.male_addendum
    rm, rf = 0.05 * h1, 0.1 * h1
    rotors = build_family(pair, "n-rack", {})
    male = dict((name, curve) for name, curve, _ in rotors.male_pieces)["sealing tip circle"]
    female = dict((name, curve) for name, curve, _ in rotors.female_pieces)["sealing tip circle"]
    o2 = np.array([pair.center_distance, 0.0])
    for curve, tip, r in ((male, pair.male_tip_radius, rm), (female, pair.female_tip_radius, rf)):  # own frames
        pts = curve.evaluate(np.linspace(curve.s0, curve.s1, 201))[0]
        # the circle's centre: least squares on the points (Kasa fit), independent of the builder
        A = np.c_[2 * pts, np.ones(len(pts))]
        cx, cy, c0 = np.linalg.lstsq(A, (pts**2).sum(axis=1), rcond=None)[0]
        radius = np.sqrt(c0 + cx**2 + cy**2)
        assert radius == pytest.approx(r, abs=1e-7)
        assert np.hypot(cx, cy) == pytest.approx(tip - r, abs=1e-7)
        assert np.abs(np.hypot(*(pts - [cx, cy]).T) - r).max() < 1e-7
        # one end on the tip circle (tangent there), the rest inside it
        assert np.hypot(*pts.T).max() == pytest.approx(tip, abs=1e-7)
    # the two circles touch at the rack's junction H: at the instant they touch, the centres and
    # the contact point are collinear with C
    from rotorcad.families.n_rack import sealing_contact

    k = sealing_contact(pair, rm, rf)
    c = np.array([pair.male_pitch_radius, 0.0])
    u = (k - c) / np.hypot(*(k - c))
    assert np.hypot(*(k - rm * u)) == pytest.approx(pair.male_tip_radius - rm, abs=1e-9)
    assert np.hypot(*(k + rf * u - o2)) == pytest.approx(pair.female_tip_radius - rf, abs=1e-9)


def test_n4_sample_has_the_published_dimensions_and_reports_its_blow_hole_and_contact_line():
    # Wu & Chi Table 1 (the N4 rotors): the sample carries those dimensions; its pitch helix angle
    # atan(2 pi r1w / lead) is 46.0 deg and its wrap angle follows from the length.
    d = load_rotor_design(SAMPLES / "n_rack_5_6.toml")
    pair = RotorPair(**d["pair"])
    assert (pair.male_teeth, pair.female_teeth, pair.center_distance) == (5, 6, 82.0)
    assert (pair.male_tip_radius, pair.male_root_radius) == (57.99, 35.66)
    assert (pair.female_tip_radius, pair.female_root_radius) == (46.34, 24.01)
    assert pair.length == 162.079
    assert np.degrees(np.arctan(2 * np.pi * pair.male_pitch_radius / pair.lead)) == pytest.approx(46.0, abs=1e-4)
    summary = design_summary(_toml(SAMPLES / "n_rack_5_6.toml"), SAMPLES)
    # a small blow-hole that opens because the tips are rounded; the projected one against the
    # curved triangle it bounds (shapely: the bores' lens corner beyond the meshline end)
    ma = MeshingAnalysis(build_family(pair, d["family"], d["params"]))
    assert 0 < summary["blow_hole_area"] < 5.0
    assert summary["blow_hole_spatial"]["area"] > summary["blow_hole_area"]
    # the meshline ends where the two sealing tip circles touch: K with |K - r_m u| = R1 - r_m,
    # |K + r_f u - O2| = R2 - r_f, u = (K - C)/|K - C| (solved here by scipy from the cusp); the
    # blow-hole is the curved triangle between K, the two tip circles and their cusp (Rinder
    # 2.2.2), built here with shapely as the bores' lens corner beyond the radial lines through K
    from scipy import optimize

    h1, o2 = pair.male_addendum, np.array([pair.center_distance, 0.0])
    rm, rf = d["params"]["male_tip_rounding"] * h1, d["params"]["female_tip_rounding"] * h1
    c = np.array([pair.male_pitch_radius, 0.0])

    def tangency(k):
        u = (k - c) / np.linalg.norm(k - c)
        male_gap = np.linalg.norm(k - rm * u) - (pair.male_tip_radius - rm)
        return [male_gap, np.linalg.norm(k + rf * u - o2) - (pair.female_tip_radius - rf)]

    k = optimize.fsolve(tangency, pair.housing_cusp, xtol=1e-13)
    np.testing.assert_allclose(summary["blow_hole_spatial"]["apex"][:2], k, atol=1e-6)
    cusp = pair.housing_cusp
    a1, a2 = np.arctan2(k[1], k[0]), np.arctan2(cusp[1], cusp[0])  # male tip arc from K's radial line to the cusp
    b1, b2 = np.arctan2(cusp[1], cusp[0] - o2[0]), np.arctan2(k[1], k[0] - o2[0])  # female tip arc
    male_arc = pair.male_tip_radius * np.column_stack([np.cos(t := np.linspace(a1, a2, 2000)), np.sin(t)])
    female_arc = o2 + pair.female_tip_radius * np.column_stack([np.cos(t := np.linspace(b1, b2, 2000)), np.sin(t)])
    triangle = shapely.Polygon(np.vstack([[k], male_arc, female_arc, [k]]))
    assert summary["blow_hole_area"] == pytest.approx(triangle.area, rel=1e-4)
    assert summary["contact_line_length"] == pytest.approx(ma.contact_line_length)
    # the contact line is the meshline lifted along the rotors: longer than its projection
    planar = np.linalg.norm(np.diff(ma.meshline, axis=0), axis=1).sum()
    assert summary["contact_line_length"] > planar
    # geometric contact on both flanks: it runs without timing gears (Stosic's aim for the N rotors)
    assert summary["runs_without_timing_gears"]
    # the rounded tips are what opens the blow-hole: sharp tips (radii to 0) close it
    sharper = build_family(pair, "n-rack", {"male_tip_rounding": 0.0, "female_tip_rounding": 0.08})
    assert MeshingAnalysis(sharper).blow_hole_area < summary["blow_hole_area"]


def test_n_rack_refuses_a_female_tip_circle_centred_outside_the_female_pitch_circle():
    # with r_f <= d1 the female circle's part nearest its tip has normals that miss the female
    # pitch circle: no generating position, and the rotors would overlap
    d1 = PAIR_N4.male_dedendum
    with pytest.raises(DesignError, match="female_tip_rounding"):
        build_family(PAIR_N4, "n-rack", {"female_tip_rounding": 0.95 * d1 / PAIR_N4.male_addendum})


def _toml(path: Path) -> dict:
    import tomllib

    with path.open("rb") as f:
        return tomllib.load(f)


# ---- Rinder's comparison (sec. 3.2) -----------------------------------------------------------------


def test_rinder_comparison_in_the_readme_is_what_rotorcad_computes():
    # The README's table of extremes is the script's output for the shipped samples (not stale),
    # and the narrow-tip's largest sliding velocity lies where Rinder puts it: at the male tip, on
    # the sealing flank, at about -25 deg in his count (+25 deg here, the sense reversed), within 5 deg.
    import importlib.util

    spec = importlib.util.spec_from_file_location("compare", SAMPLES / "rinder_comparison" / "compare.py")
    compare = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(compare)
    readme = (SAMPLES.parent / "README.md").read_text()
    assert compare.table() in readme
    narrow = compare.extremes("narrow_tip_5_6")["largest sliding velocity"]
    assert narrow["flank"] == "sealing" and narrow["place"].startswith("male tip")
    assert abs(narrow["angle_deg"] + 25.0) < 5.0


def test_a_rack_that_undercuts_its_rotor_is_refused(capsys, tmp_path):
    # A driving arc three tenths of h1 wide curves more sharply than the male can follow: the
    # generated flank loops, and the male made valid (shapely) stops 3.7 mm short of its 57.99 mm
    # tip radius (found by a new user: exit 0 and a blow-hole drawn from the nominal tip circle).
    from rotorcad.cli.main import main
    from rotorcad.families.n_rack import n_rack

    narrow = n_rack(PAIR_N4, driving_width=0.3)  # the builder itself, unchecked
    reach = np.hypot(*np.asarray(narrow.section("male").exterior.coords).T).max()
    assert reach < PAIR_N4.male_tip_radius - 3.0
    with pytest.raises(DesignError, match=r"\[profile\] parameters of the n-rack family"):
        build_family(PAIR_N4, "n-rack", {"driving_width": 0.3})  # the Python API refuses it too
    design = tmp_path / "narrow.toml"
    design.write_text((SAMPLES / "n_rack_5_6.toml").read_text().replace("driving_width = 1.25", "driving_width = 0.3"))
    capsys.readouterr()
    assert main(["rotor", str(design), "--json"]) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and "[profile]" in err and "57.99" in err and f"{reach:.4g}" in err

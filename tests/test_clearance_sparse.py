"""The clearance from sparse and scattered points: the racks' normals, the gaps' accuracy (issue 22).

References, not produced by the code under test: closed forms (straight racks), and the brute-force
closest approach of the cut outlines of an independent pair over 1500 mesh positions
(``independent_pairs.closest_approach``).
"""

from __future__ import annotations

import functools

import numpy as np
import pytest
from independent_pairs import arc_flank_5_6, closest_approach, cut_rotor, resample, trapezoid_4_6, true_gap

from rotorcad.clearance import ClearanceZone, MeshingClearance, normal_clearance, pair_quality
from rotorcad.measured.fit import close_smoothing
from rotorcad.rotor_pair import RotorPair
from rotorcad.rotor_points import lobe_pieces


def test_a_normal_does_not_cut_the_seam_between_a_rack_and_its_next_period():
    # closed form: the rack y = 0 over x in [0, 10], and its next period's copy starting 0.7 mm back
    # (x = 9.3, y = -0.2: a rack longer than its period, as the N-rack male at 80 points a lobe).
    # The polyline's seam from (10, 0) back to (9.3, -0.2) runs against both its tangents: no piece of
    # a rack. The datum at (9.9, -0.03), normal +y, is 0.03 mm from the rack (it read 0.0014 mm off
    # the seam, and -30 um for +30 um on the N-rack)
    x = np.linspace(0.0, 10.0, 101)
    first = np.column_stack([x, np.zeros_like(x)])
    second = np.column_stack([x[:30] + 9.3, np.full(30, -0.2)])
    compared = np.vstack([first, second])
    tangents = np.tile([1.0, 0.0], (len(compared), 1))
    delta = normal_clearance(np.array([[9.9, -0.03]]), np.array([[0.0, 1.0]]), compared, tangents)
    assert abs(delta[0] - 0.03) < 1e-12


@functools.cache
def sharp_pair_at_80():
    """The 4/6 trapezoid pair's cut outlines (sharp tips cut back by flats) as exact points at 80 a
    lobe, their clearance (straight rotors, contact as given), and the brute-force closest approach
    at the female points of every 10th gap row."""
    rack_pair = trapezoid_4_6()
    male, female = cut_rotor(rack_pair, "male"), cut_rotor(rack_pair, "female")

    def at(ring, teeth):
        return resample(ring, float(np.hypot(*np.diff(np.vstack([ring, ring[:1]]), axis=0).T).sum()) / teeth / 80)

    m, f = at(male, 4), at(female, 6)
    pair = RotorPair(4, 6, 100.0, **rack_pair.radii(), lead=1e5, length=1e5, strict=False)
    mc = MeshingClearance(
        pair,
        lobe_pieces(pair, m, "male", roundings=True),
        lobe_pieces(pair, f, "female", roundings=True),
        **pair_quality(m, f, (4, 6)),
    )
    d = mc.distribution()
    rows = np.flatnonzero(mc.zones == ClearanceZone.GAP)[::10]
    truth = closest_approach(rack_pair, np.column_stack([d["female_x"], d["female_y"]])[rows], male, positions=1500)
    return mc, rows, truth


def test_the_gaps_from_80_points_a_lobe_are_within_their_stated_accuracy():
    # the gap of the parts that never touch (the female root below the sharp male tip, whose corner
    # falls between points 1 mm apart) against the brute-force closest approach of the cut outlines:
    # within gap_accuracy (the contact zone's accuracy and the triangle in which the corner may lie)
    mc, rows, truth = sharp_pair_at_80()
    s = mc.summary()
    assert len(rows) > 5
    assert s["gap_accuracy"] >= s["accuracy"]
    assert np.max(np.abs(mc.gap[rows] - truth)) <= s["gap_accuracy"]


def test_the_closer_fit_of_300_points_a_lobe_with_2_um_scatter_is_within_5_um():
    # issue 22 item 2 on the 5/6 arc-flank pair (its male undercut, sharp tips), straight rotors, the
    # seed whose contact zone read 5.71 um off with n sigma^2: rotorcad clearance fits the points with
    # (n - sqrt(2 n)) sigma^2 (fit.close_smoothing), which follows the male's straight flank beside its
    # root fillet. Reference: the brute-force closest approach of the cut outlines at the same female
    # points (independent_pairs.true_gap), every 6th contact-zone row and the 20 largest
    rack_pair = arc_flank_5_6()
    male, female = cut_rotor(rack_pair, "male"), cut_rotor(rack_pair, "female")

    def at(ring, teeth, seed):
        spacing = float(np.hypot(*np.diff(np.vstack([ring, ring[:1]]), axis=0).T).sum()) / teeth / 300
        return resample(ring, spacing, 2e-3, seed=seed)

    m, f = at(male, 5, 1), at(female, 6, 101)
    pair = RotorPair(5, 6, 100.0, **rack_pair.radii(), lead=1e5, length=1e5, strict=False)
    mc = MeshingClearance(
        pair,
        lobe_pieces(pair, m, "male", close_smoothing, roundings=True),
        lobe_pieces(pair, f, "female", close_smoothing, roundings=True),
        **pair_quality(m, f, (5, 6)),
    )
    s = mc.summary()
    d = mc.distribution()
    on = np.flatnonzero(mc.contact_zone)
    pick = on[np.union1d(np.arange(0, len(on), 6), np.argsort(-np.abs(mc.clearance[on]))[:20])]
    truth = true_gap(rack_pair, female, male, np.column_stack([d["female_x"], d["female_y"]])[pick])
    worst = float(np.abs(mc.clearance[pick] - truth).max())
    assert worst < 5e-3  # 4.28 um measured (5.71 with n sigma^2)
    assert worst <= s["accuracy"]
    assert abs(s["female_rack_shift"]) < 2e-3  # truth 0: both cut by one rack at one phase
    assert s["min_normal_clearance"] > -s["accuracy"]  # no interference flag


@pytest.mark.xfail(
    strict=True,
    reason="known defect (issue 22 item 2, README's 6.1 um): the male's smoothing cubic misses its outline by 4-5 um "
    "one spacing past the curvature step where its root fillet (curvature -0.16 /mm) meets its convex flank "
    "(+0.17 /mm) at r 35.07 mm: a ringing of about +-2 um on average over 8 seeds, which the worst contact-zone "
    "rows (the female 0.5 mm below its tip) face at seeds 1, 3, 4. One run's points do not show that step above "
    "their scatter (a double knot's gain 10-26 sigma^2 there, 6-19 elsewhere, branch root-land)",
)
def test_the_4_6_pair_at_300_points_a_lobe_with_2_um_is_within_5_um():
    # issue 22 item 2 on the 4/6 trapezoid pair (tests/independent_pairs.trapezoid_4_6: root lands, sharp tips),
    # straight rotors, seed 1 (the female seed 101), as bench_clearance_accuracy reads it: 6.10 um measured at
    # the female r 67.54 mm, facing the male at r 35.30 (the male's fit 5.1 um inside its cut outline, the
    # female's 1.0, the alignment 0.6). Reference: the brute-force closest approach of the cut outlines at the
    # same female points (independent_pairs.true_gap), every 6th contact-zone row and the 20 largest
    rack_pair = trapezoid_4_6()
    male, female = cut_rotor(rack_pair, "male"), cut_rotor(rack_pair, "female")
    m = resample(male, per_lobe_300(male, 4), 2e-3, seed=1)
    f = resample(female, per_lobe_300(female, 6), 2e-3, seed=101)
    pair = RotorPair(4, 6, 100.0, **rack_pair.radii(), lead=1e5, length=1e5, strict=False)
    mc = MeshingClearance(
        pair,
        lobe_pieces(pair, m, "male", close_smoothing, roundings=True),
        lobe_pieces(pair, f, "female", close_smoothing, roundings=True),
        **pair_quality(m, f, (4, 6)),
    )
    d = mc.distribution()
    on = np.flatnonzero(mc.contact_zone)
    pick = on[np.union1d(np.arange(0, len(on), 6), np.argsort(-np.abs(mc.clearance[on]))[:20])]
    truth = true_gap(rack_pair, female, male, np.column_stack([d["female_x"], d["female_y"]])[pick])
    assert float(np.abs(mc.clearance[pick] - truth).max()) < 5e-3  # 6.10 um measured


def per_lobe_300(ring: np.ndarray, teeth: int) -> float:
    """The spacing of 300 points a lobe along the closed ring, mm."""
    return float(np.hypot(*np.diff(np.vstack([ring, ring[:1]]), axis=0).T).sum()) / teeth / 300


@pytest.mark.xfail(
    strict=True,
    reason="known defect (issue 22 item 2): the smoothing cubic beside a land rings where the land meets a root "
    "rounding, its end 3.4-7.1 um inside the male (a bias, -4.5 um over 8 seeds). Holding it on the land's end fits "
    "the outline there (least squares, branch clearance-46: 2.4-3.9 um; FITPACK's smoothing kept, branch root-land: "
    "at most 3.6 um within 0.5 mm of the land) but not the clearance, whose worst rows face another curvature step "
    "(test_the_4_6_pair_at_300_points_a_lobe_with_2_um_is_within_5_um)",
)
@pytest.mark.parametrize("seed", [1, 2, 4])
def test_a_scattered_fit_meets_its_root_land_on_the_cut_outline(seed):
    # the 4/6 male's 1.5 mm root roundings meet its root land (tests/independent_pairs.trapezoid_4_6).
    # At 300 points a lobe with 2 um scatter the free smoothing cubic rings there: its end beside the land
    # 6.97 / 5.09 / 7.10 um inside the male (seeds 1, 2, 4). (The clearance's worst row at seed 1 does not
    # face this join but the male at r 35.30: test_the_4_6_pair_at_300_points_a_lobe_with_2_um_is_within_5_um.)
    # Reference: the brute-force cut outline (shapely distance of the fitted lobe's samples), below the tip
    # corners' neighbourhood (their own zone)
    import shapely

    from rotorcad.curves import sample_curve

    rack_pair = trapezoid_4_6()
    male = cut_rotor(rack_pair, "male")
    pair = RotorPair(4, 6, 100.0, **rack_pair.radii(), lead=1e5, length=1e5, strict=False)
    pts = resample(male, per_lobe_300(male, 4), 2e-3, seed=seed)
    pieces = lobe_pieces(pair, pts, "male", close_smoothing, roundings=True)
    q = np.vstack([sample_curve(c, 2e-3)[1] for _, c in pieces])
    q = q[np.hypot(*q.T) < rack_pair.radii()["male_tip_radius"] - 0.5]
    off = shapely.distance(shapely.points(q), shapely.LinearRing(male))
    assert off.max() < 4e-3  # 6.97 / 5.09 / 7.10 um measured (2.44 / 3.11 / 3.86 with the clamp tried)


@pytest.mark.parametrize("seed", [3, 4, 5])
def test_dense_scattered_sharp_tips_stay_corners(seed):
    # the 4/6 female's tips are cut back by the rack's flats: two sharp corners a tip, twelve in all
    # (its construction, independent_pairs.trapezoid_4_6). At 2000 points a lobe with 1 um scatter the
    # vertices beside a corner turn by the noise (sqrt(6) sigma / h, 4 deg), more than a tenth of the
    # corner: seeds 3-5 read 1-3 of them as roundings the points step over, and the clearance on the
    # female flank beside them 40-42 um for 0 (benchmark, brute force); the noise's turn is no rounding
    from rotorcad.measured.fit import _resolved_corners
    from rotorcad.measured.outline import corners, read_outline

    female = cut_rotor(trapezoid_4_6(), "female")
    spacing = float(np.hypot(*np.diff(np.vstack([female, female[:1]]), axis=0).T).sum()) / 6 / 2000
    outline = read_outline(resample(female, spacing, 1e-3, seed=seed + 100), 6, "female points")
    edges, points = corners(outline.whole, outline.sigma, 30.0)
    assert len(edges) == 12
    kept, _ = _resolved_corners(outline.whole, edges, points, outline.sigma)
    assert len(kept) == 12

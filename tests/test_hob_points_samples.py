"""The hob verdict from either rotor's points, on every rotor sample: the design's (issue 22 item 3).

Inputs, made here from each sample's design (``rotorcad.rotor_build``): exact points of the male's
and of the female's whole outline, the design's own pieces sampled at a 1 um chord (their ends among
the points, as a drawing or rotorcad's CSV gives them), and 300 points a lobe evenly along that
outline with 2 um of Gaussian scatter along its normals (fixed seed), as a CMM scans.

What the hob sees is what ``rotorcad hob --male-points/--female-points`` builds: the pair generated
from the points (``pair_from_rotor_points``, the mate's tip-corner cycloids of scattered points taken
exactly: ``with_exact_cusp_paths``), both rotors' racks with the measured-piece options, ``judge`` at the
profile's stated accuracy.

References, none produced from the points:
* the smallest normal flank angle of the design's generating rack in closed form: the family's rack
  pieces (lines, arcs, tip-corner point paths: ``ScrewRotors.rack``) with their exact tangents, over
  the pieces each rotor's hob cuts with (not that rotor's own tip-corner paths), in the normal
  section atan(tan(alpha_t) cos(beta)) (Wu & Chi, *Meshing clearance evaluation*, eq. 7);
* the design's hob verdict from its exact curves (``hob`` of the sample itself);
* the rack on its contact zone: the design's closed-form rack, where a rack point's normal through
  the pitch point meets the rotors inside both tip circles (Wu & Chi sec. 2, eq. 4), not on a
  tip-corner path.
"""

from __future__ import annotations

import functools
import tomllib
from pathlib import Path

import numpy as np
import pytest
import shapely
from independent_pairs import distance_to_line, scan, segment_tree
from scipy.spatial import cKDTree

from hob.angle_accuracy import smallest_angle_accuracy
from hob.rack import rack_deviation, rotor_rack
from hob.rack_accuracy import rack_accuracy
from hob.verdict import judge, local_scatter, undercut_tolerance
from rotorcad.design import rotor_design
from rotorcad.envelope import rack_frame
from rotorcad.inverse_rack import MEASURED_JOIN_GAP, MEASURED_MIN_TURN, contact_of_rack_points
from rotorcad.measured.cusp_paths import with_exact_cusp_paths
from rotorcad.measured.pairs import pair_from_rotor_points
from rotorcad.roles import PieceRole, Side
from rotorcad.rotor_build import build_pair, pair_spec

SAMPLES = Path(__file__).resolve().parents[1] / "samples"
MEASURED = {"min_turn": MEASURED_MIN_TURN, "join_gap": MEASURED_JOIN_GAP, "cut_loops": True}  # as `rotorcad hob`
NAMES = [p.stem for p in sorted(SAMPLES.glob("*.toml")) if not {"gear", "sweep"} & set(tomllib.loads(p.read_text()))]
FORMS = {"exact": None, "scatter": (300, 2e-3)}  # points a lobe, scatter (mm)
SEED = 11
ZONE_MARGIN = 0.1  # mm inside both tip circles: the contact zone (the rotors' tip roundings aside)


@functools.cache
def design(name: str):
    spec = pair_spec(rotor_design(tomllib.loads((SAMPLES / f"{name}.toml").read_text()), SAMPLES))
    return spec, build_pair(spec)


@functools.cache
def design_verdicts(name: str) -> dict:
    _, rotors = design(name)
    return {side: judge(rotor_rack(rotors, side)) for side in ("male", "female")}


SEED_FORMS = {"scatter-1um": (300, 1e-3)}  # forms read over seeds only (not parametrised with FORMS)


def outline(name: str, rotor: str, form: str, seed: int = SEED) -> np.ndarray:
    """The rotor's whole outline as the input form gives it (own frame, counter-clockwise)."""
    spec, rotors = design(name)
    lobe = rotors.male_outline(1e-3) if rotor == "male" else rotors.female_outline(1e-3)
    pts = np.vstack([seg.points for seg in lobe.segments])
    pts = pts[np.concatenate([[True], np.hypot(*np.diff(pts, axis=0).T) > 1e-9])]
    if np.hypot(*(pts[-1] - pts[0])) < 1e-9:
        pts = pts[:-1]
    if (FORMS | SEED_FORMS)[form] is None:
        return pts
    per_lobe, noise = (FORMS | SEED_FORMS)[form]
    teeth = spec.pair.male_teeth if rotor == "male" else spec.pair.female_teeth
    fine = np.vstack([seg.resampled(1e-4).points for seg in lobe.segments])  # 0.1 um chords for the scan
    fine = fine[np.concatenate([[True], np.hypot(*np.diff(fine, axis=0).T) > 1e-9])]
    q = scan(fine[:-1] if np.hypot(*(fine[-1] - fine[0])) < 1e-9 else fine, per_lobe * teeth, 0.37)
    d = np.roll(q, -1, axis=0) - np.roll(q, 1, axis=0)  # the scatter's direction only
    normal = np.column_stack([d[:, 1], -d[:, 0]]) / np.hypot(*d.T)[:, None]
    return q + np.random.default_rng(seed).normal(0.0, noise, len(q))[:, None] * normal


@functools.cache
def from_points(name: str, rotor: str, form: str, seed: int = SEED):
    """The pair from the points, both racks and both verdicts (as `rotorcad hob --<rotor>-points`)."""
    spec, _ = design(name)
    rotors = with_exact_cusp_paths(pair_from_rotor_points(spec.pair, outline(name, rotor, form, seed), rotor))
    racks = {side: rotor_rack(rotors, side, **MEASURED) for side in ("male", "female")}
    tolerance = undercut_tolerance(rotors)  # as `rotorcad hob` judges the mate's undercut
    verdicts = {
        side: judge(
            rack,
            accuracy=rotors.accuracy,
            measured=side == rotor,
            undercut_accuracy=tolerance,
            tangent_accuracy=rotors.tangent_accuracy,
            point_scatter=local_scatter(rotors)[0],  # as `rotorcad hob`
            point_spacing=local_scatter(rotors)[1],
        )
        for side, rack in racks.items()
    }
    return rotors, racks, verdicts


@functools.cache
def closed_form(name: str) -> dict:
    """The design's generating rack (rack frame of CONTRACT.md, 1 um apart) from its closed-form pieces:
    points, unit tangents and the role of each point's piece."""
    _, rotors = design(name)
    r1 = rotors.pair.male_pitch_radius
    pts, tans, roles = [], [], []
    for piece in rotors.rack:
        c = piece.curve
        n = max(int(np.ceil(abs(c.s1 - c.s0) * 1000.0)), 2) if not np.isclose(c.s0, c.s1) else 0
        if n == 0:
            continue
        p, t = c.evaluate(np.linspace(c.s0, c.s1, min(n, 20000)))
        ok = np.isfinite(p).all(axis=1) & np.isfinite(t).all(axis=1)
        pts.append(rack_frame(p[ok], r1))
        tans.append(np.column_stack([t[ok, 1], t[ok, 0]]))  # the axes swapped, as rack_frame
        roles += [piece.kind] * int(ok.sum())
    return {"points": np.vstack(pts), "tangents": np.vstack(tans), "roles": np.array(roles, dtype=object)}


def closed_form_angle(name: str) -> float:
    """The smallest normal flank angle (deg) of the design's closed-form rack over the pieces the two
    hobs cut with (each rotor's own tip-corner paths left out of its hob), Wu & Chi eq. 7."""
    _, rotors = design(name)
    rack = closed_form(name)
    pair = rotors.pair
    beta = np.arctan(2 * np.pi * pair.male_pitch_radius / pair.lead)
    t = rack["tangents"]
    flank = np.abs(t[:, 1]) > 1e-9
    angle = np.degrees(np.arctan2(np.abs(t[:, 0]) * np.cos(beta), np.abs(t[:, 1])))
    smallest = []
    for side in (Side.MALE, Side.FEMALE):
        cuts = flank & (rack["roles"] != PieceRole.corner_path_of(side))
        smallest.append(angle[cuts].min())
    return float(min(smallest))


def on_zone(name: str, rotor: str) -> np.ndarray:
    """Which closed-form rack points lie where ``rotor`` touches the rack: its contact (the normal through
    the pitch point, Wu & Chi eq. 4) inside its tip circle by ZONE_MARGIN and inside the mate's (on it
    for the mate's tip-corner path, which touches ``rotor``'s point-generated flank), not on
    ``rotor``'s own tip-corner paths (the rotor receives only its corner there)."""
    _, rotors = design(name)
    pair = rotors.pair
    rack = closed_form(name)
    contact, _ = contact_of_rack_points(pair.male_pitch_radius, rack["points"], rack["tangents"])
    r_male = np.hypot(*contact.T)
    r_female = np.hypot(contact[:, 0] - pair.center_distance, contact[:, 1])
    own, mate = (r_male, r_female) if rotor == "male" else (r_female, r_male)
    own_tip, mate_tip = (
        (pair.male_tip_radius, pair.female_tip_radius) if rotor == "male" else (pair.female_tip_radius, pair.male_tip_radius)
    )
    inside = (own <= own_tip - ZONE_MARGIN) & (mate <= mate_tip + 1e-6)
    return inside & (rack["roles"] != PieceRole.corner_path_of(Side(rotor)))


def rack_off_design(name: str, rotor: str, form: str, seed: int = SEED) -> float:
    """Largest distance (mm) of the given rotor's rack (the one its hob is judged on) from the design's
    closed-form rack, over the contact zone."""
    zone = on_zone(name, rotor)
    tree, segments = tiled_reference(name)
    rack = from_points(name, rotor, form, seed)[1][rotor].in_contract_frame()
    pts = rack.points[~rack.corner_path]
    near = tree.query(pts)[1]
    keep = np.tile(zone, 3)[near]
    assert keep.sum() > 50
    return float(distance_to_line(pts[keep], segments).max())


@functools.cache
def tiled_reference(name: str) -> tuple[cKDTree, shapely.STRtree]:
    """The design's closed-form rack over three periods: a k-d tree of its points and the STRtree of its
    segments (built once a sample)."""
    _, rotors = design(name)
    period = rotors.pair.rack_period
    tiled = np.vstack([closed_form(name)["points"] + [k * period, 0.0] for k in (-1, 0, 1)])
    return cKDTree(tiled), segment_tree(shapely.LineString(tiled))


# Measured departures, 300 points a lobe with 2 um of scatter (seed 11), strict: each must still fail,
# and the day it passes its entry goes.
SLIP_TOUCH = (
    "the verdict is the design's now: the female generated from the scattered male turns back at its slip "
    "singularity{}, a touch (hob.turn_back: the generation factor's trend beyond it {}, not below -{}), no longer "
    "'female undercut'; the smallest angle is not the design's: {}"
)
KNOWN_VERDICTS = {
    ("n_rack_5_6", "male", "scatter"): SLIP_TOUCH.format(
        " (r = 43.5-44.6 mm, 314 um deep)", "+0.033", "0.80", "5.37 deg for 5.73"
    ),
    ("rinder_deix_5_6", "male", "scatter"): SLIP_TOUCH.format(
        " (r = 43.5-44.6 mm, 314 um deep)", "+0.033", "0.80", "5.37 deg for 5.73"
    ),
}
# The rack-involute from either rotor (2 um, seed 11) read 16.80 (male: the fit's end effect over the flank's last
# 0.8 mm before the male's tip corner) and 17.98 deg (female: the least of the straight flank's wobbling angles) for
# 18.13; a straight flank's angle is now its line's (hob.straight_flank): 18.125 / 18.121.
# The rack from 2 um of scatter is off by up to 4.5 sigma where the fitted rotor is (a smoothing spline by n sigma^2
# cuts a tip rounding of 10-20 points: rack-involute female seed 11 9.07 um for the profile's accuracy 7.81, N rack and
# Rinder-Deix female 7.76 for 7.49), and more where the generation stalls (the rack folds along the fit's curvature:
# N-rack female seeds 12/18 12.0/8.1 um for a fit 5.6/5.2 off). The test reads it against the rack's own accuracy
# (hob.rack_accuracy, the key `rack_accuracy` of `rotorcad hob`), which counts both; the three strict xfails that read
# it against the profile's `accuracy` are gone. Fits tried to lower the error itself (fit-steps, seeds 11-20):
# (n - sqrt(2n)) sigma^2, the penalised spline of the rack path, extra knots, weights at the rounding, the stepped
# spline: see benchmarks/bench_rack_fit.py and the session notes; none lowers it on every case.
KNOWN_RACKS: dict[tuple[str, str, str], str] = {}


KNOWN_DEVIATIONS: dict[tuple[str, str, str], str] = {}  # all within the stated accuracy now


def cases(known: dict[tuple[str, str, str], str]) -> list:
    return [
        pytest.param(name, rotor, form, marks=pytest.mark.xfail(strict=True, reason=known[name, rotor, form]))
        if (name, rotor, form) in known
        else (name, rotor, form)
        for name in NAMES
        for rotor in ("male", "female")
        for form in FORMS
    ]


@pytest.mark.parametrize("name", NAMES)
def test_the_design_hob_reads_its_closed_form_rack(name):
    # the reference itself: the design's verdict (from its exact curves) has the closed-form smallest angle
    smallest = min(v.normal_pressure_angle_min_deg for v in design_verdicts(name).values())
    assert smallest == pytest.approx(closed_form_angle(name), abs=0.02)


@pytest.mark.parametrize("name,rotor,form", cases(KNOWN_VERDICTS))
def test_the_hob_from_points_is_the_design_hob(name, rotor, form):
    # Issue 22 item 3: hobbable or not, and the smallest normal flank angle within 0.1 deg, from the
    # male's and from the female's points as from the design. Before (400 points a lobe, exact):
    # Krigar, Lysholm, narrow-tip, SRM-A, SRM-B, symmetric SRM from the male 0.70-6.11 deg for 0
    # (the female tip corner's path generated from the fitted male bent off the perpendicular at its
    # cusp on the pitch line); the N rack and Rinder-Deix "female undercut" from either rotor. Now
    # 0.000-0.018 deg and the design's verdict from exact points on every sample. From 300 points a lobe
    # with 2 um of scatter the male of Krigar, Lysholm, narrow-tip, SRM-A and SRM-B read 1.75-2.51 deg for 0
    # and the symmetric SRM's 0.61 (the female tip corner's cycloid kept as generated from the fit, the
    # symmetric SRM's 1.6 mm path read as flank); now taken exactly (with_exact_cusp_paths): 0.000-0.005 deg.
    verdicts = from_points(name, rotor, form)[2]
    truth = design_verdicts(name)
    assert all(v.hobbable for v in verdicts.values()) == all(v.hobbable for v in truth.values()), [
        r for v in verdicts.values() for r in v.reasons
    ]
    smallest = min(v.normal_pressure_angle_min_deg for v in verdicts.values())
    assert smallest == pytest.approx(closed_form_angle(name), abs=0.1)


@pytest.mark.parametrize("name,rotor,form", cases(KNOWN_RACKS))
def test_the_rack_from_points_on_the_contact_zone_is_the_design_rack(name, rotor, form):
    # Issue 22 item 3: the rack the hob is judged on, where the rotors touch, within 2 um of the
    # design's generating rack (closed form) from exact points; from 2 um of scatter within the bound
    # the profile states (the largest of a lobe's errors with 95 % confidence). Exact points: 0.00-1.91 um.
    # The males of Krigar, Lysholm, narrow-tip, SRM-A, SRM-B and the symmetric SRM with 2 um scatter: 7.9-19.9 um
    # before their female tip corner's cycloid was taken exactly (stated 7.4-7.8), now within it. The bound of
    # scattered points is the rack's own (hob.rack_accuracy: the profile's accuracy, or the fit's bias at its
    # tightest rounding, or its sharp corners' error, plus the rack's folds where the generation stalls): the
    # rack-involute female 9.07 um (stated 7.81 by the profile's accuracy, 11.06 by the rack's), N rack and
    # Rinder-Deix female 7.76 (7.49, 9.80); all 18 cases at seed 11 0.12-9.07 um, stated 7.6-15.6.
    rotors, racks, _ = from_points(name, rotor, form)
    error = rack_off_design(name, rotor, form)
    if form == "exact":
        assert error <= 2e-3
        return
    stated = rack_accuracy(rotors, racks[rotor])
    assert rotors.accuracy <= stated
    assert error <= max(2e-3, stated), (error, stated)
    # a statement, not a shrug: at most 3 times the error, or twice the profile's accuracy (k_N sigma) where the
    # error is small (Krigar male 0.12 um); measured 1.0-2.05 times the accuracy, 1.2-4.6 times the error
    assert stated <= max(3.0 * error, 2.0 * rotors.accuracy), (error, stated, rotors.accuracy)


@pytest.mark.parametrize(
    "name,rotor,seed",
    [("n_rack_5_6", "female", 12), ("n_rack_5_6", "male", 12), ("narrow_tip_5_6", "male", 17), ("rack_involute_5_6", "male", 28)],
)
def test_the_rack_accuracy_covers_a_stall_and_a_corner(name, rotor, seed):
    # The seeds (of 11-30, benchmarks/bench_rack_fit.py) where the rack is off by more than the fitted rotor, or the
    # fit by more than the profile's accuracy (300 points a lobe, 2 um): where the generation stalls the rack folds
    # along the fit's curvature (N-rack female seed 12: 11.96 um for a fit 5.61 off; the N-rack male's 0.67 mm tip
    # circle, seed 12: 34.4 um for 8.2; rack-involute male seed 28: 9.23 for 5.63), and beside the narrow-tip male's
    # 45 deg root corner the fit is as far off as the corner it found (seed 17: 12.85 um for an accuracy of 7.67).
    # Reference: the design's closed-form rack on the contact zone. The rack's own accuracy (hob.rack_accuracy)
    # covers each (stated 22.2, 47.3, 21.9, 13.9 um), the profile's does not. Over seeds 11-30 of the rack-involute,
    # N-rack, Rinder-Deix and narrow-tip samples, both rotors: 160 of 160 covered, stated / error median 1.9-3.7.
    rotors, racks, _ = from_points(name, rotor, "scatter", seed)
    error = rack_off_design(name, rotor, "scatter", seed)
    assert error > rotors.accuracy
    assert error <= rack_accuracy(rotors, racks[rotor]) <= 3.0 * error, (error, rack_accuracy(rotors, racks[rotor]))


def fit_off_design(name: str, rotor: str, form: str) -> float:
    """Largest distance (mm) of the fitted rotor from the design's outline (0.1 um chords) at the profile points
    whose rack points lie on the contact zone (those of rack_off_design)."""
    _, rotors = design(name)
    rack = from_points(name, rotor, form)[1][rotor].in_contract_frame()
    free = ~rack.corner_path
    keep = np.tile(on_zone(name, rotor), 3)[tiled_reference(name)[0].query(rack.points[free])[1]]
    lobe = rotors.male_outline(1e-4) if rotor == "male" else rotors.female_outline(1e-4)
    ring = np.vstack([seg.points for seg in lobe.segments])
    return float(distance_to_line(rack.profile[free][keep], shapely.LineString(ring)).max())


@pytest.mark.parametrize(
    "name,rotor",
    [("rack_involute_5_6", "female"), ("rack_involute_5_6", "male"), ("n_rack_5_6", "female"), ("lysholm_4_6", "female")],
)
def test_the_rack_bears_the_rotor_fits_error_not_more(name, rotor):
    # Where the rack from scattered points is off (2 um, 300 a lobe): a rack point is where the fitted rotor's
    # normal passes the pitch point (Wu & Chi sec. 2, eq. 4); a wrong normal moves the contact to another roll,
    # but the rotor point's velocity relative to the rack is normal to its line to the pitch point, which is
    # that normal: the rack point slides along the rack, and to first order the rack is off by what the fit is
    # off at the contact point, whatever the lever (the distance to the pitch point, large at the root
    # fillets). So the rack's largest error on the contact zone is at most the fitted rotor's at those contact
    # points plus 0.1 um on all 18 rotor samples' cases (rack-involute female 9.07 / 9.01 um, N rack 7.76 / 7.73,
    # Lysholm 4.14 / 4.16), and the 2 um asked fails at the fit, not at the inverse generation. Not so where the
    # generation stalls (the second-order slide times the rack's curvature): the N-rack male's 0.67 mm sealing
    # tip circle (~3 points a lobe) sets a rack stretch of ~2 mm by its curvature, and its rack reads 11-88 um
    # off there on 7 of seeds 12-20 with the fit 0.1-1.8 um off (seed 11: 7.46 / 7.42). References: the
    # design's outline (its exact curves) and its closed-form generating rack.
    rack, fit = rack_off_design(name, rotor, "scatter"), fit_off_design(name, rotor, "scatter")
    assert rack <= fit + 0.25e-3, (rack, fit)


@pytest.mark.parametrize("name,rotor,form", cases(KNOWN_DEVIATIONS))
def test_rack_deviation_on_the_contact_zone(name, rotor, form):
    # Issue 22 item 3: `rack_deviation` (the male's rack against the female's of the pair from the points)
    # on the contact zone only. Truth: 0 (the mate is generated from the given rotor's rack, Wu & Chi
    # sec. 2); bound: 2 um or the stated accuracy. Before, a tip corner's path read from 2 um of scatter
    # counted: 1.5-10 mm on the SRM, Lysholm and Krigar samples; then 9-239 um (Krigar, the SRMs) with the
    # female tip corner's cycloid kept as generated; now 0.00-0.06 um.
    rotors = from_points(name, rotor, form)[0]
    assert rack_deviation(rotors, **MEASURED) <= max(2e-3, rotors.accuracy), rotors.accuracy


@pytest.mark.parametrize("name,rotor,form", cases({}))
def test_the_smallest_angle_from_points_is_within_its_stated_accuracy(name, rotor, form):
    # `smallest_flank_angle_accuracy_deg` (hob.angle_accuracy: the profile's tangent accuracy carried to the
    # normal rack by the contact condition, Wu & Chi eq. 4 and 7) covers the error of the smallest angle read
    # from the points. Reference: the design's closed-form smallest angle. Errors 0.000-1.330 deg (the
    # rack-involute male with 2 um of scatter: 16.797 for 18.127, stated 1.41, then 2.66; its straight flank read by
    # its line since, hob.straight_flank: 18.125, stated 2.74, then 0.029 by the line's own accuracy); stated
    # 0.03-2.23 deg (1.9-2.06 where a cusp on the pitch line makes the rack perpendicular: within 3 deg of it, the
    # angle is stated to that).
    rotors, racks, verdicts = from_points(name, rotor, form)
    smallest = min(v.normal_pressure_angle_min_deg for v in verdicts.values())
    stated = smallest_angle_accuracy(rotors, racks, rotor, smallest)
    assert abs(smallest - closed_form_angle(name)) <= stated + 1e-6, (smallest, stated)
    # a statement, not a shrug: with the read minimum's error counted at the lobe's largest (k_N / 2 = 1.9 times
    # one point's) the rack-involute male with 2 um of scatter states 2.66 deg for its 1.33 deg error, the N-rack
    # male 2.23 for 0.36; the rest 0.26-2.06 deg as before
    assert stated < 3.0


@pytest.mark.parametrize("rotor", ["male", "female"])
@pytest.mark.parametrize("form,seeds", [("scatter-1um", (71, 72, 73, 75)), ("scatter", (11, 12, 13, 14, 15, 16))])
def test_the_smallest_angle_accuracy_covers_the_low_minimum_over_seeds(rotor, form, seeds):
    # newuser6: at 300 points a lobe with 1 um of scatter the rack-involute's smallest angle (a straight rack
    # flank, the same angle over hundreds of points) read 0.09-0.59 deg low on every seed, outside the stated
    # 0.29-0.46 deg on 8 of 12 seeds 71-76 of both rotors: the minimum of scattered angles picks the most
    # negative error, the lobe's largest, which one point's bound did not count (hob.angle_accuracy). Then
    # stated 0.54-0.68 deg, covered on all 16 of seeds 71-78 (errors -0.04..-0.59). Since the straight flank reads its
    # line (hob.straight_flank): errors -0.009..+0.002 at 1 um, -0.011..+0.004 at 2 um (seeds 11-16), and the accuracy
    # is the line's (hob.straight_flank.line_accuracy): 0.009-0.040 at 1 um, 0.017-0.090 at 2 um, for 0.54-0.91 and
    # 1.04-2.74 by the pointwise bound; 4-15 times the largest error of each rotor's seeds. Reference: the design's
    # closed-form smallest angle (Wu & Chi eq. 7 on the family's rack pieces).
    truth = closed_form_angle("rack_involute_5_6")
    for seed in seeds:
        rotors, racks, verdicts = from_points("rack_involute_5_6", rotor, form, seed)
        smallest = min(v.normal_pressure_angle_min_deg for v in verdicts.values())
        stated = smallest_angle_accuracy(rotors, racks, rotor, smallest)
        assert abs(smallest - truth) <= stated, (seed, smallest, stated)
        # a statement within issue 22's 0.1 deg, not the pointwise bound's 0.5-2.7 deg
        assert stated < 0.1, (seed, stated)


@pytest.mark.parametrize(
    "name,seed",
    [("lysholm_4_6", 13), ("narrow_tip_5_6", 12), ("srm_symmetric_4_6", 14), ("narrow_tip_5_6", 20), ("srm_asymmetric_5_6", 32)],
)
def test_a_zero_smallest_angle_read_high_from_the_male_is_within_its_stated_accuracy(name, seed):
    # The samples whose smallest angle is 0 deg have it where the male's flank leaves its root land radially on the
    # pitch circle (rack: a corner on the pitch line). From 300 points a lobe with 2 um the fit's flank end there
    # turns 4-4.6 deg off on some seeds (no corner found at the join), which the rack turns into a dip 1-2 deg off
    # over the next 1 mm (the gain 1 + y / (r_w t_x^2), large where the rack is steep): Lysholm seed 13 reads 1.39,
    # narrow-tip seed 12 2.15, symmetric SRM seed 14 1.83 deg, at 0.3-0.4 mm above the pitch line. The stated accuracy
    # (the 3 deg steep bound, hob.angle_accuracy) covers them, on all 144 male rows of seeds 17-40 of the six 0 deg
    # samples too (25 read 0.98-2.30 deg high), but narrowly: narrow-tip seed 20 1.903 for 1.926 stated, SRM-A seed 32
    # 1.899 for 1.926 (the bound does not model this end effect). Reference: the design's closed-form 0 deg.
    rotors, racks, verdicts = from_points(name, "male", "scatter", seed)
    smallest = min(v.normal_pressure_angle_min_deg for v in verdicts.values())
    truth = closed_form_angle(name)
    assert truth < 1e-3  # the design's smallest angle is 0 (1e-5 deg off from its sampled closed form)
    assert smallest > 1.0  # the high reading this test is about (not a seed that reads 0)
    assert abs(smallest - truth) <= smallest_angle_accuracy(rotors, racks, "male", smallest)


@pytest.mark.xfail(
    strict=True,
    reason="known defect, not fixed: from the rack-involute male's 2 um points, seed 28, the female's rack (generated) "
    "turns back at the male tip corner's place (y = -11.57 mm) after 1.5 mm of bent flank, 16.38 deg for 18.13, longer "
    "than hob.straight_flank's run end (4 spacings, 1.16 mm), so read pointwise; stated 1.53 (the pointwise bound) "
    "for its 1.74 error, as on main",
)
def test_the_rack_involute_male_seed_28_reads_its_straight_flank():
    # Reference: the design's closed-form smallest angle (Wu & Chi eq. 7 on the family's rack pieces). Found by the
    # survey of seeds 17-40 (1 of 30 male seeds of 11-40 uncovered; from the female, seeds 18/31/33/40 read 0.14-0.32
    # deg low where the female's 18.127 deg flank is not read as a line, covered by the pointwise bound, 1.05-1.15).
    rotors, racks, verdicts = from_points("rack_involute_5_6", "male", "scatter", 28)
    smallest = min(v.normal_pressure_angle_min_deg for v in verdicts.values())
    assert abs(smallest - closed_form_angle("rack_involute_5_6")) <= smallest_angle_accuracy(rotors, racks, "male", smallest)


@pytest.mark.parametrize("rotor", ["male", "female"])
@pytest.mark.parametrize("seed", [12, 15])
def test_a_straight_rack_flank_reads_its_angle_from_scattered_points(rotor, seed):
    # Issue 22 item 3: the rack-involute's smallest flank angle is its straight rack flank's, 18.127 deg over hundreds
    # of rack points. From 300 points a lobe with 2 um of scatter the least of its pointwise angles read 0.39 / 0.19
    # deg low from the female (seeds 12 / 15: the most negative wobble of the fitted tangents) and 0.60 / 0.70 from
    # the male (the fit's end effect before the male's tip corner); the flank's line (hob.straight_flank, decided
    # from the fitted rack and the stated scatter) reads it within 0.011 deg over seeds 11-16 of both rotors.
    # Reference: the design's closed-form smallest angle (Wu & Chi eq. 7 on the family's rack pieces).
    verdicts = from_points("rack_involute_5_6", rotor, "scatter", seed)[2]
    smallest = min(v.normal_pressure_angle_min_deg for v in verdicts.values())
    assert smallest == pytest.approx(closed_form_angle("rack_involute_5_6"), abs=0.1)


@pytest.mark.parametrize("rotor,seed", [("male", 14), ("male", 16), ("female", 12)])
def test_the_n_rack_hob_from_scattered_points_is_never_a_wrong_decided_verdict(rotor, seed):
    # Issue 22 item 3: the N-rack male from 300 points a lobe with 2 um read decided verdicts the design does not have.
    # Seed 16 (and 20, 24): "4.2 % of the profile has no rack point", samples of a corner fan where the generated
    # female's flank was cut at its tip circle (a 114 deg corner the design does not have, its female smooth there): a
    # fan is one profile point, its directions that meet no contact are off its path, not profile without a rack point
    # (rotorcad.inverse_rack.derive_rack). Seed 14: "female undercut at r = 42.21-45.00 mm, 562 um", the generation
    # factor's trend read 2.95 mm past a fold of the rack and taken back to the step (f0 -2.87 for a bound of 1.22 at
    # its window, 5.0 at the step: hob.turn_back.TurnBack.reach): now undecided, never a decided wrong verdict. The
    # female from its own points, seed 12 (and 7 more of seeds 11-30): "female undercut at r = 42.74-43.01 mm", its fit
    # turning back 1.0 um deep where the design's driving flank meets its tip rounding (r = 42.80 mm), for 14.9 um of
    # accuracy: now undecided at this accuracy (hob.verdict.undercut_reasons), the undercut within the gate.
    # Reference: the design's verdict from its exact curves (hobbable; the female touches its rack at the slip
    # singularity, Rinder's N rack), none of it produced from the points.
    truth = design_verdicts("n_rack_5_6")
    verdicts = from_points("n_rack_5_6", rotor, "scatter", seed)[2]
    assert all(v.hobbable for v in verdicts.values()) == all(v.hobbable for v in truth.values()), [
        r for v in verdicts.values() for r in v.reasons
    ]
    assert all(not v.undercut for v in verdicts.values())


@functools.cache
def dense_six_decimals() -> dict:
    """A new user's file: the narrow-tip male as 2000 points a lobe along the design's 0.01 um-chord outline,
    phase 0, rounded to 1e-6 mm as CMM software writes them; both verdicts as `rotorcad hob` gives them."""
    spec, rotors = design("narrow_tip_5_6")
    fine = np.asarray(rotors.section(Side.MALE, 1e-5).exterior.coords)[:-1]  # as `rotor --male-csv` writes it
    if shapely.Polygon(fine).exterior.is_ccw is False:
        fine = fine[::-1]
    points = np.round(scan(fine, 2000 * spec.pair.male_teeth, 0.0), 6)
    given = with_exact_cusp_paths(pair_from_rotor_points(spec.pair, points, "male"))
    racks = {side: rotor_rack(given, side, **MEASURED) for side in ("male", "female")}
    return {side: judge(rack, accuracy=given.accuracy, measured=side == "male") for side, rack in racks.items()}


def test_dense_points_to_six_decimals_give_the_design_verdict():
    # Was refused (exit 2; exit 70, an internal error, before that): the female generated from the points
    # lost every part inside its tip circle to the loop trimming (rotorcad.lobe_trim.trimmed_lobe), which
    # took a crossing of the lobe's stray part with the next lobe's copy for a loop around the whole lobe.
    # Reference: the design's verdict from its exact curves (not hobbable, both racks).
    verdicts = dense_six_decimals()
    truth = design_verdicts("narrow_tip_5_6")
    assert all(v.hobbable for v in verdicts.values()) == all(v.hobbable for v in truth.values())
    # and for the design's reason: the male rack's flank stands perpendicular to the pitch line at the cusp
    assert [r.split(" deg")[0][:24] for r in truth["male"].reasons if "flank angle" in r] == ["the flank angle falls to"]
    assert any(r.startswith("the flank angle falls to") for r in verdicts["male"].reasons), verdicts["male"].reasons


def test_dense_points_to_six_decimals_give_the_design_hob():
    # Reference: the design's closed-form smallest angle (0: the cusp on the pitch line), within 0.1 deg. Was a strict
    # xfail (the male's rack 0.149 deg off the perpendicular): the female tip corner's path (y = 0-3.3 mm of rack)
    # was not found; since exact points' corner paths run on to their piece's ends (rotorcad.measured.pairs) the
    # male's rack reads 0.0.
    smallest = min(v.normal_pressure_angle_min_deg for v in dense_six_decimals().values())
    assert smallest == pytest.approx(closed_form_angle("narrow_tip_5_6"), abs=0.1)


def test_dense_points_to_six_decimals_give_the_design_female_rack_angle():
    # Reference: the design's female rack from its exact curves, whose smallest flank angle is 6.25 deg (its driving
    # flank's end). The female generated from the male's points read 2.49 deg: a 1.6 um piece of its profile (6.5 um of
    # rack) between its tip corner's two fans, the fit's junction of what the design has as one corner, stood nearly
    # perpendicular to the pitch line (hob.verdict._corner_slivers leaves such a sliver out of the flank).
    female = dense_six_decimals()["female"].normal_pressure_angle_min_deg
    assert female == pytest.approx(design_verdicts("narrow_tip_5_6")["female"].normal_pressure_angle_min_deg, abs=0.1)

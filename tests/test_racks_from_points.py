"""The rack and the hob verdict from measured points of either rotor, on pairs rotorcad did not make.

Pairs (tests/independent_pairs.py, shapely booleans only): the 4/6 trapezoid rack pair and the 5/6
pair of a rack with one straight and one circular-arc flank, both rotors with sharp tip corners cut
back by the rack's flats. Input forms as a CMM or a drawing gives them: the cut outline itself
("exact"), 2000 points a lobe ("dense"), 300 points a lobe with 2 um Gaussian scatter along the
normals ("scatter"), 80 points a lobe ("sparse").

References, none produced by the code under test:
* the closed-form generating rack (lines and arcs, ``TrapezoidRack.sample`` with exact normals);
* the contact zone of that rack in closed form: a rack point at height y whose normal has slope
  n_x / n_y touches the rotors at sqrt((y n_x / n_y)^2 + (r_w +- y)^2) from their centres (the
  normal through the pitch point, Wu & Chi sec. 2, eq. 4), inside both tip circles;
* the normal flank angle atan(tan(alpha_t) cos(beta)) of the closed-form rack (Wu & Chi eq. 7);
* for the undercut 5/6 male, the brute-force cut: the rack's own envelope points that the cut
  removed (closed-form contact points farther than 50 um from the cut outline).

What the hob sees is what ``rotorcad hob --male-points/--female-points`` builds: the pair generated
from the measured rotor's rack (``pair_from_rotor_points``, ``with_exact_cusp_paths``), its two racks with
the measured-piece options, ``rack_deviation`` and ``judge`` at the profile's stated accuracy.
"""

from __future__ import annotations

import functools
import json
from collections import Counter
from pathlib import Path

import numpy as np
import pytest
import shapely
from independent_pairs import arc_flank_5_6, cut_rotor, distance_to_line, resample, segment_tree, trapezoid_4_6
from scipy.spatial import cKDTree

from exports.csv_points import write_points
from hob.rack import rack_deviation, rotor_rack
from hob.verdict import judge
from rotorcad.cli.main import main
from rotorcad.inverse_rack import MEASURED_JOIN_GAP, MEASURED_MIN_TURN
from rotorcad.measured.cusp_paths import with_exact_cusp_paths
from rotorcad.rotor_pair import RotorPair
from rotorcad.rotor_points import pair_from_rotor_points

LEAD = 300.0
MEASURED = {"min_turn": MEASURED_MIN_TURN, "join_gap": MEASURED_JOIN_GAP, "cut_loops": True}  # as `rotorcad hob`
PAIRS = {"4/6": trapezoid_4_6, "5/6": arc_flank_5_6}
FORMS = {
    "exact": None,
    "dense": (2000, 0.0),
    "scatter": (300, 2e-3),
    "sparse": (80, 0.0),
    "medium": (300, 0.0),
    "dense-scatter": (2000, 1e-3),
}


def rotor_pair(name: str) -> RotorPair:
    rp = PAIRS[name]()
    return RotorPair(rp.male_teeth, rp.female_teeth, 100.0, **rp.radii(), lead=LEAD, length=190.0, strict=False)


@functools.cache
def points(name: str, rotor: str, form: str) -> np.ndarray:
    """The cut rotor as the input form gives it (seeded scatter)."""
    rp = PAIRS[name]()
    ring = cut_rotor(rp, rotor)
    if FORMS[form] is None:
        return ring
    per_lobe, noise = FORMS[form]
    teeth = rp.male_teeth if rotor == "male" else rp.female_teeth
    length = float(np.hypot(*np.diff(np.vstack([ring, ring[:1]]), axis=0).T).sum())
    return resample(ring, length / teeth / per_lobe, noise=noise, seed=11)


@functools.cache
def hob_view(name: str, rotor: str, form: str):
    """The pair from the points, both racks, the rack deviation and both verdicts (as `rotorcad hob`)."""
    rotors = with_exact_cusp_paths(pair_from_rotor_points(rotor_pair(name), points(name, rotor, form), rotor))
    racks = {side: rotor_rack(rotors, side, **MEASURED) for side in ("male", "female")}
    # each rotor judged as `rotorcad hob` judges it: the measured one as fitted to its points, its mate as an envelope
    verdicts = {side: judge(rack, accuracy=rotors.accuracy, measured=side == rotor) for side, rack in racks.items()}
    return rotors, racks, rack_deviation(rotors, **MEASURED), verdicts


@functools.cache
def closed_form(name: str) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The generating rack's points (rack frame, 1 um apart), whether each lies in the contact zone
    (touching both rotors 0.1 mm inside their tip circles, not on a flat), and its normal flank angle (deg)."""
    rp = PAIRS[name]()
    pts, nrm = rp.rack.sample(0.001)
    r1, r2, h = rp.male_pitch_radius, rp.female_pitch_radius, rp.rack.height
    flank = np.abs(nrm[:, 1]) > 1e-9
    off = pts[:, 1] * nrm[:, 0] / np.where(flank, nrm[:, 1], 1.0)
    r_male, r_female = np.hypot(off, r1 + pts[:, 1]), np.hypot(off, r2 - pts[:, 1])
    zone = flank & (np.abs(nrm[:, 0]) > 1e-9) & (r_male <= r1 + h - 0.1) & (r_female <= r2 + h - 0.1)
    beta = np.arctan(2 * np.pi * r1 / LEAD)
    angle = np.degrees(np.arctan2(np.abs(nrm[:, 1]) * np.cos(beta), np.abs(nrm[:, 0])))
    return pts, zone, angle


CASES = [
    ("4/6", "male", "exact"),
    ("4/6", "male", "dense"),
    ("4/6", "male", "scatter"),
    ("4/6", "male", "sparse"),
    ("4/6", "female", "exact"),
    ("4/6", "female", "dense"),
    ("4/6", "female", "scatter"),
    ("4/6", "female", "sparse"),
    ("5/6", "female", "exact"),
    ("5/6", "female", "dense"),
    ("5/6", "female", "scatter"),
    ("5/6", "female", "sparse"),
]


@pytest.mark.parametrize("name,rotor,form", CASES)
def test_the_rack_where_both_rotors_touch_it_is_the_generating_rack(name, rotor, form):
    # The measured rotor's rack (the one the hob judges) on the closed-form contact zone: within
    # 2 um of the generating rack, or within the profile's stated accuracy where that is larger
    # (the chords' sagitta of sparse points; with scatter, the bound on the largest of the lobe's
    # N Gaussian errors with 95 % confidence, k_N sigma, k_300 = 3.76: the 4/6 male with 2 um
    # scatter reads 5.5 um over a stretch of its flank, stated 7.5 um, was 2 sigma = 4.0 um).
    rotors, racks, _, _ = hob_view(name, rotor, form)
    d = zone_error(name, racks[rotor])
    assert d.max() <= max(2e-3, rotors.accuracy), (d.max(), rotors.accuracy)


@functools.cache
def tiled_reference(name: str) -> tuple[cKDTree, np.ndarray, shapely.STRtree]:
    """The closed-form generating rack over three periods: a k-d tree of its points, whether each lies in
    the contact zone, and the STRtree of its segments (built once a pair: 180 000 points)."""
    reference, zone, _ = closed_form(name)
    period = rotor_pair(name).rack_period
    tiled = np.vstack([reference + [k * period, 0.0] for k in (-1, 0, 1)])
    return cKDTree(tiled), np.tile(zone, 3), segment_tree(shapely.LineString(tiled))


def zone_error(name: str, rack) -> np.ndarray:
    """The distance (mm) of each point of a rotor's rack (hob.rack.rotor_rack) on the closed-form contact
    zone from the closed-form generating rack (brute force: shapely's point-to-polyline distance)."""
    rack = rack.in_contract_frame()
    tree, zone, segments = tiled_reference(name)
    near = tree.query(rack.points)[1]
    on_zone = zone[near] & ~rack.corner_path
    assert on_zone.sum() > 200
    return distance_to_line(rack.points[on_zone], segments)


SEEDS = (1, 2, 3, 4, 5)
SEED_CASES = [
    ("4/6", "male", 300),
    ("4/6", "female", 300),
    ("5/6", "female", 300),
    ("4/6", "male", 80),
    ("4/6", "female", 80),
    ("5/6", "female", 80),
]


@pytest.mark.parametrize("name,rotor,per_lobe", SEED_CASES)
def test_the_stated_accuracy_covers_the_rack_over_seeds(name, rotor, per_lobe):
    # Issue 22 items 3 and 5, with 2 um of scatter over five seeds (not the one seed of the tests
    # above): the rack the hob judges, on the closed-form contact zone, within the accuracy the
    # profile states (the bound k_N sigma on the largest of a lobe's N errors, or the chords' sagitta
    # of sparse points), and within 2 um over 90 % of the zone at 300 points a lobe (5 um at 80).
    # Reference: the closed-form generating rack (zone_error). Measured, seeds 1-5, largest / 90th
    # percentile / stated (um): at 300 a lobe 4/6 male 2.3-5.7 / 1.2-1.7 / 7.6-8.2, 4/6 female
    # 2.2-4.1 / 0.9-1.8 / 7.8-8.2, 5/6 female 2.4-4.9; at 80 a lobe 4/6 male 4.5-6.5 / 2.3-4.7 / 21-23,
    # 4/6 female 5.4-8.9 / 2.2-2.9 / 39, 5/6 female 7.4-11.1 / 2.4-3.5 / 18-19. The 2 um asked is not
    # reached at the root fillets (rack y = +-6.5 mm): the smoothing spline (n sigma^2, Dierckx sec.
    # 5.2) bends with the scatter where the fillet's curvature meets the involute's; closer fits
    # (n - sqrt(2 n)) sigma^2, uniform knots 0.8-2.5 mm apart, a penalised spline by cross-validation
    # read 3.1-5.1, 2.7-34, 3.2-5.3 um there. The rack is off by what the fitted rotor is off at the contact
    # point (test_hob_points_samples::test_the_rack_bears_the_rotor_fits_error_not_more), not by the lever:
    # each measured point carried to the rack by its foot's contact roll and the carried points fitted by the
    # penalised spline in the rack frame (lines and arcs) read the 4/6 male's fillets 3.6 / 1.7 / 3.4 um
    # (seeds 1-3; 3.8 / 3.9 / 5.7 from the rotor's fit) but its flanks 1.5-2.9 um (0.4-1.9) and its angle
    # 0.27-0.40 deg lower. A rounding of m points fitted even as a known arc (3 parameters) is off by
    # sigma sqrt(3 / m) at a point, 1.1 um for m = 10 (~2.7 mm at 300 a lobe), and the largest over a lobe's
    # roundings with 95 % confidence about 2.5 times that: 2 um everywhere needs about 19 points a rounding
    # (600 a lobe) or sigma below 1.4 um.
    rp = PAIRS[name]()
    ring = cut_rotor(rp, rotor)
    teeth = rp.male_teeth if rotor == "male" else rp.female_teeth
    length = float(np.hypot(*np.diff(np.vstack([ring, ring[:1]]), axis=0).T).sum())
    for seed in SEEDS:
        pts = resample(ring, length / teeth / per_lobe, noise=2e-3, seed=seed)
        rotors = with_exact_cusp_paths(pair_from_rotor_points(rotor_pair(name), pts, rotor))
        d = zone_error(name, rotor_rack(rotors, rotor, **MEASURED))
        assert d.max() <= rotors.accuracy, (seed, d.max(), rotors.accuracy)
        assert np.quantile(d, 0.9) <= (2e-3 if per_lobe >= 300 else 5e-3), (seed, np.quantile(d, 0.9))


@pytest.mark.parametrize("name,rotor,form", CASES)
def test_rack_deviation_is_within_the_stated_accuracy(name, rotor, form):
    # Truth: 0 on the contact zone (the mate is generated from the measured rotor's rack). Bound:
    # 2 um, or the stated accuracy, a bound on the largest of the lobe's errors (k_N sigma with
    # 95 % confidence; the 4/6 female with 2 um scatter reads 5.4 um at its root land's end).
    rotors, _, deviation, _ = hob_view(name, rotor, form)
    bound = max(2e-3, rotors.accuracy)
    assert deviation <= bound, (deviation, rotors.accuracy)


@pytest.mark.parametrize("name,rotor,form", CASES)
def test_the_verdict_and_the_flank_angle_agree_with_the_generating_rack(name, rotor, form):
    # The racks are hobbable with no reasons, from the male and from the female alike (but the
    # 5/6 male, which is undercut: its verdict names that only, tests below), and the
    # smallest normal flank angle is the closed-form one over the part of the rack that the
    # measured rotor carries (Wu & Chi eq. 7): 0.2 deg for exact and dense points, 0.5 deg with
    # 2 um scatter, 1 deg from 80 points a lobe.
    _, _, _, verdicts = hob_view(name, rotor, form)
    for side, v in verdicts.items():
        if name == "5/6" and side == "male":  # the 5/6 male is undercut (brute force, test below)
            assert all("undercut at r" in r for r in v.reasons), v.reasons
            # not read from the female's 300 points a lobe with 2 um scatter (UNDERCUT_CASES)
            assert not v.hobbable or form == "scatter", v.reasons
        else:
            assert v.hobbable and v.reasons == [], (side, v.reasons)
    reference, _, angle = closed_form(name)
    rp = PAIRS[name]()
    r_w = rp.male_pitch_radius if rotor == "male" else rp.female_pitch_radius
    smallest = min(v.normal_pressure_angle_min_deg for v in verdicts.values())
    # the closed-form smallest angle over the flank parts the measured rotor carries: its contact
    # point inside its own tip circle (the other rotor is generated from that rack)
    _, nrm = rp.rack.sample(0.001)
    flank = (np.abs(nrm[:, 1]) > 1e-9) & (np.abs(nrm[:, 0]) > 1e-9)
    y = reference[:, 1] if rotor == "male" else -reference[:, 1]
    off = reference[:, 1] * nrm[:, 0] / np.where(flank, nrm[:, 1], 1.0)
    carried = flank & (np.hypot(off, r_w + y) <= r_w + rp.rack.height)
    tol = {"exact": 0.2, "dense": 0.2, "scatter": 0.5, "sparse": 1.0}[form]
    assert smallest == pytest.approx(angle[carried].min(), abs=tol)


@pytest.mark.parametrize("form", ["exact", "dense", "medium", "scatter"])
def test_the_verdict_is_the_same_from_the_male_and_from_the_female(form):
    # Issue 22 item 3 on the 4/6 pair: the smallest flank angle from the male's points and from
    # the female's within 0.1 deg, and the same verdict, exact or with 2 um of scatter (300 points
    # a lobe: 0.30 deg apart before, 0.05 now; the female's tip corner was taken where the chords
    # cross, 0.5 um off where the fits beside it cross, which bent its flank's end by 0.35 deg).
    a, b = hob_view("4/6", "male", form)[3], hob_view("4/6", "female", form)[3]
    angle = {k: min(v.normal_pressure_angle_min_deg for v in d.values()) for k, d in (("m", a), ("f", b))}
    assert abs(angle["m"] - angle["f"]) < 0.1
    assert all(v.hobbable for v in a.values()) == all(v.hobbable for v in b.values())


def test_the_undercut_male_reads_undercut():
    # The 5/6 rack's arc flank (17 deg at its foot) undercuts the male near its root: the
    # brute-force cut removed part of the rack's own envelope there (closed-form contact points
    # turned into the male frame, more than 50 um inside the cut outline's material side, at
    # 42.3-42.7 mm). The verdict from the exact cut male says the rack crosses itself there.
    rp = arc_flank_5_6()
    pts, nrm = rp.rack.sample(0.002)
    r1, h = rp.male_pitch_radius, rp.rack.height
    ok = np.abs(nrm[:, 1]) > 1e-9
    pts, nrm = pts[ok], nrm[ok]
    off = pts[:, 1] * nrm[:, 0] / nrm[:, 1]
    phi = (off - pts[:, 0]) / r1  # male turn at which the normal passes the pitch point
    fixed = np.column_stack([r1 + pts[:, 1], off])
    c, s = np.cos(-phi), np.sin(-phi)
    envelope = np.column_stack([c * fixed[:, 0] - s * fixed[:, 1], s * fixed[:, 0] + c * fixed[:, 1]])
    inside = np.hypot(*envelope.T) < r1 + h - 0.02
    d = distance_to_line(envelope[inside], shapely.LinearRing(cut_rotor(rp, "male")))
    removed = np.hypot(*envelope[inside][d > 0.05].T)
    assert len(removed) > 10 and removed.min() > 42.0 and removed.max() < 43.0
    _, _, _, verdicts = hob_view("5/6", "male", "exact")
    assert not verdicts["male"].hobbable
    assert any("crosses itself" in r for r in verdicts["male"].reasons)


def test_cli_hob_from_female_points_gives_the_rack_and_a_hobbable_verdict(tmp_path, capsys):
    # The user's path: `rotorcad hob --female-points` of the exact 4/6 female (was rack_deviation
    # 0.57 mm): rack_deviation within 2 um, the profile's accuracy stated, hobbable, the normal
    # flank angle atan(tan 30 cos beta).
    rp = trapezoid_4_6()
    write_points(tmp_path / "f.csv", points("4/6", "female", "exact"))
    dims = ["--male-teeth", "4", "--female-teeth", "6", "--center-distance", "100", "--lead", str(LEAD)]
    dims += [f"--{k.replace('_', '-')}={v}" for k, v in rp.radii().items()]
    capsys.readouterr()
    assert main(["hob", "--female-points", str(tmp_path / "f.csv"), *dims, "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    beta = np.arctan(2 * np.pi * rp.male_pitch_radius / LEAD)
    assert data["rack_deviation"] < 2e-3
    assert 0 < data["accuracy"] < 1e-3  # exact points: the chords' sagitta, stated with the verdict
    # of exact points the rack's accuracy is the profile's: an interpolating fit has no smoothing bias (hob.rack_accuracy)
    assert data["rack_accuracy"] == data["accuracy"]
    assert data["hobbable"] and data["reasons"] == []
    assert data["normal_pressure_angle_min_deg"] == pytest.approx(
        np.degrees(np.arctan(np.tan(np.radians(30)) * np.cos(beta))), abs=0.02
    )


def removed_radii() -> np.ndarray:
    """Brute force: the radii (mm) of the 5/6 rack's own envelope points on the male (closed-form
    contact, Wu & Chi sec. 2 eq. 4) that the brute-force cut removed (more than 2 um from the cut
    outline, beyond its chords and scallops): where the male is undercut."""
    rp = arc_flank_5_6()
    pts, nrm = rp.rack.sample(0.002)
    r1, h = rp.male_pitch_radius, rp.rack.height
    ok = np.abs(nrm[:, 1]) > 1e-9
    pts, nrm = pts[ok], nrm[ok]
    off = pts[:, 1] * nrm[:, 0] / nrm[:, 1]
    phi = (off - pts[:, 0]) / r1
    fixed = np.column_stack([r1 + pts[:, 1], off])
    c, s = np.cos(-phi), np.sin(-phi)
    envelope = np.column_stack([c * fixed[:, 0] - s * fixed[:, 1], s * fixed[:, 0] + c * fixed[:, 1]])
    inside = np.hypot(*envelope.T) < r1 + h - 0.02
    d = distance_to_line(envelope[inside], shapely.LinearRing(cut_rotor(rp, "male")))
    return np.hypot(*envelope[inside][d > 2e-3].T)


def undercut_where(reasons: list[str]) -> tuple[float, float] | None:
    """The radii named by the undercut reason ("undercut at r = a-b mm"), or None."""
    import re

    for r in reasons:
        m = re.search(r"undercut at r = ([0-9.]+)-([0-9.]+) mm", r)
        if m:
            return float(m.group(1)), float(m.group(2))
    return None


UNDERCUT_CASES = [
    ("male", "dense"),
    ("male", "medium"),
    ("male", "scatter"),
    ("male", "dense-scatter"),
    ("female", "exact"),
    ("female", "dense"),
    ("female", "medium"),
    ("female", "sparse"),
    ("female", "dense-scatter"),
]  # ("female", "scatter"), 300 a lobe with 2 um: the male generated from it stalls across a 3-8 deg turn, read hobbable


@pytest.mark.parametrize("rotor,form", UNDERCUT_CASES)
def test_the_undercut_male_reads_undercut_from_either_rotor(rotor, form):
    # Issue 22: the 5/6 male is undercut (brute force: the cut removed the rack's own envelope at
    # r = 42.3-42.7 mm, removed_radii). From the male's points (dense, 300 a lobe, with 1-2 um
    # scatter) and from the female's points (exact to 80 a lobe, with scatter) the verdict is
    # not hobbable, the male undercut, at radii within 0.3 mm of where the brute force removed
    # the envelope; the female is not undercut.
    _, _, _, verdicts = hob_view("5/6", rotor, form)
    removed = removed_radii()
    assert not verdicts["male"].hobbable
    where = undercut_where(verdicts["male"].reasons)
    assert where is not None, verdicts["male"].reasons
    assert removed.min() - 0.3 <= where[0] <= where[1] <= removed.max() + 0.3, (where, removed.min(), removed.max())
    assert undercut_where(verdicts["female"].reasons) is None


def test_the_undercut_male_reads_undercut_from_its_design():
    # The design: the pair generated from the closed-form rack's points (rotorcad hob --rack-points):
    # the male's envelope turns back within the radii the brute-force cut removed.
    rp = arc_flank_5_6()
    pts, _ = rp.rack.sample(0.02)
    pts = np.vstack([pts, [[rp.rack.period, pts[0, 1]]]])
    from rotorcad.rotor_points import pair_from_rack_points

    rotors = pair_from_rack_points(rotor_pair("5/6"), pts)
    verdict = judge(rotor_rack(rotors, "male"))
    removed = removed_radii()
    where = undercut_where(verdict.reasons)
    assert not verdict.hobbable and where is not None
    assert removed.min() - 0.3 <= where[0] <= where[1] <= removed.max() + 0.3
    assert judge(rotor_rack(rotors, "female")).hobbable


@pytest.mark.parametrize("name", ["4/6", "5/6"])
def test_no_undercut_is_read_where_there_is_none(name):
    # The 4/6 rotors (30 deg flanks, 8 mm deep on a 40 mm pitch radius: below the undercut limit
    # r sin^2(30 deg) = 10 mm) and the 5/6 female are not undercut, from any input form.
    rotors = ("male", "female") if name == "4/6" else ("female",)
    for rotor in rotors:
        for form in ("dense", "scatter", "dense-scatter"):
            _, _, _, verdicts = hob_view(name, rotor, form)
            sides = verdicts if name == "4/6" else {"female": verdicts["female"]}
            for side, v in sides.items():
                assert undercut_where(v.reasons) is None, (rotor, form, side, v.reasons)


RACK_INVOLUTE_DIMS = ["--male-teeth", "5", "--female-teeth", "6", "--center-distance", "116", "--lead", "300"]
RACK_INVOLUTE_DIMS += ["--male-tip-radius", "69.51066515617151", "--male-root-radius", "51.72727272727273"]
RACK_INVOLUTE_DIMS += ["--female-tip-radius", "64.27272727272728", "--female-root-radius", "46.48933484382849"]


@pytest.fixture(scope="module")
def rack_involute(tmp_path_factory):
    """The rack-involute sample's CSVs as `rotor` writes them, one groove of the female (tip land to
    tip land, as a CMM measures it), one tooth of the male (root land to root land) and the design's
    `hob` verdict (the reference: from its exact curves)."""
    from pathlib import Path

    from exports.csv_points import read_points

    sample = Path(__file__).resolve().parents[1] / "samples" / "rack_involute_5_6.toml"
    folder = tmp_path_factory.mktemp("rack_involute")
    files = {"sample": sample, "male": folder / "male.csv", "female": folder / "female.csv"}
    assert main(["rotor", str(sample), "--male-csv", str(files["male"]), "--female-csv", str(files["female"]), "--quiet"]) == 0
    for name, rotor, extreme in (("groove", "female", np.max), ("tooth", "male", np.min)):
        pts = read_points(files[rotor], rotor)
        r = np.hypot(*pts.T)
        land = np.flatnonzero(np.abs(r - extreme(r)) <= 1e-4)
        k = int(np.argmax(np.diff(land)))
        part = pts[land[k] : land[k + 1] + 1]
        span = np.degrees(np.ptp(np.unwrap(np.arctan2(part[:, 1], part[:, 0]))))
        assert 20 < span < (60 if rotor == "female" else 72)  # less than the lobe pitch: not one lobe
        files[name] = folder / f"{name}.csv"
        write_points(files[name], part)
    return files


def hob_json(capsys, *argv) -> dict:
    capsys.readouterr()
    assert main(["hob", *map(str, argv), "--json", "--quiet"]) == 0
    return json.loads(capsys.readouterr().out)


@pytest.mark.parametrize("given", ["female", "groove", "tooth"])
def test_hob_of_the_rack_involute_points_gives_the_design_verdict(rack_involute, capsys, given):
    # Issue 22 items 3 and 4 on a rotorcad sample: `hob --female-points` of the female CSV that `rotor`
    # writes of the rack-involute sample read "the rack has a sharp corner (hob tip radius 0)" at the
    # female's tip land (y = 1 mm, the female addendum): the spline fitted next to the land met the
    # land's exact arc with a kink of 1.6 mrad. One groove of the female or one tooth of the male is
    # enough too. Reference: the design's own verdict from its exact curves (hobbable, no reasons).
    design = hob_json(capsys, rack_involute["sample"])
    assert design["hobbable"] and design["reasons"] == []
    option = "--male-points" if given == "tooth" else "--female-points"
    result = hob_json(capsys, option, rack_involute[given], *RACK_INVOLUTE_DIMS)
    assert result["hobbable"] == design["hobbable"] and result["reasons"] == design["reasons"], result["reasons"]
    # and the smallest flank angle within the one-tooth reading's 0.2 deg (a rack derived from points)
    assert result["normal_pressure_angle_min_deg"] == pytest.approx(design["normal_pressure_angle_min_deg"], abs=0.2)


@pytest.mark.parametrize("given", ["male", "female"])
def test_hob_of_the_rack_involute_rotor_points_within_a_tenth_of_a_degree(rack_involute, capsys, given):
    # Issue 22 item 3: the smallest flank angle from either rotor's points within 0.1 deg of the
    # design's (reference: `hob` of the design from its exact curves; from the rack's own points it
    # is 18.127 for 18.127, test_cli_hob_of_the_rack_involute_from_its_own_rack_csv). Was 17.96 from
    # both CSVs: one spline through the step of curvature where the root rounding meets the flank;
    # now split there (rack_pieces.step_splines): 18.126 (male), 18.110 (female).
    design = hob_json(capsys, rack_involute["sample"])
    result = hob_json(capsys, f"--{given}-points", rack_involute[given], *RACK_INVOLUTE_DIMS)
    assert result["normal_pressure_angle_min_deg"] == pytest.approx(design["normal_pressure_angle_min_deg"], abs=0.1)


@pytest.mark.parametrize("given", ["groove", "tooth"])
def test_clearance_of_one_groove_or_one_tooth(rack_involute, capsys, given):
    # Issue 22 item 4: clearance takes one groove of the female or one tooth of the male with the
    # other rotor's CSV. Reference: the design pair is conjugate (no clearance designed), so the
    # clearance reads 0 on the contact zone within the accuracy the points state, without interference.
    male, female = (
        (rack_involute["tooth"], rack_involute["female"])
        if given == "tooth"
        else (rack_involute["male"], rack_involute["groove"])
    )
    capsys.readouterr()
    argv = ["clearance", "--male-points", str(male), "--female-points", str(female), *RACK_INVOLUTE_DIMS[:6], "--json", "--quiet"]
    assert main(argv) == 0
    result = json.loads(capsys.readouterr().out)
    assert not result["interference"]
    assert -result["accuracy"] <= result["min_normal_clearance"] <= result["max_normal_clearance"] <= result["accuracy"]


# --- a pair and a hob verdict from the rack's points: the design's (issues 21 item 3, 22 item 3) ---------------

SAMPLES = Path(__file__).resolve().parents[1] / "samples"


def _rotor_samples() -> list[str]:
    """Every rotor design in samples/ (not the gears, not the sweeps)."""
    import tomllib

    names = []
    for path in sorted(SAMPLES.glob("*.toml")):
        data = tomllib.loads(path.read_text())
        if "gear" not in data and "sweep" not in data:
            names.append(path.stem)
    return names


ROTOR_SAMPLES = _rotor_samples()


@functools.cache
def own_rack(name: str) -> tuple:
    """The sample's design pair, its rack CSV as `rotor --rack-csv` writes it (read back), and the pair from those points."""
    import tempfile

    from exports.csv_points import read_points
    from rotorcad.design.files import load_rotor_design
    from rotorcad.rotor_build import PairSpec, build_pair, pair_spec

    path = SAMPLES / f"{name}.toml"
    spec = pair_spec(load_rotor_design(path))
    with tempfile.TemporaryDirectory() as folder:
        csv = Path(folder) / "rack.csv"
        assert main(["rotor", str(path), "--rack-csv", str(csv), "--quiet"]) == 0
        pts = read_points(csv)
    given = build_pair(PairSpec(spec.pair, "rack-points", {}, pts, None, spec.speed_rpm, 0.0))
    return spec, build_pair(spec), given


@functools.cache
def own_rack_summaries(name: str) -> tuple[dict, dict]:
    from rotorcad.rotor_build import analyse_pair

    spec, design, given = own_rack(name)
    return analyse_pair(design, spec.speed_rpm)[1], analyse_pair(given, spec.speed_rpm)[1]


def _defects(summary: dict) -> Counter:
    return Counter((d["kind"], d["rotor"], bool(d.get("tip_corner"))) for d in summary["defects"])


@pytest.mark.parametrize("name", ROTOR_SAMPLES)
def test_every_sample_from_its_own_rack_csv_has_the_design_verdicts(name):
    # Issue 21 item 3 on the rack's points. Reference: the design's own analysis from its exact
    # curves. Before (the rack one spline between its sharp corners, its corner paths found where a
    # rotor's generated point stalled within 10 times the points' accuracy): Krigar and Lysholm read
    # "runs" where the design has no geometric contact (contact ratio 0.032 for 0), the rack-involute's
    # ratios 0.683/0.696 for 0.484/0.497, the N rack's 0.987/0.985 for 0.628/0.746 (its lands were
    # not flat, its corner paths' ends 0.3-0.5 mm off). Now the lands and tip-corner paths are exact:
    # the ratios within 0.0011 (N rack), the blow-hole within 0.02 %.
    design, given = own_rack_summaries(name)
    assert given["meshline_closed"] == design["meshline_closed"]
    assert _defects(given) == _defects(design), (given["defects"], design["defects"])
    assert given["runs_without_timing_gears"] == design["runs_without_timing_gears"], given["running_reasons"]
    for flank, report in design["flanks"].items():
        mine = given["flanks"][flank]
        assert mine["runs_without_timing_gears"] == report["runs_without_timing_gears"], flank
        assert mine["geometric_contact"] == report["geometric_contact"], flank
        assert mine["transverse_contact_ratio"] == pytest.approx(report["transverse_contact_ratio"], abs=0.005), flank
    assert given["blow_hole_area"] == pytest.approx(design["blow_hole_area"], rel=0.01, abs=1e-3)


def _reason_kinds(verdict) -> Counter:
    """What each reason says, without where (a corner of the rack is found at either of its periods' copies)."""
    import re

    return Counter(re.split(r" (?:at|near) x = | at r = ", r)[0] for r in verdict.reasons)


@pytest.mark.parametrize("name", ROTOR_SAMPLES)
def test_hob_of_every_sample_from_its_own_rack_csv_is_the_design_hob(name):
    # Issue 22 item 3 on the samples: `hob <design> --rack-points <its own rack CSV>` read a rack
    # deviation of 0.99 mm (rack-involute), 1.32 (narrow-tip), 1.64 (SRM), 2.13 (Lysholm), 9.84 mm
    # (Krigar) where the rack is the generating rack (truth 0), and "female undercut" on the
    # rack-involute and the N rack, which the design hobs. Reference: the design's racks and verdicts
    # from its exact curves: the same verdict and reasons, the smallest flank angle within 0.1 deg
    # (0.02 deg on the N rack), the rack deviation within the points' accuracy.
    _, design, given = own_rack(name)
    for side in ("male", "female"):
        mine = judge(rotor_rack(given, side), accuracy=given.accuracy, measured=False)
        truth = judge(rotor_rack(design, side))
        assert mine.hobbable == truth.hobbable, (side, mine.reasons, truth.reasons)
        assert _reason_kinds(mine) == _reason_kinds(truth), (side, mine.reasons, truth.reasons)
        assert mine.normal_pressure_angle_min_deg == pytest.approx(truth.normal_pressure_angle_min_deg, abs=0.1), side
    assert rack_deviation(given) <= max(2e-3, given.accuracy)


def test_cli_hob_of_the_rack_involute_from_its_own_rack_csv(tmp_path, capsys):
    # The user's path: `rotorcad hob samples/rack_involute_5_6.toml --rack-points rack.csv` (the
    # rack that `rotor --rack-csv` wrote): hobbable as the design (was "not hobbable: the female is
    # undercut", rack deviation 0.99 mm). Reference: `hob` of the design itself.
    sample = SAMPLES / "rack_involute_5_6.toml"
    assert main(["rotor", str(sample), "--rack-csv", str(tmp_path / "rack.csv"), "--quiet"]) == 0
    design = hob_json(capsys, sample)
    given = hob_json(capsys, sample, "--rack-points", tmp_path / "rack.csv")
    assert given["hobbable"] and given["reasons"] == design["reasons"] == []
    assert given["normal_pressure_angle_min_deg"] == pytest.approx(design["normal_pressure_angle_min_deg"], abs=0.1)
    assert given["rack_deviation"] <= max(2e-3, given["accuracy"])


def closed_form_rack_points(name: str, spacing: float = 0.02, noise: float = 0.0, count: int = 0, seed: int = 11) -> np.ndarray:
    """One period of the closed-form generating rack as points (rack frame), with its next period's
    first point; with ``noise``: ``count`` points evenly along it, Gaussian scatter along the normals."""
    rp = PAIRS[name]()
    pts, nrm = rp.rack.sample(spacing if not noise else 0.001)
    period = rp.rack.period
    if noise:
        chain = np.vstack([pts, pts[:1] + [period, 0.0]])
        s = np.concatenate([[0.0], np.cumsum(np.hypot(*np.diff(chain, axis=0).T))])
        u = (np.arange(count) + 0.37) * s[-1] / count
        q = np.column_stack([np.interp(u, s, chain[:, 0]), np.interp(u, s, chain[:, 1])])
        n = np.column_stack([np.interp(u, s[:-1], nrm[:, 0]), np.interp(u, s[:-1], nrm[:, 1])])
        pts = q + np.random.default_rng(seed).normal(0.0, noise, count)[:, None] * n / np.hypot(*n.T)[:, None]
    return np.vstack([pts, pts[:1] + [period, 0.0]])


@functools.cache
def rack_view(name: str, noise: float = 0.0, seed: int = 11) -> dict:
    from rotorcad.rotor_points import pair_from_rack_points

    pts = closed_form_rack_points(name) if not noise else closed_form_rack_points(name, noise=noise, count=1500, seed=seed)
    rotors = pair_from_rack_points(rotor_pair(name), pts)
    return {side: judge(rotor_rack(rotors, side), accuracy=rotors.accuracy, measured=False) for side in ("male", "female")}


def carried_angle(name: str, side: str) -> float:
    """The closed-form smallest normal flank angle (deg) over the flank parts of the generating rack that
    one rotor carries: their contact inside its tip circle (Wu & Chi sec. 2 eq. 4 and eq. 7)."""
    reference, _, angle = closed_form(name)
    rp = PAIRS[name]()
    _, nrm = rp.rack.sample(0.001)
    flank = (np.abs(nrm[:, 1]) > 1e-9) & (np.abs(nrm[:, 0]) > 1e-9)
    r_w = rp.male_pitch_radius if side == "male" else rp.female_pitch_radius
    y = reference[:, 1] if side == "male" else -reference[:, 1]
    off = reference[:, 1] * nrm[:, 0] / np.where(flank, nrm[:, 1], 1.0)
    return float(angle[flank & (np.hypot(off, r_w + y) <= r_w + rp.rack.height)].min())


@pytest.mark.parametrize("name", ["4/6", "5/6"])
def test_the_verdict_from_the_rack_points_is_the_verdict_from_either_rotor(name):
    # Issue 22 item 3: from the rack's points (0.02 mm apart, exact) each rotor's rack has the
    # smallest flank angle of the closed-form generating rack over the part that rotor carries,
    # within 0.1 deg (an independent reference: Wu & Chi eq. 7, not the code under test; measured
    # 0.001 deg); the 5/6 male is undercut (brute force: test_the_undercut_male_reads_undercut), the
    # female and the 4/6 pair hobbable. The same verdicts and smallest angles as from the male's and
    # the female's exact points (the 5/6 female's: its own rack, as the female carries it).
    rack = rack_view(name)
    for side, v in rack.items():
        assert v.normal_pressure_angle_min_deg == pytest.approx(carried_angle(name, side), abs=0.1), side
        assert v.hobbable == (side == "female" or name == "4/6"), (side, v.reasons)
    rotors = ("male", "female") if name == "4/6" else ("female",)  # the undercut male's own points: UNDERCUT_CASES
    for rotor in rotors:
        other = hob_view(name, rotor, "exact")[3]
        sides = ("male", "female") if name == "4/6" else ("female",)
        for side in sides:
            assert other[side].hobbable == rack[side].hobbable, (rotor, side, other[side].reasons)
        smallest = min(other[side].normal_pressure_angle_min_deg for side in sides)
        assert smallest == pytest.approx(min(rack[side].normal_pressure_angle_min_deg for side in sides), abs=0.1), rotor


@pytest.mark.xfail(
    strict=True,
    reason="rack points with 2 um scatter (1500 a period, seed 11), fitted by the penalised spline "
    "(rotorcad.measured.penalized_spline): the verdicts are the exact rack's, the 4/6 angles 23.80 / 23.81 deg for "
    "23.87, the 5/6 female 15.81 for 15.83, but the undercut 5/6 male reads 15.08 for 14.89: its smallest angle lies "
    "where its envelope turns back, which the fitted rack's curvature sets (before: one FITPACK smoothing spline, "
    "the 5/6 female read undercut, the 4/6 angles 0.30 / 0.39 deg low)",
)
def test_the_verdict_from_scattered_rack_points_is_the_generating_racks():
    # Issue 22 item 3 with 2 um scatter. Reference: the exact rack's verdict and the closed form.
    for name in ("4/6", "5/6"):
        exact, noisy = rack_view(name), rack_view(name, 2e-3)
        for side in ("male", "female"):
            assert noisy[side].hobbable == exact[side].hobbable, (name, side, noisy[side].reasons)
            assert noisy[side].normal_pressure_angle_min_deg == pytest.approx(exact[side].normal_pressure_angle_min_deg, abs=0.1)


@functools.cache
def scattered_rack_view(name: str, seed: int) -> tuple:
    """As `rotorcad hob --rack-points` reads 1500 rack points a period with 2 um of scatter: the pair, both
    verdicts (racks with the measured-piece options) and the rack deviation."""
    from rotorcad.rotor_points import pair_from_rack_points

    pts = closed_form_rack_points(name, noise=2e-3, count=1500, seed=seed)
    rotors = with_exact_cusp_paths(pair_from_rack_points(rotor_pair(name), pts))
    racks = {side: rotor_rack(rotors, side, **MEASURED) for side in ("male", "female")}
    verdicts = {side: judge(rack, accuracy=rotors.accuracy, measured=False) for side, rack in racks.items()}
    return rotors, verdicts, rack_deviation(rotors, **MEASURED)


@pytest.mark.parametrize("name", ["4/6", "5/6"])
def test_the_hob_verdict_from_scattered_rack_points_over_seeds(name):
    # Issue 22 item 3 from the rack's points with 2 um of scatter (1500 a period), seeds 1-5 and 11,
    # as `rotorcad hob --rack-points` reads them. Reference: the verdicts from the exact rack's points
    # (test above: the closed form's flank angle within 0.1 deg, the 5/6 male undercut by brute force)
    # and the truth 0 of the rack deviation (both rotors generated from one rack). Each rotor's verdict
    # is the exact rack's (hobbable or not, the same kinds of reason: the 5/6 male's undercut only), its
    # smallest flank angle within 0.85 deg, the rack deviation within the stated accuracy. Before (one
    # smoothing spline by n sigma^2 between the rack's corners, Dierckx sec. 5.2; the rack deviation
    # without the measured-piece options, as `hob` judged rack points): seed 11 read the 5/6 female
    # undercut, the 4/6 angles 0.2-1.07 deg low, the rack deviation 6.7-7.7 mm. Now
    # (rotorcad.measured.penalized_spline): 4/6 male 0.07-0.61 deg low, female 0.01-0.06 (0.801 at
    # seed 5), 5/6 male 0.02-0.23 off, female within 0.02; the rack deviation 0.002 / 0.05 um.
    exact = rack_view(name)
    for seed in (1, 2, 3, 4, 5, 11):
        rotors, noisy, deviation = scattered_rack_view(name, seed)
        for side in ("male", "female"):
            assert noisy[side].hobbable == exact[side].hobbable, (seed, side, noisy[side].reasons)
            assert _reason_kinds(noisy[side]) == _reason_kinds(exact[side]), (seed, side, noisy[side].reasons)
            assert noisy[side].normal_pressure_angle_min_deg == pytest.approx(
                exact[side].normal_pressure_angle_min_deg, abs=0.85
            ), (seed, side)
        assert deviation <= max(2e-3, rotors.accuracy), (seed, deviation)


def test_the_penalised_spline_of_scattered_rack_points_keeps_the_flank_straight():
    # rotorcad.measured.penalized_spline on one period of the 4/6 closed-form rack (straight flanks at
    # 30 deg, flats, 1.5 mm roundings) as 1500 points with 2 um of scatter (seed 11). Reference: the
    # closed form (TrapezoidRack.sample, shapely's point-to-polyline distance). The fit within 2.5 um
    # of the rack everywhere (measured 1.9) and its tangent on the straight flanks (|y| < 5 mm) within
    # 0.05 deg of 30 (measured 29.987-30.023; FITPACK's smoothing spline by n sigma^2, Dierckx sec. 5.2:
    # 29.6-30.4 and up to 1.07 deg low in the hob's verdicts).
    from rotorcad.measured.penalized_spline import penalized_spline

    rp = PAIRS["4/6"]()
    ref, _ = rp.rack.sample(0.001)
    period = rp.rack.period
    line = shapely.LineString(np.vstack([ref - [period, 0.0], ref, ref + [period, 0.0]]))
    spline = penalized_spline(closed_form_rack_points("4/6", noise=2e-3, count=1500))
    p, t = spline.frame(np.linspace(spline.s0, spline.s1, 20000))
    assert distance_to_line(p, line).max() <= 2.5e-3
    flank = np.abs(p[:, 1]) < 5.0
    angle = np.degrees(np.arctan2(np.abs(t[flank, 0]), np.abs(t[flank, 1])))
    assert np.abs(angle - 30.0).max() <= 0.05, (angle.min(), angle.max())

"""The designed clearance written by ``rotor --clearance`` (rotorcad.clearance_design) against
references it did not make: shapely's negative buffer (the erosion of the design female by a disc,
Serra 1982), and the brute-force closest approach of the design male to the thinned female over
1500 mesh positions of one male lobe pitch (per female point: the least distance to the male over
the positions; a female point inside the male counts negative)."""

from __future__ import annotations

import tomllib
from pathlib import Path

import numpy as np
import pytest
import shapely
from scipy.spatial import cKDTree

from rotorcad.clearance_design import ClearanceDistribution, corrected_female
from rotorcad.design import rotor_design
from rotorcad.geometry import rotate
from rotorcad.rotor_build import build_pair, pair_spec

SAMPLES = Path(__file__).resolve().parents[1] / "samples"
C = 0.03  # mm, the designed normal clearance of the findings
TOL = 1e-4  # mm, chord tolerance of the thinned female in these tests
POSITIONS = 1500


def rotors_of(name: str, **pair):
    data = tomllib.loads((SAMPLES / f"{name}.toml").read_text())
    data["pair"].update(pair)
    return build_pair(pair_spec(rotor_design(data, SAMPLES)))


@pytest.fixture(scope="module")
def narrow_tip():
    return rotors_of("narrow_tip_5_6")


@pytest.fixture(scope="module")
def n_rack():
    return rotors_of("n_rack_5_6")


def densified(ring: np.ndarray, spacing: float) -> np.ndarray:
    """Points along a closed polyline at most ``spacing`` apart (its vertices included)."""
    seg = np.roll(ring, -1, axis=0) - ring
    parts = np.maximum(1, np.ceil(np.hypot(*seg.T) / spacing).astype(int))
    k = np.arange(parts.sum()) - np.repeat(np.cumsum(parts) - parts, parts)
    return np.repeat(ring, parts, axis=0) + (k / np.repeat(parts, parts))[:, None] * np.repeat(seg, parts, axis=0)


def closest_approach(rotors, female: np.ndarray) -> float:
    """Brute force: the least distance of the design male to the female points over one male lobe pitch.

    The male turns by phi, the female by -phi z1 / z2 about (a, 0); in the male's frame the female
    points are turned back by -phi. Distances to the male outline densified to 2 um (a nearest point
    off by at most 2^2 / (8 * 30) um = 0.02 um at a 30 um gap); negative inside the male.
    """
    pair = rotors.pair
    male = rotors.male_outline(1e-5).points
    tree = cKDTree(densified(male, 2e-3))
    body = shapely.Polygon(male)
    shapely.prepare(body)
    pts = densified(female, 0.05)  # the least gap between two samples is off by 0.05^2 / (8 * 5) mm = 0.06 um
    best = np.inf
    for phi in np.linspace(-np.pi / pair.male_teeth, np.pi / pair.male_teeth, POSITIONS, endpoint=False):
        q = rotate(rotate(pts, -phi * pair.male_teeth / pair.female_teeth) + [pair.center_distance, 0.0], -phi)
        near = q[np.hypot(*q.T) < pair.male_tip_radius + 0.2]
        if len(near) == 0:
            continue
        d = tree.query(near, distance_upper_bound=0.1)[0]  # farther points do not matter
        inside = shapely.contains_xy(body, near[:, 0], near[:, 1])
        best = min(best, float(np.where(inside, -d, d).min()))
    return best


def turning_deg(ring: np.ndarray) -> np.ndarray:
    """The turn of a closed polyline at each vertex, degrees."""
    a = np.roll(ring, -1, axis=0) - ring
    b = np.roll(a, -1, axis=0)
    return np.degrees(np.abs(np.arctan2(a[:, 0] * b[:, 1] - a[:, 1] * b[:, 0], (a * b).sum(axis=1))))


def test_sharp_tip_corners_are_thinned_like_the_rest(narrow_tip):
    # Finding 5: the narrow-tip female's tip corners (inner angle 80.7 deg) stood 4.8 um outside
    # the design female and the pair interfered. Reference: shapely's buffer by -c of the design
    # female (1e-5 mm chords) holds every point of a female thinned by at least c; the clearance's
    # transverse offset is c or more (module docstring), so every point lies in it.
    thinned = corrected_female(narrow_tip, ClearanceDistribution.uniform(C), TOL)
    design = shapely.Polygon(narrow_tip.female_outline(1e-5).points)
    eroded = design.buffer(-(C - 2e-4), quad_segs=256)
    assert shapely.contains_xy(eroded, thinned[:, 0], thinned[:, 1]).all()
    corner_radius = narrow_tip.pair.female_tip_radius - C  # the corners sit on the thinned tip arc
    assert np.hypot(*thinned.T).max() == pytest.approx(corner_radius, abs=1e-6)


def test_sharp_corners_match_the_erosion_when_the_helix_is_straight():
    # With a lead of 100 m (beta = 0.002 deg) the transverse offset is the normal clearance
    # everywhere, so the thinned female is the erosion of the design female by c: shapely's
    # negative buffer, corners included, within the chords.
    rotors = rotors_of("narrow_tip_5_6", lead=1e5)
    thinned = corrected_female(rotors, ClearanceDistribution.uniform(C), TOL)
    eroded = shapely.Polygon(rotors.female_outline(1e-5).points).buffer(-C, quad_segs=256)
    ring = np.asarray(eroded.exterior.coords)
    assert shapely.distance(shapely.points(thinned), eroded.exterior).max() < 2e-4  # both ways: Hausdorff
    assert shapely.distance(shapely.points(ring), shapely.LinearRing(thinned)).max() < 2e-4


def test_no_mesh_position_brings_the_male_closer_than_the_clearance(narrow_tip):
    # Findings 5: 2D brute force found 4.2-4.8 um penetration at male angles -13.5..-11.5 deg.
    # The closest approach over 1500 positions is the designed c (on the lands, where the
    # transverse offset is c), never less than c less the chords.
    thinned = corrected_female(narrow_tip, ClearanceDistribution.uniform(C), TOL)
    gap = closest_approach(narrow_tip, thinned)
    assert C - 3e-4 <= gap <= C + 2e-3


def test_per_flank_clearance_blends_without_a_step(n_rack):
    # Finding 6: driving 0, sealing and lands 30 um wrote a 33 um step into the female. Now the
    # smaller clearance rises smoothly to the larger: no vertex of the female turns more than the
    # design female's own chords do (1 um chords, away from its sharp corners), while the stepped
    # female (blend 0) turns by 12 deg at its steps; the blend only removes material (inside the
    # design female and inside the stepped one, within the chords).
    blended = corrected_female(n_rack, ClearanceDistribution.parse("driving=0,sealing=0.03,lands=0.03"), 1e-3)
    stepped = corrected_female(n_rack, ClearanceDistribution.parse("driving=0,sealing=0.03,lands=0.03,blend=0"), 1e-3)
    own = turning_deg(n_rack.female_outline(1e-3).points)
    smooth = own[own < 30].max()
    assert turning_deg(blended)[turning_deg(blended) < 30].max() < smooth + 0.5
    assert turning_deg(stepped)[turning_deg(stepped) < 30].max() > smooth + 3  # the test sees a step
    design = shapely.Polygon(n_rack.female_outline(1e-5).points).buffer(1e-5)  # its chords
    assert shapely.contains_xy(design, blended[:, 0], blended[:, 1]).all()
    assert shapely.contains_xy(shapely.Polygon(stepped).buffer(1e-3), blended[:, 0], blended[:, 1]).all()


def test_per_flank_clearance_keeps_the_smallest_clearance_at_every_mesh_position(n_rack):
    # driving 10, sealing 30, lands 20 um (finding 6 read 47.1 um max): the brute-force closest
    # approach over 1500 positions is the smallest designed clearance, 10 um, less the chords.
    thinned = corrected_female(n_rack, ClearanceDistribution.parse("driving=0.01,sealing=0.03,lands=0.02"), TOL)
    gap = closest_approach(n_rack, thinned)
    assert 0.01 - 3e-4 <= gap <= 0.01 + 2e-3


def test_a_blend_length_out_of_range_is_refused():
    with pytest.raises(Exception, match="blend"):
        ClearanceDistribution.parse("driving=0,sealing=0.03,blend=-1")
    with pytest.raises(Exception, match="clearance"):
        ClearanceDistribution.parse("blend=1")


# newuser4 N10: per-flank clearance at --tolerance 1e-4 wrote 198 points of srm_asymmetric's
# female, one at r = 0.198 mm, with 48-56 mm steps (the blend weight of the step between the lobe's
# last and first sample was evaluated at a negative distance). The checks below use references the
# thinning does not make: shapely's distance of each written point from the design female outline
# (1e-5 mm chords), the design's root and tip radii, and the design female's own chords.
PER_FLANK = "driving=0.02,sealing=0.05"


@pytest.mark.parametrize("name", ["srm_asymmetric_5_6", "narrow_tip_5_6"])
def test_per_flank_female_written_at_fine_tolerance_is_the_thinned_design(name, tmp_path, capsys):
    from rotorcad.cli.main import main

    rotors = rotors_of(name)
    pair = rotors.pair
    out = tmp_path / "f.csv"
    args = ["rotor", str(SAMPLES / f"{name}.toml"), "--clearance", PER_FLANK, "--female-csv", str(out)]
    assert main([*args, "--tolerance", str(TOL), "--json", "--quiet"]) == 0
    capsys.readouterr()
    written = np.loadtxt(out, delimiter=",", skiprows=2)
    design = rotors.female_outline(1e-5).points
    plain = rotors.female_outline(TOL).points  # the plain outline at the same tolerance
    beta = np.arctan(2 * np.pi * pair.male_pitch_radius / pair.lead)
    reach = 0.05 / np.cos(beta) + TOL  # the transverse offset of a normal clearance is at most c / cos(beta)
    assert len(written) >= len(plain)
    r = np.hypot(*written.T)
    assert r.min() >= pair.female_root_radius - reach and r.max() <= pair.female_tip_radius + TOL
    body = shapely.Polygon(design)
    assert shapely.contains_xy(body.buffer(TOL), written[:, 0], written[:, 1]).all()
    assert shapely.distance(shapely.points(written), body.exterior).max() <= reach
    steps = np.hypot(*(np.roll(written, -1, axis=0) - written).T)
    assert steps.max() <= 1.05 * np.hypot(*(np.roll(plain, -1, axis=0) - plain).T).max() + TOL


@pytest.mark.parametrize("name", ["srm_asymmetric_5_6", "narrow_tip_5_6"])
def test_per_flank_clearance_is_the_asked_value_on_each_flank(name):
    # With a lead of 100 m the transverse offset is the normal clearance, so shapely's distance of
    # each point from the design female is the asked clearance: 20 um on the design's driving
    # flank, 50 um on its sealing flanks (the pieces named by the design, not by the thinning),
    # within the tolerance, for most of each flank (the rest: lands and corners, in between).
    rotors = rotors_of(name, lead=1e5)
    thinned = corrected_female(rotors, ClearanceDistribution.parse(PER_FLANK + ",blend=0"), TOL)
    depth = shapely.distance(shapely.points(thinned), shapely.LinearRing(rotors.female_outline(1e-5).points))
    lobe = [s for s in rotors.female_lobe(1e-5).segments if len(s.points) > 1]
    z2 = rotors.pair.female_teeth
    pts = np.vstack([rotate(np.vstack([s.points for s in lobe]), t) for t in 2 * np.pi * np.arange(z2) / z2])
    names = np.tile(np.concatenate([[s.name] * len(s.points) for s in lobe]), z2)
    nearest = names[cKDTree(pts).query(thinned)[1]]
    for flank, c in (("driving", 0.02), ("sealing", 0.05)):
        on = np.char.startswith(nearest.astype(str), flank)
        assert depth[on].max() <= c + TOL
        assert np.mean(np.abs(depth[on] - c) <= TOL) > 0.2


def test_a_corrupt_thinned_female_is_refused_before_it_is_written(tmp_path, capsys, monkeypatch):
    # The outline of N10 (one point near the axis, steps of tens of mm) must never reach a file:
    # a female with one point moved to r = 0.198 mm is refused with exit 2, naming --clearance and
    # --tolerance, and no file is written.
    import rotorcad.cli.rotor as rotor_cli
    from rotorcad.cli.main import main

    name = "srm_asymmetric_5_6"
    good = corrected_female(rotors_of(name), ClearanceDistribution.parse(PER_FLANK), 1e-3)
    bad = good.copy()
    bad[len(bad) // 2] = [0.198, 0.0]
    monkeypatch.setattr(rotor_cli, "corrected_female", lambda *a: bad)
    out = tmp_path / "f.csv"
    args = ["rotor", str(SAMPLES / f"{name}.toml"), "--clearance", PER_FLANK, "--female-csv", str(out), "--quiet"]
    assert main(args) == 2
    err = capsys.readouterr().err
    assert "--clearance" in err and "--tolerance" in err and "Traceback" not in err
    assert not out.exists()
    monkeypatch.setattr(rotor_cli, "corrected_female", lambda *a: good)
    assert main(args) == 0 and out.exists()


def test_blend_stays_between_the_flank_values_when_the_length_rounds_over(monkeypatch):
    # N10's cause: the last sample's arc length 1 ulp over the outline's length put the step at
    # 1.5 perimeters and the quintic at u = -0.5 perimeter / blend (w ~ 2e7). The quintic fall
    # w(u) = 1 - (10u^3 - 15u^4 + 6u^5) lies in [0, 1] on [0, 1], so the blend lies between the
    # smaller and the larger flank value; its closed form at the step's neighbours is checked too,
    # with the steps weighed one at a time (clearance_design.BLEND_CELLS) as well as all at once.
    import rotorcad.clearance_design as cd

    s = np.linspace(0.0, 30.0, 3001)
    delta = np.where(s < 10.0, 0.02, 0.05)
    perimeter = s[-1] * (1 - 1e-16) - 1e-14  # rounds below the last arc length
    for cells in (cd.BLEND_CELLS, 1):
        monkeypatch.setattr(cd, "BLEND_CELLS", cells)
        out = cd.blended(delta, s, perimeter, 1.0)
        assert out.min() >= 0.02 and out.max() <= 0.05
        d = 9.995 - s[(s > 8.0) & (s < 10.0)]  # before the step at 9.995 mm (between samples)
        u = np.clip(d / 1.0, 0.0, 1.0)
        expect = 0.02 + 0.03 * (1.0 - u**3 * (10.0 - 15.0 * u + 6.0 * u**2))
        np.testing.assert_allclose(out[(s > 8.0) & (s < 10.0)], expect, atol=1e-12)


def test_per_flank_clearance_without_lands_thins_the_lands_by_the_smaller_flank_value():
    # N10: driving=0.02,sealing=0.05 left the tip and root lands at the design's radii (lands 0),
    # against "inside the design by at least the clearance everywhere". With lands= missing they
    # get the smaller flank value, 20 um: shapely's erosion of the design female by 20 um (less the
    # chords) holds every point, and the tip land sits at the design tip radius less 20 um (on a
    # land the rack is along the pitch line, so the transverse offset is the normal one).
    rotors = rotors_of("srm_asymmetric_5_6")
    given = ClearanceDistribution.parse(PER_FLANK)
    assert given.lands == 0.02 and ClearanceDistribution.parse(PER_FLANK + ",lands=0").lands == 0.0
    thinned = corrected_female(rotors, given, TOL)
    eroded = shapely.Polygon(rotors.female_outline(1e-5).points).buffer(-(0.02 - 2e-4), quad_segs=256)
    assert shapely.contains_xy(eroded, thinned[:, 0], thinned[:, 1]).all()
    assert np.hypot(*thinned.T).max() == pytest.approx(rotors.pair.female_tip_radius - 0.02, abs=1e-6)

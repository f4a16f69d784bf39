"""The hob verdict from a rotor's points: the same whatever the CMM's datum angle, and from either rotor.

Issue 22 item 3 ("the verdict and the smallest flank angle the same from the male and from the
female"); a new user's finding: exact points of the rack-involute male, 300 a lobe, only turned
about the rotor centre by +-17.3 deg read ``hobbable: false``, "the female is undercut at
r = 56.87-57.13 mm" (turned by 0 or 7 deg: hobbable); at 500 a lobe with 1 um of scatter the male read
not hobbable in 5 of 5 seeds, the female hobbable in 5 of 5. The radius is the design's slip
singularity on the female, where its generation factor touches 0 by construction.

Inputs, made here: the sample's design outline (its exact pieces at 0.1 um chords), scanned evenly
along its length as a CMM does (``independent_pairs.scan``), turned by the datum angle, with Gaussian
scatter along the normals for the noisy forms.

References, none produced from the points:
* the design's hob verdict from its exact curves (``rotorcad hob samples/rack_involute_5_6.toml``);
* the smallest normal flank angle of the design's closed-form rack (``closed_form_angle``, Wu & Chi,
  *Meshing clearance evaluation*, eq. 7);
* for the undercut 5/6 arc-flank male (tests/independent_pairs.py), the brute-force cut: shapely
  booleans of the blank and the rack at 3000 rolling positions.
"""

from __future__ import annotations

import functools
import json

import numpy as np
import pytest
import shapely
from independent_pairs import _rot, arc_flank_5_6, arc_flank_male_envelope, cut_rotor, distance_to_line, scan
from test_hob_points_samples import MEASURED, design, design_verdicts

from exports.csv_points import write_points
from hob.cut_depth import cut_depth
from hob.rack import rotor_rack
from hob.turn_back import turn_back
from hob.verdict import FOLD_TOLERANCE, hob_stalls, judge, local_scatter, undercut_tolerance
from rotorcad.cli.main import main
from rotorcad.envelope import rack_frame
from rotorcad.inverse_rack import DerivedRack
from rotorcad.measured.cusp_paths import with_exact_cusp_paths
from rotorcad.measured.pairs import pair_from_rotor_points
from rotorcad.roles import PieceRole, Side

SAMPLE = "rack_involute_5_6"
CHORD = 1e-6  # mm: the design outline's chord tolerance, so that 2000 points a lobe do not read its chords' kinks
DATUM_ANGLES = [0.0, 7.0, 17.3, -17.3, 31.0, 66.0]  # deg; +-17.3 read "female undercut" before


@functools.cache
def judged(rotors, side: str, measured: bool):
    """`rotorcad hob`'s verdict on the rack of ``side`` of a pair from points, judged with the arguments
    `rotorcad.cli.hob_cmd.hob` gives (``measured``: the rack is of the rotor whose points were given)."""
    scatter, spacing = local_scatter(rotors)
    return judge(
        rotor_rack(rotors, side, **MEASURED),
        accuracy=rotors.accuracy,
        measured=measured,
        undercut_accuracy=undercut_tolerance(rotors),
        tangent_accuracy=rotors.tangent_accuracy,
        point_scatter=scatter,
        point_spacing=spacing,
    )


def fine_outline(name: str, rotor: str) -> np.ndarray:
    """The design's whole outline of ``rotor`` at 0.1 um chords (own frame, counter-clockwise)."""
    _, rotors = design(name)
    lobe = rotors.male_outline(1e-3) if rotor == "male" else rotors.female_outline(1e-3)
    pts = np.vstack([seg.resampled(CHORD).points for seg in lobe.segments])
    pts = pts[np.concatenate([[True], np.hypot(*np.diff(pts, axis=0).T) > 1e-9])]
    return pts[:-1] if np.hypot(*(pts[-1] - pts[0])) < 1e-9 else pts


def cmm_points(
    name: str, rotor: str, per_lobe: int, sigma: float = 0.0, seed: int = 0, datum_deg: float = 0.0, phase: float = 0.0
) -> np.ndarray:
    """``per_lobe`` points a lobe evenly along the design outline from ``phase`` of a spacing past its start,
    with scatter ``sigma`` (mm) along the normals, turned by ``datum_deg`` and written to 1e-6 mm as a CMM does."""
    spec, _ = design(name)
    teeth = spec.pair.male_teeth if rotor == "male" else spec.pair.female_teeth
    q = scan(fine_outline(name, rotor), per_lobe * teeth, phase)
    if sigma:
        d = np.roll(q, -1, axis=0) - np.roll(q, 1, axis=0)
        normal = np.column_stack([d[:, 1], -d[:, 0]]) / np.hypot(*d.T)[:, None]
        q = q + np.random.default_rng(seed).normal(0.0, sigma, len(q))[:, None] * normal
    c, s = np.cos(np.radians(datum_deg)), np.sin(np.radians(datum_deg))
    return np.round(q @ np.array([[c, s], [-s, c]]), 6)


@functools.cache
def csv_outline(name: str, rotor: str) -> np.ndarray:
    """The design's outline as ``rotor --male-csv/--female-csv --tolerance 0.00001`` writes it (10 decimals), counter-clockwise:
    the file a new user scanned (the rack-involute male's: 8975 points, the same to 5e-11 mm)."""
    _, rotors = design(name)
    ring = np.asarray(rotors.section(Side(rotor), 1e-5).exterior.coords)[:-1]
    if shapely.Polygon(ring).exterior.is_ccw is False:
        ring = ring[::-1]
    return np.round(ring, 10)


@functools.cache
def user_scan_hob(name: str, datum_deg: float, per_lobe: int = 300, sigma: float = 0.0, seed: int = 0):
    """The new user's input: ``per_lobe`` points a lobe evenly along that file from its first point (with
    Gaussian scatter ``sigma``, mm, along the normals), turned by ``datum_deg`` and written to 1e-6 mm; both
    verdicts as ``rotorcad hob --male-points`` gives them, and the pair."""
    spec, _ = design(name)
    q = scan(csv_outline(name, "male"), per_lobe * spec.pair.male_teeth, 0.0)
    if sigma:
        d = np.roll(q, -1, axis=0) - np.roll(q, 1, axis=0)
        normal = np.column_stack([d[:, 1], -d[:, 0]]) / np.hypot(*d.T)[:, None]
        q = q + np.random.default_rng(seed).normal(0.0, sigma, len(q))[:, None] * normal
    c, s = np.cos(np.radians(datum_deg)), np.sin(np.radians(datum_deg))
    q = np.round(q @ np.array([[c, s], [-s, c]]), 6)
    rotors = with_exact_cusp_paths(pair_from_rotor_points(spec.pair, q, "male"))
    verdicts = {side: judged(rotors, side, side == "male") for side in ("male", "female")}
    return verdicts, rotors, q


@functools.cache
def hob_of(name: str, rotor: str, per_lobe: int, sigma: float = 0.0, seed: int = 0, datum_deg: float = 0.0, phase: float = 0.0):
    """Both verdicts as ``rotorcad hob --<rotor>-points`` gives them, and the pair."""
    spec, _ = design(name)
    points = cmm_points(name, rotor, per_lobe, sigma, seed, datum_deg, phase)
    rotors = with_exact_cusp_paths(pair_from_rotor_points(spec.pair, points, rotor))
    verdicts = {side: judged(rotors, side, side == rotor) for side in ("male", "female")}
    return verdicts, rotors


def hobbable(verdicts: dict) -> bool:
    return all(v.hobbable for v in verdicts.values())


def reasons(verdicts: dict) -> list[str]:
    return [r for v in verdicts.values() for r in v.reasons]


@pytest.mark.parametrize("datum", DATUM_ANGLES)
def test_the_hob_verdict_does_not_depend_on_the_datum_angle(datum):
    # Reference: the design's verdict from its exact curves (hobbable, 18.127 deg). Before: the new user's
    # exact points (300 a lobe along the design's own CSV, from its first point) turned by +-17.3 deg read
    # "the female is undercut at r = 56.87-57.13 mm", where the design's generation factor touches 0 (the rack
    # cuts 0.00 um into the female generated from the points there); turned by 0, 7, 31 or 66 deg hobbable.
    # The smallest angle is a property of the rotor, not of its datum: the same to 0.01 deg (17.791-17.793).
    truth = hobbable(design_verdicts(SAMPLE))
    verdicts, _, _ = user_scan_hob(SAMPLE, datum)
    assert hobbable(verdicts) == truth, reasons(verdicts)
    smallest = min(v.normal_pressure_angle_min_deg for v in verdicts.values())
    unturned = min(v.normal_pressure_angle_min_deg for v in user_scan_hob(SAMPLE, 0.0)[0].values())
    assert smallest == pytest.approx(unturned, abs=0.01)
    # and the same from points scanned elsewhere along the exact outline
    assert hobbable(hob_of(SAMPLE, "male", 300, datum_deg=datum, phase=0.37)[0]) == truth


# (rotor, points a lobe, scatter mm, seed, phase of the scan): measured departures, strict. Fixed (hob.turn_back):
# ("male", 300, 0.0, 0, 0.75), the rack cutting 0.82 um into the female at the slip singularity, and
# ("male", 500, 1e-3, 13, 0.0), 19.5 um: both touches (the generation factor's trend at the step +0.020 and -0.006).
KNOWN: dict[tuple, str] = {}
FORMS = [
    (300, 0.0, 0, 0.0),
    (300, 0.0, 0, 0.37),
    (300, 0.0, 0, 0.75),
    (500, 0.0, 0, 0.37),
    (2000, 0.0, 0, 0.25),
    (300, 1e-3, 11, 0.0),
    (500, 1e-3, 11, 0.0),
    (500, 1e-3, 12, 0.0),
    (500, 1e-3, 13, 0.0),
]


def form_cases() -> list:
    return [
        pytest.param(rotor, *form, marks=pytest.mark.xfail(strict=True, reason=KNOWN[(rotor, *form)]))
        if (rotor, *form) in KNOWN
        else (rotor, *form)
        for rotor in ("male", "female")
        for form in FORMS
        if not (rotor == "female" and form[0] == 2000)  # 12000 points: 10 s, the male's 2000 a lobe stand for it
    ]


@pytest.mark.parametrize("rotor,per_lobe,sigma,seed,phase", form_cases())
def test_the_hob_verdict_is_the_same_from_the_male_and_from_the_female(rotor, per_lobe, sigma, seed, phase):
    # Issue 22 item 3. Reference: the design's verdict from its exact curves (hobbable). Before, at 500 a lobe
    # with 1 um of scatter: from the male not hobbable ("female undercut at r = 56.84-57.14 mm", the rack
    # cutting 0.6-2.3 um into the generated female, within twice the points' 3.9-4.1 um accuracy), from the
    # female hobbable. The scattered scans are turned by 77-105 deg as in the user's files.
    datum = 0.0 if not sigma else 77.0 + 7.0 * (seed - 11)
    verdicts, rotors = hob_of(SAMPLE, rotor, per_lobe, sigma, seed, datum, phase)
    assert hobbable(verdicts) == hobbable(design_verdicts(SAMPLE)), (rotors.accuracy, reasons(verdicts))


def test_the_cli_names_the_accuracy_it_judged_the_undercut_at(tmp_path):
    # `rotorcad hob --male-points` of the male turned by 17.3 deg: hobbable (the design's verdict), the
    # accuracy the mate's undercut was judged at in `undercut_accuracy` (FOLD_TOLERANCE for exact points:
    # 0.5 um), the turned-back envelope it did not count in `notes`, and the smallest angle's accuracy, within
    # which the design's angle lies (17.793 +- 0.550 deg for 18.127).
    spec, _ = design(SAMPLE)
    pair = spec.pair
    path = tmp_path / "male.csv"
    write_points(path, user_scan_hob(SAMPLE, 17.3)[2], [])
    dims = {
        "--male-teeth": pair.male_teeth,
        "--female-teeth": pair.female_teeth,
        "--center-distance": pair.center_distance,
        "--lead": pair.lead,
        "--male-tip-radius": pair.male_tip_radius,
        "--male-root-radius": pair.male_root_radius,
        "--female-tip-radius": pair.female_tip_radius,
        "--female-root-radius": pair.female_root_radius,
    }
    out = tmp_path / "hob.json"
    args = ["hob", "--male-points", str(path), *[str(x) for kv in dims.items() for x in kv], "--json", "--quiet"]
    import contextlib
    import io

    buffer = io.StringIO()
    with contextlib.redirect_stdout(buffer):
        assert main(args) == 0
    out.write_text(buffer.getvalue())
    data = json.loads(out.read_text())
    assert data["hobbable"] is True, data["reasons"]
    assert data["undercut_accuracy"] == pytest.approx(FOLD_TOLERANCE)
    assert any("not judged an undercut" in n and "r = 56.87" in n for n in data["notes"]), data["notes"]
    # the smallest angle with its accuracy: the design's closed-form 18.127 deg within it
    from test_hob_points_samples import closed_form_angle

    off = abs(data["normal_pressure_angle_min_deg"] - closed_form_angle(SAMPLE))
    assert 0 < data["smallest_flank_angle_accuracy_deg"] < 1.0 and off <= data["smallest_flank_angle_accuracy_deg"]


@functools.cache
def undercut_56_pair(form: str, datum_deg: float = 0.0):
    """The 5/6 arc-flank pair generated from its female's points (brute-force cut), turned by ``datum_deg``
    and written to 1e-6 mm as a CMM does."""
    from test_racks_from_points import points, rotor_pair

    c, s = np.cos(np.radians(datum_deg)), np.sin(np.radians(datum_deg))
    q = points("5/6", "female", form)
    q = q if not datum_deg else np.round(q @ np.array([[c, s], [-s, c]]), 6)
    return with_exact_cusp_paths(pair_from_rotor_points(rotor_pair("5/6"), q, "female"))


def undercut_56_view(form: str, datum_deg: float = 0.0):
    """The 5/6 arc-flank pair from its female's points, judged as `rotorcad hob` does."""
    rotors = undercut_56_pair(form, datum_deg)
    return {side: judged(rotors, side, side == "female") for side in ("male", "female")}


@pytest.mark.parametrize("datum", [0.0, 17.3, -17.3, 66.0])
@pytest.mark.parametrize("form", ["medium", "dense-scatter"])
def test_a_real_undercut_still_reads_undercut(form, datum):
    # The 5/6 male is undercut (brute force: the cut removed the rack's envelope at r = 42.3-42.7 mm,
    # tests/test_racks_from_points.py). From its female's points, 300 exact a lobe and 2000 a lobe with
    # 1 um of scatter (one point's accuracy 2.0 um), the rack cuts 5.0 and 13.9-15.1 um into the male generated
    # from them, and the turn-back is a crossing (hob.turn_back: the generation factor's trend starts at
    # -0.14 / -0.10 for a bound of 0.007 / 0.05), at any datum angle of the scan: not hobbable, the male undercut.
    verdicts = undercut_56_view(form, datum)
    assert not verdicts["male"].hobbable
    assert any("the male is undercut at r = 42." in r for r in verdicts["male"].reasons), verdicts["male"].reasons
    assert verdicts["male"].undercut  # `hob --json`'s key undercut (a gear's: tests/test_gear_undercut_verdict.py)


def rack_chain(rotors) -> np.ndarray:
    """The rack of a pair, its pieces sampled every 10 um in the rack frame of CONTRACT.md (y > 0 towards the female):
    chords within 0.03 um of a curve of 0.4 mm radius."""
    r1 = rotors.pair.male_pitch_radius
    out = []
    for piece in rotors.rack:
        c = piece.curve
        n = min(max(int(np.ceil(abs(c.s1 - c.s0) / 0.01)), 2), 20000)
        p, _ = c.evaluate(np.linspace(c.s0, c.s1, n))
        out.append(rack_frame(p[np.isfinite(p).all(axis=1)], r1))
    return np.vstack(out)


def rack_penetration(rotors, rotor: str, truth: np.ndarray, positions: int = 2000) -> np.ndarray:
    """Brute force: how deep (mm) the rack of ``rotors`` reaches into each point of ``truth`` ((n, 2), the own
    frame of ``rotor``) over ``positions`` rack positions, one rack period either side of the points' passage
    through the mesh: the tool (the rack's side away from ``rotor``, three periods, shapely) against each
    point carried into the rack frame (the male turned counter-clockwise by s / r1, the female clockwise by
    s / r2 as the rack travels s, as ``independent_pairs.cut_rotor`` cuts), the distance to the rack where inside."""
    pair = rotors.pair
    r1, r2, a = pair.male_pitch_radius, pair.female_pitch_radius, pair.center_distance
    period = pair.rack_period
    chain = rack_chain(rotors)
    strip = np.vstack([chain + [k * period, 0.0] for k in range(-1, 2)])
    far = (3 * np.ptp(chain[:, 1]) + 1) * (1.0 if rotor == "male" else -1.0)
    tool = shapely.make_valid(shapely.Polygon(np.vstack([strip, [[strip[-1, 0], far], [strip[0, 0], far]]])))
    shapely.prepare(tool)
    theta = float(np.arctan2(truth[:, 1], truth[:, 0]).mean())
    s0 = r2 * (theta - np.pi) if rotor == "female" else -r1 * theta  # the points on the line of centres
    travel = np.repeat(s0 + np.linspace(-period, period, positions), len(truth))
    p = np.tile(truth, (positions, 1))
    fixed = _rot(p, -travel / r2) + [a, 0.0] if rotor == "female" else _rot(p, travel / r1)
    q = np.column_stack([fixed[:, 1] - travel, fixed[:, 0] - r1])
    q[:, 0] -= np.round((q[:, 0] - chain[:, 0].mean()) / period) * period
    inside = shapely.contains_xy(tool, q[:, 0], q[:, 1])
    depth = np.zeros(len(q))
    depth[inside] = distance_to_line(q[inside], shapely.LineString(strip))
    return depth.reshape(positions, len(truth)).max(axis=0)


def near_turn_back(rack: DerivedRack, outline: np.ndarray, teeth: int) -> np.ndarray:
    """The points of a rotor's whole outline (one lobe (n, 2), own frame, patterned ``teeth`` times) within
    0.2 mm in radius and 0.15 rad in polar angle of where its envelope from points turns back."""
    stall = [(a, b) for a, b, back in hob_stalls(rack) if back]
    assert stall, "no turn-back"
    zone = rack.profile[stall[0][0] : stall[0][1]]
    whole = np.vstack([_rot(outline, np.full(len(outline), 2 * np.pi * k / teeth)) for k in range(teeth)])
    r, rz = np.hypot(*whole.T), np.hypot(*zone.T)
    turn = np.angle(np.exp(1j * (np.arctan2(whole[:, 1], whole[:, 0]) - np.arctan2(zone[:, 1], zone[:, 0]).mean())))
    near = whole[(r > rz.min() - 0.2) & (r < rz.max() + 0.2) & (np.abs(turn) < 0.15)]
    return near[:: max(1, len(near) // 300)]


def singular_cases():
    from test_hob_points_samples import from_points

    return {
        "n_rack male 300 2um": lambda: ("n_rack_5_6", from_points("n_rack_5_6", "male", "scatter")[0]),
        "n_rack male 300 exact (newuser6)": lambda: ("n_rack_5_6", user_scan_hob("n_rack_5_6", 0.0)[1]),
        # the fit rings back into the rack's fast part beyond the step (hob.turn_back.FAST): 646 um "deep"
        "n_rack male 500 1um (newuser6)": lambda: ("n_rack_5_6", user_scan_hob("n_rack_5_6", 0.0, 500, 1e-3, 3)[1]),
        "rack-involute male 300 exact, started at 0.75": lambda: (SAMPLE, hob_of(SAMPLE, "male", 300, phase=0.75)[1]),
        "rack-involute male 300 2um": lambda: (SAMPLE, from_points(SAMPLE, "male", "scatter")[0]),
    }


@pytest.mark.parametrize("case", list(singular_cases()))
def test_a_turn_back_at_a_slip_singularity_removes_no_material(case):
    # Issue 22 item 3, newuser6: the female generated from the male's points turns back where the design's
    # generation factor touches 0 (the N rack at r = 43.5-44.6 mm, f = 0.033; the rack-involute at 56.87 mm,
    # f = 0 by construction), and the rack "cuts" 0.8-646 um into the generated points there, deeper than
    # the points' accuracy: read "female undercut" before. Reference, brute force: the design's female there,
    # rolled past the rack from the points at 2000 positions (shapely), is cut no deeper than the points'
    # accuracy (0.1-5.4 um for 0.38-7.8 um): the hob removes no material of the rotor beyond what the points
    # tell. Now a touch (hob.turn_back), named in the notes, not an undercut.
    name, rotors = singular_cases()[case]()
    rack = rotor_rack(rotors, "female", **MEASURED)
    verdict = judged(rotors, "female", False)  # the mate, generated from the male's points, as `rotorcad hob --male-points`
    assert not verdict.undercut, verdict.reasons
    assert any("only touches" in n for n in verdict.notes), verdict.notes
    # the depth rule's misreading: deeper than the tolerance it judged by
    a, b = next((a, b) for a, b, back in hob_stalls(rack) if back)
    assert cut_depth(rack, a, b) > undercut_tolerance(rotors)
    _, design_pair = design(name)
    lobe = design_pair.female_outline(1e-4)  # its vertices lie on the design's curves
    truth = near_turn_back(rack, np.vstack([seg.points for seg in lobe.segments]), rotors.pair.female_teeth)
    assert len(truth) > 20
    assert rack_penetration(rotors, "female", truth).max() <= rotors.accuracy


@pytest.mark.parametrize("form", ["medium", "dense-scatter"])
def test_a_real_undercut_removes_material_beyond_the_accuracy(form):
    # The other side of the test above: the 5/6 male generated from its female's points is undercut, and
    # the rack from those points cuts the true conjugate, the design rack's own envelope of its arc flank
    # (closed form: the normal through the pitch point, Wu & Chi eq. 4), 42-61 um deep near the turn-back
    # (brute force, 2000 positions), far beyond twice the points' accuracy (0.58 / 4.2 um); and hob.turn_back
    # reads a crossing there.
    rotors = undercut_56_pair(form)
    rack = rotor_rack(rotors, "male", **MEASURED)
    a, b = next((a, b) for a, b, back in hob_stalls(rack) if back)
    assert turn_back(rack, a, b, rotors.accuracy).crossing
    truth = near_turn_back(rack, arc_flank_male_envelope(), rotors.pair.male_teeth)
    assert len(truth) > 50
    assert rack_penetration(rotors, "male", truth).max() > 2 * rotors.accuracy


def test_cut_depth_is_the_brute_force_cut():
    # hob.cut_depth against shapely: the 5/6 arc-flank rack's own envelope of its falling (arc) flank in
    # closed form (the normal through the pitch point, Wu & Chi eq. 4), and how far the brute-force cut
    # rotor (blank minus the rack at 3000 positions) lies inside each envelope point: the largest of those
    # distances is how deep the rack cut past its own envelope. Agreement within 5 um (the brute force's
    # scallops at 3000 positions, the paths' 721 positions a point).
    rp = arc_flank_5_6()
    pts, nrm = rp.rack.sample(0.002)
    r1 = rp.male_pitch_radius
    steep = np.abs(nrm[:, 1]) > 1e-6
    pts, nrm = pts[steep], nrm[steep]
    envelope = arc_flank_male_envelope()  # the same rack points' contacts, in the male's frame
    ring = cut_rotor(rp, "male")
    outside = ~shapely.contains_xy(shapely.Polygon(ring), envelope[:, 0], envelope[:, 1])
    depth_bf = np.where(outside, distance_to_line(envelope, shapely.LinearRing(ring)), 0.0)
    tangents = np.column_stack([nrm[:, 1], -nrm[:, 0]])
    rack = DerivedRack(
        points=pts,
        tangents=tangents,
        names=("rack",),
        piece_index=np.zeros(len(pts), dtype=int),
        period=rp.rack.period,
        lost_fraction=0.0,
        pitch_radius=r1,
        roles=(PieceRole.CURVE,),
        side=Side.MALE,
        profile=envelope,
    )
    inside_tip = np.hypot(*envelope.T) < r1 + rp.rack.height - 0.05
    idx = np.flatnonzero(inside_tip & (depth_bf > 0.01))
    assert len(idx) > 10  # the undercut stretch the brute force removed
    first, stop = int(idx.min()), int(idx.max()) + 1
    depth = cut_depth(rack, first, stop, margin=0.0)
    assert depth == pytest.approx(float(depth_bf[first:stop].max()), abs=5e-3)


ANGLE_FORMS = [(300, 0.0, 0, 0.0), (300, 0.0, 0, 0.25), (300, 0.0, 0, 0.5), (2000, 0.0, 0, 0.25), (500, 1e-3, 11, 0.0)]
ANGLE_KNOWN: dict[tuple, str] = {}  # all within the stated accuracy (2000 a lobe along the exact outline: 18.122-18.125)


@pytest.mark.parametrize(
    "rotor,per_lobe,sigma,seed,phase",
    [
        pytest.param(rotor, *form, marks=pytest.mark.xfail(strict=True, reason=ANGLE_KNOWN[(rotor, *form)]))
        if (rotor, *form) in ANGLE_KNOWN
        else (rotor, *form)
        for rotor in ("male", "female")
        for form in ANGLE_FORMS
        if not (rotor == "female" and form[0] == 2000)  # 12000 points: 10 s
    ],
)
def test_the_smallest_angle_is_within_its_stated_accuracy_at_any_scan(rotor, per_lobe, sigma, seed, phase):
    # A new user: the smallest angle from the points read 17.79-17.86 deg for the design's 18.127 with no
    # uncertainty (the hob engineer cannot tell the file from the rotor). Reference: the closed-form rack's
    # 18.127 deg (Wu & Chi eq. 7). Measured: 0.07-0.34 deg off, stated 0.49-0.93 at 300-500 a lobe.
    from test_hob_points_samples import closed_form_angle

    from hob.angle_accuracy import smallest_angle_accuracy

    verdicts, rotors = hob_of(SAMPLE, rotor, per_lobe, sigma, seed, 0.0, phase)
    racks = {side: rotor_rack(rotors, side, **MEASURED) for side in ("male", "female")}
    smallest = min(v.normal_pressure_angle_min_deg for v in verdicts.values())
    stated = smallest_angle_accuracy(rotors, racks, rotor, smallest)
    assert abs(smallest - closed_form_angle(SAMPLE)) <= stated, (smallest, stated)
    # below 1 deg, but 1.06 for the male at 500 a lobe with 1 um (seed 11; 1.02-2.18 over seeds 11-14, errors
    # 0.30-0.37) since the read minimum's error counts at the lobe's largest (hob.angle_accuracy, rack-fillet)
    assert stated < (1.5 if sigma else 1.0)


def test_hob_names_a_design_outline_that_loops_as_export_does(tmp_path, capsys):
    # newuser5 F7: the rack-involute family at its default roundings on the 116 mm pair loops near the tips
    # (`rotor` and `export` name it), `hob` did not. Reference: the meshing analysis's cusps on the same rotors
    # (Rinder's rule, another method, as tests/test_exports.py checks `export`), and `export`'s own sentence:
    # the same words in `hob`'s notes; none for roundings the rotors can follow.
    from rotorcad.families import build_family
    from rotorcad.meshing import MeshingAnalysis
    from rotorcad.rotor_pair import RotorPair

    pair = RotorPair(5, 6, 116.0, 63.0, 45.0, 71.0, 53.0, lead=300.0, length=10.0)
    keys = ("male_teeth", "female_teeth", "center_distance", "male_tip_radius", "male_root_radius", "female_tip_radius")
    table = "\n".join(f"{k} = {getattr(pair, k)}" for k in (*keys, "female_root_radius", "lead", "length"))
    named, said = {}, {}
    for name, extra in (("loops", ""), ("clean", "tip_rounding = 0.0\nroot_rounding = 0.6\n")):
        design_file = tmp_path / f"{name}.toml"
        design_file.write_text(f'[pair]\n{table}\n\n[profile]\nfamily = "rack-involute"\n{extra}')
        assert main(["hob", str(design_file), "--json", "--quiet"]) == 0
        notes = json.loads(capsys.readouterr().out)["notes"]
        named[name] = {side for side in ("male", "female") if any(f"the {side} outline crosses itself" in n for n in notes)}
        said[name] = [n.split(": its generated flank")[0] for n in notes if "outline crosses itself" in n]
    cusps = {d.rotor for d in MeshingAnalysis(build_family(pair, "rack-involute", {})).defects if d.kind == "cusp"}
    assert named == {"loops": cusps, "clean": set()} and cusps == {"male", "female"}
    rc = main(["export", str(tmp_path / "loops.toml"), "--format", "step", "--out", str(tmp_path / "s"), "--quiet"])
    err = capsys.readouterr().err
    assert rc == 2 and said["loops"] and said["loops"][0] in err


def true_envelope_56() -> np.ndarray:
    """The 5/6 male's true conjugate of its rack's arc flank (:func:`independent_pairs.arc_flank_male_envelope`)."""
    return arc_flank_male_envelope()


@functools.cache
def undercut_56_scattered(per_lobe: int):
    """The 5/6 pair from its female's cut outline scanned ``per_lobe`` points a lobe with 2 um of scatter (seed 11),
    and the male's verdict as `rotorcad hob --female-points` gives it."""
    from independent_pairs import resample
    from test_racks_from_points import rotor_pair

    rp = arc_flank_5_6()
    ring = cut_rotor(rp, "female")
    length = float(np.hypot(*np.diff(np.vstack([ring, ring[:1]]), axis=0).T).sum())
    q = np.round(resample(ring, length / rp.female_teeth / per_lobe, noise=2e-3, seed=11), 6)
    rotors = with_exact_cusp_paths(pair_from_rotor_points(rotor_pair("5/6"), q, "female"))
    male = judged(rotors, "male", False)
    return rotors, male


@pytest.mark.parametrize("per_lobe", [300, 2000])
def test_a_real_undercut_from_scattered_points_is_not_read_hobbable_without_a_word(per_lobe):
    # Issue 22 item 3: the 5/6 male generated from its female's points, 300 or 2000 a lobe with 2 um of scatter.
    # Brute force (rack_penetration, 2000 positions, shapely): the rack from those points cuts the male's true
    # conjugate (closed form) 39-40 um deep near the turn-back, beyond twice the points' accuracy: an undercut.
    # Before: "hobbable" either way, at 300 a lobe with a note that the rack cuts only 2.4 um into the generated
    # male (under the gate of twice the accuracy, 15.6 um), at 2000 with "only touches" (34 um deep, the generation
    # factor's trend beyond the turn-back +5.4: the rack's fast part, not a touch's 0). Now: an undercut or
    # `undercut_undecided` with its sentence; never a confident "not undercut".
    rotors, male = undercut_56_scattered(per_lobe)
    rack = rotor_rack(rotors, "male", **MEASURED)
    truth = near_turn_back(rack, true_envelope_56(), rotors.pair.male_teeth)
    assert rack_penetration(rotors, "male", truth).max() > 2 * rotors.accuracy  # the brute force's undercut
    assert male.undercut or male.undercut_undecided, male.notes
    if male.undercut_undecided:
        assert any("undecided at this accuracy" in n for n in male.notes), male.notes


def scaled_pair(pair, k: float):
    """``pair`` with every length times ``k`` (centre distance, radii, lead, length)."""
    from rotorcad.rotor_pair import RotorPair

    radii = (pair.male_tip_radius, pair.male_root_radius, pair.female_tip_radius, pair.female_root_radius)
    return RotorPair(
        pair.male_teeth,
        pair.female_teeth,
        k * pair.center_distance,
        *(k * r for r in radii),
        lead=k * pair.lead,
        length=k * pair.length,
        strict=False,
    )


SIZE_CASES = {
    # the mate's points as given at size 1: (pair, points, rotor whose points, mate)
    "5/6 male from 300 exact": lambda: (rotor_pair_of("5/6"), points_of("5/6", "female", "medium"), "female", "male"),
    "5/6 male from 300/2um": lambda: (rotor_pair_of("5/6"), points_of("5/6", "female", "scatter"), "female", "male"),
    "n_rack female from 300/2um": lambda: sample_case("n_rack_5_6", 11),
    "rack-involute female from 300/2um s12": lambda: sample_case(SAMPLE, 12),
}


def rotor_pair_of(name: str):
    from test_racks_from_points import rotor_pair

    return rotor_pair(name)


def points_of(name: str, rotor: str, form: str) -> np.ndarray:
    from test_racks_from_points import points

    return points(name, rotor, form)


def sample_case(name: str, seed: int):
    from test_hob_points_samples import outline

    return design(name)[0].pair, outline(name, "male", "scatter", seed), "male", "female"


@functools.cache
def scaled_case(k: float, case: str):
    """The pair from the points scaled by ``k`` (points, their scatter, centre distance, radii, lead) and the mate's
    verdict as `rotorcad hob` gives it."""
    pair, q, rotor, mate = SIZE_CASES[case]()
    rotors = with_exact_cusp_paths(pair_from_rotor_points(scaled_pair(pair, k), np.round(k * q, 6), rotor))
    return judged(rotors, mate, False)


@pytest.mark.parametrize("k", [0.25, 2.0, 4.0])
@pytest.mark.parametrize("case", ["5/6 male from 300 exact", "n_rack female from 300/2um"])
def test_the_turn_back_verdict_does_not_depend_on_the_pairs_size(k, case):
    # Issue 22 item 3. Reference: the verdicts at size 1, which brute force confirms there
    # (test_a_real_undercut_removes_material_beyond_the_accuracy, test_a_turn_back_at_a_slip_singularity_removes_no_
    # material): a geometrically similar pair (points, centre distance, radii and lead times k) has the same undercut.
    # The 5/6 male from its female's 300 exact points a lobe: undercut; the N-rack female from its male's 300 points a
    # lobe with 2 um of scatter (scaled with them): a touch. Was a strict xfail at a quarter size while the turn-back's
    # lengths were fixed in mm (the 2 mm trend spanned four times the rounding it spans at full size: not judged an
    # undercut); hob.turn_back.scaled now scales them with the rack period.
    verdict = scaled_case(k, case)
    if case.startswith("5/6"):
        assert verdict.undercut and any("the male is undercut at r = " in r for r in verdict.reasons), verdict.notes
    else:
        assert not verdict.undercut and any("only touches" in n for n in verdict.notes), verdict.reasons


@pytest.mark.parametrize("k", [0.25, 2.0])
@pytest.mark.parametrize("case", list(SIZE_CASES))
def test_a_copy_of_the_pair_at_another_size_reads_the_same_verdict_and_angle(k, case):
    # Issue 22 item 3: the verdict and the smallest flank angle must not depend on the pair's size. Reference: the same
    # pair at size 1 (geometric similarity, which no constant of the code can produce: every length of a copy, points
    # and scatter included, is k times the original's). The cases are benchmarks/bench_hob_turn_back.py's rows that
    # read differently at a quarter size while the hob's lengths were fixed in mm: the 5/6 male from 300 exact points
    # (undercut at size 1, a touch at 0.25), from 300 with 2 um (undecided, "not judged an undercut" at 0.25), the
    # rack-involute female from 300 with 2 um, seed 12 (a touch at size 1, an undercut at 0.25; brute force 0.3 um).
    one, other = scaled_case(1.0, case), scaled_case(k, case)
    assert (other.undercut, other.undercut_undecided, other.hobbable) == (one.undercut, one.undercut_undecided, one.hobbable), (
        other.reasons,
        other.notes,
    )
    assert other.normal_pressure_angle_min_deg == pytest.approx(one.normal_pressure_angle_min_deg, abs=0.1)

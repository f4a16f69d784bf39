"""Meshing clearance from profile points (Wu & Chi 2013): round trips through a designed clearance
(design a clearance, measure it back), the paper's normal-rack projection (eq. 7) and the
contact line of Rinder's eq. 1 from the meshing analysis (a second, independent computation)."""

from __future__ import annotations

import dataclasses
import json

import numpy as np
import pytest
from scipy.spatial import cKDTree

from exports.csv_points import read_points, write_points
from rotorcad.clearance import MeshingClearance, ThermalState
from rotorcad.cli.main import main
from rotorcad.envelope import rack_frame
from rotorcad.geometry import perp_cw, rotate
from rotorcad.meshing import MeshingAnalysis
from rotorcad.profile import Segment
from rotorcad.rotor_families import build_family
from rotorcad.rotor_pair import RotorPair
from rotorcad.rotor_points import lobe_pieces

DEG = np.pi / 180
# rack-involute with all corners rounded: a smooth female whose offset is a clean curve
SMOOTH = {"tip_rounding": 1.4, "root_rounding": 1.0, "lobe_width": 0.6, "sealing_tip_rounding": 1.0}
DELTA = 0.05  # designed clearance: the female flanks moved into its material by 50 um


def designed(lead: float, length: float, delta: float = DELTA, turn_deg: float = 0.0):
    """The exact pair, its male outline as points, and its female outline with ``delta`` taken off
    along the exact outward normals (and turned by ``turn_deg`` about its centre)."""
    pair = RotorPair(5, 6, 116.0, 63.0, 45.0, 71.0, 53.0, lead=lead, length=length)
    rotors = build_family(pair, "rack-involute", SMOOTH)
    male = rotors.male_outline(1e-4)
    female = rotors.female_outline(1e-4)
    female_pts = rotate(female.points - delta * perp_cw(female.tangents), turn_deg * DEG)
    return pair, rotors, male.points, female_pts


def clearance_of(pair, male_pts, female_pts, contact="as-given"):
    return MeshingClearance(pair, lobe_pieces(pair, male_pts, "male"), lobe_pieces(pair, female_pts, "female"), contact=contact)


def in_contact(mc: MeshingClearance) -> np.ndarray:
    return mc._in_both_bores(mc.clearance) & np.isfinite(mc.clearance)


def test_a_uniform_offset_comes_back_as_the_clearance_along_the_rack():
    # The rack of an offset profile is the offset rack (parallel curves stay parallel under the
    # envelope), so with a straight helix (long lead, beta ~ 0.2 deg) the normal clearance is the
    # designed 50 um everywhere in contact.
    pair, _, m, f = designed(lead=1e5, length=1e5)
    mc = clearance_of(pair, m, f)
    delta = mc.clearance[in_contact(mc)]
    np.testing.assert_allclose(delta, DELTA, atol=1e-4)
    s = mc.summary()
    assert s["mean_clearance"] == pytest.approx(DELTA, abs=1e-5)
    assert s["equal_clearance"] == pytest.approx(DELTA, abs=1e-5)  # band of constant width
    assert s["band_area"] == pytest.approx(DELTA * s["contact_line_length"], rel=1e-3)
    assert s["wetted_perimeter"] == pytest.approx(2 * s["contact_line_length"], rel=1e-3)


def test_the_normal_rack_projection_of_a_transverse_offset():
    # Wu & Chi eq. 7: the normal rack is the transverse rack with x times c = cos(beta). A
    # transverse offset delta along the unit normal (nx, ny) maps to delta (c nx, ny), and along the
    # mapped curve's unit normal (nx, c ny) / sqrt(nx^2 + c^2 ny^2) it measures
    # delta c / sqrt(nx^2 + c^2 ny^2). The transverse normals come from the analytic rack chain the
    # pair was generated from.
    pair, rotors, m, f = designed(lead=300.0, length=190.0)
    mc = clearance_of(pair, m, f)
    c = np.cos(mc.helix_angle)
    chain = [Segment.sample("r", p.curve, 1e-5) for p in rotors.rack]
    pts = rack_frame(np.vstack([s.points for s in chain]), pair.male_pitch_radius)
    tan = np.vstack([s.tangents for s in chain])[:, ::-1]  # rack frame swaps the axes
    use = in_contact(mc)
    transverse = mc.datum_rack[use] / np.array([c, 1.0])
    transverse[:, 0] = np.mod(transverse[:, 0] - pts[0, 0], pair.rack_period) + pts[0, 0]
    k = cKDTree(pts).query(transverse)[1]
    nx, ny = tan[k, 1], -tan[k, 0]
    expected = DELTA * c / np.sqrt(nx**2 + (c * ny) ** 2)
    np.testing.assert_allclose(mc.clearance[use], expected, atol=2e-4)
    assert expected.min() < 0.75 * DELTA  # the flanks really are foreshortened (beta = 47.8 deg)


def test_contact_on_the_driving_flank_opens_the_sealing_flank_by_the_flank_angles():
    # Straight rack flanks at 30 deg (driving) and 25 deg (sealing) from the normal to the pitch
    # line: sliding the female rack by delta / cos 30 closes the driving gap, and the sealing gap
    # becomes delta (1 + cos 25 / cos 30); the female's initial turn does not matter.
    for turn in (0.0, 0.4):
        pair, _, m, f = designed(lead=1e5, length=1e5, turn_deg=turn)
        mc = clearance_of(pair, m, f, contact="driving")
        delta = mc.clearance[in_contact(mc)]
        assert delta.min() == pytest.approx(0.0, abs=2e-5)
        assert delta.max() == pytest.approx(DELTA * (1 + np.cos(25 * DEG) / np.cos(30 * DEG)), abs=2e-4)
    sealing = clearance_of(pair, m, f, contact="sealing").clearance[in_contact(mc)]
    assert sealing.max() == pytest.approx(DELTA * (1 + np.cos(30 * DEG) / np.cos(25 * DEG)), abs=2e-4)


def test_contact_line_agrees_with_the_meshing_analysis():
    # The same 3D contact line (Rinder eq. 1) from the racks of measured points and from the rack
    # chain of the exact pair (MeshingAnalysis): lengths within 0.2 %; a conjugate pair has no
    # clearance beyond the points' fit.
    pair, rotors, m, _ = designed(lead=300.0, length=190.0, delta=0.0)
    f = rotors.female_outline(1e-4).points
    mc = clearance_of(pair, m, f)
    s = mc.summary()
    assert s["contact_line_length"] == pytest.approx(MeshingAnalysis(rotors).contact_line_length, rel=2e-3)
    assert abs(s["max_normal_clearance"]) < 1e-4 and abs(s["min_normal_clearance"]) < 1e-4


def test_sharp_corners_in_the_points_are_kept_as_corners(tmp_path):
    # The rack-involute sample's female has a sharp tip corner; its outline written at 1 um
    # chords gives back zero clearance within the chords (a spline through the corner would ring
    # by tenths of a millimetre).
    out = tmp_path
    args = ["rotor", "samples/rack_involute_5_6.toml", "--male-csv", str(out / "m.csv"), "--female-csv", str(out / "f.csv")]
    assert main(args) == 0
    m, f = read_points(out / "m.csv"), read_points(out / "f.csv")
    pair = RotorPair(5, 6, 116.0, np.hypot(*m.T).max(), np.hypot(*m.T).min(), np.hypot(*f.T).max(), np.hypot(*f.T).min())
    pieces = lobe_pieces(pair, f, "female")
    assert len(pieces) > 1
    mc = clearance_of(pair, m, f)
    delta = mc.clearance[in_contact(mc)]
    assert np.abs(delta).max() < 3e-3


def test_cli_clearance_keys_files_and_bad_input(tmp_path, capsys):
    _, _, m, f = designed(lead=300.0, length=190.0)
    write_points(tmp_path / "m.csv", m)
    write_points(tmp_path / "f.csv", f)
    base = ["clearance", "--male-points", str(tmp_path / "m.csv"), "--female-points", str(tmp_path / "f.csv")]
    dims = ["--male-teeth", "5", "--female-teeth", "6", "--center-distance", "116"]
    capsys.readouterr()
    assert main([*base, *dims, "--json", "--csv", str(tmp_path / "c.csv"), "--plot", str(tmp_path / "c.png")]) == 0
    data = json.loads(capsys.readouterr().out)
    keys = {"max_normal_clearance", "mean_clearance", "equal_clearance", "band_area", "contact_line_length", "wetted_perimeter"}
    assert keys <= set(data)
    assert data["min_normal_clearance"] == pytest.approx(0.0, abs=2e-5)  # contact on the driving flank
    assert (tmp_path / "c.png").stat().st_size > 0
    assert any(line.startswith("x,y,clearance,male_angle_deg,z") for line in open(tmp_path / "c.csv").read().splitlines()[:6])
    for args, word in (
        ([*base, "--male-teeth", "5", "--female-teeth", "6"], "--center-distance"),
        ([*base, "--male-teeth", "1", "--female-teeth", "6", "--center-distance", "116"], "--male-teeth"),
        ([*base, *dims, "--lead", "-3"], "lead"),
        (
            ["clearance", "--male-points", str(tmp_path / "none.csv"), "--female-points", str(tmp_path / "f.csv"), *dims],
            "--male-points",
        ),
    ):
        assert main(args) == 2
        err = capsys.readouterr().err
        assert word in err and "Traceback" not in err and err.count("\n") == 1


def test_hot_pair_in_a_housing_that_grows_more():
    # Thermal clearance (the Chinese paper of the MCE seed, eq. 1: dL = L zeta (t - t0), rotors at
    # the mean of suction and discharge temperature): steel rotors (11.5e-6/K) at 70 degC in an
    # aluminium housing (23e-6/K) move apart by da = a (k_housing - k_rotor) relative to the grown
    # rotors. With straight flanks (beta ~ 0) the driving contact needs the rack slid by
    # s = (k delta + da sin 30) / cos 30, and the widest gap, on the sealing tip rounding where
    # da sin(phi) + s cos(phi) peaks, is k delta + hypot(da, s).
    pair, _, m, f = designed(lead=9e4, length=9e4)  # the hot lead stays within 100 m
    pair = dataclasses.replace(pair, strict=False)
    thermal = ThermalState(20.0, 120.0, rotor_expansion=11.5e-6, housing_expansion=23e-6)
    hot, m_hot, f_hot = thermal.apply(pair, m, f)
    k = thermal.rotor_scale
    da = hot.center_distance - k * pair.center_distance
    mc = clearance_of(hot, m_hot, f_hot, contact="driving")
    s = (k * DELTA + da * np.sin(30 * DEG)) / np.cos(30 * DEG)
    assert mc.shift == pytest.approx(s, abs=1e-4)
    delta = mc.clearance[in_contact(mc)]
    assert delta.min() == pytest.approx(0.0, abs=2e-5)
    assert delta.max() == pytest.approx(k * DELTA + np.hypot(da, s), abs=1e-4)
    # rotors and housing growing alike keep a conjugate pair conjugate: clearances scale with k
    same = ThermalState(20.0, 120.0, rotor_expansion=11.5e-6, housing_expansion=11.5e-6)
    hot, m_hot, f_hot = same.apply(pair, m, f)
    mc = clearance_of(hot, m_hot, f_hot)
    np.testing.assert_allclose(mc.clearance[in_contact(mc)], k * DELTA, atol=1e-4)  # not k delta + da sin(phi)

"""Rinder & Deix's own load (eq. 5) beside rotorcad's, and their 5/6 example (issue 23).

References: eq. (5) of Rinder & Deix, *Analytical deflection of screw rotors* (the chord
l_s = d_K sin(pi / z_L), its load normal to the chord), computed here from the tip radii alone; the
paper's numbers of sec. 3.5 (12 bar: helical parts 0.002 mm female, 0.0005 mm male; with the
journals of Fig. 8, 0.0075 and 0.0022 mm); the closed form (p_d / p_s)^(1/n) of the default volume
ratio.
"""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest
from shared_runs import command_output
from test_deflection import _independent_chamber

from rotorcad.cli.main import main
from rotorcad.working_chamber import chord_table, flute_cycles

ROOT = Path(__file__).resolve().parents[1]


@pytest.fixture(scope="module")
def independent_chamber(built_once):
    """test_deflection's independent 4/6 chamber table, built once in a run for both modules."""
    return built_once("test_deflection.independent_chamber", _independent_chamber)


def test_chord_table_is_eq_5_over_each_flutes_cycle(independent_chamber):
    table, male, female, _ = independent_chamber
    r1, r2 = np.hypot(*male.T).max(), np.hypot(*female.T).max()
    chord = chord_table(table, 4, 6, r1, r2)
    (m0, m1), (f0, f1) = flute_cycles(4, 6)
    psi = table.phase
    on1, on2 = (psi >= m0) & (psi < m1), (psi >= f0) & (psi < f1)
    # eq. (5): |q| / p = d_K sin(pi / z_L), each rotor its own tip diameter and lobes
    assert np.hypot(*chord.male_force[on1].T) == pytest.approx(2 * r1 * np.sin(np.pi / 4), rel=1e-12)
    assert np.hypot(*chord.female_force[on2].T) == pytest.approx(2 * r2 * np.sin(np.pi / 6), rel=1e-12)
    assert not chord.male_force[~on1].any() and not chord.female_force[~on2].any()
    # far from the mesh the flute is open from tip to tip: the real chamber's load (shapely's gas
    # space) has eq. (5)'s direction, and at most its length (the opening between the tip lands, which
    # eq. 5 takes as points, test_deflection.py::test_open_flute_load_is_the_chord_times_the_pressure)
    for name, mid in (("male", np.pi), ("female", 0.5 * (f0 + f1))):
        i = int(np.argmin(np.abs(psi - mid)))
        real, eq5 = getattr(table, f"{name}_force")[i], getattr(chord, f"{name}_force")[i]
        assert np.dot(real, eq5) / (np.hypot(*real) * np.hypot(*eq5)) > np.cos(np.radians(3.0))
        assert 0.5 * np.hypot(*eq5) < np.hypot(*real) <= np.hypot(*eq5) * (1 + 1e-3)
    # near the mesh the chamber's boundary is shorter than the chord (the mate's lobe fills the flute)
    assert np.hypot(*table.male_force[on1].T).mean() < 0.95 * 2 * r1 * np.sin(np.pi / 4)


@pytest.fixture(scope="module")
def rinder_deix():
    """The sample of Rinder & Deix's example, --method paper, as JSON (run once in the run: tests/test_deflect_scaling.py
    runs the same, tests/shared_runs.py)."""
    code, out, _ = command_output("deflect", ROOT / "samples" / "rinder_deix_5_6.toml", "--method", "paper", "--json", "--quiet")
    assert code == 0
    return json.loads(out)


def test_rinder_deix_example_order_and_size(rinder_deix):
    r = rinder_deix
    assert r["method"] == "paper"
    # the paper's order: the thin-cored female deflects more than the male, helical part and with journals
    assert r["female_max_deflection_helical"] > 3 * r["male_max_deflection_helical"]  # paper 4.0
    assert r["female_max_deflection"] > 2 * r["male_max_deflection"]  # paper 3.4
    # the paper's sizes (sec. 3.5); its pair's dimensions are not printed, the sample's are industrial
    # 5/6 proportions at a = 82 mm (README: 1.92 / 0.40 um helical, 7.43 / 2.90 um with journals; which
    # dimension would match the male exactly)
    assert r["female_max_deflection_helical"] == pytest.approx(0.002, rel=0.10)
    assert r["female_max_deflection"] == pytest.approx(0.0075, rel=0.10)
    assert r["male_max_deflection_helical"] == pytest.approx(0.0005, rel=0.25)
    assert r["male_max_deflection"] == pytest.approx(0.0022, rel=0.35)
    # the journals multiply the helical deflection by a few (paper: 3.75 female, 4.4 male)
    assert 2.5 < r["female_max_deflection"] / r["female_max_deflection_helical"] < 6.0
    # eq. (5)'s full chord loads more than the real chamber's boundary, which ends at the contact line
    for rotor in ("male", "female"):
        ratio = r[f"{rotor}_max_deflection_helical_paper_to_rotorcad"]
        assert ratio == pytest.approx(r[f"{rotor}_max_deflection_helical_paper"] / r[f"{rotor}_max_deflection_helical_rotorcad"])
        assert 1.1 < ratio < 1.8
        assert r[f"{rotor}_max_deflection_helical"] == r[f"{rotor}_max_deflection_helical_paper"]
    assert r["volume_ratio"] == pytest.approx(5.0, rel=2e-3)  # the design's input, not the pressure ratio's
    assert list(r["defaults"]) == ["[deflection] terms"]  # everything else given in the sample


def test_defaults_taken_are_reported_with_how_they_were_chosen(capsys):
    design = ROOT / "samples" / "rack_involute_5_6.toml"  # 1 -> 8 bar, no volume ratio, no [deflection]
    assert main(["deflect", str(design), "--json", "--quiet", "--angle", "10"]) == 0
    r = json.loads(capsys.readouterr().out)
    d = r["defaults"]
    vi = 8.0 ** (1 / 1.4)  # closed form of the default built-in volume ratio
    assert r["volume_ratio"] == pytest.approx(vi, rel=2e-3)
    assert d["[operating] volume_ratio"].startswith(f"{r['volume_ratio']:.4g} (default: ")
    assert d["[operating] polytropic_exponent"] == "1.4 (default: isentropic air)"
    assert d["[deflection] young_modulus"].startswith("210000 N/mm^2 (default: steel")
    assert "[deflection] male_shaft_discharge" in d and "[deflection] poisson_ratio" in d


def test_rinder_deix_worst_angle_is_eq_10_and_each_line_lies_in_a_plane(rinder_deix):
    # sec. 3.5 under Fig. 10: the largest deflection comes when eq. (10) holds (a chamber at end pressure
    # has just passed the control edge); under Fig. 9: each rotor's bending line lies practically in one
    # plane (the paper's 220 deg male, 225 deg female, in axes the text does not define)
    assert rinder_deix["angle_deg"] == pytest.approx(rinder_deix["angle_eq10_deg"], abs=0.5)
    from rotorcad.cli.common import load_rotor_design
    from rotorcad.cli.export_cmd import _rotor_options
    from rotorcad.cli.rotor import _build
    from rotorcad.deflection import GasDeflection, LoadModel

    design = ROOT / "samples" / "rinder_deix_5_6.toml"
    rotors, _, _ = _build(design, _rotor_options(design), load_rotor_design(design))
    # the chamber table of the command's own run (the fixture's: phase step 1 deg, taken from working_chamber's
    # recent tables, not built again at 2 deg)
    model = GasDeflection(rotors, 1.0, 12.0, volume_ratio=5.0, load=LoadModel.CHORD, terms=10, cells=400)
    lines = model.at(np.radians(rinder_deix["angle_deg"]))
    for rotor in ("male", "female"):
        w = getattr(lines, rotor)
        mag = np.hypot(*w.T)
        direction = np.degrees(np.arctan2(w[:, 1], w[:, 0]))[mag > 0.5 * mag.max()]
        assert np.ptp(direction) < 5.0  # one plane along the whole loaded part of the line

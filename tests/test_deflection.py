"""Rotor deflection under gas load (Rinder & Deix), checked against what the code did not make:
closed forms of section values and beams (computed here), scipy's boundary-value solver for the
Timoshenko beam, the paper's printed eq. (9), shapely's gas space of independently cut rotors
(tests/independent_pairs.py), and the paper's own ranges and limits.
"""

from __future__ import annotations

import contextlib
import io
import json
import os
import stat
from functools import lru_cache
from pathlib import Path

import numpy as np
import pytest
import shapely
from independent_pairs import cut_rotor, trapezoid_4_6
from scipy.linalg import solve_banded

from rotorcad.cli.main import main
from rotorcad.rotor_beam import (
    KAPPA_ROUND,
    Beam,
    ShaftSegment,
    equivalent_diameter,
    reduced_second_moment,
    step_load_coefficients,
    stepped_deflection,
)
from rotorcad.section_properties import section_values, shear_correction, shear_correction_over_turn, width_profile
from rotorcad.working_chamber import chamber_table

ROOT = Path(__file__).resolve().parents[1]
E, MU = 210_000.0, 0.3
G = E / (2 * (1 + MU))


def _circle(r: float, n: int = 20000, center=(0.0, 0.0)) -> np.ndarray:
    t = np.linspace(0, 2 * np.pi, n, endpoint=False)
    return np.c_[center[0] + r * np.cos(t), center[1] + r * np.sin(t)]


# --- section values (eq. 1) -------------------------------------------------------------------


def test_area_and_second_moment_of_circle_and_annulus_match_closed_forms():
    v = section_values(_circle(25.0))
    assert v.area == pytest.approx(np.pi * 25.0**2, rel=1e-7)
    assert v.j_x == pytest.approx(np.pi * 50.0**4 / 64, rel=1e-7)
    assert v.j_y == pytest.approx(v.j_x, rel=1e-12) and abs(v.j_xy) < 1e-6 * v.j_x
    # annulus as one ring: outside counter-clockwise, a zero-width slit, inside clockwise
    outer, inner = _circle(30.0), _circle(18.0)[::-1]
    ring = np.vstack([outer, outer[:1], inner[-1:], inner])
    annulus = section_values(np.roll(ring, 3, axis=0) + np.array([5.0, -2.0]))  # off-centre: centroid found
    assert annulus.area == pytest.approx(np.pi * (30.0**2 - 18.0**2), rel=1e-7)
    assert annulus.j_x == pytest.approx(np.pi * (60.0**4 - 36.0**4) / 64, rel=1e-7)
    assert annulus.centroid == pytest.approx((5.0, -2.0), abs=1e-7)


def test_shear_correction_of_circle_and_rectangle_match_closed_forms():
    # kappa = A/J^2 int (S/b)^2 dA: 10/9 for a full circle, 6/5 for a rectangle (Timoshenko's values)
    assert shear_correction(_circle(10.0)) == pytest.approx(10.0 / 9.0, rel=1e-4)
    rect = np.array([[0.0, 0.0], [4.0, 0.0], [4.0, 10.0], [0.0, 10.0]])
    assert shear_correction(rect) == pytest.approx(1.2, rel=1e-5)


def test_width_profile_equals_shapely_chords_of_a_cut_rotor():
    # b(y) of eq. (1) against the length of shapely's intersection with horizontal lines, on a rotor
    # cut by brute force and turned so that many edges are nearly horizontal somewhere
    male = _independent_rotors()[0]
    for turn in np.radians([0.0, 30.0, 61.0]):
        c, s = np.cos(turn), np.sin(turn)
        ring = male @ np.array([[c, s], [-s, c]])
        poly = shapely.Polygon(ring)
        ys = np.random.default_rng(1).uniform(ring[:, 1].min(), ring[:, 1].max(), 500)
        lines = shapely.linestrings([[[-100.0, y], [100.0, y]] for y in ys])
        assert np.allclose(width_profile(ring, ys), shapely.length(shapely.intersection(poly, lines)), atol=1e-8)


@lru_cache(maxsize=1)
def _independent_rotors() -> tuple[np.ndarray, np.ndarray]:
    pair = trapezoid_4_6()
    return cut_rotor(pair, "male"), cut_rotor(pair, "female")


def test_rotor_sections_are_isotropic_and_kappa_stays_near_a_circles():
    # Rinder & Deix sec. 2.1: for z > 2 the second moment is the same about every axis; kappa varies
    # with the turn of the section (1.04 .. 1.18 for their profiles). Rotors cut by brute force (no
    # rotorcad), 4 and 6 lobes.
    for ring in _independent_rotors():
        j = []
        for turn in np.radians([0.0, 13.0, 29.0, 45.0, 77.0]):
            c, s = np.cos(turn), np.sin(turn)
            v = section_values(ring @ np.array([[c, s], [-s, c]]))
            j.append(v.j_x)
            assert abs(v.j_x - v.j_y) < 2e-4 * v.j_x and abs(v.j_xy) < 2e-4 * v.j_x  # brute-force cut: 1e-4-level asymmetry
        assert np.ptp(j) < 2e-4 * np.mean(j)
        kappa = shear_correction_over_turn(ring, np.linspace(0, np.pi, 13))
        assert 1.0 < kappa.min() and kappa.max() < 1.3  # trapezoid lobes: about a circle's 10/9
        assert np.allclose(kappa, kappa[::-1], rtol=1e-4)  # symmetric lobes: kappa(gamma) = kappa(-gamma)


# --- the equivalent beam (eqs. 2-4) ------------------------------------------------------------


def test_reduced_second_moment_runs_from_whole_section_to_core():
    # eq. (2) with "-" (the misprint fixed): no twist -> J_ges, large wrap per length -> J_F
    j_ges, j_f = 8.0e6, 3.2e6
    assert reduced_second_moment(j_ges, j_f, 90.0, 126.0, 0.0, 190.0) == pytest.approx(j_ges, rel=1e-12)
    assert reduced_second_moment(j_ges, j_f, 90.0, 126.0, 1e6, 1.0) == pytest.approx(j_f, rel=1e-6)
    values = [reduced_second_moment(j_ges, j_f, 90.0, 126.0, w, 190.0) for w in np.linspace(0.0, 950.0, 21)]
    assert np.all(np.diff(values) < 0)  # the paper: the more wrap per length, the softer


def test_equivalent_diameter_deflects_like_the_rotor_beam():
    # eq. (3) is the round bar with the rotor's midspan deflection under a central force:
    # F l^3/(48 E J) + kappa F l / (4 G A), computed here for both
    area, j_red, length = 9700.0, 5.7e6, 190.0
    d = equivalent_diameter(area, j_red, length, MU, KAPPA_ROUND)

    def midspan(a: float, j: float) -> float:
        return length**3 / (48 * E * j) + KAPPA_ROUND * length / (4 * G * a)

    assert midspan(np.pi * d**2 / 4, np.pi * d**4 / 64) == pytest.approx(midspan(area, j_red), rel=1e-12)
    # and a round bar is its own equivalent
    assert equivalent_diameter(np.pi * 80.0**2 / 4, np.pi * 80.0**4 / 64, length, MU) == pytest.approx(80.0, rel=1e-12)


# --- the deflection line (eqs. 7-9) -----------------------------------------------------------


def test_ritz_uniform_load_matches_timoshenko_closed_form():
    # simply supported, uniform q: w(L/2) = 5 q L^4 / (384 E J) + kappa q L^2 / (8 G A)
    beam = Beam.round_bar(100.0, 190.0, E, MU)
    q = 10.0
    z = (np.arange(4000) + 0.5) * beam.length / 4000
    coeff = beam.sine_coefficients(z, np.full((4000, 1), q), 301)
    w = beam.deflection(coeff, np.array([beam.length / 2]))[0, 0]
    exact = 5 * q * beam.length**4 / (384 * beam.bending) + q * beam.length**2 / (8 * beam.shear)
    assert w == pytest.approx(exact, rel=1e-5)


def _fd_deflection(length: float, load, bending, shear, z_out: np.ndarray, n: int = 20000) -> np.ndarray:
    """Timoshenko beam, simply supported, by finite differences (written here, independent of
    rotorcad): M'' = -q with M = 0 at the ends, then w'' = -M/EJ + d/dz (V / (GA/kappa)), V = M',
    w = 0 at the ends; central differences on n cells, the shear term in conservative form."""
    z = np.linspace(0.0, length, n + 1)
    h = z[1] - z[0]
    mid = 0.5 * (z[1:] + z[:-1])

    def tridiagonal_solve(rhs: np.ndarray) -> np.ndarray:  # u'' = rhs, u = 0 at both ends
        ab = np.zeros((3, n - 1))
        ab[0, 1:], ab[1, :], ab[2, :-1] = 1.0, -2.0, 1.0
        return np.concatenate([[0.0], solve_banded((1, 1), ab, h * h * rhs), [0.0]])

    moment = tridiagonal_solve(-load(z[1:-1]))
    v_over_ga = np.diff(moment) / h / shear(mid)  # at the cell midpoints
    w = tridiagonal_solve(-moment[1:-1] / bending(z[1:-1]) + np.diff(v_over_ga) / h)
    return np.interp(z_out, z, w)


def test_ritz_of_the_papers_flute_load_matches_finite_differences():
    # eq. (6): q_x = -q cos(2 pi z / h + psi0) up to r, 0 beyond; the series with the closed-form
    # coefficients against the Timoshenko beam by finite differences
    beam = Beam.round_bar(105.0, 190.0, E, MU)
    q, lead, reach, psi0 = 7.0, 300.0, 120.0, 0.7
    coeff = step_load_coefficients(q, lead, beam.length, reach, psi0, 200)
    z = np.linspace(0, beam.length, 41)
    w = beam.deflection(coeff, z)[:, 0]

    def load(s):
        return np.where(s <= reach, -q * np.cos(2 * np.pi * s / lead + psi0), 0.0)

    ref = _fd_deflection(beam.length, load, lambda s: beam.bending + 0 * s, lambda s: beam.shear + 0 * s, z)
    assert np.max(np.abs(w - ref)) < 1e-4 * np.max(np.abs(ref))
    # the closed-form coefficients equal the quadrature of the same load
    cells = (np.arange(20000) + 0.5) * beam.length / 20000
    numeric = beam.sine_coefficients(cells, np.c_[load(cells), np.zeros_like(cells)], 10)
    assert np.allclose(numeric[:, 0], coeff[:10, 0], atol=1e-3 * np.abs(coeff[:, 0]).max())


def test_first_term_is_the_printed_eq_9():
    # c_xm = l^4 q h [(2l-h) cos(pi r/l + 2 pi r/h + psi) - (2l+h) cos(pi r/l - 2 pi r/h - psi) + 2h cos psi]
    #        / (pi^5 (2l+h)(2l-h)), and c_xq the same with l^2 / pi^3 (Rinder & Deix eq. 9, as printed)
    q, h, l_, r, psi = 5.0, 300.0, 190.0, 110.0, 0.4
    bracket = (
        (2 * l_ - h) * np.cos(np.pi * r / l_ + 2 * np.pi * r / h + psi)
        - (2 * l_ + h) * np.cos(np.pi * r / l_ - 2 * np.pi * r / h - psi)
        + 2 * h * np.cos(psi)
    )
    c_xm = l_**4 * q * h * bracket / (np.pi**5 * (2 * l_ + h) * (2 * l_ - h))
    c_xq = l_**2 * q * h * bracket / (np.pi**3 * (2 * l_ + h) * (2 * l_ - h))
    q1 = step_load_coefficients(q, h, l_, r, psi, 1)[0, 0]
    assert q1 * (l_ / np.pi) ** 4 == pytest.approx(c_xm, rel=1e-12)
    assert q1 * (l_ / np.pi) ** 2 == pytest.approx(c_xq, rel=1e-12)


def test_two_term_ritz_is_a_few_percent_off_for_a_short_load_and_the_series_converges():
    beam = Beam.round_bar(105.0, 190.0, E, MU)
    z = np.linspace(0, beam.length, 381)
    peak = {}
    for terms in (2, 40, 80):
        w = beam.deflection(step_load_coefficients(7.0, 300.0, beam.length, 0.3 * beam.length, 0.2, terms), z)
        peak[terms] = np.abs(w[:, 0]).max()
    assert 0.01 < abs(peak[2] / peak[80] - 1) < 0.15  # the paper's 2 terms: several per cent
    assert abs(peak[40] / peak[80] - 1) < 1e-3


def test_stepped_shaft_matches_closed_form_and_finite_differences_with_journals():
    helical = Beam.round_bar(105.0, 190.0, E, MU)
    only = [ShaftSegment(helical.length, helical.bending, helical.shear)]
    q = 10.0
    z, w = stepped_deflection(only, 0, np.full((500, 1), q), cells=4000)
    exact = 5 * q * helical.length**4 / (384 * helical.bending) + q * helical.length**2 / (8 * helical.shear)
    assert np.interp(helical.length / 2, z, w[:, 0]) == pytest.approx(exact, rel=1e-4)
    # journals: 60 mm of d = 50 at the discharge end, 40 mm of d = 45 at the suction end
    j1, j2 = Beam.round_bar(50.0, 60.0, E, MU), Beam.round_bar(45.0, 40.0, E, MU)
    shaft = [ShaftSegment(60.0, j1.bending, j1.shear), only[0], ShaftSegment(40.0, j2.bending, j2.shear)]
    z, w = stepped_deflection(shaft, 1, np.full((500, 1), q), cells=6000)
    ends = np.array([60.0, 250.0])

    def pick(s, a, b, c):
        return np.where(s < ends[0], a, np.where(s < ends[1], b, c))

    ref = _fd_deflection(
        290.0,
        lambda s: pick(s, 0.0, q, 0.0),
        lambda s: pick(s, j1.bending, helical.bending, j2.bending),
        lambda s: pick(s, j1.shear, helical.shear, j2.shear),
        z,
    )
    assert np.max(np.abs(w[:, 0] - ref)) < 2e-3 * np.max(np.abs(ref))
    assert w[:, 0].max() > 3 * exact  # soft journals dominate (the paper: 0.0005 -> 0.0022 mm)


# --- the working chamber and its load ---------------------------------------------------------


@lru_cache(maxsize=1)
def _independent_chamber():
    male, female = _independent_rotors()
    pair = trapezoid_4_6()
    lead, length = 400.0, 200.0  # wrap 180 deg
    # the cut outlines thinned to 2 um (11 000 -> ~1 000 points) for speed
    male_s, female_s = (shapely.simplify(shapely.Polygon(ring), 2e-3) for ring in (male, female))
    table = chamber_table(male_s, female_s, 4, 6, pair.center_distance, lead, length, 1.0)
    return table, male, female, pair


@pytest.fixture(scope="module")
def independent_chamber(built_once):
    """:func:`_independent_chamber`, built once in a run for this module and tests/test_paper_deflection.py
    (whichever worker runs them: ~1.3 s of CPU, the chamber table)."""
    return built_once("test_deflection.independent_chamber", _independent_chamber)


def test_chambers_share_out_the_whole_gas_space(independent_chamber):
    # At any male angle the chambers alive hold, together, the whole gas space between the bores and
    # the rotors (shapely, here) times the length: every bit of gas in exactly one chamber.
    table, male, female, pair = independent_chamber
    a = pair.center_distance
    r1, r2 = np.hypot(*male.T).max(), np.hypot(*female.T).max()
    bores = shapely.union(shapely.Point(0, 0).buffer(r1, quad_segs=512), shapely.Point(a, 0).buffer(r2, quad_segs=512))
    start, stop = table.cycle
    for angle in np.radians([0.0, 11.0, 37.0, 62.0]):
        psi0 = angle + np.pi / 2 * np.arange(-12, 13)
        total = table.volume(psi0[(psi0 >= start) & (psi0 < stop)]).sum()
        m = shapely.affinity.rotate(shapely.Polygon(male), angle, origin=(0, 0), use_radians=True)
        f = shapely.affinity.translate(
            shapely.affinity.rotate(shapely.Polygon(female), -angle * 4 / 6, origin=(0, 0), use_radians=True), a, 0
        )
        gas = shapely.difference(bores, shapely.union(m, f)).area * table.length
        assert total == pytest.approx(gas, rel=1e-3)  # the 1 um shrink that parts touching pieces: ~3e-4


def test_largest_chamber_is_one_male_and_one_female_flute_over_the_length(independent_chamber):
    # V_max = (A1f + A2f) L with A_f = (pi r_tip^2 - A) / z from the sections alone (wrap 180 deg
    # leaves a phase at which both flutes are open over the whole length)
    table, male, female, _ = independent_chamber
    flutes = sum((np.pi * np.hypot(*ring.T).max() ** 2 - shapely.Polygon(ring).area) / z for ring, z in ((male, 4), (female, 6)))
    start, stop = table.cycle
    v = table.volume(np.linspace(start, stop, 4001))
    assert v.max() == pytest.approx(flutes * table.length, rel=1e-3)
    assert v[0] == pytest.approx(0.0, abs=1e-6 * v.max()) and v[-1] == pytest.approx(0.0, abs=1e-6 * v.max())


def test_open_flute_load_is_the_chord_times_the_pressure(independent_chamber):
    # Rinder & Deix eq. 5: the resultant of a uniform pressure on a flute is p times the chord
    # between the flute's ends on the tip circle, normal to it, towards the axis. The ends are found
    # here from the cut outline (where it leaves the tip circle).
    table, male, _, _ = independent_chamber
    r = np.hypot(*male.T)
    ang = np.arctan2(male[:, 1], male[:, 0])
    on_tip = r > r.max() - 1e-3
    i = np.argmin(np.abs(table.phase - np.pi))  # flute pointing at -x, far from the mesh
    psi = table.phase[i]
    # the flute spans the gap between the tip lands around the direction psi
    rel = (ang - psi + np.pi) % (2 * np.pi) - np.pi
    lead = rel[on_tip & (rel > 0)].min()
    trail = rel[on_tip & (rel < 0)].max()
    p1 = r.max() * np.array([np.cos(psi + lead), np.sin(psi + lead)])
    p2 = r.max() * np.array([np.cos(psi + trail), np.sin(psi + trail)])
    force = table.male_force[i]
    assert np.hypot(*force) == pytest.approx(np.hypot(*(p1 - p2)), rel=5e-3)
    assert np.dot(force, [np.cos(psi), np.sin(psi)]) == pytest.approx(-np.hypot(*force), rel=1e-4)


# --- the command ------------------------------------------------------------------------------


def _design(tmp_path: Path, extra: str = "") -> Path:
    text = (ROOT / "samples" / "rack_involute_5_6.toml").read_text()
    path = tmp_path / "pair.toml"
    path.write_text(text + "\n" + extra)
    return path


def test_deflect_json_worst_angle_and_journals(tmp_path, capsys):
    design = _design(
        tmp_path,
        "[deflection]\nmale_shaft_discharge = [[60.0, 50.0]]\nmale_shaft_suction = [[60.0, 50.0]]\n"
        "female_shaft_discharge = [[60.0, 40.0]]\nfemale_shaft_suction = [[60.0, 40.0]]\n",
    )
    plot = tmp_path / "d.png"
    assert main(["deflect", str(design), "--json", "--plot", str(plot)]) == 0
    out = json.loads(capsys.readouterr().out)
    for key in (
        "male_max_deflection",
        "female_max_deflection",
        "male_equivalent_diameter",
        "female_equivalent_diameter",
        "angle_deg",
    ):
        assert key in out
    # the equivalent bar lies between the core and the tip circle
    assert out["male_root_diameter"] < out["male_equivalent_diameter"] < 126.0
    # journals make the rotors much softer (the paper: 0.0005 -> 0.0022 mm, 0.002 -> 0.0075 mm)
    assert out["male_max_deflection"] > 3 * out["male_max_deflection_helical"]
    assert out["female_max_deflection"] > 3 * out["female_max_deflection_helical"]
    # eq. (10): the worst angle is where a chamber reaches the control edge (sweep of 100 angles)
    pitch = 72.0
    gap = abs((out["angle_deg"] - out["angle_eq10_deg"] + pitch / 2) % pitch - pitch / 2)
    assert gap <= 2.5
    # the paper's two-term Ritz form: a few per cent
    assert abs(out["male_max_deflection_helical_ritz2"] / out["male_max_deflection_helical"] - 1) < 0.1
    assert plot.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    # the volume curve's largest chamber times z1 is the displacement that `rotorcad rotor` finds from
    # the flute areas alone (Rinder: A1f + A2f per lobe pair, times L)
    assert main(["rotor", str(design), "--json"]) == 0
    rotor = json.loads(capsys.readouterr().out)
    assert out["displacement_per_male_rev"] == pytest.approx(rotor["displacement_per_rev"], rel=1e-3)
    # the bearings share the gas force (statics: |R_d| + |R_s| >= |F|, the discharge end carries more)
    for rotor in ("male", "female"):
        force, r_d, r_s = (out[f"{rotor}_{k}"] for k in ("gas_force_n", "discharge_bearing_load_n", "suction_bearing_load_n"))
        assert r_d + r_s >= force > 0 and r_d > r_s
        assert out[f"{rotor}_discharge_bearing_load_max_n"] >= r_d
    # which chambers carry which pressure, and how far: one at discharge pressure reaching into the rotors
    assert any(c["pressure_bar"] == pytest.approx(8.0) and 0 < c["to_z"] < 190.0 for c in out["chambers"])


@pytest.mark.parametrize(
    ("extra", "args", "words"),
    [
        ("", ["--terms", "0"], "--terms"),
        ("[deflection]\nmale_shaft_suction = [[60.0]]\n", [], "male_shaft_suction"),
        ("[deflection]\npoisson_ratio = 0.7\n", [], "poisson_ratio"),
    ],
)
def test_deflect_bad_input_one_sentence_exit_2(tmp_path, capsys, extra, args, words):
    design = _design(tmp_path, extra)
    assert main(["deflect", str(design), *args]) == 2
    err = capsys.readouterr().err
    assert words in err and "Traceback" not in err and err.count("\n") == 1


def test_deflect_needs_pressures(tmp_path, capsys):
    text = (ROOT / "samples" / "rack_involute_5_6.toml").read_text().replace("discharge_pressure_bar = 8.0", "")
    design = tmp_path / "p.toml"
    design.write_text(text)
    assert main(["deflect", str(design)]) == 2
    assert "discharge_pressure_bar" in capsys.readouterr().err


@pytest.fixture(scope="module")
def built_in_deflect(tmp_path_factory) -> tuple[dict, Path]:
    """``deflect`` of the rack-involute sample at 17 deg with 5 terms, ``--json`` and an SVG
    ``--plot``: its JSON and the picture. One run (some 2.5 s of CPU, the chamber table) read by two
    tests: the indicator diagram's (the built-in port model's result) and the picture's."""
    svg = tmp_path_factory.mktemp("deflect") / "d.svg"
    design = ROOT / "samples" / "rack_involute_5_6.toml"
    out = io.StringIO()
    with contextlib.redirect_stdout(out):
        code = main(["deflect", str(design), "--json", "--angle", "17", "--terms", "5", "--plot", str(svg)])
    assert code == 0
    return json.loads(out.getvalue()), svg


def test_indicator_diagram_gives_the_built_in_result_when_it_is_the_same_curve(tmp_path, capsys, built_in_deflect):
    # The built-in port model's pressure written as an indicator diagram (chamber angle in deg,
    # absolute bar) must give the same deflection: the CSV path reads angles and units as documented.
    from rotorcad.cli.export_cmd import _rotor_options
    from rotorcad.cli.rotor import _build
    from rotorcad.deflection import GasDeflection

    design = ROOT / "samples" / "rack_involute_5_6.toml"
    rotors, _, _ = _build(design, _rotor_options(design))
    cycle = GasDeflection(rotors, 1.0, 8.0, terms=5).cycle
    csv = tmp_path / "indicator.csv"
    rows = "\n".join(f"{np.degrees(t):.6f},{p * 10:.9f}" for t, p in zip(cycle.angle, cycle.pressure, strict=True))
    csv.write_text("angle_deg,pressure_bar\n" + rows + "\n")
    built_in, _ = built_in_deflect  # the same command line without --indicator (and with --plot)
    assert main(["deflect", str(design), "--json", "--angle", "17", "--terms", "5", "--indicator", str(csv)]) == 0
    given = json.loads(capsys.readouterr().out)
    assert given["male_max_deflection"] == pytest.approx(built_in["male_max_deflection"], rel=2e-3)
    assert given["female_max_deflection"] == pytest.approx(built_in["female_max_deflection"], rel=2e-3)
    assert "volume_ratio" not in given  # no port model with an indicator diagram


@pytest.mark.parametrize(
    ("extra", "args", "words"),
    [
        (
            "volume_ratio = 3.0\ndischarge_edge_deg = 600.0\n",
            [],
            "give only one of [operating] volume_ratio, [operating] discharge_edge_deg",
        ),
        ("polytropic_exponent = 3.0\n", [], "[operating] polytropic_exponent must be a number from 1 to 2"),
        ("volume_ratio = 60.0\n", [], "[operating] volume_ratio must be above 1 and up to 50"),
        ("", ["--angle", "1e300"], "--angle"),
    ],
)
def test_deflect_refuses_conflicting_or_out_of_range_operating_values(tmp_path, capsys, extra, args, words):
    # found by a new user's check: a second way to set the discharge edge was dropped silently
    text = (ROOT / "samples" / "rack_involute_5_6.toml").read_text().replace("[operating]\n", "[operating]\n" + extra)
    design = tmp_path / "p.toml"
    design.write_text(text)
    assert main(["deflect", str(design), *args]) == 2
    assert words in capsys.readouterr().err


def test_deflect_names_the_design_key_of_a_bad_speed(tmp_path, capsys):
    # deflect has no --speed: a NaN speed in the design is refused by its [operating] key
    text = (ROOT / "samples" / "rack_involute_5_6.toml").read_text().replace("speed_rpm = 3000", "speed_rpm = nan")
    design = tmp_path / "p.toml"
    design.write_text(text)
    assert main(["deflect", str(design)]) == 2
    err = capsys.readouterr().err
    assert "[operating] speed_rpm must be a positive speed" in err and "--speed" not in err


def test_indicator_must_cover_the_cycle(tmp_path, capsys, monkeypatch):
    # 0..200 deg only (or angles in radians by mistake) would hold the last pressure silently
    from rotorcad import deflection
    from rotorcad.cli.export_cmd import _rotor_options
    from rotorcad.cli.rotor import _build

    design = ROOT / "samples" / "rack_involute_5_6.toml"
    rotors, _, _ = _build(design, _rotor_options(design))
    end = np.degrees(deflection.GasDeflection(rotors, 1.0, 8.0, terms=3).cycle.angle[-1])  # the chamber table's cycle
    csv = tmp_path / "partial.csv"
    csv.write_text("angle_deg,pressure_bar\n0,1\n100,2\n200,4\n")

    def no_table(*args, **kwargs):  # refused before the chamber table (it was after its 2 s of CPU)
        raise AssertionError("deflect built the chamber table before checking --indicator")

    monkeypatch.setattr(deflection, "chamber_table", no_table)
    assert main(["deflect", str(design), "--indicator", str(csv), "--terms", "3"]) == 2
    err = capsys.readouterr().err
    assert "--indicator must cover the chamber's cycle from 0 to" in err and "200.0" in err
    assert f"from 0 to {end:.1f} deg" in err  # the cycle of the table, known before it is built


def test_plot_as_svg_by_its_suffix_and_no_special_file_replaced(tmp_path, capsys, built_in_deflect, monkeypatch):
    import xml.etree.ElementTree as ET

    design = str(ROOT / "samples" / "rack_involute_5_6.toml")
    _, svg = built_in_deflect  # `deflect SAMPLE --json --angle 17 --terms 5 --plot d.svg`
    assert ET.parse(svg).getroot().tag.endswith("svg")
    from test_pictures import check_picture  # units on every axis, the case in the title (issue 16)

    drawn = check_picture(svg, ["rack_involute_5_6.toml", "rack-involute 5/6", "1 → 8 bar"])
    # the paper's figure beside rotorcad's: Rinder & Deix's largest deflections (sec. 3.5) on the same
    # axes, and the other flute load's line (issue 23)
    assert "Rinder & Deix 5/6 at 12 bar: 0.5 µm" in drawn["text"] and "Rinder & Deix 5/6 at 12 bar: 2 µm" in drawn["text"]
    assert "|w| (paper load)" in drawn["text"] and "|w| (rotorcad load)" in drawn["text"]
    fifo = tmp_path / "fifo"
    os.mkfifo(fifo)
    from rotorcad.cli import deflect_cmd

    def no_work(*args, **kwargs):  # the FIFO is refused before the pair is built (it was after 2.5 s of work)
        raise AssertionError("deflect built the rotors before checking --plot")

    monkeypatch.setattr(deflect_cmd, "build_rotors", no_work)
    assert main(["deflect", design, "--angle", "17", "--terms", "3", "--plot", str(fifo)]) == 2
    assert "regular file" in capsys.readouterr().err and stat.S_ISFIFO(os.stat(fifo).st_mode)

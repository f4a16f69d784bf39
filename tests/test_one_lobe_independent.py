"""One lobe is enough, on a pair rotorcad did not make (issue 22 item 4).

Input: the 5/6 pair of ``tests/independent_pairs.py`` (``arc_flank_5_6``: one rack flank straight,
the other a circular arc, both rotors' tips cut back to sharp corners by the rack's flats), each rotor
cut by brute force with shapely, sampled as a CMM scans it (300 exact points a lobe, evenly along the
outline, the corners between the points). Each rotor is given to ``rotor``, ``hob`` and
``clearance`` three ways: its whole outline, one lobe (a window of one lobe pitch, from an arbitrary
angle), and one groove (the female, from tip land to tip land) or one tooth (the male, root land to
root land), which span less than the lobe pitch (49.9 of 60 and 59.7 of 72 deg here) and hold both
flanks. Reference: the same independent pair's whole outline, read by the same command (a lobe or
a groove is patterned; the whole outline is measured all round): the same defects by kind, rotor,
flank and generation, the same running verdict per flank, the transverse contact ratios within
0.01, the blow-hole within the uncertainties the two readings state, the same hob verdict and
smallest normal flank angle within 0.1 deg (issue 22 item 3's tolerance), and the clearance of the
exactly conjugate pair within the accuracy ``clearance`` states.
"""

from __future__ import annotations

import contextlib
import io
import json
from collections import Counter
from pathlib import Path

import numpy as np
import pytest
from independent_pairs import arc_flank_5_6, cut_rotor, one_lobe, scan

from exports.csv_points import write_points
from rotorcad.cli.main import main

PER_LOBE = 300
LEAD = 300.0


def land_to_land(points: np.ndarray, land_radius: float, teeth: int) -> np.ndarray:
    """The points from three quarters along one land (points within 0.1 µm of ``land_radius``) to one
    quarter along the next one: a groove (tip lands) or a tooth (root lands), less than a lobe pitch."""
    r, ang = np.hypot(*points.T), np.arctan2(points[:, 1], points[:, 0])
    on = np.abs(r - land_radius) < 1e-4
    pitch = 2 * np.pi / teeth
    rel = np.mod(ang - ang[on][0] + 0.5 * pitch, 2 * np.pi)  # one land near half a pitch, whole in [0, pitch)
    land = rel[on & (rel < pitch)]
    lo, hi = land.min(), land.max()
    start = lo + 0.75 * (hi - lo)
    end = start + pitch - 0.5 * (hi - lo)
    idx = np.flatnonzero((rel >= start) & (rel <= end))
    return points[idx[np.argsort(rel[idx])]]


def _run(*args) -> dict:
    out = io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(io.StringIO()):
        assert main([str(a) for a in args] + ["--json", "--quiet"]) == 0, args
    return json.loads(out.getvalue())


@pytest.fixture(scope="module")
def files(tmp_path_factory) -> tuple[dict[tuple[str, str], Path], list]:
    """The points files of each rotor in each form, and the pair's options."""
    folder = tmp_path_factory.mktemp("one_lobe")
    pair = arc_flank_5_6()
    paths = {}
    for rotor, z in (("male", pair.male_teeth), ("female", pair.female_teeth)):
        whole = scan(cut_rotor(pair, rotor), PER_LOBE * z, 0.37)
        r = np.hypot(*whole.T)
        forms = {
            "whole": whole,
            "lobe": one_lobe(whole, z, 10.0),
            "groove": land_to_land(whole, r.max() if rotor == "female" else r.min(), z),
        }
        span = np.ptp(np.unwrap(np.arctan2(forms["groove"][:, 1], forms["groove"][:, 0])))
        assert 0.75 * 2 * np.pi / z < span < 0.95 * 2 * np.pi / z  # less than a lobe pitch: not a lobe
        for form, pts in forms.items():
            paths[(rotor, form)] = folder / f"{rotor}_{form}.csv"
            write_points(paths[(rotor, form)], pts)
    dims = ["--male-teeth", pair.male_teeth, "--female-teeth", pair.female_teeth, "--center-distance", pair.center_distance]
    dims += ["--lead", LEAD]
    radii = [f"--{k.replace('_', '-')}={v!r}" for k, v in pair.radii().items()]
    return paths, [dims, radii]


@pytest.fixture(scope="module")
def rotor_runs(files) -> dict:
    paths, (dims, radii) = files
    return {key: _run("rotor", f"--{key[0]}-points", path, *dims, *radii) for key, path in paths.items()}


@pytest.fixture(scope="module")
def hob_runs(files) -> dict:
    paths, (dims, radii) = files
    return {key: _run("hob", f"--{key[0]}-points", path, *dims, *radii) for key, path in paths.items()}


def _defects(data: dict) -> Counter:
    return Counter((d["kind"], d["rotor"], d["flank_role"], d["point_generated"]) for d in data["defects"])


CASES = [(rotor, form) for rotor in ("male", "female") for form in ("lobe", "groove")]


@pytest.mark.parametrize(("rotor", "form"), CASES)
def test_rotor_from_one_lobe_or_groove_reads_as_the_whole_outline(rotor_runs, rotor, form):
    whole, part = rotor_runs[(rotor, "whole")], rotor_runs[(rotor, form)]
    assert _defects(part) == _defects(whole)
    assert part["runs_without_timing_gears"] == whole["runs_without_timing_gears"]
    for flank in ("driving", "sealing"):
        assert part["flanks"][flank]["runs_without_timing_gears"] == whole["flanks"][flank]["runs_without_timing_gears"]
        assert part["flanks"][flank]["transverse_contact_ratio"] == pytest.approx(
            whole["flanks"][flank]["transverse_contact_ratio"], abs=0.01
        )
    both = part["blow_hole_uncertainty"] + whole["blow_hole_uncertainty"]
    assert abs(part["blow_hole_area"] - whole["blow_hole_area"]) <= both + 1e-3 * whole["blow_hole_area"]


@pytest.mark.parametrize(("rotor", "form"), CASES)
def test_hob_from_one_lobe_or_groove_reads_as_the_whole_outline(hob_runs, rotor, form):
    whole, part = hob_runs[(rotor, "whole")], hob_runs[(rotor, form)]
    assert part["hobbable"] == whole["hobbable"]
    assert part["normal_pressure_angle_min_deg"] == pytest.approx(whole["normal_pressure_angle_min_deg"], abs=0.1)
    assert len(part["reasons"]) == len(whole["reasons"])
    assert part["rack_deviation"] == pytest.approx(whole["rack_deviation"], abs=2e-3)


@pytest.fixture(scope="module")
def clearance_whole(files) -> dict:
    paths, (dims, _) = files
    return _run("clearance", "--male-points", paths[("male", "whole")], "--female-points", paths[("female", "whole")], *dims)


@pytest.mark.parametrize(("male", "female"), [("lobe", "groove"), ("groove", "lobe")])
def test_clearance_from_one_lobe_and_one_groove_reads_as_the_whole_outlines(files, clearance_whole, male, female):
    # male lobe + female groove; male tooth (root land to root land) + female lobe
    paths, (dims, _) = files
    whole = clearance_whole
    part = _run("clearance", "--male-points", paths[("male", male)], "--female-points", paths[("female", female)], *dims)
    assert part["interference"] == whole["interference"] is False
    for key in ("max_normal_clearance", "min_normal_clearance", "mean_clearance"):
        assert part[key] == pytest.approx(whole[key], abs=max(part["accuracy"], whole["accuracy"])), key
    # the pair is exactly conjugate: both read 0 within the accuracy they state
    assert abs(part["max_normal_clearance"]) <= part["accuracy"] and abs(part["min_normal_clearance"]) <= part["accuracy"]
    assert part["contact_zone_share"] == pytest.approx(whole["contact_zone_share"], abs=0.05)

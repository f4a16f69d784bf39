"""Measure the hob's undercut verdict of a mate generated from points against brute force (issue 22 item 3; not a test).

Cases: the 5/6 arc-flank pair (tests/independent_pairs.py) from its female's points, whose male is undercut
(the brute-force cut); the N-rack and rack-involute samples from their male's points, whose female only touches
its rack at a slip singularity. For each: the mate's turn-back (hob.turn_back), the rack's cut depth into the
generated points, the gate it is compared with, the verdict, and the brute force: how deep the rack from the
points cuts the TRUE mate near the turn-back (tests/test_hob_datum.py::rack_penetration, shapely, 2000 positions).
Run from the repository: ``python benchmarks/bench_hob_turn_back.py [scale ...]`` (default 1; 0.25 and 2 scale the
pair: points, their scatter, centre distance, radii and lead); the last line counts the rows (a row is the verdict on the
judged place; "no turn-back" rows count too).
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tests"))

import test_hob_datum as hd
import test_hob_points_samples as samples
from independent_pairs import arc_flank_5_6, arc_flank_male_envelope, cut_rotor, resample
from test_racks_from_points import rotor_pair

from hob.cut_depth import cut_depths
from hob.rack import rotor_rack
from hob.turn_back import turn_back
from hob.verdict import depth_accuracy, hob_stalls, judge, local_scatter, one_place, undercut_tolerance
from rotorcad.measured.cusp_paths import with_exact_cusp_paths
from rotorcad.measured.pairs import pair_from_rotor_points
from rotorcad.rotor_pair import RotorPair

TALLY: dict[str, int] = {}  # rows by label: ok, undecided, WRONG


def scaled_pair(pair: RotorPair, k: float) -> RotorPair:
    return RotorPair(
        pair.male_teeth,
        pair.female_teeth,
        pair.center_distance * k,
        pair.male_tip_radius * k,
        pair.male_root_radius * k,
        pair.female_tip_radius * k,
        pair.female_root_radius * k,
        lead=pair.lead * k,
        length=pair.length * k,
        strict=False,
    )


def view(pair: RotorPair, points: np.ndarray, rotor: str, mate: str):
    rotors = with_exact_cusp_paths(pair_from_rotor_points(pair, points, rotor))
    rack = rotor_rack(rotors, mate, **samples.MEASURED)
    tol = undercut_tolerance(rotors)
    verdict = judge(
        rack,
        accuracy=rotors.accuracy,
        measured=False,
        undercut_accuracy=tol,
        tangent_accuracy=rotors.tangent_accuracy,
        point_scatter=local_scatter(rotors)[0],
        point_spacing=local_scatter(rotors)[1],
    )
    return rotors, rack, tol, verdict


def measure(label: str, pair, points, rotor, mate, truth_outline, truth_undercut: bool, datum: float = 0.0) -> None:
    rotors, rack, tol, verdict = view(pair, points, rotor, mate)
    runs = [(a, b) for a, b, back in one_place(rack, hob_stalls(rack)) if back]  # as judged
    if not runs:
        ok = "undecided" if verdict.undercut_undecided and not verdict.undercut else "ok"
        ok = "WRONG" if verdict.undercut != truth_undercut and ok == "ok" else ok
        print(f"{label:38s} no turn-back; undercut={verdict.undercut} truth={truth_undercut} {ok}")
        TALLY[ok] = TALLY.get(ok, 0) + 1
        return
    a, b = runs[0]
    lo, depths = cut_depths(rack, a, b)
    onset = turn_back(rack, a, b, rotors.accuracy, rotors.tangent_accuracy > 0)
    floor = depth_accuracy(rack, lo, depths, *local_scatter(rotors))
    teeth = pair.male_teeth if mate == "male" else pair.female_teeth
    # the brute force at datum 0 only: the truth is in the unturned frame (a turned scan's is judged, not checked)
    bf = float(hd.rack_penetration(rotors, mate, hd.near_turn_back(rack, truth_outline, teeth)).max()) if not datum else np.nan
    ok = "undecided" if verdict.undercut_undecided and not verdict.undercut else "ok"
    ok = "WRONG" if verdict.undercut != truth_undercut and ok == "ok" else ok
    print(
        f"{label:38s} acc {1e3 * rotors.accuracy:6.2f} depth {1e3 * depths.max():7.2f} gate {1e3 * tol:6.2f} "
        f"floor {1e3 * floor:5.2f} f0 {onset.onset:+.3f} +-{onset.accuracy:.3f} se {onset.spread:.3f} "
        f"undercut={verdict.undercut!s:5} undecided={verdict.undercut_undecided!s:5} truth={truth_undercut!s:5} "
        f"bf {1e3 * bf:6.2f} um {ok}"
    )
    TALLY[ok] = TALLY.get(ok, 0) + 1


def cases_56(k: float, forms, seeds, datums) -> None:
    rp = arc_flank_5_6()
    pair = scaled_pair(rotor_pair("5/6"), k)
    ring = cut_rotor(rp, "female")
    length = float(np.hypot(*np.diff(np.vstack([ring, ring[:1]]), axis=0).T).sum())
    truth = arc_flank_male_envelope(k)
    for per_lobe, noise in forms:
        for seed in seeds if noise else seeds[:1]:
            q = resample(ring, length / rp.female_teeth / per_lobe, noise=noise, seed=seed)
            for datum in datums:
                c, s = np.cos(np.radians(datum)), np.sin(np.radians(datum))
                p = np.round(k * q @ np.array([[c, s], [-s, c]]), 6)
                label = f"5/6 x{k} {per_lobe}/{1e3 * noise:.0f}um s{seed} d{datum}"
                measure(label, pair, p, "female", "male", truth, True, datum)


def cases_samples(k: float, name: str, forms, seeds) -> None:
    spec, design = samples.design(name)
    pair = scaled_pair(spec.pair, k)
    lobe = design.female_outline(1e-4)
    truth = k * np.vstack([seg.points for seg in lobe.segments])
    for per_lobe, noise in forms:
        for seed in seeds if noise else seeds[:1]:
            q = hd.cmm_points(name, "male", per_lobe, noise, seed, 0.0, 0.37)
            measure(
                f"{name} x{k} {per_lobe}/{1e3 * noise:.0f}um s{seed}", pair, np.round(k * q, 6), "male", "female", truth, False
            )


if __name__ == "__main__":
    scales = [float(a) for a in sys.argv[1:] if a[0].isdigit()] or [1.0]
    quick = "--quick" in sys.argv  # one seed, datum 0
    seeds, datums = ([11], [0.0]) if quick else ([11, 12, 13], [0.0, 17.3])
    for k in scales:
        cases_56(k, [(300, 0.0), (300, 2e-3), (2000, 1e-3), (2000, 2e-3)], seeds, datums)
        cases_samples(k, "n_rack_5_6", [(300, 2e-3), (2000, 2e-3)], seeds[:2])
        cases_samples(k, "rack_involute_5_6", [(300, 2e-3)], seeds[:2])
    print(" ".join(f"{key} {n}" for key, n in sorted(TALLY.items())))

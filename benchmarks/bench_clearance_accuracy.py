"""Accuracy of ``rotorcad clearance`` from CMM-like points, by density and scatter (README).

Pairs that rotorcad did not make (tests/independent_pairs.py, cut by brute force with shapely):
the 4/6 trapezoid rack pair and the 5/6 pair of a rack with one straight and one circular-arc flank
(its male undercut 90 um deep at r = 42.3-42.7 mm), both with sharp tip corners cut back by the
rack's flats. Each rotor's cut outline is resampled at 80, 300 and 2000 points a lobe with 0, 1 and
2 um Gaussian scatter along the normals (seeds 1-5), straight rotors (lead 1e5 mm: the normal
section is the transverse one), racks brought into contact on the driving flank.

Truth, not produced by rotorcad: the brute-force closest approach of the two cut outlines over 1500
mesh positions (``independent_pairs.true_gap``) at every third contact-zone row's female point
and at the 20 rows of largest |clearance|. Printed per case, over the seeds: the largest error on
the contact zone, the largest ratio of that error to the stated ``accuracy``, the stated accuracy,
the largest shift of the contact alignment (truth 0: both rotors cut by one rack at one phase), and
how many seeds raise the interference flag (truth: never, the contact zone is nowhere negative),
and the largest share of the contact line left out of the contact zone as unresolved (the flank
beside the 5/6 male's undercut corner that sparse points round over, ``ClearanceZone.UNRESOLVED``).

Run by hand: ``python benchmarks/bench_clearance_accuracy.py [seeds] [densities] [pair] [scatters]`` (about 10 minutes
for 5 seeds on an idle machine; densities a comma-separated list of points a lobe, default 2000,300,80;
pair ``4/6``, ``5/6``, ``N`` (the N-rack sample thinned by 30 µm, :func:`n_rack_rows`) or ``N-exact``
(the N-rack sample's own conjugate outlines, truth 0, seed by seed: :func:`n_rack_exact_rows`), default
the first two; scatters a comma-separated list in µm, default 0,1,2). CPU: process time of the fits
and the clearance of one case (``time.process_time``). ``CLEARANCE_REACH=a,b``: :func:`trial_reaches`.
"""

from __future__ import annotations

import os

os.environ.setdefault("OMP_NUM_THREADS", "1")
os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tests"))

from independent_pairs import arc_flank_5_6, cut_rotor, resample, trapezoid_4_6, true_gap

from rotorcad.clearance import MeshingClearance, pair_quality
from rotorcad.cli.clearance_cmd import INTERFERENCE_THRESHOLD
from rotorcad.measured.fit import close_smoothing
from rotorcad.rotor_pair import RotorPair
from rotorcad.rotor_points import lobe_pieces


def per_lobe(ring: np.ndarray, teeth: int, points: int) -> float:
    return float(np.hypot(*np.diff(np.vstack([ring, ring[:1]]), axis=0).T).sum()) / teeth / points


def evaluate(pair: RotorPair, male: np.ndarray, female: np.ndarray, **kw) -> MeshingClearance:
    quality = pair_quality(male, female, (pair.male_teeth, pair.female_teeth))
    return MeshingClearance(
        pair,
        lobe_pieces(pair, male, "male", close_smoothing, roundings=True),  # as rotorcad clearance fits them
        lobe_pieces(pair, female, "female", close_smoothing, roundings=True),
        **kw,
        **quality,
    )


def errors(rack_pair, male, female, mc: MeshingClearance) -> np.ndarray:
    """|clearance - brute-force truth| on the contact zone (every third row and the 20 largest)."""
    d = mc.distribution()
    on = np.flatnonzero(mc.contact_zone)
    c = mc.clearance[on]
    pick = np.union1d(np.arange(0, len(on), 3), np.argsort(-np.abs(c))[:20])
    pts = np.column_stack([d["female_x"], d["female_y"]])[on[pick]]
    return np.abs(c[pick] - true_gap(rack_pair, female, male, pts))


def n_rack_rows(seeds: range, densities: list[int]) -> None:
    """The N-rack sample (samples/n_rack_5_6.toml, helical: lead 226 mm) with its female thinned by a
    uniform 30 um normal clearance (``rotor --clearance 0.03``), read as given (both at the mesh
    position). Truth: the brute-force transverse closest approach of the design male to the thinned
    female (1500 positions) at every fourth contact-zone row and the 20 farthest from 30 um, turned
    into the normal section by the flank's stretch. The rows "1 µm chords" resample the outlines
    written at 1 µm chords (points on a polygon, no scatter)."""
    import tomllib

    from independent_pairs import closest_approach, scan

    from rotorcad.clearance_design import ClearanceDistribution, corrected_female
    from rotorcad.design import rotor_design
    from rotorcad.rotor_build import build_pair, pair_spec

    samples = Path(__file__).resolve().parents[1] / "samples"
    rotors = build_pair(pair_spec(rotor_design(tomllib.loads((samples / "n_rack_5_6.toml").read_text()), samples)))
    p = rotors.pair
    for chord, label in ((1e-4, ""), (1e-3, " (1 µm chords)")):
        male = rotors.male_outline(chord).points
        female = corrected_female(rotors, ClearanceDistribution.uniform(0.03), chord)[:-1]
        for points in densities:
            for noise in (0.0, 1e-3, 2e-3) if not label else (0.0,):
                worst, ratio, accuracy, flags = [], [], [], 0
                for seed in seeds if noise else [0]:
                    rng = np.random.default_rng(seed)
                    scans = []
                    for ring, teeth in ((male, 5), (female, 6)):
                        pts = scan(ring, points * teeth, 0.37)
                        d = np.roll(pts, -1, axis=0) - np.roll(pts, 1, axis=0)
                        normal = np.column_stack([d[:, 1], -d[:, 0]]) / np.hypot(*d.T)[:, None]
                        scans.append(pts + rng.normal(0.0, noise, len(pts))[:, None] * normal if noise else pts)
                    m, f = scans
                    rm, rf = np.hypot(*m.T), np.hypot(*f.T)
                    pair = RotorPair(
                        5, 6, p.center_distance, rm.max(), rm.min(), rf.max(), rf.min(), p.lead, p.length, strict=False
                    )
                    mc = evaluate(pair, m, f, contact="as-given")
                    s, dist = mc.summary(), mc.distribution()
                    on = np.flatnonzero(mc.contact_zone)
                    c = mc.clearance[on]
                    pick = np.union1d(np.arange(0, len(on), 4), np.argsort(-np.abs(c - 0.03))[:20])
                    at = np.column_stack([dist["female_x"], dist["female_y"]])[on[pick]]
                    near = female[np.argmin(np.hypot(*(female[None, :, :] - at[:, None, :]).transpose(2, 0, 1)), axis=1)]
                    tan = mc.female_rack.tangents[on[pick]]
                    stretch = np.sqrt(tan[:, 1] ** 2 / np.cos(mc.helix_angle) ** 2 + tan[:, 0] ** 2)
                    truth = closest_approach(p, near, male, positions=1500, window_deg=70.0) / stretch
                    e = float(np.abs(c[pick] - truth).max())
                    worst.append(e)
                    ratio.append(e / s["accuracy"])
                    accuracy.append(s["accuracy"])
                    flags += s["min_normal_clearance"] < -max(INTERFERENCE_THRESHOLD, s["accuracy"])
                print(
                    f"| N-rack 5/6, 30 µm{label} | {points} | {noise * 1e3:.0f} µm | {max(worst) * 1e3:.1f} µm "
                    f"| {max(ratio):.2f} "
                    f"| {min(accuracy) * 1e3:.1f}-{max(accuracy) * 1e3:.1f} µm | as given | {flags}/{len(worst)} | |",
                    flush=True,
                )


def n_rack_exact_rows(seeds: range, densities: list[int], noises: tuple[float, ...] = (0.0, 2e-3)) -> None:
    """The N-rack sample's own exact conjugate outlines (``rotor samples/n_rack_5_6.toml --male-csv
    --female-csv``: the written 1 um chords), resampled at ``points`` a lobe evenly along each outline
    (:func:`independent_pairs.resample`) with Gaussian scatter along the normals, read as the
    ``clearance`` command reads them (default contact alignment, the sample's lead and length). Truth:
    0 on the contact zone (both outlines conjugate, within the chords' 1 um). Printed per seed: the
    largest |clearance| on the contact zone, the stated accuracy, the unresolved share, CPU of the fits
    and the clearance."""
    import tomllib

    from rotorcad.cli.rotor import _exterior
    from rotorcad.design import rotor_design
    from rotorcad.roles import Side
    from rotorcad.rotor_build import build_pair, pair_spec

    samples = Path(__file__).resolve().parents[1] / "samples"
    rotors = build_pair(pair_spec(rotor_design(tomllib.loads((samples / "n_rack_5_6.toml").read_text()), samples)))
    p = rotors.pair
    male = _exterior(rotors.section(Side.MALE, 1e-3, exact_tip=True))
    female = _exterior(rotors.section(Side.FEMALE, 1e-3, exact_tip=True))
    for points in densities:
        for noise in noises:
            for seed in seeds if noise else [0]:
                m = resample(male, per_lobe(male, 5, points), noise, seed=seed)
                f = resample(female, per_lobe(female, 6, points), noise, seed=seed + 100)
                rm, rf = np.hypot(*m.T), np.hypot(*f.T)
                pair = RotorPair(5, 6, p.center_distance, rm.max(), rm.min(), rf.max(), rf.min(), p.lead, p.length, strict=False)
                t0 = time.process_time()
                mc = evaluate(pair, m, f)
                s = mc.summary()
                cpu = time.process_time() - t0
                e = float(np.abs(mc.clearance[mc.contact_zone]).max())
                print(
                    f"| N-rack 5/6 exact outlines | {points} | {noise * 1e3:.0f} µm | {seed} | {e * 1e3:.1f} µm "
                    f"| {s['accuracy'] * 1e3:.1f} µm | {100 * s['unresolved_share']:.1f} % | {cpu:.1f} s |",
                    flush=True,
                )


def trial_reaches() -> None:
    """With ``CLEARANCE_REACH=a,b`` in the environment, measure the unresolved zone's reaches as a trial:
    a point spacings (and 0.02 mm) beside a male stall below its tip (main: 4), b beside a sharp corner
    (main: 2); README's "halving both reaches" is ``CLEARANCE_REACH=2,1``."""
    if not os.environ.get("CLEARANCE_REACH"):
        return
    stall, corner = (float(v) for v in os.environ["CLEARANCE_REACH"].split(","))
    MeshingClearance.unresolved_reach = property(lambda self: 0.02 + stall * self.spacing)
    MeshingClearance.corner_reach = property(lambda self: 0.02 + corner * self.spacing)


def main() -> None:
    trial_reaches()
    seeds = range(1, 1 + (int(sys.argv[1]) if len(sys.argv) > 1 else 5))
    densities = [int(v) for v in sys.argv[2].split(",")] if len(sys.argv) > 2 else [2000, 300, 80]
    scatters = [float(v) * 1e-3 for v in sys.argv[4].split(",")] if len(sys.argv) > 4 else [0.0, 1e-3, 2e-3]
    if len(sys.argv) > 3 and sys.argv[3].lower() == "n-exact":
        print("| outlines | points a lobe | scatter | seed | largest error, contact zone | stated accuracy | unresolved | CPU |")
        print("|---|---|---|---|---|---|---|---|")
        n_rack_exact_rows(seeds, densities, tuple(scatters) if len(sys.argv) > 4 else (0.0, 2e-3))
        return
    head = "| pair | points a lobe | scatter | error on the contact zone | error / accuracy | stated accuracy | alignment |"
    print(head + " interference | unresolved | CPU a case |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    pairs = (("4/6 trapezoid", trapezoid_4_6()), ("5/6 arc flank", arc_flank_5_6()))
    if len(sys.argv) > 3 and sys.argv[3].lower().startswith("n"):
        n_rack_rows(seeds, densities)
        return
    for label, rack_pair in [p for p in pairs if len(sys.argv) < 4 or p[0].startswith(sys.argv[3])]:
        male, female = cut_rotor(rack_pair, "male"), cut_rotor(rack_pair, "female")
        z1, z2 = rack_pair.male_teeth, rack_pair.female_teeth
        pair = RotorPair(z1, z2, 100.0, **rack_pair.radii(), lead=1e5, length=1e5, strict=False)
        for points in densities:
            for noise in scatters:
                worst, ratio, shifts, accuracy, flags, unresolved, cpu = [], [], [], [], 0, [], []
                for seed in seeds if noise else [0]:
                    m = resample(male, per_lobe(male, z1, points), noise, seed=seed)
                    f = resample(female, per_lobe(female, z2, points), noise, seed=seed + 100)
                    t0 = time.process_time()
                    mc = evaluate(pair, m, f)
                    s = mc.summary()
                    cpu.append(time.process_time() - t0)
                    e = errors(rack_pair, male, female, mc)
                    worst.append(float(e.max()))
                    ratio.append(float(e.max()) / s["accuracy"])
                    shifts.append(abs(s["female_rack_shift"]))
                    accuracy.append(s["accuracy"])
                    unresolved.append(s["unresolved_share"])
                    flags += s["min_normal_clearance"] < -max(INTERFERENCE_THRESHOLD, s["accuracy"])
                n = len(worst)
                print(
                    f"| {label} | {points} | {noise * 1e3:.0f} µm | {max(worst) * 1e3:.1f} µm | {max(ratio):.2f} "
                    f"| {min(accuracy) * 1e3:.1f}-{max(accuracy) * 1e3:.1f} µm | {max(shifts) * 1e3:.1f} µm | {flags}/{n} "
                    f"| {100 * max(unresolved):.1f} % | {max(cpu):.1f} s |",
                    flush=True,
                )


if __name__ == "__main__":
    main()

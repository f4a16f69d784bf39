"""Speed of the inverse path from measured points (issue: profiles users bring): the rack-involute
5/6 sample's outlines resampled to 5000 points each with 1 um Gaussian scatter (a CMM), then

* the meshing clearance (Wu & Chi): fit (scatter estimated, smoothing spline, corners, lands),
  both racks, positioning on the driving flank, clearance along the datum rack (target 0.2 s);
* the clearance band on the 3D contact line over the male rotation angle (target 0.5 s);
* the hob derivation from the male's points: fit, rack by inverse generation, verdict (0.1 s).

Run by hand: ``python benchmarks/bench_clearance.py``; best and median of 7 runs.
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

from independent_pairs import resample

from hob.rack import rotor_rack
from hob.verdict import judge
from rotorcad.clearance import MeshingClearance
from rotorcad.cli.common import load_rotor_design
from rotorcad.rotor_families import build_family
from rotorcad.rotor_pair import RotorPair
from rotorcad.rotor_points import lobe_pieces, pair_from_rotor_points

RUNS = 7


def timed(fn) -> tuple[float, float, object]:
    runs, out = [], None
    for _ in range(RUNS):
        t = time.perf_counter()
        out = fn()
        runs.append(time.perf_counter() - t)
    return min(runs), float(np.median(runs)), out


def main() -> None:
    d = load_rotor_design(Path("samples/rack_involute_5_6.toml"))
    pair = RotorPair(**d["pair"])
    rotors = build_family(pair, d["family"], d["params"])
    outlines = [rotors.male_outline(1e-4).points, rotors.female_outline(1e-4).points]
    male, female = (resample(p, spacing=_perimeter(p) / 5000, noise=1e-3, seed=k) for k, p in enumerate(outlines))
    hot = dict(pair=RotorPair(**{**d["pair"], "strict": False}))

    def clearance() -> MeshingClearance:
        p = hot["pair"]
        mc = MeshingClearance(p, lobe_pieces(p, male, "male"), lobe_pieces(p, female, "female"), contact="driving")
        mc.clearance  # noqa: B018
        return mc

    best, median, mc = timed(clearance)
    print(
        f"clearance, driving contact ({len(male)} + {len(female)} points): best {best * 1e3:.0f} ms, median {median * 1e3:.0f} ms"
    )
    best, median, summary = timed(lambda: MeshingClearance._band.func(mc))
    print(
        f"band on the contact line ({int(np.isfinite(mc.clearance).sum())} datum points over the male angle): "
        f"best {best * 1e3:.1f} ms, median {median * 1e3:.1f} ms; max {summary['max_normal_clearance'] * 1e3:.2f} um, "
        f"equal {summary['equal_clearance'] * 1e3:.2f} um"
    )

    def hob() -> bool:
        rebuilt = pair_from_rotor_points(pair, male, "male")
        return judge(rotor_rack(rebuilt, "male")).hobbable

    best, median, ok = timed(hob)
    print(f"hob from male points (fit, rack, verdict): best {best * 1e3:.0f} ms, median {median * 1e3:.0f} ms; hobbable {ok}")


def _perimeter(p: np.ndarray) -> float:
    return float(np.hypot(*np.diff(np.vstack([p, p[:1]]), axis=0).T).sum())


if __name__ == "__main__":
    main()

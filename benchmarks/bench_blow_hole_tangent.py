"""How well scattered points can know the tangent that places the blow-hole's apex (issue 21 item 3).

On the narrow-tip and the asymmetric SRM the blow-hole's apex is where the male sealing tip corner's
path on the tip circle hands over to the sealing flank's: where the flank's normal at the corner
passes through the pitch point C (Rinder, *Special toothings for screw-compressor rotors*, sec. 2.2.1
and 2.2.2). It moves r delta / |beta' - 1| along the tip circle for a tangent turned by delta
(:attr:`rotorcad.meshing.MeshingAnalysis.blow_hole_uncertainty`). This script measures, per sample:

* the blow-hole's change per mrad of tangent (the design's apex turned both ways);
* by Monte Carlo (40 seeds of 1 µm normal scatter on the CSV's points), the error of the flank's
  tangent at the corner from an estimator given more than the pipeline has: the points of *all*
  lobes turned onto one, a polynomial through the *exact* corner (the design's), over a window and
  of a degree chosen afterwards as the best of several against the design (an oracle). Its RMS
  error bounds from below what any such local fit achieves; the tangent accuracy 1 % needs is
  1 % divided by the change per mrad.

Run by hand: ``python benchmarks/bench_blow_hole_tangent.py [samples] [seeds]`` (about 20 s).
"""

from __future__ import annotations

import sys
import tomllib
from pathlib import Path

import numpy as np

from rotorcad.design import rotor_design
from rotorcad.geometry import rotate
from rotorcad.meshing import MeshingAnalysis
from rotorcad.rotor_build import build_pair, pair_spec

SAMPLES = Path(__file__).resolve().parents[1] / "samples"
FLANK = "sealing flank"  # the segment whose end at the tip corner places the apex (both samples)


def area_per_mrad(analysis: MeshingAnalysis) -> float:
    """Change of the blow-hole (per cent of it) per mrad of the flank's tangent at the tip corner."""
    e = analysis.meshline_end
    r, phi = float(np.hypot(*e)), float(np.arctan2(e[1], e[0]))
    c = np.array([analysis.rotors.pair.male_pitch_radius, 0.0])
    v, dx = c - e, r * np.array([-np.sin(phi), np.cos(phi)])
    rate = float((v[0] * -dx[1] - v[1] * -dx[0]) / (v @ v))  # beta'
    turn = 1e-3 / abs(rate - 1.0)
    moved = [analysis._blow_hole_at(r * np.array([np.cos(phi + t), np.sin(phi + t)])).area for t in (turn, -turn)]
    return 100.0 * 0.5 * abs(moved[0] - moved[1]) / analysis.blow_hole_area


def tangent_errors(name: str, seeds: list[int], sigma: float = 1e-3) -> tuple[float, dict[tuple[float, int], np.ndarray]]:
    """Return the area change per mrad and, per (window mm, degree), the tangent errors (rad) over the seeds."""
    spec = pair_spec(rotor_design(tomllib.loads((SAMPLES / f"{name}.toml").read_text()), SAMPLES))
    rotors = build_pair(spec)
    analysis = MeshingAnalysis(rotors, spec.speed_rpm)
    ring = np.asarray(analysis.sections[0].exterior.coords)[:-1]  # what `rotor --male-csv` writes
    fine = next(s for s in rotors.male_lobe().segments if s.name.startswith(FLANK)).resampled(1e-5).points
    corner = fine[0]  # the tip corner (the segment runs from it)
    u = (fine[-1] - corner) / np.hypot(*(fine[-1] - corner))
    v = np.array([-u[1], u[0]])
    local = np.column_stack([(fine - corner) @ u, (fine - corner) @ v])
    near = local[:, 0] < 0.5
    truth = float(np.polyval(np.polyder(np.polyfit(local[near, 0], local[near, 1], 4)), 0.0))  # slope at the corner
    from scipy.spatial import cKDTree

    tree = cKDTree(fine)
    teeth = spec.pair.male_teeth
    out: dict[tuple[float, int], list[float]] = {}
    for seed in seeds:
        noisy = ring + np.random.default_rng(seed).normal(0.0, sigma, ring.shape)
        pooled = np.vstack([rotate(noisy, -2 * np.pi * k / teeth) for k in range(teeth)])  # every lobe onto one
        on = tree.query(pooled)[0] < 0.05
        uv = np.column_stack([(pooled[on] - corner) @ u, (pooled[on] - corner) @ v])
        uv = uv[uv[:, 0] > 0.05]  # off the corner itself
        for window in (4.0, 6.0, 9.0, 13.0):
            for degree in (2, 3, 4):
                m = uv[:, 0] < window
                a = np.column_stack([uv[m, 0] ** k for k in range(1, degree + 1)])  # through the exact corner
                slope = np.linalg.lstsq(a, uv[m, 1], rcond=None)[0][0]
                out.setdefault((window, degree), []).append(float(np.arctan(slope) - np.arctan(truth)))
    return area_per_mrad(analysis), {k: np.asarray(e) for k, e in out.items()}


def main(argv: list[str]) -> None:
    names = (argv[0] if argv else "narrow_tip_5_6,srm_asymmetric_5_6").split(",")
    seeds = list(range(int(argv[1]) if len(argv) > 1 else 40))
    for name in names:
        per_mrad, errors = tangent_errors(name, seeds)
        rms = {k: 1e3 * float(np.sqrt(np.mean(e**2))) for k, e in errors.items()}
        best = min(rms, key=rms.get)
        print(
            f"{name}: blow-hole {per_mrad:.2f} % per mrad, 1 % needs {1.0 / per_mrad:.3f} mrad; best pooled fit "
            f"through the exact corner ({best[0]:g} mm, degree {best[1]}): {rms[best]:.3f} mrad RMS "
            f"= {rms[best] * per_mrad:.1f} % of the blow-hole ({len(seeds)} seeds of 1 µm)"
        )
        for (window, degree), value in sorted(rms.items()):
            bias = 1e3 * errors[(window, degree)].mean()
            print(f"    window {window:4.1f} mm, degree {degree}: {value:.3f} mrad RMS, bias {bias:+.3f}")


if __name__ == "__main__":
    main(sys.argv[1:])

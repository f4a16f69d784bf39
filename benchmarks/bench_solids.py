"""Speed and memory of issue 5 on the issue's case: a 5/6 pair, male tip diameter 100 mm,
L/D 1.6, wrap 300 deg, surface tolerance 5 um. Targets: both solids < 1.5 s, interference sweep over
one pitch at 72 angles < 5 s, binary STL of a 1-million-triangle solid < 0.5 s, peak memory < 2 GB.
Run by hand: ``python benchmarks/bench_solids.py``."""

from __future__ import annotations

import resource
import tempfile
import time
from pathlib import Path

from exports.meshes import write_mesh
from rotorcad.interference import interference_2d, intersection_3d
from rotorcad.rotor_families import build_family
from rotorcad.rotor_pair import RotorPair
from rotorcad.solids import helical_solid


def main() -> None:
    length = 160.0
    pair = RotorPair(5, 6, 92.0, 50.0, 35.0, 57.0, 42.0, lead=length * 360.0 / 300.0, length=length)
    rotors = build_family(pair, "rack-involute", {"tip_rounding": 1.4, "root_rounding": 1.0, "lobe_width": 0.6})
    tol = 0.005
    t = time.perf_counter()
    male_s, female_s = rotors.section("male", tol / 2), rotors.section("female", tol / 2)
    t_sec = time.perf_counter() - t
    t = time.perf_counter()
    male = helical_solid(male_s, pair.lead, pair.length, tol)
    female = helical_solid(female_s, -pair.female_lead, pair.length, tol)
    male.manifold.num_tri()  # force evaluation
    female.manifold.num_tri()
    t_solids = time.perf_counter() - t
    print(
        f"sections {t_sec:.2f} s; both solids {t_solids:.2f} s (target < 1.5 s): {male.manifold.num_tri()} + "
        f"{female.manifold.num_tri()} triangles, {male.layers} / {female.layers} layers"
    )
    t = time.perf_counter()
    result = interference_2d(pair, male_s, female_s, 72, tol)
    print(
        f"interference sweep, 72 angles by the 2D-section integral: {time.perf_counter() - t:.2f} s (target < 5 s); "
        f"max {result.max_volume:.4f} mm3, threshold {result.threshold:.2f} mm3"
    )
    t = time.perf_counter()
    check = intersection_3d(pair, male, female, result.angle_of_max, result.threshold)
    print(f"one 3D boolean at the same tolerance: {time.perf_counter() - t:.2f} s, {check['volume']:.4f} mm3")
    mesh = male.mesh
    with tempfile.TemporaryDirectory() as d:
        t = time.perf_counter()
        write_mesh(Path(d) / "m.stl", mesh, "stl")
        dt = time.perf_counter() - t
        scale = 1e6 / len(mesh.faces)
    print(f"binary STL of {len(mesh.faces)} triangles: {dt:.2f} s (about {dt * scale:.2f} s per million; target < 0.5 s)")
    peak = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024
    print(f"peak resident memory: {peak:.0f} MB (target < 2048 MB)")


if __name__ == "__main__":
    main()

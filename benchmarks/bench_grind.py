"""Speed of issue 29: the form-grinding wheel of every screw-rotor sample's male and female and of
the sample gear (spur, and helical at 15 deg): the wheel for the new and the worn radius, each
checked (stock at the flute and the lobes either side, round trip), and the sensitivities of the new
wheel (target < 1 s per rotor; the pair's own generation is timed apart, it is not grinding); then
the whole command, ``rotorcad grind SAMPLE --rotor BODY --wheel-radius 100 --out DIR --plot PNG``, in
one process per body after a first run that loads the libraries: its CPU time (process time, so
that other load on the machine counts little) with the pair's generation, the wheel, its check, the
sensitivities, the dresser's CSV and DXF and the chart.

Run by hand: ``python benchmarks/bench_grind.py``.
"""

from __future__ import annotations

import os

os.environ.setdefault("OMP_NUM_THREADS", "1")
os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import contextlib
import io
import tempfile
import time
import tomllib
from pathlib import Path

import numpy as np

from rotorcad.design.rotors import build_pair, pair_spec
from rotorcad.design.schema import rotor_design
from rotorcad.gears import InvoluteGear
from rotorcad.grinding import grind, sensitivities

SAMPLES = Path(__file__).resolve().parents[1] / "samples"
WHEEL, WORN = 100.0, 80.0


def time_rotor(outline, twist: float, lobes: int, pitch: float, wheel: float, worn: float) -> tuple[float, dict]:
    """Seconds for the new and the worn wheel, checked, and the new wheel's sensitivities; the new wheel's figures."""
    t = time.perf_counter()
    new = grind(outline, twist, lobes, wheel, pitch)
    grind(outline, twist, lobes, worn, pitch)
    sensitivities(new.wheel)
    return time.perf_counter() - t, new.summary()


def main() -> None:
    rows = []
    for path in sorted(SAMPLES.glob("*.toml")):
        data = tomllib.loads(path.read_text())
        if "pair" not in data:
            continue
        t = time.perf_counter()
        rotors = build_pair(pair_spec(rotor_design(data, path.parent)))
        build = time.perf_counter() - t
        pair = rotors.pair
        hand = 1.0 if pair.hand == "right" else -1.0
        for side in ("male", "female"):
            outline = rotors.male_outline() if side == "male" else rotors.female_outline()
            lead = hand * pair.lead if side == "male" else -hand * pair.female_lead
            pitch = pair.male_pitch_radius if side == "male" else pair.female_pitch_radius
            lobes = pair.male_teeth if side == "male" else pair.female_teeth
            seconds, s = time_rotor(outline, 2 * np.pi / lead, lobes, pitch, WHEEL, WORN)
            rows.append((f"{path.stem} {side}", build, seconds, s))
    for beta in (0.0, 15.0):
        gear = InvoluteGear(teeth=17, module=3.0, helix_angle=np.radians(beta), shift=0.3, tolerance=1e-4)
        outline = gear.outline()
        seconds, s = time_rotor(outline, np.tan(gear.helix_angle) / gear.pitch_radius, 17, gear.pitch_radius, 60.0, 50.0)
        rows.append((f"gear z=17 m=3 beta={beta:g}", 0.0, seconds, s))
    print(f"{'rotor':34s} {'pair s':>7s} {'grind s':>8s} {'points':>7s} {'cut um':>8s} {'unreached':>9s} {'trip mm':>9s}")
    for name, build, seconds, s in rows:
        print(
            f"{name:34s} {build:7.2f} {seconds:8.2f} {s['profile_point_count']:7d} {s['secondary_cutting_deviation'] * 1e3:8.1f} "
            f"{s['unreached_point_count']:9d} {s['round_trip_deviation']:9.1e}"
        )
    worst = max(r[2] for r in rows)
    print(f"slowest grinding (new + worn wheel, checked, sensitivities): {worst:.2f} s (target < 1 s per rotor)")


def command_seconds() -> list[tuple[str, float]]:
    """CPU seconds of ``rotorcad grind`` per body of every sample (module docstring)."""
    from rotorcad.cli.main import main as rotorcad

    rows = []
    with tempfile.TemporaryDirectory() as folder:

        def run(path: Path, body: str) -> float:
            out = Path(folder) / f"{path.stem}_{body}"
            args = ["grind", str(path), "--rotor", body, "--wheel-radius", "100", "--out", str(out), "--plot", f"{out}.png"]
            with contextlib.redirect_stdout(io.StringIO()):
                t = time.process_time()
                assert rotorcad([*args, "--json"]) == 0
                return time.process_time() - t

        run(SAMPLES / "gear_pair.toml", "gear")  # the libraries loaded once
        for path in sorted(SAMPLES.glob("*.toml")):
            data = tomllib.loads(path.read_text())
            bodies = ("male", "female") if "pair" in data else ("gear", "mate") if "gear" in data else ()
            rows += [(f"{path.stem} {body}", run(path, body)) for body in bodies]
    return rows


if __name__ == "__main__":
    main()
    timed = command_seconds()
    for name, seconds in timed:
        print(f"rotorcad grind {name:30s} {seconds:6.2f} s CPU")
    print(f"slowest command (files and chart included): {max(s for _, s in timed):.2f} s CPU, load {os.getloadavg()[0]:.1f}")

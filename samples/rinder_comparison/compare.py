"""Rinder's comparison (sec. 3.2, Figs. 10-13) of the 5/6 narrow-tip and rack-involute profiles at
a = 116 mm, recomputed by rotorcad: where the largest sliding velocity and the largest slip occur
(rotor, flank, male angle). Run from the project folder:

    python samples/rinder_comparison/compare.py

It prints the table of README.md's section "Rinder's comparison" and writes the pictures next to
this file (``rotorcad rotor --plot``). Angles are the male rotation from the instant the male
tip's middle passes the line of centres O1O2, positive in the male's sense of rotation.
"""

from __future__ import annotations

import subprocess
import sys
import tomllib
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
SAMPLES = HERE.parent
PROFILES = {"narrow-tip (Fig. 5)": "narrow_tip_5_6", "rack-involute (Fig. 6)": "rack_involute_5_6"}


def _place(pair, p: np.ndarray) -> str:
    """Where a contact point lies on the two rotors: at a tip, at a root, or on the flank."""
    r1 = float(np.hypot(*p))
    r2 = float(np.hypot(p[0] - pair.center_distance, p[1]))
    tol = 0.02 * (pair.male_tip_radius - pair.male_root_radius)
    male = (
        "male tip"
        if r1 > pair.male_tip_radius - tol
        else "male root"
        if r1 < pair.male_root_radius + tol
        else f"male r = {r1:.1f} mm"
    )
    female = (
        "female tip"
        if r2 > pair.female_tip_radius - tol
        else "female root"
        if r2 < pair.female_root_radius + tol
        else f"female r = {r2:.1f} mm"
    )
    return f"{male} / {female}"


def extremes(name: str) -> dict[str, dict[str, object]]:
    """The largest sliding velocity and slips of a sample with their place, flank and angle."""
    from rotorcad.design import rotor_design
    from rotorcad.meshing import MeshingAnalysis
    from rotorcad.rotor_build import build_pair, pair_spec

    path = SAMPLES / f"{name}.toml"
    with path.open("rb") as f:
        ma = MeshingAnalysis(build_pair(pair_spec(rotor_design(tomllib.load(f), path.parent))))
    pair = ma.rotors.pair
    # the reference instant: the middle of the rack's top (the male tip) on O1O2, t = -x / r1w
    tops = []
    for piece in ma.rotors.rack:
        pts, _ = piece.curve.evaluate(np.linspace(piece.curve.s0, piece.curve.s1, 400))
        tops.append(pts[np.isclose(pts[:, 0], pair.male_tip_radius, atol=1e-9)])
    top = np.concatenate(tops)
    t_ref = -float(np.mean(top[:, 1])) / pair.male_pitch_radius
    k = ma.kinematics
    roles = np.concatenate([p.roles for p in ma.pieces])
    angle = k["angle_deg"] - np.degrees(t_ref)
    out = {}
    for key, label in (
        ("sliding", "largest sliding velocity"),
        ("slip_male", "largest male slip"),
        ("slip_female", "largest female slip"),
    ):
        v = np.abs(k[key])
        v = np.where(np.isfinite(v), v, -1.0)
        i = int(np.argmax(v))
        out[label] = {
            "value": float(v[i]),
            "flank": str(roles[i]),
            "angle_deg": float(angle[i]),
            "place": _place(pair, ma.meshline[i]),
        }
    # points of infinite slip: a tangential velocity passing zero inside a piece (Rinder: the rack
    # profile has one, where its involute is used down to the base circle)
    zeros = 0
    for piece, start in zip(ma.pieces, np.cumsum([0] + [len(p.t) for p in ma.pieces[:-1]]), strict=True):
        for key in ("v1t", "v2t"):
            v = k[key][start : start + len(piece.t)]
            zeros += int(np.sum(np.sign(v[:-1]) * np.sign(v[1:]) < 0))
    out["points of infinite slip"] = {"value": zeros}
    seal = (roles == "sealing") & (np.abs(k["slip_female"]) > 3.0)
    out["female sealing flank, slip above 3"] = {
        "value": [float(angle[seal].min()), float(angle[seal].max())] if seal.any() else None
    }
    return out


def table() -> str:
    rows = ["| quantity | " + " | ".join(PROFILES) + " |", "|---|" + "---|" * len(PROFILES)]
    data = {label: extremes(name) for label, name in PROFILES.items()}
    for quantity in next(iter(data.values())):
        cells = []
        for label in PROFILES:
            d = data[label][quantity]
            if "flank" in d:
                unit = " m/s" if "sliding" in quantity else ""
                cells.append(f"{d['value']:.2f}{unit}, {d['flank']} flank, {d['place']}, {d['angle_deg']:+.1f}°")
            elif isinstance(d["value"], list):
                cells.append(f"{d['value'][0]:+.1f}° to {d['value'][1]:+.1f}°")
            else:
                cells.append("none" if d["value"] is None else str(d["value"]))
        rows.append(f"| {quantity} | " + " | ".join(cells) + " |")
    return "\n".join(rows)


def pictures() -> None:
    for name in PROFILES.values():
        subprocess.run(
            [
                str(Path(sys.executable).with_name("rotorcad")),
                "rotor",
                str(SAMPLES / f"{name}.toml"),
                "--plot",
                str(HERE / f"{name}.png"),
            ],
            check=True,
            stdout=subprocess.DEVNULL,
        )


if __name__ == "__main__":
    print(table())
    if "--no-pictures" not in sys.argv:
        pictures()

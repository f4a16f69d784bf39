"""Rinder's comparison (sec. 3.2, Figs. 10-13) of the 5/6 narrow-tip and rack-involute profiles at
a = 116 mm, recomputed by rotorcad: where the largest sliding velocity and the largest slip occur
(rotor, flank, male angle). Run from the project folder:

    python samples/rinder_comparison/compare.py

It prints the table of README.md's section "Rinder's comparison" and writes the pictures next to
this file (``rotorcad rotor --plot``). Angles are rotorcad's one convention (CONTRACT.md, as
``rotorcad rotor --json`` gives them): the male rotation still to go until the middle of a male tip
reaches the line of centres O1O2, negative after it, as in Rinder's Figs. 10-13.
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
    k = ma.kinematics
    roles = np.concatenate([p.roles for p in ma.pieces])
    angle = k["angle_deg"]  # rotorcad's one angle convention (MeshingAnalysis.rinder_angle)
    out = {}
    for key, label in (
        ("sliding", "largest sliding velocity"),
        ("slip_male", "largest male slip"),
        ("slip_female", "largest female slip"),
    ):
        v = np.abs(k[key])
        v = np.where(np.isnan(v), -1.0, v)  # an infinite slip (a zero of v_t) is the largest
        i = int(np.argmax(v))
        out[label] = {
            "value": float(v[i]),
            "flank": str(roles[i]),
            "angle_deg": float(angle[i]),
            "place": _place(pair, ma.meshline[i]),
        }
    # points of infinite slip (Rinder: the rack profile has one, where its involute is used down to
    # the base circle)
    out["points of infinite slip"] = {"value": len(ma.slip_singularities)}
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
                value = "infinite" if np.isinf(d["value"]) else f"{d['value']:.2f}{unit}"  # v_t = 0 (meshing.analysis.slip)
                cells.append(f"{value}, {d['flank']} flank, {d['place']}, {d['angle_deg']:+.1f}°")
            elif isinstance(d["value"], list):
                cells.append(f"{d['value'][0]:+.1f}° to {d['value'][1]:+.1f}°")
            else:
                cells.append("none" if d["value"] is None else str(d["value"]))
        rows.append(f"| {quantity} | " + " | ".join(cells) + " |")
    return "\n".join(rows)


VERDICT_SAMPLES = (
    "krigar_4_6",
    "lysholm_4_6",
    "srm_symmetric_4_6",
    "srm_asymmetric_5_6",
    "srm_b_5_6",
    "narrow_tip_5_6",
    "rack_involute_5_6",
)


def sample_summary(name: str) -> dict:
    """The numbers of ``rotorcad rotor samples/NAME.toml --json``."""
    from rotorcad.rotor_build import design_summary

    with (SAMPLES / f"{name}.toml").open("rb") as f:
        return design_summary(tomllib.load(f), SAMPLES)


def verdict_table(summaries: dict[str, dict]) -> str:
    """The README's table "Rinder says | rotorcad now" from the samples' ``rotor --json`` numbers."""
    s = summaries

    def yes(v: bool) -> str:
        return "yes" if v else "no"

    def ratios(name: str, flank: str) -> str:
        f = s[name]["flanks"][flank]
        return f"ε_α {f['transverse_contact_ratio']:.2f} + ε_β {f['overlap_contact_ratio']:.2f} = {f['total_contact_ratio']:.2f}"

    def share(name: str) -> str:
        x = s[name]
        return f"{100 * x['blow_hole_area'] / (x['male_flute_area'] + x['female_flute_area']):.2f} %"

    def flutes(name: str) -> str:
        return f"flute areas {s[name]['male_flute_area']:.0f} / {s[name]['female_flute_area']:.0f} mm²"

    k, ly, sym, asym, b, nt, ri = (s[n] for n in VERDICT_SAMPLES)
    sing = ri["slip_singularities"]
    nts, ris = nt["max_sliding_at"], ri["max_sliding_at"]
    rows = [
        (
            "Krigar (Fig. 1): no flank part in geometric contact; closed meshline up to the tip circles' "
            "crossing; tight, no blow-hole; does not run",
            f"`krigar_4_6`: working length {k['flanks']['driving']['working_length']:.0f} mm on both flanks; meshline "
            f"closed: {yes(k['meshline_closed'])}; blow-hole {k['blow_hole_area']:.2f} mm²; runs without timing gears: "
            f"{yes(k['runs_without_timing_gears'])}; {flutes('krigar_4_6')}",
        ),
        (
            "Lysholm (Fig. 2): the driving flank runs perfectly, its infinitesimal transverse contact ratio made up "
            "by the helix; its circle about C is the exception to the jamming rule",
            f"`lysholm_4_6` driving flank: {ratios('lysholm_4_6', 'driving')}, runs: "
            f"{yes(ly['flanks']['driving']['runs_without_timing_gears'])}; jamming points: "
            f"{sum(d['kind'] == 'jamming' for d in ly['defects'])}; the cusp where it meets the female tip corner "
            "counts as that corner",
        ),
        (
            "Lysholm: the sealing flank has no blow-hole, but the profile needs timing gears",
            f"blow-hole {ly['blow_hole_area']:.2f} mm²; sealing flank working length "
            f"{ly['flanks']['sealing']['working_length']:.0f} mm (point-generated only), runs: "
            f"{yes(ly['flanks']['sealing']['runs_without_timing_gears'])}; the pair without timing gears: "
            f"{yes(ly['runs_without_timing_gears'])}",
        ),
        (
            "symmetric SRM (Fig. 3): runs in both directions given enough wrap; relatively large blow-hole",
            f"`srm_symmetric_4_6`: both flanks {ratios('srm_symmetric_4_6', 'driving')}, run: "
            f"{yes(sym['runs_without_timing_gears'])} (with an overlap of 0.8 neither runs); blow-hole "
            f"{sym['blow_hole_area']:.1f} mm² ({share('srm_symmetric_4_6')} of the flute areas)",
        ),
        (
            "asymmetric SRM (Fig. 4): Lysholm's driving flank; a short straight part gives the sealing flank proper "
            "running over a small region; small blow-hole",
            f"`srm_asymmetric_5_6`: sealing working part {asym['flanks']['sealing']['working_length']:.1f} of "
            f"{asym['flanks']['sealing']['meshline_length']:.1f} mm, runs: "
            f"{yes(asym['flanks']['sealing']['runs_without_timing_gears'])}; driving {ratios('srm_asymmetric_5_6', 'driving')}; "
            f"blow-hole {asym['blow_hole_area']:.2f} mm² ({share('srm_asymmetric_5_6')}); {flutes('srm_asymmetric_5_6')}",
        ),
        (
            "SRM-B: runs well without timing gears, shorter meshline, larger transverse overlap, hobs badly",
            f"`srm_b_5_6`: driving {ratios('srm_b_5_6', 'driving')} (asymmetric SRM: "
            f"{asym['flanks']['driving']['transverse_contact_ratio']:.2f} transverse), driving meshline "
            f"{b['flanks']['driving']['meshline_length']:.1f} mm (asymmetric SRM "
            f"{asym['flanks']['driving']['meshline_length']:.1f} mm); runs without timing gears: "
            f"{yes(b['runs_without_timing_gears'])}; `rotorcad hob`: not hobbable, the male rack stands perpendicular "
            "to the pitch line at the driving arc's foot",
        ),
        (
            "narrow-tip (Fig. 5): good running on both flank parts, long point-generated sealing parts, small blow-hole",
            f"`narrow_tip_5_6`: driving {ratios('narrow_tip_5_6', 'driving')}, sealing "
            f"{ratios('narrow_tip_5_6', 'sealing')}, both run: {yes(nt['runs_without_timing_gears'])}; sealing meshline "
            f"{nt['flanks']['sealing']['meshline_length']:.1f} mm, of it point-generated "
            f"{nt['flanks']['sealing']['meshline_length'] - nt['flanks']['sealing']['working_length']:.1f} mm; blow-hole "
            f"{nt['blow_hole_area']:.2f} mm² ({share('narrow_tip_5_6')}); {flutes('narrow_tip_5_6')}",
        ),
        (
            "rack-involute (Fig. 6, sec. 3.2): the laws of gearing hold at every point; the unavoidable blow-hole as "
            "small as possible; good hobbing with simple tools; infinite slip at one single point (the involute used "
            "down to the base circle)",
            f"`rack_involute_5_6`: cusps or jamming inside a working flank: "
            f"{len(ri['flanks']['driving']['defects']) + len(ri['flanks']['sealing']['defects'])}; both flanks run: "
            f"{yes(ri['runs_without_timing_gears'])}; blow-hole {ri['blow_hole_area']:.1f} mm² ({share('rack_involute_5_6')}); "
            f"points of infinite slip: {len(sing)}"
            + (
                f" ({sing[0]['rotor']} slip, {sing[0]['flank']} flank, female r = {sing[0]['female_radius']:.3f} mm, "
                f"{sing[0]['angle_deg']:+.1f}°)"
                if sing
                else ""
            )
            + f"; straight rack flanks (`rotorcad hob`: no flank-angle objection); {flutes('rack_involute_5_6')}",
        ),
        (
            "sec. 3.2: sliding velocities of the 5:6 narrow-tip and rack-involute pairs at a = 116 mm about equal, the "
            "largest at the male tip on the sealing flank, at about −25°",
            f"narrow-tip {nt['max_sliding_velocity']:.2f} m/s ({nts['flank']} flank, male r = {nts['male_radius']:.1f} mm, "
            f"{nts['angle_deg']:+.1f}°), rack-involute {ri['max_sliding_velocity']:.2f} m/s ({ris['flank']} flank, male r = "
            f"{ris['male_radius']:.1f} mm, {ris['angle_deg']:+.1f}°): ratio "
            f"{ri['max_sliding_velocity'] / nt['max_sliding_velocity']:.2f} (3000 rpm)",
        ),
    ]
    lines = ["| Rinder says | rotorcad now |", "|---|---|"]
    lines += [f"| {a} | {c} |" for a, c in rows]
    return "\n".join(lines)


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
    print(verdict_table({name: sample_summary(name) for name in VERDICT_SAMPLES}))
    print()
    print(table())
    if "--no-pictures" not in sys.argv:
        pictures()

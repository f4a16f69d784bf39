"""``rotorcad grind`` on involute gears (the gear sample, its mate, a helical pair) and the wheel's whole section.

References:

* the involute (ISO 21771: the polar angle of a flank point is a constant +- inv(arccos(r_b / r))),
  which a spur gear's form wheel reproduces as its profile: its axis lies in the transverse plane,
  so its axial section laid into that plane is the tooth space;
* the mirror symmetry of a helical gear's wheel: the mate of an external helical pair is the same
  gear of the other hand, and mirroring the whole setting in the transverse plane z = 0 maps the
  right-hand gear and its wheel onto the left-hand one with the crossing angle negated and the
  wheel's profile unchanged; the mate's wheel from the command must be the wheel rotorcad.grinding
  makes for an InvoluteGear of the mate's figures built here, right-handed;
* the wheel's section: a direct scan of the rotor's outline screwed along its helix (numpy, not the
  stock search of rotorcad.grinding): no rotor point comes nearer the wheel axis than the shoulder
  radius where its axial coordinate lies beside the profile, within the wheel's width; the DXF
  read back by ezdxf (a third-party reader).
"""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest
import shapely

from rotorcad.cli.main import main
from rotorcad.gears import InvoluteGear
from rotorcad.gears.formulas import inv
from rotorcad.grinding import grind

SAMPLES = Path(__file__).resolve().parents[1] / "samples"


def _grind(capsys, args):
    assert main(["grind", *args, "--json"]) == 0
    return json.loads(capsys.readouterr().out)


def _rows(folder: Path, stem: str) -> np.ndarray:
    return np.loadtxt(folder / f"{stem}.csv", delimiter=",", comments="#", skiprows=3)


@pytest.mark.parametrize(("rotor", "teeth", "shift"), [("gear", 17, 0.3), ("mate", 29, -0.1)])
def test_gear_sample_wheel_is_the_involute_space(tmp_path, capsys, rotor, teeth, shift):
    """samples/gear_pair.toml, each gear of the pair: the wheel's profile is the involute (ISO 21771)."""
    out = _grind(capsys, [str(SAMPLES / "gear_pair.toml"), "--rotor", rotor, "--wheel-radius", "80", "--out", str(tmp_path)])
    assert out["body"] == rotor and out["lobe_count"] == teeth and out["lead"] is None
    new = out["wheels"]["new"]
    assert new["secondary_cutting_point_count"] == 0 and new["crossing_angle_deg"] == 0.0
    rows = _rows(tmp_path, f"wheel_{rotor}_new")
    x, y = new["center_distance"] - rows[:, 1], rows[:, 0]  # the axial section laid in the transverse plane
    r = np.hypot(x, y)
    m = 3.0
    rb = 0.5 * teeth * m * np.cos(np.radians(20.0))
    tip = 0.5 * teeth * m + (1.0 + shift) * m
    # form circle (ISO 21771): where the tool's tip radius meets its flank, (1.25 - 0.38 (1 - sin 20 deg)) m below the datum
    alpha = np.radians(20.0)
    below = (1.25 - 0.38 * (1 - np.sin(alpha))) * m - shift * m
    form = np.hypot(rb, 0.5 * teeth * m * np.sin(alpha) - below / np.sin(alpha)) + 0.05
    on = (r > form) & (r < tip - 0.05)
    for sign in (1.0, -1.0):  # each flank: polar angle - sign inv(alpha(r)) is constant
        sel = on & (sign * y > 0)
        assert sel.sum() > 20
        c = np.arctan2(y[sel], x[sel]) - sign * inv(np.arccos(rb / r[sel]))
        assert np.ptp(c) * r[sel].max() < 1e-6, np.ptp(c) * r[sel].max()


def test_helical_mate_wheel_is_the_mirror_of_the_right_hand_gear(tmp_path, capsys):
    args = ["--teeth", "17", "--module", "3", "--helix-angle", "15", "--mate-teeth", "29", "--rotor", "mate"]
    out = _grind(capsys, [*args, "--wheel-radius", "70", "--out", str(tmp_path)])
    assert out["body"] == "mate" and out["lobe_count"] == 29 and out["lead"] < 0  # the other hand
    assert out["crossing_angle_deg"] == pytest.approx(-15.0, abs=1e-9)
    rows = _rows(tmp_path, "wheel_mate_new")
    twin = InvoluteGear(teeth=29, module=3.0, helix_angle=np.radians(15.0), tolerance=1e-4)
    job = grind(twin.outline(), np.tan(twin.helix_angle) / twin.pitch_radius, 29, 70.0, twin.pitch_radius)
    ok = job.wheel.valid
    t, rho = job.wheel.axial[ok], job.wheel.radius[ok]
    order = np.argsort(t)
    assert np.isclose(job.wheel.setting.crossing_angle, np.radians(15.0))
    mirrored = np.interp(rows[:, 0], t[order], rho[order])  # the same profile, t unchanged by the mirror
    inside = (rows[:, 0] > t.min() + 0.05) & (rows[:, 0] < t.max() - 0.05)
    assert inside.sum() > 100 and np.abs(mirrored[inside] - rows[inside, 1]).max() < 1e-4


@pytest.mark.parametrize(
    ("design", "extra", "sentence"),
    [
        ("gear_pair.toml", ["--rotor", "male"], "--rotor must be gear or mate"),
        ("n_rack_5_6.toml", ["--rotor", "gear"], "--rotor must be male or female"),
        (None, ["--teeth", "17", "--module", "3", "--rotor", "mate"], "--rotor mate needs a mating gear"),
        ("gear_pair.toml", ["--wheel-width", "5"], "--wheel-width must be at least"),
        ("gear_pair.toml", ["--wheel-bore-radius", "500"], "--wheel-bore-radius must be above 0 and below"),
    ],
)
def test_grind_refuses_a_body_or_section_that_makes_no_sense(tmp_path, capsys, design, extra, sentence):
    args = ([str(SAMPLES / design)] if design else []) + extra
    assert main(["grind", *args, "--wheel-radius", "80", "--out", str(tmp_path / "never")]) == 2
    err = capsys.readouterr().err.strip()
    assert err.startswith(f"rotorcad: error: {sentence}") and err.count("\n") == 0, err
    assert not (tmp_path / "never").exists()


def test_wheel_section_closes_the_profile_clear_of_the_rotor(tmp_path, capsys):
    """The whole section of the N-rack male's wheel: closed, holding the profile, shoulders that never
    come near the rotor (module docstring), and the DXF's WHEEL_SECTION the section CSV."""
    import ezdxf

    out = _grind(
        capsys, [str(SAMPLES / "n_rack_5_6.toml"), "--wheel-radius", "100", "--wheel-width", "45", "--out", str(tmp_path)]
    )
    new = out["wheels"]["new"]
    assert new["wheel_width"] == 45.0 and new["bore_radius"] == 63.5
    ring = _rows(tmp_path, "wheel_male_new_section")
    profile = _rows(tmp_path, "wheel_male_new")[:, :2]
    poly = shapely.Polygon(ring)
    assert poly.is_valid and shapely.Polygon(ring).exterior.is_ccw
    assert shapely.distance(shapely.points(profile), poly.exterior).max() < 1e-9
    assert ring[:, 0].min() == -22.5 and ring[:, 0].max() == 22.5 and ring[:, 1].min() == 63.5
    # the rotor's outline screwed along its helix: beside the profile it stays outside the shoulder radius
    a, s = new["center_distance"], np.radians(new["crossing_angle_deg"])
    k = 2 * np.pi / out["lead"]
    import tomllib

    from rotorcad.design.rotors import build_pair, pair_spec
    from rotorcad.design.schema import rotor_design
    from rotorcad.geometry import rotate

    rotors = build_pair(pair_spec(rotor_design(tomllib.loads((SAMPLES / "n_rack_5_6.toml").read_text()))))
    p = rotate(rotors.male_outline().resampled(1e-3).points, np.radians(new["flute_turn_deg"]))
    z = np.linspace(-60.0, 60.0, 2401)[:, None]
    x = p[:, 0] * np.cos(k * z) - p[:, 1] * np.sin(k * z)
    y = p[:, 0] * np.sin(k * z) + p[:, 1] * np.cos(k * z)
    t = y * np.cos(s) - z * np.sin(s)
    dist = np.hypot(x - a, y * np.sin(s) + z * np.cos(s))
    beside = (np.abs(t) <= 22.5) & ((t < profile[:, 0].min()) | (t > profile[:, 0].max()))
    assert beside.sum() > 1000 and dist[beside].min() >= new["shoulder_radius"] - 1e-9
    assert new["shoulder_radius"] == pytest.approx(a - out["tip_radius"])
    doc = ezdxf.readfile(tmp_path / "wheel_male_new_r2000.dxf")
    (wheel,) = [e for e in doc.modelspace() if e.dxf.layer == "WHEEL"]
    (sides,) = [e for e in doc.modelspace() if e.dxf.layer == "WHEEL_SECTION"]
    # the sides from the profile's first end round to its last, then the profile back: the section
    drawn = np.vstack([np.array(sides.get_points("xy")), np.array(wheel.get_points("xy"))[::-1][1:-1]])
    start = int(np.argmin(np.hypot(*(ring - drawn[0]).T)))
    assert len(drawn) == len(ring) and np.abs(np.roll(ring, -start, axis=0) - drawn).max() < 1e-9

"""Every picture of every command reads at a glance (issue 16): read back from the SVG files the
commands write (an XML parser, no image comparison), every axis that has tick labels carries a
label with its unit in brackets and proper symbols (µm, not um; °, not deg), and the title names
the case; deviations are stated with their magnification. The DXF layouts: the hob's racks and
teeth side by side with labels, the cut gear a closed outline that does not run through its centre.
The pictures of deflect and coupling are checked by :func:`check_picture` in their own test files.
"""

from __future__ import annotations

import json
import re
import xml.etree.ElementTree as ET
from pathlib import Path

import ezdxf
import numpy as np
import pytest
import shapely

from exports.csv_points import write_points
from rotorcad.cli.main import main
from rotorcad.rotor_families import build_family
from rotorcad.rotor_pair import RotorPair

ROOT = Path(__file__).resolve().parents[1]
SVG = "{http://www.w3.org/2000/svg}"
UNITS = {"mm", "µm", "°", "m/s", "mm²", "mm³", "L/min", "Hz", "MPa", "N", "–", "%", "rpm", "bar", "s", "1/Pa"}
LABEL = re.compile(r"\[([^\[\]]+)\]\s*$")
AXIS = re.compile(r"^axes-(\d+)-([xyz])axis$")


def text_of(element: ET.Element) -> str:
    return "".join(element.itertext()).strip()


def read_svg(path: Path) -> dict:
    """The title, every drawn axis (with whether it has tick labels, and its label) and all text."""
    root = ET.parse(path).getroot()
    assert root.tag == f"{SVG}svg"
    groups = {g.get("id"): g for g in root.iter(f"{SVG}g") if g.get("id")}
    axes = []
    for gid, group in groups.items():
        m = AXIS.match(gid)
        if not m:
            continue
        label_group = next((g for g in group.iter(f"{SVG}g") if g.get("id") == f"axes-{m[1]}-{m[2]}label"), None)
        ticks = [
            text_of(t)
            for g in group.iter(f"{SVG}g")
            if (g.get("id") or "").startswith(("xtick", "ytick"))
            for t in g.iter(f"{SVG}text")
        ]
        axes.append({"id": gid, "ticks": any(ticks), "label": text_of(label_group) if label_group is not None else ""})
    title = text_of(groups["title"]) if "title" in groups else ""
    texts = [text_of(t) for t in root.iter(f"{SVG}text")]
    return {"title": title, "axes": axes, "text": "\n".join(texts)}


def check_picture(path: Path, case: list[str]) -> dict:
    """Units on every labelled axis, proper symbols, the title naming the case."""
    svg = read_svg(path)
    assert svg["axes"], f"{path.name}: no axes found"
    for axis in svg["axes"]:
        if not axis["ticks"]:
            continue
        m = LABEL.search(axis["label"])
        assert m, f"{path.name}: axis {axis['id']} has no unit in its label {axis['label']!r}"
        assert m[1] in UNITS, f"{path.name}: axis {axis['id']}: unit {m[1]!r} is not a proper symbol"
    assert not re.search(r"\bum\b|\[deg\]|\[-\]", svg["text"]), f"{path.name}: 'um', '[deg]' or '[-]' instead of a symbol"
    for word in case:
        assert word in svg["title"], f"{path.name}: the title {svg['title']!r} does not name {word!r}"
    return svg


def run(capsys, *args) -> tuple[int, str, str]:
    capsys.readouterr()
    code = main([str(a) for a in args])
    out, err = capsys.readouterr()
    return code, out, err


def test_gear_picture(tmp_path, capsys):
    code, _, _ = run(
        capsys, "gear", "--teeth", 17, "--module", 3, "--mate-teeth", 29, "--shift", 0.3, "--plot", tmp_path / "g.svg"
    )
    assert code == 0
    svg = check_picture(tmp_path / "g.svg", ["z1 = 17", "z2 = 29", "m = 3 mm", "ε_α"])
    assert "path of contact" in svg["text"] and "pitch circles" in svg["text"]


def test_rotor_pictures_label_every_branch_and_state_the_case(tmp_path, capsys):
    code, _, _ = run(capsys, "rotor", ROOT / "samples" / "lysholm_4_6.toml", "--plot", tmp_path / "r.svg")
    assert code == 0
    pair = check_picture(tmp_path / "r.svg", ["lysholm 4/6", "a = 100 mm"])
    assert "meshline" in pair["text"] and "housing bores" in pair["text"]
    sliding = check_picture(tmp_path / "r_sliding.svg", ["lysholm 4/6", "3000 rpm"])
    # every branch is labelled by the flanks in contact, and the slip is not clipped into walls at ±10
    assert "male driving flank ↔ female driving flank" in " ".join(sliding["text"].split())
    assert "male slip ζ1" in sliding["text"] and "female slip ζ2" in sliding["text"]
    assert "clipped" not in sliding["text"] and "symmetric log scale" in sliding["text"]
    # Rinder's verdicts at the flank where they are (sec. 1.2: Lysholm's driving flank runs, his
    # sealing flank needs timing gears; sec. 2.2.2: the cusps at the tips are the tip corners)
    for picture in (pair, sliding):
        text = " ".join(picture["text"].split())
        assert "driving flank: runs without timing gears" in text
        assert "sealing flank: does not run without timing gears" in text
        assert "female tip corner, sealing flank" in text and "male tip corner, sealing flank" in text
        assert "slipping (male tip on the female root)" in text


def test_rotor_pictures_mark_the_point_of_infinite_slip(tmp_path, capsys):
    # Rinder sec. 3.2: the rack profile has infinite slip "nur in einem einzigen Punkt": both
    # pictures mark it, with its rotor and flank
    code, _, _ = run(capsys, "rotor", ROOT / "samples" / "rack_involute_5_6.toml", "--plot", tmp_path / "r.svg")
    assert code == 0
    texts = {
        name: " ".join(check_picture(tmp_path / name, ["rack-involute 5/6"])["text"].split())
        for name in ("r.svg", "r_sliding.svg")
    }
    assert all("infinite female slip, sealing flank" in text for text in texts.values())
    assert "infinite slip (1)" in texts["r.svg"] and "point of infinite slip" in texts["r_sliding.svg"]


def test_cut_picture_states_the_magnified_deviation(tmp_path, capsys):
    code, _, _ = run(
        capsys, "cut", "--teeth", 11, "--module", 2, "--json", "--plot", tmp_path / "c.svg", "--dxf", tmp_path / "c.dxf"
    )
    assert code == 0
    svg = check_picture(tmp_path / "c.svg", ["z = 11", "m = 2 mm"])
    scale = re.search(r"deviation ×(\d+) along the normal", svg["text"])
    assert scale and int(scale[1]) >= 100  # a deviation of a micrometre is drawn visible
    # the simulated gear in the DXF: one closed outline with the gear's area, nowhere near its centre
    doc = ezdxf.readfile(tmp_path / "c.dxf")
    sim = next(e for e in doc.modelspace().query("LWPOLYLINE") if e.dxf.layer == "GEAR_SIMULATED")
    pts = np.array(sim.get_points("xy"))
    assert sim.closed and np.hypot(*pts.T).min() > 0.99 * 8.5  # root radius (z - 2.5) m / 2 = 8.5 mm
    analytic = next(e for e in doc.modelspace().query("LWPOLYLINE") if e.dxf.layer == "GEAR_ANALYTIC")
    area = shapely.Polygon(np.array(analytic.get_points("xy"))).area
    assert shapely.Polygon(pts).area == pytest.approx(area, rel=1e-3)


def test_pump_and_nomogram_pictures(tmp_path, capsys):
    args = ["pump", "--teeth", 11, "--module", 4, "--shift", 0.3, "--face-width", 20, "--speed", 1500]
    code, _, _ = run(capsys, *args, "--plot", tmp_path / "p.svg", "--nomogram", tmp_path / "n.svg")
    assert code == 0
    pump = check_picture(tmp_path / "p.svg", ["z = 11", "1500 rpm"])
    assert "mean flow" in pump["text"]  # the mean-flow line has its legend entry
    nomogram = check_picture(tmp_path / "n.svg", ["z = 11", "α0 = 20°"])
    for words in ("x_g = ", "x′_g = ", "x″_g = ", "ε = 1", "undercut", "pointed"):
        assert words in nomogram["text"], words


def test_hob_picture_and_dxf_side_by_side(tmp_path, capsys):
    design = ROOT / "samples" / "rack_involute_5_6.toml"
    code, _, _ = run(capsys, "hob", design, "--plot", tmp_path / "h.svg", "--dxf", tmp_path / "h.dxf")
    assert code == 0
    svg = check_picture(tmp_path / "h.svg", ["rack-involute 5/6", "hobbable"])
    assert re.search(r"deviation ×\d+ along the normal", svg["text"]) and "µm of deviation" in svg["text"]
    doc = ezdxf.readfile(tmp_path / "h.dxf")
    assert len(doc.audit().errors) == 0
    msp = doc.modelspace()
    boxes = {}
    for name in ("MALE", "FEMALE"):
        tooth = next(e for e in msp.query("LWPOLYLINE") if e.dxf.layer == f"HOB_TOOTH_{name}")
        boxes[name] = shapely.Polygon(np.array(tooth.get_points("xy")))
    assert not boxes["MALE"].intersects(boxes["FEMALE"])  # side by side, not on top of each other
    labels = [e.dxf.text for e in msp.query("TEXT") if e.dxf.layer == "LABELS"]
    assert any("from the male" in t for t in labels) and any("from the female" in t for t in labels)


def test_clearance_picture_names_the_state_and_warns_of_interference(tmp_path, capsys):
    pair = RotorPair(5, 6, 116.0, 63.0, 45.0, 71.0, 53.0)
    rotors = build_family(pair, "rack-involute", {})
    write_points(tmp_path / "m.csv", rotors.male_outline(1e-3).points)
    write_points(tmp_path / "f.csv", rotors.female_outline(1e-3).points)
    base = ["clearance", "--male-points", tmp_path / "m.csv", "--female-points", tmp_path / "f.csv"]
    base += ["--male-teeth", 5, "--female-teeth", 6, "--center-distance", 116]
    # hot rotors in a cooler housing: the pair runs into interference (clearance below zero)
    hot = ["--suction-temperature", 20, "--discharge-temperature", 200, "--housing-temperature", 40]
    code, out, err = run(capsys, *base, *hot, "--json", "--plot", tmp_path / "hot.svg")
    assert code == 0
    data = json.loads(out)
    assert data["min_normal_clearance"] < 0 and data["interference"] is True
    assert "warning" in err and "interfere" in err and "µm" in err
    svg = check_picture(
        tmp_path / "hot.svg", ["5/6", "hot", "suction 20 °C", "discharge 200 °C", "housing 40 °C", "driving flank"]
    )
    assert "INTERFERENCE" in svg["text"] and "clearance band on the contact line" in svg["text"]
    assert any(a["id"].endswith("zaxis") and "[mm]" in a["label"] for a in svg["axes"])  # the 3D band is drawn
    # cold, as measured: no interference, no warning
    code, out, err = run(capsys, *base, "--contact", "sealing", "--json", "--plot", tmp_path / "cold.svg")
    assert code == 0 and json.loads(out)["interference"] is False and "warning" not in err
    check_picture(tmp_path / "cold.svg", ["cold", "sealing flank"])


def test_sweep_pictures_label_columns_with_units(tmp_path):
    # the sweep command's own writer (Outputs.add_figure) on a table of sweep columns
    from rotorcad.cli.common import Outputs
    from rotorcad.sweep_plots import column_label, plot_effects, plot_pareto

    assert column_label("blow_hole_area_mm2") == "blow-hole area [mm²]"
    assert column_label("pair.lead") == "male lead [mm]" and column_label("profile.driving_angle_deg") == "driving angle [°]"
    rng = np.random.default_rng(1)
    x, y, c = rng.random(20), rng.random(20), rng.random(20)
    lead = np.repeat([260.0, 320.0], 10)
    out = Outputs()
    names = ("blow_hole_area_mm2", "contact_line_length_mm", "max_sliding_velocity_m_s")
    out.add_figure(tmp_path / "p.svg", lambda: plot_pareto(x, y, c, names, case="s.toml"), "--pareto")
    out.add_figure(tmp_path / "e.svg", lambda: plot_effects({"pair.lead": lead}, x, names[0], case="s.toml"), "--effects")
    out.write()
    check_picture(tmp_path / "p.svg", ["s.toml", "20 variants"])
    check_picture(tmp_path / "e.svg", ["s.toml"])


def test_measured_points_against_their_profile(tmp_path, capsys):
    # Measured female points: the exact outline of the symmetric SRM pair (engine-independent of the
    # noise) with a known Gaussian scatter of 4 um along x and y. The deviation picture states the
    # spread of the points about the profile built from them: for sigma = 4 um per coordinate the
    # normal deviation has sigma 4 um, less what the smoothing spline absorbs (n sigma^2 smoothing:
    # a few per cent), so between 3 and 4.5 um.
    from rotorcad.rotor_plotting import point_deviation

    pair = RotorPair(4, 6, 100.0, 54.0, 40.0, 60.0, 46.0)
    exact = build_family(pair, "srm-symmetric", {}).section("female", tolerance=1e-4)
    ring = np.asarray(exact.exterior.coords)[:-1]
    ring = ring[:: max(1, len(ring) // 1500)]
    rng = np.random.default_rng(7)
    noisy = ring + rng.normal(0.0, 0.004, ring.shape)
    csv = tmp_path / "female.csv"
    write_points(csv, noisy, ["female, measured"])
    dims = ["--male-teeth", 4, "--female-teeth", 6, "--center-distance", 100, "--male-tip-radius", 54, "--male-root-radius", 40]
    dims += ["--female-tip-radius", 60, "--female-root-radius", 46]
    code, _, err = run(capsys, "rotor", "--female-points", csv, *dims, "--plot", tmp_path / "m.svg")
    assert code == 0, err
    svg = check_picture(tmp_path / "m_deviation.svg", ["measured female points", "female.csv"])
    assert "measured − profile" in svg["text"] and "×" in svg["text"]
    sigma = float(re.search(r"σ = ([0-9.]+) µm", svg["text"]).group(1))
    assert 3.0 < sigma < 4.5
    # the deviation itself against the exact outline the noise was added to: its spread is the noise
    foot, normal, dev = point_deviation(exact, noisy)
    assert np.std(dev) == pytest.approx(0.004, rel=0.1)
    # each point lies off its foot along the outward normal by the signed deviation, within 0.05 um
    # (the outline is a polygon of 0.1 um chords: at a vertex the normal is a fan), but at the
    # female's sharp tip corners
    miss = np.hypot(*(foot + dev[:, None] * normal - noisy).T)
    assert np.percentile(miss, 98) < 5e-5 and miss.max() < np.abs(dev).max()

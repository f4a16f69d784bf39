"""The hob's basic worm (hob.worm, ``rotorcad hob --hob-diameter --step``), checked against closed forms.

References:

* DIN 3968 / ISO 1122-1 hob and worm terms, as closed forms the code does not use: the reference
  diameter ``d_m0 = d_a0 - 2 h_a0 m`` (``h_a0`` the tool addendum, the gear's dedendum factor
  1.25), ``sin(gamma) = z0 m / d_m0``, axial pitch ``p_x = pi m / cos(gamma)``, lead ``z0 p_x`` and
  ``tan(gamma) = lead / (pi d_m0)``;
* the ISO 53 basic rack in closed form (straight flank at the pressure angle, half the pitch at the
  datum line, the tool tip line at ``-h_a0 m``): the worm's thread faces, read back from the STEP
  by OpenCASCADE's reader (a third-party reader), screwed back into the axial half-plane and the
  axial lengths multiplied by ``cos(gamma)``, must lie on that rack within 1 um. The code derives
  its rack from the gear's outline by inverse generation instead, and sweeps a transverse section.
"""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np
import pytest

from rotorcad.cli.main import main

SAMPLES = Path(__file__).resolve().parents[1] / "samples"
GEAR = ["--teeth", "17", "--module", "3", "--shift", "0.3"]  # ISO 53 profile A: alpha 20 deg, h_a0 1.25, rho 0.38


def _run(capsys, args):
    assert main(args) == 0
    return json.loads(capsys.readouterr().out)


def _read(path: Path):
    from OCP.STEPControl import STEPControl_Reader

    reader = STEPControl_Reader()
    reader.ReadFile(str(path))
    reader.TransferRoots()
    return reader.OneShape()


@pytest.fixture(scope="module")
def worm_step(tmp_path_factory):
    """A two-start left-hand worm, 60 mm outside diameter, 12 mm long, for the gear z 17, m 3, x 0.3, as STEP."""
    folder = tmp_path_factory.mktemp("worm")
    path = folder / "hob.step"
    args = ["hob", *GEAR, "--hob-diameter", "60", "--starts", "2", "--hob-hand", "left", "--hob-length", "12"]
    assert main([*args, "--step", str(path), "--json"]) == 0
    return path


def test_worm_figures_are_the_din_3968_closed_forms(capsys):
    out = _run(capsys, ["hob", *GEAR, "--hob-diameter", "80", "--starts", "3", "--gashes", "12", "--json"])
    w = out["worms"]["gear"]
    m, z0, da = 3.0, 3, 80.0
    dm = da - 2 * 1.25 * m  # DIN 3968: d_m0 = d_a0 - 2 h_a0, the datum line of the shifted gear's rack
    gamma = math.asin(z0 * m / dm)
    assert w["reference_diameter"] == pytest.approx(dm, abs=1e-9)
    assert w["lead_angle_deg"] == pytest.approx(math.degrees(gamma), abs=1e-9)
    assert w["normal_pitch"] == pytest.approx(math.pi * m, abs=1e-9)
    assert w["axial_pitch"] == pytest.approx(math.pi * m / math.cos(gamma), abs=1e-9)
    assert w["lead"] == pytest.approx(z0 * w["axial_pitch"], abs=1e-9)
    assert math.tan(math.radians(w["lead_angle_deg"])) == pytest.approx(w["lead"] / (math.pi * dm), rel=1e-12)
    # the whole depth of the gear's tooth space: h_a0 m under the datum, (1 + x) m + x m over the pitch circle
    assert w["thread_depth"] == pytest.approx((1.25 + 1.0) * m, abs=1e-6)
    assert w["root_diameter"] == pytest.approx(da - 2 * 2.25 * m, abs=1e-6)
    assert (w["hand"], w["starts"], w["gash_count"], w["worm_length"]) == ("right", 3, 12, 80.0)
    assert w["gash_depth"] == pytest.approx(1.25 * w["thread_depth"])
    assert w["rack_join_max"] == 0.0  # the gear's rack is one chain


def test_worm_step_reads_back_as_one_valid_solid(worm_step):
    from OCP.BRepCheck import BRepCheck_Analyzer
    from OCP.TopAbs import TopAbs_SOLID
    from OCP.TopExp import TopExp_Explorer

    from exports.step_exact import faces

    shape = _read(worm_step)
    solids, explorer = 0, TopExp_Explorer(shape, TopAbs_SOLID)
    while explorer.More():
        solids += 1
        explorer.Next()
    assert solids == 1 and BRepCheck_Analyzer(shape).IsValid()
    # the gear's rack has nine pieces (tool tip, tip radius, flank, the gear's tip corner path, its tip
    # land and the mirror images): nine thread faces per start, two end caps
    assert len(faces(shape)) == 2 * 9 + 2


def _off_the_basic_rack(pts: np.ndarray) -> tuple[float, float]:
    """Screw points of the 60 mm two-start left-hand worm back to its axial section and measure them.

    The axial lengths times cos(gamma) give the normal rack, compared with the ISO 53 rack in closed
    form: the largest distance of the points on the straight flanks and on the tip radius, mm.
    """
    m, alpha, rho = 3.0, math.radians(20.0), 0.38 * 3.0
    p = math.pi * m
    dm = 60.0 - 2 * 1.25 * m
    gamma = math.asin(2 * m / dm)
    lead = -2 * p / math.cos(gamma)  # left hand
    r = np.hypot(pts[:, 0], pts[:, 1])
    phi = np.arctan2(pts[:, 1], pts[:, 0])
    x = (pts[:, 2] - lead * phi / (2 * math.pi)) * math.cos(gamma)  # the axial section turned by the lead angle
    e = np.mod(x - p / 2, p)  # from the tool tooth's centre (the gear's tooth at x = 0: the tool's at p / 2)
    e = np.minimum(e, p - e)
    v = 0.5 * dm - r  # height above the datum line, + away from the gear
    half = p / 4 + v * math.tan(alpha)  # half the tool tooth at height v
    flank = (v > -1.25 * m + rho * (1 - math.sin(alpha)) + 0.01) & (v < 1.9)
    tip = v < -1.25 * m + 1e-6
    assert flank.sum() > 100 and tip.sum() > 10
    assert np.abs(e[tip]).max() < half[tip].min()  # the tip line lies inside the tooth's width
    # the tip radius: centre rho above the tip line, rho inside the flank
    centre_u = p / 4 - (1.25 * m - rho) * math.tan(alpha) - rho / math.cos(alpha)
    corner = (v > -1.25 * m + 0.01) & (v < -1.25 * m + rho * (1 - math.sin(alpha)) - 0.01) & (e > centre_u)
    assert corner.sum() > 10
    d = np.hypot(e[corner] - centre_u, v[corner] - (-1.25 * m + rho))
    return float(np.abs((e[flank] - half[flank]) * math.cos(alpha)).max()), float(np.abs(d - rho).max())


def test_worm_thread_faces_lie_on_the_basic_rack_helicoid(worm_step):
    """Face points screwed back to the axial section lie on the ISO 53 rack within 1 um (module docstring)."""
    from OCP.BRep import BRep_Tool
    from OCP.BRepTools import BRepTools

    from exports.step_exact import faces

    pts = []
    for face in faces(_read(worm_step)):
        surface = BRep_Tool.Surface_s(face)
        u0, u1, v0, v1 = BRepTools.UVBounds_s(face)
        for u in np.linspace(u0, u1, 25):
            for v in np.linspace(v0, v1, 25):
                q = surface.Value(u, v)
                pts.append((q.X(), q.Y(), q.Z()))
    pts = np.array(pts)
    pts = pts[(pts[:, 2] > 1e-6) & (pts[:, 2] < 12.0 - 1e-6)]  # the thread faces, not the end caps
    flank, corner = _off_the_basic_rack(pts)
    assert flank < 1e-3 and corner < 1e-3, (flank, corner)


def test_worm_axial_section_is_the_normal_rack_turned_by_the_lead_angle(worm_step):
    """The solid cut by a plane through its axis (OpenCASCADE's section): the ISO 53 rack within 1 um."""
    from OCP.BRepAdaptor import BRepAdaptor_Curve
    from OCP.BRepAlgoAPI import BRepAlgoAPI_Section
    from OCP.gp import gp_Dir, gp_Pln, gp_Pnt
    from OCP.TopAbs import TopAbs_EDGE
    from OCP.TopExp import TopExp_Explorer
    from OCP.TopoDS import TopoDS

    cut = BRepAlgoAPI_Section(_read(worm_step), gp_Pln(gp_Pnt(0, 0, 0), gp_Dir(0, 1, 0)), True)
    explorer, pts = TopExp_Explorer(cut.Shape(), TopAbs_EDGE), []
    while explorer.More():
        curve = BRepAdaptor_Curve(TopoDS.Edge(explorer.Current()))
        for u in np.linspace(curve.FirstParameter(), curve.LastParameter(), 40):
            q = curve.Value(u)
            pts.append((q.X(), q.Y(), q.Z()))
        explorer.Next()
    pts = np.array(pts)
    assert np.abs(pts[:, 1]).max() < 1e-9  # in the plane y = 0: the axial sections at phi = 0 and pi
    pts = pts[(pts[:, 2] > 1e-6) & (pts[:, 2] < 12.0 - 1e-6)]
    flank, corner = _off_the_basic_rack(pts)
    assert flank < 1e-3 and corner < 1e-3, (flank, corner)


def test_rotor_pair_gets_one_worm_per_rotor(tmp_path, capsys):
    out = _run(
        capsys,
        ["hob", str(SAMPLES / "srm_asymmetric_5_6.toml"), "--hob-diameter", "120", "--step", str(tmp_path / "h.step"), "--json"],
    )
    assert sorted(out["files"]) == sorted(str(tmp_path / f"h_{n}.step") for n in ("male", "female"))
    # the gaps between the derived racks' pieces, measured here on the racks themselves, are what the thread bridges
    import tomllib

    from hob.rack import rotor_rack
    from rotorcad.design.rotors import build_pair, pair_spec
    from rotorcad.design.schema import rotor_design

    rotors = build_pair(pair_spec(rotor_design(tomllib.loads((SAMPLES / "srm_asymmetric_5_6.toml").read_text()))))
    for name in ("male", "female"):
        rack = rotor_rack(rotors, name)
        p, k = rack.normal_section()[0], rack.piece_index
        ends = [(p[k == i][-1], p[k == i + 1][0]) for i in range(len(rack.names) - 1) if (k == i).any() and (k == i + 1).any()]
        widest = max(float(np.hypot(*(b - a))) for a, b in ends)
        assert out["worms"][name]["rack_join_max"] == pytest.approx(widest if widest > 1e-9 else 0.0, abs=1e-9)
    assert 1e-4 < out["worms"]["female"]["rack_join_max"] < 2e-3  # where the female's corner paths meet its tip land
    for name, w in out["worms"].items():
        assert w["step_deviation"] < 1e-3 and w["face_count"] >= 5
        assert w["hand"] == ("right" if name == "male" else "left")  # the sample's male is right-handed
        # the normal pitch is the rack's transverse period times cos(beta)
        beta = math.radians(out["racks"][name]["helix_angle_deg"])
        assert w["normal_pitch"] == pytest.approx(out["worms"]["male"]["normal_pitch"])
        assert w["axial_pitch"] == pytest.approx(w["normal_pitch"] / math.cos(math.radians(w["lead_angle_deg"])))
        assert 0 < beta < math.pi / 2


@pytest.mark.parametrize(
    ("extra", "option"),
    [
        (["--step", "W"], "--hob-diameter"),
        (["--starts", "2"], "--hob-diameter"),
        (["--hob-diameter", "10"], "--hob-diameter"),
        (["--hob-diameter", "80", "--starts", "0"], "--starts"),
        (["--hob-diameter", "80", "--gashes", "1"], "--gashes"),
        (["--hob-diameter", "80", "--gash-depth", "5"], "--gash-depth"),
        (["--hob-diameter", "80", "--gashes", "12", "--gash-depth", "2"], "--gash-depth"),
        (["--hob-diameter", "80", "--hob-length", "-1"], "--hob-length"),
    ],
)
def test_worm_options_out_of_range_are_refused(tmp_path, capsys, extra, option):
    extra = [str(tmp_path / "w.step") if a == "W" else a for a in extra]
    assert main(["hob", *GEAR, *extra, "--csv", str(tmp_path / "rack.csv")]) == 2
    err = capsys.readouterr().err.strip()
    assert err.startswith(f"rotorcad: error: {option} must") and err.count("\n") == 0, err
    assert not list(tmp_path.iterdir())

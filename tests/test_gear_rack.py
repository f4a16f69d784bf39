"""Gear racks against the closed-form ISO 53 basic rack.

References, none of them the code under test: ISO 53's basic rack (pitch p = pi m, tooth thickness
p / 2 on the datum line, addendum h_aP* m, dedendum h_fP* m, straight flanks at alpha_n, root
fillet rho_fP* m), ISO 21771's transverse section of a helical rack (p_t = p_n / cos(beta),
tan(alpha_t) = tan(alpha_n) / cos(beta)), measured on the outline with shapely and on the solid with
trimesh's plane section (the normal section, perpendicular to the teeth).
"""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np
import pytest
import shapely
import shapely.affinity

from exports.csv_points import read_points
from rotorcad.cli.main import main
from rotorcad.errors import DesignError
from rotorcad.gears.rack import GearRack, rack_solid_mesh

DEG = math.pi / 180.0
RACKS = [
    (100.0, 2.0, 20.0, 0.0, 0.38),
    (87.3, 3.0, 20.0, 15.0, 0.38),
    (60.0, 1.25, 25.0, -30.0, 0.25),
    (40.0, 4.0, 14.5, 0.0, 0.0),
]


def datum_chords(section: shapely.Polygon, y: float = 0.0) -> list[tuple[float, float]]:
    """The material's chords along the line at height y, as (start, end) along x."""
    x0, _, x1, _ = section.bounds
    cut = section.intersection(shapely.LineString([(x0 - 1, y), (x1 + 1, y)]))
    return sorted((min(g.coords[0][0], g.coords[-1][0]), max(g.coords[0][0], g.coords[-1][0])) for g in shapely.get_parts(cut))


@pytest.mark.parametrize(("length", "m", "alpha", "beta", "rho"), RACKS)
def test_pitch_thickness_heights_on_the_outline(length, m, alpha, beta, rho):
    rack = GearRack(length, m, pressure_angle=alpha * DEG, helix_angle=beta * DEG, root_radius_factor=rho, tolerance=1e-5)
    section = shapely.Polygon(rack.outline())
    assert section.is_valid
    p_t = math.pi * m / math.cos(beta * DEG)  # ISO 21771: transverse pitch of a helical rack
    chords = [c for c in datum_chords(section) if c[0] > 1e-9 and c[1] < length - 1e-9]  # whole teeth
    widths = np.array([b - a for a, b in chords])
    centres = np.array([(a + b) / 2 for a, b in chords])
    np.testing.assert_allclose(widths, p_t / 2, atol=1e-9)  # ISO 53: s = p / 2 on the datum line
    np.testing.assert_allclose(np.diff(centres), p_t, atol=1e-9)
    assert centres[0] == pytest.approx(p_t / 2, abs=1e-9)  # the frame: tooth centres at (j + 1/2) p_t
    x0, y0, x1, y1 = section.bounds
    assert (x0, x1) == pytest.approx((0.0, length), abs=1e-9)
    assert y1 == pytest.approx(m, abs=1e-12)  # h_aP* = 1
    assert y0 == pytest.approx(-(1.25 + 2.0) * m, abs=1e-12)  # the back, h_fP* m + 2 m below the datum
    # the root line at -h_fP* m: the chord just above it spans the space's root
    assert datum_chords(section, -1.25 * m + 1e-9)[0][1] - datum_chords(section, -1.25 * m + 1e-9)[0][0] < length


@pytest.mark.parametrize(("length", "m", "alpha", "beta", "rho"), RACKS)
def test_flank_angle_is_the_transverse_pressure_angle(length, m, alpha, beta, rho):
    rack = GearRack(length, m, pressure_angle=alpha * DEG, helix_angle=beta * DEG, root_radius_factor=rho)
    alpha_t = math.atan(math.tan(alpha * DEG) / math.cos(beta * DEG))
    section = shapely.Polygon(rack.outline())
    # chords at two heights on the straight flank: the tooth narrows by 2 dy tan(alpha_t)
    lo, hi = -0.5 * m, 0.8 * m
    w_lo = [b - a for a, b in datum_chords(section, lo) if a > 1e-9 and b < length - 1e-9]
    w_hi = [b - a for a, b in datum_chords(section, hi) if a > 1e-9 and b < length - 1e-9]
    n = min(len(w_lo), len(w_hi))
    np.testing.assert_allclose(np.array(w_lo[:n]) - np.array(w_hi[:n]), 2 * (hi - lo) * math.tan(alpha_t), atol=1e-9)


def test_root_fillet_radius_and_tangency():
    m, rho = 2.0, 0.38
    rack = GearRack(50.0, m, tolerance=1e-6)
    pts = rack.period()
    a = 20 * DEG
    # ISO 53: the fillet's centre lies rho m above the root line and rho m from the flank
    yc = -1.25 * m + rho * m
    xc = math.pi * m / 2 + math.pi * m / 4 + (rho * m - yc * math.sin(a)) / math.cos(a)  # right flank of the tooth at p/2
    near = pts[(pts[:, 1] < yc) & (np.abs(pts[:, 0] - xc) <= rho * m)]
    assert len(near) > 5
    np.testing.assert_allclose(np.hypot(near[:, 0] - xc, near[:, 1] - yc), rho * m, atol=1e-12)


def test_solid_normal_section_is_the_basic_rack():
    # the helical rack's solid cut by a plane perpendicular to its teeth (trimesh): ISO 53's normal
    # section, tooth thickness p_n / 2 on the datum line and flank angle alpha_n
    m, beta, b = 2.0, 20 * DEG, 30.0
    rack = GearRack(120.0, m, helix_angle=beta, tolerance=1e-5)
    tm = rack_solid_mesh(rack, b).to_trimesh()
    assert tm.is_watertight
    assert tm.volume == pytest.approx(rack.section.area * b, rel=1e-9)
    along = np.array([math.sin(beta), 0.0, math.cos(beta)])  # the teeth's direction (x shifts by z tan(beta))
    origin = np.array([60.0, 0.0, b / 2])
    path = tm.section(plane_origin=origin, plane_normal=along)
    # coordinates in the plane: u across the teeth, v = y
    u_axis = np.array([math.cos(beta), 0.0, -math.sin(beta)])
    lines = []
    for entity in path.entities:
        p = path.vertices[entity.points] - origin
        lines.append(shapely.LineString(np.column_stack([p @ u_axis, p[:, 1]])))
    polys = [p for p in shapely.get_parts(shapely.polygonize(shapely.set_precision(lines, 1e-9)))]
    section = max(polys, key=lambda p: p.area)
    x0, _, x1, _ = section.bounds
    chords = [c for c in datum_chords(section) if c[0] > x0 + 1e-6 and c[1] < x1 - 1e-6]
    assert len(chords) >= 3
    np.testing.assert_allclose([c[1] - c[0] for c in chords], math.pi * m / 2, atol=1e-6)
    np.testing.assert_allclose(np.diff([(c[0] + c[1]) / 2 for c in chords]), math.pi * m, atol=1e-6)
    lo = [c[1] - c[0] for c in datum_chords(section, -0.5 * m) if c[0] > x0 + 1e-6 and c[1] < x1 - 1e-6]
    hi = [c[1] - c[0] for c in datum_chords(section, 0.8 * m) if c[0] > x0 + 1e-6 and c[1] < x1 - 1e-6]
    n = min(len(lo), len(hi))
    np.testing.assert_allclose(np.array(lo[:n]) - np.array(hi[:n]), 2 * 1.3 * m * math.tan(20 * DEG), atol=1e-6)


@pytest.mark.parametrize(
    ("kwargs", "param"),
    [
        ({"length": 0.0}, "rack_length"),
        ({"length": -5.0}, "rack_length"),
        ({"length": 1e9}, "rack_length"),
        ({"height": 1.0}, "rack_height"),
        ({"root_radius_factor": 0.9}, "tip_radius_factor"),
        ({"addendum": 2.5}, "addendum"),
    ],
)
def test_bad_rack_values_are_named(kwargs, param):
    args = {"length": 50.0, "module": 2.0, **kwargs}
    with pytest.raises(DesignError) as err:
        GearRack(**args)
    assert err.value.param == param


def run(capsys, *args):
    rc = main([str(a) for a in args])
    out = capsys.readouterr()
    return rc, out.out, out.err


def test_cli_rack(tmp_path, capsys):
    rc, out, err = run(
        capsys, "gear", "--teeth", 20, "--module", 2, "--helix-angle", 15, "--rack", 80, "--out", tmp_path, "--json"
    )
    assert rc == 0, err
    data = json.loads(out)
    assert data["rack"]["pitch"] == pytest.approx(math.pi * 2 / math.cos(15 * DEG), abs=1e-12)
    assert data["rack"]["tooth_thickness"] == pytest.approx(math.pi * 2 / math.cos(15 * DEG) / 2, abs=1e-12)
    section = shapely.Polygon(read_points(tmp_path / "rack.csv"))
    assert section.area == pytest.approx(data["rack"]["area"], rel=1e-9)
    assert (tmp_path / "rack.dxf").exists()


def test_cli_rack_bad_length(tmp_path, capsys):
    rc, _, err = run(capsys, "gear", "--teeth", 20, "--module", 2, "--rack", -3, "--out", tmp_path / "o")
    assert rc == 2 and "--rack" in err and err.count("\n") == 1
    assert not (tmp_path / "o").exists()


def test_export_rack_body(tmp_path, capsys):
    # rotorcad export of a gear design with [rack]: the STL read back by trimesh is watertight, holds
    # the section's area x face width, and its section at mid-face is the outline shifted by z tan(beta)
    import trimesh

    design = tmp_path / "g.toml"
    design.write_text("[gear]\nteeth = 20\nmodule = 2.0\nhelix_angle_deg = 15\nface_width = 24\n\n[rack]\nlength = 60\n")
    out = tmp_path / "o"
    assert main(["export", str(design), "--out", str(out), "--format", "stl,csv,step", "--json"]) == 0
    files = {(f["body"], f["format"]): f for f in json.loads(capsys.readouterr().out)["files"]}
    section = shapely.Polygon(read_points(Path(files["rack", "csv"]["path"])))
    mesh = trimesh.load(files["rack", "stl"]["path"])
    assert mesh.is_watertight
    assert mesh.volume == pytest.approx(section.area * 24.0, rel=1e-6)
    cut = mesh.section(plane_origin=[0, 0, 12.0], plane_normal=[0, 0, 1])
    planar, to_3d = cut.to_2D()
    rings = [
        shapely.Polygon(trimesh.transform_points(np.column_stack([p, np.zeros(len(p))]), to_3d)[:, :2]) for p in planar.discrete
    ]
    mid = max(rings, key=lambda p: p.area)
    shifted = shapely.affinity.translate(section, xoff=12.0 * math.tan(15 * DEG))
    assert mid.symmetric_difference(shifted).area < 1e-6 * section.area
    from exports.step import read_step

    info = read_step(Path(files["rack", "step"]["path"]))
    fine = GearRack(60.0, 2.0, helix_angle=15 * DEG, tolerance=1e-6).section  # the CSV's chords are at tol / 4
    assert info["solids"] == 1 and info["valid"] and info["volume"] == pytest.approx(fine.area * 24.0, rel=1e-7)


def closed_form_area(n: int, m: float, alpha: float, beta: float, rho: float, height: float) -> float:
    """Section area of a rack of n whole pitches (ISO 53 profile, h_aP* = 1, h_fP* = 1.25).

    Per pitch in the normal section: the trapezoid tooth above the root line,
    (p/2)(h_a + h_f) - tan(alpha)(h_a^2 - h_f^2), plus the two root fillets, each the area between
    an arc of radius rho and its two tangents turning by psi = pi/2 - alpha, rho^2 (tan(psi/2) - psi/2);
    stretched by 1/cos(beta) along the length; below the root line the bar of height H - h_f.
    """
    h_a, h_f, p = m, 1.25 * m, math.pi * m
    psi = math.pi / 2 - alpha
    tooth = p / 2 * (h_a + h_f) - math.tan(alpha) * (h_a**2 - h_f**2) + 2 * (rho * m) ** 2 * (math.tan(psi / 2) - psi / 2)
    k = 1 / math.cos(beta)
    return n * k * tooth + n * k * p * (height - h_f)


@pytest.mark.parametrize("beta", [0.0, 20.0])
def test_rack_area_and_exact_step_volume(tmp_path, beta):
    from exports.step import read_step
    from exports.step_rack import write_rack_step

    m, n, b = 2.0, 9, 24.0
    p_t = math.pi * m / math.cos(beta * DEG)
    rack = GearRack(n * p_t, m, helix_angle=beta * DEG, tolerance=1e-6)
    area = closed_form_area(n, m, 20 * DEG, beta * DEG, 0.38, rack.back_height)
    assert rack.section.area == pytest.approx(area, abs=rack.section.length * 1e-6)  # chords within 1e-6 mm
    path = tmp_path / "rack.step"
    out = write_rack_step(path, rack, b)
    info = read_step(path)
    assert info["solids"] == 1 and info["valid"]
    assert info["volume"] == pytest.approx(area * b, rel=1e-9)  # exact surfaces: the closed form
    assert out["faces"] >= 6 * n  # one face per piece: root, fillet, flank, tip, flank, fillet per pitch

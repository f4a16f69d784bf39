"""A gear as a part: tip chamfer or rounding, bore with a DIN 6885-1 keyway, hub, herringbone.

References, none of them rotorcad's output:
- DIN 6885-1:1968 table 1 (the key sections b x h and keyway depths t1, t2 by bore; the rows
  38-230 mm as printed in Siemens MD 31.1 (2016), "Connection dimensions"), and the standard's
  own relation t1 + t2 = h + a back clearance of 0.2-0.5 mm;
- closed forms: the bore with its keyway pi R^2 + b B - [(b/2) sqrt(R^2 - b^2/4) + R^2 asin(b/2R)]
  checked against shapely's union of a circle and a rectangle; a prism's, a helical and a herringbone
  solid's volume = section area x face width (Cavalieri: every transverse slice is the section
  turned); the rim limit s_R >= 0.5 h_t of ISO 6336-3 (Y_B);
- the chamfer and rounding measured on the outline with shapely (the material cut off, its radial
  height, equal legs; the rounding's circle fitted by least squares, its centre's distance to the
  unbroken flank and to the tip circle);
- OpenCASCADE reading the STEP back (validity, one solid, faces one per piece, volume by
  Gauss-Kronrod), and the faces' points turned back by the herringbone's own turn 2 pi min(z, b-z)/h;
- the meshes' volume against the STEP's within the surface tolerance times the surface area.
"""

from __future__ import annotations

import itertools
import json
import math
import xml.etree.ElementTree as ET
from pathlib import Path

import numpy as np
import pytest
import shapely

from exports.gear_step import gear_part_shape
from exports.step import read_step
from exports.step_exact import faces, section_segments, write_shape
from rotorcad.cli.main import main
from rotorcad.errors import DesignError
from rotorcad.gear import DEG, InvoluteGear
from rotorcad.gears.features import GearFeatures, SolidFeatures, made_features
from rotorcad.gears.keys import DIN_6885_1, key_for_bore
from rotorcad.gears.part_mesh import part_solid

# DIN 6885-1 table 1: bore d (a value inside the row) -> (b, h, t1, t2), mm
DIN_ROWS = {
    7.0: (2, 2, 1.2, 1.0),
    12.0: (4, 4, 2.5, 1.8),  # 12 is the last bore of 10-12
    12.5: (5, 5, 3.0, 2.3),
    25.0: (8, 7, 4.0, 3.3),
    40.0: (12, 8, 5.0, 3.3),
    45.0: (14, 9, 5.5, 3.8),
    60.0: (18, 11, 7.0, 4.4),
    100.0: (28, 16, 10.0, 6.4),
    180.0: (45, 25, 15.0, 10.4),
    250.0: (56, 32, 20.0, 12.4),
    500.0: (100, 50, 31.0, 19.5),
}


def _volume(shape) -> float:
    from OCP.BRepGProp import BRepGProp
    from OCP.GProp import GProp_GProps

    props = GProp_GProps()
    BRepGProp.VolumePropertiesGK_s(shape, props, 1e-9, False, True)
    return float(props.Mass())


def _valid(shape) -> bool:
    from OCP.BRepCheck import BRepCheck_Analyzer

    return bool(BRepCheck_Analyzer(shape).IsValid())


def _hole(radius: float, width: float, bottom: float) -> shapely.Geometry:
    """The bore with its keyway by shapely: a circle (65 536 sides) and the keyway's rectangle."""
    circle = shapely.Point(0.0, 0.0).buffer(radius, quad_segs=16384)
    return circle.union(shapely.box(0.0, -width / 2, bottom, width / 2)) if width > 0 else circle


@pytest.fixture(scope="module")
def spur() -> InvoluteGear:
    return InvoluteGear(teeth=13, module=2.0, pressure_angle=20 * DEG, tolerance=1e-4)


@pytest.fixture(scope="module")
def helical() -> InvoluteGear:
    return InvoluteGear(teeth=11, module=2.0, pressure_angle=20 * DEG, helix_angle=20 * DEG, tolerance=1e-4)


# --- DIN 6885-1 --------------------------------------------------------------------------------


@pytest.mark.parametrize("bore", sorted(DIN_ROWS))
def test_the_key_of_a_bore_is_din_6885_1s(bore):
    key = key_for_bore(bore)
    assert (key.width, key.height, key.shaft_depth, key.hub_depth) == DIN_ROWS[bore]


def test_din_6885_1_rows_are_contiguous_and_the_key_has_its_back_clearance():
    for lower, upper in itertools.pairwise(DIN_6885_1):
        assert upper.bore_over == lower.bore_to and upper.width > lower.width
    for row in DIN_6885_1:  # t1 + t2 = h + the back clearance between key and hub (0.2 to 0.5 mm)
        assert 0.2 - 1e-9 <= row.shaft_depth + row.hub_depth - row.height <= 0.5 + 1e-9
    for bore in (6.0, 500.5):
        with pytest.raises(DesignError, match="DIN 6885-1"):
            key_for_bore(bore)


# --- bore and keyway: closed form against shapely ---------------------------------------------


@pytest.mark.parametrize("bore", [8.0, 30.0, 95.0])
def test_bore_and_keyway_area_closed_form_against_shapely(bore):
    key = key_for_bore(bore)
    solid = SolidFeatures(bore_radius=bore / 2, key_width=key.width, key_bottom=bore / 2 + key.hub_depth, turn=0.3)
    reference = _hole(bore / 2, key.width, bore / 2 + key.hub_depth)
    assert solid.hole_area == pytest.approx(reference.area, rel=1e-7)
    ring = shapely.Polygon(solid.hole_points(1e-4))
    assert ring.is_valid and ring.area == pytest.approx(reference.area, abs=ring.length * 1e-4)  # chords sag <= 0.1 um
    # turned with its body: the keyway's middle at the turn
    far = np.asarray(ring.exterior.coords)[np.argmax(np.hypot(*np.asarray(ring.exterior.coords).T))]
    assert math.atan2(far[1], far[0]) == pytest.approx(0.3, abs=key.width / bore)


# --- tip chamfer and rounding measured with shapely ---------------------------------------------


def _cut_off(gear, features, tol=1e-5) -> list[shapely.Polygon]:
    plain = shapely.Polygon(gear.outline(tol).points)
    broken = shapely.Polygon(features.outline(tol).points)
    assert broken.is_valid and broken.within(plain.buffer(2 * tol))  # both sampled to the chord tol
    pieces = shapely.get_parts(plain.difference(broken))
    return [p for p in pieces if p.area > 1e-6]


@pytest.mark.parametrize("which", ["spur", "helical"])
def test_tip_chamfer_measured_on_the_outline(which, request):
    gear = request.getfixturevalue(which)
    h_k = 0.25
    made = made_features(gear, GearFeatures(tip_chamfer=h_k))
    pieces = _cut_off(gear, made)
    assert len(pieces) == 2 * gear.teeth  # both corners of every tooth
    ra = gear.nominal_tip_radius
    plain = shapely.Polygon(gear.outline(1e-5).points).exterior
    broken = shapely.Polygon(made.outline(1e-5).points).exterior
    for piece in pieces[:6]:
        xy = np.asarray(piece.exterior.coords)[:-1]
        on_plain = shapely.distance(shapely.points(xy), plain) < 1e-9
        on_broken = shapely.distance(shapely.points(xy), broken) < 1e-9
        e1, e2 = xy[on_plain & on_broken][:2]  # where the chamfer leaves the flank and the tip circle
        d = (e2 - e1) / np.hypot(*(e2 - e1))
        off_line = np.abs((xy[:, 0] - e1[0]) * d[1] - (xy[:, 1] - e1[1]) * d[0])
        assert off_line[~on_plain].max() < 1e-9  # the chamfer's own points: one straight line
        corner = xy[np.argmax(off_line)]  # the sharp corner cut off
        r1, r2 = sorted(np.hypot(*np.array([e1, e2]).T))
        assert ra - r1 == pytest.approx(h_k, abs=2e-5)  # radial height on the flank
        assert r2 == pytest.approx(ra, abs=2e-5)  # the other end on the tip circle
        assert np.hypot(*(corner - e1)) == pytest.approx(np.hypot(*(corner - e2)), rel=1e-3)  # equal legs


@pytest.mark.parametrize("which", ["spur", "helical"])
def test_tip_rounding_is_a_circle_tangent_to_flank_and_tip(which, request):
    gear = request.getfixturevalue(which)
    r_k = 0.4
    plain = shapely.Polygon(gear.outline(1e-5).points)
    pieces = _cut_off(gear, made_features(gear, GearFeatures(tip_rounding=r_k)))
    assert len(pieces) == 2 * gear.teeth
    for piece in pieces[:4]:
        xy = np.asarray(piece.exterior.coords)[:-1]
        inside = xy[shapely.distance(shapely.points(xy), plain.exterior) > 1e-3 * r_k]  # the arc's points
        # Kasa's least-squares circle: x^2 + y^2 = 2 a x + 2 b y + c
        a, b, c = np.linalg.lstsq(np.column_stack([2 * inside, np.ones(len(inside))]), (inside**2).sum(axis=1), rcond=None)[0]
        radius = math.sqrt(c + a * a + b * b)
        assert radius == pytest.approx(r_k, rel=1e-4)
        centre = shapely.Point(a, b)
        assert centre.distance(plain.exterior) == pytest.approx(r_k, abs=2e-5)  # tangent to the flank
        assert gear.nominal_tip_radius - math.hypot(a, b) == pytest.approx(r_k, abs=2e-5)  # and to the tip circle


def test_refusals_name_the_value_and_the_range(spur):
    with pytest.raises(DesignError, match=r"below .* mm for this tooth") as err:
        made_features(spur, GearFeatures(tip_chamfer=5.0))
    assert err.value.param == "tip_chamfer"
    # ISO 6336-3: a rim of at least half the tooth height under the bore
    rim_limit = 2 * (spur.root_radius - 0.5 * (spur.tip_radius - spur.root_radius))
    made_features(spur, GearFeatures(bore_diameter=rim_limit - 1e-6))
    with pytest.raises(DesignError, match=f"at most {rim_limit:.4g} mm") as err:
        made_features(spur, GearFeatures(bore_diameter=rim_limit + 1e-3))
    assert err.value.param == "bore_diameter"
    for asked, param in [
        (GearFeatures(tip_chamfer=0.2, tip_rounding=0.2), "tip_rounding"),
        (GearFeatures(keyway=True), "keyway"),
        (GearFeatures(hub_length=5.0), "hub_diameter"),
        (GearFeatures(bore_diameter=8.0, hub_diameter=7.0, hub_length=5.0), "hub_diameter"),
        (GearFeatures(herringbone=True), "herringbone"),
    ]:
        with pytest.raises(DesignError) as err:
            made_features(spur, asked)
        assert err.value.param == param


def test_the_command_line_names_the_key(tmp_path, capsys):
    design = tmp_path / "g.toml"
    design.write_text("[gear]\nteeth = 13\nmodule = 2.0\nbore_diameter = 40.0\n")
    assert main(["gear", str(design)]) == 2
    err = capsys.readouterr().err
    assert "[gear] bore_diameter must be at most" in err and "Traceback" not in err
    design.write_text("[gear]\nteeth = 13\nmodule = 2.0\nherringbone = 1\n")
    assert main(["gear", str(design)]) == 2
    assert "[gear] herringbone must be true or false" in capsys.readouterr().err


# --- exact STEP and meshes ------------------------------------------------------------------------


PART = GearFeatures(tip_chamfer=0.2, bore_diameter=10.0, keyway=True, hub_diameter=18.0, hub_length=5.0)
WIDTH = 8.0


@pytest.fixture(scope="module")
def spur_part(spur):
    made = made_features(spur, PART)
    segments = section_segments(made.outline(1e-2), 0.0, 1e-3)
    solid, deviation = gear_part_shape(segments, float("inf"), WIDTH, 1e-3, made.solid, made.outline(1e-5).points)
    return made, segments, solid, deviation


def _closed_form_volume(made, width) -> float:
    """(section - hole) b + (hub disc - hole) L_h, the areas by shapely (not rotorcad's closed form)."""
    s = made.solid
    hole = _hole(s.bore_radius, s.key_width, s.key_bottom).area
    section = shapely.Polygon(made.outline(1e-6).points).area
    return (section - hole) * width + (math.pi * s.hub_radius**2 - hole) * s.hub_length


def test_spur_part_step_one_face_per_piece_and_its_volume(spur_part, tmp_path):
    made, segments, solid, deviation = spur_part
    assert _valid(solid) and deviation <= 1e-3
    # the section's pieces (involutes, fillets, root and tip arcs, chamfers), two end faces, the hub's
    # cylinder and end face, the bore's cylinder and the keyway's three planes
    assert len(faces(solid)) == len(segments) + 2 + 2 + 1 + 3
    assert sum(s.name == "tip chamfer" for s in segments) == 2 * made.gear.teeth
    expected = _closed_form_volume(made, WIDTH)
    assert _volume(solid) == pytest.approx(expected, rel=2e-6)
    write_shape(tmp_path / "p.step", solid, "gear")
    info = read_step(tmp_path / "p.step")
    assert info["solids"] == 1 and info["valid"] and info["volume"] == pytest.approx(expected, rel=2e-6)
    from OCP.STEPControl import STEPControl_Reader  # the faces of the file as OpenCASCADE reads it back

    reader = STEPControl_Reader()
    reader.ReadFile(str(tmp_path / "p.step"))
    reader.TransferRoots()
    assert len(faces(reader.OneShape())) == len(segments) + 8


def test_spur_part_mesh_against_the_step(spur_part):
    made, _, solid, _ = spur_part
    tol = 5e-3
    mesh = part_solid(shapely.Polygon(made.outline(tol / 4).points), float("inf"), WIDTH, tol, made.solid)
    s = made.solid
    area = shapely.Polygon(made.outline(tol).points).exterior.length * WIDTH
    area += 2 * math.pi * (s.bore_radius * (WIDTH + s.hub_length) + s.hub_radius * s.hub_length)
    assert mesh.manifold.genus() == 1  # one through hole
    assert abs(mesh.volume - _volume(solid)) <= area * tol


@pytest.fixture(scope="module")
def herringbone(helical):
    made = made_features(helical, GearFeatures(herringbone=True, tip_rounding=0.3))
    lead = 2 * math.pi * helical.pitch_radius / math.tan(helical.helix_angle)
    segments = section_segments(made.outline(1e-2), 0.0, 1e-3)
    solid, deviation = gear_part_shape(segments, lead, 12.0, 1e-3, made.solid, made.outline(1e-5).points)
    return made, lead, segments, solid, deviation


def test_herringbone_step_volume_faces_and_mirror_symmetry(herringbone):
    from OCP.BRep import BRep_Tool
    from OCP.BRepTools import BRepTools

    made, lead, segments, solid, deviation = herringbone
    width = 12.0
    assert _valid(solid) and deviation <= 1e-3
    assert len(faces(solid)) == 2 * len(segments) + 2  # every piece once per half, two end faces
    section = shapely.Polygon(made.outline(1e-6).points)
    # as the helical gear's, within the faces' measured distance from the helicoid times their area
    assert _volume(solid) == pytest.approx(section.area * width, abs=deviation * section.exterior.length * width)
    # every face point turned back by the herringbone's turn 2 pi min(z, b - z) / h lies on the section
    pts = []
    for face in faces(solid):
        surface = BRep_Tool.Surface_s(face)
        u0, u1, v0, v1 = BRepTools.UVBounds_s(face)
        pts += [surface.Value(u, v).Coord() for u in np.linspace(u0, u1, 5) for v in np.linspace(v0, v1, 5)]
    p = np.array(pts)
    side = (p[:, 2] > 1e-9) & (p[:, 2] < width - 1e-9)
    p = p[side]
    turn = -2 * np.pi * np.minimum(p[:, 2], width - p[:, 2]) / lead
    c, s = np.cos(turn), np.sin(turn)
    back = np.column_stack([c * p[:, 0] - s * p[:, 1], s * p[:, 0] + c * p[:, 1]])
    assert (p[:, 2] > width / 2 + 1).sum() > 100 and (p[:, 2] < width / 2 - 1).sum() > 100  # both halves sampled
    ring = shapely.Polygon(made.outline(1e-5).points).exterior  # 10 nm chords: 100 times finer than the check
    assert shapely.distance(shapely.points(back), ring).max() <= 1e-3


def test_herringbone_mesh_is_mirror_symmetric_and_matches_the_step(herringbone):
    made, lead, _, solid, _ = herringbone
    width, tol = 12.0, 5e-3
    section = shapely.Polygon(made.outline(tol / 4).points)
    mesh = part_solid(section, lead, width, tol, made.solid)
    assert abs(mesh.volume - _volume(solid)) <= section.exterior.length * width * tol

    def slice_at(z: float) -> shapely.Geometry:
        return shapely.union_all([shapely.Polygon(r) for r in mesh.manifold.slice(z).to_polygons()])

    low, high = slice_at(width / 4), slice_at(3 * width / 4)
    assert low.symmetric_difference(high).area <= section.exterior.length * 2 * tol  # the mid plane mirrors
    turned = shapely.affinity.rotate(section, 2 * np.pi * (width / 4) / lead, origin=(0, 0), use_radians=True)
    assert low.symmetric_difference(turned).area <= section.exterior.length * 2 * tol


# --- the command line: export and SVG --------------------------------------------------------------


DESIGN = """[gear]
teeth = 13
module = 2.0
face_width = 8.0
tip_chamfer = 0.2
bore_diameter = 10.0
keyway = true
hub_diameter = 18.0
hub_length = 5.0
"""


def test_export_of_a_gear_part(tmp_path, capsys, spur_part):
    design = tmp_path / "part.toml"
    design.write_text(DESIGN)
    capsys.readouterr()
    args = ["export", str(design), "--format", "stl,step,dxf", "--out", str(tmp_path / "o"), "--tolerance", "0.01", "--json"]
    assert main(args) == 0
    rows = {f["format"]: f for f in json.loads(capsys.readouterr().out)["files"]}
    made = spur_part[0]
    expected = _closed_form_volume(made, WIDTH)
    step = rows["step"]
    info = read_step(Path(step["path"]))
    assert info["solids"] == 1 and info["valid"] and step["faces"] == len(spur_part[1]) + 8
    assert info["volume"] == pytest.approx(expected, rel=2e-6) and step["volume"] == pytest.approx(expected, rel=2e-6)
    assert abs(rows["stl"]["volume"] - expected) <= 200.0 * 0.01 * WIDTH  # perimeters < 200 mm at 10 um
    import ezdxf  # a third-party reader of the drawing: the bore with its keyway on the layer BORE

    doc = ezdxf.readfile(rows["dxf"]["path"])
    bore = [shapely.Polygon([p[:2] for p in e.get_points()]) for e in doc.modelspace().query('LWPOLYLINE[layer=="BORE"]')]
    key = key_for_bore(10.0)
    assert len(bore) == 1 and bore[0].area == pytest.approx(
        _hole(5.0, key.width, 5.0 + key.hub_depth).area, abs=bore[0].length * 0.01
    )


def _svg_layers(path: Path) -> dict[str, list[np.ndarray]]:
    """Each layer's paths as their points in the drawing's frame (the 'd' data, y up, mm)."""
    layers: dict[str, list[np.ndarray]] = {}
    for group in ET.parse(path).getroot().iter("{http://www.w3.org/2000/svg}g"):
        for element in group:
            if element.tag.endswith("path"):
                nums = [float(t) for t in element.attrib["d"].replace("M", " ").replace("L", " ").replace("Z", " ").split()]
                layers.setdefault(group.attrib["id"], []).append(np.array(nums).reshape(-1, 2))
            elif element.tag.endswith("circle"):
                layers.setdefault(group.attrib["id"], []).append(np.array([[float(element.attrib["r"]), 0.0]]))
    return layers


def test_svg_holds_the_broken_outline_the_bore_and_the_hub(tmp_path, capsys, spur):
    design = tmp_path / "part.toml"
    design.write_text(DESIGN)
    assert main(["gear", str(design), "--svg", str(tmp_path / "p.svg")]) == 0
    capsys.readouterr()
    layers = _svg_layers(tmp_path / "p.svg")
    key = key_for_bore(10.0)
    bore = shapely.Polygon(layers["BORE"][0])
    assert bore.area == pytest.approx(_hole(5.0, key.width, 5.0 + key.hub_depth).area, abs=bore.length * 1e-4)  # chords
    assert layers["HUB"][0][0, 0] == pytest.approx(9.0)
    gear = shapely.Polygon(layers["GEAR"][0])
    plain = shapely.Polygon(spur.outline(1e-4).points)
    cut = plain.difference(gear)  # the chamfers: 2 z pieces of some 0.01 mm²
    assert len([p for p in shapely.get_parts(cut) if p.area > 1e-3]) == 2 * spur.teeth  # slivers of the chords left out
    assert gear.area < plain.area - 2 * spur.teeth * 1e-3


def test_gear_json_reports_the_features(tmp_path, capsys, spur):
    design = tmp_path / "part.toml"
    design.write_text(DESIGN)
    capsys.readouterr()
    assert main(["gear", str(design), "--json"]) == 0
    features = json.loads(capsys.readouterr().out)["features"]
    # DIN 6885-1: a 10 mm bore takes the 3 x 3 key, t1 = 1.8, t2 = 1.4 (8 < d <= 10)
    assert (features["keyway_width"], features["keyway_height"]) == (3.0, 3.0)
    assert (features["keyway_shaft_depth"], features["keyway_hub_depth"]) == (1.8, 1.4)
    # the rim: root radius r_f = m (z/2 - 1.25) (ISO 53 rack, x = 0) less the keyway's bottom d/2 + t2
    assert features["rim_thickness"] == pytest.approx(2.0 * (13 / 2 - 1.25) - (5.0 + 1.4), abs=1e-9)
    assert features["tip_break_radius"] == pytest.approx(2.0 * (13 / 2 + 1) - 0.2, abs=1e-9)
    assert features["tip_chamfer"] == 0.2 and features["tip_rounding"] is None and features["herringbone"] is False

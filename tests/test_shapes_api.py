"""Every solid as an OpenCASCADE ``TopoDS_Solid`` (exports/shapes.py), for CadQuery and build123d.

References: OpenCASCADE's own checks and mass properties of the returned solids (BRepCheck,
Gauss-Kronrod volume, bounding box), against closed forms computed here with shapely: section area
x face width (a gear, a helical rotor), a gear part's (section - bore) x face width, the housing's
block minus the union of its two bore circles; the mate's axis at the working centre distance
(ISO 21771: a_w = a cos(alpha) / cos(alpha_w), the pair's own value not used).
"""

from __future__ import annotations

import math

import pytest
import shapely

from exports.shapes import gear_shapes, housing_shapes, rotor_shapes
from rotorcad import DEG, GearPair, InvoluteGear, RotorPair, build_family
from rotorcad.families.checks import outline_loops
from rotorcad.gears.features import GearFeatures


def _props(solid) -> tuple[float, tuple[float, float, float]]:
    from OCP.BRepGProp import BRepGProp
    from OCP.GProp import GProp_GProps

    props = GProp_GProps()
    BRepGProp.VolumePropertiesGK_s(solid, props, 1e-9, False, True)
    c = props.CentreOfMass()
    return float(props.Mass()), (c.X(), c.Y(), c.Z())


def test_gear_and_mate_as_solids():
    from OCP.BRepCheck import BRepCheck_Analyzer
    from OCP.TopoDS import TopoDS_Solid

    gear = InvoluteGear(13, 2.0, 20 * DEG, helix_angle=15 * DEG)
    mate = InvoluteGear(19, 2.0, 20 * DEG, helix_angle=15 * DEG)
    solids = gear_shapes(gear, 6.0, GearPair(gear, mate), GearFeatures(bore_diameter=8.0))
    assert set(solids) == {"gear", "mate"}
    for name, g in (("gear", gear), ("mate", mate)):
        solid = solids[name]
        assert isinstance(solid, TopoDS_Solid) and BRepCheck_Analyzer(solid).IsValid()
        volume, _ = _props(solid)
        section = shapely.Polygon(g.outline(1e-6).points).area
        hole = math.pi * 4.0**2 if name == "gear" else 0.0
        assert volume == pytest.approx((section - hole) * 6.0, rel=1e-5)
    # the mate about the working centre distance: zero shifts, so a_w = a = m_t (z1 + z2) / 2
    a = 2.0 / math.cos(15 * DEG) * (13 + 19) / 2
    assert _props(solids["mate"])[1][0] == pytest.approx(a, abs=1e-3)  # its centre of mass on its axis (symmetric)


CLEAN_ROUNDINGS = {"tip_rounding": 0.0, "root_rounding": 0.6}  # on the 116 mm pair: outlines that do not cross themselves


@pytest.fixture(scope="module")
def short_pair() -> RotorPair:
    return RotorPair(5, 6, 116.0, 63.0, 45.0, 71.0, 53.0, lead=300.0, length=20.0)


@pytest.mark.parametrize("profile", [{}, CLEAN_ROUNDINGS], ids=["default roundings", "roundings it can follow"])
def test_rotors_as_solids(short_pair, profile):
    from OCP.BRepCheck import BRepCheck_Analyzer
    from OCP.TopoDS import TopoDS_Solid

    rotors = build_family(short_pair, "rack-involute", profile)
    solids = rotor_shapes(rotors)
    assert set(solids) == {"male", "female"}
    # valid (OpenCASCADE's BRepCheck) exactly where the outline does not cross itself (shapely): the default
    # roundings make the generated flanks reverse near the tips (the rack undercuts both rotors), and the
    # solids swept through the loops are not valid
    looping = {side.value for side, *_ in outline_loops(rotors, 1e-5)}
    assert looping == ({"male", "female"} if not profile else set())
    for name, solid in solids.items():
        assert isinstance(solid, TopoDS_Solid)
        assert BRepCheck_Analyzer(solid).IsValid() == (name not in looping)
        outline = (rotors.male_outline if name == "male" else rotors.female_outline)(1e-5).points
        volume, centre = _props(solid)
        assert volume == pytest.approx(shapely.Polygon(outline).area * 20.0, rel=1e-5)
        assert centre[0] == pytest.approx(0.0 if name == "male" else 116.0, abs=1.0)  # placed about its axis


def test_housing_as_solids(short_pair):
    solids = housing_shapes(short_pair, 0.1)
    r1, r2 = 63.1, 71.1
    bores = shapely.Point(0, 0).buffer(r1, quad_segs=4096).union(shapely.Point(116.0, 0).buffer(r2, quad_segs=4096))
    assert _props(solids["bores"])[0] == pytest.approx(bores.area * 20.0, rel=1e-6)
    block = shapely.box(-r1 - 10.0, -(r2 + 10.0), 116.0 + r2 + 10.0, r2 + 10.0)  # the housing's wall of 10 mm
    assert _props(solids["housing"])[0] == pytest.approx((block.area - bores.area) * 20.0, rel=1e-6)

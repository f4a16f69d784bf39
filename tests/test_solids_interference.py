"""Helical solids (manifold3d) and interference: volumes against shapely areas, slices against the
turned section, 2D-section integral against 3D booleans."""

from __future__ import annotations

import numpy as np
import pytest
import shapely
import trimesh
from shapely import affinity

from rotorcad.interference import interference_2d, intersection_3d, touching_threshold
from rotorcad.rotor_families import build_family
from rotorcad.rotor_pair import RotorPair
from rotorcad.solids import helical_solid, layers_for

CLEAN = {"tip_rounding": 1.4, "root_rounding": 1.0, "lobe_width": 0.6}
# a short pair keeps the 3D booleans fast; the geometry per section is the full 5/6 pair
PAIR = RotorPair(5, 6, 116.0, 63.0, 45.0, 71.0, 53.0, lead=300.0, length=40.0)


@pytest.fixture(scope="module")
def rotors():
    return build_family(PAIR, "rack-involute", CLEAN)


@pytest.mark.parametrize("hand", [1.0, -1.0])
def test_solid_volume_watertight_genus_and_twist(rotors, hand):
    tol = 0.02
    section = rotors.section("male", tol / 2)
    solid = helical_solid(section, hand * PAIR.lead, PAIR.length, tol)
    mesh = solid.mesh
    assert mesh.is_watertight and mesh.is_winding_consistent and solid.genus == 0
    assert mesh.volume > 0  # outward normals
    # volume = shapely area x length within the stated tessellation bound
    assert abs(solid.volume - section.area * PAIR.length) <= solid.volume_bound
    assert trimesh.Trimesh(mesh.vertices, mesh.faces).volume == pytest.approx(solid.volume, rel=1e-12)
    # the slice at height z is the section turned by 2 pi z / h (counter-clockwise for right hand)
    for z in (7.3, 25.0):
        expected = affinity.rotate(section, hand * 2 * np.pi * z / PAIR.lead, origin=(0, 0), use_radians=True)
        slice_ = solid.section_at(z)
        assert slice_.symmetric_difference(expected).area / expected.exterior.length < tol
        wrong = affinity.rotate(section, -hand * 2 * np.pi * z / PAIR.lead, origin=(0, 0), use_radians=True)
        assert slice_.symmetric_difference(wrong).area / expected.exterior.length > 10 * tol


def test_layer_count_follows_the_sag_formula():
    # measured 63 um at 50 layers and 4 um at 200 for R = 48 mm, 300 deg:
    # R dtheta^2 / 8 gives 66 um and 4.1 um; layers_for keeps it at tol / 2.
    wrap = np.radians(300.0)
    for tol in (0.1, 0.005):
        n = layers_for(tol, wrap, 48.0)
        assert 48.0 * (wrap / n) ** 2 / 8 <= tol / 2 < 48.0 * (wrap / (n - 1)) ** 2 / 8


def test_conjugate_pair_touches_and_errors_interfere(rotors):
    # Issue 5: a conjugate pair has no interference beyond the touching threshold at any angle; the
    # female 1 deg off its phase, or the male scaled by 1 %, interferes clearly.
    tol = 0.01
    male, female = rotors.section("male", tol / 2), rotors.section("female", tol / 2)
    ok = interference_2d(PAIR, male, female, 36, tol)
    assert ok.max_volume < ok.threshold and not ok.interferes and ok.housing_volume < 1e-6 * ok.threshold
    assert ok.threshold == pytest.approx(touching_threshold(PAIR, tol))
    off = interference_2d(PAIR, male, female, 36, tol, female_phase=np.radians(1.0))
    big = interference_2d(PAIR, affinity.scale(male, 1.01, 1.01, origin=(0, 0)), female, 36, tol)
    assert off.max_volume > 10 * ok.threshold and big.max_volume > 10 * ok.threshold
    assert big.housing_volume > 0  # a 1 % larger male leaves its bore


def test_2d_and_3d_methods_agree(rotors):
    # The integral of 2D section intersections along the helix against manifold3d's 3D boolean,
    # at the angle of the maximum of a clearly interfering pair (1 % scaled male), 5 um tessellation.
    tol = 0.005
    male = affinity.scale(rotors.section("male", tol / 2), 1.01, 1.01, origin=(0, 0))
    female = rotors.section("female", tol / 2)
    result = interference_2d(PAIR, male, female, 24, tol)
    m = helical_solid(male, PAIR.lead, PAIR.length, tol)
    f = helical_solid(female, -PAIR.female_lead, PAIR.length, tol)
    three = intersection_3d(PAIR, m, f, result.angle_of_max, result.threshold)
    assert three["volume"] == pytest.approx(result.max_volume, rel=0.01)
    # where it is: inside both bores' overlap, within the rotor length
    lo, hi = np.array(three["bbox"][0]), np.array(three["bbox"][1])
    assert 0.0 <= lo[2] <= hi[2] <= PAIR.length + 1e-9
    assert PAIR.center_distance - PAIR.female_tip_radius - 1.0 < three["centroid"][0] < PAIR.male_tip_radius + 1.0
    # its mass centroid against the transverse slices (shapely, no solid): at height z the pair stands
    # at male angle theta + 2 pi z / h1; volume and first moments by the midpoint rule over 400 slices
    dz = PAIR.length / 400
    volume, moment = 0.0, np.zeros(3)
    for z in (np.arange(400) + 0.5) * dz:
        phi = result.angle_of_max + 2 * np.pi * z / PAIR.lead
        m2 = affinity.rotate(male, phi, origin=(0, 0), use_radians=True)
        f2 = affinity.rotate(female, -phi * PAIR.male_teeth / PAIR.female_teeth, origin=(0, 0), use_radians=True)
        cut = m2.intersection(affinity.translate(f2, PAIR.center_distance, 0.0))
        if cut.area > 0:
            volume += cut.area * dz
            moment += cut.area * dz * np.array([cut.centroid.x, cut.centroid.y, z])
    assert volume == pytest.approx(three["volume"], rel=0.01)
    # the 3D centroid is of the larger parts only: here a 0.7 mm3 part at z = 38.6 mm is left out,
    # which moves the whole volume's centroid by 0.08 mm in z; the swept solids' own discretisation
    # (0.7 % in volume) moves x by 0.05 mm. The bounding-box centre it replaced was 4.4 mm off in z.
    np.testing.assert_allclose(three["centroid"], moment / volume, atol=0.15)


def test_section_area_table_is_periodic(rotors):
    # A(theta) repeats every male lobe pitch: the table's integral invariance checks the wrap logic.
    tol = 0.02
    male = affinity.scale(rotors.section("male", tol / 2), 1.01, 1.01, origin=(0, 0))
    female = rotors.section("female", tol / 2)
    from rotorcad.interference import section_overlap_areas

    pitch = 2 * np.pi / 5
    th = np.linspace(0.0, pitch, 7)[:-1]
    # equal up to the sampling of the sections (the patterned lobes are exact copies; GEOS rounds)
    np.testing.assert_allclose(
        section_overlap_areas(PAIR, male, female, th), section_overlap_areas(PAIR, male, female, th + pitch), rtol=1e-3, atol=1e-6
    )
    assert isinstance(male, shapely.Polygon)


def test_housing_block_and_bores():
    # Bores: two cylinders of radii r1 + c and r2 + c about O1, O2; their union's volume follows from
    # the lens of two intersecting circles (closed form); the block minus the bores holds the rest.
    from rotorcad.solids import housing_solids

    a, r1, r2, length = 116.0, 63.05, 71.05, 50.0
    block, bores = housing_solids(a, r1, r2, length, wall=10.0, segments=4096)
    d1 = (a * a + r1 * r1 - r2 * r2) / (2 * a)
    d2 = a - d1
    lens = (
        r1 * r1 * np.arccos(d1 / r1)
        - d1 * np.sqrt(r1 * r1 - d1 * d1)
        + r2 * r2 * np.arccos(d2 / r2)
        - d2 * np.sqrt(r2 * r2 - d2 * d2)
    )
    union_area = np.pi * (r1 * r1 + r2 * r2) - lens
    assert bores.volume() == pytest.approx(union_area * length, rel=1e-5)
    box = (a + r1 + r2 + 20.0) * 2 * (max(r1, r2) + 10.0) * length
    assert block.volume() == pytest.approx(box - bores.volume(), rel=1e-9)
    assert block.genus() == 1 and bores.genus() == 0  # the block has the bore as one through hole


def test_helical_gear_solid():
    # A helical gear of lead 2 pi r / tan(beta): volume = outline area x face width within the bound.
    from rotorcad.gear import InvoluteGear
    from rotorcad.solids import helical_gear_solid

    g = InvoluteGear(20, 2.0, 20 * np.pi / 180, 15 * np.pi / 180)
    outline = g.outline(1e-3).points
    s = helical_gear_solid(outline, g.pitch_radius, g.helix_angle, 20.0, 0.005)
    assert s.genus == 0 and abs(s.volume - shapely.Polygon(outline).area * 20.0) <= s.volume_bound
    assert s.lead == pytest.approx(2 * np.pi * g.pitch_radius / np.tan(g.helix_angle))
    spur = helical_gear_solid(outline, g.pitch_radius, 0.0, 20.0, 0.005)
    assert spur.volume == pytest.approx(shapely.Polygon(outline).area * 20.0, rel=1e-9)

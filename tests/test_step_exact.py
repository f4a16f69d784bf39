"""Exact STEP of helical rotors (exports.step_exact), read back by OpenCASCADE's STEP reader (a
third-party reader): one valid solid, one side face per profile segment, the volume of section
area x length (Gauss-Kronrod integration, measured), and points sampled on every face, turned
back by -2 pi z / h, on the exact section within the tolerance, at the sharp corners too (the
tip radius is not exceeded: a single B-spline through the section overshot it by 44 um)."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
import shapely

from exports.step import read_step
from exports.step_exact import SectionSegment, StepDeviationError, faces, helicoid_deviation, section_segments, write_exact_step
from rotorcad.design import load_rotor_design
from rotorcad.rotor_families import build_family
from rotorcad.rotor_pair import RotorPair

SAMPLES = Path(__file__).resolve().parents[1] / "samples"


def _read_shape(path: Path):
    from OCP.STEPControl import STEPControl_Reader

    reader = STEPControl_Reader()
    reader.ReadFile(str(path))
    reader.TransferRoots()
    return reader.OneShape()


@pytest.mark.parametrize("sample", ["rack_involute_5_6", "srm_asymmetric_5_6"])
@pytest.mark.parametrize("rotor", ["male", "female"])
def test_exact_step_is_the_helicoid_to_the_micrometre(tmp_path, sample, rotor):
    d = load_rotor_design(SAMPLES / f"{sample}.toml")
    pair = RotorPair(**d["pair"])
    rotors = build_family(pair, d["family"], d["params"])
    outline = rotors.male_outline(1e-3) if rotor == "male" else rotors.female_outline(1e-3)
    exact = (rotors.male_outline(1e-5) if rotor == "male" else rotors.female_outline(1e-5)).points
    lead = pair.lead if rotor == "male" else -pair.female_lead  # the female turns the other way
    segments = [SectionSegment(s.name, s.points, s.tangents) for s in outline.segments]
    path = tmp_path / f"{rotor}.step"
    write_exact_step(path, segments, lead, pair.length, 1e-3, rotor)
    info = read_step(path)
    assert info["solids"] == 1 and info["valid"]
    assert info["volume"] == pytest.approx(shapely.Polygon(exact).area * pair.length, rel=1e-5)
    shape = _read_shape(path)
    assert len(faces(shape)) == len(segments) + 2  # one side face a segment, two end caps
    assert helicoid_deviation(shape, exact, lead, pair.length, per_face=12) < 1e-3


def test_a_curve_of_two_samples_is_their_hermite_cubic_not_the_chord():
    # A piece sampled in closed form may keep only its two ends (a short arc within the chord
    # tolerance). Its edge is the cubic through them with their exact unit tangents on chord-length
    # parameters: on a circle of radius R over an angle theta its middle lies R theta^4 / 128 inside
    # the circle (the handles fall short of the optimal (4 R / 3) tan(theta / 4) by R theta^3 / 48,
    # de Boor ch. IV), far inside the chord's sagitta R theta^2 / 8 it was drawn as before.
    from OCP.BRepAdaptor import BRepAdaptor_Curve

    from exports.step_exact import _edge

    radius, theta = 46.5, 0.06
    ends = np.array([0.0, theta])
    seg = SectionSegment("root arc", radius * np.c_[np.cos(ends), np.sin(ends)], np.c_[-np.sin(ends), np.cos(ends)], "curve")
    curve = BRepAdaptor_Curve(_edge(seg, 1e-3))
    u0, u1 = curve.FirstParameter(), curve.LastParameter()
    xy = np.array([(p.X(), p.Y()) for p in (curve.Value(u) for u in np.linspace(u0, u1, 101))])
    off = np.abs(np.hypot(*xy.T) - radius).max()
    assert off == pytest.approx(radius * theta**4 / 128, rel=1e-2)
    assert off < 1e-3 * radius * (1 - np.cos(theta / 2))
    # an arc of two samples is the circle through them tangent to the first one's tangent
    arc = BRepAdaptor_Curve(_edge(SectionSegment("root arc", seg.points, seg.tangents, "arc", (0.0, 0.0)), 1e-3))
    xy = np.array([(p.X(), p.Y()) for p in (arc.Value(u) for u in np.linspace(arc.FirstParameter(), arc.LastParameter(), 101))])
    assert np.abs(np.hypot(*xy.T) - radius).max() < 1e-9 and np.abs(xy[[0, -1]] - seg.points).max() < 1e-9


@pytest.fixture(scope="module")
def involute_to_its_cusp():
    # the README pair: the female's sealing involute runs down to its base circle (the cusp)
    d = load_rotor_design(SAMPLES / "rack_involute_5_6.toml")
    pair = RotorPair(**{**d["pair"], "length": 30.0})
    rotors = build_family(pair, d["family"], d["params"])
    return pair, rotors.female_outline(1e-2), rotors.female_outline(1e-5).points


def test_samples_are_added_where_the_hermite_cubic_leaves_the_curve(involute_to_its_cusp):
    # At 10 um in chord the last interval before the involute's cusp (radius of curvature -> 0) is
    # bridged by a cubic 1.8 um off the curve; with the STEP tolerance of 1 um, section_segments adds
    # samples until every cubic is within a quarter of it. Reference: the exact outline sampled by
    # chords of 0.01 um, against the cubics as OpenCASCADE makes them (read back from the edges).
    from OCP.BRepAdaptor import BRepAdaptor_Curve

    from exports.step_exact import _edge
    from rotorcad.geometry import distance_to_polyline

    _, outline, exact = involute_to_its_cusp
    ring = np.vstack([exact, exact[:1]])

    def largest_gap(segments):
        gaps = []
        for seg in segments:
            if seg.kind != "curve":
                continue
            curve = BRepAdaptor_Curve(_edge(seg, 1e-3))
            u0, u1 = curve.FirstParameter(), curve.LastParameter()
            xy = np.array([(p.X(), p.Y()) for p in (curve.Value(u) for u in np.linspace(u0, u1, 40 * len(seg.points)))])
            gaps.append(distance_to_polyline(xy, ring).max())
        return max(gaps)

    flank = [i for i, s in enumerate(outline.segments[:9]) if s.name == "sealing flank"]
    assert largest_gap([section_segments(outline)[i] for i in flank]) > 1e-3  # the chord tolerance alone
    assert largest_gap([section_segments(outline, 0.0, 1e-3)[i] for i in flank]) < 0.25e-3


def test_the_face_check_looks_between_the_samples(tmp_path, involute_to_its_cusp):
    # The check samples every knot span's middle, where a cubic between two samples errs most: it
    # refuses the female swept from the 10 um samples as they were (1.8 um off) and passes it with
    # the samples section_segments adds. Reference: the exact section (0.01 um chords).
    pair, outline, exact = involute_to_its_cusp
    lead = -pair.female_lead
    with pytest.raises(StepDeviationError, match="um from the helicoid"):
        write_exact_step(tmp_path / "a.step", section_segments(outline), lead, pair.length, 1e-3, "female", exact=exact)
    refined = section_segments(outline, 0.0, 1e-3)
    done = write_exact_step(tmp_path / "b.step", refined, lead, pair.length, 1e-3, "female", exact=exact)
    assert done["deviation"] < 0.5e-3


def _brute_force_distance(points: np.ndarray, polyline: np.ndarray) -> np.ndarray:
    """Distance of every point to every segment of the polyline, the least kept (numpy, no R-tree)."""
    a, b = polyline[:-1], polyline[1:]
    d = b - a
    w = points[:, None, :] - a[None]
    foot = np.clip((w * d).sum(axis=2) / np.maximum((d * d).sum(axis=1), 1e-300), 0.0, 1.0)
    return np.hypot(*(w - foot[..., None] * d).transpose(2, 0, 1)).min(axis=1)


@pytest.mark.parametrize("shape", ["star", "hooked", "off-axis"])
def test_the_farthest_point_is_the_r_tree_s_farthest_bit_for_bit(shape):
    # reference: the R-tree query of every point (rotorcad.geometry.distance_to_polyline, GEOS),
    # and brute force over every segment; the pruned search must return the R-tree's maximum
    # itself, also where the polar-angle bound is poor (a hooked curve, not star-shaped about the
    # origin, and a section away from the origin: there the farthest point is not among the
    # largest bounds, and is found by the second pass)
    from exports.step_exact import FIRST_MEASURED, _distance_bound, farthest_distance
    from rotorcad.geometry import distance_to_polyline

    rng = np.random.default_rng(7)
    t = np.linspace(0.0, 2 * np.pi, 1001)
    r = 40.0 + 3.0 * np.cos(6 * t)
    if shape == "hooked":  # the angle runs back and forth: a curve no ray from the origin crosses once
        t = t + 0.6 * np.sin(12 * t)
    ring = np.column_stack([r * np.cos(t), r * np.sin(t)])
    if shape == "off-axis":
        ring = ring + [55.0, -20.0]
    k = rng.integers(0, len(ring) - 1, 4000)
    f = rng.random(4000)[:, None]
    points = ring[k] + f * (ring[k + 1] - ring[k]) + rng.normal(0.0, 1e-4, (4000, 2))  # near the curve, as face samples are
    far = int(np.argmin(np.abs(np.arctan2(*points[:, ::-1].T) - 0.05)))  # one point 2 um off, near angle 0.05
    a, b = ring[k[far]], ring[k[far] + 1]
    points[far] = a + f[far] * (b - a) + 2e-3 * np.array([b[1] - a[1], a[0] - b[0]]) / np.hypot(*(b - a))
    full = distance_to_polyline(points, ring)
    bound = _distance_bound(points, ring)
    assert np.all(bound >= full - 1e-12)  # an upper bound of every point's distance
    assert int(np.argmax(full)) == far
    if shape != "star":
        assert far not in np.argsort(bound)[-FIRST_MEASURED:]  # found by the second pass
    assert farthest_distance(points, ring) == float(full.max())
    assert float(full.max()) == pytest.approx(float(_brute_force_distance(points, ring).max()), abs=1e-12)


@pytest.mark.parametrize("clockwise", [False, True])
@pytest.mark.parametrize("hand", [1.0, -1.0])
def test_the_capped_solid_is_opencascade_s_own_make_solid(clockwise, hand):
    # reference: OpenCASCADE's BRepOffsetAPI_MakePipeShell.MakeSolid (end faces, then a point at
    # infinity classified against the solid to turn it outward) on the same sweep; helical_solid
    # closes the shell itself and reads the outward side off the end at z = 0. A clockwise section
    # sweeps an inside-out shell, which must be turned: the same positive volume (Gauss-Kronrod),
    # valid (BRepCheck), one face a segment and two ends.
    from OCP.BRepCheck import BRepCheck_Analyzer
    from OCP.BRepGProp import BRepGProp
    from OCP.GProp import GProp_GProps

    import exports.step_exact as step_exact

    d = load_rotor_design(SAMPLES / "rack_involute_5_6.toml")
    pair = RotorPair(**d["pair"])
    rotors = build_family(pair, d["family"], d["params"])
    outline = rotors.male_outline(1e-2)
    segments = [SectionSegment(s.name, s.points, s.tangents) for s in outline.segments]
    if clockwise:
        segments = [SectionSegment(s.name, s.points[::-1], -s.tangents[::-1]) for s in segments[::-1]]

    def volume(shape) -> float:
        props = GProp_GProps()
        BRepGProp.VolumePropertiesGK_s(shape, props, 1e-9, False, True)
        return float(props.Mass())

    ours = step_exact.helical_solid(segments, hand * pair.lead, pair.length, 1e-3)
    made = step_exact._capped_solid  # the reference: the same sweep closed by OpenCASCADE
    try:
        step_exact._capped_solid = lambda pipe: None
        theirs = step_exact.helical_solid(segments, hand * pair.lead, pair.length, 1e-3)
    finally:
        step_exact._capped_solid = made
    area = shapely.Polygon(rotors.male_outline(1e-5).points).area
    assert volume(theirs) == pytest.approx(area * pair.length, rel=1e-4)  # the reference is outward
    assert volume(ours) == pytest.approx(volume(theirs), rel=1e-9)
    assert BRepCheck_Analyzer(ours).IsValid() and len(faces(ours)) == len(segments) + 2

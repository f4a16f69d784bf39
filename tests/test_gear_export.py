"""Gear solids from the command line (`rotorcad export GEAR.toml`): the gear and its mate as meshes
and exact STEP. References: section area x face width (shapely), a watertight mesh (trimesh), and
the tooth thickness at the pitch cylinder of a plane cut through the STEP solid (OpenCASCADE reads
the file back; its faces' curves in the plane, :func:`_section_of_step`) against ISO 21771:
s = m (pi / 2 + 2 x tan(alpha)) for a spur gear."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest
import shapely

from exports.meshes import read_mesh
from exports.step import read_step
from rotorcad.cli.main import main

SAMPLES = Path(__file__).resolve().parents[1] / "samples"


def _section_of_step(path: Path, z: float) -> shapely.Polygon:
    """The STEP solid cut by the plane at height z, as a polygon (its curves sampled to 0.01 um).

    A spur gear's faces are planes normal to the axis (the end faces) and surfaces ruled along it:
    extrusions along z (the teeth's flanks, fillets and chamfers) and cylinders about it (root, tip,
    bore), each asserted so as OpenCASCADE reads it from the file. Such a face meets the plane z in its
    iso-curve at the parameter v of that height, over the face's u range: that curve is the plane cut
    OpenCASCADE's boolean section (BRepAlgoAPI_Section, 2-3.5 s of CPU a file) finds, in a tenth of
    the time. Every piece must close into rings with the others (no dangle, no cut edge: a face
    whose u range overran its trimming would leave one)."""
    from OCP.BRep import BRep_Tool
    from OCP.BRepAdaptor import BRepAdaptor_Surface
    from OCP.BRepTools import BRepTools
    from OCP.GCPnts import GCPnts_QuasiUniformDeflection
    from OCP.GeomAbs import GeomAbs_Cylinder, GeomAbs_Plane, GeomAbs_SurfaceOfExtrusion
    from OCP.GeomAdaptor import GeomAdaptor_Curve
    from OCP.STEPControl import STEPControl_Reader
    from OCP.TopAbs import TopAbs_FACE
    from OCP.TopExp import TopExp_Explorer
    from OCP.TopLoc import TopLoc_Location
    from OCP.TopoDS import TopoDS

    reader = STEPControl_Reader()
    reader.ReadFile(str(path))
    reader.TransferRoots()
    explorer = TopExp_Explorer(reader.OneShape(), TopAbs_FACE)
    lines = []
    while explorer.More():
        face = TopoDS.Face(explorer.Current())
        explorer.Next()
        surface = BRepAdaptor_Surface(face)
        kind = surface.GetType()
        if kind == GeomAbs_Plane:
            axis = surface.Plane().Axis().Direction()
        elif kind == GeomAbs_SurfaceOfExtrusion:
            axis = surface.Direction()
        else:
            assert kind == GeomAbs_Cylinder, kind
            axis = surface.Cylinder().Axis().Direction()
        assert abs(abs(axis.Z()) - 1.0) < 1e-12, (kind, axis.X(), axis.Y())  # normal to the plane, or ruled along z
        u0, u1, v0, v1 = BRepTools.UVBounds_s(face)
        z0, z1 = surface.Value(u0, v0).Z(), surface.Value(u0, v1).Z()
        if kind == GeomAbs_Plane or not min(z0, z1) < z < max(z0, z1):
            assert kind != GeomAbs_Plane or abs(z0 - z) > 1e-6  # an end face, not in the cutting plane
            continue
        location = TopLoc_Location()
        curve = BRep_Tool.Surface_s(face, location).VIso(v0 + (z - z0) / (z1 - z0) * (v1 - v0))  # z linear in v
        assert location.IsIdentity()
        sampler = GCPnts_QuasiUniformDeflection(GeomAdaptor_Curve(curve, u0, u1), 1e-5)
        lines.append(shapely.LineString([(sampler.Value(i).X(), sampler.Value(i).Y()) for i in range(1, sampler.NbPoints() + 1)]))
    # the pieces' ends meet within OpenCASCADE's tolerance: snap them to 1 nm before joining
    rings, cuts, dangles, invalid = shapely.polygonize_full(shapely.set_precision(lines, 1e-6))
    assert shapely.is_empty(cuts) and shapely.is_empty(dangles) and shapely.is_empty(invalid)
    return max(shapely.get_parts(rings), key=lambda p: p.area)


def test_a_spur_gear_pair_from_the_command_line(tmp_path, capsys):
    capsys.readouterr()
    out = tmp_path / "o"
    assert main(["export", str(SAMPLES / "gear_pair.toml"), "--out", str(out), "--format", "stl,step", "--json"]) == 0
    files = json.loads(capsys.readouterr().out)["files"]
    assert sorted(Path(f["path"]).name for f in files) == sorted(p.name for p in out.iterdir())
    assert {f["body"] for f in files} == {"gear", "mate"}
    width = 10 * 3.0  # the sample has no face_width: ten modules
    sections = {}  # each STEP file's mid-width section, cut once (OpenCASCADE) and used twice
    for f in files:
        if f["format"] == "stl":
            mesh = read_mesh(Path(f["path"]), "stl")
            assert mesh.is_watertight and mesh.volume == pytest.approx(f["volume"], rel=1e-5)
        else:
            info = read_step(Path(f["path"]))
            assert info["solids"] == 1 and info["valid"] and f["tolerance"] <= 1e-3
            assert info["volume"] == pytest.approx(f["volume"], rel=1e-5)  # area x face width
            section = sections[f["body"]] = _section_of_step(Path(f["path"]), width / 2)
            assert section.area * width == pytest.approx(info["volume"], rel=1e-5)
    # ISO 21771 tooth thickness at the pitch circle of the gear (z = 17, m = 3, x = 0.3, 20 deg)
    step = next(f for f in files if f["format"] == "step" and f["body"] == "gear")
    section = sections[step["body"]]
    r = 17 * 3.0 / 2
    circle = shapely.LineString(r * np.column_stack([np.cos(t := np.linspace(0, 2 * np.pi, 400_001)), np.sin(t)]))
    arcs = [g.length for g in shapely.get_parts(circle.intersection(section)) if g.length > 1.0]
    expected = 3.0 * (np.pi / 2 + 2 * 0.3 * np.tan(np.radians(20.0)))
    whole = [a for a in arcs if a > 0.75 * expected]  # the tooth across the circle's seam comes in two halves
    assert len(whole) >= 16
    np.testing.assert_allclose(whole, expected, atol=1e-3)  # measured: within 1 nm


def test_a_bad_gear_export_leaves_no_folder(tmp_path, capsys):
    out = tmp_path / "o"
    capsys.readouterr()
    assert main(["export", str(SAMPLES / "gear_pair.toml"), "--out", str(out), "--format", "iges"]) == 2
    err = capsys.readouterr().err.strip()
    assert "--format" in err and len(err.splitlines()) == 1 and not out.exists()

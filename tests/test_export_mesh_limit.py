"""The memory bound of ``rotorcad export`` counts only the formats that make meshes.

A new user's finding: ``export samples/rack_involute_5_6.toml --format step --tolerance 0.001`` was
refused for "10.7 million triangles", though the exact STEP holds no triangles (its surfaces follow
the helicoid to min(tolerance, 1 um) whatever the mesh tolerance). The bound and its reason stay for
a mesh at that tolerance.
"""

from __future__ import annotations

from pathlib import Path

import pytest

from exports.formats import makes_meshes, table
from rotorcad.cli.common import InputError
from rotorcad.cli.export_cmd import _design_settings, _read_design, _rotor_bodies

SAMPLE = Path(__file__).resolve().parents[1] / "samples" / "rack_involute_5_6.toml"
FINE = 0.001  # mm: the new user's --tolerance, below the 0.0028 mm a mesh of this design needs


def bodies(formats: list[str]) -> list:
    settings = _design_settings(SAMPLE, _read_design(SAMPLE))
    fmts = [table()[f] for f in formats]
    return _rotor_bodies(SAMPLE, settings, (FINE, fmts), "--tolerance", 0.0, (None, 0.0, None), {})


@pytest.mark.parametrize("formats", [["step"], ["step", "dxf", "csv"]])
def test_exact_formats_not_refused_for_triangles(formats):
    """The exact STEP, the drawing and the points: no mesh, so no triangle bound (was refused)."""
    assert not makes_meshes(table()[f] for f in formats)
    assert {b.name for b in bodies(formats)} >= {"male", "female"}


@pytest.mark.parametrize("formats", [["step", "stl"], ["step-faceted"]])
def test_mesh_formats_still_refused_with_the_reason(formats):
    """A mesh at that tolerance: still refused, naming the tolerance that fits and the triangles."""
    assert makes_meshes(table()[f] for f in formats)
    with pytest.raises(InputError) as refused:
        bodies(formats)
    text = str(refused.value)
    assert text.startswith("--tolerance must be at least")
    assert "million triangles" in text and "fit in memory" in text


def test_every_mesh_writer_declares_it():
    """Every format whose writer triangulates the solid says so (the default for a new row)."""
    meshing = {"stl", "stl-ascii", "3mf", "obj", "ply", "glb", "vtu", "xdmf", "dxf-mesh", "dxf-mesh-r12", "step-faceted"}
    rows = table()
    assert {name for name, fmt in rows.items() if fmt.meshes} == meshing & set(rows)

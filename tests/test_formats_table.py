"""The export format table (exports/formats.py, issue 25 item 3): adding a format is one writer, one row, one test.

The toy format is built exactly as README.md's developer section says: its code block is read from
README.md and run as printed, then ``rotorcad export --format off`` runs in process and the files
are read back by trimesh's own OFF reader (an independent reader). References: the volume of a
spur gear's solid is its transverse section's area (shapely) times the face width; the mate's axis
is at the working centre distance of ISO 21771 (inv alpha_w = inv alpha + 2 tan alpha (x1 + x2) /
(z1 + z2), a_w = a cos alpha / cos alpha_w).
"""

from __future__ import annotations

import json
import re
from pathlib import Path

import numpy as np
import pytest
import trimesh

from exports.formats import ExportFormat, names, register, table, unregister
from rotorcad.assembly import BodyKind
from rotorcad.cli.main import main

ROOT = Path(__file__).resolve().parents[1]
GEAR_PAIR = ROOT / "samples" / "gear_pair.toml"


def readme_example() -> str:
    """Return the python block of README.md's section on adding an export format."""
    text = (ROOT / "README.md").read_text(encoding="utf-8")
    section = text.split("## For developers: adding an export format", 1)[1]
    return re.search(r"```python\n(.*?)```", section, re.S).group(1)


@pytest.fixture
def toy_format():
    """Register the README's OFF format as printed, and remove it afterwards."""
    assert "off" not in table()
    exec(compile(readme_example(), "README.md", "exec"), {})
    yield table()["off"]
    unregister("off")


def run(capsys, *args) -> tuple[int, str, str]:
    status = main([str(a) for a in args])
    out, err = capsys.readouterr()
    return status, out, err


def working_center_distance(z1: int, z2: int, m: float, x1: float, x2: float, alpha_deg: float = 20.0) -> float:
    """ISO 21771 working centre distance of a spur pair without backlash (Newton on the involute function)."""
    alpha = np.radians(alpha_deg)
    target = np.tan(alpha) - alpha + 2 * np.tan(alpha) * (x1 + x2) / (z1 + z2)
    aw = alpha
    for _ in range(50):
        aw -= (np.tan(aw) - aw - target) / np.tan(aw) ** 2  # d inv / d alpha = tan^2
    return m * (z1 + z2) / 2 * np.cos(alpha) / np.cos(aw)


def test_toy_format_from_the_readme_writes_each_body_in_place(capsys, tmp_path, toy_format):
    """The README's OFF format, registered as printed, is written by `rotorcad export` and read back by trimesh."""
    out = tmp_path / "o"
    argv = ["export", GEAR_PAIR, "--format", "off", "--tolerance", "0.01", "--out", out, "--json", "--quiet"]
    status, text, err = run(capsys, *argv)
    assert status == 0, err
    rows = {r["body"]: r for r in json.loads(text)["files"]}
    assert sorted(rows) == ["gear", "mate"]
    width = 10 * 3.0  # face width: ten modules when not given (CONTRACT.md)
    for body, row in rows.items():
        path = Path(row["path"])
        assert path == out / f"gear_pair_{body}.off" and row["format"] == "off"
        mesh = trimesh.load(str(path), file_type="off", force="mesh", process=True)
        mesh.merge_vertices()
        assert mesh.is_watertight and mesh.is_winding_consistent
        assert row["triangles"] == len(mesh.faces) and row["tolerance"] == pytest.approx(0.01)
        assert mesh.volume == pytest.approx(row["volume"], rel=1e-7)
        # spur gear: a prism, its volume the area of its mid-face section (cut by trimesh) times the width
        cut, _ = mesh.section(plane_origin=[0.0, 0.0, width / 2], plane_normal=[0.0, 0.0, 1.0]).to_2D()
        assert mesh.volume == pytest.approx(sum(p.area for p in cut.polygons_full) * width, rel=1e-9)
    # the mate's axis at the working centre distance: its centre of mass (a mate of 29 equal teeth)
    aw = working_center_distance(17, 29, 3.0, 0.3, -0.1)
    mate = trimesh.load(str(rows["mate"]["path"]), file_type="off", force="mesh")
    np.testing.assert_allclose(mate.center_mass, [aw, 0.0, width / 2], atol=1e-3)
    gear = trimesh.load(str(rows["gear"]["path"]), file_type="off", force="mesh")
    np.testing.assert_allclose(gear.center_mass, [0.0, 0.0, width / 2], atol=1e-3)


def test_every_row_has_its_own_name_and_file_ending():
    """Two rows with one name or one ending would write one file twice."""
    rows = list(table().values())
    # the order of the formats in --help and in the refusals, as before the table (CONTRACT.md's messages)
    assert names() == (
        *("stl", "stl-ascii", "3mf", "obj", "ply", "glb", "vtu", "xdmf"),
        *("dxf", "dxf-r12", "dxf-mesh", "dxf-mesh-r12", "step", "step-faceted", "csv"),
    )
    assert len({r.name for r in rows}) == len(rows)
    assert len({r.extension for r in rows}) == len(rows)
    assert all(r.name == r.name.lower() and r.tolerance and r.bodies for r in rows)
    taken = rows[0]
    with pytest.raises(ValueError, match="extension"):
        register(ExportFormat("toy-twin", taken.extension, taken.plan, "none"))
    assert "toy-twin" not in table()


def test_format_choices_come_from_the_table(capsys, tmp_path, toy_format):
    """`--help` lists the table's formats, and `--format` accepts exactly the table's (a new row at once)."""
    import click

    from rotorcad.cli.export_cmd import export

    option = next(p for p in export.params if p.name == "formats")
    with click.Context(export) as ctx:
        listed = re.search(r"Comma-separated formats: (.*?)\. Default", option.get_help_record(ctx)[1]).group(1)
    assert tuple(listed.split(", ")) == names() and names()[-1] == "off"
    status, text, _ = run(capsys, "export", "--help")
    assert status == 0 and "Comma-separated formats: stl, stl-ascii" in " ".join(text.split())
    status, _, err = run(capsys, "export", GEAR_PAIR, "--format", "nope", "--out", tmp_path / "o")
    assert status == 2 and not (tmp_path / "o").exists()
    allowed = re.search(r"list of (.*) \(got 'nope'\)", err).group(1)
    assert tuple(allowed.split(", ")) == names(BodyKind.GEAR) and "off" in allowed
    design = ROOT / "samples" / "rack_involute_5_6.toml"
    status, _, err = run(capsys, "export", design, "--format", "stl,nope", "--out", tmp_path / "o")
    assert status == 2 and tuple(re.search(r"list of (.*) \(got 'nope'\)", err).group(1).split(", ")) == names(BodyKind.ROTOR)


def test_background_rows_hand_the_worker_what_it_can_unpickle(tmp_path):
    """A row that says background must give a BackgroundWriter whose function and arguments pickle
    (the worker process receives them by pickle, exports.background); the others write here."""
    import pickle

    from exports.background import BackgroundWriter
    from rotorcad.cli.common import load_toml
    from rotorcad.cli.gear_export import design_gear_bodies

    bodies = design_gear_bodies(GEAR_PAIR, 0.05, load_toml(GEAR_PAIR))
    for fmt in table().values():
        for body in bodies:
            writer = fmt.plan(fmt, body, 0.05, {})
            assert isinstance(writer, BackgroundWriter) == fmt.background, fmt.name
            if fmt.background:
                function, args = pickle.loads(pickle.dumps((writer.function, writer.args)))
                assert function is writer.function and len(args) == len(writer.args)

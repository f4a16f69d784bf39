"""``rotorcad export GEAR.toml``: solids of an involute gear (and its mate in mesh) in every format.

A gear design is a TOML file with a ``[gear]`` table (see ``samples/gear_pair.toml``; the face
width is ``face_width`` in mm, ten modules when not given) and an optional ``[mate]``. The gear is
swept along its helix (lead 2 pi r / tan(beta) at the pitch radius r, right hand for a positive
helix angle; a spur gear is a straight prism), the mate with the opposite hand and its own lead,
placed in mesh at the working centre distance.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

import numpy as np

from exports.formats import names
from rotorcad.assembly import BodyKind, PlacedBody, gear_bodies, gear_lead
from rotorcad.cli.common import InputError, Outputs
from rotorcad.cli.gear import build_gear, make_rack, merge_gear_params, shop_gears
from rotorcad.cli.gear_part import part_features
from rotorcad.design.files import is_gear_design

GEAR_FORMATS = names(BodyKind.GEAR)
"""The formats of the built-in table that write gears (:mod:`exports.formats`)."""


def design_gear_bodies(design: Path, tol: float, data: dict[str, Any] | None = None) -> list[PlacedBody]:
    """Return the gear of a design (and its mate in mesh) as placed bodies (:func:`rotorcad.assembly.gear_bodies`).

    Parameters
    ----------
    design : Path
        The gear design file.
    tol : float, mm
        Surface tolerance; the gears are built to a quarter of it.
    data : dict, optional
        The design's mapping, if read already.

    Raises
    ------
    InputError
        A bad design or face width (``[gear] face_width``, ten modules when not given).
    """
    params = merge_gear_params(design, {}, data)
    width = params.get("face_width")
    if width is None:
        width = 10.0 * float(params["module"])
    if not (np.isfinite(width) and 0 < width <= 1e4):
        raise InputError(f"[gear] face_width must be a length from 0 to 10000 mm (got {width}).")
    if params["internal"]:  # an internal gear ([shaper]): the ring with its outer diameter, and its pinion
        from rotorcad.assembly import internal_gear_bodies
        from rotorcad.cli.gear import SPEC
        from rotorcad.cli.gear_internal import build_internal_gear

        ring, pair = build_internal_gear(params[SPEC], tol / 4)
        return internal_gear_bodies(ring, pair, width, tol)
    g, pair = build_gear(params, tol / 4)
    _, g, pair = shop_gears(params, g, pair)  # cut at the middle of the tooth-thickness tolerance fields
    return gear_bodies(g, pair, width, tol, part_features(params, g))  # with its bore, keyway, hub, ...


def design_rack_files(
    design: Path, fmts: list[str], folder: Path, tol: float, outputs: Outputs, data: dict[str, Any] | None = None
) -> list[dict[str, Any]]:
    """Queue the files of the design's gear rack (``[rack]``, body ``rack``, in its own frame); return their rows.

    A rack is a straight or sheared extrusion, not a helical sweep, so it is not a placed body of
    the format table: its meshes come from :func:`rotorcad.gears.rack.rack_solid_mesh`, its exact
    STEP from :func:`exports.step_rack.write_rack_step` (planes and the fillets' cylinders), its
    drawing and points from its outline. Formats without a rack writer (a DXF mesh, a faceted
    STEP) are left out. No ``[rack]``: no files.
    """
    from exports.csv_points import write_points
    from exports.dxf import Drawing, write_dxf
    from exports.formats import table
    from exports.meshes import MESH_FORMATS, write_mesh
    from exports.step_rack import write_rack_step
    from rotorcad.gears.rack import rack_solid_mesh

    params = merge_gear_params(design, {}, data)
    rack = make_rack(params, tol / 4)
    if rack is None:
        return []
    width = params.get("face_width") or 10.0 * float(params["module"])
    rows: list[dict[str, Any]] = []
    for fmt in fmts:
        path = folder / f"{design.stem}_rack{table()[fmt].extension if fmt != 'csv' else '.csv'}"
        row: dict[str, Any] = {"path": str(path), "format": fmt, "body": "rack", "volume": float(rack.section.area * width)}
        if fmt in MESH_FORMATS:
            mesh = rack_solid_mesh(rack, width)
            row.update(triangles=len(mesh.faces), volume=float(mesh.volume), tolerance=rack.tolerance)
            outputs.add(path, lambda p, m=mesh, f=fmt: write_mesh(p, m, f), "--out")
        elif fmt == "dxf":
            d = Drawing(mark_size=rack.module)
            d.outlines.append(("RACK", rack.outline()))
            d.lines.append(("PITCH", (0.0, 0.0), (float(rack.length), 0.0)))
            row.update(triangles=0, tolerance=rack.tolerance)
            outputs.add(path, lambda p, dr=d: write_dxf(p, dr), "--out")
        elif fmt == "csv":
            row.update(triangles=0, tolerance=rack.tolerance)
            outputs.add(path, lambda p: write_points(p, rack.outline()), "--out")
        elif fmt == "step":  # exact: planes and the fillets' cylinders
            row.update(triangles=0, tolerance=0.0, faces=len(rack.pieces()) + 5)

            def write_step(p: Path, r: dict[str, Any] = row) -> None:
                r["faces"] = int(write_rack_step(p, rack, width)["faces"])

            outputs.add(path, write_step, "--out")
        else:
            continue
        rows.append(row)
    return rows


def export_gear(
    design: Path, fmts: list[str], folder: Path, tol: float, data: dict[str, Any] | None = None
) -> list[dict[str, Any]]:
    """Write the gear (and mate) solids in each of ``fmts`` into ``folder``; return the rows (as ``export --json``).

    Kept for callers of the former gear export; ``rotorcad export`` runs the same loop
    (:func:`exports.formats.plan_files`) with the worker process and a progress bar.
    """
    from exports.formats import plan_files, table
    from rotorcad.cli.common import Outputs

    outputs, rows = Outputs(), []
    for path, row, writer in plan_files(
        [table()[f] for f in fmts], design_gear_bodies(design, tol, data), tol, folder, design.stem
    ):
        outputs.add(path, writer, "--out")
        rows.append(row)
    outputs.write()
    for row in rows:
        row["size"] = Path(row["path"]).stat().st_size
        row["replaced"] = Path(row["path"]) in outputs.replaced  # a file that was there, replaced whole
    return rows


__all__ = ["GEAR_FORMATS", "design_gear_bodies", "export_gear", "gear_lead", "is_gear_design"]

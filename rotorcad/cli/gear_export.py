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
import shapely

from exports.csv_points import write_points
from exports.dxf import Drawing, write_dxf
from exports.meshes import MESH_FORMATS, write_mesh
from exports.step_exact import StepDeviationError, section_segments, write_exact_step
from rotorcad.cli.common import InputError, Outputs
from rotorcad.cli.gear import build_gear, make_rack, merge_gear_params, shop_gears
from rotorcad.gear import InvoluteGear
from rotorcad.geometry import rotate
from rotorcad.solids import helical_solid

GEAR_FORMATS = (*MESH_FORMATS, "dxf", "step", "csv")
STEP_TOLERANCE = 1e-3  # mm


def is_gear_design(data: dict[str, Any]) -> bool:
    """Tell whether a design mapping is a gear design (it has a ``[gear]`` table)."""
    return "gear" in data


def gear_lead(g: InvoluteGear) -> float:
    """Return the lead of the gear's helix: 2 pi r / tan(beta) at the pitch radius.

    Parameters
    ----------
    g : InvoluteGear
        The gear.

    Returns
    -------
    float, mm
        Signed lead (> 0 right hand); inf for a spur gear.
    """
    beta = g.helix_angle
    return float("inf") if abs(beta) < 1e-12 else float(2 * np.pi * g.pitch_radius / np.tan(beta))


def export_gear(
    design: Path, fmts: list[str], folder: Path, tol: float, data: dict[str, Any] | None = None
) -> list[dict[str, Any]]:
    """Write the gear (and mate) solids.

    Parameters
    ----------
    design : Path
        The gear design file.
    fmts : list of str
        Formats to write (:data:`GEAR_FORMATS`).
    folder : Path
        Output folder.
    tol : float, mm
        Surface tolerance.
    data : dict, optional
        The design's mapping, if read already.

    Returns
    -------
    list of dict
        The summary rows: path, format, body, volume (mm³), tolerance (mm), triangles or faces.

    Raises
    ------
    InputError
        A bad design or face width.
    """
    params = merge_gear_params(design, {}, data)  # data: the design's mapping, if read already
    width = params.get("face_width")
    if width is None:
        width = 10.0 * float(params["module"])
    if not (np.isfinite(width) and 0 < width <= 1e4):
        raise InputError(f"[gear] face_width must be a length from 0 to 10000 mm (got {width}).")
    g, pair = build_gear(params, tol / 4)
    _, g, pair = shop_gears(params, g, pair)  # cut at the middle of the tooth-thickness tolerance fields
    bodies: dict[str, tuple[InvoluteGear, float, tuple[float, float], float]] = {"gear": (g, gear_lead(g), (0.0, 0.0), 0.0)}
    if pair is not None:
        mate = pair.mate
        lead2 = -gear_lead(g) * mate.teeth / g.teeth if np.isfinite(gear_lead(g)) else float("inf")
        bodies["mate"] = (mate, lead2, (float(pair.working_center_distance), 0.0), np.pi + np.pi / mate.teeth)
    outputs = Outputs()
    rows: list[dict[str, Any]] = []
    for body, (gear, lead, shift, turn) in bodies.items():
        outline = gear.outline(tol / 4)
        section = shapely.Polygon(rotate(outline.points, turn))
        for fmt in fmts:
            path = folder / f"{design.stem}_{body}{_extension(fmt)}"
            row: dict[str, Any] = {"path": str(path), "format": fmt, "body": body, "volume": float(section.area * width)}
            if fmt in MESH_FORMATS:
                solid = helical_solid(section, lead if np.isfinite(lead) else 1e12 * width, width, tol)
                mesh = solid.triangle_mesh.copy()
                mesh.apply_translation([*shift, 0.0])
                row.update(triangles=len(mesh.faces), volume=solid.volume, tolerance=solid.tolerance)
                outputs.add(path, lambda p, m=mesh, f=fmt: write_mesh(p, m, f), "--out")
            elif fmt == "dxf":
                d = Drawing(mark_size=gear.module)
                d.outlines.append((body.upper(), np.asarray(section.exterior.coords)[:-1] + np.array(shift)))
                d.circles.append(("PITCH", shift, gear.pitch_radius))
                row.update(tolerance=tol / 4)
                outputs.add(path, lambda p, dr=d: write_dxf(p, dr), "--out")
            elif fmt == "csv":
                row.update(tolerance=tol / 4)
                outputs.add(path, lambda p, s=section: write_points(p, np.asarray(s.exterior.coords)[:-1]), "--out")
            else:
                step_tol = min(tol, STEP_TOLERANCE)
                exact = rotate(gear.outline(step_tol / 100).points, turn)
                row.update(faces=len(section_segments(gear.outline(10 * step_tol))) + 2)
                row.update(volume=float(shapely.Polygon(exact).area * width))

                def write_step(p: Path, g=gear, ex=exact, ld=lead, b=body, sh=shift, r=row, t=step_tol, tn=turn) -> None:
                    # the B-splines interpolate samples with their exact tangents (Hermite, see
                    # export_cmd): samples at 10 x the tolerance in chord keep a module-3 gear within
                    # 0.1 um, but a large gear's flanks, curved slowly, are sampled so sparsely that the
                    # fit strays (5.3 um at module 100): sampled 10 times finer in chord (a third of the
                    # spacing, error / 100) until the faces are within the tolerance
                    for chord in (10 * t, t, t / 10):
                        try:
                            done = write_exact_step(p, section_segments(g.outline(chord), tn), ld, width, t, b, sh, exact=ex)
                            break
                        except StepDeviationError:
                            if chord == t / 10:
                                raise
                    r["tolerance"] = done["deviation"]

                outputs.add(path, write_step, "--out")
            rows.append(row)
    rack = make_rack(params, tol / 4)
    if rack is not None:  # the gear rack of [rack], in its own frame
        rows += _rack_rows(rack, design, fmts, folder, width, outputs)
    outputs.write()
    for row in rows:
        row["size"] = Path(row["path"]).stat().st_size
        row["replaced"] = Path(row["path"]) in outputs.replaced  # a file that was there, replaced whole
    return rows


def _rack_rows(rack: Any, design: Path, fmts: list[str], folder: Path, width: float, outputs: Outputs) -> list[dict[str, Any]]:
    """Queue the rack's files (body ``rack``) and return their summary rows."""
    from exports.step_rack import write_rack_step
    from rotorcad.gears.rack import rack_solid_mesh

    rows: list[dict[str, Any]] = []
    for fmt in fmts:
        path = folder / f"{design.stem}_rack{_extension(fmt)}"
        row: dict[str, Any] = {"path": str(path), "format": fmt, "body": "rack", "volume": float(rack.section.area * width)}
        if fmt in MESH_FORMATS:
            mesh = rack_solid_mesh(rack, width)
            row.update(triangles=len(mesh.faces), volume=float(mesh.volume), tolerance=rack.tolerance)
            outputs.add(path, lambda p, m=mesh, f=fmt: write_mesh(p, m, f), "--out")
        elif fmt == "dxf":
            d = Drawing(mark_size=rack.module)
            d.outlines.append(("RACK", rack.outline()))
            d.lines.append(("PITCH", (0.0, 0.0), (float(rack.length), 0.0)))
            row.update(tolerance=rack.tolerance)
            outputs.add(path, lambda p, dr=d: write_dxf(p, dr), "--out")
        elif fmt == "csv":
            row.update(tolerance=rack.tolerance)
            outputs.add(path, lambda p: write_points(p, rack.outline()), "--out")
        elif fmt == "step":  # exact: planes and the fillets' cylinders (exports/step_rack.py)
            row.update(tolerance=0.0, faces=len(rack.pieces()) + 5)

            def write_step(p: Path, r: dict[str, Any] = row) -> None:
                r["faces"] = int(write_rack_step(p, rack, width)["faces"])

            outputs.add(path, write_step, "--out")
        else:
            continue
        rows.append(row)
    return rows


def _extension(fmt: str) -> str:
    from exports.meshes import EXTENSIONS

    return EXTENSIONS.get(fmt, {"dxf": ".dxf", "step": ".step", "csv": ".csv"}.get(fmt, ""))


__all__ = ["GEAR_FORMATS", "export_gear", "gear_lead", "is_gear_design"]

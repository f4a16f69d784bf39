"""``rotorcad cut --internal``: shaping simulation of an internal gear against its analytic envelope (CONTRACT.md)."""

from __future__ import annotations

from typing import Any

import numpy as np
import shapely

from exports.csv_points import write_points
from exports.dxf import Drawing, write_dxf
from hob.shaping import simulate_shaping
from rotorcad.cli.common import InputError, Outputs, emit_json, print_table
from rotorcad.cli.gear_internal import build_internal_gear
from rotorcad.cli.progress import Steps
from rotorcad.design.gears import GearSpec
from rotorcad.errors import DesignError


def run_internal_cut(spec: GearSpec, opts: dict[str, Any]) -> None:
    """Shape tooth space 0 of the spec's internal gear (:func:`hob.shaping.simulate_shaping`); print and write.

    Parameters
    ----------
    spec : GearSpec
        The merged spec (``internal``).
    opts : dict
        The options of ``rotorcad cut`` (``tolerance`` the scallop height, ``positions``, ``json``,
        ``dxf``, ``csv``, ``plot``, ``quiet``).
    """
    tol = opts["tolerance"]
    if tol > 0.1 * spec.module:
        raise InputError(f"--tolerance must be at most {0.1 * spec.module:.3g} mm (a tenth of the module; got {tol:g}).")
    if opts.get("plot"):
        raise InputError("--plot must not be given for an internal gear (its cut is drawn by --dxf).")
    ring, _ = build_internal_gear(spec, max(min(tol / 4.0, 1e-4), 1e-7 * spec.module))
    try:
        with Steps("shaping", None, opts["quiet"]):
            res = simulate_shaping(ring, tol, opts["positions"])
    except DesignError as exc:
        label = "--positions" if exc.param == "positions" else "--tolerance"
        raise InputError(exc.sentence(label)) from None
    pitch = shapely.Point(0.0, 0.0).buffer(ring.pitch_radius, quad_segs=4096).exterior.intersection(res.ring)
    arcs = [g for g in getattr(pitch, "geoms", [pitch]) if g.length > 0]
    middle = min(arcs, key=lambda g: abs(np.arctan2(g.centroid.y, g.centroid.x) - np.pi / ring.teeth))
    result: dict[str, Any] = {
        "internal": True,
        "max_deviation_from_envelope": res.max_deviation,
        "flank_deviation_from_envelope": res.flank_deviation,
        "tooth_thickness_pitch": float(middle.length),
        "tooth_thickness_pitch_exact": ring.tooth_thickness(ring.pitch_radius),
        "cutting_center_distance": ring.cutting_center_distance,
        "positions": res.positions,
        "tolerance_met": bool(res.max_deviation <= tol),
    }
    sector = np.asarray(shapely.geometry.polygon.orient(res.ring, 1.0).exterior.coords)[:-1]
    out = Outputs()
    out.add(opts["csv"], lambda p: write_points(p, sector, ["simulated internal gear sector (space 0), shaper cutting"]), "--csv")
    out.add(opts["dxf"], lambda p: write_dxf(p, _drawing(ring, sector)), "--dxf")
    result["files"] = [str(p) for p in out.write()]
    if opts["as_json"]:
        emit_json(result)
    else:
        print_table(f"shaping simulation z2={ring.teeth}, m={ring.module:g} mm, cutter z0={ring.cutter.teeth}", result)


def _drawing(ring: Any, sector: np.ndarray) -> Drawing:
    d = Drawing(mark_size=ring.module)
    d.outlines.append(("GEAR_SIMULATED", sector))
    d.outlines.append(("GEAR_ANALYTIC", ring.outline(1e-3).points))
    d.circles += [("PITCH", (0.0, 0.0), ring.pitch_radius), ("BASE", (0.0, 0.0), ring.base_radius)]
    d.centers.append((0.0, 0.0))
    return d

"""The HTML report's content for an internal gear design ([shaper]): the numbers of ``rotorcad gear``, its picture and files."""

from __future__ import annotations

from pathlib import Path
from typing import Any

from exports.csv_points import write_points
from exports.dxf import write_dxf


def internal_content(design: Path, data: dict[str, Any], figure: Any) -> dict[str, Any]:
    """Collect the numbers, picture and files of an internal gear design, by the code of ``rotorcad gear``.

    Parameters
    ----------
    design : Path
        The design file.
    data : dict
        Its parsed tables (with ``[shaper]``).
    figure : callable
        ``figure(fig, id)``: a matplotlib figure as inline SVG text (the report's).

    Returns
    -------
    dict
        As the report's gear content: ``kind``, ``case``, ``family`` (None), ``result`` (``rotorcad gear
        --json``), ``hob`` (an internal gear is shaped, not hobbed: not hobbable, with that reason),
        ``figures``, ``files``, ``command``.
    """
    from rotorcad.cli import gear as gear_cmd
    from rotorcad.cli.gear_internal import build_internal_gear, internal_result, ring_drawing
    from rotorcad.gears.internal_plotting import plot_internal

    params = gear_cmd.merge_gear_params(design, {}, data)
    ring, pair = build_internal_gear(params[gear_cmd.SPEC], 1e-4)  # gear's default --tolerance
    result = internal_result(ring, pair)
    case = f"internal gear z = {ring.teeth}, m = {ring.module:g} mm, cutter z0 = {ring.cutter.teeth}"
    if pair is not None:
        case += f" with pinion z = {pair.pinion.teeth}"
    hob = {
        "hobbable": False,
        "reasons": [
            "an internal gear is cut by its shaper cutter, not hobbed: the cutting's checks are "
            "cutting_involute_margin and cutting_trochoid_margin_deg (rotorcad cut simulates it)"
        ],
    }
    figures = {
        "gear": (figure(plot_internal(ring, pair), "gear"), "The internal gear (and its pinion in mesh) (rotorcad gear --plot).")
    }
    files = {
        "gear.csv": (
            lambda p: write_points(p, ring.outline().points, ["rotorcad internal gear: toothed bore"]),
            "bore outline (x,y)",
        ),
        "gear.dxf": (lambda p: write_dxf(p, ring_drawing(ring, pair)), "the ring (bore, outer circle) and pinion in mesh"),
    }
    if pair is not None:
        files["mate.csv"] = (lambda p: write_points(p, pair.pinion.outline().points, ["rotorcad pinion"]), "pinion outline (x,y)")
    return {
        "kind": "gear",
        "case": case,
        "family": None,
        "result": result,
        "hob": hob,
        "figures": figures,
        "files": files,
        "command": "rotorcad gear",
    }

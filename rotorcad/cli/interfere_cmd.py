"""``rotorcad interfere``: interference of the rotor pair and with the housing, as designed or as built (CONTRACT.md).

The rotors as built come as points or drawings (``--male-points``, ``--female-points``); their
sections are those outlines, and the depth of penetration that counts as interference follows
the accuracy the points carry (:func:`rotorcad.clearance.estimated_accuracy`, as ``clearance``
states it), unless ``--tolerance`` is given.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

import click
import numpy as np
import shapely
import shapely.validation

from exports.dxf_profile import read_profile_points
from rotorcad.assembly import check_section_work
from rotorcad.cli.common import InputError, emit_json
from rotorcad.cli.export_cmd import ASSEMBLY_OPTIONS, _assemble, _check_solid_work, _rotor_options
from rotorcad.cli.progress import Steps
from rotorcad.cli.rotor import _build as build_rotors
from rotorcad.errors import DesignError
from rotorcad.interference import interference_2d, intersection_3d
from rotorcad.rotor_pair import RotorPair
from rotorcad.solids import helical_solid

DESIGN_TOLERANCE = 0.005
"""mm: the section tolerance of a design's own rotors when ``--tolerance`` is not given."""


@click.command()
@click.argument("design", type=click.Path(path_type=Path, dir_okay=False))
@click.option("--steps", type=int, default=72, show_default=True, help="Male angles over one lobe pitch.")
@click.option(
    "--tolerance",
    type=float,
    help="Section tolerance [mm]: a deeper penetration interferes; sets the touching threshold. Default: 0.005 for "
    "the design's rotors, the points' stated accuracy (from their scatter and spacing) with --male-points/--female-points.",
)
@click.option(
    "--check-3d", is_flag=True, help="Also intersect the 3D solids at the angle of the maximum (slow at fine tolerance)."
)
@ASSEMBLY_OPTIONS[0]
@ASSEMBLY_OPTIONS[1]
@click.option(
    "--male-points",
    type=click.Path(path_type=Path, dir_okay=False),
    help="The male as built: measured outline (CSV or DXF, own frame, one lobe or whole) in place of the design's.",
)
@click.option(
    "--female-points",
    type=click.Path(path_type=Path, dir_okay=False),
    help="The female as built: measured outline (CSV or DXF, own frame or drawn at (a, 0), one lobe or whole) in place "
    "of the design's.",
)
@click.option("--layer", help="Layer of the outline in DXF points files.")
@click.option("--male-layer", help="Layer of the male in its DXF file (default: --layer).")
@click.option("--female-layer", help="Layer of the female in its DXF file (default: --layer).")
@click.option("--json", "as_json", is_flag=True, help="Print one JSON object on stdout.")
@click.option("--quiet", is_flag=True, help="No progress bar.")
def interfere(design: Path, **opts: Any) -> None:
    """Interference of the rotor pair over one lobe pitch and of the rotors with the housing bores.

    The pair's interference is the integral of 2D section intersections along the helix. As
    assembled: at --center-distance and with the female turned by --phase-deg from its mesh position
    (the rotors keep their profiles; the bores follow the centre distance).

    Exit status: 0 when clean, 1 when the rotors interfere with each other or with the housing by
    more than the touching threshold (key touching_threshold, mm³, set by --tolerance), 2 on bad
    input.
    """
    steps, tolerance = opts["steps"], opts["tolerance"]
    if not 1 <= steps <= 100_000:
        raise InputError(f"--steps must be a whole number from 1 to 100000 (got {steps}).")
    if tolerance is not None and not (np.isfinite(tolerance) and 0 < tolerance <= 1.0):
        raise InputError(f"--tolerance must be between 0 and 1 mm (got {tolerance}).")
    rotors, _, clearance = build_rotors(design, _rotor_options(design))
    given = {
        side: _read_built(opts[f"{side}_points"], f"--{side}-points", opts[f"{side}_layer"] or opts["layer"], side, rotors.pair)
        for side in ("male", "female")
    }
    source = "--tolerance" if tolerance is not None else "design" if not any(given.values()) else "points"
    if tolerance is None:
        tolerance = DESIGN_TOLERANCE if source == "design" else _points_tolerance([g for g in given.values() if g])
    try:
        check_section_work(rotors, tolerance, "--tolerance")
    except DesignError as exc:
        raise InputError(exc.sentence()) from None
    if opts["check_3d"]:
        _check_solid_work(rotors, tolerance, "--tolerance")
    male = given["male"][0] if given["male"] else rotors.section("male", tolerance / 2)
    female = given["female"][0] if given["female"] else rotors.section("female", tolerance / 2)
    pair, phase = _assemble(rotors.pair, opts["center_distance"], opts["phase_deg"], clearance)
    progress = Steps("interference: 2-D sweep", 4 if opts["check_3d"] else 1, opts["quiet"]).start()
    result_2d = interference_2d(pair, male, female, steps, tolerance, female_phase=phase, clearance=clearance)
    progress.advance(description="interference: male solid")
    result: dict[str, Any] = {
        "center_distance": pair.center_distance,
        "phase_deg": float(np.degrees(phase)),
        "max_intersection_volume": result_2d.max_volume if result_2d.interferes else 0.0,
        "max_intersection_volume_raw": result_2d.max_volume,
        "angle_deg": float(np.degrees(result_2d.angle_of_max)),
        "housing_intersection_volume": result_2d.housing_volume,
        "steps": steps,
        "touching_threshold": result_2d.threshold,
        "max_penetration": result_2d.max_penetration,
        "tolerance": tolerance,
        "tolerance_source": source,
        "interferes": result_2d.interferes or result_2d.housing_volume > result_2d.threshold,
    }
    if opts["check_3d"]:
        result["check_3d"] = _intersection_3d(pair, male, female, tolerance, result_2d, progress)
    progress.stop()
    _print(result, design, opts["as_json"])
    if result["interferes"]:
        click.get_current_context().exit(1)  # a finding, not an error: pipelines test the status


def _print(result: dict[str, Any], design: Path, as_json: bool) -> None:
    """Print the result as JSON or as a table, with the tolerance it was judged to."""
    if as_json:
        emit_json(result)
        return
    from rotorcad.cli.common import print_table

    print_table(
        f"interference of {Path(design).stem}", {k: v for k, v in result.items() if k not in ("check_3d", "tolerance_source")}
    )
    why = {"--tolerance": "given", "design": "the design's sections", "points": "the points' stated accuracy"}
    click.echo(f"judged to a penetration of {result['tolerance'] * 1e3:.3g} µm ({why[result['tolerance_source']]})")


def _read_built(
    path: Path | None, option: str, layer: str | None, side: str, pair: RotorPair
) -> tuple[shapely.Polygon, float, float, int] | None:
    """Return a rotor's section as built from ``path`` (own frame), its scatter and spacing (mm) and point count.

    None without a file. The female drawn at its place in the pair, about (a, 0) as ``rotor --dxf``
    and ``export`` draw it, is moved into its own frame (:func:`rotorcad.measured.outline.own_frame`).
    A file that cannot be read, or an outline that crosses itself (GEOS fails on it in the sweep, exit
    70), is refused in one sentence naming ``option``.
    """
    if path is None:
        return None
    from rotorcad.clearance import points_quality
    from rotorcad.measured.outline import own_frame, scatter, whole_outline
    from rotorcad.measured.point_checks import file_lines, refuse_bad_points, refuse_other_units
    from rotorcad.roles import Side

    teeth = pair.male_teeth if side == "male" else pair.female_teeth
    try:
        radii = (pair.female_root_radius, pair.female_tip_radius)
        points = own_frame(read_profile_points(path, option, layer), Side(side), pair.center_distance, option, radii)
        ring = whole_outline(points, teeth, option)
        sigma = scatter(ring)
        refuse_other_units(ring, *(pair.male_root_radius, pair.male_tip_radius) if side == "male" else radii, option)
        refuse_bad_points(ring, sigma, teeth, option, points, file_lines(points))
    except DesignError as exc:
        raise InputError(exc.sentence()) from None
    outline = shapely.Polygon(ring)
    if not outline.is_valid:
        why = shapely.validation.explain_validity(outline)
        raise InputError(f"{option} must be an outline that does not cross itself (got {path}): {why}.")
    sigma, spacing = points_quality(np.vstack([ring, ring[:1]]))
    return outline, sigma, spacing, len(ring) // teeth


def _points_tolerance(built: list[tuple[shapely.Polygon, float, float, int]]) -> float:
    """Return the penetration that the given outlines can tell from touching, mm.

    The stated accuracy of their scatter and spacing (:func:`rotorcad.clearance.estimated_accuracy`,
    the larger scatter and spacing of the two, over a lobe's points), as ``clearance`` states it.
    """
    from rotorcad.clearance import estimated_accuracy

    sigma = max(b[1] for b in built)
    spacing = max(b[2] for b in built)
    return estimated_accuracy(sigma, spacing, max(b[3] for b in built))


def _intersection_3d(
    pair: RotorPair, male: shapely.Polygon, female: shapely.Polygon, tolerance: float, result_2d: Any, progress: Steps
) -> dict[str, Any]:
    """Sweep both solids and intersect them at the male angle of the 2-D maximum (``--check-3d``)."""
    lead = pair.lead if pair.hand == "right" else -pair.lead
    m = helical_solid(male, lead, pair.length, tolerance)
    progress.advance(description="interference: female solid")
    f = helical_solid(female, -np.sign(lead) * pair.female_lead, pair.length, tolerance)
    progress.advance(description="interference: 3-D intersection")
    found = intersection_3d(pair, m, f, result_2d.angle_of_max, result_2d.threshold)
    progress.advance()
    return found


__all__ = ["interfere"]

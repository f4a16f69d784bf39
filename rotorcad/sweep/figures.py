"""The figures a sweep writes of one pair: those of ``rotorcad rotor --json`` that are columns, and nothing else.

:meth:`rotorcad.meshing.MeshingAnalysis.summary` also works out what a sweep row does not hold
(where each maximum lies, the points of infinite slip, the spatial blow-hole, the angles of the
defects in Rinder's count, the per-flank reports as text), and the angles need the male's section
as a polygon. Here the sweep's columns come from the same cached properties of the same analysis
(meshline, defects, flanks, blow-hole, velocities), so they are the command's numbers bit for bit,
with one exception, the flute areas (:func:`section_area`).

Flute areas: the command clips each outline to its tip circle with shapely (an intersection with a
polygon of 2048 sides, inscribed in the tip circle + 1 um, after making the outline valid). A
generated outline that is already a valid polygon inside its tip circle needs no clipping, and its
area is that of its points (the shoelace formula, as shapely computes a polygon's area). The two
differ only where the outline runs on the tip circle (tip lands), which the 2048-gon cuts by its
sagitta, at most r (1 - cos(pi/2048)) - 1 um = 1.2e-6 r - 1e-6 mm: relative differences of the
flute areas and the displacement below :data:`FLUTE_AREA_RTOL` (tests/test_sweep_fast_path.py
checks it against ``rotorcad rotor --json``). Any other outline takes the command's way.
"""

from __future__ import annotations

from typing import Any

import numpy as np
import shapely

from rotorcad.geometry import hypot_within
from rotorcad.meshing import MeshingAnalysis
from rotorcad.roles import Side
from rotorcad.screw_rotors import ScrewRotors

FLUTE_AREA_RTOL = 1e-6
"""Relative tolerance of a sweep's flute areas, displacement and area utilisation against
``rotorcad rotor --json`` (the tip circle as a circle instead of a 2048-gon: see the module docstring)."""


SECTION_AREAS = "_section_areas"
"""Where a pair keeps its section areas (in its ``__dict__``, beside its sampled lobes)."""


def section_area(rotors: ScrewRotors, side: Side) -> float:
    """Area of a rotor's transverse section, mm².

    That of :meth:`ScrewRotors.section` up to the clipping polygon's sagitta (module docstring):
    the outline's own area when it is a valid polygon within its tip circle, else the section's.

    Parameters
    ----------
    rotors : ScrewRotors
        The pair.
    side : Side
        Which rotor.

    Returns
    -------
    float, mm²
    """
    kept = rotors.__dict__.setdefault(SECTION_AREAS, {})  # per pair, as its sampled lobes (``_lobes``)
    if side not in kept:
        pair = rotors.pair
        points = (rotors.male_outline() if side is Side.MALE else rotors.female_outline()).points
        tip = side.pick(pair.male_tip_radius, pair.female_tip_radius)
        polygon = shapely.Polygon(points)
        # every point within the tip circle + 1 um: np.hypot(*points.T).max() <= tip + 1e-6, hypot only near it
        if len(points) and hypot_within(points[:, 0], points[:, 1], tip + 1e-6).all() and shapely.is_valid(polygon):
            kept[side] = float(polygon.area)
        else:
            kept[side] = float(rotors.section(side).area)
    return kept[side]


def sweep_figures(analysis: MeshingAnalysis) -> dict[str, Any]:
    """Return the figures of a pair that a sweep's row holds, under the keys of ``rotorcad rotor --json``.

    Parameters
    ----------
    analysis : MeshingAnalysis
        Rinder's analysis of the pair at the design's speed.

    Returns
    -------
    dict
        ``meshline_closed``, ``blow_hole_area`` (mm²), ``contact_line_length`` (mm),
        ``male_flute_area`` and ``female_flute_area`` (mm², to :data:`FLUTE_AREA_RTOL`),
        ``displacement_per_rev`` (mm³), ``area_utilisation``, ``max_sliding_velocity`` (m/s),
        ``max_slip_male`` and ``max_slip_female`` (the largest slips, eq. 4; inf at a zero of v_t),
        ``runs_without_timing_gears``, ``wrap_angle_deg``, ``rack_loss_percent`` and
        ``defect_kinds`` (the kind of every defect, as ``defects`` of the JSON lists them).
    """
    rotors = analysis.rotors
    pair = rotors.pair
    z1, z2 = pair.male_teeth, pair.female_teeth
    bore1, bore2 = np.pi * pair.male_tip_radius**2, np.pi * pair.female_tip_radius**2
    bores = np.pi * (pair.male_tip_radius**2 + pair.female_tip_radius**2)  # as MeshingAnalysis.area_utilisation
    male_flute = float((bore1 - section_area(rotors, Side.MALE)) / z1)
    female_flute = float((bore2 - section_area(rotors, Side.FEMALE)) / z2)
    velocities = analysis.velocities
    return {
        "meshline_closed": analysis.meshline_closed,
        "blow_hole_area": analysis.blow_hole_area,
        "contact_line_length": analysis.contact_line_length,
        "male_flute_area": male_flute,
        "female_flute_area": female_flute,
        "displacement_per_rev": z1 * pair.length * (male_flute + female_flute),
        "area_utilisation": float((z1 * male_flute + z2 * female_flute) / bores),
        "max_sliding_velocity": _largest(velocities["sliding"]),
        "max_slip_male": _largest(velocities["slip_male"]),
        "max_slip_female": _largest(velocities["slip_female"]),
        "runs_without_timing_gears": all(r.runs_without_timing_gears for r in analysis.flanks.values()),
        "wrap_angle_deg": float(np.degrees(pair.wrap_angle)),
        "rack_loss_percent": rotors.rack_loss,
        "defect_kinds": [d.kind for d in analysis.defects],
    }


def _largest(values: np.ndarray) -> float:
    """Largest magnitude, infinite ones included (-1 when all are nan), as ``value`` of the summary's maxima."""
    v = np.abs(values)
    v = np.where(np.isnan(v), -1.0, v)  # an infinite slip is the largest, as in rotor --json
    return float(v[int(np.argmax(v))])

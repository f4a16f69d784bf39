"""What one worker of a design sweep runs: a batch of variants, each built and judged.

Each variant gives one row of plain values (numbers with their unit in the column name, or the
reason in one sentence why the variant could not be built). Nothing here keeps a mesh or a
profile for the caller: a worker ships numbers back.

The analyses are those of the commands, with the commands' settings: the pair and Rinder's
analysis of ``rotorcad rotor --json`` (:class:`rotorcad.meshing.MeshingAnalysis`, of which a row
takes only its columns: :func:`rotorcad.sweep.figures.sweep_figures`, the command's numbers bit for
bit except the flute areas, within :data:`rotorcad.sweep.figures.FLUTE_AREA_RTOL`), the
interference of ``rotorcad interfere`` (72 male angles over one lobe pitch, sections at half its
0.005 mm tolerance, the housing bores with the design's radial clearance), the meshing clearance of
``rotorcad clearance``. The hobbability verdict of ``rotorcad hob`` belongs to the ``hob`` package,
which the core does not import: the caller passes it in ``analyses`` (the command line does).

Between variants a worker keeps the last few pairs it built, keyed by what shapes the transverse
section (tooth counts, centre distance, radii, hand, family and its parameters, points): a variant
that differs from one of them only in lead, length, speed or housing takes that pair and the
analysis of its meshline, defects, flanks, blow-hole and sections, and recomputes what depends on
lead, length and speed (contact line, spatial blow-hole, displacement, sliding). The numbers are
those of a fresh build, bit for bit (tests/test_sweep.py checks it).
"""

from __future__ import annotations

import json
import time
from collections import OrderedDict
from collections.abc import Callable, Mapping
from dataclasses import replace
from typing import Any

from rotorcad.errors import DesignError
from rotorcad.sweep.plan import Extra, Variant, apply

# summary key of ``rotorcad rotor --json`` -> column (unit in the name)
RESULT_COLUMNS = {
    "meshline_closed": "meshline_closed",
    "blow_hole_area": "blow_hole_area_mm2",
    "contact_line_length": "contact_line_length_mm",
    "male_flute_area": "male_flute_area_mm2",
    "female_flute_area": "female_flute_area_mm2",
    "displacement_per_rev": "displacement_per_rev_mm3",
    "area_utilisation": "area_utilisation",
    "max_sliding_velocity": "max_sliding_velocity_m_s",
    "wrap_angle_deg": "wrap_angle_deg",
    "rack_loss_percent": "rack_loss_percent",
    "runs_without_timing_gears": "runs_without_timing_gears",
}
# objectives and whether smaller is better (the "best" of the JSON)
OBJECTIVES = {
    "blow_hole_area_mm2": True,
    "contact_line_length_mm": True,
    "displacement_per_rev_mm3": False,
    "max_sliding_velocity_m_s": True,
}

EXTRA_COLUMNS = {
    Extra.HOBBABILITY: ("hobbable", "hob_reason"),
    Extra.INTERFERENCE: ("interference_volume_mm3", "housing_intersection_volume_mm3", "interferes"),
    Extra.VOLUME: ("male_volume_mm3", "female_volume_mm3"),
    Extra.CLEARANCE: ("clearance_mean_mm", "clearance_max_mm", "clearance_min_mm", "clearance_band_area_mm2"),
}
DEFECT_KINDS = ("cusp", "jamming", "slipping")
"""Kinds of meshline defects (Rinder sec. 2.2.1), each counted in a column ``defects_KIND``."""
BOOLEAN_COLUMNS = ("ok", "meshline_closed", "runs_without_timing_gears", "hobbable", "interferes")
TEXT_COLUMNS = ("key", "reason", "defect_kinds", "hob_reason")

INTERFERENCE_STEPS = 72
"""Male angles over one lobe pitch: those of ``rotorcad interfere`` (its --steps default)."""
INTERFERENCE_TOLERANCE = 0.005
"""Section tolerance of the interference, mm: ``rotorcad interfere``'s --tolerance default."""
INTERFERENCE_SAMPLES = 360
"""Samples of the overlap area over one pitch (:func:`rotorcad.interference.interference_2d`'s default)."""

Analysis = Callable[[Any, Any, float], dict[str, Any]]
"""An optional analysis of a variant: (rotors, spec, designed clearance in mm) -> its columns."""

CACHE_SIZE = 8
"""Pairs a worker keeps between variants (the transverse build and its analysis)."""

_BUILT: OrderedDict[str, Any] = OrderedDict()
_TRANSVERSE = ("pieces", "defects", "flanks", "cusp", "meshline_end", "blow_hole", "sections")
"""Cached properties of :class:`rotorcad.meshing.MeshingAnalysis` that depend on the transverse section only."""


def result_columns(extras: tuple[Extra, ...]) -> list[str]:
    """List the numeric result columns of a sweep with these extra analyses (for plots and objectives).

    Parameters
    ----------
    extras : tuple of Extra
        The extra analyses of the sweep.

    Returns
    -------
    list of str
        Column names, their unit at the end (``_mm``, ``_mm2``, ...).
    """
    cols = [*RESULT_COLUMNS.values(), "max_slip_male", "max_slip_female", "defects"]
    cols += [f"defects_{kind}" for kind in DEFECT_KINDS] + ["seconds"]
    cols += [c for e in extras for c in EXTRA_COLUMNS[e] if c not in TEXT_COLUMNS]
    return [c for c in cols if c not in BOOLEAN_COLUMNS]


def boolean_columns(extras: tuple[Extra, ...]) -> list[str]:
    """List the true/false columns of a sweep with these extra analyses (for constraints).

    Parameters
    ----------
    extras : tuple of Extra
        The extra analyses of the sweep.

    Returns
    -------
    list of str
    """
    present = ["ok", *RESULT_COLUMNS.values(), *(c for e in extras for c in EXTRA_COLUMNS[e])]
    return [c for c in BOOLEAN_COLUMNS if c in present]


def _transverse_key(spec: Any) -> str:
    """Return what shapes a pair's transverse section: the cache key of :func:`_build`."""
    p = spec.pair
    shape = [p.male_teeth, p.female_teeth, p.center_distance, p.male_tip_radius, p.male_root_radius]
    shape += [p.female_tip_radius, p.female_root_radius, p.hand, spec.family, sorted(spec.params.items())]
    shape += [id(spec.points), spec.smoothing]
    return json.dumps(shape, default=repr)


def _build(spec: Any) -> tuple[Any, Any, dict[str, Any]]:
    """Build and analyse a pair, reusing a kept pair of the same transverse section.

    Returns the rotors, the analysis and its figures (:func:`rotorcad.sweep.figures.sweep_figures`:
    the keys of ``rotorcad rotor --json`` that are columns).
    """
    from rotorcad.design.rotors import build_pair
    from rotorcad.meshing import MeshingAnalysis
    from rotorcad.sweep.figures import sweep_figures

    key = _transverse_key(spec)
    kept = _BUILT.get(key)
    if kept is None:
        try:
            rotors = build_pair(spec)
            analysis = MeshingAnalysis(rotors, speed_rpm=spec.speed_rpm)
            figures = sweep_figures(analysis)
        except DesignError as exc:
            _keep(key, exc)
            raise
        _keep(key, (rotors, analysis))
        return rotors, analysis, figures
    if isinstance(kept, DesignError):
        _BUILT.move_to_end(key)
        raise kept
    _BUILT.move_to_end(key)
    old_rotors, old_analysis = kept
    rotors = replace(old_rotors, pair=spec.pair)  # the same rack and lobes: the transverse section
    for name in ("male_pieces", "female_pieces", "_lobes", "_section_areas"):
        if name in old_rotors.__dict__:
            rotors.__dict__[name] = old_rotors.__dict__[name]
    analysis = MeshingAnalysis(rotors, speed_rpm=spec.speed_rpm)
    for name in _TRANSVERSE:
        if name in old_analysis.__dict__:
            analysis.__dict__[name] = old_analysis.__dict__[name]
    return rotors, analysis, sweep_figures(analysis)


def _keep(key: str, value: Any) -> None:
    _BUILT[key] = value
    while len(_BUILT) > CACHE_SIZE:
        _BUILT.popitem(last=False)


def clear_cache() -> None:
    """Forget the pairs kept between variants (:data:`CACHE_SIZE`)."""
    _BUILT.clear()


def evaluate(
    base: dict[str, Any],
    folder: str | None,
    points: Any,
    extras: tuple[Extra, ...],
    variant: Variant,
    clearance: float = 0.05,
    analyses: Mapping[Extra, Analysis] | None = None,
    families: dict[str, dict[str, Any]] | None = None,
) -> dict[str, Any]:
    """Build and judge one variant: the base design with its values.

    Parameters
    ----------
    base : dict
        The base design mapping.
    folder : str, optional
        The base design's folder (for a relative points file).
    points : (n, 2) float array or list of Curve, optional
        The base design's profile points, already read (mm).
    extras : tuple of Extra
        Extra analyses to run.
    variant : Variant
        The variant.
    clearance : float, mm
        Normal clearance designed into the female for the "clearance" analysis.
    analyses : mapping of Extra to callable, optional
        Analyses beyond :data:`ANALYSES` (the hobbability verdict of the ``hob`` package), or
        replacing them.
    families : dict, optional
        ``[families.NAME]`` parameters of a family axis (:func:`rotorcad.sweep.plan.apply`).

    Returns
    -------
    dict
        ``variant``, ``key``, the varied values, ``ok``, ``reason`` (empty when ok), ``seconds``
        and the results. Any failure, a refusal or a bug, becomes the row's reason: a variant never
        stops the sweep.
    """
    from rotorcad.design import rotor_design
    from rotorcad.design.rotors import pair_spec

    start = time.perf_counter()
    row: dict[str, Any] = {
        "variant": variant.index,
        "key": variant.key,
        **variant.values,
        "ok": False,
        "reason": "",
        "seconds": 0.0,
    }
    table = {**ANALYSES, **(analyses or {})}
    try:
        spec = pair_spec(rotor_design(apply(base, variant.values, families), folder), points)
        rotors, _, figures = _build(spec)
        for key, column in RESULT_COLUMNS.items():
            row[column] = figures.get(key)
        row["max_slip_male"] = figures["max_slip_male"]
        row["max_slip_female"] = figures["max_slip_female"]
        kinds = figures["defect_kinds"]
        row["defects"] = len(kinds)
        row["defect_kinds"] = ", ".join(sorted(set(kinds)))
        for kind in DEFECT_KINDS:
            row[f"defects_{kind}"] = sum(k == kind for k in kinds)
        for extra in extras:
            if extra not in table:
                raise DesignError("[sweep] compute", "analyses this run can make", extra.value, "its analysis was not given")
            row.update(table[extra](rotors, spec, clearance))
        row["ok"] = True
    except DesignError as exc:
        row["reason"] = exc.sentence()
    except Exception as exc:  # a variant that breaks the code must not stop the sweep: its reason is kept
        row["reason"] = f"{type(exc).__name__}: {' '.join(str(exc).split())[:200]}"
    row["seconds"] = time.perf_counter() - start
    return row


def clearance_analysis(rotors: Any, spec: Any, clearance: float) -> dict[str, Any]:
    """Meshing clearance (Wu & Chi) of the pair with ``clearance`` mm of normal clearance designed into the female.

    What ``rotor --clearance`` writes and ``rotorcad clearance`` reads back.
    """
    from rotorcad.clearance import MeshingClearance
    from rotorcad.clearance_design import ClearanceDistribution, corrected_female
    from rotorcad.rotor_points import lobe_pieces

    female = corrected_female(rotors, ClearanceDistribution(driving=clearance, sealing=clearance, lands=clearance), 1e-3)
    male = rotors.male_outline(1e-3).points
    band = MeshingClearance(spec.pair, lobe_pieces(spec.pair, male, "male"), lobe_pieces(spec.pair, female, "female")).summary()
    return {
        "clearance_mean_mm": band["mean_clearance"],
        "clearance_max_mm": band["max_normal_clearance"],
        "clearance_min_mm": band["min_normal_clearance"],
        "clearance_band_area_mm2": band["band_area"],
    }


def interference_analysis(rotors: Any, spec: Any, clearance: float) -> dict[str, Any]:
    """Interference of the pair and of the rotors with the housing, as ``rotorcad interfere`` computes it.

    72 male angles over one lobe pitch, sections at half the 0.005 mm tolerance, the bores at the
    design's radial clearance; ``interferes`` as that command's key (the pair or the housing above
    the touching threshold).
    """
    from rotorcad.interference import interference_2d

    tol = INTERFERENCE_TOLERANCE
    male, female = rotors.section("male", tol / 2), rotors.section("female", tol / 2)
    result = interference_2d(
        spec.pair, male, female, INTERFERENCE_STEPS, tol, INTERFERENCE_SAMPLES, clearance=spec.radial_clearance
    )
    return {
        "interference_volume_mm3": result.max_volume,
        "housing_intersection_volume_mm3": result.housing_volume,
        "interferes": bool(result.interferes or result.housing_volume > result.threshold),
    }


def volume_analysis(rotors: Any, spec: Any, clearance: float) -> dict[str, Any]:
    """Volume of the solids: section area x length (mm³)."""
    length = spec.pair.length
    return {
        "male_volume_mm3": rotors.section("male", 1e-3).area * length,
        "female_volume_mm3": rotors.section("female", 1e-3).area * length,
    }


ANALYSES: dict[Extra, Analysis] = {
    Extra.INTERFERENCE: interference_analysis,
    Extra.VOLUME: volume_analysis,
    Extra.CLEARANCE: clearance_analysis,
}
"""The optional analyses of the core (the hobbability verdict comes from ``hob.sweep_check``)."""


def evaluate_batch(
    variants: list[Variant],
    base: dict[str, Any],
    folder: str | None,
    points: Any,
    extras: tuple[Extra, ...],
    clearance: float = 0.05,
    analyses: Mapping[Extra, Analysis] | None = None,
    families: dict[str, dict[str, Any]] | None = None,
) -> list[dict[str, Any]]:
    """Evaluate a batch of variants: one Dask task, enough work to make the scheduler's cost small.

    Parameters
    ----------
    variants : list of Variant
        The batch.
    base, folder, points, extras, clearance, analyses, families
        As for :func:`evaluate`.

    Returns
    -------
    list of dict
        One row per variant (:func:`evaluate`).
    """
    return [evaluate(base, folder, points, extras, v, clearance, analyses, families) for v in variants]

"""What one worker of a design sweep runs: a batch of variants, each built and judged.

Each variant gives one row of plain values (numbers with their unit in the column name, or the
reason in one sentence why the variant could not be built). Nothing here keeps a mesh or a
profile: a worker ships numbers back.
"""

from __future__ import annotations

import time
from typing import Any

from rotorcad.errors import DesignError
from rotorcad.sweep_plan import Extra, Variant, apply

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
}
# objectives and whether smaller is better
OBJECTIVES = {
    "blow_hole_area_mm2": True,
    "contact_line_length_mm": True,
    "displacement_per_rev_mm3": False,
    "max_sliding_velocity_m_s": True,
}


EXTRA_COLUMNS = {
    Extra.HOBBABILITY: ("hobbable", "hob_reason"),
    Extra.INTERFERENCE: ("interference_volume_mm3", "interferes"),
    Extra.VOLUME: ("male_volume_mm3", "female_volume_mm3"),
    Extra.CLEARANCE: ("clearance_mean_mm", "clearance_max_mm", "clearance_min_mm", "clearance_band_area_mm2"),
}


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
    cols += [c for e in extras for c in EXTRA_COLUMNS[e] if c not in ("hob_reason", "hobbable", "interferes")]
    return [c for c in cols if c != "meshline_closed"]


def evaluate(
    base: dict[str, Any], folder: str | None, points: Any, extras: tuple[Extra, ...], variant: Variant, clearance: float = 0.05
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

    Returns
    -------
    dict
        ``variant``, ``key``, the varied values, ``ok``, ``reason`` (empty when ok), ``seconds``
        and the results. Any failure, a refusal or a bug, becomes the row's reason: a variant never
        stops the sweep.
    """
    from rotorcad.design import rotor_design
    from rotorcad.rotor_build import analyse_pair, build_pair, pair_spec

    start = time.perf_counter()
    row: dict[str, Any] = {
        "variant": variant.index,
        "key": variant.key,
        **variant.values,
        "ok": False,
        "reason": "",
        "seconds": 0.0,
    }
    try:
        spec = pair_spec(rotor_design(apply(base, variant.values), folder), points)
        rotors = build_pair(spec)
        _, summary = analyse_pair(rotors, spec.speed_rpm)
        for key, column in RESULT_COLUMNS.items():
            row[column] = summary.get(key)
        row["max_slip_male"] = summary["max_slip_male"]["value"]
        row["max_slip_female"] = summary["max_slip_female"]["value"]
        row["defects"] = len(summary["defects"])
        row["defect_kinds"] = ", ".join(sorted({d["kind"] for d in summary["defects"]}))
        for extra in extras:
            row.update(_extra(extra, rotors, spec, clearance))
        row["ok"] = True
    except DesignError as exc:
        row["reason"] = exc.sentence()
    except Exception as exc:  # a variant that breaks the code must not stop the sweep: its reason is kept
        row["reason"] = f"{type(exc).__name__}: {' '.join(str(exc).split())[:200]}"
    row["seconds"] = time.perf_counter() - start
    return row


def _extra(extra: Extra, rotors, spec, clearance: float) -> dict[str, Any]:
    """Run one optional analysis of a variant and return its columns.

    Hobbability (hob.verdict), interference at the design centre distance (2D sections over one lobe
    pitch), the solids' volume (section area x length), and the meshing clearance (Wu & Chi) of the
    pair with ``clearance`` mm of normal clearance designed into the female (what `rotor --clearance`
    writes and `rotorcad clearance` reads back).
    """
    if extra is Extra.CLEARANCE:
        from rotorcad.clearance import MeshingClearance
        from rotorcad.clearance_design import ClearanceDistribution, corrected_female
        from rotorcad.rotor_points import lobe_pieces

        female = corrected_female(rotors, ClearanceDistribution(driving=clearance, sealing=clearance, lands=clearance), 1e-3)
        male = rotors.male_outline(1e-3).points
        band = MeshingClearance(
            spec.pair, lobe_pieces(spec.pair, male, "male"), lobe_pieces(spec.pair, female, "female")
        ).summary()
        return {
            "clearance_mean_mm": band["mean_clearance"],
            "clearance_max_mm": band["max_normal_clearance"],
            "clearance_min_mm": band["min_normal_clearance"],
            "clearance_band_area_mm2": band["band_area"],
        }
    if extra is Extra.HOBBABILITY:
        from hob.rack import rotor_rack
        from hob.verdict import HobLimits, judge

        verdicts = [judge(rotor_rack(rotors, rotor), HobLimits()) for rotor in ("male", "female")]
        reasons = [f"{rotor}: {r}" for rotor, v in zip(("male", "female"), verdicts, strict=True) for r in v.reasons]
        return {"hobbable": all(v.hobbable for v in verdicts), "hob_reason": "; ".join(reasons)}
    if extra is Extra.INTERFERENCE:
        from rotorcad.interference import interference_2d

        tol = 1e-3
        result = interference_2d(spec.pair, rotors.section("male", tol), rotors.section("female", tol), 36, tol, 72)
        return {"interference_volume_mm3": result.max_volume, "interferes": result.interferes}
    length = spec.pair.length
    return {
        "male_volume_mm3": rotors.section("male", 1e-3).area * length,
        "female_volume_mm3": rotors.section("female", 1e-3).area * length,
    }


def evaluate_batch(
    variants: list[Variant],
    base: dict[str, Any],
    folder: str | None,
    points: Any,
    extras: tuple[Extra, ...],
    clearance: float = 0.05,
) -> list[dict[str, Any]]:
    """Evaluate a batch of variants: one Dask task, enough work to make the scheduler's cost small.

    Parameters
    ----------
    variants : list of Variant
        The batch.
    base, folder, points, extras, clearance
        As for :func:`evaluate`.

    Returns
    -------
    list of dict
        One row per variant (:func:`evaluate`).
    """
    return [evaluate(base, folder, points, extras, v, clearance) for v in variants]

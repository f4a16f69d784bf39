"""A gear inspected from measured points: profile, pitch and tooth thickness deviations (ISO 1328-1:2013).

The points are turned onto the nominal gear by a least-squares rotation
(:mod:`rotorcad.inspection.alignment`); each flank's normal deviations along the roll length
give its profile deviations (:mod:`rotorcad.inspection.profile_deviations`). From the flanks'
mean profile lines:

- a flank's *position* is its mean line's deviation at the measuring circle (the middle of the
  evaluation range), as an arc of that circle: R_M dev / r_b, + counter-clockwise;
- the *single pitch deviation* f_pt of tooth k is the difference of the positions of the same
  flank of teeth k and k - 1 (ISO 1328-1:2013: actual minus theoretical pitch, + a longer pitch,
  counted counter-clockwise), given where both teeth were measured;
- the *cumulative pitch deviation* F_p is the range of the positions over the teeth given (ISO
  1328-1 takes it over all teeth: with fewer teeth measured it is a lower bound);
- the *tooth thickness deviation* is the change of the normal arc thickness on the reference
  circle, (dev_left + dev_right) cos(beta) / cos(alpha_t) from the mean lines there (a flank
  moved by dev along its transverse normal widens the transverse arc by dev / cos(alpha_t),
  ISO 21771).

The best-fit rotation changes none of these: it moves all positions alike and the two flanks of
a tooth oppositely.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np

from rotorcad.geometry import Array
from rotorcad.inspection.alignment import FlankPoints, align
from rotorcad.inspection.nominal import NominalFlanks
from rotorcad.inspection.profile_deviations import ProfileDeviation, profile_deviation
from rotorcad.inspection.tolerances import CLASSES, FlankTolerances, flank_tolerances
from rotorcad.roles import ToothFlank


@dataclass(frozen=True)
class FlankResult:
    """One measured flank: its profile deviations, position and single pitch deviation.

    Attributes
    ----------
    tooth : int
        Tooth index (tooth 0 on +x after the rotation).
    flank : ToothFlank
        Left or right.
    profile : ProfileDeviation
        Over L_alpha.
    position : float, mm
        Arc on the measuring circle, + counter-clockwise.
    single_pitch : float or None, mm
        f_pt against tooth k - 1 (None where that tooth's flank was not measured).
    roll_length, deviation : (n,) float arrays, mm
        The flank's points for the chart (all of them, also outside L_alpha).
    """

    tooth: int
    flank: ToothFlank
    profile: ProfileDeviation
    position: float
    single_pitch: float | None
    roll_length: Array
    deviation: Array


@dataclass(frozen=True)
class GearInspection:
    """A gear inspected from points (:func:`inspect_gear`).

    Attributes
    ----------
    nominal : NominalFlanks
        The nominal gear and its evaluation range.
    fit : FlankPoints
        The rotation and the points on the flanks.
    flanks : list of FlankResult
        By tooth, left before right.
    thickness : dict of int to float, mm
        Normal tooth thickness deviation by tooth (teeth with both flanks measured).
    points_given : int
        All points read.
    tolerances : FlankTolerances or None
        Of the class asked for.
    """

    nominal: NominalFlanks
    fit: FlankPoints
    flanks: list[FlankResult]
    thickness: dict[int, float]
    points_given: int
    tolerances: FlankTolerances | None

    def worst(self, flank: ToothFlank) -> dict[str, float | None]:
        """Return the largest deviations of one side's flanks, mm (None where not measured)."""
        mine = [f for f in self.flanks if f.flank is flank]
        pitches = [abs(f.single_pitch) for f in mine if f.single_pitch is not None]
        positions = [f.position for f in mine]
        return {
            "total_profile_deviation": max((f.profile.total for f in mine), default=None),
            "profile_form_deviation": max((f.profile.form for f in mine), default=None),
            "profile_slope_deviation": max((f.profile.slope for f in mine), key=abs, default=None),
            "single_pitch_deviation": max(pitches, default=None),
            "cumulative_pitch_deviation": (max(positions) - min(positions)) if len(positions) > 1 else None,
        }

    def classes(self) -> dict[str, int | None]:
        """Return the finest ISO 1328-1:2013 class each worst deviation meets (None: coarser than class 11 or not measured)."""
        worst = [self.worst(side) for side in ToothFlank]
        names = {
            "total_profile_deviation": "total_profile",
            "profile_form_deviation": "profile_form",
            "profile_slope_deviation": "profile_slope",
            "single_pitch_deviation": "single_pitch",
            "cumulative_pitch_deviation": "cumulative_pitch",
        }
        out: dict[str, int | None] = {}
        diameter, module = 2.0 * self.nominal.reference_radius, self.nominal.module
        table = [flank_tolerances(a, module, diameter) for a in range(CLASSES[0], CLASSES[1] + 1)]
        for key, attr in names.items():
            values = [abs(w[key]) for w in worst if w[key] is not None]
            if not values:
                out[key] = None
                continue
            found = [t.tolerance_class for t in table if max(values) <= getattr(t, attr)]
            out[key] = found[0] if found else None
        return out

    def summary(self) -> dict[str, Any]:
        """Return the CONTRACT.md keys of ``rotorcad inspect`` for a gear (lengths mm, angles deg)."""
        rms = float(np.sqrt(np.mean(self.fit.deviation**2))) if len(self.fit.deviation) else None
        result: dict[str, Any] = {
            "body": "gear",
            "teeth": self.nominal.teeth,
            "points_read": self.points_given,
            "points_on_flanks": len(self.fit.deviation),
            "alignment": {
                "rotation_deg": math.degrees(self.fit.rotation),
                "method": "least squares: the rotation minimising the squared normal deviations of the involute points",
                "rms_deviation": rms,
            },
            "evaluation_range": self.nominal.summary(),
            "teeth_measured": sorted({f.tooth for f in self.flanks}),
            "flanks": [
                {
                    "tooth": f.tooth,
                    "flank": f.flank.value,
                    "points_evaluated": f.profile.points,
                    "total_profile_deviation": f.profile.total,
                    "profile_form_deviation": f.profile.form,
                    "profile_slope_deviation": f.profile.slope,
                    "position": f.position,
                    "single_pitch_deviation": f.single_pitch,
                }
                for f in self.flanks
            ],
            "left": self.worst(ToothFlank.LEFT),
            "right": self.worst(ToothFlank.RIGHT),
            "thickness_deviation": [{"tooth": k, "deviation": v} for k, v in sorted(self.thickness.items())],
            "thickness_deviation_mean": float(np.mean(list(self.thickness.values()))) if self.thickness else None,
            "classes": self.classes(),
        }
        if self.tolerances is not None:
            t = self.tolerances
            result["tolerances"] = t.summary()
            limits = {
                "total_profile_deviation": t.total_profile,
                "profile_form_deviation": t.profile_form,
                "profile_slope_deviation": t.profile_slope,
                "single_pitch_deviation": t.single_pitch,
                "cumulative_pitch_deviation": t.cumulative_pitch,
            }
            result["within_tolerance"] = {
                key: all(abs(w[key]) <= limit for w in (result["left"], result["right"]) if w[key] is not None)
                for key, limit in limits.items()
            }
        return result


def _flank_results(nominal: NominalFlanks, fit: FlankPoints) -> list[FlankResult]:
    """Evaluate every flank with enough points in L_alpha, and the single pitch deviations between them."""
    rng = nominal.evaluation_range
    xi_m = float(nominal.roll_length(nominal.measuring_radius))
    foot = nominal.roll_length(fit.radius) - fit.deviation  # the foot on the nominal involute, along the base tangent
    found: dict[tuple[int, ToothFlank], tuple[ProfileDeviation, float, Array, Array]] = {}
    order = np.lexsort((-fit.sign, fit.tooth))
    keys = np.column_stack([fit.tooth[order], fit.sign[order]])
    starts = np.nonzero(np.r_[True, np.any(np.diff(keys, axis=0) != 0, axis=1)])[0]
    for rows in np.split(order, starts[1:]):
        if len(rows) == 0:
            continue
        tooth, flank = int(fit.tooth[rows[0]]), ToothFlank.LEFT if fit.sign[rows[0]] > 0 else ToothFlank.RIGHT
        prof = profile_deviation(foot[rows], fit.deviation[rows], rng)
        if prof is None:
            continue
        position = flank.sign * prof.at(xi_m) / nominal.base_radius * nominal.measuring_radius
        found[(tooth, flank)] = (prof, position, foot[rows], fit.deviation[rows])
    out = []
    for (tooth, flank), (prof, position, xi, dev) in found.items():
        before = found.get(((tooth - 1) % nominal.teeth, flank))
        pitch = position - before[1] if before is not None and nominal.teeth > 1 else None
        out.append(FlankResult(tooth, flank, prof, position, pitch, xi, dev))
    return out


def inspect_gear(points: Array, nominal: NominalFlanks, tolerance_class: int | None = None) -> GearInspection:
    """Inspect a gear from measured points of one or more teeth.

    Parameters
    ----------
    points : (n, 2) float array, mm
        Points of the teeth in the gear's axis frame (transverse section), any order, CMM scatter.
    nominal : NominalFlanks
        The nominal gear (:func:`rotorcad.inspection.nominal.nominal_flanks`).
    tolerance_class : int, optional
        ISO 1328-1:2013 flank tolerance class (1 ... 11) to judge against.

    Returns
    -------
    GearInspection
        Flanks with fewer than :data:`~rotorcad.inspection.profile_deviations.MIN_POINTS` points
        in L_alpha are left out (the caller refuses an inspection with none).
    """
    fit = align(points, nominal)
    flanks = sorted(_flank_results(nominal, fit), key=lambda f: (f.tooth, f.flank is ToothFlank.RIGHT))
    xi_r = float(nominal.roll_length(nominal.reference_radius))
    scale = math.cos(nominal.helix_angle) / math.cos(nominal.transverse_pressure_angle)
    by_tooth: dict[int, dict[ToothFlank, FlankResult]] = {}
    for f in flanks:
        by_tooth.setdefault(f.tooth, {})[f.flank] = f
    thickness = {
        k: (sides[ToothFlank.LEFT].profile.at(xi_r) + sides[ToothFlank.RIGHT].profile.at(xi_r)) * scale
        for k, sides in by_tooth.items()
        if len(sides) == 2
    }
    tolerances = None
    if tolerance_class is not None:
        tolerances = flank_tolerances(tolerance_class, nominal.module, 2.0 * nominal.reference_radius)
    return GearInspection(nominal, fit, flanks, thickness, len(points), tolerances)


__all__ = ["FlankResult", "GearInspection", "inspect_gear"]

"""One grinding job: a rotor outline and a wheel radius to the wheel's profile, checked, as numbers.

What ``rotorcad grind`` and the benchmark run for each wheel radius (new and worn): the flute
sampled finely (:data:`FLUTE_TOLERANCE`), the setting (:func:`rotorcad.grinding.default_setting`),
the wheel's profile (:func:`rotorcad.grinding.wheel_profile`) and its check
(:func:`rotorcad.grinding.check_grinding`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np

from rotorcad.geometry import rotate
from rotorcad.grinding.ground_rotor import CHECK_TOLERANCE, GrindingCheck, check_grinding
from rotorcad.grinding.setting import default_setting
from rotorcad.grinding.wheel_profile import WheelProfile, flute_of, wheel_profile
from rotorcad.profile import Profile

FLUTE_TOLERANCE = 2e-5
"""Chord tolerance (mm) of the flute's samples: the wheel's points then lie close enough (0.2 mm at
most on the samples) that a straight line between them is within 0.1 um of the wheel
(tests/test_grinding.py: the brute-force simulation and the round trip through a spline)."""


@dataclass(frozen=True, eq=False)
class GrindingJob:
    """A wheel for a rotor and what it does to it."""

    wheel: WheelProfile
    check: GrindingCheck

    def summary(self) -> dict[str, Any]:
        """Return the numbers of one wheel (CONTRACT.md, ``rotorcad grind --json``, ``wheels``).

        Returns
        -------
        dict
            Lengths in mm, counts as int, flags as bool.
        """
        w, c, s = self.wheel, self.check, self.wheel.setting
        ok = w.valid
        return {
            "wheel_radius": s.wheel_radius,
            "center_distance": s.center_distance,
            "crossing_angle_deg": math.degrees(s.crossing_angle),
            "flute_turn_deg": math.degrees(w.flute.turn),
            "profile_point_count": int(ok.sum()),
            "profile_axial_length": float(np.ptp(w.axial[ok])) if ok.any() else 0.0,
            "profile_radial_length": float(np.ptp(w.radius[ok])) if ok.any() else 0.0,
            "wheel_max_radius": float(w.radius[ok].max()) if ok.any() else float("nan"),
            "wheel_min_radius": float(w.radius[ok].min()) if ok.any() else float("nan"),
            "profile_folds": w.folds,
            "no_contact_point_count": int((~ok).sum()),
            "unreached_point_count": int(c.unreached.sum()),
            "secondary_cutting_point_count": c.secondary_cutting_points,
            "secondary_cutting_deviation": c.secondary_cutting_deviation,
            "check_tolerance": CHECK_TOLERANCE,
            "round_trip_deviation": c.round_trip,
        }

    def rows(self) -> np.ndarray:
        """Return the dresser's rows, (n, 6), contacts only.

        Axial coordinate, radius (mm), outward unit normal (axial, radial), and the rotor point
        ground, x, y (mm) in the rotor's own frame (as its design draws it).
        """
        w = self.wheel
        ok = w.valid
        own = rotate(w.flute.points, -w.flute.turn)
        return np.column_stack([w.axial, w.radius, w.normals, own])[ok]


def grind(
    outline: Profile,
    twist: float,
    lobes: int,
    wheel_radius: float,
    setting_radius: float,
    crossing_angle: float | None = None,
    center_distance: float | None = None,
    tolerance: float = FLUTE_TOLERANCE,
) -> GrindingJob:
    """Make and check the wheel that grinds a rotor.

    Parameters
    ----------
    outline : Profile
        The rotor's transverse outline about its axis (closed, counter-clockwise, analytic segments).
    twist : float, rad/mm
        ``2 pi / h`` of the rotor's signed lead (> 0 right hand; 0 spur).
    lobes : int
        Lobes or teeth.
    wheel_radius : float, mm
        The wheel's outside radius.
    setting_radius : float, mm
        Radius whose helix angle is the default crossing angle.
    crossing_angle : float, optional, rad
        Instead of the helix angle at ``setting_radius``.
    center_distance : float, optional, mm
        Instead of root radius + wheel radius.
    tolerance : float, mm
        Chord tolerance of the flute's samples (:data:`FLUTE_TOLERANCE`).

    Returns
    -------
    GrindingJob

    Raises
    ------
    DesignError
        A setting out of range (:func:`rotorcad.grinding.default_setting`).
    """
    flute = flute_of(outline.resampled(tolerance))
    setting = default_setting(
        twist, flute.root_radius, wheel_radius, setting_radius, crossing_angle, center_distance, flute.tip_radius
    )
    wheel = wheel_profile(flute, setting)
    return GrindingJob(wheel, check_grinding(wheel, outline.points, lobes))


SCAN_TOLERANCE = 1e-4
"""Chord tolerance (mm) of the flute while crossing angles are scanned (the chosen one is checked at
:data:`FLUTE_TOLERANCE`)."""


def cut_depth(job: GrindingJob) -> float:
    """Return how deep the wheel cuts into the rotor anywhere, mm (inf when a flute point has no contact).

    The deepest negative stock of the flute and the lobes either side, also below
    :data:`~rotorcad.grinding.ground_rotor.CHECK_TOLERANCE` (0 when the wheel cuts nowhere).
    """
    c = job.check
    if not job.wheel.valid.all():
        return float("inf")
    least = min(float(np.min(c.flute_stock, initial=np.inf)), float(np.min(c.neighbour_stock, initial=np.inf)))
    return max(0.0, -least)


def least_cutting_angle(
    outline: Profile,
    twist: float,
    lobes: int,
    wheel_radius: float,
    setting_radius: float,
    center_distance: float | None = None,
) -> tuple[float, GrindingJob]:
    """Find the crossing angle at which the wheel cuts least into the rotor (secondary cutting).

    The helix angles from the root radius less 5 deg to the tip radius plus 5 deg (within +-79 deg)
    are tried in steps of 1 deg (:func:`cut_depth`, the flute at :data:`SCAN_TOLERANCE`); about the
    best, golden-section search to 0.01 deg; where several angles cut nowhere, the one nearest the
    helix angle at ``setting_radius`` is kept. The angle found is checked at :data:`FLUTE_TOLERANCE`.

    Parameters
    ----------
    outline, twist, lobes, wheel_radius, setting_radius, center_distance
        As :func:`grind`.

    Returns
    -------
    angle : float, rad
        The crossing angle.
    job : GrindingJob
        The wheel at that angle.
    """
    flute = flute_of(outline)
    limit = math.radians(79.0)
    lo = max(-limit, min(math.atan(twist * flute.root_radius), math.atan(twist * flute.tip_radius)) - math.radians(5.0))
    hi = min(limit, max(math.atan(twist * flute.root_radius), math.atan(twist * flute.tip_radius)) + math.radians(5.0))
    usual = math.atan(twist * setting_radius)

    def depth(angle: float) -> float:
        return cut_depth(grind(outline, twist, lobes, wheel_radius, setting_radius, angle, center_distance, SCAN_TOLERANCE))

    angles = np.arange(lo, hi + 1e-12, math.radians(1.0))
    depths = np.array([depth(a) for a in angles])  # one wheel per angle: a few dozen at most
    best = float(depths.min())
    if best == 0.0:
        clean = angles[depths == 0.0]
        angle = float(clean[np.argmin(np.abs(clean - usual))])
    else:
        i = int(np.argmin(depths))
        a, b = angles[max(i - 1, 0)], angles[min(i + 1, len(angles) - 1)]
        golden = (math.sqrt(5.0) - 1.0) / 2.0
        c, d = b - golden * (b - a), a + golden * (b - a)
        fc, fd = depth(c), depth(d)
        while b - a > math.radians(0.01):
            if fc <= fd:
                b, d, fd = d, c, fc
                c = b - golden * (b - a)
                fc = depth(c)
            else:
                a, c, fc = c, d, fd
                d = a + golden * (b - a)
                fd = depth(d)
        angle = 0.5 * (a + b)
        if depth(angle) > best:  # the grid point was better (a cut depth need not be unimodal)
            angle = float(angles[i])
    return angle, grind(outline, twist, lobes, wheel_radius, setting_radius, angle, center_distance)


__all__ = ["FLUTE_TOLERANCE", "SCAN_TOLERANCE", "GrindingJob", "cut_depth", "grind", "least_cutting_angle"]

"""How far the ground rotor moves off its design for an error of the wheel or its setting.

For each error the wheel is set (or dressed) wrongly by a small step either way, the rotor it then
grinds is computed in closed form (:func:`rotorcad.grinding.rotor_from_wheel`: the envelope of the
wheel in helical motion), and the displacement of every ground point along the design's outward
normal at the point it came from is divided by the step (central difference over the setting, so
exact to second order in the step; the normals themselves are the analytic ones). A point that
slides along the flank moves it by nothing to first order, so this is the rotor's normal deviation
per unit error, positive where the rotor is left thicker.

The errors (:data:`ERRORS`, unit of the error in brackets):

* ``center_distance`` [mm]: the wheel axis farther from the rotor axis;
* ``crossing_angle`` [deg]: the wheel head swivelled more;
* ``axial_position`` [mm]: the wheel moved along its own axis;
* ``wheel_radius`` [mm]: the wheel worn by this much (its outside circle smaller) but still dressed to
  the new wheel's profile shape, set to plunge to the root circle again (centre distance smaller by
  the same); the error a worn wheel makes when it is not dressed to its own profile;
* ``wheel_profile`` [mm]: the wheel's profile dressed thicker along its own normal by this much.
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass

import numpy as np

from rotorcad.geometry import Array, perp_cw
from rotorcad.grinding.ground_rotor import rotor_from_wheel
from rotorcad.grinding.wheel_profile import WheelProfile

ERRORS = ("center_distance", "crossing_angle", "axial_position", "wheel_radius", "wheel_profile")
"""The errors, in the order of :attr:`Sensitivity.per_unit`."""

UNITS = {"center_distance": "mm", "crossing_angle": "deg", "axial_position": "mm", "wheel_radius": "mm", "wheel_profile": "mm"}
"""Unit of each error: the deviation (mm) is per this unit."""

STEPS = {"center_distance": 1e-3, "crossing_angle": 1e-3, "axial_position": 1e-3, "wheel_radius": 1e-2, "wheel_profile": 1e-3}
"""Steps of the central differences, in :data:`UNITS`."""


@dataclass(frozen=True, eq=False)
class Sensitivity:
    """The rotor's normal deviation per unit error, along the flute.

    Attributes
    ----------
    points : (n, 2) float array, mm
        The flute's points with a contact (the flute turned to face the wheel, as the wheel's).
    per_unit : (5, n) float array
        Normal deviation (mm, + thicker) per unit of each error of :data:`ERRORS`.
    """

    points: Array
    per_unit: Array

    def deviation(self, errors: dict[str, float]) -> Array:
        """Return the normal deviation (mm, (n,)) of the errors given (in :data:`UNITS`), to first order."""
        return sum((self.per_unit[ERRORS.index(k)] * v for k, v in errors.items()), np.zeros(len(self.points)))

    def largest(self) -> dict[str, float]:
        """Return, per error, the largest magnitude of the deviation per unit error along the flute."""
        return {name: float(np.nanmax(np.abs(row))) for name, row in zip(ERRORS, self.per_unit, strict=True)}


def _ground(wheel: WheelProfile, errors: dict[str, float]) -> Array:
    """Return the rotor points the wheel grinds with the ``errors`` (by name, in :data:`UNITS`), exactly."""
    s, ok = wheel.setting, wheel.valid
    t, rho, nrm = wheel.axial[ok], wheel.radius[ok], wheel.normals[ok]
    a = s.center_distance + errors.get("center_distance", 0.0) - errors.get("wheel_radius", 0.0)
    angle = s.crossing_angle + math.radians(errors.get("crossing_angle", 0.0))
    s = dataclasses.replace(s, center_distance=a, crossing_angle=angle)
    d = errors.get("wheel_profile", 0.0)  # dressed thicker along the wheel's outward normal
    t = t + errors.get("axial_position", 0.0) + d * nrm[:, 0]
    rho = rho - errors.get("wheel_radius", 0.0) + d * nrm[:, 1]
    return rotor_from_wheel(t, rho, nrm, s)[0]


def normal_deviation(wheel: WheelProfile, errors: dict[str, float]) -> Array:
    """Return the rotor's normal deviation (mm, + thicker) for the ``errors`` (by name, :data:`UNITS`).

    The ground points (closed form, not linearised) against the design's points along the design's
    outward normals: exact for the ground point's offset, first order in its slide along the flank.

    Parameters
    ----------
    wheel : WheelProfile
        The wheel made for the rotor.
    errors : dict
        Error sizes by the names of :data:`ERRORS`.

    Returns
    -------
    (n,) float array, mm
        At the flute's points with a contact.
    """
    ok = wheel.valid
    n = perp_cw(wheel.flute.tangents[ok])
    return np.einsum("ij,ij->i", _ground(wheel, errors) - wheel.flute.points[ok], n)


def compensate(wheel: WheelProfile, errors: dict[str, float], free: tuple[str, ...] = ("crossing_angle",)) -> dict[str, float]:
    """Find the setting corrections that minimise the rms normal deviation the ``errors`` cause.

    Gauss-Newton on :func:`normal_deviation` (its Jacobian by central differences over the
    corrections, :data:`STEPS`), five steps, over the points where the wheel touches the rotor in
    every trial.

    Parameters
    ----------
    wheel : WheelProfile
        The wheel made for the rotor.
    errors : dict
        The errors to compensate (e.g. ``{"wheel_radius": 20.0}``: a worn wheel left at the new one's
        profile).
    free : tuple of str
        The errors used as corrections (names of :data:`ERRORS`; one also in ``errors`` adds to it).

    Returns
    -------
    dict
        The corrections by name (:data:`UNITS`).
    """
    x = np.zeros(len(free))

    def residual(v: Array) -> Array:
        merged = dict(errors)
        for name, value in zip(free, v, strict=True):  # a correction adds to an error of the same name
            merged[name] = merged.get(name, 0.0) + float(value)
        return normal_deviation(wheel, merged)

    for _ in range(5):
        r = residual(x)
        jac = np.column_stack(
            [
                (residual(x + STEPS[k] * e) - residual(x - STEPS[k] * e)) / (2 * STEPS[k])
                for k, e in zip(free, np.eye(len(free)), strict=True)
            ]
        )
        ok = np.isfinite(r) & np.isfinite(jac).all(axis=1)  # wheel points that touch the rotor in every trial
        if ok.sum() < len(free):
            break
        x = x - np.linalg.lstsq(jac[ok], r[ok], rcond=None)[0]
    return dict(zip(free, (float(v) for v in x), strict=True))


def sensitivities(wheel: WheelProfile) -> Sensitivity:
    """Compute the rotor's normal deviation per unit error for each of :data:`ERRORS` (module docstring).

    Parameters
    ----------
    wheel : WheelProfile
        The wheel made for the rotor (:func:`rotorcad.grinding.wheel_profile`).

    Returns
    -------
    Sensitivity
    """
    ok = wheel.valid
    p = wheel.flute.points[ok]
    n = perp_cw(wheel.flute.tangents[ok])
    rows = []
    for name in ERRORS:
        h = STEPS[name]
        plus, minus = _ground(wheel, {name: h}), _ground(wheel, {name: -h})
        rows.append(np.einsum("ij,ij->i", plus - minus, n) / (2 * h))
    return Sensitivity(p, np.array(rows))


__all__ = ["ERRORS", "STEPS", "UNITS", "Sensitivity", "compensate", "normal_deviation", "sensitivities"]

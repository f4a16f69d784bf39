"""The setting of a form-grinding wheel against a helical rotor: axes, crossing angle, centre distance.

The rotor turns about the z axis; its flanks are the helicoid of its transverse profile,
``r(u, theta) = Rz(theta) P(u) + (0, 0, theta / k)`` with the twist ``k = 2 pi / h`` (rad/mm;
``h`` the signed lead, > 0 right hand: the section turns counter-clockwise going up, as
:mod:`rotorcad.solids`; ``k = 0`` a spur gear). The wheel is a solid of revolution whose axis
crosses the rotor's on the common perpendicular, the x axis: it passes through ``W0 = (A, 0, 0)``
(``A`` the centre distance, the shortest distance of the axes) with the direction
``a = (0, cos S, -sin S)``. ``S`` is the crossing angle: the angle between the wheel's mid-plane and
the rotor axis (the wheel head's swivel angle). With ``S`` the helix angle at a radius ``r``
(``tan S = k r``) the wheel's mid-plane holds the helix tangent of the point ``(r, 0, 0)``: the
usual setting (Stosic, Smith & Kovacevic, *Screw Compressors: Mathematical Modelling and
Performance Calculation*, Springer 2005, on rotor manufacture: the tool set at the rotor's helix
angle). The angle between the two axes is then 90 deg - |S|.

A point of the wheel's axial profile is ``(t, rho)``: its axial coordinate along ``a`` from ``W0``
and its radius (distance from the wheel axis), mm.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from rotorcad.errors import DesignError, GeometryError
from rotorcad.geometry import Array

MAX_WHEEL_RADIUS = 2000.0
"""Largest wheel radius accepted, mm (a 4 m wheel)."""


@dataclass(frozen=True)
class GrindingSetting:
    """Where the wheel sits against the rotor.

    Parameters
    ----------
    wheel_radius : float, mm
        The wheel's outside radius, the one that grinds the rotor's root (new or worn).
    center_distance : float, mm
        Shortest distance ``A`` between the rotor axis and the wheel axis.
    crossing_angle : float, rad
        Angle ``S`` between the wheel's mid-plane and the rotor axis, signed like the helix
        (> 0 for a right-hand rotor); the axes make 90 deg - |S|.
    twist : float, rad/mm
        ``k = 2 pi / h`` of the rotor's signed lead ``h`` (0 for a spur gear).
    """

    wheel_radius: float
    center_distance: float
    crossing_angle: float
    twist: float

    def __post_init__(self) -> None:
        if not (math.isfinite(self.wheel_radius) and 0.0 < self.wheel_radius <= MAX_WHEEL_RADIUS):
            raise DesignError("wheel_radius", f"a radius above 0 and at most {MAX_WHEEL_RADIUS:g} mm", self.wheel_radius)
        if not (math.isfinite(self.center_distance) and self.center_distance > 0.0):
            raise DesignError("center_distance", "a distance above 0 mm", self.center_distance)
        if not (math.isfinite(self.crossing_angle) and abs(self.crossing_angle) < math.radians(80.0)):
            raise DesignError("crossing_angle", "an angle between -80 and 80 deg", math.degrees(self.crossing_angle))
        if not math.isfinite(self.twist):
            raise DesignError("twist", "a finite twist (rad/mm)", self.twist)

    @property
    def axis_point(self) -> Array:
        """``W0 = (A, 0, 0)``: where the wheel axis meets the common perpendicular, (3,) mm."""
        return np.array([self.center_distance, 0.0, 0.0])

    @property
    def axis(self) -> Array:
        """Unit direction ``a = (0, cos S, -sin S)`` of the wheel axis, (3,)."""
        return np.array([0.0, math.cos(self.crossing_angle), -math.sin(self.crossing_angle)])

    def meridian(self, points: Array) -> tuple[Array, Array]:
        """Axial coordinate and radius of 3D points about the wheel axis.

        Parameters
        ----------
        points : (..., 3) float array, mm
            Points in the rotor's frame.

        Returns
        -------
        t, rho : (...) float arrays, mm
            ``t = (p - W0) . a`` and the distance from the axis.
        """
        d = np.asarray(points, dtype=float) - self.axis_point
        t = d @ self.axis
        rho = np.sqrt(np.maximum(np.einsum("...i,...i->...", d, d) - t * t, 0.0))
        return t, rho


def helix_crossing_angle(twist: float, radius: float) -> float:
    """Return the helix angle of a rotor at ``radius``: the default crossing angle, rad.

    ``tan beta = k r`` with the twist ``k = 2 pi / h`` (signed by the hand).

    Parameters
    ----------
    twist : float, rad/mm
        Twist of the rotor.
    radius : float, mm
        Radius of the helix the wheel's mid-plane follows (the pitch radius by default).

    Returns
    -------
    float
        The angle, rad, signed like ``twist``.
    """
    return math.atan(twist * radius)


def default_setting(
    twist: float,
    root_radius: float,
    wheel_radius: float,
    setting_radius: float,
    crossing_angle: float | None = None,
    center_distance: float | None = None,
    tip_radius: float | None = None,
) -> GrindingSetting:
    """Make the setting a grinding engineer starts from.

    The crossing angle is the helix angle at ``setting_radius`` (:func:`helix_crossing_angle`) and
    the centre distance ``A = root radius + wheel radius``: the wheel's outside circle plunges to
    the rotor's root circle, so that the outside radius the dresser keeps is the one that grinds
    the root (as the wheel wears, ``A`` follows it down).

    Parameters
    ----------
    twist : float, rad/mm
        ``2 pi / h`` of the signed lead.
    root_radius : float, mm
        The rotor's root radius (least radius of its outline).
    wheel_radius : float, mm
        The wheel's outside radius.
    setting_radius : float, mm
        Radius whose helix angle sets the crossing angle.
    crossing_angle : float, optional, rad
        Given instead of the default.
    center_distance : float, optional, mm
        Given instead of the default.
    tip_radius : float, optional, mm
        The rotor's tip radius: the wheel axis must pass outside the tip circle (else the wheel's
        hub meets the lobes). Default: not checked.

    Returns
    -------
    GrindingSetting

    Raises
    ------
    DesignError
        A wheel radius out of range, or one that puts the wheel axis inside the tip circle
        (``wheel_radius``, a :class:`GeometryError`); a given centre distance not above the tip
        radius or more than root radius + :data:`MAX_WHEEL_RADIUS` (``center_distance``).
    """
    if not (math.isfinite(setting_radius) and setting_radius > 0.0):
        raise DesignError("setting_radius", "a radius above 0 mm", setting_radius)
    angle = helix_crossing_angle(twist, setting_radius) if crossing_angle is None else crossing_angle
    if not (math.isfinite(wheel_radius) and 0.0 < wheel_radius <= MAX_WHEEL_RADIUS):
        raise DesignError("wheel_radius", f"a radius above 0 and at most {MAX_WHEEL_RADIUS:g} mm", wheel_radius)
    inner = root_radius if tip_radius is None else tip_radius
    if center_distance is None:
        if not root_radius + wheel_radius > inner:
            raise GeometryError(
                "wheel_radius",
                f"more than the flute's depth {inner - root_radius:.6g} mm (tip radius - root radius)",
                wheel_radius,
                "the wheel axis would pass inside the rotor's tip circle",
            )
        a = root_radius + wheel_radius
    else:
        a = center_distance
        if not (math.isfinite(a) and inner < a <= root_radius + MAX_WHEEL_RADIUS):
            raise GeometryError(
                "center_distance",
                f"more than the rotor's {'tip' if tip_radius is not None else 'root'} radius {inner:.6g} mm and at most "
                f"{root_radius + MAX_WHEEL_RADIUS:.6g} mm (root radius + {MAX_WHEEL_RADIUS:g} mm)",
                a,
            )
    return GrindingSetting(float(wheel_radius), float(a), float(angle), float(twist))


__all__ = ["MAX_WHEEL_RADIUS", "GrindingSetting", "default_setting", "helix_crossing_angle"]

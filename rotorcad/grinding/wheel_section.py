"""The whole axial section of the form-grinding wheel: its profile closed by shoulders, side faces, bore.

The wheel is a disc of a stated width ``W`` about its mid-plane (``t = 0``, through the common
perpendicular of the axes). Its profile (:mod:`rotorcad.grinding.wheel_profile`) ends at the
flute's two tip points; beside them the wheel's outside surface drops to the shoulder radius
``rho_s = A - r_tip`` (``A`` the centre distance, ``r_tip`` the rotor's tip radius) and runs as a
cylinder to the side faces at ``t = -W/2`` and ``t = +W/2``, which are planes down to the bore
radius. No point of the shoulders or side faces touches the rotor: a rotor point ``(x, y, z)`` with
``x^2 + y^2 <= r_tip^2 < A^2`` lies ``sqrt((A - x)^2 + (y sin S + z cos S)^2) >= A - x >= A - r_tip``
from the wheel axis (:mod:`rotorcad.grinding.setting`), and every end of the profile lies at least
that far out (its tip points lie on the tip cylinder).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from rotorcad.errors import DesignError
from rotorcad.geometry import Array
from rotorcad.grinding.wheel_profile import WheelProfile

STANDARD_BORE_RADIUS = 63.5
"""Default bore radius, mm: the 127 mm bore common on profile-grinding wheels (ISO 603-1 sizes)."""
SIDE_MARGIN = 1.0
"""Default axial margin (mm) between the profile's farthest end and the side face."""


@dataclass(frozen=True, eq=False)
class WheelSection:
    """The closed axial section of the wheel (module docstring).

    Attributes
    ----------
    wheel : WheelProfile
        The profile.
    width : float, mm
        ``W``: the distance of the side faces.
    bore_radius : float, mm
        Radius of the bore.
    shoulder_radius : float, mm
        ``rho_s = A - r_tip``.
    """

    wheel: WheelProfile
    width: float
    bore_radius: float
    shoulder_radius: float

    def outline(self) -> Array:
        """Return the closed section, (m, 2) mm: ``(t, rho)`` counter-clockwise, first point not repeated.

        From the profile's end of least ``t`` the profile to its other end, down to the shoulder,
        along it to the side face ``t = W/2``, down to the bore, along the bore to ``t = -W/2``, up to
        the shoulder and back to the profile's first end.
        """
        w = self.wheel
        t, r = w.axial[w.valid], w.radius[w.valid]
        if t[0] > t[-1]:
            t, r = t[::-1], r[::-1]
        # the profile runs from -t to +t with the material below it: travelled so, the section is clockwise
        ring = np.vstack([np.column_stack([t, r]), self.sides()[::-1][1:-1]])
        keep = np.r_[True, np.hypot(*np.diff(ring, axis=0).T) > 1e-12]  # a zero step where an end lies on the shoulder
        return ring[keep][::-1]

    def sides(self) -> Array:
        """Return what closes the profile, (k, 2) mm: from its end of least ``t`` round to its other end.

        Counter-clockwise like :meth:`outline`: down to the shoulder, along it to the side face
        ``t = -W/2``, down to the bore, along it to ``t = W/2``, up to the shoulder and along it, up to
        the profile's end of largest ``t``. The profile and this chain make the closed section.
        """
        w = self.wheel
        t, r = w.axial[w.valid], w.radius[w.valid]
        if t[0] > t[-1]:
            t, r = t[::-1], r[::-1]
        h, s, b = 0.5 * self.width, self.shoulder_radius, self.bore_radius
        chain = np.array([[t[0], r[0]], [t[0], s], [-h, s], [-h, b], [h, b], [h, s], [t[-1], s], [t[-1], r[-1]]])
        keep = np.r_[True, np.hypot(*np.diff(chain, axis=0).T) > 1e-12]
        return chain[keep]


def wheel_section(wheel: WheelProfile, width: float | None = None, bore_radius: float | None = None) -> WheelSection:
    """Close a wheel profile into the wheel's section.

    Parameters
    ----------
    wheel : WheelProfile
        The profile (its flute's tip radius and setting give the shoulder).
    width : float, mm, optional
        Distance of the side faces, at least twice the farthest profile end's ``|t|``. Default that
        plus :data:`SIDE_MARGIN` each side, rounded up to a whole mm.
    bore_radius : float, mm, optional
        Above 0 and below the shoulder radius. Default :data:`STANDARD_BORE_RADIUS`, or half the
        shoulder radius on a wheel too small for it.

    Returns
    -------
    WheelSection

    Raises
    ------
    DesignError
        A profile without contact (``wheel``), a width the profile does not fit (``wheel_width``), a
        bore out of range (``bore_radius``).
    """
    ok = wheel.valid
    if ok.sum() < 2:
        raise DesignError("wheel", "a profile of two points or more in contact", int(ok.sum()))
    t = wheel.axial[ok]
    reach = float(max(abs(t[0]), abs(t[-1]), np.abs(t).max()))
    least = 2.0 * reach
    if width is None:
        width = float(math.ceil(least + 2.0 * SIDE_MARGIN))
    if not (math.isfinite(width) and least <= width <= 1e4):
        raise DesignError("wheel_width", f"at least {least:.6g} mm (the profile between the side faces) and at most 10000", width)
    s = wheel.setting
    shoulder = s.center_distance - wheel.flute.tip_radius
    if bore_radius is None:
        bore_radius = STANDARD_BORE_RADIUS if STANDARD_BORE_RADIUS < 0.9 * shoulder else 0.5 * shoulder
    if not (math.isfinite(bore_radius) and 0.0 < bore_radius < shoulder):
        raise DesignError("bore_radius", f"above 0 and below the shoulder radius {shoulder:.6g} mm", bore_radius)
    return WheelSection(wheel, float(width), float(bore_radius), float(shoulder))


__all__ = ["SIDE_MARGIN", "STANDARD_BORE_RADIUS", "WheelSection", "wheel_section"]

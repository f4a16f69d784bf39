"""The one angle convention of every angle rotorcad shows (Rinder Figs. 10-13, sec. 3.2).

phi = the male rotation still to go until the middle of a male tip reaches the line of centres
O1O2 (positive before, negative after): :data:`ANGLE_CONVENTION`, its zero :func:`tip_on_centre_line`.
"""

from __future__ import annotations

import numpy as np

from rotorcad.geometry import wrap_angle

ANGLE_CONVENTION = (
    "male rotation still to go until the middle of a male tip reaches the line of centres O1O2 "
    "(positive before, negative after; Rinder Figs. 10-13)"
)


def tip_on_centre_line(outline: np.ndarray, teeth: int, tip_radius: float, tolerance: float, angles: np.ndarray) -> float:
    """Return the male rotation (rad) at which the middle of a male tip lies on O1O2.

    The zero of the one angle convention (:data:`ANGLE_CONVENTION`, :meth:`MeshingAnalysis.rinder_angle`):
    the tip land is the outline's points within ``tolerance`` of ``tip_radius`` (the outermost
    point when none is), folded over the lobes; the male turns counter-clockwise, so a point at
    polar angle b is on O1O2 at rotation -b. Of the passages one pitch apart, the one nearest the
    middle of ``angles``.

    Parameters
    ----------
    outline : (n, 2) float array, mm
        The male outline (one lobe or more) in its own frame.
    teeth : int
        Male lobe count z1.
    tip_radius : float, mm
        Male tip radius.
    tolerance : float, mm
        How near the tip radius a point of the tip land lies.
    angles : (m,) float array, rad
        Male rotation angles of the contacts the convention is for (the meshline's, the
        clearance's), in the meshing engine's count.

    Returns
    -------
    float, rad
    """
    r = np.hypot(*outline.T)
    top = outline[r >= tip_radius - tolerance]
    if len(top) == 0:
        top = outline[[int(np.argmax(r))]]
    pitch = 2 * np.pi / teeth
    beta = np.arctan2(top[:, 1], top[:, 0])
    b0 = float(np.angle(np.exp(1j * teeth * beta).mean())) / teeth  # one tip, folded over the lobes
    near = wrap_angle(beta, b0, pitch)  # the tip points of every lobe, folded onto that one
    t_ref = -0.5 * (float(near.min()) + float(near.max()))
    mid = 0.5 * (float(np.min(angles)) + float(np.max(angles))) if len(angles) else 0.0
    return t_ref + pitch * round((mid - t_ref) / pitch)

"""The grinding chart: the wheel's axial profile (new and worn) and the rotor's sensitivities.

Imported only when a picture is drawn (matplotlib).
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from rotorcad import plot_style as ps
from rotorcad.grinding.sensitivity import ERRORS, UNITS, Sensitivity
from rotorcad.grinding.wheel_profile import WheelProfile

if TYPE_CHECKING:
    from matplotlib.figure import Figure

SHOWN_ERROR = {"mm": 0.01, "deg": 0.01}
"""The error each sensitivity curve is drawn for: 10 um, 0.01 deg."""


@ps.styled
def grinding_chart(wheels: dict[str, WheelProfile], sensitivity: Sensitivity, case: str) -> Figure:
    """Draw the wheels' axial profiles and the rotor's normal deviation for each setting error.

    Parameters
    ----------
    wheels : dict of WheelProfile
        By state (``new``, ``worn``).
    sensitivity : Sensitivity
        Of the new wheel (:func:`rotorcad.grinding.sensitivities`).
    case : str
        The title's first line.

    Returns
    -------
    matplotlib.figure.Figure
        Left the profiles (radius over axial coordinate), right the deviation along the flute (its
        arc length from the first tip) for an error of 10 um or 0.01 deg each.
    """
    fig = ps.new_figure(12.0, 5.0)
    left, right = fig.subplots(1, 2)
    for (state, wheel), colour in zip(wheels.items(), (ps.BLUE, ps.ORANGE), strict=False):
        ok = wheel.valid
        s = wheel.setting
        left.plot(
            wheel.axial[ok],
            wheel.radius[ok],
            color=colour,
            label=f"{state}: R = {s.wheel_radius:g} mm, A = {s.center_distance:.6g} mm",
        )
    left.set_xlabel(ps.label("axial coordinate from the wheel's mid-plane", "mm"))
    left.set_ylabel(ps.label("wheel radius", "mm"))
    ps.legend_below(left, ncol=1)
    arc = np.concatenate([[0.0], np.cumsum(np.hypot(*np.diff(sensitivity.points, axis=0).T))])
    for name, row, colour in zip(ERRORS, sensitivity.per_unit, ps.CYCLE, strict=False):
        unit = UNITS[name]
        size = SHOWN_ERROR[unit]
        shown = f"{size * 1e3:g} µm" if unit == "mm" else f"{size:g}°"
        text = f"wheel worn {shown}, profile kept" if name == "wheel_radius" else f"{name.replace('_', ' ')} +{shown}"
        right.plot(arc, row * size * 1e3, color=colour, label=text)
    right.axhline(0.0, color=ps.GREY, lw=0.8)
    right.set_xlabel(ps.label("along the flute from its first tip", "mm"))
    right.set_ylabel(ps.label("rotor's normal deviation (+ thicker)", "µm"))
    ps.legend_below(right, ncol=2)
    ps.title(fig, case, f"crossing angle {np.degrees(next(iter(wheels.values())).setting.crossing_angle):.4g}°")
    return fig


__all__ = ["grinding_chart"]

"""Files for the wheel dresser: the form-grinding wheel's axial profile as CSV and DXF (mm).

The profile is the wheel's axial section: x the axial coordinate from the wheel's mid-plane (the
plane through the common perpendicular of the axes), y the radius from the wheel axis, both mm
(:mod:`rotorcad.grinding`). The CSV also gives the profile's outward unit normal and the rotor point
each wheel point grinds; the DXF draws the profile as an open polyline on the layer WHEEL, what
closes it into the whole wheel section (shoulders, side faces and bore:
:mod:`rotorcad.grinding.wheel_section`) as an open polyline from one end of the profile to the
other on WHEEL_SECTION (the profile is not drawn twice: an R12 polyline of 2000 vertices costs
0.1 s to write), the wheel axis (y = 0) and the mid-plane (x = 0) on CENTER, and a one-line label
on LABELS.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from exports.csv_points import write_points
from exports.dxf import Drawing, write_dxf

CSV_HEADER = "axial,radius,normal_axial,normal_radial,rotor_x,rotor_y"
"""Columns of the wheel CSV: axial coordinate and radius (mm), outward unit normal, the rotor point (mm)."""


def write_wheel_csv(path: Path, rows: np.ndarray, comments: list[str]) -> None:
    """Write the wheel profile's rows (:data:`CSV_HEADER`) with full double precision.

    Parameters
    ----------
    path : Path
        The file.
    rows : (n, 6) float array
        Axial coordinate, radius (mm), normal (axial, radial), rotor point x, y (mm), in profile order.
    comments : list of str
        Lines written first, each after ``# `` (the setting).
    """
    write_points(path, rows, comments, header=CSV_HEADER)


def wheel_drawing(axial: np.ndarray, radius: np.ndarray, label: str, section: np.ndarray | None = None) -> Drawing:
    """Draw the wheel's axial section: profile, closed section, axis, mid-plane and a label.

    Parameters
    ----------
    axial, radius : (n,) float arrays, mm
        The profile in order.
    label : str
        One line of text (the setting).
    section : (m, 2) float array, mm, optional
        What closes the profile ``(axial, radius)`` from one of its ends to the other, drawn on
        WHEEL_SECTION.

    Returns
    -------
    Drawing
        For :func:`exports.dxf.write_dxf` (R12 or R2000).
    """
    t0, t1 = float(axial.min()), float(axial.max())
    if section is not None:
        t0, t1 = min(t0, float(section[:, 0].min())), max(t1, float(section[:, 0].max()))
    top = float(radius.max())
    d = Drawing(mark_size=0.02 * top)
    d.polylines.append(("WHEEL", np.column_stack([axial, radius])))
    if section is not None:
        d.polylines.append(("WHEEL_SECTION", np.asarray(section, dtype=float)))
    d.lines.append(("CENTER", (t0, 0.0), (t1, 0.0)))
    d.lines.append(("CENTER", (0.0, 0.0), (0.0, top)))
    d.texts.append(("LABELS", (t0, top + 0.05 * top), label, 0.02 * top))
    return d


def write_wheel_dxf(
    path: Path, axial: np.ndarray, radius: np.ndarray, label: str, version: str, section: np.ndarray | None = None
) -> None:
    """Write the wheel's axial section as DXF ``version`` (``"R12"`` or ``"R2000"``), mm.

    Parameters
    ----------
    path : Path
        The file.
    axial, radius : (n,) float arrays, mm
        The profile in order.
    label : str
        One line of text.
    version : str
        DXF version.
    section : (m, 2) float array, mm, optional
        What closes the profile into the wheel's section (layer WHEEL_SECTION).
    """
    write_dxf(path, wheel_drawing(axial, radius, label, section), version)


__all__ = ["CSV_HEADER", "wheel_drawing", "write_wheel_csv", "write_wheel_dxf"]

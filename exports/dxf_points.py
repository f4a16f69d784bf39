"""Measured points from a CSV file or a DXF drawing, as a CMM writes them: POINT entities, or a drawn chain.

A coordinate-measuring machine's DXF often holds the probed points as POINT entities; a drawing
of a profile (lines, arcs, polylines, splines end to end) is sampled along its chain by
:func:`exports.dxf_profile.sample_profile_dxf`, and a CSV file is read by
:func:`exports.csv_points.read_points`.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from exports.csv_points import check_profile
from exports.dxf_profile import _is_drawing, _load, read_profile_points, sample_profile_dxf
from rotorcad.errors import DesignError

FLAT = 1e-6
"""mm: POINT entities whose z differ by more than this do not lie in one transverse section."""


def read_measured_points(path: Path, label: str, layer: str | None = None) -> np.ndarray:
    """Read measured points: a DXF's POINT entities if it has any, else its profile chain, or a CSV file.

    Parameters
    ----------
    path : Path
        The file (DXF by its name or first bytes, else CSV ``x,y``).
    label : str
        The option or key that named the file; it leads the error sentence.
    layer : str or None
        Layer of the points or the profile in a DXF drawing (case-insensitive); None: all of them.

    Returns
    -------
    (n, 2) float array, mm
        The points (a POINT's x and y; consecutive repeats dropped).

    Raises
    ------
    DesignError
        As :func:`exports.dxf_profile.read_profile_points`; POINT entities at different heights z,
        or fewer than 4 of them, or all on one line (naming ``label``).
    """
    if not _is_drawing(path, label):
        return read_profile_points(path, label, layer)
    doc = _load(path, label)
    points = [
        entity.dxf.location
        for entity in doc.modelspace().query("POINT")
        if layer is None or entity.dxf.layer.casefold() == layer.casefold()
    ]
    if not points:
        return sample_profile_dxf(path, label, layer)
    xyz = np.array([(p.x, p.y, p.z) for p in points], dtype=float)
    if np.ptp(xyz[:, 2]) > FLAT:
        raise DesignError(
            label,
            "POINT entities in one plane z = const (one transverse section)",
            str(path),
            f"their z run from {xyz[:, 2].min():g} to {xyz[:, 2].max():g} mm",
        )
    return check_profile(xyz[:, :2], label, str(path))


__all__ = ["read_measured_points"]

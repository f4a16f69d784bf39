"""The work a request implies, estimated before it starts.

Issue 15: refuse what this machine cannot do, with the largest value that would work, instead of
growing to gigabytes or crashing.

A profile sampled to a chord tolerance t has a number of points that grows like 1/sqrt(t) (the
sagitta of a chord of length c on radius R is c^2 / (8 R)); a helical solid (:mod:`rotorcad.solids`)
has ``2 x points x layers`` side triangles, with ``layers`` growing like the wrap angle times
1/sqrt(t). So the triangles grow like 1/t and like 1/lead.
"""

from __future__ import annotations

import numpy as np
import shapely

from rotorcad.solids import layers_for

MAX_TRIANGLES = 4_000_000
"""Most triangles of the solids of one request: some 330 bytes a triangle at the peak while they
are swept, meshed and written (measured: 5.7 M triangles, 1.9 GB), so about 1.3 GB at the limit."""

MAX_SECTION_POINTS = 60_000
"""Most points of the two sections of an interference sweep: each is turned to 360 angles at
once (some 64 bytes a point and angle, 1.4 GB at the limit)."""


def points_at(section: shapely.Polygon, tolerance: float, target: float) -> float:
    """Points of ``section`` (sampled to ``tolerance``) scaled to the tolerance ``target``.

    Parameters
    ----------
    section : shapely.Polygon
        A section sampled to the chord tolerance ``tolerance`` (mm).
    tolerance : float
        Its tolerance, mm.
    target : float
        The tolerance asked for, mm.

    Returns
    -------
    float
        The estimated number of points at ``target`` (points grow like 1/sqrt(tolerance)).
    """
    return (len(section.exterior.coords) - 1) * float(np.sqrt(tolerance / target))


def solid_triangles(points: float, lead: float, length: float, r_max: float, tolerance: float) -> float:
    """Side triangles of a helical solid of a section of ``points`` points.

    Parameters
    ----------
    points : float
        Points of the section at the surface tolerance.
    lead : float
        Lead of the helix, mm (any sign; infinite for a straight extrusion).
    length : float
        Length of the solid, mm.
    r_max : float
        Largest radius of the section, mm.
    tolerance : float
        Surface tolerance, mm.

    Returns
    -------
    float
        ``2 x points x layers`` with the layers of :func:`rotorcad.solids.layers_for`.
    """
    wrap = 0.0 if not np.isfinite(lead) else 2.0 * np.pi * length / abs(lead)
    layers = max(1.0, abs(wrap) * np.sqrt(r_max / (4.0 * tolerance))) if wrap else 1.0
    if wrap and layers < 1e15:
        layers = float(layers_for(tolerance, wrap, r_max))
    return 2.0 * points * layers


__all__ = ["MAX_SECTION_POINTS", "MAX_TRIANGLES", "points_at", "solid_triangles"]

"""The mesh of a gear as a part: its helical (or herringbone) teeth, bore, keyway and hub (manifold3d).

The teeth are the helical solid of the section (:func:`rotorcad.solids.helical_solid`: ruled layers
chosen for the surface tolerance); a herringbone gear's second half is the first one mirrored in
the mid plane z = b/2. The bore with its keyway and the hub are straight prisms of polygons
inscribed in their circles with chords sagging at most the tolerance, cut from and joined to the
teeth by manifold3d's booleans.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import cached_property

import numpy as np
import shapely

from rotorcad.gears.features import SolidFeatures
from rotorcad.triangle_mesh import TriangleMesh


@dataclass(frozen=True, eq=False)
class PartSolid:
    """A gear part's solid as manifold3d made it (what a placed body's mesh needs).

    Attributes
    ----------
    manifold : manifold3d.Manifold
        The solid.
    tolerance : float, mm
        The surface tolerance it was made to.
    """

    manifold: object
    tolerance: float

    @cached_property
    def triangle_mesh(self) -> TriangleMesh:
        """The solid's triangles, float64, mm."""
        m = self.manifold.to_mesh64()
        return TriangleMesh(np.asarray(m.vert_properties)[:, :3], np.asarray(m.tri_verts))

    @property
    def mesh(self) -> TriangleMesh:
        """The same as :attr:`triangle_mesh` (its ``faces`` count the triangles)."""
        return self.triangle_mesh

    @property
    def volume(self) -> float:
        """The mesh's volume, mm³."""
        return float(self.manifold.volume())


def _prism(ring: np.ndarray, z0: float, z1: float):
    """Return a straight prism of a counter-clockwise ring from z0 to z1 (manifold3d)."""
    import manifold3d as m3

    section = m3.CrossSection([np.asarray(ring, dtype=float)], m3.FillRule.Positive)
    return m3.Manifold.extrude(section, z1 - z0).translate((0.0, 0.0, z0))


def _circle(radius: float, tolerance: float) -> np.ndarray:
    """Return a polygon inscribed in a circle, its chords sagging at most ``tolerance`` (at least 32 sides)."""
    n = max(32, math.ceil(math.pi / math.acos(max(1.0 - tolerance / radius, -1.0))))
    a = np.linspace(0.0, 2 * math.pi, n, endpoint=False)
    return np.column_stack([radius * np.cos(a), radius * np.sin(a)])


def part_solid(section: shapely.Polygon, lead: float, face_width: float, tolerance: float, features: SolidFeatures) -> PartSolid:
    """Make the mesh of a gear part.

    Parameters
    ----------
    section : shapely.Polygon
        The transverse section (its exterior, the teeth) in mesh, mm.
    lead : float, mm
        Signed lead (> 0 right hand); inf for a spur gear.
    face_width : float, mm
        b, from z = 0.
    tolerance : float, mm
        Surface tolerance (the helical layers, the circles' chords).
    features : SolidFeatures
        Bore, keyway, hub, herringbone.

    Returns
    -------
    PartSolid
    """
    from rotorcad.solids import helical_solid

    half = face_width / 2 if features.herringbone else face_width
    lead = lead if np.isfinite(lead) else 1e12 * face_width
    teeth = helical_solid(section, lead, half, tolerance).manifold
    if features.herringbone:  # the second half: the first mirrored in z = b/2
        teeth = teeth + teeth.mirror((0.0, 0.0, 1.0)).translate((0.0, 0.0, face_width))
    if features.hub_radius > 0:
        teeth = teeth + _prism(_circle(features.hub_radius, tolerance), -features.hub_length, 0.0)
    if features.bore_radius > 0:
        # the hole's circle inscribed too: its chords sag inwards into the hole, at most the tolerance
        hole = features.hole_points(tolerance)
        teeth = teeth - _prism(hole, -features.hub_length - 1.0, face_width + 1.0)
    return PartSolid(teeth, float(tolerance))


__all__ = ["PartSolid", "part_solid"]

"""The spatial blow-hole of a screw-rotor pair (Rinder sec. 2.2.2).

The curvilinear triangle of the screw-compressor literature (e.g. Stosic, Smith & Kovacevic,
*Screw Compressors*, 2005, sec. 2.4). Where the contact line stops short of the housing cusp, gas
leaks through a curved triangle whose sides lie on the male tip cylinder, on the female tip
cylinder and on the housing cusp line (the intersection of the two bores, parallel to the axes).
Its apex is the contact line's end E nearest the cusp (Rinder eq. 1: z = h alpha / 2 pi).
Definition used here (the paper gives no formula):

* the male side: the male tip helix from the radial projection of E on the male tip circle (at the
  height of E) to where that helix meets the cusp line; the section at height z shows the male
  turned by 2 pi z / h1 and the female by -2 pi z / h2 (the convention of the contact line);
* the female side likewise on the female tip cylinder about O2;
* the cusp line between the two meeting points, and the two radial pieces from E to its
  projections;
* the surface: the cone of straight segments from the apex E to this boundary. Its area is the
  spatial blow-hole area; its projection on the transverse plane is the projected blow-hole of
  :class:`rotorcad.meshing.MeshingAnalysis`.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property

import numpy as np

from rotorcad.geometry import wrap_angle
from rotorcad.rotor_pair import RotorPair


def apex_height(angle: float, reference: float, lead: float, teeth: int) -> float:
    """Return the height z of a contact at male rotation ``angle`` (Rinder eq. 1: z = h1 alpha / 2 pi), mm.

    Measured from the transverse section in which the middle of the nearest male tip lies on the line
    of centres O1O2 (the zero of the one angle convention, :mod:`rotorcad.meshing.angles`): alpha is the
    male rotation since that tip's passage, within +-pi/z1, so z lies within +-h1/(2 z1). The contact
    line's own start (its lowest contact) is no reference: it is where the lobe was cut, which the
    family, a drawing or points place differently. The narrow-tip apex lies 20.92 mm of z past the
    meshing engine's zero in every form, but the design's contact line started 22.24 mm below that
    (where its root arc's stationary contact was cut) and the one of its DXF splines 18.17 mm below,
    so the apex read 43.16 and 39.09 mm (30.78 from its polyline, 80.63 from its female's drawing).

    Parameters
    ----------
    angle : float, rad
        Male rotation of the contact (the meshing engine's count).
    reference : float, rad
        Male rotation at which the middle of a male tip lies on O1O2
        (:attr:`rotorcad.meshing.MeshingAnalysis.angle_reference`).
    lead : float, mm
        Male lead h1.
    teeth : int
        Male lobe count z1.

    Returns
    -------
    float, mm
    """
    pitch = 2 * np.pi / teeth
    alpha = float(wrap_angle(angle - reference, 0.0, pitch))
    return lead * alpha / (2 * np.pi)


@dataclass(frozen=True)
class SpatialBlowHole:
    """The blow-hole triangle in 3D of a pair, from the meshline end next to a housing cusp.

    Parameters
    ----------
    pair : RotorPair
        Radii, centre distance, tooth counts and male lead (mm).
    apex : (2,) float, mm
        Meshline end E nearest the cusp, fixed frame.
    apex_z : float, mm
        Its height (Rinder eq. 1), from the section where the nearest male tip's middle lies on O1O2
        (:func:`apex_height`).
    cusp : (2,) float, mm
        The housing cusp K the meshline comes nearest (upper or lower).
    samples : int
        Points per bounding curve.
    """

    pair: RotorPair
    apex: np.ndarray
    apex_z: float
    cusp: np.ndarray
    samples: int = 400

    @property
    def empty(self) -> bool:
        """True when the meshline reaches the cusp (apex within 1 µm of it): there is no blow-hole."""
        return bool(np.hypot(*(self.apex - self.cusp)) < 1e-3)

    def _sweep(self, centre: np.ndarray, radius: float, rate: float) -> tuple[np.ndarray, float]:
        """Trace the tip helix of one rotor from the projection of the apex to the cusp line.

        ``rate`` is the turn of the section per mm of z (rad/mm). Returns the (n, 3) points (mm) and
        the height (mm) where the helix meets the cusp line.
        """
        e = self.apex - centre
        phi_e = float(np.arctan2(e[1], e[0]))
        k = self.cusp - centre
        dphi = float(wrap_angle(float(np.arctan2(k[1], k[0])) - phi_e))
        dz = dphi / rate
        z = self.apex_z + np.linspace(0.0, dz, self.samples)
        ang = phi_e + rate * (z - self.apex_z)
        pts = np.column_stack([centre[0] + radius * np.cos(ang), centre[1] + radius * np.sin(ang), z])
        return pts, self.apex_z + dz

    @cached_property
    def male_tip(self) -> np.ndarray:
        """(n, 3) points on the male tip cylinder r1t, from the apex's projection to the cusp line (mm)."""
        return self._sweep(np.zeros(2), self.pair.male_tip_radius, 2 * np.pi / self.pair.lead)[0]

    @cached_property
    def female_tip(self) -> np.ndarray:
        """(n, 3) points on the female tip cylinder r2t about O2, from the apex's projection to the cusp line (mm)."""
        o2 = np.array([self.pair.center_distance, 0.0])
        return self._sweep(o2, self.pair.female_tip_radius, -2 * np.pi / self.pair.female_lead)[0]

    @cached_property
    def cusp_line(self) -> np.ndarray:
        """(n, 3) points of the housing cusp line between the two tips' meeting points (mm)."""
        z = np.linspace(self.male_tip[-1, 2], self.female_tip[-1, 2], self.samples)
        return np.column_stack([np.full_like(z, self.cusp[0]), np.full_like(z, self.cusp[1]), z])

    @cached_property
    def boundary(self) -> np.ndarray:
        """(m, 3) closed boundary of the triangle, mm.

        In order: apex, male radial piece, male tip, cusp line, female tip reversed, female radial piece
        back to the apex (the first point is repeated at the end).
        """
        a = np.array([*self.apex, self.apex_z])
        return np.vstack([[a], self.male_tip, self.cusp_line[1:], self.female_tip[::-1][1:], [a]])

    @property
    def area(self) -> float:
        """Area of the cone from the apex to the boundary (mm^2): the sum of the fan's triangles."""
        if self.empty:
            return 0.0
        a = np.array([*self.apex, self.apex_z])
        b = self.boundary
        return float(0.5 * np.linalg.norm(np.cross(b[:-1] - a, b[1:] - a), axis=1).sum())

    @property
    def projected_area(self) -> float:
        """Area of the boundary's projection on the transverse plane (mm^2, shoelace)."""
        if self.empty:
            return 0.0
        x, y = self.boundary[:, 0], self.boundary[:, 1]
        return float(0.5 * abs(np.dot(x[:-1], y[1:]) - np.dot(x[1:], y[:-1])))

    @property
    def z_range(self) -> tuple[float, float]:
        """Heights (mm, contact-line frame) between which the triangle lies."""
        z = self.boundary[:, 2]
        return float(z.min()), float(z.max())

    def as_dict(self) -> dict[str, object]:
        """Return the blow-hole's figures as plain values (the ``blow_hole_spatial`` entry of ``MeshingAnalysis.summary``).

        Returns
        -------
        dict
            ``area`` and ``projected_area`` (mm²), ``apex`` [x, y, z] (mm), ``z_min``, ``z_max`` and
            the heights where the male and the female tip helices meet the cusp line (mm,
            contact-line frame).
        """
        lo, hi = self.z_range if not self.empty else (self.apex_z, self.apex_z)
        return {
            "area": self.area,
            "projected_area": self.projected_area,
            "apex": [float(self.apex[0]), float(self.apex[1]), float(self.apex_z)],
            "z_min": lo,
            "z_max": hi,
            "male_tip_meets_cusp_z": float(self.male_tip[-1, 2]),
            "female_tip_meets_cusp_z": float(self.female_tip[-1, 2]),
        }


__all__ = ["SpatialBlowHole", "apex_height"]

"""Cross-section values of a rotor from its real profile (Rinder & Deix, sec. 2 and 2.1).

A transverse section is taken as a closed polygon (the outline sampled to a chord tolerance).
Area, centroid and second moments are exact for that polygon (Green's theorem). The shear
correction factor of eq. (1),

    kappa = A / J^2  *  integral over A of (S(y) / b(y))^2 dA,

with S(y) the first moment about the bending axis of the part of the section above y and b(y) the
section's width at height y, is evaluated from the width profile b(y). For a polygon b(y) is
piecewise linear in y (the sum of the x of the edges crossing y, + for edges running up and - for
edges running down on a counter-clockwise outline), so it is built exactly from the vertices and
integrated on a fine grid. A circle gives 10/9, a rectangle 6/5 (the closed forms the tests use).

For z > 2 lobes the second moment is the same about every axis through the centre (J_x = J_y,
J_xy = 0: the inertia tensor of a section with z-fold symmetry, z > 2, is isotropic); kappa is not,
and is reported over the turn gamma of the section (the paper finds 1.04 .. 1.18).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from rotorcad.errors import DesignError
from rotorcad.geometry import rotate
from rotorcad.profile import polygon_moments


@dataclass(frozen=True)
class SectionValues:
    """Area and second moments of a polygon about its centroid.

    Attributes
    ----------
    area : float
        A, mm^2.
    centroid : tuple[float, float]
        (x, y) of the centroid, mm.
    j_x, j_y, j_xy : float
        Second moments about axes through the centroid parallel to x and y, and the product, mm^4.
    """

    area: float
    centroid: tuple[float, float]
    j_x: float
    j_y: float
    j_xy: float

    @property
    def j(self) -> float:
        """Mean second moment (J_x + J_y) / 2, mm^4: the J of every axis when the section is isotropic."""
        return 0.5 * (self.j_x + self.j_y)


def _ccw(points: np.ndarray) -> np.ndarray:
    """Return the closed outline as an (n, 2) array without the repeated end, counter-clockwise."""
    p = np.asarray(points, dtype=float)
    if p.ndim != 2 or p.shape[1] != 2 or len(p) < 3:
        raise DesignError("section outline", "at least 3 points (x, y)", p.shape)
    if np.allclose(p[0], p[-1]):
        p = p[:-1]
    x, y = p.T
    signed = 0.5 * np.sum(x * np.roll(y, -1) - np.roll(x, -1) * y)
    if not abs(signed) > 0:
        raise DesignError("section outline", "a closed outline enclosing an area", "zero area")
    return p if signed > 0 else p[::-1]


def section_values(points: np.ndarray) -> SectionValues:
    """Area, centroid and centroidal second moments of a closed polygon.

    Parameters
    ----------
    points : (n, 2) float, mm
        The outline, either direction, closed or not.

    Returns
    -------
    SectionValues
        Exact for the polygon (Green's theorem over its edges).
    """
    m = polygon_moments(_ccw(points))  # Green's theorem over the edges (rotorcad.profile)
    area, cx, cy = m["area"], m["cx"], m["cy"]
    return SectionValues(area, (cx, cy), m["Ixx"] - area * cy**2, m["Iyy"] - area * cx**2, m["Ixy"] - area * cx * cy)


def width_profile(points: np.ndarray, levels: np.ndarray) -> np.ndarray:
    """Width b(y) of the section at the heights ``levels`` (total length of the horizontal chords).

    Parameters
    ----------
    points : (n, 2) float, mm
        Closed outline.
    levels : (m,) float, mm
        Heights y.

    Returns
    -------
    (m,) float, mm
        b(y): the sum over the edges crossing y of +x (edge running up) and -x (running down) on
        the counter-clockwise outline; exact for the polygon.
    """
    p = _ccw(points)
    a, b = p, np.roll(p, -1, axis=0)
    dy = b[:, 1] - a[:, 1]
    keep = dy != 0
    a, b, dy = a[keep], b[keep], dy[keep]
    lo, hi = np.minimum(a[:, 1], b[:, 1]), np.maximum(a[:, 1], b[:, 1])
    slope = (b[:, 0] - a[:, 0]) / dy
    sign = np.sign(dy)  # on a counter-clockwise outline an upward edge is a right boundary
    # b(y) = sum over the edges active at y (lo <= y < hi) of sign (x_a + slope (y - y_a))
    #      = C0(y) + y C1(y), C0 and C1 piecewise constant: difference arrays over the sorted levels.
    # Near-horizontal edges (|slope| > 100) would cancel catastrophically in C0 + y C1: they are
    # evaluated directly at the few levels they span.
    y = np.asarray(levels, dtype=float)
    order = np.argsort(y)
    ys = y[order]
    first, stop = np.searchsorted(ys, lo, "left"), np.searchsorted(ys, hi, "left")
    flat = np.abs(slope) > 100.0
    steep = ~flat
    offset = sign * (a[:, 0] - slope * a[:, 1])
    c0 = np.zeros(len(ys) + 1)
    c1 = np.zeros(len(ys) + 1)
    np.add.at(c0, first[steep], offset[steep])
    np.add.at(c0, stop[steep], -offset[steep])
    np.add.at(c1, first[steep], (sign * slope)[steep])
    np.add.at(c1, stop[steep], -(sign * slope)[steep])
    width = np.cumsum(c0)[:-1] + ys * np.cumsum(c1)[:-1]
    count = (stop - first)[flat]
    if count.sum():
        edge = np.repeat(np.nonzero(flat)[0], count)
        level = np.concatenate([np.arange(i, j) for i, j in zip(first[flat], stop[flat], strict=True) if j > i])
        np.add.at(width, level, sign[edge] * (a[edge, 0] + slope[edge] * (ys[level] - a[edge, 1])))
    out = np.empty(len(ys))
    out[order] = width
    return out


def shear_correction(points: np.ndarray, samples: int = 4001) -> float:
    """Shear correction factor kappa of eq. (1) for bending about the horizontal axis.

    Parameters
    ----------
    points : (n, 2) float, mm
        Closed outline (turn it to get kappa for another bending axis).
    samples : int
        Horizontal strips (midpoint rule, second order).

    Returns
    -------
    float
        kappa = A / J^2 * integral (S/b)^2 b dy (Rinder & Deix eq. 1); 10/9 for a circle.
    """
    values = section_values(points)
    p = _ccw(points)
    edges = np.linspace(p[:, 1].min(), p[:, 1].max(), samples + 1)
    dy = np.diff(edges)
    y = 0.5 * (edges[1:] + edges[:-1])  # midpoints: no level on a vertex at the extremes, where b -> 0
    b = width_profile(p, y)
    g = (y - values.centroid[1]) * b * dy  # first moment of each strip about the centroidal axis
    above = np.concatenate([np.cumsum(g[::-1])[::-1][1:], [0.0]])  # strips wholly above each strip
    s = above + 0.5 * g  # S at the strip's middle
    integrand = np.divide(s**2, b, out=np.zeros_like(b), where=b > 1e-12 * b.max())
    return float(values.area / values.j_x**2 * np.sum(integrand * dy))


def shear_correction_over_turn(points: np.ndarray, turns: np.ndarray, samples: int = 2001) -> np.ndarray:
    """Return the shear correction kappa(gamma) of the section turned by each angle (Rinder & Deix eq. 1).

    Parameters
    ----------
    points : (n, 2) float array, mm
        The closed section outline.
    turns : (k,) float array, rad
        Turns gamma of the section; kappa is taken for bending about the horizontal axis of the
        turned section (:func:`shear_correction`).
    samples : int
        Strips of the integration.

    Returns
    -------
    (k,) float array
    """
    p = _ccw(points)
    out = np.empty(len(turns))
    for i, g in enumerate(np.asarray(turns, dtype=float)):  # a few dozen turns, each vectorised
        out[i] = shear_correction(rotate(p, g), samples)
    return out


def circle_values(diameter: float) -> tuple[float, float]:
    """Return the area and second moment of a full circle: pi d^2 / 4 and pi d^4 / 64.

    Parameters
    ----------
    diameter : float, mm
        Diameter d.

    Returns
    -------
    area : float, mm²
    second_moment : float, mm⁴
    """
    return float(np.pi * diameter**2 / 4), float(np.pi * diameter**4 / 64)

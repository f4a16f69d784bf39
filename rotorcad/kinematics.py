"""Plane motions of the meshing bodies: rotors and gears turn, racks translate.

Every motion is driven by one parameter ``t``, the male (or driving gear) rotation angle in
radians (DESIGN.md conventions). A :class:`Rotation` turns its body about ``center`` by
``rate * t``; a :class:`Translation` shifts its body by ``velocity * t``. For two bodies the
instantaneous centre of their relative motion is the pitch point C (Wälzpunkt), through which
every contact normal must pass (law of gearing).

:func:`gear_mesh` and :func:`rotor_mesh` set up the standard frames: O1 = (0, 0), O2 = (a, 0),
C = (r1w, 0), male turning counter-clockwise, female with phi2 = -phi1*z1/z2, and the rack's
pitch line x = r1w moving in +y at r1w per radian of the male.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property, lru_cache

import numpy as np

from rotorcad.geometry import Array, as_points, rotate


@dataclass(frozen=True)
class Rotation:
    """A body turning about ``center`` by the angle ``rate * t``."""

    center: tuple[float, float] = (0.0, 0.0)
    rate: float = 1.0

    def angle(self, t: Array | float) -> Array | float:
        return self.rate * np.asarray(t, dtype=float)

    def to_fixed(self, points: Array, t: Array | float) -> Array:
        """Body-frame points to the fixed frame at motion parameter ``t``."""
        return rotate(points, self.angle(t), self.center)

    def to_body(self, points: Array, t: Array | float) -> Array:
        """Fixed-frame points to the body frame at ``t``."""
        return rotate(points, -self.angle(t), self.center)

    def vectors_to_fixed(self, vectors: Array, t: Array | float) -> Array:
        return rotate(vectors, self.angle(t))

    def vectors_to_body(self, vectors: Array, t: Array | float) -> Array:
        return rotate(vectors, -self.angle(t))

    def velocity_at(self, points: Array) -> Array:
        """Velocity (per unit t) of the body's material at fixed-frame ``points`` (n, 2), mm:
        rate * (-(y - y_O), x - x_O), shape (n, 2).
        """
        d = as_points(points) - np.asarray(self.center, dtype=float)
        v = np.empty_like(d)
        v[:, 0] = -d[:, 1]
        v[:, 1] = d[:, 0]
        return self.rate * v


@dataclass(frozen=True)
class Translation:
    """A body shifted by ``velocity * t`` (a rack)."""

    velocity: tuple[float, float] = (0.0, 1.0)
    rate: float = 0.0

    @cached_property
    def _velocity(self) -> Array:
        """``velocity`` as a (2,) float array, mm per unit t."""
        return np.asarray(self.velocity, dtype=float)

    def to_fixed(self, points: Array, t: Array | float) -> Array:
        shift = np.multiply.outer(np.asarray(t, dtype=float), self._velocity)
        return as_points(points) + shift

    def to_body(self, points: Array, t: Array | float) -> Array:
        shift = np.multiply.outer(np.asarray(t, dtype=float), self._velocity)
        return as_points(points) - shift

    def vectors_to_fixed(self, vectors: Array, t: Array | float) -> Array:
        return as_points(vectors)

    def vectors_to_body(self, vectors: Array, t: Array | float) -> Array:
        return as_points(vectors)

    def velocity_at(self, points: Array) -> Array:
        """The rack's velocity (per unit t) at every one of ``points`` (n, 2): shape (n, 2), mm."""
        out = np.empty_like(as_points(points))
        out[...] = self._velocity
        return out


Body = Rotation | Translation


def pitch_point(a: Body, b: Body) -> Array:
    """Instantaneous centre of the relative motion of ``a`` and ``b`` (the pitch point C).

    Two rotations: C = (w_a O_a - w_b O_b) / (w_a - w_b). A rotation and a translation V:
    the point of the rotating body whose velocity equals V.

    Parameters
    ----------
    a, b : Rotation or Translation
        The two bodies (not both translating, not turning at the same rate).

    Returns
    -------
    (2,) float array, mm
        C in the fixed frame (a new array on every call).
    """
    return _pitch_point(a, b).copy()


@lru_cache(maxsize=64)
def _pitch_point(a: Body, b: Body) -> Array:
    """:func:`pitch_point`, remembered for the few meshes in use (the bodies are frozen values)."""
    if isinstance(a, Translation) and isinstance(b, Translation):
        raise ValueError("two translating bodies have no pitch point")
    if isinstance(a, Translation):
        a, b = b, a
    assert isinstance(a, Rotation)
    oa = np.asarray(a.center, dtype=float)
    if isinstance(b, Translation):
        v = np.asarray(b.velocity, dtype=float)
        return oa + np.array([v[1], -v[0]]) / a.rate
    ob = np.asarray(b.center, dtype=float)
    if a.rate == b.rate:
        raise ValueError("bodies turning at the same rate have no pitch point")
    return (a.rate * oa - b.rate * ob) / (a.rate - b.rate)


@dataclass(frozen=True)
class Mesh:
    """The three bodies of a mesh sharing the pitch point: male (gear 1), female (gear 2), rack."""

    male: Rotation
    female: Rotation
    rack: Translation
    pitch_radius_male: float
    pitch_radius_female: float

    @property
    def pitch_point(self) -> Array:
        return np.array([self.pitch_radius_male, 0.0])

    @property
    def center_distance(self) -> float:
        return self.pitch_radius_male + self.pitch_radius_female


def rotor_mesh(z1: int, z2: int, center_distance: float) -> Mesh:
    """Frames of a male/female pair: r1w = a/(1+i), r2w = a*i/(1+i), i = z2/z1."""
    i = z2 / z1
    r1w = center_distance / (1.0 + i)
    r2w = center_distance * i / (1.0 + i)
    return Mesh(
        male=Rotation((0.0, 0.0), 1.0),
        female=Rotation((center_distance, 0.0), -z1 / z2),
        rack=Translation((0.0, r1w)),
        pitch_radius_male=r1w,
        pitch_radius_female=r2w,
    )


def gear_mesh(pitch_radius: float, mate_pitch_radius: float | None = None) -> Mesh:
    """Frames of a gear (and optional mate) with its generating rack at pitch radius r."""
    r2 = pitch_radius if mate_pitch_radius is None else mate_pitch_radius
    return Mesh(
        male=Rotation((0.0, 0.0), 1.0),
        female=Rotation((pitch_radius + r2, 0.0), -pitch_radius / r2),
        rack=Translation((0.0, pitch_radius)),
        pitch_radius_male=pitch_radius,
        pitch_radius_female=r2,
    )

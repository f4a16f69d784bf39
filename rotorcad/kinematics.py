"""Plane motions of the meshing bodies: rotors and gears turn, racks translate.

Every motion is driven by one parameter ``t``, the male (or driving gear) rotation angle in
radians (ARCHITECTURE.md, conventions). A :class:`Rotation` turns its body about ``center`` by
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

from rotorcad.geometry import Array, as_points, filled, rotate, shifted


@dataclass(frozen=True)
class Rotation:
    """A body turning about ``center`` by the angle ``rate * t``.

    Parameters
    ----------
    center : (float, float), mm
        Centre of the turn in the fixed frame (O1 = (0, 0), O2 = (a, 0)).
    rate : float
        Turn of the body per unit of the motion parameter t (rad per rad of the male): 1 for the
        male, -z1/z2 for the female (ARCHITECTURE.md, conventions).
    """

    center: tuple[float, float] = (0.0, 0.0)
    rate: float = 1.0

    def angle(self, t: Array | float) -> Array | float:
        """Return the body's turn at motion parameter ``t``.

        Parameters
        ----------
        t : float or array, rad
            Motion parameter (male rotation angle), any shape.

        Returns
        -------
        float array, rad
            ``rate * t``, of the shape of ``t``.
        """
        return self.rate * np.asarray(t, dtype=float)

    def to_fixed(self, points: Array, t: Array | float) -> Array:
        """Carry body-frame points into the fixed frame at motion parameter ``t``.

        Parameters
        ----------
        points : (n, 2) float array, mm
            Points in the body's own frame.
        t : float or array, rad
            Motion parameter: a scalar, one value per point (n,), or a stack broadcasting as in
            :func:`rotorcad.geometry.rotate`.

        Returns
        -------
        (..., n, 2) float array, mm
            The points turned by ``rate * t`` about ``center``.
        """
        return rotate(points, self.angle(t), self.center)

    def to_body(self, points: Array, t: Array | float) -> Array:
        """Carry fixed-frame points into the body frame at motion parameter ``t``.

        Parameters
        ----------
        points : (n, 2) float array, mm
            Points in the fixed frame.
        t : float or array, rad
            Motion parameter, as in :meth:`to_fixed`.

        Returns
        -------
        (..., n, 2) float array, mm
            The points turned by ``-rate * t`` about ``center``.
        """
        return rotate(points, -self.angle(t), self.center)

    def vectors_to_fixed(self, vectors: Array, t: Array | float) -> Array:
        """Turn body-frame vectors (tangents, normals) into the fixed frame at ``t``.

        Parameters
        ----------
        vectors : (n, 2) float array
            Vectors in the body's frame.
        t : float or array, rad
            Motion parameter, as in :meth:`to_fixed`.

        Returns
        -------
        (..., n, 2) float array
            The vectors turned by ``rate * t`` (about the origin: vectors have no position).
        """
        return rotate(vectors, self.angle(t))

    def vectors_to_body(self, vectors: Array, t: Array | float) -> Array:
        """Turn fixed-frame vectors into the body frame at ``t``.

        Parameters
        ----------
        vectors : (n, 2) float array
            Vectors in the fixed frame.
        t : float or array, rad
            Motion parameter, as in :meth:`to_fixed`.

        Returns
        -------
        (..., n, 2) float array
            The vectors turned by ``-rate * t``.
        """
        return rotate(vectors, -self.angle(t))

    def velocity_at(self, points: Array) -> Array:
        """Return the velocity of the body's material at fixed-frame points, per unit t.

        Parameters
        ----------
        points : (n, 2) float array, mm
            Points in the fixed frame.

        Returns
        -------
        (n, 2) float array, mm per rad
            ``rate * (-(y - y_O), x - x_O)`` with O = ``center``.
        """
        d = shifted(as_points(points), self.center, -1.0)
        v = np.empty_like(d)
        v[:, 0] = -d[:, 1]
        v[:, 1] = d[:, 0]
        return self.rate * v


@dataclass(frozen=True)
class Translation:
    """A body shifted by ``velocity * t`` (a rack).

    Parameters
    ----------
    velocity : (float, float), mm per rad
        Shift of the body per unit of the motion parameter t; a rack meshing with the male moves at
        (0, r1w).
    rate : float
        Turning rate: 0, a translation does not turn (the field mirrors :attr:`Rotation.rate`).
    """

    velocity: tuple[float, float] = (0.0, 1.0)
    rate: float = 0.0

    @cached_property
    def velocity_array(self) -> Array:
        """``velocity`` as a (2,) float array, mm per unit t (do not modify: it is kept)."""
        return np.asarray(self.velocity, dtype=float)

    @cached_property
    def speed(self) -> float:
        """|``velocity``|, mm per unit t: ``sqrt(v . v)``, as np.linalg.norm computes it for a vector."""
        v = self.velocity_array
        return float(np.sqrt(v.dot(v)))

    def to_fixed(self, points: Array, t: Array | float) -> Array:
        """Carry body-frame points into the fixed frame at motion parameter ``t``.

        Parameters
        ----------
        points : (n, 2) float array, mm
            Points in the rack's own frame.
        t : float or array, rad
            Motion parameter: a scalar, or one value per point (n,).

        Returns
        -------
        (n, 2) float array, mm
            ``points + t * velocity``.
        """
        return self._moved(points, t, 1.0)

    def to_body(self, points: Array, t: Array | float) -> Array:
        """Carry fixed-frame points into the body frame at motion parameter ``t``.

        Parameters
        ----------
        points : (n, 2) float array, mm
            Points in the fixed frame.
        t : float or array, rad
            Motion parameter: a scalar, or one value per point (n,).

        Returns
        -------
        (n, 2) float array, mm
            ``points - t * velocity``.
        """
        return self._moved(points, t, -1.0)

    def _moved(self, points: Array, t: Array | float, sign: float) -> Array:
        """``points + sign * outer(t, velocity)``: the numbers of numpy's broadcast, by columns for (n,) ``t``."""
        p, t = as_points(points), np.asarray(t, dtype=float)
        if t.ndim != 1 or p.ndim != 2 or len(t) != len(p):
            shift = np.multiply.outer(t, self.velocity_array)
            return p + shift if sign > 0 else p - shift
        vx, vy = self.velocity
        out = np.empty(p.shape)
        op = np.add if sign > 0 else np.subtract
        op(p[:, 0], t * float(vx), out=out[:, 0])
        op(p[:, 1], t * float(vy), out=out[:, 1])
        return out

    def vectors_to_fixed(self, vectors: Array, t: Array | float) -> Array:
        """Return body-frame vectors in the fixed frame (a translation leaves them as they are).

        Parameters
        ----------
        vectors : (n, 2) float array
            Vectors in the rack's frame.
        t : float or array, rad
            Motion parameter (unused: kept for the common interface of :class:`Rotation`).

        Returns
        -------
        (n, 2) float array
            ``vectors`` as a float array.
        """
        return as_points(vectors)

    def vectors_to_body(self, vectors: Array, t: Array | float) -> Array:
        """Return fixed-frame vectors in the body frame (a translation leaves them as they are).

        Parameters
        ----------
        vectors : (n, 2) float array
            Vectors in the fixed frame.
        t : float or array, rad
            Motion parameter (unused: kept for the common interface of :class:`Rotation`).

        Returns
        -------
        (n, 2) float array
            ``vectors`` as a float array.
        """
        return as_points(vectors)

    def velocity_at(self, points: Array) -> Array:
        """Return the rack's velocity at every one of ``points``, per unit t.

        Parameters
        ----------
        points : (n, 2) float array, mm
            Points in the fixed frame (only their number matters).

        Returns
        -------
        (n, 2) float array, mm per rad
            ``velocity`` repeated for every point.
        """
        return filled(len(as_points(points)), self.velocity_array)


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
    """The three bodies of a mesh sharing the pitch point: male (gear 1), female (gear 2), rack.

    Parameters
    ----------
    male, female : Rotation
        The male about O1 = (0, 0) at rate 1 and the female about O2 = (a, 0).
    rack : Translation
        The rack whose pitch line x = r1w rolls on both pitch circles.
    pitch_radius_male, pitch_radius_female : float, mm
        r1w and r2w.
    """

    male: Rotation
    female: Rotation
    rack: Translation
    pitch_radius_male: float
    pitch_radius_female: float

    @property
    def pitch_point(self) -> Array:
        """The pitch point C = (r1w, 0), mm, shape (2,)."""
        return np.array([self.pitch_radius_male, 0.0])

    @property
    def center_distance(self) -> float:
        """The centre distance a = r1w + r2w, mm."""
        return self.pitch_radius_male + self.pitch_radius_female


def rotor_mesh(z1: int, z2: int, center_distance: float) -> Mesh:
    """Set up the frames of a male/female screw-rotor pair.

    r1w = a/(1+i), r2w = a i/(1+i) with i = z2/z1 (ARCHITECTURE.md, conventions): the male turns about
    O1 = (0, 0) at rate 1, the female about O2 = (a, 0) at rate -z1/z2, the rack moves in +y at r1w
    per radian of the male.

    Parameters
    ----------
    z1, z2 : int
        Lobe counts of the male and the female.
    center_distance : float, mm
        Centre distance a.

    Returns
    -------
    Mesh
        The male, female and rack motions and both pitch radii.
    """
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
    """Set up the frames of a gear (and an optional mate) with its generating rack.

    Parameters
    ----------
    pitch_radius : float, mm
        Pitch (rolling) radius r of the gear about O1 = (0, 0); the rack moves in +y at r per radian.
    mate_pitch_radius : float, mm, optional
        Pitch radius of the mate about (r + r2, 0), turning at -r/r2; default the gear's own.

    Returns
    -------
    Mesh
        The gear, mate and rack motions and both pitch radii.
    """
    r2 = pitch_radius if mate_pitch_radius is None else mate_pitch_radius
    return Mesh(
        male=Rotation((0.0, 0.0), 1.0),
        female=Rotation((pitch_radius + r2, 0.0), -pitch_radius / r2),
        rack=Translation((0.0, pitch_radius)),
        pitch_radius_male=pitch_radius,
        pitch_radius_female=r2,
    )

"""The gearing (envelope) engine: conjugate points, meshline and contact parameter.

A generating curve is carried by one body (a rack that translates or a rotor that turns) and
generates the conjugate curve on another body. For every generating point p with outward unit
normal n the engine finds the motion parameter t at which the meshing condition
n . v_rel = 0 holds. With the relative motion a rotation about the pitch point C this is the law
of gearing: the normal at the contact point passes through C (Litvin, *Gear Geometry and Applied
Theory*, eq. 6.1.7; Rinder 1984, section 2.2). Then

* the contact point X = M_G(t) p in the fixed frame: the meshline (Eingriffslinie),
* the generated point M_B(t)^-1 X on the other body, with tangent parallel to the generating one,

all in closed form and vectorised over the points.

Generating rack (translation V): cross(n, p + V t - C) = 0 is linear in t; it has exactly one
root unless n is parallel to V (normal parallel to the pitch line), where there is no contact.

Generating rotor (centre O, rate w, angle theta = w t): with w_C = C - O = r_w (cos b, sin b)
and n = (cos psi, sin psi) the condition reads sin(b - theta - psi) = cross(n, p) / r_w = q.
|q| > 1: the normal never reaches the pitch circle, no contact. Otherwise two roots, i.e. the two
points where the normal line cuts the pitch circle:

* branch "A": the cut point lying further along the outward normal (cos(b - theta - psi) >= 0);
  this is the physical one for convex and involute flanks (for an involute it is the cut on the
  same side of the base-circle tangent point as p),
* branch "B": the other cut point.

Which one "lies on the body": given the generated body's radial ``limits`` (root and tip
radius), a point whose branch-A conjugate falls outside them while the branch-B conjugate falls
inside takes branch B. A circular arc centred exactly on the pitch circle (symmetric SRM flank)
is the degenerate case: every normal passes through the centre K, so the whole arc touches at
the one angle that brings K to C; the engine detects it from the curve's centre and uses that
angle for every point instead of the (then ill-conditioned) root choice. Likewise a rack arc
centred on the pitch line touches at the one shift that brings its centre to C, including its
end points, whose normals lie along the pitch line.
"""

from __future__ import annotations

import itertools
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Literal

import numpy as np

from rotorcad.curves import Curve, Line
from rotorcad.geometry import Array, as_points, cross, perp_cw, shifted, turned, wrap_angle
from rotorcad.kinematics import Body, Rotation, Translation, pitch_point

Branch = Literal["A", "B"]
"""Which root of the meshing equation of a generating rotor (see the module docstring)."""


@dataclass(frozen=True, eq=False)
class Contact:
    """Result of :func:`conjugate`: one row per generating point (NaN where there is no contact).

    Parameters
    ----------
    t : (n,) float array, rad
        Motion parameter at contact.
    meshline : (n, 2) float array, mm
        Contact points in the fixed frame (the meshline).
    normal : (n, 2) float array
        Outward unit normals of the generating boundary at contact, fixed frame.
    points : (n, 2) float array, mm
        Generated points in the generated body's frame.
    tangents : (n, 2) float array
        Unit tangents of the generated boundary, generated body's frame.
    sliding : (n, 2) float array, mm/rad
        Relative velocity v_rel (generating minus generated) at the contact point, fixed frame.
    pitch_point : (2,) float array, mm
        The pitch point C.
    """

    t: Array
    meshline: Array
    normal: Array
    points: Array
    tangents: Array
    sliding: Array
    pitch_point: Array

    @property
    def in_contact(self) -> Array:
        """Whether each generating point is in contact (finite ``t``), (n,) bool array."""
        return np.isfinite(self.t)

    @property
    def normals(self) -> Array:
        """Outward normals of the generated body at the generated points."""
        return perp_cw(self.tangents)

    @property
    def sliding_speed(self) -> Array:
        """|v_rel| at the contact point per unit of the motion parameter (mm/rad)."""
        return np.hypot(*self.sliding.T)


def contact_parameter(
    points: Array,
    normals: Array,
    generating: Body,
    pitch: Array,
    branch: Branch = "A",
    arc_center: Array | None = None,
    reference: float = 0.0,
    corner: bool = False,
) -> Array:
    """Motion parameter t at which each generating point is in contact (NaN: never).

    ``points`` and ``normals`` (outward, unit) are in the generating body's frame at t = 0.
    ``branch`` is "A" or "B" (see the module docstring); ``reference`` is the generating rotor's
    angle around which the root is taken (within +-pi).
    """
    p = as_points(points)
    n = as_points(normals)
    c = np.asarray(pitch, dtype=float)
    if isinstance(generating, Translation):
        v = generating.velocity_array
        if arc_center is not None:
            k = np.asarray(arc_center, dtype=float) - c
            if abs(cross(k, v)) <= 1e-12 * np.dot(v, v):  # arc centred on the pitch line
                return np.full(len(p), -np.dot(k, v) / np.dot(v, v))
        den = cross(n, v)
        ok = np.abs(den) > 1e-12 * generating.speed
        with np.errstate(divide="ignore", invalid="ignore"):
            t = np.where(ok, -cross(n, shifted(p, c, -1.0)) / np.where(ok, den, 1.0), np.nan)
        return t
    o = np.asarray(generating.center, dtype=float)
    w = c - o
    r_w = float(np.hypot(*w))
    beta = float(np.arctan2(w[1], w[0]))
    if corner:
        arc_center = None  # a corner is not a circular flank: see below
    if arc_center is not None:
        k = np.asarray(arc_center, dtype=float) - o
        if abs(np.hypot(*k) - r_w) <= 1e-9 * r_w:
            theta = wrap_angle(np.array(beta - np.arctan2(k[1], k[0])), reference)
            return np.full(len(p), theta / generating.rate)
    q = cross(n, shifted(p, o, -1.0)) / r_w
    psi = np.arctan2(n[:, 1], n[:, 0])
    with np.errstate(invalid="ignore"):
        phi = np.arcsin(q)
    if branch == "B":
        phi = np.pi - phi
    elif branch != "A":
        raise ValueError("branch must be 'A' or 'B'")
    theta = wrap_angle(beta - psi - phi, reference)
    if corner:
        # a corner on the pitch circle touches trivially, for every normal of its fan, at the
        # instant it passes C; the path it cuts comes from the other root
        d = shifted(p, o, -1.0)
        trivial = beta - np.arctan2(d[:, 1], d[:, 0])
        on_circle = np.abs(np.hypot(*d.T) - r_w) <= 1e-9 * r_w
        same = np.abs(wrap_angle(theta - trivial)) < 1e-9
        other = wrap_angle(beta - psi - (np.pi - phi), reference)
        theta = np.where(on_circle & same, other, theta)
    return theta / generating.rate


def conjugate(
    points: Array,
    tangents: Array,
    generating: Body,
    generated: Body,
    branch: Branch = "A",
    arc_center: Array | None = None,
    limits: tuple[float, float] | None = None,
    reference: float = 0.0,
    corner: bool = False,
) -> Contact:
    """Conjugate of a generating boundary given by ``points`` and boundary ``tangents``.

    The generating boundary is travelled counter-clockwise about its body, so its outward normal
    is the tangent turned clockwise. The generated tangents run the other way round (they bound
    the other body, whose material lies on the opposite side). ``limits`` = (r_min, r_max) of the
    generated rotor about its centre, or (y_min, y_max) of a generated rack about its pitch line,
    selects for a rotating generator the root whose conjugate lies on that body.
    """
    p = as_points(points)
    tg = as_points(tangents)
    n = perp_cw(tg)
    c = pitch_point(generating, generated)
    t = _contact_times(p, n, generating, generated, c, branch, arc_center, limits, reference, corner)
    x = generating.to_fixed(p, t)
    nx = generating.vectors_to_fixed(n, t)
    tx = generating.vectors_to_fixed(tg, t)
    gen_pts = generated.to_body(x, t)
    gen_tan = -generated.vectors_to_body(tx, t)
    sliding = generating.velocity_at(x) - generated.velocity_at(x)
    return Contact(t=t, meshline=x, normal=nx, points=gen_pts, tangents=gen_tan, sliding=sliding, pitch_point=c)


def _contact_times(
    p: Array,
    n: Array,
    generating: Body,
    generated: Body,
    c: Array,
    branch: Branch,
    arc_center: Array | None,
    limits: tuple[float, float] | None,
    reference: float,
    corner: bool,
) -> Array:
    """Motion parameter at contact of :func:`conjugate` (the root chosen by ``limits``), (n,) float array."""
    if limits is not None and isinstance(generating, Rotation):
        t, other = _both_branches(p, n, generating, c, branch, arc_center, reference, corner)
        r_a = _generated_extent(p, t, generating, generated, c)
        r_b = _generated_extent(p, other, generating, generated, c)
        lo, hi = limits
        tol = 1e-9 * max(abs(hi), 1.0)
        out_a = ~((r_a >= lo - tol) & (r_a <= hi + tol))
        in_b = (r_b >= lo - tol) & (r_b <= hi + tol)
        return np.where(out_a & in_b, other, t)
    return contact_parameter(p, n, generating, c, branch, arc_center, reference, corner)


def _both_branches(
    p: Array,
    n: Array,
    generating: Rotation,
    pitch: Array,
    branch: Branch,
    arc_center: Array | None,
    reference: float,
    corner: bool,
) -> tuple[Array, Array]:
    """Return the contact parameters of ``branch`` and of the other branch of a turning generator, (n,) each.

    The numbers of ``contact_parameter(..., branch, arc_center, ...)`` and of
    ``contact_parameter(..., other branch, None, ...)``, the normal's turn and arcsine computed once
    for both.
    """
    if branch not in ("A", "B"):
        raise ValueError("branch must be 'A' or 'B'")
    c = np.asarray(pitch, dtype=float)
    o = np.asarray(generating.center, dtype=float)
    w = c - o
    r_w = float(np.hypot(*w))
    beta = float(np.arctan2(w[1], w[0]))
    first = None
    if arc_center is not None and not corner:
        k = np.asarray(arc_center, dtype=float) - o
        if abs(np.hypot(*k) - r_w) <= 1e-9 * r_w:  # contact_parameter's arc centred on the pitch circle
            first = np.full(len(p), wrap_angle(np.array(beta - np.arctan2(k[1], k[0])), reference) / generating.rate)
    q = cross(n, shifted(p, o, -1.0)) / r_w
    psi = np.arctan2(n[:, 1], n[:, 0])
    with np.errstate(invalid="ignore"):
        arcsine = np.arcsin(q)

    def turn(side: Branch) -> Array:
        phi = np.pi - arcsine if side == "B" else arcsine
        theta = wrap_angle(beta - psi - phi, reference)
        if corner:  # as contact_parameter: the other root where the trivial one is taken
            d = shifted(p, o, -1.0)
            trivial = beta - np.arctan2(d[:, 1], d[:, 0])
            on_circle = np.abs(np.hypot(*d.T) - r_w) <= 1e-9 * r_w
            same = np.abs(wrap_angle(theta - trivial)) < 1e-9
            other = wrap_angle(beta - psi - (np.pi - phi), reference)
            theta = np.where(on_circle & same, other, theta)
        return theta / generating.rate

    return (turn(branch) if first is None else first), turn("B" if branch == "A" else "A")


def _generated_extent(p: Array, t: Array, generating: Body, generated: Body, pitch: Array) -> Array:
    """Return where conjugate points lie on the generated body.

    That is their radius about a rotor's centre, or for a rack their height above the pitch line
    (towards the side the rack's velocity turned clockwise points to: +x for the standard rack
    moving +y).

    Parameters
    ----------
    p : (n, 2) float array, mm
        Generating points in the generating body's frame at t = 0.
    t : (n,) float array, rad
        Motion parameter at contact.
    generating, generated : Body
        The generating and the generated body.
    pitch : (2,) float array, mm
        The pitch point C.

    Returns
    -------
    (n,) float array, mm
        Radius about the generated rotor's centre, or height above the generated rack's pitch line.
    """
    x = generating.to_fixed(p, t)
    if isinstance(generated, Rotation):
        return np.hypot(*(x - np.asarray(generated.center, dtype=float)).T)
    v = np.asarray(generated.velocity, dtype=float)
    return -cross(v / np.hypot(*v), x - pitch)


@dataclass(frozen=True)
class Generated(Curve):
    """The conjugate of ``parent`` (a curve on the ``generating`` body) on the ``generated`` body.

    Evaluates exactly at any parameter of the parent, so it can be resampled to any chord
    tolerance. Its travel runs opposite to the parent's (``s0`` = parent's ``s1``), so that a
    counter-clockwise generating boundary yields a counter-clockwise generated one. The parent's
    travel direction at construction fixes which side is outward.
    """

    parent: Curve
    generating: Body
    generated: Body
    branch: Branch = "A"
    reference: float = 0.0
    limits: tuple[float, float] | None = None
    s0: float = float("nan")
    s1: float = float("nan")
    parent_direction: float = field(default=0.0)

    def __post_init__(self) -> None:
        if np.isnan(self.s0):
            object.__setattr__(self, "s0", self.parent.s1)
            object.__setattr__(self, "s1", self.parent.s0)
        if self.parent_direction == 0.0:
            object.__setattr__(self, "parent_direction", self.parent.direction)

    def contact(self, s: Array) -> Contact:
        """Return the contact generated by the parent's points at parameters ``s``.

        The parent's boundary tangents (its canonical tangents times ``parent_direction``), its
        arc centre and its corner flag go to :func:`conjugate`.

        Parameters
        ----------
        s : float or (n,) float array
            Parameters of ``parent``.

        Returns
        -------
        Contact
            One row per parameter (NaN where there is no contact).
        """
        s = np.atleast_1d(np.asarray(s, dtype=float))
        p, t_can = self.parent.frame(s)
        return conjugate(
            p,
            t_can * self.parent_direction,
            self.generating,
            self.generated,
            self.branch,
            self.parent.arc_center(),
            limits=self.limits,
            reference=self.reference,
            corner=self.parent.is_corner(),
        )

    def meshline_contact(self, s: Array) -> tuple[Array, Array, Array, Array]:
        """Return the contact at parameters ``s`` without the generated points: the meshline alone.

        The ``t`` and ``meshline`` of :meth:`contact` (the same numbers), and the parent's points
        and tangents along its travel (those of :meth:`Curve.evaluate`), for a caller that reads
        only where the contact lies (the meshing analysis).

        Parameters
        ----------
        s : (n,) float array
            Parameters of ``parent``.

        Returns
        -------
        t : (n,) float array, rad
            Motion parameter at contact (NaN: none).
        meshline : (n, 2) float array, mm
            Contact points in the fixed frame.
        points, tangents : (n, 2) float arrays
            The parent's points (mm) and unit tangents along its travel at ``s``.
        """
        s = np.atleast_1d(np.asarray(s, dtype=float))
        p, t_can = self.parent.frame(s)
        tg = t_can * self.parent_direction
        c = pitch_point(self.generating, self.generated)
        args = (self.branch, self.parent.arc_center(), self.limits, self.reference, self.parent.is_corner())
        t = _contact_times(p, perp_cw(tg), self.generating, self.generated, c, *args)
        return t, self.generating.to_fixed(p, t), p, tg

    def frame(self, s: Array) -> tuple[Array, Array]:
        """Return points and unit tangents at parameters ``s``.

        Parameters
        ----------
        s : (n,) float array
            Parameters of ``parent``.

        Returns
        -------
        points : (n, 2) float array, mm
            Generated points in the generated body's frame (NaN where there is no contact).
        tangents : (n, 2) float array
            Unit tangents along increasing ``s``: the generated boundary tangent, -R t_parent_boundary,
            is travelled against the parent's direction.
        """
        # the numbers of contact(s).points and .tangents (conjugate's steps for these two, each
        # body's cosine and sine once for its points and vectors; no normals, no sliding)
        s = np.atleast_1d(np.asarray(s, dtype=float))
        p, t_can = self.parent.frame(s)
        p, tg = as_points(p), as_points(t_can * self.parent_direction)
        c = pitch_point(self.generating, self.generated)
        args = (self.branch, self.parent.arc_center(), self.limits, self.reference, self.parent.is_corner())
        t = _contact_times(p, perp_cw(tg), self.generating, self.generated, c, *args)
        x, tx = _carried(self.generating, p, tg, t, inverse=False)
        points, tangents = _carried(self.generated, x, tx, t, inverse=True)
        # canonical tangent (along increasing s): the generated boundary tangent is
        # -R t_parent_boundary and is travelled against the parent's direction.
        return points, (-tangents) * (-self.parent_direction)


def _carried(body: Body, points: Array, vectors: Array, t: Array, inverse: bool) -> tuple[Array, Array]:
    """Points and vectors carried by ``body`` at ``t``: to the fixed frame, or with ``inverse`` to the body's.

    The numbers of ``body.to_fixed(points, t)`` and ``body.vectors_to_fixed(vectors, t)`` (or of
    ``to_body`` and ``vectors_to_body``), a turn's cosine and sine computed once for both.

    Parameters
    ----------
    body : Rotation or Translation
        The moving body.
    points, vectors : (n, 2) float arrays
        Points (mm) and vectors in the frame they leave.
    t : (n,) float array, rad
        Motion parameter, one per point.
    inverse : bool
        From the fixed frame into the body's.

    Returns
    -------
    points, vectors : (n, 2) float arrays
        In the frame they reach.
    """
    if isinstance(body, Rotation):
        angle = -body.angle(t) if inverse else body.angle(t)
        c, s = np.cos(angle), np.sin(angle)
        return turned(points, c, s, body.center), turned(vectors, c, s)
    return (body.to_body(points, t) if inverse else body.to_fixed(points, t)), as_points(vectors)


def meshline_contacts(gens: list[Generated], params: list[Array]) -> list[tuple[Array, Array, Array, Array]]:
    """Return :meth:`Generated.meshline_contact` of several pieces, one pass over all of them.

    Pieces generated by the same translating body (a rack's pieces, all against the same rotor)
    share the closed form of the contact (module docstring: linear in t): it is solved once for all
    their points, each piece evaluating only its own points and tangents; a rack arc centred on the
    pitch line is solved again on its own points (its contact is the shift that brings the centre to
    C). The numbers are those of one call per piece, element for element; other pieces are evaluated
    one by one.

    Parameters
    ----------
    gens : list of Generated
        The pieces.
    params : list of (n_i,) float arrays
        Parameters of each piece's ``parent``.

    Returns
    -------
    list of tuple
        Per piece, ``(t, meshline, points, tangents)`` as :meth:`Generated.meshline_contact` returns them.
    """
    if not gens:
        return []
    first = gens[0]
    shared = isinstance(first.generating, Translation) and all(
        g.generating is first.generating and g.generated is first.generated for g in gens
    )
    if not shared:
        return [g.meshline_contact(s) for g, s in zip(gens, params, strict=True)]
    frames = [g.parent.frame(np.atleast_1d(np.asarray(s, dtype=float))) for g, s in zip(gens, params, strict=True)]
    p = np.concatenate([f[0] for f in frames])
    tg = np.concatenate([f[1] * g.parent_direction for f, g in zip(frames, gens, strict=True)])
    n = perp_cw(tg)
    c = pitch_point(first.generating, first.generated)
    t = contact_parameter(p, n, first.generating, c)
    bounds = np.cumsum([0] + [len(f[0]) for f in frames]).tolist()
    for g, (a, b) in zip(gens, itertools.pairwise(bounds), strict=True):
        centre = g.parent.arc_center()
        if centre is not None:  # an arc centred on the pitch line touches at one shift
            t[a:b] = contact_parameter(p[a:b], n[a:b], first.generating, c, arc_center=centre)
    x = first.generating.to_fixed(p, t)
    return [(t[a:b], x[a:b], p[a:b], tg[a:b]) for a, b in itertools.pairwise(bounds)]


def rack_line_meshline_point(gen: Generated) -> Callable[[float], tuple[float, float]] | None:
    """Return the meshline point of a straight rack piece as a function of one parameter, in float arithmetic.

    For a root search along a rack line (where its contact leaves a tip circle), evaluated once per
    step: the contact of a translating generator is linear in t (module docstring), and this is
    :meth:`Generated.meshline_contact` at one parameter operation for operation (the point
    a + s d, the normal d turned clockwise, t = -(n x (p - C)) / (n x V), x = p + t V, NaN where
    n x V vanishes), the same numbers without its arrays.

    Parameters
    ----------
    gen : Generated
        A piece whose parent is a :class:`~rotorcad.curves.Line`, generated by a
        :class:`~rotorcad.kinematics.Translation`.

    Returns
    -------
    callable or None
        s -> (x, y) of the contact in the fixed frame (mm); None for any other piece.
    """
    if type(gen.parent) is not Line or not isinstance(gen.generating, Translation):
        return None
    a0, a1 = (float(v) for v in gen.parent.a)  # the line a + s d of Line.frame
    d0, d1 = (float(v) for v in gen.parent.frame(np.zeros(1))[1][0])
    n0, n1 = d1 * gen.parent_direction, -(d0 * gen.parent_direction)  # perp_cw of the travel's tangent
    c0, c1 = (float(v) for v in pitch_point(gen.generating, gen.generated))
    v0, v1 = (float(v) for v in gen.generating.velocity_array)
    den = n0 * v1 - n1 * v0
    touching = abs(den) > 1e-12 * gen.generating.speed

    def point(s: float) -> tuple[float, float]:
        p0, p1 = a0 + s * d0, a1 + s * d1
        t = -(n0 * (p1 - c1) - n1 * (p0 - c0)) / den if touching else float("nan")
        return p0 + t * v0, p1 + t * v1

    return point


def rack_frame(points: Array, pitch_radius: float) -> Array:
    """Carry fixed-frame rack points (pitch line x = r1w, motion +y) into the rack frame of CONTRACT.md.

    In the rack frame x runs along the pitch line in the direction of motion, y = 0 on the pitch
    line, y > 0 away from the male centre.

    Parameters
    ----------
    points : (n, 2) float array, mm
        Rack points in the fixed frame.
    pitch_radius : float, mm
        Male pitch radius r1w: the rack's pitch line.

    Returns
    -------
    (n, 2) float array, mm
        ``(y, x - r1w)`` of every point.
    """
    p = as_points(points)
    return np.stack([p[:, 1], p[:, 0] - pitch_radius], axis=-1)


def from_rack_frame(points: Array, pitch_radius: float) -> Array:
    """Inverse of :func:`rack_frame`."""
    p = as_points(points)
    return np.stack([p[:, 1] + pitch_radius, p[:, 0]], axis=-1)


__all__ = [
    "Contact",
    "Generated",
    "conjugate",
    "contact_parameter",
    "from_rack_frame",
    "meshline_contacts",
    "rack_frame",
    "rack_line_meshline_point",
]

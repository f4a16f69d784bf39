"""Rotor pieces cut by a straight or circular rack piece or by a point path, sampled in closed form.

A rack piece that is a :class:`~rotorcad.curves.Line` or an :class:`~rotorcad.curves.Arc` cuts a
rotor curve that the gear's tool cut (:class:`rotorcad.gears.tool.ToolCut`) evaluates in closed form,
with its curvature: the law of gearing solved for a rack-rotor motion (Litvin, *Gear Geometry and
Applied Theory*, eq. 6.1.7). The curvature places the samples in one step
(:func:`rotorcad.gears.sampling.chord_counts`, :func:`rotorcad.gears.sampling.grid_parameters`) instead of the
generic sampler's refinement passes (:func:`rotorcad.curves.sample_curve`), which evaluate the
envelope engine several times.

The male turns counter-clockwise about O1 = (0, 0) at rate 1 while the rack moves +y at r1w per
radian: the tool cut's own setting, with r = r1w. The female turns clockwise about O2 = (a, 0); in
the mirror image x -> a - x it sits at the origin, turns counter-clockwise at rate r1w / r2w and
the rack (pitch line x = r2w) moves +y at r2w per radian of that turn: again the tool cut's
setting, with r = r2w, whose points map back to the female's own frame by (x, y) -> (-x, y).

A rack piece that is a corner's (or a tip circle's) :class:`~rotorcad.curves.PointPath` cuts the
carried point's path relative to the rotor, in contact at the path's own parameter
(:class:`_CutByPath`); the generic sampler places its samples on that closed-form evaluation.

The samples lie on the piece's :class:`~rotorcad.envelope.Generated` curve, which the segment keeps
(the exact STEP writer and the analysis evaluate it). Where the generic sampler would meet a point
out of contact (a rack normal along the motion: the envelope engine's NaN, dropped by
:meth:`rotorcad.profile.Segment.sample`) or where the closed-form chords miss the tolerance, the
piece is left to the generic sampler (``None``), so that the outline is the generic one.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from rotorcad.curves import Arc, Curve, Line, Mapped, PointPath, sample_curve
from rotorcad.gears.sampling import SAMPLING_MARGIN, arc_intervals, chord_counts, grid_parameters, involute_parameters, span
from rotorcad.gears.tool import ToolCut
from rotorcad.geometry import Array, normalize, perp_cw, take_rows
from rotorcad.kinematics import Body, Translation
from rotorcad.profile import Segment
from rotorcad.roles import Side

LAND_SAMPLES = 17
"""Fewest samples of a land (a circle about the rotor's axis, cut by a rack line parallel to the
pitch line), as :func:`rotorcad.curves.sample_curve` takes of any piece: a rotor's points file keeps
enough points on a tip or root land to be read back as one (with 5, the N rack and Rinder-Deix males
read from their own CSV gained a sealing cusp the design has not: tests/test_verdict_invariance.py)."""

GRID = 129
"""Equally spaced parameters at which a cut piece's curvature is evaluated to place its samples."""

REFINES = 2
"""Passes that split the chords whose sagitta estimate exceeds the tolerance before the generic
sampler takes the piece over."""

MOST_SAMPLES = 20_000
"""Most samples of one piece in closed form: a count beyond it (the curvature near a cusp) leaves
the piece to the generic sampler."""

_NO_CONTACT = 1e-12
"""The envelope engine's test for a rack normal along the motion, |n x v| <= 1e-12 |v|
(:func:`rotorcad.envelope.contact_parameter`), and for an arc centred on the pitch line."""


def cut_segment(
    name: str, curve: Curve, rack_curve: Curve, side: Side, r1: float, a: float, tolerance: float, rotor: Body
) -> Segment | None:
    """Sample a rotor piece cut by a straight or circular rack piece or a point path in closed form.

    Parameters
    ----------
    name : str
        Segment name.
    curve : Curve
        The piece's generated curve as :class:`rotorcad.screw_rotors.ScrewRotors` makes it: for the
        male ``Generated(rack_curve.reversed(), rack, male)``, for the female
        ``Mapped(Generated(rack_curve, rack, female), identity, (-a, 0))``; kept on the segment.
    rack_curve : Curve
        The rack piece in the fixed frame at t = 0 (pitch line x = r1w, motion +y).
    side : Side
        The rotor cut.
    r1 : float
        Male pitch radius r1w, mm.
    a : float
        Centre distance, mm.
    tolerance : float
        Largest chord error, mm.
    rotor : Body
        The rotor's motion (``pair.mesh.male`` or ``pair.mesh.female``).

    Returns
    -------
    Segment or None
        The samples (parameters of ``curve``, points in the rotor's own frame, unit tangents along
        the travel); None where the piece is not a line, an arc or a point path observed by the
        rack, where a point of a line or an arc has no contact (the generic sampler decides
        there) or where a chord misses the tolerance.
    """
    male = side is Side.MALE
    if type(rack_curve) is PointPath and type(rack_curve.observer) is Translation:
        return _path_segment(name, curve, rack_curve, rotor, tolerance)
    if type(rack_curve) not in (Line, Arc):
        return None
    r = r1 if male else a - r1
    s0, s1 = float(curve.s0), float(curve.s1)  # parameters of the rack piece (the same for both rotors)
    if isinstance(rack_curve, Line):
        ax, ay = rack_curve.a
        d = np.subtract(rack_curve.b, rack_curve.a, dtype=float)
        d /= math.hypot(*d)
        if abs(d[1]) <= _NO_CONTACT:  # normal along the motion: no contact anywhere
            return None
        start, direction = ((ax, ay), (d[0], d[1])) if male else ((a - ax, ay), (-d[0], d[1]))
        cut = ToolCut("line", r, 1.0, start=start, direction=direction)
        offset, flip = 0.0, 1.0  # tool parameter s' = s; tool tangent = mirrored tangent
    else:
        kx, ky = rack_curve.center
        on_pitch_line = abs(kx - r1) <= _NO_CONTACT * r1  # every point touches when K passes C
        if not on_pitch_line:
            lo, hi = min(s0, s1), max(s0, s1)
            k = math.floor((lo - math.pi / 2) / math.pi) + 1  # first zero of cos(s) above lo
            if lo - _NO_CONTACT <= math.pi / 2 + k * math.pi <= hi + _NO_CONTACT:
                return None
        cut = ToolCut("arc", r, 1.0, center=(kx, ky) if male else (a - kx, ky), radius=rack_curve.radius)
        if on_pitch_line:
            cut.arc = (cut.arc[0], 0.0, cut.arc[2])  # the engine's constant contact turn
        offset, flip = (0.0, 1.0) if male else (math.pi, -1.0)  # mirrored polar angle s' = pi - s
    s = _involute(cut, s0, s1, tolerance) if isinstance(rack_curve, Line) else None
    if s is None:
        grid = span(s0, s1, GRID)
        _, _, turning, speed = cut.cut(offset + flip * grid if offset else grid, curvature=True)
        if np.ndim(turning) == 0:  # a line's cut turns at a constant rate per mm of s
            turning = np.full(grid.shape, turning)
        if not (np.isfinite(turning).all() and np.isfinite(speed).all()):
            return None
        counts = chord_counts(turning, speed, abs(s1 - s0) / (GRID - 1))
        if not _few(counts, tolerance):  # a cusp's curvature: the generic sampler
            return None
        s = grid_parameters(counts, s0, s1, tolerance)
    for _ in range(REFINES + 1):
        if len(s) > MOST_SAMPLES:
            return None
        z, w = cut.cut(offset + flip * s if offset else s, pairs=False)
        if not (np.isfinite(z).all() and np.isfinite(w).all()):
            return None
        # the sagitta of a chord whose end tangents turn by d(psi): L |d(psi)| / 8 (circular arc)
        sag = np.abs(z[1:] - z[:-1]) * np.abs(np.angle(w[1:] * np.conj(w[:-1]))) / 8.0
        if (sag <= tolerance).all():
            break
        # the curvature estimate fell short (the last chords before a cusp): split those chords
        s = _split(s, np.maximum(np.ceil(np.sqrt(sag / tolerance) * SAMPLING_MARGIN), 1.0).astype(int))
    else:
        return None  # still beyond the tolerance: the generic sampler
    # tangents along the travel: a generated curve's frame tangent is the rack tangent turned with
    # the rotor; mirrored back for the female, and against the mirrored polar angle for its arcs
    w = w * (curve.direction * flip)
    if not male:
        z, w = -np.conj(z), -np.conj(w)
    return Segment(name, curve, s, _pairs(z), _pairs(w))


@dataclass(frozen=True)
class _CutByPath(Curve):
    """What a rack piece that is a point path (:class:`~rotorcad.curves.PointPath`) cuts on a rotor.

    The path is traced in the rack by a point P carried by a rotor (a sharp corner, or with
    ``offset`` the centre of a tip circle). Its normal at parameter s passes through the pitch
    point C when P is there (C is the instantaneous centre of the carrier relative to the rack),
    so the law of gearing (Litvin eq. 6.1.7) puts the contact at the motion parameter t = s and
    the cut point is the carried point, at t = s, in the generated rotor's frame: an epitrochoid
    (a hypotrochoid for the own rotor: the corner itself). It evaluates, in closed form, the
    same curve as ``Generated(path, rack, rotor)`` with ``path`` travelled as ``parent``, at the
    same parameters; points where the rack normal lies along the motion are out of contact (NaN),
    as in :func:`rotorcad.envelope.contact_parameter`.

    Parameters
    ----------
    path : PointPath
        The rack piece, observed by the rack.
    generated : Body
        The rotor cut.
    s0, s1 : float
        Travel, as the generated curve's.
    """

    path: PointPath
    generated: Body
    s0: float
    s1: float

    def frame(self, s: Array) -> tuple[Array, Array]:
        """Return points (mm) and unit tangents along increasing ``s``, (n, 2) each."""
        path = self.path
        a = np.broadcast_to(np.asarray(path.carried, dtype=float), (len(s), 2))
        x = path.carrier.to_fixed(a, s)
        tangent = normalize(path.carrier.velocity_at(x) - path.observer.velocity_at(x))  # rack frame = fixed
        if path.offset:
            x = x + path.offset * perp_cw(tangent)
        p = self.generated.to_body(x, s)
        t = self.generated.vectors_to_body(tangent, s)
        lost = np.abs(tangent[:, 1]) <= _NO_CONTACT  # rack normal along the motion (+y): no contact
        if lost.any():
            p[lost] = np.nan
            t[lost] = np.nan
        return p, t


def _path_segment(name: str, curve: Curve, path: PointPath, generated: Body, tolerance: float) -> Segment:
    """Sample what a rack point path cuts, by the generic sampler on its closed form (:class:`_CutByPath`).

    Parameters
    ----------
    name : str
        Segment name.
    curve : Curve
        The generated curve kept on the segment (``Generated``, or for the female its ``Mapped``).
    path : PointPath
        The rack piece.
    generated : Body
        The rotor cut.
    tolerance : float
        Largest chord error, mm.

    Returns
    -------
    Segment
        Parameters of ``curve``, points in the rotor's own frame, unit tangents along the travel;
        points out of contact dropped as :meth:`rotorcad.profile.Segment.sample` does.
    """
    fast = _CutByPath(path, generated, float(curve.s0), float(curve.s1))
    s, p, t = sample_curve(fast, tolerance)
    if isinstance(curve, Mapped):  # the female, about its own centre
        p = p + np.asarray(curve.shift, dtype=float)
    ok = np.isfinite(p[:, 0]) & np.isfinite(p[:, 1]) & np.isfinite(t[:, 0]) & np.isfinite(t[:, 1])  # by columns: faster
    return Segment(name, curve, s, p, t) if ok.all() else Segment(name, curve, s[ok], take_rows(p, ok), take_rows(t, ok))


def _few(counts: tuple[Array, Array], tolerance: float) -> bool:
    """Whether the chord count of :func:`rotorcad.gears.sampling.chord_counts` stays within :data:`MOST_SAMPLES`.

    Parameters
    ----------
    counts : two (m,) float arrays
        The cumulative counts of :func:`rotorcad.gears.sampling.chord_counts`.
    tolerance : float
        Largest chord error, mm.

    Returns
    -------
    bool
        True when :func:`rotorcad.gears.sampling.grid_parameters` would place fewer samples.
    """
    quadratic, cubic = counts
    total = quadratic[-1] / math.sqrt(8.0 * tolerance) + cubic[-1] / math.cbrt(72.0 * math.sqrt(3.0) * tolerance)
    return bool(total * SAMPLING_MARGIN < MOST_SAMPLES)


def _split(s: Array, parts: Array) -> Array:
    """Split interval i of the parameters ``s`` into ``parts[i]`` equal parts.

    Parameters
    ----------
    s : (m,) float array
        Parameters in order of travel.
    parts : (m - 1,) int array
        Parts of each interval (1: kept).

    Returns
    -------
    (m',) float array
        The refined parameters, the old ones among them (the ends exactly).
    """
    j = np.repeat(np.arange(len(parts)), parts)
    k = np.arange(len(j)) - np.repeat(np.cumsum(parts) - parts, parts)
    out = np.empty(len(j) + 1)
    out[:-1] = s[j] + (s[j + 1] - s[j]) * (k / parts[j])
    out[-1] = s[-1]
    return out


def _involute(cut: ToolCut, s0: float, s1: float, tolerance: float) -> Array | None:
    """Return the parameters that sample a straight rack piece's cut, an involute, to a chord tolerance.

    The cut of a straight rack piece is an involute of the base circle r_b = r |tau_x| (the line
    of action through C along the piece's normal; ISO 21771 sec. 2.3), whose radius of curvature
    is the roll distance: :func:`rotorcad.gears.sampling.involute_parameters` places its samples in one step.

    Parameters
    ----------
    cut : ToolCut
        The straight piece's cut ("line").
    s0, s1 : float
        Parameters of the piece's start and end, mm along the rack line.
    tolerance : float
        Largest chord error, mm.

    Returns
    -------
    (n,) float array or None
        Parameters from ``s0`` to ``s1``; None where the roll distance changes sign inside the
        piece (the cut passes the base circle: a cusp) or the base circle is too small to divide
        by (a piece almost parallel to the pitch line cuts a circle): the curvature grid decides.
    """
    rb = cut.r * abs(cut.tangent.real)
    if rb == 0.0:  # a piece parallel to the pitch line cuts a circle about O, turning s / r
        (ax, ay), t0 = cut.start, cut.turn[0]
        # at least as many samples as the generic sampler takes (:data:`LAND_SAMPLES`)
        n = arc_intervals(abs(s1 - s0) / cut.r, math.hypot(ax, ay + cut.r * t0), tolerance) + 1
        return span(s0, s1, max(n, LAND_SAMPLES))
    if rb <= 1e-9 * cut.r:
        return None
    a0, a1 = cut.roll()
    l0, l1 = a0 + a1 * s0, a0 + a1 * s1
    if l0 * l1 < 0.0:
        return None
    if l0 + l1 < 0.0:  # the roll distance counted the other way: its size is what matters
        a0, a1 = -a0, -a1
    return involute_parameters(s0, s1, (a0, a1), rb, tolerance)


def _pairs(z: Array) -> Array:
    """Return complex numbers x + i y as an (n, 2) float array."""
    return np.ascontiguousarray(z, dtype=complex).view(np.float64).reshape(-1, 2)  # (re, im) pairs, one copy at most


__all__ = ["GRID", "cut_segment"]

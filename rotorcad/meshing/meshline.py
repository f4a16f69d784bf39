"""The meshline of a screw-rotor pair, piece by piece, and what is read off its samples alone.

After Rinder (*Sonderverzahnungen für Schraubenverdichterrotoren*), sec. 2: the meshline
(Eingriffslinie) is the set of contact points in the fixed transverse frame; for a rack-generated
pair it is the rack's contact locus. Here: a piece's samples (:class:`MeshlinePiece`, sampled about
evenly along the meshline), the lobe part of each point (:func:`flank_roles`), the meshline's
tangents (a spline over the piece, never point differences), its reversals and sharp turns, and
the corner of a turn that a fit through points rounds (:func:`turn_corner`).
"""

from __future__ import annotations

import itertools
from dataclasses import dataclass, field
from functools import cached_property

import numpy as np

from rotorcad.envelope import Generated, meshline_contacts
from rotorcad.geometry import closest_pair, dots, hypot_within, row_norms, take_rows
from rotorcad.roles import Flank, PieceRole
from rotorcad.rotor_pair import RotorPair
from rotorcad.screw_rotors import RackPiece
from rotorcad.spline_slopes import makima_slopes

_FLANKS = np.array(list(Flank), dtype=object)
FLANK_CODE = {flank: i for i, flank in enumerate(Flank)}
"""Index of each lobe part in :data:`_FLANKS`."""


@dataclass(frozen=True, eq=False)
class MeshlinePiece:
    """Contact points of one rack piece, ordered along the piece.

    Parameters
    ----------
    name : str
        Name of the segment the piece generates on the male.
    kind : PieceRole
        What the rack piece does (a curve, or a corner's path).
    s : (n,) float array
        Parameter of the rack piece at each contact.
    t : (n,) float array, rad
        Male rotation angle at contact.
    points : (n, 2) float array, mm
        Contact points in the fixed frame (the meshline).
    tangents : (n, 2) float array
        Unit common tangent of the flanks at contact, fixed frame.
    male_name, female_name : str
        Names of the segments the piece generates on the male and on the female.
    roles : (n,) object array of Flank
        The lobe part of each point, read off the rack (:func:`flank_roles`).
    """

    name: str
    kind: PieceRole
    s: np.ndarray
    t: np.ndarray  # male rotation angle at contact (rad)
    points: np.ndarray  # fixed frame
    tangents: np.ndarray  # common tangent of the flanks at contact (unit)
    male_name: str = ""
    female_name: str = ""
    roles: np.ndarray = field(
        default_factory=lambda: np.zeros(0, dtype=object)
    )  # (n,) Flank per point: the lobe part (read off the rack)
    rack_index: int = -1  # the rack piece (index into ScrewRotors.rack) whose contacts these are
    role_codes: np.ndarray | None = None  # (n,) int: roles as indices into _FLANKS (FLANK_CODE), when known

    @cached_property
    def steps(self) -> np.ndarray:
        """Lengths of the chords between consecutive points, (n - 1,) float, mm (computed once)."""
        d = self.points[1:] - self.points[:-1]  # np.diff(points, axis=0), the same numbers
        return np.hypot(d[:, 0], d[:, 1])

    def flank_mask(self, flank: Flank) -> np.ndarray:
        """Return ``roles == flank``, (n,) bool (from :attr:`role_codes` when known: no object comparison)."""
        if self.role_codes is not None:
            return self.role_codes == FLANK_CODE[flank]
        return self.roles == flank


def flank_roles(points: np.ndarray, tangents: np.ndarray, pitch_radius: float, scale: float) -> np.ndarray:
    """Return the lobe part of rack points (fixed frame at t = 0, pitch line x = r1w, motion +y).

    Parameters
    ----------
    points, tangents : (n, 2) float array
        Rack points (mm) and unit tangents along the chain (the direction of motion).
    pitch_radius : float, mm
        Male pitch radius r1w: the rack's pitch line.
    scale : float, mm
        A length of the pair for the flatness tolerance.

    Returns
    -------
    (n,) object array of Flank
        DRIVING where the rack rises towards the male tip (x grows along the chain), SEALING
        where it falls, TIP / ROOT on a land above / below the pitch line (Rinder sec. 1.2).
    """
    return _FLANKS[flank_codes(points, tangents, pitch_radius, scale)]


def flank_codes(points: np.ndarray, tangents: np.ndarray, pitch_radius: float, scale: float) -> np.ndarray:
    """Return :func:`flank_roles` as indices into the lobe parts (:data:`FLANK_CODE`), (n,) int."""
    rise = tangents[:, 0]
    flat = np.abs(rise) <= 1e-9
    above = points[:, 0] > pitch_radius + 1e-9 * scale
    return np.where(
        flat,
        np.where(above, FLANK_CODE[Flank.TIP], FLANK_CODE[Flank.ROOT]),
        np.where(rise > 0, FLANK_CODE[Flank.DRIVING], FLANK_CODE[Flank.SEALING]),
    )


UNEVEN = 4.0
"""A piece sampled evenly over its rack parameter whose longest meshline step exceeds this many times
the mean step is resampled evenly along its meshline (:func:`even_meshline_parameters`)."""


def even_meshline_parameters(gen: Generated, s0: float, s1: float, samples: int, scale: float) -> np.ndarray:
    """Return rack parameters of one piece whose contacts lie about evenly along the meshline.

    A rack curve fitted through a whole flank of points carries, in a short stretch of its
    parameter, a long stretch of meshline (the N rack's tip circle: 0.2 mm of rack, 30 mm of
    meshline along the male tip circle); sampled evenly over the parameter, that stretch gets two or
    three contacts and no tangent. Where the even sampling is uneven along the meshline (a step over
    :data:`UNEVEN` times the mean), the parameter is redistributed by the meshline's arc length
    (plus a fifth of the samples evenly over the parameter, for the parts out of contact), twice,
    with as many samples as keep the steps at 1/2000 of the centre distance (at least ``samples``,
    at most 8 times as many).

    Parameters
    ----------
    gen : Generated
        The rack piece generating the female (its contact gives the meshline).
    s0, s1 : float
        The piece's parameter range.
    samples : int
        Samples of an even piece.
    scale : float, mm
        The centre distance.

    Returns
    -------
    (n,) float array
        Monotonic from ``s0`` to ``s1``.
    """
    return even_meshline_contact(gen, s0, s1, samples, scale)[0]


def even_meshline_contact(
    gen: Generated, s0: float, s1: float, samples: int, scale: float
) -> tuple[np.ndarray, tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]]:
    """Return the parameters of :func:`even_meshline_parameters` and the contact at them.

    The contact is :meth:`rotorcad.envelope.Generated.meshline_contact` at the returned
    parameters (the meshline alone, the numbers of the full conjugate), the one evaluation that
    placed them: a caller needs no second one.

    Parameters
    ----------
    gen, s0, s1, samples, scale
        As for :func:`even_meshline_parameters`.

    Returns
    -------
    s : (n,) float array
        Monotonic from ``s0`` to ``s1``.
    contact : tuple of (n,) and three (n, 2) float arrays
        ``t`` (rad), ``meshline`` (mm), the rack's points (mm) and unit tangents along its travel
        at ``s``.
    """
    s = np.linspace(s0, s1, samples)
    contact = gen.meshline_contact(s)
    for _ in range(2):
        spread = _spread_along_meshline(s, _meshline_steps(contact[1]), samples, scale)
        if spread is None:
            break
        s = spread
        contact = gen.meshline_contact(s)
    return s, contact


def _meshline_steps(x: np.ndarray) -> np.ndarray:
    """Lengths of the steps between meshline points ((n, 2), mm), 0 where not finite: (n - 1,) float, mm."""
    d = x[1:] - x[:-1]  # np.diff(x, axis=0), the same numbers
    step = np.hypot(d[:, 0], d[:, 1])
    return np.where(np.isfinite(step), step, 0.0)


def _spread_along_meshline(s: np.ndarray, step: np.ndarray, samples: int, scale: float) -> np.ndarray | None:
    """Parameters that spread a piece's contacts evenly along its meshline, or None where they are even.

    One round of :func:`even_meshline_parameters`: ``s`` the parameters, ``step`` the steps
    between their meshline points (:func:`_meshline_steps`, mm), ``samples`` and ``scale`` (mm)
    as there.
    """
    length = float(step.sum())
    if length <= 0 or step.max() <= UNEVEN * length / (len(s) - 1):
        return None
    measure = np.concatenate([[0.0], np.cumsum(step + 0.25 * length / (len(s) - 1))])
    n = int(np.clip(np.ceil(2000.0 * length / scale), samples, 8 * samples))
    return np.interp(np.linspace(0.0, measure[-1], n), measure, s)


def meshline_pieces(rack: list[RackPiece], pair: RotorPair, samples: int, corner_slack: float = 1e-3) -> list[MeshlinePiece]:
    """Return the meshline of a rack-generated pair, piece by piece: one pass over all the rack's pieces.

    The contacts of every rack piece inside both bores (within 1 µm), ``samples`` evenly over each
    piece's parameter, or resampled along the meshline where that is uneven (the rounds of
    :func:`even_meshline_contact`); the contacts of each round are solved for all its pieces at
    once (:func:`rotorcad.envelope.meshline_contacts`) and the points' lobe parts read off the
    rack at once (:func:`flank_roles`). Pieces with fewer than two contacts are left out.

    Parameters
    ----------
    rack : list of RackPiece
        The rack chain (:attr:`rotorcad.screw_rotors.ScrewRotors.rack`).
    pair : RotorPair
        The pair (its mesh, radii and centre distance; mm).
    samples : int
        Samples of an even piece.
    corner_slack : float, mm
        How far outside the bores a contact of a corner's path (a piece that is not a curve) still
        counts: 1 µm, or more for a profile given by points, whose tip corner may lie outside its
        tip circle by its accuracy.

    Returns
    -------
    list of MeshlinePiece
    """
    if not rack:
        return []
    mesh = pair.mesh
    a = pair.center_distance
    gens = [Generated(piece.curve, mesh.rack, mesh.female) for piece in rack]
    params = [np.linspace(piece.curve.s0, piece.curve.s1, samples) for piece in rack]
    contacts = meshline_contacts(gens, params)
    todo = list(range(len(gens)))
    # the first round's steps of all pieces at once (a piece's are those between its own points)
    ends = np.cumsum([0] + [len(p) for p in params]).tolist()
    steps = _meshline_steps(np.concatenate([c[1] for c in contacts]))
    first = [steps[i : j - 1] for i, j in itertools.pairwise(ends)]
    for round_ in range(2):  # the rounds of even_meshline_contact, for the uneven pieces together
        spread = {
            i: _spread_along_meshline(params[i], first[i] if round_ == 0 else _meshline_steps(contacts[i][1]), samples, a)
            for i in todo
        }
        todo = [i for i, new in spread.items() if new is not None]
        if not todo:
            break
        for i in todo:
            params[i] = spread[i]
        for i, contact in zip(todo, meshline_contacts([gens[i] for i in todo], [params[i] for i in todo]), strict=True):
            contacts[i] = contact
    s = np.concatenate(params)
    t, x, rack_pts, tan = (np.concatenate([c[k] for c in contacts]) for k in range(4))
    slack = np.repeat([corner_slack if piece.kind is not PieceRole.CURVE else 1e-3 for piece in rack], [len(p) for p in params])
    # within both bores (np.hypot(...) <= bound, hypot only near the bound); about O2 = (a, 0) by columns
    inside = hypot_within(x[:, 0], x[:, 1], pair.male_tip_radius + slack)
    inside &= hypot_within(x[:, 0] - a, x[:, 1], pair.female_tip_radius + slack)
    ok = np.isfinite(t) & inside & np.isfinite(x[:, 0]) & np.isfinite(x[:, 1])
    tan_fixed = mesh.rack.vectors_to_fixed(tan, t)
    codes = flank_codes(take_rows(rack_pts, ok), take_rows(tan, ok), pair.male_pitch_radius, a)
    roles = _FLANKS[codes]
    s, t, x, tan_fixed = s[ok], t[ok], take_rows(x, ok), take_rows(tan_fixed, ok)
    ends = np.cumsum([0] + [len(p) for p in params]).tolist()
    kept = [0, *np.cumsum(np.add.reduceat(ok, ends[:-1])).tolist()]  # contacts kept per piece (each has samples)
    out = []
    for index, (piece, (i, j)) in enumerate(zip(rack, itertools.pairwise(kept), strict=True)):
        if j - i < 2:
            continue
        names = (piece.male_name, piece.kind, s[i:j], t[i:j], x[i:j], tan_fixed[i:j])
        out.append(MeshlinePiece(*names, piece.male_name, piece.female_name, roles[i:j], index, codes[i:j]))
    return out


SHARP_TURN = np.pi / 4
"""rad: a meshline whose tangent turns by more than this within the resolution has a corner there
(as where a rack rounding about C meets a straight flank), at which its normal sweeps through
every direction in between."""


def reversals(points: np.ndarray, arclen: np.ndarray, longest: float = 0.0) -> np.ndarray:
    """Return the arc lengths (mm) where a sampled meshline turns back or turns sharply.

    It turns back where two consecutive chords point against each other, and sharply where its
    chords' direction changes by more than :data:`SHARP_TURN` within ``longest`` (mm); positions
    only, no tangents. A sign change of a normal's miss there is the turn, not a normal through a
    centre.
    """
    d = points[1:] - points[:-1]  # np.diff(points, axis=0), the same numbers
    back = np.flatnonzero(dots(d[:-1], d[1:]) < 0) + 1
    if longest <= 0 or len(d) < 2:
        return arclen[back]
    heading = np.unwrap(np.arctan2(d[:, 1], d[:, 0]))
    mid = 0.5 * (arclen[:-1] + arclen[1:])
    ahead = np.interp(mid + 0.5 * longest, mid, heading)
    behind = np.interp(mid - 0.5 * longest, mid, heading)
    sharp = np.flatnonzero(np.abs(ahead - behind) > SHARP_TURN)
    return np.concatenate([arclen[back], mid[sharp]])


def turn_corner(
    points: np.ndarray,
    arclen: np.ndarray,
    i: int,
    reach: float,
    circles: tuple[tuple[np.ndarray, float], ...] = (),
    accuracy: float = 0.0,
) -> np.ndarray | None:
    """Return the corner of a sampled meshline that turns sharply at sample ``i``, or None.

    A profile's curvature jump (the N rack's male tip round meeting its sealing flank) turns the
    meshline by a right angle at one point; a fit through points rounds that jump over a few
    micrometres of profile, and where one profile micrometre carries 45 of meshline (the tip round)
    the rounded turn overshoots the corner by 0.25 mm (measured from the N rack's own CSV: its
    meshline leaves the design's by up to 0.2 mm within 1 mm of the turn, by 1 um beyond). A turn
    by more than :data:`SHARP_TURN` is a corner: each branch, fitted by a quadratic in arc length
    from 2 to 4 times the resolution ``reach`` (mm, :func:`resolution`) away from the turn (outside
    the rounding), is extended towards it, and the corner is where the two extensions come nearest
    each other (within ``reach`` / 10). A branch whose fitted samples lie on one of ``circles``
    within 10 ``accuracy`` is that circle (a tip corner's path runs on its tip circle, Rinder's
    "Radlinien der Punkte"), and the corner is where the other branch's extension meets it: the
    rack-involute male's sealing tip corner meets the female's involute there, and from the
    female's points the corner's path leaves its circle by 14-60 um in the last millimetre before
    the turn.

    Parameters
    ----------
    points : (n, 2) float array, mm
        The meshline samples of one piece.
    arclen : (n,) float array, mm
        Their arc length.
    i : int
        The sample at the turn (the meshline's end nearest the housing cusp).
    reach : float, mm
        The resolution.
    circles : tuple of ((2,) float array, float), mm
        Centres and radii of circles a branch may run on (the tip circles).
    accuracy : float, mm
        Accuracy of the samples.

    Returns
    -------
    (2,) float array, mm, or None
        None where the samples within ``reach`` of sample ``i`` do not turn by more than
        :data:`SHARP_TURN` (chords either side), where a branch has under six samples or the
        extended branches turn less, or where their corner lies farther than ``reach`` from sample
        ``i`` or they pass farther than ``reach`` / 10 from each other.
    """
    s0 = arclen[i]
    back = points[int(np.searchsorted(arclen, s0 - reach))]
    ahead = points[min(int(np.searchsorted(arclen, s0 + reach)), len(points) - 1)]
    chords = (points[i] - back, ahead - points[i])
    if min(np.hypot(*chords[0]), np.hypot(*chords[1])) <= 0:
        return None
    if abs(np.angle(complex(*chords[1]) / complex(*chords[0]))) <= SHARP_TURN:
        return None  # the samples do not turn there: the nearest point of a smooth stretch
    before = (arclen >= s0 - 8 * reach) & (arclen <= s0 - 2 * reach)
    after = (arclen >= s0 + 2 * reach) & (arclen <= s0 + 8 * reach)
    if before.sum() < 6 or after.sum() < 6:
        return None
    fits = [np.polyfit(arclen[m] - s0, points[m], 2) for m in (before, after)]
    heading = [complex(*(np.polyval(np.polyder(f[:, k]), d) for k in (0, 1))) for f, d in zip(fits, (-reach, reach), strict=True)]
    if abs(np.angle(heading[1] / heading[0])) <= SHARP_TURN:
        return None
    u = np.linspace(-2 * reach, 2 * reach, 801)
    ext = [np.column_stack([np.polyval(f[:, 0], u), np.polyval(f[:, 1], u)]) for f in fits]
    for k, m in enumerate((before, after)):
        for centre, radius in circles:
            if np.abs(np.hypot(*(points[m] - centre).T) - radius).max() > 10 * accuracy:
                continue
            g = np.hypot(*(ext[1 - k] - centre).T) - radius  # the other branch's extension against the circle
            cut = np.flatnonzero(g[:-1] * g[1:] <= 0)
            if len(cut) == 0:
                return None
            j = int(cut[np.argmin(np.abs(u[cut]))])
            w = g[j] / (g[j] - g[j + 1]) if g[j] != g[j + 1] else 0.0
            corner = ext[1 - k][j] + w * (ext[1 - k][j + 1] - ext[1 - k][j])
            corner = centre + (corner - centre) * radius / np.hypot(*(corner - centre))
            return corner if np.hypot(*(corner - points[i])) <= reach else None
    a, b, gap = closest_pair(ext[0], ext[1])
    corner = 0.5 * (ext[0][a] + ext[1][b])
    if gap > 0.1 * reach or np.hypot(*(corner - points[i])) > reach:
        return None
    return corner


def meshline_tangents(piece: MeshlinePiece, arclen: np.ndarray, accuracy: float, span: float = 0.0) -> np.ndarray:
    """Return the unit tangents of a meshline piece at its samples, (n, 2).

    Of the design's exact meshline, from a shape-preserving (modified Akima) cubic over the piece's
    parameter: an interpolating cubic rings where the meshline turns sharply (a rack rounding about
    C meeting a straight flank), and its tangent flips from sample to sample. Of a meshline
    generated from a profile known to ``accuracy`` (mm, > 0), from a smoothing cubic over its arc
    length that stays within that accuracy of the samples (scipy's s = n e^2, Dierckx sec. 5.2):
    the samples wobble by the profile's error, far more than their spacing resolves. Where the samples
    scatter by more than that (:func:`local_scatter`), each is weighted by ``accuracy`` over its own.

    With a ``span`` (mm, > 0) the tangent of a given profile's meshline is the direction of the smoothing
    cubic's chord over ``span`` of arc length centred on the sample (:func:`resolved_tangents`): the
    direction a profile known to its accuracy resolves (:func:`rotorcad.meshing.defects.resolution`).
    """
    pts = piece.points
    if accuracy > 0:
        from scipy import interpolate  # a given profile only: points come through scipy's fits anyway

        keep = np.concatenate([[True], np.diff(arclen) > 1e-12])
        if keep.sum() > 8:
            weight = accuracy / np.maximum(accuracy, local_scatter(pts[keep]))
            try:
                tck, _ = interpolate.splprep(pts[keep].T, u=arclen[keep], w=weight, s=keep.sum() * accuracy**2, k=3, quiet=2)
                tau = resolved_tangents(tck, arclen, span)
                norm = np.linalg.norm(tau, axis=1, keepdims=True)
                if np.all(norm > 0):
                    return tau / norm
            except (ValueError, TypeError):
                pass  # too few distinct samples for a smoothing cubic: the interpolating one below
    step = piece.s[1:] - piece.s[:-1]
    if (step > 0).all():  # the usual order: argsort's is the identity
        tau = makima_slopes(piece.s, pts)
    elif (step < 0).all():  # its reverse
        tau = makima_slopes(piece.s[::-1], pts[::-1])[::-1]
    else:
        order = np.argsort(piece.s)
        inverse = np.empty_like(order)
        inverse[order] = np.arange(len(order))
        # the slopes in the order of s, put back in the samples' order (rows by take: numpy 2 indexes
        # the rows of a 2-d array by an index array an order of magnitude slower)
        tau = makima_slopes(piece.s[order], pts.take(order, axis=0)).take(inverse, axis=0)
    norm = row_norms(tau)
    out = np.empty_like(tau)  # tau / norm[:, None], the same numbers, by columns
    np.divide(tau[:, 0], norm, out=out[:, 0])
    np.divide(tau[:, 1], norm, out=out[:, 1])
    return out


def resolved_tangents(tck: tuple, arclen: np.ndarray, span: float) -> np.ndarray:
    """Return a smoothing cubic's tangent directions resolved over ``span`` (mm) of arc length, (n, 2), not unit.

    The chord of the cubic (scipy's ``splprep`` ``tck`` over arc length) from ``arclen - w`` to ``arclen + w``,
    w = ``span`` / 2, or less near the piece's ends (the chord stays centred on its sample): the mean of the
    cubic's tangent over the chord, which is the tangent itself on a circle and a straight line. A given
    profile's meshline is placed to its accuracy e, and the fit between its points errs at a wavelength
    of two point spacings, which the meshline's sensitivity to the profile's normal magnifies: the
    rack-involute male as 600 exact points a lobe (0.145 mm apart, their fit's tangent 40-90 µrad off)
    puts the sealing flank's meshline 3-5 µm off the design's, in waves 0.27 mm long along its first 5 mm,
    where the smoothing cubic held to 1 µm follows them, its tangent up to 0.1 rad off, and the normal
    through O2 read a cusp the design has not (the design's normal passes O2 at the flank's start only).
    A tangent is resolved only over the resolution L = sqrt(8 a e) (:func:`rotorcad.meshing.defects.
    resolution`), the length the defect tests resolve; over that chord such waves average out. ``span``
    0: the cubic's own derivative.
    """
    from scipy import interpolate

    if span <= 0:
        return np.column_stack(interpolate.splev(arclen, tck, der=1))
    w = np.minimum(0.5 * span, np.minimum(arclen - arclen[0], arclen[-1] - arclen))
    chord = np.column_stack(interpolate.splev(arclen + w, tck)) - np.column_stack(interpolate.splev(arclen - w, tck))
    short = w < 1e-9 * max(span, 1.0)  # at the very ends: the derivative (a chord of no length has no direction)
    if short.any():
        chord[short] = np.column_stack(interpolate.splev(arclen[short], tck, der=1))
    return chord


LOCAL_WINDOW = 21
"""Samples over which :func:`local_scatter` takes the median of the meshline's third differences."""


def local_scatter(points: np.ndarray) -> np.ndarray:
    """Estimate how far each meshline sample lies off the smooth meshline, 2 sigma, (n,) float, mm.

    A meshline generated from a given profile is not uniformly accurate: where it runs near a circle
    about a centre (the normal passing O2 at the rack-involute's sealing flank's start) or along a
    point-generated part, the profile's error moves its samples far more than elsewhere (1000 exact
    points a lobe of the rack-involute male: the sealing flank's samples 5-7 µm off the design's
    meshline every 0.1 mm there, 0.02 µm along most of it), and a smoothing cubic held to one accuracy
    follows that scatter (its tangent 0.15 rad off, a cusp the design has not). The scatter normal to
    the samples is estimated as the outlines' (:func:`rotorcad.measured.outline.raw_scatter`): the
    third differences' component normal to the chord over sqrt(20), by the median over
    :data:`LOCAL_WINDOW` samples about each (1.4826 times, a normal scatter's MAD).

    Parameters
    ----------
    points : (n, 2) float array, mm
        The meshline samples, in order (n >= 4).

    Returns
    -------
    (n,) float array, mm
    """
    p = np.asarray(points, dtype=float)
    d3 = p[3:] - 3.0 * p[2:-1] + 3.0 * p[1:-2] - p[:-3]
    chord = p[3:] - p[:-3]
    length = np.hypot(chord[:, 0], chord[:, 1])
    normal = np.abs(chord[:, 0] * d3[:, 1] - chord[:, 1] * d3[:, 0]) / np.maximum(length, 1e-300) / np.sqrt(20.0)
    half = LOCAL_WINDOW // 2
    padded = np.pad(normal, (half, half), mode="edge")
    local = 2.0 * 1.4826 * np.median(np.lib.stride_tricks.sliding_window_view(padded, LOCAL_WINDOW), axis=1)
    return np.concatenate([local[:1], local, local[-1:], local[-1:]])  # the difference of samples i-1..i+2 at i


def with_neighbours(pieces: list[MeshlinePiece], j: int, local: int, reach: float) -> tuple[np.ndarray, int]:
    """Return piece ``j``'s meshline samples joined with the neighbours that continue it, and sample ``local``'s index.

    A profile given by points may end a corner's path exactly where the meshline turns (the
    narrow-tip male tip corner's path handing over to the sealing flank, from rotorcad's own rack
    CSV): the turn then lies at the end of a piece, and :func:`turn_corner` needs both branches.
    A neighbour continues the piece when its end lies within ``reach`` (mm) of the piece's end.
    """
    run, at = pieces[j].points, local
    if j > 0 and len(pieces[j - 1].points) and np.hypot(*(pieces[j - 1].points[-1] - run[0])) <= reach:
        before = pieces[j - 1].points[:-1]
        run, at = np.vstack([before, run]), at + len(before)
    if j + 1 < len(pieces) and len(pieces[j + 1].points) and np.hypot(*(pieces[j + 1].points[0] - run[-1])) <= reach:
        run = np.vstack([run, pieces[j + 1].points[1:]])
    return run, at


ZIGZAG = 4
"""How many times a given profile's meshline piece may turn back in male rotation before its length is
measured on averaged points (:func:`resolved_lengths`): a design's and a smooth fit's pieces turn at
their cusps only; the narrow-tip male as 9900 points a lobe with 1 µm turned its sealing curve piece
back some 200 times."""


def resolved_lengths(points: np.ndarray, t: np.ndarray, width: float) -> np.ndarray:
    """Return the lengths of a piece's steps measured on its points averaged over ``width`` of its length, (n - 1,) mm.

    A given profile's meshline is placed to its accuracy, and where the profile's fit carries curvature
    noise its points zig-zag about the true meshline at a wavelength far below the resolution
    sqrt(8 a e) (:func:`~rotorcad.meshing.defects.resolution`): the narrow-tip male as 9900 points a
    lobe with 1 µm of scatter put its sealing flank's curve piece on 31.9 mm of polyline for the
    design's 12.2 (the male rotation running back and forth by 0.1-0.5 deg), and the working length
    read 31.7 mm. On a piece whose male rotation turns back more than :data:`ZIGZAG` times, each point
    is replaced by the mean of the points within ``width`` / 2 of it along the polyline (nearer an
    end, within its distance to that end: the ends stay), which takes the zig-zag out (22.1 mm for 26.5
    on the driving flank, design 21.9); a piece that does not zig-zag keeps its chords (averaging a
    smooth meshline over twice the resolution shortens it by up to 1-2 % at 80 points a lobe).

    Parameters
    ----------
    points : (n, 2) float array, mm
        The piece's meshline points in order.
    t : (n,) float array, rad
        The male rotation at each.
    width : float, mm
        The length averaged over (twice the resolution); 0: the chords themselves (a design).

    Returns
    -------
    (n - 1,) float array, mm
    """
    d = np.diff(points, axis=0)
    chords = np.hypot(d[:, 0], d[:, 1])
    dt = np.diff(t)
    dt = dt[dt != 0]
    if width <= 0 or len(points) < 3 or np.count_nonzero(dt[1:] * dt[:-1] < 0) <= ZIGZAG:
        return chords
    s = np.concatenate([[0.0], np.cumsum(chords)])
    half = np.minimum(0.5 * width, np.minimum(s, s[-1] - s))
    lo = np.searchsorted(s, s - half, side="left")
    hi = np.searchsorted(s, s + half, side="right")
    total = np.vstack([np.zeros((1, 2)), np.cumsum(points, axis=0)])
    mean = (total[hi] - total[lo]) / (hi - lo)[:, None]
    e = np.diff(mean, axis=0)
    return np.hypot(e[:, 0], e[:, 1])

"""Rinder's kinematic rules on the meshline (sec. 2.2.1): cusp, jamming, slipping.

A defect (:class:`Defect`) is where the meshline normal passes through O1 or O2 (cusp), through the
pitch point C (jamming, except on an arc about C) or where the meshline crosses O1O2 away from C
(slipping). Each test is judged to the accuracy of the profile (:func:`resolution`,
:func:`robust_zeros`), so that a profile given by points makes no defect its design has not; a cusp
on a tip circle is that tip's corner (:func:`is_tip_corner`). The criteria are stated in
:mod:`rotorcad.meshing`.
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np

from rotorcad.meshing.meshline import MeshlinePiece, meshline_tangents, reversals
from rotorcad.roles import Flank, Side
from rotorcad.rotor_pair import RotorPair


@dataclass(frozen=True)
class Defect:
    """A point (or stretch) of the meshline that breaks one of Rinder's rules (sec. 2.2.1).

    Parameters
    ----------
    kind : {"cusp", "jamming", "slipping"}
        Cusp: the meshline normal passes through O1 (male) or O2 (female); jamming: through the pitch
        point C; slipping: the meshline crosses O1O2 away from C.
    rotor : {"male", "female"}
        The rotor the rule names.
    x, y : float, mm
        Where it occurs, fixed frame.
    angle_deg : float, deg
        Male rotation angle at that contact.
    flank : str
        Name of the meshline piece (or, for slipping between pieces, which tip touches which root).
    point_generated : bool
        True when the whole piece has its normal through the centre (a point-generated flank).
    extent : float, mm
        Meshline length over which it holds (0: a single point).
    role : Flank, optional
        The lobe part where it occurs.
    """

    kind: str  # cusp, jamming, slipping
    rotor: Side  # male, female (text reads as the rotor)
    x: float
    y: float
    angle_deg: float
    flank: str
    point_generated: bool = False
    extent: float = 0.0  # meshline length over which it holds (0: a single point)
    role: Flank | None = None  # the lobe part where it occurs

    def __post_init__(self) -> None:
        """Read the rotor given as text ("male", "female") as a :class:`Side`."""
        object.__setattr__(self, "rotor", Side(self.rotor))

    def as_dict(self) -> dict[str, object]:
        """Return the defect as plain values (an entry of ``defects`` in :meth:`MeshingAnalysis.summary`).

        Returns
        -------
        dict
            The fields by name, ``role`` as ``flank_role`` (its text, or None).
        """
        return {
            "kind": self.kind,
            "rotor": str(self.rotor),
            "x": self.x,
            "y": self.y,
            "angle_deg": self.angle_deg,
            "flank": self.flank,
            "point_generated": self.point_generated,
            "extent": self.extent,
            "flank_role": None if self.role is None else str(self.role),
        }


def resolution(accuracy: float, scale: float) -> float:
    """Return the shortest meshline stretch (mm) that the defect tests resolve.

    A profile known to an accuracy e has its tangent direction resolved over a chord no shorter than
    the one along which a circle of the pair's size (the centre distance a) leaves its tangent by e,
    sqrt(8 a e), nor than 0.5 % of a. A stretch along which the normal passes through a centre within
    the accuracy is an arc about that centre only when it is longer than this; sign changes nearer
    each other than this cancel; defects of one kind nearer each other than this are one.

    Parameters
    ----------
    accuracy : float, mm
        Accuracy of the profile (:attr:`MeshingAnalysis.judged_accuracy`).
    scale : float, mm
        The centre distance.

    Returns
    -------
    float, mm
    """
    return max(5e-3 * scale, float(np.sqrt(8.0 * scale * accuracy)))


def _median(values: np.ndarray) -> float:
    """``np.median`` of a 1-d array, the same number, by one partition (np.median's own way, without its overhead)."""
    n = len(values)
    if n == 0 or np.isnan(values).any():
        return float(np.median(values))
    k = n // 2
    if n % 2:
        return float(np.partition(values, k)[k])
    part = np.partition(values, (k - 1, k))
    return float((part[k - 1] + part[k]) / 2)


def _median_below(values: np.ndarray, bound: float) -> bool:
    """``_median(values) < bound``, the same answer, the median only where a count cannot tell.

    Fewer than n // 2 values below the bound put both middle values (one for an odd n) at or
    above it, and so their mean: the median is not below. Else the median decides.
    """
    if int(np.count_nonzero(values < bound)) < len(values) // 2:
        return False
    return bool(_median(values) < bound)


def robust_zeros(
    f: np.ndarray,
    band: np.ndarray,
    arclen: np.ndarray,
    longest: float,
    whole: bool = False,
    reversals: np.ndarray | None = None,
) -> tuple[list[tuple[float, int, int]], list[tuple[int, int]]]:
    """Find where a sampled function changes sign beyond its uncertainty, and where it stays within it.

    A sign change counts only where ``f`` leaves the band |f| <= ``band`` on both sides with opposite
    signs (noise within the band makes none): between two samples outside the band, or across a run of
    samples inside it (then at the sign change nearest the run's middle). A run inside the band that
    is ``longest`` long or more (or all of ``f`` when ``whole``) is a stretch, not a sign change.

    Parameters
    ----------
    f : (n,) float array
        The function at the samples.
    band : (n,) float array
        Its uncertainty at each sample (same unit).
    arclen : (n,) float array, mm
        Arc length of the samples along the meshline.
    longest : float, mm
        Length from which a run inside the band is a stretch.
    whole : bool
        Take all samples as one stretch.
    reversals : (m,) float array, mm, optional
        Arc lengths where the meshline turns back (:func:`reversals`): the tangent's half turn there
        changes the sign of every miss at once, which is no normal through a centre; sign changes
        within ``longest`` of them do not count.

    Returns
    -------
    crossings : list of (float, int, int)
        Fractional sample index i + w (0 <= w < 1) of each sign change, and the first and last
        sample of the stretch within which it is uncertain (the band's run around it).
    stretches : list of (int, int)
        First and last sample index of each stretch.
    """
    n = len(f)
    if whole:
        return [], [(0, n - 1)]
    inside = np.abs(f) <= band
    sign = np.sign(f)
    flip = sign[:-1] * sign[1:] < 0
    direct = np.flatnonzero(flip & ~inside[:-1] & ~inside[1:])
    crossings = [(float(i + f[i] / (f[i] - f[i + 1])), int(i), int(i) + 1) for i in direct]
    padded = np.zeros(len(inside) + 2, dtype=bool)  # the runs inside the band: where the padded mask changes
    padded[1:-1] = inside
    edges = np.flatnonzero(padded[1:] != padded[:-1])
    stretches = []
    for a, b in zip(edges[::2], edges[1::2] - 1, strict=True):
        if arclen[b] - arclen[a] >= longest:
            stretches.append((int(a), int(b)))
        elif a > 0 and b < n - 1 and sign[a - 1] * sign[b + 1] < 0:
            k = np.flatnonzero((f[a - 1 : b + 1] * f[a : b + 2] <= 0) & (f[a - 1 : b + 1] != f[a : b + 2])) + a - 1
            i = int(k[np.argmin(np.abs(k + 0.5 - 0.5 * (a + b)))])
            crossings.append((float(i + f[i] / (f[i] - f[i + 1])), int(a) - 1, int(b) + 1))
    return _persistent(sorted(crossings), stretches, arclen, longest, reversals), stretches


def _persistent(
    crossings: list[tuple[float, int, int]],
    stretches: list[tuple[int, int]],
    arclen: np.ndarray,
    longest: float,
    turns: np.ndarray | None = None,
) -> list[tuple[float, int, int]]:
    """Keep the sign changes whose new sign persists over ``longest`` (mm of meshline).

    Two sign changes nearer each other than that are an excursion and cancel; a sign change nearer
    than that to a stretch is where the stretch ends; one nearer than that to a reversal of the
    meshline (``turns``, arc lengths) is the reversal.
    """
    if not crossings:
        return []  # nothing to keep (the usual case: no test of the stretches and turns needed)
    at = np.interp([c[0] for c in crossings], np.arange(len(arclen)), arclen)
    near_stretch = np.zeros(len(at), dtype=bool)
    for r in turns if turns is not None else ():
        near_stretch |= np.abs(at - r) < longest
    for a, b in stretches:
        near_stretch |= (at > arclen[a] - longest) & (at < arclen[b] + longest)
    kept: list[tuple[int, float]] = []
    for k, s in enumerate(at):
        if kept and s - kept[-1][1] < longest:
            kept.pop()  # f went back to its sign within the resolution: no crossing
        else:
            kept.append((k, s))
    return [crossings[k] for k, _ in kept if not near_stretch[k]]


def _ramps(g: np.ndarray, arclen: np.ndarray) -> bool:
    """Tell whether a miss within its band over a stretch runs through the band rather than staying at 0.

    ``g`` is the miss over its band (|g| <= 1) along the stretch, at arc lengths ``arclen`` (mm).
    An arc about the centre keeps g about 0 all along; a slow crossing of it (on O1O2, where the
    normal passes through O1, O2 and C at once) runs g from one side of the band to the other: its
    median |g| is over 0.3, or its straight-line trend (least squares, robust to one wobbling sample
    of a fit's end) changes g by more than 1 over the stretch.
    """
    if np.median(np.abs(g)) > 0.3:
        return True
    span = float(arclen[-1] - arclen[0])
    if len(g) < 3 or span <= 0:
        return False
    slope = np.polyfit(arclen - arclen[0], g, 1)[0]
    return bool(abs(slope) * span > 1.0)


def _merged(defects: list[Defect], distance: float, spans: dict[int, np.ndarray] | None = None) -> list[Defect]:
    """Return the defects with those of one kind, rotor and flank part nearer than ``distance`` (mm) made one.

    Nearness is between the meshline points each defect holds (a stretch's, given in ``spans`` by
    the defect's ``id``; a point's own). The first of a group stands for it (a point-generated one
    before a point); extents add up.
    """
    spans = spans or {}
    held: list[np.ndarray] = []
    out: list[Defect] = []
    for d in sorted(defects, key=lambda d: not d.point_generated):
        mine = spans.get(id(d), np.array([[d.x, d.y]]))
        for k, e in enumerate(out):
            if (e.kind, e.rotor, e.role) != (d.kind, d.rotor, d.role):
                continue
            gap = np.hypot(*(held[k][:, None, :] - mine[None, :, :]).transpose(2, 0, 1)).min()
            if gap < distance:
                out[k] = replace(e, extent=e.extent + d.extent if d.point_generated else e.extent)
                held[k] = np.vstack([held[k], mine])
                break
        else:
            out.append(d)
            held.append(mine)
    return out


def is_tip_corner(defect: Defect, pair: RotorPair, tolerance: float) -> bool:
    """Tell whether a cusp is a rotor's tip corner rather than a defect of a working flank.

    Rinder (sec. 2.2.2): "Am Haupt- bzw. Nebenläuferkopf ist demnach nur eine Spitze oder Ecke als
    Flanke denkbar": at a rotor's tip only a corner is possible, and his cusp rule (sec. 2.2.1)
    names these corners in the profiles he calls runnable ("vgl. Bild 1, 2, 3 und 4"). A smooth
    flank touches its rotor's tip circle only on O1O2, so a cusp on a tip circle away from O1O2 is
    where the working flank hands over to that tip corner's path: the corner itself, which ends the
    working part. A point-generated piece (the corner's path, its normal through the centre all
    along) is that corner too.

    Parameters
    ----------
    defect : Defect
        A defect of :attr:`MeshingAnalysis.defects`.
    pair : RotorPair
        The pair (tip radii, centre distance; mm).
    tolerance : float, mm
        How near a tip circle the point must lie.

    Returns
    -------
    bool
        True for a cusp that is point-generated or lies on either rotor's tip circle.
    """
    if defect.kind != "cusp":
        return False
    if defect.point_generated:
        return True
    p = np.array([defect.x, defect.y])
    r1 = float(np.hypot(*p))
    r2 = float(np.hypot(p[0] - pair.center_distance, p[1]))
    return min(abs(r1 - pair.male_tip_radius), abs(r2 - pair.female_tip_radius)) <= tolerance


def meshline_defects(
    pieces: list[MeshlinePiece], pair: RotorPair, accuracy: float, tolerance: float, given: bool
) -> list[Defect]:
    """Return the cusps, jamming and slipping points on the meshline (Rinder sec. 2.2.1), a list of :class:`Defect`.

    The meshline normal (from a spline over each piece) through O1 or O2 is a cusp, through C
    jamming (except on a meshline arc about C, Rinder's exception); a crossing of O1O2 away from C
    is slipping, inside a piece or between two pieces.

    Each test is judged to the accuracy e of the profile (``accuracy``, :attr:`MeshingAnalysis.judged_accuracy`): the normal's
    miss f = (q - p) . tau of a centre q is uncertain by e + max(tolerance, e / L) |q - p| (a
    position error e, and a tangent error of ``tolerance`` rad or of e over the resolution L,
    :func:`resolution`), so a sign change of f counts only where f leaves that band on both
    sides (:func:`robust_zeros`), and a stretch of the meshline longer than L along which f
    stays in the band is an arc about q (Rinder's exception at C, a point-generated flank at O1
    or O2), whichever pieces it spans. A sign change within L (of a given profile; 0.1 % of the
    centre distance for the design) of a centre or of O1O2 is judged by the slipping rule; one
    within L of another, of such a stretch, of a reversal of the meshline or of a sign change
    of another centre's miss (both flip when the tangent turns over; the normals through two
    centres meet only on O1O2) is not robust and counts for nothing. Defects of one kind, rotor
    and flank part whose meshline points come nearer each other than L are one defect; a
    profile given by points or a drawing carries its accuracy
    (:attr:`rotorcad.screw_rotors.ScrewRotors.accuracy`), the design is judged to its chord
    tolerance.

    Parameters
    ----------
    pieces : list of MeshlinePiece
        The meshline (:attr:`MeshingAnalysis.pieces`).
    pair : RotorPair
        The pair (centre distance, pitch radius; mm).
    accuracy : float, mm
        Accuracy to which the tests are judged.
    tolerance : float, rad
        Uncertainty of the meshline's tangent direction (:attr:`MeshingAnalysis.tolerance`).
    given : bool
        The profile comes from points or a drawing (:attr:`MeshingAnalysis.is_given`), not the
        design's exact curves.

    Returns
    -------
    list of Defect
    """
    o1, o2 = np.zeros(2), np.array([pair.center_distance, 0.0])
    c = np.array([pair.male_pitch_radius, 0.0])
    tol, acc = tolerance, accuracy
    scale = pair.center_distance
    longest = resolution(acc, scale)
    found: list[Defect] = []
    spans: dict[int, np.ndarray] = {}  # the meshline points of each stretch, by the defect's id
    on_line = max(1e-3 * scale, longest if given else 0.0)  # through a centre or on O1O2 within the resolution
    for piece in pieces:
        pts = piece.points
        steps = np.hypot(*np.diff(pts, axis=0).T)
        arclen = np.concatenate([[0.0], np.cumsum(steps)])
        length = float(arclen[-1])
        if len(pts) < 4 or length < 1e-6 * scale:
            continue  # the piece touches at a single point (a tip or root land): no meshline
        tau = meshline_tangents(piece, arclen, acc if given else 0.0)
        # points on O1O2 are judged by the slipping rule alone (their normal along O1O2 passes
        # through O1, O2 and C at once), and C itself lies on every meshline
        judged = None  # (n,) bool, made where a crossing needs it
        turns = reversals(pts, arclen, longest if given else 0.0)
        tests = ((o1, "cusp", "male"), (o2, "cusp", "female"), (c, "jamming", "male"))
        misses = []
        for q, _kind, _ in tests:
            to_q = q - pts
            f = np.einsum("ij,ij->i", to_q, tau)  # zero: the meshline normal passes through q
            band = acc + max(tol, acc / longest) * np.hypot(*to_q.T)
            whole = _median_below(np.abs(f), tol * max(1.0, np.abs(to_q).max()))
            misses.append((f, band, whole, *robust_zeros(f, band, arclen, longest, whole, turns)))
        at = [np.interp([c[0] for c in m[3]], np.arange(len(arclen)), arclen) if m[3] else np.zeros(0) for m in misses]
        for k, ((q, kind, rotor), (f, band, whole, crossings, stretches)) in enumerate(zip(tests, misses, strict=True)):
            for i, j in stretches:
                if kind == "jamming":
                    continue  # meshline arc about C: both curvature centres in C (Rinder's exception)
                if (
                    not whole
                    and np.abs(pts[i : j + 1, 1]).min() < 1e-3 * scale
                    and _ramps(f[i : j + 1] / band[i : j + 1], arclen[i : j + 1])  # f runs through the band: no arc
                ):
                    continue  # a slow crossing on O1O2, where the normal passes through O1, O2 and C at once
                mid = i + int(np.searchsorted(arclen[i : j + 1], 0.5 * (arclen[i] + arclen[j])))
                found.append(
                    Defect(
                        kind,
                        rotor,
                        *map(float, pts[mid]),
                        float(np.degrees(piece.t[mid])),
                        piece.name,
                        True,
                        float(arclen[j] - arclen[i]),
                        piece.roles[mid],
                    )
                )
                spans[id(found[-1])] = pts[i : j + 1 : max(1, (j - i) // 200)]
            others = np.concatenate([at[m] for m in range(len(tests)) if m != k]) if crossings else None
            for (x, lo, hi), s_x in zip(crossings, at[k], strict=True):
                if np.any(np.abs(others - s_x) < longest):
                    continue  # the misses of two centres change sign together: the tangent turned over
                i, w = min(int(x), len(pts) - 2), x - min(int(x), len(pts) - 2)
                if judged is None:
                    judged = (np.abs(pts[:, 1]) > 1e-6 * scale) & (np.hypot(*(pts - c).T) > 1e-6 * scale)
                if not (judged[i] and judged[i + 1]):
                    continue
                p = pts[i] + w * (pts[i + 1] - pts[i])
                near = pts[max(lo, 0) : hi + 1]  # where the crossing may lie
                if np.hypot(*(near - q).T).min() < on_line or np.abs(near[:, 1]).min() < on_line:
                    continue  # through q itself (C lies on every meshline), or on O1O2 (slipping rule)
                ang = piece.t[i] + w * (piece.t[i + 1] - piece.t[i])
                role = piece.roles[i if w < 0.5 else i + 1]
                found.append(Defect(kind, rotor, float(p[0]), float(p[1]), float(np.degrees(ang)), piece.name, role=role))
        # crossings of O1O2 inside the piece; a piece that only reaches O1O2 at an end is judged
        # with its neighbour (slipping_between_pieces)
        y = pts[:, 1]
        crossings, _ = robust_zeros(y, np.full(len(y), max(acc, 1e-9 * scale)), arclen, longest, False)
        for x, _, _ in crossings:
            i, w = min(int(x), len(pts) - 2), x - min(int(x), len(pts) - 2)
            p = pts[i] + w * (pts[i + 1] - pts[i])
            if abs(p[0] - c[0]) > max(1e-6 * scale, on_line if given else 0.0):  # away from C
                ang = piece.t[i] + w * (piece.t[i + 1] - piece.t[i])
                role = piece.roles[i] if piece.roles[i] == piece.roles[i + 1] else (Flank.TIP if p[0] > c[0] else Flank.ROOT)
                at = (float(p[0]), float(p[1]), float(np.degrees(ang)))
                found.append(Defect("slipping", "male", *at, piece.name, role=role))
    found.extend(slipping_between_pieces(pieces, pair, accuracy, given))
    return _merged(found, longest, spans)


def slipping_between_pieces(pieces: list[MeshlinePiece], pair: RotorPair, accuracy: float, given: bool) -> list[Defect]:
    """Apply Rinder's slipping rule where the meshline crosses O1O2 between two pieces.

    That is where a tip touches the mate's root on O1O2 (a tip corner's path or a flank handing over
    to the next one), e.g. the female tip on the male root. The pieces are the meshline in order, and
    the next lobe's first piece follows the last; pieces lying on O1O2 (tip lands) hand over. A
    piece of a profile given by points or a drawing (not the design's exact curves) may end short
    of O1O2 by up to the resolution (:func:`resolution`). Arguments as for :func:`meshline_defects`.
    """
    scale = pair.center_distance
    c_x = pair.male_pitch_radius
    near = max(1e-6 * scale, resolution(accuracy, scale) if given else 0.0)
    off = accuracy if given else 1e-9 * scale  # a side of O1O2 beyond the accuracy
    ends = []  # per piece: sign of y leaving its start, reaching its end, its end point, its angle
    for piece in pieces:
        y = piece.points[:, 1]
        side = np.nonzero(np.abs(y) > off)[0]
        if len(side) == 0:
            continue
        ends.append((np.sign(y[side[0]]), np.sign(y[side[-1]]), piece.points[-1], float(piece.t[-1])))
    found = []
    for (_, out_sign, p, t), (in_sign, _, _, _) in zip(ends, ends[1:] + ends[:1], strict=True):
        if abs(p[1]) <= near and out_sign * in_sign < 0 and abs(p[0] - c_x) > near:  # not at C
            tip = p[0] > c_x
            land = "male tip on the female root" if tip else "female tip on the male root"
            role = Flank.TIP if tip else Flank.ROOT
            found.append(Defect("slipping", "male", float(p[0]), float(p[1]), float(np.degrees(t)), land, role=role))
    return found

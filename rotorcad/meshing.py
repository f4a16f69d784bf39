"""Meshing analysis of a screw-rotor pair after Rinder (*Sonderverzahnungen für Schraubenverdichterrotoren*).

Meshline, contact line (eq. 1), the kinematic rules of sec. 2.2.1 (cusp, jamming, slipping),
tightness and blow-hole (sec. 2.2.2), flute areas and displacement, sliding velocity and slip
(eqs. 2-4).

The meshline is the set of contact points in the fixed transverse frame: for a rack-generated
pair the rack touches both rotors at the same point, so it is the rack's contact locus. Only
contacts inside both bores (tip circles) count. Its tangent comes from an interpolating spline of
each piece over the generating parameter (never from point differences).

Rinder's criteria, as this module applies them
----------------------------------------------
*Geometric contact* (sec. 1.2, of Krigar's profile: "Eine Berührung der Flanken ... im
geometrischen Sinn mit gemeinsamen Tangenten im Eingriffspunkt, wie sie für eine lauffähige
Verzahnung gefordert werden muß"): the two flanks touch with a common tangent. A rack curve
touching both rotors gives it; the path of a tip corner (a *point-generated* flank part, "Radlinien
der Punkte P_H und P_N") does not: it is a corner against a flank.

*Working part* of a flank: its meshline with geometric contact. Point-generated parts seal (they
carry the meshline to the housing cusp, sec. 2.2.2) but do not drive; Rinder's narrow-tip profile
has "lange, punkterzeugte Flankenteile an der Dichtflanke" and still "gute Laufeigenschaften an
beiden Flankenteilen", and the asymmetric SRM profile's sealing flank runs properly "zumindest in
einem kleinen Flankenbereich" (a short straight female flank): a working part of any length makes
the flank run, with the helix.

*Cusp* (Spitze, sec. 2.2.1): a meshline point whose normal passes through O1 (a cusp on the male
flank) or O2 (on the female). Rinder names these in the profiles he calls runnable ("vgl. Bild 1,
2, 3 und 4") and says of the tips "Am Haupt- bzw. Nebenläuferkopf ist demnach nur eine Spitze oder
Ecke als Flanke denkbar" (sec. 2.2.2). So a cusp that is a rotor's tip corner is no defect: a
point-generated piece (the corner's path, its normal through the centre all along) and a cusp on
either tip circle, where the working flank hands over to a tip corner's path (a smooth flank touches
its tip circle only on O1O2), end the working part (:func:`is_tip_corner`; the JSON says
``tip_corner``). A cusp inside a working part, off the tip circles, is a defect: the flank reverses
(an undercut). The rack-involute pair shows it: its female sealing involute is used down to its
base circle, where its cusp meets the male tip corner.

*Jamming* (Klemmen): the meshline normal passes through the pitch point C, except where "beide
Flankenkrümmungsmittelpunkte mit dem Wälzpunkt zusammenfallen" (Lysholm's circular driving flank and
the symmetric SRM flanks, circles about C: their meshline is an arc about C).

*Slipping* (Durchrutschen): the meshline crosses O1O2 away from C; no flank drives the other there,
but "durch die verschraubten Zähne stellt diese Bedingung aber keine Einschränkung ... dar": it
does not count against running.

*Contact ratios* per flank (helical-gear sense): the transverse ratio is the male rotation over
which the working part is in contact, per angular pitch 2 pi / z1 (0 for a circle about C, which
touches at one instant: Lysholm's "nur infinitesimale Stirnüberdeckung"); the overlap ratio
(Sprungüberdeckung) is the male rotation over which one lobe's contact line lasts along the rotor,
the wrap angle 2 pi L / h1, per angular pitch: z1 L / h1; the total ratio is their sum. The helix
carries only a working contact along the rotor, so a flank without a working part has overlap 0.

*Runs* (a flank runs, i.e. carries the drive in the sense of rotation that loads it): it has a
working part, no cusp or jamming inside it, and a total contact ratio of at least 1 ("Die nur
infinitesimale Stirnüberdeckung wird durch ... hohe Sprungüberdeckung kompensiert"; the symmetric
SRM profile runs "bei ausreichender Verschraubung der Zähne in beiden Drehrichtungen").
*Runs without timing gears*: both flanks run (Rinder: "Lauffähigkeit in beiden Drehrichtungen",
sec. 2.1); Lysholm's profile, whose sealing flank has no working part, needs them ("ohne
Koppelgetriebe nicht einwandfrei verwendbar").

Angle convention
----------------
Every angle a user reads (JSON ``angle_deg`` keys, tables, pictures, report, README) is
:meth:`MeshingAnalysis.rinder_angle`: the male rotation still to go until the middle of a male tip
reaches the line of centres O1O2 (the lobe pointing at O2), positive before and negative after that
instant. In it the male tip reaches the housing cusp on the sealing side at a negative angle, as in
Rinder's Figs. 10-13 ("ca. -25°", sec. 3.2). The figures themselves are not legible in the source;
this zero and sign are read from the text of sec. 3.2.

Blow-hole (projected definition, stated because the paper gives no formula): the curvilinear
triangle in the transverse plane between the meshline's end E nearest the housing cusp K and K
itself, bounded by the arc of the female tip circle from K to the radial projection of E on it, the
arc of the male tip circle from K to the radial projection of E on it, and the two radial pieces
to E. It is zero when the meshline runs into the cusp. The spatial (curvilinear) blow-hole is
:class:`rotorcad.blow_hole.SpatialBlowHole` (:attr:`MeshingAnalysis.spatial_blow_hole`).
"""

from __future__ import annotations

from dataclasses import dataclass, field, replace
from functools import cached_property

import numpy as np
import shapely

from rotorcad.blow_hole import SpatialBlowHole
from rotorcad.envelope import Generated
from rotorcad.geometry import cross, wrap_angle
from rotorcad.profile import DEFAULT_TOLERANCE
from rotorcad.roles import Flank, PieceRole
from rotorcad.rotor_pair import RotorPair
from rotorcad.screw_rotors import ScrewRotors
from rotorcad.spline_slopes import makima_slopes


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


_FLANKS = np.array(list(Flank), dtype=object)
_FLANK_CODE = {flank: i for i, flank in enumerate(Flank)}
"""Index of each lobe part in :data:`_FLANKS`."""

ANGLE_CONVENTION = (
    "male rotation still to go until the middle of a male tip reaches the line of centres O1O2 "
    "(positive before, negative after; Rinder Figs. 10-13)"
)


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
    rise = tangents[:, 0]
    flat = np.abs(rise) <= 1e-9
    above = points[:, 0] > pitch_radius + 1e-9 * scale
    code = np.where(
        flat,
        np.where(above, _FLANK_CODE[Flank.TIP], _FLANK_CODE[Flank.ROOT]),
        np.where(rise > 0, _FLANK_CODE[Flank.DRIVING], _FLANK_CODE[Flank.SEALING]),
    )
    return _FLANKS[code]


@dataclass(frozen=True)
class FlankReport:
    """How one flank of the lobes meshes, judged by Rinder's rules (sec. 1.2, 2.2.1; see the module docstring).

    Parameters
    ----------
    flank : Flank
        DRIVING or SEALING.
    meshline_length : float, mm
        Length of the flank's meshline inside both bores.
    geometric_share : float
        Part of that length (0 to 1) where the flanks touch with a common tangent (not a corner
        against a flank).
    defects : tuple of str
        Kinds of defect inside the flank's working part (``"cusp"``, ``"jamming"``); slipping is not
        counted, nor the tip corners that end the working part (:func:`is_tip_corner`).
    transverse_contact_ratio : float
        Male rotation over which the working part is in contact, per angular pitch 2 pi / z1 (0
        where a circular flank centred on the pitch point touches at one instant only: Lysholm's
        "nur infinitesimale Stirnüberdeckung").
    working_length : float, mm
        Meshline length of the working part: geometric contact (a common tangent), no point-generated
        part. 0: the flank has no working part.
    overlap_contact_ratio : float
        Rinder's "Sprungüberdeckung": the male rotation over which one lobe's contact line lasts
        along the rotor (the wrap angle 2 pi L / h1) per angular pitch 2 pi / z1, the overlap ratio
        of a helical gear; 0 where the flank has no working part (the helix carries a working
        contact along the rotor; a corner against a flank is none).
    tip_corners : tuple of str
        The rotors ("male", "female") whose tip corner ends the working part or generates the
        flank's point-generated part (a cusp on a tip circle, Rinder sec. 2.2.2).
    """

    flank: Flank
    meshline_length: float
    geometric_share: float
    defects: tuple[str, ...]
    transverse_contact_ratio: float
    working_length: float = 0.0
    overlap_contact_ratio: float = 0.0
    tip_corners: tuple[str, ...] = ()

    @property
    def total_contact_ratio(self) -> float:
        """Transverse plus overlap contact ratio (as for a helical gear), 0 without a working part."""
        return self.transverse_contact_ratio + self.overlap_contact_ratio if self.working_length > 0 else 0.0

    @property
    def runs_without_timing_gears(self) -> bool:
        """True when the flank carries the drive by itself (Rinder sec. 1.2, 2.2.1).

        It has a working part (geometric contact with a common tangent), no cusp or jamming inside
        it, and a total contact ratio of at least 1: a small transverse contact ratio is made up by
        the helix (Lysholm's driving flank). Slipping is allowed: the helix carries the drive past it.
        """
        return self.working_length > 0 and not self.defects and self.total_contact_ratio >= 1.0 - 1e-9

    def as_dict(self) -> dict[str, object]:
        """Return the report as plain values (an entry of ``flanks`` in :meth:`MeshingAnalysis.summary`).

        Returns
        -------
        dict
            ``meshline_length`` and ``working_length`` (mm), ``geometric_contact`` (bool),
            ``geometric_share`` (0 to 1), ``defects`` (list of str), ``tip_corners`` (list of str),
            ``runs_without_timing_gears`` (bool), ``transverse_contact_ratio``,
            ``overlap_contact_ratio``, ``total_contact_ratio``.
        """
        return {
            "meshline_length": self.meshline_length,
            "working_length": self.working_length,
            "geometric_contact": self.geometric_share >= 1.0 - 1e-6,
            "geometric_share": self.geometric_share,
            "defects": list(self.defects),
            "tip_corners": list(self.tip_corners),
            "runs_without_timing_gears": self.runs_without_timing_gears,
            "transverse_contact_ratio": self.transverse_contact_ratio,
            "overlap_contact_ratio": self.overlap_contact_ratio,
            "total_contact_ratio": self.total_contact_ratio,
        }


def _covered(intervals: list[np.ndarray]) -> float:
    """Measure the union of the ranges of the given sets of angles (rad).

    The result is the rotation over which at least one of them is in contact. A piece touching at one
    instant adds nothing.
    """
    spans = sorted((float(t.min()), float(t.max())) for t in intervals if len(t))
    total, reach = 0.0, -np.inf
    for lo, hi in spans:
        lo = max(lo, reach)
        if hi > lo:
            total += hi - lo
            reach = hi
    return total


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
    rotor: str  # male, female
    x: float
    y: float
    angle_deg: float
    flank: str
    point_generated: bool = False
    extent: float = 0.0  # meshline length over which it holds (0: a single point)
    role: Flank | None = None  # the lobe part where it occurs

    def as_dict(self) -> dict[str, object]:
        """Return the defect as plain values (an entry of ``defects`` in :meth:`MeshingAnalysis.summary`).

        Returns
        -------
        dict
            The fields by name, ``role`` as ``flank_role`` (its text, or None).
        """
        return {
            "kind": self.kind,
            "rotor": self.rotor,
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
    padded = np.zeros(n + 2, dtype=bool)  # the runs inside the band: where the padded mask changes
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
    d = np.diff(points, axis=0)
    back = np.flatnonzero(np.einsum("ij,ij->i", d[:-1], d[1:]) < 0) + 1
    if longest <= 0 or len(d) < 2:
        return arclen[back]
    heading = np.unwrap(np.arctan2(d[:, 1], d[:, 0]))
    mid = 0.5 * (arclen[:-1] + arclen[1:])
    ahead = np.interp(mid + 0.5 * longest, mid, heading)
    behind = np.interp(mid - 0.5 * longest, mid, heading)
    sharp = np.flatnonzero(np.abs(ahead - behind) > SHARP_TURN)
    return np.concatenate([arclen[back], mid[sharp]])


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
    at = np.interp([c[0] for c in crossings], np.arange(len(arclen)), arclen) if crossings else np.zeros(0)
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


def _meshline_tangents(piece: MeshlinePiece, arclen: np.ndarray, accuracy: float) -> np.ndarray:
    """Return the unit tangents of a meshline piece at its samples, (n, 2).

    Of the design's exact meshline, from a shape-preserving (modified Akima) cubic over the piece's
    parameter: an interpolating cubic rings where the meshline turns sharply (a rack rounding about
    C meeting a straight flank), and its tangent flips from sample to sample. Of a meshline
    generated from a profile known to ``accuracy`` (mm, > 0), from a smoothing cubic over its arc
    length that stays within that accuracy of the samples (scipy's s = n e^2, Dierckx sec. 5.2):
    the samples wobble by the profile's error, far more than their spacing resolves.
    """
    order = np.argsort(piece.s)
    pts = piece.points
    if accuracy > 0:
        from scipy import interpolate  # a given profile only: points come through scipy's fits anyway

        keep = np.concatenate([[True], np.diff(arclen) > 1e-12])
        if keep.sum() > 8:
            try:
                tck, _ = interpolate.splprep(pts[keep].T, u=arclen[keep], s=keep.sum() * accuracy**2, k=3, quiet=2)
                tau = np.column_stack(interpolate.splev(arclen, tck, der=1))
                norm = np.linalg.norm(tau, axis=1, keepdims=True)
                if np.all(norm > 0):
                    return tau / norm
            except (ValueError, TypeError):
                pass  # too few distinct samples for a smoothing cubic: the interpolating one below
    tau = np.empty_like(pts)
    tau[order] = makima_slopes(piece.s[order], pts[order])
    return tau / np.linalg.norm(tau, axis=1, keepdims=True)


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


@dataclass(frozen=True, eq=False)
class MeshingAnalysis:
    """Everything Rinder reads off a toothing, for one pair at a design speed.

    Parameters
    ----------
    rotors : ScrewRotors
        The generated pair.
    speed_rpm : float, rpm
        Male speed, for the sliding velocities (m/s).
    samples : int
        Samples along each rack piece.
    tolerance : float, rad
        Relative tolerance of the cusp/jamming test: the uncertainty of the meshline's tangent
        direction (a whole piece within it is a point-generated flank).
    accuracy : float, mm, optional
        Accuracy of the profile to which the defects are judged; None: that of the rotors
        (:attr:`judged_accuracy`).
    """

    rotors: ScrewRotors
    speed_rpm: float = 3000.0
    samples: int = 600
    tolerance: float = 1e-3
    accuracy: float | None = None

    # ---- meshline ------------------------------------------------------------------------
    @cached_property
    def pieces(self) -> list[MeshlinePiece]:
        """The meshline, piece by piece: the contacts of every rack piece inside both bores.

        A list of :class:`MeshlinePiece`; pieces with fewer than two contacts are left out.
        """
        pair = self.rotors.pair
        mesh = pair.mesh
        o2 = np.array([pair.center_distance, 0.0])
        out = []
        for piece in self.rotors.rack:
            gen = Generated(piece.curve, mesh.rack, mesh.female)
            s = np.linspace(piece.curve.s0, piece.curve.s1, self.samples)
            t, x, rack_pts, tan = gen.meshline_contact(s)  # the rack's points and tangents along its travel
            inside = (np.hypot(*x.T) <= pair.male_tip_radius + 1e-3) & (np.hypot(*(x - o2).T) <= pair.female_tip_radius + 1e-3)
            ok = np.isfinite(t) & inside & np.all(np.isfinite(x), axis=1)
            if ok.sum() < 2:
                continue
            tan_fixed = mesh.rack.vectors_to_fixed(tan, t)
            roles = flank_roles(rack_pts[ok], tan[ok], pair.male_pitch_radius, pair.center_distance)
            out.append(
                MeshlinePiece(
                    piece.male_name,
                    piece.kind,
                    s[ok],
                    t[ok],
                    x[ok],
                    tan_fixed[ok],
                    piece.male_name,
                    piece.female_name,
                    roles,
                )
            )
        return out

    @property
    def meshline(self) -> np.ndarray:
        """All contact points in the fixed frame, (n, 2) float, mm (piece after piece)."""
        return np.concatenate([p.points for p in self.pieces]) if self.pieces else np.zeros((0, 2))

    @property
    def contact_angles(self) -> np.ndarray:
        """Male rotation angle at every point of :attr:`meshline`, (n,) float, rad."""
        return np.concatenate([p.t for p in self.pieces]) if self.pieces else np.zeros(0)

    # ---- the rules of sec. 2.2.1 -----------------------------------------------------------
    @property
    def judged_accuracy(self) -> float:
        """The accuracy (mm) to which the defects are judged (``defect_accuracy`` of the summary).

        :attr:`accuracy` when given, else that of the profile the pair was generated from
        (:attr:`rotorcad.screw_rotors.ScrewRotors.accuracy`), at least the design's chord tolerance
        :data:`rotorcad.profile.DEFAULT_TOLERANCE`.
        """
        if self.accuracy is not None:
            return float(self.accuracy)
        return max(float(getattr(self.rotors, "accuracy", 0.0)), DEFAULT_TOLERANCE)

    @cached_property
    def defects(self) -> list[Defect]:
        """Cusps, jamming and slipping points on the meshline (Rinder sec. 2.2.1), a list of :class:`Defect`.

        The meshline normal (from a spline over each piece) through O1 or O2 is a cusp, through C
        jamming (except on a meshline arc about C, Rinder's exception); a crossing of O1O2 away from C
        is slipping, inside a piece or between two pieces.

        Each test is judged to the accuracy e of the profile (:attr:`judged_accuracy`): the normal's
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
        """
        pair = self.rotors.pair
        o1, o2 = np.zeros(2), np.array([pair.center_distance, 0.0])
        c = np.array([pair.male_pitch_radius, 0.0])
        tol, acc = self.tolerance, self.judged_accuracy
        scale = pair.center_distance
        longest = resolution(acc, scale)
        given = getattr(self.rotors, "accuracy", 0.0) > 0 or self.accuracy is not None  # not the design's exact curves
        found: list[Defect] = []
        spans: dict[int, np.ndarray] = {}  # the meshline points of each stretch, by the defect's id
        on_line = max(1e-3 * scale, longest if given else 0.0)  # through a centre or on O1O2 within the resolution
        for piece in self.pieces:
            pts = piece.points
            steps = np.hypot(*np.diff(pts, axis=0).T)
            arclen = np.concatenate([[0.0], np.cumsum(steps)])
            length = float(arclen[-1])
            if len(pts) < 4 or length < 1e-6 * scale:
                continue  # the piece touches at a single point (a tip or root land): no meshline
            tau = _meshline_tangents(piece, arclen, acc if given else 0.0)
            # points on O1O2 are judged by the slipping rule alone (their normal along O1O2 passes
            # through O1, O2 and C at once), and C itself lies on every meshline
            judged = (np.abs(pts[:, 1]) > 1e-6 * scale) & (np.hypot(*(pts - c).T) > 1e-6 * scale)
            turns = reversals(pts, arclen, longest if given else 0.0)
            tests = ((o1, "cusp", "male"), (o2, "cusp", "female"), (c, "jamming", "male"))
            misses = []
            for q, _kind, _ in tests:
                to_q = q - pts
                f = np.einsum("ij,ij->i", to_q, tau)  # zero: the meshline normal passes through q
                band = acc + max(tol, acc / longest) * np.hypot(*to_q.T)
                whole = bool(_median(np.abs(f)) < tol * max(1.0, np.abs(to_q).max()))
                misses.append((f, band, whole, *robust_zeros(f, band, arclen, longest, whole, turns)))
            at = [np.interp([c[0] for c in m[3]], np.arange(len(arclen)), arclen) for m in misses]
            for k, ((q, kind, rotor), (f, band, whole, crossings, stretches)) in enumerate(zip(tests, misses, strict=True)):
                for i, j in stretches:
                    if kind == "jamming":
                        continue  # meshline arc about C: both curvature centres in C (Rinder's exception)
                    ramp = _median(np.abs(f[i : j + 1]) / band[i : j + 1]) > 0.3  # |f| runs through the band: no arc
                    if not whole and ramp and np.abs(pts[i : j + 1, 1]).min() < 1e-3 * scale:
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
                others = np.concatenate([at[m] for m in range(len(tests)) if m != k])
                for (x, lo, hi), s_x in zip(crossings, at[k], strict=True):
                    if np.any(np.abs(others - s_x) < longest):
                        continue  # the misses of two centres change sign together: the tangent turned over
                    i, w = min(int(x), len(pts) - 2), x - min(int(x), len(pts) - 2)
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
            # with its neighbour (_slipping_between_pieces)
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
        found.extend(self._slipping_between_pieces())
        return _merged(found, longest, spans)

    def _slipping_between_pieces(self) -> list[Defect]:
        """Apply Rinder's slipping rule where the meshline crosses O1O2 between two pieces.

        That is where a tip touches the mate's root on O1O2 (a tip corner's path or a flank handing over
        to the next one), e.g. the female tip on the male root. The pieces are the meshline in order, and
        the next lobe's first piece follows the last; pieces lying on O1O2 (tip lands) hand over. A
        piece of a profile given by points or a drawing (not the design's exact curves) may end short
        of O1O2 by up to the resolution (:func:`resolution`).
        """
        pair = self.rotors.pair
        scale = pair.center_distance
        c_x = pair.male_pitch_radius
        given = getattr(self.rotors, "accuracy", 0.0) > 0 or self.accuracy is not None  # not the design's exact curves
        near = max(1e-6 * scale, resolution(self.judged_accuracy, scale) if given else 0.0)
        off = self.judged_accuracy if given else 1e-9 * scale  # a side of O1O2 beyond the accuracy
        ends = []  # per piece: sign of y leaving its start, reaching its end, its end point, its angle
        for piece in self.pieces:
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

    @property
    def point_generated_flanks(self) -> list[dict[str, str]]:
        """Flanks traced by a single corner of the mate (punkterzeugt).

        A list of dicts with ``rotor``, ``flank`` (segment name) and ``generated_by``.
        """
        out = []
        for piece in self.rotors.rack:
            if piece.kind is PieceRole.MALE_CORNER_PATH:
                out.append({"rotor": "female", "flank": piece.female_name, "generated_by": "male tip corner"})
            elif piece.kind is PieceRole.FEMALE_CORNER_PATH:
                out.append({"rotor": "male", "flank": piece.male_name, "generated_by": "female tip corner"})
        return out

    # ---- running without timing gears (1.2, 2.2.1) -----------------------------------------
    @property
    def tip_corner_tolerance(self) -> float:
        """How near a tip circle a cusp must lie to be that tip's corner (:func:`is_tip_corner`), mm.

        1e-4 of the centre distance (12 µm at a = 116 mm): far below any flank's extent, far above
        the meshline's sampling error at a corner's end; for a profile given to a coarser accuracy
        (:attr:`judged_accuracy`, measured points) 20 times that accuracy, the distance by which a
        corner found from points may sit off its tip circle.
        """
        return max(1e-4 * self.rotors.pair.center_distance, 20.0 * self.judged_accuracy)

    @cached_property
    def flanks(self) -> dict[Flank, FlankReport]:
        """Per flank (driving, sealing): working part, defects and contact ratios (Rinder sec. 1.2, 2.2.1).

        A contact is geometric where a rack curve touches both rotors (a common tangent); a corner
        path's contacts are a corner against a flank (Rinder sec. 1.2: "eine Berührung ... im
        geometrischen Sinn mit gemeinsamen Tangenten ... ist in keinem Flankenteil gegeben"). The
        working part is the geometric contact; the point-generated parts seal but do not drive.
        Contact pieces shorter than 1e-6 of the centre distance (a corner touching only at C) do not
        count. A dict Flank -> :class:`FlankReport`.
        """
        pair = self.rotors.pair
        pitch_angle = 2 * np.pi / pair.male_teeth
        overlap = float(pair.wrap_angle / pitch_angle)  # Sprungüberdeckung: wrap angle per angular pitch
        tol = self.tip_corner_tolerance
        out = {}
        steps = [np.hypot(*np.diff(piece.points, axis=0).T) for piece in self.pieces]  # chord lengths, once
        for flank in (Flank.DRIVING, Flank.SEALING):
            total = geometric = 0.0
            t_geo: list[np.ndarray] = []
            for piece, seg in zip(self.pieces, steps, strict=True):
                mask = piece.roles == flank
                if mask.sum() < 2:
                    continue
                length = float(seg[mask[:-1] & mask[1:]].sum())
                if length < 1e-6 * pair.center_distance:
                    continue
                total += length
                if piece.kind is PieceRole.CURVE:
                    geometric += length
                    t_geo.append(piece.t[mask])
            mine = [d for d in self.defects if d.role is flank and d.kind != "slipping"]
            corners = tuple(sorted({d.rotor for d in mine if is_tip_corner(d, pair, tol)}))
            defects = tuple(sorted({d.kind for d in mine if not is_tip_corner(d, pair, tol)}))
            ratio = _covered(t_geo) / pitch_angle
            out[flank] = FlankReport(
                flank,
                total,
                geometric / total if total > 0 else 0.0,
                defects,
                ratio,
                geometric,
                overlap if geometric > 0 else 0.0,
                corners,
            )
        return out

    @property
    def running_reasons(self) -> list[str]:
        """Why the pair does not run without timing gears, one sentence per flank (empty: it runs)."""
        out = []
        pair = self.rotors.pair
        for flank, report in self.flanks.items():
            if report.runs_without_timing_gears:
                continue
            if report.meshline_length == 0:
                out.append(f"the {flank} flank has no contact inside the bores.")
                continue
            parts = []
            if report.working_length == 0:
                parts.append(
                    "no geometric contact anywhere (a tip corner against the mate's flank, no common tangent): no working "
                    "part for the helix to carry"
                )
            for kind in report.defects:
                rotors = sorted(
                    {
                        d.rotor
                        for d in self.defects
                        if d.role is flank and d.kind == kind and not is_tip_corner(d, pair, self.tip_corner_tolerance)
                    }
                )
                parts.append(f"{kind} on the {' and '.join(rotors)} inside its working part")
            if report.working_length > 0 and report.total_contact_ratio < 1.0 - 1e-9:
                parts.append(
                    f"total contact ratio {report.total_contact_ratio:.2f} below 1 (transverse "
                    f"{report.transverse_contact_ratio:.2f} + overlap {report.overlap_contact_ratio:.2f}): too little wrap"
                )
            out.append(f"the {flank} flank: " + "; ".join(parts) + ".")
        return out

    # ---- one angle convention (Rinder Figs. 10-13) -------------------------------------------
    @cached_property
    def angle_reference(self) -> float:
        """Male rotation (rad) at which the middle of a male tip lies on O1O2, the zero of :meth:`rinder_angle`.

        Read off the male section (its points on the tip circle, to 1e-4 of the addendum), so it
        does not depend on how the profile was given; of the passages one pitch apart, the one
        nearest the middle of the meshline's range of angles.
        """
        pair = self.rotors.pair
        ring = np.asarray(self.sections[0].exterior.coords)
        r = np.hypot(*ring.T)
        top = ring[r >= pair.male_tip_radius - 1e-4 * max(pair.male_addendum, 1e-3)]
        if len(top) == 0:
            top = ring[[int(np.argmax(r))]]
        z1 = pair.male_teeth
        pitch = 2 * np.pi / z1
        beta = np.arctan2(top[:, 1], top[:, 0])
        b0 = float(np.angle(np.exp(1j * z1 * beta).mean())) / z1  # one tip, folded over the lobes
        near = wrap_angle(beta, b0, pitch)  # the tip points of every lobe, folded onto that one
        b_mid = 0.5 * (float(near.min()) + float(near.max()))
        t_ref = -b_mid  # the male turns counter-clockwise: a point at polar angle b is on O1O2 at t = -b
        t = self.contact_angles
        mid = 0.5 * (float(t.min()) + float(t.max())) if len(t) else 0.0
        return t_ref + pitch * round((mid - t_ref) / pitch)

    def rinder_angle(self, t: np.ndarray | float) -> np.ndarray | float:
        """Male rotation angle in the convention of every angle rotorcad shows (deg).

        phi = male rotation still to go until the middle of a male tip reaches the line of centres
        O1O2 (the lobe pointing at O2): positive before, negative after that instant. In this count
        the male tip reaches the housing cusp on the sealing side at a negative angle, as in
        Rinder's Figs. 10-13 and sec. 3.2 ("Drehwinkelstellung von ca. -25°").

        Parameters
        ----------
        t : float or (n,) float array, rad
            Male rotation angle of the meshing engine (:attr:`contact_angles`).

        Returns
        -------
        float or (n,) float array, deg
        """
        return np.degrees(self.angle_reference - np.asarray(t, dtype=float))

    # ---- tightness (2.2.2) -----------------------------------------------------------------
    @cached_property
    def cusp(self) -> np.ndarray:
        """The housing cusp that the meshline comes nearest, (2,) float, mm.

        The intersection of the tip circles above O1O2, or its mirror image below.
        """
        k = self.rotors.pair.housing_cusp
        pts = self.meshline
        lower = k * np.array([1.0, -1.0])
        return k if np.hypot(*(pts - k).T).min() <= np.hypot(*(pts - lower).T).min() else lower

    @cached_property
    def meshline_end(self) -> np.ndarray:
        """Meshline point nearest the housing cusp :attr:`cusp`, (2,) float, mm."""
        pts = self.meshline
        return pts[np.argmin(np.hypot(*(pts - self.cusp).T))]

    @property
    def meshline_closed(self) -> bool:
        """The meshline runs into the housing cusp (Rinder 2.2.2), within 1 micrometre."""
        return bool(np.hypot(*(self.meshline_end - self.cusp)) < 1e-3)

    @cached_property
    def blow_hole(self) -> shapely.Geometry:
        """Projected blow-hole polygon (see the module docstring)."""
        pair = self.rotors.pair
        k, e = self.cusp, self.meshline_end
        if np.hypot(*(e - k)) < 1e-3:
            return shapely.Polygon()
        o2 = np.array([pair.center_distance, 0.0])
        r1, r2 = pair.male_tip_radius, pair.female_tip_radius
        em = e / np.hypot(*e) * r1
        ef = o2 + (e - o2) / np.hypot(*(e - o2)) * r2

        def arc(center: np.ndarray, r: float, a: np.ndarray, b: np.ndarray) -> np.ndarray:
            t0 = np.arctan2(*(a - center)[::-1])
            t1 = np.arctan2(*(b - center)[::-1])
            t1 = wrap_angle(t1, t0)
            th = np.linspace(t0, t1, 200)
            return center + r * np.stack([np.cos(th), np.sin(th)], axis=1)

        ring = np.vstack([[e], arc(o2, r2, ef, k), arc(np.zeros(2), r1, k, em), [e]])
        return shapely.make_valid(shapely.Polygon(ring))

    @property
    def blow_hole_area(self) -> float:
        """Area of the projected blow-hole :attr:`blow_hole`, mm²."""
        return float(self.blow_hole.area)

    @cached_property
    def spatial_blow_hole(self) -> SpatialBlowHole:
        """The blow-hole triangle in 3D (:mod:`rotorcad.blow_hole`).

        Its apex is the meshline end nearest the cusp, at that point's height on the contact line (z
        measured as in :attr:`contact_line`, from the contact line's start).
        """
        pts = self.meshline
        i = int(np.argmin(np.hypot(*(pts - self.cusp).T)))
        z = self.rotors.pair.lead * self.contact_angles / (2 * np.pi)
        return SpatialBlowHole(self.rotors.pair, pts[i], float(z[i] - z.min()), self.cusp)

    # ---- contact line (eq. 1) ------------------------------------------------------------
    @cached_property
    def contact_line(self) -> np.ndarray:
        """3D contact (sealing) line, (n, 3) float, mm.

        Meshline points with z = h1 alpha / 2 pi (Rinder eq. 1, alpha the male rotation angle), shifted
        to start at z = 0 and cut at the rotor length.
        """
        pair = self.rotors.pair
        pts = self.meshline
        z = pair.lead * self.contact_angles / (2 * np.pi)
        line = np.column_stack([pts, z - z.min()])
        return line[line[:, 2] <= pair.length + 1e-9]

    @property
    def contact_line_length(self) -> float:
        """Length of the polyline :attr:`contact_line`, mm."""
        line = self.contact_line
        return float(np.linalg.norm(np.diff(line, axis=0), axis=1).sum())

    # ---- areas and displacement ------------------------------------------------------------
    @cached_property
    def sections(self) -> tuple[shapely.Polygon, shapely.Polygon]:
        """Transverse sections of the male and the female, each in its own frame (shapely polygons, mm)."""
        return self.rotors.section("male"), self.rotors.section("female")

    @property
    def male_flute_area(self) -> float:
        """Male flute area A1 = (bore area - rotor section) / z1, mm² (bore = male tip circle)."""
        pair = self.rotors.pair
        return float((np.pi * pair.male_tip_radius**2 - self.sections[0].area) / pair.male_teeth)

    @property
    def female_flute_area(self) -> float:
        """Female flute area A2 = (bore area - rotor section) / z2, mm² (bore = female tip circle)."""
        pair = self.rotors.pair
        return float((np.pi * pair.female_tip_radius**2 - self.sections[1].area) / pair.female_teeth)

    @property
    def displacement_per_rev(self) -> float:
        """Displacement per male revolution V = z1 L (A1 + A2), mm³."""
        pair = self.rotors.pair
        return pair.male_teeth * pair.length * (self.male_flute_area + self.female_flute_area)

    @property
    def area_utilisation(self) -> float:
        """Share of the two bores' area that is flute: (z1 A1 + z2 A2) / (pi r1t^2 + pi r2t^2)."""
        pair = self.rotors.pair
        flutes = pair.male_teeth * self.male_flute_area + pair.female_teeth * self.female_flute_area
        return float(flutes / (np.pi * (pair.male_tip_radius**2 + pair.female_tip_radius**2)))

    # ---- sliding velocity and slip (eqs. 2-4) ----------------------------------------------
    @cached_property
    def kinematics(self) -> dict[str, np.ndarray]:
        """Velocities and slips at every contact of :attr:`meshline` (Rinder eqs. 2-4).

        A dict of (n,) float arrays: ``v1t`` and ``v2t``, the rotors' velocities along the common
        tangent (m/s, eq. 2); ``sliding``, the sliding velocity v_g = v1t - v2t (m/s, eq. 3); ``slip_male`` and
        ``slip_female``, the slips v_g / v1t and v_g / v2t (eq. 4; infinite where a tangential velocity
        vanishes); ``angle_deg``, the male angle in Rinder's count (deg, :meth:`rinder_angle`);
        ``normal_check``, the cross product of the tangent with the relative velocity (zero: the law
        of gearing holds).
        """
        v = self.velocities
        keys = ("v1t", "v2t", "sliding", "slip_male", "slip_female")
        return {**{k: v[k] for k in keys}, "angle_deg": self.rinder_angle(self.contact_angles), "normal_check": v["normal_check"]}

    @cached_property
    def velocities(self) -> dict[str, np.ndarray]:
        """:attr:`kinematics` without ``angle_deg`` (Rinder eqs. 2-4): no section needed (a sweep's figures)."""
        pair = self.rotors.pair
        w1 = self.speed_rpm * 2 * np.pi / 60.0
        w2 = -w1 * pair.male_teeth / pair.female_teeth
        pts = self.meshline
        tau = np.concatenate([p.tangents for p in self.pieces])
        o2 = np.array([pair.center_distance, 0.0])
        v1 = w1 * np.stack([-pts[:, 1], pts[:, 0]], axis=1)
        d2 = pts - o2
        v2 = w2 * np.stack([-d2[:, 1], d2[:, 0]], axis=1)
        v1t = np.einsum("ij,ij->i", v1, tau) * 1e-3
        v2t = np.einsum("ij,ij->i", v2, tau) * 1e-3
        vg = v1t - v2t
        with np.errstate(divide="ignore", invalid="ignore"):
            z1 = vg / v1t
            z2 = vg / v2t
        return {"v1t": v1t, "v2t": v2t, "sliding": vg, "slip_male": z1, "slip_female": z2, "normal_check": cross(tau, v1 - v2)}

    @cached_property
    def slip_singularities(self) -> list[dict[str, object]]:
        """Points of infinite slip: where a rotor's tangential velocity vanishes (Rinder eq. 4, sec. 3.2).

        Rinder: "nur in einem einzigen Punkt unendliche Schlupfwerte ... daß die Evolventenflanke bis
        zum Grundkreis benutzt wurde". Found on each meshline piece where v1t (male slip infinite)
        or v2t (female slip infinite) changes sign between neighbouring contacts (located by linear
        interpolation), or, at a piece's end, falls below 1 % of the rotor's largest tangential
        velocity while falling towards that end (a zero where the piece leaves a bore: the sampled
        meshline stops within one step of it). The pitch point C is left out (both velocities
        vanish there with the sliding: pure rolling, not infinite slip). Points closer than 1 % of
        the centre distance are one.

        Returns
        -------
        list of dict
            ``rotor`` (whose slip is infinite), ``x``, ``y`` (mm), ``angle_deg`` (:meth:`rinder_angle`),
            ``flank`` (lobe part), ``male_radius``, ``female_radius`` (mm).
        """
        pair = self.rotors.pair
        k = self.kinematics
        found: list[dict[str, object]] = []
        start = 0
        for piece in self.pieces:
            n = len(piece.t)
            sl = slice(start, start + n)
            start += n
            for key, rotor in (("v1t", "male"), ("v2t", "female")):
                v = k[key][sl]
                mag = np.abs(v)
                big = float(np.abs(k[key]).max()) if len(k[key]) else 0.0
                ends = [i for i, j in ((0, 1), (n - 1, n - 2)) if n > 1 and mag[i] <= 1e-2 * big and mag[i] < mag[j]]
                cross_ = np.nonzero(v[:-1] * v[1:] < 0)[0]
                hits = [(i, 0.0) for i in ends] + [(int(i), float(v[i] / (v[i] - v[i + 1]))) for i in cross_]
                for i, w in hits:
                    j = min(i + 1, n - 1)
                    p = piece.points[i] + w * (piece.points[j] - piece.points[i])
                    t = piece.t[i] + w * (piece.t[j] - piece.t[i])
                    if np.hypot(p[0] - pair.male_pitch_radius, p[1]) < 1e-3 * pair.center_distance:
                        continue  # the pitch point: pure rolling
                    if any(
                        f["rotor"] == rotor and np.hypot(f["x"] - p[0], f["y"] - p[1]) < 1e-2 * pair.center_distance
                        for f in found
                    ):
                        continue
                    found.append(
                        {
                            "rotor": rotor,
                            "x": float(p[0]),
                            "y": float(p[1]),
                            "angle_deg": float(self.rinder_angle(t)),
                            "flank": str(piece.roles[i]),
                            "male_radius": float(np.hypot(*p)),
                            "female_radius": float(np.hypot(p[0] - pair.center_distance, p[1])),
                        }
                    )
        return found

    def _max(self, key: str) -> dict[str, float]:
        """Return the largest magnitude of a :attr:`kinematics` entry and where it occurs.

        A dict with ``value``, ``x``, ``y`` (mm), ``angle_deg``, ``flank`` and both radii (mm).
        """
        k = self.kinematics
        v = np.abs(k[key])
        v = np.where(np.isfinite(v), v, -1.0)
        i = int(np.argmax(v))
        p = self.meshline[i]
        pair = self.rotors.pair
        roles = np.concatenate([piece.roles for piece in self.pieces])
        return {
            "value": float(v[i]),
            "x": float(p[0]),
            "y": float(p[1]),
            "angle_deg": float(k["angle_deg"][i]),
            "flank": str(roles[i]),
            "male_radius": float(np.hypot(*p)),
            "female_radius": float(np.hypot(p[0] - pair.center_distance, p[1])),
        }

    def defect_dicts(self) -> list[dict[str, object]]:
        """Return :attr:`defects` as plain values, angles in Rinder's count and each cusp's reading.

        Returns
        -------
        list of dict
            :meth:`Defect.as_dict` with ``angle_deg`` converted by :meth:`rinder_angle` and
            ``tip_corner`` (bool): the cusp is a rotor's tip corner or its point-generated path
            (:func:`is_tip_corner`), not a defect of a working flank.
        """
        out = []
        pair = self.rotors.pair
        for d in self.defects:
            row = d.as_dict()
            row["angle_deg"] = float(self.rinder_angle(np.radians(d.angle_deg)))
            row["tip_corner"] = is_tip_corner(d, pair, self.tip_corner_tolerance)
            out.append(row)
        return out

    def summary(self) -> dict[str, object]:
        """Return the analysis as plain values (the figures of ``rotorcad rotor --json``).

        Returns
        -------
        dict
            Tooth counts, centre distance (mm), family, ``meshline_closed``, blow-hole areas (mm²)
            and the spatial blow-hole, contact-line length (mm), flute areas (mm²), displacement per
            revolution (mm³), area utilisation, the largest sliding velocity (m/s) and slips with where
            they occur, the points of infinite slip, speed (rpm), the angle convention, defects (with
            ``tip_corner``), point-generated flanks, per-flank reports (working part, transverse,
            overlap and total contact ratio), the pair's overlap ratio, whether the pair runs without
            timing gears and why not, wrap angle (deg). Angles in Rinder's count (:meth:`rinder_angle`).
        """
        pair = self.rotors.pair
        return {
            "male_teeth": pair.male_teeth,
            "female_teeth": pair.female_teeth,
            "center_distance": pair.center_distance,
            "family": self.rotors.family,
            "meshline_closed": self.meshline_closed,
            "blow_hole_area": self.blow_hole_area,
            "blow_hole_spatial": self.spatial_blow_hole.as_dict(),
            "contact_line_length": self.contact_line_length,
            "male_flute_area": self.male_flute_area,
            "female_flute_area": self.female_flute_area,
            "displacement_per_rev": self.displacement_per_rev,
            "area_utilisation": self.area_utilisation,
            "max_sliding_velocity": self._max("sliding")["value"],
            "max_sliding_at": self._max("sliding"),
            "max_slip_male": self._max("slip_male"),
            "max_slip_female": self._max("slip_female"),
            "slip_singularities": self.slip_singularities,
            "speed_rpm": self.speed_rpm,
            "angle_convention": ANGLE_CONVENTION,
            "defects": self.defect_dicts(),
            "defect_accuracy": self.judged_accuracy,
            "point_generated_flanks": self.point_generated_flanks,
            "flanks": {str(f): r.as_dict() for f, r in self.flanks.items()},
            "overlap_contact_ratio": float(pair.wrap_angle * pair.male_teeth / (2 * np.pi)),
            "runs_without_timing_gears": all(r.runs_without_timing_gears for r in self.flanks.values()),
            "running_reasons": self.running_reasons,
            "wrap_angle_deg": float(np.degrees(pair.wrap_angle)),
        }

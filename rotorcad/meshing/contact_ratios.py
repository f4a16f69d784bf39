"""Per flank: working part, contact ratios and whether it runs (Rinder sec. 1.2, 2.2.1).

The transverse contact ratio (male rotation over which the working part is in contact, per angular
pitch), the overlap ratio (Sprungüberdeckung, z1 L / h1) and their sum; a flank runs with a working
part, no cusp or jamming inside it and a total ratio of at least 1 (:class:`FlankReport`). The
criteria are stated in :mod:`rotorcad.meshing`.

The rotation is the union of the rotations between consecutive samples of the working part (not the
range of its samples' angles: one stray sample of a land at C, labelled a flank, stretched the N
rack's ratios from given points from 0.63 and 0.75 to 0.96). Of a profile given to an accuracy e,
contacts that cannot be told from a point-generated part or a land at that accuracy are none of the
working part (:func:`resolved_steps`): the mate's contact point, the meshline point seen from
the mate, is known to the meshline's accuracy :data:`~rotorcad.meshing.defects.MESHLINE_GAIN` e, and
where it lies that near a tip corner the contact is that corner's path (Rinder sec. 2.2.2: "Radlinien
der Punkte"); a contact that near the line O1O2 is a land's (a land touches there only); a stretch
whose contacts all stay within the resolution sqrt(8 a e) of a tip corner is that corner, rounded by
the fit. So judged, the ratio from every form of the samples' males lies within 2 sqrt(8 a e) / p_t of
the design's (p_t the transverse pitch; tests/test_contact_ratio_invariance.py). The working length
(and with it the overlap ratio and running) counts every geometric contact of a piece but two: a
contact whose meshline point lies on a rotor's tip circle to the meshline's accuracy is that rotor's
tip, rounded by the fit (:func:`on_tip_circles`; the Lysholm female from 300 exact points a lobe),
and a curve contact between the male tip corner's path and the female's shorter than the meshline's
resolution sqrt(8 a G e) (G = MESHLINE_GAIN) is the fit's rounding of a corner-to-corner hand-over
(:func:`is_corner_handover`; Krigar's, at the housing cusp).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from rotorcad.meshing.defects import MESHLINE_GAIN, TIP_CIRCLE_NEAR, Defect, is_tip_corner, tip_circle_runs
from rotorcad.meshing.meshline import MeshlinePiece, resolved_lengths
from rotorcad.meshing.ratio_accuracy import covered_rotation, end_spans, ratio_uncertainty, step_spans
from rotorcad.roles import Flank, PieceRole, Side
from rotorcad.rotor_pair import RotorPair


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
        part; of a given profile, none on a tip circle (:func:`on_tip_circles`). 0: the flank has no
        working part.
    overlap_contact_ratio : float
        Rinder's "Sprungüberdeckung": the male rotation over which one lobe's contact line lasts
        along the rotor (the wrap angle 2 pi L / h1) per angular pitch 2 pi / z1, the overlap ratio
        of a helical gear; 0 where the flank has no working part (the helix carries a working
        contact along the rotor; a corner against a flank is none).
    tip_corners : tuple of str
        The rotors ("male", "female") whose tip corner ends the working part or generates the
        flank's point-generated part (a cusp on a tip circle, Rinder sec. 2.2.2).
    transverse_contact_ratio_accuracy : float
        How far the transverse ratio may lie from the one of the exact profile the input stands for
        (:func:`ratio_uncertainty`): the rotation over which the input's accuracy does not tell working
        contact from a tip corner's path, per angular pitch.
    decided_working_length : float or None, mm
        Of a given profile, the part of ``working_length`` that the input's accuracy decides is working
        (:func:`resolved_steps`: the steps the transverse ratio counts); None: all of it (a design).
    undecided : tuple of str
        Kinds of the defects on the flank the input can neither show nor rule out
        (:func:`rotorcad.meshing.undecided.possible_rows`).
    """

    flank: Flank
    meshline_length: float
    geometric_share: float
    defects: tuple[str, ...]
    transverse_contact_ratio: float
    working_length: float = 0.0
    overlap_contact_ratio: float = 0.0
    tip_corners: tuple[str, ...] = ()
    transverse_contact_ratio_accuracy: float = 0.0
    decided_working_length: float | None = None
    undecided: tuple[str, ...] = ()

    @property
    def running_decided(self) -> bool:
        """False where the flank would run on contact the input's accuracy does not decide (else True).

        Of a given profile, the working part the input decides (:attr:`decided_working_length`) may be
        shorter than :attr:`working_length`: curve contact within the meshline's accuracy of a tip corner
        or of O1O2, or a run whose contacts all stay within the resolution of one tip corner, may be that
        corner's path rounded by the fit (:func:`resolved_steps`, the steps the transverse ratio counts).
        A flank with a working part but none decided, no defect inside it and a total contact ratio of at
        least 1 is undecided at this accuracy: it runs if that contact works, and does not if it is a
        corner's path (Krigar's male as 150 exact points a lobe: 7.0 mm of such contact on its driving
        flank, transverse ratio 0 +- 0.12, where the design has no working part). So is a flank that would run
        but for a defect the input can neither show nor rule out (:attr:`undecided`).
        """
        if self.defects or self._total_if_working < 1.0 - 1e-9:
            return True
        return not (self._decided == 0.0 < self.working_length or (self.undecided and self._decided > 0))

    @property
    def _decided(self) -> float:
        return self.working_length if self.decided_working_length is None else self.decided_working_length

    @property
    def _total_if_working(self) -> float:
        return self.transverse_contact_ratio + self.overlap_contact_ratio

    @property
    def total_contact_ratio(self) -> float:
        """Transverse plus overlap contact ratio (as for a helical gear), 0 without a working part."""
        return self.transverse_contact_ratio + self.overlap_contact_ratio if self.working_length > 0 else 0.0

    @property
    def runs_without_timing_gears(self) -> bool:
        """True when the flank carries the drive by itself (Rinder sec. 1.2, 2.2.1).

        It has a working part (geometric contact with a common tangent) that the input decides, no
        cusp or jamming inside it, and a total contact ratio of at least 1: a small transverse contact
        ratio is made up by the helix (Lysholm's driving flank). Slipping is allowed: the helix carries
        the drive past it. A flank whose working part the input does not decide is not shown to run
        (False), and :attr:`running_decided` says so.
        """
        return self._decided > 0 and not self.defects and not self.undecided and self.total_contact_ratio >= 1.0 - 1e-9

    def as_dict(self) -> dict[str, object]:
        """Return the report as plain values (an entry of ``flanks`` in :meth:`MeshingAnalysis.summary`).

        Returns
        -------
        dict
            ``meshline_length`` and ``working_length`` (mm), ``geometric_contact`` (bool),
            ``geometric_share`` (0 to 1), ``defects`` (list of str), ``tip_corners`` (list of str),
            ``runs_without_timing_gears`` (bool), ``transverse_contact_ratio``,
            ``overlap_contact_ratio``, ``total_contact_ratio``, ``transverse_contact_ratio_accuracy``,
            ``running_decided`` (bool, :attr:`running_decided`).
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
            "transverse_contact_ratio_accuracy": self.transverse_contact_ratio_accuracy,
            "running_decided": self.running_decided,
        }


def _tip_corners(pieces: list[MeshlinePiece], pair: RotorPair) -> dict[PieceRole, np.ndarray]:
    """Return the tip corners (rotor frame, mm, (k, 2)) of each rotor whose corner path is on the meshline.

    A corner path's contact is the corner itself: its samples, turned back into the corner's rotor
    (:meth:`rotorcad.kinematics.Rotation.to_body`), stand at one point; their median is taken.
    """
    mesh = pair.mesh
    bodies = {PieceRole.MALE_CORNER_PATH: mesh.male, PieceRole.FEMALE_CORNER_PATH: mesh.female}
    out: dict[PieceRole, list[np.ndarray]] = {}
    for piece in pieces:
        if piece.kind in bodies and len(piece.t):
            out.setdefault(piece.kind, []).append(np.median(bodies[piece.kind].to_body(piece.points, piece.t), axis=0))
    return {kind: np.array(corners) for kind, corners in out.items()}


def corner_gaps(pieces: list[MeshlinePiece], pair: RotorPair) -> list[np.ndarray]:
    """Return, per sample of each curve piece, how far its contact lies from a tip corner on either rotor.

    The contact point on the male (the female), the meshline point seen from that rotor
    (:meth:`rotorcad.kinematics.Rotation.to_body`), against that rotor's tip corners of
    :func:`_tip_corners` on every lobe (compared by radius and by angle modulo the angular pitch).

    Parameters
    ----------
    pieces : list of MeshlinePiece
        The meshline.
    pair : RotorPair
        The pair (its mesh, lobe counts, centre distance).

    Returns
    -------
    list of (n, 2) float arrays, mm
        One per piece: the distances on the male and on the female; inf for a rotor without a corner
        path on the meshline and for the samples of corner paths.
    """
    mesh = pair.mesh
    rotors = (
        (PieceRole.MALE_CORNER_PATH, mesh.male, np.zeros(2), pair.male_teeth),
        (PieceRole.FEMALE_CORNER_PATH, mesh.female, np.array([pair.center_distance, 0.0]), pair.female_teeth),
    )
    corners = _tip_corners(pieces, pair)
    out = []
    for piece in pieces:
        gaps = np.full((len(piece.t), 2), np.inf)
        out.append(gaps)
        if piece.kind is not PieceRole.CURVE:
            continue
        for k, (kind, body, centre, teeth) in enumerate(rotors):
            if kind not in corners:
                continue
            own = body.to_body(piece.points, piece.t) - centre  # (n, 2): the contact on that rotor
            radius, angle = np.hypot(own[:, 0], own[:, 1]), np.arctan2(own[:, 1], own[:, 0])
            q = corners[kind] - centre  # (m, 2)
            rq, aq = np.hypot(q[:, 0], q[:, 1]), np.arctan2(q[:, 1], q[:, 0])
            pitch = 2 * np.pi / teeth
            turn = (angle[:, None] - aq[None, :] + 0.5 * pitch) % pitch - 0.5 * pitch  # to the nearest lobe's corner
            gaps[:, k] = np.hypot(radius[:, None] - rq[None, :], rq[None, :] * turn).min(axis=1)
    return out


def _runs(mask: np.ndarray) -> np.ndarray:
    """Return the first and one-past-last index of each run of True in ``mask``, (m, 2) int."""
    edges = np.flatnonzero(np.diff(np.concatenate([[0], mask.astype(np.int8), [0]])))
    return edges.reshape(-1, 2)


def resolved_steps(piece: MeshlinePiece, steps: np.ndarray, gaps: np.ndarray, band: float, reach: float) -> np.ndarray:
    """Return which of a curve piece's steps (True in ``steps``, (n - 1,) bool) are working contact at the input's accuracy.

    Of a profile given to an accuracy e, the mate's contact point (the meshline point seen from the
    mate) is known to the meshline's accuracy ``band`` (:data:`~rotorcad.meshing.defects.MESHLINE_GAIN`
    e), and the working part's flank to the resolution ``reach`` (sqrt(8 a e),
    :func:`~rotorcad.meshing.defects.resolution`). A step is no working contact

    - where either end's contact lies within ``band`` of a tip corner (``gaps``, :func:`corner_gaps`):
      near its corner a flank generated from a fitted profile hands over to the corner's path along a
      rounding the fit makes (the Lysholm male's own CSV, accuracy 1 µm, gave a female whose contact
      stays within 5 µm of its tip corner while the male turns 2.5 deg: 1.5 mm of meshline along the
      female tip circle, read as a working part of ratio 0.028 for the design's 0);
    - where both ends lie within ``band`` of the line O1O2 (a land touches there only: a fit's lands
      are not flat to the 1e-9 of :func:`~rotorcad.meshing.meshline.flank_roles` and read as flank);
    - along a run of steps whose contact stays within ``reach`` of one rotor's tip corner all along:
      that rotor's flank part there is shorter than the input resolves, the corner rounded by the fit
      (the narrow-tip female's tip from 300 points a lobe: its contact wanders 0.2 mm from the corner
      while the male turns 12 deg, sealing ratio 0.28 for 0.17).

    Parameters
    ----------
    piece : MeshlinePiece
        A curve piece of the meshline.
    steps : (n - 1,) bool array
        Its steps on the flank in question.
    gaps : (n, 2) float array, mm
        :func:`corner_gaps` of the piece.
    band, reach : float, mm
        The meshline's accuracy and the resolution; 0 for a design's exact curves (every step counts).

    Returns
    -------
    (n - 1,) bool array
    """
    if band <= 0:
        return steps
    near = gaps.min(axis=1) <= band
    axis = np.abs(piece.points[:, 1]) <= band
    work = steps & ~near[:-1] & ~near[1:] & ~(axis[:-1] & axis[1:])
    for i, j in _runs(work):
        if (np.maximum(gaps[i:j], gaps[i + 1 : j + 1]).max(axis=0) <= reach).any():
            work[i:j] = False
    return work


def handover_length(accuracy: float, scale: float) -> float:
    """Return the meshline's resolution sqrt(8 a G e) (mm): the stretch along which a hand-over between two corners moves.

    A profile known to e places its meshline to :data:`~rotorcad.meshing.defects.MESHLINE_GAIN` e
    (G), and a stretch of the meshline is resolved over the chord along which a circle of the pair's
    size (the centre distance a) leaves its tangent by that: sqrt(8 a G e), sqrt(G) times the
    profile's resolution (:func:`~rotorcad.meshing.defects.resolution`). Where the design hands the
    contact over from one rotor's tip corner to the other's at a point (a corner against a corner,
    Krigar's housing cusp), a fit through points rounds both corners by its accuracy, and their
    flanks touch each other over up to that much meshline: 300 exact points a lobe of Krigar's male at
    phase 0.8 (e = 0.65 µm, a = 100 mm) put 0.96 mm of curve contact there, sqrt(8 a G e) = 2.28 mm.

    Parameters
    ----------
    accuracy : float, mm
        The profile's accuracy e.
    scale : float, mm
        The centre distance a.

    Returns
    -------
    float, mm
    """
    return float(np.sqrt(8.0 * scale * MESHLINE_GAIN * accuracy))


def on_tip_circles(piece: MeshlinePiece, pair: RotorPair, band: float, reach: float = 0.0) -> np.ndarray:
    """Return which of a piece's contacts lie on either rotor's tip circle to the meshline's accuracy ``band``.

    A contact on a rotor's tip circle is that rotor's tip (Rinder sec. 2.2.2: at the tip only a corner
    touches), not a working flank: its meshline point turns with the tip, so the meshline there is
    the tip circle itself. Of a profile given to an accuracy e, the fit rounds a tip corner, and the
    mate generated from it touches the rounding along the tip circle: the Lysholm female as 300 exact
    points a lobe (e = 0.8 µm) gave a curve piece 0.91-1.04 mm long on the male tip circle (its contact
    on the male within 0.03-0.04 mm of the tip corner), counted as sealing working part, and the
    overlap 2.31 made the flank run where the design's has no working part. A stretch longer than
    ``reach`` that keeps within :data:`~rotorcad.meshing.defects.TIP_CIRCLE_NEAR` of the centre distance
    of a tip circle, its contacts standing still on the rotor, is that tip corner's path too
    (:func:`~rotorcad.meshing.defects.tip_circle_runs`):
    the narrow-tip male as 1000 exact points a lobe put 9.8 mm of the female tip corner's path 1-7 µm
    off its tip circle, and the sealing working length read 19.1 mm for the design's 12.2.

    Parameters
    ----------
    piece : MeshlinePiece
        A piece of the meshline.
    pair : RotorPair
        The pair (tip radii, centre distance).
    band : float, mm
        The meshline's accuracy (:data:`~rotorcad.meshing.defects.MESHLINE_GAIN` e); 0 for a design
        (no contact is read as a tip).
    reach : float, mm
        The meshline's resolution; 0: no stretch test.

    Returns
    -------
    (n,) bool array
    """
    if band <= 0:
        return np.zeros(len(piece.t), dtype=bool)
    x, y = piece.points[:, 0], piece.points[:, 1]
    r1, r2 = np.hypot(x, y), np.hypot(x - pair.center_distance, y)
    out = (np.abs(r1 - pair.male_tip_radius) <= band) | (np.abs(r2 - pair.female_tip_radius) <= band)
    if reach > 0 and len(x) > 1:
        arclen = np.concatenate([[0.0], np.cumsum(piece.steps)])
        near = max(TIP_CIRCLE_NEAR * pair.center_distance, band)
        for side in (Side.MALE, Side.FEMALE):
            for i, j in tip_circle_runs(piece.points, piece.t, arclen, pair, side, near, reach):
                out[i : j + 1] = True
    return out


def _corner_path_points(pieces: list[MeshlinePiece]) -> dict[PieceRole, np.ndarray]:
    """Return the meshline samples of each rotor's tip-corner paths, (k, 2) float, mm, by path kind."""
    out: dict[PieceRole, list[np.ndarray]] = {}
    for piece in pieces:
        if piece.kind in (PieceRole.MALE_CORNER_PATH, PieceRole.FEMALE_CORNER_PATH):
            out.setdefault(piece.kind, []).append(piece.points)
    return {kind: np.vstack(points) for kind, points in out.items()}


def is_corner_handover(
    piece: MeshlinePiece, steps: np.ndarray, length: float, paths: dict[PieceRole, np.ndarray], handover: float
) -> bool:
    """Return True where a curve piece's contact on a flank is a hand-over between the two rotors' tip corners.

    Rinder sec. 1.2 counts as working only the contact with a common tangent; where a design's
    meshline passes from the male tip corner's path straight to the female's (Krigar: both corners
    meet at the housing cusp), a profile given to an accuracy e rounds both corners and leaves a short
    stretch of curve contact between the two paths. It is told from a working part by its length: one
    shorter than the meshline's resolution ``handover`` (:func:`handover_length`) whose ends lie
    within that of a male tip corner's path and of a female tip corner's path (one at each end, either
    way round) is the hand-over, not a flank the input resolves; so is one whose ends lie within that
    of one corner's path both, a piece of that path the fit broke off (the Lysholm female as 2000 exact
    points a lobe: 0.61-0.78 mm of curve contact between two pieces of the male tip corner's path, its
    contacts within 1-18 µm of the male tip circle, read as sealing working part, and the flank ran). A
    working part between the two paths longer than that (SRM-B's and the asymmetric SRM's sealing
    flanks, 13 mm) is kept.

    Parameters
    ----------
    piece : MeshlinePiece
        A curve piece.
    steps : (n - 1,) bool array
        Its steps on the flank in question.
    length : float, mm
        Their meshline length.
    paths : dict
        :func:`_corner_path_points` of the meshline.
    handover : float, mm
        The meshline's resolution; 0: never (a design).

    Returns
    -------
    bool
    """
    males, females = paths.get(PieceRole.MALE_CORNER_PATH), paths.get(PieceRole.FEMALE_CORNER_PATH)
    if handover <= 0 or length >= handover or (males is None and females is None) or not steps.any():
        return False
    idx = np.flatnonzero(steps)
    ends = piece.points[[idx[0], idx[-1] + 1]]  # (2, 2): the stretch's first and last contact

    def near(path: np.ndarray | None) -> np.ndarray:
        if path is None:
            return np.zeros(2, dtype=bool)
        return np.hypot(path[None, :, 0] - ends[:, None, 0], path[None, :, 1] - ends[:, None, 1]).min(axis=1) <= handover

    m, f = near(males), near(females)
    return bool((m[0] and f[1]) or (f[0] and m[1]) or (m[0] and m[1]) or (f[0] and f[1]))


def flank_reports(
    pieces: list[MeshlinePiece],
    defects: list[Defect],
    pair: RotorPair,
    tip_tolerance: float,
    shortest: float = 0.0,
    band: float = 0.0,
    handover: float = 0.0,
    generated: list[np.ndarray] | None = None,
    possible: list[Defect] = (),
) -> dict[Flank, FlankReport]:
    """Return per flank (driving, sealing): working part, defects and contact ratios (Rinder sec. 1.2, 2.2.1).

    A contact is geometric where a rack curve touches both rotors (a common tangent); a corner
    path's contacts are a corner against a flank (Rinder sec. 1.2: "eine Berührung ... im
    geometrischen Sinn mit gemeinsamen Tangenten ... ist in keinem Flankenteil gegeben"). The
    working part is the geometric contact; the point-generated parts seal but do not drive.
    Contact pieces shorter than 1e-6 of the centre distance (a corner touching only at C) do not
    count. The transverse ratio is the rotation covered by the steps between consecutive samples of
    the working part (:func:`covered_rotation`) that the input's accuracy resolves as working
    (:func:`resolved_steps`). The working length leaves out a given profile's contacts on a tip
    circle (:func:`on_tip_circles`).

    Parameters
    ----------
    pieces : list of MeshlinePiece
        The meshline.
    defects : list of Defect
        Its defects (:func:`rotorcad.meshing.defects.meshline_defects`).
    pair : RotorPair
        The pair (lobe count, wrap angle).
    tip_tolerance : float, mm
        How near a tip circle a cusp is that tip's corner (:attr:`MeshingAnalysis.tip_corner_tolerance`).
    shortest : float, mm
        Shortest geometric contact of a piece that makes a working part: a given profile's
        resolution (:func:`rotorcad.meshing.defects.resolution`; 1 µm of working flank came out of
        the Krigar male's points with 1 µm of scatter, which has none); 0 for a design.
    band : float, mm
        The meshline's accuracy, within which a contact is told from a tip corner's path or a land
        (:func:`resolved_steps`): :data:`~rotorcad.meshing.defects.MESHLINE_GAIN` times a given
        profile's accuracy; 0 for a design. A given profile's flank part shorter than ``shortest``
        near a tip corner is that corner too.
    handover : float, mm
        Of a given profile, the meshline's resolution (:func:`handover_length`): a curve piece's contact
        on the flank shorter than this that runs from the male tip corner's path to the female's is the
        corner-to-corner hand-over the fit rounds (:func:`is_corner_handover`), no working part; 0 for a
        design.
    generated : list of (n,) bool arrays, optional
        Of a given profile, per piece the samples the defect rules found point-generated (a cusp's
        stretch, :func:`rotorcad.meshing.defects.meshline_defects`): a corner's path, no working part
        (the Lysholm male as 2000 exact points a lobe: a curve piece along the female tip corner's path,
        35.2 mm read as one point-generated cusp, counted 8.0 mm of sealing working part, and the
        flank ran where the design's has none). None for a design.
    possible : list of Defect, optional
        Of a given profile, the defects it can neither show nor rule out (``below`` of
        :func:`rotorcad.meshing.defects.meshline_defects`): :attr:`FlankReport.undecided`.

    Returns
    -------
    dict
        Flank -> :class:`FlankReport`.
    """
    pitch_angle = 2 * np.pi / pair.male_teeth
    overlap = float(pair.wrap_angle / pitch_angle)  # Sprungüberdeckung: wrap angle per angular pitch
    tol = tip_tolerance
    out = {}
    # chord lengths (shared with the defect rules); of a given profile measured at twice its resolution
    steps = [resolved_lengths(piece.points, piece.t, 2.0 * shortest) if band > 0 else piece.steps for piece in pieces]
    gaps = corner_gaps(pieces, pair) if band > 0 else [np.zeros((0, 2))] * len(pieces)
    paths = _corner_path_points(pieces) if handover > 0 else {}
    held = generated if generated is not None else [None] * len(pieces)
    for flank in (Flank.DRIVING, Flank.SEALING):
        total = geometric = working = decided = 0.0
        spans: list[np.ndarray] = []  # (m, 2): the male rotation between consecutive working contacts
        undecided: list[np.ndarray] = []  # (m, 2): curve contact taken for none that may work
        ends = 0.0  # rad: how far the ends of the decided working stretches may be off, summed
        for piece, seg, gap, pg in zip(pieces, steps, gaps, held, strict=True):
            mask = piece.flank_mask(flank)
            if mask.sum() < 2:
                continue
            both = mask[:-1] & mask[1:]  # a step of the meshline on the flank: both its ends on it
            length = float(seg[both].sum())
            if length < 1e-6 * pair.center_distance:
                continue
            total += length
            if piece.kind is not PieceRole.CURVE:
                continue
            if length < shortest or is_corner_handover(piece, both, length, paths, handover):
                undecided.append(step_spans(piece, both))  # curve contact taken for none: it may work
            else:
                geometric += length  # a curve piece's contact is geometric but where the defect rules found a corner's path
                tip = on_tip_circles(piece, pair, band, shortest)
                on_tip = tip[:-1] & tip[1:]
                work = resolved_steps(piece, both, gap, band, shortest)
                if pg is not None:  # a point-generated stretch of the defect rules: a corner's path
                    on_tip |= pg[:-1] & pg[1:]
                    work &= ~(pg[:-1] & pg[1:])
                    geometric -= float(seg[both & pg[:-1] & pg[1:]].sum())
                if band > 0:  # a contact within the meshline's accuracy of a tip corner is that corner (resolved_steps)
                    corner = gap.min(axis=1) <= band
                    on_tip |= corner[:-1] | corner[1:]
                working += float(seg[both & ~on_tip].sum())
                spans.append(step_spans(piece, work))
                if band > 0:  # curve contact taken for none may work, but a corner's path the defect rules found
                    held_back = both & ~work if pg is None else both & ~work & ~(pg[:-1] & pg[1:])
                    undecided.append(step_spans(piece, held_back))
                at_ends, whole = end_spans(piece, work, pair, shortest)
                ends += at_ends
                undecided.append(whole)
                decided += float(seg[work & ~on_tip].sum())  # working as the input decides it
        mine = [d for d in defects if d.role is flank and d.kind != "slipping"]
        # a corner's path across O1O2 (its lobe part the tip or the root) is the corner of both flanks
        across = [d for d in defects if d.role in (Flank.TIP, Flank.ROOT) and d.kind == "cusp"]
        corners = tuple(sorted({d.rotor for d in mine + across if is_tip_corner(d, pair, tol)}))
        kinds = tuple(sorted({d.kind for d in mine if not is_tip_corner(d, pair, tol)}))
        span = np.vstack(spans) if spans else np.zeros((0, 2))
        ratio = covered_rotation(span[:, 0], span[:, 1]) / pitch_angle
        # and each end placed on the meshline to the resolution, 2 sqrt(8 a e) / p_t (p_t = r1w 2 pi / z1)
        placed = 2.0 * shortest / (pair.male_teeth * pair.center_distance / (pair.male_teeth + pair.female_teeth) * pitch_angle)
        accuracy = ratio_uncertainty(undecided, ends) / pitch_angle + placed
        out[flank] = FlankReport(
            flank,
            total,
            geometric / total if total > 0 else 0.0,
            kinds,
            ratio,
            working,
            overlap if working > 0 else 0.0,
            corners,
            accuracy,
            decided if band > 0 else None,
            tuple(sorted({d.kind for d in possible if d.role is flank})),
        )
    return out


def running_reasons(
    flanks: dict[Flank, FlankReport], defects: list[Defect], pair: RotorPair, tip_tolerance: float, possible: list[Defect] = ()
) -> list[str]:
    """Return why the pair does not run without timing gears, one sentence per flank (empty: it runs).

    Arguments: the flank reports (:func:`flank_reports`), the defects, the pair and the tip-corner
    tolerance (mm) they were judged with, and the defects the input can neither show nor rule out (their places).
    """
    out = []
    for flank, report in flanks.items():
        if report.runs_without_timing_gears:
            continue
        if report.meshline_length == 0:
            out.append(f"the {flank} flank has no contact inside the bores.")
            continue
        parts = []
        for kind in report.undecided:
            places = ", ".join(f"({d.x:.2f}, {d.y:.2f}) mm" for d in possible if d.role is flank and d.kind == kind)
            parts.append(f"{kind} the input's accuracy can neither show nor rule out at {places}: undecided, not shown to run")
        if not report.running_decided and not report.undecided:
            parts.append(
                f"its {report.working_length:.2f} mm of working part is contact the input's accuracy does not tell from "
                "a tip corner's path (a corner the fit rounded): undecided at this accuracy, not shown to run"
            )
        elif report.working_length == 0:
            parts.append(
                "no geometric contact anywhere (a tip corner against the mate's flank, no common tangent): no working "
                "part for the helix to carry"
            )
        for kind in report.defects:
            rotors = sorted(
                {d.rotor for d in defects if d.role is flank and d.kind == kind and not is_tip_corner(d, pair, tip_tolerance)}
            )
            parts.append(f"{kind} on the {' and '.join(rotors)} inside its working part")
        if report.working_length > 0 and report.total_contact_ratio < 1.0 - 1e-9:
            parts.append(
                f"total contact ratio {report.total_contact_ratio:.2f} below 1 (transverse "
                f"{report.transverse_contact_ratio:.2f} + overlap {report.overlap_contact_ratio:.2f}): too little wrap"
            )
        out.append(f"the {flank} flank: " + "; ".join(parts) + ".")
    return out

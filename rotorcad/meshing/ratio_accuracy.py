"""How well a given profile's transverse contact ratio is known: the rotation its accuracy leaves undecided.

The transverse ratio counts the male rotation over which a flank's working part (Rinder sec. 1.2:
contact "im geometrischen Sinn mit gemeinsamen Tangenten") is in contact. Each end of the working part
is where the contact reaches a rotor's tip corner or tip circle (sec. 2.2.1, 2.2.2), and a profile given
to an accuracy e places a corner only to the resolution sqrt(8 a e)
(:func:`~rotorcad.meshing.defects.resolution`) *along that rotor's profile*: a fit rounds the corner
over that much flank. The male rotation that this leaves undecided is the rotation over which the
contact on that rotor travels that far, not the resolution over the transverse pitch: where the contact
on the corner's rotor moves slowly (near a cusp its speed along the profile falls to 0; the narrow-tip
female's sealing working flank is 2.9 mm of profile for 12.2 mm of meshline) the rotation is several
times sqrt(8 a e) / p_t, and the narrow-tip male's sealing ratio from 80 points a lobe read 0.000 and 0.49
for the design's 0.175 where sqrt(8 a e) / p_t promised 0.09. Contact the accuracy rules took for no
working part (near a tip corner, on a tip circle, a corner-to-corner hand-over,
:func:`~rotorcad.meshing.contact_ratios.flank_reports`) may be working, and is undecided too; not the
stretches the defect rules found point-generated (a corner's path: the narrow-tip male as 2000 exact
points a lobe states 0.07 on its sealing ratio, 0.27 when they counted).

So the stated accuracy of the ratio is the measure of the union of those rotations, per angular pitch
(:func:`ratio_uncertainty`): an honest bound built from the input's own meshline, checked against the
designs' ratios over samples, densities and seeds of scatter in tests/test_moderate_densities.py.
"""

from __future__ import annotations

import numpy as np

from rotorcad.meshing.meshline import MeshlinePiece
from rotorcad.rotor_pair import RotorPair


def covered_rotation(lo: np.ndarray, hi: np.ndarray) -> float:
    """Return the measure of the union of the intervals ``[lo, hi]`` (rad): the rotation they cover.

    Parameters
    ----------
    lo, hi : (n,) float array, rad
        Each interval's ends (``lo <= hi``): a flank's contact between two consecutive samples.

    Returns
    -------
    float, rad
        The rotation over which at least one interval holds; 0 for none (an interval of one instant,
        a circle about C touching all along at once, adds nothing).
    """
    if len(lo) == 0:
        return 0.0
    order = np.argsort(lo, kind="stable")
    lo, hi = lo[order], hi[order]
    reach = np.concatenate([[-np.inf], np.maximum.accumulate(hi)[:-1]])  # the farthest end of the intervals before
    return float(np.maximum(hi - np.maximum(lo, reach), 0.0).sum())


def _runs(mask: np.ndarray) -> np.ndarray:
    """Return the first and one-past-last index of each run of True in ``mask``, (m, 2) int."""
    edges = np.flatnonzero(np.diff(np.concatenate([[0], mask.astype(np.int8), [0]])))
    return edges.reshape(-1, 2)


def contact_travel(piece: MeshlinePiece, pair: RotorPair) -> np.ndarray:
    """Return how far each rotor's contact point has travelled along that rotor from the piece's first sample.

    The contact on the male (the female) is the meshline point seen from that rotor
    (:meth:`rotorcad.kinematics.Rotation.to_body`); its travel the length of the polyline of those
    points (a corner's contact stands still: no travel).

    Parameters
    ----------
    piece : MeshlinePiece
        A piece of the meshline, n samples.
    pair : RotorPair
        The pair (its mesh).

    Returns
    -------
    (n, 2) float array, mm
        Cumulative travel on the male and on the female.
    """
    out = np.zeros((len(piece.t), 2))
    for k, body in enumerate((pair.mesh.male, pair.mesh.female)):
        own = body.to_body(piece.points, piece.t)
        out[1:, k] = np.cumsum(np.hypot(*np.diff(own, axis=0).T))
    return out


def end_spans(piece: MeshlinePiece, work: np.ndarray, pair: RotorPair, reach: float) -> tuple[float, np.ndarray]:
    """Return how far (rad of male rotation) the ends of the working stretches may be off, and the undecided stretches.

    At each end of a run of working steps the rotor whose tip circle the contact lies nearer (the
    corner that ends the working part, or the bore it leaves; both where the end lies within ``reach``
    of both tip circles, at the housing cusp) is taken; the end may be off by the rotation over which
    that rotor's contact (both) travels ``reach`` from the end into the stretch, at least the end's
    own step (and as far outside). A stretch whose two ends' rotations add up to its own is undecided
    as a whole: each of its contacts lies within ``reach`` of an end, and it may be a tip corner's path
    that the fit rounded (the asymmetric SRM's male with 1 µm of scatter, 150 points a lobe: 15 deg of
    driving contact along the female tip corner's path, ratio 0.21 for the design's 0).

    Parameters
    ----------
    piece : MeshlinePiece
        A curve piece, n samples.
    work : (n - 1,) bool array
        Its working steps on the flank in question.
    pair : RotorPair
        The pair (tip radii, centre distance, mesh).
    reach : float, mm
        The resolution along a profile, sqrt(8 a e); 0 for a design (each end known to its step).

    Returns
    -------
    ends : float, rad
        The sum over the ends of the decided stretches.
    whole : (m, 2) float array, rad
        The rotation of each step of the undecided stretches, lower end first.
    """
    runs = _runs(work)
    x, y = piece.points[:, 0], piece.points[:, 1]
    off_tip = np.column_stack(
        [np.abs(np.hypot(x, y) - pair.male_tip_radius), np.abs(np.hypot(x - pair.center_distance, y) - pair.female_tip_radius)]
    )
    travel = contact_travel(piece, pair) if reach > 0 and len(runs) else np.zeros((len(x), 2))
    t = piece.t
    ends, whole = 0.0, []
    for i, j in runs:  # steps i .. j - 1, samples i .. j
        own = np.sort(np.column_stack([t[i:j], t[i + 1 : j + 1]]), axis=1)
        deltas = []
        for end, inward in ((i, slice(i, j + 1)), (j, slice(j, i - 1 if i > 0 else None, -1))):
            near = off_tip[end] <= max(reach, off_tip[end].min())  # the rotor(s) on whose tip circle the end lies
            s, ts = travel[inward][:, near], t[inward]
            beyond = np.flatnonzero((np.abs(s - s[0]) >= reach).all(axis=1))
            stop = ts[beyond[0]] if len(beyond) else ts[-1]
            deltas.append(max(abs(stop - ts[0]), abs(ts[1] - ts[0])))
        if reach > 0 and sum(deltas) >= covered_rotation(own[:, 0], own[:, 1]):
            whole.append(own)
        else:
            ends += sum(deltas)
    return ends, np.vstack(whole) if whole else np.zeros((0, 2))


def step_spans(piece: MeshlinePiece, steps: np.ndarray) -> np.ndarray:
    """Return the male rotation (rad) of each of the piece's steps marked in ``steps``, (m, 2), lower end first."""
    return np.sort(np.column_stack([piece.t[:-1][steps], piece.t[1:][steps]]), axis=1)


def ratio_uncertainty(undecided: list[np.ndarray], ends: float) -> float:
    """Return the male rotation (rad) by which the working part's may be off (the ratio's accuracy times the pitch).

    The ends of the decided working stretches may each be off by their rotation (:func:`end_spans`);
    curve contact taken for none and the undecided stretches (``undecided``) may all be working, or
    none of it: the sum of the two.

    Parameters
    ----------
    undecided : list of (m, 2) float arrays, rad
        Rotation intervals of curve contact whose working or not the input's accuracy does not decide.
    ends : float, rad
        The sum of :func:`end_spans` over the pieces.

    Returns
    -------
    float, rad
    """
    loose = np.vstack(undecided) if undecided else np.zeros((0, 2))
    return ends + covered_rotation(loose[:, 0], loose[:, 1])

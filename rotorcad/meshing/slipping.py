"""Rinder's slipping rule where the meshline crosses O1O2 between two of its pieces (sec. 2.2.1).

The meshline crosses O1O2 away from the pitch point C where a tip touches the mate's root; no flank
drives the other there. A crossing inside a piece is found with the other rules
(:func:`rotorcad.meshing.defects.meshline_defects`); this module judges the hand-overs between pieces
and names a slipping point by where it lies.
"""

from __future__ import annotations

import numpy as np

from rotorcad.meshing.defect_record import MESHLINE_GAIN, Defect, resolution
from rotorcad.meshing.meshline import MeshlinePiece
from rotorcad.roles import Flank
from rotorcad.rotor_pair import RotorPair


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
    # away from C: a point's place on O1O2 is known to far better than the resolution along the meshline
    # (the rack-involute's female tip on the male root lies 1 mm from C, the resolution at 2 µm is 1.3 mm)
    away = max(1e-6 * scale, min(near, 1e-3 * scale + 20.0 * accuracy) if given else 0.0)
    # a piece's side of O1O2 where it lies beyond the meshline's scatter there: MESHLINE_GAIN times the profile's
    # accuracy (a given profile's meshline lies that far off the design's at the median; the rack-involute female
    # as 300 exact points a lobe began its driving flank 2 um on the sealing side), and three times as far from
    # O1O2 as the piece's end misses it where it hands over (its scatter measured in place: the N rack's female
    # with 1 um ends its sealing flank 27 um on the driving side). The pieces after it that keep within that
    # distance of O1O2 (lands) hand over. Three times MESHLINE_GAIN everywhere (0.5-0.6 mm at 80 points a lobe)
    # lost the female tip's slipping on the male root of the N rack, Rinder-Deix and rack-involute females from
    # 80 points a lobe: their meshline leaves O1O2 by 0.39-0.48 mm there (the design's and the points' alike)
    floor = MESHLINE_GAIN * accuracy if given else 1e-9 * scale
    ys = [piece.points[:, 1] for piece in pieces]
    found = []
    for i, (piece, y_out) in enumerate(zip(pieces, ys, strict=True)):
        p, t = piece.points[-1], float(piece.t[-1])
        if abs(p[1]) > near or abs(p[0] - c_x) <= away or not np.any(np.abs(y_out) > floor):
            continue  # off O1O2, at C, or a land
        off = max(floor, 3.0 * abs(p[1])) if given else floor
        j = _next_beyond(pieces, ys, i, off, near)
        if j is None:
            continue
        # within the resolution of the end, and within half its distance from C (a root's loop turns back to C)
        reach_out = min(near, 0.5 * abs(p[0] - c_x))
        reach_in = min(near, 0.5 * abs(pieces[j].points[0, 0] - c_x))
        out = _side(y_out[::-1], np.concatenate([[0.0], np.cumsum(piece.steps[::-1])]), off, reach_out)
        into = _side(ys[j], np.concatenate([[0.0], np.cumsum(pieces[j].steps)]), off, reach_in)
        if out * into < 0:
            role = Flank.TIP if p[0] > c_x else Flank.ROOT
            found.append(
                Defect("slipping", "male", float(p[0]), float(p[1]), float(np.degrees(t)), slipping_name(p[0], c_x), role=role)
            )
    return found


def _side(y: np.ndarray, arclen: np.ndarray, off: float, near: float) -> float:
    """Return the side of O1O2 (+1, -1; 0 for none) on which a piece lies next to one of its ends.

    ``y`` (mm) and ``arclen`` (mm of meshline) run from that end. The side is that of the sample farthest from
    O1O2 within ``near`` (mm of meshline) of the end among those beyond ``off`` (mm), else that of the first
    beyond ``off``: a given profile's meshline may wobble across O1O2 by its scatter just beside a root, where it
    leaves O1O2 tangentially (the rack-involute male as 600 exact points a lobe began its driving flank 1.2 and
    2.4 µm on the sealing side over 0.02 mm of meshline before its loop 0.39 mm on the driving side below C), and
    its first sample beyond ``off`` then named the wrong side and lost the female tip's slipping on the male root.
    ``near`` is the resolution, at most half the end's distance from C: the loop beside a root turns back across
    O1O2 at C (1 mm from the rack-involute's male root), beyond which the flank lies on the other side.
    """
    beyond = np.abs(y) > off
    if not beyond.any():
        return 0.0
    window = beyond & (arclen <= near)
    k = int(np.argmax(np.where(window, np.abs(y), -1.0))) if window.any() else int(np.argmax(beyond))
    return float(np.sign(y[k]))


def _next_beyond(pieces: list[MeshlinePiece], ys: list[np.ndarray], i: int, off: float, land: float) -> int | None:
    """Return the index of the first piece after the ``i``-th that leaves O1O2 by more than ``off`` (mm), or None.

    The pieces between that keep within ``off`` of O1O2 and are shorter than ``land`` (mm of meshline: a land's
    touch, the resolution) hand over; a longer one that keeps within ``off`` ends the search (no side beyond it).
    """
    for k in range(1, len(pieces)):
        j = (i + k) % len(pieces)
        if np.any(np.abs(ys[j]) > off):
            return j
        if float(np.sum(pieces[j].steps)) >= land:
            return None
    return None


def slipping_name(x: float, pitch_x: float) -> str:
    """Name a slipping point by where it lies on O1O2: which rotor's tip meets which root.

    Rinder sec. 2.2.1: the meshline crosses O1O2 away from the pitch point C where a tip touches the
    mate's root; beyond C (x > ``pitch_x``, mm, the male pitch radius) the male tip on the female root,
    before it the female tip on the male root. The name depends on the place alone, not on the piece of
    the meshline the crossing falls in: from points, the design's "male tip on the female root" of the
    narrow-tip pair fell inside a piece or between two, and read 'driving flank', 'tip land' or
    'sealing flank' by run.
    """
    return "male tip on the female root" if x > pitch_x else "female tip on the male root"

"""The mate's tip-corner cycloids of a pair from scattered rotor points, taken exactly for the hob.

A pair generated from one rotor's points (:func:`rotorcad.measured.pairs.pair_from_rotor_points`)
carries on its rack the path of the mate's tip corner wherever the mate's generated point stands
still. Of a corner on the mate's pitch circle (the SRM, Lysholm, Krigar and narrow-tip females: tip
radius = pitch radius) that path is a cycloid whose cusp lies on the pitch line, where the rack flank
stands perpendicular to it (Rinder sec. 2.2.2, Fig. 1-4; Litvin, *Gear Geometry and Applied Theory*,
sec. 6.1): the hob's smallest flank angle is 0 there. Of exact points the pair takes that path as its
exact cycloid; of scattered ones it keeps the path as generated from the fit, whose tangent error
grows without bound at the cusp: from 300 points a lobe with 2 um of scatter the male's rack met the
pitch line 1.75-2.51 deg off the perpendicular, 7.9-19.9 um off the design's rack, and
``rack_deviation`` read 9-239 um where the truth is 0.

Of a female given by points, the path of her own fitted tip corner (a point within the accuracy of her
tip circle, not on it) misses the cusp alike: the male generated from 2 um of scatter on the SRM-B
female reached it 0.10 deg off the perpendicular. For the hob verdict (the rack's shape at the cusp)
either path is taken as the cycloid whose corner position fits it best
(:func:`rotorcad.measured.rack_pieces.tip_corner_path`, within :data:`rotorcad.measured.pairs.PATH_FIT`
accuracies). Only for the hob: in the meshing analysis the
same exact paths moved the symmetric SRM's blow-hole from 1 um of scatter by -19..-33 %
(tests/test_verdict_invariance.py), whose verdict stays on the generated path.
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np

from rotorcad.envelope import Generated
from rotorcad.measured.mate_paths import mate_corner_runs
from rotorcad.measured.pairs import PATH_FIT
from rotorcad.measured.rack_pieces import tip_corner_path
from rotorcad.roles import PieceRole, Side
from rotorcad.screw_rotors import RackPiece, ScrewRotors


def with_exact_cusp_paths(rotors: ScrewRotors) -> ScrewRotors:
    """Return the pair with the mate's tip-corner paths on its rack replaced by their exact cycloids.

    Parameters
    ----------
    rotors : ScrewRotors
        A pair from one rotor's points (family ``male-points`` or ``female-points``).

    Returns
    -------
    ScrewRotors
        The same pair (the object itself) when it is not from rotor points, when neither rotor's tip
        circle is its pitch circle, or when no path is replaced; else a copy whose rack's tip-corner
        paths of such a rotor (the mate's, generated from the fit of scattered points, or the given
        rotor's own, the path of its fitted corner, of exact points too: the narrow-tip and asymmetric
        SRM females' of 300-2000 exact points a lobe gave the male's rack 0.06-0.13 deg at the cusp)
        that an exact cycloid holds are that cycloid
        (a :class:`rotorcad.curves.PointPath`), both rotors generated anew from it.
    """
    family = str(getattr(rotors, "family", ""))
    if family not in ("male-points", "female-points"):
        return rotors
    scattered = rotors.tangent_accuracy > 0  # exact points' pairs take the mate's paths exactly already
    pair = rotors.pair
    measured = Side(family.split("-")[0])

    def on_pitch(side: Side) -> bool:  # the tip circle is the pitch circle: a cycloid with its cusp on the pitch line
        pitch = side.pick(pair.male_pitch_radius, pair.female_pitch_radius)
        return abs(side.pick(pair.male_tip_radius, pair.female_tip_radius) - pitch) <= 1e-6 * pitch

    cusped = [side for side in ((measured.other, measured) if scattered else (measured,)) if on_pitch(side)]
    if not cusped:
        return rotors
    roles = {PieceRole.corner_path_of(side): side for side in cusped}
    tol = PATH_FIT * float(rotors.accuracy)
    mate = measured.other
    mesh = pair.mesh
    mate_tip = (np.array([mate.pick(0.0, pair.center_distance), 0.0]), mate.pick(pair.male_tip_radius, pair.female_tip_radius))
    rack: list[RackPiece] = []
    changed = False
    for piece in rotors.rack:
        curve = piece.curve
        if np.isclose(curve.s0, curve.s1) or (piece.kind not in roles and piece.kind is not PieceRole.CURVE):
            rack.append(piece)
            continue
        if piece.kind in roles:  # a mate's path generated from the fit, or the given rotor's fitted corner's path
            path = tip_corner_path(pair, roles[piece.kind], curve, curve.s0, curve.s1, tol)
            rack.append(piece if path is None else replace(piece, curve=path))
            changed |= path is not None
            continue
        if mate not in cusped:  # (of exact points too)
            rack.append(piece)
            continue
        # a flank piece: a stretch of it shorter than the profile's resolution may be the mate's cycloid, read as
        # flank of scattered points (the symmetric SRM female's path, 1.6 mm of rack at a resolution of 2.4 mm)
        runs = mate_corner_runs(
            curve,
            Generated(curve, mesh.rack, mate.pick(mesh.male, mesh.female)),
            scattered=True,
            tip=(*mate_tip, 1e-3 * pair.center_distance),
            accuracy=float(rotors.accuracy),
        )
        for a, b, corner in runs:
            path = tip_corner_path(pair, mate, curve, a, b, tol) if corner else None
            if path is not None:
                rack.append(RackPiece(path, piece.male_name, piece.female_name, kind=PieceRole.corner_path_of(mate)))
                changed = True
            else:
                rack.append(replace(piece, curve=curve.trimmed(a, b)) if len(runs) > 1 else piece)
    return replace(rotors, rack=tuple(rack)) if changed else rotors


__all__ = ["with_exact_cusp_paths"]

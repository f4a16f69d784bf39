"""Per flank: working part, contact ratios and whether it runs (Rinder sec. 1.2, 2.2.1).

The transverse contact ratio (male rotation over which the working part is in contact, per angular
pitch), the overlap ratio (Sprungüberdeckung, z1 L / h1) and their sum; a flank runs with a working
part, no cusp or jamming inside it and a total ratio of at least 1 (:class:`FlankReport`). The
criteria are stated in :mod:`rotorcad.meshing`.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from rotorcad.meshing.defects import Defect, is_tip_corner
from rotorcad.meshing.meshline import MeshlinePiece
from rotorcad.roles import Flank, PieceRole
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


def flank_reports(
    pieces: list[MeshlinePiece], defects: list[Defect], pair: RotorPair, tip_tolerance: float, shortest: float = 0.0
) -> dict[Flank, FlankReport]:
    """Return per flank (driving, sealing): working part, defects and contact ratios (Rinder sec. 1.2, 2.2.1).

    A contact is geometric where a rack curve touches both rotors (a common tangent); a corner
    path's contacts are a corner against a flank (Rinder sec. 1.2: "eine Berührung ... im
    geometrischen Sinn mit gemeinsamen Tangenten ... ist in keinem Flankenteil gegeben"). The
    working part is the geometric contact; the point-generated parts seal but do not drive.
    Contact pieces shorter than 1e-6 of the centre distance (a corner touching only at C) do not
    count.

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

    Returns
    -------
    dict
        Flank -> :class:`FlankReport`.
    """
    pitch_angle = 2 * np.pi / pair.male_teeth
    overlap = float(pair.wrap_angle / pitch_angle)  # Sprungüberdeckung: wrap angle per angular pitch
    tol = tip_tolerance
    out = {}
    steps = [piece.steps for piece in pieces]  # chord lengths, once (shared with the defect rules)
    for flank in (Flank.DRIVING, Flank.SEALING):
        total = geometric = 0.0
        t_geo: list[np.ndarray] = []
        for piece, seg in zip(pieces, steps, strict=True):
            mask = piece.flank_mask(flank)
            if mask.sum() < 2:
                continue
            length = float(seg[mask[:-1] & mask[1:]].sum())
            if length < 1e-6 * pair.center_distance:
                continue
            total += length
            if piece.kind is PieceRole.CURVE and length >= shortest:
                geometric += length
                t_geo.append(piece.t[mask])
        mine = [d for d in defects if d.role is flank and d.kind != "slipping"]
        # a corner's path across O1O2 (its lobe part the tip or the root) is the corner of both flanks
        across = [d for d in defects if d.role in (Flank.TIP, Flank.ROOT) and d.kind == "cusp"]
        corners = tuple(sorted({d.rotor for d in mine + across if is_tip_corner(d, pair, tol)}))
        kinds = tuple(sorted({d.kind for d in mine if not is_tip_corner(d, pair, tol)}))
        ratio = _covered(t_geo) / pitch_angle
        out[flank] = FlankReport(
            flank,
            total,
            geometric / total if total > 0 else 0.0,
            kinds,
            ratio,
            geometric,
            overlap if geometric > 0 else 0.0,
            corners,
        )
    return out


def running_reasons(flanks: dict[Flank, FlankReport], defects: list[Defect], pair: RotorPair, tip_tolerance: float) -> list[str]:
    """Return why the pair does not run without timing gears, one sentence per flank (empty: it runs).

    Arguments: the flank reports (:func:`flank_reports`), the defects, the pair and the tip-corner
    tolerance (mm) they were judged with.
    """
    out = []
    for flank, report in flanks.items():
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

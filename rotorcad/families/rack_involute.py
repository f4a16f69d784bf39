"""Rinder's rack-involute profile (*Sonderverzahnungen für Schraubenverdichterrotoren*, Fig. 6, ref. /5/).

Straight rack flanks (involutes on both rotors) with tip and root roundings; the sealing involute
is used up to the female tip (sharp female tip corner by default).
"""

from __future__ import annotations

import itertools
from typing import Annotated

import numpy as np

from rotorcad.errors import DesignError
from rotorcad.families.corners import flank_to_female_tip, male_tip_corner
from rotorcad.families.parameters import FlankAngle, at_least, between
from rotorcad.roles import PieceRole
from rotorcad.rotor_pair import RotorPair
from rotorcad.screw_rotors import RackPiece, ScrewRotors, rack_arc, rack_line

DEG = np.pi / 180.0
DedendumShare = Annotated[float, at_least(0.0, "at least 0 (fraction of the male dedendum)")]
"""A rounding at the rack bottom, as a fraction of the male dedendum d1."""


def rack_involute(
    pair: RotorPair,
    driving_angle_deg: FlankAngle = 30.0,
    sealing_angle_deg: FlankAngle = 25.0,
    lobe_width: Annotated[float, between(0.1, 0.9, "between 0.1 and 0.9 (share of the rack period)")] = 0.5,
    tip_rounding: Annotated[float, at_least(0.0, "at least 0 (fraction of the male addendum)")] = 0.3,
    root_rounding: DedendumShare = 0.3,
    sealing_tip_rounding: DedendumShare = 0.0,
) -> ScrewRotors:
    """Rinder's rack-involute profile (Fig. 6): a trapezoidal rack tooth with straight flanks.

    ``lobe_width`` is the male lobe's share of the rack period at the pitch line; the roundings are
    radii as fractions of h1 (rack top: male tip) and d1 (rack bottom: male root / female tip);
    ``sealing_tip_rounding`` = 0 keeps the female tip sharp on the sealing side. With
    ``tip_rounding`` = 0 the male tips are sharp corners: where a straight flank's contacts leave the
    male bore before the rack top, the flank is trimmed there and the male tip corner's own path
    generates the female beyond (:func:`male_tip_corner`), so that the rotors are conjugate to each
    other, not only to the rack (Rinder sec. 3.2: the female sealing involute used down to its base
    circle, met there by the male tip corner; ``samples/rack_involute_5_6.toml``).
    """
    p, h1, d1 = pair.rack_period, pair.male_addendum, pair.male_dedendum
    ad, as_ = driving_angle_deg * DEG, sealing_angle_deg * DEG
    w, xc = lobe_width * p, p / 2
    rt, rb, rbs = tip_rounding * h1, root_rounding * d1, sealing_tip_rounding * d1

    def x_drive(y: float) -> float:  # left (driving) flank, rising
        return xc - w / 2 + y * np.tan(ad)

    def x_seal(y: float) -> float:  # right (sealing) flank, falling
        return xc + w / 2 - y * np.tan(as_)

    # roundings: centres at the radius from the flank and from the top / bottom line
    cbl = (x_drive(-d1 + rb) - rb / np.cos(ad), -d1 + rb)
    ctl = (x_drive(h1 - rt) + rt / np.cos(ad), h1 - rt)
    ctr = (x_seal(h1 - rt) - rt / np.cos(as_), h1 - rt)
    cbr = (x_seal(-d1 + rbs) + rbs / np.cos(as_), -d1 + rbs)
    pts = {
        "bl_bottom": (cbl[0], -d1),
        "bl_flank": (cbl[0] + rb * np.cos(ad), cbl[1] - rb * np.sin(ad)),
        "tl_flank": (ctl[0] - rt * np.cos(ad), ctl[1] + rt * np.sin(ad)),
        "tl_top": (ctl[0], h1),
        "tr_top": (ctr[0], h1),
        "tr_flank": (ctr[0] + rt * np.cos(as_), ctr[1] + rt * np.sin(as_)),
        "br_flank": (cbr[0] - rbs * np.cos(as_), cbr[1] - rbs * np.sin(as_)),
        "br_bottom": (cbr[0], -d1),
    }
    order = [
        ("start", 0.0),
        ("bl_bottom", pts["bl_bottom"][0]),
        ("tl_top", pts["tl_top"][0]),
        ("tr_top", pts["tr_top"][0]),
        ("br_bottom", pts["br_bottom"][0]),
        ("end", p),
    ]
    xs = [x for _, x in order]
    if (
        not all(b >= a - 1e-9 for a, b in itertools.pairwise(xs))
        or pts["bl_flank"][1] > pts["tl_flank"][1]
        or pts["br_flank"][1] > pts["tr_flank"][1]
    ):
        raise DesignError(
            "lobe_width",
            "such that the rack tooth, its roundings and the gaps fit one rack period",
            lobe_width,
            "the flanks, roundings and lands overlap",
        )
    seal = rack_line(pair, pts["tr_flank"], pts["br_flank"])
    rack = (
        RackPiece(rack_line(pair, (0.0, -d1), pts["bl_bottom"]), "root arc", "tip arc"),
        RackPiece(rack_arc(pair, cbl, rb, -np.pi / 2, -ad), "driving root fillet", "driving tip rounding"),
    )
    drive = rack_line(pair, pts["bl_flank"], pts["tl_flank"])
    drive_cut = male_tip_corner(pair, drive, rising=True) if rt == 0.0 else None
    land_start = pts["tl_top"]
    if drive_cut is None:
        rack += (
            RackPiece(drive, "driving flank", "driving flank"),
            RackPiece(rack_arc(pair, ctl, rt, np.pi - ad, np.pi / 2), "driving tip rounding", "driving root fillet"),
        )
    else:  # sharp male driving tip beyond which the flank leaves the male bore: the corner's own path
        drive, corner, x_corner = drive_cut
        land_start = (x_corner, h1)
        rack += (
            RackPiece(drive, "driving flank", "driving flank"),
            RackPiece(corner, "driving tip corner", "driving root (male tip path)", kind=PieceRole.MALE_CORNER_PATH),
        )
    cut = male_tip_corner(pair, seal) if rt == 0.0 else None
    if cut is None:
        rack += (
            RackPiece(rack_line(pair, land_start, pts["tr_top"]), "tip arc", "root arc"),
            RackPiece(rack_arc(pair, ctr, rt, np.pi / 2, as_), "sealing tip rounding", "sealing root fillet"),
        )
    else:  # sharp male sealing tip beyond which the flank leaves the male bore: the corner's own path
        seal, corner, x_corner = cut
        if not x_corner > land_start[0]:
            raise DesignError("lobe_width", "wide enough that the male keeps a tip land", lobe_width)
        rack += (
            RackPiece(rack_line(pair, land_start, (x_corner, h1)), "tip arc", "root arc"),
            RackPiece(corner, "sealing tip corner", "sealing root (male tip path)", kind=PieceRole.MALE_CORNER_PATH),
        )
    if rbs > 0.0:
        rack += (
            RackPiece(seal, "sealing flank", "sealing flank"),
            RackPiece(rack_arc(pair, cbr, rbs, np.pi + as_, 1.5 * np.pi), "sealing root fillet", "sealing tip rounding"),
            RackPiece(rack_line(pair, pts["br_bottom"], (p, -d1)), "root arc", "tip arc"),
        )
    else:  # sharp female tip: the sealing involute is used up to the female tip (Rinder sec. 3.2)
        pieces, x_foot = flank_to_female_tip(pair, seal, True, ("sealing flank", "sealing flank"), "sealing")
        if not x_foot < p:
            raise DesignError("lobe_width", "small enough that the female tip corner's path fits the rack period", lobe_width)
        rack += (*pieces, RackPiece(rack_line(pair, (x_foot, -d1), (p, -d1)), "root arc", "tip arc"))
    return ScrewRotors(pair, rack, "rack-involute")

"""Tip-corner defects that points cannot decide: a corner, or a rounding shorter than two point spacings.

Rinder (sec. 2.2.2): at a rotor's tip only a corner is possible as a flank, and its meshline is that
corner's path; its normal passes through the rotor's centre all along, a point-generated cusp
(:func:`rotorcad.meshing.defects.is_tip_corner`). A rounding at the tip generates a curve flank of the
mate instead, whose contact moves along the rounding. Points h apart (the median spacing of the given
points, :attr:`rotorcad.screw_rotors.ScrewRotors.point_spacing`) put at most two points on a rounding
shorter than 2h, and three points are the fewest that fix a circle: such a rounding and a corner are the
same input. The corner test of a given profile therefore decides nothing within h of the corner:

- a tip-corner cusp found from points is *undecided* (``decided`` false), its ``margin`` the radius of
  rotor profile about the corner (:func:`corner_margin`) within which the rotor's contacts generate the
  path's meshline (0 for a corner), its ``margin_accuracy`` h;
- where the meshline runs at least the resolution of the defect tests (:func:`rotorcad.meshing.defects.
  resolution`) with the rotor's contacts within h of one point on its tip (:func:`undecided_corners`) and
  no cusp was found there, the input cannot tell a corner's path either, and says so
  (``undecided_defects``).

The design's margin at the same corner is the same measure on its exact meshline: an undecided defect
matches the design's verdict either way only when the design's margin is within the accuracy too
(:func:`compare_defects`), so a rounding the points would resolve (longer than 2h) is not hidden.
"""

from __future__ import annotations

from collections import Counter
from dataclasses import dataclass

import numpy as np

from rotorcad.geometry import rotate
from rotorcad.meshing.meshline import MeshlinePiece
from rotorcad.roles import Side
from rotorcad.rotor_pair import RotorPair

CONCENTRATION = 1.25
"""How much more meshline a corner's contacts may generate within two point spacings of it than within one
(:func:`undecided_corners`). A corner's path, or a rounding shorter than two spacings, holds them within one
spacing: the lost tip corners of the symmetric and asymmetric SRMs from 80-150 points a lobe read 1.03-1.08.
A rounding the points resolve spreads them along itself: the N-rack male's 0.67 mm sealing tip rounding,
generated from its female's 300 and 600 points a lobe with 2 um, read 1.40-1.52, and the slow contacts at its
tip's middle (a slip singularity, the male's contact standing still as the meshline crosses O1O2) 1.5-2.4;
both were reported undecided before, the same rounding twice."""


@dataclass(frozen=True)
class _Contacts:
    """A rotor's contact points over the whole meshline.

    Its own frame (n, 2) mm, the meshline length each sample stands for (n,) mm, the fixed-frame
    points (n, 2) mm and the lobe part of each (n,).
    """

    own: np.ndarray
    weight: np.ndarray
    points: np.ndarray
    roles: np.ndarray


def _contacts(pieces: list[MeshlinePiece], pair: RotorPair, rotor: Side) -> _Contacts:
    """Return the rotor's contacts of every meshline sample, each weighted by half its two chords."""
    body = pair.mesh.male if rotor is Side.MALE else pair.mesh.female
    own, weight, points, roles = [], [], [], []
    for piece in pieces:
        if len(piece.points) < 2:
            continue
        half = 0.5 * piece.steps
        weight.append(np.concatenate([half, [0.0]]) + np.concatenate([[0.0], half]))
        own.append(body.to_body(piece.points, piece.t))
        points.append(piece.points)
        roles.append(piece.roles if len(piece.roles) == len(piece.points) else np.full(len(piece.points), None))
    if not own:
        return _Contacts(np.zeros((0, 2)), np.zeros(0), np.zeros((0, 2)), np.zeros(0, dtype=object))
    return _Contacts(np.vstack(own), np.concatenate(weight), np.vstack(points), np.concatenate(roles))


def _lobe_copies(corner: np.ndarray, pair: RotorPair, rotor: Side) -> np.ndarray:
    """Return the corner turned to each of the rotor's lobes about its centre, (z, 2) mm."""
    male = rotor is Side.MALE
    z = pair.male_teeth if male else pair.female_teeth
    centre = (0.0, 0.0) if male else (pair.center_distance, 0.0)
    return np.vstack([rotate(np.atleast_2d(corner), 2.0 * np.pi * k / z, centre) for k in range(z)])


def _distances(own: np.ndarray, corner: np.ndarray, pair: RotorPair, rotor: Side) -> np.ndarray:
    """Distance (mm) of each contact (n, 2) from the nearest of the corner's lobe copies, (n,)."""
    copies = _lobe_copies(corner, pair, rotor)
    return np.hypot(own[:, None, 0] - copies[None, :, 0], own[:, None, 1] - copies[None, :, 1]).min(axis=1)


def _strip_pairs(xs: np.ndarray, order: np.ndarray, cx: np.ndarray, half: float) -> tuple[np.ndarray, np.ndarray]:
    """Return the (row, contact) index pairs whose contact's x lies within ``half`` (mm) of the row's ``cx``.

    ``xs`` (n,) are the contacts' x sorted (``order`` their indices), ``cx`` (b,) the x of each row's point (mm).
    """
    lo = np.searchsorted(xs, cx - half, side="left")
    hi = np.searchsorted(xs, cx + half, side="right")
    counts = np.maximum(hi - lo, 0)
    rows = np.repeat(np.arange(len(cx)), counts)
    starts = np.cumsum(counts) - counts
    return rows, order[np.arange(len(rows)) - np.repeat(starts - lo, counts)]


def _masses(own: np.ndarray, weight: np.ndarray, corners: np.ndarray, pair: RotorPair, rotor: Side, spacing: float) -> np.ndarray:
    """Meshline length (mm) of the contacts (n, 2) within ``spacing`` of each corner (m, 2) or its lobe copies, (m,).

    Row i is ``weight[_distances(own, corners[i], pair, rotor) <= spacing].sum()``, the same numbers: each
    corner's copies turned as :func:`_lobe_copies` turns them, the same contacts counted and the same sum
    per row over them in their order. A contact is within ``spacing`` of a copy where its squared distance
    is below spacing^2 (1 - 1e-9) (the square's rounding, a few units of the last place, cannot take the
    distance past ``spacing``), beyond it above spacing^2 (1 + 1e-9); only between the two is the distance
    taken as :func:`_distances` takes it. Blocks of corners of at most a million contacts at once; of each copy only
    the contacts in the strip of x within that distance are measured (:func:`_strip_pairs`; every other one lies
    farther in x alone).
    """
    male = rotor is Side.MALE
    z = pair.male_teeth if male else pair.female_teeth
    centre = (0.0, 0.0) if male else (pair.center_distance, 0.0)
    copies = np.stack([rotate(corners, 2.0 * np.pi * k / z, centre) for k in range(z)], axis=1)  # (m, z, 2)
    out = np.empty(len(corners))
    square = spacing * spacing
    sure, unsure = (square * (1.0 - 1e-9) if square > 1e-250 else -1.0), square * (1.0 + 1e-9)
    block = max(1, 1_000_000 // max(1, len(own)))
    order = np.argsort(own[:, 0], kind="stable")  # the contacts by x: a copy's candidates lie in a strip about it
    xs = own[order, 0]
    half = np.sqrt(unsure) * (1.0 + 1e-6)  # beyond it in x, dx * dx alone exceeds spacing^2 (1 + 1e-9)
    for a in range(0, len(corners), block):
        c = copies[a : a + block]
        inside = np.zeros((len(c), len(own)), dtype=bool)
        border = np.zeros_like(inside)
        for k in range(z):
            rows, cols = _strip_pairs(xs, order, c[:, k, 0], half)
            dx, dy = own[cols, 0] - c[rows, k, 0], own[cols, 1] - c[rows, k, 1]
            d2 = dx * dx + dy * dy
            near = d2 <= sure
            inside[rows[near], cols[near]] = True
            near = d2 <= unsure
            border[rows[near], cols[near]] = True
        rows, cols = np.nonzero(border & ~inside)
        if len(rows):  # the distance itself, as _distances takes it
            d = np.hypot(own[cols, None, 0] - c[rows, :, 0], own[cols, None, 1] - c[rows, :, 1]).min(axis=1)
            inside[rows, cols] = d <= spacing
        out[a : a + block] = [weight[row].sum() for row in inside]
    return out


def corner_margin(pieces: list[MeshlinePiece], pair: RotorPair, rotor: Side, corner: np.ndarray, length: float) -> float:
    """Return the radius of rotor profile about a corner within which its contacts generate ``length`` of meshline.

    A corner's path (Rinder sec. 2.2.2) is generated by the corner alone: 0. A rounding of profile
    length L generates it within about L / 2; a flank that only passes the place, within several mm.

    Parameters
    ----------
    pieces : list of MeshlinePiece
        The meshline (:attr:`rotorcad.meshing.MeshingAnalysis.pieces`).
    pair : RotorPair
        The pair (the rotors' motions, lobe counts).
    rotor : Side
        The rotor whose corner it is.
    corner : (2,) float array, mm
        The corner, in the rotor's own frame (any lobe).
    length : float, mm
        The path's meshline length.

    Returns
    -------
    float, mm
        inf when the whole meshline is shorter than ``length``.
    """
    c = _contacts(pieces, pair, rotor)
    if len(c.own) == 0:
        return float("inf")
    d = _distances(c.own, np.asarray(corner, dtype=float), pair, rotor)
    order = np.argsort(d)
    total = np.cumsum(c.weight[order])
    k = int(np.searchsorted(total, length * (1.0 - 1e-9)))  # the sum's rounding: a length summed in another order
    return float(d[order][k]) if k < len(order) else float("inf")


def corner_on_rotor(pair: RotorPair, rotor: Side, x: float, y: float, t: float) -> np.ndarray:
    """Return the rotor's point touching at meshline point (x, y) at male rotation ``t`` (rad): its own frame, (2,) mm."""
    body = pair.mesh.male if rotor is Side.MALE else pair.mesh.female
    return body.to_body(np.array([[x, y]]), np.array([t]))[0]


def undecided_corners(
    pieces: list[MeshlinePiece],
    pair: RotorPair,
    rotor: Side,
    spacing: float,
    near_tip: float,
    reach: float,
    found: list[np.ndarray],
) -> list[dict[str, object]]:
    """Return the places on a rotor's tip where its contacts stand within a point spacing over a corner path's meshline.

    Rotor contacts within ``near_tip`` of its tip circle that generate at least ``reach`` (mm, the
    resolution of the defect tests) of meshline within ``spacing`` (h) of one point are, to points h apart,
    a corner's path or a rounding's (the module's note); the densest such point first, each taking the
    contacts within 2h of it. Corners already found (``found``, own frame) within 2h are left out.

    Parameters
    ----------
    pieces : list of MeshlinePiece
        The meshline.
    pair : RotorPair
        The pair.
    rotor : Side
        Whose tip.
    spacing, near_tip, reach : float, mm
        The point spacing h, how near the tip circle, and the least meshline length.
    found : list of (2,) float arrays, mm
        Corners of the rotor already reported (its own frame).

    Returns
    -------
    list of dict
        Per place: ``x``, ``y`` (mm, fixed frame, the middle contact's meshline point), ``corner`` (2,)
        (mm, own frame), ``extent`` (mm of meshline within h), ``role`` (the commonest lobe part there).
    """
    c = _contacts(pieces, pair, rotor)
    if len(c.own) == 0:
        return []
    male = rotor is Side.MALE
    centre = np.array([0.0 if male else pair.center_distance, 0.0])
    tip = pair.male_tip_radius if male else pair.female_tip_radius
    on = np.abs(np.hypot(*(c.own - centre).T) - tip) <= near_tip
    if not on.any():
        return []
    own, weight, points, roles = c.own[on], c.weight[on], c.points[on], c.roles[on]
    cand = np.arange(len(own))[:: max(1, len(own) // 300)]
    mass = _masses(own, weight, own[cand], pair, rotor, spacing)
    left = np.ones(len(cand), dtype=bool)
    out: list[dict[str, object]] = []
    for _ in range(4):  # a rotor has two tip corners a lobe; a few more places at most
        if not (left & (mass >= reach)).any():
            break
        i = int(np.argmax(np.where(left, mass, -1.0)))
        corner = own[cand[i]]
        left &= _distances(own[cand], corner, pair, rotor) > 2.0 * spacing
        if any(_distances(np.atleast_2d(f), corner, pair, rotor)[0] <= 2.0 * spacing for f in found):
            continue
        d_all = _distances(c.own, corner, pair, rotor)
        if c.weight[d_all <= 2.0 * spacing].sum() > CONCENTRATION * c.weight[d_all <= spacing].sum():
            continue  # its contacts spread beyond a spacing: a rounding the points resolve, or a slow contact
        near = np.flatnonzero(_distances(own, corner, pair, rotor) <= spacing)
        mid = near[len(near) // 2]
        sides = Counter(r for r in roles[near] if r is not None)
        flanks = Counter({r: n for r, n in sides.items() if str(r) in ("driving", "sealing")})
        common = (flanks or sides).most_common(1)  # a flank's corner, read off the flank beside it
        role = common[0][0] if common else None
        if any(str(u["role"]) == str(role) for u in out):
            continue  # one tip corner a lobe part: the densest place found first stands for it
        out.append(
            {
                "x": float(points[mid, 0]),
                "y": float(points[mid, 1]),
                "corner": corner,
                "extent": float(mass[i]),
                "role": role,
            }
        )
    return out


def _key(d: dict) -> tuple:
    return d["kind"], d["rotor"], d["flank_role"], d["tip_corner"]


def compare_defects(design: object, given: dict) -> tuple[list[tuple], list[tuple]]:
    """Compare a given profile's defects with its design's: the differing ones, and the undecided ones that explain a difference.

    Decided defects must be the design's by kind, rotor, lobe part and tip corner. A difference in one
    such key counts as explained only by the given's undecided defects of that key (in ``defects`` with
    ``decided`` false, or in ``undecided_defects``) without a corner (:func:`possible_rows`), or whose corner
    the design generates within their ``margin_accuracy`` too (:func:`corner_margin` on the design's meshline,
    over the defect's extent): the design's margin is also within that accuracy.

    Parameters
    ----------
    design : MeshingAnalysis
        The design's analysis (its exact curves).
    given : dict
        The given profile's summary (:meth:`rotorcad.meshing.MeshingAnalysis.summary`).

    Returns
    -------
    differing : list of tuple
        (key, count in the given minus the design's) of the keys not explained.
    explained : list of tuple
        (key, count difference, the design's margins mm, the accuracy mm) of the explained ones.
    """
    want = Counter(_key(d) for d in design.defect_dicts())
    got = Counter(_key(d) for d in given["defects"])
    loose = [d for d in given["defects"] if d.get("decided") is False] + list(given.get("undecided_defects", []))
    differing, explained = [], []
    pair = design.rotors.pair
    for k in sorted(set(want) | set(got), key=str):
        diff = got[k] - want[k]
        if diff == 0:
            continue
        mine = [d for d in loose if _key(d) == k]
        margins = [  # no corner: a defect the input can neither show nor rule out (possible_rows), 0
            0.0
            if d["corner"] is None
            else corner_margin(design.pieces, pair, Side(d["rotor"]), np.asarray(d["corner"]), d["extent"])
            for d in mine
        ]
        ok = [m for m, d in zip(margins, mine, strict=True) if d["margin_accuracy"] is None or m <= d["margin_accuracy"]]
        if len(ok) >= abs(diff):
            explained.append((k, diff, [round(m, 3) for m in ok], mine[0]["margin_accuracy"]))
        else:
            differing.append((k, diff, [round(m, 3) for m in margins]))
    return differing, explained


def mark_decided(row: dict, defect, pieces: list[MeshlinePiece], pair: RotorPair, spacing: float) -> dict:
    """Add ``decided``, ``margin``, ``margin_accuracy`` (and ``corner``) to a defect's row.

    A point-generated tip corner's path found from points ``spacing`` (mm) apart is undecided: the
    points cannot tell the corner from a rounding shorter than two spacings.

    Parameters
    ----------
    row : dict
        The defect's row (``tip_corner`` already set); changed in place.
    defect : rotorcad.meshing.defect_record.Defect
        The defect.
    pieces : list of MeshlinePiece
        The meshline's pieces.
    pair : RotorPair
        The pair.
    spacing : float
        The given points' spacing, mm; 0 for a design or a drawing (every defect decided).

    Returns
    -------
    dict
        ``row``.
    """
    row["decided"], row["margin"], row["margin_accuracy"] = True, None, None
    if spacing and row["tip_corner"] and defect.point_generated:  # a corner or a rounding below 2 spacings
        corner = corner_on_rotor(pair, defect.rotor, defect.x, defect.y, np.radians(defect.angle_deg))
        row["decided"], row["corner"], row["margin_accuracy"] = False, [float(v) for v in corner], spacing
        margin = corner_margin(pieces, pair, defect.rotor, corner, defect.extent)
        row["margin"] = margin if np.isfinite(margin) else None
    return row


def undecided_rows(
    pieces: list[MeshlinePiece], pair: RotorPair, spacing: float, near: float, reach: float, rows: list[dict]
) -> list[dict[str, object]]:
    """Return the tip corners given points can neither show nor rule out, as defect rows with ``decided`` false.

    Parameters
    ----------
    pieces : list of MeshlinePiece
        The meshline's pieces.
    pair : RotorPair
        The pair.
    spacing : float
        The given points' spacing, mm (> 0).
    near : float
        How near (mm) the contacts must stay to a point to be a corner's path.
    reach : float
        The meshline stretch (mm) they must stay there over (the defects' resolution).
    rows : list of dict
        The defects found (:func:`mark_decided` rows): a rotor with a tip-corner cusp found is skipped there.

    Returns
    -------
    list of dict
    """
    out = []
    for rotor in (Side.MALE, Side.FEMALE):
        found = [np.asarray(r["corner"]) for r in rows if r.get("corner") is not None and r["rotor"] == str(rotor)]
        for u in undecided_corners(pieces, pair, rotor, spacing, near, reach, found):
            corner = u["corner"]
            margin = corner_margin(pieces, pair, rotor, corner, u["extent"])
            out.append(
                {
                    "kind": "cusp",
                    "rotor": str(rotor),
                    "x": u["x"],
                    "y": u["y"],
                    "flank_role": None if u["role"] is None else str(u["role"]),
                    "point_generated": True,
                    "extent": u["extent"],
                    "tip_corner": True,
                    "decided": False,
                    "corner": [float(v) for v in corner],
                    "margin": margin if np.isfinite(margin) else None,
                    "margin_accuracy": spacing,
                }
            )
    return out


def possible_rows(defects: list) -> list[dict[str, object]]:
    """Return defects a given profile can neither show nor rule out as ``undecided_defects`` rows (no tip corner).

    The jamming of :func:`rotorcad.meshing.defects.meshline_defects`' ``below``: the male rotation turns back and on
    again by more than the tangent's tolerance alone allows (the design's test would call it jamming) and less than
    the profile's accuracy does (:func:`rotorcad.meshing.rotation_turns.rotation_turns`). A feature there below the
    input's accuracy (the rack-involute male's sealing flank dented by 20 um over 2 mm, as 300 points a lobe with
    2 um of scatter: the rotation turns back by 4.9 mrad where 10.0 are allowed) may jam or not: the flank is
    undecided there, not shown to run (:attr:`rotorcad.meshing.contact_ratios.FlankReport.running_decided`).

    Parameters
    ----------
    defects : list of rotorcad.meshing.defect_record.Defect
        The undecided defects, each at the first end of its excursion, ``extent`` the meshline to the other (mm).

    Returns
    -------
    list of dict
        The keys of :func:`undecided_rows`' rows; ``corner``, ``margin`` and ``margin_accuracy`` None.
    """
    return [
        {
            "kind": d.kind,
            "rotor": str(d.rotor),
            "x": d.x,
            "y": d.y,
            "flank_role": None if d.role is None else str(d.role),
            "point_generated": False,
            "extent": d.extent,
            "tip_corner": False,
            "decided": False,
            "corner": None,
            "margin": None,
            "margin_accuracy": None,
        }
        for d in defects
    ]

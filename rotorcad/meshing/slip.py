"""Slip and the points of infinite slip (Rinder eqs. 2-4, sec. 3.2), judged to the profile's accuracy.

A rotor's slip is v_g / v_t (eq. 4), v_t = omega N P its velocity along the common tangent (eq. 2,
N the foot of the perpendicular from its centre O on the contact normal). The slip is infinite
where v_t vanishes: where the contact normal, which passes through the pitch point C (the law of
gearing), is perpendicular to O P, that is where the meshline crosses the circle on O C as
diameter (Thales), away from C itself (pure rolling there). Of the contact P alone,

    v_t = omega (P - O) . (P - C) / |P - C|,

so a point of infinite slip is a property of the meshline's positions (:func:`tangential_lever`).

A profile given by points places its meshline to an accuracy (:data:`~rotorcad.meshing.defects.MESHLINE_GAIN`
times its own), and two of the design's points of infinite slip move with it
(:func:`slip_singularities`):

- a rotor's tip corner on its pitch circle (the SRM females', Krigar's and Lysholm's: no addendum)
  runs on the pitch circle, which touches the Thales circle at C: the design's v_t vanishes at C
  only. A fit places that corner a few micrometres off, and the zero moves to sqrt(2 r_w dr) from C
  (r_w the pitch radius, dr the corner's radial error): 0.1-3.8 mm for the samples' males given as
  points (16-95 µm), one spurious point of infinite slip on each such path. The corner's path is a
  circle about its rotor's centre; where the radii at which the given path runs reach the pitch
  radius (widened by the meshline's accuracy), the corner's circle is the pitch circle as far as the
  input tells, and its zero is C's;
- where the design's zero lies at a corner of the meshline (the rack-involute's female involute used
  to its base circle: the male tip corner's path hands over to the involute's line of action there,
  Rinder sec. 3.2 "nur in einem einzigen Punkt"), a fit through points rounds the corner, and the
  rounded meshline misses the zero by up to the resolution (0.15-0.2 mm from the female's points:
  v_t = 0.3 omega mm, no sign change). The corner is found from the branches either side
  (:func:`~rotorcad.meshing.meshline.turn_corner`, as for the blow-hole's apex) and v_t is judged there.
"""

from __future__ import annotations

import numpy as np

from rotorcad.meshing.meshline import SHARP_TURN, MeshlinePiece, turn_corner, with_neighbours
from rotorcad.roles import PieceRole
from rotorcad.rotor_pair import RotorPair

SLIP_ZERO = 1e-9  # a tangential velocity below this share of the rotor's largest one is zero to rounding
TIP_ROUNDING = 0.25
"""Share of a given profile's resolution within which a point of infinite slip of a rotor whose tip circle is
its pitch circle lies on that tip corner's path, rounded by the fit (:func:`slip_singularities`): where the fit
leaves a piece of that path as a curve piece (a male's points, 150-300 a lobe, exact or with 1-2 µm), its
contact sinks 0.14-0.23 mm (0.08-0.13 of the resolution) inside the tip circle, and the meshline there crosses
the Thales circle 4-18 deg from C: the narrow-tip, SRM-B, asymmetric and symmetric SRM and Lysholm males read
one point of infinite slip too many. The designs' own points lie 1.66 mm and more inside (the symmetric SRM's
female, 0.57 of the resolution at 300 points a lobe with 2 µm, 0.4 at 80 a lobe)."""


def slip(sliding: np.ndarray, tangential: np.ndarray) -> np.ndarray:
    """Return the slip v_g / v_t of a rotor at the contacts (Rinder eq. 4), infinite where v_t vanishes.

    v_t is judged zero relative to its own scale: at most :data:`SLIP_ZERO` times the rotor's largest
    tangential velocity (a zero of v_t on the meshline computes as 1e-15 m/s and would give a slip of
    1e15). Where v_g vanishes too (to the same share of its largest), the slip is nan: pure rolling.

    Parameters
    ----------
    sliding : (n,) float array, m/s
        The sliding velocity v_g.
    tangential : (n,) float array, m/s
        The rotor's velocity v_t along the common tangent.

    Returns
    -------
    (n,) float array
        The slip, +-inf where v_t is zero and v_g is not, nan where both are.
    """
    zero_t = np.abs(tangential) <= SLIP_ZERO * (np.abs(tangential).max(initial=0.0))
    zero_g = np.abs(sliding) <= SLIP_ZERO * (np.abs(sliding).max(initial=0.0))
    with np.errstate(divide="ignore", invalid="ignore"):
        ratio = sliding / np.where(zero_t, 1.0, tangential)
    return np.where(zero_t, np.where(zero_g, np.nan, np.copysign(np.inf, sliding)), ratio)


def tangential_lever(points: np.ndarray, centre: np.ndarray, pitch_point: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Return v_t / omega of a rotor at contacts, from their positions alone, and its sensitivity to them.

    Rinder eq. 2: v_t = omega N P, N the foot of the perpendicular from the rotor's centre O on the
    contact normal; the normal passes through C, so N P = (P - O) . u with u = (P - C) / |P - C|.

    Parameters
    ----------
    points : (n, 2) float array, mm
        Contacts P, fixed frame (none at C).
    centre, pitch_point : (2,) float array, mm
        The rotor's centre O and the pitch point C.

    Returns
    -------
    lever : (n,) float array, mm
        (P - O) . u.
    gain : (n,) float array
        |grad lever| where the lever vanishes, sqrt(1 + |P - O|^2 / |P - C|^2): how many mm the lever
        moves per mm that P moves.
    """
    to_c = points - pitch_point
    dist = np.hypot(to_c[:, 0], to_c[:, 1])
    arm = points - centre
    with np.errstate(divide="ignore", invalid="ignore"):  # a contact at C: nan, no zero of its own
        lever = (arm[:, 0] * to_c[:, 0] + arm[:, 1] * to_c[:, 1]) / dist
        return lever, np.sqrt(1.0 + (arm[:, 0] ** 2 + arm[:, 1] ** 2) / dist**2)


def on_pitch_circle(piece: MeshlinePiece, pair: RotorPair, band: float) -> bool:
    """Return True where ``piece`` is a tip corner's path and that corner runs on its rotor's pitch circle.

    A corner's path is a circle about its rotor's centre; a given profile's path strays from one
    (its corner placed only so well). Where the pitch radius r_w lies within the radii the path runs
    at, widened by ``band`` (mm, the meshline's accuracy), the corner's circle cannot be told from the
    pitch circle. That circle touches both Thales circles (on O1 C and on O2 C as diameters) at C and
    meets neither elsewhere (each lies on its own side of the tangent there, the pitch circle inside
    or outside it): on it both rotors' v_t vanish at C only.
    """
    if piece.kind is PieceRole.MALE_CORNER_PATH:
        centre, pitch = np.zeros(2), pair.male_pitch_radius
    elif piece.kind is PieceRole.FEMALE_CORNER_PATH:
        centre, pitch = np.array([pair.center_distance, 0.0]), pair.center_distance - pair.male_pitch_radius
    else:
        return False
    radii = np.hypot(piece.points[:, 0] - centre[0], piece.points[:, 1] - centre[1])
    return bool(radii.min() - band <= pitch <= radii.max() + band)


def _corner_zero(
    run: tuple[np.ndarray, np.ndarray, int],
    i: int,
    centre: np.ndarray,
    c: np.ndarray,
    reach: float,
    circles: tuple,
    accuracy: float,
    turns: dict | None = None,
) -> tuple[np.ndarray, float] | None:
    """Return the corner of a meshline turn at sample ``i`` of a piece where the rotor's v_t vanishes, and its lever.

    ``run`` is the piece's samples joined with its neighbours (:func:`with_neighbours`), their arc
    length and the index of the piece's first sample in them (one per piece, for all its samples).

    The rounded turn's sample has a lever ``l`` (:func:`tangential_lever`); the corner
    (:func:`turn_corner`, from the branches either side) has ``l_c``. v_t vanishes at the corner
    where the two have opposite signs (the rounding cut across the zero) or ``l_c`` lies within what
    the corner's placing moves it (``reach`` / 10, how near the extended branches must pass each other).
    ``turns``, if given, keeps :func:`turn_corner`'s answers for this run by the sample's arc length and point
    (all it reads of the sample), for the other rotor's judgement and for samples that repeat a point.
    """
    points, arclen, first = run
    at = first + i
    key = (float(arclen[at]), points[at].tobytes())  # what turn_corner reads of the sample (the run's arc length, the point)
    corner = turns.get(key, False) if turns is not None else False
    if corner is False:
        corner = turn_corner(points, arclen, at, reach, circles, accuracy)
        if turns is not None:
            turns[key] = corner
    if corner is None or np.hypot(*(corner - c)) <= 0:
        return None
    (lever, gain), (mine, _) = tangential_lever(corner[None], centre, c), tangential_lever(points[at][None], centre, c)
    if lever[0] * mine[0] <= 0 or abs(lever[0]) <= gain[0] * 0.1 * reach:
        return corner, float(lever[0])
    return None


def _may_turn_sharply(run: tuple[np.ndarray, np.ndarray, int], samples: np.ndarray, reach: float) -> np.ndarray:
    """Return False at the samples of a piece where :func:`turn_corner` surely finds no corner, (k,) bool.

    :func:`turn_corner`'s first tests, for all the samples at once: it finds none where the chords from
    ``reach`` (mm) behind to the sample and from it to ``reach`` ahead turn by no more than
    :data:`SHARP_TURN` or one of them has no length, or where fewer than six samples lie from 2 to 8
    ``reach`` before or after the sample. The angle is taken here as ``atan2(cross, dot)`` of the chords,
    a few units of the last place from :func:`turn_corner`'s own, so a sample within a millionth of the
    limit is kept and judged there; the counts are those of its masks (the arc length rises), and with a
    nan among the arc lengths every sample is kept. A measured profile's meshline has some thousand
    local least |v_t|, of which few lie at a corner.
    """
    points, arclen, first = run
    if not np.isfinite(arclen).all():
        return np.ones(len(samples), dtype=bool)
    at = first + samples
    s0 = arclen[at]
    back = points[np.searchsorted(arclen, s0 - reach)]
    ahead = points[np.minimum(np.searchsorted(arclen, s0 + reach), len(points) - 1)]
    behind, onward = points[at] - back, ahead - points[at]
    short = np.minimum(np.hypot(behind[:, 0], behind[:, 1]), np.hypot(onward[:, 0], onward[:, 1])) <= 0
    turn = np.abs(
        np.arctan2(
            behind[:, 0] * onward[:, 1] - behind[:, 1] * onward[:, 0], behind[:, 0] * onward[:, 0] + behind[:, 1] * onward[:, 1]
        )
    )
    before = np.searchsorted(arclen, s0 - 2 * reach, side="right") - np.searchsorted(arclen, s0 - 8 * reach, side="left")
    after = np.searchsorted(arclen, s0 + 8 * reach, side="right") - np.searchsorted(arclen, s0 + 2 * reach, side="left")
    return ~(short | (turn <= SHARP_TURN * (1.0 - 1e-6)) | (before < 6) | (after < 6))


def slip_singularities(
    pieces: list[MeshlinePiece],
    tangential: dict[str, np.ndarray],
    pair: RotorPair,
    band: float = 0.0,
    reach: float = 0.0,
    accuracy: float = 0.0,
) -> list[dict[str, object]]:
    """Return the points of infinite slip: where a rotor's tangential velocity vanishes (Rinder eq. 4, sec. 3.2).

    Rinder: "nur in einem einzigen Punkt unendliche Schlupfwerte ... daß die Evolventenflanke bis
    zum Grundkreis benutzt wurde". Found on each meshline piece where v1t (male slip infinite) or v2t
    (female slip infinite) changes sign between neighbouring contacts (located by linear
    interpolation), or, at a piece's end, falls below 1 % of the rotor's largest tangential velocity
    while falling towards that end (a zero where the piece leaves a bore: the sampled meshline stops
    within one step of it). The pitch point C is left out (both velocities vanish there with the
    sliding: pure rolling, not infinite slip), and so is a zero on a tip corner's path where that
    corner runs on its pitch circle within ``band`` (:func:`on_pitch_circle`), and of a given profile a
    zero of such a rotor within :data:`TIP_ROUNDING` of the resolution inside its tip circle (the fit's
    rounding of that corner). Of a given
    profile (``reach`` > 0), a local least |v_t| within what the resolution moves it
    (:func:`tangential_lever`) where the meshline turns sharply is judged at the turn's corner
    (:func:`_corner_zero`). Points closer than 1 % of the centre distance are one.

    Parameters
    ----------
    pieces : list of MeshlinePiece
        The meshline.
    tangential : dict
        ``"male"`` and ``"female"``: v1t and v2t at every contact, pieces after each other, (n,) float, m/s.
    pair : RotorPair
        The pair.
    band : float, mm
        The meshline's accuracy (:data:`~rotorcad.meshing.defects.MESHLINE_GAIN` times a given
        profile's); 0 for a design.
    reach : float, mm
        A given profile's resolution (:func:`~rotorcad.meshing.defects.resolution`); 0 for a design.
    accuracy : float, mm
        A given profile's accuracy.

    Returns
    -------
    list of dict
        ``rotor``, ``x``, ``y`` (mm), ``t`` (male rotation, rad), ``flank`` (lobe part, text),
        ``male_radius``, ``female_radius`` (mm).
    """
    a = pair.center_distance
    c = np.array([pair.male_pitch_radius, 0.0])
    centres = {"male": np.zeros(2), "female": np.array([a, 0.0])}
    circles = ((centres["male"], pair.male_tip_radius), (centres["female"], pair.female_tip_radius))
    found: list[dict[str, object]] = []

    pitch = {"male": pair.male_pitch_radius, "female": a - pair.male_pitch_radius}
    tips = {"male": pair.male_tip_radius, "female": pair.female_tip_radius}

    def add(rotor: str, p: np.ndarray, t: float, role: object) -> None:
        if np.hypot(*(p - c)) < 1e-3 * a:
            return  # the pitch point: pure rolling
        if (
            reach > 0
            and abs(tips[rotor] - pitch[rotor]) <= band
            and tips[rotor] - np.hypot(*(p - centres[rotor])) <= TIP_ROUNDING * reach
        ):
            return  # the fit's rounding of a tip corner on the pitch circle: its zero is C's (on_pitch_circle)
        if any(f["rotor"] == rotor and np.hypot(f["x"] - p[0], f["y"] - p[1]) < 1e-2 * a for f in found):
            return
        found.append(
            {
                "rotor": rotor,
                "x": float(p[0]),
                "y": float(p[1]),
                "t": float(t),
                "flank": str(role),
                "male_radius": float(np.hypot(*p)),
                "female_radius": float(np.hypot(p[0] - a, p[1])),
            }
        )

    def joined(j: int) -> tuple[np.ndarray, np.ndarray, int]:
        run, first = with_neighbours(pieces, j, 0, reach)
        return run, np.concatenate([[0.0], np.cumsum(np.hypot(*np.diff(run, axis=0).T))]), first

    start = 0
    turns: dict[int, dict] = {}  # per piece, its turns' corners by sample (_corner_zero): both rotors judge the same samples
    for j, piece in enumerate(pieces):
        n = len(piece.t)
        run = None  # piece j with its neighbours, joined once for all its samples
        sl = slice(start, start + n)
        start += n
        if on_pitch_circle(piece, pair, band if band > 0 else 1e-9 * a):
            continue  # both v_t vanish at C only
        for rotor in ("male", "female"):
            v = tangential[rotor][sl]
            mag = np.abs(v)
            big = float(np.abs(tangential[rotor]).max()) if len(tangential[rotor]) else 0.0
            ends = [i for i, k in ((0, 1), (n - 1, n - 2)) if n > 1 and mag[i] <= 1e-2 * big and mag[i] < mag[k]]
            cross_ = np.nonzero(v[:-1] * v[1:] < 0)[0]
            hits = [(i, 0.0) for i in ends] + [(int(i), float(v[i] / (v[i] - v[i + 1]))) for i in cross_]
            for i, w in hits:
                k = min(i + 1, n - 1)
                add(
                    rotor,
                    piece.points[i] + w * (piece.points[k] - piece.points[i]),
                    piece.t[i] + w * (piece.t[k] - piece.t[i]),
                    piece.roles[i],
                )
            if reach <= 0 or n < 3:
                continue
            lever, gain = tangential_lever(piece.points, centres[rotor], c)
            least = np.flatnonzero((mag[1:-1] <= mag[:-2]) & (mag[1:-1] <= mag[2:])) + 1
            least = least[np.abs(lever[least]) <= gain[least] * reach]
            if len(least) == 0:
                continue
            run = joined(j) if run is None else run
            for i in least[_may_turn_sharply(run, least, reach)]:
                zero = _corner_zero(run, int(i), centres[rotor], c, reach, circles, accuracy, turns.setdefault(j, {}))
                if zero is not None:
                    add(rotor, zero[0], piece.t[i], piece.roles[i])
    return found

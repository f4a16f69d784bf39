"""Which end face a transverse section is seen from, and whether measured points are the design's mirror image.

rotorcad's convention (CONTRACT.md, "Points files"): a rotor's transverse section is seen from the
suction end face. Seen from there the male turns counter-clockwise and the female clockwise; with
a male tip on +x and a female groove facing it (its root on -x of the female's own frame), the
driving flanks (Triebflanken, Rinder sec. 1.2) of both rotors lie at y < 0, below the line of
centres O1O2, and the sealing flanks (Dichtflanken) at y > 0.

A coordinate measuring machine that scans the section from the discharge end face sees its mirror
image: the same rotor read as seen from the suction end is another rotor, the mirror image, whose
driving flank is the design's sealing flank. The mirror image's meshing analysis is right for that
other rotor and swaps the per-flank verdicts of the measured one, with nothing in the numbers to
say so (the blow-hole, the flute areas and the lobe counts of a rotor and its mirror image are
equal). :func:`seen_from_suction` mirrors such points (y -> -y, the mirror about O1O2, which keeps
both centres) before anything else reads them; :func:`design_deviation` tells, when a design is
given beside the points, whether the points or their mirror image lie on the design's outline.
"""

from __future__ import annotations

import numpy as np

from rotorcad.curves import Arc, Curve, Line, Mapped, Spline
from rotorcad.geometry import polyline_distance, rotate
from rotorcad.roles import EndFace, Side

MIRROR_FIT = 0.01
"""mm: points whose RMS distance from the design's outline (after the best turn) is below this, or
below three times their stated accuracy, lie on it; the mirror image is noted only when the points
lie farther off than this."""

MIRROR_RATIO = 4.0
"""The mirror image must lie this many times closer to the design's outline than the points as
read to be noted: an asymmetric profile's mirror image lies 0.23-3.5 mm RMS off the design's on the
samples, a symmetric profile's is the profile itself and is never noted, and another rotor (N6: the
wrong sample's points) lies about as far off either way. Not an absolute fit: a measured rotor lies
off its design by its making and its designed clearance (the asymmetric SRM's female thinned by 10
and 30 µm on its flanks: 17 µm RMS), and so does its mirror image."""

_SAMPLE = 160  # points of the outline measured for its RMS distance (spread evenly along it)
_STEP = np.radians(1.0)  # rad: the coarse search of the best turn over one lobe pitch


def _mirrored_curve(curve: Curve) -> Curve:
    """``curve`` under y -> -y, travelled the same way (its parameter keeps its meaning)."""
    if isinstance(curve, Line):
        return Line((curve.a[0], -curve.a[1]), (curve.b[0], -curve.b[1]))
    if isinstance(curve, Arc):  # s is the polar angle about the centre: it changes sign
        return Arc((curve.center[0], -curve.center[1]), curve.radius, -curve.s0, -curve.s1)
    if isinstance(curve, Spline):
        t, (cx, cy), k = curve.knots[0], curve.knots[1], curve.knots[2]
        return Spline(knots=(t, (cx, -np.asarray(cy)), k), s0=curve.s0, s1=curve.s1, periodic=curve.periodic)
    return Mapped(curve, ((1.0, 0.0), (0.0, -1.0)))


def mirrored(profile: np.ndarray | list[Curve]) -> np.ndarray | list[Curve]:
    """Return a rotor's profile mirrored about the x axis (y -> -y), in reverse order.

    The mirror about the line of centres O1O2 (the x axis of the pair's frame, through both
    centres); the order is reversed so that an outline that ran counter-clockwise still does.

    Parameters
    ----------
    profile : (n, 2) float array, mm, or list of Curve
        Points of a CSV file, or the exact curves of a drawing, chained end to end.

    Returns
    -------
    (n, 2) float array, mm, or list of Curve
        The mirror image, of the same kind (a points file's points keep their line numbers).
    """
    if isinstance(profile, np.ndarray):
        flipped = (np.asarray(profile, dtype=float) * np.array([1.0, -1.0]))[::-1].copy()
        lines = getattr(profile, "lines", None)  # a points file's line numbers stay with their points
        return type(profile).of(flipped, lines[::-1]) if lines is not None else flipped
    return [_mirrored_curve(c).reversed() for c in reversed(profile)]


def seen_from_suction(profile: np.ndarray | list[Curve], seen_from: EndFace) -> np.ndarray | list[Curve]:
    """Return a section as seen from the suction end face, rotorcad's convention.

    Parameters
    ----------
    profile : (n, 2) float array, mm, or list of Curve
        The section as measured or drawn.
    seen_from : EndFace
        The end face it was seen from.

    Returns
    -------
    (n, 2) float array, mm, or list of Curve
        ``profile`` itself when seen from the suction end, else its mirror image (:func:`mirrored`).
    """
    return profile if EndFace(seen_from) is EndFace.SUCTION else mirrored(profile)


def section_points(profile: np.ndarray | list[Curve], rotor: Side, teeth: int, center_distance: float, label: str) -> np.ndarray:
    """Return the points of a rotor's section as rotorcad reads them, in the rotor's own frame.

    A female drawn at its place in the pair is moved into its own frame
    (:func:`rotorcad.measured.drawing.own_frame`, its note said by the build); a drawing that
    approximates the outline gives the points it was drawn through, exact curves their samples at
    1 µm chord (:func:`rotorcad.measured.drawing.as_given`).

    Parameters
    ----------
    profile : (n, 2) float array, mm, or list of Curve
        The section as given (after ``--seen-from``).
    rotor : Side
        Which rotor it is.
    teeth : int
        Its lobe count.
    center_distance : float, mm
        The pair's centre distance a.
    label : str
        The option that gave it.

    Returns
    -------
    (n, 2) float array, mm
    """
    import warnings

    from rotorcad.errors import InputNote
    from rotorcad.measured.drawing import as_given, own_frame, profile_points

    with warnings.catch_warnings():  # said once, by the build
        warnings.simplefilter("ignore", InputNote)
        return profile_points(as_given(own_frame(profile, rotor, center_distance, label), teeth), 1e-3)


def _rms_after_best_turn(points: np.ndarray, closed: np.ndarray, teeth: int) -> float:
    """RMS distance (mm) of ``points`` from the closed polyline ``closed`` after the best turn about the origin.

    The turn is searched over one lobe pitch on a grid of 1 deg with every fourth point, and then by
    a bounded one-dimensional minimisation (Brent's method, scipy) with all of them around the best
    grid angle; the distance is exact to the polyline's segments
    (:func:`rotorcad.geometry.distance_to_polyline`).
    """
    from scipy.optimize import minimize_scalar

    distance = polyline_distance(closed)  # distance_to_polyline's numbers, the outline's R-tree built once

    def rms(angle: float, pts: np.ndarray = points) -> float:
        return float(np.sqrt(np.mean(distance(rotate(pts, angle)) ** 2)))

    grid = np.arange(0.0, 2.0 * np.pi / teeth, _STEP)
    coarse = points[::4]
    best = float(grid[int(np.argmin([rms(t, coarse) for t in grid]))])
    found = minimize_scalar(rms, bounds=(best - _STEP, best + _STEP), method="bounded", options={"xatol": 1e-7})
    return float(min(found.fun, rms(best)))


def design_deviation(points: np.ndarray, outline: np.ndarray, teeth: int) -> tuple[float, float]:
    """Return how far a rotor's points, and their mirror image, lie from the design's outline.

    Each is the RMS distance of the points from the outline after the turn about the rotor's centre
    that makes it least (a CMM's angular datum is arbitrary), over 160 of the points spread evenly
    along them.

    Parameters
    ----------
    points : (n, 2) float array, mm
        The rotor's points (or its fitted outline), own frame, any part of the outline.
    outline : (m, 2) float array, mm
        The design's whole outline of the same rotor, own frame, closed (no repeated end point).
    teeth : int
        The rotor's lobe count (the outline repeats over 360/teeth deg).

    Returns
    -------
    as_read : float, mm
        The points' RMS distance.
    mirrored : float, mm
        Their mirror image's (y -> -y).
    """
    pts = np.asarray(points, dtype=float)
    pts = pts[np.linspace(0, len(pts), min(_SAMPLE, len(pts)), endpoint=False).astype(int)]
    closed = np.vstack([outline, outline[:1]])
    return _rms_after_best_turn(pts, closed, teeth), _rms_after_best_turn(pts * np.array([1.0, -1.0]), closed, teeth)


def mirror_note(as_read: float, mirror: float, accuracy: float, seen_from: EndFace, option: str) -> str | None:
    """Return the note for points whose mirror image, not they, lies on the design's outline; else None.

    Parameters
    ----------
    as_read, mirror : float, mm
        :func:`design_deviation` of the points as read (after ``--seen-from``) and of their mirror image.
    accuracy : float, mm
        The points' stated accuracy.
    seen_from : EndFace
        The end face the section was read as seen from.
    option : str
        The points' option (``--male-points``).

    Returns
    -------
    str or None
        The note, naming ``--seen-from`` with the other end face; None when the points lie on the
        design's outline, or when their mirror image lies not :data:`MIRROR_RATIO` times nearer (a
        symmetric profile, another rotor).
    """
    limit = max(MIRROR_FIT, 3.0 * accuracy)
    if not (as_read > limit and MIRROR_RATIO * mirror < as_read):
        return None
    other = EndFace.DISCHARGE if EndFace(seen_from) is EndFace.SUCTION else EndFace.SUCTION
    return (
        f"the {option} section lies {1e3 * as_read:.0f} µm RMS from the design's outline and its mirror image "
        f"{1e3 * mirror:.2g} µm: seen from the {other} end face? Its driving and sealing flanks read "
        f"swapped; give --seen-from {other} (read now as seen from the {seen_from} end)"
    )


__all__ = ["MIRROR_FIT", "MIRROR_RATIO", "design_deviation", "mirror_note", "mirrored", "section_points", "seen_from_suction"]

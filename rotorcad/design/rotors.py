"""A rotor pair from a design, and its analysis as plain numbers.

The core that the CLI, a design sweep and a notebook share. The design is a mapping as a TOML
file holds it (tables ``pair``, ``profile``, ``housing``, ``operating``, ...; CONTRACT.md "Design
files"), checked by :func:`rotorcad.design.schema.rotor_design`; values given beside it (the
command's options) override it (:func:`merge_pair`). A profile given by points arrives already
read (the caller reads points files and drawings): an ``(n, 2)`` array or the curves of a drawing.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np

from rotorcad.design.labels import PAIR_FIELDS
from rotorcad.design.schema import POINT_FAMILIES, rotor_design
from rotorcad.errors import DesignError, GeometryError, MissingValueError
from rotorcad.measured.outline import as_given, own_frame, read_outline
from rotorcad.meshing import MeshingAnalysis, largest_scatter, resolution
from rotorcad.profile import DEFAULT_TOLERANCE
from rotorcad.roles import Side
from rotorcad.rotor_families import build_family
from rotorcad.rotor_pair import RotorPair
from rotorcad.rotor_points import pair_from_rack_points, pair_from_rotor_points
from rotorcad.screw_rotors import ScrewRotors

PAIR_DEFAULTS = {"lead": 300.0, "length": 190.0}
SPEED_DEFAULT = 3000.0  # rpm


@dataclass(frozen=True)
class PairSpec:
    """What builds a rotor pair: dimensions, the profile family and its parameters or points.

    Attributes
    ----------
    pair : RotorPair
    family : str
        A family name (``rotorcad.rotor_families``) or ``rack-points`` / ``male-points`` /
        ``female-points``.
    params : dict
        The family's parameters (empty for points).
    points : (n, 2) float array or list of curves, optional
        The profile of a points family, already read.
    smoothing : float, optional, mm^2
        Spline smoothing of measured points (None: estimated from their scatter).
    speed_rpm : float
        Male speed for sliding velocities.
    radial_clearance : float, mm
        Housing bores = tip radii + this.
    """

    pair: RotorPair
    family: str
    params: dict[str, float]
    points: Any = None
    smoothing: float | None = None
    speed_rpm: float = SPEED_DEFAULT
    radial_clearance: float = 0.0


def pair_spec(settings: dict[str, Any], points: Any = None, overrides: dict[str, Any] | None = None) -> PairSpec:
    """Make the spec of a checked design (:func:`rotorcad.design.rotor_design`).

    Parameters
    ----------
    settings : dict
        The checked design.
    points : (n, 2) float array or list of Curve, optional
        The profile of a points family, read by the caller from ``settings["points"]`` (mm).
    overrides : dict, optional
        Pair dimensions that replace the design's (``male_teeth``, ..., ``lead``, ``length``);
        None values are ignored.

    Returns
    -------
    PairSpec
        Lead and length default to 300 mm and 190 mm, the speed to 3000 rpm.

    Raises
    ------
    DesignError
        An incomplete [pair], a pair that cannot be made (:class:`RotorPair`), a speed that is
        not positive, or a points family whose ``points`` were not given.
    """
    if settings["family"] in POINT_FAMILIES and points is None:
        raise DesignError(
            "[profile] points",
            f"read by the caller and passed as the points argument for the {settings['family']} family (the file names it)",
            None,
        )
    values = dict(PAIR_DEFAULTS)
    values.update(settings["pair"])
    values.update({k: v for k, v in (overrides or {}).items() if v is not None})
    try:
        pair = RotorPair(**values)
    except TypeError as exc:
        raise DesignError("[pair]", "complete (teeth, centre distance, tip and root radii)", None, str(exc)) from None
    speed = float(settings["operating"].get("speed_rpm", SPEED_DEFAULT))
    if not (np.isfinite(speed) and speed > 0):
        raise DesignError("[operating] speed_rpm", "a positive speed in rpm", speed)
    return PairSpec(
        pair=pair,
        family=settings["family"],
        params=dict(settings["params"]),
        points=points,
        smoothing=settings.get("smoothing"),
        speed_rpm=speed,
        radial_clearance=float(settings["housing"].get("radial_clearance", 0.0)),
    )


def merge_pair(settings: dict[str, Any] | None, given: dict[str, Any], source: str | None = None) -> PairSpec:
    """Merge a checked design with the values given beside it: given values override the design's.

    Parameters
    ----------
    settings : dict or None
        The checked design (:func:`rotorcad.design.schema.rotor_design`), or None.
    given : dict
        Values by library name (None: not given): the pair's dimensions
        (:data:`rotorcad.design.labels.PAIR_FIELDS`, mm), ``speed_rpm`` and ``smoothing`` (mm^2).
    source : str, optional
        A points family whose points are given beside the design (``male-points``, ...): it
        replaces the design's profile.

    Returns
    -------
    PairSpec
        Without its points (``points`` None): the caller reads the points file (the design's
        ``settings["points"]`` or the one given) and puts them in (:func:`dataclasses.replace`).
        Lead and length default to 300 mm and 190 mm, the speed to 3000 rpm.

    Raises
    ------
    DesignError
        A negative smoothing, a speed that is not positive, or a pair that cannot be made
        (:class:`RotorPair`), naming the library's parameter (``smoothing``, ``speed_rpm``, a
        field of the pair: :class:`rotorcad.design.labels.PairNames` says how the user gave it).
    MissingValueError
        A dimension of the pair given by neither.
    TypeError
        A pair described incompletely in another way.
    """
    values: dict[str, Any] = dict(PAIR_DEFAULTS)
    family, params, smoothing, speed, clearance = None, {}, given.get("smoothing"), SPEED_DEFAULT, 0.0
    if settings is not None:
        values.update(settings["pair"])
        family, params = settings["family"], settings["params"]
        smoothing = settings["smoothing"] if smoothing is None else smoothing  # the given value wins, as every other
        speed = float(settings["operating"].get("speed_rpm", speed))
        clearance = float(settings["housing"].get("radial_clearance", 0.0))
    values.update({k: given[k] for k in PAIR_FIELDS if given.get(k) is not None})
    if source is not None:
        family, params = source, {}
    if given.get("speed_rpm") is not None:
        speed = given["speed_rpm"]
    if smoothing is not None and not (np.isfinite(smoothing) and smoothing >= 0):
        raise DesignError("smoothing", "a number of at least 0 mm^2", smoothing)
    if not (np.isfinite(speed) and speed > 0):
        raise DesignError("speed_rpm", "a positive speed in rpm", speed)
    missing = [k for k in PAIR_FIELDS if k not in values]
    if missing:
        raise MissingValueError(missing[0])
    pair = RotorPair(**values)
    return PairSpec(pair, family, dict(params), None, smoothing, float(speed), clearance)


def build_pair(spec: PairSpec, label: str | None = None) -> ScrewRotors:
    """Build the rotor pair of a spec: a family from its rack, or the pair from points.

    Parameters
    ----------
    spec : PairSpec
        What to build.
    label : str, optional
        How the points are named in a refusal (e.g. ``--male-points``).

    Returns
    -------
    ScrewRotors
        The generated pair.

    Raises
    ------
    DesignError
        Bad family parameters or points, or a mate generated from measured points that is not a
        smooth rotor (noise left in by the smoothing).
    """
    if spec.family == "rack-points":
        return pair_from_rack_points(spec.pair, spec.points, spec.smoothing)
    if spec.family in ("male-points", "female-points"):
        measured = Side(spec.family.split("-")[0])  # the design's text read once: "male-points" -> Side.MALE
        radii = (spec.pair.female_root_radius, spec.pair.female_tip_radius)
        points = own_frame(spec.points, measured, spec.pair.center_distance, label or f"[profile] points ({spec.family})", radii)
        _note_unused_smoothing(spec, points, measured, label)
        _note_radii_off(spec.pair, points, measured, label or f"[profile] points ({spec.family})")
        if spec.smoothing is None:  # the fit follows the estimated scatter: refuse one no verdict can be judged to
            points = _judgeable(spec.pair, points, measured, label or f"[profile] points ({spec.family})")
        else:
            points = _refuse_scatter_followed(spec, points, measured, label)
        rotors = pair_from_rotor_points(spec.pair, points, measured, spec.smoothing, label=label)
        _check_generated(rotors, measured, label or f"[profile] points ({spec.family})")
        return rotors
    return build_family(spec.pair, spec.family, spec.params)


def _refuse_scatter_followed(spec: PairSpec, points: Any, rotor: Side, label: str | None) -> Any:
    """Refuse a given smoothing that lets the fit follow the points' scatter; return the outline read.

    scipy's smoothing s bounds the sum of squared residuals of each piece, so a piece of n points
    leaves them by sqrt(s / n) RMS at most; below the estimated scatter sigma over a lobe's n points
    (s < n sigma^2, the smoothing taken when none is given) the fit follows the scatter, its tangents
    are the scatter's, and a tip corner's path is lost or made up with the blow-hole and the
    verdicts. Measured with 1 µm of scatter at 300 points a lobe (n sigma^2 = 3e-4 mm²): the
    narrow-tip male read its blow-hole 0.000 ± 0.16 mm² at 0 and 1e-5 (design 2.778); from the
    female's points at 0 the symmetric SRM lost its female driving tip corner's cusp (blow-hole 0.53
    for 70.7 mm²) and the rack-involute its root slipping, and at 8e-5 and 1.5e-4 the N rack's male
    read a sealing tip corner it has not (none at 3e-4 and above). Such a smoothing is refused,
    naming ``--smoothing`` and the least that works; exact points (no scatter estimated) take any.
    """
    if isinstance(points, list):
        return points
    teeth = rotor.pick(spec.pair.male_teeth, spec.pair.female_teeth)
    outline = read_outline(points, teeth, label or f"[profile] points ({spec.family})")
    if outline.whole is None or outline.sigma <= 0:
        return outline
    per_lobe = len(outline.whole) / teeth
    least = per_lobe * outline.sigma**2
    if spec.smoothing < least:  # below the fit through the scatter: judged as without one
        _refuse_scatter(spec.pair, outline, rotor, label or f"[profile] points ({spec.family})")
        step = 10.0 ** (np.floor(np.log10(least)) - 1)  # the least named to two digits, rounded up: it is taken
        raise DesignError(
            "smoothing",
            f"at least {np.ceil(least / step) * step:.2g} mm^2 for {label or 'these points'}, or not given (then it is that)",
            spec.smoothing,
            f"n sigma^2 over a lobe's {per_lobe:.0f} points at their estimated scatter of {outline.sigma * 1e3:.2g} um; "
            "a smaller one lets the fit follow the scatter, and the tip corners' paths, the blow-hole and the "
            "verdicts would be the noise's",
        )
    return outline


def _note_unused_smoothing(spec: PairSpec, points: Any, rotor: Side, label: str | None) -> None:
    """Say that a smoothing given for a drawing read as its exact curves is not used (an InputNote).

    Smoothing fits points (:mod:`rotorcad.measured.fit`); a drawing whose curves are the outline's own
    (:func:`rotorcad.measured.outline.as_given`: export's splines, lines and arcs meeting smoothly or at
    corners) is used as drawn, so ``--smoothing`` changes nothing there, and the user is told so.
    """
    if spec.smoothing is None or not (isinstance(points, list) and points):
        return
    teeth = rotor.pick(spec.pair.male_teeth, spec.pair.female_teeth)
    if isinstance(as_given(points, teeth), list):
        import warnings

        from rotorcad.errors import InputNote

        warnings.warn(
            f"{label or 'the points'}: the drawing is read as its exact curves (they are the outline's own), which "
            f"no smoothing changes; the smoothing of {spec.smoothing:g} mm^2 is not used",
            InputNote,
            stacklevel=2,
        )


RADII_NOTE_SHARE = 0.01
"""Share of the lobe depth (tip minus root radius) by which a measured rotor's root radius, or its tip radius
above the stated one, may differ from the pair's before a note says so (a profile thinned by a clearance of
0.03-0.1 mm, or measured warm: 12e-6 /K x 100 K x 70 mm = 0.08 mm, stays below it on the samples' 17-18 mm
deep lobes)."""


def _note_radii_off(pair: RotorPair, points: Any, rotor: Side, label: str) -> None:
    """Say (an InputNote) when a rotor's points do not have the pair's stated root and tip radii.

    The pair is generated from the points' own radii, so a file of another rotor (the narrow-tip male, root
    52.727 mm, given with the rack-involute's 51.727: a new user's finding) gave a verdict of a pair nobody
    stated, without a word. Below the stated tip a sharp tip corner the points step over lies lower by up to
    their spacing, so the tip is compared only above the stated one there.
    """
    from rotorcad.measured.drawing import profile_points

    pts = profile_points(points)
    if len(pts) < 3:
        return
    r = np.hypot(*pts.T)
    tip, root = (
        rotor.pick(pair.male_tip_radius, pair.female_tip_radius),
        rotor.pick(pair.male_root_radius, pair.female_root_radius),
    )
    allowed = RADII_NOTE_SHARE * (tip - root)
    spacing = float(np.median(np.hypot(*np.diff(pts, axis=0).T)))
    off = []
    if abs(float(r.min()) - root) > allowed:
        off.append(f"its root radius {r.min():.3f} mm against the pair's {rotor.value} root radius {root:.3f} mm")
    if float(r.max()) - tip > allowed or tip - float(r.max()) > allowed + spacing:
        off.append(f"its tip radius {r.max():.3f} mm against the pair's {rotor.value} tip radius {tip:.3f} mm")
    if off:
        import warnings

        from rotorcad.errors import InputNote

        warnings.warn(
            f"{label}: {' and '.join(off)} (more than {allowed:.3f} mm apart): the pair is generated from the "
            "points' own radii, not the stated ones (is the file this pair's rotor)",
            InputNote,
            stacklevel=2,
        )


def _judgeable(pair: RotorPair, points: Any, rotor: Side, label: str) -> Any:
    """Read a rotor's points once and refuse them when they scatter more than a verdict allows.

    The scatter is estimated from the points' third differences (:func:`rotorcad.measured.outline.scatter`)
    and compared with :func:`rotorcad.meshing.largest_scatter` of the rotor's lobe depth: beyond it
    the numbers that came out were the noise's (0.1 mm on the symmetric SRM's female: accepted, a
    contact line of the noise). Returns the outline read (:class:`rotorcad.measured.outline.Outline`),
    which the fit takes as it is. Raises :class:`GeometryError` naming ``label``.
    """
    teeth = rotor.pick(pair.male_teeth, pair.female_teeth)
    outline = read_outline(points, teeth, label)
    if outline.whole is not None:  # points in other units than mm (an inch file) are refused as such
        from rotorcad.measured.point_checks import refuse_other_units

        root, tip = (
            rotor.pick(pair.male_root_radius, pair.female_root_radius),
            rotor.pick(pair.male_tip_radius, pair.female_tip_radius),
        )
        refuse_other_units(outline.whole, root, tip, label)
    _refuse_scatter(pair, outline, rotor, label)
    return outline


def _refuse_scatter(pair: RotorPair, outline: Any, rotor: Side, label: str) -> None:
    """Refuse points that scatter more than a verdict allows (:func:`rotorcad.meshing.largest_scatter`)."""
    depth = rotor.pick(pair.male_tip_radius - pair.male_root_radius, pair.female_tip_radius - pair.female_root_radius)
    most = largest_scatter(depth, pair.center_distance)
    if outline.sigma > most:
        reach = resolution(2 * outline.sigma, pair.center_distance)  # the accuracy the points carry: 2 sigma
        raise GeometryError(
            label,
            f"points that scatter by at most {most * 1e3:.3g} µm about a smooth outline",
            f"a scatter of {outline.sigma * 1e3:.3g} µm, estimated from the points' third differences",
            f"the defect tests would resolve no stretch shorter than {reach:.3g} mm "
            f"of meshline, over a quarter of the {rotor}'s lobe depth {depth:g} mm, and the numbers would be the noise's; "
            "measure more accurately, or give --smoothing (or [profile] smoothing) of at least n sigma^2 "
            "over a lobe's points to fit through the scatter",
        )


MAX_LOBE_POINTS = 50_000
"""Most points of one generated lobe at the default tolerance (a smooth lobe has a few hundred)."""

LOBE_POINTS_FACTOR = 3.0
"""Most points of a generated lobe as a multiple of :func:`smooth_lobe_points`: the samples' lobes
have 0.17 to 0.32 of it, mates generated from points with 0.05-0.2 mm of noise 7 to 16 (their
sections then took minutes to make valid, and their numbers were those of the noise: a contact line
30 times as long)."""


def smooth_lobe_points(tip_radius: float, teeth: int, tolerance: float = DEFAULT_TOLERANCE) -> float:
    """Estimate, generously, the number of points of a smooth lobe.

    Three times the tip circle's arc of one lobe, sampled to the chord ``tolerance`` on a radius of
    curvature of the tip radius (chord sqrt(8 R t)).

    Parameters
    ----------
    tip_radius : float, mm
        Tip radius of the rotor.
    teeth : int
        Its lobes.
    tolerance : float, mm
        Chord tolerance of the sampled lobe.

    Returns
    -------
    float
        The estimated number of points.
    """
    return 3.0 * 2.0 * np.pi * tip_radius / (teeth * np.sqrt(8.0 * tip_radius * tolerance))


def _check_generated(rotors: ScrewRotors, given: Side, label: str) -> None:
    """Refuse a mate generated from measured points that is not a rotor.

    That is one that runs far beyond its tip circle (1.5 times) or folds into many more points than
    a smooth lobe has (noise the smoothing left in). Checked before the sections are made: their
    cost grows with the folds. Raises :class:`DesignError` naming ``label``.
    """
    mate = given.other
    lobe = mate.pick(rotors.male_lobe, rotors.female_lobe)()
    tip = mate.pick(rotors.pair.male_tip_radius, rotors.pair.female_tip_radius)
    teeth = mate.pick(rotors.pair.male_teeth, rotors.pair.female_teeth)
    pts = np.vstack([seg.points for seg in lobe.segments if len(seg.points)]) if lobe.segments else np.zeros((0, 2))
    reach = float(np.hypot(*pts.T).max()) if len(pts) else 0.0
    most = int(min(MAX_LOBE_POINTS, LOBE_POINTS_FACTOR * smooth_lobe_points(tip, teeth)))
    if len(pts) == 0 or len(pts) > most or reach > 1.5 * tip:
        raise GeometryError(
            label,
            "a smooth profile that generates a mate",
            None,
            f"the {mate} generated from it has {len(pts)} points in a lobe (a smooth lobe has at most {most}) and reaches "
            f"{reach:.4g} mm against its tip radius {tip:g} mm; noise in the points? (raise --smoothing or [profile] "
            "smoothing, which acts on points and on drawings read as points; a drawing's exact curves are used as drawn)",
        )


def analyse_pair(rotors: ScrewRotors, speed_rpm: float) -> tuple[MeshingAnalysis, dict[str, Any]]:
    """Run Rinder's analysis of a pair and summarise it.

    Parameters
    ----------
    rotors : ScrewRotors
        The pair.
    speed_rpm : float, rpm
        Male speed, for the sliding velocities.

    Returns
    -------
    analysis : MeshingAnalysis
        The analysis (for pictures).
    summary : dict
        :meth:`MeshingAnalysis.summary` with ``rack_loss_percent``: the keys of
        ``rotorcad rotor --json``.
    """
    analysis = MeshingAnalysis(rotors, speed_rpm=speed_rpm)
    result = analysis.summary()
    result["rack_loss_percent"] = rotors.rack_loss
    return analysis, result


def design_summary(mapping: dict[str, Any], folder: Any = None, points: Any = None) -> dict[str, Any]:
    """Build and analyse the pair of a design mapping in one call.

    Parameters
    ----------
    mapping : dict
        The design as a TOML file holds it (CONTRACT.md "Design files").
    folder : path, optional
        Where a relative points file name is resolved (:func:`rotorcad.design.rotor_design`); the
        file is not read here.
    points : (n, 2) float array or list of Curve, optional
        The profile of a points family, already read (mm).

    Returns
    -------
    dict
        The numbers of ``rotorcad rotor --json`` (``files`` aside).

    Raises
    ------
    DesignError
        A bad design.
    """
    spec = pair_spec(rotor_design(mapping, folder), points)
    return analyse_pair(build_pair(spec), spec.speed_rpm)[1]

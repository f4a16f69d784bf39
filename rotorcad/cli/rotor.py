"""``rotorcad rotor``: screw-rotor pair generation and meshing analysis (CONTRACT.md)."""

from __future__ import annotations

from dataclasses import replace
from pathlib import Path
from typing import Any

import click
import numpy as np

from exports.csv_points import read_points, write_points
from exports.dxf import Drawing, write_dxf
from exports.dxf_profile import read_profile, read_profile_points
from exports.reading import check_regular_file
from rotorcad.clearance_design import ClearanceDistribution, corrected_female, thinned_female_fault
from rotorcad.cli.common import InputError, Outputs, emit_json, end_face, load_rotor_design, print_table, seen_from_option
from rotorcad.design.labels import PAIR_FIELDS, PAIR_LABELS, PairNames, required
from rotorcad.design.rotors import PairSpec, analyse_pair, build_pair, merge_pair
from rotorcad.envelope import rack_frame
from rotorcad.errors import ConflictError, DesignError, MissingValueError
from rotorcad.measured.end_face import design_deviation, mirror_note, section_points, seen_from_suction
from rotorcad.meshing import MESHLINE_GAIN, resolution
from rotorcad.profile import Segment
from rotorcad.roles import EndFace, Side
from rotorcad.screw_rotors import ScrewRotors

PAIR_OPTIONS = PAIR_FIELDS
"""The pair's dimensions, each an option of the same name (``--male-teeth``)."""

_UNRESOLVED = (
    "; not resolved: read it as the range area ± uncertainty, not a figure; the points do not place the "
    "profile where it touches at the apex (r = {:.2f} mm), give them closer together there"
)
"""What the text output adds to the blow-hole when the input does not resolve it (``blow_hole_resolved``)."""


def _points_option(name: str, text: str):
    return click.option(name, type=click.Path(path_type=Path, dir_okay=False), help=text)


ROTOR_INPUT_DECORATORS = [
    _points_option(
        "--male-points",
        "Male profile: CSV x,y [mm] or a DXF drawing, own frame seen from the suction end (else --seen-from), "
        "one lobe or the whole outline.",
    ),
    _points_option(
        "--female-points",
        "Female profile: CSV x,y [mm] or a DXF drawing, own frame seen from the suction end (else --seen-from), "
        "one lobe or the whole outline.",
    ),
    _points_option("--rack-points", "One rack period: CSV x,y [mm] or a DXF drawing, rack frame."),
    click.option("--layer", help="Layer of the profile in a DXF points file (default: its only layer)."),
    seen_from_option,
    click.option("--male-teeth", type=int, help="Male lobes z1 (2..12)."),
    click.option("--female-teeth", type=int, help="Female lobes z2 (2..12)."),
    click.option("--male-tip-radius", type=float, help="Male tip radius [mm]."),
    click.option("--male-root-radius", type=float, help="Male root radius [mm]."),
    click.option("--female-tip-radius", type=float, help="Female tip radius [mm]."),
    click.option("--female-root-radius", type=float, help="Female root radius [mm]."),
    click.option("--lead", type=float, help="Male lead h1 [mm]. Default 300 or the design's."),
    click.option("--length", type=float, help="Rotor length L [mm]. Default 190 or the design's."),
    click.option(
        "--smoothing",
        type=float,
        help="Spline smoothing of measured points [mm^2], 0 interpolates. Default: n sigma^2 from the points' estimated scatter.",
    ),
]


def rotor_input_options(fn):
    """Add the options that give a rotor pair by points and dimensions to a command (a decorator).

    All but the centre distance, which ``rotorcad gear`` names the same way; for ``rotor`` and
    ``hob``.
    """
    for deco in reversed(ROTOR_INPUT_DECORATORS):
        fn = deco(fn)
    return fn


CONTRACT_KEYS = (
    "male_teeth",
    "female_teeth",
    "center_distance",
    "meshline_closed",
    "blow_hole_area",
    "contact_line_length",
    "male_flute_area",
    "female_flute_area",
    "displacement_per_rev",
    "max_sliding_velocity",
)


@click.command()
@click.argument("design", required=False, type=click.Path(path_type=Path, dir_okay=False))
@rotor_input_options
@click.option("--center-distance", type=float, help="Centre distance a [mm].")
@click.option("--speed", type=float, help="Male speed [rpm] for sliding velocities. Default 3000 or the design's [operating].")
@click.option("--tolerance", type=float, default=1e-3, show_default=True, help="Chord tolerance of written outlines [mm].")
@click.option("--json", "as_json", is_flag=True, help="Print one JSON object on stdout.")
@click.option(
    "--plot",
    type=click.Path(path_type=Path, dir_okay=False),
    help="PNG of the pair in mesh; sliding and slip go to NAME_sliding.png.",
)
@click.option(
    "--dxf",
    type=click.Path(path_type=Path, dir_okay=False),
    help="DXF of male, female (in mesh), rack, pitch circles and bores [mm].",
)
@click.option(
    "--male-csv", type=click.Path(path_type=Path, dir_okay=False), help="Write the male outline (own frame, mesh position)."
)
@click.option(
    "--female-csv", type=click.Path(path_type=Path, dir_okay=False), help="Write the female outline (own frame, mesh position)."
)
@click.option("--rack-csv", type=click.Path(path_type=Path, dir_okay=False), help="Write one rack period (rack frame).")
@click.option(
    "--clearance",
    "designed",
    help="Meshing clearance to design into the female written by --female-csv / --dxf, in the normal section [mm]: "
    "a value (uniform) or driving=D,sealing=S,lands=L (a missing flank 0; missing lands: the smaller of D and S, "
    "so the tip and root lands are thinned too; lands=0 leaves them as designed) "
    "(Wu & Chi's measure: rotorcad clearance reads it back).",
)
@click.option(
    "--clearance-table",
    type=click.Path(path_type=Path, dir_okay=False),
    help="CSV x,clearance [mm]: the designed normal clearance over x along the pitch line of the transverse rack "
    "(rack frame of the points files, one rack period).",
)
@click.option("--quiet", is_flag=True, help="No progress output.")
def rotor(design: Path | None, **opts: Any) -> None:
    """Build a screw-rotor pair from a design file (profile family) or from measured points.

    With Rinder's meshing analysis: meshline, cusps / jamming / slipping, tightness and blow-hole,
    contact-line length, flute areas, displacement, sliding velocity and slip.
    """
    section: dict[str, Any] = {}
    rotors, speed, clearance = _build(design, opts, section=section)
    if not (1e-6 <= opts["tolerance"] <= 1.0):  # also NaN; finer than 1 um gives millions of points
        raise InputError(f"--tolerance must be a chord tolerance from 1e-06 to 1 mm (got {opts['tolerance']}).")
    try:
        analysis, result = analyse_pair(rotors, speed)
    except DesignError as exc:
        raise InputError(exc.sentence()) from None
    result.update(section)
    tol = opts["tolerance"]
    out = Outputs()
    _add_plots(out, opts, analysis, clearance)
    designed = _designed_clearance(opts)
    male_pts = lambda: _exterior(rotors.section(Side.MALE, tol, exact_tip=True))  # noqa: E731  (--tolerance: the written chords)
    female_pts = lambda: _exterior(rotors.section(Side.FEMALE, tol, exact_tip=True))  # noqa: E731
    if designed is not None:
        result["designed_clearance"] = (
            {"driving": designed.driving, "sealing": designed.sealing, "lands": designed.lands, "blend": designed.blend}
            if designed.table is None
            else {"table": str(opts["clearance_table"])}
        )
        corrected = _corrected(rotors, designed, tol)
        female_pts = lambda: corrected  # noqa: E731
    out.add(opts["male_csv"], lambda p: write_points(p, male_pts(), ["male outline, own frame, male angle 0"]), "--male-csv")
    out.add(
        opts["female_csv"],
        lambda p: write_points(p, female_pts(), ["female outline, own frame; shift by (a, 0) to mesh"]),
        "--female-csv",
    )
    out.add(opts["rack_csv"], lambda p: write_points(p, _rack_points(rotors, tol), ["one rack period, rack frame"]), "--rack-csv")
    out.add(opts["dxf"], lambda p: write_dxf(p, _drawing(rotors, male_pts(), female_pts(), clearance, tol)), "--dxf")
    result["files"] = [str(p) for p in out.write()]
    if opts["as_json"]:
        emit_json(result)
    else:
        _print_result(rotors, result)


def _add_plots(out: Outputs, opts: dict[str, Any], analysis, clearance: float) -> None:
    """Add the pictures of --plot: the pair in mesh, its sliding and, for measured points, their deviation."""
    if opts["plot"]:
        from rotorcad.rotor_plotting import plot_pair, plot_sliding  # matplotlib only when a plot is asked for

        plot = Path(opts["plot"])
        out.add_figure(plot, lambda: plot_pair(analysis, clearance), "--plot")
        out.add_figure(plot.with_name(plot.stem + "_sliding" + (plot.suffix or ".png")), lambda: plot_sliding(analysis), "--plot")
        measured = _measured_points(opts)
        if measured is not None:
            from rotorcad.rotor_plotting import plot_point_deviation

            side, pts, source = measured
            out.add_figure(
                plot.with_name(plot.stem + "_deviation" + (plot.suffix or ".png")),
                lambda: plot_point_deviation(analysis, Side(side), pts, source),
                "--plot",
            )


_UNDECIDED_CORNER = " (undecided: a corner or a rounding shorter than two point spacings, 2 x {:.3g} mm, read alike)"


def _print_result(rotors: ScrewRotors, result: dict[str, Any]) -> None:
    """Print the table of Rinder's figures, then the defects, the spatial blow-hole, the flanks and the files."""
    print_table(
        f"{rotors.family} {result['male_teeth']}/{result['female_teeth']} rotor pair",
        {k: v for k, v in result.items() if k != "angle_convention"},  # a sentence, printed below
    )
    acc = result["defect_accuracy"]
    line = f"  defects judged to an accuracy of {1e3 * acc:.2g} µm of the profile"
    if rotors.accuracy > 0:  # a given profile: its meshline's normals to the meshline's accuracy, over the resolution
        reach = resolution(MESHLINE_GAIN * acc, result["center_distance"])
        line += f" (the meshline's normals to {1e3 * MESHLINE_GAIN * acc:.2g} µm, over {reach:.2g} mm of meshline)"
        line += ": a defect within that of the meshline's end, a turn or another is below this resolution, not seen"
    click.echo(line)
    if result.get("blow_hole_uncertainty", 0.0) > 0:  # scattered points: their tangents move the apex
        click.echo(
            f"  blow-hole {result['blow_hole_area']:.3f} ± {result['blow_hole_uncertainty']:.3f} mm² "
            "(the uncertainty of its apex from the profile's accuracy, its tangents' and its points' spacing)"
            + (
                ""
                if result.get("blow_hole_resolved", True)
                else _UNRESOLVED.format(np.hypot(*result["blow_hole_spatial"]["apex"][:2]))
            )
        )
    for d in result["defects"]:
        click.echo(
            f"  {d['kind']} on the {d['rotor']} at ({d['x']:.3f}, {d['y']:.3f}) mm, {d['angle_deg']:+.1f}°, "
            f"flank '{d['flank']}'"
            + (" (point-generated)" if d["point_generated"] else "")
            + (": the tip corner itself, not a defect of the flank" if d.get("tip_corner") else "")
            + ("" if d.get("decided", True) else _UNDECIDED_CORNER.format(d["margin_accuracy"]))
        )
    for d in result.get("undecided_defects", []):
        if d["corner"] is None:  # a jamming the accuracy can neither show nor rule out (undecided.possible_rows)
            click.echo(
                f"  possible {d['kind']} on the {d['rotor']} at ({d['x']:.3f}, {d['y']:.3f}) mm, {d['flank_role']} flank: "
                f"the male rotation turns back and on again over {d['extent']:.3g} mm of meshline within the accuracy, "
                "undecided"
            )
            continue
        click.echo(
            f"  possible {d['rotor']} tip corner's path at ({d['x']:.3f}, {d['y']:.3f}) mm, {d['flank_role']} side: "
            f"its contacts within one point spacing ({d['margin_accuracy']:.3g} mm) over {d['extent']:.3g} mm of "
            "meshline, undecided"
        )
    spatial = result["blow_hole_spatial"]
    if spatial["area"] > 0:
        click.echo(
            f"  spatial blow-hole {spatial['area']:.3f} mm² (projected {spatial['projected_area']:.3f} mm²) "
            f"between z = {spatial['z_min']:.2f} and {spatial['z_max']:.2f} mm of the contact line"
        )
    for flank, report in result["flanks"].items():
        verdict = "runs" if report["runs_without_timing_gears"] else "does not run"
        verdict = verdict if report.get("running_decided", True) else "undecided at this accuracy (not shown to run)"
        click.echo(
            f"  {flank} flank: {verdict}; geometric contact on {100 * report['geometric_share']:.0f} % of "
            f"{report['meshline_length']:.2f} mm of meshline, "
            f"transverse contact ratio {report['transverse_contact_ratio']:.3f} "
            f"(± {report['transverse_contact_ratio_accuracy']:.3f}) + overlap "
            f"{report['overlap_contact_ratio']:.3f} = {report['total_contact_ratio']:.3f}"
        )
    for f in result["slip_singularities"]:
        click.echo(f"  infinite {f['rotor']} slip at ({f['x']:.3f}, {f['y']:.3f}) mm, {f['angle_deg']:+.1f}°, {f['flank']} flank")
    click.echo(f"  angles: {result['angle_convention']}")
    fit = result.get("design_deviation")
    if fit:  # points beside a design: how near its outline they lie, and their mirror image
        click.echo(
            f"  section read as seen from the {result['seen_from']} end: {1e3 * fit['as_read']:.3g} µm RMS from the "
            f"design's outline after the best turn (its mirror image {1e3 * fit['mirrored']:.3g} µm)"
        )
    for reason in result["running_reasons"]:
        click.echo(f"  does not run without timing gears: {reason}")
    for p in result["files"]:
        click.echo(f"wrote {p}")


def _measured_points(opts: dict[str, Any]) -> tuple[str, np.ndarray, str] | None:
    """Return the rotor and the points of --male-points / --female-points when they are points.

    Points of a CSV file or sampled from a drawing, with the file's name, for the picture of their
    deviation from the profile; None otherwise.
    """
    for side in ("male", "female"):
        path = opts.get(f"{side}_points")
        if path is None:
            continue
        data = seen_from_suction(read_profile(path, f"--{side}-points", opts.get("layer")), end_face(opts.get("seen_from")))
        return (side, np.asarray(data, dtype=float), Path(path).name) if isinstance(data, np.ndarray) else None
    return None


def _designed_clearance(opts: dict[str, Any]) -> ClearanceDistribution | None:
    """Return the clearance to design from --clearance or --clearance-table (one sentence on bad input)."""
    if opts.get("designed") is not None and opts.get("clearance_table") is not None:
        raise InputError("give only one of --clearance and --clearance-table.")
    try:
        if opts.get("designed") is not None:
            return ClearanceDistribution.parse(opts["designed"])
        if opts.get("clearance_table") is not None:
            rows = read_points(opts["clearance_table"], "--clearance-table", columns=("x", "clearance"))
            return ClearanceDistribution(table=tuple(map(tuple, rows)))
    except DesignError as exc:
        label = "--clearance-table" if opts.get("clearance_table") is not None else "--clearance"
        raise InputError(exc.sentence(label if exc.param.startswith("clearance") else exc.param)) from None
    return None


def _corrected(rotors: ScrewRotors, designed: ClearanceDistribution, tol: float) -> np.ndarray:
    """Return the female thinned by the designed clearance, clipped to its tip circle, counter-clockwise, (n, 2), mm."""
    import shapely

    pts = corrected_female(rotors, designed, tol)
    radius = rotors.pair.female_tip_radius + 1e-6
    poly = shapely.make_valid(shapely.Polygon(pts))
    if np.hypot(*pts.T).max() > radius:  # a circle of 2048 chords cut a tip land to 70 nm, past a fine --tolerance
        step = 2.0 * np.arccos(1.0 - min(tol, radius) / radius)  # rad: the chord of sagitta tol
        poly = poly.intersection(shapely.Point(0.0, 0.0).buffer(radius, quad_segs=int(np.ceil(0.5 * np.pi / step))))
    if not isinstance(poly, shapely.Polygon):
        poly = max((g for g in getattr(poly, "geoms", []) if isinstance(g, shapely.Polygon)), key=lambda g: g.area)
    out = _exterior(poly)
    fault = thinned_female_fault(rotors, out, designed, tol)  # checked before any file is written
    if fault is not None:
        raise InputError(
            f"--clearance at --tolerance {tol:g}: {fault}; nothing written: try another --tolerance from 1e-06 to 1 mm."
        )
    return out


def rotors_of(design: Path | None, data: dict[str, Any] | None, opts: dict[str, Any]) -> ScrewRotors | None:
    """Build the rotor pair that the points options or the design's ``[pair]`` describe, else None.

    For a command that takes a rotor pair or something else (``hob``, ``grind``): its options of the
    pair, the points and their smoothing, without speed (:func:`_build` merges them with the design).
    """
    if not (any(opts.get(k) for k in ("male_points", "female_points", "rack_points")) or (data is not None and "pair" in data)):
        if end_face(opts.get("seen_from")) is not EndFace.SUCTION:
            raise InputError(_SEEN_FROM_ALONE)
        return None
    rotor_opts = {k: opts.get(k) for k in (*PAIR_OPTIONS, "male_points", "female_points", "rack_points", "layer", "seen_from")}
    rotor_opts.update({"smoothing": opts.get("smoothing"), "speed": None})
    settings = None
    if data is not None:
        try:
            settings = load_rotor_design(design, data)
        except DesignError as exc:
            raise InputError(exc.sentence()) from None
    return _build(design, rotor_opts, settings)[0]


_SEEN_FROM_ALONE = (
    "--seen-from discharge needs --male-points or --female-points: a design's profile is seen from the suction end."
)


def _refusal(sentence: str, center_distance: Any, names: PairNames) -> InputError:
    """Return a refusal of the pair, with the inch hint when it is about lengths and a looks typed in inches.

    ``center_distance`` is a's value (mm), or the design's ``[pair]`` mapping (its ``center_distance``
    key, if any). A rounded inch design is refused by the pair's own checks before the warning of
    a successful run could say it (newuser7 F5; :func:`rotorcad.design.plausibility.with_inch_hint`).
    """
    from rotorcad.design.plausibility import with_inch_hint

    a = center_distance.get("center_distance") if isinstance(center_distance, dict) else center_distance
    if isinstance(a, (int, float)) and not isinstance(a, bool):
        sentence = with_inch_hint(sentence, float(a), names("center_distance") or "[pair] center_distance")
    return InputError(sentence)


def _build(
    design: Path | None, opts: dict[str, Any], settings: dict[str, Any] | None = None, section: dict[str, Any] | None = None
) -> tuple[ScrewRotors, float, float]:
    """Build the rotors of a design file or of measured points, with the command-line overrides.

    The values merge in the core (:func:`rotorcad.design.rotors.merge_pair`); here the points
    files are read (a missing one refused first), mirrored when seen from the discharge end
    (``--seen-from``), and every refusal names the option or design key the user typed
    (:class:`rotorcad.design.labels.PairNames`; of values in conflict, the one typed as an option).
    ``settings`` is the design already read and checked by
    :func:`rotorcad.design.files.load_rotor_design`, so that the file is read once. Returns the
    rotors, the speed (rpm) and the housing's radial clearance (mm); ``section``, when given, gets
    the result's keys of the section read (``seen_from``; ``design_deviation`` when points come
    with a design).
    """
    sources = [k for k in ("male_points", "female_points", "rack_points") if opts.get(k)]
    if len(sources) > 1:
        raise InputError("give only one of --male-points, --female-points, --rack-points.")
    if design is None and not sources:
        raise InputError("give a design file or one of --male-points, --female-points, --rack-points.")
    face = end_face(opts.get("seen_from"))
    source = sources[0].replace("_", "-") if sources else None
    if source is not None:
        try:  # a missing or unreadable file before what else the pair needs (a new user's N9)
            check_regular_file(opts[sources[0]], f"--{source}", "points file or DXF drawing")
        except DesignError as exc:
            raise InputError(exc.sentence()) from None
    try:
        d = None if design is None else load_rotor_design(design) if settings is None else settings
    except DesignError as exc:
        raise InputError(exc.sentence()) from None
    given = {k: opts.get(k) for k in PAIR_OPTIONS} | {"speed_rpm": opts.get("speed"), "smoothing": opts["smoothing"]}
    names = PairNames(
        design is not None, frozenset(k for k, v in given.items() if v is not None), source, frozenset(d["params"] if d else ())
    )
    try:
        spec = merge_pair(d, given, source)
    except MissingValueError as exc:
        raise InputError(required(PAIR_LABELS[exc.param])) from None
    except DesignError as exc:
        exc = exc.named_by(names.options) if isinstance(exc, ConflictError) else exc
        raise _refusal(exc.sentence(names(exc.param)), given.get("center_distance") or (d or {}).get("pair", {}), names) from None
    except TypeError as exc:
        raise InputError(f"the pair is not described completely: {exc}.") from None
    from rotorcad.cli.plausible import say_warnings
    from rotorcad.design.plausibility import screw_pair_warnings

    say_warnings(screw_pair_warnings(spec.pair.center_distance, names("center_distance") or "[pair] center_distance"))
    family = spec.family
    if face is not EndFace.SUCTION and family not in ("male-points", "female-points"):
        rack = "--seen-from applies to a rotor's points, not to a rack."
        raise InputError(_SEEN_FROM_ALONE if family != "rack-points" else rack)
    try:
        path = opts[sources[0]] if sources else d["points"]
        if family == "rack-points":
            spec = replace(spec, points=read_profile_points(path, f"--{family}", opts.get("layer")))
        elif family in ("male-points", "female-points"):
            spec = replace(spec, points=seen_from_suction(read_profile(path, f"--{family}", opts.get("layer")), face))
        rotors = build_pair(spec, label=f"--{family}")
    except DesignError as exc:
        raise _refusal(exc.sentence(names(exc.param, family)), spec.pair.center_distance, names) from None
    found: dict[str, Any] = {"seen_from": str(face)}
    if d is not None and source in ("male-points", "female-points") and not str(d["family"]).endswith("-points"):
        found.update(_against_design(spec, rotors.accuracy, d, given, Side(source.removesuffix("-points")), face))
    if section is not None:
        section.update(found)
    return rotors, spec.speed_rpm, spec.radial_clearance


def _against_design(
    spec: PairSpec, accuracy: float, d: dict[str, Any], given: dict[str, Any], side: Side, face: EndFace
) -> dict[str, Any]:
    """Compare the rotor's points with the design's outline of that rotor and with its mirror image.

    Returns ``{"design_deviation": {"as_read": mm, "mirrored": mm}}`` (RMS after the best turn,
    :func:`rotorcad.measured.end_face.design_deviation`, of the points as given, after
    ``--seen-from``), and notes a section whose mirror image, not itself, lies on the design's
    outline (:func:`rotorcad.measured.end_face.mirror_note`); nothing when the design's own pair
    cannot be built with the given values. (A design whose profile is itself given by points is not
    compared.)
    """
    import warnings

    from rotorcad.errors import InputNote

    try:
        nominal = build_pair(merge_pair(d, given, None))
    except (DesignError, TypeError):
        return {}
    pair, label = spec.pair, f"--{side}-points"
    teeth = int(side.pick(pair.male_teeth, pair.female_teeth))
    points = section_points(spec.points, side, teeth, pair.center_distance, label)
    design = (nominal.male_outline if side is Side.MALE else nominal.female_outline)(1e-3).points
    as_read, mirror = design_deviation(points, design, teeth)
    note = mirror_note(as_read, mirror, accuracy, face, label)
    if note is not None:
        warnings.warn(note, InputNote, stacklevel=2)
    return {"design_deviation": {"as_read": as_read, "mirrored": mirror}}


def _exterior(polygon) -> np.ndarray:
    """Counter-clockwise exterior points without the repeated end point."""
    pts = np.asarray(polygon.exterior.coords)[:-1]
    area = 0.5 * np.sum(pts[:, 0] * np.roll(pts[:, 1], -1) - np.roll(pts[:, 0], -1) * pts[:, 1])
    return pts if area > 0 else pts[::-1]


def _rack_points(rotors: ScrewRotors, tol: float) -> np.ndarray:
    pts = np.vstack([Segment.sample("rack", piece.curve, tol).points for piece in rotors.rack])
    keep = np.concatenate([[True], np.hypot(*np.diff(pts, axis=0).T) > 1e-9])
    return rack_frame(pts[keep], rotors.pair.male_pitch_radius)


def _drawing(rotors: ScrewRotors, male: np.ndarray, female: np.ndarray, clearance: float, tol: float) -> Drawing:
    pair = rotors.pair
    a = pair.center_distance
    d = Drawing(mark_size=0.05 * pair.male_tip_radius)
    d.outlines.append(("MALE", male))
    d.outlines.append(("FEMALE", female + np.array([a, 0.0])))
    d.circles += [
        ("PITCH", (0.0, 0.0), pair.male_pitch_radius),
        ("PITCH", (a, 0.0), pair.female_pitch_radius),
        ("HOUSING", (0.0, 0.0), pair.male_tip_radius + clearance),
        ("HOUSING", (a, 0.0), pair.female_tip_radius + clearance),
    ]
    d.centers += [(0.0, 0.0), (a, 0.0)]
    rack = np.vstack([Segment.sample("rack", piece.curve, tol).points for piece in rotors.rack])
    d.polylines = [("RACK", rack)]
    return d

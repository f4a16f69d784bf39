"""``rotorcad report``: one self-contained HTML page per design, for a design review (CONTRACT.md).

The numbers are those of the other commands, computed by the same code: a screw-rotor design gets
the pair and Rinder's analysis as ``rotorcad rotor`` builds it (:func:`rotorcad.cli.rotor._build`,
:func:`rotorcad.rotor_build.analyse_pair`) and the hobbability verdict as ``rotorcad hob`` judges
it (:func:`rotorcad.cli.hob_cmd.judge_racks`); a gear design the gear (and mate) as ``rotorcad
gear`` builds it and the same verdict. The pictures are those of ``--plot``, inline as SVG; the
page is written whole or not at all, with the files of ``--files``.
"""

from __future__ import annotations

import datetime
import hashlib
from pathlib import Path
from typing import Any

import click

from exports import html_report as hr
from exports.csv_points import write_points
from exports.dxf import write_dxf
from rotorcad import __version__, quantities
from rotorcad.cli.common import InputError, Outputs, emit_json, load_rotor_design, output_folder, print_table
from rotorcad.errors import DesignError

ROTOR_OPTIONS: dict[str, Any] = {
    "male_teeth": None,
    "female_teeth": None,
    "center_distance": None,
    "male_tip_radius": None,
    "male_root_radius": None,
    "female_tip_radius": None,
    "female_root_radius": None,
    "lead": None,
    "length": None,
    "male_points": None,
    "female_points": None,
    "rack_points": None,
    "layer": None,
    "smoothing": None,
    "speed": None,
}
"""The options of ``rotorcad rotor`` as they are when only a design file is given."""

GEAR_INPUT_UNITS = {
    "teeth": "–",
    "module": "mm",
    "pressure_angle_deg": "°",
    "helix_angle_deg": "°",
    "shift": "× m (modules)",
    "addendum": "× m (modules)",
    "dedendum": "× m (modules)",
    "tip_radius": "× m (modules)",
    "face_width": "mm",
    "outer_diameter": "mm",
    "center_distance": "mm",
    "tolerance": "mm",
}
"""Units of the keys of a gear design's ``[gear]`` and ``[mate]`` tables (factors of the module)."""


def report_unit(key: str) -> str:
    """Return the unit of a result's dotted key as the page shows it.

    The unit declared in :mod:`rotorcad.quantities` (the one of the command tables), with ° for
    degrees and – for a pure number.

    Parameters
    ----------
    key : str
        A key of ``rotorcad rotor --json``, ``hob --json`` or ``gear --json``, nested keys joined
        by dots (``max_sliding_at.value``).

    Returns
    -------
    str
        The unit as printed ("mm", "m/s", "°", "–", ...).
    """
    return quantities.symbol(quantities.unit_of(key))


def _input_unit(table: str, key: str, family: str | None) -> str:
    """Return the unit of a design file's key (``table.key``).

    Keys of the ``[gear]`` and ``[mate]`` tables take :data:`GEAR_INPUT_UNITS`; a ``[profile]`` key
    of a family takes its unit from the parameter's allowed range (degrees, mm, else a pure
    number), and ``smoothing`` is in mm²; everything else follows :func:`report_unit`.

    Parameters
    ----------
    table : str
        The design file's table (``gear``, ``mate``, ``profile``, ...).
    key : str
        The key within the table.
    family : str or None
        The screw-rotor family of the design (None for a gear).

    Returns
    -------
    str
        The unit as printed.
    """
    if table in ("gear", "mate", "shaper"):
        return GEAR_INPUT_UNITS.get(key, report_unit(key))
    if table == "profile" and family is not None:
        from rotorcad.rotor_families import FAMILIES

        param = FAMILIES.get(family, (None, {}))[1].get(key)
        if param is not None:
            text = param.allowed
            return "°" if "degree" in text else ("mm" if " mm" in text else "–")
        if key == "smoothing":
            return "mm²"
    return report_unit(key)


@click.command()
@click.argument("design", type=click.Path(path_type=Path, dir_okay=False))
@click.option(
    "--out",
    "out_path",
    required=True,
    type=click.Path(path_type=Path, dir_okay=False),
    help="The HTML page to write (.html): self-contained, pictures inline as SVG, nothing loaded from elsewhere.",
)
@click.option(
    "--files",
    "files_dir",
    type=click.Path(path_type=Path, file_okay=False),
    help="Folder for the design's files, listed on the page: male.csv, female.csv, rack.csv, pair.dxf and hob.dxf of a "
    "rotor pair (gear.csv, mate.csv, gear.dxf, hob.dxf of a gear), and each picture as SVG.",
)
@click.option("--json", "as_json", is_flag=True, help="Print one JSON object on stdout.")
@click.option("--quiet", is_flag=True, help="No progress output (there is none).")
def report(design: Path, out_path: Path, files_dir: Path | None, as_json: bool, quiet: bool) -> None:
    """Write one self-contained HTML page for a screw-rotor or gear design file.

    Every number with its unit (those of `rotorcad rotor --json` or `rotorcad gear --json`), the
    hobbability verdict with its reasons, the defects, the pictures (inline SVG) and the files
    written.
    """
    from rotorcad.cli.hob_cmd import _read_design

    if out_path.suffix.lower() not in (".html", ".htm"):
        raise InputError(f"--out must name a .html file (got {out_path}).")
    data = _read_design(design)
    if data is None:  # click makes DESIGN required; kept for a call from Python
        raise InputError("DESIGN must name a design file (a .toml with [pair] or [gear]).")
    if "shaper" in data:  # an internal gear, cut by its shaper cutter
        from rotorcad.cli.report_internal import internal_content

        content = internal_content(design, data, _figure)
    else:
        content = _rotor_content(design, data) if "pair" in data else _gear_content(design, data)
    folder = output_folder(files_dir)
    outputs = Outputs()
    planned: list[tuple[Path, str]] = []
    if folder is not None:
        for name, (writer, what) in content["files"].items():
            outputs.add(folder / name, writer, "--files")
            planned.append((folder / name, what))
        for fid, (svg, caption) in content["figures"].items():
            outputs.add(folder / f"{fid}.svg", lambda p, s=svg: Path(p).write_text(s, encoding="utf-8"), "--files")
            planned.append((folder / f"{fid}.svg", caption))
    planned.append((out_path, "this page"))
    page = _page(design, data, content, planned)
    outputs.add(out_path, lambda p: hr.write_page(p, page), "--out")
    written = [str(p) for p in outputs.write()]
    result = {
        "report": str(out_path),
        "design": str(design),
        "kind": content["kind"],
        "hobbable": content["hob"]["hobbable"],
        "defect_count": len(content["result"].get("defects", [])),
        "files": written,
        "replaced": [str(p) for p in outputs.replaced],  # files that were there, replaced whole (also said on stderr)
    }
    if as_json:
        emit_json(result)
    else:
        print_table(f"report of {design.name}", {k: v for k, v in result.items() if k not in ("files", "replaced")})
        for p in written:
            click.echo(f"wrote {p}")


def _figure(fig: Any, fid: str) -> str:
    from rotorcad.plot_style import svg_text

    return svg_text(fig, salt=f"rotorcad-{fid}")


def _rotor_content(design: Path, data: dict[str, Any]) -> dict[str, Any]:
    """Collect the numbers, pictures and files of a screw-rotor design, by the code of ``rotor`` and ``hob``.

    Parameters
    ----------
    design : Path
        The design file.
    data : dict
        Its parsed tables.

    Returns
    -------
    dict
        ``kind``, ``case``, ``family``, ``result`` (the numbers), ``hob`` (the hobbability
        verdict), ``figures`` (id -> (SVG text, caption)), ``files`` (name -> (writer, what it
        holds)) and ``command`` (the command whose numbers these are).

    Raises
    ------
    InputError
        When the design cannot be built or analysed (the DesignError's sentence).
    """
    from hob.rack import rack_deviation, rotor_rack
    from hob.verdict import HobLimits
    from rotorcad.cli import hob_cmd
    from rotorcad.cli import rotor as rotor_cmd
    from rotorcad.rotor_build import analyse_pair

    try:
        settings = load_rotor_design(design, data)
    except DesignError as exc:
        raise InputError(exc.sentence()) from None
    section: dict[str, Any] = {}  # the keys of the section read that `rotor` reports (seen_from)
    rotors, speed, clearance = rotor_cmd._build(design, dict(ROTOR_OPTIONS), settings, section)
    try:
        analysis, result = analyse_pair(rotors, speed)
        result.update(section)
        racks = {"male": rotor_rack(rotors, "male"), "female": rotor_rack(rotors, "female")}
        deviation = rack_deviation(rotors)
    except DesignError as exc:
        raise InputError(exc.sentence()) from None
    verdicts, hob = hob_cmd.judge_racks(racks, deviation, HobLimits())
    pair = rotors.pair
    case = f"{rotors.family} {pair.male_teeth}/{pair.female_teeth}"
    figures = _rotor_figures(rotors, analysis, clearance, racks, verdicts, deviation, case)
    files = _rotor_files(rotors, analysis, clearance, racks)
    from rotorcad.cli.deflect_cmd import design_deflection  # with [operating] pressures: deflect's numbers too

    try:  # a design deflect refuses keeps its report: the section says why instead
        deflection = design_deflection(design, settings, rotors)
    except InputError as exc:
        deflection = {"refused": exc.format_message()}
    return {
        "deflection": deflection,
        "kind": "rotor",
        "case": f"screw-rotor pair {case}",
        "family": rotors.family,
        "result": result,
        "hob": hob,
        "figures": figures,
        "files": files,
        "command": "rotorcad rotor",
    }


def _rotor_figures(rotors, analysis, clearance: float, racks, verdicts, deviation, case: str) -> dict[str, tuple[str, str]]:
    """Return the pictures of a screw-rotor design (id -> (SVG text, caption)), those of ``rotor --plot`` and ``hob --plot``."""
    from hob.plotting import plot_hob, rotor_rack_comparison
    from rotorcad.rotor_plotting import plot_pair, plot_sliding

    root_clearance = 0.25 * rotors.pair.male_addendum  # rotorcad hob's default --root-clearance
    return {
        "pair": (_figure(plot_pair(analysis, clearance), "pair"), "The pair in mesh at male angle 0 (rotorcad rotor --plot)."),
        "sliding": (
            _figure(plot_sliding(analysis), "sliding"),
            "Sliding velocity and slip over the male rotation angle, one line per pair of flanks in contact "
            "(rotorcad rotor --plot, NAME_sliding).",
        ),
        "hob": (
            _figure(
                plot_hob(racks, verdicts, rotor_rack_comparison(rotors, racks), root_clearance, f"the {case} pair", deviation),
                "hob",
            ),
            "The racks derived from the male and from the female, their deviation magnified along the normal, and the hob "
            "teeth (rotorcad hob --plot).",
        ),
    }


def _rotor_files(rotors, analysis, clearance: float, racks) -> dict[str, tuple[Any, str]]:
    """Return the files of a screw-rotor design (name -> (writer, what it holds)), as ``rotor`` and ``hob`` write them."""
    from rotorcad.cli import hob_cmd
    from rotorcad.cli import rotor as rotor_cmd

    tol = 1e-3
    root_clearance = 0.25 * rotors.pair.male_addendum  # rotorcad hob's default --root-clearance
    male = rotor_cmd._exterior(analysis.sections[0])
    female = rotor_cmd._exterior(analysis.sections[1])
    return {
        "male.csv": (
            lambda p: write_points(p, male, ["male outline, own frame, male angle 0"]),
            "male outline (x,y, own frame)",
        ),
        "female.csv": (
            lambda p: write_points(p, female, ["female outline, own frame; shift by (a, 0) to mesh"]),
            "female outline (x,y, own frame)",
        ),
        "rack.csv": (
            lambda p: write_points(p, rotor_cmd._rack_points(rotors, tol), ["one rack period, rack frame"]),
            "one rack period (rack frame)",
        ),
        "pair.dxf": (
            lambda p: write_dxf(p, rotor_cmd._drawing(rotors, male, female, clearance, tol)),
            "the pair in mesh, rack, pitch circles and bores",
        ),
        "hob.dxf": (
            lambda p: write_dxf(p, hob_cmd._drawing(racks, root_clearance)),
            "normal racks and hob teeth side by side",
        ),
    }


def _gear_content(design: Path, data: dict[str, Any]) -> dict[str, Any]:
    """Collect the numbers, pictures and files of a gear design, by the code of ``gear`` and ``hob``.

    Parameters
    ----------
    design : Path
        The design file.
    data : dict
        Its parsed tables.

    Returns
    -------
    dict
        ``kind``, ``case``, ``family``, ``result`` (the numbers), ``hob`` (the hobbability
        verdict), ``figures`` (id -> (SVG text, caption)), ``files`` (name -> (writer, what it
        holds)) and ``command`` (the command whose numbers these are).
    """
    from hob.plotting import gear_rack_comparison, plot_hob
    from hob.rack import gear_rack
    from hob.verdict import HobLimits
    from rotorcad.cli import gear as gear_cmd
    from rotorcad.cli import hob_cmd
    from rotorcad.plotting import plot_gears

    params = gear_cmd.merge_gear_params(design, {}, data)
    g, pair = gear_cmd.build_gear(params, 1e-4)  # gear's default --tolerance
    result: dict[str, Any] = pair.summary() if pair is not None else g.summary()
    shop, g, pair = gear_cmd.shop_gears(params, g, pair)  # allowances, span, over pins, backlash: as gear --json
    if pair is not None:
        result["mate"].update(shop.pop("mate"))
    result.update(shop)
    racks = {"gear": gear_rack(g)}
    deviation = hob_cmd._basic_rack_deviation(g, racks["gear"])
    verdicts, hob = hob_cmd.judge_racks(racks, deviation, HobLimits(), gear=g)
    root_clearance = 0.25 * g.module
    case = f"gear z = {g.teeth}, m = {g.module:g} mm" + (f" with mate z = {pair.mate.teeth}" if pair is not None else "")
    figures = {
        "gear": (_figure(plot_gears(g, pair), "gear"), "The gear (and its mate in mesh) (rotorcad gear --plot)."),
        "hob": (
            _figure(
                plot_hob(racks, verdicts, gear_rack_comparison(g, racks["gear"]), root_clearance, f"the {case}", deviation), "hob"
            ),
            "The rack derived from the gear against the basic rack, the deviation magnified along the normal, and the hob "
            "tooth (rotorcad hob --plot).",
        ),
    }
    files = {
        "gear.csv": (
            lambda p: write_points(p, g.outline().points, gear_cmd._comments(g, "gear")),
            "gear outline (x,y)",
        ),
        "gear.dxf": (lambda p: write_dxf(p, gear_cmd._drawing(g, pair)), "the gear (and mate in mesh), pitch and base circles"),
        "hob.dxf": (lambda p: write_dxf(p, hob_cmd._drawing(racks, root_clearance)), "normal rack and hob tooth"),
    }
    if pair is not None:
        files["mate.csv"] = (
            lambda p: write_points(p, pair.mate.outline().points, gear_cmd._comments(pair.mate, "mate")),
            "mate outline (x,y)",
        )
    return {
        "kind": "gear",
        "case": case,
        "family": None,
        "result": result,
        "hob": hob,
        "figures": figures,
        "files": files,
        "command": "rotorcad gear",
    }


def _page(design: Path, data: dict[str, Any], content: dict[str, Any], planned: list[tuple[Path, str]]) -> str:
    """Return the HTML page of a design's content.

    Parameters
    ----------
    design : Path
        The design file.
    data : dict
        Its parsed tables.
    content : dict
        From :func:`_rotor_content` or :func:`_gear_content`.
    planned : list of (Path, str)
        The files to be written, each with what it holds.

    Returns
    -------
    str
        The page's HTML.
    """
    result, hob = content["result"], content["hob"]
    verdict = "hobbable" if hob["hobbable"] else "NOT hobbable"
    family = content.get("family")
    inputs = [
        (f"{table}.{key}", value)
        for table, values in data.items()
        if isinstance(values, dict)
        for key, value in values.items()
        if not isinstance(value, dict | list)
    ]

    def input_unit(dotted: str) -> str:
        table, _, key = dotted.partition(".")
        return _input_unit(table, key, family)

    sections = [
        hr.Section("summary", "Verdict", _summary(content, verdict)),
        hr.Section("design", "Design", hr.quantity_table(inputs, input_unit, "design key")),
        hr.Section(
            "numbers",
            f"Numbers ({content['command']} --json)",
            f"<p>Every number of <code>{content['command']} {hr.esc(design)} --json</code>, computed by the same code.</p>"
            + hr.quantity_table(hr.flatten({k: v for k, v in result.items() if k != "files"}), report_unit),
        ),
    ]
    if content["kind"] == "rotor":
        sections.append(_defects_section(result))
    if content.get("deflection") is not None:  # a rotor design with [operating] pressures
        shown = {k: v for k, v in content["deflection"].items() if k not in ("chambers", "defaults", "files", "refused")}
        body = (
            f"<p>rotorcad deflect refuses this design: {hr.esc(content['deflection']['refused'])}</p>"
            if "refused" in content["deflection"]
            else f"<p>Every number of <code>rotorcad deflect {hr.esc(design)} --json</code> (Rinder &amp; Deix), computed "
            "by the same code; the defaults it took are those of <code>deflect</code>.</p>"
            + hr.quantity_table(hr.flatten(shown), report_unit)
        )
        sections.append(hr.Section("deflection", "Deflection under gas load (rotorcad deflect --json)", body))
    sections.append(
        hr.Section(
            "hob",
            "Hobbability (rotorcad hob --json)",
            hr.verdict_box(hob["hobbable"], f"{verdict}")
            + hr.bullet_list(hob["reasons"], "No reason against.")
            + hr.quantity_table(hr.flatten(hob), report_unit),
        )
    )
    sections.append(
        hr.Section(
            "pictures",
            "Pictures",
            "\n".join(hr.figure(svg, caption, f"figure-{fid}") for fid, (svg, caption) in content["figures"].items()),
        )
    )
    sections.append(
        hr.Section(
            "files",
            "Files written",
            hr.record_table([{"path": str(p), "what": what} for p, what in planned], [("path", "file"), ("what", "content")], ""),
        )
    )
    return hr.page(f"rotorcad report: {content['case']} ({Path(design).name})", _meta(design, content), sections)


def _meta(design: Path, content: dict[str, Any]) -> list[tuple[str, str]]:
    """Return the page's head: the design file and its SHA-256, the case, who made it and when, the units."""
    text = Path(design).read_bytes() if Path(design).is_file() else b""
    return [
        ("design file", str(design)),
        ("design file SHA-256", hashlib.sha256(text).hexdigest()),
        ("case", content["case"]),
        ("made by", f"rotorcad {__version__}, rotorcad report"),
        ("made on", datetime.datetime.now(datetime.UTC).strftime("%Y-%m-%d %H:%M UTC")),
        ("units", "lengths mm, areas mm², volumes mm³, angles °, speeds m/s (CONTRACT.md)"),
    ]


def _summary(content: dict[str, Any], verdict: str) -> str:
    """Return the verdict section's HTML: hobbability, defects and meshline (a pair) or undercut (a gear), reasons."""
    result, hob = content["result"], content["hob"]
    defects = result.get("defects", [])
    summary = [hr.verdict_box(hob["hobbable"], f"Hobbability: {verdict}")]
    if content["kind"] == "rotor":
        summary.append(hr.verdict_box(not defects, f"Meshing defects: {len(defects)}" + (" (none)" if not defects else "")))
        summary.append(
            hr.verdict_box(
                bool(result.get("meshline_closed")),
                f"Meshline {'closed' if result.get('meshline_closed') else 'open'}; blow-hole "
                f"{hr.number_text(result.get('blow_hole_area'))}"
                + (f" ± {hr.number_text(result['blow_hole_uncertainty'])}" if result.get("blow_hole_uncertainty") else "")
                + " mm²",
            )
        )
    else:
        summary.append(hr.verdict_box(not result.get("undercut"), "Undercut" if result.get("undercut") else "No undercut"))
    summary.append("<h3>Why (reasons of the hobbability verdict)</h3>")
    summary.append(hr.bullet_list(hob["reasons"], "No reason against: every check of rotorcad hob passed."))
    return "\n".join(summary)


def _defects_section(result: dict[str, Any]) -> hr.Section:
    """Return the section of a pair's defects (cusps, jamming, slipping) and point-generated flanks."""
    defects = result.get("defects", [])
    return hr.Section(
        "defects",
        "Defects (cusps, jamming, slipping)",
        hr.record_table(
            defects,
            [
                ("kind", "kind"),
                ("rotor", "rotor"),
                ("flank", "flank"),
                ("x", "x [mm]"),
                ("y", "y [mm]"),
                ("angle_deg", "male angle φ1 [°] (to go until a male tip's middle is on O1O2)"),
                ("point_generated", "point-generated"),
                ("tip_corner", "tip corner (not a defect of the flank)"),
                ("extent", "extent along the meshline [mm]"),
                ("decided", "decided (false: a corner or a rounding shorter than 2 point spacings)"),
                ("margin_accuracy", "point spacing [mm]"),
            ],
            "No defect: no cusp, jamming or slipping on the meshline.",
        )
        + "<h3>Point-generated flanks</h3>"
        + hr.record_table(
            result.get("point_generated_flanks", []),
            [("rotor", "rotor"), ("flank", "flank"), ("generated_by", "generated by")],
            "None.",
        ),
    )

"""A rotor read back from the DXF files rotorcad writes gives the design's verdicts and numbers.

For every rotor sample, ``rotorcad export`` writes each rotor's drawing: a closed polyline (layer
MALE / FEMALE, the outline's points) and one C1 Hermite spline per exact piece (MALE_SPLINE /
FEMALE_SPLINE), the female drawn at its place in the pair, about (a, 0). Each of the four is read
back as ``rotor --male-points`` / ``--female-points`` reads it (:func:`exports.dxf_profile.read_profile`,
then the pair generated from that rotor) and judged against the design (reference: the pair built
from the design's own analytic outline, which never passes through the DXF reader or writer):

- the same defects (kind, rotor, flank, point-generated; each within the resolution of the input's
  accuracy of the design's), the same running verdict per flank;
- the blow-hole within 1 % (Rinder sec. 2.2.2), its spatial apex z within 1 % of h1/z1;
- the transverse contact ratio per flank within 1 %, or within the resolution of the defect tests
  at the drawing's accuracy over the working length (the splines only: a polyline's chords carry
  their sagitta into the working part's ends).

Before: the splines (34-52 control points) were read as points at their knots (rack-involute
contact ratios 0.445 against 0.484/0.497, the narrow-tip female refused as noise), the female at
(a, 0) refused, and the apex z read 43.16 / 30.78 / 42.26 / 80.63 mm for one narrow-tip apex.
"""

from __future__ import annotations

import io
import json
import sys
import tomllib
import warnings
from pathlib import Path

import ezdxf
import numpy as np
import pytest
import shapely
from test_verdict_invariance import assert_same_verdicts

from exports.csv_points import read_points, write_points
from exports.dxf import Drawing, write_dxf
from exports.dxf_profile import read_profile
from rotorcad.blow_hole import apex_height
from rotorcad.cli.main import main
from rotorcad.design import rotor_design
from rotorcad.design.rotors import PairSpec, analyse_pair, build_pair, pair_spec
from rotorcad.errors import DesignError, InputNote
from rotorcad.measured.outline import as_given, carries_tangents, own_frame, read_outline

SAMPLES = Path(__file__).resolve().parents[1] / "samples"
ROTOR_SAMPLES = [p.stem for p in sorted(SAMPLES.glob("*.toml")) if "profile" in tomllib.loads(p.read_text())]
FORMS = ("spline", "polyline")
SIDES = ("male", "female")

_FEMALE_ROUTE = (
    "the male generated from the female gets a driving cusp at +16.7 deg that the design has not, and its sealing "
    "cusp at -16.8 deg instead of -0.06 deg (the male tip's middle), from the female's exact splines and its "
    "polyline alike: the mate generated from a female's corner paths (rotorcad.measured.pairs, the female-points work)"
)
_ROUND = (
    "-2.3 %: the apex lies where the male's 0.67 mm tip rounding meets the sealing flank; the polyline's vertices "
    "(chords to export's 2.5 um) put few points on it and the fit's tangent there is off, as for evenly spaced "
    "exact points (test_verdict_invariance's KNOWN_BLOW_HOLE); its splines read -0.07 %"
)
KNOWN: dict[tuple[str, str, str], str] = {
    ("krigar_4_6", "female", "spline"): _FEMALE_ROUTE,
    ("krigar_4_6", "female", "polyline"): _FEMALE_ROUTE,
}
"""Cases whose verdicts (defects or running) depart from the design, with the cause: strict xfails."""

KNOWN_NUMBERS: dict[tuple[str, str, str], str] = {
    ("n_rack_5_6", "male", "polyline"): _ROUND,
    ("rinder_deix_5_6", "male", "polyline"): _ROUND,
    **{
        (name, "female", "spline"): (
            "+1.7 % (1.768 for 1.7375 mm²): the male's 0.67 mm tip rounding, where the apex lies, generated from the "
            "female's splines, ends where the mate's point leaves the corner path within the drawing's accuracy "
            "(rotorcad.measured.pairs.mate_wander; 0.0 % with the fixed 0.1 um it replaced; test_mate_points reads "
            "+2.8 % from 300 exact points a lobe)"
        )
        for name in ("n_rack_5_6", "rinder_deix_5_6")
    },
    ("rack_involute_5_6", "female", "polyline"): (
        "-2.2 %: the male generated from the female polyline's points (2.1 um accuracy), whose tip corner's path "
        "sets the apex (the female-points work); its splines read +0.27 %"
    ),
}
"""Cases whose blow-hole or apex departs by more than 1 %, with the cause: strict xfails."""

KNOWN_RATIOS: dict[tuple[str, str], str] = {}
"""Cases whose splines' contact ratios depart by more than 1 %, with the cause: strict xfails."""


def _summary(rotors, speed: float) -> dict:
    """The numbers compared: defects, flanks, blow-hole, apex, accuracy (plain values, picklable)."""
    result = analyse_pair(rotors, speed)[1]
    keep = ("defects", "flanks", "blow_hole_area", "blow_hole_spatial", "defect_accuracy", "center_distance")
    return {k: result[k] for k in keep}


def _export(name: str, folder: Path) -> dict[str, dict]:
    """Write the sample's DXF drawings through ``rotorcad export``; return its rows by body."""
    buffer = io.StringIO()
    with pytest.MonkeyPatch.context() as mp:  # stdout captured without capsys (shared fixture)
        mp.setattr(sys, "stdout", buffer)
        rc = main(["export", str(SAMPLES / f"{name}.toml"), "--format", "dxf", "--out", str(folder), "--no-housing", "--json"])
    assert rc == 0
    return {row["body"]: row for row in json.loads(buffer.getvalue())["files"]}


def _build(name: str, folder: Path) -> dict:
    spec = pair_spec(rotor_design(tomllib.loads((SAMPLES / f"{name}.toml").read_text()), SAMPLES))
    out: dict = {"design": _summary(build_pair(spec), spec.speed_rpm), "lead": spec.pair.lead, "teeth": spec.pair.male_teeth}
    out["female_teeth"] = spec.pair.female_teeth
    rows = _export(name, folder)
    out["rows"] = {body: {"path": row["path"], "spline_deviation": row["spline_deviation"]} for body, row in rows.items()}
    for side in SIDES:
        for form in FORMS:
            layer = side.upper() + ("_SPLINE" if form == "spline" else "")
            label = f"--{side}-points"
            with warnings.catch_warnings():
                warnings.simplefilter("ignore", InputNote)
                try:
                    data = read_profile(Path(rows[side]["path"]), label, layer)
                    given = build_pair(PairSpec(spec.pair, f"{side}-points", {}, data, None, spec.speed_rpm, 0.0), label=label)
                    out[(side, form)] = _summary(given, spec.speed_rpm)
                except DesignError as exc:
                    out[(side, form)] = {"refused": exc.sentence()}
    return out


@pytest.fixture(scope="module")
def read_back(built_once, tmp_path_factory):
    """``read_back(name)``: the design's summary and those of its four drawings read back (built once per sample)."""
    return lambda name: built_once(f"test_dxf_exact.{name}", lambda: _build(name, tmp_path_factory.mktemp(name)))


def _case(name: str, side: str, form: str, known: dict):
    reason = known.get((name, side, form))
    mark = pytest.mark.xfail(strict=True, reason=reason) if reason else ()
    return pytest.param(name, side, form, marks=mark, id=f"{name}-{side}-{form}")


CASES = [(n, s, f) for n in ROTOR_SAMPLES for s in SIDES for f in FORMS]


@pytest.mark.parametrize(("name", "side", "form"), [_case(*c, KNOWN) for c in CASES])
def test_same_defects_and_running(read_back, name, side, form):
    built = read_back(name)
    design, given = built["design"], built[(side, form)]
    assert "refused" not in given, given.get("refused")
    assert_same_verdicts(design, given)  # kind, rotor, flank, point-generated; place within the resolution


@pytest.mark.parametrize(("name", "side", "form"), [_case(*c, KNOWN_NUMBERS) for c in CASES])
def test_same_blow_hole_and_apex(read_back, name, side, form):
    built = read_back(name)
    design, given = built["design"], built[(side, form)]
    assert "refused" not in given, given.get("refused")
    assert given["blow_hole_area"] == pytest.approx(design["blow_hole_area"], rel=0.01, abs=1e-3)  # 1 %
    # the apex height (Rinder eq. 1) from the section where the nearest male tip's middle lies on O1O2:
    # within 1 % of the height of one lobe's turn, h1 / z1 (it read 43.16 / 30.78 / 42.26 / 80.63 mm)
    z_design, z_given = design["blow_hole_spatial"]["apex"][2], given["blow_hole_spatial"]["apex"][2]
    assert z_given == pytest.approx(z_design, abs=0.01 * built["lead"] / built["teeth"])


def _ratio_case(name: str, side: str):
    reason = KNOWN_RATIOS.get((name, side))
    return pytest.param(name, side, marks=pytest.mark.xfail(strict=True, reason=reason) if reason else ())


@pytest.mark.parametrize(("name", "side"), [_ratio_case(n, s) for n in ROTOR_SAMPLES for s in SIDES])
def test_spline_contact_ratios(read_back, name, side):
    # the finding: the rack-involute male's splines read 0.445 against the design's 0.484 / 0.497. Within
    # 1 %, or within what the working part's ends are known to: the resolution of the defect tests at the
    # drawing's accuracy (rotorcad.meshing.resolution) over the working length. The rack-involute male's
    # splines (0.44 um) read 0.491 against 0.497 on the sealing flank: 0.34 mm of the 29.1 mm working part
    # next to the female's sealing cusp, where the female generated from the splines retraces 1 um (the
    # splines' 0.2 um error), is read as the female's corner path, within a resolution of 0.64 mm
    # (now 0.484 after the contacts within the meshline's accuracy of a tip corner count as none): each end
    # of the working part is known to the meshline the drawing's tangent resolves, sqrt(8 a e), so the ratio
    # to 2 sqrt(8 a e) / p_t, p_t = 2 pi a / (z1 + z2) (tests/test_contact_ratio_invariance.py derives it)
    built = read_back(name)
    design, given = built["design"], built[(side, "spline")]
    a = design["center_distance"]
    e = max(given["defect_accuracy"], design["defect_accuracy"])
    known = 2 * np.sqrt(8 * a * e) / (2 * np.pi * a / (built["teeth"] + built["female_teeth"]))
    for flank, report in design["flanks"].items():
        want = report["transverse_contact_ratio"] or 0.0
        got = given["flanks"][flank]["transverse_contact_ratio"] or 0.0
        assert got == pytest.approx(want, rel=0.01, abs=max(1e-3, known)), flank


@pytest.mark.parametrize(("name", "side"), [(n, s) for n in ROTOR_SAMPLES for s in SIDES])
def test_export_splines_are_exact_curves_of_a_stated_accuracy(read_back, name, side):
    # reference: the export's measured deviation of its splines from the exact outline (the writer's
    # measurement against the design's curves, not the reader's estimate)
    built = read_back(name)
    row = built["rows"][side]
    curves = read_profile(Path(row["path"]), f"--{side}-points", f"{side.upper()}_SPLINE")
    assert all(carries_tangents(c) for c in curves if hasattr(c, "knots"))
    teeth = built["teeth"] if side == "male" else built["female_teeth"]
    if side == "female":
        with pytest.warns(InputNote, match=r"moved by \(-"):
            curves = own_frame(curves, "female", built["design"]["center_distance"], "--female-points")
    outline = read_outline(curves, teeth, f"--{side}-points")
    assert isinstance(outline.given, list)  # the curves, not points at their knots
    assert 0.3 * row["spline_deviation"] <= outline.accuracy <= max(5 * row["spline_deviation"], 1e-4)


def test_female_at_the_centre_distance_is_the_design_female(read_back):
    # reference: the design's own female section (analytic), in its own frame
    name = "narrow_tip_5_6"
    built = read_back(name)
    spec = pair_spec(rotor_design(tomllib.loads((SAMPLES / f"{name}.toml").read_text()), SAMPLES))
    exact = np.asarray(build_pair(spec).section("female", 1e-5).exterior.coords)
    drawn = read_profile(Path(built["rows"]["female"]["path"]), "--female-points", "FEMALE_SPLINE")
    with pytest.warns(InputNote, match="place in the pair"):
        moved = own_frame(drawn, "female", spec.pair.center_distance, "--female-points")
    pts = np.vstack([c.evaluate(np.linspace(c.s0, c.s1, 50))[0] for c in moved])
    gap = shapely.distance(shapely.points(pts), shapely.LinearRing(exact))
    assert gap.max() <= built["rows"]["female"]["spline_deviation"] + 1e-6
    # a male, or a female already in its own frame, is left as it is (no note)
    with warnings.catch_warnings():
        warnings.simplefilter("error", InputNote)
        assert own_frame(moved, "female", spec.pair.center_distance, "x") is moved
        assert own_frame(drawn, "male", spec.pair.center_distance, "x") is drawn


def test_off_both_centres_is_refused_saying_where(tmp_path, capsys):
    # the design's female (reference: its analytic section) drawn 5 mm past its place in the pair winds
    # around neither centre: refused naming where, not moved by a
    spec = pair_spec(rotor_design(tomllib.loads((SAMPLES / "narrow_tip_5_6.toml").read_text()), SAMPLES))
    female = np.asarray(build_pair(spec).section("female", 1e-3).exterior.coords)[:-1]
    path = tmp_path / "f.csv"
    a = spec.pair.center_distance
    write_points(path, female + (a + 5.0, 0.0))
    args = ["rotor", str(SAMPLES / "narrow_tip_5_6.toml"), "--female-points", str(path)]
    assert main(args) == 2
    err = capsys.readouterr().err
    assert "--female-points" in err and f"{a + 5:.4g} mm off the origin" in err and "Traceback" not in err


def test_a_spline_drawn_through_points_is_still_read_as_points(tmp_path):
    # a closed cubic through the outline's points (simple knots, as CAD draws a spline on points) runs
    # across the sharp tip corners: read as its points, fitted and cut at corners as measured points are
    spec = pair_spec(rotor_design(tomllib.loads((SAMPLES / "rack_involute_5_6.toml").read_text()), SAMPLES))
    male = np.asarray(build_pair(spec).section("male", 1e-3).exterior.coords)[:-1]
    path = tmp_path / "through.dxf"
    write_dxf(path, Drawing(splines=[("MALE", male)]))
    (entity,) = ezdxf.readfile(path).modelspace().query("SPLINE")
    assert len(set(entity.knots)) == len(entity.knots) - 6  # simple interior knots (ezdxf's own reading)
    curves = read_profile(path, "--male-points", "MALE")
    assert not carries_tangents(curves[0])
    assert isinstance(as_given(curves, 5), np.ndarray)


def test_apex_height_counts_from_the_tip_on_the_line_of_centres():
    # closed form (Rinder eq. 1): z = h1 alpha / 2 pi, alpha the male turn since the nearest tip's passage
    h1, z1, ref = 300.0, 5, 0.3
    for alpha in (-0.6, -0.1, 0.0, 0.25, 0.6):
        for k in (-2, 0, 1, 3):
            assert apex_height(ref + alpha + k * 2 * np.pi / z1, ref, h1, z1) == pytest.approx(h1 * alpha / (2 * np.pi))


def test_smoothing_of_an_exact_drawing_says_it_is_not_used(read_back, capsys):
    # the finding: --smoothing 0, 1e-6, 1e-4 changed nothing, silently; an exact drawing is used as drawn
    built = read_back("narrow_tip_5_6")
    args = ["rotor", str(SAMPLES / "narrow_tip_5_6.toml"), "--female-points", built["rows"]["female"]["path"]]
    args += ["--layer", "FEMALE_SPLINE", "--smoothing", "1e-4", "--json"]
    assert main(args) == 0
    out = capsys.readouterr()
    assert "smoothing of 0.0001 mm^2 is not used" in out.err
    assert json.loads(out.out)["blow_hole_area"] == pytest.approx(built["design"]["blow_hole_area"], rel=0.01)


def test_clearance_reads_each_rotor_from_its_layer(read_back, capsys):
    # export's two drawings (layers MALE_SPLINE and FEMALE_SPLINE, the female at (a, 0)) are a conjugate
    # pair (the design's): the contact zone's clearance is 0 within the stated accuracy
    built = read_back("rack_involute_5_6")
    rows = built["rows"]
    args = ["clearance", "--male-points", rows["male"]["path"], "--male-layer", "MALE_SPLINE"]
    args += ["--female-points", rows["female"]["path"], "--female-layer", "FEMALE_SPLINE"]
    args += ["--male-teeth", "5", "--female-teeth", "6", "--center-distance", "116", "--json", "--quiet"]
    assert main(args) == 0
    out = capsys.readouterr()
    result = json.loads(out.out)
    assert abs(result["min_normal_clearance"]) <= result["accuracy"]
    assert abs(result["max_normal_clearance"]) <= result["accuracy"]
    assert "place in the pair" in out.err


@pytest.fixture(scope="module")
def point_files(tmp_path_factory):
    """The rack-involute pair's own CSVs (1 µm chord) and its female grown by 3.9 µm (shapely's buffer)."""
    folder = tmp_path_factory.mktemp("interfere")
    m, f = folder / "m.csv", folder / "f.csv"
    args = ["rotor", str(SAMPLES / "rack_involute_5_6.toml"), "--male-csv", str(m), "--female-csv", str(f), "--quiet"]
    buffer = io.StringIO()
    with pytest.MonkeyPatch.context() as mp:
        mp.setattr(sys, "stdout", buffer)
        assert main(args) == 0
    grown = shapely.Polygon(read_points(f, "f")).buffer(0.0039, quad_segs=64)
    write_points(folder / "f_grown.csv", np.asarray(grown.exterior.coords)[:-1])
    return m, f, folder / "f_grown.csv"


@pytest.mark.parametrize(("female", "interferes"), [(1, False), (2, True)])
def test_interfere_judges_point_files_to_their_accuracy(point_files, capsys, female, interferes):
    # reference: the design is conjugate (touching, no interference); the female grown by 3.9 um (shapely's
    # offset, not rotorcad's) penetrates the male by 3.9 um and more, which the fixed 5 um let pass before
    design = str(SAMPLES / "rack_involute_5_6.toml")
    args = ["interfere", design, "--male-points", str(point_files[0]), "--female-points", str(point_files[female]), "--json"]
    assert main([*args, "--quiet"]) == int(interferes)
    result = json.loads(capsys.readouterr().out)
    assert result["interferes"] is interferes and result["tolerance_source"] == "points"
    assert 1e-3 <= result["tolerance"] < 3.9e-3  # the points' stated accuracy (1 um floor), below the offset
    if interferes:
        assert result["max_penetration"] >= 3.9e-3

"""The DXF splines of an exported rotor outline, read back by ezdxf and held to the exact outline.

References: ezdxf's own B-spline evaluation (``SPLINE.construction_tool()``, a third-party reader
and evaluator), the exact outline of the design sampled to a chord tolerance of 1e-5 mm (the
rotor's curves, not the spline code), shapely for distances and areas, and the closed-form
distance to a circle for the measured deviation of an arc's spline.
"""

from __future__ import annotations

import functools
import json
from pathlib import Path

import ezdxf
import numpy as np
import pytest
import shapely

from exports.dxf_spline import SplineToleranceError, hermite_spline, segment_spline
from rotorcad.cli.main import main
from rotorcad.curves import Arc
from rotorcad.design import load_rotor_design
from rotorcad.profile import Segment
from rotorcad.rotor_families import build_family
from rotorcad.rotor_pair import RotorPair

SAMPLES = Path(__file__).resolve().parents[1] / "samples"
REFERENCE_CHORD = 1e-5  # mm: chord tolerance of the exact outline the splines are held to


def _nearest(points: np.ndarray, ring: np.ndarray) -> np.ndarray:
    """Distance of each point to the closed polyline ``ring`` (shapely, an STRtree of its edges), mm."""
    edges = shapely.linestrings(np.stack([ring, np.roll(ring, -1, axis=0)], axis=1))
    return shapely.STRtree(edges).query_nearest(shapely.points(points), return_distance=True, all_matches=False)[1]


@pytest.fixture(scope="module", params=["rack_involute_5_6", "narrow_tip_5_6"])
def exported(request, tmp_path_factory):
    """Export one sample's DXF through the CLI; return its rows, the exact rotors and the spline points read back."""
    name = request.param
    out = tmp_path_factory.mktemp(name)
    design = SAMPLES / f"{name}.toml"
    argv = ["export", str(design), "--format", "dxf", "--out", str(out), "--no-housing", "--json", "--quiet"]
    with pytest.MonkeyPatch.context() as mp:  # capture stdout without capsys (module scope)
        import io
        import sys

        buffer = io.StringIO()
        mp.setattr(sys, "stdout", buffer)
        rc = main(argv)
    assert rc == 0
    rows = json.loads(buffer.getvalue())["files"]
    d = load_rotor_design(design)
    rotors = build_family(RotorPair(**d["pair"]), d["family"], d["params"])
    read = {}
    for row in rows:
        doc = ezdxf.readfile(row["path"])
        assert len(doc.audit().errors) == 0
        splines = list(doc.modelspace().query("SPLINE"))
        curves = [s.construction_tool() for s in splines]  # ezdxf's BSpline of each entity
        # every spline evaluated by ezdxf densely, its ends and the knot spans next to them included
        points = [np.array([(p.x, p.y) for p in c.points(np.linspace(0.0, c.max_t, 4000))]) for c in curves]
        read[row["body"]] = (row, curves, points)
    return rotors, read


def _xy(v) -> np.ndarray:
    """x, y of an ezdxf Vec3."""
    return np.array([v.x, v.y])


@functools.cache
def _exact(rotors, body: str) -> np.ndarray:
    """The exact outline, in mesh position as the export places it (male angle 0, female at (a, 0)); once per rotor."""
    shift = (0.0, 0.0) if body == "male" else (rotors.pair.center_distance, 0.0)
    return np.asarray(rotors.section(body, REFERENCE_CHORD).exterior.coords)[:-1] + shift


@pytest.mark.parametrize("body", ["male", "female"])
def test_every_spline_is_within_the_stated_tolerance_of_the_exact_outline(exported, body):
    rotors, read = exported
    row, _, points = read[body]
    exact = _exact(rotors, body)
    dev = max(float(_nearest(p, exact).max()) for p in points)
    # within what the file's row states (the reference ring's own chords added), and the measured
    # deviation it reports is an upper bound of the independent one. Before: one spline through the
    # whole outline, 236 um (male) and 3.6 um (female) from it where 2.5 um were stated.
    assert dev <= row["spline_deviation"] + REFERENCE_CHORD
    assert row["spline_deviation"] <= row["tolerance"]
    # and the exact outline is near the splines everywhere (the other way of the Hausdorff distance)
    edges = np.concatenate([np.stack([p[:-1], p[1:]], axis=1) for p in points])
    back = shapely.STRtree(shapely.linestrings(edges)).query_nearest(
        shapely.points(exact), return_distance=True, all_matches=False
    )[1]
    assert back.max() <= row["tolerance"]


def test_the_male_tip_corners_stay_sharp(exported):
    # The male tips of both samples are sharp corners (rack-involute: the README pair): the
    # splines meet there with a jump of direction, one per lobe at least, and near each corner the
    # splines keep to the exact outline (the old single spline swung 0.2 mm past the README male's tip).
    rotors, read = exported
    row, curves, points = read["male"]
    exact = _exact(rotors, "male")
    corners = []
    for i, c in enumerate(curves):
        nxt = curves[(i + 1) % len(curves)]
        t_out = _xy(c.derivative(c.max_t, 1)[1])
        t_in = _xy(nxt.derivative(0.0, 1)[1])
        cos = t_out @ t_in / (np.linalg.norm(t_out) * np.linalg.norm(t_in))
        if cos < np.cos(np.radians(5.0)):
            corners.append(_xy(c.point(c.max_t)))
    tip = rotors.pair.male_tip_radius
    at_tip = [q for q in corners if abs(np.hypot(*q) - tip) < 0.05 * tip]
    assert len(at_tip) >= rotors.pair.male_teeth
    everything = np.concatenate(points)
    for q in at_tip:
        near = everything[np.hypot(*(everything - q).T) < 1.0]  # within 1 mm of the corner
        assert len(near) > 10 and _nearest(near, exact).max() <= row["spline_deviation"] + REFERENCE_CHORD


@pytest.mark.parametrize("body", ["male", "female"])
def test_the_pieces_join_and_enclose_the_exact_area(exported, body):
    # CAD-side: one spline ends where the next starts (1e-6 mm, what CAD joins without a gap), and
    # the closed outline they make encloses the exact outline's area (shapely) to within its
    # perimeter times the stated tolerance (two closed curves within d of each other differ in area
    # by at most about perimeter x d), plus the chords of the evaluation.
    rotors, read = exported
    row, curves, points = read[body]
    starts = np.array([_xy(c.point(0.0)) for c in curves])
    ends = np.array([_xy(c.point(c.max_t)) for c in curves])
    assert np.hypot(*(np.roll(starts, -1, axis=0) - ends).T).max() <= 1e-6
    ring = np.concatenate([p[:-1] for p in points])
    exact = shapely.Polygon(_exact(rotors, body))
    area = shapely.Polygon(ring)
    assert area.is_valid
    bound = exact.length * (row["tolerance"] + REFERENCE_CHORD)
    assert abs(area.area - exact.area) <= bound
    # tighter in fact: the splines are within spline_deviation (some 0.1-1 um), the bound uses 2.5 um
    assert abs(area.area - exact.area) <= exact.length * (row["spline_deviation"] + REFERENCE_CHORD)


def test_arc_spline_deviation_is_an_upper_bound_of_the_closed_form_one():
    # On a circular arc the distance of a point q to the curve is | |q - c| - R | (closed form). The
    # deviation segment_spline measures must bound that of its spline (evaluated by ezdxf) and not
    # be loose by more than the chords of its own measurement.
    radius = 3.0
    arc = Arc((1.0, -2.0), radius, 0.0, 2.5)
    seg = Segment.at("tip arc", arc, np.linspace(0.0, 2.5, 4))  # 48 deg between samples: far off at first
    piece = segment_spline(seg, 1e-3)
    true = _circle_deviation(piece, arc)
    assert true <= piece.deviation <= 1e-3
    assert piece.deviation <= 4 * true + 1e-6
    with pytest.raises(SplineToleranceError, match="tip arc"):  # not met within the passes: refused, saying what was reached
        segment_spline(seg, 1e-9, passes=1)


def test_hermite_spline_interpolates_the_samples_with_their_tangents():
    # The control points of the C1 cubic Hermite B-spline (double interior knots): ezdxf evaluates
    # it through every sample, with the given tangent directions there (Piegl and Tiller, eq. 3.9).
    arc = Arc((0.0, 0.0), 2.0, 0.2, 1.7)
    s = np.linspace(0.2, 1.7, 6)
    p, t = arc.evaluate(s)
    control, knots = hermite_spline(p, t)
    curve = ezdxf.math.BSpline(np.column_stack([control, np.zeros(len(control))]), order=4, knots=knots)
    u = np.r_[0.0, np.cumsum(np.hypot(*np.diff(p, axis=0).T))]
    for ui, pi, ti in zip(u, p, t, strict=True):
        point, deriv = curve.derivative(min(ui, curve.max_t), 1)
        np.testing.assert_allclose(_xy(point), pi, atol=1e-12)
        np.testing.assert_allclose(_xy(deriv) / np.linalg.norm(_xy(deriv)), ti, atol=1e-12)


def _circle_deviation(piece, arc: Arc) -> float:
    """Largest | |q - c| - R | over the piece evaluated by ezdxf at 20 000 points, mm."""
    control = np.column_stack([piece.control_points, np.zeros(len(piece.control_points))])
    curve = ezdxf.math.BSpline(control, order=piece.degree + 1, knots=piece.knots)
    q = np.array([(v.x, v.y) for v in curve.points(np.linspace(0.0, curve.max_t, 20000))])
    return float(np.abs(np.hypot(*(q - np.asarray(arc.center)).T) - arc.radius).max())


def test_the_splines_read_back_as_one_closed_chain_of_the_exact_outline(exported):
    # The layer MALE_SPLINE read by the project's DXF reader (as `clearance --male-points` reads a
    # drawing): one SPLINE curve per entity, chained into one closed outline, on the exact outline
    # (sampled to 1e-5 mm) within the stated spline_deviation.
    from exports.dxf_profile import read_profile_dxf, sample_profile_dxf
    from rotorcad.curves import Spline

    rotors, read = exported
    row, curves, _ = read["male"]
    chain = read_profile_dxf(Path(row["path"]), "--male-points", layer="MALE_SPLINE")
    assert len(chain) == len(curves) and all(isinstance(c, Spline) for c in chain)
    pts = sample_profile_dxf(Path(row["path"]), "--male-points", layer="MALE_SPLINE", tolerance=1e-4)
    assert _nearest(pts, _exact(rotors, "male")).max() <= row["spline_deviation"] + REFERENCE_CHORD


def test_a_spline_tolerance_not_met_is_refused_naming_it(tmp_path, capsys, monkeypatch):
    # Where the splines cannot be brought within the tolerance (forced here: the refinement is
    # given no passes and a tolerance no cubic meets), the export is refused in one sentence naming
    # --tolerance and the deviation reached, exit status 2, and no file is left behind.
    import exports.dxf_spline as dxf_spline

    def no_passes(outline, tolerance, turn, shift):
        return [p for p in (dxf_spline.segment_spline(s, 1e-12, passes=0) for s in outline(0.1).segments) if p is not None]

    monkeypatch.setattr(dxf_spline, "placed_splines", no_passes)
    out = tmp_path / "o"
    design = SAMPLES / "rack_involute_5_6.toml"
    rc = main(["export", str(design), "--format", "stl,dxf", "--out", str(out), "--tolerance", "0.2", "--no-housing"])
    err = capsys.readouterr().err
    assert rc == 2 and "--tolerance 0.2 mm cannot be met by the DXF spline of the male" in err
    assert len(err.strip().splitlines()) == 1 and "Traceback" not in err
    assert not out.exists() or list(out.iterdir()) == []

"""Readers of user profiles: CSV points files (exports.csv_points) and DXF drawings
(exports.dxf_profile).

The inputs are written here by hand, by the standard library (zipfile, zlib) or by ezdxf from
closed-form geometry, never by the readers under test; each check names its reference.
"""

from __future__ import annotations

import os
import stat
import struct
import threading
import zipfile
import zlib

import ezdxf
import ezdxf.path
import numpy as np
import pytest

from exports import csv_points
from exports.csv_points import read_points
from exports.dxf_profile import read_profile_dxf, read_profile_points, sample_profile_dxf
from rotorcad.curves import Arc, Line, Spline
from rotorcad.errors import DesignError

LABEL = "--male-points"


def refused(call, *args, label: str = LABEL, **kwargs) -> str:
    """The sentence of the DesignError that ``call`` raises; it must be one sentence naming ``label``."""
    with pytest.raises(DesignError) as info:
        call(*args, **kwargs)
    sentence = info.value.sentence(label)
    assert sentence.startswith(label + " must be ")
    assert sentence.endswith(".") and "\n" not in sentence
    assert ". " not in sentence[:-1], sentence  # one sentence: no full stop before the end
    return sentence


def write(path, text: str | bytes, encoding: str = "utf-8"):
    path.write_bytes(text if isinstance(text, bytes) else text.encode(encoding))
    return path


def circle(n: int, r: float = 30.0) -> np.ndarray:
    """n points on a circle of radius r (mm), counter-clockwise from the +x axis."""
    t = 2 * np.pi * np.arange(n) / n
    return np.column_stack([r * np.cos(t), r * np.sin(t)])


SQUARE = np.array([[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]])


# ---------------------------------------------------------------------------------------------
# CSV points files
# ---------------------------------------------------------------------------------------------


def png_bytes() -> bytes:
    """A valid 1x1 greyscale PNG (PNG specification: signature, IHDR, IDAT, IEND chunks)."""

    def chunk(kind: bytes, data: bytes) -> bytes:
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data))

    ihdr = struct.pack(">IIBBBBB", 1, 1, 8, 0, 0, 0, 0)
    return b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", ihdr) + chunk(b"IDAT", zlib.compress(b"\x00\x80")) + chunk(b"IEND", b"")


def test_csv_binary_files_are_not_points_files(tmp_path):
    # A PNG image, a zip archive holding a valid CSV, NUL bytes, invalid UTF-8 with control bytes.
    png = write(tmp_path / "profile.csv", png_bytes())
    assert "not a CSV points file" in refused(read_points, png, LABEL)
    assert "PNG" in refused(read_points, png, LABEL)
    archive = tmp_path / "zipped.csv"
    with zipfile.ZipFile(archive, "w") as z:
        z.writestr("p.csv", "x,y\n0,0\n1,0\n1,1\n0,1\n")
    assert "ZIP" in refused(read_points, archive, LABEL)
    assert "NUL" in refused(read_points, write(tmp_path / "nul.csv", b"x,y\n0,0\x00\n1,0\n1,1\n0,1\n"), LABEL)
    junk = write(tmp_path / "junk.csv", b"x,y\n\xff\xfe\x01\x02\x03\x10\x90\x91\n")
    assert "not a CSV points file" in refused(read_points, junk, LABEL)
    high = write(tmp_path / "high.csv", bytes(range(0x80, 0x100)) * 8)
    assert "not a CSV points file" in refused(read_points, high, LABEL)


def test_csv_utf8_bom_and_latin1_text_are_read(tmp_path):
    body = "0,0\n1,0\n1,1\n0,1\n"
    utf8 = write(tmp_path / "utf8.csv", "\ufeff# Messung 20 °C, Rotor Ø 126\nx,y\n" + body)
    latin1 = write(tmp_path / "latin1.csv", "# Messung 20 °C, Rotor Ø 126, café\nx,y\n" + body, "latin-1")
    crlf = write(tmp_path / "crlf.csv", ("x,y\n" + body).replace("\n", "\r\n"))
    for path in (utf8, latin1, crlf):
        np.testing.assert_array_equal(read_points(path, LABEL), SQUARE)


def test_csv_special_paths_are_refused_without_reading(tmp_path):
    assert "it is a directory" in refused(read_points, tmp_path, LABEL)
    assert "no such file" in refused(read_points, tmp_path / "missing.csv", LABEL)
    if os.path.exists("/dev/null") and stat.S_ISCHR(os.stat("/dev/null").st_mode):
        assert "device" in refused(read_points, "/dev/null", LABEL)
    if hasattr(os, "mkfifo"):
        fifo = tmp_path / "pipe.csv"
        os.mkfifo(fifo)
        outcome: list[str] = []
        # Opening a FIFO for reading blocks until a writer appears: the reader must not open it.
        worker = threading.Thread(target=lambda: outcome.append(refused(read_points, fifo, LABEL)), daemon=True)
        worker.start()
        worker.join(timeout=5.0)
        assert not worker.is_alive(), "read_points blocked on a FIFO"
        assert outcome and "FIFO" in outcome[0]


def test_csv_larger_than_64_mib_is_refused_with_its_size(tmp_path):
    big = tmp_path / "big.csv"
    with open(big, "wb") as f:  # a sparse file: its size without writing 64 MiB
        f.write(b"x,y\n")
        f.truncate(64 * 2**20 + 1)
    sentence = refused(read_points, big, LABEL)
    assert "64 MiB" in sentence and str(64 * 2**20 + 1) in sentence


@pytest.mark.parametrize(
    "text",
    [
        "x,y\n0,0\n1,0\n1,1\n0,1\n",
        " X , Y \n0, 0\n1 ,0\n1,1\n0,1\n",
        "# comment\n\nx,y,z\n0,0,5\n1,0,5\n1,1,5\n0,1,5\n",
        "x;y\n0;0\n1;0\n1;1\n0;1\n",
        "x\ty\tz\n0\t0\t2\n1\t0\t2\n1\t1\t2\n0\t1\t2\n",
        "x   y\n0  0\n1    0\n 1 1\n0 1\n",
    ],
    ids=["comma", "case-and-blanks", "xyz", "semicolon", "tab", "blanks"],
)
def test_csv_header_and_separator_variants(tmp_path, text):
    np.testing.assert_array_equal(read_points(write(tmp_path / "p.csv", text), LABEL), SQUARE)


@pytest.mark.parametrize(
    ("text", "phrase"),
    [
        ("0,0\n1,0\n1,1\n0,1\n", "header line x,y is missing"),
        ("a,b\n0,0\n1,0\n1,1\n0,1\n", "line 1 reads 'a,b'"),
        ("x,y\n0,0\n1,0\n1;1\n0,1\n", "line 4 reads '1;1'"),
        ("x;y\n0;0\n1,5;0\n1;1\n0;1\n", "decimal commas"),
        ("x,y,z\n0,0,1\n1,0\n1,1,1\n0,1,1\n", "line 3"),
        ("x,y\n0,0\n1_0,0\n1,1\n0,1\n", "line 3"),
        ("", "no data"),
    ],
)
def test_csv_malformed_lines_are_refused_naming_the_line(tmp_path, text, phrase):
    assert phrase in refused(read_points, write(tmp_path / "p.csv", text), LABEL)


@pytest.mark.parametrize("bad", ["nan", "inf", "-Infinity", "1e999"])
def test_csv_non_finite_values_are_refused_naming_the_line(tmp_path, bad):
    path = write(tmp_path / "p.csv", f"# measured\nx,y\n0,0\n1,0\n{bad},1\n0,1\n")
    assert "line 5" in refused(read_points, path, LABEL)


def test_csv_consecutive_repeats_are_dropped(tmp_path):
    path = write(tmp_path / "p.csv", "x,y\n0,0\n0,0\n1,0\n1,0\n1,0\n1,1\n0,1\n0,1\n")
    np.testing.assert_array_equal(read_points(path, LABEL), SQUARE)


@pytest.mark.parametrize(
    ("text", "phrase"),
    [
        ("x,y\n0,0\n1,0\n1,1\n", "at least 4"),
        ("x,y\n0,0\n1,0\n1,0\n1,1\n", "3 distinct"),  # four lines, three points
        ("x,y\n2,3\n2,3\n2,3\n2,3\n2,3\n", "the same point"),
        ("x,y\n0,0\n1,2\n2,4\n3,6\n-5,-10\n", "one straight line"),
        # 1e-11 mm off a line 5 mm long: within 1e-9 of the extent, still a line
        ("x,y\n0,0\n1,1\n2,2.00000000001\n3,3\n", "one straight line"),
    ],
)
def test_csv_too_few_identical_or_collinear_points_are_not_a_profile(tmp_path, text, phrase):
    assert phrase in refused(read_points, write(tmp_path / "p.csv", text), LABEL)


def test_csv_nearly_straight_but_curved_points_are_a_profile(tmp_path):
    # 1e-6 mm off the line over 3 mm: 3e-7 of the extent, well above 1e-9: a (flat) profile.
    path = write(tmp_path / "p.csv", "x,y\n0,0\n1,0.000001\n2,0\n3,0\n")
    assert read_points(path, LABEL).shape == (4, 2)


def test_csv_more_than_the_point_limit_is_refused(tmp_path, monkeypatch):
    assert csv_points.MAX_POINTS == 2_000_000
    monkeypatch.setattr(csv_points, "MAX_POINTS", 10)  # the same check, without writing 2 M lines
    ok = write(tmp_path / "ten.csv", "x,y\n" + "".join(f"{x:.12g},{y:.12g}\n" for x, y in circle(10)))
    assert read_points(ok, LABEL).shape == (10, 2)
    eleven = write(tmp_path / "eleven.csv", "x,y\n" + "".join(f"{x:.12g},{y:.12g}\n" for x, y in circle(11)))
    assert "at most 10 points" in refused(read_points, eleven, LABEL)


def test_csv_round_trip_of_a_circle(tmp_path):
    # Reference: the closed form x = 30 cos t, y = 30 sin t written with 12 significant digits.
    pts = circle(360)
    csv_points.write_points(tmp_path / "c.csv", pts, comments=["circle r = 30 mm"])
    back = read_points(tmp_path / "c.csv", LABEL)
    np.testing.assert_allclose(back, pts, rtol=0, atol=1e-9)


# ---------------------------------------------------------------------------------------------
# DXF profiles, drawn with ezdxf from closed-form geometry
# ---------------------------------------------------------------------------------------------

R = 30.0  # mm, the circle of the arc-and-chord profile
TOL = 1e-4  # mm, chord tolerance of the sampled profiles (sample_profile_dxf's default)
ON = 1e-6  # mm, how far a sampled point may lie from the closed-form geometry


def save(doc, path):
    doc.saveas(path)
    return path


def polar(deg: float, r: float = R) -> tuple[float, float]:
    return (r * np.cos(np.radians(deg)), r * np.sin(np.radians(deg)))


# The circle r = 30 with two chords: arcs 0-80, 100-200 and 220-360 degrees (about the origin),
# chords 80-100 and 200-220 degrees. Exact area: pi r^2 minus the two circular segments of
# 20 degrees, each r^2 (theta - sin theta) / 2.
CHORDS = ((80.0, 100.0), (200.0, 220.0))
ARCS = ((0.0, 80.0), (100.0, 200.0), (220.0, 360.0))
SEGMENT = 0.5 * R**2 * (np.radians(20.0) - np.sin(np.radians(20.0)))
AREA = np.pi * R**2 - 2 * SEGMENT


def chorded_circle(path, order=(0, 1, 2, 3, 4), reverse_lines: bool = False, layer: str = "0", gap: float = 0.0):
    doc = ezdxf.new("R2000")
    msp = doc.modelspace()
    entities = []
    for a0, a1 in ARCS:
        entities.append(lambda a0=a0, a1=a1: msp.add_arc((0.0, 0.0), R, a0, a1, dxfattribs={"layer": layer}))
    for k, (a0, a1) in enumerate(CHORDS):
        p, q = polar(a0), polar(a1)
        if k == 0 and gap:
            q = (q[0] + gap, q[1])  # the chord stops short of the arc by ``gap`` mm
        if reverse_lines:
            p, q = q, p
        entities.append(lambda p=p, q=q: msp.add_line(p, q, dxfattribs={"layer": layer}))
    for i in order:
        entities[i]()
    return save(doc, path)


def on_chorded_circle(points: np.ndarray) -> np.ndarray:
    """Distance (mm) of each point from the arc-and-chord profile (closed form)."""
    r = np.hypot(*points.T)
    ang = np.degrees(np.arctan2(points[:, 1], points[:, 0])) % 360.0
    dist = np.abs(r - R)
    for a0, a1 in CHORDS:
        p, q = np.array(polar(a0)), np.array(polar(a1))
        u = (q - p) / np.hypot(*(q - p))
        along = np.clip((points - p) @ u, 0.0, np.hypot(*(q - p)))
        to_chord = np.hypot(*(points - p - along[:, None] * u).T)
        inside = (ang > a0) & (ang < a1)
        dist = np.where(inside, to_chord, dist)
    return dist


def signed_area(points: np.ndarray) -> float:
    x, y = points.T
    return 0.5 * float(np.sum(x * np.roll(y, -1) - np.roll(x, -1) * y))


def test_dxf_arcs_and_lines_lie_on_the_closed_form_profile(tmp_path):
    path = chorded_circle(tmp_path / "c.dxf")
    pts = sample_profile_dxf(path, LABEL, tolerance=TOL)
    assert on_chorded_circle(pts).max() < ON
    # Counter-clockwise, and the polygon of the samples loses at most TOL times the perimeter
    # (each chord cuts a sliver narrower than TOL) against the exact area.
    area = signed_area(pts)
    assert 0 < AREA - area < TOL * 2 * np.pi * R
    # chord tolerance: the sagitta r - sqrt(r^2 - (L/2)^2) of every chord on the circle
    r = np.hypot(*pts.T)
    on_arc = (np.abs(r - R) < ON) & (np.abs(np.roll(r, -1) - R) < ON)
    chord = np.hypot(*(np.roll(pts, -1, axis=0) - pts).T)[on_arc]
    chord = chord[chord < 10.0]  # not the two straight chords
    assert (R - np.sqrt(R**2 - (chord / 2) ** 2)).max() <= TOL
    assert len(pts) == len(np.unique(pts, axis=0))  # each joint once, no repeated end point


def test_dxf_arc_tangents_are_exact(tmp_path):
    chain = read_profile_dxf(chorded_circle(tmp_path / "c.dxf"), LABEL)
    arcs = [c for c in chain if isinstance(c, Arc)]
    assert len(arcs) == 3 and sum(isinstance(c, Line) for c in chain) == 2
    for arc in arcs:
        assert np.hypot(*arc.center) < 1e-12 and arc.radius == R and arc.s1 > arc.s0  # counter-clockwise
        s = np.linspace(arc.s0, arc.s1, 50)
        p, t = arc.evaluate(s)
        radial = (p - arc.center) / R
        assert np.abs(np.einsum("ij,ij->i", t, radial)).max() < 1e-12  # perpendicular to the radius
        assert np.abs(np.hypot(*t.T) - 1).max() < 1e-12
        assert (radial[:, 0] * t[:, 1] - radial[:, 1] * t[:, 0] > 0).all()  # turning counter-clockwise
    for a, b in zip(chain, chain[1:] + chain[:1], strict=True):  # end to end, closed
        assert np.hypot(*(a.end - b.start)) < 1e-9


def rotate_to(points: np.ndarray, start: tuple[float, float]) -> np.ndarray:
    return np.roll(points, -int(np.argmin(np.hypot(*(points - start).T))), axis=0)


def test_dxf_entity_order_and_direction_do_not_change_the_chain(tmp_path):
    reference = sample_profile_dxf(chorded_circle(tmp_path / "a.dxf"), LABEL)
    rng = np.random.default_rng(7)
    for k in range(3):
        order = tuple(int(i) for i in rng.permutation(5))
        other = sample_profile_dxf(chorded_circle(tmp_path / f"b{k}.dxf", order, reverse_lines=k != 1), LABEL)
        assert other.shape == reference.shape
        np.testing.assert_allclose(rotate_to(other, (R, 0.0)), rotate_to(reference, (R, 0.0)), rtol=0, atol=1e-9)


def test_dxf_gap_wider_than_the_tolerance_is_refused_naming_where(tmp_path):
    sentence = refused(sample_profile_dxf, chorded_circle(tmp_path / "g.dxf", gap=0.01), LABEL)
    assert "gap of 0.01 mm" in sentence
    x, y = polar(100.0)  # where the chord stops short: 0.01 mm beyond the arc's start at 100 degrees
    assert f"({x:.6f}, {y:.6f}) mm" in sentence and f"({x + 0.01:.6f}, {y:.6f}) mm" in sentence
    # 0.5 um is within the 1 um gap tolerance: joined
    assert len(sample_profile_dxf(chorded_circle(tmp_path / "ok.dxf", gap=0.0005), LABEL)) > 100
    # inside an open chain (a rack period in two polylines, the second 0.01 mm to the right)
    x = np.linspace(0.0, 20.0, 41)
    y = 3 * np.sin(2 * np.pi * x / 20)
    doc = ezdxf.new("R2000")
    doc.modelspace().add_lwpolyline(np.column_stack([x[:21], y[:21]]))
    doc.modelspace().add_lwpolyline(np.column_stack([x[20:] + 0.01, y[20:]]))
    sentence = refused(sample_profile_dxf, save(doc, tmp_path / "rack.dxf"), LABEL)
    assert "gap of 0.01 mm between (10.000000, 0.000000) mm and (10.010000, 0.000000) mm" in sentence


# A rounded rectangle 40 x 20 mm, corner radius 5, lower left corner at (-20, -10) (so that it
# runs around the origin), drawn clockwise as one closed polyline with bulges:
# bulge = -tan(90 deg / 4) turns each corner clockwise by a quarter turn (DXF reference, group 42).
W, H, RC = 40.0, 20.0, 5.0


def rounded_rectangle_cw() -> list[tuple[float, float, float]]:
    b = -np.tan(np.pi / 8)
    x0, y0, x1, y1 = -W / 2, -H / 2, W / 2, H / 2
    return [
        (x0, y0 + RC, 0.0),
        (x0, y1 - RC, b),
        (x0 + RC, y1, 0.0),
        (x1 - RC, y1, b),
        (x1, y1 - RC, 0.0),
        (x1, y0 + RC, b),
        (x1 - RC, y0, 0.0),
        (x0 + RC, y0, b),
    ]


def rounded_rectangle_distance(points: np.ndarray) -> np.ndarray:
    """Signed distance (mm) from the rounded rectangle (closed form: the rectangle shrunk by RC,
    offset by RC)."""
    q = np.abs(points) - np.array([W / 2 - RC, H / 2 - RC])
    return np.hypot(*np.maximum(q, 0.0).T) + np.minimum(q.max(axis=1), 0.0) - RC


def test_dxf_polyline_bulges_are_exact_arcs_in_every_polyline_kind(tmp_path):
    rows = rounded_rectangle_cw()
    doc = ezdxf.new("R2000")
    doc.modelspace().add_lwpolyline(rows, format="xyb", close=True)
    lw = sample_profile_dxf(save(doc, tmp_path / "lw.dxf"), LABEL)
    assert np.abs(rounded_rectangle_distance(lw)).max() < ON
    # drawn clockwise, read counter-clockwise; area w h - (4 - pi) r^2 less at most TOL x perimeter
    area = W * H - (4 - np.pi) * RC**2
    assert 0 <= area - signed_area(lw) < TOL * (2 * (W + H))
    chain = read_profile_dxf(tmp_path / "lw.dxf", LABEL)
    centres = {(abs(c.center[0]), abs(c.center[1])) for c in chain if isinstance(c, Arc)}
    assert centres == {(W / 2 - RC, H / 2 - RC)} and all(
        c.radius == pytest.approx(RC, abs=1e-12) for c in chain if isinstance(c, Arc)
    )
    # The same outline as an R12 2D POLYLINE, and as an LWPOLYLINE seen from below (extrusion
    # (0, 0, -1): object x = -world x, bulges turn the other way): the same points.
    doc12 = ezdxf.new("R12")
    doc12.modelspace().add_polyline2d(rows, format="xyb", close=True)
    r12 = sample_profile_dxf(save(doc12, tmp_path / "r12.dxf"), LABEL)
    below = ezdxf.new("R2000")
    mirrored_rows = [(-x, y, -b) for x, y, b in rows]
    below.modelspace().add_lwpolyline(mirrored_rows, format="xyb", close=True, dxfattribs={"extrusion": (0, 0, -1)})
    mirrored = sample_profile_dxf(save(below, tmp_path / "below.dxf"), LABEL)
    np.testing.assert_allclose(r12, lw, rtol=0, atol=1e-9)
    np.testing.assert_allclose(rotate_to(mirrored, tuple(lw[0])), lw, rtol=0, atol=1e-9)


def test_dxf_arc_seen_from_below_is_mirrored(tmp_path):
    # ARC with extrusion (0, 0, -1): centre (-10, 0) and 0..90 degrees in object coordinates are,
    # in world coordinates (arbitrary axis algorithm: object x = -world x), centre (10, 0) and the
    # quarter from (5, 0) to (10, 5), clockwise. ezdxf's own path of the entity is the reference.
    doc = ezdxf.new("R2000")
    arc = doc.modelspace().add_arc((-10.0, 0.0), 5.0, 0.0, 90.0, dxfattribs={"extrusion": (0, 0, -1)})
    reference = np.array([(v.x, v.y) for v in ezdxf.path.make_path(arc).flattening(1e-3)])
    save(doc, tmp_path / "a.dxf")
    (curve,) = read_profile_dxf(tmp_path / "a.dxf", LABEL)
    assert isinstance(curve, Arc) and np.allclose(curve.center, (10.0, 0.0), atol=1e-12, rtol=0)
    ends = {tuple(np.round(curve.start, 9)), tuple(np.round(curve.end, 9))}
    assert ends == {tuple(np.round(reference[0], 9)), tuple(np.round(reference[-1], 9))} == {(5.0, 0.0), (10.0, 5.0)}
    # ezdxf's path is a cubic Bezier quarter circle: within 2.7e-4 r of the circle
    assert np.abs(np.hypot(*(reference - (10.0, 0.0)).T) - 5.0).max() < 2.8e-4 * 5.0
    p, _ = curve.evaluate(np.linspace(curve.s0, curve.s1, 20))
    assert np.abs(np.hypot(*(p - (10.0, 0.0)).T) - 5.0).max() < 1e-12 and (p[:, 1] >= -1e-12).all()


# Polynomial curves as exact B-splines (control points = blossoms of the polynomial, de Casteljau
# / Ramshaw): the parabola y = x^2 and the cubic y = x^3 for x = 2t - 1 on [-1, 1].
PARABOLA = [(-1.0, 1.0), (0.0, -1.0), (1.0, 1.0)]  # degree 2 Bezier
# degree 3 with an interior knot at t = 0.5: control point i is the blossom at (t_i+1, t_i+2, t_i+3)
CUBIC_KNOTS = [0.0, 0.0, 0.0, 0.0, 0.5, 1.0, 1.0, 1.0, 1.0]


def cubic_control_points() -> list[tuple[float, float]]:
    knots = CUBIC_KNOTS
    out = []
    for i in range(5):
        u = knots[i + 1 : i + 4]
        out.append((2 * np.mean(u) - 1, float(np.prod([2 * v - 1 for v in u]))))
    return out


def test_dxf_splines_keep_the_drawings_knots_and_control_points(tmp_path):
    doc = ezdxf.new("R2000")
    msp = doc.modelspace()
    msp.add_open_spline(PARABOLA, degree=2, dxfattribs={"layer": "PARABOLA"})
    msp.add_line((1.0, 1.0), (-1.0, 1.0), dxfattribs={"layer": "PARABOLA"})  # closes it
    msp.add_open_spline(cubic_control_points(), degree=3, knots=CUBIC_KNOTS, dxfattribs={"layer": "CUBIC"})
    msp.add_line((1.0, 1.0), (1.0, -1.0), dxfattribs={"layer": "CUBIC"})
    msp.add_line((-1.0, -1.0), (1.0, -1.0), dxfattribs={"layer": "CUBIC"})
    path = save(doc, tmp_path / "s.dxf")
    par = sample_profile_dxf(path, LABEL, layer="PARABOLA", tolerance=1e-6)
    curved = par[par[:, 1] < 1.0 - 1e-12]
    assert len(curved) > 100 and np.abs(curved[:, 1] - curved[:, 0] ** 2).max() < 1e-12
    assert signed_area(par) == pytest.approx(4 / 3, abs=2 * 1e-6 * 5)  # area between y = 1 and y = x^2
    chain = read_profile_dxf(path, LABEL, layer="cubic")  # layer names without case
    spline = next(c for c in chain if isinstance(c, Spline))
    np.testing.assert_array_equal(spline.knots[0], CUBIC_KNOTS)
    cub = sample_profile_dxf(path, LABEL, layer="CUBIC", tolerance=1e-6)
    inside = (np.abs(cub[:, 0]) < 1 - 1e-12) & (cub[:, 1] > -1 + 1e-12)
    assert inside.sum() > 100 and np.abs(cub[inside, 1] - cub[inside, 0] ** 3).max() < 1e-12
    # chord tolerance against the closed form, across the inflection at x = 0: the distance of
    # (x, x^3) from each chord between its ends, probed at 19 points
    p = sample_profile_dxf(path, LABEL, layer="CUBIC", tolerance=TOL)
    p = p[(np.abs(p[:, 0]) <= 1) & (p[:, 1] >= -1)]
    p = p[np.argsort(p[:, 0])]
    a, d = p[:-1], np.diff(p, axis=0)
    x = a[:, :1] + d[:, :1] * np.linspace(0, 1, 21)[1:-1]
    off = np.abs(d[:, :1] * (x**3 - a[:, 1:]) - d[:, 1:] * (x - a[:, :1])) / np.hypot(*d.T)[:, None]
    assert off.max() <= TOL
    # tangents of the spline: the derivative of (x, x^3) is along (1, 3 x^2)
    s = np.linspace(spline.s0, spline.s1, 41)
    p, t = spline.evaluate(s)
    expected = np.column_stack([np.ones(len(s)), 3 * p[:, 0] ** 2])
    expected /= np.hypot(*expected.T)[:, None]
    expected *= np.sign(t[:, :1] @ [[1.0]])  # either direction of travel
    assert np.abs(t - expected).max() < 1e-12


def test_dxf_reversed_spline_gives_the_same_chain(tmp_path):
    def draw(path, reverse):
        doc = ezdxf.new("R2000")
        msp = doc.modelspace()
        cps = cubic_control_points()
        knots = CUBIC_KNOTS
        if reverse:  # the same curve travelled backwards: control points reversed, knots t -> 1 - t
            cps, knots = cps[::-1], [1.0 - k for k in knots[::-1]]
        msp.add_line((1.0, -1.0), (-1.0, -1.0))
        msp.add_open_spline(cps, degree=3, knots=knots)
        msp.add_line((1.0, -1.0), (1.0, 1.0))
        return save(doc, path)

    forward = sample_profile_dxf(draw(tmp_path / "f.dxf", False), LABEL)
    backward = sample_profile_dxf(draw(tmp_path / "b.dxf", True), LABEL)
    assert signed_area(forward) > 0 and signed_area(backward) > 0
    np.testing.assert_allclose(rotate_to(backward, (-1.0, -1.0)), rotate_to(forward, (-1.0, -1.0)), rtol=0, atol=1e-9)


def sine_spline(path, n: int):
    doc = ezdxf.new("R2000")
    x = np.linspace(0.0, 2 * np.pi, n)
    doc.modelspace().add_spline(np.column_stack([x, np.sin(x)]))
    return save(doc, path)


def distance_from_sine(points: np.ndarray) -> np.ndarray:
    """Distance (mm) from y = sin x, to first order: the vertical offset times cos of the slope."""
    return np.abs(points[:, 1] - np.sin(points[:, 0])) / np.hypot(1.0, np.cos(points[:, 0]))


def test_dxf_fit_point_spline_follows_the_sine_to_the_interpolation_error(tmp_path):
    # A cubic spline through fit points h apart deviates from a smooth f by about
    # (5/384) h^4 max|f''''| (de Boor, A Practical Guide to Splines, ch. V; max|sin''''| = 1),
    # 1.94e-5 mm for 33 points over 0..2 pi (h = pi/16). The parametric (chord-length) spline of
    # ezdxf/AutoCAD is allowed twice that; halving h must cut the error about 16 times (4th order).
    coarse = sample_profile_dxf(sine_spline(tmp_path / "s33.dxf", 33), LABEL, tolerance=1e-7)
    fine = sample_profile_dxf(sine_spline(tmp_path / "s65.dxf", 65), LABEL, tolerance=1e-7)
    bound = 5 / 384 * (np.pi / 16) ** 4
    assert distance_from_sine(coarse).max() < 2 * bound
    assert 10 < distance_from_sine(coarse).max() / distance_from_sine(fine).max() < 25
    assert coarse[0, 0] == pytest.approx(0.0, abs=1e-12) and coarse[-1, 0] == pytest.approx(2 * np.pi, abs=1e-12)
    # the fit points themselves lie on the spline (within the 1e-7 mm chord tolerance)
    x = np.linspace(0.0, 2 * np.pi, 33)
    fit = np.column_stack([x, np.sin(x)])
    seg_a, seg_b = coarse[:-1], coarse[1:]
    d = seg_b - seg_a
    u = np.clip(np.einsum("kij,ij->ki", fit[:, None, :] - seg_a[None], d) / np.einsum("ij,ij->i", d, d), 0, 1)
    gaps = np.hypot(*(seg_a[None] + u[..., None] * d[None] - fit[:, None, :]).transpose(2, 0, 1)).min(axis=1)
    assert gaps.max() < 2e-7


def test_dxf_rational_spline_and_circle_are_refused(tmp_path):
    doc = ezdxf.new("R2000")
    doc.modelspace().add_rational_spline([(0, 0), (1, 1), (2, 0)], weights=[1.0, 2.0, 1.0], degree=2)
    assert "rational" in refused(sample_profile_dxf, save(doc, tmp_path / "r.dxf"), LABEL)
    doc = ezdxf.new("R2000")
    doc.modelspace().add_circle((0, 0), 30.0)
    assert "not a circle" in refused(sample_profile_dxf, save(doc, tmp_path / "c.dxf"), LABEL)


def test_dxf_open_chains_run_around_the_origin_or_along_x(tmp_path):
    # One lobe: the arc r = 30 from 100 to 30 degrees drawn clockwise -> read with the polar
    # angle increasing. A rack period y = 3 sin(2 pi x / 20) drawn from x = 20 to 0 -> read with
    # x growing.
    doc = ezdxf.new("R2000")
    doc.modelspace().add_lwpolyline([(*polar(100.0), -np.tan(np.radians(70) / 4)), polar(30.0)], format="xyb")
    lobe = sample_profile_dxf(save(doc, tmp_path / "lobe.dxf"), LABEL)
    assert np.all(np.diff(np.arctan2(lobe[:, 1], lobe[:, 0])) > 0) and np.abs(np.hypot(*lobe.T) - R).max() < ON
    x = np.linspace(20.0, 0.0, 41)
    doc = ezdxf.new("R2000")
    doc.modelspace().add_lwpolyline(np.column_stack([x, 3 * np.sin(2 * np.pi * x / 20)]))
    rack = sample_profile_dxf(save(doc, tmp_path / "rack.dxf"), LABEL)
    np.testing.assert_array_equal(rack[:, 0], x[::-1])


def test_dxf_layers(tmp_path):
    doc = ezdxf.new("R2000")
    doc.layers.add("NOTES")
    msp = doc.modelspace()
    msp.add_lwpolyline([(0, 0), (1, 0), (1, 1), (0, 1)], close=True, dxfattribs={"layer": "MALE"})
    msp.add_lwpolyline([(5, 0), (6, 0), (6, 1), (5, 1)], close=True, dxfattribs={"layer": "Female"})
    msp.add_text("rotor", dxfattribs={"layer": "NOTES"})
    path = save(doc, tmp_path / "pair.dxf")
    assert "MALE, Female" in refused(sample_profile_dxf, path, LABEL) or "Female, MALE" in refused(
        sample_profile_dxf, path, LABEL
    )
    np.testing.assert_array_equal(sample_profile_dxf(path, LABEL, layer="female"), [[5, 0], [6, 0], [6, 1], [5, 1]])
    unknown = refused(sample_profile_dxf, path, LABEL, layer="HOUSING")
    assert "'HOUSING'" in unknown and "Female" in unknown and "MALE" in unknown
    assert "holds no" in refused(sample_profile_dxf, path, LABEL, layer="NOTES")
    # two outlines on one layer are not one profile
    doc = ezdxf.new("R2000")
    doc.modelspace().add_lwpolyline([(0, 0), (1, 0), (1, 1), (0, 1)], close=True)
    doc.modelspace().add_lwpolyline([(5, 0), (6, 0), (6, 1), (5, 1)], close=True)
    assert "one profile" in refused(sample_profile_dxf, save(doc, tmp_path / "two.dxf"), LABEL)
    empty = ezdxf.new("R2000")
    assert "holds no" in refused(sample_profile_dxf, save(empty, tmp_path / "empty.dxf"), LABEL)


def test_dxf_files_that_are_not_dxf_are_refused(tmp_path):
    csv_as_dxf = write(tmp_path / "p.dxf", "x,y\n0,0\n1,0\n1,1\n0,1\n")
    assert "a DXF drawing" in refused(sample_profile_dxf, csv_as_dxf, LABEL)
    assert "a DXF drawing" in refused(read_profile_dxf, write(tmp_path / "i.dxf", png_bytes()), LABEL)
    assert "a DXF drawing" in refused(read_profile_dxf, write(tmp_path / "t.dxf", "  0\nSECTION\n  2\nHEADER\n"), LABEL)
    assert "directory" in refused(read_profile_dxf, tmp_path, LABEL)


def wavy_outline(n: int = 200) -> np.ndarray:
    """A closed counter-clockwise outline r = 30 + 3 cos 5 theta (mm), n points."""
    t = 2 * np.pi * np.arange(n) / n
    r = 30.0 + 3.0 * np.cos(5 * t)
    return np.column_stack([r * np.cos(t), r * np.sin(t)])


def test_csv_and_dxf_of_the_same_points_agree(tmp_path):
    pts = wavy_outline()
    csv = write(tmp_path / "p.csv", "x,y\n" + "".join(f"{x:.17g},{y:.17g}\n" for x, y in pts))
    doc = ezdxf.new("R2000")
    doc.modelspace().add_lwpolyline(pts, format="xy", close=True)
    dxf = save(doc, tmp_path / "p.dxf")
    from_csv, from_dxf = read_profile_points(csv, LABEL), read_profile_points(dxf, LABEL)
    assert from_dxf.shape == from_csv.shape == pts.shape
    np.testing.assert_allclose(from_dxf, from_csv, rtol=0, atol=1e-9)
    np.testing.assert_allclose(from_csv, pts, rtol=0, atol=1e-12)


def test_read_profile_points_recognises_dxf_by_content(tmp_path):
    pts = wavy_outline(60)
    doc = ezdxf.new("R2000")
    doc.modelspace().add_lwpolyline(pts, format="xy", close=True)
    ascii_dxf = save(doc, tmp_path / "profile.txt")  # not named .dxf: recognised by "0 / SECTION"
    doc.saveas(tmp_path / "profile.bin", fmt="bin")  # binary DXF sentinel
    for path in (ascii_dxf, tmp_path / "profile.bin"):
        np.testing.assert_allclose(read_profile_points(path, LABEL), pts, rtol=0, atol=1e-12)
    assert "not a CSV points file" in refused(read_points, tmp_path / "profile.bin", LABEL)
    assert "DXF" in refused(read_points, ascii_dxf, LABEL)
    assert "FIFO" not in refused(read_profile_points, tmp_path / "missing.dxf", LABEL)

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

import numpy as np
import pytest

from exports import csv_points
from exports.csv_points import read_points
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

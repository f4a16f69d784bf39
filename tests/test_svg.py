"""SVG of outlines, read back by a third-party parser.

References: svgelements (an SVG 1.1 parser that applies the viewBox and the transforms) reads the
written file; the outlines it gives back must be rotorcad's points within 1 nm (the file's
resolution), with y up (the drawing's frame) once the viewBox is undone, and the document must be well-formed XML
(xml.etree). Read at 25.4 pixels per inch, one pixel is one millimetre.
"""

from __future__ import annotations

import xml.etree.ElementTree as ET

import numpy as np
import pytest
import shapely

from exports.dxf import Drawing
from exports.svg import write_svg
from rotorcad.cli.main import main
from rotorcad.gears.involute_gear import InvoluteGear
from rotorcad.gears.rack import GearRack

svgelements = pytest.importorskip("svgelements", reason="svgelements reads the SVG back (test dependency)")


def read_paths(path) -> list[np.ndarray]:
    """Every path of the file as the points its move and line segments end at, in the drawing's frame.

    svgelements gives viewport coordinates (the transforms and the viewBox applied: y down, the
    viewBox's corner at 0, its own px per mm); they are mapped back with the viewBox and the scale
    svgelements reports (viewport width / viewBox width).
    """
    svg = svgelements.SVG.parse(str(path), ppi=25.4, reify=True)
    box = svg.viewbox
    scale = svg.width / box.width
    out: list[np.ndarray] = []
    for element in svg.elements():
        if isinstance(element, svgelements.Path):
            ends = (seg.end for seg in element.segments() if isinstance(seg, (svgelements.Move, svgelements.Line)))
            vp = np.array([(p.x, p.y) for p in ends])
            out.append(np.column_stack([vp[:, 0] / scale + box.x, -(vp[:, 1] / scale + box.y)]))
    return out


def test_gear_outline_read_back(tmp_path):
    g = InvoluteGear(17, 3.0, shift=0.3)
    pts = g.outline().points
    d = Drawing(mark_size=3.0)
    d.outlines.append(("GEAR", pts))
    d.circles.append(("PITCH", (0.0, 0.0), g.pitch_radius))
    path = tmp_path / "g.svg"
    write_svg(path, d)
    root = ET.parse(path).getroot()  # well-formed, one group per layer
    assert root.tag.endswith("svg") and root.attrib["width"].endswith("mm")
    ids = {e.attrib.get("id") for e in root.iter() if e.tag.endswith("g")}
    assert {"GEAR", "PITCH"} <= ids
    back = read_paths(path)
    assert len(back) == 1
    got = back[0]
    assert got.shape == pts.shape
    np.testing.assert_allclose(got, pts, atol=1e-6)  # y up, mm, 1 nm resolution
    ring = shapely.Polygon(pts)
    assert shapely.Polygon(got).symmetric_difference(ring).area < ring.length * 1e-6  # points moved by < 1 nm
    circles = [e for e in svgelements.SVG.parse(str(path), ppi=25.4, reify=True).elements() if isinstance(e, svgelements.Circle)]
    svg = svgelements.SVG.parse(str(path), ppi=25.4, reify=True)
    assert len(circles) == 1 and circles[0].implicit_r * svg.viewbox.width / svg.width == pytest.approx(g.pitch_radius, abs=1e-6)


def test_cli_svg_of_gear_pair_and_rack(tmp_path, capsys):
    path = tmp_path / "p.svg"
    assert main(["gear", "--teeth", "17", "--module", "3", "--mate-teeth", "29", "--rack", "60", "--svg", str(path)]) == 0
    capsys.readouterr()
    back = read_paths(path)
    areas = sorted(shapely.Polygon(p).area for p in back)
    gear, mate = InvoluteGear(17, 3.0, tolerance=1e-4), InvoluteGear(29, 3.0, tolerance=1e-4)  # the command's tolerance
    expected = sorted(shapely.Polygon(x.outline().points).area for x in (gear, mate))
    np.testing.assert_allclose(areas, expected, atol=1e-3)  # perimeters < 1000 mm, points within 1 nm
    rack = read_paths(tmp_path / "p_rack.svg")
    assert len(rack) == 1
    section = GearRack(60.0, 3.0, tolerance=1e-4).section
    assert shapely.Polygon(rack[0]).area == pytest.approx(section.area, abs=section.length * 1e-6)

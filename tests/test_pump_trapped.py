"""The trapped space of a gear pump (newuser5 F11: promised by the README, not given by ``pump``).

``rotorcad.pump_trapped`` measures the space on the gears' outlines (the loop between the two driving
contacts, one pitch along each outline). References, none of which reads that loop:

- the flow kinematics (``GearPump.trapped_volume``): the space changes at b (q'(u_new) - q'(u_old)) / w1,
  from the tip radii and the contacts' places on the line of action alone (Kollek & Osinski's eq. 2 read
  at both contacts);
- the closed form of where it is smallest: the two contacts symmetric about the pitch point C
  (u_new = C - p_b / 2 from T1);
- for an absolute area, shapely's union of the two gears slightly dilated: the trapped space is then a
  hole of the union; its area at dilations d and 2 d, extrapolated linearly to d = 0;
- the new user's FFT of one base pitch's delivery (0.09525, 0.03581, 0.02211 of the mean flow) for the
  harmonics now listed in the table.
"""

from __future__ import annotations

import contextlib
import io
import json

import numpy as np
import pytest
import shapely

from rotorcad.cli.main import main
from rotorcad.gears.involute_gear import InvoluteGear
from rotorcad.geometry import rotate
from rotorcad.pump import GearPump
from rotorcad.pump_trapped import trapped_areas

PUMPS = {
    "z11 x0.3 equal": lambda: GearPump(InvoluteGear(teeth=11, module=4.0, shift=0.3), 20.0, 1500.0),
    "z17/29 (F1's pair)": lambda: GearPump(
        InvoluteGear(teeth=17, module=3.0, shift=0.3), 20.0, 1500.0, InvoluteGear(teeth=29, module=3.0, shift=-0.1)
    ),
    "z14 with backlash": lambda: GearPump(
        InvoluteGear(teeth=14, module=2.0, shift=0.2), 15.0, 3000.0, InvoluteGear(teeth=14, module=2.0, shift=0.2), 28.83
    ),
}


@pytest.mark.parametrize("name", PUMPS)
def test_the_outlines_space_changes_as_the_flow_kinematics_say(name):
    p = PUMPS[name]()
    phi, kinematic = p.trapped_volume(33)  # mm³, relative to the start of the double contact
    area = trapped_areas(p, phi)
    geometric = (area - area[0]) * p.face_width
    assert np.abs(geometric - kinematic).max() < 2e-3 * np.ptp(kinematic) + 1e-3


def test_smallest_where_the_contacts_lie_symmetric_about_the_pitch_point():
    p = PUMPS["z11 x0.3 equal"]()
    g = p.gear
    start, _, c, _ = p.line_of_action()
    at = (c - g.base_pitch / 2 - start) / g.base_radius  # rad: u_new = C - p_b / 2
    phi = np.linspace(at - 0.01, at + 0.01, 21)
    area = trapped_areas(p, phi)
    assert abs(phi[int(np.argmin(area))] - at) <= 0.001 + 1e-12


def _hole_area(p: GearPump, turn: float, dilation: float) -> float:
    """The trapped area as the holes of the union of both gears dilated by ``dilation`` (mm²)."""
    pair = p.pair
    gear, mate = pair.gear, pair.mate
    aw, a = pair.working_pressure_angle, pair.working_center_distance
    t1 = gear.base_radius * np.array([np.cos(aw), -np.sin(aw)])
    new = t1 + (p.line_of_action()[0] + gear.base_radius * turn) * np.array([np.sin(aw), np.cos(aw)])
    c1 = np.arctan2(new[1], new[0]) - gear.half_angle(float(np.hypot(*new)))
    rel = new - np.array([a, 0.0])
    c2 = np.arctan2(rel[1], rel[0]) - mate.half_angle(float(np.hypot(*rel)))
    g1 = shapely.Polygon(rotate(gear.outline(1e-5).points, c1)).buffer(dilation, quad_segs=32)
    g2 = shapely.Polygon(rotate(mate.outline(1e-5).points, c2) + np.array([a, 0.0])).buffer(dilation, quad_segs=32)
    union = g1.union(g2)
    return sum(shapely.Polygon(ring).area for ring in union.interiors)


def test_the_absolute_area_is_the_hole_between_the_two_gears():
    p = PUMPS["z14 with backlash"]()  # backlash: one hole between the two driving contacts
    phi, _ = p.trapped_volume(5)
    for turn, area in zip(phi[1:-1], trapped_areas(p, phi[1:-1], 1e-5), strict=True):
        d = 2e-4
        hole = 2.0 * _hole_area(p, turn, d) - _hole_area(p, turn, 2 * d)
        assert area == pytest.approx(hole, abs=2e-3)


def _pump(*args: str) -> tuple[dict, str]:
    out = io.StringIO()
    with contextlib.redirect_stdout(out):
        assert (
            main(["pump", "--teeth", "11", "--module", "4", "--shift", "0.3", "--face-width", "20", "--speed", "1500", *args])
            == 0
        )
    return (json.loads(out.getvalue()) if "--json" in args else {}), out.getvalue()


def test_pump_reports_the_trapped_space_of_a_spur_pump():
    result, _ = _pump("--json")
    p = PUMPS["z11 x0.3 equal"]()
    _, kinematic = p.trapped_volume(1025)
    assert result["trapped_volume_change"] == pytest.approx(-kinematic.min(), rel=2e-3)
    assert result["trapped_volume_max"] == pytest.approx(result["trapped_area_max"] * 20.0)
    assert result["trapped_double_contact_deg"] == pytest.approx((result["contact_ratio"] - 1.0) * 360.0 / 11)
    helical, _ = _pump("--json", "--helix-angle", "15")
    assert "trapped_volume_max" not in helical  # the sections' spaces join along the face


def test_the_table_lists_the_harmonics_asked():
    _, table = _pump("--harmonics", "3")
    rows = [line for line in table.splitlines() if "│ harmonics." in line]
    assert len(rows) == 3
    user_fft = (0.09525, 0.03581, 0.02211)  # the new user's FFT of b w (r_a² - r_w² - s²) over one base pitch
    for row, expected in zip(rows, user_fft, strict=True):
        assert float(row.split("│")[2]) == pytest.approx(expected, rel=1e-3)
    assert "harmonics.k at k x 275 Hz, over the mean flow" in " ".join(table.split())

"""Screw-rotor inspection from points: the normal deviation from the nominal outline, per flank.

References: shapely's offset curve (``buffer``: every point of it lies exactly d from the outline,
GEOS) and points moved by a known distance along the outline's normal, chosen by the test, with
a known rotation and uniform scatter.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest
import shapely

from rotorcad.design.files import load_rotor_design
from rotorcad.design.rotors import build_pair, merge_pair
from rotorcad.inspection.rotor_inspection import inspect_rotor
from rotorcad.roles import ToothFlank

SAMPLE = Path(__file__).resolve().parents[1] / "samples" / "rack_involute_5_6.toml"
SCATTER = 1.5e-3


def turned(points: np.ndarray, angle: float) -> np.ndarray:
    c, s = math.cos(angle), math.sin(angle)
    return points @ np.array([[c, s], [-s, c]])


@pytest.fixture(scope="module")
def male():
    rotors = build_pair(merge_pair(load_rotor_design(SAMPLE), {}))
    return rotors.male_outline(1e-4), rotors.pair.male_teeth


def test_an_offset_outline_turned_by_an_angle(male):
    outline, lobes = male
    offset = 8e-3  # mm: shapely's buffer of the outline polygon, round joins
    ring = np.asarray(shapely.Polygon(outline.points).buffer(offset, quad_segs=64).exterior.coords)[:-1]
    angle = 0.1  # rad
    result = inspect_rotor(turned(ring, angle), outline, lobes)
    assert result.rotation == pytest.approx(angle, abs=1e-5)  # 0.5 µm on the tip circle
    # the outline's chord tolerance (0.1 µm) and the fitted rotation's share
    assert np.abs(result.deviation - offset).max() < 0.3e-3
    summary = result.summary()
    assert summary["lobes_measured"] == list(range(lobes))
    for side in ToothFlank:
        assert summary[side.value]["rms_normal_deviation"] == pytest.approx(offset, abs=0.3e-3)


def test_flanks_moved_apart_are_told_apart(male):
    outline, lobes = male
    pts, normals = outline.points, outline.normals
    r = np.hypot(*pts.T)
    tip_angle = math.atan2(*pts[np.argmax(r)][::-1])
    pitch = 2 * math.pi / lobes
    rel = np.remainder(np.arctan2(pts[:, 1], pts[:, 0]) - tip_angle + pitch / 2, pitch) - pitch / 2
    upper = r > r.min() + 0.5 * (r.max() - r.min())  # the outer half of the lobe: clear of the root
    left, right = upper & (rel > 0.02), upper & (rel < -0.02)  # clear of the tip
    moved = {"left": 6e-3, "right": -4e-3}  # mm along the outward normal: + more material
    rng = np.random.default_rng(3)
    chosen = left | right
    shift = np.where(left, moved["left"], moved["right"])[chosen] + rng.uniform(-SCATTER, SCATTER, chosen.sum())
    measured = pts[chosen] + shift[:, None] * normals[chosen]
    result = inspect_rotor(turned(measured, -0.03), outline, lobes)
    # the best-fit rotation takes up the part of the flanks' moves that a turn makes: a turn by e
    # moves a point p along the normal n by -e n.(z x p) = -e g; least squares over the points gives
    # e = sum(shift g) / sum(g^2) (linearised: the remainder e^2 r is below 1e-6 mm)
    p, n = pts[chosen], normals[chosen]
    g = n[:, 1] * p[:, 0] - n[:, 0] * p[:, 1]
    e = float(np.sum(shift * g) / np.sum(g * g))
    assert result.rotation == pytest.approx(-0.03 + e, abs=1e-6)
    assert np.abs(result.deviation - (shift - e * g)).max() < 0.3e-3  # the chord tolerance and the rotation's remainder
    summary = result.summary()
    for side in moved:
        mask = left[chosen] if side == "left" else right[chosen]
        assert summary[side]["points"] == int(mask.sum())
        assert summary[side]["max_normal_deviation"] == pytest.approx(float((shift - e * g)[mask].max()), abs=0.3e-3)
        assert summary[side]["min_normal_deviation"] == pytest.approx(float((shift - e * g)[mask].min()), abs=0.3e-3)

"""Kollek & Osinski eq. 2 beside the textbook swept volume 2 pi b m^2 z n (issue 23).

Reference: the closed form that links the two for a standard gear pair, derived here from ISO
21771 geometry (r = z m / 2, r_a = r + m, r_b = r cos alpha, p_b = pi m cos alpha; the contact
ratio of two equal gears at the standard centre distance eps = (2 sqrt(r_a^2 - r_b^2) - 2 r sin alpha) / p_b):
mean of eq. 2 = b w (r_a^2 - r^2 - p_b^2 (eps^2/4 - eps/2 + 1/3)), so that
mean / (2 pi b m^2 z n / 60) = (z + 1 - (pi cos alpha)^2 (eps^2/4 - eps/2 + 1/3)) / z.
"""

from __future__ import annotations

import json

import numpy as np
import pytest

from rotorcad.cli.main import main
from rotorcad.gear import InvoluteGear
from rotorcad.pump import GearPump

A20 = np.radians(20.0)


@pytest.mark.parametrize("z", [17, 20, 30, 60])  # no undercut at 20 deg: the whole involute works
def test_eq_2_over_the_swept_volume_is_the_closed_form(z):
    m, b, n = 2.5, 18.0, 1450.0
    p = GearPump(InvoluteGear(z, m, A20, 0.0, 0.0), b, n)
    r = z * m / 2
    ra, rb, pb = r + m, r * np.cos(A20), np.pi * m * np.cos(A20)
    eps = (2 * np.sqrt(ra**2 - rb**2) - 2 * r * np.sin(A20)) / pb
    assert p.contact_ratio == pytest.approx(eps, rel=1e-9)
    assert p.swept_volume_flow == pytest.approx(2 * np.pi * b * m**2 * z * n / 60, rel=1e-12)
    ratio = (z + 1 - (np.pi * np.cos(A20)) ** 2 * (eps**2 / 4 - eps / 2 + 1 / 3)) / z
    assert p.mean_flow / p.swept_volume_flow == pytest.approx(ratio, rel=1e-6)


def test_pump_reports_both_flows_and_the_defaults_it_took(capsys):
    args = ["pump", "--teeth", "12", "--module", "3", "--face-width", "20", "--speed", "1500", "--json"]
    assert main([*args, "--shift", "0.3"]) == 0
    r = json.loads(capsys.readouterr().out)
    assert r["method"] == "paper" and r["mean_flow"] == r["mean_flow_paper"]
    # 2 pi b m^2 z n in L/min
    assert r["mean_flow_swept_volume"] == pytest.approx(2 * np.pi * 20 * 9 * 12 * 1500 * 1e-6, rel=1e-12)
    assert r["mean_flow_paper_to_swept_volume"] == pytest.approx(r["mean_flow_paper"] / r["mean_flow_swept_volume"])
    # --shift was given; no mate: two equal gears
    assert set(r["defaults"]) == {"--pressure-angle", "--helix-angle", "--addendum", "--mate-teeth"}
    assert r["defaults"]["--mate-teeth"] == "12 and --mate-shift 0.3 (default: two equal gears)"
    assert r["defaults"]["--pressure-angle"] == "20 deg (default: ISO 53 basic rack)"
    assert main([*args, "--method", "swept-volume"]) == 0
    r = json.loads(capsys.readouterr().out)
    assert r["method"] == "swept-volume" and r["mean_flow"] == r["mean_flow_swept_volume"]
    assert "--shift" in r["defaults"]

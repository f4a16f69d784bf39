"""`hob_tip_thickness` is what CONTRACT.md says it is (newuser5 F14: documented only in the source).

Reference: the closed form of the ISO 53 basic rack's tool tooth (h_a0 = 1.25 m, alpha = 20 deg,
tip rounding rho = 0.38 m): its width at 5 % of the rack depth (2.25 m) above its tip lies on the tip
rounding, a circle tangent to the tip line and to the flank, whose centre is rho above the tip and
rho / tan(55 deg) inside the corner of the flank with the tip line (the new user read 1.337 mm, m = 2).
"""

from __future__ import annotations

import contextlib
import io
import json

import numpy as np
import pytest

from rotorcad.cli.main import main


def _closed_form(m: float) -> float:
    alpha, rho, depth = np.radians(20.0), 0.38 * m, 2.25 * m
    half_tip = np.pi * m / 4 - 1.25 * m * np.tan(alpha)  # half the straight-flank tooth at its tip line
    centre = half_tip - rho / np.tan(np.radians(55.0))  # the interior angle of tip line and flank: 90 + 20 deg
    h = 0.05 * depth
    return 2.0 * (centre + np.sqrt(rho**2 - (rho - h) ** 2))


@pytest.mark.parametrize("module", [2.0, 5.0])
def test_hob_tip_thickness_is_the_rounded_tips_width_at_five_percent(module):
    out = io.StringIO()
    with contextlib.redirect_stdout(out):
        assert main(["hob", "--teeth", "20", "--module", str(module), "--json"]) == 0
    got = json.loads(out.getvalue())["racks"]["gear"]["hob_tip_thickness"]
    assert got == pytest.approx(_closed_form(module), abs=2e-3 * module)
    if module == 2.0:
        assert got == pytest.approx(1.337, abs=5e-4)  # the new user's reading

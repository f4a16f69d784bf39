"""Kollek & Osinski's eq. (1), the undercut model `cut` reports as ``undercut_radius_model``.

A new user's finding: read as the OCR prints it, eq. (1) put the undercut point of z = 11, m = 4
at 22.57 mm, above the 22 mm pitch circle (the simulation and the exact envelope: 20.75 mm), ignored
the helix angle (below the base circle at beta = 30 deg) and gave a radius for z = 12 at 30 deg,
which the same output called not undercut. References: (a) the model's own geometry solved
exactly here, an extended involute of the base circle at the constant distance p from the line
of action meeting the involute (hob/undercut.py's docstring), which the quartic truncates;
(b) the brute-force cut of the involute by the tool's tip rounding (tests/undercut_brute.py);
(c) the transverse-section closed form z_min = 2 cos(beta) / sin^2(alpha_t) = 11.54 at 30 deg.
"""

from __future__ import annotations

import numpy as np
import pytest
from scipy.optimize import brentq
from undercut_brute import ALPHA, M, Y, brute_undercut_radius

from hob.undercut import kollek_model, model_keys
from rotorcad.gears.involute_gear import InvoluteGear


def extended_involute_model(z: int, m: float, x: float = 0.0) -> float:
    """r'_z (mm) where the extended involute of the base circle at offset p meets the involute, solved exactly.

    In units of r_z: the extended involute's point at roll gamma lies at radius sqrt(w^2 + gamma^2),
    w = 1 - p / r_z, polar angle gamma - atan(gamma / w); the involute's at roll phi at sqrt(1 + phi^2),
    polar angle phi - atan(phi), on the other side of the base tangent: equal radii give
    phi = sqrt(w^2 + gamma^2 - 1), equal angles gamma - atan(gamma / w) = -(phi - atan(phi)).
    """
    r_z = z * m / 2 * np.cos(ALPHA)
    p = r_z - (z * m / 2 - (Y - x) * m) / np.cos(ALPHA)  # eq. (1), first line
    w = 1 - p / r_z

    def polar(gamma):
        phi = np.sqrt(w * w + gamma * gamma - 1)
        return gamma - np.arctan(gamma / w) + phi - np.arctan(phi)

    lo = np.sqrt(1 - w * w) + 1e-12  # phi = 0: the extended involute on the base circle
    gamma = brentq(polar, lo, 3.0, xtol=1e-15)
    return float(r_z * np.sqrt(w * w + gamma * gamma))


@pytest.mark.parametrize(("z", "x"), [(8, 0.0), (11, 0.0), (14, 0.0), (16, 0.0), (17, 0.0), (11, 0.2)])
def test_eq1_as_read_is_the_series_of_its_extended_involute_model(z, x):
    """gamma = (sin v - v cos v)/(1 - cos v), phi = v - gamma, r'_z = r_z sqrt(1 + phi^2): the model solved exactly, to 2 um."""
    model = kollek_model(z, M, ALPHA, x, Y)
    assert model.undercut
    assert model.active_base_radius == pytest.approx(extended_involute_model(z, M, x), abs=2e-3)


@pytest.mark.parametrize(("z", "x"), [(8, 0.0), (11, 0.0), (16, 0.0), (17, 0.0), (11, 0.2)])
def test_model_radius_on_the_flank_and_its_deviation_from_the_brute_force_cut(z, x):
    """On the flank between base and pitch circle (22.57 mm above the 22 mm pitch circle for z = 11 before),
    0.25-0.34 p above the undercut point the tool's tip rounding really cuts; the deviation key says it."""
    g = InvoluteGear(z, M, shift=x)
    keys = model_keys(g)
    radius, brute = keys["undercut_radius_model"], brute_undercut_radius(z, M, x)
    assert g.base_radius < radius < g.pitch_radius
    p = kollek_model(z, M, ALPHA, x, Y).p
    assert 0.25 * p < radius - brute < 0.34 * p
    assert keys["undercut_radius_model_deviation"] == pytest.approx(radius - brute, abs=1e-6)
    assert f"{radius - brute:+.3f} mm" in keys["undercut_model_note"]


@pytest.mark.parametrize(("z", "undercut"), [(11, True), (12, False)])
def test_helical_gear_in_the_transverse_section(z, undercut):
    """beta = 30 deg: z_min = 11.54, so 11 is undercut (model on the flank, near the exact point) and 12 has no model radius."""
    beta = np.radians(30.0)
    alpha_t = np.arctan(np.tan(ALPHA) / np.cos(beta))
    assert bool(z < 2 * Y * np.cos(beta) / np.sin(alpha_t) ** 2) is undercut
    g = InvoluteGear(z, M, helix_angle=beta)
    keys = model_keys(g)
    if not undercut:
        assert keys["undercut_radius_model"] is None and keys["undercut_radius_model_deviation"] is None
        return
    radius = keys["undercut_radius_model"]
    assert g.base_radius < radius < g.pitch_radius  # was 22.565 mm, below the 23.417 mm base circle
    # the model's own error, 0.25-0.34 p, against the exact envelope (brute-forced for spur gears above)
    p = g.base_radius - (g.pitch_radius - Y * M) / np.cos(alpha_t)
    assert 0.25 * p < radius - g.form_radius < 0.34 * p

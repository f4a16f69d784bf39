"""``rotorcad hob`` on an undercut gear: hobbable (the hob makes the undercut), but said, with the shift that avoids it.

A new user's finding: ``hob --teeth 8 --module 4`` read ``hobbable: true`` with no word of the
undercut that ``gear`` and ``cut`` report, while an undercut rotor reads "the female is undercut at
r = ...". References: the closed forms of the basic rack (ISO 21771 sec. 5; Niemann & Winter vol. II
sec. 21): undercut below z_min = 2 (y - x) cos(beta) / sin^2(alpha_t), avoided from
x_min = y - z sin^2(alpha_t) / (2 cos beta), y = h_a0* - rho_a0* (1 - sin alpha) = 1.0 for the ISO 53
rack; the form radius of a gear that is not undercut, where the tool's effective tip line meets the
line of action: sqrt(r_b^2 + (r sin(alpha) - (y - x) m / sin(alpha))^2); and the undercut point by
brute force: the largest radius of the involute (the envelope of the rack's straight flank, foot
of the normal from the pitch point) that the tool's tip rounding (its centre's path, rolled) cuts.
"""

from __future__ import annotations

import json

import numpy as np
import pytest
from undercut_brute import ALPHA, M, Y, brute_undercut_radius

from hob.undercut import gear_undercut
from rotorcad.cli.main import main
from rotorcad.gears.involute_gear import InvoluteGear


def hob_json(capsys, *args: str) -> dict:
    assert main(["hob", *args, "--json"]) == 0
    return json.loads(capsys.readouterr().out)


@pytest.mark.parametrize(("z", "x"), [(8, 0.0), (11, 0.0), (16, 0.0), (17, 0.0), (11, 0.2), (8, 0.3)])
def test_undercut_radius_is_the_brute_force_undercut_point(z, x):
    """The radius stated is where the tip rounding stops cutting the involute (brute force, to 1 nm)."""
    cut = gear_undercut(InvoluteGear(z, M, shift=x))
    assert cut.undercut
    assert cut.radius == pytest.approx(brute_undercut_radius(z, M, x), abs=1e-6)


@pytest.mark.parametrize(("z", "x"), [(18, 0.0), (11, 0.5), (8, 0.6)])
def test_not_undercut_form_radius_is_the_tip_line_on_the_line_of_action(z, x):
    """Not undercut: no radius, and the involute begins where the effective tip line meets the line of action."""
    g = InvoluteGear(z, M, shift=x)
    cut = gear_undercut(g)
    assert not cut.undercut and cut.radius is None and cut.note is None
    assert brute_undercut_radius(z, M, x) is None
    r = z * M / 2
    closed = np.hypot(r * np.cos(ALPHA), r * np.sin(ALPHA) - (Y - x) * M / np.sin(ALPHA))
    assert g.form_radius == pytest.approx(closed, abs=1e-6)


@pytest.mark.parametrize("z", [8, 11, 16, 17, 18])
def test_limit_shift_and_min_teeth_closed_forms(z):
    """x_min = 1 - z sin^2(alpha) / 2 (h_a0* = 1 effective), z_min = 2 / sin^2(alpha) = 17.1; the envelope agrees."""
    cut = gear_undercut(InvoluteGear(z, M))
    assert cut.limit_shift == pytest.approx(1 - z * np.sin(ALPHA) ** 2 / 2, abs=1e-4)
    assert cut.min_teeth == pytest.approx(2 / np.sin(ALPHA) ** 2, abs=1e-3)
    assert cut.undercut == (z < 2 / np.sin(ALPHA) ** 2)
    # the exact envelope turns undercut where the closed form says: a hundredth of a module either side
    assert InvoluteGear(z, M, shift=cut.limit_shift - 0.01).undercut
    assert not InvoluteGear(z, M, shift=cut.limit_shift + 0.01).undercut


@pytest.mark.parametrize(("z", "undercut"), [(11, True), (12, False)])
def test_helical_limit_in_the_transverse_section(z, undercut):
    """beta = 30 deg: z_min = 2 cos(beta) / sin^2(alpha_t) = 11.54 (the new user's figure), so 11 is undercut, 12 not."""
    beta = np.radians(30.0)
    alpha_t = np.arctan(np.tan(ALPHA) / np.cos(beta))
    g = InvoluteGear(z, M, helix_angle=beta)
    cut = gear_undercut(g)
    assert cut.min_teeth == pytest.approx(2 * Y * np.cos(beta) / np.sin(alpha_t) ** 2, rel=1e-9)
    assert cut.min_teeth == pytest.approx(11.54, abs=0.01)
    assert cut.undercut is undercut is g.undercut
    x_min = Y - z * np.sin(alpha_t) ** 2 / (2 * np.cos(beta))
    assert cut.limit_shift == pytest.approx(x_min, rel=1e-9)
    assert InvoluteGear(z, M, helix_angle=beta, shift=x_min - 0.01).undercut
    assert not InvoluteGear(z, M, helix_angle=beta, shift=x_min + 0.01).undercut


def test_hob_says_the_gear_is_undercut(capsys):
    """z = 8: hobbable (the hob makes the undercut), no reason, a note with the radius and the shift; keys."""
    out = hob_json(capsys, "--teeth", "8", "--module", "4")
    assert out["hobbable"] is True and out["reasons"] == []
    assert out["undercut"] is True
    assert out["undercut_radius"] == pytest.approx(brute_undercut_radius(8, M), abs=1e-6)  # 15.227 mm
    assert out["undercut_limit_shift"] == pytest.approx(1 - 8 * np.sin(ALPHA) ** 2 / 2, abs=1e-4)  # 0.532
    (note,) = [n for n in out["notes"] if "undercut" in n]
    assert "r = 15.227 mm" in note and "x >= 0.532" in note and "no reason against hobbing" in note
    plain = hob_json(capsys, "--teeth", "18", "--module", "4")
    assert plain["undercut"] is False and plain["undercut_radius"] is None
    assert not [n for n in plain["notes"] if "undercut" in n]

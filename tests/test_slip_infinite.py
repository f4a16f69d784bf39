"""Infinite slip (Rinder eq. 4: v_g / v_t where a rotor's tangential velocity v_t vanishes) is JSON
null with ``value_infinite: true`` (CONTRACT.md), judged relative to the velocities' own scale."""

from __future__ import annotations

import json

import numpy as np
import pytest

from rotorcad.cli.main import main
from rotorcad.meshing.analysis import slip


def test_a_tangential_velocity_zero_to_rounding_gives_infinite_slip():
    # v_t of 1e-15 m/s beside 20 m/s is a zero computed with rounding (the rack-involute's female
    # printed a slip of 1.17e15); 0 / 0 is pure rolling (nan); a slip of 2484 stays a number.
    vg = np.array([5.0, 5.0, 0.0, 5.0, -3.0])
    vt = np.array([1e-15, 20.0, 0.0, 5.0 / 2484.0, 1e-14])
    s = slip(vg, vt)
    assert s[0] == np.inf and s[4] == -np.inf and np.isnan(s[2])
    assert s[1] == pytest.approx(0.25) and s[3] == pytest.approx(2484.0)


def test_rack_involute_female_slip_is_null_and_infinite_at_its_base_circle(capsys):
    # Rinder sec. 3.2: the rack-involute's only infinite slip is where its involute reaches the
    # base circle, r2w cos 26 deg (26 deg: the rack's sealing flank angle; r2w = a z2 / (z1 + z2)).
    assert main(["rotor", "samples/rack_involute_5_6.toml", "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    female = data["max_slip_female"]
    assert female["value"] is None and female["value_infinite"] is True
    assert female["female_radius"] == pytest.approx(116 * 6 / 11 * np.cos(np.radians(26.0)), abs=2e-3)
    male = data["max_slip_male"]
    assert male["value_infinite"] is False and male["value"] == pytest.approx(1.0, abs=1e-6)

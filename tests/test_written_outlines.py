"""``rotor --male-csv/--female-csv`` write the outlines to the chord ``--tolerance`` asked for.

Reference: the analytic pieces of the design (their exact curves evaluated at 4000 parameters
each, not the chord sampler) against the polygon written; the largest distance of the exact
curve from the written chords is the chord error."""

from __future__ import annotations

import tomllib
from pathlib import Path

import numpy as np
import pytest
import shapely

from exports.csv_points import read_points
from rotorcad.cli.main import main
from rotorcad.design import rotor_design
from rotorcad.rotor_build import build_pair, pair_spec

SAMPLES = Path(__file__).resolve().parents[1] / "samples"


@pytest.fixture(scope="module")
def rotors():
    return build_pair(pair_spec(rotor_design(tomllib.loads((SAMPLES / "narrow_tip_5_6.toml").read_text()), SAMPLES)))


def exact_lobe(lobe) -> np.ndarray:
    """Points of a lobe's exact curves, 4000 per piece."""
    return np.vstack([s.curve.evaluate(np.linspace(s.curve.s0, s.curve.s1, 4000))[0] for s in lobe.segments])


@pytest.mark.parametrize("tol", [1e-2, 1e-4])
def test_written_outlines_follow_the_tolerance(rotors, tol, tmp_path):
    # Finding 12: the files were the same at --tolerance 1e-3 .. 1e-5 (0.93 um chords).
    m, f = tmp_path / "m.csv", tmp_path / "f.csv"
    args = ["rotor", str(SAMPLES / "narrow_tip_5_6.toml"), "--quiet", "--tolerance", str(tol)]
    assert main([*args, "--male-csv", str(m), "--female-csv", str(f)]) == 0
    for written, lobe in ((read_points(m), rotors.male_lobe()), (read_points(f), rotors.female_lobe())):
        exact = exact_lobe(lobe)
        exact = exact[np.isfinite(exact).all(axis=1)]
        error = shapely.distance(shapely.points(exact), shapely.LinearRing(written)).max()
        assert 0.3 * tol < error <= 1.05 * tol

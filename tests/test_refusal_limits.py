"""A refusal prints its limit with enough digits to show that the refused value misses it."""

from __future__ import annotations

import re

import pytest

from rotorcad.cli.main import main
from rotorcad.errors import limit_text


def test_a_tip_radius_just_below_the_pitch_radius_reads_below_it(capsys):
    # The female pitch radius r2w = a z2 / (z1 + z2) = 116 * 6 / 11 = 63.27272727... mm (closed
    # form); 63.2727272 misses it by 7e-8 mm and was refused as "at least 63.2727 mm".
    assert main(["rotor", "samples/narrow_tip_5_6.toml", "--female-tip-radius", "63.2727272"]) == 2
    err = capsys.readouterr().err
    limit = float(re.search(r"pitch radius ([0-9.]+) mm", err).group(1))
    assert limit > 63.2727272
    assert limit == pytest.approx(116 * 6 / 11, abs=1e-7)


def test_limits_keep_six_digits_when_the_value_is_far():
    assert limit_text(116 * 6 / 11, 60.0) == "63.2727"
    assert limit_text(116 * 6 / 11, "x") == "63.2727"
    assert limit_text(1.0, 1.0) == "1.0"  # equal values: the limit's own repr

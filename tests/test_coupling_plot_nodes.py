"""The coupling --plot's h_min-over-z panel is solved on a coarser grid (newuser5 F14: --plot cost 5x).

Reference: the film solved on the result's own grid (201 nodes, ``rotorcad.coupling.analyse``'s
default): the panel's curves at ``PLOT_NODES`` stay within 1 % of it (measured 0.5 % on the README
coupling), so the picture shows the same trend.
"""

from __future__ import annotations

import math

import numpy as np

from rotorcad.cli.coupling_cmd import PLOT_NODES
from rotorcad.coupling import GearCoupling, Hold, sweep_teeth


def test_the_panels_grid_keeps_h_min_within_one_percent():
    c = GearCoupling(
        teeth=40,
        module=4.0,
        face_width=32.0,
        speed_rpm=8000.0,
        power_kw=4000.0,
        viscosity=0.02,
        pressure_viscosity=2e-8,
        misalignment=math.radians(0.3),
    )  # the README's coupling
    teeth = np.array([20, 40, 80])
    for hold in (Hold.MODULE, Hold.TOOTH_LOAD):
        fine = sweep_teeth(c, teeth, hold=hold)
        coarse = sweep_teeth(c, teeth, nodes=PLOT_NODES, hold=hold)
        assert np.all(np.isfinite(fine))
        assert np.abs(coarse / fine - 1.0).max() < 0.01

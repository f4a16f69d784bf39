"""The undercut point P' near the undercut limit, against a brute-force intersection of the curves.

Issue 26, item 3: where the undercut barely exists, P' lies just outside the base circle and the
gear's polar-angle bracket (rotorcad.gear.InvoluteGear._undercut_point) now brackets it in a second
pass instead of falling back to a 2-D solve. Reference (independent of that bracket): the generated
involute and fillet sampled as 2049-point polylines crowded towards their starts, intersected by
shapely (the crossing farthest from the centre), then refined on the exact curves by
scipy.optimize.root; no crossing means the two are joined at the base circle. This was the gear's
own fallback before, with 1025 evenly spaced samples, which missed crossings in the first chord
(e.g. z = 19, x = 0, tip radius 0.2: P' 12 nm outside the base circle, 5.5e-6 rad along the
fillet; the old outline kept a 36 um loop of involute inside the fillet). P' must agree to
1e-9 mm over the grid z = 3..40, x = -0.5..1, tool tip radius 0..0.38 m (every undercut gear).
"""

from __future__ import annotations

import math

import numpy as np
import pytest
import shapely
from scipy import optimize

from rotorcad.errors import DesignError
from rotorcad.gear import InvoluteGear

DEG = math.pi / 180


def p_prime_by_intersection(flank, fillet, s_int: float, s_a: float) -> tuple[float, float]:
    """Tool parameters (flank, fillet) of P' by polyline intersection refined on the exact curves."""
    # samples crowded towards the curves' starts (spacing ~ u^2): P' near the undercut limit lies
    # within micrometres of the base circle, in the first 1e-5 of the fillet, where evenly spaced
    # chords of two almost tangent curves miss the crossing
    u = np.linspace(0.0, 1.0, 2049) ** 3
    sf = fillet.s0 + (fillet.s1 - fillet.s0) * u
    sl = s_int + (s_a - s_int) * u
    pf, pl = fillet.evaluate(sf)[0], flank.evaluate(sl)[0]
    pts = shapely.get_coordinates(shapely.LineString(pf).intersection(shapely.LineString(pl)))
    if len(pts) == 0:
        return s_int, fillet.s0
    x = pts[np.argmax(np.hypot(*pts.T))]
    i = int(np.argmin(np.hypot(*(pl - x).T)))
    j = int(np.argmin(np.hypot(*(pf - x).T)))

    def gap(v):
        return flank.evaluate(v[0])[0][0] - fillet.evaluate(v[1])[0][0]

    sol = optimize.root(gap, [sl[i], sf[j]], method="hybr", options={"xtol": 1e-14})
    return float(sol.x[0]), float(sol.x[1])


def undercut_gears():
    for z in range(3, 41):
        for x in np.linspace(-0.5, 1.0, 7):
            for rho in (0.0, 0.1, 0.2, 0.3, 0.38):
                try:
                    g = InvoluteGear(z, 2.0, 20 * DEG, shift=float(x), tip_radius_factor=rho, tolerance=1e-4)
                    g.outline()
                except DesignError:  # pointed or severed teeth are refused: no outline to compare
                    continue
                if g.undercut:
                    yield g


@pytest.fixture(scope="module")
def grid():
    return list(undercut_gears())


def test_grid_holds_the_cases_near_the_limit(grid):
    # z = 17..21 at x = 0 (ISO 21771: z_min = 2 / sin^2(20 deg) = 17.1 for a sharp rack) are in it
    assert len(grid) > 300
    assert any(g.teeth == 17 and g.shift == 0.0 and g.tip_radius_factor == 0.38 for g in grid)


def test_undercut_point_equals_the_brute_force_intersection(grid):
    worst = 0.0
    for g in grid:
        cuts = {name: (s0, s1) for name, s0, s1, _ in g._half_tooth.cuts}
        s_a, s_low = cuts["involute"]
        fil_s0 = cuts["fillet"][0]
        a0, a1 = g._cuts["flank"].roll()
        gen = g._generated
        ref_flank, ref_fillet = p_prime_by_intersection(gen["flank"], gen["tip arc"], -a0 / a1, s_a)
        new = gen["flank"].evaluate(np.array([s_low]))[0][0], gen["tip arc"].evaluate(np.array([fil_s0]))[0][0]
        ref = gen["flank"].evaluate(np.array([ref_flank]))[0][0], gen["tip arc"].evaluate(np.array([ref_fillet]))[0][0]
        for p, q in zip(new, ref, strict=True):
            worst = max(worst, float(np.hypot(*(p - q))))
        assert worst <= 1e-9, (g.teeth, g.shift, g.tip_radius_factor, worst)


@pytest.mark.parametrize("helix_deg", [0.0, 25.0])
def test_one_point_of_a_tool_cut_is_the_envelope_engines(helix_deg):
    # the undercut point's root search evaluates the fillet one point at a time (ToolCut.point);
    # reference: the envelope engine's generated curves (rotorcad.envelope.conjugate), tip arc
    # (the fillet, trochoid) and flank (the involute), at the same tool parameters
    g = InvoluteGear(17, 2.0, 20 * DEG, helix_angle=helix_deg * DEG, tolerance=1e-4)
    for name, s0, s1 in (("tip arc", g._tool.arc_end, math.pi), ("flank", 0.0, g._cuts["flank"].length)):
        cut, gen = g._cuts[name], g._generated[name]
        s = np.linspace(s0, s1, 41)
        ref = gen.evaluate(s)[0]
        got = np.array([[cut.point(float(v)).real, cut.point(float(v)).imag] for v in s])
        assert np.abs(got - ref).max() <= 1e-9, name

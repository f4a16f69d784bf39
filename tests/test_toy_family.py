"""The README's worked example "Adding a profile family", built the way it says and checked.

The toy family (a rack of two tangent circular arcs) is taken from the README's text: its module
and its registry line are executed as printed, then a design file naming it is run through
``rotorcad rotor design.toml --json`` in this process. The written outlines are compared with the
closed-form envelope of the two arcs (not with rotorcad's envelope engine): by the law of gearing
(Litvin, *Gear Geometry and Applied Theory*, eq. 6.1.7) a rack point is in contact when its normal
passes through the pitch point C, and every normal of a circular arc passes through its centre K,
so the contact point is K + rho (C - K) / |C - K|, reached when C is at polar angle theta about K:
at male angle t = (K_y cot(theta) - K_x) / r1w (C at rack x = -r1w t). That point, carried into
each rotor's frame, is the rotor's flank.
"""

from __future__ import annotations

import json
import re
from pathlib import Path

import numpy as np
import pytest
from scipy.spatial import cKDTree

from rotorcad.cli.main import main
from rotorcad.families.registry import FAMILIES, register

README = (Path(__file__).resolve().parents[1] / "README.md").read_text()
SECTION = README.split("### Adding a profile family", 1)[1].split("\n## ", 1)[0]
MODULE, REGISTRY_LINE = re.findall(r"```python\n(.*?)```", SECTION, re.S)[:2]

Z1, Z2, A = 5, 6, 116.0
MALE_TIP, MALE_ROOT, FEMALE_TIP, FEMALE_ROOT = 63.0, 45.0, 71.0, 53.0
LOBE_SHARE = 0.4
# chord tolerance of the outlines --male-csv and --female-csv write: the meshing analysis's sections,
# sampled at the pair's default tolerance (ScrewRotors.tolerance, 1e-3 mm; --tolerance does not reach them)
TOLERANCE = 1e-3

DESIGN = f"""
[pair]
male_teeth = {Z1}
female_teeth = {Z2}
center_distance = {A}
male_tip_radius = {MALE_TIP}
male_root_radius = {MALE_ROOT}
female_tip_radius = {FEMALE_TIP}
female_root_radius = {FEMALE_ROOT}
lead = 300.0
length = 190.0

[profile]
family = "two-arcs"
lobe_share = {LOBE_SHARE}
"""


@pytest.fixture(scope="module")
def registered():
    """The README's module and registry line, executed as printed; unregistered afterwards."""
    assert MODULE.startswith("# rotorcad/families/two_arcs.py") and REGISTRY_LINE.strip() == 'register("two-arcs", two_arcs)'
    scope: dict = {"__name__": "two_arcs"}
    exec(compile(MODULE, "README.md (two_arcs.py)", "exec"), scope)
    exec(compile(REGISTRY_LINE, "README.md (registry line)", "exec"), {"register": register, "two_arcs": scope["two_arcs"]})
    yield FAMILIES["two-arcs"]
    del FAMILIES["two-arcs"]


@pytest.fixture(scope="module")
def built(registered, tmp_path_factory):
    """``rotorcad rotor design.toml --json`` with the outlines written: (rc, JSON, male, female points)."""
    import contextlib
    import io

    d = tmp_path_factory.mktemp("toy")
    (d / "design.toml").write_text(DESIGN)
    male, female = d / "male.csv", d / "female.csv"
    out = io.StringIO()
    with contextlib.redirect_stdout(out):
        rc = main(
            [
                "rotor",
                str(d / "design.toml"),
                "--json",
                "--male-csv",
                str(male),
                "--female-csv",
                str(female),
                "--quiet",
            ]
        )
    return (
        rc,
        json.loads(out.getvalue()),
        np.loadtxt(male, delimiter=",", skiprows=2),
        np.loadtxt(female, delimiter=",", skiprows=2),
    )


def arc_envelope(rotor: str, samples: int = 100_001) -> list[np.ndarray]:
    """The rotor's flanks cut by the two arcs, all lobes, in closed form (module docstring), (n, 2) mm each."""
    r1 = A * Z1 / (Z1 + Z2)
    h1, d1 = MALE_TIP - r1, r1 - MALE_ROOT
    p = 2 * np.pi * r1 / Z1
    s = ((p / 2) ** 2 + (h1 + d1) ** 2) / (2 * (h1 + d1))  # the arcs touch: |K2 - K1| = rho1 + rho2
    rho1, rho2 = LOBE_SHARE * s, (1 - LOBE_SHARE) * s
    k1, k2 = np.array([p / 4, h1 - rho1]), np.array([3 * p / 4, rho2 - d1])
    phi = np.arctan2(k2[1] - k1[1], k2[0] - k1[0])
    z = Z1 if rotor == "male" else Z2
    out = []
    for k, rho, (lo, hi) in ((k1, rho1, (phi, np.pi - phi)), (k2, rho2, (np.pi + phi, 2 * np.pi - phi))):
        theta = np.linspace(lo, hi, samples)
        t = (k[1] / np.tan(theta) - k[0]) / r1  # male angle at which C lies at polar angle theta about K
        qx, qy = k[0] + rho * np.cos(theta), k[1] + rho * np.sin(theta)  # the contact point, rack frame
        fixed = np.column_stack([r1 + qy, qx + r1 * t])  # fixed frame: O1 at the origin, C = (r1, 0)
        if rotor == "male":  # the male turns counter-clockwise by t
            own, turn = fixed, -t
        else:  # the female, centred at (a, 0), turns clockwise by t z1 / z2
            own, turn = fixed - [A, 0.0], t * Z1 / Z2
        c, sn = np.cos(turn), np.sin(turn)
        flank = np.column_stack([c * own[:, 0] - sn * own[:, 1], sn * own[:, 0] + c * own[:, 1]])
        for j in range(z):  # the next lobe is cut one rack period later: turned by 2 pi / z
            g = 2 * np.pi * j / z
            out.append(flank @ np.array([[np.cos(g), np.sin(g)], [-np.sin(g), np.cos(g)]]))
    return out


def distance_to_chains(points: np.ndarray, chains: list[np.ndarray], closed: bool = False) -> np.ndarray:
    """Distance of each point to the nearest of the polylines ``chains`` (nearest vertex, then its two segments)."""
    vertices = np.vstack(chains)
    chain = np.concatenate([np.full(len(c), i) for i, c in enumerate(chains)])
    n = len(vertices)
    d, i = cKDTree(vertices).query(points)
    for step in (-1, 1):
        j = (i + step) % n if closed else np.clip(i + step, 0, n - 1)
        ok = chain[j] == chain[i]
        a, ab = vertices[i], vertices[j] - vertices[i]
        w = np.clip(np.einsum("ij,ij->i", points - a, ab) / np.maximum(np.einsum("ij,ij->i", ab, ab), 1e-300), 0.0, 1.0)
        d = np.where(ok, np.minimum(d, np.hypot(*(points - a - w[:, None] * ab).T)), d)
    return d


def test_the_readme_family_registers_its_parameter_from_the_signature(registered):
    assert registered.params["lobe_share"].default == 0.5
    assert registered.params["lobe_share"].allowed == "between 0.2 and 0.8 (the lobe arc's share of the two radii)"


@pytest.mark.parametrize("rotor", ["male", "female"])
def test_the_readme_family_through_the_cli_is_the_closed_form_envelope_of_its_arcs(built, rotor):
    rc, summary, male, female = built
    assert rc == 0 and summary["male_teeth"] == Z1 and summary["female_teeth"] == Z2
    points = male if rotor == "male" else female
    exact = arc_envelope(rotor)
    on_curve = distance_to_chains(points, exact)
    # the written vertices are points of the exact flanks (a few at the lobe's seams lie on chords)
    assert np.median(on_curve) < 1e-8
    assert on_curve.max() <= TOLERANCE
    # and the outline misses no part of them: every exact point lies within the chord tolerance of it
    back = distance_to_chains(np.vstack(exact)[::7], [points], closed=True)
    assert back.max() <= TOLERANCE * 1.01
    tip, root = (MALE_TIP, MALE_ROOT) if rotor == "male" else (FEMALE_TIP, FEMALE_ROOT)
    r = np.hypot(*points.T)  # the samples reach the tip and root circles within the chord tolerance
    # (a flank that only touches a circle at one point need not be sampled there: 0.6 um on the female)
    assert abs(tip - r.max()) <= TOLERANCE and abs(r.min() - root) <= TOLERANCE


def test_the_readme_family_refuses_a_parameter_out_of_its_declared_range(registered, tmp_path, capsys):
    (tmp_path / "design.toml").write_text(DESIGN.replace(f"lobe_share = {LOBE_SHARE}", "lobe_share = 0.9"))
    rc = main(["rotor", str(tmp_path / "design.toml"), "--json"])
    err = capsys.readouterr().err
    assert rc == 2 and "[profile] lobe_share must be between 0.2 and 0.8" in err and "Traceback" not in err

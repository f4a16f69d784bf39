"""The export's faster arithmetic gives the numbers of the plain expressions it replaces, bit for bit
(issue 26): the Hermite check's point-to-chain distances made in place and by the least squared
distance (exports.hermite), against the textbook clipped-projection distance evaluated naively; and
the command's early end (rotorcad.cli.main.run: no finalisation of every object) keeps what Python's
exit does that a user sees; a DXF written in one piece holds the bytes of ezdxf's own saveas; the
exact STEP's Hermite check bounded by the chords beside each point splits the intervals the full
check splits."""

from __future__ import annotations

import numpy as np

from exports.hermite import _gap_to_chords, distance_to_chains


def _plain_distance_to_chains(points: np.ndarray, chains: np.ndarray) -> np.ndarray:
    # the distance of p to the segment a + s d, s clipped to [0, 1] (the foot of the perpendicular),
    # as the plain expression the module had; the least over the chain's segments, NaN rows left out
    ax, ay = chains[:, None, :-1, 0], chains[:, None, :-1, 1]
    dx, dy = chains[:, None, 1:, 0] - ax, chains[:, None, 1:, 1] - ay
    px, py = points[:, :, None, 0], points[:, :, None, 1]
    wx, wy = px - ax, py - ay
    foot = np.clip((wx * dx + wy * dy) / np.maximum(dx * dx + dy * dy, 1e-300), 0.0, 1.0)
    gx, gy = wx - foot * dx, wy - foot * dy
    near = np.sqrt(gx * gx + gy * gy).min(axis=2)
    return np.nan_to_num(near, nan=0.0).max(axis=1)


def test_distances_to_chains_are_the_plain_expression_s_bit_for_bit():
    rng = np.random.default_rng(3)
    chains = np.cumsum(rng.normal(0.0, 0.3, (200, 17, 2)), axis=1) + rng.normal(0.0, 50.0, (200, 1, 2))
    points = chains[:, :1] + rng.normal(0.0, 1.0, (200, 33, 2))
    points[5, 3] = np.nan  # a point without contact
    points[7] = np.nan  # an interval of none
    chains[9, 4] = chains[9, 5]  # a chord of no length
    assert np.array_equal(distance_to_chains(points, chains), _plain_distance_to_chains(points, chains))


def test_gaps_to_chords_are_the_plain_expression_s_bit_for_bit():
    rng = np.random.default_rng(4)
    a, d, p = (rng.normal(0.0, 10.0, (50, 16, 2)) for _ in range(3))
    d[0, 0] = 0.0  # a chord of no length: the distance to its point
    got = _gap_to_chords(p[..., 0], p[..., 1], a[..., 0], a[..., 1], d[..., 0], d[..., 1])
    foot = np.clip(((p - a) * d).sum(axis=2) / np.maximum((d * d).sum(axis=2), 1e-300), 0.0, 1.0)
    gap = p - a - foot[..., None] * d
    assert np.array_equal(got, np.sqrt(gap[..., 0] * gap[..., 0] + gap[..., 1] * gap[..., 1]))


RUN = """
import atexit, sys
atexit.register(lambda: print("atexit handler ran", file=sys.stderr))
sys.argv = ["rotorcad", *{args!r}]
from rotorcad.cli.main import run
run()
print("not reached", file=sys.stderr)
"""


def test_the_command_ends_after_its_atexit_handlers_and_output():
    # reference: what Python's own exit does that a user sees (the atexit handlers, the flushed
    # standard streams, the status), kept by the command's early end (rotorcad.cli.main.run)
    import json
    import subprocess
    import sys

    ok = subprocess.run(
        [sys.executable, "-c", RUN.format(args=["gear", "--teeth", "20", "--module", "2", "--json"])],
        capture_output=True,
        text=True,
    )
    assert ok.returncode == 0 and json.loads(ok.stdout)["pitch_radius"] == 20.0  # z m / 2, the whole JSON flushed
    assert ok.stderr == "atexit handler ran\n"
    bad = subprocess.run(
        [sys.executable, "-c", RUN.format(args=["gear", "--teeth", "1", "--module", "2"])], capture_output=True, text=True
    )
    assert bad.returncode == 2 and bad.stderr.endswith("(got 1).\natexit handler ran\n")


def _without_clock(data: bytes) -> list[bytes]:
    # the save time: the values of the header's date variables and the writer's time stamp
    lines = data.split(b"\n")
    for i, line in enumerate(lines[:-1]):
        if line.strip() in (b"$TDUPDATE", b"$TDUUPDATE", b"$TDINDWG", b"$VERSIONGUID"):
            lines[i + 2] = b"<clock>"
        if b" @ " in line:
            lines[i] = line.split(b" @ ")[0]
    return lines


def test_a_drawing_is_saved_as_ezdxf_s_saveas_saves_it(tmp_path):
    # reference: ezdxf's own Drawing.saveas (text file, the drawing's encoding, its error handler)
    import ezdxf

    from exports.dxf import _save

    for version in ("R2000", "R12"):
        doc = ezdxf.new(version)
        msp = doc.modelspace()
        msp.add_line((0, 0), (1.25, 3.5))
        msp.add_text("tip radius 2.5 µm → 3 µm", height=1.0)  # µ in cp1252, the arrow escaped (dxfreplace)
        if version != "R12":
            msp.add_lwpolyline([(0, 0), (1, 0), (1, 1)], close=True)
        doc.saveas(tmp_path / "theirs.dxf")
        _save(doc, tmp_path / "ours.dxf", version)
        theirs, ours = (tmp_path / "theirs.dxf").read_bytes(), (tmp_path / "ours.dxf").read_bytes()
        assert b"\\U+2192" in ours and _without_clock(ours) == _without_clock(theirs)


def test_the_bounded_check_splits_the_same_intervals_into_the_same_samples():
    # reference: the Hermite check against every chord of every interval (interval_deviation
    # without `below`); the bound made from the chords beside each point must never be below it,
    # equal it wherever it exceeds `below`, and the refinement must add the same samples. An
    # involute from its cusp (u = 0, where the cubic errs most) and sparse samples.
    from exports.hermite import interval_deviation, refine_samples
    from rotorcad.curves import Involute

    curve = Involute(base_radius=20.0, theta0=0.3, hand=1.0, s0=0.0, s1=0.9)
    s = np.concatenate([np.linspace(0.0, 0.05, 4), np.linspace(0.08, 0.9, 9)])
    p, t = curve.evaluate(s)
    exact = interval_deviation(curve, s, p, t)
    for below in (1e-7, float(np.median(exact)), 1.0):
        bound = interval_deviation(curve, s, p, t, below)
        assert np.all(bound >= exact) and np.array_equal(bound[bound > below], exact[bound > below])
    assert np.any(exact > 1e-4) and np.any(exact < 1e-6)  # both kinds of interval in the test
    for target in (1e-4, 1e-6):
        got, want = refine_samples(curve, s, p, t, target, 8, exact=False), refine_samples(curve, s, p, t, target, 8)
        assert all(np.array_equal(a, b) for a, b in zip(got[:3], want[:3], strict=True))


def _one_curve_refinement(curve, s, p, t, target, passes, below):
    # the refinement loop of one curve as the module had it before curves were refined together:
    # measure (interval_deviation), split every interval over the target into ceil((e / target)^(1/4)) + 1
    # equal parameter parts, evaluate the new samples, drop those without contact, measure again
    from exports.hermite import interval_deviation

    err = interval_deviation(curve, s, p, t, below)
    for _ in range(passes):
        if err.max() <= target:
            break
        parts = np.where(err > target, np.ceil((err / target) ** 0.25) + 1, 1).astype(int)
        s_new, p_new, t_new = [s[:1]], [p[:1]], [t[:1]]
        for i, n in enumerate(parts):
            inner = s[i] + (s[i + 1] - s[i]) * (np.arange(1, n) / n)
            pi, ti = curve.evaluate(inner)
            s_new += [inner, s[i + 1 : i + 2]]
            p_new += [pi, p[i + 1 : i + 2]]
            t_new += [ti, t[i + 1 : i + 2]]
        s, p, t = np.concatenate(s_new), np.concatenate(p_new), np.concatenate(t_new)
        keep = np.isfinite(p).all(axis=1) & np.isfinite(t).all(axis=1)
        s, p, t = s[keep], p[keep], t[keep]
        err = interval_deviation(curve, s, p, t, below)
    return s, p, t, err


def test_curves_refined_together_get_the_samples_each_gets_alone():
    # reference: the plain one-curve loop above, curve by curve (interval by interval for the new
    # samples); refine_curves measures the intervals of all the curves at once and must give every
    # curve the same samples and deviations bit for bit. The sample's male outline (involutes,
    # generated conjugates, arcs) and an involute from its cusp sampled sparsely (several passes).
    import tomllib
    from pathlib import Path

    from exports.hermite import refine_curves
    from rotorcad.curves import Involute
    from rotorcad.design import rotor_design
    from rotorcad.rotor_build import build_pair, pair_spec

    sample = Path(__file__).resolve().parents[1] / "samples" / "rack_involute_5_6.toml"
    with sample.open("rb") as f:
        rotors = build_pair(pair_spec(rotor_design(tomllib.load(f), sample.parent)))
    pieces = [(seg.curve, seg.s, seg.points, seg.tangents) for seg in rotors.male_outline(0.05).segments if len(seg.s) >= 2]
    cusp = Involute(base_radius=20.0, theta0=0.3, hand=1.0, s0=0.0, s1=0.9)
    s = np.concatenate([np.linspace(0.0, 0.05, 4), np.linspace(0.08, 0.9, 9)])
    pieces.append((cusp, s, *cusp.evaluate(s)))
    for target, exact in ((1e-4, True), (2.5e-4, False), (1e-6, True)):
        got = refine_curves(pieces, target, 8, exact)
        passes = 0
        for piece, mine in zip(pieces, got, strict=True):
            want = _one_curve_refinement(*piece, target, 8, None if exact else target)
            assert all(np.array_equal(a, b) for a, b in zip(mine, want, strict=True))
            passes = max(passes, len(mine[0]) > len(piece[1]))
        assert passes  # some curve was refined

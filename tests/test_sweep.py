"""Design sweeps (rotorcad sweep): the plan, the rows against `rotorcad rotor --json` on each
variant's own design file, failing variants, a dask.distributed cluster started here, and resume
after the sweep is killed."""

from __future__ import annotations

import contextlib
import json
import os
import re
import signal
import subprocess
import sys
import time
from collections.abc import Iterator
from pathlib import Path

import numpy as np
import pandas as pd
import pytest
import tomli_w

from rotorcad.cli.main import main
from rotorcad.cli.sweep_run import load_sweep, parts_folder
from rotorcad.design import load_toml
from rotorcad.errors import DesignError
from rotorcad.sweep.figures import FLUTE_AREA_RTOL
from rotorcad.sweep_plan import Sampling, apply, sweep_plan

ROOT = Path(__file__).resolve().parents[1]
BASE = ROOT / "samples" / "rack_involute_5_6.toml"
RESULTS = ("blow_hole_area", "contact_line_length", "male_flute_area", "female_flute_area", "displacement_per_rev")
COLUMNS = (
    "blow_hole_area_mm2",
    "contact_line_length_mm",
    "male_flute_area_mm2",
    "female_flute_area_mm2",
    "displacement_per_rev_mm3",
)


def _write(tmp_path: Path, text: str, name: str = "sweep.toml") -> Path:
    path = tmp_path / name
    path.write_text(f'[sweep]\nbase = "{BASE.as_posix()}"\n' + text)
    return path


# --- the plan ---------------------------------------------------------------------------------


def test_grid_takes_every_combination_and_ranges_include_both_ends():
    base = load_toml(BASE)
    plan = sweep_plan({"vary": {"pair.male_teeth": [4, 5], "profile.lobe_width": {"from": 0.6, "to": 0.7, "step": 0.05}}}, base)
    variants = plan.variants()
    assert plan.count == len(variants) == 6
    assert [v.values["profile.lobe_width"] for v in variants[:3]] == [0.6, 0.65, 0.7]
    assert len({v.key for v in variants}) == 6
    assert apply(base, variants[4].values)["pair"]["male_teeth"] == 5 and base["pair"]["male_teeth"] == 5


def test_latin_hypercube_stratifies_every_parameter_and_is_repeatable():
    base = load_toml(BASE)
    data = {
        "sweep": {"method": "latin-hypercube", "samples": 50, "seed": 7},
        "vary": {"pair.lead": {"min": 200.0, "max": 400.0}, "profile.lobe_width": {"min": 0.6, "max": 0.75}},
    }
    plan = sweep_plan(data, base)
    assert plan.sampling is Sampling.LATIN_HYPERCUBE
    lead = np.array([v.values["pair.lead"] for v in plan.variants()])
    strata = np.floor((lead - 200.0) / 200.0 * 50).astype(int)
    assert sorted(strata) == list(range(50))  # one sample in each of the 50 strata (McKay et al. 1979)
    assert [v.key for v in plan.variants()] == [v.key for v in sweep_plan(data, base).variants()]


@pytest.mark.parametrize(
    ("data", "words"),
    [
        ({"vary": {"pair.lead": {"min": 200.0, "max": 400.0}}}, "method grid"),
        ({"vary": {"pairs.lead": [1.0]}}, "table.key"),
        ({"sweep": {"method": "sobol"}, "vary": {"pair.lead": [300.0]}}, "method"),
        ({"sweep": {"method": "random", "samples": 0}, "vary": {"pair.lead": {"min": 1.0, "max": 2.0}}}, "samples"),
        ({"vary": {"pair.lead": {"from": 3.0, "to": 1.0, "step": 1.0}}}, "from <= to"),
    ],
)
def test_bad_plans_are_refused_with_the_key(data, words):
    with pytest.raises(DesignError, match=words):
        sweep_plan(data, load_toml(BASE))


# --- running ----------------------------------------------------------------------------------

LHS_80 = """method = "latin-hypercube"
samples = 80
seed = 3

[vary]
"profile.lobe_width" = {min = 0.62, max = 0.75}
"profile.driving_angle_deg" = {min = 25.0, max = 35.0}
"pair.lead" = {min = 220.0, max = 380.0}
"""


def test_sweep_rows_equal_rotor_json_of_each_variants_design(tmp_path, capsys):
    # 80 variants on two Dask workers (16 batches of 5, finished out of order and joined in variant
    # order); 10 of them written as design files (tomli-w) and run through `rotorcad rotor --json`:
    # the same numbers, row by row. 80, not more: each variant is ~22 ms of CPU, and the check is
    # row against command, not the count (all 80 of this range build; 200 did too)
    sweep_file = _write(tmp_path, LHS_80)
    out = tmp_path / "r.parquet"
    assert main(["sweep", str(sweep_file), "--out", str(out), "--workers", "2", "--json", "--csv", str(tmp_path / "r.csv")]) == 0
    summary = json.loads(capsys.readouterr().out)
    table = pd.read_parquet(out)
    assert summary["variants"] == len(table) == 80 and table["key"].is_unique
    assert list(table["variant"]) == list(range(80))
    assert len(pd.read_csv(tmp_path / "r.csv")) == 80
    plan, _, _ = load_sweep(sweep_file)
    variants = plan.variants()
    for index in np.linspace(0, 79, 10).astype(int):
        row = table.iloc[index]
        design = tmp_path / f"variant_{index}.toml"
        design.write_text(tomli_w.dumps(apply(plan.base, variants[index].values)))
        code = main(["rotor", str(design), "--json"])
        if not row["ok"]:
            assert code == 2 and row["reason"] in capsys.readouterr().err
            continue
        assert code == 0
        reference = json.loads(capsys.readouterr().out)
        for key, column in zip(RESULTS, COLUMNS, strict=True):
            # the flute areas from the outline's own polygon, not clipped to a 2048-gon (rotorcad.sweep.figures)
            rel = FLUTE_AREA_RTOL if "flute" in key or "displacement" in key else 1e-12
            assert row[column] == pytest.approx(reference[key], rel=rel, abs=1e-12)
        assert row["max_sliding_velocity_m_s"] == pytest.approx(reference["max_sliding_velocity"], rel=1e-12)
    assert table["ok"].sum() > 60  # most of this range builds


def test_failing_variants_are_rows_with_their_reason(tmp_path, capsys):
    sweep_file = _write(tmp_path, '[vary]\n"pair.male_teeth" = [5, 13]\n"pair.male_root_radius" = [45.0, 64.0]\n')
    out = tmp_path / "r.parquet"
    assert main(["sweep", str(sweep_file), "--out", str(out), "--workers", "0"]) == 0
    text = capsys.readouterr().out
    table = pd.read_parquet(out)
    assert len(table) == 4 and table["ok"].sum() == 1
    reasons = table.loc[~table["ok"], "reason"]
    assert any("male_teeth" in r and "12" in r for r in reasons)  # teeth 13
    assert any("root" in r for r in reasons)  # a root outside the tip circle
    assert "3 failed" not in text  # counted by reason
    assert sum(int(line.split()[0]) for line in text.splitlines() if " failed: " in line) == 3


# the test's own scheduler serves its health check on port 8787, or on another where the killed sweep's test holds
# it on the other worker: not the sweep's words (rotorcad.sweep.run filters the same warning for its own cluster)
@pytest.mark.filterwarnings("ignore:Port .* is already in use")
def test_a_running_dask_cluster_gives_the_same_table(tmp_path, capsys):
    from dask.distributed import LocalCluster

    sweep_file = _write(tmp_path, '[vary]\n"profile.lobe_width" = [0.62, 0.66, 0.7, 0.74]\n"pair.lead" = [250.0, 300.0]\n')
    # in this process (--workers 0, no cluster) and on a running cluster: the same table. The cluster's two workers
    # are threads of this process behind a TCP scheduler (what --scheduler meets is the address, the tasks and
    # their results pickled over TCP, as to any cluster); worker processes are the tests above and below
    # (--workers 2: their own cluster, killed and resumed), and two more took 3.4 s of CPU to start here
    assert main(["sweep", str(sweep_file), "--out", str(tmp_path / "local.parquet"), "--quiet", "--workers", "0"]) == 0
    cluster_options = {"processes": False, "protocol": "tcp", "dashboard_address": None}
    with LocalCluster(n_workers=2, threads_per_worker=1, **cluster_options) as cluster:
        code = main(
            ["sweep", str(sweep_file), "--out", str(tmp_path / "cluster.parquet"), "--scheduler", cluster.scheduler_address]
        )
    assert code == 0
    capsys.readouterr()
    a = pd.read_parquet(tmp_path / "local.parquet").drop(columns="seconds")
    b = pd.read_parquet(tmp_path / "cluster.parquet").drop(columns="seconds")
    pd.testing.assert_frame_equal(a, b)


@contextlib.contextmanager
def _another_dashboard() -> Iterator[None]:
    """Port 8787 (Dask's dashboard) held by a listener of this process, unless something holds it already."""
    import socket

    holder = socket.socket()
    try:
        holder.bind(("", 8787))
        holder.listen()
    except OSError:
        pass  # something holds it already: the case to test
    try:
        yield
    finally:
        holder.close()


def test_killed_sweep_resumes_without_repeating_or_losing_a_variant_with_no_dashboard_warning(tmp_path):
    # 200 variants on two workers: 16 batches of 12 and one of 8, ~22 ms of CPU a variant; killed
    # once 3 parts are written, with some 160 variants (~3.5 s of CPU) still to go
    sweep_file = _write(tmp_path, LHS_80.replace("samples = 80", "samples = 200"))
    out = tmp_path / "r.parquet"
    command = [sys.executable, "-m", "rotorcad.cli.main", "sweep", str(sweep_file), "--out", str(out), "--workers", "2", "--json"]
    first = subprocess.Popen(command, stdout=subprocess.PIPE, stderr=subprocess.PIPE, start_new_session=True)
    deadline = time.monotonic() + 120
    while time.monotonic() < deadline and len(list(parts_folder(out).glob("part-*.parquet"))) < 3:
        time.sleep(0.05)
    os.kill(first.pid, signal.SIGKILL)  # the sweep alone, half-way: its workers and helpers must go with it
    try:
        _, killed_err = first.communicate(timeout=90)  # returns once no process of the sweep holds its stderr
    except subprocess.TimeoutExpired:
        os.killpg(first.pid, signal.SIGKILL)
        raise AssertionError("a process of the killed sweep outlived it by 90 s") from None
    assert "leaked" not in killed_err.decode() and "Traceback" not in killed_err.decode()  # issue 24
    parts = sorted(parts_folder(out).glob("part-*.parquet"))
    done = pd.concat([pd.read_parquet(p) for p in parts])
    assert 0 < len(done) < 200 and not out.exists()
    with _another_dashboard():
        second = subprocess.run(command, capture_output=True, text=True, timeout=300)
    assert second.returncode == 0, second.stderr
    # no log lines of Dask's on a successful run, not a word of another dashboard on port 8787 (issue 24)
    assert second.stderr == ""
    summary = json.loads(second.stdout)
    assert summary["resumed"] == len(done) and summary["computed"] == 200 - len(done)
    table = pd.read_parquet(out)
    assert len(table) == 200 and table["key"].is_unique and sorted(table["variant"]) == list(range(200))
    assert not parts_folder(out).exists()
    kept = table.set_index("key").loc[done["key"], "blow_hole_area_mm2"].to_numpy()
    assert np.allclose(kept, done["blow_hole_area_mm2"].to_numpy(), equal_nan=True)  # the first run's rows kept


def test_python_api_returns_the_table(tmp_path, capsys):
    import rotorcad

    sweep_file = _write(tmp_path, '[vary]\n"profile.lobe_width" = [0.66, 0.7]\n')
    table = rotorcad.sweep(sweep_file, workers=0)
    assert list(table["profile.lobe_width"]) == [0.66, 0.7] and table["ok"].all()
    # the base design (lobe width 0.6 -> 0.7 written by hand into a copy) through `rotorcad rotor --json`
    design = tmp_path / "w07.toml"
    design.write_text(BASE.read_text().replace("lobe_width = 0.6 ", "lobe_width = 0.7 "))
    assert main(["rotor", str(design), "--json"]) == 0
    reference = json.loads(capsys.readouterr().out)
    assert table["contact_line_length_mm"].iloc[1] == pytest.approx(reference["contact_line_length"], rel=1e-12)


def test_not_a_sweep_output_is_not_overwritten(tmp_path, capsys):
    sweep_file = _write(tmp_path, '[vary]\n"profile.lobe_width" = [0.7]\n')
    out = tmp_path / "precious.parquet"
    out.write_bytes(b"my own data")
    assert main(["sweep", str(sweep_file), "--out", str(out)]) == 2
    assert "--out" in capsys.readouterr().err and out.read_bytes() == b"my own data"


def test_optional_analyses_hobbability_interference_volume_clearance(tmp_path, capsys):
    # the solids' volume is the section area x length (shapely, here); the designed clearance of
    # 0.05 mm comes back as a mean normal clearance of that order, never negative (Wu & Chi)
    import shapely

    from rotorcad.design import rotor_design
    from rotorcad.rotor_build import build_pair, pair_spec

    compute = 'compute = ["hobbability", "interference", "volume", "clearance"]\nclearance = 0.05\n'
    sweep_file = _write(tmp_path, compute + '\n[vary]\n"profile.lobe_width" = [0.7]\n')
    assert main(["sweep", str(sweep_file), "--out", str(tmp_path / "r.parquet"), "--workers", "0", "--quiet"]) == 0
    capsys.readouterr()
    row = pd.read_parquet(tmp_path / "r.parquet").iloc[0]
    assert row["ok"], row["reason"]
    rotors = build_pair(pair_spec(rotor_design(apply(load_toml(BASE), {"profile.lobe_width": 0.7}), BASE.parent)))
    outline = shapely.Polygon(rotors.male_outline(1e-4).points)
    # the sweep's section is chorded at 1e-3 mm: a chord of sagitta d cuts (2/3) d per unit length of
    # outline off (or adds it on a concave part), so the areas agree within (2/3) 1e-3 x perimeter
    bound = 2 / 3 * 1e-3 * outline.length * 190.0
    assert row["male_volume_mm3"] == pytest.approx(outline.area * 190.0, abs=bound)
    assert isinstance(row["hobbable"], (bool, np.bool_)) and not row["interferes"]
    assert row["interference_volume_mm3"] < 1.0
    assert 0.02 < row["clearance_mean_mm"] < 0.2 and row["clearance_min_mm"] > -1e-6


def test_pareto_front_equals_brute_force_and_pictures_are_written(tmp_path, capsys):
    from rotorcad.sweep_plots import pareto_mask

    rng = np.random.default_rng(0)
    x, y = rng.random(300), rng.random(300)
    x[::17] = np.nan
    # brute force: no other point at most as large in both and smaller in one
    ok = np.isfinite(x) & np.isfinite(y)
    front = np.array([ok[i] and not np.any(ok & (x <= x[i]) & (y <= y[i]) & ((x < x[i]) | (y < y[i]))) for i in range(len(x))])
    assert np.array_equal(pareto_mask(x, y), front)
    assert np.array_equal(pareto_mask(x, -y, True, False), front)  # larger is better for the second
    sweep_file = _write(tmp_path, '[vary]\n"profile.lobe_width" = [0.64, 0.68, 0.72]\n"pair.lead" = [260.0, 320.0]\n')
    args = ["sweep", str(sweep_file), "--out", str(tmp_path / "r.parquet"), "--workers", "0", "--quiet"]
    args += ["--pareto", str(tmp_path / "p.png"), "--effects", str(tmp_path / "e.png")]
    assert main(args) == 0
    capsys.readouterr()
    for name in ("p.png", "e.png"):
        assert (tmp_path / name).read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


@pytest.mark.parametrize(
    ("vary", "words"),
    [
        ('"profile.lobe_widht" = [0.7]', "[vary] 'profile.lobe_widht' must be one of the rack-involute family's parameters"),
        ('"pair.colour" = ["red"]', "[vary] 'pair.colour' must be a key of [pair]"),
        ('"pair.male_teeth" = [4.5, 5.0]', "whole numbers"),
        ('"pair.lead" = [true, 300.0]', "finite numbers"),
    ],
)
def test_vary_typos_and_wrong_types_are_refused_before_anything_is_computed(tmp_path, capsys, vary, words):
    # a new user's check: these ran to the end with every row failed (or an internal error)
    sweep_file = _write(tmp_path, "[vary]\n" + vary + "\n")
    out = tmp_path / "r.parquet"
    assert main(["sweep", str(sweep_file), "--out", str(out)]) == 2
    assert words in capsys.readouterr().err
    assert not out.exists() and not parts_folder(out).exists()


def test_results_of_another_sweep_are_never_taken_nor_lost_and_a_longer_list_computes_only_the_new(tmp_path, capsys):
    out = tmp_path / "r.parquet"
    first = _write(tmp_path, '[vary]\n"profile.lobe_width" = [0.66, 0.7]\n')
    assert main(["sweep", str(first), "--out", str(out), "--workers", "0", "--quiet"]) == 0
    before = out.read_bytes()
    # the same values on another base design (length changed): refused, the file kept
    changed = tmp_path / "changed.toml"
    changed.write_text(BASE.read_text().replace("length = 190.0", "length = 100.0"))
    other = tmp_path / "other.toml"
    other.write_text(f'[sweep]\nbase = "{changed.as_posix()}"\n[vary]\n"profile.lobe_width" = [0.66, 0.7]\n')
    capsys.readouterr()
    assert main(["sweep", str(other), "--out", str(out)]) == 2
    assert "rows are of another sweep" in capsys.readouterr().err and out.read_bytes() == before
    # one more value in the list: only that variant is computed
    longer = _write(tmp_path, '[vary]\n"profile.lobe_width" = [0.64, 0.66, 0.7]\n', "longer.toml")
    assert main(["sweep", str(longer), "--out", str(out), "--workers", "0", "--json"]) == 0
    summary = json.loads(capsys.readouterr().out)
    assert (summary["computed"], summary["resumed"]) == (1, 2)
    assert list(pd.read_parquet(out)["profile.lobe_width"]) == [0.64, 0.66, 0.7]


def test_outputs_and_objectives_are_checked_before_the_work(tmp_path, capsys):
    sweep_file = _write(tmp_path, '[vary]\n"profile.lobe_width" = [0.7]\n')
    out = tmp_path / "r.parquet"
    assert main(["sweep", str(sweep_file), "--out", str(out), "--pareto", str(tmp_path / "p.png"), "--objectives", "a,b"]) == 2
    assert "--objectives must name result columns" in capsys.readouterr().err and not out.exists()
    assert main(["sweep", str(sweep_file), "--out", str(out), "--csv", str(tmp_path / "missing" / "r.csv")]) == 2
    assert "--csv" in capsys.readouterr().err and not out.exists()
    assert main(["sweep", str(sweep_file), "--out", str(tmp_path / "r.csv")]) == 2
    assert ".parquet" in capsys.readouterr().err


def test_failures_are_counted_by_cause_not_by_value(tmp_path, capsys):
    sweep_file = _write(tmp_path, '[vary]\n"pair.male_root_radius" = [64.0, 65.0, 66.0]\n')
    assert main(["sweep", str(sweep_file), "--out", str(tmp_path / "r.parquet"), "--workers", "0", "--json"]) == 0
    summary = json.loads(capsys.readouterr().out)
    assert summary["failed"] == 3 and list(summary["failures"].values()) == [3]


# --- issue 27: linked values, family axis, steering, streaming, the commands' analyses -----------

SAMPLES = ROOT / "samples"


def _dominated(cost: np.ndarray, i: int) -> bool:
    """Brute force (the definition of dominance, Deb 2001, ch. 2): some row at most as large in every column, smaller in one."""
    return bool(np.any(np.all(cost <= cost[i], axis=1) & np.any(cost < cost[i], axis=1)))


@pytest.mark.parametrize(("sample", "samples"), [("sweep_rack_involute.toml", 12), ("sweep_tooth_counts.toml", None)])
def test_sample_sweeps_rank_the_feasible_and_mark_the_pareto_front(tmp_path, capsys, sample, samples):
    # the samples as they are (the Latin hypercube one with fewer draws, to stay fast); no verdict of
    # theirs is pinned: the test checks the columns against their definitions, computed here
    text = (SAMPLES / sample).read_text()
    if samples is not None:
        text = text.replace("samples = 60", f"samples = {samples}")
    sweep_file = tmp_path / sample
    sweep_file.write_text(text)
    out, front_csv = tmp_path / "r.parquet", tmp_path / "front.csv"
    args = ["sweep", str(sweep_file), "--out", str(out), "--workers", "0", "--json", "--top", "3", "--pareto-csv", str(front_csv)]
    assert main(args) == 0
    summary = json.loads(capsys.readouterr().out)
    table = pd.read_parquet(out)
    steer_data = load_toml(sweep_file)
    # feasible: built and every constraint of the file, evaluated here from its text
    feasible = table["ok"].to_numpy(bool).copy()
    for column, condition in steer_data["constraints"].items():
        values = table[column]
        if isinstance(condition, bool):
            feasible &= (values.fillna(not condition).astype(bool) == condition).to_numpy()
        else:
            op, number = condition.split()
            x = values.to_numpy(float)
            feasible &= {"<": x < float(number), "==": x == float(number), "<=": x <= float(number)}[op]
    assert np.array_equal(table["feasible"].to_numpy(bool), feasible)
    # the objectives as costs (smaller better), evaluated here
    costs = []
    for name, spec in steer_data["objectives"].items():
        if spec in ("min", "max"):
            values = table[name].to_numpy(float)
            costs.append(values if spec == "min" else -values)
        else:  # the samples' expressions, computed here
            a = table["pair.center_distance"].to_numpy(float)
            by_hand = {
                "displacement_per_rev_mm3 / pair.center_distance ** 3": table["displacement_per_rev_mm3"].to_numpy(float) / a**3,
                "contact_line_length_mm / pair.center_distance": table["contact_line_length_mm"].to_numpy(float) / a,
            }
            ((direction, expression),) = spec.items()
            values = by_hand[expression]
            assert np.allclose(table[f"objective.{name}"], values, equal_nan=True)
            costs.append(values if direction == "min" else -values)
    cost = np.column_stack(costs)
    usable = feasible & np.all(np.isfinite(cost), axis=1)
    rows = np.flatnonzero(usable)
    front = np.zeros(len(table), bool)
    front[rows] = [not _dominated(cost[rows], k) for k in range(len(rows))]
    assert np.array_equal(table["pareto"].to_numpy(bool), front)
    assert summary["pareto_front"] == front.sum() and summary["feasible"] == feasible.sum()
    # rank: 1..feasible, the front first; the infeasible unranked
    rank = table["rank"].to_numpy()
    assert sorted(rank[usable]) == list(range(1, usable.sum() + 1)) and np.all(rank[~usable] == 0)
    if front.any():
        assert rank[front].max() == front.sum()
    assert [r["rank"] for r in summary["top"]] == list(range(1, min(3, usable.sum()) + 1))
    # the CSV holds the front's members
    members = pd.read_csv(front_csv)
    assert sorted(members["variant"]) == sorted(table.loc[front, "variant"])


def test_tooth_count_sweep_keeps_proportions_and_the_family_is_an_axis():
    # the sample's linked radii, resolved by hand for z1/z2 = 3/7 at a = 160 (m = 2a/(z1+z2) = 32,
    # r1w = a z1/(z1+z2) = 48): the female follows the male, so every pair closes at the centre distance
    from rotorcad.design import rotor_design

    plan, folder, _ = load_sweep(SAMPLES / "sweep_tooth_counts.toml")
    values = {"pair.male_teeth": 3, "pair.female_teeth": 7, "pair.center_distance": 160.0, "profile.family": "n-rack"}
    settings = rotor_design(plan.design(next(v for v in plan.iter_variants() if v.values == values)), folder)
    pair = settings["pair"]
    assert settings["family"] == "n-rack" and "lobe_width" not in settings["params"]  # the N rack's own parameters
    assert pair["male_tip_radius"] == pytest.approx(48 + 1.39 * 32) and pair["male_root_radius"] == pytest.approx(48 - 0.107 * 32)
    assert pair["female_tip_radius"] == pytest.approx(160 - (48 - 0.107 * 32))
    assert pair["lead"] == pytest.approx(2.586 * 160)


def test_linked_values_are_evaluated_safely_and_refused_by_key(tmp_path, capsys):
    from rotorcad.design import rotor_design

    base = load_toml(BASE)
    linked = apply(base, {"pair.female_tip_radius": "a - male_root_radius", "pair.lead": "sqrt(a**2) * 300 / 116"})
    settings = rotor_design(linked)
    # the expression's value by hand, from the base design's own numbers
    by_hand = base["pair"]["center_distance"] - base["pair"]["male_root_radius"]
    assert settings["pair"]["female_tip_radius"] == by_hand and settings["pair"]["lead"] == pytest.approx(300.0)
    # the same design typed as numbers gives the same `rotor --json`
    (tmp_path / "linked.toml").write_text(tomli_w.dumps(linked))
    assert main(["rotor", str(tmp_path / "linked.toml"), "--json"]) == 0
    a = json.loads(capsys.readouterr().out)
    assert main(["rotor", str(BASE), "--json"]) == 0
    b = json.loads(capsys.readouterr().out)
    assert a["contact_line_length"] == b["contact_line_length"] and a["blow_hole_area"] == b["blow_hole_area"]
    for text, words in [
        ("__import__('os').getpid()", "[pair] lead must be a number or an expression"),
        ("a.__class__", "[pair] lead must be"),
        ("2 * b", "unknown name 'b'"),
        ("lead + 1", "a cycle"),
        ("1 / (a - a)", "division by zero"),
        ("10 ** 400", "exponent above 64"),
    ]:
        with pytest.raises(DesignError, match=re.escape(words)):
            rotor_design(apply(base, {"pair.lead": text}))
    with pytest.raises(DesignError, match=r"\[pair\] center_distance must be a number"):
        rotor_design(apply(base, {"pair.center_distance": "100 + 16"}))


def test_range_end_off_the_step_grid_is_kept():
    plan = sweep_plan({"vary": {"pair.lead": {"from": 250.0, "to": 330.0, "step": 50.0}}}, load_toml(BASE))
    assert [v.values["pair.lead"] for v in plan.variants()] == [250.0, 300.0, 330.0]
    plan = sweep_plan({"vary": {"pair.male_teeth": {"from": 3, "to": 8, "step": 2}}}, load_toml(BASE))
    assert [v.values["pair.male_teeth"] for v in plan.variants()] == [3, 5, 7, 8]


def test_the_plan_is_streamed_its_memory_flat_and_a_table_too_large_is_refused():
    import tracemalloc

    base = load_toml(BASE)

    def peak(count: int, whole: bool = False) -> float:
        data = {"sweep": {"method": "latin-hypercube", "samples": count, "seed": 3}}
        data["vary"] = {"pair.lead": {"min": 1.0, "max": 2.0}}
        tracemalloc.start()
        plan = sweep_plan(data, base)
        n = len(plan.variants()) if whole else sum(1 for _ in plan.iter_variants())
        top = tracemalloc.get_traced_memory()[1]
        tracemalloc.stop()
        assert n == count
        return top

    peak(1_000)  # the first plan's one-off allocations (lazy imports) are not the stream's memory
    # 20 000 variants (five blocks of 4096) against 5 000 (two): a list-like plan would take 4x; the
    # streamed one took 1.6x at 20 000 and the same at 40 000 (measured)
    small, large, held = peak(5_000), peak(20_000), peak(20_000, whole=True)
    assert large < 2 * small  # four times the variants, about the same memory (blocks of 4096)
    assert large < held / 10  # the list of the same 20 000 variants, for scale (17x measured)
    # Latin hypercube of the streamed plan: one sample in each of n strata (McKay et al. 1979)
    data = {"sweep": {"method": "latin-hypercube", "samples": 9_000, "seed": 5}, "vary": {"pair.lead": {"min": 0.0, "max": 1.0}}}
    lead = np.array([v.values["pair.lead"] for v in sweep_plan(data, base).iter_variants()])
    assert sorted(np.floor(lead * 9_000).astype(int)) == list(range(9_000))
    # 5 M variants would need a results table of ~5 GB: refused before anything, naming the count that fits
    data = {"sweep": {"method": "random", "samples": 5_000_000}, "vary": {"pair.lead": {"min": 1.0, "max": 2.0}}}
    with pytest.raises(DesignError, match=r"\[sweep\] samples must be at most 2000000 variants"):
        sweep_plan(data, base)


def test_reusing_a_built_section_gives_the_numbers_of_a_fresh_build():
    # variants that differ in lead, length and speed only share their transverse section; the
    # reference is a fresh build of each (the cache cleared before every variant)
    from rotorcad.sweep.tasks import clear_cache, evaluate

    base = load_toml(BASE)
    data = {"vary": {"pair.lead": [250.0, 320.0], "pair.length": [150.0, 190.0], "operating.speed_rpm": [3000.0, 4500.0]}}
    plan = sweep_plan(data, base)
    clear_cache()
    reused = [evaluate(plan.base, None, None, (), v) for v in plan.variants()]
    fresh = []
    for v in plan.variants():
        clear_cache()
        fresh.append(evaluate(plan.base, None, None, (), v))
    for a, b in zip(reused, fresh, strict=True):
        a.pop("seconds"), b.pop("seconds")
        assert a == b
    assert len({r["contact_line_length_mm"] for r in reused}) > 1  # the lead and length do change results


def test_interference_column_is_that_of_rotorcad_interfere(tmp_path, capsys):
    # the same angles (72), tolerance (0.005 mm) and housing as the command: the same numbers
    sweep_file = _write(tmp_path, 'compute = ["interference"]\n[vary]\n"profile.lobe_width" = [0.7]\n')
    assert main(["sweep", str(sweep_file), "--out", str(tmp_path / "r.parquet"), "--workers", "0", "--quiet"]) == 0
    capsys.readouterr()
    row = pd.read_parquet(tmp_path / "r.parquet").iloc[0]
    design = tmp_path / "v.toml"
    design.write_text(tomli_w.dumps(apply(load_toml(BASE), {"profile.lobe_width": 0.7})))
    code = main(["interfere", str(design), "--json", "--quiet"])
    reference = json.loads(capsys.readouterr().out)
    assert code == (1 if reference["interferes"] else 0)
    assert row["interference_volume_mm3"] == pytest.approx(reference["max_intersection_volume_raw"], rel=1e-12, abs=1e-15)
    assert row["housing_intersection_volume_mm3"] == pytest.approx(reference["housing_intersection_volume"], rel=1e-12, abs=1e-15)
    assert bool(row["interferes"]) == reference["interferes"]


def test_steering_refusals_name_the_key(tmp_path):
    from rotorcad.cli.sweep_run import load_steering

    for extra, words in [
        ('[constraints]\nblow_hole = "< 1"\n', "[constraints] blow_hole must be a column of this sweep"),
        ('[constraints]\nblow_hole_area_mm2 = "about 1"\n', "[constraints] blow_hole_area_mm2 must be true, false, or a"),
        ("[constraints]\nmeshline_closed = 1\n", "[constraints] meshline_closed must be true or false"),
        ('[objectives]\nblow_hole_area_mm2 = "least"\n', '[objectives] blow_hole_area_mm2 must be "min" or "max"'),
        ('[objectives]\nx = {min = "__import__(1)"}\n', "[objectives] x must be a column or an expression"),
        ('[objectives]\nx = {min = "wrap_angle_deg / colour"}\n', "unknown column"),
    ]:
        sweep_file = _write(tmp_path, '[vary]\n"profile.lobe_width" = [0.7]\n' + extra)
        plan, _, _ = load_sweep(sweep_file)
        with pytest.raises(DesignError, match=re.escape(words)):
            load_steering(sweep_file, plan)


def test_bad_scheduler_is_refused_at_once(tmp_path, capsys):
    # (a successful run's stderr with another dashboard on port 8787, issue 24, is checked on the
    # resumed run of test_killed_sweep_resumes_..._with_no_dashboard_warning: one process fewer)
    sweep_file = _write(tmp_path, '[vary]\n"profile.lobe_width" = [0.66, 0.7]\n')
    out = tmp_path / "r.parquet"
    start = time.monotonic()
    assert main(["sweep", str(sweep_file), "--out", str(out), "--scheduler", "tcp://127.0.0.1:1"]) == 2
    assert "--scheduler must be" in capsys.readouterr().err
    assert time.monotonic() - start < 8 and not parts_folder(out).exists() and not out.exists()

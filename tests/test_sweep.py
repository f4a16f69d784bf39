"""Design sweeps (rotorcad sweep): the plan, the rows against `rotorcad rotor --json` on each
variant's own design file, failing variants, a dask.distributed cluster started here, and resume
after the sweep is killed."""

from __future__ import annotations

import json
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pandas as pd
import pytest
import tomli_w

from rotorcad.cli.main import main
from rotorcad.cli.sweep_run import load_sweep, parts_folder
from rotorcad.design import load_toml
from rotorcad.errors import DesignError
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

LHS_200 = """method = "latin-hypercube"
samples = 200
seed = 3

[vary]
"profile.lobe_width" = {min = 0.62, max = 0.75}
"profile.driving_angle_deg" = {min = 25.0, max = 35.0}
"pair.lead" = {min = 220.0, max = 380.0}
"""


def test_sweep_rows_equal_rotor_json_of_each_variants_design(tmp_path, capsys):
    # 200 variants; 10 of them written as design files (tomli-w) and run through `rotorcad rotor
    # --json`: the same numbers, row by row
    sweep_file = _write(tmp_path, LHS_200)
    out = tmp_path / "r.parquet"
    assert main(["sweep", str(sweep_file), "--out", str(out), "--workers", "2", "--json", "--csv", str(tmp_path / "r.csv")]) == 0
    summary = json.loads(capsys.readouterr().out)
    table = pd.read_parquet(out)
    assert summary["variants"] == len(table) == 200 and table["key"].is_unique
    assert list(table["variant"]) == list(range(200))
    assert len(pd.read_csv(tmp_path / "r.csv")) == 200
    plan, _, _ = load_sweep(sweep_file)
    variants = plan.variants()
    for index in np.linspace(0, 199, 10).astype(int):
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
            assert row[column] == pytest.approx(reference[key], rel=1e-12, abs=1e-12)
        assert row["max_sliding_velocity_m_s"] == pytest.approx(reference["max_sliding_velocity"], rel=1e-12)
    assert table["ok"].sum() > 150  # most of this range builds


def test_failing_variants_are_rows_with_their_reason(tmp_path, capsys):
    sweep_file = _write(tmp_path, '[vary]\n"pair.male_teeth" = [5, 13]\n"pair.male_root_radius" = [45.0, 64.0]\n')
    out = tmp_path / "r.parquet"
    assert main(["sweep", str(sweep_file), "--out", str(out), "--workers", "1"]) == 0
    text = capsys.readouterr().out
    table = pd.read_parquet(out)
    assert len(table) == 4 and table["ok"].sum() == 1
    reasons = table.loc[~table["ok"], "reason"]
    assert any("male_teeth" in r and "12" in r for r in reasons)  # teeth 13
    assert any("root" in r for r in reasons)  # a root outside the tip circle
    assert "3 failed" not in text  # counted by reason
    assert sum(int(line.split()[0]) for line in text.splitlines() if " failed: " in line) == 3


def test_a_running_dask_cluster_gives_the_same_table(tmp_path, capsys):
    from dask.distributed import LocalCluster

    sweep_file = _write(tmp_path, '[vary]\n"profile.lobe_width" = [0.62, 0.66, 0.7, 0.74]\n"pair.lead" = [250.0, 300.0]\n')
    assert main(["sweep", str(sweep_file), "--out", str(tmp_path / "local.parquet"), "--quiet"]) == 0
    with LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None) as cluster:
        code = main(
            ["sweep", str(sweep_file), "--out", str(tmp_path / "cluster.parquet"), "--scheduler", cluster.scheduler_address]
        )
    assert code == 0
    capsys.readouterr()
    a = pd.read_parquet(tmp_path / "local.parquet").drop(columns="seconds")
    b = pd.read_parquet(tmp_path / "cluster.parquet").drop(columns="seconds")
    pd.testing.assert_frame_equal(a, b)


def test_killed_sweep_resumes_without_repeating_or_losing_a_variant(tmp_path):
    sweep_file = _write(tmp_path, LHS_200.replace("samples = 200", "samples = 400"))
    out = tmp_path / "r.parquet"
    command = [sys.executable, "-m", "rotorcad.cli.main", "sweep", str(sweep_file), "--out", str(out), "--workers", "2", "--json"]
    first = subprocess.Popen(command, stdout=subprocess.PIPE, stderr=subprocess.PIPE, start_new_session=True)
    deadline = time.monotonic() + 120
    while time.monotonic() < deadline and len(list(parts_folder(out).glob("part-*.parquet"))) < 3:
        time.sleep(0.05)
    os.killpg(first.pid, signal.SIGKILL)  # the sweep and its workers, half-way
    first.wait()
    parts = sorted(parts_folder(out).glob("part-*.parquet"))
    done = pd.concat([pd.read_parquet(p) for p in parts])
    assert 0 < len(done) < 400 and not out.exists()
    second = subprocess.run(command, capture_output=True, text=True, timeout=300)
    assert second.returncode == 0, second.stderr
    assert second.stderr == ""  # no log lines of Dask's on a successful run
    summary = json.loads(second.stdout)
    assert summary["resumed"] == len(done) and summary["computed"] == 400 - len(done)
    table = pd.read_parquet(out)
    assert len(table) == 400 and table["key"].is_unique and sorted(table["variant"]) == list(range(400))
    assert not parts_folder(out).exists()
    kept = table.set_index("key").loc[done["key"], "blow_hole_area_mm2"].to_numpy()
    assert np.allclose(kept, done["blow_hole_area_mm2"].to_numpy(), equal_nan=True)  # the first run's rows kept


def test_python_api_returns_the_table(tmp_path, capsys):
    import rotorcad

    sweep_file = _write(tmp_path, '[vary]\n"profile.lobe_width" = [0.66, 0.7]\n')
    table = rotorcad.sweep(sweep_file, workers=1)
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
    assert main(["sweep", str(sweep_file), "--out", str(tmp_path / "r.parquet"), "--workers", "1", "--quiet"]) == 0
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
    args = ["sweep", str(sweep_file), "--out", str(tmp_path / "r.parquet"), "--workers", "1", "--quiet"]
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
    assert main(["sweep", str(first), "--out", str(out), "--workers", "1", "--quiet"]) == 0
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
    assert main(["sweep", str(longer), "--out", str(out), "--workers", "1", "--json"]) == 0
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
    assert main(["sweep", str(sweep_file), "--out", str(tmp_path / "r.parquet"), "--workers", "1", "--json"]) == 0
    summary = json.loads(capsys.readouterr().out)
    assert summary["failed"] == 3 and list(summary["failures"].values()) == [3]

"""Regression tests for the examples of issue 24 ("Every input gets an answer, part 2"): each test
names the example it covers and uses its exact input. Fast: refusals come before any heavy work."""

from __future__ import annotations

import json
import os
import re
import signal
import subprocess
import sys
import textwrap
import time
from pathlib import Path

import numpy as np
import pytest

from rotorcad.cli.main import main

ROOT = Path(__file__).resolve().parents[1]
SAMPLES = ROOT / "samples"


def run(capsys, *argv: object) -> tuple[int, str, str]:
    capsys.readouterr()
    status = main([str(a) for a in argv])
    out, err = capsys.readouterr()
    assert "Traceback" not in err
    return status, out, err


def refused(capsys, needle: str, *argv: object) -> str:
    status, _, err = run(capsys, *argv)
    lines = [ln for ln in err.splitlines() if ln.strip()]
    assert status == 2 and len(lines) == 1 and needle in lines[0], err
    return lines[0]


def _alive(pid: int) -> bool:
    """Whether ``pid`` is a live process (a zombie, dead but not yet reaped, counts as gone)."""
    try:
        with open(f"/proc/{pid}/stat") as f:
            return f.read().rsplit(")", 1)[1].split()[0] != "Z"
    except OSError:
        return False


@pytest.mark.skipif(sys.platform != "linux", reason="the worker process exists on Linux only")
def test_worker_dies_with_a_parent_killed_by_sigkill(tmp_path):
    """An `export` killed at a time limit left its background writer alive for 42 minutes: the
    parent is killed with SIGKILL while its worker waits, and the worker must be gone within 5 s."""
    script = textwrap.dedent(
        f"""
        import os, sys, time
        sys.path.insert(0, {str(ROOT)!r})
        from exports.background import WorkerPool
        pool = WorkerPool()
        assert pool._executor is not None, "no worker"
        pids = list(pool._executor._processes)
        print(" ".join(map(str, pids)), flush=True)
        time.sleep(600)
        """
    )
    env = {**os.environ, "ROTORCAD_WORKERS": "1"}
    parent = subprocess.Popen([sys.executable, "-c", script], stdout=subprocess.PIPE, text=True, env=env)
    workers: list[int] = []
    try:
        line = parent.stdout.readline()
        workers = [int(p) for p in line.split()]
        assert workers and all(_alive(p) for p in workers), line
        parent.send_signal(signal.SIGKILL)
        parent.wait(10)
        deadline = time.monotonic() + 5.0
        while any(_alive(p) for p in workers) and time.monotonic() < deadline:
            time.sleep(0.05)
        assert not any(_alive(p) for p in workers), f"worker {workers} outlived its parent"
    finally:
        if parent.poll() is None:
            parent.kill()
        for pid in workers:  # a worker left by a failure: end it here, not at the end of the run
            if _alive(pid):
                os.kill(pid, signal.SIGKILL)


# ----- DXF points files -----------------------------------------------------------------------
CLEARANCE = ["--male-teeth", "4", "--female-teeth", "6", "--center-distance", "100"]


@pytest.fixture(scope="module")
def outlines(tmp_path_factory) -> dict[str, np.ndarray]:
    """The symmetric sample's male and female outlines as `rotor --male-csv` writes them."""
    folder = tmp_path_factory.mktemp("outlines")
    argv = ["rotor", str(SAMPLES / "srm_symmetric_4_6.toml"), "--male-csv", str(folder / "m.csv")]
    assert main([*argv, "--female-csv", str(folder / "f.csv")]) == 0
    return {s: np.loadtxt(folder / f"{s[0]}.csv", delimiter=",", comments="#", skiprows=2) for s in ("male", "female")}


def polyline_dxf(path: Path, pts: np.ndarray, closed: bool = True) -> Path:
    """One LWPOLYLINE through ``pts`` (drawn with ezdxf, the project's DXF library)."""
    import ezdxf

    doc = ezdxf.new()
    doc.modelspace().add_lwpolyline(np.asarray(pts, dtype=float).tolist(), close=closed)
    doc.saveas(path)
    return path


def test_dxf_points_with_one_nan_coordinate(capsys, tmp_path, outlines):
    """`clearance --male-points male.dxf` with one `nan` coordinate: ZeroDivisionError in `_segment`."""
    male = outlines["male"].copy()
    male[5, 0] = np.nan
    m = polyline_dxf(tmp_path / "male.dxf", male)
    f = polyline_dxf(tmp_path / "female.dxf", outlines["female"])
    line = refused(capsys, "--male-points", "clearance", "--male-points", m, "--female-points", f, *CLEARANCE)
    assert "NaN or infinite" in line and "LWPOLYLINE" in line


def test_male_dxf_scaled_1e9(capsys, tmp_path, outlines):
    """A male DXF scaled x1e9: IndexError in `in_contract_frame`. Refused naming its farthest point,
    54 mm x 1e9 (the sample's [pair] male_tip_radius); points x1e3 (within 100 m) are refused against
    the centre distance instead."""
    m = polyline_dxf(tmp_path / "male.dxf", outlines["male"] * 1e9)
    f = polyline_dxf(tmp_path / "female.dxf", outlines["female"])
    line = refused(capsys, "--male-points", "clearance", "--male-points", m, "--female-points", f, *CLEARANCE)
    assert "5.4e+10 mm" in line
    csv = tmp_path / "male.csv"
    csv.write_text("x,y\n" + "\n".join(f"{float(x)!r},{float(y)!r}" for x, y in outlines["male"] * 1e3) + "\n")
    line = refused(capsys, "--male-points", "clearance", "--male-points", csv, "--female-points", f, *CLEARANCE)
    assert "54000 mm" in line and "--center-distance" in line


def test_clearance_lead_1e9_refused_with_the_longest_lead(capsys, tmp_path, outlines):
    """`clearance --lead 1e9` returned zeros and nulls on exit 0: no segment of the contact line
    lies within the 190 mm rotors. A lead beyond 100 m is refused as a design length; within it, a
    lead that leaves the flanks' contact zone outside the rotors is refused naming the longest lead
    that does not, and just below that bound there is a band (the rack-involute pair: the symmetric
    one, its polylines read as points as its CSV files are, keeps a contact run up to 100 m)."""
    m = polyline_dxf(tmp_path / "male.dxf", outlines["male"])
    f = polyline_dxf(tmp_path / "female.dxf", outlines["female"])
    argv = ["clearance", "--male-points", m, "--female-points", f, *CLEARANCE, "--json"]
    refused(capsys, "--lead must be a positive length up to 100000 mm", *argv, "--lead", "1e9")
    rotor = ["rotor", str(SAMPLES / "rack_involute_5_6.toml"), "--male-csv", str(tmp_path / "m.csv")]
    assert main([*rotor, "--female-csv", str(tmp_path / "f.csv"), "--quiet"]) == 0
    drawn = {s: np.loadtxt(tmp_path / f"{s}.csv", delimiter=",", comments="#", skiprows=2) for s in "mf"}
    m, f = polyline_dxf(tmp_path / "ri_male.dxf", drawn["m"]), polyline_dxf(tmp_path / "ri_female.dxf", drawn["f"])
    argv = ["clearance", "--male-points", m, "--female-points", f, "--male-teeth", "5", "--female-teeth", "6"]
    argv += ["--center-distance", "116", "--json"]
    line = refused(capsys, "--lead must be at most", *argv, "--lead", "1e5")
    bound = float(re.search(r"at most ([0-9.e+]+) mm", line).group(1))
    status, out, _ = run(capsys, *argv, "--lead", f"{bound * 0.999:.6g}")
    res = json.loads(out)
    assert status == 0 and res["mean_clearance"] is not None and res["band_area"] > 0


@pytest.mark.parametrize("gap", [0.002, 0.05])
def test_open_dxf_outline_refused_naming_the_gap(capsys, tmp_path, outlines, gap):
    """A DXF outline with an open gap was accepted by `rotor` and `interfere` (exit 0): a gap
    wider than the joining accuracy (1 um) is refused, naming its size and place."""
    pts = outlines["male"]
    m = polyline_dxf(tmp_path / "male.dxf", np.vstack([pts, pts[:1] + [gap, 0.0]]), closed=False)
    for argv in (
        ["interfere", SAMPLES / "srm_symmetric_4_6.toml", "--steps", "2"],
        ["rotor", SAMPLES / "srm_symmetric_4_6.toml"],
    ):
        line = refused(capsys, "--male-points", *argv, "--male-points", m)
        assert f"gap of {gap:g} mm" in line and f"({40 + gap:.6f}, 0.000000) mm" in line


def test_dxf_outline_closed_within_the_accuracy_says_so(capsys, tmp_path, outlines):
    """A gap of 0.8 um (within the 1 um joining accuracy) is closed, and the run says so."""
    pts = outlines["male"]
    m = polyline_dxf(tmp_path / "male.dxf", np.vstack([pts, pts[:1] + [0.0008, 0.0]]), closed=False)
    status, _, err = run(capsys, "interfere", SAMPLES / "srm_symmetric_4_6.toml", "--steps", "2", "--male-points", m)
    assert status in (0, 1)
    assert "rotorcad: note: --male-points" in err and "gap of 0.0008 mm" in err and "(40.000800, -0.000000) mm" in err


# ----- designs --------------------------------------------------------------------------------
@pytest.mark.parametrize("command", [["cut"], ["gear"], ["pump", "--face-width", "10", "--speed", "1500"], ["report"]])
def test_shift_10_to_the_30_in_a_design(capsys, tmp_path, command):
    """An integer too large for a float in a design (`shift = 10**30`): TypeError in `gear.py`
    `__post_init__` from cut, gear, pump, report. 10**30 is 1e30 (refused by the range of the shift);
    10**400 is beyond any float (refused as such)."""
    text = (SAMPLES / "gear_pair.toml").read_text()
    extra = ["--out", tmp_path / "r.html"] if command[0] == "report" else []
    for power, needle in ((30, "[gear] shift must be between -2 and 3"), (400, "[gear] shift must be a number below 1.8e308")):
        path = tmp_path / f"shift{power}.toml"
        path.write_text(re.sub(r"^shift = 0.3", f"shift = {10**power}", text, flags=re.M))
        refused(capsys, needle, command[0], path, *command[1:], *extra)
    assert not (tmp_path / "r.html").exists()


# ----- export ---------------------------------------------------------------------------------
def _face_points(path: Path, per_face: int = 7) -> np.ndarray:
    """Points on the side faces of a STEP solid, read back by OpenCASCADE's STEP reader (a grid in
    each face's parameter range), end caps left out."""
    from OCP.BRep import BRep_Tool
    from OCP.BRepTools import BRepTools
    from OCP.STEPControl import STEPControl_Reader
    from OCP.TopAbs import TopAbs_FACE
    from OCP.TopExp import TopExp_Explorer
    from OCP.TopoDS import TopoDS

    reader = STEPControl_Reader()
    assert reader.ReadFile(str(path)) == 1  # IFSelect_RetDone
    reader.TransferRoots()
    explorer, out = TopExp_Explorer(reader.OneShape(), TopAbs_FACE), []
    uv = np.linspace(0.0, 1.0, per_face)
    while explorer.More():
        face = TopoDS.Face(explorer.Current())
        surface = BRep_Tool.Surface_s(face)
        u0, u1, v0, v1 = BRepTools.UVBounds_s(face)
        pts = [surface.Value(u0 + a * (u1 - u0), v0 + b * (v1 - v0)) for a in uv for b in uv]
        pts = np.array([[p.X(), p.Y(), p.Z()] for p in pts])
        if np.ptp(pts[:, 2]) > 1e-6:
            out.append(pts)
        explorer.Next()
    return np.vstack(out)


def test_step_of_a_module_100_spur_gear_meets_its_tolerance(capsys, tmp_path):
    """`export` of a module-100 spur gear at `--tolerance 0.5`: "the STEP surface is 5.33 um from
    the helicoid, more than the tolerance 1 um" (the B-spline fit was sampled too sparsely). The
    faces read back by OpenCASCADE lie within 1 um of the gear's outline; the distance is shapely's
    (GEOS), not the writer's own check."""
    import shapely

    from rotorcad.cli.gear import build_gear, merge_gear_params

    text = "[gear]\nteeth = 17\nmodule = 100.0\nshift = 0.3\n"
    design = tmp_path / "m100.toml"
    design.write_text(text)
    argv = ["export", design, "--out", tmp_path / "o", "--format", "step", "--tolerance", "0.5", "--json", "--quiet"]
    status, out, err = run(capsys, *argv)
    assert status == 0, err
    (row,) = json.loads(out)["files"]
    assert row["tolerance"] <= 1e-3
    gear, _ = build_gear(merge_gear_params(design, {}), 1e-3)
    ring = gear.outline(1e-5).points  # chord 0.01 um
    edges = shapely.linestrings(np.stack([ring, np.roll(ring, -1, axis=0)], axis=1))
    pts = _face_points(Path(row["path"]))
    _, distance = shapely.STRtree(edges).query_nearest(shapely.points(pts[:, :2]), return_distance=True)
    assert len(pts) > 1000 and distance.max() < 1e-3, distance.max()


def test_export_format_given_twice_is_one_file(capsys, tmp_path):
    """`export --format stl,stl` wrote two rows for the same path."""
    argv = ["export", SAMPLES / "gear_pair.toml", "--out", tmp_path / "o", "--format", "stl,stl,STL", "--json", "--quiet"]
    status, out, _ = run(capsys, *argv)
    paths = [f["path"] for f in json.loads(out)["files"]]
    assert status == 0 and len(paths) == len(set(paths)) == 2 == len(list((tmp_path / "o").iterdir())), paths


def test_faceted_step_coarser_than_asked_is_refused(capsys, tmp_path):
    """`--format step-faceted` of the rack-involute sample was written at 3.1 / 3.36 mm where 5 um
    were asked (volume -3.1 %), exit 0, and `--tolerance 0.05` gave a coarser file (2.4 mm) than the
    default: now refused naming --tolerance and the tolerance that could be met, nothing written."""
    design = SAMPLES / "rack_involute_5_6.toml"
    for extra in ([], ["--tolerance", "0.05"]):
        line = refused(
            capsys,
            "--tolerance must be coarser for a faceted STEP",
            "export",
            design,
            "--out",
            tmp_path / "o",
            "--format",
            "step-faceted",
            "--quiet",
            *extra,
        )
        assert not (tmp_path / "o").exists()
        above = re.search(r"only ([0-9.e+-]+) mm would, above the 1 mm allowed", line)
        named = above or re.search(r"([0-9.e+-]+) mm or coarser would do", line)
        assert named, line
    if not above:  # the tolerance named must do: the file is written at it
        status, _, err = run(
            capsys,
            "export",
            design,
            "--out",
            tmp_path / "o",
            "--format",
            "step-faceted",
            "--quiet",
            "--tolerance",
            named.group(1),
        )
        assert status == 0 and (tmp_path / "o").is_dir(), err


# ----- files already there ----------------------------------------------------------------------
def test_report_files_names_what_it_replaces(capsys, tmp_path):
    """`report --files` silently replaced male.csv, pair.dxf, hob.dxf already in that folder. One
    policy for all commands (CONTRACT.md): replaced whole and named, on stderr and in the JSON;
    a folder of the user's other files keeps them. The gear sample (its files gear.csv, gear.dxf,
    hob.dxf; the same writer as a rotor pair's, in a third of the time)."""
    folder = tmp_path / "files"
    folder.mkdir()
    for name in ("gear.csv", "gear.dxf", "hob.dxf", "male.csv", "notes.txt"):
        (folder / name).write_text("the user's own file\n")
    argv = ["report", SAMPLES / "gear_pair.toml", "--out", tmp_path / "r.html", "--files", folder, "--json"]
    status, out, err = run(capsys, *argv)
    replaced = json.loads(out)["replaced"]
    assert status == 0 and sorted(Path(p).name for p in replaced) == ["gear.csv", "gear.dxf", "hob.dxf"]
    (note,) = [ln for ln in err.splitlines() if ln.strip()]
    assert note.startswith("rotorcad: note: replaced the existing files") and "(--files)" in note
    assert all(str(folder / n) in note for n in ("gear.csv", "gear.dxf", "hob.dxf")) and "r.html" not in note
    assert (folder / "male.csv").read_text() == "the user's own file\n"
    assert (folder / "notes.txt").read_text() == "the user's own file\n"
    assert (folder / "gear.csv").read_text() != "the user's own file\n"


def test_export_rows_say_which_file_was_replaced(capsys, tmp_path):
    """The same policy for `export`: each file row says whether it replaced a file."""
    out = tmp_path / "o"
    out.mkdir()
    (out / "gear_pair_gear.stl").write_text("the user's own file\n")
    status, text, err = run(capsys, "export", SAMPLES / "gear_pair.toml", "--out", out, "--format", "stl", "--json", "--quiet")
    rows = {Path(r["path"]).name: r["replaced"] for r in json.loads(text)["files"]}
    assert status == 0 and rows == {"gear_pair_gear.stl": True, "gear_pair_mate.stl": False}
    assert "replaced the existing file " in err and "gear_pair_gear.stl (--out)" in err


def test_dxf_mesh_r12_refused_before_any_sweep(capsys, tmp_path, monkeypatch):
    """`export --format dxf-mesh-r12` took 18 s to refuse: refused now on the estimate before the
    fine solids are swept (the sweep at the asked tolerance, 5 um, is never made)."""
    import rotorcad.solids as solids

    tolerances = []
    real = solids.helical_solid
    monkeypatch.setattr(solids, "helical_solid", lambda s, h, length, t: tolerances.append(t) or real(s, h, length, t))
    design = SAMPLES / "srm_symmetric_4_6.toml"
    line = refused(
        capsys,
        "--tolerance must be coarser for a DXF mesh",
        "export",
        design,
        "--format",
        "dxf-mesh-r12",
        "--quiet",
        "--out",
        tmp_path / "a",
    )
    needed = float(re.search(r"([0-9.]+) mm or coarser would do", line).group(1))
    # only the checks of coarse tolerances (each body's own need; the one named is the coarsest of them)
    assert tolerances and min(tolerances) > 10 * 0.005 and max(tolerances) == pytest.approx(needed, rel=1e-12)
    assert not (tmp_path / "a").exists()


# ----- kills ----------------------------------------------------------------------------------
def test_temporaries_of_a_killed_run_are_removed_by_the_next(tmp_path):
    """SIGKILL leaves a writer's hidden temporary (nothing runs on SIGKILL); the next run writing
    the same file removes it, but never the temporary of a process still running."""
    from exports.atomic import staging_prefix, write_all

    target = tmp_path / "male.csv"
    dead = subprocess.Popen([sys.executable, "-c", "pass"])
    dead.wait()  # a process id that no longer runs
    stale = tmp_path / f"{staging_prefix(target)}{dead.pid}.abc123.tmp"
    live = tmp_path / f"{staging_prefix(target)}{os.getppid()}.def456.tmp"
    for p in (stale, live):
        p.write_text("half")
    write_all([(target, lambda p: Path(p).write_text("x,y\n"))])
    assert target.read_text() == "x,y\n" and not stale.exists() and live.exists()


def test_sigterm_leaves_no_temporary_and_says_so(tmp_path):
    """A command stopped by SIGTERM (a time limit) unwinds like Ctrl-C: one line, exit 143, no
    temporary and the user's file unchanged."""
    user = tmp_path / "user.csv"
    user.write_text("the user's own file\n")
    code = "import sys; from rotorcad.cli.main import main; sys.exit(main(sys.argv[1:]))"
    # issue 24's slow cut: some 5 s of work alone (18 s under load), stopped after 2.5 s
    argv = ["cut", "--teeth", "150", "--module", "100", "--tip-radius", "0", "--mate-teeth", "150", "--csv", str(user)]
    proc = subprocess.Popen([sys.executable, "-c", code, *argv], stderr=subprocess.PIPE, text=True)
    time.sleep(2.5)
    proc.send_signal(signal.SIGTERM)
    _, err = proc.communicate(timeout=30)
    assert proc.returncode == 143 and err.strip().splitlines()[-1] == "rotorcad: terminated.", err
    assert user.read_text() == "the user's own file\n" and [p.name for p in tmp_path.iterdir()] == ["user.csv"]


# ----- slow answers ---------------------------------------------------------------------------
def test_a_command_working_past_the_wait_shows_a_bar(capsys, monkeypatch):
    """Anything over 2 s shows a progress bar on a terminal (issue 24: `interfere` with a DXF male
    and `--steps 1`, `coupling`, `hob` ran seconds with none before their own stage began). The wait
    is cut to 10 ms here; `hob` has no bar of its own, so the command's "working" bar is drawn."""
    from rotorcad.cli import progress

    monkeypatch.setattr(progress, "on_terminal", lambda: True)
    monkeypatch.setattr(progress, "WAIT_SECONDS", 0.01)
    opened = len(progress.OPENED)
    status, _, err = run(capsys, "hob", "--teeth", "17", "--module", "2")
    assert status == 0 and progress.OPENED[opened:] == ["working"] and "━" in err
    opened = len(progress.OPENED)
    status, _, err = run(capsys, "hob", "--teeth", "17", "--module", "2", "--quiet")
    assert status == 0 and progress.OPENED[opened:] == [] and "━" not in err


# ----- found by the long fuzz run (seeds 240101-240104) ----------------------------------------
def test_rotor_design_integer_key_beyond_float_range(capsys, tmp_path):
    """`[pair] male_teeth = 10**400`: OverflowError in `rotor` (an integer key, not converted)."""
    text = re.sub(
        r"^male_teeth = .*$", "male_teeth = 1" + "0" * 400, (SAMPLES / "srm_asymmetric_5_6.toml").read_text(), flags=re.M
    )
    path = tmp_path / "d.toml"
    path.write_text(text)
    refused(capsys, "[pair] male_teeth must be a number below 1.8e308", "rotor", path)


def test_interfere_names_the_design_key_of_the_speed(capsys, tmp_path):
    """`interfere` refused `[operating] speed_rpm = -2147432697499774` naming `--speed`, an option
    it does not have."""
    text = (SAMPLES / "srm_asymmetric_5_6.toml").read_text()
    text = re.sub(r"^speed_rpm = .*$", "speed_rpm = -2147432697499774.0", text, flags=re.M)
    if "speed_rpm" not in text:
        text = text.replace("[operating]\n", "[operating]\nspeed_rpm = -2147432697499774.0\n")
    path = tmp_path / "d.toml"
    path.write_text(text)
    line = refused(capsys, "[operating] speed_rpm must be a positive speed", "interfere", path, "--steps", "2")
    assert "--speed" not in line


def test_dxf_of_arcs_scaled_1e9_refused_at_once(capsys, tmp_path, outlines):
    """A drawing of arcs (bulges) scaled x1e9 hung `rotor --male-points` for minutes (its arcs
    sampled to 0.1 um): refused naming the farthest point, 54 mm x 1e9 (the tip radius)."""
    import ezdxf

    pts = outlines["male"][::2] * 1e9
    doc = ezdxf.new()
    doc.modelspace().add_lwpolyline([(x, y, 0, 0, 0.01) for x, y in pts], format="xyseb", close=True)
    doc.saveas(tmp_path / "male.dxf")
    pair = ["--male-teeth", "4", "--female-teeth", "6", "--center-distance", "100", "--male-tip-radius", "54"]
    pair += ["--male-root-radius", "40", "--female-tip-radius", "60", "--female-root-radius", "46", "--lead", "260"]
    started = time.monotonic()
    line = refused(
        capsys, "--male-points must be a profile within 100000 mm", "rotor", "--male-points", tmp_path / "male.dxf", *pair
    )
    assert "5.4e+10 mm" in line and time.monotonic() - started < 30


def test_profile_key_beyond_float_range(capsys, tmp_path):
    """`[profile] seal_stop = 10**400`: OverflowError in `rotor` (a family's key, read apart from
    the tables of fixed keys)."""
    text = (SAMPLES / "srm_asymmetric_5_6.toml").read_text()
    path = tmp_path / "d.toml"
    path.write_text(re.sub(r"^seal_stop = .*$", "seal_stop = 1" + "0" * 400, text, count=1, flags=re.M))
    refused(capsys, "[profile] seal_stop must be a number below 1.8e308", "rotor", path)


def test_interrupt_swallowed_by_a_library_still_stops_the_command(capsys, monkeypatch):
    """Ctrl-C during `interfere` gave "internal error (TypeError: unsupported operand type(s) for |:
    'ExceptionWrapper' and 'NoneType')", exit 70: trimesh wraps any exception of its imports, the
    KeyboardInterrupt included, and fails later. The signal is remembered: one line, exit 130."""
    import rotorcad.cli.gear as gear_cli

    def swallowing(*args, **kwargs):
        try:  # as trimesh's soft imports do
            os.kill(os.getpid(), signal.SIGINT)
            time.sleep(1.0)
        except BaseException:
            pass
        raise TypeError("unsupported operand type(s) for |: 'ExceptionWrapper' and 'NoneType'")

    monkeypatch.setattr(gear_cli, "build_gear", swallowing)
    status, _, err = run(capsys, "gear", "--teeth", "17", "--module", "2")
    assert status == 130 and err.strip() == "rotorcad: interrupted."


def test_export_of_a_gear_design_names_its_keys_when_flanks_never_meet(capsys, tmp_path):
    """`export` of a gear design with `[mate] center_distance = 1e30` was refused naming --teeth,
    --mate-teeth, ... options `export` does not have: the design's keys are named. (1e30 is now
    refused as a length beyond 100 m; 1e4 mm, within it, still leaves the flanks apart.)"""
    text = (SAMPLES / "gear_pair.toml").read_text().replace("[mate]\n", "[mate]\ncenter_distance = 1e4\n")
    path = tmp_path / "g.toml"
    path.write_text(text)
    line = refused(capsys, "[mate] center_distance", "export", path, "--out", tmp_path / "o", "--format", "stl")
    assert "--" not in line.split(" must ")[0] and "[gear] teeth" in line


def test_clearance_opens_a_progress_stage(capsys, tmp_path, outlines):
    """`clearance` ran 68 s (under load) without a progress bar: its work is a stage of its own."""
    from rotorcad.cli import progress

    m = polyline_dxf(tmp_path / "male.dxf", outlines["male"])
    f = polyline_dxf(tmp_path / "female.dxf", outlines["female"])
    opened = len(progress.OPENED)
    run(capsys, "clearance", "--male-points", m, "--female-points", f, *CLEARANCE, "--lead", "1e9")
    assert progress.OPENED[opened:] == ["clearance: racks, contact and band"]


def test_coupling_teeth_beyond_float_range(capsys):
    """`coupling --teeth 10**400`: OverflowError (exit 70) in the long run."""
    argv = ["coupling", "--teeth", "1" + "0" * 400, "--module", "3", "--face-width", "20", "--speed", "1500"]
    argv += ["--viscosity", "0.05", "--power", "50", "--misalignment-deg", "0.1"]
    refused(capsys, "--teeth must be a whole number from 6 to 1000 (got an integer of 401 digits)", *argv)


def test_rotor_family_check_names_the_option_typed(capsys):
    """`rotor srm_symmetric_4_6.toml --male-root-radius 1e-12` named `male_root_radius`."""
    refused(
        capsys,
        "--male-root-radius must be equal to the male pitch radius",
        "rotor",
        SAMPLES / "srm_symmetric_4_6.toml",
        "--male-root-radius",
        "1e-12",
    )


def test_interfere_self_crossing_dxf_refused(capsys, tmp_path, outlines):
    """`interfere --male-points` of a self-crossing DXF outline: GEOSException (exit 70) in the
    long run. Two points swapped make the crossing; shapely (GEOS) names where."""
    pts = outlines["male"].copy()
    pts[[100, 107]] = pts[[107, 100]]
    m = polyline_dxf(tmp_path / "male.dxf", pts)
    line = refused(
        capsys,
        "--male-points must be an outline that does not cross itself",
        "interfere",
        SAMPLES / "srm_symmetric_4_6.toml",
        "--male-points",
        m,
        "--steps",
        "2",
    )
    assert re.search(r"crosses itself at \(-?[0-9.]+, -?[0-9.]+\) mm\.$", line)  # where, read from the drawing


def test_grind_out_folder_name_too_long_is_refused(capsys, tmp_path):
    """Found by the fuzz suite's `grind` cases: an --out of 300 characters (beyond the file
    system's 255) made Path.exists raise ENAMETOOLONG, an internal error (exit 70)."""
    out = tmp_path / ("n" * 300)
    line = refused(capsys, "--out", "grind", SAMPLES / "gear_pair.toml", "--wheel-radius", "100", "--quiet", "--out", out)
    assert "File name too long" in line
    assert list(tmp_path.iterdir()) == []


def test_grind_and_hob_take_the_smoothing_their_refusal_names(capsys, tmp_path):
    """Found by the fuzz suite's `grind` cases: a noisy female's points were refused naming
    --smoothing, an option grind did not have; hob and grind now take it as rotor does (the
    same points reader), and a smoothing given is used: the refusal then quotes other numbers."""
    import click

    from rotorcad.cli.main import cli

    def options_of(command: str) -> set[str]:
        return {opt for p in cli.get_command(click.Context(cli), command).params for opt in p.opts}

    for command in ("grind", "hob"):
        assert "--smoothing" in options_of(command), command
    sample = tmp_path / "sample.csv"
    assert run(capsys, "rotor", SAMPLES / "srm_symmetric_4_6.toml", "--female-csv", sample)[0] == 0
    pts = np.loadtxt(sample, delimiter=",", skiprows=2)
    pts += np.random.default_rng(7).normal(0, 0.05, pts.shape)  # 50 µm scatter: a mate with folds
    path = tmp_path / "female.csv"
    np.savetxt(path, pts, delimiter=",", header="x,y", comments="")
    dims = ["--male-teeth", "4", "--female-teeth", "6", "--center-distance", "100", "--male-tip-radius", "54"]
    dims += ["--male-root-radius", "40", "--female-tip-radius", "60", "--female-root-radius", "46"]
    status, _, err = run(capsys, "grind", "--female-points", path, "--rotor", "female", "--wheel-radius", "100", *dims)
    assert status == 2 and len(err.strip().splitlines()) == 1, err
    assert "--smoothing" in err  # the remedy it names is an option of grind
    mentioned = set(re.findall(r"--[a-z][a-z-]*", err))
    assert mentioned <= options_of("grind"), (mentioned - options_of("grind"), err)


@pytest.mark.parametrize("command", ["gear", "cut"])
def test_pitch_circle_below_the_root_circle_gives_no_thickness(capsys, command):
    """Found by the long fuzz run: z = 17, m = 2, x = h_a* = 1.4769 was refused naming "radius"
    (no option) because the summary asked for the tooth thickness on the pitch circle, which lies
    below the root circle: r_f = r + (x - h_fP*) m = 17 + (1.4769 - 1.25) 2 = 17.454 mm > 17 mm
    (ISO 21771 root diameter). The gear is reported, its pitch-circle thickness null."""
    argv = [command, "--teeth", "17", "--module", "2", "--shift", "1.4768517364325604", "--addendum", "1.4768517364325604"]
    status, out, err = run(capsys, *argv, *(["--tolerance", "0.02"] if command == "cut" else []), "--json")
    assert status == 0, err
    result = json.loads(out)
    assert result["tooth_thickness_pitch"] is None
    if command == "gear":
        assert result["root_radius"] == pytest.approx(17 + (1.4768517364325604 - 1.25) * 2, abs=1e-9)
    # a gear whose pitch circle is on the tooth keeps the closed form s = m (pi/2 + 2 x tan(alpha))
    status, out, _ = run(capsys, "gear", "--teeth", "17", "--module", "2", "--shift", "0.3", "--json")
    assert json.loads(out)["tooth_thickness_pitch"] == pytest.approx(2 * (np.pi / 2 + 0.6 * np.tan(np.radians(20))), abs=1e-6)


def test_clearance_of_points_whose_contacts_jump_is_bounded(capsys):
    """Found by the long fuzz run (its kept case wq7zryhc: the symmetric sample's male and female,
    the female with 0.5 µm normal scatter): ``clearance`` ran past 120 s at 1.5 GB, because the
    datum rack was refined until its contact points lay 0.05 mm apart along a "meshline" of 596 m
    (the fit's normals swung the contacts back and forth: 56 666 samples became 2.3 million). Now
    an answer within a bounded time and memory: the contact refinement stops where a split does
    not shrink the gap and at 20 rack periods of meshline."""
    data = ROOT / "tests" / "reference_data" / "fuzz"
    start = time.process_time()
    status, _, err = run(
        capsys,
        "clearance",
        "--male-points",
        data / "clearance_wq7zryhc_male.csv",
        "--female-points",
        data / "clearance_wq7zryhc_female.csv",
        "--male-teeth",
        "4",
        "--female-teeth",
        "6",
        "--center-distance",
        "100",
        "--json",
        "--quiet",
    )
    assert status in (0, 2), err
    assert status == 0 or len(err.strip().splitlines()) == 1
    assert time.process_time() - start < 30.0  # CPU seconds (was over 100; 2 s alone on an idle core)


def test_internal_gear_refusals_point_the_right_way(capsys):
    """A new user's findings: (1) the involute interference of cutting a 40-tooth ring (h_a* = 0.8)
    with a 16-tooth shaper advised "a cutter with fewer teeth", but a 12-tooth cutter is worse and a
    20-tooth one passes (DIN 3993: the cutter's base tangency point moves out with its tooth count);
    (2) a centre distance the pinion cannot meet was blamed on --mate-shift, which was not typed."""
    line = refused(
        capsys, "--teeth", "gear", "--internal", "--teeth", "40", "--module", "2", "--addendum", "0.8", "--cutter-teeth", "16"
    )
    assert "more teeth" in line and "fewer teeth" not in line
    # the closed form (x2 = x0 = 0, so the cutting pressure angle is alpha): the ring's involute is
    # generated from the cutter's base tangency point T0 outwards, T2 T0 = (r_b2 - r_b0) tan(alpha)
    # along the line of action from the ring's own tangency point T2; the tip circle must lie beyond
    # it: sqrt(r_a2^2 - r_b2^2) >= T2 T0, r_a2 = r2 - h_a* m (ISO 21771 internal gear, DIN 3993)
    alpha, m, z2 = np.radians(20.0), 2.0, 40
    r_b2, r_a2 = z2 * m / 2 * np.cos(alpha), z2 * m / 2 - 0.8 * m
    for z0 in (12, 14, 16, 18, 20, 22):
        interferes = np.sqrt(r_a2**2 - r_b2**2) < (r_b2 - z0 * m / 2 * np.cos(alpha)) * np.tan(alpha)
        argv = ["gear", "--internal", "--teeth", "40", "--module", "2", "--addendum", "0.8", "--cutter-teeth", str(z0), "--json"]
        status, _, err = run(capsys, *argv)
        assert ("involute interference" in err) == bool(interferes), (z0, err)
        assert status == (2 if interferes else status), (z0, err)
    line = refused(
        capsys,
        "--center-distance",
        *("gear", "--internal", "--teeth", "60", "--module", "2", "--addendum", "0.8", "--cutter-teeth", "20"),
        *("--mate-teeth", "41", "--center-distance", "30"),
    )
    assert "--mate-shift" not in line
    # the pinion shift that centre distance asks for, ISO 21771 for an internal pair:
    # cos(alpha_w) = (r2 - r1) cos(alpha) / a, x1 = x2 - (inv(alpha_w) - inv(alpha)) (z2 - z1) / (2 tan(alpha))
    alpha_w = np.arccos((60 - 41) * m / 2 * np.cos(alpha) / 30.0)
    x1 = -((np.tan(alpha_w) - alpha_w) - (np.tan(alpha) - alpha)) * (60 - 41) / (2 * np.tan(alpha))
    needed = float(re.search(r"this one needs (-?[0-9.]+)", line).group(1))
    assert needed == pytest.approx(x1, abs=0.01)


def test_inspect_refuses_a_rotor_side_for_a_gear(capsys, tmp_path):
    """A new user's finding: `inspect --rotor female` with a gear was silently ignored (exit 0)."""
    points = tmp_path / "teeth.csv"
    assert run(capsys, "gear", "--teeth", "20", "--module", "2", "--csv", points, "--quiet")[0] == 0
    refused(capsys, "--rotor", "inspect", "--teeth", "20", "--module", "2", "--points", points, "--rotor", "female")


def test_hob_says_it_does_not_make_a_tip_chamfer(capsys):
    """A new user's finding: `hob samples/gear_part.toml` wrote the rack of the same gear without its
    0.3 mm tip chamfer, byte for byte, and said nothing; a hob of the ISO 53 basic rack cannot break
    the tip corners (a semi-topping hob does). Now a note says so; the plain gear has none."""
    status, out, _ = run(capsys, "hob", SAMPLES / "gear_part.toml", "--json")
    notes = json.loads(out)["notes"]
    assert status == 0 and len(notes) == 1 and "tip_chamfer" in notes[0] and "0.3 mm" in notes[0]
    status, out, _ = run(capsys, "hob", SAMPLES / "gear_pair.toml", "--json")
    assert status == 0 and json.loads(out)["notes"] == []


def test_contact_refinement_still_reaches_its_step_on_a_continuous_curve():
    """The bound on the contact refinement (above) must not stop it where the meshline is real: a
    circular arc (radius 5 mm, centre 2 mm outside the pitch circle r = 40 mm) on a turning body,
    its rack generated by the envelope engine, is refined until consecutive contact points lie at
    most the step apart (the definition of ``contact_step``); and with a meshline budget of 1 mm the
    samples grow by at most 1 mm / step."""
    from rotorcad.curves import Arc
    from rotorcad.envelope import Generated
    from rotorcad.inverse_rack import _refine_by_contact
    from rotorcad.kinematics import Rotation, Translation

    r, step = 40.0, 0.05
    arc = Arc((r + 2.0, 0.0), 5.0, np.pi / 2, 1.2 * np.pi)
    gen = Generated(arc, Rotation((0.0, 0.0), 1.0), Translation((0.0, r)))
    s = np.linspace(arc.s0, arc.s1, 30)
    p, t = arc.evaluate(s)
    before = np.nanmax(np.hypot(*np.diff(gen.contact(s).meshline, axis=0).T))
    s2, _, _ = _refine_by_contact(gen, s, p, t, step, 20 * 2 * np.pi * r / 4)
    gaps = np.hypot(*np.diff(gen.contact(s2).meshline, axis=0).T)
    assert before > 100 * step and np.nanmax(gaps) <= step
    s3, _, _ = _refine_by_contact(gen, s, p, t, step, 1.0)
    assert len(s3) <= len(s) + 1.0 / step

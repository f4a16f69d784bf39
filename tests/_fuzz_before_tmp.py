"""Property-based fuzzing of every command in process (issue 15): generated valid and invalid
option values, malformed design and points files, odd output paths.

Each case asserts the common rules of CONTRACT.md: exit 0 or 2 (1 only for ``interfere``'s
finding), never a traceback, on exit 2 one line on stderr naming a parameter, no file or folder
left behind by a failed run, a user's existing file unchanged by it, on success only finite and
physical numbers in the JSON (lengths, areas, volumes, loads, flows, ratios not below zero), a peak
resident memory under 2 GB, and a progress bar opened by any case that runs past a minute. The
generators draw about half their cases from the valid ranges, so that the success path is
exercised too (a third or more of ``cut``, ``rotor --*-points`` and ``clearance`` cases succeed).

The default run is some 350 cases (some 20 s); ``ROTORCAD_FUZZ_EXAMPLES=N`` multiplies each
command's count by N / 40 and draws new cases (N = 2300: about 20 000 cases), and
``ROTORCAD_FUZZ_LOG=FILE`` appends one JSON line a case (test, exit status, seconds, peak memory,
progress) for the long run's figures.
"""

from __future__ import annotations

import json
import math
import os
import re
import shutil
import signal
import tempfile
import time
from pathlib import Path

import numpy as np
import pytest
from hypothesis import HealthCheck, Phase, event, given, settings
from hypothesis import strategies as st

from rotorcad.cli import progress
from rotorcad.cli.main import main

SAMPLES = Path(__file__).resolve().parent.parent / "samples"
SCALE = int(os.environ.get("ROTORCAD_FUZZ_EXAMPLES", "0"))
CASE_SECONDS = 120  # a case running longer is a hang
PROGRESS_SECONDS = 60  # a case running longer must have opened a progress bar
MEMORY_LIMIT = 2 * 1024**3  # bytes of peak resident memory a case may reach
LOG = os.environ.get("ROTORCAD_FUZZ_LOG")


def examples(default: int) -> int:
    return max(default, SCALE * default // 40) if SCALE else default


def fuzz_settings(default: int):
    return settings(
        max_examples=examples(default),
        deadline=None,
        suppress_health_check=[HealthCheck.function_scoped_fixture, HealthCheck.too_slow, HealthCheck.data_too_large],
        derandomize=not SCALE,  # CI: the same cases every run; by hand: new ones
        database=None,
        # by hand: a failing case is reported as drawn, not shrunk (a hang would be re-run for minutes)
        phases=[Phase.explicit, Phase.generate] if SCALE else list(Phase),
    )


class CaseTimeout(BaseException):
    """A case ran past CASE_SECONDS (a BaseException, so that no handler swallows it)."""


def _alarm(signum, frame):
    raise CaseTimeout(f"a case ran longer than {CASE_SECONDS} s")


# ----- values ---------------------------------------------------------------------------------
EDGE = [0.0, -0.0, -1.0, 1e-12, 1e-9, 1e30, -1e30, 1e300, -1e300, math.nan, math.inf, -math.inf]


def number(lo: float, hi: float) -> st.SearchStrategy[float]:
    """Mostly values in [lo, hi] (valid or near the edge), sometimes edge values or anything."""
    inside = st.floats(lo, hi)
    return st.one_of(inside, inside, inside, inside, st.sampled_from(EDGE), st.floats(allow_nan=True, allow_infinity=True))


def whole(lo: int, hi: int) -> st.SearchStrategy[int]:
    return st.one_of(st.integers(lo, hi), st.integers(lo, hi), st.sampled_from([0, -1, 1, 2, 10**6, 10**20]))


def text_of(value: object) -> str:
    return repr(value) if isinstance(value, float) else str(value)


def options(**strategies: st.SearchStrategy) -> st.SearchStrategy[list[str]]:
    """Each option left out or given a generated value."""
    parts = [
        st.one_of(st.just([]), st.just([]), st.just([]), s.map(lambda v, n=name: [f"--{n.replace('_', '-')}", text_of(v)]))
        for name, s in strategies.items()
    ]
    return st.tuples(*parts).map(lambda ps: [x for p in ps for x in p])


GEAR = {
    "teeth": whole(3, 120),
    "module": number(0.05, 20.0),
    "pressure_angle": number(5.0, 35.0),
    "helix_angle": number(-45.0, 45.0),
    "shift": number(-1.0, 1.5),
    "addendum": number(0.5, 1.5),
    "dedendum": number(0.8, 1.6),
    "tip_radius": number(0.0, 0.45),
}
MATE = {"mate_teeth": whole(3, 120), "mate_shift": number(-1.0, 1.5), "center_distance": number(10.0, 500.0)}
PAIR = {
    "male_teeth": whole(2, 8),
    "female_teeth": whole(2, 8),
    "center_distance": number(50.0, 150.0),
    "male_tip_radius": number(40.0, 70.0),
    "male_root_radius": number(30.0, 50.0),
    "female_tip_radius": number(40.0, 75.0),
    "female_root_radius": number(30.0, 55.0),
    "lead": number(50.0, 1000.0),
    "length": number(20.0, 300.0),
}


VALID_GEAR = {
    "pressure_angle": st.floats(14.5, 30.0),
    "helix_angle": st.floats(-30.0, 30.0),
    "shift": st.floats(-0.3, 1.0),
    "addendum": st.floats(0.8, 1.2),
    "dedendum": st.floats(1.1, 1.4),
    "tip_radius": st.floats(0.0, 0.38),
}
"""Ranges of a gear as made: a valid gear unless the teeth are few and the shift low (then the
refusal names --shift) or the tooth pointed."""


# ----- files ----------------------------------------------------------------------------------
TOML_KEYS = [
    ("pair", "lead"),
    ("pair", "length"),
    ("pair", "center_distance"),
    ("pair", "male_tip_radius"),
    ("pair", "male_teeth"),
    ("housing", "radial_clearance"),
    ("profile", "seal_stop"),
    ("profile", "driving_foot_angle_deg"),
    ("operating", "speed_rpm"),
    ("operating", "discharge_pressure_bar"),
]


def design_file(folder: Path, kind: str, key: int, value: float) -> Path:
    """A design file: the asymmetric sample, mutated by ``kind``."""
    text = (SAMPLES / "srm_asymmetric_5_6.toml").read_text()
    path = folder / "design.toml"
    if kind == "sample":
        path.write_text(text)
    elif kind == "mutated":
        table, name = TOML_KEYS[key % len(TOML_KEYS)]
        literal = "nan" if math.isnan(value) else ("inf" if value == math.inf else "-inf" if value == -math.inf else repr(value))
        if name == "male_teeth":
            literal = str(int(value)) if math.isfinite(value) and abs(value) < 1e18 else "0"
        pattern = re.compile(rf"^{name} = .*$", re.M)
        if pattern.search(text):
            text = pattern.sub(f"{name} = {literal}", text, count=1)
        else:
            text = text.replace(f"[{table}]\n", f"[{table}]\n{name} = {literal}\n", 1)
        path.write_text(text)
    elif kind == "latin1":
        path.write_bytes(text.encode().replace(b"# Asymmetric", b"# Asym\xe9trique \xfc"))
    elif kind == "binary":
        path.write_bytes(bytes(range(256)) * 4)
    elif kind == "empty":
        path.write_bytes(b"")
    elif kind == "truncated":
        path.write_text(text[: len(text) // 3 + key])
    elif kind == "unknown-key":
        path.write_text(text.replace("[pair]\n", "[pair]\nlobe_width = 0.6\n"))
    elif kind == "no-table":
        path.write_text(text.replace("[profile]\n", ""))
    elif kind == "fifo":
        os.mkfifo(path)
    elif kind == "folder":
        path.mkdir()
    elif kind == "missing":
        pass
    elif kind == "gear":
        path.write_text((SAMPLES / "gear_pair.toml").read_text())
    return path


DESIGN_KINDS = st.sampled_from(
    ["sample", "sample", "mutated", "mutated", "mutated", "latin1", "binary", "empty", "truncated", "unknown-key", "no-table"]
    + ["fifo", "folder", "missing", "gear"]
)


def _outline(rotor: str) -> np.ndarray:
    """The symmetric sample's section of one rotor, as ``rotor --male-csv`` writes it (cached). Not
    the raw generated outline: the female's tip arc lies on its pitch circle there, which generates
    no male (see tests/test_input_edges.py)."""
    cache = _outline.__dict__.setdefault("cache", {})
    if rotor not in cache:
        from rotorcad.cli.rotor import _build

        opts = dict.fromkeys(["male_points", "female_points", "rack_points", "layer", "smoothing", "speed"])
        rotors, _, _ = _build(SAMPLES / "srm_symmetric_4_6.toml", opts)
        for side in ("male", "female"):
            cache[side] = np.asarray(rotors.section(side).exterior.coords)[:-1]
    return cache[rotor]


def _one_lobe(pts: np.ndarray, teeth: int) -> np.ndarray:
    """The points of one lobe: from the lowest point round by one pitch."""
    ring = np.roll(pts, -int(np.argmin(np.hypot(*pts.T))), axis=0)
    turn = np.unwrap(np.arctan2(ring[:, 1], ring[:, 0]))
    return ring[np.abs(turn - turn[0]) <= 2 * np.pi / teeth + 1e-9]


def points_file(folder: Path, name: str, rotor: str, kind: str, noise: float, seed: int) -> Path:
    """A points file of the symmetric sample's rotor, as measured (``clean``, ``rolled``,
    ``reversed``, ``sparse``, ``one-lobe``, ``measured``: a scatter of ``noise`` / 100 mm) or
    spoilt by ``kind``."""
    pts = _outline(rotor).copy()
    rng = np.random.default_rng(seed)
    path = folder / name
    if kind == "noisy":
        pts = pts + rng.uniform(-noise, noise, pts.shape)
    elif kind == "measured":
        pts = pts + rng.normal(0.0, noise / 100.0, pts.shape)  # a few micrometres, like a measuring machine
    elif kind == "rolled":
        pts = np.roll(pts, seed % len(pts), axis=0)
    elif kind == "reversed":
        pts = pts[::-1]
    elif kind == "sparse":
        pts = pts[:: 2 + seed % 2]
    elif kind == "one-lobe":
        pts = _one_lobe(pts, 4 if rotor == "male" else 6)
    elif kind == "duplicated":
        pts = np.repeat(pts, 2, axis=0)
    elif kind == "identical":
        pts = np.tile(pts[:1], (40, 1))
    elif kind == "collinear":
        x = np.linspace(0.0, 10.0, 40)
        pts = np.c_[x, 2 * x + 1]
    elif kind == "few":
        pts = pts[:3]
    elif kind == "shuffled":
        pts = pts[rng.permutation(len(pts))]
    elif kind == "nan":
        pts[seed % len(pts)] = [math.nan, 1.0]
    body = "x,y\n" + "\n".join(f"{float(x)!r},{float(y)!r}" for x, y in pts) + "\n"
    if kind == "latin1":
        path.write_bytes(b"# Me\xdfpunkte, gem\xe4ss\n" + body.encode())
    elif kind == "binary":
        path.write_bytes(rng.integers(0, 256, 2000, dtype=np.uint8).tobytes())
    elif kind == "empty":
        path.write_text("")
    elif kind == "no-header":
        path.write_text(body.split("\n", 1)[1])
    elif kind == "fifo":
        os.mkfifo(path)
    elif kind == "missing":
        pass
    else:
        path.write_text(body)
    return path


VALID_POINTS = ["clean", "rolled", "reversed", "sparse", "one-lobe", "measured"]
POINT_KINDS = st.one_of(
    st.sampled_from(VALID_POINTS),
    st.sampled_from(VALID_POINTS),
    st.sampled_from(VALID_POINTS),
    st.sampled_from(
        ["noisy", "duplicated", "identical", "collinear", "few", "shuffled", "nan", "latin1"]
        + ["binary", "empty", "no-header", "fifo", "missing"]
    ),
)


# ----- outputs --------------------------------------------------------------------------------
OUT_KINDS = st.sampled_from(["none", "none", "new", "existing", "missing-folder", "proc", "long-name", "folder"])


def output_path(folder: Path, kind: str, suffix: str) -> Path | None:
    if kind == "none":
        return None
    if kind == "new":
        return folder / f"out{suffix}"
    if kind == "existing":
        path = folder / f"user{suffix}"
        path.write_text("the user's own file\n")
        return path
    if kind == "missing-folder":
        return folder / "no" / "such" / f"out{suffix}"
    if kind == "proc":
        return Path(f"/proc/rotorcad-fuzz{suffix}")
    if kind == "long-name":
        return folder / ("n" * 300 + suffix)
    path = folder / f"dir{suffix}"
    path.mkdir()
    return path


# ----- the check ------------------------------------------------------------------------------
PARAMETER = re.compile(
    r"--[a-z]|\[[a-z]+\]|design file|DESIGN|SWEEP_FILE|sweep file|points file|\b[a-z_]+ must\b|command|argument|option"
)


def snapshot(folder: Path) -> dict[str, bytes | None]:
    out: dict[str, bytes | None] = {}
    for p in sorted(folder.rglob("*")):
        rel = str(p.relative_to(folder))
        if p.is_file() and not p.is_symlink():
            out[rel] = p.read_bytes()
        else:
            out[rel] = None
    return out


NOT_NEGATIVE = re.compile(
    r"area|volume|length|radius|diameter|thickness|deviation|ratio|film|velocit|speed|_n$|irregularity|^size$|^steps$"
    r"|^terms$|tolerance|stress|pressure|flow|_hz$|rpm|threshold|utilisation|moment|load|positions|triangles|teeth"
    r"|width|depth|capacity|perimeter|share|percent|frequency"
)
"""Keys of quantities that cannot be negative (magnitudes); a signed quantity (a clearance that is
an interference, a shift, an angle, a coordinate) matches none of these or :data:`SIGNED`."""
SIGNED = re.compile(r"clearance|shift|backlash|_deg$|direction|angle|^[xyz]$|_z$|^apex$|^value$")
POSITIVE = re.compile(
    r"^(pitch_radius|base_radius|tip_radius|root_radius|contact_ratio|mean_flow|displacement_per_(male_)?rev"
    r"|chamber_max_volume|[a-z]+_section_area|[a-z]+_flute_area|[a-z]+_equivalent_diameter|pump_frequency_hz)$"
)
"""Keys that must be above zero: a gear's radii, a contact ratio (0 is refused), a pump's flow."""


def finite_numbers(value: object, where: str = "") -> None:
    """Every number finite, and physical by its key (:data:`NOT_NEGATIVE`, :data:`POSITIVE`)."""
    if isinstance(value, dict):
        for k, v in value.items():
            finite_numbers(v, f"{where}.{k}")
    elif isinstance(value, list):
        for i, v in enumerate(value):
            finite_numbers(v, f"{where}[{i}]")
    elif isinstance(value, (int, float)) and not isinstance(value, bool):
        assert math.isfinite(value), f"non-finite number at {where}"
        key = where.rsplit(".", 1)[-1].split("[", 1)[0]
        if POSITIVE.search(key):
            assert value > 0, f"{where} = {value} must be above zero"
        elif NOT_NEGATIVE.search(key) and not SIGNED.search(key):
            assert value >= -1e-9, f"{where} = {value} must not be negative"


def _reset_peak() -> None:
    """Start a new peak of resident memory (Linux: 5 to /proc/self/clear_refs resets VmHWM)."""
    try:
        with open("/proc/self/clear_refs", "w") as f:
            f.write("5")
    except OSError:
        pass  # then the peak is the process's so far, which is only stricter


def _peak_bytes() -> int:
    """Peak resident memory since :func:`_reset_peak` (VmHWM), else the process's (ru_maxrss)."""
    try:
        with open("/proc/self/status") as f:
            for line in f:
                if line.startswith("VmHWM:"):
                    return int(line.split()[1]) * 1024
    except OSError:
        pass
    import resource

    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss * 1024


def _log(argv: list[str], status: int, seconds: float, peak: int, opened: bool) -> None:
    test = os.environ.get("PYTEST_CURRENT_TEST", "?").split("::")[-1].split(" ")[0]
    row = {"test": test, "exit": status, "seconds": seconds, "peak_mb": peak / 2**20, "progress": opened}
    if seconds > 10:
        row["argv"] = argv
    with open(LOG, "a") as f:
        f.write(json.dumps(row))
        f.write("\n")


def run_case(capsys, folder: Path, argv: list[str], allow_finding: bool = False) -> tuple[int, str, str]:
    """Run one command line and check the common rules; returns (status, stdout, stderr)."""
    before = snapshot(folder)
    capsys.readouterr()
    old = signal.signal(signal.SIGALRM, _alarm)
    signal.alarm(CASE_SECONDS)
    opened = len(progress.OPENED)
    _reset_peak()
    started = time.monotonic()
    try:
        status = main(argv)
    finally:
        signal.alarm(0)
        signal.signal(signal.SIGALRM, old)
    seconds, peak = time.monotonic() - started, _peak_bytes()
    out, err = capsys.readouterr()
    event(f"exit {status}")
    shown = " ".join(argv)[:400]
    if LOG:
        _log(argv, status, seconds, peak, len(progress.OPENED) > opened)
    assert peak < MEMORY_LIMIT, f"peak memory {peak / 2**30:.2f} GB for: {shown}"
    assert seconds < PROGRESS_SECONDS or len(progress.OPENED) > opened, f"{seconds:.0f} s without a progress bar: {shown}"
    assert "Traceback" not in err, f"traceback for: {shown}\n{err}"
    assert status in ((0, 1, 2) if allow_finding else (0, 2)), f"exit {status} for: {shown}\n{err}"
    after = snapshot(folder)
    if status == 2:
        lines = [ln for ln in err.splitlines() if ln.strip()]
        assert len(lines) == 1, f"not one line for: {shown}\n{err}"
        assert lines[0].startswith("rotorcad: error: "), f"{shown}\n{err}"
        assert PARAMETER.search(lines[0]), f"names no parameter: {shown}\n{err}"
        assert after == before, f"files changed by a failed run: {shown}\n{sorted(set(after) ^ set(before))}"
    else:
        for name in before:  # nothing removed; an existing output replaced whole
            assert name in after, f"{name} removed by: {shown}"
        leftovers = [n for n in after if Path(n).name.startswith(".") and n.endswith(".tmp")]
        assert not leftovers, f"temporary files left by: {shown}: {leftovers}"
        if "--json" in argv and not {"-h", "--help"} & set(argv):  # help wins over --json
            finite_numbers(json.loads(out))
    return status, out, err


@pytest.fixture
def work(monkeypatch):
    """A fresh folder per case (hypothesis runs many cases in one test call)."""
    folders: list[Path] = []

    def make() -> Path:
        folder = Path(tempfile.mkdtemp(prefix="rotorcad-fuzz-"))
        folders.append(folder)
        return folder

    monkeypatch.setenv("COLUMNS", "100")
    yield make
    for folder in folders:
        shutil.rmtree(folder, ignore_errors=True)


# ----- the commands ---------------------------------------------------------------------------
@fuzz_settings(60)
@given(
    opts=st.one_of(
        options(**VALID_GEAR, teeth=st.integers(6, 200), module=st.floats(0.5, 10.0), tolerance=st.floats(1e-4, 1e-2)),
        options(**VALID_GEAR, teeth=st.integers(6, 200), mate_teeth=st.integers(6, 200), tolerance=st.floats(1e-4, 1e-2)),
        options(**GEAR),
        options(**GEAR, **MATE, tolerance=number(1e-5, 0.01)),
    ),
    csv=OUT_KINDS,
    dxf=OUT_KINDS,
)
def test_fuzz_gear(capsys, work, opts, csv, dxf):
    folder = work()
    argv = ["gear", *opts, "--json"]
    for flag, kind, suffix in (("--csv", csv, ".csv"), ("--dxf", dxf, ".dxf")):
        path = output_path(folder, kind, suffix)
        if path is not None:
            argv += [flag, str(path)]
    if "--teeth" not in argv:
        argv += ["--teeth", "17"]
    if "--module" not in argv:
        argv += ["--module", "2"]
    run_case(capsys, folder, argv)


@st.composite
def valid_cut(draw) -> list[str]:
    """A cut inside every range: the scallop a small fraction of the module (the work stays small)."""
    module = draw(st.floats(0.5, 10.0))
    argv = ["--teeth", str(draw(st.integers(3, 60))), "--module", repr(module)]
    argv += ["--tolerance", repr(module * draw(st.floats(3e-3, 3e-2)))]
    argv += draw(options(**VALID_GEAR, hob_addendum=st.floats(1.1, 1.4)))
    if draw(st.integers(0, 7)) == 0:
        argv += ["--positions", str(draw(st.integers(30, 400)))]
    return argv


@fuzz_settings(24)
@given(
    opts=st.one_of(
        valid_cut(),
        valid_cut(),
        options(**GEAR, tolerance=number(1e-3, 0.2), positions=whole(3, 400), hob_addendum=number(0.8, 1.6)),
    ),
    csv=OUT_KINDS,
)
def test_fuzz_cut(capsys, work, opts, csv):
    folder = work()
    argv = ["cut", *opts, "--json"]
    path = output_path(folder, csv, ".csv")
    if path is not None:
        argv += ["--csv", str(path)]
    if "--teeth" not in argv:
        argv += ["--teeth", "12"]
    if "--module" not in argv:
        argv += ["--module", "2"]
    status, out, _ = run_case(capsys, folder, argv)
    if status == 0:  # the simulation met its scallop, or says that it did not
        res = json.loads(out)
        tolerance = float(argv[argv.index("--tolerance") + 1]) if "--tolerance" in argv else 1e-3
        assert res["tolerance_met"] == (res["max_deviation_from_envelope"] <= tolerance)


@fuzz_settings(40)
@given(
    opts=st.one_of(
        options(**VALID_GEAR, face_width=st.floats(2.0, 50.0), speed=st.floats(100.0, 5000.0), harmonics=st.integers(1, 64)),
        options(**GEAR, face_width=number(1.0, 50.0), speed=number(100.0, 5000.0), harmonics=whole(1, 64)),
    )
)
def test_fuzz_pump(capsys, work, opts):
    folder = work()
    argv = ["pump", *opts, "--json"]
    for flag, value in (("--teeth", "11"), ("--module", "2"), ("--face-width", "10"), ("--speed", "1500")):
        if flag not in argv:
            argv += [flag, value]
    run_case(capsys, folder, argv)


@fuzz_settings(25)
@given(
    opts=options(**GEAR, min_flank_angle=number(0.0, 20.0), min_tip_radius_mm=number(0.0, 1.0), root_clearance=number(0, 1)),
    design=st.sampled_from(["none", "none", "gear", "rotor", "mutated", "latin1", "fifo", "binary"]),
    key=st.integers(0, 20),
    value=number(-10.0, 1000.0),
)
def test_fuzz_hob(capsys, work, opts, design, key, value):
    folder = work()
    argv = ["hob", *opts, "--json"]
    if design == "none":
        for flag, v in (("--teeth", "17"), ("--module", "2")):
            if flag not in argv:
                argv += [flag, v]
    else:
        argv.insert(1, str(design_file(folder, {"rotor": "sample"}.get(design, design), key, value)))
    run_case(capsys, folder, argv)


@fuzz_settings(40)
@given(
    design=DESIGN_KINDS,
    key=st.integers(0, 20),
    value=number(-10.0, 1000.0),
    opts=options(tolerance=number(1e-4, 0.1), speed=number(100.0, 10000.0)),
    csv=OUT_KINDS,
)
def test_fuzz_rotor_design(capsys, work, design, key, value, opts, csv):
    folder = work()
    argv = ["rotor", str(design_file(folder, design, key, value)), *opts, "--json"]
    path = output_path(folder, csv, ".csv")
    if path is not None:
        argv += ["--male-csv", str(path)]
    run_case(capsys, folder, argv)


SYM_SAMPLE = {"male_teeth": 4, "female_teeth": 6, "center_distance": 100, "male_tip_radius": 54, "male_root_radius": 40}
SYM_SAMPLE.update({"female_tip_radius": 60, "female_root_radius": 46, "lead": 260, "length": 150})


@fuzz_settings(40)
@given(
    rotor=st.sampled_from(["male", "female"]),
    kind=POINT_KINDS,
    noise=st.floats(0.0, 0.2),
    seed=st.integers(0, 1000),
    opts=st.one_of(
        st.just([]),
        st.just([]),
        options(lead=st.floats(100.0, 600.0), length=st.floats(50.0, 300.0), smoothing=st.floats(0.0, 1e-4)),
        options(lead=st.floats(100.0, 600.0), length=st.floats(50.0, 300.0), smoothing=st.floats(0.0, 1e-4)),
        options(lead=PAIR["lead"], length=PAIR["length"]),
        options(smoothing=number(0.0, 10.0)),
        options(**PAIR, smoothing=number(0.0, 10.0)),
    ),
)
def test_fuzz_rotor_points(capsys, work, rotor, kind, noise, seed, opts):
    folder = work()
    path = points_file(folder, "points.csv", rotor, kind, noise, seed)
    argv = ["rotor", f"--{rotor}-points", str(path), *opts, "--json"]
    for name, value in SYM_SAMPLE.items():
        flag = "--" + name.replace("_", "-")
        if flag not in argv:
            argv += [flag, str(value)]
    run_case(capsys, folder, argv)


@fuzz_settings(25)
@given(
    male=POINT_KINDS,
    female=POINT_KINDS,
    noise=st.floats(0.0, 0.05),
    seed=st.integers(0, 1000),
    opts=st.one_of(
        st.just([]),
        options(
            lead=st.floats(100.0, 2000.0),
            length=st.floats(20.0, 300.0),
            smoothing=st.floats(0.0, 1e-4),
            contact=st.sampled_from(["driving", "sealing", "as-given"]),
        ),
        options(lead=number(50.0, 1e4), length=number(10.0, 400.0), smoothing=number(0.0, 1.0)),
    ),
)
def test_fuzz_clearance(capsys, work, male, female, noise, seed, opts):
    folder = work()
    m = points_file(folder, "male.csv", "male", male, noise, seed)
    f = points_file(folder, "female.csv", "female", female, noise, seed + 1)
    argv = ["clearance", "--male-points", str(m), "--female-points", str(f), "--male-teeth", "4", "--female-teeth", "6"]
    argv += ["--center-distance", "100", *opts, "--json"]
    run_case(capsys, folder, argv)


@fuzz_settings(20)
@given(
    design=st.one_of(st.just("sample"), DESIGN_KINDS),
    key=st.integers(0, 20),
    value=number(-10.0, 1000.0),
    opts=st.one_of(
        options(steps=st.integers(1, 40), tolerance=st.floats(0.005, 0.2), phase_deg=st.floats(-2.0, 2.0)),
        options(steps=whole(1, 40), tolerance=number(0.002, 0.2), phase_deg=number(-5.0, 5.0)),
    ),
    distance=st.one_of(st.none(), st.none(), number(110.0, 122.0)),
)
def test_fuzz_interfere(capsys, work, design, key, value, opts, distance):
    folder = work()
    argv = ["interfere", str(design_file(folder, design, key, value)), *opts, "--json"]
    if distance is not None:
        argv += ["--center-distance", text_of(distance)]
    run_case(capsys, folder, argv, allow_finding=True)


@fuzz_settings(10)
@given(
    design=DESIGN_KINDS,
    key=st.integers(0, 20),
    value=number(-10.0, 1000.0),
    tolerance=number(0.05, 1.0),
    fmt=st.sampled_from(["stl", "obj", "csv", "dxf", "stl,csv", "bogus"]),
    out=st.sampled_from(["new", "nested", "existing", "file"]),
)
def test_fuzz_export(capsys, work, design, key, value, tolerance, fmt, out):
    folder = work()
    target = {"new": folder / "out", "nested": folder / "a" / "b", "existing": folder / "there", "file": folder / "f"}[out]
    if out == "existing":
        target.mkdir()
    if out == "file":
        target.write_text("the user's own file\n")
    argv = ["export", str(design_file(folder, design, key, value)), "--out", str(target), "--format", fmt]
    argv += ["--tolerance", text_of(tolerance), "--json", "--quiet"]
    run_case(capsys, folder, argv)


@fuzz_settings(10)
@given(
    design=DESIGN_KINDS,
    key=st.integers(0, 20),
    value=number(-10.0, 1000.0),
    opts=options(terms=whole(1, 60), angle=number(-90.0, 90.0)),
)
def test_fuzz_deflect(capsys, work, design, key, value, opts):
    folder = work()
    argv = ["deflect", str(design_file(folder, design, key, value)), *opts, "--json", "--quiet"]
    run_case(capsys, folder, argv)


@fuzz_settings(15)
@given(
    opts=st.one_of(
        options(
            teeth=st.integers(20, 60),
            module=st.floats(2.0, 5.0),
            face_width=st.floats(15.0, 40.0),
            speed=st.floats(500.0, 3000.0),
            viscosity=st.floats(0.02, 0.1),
            power=st.floats(10.0, 100.0),
            misalignment_deg=st.floats(0.02, 0.2),
            load_factor=st.floats(1.0, 1.5),
        ),
        options(
            teeth=whole(10, 80),
            module=number(1.0, 8.0),
            face_width=number(5.0, 60.0),
            speed=number(100.0, 5000.0),
            viscosity=number(0.005, 0.2),
            power=number(1.0, 500.0),
            misalignment_deg=number(0.0, 1.0),
            load_factor=number(1.0, 2.0),
        ),
    )
)
def test_fuzz_coupling(capsys, work, opts):
    folder = work()
    argv = ["coupling", *opts, "--json"]
    defaults = (("--teeth", "40"), ("--module", "3"), ("--face-width", "20"), ("--speed", "1500"))
    defaults += (("--viscosity", "0.05"), ("--power", "50"), ("--misalignment-deg", "0.1"), ("--pressure-viscosity", "2e-8"))
    for flag, v in defaults:
        if flag not in argv:
            argv += [flag, v]
    run_case(capsys, folder, argv)


@fuzz_settings(10)
@given(kind=st.sampled_from(["binary", "empty", "latin1", "fifo", "folder", "missing", "truncated"]), key=st.integers(0, 9))
def test_fuzz_sweep_files(capsys, work, kind, key):
    """Malformed sweep files only: a sweep that runs starts a Dask cluster (seconds a case)."""
    folder = work()
    path = design_file(folder, kind, key, 1.0)
    run_case(capsys, folder, ["sweep", str(path), "--out", str(folder / "r.parquet"), "--quiet"])


@fuzz_settings(30)
@given(
    argv=st.lists(st.sampled_from(["gear", "rotor", "--json", "--teeth", "x", "-h", "--", "é", "--out", "1e999", ""]), max_size=5)
)
def test_fuzz_command_lines(capsys, work, argv):
    """Arbitrary words: click's own refusals are one line too."""
    folder = work()
    if argv and argv[0] in ("gear", "rotor") and "-h" not in argv:
        argv = [a if a != "--out" else "--quiet" for a in argv]
    run_case(capsys, folder, argv)

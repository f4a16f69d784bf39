"""Results several test modules compute alike, made once per test run: pairs from points, command runs.

Several test modules analyse the very same points: a sample's design outline scanned at the same density and
phase, with the same scatter and seed (tests/test_moderate_densities.py reads 102 such inputs, 87 of them
distinct; its 300-a-lobe exact males are tests/test_verdict_invariance.py's ``even-300`` form; its 80-a-lobe
exact females are tests/test_blow_hole_points.py's, whose 1 um scans tests/test_generating_line.py reads too).
:func:`points_summary` builds and analyses such an input once in a test run and hands its summary to every
caller: keyed by everything the build reads (the pair's dimensions, the points' bytes, the smoothing, speed,
clearance and label), so that only an identical input is shared, and a caller whose points differ in one bit
gets its own analysis. The checks stay each module's own; only the repeated computation goes.
:func:`command_output` does the same for a command run in process (``rotorcad.cli.main.main``) with the very
same arguments in several modules (``deflect`` of the Rinder-Deix sample: tests/test_deflect_scaling.py and
tests/test_paper_deflection.py, tests/test_deflect_housing.py and tests/test_report_deflection.py), for
arguments that name only files no test writes (the samples).

Across pytest-xdist's workers the first to ask builds and leaves the summary pickled in the run's temporary
folder (the other waits for it and reads it, as tests/conftest.py's ``built_once``), within a process it is
kept in memory; nothing is kept from one run to the next. The warnings the build and the analysis issue (an
``InputNote``, a spline fit's warning) are recorded with the summary and issued again at each call, so that
every caller sees what it saw when it built the pair itself, under its own warning filters; a refusal
(``DesignError``) is not kept: each caller meets it as before.
"""

from __future__ import annotations

import contextlib
import hashlib
import io
import os
import pickle
import warnings
from collections.abc import Callable
from pathlib import Path
from typing import Any

import numpy as np

from rotorcad.rotor_build import PairSpec, analyse_pair, build_pair

try:
    import fcntl
except ImportError:  # not on POSIX: each worker builds its own
    fcntl = None

ROOT: Path | None = None
"""The run's folder that pytest-xdist's workers share (set by tests/conftest.py); None: this process only."""
_MEMO: dict[str, Any] = {}


def built_once(root: Path, name: str, build: Callable[[], Any]) -> Any:
    """``build()``, made by the first worker that asks and read from ``root`` by the others."""
    path = root / f"{name}.pickle"
    with open(root / f"{name}.lock", "w") as lock:
        fcntl.flock(lock, fcntl.LOCK_EX)  # the other worker waits while this one builds
        try:
            if path.exists():
                return pickle.loads(path.read_bytes())
            value = build()
            partial = path.with_suffix(".partial")
            partial.write_bytes(pickle.dumps(value))
            partial.replace(path)
            return value
        finally:
            fcntl.flock(lock, fcntl.LOCK_UN)


def once(name: str, build: Callable[[], Any]) -> Any:
    """``build()`` made once in this run: kept in this process, and shared with the other workers under xdist."""
    if name not in _MEMO:
        shared = ROOT is not None and fcntl is not None and os.environ.get("PYTEST_XDIST_WORKER")
        _MEMO[name] = built_once(ROOT, name, build) if shared else build()
    return _MEMO[name]


def _key(spec: PairSpec, speed_rpm: float, label: str | None) -> str:
    """A digest of everything :func:`build_pair` and :func:`analyse_pair` read of the input."""
    digest = hashlib.sha256()
    points = spec.points
    if isinstance(points, np.ndarray):
        digest.update(repr((points.shape, points.dtype.str)).encode())
        digest.update(np.ascontiguousarray(points).tobytes())
    else:  # curves read from a drawing
        digest.update(pickle.dumps(points))
    fields = (repr(spec.pair), spec.family, repr(sorted(spec.params.items())), spec.smoothing, spec.speed_rpm)
    digest.update(repr((*fields, spec.radial_clearance, label, float(speed_rpm))).encode())
    return digest.hexdigest()[:32]


def _noted(spec: PairSpec, speed_rpm: float, label: str | None) -> tuple[dict, list[tuple]]:
    """The summary of the pair built from ``spec`` and the warnings its build and analysis issued."""
    failed: Exception | None = None
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        try:
            summary = analyse_pair(build_pair(spec, label=label), speed_rpm)[1]
        except Exception as error:  # a refusal: its warnings issued, then raised (and not kept)
            failed = error
    noted = [(w.message, w.category, w.filename, w.lineno) for w in caught]
    if failed is not None:
        _issue(noted)
        raise failed
    return summary, noted


_REGISTRIES: dict[str, dict] = {}
"""One warnings registry per source file the recorded warnings came from: as the issuing module's own, a warning
shown once per place ("default") is shown once per test (pytest's filters, set anew for each test, reset them)."""


def _issue(noted: list[tuple]) -> None:
    """Issue recorded warnings again, each from where it was first issued (the caller's filters decide)."""
    for message, category, filename, lineno in noted:
        warnings.warn_explicit(message, category, filename, lineno, registry=_REGISTRIES.setdefault(filename, {}))


def points_summary(spec: PairSpec, label: str | None = None, speed_rpm: float | None = None) -> dict:
    """``analyse_pair(build_pair(spec, label=label), speed_rpm)[1]``, made once in this run for these points.

    Parameters
    ----------
    spec : PairSpec
        A pair from points (``male-points``, ``female-points`` or ``rack-points``) with its points.
    label : str, optional
        How the points are named in a refusal, as for :func:`build_pair`.
    speed_rpm : float, rpm, optional
        Male speed of the analysis; the spec's by default.

    Returns
    -------
    dict
        The summary (the keys of ``rotorcad rotor --json``), shared with every caller of the same input: read it,
        never change it.

    Raises
    ------
    DesignError
        The points are refused (each call builds again and meets the refusal).
    """
    speed = spec.speed_rpm if speed_rpm is None else speed_rpm
    name = f"points_summary.{_key(spec, speed, label)}"
    summary, noted = once(name, lambda: _noted(spec, speed, label))
    _issue(noted)
    return summary


def command_output(*args: object) -> tuple[int, str, str]:
    """``rotorcad.cli.main.main(args)`` run once in this run: its exit status, stdout and stderr.

    Parameters
    ----------
    *args : object
        The command line (each turned into a string); files it names must not change during the run.

    Returns
    -------
    code : int
        The exit status.
    out, err : str
        What the command printed on stdout and stderr.
    """
    argv = [str(a) for a in args]

    def run() -> tuple[int, str, str]:
        from rotorcad.cli.main import main

        out, err = io.StringIO(), io.StringIO()
        with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
            code = main(argv)
        return code, out.getvalue(), err.getvalue()

    return once("command_output." + hashlib.sha256(repr(argv).encode()).hexdigest()[:32], run)


def beside_the_design(rotors, lobe: np.ndarray, teeth: int) -> tuple[dict[str, np.ndarray], float]:
    """Return a closed-form male ring and the design's beside it, and how far the design lies from it (mm).

    ``lobe`` ((n, 2), mm) is one lobe of an independent closed form, patterned over ``teeth`` lobes; the design's
    ring is its male lobe at a 0.01 um chord. The distance is the largest of the design's vertices from the closed
    form's nearest point (k-d tree), so a test can require the closed form to be the design's profile.
    """
    from independent_pairs import patterned
    from scipy.spatial import cKDTree

    ring = patterned(lobe, teeth)
    design_ring = patterned(np.vstack([s.resampled(1e-5).points for s in rotors.male_lobe().segments]), teeth)
    off = float(cKDTree(ring).query(design_ring)[0].max())
    return {"closed form": ring, "design": design_ring}, off

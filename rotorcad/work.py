"""The work a request implies, estimated before it starts.

Issue 15: refuse what this machine cannot do, with the largest value that would work, instead of
growing to gigabytes or crashing.

A profile sampled to a chord tolerance t has a number of points that grows like 1/sqrt(t) (the
sagitta of a chord of length c on radius R is c^2 / (8 R)); a helical solid (:mod:`rotorcad.solids`)
has ``2 x points x layers`` side triangles, with ``layers`` growing like the wrap angle times
1/sqrt(t). So the triangles grow like 1/t and like 1/lead.

Issue 24: anything that would take over a minute says so before it starts, with the option that
makes it faster (:func:`long_run_note`). Measured on the project's 2-core machine, the other
commands stay under a minute at their bounds, so only ``sweep``, ``clearance`` (2.6 million
points: 67 s) and the exact STEP of ``export`` (a gear of 1000 teeth: 7002 faces, some 4 minutes
under load, :func:`step_seconds`) need the note: ``export``'s meshes at
:data:`MAX_TRIANGLES` (about 2.2 us a triangle: 8.8 s), ``cut`` at its union budget
(:data:`hob.cutting.MAX_UNION_VERTICES`, some 3 s a pass, at most 8 passes; the issue's 45-s cases
now 6.6 s), ``deflect --terms 400`` (15 s), ``interfere --steps 100000`` (3.3 s on the
loaded machine).
"""

from __future__ import annotations

import numpy as np
import shapely

from rotorcad.solids import layers_for

MAX_TRIANGLES = 4_000_000
"""Most triangles of the solids of one request: some 330 bytes a triangle at the peak while they
are swept, meshed and written (measured: 5.7 M triangles, 1.9 GB), so about 1.3 GB at the limit."""

MAX_SECTION_POINTS = 60_000
"""Most points of the two sections of an interference sweep: each is turned to 360 angles at
once (some 64 bytes a point and angle, 1.4 GB at the limit)."""


def points_at(section: shapely.Polygon, tolerance: float, target: float) -> float:
    """Points of ``section`` (sampled to ``tolerance``) scaled to the tolerance ``target``.

    Parameters
    ----------
    section : shapely.Polygon
        A section sampled to the chord tolerance ``tolerance`` (mm).
    tolerance : float
        Its tolerance, mm.
    target : float
        The tolerance asked for, mm.

    Returns
    -------
    float
        The estimated number of points at ``target`` (points grow like 1/sqrt(tolerance)).
    """
    return (len(section.exterior.coords) - 1) * float(np.sqrt(tolerance / target))


def solid_triangles(points: float, lead: float, length: float, r_max: float, tolerance: float) -> float:
    """Side triangles of a helical solid of a section of ``points`` points.

    Parameters
    ----------
    points : float
        Points of the section at the surface tolerance.
    lead : float
        Lead of the helix, mm (any sign; infinite for a straight extrusion).
    length : float
        Length of the solid, mm.
    r_max : float
        Largest radius of the section, mm.
    tolerance : float
        Surface tolerance, mm.

    Returns
    -------
    float
        ``2 x points x layers`` with the layers of :func:`rotorcad.solids.layers_for`.
    """
    wrap = 0.0 if not np.isfinite(lead) else 2.0 * np.pi * length / abs(lead)
    layers = max(1.0, abs(wrap) * np.sqrt(r_max / (4.0 * tolerance))) if wrap else 1.0
    if wrap and layers < 1e15:
        layers = float(layers_for(tolerance, wrap, r_max))
    return 2.0 * points * layers


LONG_RUN_SECONDS = 60.0
"""A request estimated to take longer than this says so before it starts (CONTRACT.md, long runs)."""

SWEEP_SECONDS = {None: 0.022, "hobbability": 0.046, "interference": 0.164, "volume": 0.008, "clearance": 0.202}
"""CPU-seconds of one sweep variant: the pair and Rinder's analysis (key None), plus each analysis of
``[sweep] compute``. Measured with ``rotorcad sweep --workers 0 --json`` on the 60 variants of
``samples/sweep_rack_involute.toml`` without its [constraints] and [objectives], one run per
analysis alone (``cpu_seconds`` / ``computed``: 1.32 s with none, 4.06 s hobbability, 11.18 s
interference, 1.78 s volume, 13.44 s clearance; each analysis is its run less the first). The wall
time on the loaded 2-core machine was about twice that."""

CLEARANCE_SECONDS = (1.7, 2.5e-5)
"""Seconds of ``clearance``: a constant and a time per profile point read (male and female). Measured
as wall time of ``rotorcad clearance --json`` on the symmetric sample's outlines (``rotor
--male-csv``) made 100 and 1000 times denser by linear interpolation: 262 800 points 8.2 s,
2 628 000 points 67 s on the loaded 2-core machine (the line through the two)."""

STEP_FACE_SECONDS = ((702, 5.2), (2102, 17.1), (4202, 58.0), (7002, 213.0))
"""Wall seconds of writing an exact STEP file of F faces (sewing and checking the faces grows faster
than their number). Measured with ``rotorcad export --format step`` of helical gears (m = 1 mm,
b = 20 mm, beta = 20 deg; 7 faces a tooth: z = 100, 300, 600, 1000) on the project's loaded 2-core
machine, less the 1.5 s the command takes to start; the CPU times were 1.25, 5.6, 17.5 and 57 s, and
the largest took 761 MB (the gear's limit, :data:`rotorcad.gears.involute_gear.MAX_TEETH`, bounds it)."""

STEP_MEGABYTES = {False: (290.0, 0.067), True: (327.0, 0.14)}
"""Peak memory of writing an exact STEP of F faces, MB: ``a + b F``, for a plain solid (False) and a
herringbone gear (True, F counting both halves' faces). Measured (max RSS of ``rotorcad export
--format step``, m = 1 mm, b = 20 mm, beta = 20 deg): helical z = 100 / 300 / 600 / 1000 (702 / 2102 /
4202 / 7002 faces) 340 / 439 / 571 / 761 MB; herringbone z = 300 / 500 (4202 / 7002 faces) 915 /
1306 MB (and 51 / 236 s wall, as :data:`STEP_FACE_SECONDS` gives for those faces)."""

MAX_STEP_MEGABYTES = 2000.0
"""Most memory an exact STEP may need (CONTRACT.md: a request over about 2 GB is refused)."""

CLUSTER_START_SECONDS = 5.0
"""CPU-seconds to start a local Dask cluster (:data:`rotorcad.sweep.run.IN_PROCESS_BELOW`)."""


def sweep_seconds(count: int, extras: tuple[str, ...], workers: int) -> float:
    """Estimated wall time of a sweep, s: ``count`` variants over ``workers`` processes.

    Parameters
    ----------
    count : int
        Variants to compute.
    extras : tuple of str
        The analyses of ``[sweep] compute`` (values of :class:`rotorcad.sweep.plan.Extra`).
    workers : int
        Processes sharing the variants; 1 in this process (no cluster to start).

    Returns
    -------
    float
        ``count x (base + extras) / workers``, plus :data:`CLUSTER_START_SECONDS` with a cluster.
    """
    each = SWEEP_SECONDS[None] + sum(SWEEP_SECONDS.get(x, 0.0) for x in extras)
    return count * each / max(workers, 1) + (CLUSTER_START_SECONDS if workers > 1 else 0.0)


def clearance_seconds(points: int) -> float:
    """Estimated wall time of ``clearance`` from the profile points read, s (:data:`CLEARANCE_SECONDS`).

    Parameters
    ----------
    points : int
        Points of the male and female profiles together.

    Returns
    -------
    float
        ``constant + points x seconds a point``.
    """
    return CLEARANCE_SECONDS[0] + CLEARANCE_SECONDS[1] * points


def step_seconds(faces: float) -> float:
    """Estimated wall time of writing an exact STEP of ``faces`` faces, s (:data:`STEP_FACE_SECONDS`).

    Interpolated in the measured table on log-log axes, extrapolated along its last slope.

    Parameters
    ----------
    faces : float
        Faces of the file's solid (one per section segment, and the end faces).

    Returns
    -------
    float
    """
    if not faces > 0:
        return 0.0
    f, t = np.log(np.array(STEP_FACE_SECONDS, dtype=float)).T
    x = np.log(faces)
    slope = (t[-1] - t[-2]) / (f[-1] - f[-2]) if x > f[-1] else (t[1] - t[0]) / (f[1] - f[0]) if x < f[0] else 0.0
    edge = f[-1] if x > f[-1] else f[0] if x < f[0] else x
    return float(np.exp(np.interp(edge, f, t) + slope * (x - edge)))


STEP_NOTE_SECONDS = 20.0
"""An exact STEP estimated (:func:`step_seconds`, times :func:`load_factor`) over this says so first.

Lower than :data:`LONG_RUN_SECONDS`: the table is from one machine at one load, and a new user's
gear of 600 teeth (4202 faces, 58 s by the table) took 305 s of wall time (33.5 s of CPU) on a
machine loaded some 9 times over, without a word."""


def load_factor(load: float | None = None, cpus: int | None = None) -> float:
    """Return how much longer than on an idle machine a single-threaded run may take now: ``max(1, load / cpus)``.

    Parameters
    ----------
    load : float, optional
        The 1-minute load average (:func:`os.getloadavg`; 0 where there is none).
    cpus : int, optional
        Cores (:func:`os.cpu_count`).

    Returns
    -------
    float
        At least 1.
    """
    import os

    if load is None:
        try:
            load = os.getloadavg()[0]
        except (AttributeError, OSError):  # no load average (Windows)
            load = 0.0
    cpus = cpus or os.cpu_count() or 1
    return max(1.0, float(load) / cpus)


def step_megabytes(faces: float, herringbone: bool = False) -> float:
    """Estimated peak memory of writing an exact STEP of ``faces`` faces, MB (:data:`STEP_MEGABYTES`).

    Parameters
    ----------
    faces : float
        Faces of the solid (both halves' for a herringbone gear).
    herringbone : bool
        A herringbone gear (its two halves sewn: more memory a face).

    Returns
    -------
    float
    """
    a, b = STEP_MEGABYTES[bool(herringbone)]
    return a + b * faces


def step_faces_within(megabytes: float, herringbone: bool = False) -> float:
    """Return the most faces whose STEP stays within ``megabytes`` (the inverse of :func:`step_megabytes`)."""
    a, b = STEP_MEGABYTES[bool(herringbone)]
    return max(0.0, (megabytes - a) / b)


def _duration(seconds: float) -> str:
    """``about N min`` (or ``N h``) for a duration above a minute, ``N s`` below."""
    if seconds < 90:
        return f"{seconds:.0f} s"
    if seconds < 5400:
        return f"{seconds / 60:.0f} min"
    return f"{seconds / 3600:.1f} h"


def long_run_note(
    seconds: float, faster: tuple[str, object, float] | None, threshold: float = LONG_RUN_SECONDS, caveat: str = ""
) -> str | None:
    """Return the note said before a request estimated to take over :data:`LONG_RUN_SECONDS`, else None.

    Parameters
    ----------
    seconds : float
        The estimated run time, s.
    faster : tuple of (str, object, float), optional
        An option, its value and the run time it would give, s; None when no option helps.
    threshold : float
        Said above this many seconds (:data:`LONG_RUN_SECONDS`; the STEP export's :data:`STEP_NOTE_SECONDS`).
    caveat : str
        Words said after the time (e.g. ``" (an estimate ...)"``).

    Returns
    -------
    str or None
        ``this will take about N min; --OPTION VALUE would make it about M s`` (no final stop).
    """
    if not seconds > threshold:
        return None
    text = f"this will take about {_duration(seconds)}{caveat}"
    if faster is not None:
        option, value, quicker = faster
        text += f"; {option} {value} would make it about {_duration(quicker)}"
    return text


__all__ = [
    "LONG_RUN_SECONDS",
    "MAX_SECTION_POINTS",
    "MAX_STEP_MEGABYTES",
    "MAX_TRIANGLES",
    "STEP_NOTE_SECONDS",
    "SWEEP_SECONDS",
    "clearance_seconds",
    "load_factor",
    "long_run_note",
    "points_at",
    "solid_triangles",
    "step_faces_within",
    "step_megabytes",
    "step_seconds",
    "sweep_seconds",
]

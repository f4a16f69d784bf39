"""Summarise the log of a long fuzz run of the CLI (issue 24, item 3).

The log is the one ``tests/test_fuzz_cli.py`` appends to with ``ROTORCAD_FUZZ_LOG=FILE``: one JSON
line a case (test, command, exit status, wall and CPU seconds, peak memory), a line per broken rule
(``failure``), per refusal that does not name what the user typed (``unclear``) and per kill. This
prints the cases per command, the exit statuses, the failures by kind (internal error, hang,
unclear refusal, leftovers, orphan process, user file lost, memory, other), the slowest cases with
their command lines, the peak memory, and the cases past 60 s of wall time.

On a shared machine a case can take a minute of wall time with a few seconds of CPU; ``--rerun``
runs each case past ``--over`` seconds again alone (a fresh process, its inputs as the run kept them
in ``FILE.cases/``) and says whether it is a hang (still past the limit alone) or the load. A log
still being written can be read at any time (a last, partial line is left out).

Usage::

    python benchmarks/fuzz_summary.py fuzz-run/long.jsonl [--slowest 15] [--rerun] [--over 60]
"""

from __future__ import annotations

import argparse
import collections
import json
import os
import re
import resource
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

KINDS = ("internal error", "hang", "unclear refusal", "leftovers", "orphan", "user file lost", "memory", "other")
TEST_COMMAND = {
    "test_fuzz_gear": "gear",
    "test_fuzz_cut": "cut",
    "test_fuzz_pump": "pump",
    "test_fuzz_hob": "hob",
    "test_fuzz_rotor_design": "rotor",
    "test_fuzz_rotor_points": "rotor",
    "test_fuzz_clearance": "clearance",
    "test_fuzz_interfere": "interfere",
    "test_fuzz_export": "export",
    "test_fuzz_deflect": "deflect",
    "test_fuzz_coupling": "coupling",
    "test_fuzz_sweep_files": "sweep",
}
"""The command of a test that runs one command (logs without a ``command`` key)."""


def read_log(path: Path) -> list[dict]:
    """The rows of the log; a line that is not JSON (the last one, still being written) is left out."""
    rows = []
    with open(path, encoding="utf-8") as f:
        for line in f:
            try:
                rows.append(json.loads(line))
            except json.JSONDecodeError:
                continue
    return rows


def command_of(row: dict) -> str:
    """The command a row is about (``(none)`` for a command line without one)."""
    if row.get("command") is not None:
        return row["command"] or "(none)"
    argv = row.get("argv")
    if argv:
        return next((a for a in argv if not a.startswith("-")), "(none)")
    return TEST_COMMAND.get(row.get("test", ""), row.get("test", "?"))


def kind_of(row: dict) -> str:
    """The kind of a failure or unclear row (one of :data:`KINDS`)."""
    if "unclear" in row:
        return "unclear refusal"
    text = row["failure"]
    if text.startswith("hang") or "still running" in text or "without a progress bar" in text:
        return "hang"
    if "processes left" in text:
        return "orphan"
    if "user's file" in text or "removed by" in text:
        return "user file lost"
    if re.search(r"^exit 70\b|Traceback|traceback for|internal error", text):
        return "internal error"
    if text.startswith("peak memory"):
        return "memory"
    if re.search(r"files changed by a failed run|temporar|left", text):
        return "leftovers"
    if re.search(r"not one line|names no parameter|^rotorcad: error", text):
        return "unclear refusal"
    return "other"


def rerun(row: dict, limit: float) -> dict:
    """Run a kept case again alone: its wall and CPU seconds, exit status and verdict.

    A hang: still running after five times ``limit``, or past ``limit`` of CPU time; the load: within
    ``limit`` alone, or past it in wall time only (the other work of the machine).
    """
    argv, old, kept = row.get("argv"), row.get("folder"), row.get("kept")
    if not argv:
        return {"verdict": "no command line in the log"}
    work = Path(tempfile.mkdtemp(prefix="rotorcad-fuzz-rerun-"))
    try:
        if kept and Path(kept).is_dir():
            shutil.copytree(kept, work, dirs_exist_ok=True)
        args = [a.replace(old, str(work)) if old else a for a in argv]
        code = "import sys; from rotorcad.cli.main import main; sys.exit(main(sys.argv[1:]))"
        before = resource.getrusage(resource.RUSAGE_CHILDREN)
        started = time.monotonic()
        try:
            done = subprocess.run(
                [sys.executable, "-c", code, *args],
                capture_output=True,
                text=True,
                timeout=5 * limit,
                env={**os.environ, "COLUMNS": "100"},
            )
        except subprocess.TimeoutExpired:
            return {"verdict": f"hang: still running after {5 * limit:g} s alone", "seconds": 5 * limit}
        seconds = time.monotonic() - started
        after = resource.getrusage(resource.RUSAGE_CHILDREN)
        cpu = after.ru_utime + after.ru_stime - before.ru_utime - before.ru_stime
        if seconds < limit:
            verdict = "load: within the limit alone"
        elif cpu < limit:
            verdict = "load: past the limit in wall time only, CPU within it"
        else:
            verdict = "hang: past the limit in CPU time alone"
        return {"verdict": verdict, "seconds": seconds, "cpu": cpu, "exit": done.returncode, "stderr": done.stderr[-300:]}
    finally:
        shutil.rmtree(work, ignore_errors=True)


def shown(argv: list[str] | None, width: int = 160) -> str:
    text = " ".join(argv or ["(command line not logged)"])
    return text if len(text) <= width else text[: width - 3] + "..."


def summarise(rows: list[dict], slowest: int, over: float) -> dict:
    """The figures of a log (also printed by :func:`main`)."""
    cases = [r for r in rows if "exit" in r and "kill" not in r]
    kills = [r for r in rows if "kill" in r]
    problems = [r for r in rows if "failure" in r or "unclear" in r]
    per_command = collections.Counter(command_of(r) for r in cases)
    for r in kills:
        per_command[f"{command_of(r)} (killed)"] += 1
    exits = collections.Counter(r["exit"] for r in cases)
    exits_by_command: dict[str, collections.Counter] = collections.defaultdict(collections.Counter)
    for r in cases:
        exits_by_command[command_of(r)][r["exit"]] += 1
    by_kind: dict[str, list[dict]] = {k: [] for k in KINDS}
    for r in problems:
        by_kind[kind_of(r)].append(r)
    hangs = [r for r in problems if kind_of(r) == "hang" and r.get("failure", "").startswith("hang")]
    timed = sorted(cases + hangs, key=lambda r: -r.get("seconds", 120.0))
    return {
        "cases": len(cases) + len(kills),
        "per_command": per_command,
        "exits": exits,
        "exits_by_command": exits_by_command,
        "kills": kills,
        "by_kind": by_kind,
        "slowest": timed[:slowest],
        "over": [r for r in timed if r.get("seconds", 120.0) > over],
        "peak": max(cases, key=lambda r: r.get("peak_mb", 0.0), default=None),
        "peak_by_command": {c: max(r.get("peak_mb", 0.0) for r in cases if command_of(r) == c) for c in sorted(exits_by_command)},
        "seconds": sum(r.get("seconds", 0.0) for r in cases) + sum(r.get("seconds", 0.0) for r in kills),
        "cpu": sum(r.get("cpu", 0.0) for r in cases),
    }


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("log", type=Path, help="the JSON lines of ROTORCAD_FUZZ_LOG")
    parser.add_argument("--slowest", type=int, default=15, help="how many of the slowest cases to show")
    parser.add_argument("--over", type=float, default=60.0, help="wall seconds past which a case is re-run alone")
    parser.add_argument("--rerun", action="store_true", help="re-run each case past --over alone, to tell load from a hang")
    parser.add_argument("--examples", type=int, default=3, help="failures shown of each kind")
    args = parser.parse_args(argv)
    s = summarise(read_log(args.log), args.slowest, args.over)

    print(f"{args.log}: {s['cases']} cases, {s['seconds'] / 3600:.2f} h of wall time in the cases, {s['cpu'] / 3600:.2f} h CPU")
    print("\ncases per command (exit statuses):")
    for command, n in sorted(s["per_command"].items(), key=lambda kv: (-kv[1], kv[0])):
        statuses = s["exits_by_command"].get(command)
        detail = ", ".join(f"{k}: {v}" for k, v in sorted(statuses.items())) if statuses else ""
        print(f"  {command:<20} {n:>6}   {detail}")
    print("\nexit statuses: " + ", ".join(f"{k}: {v}" for k, v in sorted(s["exits"].items())))
    if s["kills"]:
        k = s["kills"]
        signals = collections.Counter(r["kill"] for r in k)
        print(
            f"kills: {len(k)} ({', '.join(f'{a} {b}' for a, b in sorted(signals.items()))}), "
            f"orphan processes {sum(r.get('orphans', 0) for r in k)}, "
            f"temporaries seen {sum(r.get('temporaries', 0) for r in k)}, "
            f"killed before rotorcad started {sum(bool(r.get('before_start')) for r in k)}"
        )
    print("\nfailures by kind:")
    for kind in KINDS:
        found = s["by_kind"][kind]
        print(f"  {kind:<16} {len(found)}")
        for r in found[: args.examples]:
            what = r.get("unclear") or r.get("failure", "")
            message = f" -- {r['message']}" if "message" in r else ""
            print(f"      [{command_of(r)}] {' '.join(what.split())[:200]}{message[:200]}")
            print(f"        argv: {shown(r.get('argv'))}")
    print(f"\nthe {len(s['slowest'])} slowest cases (wall s, CPU s, exit, peak MB):")
    for r in s["slowest"]:
        cpu = f"{r['cpu']:7.1f}" if "cpu" in r else "      ?"
        status, peak = r.get("exit", "hang"), r.get("peak_mb", 0)
        print(f"  {r.get('seconds', 120.0):7.1f} {cpu} {status!s:>5} {peak:7.0f}  {shown(r.get('argv'))}")
    if s["peak"]:
        p = s["peak"]
        print(f"\npeak memory: {p['peak_mb']:.0f} MB ({command_of(p)}, {p['test']}: {shown(p.get('argv'), 120)})")
        print("  by command: " + ", ".join(f"{c} {mb:.0f}" for c, mb in s["peak_by_command"].items()) + " (MB)")
    print(f"\ncases past {args.over:g} s of wall time: {len(s['over'])}")
    for r in s["over"]:
        line = f"  {r.get('seconds', 120.0):7.1f} s  {shown(r.get('argv'), 120)}"
        if args.rerun:
            again = rerun(r, max(args.over, 60.0))
            figures = ""
            if "cpu" in again:
                figures = f" ({again['seconds']:.1f} s wall, {again['cpu']:.1f} s CPU, exit {again['exit']})"
            line += f"\n      alone: {again['verdict']}{figures}"
        print(line)
    return 0


if __name__ == "__main__":
    sys.exit(main())

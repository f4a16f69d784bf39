"""Entry point of the ``rotorcad`` command: the command group and the error policy.

Every input problem ends as one sentence on stderr and exit status 2, without a traceback
(CONTRACT.md, common rules).
"""

from __future__ import annotations

# The first statements of the command, before any other import (typing, click and the rest take
# some 50 ms, and a Ctrl-C then printed Python's traceback): Ctrl-C from here on is one line and
# exit 130. What runs before this module (the interpreter's start-up and ``site``) is Python's.
import os
import sys


def _interrupted_hook(kind, value, tb):  # pragma: no cover - exercised by a real Ctrl-C at start-up
    """Ctrl-C before :func:`main` runs (while Python imports the command): one line, exit 130."""
    if issubclass(kind, KeyboardInterrupt):
        sys.stderr.write("\nrotorcad: interrupted.\n")
        sys.stderr.flush()
        os._exit(130)
    sys.__excepthook__(kind, value, tb)


sys.excepthook = _interrupted_hook

import gc  # noqa: E402
import importlib  # noqa: E402
import re  # noqa: E402
import signal  # noqa: E402
import threading  # noqa: E402
import warnings  # noqa: E402
from typing import Any  # noqa: E402

import click  # noqa: E402

from rotorcad import __version__  # noqa: E402
from rotorcad.errors import DesignError, InputNote  # noqa: E402

# name -> (module:attribute, one-line summary): a command's module (and the heavy libraries it
# needs) is imported only when that command runs, so `rotorcad --help` starts at once
COMMANDS: dict[str, tuple[str, str]] = {
    "gear": ("rotorcad.cli.gear:gear", "One involute gear cut by the ISO 53 basic rack, optionally with its mate."),
    "rotor": ("rotorcad.cli.rotor:rotor", "A screw-rotor pair from a design or from points, with Rinder's analysis."),
    "hob": ("rotorcad.cli.hob_cmd:hob", "Rack and hob tooth of a gear or rotor pair, and the hobbability verdict."),
    "cut": ("rotorcad.cli.cut_cmd:cut", "Hob cutting simulation of a gear against the analytic envelope."),
    "pump": ("rotorcad.cli.pump_cmd:pump", "Delivery, irregularity and harmonics of an external gear pump."),
    "export": ("rotorcad.cli.export_cmd:export", "Solids of a rotor pair or gear design in every format (STL, STEP, DXF, ...)."),
    "interfere": (
        "rotorcad.cli.interfere_cmd:interfere",
        "Interference of the rotor pair and with the housing, as designed or assembled.",
    ),
    "clearance": ("rotorcad.cli.clearance_cmd:clearance", "Meshing clearance (Wu & Chi) of a pair from measured points."),
    "deflect": ("rotorcad.cli.deflect_cmd:deflect", "Deflection of the rotors under gas load (Rinder & Deix)."),
    "sweep": ("rotorcad.cli.sweep_cmd:sweep", "Thousands of rotor variants built and judged side by side, on Dask."),
    "coupling": ("rotorcad.cli.coupling_cmd:coupling", "Oil film of a gear coupling with barrel-shaped teeth (Belkov et al.)."),
    "grind": ("rotorcad.cli.grind_cmd:grind_cmd", "Form-grinding wheel of a rotor or gear, checked; the dresser's files."),
    "report": ("rotorcad.cli.report_cmd:report", "One self-contained HTML page per rotor or gear design, for a design review."),
    "inspect": ("rotorcad.cli.inspect_cmd:inspect", "Measured gear teeth (ISO 1328-1) or rotor against the nominal part."),
}


class LazyGroup(click.Group):
    """A command group that imports a command's module when the command is used."""

    def list_commands(self, ctx: click.Context) -> list[str]:
        """Return the names of the commands, in the order of :data:`COMMANDS`."""
        return list(COMMANDS)

    def get_command(self, ctx: click.Context, cmd_name: str) -> click.Command | None:
        """Import the module of command ``cmd_name`` and return the command (None for an unknown name)."""
        if cmd_name not in COMMANDS:
            return None
        module, _, attr = COMMANDS[cmd_name][0].partition(":")
        running = gc.isenabled()
        gc.disable()  # imports make many objects and no garbage: no collection walks them meanwhile
        try:
            return getattr(importlib.import_module(module), attr)
        finally:
            if running:
                # and none afterwards: the modules' objects, all young, would make the next
                # collection walk every one of them (10 ms after the export's imports, measured)
                gc.freeze()
                gc.enable()

    def format_commands(self, ctx: click.Context, formatter: click.HelpFormatter) -> None:
        """Write the command list from the one-line summaries of :data:`COMMANDS` (no module is imported)."""
        with formatter.section("Commands"):
            formatter.write_dl([(name, summary) for name, (_, summary) in COMMANDS.items()])


@click.group(cls=LazyGroup, context_settings={"help_option_names": ["-h", "--help"]})
@click.version_option(__version__, prog_name="rotorcad")
def cli() -> None:
    """rotorcad: conjugate profiles, gears and screw rotors to manufacturing files.

    Lengths in mm, angles in degrees on the command line. Run `rotorcad COMMAND --help`.
    """


def main(argv: list[str] | None = None) -> int:
    """Run the CLI; return the exit status.

    Parameters
    ----------
    argv : list of str, optional
        The arguments after ``rotorcad``; ``sys.argv[1:]`` when None.

    Returns
    -------
    int
        0 success, 1 a finding a command reports as its status (``interfere``: interference),
        2 bad input, 130 interrupted (Ctrl-C), 70 an internal error (a bug: please report it).
    """
    args = sys.argv[1:] if argv is None else list(argv)
    from rotorcad.cli import progress

    previous = _on_signals()
    progress.start_waiting("--quiet" in args or not args or {"-h", "--help", "--version"} & set(args))
    try:
        with warnings.catch_warnings(record=True) as caught:  # numpy's RuntimeWarnings are no message for a user
            warnings.simplefilter("ignore", RuntimeWarning)
            warnings.simplefilter("always", InputNote)
            status = _run(args)
    finally:
        progress.stop_waiting()
        progress.SIGNALLED.clear()
        for signum, handler in previous.items():
            signal.signal(signum, handler)
    for w in caught:  # other warnings as before
        if not issubclass(w.category, InputNote):
            warnings.showwarning(w.message, w.category, w.filename, w.lineno)
    if status in (0, 1):  # a refusal stays one sentence; after a result, what was done to the input
        said = ((getattr(w.category, "label", "note"), str(w.message)) for w in caught if issubclass(w.category, InputNote))
        for label, note in dict.fromkeys(said):  # "warning" for a value that looks like another unit
            click.echo(f"rotorcad: {label}: {note}.", err=True)
    common = sys.modules.get("rotorcad.cli.common")  # imported by any command that makes a folder
    if common is not None:
        if status not in (0, 1):
            common.remove_created_folders()
        common.CREATED_FOLDERS.clear()
    return status


class Terminated(KeyboardInterrupt):
    """SIGTERM (a time limit, ``kill``): unwound like Ctrl-C, so that temporaries and the worker go."""


def _signalled(signum: int, frame: object) -> None:
    """Record Ctrl-C or SIGTERM and unwind.

    A library that swallows the exception (trimesh wraps any exception of its imports) is caught
    again at the next progress step (:data:`rotorcad.cli.progress.SIGNALLED`).
    """
    from rotorcad.cli import progress

    progress.SIGNALLED.append(signum)
    raise Terminated if signum == signal.SIGTERM else KeyboardInterrupt


def _on_signals() -> dict[int, Any]:
    """Route SIGINT and SIGTERM to :func:`_signalled` while a command runs; return the handlers replaced.

    Nothing is changed outside the main thread, where Python cannot set a handler.
    """
    if threading.current_thread() is not threading.main_thread():
        return {}
    return {signum: signal.signal(signum, _signalled) for signum in (signal.SIGINT, signal.SIGTERM)}


def _stopped() -> int:
    """Say why the command was stopped (one line) and return its status: 143 SIGTERM, else 130."""
    from rotorcad.cli import progress

    if signal.SIGTERM in progress.SIGNALLED:
        click.echo("rotorcad: terminated.", err=True)
        return 143
    click.echo("rotorcad: interrupted.", err=True)
    return 130


def _run(args: list[str]) -> int:
    """:func:`main` without the clean-up: the exit status of one command line."""
    try:
        if not args:  # bare `rotorcad`: the help, as with --help
            with click.Context(cli, info_name="rotorcad") as ctx:
                click.echo(cli.get_help(ctx))
            return 0
        status = cli.main(args=args, prog_name="rotorcad", standalone_mode=False)
    except click.exceptions.Exit as exc:
        return int(exc.exit_code)
    except (click.exceptions.Abort, KeyboardInterrupt):
        return _stopped()
    except click.ClickException as exc:
        message = " ".join(exc.format_message().split())
        # click's "No such option '--x'. Did you mean '--y'?" as one sentence: "... '--x' (did you mean '--y'?)."
        message = re.sub(r"\. \(?Did you mean (.*?)\??\)?$", r" (did you mean \1?)", message)
        if not message.endswith((".", "?", "!", ")")):
            message += "."
        elif message.endswith(")"):
            message += "."
        click.echo(f"rotorcad: error: {message}", err=True)
        return 2 if exc.exit_code in (1, 2) else int(exc.exit_code)
    except DesignError as exc:
        click.echo(f"rotorcad: error: {exc}", err=True)
        return 2
    except MemoryError:
        click.echo("rotorcad: error: the request needs more memory than this machine has; ask for less detail.", err=True)
        return 2
    except Exception as exc:  # a bug: one line (set ROTORCAD_DEBUG=1 for the traceback), never a silent pass
        if sys.modules["rotorcad.cli.progress"].SIGNALLED:  # the signal's exception was swallowed and this followed
            return _stopped()
        if os.environ.get("ROTORCAD_DEBUG"):
            raise
        text = " ".join(str(exc).split())[:300]
        click.echo(
            f"rotorcad: internal error ({type(exc).__name__}: {text}); please report it with the command line "
            "(ROTORCAD_DEBUG=1 shows the traceback).",
            err=True,
        )
        return 70
    return status if isinstance(status, int) and not isinstance(status, bool) else 0


def run() -> None:
    """Run the ``rotorcad`` command (console script, ``python -m rotorcad.cli.main``): :func:`main`, then exit.

    Python's finalisation frees every object left one by one (the modules of numpy, shapely,
    click and rich, the command's arrays): 40-75 ms of CPU after an export (measured, 2 cores),
    for a process that is ending. The command ends at once instead, once it has done what that
    finalisation does that anyone sees: the ``atexit`` handlers run (logging's flush, temporary
    folders, a Dask client's close) and the standard streams are flushed. Only when this is the
    only thread left (Python would wait for another) and the streams flush; else it exits as usual.
    :func:`main` (for a caller in Python) returns the status as before.
    """
    import atexit

    status = main()
    if threading.active_count() == 1:
        atexit._run_exitfuncs()
        try:
            sys.stdout.flush()
            sys.stderr.flush()
        except (OSError, ValueError):  # a closed pipe: Python's own exit says so, with its status
            sys.exit(status)
        os._exit(status)
    sys.exit(status)


if __name__ == "__main__":  # pragma: no cover
    run()

"""Progress of a command's long stages.

Issue 15: nothing runs longer than a minute without a progress bar. A :class:`Steps` is opened
around every stage that can run long on valid input: the cutting passes of ``cut``, the solids and
files of ``export``, the 2-D sweep and the solids of ``interfere``, the angle sweep of
``deflect``, the outline and files of ``gear``, the build and analysis of ``rotor``, the variants
of ``sweep``. It draws a rich bar on stderr only on a terminal and without ``--quiet``
(CONTRACT.md: progress bars appear only on a terminal); it is counted in :data:`OPENED` either
way, so that the fuzz suite can check that a long case reported its progress whether or not a
terminal was there to show it.
"""

from __future__ import annotations

import sys
from types import TracebackType
from typing import Any

SIGNALLED: list[int] = []
"""Ctrl-C or SIGTERM received while the command runs (set by the command line's handlers): the
next progress step raises again, in case a library swallowed the first exception."""

OPENED: list[str] = []
"""The descriptions of every :class:`Steps` opened in this process, in order (for the tests)."""


def on_terminal() -> bool:
    """Whether stderr is a terminal (the tests replace this to see the bars)."""
    return bool(getattr(sys.stderr, "isatty", lambda: False)())


class Steps:
    """A progress bar over ``total`` steps (None: a pulsing bar of unknown length).

    Parameters
    ----------
    description : str
        What the command is doing, shown left of the bar ("cutting", "sweeping solids").
    total : int or None
        Number of steps, or None when it is not known beforehand.
    quiet : bool
        The command's ``--quiet``: no bar at all.

    Use as a context manager; :meth:`advance` after each step. The bar is transient: it is gone
    when the stage ends, so that a table or JSON printed afterwards stands alone.
    """

    def __init__(
        self, description: str, total: int | None, quiet: bool = False, columns: tuple[str, ...] = (), **fields: Any
    ) -> None:
        stop_waiting()  # a stage's own bar replaces the command's "working" bar
        _OWN_BAR_SHOWN.append(True)
        self._setup(description, total, quiet, columns, fields)

    def _setup(self, description: str, total: int | None, quiet: bool, columns: tuple[str, ...], fields: dict) -> None:
        self.description = description
        self.total = total
        self.done = 0
        self._bar: Any = None
        self._task: Any = None
        OPENED.append(description)
        if quiet or not on_terminal():
            return
        from rich.console import Console
        from rich.progress import BarColumn, MofNCompleteColumn, Progress, TextColumn, TimeElapsedColumn

        shown = [TextColumn("{task.description}"), BarColumn()]
        shown += [MofNCompleteColumn()] if total is not None else []
        shown += [TextColumn(c) for c in columns]  # e.g. "{task.fields[failed]} failed" with failed=0 in ``fields``
        self._bar = Progress(*shown, TimeElapsedColumn(), console=Console(file=sys.stderr, force_terminal=True), transient=True)
        self._task = self._bar.add_task(description, total=total, **fields)

    @property
    def shown(self) -> bool:
        """Whether a bar is drawn (a terminal and no ``--quiet``)."""
        return self._bar is not None

    def __enter__(self) -> Steps:
        return self.start()

    def start(self) -> Steps:
        """Draw the bar (when shown); the context manager does this."""
        if self._bar is not None:
            self._bar.start()
        return self

    def stop(self) -> None:
        """Take the bar away (when shown); the context manager does this."""
        if self._bar is not None:
            self._bar.stop()

    def advance(self, steps: int = 1, description: str | None = None) -> None:
        """Count one step (or ``steps``) done.

        Parameters
        ----------
        steps : int
            Steps done since the last call.
        description : str, optional
            Replaces the text left of the bar.
        """
        if SIGNALLED:
            raise KeyboardInterrupt
        self.done += steps
        if self._bar is not None:
            fields: dict[str, Any] = {"advance": steps}
            if description is not None:
                fields["description"] = description
            self._bar.update(self._task, **fields)

    def update(self, completed: int, **fields: Any) -> None:
        """Set the steps done to ``completed`` and the extra ``fields`` of the columns.

        Parameters
        ----------
        completed : int
            Steps done so far.
        **fields
            Values of the columns' fields (e.g. ``failed=3``).
        """
        if SIGNALLED:
            raise KeyboardInterrupt
        self.done = completed
        if self._bar is not None:
            self._bar.update(self._task, completed=completed, **fields)

    def __exit__(self, kind: type[BaseException] | None, exc: BaseException | None, tb: TracebackType | None) -> None:
        self.stop()


WAIT_SECONDS = 2.0
"""A command still working after this long without a bar of its own shows a "working" bar."""
_WAITING: list[Steps] = []
_TIMER: list[Any] = []  # the SIGALRM handler the timer replaced


def _show_waiting(signum: int, frame: Any) -> None:
    _restore_timer()
    if _WAITING or _OWN_BAR_SHOWN:
        return
    try:  # a handler's exception would surface anywhere in the command: a bar is never worth that
        bar = Steps.__new__(Steps)  # not through __init__: it would stop this very bar
        Steps._setup(bar, "working", None, False, (), {})
        _WAITING.append(bar.start())
    except Exception:
        pass


def _restore_timer() -> None:
    import signal

    if _TIMER:
        signal.setitimer(signal.ITIMER_REAL, 0.0)
        signal.signal(signal.SIGALRM, _TIMER.pop())


def start_waiting(quiet: bool) -> None:
    """Arm the "working" bar: shown after :data:`WAIT_SECONDS` if no stage has a bar by then.

    Only on a terminal, without ``--quiet`` and in the main thread (a SIGALRM timer, not a thread:
    a thread would keep ``export`` from forking its writer process).
    """
    import signal
    import threading

    if quiet or not on_terminal() or threading.current_thread() is not threading.main_thread():
        return
    if signal.getsignal(signal.SIGALRM) not in (signal.SIG_DFL, signal.SIG_IGN, None):
        return  # the caller's own alarm (e.g. a test's time limit) is left alone
    import rich.console  # imported here, never inside the signal handler
    import rich.progress  # noqa: F401

    _OWN_BAR_SHOWN.clear()
    _TIMER.append(signal.signal(signal.SIGALRM, _show_waiting))
    signal.setitimer(signal.ITIMER_REAL, WAIT_SECONDS)


def stop_waiting() -> None:
    """Disarm the timer and take the "working" bar away (idempotent)."""
    _restore_timer()
    while _WAITING:
        _WAITING.pop().stop()


_OWN_BAR_SHOWN: list[bool] = []

NOTED: list[str] = []
"""Every note said before a long run in this process (for the tests)."""


def say_long_run(note: str | None, quiet: bool) -> None:
    """Say on stderr, before the work starts, that it will take over a minute (CONTRACT.md).

    Written whether or not stderr is a terminal (a script's log then shows why it waits), never on
    stdout (``--json`` stays one object), and not with ``--quiet``.

    Parameters
    ----------
    note : str or None
        :func:`rotorcad.work.long_run_note`; None says nothing.
    quiet : bool
        The command's ``--quiet``.
    """
    if note is None:
        return
    NOTED.append(note)
    if not quiet:
        sys.stderr.write(f"rotorcad: note: {note}.\n")
        sys.stderr.flush()


__all__ = ["NOTED", "OPENED", "Steps", "on_terminal", "say_long_run", "start_waiting", "stop_waiting"]

"""Writers that run in a second process while this one goes on.

An export spends its time in two independent halves: sweeping and meshing (manifold3d, trimesh)
and the exact STEP and DXF files (OpenCASCADE, whose import alone takes 0.6 s, and ezdxf). On a
Linux machine with two or more cores the second half runs in one worker process, so that
OpenCASCADE is never loaded here.

The worker is forked, not spawned: ``spawn`` (and ``forkserver``) run the caller's main script again
in the worker, which breaks any user script that calls rotorcad without the
``if __name__ == "__main__"`` guard. A fork copies only the calling thread, so the pool is made
before the command starts any thread of its own (the progress bar) and is not made at all when
other Python threads are running. With one core, another system, ``ROTORCAD_WORKERS=0`` in the
environment, or when no worker can be started, every job runs here, in order, with the same result.
"""

from __future__ import annotations

import gc
import importlib
import multiprocessing
import os
import signal
import sys
import threading
from collections.abc import Callable
from concurrent.futures import Future, ProcessPoolExecutor
from concurrent.futures.process import BrokenProcessPool
from dataclasses import dataclass
from pathlib import Path
from typing import Any


@dataclass(frozen=True)
class BackgroundWriter:
    """A file writer that may run in the worker process.

    Parameters
    ----------
    function
        A module-level function (it is pickled by name), called as ``function(path, *args)``.
    args
        Its further arguments; they are pickled, so plain values and numpy arrays, not meshes.
    done
        Called in this process with the function's return value (e.g. to fill a table row).
    failed
        Called in this process with a ``ValueError`` the function raised; returns the exception
        to raise instead (e.g. one naming the command-line option).
    """

    function: Callable[..., Any]
    args: tuple[Any, ...] = ()
    done: Callable[[Any], None] | None = None
    failed: Callable[[ValueError], BaseException] | None = None

    def finish(self, run: Callable[[], Any]) -> None:
        """Run ``run`` (which returns the function's value) and hand its value or failure on.

        Parameters
        ----------
        run : callable
            Runs the job (here or by waiting for the worker) and returns the function's value.

        Raises
        ------
        BaseException
            The exception ``failed`` makes of a ``ValueError`` the job raised (the ``ValueError``
            itself without ``failed``); other exceptions pass unchanged.
        """
        try:
            value = run()
        except ValueError as exc:
            if self.failed is None:
                raise
            raise self.failed(exc) from None
        if self.done is not None:
            self.done(value)


def worker_count() -> int:
    """Return the number of worker processes to use: 1 or 0 (run here).

    1 on Linux with two or more cores and no other Python thread running, else 0;
    ``ROTORCAD_WORKERS=0`` in the environment also says 0.
    """
    if os.environ.get("ROTORCAD_WORKERS", "").strip() == "0":
        return 0
    if sys.platform != "linux" or threading.active_count() > 1:
        return 0
    return 1 if (os.cpu_count() or 1) >= 2 else 0


PR_SET_PDEATHSIG = 1  # prctl(2) option: the signal this process gets when its parent dies


def _die_with_parent(parent: int) -> None:
    """Make this process end when its parent does, however the parent ends (SIGKILL included).

    On Linux the kernel sends SIGKILL to this process when the thread that forked it exits
    (``prctl(PR_SET_PDEATHSIG)``, prctl(2)); a parent that died before the call is seen by the
    parent id having changed. Elsewhere nothing is done (the pool runs here there).

    Parameters
    ----------
    parent : int
        The parent's process id, taken before the fork.
    """
    if sys.platform != "linux":
        return
    import ctypes

    try:
        libc = ctypes.CDLL(None, use_errno=True)
        libc.prctl(PR_SET_PDEATHSIG, signal.SIGKILL, 0, 0, 0)
    except (OSError, AttributeError):  # no prctl: the parent's check below still holds at start
        pass
    if os.getppid() != parent:  # the parent died before the call
        os._exit(1)


def _start_worker(preload: tuple[str, ...], parent: int | None = None) -> None:
    """Prepare the worker: end with the parent, leave Ctrl-C to it, import ``preload`` meanwhile.

    The parent stops the worker and removes what it wrote; a parent killed outright (SIGKILL, a
    time limit) takes the worker with it (:func:`_die_with_parent`), so no worker outlives it.
    """
    if parent is not None:
        _die_with_parent(parent)
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    signal.signal(signal.SIGTERM, signal.SIG_DFL)  # not the command's handler, inherited by the fork
    import_without_collections(preload)
    gc.freeze()  # what the worker has imported stays for its life: its later collections leave it alone


def import_without_collections(modules: tuple[str, ...]) -> None:
    """Import ``modules`` with the cyclic garbage collector paused and the symbols of their libraries bound lazily.

    Importing OpenCASCADE makes some hundred thousand objects (its classes and functions), none of
    them garbage, and each few hundred of them start a collection that walks the younger ones
    again: measured on 2 cores, ``import OCP.STEPControl, ezdxf`` took 0.9 s of CPU with the
    collector paused and 1.1 s with it running. Garbage made meanwhile is collected once it runs again.

    Python loads extension modules with ``RTLD_NOW`` (``sys.getdlopenflags()``), which makes the
    dynamic linker resolve every function symbol of the module and of the libraries it pulls in
    before the import returns: for OpenCASCADE's 60 libraries some 135 000 relocations
    (``LD_DEBUG=statistics``), most of them for functions an export never calls. Here they are
    loaded with ``RTLD_LAZY`` (dlopen(3): a function's symbol is resolved at its first call), the
    flags restored afterwards: ``import OCP.STEPControl`` measured 605 ms of CPU instead of 649
    (least of 8 interleaved runs each, 2 cores; medians 660 and 709 ms).

    Parameters
    ----------
    modules : tuple of str
        Module names (``"OCP.STEPControl"``).
    """
    running = gc.isenabled()
    gc.disable()
    flags = sys.getdlopenflags() if hasattr(sys, "getdlopenflags") else None
    try:
        if flags is not None and hasattr(os, "RTLD_LAZY"):
            sys.setdlopenflags((flags & ~getattr(os, "RTLD_NOW", 0)) | os.RTLD_LAZY)
        for module in modules:
            importlib.import_module(module)
    finally:
        if flags is not None:
            sys.setdlopenflags(flags)
        if running:
            gc.enable()


class WorkerPool:
    """Runs :class:`BackgroundWriter` jobs in one worker process, or here when there is none.

    Use as a context manager around the work, entered before any thread is started: the worker is
    forked on entry. Leaving it waits for the running job (so that no file is written after the
    caller has cleaned up) and stops the worker.

    Parameters
    ----------
    background
        False runs every job here (e.g. when nothing will be written in the background).
    preload
        Modules the worker imports as soon as it starts (e.g. ``"OCP.STEPControl"``, 0.6 s), with
        the garbage collector paused (:func:`import_without_collections`); imported here when the
        jobs run here.
    """

    def __init__(self, background: bool = True, preload: tuple[str, ...] = ()) -> None:
        self._executor: ProcessPoolExecutor | None = None
        if background and worker_count():
            # the objects made so far are frozen for the fork (gc.freeze, as the gc module's docs
            # advise before a fork without exec): the worker's collections, many while it imports
            # OpenCASCADE, then leave them alone instead of touching, and so copying, every page
            # of the inherited heap; this process takes them back at once
            frozen = gc.get_freeze_count()  # a caller's own frozen objects stay frozen
            gc.freeze()
            try:
                self._executor = ProcessPoolExecutor(
                    max_workers=1,
                    mp_context=multiprocessing.get_context("fork"),
                    initializer=_start_worker,
                    initargs=(preload, os.getpid()),
                )
                self._executor.submit(int)  # forks now, while this is the only thread
            except (OSError, NotImplementedError, ValueError, BrokenProcessPool):  # e.g. no /dev/shm: run here
                self._executor = None
            finally:
                if not frozen:
                    gc.unfreeze()
        if background and self._executor is None:  # the jobs run here: their libraries imported as the worker would
            import_without_collections(preload)

    def __enter__(self) -> WorkerPool:
        return self

    def __exit__(self, kind: type[BaseException] | None, *exc: object) -> None:
        self.stop(kill=kind is not None and issubclass(kind, KeyboardInterrupt))

    def stop(self, kill: bool = False) -> None:
        """Cancel what has not started, wait for the running job, stop the worker (idempotent).

        Parameters
        ----------
        kill : bool
            End the worker at once instead of waiting for its job (Ctrl-C, SIGTERM): what it was
            writing is a temporary the caller removes, and a dead worker writes nothing more.
        """
        if self._executor is not None:
            if kill:
                for process in list(getattr(self._executor, "_processes", {}).values()):
                    try:
                        process.kill()
                        process.join(5.0)
                    except (OSError, ValueError, AttributeError):
                        pass
            try:
                self._executor.shutdown(wait=True, cancel_futures=True)
            except BrokenProcessPool:  # the worker was just ended
                pass
            self._executor = None

    def submit(self, job: BackgroundWriter, path: Path) -> Callable[[], None]:
        """Start ``job`` writing ``path``; return the call that waits for it and finishes it.

        Without a worker the job runs when that call is made. When the worker dies (killed, out of
        memory) the job is run here instead.

        Parameters
        ----------
        job : BackgroundWriter
            The writer.
        path : Path
            The (temporary) file to write.

        Returns
        -------
        callable
            Call it to wait for the job and hand on its value or failure (:meth:`BackgroundWriter.finish`).
        """
        if self._executor is None:
            return lambda: job.finish(lambda: job.function(path, *job.args))
        future: Future = self._executor.submit(job.function, path, *job.args)

        def result() -> Any:
            try:
                return future.result()
            except BrokenProcessPool:  # the worker died (killed, out of memory): do it here instead
                return job.function(path, *job.args)

        return lambda: job.finish(result)

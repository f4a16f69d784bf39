"""All-or-nothing writing of a group of output files.

Each file is written by its writer to a hidden temporary name in the target folder; only when
every writer succeeded are the temporaries renamed over the targets (``os.replace`` is atomic on
one file system). On any failure the temporaries are removed and the existing files are left
untouched. A writer is either a function of the path, run here in order, or a
:class:`~exports.background.BackgroundWriter`, started first in a worker process so that it runs
while the others do.
"""

from __future__ import annotations

import os
import tempfile
from collections.abc import Callable, Iterable
from pathlib import Path

from exports.background import BackgroundWriter, WorkerPool
from rotorcad.errors import DesignError

Writer = Callable[[Path], None] | BackgroundWriter
NAME_MAX = 255  # bytes of one file name (Linux, macOS, Windows)


def staging_prefix(target: Path) -> str:
    """Return the start of the hidden temporary name for ``target``.

    Its name cut to 100 bytes, so that a name near the file system's limit still leaves room for the
    temporary's suffix.

    Parameters
    ----------
    target : Path
        The file to be written.

    Returns
    -------
    str
        ``"." + name[:100 bytes] + "."``.
    """
    return "." + os.fsencode(target.name)[:100].decode(errors="ignore") + "."


def check_writable(path: Path, label: str) -> None:
    """Refuse a target that cannot be written, before any work is done.

    Parameters
    ----------
    path : Path
        The file to be written.
    label : str
        The option that named it (leads the error sentence).

    Raises
    ------
    DesignError
        A name over :data:`NAME_MAX` bytes, a folder, a path that is not a regular file (a device, a
        FIFO or a socket would be replaced by a file), or a folder that is missing or not writable.
    """
    folder = path.parent if str(path.parent) else Path(".")
    size = len(os.fsencode(path.name))
    if size > NAME_MAX:
        raise DesignError(label, f"a file name of at most {NAME_MAX} bytes", f"{size} bytes")
    if path.exists() and path.is_dir():
        raise DesignError(label, "a file path, not a folder", str(path))
    if path.exists() and not path.is_file():
        raise DesignError(label, "a regular file (not a device, FIFO or socket)", str(path))
    if not folder.is_dir():
        raise DesignError(label, "in an existing folder", str(path))
    if not os.access(folder, os.W_OK):
        raise DesignError(label, "in a writable folder", str(path))


def write_all(outputs: Iterable[tuple[Path, Writer]], pool: WorkerPool | None = None) -> list[Path]:
    """Write every ``(target, writer)`` pair or none of them.

    The background writers start first, in ``pool``'s worker (here without a pool); the others run
    here meanwhile, in the given order. A target that is a symbolic link is written where the link
    points; a file replaced keeps its permissions.

    Parameters
    ----------
    outputs : iterable of (Path, Writer)
        Targets and their writers (a function of the temporary path, or a
        :class:`~exports.background.BackgroundWriter`).
    pool : WorkerPool, optional
        Worker for the background writers; default none (they run here).

    Returns
    -------
    list of Path
        The targets written.
    """
    staged: list[tuple[Path, Path, Writer]] = []
    workers = pool or WorkerPool(background=False)
    try:
        for target, writer in outputs:
            target = Path(target)
            if target.is_symlink():  # write the file the link points to; the link stays
                target = Path(os.path.realpath(target))
            remove_stale_temporaries(target)
            fd, tmp = tempfile.mkstemp(prefix=f"{staging_prefix(target)}{os.getpid()}.", suffix=".tmp", dir=target.parent or ".")
            os.close(fd)
            staged.append((Path(tmp), target, writer))
        waiting = [workers.submit(w, tmp) for tmp, _, w in staged if isinstance(w, BackgroundWriter)]
        for tmp, _, writer in staged:
            if not isinstance(writer, BackgroundWriter):
                writer(tmp)
        for finish in waiting:
            finish()
        for tmp, target, _ in staged:
            mode = target.stat().st_mode & 0o777 if target.exists() else 0o666 & ~_umask()
            os.chmod(tmp, mode)
        for tmp, target, _ in staged:
            os.replace(tmp, target)
    except BaseException as exc:
        workers.stop(kill=isinstance(exc, KeyboardInterrupt))  # no job may write after its temporary is removed
        for tmp, *_ in staged:
            tmp.unlink(missing_ok=True)
        raise
    return [target for _, target, _ in staged]


def remove_stale_temporaries(target: Path) -> list[Path]:
    """Remove the temporaries of ``target`` left by a run that was killed outright (SIGKILL).

    A temporary is named ``staging_prefix(target) + PID + "." + random + ".tmp"``; one whose
    process no longer runs can never be finished, and is removed. Those of live processes (another
    run writing the same file) are left alone.

    Parameters
    ----------
    target : Path
        The file about to be written.

    Returns
    -------
    list of Path
        The temporaries removed.
    """
    folder = target.parent if str(target.parent) else Path(".")
    prefix = staging_prefix(target)
    removed = []
    try:
        names = [n for n in os.listdir(folder) if n.startswith(prefix) and n.endswith(".tmp")]
    except OSError:
        return removed
    for name in names:
        pid = name[len(prefix) :].split(".", 1)[0]
        if not pid.isdigit() or int(pid) == os.getpid() or _running(int(pid)):
            continue
        try:
            (folder / name).unlink()
            removed.append(folder / name)
        except OSError:
            pass
    return removed


def _running(pid: int) -> bool:
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except OSError:  # another user's process: it runs
        return True
    return True


def _umask() -> int:
    mask = os.umask(0)
    os.umask(mask)
    return mask

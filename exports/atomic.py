"""All-or-nothing writing of a group of output files.

Each file is written by its writer function to a hidden temporary name in the target folder;
only when every writer succeeded are the temporaries renamed over the targets (``os.replace`` is
atomic on one file system). On any failure the temporaries are removed and the existing files
are left untouched.
"""

from __future__ import annotations

import os
import tempfile
from collections.abc import Callable, Iterable
from pathlib import Path

from rotorcad.errors import DesignError

Writer = Callable[[Path], None]


def check_writable(path: Path, label: str) -> None:
    """Refuse, before any work is done, a target whose folder is missing or not writable."""
    folder = path.parent if str(path.parent) else Path(".")
    if path.exists() and path.is_dir():
        raise DesignError(label, "a file path, not a folder", str(path))
    if not folder.is_dir():
        raise DesignError(label, "in an existing folder", str(path))
    if not os.access(folder, os.W_OK):
        raise DesignError(label, "in a writable folder", str(path))


def write_all(outputs: Iterable[tuple[Path, Writer]]) -> list[Path]:
    """Write every ``(target, writer)`` pair or none of them; return the targets written."""
    staged: list[tuple[Path, Path]] = []
    try:
        for target, writer in outputs:
            target = Path(target)
            fd, tmp = tempfile.mkstemp(prefix=f".{target.name}.", suffix=".tmp", dir=target.parent or ".")
            os.close(fd)
            staged.append((Path(tmp), target))
            writer(Path(tmp))
            mode = target.stat().st_mode & 0o777 if target.exists() else 0o666 & ~_umask()
            os.chmod(tmp, mode)
        for tmp, target in staged:
            os.replace(tmp, target)
    except BaseException:
        for tmp, _ in staged:
            tmp.unlink(missing_ok=True)
        raise
    return [t for _, t in staged]


def _umask() -> int:
    mask = os.umask(0)
    os.umask(mask)
    return mask

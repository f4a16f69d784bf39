"""Reading a user's file defensively: the one place that opens design, points and drawing files.

In the core so that design files are read there (:mod:`rotorcad.design.files`); ``exports``
reads points and drawings through it (its old path :mod:`exports.reading` re-exports it).

A path that is missing, not a regular file (a directory, FIFO, device or socket: checked with
``os.stat`` before it is opened, and opened non-blocking, so nothing hangs) or larger than the
limit is refused in one sentence naming the option or key that gave the file (``label``). Text
is UTF-8 (a byte-order mark is dropped) or, failing that, Latin-1; a NUL byte is binary data,
refused naming its line.
"""

from __future__ import annotations

import os
import stat
from pathlib import Path

from rotorcad.errors import InputFileError

MAX_BYTES = 64 * 2**20
"""Largest file read by default, bytes (64 MiB: points files and drawings)."""

_FILE_KINDS = (
    (stat.S_ISDIR, "a directory"),
    (stat.S_ISFIFO, "a FIFO (named pipe)"),
    (stat.S_ISCHR, "a character device"),
    (stat.S_ISBLK, "a block device"),
    (stat.S_ISSOCK, "a socket"),
)


def _size(limit: int) -> str:
    """``limit`` bytes as the sentence says it: whole MiB or KiB."""
    return f"{limit // 2**20} MiB" if limit % 2**20 == 0 else f"{limit // 1024} KiB"


def check_regular_file(path: Path, label: str, kind: str = "CSV points file", limit: int = MAX_BYTES) -> os.stat_result:
    """Refuse, without opening it, a ``path`` that is missing, not a regular file or too large.

    Parameters
    ----------
    path : Path
        The file to be read.
    label : str
        The option or key that named the file; it leads the error sentence.
    kind : str
        What the file should be, a noun for the error sentence (``"CSV points file"``).
    limit : int
        Largest size accepted, bytes.

    Returns
    -------
    os.stat_result
        The file's status (``st_size`` in bytes).

    Raises
    ------
    InputFileError
        Naming ``label``, what is allowed and what the path is.
    """
    try:
        st = os.stat(path)
    except (FileNotFoundError, NotADirectoryError):
        raise InputFileError(label, f"an existing {kind}", str(path), "there is no such file") from None
    except PermissionError:
        raise InputFileError(label, f"a readable {kind}", str(path), "permission denied") from None
    except (OSError, ValueError) as exc:
        reason = getattr(exc, "strerror", None) or str(exc)
        raise InputFileError(label, f"an existing {kind}", str(path), reason.rstrip(".")) from None
    if not stat.S_ISREG(st.st_mode):
        what = next((name for test, name in _FILE_KINDS if test(st.st_mode)), "not a regular file")
        raise InputFileError(label, f"a {kind}, not a directory, pipe or device", str(path), f"it is {what}")
    if st.st_size > limit:
        raise InputFileError(
            label, f"a {kind} of at most {_size(limit)}", str(path), f"it has {st.st_size} bytes ({st.st_size / 2**20:.1f} MiB)"
        )
    return st


def read_bytes(path: Path, label: str, kind: str, limit: int = MAX_BYTES) -> bytes:
    """Read the whole content of a regular file checked by :func:`check_regular_file`.

    Parameters
    ----------
    path : Path
        The file.
    label : str
        The option or key that named the file.
    kind : str
        What the file should be, for the error sentence.
    limit : int
        Largest size accepted, bytes (a file that grows past it while being read is refused).

    Returns
    -------
    bytes
        The content.

    Raises
    ------
    InputFileError
        A path that is missing, unreadable, not a regular file (also if swapped after the check) or
        larger than ``limit``.
    """
    check_regular_file(path, label, kind, limit)
    flags = os.O_RDONLY | getattr(os, "O_NONBLOCK", 0) | getattr(os, "O_BINARY", 0)
    try:
        fd = os.open(path, flags)  # non-blocking: a FIFO swapped in after the check cannot hang the read
    except OSError as exc:
        raise InputFileError(label, f"a readable {kind}", str(path), exc.strerror or "it cannot be opened") from None
    with os.fdopen(fd, "rb") as f:
        if not stat.S_ISREG(os.fstat(f.fileno()).st_mode):
            raise InputFileError(label, f"a {kind}, not a directory, pipe or device", str(path), "it changed while opened")
        try:
            data = f.read(limit + 1)
        except OSError as exc:
            raise InputFileError(label, f"a readable {kind}", str(path), exc.strerror or "it cannot be read") from None
    if len(data) > limit:
        raise InputFileError(label, f"a {kind} of at most {_size(limit)}", str(path), "it grew while being read")
    return data


def read_text(path: Path, label: str, kind: str, limit: int = MAX_BYTES) -> str:
    """Read the text of a user's file (:func:`read_bytes`), UTF-8 or Latin-1.

    Parameters
    ----------
    path : Path
        The file.
    label : str
        The option or key that named the file.
    kind : str
        What the file should be (``"TOML design file"``), for the error sentence.
    limit : int
        Largest size accepted, bytes.

    Returns
    -------
    str
        The decoded text (a UTF-8 byte-order mark dropped).

    Raises
    ------
    InputFileError
        As :func:`read_bytes`, and for a NUL byte, naming its line.
    """
    data = read_bytes(path, label, kind, limit)
    if b"\x00" in data:
        line = data[: data.index(b"\x00")].count(b"\n") + 1
        raise InputFileError(label, f"a {kind} (text)", str(path), f"line {line} holds a NUL byte (binary data)")
    try:
        return data.decode("utf-8-sig")
    except UnicodeDecodeError:
        return data.decode("latin-1")


__all__ = ["MAX_BYTES", "check_regular_file", "read_bytes", "read_text"]

"""Reading user files safely: regular files only, never more than a limit.

A path a user (or a file's content) names may be a FIFO (opening it would wait for a writer
for ever), a symlink to ``/dev/zero`` (reading it never ends), a device, or a file that grows
while it is read. :func:`read_limited` refuses everything but a regular file and never reads
more than its limit, so reading is bounded in time and memory whatever the path is.

Below the atomic writers (:mod:`scanplan.io.atomic`), the journal and the output targets:
the whole write of a file descriptor (:func:`write_all`), a folder's fsync
(:func:`fsync_dir`), a folder's reader/writer lock (:func:`dir_lock`), the kind of a file
mode (:func:`file_kind`) and CSV cells that never start a formula (:func:`csv_safe`).
"""

from __future__ import annotations

import contextlib
import errno
import os
import stat
from collections.abc import Iterator
from pathlib import Path
from typing import Any

from ..errors import InputError, NotFoundError

__all__ = ["csv_safe", "csv_safe_frame", "dir_lock", "file_kind", "fsync_dir", "lock_file_for",
           "read_limited", "size_text", "user_cache_dir", "write_all"]


_FORMULA_START = ("=", "+", "-", "@", "\t", "\r")


def csv_safe(value: object) -> object:
    """A CSV cell that a spreadsheet will not run as a formula.

    Text starting with ``=``, ``+``, ``-``, ``@``, a tab or a carriage return gets a
    leading ``'`` (OWASP, "CSV Injection": a spreadsheet shows the text, it does not run
    it). Numbers, and text that is a plain number (``-12.5``), are returned unchanged.

    Parameters
    ----------
    value : object
        The cell's value.

    Returns
    -------
    object
        ``value``, or ``"'" + value`` for text a spreadsheet would read as a formula.
    """
    if not isinstance(value, str) or not value.startswith(_FORMULA_START):
        return value
    try:
        float(value)
    except ValueError:
        return "'" + value
    return value if value.strip() == value else "'" + value


def csv_safe_frame(frame: Any) -> Any:
    """A copy of a pandas DataFrame whose text columns are :func:`csv_safe`; numeric
    columns are left as they are."""
    from pandas.api.types import is_bool_dtype, is_numeric_dtype

    out = frame.copy()
    for col in out.columns:
        if not (is_numeric_dtype(out[col].dtype) or is_bool_dtype(out[col].dtype)):
            out[col] = out[col].map(csv_safe, na_action="ignore")
    return out


def size_text(n: int) -> str:
    """``12.3 MB`` or ``1,234 bytes``."""
    return f"{n / 2**20:.1f} MB" if n >= 2**20 else f"{n:,} bytes"


def file_kind(mode: int) -> str:
    """What a non-regular file is, for messages (``a FIFO (named pipe)``)."""
    if stat.S_ISDIR(mode):
        return "a folder"
    if stat.S_ISFIFO(mode):
        return "a FIFO (named pipe)"
    if stat.S_ISCHR(mode) or stat.S_ISBLK(mode):
        return "a device"
    if stat.S_ISSOCK(mode):
        return "a socket"
    return "not a regular file"


def read_limited(path: str | os.PathLike[str], limit: int, *, field: str | None = None) -> bytes:
    """The bytes of the regular file ``path``, refused beyond ``limit`` bytes.

    The path is checked before it is opened (a FIFO or a device is never opened), opened
    without blocking, checked again on the open descriptor (nothing swapped in between),
    and read with a bound (a growing file, or a ``/proc`` file that reports size 0, cannot
    exceed it).

    Parameters
    ----------
    path : path
        The file (symlinks are followed: a link to a regular file is fine).
    limit : int
        Most bytes accepted.
    field : str, optional
        How errors name the file (default: the path).

    Raises
    ------
    NotFoundError
        The file does not exist.
    InputError
        It cannot be read, is not a regular file, or is larger than ``limit``.
    """
    name = field if field is not None else os.fspath(path)
    too_big = f"the limit is {size_text(limit)}"
    try:
        st = os.stat(path)
    except FileNotFoundError as exc:
        raise NotFoundError(name, f"cannot be read: {exc.strerror or 'no such file'}") from None
    except OSError as exc:
        raise InputError(name, f"cannot be read: {exc.strerror or exc}") from None
    if not stat.S_ISREG(st.st_mode):
        raise InputError(name, f"is {file_kind(st.st_mode)}, not a regular file")
    if st.st_size > limit:
        raise InputError(name, f"is {size_text(st.st_size)}; {too_big}")
    flags = os.O_RDONLY | getattr(os, "O_NONBLOCK", 0) | getattr(os, "O_CLOEXEC", 0)
    flags |= getattr(os, "O_BINARY", 0)
    try:
        fd = os.open(path, flags)
    except OSError as exc:
        raise InputError(name, f"cannot be read: {exc.strerror or exc}") from None
    try:
        st = os.fstat(fd)
        if not stat.S_ISREG(st.st_mode):
            raise InputError(name, f"is {file_kind(st.st_mode)}, not a regular file")
        chunks: list[bytes] = []
        got = 0
        while True:
            try:
                chunk = os.read(fd, min(1 << 20, limit + 1 - got))
            except OSError as exc:
                raise InputError(name, f"cannot be read: {exc.strerror or exc}") from None
            if not chunk:
                break
            got += len(chunk)
            if got > limit:
                raise InputError(name, f"is larger than it said (still growing?); {too_big}")
            chunks.append(chunk)
        return b"".join(chunks)
    finally:
        os.close(fd)


def write_all(fd: int, data: bytes) -> None:
    """Write all of ``data`` to the open file ``fd`` and fsync it.

    ``os.write`` may write less than asked (a full disk, a signal); the loop goes on until
    everything is written, and a write that makes no progress is reported as a full disk.

    Parameters
    ----------
    fd : int
        An open file descriptor.
    data : bytes
        The whole content.

    Raises
    ------
    OSError
        From the system, or ``ENOSPC`` when a write makes no progress.
    """
    view = memoryview(data).cast("B")
    while view:
        n = os.write(fd, view)
        if n <= 0:
            raise OSError(errno.ENOSPC, os.strerror(errno.ENOSPC))
        view = view[n:]
    os.fsync(fd)


def fsync_dir(folder: str | os.PathLike[str]) -> None:
    """fsync a folder, so that the renames and new names in it survive a power loss.

    Best effort: a file system or platform that cannot fsync a folder (Windows, some network
    shares) is skipped silently — the files themselves were fsynced before.

    Parameters
    ----------
    folder : path
        The folder.
    """
    try:
        fd = os.open(folder, os.O_RDONLY | getattr(os, "O_DIRECTORY", 0))
    except OSError:
        return
    try:
        os.fsync(fd)
    except OSError:
        pass
    finally:
        os.close(fd)


_HELD: dict[str, int] = {}  # folders this process holds a dir_lock on → nesting depth


def user_cache_dir() -> Path:
    """scanplan's folder in the user's cache folder (the platform's, through platformdirs:
    ``$XDG_CACHE_HOME/scanplan`` on Linux): the norm folder's lock files, the compiled
    report templates."""
    import platformdirs

    return platformdirs.user_cache_path("scanplan", appauthor=False)


def lock_file_for(folder: str | os.PathLike[str]) -> Path:
    """The lock file of ``folder``: in the user's cache folder (:func:`user_cache_dir`),
    named by a hash of the folder's real path — never a file inside the folder itself,
    which may be read-only or a user's own project folder."""
    import hashlib

    real = os.path.normcase(os.path.realpath(folder))
    digest = hashlib.sha256(os.fsencode(real)).hexdigest()[:32]
    return user_cache_dir() / "locks" / f"{digest}.lock"


@contextlib.contextmanager
def dir_lock(folder: str | os.PathLike[str], *, exclusive: bool) -> Iterator[None]:
    """Hold a reader/writer lock on ``folder``: shared for readers, exclusive for writers.

    filelock's :class:`~filelock.ReadWriteLock` on :func:`lock_file_for` (SQLite's file
    locking: POSIX, Windows and macOS alike). Where the lock file cannot be made (no cache
    folder, no permission) it is a no-op: locking is cooperation between scanplan
    processes, and a read-only folder is not locked against anyone. A lock this process
    already holds on the folder covers a nested request (two locks of one process on one
    file would otherwise wait for each other for ever).

    Parameters
    ----------
    folder : path
        The folder to lock.
    exclusive : bool
        Exclusive (writers) or shared (readers).
    """
    key = os.path.realpath(folder)
    if _HELD.get(key):
        _HELD[key] += 1
        try:
            yield
        finally:
            _HELD[key] -= 1
        return
    import sqlite3

    import filelock

    hold: contextlib.AbstractContextManager[None] | None = None
    try:
        path = lock_file_for(folder)
        path.parent.mkdir(parents=True, exist_ok=True)
        lock = filelock.ReadWriteLock(path, is_singleton=False)
        hold = lock.write_lock() if exclusive else lock.read_lock()
        hold.__enter__()
    except (OSError, ValueError, sqlite3.Error):  # no usable lock file here: no lock
        hold = None
    _HELD[key] = 1
    try:
        yield
    finally:
        del _HELD[key]
        if hold is not None:
            hold.__exit__(None, None, None)


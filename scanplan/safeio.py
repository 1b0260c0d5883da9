"""Reading user files safely: regular files only, never more than a limit.

A path a user (or a file's content) names may be a FIFO (opening it would wait for a writer
for ever), a symlink to ``/dev/zero`` (reading it never ends), a device, or a file that grows
while it is read. :func:`read_limited` refuses everything but a regular file and never reads
more than its limit, so reading is bounded in time and memory whatever the path is.
"""

from __future__ import annotations

import contextlib
import errno
import os
import stat
from collections.abc import Iterator

from .errors import InputError, NotFoundError

__all__ = ["dir_lock", "file_kind", "fsync_dir", "read_limited", "size_text", "write_all"]


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


@contextlib.contextmanager
def dir_lock(folder: str | os.PathLike[str], *, exclusive: bool) -> Iterator[None]:
    """Hold a ``flock`` on ``folder``: shared for readers, exclusive for writers.

    A no-op where ``flock`` is missing (not POSIX) or the folder cannot be opened (it does
    not exist, no permission): locking is cooperation between scanplan processes.

    Parameters
    ----------
    folder : path
        The folder to lock.
    exclusive : bool
        ``LOCK_EX`` (writers) or ``LOCK_SH`` (readers).
    """
    fd = None
    try:
        import fcntl

        fd = os.open(folder, os.O_RDONLY)
        fcntl.flock(fd, fcntl.LOCK_EX if exclusive else fcntl.LOCK_SH)
    except (ImportError, OSError):
        pass
    try:
        yield
    finally:
        if fd is not None:
            os.close(fd)

"""One temporary folder per run: everything temporary scanplan or its libraries make lives
in it, and it goes when the run ends — however it ends.

scanplan and the libraries it drives make temporary files and folders of their own:
WeasyPrint a ``weasyprint-*`` folder of fonts for each process that renders a PDF (never
removed by WeasyPrint), openpyxl ``openpyxl.*`` files while it saves a workbook, the
GeoPackage writer ``scanplan-gpkg-*``, the page's server its uploads and one
``scanplan-job-*`` folder per plan (hard links to the uploads), multiprocessing its
``pymp-*`` folders. A run that is killed, stopped by a time limit or by ``SIGTERM`` would
leave them in the system's temporary folder for good.

So a run gets **one folder**, ``<temp>/scanplan-run-XXXXXXXX`` (private, 0700):

* :func:`temporaries` makes it the temporary folder of the process while a run is in it
  (``tempfile.tempdir``, and ``TMPDIR``/``TMP``/``TEMP``/``CPL_TMPDIR`` for the child
  processes and the GDAL it starts), so every library's temporaries land in it;
* :func:`run_scope` is a whole command's run (the command line): the folder is removed
  when the command ends — normally, by an error, by Ctrl+C, or by ``SIGTERM``/``SIGHUP``,
  which end the command the way Ctrl+C does (writes roll back, workers are stopped,
  ``finally`` blocks run) with the exit code 128 + the signal;
* a process that uses scanplan as a library (the Python API) keeps one folder for its
  life, removed when it exits (:mod:`atexit`);
* a run killed outright (``kill -9``, a power loss) cannot remove its folder: the next
  run sweeps it (:func:`sweep`) — **only when its owner is gone**. The owner holds an
  exclusive ``flock`` on the folder's ``.owner`` file for its whole life (the kernel
  releases it when the process dies, whatever the reason; no process id is trusted, so a
  reused id never keeps a stale folder nor loses a live one); a sweep removes a folder
  whose lock it can take, holding it meanwhile, and never follows a link.

Child processes use the folder of the run that started them and never remove it: a forked
child (the PDF worker, a batch's workers) shares the run's state, any other child finds
the folder in ``TMPDIR``; the page's worker gets a folder of its own inside it, removed
when the worker is stopped — also when a plan passes its time limit and the worker is
killed (:mod:`scanplan.web.worker`).
"""

from __future__ import annotations

import atexit
import contextlib
import os
import re
import shutil
import signal
import stat
import sys
import tempfile
import threading
import time
from collections.abc import Iterator
from pathlib import Path

__all__ = ["OWNER", "PREFIX", "remove", "run_dir", "run_scope", "sweep", "temporaries"]

PREFIX = "scanplan-run-"
"""Name of a run's folder: this prefix and 8 characters of :func:`tempfile.mkdtemp`."""
OWNER = ".owner"
"""The file in a run's folder its owner holds locked (and names itself in)."""
TEMP_VARIABLES = ("TMPDIR", "TMP", "TEMP", "CPL_TMPDIR")
"""The environment variables that name the temporary folder (CPL_TMPDIR: GDAL's)."""
UNLOCKED_GRACE_S = 600.0
"""A run's folder without a locked owner file (a run killed between making the folder and
locking it) is swept only when it is older than this [s]."""
_NAME = re.compile(re.escape(PREFIX) + r"[a-z0-9_]{8}")


class _State:
    path: Path | None = None
    owner: int | None = None  # the process id that made (and removes) the folder
    fd: int | None = None  # the locked owner file
    registered: bool = False  # remove() registered with atexit


_STATE = _State()
_LOCK = threading.RLock()


def _lock_owner(folder: Path) -> int:
    """Lock the folder's owner file (made locked, then named, so that a sweep never finds
    it unlocked): its descriptor."""
    import fcntl

    tmp = folder / f"{OWNER}.new"
    fd = os.open(tmp, os.O_WRONLY | os.O_CREAT | os.O_EXCL | os.O_NOFOLLOW, 0o600)
    try:
        fcntl.flock(fd, fcntl.LOCK_EX)
        os.write(fd, f"{os.getpid()}\n".encode())
        os.replace(tmp, folder / OWNER)
    except BaseException:
        os.close(fd)
        raise
    return fd


def _base() -> str:
    """The system's temporary folder (not a run's own)."""
    base = tempfile.gettempdir()
    if _STATE.path is not None and os.path.normpath(base).startswith(str(_STATE.path)):
        return str(_STATE.path.parent)
    return base


def run_dir() -> Path:
    """The run's folder, made on first use (after sweeping the stale ones).

    Returns
    -------
    Path
        An existing folder, private to this user.
    """
    with _LOCK:
        if _STATE.path is not None and _STATE.path.is_dir():
            return _STATE.path
        base = _base()
        sweep(base)
        folder = Path(tempfile.mkdtemp(prefix=PREFIX, dir=base))
        try:
            _STATE.fd = _lock_owner(folder)
        except (OSError, ImportError):  # no flock here (not POSIX): the folder still serves
            _STATE.fd = None
        _STATE.path, _STATE.owner = folder, os.getpid()
        if not _STATE.registered:
            atexit.register(remove)
            _STATE.registered = True
        return folder


def remove() -> None:
    """Remove the run's folder and everything in it — only in the process that made it
    (a forked child never does)."""
    with _LOCK:
        if _STATE.path is None or _STATE.owner != os.getpid():
            return
        folder, fd = _STATE.path, _STATE.fd
        _STATE.path = _STATE.owner = _STATE.fd = None
        kept = _multiprocessing_folders(folder)
        for entry in os.listdir(folder) if kept else ():
            if entry not in kept and entry != OWNER:
                _rmtree(os.path.join(folder, entry))
        if kept:  # removed by multiprocessing as this process exits; the rest after it
            import multiprocessing.util

            multiprocessing.util.Finalize(None, _remove_last, args=(str(folder), fd),
                                          exitpriority=-101)
            return
        _remove_last(str(folder), fd)


def _multiprocessing_folders(folder: Path) -> set[str]:
    """The ``pymp-*`` folders of :mod:`multiprocessing` in ``folder`` (its fork server's
    socket): multiprocessing removes them itself when the process exits, and fails loudly
    if they are gone."""
    if "multiprocessing.util" not in sys.modules:
        return set()
    try:
        return {n for n in os.listdir(folder) if n.startswith("pymp-")}
    except OSError:
        return set()


def _rmtree(path: str) -> None:
    if os.path.isdir(path) and not os.path.islink(path):
        shutil.rmtree(path, ignore_errors=True)
    else:
        with contextlib.suppress(OSError):
            os.unlink(path)


def _remove_last(folder: str, fd: int | None) -> None:
    """Remove the folder, then release its lock (no sweep sees it unowned before)."""
    shutil.rmtree(folder, ignore_errors=True)
    if fd is not None:
        os.close(fd)


@contextlib.contextmanager
def temporaries() -> Iterator[Path]:
    """Within the block, the run's folder is the temporary folder of this process and of
    the processes it starts (restored afterwards; blocks nest)."""
    folder = run_dir()
    with _LOCK:
        saved = (tempfile.tempdir, {k: os.environ.get(k) for k in TEMP_VARIABLES})
        tempfile.tempdir = str(folder)
        for key in TEMP_VARIABLES:
            os.environ[key] = str(folder)
    try:
        yield folder
    finally:
        with _LOCK:
            tempfile.tempdir = saved[0]
            for key, value in saved[1].items():
                if value is None:
                    os.environ.pop(key, None)
                else:
                    os.environ[key] = value


class Terminated(SystemExit):
    """``SIGTERM``/``SIGHUP`` received: the command ends as an interrupted one (exit code
    128 + the signal), its ``finally`` blocks run."""


def _terminate(signum: int, frame: object) -> None:
    raise Terminated(128 + signum)


@contextlib.contextmanager
def _signals_end_the_run() -> Iterator[None]:
    """``SIGTERM`` and ``SIGHUP`` raise :class:`Terminated` within the block (only where
    their handler is the default one, and in the main thread)."""
    installed = {}
    if threading.current_thread() is threading.main_thread():
        for name in ("SIGTERM", "SIGHUP"):
            sig = getattr(signal, name, None)
            if sig is not None and signal.getsignal(sig) == signal.SIG_DFL:
                installed[sig] = signal.signal(sig, _terminate)
    try:
        yield
    finally:
        for sig, previous in installed.items():
            signal.signal(sig, previous)


@contextlib.contextmanager
def run_scope() -> Iterator[Path]:
    """A whole command's run: its own folder (:func:`temporaries`), removed when the
    block ends however it ends, ``SIGTERM``/``SIGHUP`` ending it as Ctrl+C does. A block
    inside another run (a nested command) uses that run's folder and leaves it."""
    outer = _STATE.path is not None and _STATE.owner == os.getpid()
    with _signals_end_the_run(), temporaries() as folder:
        try:
            yield folder
        finally:
            if not outer:
                remove()


def sweep(base: str | os.PathLike[str]) -> list[str]:
    """Remove the run folders in ``base`` whose owner process is gone.

    A folder is removed only when it is this user's, a real folder (not a link), named
    as a run's, and either its ``.owner`` lock can be taken (held while it is removed, so
    two sweeps never race) or it has no owner file and is older than
    :data:`UNLOCKED_GRACE_S`.

    Returns
    -------
    list of str
        The folders removed.
    """
    try:
        import fcntl
    except ImportError:  # pragma: no cover - not POSIX: nothing can be judged safely
        return []
    try:
        names = os.listdir(base)
    except OSError:
        return []
    removed = []
    uid = os.getuid() if hasattr(os, "getuid") else None
    for name in names:
        if not _NAME.fullmatch(name):
            continue
        folder = os.path.join(base, name)
        if _STATE.path is not None and folder == str(_STATE.path):
            continue
        try:
            st = os.lstat(folder)
        except OSError:
            continue
        if not stat.S_ISDIR(st.st_mode) or (uid is not None and st.st_uid != uid):
            continue
        try:
            fd = os.open(os.path.join(folder, OWNER), os.O_RDONLY | os.O_NOFOLLOW)
        except FileNotFoundError:
            if time.time() - st.st_mtime > UNLOCKED_GRACE_S:
                shutil.rmtree(folder, ignore_errors=True)
                removed.append(folder)
            continue
        except OSError:
            continue
        try:
            try:
                fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
            except OSError:
                continue  # its owner is alive
            shutil.rmtree(folder, ignore_errors=True)
            removed.append(folder)
        finally:
            os.close(fd)
    return removed


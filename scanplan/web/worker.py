"""One plan at a time, in a worker process, within a time limit.

:class:`Planner` runs the jobs of :mod:`scanplan.web.jobs` in one long-lived child process
(started by the ``forkserver`` method, which has the engine imported once, so a replacement
starts in milliseconds). A request waits for the previous plan (at most ``wait_s``), sends
its job through a pipe and waits at most ``limit_s`` for the answer; a job past its limit
is ended by killing the process, which is started again for the next request. The child
answers with the result, or the field and message of an input error (the command line's),
or a one-line failure.

Each worker has a temporary folder of its own in the run's folder
(:func:`scanplan.io.rundir.run_dir`): the jobs' folders (``scanplan-job-*``, hard links to
the uploads), WeasyPrint's fonts, openpyxl's and the GeoPackage writer's temporaries all go
there, and the folder is removed whenever the worker is stopped — a job past its limit
leaves nothing behind, not even a link that keeps a removed upload's bytes on the disk.

``inline=True`` runs the jobs in the server's own process (the tests of the API, where the
time limit is not what is tested); the lock still gives one plan at a time.
"""

from __future__ import annotations

import contextlib
import multiprocessing
import os
import shutil
import tempfile
import threading
from typing import Any

from ..errors import InputError

__all__ = ["Busy", "Failed", "Planner", "TimedOut"]

PRELOAD = ["scanplan.web.jobs", "scanplan.project.spec", "scanplan.reports.jsondoc",
           "scanplan.reports.view", "scanplan.web.mapdata"]
"""Modules the fork server imports once, before any worker is forked from it."""


class Busy(Exception):
    """Another plan held the planner for longer than the request may wait."""


class TimedOut(Exception):
    """The plan passed its time limit and was stopped."""


class Failed(Exception):
    """The job failed for another reason than its input (the message says how)."""


def _answer(job: str, args: tuple[Any, ...]) -> tuple[str, Any]:
    """Run one job; the tagged answer (``ok``, ``input`` or ``failed``)."""
    from .bodies import printable, printable_data
    from .jobs import JOBS

    try:
        return "ok", printable_data(JOBS[job](*args))
    except InputError as exc:
        return "input", (printable(exc.field), printable(exc.message))
    except MemoryError:
        return "failed", "the plan needs more memory than the machine has"
    except RecursionError:
        return "failed", "the project is nested too deeply to be planned"
    except Exception as exc:  # a bug or the environment: one line, never a traceback
        return "failed", printable(f"{type(exc).__name__}: {exc}"[:500])


def _loop(conn: Any, folder: str) -> None:  # pragma: no cover - runs in the child process
    """The worker: answer jobs until the pipe closes; every temporary file in ``folder``."""
    import warnings

    warnings.simplefilter("ignore")  # as the command line: no library warning on stderr
    tempfile.tempdir = folder
    for key in ("TMPDIR", "TMP", "TEMP", "CPL_TMPDIR"):
        os.environ[key] = folder
    while True:
        try:
            job, args = conn.recv()
        except (EOFError, OSError):
            return
        conn.send(_answer(job, args))


_SOCKET_ROOM = 50
"""Longest temporary folder [bytes] the fork server's socket is made in (a socket's path
has at most 107 bytes; multiprocessing adds some 40)."""


@contextlib.contextmanager
def _socket_folder() -> Any:
    """Where multiprocessing makes its fork server's socket (on the fork server's first
    start): the run's folder, or the system's temporary folder when the run's is too deep
    for a socket's path."""
    if len(os.fsencode(tempfile.gettempdir())) <= _SOCKET_ROOM:
        yield
        return
    saved = tempfile.tempdir
    tempfile.tempdir = None  # TMPDIR is the run's folder: the system's default instead
    try:
        base = os.path.dirname(saved or "") if saved else None
        tempfile.tempdir = base if base and len(os.fsencode(base)) <= _SOCKET_ROOM else "/tmp"
        yield
    finally:
        tempfile.tempdir = saved


class Planner:
    """Runs jobs one at a time (see the module docstring).

    Parameters
    ----------
    limit_s : float
        Longest a plan may run [s].
    report_limit_s : float
        Longest a download (reports, files) may take [s].
    wait_s : float
        Longest a request waits for the plan before it [s].
    inline : bool
        Run in this process (no time limit).
    """

    def __init__(self, *, limit_s: float = 30.0, report_limit_s: float = 120.0,
                 wait_s: float = 60.0, inline: bool = False) -> None:
        self.limit_s = limit_s
        self.report_limit_s = report_limit_s
        self.wait_s = wait_s
        self.inline = inline
        self._lock = threading.Lock()
        self._proc: Any = None
        self._conn: Any = None
        self._folder: str | None = None

    def _start(self) -> None:
        from ..io.rundir import run_dir

        ctx = multiprocessing.get_context("forkserver")
        ctx.set_forkserver_preload(PRELOAD)
        self._folder = tempfile.mkdtemp(prefix="worker-", dir=run_dir())
        parent, child = ctx.Pipe()
        proc = ctx.Process(target=_loop, args=(child, self._folder), daemon=True,
                           name="scanplan-plan")
        with _socket_folder():
            proc.start()
        child.close()
        self._proc, self._conn = proc, parent

    def _stop(self) -> None:
        if self._proc is not None:
            self._proc.kill()
            self._proc.join(5)
            self._conn.close()
        if self._folder is not None:  # the worker's temporaries, a killed job's folder too
            shutil.rmtree(self._folder, ignore_errors=True)
        self._proc = self._conn = self._folder = None

    def warm_up(self) -> None:
        """Start the worker now (the first plan then does not wait for the imports)."""
        if not self.inline:
            with self._lock:
                if self._proc is None:
                    self._start()

    def run(self, job: str, *args: Any, limit_s: float | None = None) -> Any:
        """The result of ``job(*args)``.

        Raises
        ------
        InputError
            The job's input error (the command line's field and message).
        Busy, TimedOut, Failed
            As their docstrings say.
        """
        if not self._lock.acquire(timeout=self.wait_s):
            raise Busy(f"another plan is running; tried for {self.wait_s:g} s")
        try:
            if self.inline:
                tag, value = _answer(job, args)
            else:
                tag, value = self._remote(job, args, limit_s or self.limit_s)
        finally:
            self._lock.release()
        if tag == "input":
            raise InputError(*value)
        if tag == "failed":
            raise Failed(value)
        return value

    def _remote(self, job: str, args: tuple[Any, ...], limit_s: float) -> tuple[str, Any]:
        if self._proc is None or not self._proc.is_alive():
            self._stop()
            self._start()
        try:
            self._conn.send((job, args))
            if self._conn.poll(limit_s):
                return self._conn.recv()  # type: ignore[no-any-return]
        except (EOFError, OSError):  # the worker died (killed for memory, a crash)
            self._stop()
            return "failed", "the planning process stopped unexpectedly"
        self._stop()
        raise TimedOut(f"the plan took longer than {limit_s:g} s and was stopped")

    def close(self) -> None:
        """Stop the worker."""
        with self._lock:
            self._stop()

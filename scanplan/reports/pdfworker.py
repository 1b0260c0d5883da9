"""The PDF rendered on the second core, by a process started before the plan is made.

A plan with both reports spends most of its time on the PDF: importing WeasyPrint and
matplotlib, drawing the plots, laying out the pages. :class:`PdfWorker` forks a child at the
start of a run that will write a PDF; while the parent reads the project, plans it and
draws the plots, the child imports the renderer and warms it up (templates compiled,
bundled fonts loaded). The parent hands it the result's view
(:func:`scanplan.reports.view.build_view`, pickled, the plots in it) and builds the workbook
itself while the child renders the PDF; the child returns the PDF's bytes, and the parent
writes both files in one transaction as before (nothing is written by the child). The bytes
are the same as those of an in-process render (the view carries the creation time;
``SOURCE_DATE_EPOCH`` holds for both processes).

Robustness: Linux only (``os.fork``; macOS's system libraries are not safe to use in a child
forked without exec, which is why Python's own multiprocessing spawns there); elsewhere,
under ``SCANPLAN_DEBUG=1`` (tracebacks of the renderer stay in the process that shows them)
and when ``SCANPLAN_NO_FORK=1`` is set, :meth:`PdfWorker.start` returns None and the caller
renders in-process. A child that fails for any reason (an error in the renderer, a crash, a
view that cannot be pickled) makes :meth:`PdfWorker.result` return None, and the caller
renders the PDF in-process — so a real error is raised there and reported exactly as without
the worker. The child never returns into the caller's code (``os._exit``), and every child
is reaped: by :meth:`PdfWorker.result`, or killed and reaped by :meth:`PdfWorker.stop` (also
when the run fails before the view is sent). Batches (``plan DIR --jobs N``) do not use it:
their worker processes already keep the cores busy.
"""

from __future__ import annotations

import os
import pickle
import signal
import sys
import threading
from typing import Any

__all__ = ["PdfWorker"]


def _warm() -> None:
    """What the child does while the parent plans: the imports and first-use costs."""
    import warnings

    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        from . import pdf  # WeasyPrint (the fast import), the templates' helpers

        # matplotlib is not imported here: the parent draws the plots (it has the time while
        # the child imports WeasyPrint); only a map or terrain figure, drawn in the child,
        # imports it, when the report has one
        pdf.warm_up()


def _read_all(fd: int) -> bytes:
    chunks = []
    while True:
        chunk = os.read(fd, 1 << 20)
        if not chunk:
            return b"".join(chunks)
        chunks.append(chunk)


def _write_all(fd: int, data: bytes) -> None:
    view = memoryview(data)
    while view:
        view = view[os.write(fd, view):]


def _child(requests: int, replies: int) -> None:
    """The child's whole life; never returns (``os._exit``)."""
    code = 0
    try:
        try:
            _warm()
        except Exception:  # the render below meets the same error and reports it
            pass
        data = _read_all(requests)
        if data:
            try:
                from .pdf import render_pdf

                reply: tuple[str, Any] = ("ok", render_pdf(view=pickle.loads(data)))
            except BaseException as exc:  # reported to the parent, which renders
                reply = ("error", f"{type(exc).__name__}: {exc}")
            _write_all(replies, pickle.dumps(reply, protocol=pickle.HIGHEST_PROTOCOL))
    except BaseException:  # a child must never unwind into the caller
        code = 1
    finally:
        os._exit(code)


class PdfWorker:
    """A forked child that renders one PDF (see the module docstring).

    Use :meth:`start`; then :meth:`submit` the view, :meth:`result` for the bytes, and
    :meth:`stop` in a ``finally`` (harmless after :meth:`result`).
    """

    def __init__(self, pid: int, requests: int, replies: int) -> None:
        self.pid = pid
        self._requests: int | None = requests  # parent → child (the view)
        self._replies: int | None = replies  # child → parent (the PDF)
        self.error = ""  # why the worker gave no PDF (for tests and SCANPLAN_DEBUG)
        self._sender: threading.Thread | None = None  # writes the view (submit)

    @classmethod
    def start(cls) -> PdfWorker | None:
        """Fork the child; None where that is not possible or not wanted.

        Returns
        -------
        PdfWorker or None
        """
        if (not sys.platform.startswith("linux") or not hasattr(os, "fork")
                or os.environ.get("SCANPLAN_DEBUG") or os.environ.get("SCANPLAN_NO_FORK")):
            return None
        try:
            req_r, req_w = os.pipe()
            rep_r, rep_w = os.pipe()
        except OSError:
            return None
        for stream in (sys.stdout, sys.stderr):  # nothing buffered is written twice
            try:
                stream.flush()
            except (OSError, ValueError):
                pass
        try:
            pid = os.fork()
        except OSError:
            for fd in (req_r, req_w, rep_r, rep_w):
                os.close(fd)
            return None
        if pid == 0:  # the child
            os.close(req_w)
            os.close(rep_r)
            _child(req_r, rep_w)
        os.close(req_r)
        os.close(rep_w)
        return cls(pid, req_w, rep_r)

    def submit(self, view: Any) -> bool:
        """Send the report's view to the child.

        Parameters
        ----------
        view : ReportView
            The view of the result (pickled: the child renders it).

        Returns
        -------
        bool
            False when the view could not be sent (the caller renders in-process).
        """
        if self._requests is None:
            return False
        # the plots are drawn here, while the child still imports WeasyPrint, and travel
        # with the view (drawn once: ReportView.plot keeps them)
        draw = getattr(view, "draw_plots", None)  # not a view: the child reports it
        if draw is not None:
            draw()
        try:
            data = pickle.dumps(view, protocol=pickle.HIGHEST_PROTOCOL)
        except Exception as exc:  # unpicklable
            self.error = f"{type(exc).__name__}: {exc}"
            self.stop()
            return False
        # written by a thread: the child reads only when its warm-up is done, and the
        # parent has the workbook to build meanwhile (a pipe holds 64 kB)
        fd, self._requests = self._requests, None
        self._sender = threading.Thread(target=self._send, args=(fd, data), daemon=True)
        self._sender.start()
        return True

    def _send(self, fd: int, data: bytes) -> None:
        try:
            _write_all(fd, data)
        except OSError as exc:  # the child is gone (broken pipe): result() gives None
            self.error = f"{type(exc).__name__}: {exc}"
        finally:
            os.close(fd)

    def result(self) -> bytes | None:
        """The PDF's bytes; None when the child failed (the caller renders in-process).

        Returns
        -------
        bytes or None
        """
        if self._replies is None:
            return None
        try:
            data = _read_all(self._replies)  # EOF also when the child dies
        finally:
            os.close(self._replies)
            self._replies = None
            self._reap()
        if self._sender is not None:
            self._sender.join()
        try:
            status, payload = pickle.loads(data)
        except Exception:  # a child killed before it replied
            self.error = "the PDF worker stopped without a result"
            return None
        if status != "ok":
            self.error = str(payload)
            return None
        return bytes(payload)

    def stop(self) -> None:
        """End the child if it still runs and reap it (no zombie); idempotent."""
        for attr in ("_requests", "_replies"):
            fd = getattr(self, attr)
            if fd is not None:
                os.close(fd)
                setattr(self, attr, None)
        if self.pid:
            try:
                os.kill(self.pid, signal.SIGKILL)
            except ProcessLookupError:
                pass
            self._reap()
        if self._sender is not None:  # its write ends with the child (broken pipe)
            self._sender.join()

    def _reap(self) -> None:
        if self.pid:
            try:
                os.waitpid(self.pid, 0)
            except ChildProcessError:
                pass
            self.pid = 0

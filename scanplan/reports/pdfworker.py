"""The PDF rendered on the second core, by a process started before the plan is made.

A plan with both reports spends most of its time on the PDF: importing WeasyPrint, laying
out and painting the pages. :class:`PdfWorker` forks a child at the start of a run that will
write a PDF; while the parent imports the engine, reads the project, plans it and writes the
report's HTML (:func:`scanplan.reports.pdfhtml.render_html`: the plots drawn, the
templates filled), the child imports the renderer alone (:mod:`.pdfrender`: WeasyPrint, not
the engine) and warms it up (the bundled fonts loaded). The parent hands it the HTML and
builds the workbook while the child renders the PDF; the child returns the PDF's bytes, and
the parent writes both files in one transaction as before (nothing is written by the
child). The bytes are those of an in-process render of the same HTML (:func:`scanplan.
reports.pdf.render_pdf` renders exactly that HTML).

Robustness: Linux only (``os.fork``; macOS's system libraries are not safe to use in a child
forked without exec, which is why Python's own multiprocessing spawns there); elsewhere,
under ``SCANPLAN_DEBUG=1`` (tracebacks of the renderer stay in the process that shows them)
and when ``SCANPLAN_NO_FORK=1`` is set, :meth:`PdfWorker.start` returns None and the caller
renders in-process. A child that fails for any reason (an error in the renderer, a crash)
makes :meth:`PdfWorker.result` return None, and the caller renders the PDF in-process — so a
real error is raised there and reported exactly as without the worker. The child never
returns into the caller's code (``os._exit``), and every child is reaped: by
:meth:`PdfWorker.result`, or killed and reaped by :meth:`PdfWorker.stop` (also when the run
fails before the HTML is sent). Batches (``plan DIR --jobs N``) do not use it: their worker
processes already keep the cores busy.
"""

from __future__ import annotations

import gc
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
        from . import pdfrender  # WeasyPrint (the fast import) and nothing of the engine

        pdfrender.warm_up()


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
    """The child's whole life; never returns (``os._exit``).

    Its garbage collector is off: the child renders one document and exits, taking its
    garbage with it. A collection would walk every object inherited from the parent too
    (copying their pages) and costs about a tenth of the import and render; with it off,
    a 100 km² block's report (a 560,000-character HTML) peaks 5 % higher in memory."""
    gc.disable()
    code = 0
    try:
        try:
            _warm()
        except Exception:  # the render below meets the same error and reports it
            pass
        data = _read_all(requests)
        if data:
            try:
                from .pdfrender import html_to_pdf

                reply: tuple[str, Any] = ("ok", html_to_pdf(data.decode("utf-8")))
            except BaseException as exc:  # reported to the parent, which renders
                reply = ("error", f"{type(exc).__name__}: {exc}")
            _write_all(replies, pickle.dumps(reply, protocol=pickle.HIGHEST_PROTOCOL))
    except BaseException:  # a child must never unwind into the caller
        code = 1
    finally:
        os._exit(code)


class PdfWorker:
    """A forked child that renders one PDF (see the module docstring).

    Use :meth:`start`; then :meth:`submit` the HTML, :meth:`result` for the bytes, and
    :meth:`stop` in a ``finally`` (harmless after :meth:`result`).
    """

    def __init__(self, pid: int, requests: int, replies: int) -> None:
        self.pid = pid
        self._requests: int | None = requests  # parent → child (the HTML)
        self._replies: int | None = replies  # child → parent (the PDF)
        self.error = ""  # why the worker gave no PDF (for tests and SCANPLAN_DEBUG)
        self._sender: threading.Thread | None = None  # writes the HTML (submit)

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

    def submit(self, html: str) -> bool:
        """Send the report's HTML to the child.

        Parameters
        ----------
        html : str
            The report (:func:`scanplan.reports.pdfhtml.render_html`).

        Returns
        -------
        bool
            False when it could not be sent (not a text, or the child is gone before it
            was asked: the caller renders in-process).
        """
        if self._requests is None:
            return False
        try:
            data = html.encode("utf-8")
        except (AttributeError, UnicodeError) as exc:  # not a str; lone surrogates
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

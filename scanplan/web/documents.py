"""The page's downloads, rendered while the user looks at the plan.

Rendering the documents of a town plan (the PDF with its map, the workbook with every
photo centre, the missions and GIS files of ``plan --out``) takes seconds; the page asks
for them only when the user clicks a download. :class:`Documents` renders them ahead:
after a plan is shown (``POST /api/view``) and the inputs have not changed for
:data:`QUIET_S`, it renders all three downloads (``pdf``, ``xlsx``, ``zip``) of that
project in a worker process of its own (:class:`~scanplan.web.worker.Planner`, so the page's
plans never wait for it) and keeps them by the hash of the request: the project's tables
and the upload ids it names (an upload id always names the same bytes). A download of the
same request is then served from memory; one that is being rendered waits for it; any
other is rendered as before. Only the latest request shown is rendered ahead, and only the
last :data:`KEPT` results are kept.

The bytes are the ones ``files_job`` gives for the request (the same job renders them).
"""

from __future__ import annotations

import hashlib
import json
import threading
from collections import OrderedDict
from collections.abc import Callable, Mapping
from typing import Any

from .worker import Planner

__all__ = ["KEPT", "QUIET_S", "Documents", "request_key"]

QUIET_S = 1.0
"""How long the inputs must stay unchanged before their documents are rendered ahead [s]
(a user typing or dragging a vertex is not rendered for at every step)."""
KEPT = 3
"""Requests whose documents are kept."""

Rendered = dict[str, tuple[str, bytes]]


def request_key(project: Mapping[str, Any], files: Mapping[str, str]) -> str:
    """The hash of a request: its project tables and the upload ids it names."""
    text = json.dumps({"project": project, "files": dict(files)}, sort_keys=True,
                      ensure_ascii=False, default=str)
    return hashlib.sha256(text.encode("utf-8")).hexdigest()


class Documents:
    """Downloads rendered ahead and kept (see the module docstring).

    Parameters
    ----------
    planner : Planner
        Runs the ``documents`` job (a worker of its own).
    resolve : callable
        Upload ids → the stored files' paths, as the page's routes resolve them.
    """

    def __init__(self, planner: Planner, resolve: Callable[[Mapping[str, str]], dict[str, str]]
                 ) -> None:
        self.planner = planner
        self._resolve = resolve
        self._kept: OrderedDict[str, Rendered] = OrderedDict()
        self._cond = threading.Condition()
        self._wanted: tuple[str, Any, dict[str, str]] | None = None
        self._running: set[str] = set()
        self._closed = False
        self._thread: threading.Thread | None = None

    @classmethod
    def beside(cls, planner: Planner,
               resolve: Callable[[Mapping[str, str]], dict[str, str]]) -> Documents:
        """Documents rendered by a worker of their own, with ``planner``'s limits (in this
        process when ``planner`` runs inline)."""
        return cls(Planner(limit_s=planner.limit_s, report_limit_s=planner.report_limit_s,
                           wait_s=planner.wait_s, inline=planner.inline), resolve)

    # -- rendering ahead --------------------------------------------------------------
    def ahead(self, project: Mapping[str, Any], files: Mapping[str, str]) -> None:
        """Render the downloads of this request once the inputs are quiet (the request
        the page has just shown; a later one replaces it)."""
        key = request_key(project, files)
        with self._cond:
            if self._closed or key in self._kept or key in self._running:
                return
            self._wanted = (key, dict(project), dict(files))
            if self._thread is None:
                self._thread = threading.Thread(target=self._loop, daemon=True,
                                                name="scanplan-documents")
                self._thread.start()
            self._cond.notify_all()

    def _loop(self) -> None:
        while True:
            with self._cond:
                while self._wanted is None and not self._closed:
                    self._cond.wait()
                key = self._quiet_key()
                if key is None:
                    if self._closed:
                        return
                    continue
                wanted = self._wanted
                assert wanted is not None
                self._wanted = None
                self._running.add(key)
            try:
                self._render(*wanted)
            except Exception:  # ahead of time only: the download says why
                pass
            finally:
                with self._cond:
                    self._running.discard(key)
                    self._cond.notify_all()

    def _quiet_key(self) -> str | None:
        """(Holding the lock) the key wanted once no other came for :data:`QUIET_S`; None
        when closed, taken by a download, or already kept."""
        key = None
        while not self._closed and self._wanted is not None and self._wanted[0] != key:
            key = self._wanted[0]
            self._cond.wait(QUIET_S)
        if self._closed or self._wanted is None or key in self._kept:
            self._wanted = None
            return None
        return key

    def _render(self, key: str, project: Any, files: dict[str, str]) -> Rendered:
        rendered: Rendered = self.planner.run("documents", project, self._resolve(files),
                                              limit_s=self.planner.report_limit_s)
        with self._cond:
            self._kept[key] = rendered
            self._kept.move_to_end(key)
            while len(self._kept) > KEPT:
                self._kept.popitem(last=False)
        return rendered

    # -- a download -------------------------------------------------------------------
    def get(self, project: Mapping[str, Any], files: Mapping[str, str], what: str
            ) -> tuple[str, bytes]:
        """The download ``what`` (``pdf``, ``xlsx`` or ``zip``) of this request: kept, or
        waited for while it is rendered ahead, or rendered now.

        Raises
        ------
        InputError, Busy, TimedOut, Failed
            As the ``files`` job does.
        """
        if what not in ("pdf", "xlsx", "zip"):
            from ..errors import InputError

            raise InputError("what", f'must be "pdf", "xlsx" or "zip" (got {what!r})')
        key = request_key(project, files)
        with self._cond:
            while key in self._running:
                self._cond.wait()
            got = self._kept.get(key)
            if got is not None:
                self._kept.move_to_end(key)
            else:  # rendered here, now: not again ahead
                if self._wanted is not None and self._wanted[0] == key:
                    self._wanted = None
                self._running.add(key)
        if got is None:
            try:
                got = self._render(key, dict(project), dict(files))
            finally:
                with self._cond:
                    self._running.discard(key)
                    self._cond.notify_all()
        return got[what]

    def close(self) -> None:
        """Stop rendering ahead and the worker."""
        with self._cond:
            self._closed = True
            self._cond.notify_all()
        self.planner.close()

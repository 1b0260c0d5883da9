"""The latest edit of a page only: a request a newer one of the same page has replaced is
answered without planning it.

The page plans on every change (a vertex dragged, a digit typed). Each ``POST /api/view``
it sends carries ``X-Scanplan-Edit: PAGE/N`` — a random id of the page and the number of the
edit, counting up. The views run one at a time (:class:`EditGate`); when a view's turn
comes and the same page has sent a higher number meanwhile, the view is answered 409
(superseded) at once, so a burst of edits costs one plan being finished and the newest one,
never the ones in between. The page drops an answer older than its latest request anyway;
this keeps the server from computing them.

A request without the header is planned as before (other clients of the API).
"""

from __future__ import annotations

import re
import threading
from collections import OrderedDict
from collections.abc import Callable
from typing import Any, TypeVar

__all__ = ["MAX_PAGES", "EditGate", "Superseded", "parse_edit"]

MAX_PAGES = 256
"""Most pages whose latest edit number is remembered (the oldest forgotten first)."""
_EDIT = re.compile(r"^([A-Za-z0-9_-]{8,64})/(\d{1,15})$")
T = TypeVar("T")


class Superseded(Exception):
    """A newer edit of the same page arrived while this one waited."""


def parse_edit(header: str | None) -> tuple[str, int] | None:
    """``(page id, edit number)`` of an ``X-Scanplan-Edit`` header, None when absent or
    malformed (such a request is planned as any other).

    >>> parse_edit("k3J9x0aQpL/12"), parse_edit("../1"), parse_edit(None)
    (('k3J9x0aQpL', 12), None, None)
    """
    m = _EDIT.match(header or "")
    return (m.group(1), int(m.group(2))) if m else None


class EditGate:
    """Runs views one at a time, skipping an edit a newer one of its page replaced.

    Parameters
    ----------
    wait_s : float
        Longest a view waits for the one before it [s]; past it ``busy()`` is raised.
    """

    def __init__(self, wait_s: float = 60.0) -> None:
        self.wait_s = wait_s
        self._run = threading.Lock()
        self._seen = threading.Lock()
        self._latest: OrderedDict[str, int] = OrderedDict()

    def note(self, edit: tuple[str, int] | None) -> None:
        """Remember ``edit`` as its page's latest if it is newer than the one known."""
        if edit is None:
            return
        page, number = edit
        with self._seen:
            if number >= self._latest.get(page, -1):
                self._latest[page] = number
                self._latest.move_to_end(page)
            while len(self._latest) > MAX_PAGES:
                self._latest.popitem(last=False)

    def stale(self, edit: tuple[str, int] | None) -> bool:
        """Whether a newer edit of ``edit``'s page has been noted."""
        if edit is None:
            return False
        with self._seen:
            return self._latest.get(edit[0], -1) > edit[1]

    def run(self, edit: tuple[str, int] | None, job: Callable[[], T],
            busy: Callable[[], Exception]) -> T:
        """``job()`` in turn, unless a newer edit of the page came first.

        Raises
        ------
        Superseded
            A newer edit of the same page was noted before this one's turn.
        Exception
            ``busy()`` when the view before it held the gate past :attr:`wait_s`.
        """
        self.note(edit)
        if not self._run.acquire(timeout=self.wait_s):
            raise busy()
        try:
            if self.stale(edit):
                raise Superseded
            return job()
        finally:
            self._run.release()


def superseded_answer() -> dict[str, Any]:
    """The body of the 409 answer to a superseded edit."""
    return {"detail": "a newer edit of this page replaced this request", "superseded": True}

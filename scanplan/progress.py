"""Progress of long work, told to whoever listens: the stages of one plan (the missions of
every sortie, the reports, the files written) report their steps here, and the command
line draws them (:class:`scanplan.cli.console.StageBar`); with no listener a step costs
one context-variable look-up and nothing is drawn.

A stage is opened with its number of steps and advanced step by step::

    with stage("QGroundControl missions", len(missions), "sorties") as step:
        for m in missions:
            ...
            step()

The listener (a :class:`Listener`) is set for a block of code with :func:`listening`;
it lives in a context variable, so threads and the notebook API never see another
command's bar.
"""

from __future__ import annotations

import contextlib
from collections.abc import Callable, Iterator
from contextvars import ContextVar
from typing import Protocol

__all__ = ["Listener", "listened", "listening", "stage"]


class Listener(Protocol):
    """What draws progress: told when a stage begins, each step, and when it ends."""

    def begin(self, label: str, total: int, unit: str) -> None:
        """A stage of ``total`` steps (each one ``unit``) begins."""

    def advance(self, steps: int) -> None:
        """``steps`` more steps of the current stage are done."""

    def end(self) -> None:
        """The current stage is over (all of its steps done, or stopped by an error)."""


_listener: ContextVar[Listener | None] = ContextVar("scanplan_progress", default=None)


def _nothing(steps: int = 1) -> None:
    """A step when nobody listens."""


@contextlib.contextmanager
def stage(label: str, total: int, unit: str = "") -> Iterator[Callable[..., None]]:
    """A stage of ``total`` steps; yields ``step(n=1)``, to be called as steps are done.

    Parameters
    ----------
    label : str
        What is being done, for the user ("DJI routes").
    total : int
        The number of steps.
    unit : str
        What one step is ("sorties", "files"), for the rate.

    Yields
    ------
    callable
        ``step(n=1)``: ``n`` more steps are done.
    """
    listener = _listener.get()
    if listener is None:
        yield _nothing
        return
    listener.begin(label, int(total), unit)
    try:
        yield lambda steps=1: listener.advance(int(steps))
    finally:
        listener.end()


@contextlib.contextmanager
def listening(listener: Listener | None) -> Iterator[None]:
    """Tell the stages of the code run within this block to ``listener`` (None: nobody)."""
    token = _listener.set(listener)
    try:
        yield
    finally:
        _listener.reset(token)


def listened() -> bool:
    """Whether somebody listens to the stages here (a terminal draws them)."""
    return _listener.get() is not None

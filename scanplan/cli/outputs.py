"""Which outputs ``scanplan plan --out`` writes, and what happens without a PDF engine.

``--formats`` names the outputs wanted, comma-separated (default: all of them):

- ``xlsx`` — the workbook (``spec.xlsx``);
- ``pdf`` — the PDF specification (``spec.pdf``);
- ``missions`` — the flight missions (``mission.plan`` for QGroundControl,
  ``mission.waypoints`` for Mission Planner, one pair per sortie);
- ``gis`` — the flight and photo centres for a GIS (``flight.kml``, ``flight.geojson``,
  ``photos.csv``; film: ``film-flight.*``, ``film-frames.csv``).

**Without a PDF engine.** The PDF is drawn by WeasyPrint, which needs the system's Pango
library. When WeasyPrint cannot load, the other outputs are still written and a warning
says what is missing and how to install it. Exit code: 0 when the PDF was only part of
the default set; 1 (a runtime failure) after the others are written when it was asked for
by name (``--formats pdf``, ``--pdf FILE``).
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import click

from ..errors import InputError

__all__ = ["FORMATS", "parse_formats", "pdf_failure_exit", "pdf_missing", "pdf_renderer",
           "reset", "selected", "warn_stale"]

FORMATS = ("xlsx", "pdf", "missions", "gis")
"""The outputs ``--formats`` can name, in the order of the files written
(:data:`scanplan.reports.documents.OUTPUTS`; a test keeps the two alike: this module does
not import the reports, so ``scanplan --help`` stays light)."""

_state: dict[str, Any] = {"missing": None, "warned": False}


def reset() -> None:
    """Forget an earlier run's PDF engine failure (each command run starts afresh)."""
    _state.update(missing=None, warned=False)


def parse_formats(ctx: click.Context | None, param: click.Parameter | None,
                  value: str | None) -> tuple[str, ...] | None:
    """A click callback: ``"xlsx,missions"`` → ``("xlsx", "missions")`` (None: all).

    >>> parse_formats(None, None, "gis, XLSX")
    ('xlsx', 'gis')
    """
    if value is None:
        return None
    names = [v.strip().lower() for v in value.split(",") if v.strip()]
    bad = [v for v in names if v not in FORMATS]
    if bad or not names:
        raise InputError("--formats", f"must name some of {', '.join(FORMATS)}, "
                         f"comma-separated (got {value!r})")
    return tuple(f for f in FORMATS if f in names)


def selected(formats: tuple[str, ...] | None, name: str) -> bool:
    """Whether output ``name`` is among the chosen ``formats`` (None: all are)."""
    return formats is None or name in formats


def pdf_missing() -> str | None:
    """Why the PDF engine could not load in this run (None: it loaded, or was not tried)."""
    return _state["missing"]


def pdf_renderer(explicit: bool = False) -> Callable[..., bytes] | None:
    """:func:`scanplan.reports.pdf.render_pdf`, or None when its engine cannot load — then
    a warning on stderr (once) says what is missing and how to install it
    (:func:`scanplan.reports.documents.load_pdf_engine`).

    Parameters
    ----------
    explicit : bool
        The PDF was asked for by name: the warning says the command will fail at the end.
    """
    from ..errors import PdfEngineError
    from ..reports.documents import load_pdf_engine

    try:
        return load_pdf_engine()
    except PdfEngineError as exc:
        _state["missing"] = exc.reason
        if not _state["warned"]:
            _state["warned"] = True
            then = ("the other files are written, then the command fails" if explicit
                    else "the other files are written")
            click.echo(f"warning: {exc.message}; {then}", err=True)
        return None


def warn_stale(paths: list[str]) -> None:
    """Warn of report files left from an earlier plan that this run could not replace."""
    import os

    for path in paths:
        if os.path.exists(path):
            click.echo(f"warning: {path} is from an earlier plan and does not match this "
                       "one", err=True)


def pdf_failure_exit(explicit: bool) -> None:
    """At the end of a command: fail (exit 1) when a PDF asked for by name could not be
    made.

    Raises
    ------
    scanplan.cli.errors.Failed
    """
    from .errors import Failed

    if explicit and _state["missing"] is not None:
        raise Failed(["the PDF was not written: its engine could not load (see the warning "
                      "above)"])

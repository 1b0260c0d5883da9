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

import sys
from collections.abc import Callable
from typing import Any

import click

from ..errors import InputError

__all__ = ["FORMATS", "PDF_HELP", "chosen_exports", "parse_formats",
           "pdf_failure_exit", "pdf_missing", "pdf_renderer", "reset", "selected",
           "warn_stale"]

FORMATS = ("xlsx", "pdf", "missions", "gis")
"""The outputs ``--formats`` can name, in the order of the files written."""

PDF_HELP = {
    "linux": "install Pango (Debian/Ubuntu: apt-get install libpango-1.0-0 "
             "libpangoft2-1.0-0; Fedora: dnf install pango)",
    "darwin": "install Pango (brew install pango)",
    "win32": "install the GTK3 runtime (which brings Pango), as WeasyPrint's installation "
             "guide describes",
}
"""How to get the PDF engine's system library, by platform."""

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


def chosen_exports(exports: dict[str, tuple[Any, bytes]],
                   formats: tuple[str, ...] | None) -> dict[str, tuple[Any, bytes]]:
    """The exported files (path → (format, bytes)) of the chosen outputs: those whose
    format (:data:`scanplan.geo.export.formats.FORMATS`) belongs to one of ``formats``."""
    if formats is None:
        return exports
    return {path: item for path, item in exports.items() if item[0].output in formats}


def pdf_missing() -> str | None:
    """Why the PDF engine could not load in this run (None: it loaded, or was not tried)."""
    return _state["missing"]


def _load_engine() -> Callable[..., bytes]:
    from ..reports.pdf import render_pdf

    return render_pdf


def pdf_renderer(explicit: bool = False) -> Callable[..., bytes] | None:
    """:func:`scanplan.reports.pdf.render_pdf`, or None when its engine cannot load — then
    a warning on stderr (once) says what is missing and how to install it.

    Parameters
    ----------
    explicit : bool
        The PDF was asked for by name: the warning says the command will fail at the end.
    """
    try:
        return _load_engine()
    except (OSError, ImportError) as exc:  # cffi's dlopen of Pango, or no WeasyPrint
        text = str(exc)  # the library's own first line: what could not be loaded
        reason = text.splitlines()[0] if text.strip() else type(exc).__name__
        _state["missing"] = reason
        if not _state["warned"]:
            _state["warned"] = True
            how = PDF_HELP.get(sys.platform, PDF_HELP["linux"])
            then = ("the other files are written, then the command fails" if explicit
                    else "the other files are written")
            click.echo(f"warning: no PDF written: the PDF engine (WeasyPrint) could not "
                       f"load ({reason}); {how}; {then}", err=True)
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

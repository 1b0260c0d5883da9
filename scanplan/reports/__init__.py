"""Reports for approval: shared pieces of the Excel and PDF writers.

Reports *render* result objects (:class:`scanplan.rules.film.ScanPlan`,
:class:`scanplan.rules.uav.UavPlan` and their norm set); they never recompute a number.
What they show is built once per result by :func:`scanplan.reports.view.build_view` (the
sections, the labels and the number formatter of the report's language, the plots) and
laid out by the renderers: :mod:`.text`, :mod:`.jsondoc`, :mod:`.excel`, :mod:`.pdf`.
Writing is atomic: the whole file is rendered to memory, written to a temporary file
beside the target and renamed over it, so a crash never leaves a half-written report and
never destroys the previous one. Several files that belong together (spec.xlsx and
spec.pdf) are written as one transaction (:func:`scanplan.io.atomic.write_atomic_many`):
after any failure all of the previous files are as they were. With
``SOURCE_DATE_EPOCH`` set, output is reproducible.
"""

from __future__ import annotations

import datetime as _dt
import os
from pathlib import Path
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    from ..io.atomic import write_atomic, write_atomic_many
    from ..project.file import ReportMeta

__all__ = ["ReportMeta", "report_datetime", "templates_dir", "write_atomic",
           "write_atomic_many"]

_LAZY = {"write_atomic": "..io.atomic", "write_atomic_many": "..io.atomic",  # the writers
         "ReportMeta": "..project.file"}  # project metadata: it lives with the project file
"""Names re-exported from below, imported when first asked for: the PDF worker's child
(:mod:`.pdfworker`), forked once this package is imported, needs only
:func:`templates_dir`, so the fork does not wait for the file writers and the project
file's reader."""


def __getattr__(name: str) -> Any:
    if name in _LAZY:
        import importlib

        value = getattr(importlib.import_module(_LAZY[name], __name__), name)
        globals()[name] = value
        return value
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


def report_datetime() -> _dt.datetime:
    """Now (UTC), or ``SOURCE_DATE_EPOCH`` when set (reproducible builds)."""
    epoch = os.environ.get("SOURCE_DATE_EPOCH")
    if epoch and epoch.strip().isdigit():
        return _dt.datetime.fromtimestamp(int(epoch), tz=_dt.UTC)
    return _dt.datetime.now(tz=_dt.UTC).replace(microsecond=0)


def templates_dir() -> Path:
    """Bundled templates and fonts (``templates/`` in a checkout, packaged in a wheel)."""
    here = Path(__file__).resolve().parent.parent
    for candidate in (here / "_data" / "templates", here.parent / "templates"):
        if (candidate / "fonts").is_dir():
            return candidate
    raise RuntimeError(f"scanplan's bundled templates are missing (looked in "
                       f"{here / '_data' / 'templates'} and {here.parent / 'templates'}); "
                       "reinstall scanplan")

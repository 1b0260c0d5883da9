"""The batch summary files: ``summary.csv`` and ``summary.xlsx`` (one row per project).

Both are rendered to bytes from a :class:`pandas.DataFrame` (the batch summary of
:mod:`scanplan.api`); with ``SOURCE_DATE_EPOCH`` set the bytes depend on the rows only.
Text cells are written as text, never as formulas.
"""

from __future__ import annotations

import datetime as _dt
import io
import math
import zipfile
from typing import Any

from .._version import __version__
from . import report_datetime

__all__ = ["summary_csv", "summary_xlsx"]


# The digits a summary shows of each measured column, as the specification prints them
# (a scan pixel to 0.1 µm, a height to 0.1 m, a GSD to 0.01 cm): a summary is read and
# compared by people, and 213.94285714285706 m says nothing 213.9 m does not.
DIGITS = {"film_scan_pixel_um": 1, "film_scanner_pixel_um": 1, "film_scanned_gigabytes": 2,
          "uav_recommended_height_m": 1, "uav_max_planned_height_m": 1, "uav_gsd_cm": 2}


def _rounded(frame: Any) -> Any:
    """``frame`` with its measured columns rounded to :data:`DIGITS`."""
    cols = {c: d for c, d in DIGITS.items() if c in frame.columns}
    return frame.round(cols) if cols else frame


def summary_csv(frame: Any) -> bytes:
    """The summary as UTF-8 CSV (with a byte-order mark, so Excel reads the Cyrillic),
    measured columns rounded as the specification prints them (:data:`DIGITS`); a text
    cell a spreadsheet would run as a formula (a project named ``=cmd|…``) starts with
    ``'`` (:func:`scanplan.io.files.csv_safe`)."""
    from ..io.files import csv_safe_frame

    return (csv_safe_frame(_rounded(frame)).to_csv(index=False, lineterminator="\n")
            .encode("utf-8-sig"))


def _cell(value: Any) -> Any:
    import pandas as pd

    if value is None or value is pd.NA or (isinstance(value, float)
                                           and not math.isfinite(value)):
        return None
    if hasattr(value, "item"):  # a numpy scalar
        value = value.item()
    return value


def summary_xlsx(frame: Any) -> bytes:
    """The summary as one worksheet (header row frozen, text cells as text)."""
    from openpyxl import Workbook
    from openpyxl.styles import Font
    from openpyxl.writer.excel import ExcelWriter

    from .excel import _repack, put_text

    when = report_datetime()
    wb = Workbook()
    ws = wb.active
    ws.title = "summary"
    for col, name in enumerate(frame.columns, start=1):
        put_text(ws, 1, col, name).font = Font(bold=True)
    for row, values in enumerate(_rounded(frame).itertuples(index=False), start=2):
        for col, value in enumerate(values, start=1):
            value = _cell(value)
            if isinstance(value, str):
                put_text(ws, row, col, value)
            elif value is not None:
                ws.cell(row=row, column=col, value=value)
    ws.freeze_panes = "A2"
    naive = when.astimezone(_dt.UTC).replace(tzinfo=None)
    wb.properties.created = wb.properties.modified = naive
    wb.properties.creator = f"scanplan {__version__}"
    wb.properties.lastModifiedBy = None
    raw = io.BytesIO()
    archive = zipfile.ZipFile(raw, "w", zipfile.ZIP_DEFLATED, allowZip64=True)
    ExcelWriter(wb, archive).save()
    return _repack(raw.getvalue(), when)

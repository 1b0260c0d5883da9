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


def summary_csv(frame: Any) -> bytes:
    """The summary as UTF-8 CSV (with a byte-order mark, so Excel reads the Cyrillic); a
    text cell a spreadsheet would run as a formula (a project named ``=cmd|…``) starts
    with ``'`` (:func:`scanplan.safeio.csv_safe`)."""
    from ..safeio import csv_safe_frame

    return csv_safe_frame(frame).to_csv(index=False, lineterminator="\n").encode("utf-8-sig")


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
    for row, values in enumerate(frame.itertuples(index=False), start=2):
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

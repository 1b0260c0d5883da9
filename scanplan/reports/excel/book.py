"""The report workbook being filled sheet by sheet: page setup, label | value rows, sections,
the report's formatter (``book.f``: words and numbers), the deterministic save."""

from __future__ import annotations

import datetime as _dt
import io
import zipfile
from collections.abc import Sequence
from typing import TYPE_CHECKING

from openpyxl import Workbook
from openpyxl.worksheet.worksheet import Worksheet
from openpyxl.writer.excel import ExcelWriter

from ..._version import __version__

if TYPE_CHECKING:
    from ..view import ReportView

from .cells import (
    _SECTION,
    MISSING,
    _clean_text,
    _fit_rows,
    _repack,
    _widths,
    localise_scales,
    put_num,
    put_text,
)


class Book:
    """One report workbook being filled sheet by sheet."""

    def __init__(self, view: ReportView) -> None:
        self.view = view
        self.meta = view.meta
        self.loc = view.locale
        self.platform = view.platform  # "aircraft": the sheets name an aerial survey
        # the one formatter of the report's language, with this workbook's reference list
        # (numbered as the PDF of the same result numbers the works)
        self.f = view.document_fmt()
        self.when = view.when
        self.wb = Workbook()
        self._first = True
        self.title_text = ""

    def sheet(self, key: str, *, landscape: bool, widths: Sequence[float],
              header_rows: int = 1) -> Worksheet:
        """A new sheet with A4 page setup, print titles and a frozen header."""
        if self._first:
            ws = self.wb.active
            ws.title = self.f(key)
            self._first = False
        else:
            ws = self.wb.create_sheet(self.f(key))
        ws.page_setup.paperSize = ws.PAPERSIZE_A4
        ws.page_setup.orientation = "landscape" if landscape else "portrait"
        ws.page_setup.fitToWidth = 1
        ws.page_setup.fitToHeight = 0
        ws.sheet_properties.pageSetUpPr.fitToPage = True
        ws.page_margins.left = ws.page_margins.right = 0.5
        ws.page_margins.top = ws.page_margins.bottom = 0.6
        ws.print_title_rows = f"1:{header_rows}"
        ws.freeze_panes = f"A{header_rows + 1}"
        sep = " / " if self.loc == "ru" else " "
        ws.oddFooter.center.text = f"{self.f('sheet')} &P{sep}{self.f('sheets_of')} &N"
        ws.oddFooter.right.text = "&A"
        _widths(ws, widths)
        return ws

    def kv(self, ws: Worksheet, row: int, label: str, value: object, fmt: str | None = None,
           *, wrap: bool = False) -> int:
        """One ``label | value`` row; returns the next row."""
        put_text(ws, row, 1, label, wrap=True)
        if isinstance(value, bool):
            put_text(ws, row, 2, self.f.yes_no(value))
        elif fmt is not None:
            put_num(ws, row, 2, value, fmt)
        elif value is None or value == "":
            put_text(ws, row, 2, MISSING)
        else:
            put_text(ws, row, 2, value, wrap=wrap)
        return row + 1

    def _wide_kv(self, ws: Worksheet, row: int, label: str, text: str) -> int:
        """A ``label | long text`` row whose text spans the sheet's columns B…J (merged),
        so a paragraph reads as a paragraph, not a narrow column."""
        put_text(ws, row, 1, label, wrap=True)
        put_text(ws, row, 2, text, wrap=True)
        ws.merge_cells(start_row=row, start_column=2, end_row=row, end_column=10)
        return row + 1

    def kv_list(self, ws: Worksheet, row: int, label: str, values: Sequence[float],
                fmt: str) -> int:
        """``label | v1 | v2 | ...`` (several numbers, each in its own cell)."""
        put_text(ws, row, 1, label, wrap=True)
        if not values:
            put_text(ws, row, 2, MISSING)
        for i, v in enumerate(values):
            put_num(ws, row, 2 + i, v, fmt)
        return row + 1

    def section(self, ws: Worksheet, row: int, text: str) -> int:
        cell = put_text(ws, row, 1, text)
        cell.font = _SECTION
        return row + 1

    def to_bytes(self) -> bytes:
        """Save to memory with fixed timestamps; re-pack the zip deterministically."""
        naive = self.when.astimezone(_dt.UTC).replace(tzinfo=None)
        props = self.wb.properties
        props.created = naive
        props.modified = naive
        props.creator = f"scanplan {__version__}"
        props.lastModifiedBy = None
        props.language = "ru-RU" if self.loc == "ru" else "en-US"
        props.title = _clean_text(self.title_text)[:255]
        if self.meta.project:
            props.subject = _clean_text(self.meta.project)[:255]
        for ws in self.wb.worksheets:
            _fit_rows(ws)
            localise_scales(ws, self.loc)
        raw = io.BytesIO()
        # ExcelWriter, not Workbook.save: save() stamps `modified` with the current time.
        archive = zipfile.ZipFile(raw, "w", zipfile.ZIP_DEFLATED, allowZip64=True)
        ExcelWriter(self.wb, archive).save()
        return _repack(raw.getvalue(), self.when)

"""Cells of the report workbook: invariant number formats, styles, safe text and number cells,
the deterministic zip."""

from __future__ import annotations

import datetime as _dt
import io
import math
import re
import zipfile
from collections.abc import Iterable, Sequence
from typing import Any

from openpyxl.cell.cell import ILLEGAL_CHARACTERS_RE
from openpyxl.styles import Alignment, Font, PatternFill
from openpyxl.utils import get_column_letter
from openpyxl.worksheet.worksheet import Worksheet

# Invariant number formats (Excel shows them with the user's decimal separator).
SCALE = '"1:"0'
# A scale as a Russian document writes it (scanplan.i18n.messages.scale_text): the denominator
# grouped from five digits (1:25 000, with the user's separator), four digits whole (1:2000).
SCALE_RU = '[>=10000]"1:"#,##0;"1:"0'
INT = "#,##0"
F1 = "0.0"
F2 = "0.00"
F3 = "0.000"
F4 = "0.0000"
PCT = "0.0"
UM = "0.00"
MB = "#,##0.0"
M_LARGE = "#,##0.0"

MISSING = "—"


def number_format(digits: int) -> str:
    """The cell format of a number shown with ``digits`` decimals: thousands grouped (one
    rule with the documents' text: ``2,093.5``, shown by a Russian Excel as ``2 093,5``).

    >>> number_format(0), number_format(2)
    ('#,##0', '#,##0.00')
    """
    return "#,##0" + ("." + "0" * digits if digits > 0 else "")
_ZIP_EPOCH = (1980, 1, 1, 0, 0, 0)
_MAX_CELL_TEXT = 32_767

_BOLD = Font(bold=True)
_TITLE = Font(bold=True, size=14)
_SECTION = Font(bold=True, size=12)
_HEADER_FILL = PatternFill("solid", fgColor="DDEBF7")
_BINDING_FILL = PatternFill("solid", fgColor="FFE699")
_WARNING_FILL = PatternFill("solid", fgColor="FCE4D6")
_WRAP = Alignment(wrap_text=True, vertical="top")
_FORMULA_START = re.compile(r"^[=+\-@\t\r]")


def _clean_text(value: object) -> str:
    """User or engine text as a string Excel accepts (no control characters, max length)."""
    text = ILLEGAL_CHARACTERS_RE.sub("", str(value))
    return text[:_MAX_CELL_TEXT]


def put_text(ws: Worksheet, row: int, col: int, value: object, *, bold: bool = False,
             wrap: bool = False) -> Any:
    """Write ``value`` as a string cell — never a formula, whatever it starts with."""
    text = _clean_text(value)
    cell = ws.cell(row=row, column=col)
    cell.value = text
    cell.data_type = "s"  # openpyxl would turn "=..." into a formula
    if _FORMULA_START.match(text):
        cell.quotePrefix = True  # and Excel keeps it text when the cell is edited
    if bold:
        cell.font = _BOLD
    if wrap:
        cell.alignment = _WRAP
    return cell


def _finite(value: object) -> float | None:
    if value is None or isinstance(value, bool):
        return None
    try:
        v = float(value)  # type: ignore[arg-type]
    except (TypeError, ValueError):
        return None
    return v if math.isfinite(v) else None


def put_num(ws: Worksheet, row: int, col: int, value: object, fmt: str, *,
            missing: str | None = MISSING) -> Any:
    """Write a number with an invariant number format (missing/non-finite → ``missing``)."""
    v = _finite(value)
    if v is None:
        if missing is None:
            return ws.cell(row=row, column=col)
        return put_text(ws, row, col, missing)
    cell = ws.cell(row=row, column=col)
    cell.value = int(v) if fmt in (SCALE, INT) and v.is_integer() else v
    cell.number_format = fmt
    return cell


def _mark(cells: Iterable[Any]) -> None:
    for cell in cells:
        cell.font = _BOLD
        cell.fill = _BINDING_FILL


def _header(ws: Worksheet, row: int, labels: Sequence[str], col: int = 1) -> None:
    for i, text in enumerate(labels):
        cell = put_text(ws, row, col + i, text, bold=True, wrap=True)
        cell.fill = _HEADER_FILL


def _widths(ws: Worksheet, widths: Sequence[float]) -> None:
    for i, w in enumerate(widths, start=1):
        ws.column_dimensions[get_column_letter(i)].width = w


def _fit_rows(ws: Worksheet) -> None:
    """Row heights for wrapped text, so no wrapped cell runs over the next row in programs
    that do not measure text when opening a file (LibreOffice keeps stored heights)."""
    width = {c: (ws.column_dimensions[get_column_letter(c)].width or 8.43)
             for c in range(1, ws.max_column + 1)}
    merged = {(r.min_row, r.min_col): sum(width.get(c, 8.43)
                                          for c in range(r.min_col, r.max_col + 1))
              for r in ws.merged_cells.ranges if r.min_row == r.max_row}
    for row in ws.iter_rows():
        lines = 1
        for cell in row:
            if not isinstance(cell.value, str) or not cell.alignment.wrap_text:
                continue
            w = merged.get((cell.row, cell.column), width.get(cell.column, 8.43))
            chars = max(w * (0.9 if cell.font.bold else 1.05) - 1, 4)
            n = sum(max(1, math.ceil(len(part) / chars)) for part in cell.value.split("\n"))
            lines = max(lines, n)
        if lines > 1:
            ws.row_dimensions[row[0].row].height = 15 * lines + 2
            for cell in row:  # numbers beside a paragraph read from its first line
                if cell.value is not None and cell.alignment.vertical != "top":
                    al = cell.alignment
                    cell.alignment = Alignment(horizontal=al.horizontal, vertical="top",
                                               wrap_text=al.wrap_text)


def localise_scales(ws: Worksheet, locale: str) -> None:
    """In a Russian workbook write every scale cell (format :data:`SCALE`) as the Russian
    text does, 1:25 000 and 1:2000 (:data:`SCALE_RU`); English keeps 1:25000."""
    if locale != "ru":
        return
    for row in ws.iter_rows():
        for cell in row:
            if cell.number_format == SCALE:
                cell.number_format = SCALE_RU


def _repack(raw: bytes, when: _dt.datetime) -> bytes:
    """Rewrite the zip with one fixed timestamp, compression and permissions per member.

    openpyxl stamps every member with the current time; the re-pack keeps the member order
    and contents and makes the bytes depend on ``when`` only.
    """
    utc = when.astimezone(_dt.UTC)
    stamp = max((utc.year, utc.month, utc.day, utc.hour, utc.minute, utc.second), _ZIP_EPOCH)
    out = io.BytesIO()
    with zipfile.ZipFile(io.BytesIO(raw)) as src, \
            zipfile.ZipFile(out, "w", zipfile.ZIP_DEFLATED) as dst:
        for info in src.infolist():
            member = zipfile.ZipInfo(info.filename, date_time=stamp)
            member.compress_type = zipfile.ZIP_DEFLATED
            member.create_system = 3
            member.external_attr = 0o644 << 16
            dst.writestr(member, src.read(info.filename), compresslevel=6)
    return out.getvalue()

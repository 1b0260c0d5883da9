"""The survey design sheet of the workbook and the norm set's GSD table, laid out from
:func:`scanplan.reports.design.design_view` and the norm set."""

from __future__ import annotations

from typing import Any

from openpyxl.styles import Alignment

from ...i18n.messages import Message, localize
from ..design import Figure, design_view
from ..wording import with_status
from .cells import put_num, put_text

__all__ = ["write_design_sheet", "write_gsd_limits"]


def write_design_sheet(book: Any, spec: Any) -> None:
    """The survey design sheet of the workbook (after the Summary), from :func:`design_view`.

    Parameters
    ----------
    book : scanplan.reports.excel.Book
        The workbook being built (its sheet factory, labels and bibliography).
    spec : PlanResult
        The specification.
    """
    top_left = Alignment(horizontal="left", vertical="top")
    view = design_view(spec, book.loc, book.bib.cite)
    if view is None:
        return
    ws = book.sheet("xlsx_sheet_design", landscape=True, widths=(46, 60, 50))
    for col, key in enumerate(("design_quantity", "design_value", "design_norm"), start=1):
        put_text(ws, 1, col, book.t(key), bold=True)
    row = 2
    for label, value, norm in view.rows:
        put_text(ws, row, 1, label, wrap=True)
        if isinstance(value, Figure):  # a number cell with its number format
            put_num(ws, row, 2, value.value, value.number_format).alignment = top_left
        else:
            put_text(ws, row, 2, value, wrap=True)
        put_text(ws, row, 3, norm, wrap=True)
        row += 1
    if view.notes:
        row += 1
        put_text(ws, row, 1, book.t("design_notes"), bold=True)
        for note in view.notes:
            row += 1
            put_text(ws, row, 1, note, wrap=True)
            ws.merge_cells(start_row=row, start_column=1, end_row=row, end_column=3)


def write_gsd_limits(book: Any, ws: Any, row: int, ns: Any) -> int:
    """The norm set's table of the largest GSD per plan scale on the workbook's norms sheet
    (nothing when the set has none); returns the next row."""
    if not ns.gsd_limits:
        return row
    row = book.section(ws, row + 1, book.t("xlsx_gsd_limits"))
    for col, key in enumerate(("map_scale", "xlsx_gsd_area", "xlsx_max_gsd_cm", "source"),
                              start=1):
        put_text(ws, row, col, book.t(key), bold=True)
    row += 1
    for g in ns.gsd_limits:
        put_num(ws, row, 1, g.map_scale, '"1:"0')
        put_text(ws, row, 2, localize(Message(f"gsd_area.{g.area}"), book.loc), wrap=True)
        put_num(ws, row, 3, g.max_gsd_cm, "0.##")
        put_text(ws, row, 4, with_status(book.bib.cite(g.source), g.status, book.loc),
                 wrap=True)
        row += 1
    return row

"""The survey design sheet of the workbook and the norm set's GSD table, laid out from
the view's ``design`` table (:mod:`scanplan.reports.views.design`) and the norm set."""

from __future__ import annotations

from typing import Any

from openpyxl.styles import Alignment

from ...i18n.messages import Message, localize
from ..views.table import Num
from ..wording import sentence, with_status
from .cells import put_num, put_text

__all__ = ["write_design_sheet", "write_gsd_limits"]


def write_design_sheet(book: Any, spec: Any) -> None:
    """The survey design sheet of the workbook (after the Summary): the view's ``design``
    and ``design_notes`` tables; a value that is one number is a number cell.

    Parameters
    ----------
    book : scanplan.reports.excel.Book
        The workbook being built (its sheet factory and formatter).
    spec : PlanResult
        The specification.
    """
    top_left = Alignment(horizontal="left", vertical="top")
    tables = book.view.tables
    if not tables.has("design"):
        return
    f = book.f
    ws = book.sheet("sheet_design", landscape=True, widths=(46, 60, 50))
    for col, key in enumerate(("item", "proposed_value", "norm_met"), start=1):
        put_text(ws, 1, col, f(key), bold=True)
    row = 2
    for r in tables["design"].rows:
        value, norm = r.values
        put_text(ws, row, 1, f.row_label(r), wrap=True)
        if isinstance(value, Num) and value.value is not None:  # a number cell
            fmt = "#,##0" + ("." + "0" * value.digits if value.digits else "")
            put_num(ws, row, 2, round(float(value.value), value.digits or 0),
                    fmt).alignment = top_left
        else:
            put_text(ws, row, 2, f.show(value), wrap=True)
        put_text(ws, row, 3, f.show(norm) if norm else "", wrap=True)
        row += 1
    notes = tables["design_notes"].rows
    if notes:
        row += 1
        put_text(ws, row, 1, f("survey_design_notes"), bold=True)
        for r in notes:
            row += 1
            put_text(ws, row, 1, sentence(f.show(r.value)), wrap=True)
            ws.merge_cells(start_row=row, start_column=1, end_row=row, end_column=3)


def write_gsd_limits(book: Any, ws: Any, row: int, ns: Any) -> int:
    """The norm set's table of the largest GSD per plan scale on the workbook's norms sheet
    (nothing when the set has none); returns the next row."""
    if not ns.gsd_limits:
        return row
    row = book.section(ws, row + 1, book.f("gsd_limits"))
    for col, key in enumerate(("map_scale", "gsd_territory", "max_gsd_cm", "source"),
                              start=1):
        put_text(ws, row, col, book.f(key), bold=True)
    row += 1
    for g in ns.gsd_limits:
        put_num(ws, row, 1, g.map_scale, '"1:"0')
        put_text(ws, row, 2, localize(Message(f"gsd_area.{g.area}"), book.loc), wrap=True)
        put_num(ws, row, 3, g.max_gsd_cm, "0.##")
        put_text(ws, row, 4, with_status(book.f.cite(g.source), g.status, book.loc),
                 wrap=True)
        row += 1
    return row

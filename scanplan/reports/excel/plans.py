"""The workbook's sheet of the plans compared for a UAV block (the ``plans`` table,
:mod:`scanplan.reports.views.plans`): the figures as numbers, the words of
:mod:`scanplan.reports.planwords` through the workbook's formatter."""

from __future__ import annotations

from typing import Any

from ..planwords import plan_cells, plan_head
from .cells import put_num, put_text

__all__ = ["write_plans_sheet"]

#: Number formats of the numeric columns (by the table's column index).
_FORMATS = {1: "0.0", 2: "0", 3: "#,##0", 4: "#,##0", 5: "#,##0", 6: "0"}


def write_plans_sheet(book: Any, view: Any) -> None:
    """The plans compared: one row each (the recommended one first), the GSD flown as
    two columns, then the binding constraint and what it misses; the note under it.

    Parameters
    ----------
    book : scanplan.reports.excel.Book
        The workbook being built.
    view : ReportView
        The result's view (its ``plans`` table).
    """
    if not view.tables.has("plans") or not view.tables["plans"].rows:
        return
    tbl = view.tables["plans"]
    f = book.f
    ws = book.sheet("plans_title", landscape=True,
                    widths=(34, 10, 16, 10, 10, 10, 12, 9, 10, 10, 10, 70))
    head = plan_head(f)
    gsd = head[7]
    titles = [head[0], head[1], "", *head[2:7], f"{gsd} ↓", f"{gsd} ↑", *head[8:]]
    for col, text in enumerate(titles, start=1):
        put_text(ws, 1, col, text, bold=True, wrap=True)
    row = 2
    for r in tbl.rows:
        words = plan_cells(r, f)
        _, deg, height, photos, gb, minutes, sorties, gsd_pair, binding, _ = r.values
        put_text(ws, row, 1, words[0], bold="recommended" in r.flags)
        put_num(ws, row, 2, deg, _FORMATS[1])
        put_text(ws, row, 3, f(f"plans_dir_{r.key}"))
        for col, value, fmt in ((4, height, _FORMATS[2]), (5, photos, _FORMATS[3]),
                                (6, gb, _FORMATS[4]), (7, minutes, _FORMATS[5]),
                                (8, sorties, _FORMATS[6])):
            put_num(ws, row, col, value, fmt)
        lo, hi = gsd_pair if gsd_pair is not None else (None, None)
        put_num(ws, row, 9, lo, "0.00")
        put_num(ws, row, 10, hi, "0.00")
        put_text(ws, row, 11, binding or "")
        put_text(ws, row, 12, words[-1], wrap=True)
        row += 1
    choice = getattr(view.spec.uav, "choice", None)
    notes = ([f.message(choice)] if choice is not None else []) + [f("plans_note")]
    for note in notes:
        row += 1
        put_text(ws, row, 1, note, wrap=True)
        ws.merge_cells(start_row=row, start_column=1, end_row=row, end_column=12)

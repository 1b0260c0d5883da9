"""The workbook's Control sheet (``[control]``): the counts, the figures and the error
budget at best as numbers, the control's precision against the target, and the layout rules
with their statuses and sources — the rows of :mod:`scanplan.reports.views.control`, worded
by :mod:`scanplan.reports.controlwords` as in the PDF."""

from __future__ import annotations

from typing import Any

from ..controlwords import check_rows, rule_rows
from .cells import put_num, put_text

__all__ = ["control_sheet"]


def _number_format(digits: int | None) -> str:
    return "#,##0" if not digits else "0." + "0" * digits


def control_sheet(book: Any, spec: Any) -> None:
    """The Control sheet, after the survey design (nothing without ``[control]``).

    Parameters
    ----------
    book : scanplan.reports.excel.Book
        The workbook being built.
    spec : PlanResult
        The specification.
    """
    if spec is None or getattr(spec, "control", None) is None:
        return
    tables = book.view.tables
    ws = book.sheet("control_sheet", landscape=True, widths=(60, 16, 14, 14, 60))
    put_text(ws, 1, 1, book.t("control_points"), bold=True)
    row = 2
    for r in tables["control"].rows:
        put_text(ws, row, 1, book.t(r.key), wrap=True)
        if r.key == "control_mode":
            put_text(ws, row, 2, book.t(r.fields["mode"]))
        else:
            put_num(ws, row, 2, r.value, _number_format(r.digits))
            if "rule" in r.fields:
                put_text(ws, row, 3, book.t(r.fields["rule"]))
            if r.key in ("control_budget_z", "control_budget_h"):
                put_text(ws, row, 3, book.t("control_at_best"))
        row += 1
    put_text(ws, row, 1, book.t("control_at_best_note"), wrap=True)
    ws.merge_cells(start_row=row, start_column=1, end_row=row, end_column=5)
    row += 2
    put_text(ws, row, 1, book.t("control_check"), bold=True)
    row += 1
    for col, key in enumerate(("control_rule", "control_ratio", "term_required_rms",
                               "control_ok", "control_source"), start=1):
        put_text(ws, row, col, book.t(key), bold=True)
    for (rule, axis, _, _, ok, source), r in zip(check_rows(tables, book.loc),
                                                  tables["control_checks"].rows, strict=True):
        row += 1
        put_text(ws, row, 1, f"{rule} ({axis})", wrap=True)
        put_num(ws, row, 2, r.values[0], "0.0")
        put_num(ws, row, 3, r.values[1], "0")
        put_text(ws, row, 4, ok)
        put_text(ws, row, 5, book.bib.cite(source), wrap=True)
    row += 2
    put_text(ws, row, 1, book.t("control_rules"), bold=True)
    row += 1
    for col, key in enumerate(("control_rule", "control_value", "control_status",
                               "", "control_source"), start=1):
        if key:
            put_text(ws, row, col, book.t(key), bold=True)
    for (rule, _, status, source), r in zip(rule_rows(tables, book.loc),
                                            tables["control_rules"].rows, strict=True):
        row += 1
        put_text(ws, row, 1, rule, wrap=True)
        put_num(ws, row, 2, r.value, "0.##")
        put_text(ws, row, 3, status, wrap=True)
        put_text(ws, row, 5, book.bib.cite(source), wrap=True)

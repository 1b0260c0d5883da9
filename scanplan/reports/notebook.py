"""A report table (:mod:`scanplan.reports.views`) as a small HTML table: what a notebook's
``_repr_html_`` shows of a result (:mod:`scanplan.api`), worded as the documents word it
(:mod:`.tablewords`)."""

from __future__ import annotations

import html

from ..i18n.numbers import Numbers
from .tablewords import row_label, row_unit, row_value
from .view import Labels
from .views import Column, Table

__all__ = ["table_html"]

#: The label of a column named by its key.
_COLUMNS = {"limit": "xlsx_limit_m", "compares": "xlsx_compares", "max_height": "max_height_m",
            "max_flown": "max_flown_height_m", "margin_pct": "margin_pct", "film": "spec_film",
            "uav": "spec_uav"}


def _heading(c: Column, labels: Labels, numbers: Numbers) -> str:
    if c.unit == "scale":
        return numbers.scale(c.value)
    if c.key == "at_height":
        return labels("pdf_at_height", h=numbers.g(c.value))
    return labels(_COLUMNS[c.key]) if c.key in _COLUMNS else c.key


def table_html(tbl: Table, title: str, locale: str = "en", platform: str = "uav",
               units: bool = False) -> str:
    """``tbl`` as an HTML table under ``title``; binding values (rows) in bold.

    Parameters
    ----------
    tbl : Table
        A table of a result (:class:`scanplan.reports.views.ResultTables`).
    title : str
        The heading above it.
    locale : {"en", "ru"}
        The language of its words and numbers.
    platform : {"uav", "aircraft"}
        The wording of a digital camera's rows.
    units : bool
        Whether the rows' units follow in a last column (the tables whose labels carry no
        unit: the film table, the comparison).

    Returns
    -------
    str
        ``<div><strong>title</strong><table>…</table></div>``.
    """
    labels, numbers = Labels(locale, platform), Numbers(locale)
    head = "".join(f"<th>{html.escape(_heading(c, labels, numbers))}</th>" for c in tbl.columns)
    body = [f"<tr><th></th>{head}" + ("<th></th>" if units else "") + "</tr>"]
    for r in tbl.rows:
        cells = []
        for i, value in enumerate(r.values):
            digits = r.digits if r.digits is not None else (
                tbl.columns[i].digits if i < len(tbl.columns) else None)
            text = html.escape(row_value(r, value, numbers, digits))
            strong = r.flagged(i, "binding") or "binding" in r.flags
            cells.append(f"<td><b>{text}</b></td>" if strong else f"<td>{text}</td>")
        cells += ["<td></td>"] * (len(tbl.columns) - len(r.values))
        unit = f"<td>{html.escape(row_unit(r.unit, labels))}</td>" if units else ""
        body.append(f"<tr><th style='text-align:left'>"
                    f"{html.escape(row_label(r, labels, numbers))}</th>{''.join(cells)}{unit}</tr>")
    return f"<div><strong>{html.escape(title)}</strong><table>{''.join(body)}</table></div>"

"""A report table (:mod:`scanplan.reports.views`) as a small HTML table: what a notebook's
``_repr_html_`` shows of a result (:mod:`scanplan.api`), worded as the documents word it
(:class:`~.formatter.Formatter`)."""

from __future__ import annotations

import html

from .formatter import Formatter, formatter
from .views import Column, Table

__all__ = ["table_html"]

#: The label of a column named by its key.
_COLUMNS = {"limit": "limit_m", "compares": "compares", "max_height": "max_height_m",
            "max_flown": "max_flown_height_m", "margin_pct": "margin_pct", "film": "spec_film",
            "uav": "spec_uav"}


def _heading(c: Column, f: Formatter) -> str:
    if c.unit == "scale":
        return f.scale(c.value)
    if c.key == "at_height":
        return f("at_height", h=f.g(c.value))
    return f(_COLUMNS[c.key]) if c.key in _COLUMNS else c.key


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
    f = formatter(locale, platform)
    head = "".join(f"<th>{html.escape(_heading(c, f))}</th>" for c in tbl.columns)
    body = [f"<tr><th></th>{head}" + ("<th></th>" if units else "") + "</tr>"]
    for r in tbl.rows:
        cells = []
        for i, value in enumerate(r.values):
            digits = r.digits if r.digits is not None else (
                tbl.columns[i].digits if i < len(tbl.columns) else None)
            text = html.escape(f.value(r, value, digits))
            strong = r.flagged(i, "binding") or "binding" in r.flags
            cells.append(f"<td><b>{text}</b></td>" if strong else f"<td>{text}</td>")
        cells += ["<td></td>"] * (len(tbl.columns) - len(r.values))
        unit = f"<td>{html.escape(f.unit(r.unit))}</td>" if units else ""
        body.append(f"<tr><th style='text-align:left'>"
                    f"{html.escape(f.row_label(r))}</th>{''.join(cells)}{unit}</tr>")
    return f"<div><strong>{html.escape(title)}</strong><table>{''.join(body)}</table></div>"

"""The terminal's one layout: aligned tables of a report table's rows, wrapped notes."""

from __future__ import annotations

import textwrap
from collections.abc import Callable, Sequence
from typing import Any

from ..views import Row, Table

__all__ = ["WIDTH", "code_tag", "table", "text_table", "wrap"]

WIDTH = 96
"""The terminal's line width [characters]."""


def table(rows: Sequence[Sequence[str]], *, align: str = "", gap: int = 2) -> str:
    """Align rows of cells; ``align`` holds 'l'/'r' per column (default: first l, rest r)."""
    widths = [max(len(r[i]) for r in rows if i < len(r)) for i in range(max(map(len, rows)))]
    out = []
    for r in rows:
        cells = []
        for i, cell in enumerate(r):
            a = align[i] if i < len(align) else ("l" if i == 0 else "r")
            cells.append(cell.ljust(widths[i]) if a == "l" else cell.rjust(widths[i]))
        out.append((" " * gap).join(cells).rstrip())
    return "\n".join(out)


def text_table(tbl: Table, *, label: Callable[[Row], str],
               cell: Callable[[Row, int, Any], str], unit: Callable[[Row], str] | None = None,
               head: Sequence[str] | None = None, align: str = "",
               columns: Sequence[int] | None = None,
               after: Callable[[Row], str] | None = None) -> str:
    """A report table (:class:`scanplan.reports.views.Table`) as aligned text: the one
    layout of the terminal's tables.

    Parameters
    ----------
    tbl : Table
        The table, built once per result.
    label : callable
        A row's label in the reader's language.
    cell : callable
        ``(row, i, value)`` → the text of value ``i`` of the row.
    unit : callable, optional
        A row's unit in words (a column after the label); none when not given.
    head : sequence of str, optional
        The heading row.
    align : str
        ``"l"`` / ``"r"`` per column (:func:`table`).
    columns : sequence of int, optional
        The columns shown, in order (default: all).
    after : callable, optional
        A last column after the values (a row's unit there, not after the label).

    Returns
    -------
    str
    """
    rows = [list(head)] if head is not None else []
    for r in tbl.rows:
        shown = range(len(r.values)) if columns is None else columns
        rows.append([label(r), *([unit(r)] if unit is not None else []),
                     *(cell(r, i, r.values[i]) for i in shown),
                     *([after(r)] if after is not None else [])])
    return table(rows, align=align)


def wrap(text: str, indent: str) -> str:
    """``text`` wrapped to the terminal's width after ``indent``."""
    return textwrap.fill(text, width=WIDTH, initial_indent=indent,
                         subsequent_indent=" " * len(indent))


def code_tag(code: str, locale: str) -> str:
    """`` [code]`` after a warning in the English terminal (a word to search the docs for);
    nothing in Russian, whose reader gets no English identifiers."""
    return "" if locale == "ru" else f" [{code}]"

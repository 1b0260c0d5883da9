"""The norm template workbook: a norm set pre-filled, one sheet per table, header
comments with units and data validation (openpyxl, imported lazily)."""

from __future__ import annotations

import io
import os
import re
from pathlib import Path
from typing import Any

from ..errors import InputError, WriteError
from ..io.atomic import write_atomic
from . import store as _norms
from .cells import _FORMULA_START, _shown
from .export import _set_rows
from .grid import _col_letter
from .limits import META_KEYS, META_TABLE
from .schema import PARAMETERS, TABLES, ColumnSpec, TableSpec, ValueSpec


def _header_text(col: ColumnSpec, lang: str) -> str:
    if lang == "ru":
        for a in col.aliases:
            if re.search("[а-яё]", a, re.I):
                return a[0].upper() + a[1:]
    return col.name


def write_template(
    path: str | os.PathLike[str],
    norm_set: str = _norms.DEFAULT_NORM_SET,
    *,
    lang: str = "en",
    catalogue: bool = True,
    force: bool = False,
) -> Path:
    """Write a norm workbook pre-filled with a norm set (import it back to get the set).

    One sheet per table (plus ``set`` with the title and source), a bold frozen header
    whose cells carry comments (description, unit, rule), data validation on numeric
    columns and parameter values, and fitted column widths. Rendered in memory, then
    written atomically (:func:`scanplan.io.atomic.write_atomic`): on any failure an existing
    file is left as it was (mode included) and no temporary file remains.

    Parameters
    ----------
    path : str or path
        The ``.xlsx`` to write.
    norm_set : str
        Set to pre-fill with (name or folder; default the bundled set).
    lang : {"en", "ru"}
        Sheet names and headers in English (schema names) or Russian (titles, aliases).
    catalogue : bool
        Include the cameras and scanners the set sees.
    force : bool
        Overwrite an existing file.

    Returns
    -------
    Path
    """
    from openpyxl import Workbook

    out = Path(path)
    _check_target(out, lang, force)
    ns = _norms.load_norm_set(norm_set)
    wb = Workbook()
    wb.remove(wb.active)
    for tname, rows in _set_rows(ns, catalogue).items():
        spec = TABLES[tname]
        ws = wb.create_sheet(spec.title_ru if lang == "ru" else spec.name)
        _header_row(ws, spec, lang, with_comments=True)
        for ri, row in enumerate(rows, start=2):
            for ci, col in enumerate(spec.columns, start=1):
                _text_cell(ws.cell(row=ri, column=ci), row.get(col.name))
        _fit_widths(ws, spec, rows)
        ws.freeze_panes = "A2"
        _column_validations(ws, spec, len(rows))
        if tname == "parameters":
            _parameter_notes(ws, spec, rows)
    _meta_sheet(wb, ns, lang)
    buf = io.BytesIO()
    wb.save(buf)  # rendered in memory: a failure here touches no file
    try:
        out.parent.mkdir(parents=True, exist_ok=True)
    except OSError as exc:
        raise WriteError.from_os_error(str(out.parent), exc, action="create folder") from exc
    write_atomic(path, buf.getvalue())  # temporary file, fsync, the replaced file's mode
    return out


def _check_target(out: Path, lang: str, force: bool) -> None:
    """The template's file and language (links, folders, FIFOs, existing files refused)."""
    if out.suffix.lower() != ".xlsx":
        raise InputError("FILE", f"the template must be an .xlsx file (got {out.name!r})")
    if lang not in ("en", "ru"):
        raise InputError("--locale", f"must be en or ru (got {lang!r})")
    if out.exists() and not force:
        raise InputError("FILE", f"{out} exists; give --force to overwrite it")
    from ..io.targets import check_target  # links, folders, FIFOs, write-protected, long names

    check_target(os.fspath(out), "FILE", "xlsx", force=True)


def _header_row(ws: Any, spec: TableSpec, lang: str, *, with_comments: bool) -> None:
    """The bold, filled header row; ``with_comments``: each cell notes the column's
    meaning, unit and rule."""
    from openpyxl.comments import Comment
    from openpyxl.styles import Alignment, Font, PatternFill

    bold, fill = Font(bold=True), PatternFill("solid", fgColor="DDEBF7")
    for ci, col in enumerate(spec.columns, start=1):
        cell = ws.cell(row=1, column=ci, value=_header_text(col, lang))
        cell.font, cell.fill = bold, fill
        if not with_comments:
            continue
        cell.alignment = Alignment(wrap_text=True, vertical="top")
        rule = (
            "rule depends on the parameter (see the note on its value cell)"
            if spec.name == "parameters" and col.name == "value"
            else col.value.describe()
        )
        text = f"{col.name}: {col.description}\nunit: {col.value.unit or '-'}\nrule: {rule}" + (
            "\nrequired" if col.value.required else "\noptional"
        )
        cell.comment = Comment(text, "scanplan", width=320, height=120)


def _fit_widths(ws: Any, spec: TableSpec, rows: list[dict[str, Any]]) -> None:
    """Column widths fitted to the header and the longest value (8 to 60 characters)."""
    widths = [len(str(ws.cell(row=1, column=ci).value)) for ci in range(1, len(spec.columns) + 1)]
    for row in rows:
        for ci, col in enumerate(spec.columns):
            widths[ci] = max(widths[ci], len(_shown(row.get(col.name))))
    for ci, w in enumerate(widths, start=1):
        ws.column_dimensions[_col_letter(ci)].width = min(max(w + 2, 8), 60)


def _column_validations(ws: Any, spec: TableSpec, n_rows: int) -> None:
    """Data validation down each numeric column (its bounds) and each choice column (a
    drop-down list), 500 rows past the data (at least to row 1,000)."""
    from openpyxl.worksheet.datavalidation import DataValidation

    for ci, col in enumerate(spec.columns, start=1):
        if col.value.kind in ("float", "int"):
            dv = _validation(DataValidation, col.value, col.name)
        elif col.value.kind == "choice":
            dv = DataValidation(
                type="list",
                formula1='"' + ",".join(col.value.choices) + '"',
                allow_blank=not col.value.required,
            )
        else:
            continue
        dv.add(f"{_col_letter(ci)}2:{_col_letter(ci)}{max(n_rows + 500, 1000)}")
        ws.add_data_validation(dv)


def _parameter_notes(ws: Any, spec: TableSpec, rows: list[dict[str, Any]]) -> None:
    """Each parameter's value cell: a note with its meaning and rule, and its validation."""
    from openpyxl.comments import Comment
    from openpyxl.worksheet.datavalidation import DataValidation

    vcol = _col_letter([c.name for c in spec.columns].index("value") + 1)
    for ri, row in enumerate(rows, start=2):
        pspec = PARAMETERS[row["name"]]
        ws[f"{vcol}{ri}"].comment = Comment(
            f"{pspec.description}\nrule: {pspec.value.describe()}",
            "scanplan",
            width=320,
            height=90,
        )
        if pspec.value.kind in ("float", "int"):
            dv = _validation(DataValidation, pspec.value, row["name"])
        elif pspec.value.kind == "choice":
            dv = DataValidation(type="list", formula1='"' + ",".join(pspec.value.choices) + '"')
        else:
            continue
        dv.add(f"{vcol}{ri}")
        ws.add_data_validation(dv)


def _meta_sheet(wb: Any, ns: Any, lang: str) -> None:
    """The ``set`` sheet: the set's title, Russian title and source."""
    ws = wb.create_sheet(META_TABLE.title_ru if lang == "ru" else META_TABLE.name)
    _header_row(ws, META_TABLE, lang, with_comments=False)
    for ri, key in enumerate(META_KEYS, start=2):
        ws.cell(row=ri, column=1, value=key)
        _text_cell(ws.cell(row=ri, column=2), getattr(ns, key) or None)
    ws.column_dimensions["A"].width = 12
    ws.column_dimensions["B"].width = 100
    ws.freeze_panes = "A2"


_XML_ILLEGAL = re.compile(r"[\x00-\x08\x0b\x0c\x0e-\x1f]")


def _text_cell(cell: Any, value: Any) -> None:
    """Put ``value`` in a template cell; text stays text (never a formula, whatever it
    starts with), and characters a workbook cannot hold are dropped."""
    if not isinstance(value, str):
        cell.value = value
        return
    cell.value = _XML_ILLEGAL.sub("", value)
    cell.data_type = "s"  # openpyxl would make "=..." a formula
    if value[:1] in _FORMULA_START:
        cell.quotePrefix = True  # and Excel keeps it text when the cell is edited


def _validation(cls: Any, spec: ValueSpec, name: str) -> Any:
    """An Excel data validation for a numeric rule."""
    kind = "whole" if spec.kind == "int" else "decimal"
    lo, hi = spec.min, spec.max
    if lo is not None and hi is not None:
        dv = cls(type=kind, operator="between", formula1=f"{lo:g}", formula2=f"{hi:g}")
    elif lo is not None:
        dv = cls(
            type=kind,
            operator="greaterThan" if spec.min_open else "greaterThanOrEqual",
            formula1=f"{lo:g}",
        )
    elif hi is not None:
        dv = cls(
            type=kind,
            operator="lessThan" if spec.max_open else "lessThanOrEqual",
            formula1=f"{hi:g}",
        )
    else:
        dv = cls(type=kind, operator="between", formula1="-1E+307", formula2="1E+307")
    dv.allow_blank = not spec.required
    dv.showErrorMessage = True
    dv.errorTitle = name
    dv.error = f"{name} must be {spec.describe()}"
    return dv

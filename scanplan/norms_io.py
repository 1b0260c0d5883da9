"""Norm spreadsheets in and out: read .xlsx/.csv norm tables, check them, write norm sets.

Enterprises keep their norm tables in Excel, often a Russian-locale Excel. This module
takes such a workbook (or a single-table CSV), finds each table's header row, maps English
or Russian headers to the schema's columns (:mod:`scanplan.normschema` declares every
alias), reads text as text (``"0,20"`` → 0.2, ``"1:2 000"`` → 2000, U+2212 minus), checks
every value and every cross-table rule, and collects *all* problems with an address a user
can paste into Excel's Name Box (``'Objects'!C7``). Only a fully valid input is written,
atomically, as a norm-set folder under :func:`scanplan.norms.user_norms_dir`.

The reverse direction, :func:`write_template`, writes a workbook pre-filled with a norm set
(one sheet per table, header comments with units, data validation on numeric columns);
importing it back gives the same set.

Public functions
----------------
read_norm_file
    Parse and check a workbook or CSV; return a :class:`ParsedNormSet` or raise
    :class:`NormImportError` listing every problem.
write_norm_set
    Write a parsed set as a user norm set (temporary folder + rename; ``force`` replaces).
import_norm_file
    ``read_norm_file`` + ``write_norm_set``.
write_template
    The template workbook.
norm_set_dict
    A norm set as plain data (``scanplan norms show --json``).
check_set_name
    Refuse unsafe or shadowing set names.

openpyxl is imported lazily: the rest of scanplan never needs it.
"""

from __future__ import annotations

import csv
import dataclasses
import datetime as _dt
import io
import json
import math
import os
import re
import shutil
import tempfile
import zipfile
from collections.abc import Iterable, Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from . import norms as _norms
from .errors import InputError, NotFoundError
from .normschema import PARAMETERS, TABLES, ColumnSpec, TableSpec, ValueSpec

__all__ = [
    "HEADER_SCAN_ROWS",
    "MAX_COMPRESSION_RATIO",
    "MAX_ERRORS_SHOWN",
    "MAX_FILE_BYTES",
    "MAX_MEMBER_BYTES",
    "MAX_ROWS",
    "MAX_TOTAL_UNCOMPRESSED_BYTES",
    "META_TABLE",
    "ImportProblem",
    "NormImportError",
    "ParsedNormSet",
    "check_set_name",
    "format_problems",
    "import_norm_file",
    "norm_set_dict",
    "parse_number",
    "read_norm_file",
    "write_norm_set",
    "write_template",
]

# --- limits (module constants so tests and embedders can tighten them) --------------------
MAX_FILE_BYTES = 20 * 1024 * 1024
"""Largest input file accepted [bytes]."""
MAX_MEMBER_BYTES = 100 * 1024 * 1024
"""Largest uncompressed size of one member of an .xlsx (zip) [bytes]."""
MAX_TOTAL_UNCOMPRESSED_BYTES = 200 * 1024 * 1024
"""Largest total uncompressed size of an .xlsx [bytes]."""
MAX_COMPRESSION_RATIO = 200
"""Largest uncompressed/compressed ratio of a member bigger than 1 MB (zip bombs)."""
MAX_ROWS = 200_000
"""Most rows one sheet or CSV may have."""
MAX_ERRORS_SHOWN = 20
"""Problem lines a message shows before "+N more"."""
MAX_ERRORS_KEPT = 1000
"""Problems kept for ``--json`` (the total is always counted)."""
HEADER_SCAN_ROWS = 20
"""Rows searched for the header row."""

XLSX_SUFFIXES = (".xlsx", ".xlsm")
CSV_SUFFIXES = (".csv", ".txt", ".tsv")

META_TABLE = TableSpec(
    "set",
    "set.toml",
    ("key",),
    (
        ColumnSpec("key", ValueSpec("text"), "title, title_ru or source", ("ключ", "поле")),
        ColumnSpec("value", ValueSpec("text", required=False), "its text", ("значение",)),
    ),
    required=False,
    title_ru="Набор",
    description="title, Russian title and source of the norm set",
)
"""The optional ``set`` sheet of a workbook: the set's title, title_ru and source."""
META_KEYS = ("title", "title_ru", "source")

_EXCEL_ERRORS = frozenset(
    (
        "#NULL!",
        "#DIV/0!",
        "#VALUE!",
        "#REF!",
        "#NAME?",
        "#NUM!",
        "#N/A",
        "#GETTING_DATA",
        "#SPILL!",
        "#CALC!",
        "#FIELD!",
        "#BLOCKED!",
        "#CONNECT!",
        "#UNKNOWN!",
        "#BUSY!",
    )
)
_DELETE_SPACES = dict.fromkeys(map(ord, " \t\u00a0\u202f\u2009\u2007\u200a\u2008\u2006"), None)
_NUMBER_RE = re.compile(r"[+-]?(?:\d+\.?\d*|\.\d+)(?:[eE][+-]?\d+)?")


# =========================================================================================
# Problems
# =========================================================================================


@dataclass(frozen=True)
class ImportProblem:
    """One problem of an input file.

    Attributes
    ----------
    address : str
        Where: ``'Objects'!C7`` (paste into Excel's Name Box), or a file name for problems
        that have no cell.
    message : str
        What is wrong (without the address), e.g. ``must be a number > 0 [m]``.
    header : str
        The column's header as written in the file ("" when not about a column).
    value : str or None
        The offending value as written (None when not about a value).
    hint : str
        How to fix it.
    """

    address: str
    message: str
    header: str = ""
    value: str | None = None
    hint: str = ""

    def __str__(self) -> str:
        parts = [self.address]
        if self.header:
            parts.append(f'column "{self.header}"')
        if self.value is not None:
            if self.value != "":
                parts.append(f'value "{self.value}"')
        text = ": ".join(parts) + ": " + self.message
        return text + (f"; hint: {self.hint}" if self.hint else "")

    def as_dict(self) -> dict[str, Any]:
        """The problem as JSON-ready data (``text`` is the one-line form)."""
        d = dataclasses.asdict(self)
        d["text"] = str(self)
        return d


def format_problems(
    problems: Sequence[ImportProblem], total: int | None = None, limit: int | None = None
) -> list[str]:
    """One line per problem, capped at ``limit`` (default :data:`MAX_ERRORS_SHOWN`).

    Parameters
    ----------
    problems : sequence of ImportProblem
        Problems kept.
    total : int, optional
        How many there were in all (default ``len(problems)``).
    limit : int, optional
        Lines shown before a final ``+N more``.
    """
    limit = MAX_ERRORS_SHOWN if limit is None else limit
    total = len(problems) if total is None else total
    lines = [str(p) for p in problems[:limit]]
    if total > len(lines):
        lines.append(f"+{total - len(lines)} more")
    return lines


class NormImportError(InputError):
    """An input file that cannot become a norm set, with every problem found.

    Attributes
    ----------
    problems : tuple of ImportProblem
        The problems (at most :data:`MAX_ERRORS_KEPT`).
    total : int
        How many problems there were in all.
    """

    def __init__(
        self, source: str, problems: Sequence[ImportProblem], total: int | None = None
    ) -> None:
        self.problems = tuple(problems)
        self.total = len(self.problems) if total is None else total
        n = self.total
        head = f"{n} problem{'s' if n != 1 else ''} found; nothing was written"
        super().__init__(
            source, head + "\n  " + "\n  ".join(format_problems(self.problems, self.total))
        )


class _Problems:
    """Collects problems (keeps the first MAX_ERRORS_KEPT, counts all)."""

    def __init__(self) -> None:
        self.items: list[ImportProblem] = []
        self.total = 0

    def add(self, problem: ImportProblem) -> None:
        self.total += 1
        if len(self.items) < MAX_ERRORS_KEPT:
            self.items.append(problem)

    def raise_if_any(self, source: str) -> None:
        if self.total:
            raise NormImportError(source, self.items, self.total)


def _fail(source: str, message: str, hint: str = "") -> NormImportError:
    return NormImportError(source, [ImportProblem(source, message, hint=hint)])


# =========================================================================================
# Values
# =========================================================================================


def parse_number(text: str, *, scale: bool = False, percent: bool = False) -> float:
    """A number from spreadsheet text, in any locale Excel users type.

    Accepts a decimal comma (``0,20``) or point, thousands separators made of spaces,
    NBSP, narrow NBSP or thin spaces (``2 000``), both separators (``1 000,5``,
    ``1,000.5``, ``1.000,5``), the minus sign U+2212, and with ``scale`` a ``1:``
    prefix (``1:2000``); with ``percent`` a trailing ``%``.

    Parameters
    ----------
    text : str
        The cell text.
    scale : bool
        Allow ``1:N``.
    percent : bool
        Allow a trailing ``%`` (the number is kept as written: ``60%`` → 60).

    Returns
    -------
    float

    Raises
    ------
    ValueError
        When the text is not a finite number.
    """
    s = text.translate(_DELETE_SPACES).replace("\u2212", "-").replace("\u2012", "-")
    if scale and s.startswith("1:"):
        s = s[2:]
    if percent and s.endswith("%"):
        s = s[:-1]
    if "," in s and "." in s:
        if s.rfind(",") > s.rfind("."):  # 1.000,5
            s = s.replace(".", "").replace(",", ".")
        else:  # 1,000.5
            s = s.replace(",", "")
    elif s.count(",") == 1:  # decimal comma (a Russian-locale 0,20)
        s = s.replace(",", ".")
    elif s.count(",") > 1 and re.fullmatch(r"[+-]?\d{1,3}(,\d{3})+", s):
        s = s.replace(",", "")
    elif s.count(".") > 1 and re.fullmatch(r"[+-]?\d{1,3}(\.\d{3})+", s):
        s = s.replace(".", "")
    if not _NUMBER_RE.fullmatch(s):
        raise ValueError(text)
    v = float(s)
    if not math.isfinite(v):
        raise ValueError(text)
    return v


def _num_text(v: float) -> str:
    """Shortest text that reads back as ``v`` (``2000`` not ``2000.0``)."""
    if v == int(v) and abs(v) < 1e15:
        return str(int(v))
    return repr(v)


def _shown(raw: object) -> str:
    """A raw cell value as the user sees it."""
    if raw is None:
        return ""
    if isinstance(raw, bool):
        return "TRUE" if raw else "FALSE"
    if isinstance(raw, float):
        return _num_text(raw)
    if isinstance(raw, _dt.datetime | _dt.date | _dt.time):
        return raw.isoformat()
    return str(raw)


class _Bad(Exception):
    """A value breaks its rule (message, hint)."""

    def __init__(self, message: str, hint: str = "") -> None:
        super().__init__(message)
        self.message = message
        self.hint = hint


def _number_hint(spec: ValueSpec, scale: bool) -> str:
    if scale:
        return "type the scale denominator, e.g. 2000, 2 000 or 1:2000"
    if spec.kind == "int":
        return "type a whole number, e.g. 2000"
    return "type a decimal number, e.g. 0,20 or 0.20"


def _is_empty(raw: object) -> bool:
    return raw is None or (isinstance(raw, str) and raw.strip() == "")


def _convert(
    raw: object, spec: ValueSpec, *, scale: bool = False, percent_cell: bool = False
) -> str:
    """Check one raw cell value against its rule; return its canonical text, or raise _Bad.

    ``percent_cell``: the cell has a percent number format (Excel stores 60 % as 0.6).
    """
    if _is_empty(raw):
        if spec.required:
            raise _Bad(f"is empty; must be {spec.describe()}", "fill in the cell")
        return ""
    if isinstance(raw, str) and raw.strip() in _EXCEL_ERRORS:
        raise _Bad(
            f"the cell shows an Excel error; must be {spec.describe()}",
            "fix the formula or type the value",
        )
    if isinstance(raw, _dt.datetime | _dt.date | _dt.time | _dt.timedelta):
        raise _Bad(
            f"is a date or time; must be {spec.describe()}",
            "Excel turned the value into a date: format the column as Text or "
            "Number and type the value again",
        )
    if spec.kind in ("float", "int"):
        if isinstance(raw, bool):
            raise _Bad(f"must be {spec.describe()}", "type a number, not TRUE/FALSE")
        if isinstance(raw, int | float):
            v = float(raw)
            if percent_cell and spec.unit == "%":
                v *= 100.0
            v = float(f"{v:.15g}")  # drop binary noise of Excel's doubles
        else:
            try:
                v = parse_number(str(raw), scale=scale, percent=spec.unit == "%")
            except ValueError:
                raise _Bad(f"must be {spec.describe()}", _number_hint(spec, scale)) from None
        problem = spec.check(v)
        if problem:
            hint = (
                _number_hint(spec, scale)
                if spec.kind == "int" and v != int(v)
                else (
                    f"check the unit: {spec.unit}"
                    if spec.unit and spec.unit != "-"
                    else "check the value"
                )
            )
            raise _Bad(problem, hint)
        return str(int(v)) if spec.kind == "int" else _num_text(v)
    if isinstance(raw, bool):
        text = "TRUE" if raw else "FALSE"
    elif isinstance(raw, float):
        text = _num_text(raw)
    else:
        text = str(raw).strip()
    if spec.kind == "choice":
        folded = {c.casefold(): c for c in spec.choices}
        text = folded.get(text.casefold(), text)
    elif spec.kind == "list":
        folded = {c.casefold(): c for c in spec.choices}
        items = [x.strip() for x in re.split(r"[,;]", text) if x.strip()]
        text = ",".join(folded.get(x.casefold(), x) for x in items)
    problem = spec.check(text)
    if problem:
        raise _Bad(problem, "spelling matters" if spec.choices else "")
    return text


# =========================================================================================
# Headers
# =========================================================================================


def _norm(text: object) -> str:
    """Header text folded for matching: case, ё, punctuation, underscores, spaces."""
    s = str(text).casefold().replace("ё", "е").replace("_", " ")
    s = re.sub(r"[^\w]+", " ", s)
    return " ".join(s.split())


def _header_forms(text: str) -> list[str]:
    """Ways to read a header, most literal first ("Размер объекта L, м" → ... "размер")."""
    forms = [_norm(text)]
    no_paren = re.sub(r"\([^)]*\)|\[[^\]]*\]", " ", text)
    forms.append(_norm(no_paren))
    if "," in no_paren:
        forms.append(_norm(no_paren.rsplit(",", 1)[0]))
    last = forms[-1].split()
    if len(last) > 1 and len(last[-1]) <= 2:
        forms.append(" ".join(last[:-1]))
    seen: list[str] = []
    for f in forms:
        if f and f not in seen:
            seen.append(f)
    return seen


def _alias_index(items: Iterable[tuple[str, Iterable[str]]]) -> dict[str, str]:
    """normalised alias → canonical name (names themselves are aliases too)."""
    index: dict[str, str] = {}
    for name, aliases in items:
        for a in (name, *aliases):
            index.setdefault(_norm(a), name)
    return index


_COLUMN_INDEX: dict[str, dict[str, str]] = {
    t.name: _alias_index((c.name, c.aliases) for c in t.columns)
    for t in (*TABLES.values(), META_TABLE)
}
_PARAMETER_INDEX = _alias_index((p.name, p.aliases) for p in PARAMETERS.values())
_ALL_TABLES: dict[str, TableSpec] = {**TABLES, META_TABLE.name: META_TABLE}
_SHEET_INDEX = _alias_index((t.name, (t.title_ru, Path(t.file).stem)) for t in _ALL_TABLES.values())


def _match(index: Mapping[str, str], text: object) -> str | None:
    if _is_empty(text):
        return None
    for form in _header_forms(str(text)):
        if form in index:
            return index[form]
    return None


def _col_letter(col: int) -> str:
    s = ""
    while col:
        col, r = divmod(col - 1, 26)
        s = chr(65 + r) + s
    return s


def _col_number(letters: str) -> int:
    n = 0
    for ch in letters:
        n = n * 26 + ord(ch) - 64
    return n


def _cell_ref(ref: str) -> tuple[int, int]:
    m = re.fullmatch(r"\$?([A-Z]{1,3})\$?(\d+)", ref)
    if not m:
        raise ValueError(ref)
    return int(m.group(2)), _col_number(m.group(1))


# =========================================================================================
# Grids: a sheet or a CSV as rows of raw values
# =========================================================================================


@dataclass
class _Grid:
    """One sheet (or CSV) as raw cell values, 1-based rows/columns."""

    label: str  # sheet name (or CSV stem)
    rows: list[Sequence[Any]]
    merged: list[tuple[int, int, int, int]] = field(default_factory=list)
    formula_without_value: set[tuple[int, int]] = field(default_factory=set)
    percent_cells: set[tuple[int, int]] = field(default_factory=set)
    file_label: str = ""  # for base-set CSVs: "set/objects.csv" (file:row addresses)
    _fill: dict[tuple[int, int], Any] = field(default_factory=dict)
    _group: dict[tuple[int, int], Any] = field(default_factory=dict)

    def __post_init__(self) -> None:
        for r1, c1, r2, c2 in self.merged:
            top = self.raw(r1, c1)
            if c1 == c2:  # a vertical merge: every row of it shows the value
                for r in range(r1 + 1, r2 + 1):
                    self._fill[(r, c1)] = top
            for r in range(r1, min(r2, HEADER_SCAN_ROWS) + 1):  # only headers use groups
                for c in range(c1, min(c2, c1 + 200) + 1):
                    self._group[(r, c)] = top

    def raw(self, r: int, c: int) -> Any:
        if r - 1 < len(self.rows):
            row = self.rows[r - 1]
            if c - 1 < len(row):
                return row[c - 1]
        return None

    def value(self, r: int, c: int) -> Any:
        v = self.raw(r, c)
        if v is None and (r, c) in self._fill:
            return self._fill[(r, c)]
        return v

    def group(self, r: int, c: int) -> Any:
        return self._group.get((r, c), self.value(r, c))

    def width(self, r: int) -> int:
        return len(self.rows[r - 1]) if r - 1 < len(self.rows) else 0

    def address(self, r: int, c: int, column: str = "") -> str:
        if self.file_label:
            return f"{self.file_label}:{r}" + (f" ({column})" if column else "")
        return "'" + self.label.replace("'", "''") + f"'!{_col_letter(c)}{r}"

    def merge_bottom(self, r: int, c: int) -> int:
        for r1, c1, r2, c2 in self.merged:
            if r1 <= r <= r2 and c1 <= c <= c2:
                return r2
        return r


@dataclass
class _Located:
    """A grid with its header found: column name → (column number, header text)."""

    spec: TableSpec
    grid: _Grid
    header_row: int
    columns: dict[str, tuple[int, str]]
    data_start: int


def _find_header(grid: _Grid, spec: TableSpec, problems: _Problems | None) -> _Located | None:
    """The header row of ``grid`` for table ``spec``: the row matching most columns."""
    index = _COLUMN_INDEX[spec.name]
    last_row = min(HEADER_SCAN_ROWS, len(grid.rows))
    width = max(
        [grid.width(r) for r in range(1, last_row + 1)] + [c for (_, c) in grid._fill], default=0
    )
    best: tuple[int, dict[str, tuple[int, str]], list[tuple[int, str, str]]] | None = None
    for r in range(1, last_row + 1):
        found: dict[str, tuple[int, str]] = {}
        dups: list[tuple[int, str, str]] = []
        for c in range(1, width + 1):
            text = grid.value(r, c)
            name = _match(index, text)
            if name is None and r > 1:  # a group header above: "Размер" over "объекта, м"
                upper = grid.group(r - 1, c)
                if not _is_empty(upper) and not _is_empty(text):
                    text = f"{upper} {text}"
                    name = _match(index, text)
            if name is None:
                continue
            if name in found:
                dups.append((c, str(text), name))
                continue
            found[name] = (c, " ".join(str(text).split()))
        if found and (best is None or len(found) > len(best[1])):
            best = (r, found, dups)
    if best is None:
        if problems is not None:
            problems.add(
                ImportProblem(
                    grid.address(1, 1),
                    f"no header row of table {spec.name!r} in the first {HEADER_SCAN_ROWS} rows",
                    hint="headers such as "
                    + ", ".join(
                        f'"{c.name}"' + (f' / "{c.aliases[-1]}"' if c.aliases else "")
                        for c in spec.columns[:4]
                    ),
                )
            )
        return None
    r, found, dups = best
    ok = True
    for c, text, name in dups:
        ok = False
        if problems is not None:
            problems.add(
                ImportProblem(
                    grid.address(r, c),
                    f"a second column for {name!r} (the first is {_col_letter(found[name][0])})",
                    header=text,
                    hint="delete or rename one of them",
                )
            )
    needed = [c for c in spec.columns if c.value.required or c.name in spec.key]
    missing = [c for c in needed if c.name not in found]
    if missing:
        ok = False
        if problems is not None:
            last = max(c for c, _ in found.values())
            for col in missing:
                aliases = ", ".join(f'"{a}"' for a in col.aliases[:3])
                problems.add(
                    ImportProblem(
                        grid.address(r, last + 1),
                        f"missing column {col.name!r} ({col.description}) in the header row {r}",
                        hint=f'add a column headed "{col.name}"'
                        + (f" or one of {aliases}" if aliases else ""),
                    )
                )
    if not ok:
        return None
    start = max(grid.merge_bottom(r, c) for c, _ in found.values()) + 1
    return _Located(spec, grid, r, found, start)


# =========================================================================================
# Tables → canonical rows
# =========================================================================================


@dataclass
class _Row:
    """One data row: canonical texts and where each came from."""

    number: int
    values: dict[str, str]
    grid: _Grid
    cols: dict[str, int]
    headers: dict[str, str]
    raw: dict[str, Any]
    bad: bool = False

    def problem(
        self, column: str, message: str, hint: str = "", with_value: bool = True
    ) -> ImportProblem:
        c = self.cols.get(column, 1)
        return ImportProblem(
            self.grid.address(self.number, c, column),
            message,
            header=self.headers.get(column, column),
            value=_shown(self.raw.get(column)) if with_value else None,
            hint=hint,
        )


@dataclass
class _Table:
    spec: TableSpec
    rows: list[_Row]
    grid: _Grid
    header_row: int
    cols: dict[str, int]
    headers: dict[str, str]


def _data_rows(loc: _Located, problems: _Problems) -> _Table:
    """Convert every data row of a located table (problems collected, bad rows dropped)."""
    spec, grid = loc.spec, loc.grid
    cols = {name: c for name, (c, _) in loc.columns.items()}
    headers = {name: h for name, (_, h) in loc.columns.items()}
    for col in spec.columns:
        headers.setdefault(col.name, col.name)
    is_params = spec.name == "parameters"
    rows: list[_Row] = []
    n_rows = 0
    fw, pc = grid.formula_without_value, grid.percent_cells
    no_fill = not grid._fill
    items = list(cols.items())
    for r in range(loc.data_start, len(grid.rows) + 1):
        if no_fill:
            line = grid.rows[r - 1]
            raw = {name: (line[c - 1] if c - 1 < len(line) else None) for name, c in items}
        else:
            raw = {name: grid.value(r, c) for name, c in items}
        if all(_is_empty(v) and (r, cols[n]) not in fw for n, v in raw.items()):
            continue  # blank (or trailing empty) row
        n_rows += 1
        if n_rows > MAX_ROWS:
            raise _fail(
                grid.address(r, 1),
                f"more than {MAX_ROWS:,} rows in one table; split the table or delete unused rows",
            )
        row = _Row(r, {}, grid, cols, headers, raw)
        bad = False
        for col in spec.columns:
            c = cols.get(col.name)
            if c is not None and (r, c) in fw:
                problems.add(
                    row.problem(
                        col.name,
                        "formula without a cached value",
                        "open and save the file in Excel, or type the value",
                        with_value=False,
                    )
                )
                bad = True
                continue
            vspec = col.value
            if is_params and col.name == "value":
                pname = _match(_PARAMETER_INDEX, raw.get("name"))
                if pname is None:
                    continue  # reported with the name
                vspec = PARAMETERS[pname].value
            try:
                row.values[col.name] = _convert(
                    raw.get(col.name),
                    vspec,
                    scale=col.value.unit == "1:Mk",
                    percent_cell=c is not None and (r, c) in pc,
                )
            except _Bad as exc:
                problems.add(row.problem(col.name, exc.message, exc.hint))
                bad = True
        if is_params:
            pname = _match(_PARAMETER_INDEX, raw.get("name"))
            if pname is None:
                if not _is_empty(raw.get("name")):
                    problems.add(
                        row.problem("name", "unknown parameter", "known: " + ", ".join(PARAMETERS))
                    )
                bad = True
            else:
                row.values["name"] = pname
                if not row.values.get("unit"):
                    row.values["unit"] = PARAMETERS[pname].value.unit
        row.bad = bad
        rows.append(row)  # bad rows still count for keys and references (no cascades)
    return _Table(spec, rows, grid, loc.header_row, cols, headers)


# =========================================================================================
# Reading files
# =========================================================================================


def _size(n: int) -> str:
    return f"{n / 2**20:.1f} MB" if n >= 2**20 else f"{n:,} bytes"


def _check_file(path: Path) -> int:
    try:
        size = path.stat().st_size
    except OSError as exc:
        raise NotFoundError(str(path), f"cannot be read: {exc.strerror or exc}") from None
    if not path.is_file():
        raise InputError(str(path), "is not a file")
    if size > MAX_FILE_BYTES:
        raise _fail(
            path.name,
            f"the file is {_size(size)}; the limit is {_size(MAX_FILE_BYTES)}",
            "a norm workbook is small: delete unused sheets, images and rows",
        )
    return size


_DOCTYPE = re.compile(rb"<!\s*(?:DOCTYPE|ENTITY)", re.I)


def _inspect_xlsx(path: Path) -> dict[str, bytes]:
    """Check an .xlsx before any XML parser sees it: zip limits, no DTD anywhere.

    Returns
    -------
    dict
        Worksheet member name (``xl/worksheets/sheet1.xml``) → its XML.
    """
    name = path.name
    try:
        zf = zipfile.ZipFile(path)
    except (zipfile.BadZipFile, OSError) as exc:
        raise _fail(
            name,
            f"is not an .xlsx workbook (not a zip file: {exc})",
            'save it from Excel as "Excel Workbook (*.xlsx)"',
        ) from None
    out: dict[str, bytes] = {}
    total = 0
    with zf:
        infos = zf.infolist()
        if len(infos) > 10_000:
            raise _fail(name, f"has {len(infos)} zip members; not a norm workbook")
        for info in infos:
            if info.file_size > MAX_MEMBER_BYTES:
                raise _fail(
                    name,
                    f"zip member {info.filename} would unpack to "
                    f"{_size(info.file_size)}; the limit is "
                    f"{_size(MAX_MEMBER_BYTES)}",
                    "not a norm workbook",
                )
            if (
                info.file_size > 1_000_000
                and info.compress_size
                and info.file_size / info.compress_size > MAX_COMPRESSION_RATIO
            ):
                raise _fail(
                    name,
                    f"zip member {info.filename} is compressed "
                    f"{info.file_size / info.compress_size:.0f}:1; the limit is "
                    f"{MAX_COMPRESSION_RATIO}:1 (a zip bomb?)",
                    "not a norm workbook",
                )
            if not info.filename.lower().endswith((".xml", ".rels", ".vml")):
                continue
            data = bytearray()
            try:
                with zf.open(info) as fh:
                    while chunk := fh.read(1 << 20):
                        data += chunk
                        if len(data) > MAX_MEMBER_BYTES:
                            raise _fail(
                                name,
                                f"zip member {info.filename} unpacks to more "
                                f"than {_size(MAX_MEMBER_BYTES)}",
                                "not a norm workbook",
                            )
            except (
                zipfile.BadZipFile,
                OSError,
                EOFError,
                RuntimeError,
                NotImplementedError,
            ) as exc:
                raise _fail(
                    name,
                    f"is a damaged .xlsx ({info.filename}: {exc})",
                    "open it in Excel and save it again",
                ) from None
            total += len(data)
            if total > MAX_TOTAL_UNCOMPRESSED_BYTES:
                raise _fail(
                    name,
                    f"unpacks to more than {_size(MAX_TOTAL_UNCOMPRESSED_BYTES)}",
                    "not a norm workbook",
                )
            if b"<!" in data and _DOCTYPE.search(data):
                raise _fail(
                    name,
                    f"zip member {info.filename} declares a DTD or XML entities "
                    "(entity expansion, 'billion laughs'); refused",
                    "Excel never writes these: the file was made by something else",
                )
            if info.filename.startswith("xl/worksheets/"):
                out[info.filename] = bytes(data)
    return out


class _Refused(Exception):
    """The XML declares a DTD or entities."""


def _refuse(*_: object) -> None:
    raise _Refused


class _SheetReader:
    """Streams one worksheet's XML (expat, C speed) into rows of raw cell values.

    Values: str, float, bool, an Excel error string (``"#DIV/0!"``), ``datetime`` marker for
    date-formatted numbers. Also records merged ranges, formula cells without a cached
    value and percent-formatted cells. DTDs and entity declarations are refused, as
    defusedxml does.
    """

    def __init__(
        self,
        shared: Sequence[Any],
        date_styles: set[int],
        percent_styles: set[int],
        max_rows: int,
        epoch: _dt.datetime = _dt.datetime(1899, 12, 30),
    ) -> None:
        self.shared = shared
        self.epoch = epoch
        self.date_styles = date_styles
        self.percent_styles = percent_styles
        self.max_rows = max_rows
        self.rows: dict[int, dict[int, Any]] = {}
        self.merged: list[tuple[int, int, int, int]] = []
        self.formula_missing: set[tuple[int, int]] = set()
        self.percent: set[tuple[int, int]] = set()
        self.too_many = 0
        self._row = 0
        self._col = 0
        self._attrs: dict[str, str] = {}
        self._text: list[str] | None = None
        self._v: str | None = None
        self._inline: list[str] = []
        self._has_f = False
        self._in_is = False
        self._in_rph = 0

    def parse(self, data: bytes) -> None:
        import xml.parsers.expat as expat

        p = expat.ParserCreate()
        p.buffer_text = True
        p.StartDoctypeDeclHandler = _refuse
        p.EntityDeclHandler = _refuse
        p.UnparsedEntityDeclHandler = _refuse
        p.ExternalEntityRefHandler = _refuse  # type: ignore[assignment]
        p.SetParamEntityParsing(expat.XML_PARAM_ENTITY_PARSING_NEVER)
        p.StartElementHandler = self._start
        p.EndElementHandler = self._end
        p.CharacterDataHandler = self._chars
        p.Parse(data, True)

    def _start(self, tag: str, attrs: dict[str, str]) -> None:
        tag = tag.rpartition(":")[2]
        if tag == "c":
            ref = attrs.get("r")
            if ref:
                m = re.fullmatch(r"([A-Z]{1,3})(\d+)", ref)
                if m:
                    self._col = _col_number(m.group(1))
                    self._row = int(m.group(2))
                else:
                    self._col += 1
            else:
                self._col += 1
            self._attrs = attrs
            self._v = None
            self._inline = []
            self._has_f = False
        elif tag == "row":
            r = attrs.get("r")
            self._row = int(r) if r and r.isdigit() else self._row + 1
            self._col = 0
            if self._row > self.max_rows:
                self.too_many = self._row
                raise _Refused("rows")
        elif tag == "v":
            self._text = []
        elif tag == "t" and self._in_is and not self._in_rph:
            self._text = []
        elif tag == "is":
            self._in_is = True
        elif tag == "rPh":
            self._in_rph += 1
        elif tag == "f":
            self._has_f = True
        elif tag == "mergeCell":
            ref = attrs.get("ref", "")
            try:
                a, _, b = ref.partition(":")
                r1, c1 = _cell_ref(a)
                r2, c2 = _cell_ref(b) if b else (r1, c1)
                self.merged.append((r1, c1, r2, c2))
            except ValueError:
                pass

    def _chars(self, data: str) -> None:
        if self._text is not None:
            self._text.append(data)

    def _end(self, tag: str) -> None:
        tag = tag.rpartition(":")[2]
        if tag == "v":
            self._v = "".join(self._text or ())
            self._text = None
        elif tag == "t" and self._text is not None:
            self._inline.append("".join(self._text))
            self._text = None
        elif tag == "is":
            self._in_is = False
        elif tag == "rPh":
            self._in_rph -= 1
        elif tag == "c":
            self._cell()

    def _cell(self) -> None:
        t = self._attrs.get("t", "n")
        v = self._v
        pos = (self._row, self._col)
        value: Any
        if t == "inlineStr":
            value = "".join(self._inline)
        elif v is None or v == "":
            if self._has_f:
                self.formula_missing.add(pos)
            return
        elif t == "s":
            try:
                value = self.shared[int(v)]
            except (ValueError, IndexError):
                value = None
            if value is not None and not isinstance(value, str):
                value = str(value)
        elif t in ("str", "e"):
            value = v
        elif t == "b":
            value = v.strip() in ("1", "true")
        elif t == "d":
            try:
                value = _dt.datetime.fromisoformat(v)
            except ValueError:
                value = _dt.datetime(1900, 1, 1)  # only its being a date matters
        else:
            try:
                value = float(v)
            except ValueError:
                value = v
            s = self._attrs.get("s")
            if s is not None and s.isdigit():
                si = int(s)
                if si in self.date_styles and isinstance(value, float):
                    try:
                        value = self.epoch + _dt.timedelta(days=value)
                    except OverflowError:
                        value = _dt.datetime(1900, 1, 1)
                elif si in self.percent_styles:
                    self.percent.add(pos)
        if value is None:
            return
        self.rows.setdefault(self._row, {})[self._col] = value

    def grid(self, label: str) -> _Grid:
        n = max(self.rows, default=0)
        rows: list[Sequence[Any]] = []
        for r in range(1, n + 1):
            cells = self.rows.get(r)
            if not cells:
                rows.append(())
                continue
            line = [None] * max(cells)
            for c, v in cells.items():
                line[c - 1] = v
            rows.append(line)
        return _Grid(
            label,
            rows,
            merged=self.merged,
            formula_without_value=self.formula_missing,
            percent_cells=self.percent,
        )


def _percent_styles(wb: Any) -> set[int]:
    """Style ids (``s=``) whose number format shows a percentage."""
    out = set()
    try:
        from openpyxl.styles.numbers import BUILTIN_FORMATS

        custom = list(wb._number_formats)
        for i, style in enumerate(wb._cell_styles):
            fid = style.numFmtId
            fmt = (
                BUILTIN_FORMATS.get(fid)
                if fid < 164
                else (custom[fid - 164] if fid - 164 < len(custom) else None)
            )
            if fmt and "%" in str(fmt):
                out.add(i)
    except Exception:  # styles are a convenience; never fail an import on them
        return set()
    return out


def _read_xlsx(path: Path) -> list[_Grid]:
    """Every sheet of a workbook as a grid.

    openpyxl (which uses defusedxml when it is installed) reads the workbook part: sheet
    names and order, shared strings, number formats. The worksheets themselves are
    streamed by :class:`_SheetReader` (expat, DTDs refused) — openpyxl's cell reader
    takes several times longer on a 10,000-row table.
    """
    sheets_xml = _inspect_xlsx(path)
    try:
        import openpyxl
    except ImportError:  # pragma: no cover - a declared dependency
        raise InputError(
            path.name, "reading .xlsx needs openpyxl: pip install openpyxl defusedxml"
        ) from None
    if not getattr(openpyxl, "DEFUSEDXML", False):  # pragma: no cover
        raise InputError(path.name, "reading .xlsx safely needs defusedxml: pip install defusedxml")
    try:
        wb = openpyxl.load_workbook(path, read_only=True, data_only=True, keep_links=False)
    except Exception as exc:  # openpyxl raises many types for broken files
        kind = type(exc).__name__
        cause: BaseException | None = exc
        while cause is not None:  # openpyxl wraps defusedxml's refusal in a ValueError
            if any(w in type(cause).__name__ for w in ("Forbidden", "DTD", "Entit")):
                raise _fail(
                    path.name,
                    f"declares a DTD or XML entities ({type(cause).__name__}); refused",
                    "Excel never writes these: the file was made by something else",
                ) from None
            cause = cause.__cause__ or cause.__context__
        raise _fail(
            path.name,
            f"cannot be read as an .xlsx workbook ({kind}: {exc})",
            'open it in Excel and save it as "Excel Workbook (*.xlsx)"',
        ) from None
    grids = []
    try:
        date_styles = set(getattr(wb, "_date_formats", ())) | set(
            getattr(wb, "_timedelta_formats", ())
        )
        pct_styles = _percent_styles(wb)
        epoch = _dt.datetime(1899, 12, 30)
        if getattr(wb, "epoch", None) == _dt.datetime(1904, 1, 1):
            epoch = _dt.datetime(1904, 1, 1)
        for ws in wb.worksheets:
            if (
                getattr(ws, "sheet_state", "visible") != "visible"
                and _match(_SHEET_INDEX, ws.title) is None
            ):
                continue
            member = str(getattr(ws, "_worksheet_path", "")).lstrip("/")
            data = sheets_xml.get(member)
            if data is None:
                raise _fail(
                    path.name,
                    f"sheet {ws.title!r} has no worksheet part ({member or '?'})",
                    "open it in Excel and save it again",
                )
            reader = _SheetReader(
                getattr(ws, "_shared_strings", []),
                date_styles,
                pct_styles,
                MAX_ROWS + HEADER_SCAN_ROWS,
                epoch,
            )
            try:
                reader.parse(data)
            except _Refused:
                if reader.too_many:
                    raise _fail(
                        _Grid(ws.title, []).address(reader.too_many, 1),
                        f"sheet {ws.title!r} has more than {MAX_ROWS:,} rows",
                        "delete unused rows below the table or split it",
                    ) from None
                raise _fail(
                    path.name,
                    f"sheet {ws.title!r} declares a DTD or XML entities; refused",
                    "Excel never writes these",
                ) from None
            except Exception as exc:  # expat errors on a damaged sheet
                raise _fail(
                    path.name,
                    f"sheet {ws.title!r} cannot be read ({type(exc).__name__}: {exc})",
                    "open it in Excel and save it again",
                ) from None
            grids.append(reader.grid(ws.title))
    finally:
        wb.close()
    return grids


def _decode_text(data: bytes) -> str:
    if data.startswith((b"\xff\xfe", b"\xfe\xff")):
        return data.decode("utf-16")
    try:
        return data.decode("utf-8-sig")
    except UnicodeDecodeError:
        return data.decode("cp1251")  # a Russian-locale Excel "CSV (разделители - запятые)"


def _read_csv_grid(path: Path) -> _Grid:
    """A CSV (UTF-8, UTF-16 or cp1251; comma, semicolon or tab separated) as a grid."""
    text = _decode_text(path.read_bytes())
    sample = "\n".join(text.splitlines()[: HEADER_SCAN_ROWS + 5])
    counts = {d: sample.count(d) for d in (";", "\t", ",")}
    try:
        delim = csv.Sniffer().sniff(sample, delimiters=";\t,").delimiter
    except csv.Error:
        delim = max(counts, key=lambda d: counts[d])
    # a Russian Excel writes ";" and decimal commas: prefer ";" when it is on every line
    if delim == "," and counts[";"] and all(";" in ln for ln in sample.splitlines() if ln):
        delim = ";"
    rows = []
    for i, row in enumerate(csv.reader(io.StringIO(text, newline=""), delimiter=delim)):
        if i > MAX_ROWS + HEADER_SCAN_ROWS:
            raise _fail(
                path.name,
                f"has more than {MAX_ROWS:,} rows",
                "split the table or delete unused rows",
            )
        rows.append(tuple(row))
    return _Grid(path.stem, rows)


# =========================================================================================
# Assembling a set
# =========================================================================================


@dataclass(frozen=True)
class ParsedNormSet:
    """A checked norm set, ready to write.

    Attributes
    ----------
    source_file : str
        Name of the file it came from.
    tables : dict
        Table name → rows (dicts of schema column → canonical text), ready for CSV.
    meta : dict
        ``title``, ``title_ru``, ``source`` (from the workbook's ``set`` sheet or the base).
    base : str or None
        The base set the file was merged onto.
    from_file : tuple of str
        Tables the file supplied (the rest came from ``base``).
    warnings : tuple of str
        Notes (ignored sheets and columns).
    """

    source_file: str
    tables: dict[str, list[dict[str, str]]]
    meta: dict[str, str]
    base: str | None = None
    from_file: tuple[str, ...] = ()
    warnings: tuple[str, ...] = ()

    def counts(self) -> dict[str, int]:
        """Rows per table."""
        return {k: len(v) for k, v in self.tables.items()}


def _base_tables(base: str) -> tuple[dict[str, _Table], dict[str, str], str]:
    """The tables of a base norm set (as grids read from its CSV files)."""
    ns = _norms.load_norm_set(base)  # checks it and resolves name or path
    tables: dict[str, _Table] = {}
    scratch = _Problems()
    for spec in TABLES.values():
        p = ns.path / spec.file
        if not p.is_file():
            continue
        with p.open(encoding="utf-8", newline="") as fh:
            rows = [tuple(r) for r in csv.reader(fh)]
        grid = _Grid(p.stem, rows, file_label=f"{ns.name}/{spec.file}")
        loc = _find_header(grid, spec, scratch)
        if loc is not None:
            tables[spec.name] = _data_rows(loc, scratch)
    if scratch.total:  # the loader accepted it, so this would be a bug
        raise NormImportError(f"base set {base}", scratch.items, scratch.total)
    meta = {"title": ns.title, "title_ru": ns.title_ru, "source": ns.source}
    return tables, meta, ns.name


def _locate_csv_table(grid: _Grid, table: str | None, name: str) -> _Located:
    problems = _Problems()
    if table:
        spec = _ALL_TABLES.get(table) or _ALL_TABLES.get(_match(_SHEET_INDEX, table) or "")
        if spec is None or spec is META_TABLE:
            raise InputError("--table", f"unknown table {table!r}; one of {', '.join(TABLES)}")
        loc = _find_header(grid, spec, problems)
        problems.raise_if_any(name)
        assert loc is not None
        return loc
    by_name = _match(_SHEET_INDEX, grid.label)
    if by_name in TABLES:
        loc = _find_header(grid, TABLES[by_name], problems)
        problems.raise_if_any(name)
        assert loc is not None
        return loc
    scored = []
    for spec in TABLES.values():
        loc = _find_header(grid, spec, None)
        if loc is not None:
            scored.append((len(loc.columns) / len(spec.columns), len(loc.columns), loc))
    scored.sort(key=lambda t: (t[0], t[1]), reverse=True)
    if not scored:
        raise _fail(
            name,
            "its header row matches no norm table",
            "name the file after the table (objects.csv, ...) or give --table " + "|".join(TABLES),
        )
    if len(scored) > 1 and scored[0][:2] == scored[1][:2]:
        raise _fail(
            name,
            "its header row fits tables "
            f"{scored[0][2].spec.name!r} and {scored[1][2].spec.name!r} equally",
            "give --table",
        )
    return scored[0][2]


def _cross_checks(
    tables: dict[str, _Table], problems: _Problems, label: str, present: set[str]
) -> None:
    """The rules the loader checks across rows and tables, all collected."""
    for t in tables.values():
        seen: dict[tuple[str, ...], _Row] = {}
        for row in t.rows:
            if any(k not in row.values for k in t.spec.key):
                continue
            key = tuple(row.values[k] for k in t.spec.key)
            if key in seen:
                first = seen[key]
                problems.add(
                    row.problem(
                        t.spec.key[-1] if t.spec.name == "scanners" else t.spec.key[0],
                        f"duplicate {'/'.join(t.spec.key)}: the same as "
                        f"{first.grid.address(first.number, first.cols.get(t.spec.key[0], 1))}",
                        "keep one row per " + "/".join(t.spec.key),
                    )
                )
            else:
                seen[key] = row
    shapes = tables.get("shapes")
    shape_ids = [r.values["shape"] for r in shapes.rows if "shape" in r.values] if shapes else []
    by_ru = {}
    if shapes:
        for r in shapes.rows:
            for alt in (r.values.get("name_ru", ""), r.values.get("shape", "")):
                if alt:
                    by_ru.setdefault(alt.casefold(), r.values["shape"])

    def resolve_shape(row: _Row, column: str, what: str) -> None:
        if column not in row.values:
            return  # already reported
        given = row.values[column]
        if given in shape_ids or not shapes:
            return
        if given.casefold() in by_ru:
            row.values[column] = by_ru[given.casefold()]
            return
        problems.add(
            row.problem(
                column,
                f"{what} must be a shape of the shapes table ({', '.join(shape_ids) or 'none'})",
                "add it to the shapes sheet or fix the spelling",
            )
        )

    params = tables.get("parameters")
    if params is not None:
        for row in params.rows:
            if row.values.get("name") == "shape":
                resolve_shape(row, "value", "the default shape")
        defined = {r.values.get("name") for r in params.rows}
        missing = [p for p in PARAMETERS if p not in defined]
        if missing:
            g = params.grid
            last = max((r.number for r in params.rows), default=params.header_row) + 1
            for p in missing:
                spec = PARAMETERS[p]
                problems.add(
                    ImportProblem(
                        g.address(last, params.cols.get("name", 1), "name"),
                        f"missing parameter {p!r} ({spec.description}); must be "
                        f"{spec.value.describe()}",
                        hint=f'add a row "{p}"'
                        + (f' (or "{spec.aliases[-1]}")' if spec.aliases else ""),
                    )
                )
    objects = tables.get("objects")
    if objects is not None:
        for row in objects.rows:
            resolve_shape(row, "shape", f"the shape of {row.values.get('object', '')!r}")
    for name in ("parameters", "shapes", "objects"):
        if name not in tables and name not in present:  # a broken sheet is reported already
            spec = TABLES[name]
            problems.add(
                ImportProblem(
                    label,
                    f"no sheet for table {name!r} ({spec.description})",
                    hint=f'add a sheet named "{spec.name}" or "{spec.title_ru}", or import '
                    "with --base NAME to take it from another set",
                )
            )


def read_norm_file(
    path: str | os.PathLike[str], *, table: str | None = None, base: str | None = None
) -> ParsedNormSet:
    """Read and check a norm workbook (.xlsx) or a single-table CSV.

    Parameters
    ----------
    path : str or path
        The file. ``.xlsx``/``.xlsm``: one sheet per table (sheet names are table names
        or their Russian titles). ``.csv``/``.txt``/``.tsv``: one table.
    table : str, optional
        The table a CSV holds (default: from the file name, else from its headers).
    base : str, optional
        A norm set (name or folder) supplying what the file lacks. A CSV is always merged
        onto a base (default the bundled set); a workbook only when ``base`` is given.
        Merging replaces whole tables, except ``parameters``, which merge by name.

    Returns
    -------
    ParsedNormSet

    Raises
    ------
    NormImportError
        Listing every problem (cell address, header, value, rule, hint).
    InputError
        For an unreadable file, or one over the size limits.
    """
    p = Path(path)
    _check_file(p)
    suffix = p.suffix.lower()
    problems = _Problems()
    warnings: list[str] = []
    located: list[_Located] = []
    present: set[str] = set()
    meta_loc: _Located | None = None
    if suffix in XLSX_SUFFIXES:
        grids = _read_xlsx(p)
        seen: dict[str, str] = {}
        for g in grids:
            name = _match(_SHEET_INDEX, g.label)
            if name is None:
                warnings.append(
                    f"sheet {g.label!r} ignored (not a norm table: {', '.join(_ALL_TABLES)})"
                )
                continue
            if name in seen:
                problems.add(
                    ImportProblem(
                        g.address(1, 1),
                        f"a second sheet for table {name!r} (the first is {seen[name]!r})",
                        hint="delete or rename one of them",
                    )
                )
                continue
            seen[name] = g.label
            present.add(name)
            loc = _find_header(g, _ALL_TABLES[name], problems)
            if loc is None:
                continue
            if name == META_TABLE.name:
                meta_loc = loc
            else:
                located.append(loc)
    elif suffix in CSV_SUFFIXES:
        located.append(_locate_csv_table(_read_csv_grid(p), table, p.name))
        base = base or _norms.DEFAULT_NORM_SET
    elif suffix == ".xls":
        raise _fail(
            p.name,
            "is an old binary Excel file (.xls)",
            'save it from Excel as "Excel Workbook (*.xlsx)"',
        )
    else:
        raise _fail(p.name, f"unknown file type {suffix or '(none)'}; give .xlsx or .csv")

    for loc in located:
        known = {c for c, _ in loc.columns.values()}
        for c in range(1, loc.grid.width(loc.header_row) + 1):
            h = loc.grid.value(loc.header_row, c)
            if c not in known and not _is_empty(h):
                warnings.append(
                    f'{loc.grid.address(loc.header_row, c)}: column "{h}" '
                    "ignored (not a column of table "
                    f"{loc.spec.name!r})"
                )
    file_tables = {loc.spec.name: _data_rows(loc, problems) for loc in located}

    meta = {k: "" for k in META_KEYS}
    base_name = None
    tables: dict[str, _Table] = {}
    if base:
        tables, base_meta, base_name = _base_tables(base)
        meta["source"] = f"base set {base_name}" + (
            f": {base_meta['source']}" if base_meta["source"] else ""
        )
    if meta_loc is not None:
        for row in _data_rows(meta_loc, problems).rows:
            key = _norm(row.values.get("key", "")).replace(" ", "_")
            if key in META_KEYS:
                meta[key] = row.values.get("value", "")
            else:
                warnings.append(
                    f"{row.grid.address(row.number, row.cols['key'])}: "
                    f"key {row.values.get('key')!r} ignored ({', '.join(META_KEYS)})"
                )
    for name, t in file_tables.items():
        if name == "parameters" and name in tables:  # merge by parameter name
            given = {r.values.get("name") for r in t.rows}
            kept = [r for r in tables[name].rows if r.values["name"] not in given]
            t.rows = kept + t.rows
        tables[name] = t
    _cross_checks(tables, problems, p.name, present)
    problems.raise_if_any(p.name)
    order = [n for n in TABLES if n in tables]
    canonical = {
        n: [{c.name: r.values.get(c.name, "") for c in TABLES[n].columns} for r in tables[n].rows]
        for n in order
    }
    return ParsedNormSet(p.name, canonical, meta, base_name, tuple(file_tables), tuple(warnings))


# =========================================================================================
# Writing a set
# =========================================================================================

_SAFE_NAME = re.compile(r"[\w][\w.\-]{0,63}")
_RESERVED = frozenset(
    ("con", "prn", "aux", "nul", *(f"com{i}" for i in range(10)), *(f"lpt{i}" for i in range(10)))
)


def check_set_name(name: str) -> str:
    """Return ``name`` if it is a safe, free-to-use norm-set folder name.

    Parameters
    ----------
    name : str
        Letters, digits, ``_``, ``-``, ``.``; starts with a letter, digit or ``_``; at most
        64 characters; not ``..``; not a bundled set's name or ``catalogue``.

    Raises
    ------
    InputError
        Field ``--name``.
    """
    if (
        not isinstance(name, str)
        or not _SAFE_NAME.fullmatch(name)
        or ".." in name
        or name.split(".")[0].casefold() in _RESERVED
        or name.endswith(".")
    ):
        raise InputError(
            "--name",
            f"{name!r} is not a safe set name: use letters, digits, "
            "'_', '-' and '.', start with a letter or digit, at most 64 "
            "characters (e.g. my-enterprise-2024)",
        )
    bundled = _norms.bundled_norms_dir()
    taken = {p.name.casefold() for p in bundled.iterdir() if p.is_dir()} | {_norms.CATALOGUE}
    if name.casefold() in taken:
        raise InputError(
            "--name",
            f"{name!r} is a bundled norm set; choose another name "
            "(a user set must not shadow a bundled one)",
        )
    return name


def _now_iso() -> str:
    epoch = os.environ.get("SOURCE_DATE_EPOCH")
    if epoch:
        try:
            when = _dt.datetime.fromtimestamp(int(epoch), _dt.UTC)
        except (ValueError, OverflowError):
            raise InputError("SOURCE_DATE_EPOCH", f"must be an integer (got {epoch!r})") from None
    else:
        when = _dt.datetime.now(_dt.UTC)
    return when.replace(microsecond=0).isoformat().replace("+00:00", "Z")


def _toml_str(s: str) -> str:
    return json.dumps(s, ensure_ascii=False)  # a JSON string is a TOML basic string


def _write_file(path: Path, text: str) -> None:
    with open(path, "w", encoding="utf-8", newline="") as fh:
        fh.write(text)
        fh.flush()
        os.fsync(fh.fileno())


def _csv_text(spec: TableSpec, rows: Sequence[Mapping[str, str]]) -> str:
    buf = io.StringIO()
    w = csv.writer(buf, lineterminator="\n")
    w.writerow([c.name for c in spec.columns])
    for r in rows:
        w.writerow([r.get(c.name, "") for c in spec.columns])
    return buf.getvalue()


def write_norm_set(
    parsed: ParsedNormSet,
    name: str,
    *,
    force: bool = False,
    root: str | os.PathLike[str] | None = None,
    title: str | None = None,
) -> Path:
    """Write a checked set as a user norm set, atomically.

    The set is written to a temporary folder next to the target (same file system),
    loaded back with the regular loader, and renamed into place. With ``force`` an
    existing set is moved aside, the new one renamed in, and the old one deleted (restored
    if the rename fails). Any failure leaves the norm directory as it was.

    Parameters
    ----------
    parsed : ParsedNormSet
        From :func:`read_norm_file`.
    name : str
        Set name (see :func:`check_set_name`).
    force : bool
        Replace an existing user set of that name.
    root : path, optional
        Norm directory (default :func:`scanplan.norms.user_norms_dir`).
    title : str, optional
        Overrides the title.

    Returns
    -------
    Path
        The set's folder.
    """
    check_set_name(name)
    root_dir = Path(root) if root is not None else _norms.user_norms_dir()
    target = root_dir / name
    if target.exists() and not force:
        raise InputError(
            "--name", f"norm set {name!r} already exists ({target}); give --force to replace it"
        )
    root_dir.mkdir(parents=True, exist_ok=True)
    meta = dict(parsed.meta)
    default_title = (
        f"{name}: imported from {parsed.source_file}"
        if not parsed.base
        else f"{meta.get('title') or parsed.base} with "
        f"{', '.join(parsed.from_file)} from {parsed.source_file}"
    )
    if title is not None:
        meta["title"] = title
    elif not meta.get("title"):
        meta["title"] = default_title
    toml = ["[set]", f"name = {_toml_str(name)}"]
    toml += [f"{k} = {_toml_str(meta.get(k, ''))}" for k in META_KEYS]
    toml += [
        f"imported_from = {_toml_str(parsed.source_file)}",
        f"imported_at = {_toml_str(_now_iso())}",
    ]
    if parsed.base:
        toml.append(f"base = {_toml_str(parsed.base)}")
    tmp = Path(tempfile.mkdtemp(prefix=f".{name}.tmp-", dir=root_dir))
    old: Path | None = None
    try:
        mask = os.umask(0o022)
        os.umask(mask)
        os.chmod(tmp, 0o777 & ~mask)  # mkdtemp makes 0700; a set folder is an ordinary one
        for tname, rows in parsed.tables.items():
            _write_file(tmp / TABLES[tname].file, _csv_text(TABLES[tname], rows))
        _write_file(tmp / "set.toml", "\n".join(toml) + "\n")
        _norms.read_norm_set_folder(tmp.resolve())  # the loader must accept it
        if target.exists():
            old = Path(tempfile.mkdtemp(prefix=f".{name}.old-", dir=root_dir))
            old.rmdir()
            os.replace(target, old)
            try:
                os.replace(tmp, target)
            except BaseException:
                os.replace(old, target)
                old = None
                raise
        else:
            os.replace(tmp, target)
    except BaseException:
        shutil.rmtree(tmp, ignore_errors=True)
        raise
    if old is not None:
        shutil.rmtree(old, ignore_errors=True)
    return target


def import_norm_file(
    path: str | os.PathLike[str],
    name: str,
    *,
    force: bool = False,
    table: str | None = None,
    base: str | None = None,
    root: str | os.PathLike[str] | None = None,
    title: str | None = None,
) -> tuple[Path, ParsedNormSet]:
    """Read, check and write a norm file as user set ``name`` (nothing written on failure).

    Parameters are those of :func:`read_norm_file` and :func:`write_norm_set`.

    Returns
    -------
    (Path, ParsedNormSet)
        The set's folder and what was imported.
    """
    check_set_name(name)
    root_dir = Path(root) if root is not None else _norms.user_norms_dir()
    if (root_dir / name).exists() and not force:
        raise InputError(
            "--name",
            f"norm set {name!r} already exists ({root_dir / name}); give --force to replace it",
        )
    parsed = read_norm_file(path, table=table, base=base)
    return write_norm_set(parsed, name, force=force, root=root_dir, title=title), parsed


# =========================================================================================
# Showing a set, and the template
# =========================================================================================


def _raw_csv(path: Path) -> list[dict[str, str]]:
    if not path.is_file():
        return []
    with path.open(encoding="utf-8", newline="") as fh:
        return [dict(r) for r in csv.DictReader(fh)]


def _typed(text: object, spec: ValueSpec) -> Any:
    """A canonical text as the value a cell should hold (number or text)."""
    if text is None or text == "":
        return None
    if spec.kind == "int":
        return int(float(str(text)))
    if spec.kind == "float":
        return float(str(text))
    if spec.kind == "list" and isinstance(text, tuple | list):
        return ",".join(text)
    return str(text)


def _set_rows(ns: Any, catalogue: bool = True) -> dict[str, list[dict[str, Any]]]:
    """Table name → rows of typed values (numbers as numbers) of a loaded norm set."""
    raw_params = {r.get("name", ""): r for r in _raw_csv(ns.path / "parameters.csv")}
    out: dict[str, list[dict[str, Any]]] = {"parameters": [], "shapes": [], "objects": []}
    for pname, spec in PARAMETERS.items():
        v = ns.parameters[pname]
        raw = raw_params.get(pname, {})
        out["parameters"].append(
            {
                "name": pname,
                "value": _typed(v, spec.value),
                "unit": raw.get("unit") or spec.value.unit,
                "source": ns.parameter_sources.get(pname, ""),
                "note": raw.get("note", ""),
            }
        )
    sh = TABLES["shapes"]
    for row in ns.shape_rows.values():
        out["shapes"].append({c.name: _typed(row.get(c.name, ""), c.value) for c in sh.columns})
    for o in ns.objects:
        out["objects"].append(
            {
                "map_scale": o.map_scale,
                "object": o.name,
                "object_ru": o.name_ru or None,
                "size_m": o.size_m,
                "shape": o.shape,
                "source": o.source or None,
            }
        )
    if not catalogue:
        return out
    cam_cols = [c.name for c in TABLES["cameras"].columns]
    out["cameras"] = [
        {k: (v if v != "" else None) for k, v in dataclasses.asdict(c).items() if k in cam_cols}
        for c in sorted(ns.cameras.values(), key=lambda c: c.id)
    ]
    src: dict[tuple[str, float], str] = {}
    for folder in (_norms.bundled_norms_dir() / _norms.CATALOGUE, ns.path):
        for r in _raw_csv(folder / "scanners.csv"):
            try:
                src[(r["scanner"], float(r["pixel_um"]))] = r.get("source", "")
            except (KeyError, ValueError):
                continue
    out["scanners"] = [
        {
            "scanner": s,
            "name": ns.scanner_names.get(s, s),
            "pixel_um": px,
            "source": src.get((s, px)) or None,
        }
        for s in sorted(ns.scanners)
        for px in ns.scanners[s]
    ]
    return out


def norm_set_dict(ns: Any) -> dict[str, Any]:
    """A loaded :class:`scanplan.norms.NormSet` as plain JSON-ready data.

    Parameters
    ----------
    ns : NormSet

    Returns
    -------
    dict
        ``name``, ``title``, ``title_ru``, ``source``, ``path``, ``bundled``,
        ``imported_from``, ``imported_at``, ``parameters`` (name → value, unit, source,
        description) and ``shapes``, ``objects``, ``cameras``, ``scanners`` as row lists.
    """
    rows = _set_rows(ns)
    params = {
        r["name"]: {
            "value": (
                list(ns.parameters[r["name"]])
                if isinstance(ns.parameters[r["name"]], tuple)
                else ns.parameters[r["name"]]
            ),
            "unit": r["unit"],
            "source": r["source"],
            "description": PARAMETERS[r["name"]].description,
        }
        for r in rows.pop("parameters")
    }
    return {
        "name": ns.name,
        "title": ns.title,
        "title_ru": ns.title_ru,
        "source": ns.source,
        "path": str(ns.path),
        "bundled": ns.bundled,
        "imported_from": ns.imported_from,
        "imported_at": ns.imported_at,
        "parameters": params,
        **rows,
    }


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
    columns and parameter values, and fitted column widths. Written to a temporary file and
    renamed into place.

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
    from openpyxl.comments import Comment
    from openpyxl.styles import Alignment, Font, PatternFill
    from openpyxl.worksheet.datavalidation import DataValidation

    out = Path(path)
    if out.suffix.lower() != ".xlsx":
        raise InputError("FILE", f"the template must be an .xlsx file (got {out.name!r})")
    if lang not in ("en", "ru"):
        raise InputError("--lang", f"must be en or ru (got {lang!r})")
    if out.exists() and not force:
        raise InputError("FILE", f"{out} exists; give --force to overwrite it")
    ns = _norms.load_norm_set(norm_set)
    data = _set_rows(ns, catalogue)
    wb = Workbook()
    wb.remove(wb.active)
    bold, fill = Font(bold=True), PatternFill("solid", fgColor="DDEBF7")
    for tname, rows in data.items():
        spec = TABLES[tname]
        ws = wb.create_sheet(spec.title_ru if lang == "ru" else spec.name)
        for ci, col in enumerate(spec.columns, start=1):
            cell = ws.cell(row=1, column=ci, value=_header_text(col, lang))
            cell.font, cell.fill = bold, fill
            cell.alignment = Alignment(wrap_text=True, vertical="top")
            unit = col.value.unit
            rule = (
                "rule depends on the parameter (see the note on its value cell)"
                if tname == "parameters" and col.name == "value"
                else col.value.describe()
            )
            text = f"{col.name}: {col.description}\nunit: {unit or '-'}\nrule: {rule}" + (
                "\nrequired" if col.value.required else "\noptional"
            )
            cell.comment = Comment(text, "scanplan", width=320, height=120)
        for ri, row in enumerate(rows, start=2):
            for ci, col in enumerate(spec.columns, start=1):
                ws.cell(row=ri, column=ci, value=row.get(col.name))
        widths = [
            len(str(ws.cell(row=1, column=ci).value)) for ci in range(1, len(spec.columns) + 1)
        ]
        for row in rows:
            for ci, col in enumerate(spec.columns):
                widths[ci] = max(widths[ci], len(_shown(row.get(col.name))))
        for ci, w in enumerate(widths, start=1):
            ws.column_dimensions[_col_letter(ci)].width = min(max(w + 2, 8), 60)
        ws.freeze_panes = "A2"
        for ci, col in enumerate(spec.columns, start=1):
            if col.value.kind in ("float", "int"):
                dv = _validation(DataValidation, col.value, col.name)
                dv.add(f"{_col_letter(ci)}2:{_col_letter(ci)}{max(len(rows) + 500, 1000)}")
                ws.add_data_validation(dv)
            elif col.value.kind == "choice":
                dv = DataValidation(
                    type="list",
                    formula1='"' + ",".join(col.value.choices) + '"',
                    allow_blank=not col.value.required,
                )
                dv.add(f"{_col_letter(ci)}2:{_col_letter(ci)}{max(len(rows) + 500, 1000)}")
                ws.add_data_validation(dv)
        if tname == "parameters":
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
                    dv = DataValidation(
                        type="list", formula1='"' + ",".join(pspec.value.choices) + '"'
                    )
                else:
                    continue
                dv.add(f"{vcol}{ri}")
                ws.add_data_validation(dv)
    ws = wb.create_sheet(META_TABLE.title_ru if lang == "ru" else META_TABLE.name)
    for ci, col in enumerate(META_TABLE.columns, start=1):
        c = ws.cell(row=1, column=ci, value=_header_text(col, lang))
        c.font, c.fill = bold, fill
    for ri, key in enumerate(META_KEYS, start=2):
        ws.cell(row=ri, column=1, value=key)
        ws.cell(row=ri, column=2, value=getattr(ns, key) or None)
    ws.column_dimensions["A"].width = 12
    ws.column_dimensions["B"].width = 100
    ws.freeze_panes = "A2"
    out.parent.mkdir(parents=True, exist_ok=True)
    fd, tmp_name = tempfile.mkstemp(prefix=f".{out.stem}.", suffix=".xlsx.tmp", dir=out.parent)
    os.close(fd)
    try:
        wb.save(tmp_name)
        os.replace(tmp_name, out)
    except BaseException:
        Path(tmp_name).unlink(missing_ok=True)
        raise
    return out


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

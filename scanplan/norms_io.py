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
recover_norm_dir
    Finish or undo an import a crash interrupted (``.NAME.old-*``, ``.NAME.tmp-*``).
write_template
    The template workbook.
norm_set_dict
    A norm set as plain data (``scanplan norms show --json``).
check_set_name
    Refuse unsafe or shadowing set names.

openpyxl is imported lazily: the rest of scanplan never needs it.
"""

from __future__ import annotations

import bisect
import contextlib
import csv
import dataclasses
import datetime as _dt
import io
import json
import math
import os
import re
import secrets
import shutil
import stat
import tempfile
import zipfile
import zlib
from collections.abc import Iterable, Iterator, Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from . import norms as _norms
from .errors import InputError, NotFoundError, WriteError
from .normschema import PARAMETERS, TABLES, ColumnSpec, TableSpec, ValueSpec
from .reports import write_atomic
from .safeio import dir_lock, file_kind, fsync_dir, read_limited, write_all

__all__ = [
    "HEADER_SCAN_ROWS",
    "MAX_CELLS",
    "MAX_CELL_CHARS",
    "MAX_COLUMNS",
    "MAX_COMPRESSION_RATIO",
    "MAX_CSV_ROW_CHARS",
    "MAX_ERRORS_SHOWN",
    "MAX_FILE_BYTES",
    "MAX_MEMBER_BYTES",
    "MAX_MERGED",
    "MAX_ROWS",
    "MAX_TOTAL_UNCOMPRESSED_BYTES",
    "MAX_ZIP_DIRECTORY_BYTES",
    "MAX_ZIP_MEMBERS",
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
    "recover_norm_dir",
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
MAX_COLUMNS = 256
"""Rightmost column a value may be in (IV, Excel 2003's last); a norm table has 14 at most."""
MAX_CELLS = 3_000_000
"""Most filled cells one workbook or CSV may have (bounds the memory a file can take)."""
MAX_MERGED = 1_000
"""Most merged cell ranges one sheet may have."""
MAX_CELL_CHARS = 32_767
"""Longest text one cell may hold (Excel's own limit)."""
MAX_CSV_ROW_CHARS = 1_000_000
"""Longest row of a CSV, all its lines [characters]."""
MAX_ZIP_MEMBERS = 10_000
"""Most parts (zip members) an .xlsx may have."""
MAX_PART_ELEMENTS = 100_000
"""Most XML elements in a workbook part other than a worksheet or the shared strings
(styles, workbook, relationships, ...; Excel itself keeps at most 64,000 cell styles)."""
MAX_STRINGS_ELEMENTS = 600_000
"""Most XML elements in the shared strings part: 200,000 distinct texts of up to three
elements each (about 5 s and 100 MB to read)."""
MAX_ZIP_DIRECTORY_BYTES = 2 * 1024 * 1024
"""Largest zip directory of an .xlsx [bytes] (checked before it is parsed)."""

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

    def __post_init__(self) -> None:
        # text from the file is shown on a terminal: no control characters, no megabytes
        for name, limit in (("address", 300), ("message", 2000), ("header", 200)):
            object.__setattr__(self, name, _printable(getattr(self, name), limit))
        if self.value is not None:
            object.__setattr__(self, "value", _printable(self.value, 200))

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


_UNPRINTABLE = re.compile(r"[\x00-\x1f\x7f-\x9f\u202a-\u202e\u2066-\u2069]")


def _printable(text: str, limit: int) -> str:
    """``text`` safe to print: control (and bidi) characters escaped, cut at ``limit``."""
    text = _UNPRINTABLE.sub(lambda m: f"\\u{ord(m.group()):04x}", str(text))
    if len(text) > limit:
        text = text[:limit] + f"… ({len(text):,} characters)"
    return text


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


def _fail(source: str, message: str, hint: str = "", at: str | None = None) -> NormImportError:
    """One problem of file ``source``, at cell ``at`` (default: the file itself)."""
    return NormImportError(source, [ImportProblem(at or source, message, hint=hint)])


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
    if spec.kind == "text":
        _check_text(text)
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


_CONTROL = re.compile(r"[\x00-\x08\x0b\x0c\x0e-\x1f\x7f-\x9f]")
_FORMULA_START = "=+-@"


def _check_text(text: str) -> None:
    """Refuse text a norm set must not store (raise _Bad).

    A norm set is CSV files engineers open in Excel, and its text goes into workbooks:
    text starting with ``=``, ``+``, ``-`` or ``@`` would run as a formula there
    (``=HYPERLINK(...)``, ``+cmd|' /C calc'!A0``), so it is refused — numbers such as
    ``-2`` and a lone ``-`` are fine. Leading tabs and line breaks are trimmed before.
    Control characters (terminal escapes) and text longer than Excel's cell limit are
    refused too.
    """
    if len(text) > MAX_CELL_CHARS:
        raise _Bad(
            f"the text is {len(text):,} characters long; the limit is {MAX_CELL_CHARS:,} "
            "(Excel's, for one cell)",
            "shorten it",
        )
    bad = _CONTROL.search(text)
    if bad:
        raise _Bad(
            f"the text contains the control character U+{ord(bad.group()):04X}",
            "delete it (it comes with text copied from another program)",
        )
    if len(text) > 1 and text[0] in _FORMULA_START and not _NUMBER_RE.fullmatch(text):
        raise _Bad(
            f'text may not start with "{text[0]}": it would run as a formula in Excel '
            "(the norm set is stored as CSV files)",
            f'delete the leading "{text[0]}", or start the text with a letter or digit',
        )


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
    # vertical merges: column → sorted (first row, last row, value); looked up, not expanded
    _fill: dict[int, list[tuple[int, int, Any]]] = field(default_factory=dict)
    _fill_starts: dict[int, list[int]] = field(default_factory=dict)
    _group: dict[tuple[int, int], Any] = field(default_factory=dict)

    def __post_init__(self) -> None:
        n = len(self.rows)
        for r1, c1, r2, c2 in self.merged:
            if not (1 <= r1 <= n and 1 <= c1 <= MAX_COLUMNS) or r2 < r1 or c2 < c1:
                continue  # nothing there (a merge below the data or right of the limit)
            top = self.raw(r1, c1)
            r2, c2 = min(r2, n), min(c2, MAX_COLUMNS)
            if c1 == c2 and r2 > r1 and top is not None:  # every row of it shows the value
                self._fill.setdefault(c1, []).append((r1, r2, top))
            for r in range(r1, min(r2, HEADER_SCAN_ROWS) + 1):  # only headers use groups
                for c in range(c1, min(c2, c1 + 200) + 1):
                    self._group[(r, c)] = top
        for c, spans in self._fill.items():
            spans.sort(key=lambda s: s[0])
            self._fill_starts[c] = [s[0] for s in spans]

    def raw(self, r: int, c: int) -> Any:
        if r - 1 < len(self.rows):
            row = self.rows[r - 1]
            if c - 1 < len(row):
                return row[c - 1]
        return None

    def value(self, r: int, c: int) -> Any:
        v = self.raw(r, c)
        if v is None and c in self._fill:
            i = bisect.bisect_left(self._fill_starts[c], r) - 1
            if i >= 0:
                r1, r2, top = self._fill[c][i]
                if r1 < r <= r2:
                    return top
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
        [grid.width(r) for r in range(1, last_row + 1)] + list(grid._fill), default=0
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
        st = path.stat()
    except OSError as exc:
        raise NotFoundError(str(path), f"cannot be read: {exc.strerror or exc}") from None
    if not stat.S_ISREG(st.st_mode):
        raise InputError(
            str(path),
            f"is {file_kind(st.st_mode)}, not a regular file; give the workbook or CSV file",
        )
    size = st.st_size
    if size > MAX_FILE_BYTES:
        raise _fail(
            path.name,
            f"the file is {_size(size)}; the limit is {_size(MAX_FILE_BYTES)}",
            "a norm workbook is small: delete unused sheets, images and rows",
        )
    return size


# "<!DOCTYPE" / "<!ENTITY" in UTF-8 (or any ASCII-compatible encoding) and in UTF-16 LE/BE
_DOCTYPE = re.compile(
    rb"<!\s*(?:DOCTYPE|ENTITY)"
    rb"|<\x00!\x00(?:\s\x00)*(?:D\x00O\x00C\x00T\x00Y\x00P\x00E|E\x00N\x00T\x00I\x00T\x00Y)"
    rb"|\x00<\x00!(?:\x00\s)*\x00(?:D\x00O\x00C\x00T\x00Y\x00P\x00E|E\x00N\x00T\x00I\x00T\x00Y)",
    re.I,
)
_SCAN_OVERLAP = 64  # bytes of one chunk searched again with the next (a DTD split by a chunk)
_CHUNK = 1 << 20
_ZIP_ERRORS: tuple[type[BaseException], ...] = (
    zipfile.BadZipFile,
    zlib.error,
    OSError,
    EOFError,
    RuntimeError,  # an encrypted member
    NotImplementedError,  # an unknown compression method
)
try:
    import lzma

    _ZIP_ERRORS += (lzma.LZMAError,)
except ImportError:  # pragma: no cover - Python without lzma
    pass
_WIDEST_TABLE = max(len(t.columns) for t in TABLES.values())
_WORKSHEET = re.compile(r"xl/worksheets/[^/]+\.xml")  # checked while they are streamed


def _zip_directory_size(path: Path) -> int | None:
    """Size of a zip's central directory [bytes] from its end records (None: none found).

    Read before :class:`zipfile.ZipFile` parses the directory, whose every entry becomes an
    object: a 20 MB file of empty entries would cost seconds and 100+ MB.
    """
    with open(path, "rb") as fh:
        fh.seek(0, os.SEEK_END)
        size = fh.tell()
        n = min(size, 22 + 65535)
        fh.seek(size - n)
        tail = fh.read(n)
        i = tail.rfind(b"PK\x05\x06")
        if i < 0 or len(tail) - i < 22:
            return None
        cd = int.from_bytes(tail[i + 12 : i + 16], "little")
        if i >= 20 and tail[i - 20 : i - 16] == b"PK\x06\x07":  # zip64: its record wins
            fh.seek(int.from_bytes(tail[i - 12 : i - 4], "little"))
            rec = fh.read(56)
            if len(rec) == 56 and rec[:4] == b"PK\x06\x06":
                cd = max(cd, int.from_bytes(rec[40:48], "little"))
    return cd


def _inspect_xlsx(zf: zipfile.ZipFile, name: str) -> dict[str, zipfile.ZipInfo]:
    """Check an .xlsx before any XML parser sees it: zip limits, no DTD in any XML part.

    Every limit is checked on the zip directory first (nothing is decompressed for a zip
    bomb); then every XML part but the worksheets is streamed through the DTD check and
    dropped (worksheets are checked the same way while :func:`_read_xlsx` streams them).

    Returns
    -------
    dict
        Member name → its :class:`zipfile.ZipInfo`.
    """
    infos = zf.infolist()
    if len(infos) > MAX_ZIP_MEMBERS:
        raise _fail(
            name, f"has {len(infos):,} zip members (the limit is {MAX_ZIP_MEMBERS:,})",
            "not a norm workbook",
        )
    total = 0
    for info in infos:
        sheet = info.filename.startswith("xl/worksheets/")
        hint = (
            f"delete unused rows and columns: a norm table has at most {MAX_ROWS:,} rows"
            if sheet
            else "not a norm workbook"
        )
        if info.file_size > MAX_MEMBER_BYTES:
            raise _fail(
                name,
                f"zip member {info.filename} would unpack to {_size(info.file_size)}; the "
                f"limit is {_size(MAX_MEMBER_BYTES)}",
                hint,
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
        total += info.file_size
    if total > MAX_TOTAL_UNCOMPRESSED_BYTES:
        raise _fail(
            name,
            f"would unpack to {_size(total)}; the limit is "
            f"{_size(MAX_TOTAL_UNCOMPRESSED_BYTES)}",
            "not a norm workbook",
        )
    for info in infos:
        low = info.filename.lower()
        if _WORKSHEET.fullmatch(low) or not low.endswith((".xml", ".rels", ".vml")):
            continue
        limit = MAX_STRINGS_ELEMENTS if low == "xl/sharedstrings.xml" else MAX_PART_ELEMENTS
        _stream_member(zf, info, name, f"zip member {info.filename}", _ElementCount(
            name, info.filename, limit))
    return {i.filename: i for i in infos}


class _ElementCount:
    """A :func:`_stream_member` sink that refuses a part with more than ``limit`` XML
    elements (start tags): parsing styles or strings costs time and memory per element,
    so a small file with millions of them is refused before any parser sees it."""

    def __init__(self, name: str, member: str, limit: int) -> None:
        self.name, self.member, self.limit, self.n = name, member, limit, 0

    def __call__(self, chunk: bytes) -> None:
        self.n += chunk.count(b"<") - chunk.count(b"</")
        if self.n > self.limit:
            raise _fail(
                self.name,
                f"zip member {self.member} holds more than {self.limit:,} XML elements (the "
                "limit); refused without reading it",
                "not a norm workbook: Excel keeps at most 64,000 cell styles; open it in "
                "Excel, delete unused styles, and save it again",
            )


def _stream_member(
    zf: zipfile.ZipFile, info: zipfile.ZipInfo, name: str, part: str, sink: Any
) -> None:
    """Decompress one member in 1 MB chunks into ``sink``, refusing a DTD in any chunk
    (before ``sink`` sees it) and more bytes than :data:`MAX_MEMBER_BYTES`.

    Nothing is kept: memory is one chunk whatever the member's size. ``sink`` may raise
    to stop early (the rest is never decompressed).
    """
    got = 0
    tail = b""
    try:
        with zf.open(info) as fh:
            while chunk := fh.read(_CHUNK):
                got += len(chunk)
                if got > MAX_MEMBER_BYTES:
                    raise _fail(
                        name,
                        f"{part} unpacks to more than {_size(MAX_MEMBER_BYTES)}",
                        "not a norm workbook",
                    )
                window = tail + chunk
                if _DOCTYPE.search(window):
                    raise _fail(
                        name,
                        f"{part} declares a DTD or XML entities (entity expansion, "
                        "'billion laughs', external entities); refused, nothing was read",
                        "Excel never writes these: the file was made by something else",
                    )
                tail = window[-_SCAN_OVERLAP:]
                sink(chunk)
    except _ZIP_ERRORS as exc:
        raise _fail(
            name,
            f"is a damaged .xlsx ({info.filename}: {exc})",
            "open it in Excel and save it again",
        ) from None


class _Refused(Exception):
    """The XML declares a DTD or entities, or a sheet breaks a limit (see ``reason``)."""

    def __init__(self, reason: str = "dtd", where: tuple[int, int] = (0, 0)) -> None:
        super().__init__(reason)
        self.reason = reason
        self.where = where


def _refuse(*_: object) -> None:
    raise _Refused


class _SparseRow(Sequence[Any]):
    """A row with few values far apart (``A5`` and ``IV5``): stored as a dict, not a list."""

    __slots__ = ("cells", "n")

    def __init__(self, cells: dict[int, Any], n: int) -> None:
        self.cells = cells  # 1-based column → value
        self.n = n

    def __len__(self) -> int:
        return self.n

    def __getitem__(self, i: Any) -> Any:
        if isinstance(i, slice):
            return [self[j] for j in range(*i.indices(self.n))]
        if i < 0:
            i += self.n
        if not 0 <= i < self.n:
            raise IndexError(i)
        return self.cells.get(i + 1)


class _SheetReader:
    """Streams one worksheet's XML (expat, C speed) into rows of raw cell values.

    Values: str, float, bool, an Excel error string (``"#DIV/0!"``), ``datetime`` marker for
    date-formatted numbers. Also records merged ranges, formula cells without a cached
    value and percent-formatted cells. DTDs and entity declarations are refused, as
    defusedxml does. Feed it chunks (:meth:`feed`, :meth:`close`) or a whole part
    (:meth:`parse`).

    Limits (raise :class:`_Refused` with ``reason`` and the cell, and stop reading): a value
    below row ``max_rows`` ("rows"), right of column ``max_columns`` ("columns"), more than
    ``max_cells`` values ("cells"), more than :data:`MAX_MERGED` merged ranges ("merged").
    Empty rows and cells (formatting only) count for none of them.
    """

    def __init__(
        self,
        shared: Sequence[Any],
        date_styles: set[int],
        percent_styles: set[int],
        max_rows: int,
        epoch: _dt.datetime = _dt.datetime(1899, 12, 30),
        *,
        max_columns: int | None = None,
        max_cells: int | None = None,
    ) -> None:
        self.shared = shared
        self.epoch = epoch
        self.date_styles = date_styles
        self.percent_styles = percent_styles
        self.max_rows = max_rows
        self.max_columns = MAX_COLUMNS if max_columns is None else max_columns
        self.cells_left = MAX_CELLS if max_cells is None else max_cells
        self.rows: dict[int, dict[int, Any]] = {}
        self.merged: list[tuple[int, int, int, int]] = []
        self.formula_missing: set[tuple[int, int]] = set()
        self.percent: set[tuple[int, int]] = set()
        self._parser: Any = None
        self._row = 0
        self._col = 0
        self._attrs: dict[str, str] = {}
        self._text: list[str] | None = None
        self._v: str | None = None
        self._inline: list[str] = []
        self._has_f = False
        self._in_is = False
        self._in_rph = 0

    def _make_parser(self) -> Any:
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
        return p

    def feed(self, data: bytes) -> None:
        """Parse the next chunk of the part."""
        if self._parser is None:
            self._parser = self._make_parser()
        self._parser.Parse(data, False)

    def close(self) -> None:
        """The part is complete (expat reports a truncated one)."""
        if self._parser is None:
            self._parser = self._make_parser()
        self._parser.Parse(b"", True)

    def parse(self, data: bytes) -> None:
        """Parse a whole part."""
        self.feed(data)
        self.close()

    def _place(self, pos: tuple[int, int]) -> None:
        """Count a value at ``pos`` against the limits (refuse, and stop, past one)."""
        if pos[0] > self.max_rows:
            raise _Refused("rows", pos)
        if pos[1] > self.max_columns:
            raise _Refused("columns", pos)
        self.cells_left -= 1
        if self.cells_left < 0:
            raise _Refused("cells", pos)

    def _start(self, tag: str, attrs: dict[str, str]) -> None:
        tag = tag.rpartition(":")[2]
        if tag == "c":
            ref = attrs.get("r")
            if ref:
                m = re.fullmatch(r"([A-Z]{1,3})(\d{1,9})", ref)
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
            self._row = int(r) if r and r.isdigit() and len(r) < 10 else self._row + 1
            self._col = 0
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
            except ValueError:
                return
            if len(self.merged) >= MAX_MERGED:
                raise _Refused("merged", (r1, c1))
            self.merged.append((r1, c1, r2, c2))

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
                self._place(pos)
                self.formula_missing.add(pos)
            return
        elif t == "s":
            try:
                i = int(v)
            except ValueError:
                i = -1
            value = self.shared[i] if 0 <= i < len(self.shared) else None
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
                    except (OverflowError, ValueError):
                        value = _dt.datetime(1900, 1, 1)
                elif si in self.percent_styles:
                    self.percent.add(pos)
        if value is None or value == "":
            return
        self._place(pos)
        self.rows.setdefault(self._row, {})[self._col] = value

    def grid(self, label: str) -> _Grid:
        n = max(self.rows, default=0)
        rows: list[Sequence[Any]] = []
        for r in range(1, n + 1):
            cells = self.rows.get(r)
            if not cells:
                rows.append(())
                continue
            width = max(cells)
            if width > 2 * len(cells) + 16:  # a few values far apart: keep them sparse
                rows.append(_SparseRow(cells, width))
                continue
            line = [None] * width
            for c, v in cells.items():
                if c > 0:
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


def _sheet_refusal(exc: _Refused, title: str, name: str) -> NormImportError:
    """The message for a worksheet :class:`_SheetReader` refused."""
    r, c = exc.where
    at = _Grid(title, []).address(r, max(c, 1))
    if exc.reason == "rows":
        return _fail(
            name,
            f"sheet {title!r} has more than {MAX_ROWS:,} rows (a value in row {r:,}); "
            "refused without reading further",
            "delete unused rows below the table or split it",
            at=at,
        )
    if exc.reason == "columns":
        return _fail(
            name,
            f"a value in column {_col_letter(c)}, right of column {_col_letter(MAX_COLUMNS)} "
            f"(the limit; a norm table has at most {_WIDEST_TABLE} columns)",
            "delete the cells right of the table, or move notes to another sheet",
            at=at,
        )
    if exc.reason == "cells":
        return _fail(
            name,
            f"more than {MAX_CELLS:,} filled cells in the workbook; refused without reading "
            "further",
            "a norm workbook is small: delete unused rows, columns and sheets",
            at=at,
        )
    if exc.reason == "merged":
        return _fail(
            name,
            f"sheet {title!r} has more than {MAX_MERGED:,} merged cell ranges",
            "unmerge the cells (Home → Merge & Center → Unmerge Cells)",
            at=at,
        )
    return _fail(
        name,
        f"sheet {title!r} declares a DTD or XML entities; refused, nothing was read",
        "Excel never writes these",
    )


def _read_xlsx(path: Path) -> list[_Grid]:
    """Every sheet of a workbook as a grid (sheets that are no norm table: empty grids).

    openpyxl (which uses defusedxml when it is installed) reads the workbook part: sheet
    names and order, shared strings, number formats (:func:`_read_workbook_part`). The
    worksheets of norm tables are streamed from the zip by :class:`_SheetReader` (expat,
    DTDs refused) in 1 MB chunks, and reading stops at the first limit broken — a
    million-row sheet is refused after :data:`MAX_ROWS` rows, never held in memory. Other
    sheets are never read. openpyxl's cell reader takes several times longer on a
    10,000-row table.
    """
    name = path.name
    try:
        directory = _zip_directory_size(path)
    except OSError as exc:
        raise _fail(name, f"cannot be read ({exc.strerror or exc})") from None
    if directory is not None and directory > MAX_ZIP_DIRECTORY_BYTES:
        raise _fail(
            name,
            f"has a zip directory of {_size(directory)}; the limit is "
            f"{_size(MAX_ZIP_DIRECTORY_BYTES)}",
            "not a norm workbook",
        )
    try:
        zf = zipfile.ZipFile(path)
    except Exception as exc:  # BadZipFile, OSError, ValueError, ... for a file that is no zip
        raise _fail(
            name,
            f"is not an .xlsx workbook (not a zip file: {exc})",
            'save it from Excel as "Excel Workbook (*.xlsx)"',
        ) from None
    with zf:
        members = _inspect_xlsx(zf, name)
        book = _read_workbook_part(path, name)
        grids = []
        date_styles, pct_styles, epoch = book["date_styles"], book["percent_styles"], book["epoch"]
        cells_left = MAX_CELLS
        for title, state, member in book["sheets"]:
            table = _match(_SHEET_INDEX, title)
            if table is None:
                if state == "visible":
                    grids.append(_Grid(title, []))  # ignored (with a note), never read
                continue
            info = members.get(member)
            if info is None:
                raise _fail(
                    name,
                    f"sheet {title!r} has no worksheet part ({member or '?'})",
                    "open it in Excel and save it again",
                )
            reader = _SheetReader(
                book["shared"],
                date_styles,
                pct_styles,
                MAX_ROWS + HEADER_SCAN_ROWS,
                epoch,
                max_cells=cells_left,
            )
            part = f"sheet {title!r} (zip member {member})"
            try:
                _stream_member(zf, info, name, part, reader.feed)
                reader.close()
            except _Refused as exc:
                raise _sheet_refusal(exc, title, name) from None
            except InputError:
                raise
            except Exception as exc:  # expat errors on a damaged sheet
                raise _fail(
                    name,
                    f"sheet {title!r} cannot be read ({type(exc).__name__}: {exc})",
                    "open it in Excel and save it again",
                ) from None
            cells_left = reader.cells_left
            grids.append(reader.grid(title))
    return grids


def _read_workbook_part(path: Path, name: str) -> dict[str, Any]:
    """What openpyxl reads of a workbook: sheet names, states and parts, shared strings,
    date and percent styles, the date epoch.

    openpyxl parses these parts with defusedxml (its presence switches openpyxl to it). Its
    ``load_workbook`` would also parse the start of every worksheet — all of one without a
    ``<dimension>`` element, 12 s for a million rows — so only the parts needed are read,
    with openpyxl's own reader, and no worksheet is opened here.
    """
    try:
        import openpyxl
        from openpyxl.reader.excel import ExcelReader
        from openpyxl.styles.stylesheet import apply_stylesheet
    except ImportError:  # pragma: no cover - a declared dependency
        raise InputError(
            name, "reading .xlsx needs openpyxl: pip install openpyxl defusedxml"
        ) from None
    if not getattr(openpyxl, "DEFUSEDXML", False):  # pragma: no cover
        raise InputError(name, "reading .xlsx safely needs defusedxml: pip install defusedxml")
    reader = None
    try:
        reader = ExcelReader(path, read_only=True, keep_vba=False, data_only=True,
                             keep_links=False)
        reader.read_manifest()
        reader.read_strings()
        reader.read_workbook()
        wb = reader.wb
        apply_stylesheet(reader.archive, wb)
        sheets = [
            (str(sheet.name), str(sheet.state or "visible"), str(rel.target).lstrip("/"))
            for sheet, rel in reader.parser.find_sheets()
            if "chartsheet" not in str(rel.Type)
        ]
    except Exception as exc:  # openpyxl raises many types for broken files
        kind = type(exc).__name__
        cause: BaseException | None = exc
        while cause is not None:  # openpyxl wraps defusedxml's refusal in a ValueError
            if any(w in type(cause).__name__ for w in ("Forbidden", "DTD", "Entit")):
                raise _fail(
                    name,
                    f"declares a DTD or XML entities ({type(cause).__name__}); refused",
                    "Excel never writes these: the file was made by something else",
                ) from None
            cause = cause.__cause__ or cause.__context__
        raise _fail(
            name,
            f"cannot be read as an .xlsx workbook ({kind}: {exc})",
            'open it in Excel and save it as "Excel Workbook (*.xlsx)"',
        ) from None
    finally:
        if reader is not None:
            reader.archive.close()
    epoch = _dt.datetime(1899, 12, 30)
    if getattr(wb, "epoch", None) == _dt.datetime(1904, 1, 1):
        epoch = _dt.datetime(1904, 1, 1)
    return {
        "sheets": sheets,
        "shared": reader.shared_strings,
        "date_styles": set(getattr(wb, "_date_formats", ()))
        | set(getattr(wb, "_timedelta_formats", ())),
        "percent_styles": _percent_styles(wb),
        "epoch": epoch,
    }


def _decode_text(data: bytes, name: str = "the file") -> str:
    """The text of a CSV: UTF-16 (with a BOM), UTF-8 (BOM or not), else Windows-1251."""
    hint = 'save it from Excel as "CSV UTF-8 (Comma delimited) (*.csv)"'
    if data.startswith((b"\xff\xfe", b"\xfe\xff")):
        try:
            text = data.decode("utf-16")
        except UnicodeDecodeError as exc:
            raise _fail(
                name, f"is not valid UTF-16 text (byte {exc.start:,}: {exc.reason})", hint
            ) from None
    else:
        try:
            text = data.decode("utf-8-sig")
        except UnicodeDecodeError:
            try:  # a Russian-locale Excel "CSV (разделители - запятые)"
                text = data.decode("cp1251")
            except UnicodeDecodeError as exc:
                raise _fail(
                    name,
                    f"is neither UTF-8 nor Windows-1251 text (byte 0x{data[exc.start]:02X} at "
                    f"position {exc.start:,})",
                    hint,
                ) from None
    if "\x00" in text:
        raise _fail(
            name,
            "contains NUL characters: a binary file, or UTF-16 text without a byte-order mark",
            hint,
        )
    return text


_EOL = re.compile(r"\r\n|\r|\n")


class _RowTooLong(Exception):
    """A CSV row (with all its lines) is longer than :data:`MAX_CSV_ROW_CHARS`."""


def _read_csv_grid(path: Path) -> _Grid:
    """A CSV (UTF-8, UTF-16 or cp1251; comma, semicolon or tab separated) as a grid.

    Bounded: the file is read with a limit, a row may hold at most
    :data:`MAX_CSV_ROW_CHARS` characters (checked line by line, before the row is split),
    :data:`MAX_COLUMNS` columns and the file :data:`MAX_CELLS` values; reading stops at the
    first row past :data:`MAX_ROWS`.
    """
    name = path.name
    text = _decode_text(read_limited(path, MAX_FILE_BYTES, field=str(path)), name)
    head = text[: 64 * 1024]  # the separator is sniffed on the first lines only
    sample = "\n".join(head.splitlines()[: HEADER_SCAN_ROWS + 5])
    counts = {d: sample.count(d) for d in (";", "\t", ",")}
    try:
        delim = csv.Sniffer().sniff(sample, delimiters=";\t,").delimiter
    except csv.Error:
        delim = max(counts, key=lambda d: counts[d])
    # a Russian Excel writes ";" and decimal commas: prefer ";" when it is on every line
    if delim == "," and counts[";"] and all(";" in ln for ln in sample.splitlines() if ln):
        delim = ";"
    row_chars = [0]

    def lines() -> Iterator[str]:  # physical lines, each counted before it is cut out
        pos, end = 0, len(text)
        while pos < end:
            m = _EOL.search(text, pos)
            stop = m.end() if m else end
            row_chars[0] += stop - pos
            if row_chars[0] > MAX_CSV_ROW_CHARS:
                raise _RowTooLong
            yield text[pos:stop]
            pos = stop

    label = _Grid(path.stem, [])
    rows: list[Sequence[str]] = []
    cells = 0
    reader = csv.reader(lines(), delimiter=delim)
    try:
        for row in reader:
            row_chars[0] = 0
            n = len(rows) + 1
            if n > MAX_ROWS + HEADER_SCAN_ROWS:
                raise _fail(
                    name,
                    f"more than {MAX_ROWS:,} rows (row {n:,} is past the limit); refused "
                    "without reading further",
                    "split the table or delete unused rows",
                    at=label.address(n, 1),
                )
            while row and not row[-1]:  # Excel pads rows with separators
                row.pop()
            if len(row) > MAX_COLUMNS:
                raise _fail(
                    name,
                    f"row {n:,} has {len(row):,} columns; the limit is {MAX_COLUMNS} (a norm "
                    f"table has at most {_WIDEST_TABLE})",
                    "delete the columns right of the table",
                    at=label.address(n, MAX_COLUMNS + 1),
                )
            cells += sum(1 for v in row if v)
            if cells > MAX_CELLS:
                raise _fail(
                    name,
                    f"more than {MAX_CELLS:,} filled cells; refused without reading further",
                    "a norm table is small: delete unused rows and columns",
                    at=label.address(n, 1),
                )
            rows.append(tuple(row))
    except _RowTooLong:
        raise _fail(
            name,
            f"row {len(rows) + 1:,} is longer than {MAX_CSV_ROW_CHARS:,} characters (a "
            "runaway quote, or not a CSV file)",
            "check the quotes in that row; a norm table row is short",
            at=label.address(len(rows) + 1, 1),
        ) from None
    except csv.Error as exc:
        raise _fail(
            name,
            f"cannot be read as CSV (line {reader.line_num:,}: {exc})",
            f"one cell holds at most {MAX_CELL_CHARS:,} characters; check the quotes",
            at=label.address(len(rows) + 1, 1),
        ) from None
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
        if not present:  # an import that takes nothing from the file is an error
            sheets = ", ".join(repr(_printable(g.label, 60)) for g in grids) or "none"
            raise _fail(
                p.name,
                f"no sheet is a norm table (sheets: {sheets}); nothing would be imported",
                "name each sheet after its table: " + ", ".join(_ALL_TABLES)
                + " (Excel names a new sheet after the file or 'Sheet1'; rename it)",
            )
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
                    f'{loc.grid.address(loc.header_row, c)}: column "{_printable(h, 200)}" '
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
    """Create ``path`` (it must not exist) with ``text`` as UTF-8, fsynced."""
    fd = os.open(path, os.O_WRONLY | os.O_CREAT | os.O_EXCL | getattr(os, "O_BINARY", 0), 0o666)
    try:
        write_all(fd, text.encode("utf-8"))
    finally:
        os.close(fd)


# An import's own folders beside the set: ".NAME.tmp-XXXXXXXX" (the new set being written)
# and ".NAME.old-XXXXXXXX" (the set it replaces, between the two renames).
_LEFTOVER = re.compile(r"\.(?P<name>.+)\.(?P<kind>tmp|old)-[A-Za-z0-9_]{8}")


def _norm_dir_lock(folder: Path) -> contextlib.AbstractContextManager[None]:
    """Serialise imports and repairs in one norm directory, and keep loads out while a set
    is swapped (an exclusive ``flock``; loads take it shared; no-op without ``flock``)."""
    return dir_lock(folder, exclusive=True)


def recover_norm_dir(
    root: str | os.PathLike[str] | None = None, name: str | None = None
) -> list[str]:
    """Finish or undo the imports a crash (power loss, ``kill -9``) interrupted.

    :func:`write_norm_set` replaces a set by renaming it to ``.NAME.old-*``, renaming the
    new one (``.NAME.tmp-*``) in, and deleting the old one. After a crash between the two
    renames the set is missing and its previous content sits in ``.NAME.old-*``: it is put
    back. A ``.NAME.old-*`` beside an existing ``NAME`` (the crash came after the swap) and
    every ``.NAME.tmp-*`` (an unfinished new set) are deleted. Runs at the start of every
    import, of ``scanplan norms list``, and when a set name is not found.

    Parameters
    ----------
    root : path, optional
        Norm directory (default :func:`scanplan.norms.user_norms_dir`).
    name : str, optional
        Only this set's leftovers.

    Returns
    -------
    list of str
        What was done, one line each (empty when nothing was left over).

    Raises
    ------
    WriteError
        A previous set could not be put back (it stays where it is; nothing is deleted).
    """
    root_dir = Path(root) if root is not None else _norms.user_norms_dir()
    if not root_dir.is_dir():
        return []
    with _norm_dir_lock(root_dir):
        return _recover_locked(root_dir, name)


def _recover_locked(root_dir: Path, only: str | None = None) -> list[str]:
    found: dict[str, dict[str, list[Path]]] = {}
    for p in sorted(root_dir.iterdir()):
        m = _LEFTOVER.fullmatch(p.name)
        if m and (only is None or m["name"] == only) and p.is_dir() and not p.is_symlink():
            found.setdefault(m["name"], {"tmp": [], "old": []})[m["kind"]].append(p)
    done = []
    for name, kinds in found.items():
        target = root_dir / name
        olds = kinds["old"]
        backups = [p for p in olds if (p / "set.toml").is_file()]
        if backups and not os.path.lexists(target):
            keep = max(backups, key=lambda p: (p / "set.toml").stat().st_mtime)
            try:
                os.replace(keep, target)
            except OSError as exc:
                raise WriteError.from_os_error(
                    str(target), exc, action=f"put back norm set {name!r} from {keep.name} to"
                ) from exc
            olds = [p for p in olds if p != keep]
            done.append(f"put back norm set {name!r} (an interrupted import had moved it to "
                        f"{keep.name})")
        for p in olds + kinds["tmp"]:
            shutil.rmtree(p, ignore_errors=True)
            done.append(f"deleted {p.name} (left by an interrupted import)")
    return done


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
    if the rename fails). Any failure — including ``KeyboardInterrupt`` — leaves the norm
    directory as it was; what a crash leaves behind is put right by
    :func:`recover_norm_dir`, which runs first (under a lock on the directory).

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

    Raises
    ------
    InputError
        ``--name``: unsafe, or taken and no ``force``.
    WriteError
        The set could not be written (disk full, permission, interrupted rename); the
        message names the set's folder and the reason.
    """
    check_set_name(name)
    root_dir = Path(root) if root is not None else _norms.user_norms_dir()
    target = root_dir / name
    if target.exists() and not force:
        raise InputError(
            "--name", f"norm set {name!r} already exists ({target}); give --force to replace it"
        )
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
    files = {TABLES[t].file: _csv_text(TABLES[t], rows) for t, rows in parsed.tables.items()}
    files["set.toml"] = "\n".join(toml) + "\n"
    action = f"write norm set {name!r} to"
    created = []  # the norm directory and its parents this import creates
    probe = root_dir.absolute()
    while not os.path.lexists(probe) and probe != probe.parent:
        created.append(probe)
        probe = probe.parent
    try:
        try:
            root_dir.mkdir(parents=True, exist_ok=True)
        except OSError as exc:
            raise WriteError.from_os_error(str(root_dir), exc, action="create folder") from exc
        with _norm_dir_lock(root_dir):
            try:
                _recover_locked(root_dir, name)
                if target.exists() and not force:  # a set the recovery put back
                    raise InputError(
                        "--name",
                        f"norm set {name!r} already exists ({target}); give --force to "
                        "replace it",
                    )
                _swap_in(root_dir, name, files)
            except OSError as exc:
                if isinstance(exc, WriteError):
                    raise
                raise WriteError.from_os_error(str(target), exc, action=action) from exc
    except BaseException:
        for folder in created:  # deepest first; only while still empty
            try:
                folder.rmdir()
            except OSError:
                break
        raise
    return target


def _swap_in(root_dir: Path, name: str, files: Mapping[str, str]) -> None:
    """Write ``files`` as set ``name``: temporary folder, verify, rename (swap) into place."""
    target = root_dir / name
    tmp = Path(tempfile.mkdtemp(prefix=f".{name}.tmp-", dir=root_dir))
    old: Path | None = None
    try:
        mask = os.umask(0o022)
        os.umask(mask)
        os.chmod(tmp, 0o777 & ~mask)  # mkdtemp makes 0700; a set folder is an ordinary one
        for fname, text in files.items():
            _write_file(tmp / fname, text)
        _norms.read_norm_set_folder(tmp.resolve())  # the loader must accept it
        if not os.path.lexists(target):
            os.replace(tmp, target)
            fsync_dir(root_dir)  # the rename survives a power loss
            return
        old = root_dir / f".{name}.old-{secrets.token_hex(4)}"
        os.replace(target, old)
        try:
            os.replace(tmp, target)
        except BaseException as exc:
            try:
                os.replace(old, target)
            except OSError as undo:
                note = (
                    f"the previous set could not be put back ({undo.strerror or undo}); it is "
                    f"kept in {old}, and listing, importing or loading the set puts it back"
                )
                if isinstance(exc, OSError):
                    raise WriteError.from_os_error(
                        str(target), exc, action=f"write norm set {name!r} to", note=note
                    ) from exc
                raise
            old = None
            raise
    except BaseException:
        shutil.rmtree(tmp, ignore_errors=True)
        raise
    fsync_dir(root_dir)
    shutil.rmtree(old, ignore_errors=True)


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
        {k: (v if v != "" else None) for k, v in c.row().items() if k in cam_cols}
        for c in sorted(ns.cameras.values(), key=lambda c: c.id)
    ]
    out["scanners"] = [
        {
            "scanner": st.scanner,
            "name": st.name or None,
            "pixel_um": st.pixel_um,
            "bit_depth": st.bit_depth or None,
            "frame_scan_min": st.frame_scan_min,
            "note": st.note or None,
            "source": st.source or None,
        }
        for s in sorted(ns.scanner_details)
        for st in ns.scanner_details[s]
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
    columns and parameter values, and fitted column widths. Rendered in memory, then
    written atomically (:func:`scanplan.reports.write_atomic`): on any failure an existing
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
    from .outpaths import check_target  # links, folders, FIFOs, write-protected, long names

    check_target(os.fspath(out), "FILE", "xlsx", force=True)
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
                _text_cell(ws.cell(row=ri, column=ci), row.get(col.name))
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
        _text_cell(ws.cell(row=ri, column=2), getattr(ns, key) or None)
    ws.column_dimensions["A"].width = 12
    ws.column_dimensions["B"].width = 100
    ws.freeze_panes = "A2"
    buf = io.BytesIO()
    wb.save(buf)  # rendered in memory: a failure here touches no file
    try:
        out.parent.mkdir(parents=True, exist_ok=True)
    except OSError as exc:
        raise WriteError.from_os_error(str(out.parent), exc, action="create folder") from exc
    write_atomic(path, buf.getvalue())  # temporary file, fsync, the replaced file's mode
    return out


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

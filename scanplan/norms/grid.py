"""A sheet as a grid of cells: finding a table's header row and its data rows."""

from __future__ import annotations

import bisect
import re
from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import Any

from . import limits as _limits
from .cells import (
    _COLUMN_INDEX,
    _PARAMETER_INDEX,
    Bad,
    ImportProblem,
    Problems,
    _convert,
    _is_empty,
    _match,
    _shown,
    fail,
)
from .schema import PARAMETERS, TableSpec


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
            if not (1 <= r1 <= n and 1 <= c1 <= _limits.MAX_COLUMNS) or r2 < r1 or c2 < c1:
                continue  # nothing there (a merge below the data or right of the limit)
            top = self.raw(r1, c1)
            r2, c2 = min(r2, n), min(c2, _limits.MAX_COLUMNS)
            if c1 == c2 and r2 > r1 and top is not None:  # every row of it shows the value
                self._fill.setdefault(c1, []).append((r1, r2, top))
            for r in range(r1, min(r2, _limits.HEADER_SCAN_ROWS) + 1):  # only headers use groups
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


def _find_header(grid: _Grid, spec: TableSpec, problems: Problems | None) -> _Located | None:
    """The header row of ``grid`` for table ``spec``: the row matching most columns."""
    index = _COLUMN_INDEX[spec.name]
    last_row = min(_limits.HEADER_SCAN_ROWS, len(grid.rows))
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
                    f"no header row of table {spec.name!r} in the first "
                    f"{_limits.HEADER_SCAN_ROWS} rows",
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


def _data_rows(loc: _Located, problems: Problems) -> _Table:
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
        if n_rows > _limits.MAX_ROWS:
            raise fail(
                grid.address(r, 1),
                f"more than {_limits.MAX_ROWS:,} rows in one table; split the table or delete "
                "unused rows",
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
            except Bad as exc:
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


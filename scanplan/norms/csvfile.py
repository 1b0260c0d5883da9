"""Reading a one-table CSV (UTF-8, UTF-16 or Windows-1251; comma, semicolon or tab)."""

from __future__ import annotations

import csv
import re
from collections.abc import Iterator, Sequence
from pathlib import Path

from ..io.files import read_limited
from . import limits as _limits
from .cells import fail
from .grid import _Grid
from .sheetscan import _WIDEST_TABLE


def _decode_text(data: bytes, name: str = "the file") -> str:
    """The text of a CSV: UTF-16 (with a BOM), UTF-8 (BOM or not), else Windows-1251."""
    hint = 'save it from Excel as "CSV UTF-8 (Comma delimited) (*.csv)"'
    if data.startswith((b"\xff\xfe", b"\xfe\xff")):
        try:
            text = data.decode("utf-16")
        except UnicodeDecodeError as exc:
            raise fail(
                name, f"is not valid UTF-16 text (byte {exc.start:,}: {exc.reason})", hint
            ) from None
    else:
        try:
            text = data.decode("utf-8-sig")
        except UnicodeDecodeError:
            try:  # a Russian-locale Excel "CSV (разделители - запятые)"
                text = data.decode("cp1251")
            except UnicodeDecodeError as exc:
                raise fail(
                    name,
                    f"is neither UTF-8 nor Windows-1251 text (byte 0x{data[exc.start]:02X} at "
                    f"position {exc.start:,})",
                    hint,
                ) from None
    if "\x00" in text:
        raise fail(
            name,
            "contains NUL characters: a binary file, or UTF-16 text without a byte-order mark",
            hint,
        )
    return text


_EOL = re.compile(r"\r\n|\r|\n")


class _RowTooLong(Exception):
    """A CSV row (with all its lines) is longer than :data:`MAX_CSV_ROW_CHARS`."""


def _sniff_delimiter(text: str) -> str:
    """The separator of a CSV text, sniffed on its first lines only; ``;`` when a Russian
    Excel wrote it (``;`` on every line, decimal commas)."""
    head = text[: 64 * 1024]
    sample = "\n".join(head.splitlines()[: _limits.HEADER_SCAN_ROWS + 5])
    counts = {d: sample.count(d) for d in (";", "\t", ",")}
    try:
        delim = csv.Sniffer().sniff(sample, delimiters=";\t,").delimiter
    except csv.Error:
        delim = max(counts, key=lambda d: counts[d])
    if delim == "," and counts[";"] and all(";" in ln for ln in sample.splitlines() if ln):
        delim = ";"
    return delim


class _Lines:
    """The physical lines of a text for :func:`csv.reader`, each counted before it is cut
    out: a row (all its lines) longer than :data:`MAX_CSV_ROW_CHARS` raises
    :class:`_RowTooLong`. Call :meth:`new_row` after each row."""

    def __init__(self, text: str) -> None:
        self.text = text
        self.row_chars = 0

    def new_row(self) -> None:
        self.row_chars = 0

    def __iter__(self) -> Iterator[str]:
        text = self.text
        pos, end = 0, len(text)
        while pos < end:
            m = _EOL.search(text, pos)
            stop = m.end() if m else end
            self.row_chars += stop - pos
            if self.row_chars > _limits.MAX_CSV_ROW_CHARS:
                raise _RowTooLong
            yield text[pos:stop]
            pos = stop


def _check_csv_row(row: list[str], n: int, cells: int, name: str, label: _Grid) -> int:
    """Row ``n`` (trailing empty cells dropped in place) against the row, column and cell
    limits; returns the filled cells so far."""
    if n > _limits.MAX_ROWS + _limits.HEADER_SCAN_ROWS:
        raise fail(
            name,
            f"more than {_limits.MAX_ROWS:,} rows (row {n:,} is past the limit); refused "
            "without reading further",
            "split the table or delete unused rows",
            at=label.address(n, 1),
        )
    while row and not row[-1]:  # Excel pads rows with separators
        row.pop()
    if len(row) > _limits.MAX_COLUMNS:
        raise fail(
            name,
            f"row {n:,} has {len(row):,} columns; the limit is "
            f"{_limits.MAX_COLUMNS} (a norm "
            f"table has at most {_WIDEST_TABLE})",
            "delete the columns right of the table",
            at=label.address(n, _limits.MAX_COLUMNS + 1),
        )
    cells += sum(1 for v in row if v)
    if cells > _limits.MAX_CELLS:
        raise fail(
            name,
            f"more than {_limits.MAX_CELLS:,} filled cells; refused without reading "
            "further",
            "a norm table is small: delete unused rows and columns",
            at=label.address(n, 1),
        )
    return cells


def _read_csv_grid(path: Path) -> _Grid:
    """A CSV (UTF-8, UTF-16 or cp1251; comma, semicolon or tab separated) as a grid.

    Bounded: the file is read with a limit, a row may hold at most
    :data:`MAX_CSV_ROW_CHARS` characters (checked line by line, before the row is split),
    :data:`MAX_COLUMNS` columns and the file :data:`MAX_CELLS` values; reading stops at the
    first row past :data:`MAX_ROWS`.
    """
    name = path.name
    text = _decode_text(read_limited(path, _limits.MAX_FILE_BYTES, field=str(path)), name)
    lines = _Lines(text)
    label = _Grid(path.stem, [])
    rows: list[Sequence[str]] = []
    cells = 0
    reader = csv.reader(lines, delimiter=_sniff_delimiter(text))
    try:
        for row in reader:
            lines.new_row()
            cells = _check_csv_row(row, len(rows) + 1, cells, name, label)
            rows.append(tuple(row))
    except _RowTooLong:
        raise fail(
            name,
            f"row {len(rows) + 1:,} is longer than {_limits.MAX_CSV_ROW_CHARS:,} characters (a "
            "runaway quote, or not a CSV file)",
            "check the quotes in that row; a norm table row is short",
            at=label.address(len(rows) + 1, 1),
        ) from None
    except csv.Error as exc:
        raise fail(
            name,
            f"cannot be read as CSV (line {reader.line_num:,}: {exc})",
            f"one cell holds at most {_limits.MAX_CELL_CHARS:,} characters; check the quotes",
            at=label.address(len(rows) + 1, 1),
        ) from None
    return _Grid(path.stem, rows)

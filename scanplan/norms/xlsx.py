"""Reading .xlsx workbooks safely, through python-calamine.

In this order, each step before the next sees a byte: the zip directory (its size, then
every member's size and compression ratio: nothing is decompressed for a zip bomb); every
XML part but the worksheets streamed once (DTD and entity declarations refused, elements
counted, each part also through an expat parser that refuses a DTD); the sheet list and
the percent number formats (:mod:`.sheetscan`, defusedxml); each norm table's worksheet
streamed through :class:`~.sheetscan._SheetScan` (row, column, cell, merge and area
limits; formula, error and percent cells). Only then does calamine read the values and
merged ranges of those sheets, from the same bytes. See docs/norms.md "Reading a workbook".
"""

from __future__ import annotations

import io
import os
import re
import zipfile
import zlib
from collections.abc import Sequence
from pathlib import Path
from typing import Any

from ..errors import InputError
from . import limits as _limits
from .cells import _SHEET_INDEX, _match, _size, fail
from .grid import _Grid
from .sheetscan import (
    _dtd_refusing_parser,
    _percent_styles,
    _Refused,
    _sheet_refusal,
    _SheetScan,
    _workbook_sheets,
)

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
_WORKSHEET = re.compile(r"xl/worksheets/[^/]+\.xml")  # checked while they are streamed


def _zip_directory_size(fh: Any) -> int | None:
    """Size of a zip's central directory [bytes] from its end records (None: none found).

    Read before :class:`zipfile.ZipFile` parses the directory, whose every entry becomes an
    object: a 20 MB file of empty entries would cost seconds and 100+ MB.

    Parameters
    ----------
    fh : binary file
        The workbook, seekable.
    """
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
    if len(infos) > _limits.MAX_ZIP_MEMBERS:
        raise fail(
            name, f"has {len(infos):,} zip members (the limit is {_limits.MAX_ZIP_MEMBERS:,})",
            "not a norm workbook",
        )
    total = 0
    for info in infos:
        sheet = info.filename.startswith("xl/worksheets/")
        hint = (
            f"delete unused rows and columns: a norm table has at most {_limits.MAX_ROWS:,} rows"
            if sheet
            else "not a norm workbook"
        )
        if info.file_size > _limits.MAX_MEMBER_BYTES:
            raise fail(
                name,
                f"zip member {info.filename} would unpack to {_size(info.file_size)}; the "
                f"limit is {_size(_limits.MAX_MEMBER_BYTES)}",
                hint,
            )
        if (
            info.file_size > 1_000_000
            and info.compress_size
            and info.file_size / info.compress_size > _limits.MAX_COMPRESSION_RATIO
        ):
            raise fail(
                name,
                f"zip member {info.filename} is compressed "
                f"{info.file_size / info.compress_size:.0f}:1; the limit is "
                f"{_limits.MAX_COMPRESSION_RATIO}:1 (a zip bomb?)",
                "not a norm workbook",
            )
        total += info.file_size
    if total > _limits.MAX_TOTAL_UNCOMPRESSED_BYTES:
        raise fail(
            name,
            f"would unpack to {_size(total)}; the limit is "
            f"{_size(_limits.MAX_TOTAL_UNCOMPRESSED_BYTES)}",
            "not a norm workbook",
        )
    for info in infos:
        low = info.filename.lower()
        if _WORKSHEET.fullmatch(low) or not low.endswith((".xml", ".rels", ".vml")):
            continue
        strings = low == "xl/sharedstrings.xml"
        limit = _limits.MAX_STRINGS_ELEMENTS if strings else _limits.MAX_PART_ELEMENTS
        check = _ElementCount(name, info.filename, limit)
        _stream_member(zf, info, name, f"zip member {info.filename}", check)
        check.close()
    return {i.filename: i for i in infos}


class _ElementCount:
    """A :func:`_stream_member` sink that refuses a part with more than ``limit`` XML
    elements (start tags): parsing styles or strings costs time and memory per element,
    so a small file with millions of them is refused before any parser sees it.

    Each chunk also goes through an expat parser with no element handlers (C speed) that
    refuses a DTD or an entity declaration: a second line behind the byte pattern. A part
    expat cannot parse is left to the reader that needs it (only a DTD is refused here).
    """

    def __init__(self, name: str, member: str, limit: int) -> None:
        self.name, self.member, self.limit, self.n = name, member, limit, 0
        self.parser: Any = _dtd_refusing_parser()

    def __call__(self, chunk: bytes) -> None:
        self.n += chunk.count(b"<") - chunk.count(b"</")
        if self.n > self.limit:
            raise fail(
                self.name,
                f"zip member {self.member} holds more than {self.limit:,} XML elements (the "
                "limit); refused without reading it",
                "not a norm workbook: Excel keeps at most 64,000 cell styles; open it in "
                "Excel, delete unused styles, and save it again",
            )
        self._parse(chunk, False)

    def close(self) -> None:
        """The part is complete."""
        self._parse(b"", True)

    def _parse(self, chunk: bytes, final: bool) -> None:
        if self.parser is None:
            return
        try:
            self.parser.Parse(chunk, final)
        except _Refused:
            raise fail(
                self.name,
                f"zip member {self.member} declares a DTD or XML entities (entity expansion, "
                "'billion laughs', external entities); refused, nothing was read",
                "Excel never writes these: the file was made by something else",
            ) from None
        except Exception:  # not well-formed (or not XML): no DTD check possible past it
            self.parser = None


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
                if got > _limits.MAX_MEMBER_BYTES:
                    raise fail(
                        name,
                        f"{part} unpacks to more than {_size(_limits.MAX_MEMBER_BYTES)}",
                        "not a norm workbook",
                    )
                window = tail + chunk
                if (b"<!" in window or b"<\x00!" in window) and _DOCTYPE.search(window):
                    raise fail(
                        name,
                        f"{part} declares a DTD or XML entities (entity expansion, "
                        "'billion laughs', external entities); refused, nothing was read",
                        "Excel never writes these: the file was made by something else",
                    )
                tail = window[-_SCAN_OVERLAP:]
                sink(chunk)
    except _ZIP_ERRORS as exc:
        raise fail(
            name,
            f"is a damaged .xlsx ({info.filename}: {exc})",
            "open it in Excel and save it again",
        ) from None



def _read_xlsx(path: Path) -> list[_Grid]:
    """Every sheet of a workbook as a grid (sheets that are no norm table: empty grids).

    The file is read once into memory (it is at most
    :data:`~scanplan.norms.limits.MAX_FILE_BYTES`), so every check and calamine see the
    same bytes. The zip and its XML parts are checked first (:func:`_inspect_xlsx`); each
    norm table's worksheet is then streamed through :class:`_SheetScan` in 1 MB chunks,
    which stops at the first limit broken — a million-row sheet is refused after
    :data:`~scanplan.norms.limits.MAX_ROWS` rows and never reaches calamine. calamine
    reads the values of the sheets that passed; other sheets are never read.
    """
    name = path.name
    try:
        data = path.read_bytes()
    except OSError as exc:
        raise fail(name, f"cannot be read ({exc.strerror or exc})") from None
    directory = _zip_directory_size(io.BytesIO(data))
    if directory is not None and directory > _limits.MAX_ZIP_DIRECTORY_BYTES:
        raise fail(
            name,
            f"has a zip directory of {_size(directory)}; the limit is "
            f"{_size(_limits.MAX_ZIP_DIRECTORY_BYTES)}",
            "not a norm workbook",
        )
    try:
        zf = zipfile.ZipFile(io.BytesIO(data))
    except Exception as exc:  # BadZipFile, OSError, ValueError, ... for a file that is no zip
        raise fail(
            name,
            f"is not an .xlsx workbook (not a zip file: {exc})",
            'save it from Excel as "Excel Workbook (*.xlsx)"',
        ) from None
    with zf:
        members = _inspect_xlsx(zf, name)
        sheets = _workbook_sheets(zf, name)
        percent_styles = _percent_styles(zf, name)
        scans = _scan_sheets(zf, name, members, sheets, percent_styles)
    return _calamine_grids(data, name, sheets, scans)


def _scan_sheets(
    zf: zipfile.ZipFile,
    name: str,
    members: dict[str, zipfile.ZipInfo],
    sheets: list[tuple[str, str, str]],
    percent_styles: set[int],
) -> dict[str, _SheetScan]:
    """Stream each norm table's worksheet through :class:`_SheetScan` (title → its scan);
    sheets that are no norm table are not read."""
    scans: dict[str, _SheetScan] = {}
    cells_left = _limits.MAX_CELLS
    for title, _state, member in sheets:
        if _match(_SHEET_INDEX, title) is None:
            continue
        info = members.get(member)
        if info is None:
            raise fail(
                name,
                f"sheet {title!r} has no worksheet part ({member or '?'})",
                "open it in Excel and save it again",
            )
        scan = _SheetScan(
            percent_styles, _limits.MAX_ROWS + _limits.HEADER_SCAN_ROWS, max_cells=cells_left
        )
        part = f"sheet {title!r} (zip member {member})"
        try:
            _stream_member(zf, info, name, part, scan.feed)
            scan.close()
        except _Refused as exc:
            raise _sheet_refusal(exc, title, name) from None
        except InputError:
            raise
        except Exception as exc:  # expat errors on a damaged sheet
            raise fail(
                name,
                f"sheet {title!r} cannot be read ({type(exc).__name__}: {exc})",
                "open it in Excel and save it again",
            ) from None
        cells_left = scan.cells_left
        scans[title] = scan
    return scans


def _calamine_grids(
    data: bytes, name: str, sheets: list[tuple[str, str, str]], scans: dict[str, _SheetScan]
) -> list[_Grid]:
    """The grids of the checked workbook: calamine reads the scanned sheets; other visible
    sheets become empty grids (ignored with a note), hidden ones are left out."""
    grids: list[_Grid] = []
    book: Any = None
    try:
        for title, state, _member in sheets:
            scan = scans.get(title)
            if scan is None:
                if state == "visible":
                    grids.append(_Grid(title, []))  # ignored (with a note), never read
                continue
            if book is None:
                from python_calamine import CalamineWorkbook

                book = CalamineWorkbook.from_filelike(io.BytesIO(data))
            grids.append(_sheet_grid(book.get_sheet_by_name(title), title, scan))
    except InputError:
        raise
    except Exception as exc:  # calamine's errors for a damaged workbook or sheet
        raise fail(
            name,
            f"cannot be read as an .xlsx workbook ({type(exc).__name__}: {exc})",
            'open it in Excel and save it as "Excel Workbook (*.xlsx)"',
        ) from None
    finally:
        if book is not None:
            book.close()
    return grids


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


def _sheet_grid(sheet: Any, title: str, scan: _SheetScan) -> _Grid:
    """One calamine sheet as a grid: empty cells as None, the Excel errors the scan found
    put back (calamine returns them empty), the formula cells calamine left empty marked
    as formulas without a cached value, percent-formatted numbers marked."""
    errors: dict[int, list[tuple[int, str]]] = {}
    for (r, c), text in scan.errors.items():
        errors.setdefault(r, []).append((c, text))
    first_col = (sheet.start or (0, 0))[1]
    pad = [""] * first_col
    rows: list[Sequence[Any]] = []
    for r, line in enumerate(sheet.iter_rows(), start=1):
        if first_col:
            line = pad + line
        for c, text in errors.get(r, ()):
            if c > len(line):
                line.extend([""] * (c - len(line)))
            if line[c - 1] == "":
                line[c - 1] = text
        rows.append(_compact_row(line))
    formula_missing = {p for p in scan.formulas if _raw(rows, *p) is None}
    percent = {p for p in scan.percent if isinstance(_raw(rows, *p), float)}
    merged = [(r1 + 1, c1 + 1, r2 + 1, c2 + 1)
              for (r1, c1), (r2, c2) in sheet.merged_cell_ranges or ()]
    return _Grid(title, rows, merged=merged, formula_without_value=formula_missing,
                 percent_cells=percent)


def _compact_row(line: list[Any]) -> Sequence[Any]:
    """A calamine row without its trailing empty cells, ``""`` as None; a long row with few
    values as a :class:`_SparseRow`."""
    n = len(line)
    while n and line[n - 1] == "":
        n -= 1
    if n > 48:
        cells = {c + 1: v for c, v in enumerate(line[:n]) if v != ""}
        if n > 2 * len(cells) + 16:
            return _SparseRow(cells, n)
    return [None if v == "" else v for v in line[:n]]


def _raw(rows: list[Sequence[Any]], r: int, c: int) -> Any:
    if r - 1 < len(rows):
        row = rows[r - 1]
        if c - 1 < len(row):
            return row[c - 1]
    return None

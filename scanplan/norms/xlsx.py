"""Reading .xlsx workbooks safely: zip directory checks first (size, ratio, members),
DTD/entity refusal, per-part element bounds, a streaming worksheet reader, percent
styles and formulas without a cached value."""

from __future__ import annotations

import datetime as _dt
import os
import re
import zipfile
import zlib
from collections.abc import Sequence
from pathlib import Path
from typing import Any

from ..errors import InputError
from . import limits as _limits
from .cells import _SHEET_INDEX, NormImportError, _fail, _match, _size
from .grid import _cell_ref, _col_letter, _col_number, _Grid
from .schema import TABLES

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
    if len(infos) > _limits.MAX_ZIP_MEMBERS:
        raise _fail(
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
            raise _fail(
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
            raise _fail(
                name,
                f"zip member {info.filename} is compressed "
                f"{info.file_size / info.compress_size:.0f}:1; the limit is "
                f"{_limits.MAX_COMPRESSION_RATIO}:1 (a zip bomb?)",
                "not a norm workbook",
            )
        total += info.file_size
    if total > _limits.MAX_TOTAL_UNCOMPRESSED_BYTES:
        raise _fail(
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
                if got > _limits.MAX_MEMBER_BYTES:
                    raise _fail(
                        name,
                        f"{part} unpacks to more than {_size(_limits.MAX_MEMBER_BYTES)}",
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
        self.max_columns = _limits.MAX_COLUMNS if max_columns is None else max_columns
        self.cells_left = _limits.MAX_CELLS if max_cells is None else max_cells
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
            if len(self.merged) >= _limits.MAX_MERGED:
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
            f"sheet {title!r} has more than {_limits.MAX_ROWS:,} rows (a value in row {r:,}); "
            "refused without reading further",
            "delete unused rows below the table or split it",
            at=at,
        )
    if exc.reason == "columns":
        return _fail(
            name,
            f"a value in column {_col_letter(c)}, right of column "
            f"{_col_letter(_limits.MAX_COLUMNS)} "
            f"(the limit; a norm table has at most {_WIDEST_TABLE} columns)",
            "delete the cells right of the table, or move notes to another sheet",
            at=at,
        )
    if exc.reason == "cells":
        return _fail(
            name,
            f"more than {_limits.MAX_CELLS:,} filled cells in the workbook; refused without "
            "reading further",
            "a norm workbook is small: delete unused rows, columns and sheets",
            at=at,
        )
    if exc.reason == "merged":
        return _fail(
            name,
            f"sheet {title!r} has more than {_limits.MAX_MERGED:,} merged cell ranges",
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
    if directory is not None and directory > _limits.MAX_ZIP_DIRECTORY_BYTES:
        raise _fail(
            name,
            f"has a zip directory of {_size(directory)}; the limit is "
            f"{_size(_limits.MAX_ZIP_DIRECTORY_BYTES)}",
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
        cells_left = _limits.MAX_CELLS
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
                _limits.MAX_ROWS + _limits.HEADER_SCAN_ROWS,
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


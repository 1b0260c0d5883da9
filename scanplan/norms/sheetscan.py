"""What python-calamine does not tell about an .xlsx, read by small bounded scans.

calamine (:mod:`python_calamine`) reads cell values, dates and merged ranges, but it holds
a sheet as one dense rectangle (a value at ``A1`` and one at ``XFD1048576`` would ask for
17 billion cells), drops Excel error values and formulas without a cached value (both
come back as empty cells) and does not report number formats. So before calamine sees a
worksheet, :class:`_SheetScan` streams its XML once (expat, start tags only, nothing
kept but a few positions) and

- refuses a value below :data:`~scanplan.norms.limits.MAX_ROWS` (plus the header rows),
  right of :data:`~scanplan.norms.limits.MAX_COLUMNS`, more than
  :data:`~scanplan.norms.limits.MAX_CELLS` filled cells, more than
  :data:`~scanplan.norms.limits.MAX_MERGED` merged ranges, a rectangle of more than
  :data:`~scanplan.norms.limits.MAX_SHEET_AREA` cells, and any DTD — stopping at the first;
- records the cells holding a formula, the Excel error values (``#DIV/0!``) and the numeric
  cells whose style shows a percentage.

:func:`_workbook_sheets` reads the sheet list (name, state, zip member) and
:func:`_percent_styles` the percent number formats, with defusedxml, from parts whose size
and element count :mod:`scanplan.norms.xlsx` has already bounded.
"""

from __future__ import annotations

import posixpath
import re
import zipfile
from typing import Any

from . import limits as _limits
from .cells import NormImportError, fail
from .grid import _cell_ref, _col_letter, _col_number, _Grid
from .schema import TABLES

_WIDEST_TABLE = max(len(t.columns) for t in TABLES.values())
_REF = re.compile(r"([A-Z]{1,3})(\d{1,9})")
_COLUMNS = {_col_letter(c): c for c in range(1, 703)}  # A..ZZ

# The fast path (:meth:`_SheetScan._fast`): cells as Excel and openpyxl write them,
# counted by byte patterns at C speed. Anything else switches the scan to expat for the
# rest of the part. Every cell start tag must be one of the two plain forms.
_ANY_CELL = re.compile(rb"<c[\s/>]")
_FILLED_CELL = re.compile(rb'<c r="([A-Z]{1,3})([0-9]{1,9})"[^>/]*><(?:v|is)>')
_EMPTY_CELL = re.compile(rb'<c r="[A-Z]{1,3}[0-9]{1,9}"[^>/]*(?:/>|></c>)')
_ANY_ROW = re.compile(rb"<row[\s/>]")
_ROW_WITH_R = re.compile(rb'<row r="[0-9]{1,9}"')
# formulas, error cells, merged ranges, prefixed tags: the expat scan records them
_UNUSUAL_BYTES = (b"<f", b't="e"', b"t='e'", b"<mergeCell")
_PREFIXED_TAG = re.compile(rb"<[A-Za-z_][\w.-]*:")
_LAST_TAG = re.compile(rb'<(?:c|row) r="([A-Z]{0,3})([0-9]{1,9})"')
_MAX_CARRY = 4 << 20  # bytes of one unfinished cell the fast path holds before it gives up
# Excel's built-in number formats that show a percentage (ECMA-376 part 1, 18.8.30)
_BUILTIN_PERCENT = frozenset((9, 10))
_MAIN_NS = "{http://schemas.openxmlformats.org/spreadsheetml/2006/main}"
_REL_NS = "{http://schemas.openxmlformats.org/package/2006/relationships}"
_DOC_REL = "{http://schemas.openxmlformats.org/officeDocument/2006/relationships}id"


class _Refused(Exception):
    """The XML declares a DTD or entities, or a sheet breaks a limit (see ``reason``)."""

    def __init__(self, reason: str = "dtd", where: tuple[int, int] = (0, 0)) -> None:
        super().__init__(reason)
        self.reason = reason
        self.where = where


def _refuse(*_: object) -> None:
    raise _Refused


def _dtd_refusing_parser() -> Any:
    """An expat parser that raises :class:`_Refused` at a DTD or entity declaration."""
    import xml.parsers.expat as expat

    p = expat.ParserCreate()
    p.StartDoctypeDeclHandler = _refuse
    p.EntityDeclHandler = _refuse
    p.UnparsedEntityDeclHandler = _refuse
    p.ExternalEntityRefHandler = _refuse  # type: ignore[assignment]
    p.SetParamEntityParsing(expat.XML_PARAM_ENTITY_PARSING_NEVER)
    return p


class _SheetScan:
    """One pass over a worksheet's XML before calamine reads it (see the module docstring).

    Feed it chunks (:meth:`feed`, :meth:`close`) or a whole part (:meth:`parse`). Cell
    positions follow the same rules as calamine's: a cell's ``r`` (``B7``), else one right
    of the previous cell; a row's ``r``, else one below the previous row.

    Two ways to scan, one exact result: while the part holds only plain cells
    (``<c r="B7" ...><v>`` or ``<is>``, or empty) and nothing to record, whole runs of
    cells are counted with byte patterns (:meth:`_fast`); at the first run that holds
    anything else, or would break a limit, the scan switches to expat with a handler per
    start tag for the rest of the part (:meth:`_start`), which records it and names the
    exact cell a limit refuses. expat parses every byte either way (DTDs refused).

    Attributes (1-based ``(row, column)`` positions)
    ------------------------------------------------
    formulas : set
        Cells with a formula (those calamine returns empty have no cached value).
    errors : dict
        Cells of type ``e`` → the error text Excel shows (``"#DIV/0!"``).
    percent : set
        Numeric cells whose style is one of ``percent_styles``.
    extent : tuple
        The last row and the last column holding a value (0, 0 for none).
    cells_left : int
        ``max_cells`` less the filled cells seen (passed on to the next sheet).

    ``fast=False`` scans with expat from the first byte (the tests compare the two).
    """

    def __init__(
        self,
        percent_styles: set[int],
        max_rows: int,
        *,
        max_columns: int | None = None,
        max_cells: int | None = None,
        fast: bool = True,
    ) -> None:
        self.percent_styles = {str(i) for i in percent_styles}
        self._percent_re = (
            re.compile(rb"""\ss=["'](?:%s)["']""" % b"|".join(b"%d" % i for i in percent_styles))
            if percent_styles
            else None
        )
        self.max_rows = max_rows
        self.max_columns = _limits.MAX_COLUMNS if max_columns is None else max_columns
        self.cells_left = _limits.MAX_CELLS if max_cells is None else max_cells
        self.formulas: set[tuple[int, int]] = set()
        self.errors: dict[tuple[int, int], str] = {}
        self.percent: set[tuple[int, int]] = set()
        self.extent = (0, 0)
        self.merged = 0
        self._parser: Any = None
        self._row = 0
        self._col = 0
        self._pos: tuple[int, int] | None = None  # the open cell, until it is counted
        self._error_at: tuple[int, int] | None = None  # an open error cell
        self._error: list[str] = []  # its text
        self._exact = not fast  # expat handlers on (for the rest of the part)
        self._carry = b""  # the fast path's unfinished tail

    def feed(self, data: bytes) -> None:
        """Scan the next chunk of the part."""
        if self._parser is None:
            self._parser = _dtd_refusing_parser()
            self._parser.buffer_text = True
            if self._exact:
                self._go_exact()
        if self._exact:
            self._parser.Parse(data, False)
            return
        buf = self._carry + data if self._carry else data
        cut = buf.rfind(b"<c")  # the last cell may be unfinished: keep it for the next chunk
        if cut < 0:
            cut = buf.rfind(b"<")
        if cut < 0:
            cut = len(buf)
        if len(buf) - cut > _MAX_CARRY or not self._fast(buf[:cut]):
            self._carry = b""
            self._go_exact()
            self._parser.Parse(buf, False)
            return
        self._parser.Parse(buf[:cut], False)
        self._carry = buf[cut:]

    def close(self) -> None:
        """The part is complete (expat reports a truncated one)."""
        if self._parser is None:
            self.feed(b"")
        if not self._exact:
            carry, self._carry = self._carry, b""
            self._go_exact()
            self._parser.Parse(carry, False)
        self._parser.Parse(b"", True)
        if self._error_at is not None:
            self._end_error()

    def _go_exact(self) -> None:
        self._exact = True
        self._parser.StartElementHandler = self._start

    def _fast(self, part: bytes) -> bool:
        """Count the complete cells of ``part`` if all are plain and within the limits;
        False (nothing counted) when expat must scan it."""
        if any(b in part for b in _UNUSUAL_BYTES) or _PREFIXED_TAG.search(part):
            return False
        if self._percent_re is not None and self._percent_re.search(part):
            return False
        refs = _FILLED_CELL.findall(part)
        others = len(_ANY_CELL.findall(part)) - len(refs)
        if others and others != len(_EMPTY_CELL.findall(part)):
            return False
        if len(_ANY_ROW.findall(part)) != len(_ROW_WITH_R.findall(part)):
            return False
        if refs:
            rows = max(self.extent[0], max(int(d) for _, d in refs))
            letters = {c for c, _ in refs}
            cols = max(self.extent[1], *(_COLUMNS.get(c.decode()) or 16385 for c in letters))
            if (
                rows > self.max_rows
                or cols > self.max_columns
                or len(refs) > self.cells_left
                or rows * cols > _limits.MAX_SHEET_AREA
            ):
                return False  # expat finds the cell and refuses it
            self.cells_left -= len(refs)
            self.extent = (rows, cols)
        i = max(part.rfind(b'<c r="'), part.rfind(b'<row r="'))
        m = _LAST_TAG.match(part, i) if i >= 0 else None
        if m:  # where the next cell without a reference goes
            self._row = int(m.group(2))
            letters = m.group(1).decode()
            self._col = _COLUMNS.get(letters) or _col_number(letters)
        return True

    def parse(self, data: bytes) -> None:
        """Scan a whole part."""
        self.feed(data)
        self.close()

    def _start(self, tag: str, attrs: dict[str, str]) -> None:
        if ":" in tag:
            tag = tag.rpartition(":")[2]
        if tag == "v":
            if self._pos is not None:
                self._filled()
            if self._error_at is not None:
                self._parser.CharacterDataHandler = self._error.append
        elif tag == "c":
            if self._error_at is not None:
                self._end_error()
            self._open_cell(attrs)
        elif tag == "is":
            if self._pos is not None:
                self._filled()
        elif tag == "f":
            if self._pos is not None:
                self.formulas.add(self._pos)
                self._filled()
        elif tag == "row":
            if self._error_at is not None:
                self._end_error()
            self._pos = None
            r = attrs.get("r")
            self._row = int(r) if r and r.isdigit() and len(r) < 10 else self._row + 1
            self._col = 0
        elif tag == "mergeCell":
            self._merge(attrs.get("ref", ""))

    def _open_cell(self, attrs: dict[str, str]) -> None:
        ref = attrs.get("r")
        m = _REF.fullmatch(ref) if ref else None
        if m:
            letters = m.group(1)
            col = _COLUMNS.get(letters)
            self._col = col if col is not None else _col_number(letters)
            self._row = int(m.group(2))
        else:
            self._col += 1
        pos = self._pos = (self._row, self._col)
        t = attrs.get("t")
        if t is None or t == "n":
            if self.percent_styles and attrs.get("s") in self.percent_styles:
                self.percent.add(pos)
        elif t == "inlineStr":
            self._filled()
        elif t == "e":
            self._error_at = pos
            self._error = []

    def _end_error(self) -> None:
        """Keep the text of the error cell just closed (``#DIV/0!``)."""
        self._parser.CharacterDataHandler = None
        text = "".join(self._error).strip()
        if text and self._error_at is not None:
            self.errors[self._error_at] = text[:64]
        self._error_at = None

    def _filled(self) -> None:
        """The open cell holds a value (or a formula): count it against the limits
        (refuse, and stop, past one)."""
        pos = self._pos
        assert pos is not None
        self._pos = None  # counted once
        if pos[0] > self.max_rows:
            raise _Refused("rows", pos)
        if pos[1] > self.max_columns:
            raise _Refused("columns", pos)
        self.cells_left -= 1
        if self.cells_left < 0:
            raise _Refused("cells", pos)
        rows, cols = self.extent
        if pos[0] > rows or pos[1] > cols:
            rows, cols = max(rows, pos[0]), max(cols, pos[1])
            if rows * cols > _limits.MAX_SHEET_AREA:
                raise _Refused("area", pos)
            self.extent = (rows, cols)

    def _merge(self, ref: str) -> None:
        try:
            a, _, b = ref.partition(":")
            r1, c1 = _cell_ref(a)
            if b:
                _cell_ref(b)
        except ValueError:
            return
        self.merged += 1
        if self.merged > _limits.MAX_MERGED:
            raise _Refused("merged", (r1, c1))


def _sheet_refusal(exc: _Refused, title: str, name: str) -> NormImportError:
    """The message for a worksheet :class:`_SheetScan` refused."""
    r, c = exc.where
    at = _Grid(title, []).address(r, max(c, 1))
    if exc.reason == "rows":
        return fail(
            name,
            f"sheet {title!r} has more than {_limits.MAX_ROWS:,} rows (a value in row {r:,}); "
            "refused without reading further",
            "delete unused rows below the table or split it",
            at=at,
        )
    if exc.reason == "columns":
        return fail(
            name,
            f"a value in column {_col_letter(c)}, right of column "
            f"{_col_letter(_limits.MAX_COLUMNS)} "
            f"(the limit; a norm table has at most {_WIDEST_TABLE} columns)",
            "delete the cells right of the table, or move notes to another sheet",
            at=at,
        )
    if exc.reason == "cells":
        return fail(
            name,
            f"more than {_limits.MAX_CELLS:,} filled cells in the workbook; refused without "
            "reading further",
            "a norm workbook is small: delete unused rows, columns and sheets",
            at=at,
        )
    if exc.reason == "area":
        return fail(
            name,
            f"sheet {title!r} spans more than {_limits.MAX_SHEET_AREA:,} cells from A1 to its "
            f"last value (a value in row {r:,}, column {_col_letter(c)}); refused without "
            "reading further",
            "delete the cells far right of or below the table, or move them to another sheet",
            at=at,
        )
    if exc.reason == "merged":
        return fail(
            name,
            f"sheet {title!r} has more than {_limits.MAX_MERGED:,} merged cell ranges",
            "unmerge the cells (Home → Merge & Center → Unmerge Cells)",
            at=at,
        )
    return fail(
        name,
        f"sheet {title!r} declares a DTD or XML entities; refused, nothing was read",
        "Excel never writes these",
    )


# =========================================================================================
# The workbook part (sheet list) and the styles part (percent formats), with defusedxml
# =========================================================================================


def _parse_part(zf: zipfile.ZipFile, member: str, name: str) -> Any | None:
    """The root element of one (already bounded) XML part, parsed by defusedxml; None when
    the zip has no such member."""
    from defusedxml import DefusedXmlException
    from defusedxml.ElementTree import fromstring

    try:
        data = zf.read(member)
    except KeyError:
        return None
    try:
        return fromstring(data, forbid_dtd=True)
    except DefusedXmlException as exc:
        raise fail(
            name,
            f"zip member {member} declares a DTD or XML entities ({type(exc).__name__}); "
            "refused",
            "Excel never writes these: the file was made by something else",
        ) from None
    except Exception as exc:  # ParseError and the like for a damaged part
        raise fail(
            name,
            f"cannot be read as an .xlsx workbook (zip member {member}: {exc})",
            'open it in Excel and save it as "Excel Workbook (*.xlsx)"',
        ) from None


def _rels(zf: zipfile.ZipFile, part: str, name: str) -> dict[str, tuple[str, str]]:
    """Relationships of ``part``: id → (type, member), targets resolved inside the zip."""
    folder, _, base = part.rpartition("/")
    root = _parse_part(zf, posixpath.join(folder, "_rels", base + ".rels"), name)
    out: dict[str, tuple[str, str]] = {}
    for rel in [] if root is None else root.iter(f"{_REL_NS}Relationship"):
        target = rel.get("Target", "")
        if rel.get("TargetMode") == "External":
            continue
        member = (target[1:] if target.startswith("/") else
                  posixpath.normpath(posixpath.join(folder, target)))
        out[rel.get("Id", "")] = (rel.get("Type", ""), member)
    return out


def _workbook_member(zf: zipfile.ZipFile, name: str) -> str:
    """The workbook part (the package's office document; ``xl/workbook.xml`` from Excel)."""
    for kind, member in _rels(zf, "", name).values():
        if kind.endswith("/officeDocument"):
            return member
    return "xl/workbook.xml"


def _workbook_sheets(zf: zipfile.ZipFile, name: str) -> list[tuple[str, str, str]]:
    """Every worksheet of the workbook: (title, state, zip member), in workbook order.

    Chart sheets are left out; a member that is not in the zip is returned as named (the
    caller reports it). Part names are looked up in the zip, never on disk.
    """
    member = _workbook_member(zf, name)
    root = _parse_part(zf, member, name)
    if root is None:
        raise fail(
            name,
            f"is not an .xlsx workbook (no workbook part {member})",
            'save it from Excel as "Excel Workbook (*.xlsx)"',
        )
    rels = _rels(zf, member, name)
    sheets = []
    for sheet in root.iter(f"{_MAIN_NS}sheet"):
        kind, part = rels.get(sheet.get(_DOC_REL, ""), ("", ""))
        if "chartsheet" in kind:
            continue
        sheets.append((str(sheet.get("name", "")), str(sheet.get("state") or "visible"), part))
    return sheets


def _percent_styles(zf: zipfile.ZipFile, name: str) -> set[int]:
    """Cell style indices (a cell's ``s``) whose number format shows a percentage.

    Built-in formats 9 (``0%``) and 10 (``0.00%``), and custom formats with a ``%`` outside
    quotes and backslash escapes (ECMA-376 part 1, 18.8.30-31).
    """
    root = _parse_part(zf, "xl/styles.xml", name)
    if root is None:
        return set()
    percent_ids = set(_BUILTIN_PERCENT)
    for fmt in root.iter(f"{_MAIN_NS}numFmt"):
        code = re.sub(r'"[^"]*"|\\.', "", fmt.get("formatCode", ""))
        if "%" in code and (fmt.get("numFmtId") or "").isdigit():
            percent_ids.add(int(fmt.get("numFmtId", "")))
    xfs = root.find(f"{_MAIN_NS}cellXfs")
    out = set()
    for i, xf in enumerate([] if xfs is None else xfs.iter(f"{_MAIN_NS}xf")):
        fid = xf.get("numFmtId") or "0"
        if fid.isdigit() and int(fid) in percent_ids:
            out.add(i)
    return out

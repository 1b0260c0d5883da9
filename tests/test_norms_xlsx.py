"""The .xlsx reader on python-calamine: what the bounded pre-scan adds to calamine.

calamine returns Excel errors and formulas without a cached value as empty cells, does not
report number formats and holds a sheet as one dense rectangle; these tests pin what
scanplan.norms.sheetscan and scanplan.norms.xlsx put on top (see docs/norms.md "Reading a
workbook")."""

from __future__ import annotations

import re
import zipfile
from pathlib import Path

import pytest
from norm_corpus import english_workbook, rewrite_member, save, sheet_member

from scanplan.norms import NormImportError, read_norm_file, sheetscan
from scanplan.norms import limits as norms_limits
from scanplan.norms import xlsx as norms_xlsx

NS = b"http://schemas.openxmlformats.org/spreadsheetml/2006/main"
HEADER = (b'<row r="{r}"><c r="{a}{r}" t="inlineStr"><is><t>map_scale</t></is></c>'
          b'<c r="{b}{r}" t="inlineStr"><is><t>object</t></is></c>'
          b'<c r="{c}{r}" t="inlineStr"><is><t>size_m</t></is></c>'
          b'<c r="{d}{r}" t="inlineStr"><is><t>shape</t></is></c></row>')


def sheet_xml(rows: bytes, tail: bytes = b"") -> bytes:
    return (b'<?xml version="1.0" encoding="UTF-8"?>\n<worksheet xmlns="' + NS
            + b'"><sheetData>' + rows + b"</sheetData>" + tail + b"</worksheet>")


def scan(rows: bytes, percent_styles: frozenset[int] = frozenset(), **kw) -> sheetscan._SheetScan:
    s = sheetscan._SheetScan(set(percent_styles), kw.pop("max_rows", 100), **kw)
    s.parse(sheet_xml(rows))
    return s


@pytest.fixture(scope="module")
def book(tmp_path_factory) -> tuple[Path, str]:
    folder = tmp_path_factory.mktemp("xlsx")
    path = save(english_workbook(), folder, "good.xlsx")
    return path, sheet_member(path, "objects")


def with_objects(book, tmp_path: Path, sheet: bytes, name: str = "t.xlsx") -> Path:
    src, member = book
    return rewrite_member(src, tmp_path / name, re.escape(member), lambda _: sheet)


# ---------------------------------------------------------------------------------------
# The pre-scan
# ---------------------------------------------------------------------------------------


def test_scan_positions_follow_r_or_count_on_like_calamine():
    s = scan(b'<row><c><v>1</v></c><c><v>2</v></c><c r="E1"><v>5</v></c><c><v>6</v></c></row>'
             b'<row><c><v>3</v></c></row><row r="5"><c><f>1</f></c></row>')
    assert s.extent == (5, 6)
    assert s.formulas == {(5, 1)}


def test_scan_formatting_only_cells_count_for_no_limit():
    """A styled empty cell in row 1,000,000 or column XFD is no value: not refused."""
    s = scan(b'<row r="2"><c r="A2"><v>1</v></c><c r="XFD2" s="3"/></row>'
             b'<row r="1000000"><c r="A1000000" s="3"/></row>')
    assert s.extent == (2, 1)


@pytest.mark.parametrize(("rows", "reason", "where"), [
    (b'<row r="101"><c r="B101"><v>1</v></c></row>', "rows", (101, 2)),
    (b'<row r="1"><c r="IW1" t="inlineStr"><is><t>x</t></is></c></row>', "columns", (1, 257)),
    (b'<row r="7"><c r="C7"><f>1+1</f></c></row>' * 1 + b'<row r="101"><c r="A101"><f>1</f>'
     b"</c></row>", "rows", (101, 1)),
])
def test_scan_refuses_a_value_past_a_limit_at_its_cell(rows, reason, where):
    with pytest.raises(sheetscan._Refused) as info:
        scan(rows)
    assert (info.value.reason, info.value.where) == (reason, where)


def test_scan_counts_cells_across_sheets_and_stops_at_the_limit():
    rows = b"".join(b'<row r="%d"><c r="A%d"><v>1</v></c></row>' % (r, r) for r in range(1, 6))
    s = scan(rows, max_cells=10)
    assert s.cells_left == 5
    with pytest.raises(sheetscan._Refused) as info:
        scan(rows, max_cells=4)
    assert (info.value.reason, info.value.where) == ("cells", (5, 1))


def test_scan_refuses_a_rectangle_calamine_would_hold_whole(monkeypatch):
    """calamine keeps a sheet as a dense rectangle: A1 and IV200000 would be 51 million
    cells. The rectangle is bounded; the refusal names the cell that widened it."""
    monkeypatch.setattr(norms_limits, "MAX_SHEET_AREA", 1_000)
    with pytest.raises(sheetscan._Refused) as info:
        scan(b'<row r="1"><c r="A1"><v>1</v></c></row><row r="99"><c r="K99"><v>1</v></c></row>')
    assert (info.value.reason, info.value.where) == ("area", (99, 11))
    s = scan(b'<row r="1"><c r="A1"><v>1</v></c></row><row r="99"><c r="J99"><v>1</v></c></row>')
    assert s.extent == (99, 10)  # 990 cells: within


def test_scan_records_error_texts_formulas_and_percent_cells():
    s = scan(b'<row r="2"><c r="A2" t="e"><f>1/0</f><v>#DIV/0!</v></c>'
             b'<c r="B2" t="e"><v>#N/A</v></c><c r="C2" s="4"><v>0.6</v></c>'
             b'<c r="D2" s="4" t="s"><v>0</v></c><c r="E2" s="5"><v>0.6</v></c>'
             b'<c r="F2"><f>SUM(A1)</f><v></v></c></row>', frozenset({4}))
    assert s.errors == {(2, 1): "#DIV/0!", (2, 2): "#N/A"}
    assert s.formulas == {(2, 1), (2, 6)}
    assert s.percent == {(2, 3)}  # a text cell with the style is no percentage


def test_scan_refuses_a_dtd_and_too_many_merges(monkeypatch):
    with pytest.raises(sheetscan._Refused) as info:
        sheetscan._SheetScan(set(), 10).parse(
            b'<!DOCTYPE x [<!ENTITY a "b">]><worksheet/>')
    assert info.value.reason == "dtd"
    monkeypatch.setattr(norms_limits, "MAX_MERGED", 2)
    merges = b"".join(b'<mergeCell ref="A%d:B%d"/>' % (r, r) for r in (1, 4, 9))
    with pytest.raises(sheetscan._Refused) as info:
        sheetscan._SheetScan(set(), 10).parse(
            sheet_xml(b"", b"<mergeCells>" + merges + b"</mergeCells>"))
    assert (info.value.reason, info.value.where) == ("merged", (9, 1))


# ---------------------------------------------------------------------------------------
# Styles and the sheet list (defusedxml)
# ---------------------------------------------------------------------------------------


def _zip(tmp_path: Path, parts: dict[str, bytes]) -> zipfile.ZipFile:
    p = tmp_path / "parts.zip"
    with zipfile.ZipFile(p, "w") as zf:
        for k, v in parts.items():
            zf.writestr(k, v)
    return zipfile.ZipFile(p)


def test_percent_styles_builtin_and_custom_formats(tmp_path):
    """Built-in 9 (0%) and 10 (0.00%), custom formats with a real %; a quoted or escaped
    % is a literal sign (Excel does not scale the value) and is no percent format."""
    styles = (b'<styleSheet xmlns="' + NS + b'"><numFmts count="4">'
              b'<numFmt numFmtId="164" formatCode="0.0%"/>'
              b'<numFmt numFmtId="165" formatCode="0&quot;%&quot;"/>'
              b'<numFmt numFmtId="166" formatCode="0\\%"/>'
              b'<numFmt numFmtId="167" formatCode="#,##0.00"/></numFmts>'
              b'<cellStyleXfs count="1"><xf numFmtId="9"/></cellStyleXfs>'
              b'<cellXfs count="7"><xf numFmtId="0"/><xf numFmtId="9"/><xf numFmtId="10"/>'
              b'<xf numFmtId="164"/><xf numFmtId="165"/><xf numFmtId="166"/>'
              b'<xf numFmtId="167"/></cellXfs></styleSheet>')
    with _zip(tmp_path, {"xl/styles.xml": styles}) as zf:
        assert sheetscan._percent_styles(zf, "t.xlsx") == {1, 2, 3}
    with _zip(tmp_path, {"xl/other.xml": b"<x/>"}) as zf:
        assert sheetscan._percent_styles(zf, "t.xlsx") == set()


def test_sheet_list_states_members_and_chart_sheets(book):
    path, member = book
    with zipfile.ZipFile(path) as zf:
        sheets = sheetscan._workbook_sheets(zf, path.name)
    assert [s[0] for s in sheets] == ["parameters", "shapes", "objects"]
    assert dict((t, m) for t, _, m in sheets)["objects"] == member
    assert {s[1] for s in sheets} == {"visible"}


def test_a_dtd_in_the_styles_is_refused_by_defusedxml_too(book, tmp_path, monkeypatch):
    """With the byte pattern and the expat check off, defusedxml refuses it."""
    path, _ = book
    bad = rewrite_member(path, tmp_path / "styles.xlsx", r"xl/styles\.xml",
                         lambda d: b'<!DOCTYPE s [<!ENTITY a "b">]>'
                         + re.sub(rb"^<\?xml[^>]*\?>\s*", b"", d))
    monkeypatch.setattr(norms_xlsx, "_DOCTYPE", re.compile(rb"(?!)"))
    monkeypatch.setattr(norms_xlsx, "_dtd_refusing_parser", lambda: None)
    with pytest.raises(NormImportError, match=r"xl/styles\.xml declares a DTD"):
        read_norm_file(bad)


# ---------------------------------------------------------------------------------------
# The grids calamine's values become
# ---------------------------------------------------------------------------------------


def _objects(grid_rows: bytes, tail: bytes = b"", **cols: bytes) -> bytes:
    letters = {"a": b"A", "b": b"B", "c": b"C", "d": b"D", **cols}
    head = HEADER
    for k, v in letters.items():
        head = head.replace(b"{%s}" % k.encode(), v)
    return sheet_xml(head.replace(b"{r}", b"1") + grid_rows, tail)


def test_table_away_from_a1_keeps_its_cell_addresses(book, tmp_path):
    """calamine's rows start at the first column holding a value; the grid puts them back
    at their columns, so messages name the cell Excel shows (D4, not B2)."""
    head = HEADER
    for k, v in {"a": b"C", "b": b"D", "c": b"E", "d": b"F"}.items():
        head = head.replace(b"{%s}" % k.encode(), v)
    rows = (head.replace(b"{r}", b"3")
            + b'<row r="4"><c r="C4"><v>2000</v></c><c r="D4" t="inlineStr"><is><t>poles</t>'
              b'</is></c><c r="E4" t="inlineStr"><is><t>big</t></is></c>'
              b'<c r="F4" t="inlineStr"><is><t>circle</t></is></c></row>')
    p = with_objects(book, tmp_path, sheet_xml(rows))
    with pytest.raises(NormImportError) as info:
        read_norm_file(p)
    assert "'objects'!E4" in str(info.value) and 'column "size_m"' in str(info.value)


def test_error_and_formula_in_the_last_column_are_found(book, tmp_path):
    """calamine returns both as empty cells at the end of a row (trimmed); the reader puts
    the error back and still finds the formula without a value."""
    rows = (b'<row r="2"><c r="A2"><v>2000</v></c><c r="B2" t="inlineStr"><is><t>poles</t>'
            b'</is></c><c r="C2" t="e"><v>#VALUE!</v></c></row>'
            b'<row r="3"><c r="A3"><v>5000</v></c><c r="B3" t="inlineStr"><is><t>wells</t>'
            b'</is></c><c r="C3"><v>0.5</v></c><c r="D3"><f>A1</f><v></v></c></row>')
    p = with_objects(book, tmp_path, _objects(rows))
    with pytest.raises(NormImportError) as info:
        read_norm_file(p)
    msg = str(info.value)
    assert "'objects'!C2" in msg and "the cell shows an Excel error" in msg and "#VALUE!" in msg
    assert "'objects'!D3" in msg and "formula without a cached value" in msg


def test_merged_header_cells_come_from_calamine(book, tmp_path):
    """A group header merged over two columns ("size" over "m"), read as calamine
    reports the merge: the table imports."""
    rows = (b'<row r="1"><c r="A1" t="inlineStr"><is><t>map_scale</t></is></c>'
            b'<c r="B1" t="inlineStr"><is><t>object</t></is></c>'
            b'<c r="C1" t="inlineStr"><is><t>size</t></is></c>'
            b'<c r="D1" t="inlineStr"><is><t>shape</t></is></c></row>'
            b'<row r="2"><c r="C2" t="inlineStr"><is><t>m</t></is></c></row>'
            b'<row r="3"><c r="A3"><v>2000</v></c><c r="B3" t="inlineStr"><is><t>poles</t>'
            b'</is></c><c r="C3"><v>0.2</v></c><c r="D3" t="inlineStr"><is><t>circle</t>'
            b"</is></c></row>")
    merges = b'<mergeCells count="3"><mergeCell ref="A1:A2"/><mergeCell ref="B1:B2"/>' \
             b'<mergeCell ref="D1:D2"/></mergeCells>'
    p = with_objects(book, tmp_path, sheet_xml(rows, merges))
    parsed = read_norm_file(p)
    assert [r["size_m"] for r in parsed.tables["objects"]] == ["0.2"]


def test_sparse_far_cells_are_kept_sparse(book, tmp_path):
    """A value at IV in every row: rows are kept as a few cells, not 256-wide lists."""
    rows = b"".join(b'<row r="%d"><c r="A%d"><v>%d</v></c><c r="B%d" t="inlineStr"><is>'
                    b'<t>o%d</t></is></c><c r="C%d"><v>0.5</v></c><c r="D%d" t="inlineStr">'
                    b'<is><t>circle</t></is></c><c r="IV%d" t="inlineStr"><is><t>note</t>'
                    b'</is></c></row>' % (r, r, 1000 + r, r, r, r, r, r)
                    for r in range(2, 50))
    p = with_objects(book, tmp_path, _objects(rows))
    grids = {g.label: g for g in norms_xlsx._read_xlsx(p)}
    row = grids["objects"].rows[5]
    assert isinstance(row, norms_xlsx._SparseRow) and len(row) == 256
    assert row[255] == "note" and row[100] is None and row[0] == 1006.0
    assert len(read_norm_file(p).tables["objects"]) == 48


# ---------------------------------------------------------------------------------------
# The pre-scan's fast path (byte patterns) and its expat path agree
# ---------------------------------------------------------------------------------------

_CELLS = [
    b'<c r="{c}{r}"><v>1</v></c>',
    b'<c r="{c}{r}" t="s"><v>0</v></c>',
    b'<c r="{c}{r}" t="inlineStr"><is><t>x</t></is></c>',
    b'<c r="{c}{r}" s="3"/>',
    b'<c r="{c}{r}" s="4"><v>0.6</v></c>',  # percent style
    b'<c r="{c}{r}"></c>',
    b"<c><v>2</v></c>",  # no reference
    b'<c r="{c}{r}"><f>1+1</f><v></v></c>',
    b'<c r="{c}{r}" t="e"><v>#N/A</v></c>',
    b'<c r="{c}{r}">\n  <v>3</v>\n</c>',  # pretty-printed
    b'<c r="{c}{r}" t=\'e\'><v>#REF!</v></c>',
    b'<x:c r="{c}{r}"><x:v>4</x:v></x:c>',
]


def _random_sheet(rng) -> bytes:
    rows = []
    r = 0
    kinds = _CELLS if rng.random() < 0.6 else [*_CELLS[:4], _CELLS[5]]  # else plain cells
    for _ in range(rng.randint(0, 40)):
        r += rng.choice((1, 1, 1, 2, 30))
        cells = []
        for c in sorted(rng.sample(range(1, 30), rng.randint(0, 6))):
            letters = sheetscan._col_letter(c if rng.random() > 0.05 else 300).encode()
            cells.append(rng.choice(kinds).replace(b"{c}", letters).replace(b"{r}", b"%d" % r))
        head = b'<row r="%d">' % r if kinds is not _CELLS or rng.random() > 0.1 else b"<row>"
        rows.append(head + b"".join(cells) + b"</row>")
    tail = b""
    if rng.random() < 0.3:
        tail = b"<mergeCells>" + b'<mergeCell ref="A1:B2"/>' * rng.randint(1, 3) + b"</mergeCells>"
    return (b'<?xml version="1.0"?>\n<worksheet xmlns="' + NS + b'" xmlns:x="' + NS
            + b'"><sheetData>' + b"".join(rows) + b"</sheetData>" + tail + b"</worksheet>")


def _outcome(data: bytes, fast: bool, cuts: list[int], max_rows: int, max_cells: int):
    s = sheetscan._SheetScan({4}, max_rows, max_cells=max_cells, max_columns=200, fast=fast)
    try:
        start = 0
        for cut in [*cuts, len(data)]:
            s.feed(data[start:cut])
            start = cut
        s.close()
    except sheetscan._Refused as exc:
        return ("refused", exc.reason, exc.where)
    return (s.extent, s.cells_left, s.formulas, s.errors, s.percent, s.merged)


def test_fast_and_expat_scans_agree_on_random_sheets():
    """Many random sheets of plain and unusual cells, each cut into random chunks: the
    fast path (switching to expat where it must) gives what expat alone gives."""
    import random

    rng = random.Random(20261123)
    switched = plain = 0
    for _ in range(600):
        data = _random_sheet(rng)
        cuts = sorted(rng.sample(range(1, len(data)), min(len(data) - 1, rng.randint(0, 8))))
        limits = (rng.choice((30, 200, 10**6)), rng.choice((15, 10**6)))
        want = _outcome(data, False, cuts, *limits)
        assert _outcome(data, True, cuts, *limits) == want, data
        s = sheetscan._SheetScan({4}, 10**6, max_columns=10**6, max_cells=10**9)
        s.feed(data)
        switched += s._exact
        plain += not s._exact
    assert switched > 100 and plain > 100  # both paths were exercised


def test_fast_path_takes_a_plain_sheet_without_expat_handlers(monkeypatch):
    rows = b"".join(b'<row r="%d"><c r="A%d"><v>1</v></c><c r="B%d" t="s"><v>0</v></c>'
                    b'<c r="C%d" s="2"/></row>' % (r, r, r, r) for r in range(1, 2000))
    calls = []
    monkeypatch.setattr(sheetscan._SheetScan, "_start", lambda self, *a: calls.append(a))
    s = sheetscan._SheetScan(set(), 5000)
    data = sheet_xml(rows)
    for i in range(0, len(data), 1000):
        s.feed(data[i:i + 1000])
    assert not s._exact and calls == []
    s.close()  # the last unfinished bit goes through expat
    assert s.extent == (1999, 2) and s.cells_left == norms_limits.MAX_CELLS - 2 * 1999


def test_a_row_without_reference_hands_the_right_row_to_expat():
    """The fast path leaves the part to expat at the formula; the row before it has no
    ``r``: the formula cell is in row 2 (one below), not row 1."""
    rows = b'<row r="1"><c r="A1"><v>1</v></c></row><row><c><f>1</f></c></row>'
    for fast in (True, False):
        assert scan(rows, fast=fast).formulas == {(2, 1)}


def test_sheet_area_refusal_names_the_cell(book, tmp_path, monkeypatch):
    monkeypatch.setattr(norms_limits, "MAX_SHEET_AREA", 200)
    rows = b'<row r="2"><c r="A2"><v>2000</v></c></row><row r="30"><c r="H30"><v>1</v></c></row>'
    p = with_objects(book, tmp_path, _objects(rows))
    with pytest.raises(NormImportError) as info:
        read_norm_file(p)
    msg = str(info.value)
    assert "'objects'!H30" in msg and "spans more than 200 cells" in msg
    assert "delete the cells far right of or below the table" in msg

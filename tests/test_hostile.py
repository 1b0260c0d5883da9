"""Hostile files (issue 7): every one is refused or neutralised with a clear message, in
bounded time and memory, through the command line (click's CliRunner on ``scanplan.cli.main.main``)
and the API.

- norm workbooks: entity expansion (sheet, shared strings, external entities, UTF-16), a real
  zip bomb (300 MB deflated to 0.3 MB) and a zip whose sizes lie, a real 1,000,000-row sheet,
  formula cells with and without a cached value, formula-injection text, far columns,
  merged-cell and row-number bombs, a huge cell, a huge zip directory, damaged zips;
- norm CSVs: 1,000,000 lines, formula-injection text, NUL bytes, bad encodings, huge cells,
  endless lines, too many columns, control characters;
- project files: HTML, ``file://`` and ``http://`` in every text key (the PDF shows them
  literally and fetches nothing, the workbook stores text), control characters, ``..`` in
  names, FIFOs and ``/dev/zero``;
- names with ``..``: ``--name``, ``--norms``, ``--camera``, ``[norms] set``, ``[uav] camera``,
  ``--out``, a workbook's part names.

Time is bounded by construction (limits checked before work, reading stops at the first
limit): no test asserts a duration. Memory is measured (``tracemalloc`` in process, or the
peak RSS of a child process for the million-row files) against a generous bound.
"""

from __future__ import annotations

import contextlib
import csv
import json
import os
import re
import resource
import shutil
import signal
import socket
import subprocess
import sys
import textwrap
import tracemalloc
import zipfile
from pathlib import Path

import openpyxl
import pytest
from click.testing import CliRunner
from norm_corpus import BILLION_LAUGHS, english_workbook, save, sheet_member, to_shared_strings

from scanplan.cli.main import main
from scanplan.norms import DEFAULT_NORM_SET, bundled_norms_dir
from scanplan.norms import cells as norms_cells
from scanplan.norms import importer as norms_importer
from scanplan.norms import limits as norms_limits
from scanplan.norms import xlsx as norms_xlsx
from scanplan.norms.schema import TABLES

MB = 2**20
MEMORY_BOUND_MB = 200  # generous: what any refused file may cost on top of the program


# ---------------------------------------------------------------------------------------
# Helpers
# ---------------------------------------------------------------------------------------

_OPENED: list[str] | None = None


def _audit(event: str, args: tuple) -> None:
    if _OPENED is not None and event == "open" and args:
        path = args[0]
        if isinstance(path, str | bytes | os.PathLike):
            _OPENED.append(os.fsdecode(path))


sys.addaudithook(_audit)  # inert unless a test arms it with opened_files()


@contextlib.contextmanager
def opened_files():
    """Every path Python opens inside the block (``open`` audit events)."""
    global _OPENED
    _OPENED = []
    try:
        yield _OPENED
    finally:
        _OPENED = None


@contextlib.contextmanager
def hang_guard(seconds: int = 60):
    """Fail (instead of hanging for ever) if the block blocks, e.g. on a FIFO."""

    def boom(*_):
        raise TimeoutError(f"blocked for {seconds} s")

    old = signal.signal(signal.SIGALRM, boom)
    signal.alarm(seconds)
    try:
        yield
    finally:
        signal.alarm(0)
        signal.signal(signal.SIGALRM, old)


def cli(*args: str):
    """Run ``scanplan ARGS``; never a traceback, whatever happens."""
    r = CliRunner().invoke(main, [str(a) for a in args])
    out = r.output + (r.stderr or "")
    assert "Traceback" not in out, out
    assert r.exception is None or isinstance(r.exception, SystemExit), repr(r.exception)
    return r


def refused(r, *parts: str) -> str:
    """Exit 2 with ``error: ...`` naming each of ``parts``; returns stderr."""
    err = r.stderr
    assert r.exit_code == 2, (r.exit_code, r.output)
    assert err.startswith("error: "), err
    for part in parts:
        assert part in err, (part, err)
    return err


def peak_mb(fn, *args, **kwargs):
    """(result or exception, peak Python allocation in MB) of ``fn(*args)``."""
    tracemalloc.start()
    try:
        try:
            out = fn(*args, **kwargs)
        except Exception as exc:  # the refusal is the result
            out = exc
        return out, tracemalloc.get_traced_memory()[1] / MB
    finally:
        tracemalloc.stop()


def tree(root: Path) -> set[str]:
    return {str(p.relative_to(root)) for p in root.rglob("*")}


def parts_of(path: Path) -> dict[str, bytes]:
    with zipfile.ZipFile(path) as zf:
        return {i.filename: zf.read(i) for i in zf.infolist()}


def write_xlsx(dst: Path, parts: dict[str, bytes], stream: tuple | None = None,
               level: int = 6) -> Path:
    """A zip of ``parts``; ``stream=(member, chunks)`` writes one member chunk by chunk
    (zipfile streaming writes: nothing big is ever held in memory)."""
    with zipfile.ZipFile(dst, "w", zipfile.ZIP_DEFLATED, compresslevel=level) as zf:
        for name, data in parts.items():
            if stream and name == stream[0]:
                with zf.open(name, "w") as fh:
                    for chunk in stream[1]:
                        fh.write(chunk)
            else:
                zf.writestr(name, data)
    return dst


@pytest.fixture(scope="module")
def book(tmp_path_factory):
    """The bundled set as a workbook: (path, parts, member of the objects sheet)."""
    folder = tmp_path_factory.mktemp("book")
    path = save(english_workbook(), folder, "good.xlsx")
    return path, parts_of(path), sheet_member(path, "objects")


def sheet_xml(rows: bytes, tail: bytes = b"") -> bytes:
    ns = b"http://schemas.openxmlformats.org/spreadsheetml/2006/main"
    return (b'<?xml version="1.0" encoding="UTF-8" standalone="yes"?>\n<worksheet xmlns="' + ns
            + b'"><sheetData>' + rows + b"</sheetData>" + tail + b"</worksheet>")


OBJECTS_HEADER = (b'<row r="1"><c r="A1" t="inlineStr"><is><t>map_scale</t></is></c>'
                  b'<c r="B1" t="inlineStr"><is><t>object</t></is></c>'
                  b'<c r="C1" t="inlineStr"><is><t>size_m</t></is></c>'
                  b'<c r="D1" t="inlineStr"><is><t>shape</t></is></c></row>')


def objects_row(r: int, scale: bytes = b"2000", obj: bytes = b"poles", size: bytes = b"0.2",
                shape: bytes = b"circle") -> bytes:
    return (b'<row r="%d"><c r="A%d"><v>%s</v></c><c r="B%d" t="inlineStr"><is><t>%s</t></is>'
            b'</c><c r="C%d"><v>%s</v></c><c r="D%d" t="inlineStr"><is><t>%s</t></is></c></row>'
            % (r, r, scale, r, obj, r, size, r, shape))


def with_objects(book, tmp_path: Path, name: str, sheet: bytes) -> Path:
    """The good workbook with the objects sheet replaced by ``sheet``."""
    _, parts, member = book
    return write_xlsx(tmp_path / name, {**parts, member: sheet})


CHILD = textwrap.dedent("""
    import json, resource, sys, time
    def peak_kb():  # VmHWM: this process's own peak (ru_maxrss starts at the parent's)
        try:
            with open("/proc/self/status") as fh:
                return next(int(ln.split()[1]) for ln in fh if ln.startswith("VmHWM:"))
        except (OSError, StopIteration):
            return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
    from scanplan.norms import cells as norms_cells
    from scanplan.norms import importer as norms_importer
    from scanplan.norms import limits as norms_limits
    from scanplan.norms import xlsx as norms_xlsx
    from click.testing import CliRunner
    from scanplan.cli.main import main
    fed = [0]
    feed = norms_xlsx._SheetScan.feed
    def counting(self, data):
        fed[0] += len(data)
        return feed(self, data)
    norms_xlsx._SheetScan.feed = counting
    before = peak_kb()
    t = time.perf_counter()
    r = CliRunner().invoke(main, sys.argv[1:])
    print(json.dumps({"exit": r.exit_code, "stderr": r.stderr, "seconds": time.perf_counter() - t,
                      "rss_mb": (peak_kb() - before) / 1024, "fed": fed[0],
                      "traceback": "Traceback" in r.output}))
""")


def run_child(*args: str, env: dict | None = None) -> dict:
    """``scanplan ARGS`` in a fresh process (address space capped at 2 GB): its exit code,
    stderr, seconds, peak RSS growth [MB] and the worksheet bytes parsed."""

    def cap():
        resource.setrlimit(resource.RLIMIT_AS, (2 << 30, 2 << 30))

    p = subprocess.run([sys.executable, "-c", CHILD, *map(str, args)], capture_output=True,
                       text=True, preexec_fn=cap, env={**os.environ, **(env or {})},
                       timeout=600)
    assert p.returncode == 0, p.stderr[-2000:]
    return json.loads(p.stdout.splitlines()[-1])


MEASURED: dict[str, str] = {}  # case → "time, memory" (printed with -s; see the report)


def note(case: str, **numbers: float) -> None:
    MEASURED[case] = ", ".join(f"{k} {v:.2f}" for k, v in numbers.items())
    print(f"[measured] {case}: {MEASURED[case]}")


# ---------------------------------------------------------------------------------------
# 1. XML entity expansion and external entities: refused, nothing read
# ---------------------------------------------------------------------------------------

XXE = (b'<?xml version="1.0" encoding="UTF-8"?>\n'
       b'<!DOCTYPE worksheet [<!ENTITY xxe SYSTEM "file:///etc/passwd">]>\n')


def _sheet_with_entity(prolog: bytes, entity: bytes) -> bytes:
    body = sheet_xml(OBJECTS_HEADER + b'<row r="2"><c r="A2"><v>2000</v></c><c r="B2" '
                     b't="inlineStr"><is><t>' + entity + b"</t></is></c></row>")
    return prolog + re.sub(rb"^<\?xml[^>]*\?>\s*", b"", body)


@pytest.mark.parametrize("case", ["laughs-sheet", "laughs-shared-strings", "xxe-sheet",
                                  "xxe-shared-strings", "laughs-utf16-sheet"])
@pytest.mark.parametrize("prescan", [True, False], ids=["prescan", "parsers-only"])
def test_entities_refused_and_nothing_read(case, prescan, book, tmp_path, user_dir,
                                           monkeypatch):
    """Billion laughs and ``SYSTEM "file:///etc/passwd"`` in a worksheet or in the shared
    strings: exit 2 naming the file (and the part), nothing written, /etc/passwd never
    opened. ``parsers-only``: with the byte pre-scan switched off, the parsers themselves
    (expat for sheets, defusedxml under openpyxl for shared strings) refuse the DTD."""
    path, parts, member = book
    if "shared" in case:
        shared = to_shared_strings(path, tmp_path / "shared.xlsx")
        parts = parts_of(shared)
        prolog = BILLION_LAUGHS if "laughs" in case else XXE
        entity = b"&lol9;" if "laughs" in case else b"&xxe;"
        body = re.sub(rb"^<\?xml[^>]*\?>\s*", b"", parts["xl/sharedStrings.xml"])
        parts["xl/sharedStrings.xml"] = prolog + body.replace(b"<si><t>", b"<si><t>" + entity, 1)
        where = "xl/sharedStrings.xml"
    else:
        prolog = XXE if "xxe" in case else BILLION_LAUGHS
        entity = b"&xxe;" if "xxe" in case else b"&lol9;"
        sheet = _sheet_with_entity(prolog, entity)
        if "utf16" in case:  # the DTD as UTF-16: not the bytes "<!DOCTYPE"
            sheet = sheet.replace(b'encoding="UTF-8"', b'encoding="UTF-16"').decode()
            sheet = sheet.encode("utf-16")
        parts = {**parts, member: sheet}
        where = "objects" if not prescan else member
    bad = write_xlsx(tmp_path / f"{case}.xlsx", parts)
    if not prescan:
        monkeypatch.setattr(norms_xlsx, "_DOCTYPE", re.compile(rb"(?!)"))
    with opened_files() as opened:
        r = cli("norms", "import", bad, "--name", "x")
    err = refused(r, f"{case}.xlsx", "DTD or XML entities")
    if prescan or "shared" not in case:
        assert where in err, err
    assert "root:" not in r.output + err
    assert not any("passwd" in p for p in opened), opened
    assert list(user_dir.iterdir()) == []


# ---------------------------------------------------------------------------------------
# 2. Zip bombs: refused from the zip directory, before decompression
# ---------------------------------------------------------------------------------------

BOMB_MB = 300


@pytest.fixture(scope="module")
def bomb(book, tmp_path_factory):
    """The objects sheet padded with 300 MB of spaces (valid XML), deflated to ~0.3 MB."""
    _, parts, member = book
    folder = tmp_path_factory.mktemp("bomb")
    head = parts[member]
    pad = b" " * MB
    path = write_xlsx(folder / "bomb.xlsx", parts,
                      (member, [head, *([pad] * BOMB_MB)]), level=9)
    return path, member


def _set_size(path: Path, member: str, size: int) -> None:
    """Make the zip's local and central headers claim ``size`` bytes for ``member``."""
    data = bytearray(path.read_bytes())
    name = member.encode()
    for sig, off in ((b"PK\x03\x04", 22), (b"PK\x01\x02", 24)):
        i = data.find(sig)
        while i >= 0:
            n = int.from_bytes(data[i + off + 4: i + off + 6] if sig == b"PK\x03\x04"
                               else data[i + 28: i + 30], "little")
            start = i + (30 if sig == b"PK\x03\x04" else 46)
            if data[start: start + n] == name:
                data[i + off: i + off + 4] = size.to_bytes(4, "little")
            i = data.find(sig, i + 4)
    path.write_bytes(bytes(data))


def test_zip_bomb_refused_before_decompression(bomb, user_dir):
    path, member = bomb
    assert path.stat().st_size < MB
    with zipfile.ZipFile(path) as zf:
        assert zf.getinfo(member).file_size > BOMB_MB * MB
    r = cli("norms", "import", path, "--name", "x")
    refused(r, "bomb.xlsx", member, "would unpack to 300.0 MB", "the limit is 100.0 MB")
    exc, peak = peak_mb(norms_importer.read_norm_file, path)
    assert isinstance(exc, norms_cells.NormImportError)
    assert peak < MEMORY_BOUND_MB
    note("zip bomb (300 MB in 0.3 MB)", peak_python_mb=peak)
    assert list(user_dir.iterdir()) == []


def test_zip_bomb_with_lying_sizes_reads_only_what_it_claims(bomb, tmp_path, monkeypatch):
    """The headers claim 1,000 bytes for the 300 MB member (no ratio check applies below
    1 MB): reading stops after 1,000 bytes and the CRC exposes the lie — exit 2, bounded."""
    path, member = bomb
    liar = tmp_path / "liar.xlsx"
    shutil.copy(path, liar)
    _set_size(liar, member, 1000)
    with zipfile.ZipFile(liar) as zf:
        assert zf.getinfo(member).file_size == 1000
    fed: dict[str, int] = {}
    real = norms_xlsx._stream_member

    def counting(zf, info, name, part, sink):
        fed[info.filename] = 0

        def count(chunk):
            fed[info.filename] += len(chunk)
            sink(chunk)

        return real(zf, info, name, part, count)

    monkeypatch.setattr(norms_xlsx, "_stream_member", counting)
    exc, peak = peak_mb(norms_importer.read_norm_file, liar)
    assert isinstance(exc, norms_cells.NormImportError), exc
    assert "damaged" in str(exc) and member in str(exc)
    assert fed[member] <= 1000 and peak < MEMORY_BOUND_MB
    note("zip with lying sizes", peak_python_mb=peak)
    refused(cli("norms", "validate", liar), "liar.xlsx", "damaged")


def test_total_size_and_member_count_limits(book, tmp_path, monkeypatch):
    """Members under every per-member limit that add up to too much; too many members; a
    huge zip directory (checked before :mod:`zipfile` parses it)."""
    _, parts, _ = book
    pads = {f"xl/media/pad{i}.bin": b"\0" * 900_000 for i in range(3)}
    p = write_xlsx(tmp_path / "total.xlsx", {**parts, **pads})
    monkeypatch.setattr(norms_limits, "MAX_TOTAL_UNCOMPRESSED_BYTES", 2_000_000)
    refused(cli("norms", "validate", p), "total.xlsx", "would unpack to", "the limit is 1.9 MB")
    many = {f"xl/media/{i}.bin": b"" for i in range(10_001)}
    p = write_xlsx(tmp_path / "many.xlsx", {**parts, **many})
    refused(cli("norms", "validate", p), "many.xlsx", "10,012 zip members")
    monkeypatch.setattr(norms_limits, "MAX_ZIP_DIRECTORY_BYTES", 100_000)
    refused(cli("norms", "validate", p), "many.xlsx", "zip directory")


# ---------------------------------------------------------------------------------------
# 3. A real 1,000,000-row sheet and a 1,000,000-line CSV: refused, reading stops early
# ---------------------------------------------------------------------------------------

ROWS = 1_000_000


def _million_compact(start: int, stop: int):
    """Rows ``<row r="i"><c r="Ai"><v>i</v></c></row>``, 100,000 at a time."""
    for a in range(start, stop, 100_000):
        yield b"".join(b'<row r="%d"><c r="A%d"><v>%d</v></c></row>' % (i, i, i)
                       for i in range(a, min(a + 100_000, stop)))


def test_million_row_sheet_refused_after_the_limit(book, tmp_path, user_dir):
    """1,000,001 rows (46 MB of XML, 5 MB zipped): exit 2 at row 200,021, having parsed
    ~20 % of the sheet — never the rest, never all of it in memory."""
    _, parts, member = book
    head, tail = sheet_xml(b"\x00").split(b"\x00")
    chunks = [head, OBJECTS_HEADER, *_million_compact(2, ROWS + 2), tail]
    path = write_xlsx(tmp_path / "million.xlsx", parts, (member, chunks), level=1)
    with zipfile.ZipFile(path) as zf:
        size = zf.getinfo(member).file_size
    assert size > 40 * MB
    res = run_child("norms", "import", path, "--name", "x",
                    env={"SCANPLAN_NORMS_DIR": str(user_dir)})
    assert res["exit"] == 2 and not res["traceback"], res
    assert "'objects'!A200021" in res["stderr"]
    assert "has more than 200,000 rows" in res["stderr"]
    assert res["fed"] < size * 0.35  # stopped early: the parser saw about a fifth of it
    assert res["rss_mb"] < MEMORY_BOUND_MB, res
    note("1,000,000-row sheet", seconds=res["seconds"], rss_growth_mb=res["rss_mb"],
         parsed_share=res["fed"] / size)
    assert list(user_dir.iterdir()) == []


def test_million_row_sheet_as_excel_writes_it_is_refused_unopened(book, tmp_path):
    """The same million rows with four columns, as a real Excel sheet is: 150+ MB of XML,
    refused from the zip directory (member size) before a byte is decompressed."""
    _, parts, member = book
    row = (b'<row><c><v>2000</v></c><c t="inlineStr"><is><t>poles</t></is></c><c><v>0.2</v>'
           b'</c><c t="inlineStr"><is><t>circle</t></is></c></row>')
    block = row * 10_000
    head, tail = sheet_xml(b"\x00").split(b"\x00")
    path = write_xlsx(tmp_path / "excel-million.xlsx", parts,
                      (member, [head, OBJECTS_HEADER, *([block] * (ROWS // 10_000)), tail]),
                      level=1)
    with zipfile.ZipFile(path) as zf:
        assert zf.getinfo(member).file_size > norms_limits.MAX_MEMBER_BYTES
    exc, peak = peak_mb(norms_importer.read_norm_file, path)
    assert "would unpack to" in str(exc) and f"at most {norms_limits.MAX_ROWS:,} rows" in str(exc)
    assert peak < 20
    refused(cli("norms", "validate", path), "excel-million.xlsx", member)


def test_million_line_csv_refused_after_the_limit(tmp_path, user_dir):
    path = tmp_path / "objects.csv"
    with path.open("w", encoding="utf-8") as fh:
        fh.write("map_scale,object,size_m,shape\n")
        for a in range(1, ROWS + 1, 100_000):
            fh.write("".join(f"{i},o,0.5,circle\n" for i in range(a, a + 100_000)))
    assert path.stat().st_size < norms_limits.MAX_FILE_BYTES
    res = run_child("norms", "import", path, "--name", "x",
                    env={"SCANPLAN_NORMS_DIR": str(user_dir)})
    assert res["exit"] == 2 and not res["traceback"], res
    assert "'objects'!A200021" in res["stderr"] and "more than 200,000 rows" in res["stderr"]
    assert res["rss_mb"] < MEMORY_BOUND_MB, res
    note("1,000,000-line CSV", seconds=res["seconds"], rss_growth_mb=res["rss_mb"])
    assert list(user_dir.iterdir()) == []


def test_row_numbers_and_columns_far_away(book, tmp_path):
    """A value in row 999,999,999 or in column XFD (the grid was built up to it: hours, or
    GBs — 16,384 columns × every row); 5,000 rows each with a value at XFD."""
    far_row = sheet_xml(OBJECTS_HEADER + objects_row(2)
                        + b'<row r="3"><c r="A999999999"><v>1</v></c></row>')
    p = with_objects(book, tmp_path, "far-row.xlsx", far_row)
    with hang_guard():
        err = refused(cli("norms", "validate", p), "'objects'!A999999999",
                      "more than 200,000 rows")
    assert "row 999,999,999" in err
    wide = sheet_xml(OBJECTS_HEADER + b"".join(
        objects_row(r)[:-6] + b'<c r="XFD%d"><v>1</v></c></row>' % r for r in range(2, 5002)))
    p = with_objects(book, tmp_path, "wide.xlsx", wide)
    exc, peak = peak_mb(norms_importer.read_norm_file, p)
    assert "'objects'!XFD2" in str(exc) and "right of column IV" in str(exc)
    assert peak < 50
    widest = max(len(t.columns) for t in TABLES.values())  # the camera table's
    refused(cli("norms", "validate", p), "'objects'!XFD2",
            f"a norm table has at most {widest} columns")


def test_merged_cell_bombs(book, tmp_path):
    """Merges down to row 1,048,576 were expanded cell by cell (a dict entry per row);
    now they are looked up. More than 1,000 merged ranges: refused."""
    merges = b"".join(b'<mergeCell ref="%s2:%s1048576"/>' % (c, c) for c in (b"E", b"F", b"G"))
    rows = OBJECTS_HEADER + b"".join(objects_row(r, b"%d" % (1000 * r)) for r in range(2, 6))
    rows = rows.replace(b"</row>", b'<c r="E2" t="inlineStr"><is><t>note</t></is></c></row>', 2)
    rows = rows.replace(b'<c r="E2" t="inlineStr"><is><t>note</t></is></c></row>', b"</row>", 1)
    sheet = sheet_xml(rows, b'<mergeCells count="3">' + merges + b"</mergeCells>")
    p = with_objects(book, tmp_path, "merged.xlsx", sheet)
    parsed, peak = peak_mb(norms_importer.read_norm_file, p)
    assert not isinstance(parsed, Exception), parsed
    assert peak < 30
    many = b"".join(b'<mergeCell ref="H%d:I%d"/>' % (r, r) for r in range(1, 1002))
    sheet = sheet_xml(OBJECTS_HEADER + objects_row(2), b"<mergeCells>" + many + b"</mergeCells>")
    p = with_objects(book, tmp_path, "merged-many.xlsx", sheet)
    refused(cli("norms", "validate", p), "merged-many.xlsx", "'objects'!H1001",
            "more than 1,000 merged")


# ---------------------------------------------------------------------------------------
# 4. Formulas: without a cached value refused (cell named), with one the value is used
# ---------------------------------------------------------------------------------------


def test_formula_without_cached_value_names_the_cell(tmp_path, user_dir):
    wb = english_workbook()
    wb["objects"]["D3"] = "=1/0"  # openpyxl writes the formula and no cached value
    path = save(wb, tmp_path, "formula.xlsx")
    r = cli("norms", "import", path, "--name", "x")
    refused(r, "'objects'!D3", "formula without a cached value",
            "open and save the file in Excel")
    assert list(user_dir.iterdir()) == []


def test_formula_with_cached_value_uses_the_value_never_the_formula(book, tmp_path, user_dir):
    """A number and a text formula with cached values (as Excel saves them): imported with
    the values; the written CSV holds "x", not ``=HYPERLINK(...)``."""
    rows = (OBJECTS_HEADER + objects_row(2)
            + b'<row r="3"><c r="A3"><v>5000</v></c><c r="B3" t="str">'
              b'<f>HYPERLINK("http://127.0.0.1:9/","wells")</f><v>wells</v></c>'
              b'<c r="C3"><f>0.5+0.2</f><v>0.7</v></c>'
              b'<c r="D3" t="inlineStr"><is><t>circle</t></is></c></row>')
    p = with_objects(book, tmp_path, "cached.xlsx", sheet_xml(rows))
    r = cli("norms", "import", p, "--name", "cached")
    assert r.exit_code == 0, r.output
    text = (user_dir / "cached" / "objects.csv").read_text(encoding="utf-8")
    assert "5000,wells,,0.7,circle," in text and "HYPERLINK" not in text


# ---------------------------------------------------------------------------------------
# 5. Formula injection: text that Excel would run is refused, cell named
# ---------------------------------------------------------------------------------------

INJECTIONS = ['=HYPERLINK("http://127.0.0.1:9/","x")', "+cmd|' /C calc'!A0", "@SUM(1)",
              "-2+3", "\t=cmd|' /C calc'!A0", "\r=1+1"]


def _objects_csv(path: Path, rows: list[list[str]]) -> Path:
    with path.open("w", encoding="utf-8", newline="") as fh:
        csv.writer(fh).writerows([["map_scale", "object", "object_ru", "size_m", "shape",
                                   "source"], *rows])
    return path


def test_csv_formula_injection_refused_cell_by_cell(tmp_path, user_dir):
    rows = [[str(1000 * (i + 1)), text, "", "0.5", "circle", ""]
            for i, text in enumerate(INJECTIONS)]
    rows.append(["9000", "wells", "", "0.5", "circle", "@evil"])
    r = cli("norms", "import", _objects_csv(tmp_path / "objects.csv", rows), "--name", "x")
    err = refused(r, f"{len(INJECTIONS) + 1} problems", "it would run as a formula in Excel")
    for i in range(len(INJECTIONS)):
        assert f"'objects'!B{i + 2}: column \"object\"" in err, err
    assert "'objects'!F8: column \"source\"" in err
    for lead in "=+-@":
        assert f'may not start with "{lead}"' in err
    assert list(user_dir.iterdir()) == []


def test_xlsx_formula_injection_text_refused(book, tmp_path):
    """The same text in workbook cells (inline and shared strings)."""
    rows = OBJECTS_HEADER + objects_row(2, obj=b"=HYPERLINK(&quot;http://x&quot;)") + \
        objects_row(3, b"5000", obj=b"@SUM(1)")
    p = with_objects(book, tmp_path, "inject.xlsx", sheet_xml(rows))
    shared = to_shared_strings(p, tmp_path / "inject-shared.xlsx")
    for path in (p, shared):
        refused(cli("norms", "validate", path), "'objects'!B2", "'objects'!B3",
                'may not start with "="', 'may not start with "@"')


def test_safe_text_numbers_and_dashes_are_kept_and_stay_text(tmp_path, user_dir):
    """A lone "-" (a unit), "-5" as a name, "a=b", a negative number in a numeric column
    (refused only by its range): what is stored reads back the same, and the template
    written from the set keeps every text a text cell (data_type "s", never "f")."""
    rows = [["2000", "-5", "", "0.2", "circle", "-"], ["5000", "a=b @c", "", "0.5", "circle",
                                                        "+7"]]
    p = _objects_csv(tmp_path / "objects.csv", rows)
    r = cli("norms", "import", p, "--name", "safe")
    assert r.exit_code == 0, r.output
    with (user_dir / "safe" / "objects.csv").open(encoding="utf-8", newline="") as fh:
        back = list(csv.DictReader(fh))
    assert [(b["object"], b["source"]) for b in back] == [("-5", "-"), ("a=b @c", "+7")]
    t = tmp_path / "t.xlsx"
    assert cli("norms", "template", t, "--norms", "safe").exit_code == 0
    ws = openpyxl.load_workbook(t)["objects"]
    cells = {c.value: c for row in ws.iter_rows() for c in row if c.value is not None}
    for text in ("-5", "a=b @c", "+7"):
        assert cells[text].data_type == "s", text
    bad = _objects_csv(tmp_path / "neg.csv", [["2000", "poles", "", "-2", "circle", ""]])
    err = refused(cli("norms", "validate", bad, "--table", "objects"), "'neg'!D2")
    assert "must be a number > 0" in err and "formula" not in err


def test_template_from_a_hand_made_set_never_writes_a_formula(tmp_path, user_dir):
    """A norm-set folder written by hand (not imported) with ``=HYPERLINK(...)`` as an object
    name: the template stores it as a text cell, and importing that template back refuses
    it with the cell named."""
    folder = tmp_path / "hand-made"
    shutil.copytree(bundled_norms_dir() / DEFAULT_NORM_SET, folder)
    with (folder / "objects.csv").open(encoding="utf-8", newline="") as fh:
        rows = list(csv.reader(fh))
    rows[1][1] = '=HYPERLINK("http://x","y")'
    with (folder / "objects.csv").open("w", encoding="utf-8", newline="") as fh:
        csv.writer(fh).writerows(rows)
    t = tmp_path / "t.xlsx"
    r = cli("norms", "template", t, "--norms", folder)
    assert r.exit_code == 0, r.output
    ws = openpyxl.load_workbook(t)["objects"]
    cell = next(c for row in ws.iter_rows() for c in row if "HYPERLINK" in str(c.value))
    assert cell.data_type == "s" and cell.value == '=HYPERLINK("http://x","y")'
    refused(cli("norms", "import", t, "--name", "back"), f"'objects'!{cell.coordinate}",
            'may not start with "="')


# ---------------------------------------------------------------------------------------
# 6. Project text: HTML, file:// and http:// shown as text, nothing fetched; paths safe
# ---------------------------------------------------------------------------------------

HOSTILE_TEXT = {
    "name": "<script>alert(1)</script> & <b>bold</b>",
    "customer": '<img src="http://127.0.0.1:9/pixel.png"> file:///etc/passwd',
    "contractor": '<link rel="stylesheet" href="file:///etc/passwd">',
    "approver_position": "<style>@import url(http://127.0.0.1:9/x.css); * { display: none }"
                         "</style>",
    "approver_name": '=HYPERLINK("http://127.0.0.1:9/","x") http://127.0.0.1:9/',
}
HOSTILE_OBJECTS = {  # a hand-made norm set's object names (not imported: not checked)
    "2000": '<img src="http://127.0.0.1:9/obj.png"> ' + "pole " * 250,  # 1,250 characters
    "5000": '=HYPERLINK("http://127.0.0.1:9/","wells")',
}


def _hostile_set(folder: Path) -> Path:
    shutil.copytree(bundled_norms_dir() / DEFAULT_NORM_SET, folder)
    path = folder / "objects.csv"
    with path.open(encoding="utf-8", newline="") as fh:
        rows = list(csv.reader(fh))
    for row in rows[1:]:
        row[1] = HOSTILE_OBJECTS.get(row[0], row[1])
    with path.open("w", encoding="utf-8", newline="") as fh:
        csv.writer(fh).writerows(rows)
    return folder


def _squash(text: str) -> str:
    return re.sub(r"[\s\u200b]+", "", text)


def test_project_text_is_text_everywhere_and_nothing_is_fetched(tmp_path, monkeypatch):
    """``scanplan plan`` of a project whose every text key holds HTML, ``file://`` and
    ``http://`` URLs, with a hand-made norm set (a folder beside the project, named
    relative to it) whose object names do too, run from another folder with ``--out
    ../out``: the PDF shows every text literally, the URL fetcher is asked for bundled
    assets only and no socket is opened, the workbook stores them as text cells, and
    nothing is written but out/spec.xlsx and out/spec.pdf."""
    pypdf = pytest.importorskip("pypdf")
    from scanplan.reports import pdf as P

    proj = tmp_path / "contract"
    proj.mkdir()
    _hostile_set(proj / "hostile-set")
    keys = "\n".join(f"{k} = {json.dumps(v)}" for k, v in HOSTILE_TEXT.items())
    (proj / "p.toml").write_text(
        f"[project]\n{keys}\n[map]\nscale = 2000\nrelief_interval_m = 0.5\n"
        '[norms]\nset = "./hostile-set"\n'
        '[uav]\ncamera = "canon-eos-5d-mark-ii-50"\nf_number = 8\nheight_m = 300\n',
        encoding="utf-8")
    work = tmp_path / "work"
    work.mkdir()
    monkeypatch.chdir(work)
    fetchers: list = []

    class Spy(P.BundledAssetFetcher):
        def __init__(self, *a, **k):
            super().__init__(*a, **k)
            fetchers.append(self)

    connects: list = []

    def no_connect(self, address, *a, **k):
        connects.append(address)
        raise OSError("network access while writing a report")

    monkeypatch.setattr(P, "BundledAssetFetcher", Spy)
    monkeypatch.setattr(socket.socket, "connect", no_connect)
    monkeypatch.setenv("SCANPLAN_NO_FORK", "1")  # the spies see this process's render
    before = tree(tmp_path)
    with opened_files() as opened:
        r = cli("plan", proj / "p.toml", "--out", "../out")
    assert r.exit_code == 0, r.output
    assert {p for p in tree(tmp_path) - before if ".scanplan-sets" not in p} == {
        "out", "out/spec.xlsx", "out/spec.pdf"}  # (and the set they are links to)
    assert not any("passwd" in p for p in opened)
    # the PDF: literal text; the fetcher asked for bundled files and data: URLs only
    text = _squash(" ".join(p.extract_text() for p in pypdf.PdfReader("../out/spec.pdf").pages))
    for value in HOSTILE_TEXT.values():
        assert _squash(value) in text, value
    # the recognition table lists the objects of the map scale (1:2000) only (issue 13)
    assert _squash(HOSTILE_OBJECTS["2000"][:60]) in text
    assert _squash(HOSTILE_OBJECTS["5000"]) not in text
    root = P.templates_dir().resolve().as_uri() + "/"
    (fetcher,) = fetchers
    assert fetcher.requested and fetcher.refused == [] and connects == []
    assert all(u.startswith(("data:", root)) for u in fetcher.requested), fetcher.requested
    # the workbook: every such text is in string cells, never a formula
    wb = openpyxl.load_workbook("../out/spec.xlsx")
    cells = [c for ws in wb.worksheets for row in ws.iter_rows() for c in row
             if isinstance(c.value, str)]
    assert not [c for c in cells if c.data_type == "f"]
    for value in [*HOSTILE_TEXT.values(), *HOSTILE_OBJECTS.values()]:
        holding = [c for c in cells if value in c.value]
        assert holding and all(c.data_type == "s" for c in holding), value


def test_html_in_project_text_cannot_reach_markup_or_stylesheet(tmp_path):
    """The rendered HTML: the user's text only escaped, the one stylesheet the bundled
    report.css, the one <style> the footer; a long unbroken text gets break points (the
    table layout was quadratic in a cell's length: 3,000 characters took 52 s)."""
    from scanplan.project.file import load_project
    from scanplan.project.spec import plan_project
    from scanplan.reports import templates_dir
    from scanplan.reports.pdf import render_html

    p = tmp_path / "p.toml"
    keys = "\n".join(f"{k} = {json.dumps(v)}" for k, v in HOSTILE_TEXT.items())
    p.write_text(f"[project]\n{keys}\n[map]\nscale = 2000\nrelief_interval_m = 0.5\n"
                 '[uav]\ncamera = "canon-eos-5d-mark-ii-50"\nf_number = 8\nheight_m = 300\n',
                 encoding="utf-8")
    res = plan_project(load_project(p))
    html = render_html(uav=res.uav.job, meta=res.meta, spec=res)
    for tag in ("<script", '<img src="http', "<b>", '<link rel="stylesheet" href="file',
                "display: none }</style>"):
        assert tag not in html, tag
    assert all(src.startswith("data:") for src in re.findall(r'<img src="([^"]*)"', html))
    assert html.count("<link ") == 1 and 'href="report.css"' in html
    (style,) = re.findall(r"<style>(.*?)</style>", html, re.S)
    assert "@page" in style and "passwd" not in style and "import" not in style
    assert "&lt;style&gt;@import url(http://127.0.0.1:9/x.css)" in html
    rules = (templates_dir() / "report.css").read_text(encoding="utf-8")
    assert not re.search(r"^td\s*{[^}]*anywhere", rules, re.M)
    assert re.search(r"\.titleblock {[^}]*table-layout: fixed", rules)
    long = render_html(uav=res.uav.job, meta=type(res.meta)(customer="x" * 2000))
    assert "x" * 31 not in long and "\u200b" in long


@pytest.mark.parametrize(("key", "value", "says"), [
    ("name", '"\\u001b]0;owned\\u0007 title"', "control character U+001B"),
    ("customer", json.dumps("y" * 1001), "1,001 characters long; at most 1,000"),
])
def test_project_text_controls_and_length(key, value, says, tmp_path):
    p = tmp_path / "p.toml"
    p.write_text(f"[project]\n{key} = {value}\n[map]\nscale = 2000\nrelief_interval_m = 0.5\n"
                 '[uav]\ncamera = "canon-eos-5d-mark-ii-50"\nheight_m = 300\n', encoding="utf-8")
    err = refused(cli("plan", p), f"project.{key} (line 2)", says)
    assert "\x1b" not in err and len(err) < 2000


# ---------------------------------------------------------------------------------------
# 7. Names with "..": never a path outside what the user named
# ---------------------------------------------------------------------------------------


def test_set_name_with_dotdot_writes_nothing_anywhere(book, tmp_path, user_dir):
    path, _, _ = book
    before = tree(tmp_path)
    for name in ("../../x", "..", "../x", "x/../../y", "./x"):
        refused(cli("norms", "import", path, "--name", name), "--name", "not a safe set name")
    assert tree(tmp_path) == before


def test_norms_dotdot_never_looks_above_the_norm_folders(tmp_path, user_dir, monkeypatch):
    """``--norms ..`` was looked up as a *name* — ``<norm dir>/../set.toml`` and
    ``<bundled>/../set.toml`` — so a norm set one level above the user norm directory was
    used. Now a name never contains a path step: ``..`` is the folder ``..`` (of the
    current folder), and a missing folder gets its own message."""
    shutil.copytree(bundled_norms_dir() / DEFAULT_NORM_SET, user_dir.parent, dirs_exist_ok=True)
    (tmp_path / "a" / "b").mkdir(parents=True)
    monkeypatch.chdir(tmp_path / "a" / "b")  # ".." is tmp/a: no set.toml there
    args = ["scan", "--map-scale", "2000", "--relief", "0.5", "--photo-scale", "10000",
            "--camera", "rc30-153"]
    err = refused(cli(*args, "--norms", ".."), "no norm set folder '..'", "has no set.toml")
    assert str(tmp_path / "a") in err
    refused(cli(*args, "--norms", "../x"), "no norm set folder '../x'")
    refused(cli("norms", "show", "../../x"), "no norm set folder '../../x'")
    # a folder that is a norm set is a legitimate --norms (the documented NAME|PATH)
    assert cli(*args, "--norms", user_dir.parent).exit_code == 0


@pytest.mark.parametrize("camera", ["../../etc/passwd", "/etc/passwd", "..", "rc30-153/../x"])
def test_camera_ids_are_never_paths(camera, tmp_path):
    with opened_files() as opened:
        r = cli("scan", "--map-scale", "2000", "--relief", "0.5", "--photo-scale", "10000",
                "--camera", camera)
    refused(r, "--camera", f"unknown camera {camera!r}")
    assert not any("passwd" in p for p in opened)


def test_project_names_with_dotdot(tmp_path, monkeypatch):
    """``[uav] camera = "../x"`` is an unknown id; ``[norms] set = "../../etc"`` a folder
    that has no set.toml — both named with their line. A relative ``set`` is taken from
    the project file's folder, wherever scanplan runs."""
    base = "[map]\nscale = 2000\nrelief_interval_m = 0.5\n"
    uav = '[uav]\ncamera = "canon-eos-5d-mark-ii-50"\nheight_m = 300\n'
    proj = tmp_path / "p"
    proj.mkdir()
    (tmp_path / "elsewhere").mkdir()
    monkeypatch.chdir(tmp_path / "elsewhere")
    p = proj / "cam.toml"
    p.write_text(base + '[uav]\ncamera = "../x"\nheight_m = 300\n', encoding="utf-8")
    refused(cli("plan", p), "uav.camera (line 5)", "unknown camera '../x'")
    p = proj / "set.toml"
    p.write_text(base + '[norms]\nset = "../../etc"\n' + uav, encoding="utf-8")
    err = refused(cli("plan", p), "norms.set (line 5)", "no norm set folder")
    assert str(proj / "../../etc") in err
    shutil.copytree(bundled_norms_dir() / DEFAULT_NORM_SET, proj / "sets" / "mine")
    p.write_text(base + '[norms]\nset = "sets/mine"\n' + uav, encoding="utf-8")
    assert cli("plan", p).exit_code == 0  # found beside the project, not in ./elsewhere


def test_workbook_part_names_are_never_file_paths(book, tmp_path):
    """A workbook whose relationships point the objects sheet at ``../../../etc/passwd``:
    part names are looked up in the zip, never on disk."""
    _, parts, member = book
    rels = parts["xl/_rels/workbook.xml.rels"]
    target = member.removeprefix("xl/").encode()
    bad = rels.replace(target, b"../../../../../../etc/passwd")
    assert bad != rels
    p = write_xlsx(tmp_path / "rels.xlsx", {**parts, "xl/_rels/workbook.xml.rels": bad})
    with opened_files() as opened:
        r = cli("norms", "validate", p)
    refused(r, "rels.xlsx")
    assert not any("passwd" in o for o in opened), opened


# ---------------------------------------------------------------------------------------
# 8. Not files, not zips, not text: FIFOs, /dev/zero, damaged zips, bad encodings
# ---------------------------------------------------------------------------------------


@pytest.mark.parametrize("suffix", [".csv", ".xlsx", ".toml"])
@pytest.mark.parametrize("kind", ["fifo", "dev-zero"])
def test_fifo_and_dev_zero_are_refused_not_read(kind, suffix, tmp_path):
    """Reading /dev/zero never ends and opening a FIFO waits for a writer for ever: both
    are refused as "not a regular file" before they are opened."""
    path = tmp_path / f"objects{suffix}"
    if kind == "fifo":
        os.mkfifo(path)
    else:
        path.symlink_to("/dev/zero")
    args = ("plan", path) if suffix == ".toml" else ("norms", "validate", path)
    with hang_guard(), opened_files() as opened:
        r = cli(*args)
    what = "a FIFO (named pipe)" if kind == "fifo" else "a device"
    refused(r, f"is {what}, not a regular file")
    assert str(path) not in opened and "/dev/zero" not in opened


def test_norm_set_folder_with_a_dev_zero_file(tmp_path):
    folder = tmp_path / "set"
    shutil.copytree(bundled_norms_dir() / DEFAULT_NORM_SET, folder)
    (folder / "objects.csv").unlink()
    (folder / "objects.csv").symlink_to("/dev/zero")
    with hang_guard():
        r = cli("norms", "show", folder)
    refused(r, "objects.csv", "is a device, not a regular file")


def test_not_a_zip_and_damaged_zips(book, tmp_path):
    """A text file named .xlsx; a deflate stream with garbage in it (zlib.error escaped as a
    crash, exit 1); a truncated zip."""
    p = tmp_path / "text.xlsx"
    p.write_bytes(b"map_scale,object\n2000,poles\n")
    refused(cli("norms", "validate", p), "text.xlsx", "not a zip file")
    path, _, member = book
    data = bytearray(path.read_bytes())
    with zipfile.ZipFile(path) as zf:
        info = zf.getinfo(member)
    start = info.header_offset + 30 + len(info.filename.encode()) + len(info.extra)
    data[start + 5: start + 45] = b"\xff" * 40  # the sheet's compressed data, damaged
    p = tmp_path / "garbled.xlsx"
    p.write_bytes(bytes(data))
    refused(cli("norms", "validate", p), "garbled.xlsx", "damaged")
    p = tmp_path / "cut.xlsx"
    p.write_bytes(path.read_bytes()[: path.stat().st_size // 2])
    refused(cli("norms", "validate", p), "cut.xlsx")


CSV_HEAD = b"map_scale,object,size_m,shape\n"


@pytest.mark.parametrize(("name", "data", "says"), [
    ("nul.csv", CSV_HEAD + b"2000,po\x00les,0.2,circle\n", "contains NUL characters"),
    ("cp1251-undefined.csv", CSV_HEAD + b"2000,\x98\x98,0.2,circle\n",
     "neither UTF-8 nor Windows-1251 text (byte 0x98"),
    ("utf16-cut.csv", b"\xff\xfe" + (CSV_HEAD + b"2000,a,0.2,circle\n").decode().encode(
        "utf-16-le") + b"x", "is not valid UTF-16 text"),
    ("utf16-no-bom.csv", (CSV_HEAD + b"2000,a,0.2,circle\n").decode().encode("utf-16-le"),
     "contains NUL characters"),
    ("escape.csv", CSV_HEAD + b"2000,\x1b]0;owned\x07,0.2,circle\n",
     "control character U+001B"),
    ("long-cell.csv", CSV_HEAD + b"2000," + b"a" * 40_000 + b",0.2,circle\n",
     "40,000 characters long; the limit is 32,767"),
    ("huge-field.csv", CSV_HEAD + b'2000,"' + b"a" * 200_000 + b'",0.2,circle\n',
     "field larger than field limit"),
    ("endless-line.csv", CSV_HEAD + b"ab," * 3_000_000 + b"\n",
     "row 2 is longer than 1,000,000 characters"),
    ("runaway-quote.csv", CSV_HEAD + b'2000,"poles,0.2,circle\n'
     + b"5000,wells,0.5,circle\n" * 100_000, "check the quotes"),
    ("wide.csv", CSV_HEAD + b"2000,a,0.2,circle" + b",x" * 300 + b"\n",
     "row 2 has 304 columns; the limit is 256"),
], ids=lambda v: v if isinstance(v, str) and v.endswith(".csv") else "")
def test_bad_csv_bytes(name, data, says, tmp_path, user_dir):
    """Each: exit 2 with the file (or cell) named, no traceback, nothing written; what is
    shown of the value is printable and short (no terminal escapes, no megabytes)."""
    p = tmp_path / name
    p.write_bytes(data)
    err = refused(cli("norms", "import", p, "--name", "x", "--table", "objects"), says)
    assert "\x1b" not in err and len(err) < 3000, err[:3000]
    assert list(user_dir.iterdir()) == []


def test_utf16_and_bom_csv_still_work(tmp_path, user_dir):
    rows = "map_scale;object;size_m;shape\n2000;столбы;0,2;circle\n5000;колодцы;0,5;circle\n"
    for enc, name in (("utf-16", "a.csv"), ("utf-8-sig", "b.csv")):
        p = tmp_path / name
        p.write_bytes(rows.encode(enc))
        r = cli("norms", "validate", p, "--table", "objects")
        assert r.exit_code == 0, r.output


def test_huge_cell_in_a_workbook(book, tmp_path):
    """A 10 MB (incompressible) text in one cell (openpyxl cannot even write one: it cuts
    at 32,767): refused at its cell, the value cut short in the message."""
    import base64

    huge = base64.b64encode(os.urandom(7_500_000))
    rows = OBJECTS_HEADER + objects_row(2) + objects_row(3, b"5000", obj=huge)
    p = with_objects(book, tmp_path, "huge.xlsx", sheet_xml(rows))
    assert p.stat().st_size < norms_limits.MAX_FILE_BYTES
    err = refused(cli("norms", "validate", p), "'objects'!B3", "10,000,000 characters long",
                  "the limit is 32,767")
    assert len(err) < 3000


@pytest.mark.parametrize(("data", "ok", "says"), [
    (b"\xef\xbb\xbf", True, ""),  # Notepad's UTF-8 with a byte-order mark
    (b"", False, "is UTF-16 text; save it as UTF-8"),
    (b"\xff", False, "is not UTF-8 text"),
])
def test_project_encodings(data, ok, says, tmp_path):
    text = ('[map]\nscale = 2000\nrelief_interval_m = 0.5\n'
            '[uav]\ncamera = "canon-eos-5d-mark-ii-50"\nheight_m = 300\n')
    p = tmp_path / "p.toml"
    p.write_bytes(text.encode("utf-16") if not data else data + text.encode())
    r = cli("plan", p, "--json")
    if ok:
        assert r.exit_code == 0, r.output
    else:
        refused(r, "p.toml", says)


def test_big_project_file_is_refused_unread(tmp_path):
    p = tmp_path / "big.toml"
    with p.open("wb") as fh:
        fh.truncate(50 * MB)  # sparse: costs no disk
    refused(cli("plan", p), "big.toml", "the limit is")


@pytest.mark.parametrize("option", ["--project-name", "--customer", "--contractor",
                                    "--approver-position", "--approver-name"])
@pytest.mark.parametrize("value", ["x" * 1001, "red \x1b[31malert", "a\x00b"])
def test_report_text_options_follow_the_project_file_rule(option, value):
    """The title-block options are bounded and free of control characters, like the project
    file's [project] text (a terminal escape would reach the terminal and the reports)."""
    r = CliRunner().invoke(main, ["scan", "--map-scale", "2000", "--relief", "1",
                                  "--photo-scale", "10000", "--camera", "afa-te-100",
                                  option, value])
    assert r.exit_code == 2, r.output
    assert option in r.output and "Traceback" not in r.output

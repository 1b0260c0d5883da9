"""A corpus of norm workbooks built in code (no binary fixtures).

Every case is a function ``build(folder) -> Path`` plus what importing it must give:
``ok`` (it imports) or the cell addresses that must appear in the error message. The
workbooks start from the bundled set's CSV files and change one thing each.
"""

from __future__ import annotations

import csv
import datetime as dt
import html
import re
import shutil
import zipfile
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any
from xml.sax.saxutils import escape

import openpyxl

from scanplan.norms import DEFAULT_NORM_SET, bundled_norms_dir

NBSP, NNBSP, MINUS = "\u00a0", "\u202f", "\u2212"


def bundled_rows(table: str) -> list[list[str]]:
    """Header + rows of a bundled CSV (``parameters``, ``shapes``, ``objects``)."""
    path = bundled_norms_dir() / DEFAULT_NORM_SET / f"{table}.csv"
    with path.open(encoding="utf-8", newline="") as fh:
        return [list(r) for r in csv.reader(fh)]


def save(wb: openpyxl.Workbook, folder: Path, name: str) -> Path:
    path = folder / name
    wb.save(path)
    return path


def english_workbook(
    edit: Callable[[dict[str, list[list[Any]]]], None] | None = None,
) -> openpyxl.Workbook:
    """The bundled set as a plain English workbook; ``edit`` changes the rows first."""
    tables = {t: bundled_rows(t) for t in ("parameters", "shapes", "objects")}
    if edit:
        edit(tables)
    wb = openpyxl.Workbook()
    wb.remove(wb.active)
    for name, rows in tables.items():
        ws = wb.create_sheet(name)
        for row in rows:
            ws.append(row)
    return wb


def set_cell(rows: list[list[Any]], key: str, column: str, value: Any) -> None:
    """Set ``column`` of the row whose first cell is ``key``."""
    col = rows[0].index(column)
    for row in rows[1:]:
        if str(row[0]) == key:
            row[col] = value
            return
    raise KeyError(key)


# --- the Russian-locale workbook ---------------------------------------------------------

RU_PLANIMETRIC = "0,4"  # V_s doubled → P_S doubles
RU_SIZE_2000 = "0,40"  # L at 1:2000 doubled → P_D doubles


def russian_workbook(
    *,
    objects_extra: list[list[Any]] | None = None,
    size_2000: Any = RU_SIZE_2000,
    scale_2000: Any = f"1:2{NBSP}000",
) -> openpyxl.Workbook:
    """A Russian-locale workbook: Russian sheet names and headers, decimal commas,
    ``1:2 000`` scales with NBSP, a title row and a merged two-row header, Russian
    parameter and shape names, trailing empty rows."""
    wb = openpyxl.Workbook()
    wb.remove(wb.active)

    ws = wb.create_sheet("Параметры")
    ws.append(["Коэффициенты технической инструкции предприятия"])
    ws.merge_cells("A1:E1")
    ws.append([])
    ws.append(["Параметр", "Значение", "Ед. изм.", "Источник", "Примечание"])
    names_ru = {
        "planimetric_accuracy_mm": "Точность в плане",
        "height_accuracy_fraction": "Точность по высоте",
        "processing_loss_k": "Коэффициент потери точности",
        "photoplan_resolution_mm": "Разрешение фотоплана",
        "pr_coefficient": "Коэффициент PR",
        "probability": "Вероятность",
        "shape": "Форма",
        "height_formula": "Формула высот",
        "constraints": "Ограничения",
        "standard_forward_overlap_pct": "Стандартное перекрытие",
        "recognition_rounding": "Округление",
    }
    values = {r[0]: r[1] for r in bundled_rows("parameters")[1:]}
    values.update(
        {
            "planimetric_accuracy_mm": RU_PLANIMETRIC,
            "photoplan_resolution_mm": "0,070",
            "shape": "круг",
            "standard_forward_overlap_pct": "60",
        }
    )
    for name, value in values.items():
        ws.append([names_ru.get(name, name), value, "", "СТП предприятия", ""])
    ws.append([None, None])
    ws.append(["", "  "])  # trailing empty rows

    ws = wb.create_sheet("Коэффициенты формы")
    ws.append(["Форма", "Коэффициент распознавания формы B", "Название"])
    for shape, coef, name_ru, _src in bundled_rows("shapes")[1:]:
        ws.append([shape, coef.replace(".", ","), name_ru])

    ws = wb.create_sheet("Минимальные объекты")
    ws.append(["Минимальные размеры объектов, изображаемых на карте"])
    ws.merge_cells("A1:F1")
    ws.append([])
    # a two-row header: vertical merges and a group title over two sub-columns
    ws["A3"] = "Масштаб карты (плана)"
    ws.merge_cells("A3:A4")
    ws["B3"] = "Объект"
    ws.merge_cells("B3:C3")
    ws["B4"] = "Наименование объекта"
    ws["C4"] = "Объект (рус.)"
    ws["D3"] = "Размер объекта L, м"
    ws.merge_cells("D3:D4")
    ws["E3"] = "Форма"
    ws.merge_cells("E3:E4")
    ws["F3"] = "Источник"
    ws.merge_cells("F3:F4")
    ws.append([scale_2000, "столбы", "столбы, гидранты", size_2000, "круг", "СТП"])
    ws.append([f"5{NNBSP}000", "колодцы", "колодцы", "1,50", "круг", "СТП"])
    ws.append(["10 000", "скважины", "буровые скважины", "2,2", "circle", "СТП"])
    ws.append([25000, "скважины", "буровые скважины", 2.2, "круг", "СТП"])
    for _ in range(5):
        ws.append([None, "", None])
    if objects_extra:
        for row in objects_extra:
            ws.append(row)
    return wb


# --- zip surgery (for what openpyxl cannot write) ----------------------------------------


def rewrite_member(
    src: Path, dst: Path, member_pattern: str, edit: Callable[[bytes], bytes]
) -> Path:
    """Copy an .xlsx, passing members whose name matches through ``edit``."""
    with zipfile.ZipFile(src) as zin, zipfile.ZipFile(dst, "w", zipfile.ZIP_DEFLATED) as zout:
        for info in zin.infolist():
            data = zin.read(info)
            if re.fullmatch(member_pattern, info.filename):
                data = edit(data)
            zout.writestr(info.filename, data)
    return dst


def to_shared_strings(src: Path, dst: Path) -> Path:
    """Rewrite an openpyxl workbook the way Excel stores text: a shared-string table
    (``t="s"``, some entries as rich text runs) instead of inline strings."""
    strings: list[str] = []
    index: dict[str, int] = {}

    def share(m: re.Match[bytes]) -> bytes:
        # the cell's text, its XML escapes resolved (openpyxl writes non-ASCII as "&#1050;"
        # when lxml is installed): split into runs and escaped again below
        text = html.unescape(m.group(2).decode())
        if text not in index:
            index[text] = len(strings)
            strings.append(text)
        return m.group(1) + b' t="s"><v>' + str(index[text]).encode() + b"</v></c>"

    cell = re.compile(
        rb'(<c r="[A-Z]+\d+"(?: s="\d+")?) t="inlineStr"><is><t[^>]*>(.*?)</t></is></c>'
    )
    with zipfile.ZipFile(src) as zin:
        parts = {i.filename: zin.read(i) for i in zin.infolist()}
    for name in parts:
        if name.startswith("xl/worksheets/"):
            parts[name] = cell.sub(share, parts[name])

    def si(text: str) -> str:
        if len(text) > 3:  # rich text: two runs, as Excel writes a partly bold cell
            a, b = text[:2], text[2:]
            return (
                f"<si><r><rPr><b/></rPr><t>{escape(a)}</t></r>"
                f'<r><t xml:space="preserve">{escape(b)}</t></r></si>'
            )
        return f"<si><t>{escape(text)}</t></si>"

    ns = "http://schemas.openxmlformats.org/spreadsheetml/2006/main"
    parts["xl/sharedStrings.xml"] = (
        f'<?xml version="1.0" encoding="UTF-8" standalone="yes"?>\n<sst xmlns="{ns}" '
        f'count="{len(strings)}" uniqueCount="{len(strings)}">'
        + "".join(si(t) for t in strings)
        + "</sst>"
    ).encode()
    ct = "application/vnd.openxmlformats-officedocument.spreadsheetml.sharedStrings+xml"
    parts["[Content_Types].xml"] = parts["[Content_Types].xml"].replace(
        b"</Types>",
        f'<Override PartName="/xl/sharedStrings.xml" ContentType="{ct}"/></Types>'.encode(),
    )
    with zipfile.ZipFile(dst, "w", zipfile.ZIP_DEFLATED) as zout:
        for name, data in parts.items():
            zout.writestr(name, data)
    return dst


def sheet_member(path: Path, title: str) -> str:
    wb = openpyxl.load_workbook(path, read_only=True)
    try:
        return str(wb[title]._worksheet_path).lstrip("/")
    finally:
        wb.close()


BILLION_LAUGHS = (
    b'<?xml version="1.0" encoding="UTF-8" standalone="yes"?>\n'
    b'<!DOCTYPE lolz [<!ENTITY lol "lol">'
    b'<!ENTITY lol2 "&lol;&lol;&lol;&lol;&lol;&lol;&lol;&lol;&lol;&lol;">'
    b'<!ENTITY lol3 "&lol2;&lol2;&lol2;&lol2;&lol2;&lol2;&lol2;&lol2;&lol2;&lol2;">'
    b'<!ENTITY lol4 "&lol3;&lol3;&lol3;&lol3;&lol3;&lol3;&lol3;&lol3;&lol3;&lol3;">'
    b'<!ENTITY lol5 "&lol4;&lol4;&lol4;&lol4;&lol4;&lol4;&lol4;&lol4;&lol4;&lol4;">'
    b'<!ENTITY lol6 "&lol5;&lol5;&lol5;&lol5;&lol5;&lol5;&lol5;&lol5;&lol5;&lol5;">'
    b'<!ENTITY lol7 "&lol6;&lol6;&lol6;&lol6;&lol6;&lol6;&lol6;&lol6;&lol6;&lol6;">'
    b'<!ENTITY lol8 "&lol7;&lol7;&lol7;&lol7;&lol7;&lol7;&lol7;&lol7;&lol7;&lol7;">'
    b'<!ENTITY lol9 "&lol8;&lol8;&lol8;&lol8;&lol8;&lol8;&lol8;&lol8;&lol8;&lol8;">]>\n'
)


def with_entities(data: bytes) -> bytes:
    """Put a 'billion laughs' DTD in front of an XML part and use the entity in it."""
    body = re.sub(rb"^<\?xml[^>]*\?>\s*", b"", data)
    body = body.replace(
        b"</sheetData>",
        b'<row r="99"><c r="A99" t="inlineStr"><is><t>&lol9;</t></is></c></row></sheetData>',
        1,
    )
    return BILLION_LAUGHS + body


# --- the corpus -------------------------------------------------------------------------


@dataclass(frozen=True)
class Case:
    """One workbook and what importing it must give."""

    name: str
    build: Callable[[Path], Path]
    ok: bool
    addresses: tuple[str, ...] = ()
    contains: tuple[str, ...] = ()
    limits: dict[str, int] = field(default_factory=dict)


def _english(
    name: str, edit: Callable[[dict[str, list[list[Any]]]], None]
) -> Callable[[Path], Path]:
    return lambda folder: save(english_workbook(edit), folder, f"{name}.xlsx")


def _objects_size(row_scale: str, value: Any) -> Callable[[dict[str, list[list[Any]]]], None]:
    return lambda t: set_cell(t["objects"], row_scale, "size_m", value)


def _param(name: str, value: Any) -> Callable[[dict[str, list[list[Any]]]], None]:
    return lambda t: set_cell(t["parameters"], name, "value", value)


def _formula(folder: Path) -> Path:
    wb = english_workbook()
    wb["objects"]["D3"] = "=1/0"  # openpyxl writes no cached value
    return save(wb, folder, "formula.xlsx")


def _formula_cached(folder: Path) -> Path:
    """A formula with a cached value (as Excel saves it): accepted."""
    wb = english_workbook()
    wb["objects"]["D3"] = "=1.5*1"
    src = save(wb, folder, "formula-src.xlsx")
    member = sheet_member(src, "objects")
    return rewrite_member(
        src,
        folder / "formula-cached.xlsx",
        re.escape(member),
        lambda d: re.sub(
            rb"(<f>1\.5\*1</f>)<v\s*/>|(<f>1\.5\*1</f>)<v></v>"
            rb"|(<f>1\.5\*1</f>)",
            b"<f>1.5*1</f><v>1.5</v>",
            d,
            count=1,
        ),
    )


def _error_cell(folder: Path) -> Path:
    wb = english_workbook()
    wb["objects"]["D4"] = "#DIV/0!"
    return save(wb, folder, "error-cell.xlsx")


def _date_cell(folder: Path) -> Path:
    wb = english_workbook()
    wb["objects"]["D2"] = dt.datetime(2024, 2, 20)  # Excel's reading of "20.02"
    return save(wb, folder, "date-cell.xlsx")


def _bool_cell(folder: Path) -> Path:
    wb = english_workbook()
    wb["shapes"]["B3"] = True
    return save(wb, folder, "bool-cell.xlsx")


def _missing_column(folder: Path) -> Path:
    def edit(t: dict[str, list[list[Any]]]) -> None:
        for row in t["objects"]:
            del row[3]  # size_m

    return save(english_workbook(edit), folder, "missing-column.xlsx")


def _missing_sheet(folder: Path) -> Path:
    wb = english_workbook()
    wb.remove(wb["shapes"])
    return save(wb, folder, "missing-sheet.xlsx")


def _no_header(folder: Path) -> Path:
    wb = english_workbook()
    wb.remove(wb["objects"])
    ws = wb.create_sheet("objects")
    for i in range(5):
        ws.append([f"text {i}", i])
    return save(wb, folder, "no-header.xlsx")


def _duplicate_sheet(folder: Path) -> Path:
    wb = english_workbook()
    ws = wb.create_sheet("Минимальные объекты")
    for row in bundled_rows("objects"):
        ws.append(row)
    return save(wb, folder, "duplicate-sheet.xlsx")


def _missing_parameter(folder: Path) -> Path:
    def edit(t: dict[str, list[list[Any]]]) -> None:
        t["parameters"] = [r for r in t["parameters"] if r[0] != "probability"]

    return save(english_workbook(edit), folder, "missing-parameter.xlsx")


def _unknown_parameter(folder: Path) -> Path:
    return save(
        english_workbook(
            lambda t: t["parameters"].append(["flux_capacitance", "1.21", "GW", "", ""])
        ),
        folder,
        "unknown-parameter.xlsx",
    )


def _duplicate_key(folder: Path) -> Path:
    return save(
        english_workbook(
            lambda t: t["objects"].append(["2 000", "again", "", "0.3", "circle", ""])
        ),
        folder,
        "duplicate-key.xlsx",
    )


def _many_errors(folder: Path) -> Path:
    def edit(t: dict[str, list[list[Any]]]) -> None:
        for i in range(30):
            t["objects"].append([str(50000 + i), f"o{i}", "", "abc", "circle", ""])

    return save(english_workbook(edit), folder, "many-errors.xlsx")


def _percent(folder: Path) -> Path:
    """Overlap typed as 60 % in a percent-formatted cell (Excel stores 0.6)."""
    wb = english_workbook()
    ws = wb["parameters"]
    for row in ws.iter_rows(min_row=2):
        if row[0].value == "standard_forward_overlap_pct":
            row[1].value = 0.6
            row[1].number_format = "0%"
    return save(wb, folder, "percent.xlsx")


def _extra_columns(folder: Path) -> Path:
    """Unknown columns and sheets are ignored (with a note); numbers stored as numbers."""

    def edit(t: dict[str, list[list[Any]]]) -> None:
        for i, row in enumerate(t["objects"]):
            row.insert(0, "№" if i == 0 else i)
            if i:
                row[1] = int(row[1])
                row[4] = float(row[4])

    wb = english_workbook(edit)
    wb.create_sheet("Notes").append(["anything goes here"])
    return save(wb, folder, "extra-columns.xlsx")


def _entities(folder: Path) -> Path:
    src = save(english_workbook(), folder, "entities-src.xlsx")
    member = sheet_member(src, "objects")
    return rewrite_member(src, folder / "entities.xlsx", re.escape(member), with_entities)


def _zip_bomb(folder: Path) -> Path:
    src = save(english_workbook(), folder, "bomb-src.xlsx")
    member = sheet_member(src, "objects")
    pad = b" " * 4_000_000  # whitespace compresses ~1000:1
    return rewrite_member(
        src,
        folder / "bomb.xlsx",
        re.escape(member),
        lambda d: d.replace(b"</worksheet>", pad + b"</worksheet>"),
    )


def _not_zip(folder: Path) -> Path:
    path = folder / "not-a-workbook.xlsx"
    path.write_bytes(b"name,value\nthis is text, not a zip\n")
    return path


def _too_big(folder: Path) -> Path:
    return save(english_workbook(), folder, "too-big.xlsx")


def _too_many_rows(folder: Path) -> Path:
    def edit(t: dict[str, list[list[Any]]]) -> None:
        for i in range(120):
            t["objects"].append([str(60000 + i), f"o{i}", "", "0.5", "circle", ""])

    return save(english_workbook(edit), folder, "too-many-rows.xlsx")


CORPUS: tuple[Case, ...] = (
    # --- good ones
    Case("english", lambda f: save(english_workbook(), f, "english.xlsx"), True),
    Case("russian-locale", lambda f: save(russian_workbook(), f, "russian.xlsx"), True),
    Case(
        "russian-shared-strings",
        lambda f: to_shared_strings(
            save(russian_workbook(), f, "ru-inline.xlsx"), f / "russian-shared.xlsx"
        ),
        True,
    ),
    Case("formula-cached", _formula_cached, True),
    Case("percent-format", _percent, True),
    Case("extra-columns", _extra_columns, True),
    # --- bad values
    Case(
        "text-not-number",
        _english("abc", _objects_size("5000", "abc")),
        False,
        ("'objects'!D3",),
        ('column "size_m"', 'value "abc"', "must be a number > 0", "hint: type a decimal number"),
    ),
    Case(
        "zero-size",
        _english("zero", _objects_size("10000", "0,0")),
        False,
        ("'objects'!D4",),
        ("must be a number > 0 and ≤ 1000 [m]",),
    ),
    Case(
        "minus-sign",
        _english("minus", _objects_size("2000", f"{MINUS}0,5")),
        False,
        ("'objects'!D2",),
        ("must be a number > 0",),
    ),
    Case(
        "bad-scale",
        _english("scale", lambda t: set_cell(t["objects"], "25000", "map_scale", "1:25 000,5")),
        False,
        ("'objects'!A5",),
        ("must be an integer",),
    ),
    Case(
        "empty-required",
        _english("empty", _objects_size("2000", "")),
        False,
        ("'objects'!D2",),
        ("is empty", "fill in the cell"),
    ),
    Case(
        "bad-choice",
        _english("choice", _param("height_formula", "sideways")),
        False,
        ("'parameters'!B9",),
        ("must be one of instruction, parallax",),
    ),
    Case(
        "param-range",
        _english("prange", _param("probability", "1,5")),
        False,
        ("'parameters'!B7",),
        ("< 1",),
    ),
    Case(
        "formula-no-cache",
        _formula,
        False,
        ("'objects'!D3",),
        ("formula without a cached value", "open and save the file in Excel"),
    ),
    Case("excel-error", _error_cell, False, ("'objects'!D4",), ("Excel error",)),
    Case("date-cell", _date_cell, False, ("'objects'!D2",), ("date",)),
    Case("bool-cell", _bool_cell, False, ("'shapes'!B3",), ("TRUE/FALSE",)),
    # --- bad structure
    Case("missing-column", _missing_column, False, ("'objects'!G1",), ("missing column 'size_m'",)),
    Case(
        "missing-sheet",
        _missing_sheet,
        False,
        ("missing-sheet.xlsx",),
        ("no sheet for table 'shapes'",),
    ),
    Case("no-header", _no_header, False, ("'objects'!A1",), ("no header row",)),
    Case(
        "duplicate-sheet",
        _duplicate_sheet,
        False,
        ("'Минимальные объекты'!A1",),
        ("a second sheet for table 'objects'",),
    ),
    Case(
        "missing-parameter",
        _missing_parameter,
        False,
        ("'parameters'!A23",),
        ("missing parameter 'probability'",),
    ),
    Case(
        "unknown-parameter",
        _unknown_parameter,
        False,
        ("'parameters'!A24",),
        ("unknown parameter",),
    ),
    Case(
        "duplicate-key",
        _duplicate_key,
        False,
        ("'objects'!A8",),  # after the 6 bundled rows (1:500 and 1:1000 added, issue 13)
        ("duplicate map_scale", "'objects'!A2"),
    ),
    Case(
        "unknown-shape",
        _english("shape", lambda t: set_cell(t["objects"], "5000", "shape", "oval")),
        False,
        ("'objects'!E3",),
        ("must be a shape of the shapes table",),
    ),
    Case(
        "default-shape",
        _english("dshape", _param("shape", "hexagon")),
        False,
        ("'parameters'!B8",),
        ("the default shape",),
    ),
    Case(
        "many-errors",
        _many_errors,
        False,
        ("'objects'!D8", "'objects'!D27"),
        ("30 problems", "+10 more"),
    ),
    # --- hostile or oversized files
    Case("entity-expansion", _entities, False, ("entities.xlsx",), ("DTD or XML entities",)),
    Case("zip-bomb", _zip_bomb, False, ("bomb.xlsx",), ("compressed",)),
    Case("not-a-zip", _not_zip, False, ("not-a-workbook.xlsx",), ("not a zip file",)),
    Case(
        "file-too-big",
        _too_big,
        False,
        ("too-big.xlsx",),
        ("the limit is",),
        {"MAX_FILE_BYTES": 2000},
    ),
    Case(
        "too-many-rows",
        _too_many_rows,
        False,
        ("'objects'!A",),
        ("more than 100 rows",),
        {"MAX_ROWS": 100},
    ),
)


def build_all(folder: Path) -> dict[str, Path]:
    """Build every workbook of the corpus into ``folder`` (for manual inspection)."""
    folder.mkdir(parents=True, exist_ok=True)
    return {c.name: c.build(folder) for c in CORPUS}


if __name__ == "__main__":  # python tests/norm_corpus.py OUT_DIR
    import sys

    out = Path(sys.argv[1] if len(sys.argv) > 1 else "norm-corpus")
    shutil.rmtree(out, ignore_errors=True)
    for name, path in build_all(out).items():
        print(f"{name:20s} {path}")

"""The closing sheets: the norm set and its rows used, the warnings, the references."""

from __future__ import annotations

import re
from typing import TYPE_CHECKING, Any

from openpyxl.styles import Alignment
from openpyxl.worksheet.worksheet import Worksheet

from ..view import warning_heading_key
from ..views import Row
from ..wording import (
    param_name,
    param_value,
    sentence,
    with_status,
)

if TYPE_CHECKING:
    from ...norms import NormSet
    from ...project.jobs import ScanJob, UavJob

from .book import Book
from .cells import (
    _WARNING_FILL,
    F2,
    F3,
    INT,
    SCALE,
    _header,
    _mark,
    put_num,
    put_text,
)
from .design import write_gsd_limits

_SECTIONS = {"film": "film_scan", "uav": "uav_section", "spec": "spec_title"}


def _warning_items(book: Book, scan: ScanJob | None,
                   uav: UavJob | None) -> list[tuple[str, Row, Any]]:
    """Every warning of the result once (the view's ``warnings`` table): its section's
    name, its row and the norm set its sentence names ids of."""
    norm_sets = {"film": scan.norm_set if scan is not None else None,
                 "uav": uav.norm_set if uav is not None else None, "spec": None}
    return [(book.f(_SECTIONS[r.fields["section"]]), r, norm_sets[r.fields["section"]])
            for r in book.view.tables["warnings"].rows]


def _heading(book: Book, r: Row) -> str:
    key = warning_heading_key(r.key)
    return book.f(key) if key else ""


def _warning_lines(book: Book, scan: ScanJob | None, uav: UavJob | None, *,
                   info: bool = False) -> list[str]:
    """Every warning in short form (the Summary sheet's box), ``"! "`` before each; with
    ``info``, the information and conditions checked instead, ``"i "`` before each (as the
    PDF's page 1 keeps them apart from what to act on)."""
    scales: dict[str, list[str]] = {}  # heading → photo scales, one line per heading
    for _section, r, ns in _warning_items(book, scan, uav):
        if (r.fields["severity"] == "info") != info:
            continue
        message, photo_scales = r.values
        head = _heading(book, r) or book.f.message(message, ns)
        listed = scales.setdefault(head, [])
        listed += [x for x in (book.f.scale(s) for s in photo_scales)
                   if x not in listed]
    sep = _list_sep(book)
    mark = "i" if info else "!"
    return [f"{mark} {head}" + (f": {sep.join(xs)}" if xs else "")
            for head, xs in scales.items()]


def _list_sep(book: Book) -> str:
    """Between the scales of a list (the formatter's list separator)."""
    return book.f.list_sep


def norms_sheet(book: Book, scan: ScanJob | None, uav: UavJob | None) -> None:
    used: list[tuple[NormSet, list[Any], str]] = []
    tables = book.view.tables
    for job, obj, section in (
            (scan, tables["film_inputs"].row("object").value if scan else None, "film_scan"),
            (uav, tables["uav_inputs"].row("object").value if uav else None, "uav_section")):
        if job is None:
            continue
        for ns, objs, _section in used:
            if ns.name == job.norm_set.name and ns.path == job.norm_set.path:
                objs.append(obj)
                break
        else:
            used.append((job.norm_set, [obj], section))
    ws = book.sheet("sheet_norms", landscape=True,
                    widths=(46, 34, 44, 12, 24, 50))
    _header(ws, 1, [book.f("parameter"), book.f("value"), book.f("source")])
    row = 2
    for ns, objs, _section in used:
        row = _norm_set(book, ws, row, ns, [o for o in objs if o is not None]) + 1


def _norm_set(book: Book, ws: Worksheet, row: int, ns: NormSet, objs: list[Any]) -> int:
    title = ns.title_ru if book.loc == "ru" and ns.title_ru else ns.title
    row = book.section(ws, row, f"{book.f('norm_set')}: {title}")
    row = book.kv(ws, row, book.f("title"), title, wrap=True)
    numbers = re.findall(r"\[\d+\]", book.f.cite(ns.source))
    row = book.kv(ws, row, book.f("source"),
                  "; ".join(dict.fromkeys(numbers)) if numbers else ns.source, wrap=True)
    row = book.kv(ws, row, book.f("bundled"),
                  book.f("bundled_yes" if ns.bundled else "bundled_no"))
    if not ns.bundled:  # a bundled set's folder depends on the installation
        row = book.kv(ws, row, book.f("folder"), str(ns.path))
    if ns.imported_from:
        row = book.kv(ws, row, book.f("imported_from"), ns.imported_from)
        row = book.kv(ws, row, book.f("imported_at"), ns.imported_at)
    row = book.section(ws, row + 1, book.f("parameters"))
    _header(ws, row, [book.f("parameter"), book.f("value"), book.f("source")])
    row += 1
    for key in ns.parameters:
        value = ns.parameters[key]
        put_text(ws, row, 1, param_name(ns, key, book.loc), wrap=True)
        if isinstance(value, int | float) and not isinstance(value, bool):
            put_num(ws, row, 2, value, "0.0##")
            ws.cell(row, 2).alignment = Alignment(horizontal="left", vertical="top")
        else:
            put_text(ws, row, 2, param_value(ns, key, value, book.loc), wrap=True)
        put_text(ws, row, 3, with_status(book.f.cite(ns.parameter_sources.get(key, "")),
                                         ns.parameter_status.get(key, ""), book.loc),
                 wrap=True)
        row += 1
    shapes_used = {o.shape for o in objs}
    row = book.section(ws, row + 1, book.f("shapes"))
    _header(ws, row, [book.f("shape"), book.f("shape_coefficient"),
                      book.f("source"), book.f("used")])
    row += 1
    for shape, coef in ns.shapes.items():
        meta = ns.shape_rows.get(shape, {})
        cells = [put_text(ws, row, 1, book.f.shape(ns, shape)),
                 put_num(ws, row, 2, coef, F2),
                 put_text(ws, row, 4, book.f.yes_no(shape in shapes_used))]
        put_text(ws, row, 3, book.f.cite(meta.get("source", "")), wrap=True)
        if shape in shapes_used:
            _mark(cells)
        row += 1
    row = book.section(ws, row + 1, book.f("objects"))
    _header(ws, row, [book.f("map_scale"), book.f("object_name"),
                      book.f("object_size_m"), book.f("used"),
                      book.f("shape"), book.f("source")])
    row += 1
    used_rows = {(o.map_scale, o.name, o.size_m) for o in objs if o.map_scale is not None}
    for obj in ns.objects:
        is_used = (obj.map_scale, obj.name, obj.size_m) in used_rows
        cells = [put_num(ws, row, 1, obj.map_scale, SCALE),
                 put_text(ws, row, 2, book.f.object(obj), wrap=True),
                 put_num(ws, row, 3, obj.size_m, F3),
                 put_text(ws, row, 4, book.f.yes_no(is_used)),
                 put_text(ws, row, 5, book.f.shape(ns, obj.shape))]
        put_text(ws, row, 6, with_status(book.f.cite(obj.source), obj.status, book.loc),
                 wrap=True)
        if is_used:
            _mark(cells)
        row += 1
    return write_gsd_limits(book, ws, row, ns)


def warnings_sheet(book: Book, scan: ScanJob | None, uav: UavJob | None) -> None:
    """Every warning of the result once (the view's ``warnings`` table), warnings filled."""
    ws = book.sheet("warnings", landscape=True, widths=(20, 14, 30, 20, 90))
    _header(ws, 1, [book.f("section"), book.f("severity"), book.f("warning"),
                    book.f("photo_scale"), book.f("message")])
    items = _warning_items(book, scan, uav)
    if not items:
        put_text(ws, 2, 1, book.f("no_warnings"))
        return
    for row, (section, r, ns) in enumerate(items, start=2):
        message, photo_scales = r.values
        try:
            severity = book.f(f"severity_{r.fields['severity']}")
        except KeyError:
            severity = r.fields["severity"]
        cells = [put_text(ws, row, 1, section, wrap=True),
                 put_text(ws, row, 2, severity),
                 put_text(ws, row, 3, _heading(book, r), wrap=True),
                 put_text(ws, row, 4, _list_sep(book).join(book.f.scale(s)
                                                           for s in photo_scales),
                          wrap=True),
                 put_text(ws, row, 5, sentence(book.f.message(message, ns)), wrap=True)]
        if r.fields["severity"] == "warning":
            for cell in cells:
                cell.fill = _WARNING_FILL
    ws.auto_filter.ref = f"A1:E{len(items) + 1}"


def references_sheet(book: Book) -> None:
    """The works the workbook cites, numbered as in its cells; then the list of symbols of
    its formulas (the view's ``symbols`` table)."""
    ws = book.sheet("references", landscape=False, widths=(8, 110, 8))
    _header(ws, 1, ["№", book.f("references")])
    row = 2
    for n, text in book.f.references():
        put_num(ws, row, 1, n, INT)
        put_text(ws, row, 2, text, wrap=True)
        row += 1
    symbols = book.view.tables["symbols"].rows
    if symbols:
        row = book.section(ws, row + 1, book.f("symbols"))
        for r in symbols:
            put_text(ws, row, 1, r.value)
            put_text(ws, row, 2, book.f(r.fields["meaning"]), wrap=True)
            row += 1

"""The Summary sheet: title and approval blocks, the warnings box, the specification, the
headline results."""

from __future__ import annotations

from typing import TYPE_CHECKING

from openpyxl.worksheet.worksheet import Worksheet

from ..views import Row, Table
from ..wording import (
    sentence,
)

if TYPE_CHECKING:
    from ...project.jobs import ScanJob, UavJob
    from ...project.spec import PlanResult

from .book import Book
from .cells import (
    _SECTION,
    _TITLE,
    _WARNING_FILL,
    F1,
    F2,
    F3,
    F4,
    MB,
    MISSING,
    SCALE,
    UM,
    _header,
    _mark,
    put_num,
    put_text,
)
from .closing import _warning_lines


def summary_sheet(book: Book, scan: ScanJob | None, uav: UavJob | None,
            spec: PlanResult | None = None) -> None:
    ws = book.sheet("summary", landscape=True,
                    widths=(34, 16, 26, 14, 14, 14, 14, 14, 14, 70))
    titles = ([book.f("title_scan")] if scan else []) + ([book.f("title_uav")] if uav else [])
    book.title_text = "; ".join(titles)
    put_text(ws, 1, 1, book.title_text).font = _TITLE
    m = book.meta
    row = 3
    block = [("project", m.project), ("customer", m.customer), ("contractor", m.contractor)]
    block += [(k, v) for k, v in (("organisation", m.organisation),
                                  ("contract_number", m.contract_number)) if v]
    block.append(("date", book.f.date(m.date or book.when.date())))
    for key, value in block:
        put_text(ws, row, 1, book.f(key), bold=True)
        put_text(ws, row, 2, value)  # one line, running over the empty cells beside it
        row += 1
    line = "________________"
    blocks = [("approved", m.approver_position + (f", {m.organisation}"
                                                 if m.organisation else ""),
               m.approver_name)]
    if m.agreed_position or m.agreed_name or m.agreed_organisation:
        blocks.append(("agreed", m.agreed_position + (f", {m.agreed_organisation}"
                                                     if m.agreed_organisation else ""),
                       m.agreed_name))
    for head, position, name in blocks:
        row += 1
        put_text(ws, row, 1, book.f(head)).font = _SECTION
        row += 1
        for key, value in (("position", position), ("name", name),
                           ("signature", line), ("date", line)):
            put_text(ws, row, 1, book.f(key), bold=True)
            put_text(ws, row, 2, value)
            row += 1
    row += 1
    for key, value in (("compiled_by", m.compiled_by), ("checked_by", m.checked_by)):
        put_text(ws, row, 1, book.f(key), bold=True)
        put_text(ws, row, 2, value or line)
        put_text(ws, row, 3, line)
        row += 1
    for key, info in (("warnings", False), ("notes_box", True)):
        box = _warning_lines(book, scan, uav, info=info)
        if box:
            row = book.section(ws, row + 1, book.f(key))
            for text in box:
                cell = put_text(ws, row, 1, text, wrap=False)
                if not info:  # what to act on is filled; information is not
                    cell.fill = _WARNING_FILL
                row += 1
    if spec is not None:
        row = _summary_spec(book, ws, row + 1, spec)
    if scan is not None:
        row = _summary_scan(book, ws, row + 1, scan)
    if uav is not None:
        row = _summary_uav(book, ws, row + 1, uav)


def _summary_spec(book: Book, ws: Worksheet, row: int, spec: PlanResult) -> int:
    """The specification of ``scanplan plan``: what was chosen and why (the ``spec_film``
    and ``spec_uav`` tables), and the comparison."""
    row = book.section(ws, row, book.f("spec_title"))
    tables = book.view.tables
    if tables.has("spec_film"):
        row = _spec_film(book, ws, row, tables["spec_film"])
    if tables.has("spec_uav"):
        row = _spec_uav(book, ws, row, tables["spec_uav"])
    if spec.comparison:
        row = book.section(ws, row + 1, book.f("spec_comparison"))
        _header(ws, row, [book.f("spec_quantity"), book.f("spec_film"), book.f("spec_uav"),
                          book.f("unit")])
        row += 1
        for r in book.view.tables["comparison"].rows:
            put_text(ws, row, 1, book.f.row_label(r))
            for col, value in enumerate(r.values, start=2):
                if isinstance(value, int | float):
                    put_num(ws, row, col, value, "#,##0" if r.digits == 0 else "#,##0.000")
                else:
                    put_text(ws, row, col, MISSING)
            put_text(ws, row, 4, book.f.unit(r.unit))
            row += 1
    return row


#: The workbook's number format of a headline row's decimals.
_DIGITS = {0: "0", 1: "0.0", 2: "0.00"}
#: The rows of the headlines shown with grouped thousands.
_GROUPED = {"frame_megabytes": "#,##0", "frames": "#,##0", "scanned_gb": "#,##0.0",
            "photos": "#,##0", "data_volume_gb": "#,##0.0", "data_volume_jpeg_gb": "#,##0.0"}


def _headline_row(book: Book, ws: Worksheet, row: int, r: Row, label: str) -> int:
    """One ``label | value`` row of a headline: a constraint by its name, a number in its
    decimals, the reason across the sheet."""
    if r.key == "reason":
        return book._wide_kv(ws, row, label, sentence(book.f.message(r.value,
                                                                r.details[0]["norm_set"])))
    if "constraint" in r.flags:
        return book.kv(ws, row, label, book.f.cname(r.value))
    fmt = '"1:"0' if r.unit == "scale" else _GROUPED.get(r.key, _DIGITS[r.digits or 0])
    return book.kv(ws, row, label, r.value, fmt)


#: The film headline's rows the sheet shows and their labels.
_FILM_LABELS = {"scan_pixel_um": "scan_pixel_um", "scanner_pixel_um": "scanner_pixel_um",
                "binding": "binding", "frame_megabytes": "frame_megabytes",
                "frames": "spec_frames", "scanned_gb": "spec_scanned_gb",
                "reason": "spec_reason"}


def _spec_film(book: Book, ws: Worksheet, row: int, tbl: Table) -> int:
    for r in tbl.rows:
        if r.key == "photo_scale":
            key = ("spec_archive_photo_scale" if "archive" in r.flags
                   else "spec_recommended_photo_scale")
        elif r.key == "probability":
            key = "terrain_film_probability" if "over_relief" in r.flags else "probability"
        elif r.key in _FILM_LABELS:
            key = _FILM_LABELS[r.key]
        else:
            continue
        row = _headline_row(book, ws, row, r, book.f(key))
    return row


#: The digital camera headline's rows the sheet shows and their labels.
_UAV_LABELS = {"planned_height_m": "spec_planned_height_m",
               "recommended_height_m": "spec_recommended_height_m",
               "max_height_relief_m": "spec_max_height_relief_m",
               "max_flown_height_m": "max_flown_height_m", "binding": "binding",
               "gsd_cm": "gsd_recommended_cm", "forward_overlap_pct": "forward_overlap_pct",
               "side_overlap_pct": "side_overlap_pct", "photos": "spec_photos",
               "data_volume_gb": "data_volume_gb",
               "data_volume_jpeg_gb": "data_volume_jpeg_gb", "reason": "spec_reason"}


def _spec_uav(book: Book, ws: Worksheet, row: int, tbl: Table) -> int:
    for r in tbl.rows:
        if r.key == "max_height_m":
            key = "spec_max_height_flat_m" if "flat" in r.flags else "max_height_m"
        elif r.key in _UAV_LABELS:
            key = _UAV_LABELS[r.key]
        else:
            continue
        row = _headline_row(book, ws, row, r, book.f(key))
    return row


def _summary_scan(book: Book, ws: Worksheet, row: int, job: ScanJob) -> int:
    """The film plan's results per photo scale (the ``film_constraints`` table and each
    scale's explanation), the interpretation limit and the smallest photo scale each scan
    pixel supports (``film_reach``)."""
    tables = book.view.tables
    row = book.section(ws, row, f"{book.f('results')}: {book.f('film_scan')}")
    _header(ws, row, [book.f("photo_scale"), book.f("photo_to_map"), book.f("binding"),
                      book.f("scan_pixel_um"), book.f("scanner_pixel_um"),
                      book.f("frame_megabytes"), book.f("resolution_on_ground_mm"),
                      book.f("required_r_lpmm"), book.f("probability"),
                      book.f("explanation")])
    row += 1
    film = tables["film_constraints"]
    values = {r.key: r.values for r in film.rows}
    explanations = [r.value for r in tables["film_explanations"].rows]
    none = (None,) * len(film.columns)
    for i, column in enumerate(film.columns):
        put_num(ws, row, 1, column.value, SCALE)
        put_num(ws, row, 2, values["photo_to_map"][i], F2)
        binding = put_text(ws, row, 3, book.f.cname(values["binding"][i]))
        pixel = put_num(ws, row, 4, values["scan_pixel_um"][i], UM)
        _mark((binding, pixel))
        put_num(ws, row, 5, values.get("scanner_pixel_um", none)[i], UM)
        put_num(ws, row, 6, values["frame_megabytes"][i], MB)
        put_num(ws, row, 7, values["resolution_on_ground"][i], F1)
        put_num(ws, row, 8, values.get("required_r", none)[i], F1)
        put_num(ws, row, 9, values.get("recognition_probability", none)[i], F3)
        put_text(ws, row, 10, book.f.message(explanations[i], job.norm_set), wrap=True)
        row += 1
    row += 1
    reach = tables["film_reach"]
    limit = reach.row("interpretation_limit").value
    put_text(ws, row, 1, book.f("interpretation_limit_mc"), wrap=True)
    put_num(ws, row, 2, limit, SCALE)
    row += 1
    pixels = [r for r in reach.rows if r.key == "reach"]
    if pixels:
        row = book.section(ws, row + 1, book.f("reach"))
        both = limit is not None
        _header(ws, row, [book.f("pixel_um"), book.f("reach_pixel"),
                          book.f("limiting_constraint")]
                + ([book.f("reach_interpretable")] if both else []))
        row += 1
        for r in pixels:
            pixel, largest, limiting, interpretable = r.values
            put_num(ws, row, 1, pixel, UM)
            put_num(ws, row, 2, largest, SCALE)
            put_text(ws, row, 3, book.f.cname(limiting))
            if both:
                put_num(ws, row, 4, interpretable, SCALE)
            row += 1
    return row


def _summary_uav(book: Book, ws: Worksheet, row: int, job: UavJob) -> int:
    """The digital camera's headline results (the ``uav_figures`` table), the maximum
    height and the map object's recognition (``uav_recognition``)."""
    tables = book.view.tables
    fig = {r.key: r for r in tables["uav_figures"].rows}
    row = book.section(ws, row, f"{book.f('results')}: {book.f('uav_section')}")
    _header(ws, row, [book.f("parameter"), book.f("value")])
    row += 1
    row = book.kv(ws, row, book.f("height_m"), fig["height_m"].value, F1)
    row = book.kv(ws, row, book.f("gsd_m"), fig["gsd_m"].value, F4)
    resolution = fig["ground_resolution_m"]
    if "not_resolvable" in resolution.flags:
        row = book.kv(ws, row, book.f("ground_resolution_m"), book.f("not_resolvable"))
    else:
        row = book.kv(ws, row, book.f("ground_resolution_m"), resolution.value, F4)
    row = book.kv(ws, row, book.f("l_over_gsd"), fig["l_over_gsd"].value, F2)
    row = book.kv(ws, row, book.f("resolving_power_system"),
                  fig["resolving_power_system"].value, F1)
    if "max_height_m" in fig:
        r0 = row
        row = book.kv(ws, row, book.f("max_height_m"), fig["max_height_m"].value, F1)
        row = book.kv(ws, row, book.f("binding"), book.f.cname(fig["binding"].value))
        _mark((ws.cell(r0, 2), ws.cell(r0 + 1, 2)))
    obj = tables["uav_inputs"].row("object").value
    if obj is not None:
        row = book.kv(ws, row, book.f("object"), book.f.object(obj), wrap=True)
        own = next((r for r in tables["uav_recognition"].rows
                    if r.fields["name"] == obj.name and r.fields["size_m"] == obj.size_m),
                   None)
        if own is not None:
            row = book.kv(ws, row, book.f("p_planned"), own.values[3], F3)
            row = book.kv(ws, row, book.f("p_max"), own.values[4], F3)
    return row

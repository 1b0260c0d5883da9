"""The Summary sheet: title and approval blocks, the warnings box, the specification, the
headline results."""

from __future__ import annotations

from typing import TYPE_CHECKING

from openpyxl.worksheet.worksheet import Worksheet

from ...core import flight as FL
from ..design import relief_max_height_m
from ..tablewords import row_label, row_unit
from ..wording import (
    document_date,
    object_title,
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
    titles = ([book.t("title_scan")] if scan else []) + ([book.t("title_uav")] if uav else [])
    book.title_text = "; ".join(titles)
    put_text(ws, 1, 1, book.title_text).font = _TITLE
    m = book.meta
    row = 3
    block = [("project", m.project), ("customer", m.customer), ("contractor", m.contractor)]
    block += [(k, v) for k, v in (("organisation", m.organisation),
                                  ("contract_number", m.contract_number)) if v]
    block.append(("date", document_date(m.date or book.when.date(), book.loc)))
    for key, value in block:
        put_text(ws, row, 1, book.t(key), bold=True)
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
        put_text(ws, row, 1, book.t(head)).font = _SECTION
        row += 1
        for key, value in (("position", position), ("name", name),
                           ("signature", line), ("date", line)):
            put_text(ws, row, 1, book.t(key), bold=True)
            put_text(ws, row, 2, value)
            row += 1
    row += 1
    for key, value in (("compiled_by", m.compiled_by), ("checked_by", m.checked_by)):
        put_text(ws, row, 1, book.t(key), bold=True)
        put_text(ws, row, 2, value or line)
        put_text(ws, row, 3, line)
        row += 1
    for key, info in (("warnings", False), ("notes_box", True)):
        box = _warning_lines(book, scan, uav, info=info)
        if box:
            row = book.section(ws, row + 1, book.t(key))
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
    """The specification of ``scanplan plan``: what was chosen and why."""
    row = book.section(ws, row, book.t("spec_title"))
    if spec.film is not None:
        f, rec = spec.film, spec.film.recommended
        if rec is not None:
            key = ("spec_archive_photo_scale" if f.archive
                   else "spec_recommended_photo_scale")
            row = book.kv(ws, row, book.t(key), rec.photo_scale, '"1:"0')
            row = book.kv(ws, row, book.t("scan_pixel_um"), rec.scan_pixel_um, "0.0")
            if rec.scanner_pixel_um is not None:
                row = book.kv(ws, row, book.t("scanner_pixel_um"), rec.scanner_pixel_um,
                              "0.0")
            row = book.kv(ws, row, book.t("binding"),
                          book.cname(rec.binding))
            over_relief = getattr(f, "terrain", None) is not None and getattr(
                f, "flat", None) is not None  # the headline is the lowest ground's frame
            row = book.kv(ws, row, book.t("terrain_film_probability" if over_relief
                                          else "probability"),
                          rec.recognition_probability, "0.00")
            row = book.kv(ws, row, book.t("frame_megabytes"), rec.frame_megabytes, "#,##0")
            if f.frames is not None:
                row = book.kv(ws, row, book.t("spec_frames"), f.frames, "#,##0")
                row = book.kv(ws, row, book.t("spec_scanned_gb"), f.scanned_gigabytes,
                              "#,##0.0")
        row = book._wide_kv(ws, row, book.t("spec_reason"),
                            sentence(book.text(f.reason, f.job.norm_set)))
    if spec.uav is not None:
        u, p = spec.uav, spec.uav.job.plan
        if u.planned_height_m is not None:
            row = book.kv(ws, row, book.t("spec_planned_height_m"), u.planned_height_m,
                          "0")
        row = book.kv(ws, row, book.t("spec_recommended_height_m"),
                      u.recommended_height_m, "0")
        relief = relief_max_height_m(u)
        row = book.kv(ws, row, book.t("max_height_m" if relief is None
                                      else "spec_max_height_flat_m"), u.max_height_m, "0")
        if relief is not None:
            row = book.kv(ws, row, book.t("spec_max_height_relief_m"), relief, "0")
        if p.max_flown_height_m is not None:
            row = book.kv(ws, row, book.t("max_flown_height_m"), p.max_flown_height_m, "0")
        if p.binding:
            row = book.kv(ws, row, book.t("binding"),
                          book.cname(p.binding))
        row = book.kv(ws, row, book.t("design_gsd_planned"), p.gsd_m * 100.0, "0.00")
        row = book.kv(ws, row, book.t("forward_overlap_pct"),
                      p.inputs.forward_overlap_pct, "0")
        row = book.kv(ws, row, book.t("side_overlap_pct"),
                      p.inputs.side_overlap_pct, "0")
        if "photos" in p.flight:
            row = book.kv(ws, row, book.t("spec_photos"), p.flight["photos"], "#,##0")
        if "data_volume_bytes" in p.flight:
            row = book.kv(ws, row, book.t("data_volume_gb"),
                          p.flight["data_volume_bytes"] / 1e9, "#,##0.0")
            row = book.kv(ws, row, book.t("data_volume_jpeg_gb"), float(
                FL.jpeg_volume_bytes(p.flight["data_volume_bytes"])) / 1e9, "#,##0.0")
        row = book._wide_kv(ws, row, book.t("spec_reason"),
                            sentence(book.text(u.reason, u.job.norm_set)))
    if spec.comparison:
        row = book.section(ws, row + 1, book.t("spec_comparison"))
        _header(ws, row, [book.t("spec_quantity"), book.t("spec_film"), book.t("spec_uav"),
                          book.t("unit")])
        row += 1
        for r in book.view.tables["comparison"].rows:
            put_text(ws, row, 1, row_label(r, book.view.labels, book.numbers))
            for col, value in enumerate(r.values, start=2):
                if isinstance(value, int | float):
                    put_num(ws, row, col, value, "#,##0" if r.digits == 0 else "#,##0.000")
                else:
                    put_text(ws, row, col, MISSING)
            put_text(ws, row, 4, row_unit(r.unit, book.view.labels))
            row += 1
    return row


def _summary_scan(book: Book, ws: Worksheet, row: int, job: ScanJob) -> int:
    plan = job.plan
    row = book.section(ws, row, f"{book.t('results')}: {book.t('xlsx_section_scan')}")
    _header(ws, row, [book.t("photo_scale"), book.t("photo_to_map"), book.t("binding"),
                      book.t("scan_pixel_um"), book.t("scanner_pixel_um"),
                      book.t("frame_megabytes"), book.t("xlsx_resolution_on_ground_mm"),
                      book.t("xlsx_required_r_lpmm"), book.t("probability"),
                      book.t("xlsx_explanation")])
    row += 1
    for s in plan.scenarios:
        put_num(ws, row, 1, s.photo_scale, SCALE)
        put_num(ws, row, 2, s.photo_to_map_ratio, F2)
        binding = put_text(ws, row, 3, book.cname(s.binding))
        pixel = put_num(ws, row, 4, s.scan_pixel_um, UM)
        _mark((binding, pixel))
        put_num(ws, row, 5, s.scanner_pixel_um, UM)
        put_num(ws, row, 6, s.frame_megabytes, MB)
        put_num(ws, row, 7, s.resolution_on_ground_mm, F1)
        put_num(ws, row, 8, s.required_resolving_power_lpmm, F1)
        put_num(ws, row, 9, s.recognition_probability, F3)
        put_text(ws, row, 10, book.text(s.explanation, job.norm_set), wrap=True)
        row += 1
    row += 1
    put_text(ws, row, 1, book.t("xlsx_interpretation_limit"), wrap=True)
    put_num(ws, row, 2, plan.interpretation_limit_photo_scale, SCALE)
    row += 1
    if plan.max_photo_scales:
        row = book.section(ws, row + 1, book.t("xlsx_reach"))
        both = plan.interpretation_limit_photo_scale is not None
        _header(ws, row, [book.t("pixel_um"), book.t("reach_pixel"), book.t("xlsx_limit")]
                + ([book.t("reach_interpretable")] if both else []))
        row += 1
        for reach in plan.max_photo_scales:
            put_num(ws, row, 1, reach.pixel_um, UM)
            put_num(ws, row, 2, reach.max_photo_scale if reach.max_photo_scale > 0
                    else None, SCALE)
            put_text(ws, row, 3, book.cname(reach.limit))
            if both:
                put_num(ws, row, 4, reach.max_photo_scale_interpretable or None, SCALE)
            row += 1
    return row


def _summary_uav(book: Book, ws: Worksheet, row: int, job: UavJob) -> int:
    plan = job.plan
    row = book.section(ws, row, f"{book.t('results')}: {book.t('uav_section')}")
    _header(ws, row, [book.t("parameter"), book.t("value")])
    row += 1
    row = book.kv(ws, row, book.t("height_m"), plan.heights_m.get("planned"), F1)
    row = book.kv(ws, row, book.t("gsd_m"), plan.gsd_m, F4)
    if plan.ground_resolution_m is None:
        row = book.kv(ws, row, book.t("ground_resolution_m"), book.t("not_resolvable"))
    else:
        row = book.kv(ws, row, book.t("ground_resolution_m"), plan.ground_resolution_m, F4)
    row = book.kv(ws, row, book.t("l_over_gsd"), plan.ground_resolution_to_gsd, F2)
    row = book.kv(ws, row, book.t("resolving_power_system"), plan.resolving_power_lpmm, F1)
    if plan.max_height_m is not None:
        r0 = row
        row = book.kv(ws, row, book.t("max_height_m"), plan.max_height_m, F1)
        row = book.kv(ws, row, book.t("binding"), book.cname(plan.binding or ""))
        _mark((ws.cell(r0, 2), ws.cell(r0 + 1, 2)))
    obj = plan.inputs.map_object
    if obj is not None:
        row = book.kv(ws, row, book.t("object"), object_title(obj, book.loc), wrap=True)
        for rec in plan.recognition:
            if rec.object == obj.name and rec.object_size_m == obj.size_m:
                row = book.kv(ws, row, book.t("xlsx_p_planned"), rec.probability, F3)
                row = book.kv(ws, row, book.t("xlsx_p_max"),
                              rec.probability_at_max_height, F3)
                break
    return row

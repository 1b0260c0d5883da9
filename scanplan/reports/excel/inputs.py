"""The Inputs sheet: what the plans were computed from."""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

from openpyxl.worksheet.worksheet import Worksheet

from ...rules.film import height_formula_name
from ..wording import (
    camera_title,
    object_title,
    scanner_title,
)

if TYPE_CHECKING:
    from ...norms import NormSet
    from ...project.jobs import ScanJob, UavJob

from .book import Book
from .cells import (
    F1,
    F2,
    F3,
    F4,
    INT,
    M_LARGE,
    SCALE,
    UM,
    _header,
)


def inputs_sheet(book: Book, scan: ScanJob | None, uav: UavJob | None) -> None:
    ws = book.sheet("inputs", landscape=False, widths=(46, 16, 12, 12, 12, 12,
                                                                   12, 12))
    _header(ws, 1, [book.t("parameter"), book.t("value")])
    row = 2
    if scan is not None:
        row = _inputs_scan(book, ws, row, scan) + 1
    if uav is not None:
        row = _inputs_uav(book, ws, row, uav)


def _object_rows(book: Book, ws: Worksheet, row: int, obj: Any, ns: NormSet) -> int:
    if obj is None:
        return book.kv(ws, row, book.t("object"), None)
    row = book.kv(ws, row, book.t("object"), object_title(obj, book.loc), wrap=True)
    row = book.kv(ws, row, book.t("xlsx_object_size_m"), obj.size_m, F3)
    row = book.kv(ws, row, book.t("shape"), book.shape_name(ns, obj.shape))
    row = book.kv(ws, row, book.t("xlsx_shape_coefficient"), obj.shape_coefficient, F2)
    return book.kv(ws, row, book.t("xlsx_object_source"), book.text(obj.source),
                   wrap=True)


def _inputs_scan(book: Book, ws: Worksheet, row: int, job: ScanJob) -> int:
    inp, rules = job.plan.inputs, job.plan.rules
    row = book.section(ws, row, book.t("xlsx_section_scan"))
    row = book.kv(ws, row, book.t("map_scale"), inp.map_scale, SCALE)
    row = book.kv(ws, row, book.t("relief_interval_m"), inp.relief_interval_m, F2)
    row = book.kv_list(ws, row, book.t("photo_scale"), inp.photo_scales, SCALE)
    row = book.kv(ws, row, book.t("camera"),
                  camera_title(job.norm_set, inp.camera, book.loc, inp.camera_name) or None,
                  wrap=True)
    row = book.kv(ws, row, book.t("focal_mm"), inp.focal_mm, F2)
    row = book.kv(ws, row, book.t("xlsx_frame_across_mm"), inp.frame_width_mm, F1)
    row = book.kv(ws, row, book.t("xlsx_frame_along_mm"), inp.frame_along_mm, F1)
    row = book.kv(ws, row, book.t("resolving_power_lpmm"), inp.resolving_power_lpmm, F1)
    row = book.kv(ws, row, book.t("forward_overlap_pct"), inp.forward_overlap_pct, F1)
    row = _object_rows(book, ws, row, inp.object, job.norm_set)
    row = book.kv(ws, row, book.t("probability"), rules.probability, F3)
    row = book.kv(ws, row, book.t("xlsx_height_formula"),
                  book.text(height_formula_name(rules.height_formula)))
    row = book.kv(ws, row, book.t("xlsx_pr_coefficient"), rules.pr_coefficient, F2)
    row = book.kv(ws, row, book.t("scanner"),
                  scanner_title(job.norm_set, inp.scanner, book.loc) or None)
    if inp.scanner_steps_um:
        row = book.kv_list(ws, row, book.t("xlsx_scanner_steps_um"), inp.scanner_steps_um,
                           UM)
    if inp.candidate_pixels_um:
        row = book.kv_list(ws, row, book.t("xlsx_candidate_pixels_um"),
                           inp.candidate_pixels_um, UM)
    row = book.kv(ws, row, book.t("xlsx_bands"), inp.bands, INT)
    return book.kv(ws, row, book.t("xlsx_bits_per_band"), inp.bits_per_band, INT)


def _inputs_uav(book: Book, ws: Worksheet, row: int, job: UavJob) -> int:
    inp = job.plan.inputs
    row = book.section(ws, row, book.t("uav_section"))
    rows: list[tuple[str, object, str | None]] = [
        ("camera", camera_title(job.norm_set, inp.camera, book.loc, inp.camera_name)
         or None, None),
        ("pixel_pitch_um", inp.pixel_um, F2),
        ("focal_mm", inp.focal_mm, F2),
        ("xlsx_f_number", inp.f_number, F1),
        ("orientation", book.t(f"orientation_{inp.orientation}"), None),
        ("xlsx_sensor_width_mm", inp.sensor_width_mm, F2),
        ("xlsx_sensor_height_mm", inp.sensor_height_mm, F2),
        ("xlsx_image_width_px", inp.image_width_px, INT),
        ("xlsx_image_height_px", inp.image_height_px, INT),
        ("min_trigger_interval_s", inp.min_trigger_interval_s, F3),
        ("height_m", inp.height_m, F1),
        ("xlsx_tolerance_up_pct", inp.height_tolerance_up_pct, F1),
        ("xlsx_tolerance_down_pct", inp.height_tolerance_down_pct, F1),
        ("ground_speed_ms", inp.speed_ms, F1),
        ("exposure_s", inp.exposure_s, "0.00000"),
        ("forward_overlap_pct", inp.forward_overlap_pct, F1),
        ("side_overlap_pct", inp.side_overlap_pct, F1),
        ("xlsx_area_width_m", inp.area_width_m, M_LARGE),
        ("xlsx_area_length_m", inp.area_length_m, M_LARGE),
        ("map_scale", inp.map_scale, SCALE),
        ("relief_interval_m", inp.relief_interval_m, F2),
    ]
    for key, value, fmt in rows:
        row = book.kv(ws, row, book.t(key), value, fmt)
    row = _object_rows(book, ws, row, inp.map_object, job.norm_set)
    for key, value, fmt in [
        ("xlsx_r_max", inp.r_max, F3), ("xlsx_r_min", inp.r_min, F3),
        ("threshold_k0", inp.threshold_k0, F3),
        ("xlsx_haze_contrast", inp.haze_contrast, F3),
        ("xlsx_shift_factor", inp.shift_factor, F2),
        ("xlsx_random_speed_ms", inp.random_speed_ms, F2),
        ("xlsx_roll_rate_rad_s", inp.roll_rate_rad_s, F4),
        ("xlsx_pitch_rate_rad_s", inp.pitch_rate_rad_s, F4),
        ("xlsx_yaw_rate_rad_s", inp.yaw_rate_rad_s, F4),
        ("xlsx_roll_deg", inp.roll_deg, F2),
        ("xlsx_pitch_deg", inp.pitch_deg, F2),
        ("xlsx_bands", inp.bands, INT),
        ("xlsx_bits_per_band", inp.bits_per_band, INT),
    ]:
        row = book.kv(ws, row, book.t(key), value, fmt)
    return row

"""The Inputs sheet: what the plans were computed from."""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

from openpyxl.worksheet.worksheet import Worksheet

from ...rules.film import height_formula_name

if TYPE_CHECKING:
    from ...norms import NormSet
    from ...project.jobs import ScanJob, UavJob

from ..views import Row
from .book import Book
from .cells import (
    F1,
    F2,
    F3,
    F4,
    INT,
    M_LARGE,
    SCALE,
    _header,
)


def inputs_sheet(book: Book, scan: ScanJob | None, uav: UavJob | None) -> None:
    ws = book.sheet("inputs", landscape=False, widths=(46, 16, 12, 12, 12, 12,
                                                                   12, 12))
    _header(ws, 1, [book.f("parameter"), book.f("value")])
    row = 2
    if scan is not None:
        row = _inputs_scan(book, ws, row, scan) + 1
    if uav is not None:
        row = _inputs_uav(book, ws, row, uav)


def _object_rows(book: Book, ws: Worksheet, row: int, obj: Any, ns: NormSet) -> int:
    if obj is None:
        return book.kv(ws, row, book.f("object"), None)
    row = book.kv(ws, row, book.f("object"), book.f.object(obj), wrap=True)
    row = book.kv(ws, row, book.f("object_size_m"), obj.size_m, F3)
    row = book.kv(ws, row, book.f("shape"), book.f.shape(ns, obj.shape))
    row = book.kv(ws, row, book.f("shape_coefficient"), obj.shape_coefficient, F2)
    return book.kv(ws, row, book.f("object_source"), book.f.message(obj.source),
                   wrap=True)


#: The Inputs sheet's label of each row of the ``film_inputs`` table.
_FILM_LABELS = {"map_scale": "map_scale", "relief_interval_m": "relief_interval_m",
                "photo_scales": "photo_scale", "focal_mm": "focal_mm",
                "resolving_power_lpmm": "resolving_power_lpmm",
                "forward_overlap_pct": "forward_overlap_pct",
                "object_size_m": "object_size_m",
                "shape_coefficient": "shape_coefficient", "probability": "probability",
                "pr_coefficient": "pr_coefficient",
                "scanner_steps_um": "scanner_steps_um",
                "candidate_pixels_um": "candidate_pixels_um", "bands": "bands",
                "bits_per_band": "bits_per_band"}


def _number_format(r: Row) -> str:
    """A number's cell format: a scale, grouped digits for a count, else the row's
    decimals (the input registry's)."""
    if r.unit == "scale":
        return SCALE
    return INT if r.digits == 0 else "0." + "0" * (r.digits or 0)


def _inputs_scan(book: Book, ws: Worksheet, row: int, job: ScanJob) -> int:
    """The film plan's inputs (the ``film_inputs`` table)."""
    tbl = book.view.tables["film_inputs"]
    row = book.section(ws, row, book.f("film_scan"))
    for r in tbl.rows:
        if isinstance(r.value, tuple) and r.key != "frame_mm":
            row = book.kv_list(ws, row, book.f(_FILM_LABELS[r.key]), r.value,
                               _number_format(r))
        elif r.key in _FILM_LABELS:
            row = book.kv(ws, row, book.f(_FILM_LABELS[r.key]), r.value, _number_format(r))
        else:
            row = _film_text(book, ws, row, r, job)
    return row


def _film_text(book: Book, ws: Worksheet, row: int, r: Row, job: ScanJob) -> int:
    """A film input's row shown as a name, not a number (the frame: two rows)."""
    ns = job.norm_set
    if r.key == "camera":
        return book.kv(ws, row, book.f("camera"),
                       book.f.camera(ns, r.value, r.fields["name"]) or None,
                       wrap=True)
    if r.key == "frame_mm":
        row = book.kv(ws, row, book.f("frame_across_mm"), r.value[0], F1)
        return book.kv(ws, row, book.f("frame_along_mm"), r.value[1], F1)
    if r.key == "object":
        if r.value is None:
            return book.kv(ws, row, book.f("object"), None)
        return book.kv(ws, row, book.f("object"), book.f.object(r.value), wrap=True)
    if r.key == "shape":
        return book.kv(ws, row, book.f("shape"), book.f.shape(ns, r.value))
    if r.key == "object_source":
        return book.kv(ws, row, book.f("object_source"), book.f.message(r.value), wrap=True)
    if r.key == "height_formula":
        return book.kv(ws, row, book.f("height_formula_form"),
                       book.f.message(height_formula_name(r.value)))
    if r.key == "scanner":
        return book.kv(ws, row, book.f("scanner"),
                       book.f.scanner(ns, r.value) or None)
    raise KeyError(r.key)


def _inputs_uav(book: Book, ws: Worksheet, row: int, job: UavJob) -> int:
    inp = job.plan.inputs
    row = book.section(ws, row, book.f("uav_section"))
    rows: list[tuple[str, object, str | None]] = [
        ("camera", book.f.camera(job.norm_set, inp.camera, inp.camera_name)
         or None, None),
        ("pixel_pitch_um", inp.pixel_um, F2),
        ("focal_mm", inp.focal_mm, F2),
        ("f_number", inp.f_number, F1),
        ("orientation", book.f(f"orientation_{inp.orientation}"), None),
        ("sensor_width_mm", inp.sensor_width_mm, F2),
        ("sensor_height_mm", inp.sensor_height_mm, F2),
        ("image_width_px", inp.image_width_px, INT),
        ("image_height_px", inp.image_height_px, INT),
        ("min_trigger_interval_s", inp.min_trigger_interval_s, F3),
        ("height_m", inp.height_m, F1),
        ("tolerance_up_pct", inp.height_tolerance_up_pct, F1),
        ("tolerance_down_pct", inp.height_tolerance_down_pct, F1),
        ("ground_speed_ms", inp.speed_ms, F1),
        ("exposure_s", inp.exposure_s, "0.00000"),
        ("forward_overlap_pct", inp.forward_overlap_pct, F1),
        ("side_overlap_pct", inp.side_overlap_pct, F1),
        ("area_width_m", inp.area_width_m, M_LARGE),
        ("area_length_m", inp.area_length_m, M_LARGE),
        ("map_scale", inp.map_scale, SCALE),
        ("relief_interval_m", inp.relief_interval_m, F2),
    ]
    for key, value, fmt in rows:
        row = book.kv(ws, row, book.f(key), value, fmt)
    row = _object_rows(book, ws, row, inp.map_object, job.norm_set)
    for key, value, fmt in [
        ("r_max", inp.r_max, F3), ("r_min", inp.r_min, F3),
        ("threshold_k0", inp.threshold_k0, F3),
        ("haze_contrast", inp.haze_contrast, F3),
        ("shift_factor", inp.shift_factor, F2),
        ("random_speed_ms", inp.random_speed_ms, F2),
        ("roll_rate_rad_s", inp.roll_rate_rad_s, F4),
        ("pitch_rate_rad_s", inp.pitch_rate_rad_s, F4),
        ("yaw_rate_rad_s", inp.yaw_rate_rad_s, F4),
        ("roll_deg", inp.roll_deg, F2),
        ("pitch_deg", inp.pitch_deg, F2),
        ("bands", inp.bands, INT),
        ("bits_per_band", inp.bits_per_band, INT),
    ]:
        row = book.kv(ws, row, book.f(key), value, fmt)
    return row

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
    SCALE,
    _header,
    number_format,
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
    """A number's cell format: a scale, else the row's decimals (the input registry's),
    thousands grouped (:func:`.cells.number_format`)."""
    if r.unit == "scale":
        return SCALE
    return number_format(r.digits or 0)


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


#: The Inputs sheet's rows of the ``uav_inputs`` table: (row key, label key) in the
#: sheet's order (the map object's rows follow the relief interval).
_UAV_ROWS = (
    ("camera", "camera"), ("pixel_um", "pixel_pitch_um"), ("focal_mm", "focal_mm"),
    ("f_number", "f_number"), ("orientation", "orientation"),
    ("sensor_width_mm", "sensor_width_mm"), ("sensor_height_mm", "sensor_height_mm"),
    ("image_width_px", "image_width_px"), ("image_height_px", "image_height_px"),
    ("min_trigger_interval_s", "min_trigger_interval_s"), ("height_m", "height_m"),
    ("height_tolerance_up_pct", "tolerance_up_pct"),
    ("height_tolerance_down_pct", "tolerance_down_pct"), ("speed_ms", "ground_speed_ms"),
    ("exposure_s", "exposure_s"), ("forward_overlap_pct", "forward_overlap_pct"),
    ("side_overlap_pct", "side_overlap_pct"), ("area_width_m", "area_width_m"),
    ("area_length_m", "area_length_m"), ("map_scale", "map_scale"),
    ("relief_interval_m", "relief_interval_m"),
)
_UAV_SCENE = (
    ("r_max", "r_max"), ("r_min", "r_min"), ("threshold_k0", "threshold_k0"),
    ("haze_contrast", "haze_contrast"), ("shift_factor", "shift_factor"),
    ("random_speed_ms", "random_speed_ms"), ("roll_rate_rad_s", "roll_rate_rad_s"),
    ("pitch_rate_rad_s", "pitch_rate_rad_s"), ("yaw_rate_rad_s", "yaw_rate_rad_s"),
    ("roll_deg", "roll_deg"), ("pitch_deg", "pitch_deg"), ("bands", "bands"),
    ("bits_per_band", "bits_per_band"),
)


def _uav_value(book: Book, ws: Worksheet, row: int, r: Row, label: str) -> int:
    """One input of the UAV plan: a number with its decimals, else its words."""
    if r.key == "camera":
        return book.kv(ws, row, label, book.f.show(r.value) if r.value is not None
                       else None, wrap=True)
    if r.key == "orientation":
        return book.kv(ws, row, label, book.f(f"orientation_{r.value}"))
    return book.kv(ws, row, label, r.value, _number_format(r))


def _inputs_uav(book: Book, ws: Worksheet, row: int, job: UavJob) -> int:
    """The UAV plan's inputs (the ``uav_inputs`` table)."""
    r = {x.key: x for x in book.view.tables["uav_inputs"].rows}
    row = book.section(ws, row, book.f("uav_section"))
    for key, label in _UAV_ROWS:
        row = _uav_value(book, ws, row, r[key], book.f(label))
    row = _object_rows(book, ws, row, r["object"].value, job.norm_set)
    for key, label in _UAV_SCENE:
        row = _uav_value(book, ws, row, r[key], book.f(label))
    return row

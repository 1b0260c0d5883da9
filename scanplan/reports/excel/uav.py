"""The UAV sheets: results, the limits as heights, recognition, flight geometry and the
height chart; the MTF sheet.

The constraints and the recognition are the tables the PDF and the terminal lay out
(:mod:`scanplan.reports.views`), in the same order. The results and the flight geometry
are the workbook's own: every figure of the plan at full precision, one per row (the data
a reader recomputes from), where the PDF's tables pick the ones a signer reads."""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

from openpyxl.chart import Reference, ScatterChart
from openpyxl.chart.axis import ChartLines
from openpyxl.worksheet.worksheet import Worksheet

from ...core.mtf import component_label

if TYPE_CHECKING:
    from ...project.jobs import UavJob
    from ...rules.uav import UavPlan

from ..views import constraint_title
from .book import Book
from .cells import (
    F1,
    F2,
    F3,
    F4,
    INT,
    PCT,
    SCALE,
    _finite,
    _header,
    _mark,
    put_num,
    put_text,
)
from .charts import (
    _add_series,
    _chart_below,
    _log_floor,
    _scatter,
)


def _height_rows(book: Book, ws: Worksheet, row: int, plan: UavPlan) -> int:
    """Highest flown height at the maximum, the ceiling, and the height accuracy."""
    row = book.kv(ws, row, book.t("max_flown_height_m"), plan.max_flown_height_m, F1)
    if plan.ceiling_m is not None:
        row = book.kv(ws, row, book.t("ceiling_m"), plan.ceiling_m, F1)
    if plan.constraints_max_height_m is not None:
        row = book.kv(ws, row, book.t("constraints_max_height_m"),
                      plan.constraints_max_height_m, F1)
    acc = plan.height_accuracy
    if acc:
        row = book.kv(ws, row, book.t("height_accuracy_m"), acc["height_accuracy_m"], F4)
        row = book.kv(ws, row, book.t("sigma_z_m"),
                      acc["sigma_z_at_highest_flown_height_m"], F4)
        row = book.kv(ws, row, book.t("stereo_base_to_height"),
                      acc["stereo_base_to_height"], "0.000")
        row = book.kv(ws, row, book.t("image_measurement_px"),
                      acc["image_measurement_px"], F2)
        for form in ("normal_case", "instruction", "parallax"):
            row = book.kv(ws, row, f"{book.t('height_forms')}: {book.t('hf_' + form)}",
                          acc["forms"][form]["max_planned_height_m"], F1)
    return row


def uav_sheet(book: Book, job: UavJob) -> None:
    """The UAV sheet: results, the limits as heights, recognition, flight geometry,
    GSD and L against the height (table and chart)."""
    plan = job.plan
    ws = book.sheet("xlsx_sheet_uav", landscape=True,
                    widths=(46, 16, 16, 16, 16, 16, 14, 12, 50, 50))
    _header(ws, 1, [book.t("parameter"), book.t("value")])
    row = 2
    h = plan.heights_m
    lr = plan.ground_resolution_m
    for key, value, fmt in [
        ("height_m", h.get("planned"), F1),
        ("xlsx_height_min_m", h.get("min"), F1),
        ("xlsx_height_max_m", h.get("max"), F1),
        ("gsd_m", plan.gsd_m, F4),
        ("xlsx_gsd_at_max_m", plan.gsd_at_max_height_m, F4),
        ("ground_resolution_m", lr if lr is not None else book.t("not_resolvable"),
         F4 if lr is not None else None),
        ("xlsx_l_corner_m", plan.ground_resolution_corner_m, F4),
        ("xlsx_l_at_max_m", plan.ground_resolution_at_max_height_m, F4),
        ("l_over_gsd", plan.ground_resolution_to_gsd, F2),
        ("resolving_power_system", plan.resolving_power_lpmm, F1),
        ("xlsx_r_corner_lpmm", plan.resolving_power_corner_lpmm, F1),
        ("nyquist_lpmm", plan.nyquist_lpmm, F1),
        ("xlsx_resolvable", bool(plan.resolvable), None),
        ("xlsx_sensor_limited", bool(plan.sensor_limited), None),
        ("motion_blur_px", plan.motion_blur_px, F2),
        ("xlsx_max_exposure_s", plan.max_exposure_s, "0.00000"),
        ("xlsx_max_speed_ms", plan.max_speed_ms, F1),
        ("xlsx_tilted_corner_gsd_m", plan.tilted_corner_gsd_m, F4),
    ]:
        row = book.kv(ws, row, book.t(key), value, fmt)
    if plan.max_height_m is not None:
        r0 = row
        row = book.kv(ws, row, book.t("max_height_m"), plan.max_height_m, F1)
        row = book.kv(ws, row, book.t("binding"), book.cname(plan.binding or ""))
        _mark((ws.cell(r0, 2), ws.cell(r0 + 1, 2)))
        row = _height_rows(book, ws, row, plan)
    row = _limits_rows(book, ws, row)
    row = _recognition_rows(book, ws, row, job)
    row = _flight_rows(book, ws, row, plan)
    _height_chart(book, ws, row, plan)


def _limits_rows(book: Book, ws: Worksheet, row: int) -> int:
    """The constraints as maximum flight heights, lowest first as on the PDF's page (the
    ``uav_limits`` table; binding highlighted), with each one's reason and equation."""
    rows = book.view.tables["uav_limits"].rows
    if not rows:
        return row
    row = book.section(ws, row + 1, book.t("xlsx_height_limits"))
    _header(ws, row, [book.t("xlsx_id"), book.t("constraint"), book.t("xlsx_compares"),
                      book.t("xlsx_limit_m"), book.t("max_height_m"),
                      book.t("margin_pct"), book.t("binding"),
                      book.t("max_flown_height_m"), book.t("reason"),
                      book.t("xlsx_equation")])
    row += 1
    for r in rows:
        limit_m, compares, max_height_m, _, _ = r.values
        binding = "binding" in r.flags
        cells = [put_text(ws, row, 1, r.key),
                 put_text(ws, row, 2, constraint_title(r.key, book.loc, r.fields["name"])),
                 put_text(ws, row, 3, compares),
                 put_num(ws, row, 4, limit_m, F4),
                 put_num(ws, row, 5, max_height_m, F1),
                 put_num(ws, row, 6, r.fields["margin_pct"], PCT),
                 put_text(ws, row, 7, book.yes_no(binding)),
                 put_num(ws, row, 8, r.fields["max_flown_m"], F1)]
        put_text(ws, row, 9, book.text(r.fields["reason"]), wrap=True)
        put_text(ws, row, 10, book.text(r.fields["equation"]), wrap=True)
        if binding:
            _mark(cells)
        row += 1
    return row


def _recognition_rows(book: Book, ws: Worksheet, row: int, job: UavJob) -> int:
    """Recognition of the norm objects (the map's object highlighted)."""
    plan = job.plan
    if not plan.recognition:
        return row
    row = book.section(ws, row + 1, book.t("xlsx_recognition"))
    _header(ws, row, [book.t("object_name"), book.t("xlsx_object_size_m"),
                      book.t("shape"), book.t("map_scale"),
                      book.t("xlsx_p_planned"), book.t("xlsx_p_max"),
                      book.t("xlsx_p_corner_max")])
    row += 1
    for r in book.view.tables["uav_recognition"].rows:
        scale, size, shape, p, p_max, p_corner = r.values
        cells = [put_text(ws, row, 1, book.obj_name(job.norm_set, r.fields["name"], scale),
                          wrap=True),
                 put_num(ws, row, 2, size, F3),
                 put_text(ws, row, 3, book.shape_name(job.norm_set, shape)),
                 put_num(ws, row, 4, scale, SCALE),
                 put_num(ws, row, 5, p, F3),
                 put_num(ws, row, 6, p_max, F3),
                 put_num(ws, row, 7, p_corner, F3)]
        if "emph" in r.flags:  # the map's own object
            _mark(cells)
        row += 1
    return row


#: The label of each figure of :attr:`UavPlan.flight` (another: by its name).
_FLIGHT_LABELS = {
    "footprint_across_m": "xlsx_flight_footprint_across_m",
    "footprint_along_m": "xlsx_flight_footprint_along_m",
    "base_m": "base_m", "line_spacing_m": "line_spacing_m",
    "photo_interval_s": "photo_interval_s",
    "forward_overlap_at_min_height_pct": "xlsx_flight_forward_overlap_at_min_height_pct",
    "side_overlap_at_min_height_pct": "xlsx_flight_side_overlap_at_min_height_pct",
    "forward_overlap_at_max_height_pct": "xlsx_flight_forward_overlap_at_max_height_pct",
    "min_trigger_interval_s": "min_trigger_interval_s",
    "max_speed_for_trigger_ms": "xlsx_flight_max_speed_for_trigger_ms",
    "strips": "n_strips", "photos_per_strip": "xlsx_flight_photos_per_strip",
    "photos": "xlsx_flight_photos", "sorties": "xlsx_flight_sorties",
    "flight_length_m": "xlsx_flight_flight_length_m",
    "flight_time_s": "xlsx_flight_flight_time_s",
    "data_volume_bytes": "xlsx_flight_data_volume_bytes",
}


def _flight_rows(book: Book, ws: Worksheet, row: int, plan: UavPlan) -> int:
    """The flight geometry (footprint, base, line spacing, photos ...)."""
    if not plan.flight:
        return row
    row = book.section(ws, row + 1, book.t("xlsx_flight"))
    for key, value in plan.flight.items():
        label = book.t(_FLIGHT_LABELS[key]) if key in _FLIGHT_LABELS else key
        fmt = INT if (key.endswith("_bytes") or key in ("strips", "photos",
                                                        "photos_per_strip")) else F2
        row = book.kv(ws, row, label, value, fmt if not isinstance(value, str)
                      else None)
    return row


def _height_chart(book: Book, ws: Worksheet, row: int, plan: UavPlan) -> None:
    """GSD and L against the flight height: the table and its chart."""
    curve = plan.height_curve
    heights = list(curve.get("height_m", []))
    if heights:
        row = book.section(ws, row + 1, book.t("plot_height"))
        _header(ws, row, [book.t("height_m"), book.t("gsd_m"), book.t("ground_resolution_m")])
        first = row + 1
        for i, hm in enumerate(heights):
            put_num(ws, first + i, 1, hm, F1, missing=None)
            put_num(ws, first + i, 2, curve["gsd_m"][i], F4, missing=None)
            put_num(ws, first + i, 3, curve["ground_resolution_m"][i], F4, missing=None)
        n = len(heights)
        chart = _scatter(book.t("plot_height"), book.t("height_m"), book.t("gsd_m") + "; L")
        chart.x_axis.scaling.min = 0
        chart.y_axis.scaling.min = 0
        chart.x_axis.majorGridlines = ChartLines()
        chart.x_axis.number_format = "0"
        chart.y_axis.number_format = "0.00"
        xref = Reference(ws, min_col=1, min_row=first, max_row=first + n - 1)
        _add_series(chart, ws, xref, 2, n, book.t("gsd_m"), first_row=first)
        _add_series(chart, ws, xref, 3, n, book.t("ground_resolution_m"), first_row=first)
        top = max((v for v in (_finite(x) for key in ("gsd_m", "ground_resolution_m")
                               for x in curve[key]) if v is not None), default=1.0)
        end = _height_markers(book, chart, ws, plan, first + n + 1, top,
                                   max(heights))
        _chart_below(ws, chart, end + 1)


def _height_markers(book: Book, chart: ScatterChart, ws: Worksheet, plan: Any, row: int,
                    top: float, right: float) -> int:
    """Vertical lines at the planned, highest flown and maximum heights and the binding
    ground limit as a horizontal line (two-point series, their cells below the curve).
    Returns the next free row."""
    h = plan.heights_m
    m = " м" if book.loc == "ru" else " m"
    marks: list[tuple[str, float, float, float, float, str, str]] = []
    if h.get("planned"):
        marks.append((f"{book.t('planned')}: {book.numbers.height(h['planned'])}{m}",
                      h["planned"], 0.0, h["planned"], top, "000000", "solid"))
    if plan.over_relief and h.get("min") and h["min"] < h.get("planned", 0.0) - 0.05:
        marks.append((f"{book.t('lowest_flown')}: {book.numbers.height(h['min'])}{m}",
                      h["min"], 0.0, h["min"], top, "7F7F7F", "sysDot"))
    if h.get("max") and h["max"] != h.get("planned"):
        marks.append((f"{book.t('highest_flown')}: {book.numbers.height(h['max'])}{m}",
                      h["max"], 0.0, h["max"], top, "7F7F7F", "dash"))
    if plan.max_height_m is not None:
        marks.append((f"{book.t('max_height_m').split(',')[0]} ({plan.binding}): "
                      f"{book.numbers.whole(round(plan.max_height_m))}{m}",
                      plan.max_height_m, 0.0, plan.max_height_m, top, "C00000", "sysDot"))
        flown = plan.max_flown_height_m  # where the binding limit is checked
        if flown is not None and flown > plan.max_height_m * (1 + 1e-9):
            marks.append((f"{book.t('xlsx_max_flown')}: {book.numbers.whole(flown)}{m}",
                          flown, 0.0, flown, top, "C00000", "dash"))
    b = next((lim for lim in plan.limits if lim.binding), None)
    if b is not None and b.limit_m <= top * 1.5:
        marks.append((f"{b.compares} ≤ {book.numbers.fixed(b.limit_m, 3)}{m} "
                      f"({b.id})", 0.0, b.limit_m, right, b.limit_m, "C00000", "dashDot"))
    if not marks:
        return row
    _header(ws, row, [book.t("xlsx_marker"), "x", "y"])
    row += 1
    for label, x0, y0, x1, y1, color, dash in marks:
        put_text(ws, row, 1, label)
        put_num(ws, row, 2, x0, F1)
        put_num(ws, row, 3, y0, F4)
        put_num(ws, row + 1, 2, x1, F1)
        put_num(ws, row + 1, 3, y1, F4)
        xref = Reference(ws, min_col=2, min_row=row, max_row=row + 1)
        _add_series(chart, ws, xref, 3, 2, label, first_row=row, color=color,
                    dash=None if dash == "solid" else dash)
        row += 2
    return row


def mtf_sheet(book: Book, job: UavJob) -> None:
    plan = job.plan
    mc = plan.mtf_centre
    freq = list(mc.get("freq_lpmm", []))
    if not freq:
        return
    special = ("freq_lpmm", "system", "image_contrast", "threshold")
    comps = [k for k in mc if k not in special and isinstance(mc[k], list)]
    cols = comps + [k for k in ("system", "image_contrast", "threshold") if k in mc]
    heads = [book.t("frequency_lpmm")]
    for k in cols:
        if k == "image_contrast":
            heads.append(book.t("image_contrast"))
        elif k == "threshold":
            heads.append(book.t("threshold"))
        elif k == "system":
            heads.append(book.t("xlsx_mtf_system"))
        else:  # a registered MTF component names itself in both languages
            heads.append(component_label(k, book.loc))
    ncol = len(cols) + 1
    ws = book.sheet("xlsx_sheet_mtf", landscape=True,
                    widths=(14,) + (12,) * len(cols) + (3, 16, 12))
    _header(ws, 1, heads)
    n = len(freq)
    for i, f in enumerate(freq):
        put_num(ws, i + 2, 1, f, F2, missing=None)
        for j, k in enumerate(cols):
            put_num(ws, i + 2, 2 + j, mc[k][i], F4, missing=None)
    chart = _scatter(book.t("plot_mtf"), book.t("frequency_lpmm"), book.t("contrast"))
    chart.x_axis.scaling.min = 0
    # contrast and threshold meet low on the curve: a log axis shows the crossing
    low = [v for k in ("image_contrast", "threshold") if k in mc
           for v in (_finite(x) for x in mc[k]) if v is not None and v > 0]
    chart.y_axis.scaling.logBase = 10
    chart.y_axis.scaling.min = _log_floor(min(low, default=0.01))
    chart.y_axis.scaling.max = 1
    chart.y_axis.majorGridlines = ChartLines()
    chart.y_axis.minorGridlines = ChartLines()
    chart.y_axis.number_format = "General"
    chart.x_axis.number_format = "0"
    xref = Reference(ws, min_col=1, min_row=2, max_row=n + 1)
    for k in ("image_contrast", "threshold"):
        if k in cols:
            _add_series(chart, ws, xref, 2 + cols.index(k), n, heads[1 + cols.index(k)])
    r = plan.resolving_power_lpmm
    mcol = ncol + 2
    if r is not None and "image_contrast" in mc:
        # a two-point vertical series at R marks the crossing
        top = 1.0
        _header(ws, 1, [book.t("xlsx_r_marker"), book.t("contrast")], col=mcol)
        for i, yv in enumerate((chart.y_axis.scaling.min, top)):
            put_num(ws, 2 + i, mcol, r, F1)
            put_num(ws, 2 + i, mcol + 1, yv, F3)
        mref = Reference(ws, min_col=mcol, min_row=2, max_row=3)
        unit = "мм⁻¹" if book.loc == "ru" else "lines/mm"
        label = f"R = {book.numbers.fixed(r)} {unit}"
        _add_series(chart, ws, mref, mcol + 1, 2, label, dash="dash", color="C00000")
    _chart_below(ws, chart, n + 3)

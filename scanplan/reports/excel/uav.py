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

if TYPE_CHECKING:
    from ...project.jobs import UavJob

from .book import Book
from .cells import (
    F1,
    F2,
    F3,
    F4,
    PCT,
    SCALE,
    _finite,
    _header,
    _mark,
    number_format,
    put_num,
    put_text,
)
from .charts import (
    _add_series,
    _chart_below,
    _log_floor,
    _scatter,
)

#: The UAV sheet's rows of the ``uav_figures`` table before the maximum height: (row key,
#: the cell format).
_FIGURES = (("height_m", F1), ("height_min_m", F1), ("height_max_m", F1), ("gsd_m", F4),
            ("gsd_at_max_m", F4), ("ground_resolution_m", F4), ("l_corner_m", F4),
            ("l_at_max_m", F4), ("l_over_gsd", F2), ("resolving_power_system", F1),
            ("r_corner_lpmm", F1), ("nyquist_lpmm", F1), ("resolvable", None),
            ("sensor_limited", None), ("motion_blur_px", F2), ("max_exposure_s", "0.00000"),
            ("max_speed_ms", F1), ("tilted_corner_gsd_m", F4))


def _height_rows(book: Book, ws: Worksheet, row: int, fig: dict[str, Any]) -> int:
    """Highest flown height at the maximum, the ceiling, and the height accuracy (the
    ``uav_figures`` and ``uav_accuracy`` tables)."""
    row = book.kv(ws, row, book.f("max_flown_height_m"), fig["max_flown_height_m"].value, F1)
    for key in ("ceiling_m", "constraints_max_height_m"):
        if key in fig:
            row = book.kv(ws, row, book.f(key), fig[key].value, F1)
    acc = {r.key: r for r in book.view.tables["uav_accuracy"].rows}
    if acc:
        row = book.kv(ws, row, book.f("height_accuracy_m"), acc["height_accuracy_m"].value, F4)
        row = book.kv(ws, row, book.f("sigma_z_m"), acc["sigma_z_m"].value, F4)
        row = book.kv(ws, row, book.f("stereo_base_to_height"),
                      acc["stereo_base_to_height"].value, "0.000")
        row = book.kv(ws, row, book.f("image_measurement_px"),
                      acc["image_measurement_px"].value, F2)
        for form in ("normal_case", "instruction", "parallax"):
            row = book.kv(ws, row, f"{book.f('height_forms')}: {book.f('hf_' + form)}",
                          acc["form_" + form].value, F1)
    return row


def uav_sheet(book: Book, job: UavJob) -> None:
    """The UAV sheet: results (the ``uav_figures`` table), the limits as heights,
    recognition, flight geometry, GSD and L against the height (table and chart)."""
    ws = book.sheet("sheet_uav", landscape=True,
                    widths=(46, 16, 16, 16, 16, 16, 14, 12, 50, 50))
    _header(ws, 1, [book.f("parameter"), book.f("value")])
    row = 2
    fig = {r.key: r for r in book.view.tables["uav_figures"].rows}
    for key, fmt in _FIGURES:
        r = fig[key]
        if "not_resolvable" in r.flags:
            row = book.kv(ws, row, book.f(key), book.f("not_resolvable"))
        else:
            row = book.kv(ws, row, book.f(key), r.value, fmt)
    if "max_height_m" in fig:
        r0 = row
        row = book.kv(ws, row, book.f("max_height_m"), fig["max_height_m"].value, F1)
        row = book.kv(ws, row, book.f("binding"), book.f.cname(fig["binding"].value))
        _mark((ws.cell(r0, 2), ws.cell(r0 + 1, 2)))
        row = _height_rows(book, ws, row, fig)
    row = _limits_rows(book, ws, row)
    row = _recognition_rows(book, ws, row, job)
    row = _flight_rows(book, ws, row)
    _height_chart(book, ws, row, fig)


def _limits_rows(book: Book, ws: Worksheet, row: int) -> int:
    """The constraints as maximum flight heights, lowest first as on the PDF's page (the
    ``uav_limits`` table; binding highlighted), with each one's reason and equation."""
    rows = book.view.tables["uav_limits"].rows
    if not rows:
        return row
    row = book.section(ws, row + 1, book.f("height_limits"))
    _header(ws, row, [book.f("id"), book.f("constraint"), book.f("compares"),
                      book.f("limit_m"), book.f("max_height_m"),
                      book.f("margin_pct"), book.f("binding"),
                      book.f("max_flown_height_m"), book.f("reason"),
                      book.f("equation")])
    row += 1
    for r in rows:
        limit_m, compares, max_height_m, _, _ = r.values
        binding = "binding" in r.flags
        cells = [put_text(ws, row, 1, r.key),
                 put_text(ws, row, 2, book.f.constraint(r.key, r.fields["name"])),
                 put_text(ws, row, 3, book.f.compared(compares)),
                 put_num(ws, row, 4, limit_m, F4),
                 put_num(ws, row, 5, max_height_m, F1),
                 put_num(ws, row, 6, r.fields["margin_pct"], PCT),
                 put_text(ws, row, 7, book.f.yes_no(binding)),
                 put_num(ws, row, 8, r.fields["max_flown_m"], F1)]
        put_text(ws, row, 9, book.f.message(r.fields["reason"]), wrap=True)
        put_text(ws, row, 10, book.f.message(r.fields["equation"]), wrap=True)
        if binding:
            _mark(cells)
        row += 1
    return row


def _recognition_rows(book: Book, ws: Worksheet, row: int, job: UavJob) -> int:
    """Recognition of the norm objects (the ``uav_recognition`` table; the map's object
    highlighted)."""
    rows = book.view.tables["uav_recognition"].rows
    if not rows:
        return row
    row = book.section(ws, row + 1, book.f("recognition_objects"))
    _header(ws, row, [book.f("object_name"), book.f("object_size_m"),
                      book.f("shape"), book.f("map_scale"),
                      book.f("p_planned"), book.f("p_max"),
                      book.f("p_corner_max")])
    row += 1
    for r in rows:
        scale, size, shape, p, p_max, p_corner = r.values
        name = book.f.object_named(job.norm_set, r.fields["name"], None, scale)
        cells = [put_text(ws, row, 1, name, wrap=True),
                 put_num(ws, row, 2, size, F3),
                 put_text(ws, row, 3, book.f.shape(job.norm_set, shape)),
                 put_num(ws, row, 4, scale, SCALE),
                 put_num(ws, row, 5, p, F3),
                 put_num(ws, row, 6, p_max, F3),
                 put_num(ws, row, 7, p_corner, F3)]
        if "emph" in r.flags:  # the map's own object
            _mark(cells)
        row += 1
    return row


def _flight_rows(book: Book, ws: Worksheet, row: int) -> int:
    """The flight geometry (the ``uav_flight_figures`` table: footprint, base, line
    spacing, photos ...)."""
    rows = book.view.tables["uav_flight_figures"].rows
    if not rows:
        return row
    row = book.section(ws, row + 1, book.f("flight_geometry"))
    for r in rows:
        fmt = None if isinstance(r.value, str) else number_format(r.digits or 0)
        row = book.kv(ws, row, book.f.get(r.key, r.key), r.value, fmt)
    return row


def _height_chart(book: Book, ws: Worksheet, row: int, fig: dict[str, Any]) -> None:
    """GSD and L against the flight height (the ``uav_height_curve`` table): the table
    and its chart."""
    curve = {r.key: r.values for r in book.view.tables["uav_height_curve"].rows}
    heights = list(curve["height_m"])
    if heights:
        row = book.section(ws, row + 1, book.f("plot_height"))
        _header(ws, row, [book.f("height_m"), book.f("gsd_m"),
                          book.f("ground_resolution_m")])
        first = row + 1
        for i, hm in enumerate(heights):
            put_num(ws, first + i, 1, hm, F1, missing=None)
            put_num(ws, first + i, 2, curve["gsd_m"][i], F4, missing=None)
            put_num(ws, first + i, 3, curve["ground_resolution_m"][i], F4, missing=None)
        n = len(heights)
        chart = _scatter(book.f("plot_height"), book.f("height_m"), book.f("gsd_m") + "; L")
        chart.x_axis.scaling.min = 0
        chart.y_axis.scaling.min = 0
        chart.x_axis.majorGridlines = ChartLines()
        chart.x_axis.number_format = "0"
        chart.y_axis.number_format = "0.00"
        xref = Reference(ws, min_col=1, min_row=first, max_row=first + n - 1)
        _add_series(chart, ws, xref, 2, n, book.f("gsd_m"), first_row=first)
        _add_series(chart, ws, xref, 3, n, book.f("ground_resolution_m"), first_row=first)
        top = max((v for v in (_finite(x) for key in ("gsd_m", "ground_resolution_m")
                               for x in curve[key]) if v is not None), default=1.0)
        end = _height_markers(book, chart, ws, fig, first + n + 1, top, max(heights))
        _chart_below(ws, chart, end + 1)


def _height_markers(book: Book, chart: ScatterChart, ws: Worksheet, fig: dict[str, Any],
                    row: int, top: float, right: float) -> int:
    """Vertical lines at the planned, highest flown and maximum heights and the binding
    ground limit as a horizontal line (two-point series, their cells below the curve).
    Returns the next free row."""
    planned, highest = fig["height_m"].value, fig["height_max_m"].value
    m = " " + book.f("m")
    marks: list[tuple[str, float, float, float, float, str, str]] = []
    if planned:
        marks.append((f"{book.f('planned')}: {book.f.height(planned)}{m}",
                      planned, 0.0, planned, top, "000000", "solid"))
    low = fig["height_min_m"]
    if "over_relief" in low.flags and low.value and low.value < (planned or 0.0) - 0.05:
        marks.append((f"{book.f('lowest_flown')}: {book.f.height(low.value)}{m}",
                      low.value, 0.0, low.value, top, "7F7F7F", "sysDot"))
    if highest and highest != planned:
        marks.append((f"{book.f('highest_flown')}: {book.f.height(highest)}{m}",
                      highest, 0.0, highest, top, "7F7F7F", "dash"))
    if "max_height_m" in fig:
        top_m = fig["max_height_m"].value
        marks.append((f"{book.f('max_height_m').split(',')[0]} ({fig['binding'].value}): "
                      f"{book.f.whole(round(top_m))}{m}",
                      top_m, 0.0, top_m, top, "C00000", "sysDot"))
        flown = fig["max_flown_height_m"].value  # where the binding limit is checked
        if flown is not None and flown > top_m * (1 + 1e-9):
            marks.append((f"{book.f('max_flown_at_max')}: {book.f.whole(flown)}{m}",
                          flown, 0.0, flown, top, "C00000", "dash"))
    b = next((r for r in book.view.tables["uav_limits"].rows if "binding" in r.flags), None)
    if b is not None and b.values[0] <= top * 1.5:
        limit_m, compares = b.values[0], b.values[1]
        marks.append((f"{book.f.compared(compares)} ≤ {book.f.fixed(limit_m, 3)}{m} "
                      f"({b.key})", 0.0, limit_m, right, limit_m, "C00000", "dashDot"))
    if not marks:
        return row
    _header(ws, row, [book.f("chart_marker"), "x", "y"])
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
    """The MTF of every component at the frame centre, the image contrast and the
    threshold (the ``uav_mtf`` table), with a chart marking the resolving power R."""
    rows = {r.key: r for r in book.view.tables["uav_mtf"].rows}
    if not rows:
        return
    freq = list(rows["freq_lpmm"].values)
    mc = {key: list(r.values) for key, r in rows.items()
          if key not in ("freq_lpmm", "resolving_power")}
    comps = [key for key, r in rows.items() if "component" in r.flags]
    cols = comps + [k for k in ("system", "image_contrast", "threshold") if k in mc]
    heads = [book.f("frequency_lpmm")]
    for k in cols:
        if k == "image_contrast":
            heads.append(book.f("image_contrast"))
        elif k == "threshold":
            heads.append(book.f("threshold"))
        elif k == "system":
            heads.append(book.f("mtf_system"))
        else:  # a registered MTF component names itself in both languages
            heads.append(book.f.show(rows[k].fields["label"]))
    ncol = len(cols) + 1
    ws = book.sheet("sheet_mtf", landscape=True,
                    widths=(14,) + (12,) * len(cols) + (3, 16, 12))
    _header(ws, 1, heads)
    n = len(freq)
    for i, f in enumerate(freq):
        put_num(ws, i + 2, 1, f, F2, missing=None)
        for j, k in enumerate(cols):
            put_num(ws, i + 2, 2 + j, mc[k][i], F4, missing=None)
    chart = _scatter(book.f("plot_mtf"), book.f("frequency_lpmm"), book.f("contrast"))
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
    r = rows["resolving_power"].value if "resolving_power" in rows else None
    mcol = ncol + 2
    if r is not None and "image_contrast" in mc:
        # a two-point vertical series at R marks the crossing
        top = 1.0
        _header(ws, 1, [book.f("r_marker"), book.f("contrast")], col=mcol)
        for i, yv in enumerate((chart.y_axis.scaling.min, top)):
            put_num(ws, 2 + i, mcol, r, F1)
            put_num(ws, 2 + i, mcol + 1, yv, F3)
        mref = Reference(ws, min_col=mcol, min_row=2, max_row=3)
        label = f"R = {book.f.fixed(r)} {book.f('lpmm')}"
        _add_series(chart, ws, mref, mcol + 1, 2, label, dash="dash", color="C00000")
    _chart_below(ws, chart, n + 3)

"""The film sheets: every constraint at every photo scale, and the photo-scale sweep with its
chart."""

from __future__ import annotations

from typing import TYPE_CHECKING

from openpyxl.chart import Reference, ScatterChart
from openpyxl.chart.axis import ChartLines
from openpyxl.chart.label import DataLabelList
from openpyxl.chart.shapes import GraphicalProperties
from openpyxl.worksheet.worksheet import Worksheet

if TYPE_CHECKING:
    from ...project.jobs import ScanJob
    from ...project.spec import PlanResult

from .book import Book
from .cells import (
    F2,
    PCT,
    SCALE,
    SCALE_RU,
    UM,
    _finite,
    _header,
    _mark,
    put_num,
    put_text,
)
from .charts import (
    _add_series,
    _chart_below,
    _log_ceil,
    _log_floor,
    _scale_ticks,
    _scatter,
)


def constraints_sheet(book: Book) -> None:
    """Every constraint at every photo scale, one row each (the view's film table, with
    each constraint's margins, reason and equation); the binding ones marked."""
    ws = book.sheet("sheet_constraints", landscape=True,
                    widths=(14, 9, 8, 34, 12, 12, 12, 12, 60, 60))
    _header(ws, 1, [book.f("photo_scale"), book.f("photo_to_map"), book.f("id"),
                    book.f("constraint"), book.f("pixel_um"), book.f("margin_um"),
                    book.f("margin_pct"), book.f("binding"), book.f("reason"),
                    book.f("equation")])
    film = book.view.tables["film_constraints"]
    ratios = film.row("photo_to_map").values
    constraints = [r for r in film.rows if "constraint" in r.flags]
    row = 2
    for i, column in enumerate(film.columns):
        for r in constraints:
            d = r.details[i]
            cells = [put_num(ws, row, 1, column.value, SCALE),
                     put_num(ws, row, 2, ratios[i], F2),
                     put_text(ws, row, 3, r.key),
                     put_text(ws, row, 4, book.f.constraint(r.key, d["name"])),
                     put_num(ws, row, 5, r.values[i], UM),
                     put_num(ws, row, 6, d["margin_um"], UM),
                     put_num(ws, row, 7, d["margin_pct"], PCT),
                     put_text(ws, row, 8, book.f.yes_no(r.flagged(i, "binding")))]
            put_text(ws, row, 9, book.f.message(d["reason"]), wrap=True)
            put_text(ws, row, 10, book.f.message(d["equation"]), wrap=True)
            if r.flagged(i, "binding"):
                _mark(cells)
            row += 1
    if row > 2:
        ws.auto_filter.ref = f"A1:J{row - 1}"


def sweep_sheet(book: Book, job: ScanJob, spec: PlanResult | None = None) -> None:
    """The dense photo-scale sweep (the ``film_sweep`` table) with its chart, the
    candidate photo scales marked (the recommended one: the specification's)."""
    tables = book.view.tables
    rows = {r.key: r for r in tables["film_sweep"].rows}
    sweep = {key: list(r.values) for key, r in rows.items()}
    scales = sweep["photo_scale"]
    ids = [key for key, r in rows.items() if "constraint" in r.flags]
    candidates = [c.value for c in tables["film_constraints"].columns]
    ws = book.sheet("sweep", landscape=True,
                    widths=(14,) + (16,) * len(ids) + (16, 30))
    heads = [book.f("photo_scale")] + [f"{book.f.cname(cid)}, {book.f('um')}" for cid in ids]
    _header(ws, 1, [*heads, book.f("scan_pixel_um"), book.f("binding")])
    n = len(scales)
    pixel_col = len(ids) + 2
    binding = sweep["binding"]
    scan_px = sweep["scan_pixel_um"]
    for i in range(n):
        row = i + 2
        put_num(ws, row, 1, scales[i], SCALE, missing=None)
        for j, cid in enumerate(ids):
            cell = put_num(ws, row, 2 + j, sweep[cid][i], UM, missing=None)
            if i < len(binding) and binding[i] == cid:
                _mark((cell,))
        put_num(ws, row, pixel_col, scan_px[i] if i < len(scan_px) else None, UM,
                missing=None)
        if i < len(binding):
            put_text(ws, row, pixel_col + 1, binding[i])
    if n == 0:
        return
    chart = _scatter(book.f("plot_constraints"), book.f("photo_scale"), book.f("pixel_um"))
    chart.x_axis.number_format = SCALE_RU if book.loc == "ru" else SCALE
    # a linear axis whose ticks fall on every candidate photo scale (a log axis would
    # label only 1:1000, 1:10000, ...)
    lo, hi, step = _scale_ticks(candidates,
                                _finite(scales[0]) or 0.0, _finite(scales[-1]) or 1.0)
    chart.x_axis.scaling.min = lo
    chart.x_axis.scaling.max = hi
    chart.x_axis.majorUnit = step
    chart.x_axis.majorGridlines = ChartLines()
    chart.y_axis.number_format = "General"
    # pixels span a decade or more: a log axis shows the deciding (smallest) one clearly
    values = [v for cid in ids for v in (_finite(x) for x in sweep[cid]) if v]
    chart.y_axis.scaling.logBase = 10
    chart.y_axis.scaling.min = _log_floor(min(values, default=1.0))
    chart.y_axis.scaling.max = _log_ceil(max(values, default=100.0))
    chart.y_axis.majorGridlines = ChartLines()
    chart.y_axis.minorGridlines = ChartLines()
    xref = Reference(ws, min_col=1, min_row=2, max_row=n + 1)
    for j, cid in enumerate(ids):
        _add_series(chart, ws, xref, 2 + j, n, book.f.cname(cid))
    _add_series(chart, ws, xref, pixel_col, n, book.f("scan_pixel_um"), width_emu=44450,
                dash="dash", color="000000")
    recommended = None
    if tables.has("spec_film") and "photo_scale" in tables["spec_film"].keys():
        recommended = tables["spec_film"].row("photo_scale").value
    _candidate_markers(book, chart, ws, n + 3, recommended)
    _chart_below(ws, chart, n + 1 + 2 + len(candidates) + 2)


def _candidate_markers(book: Book, chart: ScatterChart, ws: Worksheet, first_row: int,
                       recommended: float | None) -> None:
    """One labelled point per candidate photo scale at its scan pixel: the chart names
    every candidate scale (a log axis labels only 1:1000, 1:10000, ...); the
    recommended one (the smallest feasible scale) stands out."""
    film = book.view.tables["film_constraints"]
    pixels, bindings = film.row("scan_pixel_um").values, film.row("binding").values
    _header(ws, first_row, [book.f("photo_scale"), book.f("scan_pixel_um"),
                            book.f("binding")])
    for i, column in enumerate(film.columns):
        row = first_row + 1 + i
        scale = column.value
        put_num(ws, row, 1, scale, SCALE)
        put_num(ws, row, 2, pixels[i], UM)
        put_text(ws, row, 3, bindings[i])
        label = book.f.scale(scale)
        if scale == recommended:
            label += " (" + book.f("recommended") + ")"
        xref = Reference(ws, min_col=1, min_row=row, max_row=row)
        series = _add_series(chart, ws, xref, 2, 1, label, first_row=row)
        series.graphicalProperties.line.noFill = True
        series.marker.symbol = "diamond" if scale == recommended else "circle"
        series.marker.size = 11 if scale == recommended else 7
        color = "C00000" if scale == recommended else "000000"
        series.marker.graphicalProperties = GraphicalProperties(solidFill=color)
        series.marker.graphicalProperties.line.solidFill = color
        series.dLbls = DataLabelList()
        series.dLbls.showSerName = True
        series.dLbls.showVal = False
        series.dLbls.showCatName = False
        series.dLbls.showLegendKey = False
        series.dLbls.position = "t"

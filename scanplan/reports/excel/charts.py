"""The workbook's native charts: scatter charts, log-axis ticks, placement under a table."""

from __future__ import annotations

import math
from collections.abc import Sequence

from openpyxl.chart import Reference, ScatterChart, Series
from openpyxl.utils import get_column_letter
from openpyxl.worksheet.pagebreak import Break
from openpyxl.worksheet.worksheet import Worksheet

from .cells import (
    _clean_text,
)


def _scatter(title: str, x_title: str, y_title: str) -> ScatterChart:
    chart = ScatterChart()
    chart.title = title
    chart.style = 2
    chart.scatterStyle = "line"
    chart.x_axis.title = x_title
    chart.y_axis.title = y_title
    chart.x_axis.axPos = "b"
    chart.x_axis.delete = False  # newer Excel hides axes openpyxl leaves undecided
    chart.y_axis.delete = False
    chart.legend.position = "b"
    chart.width = 24
    chart.height = 13
    return chart


def _scale_ticks(candidates: Sequence[float], lo: float, hi: float) -> tuple[float, float,
                                                                            float]:
    """(min, max, major unit) of a photo-scale axis with a tick on every candidate scale:
    the largest round step that divides them all, at most 20 ticks over the range."""
    for step in (10000.0, 5000.0, 2500.0, 2000.0, 1000.0, 500.0, 250.0, 100.0):
        if all(float(c) % step == 0 for c in candidates) and (hi - lo) / step <= 20:
            break
    else:
        step = max((hi - lo) / 10, 1.0)
    return math.floor(lo / step) * step, math.ceil(hi / step) * step, step


def _log_floor(x: float) -> float:
    """The power of ten at or below ``x`` (a log axis's minimum)."""
    return float(10 ** math.floor(math.log10(x))) if x > 0 else 0.01


def _log_ceil(x: float) -> float:
    """The power of ten at or above ``x`` (a log axis's maximum)."""
    return float(10 ** math.ceil(math.log10(x))) if x > 0 else 1.0


_CM_PER_CHAR = 0.2  # a column width unit (one "0" of Calibri 11) on paper [cm], about



def _sheet_width_cm(ws: Worksheet) -> float:
    """The printed width of the sheet's used columns at 100 % [cm]."""
    widths = [ws.column_dimensions[get_column_letter(c)].width or 8.43
              for c in range(1, ws.max_column + 1)]
    return sum(widths) * _CM_PER_CHAR


def _chart_below(ws: Worksheet, chart: ScatterChart, row: int) -> None:
    """Put ``chart`` below the data from ``row`` on, starting a printed page, sized to the
    sheet's printed width (the page is fitted to that width) and short enough to fit the
    page's height: a chart is never split across pages nor shrunk to a stamp."""
    ws.row_breaks.append(Break(id=row - 1))
    sheet_cm = max(_sheet_width_cm(ws), 24.0)
    landscape = ws.page_setup.orientation == "landscape"
    page_ratio = (17.0 / 27.7) if landscape else (26.0 / 19.0)  # printable height/width
    chart.width = 0.95 * sheet_cm
    chart.height = min(0.55 * chart.width, 0.8 * sheet_cm * page_ratio)
    ws.add_chart(chart, f"A{row}")


def _add_series(chart: ScatterChart, ws: Worksheet, xref: Reference, col: int, n: int,
                title: str, *, first_row: int = 2, width_emu: int = 22225,
                dash: str | None = None, color: str | None = None) -> Series:
    yref = Reference(ws, min_col=col, min_row=first_row, max_row=first_row + n - 1)
    series = Series(yref, xref, title=_clean_text(title))
    series.marker.symbol = "none"
    series.smooth = False
    series.graphicalProperties.line.width = width_emu
    if dash:
        series.graphicalProperties.line.dashStyle = dash
    if color:
        series.graphicalProperties.line.solidFill = color
    chart.series.append(series)
    return series

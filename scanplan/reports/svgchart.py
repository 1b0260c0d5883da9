"""Line charts written as SVG text directly, for the PDF report's plots (no matplotlib).

A :class:`Chart` is one or more stacked :class:`Panel` s sharing the x axis; a panel has a
linear or logarithmic x and y axis, and takes polylines, circle markers, vertical and
horizontal reference lines, step bands (the range between a lowest and a highest value),
and text annotations. The legend goes below the plot area, its entries in columns, so that
it never covers a curve.

The layout measures no arbitrary text. Tick labels are digits, separators and signs, whose
advance widths in the report's font (DejaVu Sans, bundled as ``Scanplan Sans``,
templates/fonts) are held in a small table (:data:`.chartscale.ADVANCE`, checked against
the font by the tests): the left margin is the widest y tick label, x tick labels never collide. The
legend's columns are sized by a generous estimate of the labels' widths
(:func:`.chartscale.estimate_width_pt`, checked in the tests to be at least the real width of every
label of the report's plots).

The output is deterministic (same input, same bytes): coordinates rounded to 0.01 pt, no
dates, no random identifiers. Sizes are in points (1/72 in); the figure is 6.6 in wide as
before, and the PDF scales it to the text width.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Iterable, Sequence
from itertools import pairwise
from typing import Any

from .chartscale import (
    ADVANCE,
    ASCENT_EM,
    CAP_EM,
    DESCENT_EM,
    estimate_width_pt,
    log_ticks,
    nice_ticks,
    text_width_pt,
)
from .formatter import formatter

__all__ = ["ADVANCE", "Chart", "Panel", "estimate_width_pt", "log_ticks", "nice_ticks",
           "text_width_pt"]

FONT_FAMILY = "Scanplan Sans"
WIDTH_PT = 475.2  # 6.6 in, as the figures were

TICK_PT, LABEL_PT, LEGEND_PT = 7.0, 8.0, 7.0
TICK_LEN_PT, TICK_PAD_PT = 3.5, 3.5
GRID_COLOUR, GRID_WIDTH_PT = "#d8d8d8", 0.5
SPINE_WIDTH_PT = 0.8
_PAD_PT = 4.0  # between the figure's edge and its outermost text
_DASHES = {"-": None, "solid": None, "--": (3.7, 1.6), ":": (1.0, 1.65),
           "-.": (6.4, 1.6, 1.0, 1.6)}  # in line widths (as matplotlib scales them)


def escape(text: str) -> str:
    """``text`` as XML character data (``&``, ``<``, ``>`` escaped; xml.sax.saxutils would
    import urllib and ssl, 30 ms)."""
    return text.replace("&", "&amp;").replace("<", "&lt;").replace(">", "&gt;")


def _n(v: float) -> str:
    """A coordinate with at most two decimals, no trailing zeros (deterministic)."""
    text = f"{v:.2f}".rstrip("0").rstrip(".")
    return "0" if text in ("-0", "") else text


def _finite(v: Any) -> bool:
    return v is not None and isinstance(v, (int, float)) and math.isfinite(v)


class _Axis:
    """An axis: its scale, fixed limits and ticks if any, title, and the data drawn on it
    (a plain class: a dataclass is built when the module is imported)."""

    def __init__(self, scale: str = "linear", integer: bool = False, label: str = "") -> None:
        self.scale, self.integer, self.label = scale, integer, label
        self.lo: float | None = None
        self.hi: float | None = None
        self.ticks: list[float] | None = None
        self.fmt: Callable[[float], str] | None = None  # tick labels (default Numbers.tick)
        self.data: list[float] = []

    def ok(self, v: Any) -> bool:
        """Whether ``v`` can be drawn on this axis (finite; positive on a log axis)."""
        return _finite(v) and (self.scale != "log" or v > 0)

    def add(self, values: Iterable[Any]) -> None:
        self.data.extend(float(v) for v in values if self.ok(v))

    def limits(self) -> tuple[float, float]:
        """The axis range: the given limits, else the data with a 5 % margin."""
        log = self.scale == "log"
        data = self.data or ([1.0, 10.0] if log else [0.0, 1.0])
        dlo, dhi = min(data), max(data)
        if log:
            dlo, dhi = math.log10(dlo), math.log10(dhi)
        if dhi == dlo:
            dlo, dhi = dlo - 0.5, dhi + 0.5
        pad = 0.05 * (dhi - dlo)
        lo, hi = dlo - pad, dhi + pad
        if log:
            lo, hi = 10.0 ** lo, 10.0 ** hi
        lo = self.lo if self.lo is not None else lo
        hi = self.hi if self.hi is not None else hi
        if hi <= lo:
            hi = lo * 10 if log else lo + 1
        return lo, hi


class _Style:
    """A line's stroke: colour, width [pt], dash pattern [line widths], opacity."""

    __slots__ = ("alpha", "colour", "dash", "width")

    def __init__(self, colour: str, width: float, dash: tuple[float, ...] | None = None,
                 alpha: float = 1.0) -> None:
        self.colour, self.width, self.dash, self.alpha = colour, width, dash, alpha

    def attrs(self) -> str:
        out = f'stroke="{self.colour}" stroke-width="{_n(self.width)}"'
        if self.dash:
            out += ' stroke-dasharray="' + " ".join(_n(d * self.width) for d in self.dash) + '"'
        if self.alpha < 1:
            out += f' stroke-opacity="{_n(self.alpha)}"'
        return out


def _dash(style: str | Sequence[float] | None) -> tuple[float, ...] | None:
    if style is None or isinstance(style, str):
        return _DASHES[style or "-"]
    return tuple(float(d) for d in style)


class Panel:
    """One plot area with its x and y axes; draw on it, then render the :class:`Chart`.

    The methods follow matplotlib's names where they do the same thing. Colours are SVG
    colours (``"#1f77b4"``); widths are in points; a dash is ``"-"``, ``"--"``, ``":"``,
    ``"-."`` or a pattern in line widths (``(5, 2, 1, 2)``), as matplotlib scales them.
    """

    def __init__(self, weight: float = 1.0) -> None:
        self.weight = weight
        self.x, self.y = _Axis(), _Axis()
        self.items: list[tuple[Any, ...]] = []
        self.legend: list[tuple[str, Any, str]] = []

    # -- axes ------------------------------------------------------------------------
    def set_xscale(self, scale: str, *, integer: bool = False) -> None:
        """``"linear"`` or ``"log"``; ``integer``: whole-number ticks only."""
        self.x.scale, self.x.integer = scale, integer

    def set_yscale(self, scale: str) -> None:
        """``"linear"`` or ``"log"``."""
        self.y.scale = scale

    def set_xlim(self, left: float | None = None, right: float | None = None) -> None:
        """Fix the x range (either end; the other follows the data)."""
        self.x.lo, self.x.hi = left, right

    def set_ylim(self, bottom: float | None = None, top: float | None = None) -> None:
        """Fix the y range (either end; the other follows the data)."""
        self.y.lo, self.y.hi = bottom, top

    def set_xticks(self, ticks: Sequence[float],
                   fmt: Callable[[float], str] | None = None) -> None:
        """These x ticks (those within the range; a label that would collide is left out),
        labelled by ``fmt`` when given (else as numbers, :meth:`Numbers.tick`)."""
        self.x.ticks = [float(v) for v in ticks]
        self.x.fmt = fmt

    def set_yticks(self, ticks: Sequence[float]) -> None:
        """These y ticks (those within the range)."""
        self.y.ticks = [float(v) for v in ticks]

    def set_xlabel(self, text: str) -> None:
        """The x axis title (drawn under the lowest panel)."""
        self.x.label = text

    def set_ylabel(self, text: str) -> None:
        """The y axis title (rotated, left of the tick labels)."""
        self.y.label = text

    # -- data ------------------------------------------------------------------------
    def plot(self, xs: Sequence[Any], ys: Sequence[Any], *, colour: str, width: float = 1.0,
             dash: str | Sequence[float] | None = None, alpha: float = 1.0,
             label: str | None = None) -> None:
        """A polyline through (xs, ys); a missing or non-finite value (or a non-positive
        one on a log axis) breaks the line."""
        xs, ys = list(xs), list(ys)
        style = _Style(colour, width, _dash(dash), alpha)
        self.items.append(("line", xs, ys, style))
        self._extend(xs, ys)
        if label is not None:
            self.legend.append(("line", style, label))

    def markers(self, xs: Sequence[float], ys: Sequence[float], *, colour: str,
                size: float = 4.5) -> None:
        """Filled circles of diameter ``size`` [pt] at (xs, ys)."""
        xs, ys = list(xs), list(ys)
        self.items.append(("markers", xs, ys, colour, size))
        self._extend(xs, ys)

    def axvline(self, x: float, *, colour: str, width: float = 1.0,
                dash: str | Sequence[float] | None = None, label: str | None = None) -> None:
        """A vertical line across the panel at ``x``."""
        style = _Style(colour, width, _dash(dash))
        self.items.append(("vline", x, style))
        self.x.add([x])
        if label is not None:
            self.legend.append(("line", style, label))

    def axhline(self, y: float, *, colour: str, width: float = 1.0,
                dash: str | Sequence[float] | None = None, label: str | None = None) -> None:
        """A horizontal line across the panel at ``y``."""
        style = _Style(colour, width, _dash(dash))
        self.items.append(("hline", y, style))
        self.y.add([y])
        if label is not None:
            self.legend.append(("line", style, label))

    def band(self, xs: Sequence[float], lo: Sequence[float], hi: Sequence[float], *,
             colour: str, alpha: float = 0.35, label: str | None = None) -> None:
        """The range lo … hi at each x as steps changing halfway between the xs (filled,
        ``alpha`` opaque), with its edges drawn as steps (0.9 pt the top, 0.6 pt the
        bottom)."""
        xs, lo, hi = list(xs), list(lo), list(hi)
        self.items.append(("band", xs, lo, hi, colour, alpha))
        self._extend(xs, lo)
        self._extend(xs, hi)
        if label is not None:
            self.legend.append(("patch", (colour, alpha), label))

    def annotate(self, text: str, x: float, y: float, *, dx: float = 0.0, dy: float = 0.0,
                 y_axes: bool = False, anchor: str = "start", middle: bool = False,
                 rotation: float = 0.0, size: float = 7.0, colour: str = "#000000") -> None:
        """``text`` with its baseline start (``anchor``: start / middle / end) at the data
        point (x, y) moved by (dx, dy) [pt, y downwards].

        ``y_axes``: y is a fraction of the panel's height (0 bottom, 1 top) instead of
        data. ``middle``: the text is centred on the point across its baseline.
        ``rotation`` [degrees] turns it anticlockwise (90: read upwards).
        """
        self.items.append(("text", text, x, y, dx, dy, y_axes, anchor, middle, rotation,
                           size, colour))

    def y_fraction(self, y: float) -> float:
        """Where ``y`` lies on the y axis as drawn so far: 0 at the bottom, 1 at the top
        (to place a label clear of the curves)."""
        lo, hi = self.y.limits()
        if self.y.scale == "log":
            lo, hi, y = math.log10(lo), math.log10(hi), math.log10(y)
        return (y - lo) / (hi - lo)

    def _extend(self, xs: Sequence[Any], ys: Sequence[Any]) -> None:
        pts = [(a, b) for a, b in zip(xs, ys, strict=False)
               if self.x.ok(a) and self.y.ok(b)]
        self.x.add(a for a, _ in pts)
        self.y.add(b for _, b in pts)


class _Frame:
    """A panel placed on the figure: data → points."""

    def __init__(self, panel: Panel, xlim: tuple[float, float], left: float, top: float,
                 width: float, height: float) -> None:
        self.p, self.left, self.top, self.w, self.h = panel, left, top, width, height
        self.xlog, self.ylog = panel.x.scale == "log", panel.y.scale == "log"
        self.x0, self.x1 = self._t(xlim, self.xlog)
        self.ylim = panel.y.limits()
        self.y0, self.y1 = self._t(self.ylim, self.ylog)

    @staticmethod
    def _t(lim: tuple[float, float], log: bool) -> tuple[float, float]:
        return (math.log10(lim[0]), math.log10(lim[1])) if log else lim

    def px(self, v: float) -> float:
        v = math.log10(v) if self.xlog else v
        return self.left + (v - self.x0) / (self.x1 - self.x0) * self.w

    def py(self, v: float) -> float:
        v = math.log10(v) if self.ylog else v
        return self.top + self.h - (v - self.y0) / (self.y1 - self.y0) * self.h

    def inside_x(self, v: float) -> bool:
        return self.left - 0.01 <= self.px(v) <= self.left + self.w + 0.01

    def inside_y(self, v: float) -> bool:
        return self.top - 0.01 <= self.py(v) <= self.top + self.h + 0.01


def _text(x: float, y: float, text: str, size: float, *, anchor: str = "start",
          rotation: float = 0.0, colour: str | None = None) -> str:
    fill = f' fill="{colour}"' if colour and colour != "#000000" else ""
    a = "" if anchor == "start" else f' text-anchor="{anchor}"'
    if rotation:
        return (f'<text transform="translate({_n(x)} {_n(y)}) rotate({_n(-rotation)})" '
                f'font-size="{_n(size)}"{a}{fill}>{escape(text)}</text>')
    return (f'<text x="{_n(x)}" y="{_n(y)}" font-size="{_n(size)}"{a}{fill}>'
            f"{escape(text)}</text>")


def _wrap(label: str, length_pt: float) -> list[str]:
    """An axis title in one line, or two (split at the space nearest its middle) when it
    may be longer than ``length_pt``; none when empty."""
    if not label:
        return []
    if estimate_width_pt(label, LABEL_PT) <= length_pt - 4.0 or " " not in label:
        return [label]
    spaces = [i for i, c in enumerate(label) if c == " "]
    cut = min(spaces, key=lambda i: abs(2 * i - len(label)))
    return [label[:cut], label[cut + 1:]]


def _segments(xs: Sequence[Any], ys: Sequence[Any], f: _Frame) -> list[list[tuple]]:
    """Runs of drawable points: a missing value breaks the line (as matplotlib does)."""
    runs: list[list[tuple]] = [[]]
    for a, b in zip(xs, ys, strict=False):
        if f.p.x.ok(a) and f.p.y.ok(b):
            runs[-1].append((f.px(a), f.py(b)))
        elif runs[-1]:
            runs.append([])
    return [r for r in runs if r]


def _polyline(pts: Sequence[tuple[float, float]], attrs: str) -> str:
    coords = " ".join(f"{_n(x)},{_n(y)}" for x, y in pts)
    return f'<polyline points="{coords}" fill="none" {attrs}/>'


def _steps_mid(xs: Sequence[float], ys: Sequence[float]) -> tuple[list, list]:
    """A step line: each value held from halfway to the previous x to halfway to the next
    (the first and last a half step past their x, a lone one ±0.5)."""
    sx, sy = [], []
    n = len(xs)
    for i, (x, y) in enumerate(zip(xs, ys, strict=True)):
        before = (x - xs[i - 1]) / 2 if i > 0 else (xs[1] - x) / 2 if n > 1 else 0.5
        after = (xs[i + 1] - x) / 2 if i < n - 1 else before
        sx += [x - before, x + after]
        sy += [y, y]
    return sx, sy


class Chart:
    """A figure of stacked panels sharing the x axis, with one legend below them.

    Parameters
    ----------
    locale : {"en", "ru"}
        The tick labels' number format (:meth:`scanplan.reports.formatter.Formatter.tick`).
    weights : sequence of float
        One panel per weight, top to bottom, heights in that ratio.
    plot_height_pt : float
        The height [pt] of all the panels together (their gaps excluded).
    width_pt : float
        The figure's width [pt].

    Examples
    --------
    >>> chart = Chart("ru")
    >>> ax = chart.panels[0]
    >>> ax.plot([0, 1, 2], [0, 1, 4], colour="#1f77b4", label="y = x²")
    >>> ax.set_xlabel("x")
    >>> svg = chart.svg()
    >>> svg.startswith("<?xml") and "y = x²" in svg
    True
    """

    def __init__(self, locale: str = "en", weights: Sequence[float] = (1.0,), *,
                 plot_height_pt: float = 140.0, width_pt: float = WIDTH_PT) -> None:
        self.numbers = formatter(locale)  # its tick labels in the report's convention
        self.panels = [Panel(w) for w in weights]
        self.plot_height_pt, self.width_pt = plot_height_pt, width_pt

    # -- ticks -----------------------------------------------------------------------
    def _ticks(self, axis: _Axis, lim: tuple[float, float], length: float,
               vertical: bool) -> list[tuple[float, str]]:
        lo, hi = lim
        if axis.ticks is not None:
            values = axis.ticks
        elif axis.scale == "log":
            values = log_ticks(lo, hi)
        else:
            values = []
            for bins in range(9, 0, -1):
                values = nice_ticks(lo, hi, bins, integer=axis.integer)
                if len(values) < 2:
                    break
                gap = (values[1] - values[0]) / (hi - lo) * length
                need = (2.2 * TICK_PT if vertical else 6.0 + max(
                    text_width_pt(self.numbers.tick(v), TICK_PT) for v in values))
                if gap >= need:
                    break
        label = axis.fmt or self.numbers.tick
        inside = [v for v in values
                  if axis.ok(v) and lo - 1e-9 * abs(hi - lo) <= v <= hi + 1e-9 * abs(hi - lo)]
        if axis.ticks is None and axis.scale == "log" and len(inside) > 1:
            # too crowded for 1-2-5: the decades only
            span = math.log10(hi) - math.log10(lo)
            closest = min(math.log10(b) - math.log10(a) for a, b in pairwise(inside))
            if closest / span * length < (2.2 * TICK_PT if vertical else 40.0):
                decades = [v for v in inside if abs(math.log10(v) - round(math.log10(v))) < 1e-9]
                inside = decades or inside[:1]
        return [(v, label(v)) for v in inside]

    # -- legend ----------------------------------------------------------------------
    def _legend_layout(self, entries: list, width: float) -> list[float]:
        """The legend's column widths [pt]: as many columns as fit ``width`` (filled
        top to bottom, then left to right), each as wide as its widest entry."""
        if not entries:
            return []
        cells = [38.0 + estimate_width_pt(label, LEGEND_PT) for _, _, label in entries]
        for cols in range(len(entries), 1, -1):
            rows = math.ceil(len(entries) / cols)
            widths = [max(cells[c * rows:(c + 1) * rows], default=0.0) for c in range(cols)]
            if 0.0 not in widths and sum(widths) <= width:
                return widths
        return [width]

    def _legend_place(self, entries: list, left: float) -> tuple[list[float], float]:
        """(column widths, left edge) [pt] of the legend under the plot area: aligned with
        the plot, or from the figure's left edge when that gives more columns."""
        col_w = self._legend_layout(entries, self.width_pt - left - _PAD_PT)
        wider = self._legend_layout(entries, self.width_pt - 2 * _PAD_PT)
        return (wider, _PAD_PT) if len(wider) > len(col_w) else (col_w, left)

    # -- the figure ------------------------------------------------------------------
    def _x_layout(self, xaxis: _Axis, xlim: tuple[float, float],
                  left: float) -> tuple[float, list[tuple[float, str]]]:
        """(plot width [pt], x ticks): the right margin holds half the last tick label."""
        right = 12.0
        width = self.width_pt - left - right
        xticks = self._ticks(xaxis, xlim, width, False)
        if xticks:
            probe = _Frame(self.panels[-1], xlim, left, 0, width, 1)
            v, s = xticks[-1]
            overhang = probe.px(v) + text_width_pt(s, TICK_PT) / 2 + 2 - (left + width)
            if overhang > 0:
                width -= overhang
                xticks = self._ticks(xaxis, xlim, width, False)
        return width, xticks

    def svg(self) -> str:
        """The figure as a standalone SVG document (deterministic)."""
        panels = self.panels
        bottom_panel = panels[-1]
        xaxis = _Axis(scale=bottom_panel.x.scale, integer=bottom_panel.x.integer,
                      label=bottom_panel.x.label)
        for p in panels:
            xaxis.data += p.x.data
            xaxis.lo = p.x.lo if p.x.lo is not None else xaxis.lo
            xaxis.hi = p.x.hi if p.x.hi is not None else xaxis.hi
            xaxis.ticks = p.x.ticks if p.x.ticks is not None else xaxis.ticks
            xaxis.fmt = p.x.fmt or xaxis.fmt
        xlim = xaxis.limits()
        gap_pt = 8.0
        total = sum(p.weight for p in panels)
        heights = [self.plot_height_pt * p.weight / total for p in panels]
        yticks = [self._ticks(p.y, p.y.limits(), h, True)
                  for p, h in zip(panels, heights, strict=True)]
        widest = max((text_width_pt(s, TICK_PT) for ts in yticks for _, s in ts), default=0)
        ylabels = [_wrap(p.y.label, h) for p, h in zip(panels, heights, strict=True)]
        nlines = max(len(lines) for lines in ylabels)
        ylabel_x = _PAD_PT + ASCENT_EM * LABEL_PT
        line_pt = 1.15 * LABEL_PT
        left = (ylabel_x + (nlines - 1) * line_pt + DESCENT_EM * LABEL_PT + 4.0
                if nlines else _PAD_PT)
        left += widest + TICK_PAD_PT + TICK_LEN_PT
        width, xticks = self._x_layout(xaxis, xlim, left)
        top = 6.0
        frames = []
        for p, h in zip(panels, heights, strict=True):
            frames.append(_Frame(p, xlim, left, top, width, h))
            top += h + gap_pt
        plot_bottom = frames[-1].top + frames[-1].h
        xtick_base = plot_bottom + TICK_LEN_PT + TICK_PAD_PT + CAP_EM * TICK_PT
        y = xtick_base + DESCENT_EM * TICK_PT if xticks else plot_bottom + TICK_LEN_PT
        xlabel_base = None
        if xaxis.label:
            xlabel_base = y + 3.0 + ASCENT_EM * LABEL_PT
            y = xlabel_base + DESCENT_EM * LABEL_PT
        entries = [e for p in panels for e in p.legend]
        col_w, legend_left = self._legend_place(entries, left)
        rows = math.ceil(len(entries) / len(col_w)) if col_w else 0
        row_h = LEGEND_PT * 1.45
        legend_top = y + 5.0
        height = (legend_top + rows * row_h if rows else y) + _PAD_PT

        out = [
            '<?xml version="1.0" encoding="utf-8" standalone="no"?>',
            f'<svg xmlns="http://www.w3.org/2000/svg" version="1.1" '
            f'width="{_n(self.width_pt)}pt" height="{_n(height)}pt" '
            f'viewBox="0 0 {_n(self.width_pt)} {_n(height)}">',
            f'<rect width="{_n(self.width_pt)}" height="{_n(height)}" fill="#ffffff"/>',
            f'<g font-family="\'{FONT_FAMILY}\'" stroke-linejoin="round" '
            f'stroke-linecap="butt">',
        ]
        for i, (f, yt) in enumerate(zip(frames, yticks, strict=True)):
            out += self._panel_svg(f, i, yt, xticks, labels=f is frames[-1])
        if xlabel_base is not None:
            out.append(_text(left + width / 2, xlabel_base, xaxis.label, LABEL_PT,
                             anchor="middle"))
        for f, lines in zip(frames, ylabels, strict=True):
            x = ylabel_x + (nlines - len(lines)) * line_pt  # next to the tick labels
            for k, line in enumerate(lines):
                out.append(_text(x + k * line_pt, f.top + f.h / 2, line, LABEL_PT,
                                 anchor="middle", rotation=90))
        out += self._legend_svg(entries, col_w, rows, legend_left, legend_top, row_h)
        out += ["</g>", "</svg>", ""]
        return "\n".join(out)

    def _panel_svg(self, f: _Frame, index: int, yticks: list[tuple[float, str]],
                   xticks: list[tuple[float, str]], *, labels: bool) -> list[str]:
        left, top, w, h = f.left, f.top, f.w, f.h
        bottom, right = top + h, left + w
        out = [f'<g id="panel{index}">']
        grid = [f"M{_n(f.px(v))} {_n(top)}V{_n(bottom)}" for v, _ in xticks]
        grid += [f"M{_n(left)} {_n(f.py(v))}H{_n(right)}" for v, _ in yticks]
        if grid:
            out.append(f'<path d="{"".join(grid)}" fill="none" stroke="{GRID_COLOUR}" '
                       f'stroke-width="{_n(GRID_WIDTH_PT)}"/>')
        clip = f"clip{index}"
        out.append(f'<clipPath id="{clip}"><rect x="{_n(left)}" y="{_n(top)}" '
                   f'width="{_n(w)}" height="{_n(h)}"/></clipPath>')
        out.append(f'<g clip-path="url(#{clip})">')
        texts = []
        for item in f.p.items:
            kind = item[0]
            if kind == "line":
                _, xs, ys, style = item
                out += [_polyline(run, style.attrs()) for run in _segments(xs, ys, f)]
            elif kind == "markers":
                _, xs, ys, colour, size = item
                out += [f'<circle cx="{_n(x)}" cy="{_n(y)}" r="{_n(size / 2)}" '
                        f'fill="{colour}"/>' for run in _segments(xs, ys, f) for x, y in run]
            elif kind == "vline" and f.p.x.ok(item[1]) and f.inside_x(item[1]):
                x = f.px(item[1])
                out.append(f'<path d="M{_n(x)} {_n(top)}V{_n(bottom)}" fill="none" '
                           f"{item[2].attrs()}/>")
            elif kind == "hline" and f.p.y.ok(item[1]) and f.inside_y(item[1]):
                y = f.py(item[1])
                out.append(f'<path d="M{_n(left)} {_n(y)}H{_n(right)}" fill="none" '
                           f"{item[2].attrs()}/>")
            elif kind == "band":
                out += self._band_svg(f, *item[1:])
            elif kind == "text":
                texts.append(item)
        out.append("</g>")
        placed: list[tuple[float, float, float, float]] = []
        for item in texts:
            out += self._annotation_svg(f, placed, *item[1:])
        # spines, ticks, tick labels
        marks = [f"M{_n(f.px(v))} {_n(bottom)}v{_n(TICK_LEN_PT)}" for v, _ in xticks]
        marks += [f"M{_n(left)} {_n(f.py(v))}h{_n(-TICK_LEN_PT)}" for v, _ in yticks]
        out.append(f'<path d="M{_n(left)} {_n(top)}V{_n(bottom)}H{_n(right)}{"".join(marks)}" '
                   f'fill="none" stroke="#000000" stroke-width="{_n(SPINE_WIDTH_PT)}" '
                   f'stroke-linecap="square"/>')
        minor = self._minor(f)
        if minor:
            out.append(f'<path d="{minor}" fill="none" stroke="#000000" stroke-width="0.6"/>')
        base = bottom + TICK_LEN_PT + TICK_PAD_PT + CAP_EM * TICK_PT
        if labels:
            last_end = -math.inf
            for v, s in xticks:
                x, half = f.px(v), text_width_pt(s, TICK_PT) / 2
                if x - half < last_end + 3.0:  # a fixed tick too close to the last: no label
                    continue
                last_end = x + half
                out.append(_text(x, base, s, TICK_PT, anchor="middle"))
        for v, s in yticks:
            out.append(_text(left - TICK_LEN_PT - TICK_PAD_PT,
                             f.py(v) + CAP_EM * TICK_PT / 2, s, TICK_PT, anchor="end"))
        out.append("</g>")
        return out

    @staticmethod
    def _minor(f: _Frame) -> str:
        """Minor tick marks (2 … 9 × 10^k) on the log axes."""
        d = []
        for axis, lim, vertical in ((f.p.x, (f.x0, f.x1), False),
                                    (f.p.y, (f.y0, f.y1), True)):
            if axis.scale != "log":
                continue
            for e in range(math.floor(lim[0]), math.ceil(lim[1]) + 1):
                for m in range(2, 10):
                    v = m * 10.0 ** e
                    if not lim[0] <= math.log10(v) <= lim[1]:
                        continue
                    if vertical:
                        d.append(f"M{_n(f.left)} {_n(f.py(v))}h-2")
                    else:
                        d.append(f"M{_n(f.px(v))} {_n(f.top + f.h)}v2")
        return "".join(d)

    @staticmethod
    def _band_svg(f: _Frame, xs: list, lo: list, hi: list, colour: str,
                  alpha: float) -> list[str]:
        ok = [i for i in range(len(xs)) if f.p.x.ok(xs[i]) and f.p.y.ok(lo[i])
              and f.p.y.ok(hi[i])]
        if not ok:
            return []
        x = [xs[i] for i in ok]
        sx, slo = _steps_mid(x, [lo[i] for i in ok])
        _, shi = _steps_mid(x, [hi[i] for i in ok])
        upper = [(f.px(a), f.py(b)) for a, b in zip(sx, shi, strict=True)]
        lower = [(f.px(a), f.py(b)) for a, b in zip(sx, slo, strict=True)]
        ring = upper + lower[::-1]
        coords = " ".join(f"{_n(a)},{_n(b)}" for a, b in ring)
        return [f'<polygon points="{coords}" fill="{colour}" fill-opacity="{_n(alpha)}" '
                f'stroke="none"/>',
                _polyline(upper, f'stroke="{colour}" stroke-width="0.9"'),
                _polyline(lower, f'stroke="{colour}" stroke-width="0.6"')]

    @staticmethod
    def _annotation_svg(f: _Frame, placed: list[tuple[float, float, float, float]],
                        text: str, x: float, y: float, dx: float, dy: float, y_axes: bool,
                        anchor: str, middle: bool, rotation: float, size: float,
                        colour: str) -> list[str]:
        """An annotation; a level one that would run into one already ``placed`` goes to
        the other side of its point (above instead of below), e.g. the labels of photo
        scales close together, and is left out when both sides are taken."""
        if not f.p.x.ok(x) or not (y_axes or f.p.y.ok(y)):
            return []
        px = f.px(x) + dx
        at = f.top + f.h * (1 - y) if y_axes else f.py(y)
        shift = CAP_EM * size / 2 if middle else 0.0
        if rotation:
            # the baseline shift runs across the rotated text
            r = math.radians(rotation)
            return [_text(px + shift * math.sin(r), at + dy + shift * math.cos(r), text,
                          size, anchor=anchor, rotation=rotation, colour=colour)]
        w = estimate_width_pt(text, size)
        x0 = px - (w / 2 if anchor == "middle" else w if anchor == "end" else 0.0)

        def box(base: float) -> tuple[float, float, float, float]:
            return (x0, x0 + w, base - CAP_EM * size, base + DESCENT_EM * size)

        def clear(b: tuple[float, float, float, float]) -> bool:
            return all(b[1] <= o[0] or o[1] <= b[0] or b[3] <= o[2] or o[3] <= b[2]
                       for o in placed)

        base = at + dy + shift
        if not clear(box(base)):
            other = at - dy + shift + (CAP_EM * size if dy > 0 else -CAP_EM * size)
            if not dy or not clear(box(other)):
                return []  # no room on either side: left out rather than overprinted
            base = other
        placed.append(box(base))
        return [_text(px, base, text, size, anchor=anchor, colour=colour)]

    @staticmethod
    def _legend_svg(entries: list, col_w: list[float], rows: int, left: float,
                    top: float, row_h: float) -> list[str]:
        out = []
        for k, (kind, style, label) in enumerate(entries):
            col, row = divmod(k, rows)
            x = left + sum(col_w[:col])
            mid = top + row * row_h + row_h / 2
            if kind == "line":
                out.append(f'<path d="M{_n(x)} {_n(mid)}h20" fill="none" {style.attrs()}/>')
            else:
                colour, alpha = style
                out.append(f'<rect x="{_n(x)}" y="{_n(mid - 3.5)}" width="20" height="7" '
                           f'fill="{colour}" fill-opacity="{_n(alpha)}" stroke="{colour}" '
                           f'stroke-width="0.6"/>')
            out.append(_text(x + 24, mid + CAP_EM * LEGEND_PT / 2, label, LEGEND_PT))
        return out

"""Plots for the PDF report and the page: deterministic SVG written directly
(:mod:`.svgchart`).

Each function draws the tables of a result (:class:`~.views.ResultTables`: the film plan's
sweep, the UAV plan's MTF and height curve, its heights and limits) or a terrain result's
photos — nothing is recomputed here. No plotting library is imported: the charts are SVG
text (polylines, circles, text) whose labels name the report's bundled DejaVu Sans
(``Scanplan Sans``, templates/fonts), so the figures look the same on any machine, the PDF
embeds only the bundled font and paints them quickly. The same plan gives the same
bytes.
"""

from __future__ import annotations

import math
from typing import Any

from ..i18n.labels import t
from ..i18n.messages import scale_text
from .formatter import formatter
from .svgchart import Chart, log_ticks
from .view import ReportView, svg_data_uri
from .views import ResultTables, constraint_title

__all__ = ["PLOT_JOBS", "constraints_svg", "draw_view_plots", "height_svg", "mtf_svg",
           "number", "terrain_svg", "view_plot", "view_plot_uri"]

#: The plots a report draws and the plan each is drawn from: the film plan's constraints
#: against the photo scale; the UAV plan's MTF at the frame centre and its GSD and L
#: against the height (``<name>_svg``).
PLOT_JOBS: dict[str, str] = {"constraints": "scan", "mtf": "uav", "height": "uav"}

_COLOURS = {"PS": "#1f77b4", "PZ": "#d62728", "PP": "#2ca02c", "PR": "#9467bd",
            "PD": "#ff7f0e"}
#: colours of further constraints, in turn (matplotlib's cycle, the ones above left out)
_MORE_COLOURS = ("#8c564b", "#e377c2", "#7f7f7f", "#bcbd22", "#17becf")
#: each constraint's dash, so lines that coincide stay apart: P_Z of the Instruction's
#: formula lies within 1 % of P_P at 1:2000 and was hidden under it. The dashed lines are
#: drawn after the solid ones, so the colour of the line beneath shows in their gaps.
_DASHES = {"PZ": (5.0, 2.5), "PR": (6.0, 2.0, 1.5, 2.0), "PD": (1.5, 1.5)}
#: the mantissas of the photo-scale ticks of a short axis (one or two evaluated scales)
_SCALE_MANTISSAS = (1.0, 1.5, 2.0, 3.0, 4.0, 5.0, 6.0, 8.0)
_TICK_GAP = 1.2  # the smallest ratio between neighbouring scale ticks (their labels fit)


def number(x: float, digits: int, locale: str) -> str:
    """``x`` with ``digits`` decimals, decimal comma in Russian, thin-space thousands
    (:meth:`scanplan.i18n.numbers.Numbers.num`).

    Parameters
    ----------
    x : float
        The value.
    digits : int
        Decimals.
    locale : {"en", "ru"}
        Decimal separator and thousands grouping.

    Returns
    -------
    str
        ``"12.5"`` / ``"12,5"``; ``"10,000"`` / ``"10 000"`` (no-break space); ``"—"`` for
        a non-finite value.
    """
    return formatter(locale).num(x, digits)




def constraints_svg(tables: ResultTables, locale: str = "en") -> str:
    """Each constraint's scan pixel against the photo scale (the ``film_sweep`` table),
    log–log.

    The evaluated photo scales are marked on the scan pixel curve (the minimum) and, when
    at most six, labelled with the binding constraint and the scan pixel
    (``film_constraints``).

    Parameters
    ----------
    tables : ResultTables
        A film plan's tables.
    locale : {"en", "ru"}
        Language of the labels and decimal separator.

    Returns
    -------
    str
        An SVG document.
    """
    sweep = {r.key: r for r in tables["film_sweep"].rows}
    xs = list(sweep["photo_scale"].values)
    chart = Chart(locale)
    ax = chart.panels[0]
    more = iter(_MORE_COLOURS)
    ax.plot(xs, sweep["scan_pixel_um"].values, colour="#000000", width=2.4, alpha=0.25,
            label=t("scan_pixel_um", locale))  # beneath the constraints' lines
    ids = [cid for cid, r in sweep.items() if "constraint" in r.flags]
    colours = {cid: _COLOURS.get(cid) or next(more, "#000000") for cid in ids}
    for cid in sorted(ids, key=lambda c: c in _DASHES):  # solid first, dashed over them
        name = constraint_title(cid, locale)
        ax.plot(xs, sweep[cid].values, colour=colours[cid], width=1.1, dash=_DASHES.get(cid),
                label=f"{cid} — {name}")
    film = tables["film_constraints"]
    px = [c.value for c in film.columns]
    py = list(film.row("scan_pixel_um").values)
    ax.markers(px, py, colour="#000000", size=4.5)
    for x, y, b in zip(px, py, film.row("binding").values, strict=True) if len(px) <= 6 \
            else ():
        ax.annotate(f"{b} {number(y, 1, locale)}", x, y, dy=11, anchor="middle", size=6.5)
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlim(min(xs), max(xs))
    # label the evaluated photo scales (1-2-5 ticks when many): log minor labels collide
    ticks = (log_ticks(min(xs), max(xs)) if len(set(px)) > 6 else sorted(set(px))
             if len(set(px)) >= 3 else _scale_ticks(px, min(xs), max(xs)))
    ax.set_xticks(ticks, fmt=lambda x: scale_text(x, locale).removeprefix("1:"))
    ax.set_xlabel(f"{t('photo_scale', locale)} 1:Mc")
    ax.set_ylabel(t("pixel_um", locale))
    return chart.svg()


def _scale_ticks(evaluated: list[float], lo: float, hi: float) -> list[float]:
    """The photo-scale ticks of an axis with one or two evaluated scales (an archive's one
    scale was the axis's only tick): the evaluated scales, and round scales (1, 1.5, 2, 3,
    4, 5, 6, 8 × 10ⁿ) within [lo, hi] that keep :data:`_TICK_GAP` from every other tick."""
    ticks = sorted(set(evaluated))
    for e in range(math.floor(math.log10(lo)), math.ceil(math.log10(hi)) + 1):
        for m in _SCALE_MANTISSAS:
            v = float(f"{m * 10.0 ** e:.12g}")
            if lo <= v <= hi and all(max(v, x) / min(v, x) >= _TICK_GAP for x in ticks):
                ticks.append(v)
    return sorted(ticks)


def mtf_svg(tables: ResultTables, locale: str = "en") -> str:
    """Image contrast and threshold contrast against frequency (the ``uav_mtf`` table, at
    the planned height), with R and the sensor's limit marked.

    Parameters
    ----------
    tables : ResultTables
        A UAV plan's tables.
    locale : {"en", "ru"}
        Language of the labels and decimal separator.

    Returns
    -------
    str
        An SVG document.
    """
    rows = {r.key: r for r in tables["uav_mtf"].rows}
    m = {key: list(r.values) for key, r in rows.items()}
    freq = m["freq_lpmm"]
    chart = Chart(locale)
    ax = chart.panels[0]
    ax.set_yscale("log")
    ax.plot(freq, m["image_contrast"], colour="#1f77b4", width=1.4,
            label=t("image_contrast", locale))
    ax.plot(freq, m["threshold"], colour="#d62728", width=1.2, dash="--",
            label=t("threshold", locale))
    right = max(freq) * 1.02 if freq else 1.0
    r = rows["resolving_power"].value if "resolving_power" in rows else None
    if r is not None:
        ax.axvline(r, colour="#000000", width=0.8, dash=":")
        # beside the line, on the side with room for the text
        near_end = r > 0.8 * right
        ax.annotate(f"R = {number(r, 1, locale)}", r, 1.0, y_axes=True,
                    dx=-3 if near_end else 3, dy=10, anchor="end" if near_end else "start",
                    size=7)
    nyquist = tables["uav_figures"].row("nyquist_lpmm").value
    ax.axvline(nyquist, colour="#808080", width=0.6)
    ax.annotate(t("nyquist_short", locale), nyquist,
                _clear_of(ax, m, freq, nyquist), y_axes=True, dx=-4, rotation=90,
                anchor="middle", size=6.5, colour="#808080")
    ax.set_xlim(0, right)
    ax.set_xlabel(t("frequency_lpmm", locale))
    ax.set_ylabel(t("contrast", locale))
    return chart.svg()


def _clear_of(ax: Any, m: dict[str, Any], freq: list[float], at: float) -> float:
    """The height (fraction of the plot, 0.2 / 0.5 / 0.8) of a label beside the line at
    frequency ``at`` farthest from both curves there (matplotlib's was always 0.5, often
    across the image contrast curve)."""
    i = max((k for k, f in enumerate(freq) if f <= at), default=None)
    ys = [m[key][i] for key in ("image_contrast", "threshold")
          if i is not None and m[key][i] and m[key][i] > 0]
    taken = [ax.y_fraction(v) for v in ys]
    return max((0.5, 0.2, 0.8), key=lambda y: min((abs(y - f) for f in taken), default=1.0))


def height_svg(tables: ResultTables, locale: str = "en") -> str:
    """GSD and ground resolution L against flight height (the ``uav_height_curve``
    table), the planned, flown and maximum heights (``uav_figures``), the binding limit
    (``uav_limits``).

    Parameters
    ----------
    tables : ResultTables
        A UAV plan's tables.
    locale : {"en", "ru"}
        Language of the labels and decimal separator.

    Returns
    -------
    str
        An SVG document.
    """
    c = {r.key: list(r.values) for r in tables["uav_height_curve"].rows}
    fig = {r.key: r.value for r in tables["uav_figures"].rows}
    planned, highest = fig["height_m"], fig["height_max_m"]
    ceiling, top = fig.get("ceiling_m"), fig.get("max_height_m")
    binding, flown = fig.get("binding"), fig.get("max_flown_height_m")
    hs = c["height_m"]
    ls = [math.nan if v is None else v for v in c["ground_resolution_m"]]
    chart = Chart(locale)
    ax = chart.panels[0]
    f = formatter(locale)
    ax.plot(hs, c["gsd_m"], colour="#2ca02c", width=1.3, label=f.compared("GSD"))
    ax.plot(hs, ls, colour="#1f77b4", width=1.3, label="L")
    # planned / highest flown at the plan; maximum planned / its highest flown height:
    # a GSD or L limit line meets its curve at the highest flown height, not the plan
    marks: list[tuple[float, str, Any, str]] = [
        (planned, "#000000", "-", t("planned", locale))]
    lowest = fig["height_min_m"]
    if "over_relief" in tables["uav_figures"].row("height_min_m").flags \
            and lowest is not None and lowest < planned - 0.05:
        # over relief the photos fly from the lowest to the highest height above the ground
        marks.append((lowest, "#808080", ":", t("lowest_flown", locale)))
    if highest != planned:
        marks.append((highest, "#808080", "--", t("highest_flown", locale)))
    # the ceiling before the maximum's lines: where the ceiling binds, the highest flown
    # height at the maximum is the ceiling, and its dash-dot is drawn over the solid line
    if ceiling is not None and ceiling <= max(hs):
        marks.append((ceiling, "#8c564b", "-", t("HC", locale)))
    if top is not None and binding:
        marks.append((top, "#d62728", ":", t("h_max_planned", locale).format(cid=binding)))
        if flown is not None and flown > top * (1 + 1e-9):
            marks.append((flown, "#ff7f0e", (5, 2, 1, 2), t("h_max_flown", locale)))
    for h, colour, style, label in marks:
        # the maximum planned height and its highest flown one in whole metres, as the
        # tables state them
        text = f.num(h, 0) if h in (top, flown) else f.height(h)
        ax.axvline(h, colour=colour, dash=style, width=0.9,
                   label=f"{label}: {text} {t('m', locale)}")
    for lim in tables["uav_limits"].rows:
        limit_m, compares = lim.values[0], lim.values[1]
        if "binding" in lim.flags and compares in ("GSD", "L") and limit_m <= max(
                max(c["gsd_m"]), max((v for v in ls if v == v), default=0.0)) * 1.05:
            ax.axhline(limit_m, colour="#d62728", width=0.6, dash="-.",
                       label=f"{f.compared(compares)} ≤ {number(limit_m, 3, locale)} "
                             f"{t('m', locale)} ({lim.key})")
    ax.set_xlim(0, max(hs))
    ax.set_ylim(bottom=0)
    ax.set_xlabel(t("height_m", locale))
    ax.set_ylabel(f"{f.compared('GSD')}, L, {t('m', locale)}")
    return chart.svg()


def _per_strip(strip: Any, values: Any) -> tuple[list[float], list[float], list[float]]:
    """(strip numbers, min, max) of ``values`` over each strip's photos."""
    import numpy as np

    strip = np.asarray(strip)
    v = np.asarray(values, dtype=float)
    order = np.argsort(strip, kind="stable")
    s, v = strip[order], v[order]
    starts = np.flatnonzero(np.r_[True, s[1:] != s[:-1]])
    return (s[starts].astype(float).tolist(), np.minimum.reduceat(v, starts).tolist(),
            np.maximum.reduceat(v, starts).tolist())


def terrain_svg(terrain: Any, limit_m: float | None, locale: str = "en") -> str:
    """Heights above ground of the photos of every strip (issue 12), with the planned
    height and the maximum planned height; below, the ground and the flight altitude.

    Parameters
    ----------
    terrain : scanplan.geo.terrain.TerrainResult
        Photos with ``strip``, ``agl_m``, ``ground_m``, ``altitude_m``.
    limit_m : float or None
        The maximum planned height above ground (the binding constraint's) [m].
    locale : {"en", "ru"}

    Returns
    -------
    str
        An SVG document: per strip the range (lowest … highest) over its photos.
    """
    import numpy as np

    ph = terrain.layout.photos
    agl = np.asarray(ph["agl_m"], dtype=float)
    alt = np.asarray(ph["altitude_m"], dtype=float)
    ground = np.asarray(ph["ground_m"], dtype=float)
    ground = np.where(np.isfinite(ground), ground, alt - agl)
    m = t("m", locale)
    chart = Chart(locale, (3.0, 2.0), plot_height_pt=220.0)
    top, bottom = chart.panels

    def band(ax: Any, values: Any, colour: str, label: str) -> list[float]:
        x, lo, hi = _per_strip(ph["strip"], values)
        ax.band(x, lo, hi, colour=colour, alpha=0.35, label=label)
        return x

    strips = band(top, agl, "#1f77b4", t("agl_m", locale))
    top.axhline(terrain.height_m, colour="#000000", width=0.9,
                label=f"{t('terrain_plot_planned', locale)}: "
                      f"{number(terrain.height_m, 0, locale)} {m}")
    if limit_m is not None:
        top.axhline(limit_m, colour="#d62728", dash=":", width=1.0,
                    label=f"{t('max_height', locale)}"
                          + (f" ({terrain.binding})" if terrain.binding else "")
                          + f": {number(limit_m, 0, locale)} {m}")
    top.set_ylabel(t("agl_m", locale))
    top.set_ylim(bottom=0)
    band(bottom, ground, "#8c564b", t("ground_m", locale))
    band(bottom, alt, "#2ca02c", t("altitude_m", locale))
    bottom.set_xscale("linear", integer=True)
    bottom.set_xlim(min(strips) - 0.5, max(strips) + 0.5)  # each strip's step, whole
    bottom.set_xlabel(t("terrain_plot_x", locale))
    bottom.set_ylabel(t("terrain_plot_y_amsl", locale))
    return chart.svg()


def view_plot(view: ReportView, name: str) -> str:
    """A plot of a report's view as SVG text, drawn on first use and kept in the view.

    Parameters
    ----------
    view : ReportView
        The result as the documents show it; its ``charts`` keep the plots drawn.
    name : {"constraints", "mtf", "height"}
        The film plan's constraints against the photo scale; the UAV plan's MTF at the
        frame centre; the UAV plan's GSD and L against the height.

    Returns
    -------
    str
        A deterministic SVG.
    """
    if name not in view.charts:
        view.job_of(PLOT_JOBS[name])  # ValueError when the report has not that plan
        draw = {"constraints": constraints_svg, "mtf": mtf_svg, "height": height_svg}[name]
        view.charts[name] = draw(view.tables, view.locale)
    return view.charts[name]


def view_plot_uri(view: ReportView, name: str) -> str:
    """:func:`view_plot` as a ``data:`` URI (what the PDF's HTML embeds)."""
    return svg_data_uri(view_plot(view, name))


def draw_view_plots(view: ReportView) -> None:
    """Draw every plot the report has (of :data:`PLOT_JOBS` whose plan it carries), so
    that they travel with the view (e.g. to the PDF worker)."""
    for name, job in PLOT_JOBS.items():
        if getattr(view, job) is not None:
            view_plot(view, name)

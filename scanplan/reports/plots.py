"""Plots for the PDF report: deterministic SVG from matplotlib (no pyplot, no global state).

Each function draws numbers already held by a plan object (``ScanPlan.sweep``,
``UavPlan.mtf_centre``, ``UavPlan.height_curve``) — nothing is recomputed here. Text stays
text (drawing glyphs as paths made the PDF about 0.6 s slower to paint): matplotlib lays it
out with its DejaVu Sans, and the SVG names the report's bundled copy of the same font
(``Scanplan Sans``, templates/fonts), so the figures look the same on any machine and the
PDF embeds only the bundled font. ``svg.hashsalt`` plus an empty date make the SVG
byte-identical from run to run.
"""

from __future__ import annotations

import io
import math
from collections.abc import Callable, Sequence
from typing import TYPE_CHECKING, Any

from ..rules.film import CONSTRAINTS, ScanPlan
from ..rules.uav import UavPlan
from .labels import t
from .view import Numbers

if TYPE_CHECKING:  # matplotlib (0.2 s) is imported when a figure is drawn
    from matplotlib.figure import Figure
    from matplotlib.ticker import FuncFormatter

__all__ = ["constraints_svg", "height_svg", "mtf_svg", "number", "terrain_svg"]

_RC: dict[str, Any] = {
    "svg.hashsalt": "scanplan",
    "svg.fonttype": "none",
    "font.family": "DejaVu Sans",
    "font.size": 8.0,
    "axes.titlesize": 8.5,
    "axes.labelsize": 8.0,
    "legend.fontsize": 7.0,
    "xtick.labelsize": 7.0,
    "ytick.labelsize": 7.0,
    "axes.grid": True,
    "grid.color": "#d8d8d8",
    "grid.linewidth": 0.5,
    "axes.spines.top": False,
    "axes.spines.right": False,
    "path.simplify": False,
}
_COLOURS = {"PS": "#1f77b4", "PZ": "#d62728", "PP": "#2ca02c", "PR": "#9467bd",
            "PD": "#ff7f0e"}
_SIZE_IN = (6.6, 3.0)


def number(x: float, digits: int, locale: str) -> str:
    """``x`` with ``digits`` decimals, decimal comma in Russian, thin-space thousands
    (:meth:`scanplan.reports.view.Numbers.num`).

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
    return Numbers(locale).num(x, digits)


def _height_digits(h: float) -> int:
    """Decimals of a height [m] in a legend: as the tables give it (148.5, not 148; 70, not
    70.0)."""
    return 0 if abs(h - round(h)) < 0.05 else 1


def _tick(locale: str) -> FuncFormatter:
    from matplotlib.ticker import FuncFormatter

    numbers = Numbers(locale)

    def fmt(x: float, _pos: int | None = None) -> str:
        return numbers.tick(x)
    return FuncFormatter(fmt)


def _nice_log_ticks(lo: float, hi: float) -> list[float]:
    """1-2-5 ticks covering [lo, hi] (for short log axes)."""
    out = []
    for e in range(math.floor(math.log10(lo)) - 1, math.ceil(math.log10(hi)) + 1):
        for m in (1, 2, 5):
            v = m * 10.0 ** e
            if lo / 1.3 <= v <= hi * 1.3:
                out.append(float(f"{v:.12g}"))
    return out


def _svg(draw: Callable[[Figure], None]) -> str:
    import matplotlib
    from matplotlib.backends.backend_svg import FigureCanvasSVG
    from matplotlib.figure import Figure

    with matplotlib.rc_context(_RC):
        fig = Figure(figsize=_SIZE_IN, layout="constrained")
        FigureCanvasSVG(fig)  # the text is measured as the SVG writer sets it
        draw(fig)
        # The constrained layout is computed once, here; savefig would otherwise draw the
        # whole figure a first time (to an idle renderer) only to lay it out. Same bytes.
        fig.get_layout_engine().execute(fig)
        fig.set_layout_engine("none")
        buf = io.StringIO()
        fig.savefig(buf, format="svg", metadata={"Date": None, "Creator": None})
    # same glyphs and metrics: point the text at the bundled font, never a system one
    return buf.getvalue().replace("'DejaVu Sans'", "'Scanplan Sans'").replace(
        '"DejaVu Sans"', '"Scanplan Sans"').replace("DejaVu Sans", "Scanplan Sans")


def constraints_svg(plan: ScanPlan, locale: str = "en") -> str:
    """Each constraint's scan pixel against the photo scale (``plan.sweep``), log–log.

    The evaluated photo scales are marked on the scan pixel curve (the minimum).

    Parameters
    ----------
    plan : ScanPlan
        A plan with its dense sweep.
    locale : {"en", "ru"}
        Language of the labels and decimal separator.

    Returns
    -------
    str
        An SVG document.
    """
    sweep = plan.sweep
    xs: Sequence[float] = sweep["photo_scale"]

    def draw(fig: Figure) -> None:
        from matplotlib.ticker import FixedLocator, NullFormatter

        ax = fig.add_subplot()
        for cid in plan.constraint_ids:
            if cid not in sweep:
                continue
            name = CONSTRAINTS[cid].name_ru if locale == "ru" else CONSTRAINTS[cid].name
            ax.plot(xs, sweep[cid], color=_COLOURS.get(cid), linewidth=1.1,
                    label=f"{cid} — {name}")
        ax.plot(xs, sweep["scan_pixel_um"], color="black", linewidth=2.4, alpha=0.25,
                label=t("scan_pixel_um", locale))
        px = [s.photo_scale for s in plan.scenarios]
        py = [s.scan_pixel_um for s in plan.scenarios]
        ax.plot(px, py, linestyle="none", marker="o", markersize=4.5, color="black")
        for s in plan.scenarios if len(plan.scenarios) <= 6 else ():
            ax.annotate(f"{s.binding} {number(s.scan_pixel_um, 1, locale)}",
                        (s.photo_scale, s.scan_pixel_um), textcoords="offset points",
                        xytext=(0, -11), ha="center", fontsize=6.5)
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlim(min(xs), max(xs))
        # label the evaluated photo scales (1-2-5 ticks when many): log minor labels collide
        ticks = sorted(set(px)) if len(set(px)) <= 6 else _nice_log_ticks(min(xs), max(xs))
        ax.xaxis.set_major_locator(FixedLocator(ticks))
        ax.xaxis.set_minor_formatter(NullFormatter())
        ax.xaxis.set_major_formatter(_tick(locale))
        lo = min(min(v for v in sweep[c] if v == v) for c in plan.constraint_ids
                 if c in sweep)
        hi = max(max(v for v in sweep[c] if v == v) for c in plan.constraint_ids
                 if c in sweep)
        ax.yaxis.set_major_locator(FixedLocator(_nice_log_ticks(lo, hi)))
        ax.yaxis.set_minor_formatter(NullFormatter())
        ax.yaxis.set_major_formatter(_tick(locale))
        ax.set_xlabel(f"{t('photo_scale', locale)} 1:Mc")
        ax.set_ylabel(t("pixel_um", locale))
        ax.legend(loc="upper right", frameon=False)

    return _svg(draw)


def mtf_svg(plan: UavPlan, locale: str = "en") -> str:
    """Image contrast and threshold contrast against frequency, with R marked.

    Parameters
    ----------
    plan : UavPlan
        A plan with ``mtf_centre`` (at the planned height).
    locale : {"en", "ru"}
        Language of the labels and decimal separator.

    Returns
    -------
    str
        An SVG document.
    """
    m = plan.mtf_centre
    freq = m["freq_lpmm"]

    def draw(fig: Figure) -> None:
        from matplotlib.ticker import FixedLocator, NullFormatter

        ax = fig.add_subplot()
        ax.plot(freq, m["image_contrast"], color="#1f77b4", linewidth=1.4,
                label=t("image_contrast", locale))
        ax.plot(freq, m["threshold"], color="#d62728", linewidth=1.2, linestyle="--",
                label=t("threshold", locale))
        r = plan.resolving_power_lpmm
        if r is not None:
            ax.axvline(r, color="black", linewidth=0.8, linestyle=":")
            ax.annotate(f"R = {number(r, 1, locale)}", (r, 1.0),
                        xycoords=("data", "axes fraction"), textcoords="offset points",
                        xytext=(3, -10), fontsize=7)
        ax.axvline(plan.nyquist_lpmm, color="grey", linewidth=0.6)
        ax.annotate(t("pdf_nyquist_short", locale), (plan.nyquist_lpmm, 0.5),
                    xycoords=("data", "axes fraction"), textcoords="offset points",
                    xytext=(-7, 0), rotation=90, ha="right", va="center", fontsize=6.5,
                    color="grey")
        ax.set_yscale("log")
        ax.set_xlim(0, max(freq) * 1.02 if freq else 1)
        values = [v for k in ("image_contrast", "threshold") for v in m[k] if v and v > 0]
        if values:
            ax.yaxis.set_major_locator(FixedLocator(_nice_log_ticks(min(values),
                                                                    max(values))))
        ax.yaxis.set_minor_formatter(NullFormatter())
        ax.xaxis.set_major_formatter(_tick(locale))
        ax.yaxis.set_major_formatter(_tick(locale))
        ax.set_xlabel(t("frequency_lpmm", locale))
        ax.set_ylabel(t("contrast", locale))
        fig.legend(loc="outside right upper", frameon=False)

    return _svg(draw)


def height_svg(plan: UavPlan, locale: str = "en") -> str:
    """GSD and ground resolution L against flight height, planned/flown/maximum heights.

    Parameters
    ----------
    plan : UavPlan
        A plan with ``height_curve``.
    locale : {"en", "ru"}
        Language of the labels and decimal separator.

    Returns
    -------
    str
        An SVG document.
    """
    c = plan.height_curve
    hs = c["height_m"]
    ls = [math.nan if v is None else v for v in c["ground_resolution_m"]]

    def draw(fig: Figure) -> None:
        ax = fig.add_subplot()
        ax.plot(hs, c["gsd_m"], color="#2ca02c", linewidth=1.3, label="GSD")
        ax.plot(hs, ls, color="#1f77b4", linewidth=1.3, label="L")
        # planned / highest flown at the plan; maximum planned / its highest flown height:
        # a GSD or L limit line meets its curve at the highest flown height, not the plan
        marks = [(plan.heights_m["planned"], "black", "-", t("pdf_h_planned", locale))]
        if plan.heights_m["max"] != plan.heights_m["planned"]:
            marks.append((plan.heights_m["max"], "grey", "--", t("pdf_h_flown_max", locale)))
        if plan.max_height_m is not None and plan.binding is not None:
            marks.append((plan.max_height_m, "#d62728", ":",
                          t("pdf_h_max", locale).format(cid=plan.binding)))
            flown = plan.max_flown_height_m
            if flown is not None and flown > plan.max_height_m * (1 + 1e-9):
                marks.append((flown, "#ff7f0e", (0, (5, 2, 1, 2)),
                              t("pdf_h_max_flown", locale)))
        if plan.ceiling_m is not None and plan.ceiling_m <= max(hs):
            marks.append((plan.ceiling_m, "#8c564b", "-", t("pdf_h_ceiling", locale)))
        for h, colour, style, label in marks:
            # the maximum planned height and its highest flown one in whole metres, as the
            # tables state them
            digits = (0 if h in (plan.max_height_m, plan.max_flown_height_m)
                      else _height_digits(h))
            ax.axvline(h, color=colour, linestyle=style, linewidth=0.9,
                       label=f"{label}: {number(h, digits, locale)} {t('pdf_m', locale)}")
        for lim in plan.limits:
            if lim.binding and lim.compares in ("GSD", "L") and lim.limit_m <= max(
                    max(c["gsd_m"]), max((v for v in ls if v == v), default=0.0)) * 1.05:
                ax.axhline(lim.limit_m, color="#d62728", linewidth=0.6, linestyle="-.",
                           label=f"{lim.compares} ≤ {number(lim.limit_m, 3, locale)} "
                                 f"{t('pdf_m', locale)} ({lim.id})")
        ax.set_xlim(0, max(hs))
        ax.set_ylim(bottom=0)
        ax.xaxis.set_major_formatter(_tick(locale))
        ax.yaxis.set_major_formatter(_tick(locale))
        ax.set_xlabel(t("height_m", locale))
        ax.set_ylabel(f"GSD, L, {t('pdf_m', locale)}")
        fig.legend(loc="outside right upper", frameon=False)

    return _svg(draw)


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
    m = t("pdf_m", locale)

    def band(ax: Any, values: Any, colour: str, label: str) -> None:
        x, lo, hi = _per_strip(ph["strip"], values)
        ax.fill_between(x, lo, hi, color=colour, alpha=0.35, linewidth=0, step="mid",
                        label=label)
        ax.step(x, hi, where="mid", color=colour, linewidth=0.9)
        ax.step(x, lo, where="mid", color=colour, linewidth=0.6)

    def draw(fig: Figure) -> None:
        top, bottom = fig.subplots(2, 1, sharex=True, height_ratios=(3, 2))
        band(top, agl, "#1f77b4", t("terrain_agl_m", locale))
        top.axhline(terrain.height_m, color="black", linewidth=0.9,
                    label=f"{t('terrain_plot_planned', locale)}: "
                          f"{number(terrain.height_m, 0, locale)} {m}")
        if limit_m is not None:
            top.axhline(limit_m, color="#d62728", linestyle=":", linewidth=1.0,
                        label=f"{t('terrain_plot_limit', locale)}"
                              + (f" ({terrain.binding})" if terrain.binding else "")
                              + f": {number(limit_m, 0, locale)} {m}")
        top.set_ylabel(t("terrain_plot_y", locale))
        top.set_ylim(bottom=0)
        band(bottom, ground, "#8c564b", t("terrain_ground_m", locale))
        band(bottom, alt, "#2ca02c", t("terrain_altitude_m", locale))
        bottom.set_xlabel(t("terrain_plot_x", locale))
        bottom.set_ylabel(t("terrain_plot_y_amsl", locale))
        for ax in (top, bottom):
            ax.xaxis.set_major_formatter(_tick(locale))
            ax.yaxis.set_major_formatter(_tick(locale))
        fig.legend(loc="outside right upper", frameon=False)

    return _svg(draw)

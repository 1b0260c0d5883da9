"""The flight over the area in the reports: a map page and a strips table (issue 11).

:func:`map_svg` draws a flight layout in its planning CRS with matplotlib (deterministic
SVG, no web tiles, the report's font — as :mod:`scanplan.reports.plots`): the area (holes
included), the strips with their flight direction and numbers, the photo centres, a north
arrow (true north at the area's centre: the grid of a projected CRS is turned from it by
the meridian convergence), a scale bar and the CRS named. :func:`geo_views` gives the PDF
its map page, a summary and a strips table per layout; an abstract width × length block
gets a sentence saying why it has no map and no files.

Nothing is recomputed here: every number comes from the :class:`FlightLayout` and the
view :mod:`scanplan.reports.views.flight` (heights above ground, strip ends as lon/lat).
"""

from __future__ import annotations

import base64
import io
import math
from typing import TYPE_CHECKING, Any

import numpy as np

from ..i18n.labels import t
from ..i18n.labels_geo import crs_name
from ..i18n.messages import scale_text
from . import exports as _exports
from .plots import number
from .views.flight import (
    MapTerrain,
    ground_known,
    map_basemap,
    map_extent,
    map_terrain,
    strip_ends_lonlat,
    tile_host,
)

#: matplotlib's style of the map page (the one figure still drawn with it): deterministic
#: SVG, text as text, the same font, sizes and grid as the line charts
#: (:mod:`scanplan.reports.svgchart`)
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


if TYPE_CHECKING:  # matplotlib is imported when a map is drawn (the workbook draws none)
    from matplotlib.figure import Figure
    from matplotlib.ticker import FuncFormatter

    from ..geo.layout import Area, FlightLayout

__all__ = ["MAX_MAP_PHOTOS", "MAX_SHEET_PHOTOS", "MAX_TABLE_STRIPS", "MapTerrain",
           "area_crs_text", "crs_text", "geo_views", "ground_known", "map_svg", "map_terrain"]

MAX_MAP_PHOTOS = 4000
"""Most photo centres drawn on the map (every k-th beyond it: the SVG stays small)."""
MAX_SHEET_PHOTOS = 10_000
"""Most photo centres put on the workbook's Photos sheet (openpyxl writes about 10⁴ rows a
second; :mod:`.geosheets`); the map's notes say where a larger layout's photos are."""
MAX_SORTIE_LABELS = 60
"""Most sortie numbers written on the map (beyond: every k-th sortie)."""
MAX_TABLE_STRIPS = 150
"""Most strips listed in the PDF's strips table (the workbook lists all)."""
_MAP_SIZE_IN = (6.6, 8.2)  # width, greatest height [in]
_PHOTO_DPI = 300
"""Resolution [dots per inch] of the photo centres of a map without terrain, its only raster
layer: thousands of 1.6 pt dots as SVG elements took WeasyPrint about 1.3 s to draw (4,575
photos), as one 300 dpi picture 0.1 s; printed or zoomed to 400 %, a dot looks the same.
The area, the strips, the text and the legend stay vector."""
_RASTER_DPI = 150  # the photo centres coloured by height above ground (terrain maps)

def crs_text(layout: FlightLayout, locale: str) -> str:
    """The planning CRS of a layout's area named for a report (:func:`area_crs_text`)."""
    return area_crs_text(layout.area, locale)


def area_crs_text(area: Area, locale: str) -> str:
    """The planning CRS of ``area`` named for a report or the page:
    ``EPSG:32635 — WGS 84 / UTM zone 35N``.

    Russian names translate the common words (:func:`scanplan.i18n.labels_geo.crs_name`);
    a name with other English words is left out (the EPSG code alone names the system).
    """
    if not area.georeferenced:
        return t("map_local", locale)
    code = area.plan_crs if len(area.plan_crs) < 40 else ""  # a WKT is not shown
    name = crs_name(getattr(area, "plan_crs_name", "") or "", locale)
    parts = [p for p in (code, name) if p]
    return " — ".join(parts) if parts else t("map_local", locale)


def _nice(length: float) -> float:
    """A 1-2-5 length not over ``length``."""
    e = 10 ** math.floor(math.log10(length))
    return max(m * e for m in (1, 2, 5) if m * e <= length)


def _true_north_deg(layout: FlightLayout) -> float | None:
    """Direction of true north at the area's centre, clockwise from grid north [°]."""
    if not layout.area.georeferenced or layout.area.centroid_lonlat is None:
        return None
    from pyproj import CRS, Transformer

    tr = Transformer.from_crs(CRS.from_epsg(4326), CRS.from_user_input(layout.area.plan_crs),
                              always_xy=True)
    lon, lat = layout.area.centroid_lonlat
    x0, y0 = tr.transform(lon, lat)
    x1, y1 = tr.transform(lon, min(lat + 0.01, 89.99))
    return math.degrees(math.atan2(x1 - x0, y1 - y0))


def _draw_area(ax: Any, geometry: Any, scale: float, label: str) -> None:
    polys = list(getattr(geometry, "geoms", [geometry]))
    for k, poly in enumerate(polys):
        ext = np.asarray(poly.exterior.coords)[:, :2] / scale
        ax.fill(ext[:, 0], ext[:, 1], facecolor="#fde0dc", edgecolor="#c62828",
                linewidth=1.2, zorder=1, label=label if k == 0 else None)
        for ring in poly.interiors:
            hole = np.asarray(ring.coords)[:, :2] / scale
            ax.fill(hole[:, 0], hole[:, 1], facecolor="white", edgecolor="#c62828",
                    linewidth=1.0, zorder=1.5)


def _draw_strips(ax: Any, layout: FlightLayout, scale: float, label: str) -> None:
    n = len(layout.strips)
    every = max(1, math.ceil(n / 40))  # strip numbers: at most ~40 on the map
    for k, s in enumerate(layout.strips):
        (x0, y0), (x1, y1) = np.asarray(s.start_xy_m) / scale, np.asarray(s.end_xy_m) / scale
        ax.plot([x0, x1], [y0, y1], color="#1565c0", linewidth=0.8, zorder=2,
                label=label if k == 0 else None)
        if k % max(1, math.ceil(n / 15)) == 0:  # flight direction on ~15 strips
            ax.annotate("", xy=(x0 + 0.55 * (x1 - x0), y0 + 0.55 * (y1 - y0)),
                        xytext=(x0 + 0.45 * (x1 - x0), y0 + 0.45 * (y1 - y0)),
                        arrowprops={"arrowstyle": "-|>", "color": "#1565c0", "lw": 0.8,
                                    "mutation_scale": 9},
                        zorder=3)
        if k % every == 0 or k == n - 1:
            ax.annotate(str(s.number), (x0, y0), fontsize=6, color="#0d47a1",
                        ha="center", va="center", zorder=4,
                        bbox={"boxstyle": "round,pad=0.15", "fc": "white", "ec": "none",
                              "alpha": 0.8})


def _sortie_starts(layout: FlightLayout) -> list[tuple[int, float, float]]:
    """(sortie, x, y) of every sortie's first photo [m] (flight order)."""
    ph = layout.photos
    if not len(ph):
        return []
    sortie = np.asarray(ph["sortie"]).astype(np.int64)
    photo = np.asarray(ph["photo"]).astype(np.int64)
    order = np.lexsort((photo, sortie))
    first = order[np.r_[True, np.diff(sortie[order]) != 0]]
    return [(int(sortie[i]), float(ph["x_m"][i]), float(ph["y_m"][i])) for i in first]


def _draw_sorties(ax: Any, layout: FlightLayout, scale: float, locale: str) -> None:
    """Where each sortie starts (its number; at most :data:`MAX_SORTIE_LABELS`, else
    every k-th), the take-off point and the transit from it to each sortie's start."""
    if layout.kind == "film":
        return
    starts = _sortie_starts(layout)
    takeoff = layout.notes.get("takeoff_xy_m")
    if takeoff is not None:
        tx, ty = takeoff[0] / scale, takeoff[1] / scale
        for k, (_n, x, y) in enumerate(starts):
            ax.plot([tx, x / scale], [ty, y / scale], color="#6a1b9a", linewidth=0.6,
                    linestyle=(0, (3, 2)), zorder=1.8,
                    label=t("map_legend_transit", locale) if k == 0 else None)
        ax.plot([tx], [ty], linestyle="none", marker="^", markersize=7, color="black",
                zorder=7, label=t("takeoff_point", locale))
    if len(starts) < 2:
        return
    step = max(1, math.ceil(len(starts) / MAX_SORTIE_LABELS))
    shown = starts[::step]
    ax.plot([x / scale for _, x, _ in shown], [y / scale for _, _, y in shown],
            linestyle="none", marker="s", markersize=3.5, color="#6a1b9a", zorder=6,
            label=t("map_legend_sorties", locale))
    for n, x, y in shown:
        ax.annotate(str(n), (x / scale, y / scale), fontsize=6, color="#6a1b9a",
                    xytext=(3, 3), textcoords="offset points", zorder=6)


def _km_ticks(axis: Any, locale: str) -> FuncFormatter:
    """Tick labels in km with as many decimals as the tick step needs."""
    from matplotlib.ticker import FuncFormatter

    def fmt(v: float, _pos: int | None = None) -> str:
        ticks = axis.get_majorticklocs()
        step = float(np.min(np.diff(ticks))) if len(ticks) > 1 else 1.0
        digits = next((d for d in range(4) if abs(round(step, d) - step) < 1e-9 * max(step, 1)),
                      3)  # as many decimals as the step has (0.25 km: two)
        return number(v, digits, locale)
    return FuncFormatter(fmt)


def _scale_ticks(locale: str) -> FuncFormatter:
    """Tick labels of the colour bar's local photo scales 1:Mc, written as the text writes
    scales (:func:`scanplan.i18n.messages.scale_text` without ``1:``): 6000, 25000; Russian
    6000, 25 000 — not the grouped numbers 6,000 / 6 000."""
    from matplotlib.ticker import FuncFormatter

    return FuncFormatter(lambda v, _p: scale_text(round(v), locale).removeprefix("1:"))


def _scale_bar(ax: Any, span_km: float, locale: str) -> None:
    """A scale bar in the lower right, in metres or kilometres."""
    length_km = _nice(span_km / 4)
    x0, x1 = ax.get_xlim()
    y0, y1 = ax.get_ylim()
    bx, by = x1 - 0.05 * (x1 - x0) - length_km, y0 + 0.04 * (y1 - y0)
    ax.plot([bx, bx + length_km], [by, by], color="black", linewidth=2.5, zorder=6,
            solid_capstyle="butt")
    text = (f"{number(length_km, 0 if length_km >= 1 else 1, locale)} {t('km', locale)}"
            if length_km >= 1 else f"{number(length_km * 1000, 0, locale)} {t('m', locale)}")
    ax.text(bx + length_km / 2, by + 0.015 * (y1 - y0), text, ha="center", va="bottom",
            fontsize=7, zorder=6, bbox={"fc": "white", "ec": "none", "alpha": 0.8, "pad": 1})


def _north_arrow(ax: Any, north_deg: float, locale: str) -> None:
    """An arrow to true north in the upper right corner (axes coordinates)."""
    cx, cy, r = 0.93, 0.88, 0.05
    dx, dy = r * math.sin(math.radians(north_deg)), r * math.cos(math.radians(north_deg))
    ax.annotate("", xy=(cx + dx, cy + dy), xytext=(cx - dx, cy - dy),
                xycoords="axes fraction",
                arrowprops={"arrowstyle": "-|>,head_width=0.4,head_length=0.8",
                            "color": "black", "lw": 1.4}, zorder=7)
    ax.text(cx + 1.5 * dx, cy + 1.5 * dy, t("map_north", locale), transform=ax.transAxes,
            ha="center", va="center", fontsize=9, fontweight="bold", zorder=7)


def _draw_photos_agl(fig: Figure, ax: Any, layout: FlightLayout, mt: MapTerrain,
                     scale: float, locale: str) -> None:
    """The photo centres coloured by height above ground (one scatter), a colour bar in
    metres (film: with the local photo scale beside it), and one marker layer for each
    failed check. Vectorised: no per-photo Python work."""
    from matplotlib.ticker import FuncFormatter

    ph = layout.photos
    film = layout.kind == "film"
    x = np.asarray(ph["x_m"], float) / scale
    y = np.asarray(ph["y_m"], float) / scale
    step = max(1, math.ceil(x.size / MAX_MAP_PHOTOS))
    agl = mt.agl_m
    finite = agl[np.isfinite(agl)]
    lo, hi = (float(finite.min()), float(finite.max())) if finite.size else (0.0, 1.0)
    if mt.agl_range_m is not None:  # the heights the ground allows (a range: unknown)
        lo, hi = min(lo, mt.agl_range_m[0]), max(hi, mt.agl_range_m[1])
    if hi - lo < 1.0:
        lo, hi = lo - 0.5, hi + 0.5
    label = t("map_legend_frames_agl" if film else "map_legend_photos_agl", locale)
    if step > 1:
        label += f" ({t('map_one_in', locale).format(k=step)})"
    shown = math.ceil(x.size / step)
    size = min(max(3000.0 / max(shown, 1), 3.0), 16.0)  # few frames: larger dots
    sc = ax.scatter(x[::step], y[::step], c=agl[::step], s=size, cmap="viridis", vmin=lo,
                    vmax=hi, edgecolors="#333333", linewidths=0.25 if size > 3.0 else 0.0,
                    zorder=2.5, label=label, rasterized=True)
    cax = ax.inset_axes((1.03, 0.12, 0.025, 0.76))  # beside the map, which keeps its width
    cb = fig.colorbar(sc, cax=cax)
    cb.set_label(t("agl_m", locale))
    cb.ax.yaxis.set_major_formatter(FuncFormatter(lambda v, _p: number(v, 0, locale)))
    if mt.scale_of_height is not None and mt.height_of_scale is not None:
        sec = cb.ax.secondary_yaxis("left", functions=(mt.scale_of_height, mt.height_of_scale))
        sec.set_ylabel(t("map_local_scale_axis", locale))
        sec.yaxis.set_major_formatter(_scale_ticks(locale))
        sec.tick_params(labelsize=6)
    marks = ((mt.too_high, "x", "#c62828", t("map_legend_too_high", locale).format(
                 limit=number(mt.limit_m, 0, locale) if mt.limit_m is not None else "—",
                 cid=mt.cid)),
             (mt.overlap_short & ~mt.too_high, "v", "#e65100",
              t("map_legend_overlap_short", locale)))
    for mask, marker, color, text in marks:
        idx = np.flatnonzero(mask)
        if idx.size:
            idx = idx[::max(1, math.ceil(idx.size / MAX_MAP_PHOTOS))]
            ax.scatter(x[idx], y[idx], marker=marker, s=9.0, c=color, linewidths=0.6,
                       zorder=2.7, label=text)
    if mt.highlight is not None:
        at = np.flatnonzero(np.asarray(ph["photo"]) == mt.highlight)
        if at.size:
            ax.scatter(x[at[:1]], y[at[:1]], marker="o", s=60.0, facecolors="none",
                       edgecolors="black", linewidths=1.1, zorder=2.9,
                       label=t(mt.highlight_key, locale).format(n=mt.highlight))


def _draw_control(ax: Any, control: Any, scale: float, locale: str) -> None:
    """The GCPs (red triangles) and the checkpoints (blue circles) of ``[control]``."""
    c = control.columns
    for role, marker, colour, key in (("gcp", "^", "#c62828", "map_legend_gcp"),
                                      ("check", "o", "#1565c0", "map_legend_checkpoint")):
        m = control.role(role)
        if m.any():
            ax.scatter(c["x_m"][m] / scale, c["y_m"][m] / scale, marker=marker, s=30,
                       facecolor=colour, edgecolor="black", linewidth=0.4, zorder=8,
                       label=t(key, locale))


def map_svg(layout: FlightLayout, locale: str = "en", terrain: MapTerrain | None = None,
            basemap: Any = None, control: Any = None) -> str:
    """The flight layout drawn in its planning CRS (see the module docstring).

    Parameters
    ----------
    layout : FlightLayout
        Area, strips and photo centres.
    locale : {"en", "ru"}
        Language of the labels and decimal separator.
    terrain : MapTerrain, optional
        ``[terrain]``: the photo centres are coloured by their height above ground, with a
        colour bar, and the photos that break a constraint are marked
        (:func:`map_terrain`).
    basemap : scanplan.geo.basemap.Basemap, optional
        ``[map] basemap``: the background image in the layout's planning CRS, drawn under
        everything (:func:`scanplan.reports.views.flight.map_basemap`).
    control : ControlPoints, optional
        ``[control]``: the GCPs (triangles) and checkpoints (circles) over the flight.

    Returns
    -------
    str
        An SVG document.
    """
    import matplotlib
    from matplotlib.figure import Figure

    scale = 1000.0  # axes in km
    ph = layout.photos

    def draw(fig: Figure) -> None:
        ax = fig.add_subplot()
        _draw_area(ax, layout.area.geometry, scale, t("area", locale))
        _draw_strips(ax, layout, scale, t("map_legend_strips", locale))
        _draw_sorties(ax, layout, scale, locale)
        if len(ph) and terrain is not None:
            _draw_photos_agl(fig, ax, layout, terrain, scale, locale)
        elif len(ph):
            _draw_photos_plain(ax, layout, scale, locale)
        if basemap is not None:
            _draw_basemap(ax, basemap, scale)
        if control is not None and len(control):
            _draw_control(ax, control, scale, locale)
        ax.set_aspect("equal", adjustable="datalim")
        ax.margins(0.1)
        ax.xaxis.set_major_formatter(_km_ticks(ax.xaxis, locale))
        ax.yaxis.set_major_formatter(_km_ticks(ax.yaxis, locale))
        ax.set_xlabel(t("map_easting_km", locale))
        ax.set_ylabel(t("map_northing_km", locale))
        ax.set_title(crs_text(layout, locale), fontsize=8)
        longest = max((len(x) for x in ax.get_legend_handles_labels()[1]), default=0)
        fig.legend(loc="outside lower center", frameon=False,  # a terrain map's longer
                   ncols=3 if terrain is None else (2 if longest <= 48 else 1))  # entries
        fig.canvas.draw()  # limits are final before the bar and the arrow are placed
        x0, x1 = ax.get_xlim()
        _scale_bar(ax, x1 - x0, locale)
        north = _true_north_deg(layout)
        if north is not None:
            _north_arrow(ax, north, locale)

    with matplotlib.rc_context({**_RC, "axes.grid": True}):
        fig = Figure(figsize=_map_size_in(layout), layout="constrained")
        draw(fig)
        buf = io.StringIO()
        # the photo centres are the one raster layer of a map (thousands of points as SVG
        # elements take long to write and to print): coloured by height above ground at
        # 150 dpi, plain at 300 dpi
        fig.savefig(buf, format="svg", metadata={"Date": None, "Creator": None},
                    dpi=_RASTER_DPI if terrain is not None else _PHOTO_DPI)
    return buf.getvalue().replace("'DejaVu Sans'", "'Scanplan Sans'").replace(
        '"DejaVu Sans"', '"Scanplan Sans"').replace("DejaVu Sans", "Scanplan Sans")


def _draw_basemap(ax: Any, image: Any, scale: float) -> None:
    """The background image under everything, the map's extent kept to the flight's; the
    area (and its holes) outlined only, so the ground shows through."""
    for patch in ax.patches:
        patch.set_facecolor("none")
    flight = ax.dataLim.frozen()
    left, bottom, right, top = (v / scale for v in image.bounds)
    ax.imshow(image.rgba, extent=(left, right, bottom, top), origin="upper", zorder=0,
              interpolation="bilinear", rasterized=True, aspect="equal")
    ax.dataLim.set(flight)  # the image does not widen the map


def _draw_photos_plain(ax: Any, layout: FlightLayout, scale: float, locale: str) -> None:
    """The photo centres as plain dots (no ``[terrain]``, or no known ground under them):
    one picture at print resolution, not thousands of vector dots (``_PHOTO_DPI``)."""
    ph = layout.photos
    step = max(1, math.ceil(len(ph) / MAX_MAP_PHOTOS))
    x = np.asarray(ph["x_m"], float)[::step] / scale
    y = np.asarray(ph["y_m"], float)[::step] / scale
    label = t("frame_centres" if layout.kind == "film" else "photo_centres", locale)
    if step > 1:
        label += f" ({t('map_one_in', locale).format(k=step)})"
    ax.plot(x, y, linestyle="none", marker="o", markersize=1.6, color="#2e7d32",
            zorder=2.5, label=label, rasterized=True)


def _map_size_in(layout: FlightLayout) -> tuple[float, float]:
    """The map figure's (width, height) [in]: the page's width, a height the area (its
    strips and take-off point included) fills."""
    minx, miny, maxx, maxy = map_extent(layout)
    width_in, max_h = _MAP_SIZE_IN
    ratio = (maxy - miny) / (maxx - minx) if maxx > minx else 1.0
    return width_in, min(max(width_in * 0.85 * ratio + 1.2, 3.8), max_h)


def _svg_uri(svg: str) -> str:
    return "data:image/svg+xml;base64," + base64.b64encode(svg.encode("utf-8")).decode()


def _point_text(xy: tuple[float, float], lonlat: Any, locale: str) -> str:
    """A strip's end: latitude; longitude, or the plane coordinates of an area without a
    coordinate system (``lonlat`` None)."""
    if lonlat is None:  # a Russian surveyor reads X (north) first, then Y (east)
        first, second = (xy[1], xy[0]) if locale == "ru" else xy
        return f"{number(first, 0, locale)}; {number(second, 0, locale)}"
    lon, lat = lonlat
    return f"{number(lat, 6, locale)}; {number(lon, 6, locale)}"


def _direction(layout: FlightLayout, locale: str) -> float | str:
    """The lines' direction [°]; a crosshatch's two as words."""
    if layout.cross_direction_deg is None:
        return layout.direction_deg
    return t("geo_crosshatch", locale).format(first=number(layout.direction_deg, 1, locale),
                                              second=number(layout.cross_direction_deg, 1,
                                                            locale))


def summary_items(layout: FlightLayout, locale: str) -> list[tuple[str, Any, int]]:
    """The layout's figures as (label, value, decimals); the CRS is text."""
    film = layout.kind == "film"
    a = layout.area
    rows: list[tuple[str, Any, int]] = [
        (t("coordinate_system", locale), crs_text(layout, locale), 0),
        (t("area_km2", locale), a.area_km2, 2),  # the digits of every other document
        (t("geo_perimeter_km", locale), a.perimeter_km, 1),
        (t("geo_direction_deg", locale), _direction(layout, locale), 1),
        (t("geo_spacing_m", locale), layout.spacing_m, 1),
        (t("geo_base_m", locale), layout.base_m, 1),
        (t("n_strips", locale), len(layout.strips), 0),
        (t("geo_n_frames" if film else "geo_n_photos", locale), len(layout.photos), 0)]
    if not film and layout.notes.get("max_flight_time_min"):  # the sortie time known
        rows.append((t("geo_n_sorties", locale), len(layout.sorties), 0))
    rows.append((t("geo_flight_km", locale), layout.flight_length_m / 1000, 1))
    if layout.notes.get("takeoff_xy_m") is not None:
        rows.append((t("geo_transit_km", locale),
                     float(layout.notes.get("transit_m", 0.0)) / 1000, 1))
    if layout.flight_time_s:
        rows.append((t("geo_flight_min", locale), layout.flight_time_s / 60, 0))
    return rows


def summary_rows(layout: FlightLayout, locale: str) -> list[tuple[str, str]]:
    """:func:`summary_items` as text (the PDF)."""
    return [(label, value if isinstance(value, str) else number(float(value), d, locale))
            for label, value, d in summary_items(layout, locale)]


def strips_table(layout: FlightLayout, locale: str, limit: int | None = MAX_TABLE_STRIPS
                 ) -> dict[str, Any]:
    """The strips as table rows (the first ``limit``), with their header and a note; the
    numeric columns first (``numeric``: how many)."""
    film = layout.kind == "film"
    ends = strip_ends_lonlat(layout)
    where = t("strip_lat_lon" if ends is not None else "strip_xy", locale)
    head = [t("strip", locale), t("sortie", locale),
            t("strip_frames" if film else "strip_photos", locale), t("strip_length_m", locale),
            t("strip_parts", locale), f"{t('strip_start', locale)} ({where})",
            f"{t('strip_end', locale)} ({where})"]
    shown = layout.strips if limit is None else layout.strips[:limit]
    rows = [[str(s.number), s.sorties_text, number(s.photos, 0, locale),
             number(s.length_m, 0, locale), str(max(s.segments, len(s.parts) or 1)),
             _point_text(s.start_xy_m, None if ends is None else ends[k][0], locale),
             _point_text(s.end_xy_m, None if ends is None else ends[k][1], locale)]
            for k, s in enumerate(shown)]
    if film:  # an aerial survey has no sorties of a battery
        head = [h for k, h in enumerate(head) if k != 1]
        rows = [[c for k, c in enumerate(r) if k != 1] for r in rows]
    notes = [] if film else [continued_note(layout.strips, locale)]
    if len(shown) < len(layout.strips):
        notes.append(t("strips_more", locale).format(shown=len(shown),
                                                     total=len(layout.strips)))
    return {"head": head, "rows": rows, "note": " ".join(n for n in notes if n),
            "numeric": 4 if film else 5}


def continued_note(strips: Any, locale: str) -> str:
    """Where a later sortie takes over a strip (the battery changes mid-strip): the strip,
    the sortie and its first photo there; "" when every strip is flown in one sortie."""
    items = [t("strip_continued_item", locale).format(
        strip=s.number, sortie=sortie, photo=number(photo, 0, locale))
        for s in strips for sortie, photo in s.continued]
    return t("strips_continued", locale).format(list="; ".join(items)) if items else ""


def _control_of(spec: Any) -> Any:
    """The GCPs and checkpoints of a specification's ``[control]``, or None."""
    control = getattr(spec, "control", None)
    return control.points if control is not None else None


def _background_note(spec: Any, layout: FlightLayout, kind: str, locale: str) -> str:
    """The map's background named as its attribution asks (``[map] basemap_attribution``,
    else the file's name); empty without a background (none asked, or no tile came)."""
    m = getattr(getattr(spec, "project", None), "map", None)
    if not layout.area.georeferenced or m is None:
        return ""
    if getattr(m, "basemap_url", None):
        if kind not in (getattr(spec, "backgrounds", None) or {}):
            return t("map_background_none", locale).format(host=tile_host(m.basemap_url))
        return t("map_background", locale).format(source=m.basemap_attribution)
    if getattr(m, "basemap", None) is None:
        return ""
    return t("map_background", locale).format(source=m.basemap_attribution or m.basemap.name)


def geo_views(spec: Any, locale: str) -> list[dict[str, Any]]:
    """The PDF's map pages: one per flight layout of ``spec`` (UAV first, then film).

    Each view: ``title``, ``map`` (an SVG ``data:`` URI, or None for an abstract block),
    ``caption`` (the CRS), ``rows`` (summary), ``strips`` (table), ``notes``.
    """
    views = []
    for _kind, layout in _exports.spec_layouts(spec):
        film = layout.kind == "film" or _kind == "film"
        notes = []
        if not layout.feasible:
            notes.append(t("geo_not_feasible", locale).format(reason=layout.reason or ""))
        if not layout.area.georeferenced:
            notes.append(t("geo_not_georeferenced", locale))
        elif "altitude_mode" in layout.notes and not ground_known(spec, _kind):
            notes.append(t("map_ground_unknown", locale))
        elif _exports.files_beside(spec, layout):
            items = [t("geo_file_flight", locale),
                     t("geo_file_frames" if film else "geo_file_photos", locale)]
            if not film and _exports.mission_options(spec, layout) is not None:
                items.insert(0, t("geo_file_mission", locale))
            notes.append(t("geo_files_note", locale).format(items="; ".join(items)))
        background = _background_note(spec, layout, _kind, locale)
        if background:
            notes.append(background)
        if layout.area.georeferenced and len(layout.photos) > MAX_SHEET_PHOTOS:
            notes.append(t("geo_photos_elsewhere" if _exports.files_beside(spec, layout)
                           else "geo_photos_too_many", locale).format(
                n=number(len(layout.photos), 0, locale)))
        views.append({
            "title": t("map_title_film" if film else "map_title", locale)
            if layout.area.georeferenced else t("geo_summary", locale),
            "map": _svg_uri(map_svg(layout, locale, map_terrain(spec, _kind, layout),
                                    map_basemap(spec, layout, _kind),
                                    None if film else _control_of(spec)))
            if layout.area.georeferenced else None,
            "caption": crs_text(layout, locale),
            "rows": summary_rows(layout, locale),
            "strips": strips_table(layout, locale),
            "notes": notes,
        })
    return views

"""Plain-text rendering of results for the terminal (aligned tables, wrapped notes)."""

from __future__ import annotations

import math
import os
import textwrap
from collections.abc import Callable, Sequence
from typing import Any

import numpy as np

from ..i18n.labels import LABELS, t
from ..i18n.labels_geo import crs_name
from ..i18n.messages import localize, scale_text
from ..i18n.numbers import Numbers
from .jsondoc import scale_value
from .tablewords import COMPARISON_LABELS
from .views import ResultTables, Row, Table, constraint_title

__all__ = ["format_plan_result", "table", "text_table", "volume_text"]


def table(rows: Sequence[Sequence[str]], *, align: str = "", gap: int = 2) -> str:
    """Align rows of cells; ``align`` holds 'l'/'r' per column (default: first l, rest r)."""
    widths = [max(len(r[i]) for r in rows if i < len(r)) for i in range(max(map(len, rows)))]
    out = []
    for r in rows:
        cells = []
        for i, cell in enumerate(r):
            a = align[i] if i < len(align) else ("l" if i == 0 else "r")
            cells.append(cell.ljust(widths[i]) if a == "l" else cell.rjust(widths[i]))
        out.append((" " * gap).join(cells).rstrip())
    return "\n".join(out)


def text_table(tbl: Table, *, label: Callable[[Row], str],
               cell: Callable[[Row, int, Any], str], unit: Callable[[Row], str] | None = None,
               head: Sequence[str] | None = None, align: str = "",
               columns: Sequence[int] | None = None,
               after: Callable[[Row], str] | None = None) -> str:
    """A report table (:class:`scanplan.reports.views.Table`) as aligned text: the one
    layout of the terminal's tables.

    Parameters
    ----------
    tbl : Table
        The table, built once per result.
    label : callable
        A row's label in the reader's language.
    cell : callable
        ``(row, i, value)`` → the text of value ``i`` of the row.
    unit : callable, optional
        A row's unit in words (a column after the label); none when not given.
    head : sequence of str, optional
        The heading row.
    align : str
        ``"l"`` / ``"r"`` per column (:func:`table`).
    columns : sequence of int, optional
        The columns shown, in order (default: all).
    after : callable, optional
        A last column after the values (a row's unit there, not after the label).

    Returns
    -------
    str
    """
    rows = [list(head)] if head is not None else []
    for r in tbl.rows:
        shown = range(len(r.values)) if columns is None else columns
        rows.append([label(r), *([unit(r)] if unit is not None else []),
                     *(cell(r, i, r.values[i]) for i in shown),
                     *([after(r)] if after is not None else [])])
    return table(rows, align=align)


_EN = Numbers("en")  # English numbers (scanplan.reports.terminal writes `scan` and `uav`)


def _num(x: float | None, digits: int = 1) -> str:
    return _EN.fixed(x, digits)


def _um(x: float | None) -> str:
    """A pixel [µm]: one decimal, or two significant digits below 1 µm (never ``0.0``)."""
    return _EN.um(x)


def _interval(seconds: float) -> str:
    """The photo interval; none at ground speed 0 (a hovering UAV), never ``inf``."""
    return f"{seconds:.2f} s" if math.isfinite(seconds) else "— (ground speed ≈ 0)"


def _wrap(text: str, indent: str) -> str:
    return textwrap.fill(text, width=96, initial_indent=indent,
                         subsequent_indent=" " * len(indent))


class _Terminal:
    """The terminal summary's words in one language: ``term_<key>`` of the label
    catalogue, else the concept key ``<key>`` the other renderers share (``um``, ``km``)."""

    def __init__(self, locale: str) -> None:
        self.locale = locale

    def __getitem__(self, key: str) -> str:
        own = f"term_{key}"
        return t(own if own in LABELS[self.locale] else key, self.locale)

    def get(self, key: str, default: str) -> str:
        """The word ``key``, or ``default`` when the catalogue has none."""
        return LABELS[self.locale].get(f"term_{key}", default)


def _n(x: float | None, digits: int, loc: str, group: bool = False) -> str:
    """A number in the locale's convention (decimal comma and thin grouping in Russian)."""
    return Numbers(loc).num(x, digits) if group else Numbers(loc).fixed(x, digits)


def _um_loc(x: float | None, loc: str) -> str:
    """A pixel [µm] as :func:`_um` writes it, with the locale's decimal separator."""
    return Numbers(loc).um(x)


def _g(x: float, loc: str) -> str:
    return Numbers(loc).short(x)


def _sc(x: float, loc: str) -> str:
    return scale_text(x, loc)


def format_plan_result(result: Any, locale: str | None = None,
                       tables: ResultTables | None = None) -> str:
    """The concise terminal summary of ``scanplan plan``, in the project's language
    (``[project] locale``) unless ``locale`` is given.

    Parameters
    ----------
    result : PlanResult
        The specification.
    locale : {"en", "ru"}, optional
        The language (default: the project's).
    tables : ResultTables, optional
        The result's tables when a view of it already holds them (``view.tables``): the
        summary lays out the same records as the documents; built here otherwise.

    Returns
    -------
    str
    """
    meta = result.meta
    loc = locale or (meta.locale if meta.locale in LABELS else "en")
    T = _Terminal(loc)

    def cname(cid: str) -> str:
        return constraint_title(cid, loc)

    if tables is None:
        tables = ResultTables.of_jobs(result.film.job if result.film else None,
                                      result.uav.job if result.uav else None, result)
    lines = _plan_heading(result, loc, T)
    lines += [_wrap(t, "") for t in format_terrain(result, loc)]
    if result.film:
        lines += _film_summary(tables["spec_film"], loc, T, cname)
    if result.uav:
        lines += _uav_summary(tables["spec_uav"], result.uav.job.plan.inputs.platform, loc, T,
                              cname)
    if result.comparison:
        lines += _comparison_lines(result, loc, T, tables)
    if getattr(result, "control", None) is not None:
        lines += _control_lines(tables, loc)
    from .design import design_text_lines

    lines += [textwrap.fill(x.strip(), width=96, initial_indent="  ", subsequent_indent="    ")
              if x.startswith("  ") else x for x in design_text_lines(result, loc)]
    if result.warnings:
        lines += _warning_lines(result, loc, T, tables)
    return "\n".join(lines)


def _plan_heading(result: Any, loc: str, T: _Terminal) -> list[str]:
    """The project, map scale and relief interval, the parties, the area and its flight
    lines."""
    meta = result.meta
    inp_map = result.project.map
    lines = [f"{meta.project} — {T['map']} {_sc(scale_value(inp_map.scale), loc)}, "
             f"{T['relief']} {_g(inp_map.relief_interval_m, loc)} {T['m']}"]
    if meta.customer or meta.contractor:
        lines.append(", ".join(x for x in (f"{T['customer']} {meta.customer}"
                                           if meta.customer else "",
                                           f"{T['contractor']} {meta.contractor}"
                                           if meta.contractor else "") if x))
    area = getattr(result, "area", None)
    if area is not None and area.georeferenced:
        lines.append(format_area(area, loc))
        for kind, lay in result.layouts.items():
            scale = (_sc(result.film.recommended.photo_scale, loc)
                     if kind == "film" and result.film.recommended else "")
            lines.append(format_layout(lay, scale, loc))
    return lines


def _film_summary(tbl: Table, loc: str, T: _Terminal, cname: Any) -> list[str]:
    """The film block (the ``spec_film`` table): photo scale, scan pixel, binding
    constraint, frames, the reason."""
    r = {row.key: row for row in tbl.rows}
    lines = ["", T["film"]]
    reason = _wrap(localize(r["reason"].value, loc), "  ")
    if "photo_scale" not in r:
        return [*lines, reason]
    px = (f"{_um_loc(r['scan_pixel_um'].value, loc)} {T['um']}"
          + (f" → {T['scanner_step']} {_g(r['scanner_pixel_um'].value, loc)} {T['um']}"
             if r.get("scanner_pixel_um") and r["scanner_pixel_um"].value else ""))
    binding, scale = r["binding"].value, r["photo_scale"]
    rows = [[f"  {T['photo_scale_archive' if 'archive' in scale.flags else 'photo_scale']}",
             _sc(scale.value, loc)],
            [f"  {T['scan_pixel']}", px],
            [f"  {T['binding']}", f"{binding} ({cname(binding)})"],
            [f"  {T['recognition']}", _n(r["probability"].value, 2, loc)],
            [f"  {T['frame']}", f"{_n(r['frame_megabytes'].value, 0, loc, True)} {T['mb']}"]]
    if "frames" in r:
        frames, strips = r["frames"].value, r["strips"].value
        gb = _n(r["scanned_gb"].value, 1, loc, True)
        rows.append([f"  {T['frames']}",
                     f"{frames} ({strips} {T['strips']}), {gb} {T['gb']} {T['scanned']}"
                     if loc == "en" else
                     f"{frames} ({T['strips']}: {strips}), {T['scanned']} {gb} {T['gb']}"])
    return [*lines, table(rows, align="ll"), reason]


def _comparison_lines(result: Any, loc: str, T: _Terminal, tables: ResultTables) -> list[str]:
    """Film and digital camera side by side (the ``comparison`` table; counts grouped as
    the documents group them)."""
    aircraft = bool(result.uav) and result.uav.job.plan.inputs.platform == "aircraft"
    numbers = Numbers(loc)

    def quantity(r: Row) -> str:  # the documents' word
        key = COMPARISON_LABELS.get(r.key)
        return "  " + (t(key, loc) if key else r.fields["quantity"])

    def cell(r: Row, i: int, x: Any) -> str:
        return "—" if x is None else numbers.num(x, r.digits if r.digits is not None else 3)

    def unit(r: Row) -> str:
        return {"m": T["m"], "GB": T["gb"]}.get(r.unit, r.unit)

    head = [f"  {T['quantity']}", T["film_col"], T["digital_col" if aircraft else "uav_col"],
            T["unit"]]
    text = text_table(tables["comparison"], label=quantity, cell=cell, head=head,
                      align="lrrl", after=unit)
    return ["", T["side_by_side_aircraft" if aircraft else "side_by_side"], text]


def _control_lines(tables: ResultTables, loc: str) -> list[str]:
    """The ground control: counts, figures and the error budget at best, and the control's
    precision against the target (the ``control`` and ``control_checks`` tables)."""
    from .controlwords import check_rows, summary_rows

    rows = summary_rows(tables, loc)
    width = max(len(label) for label, _, _ in rows)
    lines = ["", t("control_points", loc) + ":"]
    lines += [f"  {label:<{width}}  {value}" for label, value, _ in rows]
    lines.append(f"  {t('control_check', loc)}:")
    for rule, axis, ratio, required, ok, _ in check_rows(tables, loc):
        lines.append(f"    {rule} ({axis}): {ratio} / {required} — {ok}")
    return lines


def _warning_lines(result: Any, loc: str, T: _Terminal, tables: ResultTables) -> list[str]:
    """The warnings (``!``) and notes (``i``) with their codes (the ``spec_warnings``
    table)."""
    lines = ["", T["warnings"]]
    for r in tables["spec_warnings"].rows:
        mark = "!" if "warning" in r.flags else "i"
        message = r.values[0]
        text = localize(message, loc)
        if loc == "ru":  # ids by their names, as the Russian documents show them
            from .wording import display_message

            ns = (result.film or result.uav).job.norm_set
            text = display_message(message, ns, loc)
        lines.append(_wrap(text + code_tag(r.key, loc), f"  {mark} "))
    return lines


_AREA_TEXT = {
    "en": {"area": "Area", "perimeter": "perimeter", "lines": "Flight lines", "at": "at scale",
           "direction": "direction", "strips": ("strip", "strips"), "photos": ("photo", "photos"),
           "turns": "turns", "sorties": "sorties", "not_feasible": "NOT FEASIBLE",
           "km2": "km²", "km": "km", "min": "min"},
    "ru": {"area": "Участок", "perimeter": "периметр", "lines": "Маршруты", "at": "в масштабе",
           "direction": "направление", "strips": ("маршрут", "маршрута", "маршрутов"),
           "photos": ("снимок", "снимка", "снимков"),
           "turns": "развороты", "sorties": "вылетов", "not_feasible": "НЕВЫПОЛНИМО",
           "km2": "км²", "km": "км", "min": "мин"},
}


def code_tag(code: str, locale: str) -> str:
    """`` [code]`` after a warning in the English terminal (a word to search the docs for);
    nothing in Russian, whose reader gets no English identifiers."""
    return "" if locale == "ru" else f" [{code}]"


def area_source(area: Any, locale: str = "en") -> str:
    """Where the area comes from, in ``locale``: the file and feature, an inline polygon, or
    the rectangle."""
    if locale != "ru":
        return area.source
    if area.source_file:
        return (f"{area.source_file}, объект «{area.source_feature}»"
                + (f" слоя «{area.source_layer}»" if area.source_layer else ""))
    if not area.georeferenced:
        return area.source.replace("rectangle", "прямоугольник").replace(" m", " м")
    return "полигон, заданный в файле проекта"


def format_area(area: Any, locale: str = "en") -> str:
    """One line: where the area comes from, its size, perimeter and planning CRS."""
    T = _AREA_TEXT[locale]
    name = crs_name(area.plan_crs_name or "", locale) or (
        area.plan_crs if len(area.plan_crs or "") < 40 else "")  # the code; a WKT is not shown
    crs = f", {name}" if area.plan_crs_name and name else ""
    return _wrap(f"{T['area']}: {area_source(area, locale)} — "
                 f"{_n(area.area_km2, 2, locale, True)} {T['km2']}, {T['perimeter']} "
                 f"{_n(area.perimeter_km, 1, locale, True)} {T['km']}{crs}", "")


def format_layout(layout: Any, scale: str = "", locale: str = "en") -> str:
    """One line per layout: direction, strips, photos, length (turns), time, sorties; the
    reason when it cannot be flown. Photo centres are in the exported files, not here."""
    from ..i18n.messages import plural

    T = _AREA_TEXT[locale]
    head = f"{T['lines']}" + (f" {T['at']} {scale}" if scale else "")
    n_photos = int(layout.notes.get("photos", len(layout.photos)))
    text = (f"{head}: {T['direction']} {_n(layout.direction_deg, 1, locale)}°, "
            f"{len(layout.strips)} {plural(len(layout.strips), T['strips'], locale)}, "
            f"{_n(n_photos, 0, locale, True)} {plural(n_photos, T['photos'], locale)}, "
            f"{_n(layout.flight_length_m / 1000, 1, locale, True)} {T['km']} "
            f"({T['turns']} {_n(layout.turn_length_m / 1000, 1, locale, True)} {T['km']})")
    if layout.flight_time_s:
        text += f", {_n(layout.flight_time_s / 60, 0, locale, True)} {T['min']}"
    if layout.kind == "uav" and layout.notes.get("max_flight_time_min"):  # sortie time known
        text += f", {T['sorties']}:\0{len(layout.sorties)}"  # kept on one line
    if not layout.feasible:
        text += f" — {T['not_feasible']}: {localize(layout.reason, locale)}"
    return _wrap(text, "").replace("\0", " ")


def _uav_summary(tbl: Table, platform: str, loc: str, T: _Terminal,
                 cname: Any) -> list[str]:
    """The UAV part of :func:`format_plan_result` (the ``spec_uav`` table)."""
    r = {row.key: row for row in tbl.rows}
    lines = ["", T["aircraft" if platform == "aircraft" else "uav"]]
    reason = _wrap(localize(r["reason"].value, loc), "  ")
    height = r["recommended_height_m"]
    if height.value is None:
        return [*lines, reason]
    rows = _uav_heights(r, loc, T, cname)
    rows += _uav_flight_rows(r, loc, T)
    lines.append(table(rows, align="ll"))
    lines.append(reason)
    return lines


def _uav_heights(r: dict[str, Row], loc: str, T: _Terminal, cname: Any) -> list[list[str]]:
    """The heights, the binding constraint, the GSD, the height accuracy, the recognition."""
    height = r["recommended_height_m"]
    tol = height.fields["tolerance_pct"]
    m = T["m"]
    flown = r.get("max_flown_height_m")
    binding = r["binding"].value if "binding" in r else None
    rows = [[f"  {T['height']}", f"{_g(height.value, loc)} {m}"
             + (f" ({T['flown']} {_g(height.fields['flown'], loc)} {m}, +{_g(tol, loc)} %)"
                if tol else "")],
            [f"  {T['max_height']}", f"{_n(r['max_height_m'].value, 0, loc)} {m}"
             + (f" ({T['flown']} {_n(flown.value, 0, loc)} {m})"
                if tol and flown is not None else "")
             + f" ({binding} {cname(binding)})" if binding else "—"],
            [f"  {T['gsd']}", f"{_n(r['gsd_m'].value, 3, loc)} {m} / "
             f"{_n(r['ground_resolution_m'].value, 3, loc)} {m} (L/GSD "
             f"{_n(r['l_over_gsd'].value, 2, loc)})"]]
    if "constraints_max_height_m" in r:
        rows.append([f"  {T['no_ceiling']}",
                     f"{_n(r['constraints_max_height_m'].value, 0, loc)} {m} "
                     f"{T['no_ceiling_note']}"])
    if "sigma_z" in r:
        sz = r["sigma_z"]
        rows.append([f"  {T['sigma_z']}",
                     f"{_n(sz.value, 3, loc)} {m} {T['at']} {_g(sz.fields['at'], loc)} {m} "
                     f"({T['required_rms']} {_g(sz.fields['required'], loc)} {m} {T['rms']})"])
    if "recognition" in r:
        rec = r["recognition"]
        name = (rec.fields["name_ru"] or rec.fields["name"]) if loc == "ru" \
            else rec.fields["name"]
        rows.append([f"  {T['recognition']}", f"{_n(rec.value, 2, loc)} ({name}, "
                     f"{_g(rec.fields['size_m'], loc)} {m})"])
    return rows


def _uav_flight_rows(r: dict[str, Row], loc: str, T: _Terminal) -> list[list[str]]:
    """The overlaps, the photo interval, the photos, the flight, the volume, the blur."""
    m = T["m"]
    interval = r["photo_interval"].value
    rows = [[f"  {T['overlaps']}",
             f"{_g(r['forward_overlap_pct'].value, loc)} % / "
             f"{_g(r['side_overlap_pct'].value, loc)} % "
             f"— {_n(r['base'].value, 1, loc)} {m} / {_n(r['line_spacing'].value, 1, loc)} {m}"],
            [f"  {T['interval']}",
             _interval(interval) if loc == "en" else
             (f"{_n(interval, 2, loc)} {T['s']}"
              if math.isfinite(interval) else "— (путевая скорость ≈ 0)")]]
    if "photos" in r:
        rows.append([f"  {T['photos']}",  # grouped as the flight-lines line and the PDF
                     f"{_n(r['photos'].value, 0, loc, True)} / "
                     f"{_n(r['strips'].value, 0, loc, True)}"])
        minutes = r["flight_time_min"].value
        rows.append([f"  {T['flight']}", f"{_n(r['flight_length_km'].value, 1, loc)} {T['km']}"
                     + (f", {_n(minutes, 0, loc)} {T['min']}" if minutes else "")])
        if "data_volume_gb" in r:
            rows.append([f"  {T['volume']}", volume_text(
                r["data_volume_gb"].value, r["data_volume_jpeg_gb"].value, loc)])
    rows.append([f"  {T['blur']}",
                 f"{T['exposure']} ≤ 1/{math.ceil(1 / r['max_exposure_s'].value):d} "
                 f"{T['s']} {T['or_speed']} ≤ {_n(r['max_speed_ms'].value, 1, loc)} {T['ms']}"])
    return rows


_BATCH_HEADER = ["project", "map", "film: photo scale", "scan µm", "digital camera: height m",
                 "max m", "binding"]


def batch_row(path: str, r: Any) -> list[str]:
    """The row of one project in :func:`batch_table` (text only: a batch keeps these, not
    the projects' results)."""
    f, u = r.film, r.uav
    rec = f.recommended if f else None
    return [
        os.path.basename(path), f"1:{r.project.map.scale}",
        (f"1:{scale_value(rec.photo_scale)}" if rec else "none") if f else "—",
        (_um(rec.scanner_pixel_um or rec.scan_pixel_um) if rec else "—") if f else "—",
        _num(u.recommended_height_m, 0) if u else "—",
        _num(u.max_height_m, 0) if u else "—",
        " / ".join(x for x in ((rec.binding if rec else "") if f else "",
                               (u.job.plan.binding or "") if u else "") if x) or "—"]


def batch_table(rows: list[list[str]], failed: list[tuple[str, str]]) -> str:
    """One table for a batch of projects: the rows of :func:`batch_row`, then the
    failures."""
    out = table([_BATCH_HEADER, *rows], align="llrrrrl")
    if failed:
        out += f"\n{len(rows)} planned, {len(failed)} failed:"
        for path, msg in failed:
            out += "\n" + _wrap(f"{os.path.basename(path)}: {msg}", "  ! ")
    return out


def batch_summary(done: list[tuple[str, Any]], failed: list[tuple[str, str]]) -> str:
    """One table for a batch of projects: the headline of each, then the failures."""
    return batch_table([batch_row(path, r) for path, r in done], failed)


def volume_text(gigabytes: float, jpeg_gigabytes: float, loc: str = "en") -> str:
    """``163.5 GB uncompressed (JPEG ≈ 18.2 GB at 9:1)`` in the locale's words and numbers.

    Parameters
    ----------
    gigabytes, jpeg_gigabytes : float
        The uncompressed volume and its JPEG estimate [GB].
    loc : {"en", "ru"}

    Returns
    -------
    str
    """
    from ..core.flight import JPEG_COMPRESSION_RATIO

    full = _n(gigabytes, 1, loc, True)
    jpeg = _n(jpeg_gigabytes, 1, loc, True)
    ratio = _g(JPEG_COMPRESSION_RATIO, loc)
    if loc == "ru":
        return f"{full} ГБ без сжатия (JPEG ≈ {jpeg} ГБ при {ratio}:1)"
    return f"{full} GB uncompressed (JPEG ≈ {jpeg} GB at {ratio}:1)"


def project_warnings(path: str, r: Any) -> str:
    """The warnings of one project of a batch under its file name ("" if none)."""
    if not r.warnings:
        return ""
    out = ["", f"Warnings — {os.path.basename(path)}:"]
    for w in r.warnings:
        mark = "!" if w.severity == "warning" else "i"
        out.append(_wrap(w.text(r.meta.locale) + code_tag(w.code, r.meta.locale), f"  {mark} "))
    return "\n".join(out)


def batch_warnings(done: list[tuple[str, Any]]) -> str:
    """The warnings of each project of a batch, under its file name ("" if none)."""
    return "\n".join(t for t in (project_warnings(p, r) for p, r in done) if t)


_TERRAIN_TEXT = {
    "en": {"head": "Terrain", "dem": "DEM", "range": "ground given as a range",
           "ground": "ground", "under": "under the photos", "mode": "altitude",
           "constant": "constant", "strip": "per strip", "follow": "following the terrain",
           "agl": "height above ground", "at_photo": "largest at photo", "strip_n": "strip",
           "max": "maximum height over the relief", "film": "Terrain (film): photo scale",
           "binds": "binds: scan pixel", "frame": "frame", "m": "m", "um": "µm",
           "lowest": "the frame over the lowest ground", "flat": "on flat ground",
           "spec": "the specification's scan pixel is the binding frame's", "AMSL": "AMSL",
           "film_alt": "flight altitude"},
    "ru": {"head": "Рельеф", "dem": "ЦМР", "range": "отметки заданы диапазоном",
           "ground": "отметки", "under": "под снимками", "mode": "высота полёта",
           "constant": "постоянная", "strip": "по маршрутам", "follow": "с огибанием рельефа",
           "agl": "высота над рельефом", "at_photo": "наибольшая у снимка",
           "strip_n": "маршрут", "max": "максимальная высота с учётом рельефа",
           "film": "Рельеф (плёнка): масштаб снимков", "binds": "определяет: пиксель",
           "frame": "снимок", "m": "м", "um": "мкм",
           "lowest": "снимок над наинизшей точкой", "flat": "для плоской местности",
           "spec": "пиксель сканирования назначен по определяющему снимку",
           "AMSL": "над уровнем моря", "film_alt": "высота полёта"},
}


def format_terrain(result: Any, locale: str = "en") -> list[str]:
    """Lines on the terrain (issue 12): the ground, the altitude mode, the AGL range and
    the worst photo, the maximum height over the relief; for film the local photo scales
    and the binding frame. Nothing without ``[terrain]``."""
    T = _TERRAIN_TEXT[locale if locale in _TERRAIN_TEXT else "en"]
    out: list[str] = []
    uav = getattr(result, "uav", None)
    tr = getattr(uav, "terrain", None) if uav is not None else None
    if tr is not None:
        d = tr.summary()
        src = (f"{T['dem']} {d['dem']} ({d['dem_crs']})" if d["source"] == "dem"
               else T["range"])
        alts = _altitudes(tr.layout.photos["altitude_m"], locale)
        text = (f"{T['head']}: {src}, {T['ground']} {_n(d['ground_min_m'], 1, locale)}–"
                f"{_n(d['ground_max_m'], 1, locale)} {T['m']} {T['under']}; {T['mode']} "
                f"{T[tr.mode]} {alts} {T['m']} ({T.get(tr.altitude_frame, tr.altitude_frame)}); "
                f"{T['agl']} "
                f"{_n(d['agl_min_m'], 0, locale)}–{_n(d['agl_max_m'], 0, locale)} {T['m']}"
                # a photo is named only over a DEM: with a range, no photo's ground is known
                + (f" ({T['at_photo']} {tr.worst_resolution_photo})" if d["source"] == "dem"
                   else ""))
        if tr.max_height_m is not None:
            text += (f"; {T['max']} {_n(tr.max_height_m, 0, locale)} {T['m']}"
                     + (f" ({tr.binding})" if tr.binding else ""))
        out.append(text)
    film = getattr(result, "film", None)
    ft = getattr(film, "terrain", None) if film is not None else None
    if ft is not None:
        who = (f"{T['frame']} {ft.binding_frame} ({T['strip_n']} {ft.binding_strip})"
               if ft.ground_known else T["lowest"])
        out.append(f"{T['film']} {_sc(round(ft.mc_min), locale)} … "
                   f"{_sc(round(ft.mc_max), locale)}; {who} {T['binds']} "
                   f"{_um_loc(ft.scan_pixel_um, locale)} {T['um']} ({ft.binding}), {T['flat']} "
                   f"{_um_loc(ft.scan_pixel_planned_um, locale)} {T['um']} "
                   f"({ft.binding_planned or '—'})"
                   + (f"; {T['spec']}" if getattr(film, "flat", None) is not None else "")
                   + _film_altitude(ft, T, locale))
    return out


def _altitudes(alt: Any, locale: str) -> str:
    """The flight altitudes of the photos [m]: ``235``, or ``233–295`` when they differ by
    more than half a metre; ``—`` without photos."""
    alt = np.asarray(alt, dtype=float)
    if not alt.size:
        return _n(None, 0, locale)
    lo, hi = float(alt.min()), float(alt.max())
    return f"{_n(lo, 0, locale)}–{_n(hi, 0, locale)}" if hi - lo > 0.5 else _n(hi, 0, locale)


def _film_altitude(ft: Any, T: dict[str, str], locale: str) -> str:
    """``; flight altitude 830 m`` of the frames over the relief ("" without frames)."""
    if not len(ft.altitude_m):
        return ""
    return f"; {T['film_alt']} {_altitudes(ft.altitude_m, locale)} {T['m']}"

"""The terminal's lines on the area, its flight lines and the terrain under them."""

from __future__ import annotations

from typing import Any

import numpy as np

from ...i18n.labels_geo import crs_name
from ...i18n.messages import plural
from ..formatter import Formatter, formatter
from .layout import wrap

__all__ = ["area_source", "format_area", "format_layout", "format_terrain"]


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


def _forms(f: Formatter, key: str) -> list[str]:
    """A noun's forms after a count (``strip|strips``), as the catalogue gives them."""
    return f.cli(key).split("|")


def format_area(area: Any, locale: str = "en") -> str:
    """One line: where the area comes from, its size, perimeter and planning CRS."""
    f = formatter(locale)
    name = crs_name(area.plan_crs_name or "", f.locale) or (
        area.plan_crs if len(area.plan_crs or "") < 40 else "")  # the code; a WKT is not shown
    crs = f", {name}" if area.plan_crs_name and name else ""
    return wrap(f"{f.cli('area_place')}: {area_source(area, f.locale)} — "
                f"{f.num(area.area_km2, 2)} {f.cli('km2')}, {f.cli('perimeter')} "
                f"{f.num(area.perimeter_km, 1)} {f.cli('km')}{crs}", "")


def format_layout(layout: Any, scale: str = "", locale: str = "en") -> str:
    """One line per layout: direction, strips, photos, length (turns), time, sorties; the
    reason when it cannot be flown. Photo centres are in the exported files, not here."""
    f = formatter(locale)
    head = f.cli("flight_lines") + (f" {f.cli('at_scale')} {scale}" if scale else "")
    n_photos = int(layout.notes.get("photos", len(layout.photos)))
    n_strips = len(layout.strips)
    lines = f"{f.cli('direction')} {f.fixed(layout.direction_deg, 1)}°"
    cross = getattr(layout, "cross_direction_deg", None)  # a crosshatch's second pass
    if cross is not None:
        lines = f.cli("crosshatch", first=f.fixed(layout.direction_deg, 1),
                      second=f.fixed(cross, 1))
    text = (f"{head}: {lines}, "
            f"{n_strips} {plural(n_strips, _forms(f, 'strip_forms'), f.locale)}, "
            f"{f.num(n_photos, 0)} {plural(n_photos, _forms(f, 'photo_forms'), f.locale)}, "
            f"{f.num(layout.flight_length_m / 1000, 1)} {f.cli('km')} "
            f"({f.cli('turns')} {f.num(layout.turn_length_m / 1000, 1)} {f.cli('km')})")
    if layout.flight_time_s:
        text += f", {f.num(layout.flight_time_s / 60, 0)} {f.cli('min')}"
    if layout.kind == "uav":
        text += f", {f.cli('sorties_n')}:\0{len(layout.sorties)}"  # kept on one line
    if not layout.feasible:
        text += f" — {f.cli('not_feasible')}: {f.text(layout.reason)}"
    return wrap(text, "").replace("\0", " ")


def format_terrain(result: Any, locale: str = "en") -> list[str]:
    """Lines on the terrain: the ground, the altitude mode, the AGL range and the worst
    photo, the maximum height over the relief; for film the local photo scales and the
    binding frame. Nothing without ``[terrain]``."""
    f = formatter(locale)
    out: list[str] = []
    uav = getattr(result, "uav", None)
    tr = getattr(uav, "terrain", None) if uav is not None else None
    m = f.cli("m")
    if tr is not None:
        d = tr.summary()
        src = (f"{f.cli('dem')} {d['dem']} ({d['dem_crs']})" if d["source"] == "dem"
               else f.cli("ground_as_range"))
        alts = _altitudes(tr.layout.photos["altitude_m"], f)
        frame = f.cli_get(f"frame_{tr.altitude_frame}", tr.altitude_frame)
        text = (f"{f.cli('terrain')}: {src}, {f.cli('ground_heights')} "
                f"{f.fixed(d['ground_min_m'], 1)}–{f.fixed(d['ground_max_m'], 1)} {m} "
                f"{f.cli('under_photos')}; {f.cli('altitude_mode')} "
                f"{f.cli('altitude_' + tr.mode)} {alts} {m} ({frame}); "
                f"{f.cli('height_above_ground')} "
                f"{f.fixed(d['agl_min_m'], 0)}–{f.fixed(d['agl_max_m'], 0)} {m}"
                # a photo is named only over a DEM: with a range, no photo's ground is known
                + (f" ({f.cli('largest_at_photo')} {tr.worst_resolution_photo})"
                   if d["source"] == "dem" else ""))
        if tr.max_height_m is not None:
            text += (f"; {f.cli('max_over_relief')} {f.fixed(tr.max_height_m, 0)} {m}"
                     + (f" ({tr.binding})" if tr.binding else ""))
        out.append(text)
    film = getattr(result, "film", None)
    ft = getattr(film, "terrain", None) if film is not None else None
    if ft is not None:
        um = f.cli("um")
        who = (f"{f.cli('frame')} {ft.binding_frame} ({f.cli('strip')} {ft.binding_strip})"
               if ft.ground_known else f.cli("frame_lowest_ground"))
        out.append(f"{f.cli('terrain_film_scale')} {f.scale(round(ft.mc_min))} … "
                   f"{f.scale(round(ft.mc_max))}; {who} {f.cli('binds_scan_pixel')} "
                   f"{f.um(ft.scan_pixel_um)} {um} ({ft.binding}), {f.cli('on_flat_ground')} "
                   f"{f.um(ft.scan_pixel_planned_um)} {um} ({ft.binding_planned or '—'})"
                   + (f"; {f.cli('scan_pixel_of_binding_frame')}"
                      if getattr(film, "flat", None) is not None else "")
                   + _film_altitude(ft, f))
    return out


def _altitudes(alt: Any, f: Formatter) -> str:
    """The flight altitudes of the photos [m]: ``235``, or ``233–295`` when they differ by
    more than half a metre; ``—`` without photos."""
    alt = np.asarray(alt, dtype=float)
    if not alt.size:
        return f.fixed(None, 0)
    lo, hi = float(alt.min()), float(alt.max())
    return f"{f.fixed(lo, 0)}–{f.fixed(hi, 0)}" if hi - lo > 0.5 else f.fixed(hi, 0)


def _film_altitude(ft: Any, f: Formatter) -> str:
    """``; flight altitude 830 m`` of the frames over the relief ("" without frames)."""
    if not len(ft.altitude_m):
        return ""
    return f"; {f.cli('flight_altitude')} {_altitudes(ft.altitude_m, f)} {f.cli('m')}"

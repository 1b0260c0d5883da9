"""The "Terrain" sheet of a ``[terrain]`` plan (issue 12)."""

from __future__ import annotations

from typing import Any

from .book import Book
from .cells import _header, put_num

__all__ = ["terrain_sheet"]


def terrain_sheet(book: Book, spec: Any) -> None:
    """Every strip's ground, flight altitude, heights above ground, the highest altitude
    meeting every constraint and by how much its worst photo exceeds it. Per-photo
    elevations and heights are in the photo exports; nothing is added without
    ``[terrain]``."""
    tr = getattr(getattr(spec, "uav", None), "terrain", None)
    if tr is None or not tr.strips:
        _film_sheet(book, spec)
        return
    ws = book.sheet("terrain_sheet", landscape=True, widths=[9, 12, 12, 12, 12, 12, 12, 14,
                                                              12, 10])
    _header(ws, 1, [book.f(k) for k in (
        "strip", "terrain_col_ground_min", "terrain_col_ground_max",
        "terrain_col_alt_min", "terrain_col_alt_max", "terrain_col_agl_min",
        "terrain_col_agl_max", "terrain_col_max_alt", "terrain_col_excess",
        "terrain_col_worst")])
    for r, s in enumerate(tr.strips, start=2):
        put_num(ws, r, 1, s.number, "0")
        for c, v in enumerate((s.ground_min_m, s.ground_max_m, s.altitude_min_m,
                               s.altitude_max_m, s.agl_min_m, s.agl_max_m,
                               s.max_altitude_m, s.excess_m), start=2):
            put_num(ws, r, c, v, "0.0")
        put_num(ws, r, 10, s.worst_photo, "0")
    _film_sheet(book, spec, ws, len(tr.strips) + 3)


def _film_sheet(book: Book, spec: Any, ws: Any = None, row: int = 1) -> None:
    """The film frames over the relief: the local photo scales, the binding frame, the
    scan pixel there and on flat ground (on the UAV's Terrain sheet below its strips, or on
    a sheet of its own)."""
    film = getattr(spec, "film", None)
    ft = getattr(film, "terrain", None) if film is not None else None
    if ft is None:
        return
    if ws is None:
        ws = book.sheet("terrain_sheet", landscape=False, widths=[52, 26])
    row = book.section(ws, row, book.f("terrain_film_title"))
    row = book.kv(ws, row, book.f("terrain_film_planned"), ft.photo_scale, '"1:"0')
    row = book.kv(ws, row, book.f("terrain_film_mc_max"), round(ft.mc_max), '"1:"0')
    frame = (f"{ft.binding_frame} ({ft.binding_strip})" if ft.ground_known
             else book.f("terrain_film_frame_range").format(low=f"{ft.ground_low_m:g}"))
    row = book.kv(ws, row, book.f("terrain_film_frame"), frame)
    row = book.kv(ws, row, book.f("terrain_film_binding"), book.f.cname(ft.binding))
    row = book.kv(ws, row, book.f("terrain_film_pixel"), ft.scan_pixel_um, "0.0")
    row = book.kv(ws, row, book.f("terrain_film_flat_pixel"), ft.scan_pixel_planned_um, "0.0")
    row = book.kv(ws, row, book.f("terrain_film_flat_binding"),
                  book.f.cname(ft.binding_planned) if ft.binding_planned else None)
    rejected = getattr(film, "rejected", ())
    if rejected:
        row = book.kv(ws, row, book.f("terrain_film_rejected"), "; ".join(
            book.f("terrain_film_rejected_value").format(
                scale=book.f.scale(round(r.photo_scale)),
                local=book.f.scale(round(t.mc_max)))
            for r, t in rejected))
    if getattr(film, "flat", None) is not None:
        book.kv(ws, row, book.f("terrain_film_specified"), True)

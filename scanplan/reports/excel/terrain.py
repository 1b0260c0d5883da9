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
        return
    ws = book.sheet("terrain_sheet", landscape=True, widths=[9, 12, 12, 12, 12, 12, 12, 14,
                                                              12, 10])
    _header(ws, 1, [book.t(k) for k in (
        "terrain_col_strip", "terrain_col_ground_min", "terrain_col_ground_max",
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

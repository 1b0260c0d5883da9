"""The workbook's "Strips" and "Photos" sheets (issue 11).

Strips: the layout's figures (as on the PDF's map page) and one row per strip — number,
sortie, photos, length, photographed parts, start and end (latitude/longitude and
easting/northing in the planning CRS). Photos: one row per photo centre with every column
of :data:`scanplan.geo.layout.PHOTO_COLUMNS`, up to :data:`MAX_SHEET_PHOTOS`; a larger
block keeps its photo centres in the CSV written beside the report, and the Strips sheet
says so; an abstract width × length block (a uniform grid in a local frame) has no Photos
sheet. Film layouts get the same sheets for the flight scheme's frames.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

import numpy as np

from . import exports as _exports
from .mapview import MAX_SHEET_PHOTOS, continued_note, summary_items
from .plots import number
from .views.flight import photo_columns, strip_ends_lonlat

if TYPE_CHECKING:
    from ..geo.layout import FlightLayout

__all__ = ["MAX_SHEET_PHOTOS", "add_geo_sheets"]  # MAX_SHEET_PHOTOS: from .mapview


_PHOTO_FORMATS = {"photo": "0", "strip": "0", "index": "0", "sortie": "0",
                  "x_m": "0.000", "y_m": "0.000", "lon_deg": "0.00000000",
                  "lat_deg": "0.00000000", "ground_m": "0.00", "altitude_m": "0.00",
                  "agl_m": "0.00", "gsd_cm": "0.000", "resolution_cm": "0.000",
                  "recognition_p": "0.0000", "ground_min_m": "0.00", "ground_max_m": "0.00",
                  "forward_overlap_pct": "0.0", "side_overlap_pct": "0.0"}
#: The label of each photo column (:func:`~scanplan.reports.views.flight.photo_columns`).
_PHOTO_LABELS = {"photo": "photo_photo", "strip": "strip", "index": "photo_index",
                 "sortie": "sortie", "x_m": "photo_x_m", "y_m": "photo_y_m",
                 "lon_deg": "photo_lon_deg", "lat_deg": "photo_lat_deg",
                 "ground_m": "ground_m", "altitude_m": "altitude_m", "agl_m": "agl_m",
                 "gsd_cm": "photo_gsd_cm", "resolution_cm": "photo_resolution_cm",
                 "recognition_p": "probability", "ground_min_m": "photo_ground_min_m",
                 "ground_max_m": "photo_ground_max_m",
                 "forward_overlap_pct": "forward_overlap_pct",
                 "side_overlap_pct": "side_overlap_pct"}


def add_geo_sheets(book: Any, spec: Any) -> None:
    """Add the Strips and Photos sheets of every flight layout of ``spec`` to ``book``
    (a :class:`scanplan.reports.excel._Book`)."""
    for kind, layout in _exports.spec_layouts(spec):
        film = kind == "film"
        _strips_sheet(book, layout, "sheet_strips_film" if film else "strips",
                      _exports.files_beside(spec, layout))
        if layout.area.georeferenced and 0 < len(layout.photos) <= MAX_SHEET_PHOTOS:
            _photos_sheet(book, layout, "sheet_frames" if film else "sheet_photos")


def _strips_sheet(book: Any, layout: FlightLayout, key: str, files_beside: bool) -> None:
    from .excel.cells import _header, put_num, put_text

    loc = book.loc
    ws = book.sheet(key, landscape=True,
                    widths=(46, 10, 10, 12, 14, 16, 16, 16, 16, 14, 14, 14, 14))
    row = book.section(ws, 1, book.f("geo_summary"))
    for label, value, digits in summary_items(layout, loc):
        fmt = None if isinstance(value, str) else ("#,##0" if digits == 0 else
                                                   "#,##0." + "0" * digits)
        row = book.kv(ws, row, label, value, fmt)
    notes = []
    if not layout.feasible:
        notes.append(book.f("geo_not_feasible").format(reason=layout.reason or ""))
    if not layout.area.georeferenced:
        notes.append(book.f("geo_not_georeferenced"))
    elif len(layout.photos) > MAX_SHEET_PHOTOS:
        notes.append(book.f("geo_photos_elsewhere" if files_beside else "geo_photos_too_many")
                     .format(n=number(len(layout.photos), 0, loc)))
    if layout.kind != "film":
        notes.append(continued_note(layout.strips, loc))
    for note in filter(None, notes):
        row = book._wide_kv(ws, row, "", note)
    row += 1
    ends = [(book.f(e), book.f(c)) for e in ("strip_start", "strip_end")
            for c in ("photo_lat_deg", "photo_lon_deg")]
    xy_cols = _xy_order(loc)
    ends += [(book.f(e), book.f(c)) for e in ("strip_start", "strip_end") for c in xy_cols]
    i, j = (0, 1) if xy_cols[0] == "photo_x_m" else (1, 0)
    head = [book.f("strip"), book.f("sortie"),
            book.f("strip_frames" if layout.kind == "film" else "strip_photos"),
            book.f("strip_length_m"), book.f("strip_parts"), *(f"{e}: {c}" for e, c in ends)]
    _header(ws, row, head)
    row += 1
    lonlat = strip_ends_lonlat(layout)
    ll = (lonlat.reshape(-1, 2) if lonlat is not None
          else np.full((2 * len(layout.strips), 2), np.nan))
    for k, s in enumerate(layout.strips):
        put_num(ws, row, 1, s.number, "0")
        if s.last_sortie == s.sortie:
            put_num(ws, row, 2, s.sortie, "0")
        else:  # a battery change mid-strip: the sorties, as text
            put_text(ws, row, 2, s.sorties_text)
        put_num(ws, row, 3, s.photos, "#,##0")
        put_num(ws, row, 4, s.length_m, "#,##0.0")
        put_num(ws, row, 5, max(s.segments, len(s.parts) or 1), "0")
        (lon0, lat0), (lon1, lat1) = ll[2 * k], ll[2 * k + 1]
        for col, v, fmt in ((6, lat0, "0.00000000"), (7, lon0, "0.00000000"),
                            (8, lat1, "0.00000000"), (9, lon1, "0.00000000"),
                            (10, s.start_xy_m[i], "0.000"), (11, s.start_xy_m[j], "0.000"),
                            (12, s.end_xy_m[i], "0.000"), (13, s.end_xy_m[j], "0.000")):
            put_num(ws, row, col, v, fmt)
        row += 1
    if not layout.strips:
        put_text(ws, row, 1, "—")


def _xy_order(locale: str) -> tuple[str, str]:
    """The plane coordinates' columns in the reader's order: a Russian surveyor reads X
    (north) first, then Y (east) — the geodetic convention of the Gauss–Krüger
    coordinates in Russia; elsewhere easting, northing."""
    return ("photo_y_m", "photo_x_m") if locale == "ru" else ("photo_x_m", "photo_y_m")


def _photos_sheet(book: Any, layout: FlightLayout, key: str) -> None:
    from .excel.cells import _header, put_num

    ph = layout.photos
    cols = photo_columns(layout)
    if _xy_order(book.loc)[0] == "photo_y_m" and {"x_m", "y_m"} <= set(cols):
        a, b = cols.index("x_m"), cols.index("y_m")  # X (north) before Y (east)
        cols[a], cols[b] = cols[b], cols[a]
    ws = book.sheet(key, landscape=True, widths=[14] * len(cols))
    _header(ws, 1, [book.f(_PHOTO_LABELS[c]) for c in cols])
    arrays = [np.asarray(ph[c]) for c in cols]
    fmts = [_PHOTO_FORMATS.get(c, "0.000") for c in cols]
    for i in range(len(ph)):
        for j, (arr, fmt) in enumerate(zip(arrays, fmts, strict=True), start=1):
            put_num(ws, i + 2, j, arr[i], fmt)

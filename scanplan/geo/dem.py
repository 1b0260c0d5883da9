"""Ground elevations from a digital elevation model (a GeoTIFF in any CRS).

The DEM is opened with rasterio: the points to sample (photo centres in the planning CRS)
are reprojected into the DEM's own CRS with pyproj — the DEM is not warped, so a
geographic DEM (degrees) is sampled exactly where its own grid is — and then read tile by
tile (windows of at most :data:`TILE_PX` × :data:`TILE_PX` pixels, only the tiles that
hold points), so memory stays bounded whatever the size of the file. A small DEM (at most
:data:`WHOLE_MAX_PX` pixels) is read whole once and kept while its file is unchanged: a
plan samples it many times, and the pixels are the same.

Sampling is bilinear between the four pixel centres around a point (a point within half a
pixel of the raster's edge takes the edge pixels; outside the raster it has no value). A
point with a nodata pixel among its four neighbours has no value either: scanplan does not
invent ground it has not been given.

Vertical units: metres unless ``[terrain] vertical_unit`` says feet or centimetres, or the
band's own unit metadata does; values that look like centimetres or feet are reported
(:func:`unit_problem`).

Bad input never gives a traceback: a file that is not a readable GeoTIFF, has no CRS, is
too large under the area, or does not cover it is an :class:`~scanplan.errors.InputError`
naming the key (and saying how much is missing).
"""

from __future__ import annotations

import math
import os
import re
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import NDArray

from ..errors import InputError
from ..extras import require
from ..io.kept import MISSING, Kept
from .gdal_guard import KIND_NAMES, gdal_messages, harden, read_head, sniff
from .grids import require_grids

__all__ = ["UNIT_FACTORS", "DemInfo", "Samples", "dem_transformer", "open_dem", "sample_dem",
           "unit_problem"]

TILE_PX = 2048
"""Side of the largest window read at once [pixels] (2048² float64 = 32 MB)."""
MAX_READ_PX = 400_000_000
"""Most pixels read under one area (4·10⁸: a 20 km × 20 km block at 1 m)."""
MAX_DIMENSION_PX = 1_000_000
"""Largest raster side a header may declare [pixels]; beyond it the file is refused."""
HIGHEST_GROUND_M = 8_849.0
"""Everest: no ground is higher [m]."""
LOWEST_GROUND_M = -450.0
"""Dead Sea shore: no dry ground is lower [m]."""

#: metres per vertical unit ([terrain] vertical_unit).
UNIT_FACTORS: dict[str, float] = {"m": 1.0, "ft": 0.3048, "us-ft": 1200.0 / 3937.0,
                                  "cm": 0.01, "dm": 0.1}

GTIFF = "GTiff"
"""The only GDAL driver a DEM is opened with."""

_FOOT_NAMES = ("ft", "foot", "feet", "us-ft", "us survey foot", "us_survey_foot")


@dataclass(frozen=True)
class DemInfo:
    """What the DEM's header says.

    Attributes
    ----------
    path : Path
    crs_wkt : str
        The DEM's horizontal CRS (WKT).
    geographic : bool
        True when the CRS is geographic (cell sizes in degrees).
    width_px, height_px : int
    cell_size : tuple of float
        Pixel size (x, y) in the CRS's units (degrees for a geographic DEM).
    bounds : tuple of float
        (left, bottom, right, top) in the DEM's CRS.
    nodata : float or None
    band_unit : str
        The band's unit metadata ("" when absent).
    horizontal_unit : str
        The CRS's linear unit name ("degree" for a geographic CRS).
    local : bool
        True when the CRS is a local (engineering) one, tied to no place on Earth.
    """

    path: Path
    crs_wkt: str
    geographic: bool
    width_px: int
    height_px: int
    cell_size: tuple[float, float]
    bounds: tuple[float, float, float, float]
    nodata: float | None
    band_unit: str
    horizontal_unit: str
    local: bool = False


@dataclass(frozen=True)
class Samples:
    """Bilinear DEM values at points [m] (NaN where there is no value).

    ``outside`` marks points outside the raster, ``nodata`` those with a nodata pixel among
    their four neighbours.
    """

    elevation_m: NDArray[np.float64]
    outside: NDArray[np.bool_]
    nodata: NDArray[np.bool_]


def _refuse(key: str, path: Path, why: str) -> InputError:
    return InputError(key, f"{path.name}: {why}")


def open_dem(path: str | Path, key: str = "terrain.dem") -> DemInfo:
    """Open a DEM and check its header (nothing is read but the header).

    Only a TIFF is opened, decided by its first bytes whatever its name, with GDAL's GTiff
    driver alone and GDAL's network and virtual-file access off (:mod:`.gdal_guard`); its
    ``.ovr`` and ``.msk`` companions, which GDAL opens by name, must be TIFFs too.

    Raises
    ------
    InputError
        Naming ``key``: the file is missing, not a TIFF (a VRT, an archive, …), damaged,
        has no CRS or no georeference, several bands without a choice, or absurd
        dimensions.
    """
    harden()
    require("terrain", key, "a DEM")  # rasterio and scipy: an extra of the install
    import rasterio
    from rasterio.errors import RasterioError

    p = Path(path)
    if not p.is_file():
        raise _refuse(key, p, "no such file")
    memo = _file_version(p)
    found = _OPENED.get(memo) if memo is not None else MISSING
    if found is not MISSING:  # a plan opens its DEM for every layout
        return found  # type: ignore[return-value]
    _check_tiff(p, key)
    try:
        with gdal_messages() as said, rasterio.open(p, driver=GTIFF) as src:
            info = _header(src, p, key)
    except InputError:
        raise
    except (RasterioError, OSError, ValueError) as exc:
        raise _refuse(key, p, f"is not a readable GeoTIFF ({_short(exc)})") from None
    damage = said.damage()
    if damage is not None:
        raise _refuse(key, p, f"is a damaged GeoTIFF: {damage}; save it again from your GIS")
    if memo is not None:
        _OPENED.put(memo, info)
    return info


_KEPT_OPENED = 8
_OPENED: Kept[tuple[Any, ...], DemInfo] = Kept(_KEPT_OPENED)
"""The headers of the DEMs opened and accepted, by file version (refusals not kept)."""


def file_stamp(path: str | os.PathLike[str]) -> tuple[Any, ...] | None:
    """One version of a file: its name as given, size, modification and change times,
    inode and device — a file rewritten or replaced has another (None when it cannot be
    looked at). What the DEM's header, its pixels and its pyramid are kept by."""
    try:
        st = os.stat(path)
    except OSError:
        return None
    return (os.fspath(path), st.st_size, st.st_mtime_ns, st.st_ctime_ns, st.st_ino, st.st_dev)


def _file_version(p: Path) -> tuple[Any, ...] | None:
    """What an accepted DEM's header depends on: the file as given (:func:`file_stamp`, and
    the working folder a relative name is read from) and its ``.ovr`` / ``.msk``
    companions'; None when they cannot be looked at (the file is then opened and checked
    as always)."""
    stamp = file_stamp(p)
    try:
        stem = p.name.casefold() + "."
        mates = sorted((q.name, q.stat().st_size, q.stat().st_mtime_ns)
                       for q in p.parent.iterdir() if q.name.casefold().startswith(stem))
    except OSError:
        return None
    return None if stamp is None else (stamp, str(Path.cwd()), tuple(mates))


def _header(src: Any, p: Path, key: str) -> DemInfo:
    """The checked header of an open DEM."""
    if src.count < 1:
        raise _refuse(key, p, "has no raster band")
    if src.width > MAX_DIMENSION_PX or src.height > MAX_DIMENSION_PX:
        raise _refuse(key, p, f"declares {src.width} × {src.height} pixels, more than "
                      f"{MAX_DIMENSION_PX:,} on a side: not a DEM scanplan reads "
                      "(cut it to the area first)")
    if src.crs is None:
        raise _refuse(key, p, "has no coordinate reference system: write one into "
                      "the file (a GeoTIFF with its EPSG code)")
    t = src.transform
    if t.is_identity or t.b != 0 or t.d != 0:
        raise _refuse(key, p, "has no north-up georeference (identity or rotated "
                      "transform): warp it to a north-up grid first")
    geographic = bool(src.crs.is_geographic)
    local = not geographic and not bool(src.crs.is_projected)
    unit = "degree" if geographic else str(src.crs.linear_units or "metre")
    band_unit = (src.units[0] or "") if src.units else ""
    return DemInfo(path=p, crs_wkt=src.crs.to_wkt(), geographic=geographic,
                   width_px=int(src.width), height_px=int(src.height),
                   cell_size=(abs(t.a), abs(t.e)), bounds=tuple(src.bounds),
                   nodata=None if src.nodata is None else float(src.nodata),
                   band_unit=band_unit, horizontal_unit=unit, local=local)


def _check_tiff(p: Path, key: str) -> None:
    """The DEM and its ``.ovr`` / ``.msk`` companions must be TIFFs by content."""
    head = read_head(p)
    if head is None:
        raise _refuse(key, p, "is not a regular file that can be read")
    kind = sniff(head)
    if kind == "vrt":
        raise _refuse(key, p, "is a GDAL virtual raster (VRT), not a GeoTIFF: it names "
                      "other files or URLs to read, and scanplan opens only the GeoTIFF "
                      "itself; give the GeoTIFF")
    if kind != "tiff":
        raise _refuse(key, p, f"is not a readable GeoTIFF (its content is "
                      f"{KIND_NAMES[kind]}, whatever its name)")
    stem = p.name.casefold()
    try:
        siblings = [q for q in p.parent.iterdir() if q.name.casefold().startswith(stem + ".")
                    and q.name.casefold().endswith((".ovr", ".msk"))]
    except OSError:
        siblings = []
    for q in siblings[:20]:
        if sniff(read_head(q) or b"") != "tiff":
            raise _refuse(key, p, f"its companion file {q.name} (overviews or mask, which "
                          "GDAL opens with the DEM) is not a TIFF; remove it")


def _short(exc: Exception) -> str:
    text = re.sub(r"\s+", " ", str(exc)).strip()
    return text[:160] + ("…" if len(text) > 160 else "")


def vertical_factor(info: DemInfo, unit: str | None) -> tuple[float, str]:
    """Metres per DEM value and where that came from ("project", "metadata" or "default")."""
    if unit is not None:
        return UNIT_FACTORS[unit], "project"
    band = info.band_unit.strip().lower()
    if band in _FOOT_NAMES:
        return (UNIT_FACTORS["us-ft"] if "us" in band else UNIT_FACTORS["ft"]), "metadata"
    if band in ("cm", "centimetre", "centimeter", "centimetres", "centimeters"):
        return UNIT_FACTORS["cm"], "metadata"
    return 1.0, "default"


def unit_problem(values_m: NDArray[np.float64], info: DemInfo, source: str) -> str | None:
    """A heuristic: do the elevations (already scaled to metres) look like another unit?

    Returns ``"cm"`` when they reach above Everest or below the Dead Sea shore (centimetres
    or decimetres read as metres), ``"ft"`` when the DEM's horizontal unit is the foot but
    nothing says the heights are in feet (US and some state-plane DEMs hold feet in both),
    else None. Only when the unit was not stated in the project.
    """
    if source == "project":
        return None
    finite = values_m[np.isfinite(values_m)]
    if finite.size and (float(finite.max()) > HIGHEST_GROUND_M
                        or float(finite.min()) < LOWEST_GROUND_M):
        return "cm"
    if source == "default" and "foot" in info.horizontal_unit.lower():
        return "ft"
    if source == "default" and "feet" in info.horizontal_unit.lower():
        return "ft"
    return None


_MAX_TRANSFORMERS = 32
_DEM_TRANSFORMERS: Kept[tuple[str, str], Any] = Kept(_MAX_TRANSFORMERS)
"""The transformer (or None) of each (DEM CRS, planning CRS) pair met, refusals not kept
(pyproj's transformers are thread-safe since pyproj 3.1)."""


def dem_transformer(info: DemInfo, plan_crs: str, key: str = "terrain.dem") -> Any:
    """The pyproj transformer from the planning CRS to the DEM's (None: the same frame).

    Raises
    ------
    InputError
        Naming ``key``: the DEM is in a local (engineering) CRS while the area is placed on
        the Earth, or pyproj has no transformation between the two CRSs.
    """
    from pyproj import CRS, Transformer
    from pyproj.exceptions import CRSError, ProjError

    if plan_crs.upper() == "LOCAL":
        return None  # an abstract block: a DEM for it is in the same local frame
    if info.local:
        raise _refuse(key, info.path, "is in a local (engineering) coordinate system, tied "
                      "to no place on the Earth, while the area is georeferenced: give a "
                      "DEM in a geographic or projected CRS (e.g. its EPSG code)")
    kept = (info.crs_wkt, plan_crs)
    found = _DEM_TRANSFORMERS.get(kept)
    if found is not MISSING:  # a plan samples the same DEM many times
        return found
    try:
        dem_crs = CRS.from_wkt(info.crs_wkt)
        src = CRS.from_user_input(plan_crs)
        if src == dem_crs:
            tr = None
        else:
            require_grids(dem_crs, key)
            tr = Transformer.from_crs(src, dem_crs, always_xy=True)
    except (CRSError, ProjError) as exc:
        raise _refuse(key, info.path, f"its CRS cannot be related to the planning CRS "
                      f"{plan_crs} ({_short(exc)})") from None
    return _DEM_TRANSFORMERS.put(kept, tr)


def _to_dem_crs(x: NDArray[np.float64], y: NDArray[np.float64], plan_crs: str,
                info: DemInfo, key: str = "terrain.dem"
                ) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """The points in the DEM's CRS (pyproj, lon/lat order for a geographic CRS)."""
    tr = dem_transformer(info, plan_crs, key)
    if tr is None:
        return x, y
    xx, yy = tr.transform(x, y)
    return np.asarray(xx, dtype=float), np.asarray(yy, dtype=float)


def sample_dem(info: DemInfo, x_m: NDArray[np.float64], y_m: NDArray[np.float64],
               plan_crs: str, factor_m: float = 1.0, key: str = "terrain.dem") -> Samples:
    """Bilinear DEM values at points given in the planning CRS [m].

    The points go into the DEM's CRS (pyproj); the pixels around them are read in tiles of
    at most :data:`TILE_PX` square, only where points fall; each point's value is the
    bilinear mean of its four neighbouring pixel centres, times ``factor_m``.

    Parameters
    ----------
    info : DemInfo
        From :func:`open_dem`.
    x_m, y_m : ndarray
        The points in the planning CRS [m].
    plan_crs : str
        The planning CRS (``"EPSG:32637"``, or ``"LOCAL"`` when the DEM is in the same
        local frame).
    factor_m : float
        Metres per DEM value.

    Returns
    -------
    Samples

    Raises
    ------
    InputError
        When the pixels under the points exceed :data:`MAX_READ_PX`, or the file fails
        while being read.
    """
    x = np.asarray(x_m, dtype=float).ravel()
    y = np.asarray(y_m, dtype=float).ravel()
    n = x.size
    elev = np.full(n, np.nan)
    nodata = np.zeros(n, dtype=bool)
    if n == 0:
        return Samples(elev, np.zeros(0, dtype=bool), nodata)
    dx, dy = _to_dem_crs(x, y, plan_crs, info, key)
    pos = _pixel_positions(info, dx, dy)
    if pos.inside.size:
        _read_windows(info, pos, elev, nodata, key)
    elev *= factor_m
    return Samples(elev, pos.outside, nodata)


@dataclass(frozen=True)
class _Positions:
    """Where the points fall on the DEM's grid: ``outside`` (all points), then for the
    points ``inside`` their fractional (col, row) between pixel centres and the upper-left
    pixel (c0, r0) of their four neighbours."""

    outside: NDArray[np.bool_]
    inside: NDArray[np.int64]
    col: NDArray[np.float64]
    row: NDArray[np.float64]
    c0: NDArray[np.int64]
    r0: NDArray[np.int64]


def _pixel_positions(info: DemInfo, dx: NDArray[np.float64], dy: NDArray[np.float64]
                     ) -> _Positions:
    """The points (in the DEM's CRS) on its pixel grid; within half a pixel of the edge a
    point takes the edge pixels, beyond it the point is outside."""
    left, _bottom, _right, top = info.bounds
    cw, ch = info.cell_size
    # fractional index of the point between pixel centres (centre of pixel 0 at 0.0)
    col = (dx - left) / cw - 0.5
    row = (top - dy) / ch - 0.5
    outside = ~(np.isfinite(col) & np.isfinite(row) & (col >= -0.5) & (row >= -0.5)
                & (col <= info.width_px - 0.5) & (row <= info.height_px - 0.5))
    inside = np.flatnonzero(~outside)
    col_i = np.clip(col[inside], 0.0, info.width_px - 1.0)
    row_i = np.clip(row[inside], 0.0, info.height_px - 1.0)
    c0 = np.minimum(np.floor(col_i).astype(np.int64), max(info.width_px - 2, 0))
    r0 = np.minimum(np.floor(row_i).astype(np.int64), max(info.height_px - 2, 0))
    return _Positions(outside, inside, col_i, row_i, c0, r0)


def _read_windows(info: DemInfo, pos: _Positions, elev: NDArray[np.float64],
                  nodata: NDArray[np.bool_], key: str) -> None:
    """Read the pixels around the points tile by tile (windows of at most
    :data:`TILE_PX` square, only tiles holding points) and write the bilinear values
    into ``elev`` (and the nodata flags into ``nodata``).

    Raises
    ------
    InputError
        When the pixels read exceed :data:`MAX_READ_PX` or the file fails while read.
    """
    import rasterio
    from rasterio.errors import RasterioError
    from rasterio.windows import Window

    c0, r0 = pos.c0, pos.r0
    ntc = info.width_px // TILE_PX + 1
    tile_id = (r0 // TILE_PX) * ntc + c0 // TILE_PX
    order = np.argsort(tile_id, kind="stable")
    _ids, starts = np.unique(tile_id[order], return_index=True)
    ends = np.append(starts[1:], order.size)
    windows = []
    read_px = 0
    for s, e in zip(starts.tolist(), ends.tolist(), strict=True):
        sel = order[s:e]
        r_lo, c_lo = int(r0[sel].min()), int(c0[sel].min())
        r_hi = min(int(r0[sel].max()) + 2, info.height_px)
        c_hi = min(int(c0[sel].max()) + 2, info.width_px)
        read_px += (r_hi - r_lo) * (c_hi - c_lo)
        if read_px > MAX_READ_PX:
            raise _refuse(key, info.path, f"the area covers more than {MAX_READ_PX:,} of its "
                          "pixels: resample the DEM to a coarser grid under the area first")
        windows.append((sel, r_lo, c_lo, r_hi, c_hi))

    def put(data: NDArray[np.float64], sel: NDArray[np.int64], r_lo: int, c_lo: int) -> None:
        _bilinear(data, pos.col[sel] - c_lo, pos.row[sel] - r_lo, c0[sel] - c_lo,
                  r0[sel] - r_lo, pos.inside[sel], elev, nodata)

    whole = _whole(info)
    if whole is not None:  # a small DEM, read once: the same pixels as the windows'
        for sel, r_lo, c_lo, r_hi, c_hi in windows:
            put(whole[r_lo:r_hi, c_lo:c_hi], sel, r_lo, c_lo)
        return
    try:
        with gdal_messages() as said, rasterio.open(info.path, driver=GTIFF) as src:
            for sel, r_lo, c_lo, r_hi, c_hi in windows:
                win = Window(c_lo, r_lo, c_hi - c_lo, r_hi - r_lo)
                block = src.read(1, window=win, masked=True).astype(np.float64)
                put(np.ma.filled(block, np.nan), sel, r_lo, c_lo)
    except (RasterioError, OSError, ValueError, MemoryError) as exc:
        raise _refuse(key, info.path, f"could not be read ({_short(exc)})") from None
    damage = said.damage()
    if damage is not None:
        raise _refuse(key, info.path, f"could not be read ({damage})")


WHOLE_MAX_PX = 1 << 22
"""A DEM of at most this many pixels (4 Mpx, 32 MB as float64) is read whole once and
kept while the file is unchanged (a plan samples it many times); a larger one is read in
windows under the points every time."""
_KEPT_WHOLE = 2
_WHOLE: Kept[tuple[Any, ...], NDArray[np.float64]] = Kept(_KEPT_WHOLE)


def _whole(info: DemInfo) -> NDArray[np.float64] | None:
    """A small DEM's pixels (float64, NaN on no-data, read-only), read once per file
    version (:func:`file_stamp`); None for a large DEM, a file that cannot
    be looked at, or one whose whole read fails or draws a GDAL message (it is then read
    in windows, which says why as before)."""
    import rasterio
    from rasterio.errors import RasterioError

    if info.width_px * info.height_px > WHOLE_MAX_PX:
        return None
    stamp = file_stamp(info.path)
    if stamp is None:
        return None
    memo = (stamp, info)
    found = _WHOLE.get(memo)
    if found is not MISSING:
        return found  # type: ignore[return-value]
    try:
        with gdal_messages() as said, rasterio.open(info.path, driver=GTIFF) as src:
            data = np.ma.filled(src.read(1, masked=True).astype(np.float64), np.nan)
    except (RasterioError, OSError, ValueError, MemoryError):
        return None
    if said.damage() is not None or data.shape != (info.height_px, info.width_px):
        return None
    data.setflags(write=False)
    return _WHOLE.put(memo, data)


def _bilinear(data: NDArray[np.float64], fc: NDArray[np.float64], fr: NDArray[np.float64],
              c0: NDArray[np.int64], r0: NDArray[np.int64], where: NDArray[np.int64],
              out: NDArray[np.float64], nodata: NDArray[np.bool_]) -> None:
    """Bilinear values of ``data`` at fractional (col, row) into ``out[where]``."""
    h, w = data.shape
    c1 = np.minimum(c0 + 1, w - 1)
    r1 = np.minimum(r0 + 1, h - 1)
    tx = np.clip(fc - c0, 0.0, 1.0)
    ty = np.clip(fr - r0, 0.0, 1.0)
    z00, z01 = data[r0, c0], data[r0, c1]
    z10, z11 = data[r1, c0], data[r1, c1]
    v = (z00 * (1 - tx) * (1 - ty) + z01 * tx * (1 - ty) + z10 * (1 - tx) * ty
         + z11 * tx * ty)
    bad = ~np.isfinite(v)
    out[where] = np.where(bad, np.nan, v)
    nodata[where] = bad


def coverage_gap(info: DemInfo, area_geometry: object, plan_crs: str,
                 key: str = "terrain.dem") -> tuple[float, float]:
    """How much of the area the DEM's extent misses: (km², share 0 … 1).

    The DEM's bounds, densified along their edges, are projected into the planning CRS
    (pyproj) and differenced from the area (shapely).

    Raises
    ------
    InputError
        Naming ``key``: the DEM's CRS cannot be related to the planning CRS
        (:func:`dem_transformer`).
    """
    import shapely

    from . import crs as geocrs

    dem_transformer(info, plan_crs, key)  # a local DEM under a georeferenced area: refused
    left, bottom, right, top = info.bounds
    k = 64
    t = np.linspace(0.0, 1.0, k, endpoint=False)
    xs = np.concatenate([left + (right - left) * t, np.full(k, right),
                         right - (right - left) * t, np.full(k, left)])
    ys = np.concatenate([np.full(k, bottom), bottom + (top - bottom) * t,
                         np.full(k, top), top - (top - bottom) * t])
    if plan_crs.upper() != "LOCAL":
        tr = geocrs.transformer(info.crs_wkt, plan_crs)  # made once per process
        xs, ys = (np.asarray(v, dtype=float) for v in tr.transform(xs, ys))
    extent = shapely.Polygon(np.column_stack([xs, ys]))
    if not extent.is_valid:
        extent = shapely.make_valid(extent)
    area = area_geometry
    total = float(area.area)  # type: ignore[attr-defined]
    if not math.isfinite(total) or total <= 0:
        return 0.0, 0.0
    missing = float(shapely.difference(area, extent).area)
    return missing / 1e6, missing / total

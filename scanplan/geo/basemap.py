"""A background image under the plan: a user's orthophoto or any GeoTIFF, or the tiles of
an MBTiles file, reprojected.

:func:`read_basemap` reads a GeoTIFF — checked as a DEM is (:func:`scanplan.geo.dem.open_dem`:
a TIFF by content, GDAL's GTiff driver alone, a north-up georeference, a CRS, sane
dimensions) — at most :data:`MAX_SOURCE_PX` pixels a side (decimated on reading, so a
large orthophoto costs bounded memory), and warps it with rasterio into another CRS (the
page's Web Mercator, a report's planning CRS) at most ``max_px`` pixels a side, as RGBA
bytes: three or more 8-bit bands as colour (a fourth as alpha), anything else (a DEM, a
16-bit band) as grey stretched between its 2nd and 98th percentiles; no-data and the
outside of the image transparent. An MBTiles file (an SQLite database of Web Mercator
tiles, recognised by its first bytes, opened read-only) gives the tiles over the area asked
for, at the deepest zoom that needs at most :data:`MAX_TILES` of them, stitched and warped
the same way.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

from ..errors import InputError

__all__ = ["MAX_SOURCE_PX", "MAX_TILES", "Basemap", "check_basemap", "is_mbtiles", "png_bytes",
           "read_basemap"]

MAX_SOURCE_PX = 4096
"""Most pixels a side read from the source image (it is decimated to this on reading)."""
MAX_TILES = 256
"""Most tiles of an MBTiles file stitched for one picture (16 × 16: 4,096 pixels a side)."""
_SQLITE = b"SQLite format 3\x00"


def is_mbtiles(path: str | Path) -> bool:
    """Whether the file is an SQLite database (an MBTiles file), by its first bytes."""
    try:
        with open(path, "rb") as f:
            return f.read(16) == _SQLITE
    except OSError:
        return False


def _mbtiles(path: Path, key: str) -> Any:
    """A read-only connection to an MBTiles file, its ``tiles`` table checked."""
    import sqlite3

    try:
        db = sqlite3.connect(f"{path.resolve().as_uri()}?mode=ro", uri=True)
        db.execute("SELECT zoom_level, tile_column, tile_row, tile_data FROM tiles LIMIT 1")
    except sqlite3.Error as exc:
        raise InputError(key, f"{path.name}: is not an MBTiles file ({exc})") from None
    return db


def check_basemap(path: str | Path, key: str = "map.basemap") -> None:
    """Refuse a background that is neither a GeoTIFF scanplan reads nor an MBTiles file."""
    p = Path(path)
    if is_mbtiles(p):
        _mbtiles(p, key).close()
        return
    from .dem import open_dem

    open_dem(p, key)


@dataclass(frozen=True)
class Basemap:
    """A background image in a CRS.

    Attributes
    ----------
    rgba : numpy.ndarray
        (rows, columns, 4) uint8, north up.
    bounds : tuple of float
        (left, bottom, right, top) of the image in ``crs`` [CRS units].
    crs : str
        The CRS the image is in (WKT or ``EPSG:n``).
    name : str
        The source file's name (what the map's attribution prints).
    """

    rgba: np.ndarray
    bounds: tuple[float, float, float, float]
    crs: str
    name: str


def _rgba(data: np.ndarray, valid: np.ndarray) -> np.ndarray:
    """(bands, rows, cols) source values → (rows, cols, 4) uint8."""
    bands, rows, cols = data.shape
    out = np.zeros((rows, cols, 4), dtype=np.uint8)
    if bands >= 3 and data.dtype == np.uint8:
        out[..., :3] = np.moveaxis(data[:3], 0, -1)
        alpha = data[3] if bands >= 4 else np.full((rows, cols), 255, np.uint8)
    else:
        band = data[0].astype(np.float64)
        good = valid & np.isfinite(band)
        if good.any():
            lo, hi = np.percentile(band[good], [2, 98])
            scale = 255.0 / (hi - lo) if hi > lo else 0.0
            grey = np.clip((band - lo) * scale, 0, 255)
            grey = np.where(good, grey, 0).astype(np.uint8)
        else:
            grey = np.zeros((rows, cols), np.uint8)
        out[..., :3] = grey[..., None]
        alpha = np.full((rows, cols), 255, np.uint8)
    out[..., 3] = np.where(valid, alpha, 0)
    return out


def read_basemap(path: str | Path, dst_crs: str, *, max_px: int = 2048,
                 key: str = "map.basemap",
                 area_lonlat: tuple[float, float, float, float] | None = None) -> Basemap:
    """The GeoTIFF or MBTiles file at ``path`` warped into ``dst_crs`` (module docstring).

    Parameters
    ----------
    path : str or Path
        The GeoTIFF.
    dst_crs : str
        The CRS to warp into (``"EPSG:3857"``, a report's planning CRS as WKT).
    max_px : int
        Most pixels a side of the result.
    key : str
        The input named in an error.
    area_lonlat : tuple of float, optional
        (west, south, east, north) [°] the picture must cover: an MBTiles file is read
        there (at the deepest zoom whose tiles over it are at most :data:`MAX_TILES`);
        default: the file's own ``bounds``.

    Raises
    ------
    InputError
        Naming ``key``: not a GeoTIFF scanplan reads (see :func:`~.dem.open_dem`), or one
        that fails while read.
    """
    if is_mbtiles(path):
        return _read_mbtiles(Path(path), dst_crs, max_px, key, area_lonlat)
    from .dem import open_dem

    info = open_dem(path, key)
    import rasterio
    from rasterio.enums import Resampling
    from rasterio.errors import RasterioError

    p = Path(path)
    try:
        with rasterio.open(p, driver="GTiff") as src:
            shrink = max(1.0, max(src.width, src.height) / MAX_SOURCE_PX)
            rows, cols = max(1, round(src.height / shrink)), max(1, round(src.width / shrink))
            colour = src.count >= 3 and all(d == "uint8" for d in src.dtypes[:3])
            indexes = list(range(1, min(src.count, 4) + 1)) if colour else [1]
            data = src.read(indexes, out_shape=(len(indexes), rows, cols),
                            resampling=Resampling.average if shrink > 1 else Resampling.nearest)
            mask = src.read_masks(1, out_shape=(rows, cols)) > 0
            src_crs = src.crs
    except (RasterioError, OSError, ValueError, MemoryError) as exc:
        raise InputError(key, f"{p.name}: cannot be read ({str(exc)[:200]})") from None
    rgba = _rgba(data, mask)
    return _warp(rgba, tuple(info.bounds), src_crs.to_wkt(), dst_crs, max_px, p.name)


def png_bytes(image: Basemap) -> bytes:
    """The image as PNG bytes (Pillow, which WeasyPrint brings)."""
    import io

    from PIL import Image

    buf = io.BytesIO()
    Image.fromarray(image.rgba, "RGBA").save(buf, "PNG", optimize=False)
    return buf.getvalue()


def _tile_xy(lon: float, lat: float, z: int) -> tuple[int, int]:
    """The XYZ tile holding a point at zoom ``z`` (the Web Mercator tiling)."""
    import math

    n = 2 ** z
    lat = max(min(lat, 85.0511), -85.0511)
    x = int((lon + 180.0) / 360.0 * n)
    y = int((1.0 - math.asinh(math.tan(math.radians(lat))) / math.pi) / 2.0 * n)
    return min(max(x, 0), n - 1), min(max(y, 0), n - 1)


def _read_mbtiles(path: Path, dst_crs: str, max_px: int, key: str,
                  area: tuple[float, float, float, float] | None) -> Basemap:
    """An MBTiles file's tiles over ``area`` stitched (Web Mercator) and warped."""
    import io
    import math

    from PIL import Image

    db = _mbtiles(path, key)
    try:
        meta = dict(db.execute("SELECT name, value FROM metadata").fetchall())
        if area is None:
            try:
                area = tuple(float(v) for v in str(meta["bounds"]).split(","))  # type: ignore
            except (KeyError, ValueError):
                raise InputError(key, f"{path.name}: names no bounds; the area to cover "
                                 "is needed") from None
        assert area is not None
        zooms = [int(z) for (z,) in db.execute(
            "SELECT DISTINCT zoom_level FROM tiles ORDER BY zoom_level DESC")]
        for z in zooms:
            x0, y0 = _tile_xy(area[0], area[3], z)
            x1, y1 = _tile_xy(area[2], area[1], z)
            if (x1 - x0 + 1) * (y1 - y0 + 1) <= MAX_TILES:
                break
        else:
            raise InputError(key, f"{path.name}: holds no tiles")
        size = 256
        mosaic = Image.new("RGBA", ((x1 - x0 + 1) * size, (y1 - y0 + 1) * size))
        rows = db.execute("SELECT tile_column, tile_row, tile_data FROM tiles WHERE "
                          "zoom_level=? AND tile_column BETWEEN ? AND ? AND tile_row BETWEEN "
                          "? AND ?", (z, x0, x1, 2 ** z - 1 - y1, 2 ** z - 1 - y0))
        for x, row, data in rows:
            try:
                tile = Image.open(io.BytesIO(data)).convert("RGBA").resize((size, size))
            except (OSError, ValueError):
                continue  # a damaged tile stays transparent
            mosaic.paste(tile, ((x - x0) * size, (2 ** z - 1 - row - y0) * size))
    finally:
        db.close()
    half = math.pi * 6378137.0
    step = 2 * half / 2 ** z
    left, top = -half + x0 * step, half - y0 * step
    right, bottom = -half + (x1 + 1) * step, half - (y1 + 1) * step
    return _warp(np.asarray(mosaic), (left, bottom, right, top), "EPSG:3857", dst_crs,
                 max_px, path.name)


def _warp(rgba: np.ndarray, bounds: tuple[float, float, float, float], src_crs: str,
          dst_crs: str, max_px: int, name: str) -> Basemap:
    """An RGBA picture over ``bounds`` in ``src_crs`` warped into ``dst_crs``."""
    import pyproj
    from rasterio.enums import Resampling
    from rasterio.transform import from_bounds
    from rasterio.warp import reproject

    rows, cols = rgba.shape[:2]
    left, bottom, right, top = pyproj.Transformer.from_crs(
        pyproj.CRS.from_user_input(src_crs), pyproj.CRS.from_user_input(dst_crs),
        always_xy=True).transform_bounds(*bounds, densify_pts=64)
    step = max(right - left, top - bottom) / max_px
    width = max(1, round((right - left) / step))
    height = max(1, round((top - bottom) / step))
    out = np.zeros((4, height, width), dtype=np.uint8)
    for b in range(4):
        reproject(np.ascontiguousarray(rgba[..., b]), out[b],
                  src_transform=from_bounds(*bounds, cols, rows), src_crs=src_crs,
                  dst_transform=from_bounds(left, bottom, right, top, width, height),
                  dst_crs=dst_crs, resampling=Resampling.bilinear, src_nodata=None,
                  dst_nodata=0)
    return Basemap(np.ascontiguousarray(np.moveaxis(out, 0, -1)),
                   (left, bottom, right, top), str(dst_crs), name)

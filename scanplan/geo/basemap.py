"""A background image under the plan: a user's orthophoto or any GeoTIFF, or the tiles of
an MBTiles file or of a tile server, reprojected.

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
the same way. :func:`read_tiles` does the same with a tile server's XYZ tiles (fetched and
kept on disk by :class:`scanplan.geo.tiles.TileCache`) at the zoom a picture of ``max_px``
pixels needs (:func:`tiles_zoom`).
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

from ..errors import InputError

__all__ = ["DEFAULT_MAX_ZOOM", "MAX_MBTILES_ZOOM", "MAX_SOURCE_PX", "MAX_TILES", "MAX_TILE_PX",
           "Basemap", "TilesRead",
           "check_basemap", "is_mbtiles", "layout_extent", "layout_extent_lonlat", "png_bytes",
           "read_basemap", "read_tiles", "tiles_zoom"]

MAX_SOURCE_PX = 4096
"""Most pixels a side read from the source image (it is decimated to this on reading)."""
MAX_TILES = 256
"""Most tiles of an MBTiles file stitched for one picture (16 × 16: 4,096 pixels a side)."""
DEFAULT_MAX_ZOOM = 19
"""Deepest zoom of an XYZ template's tiles asked for the PDF (OpenStreetMap's deepest)."""
MAX_MBTILES_ZOOM = 30
"""Deepest zoom level of an MBTiles file read (the XYZ tiling's zoom 30: 4 cm tiles)."""
MAX_TILE_PX = 1024
"""Largest tile read [pixels a side] (tiles are 256 or 512; a larger header is a
decompression bomb's: the tile stays transparent)."""
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


def _tile_range(area: tuple[float, float, float, float], z: int) -> tuple[int, int, int, int]:
    """(x0, y0, x1, y1): the tiles of zoom ``z`` over ``area`` (west, south, east, north)."""
    x0, y0 = _tile_xy(area[0], area[3], z)
    x1, y1 = _tile_xy(area[2], area[1], z)
    return x0, y0, x1, y1


def _tile_count(area: tuple[float, float, float, float], z: int) -> int:
    x0, y0, x1, y1 = _tile_range(area, z)
    return (x1 - x0 + 1) * (y1 - y0 + 1)


def _stitch(tiles: dict[tuple[int, int], bytes], z: int, x0: int, y0: int, x1: int, y1: int,
            dst_crs: str, max_px: int, name: str) -> Basemap:
    """The tiles ``{(x, y): image bytes}`` of zoom ``z`` over columns ``x0 … x1`` and rows
    ``y0 … y1`` stitched in Web Mercator (a missing or damaged tile transparent) and warped
    into ``dst_crs``."""
    import io
    import math

    from PIL import Image

    size = 256
    mosaic = Image.new("RGBA", ((x1 - x0 + 1) * size, (y1 - y0 + 1) * size))
    for (x, y), data in tiles.items():
        try:
            tile = Image.open(io.BytesIO(data))
            if max(tile.size) > MAX_TILE_PX:
                continue  # a bomb's header: transparent, never decoded
            tile = tile.convert("RGBA").resize((size, size))
        except (OSError, ValueError, Image.DecompressionBombError):
            continue  # a damaged tile stays transparent
        mosaic.paste(tile, ((x - x0) * size, (y - y0) * size))
    half = math.pi * 6378137.0  # the Web Mercator square's half side [m]
    step = 2 * half / 2 ** z
    left, top = -half + x0 * step, half - y0 * step
    right, bottom = -half + (x1 + 1) * step, half - (y1 + 1) * step
    return _warp(np.asarray(mosaic), (left, bottom, right, top), "EPSG:3857", dst_crs,
                 max_px, name)


def _read_mbtiles(path: Path, dst_crs: str, max_px: int, key: str,
                  area: tuple[float, float, float, float] | None) -> Basemap:
    """An MBTiles file's tiles over ``area`` stitched (Web Mercator) and warped; a
    database error (a table missing, a damaged file) is an input error naming ``key``, a
    zoom level that is not a whole number from 0 to :data:`MAX_MBTILES_ZOOM` is not read."""
    import math
    import sqlite3

    db = _mbtiles(path, key)
    try:
        meta = dict(db.execute("SELECT name, value FROM metadata").fetchall())
        if area is None:
            try:
                area = tuple(float(v) for v in str(meta["bounds"]).split(","))  # type: ignore
                if len(area) != 4 or not all(math.isfinite(v) for v in area):
                    raise ValueError
            except (KeyError, ValueError):
                raise InputError(key, f"{path.name}: names no bounds; the area to cover "
                                 "is needed") from None
        assert area is not None
        zooms = [z for (z,) in db.execute(
            "SELECT DISTINCT zoom_level FROM tiles WHERE typeof(zoom_level) = 'integer' "
            f"AND zoom_level BETWEEN 0 AND {MAX_MBTILES_ZOOM} ORDER BY zoom_level DESC")]
        for z in zooms:
            if _tile_count(area, z) <= MAX_TILES:
                break
        else:
            raise InputError(key, f"{path.name}: holds no tiles")
        x0, y0, x1, y1 = _tile_range(area, z)
        rows = db.execute("SELECT tile_column, tile_row, tile_data FROM tiles WHERE "
                          "zoom_level=? AND tile_column BETWEEN ? AND ? AND tile_row BETWEEN "
                          "? AND ?", (z, x0, x1, 2 ** z - 1 - y1, 2 ** z - 1 - y0))
        tiles = {(x, 2 ** z - 1 - row): data for x, row, data in rows
                 if isinstance(x, int) and isinstance(row, int) and isinstance(data, bytes)
                 and data}  # MBTiles count rows from the south (TMS)
    except sqlite3.Error as exc:
        raise InputError(key, f"{path.name}: is not an MBTiles file scanplan reads "
                         f"({str(exc)[:200]})") from None
    finally:
        db.close()
    return _stitch(tiles, z, x0, y0, x1, y1, dst_crs, max_px, path.name)


def tiles_zoom(area: tuple[float, float, float, float], max_px: int,
               max_zoom: int = DEFAULT_MAX_ZOOM) -> int:
    """The zoom whose tiles print ``area`` (west, south, east, north) [°] at ``max_px``
    pixels across its longer side: the shallowest whose pixel is at most the printed one
    on the ground at the area's middle latitude, at most ``max_zoom`` and at most
    :data:`MAX_TILES` tiles.

    A Web Mercator tile pixel at zoom z covers 2πR·cos φ / (256 · 2^z) metres of ground
    (R = 6,378,137 m; https://wiki.openstreetmap.org/wiki/Zoom_levels), so
    z = ⌈log₂(2πR·cos φ / (256 · pixel_m))⌉.
    """
    import math

    import pyproj

    geod = pyproj.Geod(ellps="WGS84")
    mid_lat = (area[1] + area[3]) / 2
    mid_lon = (area[0] + area[2]) / 2
    across_m = geod.inv(area[0], mid_lat, area[2], mid_lat)[2]
    along_m = geod.inv(mid_lon, area[1], mid_lon, area[3])[2]
    pixel_m = max(across_m, along_m, 1.0) / max_px
    ground = 2 * math.pi * 6378137.0 * math.cos(math.radians(mid_lat)) / 256
    z = min(max(0, math.ceil(math.log2(ground / pixel_m))), max_zoom)
    while z > 0 and _tile_count(area, z) > MAX_TILES:
        z -= 1
    return z


@dataclass(frozen=True)
class TilesRead:
    """What :func:`read_tiles` got: the picture (None when no tile came), the tiles asked
    for and those that did not come, and the host asked."""

    image: Basemap | None
    asked: int
    missing: int
    host: str


def read_tiles(url: str, dst_crs: str, area_lonlat: tuple[float, float, float, float], *,
               max_px: int = 1600, name: str = "", cache: Path | None = None,
               max_zoom: int = DEFAULT_MAX_ZOOM) -> TilesRead:
    """The XYZ tiles of the template ``url`` over ``area_lonlat`` at the zoom the picture
    needs (:func:`tiles_zoom`), from the disk cache or fetched and kept there
    (:class:`scanplan.geo.tiles.TileCache`), stitched and warped into ``dst_crs``.

    Never raises for the network: once the server does not answer, the rest come from
    the cache only; the tiles that did not come are counted (``missing``) and left
    transparent, and without any tile ``image`` is None.

    Parameters
    ----------
    url : str
        The template (checked: :func:`scanplan.geo.tiles.check_template`).
    dst_crs : str
        The CRS to warp into.
    area_lonlat : tuple of float
        (west, south, east, north) [°] the picture covers.
    max_px : int
        Most pixels a side of the result (and the print resolution the zoom is chosen for).
    name : str
        What the picture is called (its attribution).
    cache : Path or None
        The cache folder (default: the user's, as the page's).
    max_zoom : int
        Deepest zoom asked for.
    """
    from .tiles import TileCache, TileUnreachable, template_host

    tiles_cache = TileCache(cache)
    z = tiles_zoom(area_lonlat, max_px, max_zoom)
    x0, y0, x1, y1 = _tile_range(area_lonlat, z)
    got: dict[tuple[int, int], bytes] = {}
    online = True
    for y in range(y0, y1 + 1):
        for x in range(x0, x1 + 1):
            try:
                tile = tiles_cache.get(url, z, x, y, fetch=online)
            except TileUnreachable:
                online, tile = False, None  # the rest from the cache only
            if tile is not None:
                got[(x, y)] = tile[0]
    asked = (x1 - x0 + 1) * (y1 - y0 + 1)
    image = _stitch(got, z, x0, y0, x1, y1, dst_crs, max_px, name) if got else None
    return TilesRead(image, asked, asked - len(got), template_host(url))


def layout_extent_lonlat(layout: Any, pad: float = 0.15) -> tuple[float, float, float, float]:
    """(west, south, east, north) [°] of what a layout's map shows: the area, the strips'
    ends and the take-off point, widened by ``pad`` of the longer side each way (the map's
    margins)."""
    import pyproj

    minx, miny, maxx, maxy = layout_extent(layout)
    margin = pad * max(maxx - minx, maxy - miny)
    return pyproj.Transformer.from_crs(pyproj.CRS.from_user_input(layout.area.plan_crs),
                                       4326, always_xy=True).transform_bounds(
        minx - margin, miny - margin, maxx + margin, maxy + margin, densify_pts=21)


def layout_extent(layout: Any) -> tuple[float, float, float, float]:
    """(minx, miny, maxx, maxy) in the planning CRS [m]: the area, the strips' ends and the
    take-off point of a :class:`~scanplan.geo.layout.FlightLayout`."""
    minx, miny, maxx, maxy = layout.area.geometry.bounds
    if layout.strips:
        ends = np.array([p for s in layout.strips for p in (s.start_xy_m, s.end_xy_m)])
        minx, miny = min(minx, ends[:, 0].min()), min(miny, ends[:, 1].min())
        maxx, maxy = max(maxx, ends[:, 0].max()), max(maxy, ends[:, 1].max())
    takeoff = layout.notes.get("takeoff_xy_m")
    if takeoff is not None:
        minx, miny = min(minx, takeoff[0]), min(miny, takeoff[1])
        maxx, maxy = max(maxx, takeoff[0]), max(maxy, takeoff[1])
    return float(minx), float(miny), float(maxx), float(maxy)


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

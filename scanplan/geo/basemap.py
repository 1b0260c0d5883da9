"""A background image under the plan: a user's orthophoto or any GeoTIFF, reprojected.

:func:`read_basemap` reads a GeoTIFF — checked as a DEM is (:func:`scanplan.geo.dem.open_dem`:
a TIFF by content, GDAL's GTiff driver alone, a north-up georeference, a CRS, sane
dimensions) — at most :data:`MAX_SOURCE_PX` pixels a side (decimated on reading, so a
large orthophoto costs bounded memory), and warps it with rasterio into another CRS (the
page's Web Mercator, a report's planning CRS) at most ``max_px`` pixels a side, as RGBA
bytes: three or more 8-bit bands as colour (a fourth as alpha), anything else (a DEM, a
16-bit band) as grey stretched between its 2nd and 98th percentiles; no-data and the
outside of the image transparent.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import numpy as np

from ..errors import InputError

__all__ = ["MAX_SOURCE_PX", "Basemap", "png_bytes", "read_basemap"]

MAX_SOURCE_PX = 4096
"""Most pixels a side read from the source image (it is decimated to this on reading)."""


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
                 key: str = "map.basemap") -> Basemap:
    """The GeoTIFF at ``path`` warped into ``dst_crs`` (module docstring).

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

    Raises
    ------
    InputError
        Naming ``key``: not a GeoTIFF scanplan reads (see :func:`~.dem.open_dem`), or one
        that fails while read.
    """
    from .dem import open_dem

    info = open_dem(path, key)
    import rasterio
    from rasterio.enums import Resampling
    from rasterio.errors import RasterioError
    from rasterio.transform import from_bounds
    from rasterio.warp import reproject

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
            transform = from_bounds(*src.bounds, cols, rows)
            src_crs = src.crs
    except (RasterioError, OSError, ValueError, MemoryError) as exc:
        raise InputError(key, f"{p.name}: cannot be read ({str(exc)[:200]})") from None
    rgba = _rgba(data, mask)
    # the destination's extent: the source's edges transformed densely (pyproj; GDAL's
    # own default-transform helper opens a VRT, a driver the hardened GDAL has not)
    import pyproj

    left, bottom, right, top = pyproj.Transformer.from_crs(
        pyproj.CRS.from_user_input(src_crs.to_wkt()), pyproj.CRS.from_user_input(dst_crs),
        always_xy=True).transform_bounds(*info.bounds, densify_pts=64)
    step = max(right - left, top - bottom) / max_px
    width = max(1, round((right - left) / step))
    height = max(1, round((top - bottom) / step))
    out = np.zeros((4, height, width), dtype=np.uint8)
    dst_transform = from_bounds(left, bottom, right, top, width, height)
    for b in range(4):
        reproject(rgba[..., b], out[b], src_transform=transform, src_crs=src_crs,
                  dst_transform=dst_transform, dst_crs=dst_crs,
                  resampling=Resampling.bilinear, src_nodata=None, dst_nodata=0)
    return Basemap(np.ascontiguousarray(np.moveaxis(out, 0, -1)),
                   (left, bottom, right, top), str(dst_crs), p.name)


def png_bytes(image: Basemap) -> bytes:
    """The image as PNG bytes (Pillow, which WeasyPrint brings)."""
    import io

    from PIL import Image

    buf = io.BytesIO()
    Image.fromarray(image.rgba, "RGBA").save(buf, "PNG", optimize=False)
    return buf.getvalue()

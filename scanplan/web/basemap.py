"""The ground under the plan on the page: tile layers the server was configured with, and
a user's orthophoto.

**Tiles.** The page asks the server for every tile (``GET /api/tiles/{source}/{z}/{x}/{y}``):

- an XYZ source is fetched only from the URL template ``scanplan serve --tiles`` was given
  (or OpenStreetMap's), never from a URL a request names: the request gives the source's
  id and three integers, checked (``z`` ≤ :data:`MAX_ZOOM`, ``x``, ``y`` < 2^z), and the
  server fills its own template. A fetched tile (an image, at most :data:`MAX_TILE_BYTES`)
  is kept on disk (``--tile-cache``, by default the user's cache folder) and served from
  there afterwards — also offline; the cache keeps at most :data:`MAX_CACHE_TILES` tiles
  (:class:`scanplan.geo.tiles.TileCache`, which the PDF's map page uses too);
- an MBTiles file (``--mbtiles FILE``: a SQLite database of tiles, the format QGIS, GDAL and
  the tile tools write) is read with :mod:`sqlite3`, read-only — offline by nature.

Each source carries its attribution, which the page shows on the map.

**An orthophoto.** An uploaded GeoTIFF is warped to Web Mercator on the server
(:func:`scanplan.geo.basemap.read_basemap`, bounded like a DEM) in the worker process, kept
beside the upload as a PNG and shown under the plan; the project names it as
``[map] basemap``, and the PDF's map page prints it.
"""

from __future__ import annotations

import contextlib
import os
import sqlite3
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from ..errors import InputError
from ..geo.tiles import (
    MAX_CACHE_TILES,
    MAX_TILE_BYTES,
    MAX_ZOOM,
    OSM_ATTRIBUTION,
    OSM_URL,
    TileCache,
    TileUnreachable,
    check_template,
    default_cache,
    image_type,
    template_host,
)

__all__ = ["MAX_CACHE_TILES", "MAX_TILE_BYTES", "MAX_ZOOM", "OSM_ATTRIBUTION", "OSM_URL",
           "Basemaps", "TileSource", "check_template", "default_cache", "ortho_job"]


@dataclass(frozen=True)
class TileSource:
    """One tile layer: ``id`` (in the route), ``name`` and ``attribution`` (shown), the
    ``url`` template (XYZ) or the MBTiles ``path``, and its deepest zoom."""

    id: str
    name: str
    attribution: str
    url: str | None = None
    path: Path | None = None
    max_zoom: int = 19


def _mbtiles_meta(path: Path) -> dict[str, str]:
    """The ``metadata`` table of an MBTiles file (name, attribution, maxzoom …)."""
    try:
        with contextlib.closing(_connect(path)) as db:
            rows = db.execute("SELECT name, value FROM metadata").fetchall()
            db.execute("SELECT zoom_level, tile_column, tile_row, tile_data FROM tiles "
                       "LIMIT 1").fetchall()
    except sqlite3.Error as exc:
        raise InputError("--mbtiles", f"{path.name} is not an MBTiles file ({exc})") from None
    return {str(k): str(v) for k, v in rows}


def _connect(path: Path) -> sqlite3.Connection:
    """A read-only connection to an MBTiles file."""
    return sqlite3.connect(f"{path.resolve().as_uri()}?mode=ro", uri=True,
                           check_same_thread=False)


class Basemaps:
    """The tile sources of a server and their cache (see the module docstring).

    Parameters
    ----------
    tiles : str
        ``"osm"``, ``"none"`` or an http(s) URL template with ``{z}``, ``{x}``, ``{y}``.
    attribution : str or None
        The attribution of a URL template's tiles (shown on the map and printed).
    mbtiles : Path or None
        An MBTiles file to offer (offline).
    cache : Path or None
        Where fetched tiles are kept (default :func:`default_cache`).
    """

    def __init__(self, tiles: str = "osm", attribution: str | None = None,
                 mbtiles: Path | None = None, cache: Path | None = None) -> None:
        self.sources: dict[str, TileSource] = {}
        if tiles == "osm":
            self.sources["osm"] = TileSource("osm", "OpenStreetMap", OSM_ATTRIBUTION, OSM_URL)
        elif tiles != "none":
            check_template(tiles)
            self.sources["tiles"] = TileSource("tiles", attribution or template_host(tiles),
                                               attribution or template_host(tiles), tiles)
        if mbtiles is not None:
            meta = _mbtiles_meta(Path(mbtiles))
            zoom = int(meta["maxzoom"]) if meta.get("maxzoom", "").isdigit() else MAX_ZOOM
            self.sources["mbtiles"] = TileSource(
                "mbtiles", meta.get("name") or Path(mbtiles).name,
                meta.get("attribution") or meta.get("name") or Path(mbtiles).name,
                path=Path(mbtiles), max_zoom=min(zoom, MAX_ZOOM))
        self.cache = cache if cache is not None else default_cache()
        self._tiles = TileCache(self.cache)
        self.default = "mbtiles" if "mbtiles" in self.sources else next(
            iter(self.sources), "none")

    def page_list(self, token: str | None = None) -> list[dict[str, Any]]:
        """The sources as the page's configuration lists them."""
        q = "" if not token else "?token=" + token
        return [{"id": s.id, "name": s.name, "attribution": s.attribution,
                 "max_zoom": s.max_zoom, "url": f"api/tiles/{s.id}/{{z}}/{{x}}/{{y}}{q}",
                 "offline": s.path is not None} for s in self.sources.values()]

    def tile(self, source: str, z: int, x: int, y: int) -> tuple[bytes, str] | None:
        """The tile's bytes and media type; None when the source has none there.

        Raises
        ------
        InputError
            An unknown source or a tile number out of range.
        """
        s = self.sources.get(source)
        if s is None:
            raise InputError("source", f"must be one of {', '.join(self.sources) or 'none'}")
        if not (0 <= z <= MAX_ZOOM and 0 <= x < 2 ** z and 0 <= y < 2 ** z):
            raise InputError("tile", f"z must be 0 … {MAX_ZOOM} and x, y 0 … 2^z − 1")
        if s.path is not None:
            return self._mbtile(s.path, z, x, y)
        return self._fetched(s, z, x, y)

    def _mbtile(self, path: Path, z: int, x: int, y: int) -> tuple[bytes, str] | None:
        with contextlib.closing(_connect(path)) as db:
            row = db.execute("SELECT tile_data FROM tiles WHERE zoom_level=? AND "
                             "tile_column=? AND tile_row=?", (z, x, 2 ** z - 1 - y)).fetchone()
        if row is None or not row[0] or len(row[0]) > MAX_TILE_BYTES:
            return None
        data = bytes(row[0])
        kind = image_type(data)
        return (data, kind) if kind else None

    def _fetched(self, s: TileSource, z: int, x: int, y: int) -> tuple[bytes, str] | None:
        assert s.url is not None
        try:
            return self._tiles.get(s.url, z, x, y)
        except TileUnreachable:
            return None


def ortho_job(path: str, cache: str) -> dict[str, Any]:
    """An uploaded GeoTIFF warped to Web Mercator as a PNG at ``cache`` (once): its
    ``bounds`` [[south, west], [north, east]] in degrees and its size in pixels. Runs in the
    worker process."""
    import pyproj

    from ..geo.basemap import png_bytes, read_basemap

    image = read_basemap(path, "EPSG:3857", max_px=2048, key="file")
    target = Path(cache)
    tmp = target.with_suffix(".part")
    tmp.write_bytes(png_bytes(image))
    os.replace(tmp, target)
    left, bottom, right, top = image.bounds
    tr = pyproj.Transformer.from_crs(3857, 4326, always_xy=True)
    (w, e), (s, n) = tr.transform([left, right], [bottom, top])
    return {"bounds": [[s, w], [n, e]], "width": int(image.rgba.shape[1]),
            "height": int(image.rgba.shape[0])}

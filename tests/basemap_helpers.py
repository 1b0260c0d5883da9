"""Shared by the tests of the background map: a synthetic orthophoto, an MBTiles file and a
tile server on 127.0.0.1 (no test reaches the internet)."""

from __future__ import annotations

import io
import sqlite3
import threading
from collections.abc import Callable
from http.server import BaseHTTPRequestHandler, ThreadingHTTPServer
from pathlib import Path

import numpy as np

TOWN_BOUNDS_LONLAT = (38.765, 55.069, 38.818, 55.092)
"""(west, south, east, north) [°] around examples/areas/town-uav.kml."""
ORTHO_COLOUR = (200, 40, 160)
"""The orthophoto's magenta squares: a colour nothing else on the page or the map has."""


def write_ortho(path: Path, bounds: tuple[float, float, float, float] = TOWN_BOUNDS_LONLAT,
                epsg: int = 32637, size: int = 400) -> Path:
    """A synthetic RGB orthophoto (8-bit, 3 bands) in UTM over ``bounds``: magenta and
    white squares of 20 pixels."""
    import pyproj
    import rasterio
    from rasterio.transform import from_bounds

    tr = pyproj.Transformer.from_crs(4326, epsg, always_xy=True)
    xs, ys = tr.transform([bounds[0], bounds[2], bounds[0], bounds[2]],
                          [bounds[1], bounds[1], bounds[3], bounds[3]])
    left, right, bottom, top = min(xs), max(xs), min(ys), max(ys)
    rows, cols = np.mgrid[0:size, 0:size]
    check = ((rows // 20 + cols // 20) % 2).astype(bool)
    rgb = np.full((3, size, size), 255, np.uint8)
    for b, v in enumerate(ORTHO_COLOUR):
        rgb[b][check] = v
    with rasterio.open(path, "w", driver="GTiff", width=size, height=size, count=3,
                       dtype="uint8", crs=f"EPSG:{epsg}",
                       transform=from_bounds(left, bottom, right, top, size, size)) as dst:
        dst.write(rgb)
    return path


def tile_png(colour: tuple[int, int, int]) -> bytes:
    """A 256-pixel PNG tile of one colour."""
    from PIL import Image

    buf = io.BytesIO()
    Image.new("RGB", (256, 256), colour).save(buf, "PNG")
    return buf.getvalue()


def write_mbtiles(path: Path, colour: tuple[int, int, int], zooms: range = range(0, 17),
                  bounds: tuple[float, float, float, float] = TOWN_BOUNDS_LONLAT,
                  attribution: str = "Test tiles © the test") -> Path:
    """An MBTiles file with a tile of ``colour`` at every zoom of ``zooms`` over ``bounds``."""
    import math

    data = tile_png(colour)
    db = sqlite3.connect(path)
    db.execute("CREATE TABLE metadata (name text, value text)")
    db.execute("CREATE TABLE tiles (zoom_level integer, tile_column integer, tile_row "
               "integer, tile_data blob)")
    db.executemany("INSERT INTO metadata VALUES (?, ?)", [
        ("name", "test tiles"), ("format", "png"), ("attribution", attribution),
        ("minzoom", str(zooms.start)), ("maxzoom", str(zooms.stop - 1)),
        ("bounds", ",".join(str(v) for v in bounds))])

    def xy(lon: float, lat: float, z: int) -> tuple[int, int]:
        n = 2 ** z
        x = int((lon + 180) / 360 * n)
        y = int((1 - math.asinh(math.tan(math.radians(lat))) / math.pi) / 2 * n)
        return x, y

    for z in zooms:
        x0, y0 = xy(bounds[0], bounds[3], z)
        x1, y1 = xy(bounds[2], bounds[1], z)
        for x in range(x0, x1 + 1):
            for y in range(y0, y1 + 1):
                db.execute("INSERT INTO tiles VALUES (?, ?, ?, ?)", (z, x, 2 ** z - 1 - y, data))
    db.commit()
    db.close()
    return path


class TileServer:
    """An XYZ tile server on 127.0.0.1 answering every ``/{z}/{x}/{y}.png`` with one colour
    (only those ``has(z, x, y)`` is true for, when given; 404 for the others), counting the
    requests (``hits``); a context manager."""

    def __init__(self, colour: tuple[int, int, int],
                 has: Callable[[int, int, int], bool] | None = None) -> None:
        data = tile_png(colour)
        hits: list[str] = []
        self.hits = hits

        class Handler(BaseHTTPRequestHandler):
            def do_GET(self) -> None:
                hits.append(self.path)
                z, x, y = (int(v) for v in self.path.removesuffix(".png").split("/")[-3:])
                if has is not None and not has(z, x, y):
                    self.send_error(404)
                    return
                self.send_response(200)
                self.send_header("Content-Type", "image/png")
                self.send_header("Content-Length", str(len(data)))
                self.end_headers()
                self.wfile.write(data)

            def log_message(self, *args: object) -> None:
                pass

        self.httpd = ThreadingHTTPServer(("127.0.0.1", 0), Handler)
        self.url = f"http://127.0.0.1:{self.httpd.server_address[1]}/{{z}}/{{x}}/{{y}}.png"
        self.thread = threading.Thread(target=self.httpd.serve_forever, daemon=True)

    def __enter__(self) -> TileServer:
        self.thread.start()
        return self

    def __exit__(self, *exc: object) -> None:
        self.httpd.shutdown()
        self.httpd.server_close()
        self.thread.join(10)

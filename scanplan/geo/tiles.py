"""XYZ map tiles from a URL template, kept on disk: the one fetch and cache the page's tile
layer (:mod:`scanplan.web.basemap`) and the PDF's map page (``[map] basemap`` as a URL,
:func:`scanplan.geo.basemap.read_tiles`) share.

A template is an http(s) URL with ``{z}``, ``{x}`` and ``{y}`` and no other placeholder (the
"slippy map" tile numbering of OpenStreetMap and every XYZ service: zoom ``z``, column ``x``
from the west, row ``y`` from the north — https://wiki.openstreetmap.org/wiki/Slippy_map_tilenames).
A fetched tile (an image by its first bytes, at most :data:`MAX_TILE_BYTES`) is kept under
the cache folder (by default the user's cache, :func:`default_cache`) — one folder per
template — and read from there afterwards, also offline; the cache keeps at most
:data:`MAX_CACHE_TILES` tiles.
"""

from __future__ import annotations

import hashlib
import os
import re
import tempfile
import threading
import urllib.error
import urllib.request
from pathlib import Path

from .._version import __version__
from ..errors import InputError

__all__ = ["FETCH_TIMEOUT_S", "MAX_CACHE_TILES", "MAX_TILE_BYTES", "MAX_ZOOM",
           "OSM_ATTRIBUTION", "OSM_URL", "TileCache", "TileUnreachable", "check_template",
           "default_cache", "image_type", "template_host"]

OSM_URL = "https://tile.openstreetmap.org/{z}/{x}/{y}.png"
OSM_ATTRIBUTION = "© OpenStreetMap contributors"
MAX_ZOOM = 22
"""Deepest zoom level a tile is asked for."""
MAX_TILE_BYTES = 2 * 1024 * 1024
"""Largest tile fetched or read [bytes]."""
MAX_CACHE_TILES = 200_000
"""Most tiles the disk cache keeps (a town at zoom 12–19 is a few thousand)."""
FETCH_TIMEOUT_S = 10.0
"""How long one tile's request may take [s]."""
_IMAGE = (b"\x89PNG\r\n\x1a\n", b"\xff\xd8\xff", b"RIFF", b"GIF8")
_PLACEHOLDER = re.compile(r"\{[^}]*\}")


class TileUnreachable(OSError):
    """The tile server did not answer (no network, a refused connection, a timeout) — as
    opposed to a server that answered without a tile."""


def image_type(data: bytes) -> str | None:
    """The media type of a PNG, JPEG, WebP or GIF image by its first bytes; None otherwise."""
    if data.startswith(_IMAGE[0]):
        return "image/png"
    if data.startswith(_IMAGE[1]):
        return "image/jpeg"
    if data.startswith(_IMAGE[2]) and data[8:12] == b"WEBP":
        return "image/webp"
    if data.startswith(_IMAGE[3]):
        return "image/gif"
    return None


def default_cache() -> Path:
    """The user's cache folder for tiles (``$XDG_CACHE_HOME/scanplan/tiles``)."""
    root = os.environ.get("XDG_CACHE_HOME") or str(Path.home() / ".cache")
    return Path(root) / "scanplan" / "tiles"


def check_template(url: str, field: str = "--tiles",
                   allowed: str = '"osm", "none" or ') -> None:
    """Refuse a tile URL that is not http(s) with ``{z}``, ``{x}`` and ``{y}`` (and no other
    placeholder), naming ``field`` and the allowed form (``allowed`` precedes "an http(s)
    URL …")."""
    others = set(_PLACEHOLDER.findall(url)) - {"{z}", "{x}", "{y}"}
    if not (url.startswith(("https://", "http://")) and len(url) <= 2000 and not others
            and all(k in url for k in ("{z}", "{x}", "{y}"))):
        raise InputError(field, f"must be {allowed}an http(s) URL with {{z}}, {{x}} and "
                         f"{{y}}, e.g. {OSM_URL!r} (got {url[:200]!r})")


def template_host(url: str) -> str:
    """The host a template's tiles come from (``tile.openstreetmap.org``)."""
    m = re.match(r"^https?://([^/]+)", url)
    return m.group(1) if m else url


class TileCache:
    """XYZ tiles fetched from URL templates and kept on disk (see the module docstring).

    Parameters
    ----------
    root : Path or None
        The cache folder (default :func:`default_cache`).
    """

    def __init__(self, root: Path | None = None) -> None:
        self.root = root if root is not None else default_cache()
        self._lock = threading.Lock()

    def _folder(self, url: str, z: int, x: int) -> Path:
        return self.root / hashlib.sha256(url.encode()).hexdigest()[:16] / str(z) / str(x)

    def cached(self, url: str, z: int, x: int, y: int) -> tuple[bytes, str] | None:
        """The kept tile's bytes and media type, or None when it is not kept."""
        path = self._folder(url, z, x) / str(y)
        try:
            data = path.read_bytes() if path.is_file() else b""
        except OSError:
            return None
        kind = image_type(data)
        return (data, kind) if kind and len(data) <= MAX_TILE_BYTES else None

    def get(self, url: str, z: int, x: int, y: int, *, fetch: bool = True
            ) -> tuple[bytes, str] | None:
        """Tile ``z/x/y`` of the template ``url``: from the cache, else fetched (when
        ``fetch``) and kept; None when the server has no such tile (or not an image).

        Raises
        ------
        TileUnreachable
            The server did not answer.
        """
        got = self.cached(url, z, x, y)
        if got is not None or not fetch:
            return got
        tile_url = url.replace("{z}", str(z)).replace("{x}", str(x)).replace("{y}", str(y))
        req = urllib.request.Request(tile_url, headers={
            "User-Agent": f"scanplan/{__version__} (survey planning; tile cache)"})
        try:
            with urllib.request.urlopen(req, timeout=FETCH_TIMEOUT_S) as r:
                data = r.read(MAX_TILE_BYTES + 1)
        except urllib.error.HTTPError:
            return None  # it answered: no tile there
        except (OSError, ValueError) as exc:
            raise TileUnreachable(str(exc)) from None
        kind = image_type(data)
        if len(data) > MAX_TILE_BYTES or kind is None:
            return None
        self._keep(self._folder(url, z, x), str(y), data)
        return data, kind

    def _keep(self, folder: Path, name: str, data: bytes) -> None:
        """Write a tile into the cache (atomically; nothing past :data:`MAX_CACHE_TILES`)."""
        with self._lock:
            count_file = self.root / "count"
            try:
                count = int(count_file.read_text()) if count_file.is_file() else 0
            except (OSError, ValueError):
                count = 0
            if count >= MAX_CACHE_TILES:
                return
            try:
                folder.mkdir(parents=True, exist_ok=True)
                fd, tmp = tempfile.mkstemp(dir=folder, prefix=".tile-")
                with os.fdopen(fd, "wb") as f:
                    f.write(data)
                os.replace(tmp, folder / name)
                count_file.write_text(str(count + 1))
            except OSError:
                return

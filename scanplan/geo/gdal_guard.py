"""GDAL for untrusted inputs: no network, no other files, formats decided by content.

GDAL opens far more than the file it is given: a virtual dataset (VRT, an XML file of any
name) names other files, ``/vsizip/`` archives or ``/vsicurl/`` URLs to read; any file may
be zip bytes that a driver unpacks; a raster's ``.ovr`` or ``.msk`` companion is opened with
any driver. scanplan's GIS inputs (``[area] file``, ``[terrain] dem``) therefore go through
three guards:

1. :func:`harden` sets GDAL's configuration for the whole process before anything is
   opened (:data:`GDAL_CONFIG`): ``/vsicurl/`` — and the cloud file systems built on it —
   may open no file at all, no directory is listed on open, no ``.aux.xml`` is read or
   written, and the drivers that open other datasets or URLs by name are deregistered
   (:data:`SKIPPED_DRIVERS`).
2. :func:`sniff` decides what a file is by its first bytes, never by its name; the callers
   accept only the kinds they read (an area: KML, KMZ, GeoJSON, GeoPackage, Shapefile; a
   DEM: TIFF) and refuse a VRT, an archive or anything else with a message naming the file.
3. Each open allows only the drivers of that kind (rasterio's ``driver=``; the driver
   pyogrio used is checked against the kind).

:func:`gdal_messages` keeps GDAL's own errors and the tracebacks rasterio prints for a
message it cannot decode (a damaged TIFF text tag) off the terminal, so the caller can
refuse the file with one clean message.
"""

from __future__ import annotations

import contextlib
import importlib.util
import io
import logging
import os
import re
import sys
import warnings
import zipfile
from collections.abc import Iterator
from dataclasses import dataclass, field
from types import ModuleType
from typing import Any

__all__ = ["GDAL_CONFIG", "KIND_NAMES", "SKIPPED_DRIVERS", "GdalMessages", "gdal_messages",
           "harden", "indirection", "read_head", "sniff"]

GDAL_CONFIG: dict[str, str] = {
    # /vsicurl/ (and /vsis3/, /vsigs/, /vsiaz/ … built on it) opens only names ending in
    # an allowed extension: none is allowed, so no URL is ever requested
    "CPL_VSIL_CURL_ALLOWED_EXTENSIONS": "",
    # everything GDAL fetches itself (a CRS "link", a driver's HTTP request) goes through
    # a proxy of no scheme curl knows: it fails before any connection or name lookup
    "GDAL_HTTP_PROXY": "none://no-network.invalid:9",
    "GDAL_HTTPS_PROXY": "none://no-network.invalid:9",
    "GDAL_HTTP_MAX_RETRY": "0",
    "GDAL_HTTP_TIMEOUT": "1",
    "GDAL_HTTP_CONNECTTIMEOUT": "1",
    # no directory listing on open (GDAL otherwise lists the folder to find companions)
    "GDAL_DISABLE_READDIR_ON_OPEN": "EMPTY_DIR",
    # no .aux.xml companion read (nor written beside the user's DEM)
    "GDAL_PAM_ENABLED": "NO",
    # should a VRT ever open: no Python pixel functions, no raw access to other files
    "GDAL_VRT_ENABLE_PYTHON": "NO",
    "GDAL_VRT_ENABLE_RAWRASTERBAND": "NO",
}
"""GDAL configuration options set for the whole process (environment and pyogrio's GDAL)."""

SKIPPED_DRIVERS: tuple[str, ...] = (
    "VRT", "OGR_VRT", "GTI", "GDALG", "STACIT", "STACTA", "WMS", "WMTS", "WCS", "WFS",
    "OAPIF", "OGCAPI", "CSW", "HTTP", "PLMosaic", "EEDA", "EEDAI", "NGW", "Elasticsearch",
    "CouchDB", "Carto", "AmigoCloud", "DAAS", "ESRIC", "TileDB", "Zarr",
)
"""Drivers deregistered (GDAL_SKIP): those whose datasets name other datasets, files or
URLs to open (virtual and tile-index formats, web services)."""

_state = {"done": False}


def import_pyogrio() -> ModuleType:
    """pyogrio, imported without pandas where nothing can need it.

    pyogrio's package imports its GeoPandas layer, which imports pandas (0.3–0.9 s) only to
    note its version for ``read_dataframe``/``write_dataframe`` — functions that need
    GeoPandas. scanplan reads and writes with ``pyogrio.raw``; so where GeoPandas is not
    installed and pandas not yet imported, pandas is hidden while pyogrio is imported
    (pyogrio then notes "no pandas", which without GeoPandas changes nothing it can do).
    pandas itself stays importable afterwards.
    """
    if "pyogrio" in sys.modules or "pandas" in sys.modules or \
            importlib.util.find_spec("geopandas") is not None:
        import pyogrio

        return pyogrio
    sys.modules["pandas"] = None  # type: ignore[assignment]  # "import pandas" fails
    try:
        import pyogrio
    finally:
        if sys.modules.get("pandas", 0) is None:
            del sys.modules["pandas"]
    return pyogrio


def harden() -> None:
    """Set :data:`GDAL_CONFIG` and :data:`SKIPPED_DRIVERS` for the process (idempotent).

    The options go into the environment, where every GDAL in the process (pyogrio's and
    rasterio's wheels each carry one) reads them at each open; a GDAL already loaded gets
    them as configuration options, and pyogrio's drivers are registered again so that the
    skipped ones are gone even when pyogrio was imported before scanplan.
    """
    if not _state["done"]:
        # pyogrio's GDAL registers its drivers when imported, and would print "unable to
        # find driver" to stderr for each skipped one it was built without: imported
        # first, its drivers are re-registered below with its error handler in place
        # (also when a hardened parent process left GDAL_SKIP in the environment)
        inherited = os.environ.pop("GDAL_SKIP", None)
        try:
            with contextlib.suppress(ImportError):
                import_pyogrio()
        finally:
            if inherited is not None:
                os.environ["GDAL_SKIP"] = inherited
    skip = " ".join(dict.fromkeys(
        [*os.environ.get("GDAL_SKIP", "").split(), *SKIPPED_DRIVERS]))
    wanted = {**GDAL_CONFIG, "GDAL_SKIP": skip}
    os.environ.update(wanted)
    if _state["done"]:
        return
    if "pyogrio" in sys.modules:  # imported before us: its GDAL registered every driver
        import pyogrio

        pyogrio.set_gdal_config_options(wanted)
        with contextlib.suppress(ImportError, AttributeError), warnings.catch_warnings():
            warnings.simplefilter("ignore", RuntimeWarning)  # a skipped driver not built in
            from pyogrio._ogr import _register_drivers

            _register_drivers()  # GDALAllRegister again: applies GDAL_SKIP
    if "rasterio" in sys.modules:
        from rasterio import _env

        for key, value in wanted.items():
            _env.set_gdal_config(key, value)
    _state["done"] = True


# -------------------------------------------------------------------------------------------
# Content
# -------------------------------------------------------------------------------------------
_INDIRECTION = re.compile(rb"/vsi[a-z0-9_]*/|<\s*(?:OGR)?VRT(?:DataSource|Dataset)\b",
                          re.IGNORECASE)
_TIFF = (b"II*\x00", b"MM\x00*", b"II+\x00", b"MM\x00+")
_GPKG_IDS = (b"GPKG", b"GP10", b"GP11")


def sniff(data: bytes) -> str:
    """What the bytes are, from their content alone.

    Returns one of ``"zip"``, ``"gzip"``, ``"archive"`` (7z, rar, tar, bzip2, xz),
    ``"tiff"``, ``"gpkg"``, ``"sqlite"`` (not a GeoPackage), ``"shp"`` (a Shapefile's
    ``.shp``), ``"vrt"`` (a GDAL virtual dataset, raster or vector), ``"kml"``, ``"xml"``
    (other XML), ``"json"``, ``"empty"`` or ``"unknown"``.
    """
    head = data[:1024]
    if head.startswith((b"PK\x03\x04", b"PK\x05\x06", b"PK\x07\x08")):
        return "zip"
    if head.startswith(b"\x1f\x8b"):
        return "gzip"
    if head.startswith((b"7z\xbc\xaf\x27\x1c", b"Rar!", b"BZh", b"\xfd7zXZ")) or \
            data[257:262] == b"ustar":
        return "archive"
    if head.startswith(_TIFF):
        return "tiff"
    if head.startswith(b"SQLite format 3\x00"):
        return "gpkg" if data[68:72] in _GPKG_IDS else "sqlite"
    if head.startswith(b"\x00\x00\x27\x0a"):
        return "shp"
    text = head.lstrip(b"\xef\xbb\xbf \t\r\n")
    if re.search(rb"<\s*(?:OGR)?VRT(?:DataSource|Dataset)\b", head, re.IGNORECASE):
        return "vrt"
    if text.startswith(b"<"):
        return "kml" if re.search(rb"<\s*(?:\w+:)?kml\b", data[:65536]) else "xml"
    if text.startswith((b"{", b"[")):
        return "json"
    if not data:
        return "empty"
    if zipfile.is_zipfile(io.BytesIO(data)):  # a zip behind a prefix (self-extracting)
        return "zip"
    return "unknown"


KIND_NAMES: dict[str, str] = {
    "zip": "a zip archive", "gzip": "a gzip-compressed file",
    "archive": "a compressed archive", "tiff": "a TIFF raster",
    "gpkg": "a GeoPackage", "sqlite": "an SQLite database (not a GeoPackage)",
    "shp": "a Shapefile", "vrt": "a GDAL virtual dataset (VRT)", "kml": "KML",
    "xml": "XML that is not KML", "json": "JSON", "empty": "empty",
    "unknown": "of no format scanplan reads",
}
"""How messages name each kind of :func:`sniff`."""


def read_head(path: str | os.PathLike[str], size: int = 1024) -> bytes | None:
    """The first ``size`` bytes of the regular file ``path``; None when it is not a
    regular file or cannot be read (a FIFO or a device is never opened)."""
    import stat

    try:
        if not stat.S_ISREG(os.stat(path).st_mode):
            return None
        fd = os.open(path, os.O_RDONLY | getattr(os, "O_NONBLOCK", 0)
                     | getattr(os, "O_CLOEXEC", 0) | getattr(os, "O_BINARY", 0))
    except OSError:
        return None
    try:
        if not stat.S_ISREG(os.fstat(fd).st_mode):
            return None
        return os.read(fd, size)
    except OSError:
        return None
    finally:
        os.close(fd)


def indirection(data: bytes) -> str | None:
    """The first reference to another dataset in ``data`` (a ``/vsi…/`` path or a VRT
    element), or None."""
    m = _INDIRECTION.search(data)
    return None if m is None else m.group(0).decode("ascii", "replace")


# -------------------------------------------------------------------------------------------
# Messages
# -------------------------------------------------------------------------------------------
@dataclass
class GdalMessages:
    """What GDAL said during a :func:`gdal_messages` block.

    ``errors``: GDAL errors (logged by rasterio at ERROR or above); ``undecodable``: how
    many GDAL messages could not even be decoded (their text held bytes that are not UTF-8,
    e.g. a damaged TIFF text tag); ``warnings``: GDAL warnings (kept, never printed).
    """

    errors: list[str] = field(default_factory=list)
    warnings: list[str] = field(default_factory=list)
    undecodable: int = 0

    def damage(self) -> str | None:
        """A one-line account of what GDAL could not read, or None when nothing."""
        if self.undecodable:
            return ("a metadata text in it is not valid text, so GDAL could not read it "
                    "(a unit, nodata or scale it holds would be lost)")
        if self.errors:
            return " ".join(self.errors[0].split())[:200]
        return None


class _Collect(logging.Handler):
    def __init__(self, sink: GdalMessages) -> None:
        super().__init__(logging.DEBUG)
        self.sink = sink

    def emit(self, record: logging.LogRecord) -> None:
        text = record.getMessage()
        if record.levelno >= logging.ERROR:
            self.sink.errors.append(text)
        elif record.levelno >= logging.WARNING:
            self.sink.warnings.append(text)


@contextlib.contextmanager
def gdal_messages() -> Iterator[GdalMessages]:
    """Collect what rasterio's GDAL says instead of printing it.

    rasterio logs GDAL's errors and warnings (logger ``rasterio``); a message whose bytes
    are not UTF-8 makes its error handler raise inside GDAL's callback, and Python prints
    that exception as an "ignored" traceback. Within the block both are collected into the
    yielded :class:`GdalMessages` and nothing reaches the terminal.

    The block swaps process-wide hooks (``sys.unraisablehook``, ``sys.stderr``): it is
    meant for the short opens and reads of one thread, as scanplan's DEM reader does.
    """
    sink = GdalMessages()
    logger = logging.getLogger("rasterio")
    handler = _Collect(sink)
    old_level, old_propagate = logger.level, logger.propagate
    old_hook = sys.unraisablehook

    def hook(unraisable: Any) -> None:
        if isinstance(unraisable.exc_value, UnicodeDecodeError):
            sink.undecodable += 1
        else:
            old_hook(unraisable)

    logger.addHandler(handler)
    logger.setLevel(logging.WARNING)
    logger.propagate = False
    sys.unraisablehook = hook
    printed = io.StringIO()
    try:
        with contextlib.redirect_stderr(printed):  # the exception's own line, printed by C
            yield sink
    finally:
        sys.unraisablehook = old_hook
        logger.removeHandler(handler)
        logger.setLevel(old_level)
        logger.propagate = old_propagate
        if "UnicodeDecodeError" in printed.getvalue():
            sink.undecodable = max(sink.undecodable, 1)
        rest = "\n".join(line for line in printed.getvalue().splitlines()
                         if "UnicodeDecodeError" not in line)
        if rest.strip():
            sink.warnings.append(rest.strip())


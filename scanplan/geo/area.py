"""The contract area: a polygon from a GIS file or the project file, in a metric planning CRS.

Sources (one of them):

- a file — KML, KMZ, GeoJSON, GeoPackage, Shapefile, recognised by its content (not its
  name) and read with pyogrio; ``layer`` and ``feature`` choose when it holds several
  polygons;
- an inline ring ``[[lon, lat], ...]`` (or ``[[x, y], ...]`` in ``crs``);
- the abstract ``width_m × length_m`` block: a rectangle in a local metric frame, not
  georeferenced, planned by the same code as a real polygon.

Planning happens in a projected metric CRS: ``plan_crs`` when given; else the CRS the
coordinates came in, when that is projected in metres (a Gauss–Krüger zone, a local
system); else the UTM zone of a point inside the area (by the zone rule, with the UTM grid's
Norway and Svalbard exceptions: :mod:`.crs`).

Every problem is an :class:`~scanplan.errors.InputError` naming the file (and feature) or
the key, what is wrong and what is allowed; nothing is guessed. Hostile files are refused
before a parser sees them: GDAL's network and virtual-file access is off for the process
(:mod:`.gdal_guard`); a size bound; the kind decided by content, a VRT or a reference to
another dataset refused; zip content of any name read only as a KMZ, its zip directory
checked (entries, inflated size, compression ratio) before anything is inflated and an
inner archive refused; KML with a document type declaration (entities) refused; KML,
GeoJSON and GeoPackage handed to GDAL from memory; more than :data:`MAX_FEATURES` features
refused with their count, never cut (docs/gis-inputs.md).
"""

from __future__ import annotations

import hashlib
import io
import math
import os
import re
import warnings
import zipfile
import zlib
from collections.abc import Sequence
from dataclasses import dataclass, replace
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np
import shapely
from shapely.validation import explain_validity

from ..errors import InputError
from ..io.files import read_limited, size_text
from ..io.kept import MISSING, Kept
from . import crs as geocrs
from .gdal_guard import KIND_NAMES, harden, import_pyogrio, indirection, read_head, sniff
from .grids import require_grids
from .layout import Area
from .vertices import VERTEX_SUFFIXES, read_vertices

if TYPE_CHECKING:  # pyproj (60 ms) is imported when a polygon is read, not for a block
    import pyproj

__all__ = ["MAX_AREA_KM2", "AreaSpec", "forget_read_areas", "load_area", "rectangle_area"]

MAX_AREA_KM2 = 10_000.0
"""Largest contract area [km²] (a larger block is a regional programme, not one plan)."""
MIN_AREA_M2 = 1.0
"""Smallest area [m²]: below it the polygon is degenerate (points on a line)."""
MIN_WIDTH_M = 0.1
"""Smallest mean width 2·area/perimeter [m]: a thinner polygon is a line drawn as a ring."""
MAX_FILE_BYTES = 64 * 1024 * 1024
"""Largest area file read [bytes] (a town boundary is kilobytes)."""
MAX_KMZ_ENTRIES = 1_000
"""Most entries in a KMZ's zip directory."""
MAX_KMZ_INFLATED = 64 * 1024 * 1024
"""Most bytes a KMZ may inflate to, all entries together [bytes]."""
MAX_KMZ_RATIO = 200.0
"""Largest compression ratio of a KMZ entry (text compresses ~10:1; a bomb ~1000:1)."""
MAX_FEATURES = 100_000
"""Most features read from one file."""
MAX_VERTICES = 1_000_000
"""Most vertices of the area."""
MAX_SCALE_ERROR_PCT = 0.1
"""Largest scale error of the planning projection over the area without a warning [%]:
what a 6° UTM zone reaches at its edge on the equator (k ≈ 1.001); inside its zone no
UTM or 6° Gauss–Krüger area exceeds it (geodetic property of the projection, not a norm)."""
_DTD = re.compile(rb"<!\s*(DOCTYPE|ENTITY)", re.IGNORECASE)
_GEOJSON_CRS = re.compile(rb'"crs"\s*:\s*\{[^{}]*(?:\{[^{}]*\}[^{}]*)*\}')
_NAME_FIELDS = ("name", "Name", "NAME", "title", "Title")


@dataclass(frozen=True)
class AreaSpec:
    """What the project (or the command line) says about the area.

    Attributes
    ----------
    file : path or None
        A GIS file with the polygon.
    layer : str or None
        Layer of ``file`` to read (default: every layer).
    feature : str, int or None
        The polygon's name (its ``name`` attribute) or running number from 1.
    polygon : sequence of (x, y) or None
        An inline ring, lon/lat in WGS 84 unless ``crs``.
    crs : str or None
        CRS of ``polygon`` (or of a file that declares none), e.g. ``"EPSG:28407"``.
    plan_crs : str or None
        Planning CRS (projected, metres).
    width_m, length_m : float or None
        The abstract rectangle.
    """

    file: str | os.PathLike[str] | None = None
    layer: str | None = None
    feature: str | int | None = None
    polygon: Sequence[Sequence[float]] | None = None
    crs: str | int | None = None
    plan_crs: str | int | None = None
    width_m: float | None = None
    length_m: float | None = None


def rectangle_area(width_m: float, length_m: float) -> Area:
    """The abstract block ``width_m × length_m`` as an area in a local metric frame.

    The rectangle runs from (0, 0) to (width, length): x across the flight lines, y along
    them (flight direction 0°), so the same flight-line code plans it as any polygon.
    """
    geom = shapely.box(0.0, 0.0, float(width_m), float(length_m))
    return Area(geometry=geom, plan_crs="LOCAL",
                source=f"rectangle {width_m:g} × {length_m:g} m", georeferenced=False,
                area_km2=width_m * length_m / 1e6,
                perimeter_km=2.0 * (width_m + length_m) / 1e3, centroid_lonlat=None,
                plan_crs_name="", input_crs=None)


def load_area(spec: AreaSpec) -> Area | None:
    """The area ``spec`` describes, in its planning CRS (None when it describes none).

    Raises
    ------
    InputError
        ``field`` names the file (and feature) or the key (``polygon``, ``crs``,
        ``plan_crs``, ``file``, ``layer``, ``feature``); the message says what is wrong and
        what is allowed.
    """
    given = [k for k in ("file", "polygon") if getattr(spec, k) is not None]
    rect = spec.width_m is not None or spec.length_m is not None
    if len(given) > 1 or (given and rect):
        raise InputError(given[-1] if len(given) > 1 else given[0],
                         "give one area: a file, an inline polygon, or width_m × length_m")
    for key in ("layer", "feature"):
        if getattr(spec, key) is not None and spec.file is None:
            raise InputError(key, "chooses among the polygons of [area] file; give the file")
    if not given:
        if spec.crs is not None or spec.plan_crs is not None:
            raise InputError("crs" if spec.crs is not None else "plan_crs",
                             "applies to a polygon; give [area] file or polygon")
        if not rect:
            return None
        if spec.width_m is None or spec.length_m is None:
            raise InputError("width_m" if spec.width_m is None else "length_m",
                             "is required with the other side of [area]: give both width_m "
                             "and length_m")
        return rectangle_area(float(spec.width_m), float(spec.length_m))
    key = _kept_key(spec)
    name = str(spec.file) if spec.file is not None else ""
    found = _KEPT.get(key) if key is not None else MISSING
    if found is not MISSING:
        was, area = found  # type: ignore[misc]
        return area if was == name else _renamed(area, was, name)
    area = _load_polygon(spec)
    if key is not None:
        _KEPT.put(key, (name, area))
    return area


def _renamed(area: Area, was: str, name: str) -> Area:
    """A kept area read from the same bytes under another name (the page stages every
    request's uploads in a folder of its own): the file named as it is now."""
    return replace(area, source=name + area.source[len(was):] if area.source.startswith(was)
                   else area.source,
                   source_file=name if area.source_file == was else area.source_file)


_KEPT_AREAS = 32
_KEPT: Kept[tuple[Any, ...], tuple[str, Area]] = Kept(_KEPT_AREAS)
"""Polygons kept read and projected (the page re-plans the same area on every edit)."""


def forget_read_areas() -> None:
    """Forget every polygon kept read and projected (the next :func:`load_area` of a file
    or an inline polygon reads and projects it again)."""
    _KEPT.clear()


def _kept_key(spec: AreaSpec) -> tuple[Any, ...] | None:
    """What a polygon's :class:`Area` depends on: the keys, and the file's bytes (their
    SHA-256; the file's name is only its label) — None for a Shapefile, whose companion
    files matter too (read every time)."""
    keys = (spec.layer, spec.feature, repr(spec.crs), repr(spec.plan_crs))
    if spec.file is None:
        try:
            return ("polygon", repr(spec.polygon), *keys)
        except RecursionError:  # a nesting no polygon has: refused by the reader
            return None
    path = Path(spec.file)
    try:
        data = read_limited(path, MAX_FILE_BYTES, field=str(path))
    except (InputError, OSError):  # refused as before by the reader, in its words
        return None
    if path.suffix.lower() not in VERTEX_SUFFIXES and sniff(data) == "shp":
        return None
    return ("file", hashlib.sha256(data).hexdigest(), *keys)


def _load_polygon(spec: AreaSpec) -> Area:
    """:func:`load_area` of a file or an inline polygon, read and projected."""
    user_crs = _crs(spec.crs, "crs") if spec.crs is not None else None
    if spec.file is not None:
        geom, file_crs, where, parts = _read_source(Path(spec.file), spec.layer, spec.feature)
        if file_crs is not None and user_crs is not None and file_crs != user_crs:
            raise InputError("crs", f"{user_crs.to_string()} differs from the CRS "
                             f"{file_crs.to_string()} that {where} declares; remove "
                             "[area] crs (it is for coordinates without a CRS)")
        in_crs = file_crs or user_crs or geocrs.epsg_crs(4326)
    else:
        geom = _inline(spec.polygon)
        file_crs = None
        where = "inline polygon"
        parts = (None, None, None)
        in_crs = user_crs or geocrs.epsg_crs(4326)
    field = where if spec.file is not None else "polygon"
    assumed = spec.file is not None and file_crs is None and user_crs is None
    try:
        _check_input_geometry(geom, in_crs, field)
    except InputError as exc:
        if assumed and ("latitude" in exc.message or "longitude" in exc.message):
            raise InputError(exc.field, exc.message + "; the file declares no CRS, so WGS 84 "
                             "lon/lat was assumed: give [area] crs, e.g. \"EPSG:28407\""
                             ) from None
        raise
    plan = _plan_crs(spec.plan_crs, in_crs, geom)
    return replace(_project(geom, in_crs, plan, where, field), source_file=parts[0],
                   source_feature=parts[1], source_layer=parts[2])


# -------------------------------------------------------------------------------------------
# Sources
# -------------------------------------------------------------------------------------------
def _inline(ring: Any) -> shapely.Polygon:
    """An inline ring → a polygon; at least 3 distinct points of two finite numbers each."""
    if not isinstance(ring, list | tuple) or not ring:
        raise InputError("polygon", "must be a list of [lon, lat] points, e.g. [[37.60, "
                         "55.75], [37.62, 55.75], [37.62, 55.76]]")
    if len(ring) > MAX_VERTICES:
        raise InputError("polygon", f"has {len(ring):,} points; at most {MAX_VERTICES:,}")
    pts: list[tuple[float, float]] = []
    for i, p in enumerate(ring, start=1):
        ok = (isinstance(p, list | tuple) and len(p) == 2
              and all(isinstance(c, int | float) and not isinstance(c, bool) for c in p))
        if not ok or not all(math.isfinite(float(c)) for c in p):
            raise InputError("polygon", f"point {i} must be [lon, lat] (two finite numbers); "
                             f"got {p!r}"[:300])
        pts.append((float(p[0]), float(p[1])))
    if len(pts) > 1 and pts[0] == pts[-1]:
        pts = pts[:-1]
    if len(set(pts)) < 3:
        raise InputError("polygon", f"has {len(set(pts))} distinct point(s); a polygon needs "
                         "at least 3")
    return shapely.Polygon(pts)


def _read_source(path: Path, layer: str | None, feature: str | int | None
                 ) -> tuple[Any, pyproj.CRS | None, str, tuple[str, str, str | None]]:
    """A list of the boundary's vertices (CSV/TXT, :mod:`.vertices`), else a GIS file."""
    name = str(path)
    vertices = read_vertices(path, name) if path.suffix.lower() in VERTEX_SUFFIXES else None
    if vertices is None:
        return _read_file(path, layer, feature)
    extra = "layer" if layer is not None else "feature" if feature is not None else None
    if extra is not None:
        raise InputError(extra, f"{name} is a list of vertices: one polygon, no layers; "
                         f"remove [area] {extra}")
    return vertices, None, name, (name, "vertices", None)


def _read_file(path: Path, layer: str | None, feature: str | int | None
               ) -> tuple[Any, pyproj.CRS | None, str, tuple[str, str, str | None]]:
    """The chosen polygon of a GIS file, its CRS (None if it declares none), its name, and
    (file, feature, layer) for reports."""
    pyogrio = import_pyogrio()

    name = str(path)
    source, layers = _layers(path, name)
    names = [str(n) for n, _ in layers]
    if layer is not None:
        if layer not in names:
            raise InputError("layer", f"{layer!r} is not a layer of {name}; its layers: "
                             f"{_listed(names)}")
        names = [layer]
    found: list[tuple[str, str, Any, pyproj.CRS | None]] = []  # (label, layer, geom, crs)
    other = 0
    all_names = [str(n) for n, _ in layers]
    for lyr in names:
        _rewound(source)
        try:  # by index: a layer read from memory gets a new random name at every open
            with warnings.catch_warnings():
                warnings.simplefilter("ignore", RuntimeWarning)
                meta, _, wkb, fields = pyogrio.raw.read(
                    source, layer=all_names.index(lyr), max_features=MAX_FEATURES + 1)
        except Exception as exc:
            raise InputError(name, f"layer {lyr!r} cannot be read: "
                             f"{_gdal_text(exc, name)}") from None
        if wkb is not None and len(wkb) > MAX_FEATURES:
            raise InputError(name, f"layer {lyr!r} holds "
                             f"{_feature_count(source, all_names.index(lyr))} features; at "
                             f"most {MAX_FEATURES:,} are read (none is dropped unseen): save "
                             "the contract area on its own")
        if wkb is None:
            continue
        geoms = shapely.from_wkb(wkb, on_invalid="ignore")
        crs = geocrs.crs(meta["crs"]) if meta.get("crs") else None
        if crs is not None:
            require_grids(crs, name)
        labels = _labels(meta, fields, len(geoms))
        for label, g in zip(labels, geoms, strict=True):
            if g is None or g.is_empty:
                continue
            g = shapely.force_2d(g)
            if isinstance(g, shapely.GeometryCollection) and not isinstance(
                    g, shapely.MultiPolygon):
                polys = [p for p in g.geoms
                         if isinstance(p, shapely.Polygon | shapely.MultiPolygon)]
                g = shapely.union_all(polys) if polys else None
            if isinstance(g, shapely.Polygon | shapely.MultiPolygon):
                found.append((label, lyr, g, crs))
            else:
                other += 1
    if not found:
        what = f" (it holds {other} point or line feature(s): draw the boundary as a " \
               "polygon)" if other else ""
        raise InputError(name, f"holds no polygon{what}")
    if feature is not None:
        chosen = _choose(found, feature, name)
    elif len(found) == 1:
        chosen = found[0]
    else:
        raise InputError(name, f"holds {len(found)} polygons: "
                         f"{_listed([f'{i}: {f[0]}' for i, f in enumerate(found, 1)])}; "
                         "choose one with [area] feature = \"its name\" or its number"
                         + (" (and [area] layer)" if len(names) > 1 else ""))
    label, lyr, geom, crs = chosen
    where = f"{name}, feature {label!r}" + (f" of layer {lyr!r}" if len(names) > 1 else "")
    return geom, crs, where, (name, label, lyr if len(names) > 1 else None)


def _choose(found: list[tuple[str, str, Any, Any]], feature: str | int, name: str
            ) -> tuple[str, str, Any, Any]:
    if isinstance(feature, int) and not isinstance(feature, bool):
        if not 1 <= feature <= len(found):
            raise InputError("feature", f"must be 1 … {len(found)}, the number of a polygon "
                             f"of {name} (got {feature})")
        return found[feature - 1]
    hits = [f for f in found if f[0] == feature] or [
        f for f in found if f[0].casefold() == str(feature).casefold()]
    if len(hits) == 1:
        return hits[0]
    if not hits:
        raise InputError("feature", f"{name} has no polygon named {feature!r}; its polygons: "
                         f"{_listed([f[0] for f in found])}")
    raise InputError("feature", f"{name} has {len(hits)} polygons named {feature!r}; give its "
                     f"number (1 … {len(found)}) instead")


def _labels(meta: dict[str, Any], fields: list[Any], n: int) -> list[str]:
    """Each feature's name (its name attribute), else ``#k``."""
    cols = list(meta.get("fields", []))
    for key in _NAME_FIELDS:
        if key in cols:
            values = fields[cols.index(key)]
            return [str(v) if v not in (None, "") else f"#{i + 1}"
                    for i, v in enumerate(values)]
    return [f"#{i + 1}" for i in range(n)]


def _listed(items: list[str], most: int = 10) -> str:
    shown = ", ".join(items[:most])
    return shown + (f" … ({len(items)} in all)" if len(items) > most else "")


_VSIMEM = re.compile(r"/vsimem/\S+?(?=\s*[:;,)]|\s|$)")


def _gdal_text(exc: Exception, name: str) -> str:
    """GDAL's error in one line, the in-memory path pyogrio gave the file's bytes
    (``/vsimem/pyogrio_…``) replaced by the name of the user's file ``name``."""
    said = _VSIMEM.sub(lambda _: Path(name).name, f"{exc}").replace(" :", ": ")
    text = " ".join(said.split()).split("; It might help")[0]
    return text[:300] or type(exc).__name__


_DRIVERS: dict[str, tuple[str, ...]] = {
    "kml": ("LIBKML", "KML"), "json": ("GeoJSON", "GeoJSONSeq"), "gpkg": ("GPKG",),
    "shp": ("ESRI Shapefile",)}
"""The GDAL drivers allowed to open each kind of area file (decided by content)."""
_FORMATS = "KML, KMZ, GeoJSON, GeoPackage, Shapefile or a CSV/TXT list of vertices"
MAX_COMPANION_TEXT_BYTES = 1024 * 1024
"""Largest text companion of a Shapefile (.prj, .cpg) [bytes]."""


def _source(path: Path, name: str) -> tuple[str | io.BytesIO, tuple[str, ...]]:
    """What pyogrio opens for the area file ``path`` and the drivers allowed to open it.

    The kind is decided by the file's content, never by its name (:func:`.gdal_guard.
    sniff`): zip bytes of any name go through the bounded KMZ path and must hold a KML
    document (an archive in the archive is refused); KML, GeoJSON and GeoPackage are read
    whole (bounded) and handed to GDAL from memory, so GDAL sees no other file; a Shapefile
    is opened by its path with its companions checked. A VRT, another archive or any other
    content is refused.
    """
    harden()
    data = read_limited(path, MAX_FILE_BYTES, field=name)
    kind = sniff(data)
    if kind == "zip":
        data = _kmz_document(data, name)
        kind = sniff(data)
        if kind != "kml":
            raise InputError(name, f"is a zip archive (a KMZ) whose document is "
                             f"{KIND_NAMES[kind]}, not KML; an archive inside the archive "
                             "is refused. Save the polygon again as KML or KMZ")
    if kind == "vrt":
        raise InputError(name, "is a GDAL virtual dataset (VRT): it names other files or URLs "
                         "to read, and scanplan reads only the file itself; give the "
                         f"polygon as {_FORMATS}")
    if kind == "shp":
        _check_companions(path, name)
        return str(path), _DRIVERS[kind]
    if kind not in _DRIVERS:
        raise InputError(name, f"cannot be read as a GIS file: its content is "
                         f"{KIND_NAMES[kind]}; an area file is {_FORMATS} (recognised by "
                         "its content, whatever its name)")
    if kind in ("kml", "json"):
        ref = indirection(data)
        if ref is not None:
            raise InputError(name, f"names another dataset ({ref!r}); an area file must hold "
                             "its polygon itself: GDAL's virtual files and URLs are refused")
    if kind == "json" and any(b'"link"' in m.group(0) for m in _GEOJSON_CRS.finditer(data)):
        raise InputError(name, "gives its CRS as a link (a URL or another file), which GDAL "
                         "would fetch; scanplan reads nothing but the file itself: give the "
                         "CRS by name (\"EPSG:…\") in the file or as [area] crs")
    if kind == "kml" and (_DTD.search(data[:65536]) or _DTD.search(data)):
        raise InputError(name, "holds a document type declaration (<!DOCTYPE> or "
                         "<!ENTITY>); KML needs none, and entities are refused. Save "
                         "the polygon again from Google Earth or QGIS")
    return io.BytesIO(data), _DRIVERS[kind]


def _layers(path: Path, name: str) -> tuple[str | io.BytesIO, Any]:
    """The source pyogrio reads (:func:`_source`) and its layers, the driver GDAL used
    checked against the kind the content says."""
    pyogrio = import_pyogrio()

    source, drivers = _source(path, name)
    try:
        with warnings.catch_warnings():  # a GeoPackage read from memory has no .gpkg name
            warnings.simplefilter("ignore", RuntimeWarning)
            layers = pyogrio.list_layers(source)
            driver = (_rewound(source) and pyogrio.read_info(source, layer=0)["driver"]
                      if len(layers) else drivers[0])
    except Exception as exc:  # GDAL's errors are many classes; any of them: unreadable
        raise InputError(name, "cannot be read as a GIS file: "
                         f"{_gdal_text(exc, name)}") from None
    if driver not in drivers:
        raise InputError(name, f"was opened by GDAL as {driver}, not as {drivers[0]} as its "
                         "content says; refused")
    return source, layers


def _rewound(source: str | io.BytesIO) -> bool:
    if isinstance(source, io.BytesIO):
        source.seek(0)
    return True


def _feature_count(source: str | io.BytesIO, layer: int) -> str:
    """The number of features of a layer (``"more than N"`` when GDAL cannot count)."""
    pyogrio = import_pyogrio()

    _rewound(source)
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", RuntimeWarning)
            n = int(pyogrio.read_info(source, layer=layer, force_feature_count=True)
                    ["features"])
    except Exception:  # counting is only for the message
        n = -1
    return f"{n:,}" if n > MAX_FEATURES else f"more than {MAX_FEATURES:,}"


def _check_companions(path: Path, name: str) -> None:
    """A Shapefile's companions (.shx, .dbf, .prj, .cpg, …), which GDAL opens beside it:
    regular files only (a pipe or a device would be a read that never ends), the index a
    Shapefile index, the text ones small and naming no other dataset or URL."""
    import stat

    try:
        siblings = [p for p in path.parent.iterdir()
                    if p.stem.casefold() == path.stem.casefold() and p != path]
    except OSError:
        siblings = []
    for sib in siblings[:100]:
        try:
            mode = sib.stat().st_mode
        except OSError:
            continue
        if not (stat.S_ISREG(mode) or stat.S_ISDIR(mode)):
            raise InputError(name, f"its companion file {sib.name} is not a regular file")
        ext = sib.suffix.lower()
        if ext == ".shx" and sniff(read_head(sib, 4) or b"") != "shp":
            raise InputError(name, f"its companion file {sib.name} is not a Shapefile index")
        if ext in (".prj", ".cpg"):
            text = read_limited(sib, MAX_COMPANION_TEXT_BYTES, field=f"{name}: {sib.name}")
            if (indirection(text) is not None or b"://" in text
                    or sniff(text) in ("zip", "gzip", "archive")):
                raise InputError(name, f"its companion file {sib.name} is not the plain "
                                 "text it should be")


def _kmz_document(data: bytes, name: str) -> bytes:
    """The KML inside a KMZ, its zip directory checked before anything is inflated."""
    try:
        zf = zipfile.ZipFile(io.BytesIO(data))
    except (zipfile.BadZipFile, OSError, ValueError) as exc:
        raise InputError(name, f"is not a KMZ (zip) file: {exc}") from None
    with zf:
        infos = zf.infolist()
        if len(infos) > MAX_KMZ_ENTRIES:
            raise InputError(name, f"holds {len(infos):,} entries; at most "
                             f"{MAX_KMZ_ENTRIES:,}")
        total = sum(i.file_size for i in infos)
        if total > MAX_KMZ_INFLATED:
            raise InputError(name, f"would inflate to {size_text(total)}; the limit is "
                             f"{size_text(MAX_KMZ_INFLATED)} (a zip bomb?)")
        for i in infos:
            if i.file_size > 1024 and i.file_size > MAX_KMZ_RATIO * max(i.compress_size, 1):
                raise InputError(name, f"entry {i.filename!r} inflates "
                                 f"{i.file_size / max(i.compress_size, 1):,.0f} times; at most "
                                 f"{MAX_KMZ_RATIO:g} (a zip bomb?)")
        kml = [i for i in infos if i.filename.lower().endswith(".kml")]
        if not kml:
            raise InputError(name, "holds no .kml document")
        doc = next((i for i in kml if i.filename.lower() == "doc.kml"), kml[0])
        try:
            with zf.open(doc) as fh:
                out = fh.read(doc.file_size + 1)
        except (zipfile.BadZipFile, OSError, ValueError, RuntimeError, EOFError,
                NotImplementedError, zlib.error) as exc:  # zlib: damaged compressed data
            raise InputError(name, f"entry {doc.filename!r} cannot be read: {exc}") from None
        if len(out) > doc.file_size:
            raise InputError(name, f"entry {doc.filename!r} is larger than its zip directory "
                             "says; refused")
        return out


# -------------------------------------------------------------------------------------------
# Checks and projection
# -------------------------------------------------------------------------------------------
def _crs(value: str | int, key: str) -> pyproj.CRS:
    import pyproj

    try:
        crs = geocrs.crs(value)
    except (pyproj.exceptions.CRSError, TypeError, ValueError):
        raise InputError(key, f"{value!r} is not a CRS that pyproj knows; give an EPSG code "
                         "such as \"EPSG:32637\" (UTM 37N) or \"EPSG:28407\" (Pulkovo 1942 / "
                         "Gauss–Krüger zone 7)") from None
    require_grids(crs, key)
    return crs


def _n_vertices(geom: Any) -> int:
    return int(shapely.get_num_coordinates(geom))


def _check_input_geometry(geom: Any, crs: pyproj.CRS, field: str) -> None:
    """Vertex count, lon/lat ranges (geographic input), closed valid rings."""
    if _n_vertices(geom) > MAX_VERTICES:
        raise InputError(field, f"has {_n_vertices(geom):,} vertices; at most "
                         f"{MAX_VERTICES:,}")
    xy = shapely.get_coordinates(geom)
    if not np.isfinite(xy).all():
        raise InputError(field, "has a coordinate that is not a finite number")
    if crs.is_geographic:
        lon, lat = xy[:, 0], xy[:, 1]
        if (np.abs(lat) > 90).any():
            k = int(np.argmax(np.abs(lat) > 90))
            hint = (" — latitude and longitude look swapped: give [lon, lat], longitude first"
                    if (np.abs(lon) <= 90).all() else "")
            raise InputError(field, f"latitude {lat[k]:g}° is outside −90 … 90{hint}")
        if (np.abs(lon) > 180).any():
            k = int(np.argmax(np.abs(lon) > 180))
            raise InputError(field, f"longitude {lon[k]:g}° is outside −180 … 180")
    polys = list(getattr(geom, "geoms", [geom]))
    for p in polys:
        if len(set(map(tuple, shapely.get_coordinates(p.exterior)))) < 3:
            raise InputError(field, "has fewer than 3 distinct points; a polygon needs at "
                             "least 3")
    if not shapely.area(shapely.convex_hull(geom)) > 0:
        raise InputError(field, "encloses no area: its points lie on a line; a block needs "
                         f"an area ≥ {MIN_AREA_M2:g} m²")
    if not shapely.is_valid(geom):
        reason = explain_validity(geom)
        m = re.match(r"(.*?)\[\s*([-0-9.eE+]+)\s+([-0-9.eE+]+)\s*\]", reason)
        unit = ("lon {:.6f}, lat {:.6f}" if crs.is_geographic else "x {:.2f}, y {:.2f}")
        if m and "self-intersection" in m.group(1).lower():
            at = unit.format(float(m.group(2)), float(m.group(3)))
            raise InputError(field, f"crosses itself at {at}; redraw the boundary so that it "
                             "does not cross itself (a figure of eight is two polygons)")
        if m:
            at = unit.format(float(m.group(2)), float(m.group(3)))
            raise InputError(field, f"is not a valid polygon: {m.group(1).strip()} at {at}")
        raise InputError(field, f"is not a valid polygon: {reason}")


def _plan_crs(value: str | int | None, in_crs: pyproj.CRS, geom: Any) -> pyproj.CRS:
    """The planning CRS: given, else the input's when metric projected, else the UTM zone
    of a point inside the area (:func:`.crs.utm_epsg`)."""
    if value is not None:
        plan = _crs(value, "plan_crs")
        if not _metric_projected(plan):
            raise InputError("plan_crs", f"{plan.name} is not a projected CRS in metres; give "
                             "a projected one such as a UTM or a Gauss–Krüger zone")
        return plan
    if _metric_projected(in_crs):
        return in_crs
    c = geom.representative_point() if not geom.is_empty else geom
    lon, lat = geocrs.transformer(in_crs, 4326).transform(c.x, c.y)
    code = geocrs.utm_epsg(lon, lat)
    if code is None:
        raise InputError("plan_crs", f"no UTM zone covers lon {lon:.4f}, lat {lat:.4f} (polar "
                         "area); give [area] plan_crs, e.g. \"EPSG:3413\"")
    return geocrs.epsg_crs(code)


def _metric_projected(crs: pyproj.CRS) -> bool:
    return bool(crs.is_projected and crs.axis_info
                and all(a.unit_name in ("metre", "meter") for a in crs.axis_info[:2]))


def _project(geom: Any, in_crs: pyproj.CRS, plan: pyproj.CRS, where: str, field: str) -> Area:
    tr = geocrs.transformer(in_crs, plan)

    def fwd(xy: np.ndarray) -> np.ndarray:
        x, y = tr.transform(xy[:, 0], xy[:, 1])
        return np.column_stack([x, y])

    with np.errstate(all="ignore"):
        projected = shapely.transform(geom, fwd)
    if not np.isfinite(shapely.get_coordinates(projected)).all():
        raise InputError(field, f"cannot be projected to {plan.name}: it lies outside the "
                         "CRS's area of use; give [area] plan_crs")
    if not shapely.is_valid(projected):
        projected = shapely.make_valid(projected)
    area_m2 = float(projected.area)
    width_m = 2.0 * area_m2 / max(float(projected.length), 1e-300)  # a sliver's width
    if not (area_m2 >= MIN_AREA_M2 and width_m >= MIN_WIDTH_M):
        raise InputError(field, f"encloses {area_m2:g} m² (mean width {width_m:.2g} m): its "
                         f"points lie on a line; a block needs an area ≥ {MIN_AREA_M2:g} m² "
                         f"and a width ≥ {MIN_WIDTH_M:g} m")
    if area_m2 / 1e6 > MAX_AREA_KM2:
        raise InputError(field, f"encloses {area_m2 / 1e6:,.0f} km²; at most "
                         f"{MAX_AREA_KM2:,.0f} km² — split a regional programme into blocks "
                         "(or are the coordinates in the wrong CRS? set [area] crs)")
    to_ll = geocrs.transformer(plan, 4326)
    c = projected.centroid
    lon, lat = to_ll.transform(c.x, c.y)
    epsg = plan.to_epsg()
    in_epsg = in_crs.to_epsg()
    scale_error_pct, lon_range = _scale_error(geom, in_crs, plan)
    return Area(geometry=projected, plan_crs=f"EPSG:{epsg}" if epsg else plan.to_wkt(),
                source=where, georeferenced=True, area_km2=area_m2 / 1e6,
                perimeter_km=float(projected.length) / 1e3,
                centroid_lonlat=(float(lon), float(lat)), plan_crs_name=plan.name,
                input_crs=f"EPSG:{in_epsg}" if in_epsg else in_crs.name,
                scale_error_pct=scale_error_pct, lon_range_deg=lon_range)


def _scale_error(geom: Any, in_crs: pyproj.CRS, plan: pyproj.CRS
                 ) -> tuple[float, tuple[float, float]]:
    """The planning projection's largest scale error ``max |k − 1|`` [%] over the area's
    vertices (inf where pyproj cannot evaluate it) and the area's longitude range [°].

    A 6° UTM zone stays within 0.1 % everywhere (k = 0.9996 on the central meridian, about
    1.001 at the zone's edge on the equator); a larger error means the area runs far out
    of the projection's zone — often a mistyped coordinate.
    """
    import pyproj

    xy = shapely.get_coordinates(geom)
    lon, lat = geocrs.transformer(in_crs, 4326).transform(xy[:, 0], xy[:, 1])
    lon, lat = np.asarray(lon, dtype=float), np.asarray(lat, dtype=float)
    with np.errstate(all="ignore"):
        try:
            factors = geocrs.proj(plan).get_factors(lon, lat, errcheck=False)
            k = np.concatenate([np.atleast_1d(factors.meridional_scale),
                                np.atleast_1d(factors.parallel_scale)]).astype(float)
        except (pyproj.exceptions.ProjError, ValueError, TypeError):
            k = np.array([np.inf])
    err = np.abs(k - 1.0) * 100.0
    worst = float(np.max(np.where(np.isfinite(err), err, np.inf))) if err.size else 0.0
    return worst, (float(np.min(lon)), float(np.max(lon)))

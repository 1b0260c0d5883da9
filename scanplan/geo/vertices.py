"""An area given as a list of its vertices: a CSV or TXT file, one vertex a row.

What a customer's engineer often sends instead of a GIS file::

    lon,lat                lat;lon                  # no header: x then y
    37.6012,55.7503        55,7503;37,6012          37.6012 55.7503
    ...                    ...                      ...

* The delimiter is a semicolon, a tab, a comma or spaces: the first of ``;``, tab, ``,``
  found on every row, else whitespace; the cells are split by :mod:`csv` and pandas.
* A decimal comma is read where the delimiter is not a comma (``55,7503;37,6012``).
* A header row is one whose cells are not all numbers; it names the columns: ``lon`` /
  ``longitude`` / ``x`` / ``easting`` / ``e`` and ``lat`` / ``latitude`` / ``y`` /
  ``northing`` / ``n`` (any case; ``долгота``, ``широта`` too), in either order, other
  columns (a point number) ignored. Without a header the file must have two columns:
  x (longitude, easting) then y (latitude, northing).
* Coordinates are WGS 84 longitude/latitude unless ``[area] crs`` states the CRS of the
  list (``"EPSG:28407"``); x is always the easting — a survey list whose X is the
  northing must name its columns (``northing;easting``).
* A table whose header names a ``WKT`` (or ``geometry``) column holds a polygon per row,
  read by shapely (never by GDAL, whose CSV driver follows references): the area is their
  union.
* Blank lines and lines starting with ``#`` are skipped; the ring may repeat its first
  vertex at the end.

The file is split into rows and cells by pandas (:func:`pandas.read_csv`) and the numbers
read by :func:`pandas.to_numeric`; a cell that is not a number is an input error naming
its line and column (exit 2).
"""

from __future__ import annotations

import csv
import io
import re
from pathlib import Path
from typing import Any

import numpy as np
import shapely

from ..errors import InputError
from ..io.files import read_limited

__all__ = ["VERTEX_SUFFIXES", "read_vertices"]

VERTEX_SUFFIXES = (".csv", ".txt")
MAX_VERTEX_BYTES = 8 * 1024 * 1024  # a vertex list larger than this is not an area boundary
_X_NAMES = {"lon", "long", "lng", "longitude", "x", "easting", "east", "e", "долгота"}
_Y_NAMES = {"lat", "latitude", "y", "northing", "north", "n", "широта"}
_GEOMETRY_NAMES = {"wkt", "geometry", "the_geom", "geom"}
_NUMBER = re.compile(r"^[+-]?(\d+([.,]\d*)?|[.,]\d+)([eE][+-]?\d+)?$")


def _lines(text: str) -> list[tuple[int, str]]:
    """The file's non-blank, non-comment lines with their line numbers (from 1)."""
    return [(i, line) for i, line in enumerate(text.splitlines(), start=1)
            if line.strip() and not line.lstrip().startswith("#")]


def _delimiter(rows: list[str]) -> str | None:
    """The delimiter of ``rows``: the first of ``;``, tab, ``,`` found on every row (a
    semicolon first: it is never a decimal mark); None: whitespace."""
    for cand in (";", "\t", ","):
        if all(cand in r for r in rows):
            return cand
    return None


def _cells(line: str, sep: str | None) -> list[str]:
    parts = next(csv.reader([line], delimiter=sep)) if sep else line.split()
    return [p.strip() for p in parts]


def read_vertices(path: Path, name: str) -> shapely.Geometry | None:
    """The polygon of a vertex list (rules in the module docstring).

    Parameters
    ----------
    path : Path
        The CSV or TXT file.
    name : str
        How messages name it.

    Returns
    -------
    shapely.Polygon or shapely.MultiPolygon or None
        In the coordinates of the file (the caller applies ``[area] crs``): the polygon of
        the vertices, or the union of the polygons of a table with a geometry column
        (``WKT``, ``geometry``). None is never returned for a file that has rows; it is
        kept for the caller's "not a vertex list" branch.

    Raises
    ------
    InputError
        Naming the file, its line and column (exit 2).
    """
    lines = _text_lines(path, name)
    sep = _delimiter([line for _, line in lines])
    first = _cells(lines[0][1], sep)
    if {c.strip().strip('"').lower() for c in first} & _GEOMETRY_NAMES:
        return _wkt_table(lines, sep, name)
    header = not all(_NUMBER.match(c) for c in first if c) or not any(first)
    cols = _columns(first, name, lines[0][0]) if header else (0, 1, "x", "y")
    body = lines[1:] if header else lines
    if not body:
        raise InputError(name, "holds a header but no vertex: give one row per vertex of the "
                         "boundary")
    _check_widths(body, sep, len(first) if header else 2, header, name)
    x = _column(body, sep, len(first) if header else 2, cols[0], cols[2], name)
    y = _column(body, sep, len(first) if header else 2, cols[1], cols[3], name)
    pts = list(zip(x.tolist(), y.tolist(), strict=True))
    if len(pts) > 1 and pts[0] == pts[-1]:
        pts = pts[:-1]
    if len(set(pts)) < 3:
        raise InputError(name, f"has {len(set(pts))} distinct vertex(es); a polygon needs at "
                         "least 3")
    return shapely.Polygon(pts)


def _text_lines(path: Path, name: str) -> list[tuple[int, str]]:
    """The file's UTF-8 text as (line number, line), blank and ``#`` lines left out."""
    data = read_limited(path, MAX_VERTEX_BYTES, field=name)
    try:
        text = data.decode("utf-8-sig")
    except UnicodeDecodeError as exc:
        raise InputError(name, f"is not UTF-8 text (byte {exc.start + 1}); save the vertex "
                         "list as UTF-8 CSV") from None
    lines = _lines(text)
    if not lines:
        raise InputError(name, "holds no vertex: give one 'lon,lat' (or 'x,y') row per "
                         "vertex of the boundary")
    return lines


def _check_widths(body: list[tuple[int, str]], sep: str | None, width: int, header: bool,
                  name: str) -> None:
    """Every row has ``width`` cells: a row of another width (a stray delimiter, a decimal
    comma in a comma-separated file) is refused, never guessed."""
    for number, line in body:
        n = len(_cells(line, sep))
        if n != width:
            raise InputError(name, f"line {number} has {n} cells; "
                             + (f"the header has {width}" if header else
                                "without a header the file must have two columns: x, y "
                                "(longitude, latitude), or a header naming them lon and "
                                "lat (or x and y)")
                             + ("; with a comma delimiter the decimal mark is a point"
                                if sep == "," else ""))


def _column(body: list[tuple[int, str]], sep: str | None, width: int, k: int, label: str,
            name: str) -> np.ndarray:
    """Column ``k`` of the rows as numbers (pandas splits and converts; a decimal comma
    where the delimiter is not a comma); a cell that is no finite number names its line."""
    import pandas as pd

    try:
        frame = pd.read_csv(io.StringIO("\n".join(line for _, line in body)),
                            sep=sep if sep else r"\s+", header=None, dtype=str,
                            keep_default_na=False, skipinitialspace=True, engine="python",
                            names=range(width))
    except (ValueError, csv.Error) as exc:  # pandas' ParserError is a ValueError
        raise InputError(name, f"cannot be read as a vertex list: {exc}"[:300]) from None
    decimal_comma = sep != ","
    raw = frame[k].fillna("").astype(str).str.strip()
    values = pd.to_numeric(raw.str.replace(",", ".", regex=False) if decimal_comma else raw,
                           errors="coerce").to_numpy(dtype=float, na_value=np.nan)
    bad = np.flatnonzero(~np.isfinite(values))
    if len(bad):
        i = int(bad[0])
        raise InputError(name, f"line {body[i][0]}, column {label!r}: {raw.iloc[i]!r} is not "
                         "a finite number" + ("" if decimal_comma else
                                              " (with a comma delimiter the decimal mark is "
                                              "a point)"))
    return values


def _columns(header: list[str], name: str, line: int) -> tuple[Any, Any, str, str]:
    """(x column, y column, x name, y name) from a header row."""
    low = [h.strip().strip('"').lower() for h in header]
    xs = [i for i, h in enumerate(low) if h in _X_NAMES]
    ys = [i for i, h in enumerate(low) if h in _Y_NAMES]
    if len(xs) != 1 or len(ys) != 1:
        raise InputError(name, f"line {line} {header!r} is a header but does not name one x and "
                         "one y column: name them lon and lat (or x and y, easting and "
                         "northing)"[:400])
    return xs[0], ys[0], header[xs[0]], header[ys[0]]


def _wkt_table(lines: list[tuple[int, str]], sep: str | None, name: str) -> shapely.Geometry:
    """The union of the polygons of a table with a WKT column (one geometry a row)."""
    # a polygon's WKT is one cell of up to the file's own bound (csv allows 128 KiB by
    # default: a 20,000-vertex boundary is 0.44 MB)
    limit = csv.field_size_limit()
    csv.field_size_limit(max(limit, MAX_VERTEX_BYTES))
    try:
        rows = list(csv.reader(io.StringIO("\n".join(line for _, line in lines)),
                               delimiter=sep or ","))
    except csv.Error as exc:
        raise InputError(name, f"is not a table of WKT polygons: {exc}") from None
    finally:
        csv.field_size_limit(limit)
    head = [c.strip().lower() for c in rows[0]]
    k = next(i for i, c in enumerate(head) if c in _GEOMETRY_NAMES)
    parts = []
    for (line, _), row in zip(lines[1:], rows[1:], strict=False):
        text = row[k].strip() if k < len(row) else ""
        try:
            geom = shapely.from_wkt(text)
        except (shapely.errors.GEOSException, ValueError):
            geom = None
        if geom is None or geom.is_empty or geom.geom_type not in ("Polygon", "MultiPolygon"):
            raise InputError(name, f"line {line}, column {head[k]}: not a polygon in WKT "
                             f"({text[:40]!r}); give POLYGON((x y, ...)) a row")
        parts.append(geom)
    if not parts:
        raise InputError(name, "holds a header but no polygon: give one WKT polygon a row")
    return shapely.union_all(parts)


"""The flight for Google Earth and a GIS: KML, GeoJSON (RFC 7946) and the photo table (CSV).

* ``flight.kml`` (OGC KML 2.2): a document with three folders — the area (polygon), the
  strips (lines, numbered, in flight order) and the photo centres (points named by their
  running number) — and a style for each. Written with :mod:`xml.etree.ElementTree`, which
  escapes all text (a project name with ``<`` or ``&`` stays text). Geometry is clamped
  to the ground; the flight altitude of each photo is in its data.
* ``flight.geojson`` (RFC 7946): one FeatureCollection of the area, the strips and the
  photo centres (``"kind"``: ``area`` / ``strip`` / ``photo``), WGS 84 longitude/latitude
  (no ``crs`` member), polygons by the right-hand rule, 7 decimals of a degree (about
  1 cm). The writer is named in the foreign member ``"generator"``.
* ``photos.csv``: every photo centre, one row each, the columns of
  :data:`scanplan.geo.layout.PHOTO_COLUMNS` (units in the names), comma-separated, a dot
  for decimals, UTF-8, empty cells for values that do not apply.

A strip that crosses the area several times and is split is a MultiLineString of its
segments (photos further apart than 1.5 bases start a new segment). A block across the
antimeridian is not split (RFC 7946, 3.1.9): contract areas here are far from it.
"""

from __future__ import annotations

import io
import json
import math
import xml.etree.ElementTree as ET
from dataclasses import dataclass
from typing import Any

import numpy as np
import shapely

from ..control import CONTROL_COLUMNS, ControlPoints
from ..layout import PHOTO_COLUMNS, FlightLayout
from ..mission import sortie_missions
from ..terrain import TERRAIN_PHOTO_COLUMNS
from .common import GENERATOR, LonLat, lonlat, photos_by_strip

__all__ = ["CONTROL_DECIMALS", "CSV_DECIMALS", "ExportNames", "photo_columns",
           "render_control_csv", "render_csv", "render_geojson", "render_kml"]

_KML_NS = "http://www.opengis.net/kml/2.2"
_DEG = 7  # decimals of a degree written (1e-7° ≈ 1 cm)
_LABELLED_PHOTOS = 1000  # up to this many photo centres, their numbers always show in KML
#: Decimals written per CSV column (integers: none; the rest: 3).
CSV_DECIMALS = {"x_m": 3, "y_m": 3, "lon_deg": 8, "lat_deg": 8, "ground_m": 2,
                "altitude_m": 2, "agl_m": 2, "gsd_cm": 3, "resolution_cm": 3,
                "ground_min_m": 2, "ground_max_m": 2, "forward_overlap_pct": 2,
                "side_overlap_pct": 2,
                "recognition_p": 4}
_INT_COLUMNS = ("photo", "strip", "index", "sortie")
#: Decimals of the control points' coordinates in every file: 8 of a degree (about 1 mm),
#: 3 of a metre — control.csv, the GeoPackage, KML and GeoJSON agree to well under 1 cm.
CONTROL_DECIMALS = {"x_m": 3, "y_m": 3, "lon_deg": 8, "lat_deg": 8, "ground_m": 3}


def photo_columns(photos: Any) -> list[str]:
    """The per-photo columns written (the CSV header, the GeoJSON properties, the sheet):
    those of :data:`~scanplan.geo.layout.PHOTO_COLUMNS` the photos have, then a terrain
    plan's :data:`~scanplan.geo.terrain.TERRAIN_PHOTO_COLUMNS` (the ground range under the
    footprint, the overlaps with the neighbours)."""
    return ([c for c in PHOTO_COLUMNS if c in photos.columns]
            + [c for c in TERRAIN_PHOTO_COLUMNS if c in photos.columns])


@dataclass(frozen=True)
class ExportNames:
    """The human-readable names inside the files (the report's language)."""

    title: str = "Flight plan"
    area: str = "Area"
    strips: str = "Strips"
    photos: str = "Photo centres"
    strip: str = "Strip {n}"
    sortie: str = "sortie {n}"
    sorties: str = "Sorties"
    takeoff: str = "Take-off point"
    control: str = "Ground control and checkpoints"


def _coords(points: np.ndarray) -> str:
    return " ".join(f"{lon:.{_DEG}f},{lat:.{_DEG}f}" for lon, lat in points)


def _sub(parent: ET.Element, tag: str, text: str | None = None) -> ET.Element:
    el = ET.SubElement(parent, tag)
    if text is not None:
        el.text = text
    return el


def _style(doc: ET.Element, sid: str, *, line: str | None = None, width: float = 2.0,
           fill: str | None = None, icon_scale: float | None = None,
           label_scale: float = 0.6) -> None:
    """A KML style (colours are aabbggrr)."""
    st = _sub(doc, "Style")
    st.set("id", sid)
    if icon_scale is not None:
        ic = _sub(st, "IconStyle")
        _sub(ic, "color", line or "ff00ffff")
        _sub(ic, "scale", f"{icon_scale:g}")
        icon = _sub(ic, "Icon")
        _sub(icon, "href", "http://maps.google.com/mapfiles/kml/shapes/placemark_circle.png")
        lab = _sub(st, "LabelStyle")
        _sub(lab, "scale", f"{label_scale:g}")
        return
    if line is not None:
        ls = _sub(st, "LineStyle")
        _sub(ls, "color", line)
        _sub(ls, "width", f"{width:g}")
    ps = _sub(st, "PolyStyle")
    _sub(ps, "color", fill or "00ffffff")
    _sub(ps, "fill", "0" if fill is None else "1")


def _kml_polygon(parent: ET.Element, poly: Any) -> None:
    pg = _sub(parent, "Polygon")
    for tag, ring in [("outerBoundaryIs", poly.exterior),
                      *[("innerBoundaryIs", r) for r in poly.interiors]]:
        lr = _sub(_sub(pg, tag), "LinearRing")
        _sub(lr, "coordinates", _coords(np.asarray(ring.coords)[:, :2]))


def _data(pm: ET.Element, values: dict[str, Any]) -> None:
    ext = _sub(pm, "ExtendedData")
    for key, value in values.items():
        d = _sub(ext, "Data")
        d.set("name", key)
        _sub(d, "value", value)


def _fmt(value: Any, decimals: int) -> str:
    v = float(value)
    if not math.isfinite(v):
        return ""
    return f"{v:.{decimals}f}"


def _strip_lines(layout: FlightLayout, geo: LonLat
                 ) -> list[tuple[int, np.ndarray, list[np.ndarray]]]:
    """(strip number, its flown line start→end in lon/lat, its photographed segments)."""
    by_strip = photos_by_strip(layout)
    ph = layout.photos
    lon = np.asarray(ph["lon_deg"]) if len(ph) else np.empty(0)
    lat = np.asarray(ph["lat_deg"]) if len(ph) else np.empty(0)
    out = []
    for s in layout.strips:
        line = geo.points(np.array([s.start_xy_m, s.end_xy_m]))
        segments = []
        sp = by_strip.get(s.number)
        if len(s.parts) > 1:  # the photographed parts the layout gives
            segments = [geo.points(np.array([a, b])) for a, b in s.parts]
        elif not s.parts and sp is not None and len(sp.runs) > 1:
            for a, b in sp.runs:
                i, j = int(sp.order[a]), int(sp.order[b])
                segments.append(np.array([[lon[i], lat[i]], [lon[j], lat[j]]]))
        out.append((s.number, line, segments))
    return out


def render_kml(layout: FlightLayout, names: ExportNames | None = None,
               control: ControlPoints | None = None) -> bytes:
    """The flight scheme as KML for Google Earth (see the module docstring).

    Parameters
    ----------
    layout : FlightLayout
        A georeferenced layout.
    names : ExportNames, optional
        The names of the document, folders and strips (default English).
    control : ControlPoints, optional
        GCPs and checkpoints: a folder of their own (a triangle for a GCP, a circle for a
        checkpoint).

    Returns
    -------
    bytes
        The ``.kml`` (UTF-8 XML).
    """
    names = names or ExportNames()
    geo = lonlat(layout)
    root = ET.Element("kml", {"xmlns": _KML_NS})
    doc = _sub(root, "Document")
    _sub(doc, "name", names.title)
    _sub(doc, "description",
         f"{layout.area.source}; {layout.area.plan_crs}; {names.strips}: "
         f"{len(layout.strips)}; {names.photos}: {len(layout.photos)}")
    _kml_styles(doc, len(layout.photos))
    _kml_area(doc, layout, geo, names)
    _kml_strips(doc, layout, geo, names)
    _kml_sorties(doc, layout, geo, names)
    if control is not None and len(control):
        _kml_control(doc, control, names)
    folder = _sub(doc, "Folder")
    _sub(folder, "name", names.photos)
    _sub(folder, "Placemark").text = _PHOTOS_MARK  # the photo placemarks go here
    body = ET.tostring(root, encoding="unicode", short_empty_elements=True)
    head = ('<?xml version="1.0" encoding="UTF-8"?>\n'
            f"<!-- {GENERATOR}: flight plan (area, strips, photo centres) -->\n")
    body = body.replace(f"<Placemark>{_PHOTOS_MARK}</Placemark>",
                        _kml_photos(layout.photos, "altitude_mode" in layout.notes))
    return (head + body + "\n").encode("utf-8")


def _kml_styles(doc: ET.Element, n_photos: int) -> None:
    """The styles of the area, strips, sorties, take-off and photo centres."""
    _style(doc, "area", line="ff0000ff", width=2.5, fill="330000ff")
    _style(doc, "strip", line="ffff7f00", width=2.0)
    _style(doc, "sortie", line="ff9a1b6a", width=1.2)
    _style(doc, "takeoff", line="ff000000", icon_scale=1.1, label_scale=0.9)
    # photo numbers: shown for a small block; for a large one on pointing (a StyleMap), as
    # thousands of labels would hide the map
    few = n_photos <= _LABELLED_PHOTOS
    _style(doc, "photo-normal", line="ff00ffff", icon_scale=0.45,
           label_scale=0.6 if few else 0.0)
    _style(doc, "photo-highlight", line="ff00ffff", icon_scale=0.7, label_scale=0.9)
    smap = _sub(doc, "StyleMap")
    smap.set("id", "photo")
    for key in ("normal", "highlight"):
        pair = _sub(smap, "Pair")
        _sub(pair, "key", key)
        _sub(pair, "styleUrl", f"#photo-{key}")


_CONTROL_ICONS = {"gcp": "http://maps.google.com/mapfiles/kml/shapes/triangle.png",
                  "check": "http://maps.google.com/mapfiles/kml/shapes/target.png"}


def _kml_control(doc: ET.Element, control: ControlPoints, names: ExportNames) -> None:
    """The markers' folder: a placemark per GCP (red triangle) and checkpoint (blue target),
    named by its id, with its columns as data."""
    for role, colour in (("gcp", "ff0000ff"), ("check", "ffff0000")):
        st = _sub(doc, "Style")
        st.set("id", f"control-{role}")
        ic = _sub(st, "IconStyle")
        _sub(ic, "color", colour)
        _sub(ic, "scale", "0.9")
        _sub(_sub(ic, "Icon"), "href", _CONTROL_ICONS[role])
    folder = _sub(doc, "Folder")
    _sub(folder, "name", names.control)
    c = control.columns
    for i in range(len(control)):
        pm = _sub(folder, "Placemark")
        _sub(pm, "name", str(c["id"][i]))
        _sub(pm, "styleUrl", f"#control-{c['role'][i]}")
        _data(pm, {k: _control_cell(c, k, i) for k in CONTROL_COLUMNS
                   if k not in ("id", "lon_deg", "lat_deg")})
        _sub(_sub(pm, "Point"), "coordinates",
             f"{float(c['lon_deg'][i]):.{CONTROL_DECIMALS['lon_deg']}f},"
             f"{float(c['lat_deg'][i]):.{CONTROL_DECIMALS['lat_deg']}f}")


def _control_cell(c: dict[str, np.ndarray], key: str, i: int) -> str:
    """One control point's value as the files write it (empty for NaN)."""
    v = c[key][i]
    if key in CONTROL_DECIMALS:
        return _fmt(v, CONTROL_DECIMALS[key])
    return str(v)


def render_control_csv(control: ControlPoints) -> bytes:
    """``control.csv``: one row per marker, the columns of
    :data:`~scanplan.geo.control.CONTROL_COLUMNS` (GCPs first), comma-separated, a dot for
    decimals, UTF-8, an empty cell for a ground height without a DEM."""
    buf = io.StringIO()
    buf.write(",".join(CONTROL_COLUMNS) + "\n")
    for i in range(len(control)):
        buf.write(",".join(_control_cell(control.columns, k, i) for k in CONTROL_COLUMNS)
                  + "\n")
    return buf.getvalue().encode("utf-8")


def _geojson_control(control: ControlPoints) -> list[dict[str, Any]]:
    """The markers as GeoJSON Point features (``"kind"``: ``gcp`` / ``check``)."""
    c = control.columns
    out = []
    for i in range(len(control)):
        props: dict[str, Any] = {"kind": str(c["role"][i]), "name": str(c["id"][i])}
        for k in CONTROL_COLUMNS:
            if k in ("lon_deg", "lat_deg"):
                continue
            v = c[k][i]
            props[k] = (_num(round(float(v), CONTROL_DECIMALS[k])) if k in CONTROL_DECIMALS
                        else _num(v) if k in ("block", "photos") else str(v))
        out.append({"type": "Feature", "properties": props, "geometry": {
            "type": "Point", "coordinates": [round(float(c["lon_deg"][i]), 8),
                                             round(float(c["lat_deg"][i]), 8)]}})
    return out


def _kml_area(doc: ET.Element, layout: FlightLayout, geo: LonLat, names: ExportNames) -> None:
    """The area's folder: its polygon (or polygons) with its figures."""
    folder = _sub(doc, "Folder")
    _sub(folder, "name", names.area)
    pm = _sub(folder, "Placemark")
    _sub(pm, "name", names.area)
    _sub(pm, "styleUrl", "#area")
    _data(pm, {"area_km2": _fmt(layout.area.area_km2, 4),
               "perimeter_km": _fmt(layout.area.perimeter_km, 3),
               "plan_crs": layout.area.plan_crs})
    polys = list(getattr(geo.area, "geoms", [geo.area]))
    if len(polys) == 1:
        _kml_polygon(pm, polys[0])
    else:
        mg = _sub(pm, "MultiGeometry")
        for poly in polys:
            _kml_polygon(mg, poly)


def _kml_strips(doc: ET.Element, layout: FlightLayout, geo: LonLat, names: ExportNames) -> None:
    """The strips' folder: one placemark per strip, its parts where the area is cut."""
    folder = _sub(doc, "Folder")
    _sub(folder, "name", names.strips)
    for (number, line, segments), strip in zip(_strip_lines(layout, geo), layout.strips,
                                               strict=True):
        pm = _sub(folder, "Placemark")
        _sub(pm, "name", names.strip.format(n=number))
        _sub(pm, "description", names.sortie.format(n=strip.sorties_text))
        _sub(pm, "styleUrl", "#strip")
        _data(pm, {"strip": str(number), "sortie": str(strip.sortie),
                   "last_sortie": str(strip.last_sortie),
                   "photos": str(strip.photos), "length_m": _fmt(strip.length_m, 1)})
        parent = _sub(pm, "MultiGeometry") if segments else pm
        for seg in segments or [line]:
            ls = _sub(parent, "LineString")
            _sub(ls, "tessellate", "1")
            _sub(ls, "coordinates", _coords(seg))


_PHOTOS_MARK = "@@scanplan-photo-centres@@"


def _kml_sorties(doc: ET.Element, layout: FlightLayout, geo: LonLat,
                 names: ExportNames) -> None:
    """A UAV layout's sorties — each the path of its mission (take-off, run-in, strips,
    turns, run-out, back; :func:`scanplan.geo.mission.sortie_missions`) — and the
    take-off point when one is given."""
    if layout.kind == "film" or not layout.speed_ms or not len(layout.photos):
        return
    folder = _sub(doc, "Folder")
    _sub(folder, "name", names.sorties)
    takeoff = layout.notes.get("takeoff_xy_m")
    if takeoff is not None:
        pm = _sub(folder, "Placemark")
        _sub(pm, "name", names.takeoff)
        _sub(pm, "styleUrl", "#takeoff")
        pt = _sub(pm, "Point")
        _sub(pt, "coordinates", _coords(geo.points(np.array([takeoff]))))
    for m in sortie_missions(layout, float(layout.speed_ms)):
        xy = np.array([[p.x_m, p.y_m] for p in m.points])
        if m.takeoff_xy_m is not None:
            xy = np.vstack([m.takeoff_xy_m, xy, m.takeoff_xy_m])
        pm = _sub(folder, "Placemark")
        _sub(pm, "name", names.sortie.format(n=m.number))
        _sub(pm, "styleUrl", "#sortie")
        sortie = layout.sorties[m.number - 1]
        _data(pm, {"sortie": str(m.number), "photos": str(m.photos),
                   "length_m": _fmt(sortie.length_m, 1),
                   "transit_m": _fmt(sortie.transit_m, 1)})
        ls = _sub(pm, "LineString")
        _sub(ls, "tessellate", "1")
        _sub(ls, "coordinates", _coords(geo.points(xy)))


def _kml_decimal(ph: Any, key: str) -> np.ndarray:
    """A column as text with one decimal, empty where not finite."""
    v = np.asarray(ph[key], float)
    return np.where(np.isfinite(v), np.char.mod("%.1f", v), "")


def _kml_photos(ph: Any, terrain: bool = False) -> str:
    """The photo placemarks as KML text (numbers only: nothing to escape), built column by
    column — 10⁵ photos in well under a second, where one element tree node each takes
    tens of seconds. A terrain plan's photos also carry their ground elevation and flight
    altitude (``ground_m``, ``altitude_m``, the DEM's height system)."""
    if not len(ph):
        return ""
    n, strip, index, sortie = (np.asarray(ph[k]).astype(np.int64).astype(str) for k in
                               ("photo", "strip", "index", "sortie"))
    data = '</value></Data><Data name="{}"><value>'.format
    pieces: list[Any] = [
        "<Placemark><name>", n, "</name><styleUrl>#photo</styleUrl><ExtendedData>"
        '<Data name="strip"><value>', strip, data("index"), index, data("sortie"), sortie,
        data("agl_m"), _kml_decimal(ph, "agl_m")]
    if terrain:
        pieces += [data("ground_m"), _kml_decimal(ph, "ground_m"),
                   data("altitude_m"), _kml_decimal(ph, "altitude_m")]
    pieces += ["</value></Data></ExtendedData><Point><coordinates>",
               np.char.mod(f"%.{_DEG}f", np.asarray(ph["lon_deg"], float)), ",",
               np.char.mod(f"%.{_DEG}f", np.asarray(ph["lat_deg"], float)),
               "</coordinates></Point></Placemark>"]
    return _rows_joined(pieces, len(ph))


def _rows_joined(pieces: list[Any], n: int) -> str:
    """``n`` rows of text, row i the concatenation of each piece (a string, or an array of
    ``n`` strings: its i-th), joined in one call — the pieces side by side in an object
    table, instead of a Python loop over 10⁵ rows."""
    table = np.empty((n, len(pieces)), dtype=object)
    for col, piece in enumerate(pieces):
        table[:, col] = piece
    return "".join(table.ravel().tolist())


def _round(points: np.ndarray) -> list[list[float]]:
    return [[round(float(a), _DEG), round(float(b), _DEG)] for a, b in points]


def _geojson_geometry(geom: Any) -> dict[str, Any]:
    """A shapely geometry (lon/lat) as a GeoJSON geometry object, coordinates rounded."""
    mapping = shapely.geometry.mapping(geom)

    def rnd(c: Any) -> Any:
        if isinstance(c, (list, tuple)) and c and isinstance(c[0], (int, float)):
            return [round(float(c[0]), _DEG), round(float(c[1]), _DEG)]
        return [rnd(x) for x in c]

    return {"type": mapping["type"], "coordinates": rnd(mapping["coordinates"])}


def _num(value: Any) -> Any:
    v = float(value)
    if not math.isfinite(v):
        return None
    return int(v) if v.is_integer() and abs(v) < 2**53 else v


def render_geojson(layout: FlightLayout, names: ExportNames | None = None,
                   control: ControlPoints | None = None) -> bytes:
    """The flight scheme as one RFC 7946 FeatureCollection (see the module docstring);
    with ``control``, its GCPs and checkpoints as Point features after the strips.

    Returns
    -------
    bytes
        The ``.geojson`` (UTF-8 JSON).
    """
    names = names or ExportNames()
    geo = lonlat(layout)
    features: list[dict[str, Any]] = [{
        "type": "Feature",
        "properties": {"kind": "area", "name": names.area, "source": layout.area.source,
                       "plan_crs": layout.area.plan_crs,
                       "area_km2": _num(round(layout.area.area_km2, 6)),
                       "perimeter_km": _num(round(layout.area.perimeter_km, 6))},
        "geometry": _geojson_geometry(geo.area),
    }]
    for (number, line, segments), strip in zip(_strip_lines(layout, geo), layout.strips,
                                               strict=True):
        geometry = ({"type": "MultiLineString", "coordinates": [_round(s) for s in segments]}
                    if segments else {"type": "LineString", "coordinates": _round(line)})
        features.append({
            "type": "Feature",
            "properties": {"kind": "strip", "name": names.strip.format(n=number),
                           "strip": number, "sortie": strip.sortie,
                           "last_sortie": strip.last_sortie, "photos": strip.photos,
                           "length_m": _num(round(strip.length_m, 2))},
            "geometry": geometry,
        })
    if control is not None:
        features.extend(_geojson_control(control))
    doc = {"type": "FeatureCollection", "name": names.title, "generator": GENERATOR,
           "features": features}
    text = json.dumps(doc, ensure_ascii=False, allow_nan=False, separators=(",", ":"))
    photos = _geojson_photos(layout.photos)
    if photos:  # the photo features after the area and the strips
        text = text[:-2] + "," + photos + "]}"
    return (text + "\n").encode("utf-8")


def _json_column(values: np.ndarray, decimals: int | None) -> np.ndarray:
    """One column as JSON literals: integers, numbers rounded to ``decimals`` (shortest
    form, as :func:`json.dumps` writes a float), ``null`` for NaN."""
    if decimals is None:
        return values.astype(np.int64).astype(str).astype(object)
    v = np.round(values.astype(float), decimals)
    if not len(v):
        return np.array([], dtype=object)
    # json's C encoder writes each float as repr() does, a hundred times faster than a
    # Python loop over the column; NaN and infinities become null below
    out = np.array(json.dumps(v.tolist())[1:-1].split(", "), dtype=object)
    out[~np.isfinite(v)] = "null"
    return out


def _geojson_photos(ph: Any) -> str:
    """The photo-centre features as JSON text, built column by column (fast for 10⁵)."""
    if not len(ph):
        return ""
    cols = photo_columns(ph)
    lits = [_json_column(np.asarray(ph[c]),
                         None if c in _INT_COLUMNS else CSV_DECIMALS.get(c, 3)) for c in cols]
    lon = _json_column(np.asarray(ph["lon_deg"]), _DEG)
    lat = _json_column(np.asarray(ph["lat_deg"]), _DEG)
    keys = [json.dumps(c) + ":" for c in cols]
    pieces: list[Any] = ['{"type":"Feature","properties":{"kind":"photo",']
    for n, (k, v) in enumerate(zip(keys, lits, strict=True)):
        pieces += [("," + k) if n else k, v]
    pieces += ['},"geometry":{"type":"Point","coordinates":[', lon, ",", lat, "]}},"]
    return _rows_joined(pieces, len(ph))[:-1]  # the last feature's comma


def render_csv(layout: FlightLayout) -> bytes:
    """Every photo centre as a CSV row (see the module docstring).

    Works for an abstract block too (lon/lat empty, x/y in its local frame).

    Returns
    -------
    bytes
        The ``.csv`` (UTF-8, ``\\n`` line ends).
    """
    import pandas as pd  # here: a report that writes no CSV does not import pandas (0.3 s)

    ph = layout.photos
    cols = photo_columns(ph)
    frame = pd.DataFrame({c: np.asarray(ph[c]) for c in cols}, columns=cols)
    for c in cols:
        if c in _INT_COLUMNS:
            frame[c] = frame[c].astype(np.int64)
        else:
            frame[c] = frame[c].astype(float).round(CSV_DECIMALS.get(c, 3))
    from ...io.files import csv_safe_frame  # text cells never start a formula

    buf = io.StringIO()
    csv_safe_frame(frame).to_csv(buf, index=False, lineterminator="\n", na_rep="")
    return buf.getvalue().encode("utf-8")

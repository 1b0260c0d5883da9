"""The flight as one OGC GeoPackage (``flight.gpkg``) for QGIS, ArcGIS and any GDAL reader.

Written through GDAL by pyogrio (``pyogrio.raw.write``, driver ``GPKG``), in the planning
CRS of the layout (metric: UTM or the project's CRS), one layer per feature kind:

* ``area`` — the area (MultiPolygon, with its holes);
* ``strips`` — one MultiLineString per strip in flight order (``strip``, ``sortie``,
  ``photos``, ``length_m``; a strip split over a gap has one line per photographed part);
* ``photos`` — every photo centre as a Point with every column of photos.csv;
* ``sorties`` — one MultiLineString per sortie (its strips), with ``sortie``, ``strips``,
  ``length_m`` and ``time_min``;
* ``control`` — with ``[control]``, every GCP and checkpoint as a Point with the columns of
  control.csv (``id``, ``role``, ``block``, ``x_m``, ``y_m``, ``lon_deg``, ``lat_deg``,
  ``ground_m``, ``photos``).

The project has no take-off site, so no take-off layer is written. GDAL writes to a file,
so the GeoPackage is built in a private temporary folder and returned as bytes; the caller
writes it with the reports in one all-or-nothing transaction. The dataset metadata item
``GENERATOR`` names scanplan (its mark: scanplan replaces its own files).
"""

from __future__ import annotations

import os
import tempfile
from typing import Any

import numpy as np
import shapely

from ..control import ControlPoints
from ..gdal_guard import import_pyogrio
from ..layout import FlightLayout
from .common import GENERATOR, photos_by_strip
from .gis import photo_columns

__all__ = ["GPKG_LAYERS", "render_gpkg"]

#: The layers of flight.gpkg, in the order written.
GPKG_LAYERS = ("area", "strips", "photos", "sorties")
"""The layers of every GeoPackage; ``takeoff`` (one point) is added when the project gives
a take-off point (``[flight] takeoff``)."""
_INT_COLUMNS = ("photo", "strip", "index", "sortie")


def _strip_geometries(layout: FlightLayout) -> list[Any]:
    """Each strip as a LineString (start → end) or, split over gaps, a MultiLineString of
    its photographed parts (planning CRS) — as flight.kml draws them."""
    by_strip = photos_by_strip(layout)
    x = np.asarray(layout.photos["x_m"], float) if len(layout.photos) else np.empty(0)
    y = np.asarray(layout.photos["y_m"], float) if len(layout.photos) else np.empty(0)
    out = []
    for s in layout.strips:
        sp = by_strip.get(s.number)
        if len(s.parts) > 1:
            out.append(shapely.multilinestrings([[a, b] for a, b in s.parts]))
        elif not s.parts and sp is not None and len(sp.runs) > 1:
            out.append(shapely.multilinestrings(
                [[(x[sp.order[a]], y[sp.order[a]]), (x[sp.order[b]], y[sp.order[b]])]
                 for a, b in sp.runs]))
        else:
            out.append(shapely.linestrings([s.start_xy_m, s.end_xy_m]))
    return out


def _write(path: str, layer: str, geoms: list[Any], fields: dict[str, np.ndarray],
           geometry_type: str, crs: str, first: bool) -> None:
    import_pyogrio()
    from pyogrio.raw import write

    write(path, np.array(shapely.to_wkb(geoms), dtype=object),
          list(fields.values()), fields=list(fields), layer=layer, driver="GPKG",
          geometry_type=geometry_type, crs=crs,
          promote_to_multi=geometry_type.startswith("Multi"),
          dataset_metadata={"GENERATOR": GENERATOR} if first else None,
          # GeoPackage 1.2: read by every GDAL from 2.2 and QGIS 3 (1.4 warns in older ones)
          dataset_options={"VERSION": "1.2"} if first else None)


def _build_time() -> str:
    """``SOURCE_DATE_EPOCH`` (else now, to the second) as GeoPackage writes a timestamp."""
    import datetime as _dt

    epoch = os.environ.get("SOURCE_DATE_EPOCH", "")
    when = (_dt.datetime.fromtimestamp(int(epoch), _dt.UTC) if epoch.isdigit()
            else _dt.datetime.now(_dt.UTC).replace(microsecond=0))
    return when.strftime("%Y-%m-%dT%H:%M:%S.000Z")


def render_gpkg(layout: FlightLayout, control: ControlPoints | None = None) -> bytes:
    """``layout`` as a GeoPackage: layers :data:`GPKG_LAYERS` in the planning CRS.

    Parameters
    ----------
    layout : FlightLayout
        A georeferenced layout.
    control : ControlPoints, optional
        GCPs and checkpoints: a ``control`` layer of Points with the columns of control.csv.

    Returns
    -------
    bytes
        The ``.gpkg`` file.
    """
    pyogrio = import_pyogrio()
    crs = layout.area.plan_crs
    area = layout.area.geometry
    strips = layout.strips
    # the layers' last_change: the build time (SOURCE_DATE_EPOCH, as the reports), so the
    # same plan gives the same bytes and a rerun is not a different file
    pyogrio.set_gdal_config_options({"OGR_CURRENT_DATE": _build_time()})
    with tempfile.TemporaryDirectory(prefix="scanplan-gpkg-") as tmp:
        path = os.path.join(tmp, "flight.gpkg")
        _write(path, "area", [area], {"name": np.array(["area"], dtype=object)},
               "MultiPolygon", crs, True)
        if strips:
            geoms = _strip_geometries(layout)
            _write(path, "strips", geoms, {
                "strip": np.array([s.number for s in strips], np.int32),
                "sortie": np.array([s.sortie for s in strips], np.int32),
                "last_sortie": np.array([s.last_sortie for s in strips], np.int32),
                "photos": np.array([s.photos for s in strips], np.int32),
                "length_m": np.array([s.length_m for s in strips], float),
            }, "MultiLineString", crs, False)
        ph = layout.photos
        if len(ph):
            cols = photo_columns(ph)
            fields = {c: (np.asarray(ph[c]).astype(np.int32) if c in _INT_COLUMNS
                          else np.asarray(ph[c], float)) for c in cols}
            _write(path, "photos", list(shapely.points(np.asarray(ph["x_m"], float),
                                                       np.asarray(ph["y_m"], float))),
                   fields, "Point", crs, False)
        flown = [s for s in layout.sorties if s.strips]
        if flown and strips:
            lines = {s.number: s for s in strips}
            _write(path, "sorties", [shapely.multilinestrings(
                [[lines[n].start_xy_m, lines[n].end_xy_m] for n in s.strips]) for s in flown], {
                "sortie": np.array([s.number for s in flown], np.int32),
                "strips": np.array([len(s.strips) for s in flown], np.int32),
                "length_m": np.array([s.length_m for s in flown], float),
                "time_min": np.array([s.time_s / 60.0 if s.time_s is not None else np.nan
                                      for s in flown], float),
            }, "MultiLineString", crs, False)
        if control is not None and len(control):
            c = control.columns
            _write(path, "control", list(shapely.points(c["x_m"], c["y_m"])), {
                k: (np.asarray(c[k]).astype(np.int32) if k in ("block", "photos")
                    else np.asarray(c[k], dtype=object) if k in ("id", "role")
                    else np.asarray(c[k], float)) for k in c}, "Point", crs, False)
        takeoff = layout.notes.get("takeoff_xy_m")
        if takeoff is not None:  # [flight] takeoff: where every sortie starts and returns
            _write(path, "takeoff", [shapely.Point(*takeoff)],
                   {"name": np.array(["take-off"], dtype=object)}, "Point", crs, False)
        with open(path, "rb") as fh:
            return fh.read()

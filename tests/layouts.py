"""FlightLayout records built by hand for the export and report tests.

A serpentine over a rectangle (or an L-shaped area whose middle strips are split) in UTM
zone 35N near Lida: simple enough to know every count, made with pyproj and shapely only,
independent of the planner that fills layouts in production.
"""

from __future__ import annotations

import math

import numpy as np
import shapely
from pyproj import Transformer

from scanplan.geo.layout import Area, FlightLayout, Photos, Sortie, Strip

LIDA_LONLAT = (25.30, 53.89)
UTM35 = "EPSG:32635"


def make_layout(*, width_m: float = 800.0, length_m: float = 500.0, spacing_m: float = 150.0,
                base_m: float = 60.0, agl_m: float = 120.0, ground_m: float = 150.0,
                sorties: int = 1, notch: bool = False, georeferenced: bool = True,
                parts: bool = True) -> FlightLayout:
    """A north–south serpentine; ``notch`` cuts the area's middle (strips there split)."""
    if georeferenced:
        to_utm = Transformer.from_crs("EPSG:4326", UTM35, always_xy=True)
        x0, y0 = to_utm.transform(*LIDA_LONLAT)
        crs = UTM35
    else:
        x0, y0, crs = 0.0, 0.0, "LOCAL"
    area = shapely.box(x0, y0, x0 + width_m, y0 + length_m)
    if notch:  # a hole-like notch across the middle third of the length
        cut = shapely.box(x0 + 0.3 * width_m, y0 + 0.35 * length_m, x0 + 0.7 * width_m,
                          y0 + 0.65 * length_m)
        area = area.difference(cut)
    n = math.ceil(width_m / spacing_m)
    xs = x0 + width_m / 2 + (np.arange(n) - (n - 1) / 2) * spacing_m
    per = math.ceil(length_m / base_m) + 1 + 2  # one base past each end
    y_lo = y0 + length_m / 2 - (per - 1) * base_m / 2
    strips, cols = [], {k: [] for k in ("photo", "strip", "index", "sortie", "x_m", "y_m")}
    per_sortie = math.ceil(n / sorties)
    count = 0
    for i, x in enumerate(xs):
        ys = y_lo + np.arange(per) * base_m
        if i % 2:
            ys = ys[::-1]
        if notch and x0 + 0.3 * width_m < x < x0 + 0.7 * width_m:
            keep = ~((ys > y0 + 0.35 * length_m + base_m / 2)
                     & (ys < y0 + 0.65 * length_m - base_m / 2))
            ys = ys[keep]
        sortie = i // per_sortie + 1
        cut = np.flatnonzero(np.abs(np.diff(ys)) > 1.5 * base_m)
        firsts, lasts = np.r_[0, cut + 1], np.r_[cut, len(ys) - 1]
        strip_parts = tuple(((float(x), float(ys[a])), (float(x), float(ys[b])))
                            for a, b in zip(firsts, lasts, strict=True)) if parts else ()
        strips.append(Strip(number=i + 1, start_xy_m=(float(x), float(ys[0])),
                            end_xy_m=(float(x), float(ys[-1])),
                            length_m=float(abs(ys[-1] - ys[0])), photos=len(ys),
                            first_photo=count + 1, sortie=sortie,
                            segments=len(firsts), parts=strip_parts))
        for j, y in enumerate(ys):
            count += 1
            for k, v in (("photo", count), ("strip", i + 1), ("index", j + 1),
                         ("sortie", sortie), ("x_m", x), ("y_m", y)):
                cols[k].append(v)
    arr = {k: np.asarray(v, dtype=np.int64 if k in ("photo", "strip", "index", "sortie")
                         else float) for k, v in cols.items()}
    m = len(arr["photo"])
    if georeferenced:
        back = Transformer.from_crs(UTM35, "EPSG:4326", always_xy=True)
        lon, lat = back.transform(arr["x_m"], arr["y_m"])
        arr["lon_deg"], arr["lat_deg"] = np.asarray(lon), np.asarray(lat)
    else:
        arr["lon_deg"] = arr["lat_deg"] = np.full(m, np.nan)
    arr["ground_m"] = np.full(m, ground_m)
    arr["altitude_m"] = np.full(m, ground_m + agl_m)
    arr["agl_m"] = np.full(m, agl_m)
    arr["gsd_cm"] = np.full(m, 2.5)
    arr["resolution_cm"] = np.full(m, 4.1)
    arr["recognition_p"] = np.full(m, 0.83)
    sortie_recs = tuple(
        Sortie(number=s, strips=tuple(st.number for st in strips if st.sortie == s),
               length_m=sum(st.length_m for st in strips if st.sortie == s), time_s=600.0)
        for s in sorted({st.sortie for st in strips}))
    c = area.centroid
    centroid = None
    if georeferenced:
        lon_c, lat_c = Transformer.from_crs(UTM35, "EPSG:4326", always_xy=True).transform(c.x, c.y)
        centroid = (float(lon_c), float(lat_c))
    return FlightLayout(
        area=Area(geometry=area, plan_crs=crs, source="test block", georeferenced=georeferenced,
                  area_km2=area.area / 1e6, perimeter_km=area.length / 1e3,
                  centroid_lonlat=centroid),
        direction_deg=0.0, spacing_m=spacing_m, base_m=base_m, strips=tuple(strips),
        sorties=sortie_recs, photos=Photos(arr),
        flight_length_m=sum(s.length_m for s in strips) + (n - 1) * spacing_m,
        turn_length_m=(n - 1) * spacing_m, flight_time_s=1200.0)

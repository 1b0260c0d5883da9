"""The map of a plan as GeoJSON (WGS 84, lon/lat) for the page.

One FeatureCollection: the area (``kind: "area"``), each strip's photographed parts
(``"strip"``, with its number and sortie, and over a DEM its height ``profile``: the
ground under each photo and its flight altitude), the photo centres (``"photos"``, one feature per
flight, every k-th when there are more than :data:`MAX_MAP_PHOTOS`, in the compact form of
:func:`pack_lonlat` — no geometry, ``properties.packed``: a few bytes a photo instead of a
JSON pair of numbers; :func:`unpack_lonlat` reads it back)
each sortie's take-off (``"takeoff"``: its first photo, where the mission files put
the home) and, with ``[control]``, the GCPs (``"gcp"``) and checkpoints (``"check"``).
Coordinates come from the same layout as the exported files; an abstract block
(``width_m × length_m``) has no place on the map and gives an empty collection.
"""

from __future__ import annotations

import functools
from typing import Any

import numpy as np

__all__ = ["LONLAT_UNIT_DEG", "MAX_MAP_PHOTOS", "area_features", "map_features", "pack_lonlat",
           "unpack_lonlat"]

MAX_MAP_PHOTOS = 20_000
"""Most photo centres drawn on the map; a larger flight shows every k-th."""
LONLAT_UNIT_DEG = 1e-7
"""The step of a packed coordinate [°]: 1.1 cm of latitude, finer than any photo centre's
accuracy (the GeoJSON it replaces rounded to 7 decimals as well)."""


def pack_lonlat(lon_deg: np.ndarray, lat_deg: np.ndarray) -> str:
    """Longitudes and latitudes [°] as base64 of little-endian int32 pairs, each in units of
    :data:`LONLAT_UNIT_DEG` (lon₀, lat₀, lon₁, lat₁ …): 8 bytes a point, about 11 characters
    against about 24 for the GeoJSON pair; the page reads it into an ``Int32Array``.

    >>> pack_lonlat(np.array([37.6]), np.array([55.75]))
    'AE5pFmDGOiE='
    >>> unpack_lonlat('AE5pFmDGOiE=').tolist()
    [[37.6, 55.75]]
    """
    import base64

    ints = np.rint(np.column_stack([lon_deg, lat_deg]) / LONLAT_UNIT_DEG).astype("<i4")
    return base64.b64encode(ints.tobytes()).decode("ascii")


def unpack_lonlat(packed: str) -> np.ndarray:
    """The (n, 2) array [°] of :func:`pack_lonlat`'s text."""
    import base64

    ints = np.frombuffer(base64.b64decode(packed), dtype="<i4").reshape(-1, 2)
    return np.round(ints * LONLAT_UNIT_DEG, 7)


@functools.lru_cache(maxsize=8)
def _to_wgs84(plan_crs: Any) -> Any:
    """The transformer from an area's planning CRS to WGS 84 (lon, lat), made once per CRS
    (the jobs that draw the map run one at a time)."""
    import pyproj

    return pyproj.Transformer.from_crs(plan_crs, 4326, always_xy=True)


def _feature(kind: str, geometry: dict[str, Any], **props: Any) -> dict[str, Any]:
    return {"type": "Feature", "geometry": geometry, "properties": {"kind": kind, **props}}


def _area(area: Any) -> dict[str, Any]:
    import shapely

    tr = _to_wgs84(area.plan_crs)
    geom = shapely.transform(area.geometry, tr.transform,
                             interleaved=False)
    return _feature("area", shapely.geometry.mapping(geom))


def _profile(photos: Any, number: int) -> dict[str, Any]:
    """A strip's height profile over the DEM (``photos`` None without one): each photo's
    distance along the strip from its first photo [m], the ground under it and its flight
    altitude [m, the DEM's height system], to 0.1 m; nothing without known ground."""
    if photos is None or not len(photos) or "ground_m" not in photos.columns:
        return {}
    mine = np.asarray(photos["strip"]) == number
    ground = np.asarray(photos["ground_m"], dtype=float)[mine]
    if not len(ground) or not np.isfinite(ground).all():
        return {}
    x, y = np.asarray(photos["x_m"], float)[mine], np.asarray(photos["y_m"], float)[mine]
    d = np.concatenate([[0.0], np.cumsum(np.hypot(np.diff(x), np.diff(y)))])
    alt = np.asarray(photos["altitude_m"], dtype=float)[mine]
    return {"profile": {"d_m": d.round(1).tolist(), "ground_m": ground.round(1).tolist(),
                        "altitude_m": alt.round(1).tolist()}}


def _layout(platform: str, layout: Any, most_photos: int, dem: bool = False
            ) -> list[dict[str, Any]]:
    tr = _to_wgs84(layout.area.plan_crs)
    out = []
    for s in layout.strips:
        parts = s.parts or ((s.start_xy_m, s.end_xy_m),)
        xy = np.array([[*a, *b] for a, b in parts], dtype=float).reshape(-1, 4)
        lon0, lat0 = tr.transform(xy[:, 0], xy[:, 1])
        lon1, lat1 = tr.transform(xy[:, 2], xy[:, 3])
        lines = [[[float(a), float(b)], [float(c), float(d)]]
                 for a, b, c, d in zip(lon0, lat0, lon1, lat1, strict=True)]
        out.append(_feature("strip", {"type": "MultiLineString", "coordinates": lines},
                            platform=platform, number=s.number, sortie=s.sortie,
                            last_sortie=s.last_sortie, sorties=s.sorties_text,
                            photos=s.photos,
                            **_profile(layout.photos if dem else None, s.number)))
    ph = layout.photos
    n = len(ph)
    if n:
        step = max(1, -(-n // most_photos))
        lon, lat = ph["lon_deg"][::step], ph["lat_deg"][::step]
        out.append({"type": "Feature", "geometry": None, "properties": {
            "kind": "photos", "platform": platform, "count": n, "every": step,
            "shown": len(lon), "packed": pack_lonlat(lon, lat)}})
        # each sortie's first photo (photos are in flight order: their sorties ascend; a
        # sortie may start in mid-strip, where the previous battery ran out)
        sorties = np.asarray(ph["sortie"])
        first = {k.number: int(np.searchsorted(sorties, k.number)) for k in layout.sorties}
        for number, i in first.items():
            if 0 <= i < n:
                out.append(_feature("takeoff", {"type": "Point", "coordinates": [
                    float(ph["lon_deg"][i]), float(ph["lat_deg"][i])]}, platform=platform,
                    sortie=number))
    return out


def area_features(area: Any) -> dict[str, Any]:
    """The GeoJSON FeatureCollection of an area alone (empty when it has no place on the
    map)."""
    features = [_area(area)] if area is not None and area.georeferenced else []
    return {"type": "FeatureCollection", "features": features}


def map_features(result: Any) -> dict[str, Any]:
    """The GeoJSON FeatureCollection of a :class:`~scanplan.project.spec.PlanResult`."""
    from ..reports.exports import spec_layouts
    from ..reports.mapview import ground_known

    features: list[dict[str, Any]] = []
    area = result.area
    if area is not None and area.georeferenced:
        features.append(_area(area))
        for platform, layout in spec_layouts(result):
            dem = "altitude_mode" in layout.notes and ground_known(result, platform)
            features += _layout(platform, layout, MAX_MAP_PHOTOS, dem)
        features += _control(result)
    return {"type": "FeatureCollection", "features": features}


def _control(result: Any) -> list[dict[str, Any]]:
    """The GCPs (``kind: "gcp"``) and checkpoints (``"check"``) of ``[control]``, each a
    Point named by its id — the same points as control.csv."""
    control = getattr(result, "control", None)
    if control is None:
        return []
    c = control.points.columns
    return [_feature(str(c["role"][i]), {"type": "Point", "coordinates": [
        round(float(c["lon_deg"][i]), 8), round(float(c["lat_deg"][i]), 8)]},
        id=str(c["id"][i]), photos=int(c["photos"][i])) for i in range(len(control.points))]

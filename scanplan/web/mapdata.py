"""The map of a plan as GeoJSON (WGS 84, lon/lat) for the page.

One FeatureCollection: the area (``kind: "area"``), each strip's photographed parts
(``"strip"``, with its number and sortie), the photo centres (``"photos"``, one MultiPoint
per flight, every k-th when there are more than :data:`MAX_MAP_PHOTOS`)
each sortie's take-off (``"takeoff"``: its first photo, where the mission files put
the home) and, with ``[control]``, the GCPs (``"gcp"``) and checkpoints (``"check"``).
Coordinates come from the same layout as the exported files; an abstract block
(``width_m × length_m``) has no place on the map and gives an empty collection.
"""

from __future__ import annotations

from typing import Any

import numpy as np

__all__ = ["MAX_MAP_PHOTOS", "map_features"]

MAX_MAP_PHOTOS = 5_000
"""Most photo centres drawn on the map; a larger flight shows every k-th."""


def _feature(kind: str, geometry: dict[str, Any], **props: Any) -> dict[str, Any]:
    return {"type": "Feature", "geometry": geometry, "properties": {"kind": kind, **props}}


def _area(area: Any) -> dict[str, Any]:
    import pyproj
    import shapely

    tr = pyproj.Transformer.from_crs(area.plan_crs, 4326, always_xy=True)
    geom = shapely.transform(area.geometry, tr.transform,
                             interleaved=False)
    return _feature("area", shapely.geometry.mapping(geom))


def _layout(platform: str, layout: Any, most_photos: int) -> list[dict[str, Any]]:
    import pyproj

    tr = pyproj.Transformer.from_crs(layout.area.plan_crs, 4326, always_xy=True)
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
                            photos=s.photos))
    ph = layout.photos
    n = len(ph)
    if n:
        step = max(1, -(-n // most_photos))
        lon, lat = ph["lon_deg"][::step], ph["lat_deg"][::step]
        out.append(_feature("photos", {"type": "MultiPoint", "coordinates": np.column_stack(
            [lon, lat]).round(7).tolist()}, platform=platform, count=n, every=step))
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


def map_features(result: Any) -> dict[str, Any]:
    """The GeoJSON FeatureCollection of a :class:`~scanplan.project.spec.PlanResult`."""
    from ..reports.exports import spec_layouts

    features: list[dict[str, Any]] = []
    area = result.area
    if area is not None and area.georeferenced:
        features.append(_area(area))
        for platform, layout in spec_layouts(result):
            features += _layout(platform, layout, MAX_MAP_PHOTOS)
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

"""What every exported file needs: WGS 84 coordinates of the layout, photos by strip.

The layout holds its geometry in the planning CRS (metric) and the photo centres also in
WGS 84 (``lon_deg``/``lat_deg``). The strip ends and the area are transformed here with
pyproj (``always_xy``: longitude first, as RFC 7946 and KML want), never by hand.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property
from typing import Any

import numpy as np
import shapely

from ..._version import __version__
from ..layout import FlightLayout

__all__ = ["GENERATOR", "LonLat", "StripPhotos", "lonlat", "photos_by_strip"]

GENERATOR = f"scanplan {__version__}"
"""How every exported file names its writer (its mark: scanplan replaces its own files)."""


def _transformer(plan_crs: str) -> Any:
    from pyproj import CRS, Transformer

    return Transformer.from_crs(CRS.from_user_input(plan_crs), CRS.from_epsg(4326),
                                always_xy=True)


@dataclass(frozen=True)
class LonLat:
    """The layout's geometry in WGS 84 (EPSG:4326), longitude first [°]."""

    layout: FlightLayout

    @cached_property
    def _tr(self) -> Any:
        return _transformer(self.layout.area.plan_crs)

    def points(self, xy_m: np.ndarray) -> np.ndarray:
        """(n, 2) planning-CRS points [m] → (n, 2) lon/lat [°]."""
        xy = np.asarray(xy_m, dtype=float).reshape(-1, 2)
        lon, lat = self._tr.transform(xy[:, 0], xy[:, 1])
        return np.column_stack([np.asarray(lon, float), np.asarray(lat, float)])

    @cached_property
    def area(self) -> Any:
        """The area (shapely) in lon/lat, exterior rings counter-clockwise and holes
        clockwise (the right-hand rule of RFC 7946, section 3.1.6)."""
        geom = shapely.transform(self.layout.area.geometry, self.points)
        return shapely.orient_polygons(geom, exterior_cw=False)


def lonlat(layout: FlightLayout) -> LonLat:
    """The WGS 84 view of ``layout`` (it must be georeferenced)."""
    if not layout.area.georeferenced:
        raise ValueError("the layout is not georeferenced (an abstract width × length block)")
    return LonLat(layout)


@dataclass(frozen=True)
class StripPhotos:
    """The photos of one strip, in flight order, split where the strip leaves the area.

    ``runs`` are (first, last) positions into the photo arrays (inclusive): a strip that
    crosses a concave area or a hole several times and is split has one run per segment
    (photos further apart than 1.5 bases start a new run).
    """

    strip: int
    order: np.ndarray  # positions of the strip's photos in the layout's photo arrays
    runs: tuple[tuple[int, int], ...]


def photos_by_strip(layout: FlightLayout) -> dict[int, StripPhotos]:
    """The photos of every strip (strip number → :class:`StripPhotos`)."""
    ph = layout.photos
    if len(ph) == 0:
        return {}
    strip = np.asarray(ph["strip"]).astype(np.int64)
    index = np.asarray(ph["index"]).astype(np.int64)
    order = np.lexsort((index, strip))
    s_sorted = strip[order]
    bounds = np.flatnonzero(np.diff(s_sorted)) + 1
    starts = np.r_[0, bounds]
    ends = np.r_[bounds, len(order)]
    x = np.asarray(ph["x_m"], float)[order]
    y = np.asarray(ph["y_m"], float)[order]
    step = np.hypot(np.diff(x), np.diff(y))
    gap = np.r_[step > 1.5 * layout.base_m, False] if len(step) else np.array([False])
    out: dict[int, StripPhotos] = {}
    for a, b in zip(starts, ends, strict=True):
        cuts = [int(a + i) for i in np.flatnonzero(gap[a:b - 1])]
        first = [int(a)] + [c + 1 for c in cuts]
        last = [*cuts, int(b - 1)]
        runs = tuple((i - int(a), j - int(a)) for i, j in zip(first, last, strict=True))
        out[int(s_sorted[a])] = StripPhotos(int(s_sorted[a]), order[a:b], runs)
    return out

"""Coordinate systems: the UTM zone of a place by arithmetic, and pyproj objects kept.

A plan is recomputed on every edit of the page, so nothing here searches PROJ's database
or builds a transformation twice:

- :func:`utm_epsg` — the WGS 84 UTM zone of a longitude and latitude by the zone rule
  (6° zones from 180°W, north from the equator, 80°S … 84°N) with the two exceptions of
  the UTM grid: zone 32 widened to 3°E … 12°E between 56°N and 64°N (south-west Norway)
  and zones 31, 33, 35, 37 widened to 9°, 12°, 12°, 9° between 72°N and 84°N, where 32,
  34 and 36 are not used (Svalbard). A point on a zone's edge is in the western zone, a
  point on the equator in the northern one (what a search of the EPSG zones' areas of use
  gave before, which the tests compare it with).
- :func:`crs`, :func:`transformer`, :func:`proj` — pyproj objects made once per process
  and reused (pyproj's CRS and Transformer objects are thread-safe since pyproj 3.1).

Sources: *The Universal Grids: Universal Transverse Mercator (UTM) and Universal Polar
Stereographic (UPS)*, DMA Technical Manual 8358.2 (1989), §2-6 (zone boundaries, the
Norway and Svalbard exceptions); NGA, *The Universal Grids and the Transverse Mercator
and Polar Stereographic Map Projections*, NGA.SIG.0012_2.0.0_UTMUPS (2014), §2.
"""

from __future__ import annotations

import math
from functools import cache
from typing import TYPE_CHECKING, Any

from ..io.kept import Kept

if TYPE_CHECKING:
    import pyproj

__all__ = ["crs", "proj", "transformer", "utm_epsg"]

UTM_SOUTH_LAT = -80.0
"""Southern limit of the UTM grid [°] (UPS beyond)."""
UTM_NORTH_LAT = 84.0
"""Northern limit of the UTM grid [°] (UPS beyond)."""
_SVALBARD_EDGES = ((9.0, 31), (21.0, 33), (33.0, 35), (42.0, 37))
"""East edge [°E] of each widened zone between 72°N and 84°N, and the zone."""


def utm_epsg(lon_deg: float, lat_deg: float) -> int | None:
    """EPSG code of the WGS 84 UTM zone that holds a point (None outside 80°S … 84°N).

    Parameters
    ----------
    lon_deg, lat_deg : float
        Longitude and latitude on WGS 84 [°].

    Returns
    -------
    int or None
        326zz north of the equator (the equator included), 327zz south of it, zz the zone
        1 … 60; None where the UTM grid does not reach (the polar caps) or for a
        longitude outside −180 … 180.

    Examples
    --------
    >>> utm_epsg(37.6, 55.75), utm_epsg(-70.6, -33.4)    # Moscow, Santiago
    (32637, 32719)
    >>> utm_epsg(5.3, 60.4), utm_epsg(15.6, 78.2)        # Bergen (32V), Longyearbyen (33X)
    (32632, 32633)
    """
    lon, lat = float(lon_deg), float(lat_deg)
    if not (UTM_SOUTH_LAT <= lat <= UTM_NORTH_LAT and -180.0 <= lon <= 180.0):
        return None
    zone = min(max(math.ceil((lon + 180.0) / 6.0), 1), 60)
    if 56.0 <= lat < 64.0 and 3.0 < lon <= 12.0:  # zone 32V reaches west to 3°E
        zone = 32
    elif lat >= 72.0 and 0.0 < lon <= 42.0:  # band X: 31X, 33X, 35X, 37X only
        zone = next(z for east, z in _SVALBARD_EDGES if lon <= east)
    return (32600 if lat >= 0.0 else 32700) + zone


def _key(value: Any) -> tuple[str, str]:
    """A hashable key of a CRS given as a pyproj CRS, an EPSG code or a string."""
    srs = getattr(value, "srs", None)
    if srs is not None:
        return ("crs", str(srs))
    return (type(value).__name__, str(value))


_MAX_KEPT = 64
_CRS_CACHE: Kept[tuple[str, str], Any] = Kept(_MAX_KEPT)
_TRANSFORMERS: Kept[tuple[tuple[str, str], tuple[str, str]], Any] = Kept(_MAX_KEPT)
_PROJS: Kept[tuple[str, str], Any] = Kept(_MAX_KEPT)


def crs(value: Any) -> pyproj.CRS:
    """``pyproj.CRS.from_user_input(value)``, made once per process.

    Raises
    ------
    pyproj.exceptions.CRSError, TypeError, ValueError
        As pyproj does for a value it does not know (nothing is kept then).
    """
    import pyproj

    if isinstance(value, pyproj.CRS):
        return value
    return _CRS_CACHE.made(_key(value), lambda: pyproj.CRS.from_user_input(value))


def transformer(src: Any, dst: Any) -> pyproj.Transformer:
    """``pyproj.Transformer.from_crs(src, dst, always_xy=True)``, made once per process.

    Parameters
    ----------
    src, dst : pyproj.CRS, int or str
        The CRSs (an EPSG code, ``"EPSG:32637"``, WKT, …).
    """
    import pyproj

    return _TRANSFORMERS.made((_key(src), _key(dst)),
                              lambda: pyproj.Transformer.from_crs(src, dst, always_xy=True))


def proj(value: Any) -> pyproj.Proj:
    """``pyproj.Proj(value)`` (for its scale factors), made once per process."""
    import pyproj

    return _PROJS.made(_key(value), lambda: pyproj.Proj(value))


@cache
def epsg_crs(code: int) -> pyproj.CRS:
    """``pyproj.CRS.from_epsg(code)``, made once per process."""
    import pyproj

    return pyproj.CRS.from_epsg(int(code))

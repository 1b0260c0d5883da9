"""Where the area is, checked against what else the project says about the place.

Two checks on a georeferenced area (a polygon from a file or inline), each a warning the
terminal, the JSON and the documents show:

- **latitude and longitude swapped** (``area_latlon_swapped``): a polygon given as
  ``[lat, lon]`` where ``[lon, lat]`` is meant (a Moscow block then lands in Iran) plans
  without an error, since both orders are valid coordinates. The swap is said when the
  other evidence of the project points to the swapped place and not to the given one: the
  ``[site]`` of the sun window lies within :data:`SITE_FAR_KM` of the swapped centre and
  farther from the given one, or the swapped centre falls inside the area of use of the
  polygon's CRS or of the planning CRS (a Gauss–Krüger zone, a national system) while the
  given one does not. Nothing is guessed or changed: the user checks the file.
- **the site far from the area** (``site_far_from_area``): ``[site] lat_deg, lon_deg`` is
  typed separately from the area; the sun window is computed there. Without ``[site]`` the
  area's centre is the site (:func:`scanplan.project.design.layout_site`); a site given
  farther than :data:`SITE_FAR_KM` from the area's centre is said, with the distance.

Distances are geodesic on the WGS 84 ellipsoid (:class:`pyproj.Geod`).
"""

from __future__ import annotations

import functools
import math
from typing import Any

from ..geo.layout import Area
from ..i18n.messages import Message
from ..rules.results import PlanWarning

__all__ = ["SITE_FAR_KM", "area_site_warnings", "site_of", "swapped_reason"]

SITE_FAR_KM = 50.0
"""Largest distance [km] between ``[site]`` and the area's centre without a warning.

The sun's elevation at two places differs by at most the arc between them (the zenith
angle is the arc from the place to the sub-solar point; by the triangle inequality on the
sphere two such arcs differ by at most the arc between the places): 50 km is 0.45° of arc
(1° ≈ 111.2 km on the mean Earth radius 6371 km), which moves the start and end of a sun
window by a few minutes at most. A site farther away is not the area's — usually a typing
error, or the coordinates of the contractor's office."""
_KM_PER_DEG = 6371.0 * math.pi / 180.0  # mean Earth radius 6371 km (IUGG), km per degree


def _distance_km(lon1: float, lat1: float, lon2: float, lat2: float) -> float:
    """Geodesic distance [km] on the WGS 84 ellipsoid."""
    from pyproj import Geod

    _, _, metres = Geod(ellps="WGS84").inv(lon1, lat1, lon2, lat2)
    return float(metres) / 1000.0


def _inside_use(crs_text: str | None, lon: float, lat: float) -> tuple[bool, str] | None:
    """Whether (lon, lat) [°] lies inside the area of use of ``crs_text``, and the CRS as
    the reports name it (its EPSG code, the same in every language); None when the CRS
    has no bounded area of use (WGS 84 covers the world)."""
    if not crs_text or crs_text == "LOCAL":
        return None
    found = _area_of_use(crs_text)
    if found is None:
        return None
    west, east, south, north, name = found
    if west <= east:
        in_lon = west <= lon <= east
    else:  # an area of use across the antimeridian
        in_lon = lon >= west or lon <= east
    return in_lon and south <= lat <= north, name


@functools.lru_cache(maxsize=64)
def _area_of_use(crs_text: str) -> tuple[float, float, float, float, str] | None:
    """The bounded area of use of ``crs_text`` (west, east, south, north [°]) and its name
    in the reports, or None (looked up in PROJ's database once per CRS: the page re-plans
    the same area on every edit)."""
    import pyproj

    try:
        crs = pyproj.CRS.from_user_input(crs_text)
    except pyproj.exceptions.CRSError:
        return None
    use = crs.area_of_use
    if use is None or (use.east - use.west >= 359.0 and use.north - use.south >= 179.0):
        return None
    code = crs.to_epsg()
    return use.west, use.east, use.south, use.north, f"EPSG:{code}" if code else crs.name


def swapped_reason(area: Area, site: tuple[float, float] | None) -> Message | None:
    """Why the area's coordinates look swapped (latitude given as longitude and back), or
    None.

    Parameters
    ----------
    area : Area
        The planned area; only a georeferenced one given in geographic coordinates is
        checked (a projected polygon's x/y order is the CRS's).
    site : tuple of float or None
        ``[site]`` (lat, lon) [°] as the project gives it, None when not given.
    """
    if not area.georeferenced or area.centroid_lonlat is None:
        return None
    lon, lat = area.centroid_lonlat
    if abs(lon) > 90.0:  # swapped, it would be a latitude beyond the pole
        return None
    if site is not None:
        s_lat, s_lon = site
        given = _distance_km(lon, lat, s_lon, s_lat)
        swapped = _distance_km(lat, lon, s_lon, s_lat)
        if swapped <= SITE_FAR_KM < given:
            return Message("area_swap.site", given=given, swapped=swapped)
    for crs in (area.input_crs, area.plan_crs):
        now = _inside_use(crs, lon, lat)
        other = _inside_use(crs, lat, lon)
        if now is not None and other is not None and not now[0] and other[0]:
            return Message("area_swap.crs", crs=now[1])
    return None


def area_site_warnings(area: Area | None, site: tuple[float, float] | None
                       ) -> list[PlanWarning]:
    """The warnings of the area's place: coordinates that look swapped, a site far from
    the area (see the module docstring).

    Parameters
    ----------
    area : Area or None
        The planned area (None, or an abstract rectangle: nothing to check).
    site : tuple of float or None
        ``[site]`` (lat, lon) [°] as given, None when the project leaves it out.

    Returns
    -------
    list of PlanWarning
    """
    if area is None or not area.georeferenced or area.centroid_lonlat is None:
        return []
    lon, lat = area.centroid_lonlat
    why = swapped_reason(area, site)
    if why is not None:
        return [PlanWarning("area_latlon_swapped", Message(
            "area_latlon_swapped", lon=lon, lat=lat, slon=lat, slat=lon, why=why))]
    if site is None:
        return []
    s_lat, s_lon = site
    km = _distance_km(lon, lat, s_lon, s_lat)
    if km <= SITE_FAR_KM:
        return []
    return [PlanWarning("site_far_from_area", Message(
        "site_far_from_area", lat=s_lat, lon=s_lon, km=km, alat=lat, alon=lon,
        limit=SITE_FAR_KM, deg=min(km / _KM_PER_DEG, 180.0)))]


def site_of(project: Any) -> tuple[float, float] | None:
    """``[site]`` as the project gives it.

    Parameters
    ----------
    project : ProjectModel
        The parsed project file (its ranges already checked).

    Returns
    -------
    tuple of float or None
        (lat, lon) [°] when both are given, else None.
    """
    site = project.site
    lat = site.lat_deg if site is not None else None
    lon = site.lon_deg if site is not None else None
    return None if lat is None or lon is None else (float(lat), float(lon))

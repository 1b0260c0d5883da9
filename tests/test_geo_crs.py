"""The planning CRS without a database search (scanplan.geo.crs): the UTM zone of a place by
the zone rule agrees with PROJ's EPSG zones wherever those apply, follows the UTM grid's
Norway and Svalbard exceptions, and pyproj's objects are made once per process."""

from __future__ import annotations

import numpy as np
import pytest

from scanplan.geo import crs as geocrs
from scanplan.geo.area import AreaSpec, load_area


def _zones() -> list:
    """PROJ's WGS 84 UTM zones with their areas of use (one database query)."""
    from pyproj.database import query_utm_crs_info

    return query_utm_crs_info(datum_name="WGS 84")


def _by_database(lon: float, lat: float, zones: list) -> int | None:
    """The zone as the planner found it before: PROJ's WGS 84 UTM zones whose area of use
    holds the point (edges included), the nearest central meridian first, then the lower
    code — the query with a point as the area of interest, done once for every zone."""
    hits = [z for z in zones if z.area_of_use.west <= lon <= z.area_of_use.east
            and z.area_of_use.south <= lat <= z.area_of_use.north]
    if not hits:
        return None
    hits.sort(key=lambda z: (abs((z.area_of_use.west + z.area_of_use.east) / 2 - lon),
                             z.code))
    return int(hits[0].code)


def test_the_emulated_query_is_the_query():
    """A few points (a query of PROJ's database takes tenths of a second) queried as the
    planner did, against the emulation the test below uses for thousands."""
    from pyproj.aoi import AreaOfInterest
    from pyproj.database import query_utm_crs_info

    zones = _zones()
    for lon, lat in ((6.0, 45.0), (0.0, 0.0), (37.6, 55.7), (10.0, 84.2), (-180.0, -80.0)):
        found = query_utm_crs_info(datum_name="WGS 84", area_of_interest=AreaOfInterest(
            lon, lat, lon, lat))
        found.sort(key=lambda z: (abs((z.area_of_use.west + z.area_of_use.east) / 2 - lon),
                                  z.code))
        assert (int(found[0].code) if found else None) == _by_database(lon, lat, zones)


def _outside_exceptions(lon: float, lat: float) -> bool:
    """Outside the grid's two exceptions, and outside the one zone whose EPSG area of use is
    not the zone: zone 29N's reaches 12.01°W and 84.01°N, so its middle lies 0.005° west of
    the zone's (the nearest middle then chose zone 29 at 12.01°W … 12°W where the zone rule
    says 28, zone 30 on 6°W where it says 29, zone 29 north of 84°N where it says none, and
    29S on the equator in zone 29 where it says 29N)."""
    in_29 = -12.01 <= lon <= -6.0
    quirk = (-12.01 <= lon <= -12.0 or lon == -6.0
             or (in_29 and (84.0 < lat <= 84.01 or lat == 0.0)))
    return not ((56 <= lat < 64 and 3 < lon <= 12) or (lat >= 72 and 0 < lon <= 42) or quirk)


def _sample() -> list[tuple[float, float]]:
    rng = np.random.default_rng(3)
    pts = [(float(x), float(y)) for x, y in zip(rng.uniform(-180, 180, 3000),
                                                rng.uniform(-85, 85, 3000), strict=True)]
    pts += [(float(x), float(y)) for x in np.arange(-180.0, 180.1, 1.5)
            for y in np.arange(-81.0, 85.1, 3.0)]
    # every kind of edge: zone edges, the antimeridian, the equator, the grid's limits
    for lon in (-180.0, -174.0, -173.9999999, -12.0, -6.0, 0.0, 5.9999999, 6.0, 6.0000001,
                174.0, 180.0):
        for lat in (-80.0000001, -80.0, -1e-9, 0.0, 1e-9, 45.0, 84.0, 84.0000001, 84.02):
            pts.append((lon, lat))
    return pts


def test_the_zone_rule_agrees_with_the_epsg_zones():
    zones = _zones()
    pts = [(lon, lat) for lon, lat in _sample() if _outside_exceptions(lon, lat)]
    assert len(pts) > 3000
    for lon, lat in pts:
        assert geocrs.utm_epsg(lon, lat) == _by_database(lon, lat, zones), (lon, lat)


@pytest.mark.parametrize(("lon", "lat", "zone"), [
    (5.32, 60.39, 32632),  # Bergen: 32V reaches west to 3°E (nominally zone 31)
    (3.5, 56.0, 32632),
    (3.0, 60.0, 32631),  # on the edge: the western zone
    (5.0, 64.0, 32631),  # band W: no exception
    (7.0, 55.99, 32632),
    (15.63, 78.22, 32633),  # Longyearbyen: 33X
    (8.0, 78.0, 32631),  # 31X reaches east to 9°E (nominally zone 32)
    (10.0, 79.0, 32633),  # 33X from 9°E
    (23.0, 80.0, 32635),  # 35X from 21°E (nominally 34)
    (34.0, 80.0, 32637),  # 37X from 33°E (nominally 36)
    (45.0, 80.0, 32638),  # east of 42°E: nominal
    (8.0, 71.99, 32632),  # below band X: nominal
])
def test_the_norway_and_svalbard_exceptions(lon, lat, zone):
    """DMA TM 8358.2 §2-6: zone 32V spans 3°E … 12°E; in band X (72°N … 84°N) zones 32, 34
    and 36 are not used, 31X/37X span 9°, 33X/35X 12°."""
    assert geocrs.utm_epsg(lon, lat) == zone


def test_zone_29_is_its_nominal_6_degrees():
    """Where EPSG's area of use of zone 29N runs 0.01° past the zone, the zone rule holds."""
    assert _by_database(-12.001, 10.0, _zones()) == 32629
    assert geocrs.utm_epsg(-12.001, 10.0) == 32628 and geocrs.utm_epsg(-11.99, 10.0) == 32629
    assert geocrs.utm_epsg(-8.0, 84.005) is None and geocrs.utm_epsg(-9.0, 0.0) == 32629
    assert _by_database(-6.0, 10.0, _zones()) == 32630 and geocrs.utm_epsg(-6.0, 10.0) == 32629


def test_polar_caps_and_bad_longitudes_have_no_zone():
    assert geocrs.utm_epsg(10.0, 84.5) is None and geocrs.utm_epsg(10.0, -80.5) is None
    assert geocrs.utm_epsg(180.5, 10.0) is None


def test_a_polygon_in_western_norway_is_planned_in_zone_32():
    ring = [[5.30, 60.38], [5.34, 60.38], [5.34, 60.40], [5.30, 60.40]]
    a = load_area(AreaSpec(polygon=ring))
    assert a.plan_crs == "EPSG:32632" and a.scale_error_pct < 0.1


def test_pyproj_objects_are_made_once():
    assert geocrs.transformer("EPSG:32637", 4326) is geocrs.transformer("EPSG:32637", 4326)
    assert geocrs.epsg_crs(32637) is geocrs.epsg_crs(32637)
    assert geocrs.proj("EPSG:32637") is geocrs.proj("EPSG:32637")
    t = geocrs.transformer(geocrs.epsg_crs(4326), "EPSG:32637")
    x, y = t.transform(39.0, 0.0)
    assert x == pytest.approx(500_000.0) and y == pytest.approx(0.0, abs=1e-6)

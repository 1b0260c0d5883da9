"""Issue 11, item 3: the exported files, read back by parsers that are not ours.

* KML and GeoJSON: GDAL (through pyogrio) opens them; feature counts, longitude/latitude
  order (Lida is at 25.3° E, 53.9° N: a swapped pair would put it in the Indian Ocean)
  and the area returned to the planning CRS with its size;
* the QGroundControl Plan file: checked against the format rules of QGroundControl's
  loader (``JsonHelper::validateExternalQGCJsonFile``, ``MissionController::
  _loadJsonMissionFileV2``, ``MissionItem::load``: fileType "Plan", version 1, a string
  groundStation, mission version 2, firmwareType, plannedHomePosition, items of
  SimpleItem with seven params), the MAV_CMD and MAV_FRAME numbers of MAVLink's common
  set, and what the crew relies on: take-off, speed, the trigger set at every strip's
  first photo and cleared at its last, return to launch;
* the CSV: pandas.
"""

from __future__ import annotations

import json
import math
import xml.etree.ElementTree as ET

import numpy as np
import pandas as pd
import pytest
import shapely
from hypothesis import given, settings
from hypothesis import strategies as st
from layouts import UTM35, make_layout
from pyogrio import list_layers
from pyogrio.raw import read
from pyproj import Geod, Transformer

from scanplan.geo.export import (
    ExportNames,
    MissionOptions,
    layout_files,
    render_csv,
    render_geojson,
    render_kml,
    render_plan,
)
from scanplan.geo.layout import PHOTO_COLUMNS

# MAVLink common.xml: the commands and frames a survey mission may hold
MAV_CMD_NAV_WAYPOINT, MAV_CMD_NAV_RETURN_TO_LAUNCH, MAV_CMD_NAV_TAKEOFF = 16, 20, 22
MAV_CMD_DO_CHANGE_SPEED, MAV_CMD_DO_SET_CAM_TRIGG_DIST = 178, 206
MAV_FRAME = {0: "GLOBAL", 2: "MISSION", 3: "GLOBAL_RELATIVE_ALT", 10: "GLOBAL_TERRAIN_ALT"}
POSITIONED = {MAV_CMD_NAV_WAYPOINT, MAV_CMD_NAV_TAKEOFF}


def _read_layers(path):
    """{layer name: (geometries, fields dict)} through GDAL."""
    out = {}
    for name, _ in list_layers(path):
        meta, _, wkb, fields = read(path, layer=name)
        out[str(name)] = (shapely.from_wkb(wkb), dict(zip(meta["fields"], fields, strict=True)),
                          meta["crs"])
    return out


def _write(tmp_path, files):
    for name, data in files.items():
        (tmp_path / name).write_bytes(data)


# ---------------------------------------------------------------------------------------
# KML
# ---------------------------------------------------------------------------------------


@pytest.mark.parametrize("parts", [True, False], ids=["parts-given", "parts-from-photos"])
def test_kml_opens_in_gdal_with_area_strips_and_numbered_photo_centres(tmp_path, parts):
    layout = make_layout(notch=True, parts=parts)
    path = tmp_path / "flight.kml"
    path.write_bytes(render_kml(layout))
    layers = _read_layers(path)
    assert list(layers) == ["Area", "Strips", "Photo centres"]
    area, _, crs = layers["Area"]
    strips, strip_fields, _ = layers["Strips"]
    photos, photo_fields, _ = layers["Photo centres"]
    assert crs == "EPSG:4326"
    assert len(area) == 1 and len(strips) == len(layout.strips) == 6
    assert len(photos) == len(layout.photos) == 68
    # numbered in flight order; lon first: Lida, not the Indian Ocean
    assert list(photo_fields["Name"][:3]) == ["1", "2", "3"]
    xy = shapely.get_coordinates(photos)
    assert np.allclose(xy[:, 0], layout.photos["lon_deg"], atol=1e-7)
    assert np.allclose(xy[:, 1], layout.photos["lat_deg"], atol=1e-7)
    assert 25.2 < xy[:, 0].min() and xy[:, 1].max() < 54.0
    # the area back in UTM: its size and its hole (the notch) survive
    to_utm = Transformer.from_crs("EPSG:4326", UTM35, always_xy=True)
    back = shapely.transform(area[0], lambda p: np.column_stack(to_utm.transform(p[:, 0],
                                                                                p[:, 1])))
    assert back.area == pytest.approx(layout.area.geometry.area, rel=1e-4)  # 1 cm rounding
    assert len(back.interiors) == 1
    # the split strips are two lines each
    kinds = [g.geom_type for g in strips]
    assert kinds.count("MultiLineString") == 2 and kinds.count("LineString") == 4
    assert list(strip_fields["Name"][:2]) == ["Strip 1", "Strip 2"]


def test_kml_escapes_text_and_is_styled(tmp_path):
    layout = make_layout()
    names = ExportNames(title='Lida <"north"> & co', strip="Маршрут {n}")
    data = render_kml(layout, names)
    root = ET.fromstring(data)  # well-formed
    ns = {"k": "http://www.opengis.net/kml/2.2"}
    assert root.find("k:Document/k:name", ns).text == 'Lida <"north"> & co'
    assert {s.get("id") for s in root.findall("k:Document/k:Style", ns)} == {
        "area", "strip", "sortie", "takeoff", "photo-normal", "photo-highlight"}
    assert root.find("k:Document/k:StyleMap", ns).get("id") == "photo"
    assert b"scanplan" in data.split(b"<kml", 1)[0]  # the writer's mark, before the root
    path = tmp_path / "f.kml"
    path.write_bytes(data)
    assert list(_read_layers(path)["Strips"][1]["Name"][:1]) == ["Маршрут 1"]


# ---------------------------------------------------------------------------------------
# GeoJSON
# ---------------------------------------------------------------------------------------


def test_geojson_is_rfc7946_and_opens_in_gdal(tmp_path):
    layout = make_layout(notch=True)
    data = render_geojson(layout)
    doc = json.loads(data)
    assert doc["type"] == "FeatureCollection" and "crs" not in doc
    kinds = [f["properties"]["kind"] for f in doc["features"]]
    assert kinds.count("area") == 1 and kinds.count("strip") == 6 and kinds.count("photo") == 68
    # right-hand rule: exterior counter-clockwise, holes clockwise (RFC 7946, 3.1.6)
    poly = shapely.geometry.shape(doc["features"][0]["geometry"])
    assert poly.exterior.is_ccw and not poly.interiors[0].is_ccw
    path = tmp_path / "flight.geojson"
    path.write_bytes(data)
    layers = _read_layers(path)
    assert len(layers) == 1
    geoms, fields, crs = next(iter(layers.values()))
    assert crs == "EPSG:4326" and len(geoms) == 1 + 6 + 68
    pts = shapely.get_coordinates(geoms[fields["kind"] == "photo"])
    assert np.allclose(pts[:, 0], layout.photos["lon_deg"], atol=1e-7)
    assert np.allclose(pts[:, 1], layout.photos["lat_deg"], atol=1e-7)
    assert set(PHOTO_COLUMNS) <= set(fields)
    assert np.array_equal(fields["strip"][fields["kind"] == "photo"], layout.photos["strip"])


# ---------------------------------------------------------------------------------------
# CSV
# ---------------------------------------------------------------------------------------


def test_photos_csv_reads_in_pandas_with_every_column():
    layout = make_layout(sorties=2)
    frame = pd.read_csv(__import__("io").BytesIO(render_csv(layout)))
    assert list(frame.columns) == list(PHOTO_COLUMNS)
    assert len(frame) == len(layout.photos)
    assert frame["photo"].tolist() == list(range(1, len(frame) + 1))
    assert frame["sortie"].max() == 2
    assert np.allclose(frame["lon_deg"], layout.photos["lon_deg"], atol=1e-8)
    assert np.allclose(frame["x_m"], layout.photos["x_m"], atol=1e-3)
    assert (frame["agl_m"] == 120).all() and (frame["altitude_m"] - frame["ground_m"] == 120).all()


def test_an_abstract_block_has_no_georeferenced_files():
    layout = make_layout(georeferenced=False)
    assert layout_files(layout, mission=MissionOptions(speed_ms=10)) == {}
    frame = pd.read_csv(__import__("io").BytesIO(render_csv(layout)))
    assert frame["lon_deg"].isna().all() and len(frame) == len(layout.photos)
    with pytest.raises(ValueError, match="not georeferenced"):
        render_kml(layout)


# ---------------------------------------------------------------------------------------
# QGroundControl Plan
# ---------------------------------------------------------------------------------------


def check_qgc_plan(doc: dict) -> list[dict]:
    """The rules QGroundControl's loader applies, and MAVLink's numbers; the items."""
    assert doc["fileType"] == "Plan" and doc["version"] == 1
    assert isinstance(doc["groundStation"], str)
    assert doc["geoFence"]["version"] == 2 and doc["rallyPoints"]["version"] == 2
    m = doc["mission"]
    assert m["version"] == 2
    assert m["firmwareType"] in (0, 3, 12) and m["vehicleType"] in (1, 2, 22)
    assert m["cruiseSpeed"] > 0 and m["hoverSpeed"] > 0
    lat, lon, _alt = m["plannedHomePosition"]
    assert -90 <= lat <= 90 and -180 <= lon <= 180
    items = m["items"]
    assert items, "a plan holds at least one mission item"
    for k, item in enumerate(items, start=1):
        assert item["type"] == "SimpleItem" and item["autoContinue"] is True
        assert item["doJumpId"] == k
        assert len(item["params"]) == 7
        assert all(p is None or isinstance(p, int | float) for p in item["params"])
        assert item["command"] in (16, 20, 22, 178, 206)
        assert item["frame"] in MAV_FRAME
        if item["command"] in POSITIONED:
            assert item["frame"] in (0, 3, 10)
            p = item["params"]
            assert -90 <= p[4] <= 90 and -180 <= p[5] <= 180 and math.isfinite(p[6])
        else:
            assert item["frame"] == 2
    return items


def _trigger_runs(items):
    """[(first waypoint item, last waypoint item, distance)] of every triggered run."""
    runs, open_at, last_wp = [], None, None
    for item in items:
        if item["command"] == MAV_CMD_NAV_WAYPOINT:
            last_wp = item
        elif item["command"] == MAV_CMD_DO_SET_CAM_TRIGG_DIST:
            if item["params"][0] > 0:
                assert open_at is None, "the trigger is set twice without being cleared"
                open_at = (last_wp, item["params"][0])
            else:
                assert open_at is not None, "the trigger is cleared without being set"
                runs.append((open_at[0], last_wp, open_at[1]))
                open_at = None
    assert open_at is None, "the trigger is left on"
    return runs


@pytest.mark.parametrize("parts", [True, False], ids=["parts-given", "parts-from-photos"])
def test_plan_file_follows_the_qgc_format_and_triggers_per_strip(parts):
    layout = make_layout(notch=True, parts=parts)
    doc = json.loads(render_plan(layout, 1, MissionOptions(speed_ms=12.0)))
    items = check_qgc_plan(doc)
    commands = [i["command"] for i in items]
    assert commands[0] == MAV_CMD_NAV_TAKEOFF and commands[1] == MAV_CMD_DO_CHANGE_SPEED
    assert commands[-1] == MAV_CMD_NAV_RETURN_TO_LAUNCH
    assert items[1]["params"][1] == 12.0
    assert {i["frame"] for i in items if i["command"] in POSITIONED} == {3}  # above home
    assert doc["mission"]["globalPlanAltitudeMode"] == 1
    runs = _trigger_runs(items)
    assert len(runs) >= 6 + 2  # one per strip, one more for each split strip (or more)
    # every run fires the strip's photos: (photos - 1) bases between its ends, geodesic
    geod = Geod(ellps="WGS84")
    per_run = []
    for first, last, dist in runs:
        assert dist == pytest.approx(layout.base_m, rel=1e-3)  # on the ground: grid base / k
        _, _, d = geod.inv(first["params"][5], first["params"][4], last["params"][5],
                           last["params"][4])
        per_run.append(math.floor(d / dist) + 1)  # disarmed half a base past the last
    assert sum(per_run) == len(layout.photos)
    assert all(i["params"][6] == 120.0 for i in items if i["command"] in POSITIONED)


def test_several_sorties_give_one_plan_each_covering_every_strip_once():
    layout = make_layout(sorties=2)
    files = layout_files(layout, mission=MissionOptions(speed_ms=10.0, vehicle="fixed_wing",
                                                        firmware="px4"))
    plans = sorted(k for k in files if k.endswith(".plan"))
    assert plans == ["mission-01.plan", "mission-02.plan"]
    total = 0
    for name in plans:
        doc = json.loads(files[name])
        items = check_qgc_plan(doc)
        assert doc["mission"]["vehicleType"] == 1 and doc["mission"]["firmwareType"] == 12
        assert items[0]["params"][0] == 15.0  # a fixed wing climbs out at 15° pitch
        total += len(_trigger_runs(items))
    assert total == len(layout.strips)
    assert {"flight.kml", "flight.geojson", "photos.csv"} <= set(files)


def test_altitude_frame_and_altitudes_per_waypoint():
    layout = make_layout(agl_m=100.0, ground_m=210.0)
    amsl = json.loads(render_plan(layout, 1, MissionOptions(speed_ms=8, frame="amsl")))
    wps = [i for i in check_qgc_plan(amsl) if i["command"] == MAV_CMD_NAV_WAYPOINT]
    assert {i["frame"] for i in wps} == {0} and {i["params"][6] for i in wps} == {310.0}
    assert amsl["mission"]["plannedHomePosition"][2] == 210.0
    terrain = json.loads(render_plan(layout, 1, MissionOptions(speed_ms=8, frame="terrain")))
    items = check_qgc_plan(terrain)
    assert {i["frame"] for i in items if i["command"] == MAV_CMD_NAV_WAYPOINT} == {10}
    assert items[0]["frame"] == 3  # the take-off climbs above the home
    n = len(wps)
    given = np.linspace(90.0, 110.0, n)
    doc = json.loads(render_plan(layout, 1, MissionOptions(speed_ms=8), altitudes_m=given))
    got = [i["params"][6] for i in check_qgc_plan(doc) if i["command"] == MAV_CMD_NAV_WAYPOINT]
    assert np.allclose(got, given)
    with pytest.raises(ValueError, match=f"must hold {n} finite altitudes"):
        render_plan(layout, 1, MissionOptions(speed_ms=8), altitudes_m=given[:-1])


def test_mission_options_are_checked():
    with pytest.raises(ValueError, match="speed_ms"):
        MissionOptions(speed_ms=0)
    with pytest.raises(ValueError, match="frame must be one of relative, amsl, terrain"):
        MissionOptions(speed_ms=5, frame="agl")  # type: ignore[arg-type]


def test_without_listed_photo_centres_no_mission_and_no_table():
    """A block whose photo centres were too many to list: no mission (its trigger points
    and altitudes are unknown; a mission that never triggers must not be written)."""
    import dataclasses

    from scanplan.geo.layout import Photos

    layout = dataclasses.replace(make_layout(), photos=Photos({}))
    files = layout_files(layout, mission=MissionOptions(speed_ms=10))
    assert sorted(files) == ["flight.geojson", "flight.gpkg", "flight.kml"]


@settings(max_examples=25, deadline=None)
@given(width=st.floats(200.0, 3000.0), length=st.floats(200.0, 3000.0),
       spacing=st.floats(40.0, 300.0), base=st.floats(15.0, 120.0),
       sorties=st.integers(1, 3), notch=st.booleans(), parts=st.booleans())
def test_every_mission_fires_every_photo_and_passes_the_format(width, length, spacing, base,
                                                               sorties, notch, parts):
    """Over random serpentines (split strips or not, parts given or found from the
    photos, several sorties): every sortie's plan passes the QGC format checks, the trigger
    is set and cleared in pairs, and the triggered runs fire exactly the photo count."""
    layout = make_layout(width_m=width, length_m=length, spacing_m=spacing, base_m=base,
                         sorties=min(sorties, math.ceil(width / spacing)), notch=notch,
                         parts=parts)
    geod, fired = Geod(ellps="WGS84"), 0
    for s in layout.sorties:
        items = check_qgc_plan(json.loads(render_plan(layout, s.number,
                                                      MissionOptions(speed_ms=9.0))))
        for first, last, dist in _trigger_runs(items):
            _, _, d = geod.inv(first["params"][5], first["params"][4], last["params"][5],
                               last["params"][4])
            n = math.floor(d / dist)  # whole bases and the half base to the disarm point
            # half a base on the line, or less on the arc of a semicircle turn
            assert 0.15 * dist - 1e-3 * d <= d - n * dist <= 0.5 * dist + 1e-3 * d
            fired += n + 1
    assert fired == len(layout.photos)


def test_a_strip_without_photos_is_flown_with_the_camera_off():
    """A strip whose photos all fall outside (a sliver): the mission flies from the strip
    before it to the strip after it, no trigger on it."""
    import dataclasses

    from scanplan.geo.layout import Photos

    layout = make_layout()
    keep = layout.photos["strip"] != 2
    photos = Photos({k: v[keep] for k, v in layout.photos.columns.items()})
    strips = tuple(dataclasses.replace(s, photos=0, parts=()) if s.number == 2 else s
                   for s in layout.strips)
    layout = dataclasses.replace(layout, photos=photos, strips=strips)
    items = check_qgc_plan(json.loads(render_plan(layout, 1, MissionOptions(speed_ms=5))))
    assert len(_trigger_runs(items)) == len(layout.strips) - 1
    wps = [i for i in items if i["command"] == MAV_CMD_NAV_WAYPOINT]
    assert {w["params"][6] for w in wps} == {120.0}

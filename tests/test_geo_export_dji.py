"""The mission for DJI Pilot 2 (WPML route files) and the flight as a GeoPackage.

Every WPML file of the polygon examples is unpacked and both its documents parsed with a
real XML parser (defusedxml); the elements and enums DJI's WPML documentation requires are
checked, and the photos the route's actions fire are counted strip by strip against
photos.csv. The djikmz package (an independent WPML model) reads the mission configuration,
every waypoint, every trigger and every action back. flight.gpkg is read with pyogrio
(GDAL) and, where installed, GDAL's ogrinfo.
"""

from __future__ import annotations

import functools
import io
import itertools
import math
import os
import shutil
import subprocess
import zipfile
from pathlib import Path

import defusedxml.ElementTree as DET
import numpy as np
import pandas as pd
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from pyproj import Geod

from scanplan.geo.export import format_named
from scanplan.geo.export import wpml as wpml_mod
from scanplan.geo.export.gpkg import GPKG_LAYERS
from scanplan.io.targets import written_by_scanplan
from scanplan.project.file import load_project
from scanplan.project.spec import plan_project
from scanplan.reports.exports import export_files, stale_exports

EXAMPLES = Path(__file__).resolve().parent.parent / "examples"
POLYGON_UAV = ["uav-town-2000", "uav-town-valley-2000"]
W = "{http://www.dji.com/wpmz/1.0.2}"
K = "{http://www.opengis.net/kml/2.2}"
GEOD = Geod(ellps="WGS84")
#: Enums of DJI's WPML documentation ("Common Elements", "Product Support") and, for the
#: Zenmuse P1 (50) and L2 (84), DJI Payload SDK's E_DjiCameraType.
DRONE_ENUMS = {89, 60, 67, 77, 91}
PAYLOAD_ENUMS = {42, 43, 50, 52, 53, 61, 66, 67, 68, 80, 81, 82, 83, 84, 65534}
TRIGGERS = {"reachPoint", "betweenAdjacentPoints", "multipleTiming", "multipleDistance"}
TURN_MODES = {"coordinateTurn", "toPointAndStopWithDiscontinuityCurvature",
              "toPointAndStopWithContinuityCurvature", "toPointAndPassWithContinuityCurvature"}
MISSION_CONFIG = ("flyToWaylineMode", "finishAction", "exitOnRCLost", "takeOffSecurityHeight",
                  "globalTransitionalSpeed", "globalRTHHeight", "droneInfo", "payloadInfo")


def _files(name: str, folder: str) -> dict[str, bytes]:
    spec = plan_project(load_project(str(EXAMPLES / f"{name}.toml")))
    notes: list[str] = []
    files = export_files(spec, folder, note=notes.append)
    return {os.path.basename(p): data for p, (_, data) in files.items()} | {
        "_notes": "\n".join(notes).encode()}


@pytest.fixture(scope="module", params=POLYGON_UAV)
def example(request, tmp_path_factory):
    folder = str(tmp_path_factory.mktemp(request.param))
    return request.param, folder, _files(request.param, folder)


def _kmzs(files: dict[str, bytes]) -> dict[str, bytes]:
    return {k: v for k, v in files.items() if k.endswith(".kmz")}


def _needs_geoid(name: str) -> None:
    if name == "uav-town-valley-2000" and wpml_mod.egm96_separation_m(
            np.array([37.0]), np.array([55.0])) is None:
        pytest.skip("PROJ has no EGM96 grid here (Debian proj-data); the terrain plan's DJI "
                    "file is then not written, which test_no_geoid_no_dji_file checks")


def _unpack(data: bytes):
    with zipfile.ZipFile(io.BytesIO(data)) as zf:
        assert sorted(zf.namelist()) == ["wpmz/template.kml", "wpmz/waylines.wpml"]
        assert zf.comment.startswith(b"scanplan ")
        return (DET.fromstring(zf.read("wpmz/template.kml")),
                DET.fromstring(zf.read("wpmz/waylines.wpml")))


def _text(el, path: str) -> str:
    found = el.find(path)
    assert found is not None, path
    return (found.text or "").strip()


def _placemarks(wayl):
    return wayl.findall(f"{K}Document/{K}Folder/{K}Placemark")


def _lonlat(pm) -> tuple[float, float]:
    lon, lat = _text(pm, f"{K}Point/{K}coordinates").split(",")
    return float(lon), float(lat)


def test_every_sortie_has_a_dji_route(example):
    name, _, files = example
    _needs_geoid(name)
    plans = sorted(k for k in files if k.endswith(".plan"))
    kmzs = sorted(_kmzs(files))
    assert len(kmzs) == len(plans) > 1
    assert kmzs == [p.replace("mission-", "mission-dji-").replace(".plan", ".kmz")
                    for p in plans]


def test_wpml_elements_and_enums(example):
    name, _, files = example
    _needs_geoid(name)
    for fname, data in _kmzs(files).items():
        tmpl, wayl = _unpack(data)
        for root in (tmpl, wayl):
            cfg = root.find(f"{K}Document/{W}missionConfig")
            for tag in MISSION_CONFIG:
                assert cfg.find(W + tag) is not None, (fname, tag)
            assert _text(cfg, f"{W}flyToWaylineMode") in {"safely", "pointToPoint"}
            assert _text(cfg, f"{W}finishAction") in {"goHome", "noAction", "autoLand",
                                                       "gotoFirstWaypoint"}
            assert _text(cfg, f"{W}exitOnRCLost") in {"goContinue", "executeLostAction"}
            assert _text(cfg, f"{W}executeRCLostAction") in {"goBack", "landing", "hover"}
            assert 2 <= float(_text(cfg, f"{W}takeOffSecurityHeight")) <= 1500
            assert 0 < float(_text(cfg, f"{W}globalTransitionalSpeed")) <= 15
            assert int(_text(cfg, f"{W}droneInfo/{W}droneEnumValue")) in DRONE_ENUMS
            assert int(_text(cfg, f"{W}payloadInfo/{W}payloadEnumValue")) in PAYLOAD_ENUMS
            assert (int(_text(cfg, f"{W}droneInfo/{W}droneEnumValue")),
                    int(_text(cfg, f"{W}payloadInfo/{W}payloadEnumValue"))) == (89, 50)
            assert _text(cfg, f"{W}payloadInfo/{W}payloadPositionIndex") == "0"
        folder = wayl.find(f"{K}Document/{K}Folder")
        assert _text(folder, f"{W}templateId") == "0" and _text(folder, f"{W}waylineId") == "0"
        assert _text(folder, f"{W}executeHeightMode") == (
            "WGS84" if name == "uav-town-valley-2000" else "relativeToStartPoint")
        assert float(_text(folder, f"{W}autoFlightSpeed")) == 12
        pms = _placemarks(wayl)
        assert [int(_text(pm, f"{W}index")) for pm in pms] == list(range(len(pms)))
        ids = []
        for k, pm in enumerate(pms):
            lon, lat = _lonlat(pm)
            assert -180 <= lon <= 180 and -90 <= lat <= 90
            float(_text(pm, f"{W}executeHeight"))
            assert _text(pm, f"{W}waypointHeadingParam/{W}waypointHeadingMode") == \
                "followWayline"
            assert _text(pm, f"{W}waypointTurnParam/{W}waypointTurnMode") in TURN_MODES
            for group in pm.findall(f"{W}actionGroup"):
                ids.append(int(_text(group, f"{W}actionGroupId")))
                start = int(_text(group, f"{W}actionGroupStartIndex"))
                end = int(_text(group, f"{W}actionGroupEndIndex"))
                assert start == k and start <= end < len(pms)
                assert _text(group, f"{W}actionGroupMode") == "sequence"
                trig = _text(group, f"{W}actionTrigger/{W}actionTriggerType")
                assert trig in TRIGGERS
                if trig == "multipleDistance":
                    assert float(_text(group, f"{W}actionTrigger/{W}actionTriggerParam")) > 0
        assert len(ids) == len(set(ids)), "action group ids are unique within the file"
        # the gimbal looks straight down from the first waypoint on
        first = pms[0].find(f"{W}actionGroup/{W}action/{W}actionActuatorFuncParam")
        assert _text(first, f"{W}gimbalPitchRotateAngle") == "-90"
        assert _text(first, f"{W}gimbalPitchRotateEnable") == "1"


def _fired(wayl) -> dict[int, list[tuple[tuple[float, float], tuple[float, float], int]]]:
    """Strip → (first photo lon/lat, last photo lon/lat, photos) of every takePhoto group,
    counted from the trigger: reachPoint one photo; multipleDistance one at the start and
    one every interval up to the group's end waypoint (its length on the ellipsoid)."""
    pms = _placemarks(wayl)
    out: dict[int, list] = {}
    for pm in pms:
        for group in pm.findall(f"{W}actionGroup"):
            funcs = [a.text for a in group.iter(f"{W}actionActuatorFunc")]
            if "takePhoto" not in funcs:
                continue
            strip = int(_text(group, f".//{W}fileSuffix").removeprefix("strip"))
            a = _lonlat(pms[int(_text(group, f"{W}actionGroupStartIndex"))])
            b = _lonlat(pms[int(_text(group, f"{W}actionGroupEndIndex"))])
            trig = _text(group, f"{W}actionTrigger/{W}actionTriggerType")
            if trig == "reachPoint":
                n = 1
            else:
                d = float(_text(group, f"{W}actionTrigger/{W}actionTriggerParam"))
                _, _, length = GEOD.inv(a[0], a[1], b[0], b[1])
                n = math.floor(length / d) + 1
            out.setdefault(strip, []).append((a, b, n))
    return out


def test_route_fires_exactly_the_photos_of_photos_csv(example):
    name, _, files = example
    _needs_geoid(name)
    photos = pd.read_csv(io.BytesIO(files["photos.csv"]))
    fired: dict[int, list] = {}
    for data in _kmzs(files).values():
        for strip, runs in _fired(_unpack(data)[1]).items():
            fired.setdefault(strip, []).extend(runs)  # a battery may end mid-strip
    per_strip = photos.groupby("strip").size().to_dict()
    assert {s: sum(n for *_, n in runs) for s, runs in fired.items()} == per_strip
    assert sum(per_strip.values()) == len(photos)
    for strip, runs in fired.items():  # every run starts and ends on a photo centre
        mine = photos[photos.strip == strip]
        for a, b, _ in runs:
            for lon, lat in (a, b):
                _, _, d = GEOD.inv(np.full(len(mine), lon), np.full(len(mine), lat),
                                   mine.lon_deg.to_numpy(), mine.lat_deg.to_numpy())
                assert float(np.min(d)) < 0.02, (strip, lon, lat)


@functools.cache
def _grid():
    import rasterio

    grid = next((g for g in wpml_mod._SYSTEM_GRIDS if os.path.isfile(g)), None)
    if grid is None:
        return None
    with rasterio.open(grid) as ds:
        return ~ds.transform, ds.read(1).astype(float)


def _geoid(lon: float, lat: float) -> float:
    """N of EGM96 read from the grid file itself by GDAL (rasterio) and interpolated
    bilinearly between its nodes, as PROJ does; else PROJ's own value."""
    if _grid() is None:
        return float(wpml_mod.egm96_separation_m(np.array([lon]), np.array([lat]))[0])
    inverse, data = _grid()
    col, row = inverse @ (lon, lat)  # fractional pixel; the nodes are pixel centres
    r0, c0 = math.floor(row - 0.5), math.floor(col - 0.5)
    fr, fc = row - 0.5 - r0, col - 0.5 - c0
    q = data[r0:r0 + 2, c0:c0 + 2]
    return float((q[0, 0] * (1 - fc) + q[0, 1] * fc) * (1 - fr)
                 + (q[1, 0] * (1 - fc) + q[1, 1] * fc) * fr)


def test_heights_relative_or_ellipsoidal(example):
    name, _, files = example
    _needs_geoid(name)
    from scipy.spatial import cKDTree

    photos = pd.read_csv(io.BytesIO(files["photos.csv"]))
    # the photo nearest a waypoint: looked up in a tree of the centres (longitudes scaled
    # to the block's latitude), its distance then taken on the ellipsoid (one geodesic per
    # waypoint, not one per waypoint and photo)
    east = np.cos(np.radians(float(photos.lat_deg.mean())))
    tree = cKDTree(np.c_[photos.lon_deg.to_numpy() * east, photos.lat_deg.to_numpy()])
    at_photos = 0  # waypoints on a photo centre (their height checked against it)
    for data in _kmzs(files).values():
        tmpl, wayl = _unpack(data)
        for pm in _placemarks(wayl):
            lon, lat = _lonlat(pm)
            h = float(_text(pm, f"{W}executeHeight"))
            near = photos.iloc[int(tree.query([lon * east, lat])[1])]
            _, _, d = GEOD.inv(lon, lat, float(near.lon_deg), float(near.lat_deg))
            if name == "uav-town-2000":  # flat: the planned height above the take-off
                assert h == pytest.approx(near.agl_m, abs=0.01)
            elif float(d) < 0.05:  # terrain: EGM96 altitude + the geoid (PROJ)
                at_photos += 1
                expected = near.altitude_m + _geoid(lon, lat)
                assert 5 < expected - near.altitude_m < 30  # EGM96 over central Russia
                assert h == pytest.approx(expected, abs=0.02)
        cfg = wayl.find(f"{K}Document/{W}missionConfig")
        rth = float(_text(cfg, f"{W}globalRTHHeight"))
        takeoff = float(_text(cfg, f"{W}takeOffSecurityHeight"))
        if name == "uav-town-2000":
            assert rth == takeoff == pytest.approx(float(photos.agl_m.iloc[0]), abs=0.1)
        else:  # home the sortie's first photo's ground; return above its highest waypoint
            assert rth >= takeoff
        sys_ = tmpl.find(f"{K}Document/{K}Folder/{W}waylineCoordinateSysParam")
        assert _text(sys_, f"{W}heightMode") == (
            "EGM96" if name == "uav-town-valley-2000" else "relativeToStartPoint")
        assert float(_text(sys_, f"{W}globalShootHeight")) == pytest.approx(
            float(photos.agl_m.median()), abs=0.01)
    if name != "uav-town-2000":
        assert at_photos > 100, at_photos  # the check above ran, on many waypoints


def test_template_is_the_mapping_of_the_area(example):
    import pyogrio
    import shapely

    name, folder, files = example
    _needs_geoid(name)
    kml = Path(folder) / "flight.kml"
    kml.write_bytes(files["flight.kml"])
    _, _, wkb, _ = pyogrio.raw.read(kml, layer=0)
    area = shapely.from_wkb(wkb[0])
    for data in _kmzs(files).values():
        tmpl, _ = _unpack(data)
        folder_el = tmpl.find(f"{K}Document/{K}Folder")
        assert _text(folder_el, f"{W}templateType") == "mapping2d"
        pm = folder_el.find(f"{K}Placemark")
        assert _text(pm, f"{W}shootType") in {"time", "distance"}
        assert 0 <= int(_text(pm, f"{W}direction")) <= 360
        int(_text(pm, f"{W}margin"))
        assert int(_text(pm, f"{W}overlap/{W}orthoCameraOverlapH")) == 80
        assert int(_text(pm, f"{W}overlap/{W}orthoCameraOverlapW")) == 70
        ring = _text(pm, f"{K}Polygon/{K}outerBoundaryIs/{K}LinearRing/{K}coordinates")
        poly = shapely.Polygon([tuple(map(float, c.split(",")[:2])) for c in ring.split()])
        assert poly.is_valid
        assert poly.symmetric_difference(area).area < 1e-6 * area.area


def test_djikmz_reads_the_routes(example):
    """djikmz models DJI's WPML with pydantic and validates every value it reads. It takes
    one action group per waypoint and an action group id no larger than its first
    waypoint (its own simplification, not the documentation's rule), so the groups are
    given to it as their trigger and actions."""
    import xmltodict  # djikmz's own XML reader (its dependency)
    from djikmz.model.action.action import Action
    from djikmz.model.action_group import ActionTrigger
    from djikmz.model.mission_config import MissionConfig
    from djikmz.model.waypoint import Waypoint

    name, _, files = example
    _needs_geoid(name)
    photos = 0
    for data in _kmzs(files).values():
        with zipfile.ZipFile(io.BytesIO(data)) as zf:
            doc = xmltodict.parse(zf.read("wpmz/waylines.wpml"),
                                  force_list=("Placemark", "wpml:actionGroup"))["kml"]["Document"]
        cfg = MissionConfig.from_dict(doc["wpml:missionConfig"])
        assert cfg.drone_info.drone_enum_value == 89
        assert cfg.payload_info.payload_model.value == 50  # Zenmuse P1
        for k, pm in enumerate(doc["Folder"]["Placemark"]):
            groups = pm.pop("wpml:actionGroup", [])
            wp = Waypoint.from_dict(pm)
            assert wp.waypoint_id == k
            for g in groups:
                trig = ActionTrigger.from_dict(g["wpml:actionTrigger"])
                action = Action.from_dict(g["wpml:action"])
                if str(action.action_type) == "takePhoto":
                    photos += 1
                    assert str(trig.type) in {"reachPoint", "multipleDistance"}
    assert photos > 0


def test_a_camera_dji_pilot_cannot_fly_gets_no_dji_file(tmp_path):
    """The mission for MAVLink ground stations is written; the terminal says why no DJI
    route is."""
    from click.testing import CliRunner

    from scanplan.cli.main import main

    text = (EXAMPLES / "uav-town-2000.toml").read_text().replace(
        'camera = "dji-zenmuse-p1-35"', 'camera = "canon-eos-5d-mark-ii-50"')
    assert "canon-eos-5d-mark-ii-50" in text
    (tmp_path / "areas").mkdir()
    shutil.copy(EXAMPLES / "areas" / "town-uav.kml", tmp_path / "areas")
    (tmp_path / "p.toml").write_text(text)
    res = CliRunner().invoke(main, ["plan", str(tmp_path / "p.toml"), "--out",
                                    str(tmp_path / "out"), "--formats", "missions,gis"])
    assert res.exit_code == 0, res.output  # the missions and GIS files: those looked at
    names = set(os.listdir(tmp_path / "out"))
    assert "flight.gpkg" in names and any(n.endswith(".plan") for n in names)
    assert not any(n.endswith(".kmz") for n in names)
    assert "no mission-dji.kmz: the camera 'canon-eos-5d-mark-ii-50' is not one DJI Pilot 2" \
        in res.output


def test_no_geoid_no_dji_file(monkeypatch):
    """Without PROJ's EGM96 grid a terrain plan gets no DJI route (its ellipsoidal heights
    would be wrong by the geoid's 10–20 m), and the reason says what to install."""
    from scanplan.reports import exports

    spec = plan_project(load_project(str(EXAMPLES / "uav-town-valley-2000.toml")))
    monkeypatch.setattr(wpml_mod, "egm96_separation_m", lambda lon, lat: None)
    notes: list[str] = []
    files = exports.export_files(spec, "", note=notes.append)
    assert not any(name.endswith(".kmz") for name in files)
    assert any(name.endswith(".plan") for name in files)  # the other missions are written
    assert len(notes) == 1 and notes[0].startswith("no mission-dji.kmz: ")
    assert "EGM96" in notes[0] and "proj-data" in notes[0]


def test_flight_gpkg_reads_back(example):
    import pyogrio

    _, folder, files = example
    path = Path(folder) / "flight.gpkg"
    path.write_bytes(files["flight.gpkg"])
    photos = pd.read_csv(io.BytesIO(files["photos.csv"]))
    layers = [str(n) for n, _ in pyogrio.list_layers(path)]
    assert layers == list(GPKG_LAYERS)
    info = pyogrio.read_info(path, layer="photos")
    assert info["features"] == len(photos)
    assert "32637" in info["crs"]
    assert info["dataset_metadata"]["GENERATOR"].startswith("scanplan ")
    meta, _, _, fields = pyogrio.raw.read(path, layer="photos")
    got = dict(zip(meta["fields"], fields, strict=True))
    assert list(got) == list(photos.columns)
    for col in photos.columns:
        np.testing.assert_allclose(np.asarray(got[col], float), photos[col].to_numpy(float),
                                   atol=10 ** -(2 if col in ("ground_m", "altitude_m",
                                                             "agl_m", "ground_min_m",
                                                             "ground_max_m",
                                                             "forward_overlap_pct",
                                                             "side_overlap_pct") else 3),
                                   equal_nan=True, err_msg=col)
    n_strips = pyogrio.read_info(path, layer="strips")["features"]
    assert n_strips == photos.strip.max()
    sorties = pyogrio.read_info(path, layer="sorties")["features"]
    assert sorties == photos.sortie.nunique()
    assert pyogrio.read_info(path, layer="area")["features"] == 1
    assert written_by_scanplan(path, format_named("gpkg"))
    if shutil.which("ogrinfo"):  # GDAL's own command, as QGIS users run it
        out = subprocess.run(["ogrinfo", "-ro", "-so", "-al", str(path)], capture_output=True,
                             text=True, check=True).stdout
        for layer in GPKG_LAYERS:
            assert f"Layer name: {layer}" in out
        assert f"Feature Count: {len(photos)}" in out


def test_own_files_are_recognised_and_stale_ones_removed(tmp_path, example):
    _, _, files = example
    kmz = next(iter(_kmzs(files).values()), None)
    if kmz is None:
        pytest.skip("no DJI file here (no EGM96 grid)")
    (tmp_path / "mission-dji-09.kmz").write_bytes(kmz)
    (tmp_path / "flight.gpkg").write_bytes(files["flight.gpkg"])
    buf = io.BytesIO()
    with zipfile.ZipFile(buf, "w") as zf:
        zf.writestr("wpmz/template.kml", "<kml/>")
    (tmp_path / "mission-dji-08.kmz").write_bytes(buf.getvalue())  # not ours: kept
    assert written_by_scanplan(tmp_path / "mission-dji-09.kmz", format_named("kmz"))
    assert not written_by_scanplan(tmp_path / "mission-dji-08.kmz", format_named("kmz"))
    assert stale_exports(str(tmp_path), set()) == [str(tmp_path / "flight.gpkg"),
                                                   str(tmp_path / "mission-dji-09.kmz")]


@settings(max_examples=25, deadline=None)
@given(width=st.floats(200.0, 3000.0), length=st.floats(200.0, 3000.0),
       spacing=st.floats(40.0, 300.0), base=st.floats(15.0, 400.0),
       sorties=st.integers(1, 3), notch=st.booleans(), parts=st.booleans())
def test_random_serpentines_fire_every_photo_once(width, length, spacing, base, sorties,
                                                  notch, parts):
    """Over random serpentines (split strips, parts of one photo when the base is long,
    several sorties): the WPML routes fire every photo of every strip exactly once, with
    no two consecutive waypoints at one place."""
    import sys

    sys.path.insert(0, str(Path(__file__).parent))
    from layouts import make_layout

    from scanplan.geo.export import MissionOptions

    layout = make_layout(width_m=width, length_m=length, spacing_m=spacing, base_m=base,
                         sorties=min(sorties, math.ceil(width / spacing)), notch=notch,
                         parts=parts)
    payload = wpml_mod.DJI_CAMERAS["dji-mavic-3e"]
    mission = wpml_mod.WpmlMission(
        payload=payload, speed_ms=9.0, height_mode="relativeToStartPoint",
        takeoff_height_m=120.0, rth_height_m=120.0, shoot_height_m=120.0,
        forward_overlap_pct=80.0, side_overlap_pct=70.0, direction_deg=0.0, margin_m=0.0,
        area_lonlat=[(0.0, 0.0), (1.0, 0.0), (1.0, 1.0)], area_height_m=120.0,
        area_ellipsoid_height_m=120.0)
    per_strip: dict[int, int] = {}
    for s in layout.sorties:
        if not s.strips:
            continue
        route = wpml_mod.sortie_route(layout, s.number, MissionOptions(speed_ms=9.0))
        for a, b in itertools.pairwise(route):
            assert GEOD.inv(a.lon_deg, a.lat_deg, b.lon_deg, b.lat_deg)[2] > 0.005
        wayl = DET.fromstring(wpml_mod.render_waylines(route, mission))
        for strip, runs in _fired(wayl).items():
            per_strip[strip] = per_strip.get(strip, 0) + sum(n for *_, n in runs)
    strips = np.asarray(layout.photos["strip"]).astype(int)
    assert per_strip == {int(k): int(v) for k, v in zip(*np.unique(strips, return_counts=True),
                                                         strict=True)}


def test_a_part_of_one_photo_fires_once_at_one_waypoint():
    """A strip whose last photographed part holds a single photo: that photo is one
    waypoint with a ``reachPoint`` photo (not two waypoints at one place)."""
    import dataclasses
    import sys

    sys.path.insert(0, str(Path(__file__).parent))
    from layouts import make_layout

    from scanplan.geo.export import MissionOptions
    from scanplan.geo.layout import Photos

    layout = make_layout(width_m=800.0, length_m=3000.0, spacing_m=150.0, base_m=400.0,
                         notch=True)
    strip = next(s for s in layout.strips if len(s.parts) == 2)
    (a, b), (c, d) = strip.parts
    ph = layout.photos
    x, y = np.asarray(ph["x_m"]), np.asarray(ph["y_m"])
    on_strip = np.asarray(ph["strip"]) == strip.number
    lo, hi = sorted((c[1], d[1]))
    in_part = on_strip & (y >= lo - 1e-6) & (y <= hi + 1e-6)
    keep_one = np.flatnonzero(in_part & (np.abs(y - c[1]) < 1e-6))
    drop = in_part.copy()
    drop[keep_one] = False
    photos = Photos({k: np.asarray(v)[~drop] for k, v in ph.columns.items()})
    strips = tuple(dataclasses.replace(s, parts=((a, b), (c, c)), photos=s.photos - int(
        drop.sum())) if s.number == strip.number else s for s in layout.strips)
    layout = dataclasses.replace(layout, photos=photos, strips=strips)
    route = wpml_mod.sortie_route(layout, 1, MissionOptions(speed_ms=9.0))
    mine = [p for p in route if p.strip == strip.number]
    assert mine and sum(p.photos for p in mine) == int(on_strip.sum() - drop.sum())
    for p, q in itertools.pairwise(route):
        assert GEOD.inv(p.lon_deg, p.lat_deg, q.lon_deg, q.lat_deg)[2] > 0.005
    assert sum(p.photos for p in route) == len(photos)
    assert x.size > len(photos)


def test_the_geopackage_is_the_same_bytes_for_the_same_plan(monkeypatch):
    """Its layers' timestamps are the build time (SOURCE_DATE_EPOCH), so a rerun of the same
    plan writes the same file and the output set stays one run's."""
    from scanplan.geo.export.gpkg import render_gpkg
    from scanplan.project.file import load_project
    from scanplan.project.spec import plan_project

    monkeypatch.setenv("SOURCE_DATE_EPOCH", "1700000000")
    layout = plan_project(load_project(EXAMPLES / "uav-town-2000.toml")).uav.job.layout
    first = render_gpkg(layout)
    import time

    time.sleep(1.1)
    assert render_gpkg(layout) == first


def test_the_geopackage_holds_the_take_off_point_when_one_is_given(tmp_path):
    import pyogrio

    from scanplan.geo.export.gpkg import render_gpkg
    from scanplan.project.file import load_project
    from scanplan.project.spec import plan_project

    src = (EXAMPLES / "uav-town-2000.toml").read_text(encoding="utf-8")
    src = src.replace('file = "areas/', f'file = "{(EXAMPLES / "areas").as_posix()}/')
    path = tmp_path / "p.toml"
    path.write_text(src + "\n[flight]\ntakeoff = [38.80, 55.09]\n", encoding="utf-8")
    layout = plan_project(load_project(path)).uav.job.layout
    gpkg = tmp_path / "flight.gpkg"
    gpkg.write_bytes(render_gpkg(layout))
    layers = [str(n) for n, _ in pyogrio.list_layers(gpkg)]
    assert layers[-1] == "takeoff" and set(layers) >= {"area", "strips", "photos", "sorties"}
    import shapely
    from pyogrio.raw import read

    _, _, geometry, _ = read(gpkg, layer="takeoff")
    pt = shapely.from_wkb(geometry[0])
    assert (pt.x, pt.y) == pytest.approx(layout.notes["takeoff_xy_m"])

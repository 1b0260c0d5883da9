"""The missions fly what photos.csv promises: a distance-trigger simulator over the files.

The simulator is written from ArduPilot's camera backend, not from scanplan: the aircraft
flies the written waypoints (read back from the .plan JSON and with pymavlink from the
.waypoints) along geodesics at the plan's ground speed; a DO command acts at the first
50 Hz step at or past the waypoint before it; DO_SET_CAM_TRIGG_DIST sets the distance and,
with param3 = 1, takes an image at once; at every step an image is taken when the
ellipsoidal distance from the last image reaches the distance — so each image is up to one
step late and the lateness adds up (flown at the plan's speed, and 1.3 % and 3.1 % faster,
which changes the lateness per image). Every exposure is matched to its nearest planned photo
centre; every strip must get as many exposures as photos.csv holds, one per planned photo,
and every distance-triggered spacing must keep the planned forward overlap within one
percentage point. Areas: the polygon examples, a Gauss–Krüger rectangle (k > 1), one in
the southern hemisphere and one across a UTM zone edge.
"""

from __future__ import annotations

import json
import math
import re
from collections import Counter
from pathlib import Path

import numpy as np
import pandas as pd
import pytest
from pyproj import Geod, Transformer
from scipy.spatial import cKDTree
from terrain_helpers import valley_pinned

from scanplan.project.file import load_project
from scanplan.project.spec import plan_project
from scanplan.reports.exports import export_files

ROOT = Path(__file__).resolve().parent.parent
EXAMPLES = ROOT / "examples"
GEOD = Geod(ellps="WGS84")
LOOP_HZ = 50.0


def simulate(items: list[dict], speed_ms: float, phase: float) -> list[tuple[float, float, bool]]:
    """Exposures (lon, lat, by distance?) of one mission's items flown at ``speed_ms``."""
    wps: list[tuple[float, float]] = []
    dos: list[list[list[float]]] = []
    for it in items:
        if it["command"] == 16:
            p = it["params"]
            wps.append((p[5], p[4]))
            dos.append([])
        elif it["command"] == 206:
            dos[-1].append(it["params"])
    step = speed_ms / LOOP_HZ
    shots: list[tuple[float, float, bool]] = []
    dist_m, last = 0.0, None
    t0 = phase * step  # where the first step falls on the first segment
    for k in range(len(wps) - 1):
        (lon0, lat0), (lon1, lat1) = wps[k], wps[k + 1]
        az, _, seg = GEOD.inv(lon0, lat0, lon1, lat1)
        s = np.arange(t0, seg, step) if seg > 0 else np.zeros(0)
        t0 = (s[-1] + step - seg) if len(s) else t0 - seg
        if not len(s):
            for cmd in dos[k]:  # reached within the step: acts at the next one
                dos[k + 1][:0] = [cmd]
            continue
        lon, lat, _ = GEOD.fwd(np.full(len(s), lon0), np.full(len(s), lat0),
                               np.full(len(s), az), s)
        for cmd in dos[k]:  # the waypoint reached at this segment's first step
            dist_m = cmd[0]
            if cmd[2] == 1:
                last = (lon[0], lat[0])
                shots.append((lon[0], lat[0], False))
        j = 0
        span = int(2 * dist_m / step) + 2 if dist_m > 0 else 0  # steps to the next shot, 2x
        while dist_m > 0 and last is not None and j < len(s):
            hit = _first_at(last, lon, lat, j, dist_m, span)
            if hit is None:
                break
            j = hit
            last = (lon[j], lat[j])
            shots.append((lon[j], lat[j], True))
            j += 1
    return shots


def _first_at(last: tuple[float, float], lon: np.ndarray, lat: np.ndarray, j: int,
              dist_m: float, span: int) -> int | None:
    """The first loop step from ``j`` on at ``dist_m`` or more from ``last`` (None: none
    on this segment). The steps are measured ``span`` at a time, nearest first: the same
    first step as measuring every step to the segment's end, without measuring the whole
    rest of a long strip again for each of its photos."""
    while j < len(lon):
        end = min(len(lon), j + span)
        _, _, d = GEOD.inv(np.full(end - j, last[0]), np.full(end - j, last[1]),
                           lon[j:end], lat[j:end])
        hit = np.flatnonzero(d >= dist_m)
        if len(hit):
            return j + int(hit[0])
        j = end
    return None


def _polygon_project(tmp: Path, name: str, ring: list[tuple[float, float]], extra: str = ""
                     ) -> Path:
    src = (EXAMPLES / "uav-town-2000.toml").read_text()
    src = src.replace('file = "areas/town-uav.kml"',
                      "polygon = " + json.dumps([list(p) for p in ring]) + "\n" + extra)
    path = tmp / f"{name}.toml"
    path.write_text(src)
    return path


def _rect(lon: float, lat: float, w_deg: float, h_deg: float) -> list[tuple[float, float]]:
    return [(lon, lat), (lon + w_deg, lat), (lon + w_deg, lat + h_deg), (lon, lat + h_deg),
            (lon, lat)]


def _projects(tmp: Path) -> list[Path]:
    return [
        EXAMPLES / "uav-town-2000.toml",
        # the valley at one altitude, and following the terrain (the example leaves the
        # mode to scanplan, which follows the terrain there)
        valley_pinned(tmp, "constant"),
        valley_pinned(tmp, "follow"),
        # Gauss–Krüger zone 7 (central meridian 39°E): k > 1 off the meridian
        _polygon_project(tmp, "gk", _rect(40.9, 55.70, 0.05, 0.03),
                         'plan_crs = "EPSG:28407"'),
        _polygon_project(tmp, "south", _rect(-47.95, -15.80, 0.04, 0.03)),
        _polygon_project(tmp, "zones", _rect(35.97, 55.70, 0.06, 0.02)),
        # a crosshatch: both passes, the pass transit between them, a sortie across it
        _crosshatched(_polygon_project(tmp, "crosshatch", _rect(37.2, 55.70, 0.02, 0.012))),
        # a crosshatch following the terrain: each strip at its own direction's ground
        _crosshatched(valley_pinned(tmp, "follow"), "valley-crosshatch"),
    ]


def _crosshatched(path: Path, name: str | None = None) -> Path:
    """The project ``path`` flown as a crosshatch (``[uav] crosshatch = true``)."""
    text = path.read_text(encoding="utf-8")
    out = path.with_name(f"{name or path.stem}.toml")
    out.write_text(text.replace("[uav]\n", "[uav]\ncrosshatch = true\n", 1), encoding="utf-8")
    return out


def _from_waypoints(path: Path) -> list[dict]:
    """The mission items of a ``.waypoints`` file as pymavlink reads it (the home left out),
    in the Plan file's shape."""
    mavwp = pytest.importorskip("pymavlink.mavwp")
    loader = mavwp.MAVWPLoader()
    n = loader.load(str(path))
    wps = [loader.wp(i) for i in range(1, n)]
    return [{"command": w.command, "params": [w.param1, w.param2, w.param3, w.param4,
                                                w.x, w.y, w.z]} for w in wps]


def _check(path: Path, tmp: Path) -> dict[str, float]:
    spec = plan_project(load_project(path))
    layout = spec.uav.layout
    out = tmp / path.stem
    out.mkdir()
    files = export_files(spec, str(out))
    for p, (_kind, data) in files.items():
        Path(p).write_bytes(data)
    photos = pd.read_csv(out / "photos.csv")
    assert len(photos) == len(layout.photos) > 0
    plans = sorted(out.glob("*.plan"))
    assert len(plans) == len(layout.sorties)
    tr = Transformer.from_crs(4326, layout.area.plan_crs, always_xy=True)
    tree = cKDTree(photos[["x_m", "y_m"]].to_numpy())
    matched: list[int] = []
    spacings: list[float] = []
    for k, plan in enumerate(plans):
        doc = json.loads(plan.read_text())
        items = doc["mission"]["items"]
        if k % 2:  # every other sortie as Mission Planner's file, read by pymavlink
            items = _from_waypoints(plan.with_suffix(".waypoints"))
        speed = next(i["params"][1] for i in items if i["command"] == 178)
        # the plan's speed, and a few percent faster as a real ground speed varies: the
        # lateness per image (a fraction of a loop step) then differs
        speed *= (1.0, 1.013, 1.031)[k % 3]
        shots = simulate(items, speed, phase=(k * 0.37) % 1.0)
        lon = np.array([s[0] for s in shots])
        lat = np.array([s[1] for s in shots])
        x, y = tr.transform(lon, lat)
        _, nearest = tree.query(np.column_stack([x, y]))
        if layout.crosshatch:  # the passes' centres cross: the sortie's photos in order
            mine = np.flatnonzero(photos["sortie"].to_numpy() == k + 1)
            assert len(shots) == len(mine), (path.name, plan.name)
            off = np.hypot(x - photos["x_m"].to_numpy()[mine],
                           y - photos["y_m"].to_numpy()[mine])
            assert np.all(off <= layout.base_m / 2.0), (plan.name, float(off.max()))
            nearest = mine
        matched += nearest.tolist()
        by_dist = np.array([s[2] for s in shots])
        _, _, d = GEOD.inv(lon[:-1], lat[:-1], lon[1:], lat[1:])
        spacings += d[by_dist[1:]].tolist()
    # one exposure per planned photo, so per strip as many as photos.csv holds
    assert sorted(matched) == list(range(len(photos))), path.name
    got = Counter(photos["strip"].to_numpy()[matched].tolist())
    assert got == Counter(photos["strip"].tolist())
    planned = 1.0 - layout.base_m / layout.footprint_along_m
    overlap = 1.0 - np.asarray(spacings) / layout.footprint_along_m
    assert np.all(np.abs(overlap - planned) <= 0.01), path.name
    directions = {round(layout.strip_direction_deg(int(k)), 6) for k in photos["strip"]}
    return {"photos": len(photos), "worst_pp": float(np.max(np.abs(overlap - planned)) * 100),
            "directions": len(directions)}


@pytest.mark.parametrize("which", range(8), ids=["town", "valley", "valley-follow",
                                                  "gauss-kruger", "southern", "zone-edge",
                                                  "crosshatch", "valley-crosshatch"])
def test_the_distance_trigger_fires_every_photo_of_photos_csv(tmp_path, which):
    path = _projects(tmp_path)[which]
    got = _check(path, tmp_path)
    if "crosshatch" in path.stem:  # both passes flown: strips in two directions
        assert got["directions"] == 2


def _path_m(items: list[dict], home: tuple[float, float] | None) -> float:
    """The geodesic length of the waypoints' path (from and back to ``home`` if given)."""
    pts = [(i["params"][5], i["params"][4]) for i in items if i["command"] == 16]
    if home is not None:
        pts = [home, *pts, home]
    lon, lat = np.array(pts).T
    return float(GEOD.line_length(lon, lat))


@pytest.mark.parametrize("turn", ["turnaround_m = 20", "turn_radius_m = 80",
                                  "turn_radius_m = 300", "bank_deg = 25"])
@pytest.mark.parametrize("takeoff", [False, True])
def test_the_mission_path_is_the_reported_flight_length(tmp_path, turn, takeoff):
    """Multirotor (turnaround) and fixed wing (turn radius, wide and omega turns; a bank
    angle): the written waypoints' path, transit included, is the reported length within
    1 %; a fixed wing's camera is armed only after a straight of one turn radius on the
    line. Without a take-off point each sortie takes off from the area's boundary point
    nearest its first strip (the Plan's home) and the way there and back is flown and
    counted all the same."""
    src = (EXAMPLES / "uav-town-2000.toml").read_text().replace(
        '"areas/', f'"{EXAMPLES}/areas/').replace("turnaround_m = 20", turn)
    if takeoff:
        src += "\n[flight]\ntakeoff = [38.805, 55.081]\n"
    path = tmp_path / "p.toml"
    path.write_text(src)
    spec = plan_project(load_project(path))
    layout = spec.uav.layout
    assert layout.feasible
    files = export_files(spec, str(tmp_path))
    plans = sorted((p, d) for p, (kind, d) in files.items() if kind.name == "plan")
    assert len(plans) == len(layout.sorties)
    total, radius = 0.0, layout.notes["turn_m"] if "radius" in layout.turn else 0.0
    for _name, data in plans:
        doc = json.loads(data)
        lat, lon, _ = doc["mission"]["plannedHomePosition"]
        items = doc["mission"]["items"]
        total += _path_m(items, (lon, lat))
        if radius:
            _armed_on_the_line(items, radius)
    assert total == pytest.approx(layout.flight_length_m, rel=0.01)
    assert layout.notes["transit_m"] > 0  # the return leg always
    assert sum(s.transit_m for s in layout.sorties) == pytest.approx(
        layout.notes["transit_m"])


def test_a_crosshatch_mission_path_is_the_reported_flight_length(tmp_path):
    """Both passes and the pass transit between them: the written waypoints' path is the
    reported length within 1 %, with the turnaround's run-in and run-out at the pass
    transit too."""
    path = _crosshatched(_polygon_project(tmp_path, "cross", _rect(37.2, 55.70, 0.02, 0.012)))
    spec = plan_project(load_project(path))
    layout = spec.uav.layout
    assert layout.crosshatch and layout.feasible and layout.notes["pass_transit_m"] > 0
    files = export_files(spec, str(tmp_path))
    plans = sorted((p, d) for p, (kind, d) in files.items() if kind.name == "plan")
    assert len(plans) == len(layout.sorties)
    total = 0.0
    for _name, data in plans:
        doc = json.loads(data)
        lat, lon, _ = doc["mission"]["plannedHomePosition"]
        total += _path_m(doc["mission"]["items"], (lon, lat))
    assert total == pytest.approx(layout.flight_length_m, rel=0.01)


def _armed_on_the_line(items: list[dict], radius_m: float) -> None:
    """Before every trigger-on waypoint the aircraft flies ≥ radius straight on the line."""
    wps, armed = [], []
    for it in items:
        if it["command"] == 16:
            wps.append((it["params"][5], it["params"][4]))
        elif it["command"] == 206 and it["params"][0] > 0:
            armed.append(len(wps) - 1)
    for k in armed:
        if k < 1 or k + 1 >= len(wps):
            continue
        az_in, _, d_in = GEOD.inv(*wps[k - 1], *wps[k])
        az_out, _, _ = GEOD.inv(*wps[k], *wps[k + 1])
        assert abs((az_in - az_out + 180) % 360 - 180) < 1.0  # on the line's heading
        straight = d_in
        j = k - 1
        while straight < radius_m * 0.999 and j >= 1:  # run-in: straight back to the turn
            az, _, d = GEOD.inv(*wps[j - 1], *wps[j])
            if abs((az - az_in + 180) % 360 - 180) >= 1.0:
                break
            straight += d
            j -= 1
        assert straight >= radius_m * 0.999


def test_a_ten_km_block_is_packed_within_ten_percent_of_the_bound(tmp_path):
    """10 × 10 km, the town's batteries: sorties cut strips where the battery ends (one
    10 km strip per sortie was 56 % of a battery); no packing beats the serpentine's length
    over one battery, every sortie fits its battery, and every sortie but the last is full
    within 10 % (the way back from the middle of a 10 km block is most of the rest)."""
    src = (EXAMPLES / "uav-town-2000.toml").read_text().replace(
        'file = "areas/town-uav.kml"', "width_m = 10000\nlength_m = 10000").replace(
        'direction_deg = "auto"\n', "")
    path = tmp_path / "block.toml"
    path.write_text(src)
    layout = plan_project(load_project(path)).uav.layout
    limit_s = layout.notes["max_flight_time_min"] * 60
    serpentine = sum(s.length_m for s in layout.strips) + layout.turn_length_m
    bound = math.ceil(serpentine / (limit_s * layout.speed_ms))
    assert layout.feasible and len(layout.strips) > 200
    assert bound <= len(layout.sorties)
    assert all(s.time_s <= limit_s + 1e-6 for s in layout.sorties)
    assert all(s.time_s >= 0.9 * limit_s for s in layout.sorties[:-1])
    assert sorted(set(layout.photos["sortie"].tolist())) == list(
        range(1, len(layout.sorties) + 1))


def test_exactly_fifty_percent_overlap_leaves_no_ground_without_stereo(tmp_path):
    """At exactly 50 % forward overlap the footprints of neighbouring photos only touch:
    the ground distance of the centres must not exceed the base anywhere. The layout puts
    them a base times the least scale factor of the area apart in the grid (UTM k = 0.9996
    near the central meridian: a grid base would be 0.04 % longer on the ground), and an
    extension photo whose footprint misses the area is not taken."""
    ring = _rect(38.95, 55.70, 0.05, 0.03)  # on UTM 37N's central meridian (39°E)
    path = _polygon_project(tmp_path, "fifty", ring)
    path.write_text(path.read_text().replace("forward_overlap_pct = 80",
                                             "forward_overlap_pct = 50"))
    layout = plan_project(load_project(path)).uav.layout
    assert layout.notes["grid_scale"] == pytest.approx(0.9996, abs=2e-5)
    ph = layout.photos
    worst = 0.0
    for s in layout.strips:
        mine = np.flatnonzero(ph["strip"] == s.number)
        order = mine[np.argsort(ph["index"][mine])]
        _, _, d = GEOD.inv(ph["lon_deg"][order[:-1]], ph["lat_deg"][order[:-1]],
                           ph["lon_deg"][order[1:]], ph["lat_deg"][order[1:]])
        worst = max(worst, float(np.max(d)) if len(d) else 0.0)
    assert worst <= layout.base_m * (1 + 1e-7)  # footprints 2·base long overlap or touch
    assert layout.footprint_along_m == pytest.approx(2 * layout.base_m)
    # at 50 % an extension photo's footprint ends where the part begins: none is taken
    src = path.read_text()
    path.write_text(src.replace("extension_bases = 1", "extension_bases = 0"))
    assert len(plan_project(load_project(path)).uav.layout.photos) == len(ph)
    path.write_text(src.replace("forward_overlap_pct = 50", "forward_overlap_pct = 80"))
    e1 = len(plan_project(load_project(path)).uav.layout.photos)
    path.write_text(src.replace("forward_overlap_pct = 50", "forward_overlap_pct = 80")
                    .replace("extension_bases = 1", "extension_bases = 0"))
    e0 = plan_project(load_project(path)).uav.layout
    assert e1 == len(e0.photos) + 2 * sum(s.segments for s in e0.strips)


# -------------------------------------------------------------------------------------------
# DJI routes: the WPML distance trigger over the route as written
# -------------------------------------------------------------------------------------------
def simulate_wpml(data: bytes) -> list[tuple[float, float, int]]:
    """Exposures (lon, lat, strip) of a DJI route as DJI's WPML documentation defines its
    triggers ("Common Elements", ``wpml:actionTrigger``): ``reachPoint`` fires once at its
    waypoint; ``multipleDistance`` fires at the group's start waypoint and every
    ``actionTriggerParam`` metres flown from there, up to its end waypoint. Flown along
    geodesics between the waypoints as written."""
    import io
    import zipfile

    import defusedxml.ElementTree as DET

    w, k = "{http://www.dji.com/wpmz/1.0.2}", "{http://www.opengis.net/kml/2.2}"
    with zipfile.ZipFile(io.BytesIO(data)) as zf:
        wayl = DET.fromstring(zf.read("wpmz/waylines.wpml"))
    pms = wayl.findall(f"{k}Document/{k}Folder/{k}Placemark")
    pts = [tuple(map(float, pm.find(f"{k}Point/{k}coordinates").text.split(",")))
           for pm in pms]
    shots: list[tuple[float, float, int]] = []
    for pm in pms:
        for group in pm.findall(f"{w}actionGroup"):
            if "takePhoto" not in [a.text for a in group.iter(f"{w}actionActuatorFunc")]:
                continue
            strip = int(group.find(f".//{w}fileSuffix").text.removeprefix("strip"))
            a = int(group.find(f"{w}actionGroupStartIndex").text)
            b = int(group.find(f"{w}actionGroupEndIndex").text)
            trig = group.find(f"{w}actionTrigger/{w}actionTriggerType").text
            if trig == "reachPoint":
                shots.append((*pts[a], strip))
                continue
            step = float(group.find(f"{w}actionTrigger/{w}actionTriggerParam").text)
            flown = 0.0  # along the path from the group's start
            due = 0.0
            for j in range(a, b):
                (lon0, lat0), (lon1, lat1) = pts[j], pts[j + 1]
                az, _, seg = GEOD.inv(lon0, lat0, lon1, lat1)
                while due <= flown + seg + 1e-9:
                    lon, lat, _ = GEOD.fwd(lon0, lat0, az, due - flown)
                    shots.append((lon, lat, strip))
                    due += step
                flown += seg
    return shots


@pytest.mark.parametrize("which", range(8), ids=["town", "valley", "valley-follow",
                                                  "gauss-kruger", "southern", "zone-edge",
                                                  "crosshatch", "valley-crosshatch"])
def test_the_dji_route_fires_every_photo_of_photos_csv(tmp_path, which):
    """Every DJI route of the sorties fires each photo of photos.csv once (matched to its
    nearest centre within 5 cm), strip by strip; the runs are flown through (no stopping
    waypoint but the route's first and last)."""
    from scanplan.geo.export import wpml as wpml_mod

    path = _projects(tmp_path)[which]
    spec = plan_project(load_project(path))
    layout = spec.uav.layout
    if layout.notes.get("altitude_frame") and wpml_mod.egm96_separation_m(
            np.array([37.0]), np.array([55.0])) is None:
        pytest.skip("PROJ has no EGM96 grid here: no DJI route for a terrain plan")
    out = tmp_path / path.stem
    out.mkdir()
    files = export_files(spec, str(out))
    kmzs = sorted(p for p in files if p.endswith(".kmz"))
    assert len(kmzs) == len(layout.sorties)
    photos = pd.read_csv(io_bytes(files, "photos.csv"))
    tr = Transformer.from_crs(4326, layout.area.plan_crs, always_xy=True)
    tree = cKDTree(photos[["x_m", "y_m"]].to_numpy())
    matched: list[int] = []
    strips: list[int] = []
    for name in kmzs:
        data = files[name][1]
        shots = simulate_wpml(data)
        x, y = tr.transform([s[0] for s in shots], [s[1] for s in shots])
        dist, nearest = tree.query(np.column_stack([x, y]))
        assert np.all(dist < 0.05), (name, float(np.max(dist)))
        matched += nearest.tolist()
        strips += [s[2] for s in shots]
        modes = re.findall(rb"<wpml:waypointTurnMode>(\w+)<", _waylines(data))
        assert modes[0] == modes[-1] == b"toPointAndStopWithDiscontinuityCurvature"
        assert set(modes[1:-1]) <= {b"toPointAndPassWithContinuityCurvature"}, name
    assert sorted(matched) == list(range(len(photos))), path.name
    assert Counter(strips) == Counter(photos["strip"].tolist())
    assert Counter(photos["strip"].to_numpy()[matched].tolist()) == Counter(strips)


def io_bytes(files: dict, name: str):
    import io

    return io.BytesIO(next(d for p, (_k, d) in files.items() if Path(p).name == name))


def _waylines(data: bytes) -> bytes:
    import io
    import zipfile

    with zipfile.ZipFile(io.BytesIO(data)) as zf:
        return zf.read("wpmz/waylines.wpml")

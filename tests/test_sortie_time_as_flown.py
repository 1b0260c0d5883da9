"""No sortie exceeds its battery when it is flown from its mission file (docs/flight-lines.md,
"The sortie time as flown").

The simulation here is written from the autopilots' documented behaviour, not from
scanplan.geo.sorties: the mission file is read back (the QGroundControl Plan's JSON, the DJI
route's WPML with defusedxml); the aircraft climbs from its take-off point (the Plan's
planned home) to the first waypoint's height, flies every waypoint along geodesics at the
mission's speed in small time steps — accelerating at ``a`` while no limit ahead needs it
to brake, braking at ``a`` for each limit ahead (a stop: 0; a corner of turn θ cut a
tangent length t before the waypoint: sqrt(a_c · t / tan(θ/2))) —, returns to the take-off
point, stops there and descends. ArduPilot cuts a corner within WPNAV_RADIUS; a DJI
waypoint flown through cuts it by its ``waypointTurnDampingDist`` and a ``toPointAndStop…``
waypoint is a stop. The numbers (``a``, ``a_c``, the radius, the climb and descent speeds)
are the flight model's of norms/catalogue/flight-model.csv, with their sources.

Every sortie of every UAV example — the polygon examples from their mission files, the
rectangles from the format-neutral mission (scanplan.geo.mission: they have no place on
the map for a file) — must fit the battery its layout was packed for, and its reported
time must not be shorter than the flight.
"""

from __future__ import annotations

import io
import json
import math
import re
import zipfile
from pathlib import Path

import defusedxml.ElementTree as DET
import numpy as np
import pytest
from pyproj import Geod

from scanplan.geo.mission import sortie_missions
from scanplan.norms.aircraft import flight_model_params
from scanplan.project.file import load_project
from scanplan.project.spec import plan_project
from scanplan.reports.exports import export_files

ROOT = Path(__file__).resolve().parent.parent
EXAMPLES = ROOT / "examples"
GEOD = Geod(ellps="WGS84")
W = "{http://www.dji.com/wpmz/1.0.2}"
K = "{http://www.opengis.net/kml/2.2}"
DT_S = 0.05
P = {k: p.value for k, p in flight_model_params().items()}


def fly_s(legs_m: np.ndarray, limits_ms: np.ndarray, speed_ms: float) -> float:
    """Time to fly the legs, stepping DT_S: the speed grows by a·dt while every limit
    ahead can still be met braking at a, and never exceeds the cruise speed."""
    a = P["horizontal_accel_ms2"]
    node_s = np.r_[0.0, np.cumsum(legs_m)]
    total = float(node_s[-1])
    s = v = t = 0.0
    while s < total - 1e-6:
        ahead = np.flatnonzero(node_s > s + 1e-9)
        # the highest speed from which every limit ahead is still met, from where this
        # step may end at the most
        reach = s + v * DT_S + a * DT_S ** 2 / 2
        room = np.sqrt(limits_ms[ahead] ** 2 + 2 * a * np.maximum(node_s[ahead] - reach, 0))
        cap = min(speed_ms, float(room.min()))
        v_new = min(v + a * DT_S, cap)
        if v_new < a * DT_S / 2:  # at a stop (or a reversal): go on from rest
            v_new = min(a * DT_S / 2, speed_ms)
        step = (v + v_new) / 2 * DT_S
        if s + step >= total:
            t += (total - s) / max((v + v_new) / 2, 1e-9)
            break
        s, v, t = s + step, v_new, t + DT_S
    return t


def _geodesic(lonlat: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Leg lengths [m] and the turn at each interior point [rad]."""
    lon, lat = lonlat[:, 0], lonlat[:, 1]
    az1, az2, d = GEOD.inv(lon[:-1], lat[:-1], lon[1:], lat[1:])
    az1, az2 = np.atleast_1d(az1), np.atleast_1d(az2)  # az2: the back azimuth at the end
    turn = np.radians(np.abs((az1[1:] - (az2[:-1] + 180.0) + 180.0) % 360.0 - 180.0))
    return np.atleast_1d(d).astype(float), turn


def _limits(legs: np.ndarray, turn: np.ndarray, tangent_m: np.ndarray, speed: float,
            stop: np.ndarray) -> np.ndarray:
    """Speed limit at every node: 0 at the ends and at stops, the corner's elsewhere."""
    t = np.minimum(np.minimum(tangent_m, legs[:-1] / 2), legs[1:] / 2)
    with np.errstate(divide="ignore", invalid="ignore"):
        corner = np.sqrt(P["corner_accel_ms2"] * t / np.tan(turn / 2))
    inner = np.where(turn > 1e-7, np.minimum(corner, speed), speed)
    inner = np.where(stop, 0.0, inner)
    return np.r_[0.0, inner, 0.0]


def _vertical_s(climb_m: float, descent_m: float) -> float:
    return max(climb_m, 0.0) / P["climb_speed_ms"] + max(descent_m, 0.0) / P["descent_speed_ms"]


def plan_sortie_s(doc: dict) -> float:
    """A QGroundControl Plan flown by ArduPilot: take-off at the home, the waypoints,
    return to launch."""
    m = doc["mission"]
    lat0, lon0, ground = m["plannedHomePosition"]
    items = m["items"]
    speed = next(i["params"][1] for i in items if i["command"] == 178)
    wps = [i for i in items if i["command"] == 16]
    rel = [(w["params"][6] - (ground if w["frame"] == 0 else 0.0)) for w in wps]
    pts = np.array([[lon0, lat0]] + [[w["params"][5], w["params"][4]] for w in wps]
                   + [[lon0, lat0]])
    legs, turn = _geodesic(pts)
    keep = legs > 1e-6
    if not keep.all():  # a waypoint at the home: one node
        pts = np.vstack([pts[:1], pts[1:][keep]])
        legs, turn = _geodesic(pts)
    limits = _limits(legs, turn, np.full(len(turn), P["corner_radius_m"]), speed,
                     np.zeros(len(turn), bool))
    return fly_s(legs, limits, speed) + _vertical_s(rel[0], rel[-1])


def kmz_sortie_s(data: bytes, home_lonlat: tuple[float, float], climb_m: float,
                 descent_m: float) -> tuple[float, list[str]]:
    """A DJI route: from the take-off point to the first waypoint, every waypoint with the
    turn mode written (a stop, or flown through cutting the corner by its damping
    distance), back to the take-off point; and the turn modes."""
    with zipfile.ZipFile(io.BytesIO(data)) as zf:
        wayl = DET.fromstring(zf.read("wpmz/waylines.wpml"))
    folder = wayl.find(f"{K}Document/{K}Folder")
    speed = float(folder.find(f"{W}autoFlightSpeed").text)
    pts, modes, damping = [], [], []
    for pm in folder.findall(f"{K}Placemark"):
        lon, lat = map(float, pm.find(f"{K}Point/{K}coordinates").text.split(","))
        pts.append((lon, lat))
        mode = pm.find(f"{W}waypointTurnParam/{W}waypointTurnMode").text
        modes.append(mode)
        d = pm.find(f"{W}waypointTurnParam/{W}waypointTurnDampingDist")
        damping.append(float(d.text) if d is not None else 0.0)
    lonlat = np.array([home_lonlat, *pts, home_lonlat])
    legs, turn = _geodesic(lonlat)
    stop = np.array([m.startswith("toPointAndStop") for m in modes])
    limits = _limits(legs, turn, np.array(damping), speed, stop)
    return fly_s(legs, limits, speed) + _vertical_s(climb_m, descent_m), modes


def _projects() -> list[Path]:
    return sorted(EXAMPLES.glob("*.toml"))


@pytest.mark.parametrize("path", [p for p in _projects()
                                  if "[uav]" in p.read_text(encoding="utf-8")],
                         ids=lambda p: p.stem)
def test_no_sortie_exceeds_its_battery_as_flown(path, tmp_path):
    spec = plan_project(load_project(path))
    layout = spec.uav.layout
    if layout is None or not layout.speed_ms:
        pytest.skip("no flight layout")
    if "sortie_overhead_s" not in layout.notes:
        pytest.skip("a manned survey aircraft: its sorties are its length at the speed")
    limit_s = (layout.notes.get("max_flight_time_min") or math.inf) * 60.0
    reported = {s.number: s.time_s for s in layout.sorties}
    flown: dict[int, float] = {}
    if layout.area.georeferenced:  # from the mission files, as a crew loads them
        files = {Path(p).name: data for p, (_k, data) in export_files(spec, str(tmp_path))
                 .items()}
        plans = sorted(n for n in files if re.fullmatch(r"mission(-\d+)?\.plan", n))
        assert len(plans) == len(layout.sorties)
        for k, name in enumerate(plans, start=1):
            doc = json.loads(files[name])
            flown[k] = plan_sortie_s(doc)
            kmz = name.replace("mission", "mission-dji").replace(".plan", ".kmz")
            if kmz in files:
                m = doc["mission"]
                lat0, lon0, ground = m["plannedHomePosition"]
                wps = [i for i in m["items"] if i["command"] == 16]
                rel = [w["params"][6] - (ground if w["frame"] == 0 else 0.0) for w in wps]
                dji_s, modes = kmz_sortie_s(files[kmz], (lon0, lat0), rel[0], rel[-1])
                flown[k] = max(flown[k], dji_s)
                # flown through: a stop only where the route starts and ends
                assert all(md == "toPointAndPassWithContinuityCurvature"
                           for md in modes[1:-1]), (kmz, set(modes[1:-1]))
    else:  # a block with no place on the map: its format-neutral mission, in the plane
        for m in sortie_missions(layout, layout.speed_ms):
            xy = np.array([m.home_xy_m, *[(p.x_m, p.y_m) for p in m.points], m.home_xy_m])
            d = np.diff(xy, axis=0)
            xy = xy[np.r_[True, np.hypot(d[:, 0], d[:, 1]) > 1e-6]]  # one node per place
            d = np.diff(xy, axis=0)
            legs = np.hypot(d[:, 0], d[:, 1])
            h = np.arctan2(d[:, 0], d[:, 1])
            turn = np.abs((h[1:] - h[:-1] + np.pi) % (2 * np.pi) - np.pi)
            limits = _limits(legs, turn, np.full(len(turn), P["corner_radius_m"]),
                             layout.speed_ms, np.zeros(len(turn), bool))
            # the mission's altitudes above the ground of its first photo (a ground range
            # without a DEM: above the lowest ground, the photos' height above ground)
            alt = np.asarray(layout.photos["altitude_m"], float)
            ground = np.asarray(layout.photos["ground_m"], float)
            agl = np.asarray(layout.photos["agl_m"], float)
            first, last = m.points[0].photo, m.points[-1].photo
            up = alt[first] - ground[first] if np.isfinite(ground[first]) else agl[first]
            down = alt[last] - ground[first] if np.isfinite(ground[first]) else agl[last]
            flown[m.number] = fly_s(legs, limits, layout.speed_ms) + _vertical_s(up, down)
    assert flown
    for k, t in flown.items():
        assert t <= limit_s * 1.001, (path.stem, k, t, limit_s)
        assert t <= reported[k] * 1.001, (path.stem, k, t, reported[k])


def test_the_simulation_reproduces_the_trapezoid():
    """The stepping simulation against the closed form: 100 m from rest to rest at 10 m/s
    and 2.5 m/s² take 100/10 + 10/2.5 = 14 s; through a limit of 10 m/s, 10 s more per
    100 m."""
    assert fly_s(np.array([100.0]), np.array([0.0, 0.0]), 10.0) == pytest.approx(14.0, abs=0.1)
    assert fly_s(np.array([100.0, 100.0]), np.array([0.0, 10.0, 0.0]), 10.0) == \
        pytest.approx(24.0, abs=0.1)

"""The mission a crew flies: a QGroundControl Plan file (``.plan``) per sortie.

Format: QGroundControl Developer Guide, "Plan File Format" (JSON; ``fileType`` "Plan",
``version`` 1; ``mission`` version 2 with ``firmwareType``, ``vehicleType``,
``cruiseSpeed``, ``hoverSpeed``, ``plannedHomePosition`` [lat, lon, alt AMSL] and
``items``; ``geoFence`` and ``rallyPoints`` version 2), mission items as ``SimpleItem``:
``command`` (MAV_CMD), ``frame`` (MAV_FRAME), ``params`` (seven values, NaN written as
``null``), ``autoContinue``, ``doJumpId``. Commands and frames: MAVLink common message set
(https://mavlink.io/en/messages/common.html). QGroundControl opens it; Mission Planner
reads only its simple items and gets the same mission as a waypoint file (:mod:`.wpl`).

Each sortie is one mission, rendered from the format-neutral
:class:`~scanplan.geo.mission.SortieMission` (its waypoints, trigger points and turns)::

    NAV_TAKEOFF (22)                 climb at the planned home (the take-off point)
    DO_CHANGE_SPEED (178)            the planned ground speed
    for each strip of the sortie (whole or in part):
        NAV_WAYPOINT (16)            run-in (a turnaround or a fixed wing's turn radius)
        for each run of photos:
            NAV_WAYPOINT (16)            the run's first photo centre
            DO_SET_CAM_TRIGG_DIST (206)  its ground base, one image at once
            NAV_WAYPOINT (16)            the run's last photo centre
            NAV_WAYPOINT (16)            half a base on
            DO_SET_CAM_TRIGG_DIST (206)  distance 0: trigger off
        NAV_WAYPOINT (16) …          the run-out and the turn to the next strip
    NAV_RETURN_TO_LAUNCH (20)

A DO command acts once the aircraft has reached the NAV waypoint before it: the camera
fires from the first photo centre of a run to half a base past its last one, never in a
turn (:mod:`scanplan.geo.mission` states the trigger behaviour relied on). The planned
home is the sortie's take-off point: ``[flight] takeoff``, else the area's boundary point
nearest the sortie's run-in (:mod:`scanplan.geo.sorties`; the sortie's time counts the way
there and back), else — a block with no place on the map — its first waypoint.

Altitudes: one per waypoint (:func:`waypoint_altitudes`, or given). The frame is stated on
every item: MAV_FRAME_GLOBAL_RELATIVE_ALT (3, above the home) for flat ground,
MAV_FRAME_GLOBAL (0, above mean sea level) or MAV_FRAME_GLOBAL_TERRAIN_ALT (10, above the
terrain under each waypoint) when the ground is known.
"""

from __future__ import annotations

import json
import math
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any, Literal

import numpy as np

from ...progress import stage
from ..layout import FlightLayout
from ..mission import MissionPoint, SortieMission, sortie_missions
from .common import GENERATOR, LonLat, lonlat

__all__ = ["FIRMWARE", "FRAMES", "MAV_CMD", "VEHICLE", "MissionOptions", "plan_files",
           "render_mission", "render_plan", "waypoint_altitudes"]

#: MAV_CMD numbers used (MAVLink common.xml).
MAV_CMD = {
    "NAV_WAYPOINT": 16,
    "NAV_RETURN_TO_LAUNCH": 20,
    "NAV_TAKEOFF": 22,
    "DO_CHANGE_SPEED": 178,
    "DO_SET_CAM_TRIGG_DIST": 206,
}
#: Altitude frame → (MAV_FRAME of the waypoints, QGroundControl's AltitudeMode).
#: MAV_FRAME: 0 GLOBAL (AMSL), 3 GLOBAL_RELATIVE_ALT (above home), 10 GLOBAL_TERRAIN_ALT.
#: QGroundControl AltitudeMode: 1 relative, 2 absolute, 4 terrain frame.
FRAMES: dict[str, tuple[int, int]] = {"relative": (3, 1), "amsl": (0, 2), "terrain": (10, 4)}
MAV_FRAME_MISSION = 2  # a command without a position (DO_*, RTL)
#: Autopilot family → MAV_AUTOPILOT (the plan's firmwareType).
FIRMWARE = {"generic": 0, "ardupilot": 3, "px4": 12}
#: Aircraft → MAV_TYPE (the plan's vehicleType).
VEHICLE = {"fixed_wing": 1, "multirotor": 2, "vtol": 22}
_SPEED_GROUND = 1  # DO_CHANGE_SPEED param1: 0 airspeed, 1 ground speed


@dataclass(frozen=True)
class MissionOptions:
    """How the mission is flown (what the layout does not say).

    Attributes
    ----------
    speed_ms : float
        Ground speed along the strips [m/s] (the speed the motion blur was computed for).
    frame : {"relative", "amsl", "terrain"}
        Altitude frame of the waypoints (flat ground: ``"relative"``, above the home).
    firmware : {"ardupilot", "px4", "generic"}
        The autopilot (the plan's firmwareType).
    vehicle : {"multirotor", "fixed_wing", "vtol"}
        The aircraft (the plan's vehicleType; a fixed wing takes off with 15° pitch).
    home_lonlat : (float, float), optional
        The planned home (launch point), WGS 84 [°]; default: the sortie's first photo.
    home_ground_m : float, optional
        Ground elevation at the home [m], same height system as the layout's ``ground_m``;
        default: the ground under the sortie's first photo.
    """

    speed_ms: float
    frame: Literal["relative", "amsl", "terrain"] = "relative"
    firmware: Literal["ardupilot", "px4", "generic"] = "ardupilot"
    vehicle: Literal["multirotor", "fixed_wing", "vtol"] = "multirotor"
    home_lonlat: tuple[float, float] | None = None
    home_ground_m: float | None = None

    def __post_init__(self) -> None:
        if not (math.isfinite(self.speed_ms) and self.speed_ms > 0):
            raise ValueError(f"speed_ms must be a positive number (got {self.speed_ms!r})")
        for name, allowed in (("frame", FRAMES), ("firmware", FIRMWARE),
                              ("vehicle", VEHICLE)):
            if getattr(self, name) not in allowed:
                raise ValueError(f"{name} must be one of {', '.join(allowed)} "
                                 f"(got {getattr(self, name)!r})")


def waypoint_altitudes(layout: FlightLayout, frame: str, points: Sequence[MissionPoint],
                       home_ground_m: float) -> np.ndarray:
    """The altitude of each waypoint in ``frame`` [m]: that of its photo
    (:attr:`MissionPoint.photo`) — ``altitude_m`` (above mean sea level, ``"amsl"``),
    ``agl_m`` (``"terrain"``) or ``altitude_m - home_ground_m`` (``"relative"``). Flat
    ground: every waypoint at the planned height above the home."""
    ph = layout.photos
    i = np.array([p.photo for p in points], dtype=np.int64)
    if frame == "amsl":
        return np.asarray(ph["altitude_m"], float)[i]
    if frame == "terrain":
        return np.asarray(ph["agl_m"], float)[i]
    return np.asarray(ph["altitude_m"], float)[i] - home_ground_m


def _item(seq: int, command: str, frame: int, params: Sequence[float | None],
          altitude_mode: int | None = None) -> dict[str, Any]:
    clean = [None if p is None or (isinstance(p, float) and not math.isfinite(p))
             else (round(p, 8) if isinstance(p, float) else p) for p in params]
    item: dict[str, Any] = {}
    if altitude_mode is not None:  # as QGroundControl writes a positioned item
        item["AMSLAltAboveTerrain"] = None
        item["Altitude"] = clean[6]
        item["AltitudeMode"] = altitude_mode
    item.update({"autoContinue": True, "command": MAV_CMD[command], "doJumpId": seq,
                 "frame": frame, "params": clean, "type": "SimpleItem"})
    return item


def render_plan(layout: FlightLayout, sortie: int, options: MissionOptions, *,
                altitudes_m: Sequence[float] | None = None,
                geo: LonLat | None = None) -> bytes:
    """One sortie of ``layout`` as a QGroundControl Plan file.

    Parameters
    ----------
    layout : FlightLayout
        A georeferenced, feasible layout.
    sortie : int
        The sortie, from 1.
    options : MissionOptions
        Speed, altitude frame, autopilot, aircraft, home.
    altitudes_m : sequence of float, optional
        One altitude per waypoint of the sortie in ``options.frame`` [m] (the run-in, the
        first and last photo of each segment and the run-out of every strip, in flight
        order); default :func:`waypoint_altitudes` from the photo centres.
    geo : LonLat, optional
        The layout in WGS 84 (computed when not given).

    Returns
    -------
    bytes
        The ``.plan`` (UTF-8 JSON).
    """
    geo = geo if geo is not None else lonlat(layout)
    mission = next(iter(sortie_missions(layout, options.speed_ms, numbers={sortie})),
                   None)
    if mission is None:
        raise ValueError(f"sortie {sortie} has no photos")
    return render_mission(layout, mission, options, altitudes_m=altitudes_m, geo=geo)


def render_mission(layout: FlightLayout, mission: SortieMission, options: MissionOptions, *,
                   altitudes_m: Sequence[float] | None = None,
                   geo: LonLat | None = None) -> bytes:
    """One :class:`~scanplan.geo.mission.SortieMission` as a QGroundControl Plan file
    (parameters as :func:`render_plan`)."""
    geo = geo if geo is not None else lonlat(layout)
    points = mission.points
    home, home_ground = _home(layout, options, geo, mission)
    if altitudes_m is None:
        alts = waypoint_altitudes(layout, options.frame, points, home_ground)
    else:
        alts = np.asarray(altitudes_m, float)
        if alts.shape != (len(points),) or not np.all(np.isfinite(alts)):
            raise ValueError(f"altitudes_m must hold {len(points)} finite altitudes, one per "
                             f"waypoint of sortie {mission.number} (got shape {alts.shape})")
    takeoff_alt = float(alts[0])
    if options.frame == "terrain":  # the take-off climbs above the home, not the terrain
        takeoff_alt = float(waypoint_altitudes(layout, "relative", points, home_ground)[0])
    lonlats = geo.points(np.array([[p.x_m, p.y_m] for p in points]))
    items = _mission_items(options, points, lonlats, alts, home, takeoff_alt)
    return _plan_document(options, items, home, home_ground)


def _home(layout: FlightLayout, options: MissionOptions, geo: LonLat,
          mission: SortieMission) -> tuple[tuple[float, float], float]:
    """The planned home (lon, lat) [°] and its ground elevation [m]: the options' home,
    else the take-off point (the mission's first waypoint without one); its ground: the
    options', else the layout's take-off ground, else that of the sortie's first photo."""
    ph = layout.photos
    if options.home_lonlat is not None:
        home = options.home_lonlat
    else:
        home = tuple(geo.points(np.array([mission.home_xy_m]))[0])
    first = mission.points[0].photo
    ground = layout.notes.get("takeoff_ground_m")
    home_ground = (options.home_ground_m if options.home_ground_m is not None
                   else float(ground) if ground is not None and mission.takeoff_xy_m
                   else float(ph["ground_m"][first]))
    if not math.isfinite(home_ground):
        home_ground = 0.0
    return (float(home[0]), float(home[1])), home_ground


def _mission_items(options: MissionOptions,
                   points: Sequence[MissionPoint], lonlats: np.ndarray, alts: np.ndarray,
                   home: tuple[float, float], takeoff_alt: float) -> list[dict[str, Any]]:
    """The mission items: take-off at the home, the speed, every waypoint with the camera
    trigger switched on and off along the strips, return to launch."""
    frame, alt_mode = FRAMES[options.frame]
    takeoff_frame = 0 if options.frame == "amsl" else 3  # a take-off is never terrain-framed
    items: list[dict[str, Any]] = []

    def add(command: str, frame_: int, params: Sequence[float | None],
            mode: int | None = None) -> None:
        items.append(_item(len(items) + 1, command, frame_, params, mode))

    pitch = 15.0 if options.vehicle == "fixed_wing" else 0.0
    add("NAV_TAKEOFF", takeoff_frame, [pitch, 0.0, 0.0, None, home[1], home[0], takeoff_alt],
        2 if takeoff_frame == 0 else 1)
    add("DO_CHANGE_SPEED", MAV_FRAME_MISSION, [_SPEED_GROUND, float(options.speed_ms), -1.0,
                                               0.0, 0.0, 0.0, 0.0])
    for wp, (lon, lat), alt in zip(points, lonlats, alts, strict=True):
        add("NAV_WAYPOINT", frame, [0.0, 0.0, 0.0, None, float(lat), float(lon), float(alt)],
            alt_mode)
        if wp.role == "trigger_on":  # distance, shutter time (0: ignore), one image now
            add("DO_SET_CAM_TRIGG_DIST", MAV_FRAME_MISSION,
                [round(float(wp.trigger_m), 4), 0.0, 1.0, 0.0, 0.0, 0.0, 0.0])
        elif wp.role == "trigger_off":
            add("DO_SET_CAM_TRIGG_DIST", MAV_FRAME_MISSION,
                [0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0])
    add("NAV_RETURN_TO_LAUNCH", MAV_FRAME_MISSION, [0.0] * 7)
    return items


def _plan_document(options: MissionOptions, items: list[dict[str, Any]],
                   home: tuple[float, float], home_ground: float) -> bytes:
    """The ``.plan`` file around the mission items (UTF-8 JSON, QGroundControl format 1)."""
    doc = {
        "fileType": "Plan",
        "geoFence": {"circles": [], "polygons": [], "version": 2},
        "groundStation": GENERATOR,
        "mission": {
            "cruiseSpeed": float(options.speed_ms),
            "firmwareType": FIRMWARE[options.firmware],
            "globalPlanAltitudeMode": FRAMES[options.frame][1],
            "hoverSpeed": float(options.speed_ms),
            "items": items,
            "plannedHomePosition": [round(home[1], 8), round(home[0], 8),
                                    round(home_ground, 3)],
            "vehicleType": VEHICLE[options.vehicle],
            "version": 2,
        },
        "rallyPoints": {"points": [], "version": 2},
        "version": 1,
    }
    return (json.dumps(doc, indent=2, ensure_ascii=False, allow_nan=False) + "\n").encode()


def plan_files(layout: FlightLayout, options: MissionOptions, *, stem: str = "mission",
               geo: LonLat | None = None) -> dict[str, bytes]:
    """Every sortie's Plan file: ``mission.plan`` for one sortie, else ``mission-01.plan``,
    ``mission-02.plan`` … (numbered in flight order, zero-padded so they sort).

    Returns
    -------
    dict of str to bytes
        File name → content; empty for a layout that is not georeferenced or not feasible,
        and for one whose photo centres were not listed (too many to keep: without them
        the trigger points and altitudes are unknown).
    """
    if (not layout.area.georeferenced or not layout.feasible or not layout.sorties
            or len(layout.photos) == 0):
        return {}
    geo = geo if geo is not None else lonlat(layout)
    missions = sortie_missions(layout, options.speed_ms)
    if len(missions) == 1:
        return {f"{stem}.plan": render_mission(layout, missions[0], options, geo=geo)}
    width = max(2, len(str(len(layout.sorties))))
    files = {}
    with stage("QGroundControl missions", len(missions), "sorties") as step:
        for m in missions:
            files[f"{stem}-{m.number:0{width}d}.plan"] = render_mission(layout, m, options,
                                                                        geo=geo)
            step()
    return files

"""The mission a crew flies: a QGroundControl Plan file (``.plan``) per sortie.

Format: QGroundControl Developer Guide, "Plan File Format" (JSON; ``fileType`` "Plan",
``version`` 1; ``mission`` version 2 with ``firmwareType``, ``vehicleType``,
``cruiseSpeed``, ``hoverSpeed``, ``plannedHomePosition`` [lat, lon, alt AMSL] and
``items``; ``geoFence`` and ``rallyPoints`` version 2), mission items as ``SimpleItem``:
``command`` (MAV_CMD), ``frame`` (MAV_FRAME), ``params`` (seven values, NaN written as
``null``), ``autoContinue``, ``doJumpId``. Commands and frames: MAVLink common message set
(https://mavlink.io/en/messages/common.html). QGroundControl opens it; Mission Planner
reads only its simple items and gets the same mission as a waypoint file (:mod:`.wpl`).

Each sortie is one mission::

    NAV_TAKEOFF (22)                 climb at the planned home to the first strip's altitude
    DO_CHANGE_SPEED (178)            the planned ground speed
    for each strip, for each of its segments:
        NAV_WAYPOINT (16)            run-in: the strip's start (when before its first photo)
        NAV_WAYPOINT (16)            the segment's first photo centre
        DO_SET_CAM_TRIGG_DIST (206)  trigger every photo base, the first photo at once
        NAV_WAYPOINT (16)            the segment's last photo centre
        DO_SET_CAM_TRIGG_DIST (206)  distance 0: trigger off
        NAV_WAYPOINT (16)            run-out: the strip's end (when past its last photo)
    NAV_RETURN_TO_LAUNCH (20)

A DO command acts once the aircraft has reached the NAV waypoint before it, so the camera
triggers from the first photo centre to the last one of each segment and never in a turn.
The launch point is not known to scanplan: the planned home is put at the first photo of
the sortie (the crew moves it to the take-off site in the ground station; return-to-launch
goes to where the aircraft was armed).

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

from ..layout import FlightLayout
from .common import GENERATOR, LonLat, StripPhotos, lonlat, photos_by_strip

__all__ = ["FIRMWARE", "FRAMES", "MAV_CMD", "VEHICLE", "MissionOptions", "plan_files",
           "render_plan", "waypoint_altitudes"]

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


@dataclass(frozen=True)
class _Waypoint:
    x_m: float
    y_m: float
    photo: int | None  # position in the photo arrays (None: the strip's run-in/run-out)
    trigger: str | None  # "on" after it, "off" after it, or None


def _nearest(x: np.ndarray, y: np.ndarray, candidates: np.ndarray, xy: tuple[float, float]
             ) -> int:
    """The candidate photo nearest to ``xy`` (a position in the photo arrays)."""
    d = np.hypot(x[candidates] - xy[0], y[candidates] - xy[1])
    return int(candidates[int(np.argmin(d))])


def _strip_waypoints(layout: FlightLayout, number: int, sp: StripPhotos | None
                     ) -> list[_Waypoint]:
    """The waypoints of one strip in flight order, with the trigger changes.

    The photographed parts are the strip's ``parts`` (trigger-on and trigger-off points)
    when the layout gives them, else runs of photos (a gap over 1.5 bases splits a run).
    """
    strip = layout.strips[number - 1]
    start, end = strip.start_xy_m, strip.end_xy_m
    if sp is None or not len(sp.order):  # no photo on it: fly it, the camera off
        return [_Waypoint(*start, None, None), _Waypoint(*end, None, None)]
    x, y = layout.photos["x_m"], layout.photos["y_m"]
    if strip.parts:
        parts = [(tuple(map(float, a)), tuple(map(float, b))) for a, b in strip.parts]
    else:
        parts = [((float(x[sp.order[a]]), float(y[sp.order[a]])),
                  (float(x[sp.order[b]]), float(y[sp.order[b]]))) for a, b in sp.runs]
    wps: list[_Waypoint] = []
    if math.dist(parts[0][0], start) > 0.5:
        wps.append(_Waypoint(*start, None, None))
    for a, b in parts:
        wps.append(_Waypoint(*a, _nearest(x, y, sp.order, a), "on"))
        wps.append(_Waypoint(*b, _nearest(x, y, sp.order, b), "off"))
    if math.dist(parts[-1][1], end) > 0.5:
        wps.append(_Waypoint(*end, None, None))
    return wps


def waypoint_altitudes(layout: FlightLayout, frame: str, points: Sequence[_Waypoint],
                       strip_numbers: Sequence[int], home_ground_m: float) -> np.ndarray:
    """The altitude of each waypoint in ``frame`` [m].

    At a photo centre: its ``altitude_m`` (above mean sea level, ``"amsl"``), its
    ``agl_m`` (``"terrain"``) or ``altitude_m - home_ground_m`` (``"relative"``); at a
    run-in/run-out point the strip's altitude (``Strip.altitude_m``, else that of its
    nearest photo; a strip without photos: the nearest photo of the sortie). Flat ground:
    every waypoint at the planned height above the home.
    """
    ph = layout.photos
    alt, agl = np.asarray(ph["altitude_m"], float), np.asarray(ph["agl_m"], float)
    out = np.empty(len(points))
    for k, (wp, number) in enumerate(zip(points, strip_numbers, strict=True)):
        i = wp.photo
        if i is None:  # the nearest photo waypoint of the same strip, else of any strip
            near = ([p.photo for p, n in zip(points, strip_numbers, strict=True)
                     if n == number and p.photo is not None]
                    or [p.photo for p in points if p.photo is not None])
            i = min(near, key=lambda j: math.hypot(ph["x_m"][j] - wp.x_m,
                                                   ph["y_m"][j] - wp.y_m)) if near else None
        strip_alt = layout.strips[number - 1].altitude_m
        if i is None:
            raise ValueError(f"sortie of strip {number} has no photo to take altitudes from")
        absolute = strip_alt if (wp.photo is None and strip_alt is not None) else alt[i]
        if frame == "amsl":
            out[k] = absolute
        elif frame == "terrain":
            out[k] = agl[i] + (absolute - alt[i])
        else:
            out[k] = absolute - home_ground_m
    return out


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
    strip_numbers = layout.sorties[sortie - 1].strips
    if not strip_numbers:
        raise ValueError(f"sortie {sortie} has no strips")
    points, owners = _sortie_waypoints(layout, strip_numbers)
    home, home_ground = _home(layout, options, geo, points)
    if altitudes_m is None:
        alts = waypoint_altitudes(layout, options.frame, points, owners, home_ground)
    else:
        alts = np.asarray(altitudes_m, float)
        if alts.shape != (len(points),) or not np.all(np.isfinite(alts)):
            raise ValueError(f"altitudes_m must hold {len(points)} finite altitudes, one per "
                             f"waypoint of sortie {sortie} (got shape {alts.shape})")
    takeoff_alt = float(alts[0])
    if options.frame == "terrain":  # the take-off climbs above the home, not the terrain
        takeoff_alt = float(waypoint_altitudes(layout, "relative", points, owners,
                                               home_ground)[0])
    lonlats = geo.points(np.array([[p.x_m, p.y_m] for p in points]))
    items = _mission_items(layout, options, points, lonlats, alts, home, takeoff_alt)
    return _plan_document(options, items, home, home_ground)


def _sortie_waypoints(layout: FlightLayout, strip_numbers: Sequence[int]
                      ) -> tuple[list[_Waypoint], list[int]]:
    """The waypoints of a sortie's strips in flight order, and the strip of each."""
    by_strip = photos_by_strip(layout)
    points: list[_Waypoint] = []
    owners: list[int] = []
    for n in strip_numbers:
        wps = _strip_waypoints(layout, n, by_strip.get(n))
        points += wps
        owners += [n] * len(wps)
    return points, owners


def _home(layout: FlightLayout, options: MissionOptions, geo: LonLat,
          points: Sequence[_Waypoint]) -> tuple[tuple[float, float], float]:
    """The planned home (lon, lat) [°] and its ground elevation [m]: the options' home, else
    the sortie's first photo (else its first waypoint on ground 0)."""
    ph = layout.photos
    first_photo = next((p.photo for p in points if p.photo is not None), None)
    if options.home_lonlat is not None:
        home = options.home_lonlat
    elif first_photo is not None:
        home = (float(ph["lon_deg"][first_photo]), float(ph["lat_deg"][first_photo]))
    else:
        home = tuple(geo.points(np.array([[points[0].x_m, points[0].y_m]]))[0])
    home_ground = (options.home_ground_m if options.home_ground_m is not None
                   else float(ph["ground_m"][first_photo]) if first_photo is not None else 0.0)
    return home, home_ground


def _mission_items(layout: FlightLayout, options: MissionOptions,
                   points: Sequence[_Waypoint], lonlats: np.ndarray, alts: np.ndarray,
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
        if wp.trigger == "on":  # distance, shutter time (0: ignore), trigger once now
            add("DO_SET_CAM_TRIGG_DIST", MAV_FRAME_MISSION,
                [float(layout.base_m), 0.0, 1.0, 0.0, 0.0, 0.0, 0.0])
        elif wp.trigger == "off":
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
    flown = [s for s in layout.sorties if s.strips]
    if len(flown) == 1:
        return {f"{stem}.plan": render_plan(layout, flown[0].number, options, geo=geo)}
    width = max(2, len(str(len(layout.sorties))))
    return {f"{stem}-{s.number:0{width}d}.plan": render_plan(layout, s.number, options, geo=geo)
            for s in flown}

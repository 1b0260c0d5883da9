"""The mission for DJI Pilot 2 and FlightHub 2: a WPML route file (``.kmz``) per sortie.

Format: DJI Cloud API documentation, "DJI WPML" (WayPoint Markup Language, namespace
``http://www.dji.com/wpmz/1.0.2``): a ZIP archive holding ``wpmz/template.kml`` (the
template: here ``mapping2d`` — the area polygon, overlaps, direction, margin, shooting
height — so DJI Pilot 2 can regenerate a route itself) and ``wpmz/waylines.wpml`` (the
route the aircraft executes: waypoints, heights, speeds, actions). Element names, enums
and required elements follow the documentation's pages "Template.kml", "Waylines.wpml"
and "Common Elements"; drone and payload enums its "Product Support" table and, for the
Zenmuse P1 (50) and L2 (84), DJI Payload SDK's ``E_DjiCameraType``.

The route (:func:`render_waylines`) is built from the sortie's ordered waypoints
(:class:`RoutePoint`) — the same ones the QGroundControl mission flies (:mod:`.qgc`):
the run-in, the first and the last photo of every photographed part, the run-out of every
strip. The first waypoint turns the gimbal to −90° (nadir). Each photographed part is an
action group from its first photo's waypoint to its last one with the trigger
``multipleDistance`` (a photo every ``interval`` metres from the group's start, the
specification's "same distance trigger") and the action ``takePhoto``; the interval is
the part's length on the ellipsoid divided by its photo count less one, written rounded
down to 0.1 mm, so the last photo falls on the part's last waypoint (at most a millimetre
before it, never past it) and the part fires exactly its photos of photos.csv. A
part of one photo fires once on arrival (``reachPoint``). The aircraft heads along the
route (``followWayline``).

**No needless stops.** A photographed part is one action group from its first photo to its
last, however long: DJI's distance trigger counts from the group's start, so it is not cut
into pieces for an autopilot's trigger lateness as the MAVLink missions are
(:mod:`scanplan.geo.mission`). A waypoint stands only where the path turns, the trigger
starts or ends, or the height changes (a point straight on at the same height with no
photo to end is left out). Every waypoint but the first and the last is flown through
without stopping: ``toPointAndPassWithContinuityCurvature`` ("fly in a curve and the
aircraft will not stop at the point") with ``useStraightLine`` 1 (the segments as straight
lines: DJI Pilot 2's "turns before waypoint, flies through"), its
``waypointTurnDampingDist`` — how far before the waypoint the turn begins, required for
that mode with ``useStraightLine`` 1, in (0, the segment's length] — 0.45 of the shorter
of its two segments (so two neighbours' turns never meet on a segment, as the
documentation requires) and at most :data:`MAX_DAMPING_M`; on a straight photo run the
turn angle is zero and the path stays on the line. The first and the last waypoint, where
the aircraft starts from and ends at rest, use ``toPointAndStopWithDiscontinuityCurvature``
("fly in a straight line and the aircraft stops at the point"). Enums and ranges: DJI
Cloud API, DJI WPML, "Common Elements", ``wpml:waypointTurnParam``
(developer.dji.com/doc/cloud-api-tutorial/en/api-reference/dji-wpml/common-element.html).

Heights: relative to the take-off point (``relativeToStartPoint``) for a flat plan;
WGS 84 ellipsoidal heights (``WGS84``) for a terrain plan: the photos' altitudes (the
DEM's height system, taken as EGM96 heights) plus the EGM96 geoid separation from PROJ
(:func:`egm96_separation_m`; the grid ``us_nga_egm96_15.tif`` or Debian's
``egm96_15.gtx`` of ``proj-data`` must be installed — without it no DJI file is written).
"""

from __future__ import annotations

import io
import math
import os
import zipfile
from collections.abc import Sequence
from dataclasses import dataclass, replace
from typing import Any, Literal
from xml.etree import ElementTree as ET

import numpy as np

from ...progress import stage
from ..layout import FlightLayout
from ..mission import SortieMission, sortie_missions
from .common import GENERATOR, LonLat, lonlat
from .qgc import MissionOptions, _home, waypoint_altitudes

__all__ = ["DJI_CAMERAS", "KML_NS", "PASS_THROUGH", "STOP", "WPML_NS", "DjiPayload",
           "RoutePoint", "WpmlMission", "damping_distances_m", "egm96_separation_m",
           "render_kmz", "render_template", "render_waylines", "segment_lengths_m",
           "sortie_route", "wpml_files"]

KML_NS = "http://www.opengis.net/kml/2.2"
WPML_NS = "http://www.dji.com/wpmz/1.0.2"
_W = "{" + WPML_NS + "}"
_K = "{" + KML_NS + "}"
ET.register_namespace("wpml", WPML_NS)

#: The largest ``wpml:globalTransitionalSpeed`` the format allows (Waylines.wpml: 0 … 15).
MAX_TRANSITIONAL_SPEED = 15.0
#: Turn modes written (DJI WPML "Common Elements", ``wpml:waypointTurnMode``): flown
#: through, and the stop at the route's first and last waypoint.
PASS_THROUGH = "toPointAndPassWithContinuityCurvature"
STOP = "toPointAndStopWithDiscontinuityCurvature"
#: The largest damping distance written [m]: the turn at a strip's end begins at most this
#: far before its corner.
MAX_DAMPING_M = 10.0
#: Share of the shorter neighbouring segment a waypoint's turn may take (two neighbours'
#: turns then never overlap: the documentation asks a segment to be longer than the sum
#: of the turn intercepts at its two ends).
DAMPING_SHARE = 0.45
#: The ZIP's fixed time stamp: the same plan gives the same bytes.
_ZIP_TIME = (2020, 1, 1, 0, 0, 0)


@dataclass(frozen=True)
class DjiPayload:
    """A DJI aircraft and camera as WPML names them.

    Attributes
    ----------
    drone_enum, drone_sub_enum : int
        ``wpml:droneEnumValue`` / ``wpml:droneSubEnumValue`` (Product Support table).
    payload_enum : int
        ``wpml:payloadEnumValue``.
    image_format : str
        ``wpml:imageFormat`` of the template's payload parameters (the lens stored).
    name : str
        The aircraft and camera, for messages and documents.
    """

    drone_enum: int
    drone_sub_enum: int
    payload_enum: int
    image_format: str
    name: str


#: Catalogue camera → the DJI aircraft that carries it. The Zenmuse P1 and L2 are gimbal
#: cameras of the Matrice 350 RTK (89) and 300 RTK (60): the newer M350 RTK is written;
#: an M300 RTK crew changes ``droneEnumValue`` to 60 (DJI Pilot 2 asks on import).
DJI_CAMERAS: dict[str, DjiPayload] = {
    "dji-zenmuse-p1-35": DjiPayload(89, 0, 50, "visible", "Matrice 350 RTK with Zenmuse P1"),
    "dji-zenmuse-l2-rgb": DjiPayload(89, 0, 84, "visible", "Matrice 350 RTK with Zenmuse L2"),
    "dji-mavic-3e": DjiPayload(77, 0, 66, "wide", "Mavic 3 Enterprise (M3E)"),
}


@dataclass(frozen=True)
class RoutePoint:
    """One waypoint of a sortie's route, in flight order.

    Attributes
    ----------
    lon_deg, lat_deg : float
        WGS 84 [°].
    height_m : float
        In the route's height mode (above the take-off point, or ellipsoidal) [m].
    strip : int
        The strip it belongs to.
    photos : int
        Photos fired from this waypoint to the next one (0: camera off on that leg; 1: one
        photo on arrival here; n > 1: n photos evenly from here to the next waypoint, the
        first here and the last there).
    """

    lon_deg: float
    lat_deg: float
    height_m: float
    strip: int
    photos: int = 0


@dataclass(frozen=True)
class WpmlMission:
    """What the route and the template say beside the waypoints.

    Attributes
    ----------
    payload : DjiPayload
    speed_ms : float
        Ground speed along the strips [m/s].
    height_mode : {"relativeToStartPoint", "WGS84"}
        How the waypoint heights are given.
    takeoff_height_m : float
        Safe take-off height above the take-off point [m] (2 … 1500): the first waypoint's.
    rth_height_m : float
        Return-to-home height above the take-off point [m]: the sortie's highest waypoint.
    shoot_height_m : float
        Planned height above the ground [m] (the template's shooting height).
    forward_overlap_pct, side_overlap_pct : float
        The layout's overlaps [%].
    direction_deg : float
        Flight-line direction, clockwise from true north [°], 0 … 360.
    margin_m : float
        The template's margin outside the area [m].
    area_lonlat : list of (lon, lat)
        The area's outer ring, WGS 84 [°].
    area_height_m : float
        The template's route height [m]: above the take-off point (flat), or EGM96 (terrain).
    area_ellipsoid_height_m : float
        The same height above the WGS 84 ellipsoid (terrain); a flat plan, whose take-off
        site's ellipsoidal height is unknown, repeats ``area_height_m`` [m].
    surface_follow : bool
        The plan follows the terrain (``altitude_mode = "follow"``): the template asks DJI
        Pilot 2 to follow the surface at ``shoot_height_m``
        (``wpml:surfaceFollowModeEnable`` 1, ``wpml:surfaceRelativeHeight``).
    """

    payload: DjiPayload
    speed_ms: float
    height_mode: Literal["relativeToStartPoint", "WGS84"]
    takeoff_height_m: float
    rth_height_m: float
    shoot_height_m: float
    forward_overlap_pct: float
    side_overlap_pct: float
    direction_deg: float
    margin_m: float
    area_lonlat: Sequence[tuple[float, float]]
    area_height_m: float
    area_ellipsoid_height_m: float
    surface_follow: bool = False


def _sub(parent: ET.Element, tag: str, text: Any = None, ns: str = _W) -> ET.Element:
    el = ET.SubElement(parent, ns + tag)
    if text is not None:
        el.text = _fmt(text)
    return el


def _fmt(value: Any) -> str:
    if isinstance(value, float):
        return f"{value:.8f}".rstrip("0").rstrip(".") if math.isfinite(value) else "0"
    return str(value)


def _mission_config(doc: ET.Element, m: WpmlMission) -> None:
    cfg = _sub(doc, "missionConfig")
    _sub(cfg, "flyToWaylineMode", "safely")
    _sub(cfg, "finishAction", "goHome")
    _sub(cfg, "exitOnRCLost", "executeLostAction")
    _sub(cfg, "executeRCLostAction", "goBack")
    _sub(cfg, "takeOffSecurityHeight", round(min(max(m.takeoff_height_m, 2.0), 1500.0), 1))
    _sub(cfg, "globalTransitionalSpeed", round(min(m.speed_ms, MAX_TRANSITIONAL_SPEED), 2))
    _sub(cfg, "globalRTHHeight", round(min(max(m.rth_height_m, 2.0), 1500.0), 1))
    drone = _sub(cfg, "droneInfo")
    _sub(drone, "droneEnumValue", m.payload.drone_enum)
    _sub(drone, "droneSubEnumValue", m.payload.drone_sub_enum)
    payload = _sub(cfg, "payloadInfo")
    _sub(payload, "payloadEnumValue", m.payload.payload_enum)
    _sub(payload, "payloadSubEnumValue", 0)
    _sub(payload, "payloadPositionIndex", 0)


def _document() -> tuple[ET.Element, ET.Element]:
    root = ET.Element(_K + "kml")
    return root, ET.SubElement(root, _K + "Document")


def _xml(root: ET.Element) -> bytes:
    ET.indent(root, space=" ")
    ET.register_namespace("wpml", WPML_NS)  # again: a library may have remapped the prefix
    # KML as the default namespace of this document only (not registered for the process,
    # where another writer's default, e.g. SVG's, would take it away)
    body = ET.tostring(root, encoding="unicode", default_namespace=KML_NS)
    return (f'<?xml version="1.0" encoding="UTF-8"?>\n<!-- {GENERATOR} -->\n{body}\n'
            ).encode()


def _action_group(pm: ET.Element, group_id: int, start: int, end: int, trigger: str,
                  param: float | None) -> ET.Element:
    group = _sub(pm, "actionGroup")
    _sub(group, "actionGroupId", group_id)
    _sub(group, "actionGroupStartIndex", start)
    _sub(group, "actionGroupEndIndex", end)
    _sub(group, "actionGroupMode", "sequence")
    trig = _sub(group, "actionTrigger")
    _sub(trig, "actionTriggerType", trigger)
    if param is not None:  # rounded down: n photos never need more than the part's length
        _sub(trig, "actionTriggerParam", math.floor(param * 1e4) / 1e4)
    return group


def _action(group: ET.Element, action_id: int, func: str) -> ET.Element:
    action = _sub(group, "action")
    _sub(action, "actionId", action_id)
    _sub(action, "actionActuatorFunc", func)
    return _sub(action, "actionActuatorFuncParam")


def _gimbal_nadir(group: ET.Element) -> None:
    p = _action(group, 0, "gimbalRotate")
    for tag, value in (("gimbalHeadingYawBase", "north"), ("gimbalRotateMode", "absoluteAngle"),
                       ("gimbalPitchRotateEnable", 1), ("gimbalPitchRotateAngle", -90),
                       ("gimbalRollRotateEnable", 0), ("gimbalRollRotateAngle", 0),
                       ("gimbalYawRotateEnable", 0), ("gimbalYawRotateAngle", 0),
                       ("gimbalRotateTimeEnable", 0), ("gimbalRotateTime", 0),
                       ("payloadPositionIndex", 0)):
        _sub(p, tag, value)


def _take_photo(group: ET.Element, action_id: int, suffix: str) -> None:
    p = _action(group, action_id, "takePhoto")
    _sub(p, "payloadPositionIndex", 0)
    _sub(p, "fileSuffix", suffix)
    _sub(p, "useGlobalPayloadLensIndex", 1)


def trigger_interval_m(a: RoutePoint, b: RoutePoint, photos: int) -> float:
    """The ``multipleDistance`` interval of a photographed part from ``a`` to ``b``: its
    length on the WGS 84 ellipsoid [m] over ``photos - 1`` (pyproj ``Geod.inv``)."""
    from pyproj import Geod

    # from the coordinates as written (8 decimals), so a reader measures the same length
    _, _, dist = Geod(ellps="WGS84").inv(round(a.lon_deg, 8), round(a.lat_deg, 8),
                                         round(b.lon_deg, 8), round(b.lat_deg, 8))
    return float(dist) / (photos - 1)


def segment_lengths_m(points: Sequence[RoutePoint]) -> np.ndarray:
    """The length of each segment between consecutive waypoints on the WGS 84 ellipsoid,
    from the coordinates as written (8 decimals) [m]."""
    from pyproj import Geod

    if len(points) < 2:
        return np.zeros(0)
    lon = np.round([p.lon_deg for p in points], 8)
    lat = np.round([p.lat_deg for p in points], 8)
    _, _, d = Geod(ellps="WGS84").inv(lon[:-1], lat[:-1], lon[1:], lat[1:])
    return np.asarray(d, dtype=float)


def damping_distances_m(points: Sequence[RoutePoint]) -> np.ndarray:
    """Each waypoint's ``waypointTurnDampingDist`` [m]: :data:`DAMPING_SHARE` of the
    shorter of its two segments, at most :data:`MAX_DAMPING_M` (0 at the first and the
    last waypoint, which are stops)."""
    n = len(points)
    out = np.zeros(n)
    if n < 3:
        return out
    seg = segment_lengths_m(points)
    out[1:-1] = np.minimum(DAMPING_SHARE * np.minimum(seg[:-1], seg[1:]), MAX_DAMPING_M)
    return out


def render_waylines(points: Sequence[RoutePoint], mission: WpmlMission) -> bytes:
    """The route of one sortie: ``wpmz/waylines.wpml``.

    Parameters
    ----------
    points : sequence of RoutePoint
        The sortie's waypoints in flight order (at most 65,536), each saying how many
        photos it fires up to the next one (:func:`sortie_route`).
    mission : WpmlMission
        Aircraft, speed, height mode, take-off height.

    Returns
    -------
    bytes
        UTF-8 XML.
    """
    if not points:
        raise ValueError("a route needs at least one waypoint")
    if len(points) > 65536:
        raise ValueError(f"{len(points)} waypoints; a WPML route holds at most 65,536")
    root, doc = _document()
    _mission_config(doc, mission)
    folder = ET.SubElement(doc, _K + "Folder")
    _sub(folder, "templateId", 0)
    _sub(folder, "executeHeightMode", mission.height_mode)
    _sub(folder, "waylineId", 0)
    _sub(folder, "autoFlightSpeed", round(mission.speed_ms, 2))
    group_id = 0
    damping = damping_distances_m(points)
    for k, p in enumerate(points):
        pm = ET.SubElement(folder, _K + "Placemark")
        pt = ET.SubElement(pm, _K + "Point")
        ET.SubElement(pt, _K + "coordinates").text = f"{p.lon_deg:.8f},{p.lat_deg:.8f}"
        _sub(pm, "index", k)
        _sub(pm, "executeHeight", round(p.height_m, 3))
        _sub(pm, "waypointSpeed", round(mission.speed_ms, 2))
        heading = _sub(pm, "waypointHeadingParam")
        _sub(heading, "waypointHeadingMode", "followWayline")
        turn = _sub(pm, "waypointTurnParam")
        if k == 0 or k == len(points) - 1 or not damping[k] > 0:
            _sub(turn, "waypointTurnMode", STOP)  # at rest: the start, the end
        else:  # flown through; the damping distance (0, segment] is then required
            _sub(turn, "waypointTurnMode", PASS_THROUGH)
            _sub(turn, "waypointTurnDampingDist", math.floor(damping[k] * 1000) / 1000)
        _sub(pm, "useStraightLine", 1)
        if k == 0:  # the camera looks straight down for the whole route
            _gimbal_nadir(_action_group(pm, group_id, 0, 0, "reachPoint", None))
            group_id += 1
        if p.photos == 1:
            group = _action_group(pm, group_id, k, k, "reachPoint", None)
            _take_photo(group, 0, f"strip{p.strip}")
            group_id += 1
        elif p.photos > 1:
            if k + 1 >= len(points):
                raise ValueError(f"waypoint {k} fires {p.photos} photos but is the last one")
            interval = trigger_interval_m(p, points[k + 1], p.photos)
            group = _action_group(pm, group_id, k, k + 1, "multipleDistance", interval)
            _take_photo(group, 0, f"strip{p.strip}")
            group_id += 1
    return _xml(root)


def render_template(mission: WpmlMission, *, created_ms: int = 0) -> bytes:
    """The mapping template: ``wpmz/template.kml`` (``mapping2d``).

    Parameters
    ----------
    mission : WpmlMission
        Area, overlaps, direction, margin, heights, aircraft.
    created_ms : int
        ``wpml:createTime`` / ``updateTime`` [ms since 1970] (0: not stated, the files
        then depend on the plan alone).

    Returns
    -------
    bytes
        UTF-8 XML.
    """
    root, doc = _document()
    _sub(doc, "author", GENERATOR)
    _sub(doc, "createTime", created_ms)
    _sub(doc, "updateTime", created_ms)
    _mission_config(doc, mission)
    folder = ET.SubElement(doc, _K + "Folder")
    _sub(folder, "templateType", "mapping2d")
    _sub(folder, "templateId", 0)
    sys_ = _sub(folder, "waylineCoordinateSysParam")
    _sub(sys_, "coordinateMode", "WGS84")
    _sub(sys_, "heightMode", "relativeToStartPoint" if mission.height_mode ==
         "relativeToStartPoint" else "EGM96")
    _sub(sys_, "globalShootHeight", round(mission.shoot_height_m, 2))
    # Template.kml, wpml:waylineCoordinateSysParam: surface following at a height above
    # the ground, as the plan's terrain following flies
    _sub(sys_, "surfaceFollowModeEnable", int(mission.surface_follow))
    if mission.surface_follow:
        _sub(sys_, "surfaceRelativeHeight", round(mission.shoot_height_m, 2))
    _sub(folder, "autoFlightSpeed", round(mission.speed_ms, 2))
    payload = _sub(folder, "payloadParam")
    _sub(payload, "payloadPositionIndex", 0)
    _sub(payload, "imageFormat", mission.payload.image_format)
    pm = ET.SubElement(folder, _K + "Placemark")
    _sub(pm, "caliFlightEnable", 0)
    _sub(pm, "elevationOptimizeEnable", 0)
    _sub(pm, "smartObliqueEnable", 0)
    _sub(pm, "shootType", "distance")
    _sub(pm, "direction", round(mission.direction_deg) % 360)
    _sub(pm, "margin", round(mission.margin_m))
    overlap = _sub(pm, "overlap")
    _sub(overlap, "orthoCameraOverlapH", round(mission.forward_overlap_pct))
    _sub(overlap, "orthoCameraOverlapW", round(mission.side_overlap_pct))
    _sub(pm, "ellipsoidHeight", round(mission.area_ellipsoid_height_m, 3))
    _sub(pm, "height", round(mission.area_height_m, 3))
    poly = ET.SubElement(pm, _K + "Polygon")
    ring = ET.SubElement(ET.SubElement(poly, _K + "outerBoundaryIs"), _K + "LinearRing")
    ET.SubElement(ring, _K + "coordinates").text = " ".join(
        f"{lon:.8f},{lat:.8f},0" for lon, lat in mission.area_lonlat)
    return _xml(root)


def render_kmz(points: Sequence[RoutePoint], mission: WpmlMission) -> bytes:
    """The WPML route file: a ZIP of ``wpmz/template.kml`` and ``wpmz/waylines.wpml``.

    The ZIP comment names scanplan (its mark: scanplan replaces its own files).
    """
    buf = io.BytesIO()
    with zipfile.ZipFile(buf, "w", zipfile.ZIP_DEFLATED) as zf:
        for name, data in (("wpmz/template.kml", render_template(mission)),
                           ("wpmz/waylines.wpml", render_waylines(points, mission))):
            info = zipfile.ZipInfo(name, date_time=_ZIP_TIME)
            info.compress_type = zipfile.ZIP_DEFLATED
            info.external_attr = 0o644 << 16
            zf.writestr(info, data)
        zf.comment = GENERATOR.encode()
    return buf.getvalue()


# --- from a layout -------------------------------------------------------------------

_GEOID: list[Any] = []


#: Where a system's PROJ keeps the EGM96 grid when pyproj's own data folder has none
#: (Debian and Ubuntu: package proj-data).
_SYSTEM_GRIDS = ("/usr/share/proj/us_nga_egm96_15.tif", "/usr/share/proj/egm96_15.gtx")


def _egm96_transformer() -> Any:
    """PROJ's EGM96 height → WGS 84 ellipsoidal height with the geoid grid, else None.

    First PROJ's own choice (EPSG:9707 → EPSG:4979) when its grid is in PROJ's search path;
    else the grid file of the system's PROJ data through a ``vgridshift`` pipeline
    (h = H + N). PROJ's "ballpark" operation (N taken as 0) is never used.
    """
    if _GEOID:
        return _GEOID[0]
    import warnings

    from pyproj import CRS, Transformer
    from pyproj.transformer import TransformerGroup

    found = None
    with warnings.catch_warnings():  # "best transformation is not available": we look on
        warnings.simplefilter("ignore")
        group = TransformerGroup(CRS.from_epsg(9707), CRS.from_epsg(4979), always_xy=True)
    for tr in group.transformers:
        if "ballpark" not in tr.description.lower() and (tr.accuracy or -1) >= 0:
            found = tr
            break
    for grid in _SYSTEM_GRIDS if found is None else ():
        if os.path.isfile(grid):
            found = Transformer.from_pipeline(
                "+proj=pipeline +step +proj=unitconvert +xy_in=deg +xy_out=rad "
                f"+step +proj=vgridshift +grids={grid} +multiplier=1 "
                "+step +proj=unitconvert +xy_in=rad +xy_out=deg")
            break
    _GEOID.append(found)
    return found


def egm96_separation_m(lon_deg: np.ndarray, lat_deg: np.ndarray) -> np.ndarray | None:
    """The EGM96 geoid's height above the WGS 84 ellipsoid (N) at each point [m], from
    PROJ (EPSG:9707 WGS 84 + EGM96 height → EPSG:4979); None when PROJ has no EGM96
    grid (``us_nga_egm96_15.tif``, or Debian ``proj-data``'s ``egm96_15.gtx``)."""
    tr = _egm96_transformer()
    if tr is None:
        return None
    lon = np.asarray(lon_deg, float)
    lat = np.asarray(lat_deg, float)
    _, _, h = tr.transform(lon, lat, np.zeros_like(lon))
    h = np.asarray(h, float)
    return h if np.all(np.isfinite(h)) else None


def sortie_route(layout: FlightLayout, sortie: int, options: MissionOptions, *,
                 geo: LonLat | None = None, geoid: bool = False,
                 missions: Sequence[SortieMission] | None = None) -> list[RoutePoint]:
    """The route of one sortie: the waypoints of its mission (:mod:`scanplan.geo.mission`,
    the same the QGroundControl and Mission Planner files fly: run-in, runs of photos,
    run-out, turns) with the photos each run fires and their heights for WPML.

    Parameters
    ----------
    layout : FlightLayout
        Georeferenced and feasible.
    sortie : int
        From 1.
    options : MissionOptions
        The mission's frame ("relative": heights above the home; "amsl": above sea level).
    geo : LonLat, optional
    geoid : bool
        Add the EGM96 separation (ellipsoidal heights, for ``"amsl"``).
    missions : sequence of SortieMission, optional
        Every sortie's mission at the options' speed (made here when not given; a caller
        that routes every sortie makes them once).

    Returns
    -------
    list of RoutePoint

    Raises
    ------
    ValueError
        When ``geoid`` is asked and PROJ has no EGM96 grid.
    """
    geo = geo if geo is not None else lonlat(layout)
    if missions is None:
        missions = sortie_missions(layout, options.speed_ms, numbers={sortie},
                                   loop_hz=math.inf)
    mission = next((m for m in missions if m.number == sortie), None)
    if mission is None:
        raise ValueError(f"sortie {sortie} has no photos")
    points = mission.points
    _, home_ground = _home(layout, options, geo, mission)
    frame = "amsl" if options.frame == "amsl" else "relative"
    heights = waypoint_altitudes(layout, frame, points, home_ground)
    lonlats = geo.points(np.array([[p.x_m, p.y_m] for p in points]))
    if geoid:
        n = egm96_separation_m(lonlats[:, 0], lonlats[:, 1])
        if n is None:
            raise ValueError("PROJ has no EGM96 geoid grid")
        heights = heights + n
    index = np.asarray(layout.photos["index"]).astype(np.int64)
    out = []
    for k, wp in enumerate(points):
        photos = 0
        if wp.role == "trigger_on":  # a run: its photos up to its last centre ("photo");
            # a run of one photo has none, its trigger is switched off next
            end = next(p for p in points[k + 1:] if p.role in ("photo", "trigger_off"))
            photos = int(index[end.photo] - index[wp.photo]) + 1 if end.role == "photo" else 1
        elif k and math.dist((wp.x_m, wp.y_m), (points[k - 1].x_m, points[k - 1].y_m)) < 0.01:
            continue  # the last photo of a one-photo part: the same place as its first
        out.append(RoutePoint(float(lonlats[k, 0]), float(lonlats[k, 1]), float(heights[k]),
                              int(wp.strip), photos))
    return _needed(out)


_STRAIGHT_DEG = 0.01
"""A waypoint whose path turns by less than this is straight on [°]."""


def _needed(points: list[RoutePoint]) -> list[RoutePoint]:
    """The route without the waypoints nothing happens at: straight on, at the height of
    both neighbours, firing no photos and ending no photographed part (the MAVLink
    missions' trigger-off points, which DJI's action groups do not need)."""
    from pyproj import Geod

    if len(points) < 3:
        return points
    geod = Geod(ellps="WGS84")
    keep = [points[0]]
    for k in range(1, len(points) - 1):
        a, p, b = keep[-1], points[k], points[k + 1]
        if p.photos or a.photos > 1:  # fires, or ends the part the one before starts
            keep.append(p)
            continue
        same_height = abs(p.height_m - a.height_m) < 0.01 and abs(p.height_m - b.height_m) < 0.01
        az1, _, d1 = geod.inv(a.lon_deg, a.lat_deg, p.lon_deg, p.lat_deg)
        az2, _, d2 = geod.inv(p.lon_deg, p.lat_deg, b.lon_deg, b.lat_deg)
        turn = abs((az2 - az1 + 180.0) % 360.0 - 180.0) if d1 > 0 and d2 > 0 else 0.0
        if not (same_height and turn < _STRAIGHT_DEG):
            keep.append(p)
    keep.append(points[-1])
    return keep


def _overlaps(layout: FlightLayout) -> tuple[float, float]:
    """Forward and side overlap of the layout [%]: 1 − base / footprint along,
    1 − spacing / footprint across."""
    fwd = 100.0 * (1.0 - layout.base_m / layout.footprint_along_m)
    side = 100.0 * (1.0 - layout.spacing_m / layout.footprint_across_m)
    return (fwd if math.isfinite(fwd) else 0.0, side if math.isfinite(side) else 0.0)


def _true_direction(layout: FlightLayout, geo: LonLat) -> float:
    """The first strip's azimuth from true north on the ellipsoid [°], 0 … 360."""
    from pyproj import Geod

    s = layout.strips[0]
    (lon1, lat1), (lon2, lat2) = geo.points(np.array([s.start_xy_m, s.end_xy_m]))
    az, _, _ = Geod(ellps="WGS84").inv(lon1, lat1, lon2, lat2)
    return float(az) % 360.0


def _outer_ring(geo: LonLat) -> list[tuple[float, float]]:
    """The area's outer ring (the largest polygon of a multi-part area) [°]."""
    area = geo.area
    polys = list(getattr(area, "geoms", [area]))
    largest = max(polys, key=lambda p: p.area)
    return [(float(x), float(y)) for x, y in largest.exterior.coords]


def wpml_files(layout: FlightLayout, options: MissionOptions, camera_id: str, *,
               stem: str = "mission-dji", geo: LonLat | None = None
               ) -> tuple[dict[str, bytes], str | None]:
    """Every sortie's WPML route file: ``mission-dji.kmz`` for one sortie, else
    ``mission-dji-01.kmz`` … (numbered in flight order like the Plan files).

    Parameters
    ----------
    layout : FlightLayout
        Georeferenced and feasible (terrain following: the mission's runs end at every
        altitude step, :mod:`scanplan.geo.mission`).
    options : MissionOptions
        Speed and height frame of the mission.
    camera_id : str
        The catalogue camera (:data:`DJI_CAMERAS` names those DJI Pilot 2 flies).

    Returns
    -------
    files : dict of str to bytes
        File name → content (empty when none is written).
    reason : str or None
        Why no file was written (a camera DJI Pilot 2 cannot fly, no EGM96 grid).
    """
    if (not layout.area.georeferenced or not layout.feasible or not layout.sorties
            or len(layout.photos) == 0):
        return {}, None
    payload = DJI_CAMERAS.get(camera_id)
    if payload is None:
        known = ", ".join(DJI_CAMERAS)
        return {}, (f"the camera {camera_id!r} is not one DJI Pilot 2 flies (a DJI route "
                    f"is written for {known})")
    geo = geo if geo is not None else lonlat(layout)
    terrain = options.frame == "amsl"
    if terrain and egm96_separation_m(np.array([0.0]), np.array([0.0])) is None:
        return {}, ("PROJ has no EGM96 geoid grid for the ellipsoidal heights of a terrain "
                    "plan (install the PROJ grid us_nga_egm96_15.tif, e.g. Debian's "
                    "proj-data)")
    flown = [s for s in layout.sorties if s.strips]
    width = max(2, len(str(len(layout.sorties))))
    common = {"payload": payload, "speed_ms": float(options.speed_ms),
              "height_mode": "WGS84" if terrain else "relativeToStartPoint",
              "shoot_height_m": float(np.nanmedian(np.asarray(layout.photos["agl_m"], float))),
              "direction_deg": _true_direction(layout, geo), "margin_m": 0.0,
              "area_lonlat": _outer_ring(geo),
              "surface_follow": layout.notes.get("altitude_mode") == "follow"}
    common["forward_overlap_pct"], common["side_overlap_pct"] = _overlaps(layout)
    files: dict[str, bytes] = {}
    # once: every route picks its own; DJI's distance trigger counts from each part's
    # start, so the parts are not cut for an autopilot loop's lateness (loop_hz = inf)
    missions = sortie_missions(layout, options.speed_ms, loop_hz=math.inf)
    with stage("DJI routes", len(flown), "sorties") as step:
        for s in flown:
            route = sortie_route(layout, s.number, options, geo=geo, geoid=terrain,
                                 missions=missions)
            # above the take-off point (the take-off height), and the template's EGM96 height
            relative = sortie_route(layout, s.number, replace(options, frame="relative"),
                                    geo=geo, missions=missions)
            amsl = (sortie_route(layout, s.number, options, geo=geo, missions=missions)
                    if terrain else relative)
            mission = WpmlMission(
                **common, takeoff_height_m=relative[0].height_m,
                rth_height_m=max(p.height_m for p in relative),
                area_height_m=float(np.median([p.height_m for p in amsl])),
                area_ellipsoid_height_m=float(np.median([p.height_m for p in route])))
            name = f"{stem}.kmz" if len(flown) == 1 else f"{stem}-{s.number:0{width}d}.kmz"
            files[name] = render_kmz(route, mission)
            step()
    return files, None

"""The mission for Mission Planner: a waypoint file (``QGC WPL 110``) beside each ``.plan``.

Mission Planner (ArduPilot's ground station) saves and loads missions as the text format
``QGC WPL 110`` (``.waypoints``): the header line, then one line per mission item, its
fields separated by tabs::

    index  current  frame  command  p1  p2  p3  p4  x/lat  y/lon  z/alt  autocontinue

Item 0 is the home (frame 0, its altitude above mean sea level); a line starting with ``#``
is a comment. Source: Mission Planner's reader ``WaypointFile.ReadWaypointFile``
(ArduPilot/MissionPlanner, ``ExtLibs/Utilities/MissionFile.cs``: the header must contain
"QGC WPL", lines starting with "#" are skipped, a first item whose index is not 0 gets a
blank home put before it, frame 3 is read as relative and 10 as terrain altitudes) and
pymavlink's ``MAVWPLoader._read_waypoints_v110`` (12 fields, ``#`` comments).

Mission Planner also opens a QGroundControl ``.plan`` (``MissionFile.ConvertToLocationwps``
in the same file), but only its ``SimpleItem``s — complex items are dropped — and, by
release, with the position from ``params[4..6]`` or from a ``coordinate`` member the Plan
format does not require. The waypoint file is the format it writes itself, and also what
MAVProxy and pymavlink load. It holds exactly the items of the ``.plan``: it is rendered
from that file's JSON (:func:`render_waypoints`), so commands, frames, parameters,
coordinates and altitudes cannot differ; a ``null`` parameter (QGroundControl's "unset",
the yaw of a waypoint) is written 0, as Mission Planner reads it.
"""

from __future__ import annotations

import json
import math
from collections.abc import Mapping
from typing import Any

from ...progress import stage
from .common import GENERATOR

__all__ = ["HEADER", "render_waypoints", "waypoint_files"]

HEADER = "QGC WPL 110"
"""The first line of the file (the format and its version)."""
_HOME_FRAME = 0  # MAV_FRAME_GLOBAL: the home's altitude is above mean sea level
_NAV_WAYPOINT = 16  # the home is written as a waypoint, as Mission Planner writes it


def _field(value: Any) -> str:
    """One number as the file writes it: an integer plainly, else up to 8 decimals (the
    ``.plan``'s own rounding), a missing value 0."""
    if value is None or (isinstance(value, float) and not math.isfinite(value)):
        return "0"
    if isinstance(value, bool):
        return "1" if value else "0"
    if isinstance(value, int):
        return str(value)
    text = f"{float(value):.8f}".rstrip("0").rstrip(".")
    return "0" if text in ("", "-0") else text


def render_waypoints(plan: bytes | str | Mapping[str, Any], note: str = "") -> bytes:
    """A QGroundControl Plan file's mission as a ``QGC WPL 110`` waypoint file.

    Parameters
    ----------
    plan : bytes, str or mapping
        The ``.plan`` (its JSON text, or the parsed document) of one sortie.
    note : str
        Said in the comment line after the header (e.g. the sortie).

    Returns
    -------
    bytes
        The file (ASCII, lines ending in CR LF as Mission Planner writes them).

    Examples
    --------
    >>> doc = {"mission": {"plannedHomePosition": [55.75, 37.62, 150.0], "items": [
    ...     {"command": 22, "frame": 3, "params": [0, 0, 0, None, 55.75, 37.62, 95.0],
    ...      "autoContinue": True},
    ...     {"command": 20, "frame": 2, "params": [0, 0, 0, 0, 0, 0, 0],
    ...      "autoContinue": True}]}}
    >>> for line in render_waypoints(doc).decode().splitlines():  # doctest: +ELLIPSIS
    ...     print(line.replace("\\t", " "))
    QGC WPL 110
    # scanplan ...
    0 1 0 16 0 0 0 0 55.75 37.62 150 1
    1 0 3 22 0 0 0 0 55.75 37.62 95 1
    2 0 2 20 0 0 0 0 0 0 0 1
    """
    doc = json.loads(plan) if isinstance(plan, bytes | str) else plan
    mission = doc["mission"]
    lat, lon, alt = mission["plannedHomePosition"]
    rows: list[list[Any]] = [[0, 1, _HOME_FRAME, _NAV_WAYPOINT, 0, 0, 0, 0, lat, lon, alt, 1]]
    for seq, item in enumerate(mission["items"], start=1):
        params = list(item["params"])
        if len(params) != 7 or item.get("type", "SimpleItem") != "SimpleItem":
            raise ValueError(f"mission item {seq} is not a simple item with seven params")
        rows.append([seq, 0, item["frame"], item["command"], *params,
                     1 if item.get("autoContinue", True) else 0])
    comment = f"# {GENERATOR}" + (f": {note}" if note else "")
    lines = [HEADER, comment, *("\t".join(_field(v) for v in row) for row in rows)]
    return ("\r\n".join(lines) + "\r\n").encode("ascii")


def waypoint_files(plans: Mapping[str, bytes]) -> dict[str, bytes]:
    """The waypoint file of every Plan file: ``mission.plan`` → ``mission.waypoints``,
    ``mission-01.plan`` → ``mission-01.waypoints`` …"""
    out = {}
    with stage("Mission Planner missions", len(plans), "sorties") as step:
        for name, data in plans.items():
            if name.endswith(".plan"):
                stem = name[: -len(".plan")]
                out[f"{stem}.waypoints"] = render_waypoints(data,
                                                            note=f"the mission of {name}")
            step()
    return out

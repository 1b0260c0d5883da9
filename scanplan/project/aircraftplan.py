"""What a plan says about its aircraft and its sorties (docs/aircraft.md).

After the UAV plan and the survey design, :func:`aircraft_warnings` states:

- an unknown sortie time (no aircraft, no ``max_flight_time_min``, no ``[schedule]``): the
  flight is then one flight of the whole block, which no battery flies — a warning, so it
  stands at the top of page 1 instead of "1 sortie of 94 days";
- where the sortie time comes from when the aircraft's battery sets it (information);
- a camera the catalogue does not list on the aircraft, a ground speed above the
  aircraft's maximum (warnings);
- the take-off point assumed when none is given (information: each sortie takes off from
  the area's boundary point nearest its first strip, :mod:`scanplan.geo.sorties`);
- a plan that needs more flying days than ``[flight] max_flying_days``: by the survey
  design's sun windows when it counts them, else at least the flight time and the ground
  time between sorties flown around the clock (a warning).
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

from ..i18n.messages import Message, PlanWarning
from ..norms.aircraft import aircraft, flight_model_params
from .inputs import by_key
from .sorties import SORTIE_DEFAULTS_MIN, sortie_length

if TYPE_CHECKING:
    from .model import ProjectModel
    from .results import SurveyDesign, UavSpec

__all__ = ["aircraft_warnings", "flying_days_needed"]


def flying_days_needed(project: ProjectModel, uav: UavSpec, design: SurveyDesign | None
                       ) -> tuple[int | None, bool]:
    """The flying days the UAV flight needs, and whether that is a lower bound.

    The survey design's count (its sun windows) when it has one; else the flight time and
    the ground time between sorties (``[schedule] turnaround_min`` or the platform's
    default) flown around the clock, rounded up: no crew flies faster.
    """
    sun = design.sun if design is not None else None
    if sun is not None and sun.days is not None and sun.days.days is not None:
        return int(sun.days.days), False
    layout = uav.job.layout
    if layout is None or not layout.flight_time_s:
        return None, True
    turn_min = (project.schedule.turnaround_min if project.schedule is not None
                and project.schedule.turnaround_min is not None
                else SORTIE_DEFAULTS_MIN["uav"][1])
    ground_s = max(len(layout.sorties) - 1, 0) * turn_min * 60.0
    return max(1, math.ceil((layout.flight_time_s + ground_s) / 86400.0)), True


def aircraft_warnings(project: ProjectModel, uav: UavSpec | None,
                      design: SurveyDesign | None = None) -> list[PlanWarning]:
    """The aircraft's and the sorties' warnings and notes of a UAV plan (see the module)."""
    if uav is None:
        return []
    out: list[PlanWarning] = []
    layout = uav.job.layout
    length = sortie_length(project, "uav")
    plan = uav.job.plan
    camera = project.uav.given.get("camera") if project.uav is not None else None
    cam = uav.job.norm_set.cameras.get(camera) if isinstance(camera, str) else None
    if getattr(cam, "carrier", "uav") == "aircraft":  # a manned survey: no battery
        return out
    if layout is not None and length.minutes is None and layout.flight_time_s:
        out.append(PlanWarning("sortie_time_unknown", Message(
            "sortie_time_unknown", hours=layout.flight_time_s / 3600.0)))
    if length.aircraft is not None:
        craft = aircraft(length.aircraft)
        if length.source == "aircraft" and craft.max_flight_time_min is not None:
            reserve = flight_model_params()["battery_reserve_pct"].value
            out.append(PlanWarning("aircraft_sortie", Message(
                "aircraft_sortie", minutes=length.minutes, name=craft.name,
                published=craft.max_flight_time_min,
                conditions=Message(f"flight_time.{craft.flight_time_basis or 'approximate'}"),
                reserve=reserve), severity="info"))
        if isinstance(camera, str) and craft.cameras and camera not in craft.cameras:
            out.append(PlanWarning("aircraft_camera_unlisted", Message(
                "aircraft_camera_unlisted", camera=camera, name=craft.name,
                cameras=", ".join(craft.cameras))))
        speed = plan.inputs.speed_ms
        if craft.max_speed_ms is not None and speed > craft.max_speed_ms:
            out.append(PlanWarning("aircraft_speed_above_max", Message(
                "aircraft_speed_above_max", speed=speed, name=craft.name,
                max=craft.max_speed_ms)))
    if (layout is not None and layout.area.georeferenced and project.flight.takeoff is None
            and any(s.takeoff_xy_m is not None for s in layout.sorties)):
        out.append(PlanWarning("takeoff_assumed", Message(
            "takeoff_assumed", km=sum(s.transit_m for s in layout.sorties) / 1000.0),
            severity="info"))
    days, bound = flying_days_needed(project, uav, design)
    most = (project.flight.max_flying_days if project.flight.max_flying_days is not None
            else by_key("flight", "max_flying_days").default)
    if days is not None and days > most:
        needed = Message("flying_days.at_least" if bound else "flying_days.by_schedule",
                         days=days)
        out.append(PlanWarning("flying_days_exceeded", Message(
            "flying_days_exceeded", needed=needed, most=most)))
    return out

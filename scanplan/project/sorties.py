"""One sortie length for the flight layout and the schedule.

A crew flies a block in sorties: one battery (or one tank) each. The flight layout splits
the strips into sorties (:func:`scanplan.geo.lines.plan_lines`, ``max_flight_time_min``) and
the survey design counts the flying days from the same sorties
(:func:`scanplan.project.design.survey_design`), so the crew reads one number of sorties
everywhere. The one length comes from the project file:

- ``[uav] max_flight_time_min``: the flight time of one sortie [min] — the aircraft's
  endurance on one battery less the crew's reserve;
- ``[schedule] sortie_time_min``: the same number, where the schedule is written; given
  alone it also splits the layout;
- both given: they must agree (else exit 2 naming both keys — two sortie lengths would
  give two sortie counts);
- neither: with ``[schedule]`` (the flying days are planned) the platform's default
  (:data:`SORTIE_DEFAULTS_MIN`: 25 min for a UAV battery, 180 min for a survey aircraft)
  splits the layout as well; without it the layout is one flight.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from ..errors import InputError
from .file import Project

__all__ = ["MAX_SORTIE_MIN", "SORTIE_DEFAULTS_MIN", "SortieLength", "sortie_length"]

SORTIE_DEFAULTS_MIN = {"uav": (25.0, 15.0), "aircraft": (180.0, 60.0)}
"""(sortie flight time, ground time between sorties) [min] when the project does not say:
a multirotor battery gives 25–40 min, a survey aircraft's fuel several hours."""
MAX_SORTIE_MIN = 24 * 60.0
"""Longest sortie [min] (one day)."""

_KEYS = (("uav", "max_flight_time_min"), ("schedule", "sortie_time_min"))


@dataclass(frozen=True)
class SortieLength:
    """The flight time of one sortie and where it comes from.

    Attributes
    ----------
    minutes : float or None
        Flight time of one sortie [min]; None: the layout is one flight (no ``[schedule]``
        and no key).
    source : {"uav", "schedule", "default", ""}
        ``[uav] max_flight_time_min``, ``[schedule] sortie_time_min``, the platform's
        default, or none.
    """

    minutes: float | None
    source: str


def sortie_length(project: Project, platform: str = "uav") -> SortieLength:
    """The one sortie length of ``project`` (see the module's rules).

    Parameters
    ----------
    project : Project
        The project file.
    platform : {"uav", "aircraft"}
        The carrier of the camera (its default sortie).

    Raises
    ------
    InputError
        Naming ``[schedule] sortie_time_min`` and ``[uav] max_flight_time_min`` (with
        their lines) when both are given and differ, or a key out of range.

    Examples
    --------
    >>> from scanplan.project.file import Project
    >>> p = Project("p.toml", "p", {"schedule": {"sortie_time_min": 30}})
    >>> sortie_length(p)
    SortieLength(minutes=30.0, source='schedule')
    >>> sortie_length(Project("p.toml", "p", {"uav": {}}))
    SortieLength(minutes=None, source='')
    """
    uav, schedule = (project.number(s, k, 0, MAX_SORTIE_MIN, None, "min", lo_open=True,
                                    meaning="a flight time") for s, k in _KEYS)
    if uav is not None and schedule is not None and not math.isclose(uav, schedule,
                                                                     rel_tol=1e-9):
        raise InputError(
            f"{project.path}: {project.where('schedule', 'sortie_time_min')}",
            f"is {schedule:g} min but {project.where('uav', 'max_flight_time_min')} is "
            f"{uav:g} min: both are the flight time of one sortie, which splits the flight "
            "layout and counts the flying days; give one of them (or the same number)")
    if uav is not None:
        return SortieLength(uav, "uav")
    if schedule is not None:
        return SortieLength(schedule, "schedule")
    if project.has("schedule"):
        default = SORTIE_DEFAULTS_MIN.get(platform, SORTIE_DEFAULTS_MIN["uav"])[0]
        return SortieLength(default, "default")
    return SortieLength(None, "")

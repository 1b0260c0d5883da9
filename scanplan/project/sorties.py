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
- neither: the aircraft's usable flight time — ``[uav] aircraft``, or the one catalogue
  aircraft that carries the camera (:mod:`scanplan.norms.aircraft`: the published flight
  time less the battery reserve of ``norms/catalogue/flight-model.csv``);
- none of them: with ``[schedule]`` (the flying days are planned) the platform's default
  (:data:`SORTIE_DEFAULTS_MIN`: 25 min for a UAV battery, 180 min for a survey aircraft)
  splits the layout as well; without it the layout is one flight, and the sortie time is
  said to be unknown (:func:`unknown_sortie_warning`).
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import lru_cache
from typing import TYPE_CHECKING, Any

from .inputs import PROJECT_DOMAINS

if TYPE_CHECKING:
    from .model import ProjectModel

__all__ = ["MAX_SORTIE_MIN", "SORTIE_DEFAULTS_MIN", "SortieLength", "project_aircraft",
           "sortie_length", "terrain_relief_m"]

RELIEF_SAMPLES = 96
"""The DEM is sampled on a grid of this many points a side over the area for its relief."""
RELIEF_MARGIN = 0.05
"""Added to a sampled relief (a grid can miss the highest and lowest ground) [share]."""

SORTIE_DEFAULTS_MIN = {"uav": (25.0, 15.0), "aircraft": (180.0, 60.0)}
"""(sortie flight time, ground time between sorties) [min] when the project does not say:
a multirotor battery gives 25–40 min, a survey aircraft's fuel several hours."""
MAX_SORTIE_MIN = PROJECT_DOMAINS["sortie_time_min"].hi
"""Longest sortie [min] (one day; the input registry's domain of both keys)."""


@dataclass(frozen=True)
class SortieLength:
    """The flight time of one sortie and where it comes from.

    Attributes
    ----------
    minutes : float or None
        Flight time of one sortie [min]; None: the layout is one flight (no ``[schedule]``
        and no key).
    source : {"uav", "schedule", "aircraft", "default", ""}
        ``[uav] max_flight_time_min``, ``[schedule] sortie_time_min``, the aircraft's
        usable flight time, the platform's default, or none.
    aircraft : str or None
        The catalogue aircraft of the project (given, or the camera's one carrier).
    """

    minutes: float | None
    source: str
    aircraft: str | None = None


def project_aircraft(model: ProjectModel) -> str | None:
    """The project's catalogue aircraft: ``[uav] aircraft``, else the one catalogue
    aircraft that carries ``[uav] camera`` (None: not given and none or several carry
    it)."""
    if model.flight.aircraft:
        return model.flight.aircraft
    camera = model.uav.given.get("camera") if model.uav is not None else None
    from ..norms.aircraft import carriers_of

    carriers = carriers_of(camera if isinstance(camera, str) else None)
    return carriers[0].id if len(carriers) == 1 else None


def sortie_length(model: ProjectModel, platform: str = "uav") -> SortieLength:
    """The one sortie length of a project (see the module's rules).

    Both keys were checked when the file was parsed (:func:`scanplan.project.model.
    build_model`: in range, and the same number when both are given).

    Parameters
    ----------
    model : ProjectModel
        The parsed project file.
    platform : {"uav", "aircraft"}
        The carrier of the camera (its default sortie).

    Examples
    --------
    >>> from scanplan.project.file import parse_project
    >>> from scanplan.project.model import build_model
    >>> head = "[map]\\nscale = 2000\\nrelief_interval_m = 1\\n[uav]\\n"
    >>> sortie_length(build_model(parse_project(head + "[schedule]\\nsortie_time_min = 30")))
    SortieLength(minutes=30.0, source='schedule', aircraft=None)
    >>> sortie_length(build_model(parse_project(head)))
    SortieLength(minutes=None, source='', aircraft=None)
    """
    uav = model.flight.max_flight_time_min
    schedule = model.schedule.sortie_time_min if model.schedule is not None else None
    craft = project_aircraft(model) if platform == "uav" else None
    if uav is not None:
        return SortieLength(uav, "uav", craft)
    if schedule is not None:
        return SortieLength(schedule, "schedule", craft)
    if craft is not None:
        from ..norms.aircraft import aircraft

        usable = aircraft(craft).usable_flight_time_min()
        if usable is not None:
            return SortieLength(usable, "aircraft", craft)
    if model.schedule is not None:
        default = SORTIE_DEFAULTS_MIN.get(platform, SORTIE_DEFAULTS_MIN["uav"])[0]
        return SortieLength(default, "default", craft)
    return SortieLength(None, "", craft)


def terrain_relief_m(model: ProjectModel, area: Any) -> float:
    """The ground's height range under the area [m] (0 without ``[terrain]``): what a
    sortie may climb and descend beyond its planned height above the ground between its
    take-off point and its altitude (:func:`scanplan.geo.lines.plan_lines`, ``climb_m``).

    ``ground_elevation_m`` when given; else the DEM sampled on a
    :data:`RELIEF_SAMPLES`-square grid over the area, plus :data:`RELIEF_MARGIN`.
    """
    terrain = model.terrain
    if terrain is None or area is None:
        return 0.0
    cfg = terrain.config
    if cfg.ground_range_m is not None:
        return float(cfg.ground_range_m[1] - cfg.ground_range_m[0])
    if cfg.dem is None or not str(cfg.dem) or not area.georeferenced:
        return 0.0
    from ..errors import InputError

    try:
        return _dem_relief_m(str(cfg.dem), cfg.vertical_unit, tuple(area.geometry.bounds),
                             area.plan_crs)
    except InputError:  # a DEM the terrain check refuses, naming the key and its line
        return 0.0


@lru_cache(maxsize=8)
def _dem_relief_m(dem: str, unit: str | None, bounds: tuple[float, ...], plan_crs: str
                  ) -> float:
    import numpy as np

    from ..geo.dem import open_dem, sample_dem, vertical_factor

    info = open_dem(dem)
    factor, _ = vertical_factor(info, unit)
    x0, y0, x1, y1 = bounds
    gx, gy = np.meshgrid(np.linspace(x0, x1, RELIEF_SAMPLES), np.linspace(y0, y1, RELIEF_SAMPLES))
    z = np.asarray(sample_dem(info, gx.ravel(), gy.ravel(), plan_crs, factor).elevation_m,
                   dtype=float)
    z = z[np.isfinite(z)]
    return float(np.ptp(z)) * (1.0 + RELIEF_MARGIN) if z.size else 0.0

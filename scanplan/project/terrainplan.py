"""``[terrain]`` in a project: the plan checked over the ground under every photo.

The project layer's bridge to :mod:`scanplan.geo.terrain`: reads the ``[terrain]`` keys,
resolves the DEM beside the project file, and gives the UAV specification its terrain
result — at the planned height, and, when the flat-ground recommendation fails over the
relief, at the largest height the worst photo allows (rounded down like every
recommended height). Film: the local photo scale of every frame of the flight scheme.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import replace
from pathlib import Path
from typing import Any

from ..errors import InputError
from ..geo.layout import FlightLayout
from ..geo.terrain import (
    FilmTerrain,
    Ground,
    TerrainConfig,
    TerrainResult,
    film_terrain,
    ground_under,
    uav_terrain,
)
from ..messages import Message
from ..rules.results import PlanWarning, ScanRules
from .api import UavJob, recommended_height_m
from .file import KEYS, Project

__all__ = ["TERRAIN_KEYS", "film_terrain_spec", "terrain_config", "uav_terrain_spec"]

TERRAIN_KEYS = KEYS["terrain"]
"""The ``[terrain]`` keys (defined with every project key in :mod:`.file`)."""

_MODE_NAMES = {
    "constant": {"en": '"constant"', "ru": "постоянной высоты"},
    "strip": {"en": '"strip"', "ru": "высоты по маршрутам"},
    "follow": {"en": '"follow"', "ru": "следования рельефу"},
}  # [terrain] altitude_mode, as the reports name it

_MAX_REFINE = 4  # re-layouts at a lower height before giving up


def terrain_config(project: Project) -> TerrainConfig | None:
    """The ``[terrain]`` section as a :class:`TerrainConfig` (None without it).

    Raises
    ------
    InputError
        Naming the key and its line.
    """
    if not project.has("terrain"):
        return None
    g = project.get
    dem = g("terrain", "dem")
    rng = g("terrain", "ground_elevation_m")
    try:
        return TerrainConfig(
            dem=(Path(dem) if Path(dem).is_absolute() else project.path.parent / dem)
            if dem is not None and dem.strip() else (Path("") if dem is not None else None),
            ground_range_m=(float(rng[0]), float(rng[1])) if rng is not None else None,
            altitude_mode=g("terrain", "altitude_mode", "constant"),
            follow_tolerance_m=float(g("terrain", "follow_tolerance_m", 5.0)),
            vertical_unit=g("terrain", "vertical_unit"))
    except InputError as exc:
        raise _named(project, exc) from None


def _named(project: Project, exc: InputError) -> InputError:
    """``terrain.dem`` → ``project.toml: terrain.dem (line 31)``."""
    field = exc.field
    if field.startswith("terrain.") or field == "terrain":
        section, _, key = field.partition(".")
        where = project.where(section, key) if key else f"[{section}]"
        return InputError(f"{project.path}: {where}", exc.message)
    return exc


def _ground(project: Project, cfg: TerrainConfig, layout: FlightLayout) -> Ground:
    if cfg.dem is not None and not layout.area.georeferenced:
        raise InputError(f"{project.path}: {project.where('terrain', 'dem')}",
                         "a DEM needs an area on the ground: give the area as a polygon or a "
                         "file ([area] file / polygon), or use ground_elevation_m = [min, max] "
                         "with the width_m × length_m block")
    try:
        return ground_under(layout, cfg)
    except InputError as exc:
        raise _named(project, exc) from None


def uav_terrain_spec(project: Project, cfg: TerrainConfig, job: UavJob,
                     planned_m: float | None, job_at: Callable[[float], UavJob]
                     ) -> tuple[UavJob, TerrainResult, float | None, Message | None,
                                tuple[PlanWarning, ...]]:
    """The UAV job over the terrain.

    The job at the flat-ground recommendation is checked photo by photo. When the
    project gave no height, or a height its worst photo cannot meet, the recommendation
    becomes the largest height above the reference ground the worst photo allows
    (:attr:`TerrainResult.max_height_m`, rounded down), re-laid out and re-checked (the
    photo centres move with the height).

    Returns
    -------
    job, terrain result, the recommended height [m] (None when nothing is recommended
    anew), the reason (a Message), the warnings of the final check — and, when a height
    the project gave was lowered, the check of that height (which strips and photos fail
    and by how much); the lowering itself is the specification's reason and its
    ``height_lowered`` warning.
    """
    if job.layout is None:
        raise InputError(f"{project.path}: [terrain]", "needs an area to lay the photos over "
                         "([area] width_m × length_m, polygon or file)")
    ground = _ground(project, cfg, job.layout)
    res = uav_terrain(job.layout, ground, job.plan.inputs, job.plan, cfg.altitude_mode,
                      cfg.follow_tolerance_m)
    height = job.plan.inputs.height_m
    first = res
    rec: float | None = None
    reason: Message | None = None
    for _ in range(_MAX_REFINE):
        if res.max_height_m is None or res.max_height_m >= height - 1e-9:
            break
        lower = recommended_height_m(res.max_height_m)
        if lower is None or lower >= height:
            break
        job = job_at(lower)
        if job.layout is None:
            break
        res = uav_terrain(job.layout, _ground(project, cfg, job.layout), job.plan.inputs,
                          job.plan, cfg.altitude_mode, cfg.follow_tolerance_m)
        height, rec = lower, lower
    if rec is not None:
        reason = Message("terrain_height_lowered", planned=planned_m or 0.0,
                         flat=job.plan.max_height_m or 0.0, max=res.max_height_m or 0.0,
                         recommended=rec, mode=_MODE_NAMES[cfg.altitude_mode],
                         cid=res.binding or "")
    notes = dict(res.layout.notes)
    notes["waypoints"] = res.waypoints
    layout = replace(res.layout, notes=notes)
    res = replace(res, layout=layout)
    warnings = res.warnings
    if rec is not None and planned_m is not None:  # what the height asked for would miss
        warnings = tuple(w for w in first.warnings if w.code == "terrain_resolution") + warnings
    return replace(job, layout=layout), res, rec, reason, warnings


def film_terrain_spec(project: Project, cfg: TerrainConfig, layout: FlightLayout,
                      rules: ScanRules, **scenario: Any) -> FilmTerrain:
    """The local photo scale of every frame of the flight scheme (see
    :func:`scanplan.geo.terrain.film_terrain`)."""
    ground = _ground(project, cfg, layout)
    return film_terrain(layout, ground, rules, mode=cfg.altitude_mode,
                        follow_tolerance_m=cfg.follow_tolerance_m, **scenario)

"""``[terrain]`` in a project: the plan checked over the ground under every photo.

The project layer's bridge to the terrain (:mod:`.terraincheck`: the ground and geometry of
:mod:`scanplan.geo.terrain` checked by :mod:`scanplan.rules.terrain`): reads the ``[terrain]`` keys,
resolves the DEM beside the project file, and gives the UAV specification its terrain
result — at the planned height, and, when the flat-ground recommendation fails over the
relief, at the largest height the worst photo allows (rounded down like every
recommended height). Film: the local photo scale of every frame of the flight scheme,
and the photo scale chosen so that the frame over the lowest ground still meets every
constraint (:func:`film_over_terrain`).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, replace
from typing import Any

from ..errors import InputError
from ..geo.layout import FlightLayout
from ..geo.terrain import Ground, TerrainConfig, TerrainResult, ground_under
from ..geo.terrain_choice import DIRECTIONS_DEG, ModeHeights, mode_heights
from ..geo.terrain_film import FilmTerrain, frames_over_terrain
from ..i18n.messages import Message
from ..rules.results import PlanWarning, ScanPlan, ScanRules, ScanScenario
from ..rules.terrain import (
    film_scale_warning,
    frame_recognition_p,
    height_accuracy_warnings,
    local_forward_overlap_pct,
)
from .file import KEYS
from .jobs import UavJob, recommended_height_m
from .model import ProjectModel
from .terraincheck import film_terrain, uav_terrain

__all__ = ["TERRAIN_KEYS", "FilmOverTerrain", "archive_over_terrain", "film_over_terrain",
           "film_terrain_spec", "terrain_config", "uav_terrain_spec"]

TERRAIN_KEYS = KEYS["terrain"]
"""The ``[terrain]`` keys (defined with every project key in :mod:`.file`)."""

_MODE_NAMES = {
    "constant": {"en": '"constant"', "ru": "постоянной высоты"},
    "strip": {"en": '"strip"', "ru": "высоты по маршрутам"},
    "follow": {"en": '"follow"', "ru": "следования рельефу"},
}  # [terrain] altitude_mode, as the reports name it

_MAX_REFINE = 4  # re-layouts at a lower height before giving up


def terrain_config(project: ProjectModel) -> TerrainConfig | None:
    """The ``[terrain]`` section as a :class:`TerrainConfig` (None without it), as parsed
    once with the file (:func:`scanplan.project.model.build_model`, which names a bad key
    and its line)."""
    return project.terrain.config if project.terrain is not None else None


def _named(project: ProjectModel, exc: InputError) -> InputError:
    """``terrain.dem`` → ``project.toml: terrain.dem (line 31)``."""
    field = exc.field
    if field.startswith("terrain.") or field == "terrain":
        section, _, key = field.partition(".")
        where = project.where(section, key) if key else f"[{section}]"
        return InputError(f"{project.path}: {where}", exc.message)
    return exc


def _ground(project: ProjectModel, cfg: TerrainConfig, layout: FlightLayout) -> Ground:
    if cfg.dem is not None and not layout.area.georeferenced:
        raise InputError(f"{project.path}: {project.where('terrain', 'dem')}",
                         "a DEM needs an area on the ground: give the area as a polygon or a "
                         "file ([area] file / polygon), or use ground_elevation_m = [min, max] "
                         "with the width_m × length_m block")
    try:
        return ground_under(layout, cfg)
    except InputError as exc:
        raise _named(project, exc) from None


def uav_terrain_spec(project: ProjectModel, cfg: TerrainConfig, job: UavJob,
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
    anew), the reason (a Message; when a height the project gave was lowered, with what
    that height would miss: which strips and photos, by how much — the specification's
    ``height_lowered`` warning), the warnings of the final check.
    """
    if job.layout is None:
        raise InputError(f"{project.path}: [terrain]", "needs an area to lay the photos over "
                         "([area] width_m × length_m, polygon or file)")
    start_m = job.plan.inputs.height_m
    job, res, rec, first = _settle(project, cfg, job, job_at)
    choice = _choices(cfg, job, res)
    if choice is not None and _auto_direction(project, job):
        if cfg.altitude_mode == "strip":
            job, res, rec, first = _strip_direction(project, cfg, job, res, rec, first,
                                                    job_at, start_m, choice)
    reason: Message | None = None
    if rec is not None:  # with what the height the project gave would miss, as the why
        reason = Message("terrain_height_lowered", planned=planned_m or 0.0,
                         flat=job.plan.max_height_m or 0.0, max=res.max_height_m or 0.0,
                         recommended=rec, mode=_MODE_NAMES[cfg.altitude_mode],
                         cid=res.binding or "",
                         why=(_missed_at_planned(first.warnings, cfg.altitude_mode)
                              if planned_m is not None else None))
    notes = dict(res.layout.notes)
    notes["waypoints"] = res.waypoints
    layout = replace(res.layout, notes=notes)
    res = replace(res, layout=layout)
    hint = _other_choice(cfg, res, choice, start_m) if choice is not None else None
    warnings = res.warnings + ((hint,) if hint is not None else ())
    return (replace(job, layout=layout), res, rec, reason,
            warnings + _height_accuracy_over_relief(job, res))


def _settle(project: ProjectModel, cfg: TerrainConfig, job: UavJob,
            job_at: Callable[[float], UavJob]
            ) -> tuple[UavJob, TerrainResult, float | None, TerrainResult]:
    """The job checked over the terrain, lowered (and laid out again) while its worst
    photo fails: (job, result, the lowered height or None, the first result)."""
    assert job.layout is not None
    res = uav_terrain(job.layout, _ground(project, cfg, job.layout), job.plan.inputs,
                      job.plan, cfg.altitude_mode, cfg.follow_tolerance_m)
    height = job.plan.inputs.height_m
    first = res
    rec: float | None = None
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
    return job, res, rec, first


def _auto_direction(project: ProjectModel, job: UavJob) -> bool:
    """True when the project leaves the direction to scanplan over a real area."""
    d = project.area.direction_deg
    return (d is None or d == "auto") and job.layout is not None \
        and job.layout.area.georeferenced


def _choices(cfg: TerrainConfig, job: UavJob, res: TerrainResult) -> ModeHeights | None:
    """The heights each mode and strip direction allow over this DEM (an estimate)."""
    lay = job.layout
    limit = job.plan.max_height_m
    if lay is None or limit is None or res.ground.grid is None or not lay.n_photos:
        return None
    dirs = tuple(sorted({*DIRECTIONS_DEG, round(lay.direction_deg % 180.0, 3)}))
    return mode_heights(res.ground.grid, lay.area.geometry, limit, lay.spacing_m,
                        lay.footprint_across_m, cfg.follow_tolerance_m, dirs)


def _strip_direction(project: ProjectModel, cfg: TerrainConfig, job: UavJob, res: TerrainResult,
                     rec: float | None, first: TerrainResult,
                     job_at: Callable[..., UavJob], start_m: float,
                     choice: ModeHeights | None
                     ) -> tuple[UavJob, TerrainResult, float | None, TerrainResult]:
    """``strip`` mode with the automatic direction: the direction whose strips span the
    least relief, when it allows a markedly higher plan than the direction of the least
    flight length, laid out and checked; taken when it needs fewer photos."""
    if choice is None or job.layout is None:
        return job, res, rec, first
    d_best, h_best = choice.best_strip()
    here = choice.strip_m[choice.directions_deg.index(round(job.layout.direction_deg % 180.0,
                                                            3))]
    if h_best < here + max(5.0, 0.05 * here) or res.height_m >= start_m - 1e-9:
        return job, res, rec, first
    other = job_at(start_m, d_best)
    if other.layout is None:
        return job, res, rec, first
    o_job, o_res, o_rec, o_first = _settle(project, cfg, other,
                                           lambda h: job_at(h, d_best))
    if o_job.layout is None or o_job.layout.n_photos >= job.layout.n_photos:
        return job, res, rec, first
    notes = dict(o_res.layout.notes)
    notes["terrain_direction"] = {"direction_deg": d_best,
                                  "instead_of_deg": job.layout.direction_deg,
                                  "photos_instead_of": job.layout.n_photos}
    o_res = replace(o_res, layout=replace(o_res.layout, notes=notes))
    return replace(o_job, layout=o_res.layout), o_res, o_rec, o_first


FAR_FEWER = 0.25
"""Another mode or direction is named when it needs at least this share fewer photos."""


def _other_choice(cfg: TerrainConfig, res: TerrainResult, choice: ModeHeights,
                  start_m: float) -> PlanWarning | None:
    """An info note when another altitude mode or strip direction would need far fewer
    photos (photos ∝ 1/H² at the heights :func:`~scanplan.geo.terrain_choice.mode_heights`
    estimates, each rounded down like a recommended height and at most the height the
    plan started from)."""
    n = res.layout.n_photos
    h = res.height_m
    if not n or not h > 0:
        return None
    d_best, h_strip = choice.best_strip()
    options = {"constant": (choice.constant_m, None), "follow": (choice.follow_m, None),
               "strip": (h_strip, d_best)}
    best = None
    for mode, (h_est, d) in options.items():
        if mode == cfg.altitude_mode and (mode != "strip" or abs(
                ((d - res.layout.direction_deg) + 90.0) % 180.0 - 90.0) < 10.0):
            continue
        h_alt = min(recommended_height_m(h_est) or 0.0, start_m)
        if h_alt <= h:
            continue
        n_alt = n * (h / h_alt) ** 2
        if n_alt <= (1.0 - FAR_FEWER) * n and (best is None or n_alt < best[2]):
            best = (mode, d, n_alt, h_alt)
    if best is None:
        return None
    mode, d, n_alt, h_alt = best
    what = (Message("terrain_choice.strip", mode=_MODE_NAMES[mode], direction=d)
            if d is not None else Message("terrain_choice.mode", mode=_MODE_NAMES[mode]))
    return PlanWarning("terrain_other_choice", Message(
        "terrain_other_choice", what=what, height=h_alt, current=h, photos=float(n_alt),
        now=n, pct=(1.0 - n_alt / n) * 100.0), severity="info")


def _height_accuracy_over_relief(job: UavJob, res: TerrainResult) -> tuple[PlanWarning, ...]:
    """σ_Z at the photo highest above its ground, at its highest flown height, with the
    mission's trigger distance (fixed in metres at the planned height): a warning when it
    exceeds V_z. The terrain check holds every photo to the flat limit, which is exact at
    every overlap (the base grows with the height above ground and never falls with the
    overlap flown, docs/uav-models.md §9), so it fires for a photo left above the limit:
    see :func:`scanplan.rules.terrain.height_accuracy_warnings`."""
    acc = job.plan.height_accuracy
    if acc.get("formula") != "normal_case":
        return ()
    return height_accuracy_warnings(job.plan.inputs, job.norm_set.rules(), acc,
                                    res.layout.photos.columns.get("agl_m", ()))


def _missed_at_planned(checked: tuple[PlanWarning, ...], mode: str) -> Message | None:
    """Why the height the project gave was lowered: its ``terrain_resolution`` finding
    (which photo, which strips, by how much), with the ways to fly higher instead of "lower
    the planned height" — said inside the one ``height_lowered`` warning, not beside it."""
    for w in checked:
        if w.code == "terrain_resolution" and isinstance(w.message, Message):
            params = {k: v for k, v in w.message.params.items() if k != "remedy"}
            return Message("terrain_resolution_lowered", params,
                           remedy=Message(f"terrain_higher.{mode}"))
    return None


def film_terrain_spec(project: ProjectModel, cfg: TerrainConfig, layout: FlightLayout,
                      rules: ScanRules, **scenario: Any) -> FilmTerrain:
    """The local photo scale of every frame of the flight scheme (see
    :func:`scanplan.project.terraincheck.film_terrain`)."""
    ground = _ground(project, cfg, layout)
    return film_terrain(layout, ground, rules, mode=cfg.altitude_mode,
                        follow_tolerance_m=cfg.follow_tolerance_m, **scenario)


@dataclass(frozen=True)
class FilmOverTerrain:
    """The film specification over the relief (see :func:`film_over_terrain`).

    Attributes
    ----------
    flat : ScanScenario or None
        The chosen candidate as the engine gives it on flat ground (its planned scale).
    headline : ScanScenario or None
        The specification's scenario: the engine's answer at the smallest local photo
        scale of the block (``local_photo_scale``), labelled with the flown ``photo_scale``.
    layout : FlightLayout or None
        The flight scheme at the chosen scale, every frame's ground and height filled in.
    terrain : FilmTerrain or None
    rejected : tuple
        (candidate, its FilmTerrain) for the candidates with fewer frames (larger Mc) the
        relief rules out.
    reason : Message
    warnings : tuple of PlanWarning
    """

    flat: ScanScenario | None
    headline: ScanScenario | None
    layout: FlightLayout | None
    terrain: FilmTerrain | None
    rejected: tuple[tuple[ScanScenario, FilmTerrain], ...]
    reason: Message
    warnings: tuple[PlanWarning, ...] = ()


def _film_args(plan: ScanPlan, photo_scale: float) -> dict[str, Any]:
    inp = plan.inputs
    obj = inp.object
    return dict(map_scale=inp.map_scale, photo_scale=photo_scale,
                relief_interval_m=inp.relief_interval_m, focal_mm=inp.focal_mm,
                frame_along_mm=inp.frame_along_mm,
                forward_overlap_pct=inp.forward_overlap_pct,
                resolving_power_lpmm=inp.resolving_power_lpmm,
                object_size_m=obj.size_m if obj is not None else math.nan,
                shape_coefficient=obj.shape_coefficient if obj is not None else math.nan)


def _at_worst_frame(plan: ScanPlan, ft: FilmTerrain) -> Any:
    """The engine's inputs at the frame with the largest local Mc: that scale, and for the
    parallax form the local image base (:func:`local_forward_overlap_pct`)."""
    inp = plan.inputs
    return replace(inp, photo_scales=(ft.mc_max,), forward_overlap_pct=local_forward_overlap_pct(
        plan.rules, inp.forward_overlap_pct, ft.photo_scale, ft.mc_max))


def worst_frame_scenario(plan: ScanPlan, candidate: ScanScenario, ft: FilmTerrain
                         ) -> tuple[ScanScenario, ScanScenario]:
    """The engine's scenario at the block's smallest local photo scale (``ft.mc_max``):
    as computed (labelled with that Mc) and as the specification states it (labelled with
    the flown scale of ``candidate``, ``local_photo_scale`` = Mc max)."""
    from ..rules.film import plan_scan

    raw = plan_scan(_at_worst_frame(plan, ft), plan.rules).scenarios[0]
    return raw, replace(raw, photo_scale=candidate.photo_scale,
                        photo_to_map_ratio=candidate.photo_to_map_ratio,
                        local_photo_scale=ft.mc_max)


def _where(ft: FilmTerrain) -> Message:
    if ft.ground_known:
        return Message("terrain_film_where.dem", frame=ft.binding_frame, strip=ft.binding_strip)
    return Message("terrain_film_where.range", low=ft.ground_low_m)


def _rejected_fields(rejected: list[tuple[ScanScenario, FilmTerrain]]) -> dict[str, list[float]]:
    """The rejected photo scales and their largest local Mc, as the messages take them."""
    return {"scales": [r.photo_scale for r, _ in rejected],
            "locals": [float(round(t.mc_max)) for _, t in rejected]}


def film_over_terrain(project: ProjectModel, cfg: TerrainConfig, plan: ScanPlan,
                      candidates: list[ScanScenario],
                      layout_at: Callable[[ScanScenario], FlightLayout],
                      feasible: Callable[[ScanScenario], bool]) -> FilmOverTerrain:
    """The photo scale and scan pixel that hold at every frame over the relief.

    The candidates that meet every constraint on flat ground are tried from the smallest
    scale (fewest frames) up: each is laid out over the area, every frame gets its local
    photo scale (:func:`scanplan.project.terraincheck.film_terrain`), and the engine is run at
    the largest local Mc. The first whose worst frame is ``feasible`` (the flat-ground
    choice's own test: interpretable, within the scanner and the film) is the
    specification: its scan pixel and binding constraint are those of the worst frame.
    Bisection-free: the engine is evaluated once per candidate tried.
    """
    rejected: list[tuple[ScanScenario, FilmTerrain]] = []
    for s in candidates:
        layout = layout_at(s)
        ft = film_terrain_spec(project, cfg, layout, plan.rules, **_film_args(plan, s.photo_scale))
        raw, headline = worst_frame_scenario(plan, s, ft)
        if not feasible(raw):
            rejected.append((s, ft))
            continue
        pixel = headline.scanner_pixel_um or headline.scan_pixel_um
        layout = frames_over_terrain(layout, ft, pixel, plan.inputs.focal_mm, cfg.altitude_mode,
                                     frame_recognition_p(plan.inputs, plan.rules, ft.mc, pixel))
        rej = (Message("spec.film_terrain.rejected", **_rejected_fields(rejected))
               if rejected else None)
        reason = Message("spec.film_terrain", scale=s.photo_scale, where=_where(ft),
                         local=float(round(ft.mc_max)), explanation=raw.explanation,
                         rejected=rej)
        warnings = list(ft.warnings)
        if rejected:
            r, rt = rejected[0]
            warnings.append(PlanWarning("terrain_film_scale_changed", Message(
                "terrain_film_scale_changed", flat=r.photo_scale, where=_where(rt),
                local=float(round(rt.mc_max)), scale=s.photo_scale,
                hi=float(round(ft.mc_max))), photo_scales=(r.photo_scale,)))
        return FilmOverTerrain(s, headline, layout, ft, tuple(rejected), reason,
                               tuple(warnings))
    why = ([Message("no_feasible_photo_scale.relief", **_rejected_fields(rejected))]
           if rejected else [])
    return FilmOverTerrain(None, None, None, None, tuple(rejected),
                           Message("no_feasible_photo_scale", why=why))


def archive_over_terrain(project: ProjectModel, cfg: TerrainConfig, raw: Any, flat_job: Any,
                         flat: ScanScenario, layout: FlightLayout) -> FilmOverTerrain:
    """Archive photos (``[film] photo_scale``, the scale given) over the relief: the scan
    pixel that holds at the frame over the lowest ground.

    ``raw`` is the engine's job at the archive scale, ``flat_job``/``flat`` its archive
    restatement on flat ground (:func:`scanplan.project.archive.archive_film`). The same
    restatement is made at the largest local Mc; its scan pixel, binding constraint and
    volume are the specification's, labelled with the archive scale.
    """
    from ..rules.film import plan_scan
    from .archive import archive_film

    plan = raw.plan
    ft = film_terrain_spec(project, cfg, layout, plan.rules,
                           **_film_args(plan, flat.photo_scale))
    worst_plan = plan_scan(_at_worst_frame(plan, ft), plan.rules)
    wjob, ws, _ = archive_film(replace(raw, plan=worst_plan))
    headline = replace(ws, photo_scale=flat.photo_scale,
                       photo_to_map_ratio=flat.photo_to_map_ratio, local_photo_scale=ft.mc_max)
    pixel = headline.scanner_pixel_um or headline.scan_pixel_um
    layout = frames_over_terrain(layout, ft, pixel, plan.inputs.focal_mm, cfg.altitude_mode,
                                 frame_recognition_p(plan.inputs, plan.rules, ft.mc, pixel))
    # the terrain figures as the archive restatement gives them (P_D set aside where the
    # objects cannot be interpreted), not the raw engine's
    kept = tuple(w for w in ft.warnings if w.code != "terrain_film_scale")
    note = film_scale_warning(headline.scan_pixel_um, flat.scan_pixel_um, headline.binding,
                              ft.mc_min, ft.mc_max, _where(ft))
    kept += (note,) if note is not None else ()
    ft = replace(ft, scan_pixel_um=headline.scan_pixel_um, binding=headline.binding,
                 scan_pixel_planned_um=flat.scan_pixel_um, binding_planned=flat.binding,
                 warnings=kept)
    reason = Message("spec.film_archive_terrain", scale=flat.photo_scale, where=_where(ft),
                     local=float(round(ft.mc_max)), pixel=headline.scan_pixel_um,
                     explanation=ws.explanation)
    seen = {w.code for w in flat_job.plan.warnings}
    extra = [w for w in wjob.plan.warnings if w.code in ("archive_not_interpretable",
                                                          "archive_scanner_too_coarse")
             and w.code not in seen]
    return FilmOverTerrain(flat, headline, layout, ft, (), reason, (*ft.warnings, *extra))

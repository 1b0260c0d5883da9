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
from ..geo.terrain_film import FilmTerrain, frames_over_terrain
from ..i18n.messages import Message, Names
from ..rules.results import PlanWarning, ScanPlan, ScanRules, ScanScenario, UavInputs
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

__all__ = ["MAX_TRIES", "MODE_NAMES", "TERRAIN_KEYS", "FilmOverTerrain", "Settled",
           "archive_over_terrain", "film_over_terrain", "film_terrain_spec", "flown_band_m",
           "ground_of",
           "passes", "settle", "terrain_check", "terrain_config", "terrain_outcome"]

TERRAIN_KEYS = KEYS["terrain"]
"""The ``[terrain]`` keys (defined with every project key in :mod:`.file`)."""

MODE_NAMES = _MODE_NAMES = {
    "constant": Names('"constant"', "постоянной высоты"),
    "strip": Names('"strip"', "высоты по маршрутам"),
    "follow": Names('"follow"', "следования рельефу"),
}  # [terrain] altitude_mode, as the reports name it



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


def terrain_check(project: ProjectModel, cfg: TerrainConfig, job: UavJob, mode: str, *,
                  ground: Ground | None = None, figures: bool = True) -> TerrainResult:
    """The UAV job's photos over the terrain flown in altitude ``mode``, checked photo by
    photo (:func:`scanplan.project.terraincheck.uav_terrain`; ``ground``: the ground under
    the job's layout when known, :func:`ground_of`; ``figures``: every photo's GSD, L and
    recognition probability)."""
    if job.layout is None:
        raise InputError(f"{project.path}: [terrain]", "needs an area to lay the photos over "
                         "([area] width_m × length_m, polygon or file)")
    if ground is None:
        ground = _ground(project, cfg, job.layout)
    return uav_terrain(job.layout, ground, job.plan.inputs, job.plan, mode,
                       cfg.follow_tolerance_m, figures)


def ground_of(project: ProjectModel, cfg: TerrainConfig, layout: FlightLayout) -> Ground:
    """The ground under a layout's photos (the DEM read under it, or the range), its
    errors named by the project's keys."""
    return _ground(project, cfg, layout)


def passes(res: TerrainResult) -> bool:
    """Whether the worst photo meets every limit at the height the result was planned at."""
    return res.max_height_m is None or res.max_height_m >= res.height_m - 1e-9


@dataclass(frozen=True)
class Settled:
    """A layout and the height it is flown at, held to a fixed point (:func:`settle`).

    Attributes
    ----------
    job : UavJob
        The job at the height found (its layout laid out at that height).
    result : TerrainResult
        Its check over the terrain.
    first : TerrainResult
        The check at the height the search started from.
    tried : tuple of (float, bool)
        Every height laid out and checked, and whether its worst photo met every limit, in
        the order tried [m].
    """

    job: UavJob
    result: TerrainResult
    first: TerrainResult
    tried: tuple[tuple[float, bool], ...]

    @property
    def lowered_m(self) -> float | None:
        """The height when it is below the start, else None [m]."""
        start = self.tried[0][0]
        h = self.result.height_m
        return h if h < start - 1e-9 else None


MAX_TRIES = 8
"""Most heights laid out and checked for one layout's fixed point."""


def _below(height_m: float) -> float | None:
    """The recommended height one step below ``height_m`` [m] (None below 1 m)."""
    return recommended_height_m(height_m - 1e-6)


def settle(check: Callable[[UavJob], TerrainResult], start: UavJob,
           job_at: Callable[[float], UavJob]) -> Settled:
    """The highest height whose own layout meets every limit over the terrain: layout and
    height iterated to a fixed point.

    The photo centres move with the height (the base and the line spacing scale with it),
    so a height lowered for the ground under one layout may be too low for the layout at
    that height: a narrow spike under a line of the 120 m layout lowers it to 105 m, and
    the lines laid out at 105 m miss the spike, whose check then allows more. Each layout's
    check gives the largest height *its* ground allows (closed form, :attr:`TerrainResult.
    max_height_m`); the search tries, on the grid of recommended heights, the height that
    hint gives — down while nothing passes, then up between the highest height that passes
    and the lowest above it that fails — until no height between them is left untried, at
    most :data:`MAX_TRIES` layouts. It returns the highest that passes (the lowest tried
    when none does), never above the start.

    Parameters
    ----------
    check : callable
        A job → its check over the terrain (:func:`terrain_check` in one altitude mode).
    start : UavJob
        The job at the height to start from (the flat recommendation or the project's).
    job_at : callable
        A height [m] → the job laid out at that height.

    Returns
    -------
    Settled
    """
    top = float(start.plan.inputs.height_m)
    done: dict[float, tuple[bool, float | None]] = {}  # height → (passes, its hint)
    kept: dict[float, tuple[UavJob, TerrainResult]] = {}  # the start, the best so far
    order: list[float] = []
    h: float | None = top
    while h is not None and h not in done and len(done) < MAX_TRIES:
        job = start if h == top else job_at(h)
        if job.layout is None:
            break
        res = check(job)
        done[h] = (passes(res), res.max_height_m)
        order.append(h)
        kept[h] = (job, res)
        best = _best_height(done)
        kept = {x: v for x, v in kept.items() if x in (top, best)}  # the others' layouts go
        h = _next_height(done, top)
    job, res = kept[_best_height(done)]
    return Settled(job, res, kept[top][1], tuple((x, done[x][0]) for x in order))


def _best_height(done: dict[float, tuple[bool, float | None]]) -> float:
    """The highest height that passes, else the lowest tried."""
    good = [x for x in done if done[x][0]]
    return max(good) if good else min(done)


def _next_height(done: dict[float, tuple[bool, float | None]], top: float) -> float | None:
    """The next height to lay out (see :func:`settle`), None when the search is over."""
    good = [x for x in done if done[x][0]]
    if not good:  # nothing passes yet: down, by the lowest failing layout's hint
        low = min(done)
        nxt = recommended_height_m(done[low][1])
        if nxt is None or nxt >= low:
            nxt = _below(low)
        return nxt
    lo = max(good)
    above = [x for x in done if not done[x][0] and x > lo]
    cap = _below(min(above)) if above else top
    hint = recommended_height_m(done[lo][1])
    if cap is None or hint is None:
        return None
    nxt = min(hint, cap)
    return nxt if nxt > lo + 1e-9 else None


def flown_band_m(res: TerrainResult, inp: UavInputs) -> tuple[float, float] | None:
    """The lowest and highest heights above the ground the photos are really flown at over
    the relief, the height tolerances included [m]: the least height over the ground under
    a photo centre (the highest ground under it where unknown) × (1 − down) and the photo
    highest above its ground (:attr:`TerrainResult.layout` ``agl_m``) × (1 + up); None
    without photos."""
    summary = res.summary()
    lo, hi = summary.get("agl_min_m"), summary.get("agl_max_m")
    if lo is None or hi is None or not (math.isfinite(lo) and math.isfinite(hi)):
        return None
    return (lo * (1.0 - inp.height_tolerance_down_pct / 100.0),
            hi * (1.0 + inp.height_tolerance_up_pct / 100.0))


def terrain_outcome(settled: Settled, mode: str, planned_m: float | None
                    ) -> tuple[TerrainResult, Message | None, tuple[PlanWarning, ...]]:
    """The specification's terrain result of a settled layout: the result with its
    altitude waypoints in the layout's notes, the reason when the height was lowered
    from the start (with what the height the project gave would miss), and the warnings
    of the final check with the height accuracy over the relief."""
    job, res, first = settled.job, settled.result, settled.first
    rec = settled.lowered_m
    reason: Message | None = None
    if rec is not None:  # with what the height the project gave would miss, as the why
        reason = Message("terrain_height_lowered", planned=planned_m or 0.0,
                         flat=job.plan.max_height_m or 0.0, max=res.max_height_m or 0.0,
                         recommended=rec, mode=_MODE_NAMES[mode], cid=res.binding or "",
                         why=(_missed_at_planned(first.warnings, mode)
                              if planned_m is not None else None))
    notes = dict(res.layout.notes)
    notes["waypoints"] = res.waypoints
    res = replace(res, layout=replace(res.layout, notes=notes))
    return res, reason, res.warnings + _height_accuracy_over_relief(job, res)


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

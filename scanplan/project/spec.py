"""The specification for a mapping contract: what ``scanplan plan PROJECT.toml`` answers.

Film: the recommended photo scale among the candidates — the one that meets every
constraint at the least cost (fewest frames = the smallest photo scale, i.e. the largest
Mc, that keeps the map's objects interpretable and that the scanner can scan), its scan
pixel rounded to the scanner's steps, frames and scanned volume for the area.
UAV: the recommended and maximum flight height (with the height tolerance) and the flight
at the recommended height. Both: a side-by-side comparison. Nothing here recomputes a
formula; it chooses among engine results.
"""

from __future__ import annotations

import inspect
import math
from dataclasses import replace
from functools import cache
from typing import TYPE_CHECKING, Any

from ..core.domains import DOMAINS
from ..core.photoscale import scanned_ground_pixel_m
from ..errors import InputError
from ..geo.area import AreaSpec
from ..geo.layout import Area, FlightLayout
from ..i18n.messages import Message
from ..io.kept import MISSING, Kept
from ..norms.store import one_version
from ..rules.film import PlanWarning, ScanScenario
from ..rules.uav import with_curves
from .aircraftplan import aircraft_warnings
from .alternatives import JobAt, choose_plan
from .archive import archive_film
from .background import map_backgrounds
from .control import ControlSpec, plan_control
from .design import survey_design
from .file import Project
from .flightplan import (
    LayoutOptions,
    area_from_options,
    check_options,
    film_layout,
    layout_warnings,
)
from .inputs import by_key
from .jobs import (
    PROVISIONAL_HEIGHT_M,
    ScanJob,
    UavJob,
    height_step_m,
    recommended_height_m,
    scan_job,
    uav_job,
)
from .model import ProjectModel, build_model
from .results import FilmSpec, PlanResult, UavSpec
from .sorties import project_aircraft, sortie_length, terrain_relief_m

if TYPE_CHECKING:  # the relief's modules are imported for a plan with [terrain] only
    from ..geo.terrain_film import FilmTerrain
    from ..rules.results import UavPlan

__all__ = ["FilmSpec", "PlanResult", "UavSpec", "plan_project", "project_area"]

DEFAULT_FILM_SIDE_OVERLAP_PCT: float = by_key("film", "side_overlap_pct").default
"""Side overlap of film photos when the project gives none [%] (the input registry's)."""
_AREA_KEYS = ("file", "layer", "feature", "polygon", "crs", "plan_crs", "width_m", "length_m",
              "direction_deg", "extension_bases")


def _job_kwargs(given: Any, takes: Any) -> dict[str, Any]:
    """The keyword arguments of :func:`scan_job` / :func:`uav_job` the project gives: the
    inputs of the plan's section of the model (:attr:`~scanplan.project.model.FilmSection.
    given`) the job function ``takes``; keys the file leaves out take the API's defaults,
    which are the registry's."""
    params = _parameters(takes)
    return {name: value for name, value in given.items() if name in params}


@cache
def _parameters(func: Any) -> frozenset[str]:
    """The names of ``func``'s parameters (read once: inspect takes a millisecond)."""
    return frozenset(inspect.signature(func).parameters)


def _film(project: ProjectModel, area: Area | None) -> FilmSpec:
    assert project.film is not None
    archive_scale = project.film.photo_scale
    kw = _job_kwargs(project.film.given, scan_job)
    if archive_scale is not None:
        kw["photo_scales"] = [archive_scale]
    side = project.film.side_overlap_pct
    try:
        job = scan_job(**kw)
    except InputError as exc:
        raise project.named(exc, "film", archive=archive_scale is not None) from None
    if archive_scale is not None:
        raw = job
        job, best, reason = archive_film(job)
        if area is not None and project.terrain is not None:
            return _archive_over_terrain(project, raw, job, best, side, area)
    else:
        best, reason = _choose_photo_scale(job)
        if best is not None and area is not None and project.terrain is not None:
            return _film_over_terrain(project, job, side, area)
    return _film_spec(project, job, best, reason, side, area)


def _archive_over_terrain(project: ProjectModel, raw: ScanJob, job: ScanJob, best: ScanScenario,
                          side: float, area: Area) -> FilmSpec:
    """``[terrain]`` with archive photos: the scan pixel of the frame over the lowest
    ground (:func:`scanplan.project.terrainplan.archive_over_terrain`)."""
    assert project.terrain is not None
    cfg = project.terrain.config
    inp = job.plan.inputs
    try:
        layout = film_layout(best, inp.frame_width_mm, inp.frame_along_mm, inp.focal_mm,
                             inp.forward_overlap_pct, side, area, _layout_options(project))
    except InputError as exc:
        raise project.named(exc, "uav") from None
    from .terrainplan import archive_over_terrain

    got = archive_over_terrain(project, cfg, raw, job, best, layout)
    rec, layout = got.headline, got.layout
    frames = int(layout.notes.get("photos", len(layout.photos))) if layout else None
    if got.warnings:
        job = replace(job, plan=replace(job.plan, warnings=job.plan.warnings + got.warnings))
    return FilmSpec(job=job, recommended=rec, reason=got.reason, frames=frames,
                    strips=len(layout.strips) if layout else None,
                    scanned_gigabytes=(frames * rec.frame_megabytes / 1000.0
                                       if frames is not None and rec is not None else None),
                    side_overlap_pct=side, archive=True, layout=layout, terrain=got.terrain,
                    flat=got.flat)


def _feasible(plan: Any, s: ScanScenario) -> bool:
    """A photo scale the specification may take: within the interpretation limit, the
    scanner reaches its scan pixel, and the pixel is not below any scanner's (and the
    film's)."""
    limit = plan.interpretation_limit_photo_scale
    finest = DOMAINS["pixel_um"].lo  # below it no scanner (nor film) gives a meaningful pixel
    return ((limit is None or s.photo_scale <= limit * (1 + 1e-12))
            and (not plan.inputs.scanner or s.scanner_pixel_um is not None)
            and s.scan_pixel_um >= finest)


def _film_over_terrain(project: ProjectModel, job: ScanJob, side: float, area: Area) -> FilmSpec:
    """``[terrain]``: the photo scale and scan pixel that hold at every frame over the
    relief (:func:`scanplan.project.terrainplan.film_over_terrain`)."""
    plan = job.plan
    assert project.terrain is not None
    cfg = project.terrain.config
    inp = plan.inputs
    candidates = sorted((s for s in plan.scenarios if _feasible(plan, s)),
                        key=lambda s: (s.photo_scale, s.scanner_pixel_um or 0), reverse=True)

    def layout_at(s: ScanScenario) -> FlightLayout:
        try:
            return film_layout(s, inp.frame_width_mm, inp.frame_along_mm, inp.focal_mm,
                               inp.forward_overlap_pct, side, area, _layout_options(project))
        except InputError as exc:
            raise project.named(exc, "uav") from None

    from .terrainplan import film_over_terrain

    got = film_over_terrain(project, cfg, plan, candidates, layout_at,
                            lambda s: _feasible(plan, s))
    rec, layout = got.headline, got.layout
    frames = strips = gigabytes = None
    if rec is not None and layout is not None:
        strips = len(layout.strips)
        frames = int(layout.notes.get("photos", len(layout.photos)))
        gigabytes = frames * rec.frame_megabytes / 1000.0
    if got.warnings:  # shown with the film plan's own warnings
        job = replace(job, plan=replace(plan, warnings=plan.warnings + got.warnings))
    return FilmSpec(job=job, recommended=rec, reason=got.reason, frames=frames, strips=strips,
                    scanned_gigabytes=gigabytes, side_overlap_pct=side, archive=False,
                    layout=layout, terrain=got.terrain, flat=got.flat,
                    rejected=got.rejected)


def _choose_photo_scale(job: ScanJob) -> tuple[ScanScenario | None, str]:
    """Among candidate photo scales: the smallest that meets every constraint."""
    plan = job.plan
    limit = plan.interpretation_limit_photo_scale
    finest = DOMAINS["pixel_um"].lo
    feasible = [s for s in plan.scenarios if _feasible(plan, s)]
    if feasible:
        best = max(feasible, key=lambda s: (s.photo_scale, s.scanner_pixel_um or 0))
        reason = Message("spec.film", scale=best.photo_scale, explanation=best.explanation)
    else:
        best = None
        why = []
        if limit is not None:
            why.append(Message("no_feasible_photo_scale.objects", limit=math.floor(limit)))
        if plan.inputs.scanner:
            why.append(Message("no_feasible_photo_scale.scanner", scanner=plan.inputs.scanner))
        if any(s.scan_pixel_um < finest for s in plan.scenarios):
            why.append(Message("no_feasible_photo_scale.pixel", finest=finest))
        reason = Message("no_feasible_photo_scale", why=why)
    return best, reason


def _film_spec(project: ProjectModel, job: ScanJob, best: ScanScenario | None, reason: str,
               side: float, area: Area | None) -> FilmSpec:
    """Frames and scanned volume of the recommended photo scale over ``[area]``: the aerial
    survey's flight scheme (strips and frames laid out over the area)."""
    plan = job.plan
    frames = strips = None
    gigabytes = None
    layout = None
    if best is not None and area is not None:
        inp = plan.inputs
        try:
            layout = film_layout(best, inp.frame_width_mm, inp.frame_along_mm, inp.focal_mm,
                                 inp.forward_overlap_pct, side, area,
                                 _layout_options(project))
        except InputError as exc:
            raise project.named(exc, "uav") from None
        strips = len(layout.strips)
        frames = int(layout.notes.get("photos", len(layout.photos)))
        gigabytes = frames * best.frame_megabytes / 1000.0
    terrain = _film_terrain(project, plan, best, layout)
    if terrain is not None and terrain.warnings:  # shown with the film plan's own warnings
        job = replace(job, plan=replace(plan, warnings=plan.warnings + terrain.warnings))
    return FilmSpec(job=job, recommended=best, reason=reason, frames=frames, strips=strips,
                    scanned_gigabytes=gigabytes, side_overlap_pct=side,
                    archive=project.film is not None and project.film.archive, layout=layout,
                    terrain=terrain)


def _film_terrain(project: ProjectModel, plan: Any, best: ScanScenario | None,
                  layout: FlightLayout | None) -> FilmTerrain | None:
    """``[terrain]``: the local photo scale of every frame of the flight scheme."""
    if project.terrain is None or best is None or layout is None:
        return None
    cfg = project.terrain.config
    inp = plan.inputs
    obj = inp.object
    from .terrainplan import film_terrain_spec

    return film_terrain_spec(
        project, cfg, layout, plan.rules, map_scale=inp.map_scale,
        photo_scale=best.photo_scale, relief_interval_m=inp.relief_interval_m,
        focal_mm=inp.focal_mm, frame_along_mm=inp.frame_along_mm,
        forward_overlap_pct=inp.forward_overlap_pct,
        resolving_power_lpmm=inp.resolving_power_lpmm,
        object_size_m=obj.size_m if obj is not None else math.nan,
        shape_coefficient=obj.shape_coefficient if obj is not None else math.nan)


def project_area(project: ProjectModel) -> Area | None:
    """The project's ``[area]`` in its planning CRS: a file, an inline polygon or the
    ``width_m × length_m`` block (None without one).

    Raises
    ------
    InputError
        Naming the project file, the ``[area]`` key and its line (and the area file and
        feature for a problem in the file).
    """
    a = project.area
    spec = AreaSpec(file=a.file, layer=a.layer, feature=a.feature, polygon=a.polygon,
                    crs=a.crs, plan_crs=a.plan_crs, width_m=a.width_m, length_m=a.length_m)
    try:
        return area_from_options(spec)
    except InputError as exc:
        if exc.field in _AREA_KEYS:
            where = project.where("area", exc.field)
        else:  # the area file, its feature
            where = f"{project.where('area', 'file')}: {exc.field}"
        raise InputError(f"{project.path}: {where}", exc.message) from None


def _layout_keys_given(project: ProjectModel) -> list[tuple[str, str]]:
    """The flight layout's keys the file gives, in the order an error names the first."""
    a, f = project.area, project.flight
    keys = ((("area", "direction_deg"), a.direction_deg),
            (("area", "extension_bases"), a.extension_bases),
            (("uav", "turnaround_m"), f.turnaround_m), (("uav", "turn_radius_m"), f.turn_radius_m),
            (("uav", "bank_deg"), f.bank_deg), (("uav", "max_flight_time_min"),
                                                f.max_flight_time_min),
            (("flight", "takeoff"), f.takeoff),
            (("uav", "crosshatch"), f.crosshatch or None))
    return [k for k, v in keys if v is not None]


def _check_layout_keys(project: ProjectModel, area: Area | None) -> None:
    """The layout keys checked once, before any plan: in range, and only with an area."""
    given = _layout_keys_given(project)
    if area is None:
        if given:
            s, k = given[0]
            raise InputError(project.at(s, k), "applies to an area: "
                             "give [area] file, polygon, or width_m and length_m")
        return
    speed = project.uav.speed_ms if project.uav is not None else by_key("uav",
                                                                         "speed_ms").default
    try:
        check_options(_layout_options(project), area, speed if speed and speed > 0 else None)
    except InputError as exc:
        raise project.named(exc, "uav") from None


def _layout_options(project: ProjectModel, platform: str = "uav",
                    relief_m: float = 0.0) -> LayoutOptions:
    a, f = project.area, project.flight
    return LayoutOptions(
        direction_deg=a.direction_deg,
        extension_bases=(a.extension_bases if a.extension_bases is not None
                         else by_key("area", "extension_bases").default),
        turnaround_m=f.turnaround_m, turn_radius_m=f.turn_radius_m, bank_deg=f.bank_deg,
        # the one sortie length: it splits the layout and counts the schedule's sorties
        max_flight_time_min=sortie_length(project, platform).minutes,
        takeoff_lonlat=f.takeoff, relief_m=relief_m, crosshatch=f.crosshatch)


def _platform(kw: dict[str, Any]) -> str:
    """The carrier of the job's camera (``uav`` or ``aircraft``, the catalogue's)."""
    camera = kw.get("camera")
    if camera is None:
        return "uav"
    try:
        from ..norms import DEFAULT_NORM_SET, load_norm_set

        cam = load_norm_set(kw.get("norms") or DEFAULT_NORM_SET).camera(camera, "camera")
    except InputError:  # the job itself names the bad camera or norm set
        return "uav"
    return getattr(cam, "carrier", "uav") or "uav"


def _uav_kwargs(project: ProjectModel, height_m: float, the_area: Area | None
                ) -> dict[str, Any]:
    assert project.uav is not None
    kw = _job_kwargs(project.uav.given, uav_job)
    craft = project_aircraft(project)
    if craft is not None and "speed_ms" not in kw:  # the aircraft's cruise speed, if known
        from ..norms.aircraft import aircraft

        cruise = aircraft(craft).cruise_speed_ms
        if cruise is not None:
            kw["speed_ms"] = cruise
    kw.update(height_m=height_m, area_m=project.area.rectangle, area=the_area,
              layout_options=_layout_options(project, _platform(kw),
                                             terrain_relief_m(project, the_area)))
    return kw


def _uav(project: ProjectModel, the_area: Area | None) -> UavSpec:
    """The UAV plan chosen, with the curves for plots of its plan alone (the plans solved
    to choose it are planned without them: :func:`_jobs`)."""
    spec = _uav_chosen(project, the_area)
    return replace(spec, job=replace(spec.job, plan=with_curves(spec.job.plan)))


def _uav_chosen(project: ProjectModel, the_area: Area | None) -> UavSpec:
    assert project.uav is not None
    planned = project.uav.height_m
    job_at = _jobs(project, the_area)
    first_height = planned if planned is not None else PROVISIONAL_HEIGHT_M
    # the limits do not depend on the area: the layout is made once, at the height chosen
    first = job_at(first_height, limits_only=True)
    max_h = first.plan.max_height_m
    rounded = recommended_height_m(max_h)
    if max_h is None or rounded is None:
        return UavSpec(job_at(first_height), planned, None, max_h, Message("spec.uav_none"))
    if planned is None:
        rec = rounded
        reason = Message("spec.uav_rounded", max=max_h, cid=first.plan.binding,
                         step=height_step_m(max_h))
    elif planned > max_h:
        rec = rounded
        reason = Message("height_lowered", planned=planned, max=max_h,
                         cid=first.plan.binding, recommended=rec)
    else:
        rec = planned
        reason = Message("spec.uav_within", max=max_h)
    job = job_at(rec)
    if job.layout is None or (project.terrain is None and not job.layout.area.georeferenced):
        return UavSpec(job, planned, rec, max_h, reason)  # nothing to choose
    choice = choose_plan(project, job, job_at, planned)
    if choice.lowered is not None:
        rec, reason = choice.height_m, choice.lowered
    job = choice.job
    if choice.warnings:  # shown with the UAV plan's own warnings (terminal, JSON, PDF, workbook)
        job = replace(job, plan=replace(job.plan, warnings=job.plan.warnings + choice.warnings))
    return UavSpec(job, planned, rec, max_h, reason, choice.terrain, choice.warnings,
                   choice.alternatives, choice.choice)


_JOBS_KEPT = 6
"""Jobs kept for reuse while the plans are compared (the modes of a direction share its
layouts; a job is laid out again when it was dropped)."""


def _jobs(project: ProjectModel, the_area: Area | None) -> JobAt:
    """The project's UAV job at a height (:data:`scanplan.project.alternatives.JobAt`),
    each laid out once: along the project's direction or another one, its figures at the
    heights really flown over relief. Their plans have no curves for plots (:func:`_uav`
    adds them to the plan chosen)."""
    done: Kept[tuple[Any, ...], UavJob] = Kept(_JOBS_KEPT)
    limits: Kept[tuple[Any, ...], UavPlan] = Kept(_JOBS_KEPT)  # per height, any direction
    own = project.area.direction_deg

    def job_at(height_m: float, direction_deg: float | str | None = None,
               flown_band_m: tuple[float, float] | None = None,
               laid_out: FlightLayout | None = None, limits_only: bool = False) -> UavJob:
        if direction_deg is not None and (direction_deg == own or (
                own is None and direction_deg == "auto")):
            direction_deg = None  # the project's own
        key = (float(height_m), direction_deg, flown_band_m, limits_only)
        job = done.get(key)
        if job is not MISSING:
            return job  # type: ignore[return-value]
        try:
            kw = _uav_kwargs(project, height_m, the_area)
            if direction_deg is not None:
                kw["layout_options"] = replace(kw["layout_options"],
                                               direction_deg=direction_deg)
            if limits_only:  # only its limits are asked for: no strips over the area
                kw.update(area=None, area_m=None)
            same = (float(height_m), flown_band_m, kw["area_m"])  # the same inputs
            made = done.put(key, uav_job(**kw, flown_band_m=flown_band_m, laid_out=laid_out,
                                         limits=limits.get(same, None), curves=False))
        except InputError as exc:
            raise project.named(exc, "uav") from None
        if made.limits is not None:
            limits.put(same, made.limits)
        return made

    return job_at


def _comparison(film: FilmSpec, uav: UavSpec) -> list[dict[str, Any]]:
    s = film.recommended
    u = uav.job.plan
    rows: list[dict[str, Any]] = []

    def row(key: str, quantity: str, film_value: Any, uav_value: Any, unit: str) -> None:
        rows.append({"quantity": quantity, "key": key, "film": film_value, "uav": uav_value,
                     "unit": unit})

    if s is not None:
        pixel = s.scanner_pixel_um or s.scan_pixel_um
        row("ground_pixel", "pixel on the ground",
            float(scanned_ground_pixel_m(pixel, s.photo_scale)), u.gsd_m, "m")
        row("ground_resolution", "resolution on the ground (A / L)",
            s.resolution_on_ground_mm / 1000.0, u.ground_resolution_m, "m")
        obj = uav.job.plan.inputs.map_object
        p_uav = None
        if obj is not None:
            p_uav = next((r.probability for r in u.recognition if r.object == obj.name
                          and r.object_size_m == obj.size_m), None)
        row("recognition", "recognition probability of the map object",
            s.recognition_probability, p_uav, "")
    row("frames", "frames / photos", film.frames, u.flight.get("photos"), "")
    vol = u.flight.get("data_volume_bytes")
    row("data_volume", "data volume", film.scanned_gigabytes, vol / 1e9 if vol else None, "GB")
    return rows


def _check_terrain(project: ProjectModel, area: Area | None) -> None:
    """``[terrain]``, parsed with the file, checked once before any plan: that there is an
    area to lay the photos over."""
    if project.terrain is not None and area is None:
        key = "dem" if project.terrain.config.dem is not None else "ground_elevation_m"
        raise InputError(project.at("terrain", key), "needs an area "
                         "to lay the photos over ([area] width_m × length_m, polygon or file)")


def plan_project(project: Project | ProjectModel) -> PlanResult:
    """Compute the specification for a validated project.

    Parameters
    ----------
    project : Project or ProjectModel
        The loaded project file (parsed here into its model,
        :func:`scanplan.project.model.build_model`) or its model.

    Raises
    ------
    InputError
        Naming the project key and its line for out-of-range values.
    """
    if isinstance(project, Project):
        project = build_model(project)  # every key checked once, here
    with one_version():  # every job of the plan reads one version of each norm set
        return _planned(project)


def _planned(project: ProjectModel) -> PlanResult:
    """:func:`plan_project` of the model."""
    area = project_area(project)  # checked even when no plan uses it
    _check_layout_keys(project, area)
    _check_terrain(project, area)
    film = _film(project, area) if project.film is not None else None
    uav = _uav(project, area) if project.uav is not None else None
    warnings: list[PlanWarning] = []
    if film:
        warnings.extend(film.job.plan.warnings)
        if film.recommended is None:
            warnings.append(PlanWarning("no_feasible_photo_scale", film.reason))
        if film.layout is not None:
            warnings.extend(layout_warnings(film.layout))
    if uav:
        warnings.extend(uav.job.plan.warnings)
        if uav.planned_height_m and uav.recommended_height_m and \
                uav.recommended_height_m < uav.planned_height_m:
            warnings.append(PlanWarning("height_lowered", uav.reason))
    comparison = _comparison(film, uav) if film and uav else []
    design = survey_design(project, film, uav)
    warnings.extend(design.warnings)
    warnings.extend(aircraft_warnings(project, uav, design))
    control = _control(project, uav, area)
    if control is not None:
        warnings.extend(control.warnings)
    layouts = {k: p.layout for k, p in (("uav", uav), ("film", film))
               if p is not None and p.layout is not None}
    backgrounds, warned = map_backgrounds(project, layouts)
    warnings.extend(warned)
    return PlanResult(project=project, meta=project.meta, film=film, uav=uav, comparison=comparison,
                      warnings=tuple(warnings), area=area, design=design, control=control,
                      backgrounds=backgrounds)


def _control(project: ProjectModel, uav: UavSpec | None, area: Area | None
             ) -> ControlSpec | None:
    """``[control]`` over the UAV flight (the DEM, when given, keeps markers off steep
    ground)."""
    if project.control is None:
        return None
    ground = None
    terrain = uav.terrain if uav is not None else None
    if terrain is not None and terrain.ground.dem is not None and area is not None:
        g = terrain.ground

        def ground(x: Any, y: Any) -> Any:
            return g.sample(x, y, area.plan_crs)
    return plan_control(project, uav.job if uav is not None else None, area, ground)

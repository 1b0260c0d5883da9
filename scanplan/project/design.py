"""The survey design (технический проект АФС): today's Russian norms applied to a plan.

Three checks beside the Instruction's constraints, each with its norm:

- the GSD against the largest GSD per plan scale, ГОСТ Р 59562-2021 Table Б.1 (the norm
  set's ``gsd_limits``): for a digital camera it is the constraint GL of the rules engine
  (here it is only read back for the sheet); for film the scanned ground pixel
  (scan pixel × Mc) is compared with the same table, for information;
- one photographing height per block (ГОСТ Р 59328-2021 §6.2.1, second draft):
  :func:`scanplan.core.blocks.block_height_check` on the ground of the plan — the DEM's
  samples under every photo's footprint (``[terrain] dem``), else ``[terrain]
  ground_elevation_m``; waived, with the reason printed, when the flight follows the relief
  (``[terrain] altitude_mode = "follow"``), as the draft's wording allows;
- the sun window and the flying days (:mod:`scanplan.geo.sun`) from ``[site]`` and
  ``[schedule]``.

:func:`survey_design` returns a :class:`SurveyDesign`; the reports render it (the survey
design sheet) and never recompute a number.
"""

from __future__ import annotations

import datetime as dt
from typing import Any

from ..core.blocks import BlockHeightCheck, block_height_check
from ..core.photoscale import height_at_photo_scale_m, scanned_ground_pixel_cm
from ..errors import InputError
from ..geo.layout import FlightLayout
from ..geo.sun import SunWindow, equal_sorties_s, flying_days, sun_windows, time_zone_at
from ..i18n.messages import Message
from ..rules.results import PlanWarning
from .model import ProjectModel
from .results import FilmSpec, GsdCompliance, SunPlan, SurveyDesign, UavSpec
from .site import area_site_warnings, site_of
from .sorties import SORTIE_DEFAULTS_MIN, sortie_length

__all__ = [
    "GsdCompliance",
    "SunPlan",
    "SurveyDesign",
    "block_rule",
    "design_dict",
    "layout_of",
    "layout_site",
    "layout_sorties_s",
    "survey_design",
    "terrain_ground_m",
]

DEFAULT_SCHEDULE_DAYS = 30
"""``[schedule] end_date`` defaults to this many days after the start."""
MAX_SCHEDULE_DAYS = 366
"""Longest schedule the sun window is computed for [days]."""


def _worst_gsd_m(uav: UavSpec) -> float:
    """The GSD at the highest flown height of the worst photo [m]: over relief
    (``[terrain]``) the photo highest above its ground — photos.csv's largest ``gsd_cm`` —
    times 1 + the height tolerance; on flat ground the plan's."""
    import numpy as np

    plan = uav.job.plan
    flat = float(plan.gsd_at_max_height_m)
    terrain = getattr(uav, "terrain", None)
    if terrain is None:
        return flat
    gsd_cm = np.asarray(terrain.layout.photos.columns.get("gsd_cm", ()), dtype=float)
    gsd_cm = gsd_cm[np.isfinite(gsd_cm)]
    if not gsd_cm.size:
        return flat
    up = 1.0 + plan.inputs.height_tolerance_up_pct / 100.0
    return max(flat, float(gsd_cm.max()) / 100.0 * up)


def _gsd_checks(project: ProjectModel, film: FilmSpec | None, uav: UavSpec | None
                ) -> tuple[list[GsdCompliance], list[PlanWarning]]:
    out: list[GsdCompliance] = []
    warnings: list[PlanWarning] = []
    area = project.norms.gsd_area or "general"
    if uav is not None:
        inp = uav.job.plan.inputs
        reason = project.norms.gsd_limit_reason
        ns = uav.job.norm_set
        row = (ns.gsd_limit(inp.map_scale, area) if inp.map_scale is not None
               and "GL" in ns.parameters["constraints"] else None)
        if inp.gsd_limit_m is not None and inp.map_scale is not None:
            plan = uav.job.plan
            gsd_m = _worst_gsd_m(uav)
            out.append(GsdCompliance(
                "digital", int(inp.map_scale), inp.gsd_limit_area,
                round(inp.gsd_limit_m * 100.0, 9),  # the table's cm, without float noise
                gsd_m * 100.0, gsd_m <= inp.gsd_limit_m * (1 + 1e-9),
                plan.binding == "GL", inp.gsd_limit_source,
                row.status if row is not None else ""))
        elif reason and row is not None:
            gsd_m = _worst_gsd_m(uav)
            out.append(GsdCompliance(
                "digital", int(inp.map_scale), row.area, row.max_gsd_cm, gsd_m * 100.0,
                gsd_m <= row.max_gsd_cm / 100.0 * (1 + 1e-9), False, row.source, row.status,
                reason))
            warnings.append(PlanWarning("recommendation_set_aside", Message(
                "recommendation_set_aside", reason=reason, what=Message(
                    "set_aside.gsd_limits", gsd=gsd_m * 100.0, limit=row.max_gsd_cm)),
                severity="info"))
    if film is not None and film.recommended is not None:
        ns = film.job.norm_set
        rules = film.job.plan.rules
        mk = film.job.plan.inputs.map_scale
        row = ns.gsd_limit(mk, area) if "GL" in rules.constraints else None
        if row is not None:
            s = film.recommended
            pixel = s.scanner_pixel_um or s.scan_pixel_um
            mc = s.checked_photo_scale  # over relief: the frame over the lowest ground
            ground_cm = float(scanned_ground_pixel_cm(pixel, mc))
            ok = ground_cm <= row.max_gsd_cm * (1 + 1e-9)
            out.append(GsdCompliance("film", int(mk), row.area, row.max_gsd_cm, ground_cm, ok,
                                     False, row.source))
            warnings.append(PlanWarning(
                "gsd_limit_film",
                Message("gsd_limit_film", scale=float(round(mc)), pixel=pixel,
                        ground=ground_cm,
                        verdict=Message("gsd_limit.within" if ok else "gsd_limit.over"),
                        limit=row.max_gsd_cm, map=mk, area=Message(f"gsd_area.{row.area}")),
                photo_scales=(s.photo_scale,), severity="info"))
    return out, warnings


def _flight_height_m(film: FilmSpec | None, uav: UavSpec | None) -> float | None:
    """The photographing height of the plan: the UAV's recommended height, else the film
    photo scale × focal length [m]."""
    if uav is not None and uav.recommended_height_m is not None:
        return float(uav.recommended_height_m)
    if film is not None and film.recommended is not None:
        return float(height_at_photo_scale_m(film.recommended.photo_scale,
                                             film.job.plan.inputs.focal_mm))
    return None


def _ground_samples(project: ProjectModel, film: FilmSpec | None, uav: UavSpec | None
                    ) -> tuple[Any, str] | None:
    """The ground elevations of the block [m] and where they come from.

    ``"dem"``: with a DEM, the lowest and highest ground under every photo's footprint
    and under its centre (the UAV terrain check's columns; for film the ground under
    every frame); ``"range"``: ``[terrain] ground_elevation_m``; None without either.
    """
    import numpy as np

    terrain = getattr(uav, "terrain", None)
    if terrain is not None and terrain.ground.source == "dem":
        return terrain_ground_m(project, terrain), "dem"
    ft = getattr(film, "terrain", None)
    if ft is not None and ft.ground_known and ft.ground_m is not None:
        z = np.asarray(ft.ground_m, dtype=float)
        z = z[np.isfinite(z)]
        if z.size:
            return np.append(z, ft.ground_low_m) if np.isfinite(ft.ground_low_m) else z, "dem"
    ground = project.terrain.ground_elevation_m if project.terrain is not None else None
    if ground is not None:
        return ground, "range"
    return None


def terrain_ground_m(project: ProjectModel, terrain: Any) -> Any:
    """The ground elevations a UAV terrain result flies over [m]: over a DEM the lowest and
    highest ground under every photo's footprint and its centre, else ``[terrain]
    ground_elevation_m``'s two ends (what the one-height rule is checked on)."""
    import numpy as np

    if terrain.ground.source == "dem":
        cols = terrain.layout.photos.columns
        parts = [np.asarray(cols[k], dtype=float).ravel()
                 for k in ("ground_min_m", "ground_max_m", "ground_m") if k in cols]
        z = np.concatenate(parts) if parts else np.zeros(0)
        z = z[np.isfinite(z)]
        return z if z.size else np.array([terrain.ground.low_m, terrain.ground.high_m])
    return np.array([terrain.ground.low_m, terrain.ground.high_m])


def block_rule(project: ProjectModel, ns: Any, ground_m: Any, height_m: float,
               mode: str | None) -> tuple[BlockHeightCheck | None, bool]:
    """The one-height rule (ГОСТ Р 59328 §6.2.1, second draft) for a block flown at
    ``height_m`` over ``ground_m`` in altitude ``mode``: (the check, whether it holds).

    It holds when the ground range is within the norm's share of the height, when the
    flight follows the relief (waived: the check is None) and when the project sets the
    rule aside (``[norms] block_relief_reason``: None).
    """
    if project.norms.block_relief_reason or mode == "follow":
        return None, True
    relief = _relief_class(project)
    pname = {"flat": "block_relief_flat_pct", "hilly": "block_relief_hilly_pct",
             "mountainous": "block_relief_mountain_pct"}[relief]
    check = block_height_check(ground_m, height_m, relief, float(ns.parameters[pname]))
    return check, not check.split_needed


def _block(project: ProjectModel, film: FilmSpec | None, uav: UavSpec | None
           ) -> tuple[BlockHeightCheck | None, str, list[PlanWarning], str, bool]:
    """The one-height rule (ГОСТ Р 59328 §6.2.1, second draft) on the block's ground:
    (check, its source, warnings, where the ground came from, waived)."""
    relief = _relief_class(project)
    samples = _ground_samples(project, film, uav)
    height = _flight_height_m(film, uav)
    if samples is None or height is None:
        return None, "", [], "", False
    ground, origin = samples
    ns = (uav.job.norm_set if uav is not None else film.job.norm_set)  # type: ignore[union-attr]
    pname = {"flat": "block_relief_flat_pct", "hilly": "block_relief_hilly_pct",
             "mountainous": "block_relief_mountain_pct"}[relief]
    check = block_height_check(ground, height, relief, float(ns.parameters[pname]))
    warnings = []
    waived = _flown_mode(project, uav) == "follow"
    set_aside = project.norms.block_relief_reason
    if set_aside:
        warnings.append(PlanWarning("recommendation_set_aside", Message(
            "recommendation_set_aside", reason=set_aside, what=Message(
                "set_aside.block_relief", pct=check.range_pct, limit=check.limit_pct)),
            severity="info"))
    elif waived:
        warnings.append(PlanWarning("block_height_waived", Message(
            "block_height_waived", range=check.range_m, pct=check.range_pct, h=height,
            limit=check.limit_pct, relief=Message(f"relief.{relief}")), severity="info"))
    elif check.split_needed:
        warnings.append(PlanWarning("block_split", Message(
            "block_split", range=check.range_m, pct=check.range_pct, h=height,
            limit=check.limit_pct, relief=Message(f"relief.{relief}"), n=check.blocks,
            bands=[Message("block.band", lo=lo, hi=hi) for lo, hi in check.bands_m])))
    return check, ns.parameter_sources.get(pname, ""), warnings, origin, waived


def _flown_mode(project: ProjectModel, uav: UavSpec | None) -> str | None:
    """The altitude mode the plan flies: the UAV terrain result's (the mode chosen when the
    project leaves it to scanplan), else the project's (a film plan flies ``constant``
    unless told otherwise); None without ``[terrain]``."""
    terrain = getattr(uav, "terrain", None)
    if terrain is not None:
        return str(terrain.mode)
    return project.terrain.config.altitude_mode if project.terrain is not None else None


def layout_of(spec: FilmSpec | UavSpec | None) -> FlightLayout | None:
    """The flight layout of a specification part, when the geography has laid one out
    (``job.layout``); None for the abstract block."""
    job = getattr(spec, "job", None)
    return getattr(job, "layout", None)


def layout_sorties_s(layout: FlightLayout | None) -> list[float] | None:
    """The flight time of each sortie of a layout [s], or None (no layout, no times, or no
    sortie limit given to the layout: it is then one flight, and the schedule's own
    estimate applies).

    >>> from scanplan.geo.layout import Sortie
    >>> class L:
    ...     sorties = (Sortie(1, (1, 2), 9000.0, 1500.0), Sortie(2, (3,), 4000.0, 700.0))
    ...     notes = {"max_flight_time_min": 25}
    >>> layout_sorties_s(L())
    [1500.0, 700.0]
    """
    if layout is None or not layout.sorties:
        return None
    notes = getattr(layout, "notes", {})
    if "max_flight_time_min" in notes and not notes["max_flight_time_min"]:
        return None  # laid out as one flight: the schedule's sortie time applies
    times = [float(s.time_s) for s in layout.sorties if s.time_s]
    return times or None


def layout_site(layout: FlightLayout | None) -> tuple[float, float] | None:
    """(lat, lon) of the area's centroid [°] when the layout is georeferenced, else None."""
    if layout is None or not layout.area.georeferenced or layout.area.centroid_lonlat is None:
        return None
    lon, lat = layout.area.centroid_lonlat
    return float(lat), float(lon)


def _area_of(film: FilmSpec | None, uav: UavSpec | None) -> Any:
    """The planned area (its layout's), or None."""
    layout = layout_of(uav) or layout_of(film) or getattr(film, "layout", None)
    return layout.area if layout is not None else None


def _relief_class(project: ProjectModel) -> str:
    """``[terrain] relief_class`` (flat without ``[terrain]``)."""
    return project.terrain.relief_class if project.terrain is not None else "flat"


def _sun(project: ProjectModel, film: FilmSpec | None, uav: UavSpec | None
         ) -> tuple[SunPlan | None, list[PlanWarning]]:
    site, schedule = project.site, project.schedule
    lat = site.lat_deg if site is not None else None
    lon = site.lon_deg if site is not None else None
    layout = layout_of(uav) or layout_of(film)
    centroid = layout_site(layout)
    if lat is None and lon is None and centroid is not None:  # [area] polygon: its centroid
        lat, lon = centroid
    offset = schedule.utc_offset_h if schedule is not None else None
    elev = schedule.min_sun_elevation_deg if schedule is not None else None
    platform = uav.job.plan.inputs.platform if uav is not None else "aircraft"
    sortie_d, turn_d = SORTIE_DEFAULTS_MIN.get(platform, SORTIE_DEFAULTS_MIN["uav"])
    # the one sortie length, the layout's too (scanplan.project.sorties)
    sortie = sortie_length(project, platform).minutes or sortie_d
    turn = schedule.turnaround_min if schedule is not None else None
    turn = turn_d if turn is None else turn
    assert sortie is not None
    start = schedule.start_date if schedule is not None else None
    if start is None or lat is None or lon is None:
        for key, value in (("lat_deg", lat), ("lon_deg", lon), ("start_date", start)):
            if value is None and (site is not None or schedule is not None):
                section = "schedule" if key == "start_date" else "site"
                raise InputError(project.at(section, key), "is required for the sun "
                                 "window: give [site] lat_deg, lon_deg and [schedule] "
                                 "start_date")
        return None, []
    assert schedule is not None
    end = schedule.end_date or start + dt.timedelta(days=DEFAULT_SCHEDULE_DAYS - 1)
    if end < start:
        raise InputError(project.at("schedule", "end_date"),
                         f"must not be before start_date {start.isoformat()}")
    if (end - start).days + 1 > MAX_SCHEDULE_DAYS:
        raise InputError(project.at("schedule", "end_date"),
                         f"the schedule may span at most {MAX_SCHEDULE_DAYS} days")
    zone = None if offset is not None else time_zone_at(lat, lon)
    ns = (uav.job.norm_set if uav is not None else film.job.norm_set)  # type: ignore[union-attr]
    source = "project"
    if elev is None:
        elev = float(ns.parameters["min_sun_elevation_deg"])
        source = ns.parameter_sources.get("min_sun_elevation_deg", "")
    dates = [start + dt.timedelta(days=i) for i in range((end - start).days + 1)]
    windows = sun_windows(dates, lat, lon, elev, utc_offset_h=offset, time_zone=zone)
    flight_s = uav.job.plan.flight.get("flight_time_s") if uav is not None else None
    from_layout = layout_sorties_s(layout)
    sortie_s = sortie * 60.0  # the planned sortie; the layout's sorties are at most this long
    days = None
    warnings: list[PlanWarning] = []
    if not any(w.hours > 0 for w in windows):
        warnings.append(PlanWarning("sun_no_window", Message(
            "sun_no_window", elev=elev, start=start.isoformat(), end=end.isoformat(),
            top=max(w.max_elevation_deg for w in windows))))
    elif flight_s or from_layout:
        # the layout's sorties when the geography has split the flight, else equal ones
        sorties = from_layout or equal_sorties_s(float(flight_s), sortie_s)
        days = flying_days(windows, sorties, turn * 60.0)
        if days.days is None:
            warnings.append(PlanWarning("sun_dates_short", Message(
                "sun_dates_short", n=days.sorties, flown=sum(days.sorties_per_day),
                start=start.isoformat(), end=end.isoformat())))
    return SunPlan(lat, lon, windows[0].utc_offset_h, elev, source, start, end, windows,
                   sortie_s, turn * 60.0, float(flight_s) if flight_s else None, days,
                   zone), warnings


def survey_design(project: ProjectModel, film: FilmSpec | None, uav: UavSpec | None
                  ) -> SurveyDesign:
    """The survey design checks of a planned project.

    Parameters
    ----------
    project : ProjectModel
        The parsed project file (``[terrain]``, ``[site]``, ``[schedule]``, ``[norms]
        gsd_area`` are read here).
    film, uav : FilmSpec or UavSpec or None
        The specification's parts.

    Raises
    ------
    InputError
        Naming the project key and its line for an out-of-range value.
    """
    gsd, w1 = _gsd_checks(project, film, uav)
    block, block_source, w2, block_ground, waived = _block(project, film, uav)
    sun, w3 = _sun(project, film, uav)
    w3 = area_site_warnings(_area_of(film, uav), site_of(project)) + w3
    ns = uav.job.norm_set if uav is not None else film.job.norm_set if film is not None \
        else None
    status = ns.parameter_status if ns is not None else {}
    relief = _relief_class(project)
    pname = {"flat": "block_relief_flat_pct", "hilly": "block_relief_hilly_pct",
             "mountainous": "block_relief_mountain_pct"}.get(relief, "block_relief_flat_pct")
    sun_status = ("" if sun is None or sun.elevation_source == "project"
                  else status.get("min_sun_elevation_deg", ""))
    return SurveyDesign(tuple(gsd), block, block_source, sun, tuple(w1 + w2 + w3),
                        block_ground, waived, status.get(pname, ""),
                        project.norms.block_relief_reason, sun_status)


def design_dict(design: SurveyDesign) -> dict[str, Any]:
    """The survey design as JSON-ready data (``plan --json`` key ``survey_design``)."""
    out: dict[str, Any] = {"gsd_limits": [
        {"workflow": g.workflow, "map_scale": g.map_scale, "area": g.area,
         "limit_cm": g.limit_cm, "gsd_cm": round(g.gsd_cm, 4), "complies": g.complies,
         "binding": g.binding, "source": g.source, "status": g.status,
         "set_aside": g.set_aside or None} for g in design.gsd]}
    b = design.block
    if b is not None:
        out["block_height"] = {
            "relief_class": b.relief_class, "limit_pct": b.limit_pct,
            "flight_height_m": b.flight_height_m, "ground_min_m": b.ground_min_m,
            "ground_max_m": b.ground_max_m, "range_m": b.range_m,
            "range_pct": round(b.range_pct, 3),
            # the rule applies unless the flight follows the relief or the project sets it
            # aside: only then does the range split the block (exceeds_limit says the range)
            "split_needed": b.split_needed and not (design.block_waived
                                                    or design.block_set_aside),
            "exceeds_limit": b.split_needed,
            "blocks": b.blocks if not (design.block_waived or design.block_set_aside) else 1,
            "bands_m": [list(x) for x in b.bands_m],
            "samples": b.samples, "ground": design.block_ground,
            "waived": design.block_waived, "source": design.block_source,
            "status": design.block_status, "set_aside": design.block_set_aside or None}
    s = design.sun
    if s is not None:
        lo, hi = s.window_hours
        out["sun"] = {
            "lat_deg": s.lat_deg, "lon_deg": s.lon_deg, "utc_offset_h": s.utc_offset_h,
            "time_zone": s.time_zone,
            "min_elevation_deg": s.min_elevation_deg, "start_date": s.start_date.isoformat(),
            "end_date": s.end_date.isoformat(), "window_hours_min": lo,
            "window_hours_max": hi,
            "first_window": _window_dict(s.windows[0]),
            "sortie_time_min": s.sortie_time_s / 60.0, "turnaround_min": s.turnaround_s / 60.0,
            "flight_time_min": None if s.flight_time_s is None else s.flight_time_s / 60.0,
            "sorties": s.days.sorties if s.days else None,
            "flying_days": s.days.days if s.days else None,
            "last_date": s.days.last_date.isoformat() if s.days and s.days.last_date else None}
    return out


def _window_dict(w: SunWindow) -> dict[str, Any]:
    return {"date": w.date.isoformat(),
            "start": w.start_local.strftime("%H:%M") if w.start_local else None,
            "end": w.end_local.strftime("%H:%M") if w.end_local else None,
            "hours": round(w.hours, 2), "max_elevation_deg": round(w.max_elevation_deg, 2)}

"""The worst photo over the relief: the ground and geometry of :mod:`scanplan.geo.terrain`
checked by the constraints of :mod:`scanplan.rules.terrain`.

:func:`uav_terrain` gives every photo of a UAV block its ground, altitude, height above
ground, figures at that height and overlaps, and checks the plan's limits at the worst
photo; :func:`film_terrain` gives every film frame its local photo scale and the scan pixel
at the frame with the largest Mc. The geometry (which ground, which altitude) stays in
``geo/``, the constraints in ``rules/``; this module only joins them.
"""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np

from ..core.photoscale import footprint_side_m
from ..geo import terrain as G
from ..geo.layout import FlightLayout, Photos
from ..geo.terrain_film import FilmTerrain, frame_scales
from ..geo.terrain_overlaps import photo_overlaps
from ..i18n.messages import Message
from ..rules import terrain as RT
from ..rules.results import ScanRules, UavInputs, UavPlan

__all__ = ["film_terrain", "uav_terrain", "with_photo_figures"]


def uav_terrain(layout: FlightLayout, ground: G.Ground, inp: UavInputs, plan: UavPlan,
                mode: str = "constant",
                follow_tolerance_m: float = G.DEFAULT_FOLLOW_TOLERANCE_M,
                figures: bool = True) -> G.TerrainResult:
    """Every photo at its own AGL; the constraints at the worst photo.

    Steps: the photos in strip order with their ground
    (:func:`scanplan.geo.terrain.worst_ground`: the altitudes of the mode, the lowest and
    highest ground under every footprint and stretch of path) and their AGL; the figures at
    that AGL (:func:`scanplan.rules.terrain.photo_figures`); the overlaps with the
    neighbours (:func:`scanplan.geo.terrain_overlaps.photo_overlaps`); the ground each photo
    is checked at (:func:`scanplan.rules.terrain.checked_ground_m`); the strips, the
    closed-form maximum height and the warnings.

    Parameters
    ----------
    layout : FlightLayout
        Flight lines and photo centres (from the planned height ``inp.height_m``).
    ground : Ground
        From :func:`scanplan.geo.terrain.ground_under`.
    inp : UavInputs
        The camera and flight; ``height_m`` is the planned AGL over the reference ground [m].
    plan : UavPlan
        The flat-ground plan: its limits as planned heights (``max_height_m``, ``binding``).
    mode : str
        ``constant``, ``strip`` or ``follow``.
    follow_tolerance_m : float
        How far the AGL may exceed the planned height in ``follow`` mode [m].
    figures : bool
        Every photo's GSD, L and recognition probability at its AGL (the MTF chain at
        every photo); False leaves the layout's flat values, for a plan only compared
        (:func:`with_photo_figures` adds them later).

    Returns
    -------
    TerrainResult
    """
    ph = layout.photos
    n = len(ph)
    order = G.strip_order(ph)
    cols = {k: np.asarray(v)[order] for k, v in ph.columns.items()}
    strip = cols["strip"].astype(np.int64)
    h = float(inp.height_m)
    g0 = ground.centre_m[order] if ground.centre_m.size == n else np.full(n, np.nan)
    wg = G.worst_ground(layout, ground, cols, g0, mode, h, follow_tolerance_m,
                        float(footprint_side_m(inp.sensor_width_mm, 1.0, inp.focal_mm)),
                        float(footprint_side_m(inp.sensor_height_mm, 1.0, inp.focal_mm)))
    g_alt, alt = wg.path_high_m, wg.altitude_m
    agl = alt - wg.footprint_low_m
    up = inp.height_tolerance_up_pct / 100.0
    cols.update(ground_m=wg.centre_m, altitude_m=alt, agl_m=agl,
                **(RT.photo_figures(inp, agl) if figures else {}))
    ov = photo_overlaps(layout, cols, alt, ground, inp.sensor_width_mm, inp.sensor_height_mm,
                        inp.focal_mm, inp.height_tolerance_down_pct / 100.0)
    cols.update(ground_min_m=wg.footprint_low_m, ground_max_m=wg.footprint_high_m,
                forward_overlap_pct=ov.forward_photo, side_overlap_pct=ov.side_photo)
    limit = plan.max_height_m
    g_res = RT.checked_ground_m(plan, wg.footprint_low_m, wg.path_low_m)
    strips = G.strip_rows(cols, g_res, g_alt, limit)
    worst_res = int(cols["photo"][int(np.argmax(alt - g_res))]) if n else 0
    both = np.fmin(ov.forward_photo, ov.side_photo)
    worst_ov = int(cols["photo"][int(np.nanargmin(both))]) if np.isfinite(both).any() else 0
    max_h = None
    if limit is not None:
        max_h = G.max_height_above_reference_m(limit, g_res, g_alt, strip, mode,
                                               follow_tolerance_m)
    warnings = list(ground.warnings)
    warnings += RT.resolution_warnings(strips, plan, mode, h, max_h, up)
    warnings += RT.overlap_warnings(inp, ov.forward, ov.forward_pct, ov.side, ov.side_pct,
                                    cols["photo"])
    return G.TerrainResult(
        layout=G.terrain_layout(layout, cols, order, strips, mode), mode=mode, height_m=h,
        strips=strips, max_height_m=max_h, binding=plan.binding,
        worst_resolution_photo=worst_res, worst_overlap_photo=worst_ov,
        min_forward_overlap_pct=(float(np.nanmin(ov.forward_pct)) if ov.forward_pct.size
                                 else math.nan),
        min_side_overlap_pct=float(np.nanmin(ov.side_pct)) if ov.side_pct.size else math.nan,
        waypoints=G.altitude_waypoints(cols, mode), warnings=tuple(warnings), ground=ground,
        path=G.path_summary(alt, wg))


def with_photo_figures(res: G.TerrainResult, inp: UavInputs) -> G.TerrainResult:
    """``res`` with every photo's GSD, L and recognition probability at its own AGL
    (:func:`scanplan.rules.terrain.photo_figures`), for a result checked without them."""
    ph = res.layout.photos
    cols = dict(ph.columns)
    cols.update(RT.photo_figures(inp, np.asarray(cols["agl_m"], dtype=float)))
    return replace(res, layout=replace(res.layout, photos=Photos(cols)))


def film_terrain(layout: FlightLayout, ground: G.Ground, rules: ScanRules, *, map_scale: float,
                 photo_scale: float, relief_interval_m: float, focal_mm: float,
                 frame_along_mm: float, forward_overlap_pct: float,
                 resolving_power_lpmm: float, object_size_m: float = math.nan,
                 shape_coefficient: float = math.nan, mode: str = "constant",
                 follow_tolerance_m: float = G.DEFAULT_FOLLOW_TOLERANCE_M) -> FilmTerrain:
    """The local photo scale of every frame and the scan pixel at the smallest of them.

    The aircraft flies the planned Mc over the reference ground (the highest, by the
    altitude mode): A = g_ref + f·Mc. A frame over ground g has Mc = (A − g)/f
    (:func:`scanplan.geo.terrain_film.frame_scales`); the frame over the lowest ground
    binds, and the engine is run there and at the planned Mc, flat ground, for comparison
    (:func:`scanplan.rules.terrain.film_at_worst_frame`).
    """
    fs = frame_scales(layout, ground, photo_scale=photo_scale, focal_mm=focal_mm, mode=mode,
                      follow_tolerance_m=follow_tolerance_m)
    ph = layout.photos
    n = len(ph)
    inverse = np.empty(n, dtype=np.int64)
    inverse[fs.order] = np.arange(n)
    i = fs.worst
    mc_hi = float(fs.mc[i]) if n else photo_scale
    wf = RT.film_at_worst_frame(
        rules, photo_scale=photo_scale, worst_scale=mc_hi, map_scale=map_scale,
        relief_interval_m=relief_interval_m, focal_mm=focal_mm, frame_along_mm=frame_along_mm,
        forward_overlap_pct=forward_overlap_pct, resolving_power_lpmm=resolving_power_lpmm,
        object_size_m=object_size_m, shape_coefficient=shape_coefficient)
    frame = int(np.asarray(ph["photo"])[fs.order][i]) if n else 0
    strip_i = int(np.asarray(ph["strip"])[fs.order].astype(np.int64)[i]) if n else 0
    warnings = list(ground.warnings)
    known = ground.dem is not None
    where = (Message("terrain_film_where.dem", frame=frame, strip=strip_i) if known
             else Message("terrain_film_where.range", low=ground.low_m))
    note = RT.film_scale_warning(wf.scan_pixel_um, wf.scan_pixel_planned_um, wf.binding,
                                 fs.mc_min, mc_hi, where)
    if note is not None:
        warnings.append(note)
    return FilmTerrain(photo_scale=photo_scale, altitude_m=fs.altitude_m[inverse],
                       mc=fs.mc[inverse], mc_min=fs.mc_min, mc_max=mc_hi,
                       binding_frame=frame, binding_strip=strip_i,
                       scan_pixel_um=wf.scan_pixel_um,
                       scan_pixel_planned_um=wf.scan_pixel_planned_um, binding=wf.binding,
                       warnings=tuple(warnings), ground_m=fs.ground_m[inverse],
                       binding_planned=wf.binding_planned, ground_known=known,
                       ground_low_m=float(ground.low_m))

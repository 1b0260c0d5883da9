"""Result objects → plain dicts (the one shape that --json and the reports print)."""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import asdict
from typing import Any

import numpy as np

from ..i18n.messages import Message, params_json
from ..norms import NormSet
from ..rules.film import PlanWarning, ScanPlan
from ..rules.uav import UavPlan

__all__ = ["area_dict", "layout_dict", "norm_set_dict", "plan_result_dict", "scale_value",
           "scan_plan_dict", "uav_plan_dict", "warning_dict"]


def scale_value(x: float) -> int | float:
    """A scale denominator as an int when it is whole (10000, not 10000.0)."""
    return int(x) if math.isfinite(x) and float(x).is_integer() else x


_PLAIN = (str, int, bool, type(None))


def _clean(x: Any) -> Any:
    """``x`` with every non-finite float None, mappings as dicts, sequences as lists."""
    kind = type(x)  # the plain types first, without the ABC checks below (same answers)
    if kind is dict:
        return {k: _clean(v) for k, v in x.items()}
    if kind is float:
        return x if math.isfinite(x) else None
    if kind in _PLAIN:
        return x
    if kind is list or kind is tuple:
        return [_clean(v) for v in x]
    if isinstance(x, float) and not math.isfinite(x):
        return None
    if isinstance(x, Mapping):  # a dict, or a name in both languages (i18n Names)
        return {k: _clean(v) for k, v in x.items()}
    if isinstance(x, list | tuple):
        return [_clean(v) for v in x]
    return x


def area_dict(area: Any) -> dict[str, Any]:
    """The contract area: source, planning CRS (code and name), the CRS it was given in,
    km², perimeter, centroid (lon, lat); ``georeferenced`` False for the abstract block."""
    return _clean({
        "source": area.source, "file": area.source_file, "feature": area.source_feature,
        "layer": area.source_layer, "crs": area.plan_crs, "crs_name": area.plan_crs_name,
        "input_crs": area.input_crs, "georeferenced": area.georeferenced,
        "area_km2": area.area_km2, "perimeter_km": area.perimeter_km,
        "centroid_lonlat": list(area.centroid_lonlat) if area.centroid_lonlat else None})


def layout_dict(layout: Any) -> dict[str, Any]:
    """A flight layout without its photo centres (those go to the exported files): the
    direction, spacing, base, counts, length and time, ``strips[]`` and ``sorties[]``.

    Strip ends are in the planning CRS (``start_xy_m``/``end_xy_m``) and, for a
    georeferenced area, in WGS 84 (``start_lonlat``/``end_lonlat``, lon first)."""
    ends = np.array([[*s.start_xy_m, *s.end_xy_m] for s in layout.strips]).reshape(-1, 4)
    lonlat = None
    if layout.area.georeferenced and len(ends):
        from ..geo.crs import transformer

        tr = transformer(layout.area.plan_crs, 4326)
        lon0, lat0 = tr.transform(ends[:, 0], ends[:, 1])
        lon1, lat1 = tr.transform(ends[:, 2], ends[:, 3])
        lonlat = np.column_stack([lon0, lat0, lon1, lat1])
    strips = []
    for i, s in enumerate(layout.strips):
        row: dict[str, Any] = {
            "number": s.number, "sortie": s.sortie, "photos": s.photos,
            "first_photo": s.first_photo, "length_m": s.length_m, "segments": s.segments,
            "start_xy_m": list(s.start_xy_m), "end_xy_m": list(s.end_xy_m)}
        if lonlat is not None:
            row["start_lonlat"] = [float(lonlat[i, 0]), float(lonlat[i, 1])]
            row["end_lonlat"] = [float(lonlat[i, 2]), float(lonlat[i, 3])]
        if layout.crosshatch:
            row["direction_deg"] = layout.strip_direction_deg(s.number)
        strips.append(row)
    cross = ({"crosshatch": True, "cross_direction_deg": layout.cross_direction_deg,
              "first_pass_strips": layout.first_pass_strips,
              "pass_transit_m": layout.notes.get("pass_transit_m")}
             if layout.crosshatch else {})
    return _clean({**cross,
        "kind": layout.kind, "direction_deg": layout.direction_deg,
        "line_spacing_m": layout.spacing_m, "base_m": layout.base_m,
        "footprint_across_m": layout.footprint_across_m,
        "footprint_along_m": layout.footprint_along_m,
        "extension_bases": layout.extension_bases, "turn": layout.turn,
        "n_strips": len(layout.strips),
        "n_photos": int(layout.notes.get("photos", len(layout.photos))),
        "n_sorties": len(layout.sorties),
        "flight_length_m": layout.flight_length_m, "turn_length_m": layout.turn_length_m,
        "flight_time_s": layout.flight_time_s, "speed_ms": layout.speed_ms,
        "bridged_m": layout.notes.get("bridged_m"),
        "feasible": layout.feasible, "reason": layout.reason,
        "strips": strips,
        "sorties": [{"number": k.number, "strips": list(k.strips), "length_m": k.length_m,
                     "time_s": k.time_s} for k in layout.sorties]})


def warning_dict(w: PlanWarning) -> dict[str, Any]:
    """A warning: ``code``, ``message`` (English), ``photo_scales``, ``severity`` and the
    message's ``params`` (the numbers and names in it; a nested message as
    ``{"code", "params"}``)."""
    doc = asdict(w)
    if isinstance(w.message, Message):
        doc["params"] = params_json(w.message.params)
    return doc


def norm_set_dict(ns: NormSet, map_scale: float | None = None) -> dict[str, Any]:
    """Which norm set, and which of its rows a plan used."""
    used_obj = ns.object_for(map_scale) if map_scale is not None else None
    return {
        "name": ns.name,
        "title": ns.title,
        "path": str(ns.path),
        "bundled": ns.bundled,
        "imported_from": ns.imported_from or None,
        "imported_at": ns.imported_at or None,
        "parameters": {k: (list(v) if isinstance(v, tuple) else v)
                       for k, v in ns.parameters.items()},
        "parameter_sources": dict(ns.parameter_sources),
        "object_row": asdict(used_obj) if used_obj else None,
    }


def scan_plan_dict(plan: ScanPlan, ns: NormSet | None = None) -> dict[str, Any]:
    """The ``scanplan scan --json`` document (keys per spec/interface.md, plus extras)."""
    inp = plan.inputs
    scenarios = []
    for s in plan.scenarios:
        constraints = {}
        for c in s.constraints:
            entry: dict[str, Any] = {"pixel_um": c.pixel_um, "margin_um": c.margin_um,
                                     "margin_pct": c.margin_pct, "binding": c.binding,
                                     "name": c.name, "reason": c.reason,
                                     "equation": c.equation}
            entry.update(c.details)
            constraints[c.id] = entry
        scenarios.append({
            "photo_scale": scale_value(s.photo_scale),
            "photo_to_map_ratio": s.photo_to_map_ratio,
            "constraints": constraints,
            "binding": s.binding,
            "scan_pixel_um": s.scan_pixel_um,
            "explanation": s.explanation,
            "scanner_pixel_um": s.scanner_pixel_um,
            "frame_megabytes": s.frame_megabytes,
            "resolution_on_ground_mm": s.resolution_on_ground_mm,
            "required_resolving_power_lpmm": s.required_resolving_power_lpmm,
            "recognition_probability": s.recognition_probability,
        })
    doc: dict[str, Any] = {
        "inputs": {
            "map_scale": scale_value(inp.map_scale),
            "relief_interval_m": inp.relief_interval_m,
            "photo_scales": [scale_value(x) for x in inp.photo_scales],
            "camera": inp.camera or None,
            "focal_mm": inp.focal_mm,
            "frame_mm": [inp.frame_width_mm, inp.frame_along_mm],
            "resolving_power_lpmm": inp.resolving_power_lpmm,
            "forward_overlap_pct": inp.forward_overlap_pct,
            "object": asdict(inp.object) if inp.object else None,
            "scanner": inp.scanner or None,
            "scanner_steps_um": list(inp.scanner_steps_um),
            "bands": inp.bands,
            "bits_per_band": inp.bits_per_band,
        },
        "scenarios": scenarios,
        "interpretation_limit_photo_scale": plan.interpretation_limit_photo_scale,
        "max_photo_scales": [asdict(r) for r in plan.max_photo_scales],
        "sweep": plan.sweep,
        "warnings": [warning_dict(w) for w in plan.warnings],
    }
    if ns is not None:
        doc["norms"] = norm_set_dict(ns, inp.map_scale)
    return _clean(doc)


def uav_plan_dict(plan: UavPlan, ns: NormSet | None = None) -> dict[str, Any]:
    """The ``scanplan uav --json`` document (keys per spec/interface.md, plus extras)."""
    inp = plan.inputs
    doc: dict[str, Any] = {
        "inputs": {k: v for k, v in asdict(inp).items() if k not in ("objects", "map_object")},
        "heights_m": plan.heights_m,
        "gsd_m": plan.gsd_m,
        "gsd_at_max_height_m": plan.gsd_at_max_height_m,
        "nyquist_lpmm": plan.nyquist_lpmm,
        "resolving_power_lpmm": plan.resolving_power_lpmm,
        "resolving_power_corner_lpmm": plan.resolving_power_corner_lpmm,
        "resolvable": plan.resolvable,
        "sensor_limited": plan.sensor_limited,
        "ground_resolution_m": plan.ground_resolution_m,
        "ground_resolution_corner_m": plan.ground_resolution_corner_m,
        "ground_resolution_at_max_height_m": plan.ground_resolution_at_max_height_m,
        "ground_resolution_to_gsd": plan.ground_resolution_to_gsd,
        "motion_blur_px": plan.motion_blur_px,
        "max_exposure_s": plan.max_exposure_s,
        "max_speed_ms": plan.max_speed_ms,
        "tilted_corner_gsd_m": plan.tilted_corner_gsd_m,
        "flight": _flight_json(plan.flight),
        "recognition": [asdict(r) for r in plan.recognition],
        "map_object": asdict(inp.map_object) if inp.map_object else None,
        "constraints": {lim.id: {k: v for k, v in asdict(lim).items() if k != "id"}
                        for lim in plan.limits},
        "max_height_m": plan.max_height_m,
        "max_planned_height_m": plan.max_height_m,
        "max_flown_height_m": plan.max_flown_height_m,
        "ceiling_m": plan.ceiling_m,
        "constraints_max_height_m": plan.constraints_max_height_m,
        "height_accuracy": plan.height_accuracy,
        "binding": plan.binding,
        "warnings": [warning_dict(w) for w in plan.warnings],
        "mtf_centre": plan.mtf_centre,
        "height_curve": plan.height_curve,
    }
    if ns is not None:
        doc["norms"] = norm_set_dict(ns, inp.map_scale)
    return _clean(doc)


def _film_spec(f: Any) -> dict[str, Any]:
    """``specification.film`` of ``plan --json``: the recommended photo scale and scan pixel,
    the margins, the frames, the flat-ground figures of a ``[terrain]`` plan, the layout."""
    rec = f.recommended
    out: dict[str, Any] = {
        "recommended_photo_scale": scale_value(rec.photo_scale) if rec else None,
        "archive": f.archive,
        "reason": f.reason,
        "binding": rec.binding if rec else None,
        "scan_pixel_um": rec.scan_pixel_um if rec else None,
        "scanner_pixel_um": rec.scanner_pixel_um if rec else None,
        "margins_pct": {c.id: c.margin_pct for c in rec.constraints} if rec else None,
        "recognition_probability": rec.recognition_probability if rec else None,
        "frame_megabytes": rec.frame_megabytes if rec else None,
        "frames": f.frames, "strips": f.strips, "scanned_gigabytes": f.scanned_gigabytes,
        "side_overlap_pct": f.side_overlap_pct,
    }
    flat = getattr(f, "flat", None)
    if rec is not None and flat is not None:  # [terrain]: held at the worst frame
        out["local_photo_scale"] = rec.local_photo_scale
        out["flat_ground"] = {
            "photo_scale": scale_value(flat.photo_scale), "binding": flat.binding,
            "scan_pixel_um": flat.scan_pixel_um,
            "scanner_pixel_um": flat.scanner_pixel_um,
            "frame_megabytes": flat.frame_megabytes}
    if f.layout is not None:
        out["layout"] = layout_dict(f.layout)
    return out


def _uav_spec(u: Any) -> dict[str, Any]:
    """``specification.uav`` of ``plan --json``: the heights, the binding constraint, the
    ground resolution, the overlaps, the motion, the flight's figures, the layout."""
    p = u.job.plan
    out: dict[str, Any] = {
        "planned_height_m": u.planned_height_m,
        "recommended_height_m": u.recommended_height_m,
        "max_height_m": u.max_height_m, "max_planned_height_m": u.max_height_m,
        "max_flown_height_m": p.max_flown_height_m,
        "recommended_flown_height_m": p.heights_m["max"],
        "ceiling_m": p.ceiling_m,
        "constraints_max_height_m": p.constraints_max_height_m,
        "height_accuracy_m": p.height_accuracy.get("height_accuracy_m"),
        "sigma_z_m": p.height_accuracy.get("sigma_z_at_highest_flown_height_m"),
        "reason": u.reason, "choice": getattr(u, "choice", None), "binding": p.binding,
        "height_tolerance_pct": p.inputs.height_tolerance_up_pct,
        "gsd_m": p.gsd_m, "ground_resolution_m": p.ground_resolution_m,
        "ground_resolution_to_gsd": p.ground_resolution_to_gsd,
        "recognition": [asdict(r) for r in p.recognition],
        "forward_overlap_pct": p.inputs.forward_overlap_pct,
        "side_overlap_pct": p.inputs.side_overlap_pct,
        "orientation": p.inputs.orientation, "platform": p.inputs.platform,
        "motion_blur_px": p.motion_blur_px, "max_exposure_s": p.max_exposure_s,
        "max_speed_ms": p.max_speed_ms,
        # the flight's figures (its JPEG estimate is uav.flight's, as it always was)
        **{k: v for k, v in p.flight.items() if k not in _JPEG_KEYS},
    }
    if u.layout is not None:
        out["layout"] = _uav_layout_dict(u)
    return out


def plan_result_dict(result: Any) -> dict[str, Any]:
    """The ``scanplan plan --json`` document: project, film, uav, specification, warnings."""
    from dataclasses import asdict as _asdict

    doc: dict[str, Any] = {"project": {"file": str(result.project.path),
                                       **_asdict(result.meta)}}
    if getattr(result, "area", None) is not None:
        doc["area"] = area_dict(result.area)
    spec: dict[str, Any] = {}
    if result.film:
        doc["film"] = scan_plan_dict(result.film.job.plan, result.film.job.norm_set)
        spec["film"] = _film_spec(result.film)
    if result.uav:
        doc["uav"] = uav_plan_dict(result.uav.job.plan, result.uav.job.norm_set)
        spec["uav"] = _uav_spec(result.uav)
    if result.comparison:
        spec["comparison"] = result.comparison
    if getattr(result, "control", None) is not None:
        from ..project.control import control_dict

        spec["control"] = control_dict(result.control)
    doc["specification"] = spec
    if getattr(result, "design", None) is not None:
        from ..project.design import design_dict

        doc["survey_design"] = design_dict(result.design)
    terrain = terrain_dict(result)
    if terrain:
        doc["terrain"] = terrain
    doc["warnings"] = [warning_dict(w) for w in result.warnings]
    return _clean(doc)


def _uav_layout_dict(uav: Any) -> dict[str, Any]:
    """The UAV flight layout with the plans compared (``alternatives``, the recommended one
    marked: docs/plan-choice.md) when there was a choice."""
    out = layout_dict(uav.layout)
    if getattr(uav, "alternatives", ()):
        from ..project.alternatives import alternatives_dicts

        out["alternatives"] = alternatives_dicts(uav.alternatives)
    return out


def terrain_dict(result: Any) -> dict[str, Any]:
    """The ``terrain`` section of ``plan --json`` (issue 12): the ground, the altitude mode
    and frame, the AGL range, the worst photos, the maximum height over the relief, every
    strip's altitude and maximum altitude (``uav``); the local photo scales (``film``).
    Empty without ``[terrain]``. Per-photo elevations and AGL are in the exported files."""
    out: dict[str, Any] = {}
    uav = getattr(result, "uav", None)
    if uav is not None and getattr(uav, "terrain", None) is not None:
        out["uav"] = uav.terrain.summary()
    film = getattr(result, "film", None)
    ft = getattr(film, "terrain", None) if film is not None else None
    if ft is not None:
        out["film"] = {"photo_scale": ft.photo_scale, "photo_scale_min": ft.mc_min,
                       "photo_scale_max": ft.mc_max, "binding_frame": ft.binding_frame,
                       "binding_strip": ft.binding_strip, "binding": ft.binding,
                       "scan_pixel_um": ft.scan_pixel_um,
                       "scan_pixel_at_planned_scale_um": ft.scan_pixel_planned_um,
                       "binding_at_planned_scale": ft.binding_planned,
                       "ground_from_dem": ft.ground_known,
                       "specified_at_binding_frame": getattr(film, "flat", None) is not None,
                       "rejected_photo_scales": [
                           {"photo_scale": r.photo_scale, "photo_scale_max": t.mc_max}
                           for r, t in getattr(film, "rejected", ())]}
    return out


_JPEG_KEYS = ("data_volume_jpeg_bytes", "jpeg_compression_ratio")


def _flight_json(flight: dict[str, Any]) -> dict[str, Any]:
    """The flight dict as the plan carries it (with a data volume: its JPEG estimate
    ``data_volume_jpeg_bytes`` and the ``jpeg_compression_ratio`` assumed)."""
    return dict(flight)

"""A plan's inputs: what it was computed from, each number with the input registry's unit
and decimals (:mod:`scanplan.project.inputs`) — the workbook's Inputs sheet, the PDF's
film and digital-camera sections and the terminal's heading lay them out
(:func:`film_inputs`, :func:`uav_inputs`)."""

from __future__ import annotations

from typing import Any

from ...i18n.messages import Names
from ...project.inputs import get
from .table import Column, Named, Row, Table

__all__ = ["film_inputs", "uav_inputs"]


def _number(name: str, value: Any, key: str = "") -> Row:
    """A number given by the user: the registry record's unit and decimals."""
    rec = get(name, "film")
    unit = "scale" if rec.kind in ("scale", "scales") else rec.unit
    return Row(key or name, (value,), unit=unit, digits=rec.digits)


def film_inputs(plan: Any) -> Table:
    """The inputs of a film scan plan, in the order the Inputs sheet lists them.

    Parameters
    ----------
    plan : ScanPlan

    Returns
    -------
    Table
        One column; rows keyed by the input's Python name
        (:func:`scanplan.project.inputs.get`), each number with its record's unit
        (``"scale"`` for a scale) and decimals:
        ``map_scale``, ``relief_interval_m``, ``photo_scales`` (the scales as one value),
        ``camera`` (field ``name``: the camera's own name), ``focal_mm``, ``frame_mm`` (a
        pair: across, along; the record has no decimals), ``resolving_power_lpmm``,
        ``forward_overlap_pct``, ``object`` (the map object or None; with one
        ``object_size_m``, ``shape`` (its id), ``shape_coefficient`` and ``object_source``
        (a :class:`~scanplan.messages.Message`)), ``probability``, ``height_formula``
        (field ``used``: whether the height accuracy constraint is),
        ``pr_coefficient``, ``scanner``, with steps ``scanner_steps_um`` and with candidate
        pixels ``candidate_pixels_um`` (decimals of ``pixel_um``), ``bands`` and
        ``bits_per_band``.
    """
    inp, rules = plan.inputs, plan.rules
    rows = [_number("map_scale", inp.map_scale),
            _number("relief_interval_m", inp.relief_interval_m),
            _number("photo_scales", tuple(inp.photo_scales)),
            Row("camera", (inp.camera,), fields={"name": inp.camera_name}),
            _number("focal_mm", inp.focal_mm),
            Row("frame_mm", ((inp.frame_width_mm, inp.frame_along_mm),),
                unit=get("frame_mm", "film").unit),
            _number("resolving_power_lpmm", inp.resolving_power_lpmm),
            _number("forward_overlap_pct", inp.forward_overlap_pct),
            Row("object", (inp.object,))]
    if inp.object is not None:
        obj = inp.object
        rows += [_number("object_size_m", obj.size_m), Row("shape", (obj.shape,)),
                 Row("shape_coefficient", (obj.shape_coefficient,), digits=2),
                 Row("object_source", (obj.source,))]
    rows += [_number("probability", rules.probability),
             Row("height_formula", (rules.height_formula,),
                 fields={"used": "PZ" in rules.constraints}),
             _number("pr_coefficient", rules.pr_coefficient),
             Row("scanner", (inp.scanner,))]
    if inp.scanner_steps_um:
        rows.append(_number("pixel_um", tuple(inp.scanner_steps_um), "scanner_steps_um"))
    if inp.candidate_pixels_um:
        rows.append(_number("pixel_um", tuple(inp.candidate_pixels_um),
                            "candidate_pixels_um"))
    rows += [_number("bands", inp.bands), _number("bits_per_band", inp.bits_per_band)]
    return Table("film_inputs", "inputs", (Column("value"),), tuple(rows))


def _uav(name: str, value: Any, key: str = "", digits: int | None = None) -> Row:
    """A number of the UAV plan's inputs: the registry record's unit and decimals (a
    figure the registry has no record of: ``digits``)."""
    try:
        rec = get(name, "uav")
    except KeyError:
        return Row(key or name, (value,), digits=digits)
    unit = "scale" if rec.kind in ("scale", "scales") else rec.unit
    return Row(key or name, (value,), unit=unit,
               digits=rec.digits if digits is None else digits)


def uav_inputs(job: Any) -> Table:
    """The inputs of a UAV plan, in the order the Inputs sheet lists them, each number with
    the input registry's unit and decimals.

    Parameters
    ----------
    job : UavJob
        The plan and its norm set (the camera's and the shapes' names).

    Returns
    -------
    Table
        One column; rows keyed by the input's Python name: ``camera`` (a
        :class:`~.table.Named` camera; field ``id``), ``pixel_um``, ``focal_mm``,
        ``f_number``, ``orientation``, ``sensor_width_mm``, ``sensor_height_mm`` (field
        ``as_given``: the sides' decimals as measured), ``image_width_px``,
        ``image_height_px``, ``min_trigger_interval_s``, ``height_m``, ``heights`` (a
        pair: the lowest and highest flown height; field ``planned``),
        ``height_tolerance_up_pct``, ``height_tolerance_down_pct``, ``ceiling_m``,
        ``gsd_target_cm``, ``speed_ms``, ``exposure_s``, the overlaps, ``area_width_m``,
        ``area_length_m``, ``map_scale``, ``relief_interval_m``, ``object`` (the map
        object or None; with one ``object_size_m``, ``object_status`` (its norm row's
        status, "" for the user's object), ``shape`` (Named), ``shape_coefficient``,
        ``object_source``), the scene (``r_max``, ``r_min``, ``threshold_k0``,
        ``haze_contrast``), the motion (``shift_factor``, ``random_speed_ms``, the rates),
        ``roll_deg``, ``pitch_deg``, ``bands``, ``bits_per_band``, ``platform`` and
        ``norm_set`` (its title in both languages: fields ``en``, ``ru``).
    """
    plan, ns = job.plan, job.norm_set
    inp, h = plan.inputs, plan.heights_m
    rows = [Row("camera", (Named("camera", inp.camera, ns, inp.camera_name)
                           if inp.camera or inp.camera_name else None,),
                fields={"id": inp.camera, "name": inp.camera_name}),
            _uav("pixel_um", inp.pixel_um), _uav("focal_mm", inp.focal_mm),
            _uav("f_number", inp.f_number), Row("orientation", (inp.orientation,)),
            _uav("sensor_width_mm", inp.sensor_width_mm, digits=2),
            _uav("sensor_height_mm", inp.sensor_height_mm, digits=2),
            _uav("image_width_px", inp.image_width_px, digits=0),
            _uav("image_height_px", inp.image_height_px, digits=0),
            _uav("min_trigger_interval_s", inp.min_trigger_interval_s, digits=3),
            _uav("height_m", h["planned"]),
            Row("heights", ((h["min"], h["max"]),), unit="m", digits=1,
                fields={"planned": h["planned"], "over_relief": plan.over_relief}),
            _uav("height_tolerance_pct", inp.height_tolerance_up_pct,
                 "height_tolerance_up_pct"),
            _uav("height_tolerance_pct", inp.height_tolerance_down_pct,
                 "height_tolerance_down_pct"),
            _uav("max_height_m", inp.ceiling_m, "ceiling_m"),
            _uav("gsd_cm", inp.gsd_target_m * 100.0 if inp.gsd_target_m is not None
                 else None, "gsd_target_cm"),
            _uav("speed_ms", inp.speed_ms), _uav("exposure_s", inp.exposure_s),
            _uav("forward_overlap_pct", inp.forward_overlap_pct),
            _uav("side_overlap_pct", inp.side_overlap_pct),
            Row("area_width_m", (inp.area_width_m,), unit="m", digits=1),
            Row("area_length_m", (inp.area_length_m,), unit="m", digits=1),
            _uav("map_scale", inp.map_scale),
            _uav("relief_interval_m", inp.relief_interval_m),
            Row("object", (inp.map_object,))]
    obj = inp.map_object
    if obj is not None:
        rows += [_uav("object_size_m", obj.size_m), Row("object_status", (obj.status,)),
                 Row("shape", (Named("shape", obj.shape, ns),)),
                 Row("shape_coefficient", (obj.shape_coefficient,), digits=2),
                 Row("object_source", (obj.source,))]
    rows += [_uav(name, getattr(inp, name)) for name in (
        "r_max", "r_min", "threshold_k0", "haze_contrast", "shift_factor", "random_speed_ms",
        "roll_rate_rad_s", "pitch_rate_rad_s", "yaw_rate_rad_s", "roll_deg", "pitch_deg")]
    rows += [Row("bands", (inp.bands,), digits=0),
             Row("bits_per_band", (inp.bits_per_band,), digits=0),
             Row("platform", (inp.platform,))]
    if ns is not None:
        rows.append(Row("norm_set", (ns.name,), fields={"title": Names(ns.title, ns.title_ru)}))
    return Table("uav_inputs", "inputs", (Column("value"),), tuple(rows))

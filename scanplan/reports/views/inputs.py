"""The film plan's inputs: what the plan was computed from, each number with the input
registry's unit and decimals (:mod:`scanplan.project.inputs`) — the workbook's Inputs sheet
and the PDF's film section lay it out (:func:`film_inputs`)."""

from __future__ import annotations

from typing import Any

from ...project.inputs import get
from .table import Column, Row, Table

__all__ = ["film_inputs"]


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

"""The UAV (digital camera) plan's tables: the results at the planned and the highest flown
height, the constraints as maximum planned heights and the flight geometry — the terminal
report of ``scanplan uav``, the PDF's digital-camera section and a notebook's ``UavResult``
lay them out."""

from __future__ import annotations

from typing import Any

from ...core.flight import MAX_BLUR_PX
from ...core.shown import shown_decimals
from .table import Column, Row, Table

__all__ = ["uav_flight", "uav_limits", "uav_recognition", "uav_results"]


def uav_results(plan: Any) -> Table:
    """The results of a UAV plan at the planned height (and the highest flown one).

    Parameters
    ----------
    plan : UavPlan

    Returns
    -------
    Table
        Columns ``at_height`` (``value``: the planned height; a second one at the highest
        flown height when it differs); rows ``gsd_m``, ``nyquist_lpmm``,
        ``resolving_power`` (a pair: centre, corner), ``ground_resolution_m``,
        ``l_corner``, ``l_over_gsd``, ``motion_blur_px`` (field ``h``: the lowest flown
        height; its decimals show the blur against the limit) and, for a tilted camera,
        ``tilted_gsd`` (fields ``roll``, ``pitch``) in the last column ("" in the first
        of two: none there).
    """
    h = plan.heights_m
    two = h["max"] != h["planned"]
    columns = [Column("at_height", h["planned"])]
    if two:
        columns.append(Column("at_height", h["max"]))

    def both(at_planned: Any, at_max: Any) -> tuple[Any, ...]:
        return (at_planned, at_max) if two else (at_planned,)

    blur = plan.motion_blur_px
    rows = [
        Row("gsd_m", both(plan.gsd_m, plan.gsd_at_max_height_m), unit="m", digits=3),
        Row("nyquist_lpmm", (plan.nyquist_lpmm,), unit="lpmm", digits=1),
        Row("resolving_power", ((plan.resolving_power_lpmm,
                                 plan.resolving_power_corner_lpmm),), unit="lpmm", digits=1),
        Row("ground_resolution_m", both(plan.ground_resolution_m,
                                        plan.ground_resolution_at_max_height_m),
            unit="m", digits=3),
        Row("l_corner", (plan.ground_resolution_corner_m,), unit="m", digits=3),
        Row("l_over_gsd", (plan.ground_resolution_to_gsd,), digits=2),
        Row("motion_blur_px", (blur,), unit="px", digits=shown_decimals(blur, MAX_BLUR_PX),
            fields={"h": h["min"]}),
    ]
    if plan.tilted_corner_gsd_m is not None:
        rows.append(Row("tilted_gsd", both("", plan.tilted_corner_gsd_m) if two
                        else (plan.tilted_corner_gsd_m,), unit="m", digits=3,
                        fields={"roll": plan.inputs.roll_deg, "pitch": plan.inputs.pitch_deg}))
    return Table("uav_results", "uav_results", tuple(columns), tuple(rows))


def uav_limits(plan: Any) -> Table:
    """The constraints of a UAV plan as maximum planned heights, lowest first.

    Parameters
    ----------
    plan : UavPlan

    Returns
    -------
    Table
        One row per constraint (key: its id; flags ``"constraint"`` and, for the one that
        binds, ``"binding"``); columns ``limit`` (the ground limit [m], or the ceiling),
        ``compares`` (``GSD``, ``L`` or ``H``), ``max_height`` (the largest planned
        height [m]), ``max_flown`` (its highest flown height [m]) and ``margin_pct``
        (None for the binding one and an unlimited one). No rows without limits. Each
        row's fields carry the constraint as the rules give it, for the workbook's full
        table: ``name``, ``reason`` and ``equation`` (messages or text), ``margin_pct``
        (its headroom, also for the binding one), ``max_flown_m`` (None when not
        computed) and ``rank`` (its place in the registry's order: the formulas' list).
    """
    columns = (Column("limit", unit="m", digits=3), Column("compares"),
               Column("max_height", unit="m", digits=0),
               Column("max_flown", unit="m", digits=0),
               Column("margin_pct", unit="pct", digits=0))
    rows = []
    for lim in sorted(plan.limits, key=lambda x: x.max_height_m):
        margin = None if lim.binding or lim.margin_pct != lim.margin_pct \
            or abs(lim.margin_pct) == float("inf") else lim.margin_pct
        flags = {"constraint", "binding"} if lim.binding else {"constraint"}
        rows.append(Row(lim.id, (lim.limit_m, lim.compares, lim.max_height_m,
                                 lim.max_flown_height_m or lim.max_height_m, margin),
                        flags=frozenset(flags),
                        fields={"name": lim.name, "reason": lim.reason,
                                "equation": lim.equation, "margin_pct": lim.margin_pct,
                                "max_flown_m": lim.max_flown_height_m,
                                "rank": plan.limits.index(lim)}))
    return Table("uav_limits", "uav_limits", columns, tuple(rows))


def uav_flight(plan: Any) -> Table:
    """The flight geometry of a UAV plan at the planned height.

    Parameters
    ----------
    plan : UavPlan

    Returns
    -------
    Table
        One column; rows ``footprint`` (a pair: across, along [m]), ``base`` and
        ``line_spacing`` [m], ``photo_interval`` [s] (field ``min_trigger``: the camera's
        shortest interval, when known), ``overlap_range`` (a pair: the forward overlap at
        the lowest and the highest flown height [%]; fields ``lo``, ``hi``) and, with an
        area, ``strips`` (strips, photos per strip, photos) or ``strips_photos`` (strips,
        photos), ``flight_length_km``, ``flight_time_min`` (None without a speed) and
        with a data volume ``data_volume_gb`` and ``data_volume_jpeg_gb``.
    """
    fl, h = plan.flight, plan.heights_m
    trigger = {"min_trigger": fl["min_trigger_interval_s"]} \
        if "min_trigger_interval_s" in fl else {}
    rows = [Row("footprint", ((fl["footprint_across_m"], fl["footprint_along_m"]),),
                unit="m", digits=0),
            Row("base", (fl["base_m"],), unit="m", digits=1),
            Row("line_spacing", (fl["line_spacing_m"],), unit="m", digits=1),
            Row("photo_interval", (fl["photo_interval_s"],), unit="s", digits=2,
                fields=trigger),
            Row("overlap_range", ((fl["forward_overlap_at_min_height_pct"],
                                   fl["forward_overlap_at_max_height_pct"]),),
                unit="pct", digits=1, fields={"lo": h["min"], "hi": h["max"]})]
    if "strips" in fl:
        if "photos_per_strip" in fl:
            rows.append(Row("strips", ((fl["strips"], fl["photos_per_strip"], fl["photos"]),),
                            digits=0))
        else:  # a polygon: the strips differ in length
            rows.append(Row("strips_photos", ((fl["strips"], fl["photos"]),), digits=0))
        rows.append(Row("flight_length_km", (fl["flight_length_m"] / 1000,), unit="km",
                        digits=1))
        rows.append(Row("flight_time_min", (fl["flight_time_s"] / 60
                                            if fl.get("flight_time_s") else None,),
                        unit="min", digits=0))
        if "data_volume_bytes" in fl:
            rows.append(Row("data_volume_gb", (fl["data_volume_bytes"] / 1e9,), unit="GB",
                            digits=1))
            rows.append(Row("data_volume_jpeg_gb", (fl["data_volume_jpeg_bytes"] / 1e9,),
                            unit="GB", digits=1,
                            fields={"ratio": fl["jpeg_compression_ratio"]}))
    return Table("uav_flight", "uav_flight", (Column("value"),), tuple(rows))


def uav_recognition(plan: Any) -> Table:
    """The recognition probability of the norm set's objects (P = exp(−(B·L/L_obj)²)).

    Parameters
    ----------
    plan : UavPlan

    Returns
    -------
    Table
        One row per object (key ``"object"``; fields ``name``, ``size_m``, ``shape`` and
        ``map_scale``: the object as the norm set gives it; flag ``"emph"`` on the map's
        own object); columns ``map_scale``, ``size_m``, ``shape``, ``p`` at the planned
        height, ``p_max`` at the highest flown one and ``p_corner`` there at the frame
        corner (``value``: the height), probabilities to 2 decimals.
    """
    h = plan.heights_m
    mobj = plan.inputs.map_object
    columns = (Column("map_scale", unit="scale"), Column("size_m", unit="m"),
               Column("shape"), Column("p", h["planned"], digits=2),
               Column("p_max", h["max"], digits=2), Column("p_corner", h["max"], digits=2))
    rows = []
    for r in plan.recognition:
        own = (mobj is not None and r.object == mobj.name and r.object_size_m == mobj.size_m
               and r.map_scale == mobj.map_scale)
        rows.append(Row("object", (r.map_scale, r.object_size_m, r.shape, r.probability,
                                   r.probability_at_max_height,
                                   r.probability_corner_at_max_height),
                        flags=frozenset({"emph"}) if own else frozenset(),
                        fields={"name": r.object, "size_m": r.object_size_m,
                                "shape": r.shape, "map_scale": r.map_scale}))
    return Table("uav_recognition", "recognition", columns, tuple(rows))

"""The flight layout of a job: the area of the contract, the strips and photo centres over it.

The project layer's bridge between the engines (a UAV plan, a film scenario) and the
geography (:mod:`scanplan.geo`): it turns a plan's footprint, base and spacing into a
:class:`~scanplan.geo.layout.FlightLayout` over the area, and the layout's counts into the
flight figures every report shows — so the abstract ``width_m × length_m`` block and a
real polygon are planned by one model.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass, replace
from typing import Any

import numpy as np

from ..core import flight as FL
from ..core.photoscale import (
    frame_side_on_ground_m,
    height_at_photo_scale_m,
    scanned_ground_pixel_cm,
)
from ..errors import InputError
from ..geo.area import MAX_SCALE_ERROR_PCT, AreaSpec, load_area, rectangle_area
from ..geo.layout import Area, FlightLayout
from ..geo.lines import Turn, plan_lines, turn_radius_m
from ..i18n.messages import Message
from ..rules.results import PlanWarning, ScanScenario, UavPlan
from .inputs import by_key, domain_of

__all__ = ["LayoutOptions", "area_from_options", "check_options", "film_layout",
           "layout_warnings",
           "uav_flight_figures", "uav_layout", "with_layout"]

MAX_EXTENSION_BASES = 10
"""Most exposures past each end of a strip."""


@dataclass(frozen=True)
class LayoutOptions:
    """How to lay the strips out (project keys in brackets).

    Attributes
    ----------
    direction_deg : float or "auto"
        ``[area] direction_deg``: clockwise from grid north [°] (default "auto"; a
        ``width_m × length_m`` block is flown along its length).
    extension_bases : int
        ``[area] extension_bases``: exposures past each end (default 1).
    turnaround_m, turn_radius_m, bank_deg : float or None
        ``[uav]``: the turn between strips (at most one; default a semicircle across the
        line spacing).
    max_flight_time_min : float or None
        ``[uav] max_flight_time_min``: longest sortie [min].
    ground_m : float
        elevation of the flat ground [m] (API only; default 0).
    takeoff_lonlat : (float, float) or None
        ``[flight] takeoff``: the take-off and landing point of every sortie, WGS 84 [°].
    relief_m : float
        The ground's height range under the area [m]: a sortie climbs and descends at
        most this much more than its planned height (the sortie time).
    crosshatch : bool
        ``[uav] crosshatch``: fly the area twice, the second pass at the direction + 90°
        (a double grid, :mod:`scanplan.geo.crosshatch`; default False).
    """

    direction_deg: float | str | None = None
    extension_bases: int = 1
    turnaround_m: float | None = None
    turn_radius_m: float | None = None
    bank_deg: float | None = None
    max_flight_time_min: float | None = None
    ground_m: float = 0.0
    takeoff_lonlat: tuple[float, float] | None = None
    relief_m: float = 0.0
    crosshatch: bool = False


def area_from_options(spec: AreaSpec, area_m: tuple[float, float] | None = None
                      ) -> Area | None:
    """The area of a job: ``spec`` (file, polygon or rectangle) or the ``area_m`` block."""
    if area_m is not None and spec == AreaSpec():
        return rectangle_area(*area_m)
    return load_area(spec)


def check_options(opts: LayoutOptions, area: Area, speed_ms: float | None) -> None:
    """Raise :class:`InputError` (the option's name as field) for layout options out of
    range, or that do not apply to ``area``."""
    d = opts.direction_deg
    if d is not None and d != "auto":
        if isinstance(d, str) or not math.isfinite(float(d)) or not -360 <= float(d) <= 360:
            raise InputError("direction_deg", f'must be "auto" or an angle in −360 … 360° '
                             f"clockwise from grid north (got {d!r})")
        if not area.georeferenced:
            raise InputError("direction_deg", "applies to a polygon area; the width_m × "
                             "length_m block is flown along its length")
    if d == "auto" and not area.georeferenced:
        raise InputError("direction_deg", "applies to a polygon area; the width_m × "
                         "length_m block is flown along its length")
    if not (isinstance(opts.extension_bases, int) and
            0 <= opts.extension_bases <= MAX_EXTENSION_BASES):
        raise InputError("extension_bases", f"must be a whole number 0 … "
                         f"{MAX_EXTENSION_BASES} (got {opts.extension_bases!r})")
    turns = [k for k in ("turnaround_m", "turn_radius_m", "bank_deg")
             if getattr(opts, k) is not None]
    if len(turns) > 1:
        raise InputError(turns[1], f"give one turn: {' or '.join(turns)}, not both")
    for key in ("turnaround_m", "turn_radius_m", "bank_deg", "max_flight_time_min"):
        v = getattr(opts, key)
        d = domain_of(by_key("uav", key))  # the input registry's range of the key
        assert d is not None
        if v is not None and not ((d.lo < v or (v == d.lo and not d.lo_open)) and v <= d.hi):
            raise InputError(key, f"must be in ({d.lo:g}, {d.hi:g}] (got {v!r})")
    if opts.bank_deg is not None and not speed_ms:
        raise InputError("bank_deg", "needs the ground speed (> 0) for the turn radius")
    if not isinstance(opts.crosshatch, bool):
        raise InputError("crosshatch", f"must be true or false (got {opts.crosshatch!r})")
    if opts.takeoff_lonlat is not None and not area.georeferenced:
        raise InputError("takeoff", "applies to a polygon area; the width_m × length_m "
                         "block has no place on the map")
    if not math.isfinite(opts.ground_m) or not -500 <= opts.ground_m <= 9000:
        raise InputError("ground_elevation_m", f"must be in −500 … 9000 m (got "
                         f"{opts.ground_m!r})")


def _turn(opts: LayoutOptions, speed_ms: float | None) -> Turn:
    if opts.turnaround_m is not None:
        return Turn("turnaround", float(opts.turnaround_m))
    if opts.turn_radius_m is not None:
        return Turn("radius", float(opts.turn_radius_m))
    if opts.bank_deg is not None and speed_ms:
        return Turn("radius", round(turn_radius_m(speed_ms, opts.bank_deg), 1))
    return Turn()


def _direction(opts: LayoutOptions, area: Area) -> float | str:
    if not area.georeferenced:
        return 0.0
    return "auto" if opts.direction_deg in (None, "auto") else float(opts.direction_deg)


def uav_layout(plan: UavPlan, area: Area, opts: LayoutOptions | None = None,
               manned: bool = False) -> FlightLayout:
    """Strips and photo centres of a UAV plan (at its planned height) over ``area``
    (``manned``: the camera is on a manned survey aircraft, whose sorties are their length
    at the speed, :func:`scanplan.geo.lines.plan_lines`)."""
    opts = opts or LayoutOptions()
    inp = plan.inputs
    speed = inp.speed_ms if inp.speed_ms > 0 else None
    check_options(opts, area, speed)
    fl = plan.flight
    obj = inp.map_object
    p_rec = None
    if obj is not None:
        p_rec = next((r.probability for r in plan.recognition if r.object == obj.name
                      and r.object_size_m == obj.size_m), None)
    values = {"gsd_cm": plan.gsd_m * 100.0,
              "resolution_cm": (plan.ground_resolution_m * 100.0
                                if plan.ground_resolution_m is not None else math.nan),
              "recognition_p": p_rec if p_rec is not None else math.nan}
    lay_out = plan_lines
    if opts.crosshatch:  # the area flown twice, the second pass at + 90°
        from ..geo.crosshatch import plan_crosshatch as lay_out
    return lay_out(
        area, spacing_m=fl["line_spacing_m"], base_m=fl["base_m"],
        footprint_across_m=fl["footprint_across_m"], footprint_along_m=fl["footprint_along_m"],
        height_m=plan.heights_m["planned"], direction_deg=_direction(opts, area),
        extension_bases=opts.extension_bases, turn=_turn(opts, speed), speed_ms=speed,
        max_flight_time_min=opts.max_flight_time_min, ground_m=opts.ground_m,
        photo_values=values, kind="uav", takeoff_xy_m=_takeoff_xy(opts, area),
        manned=manned, climb_m=plan.heights_m["planned"] + opts.relief_m)


def _takeoff_xy(opts: LayoutOptions, area: Area) -> tuple[float, float] | None:
    """The take-off point in the area's planning CRS [m] (None when not given)."""
    if opts.takeoff_lonlat is None or not area.georeferenced:
        return None
    from ..geo.crs import transformer

    x, y = transformer(4326, area.plan_crs).transform(*map(float, opts.takeoff_lonlat))
    return float(x), float(y)


def uav_flight_figures(plan: UavPlan, layout: FlightLayout) -> dict[str, Any]:
    """The flight figures of the reports from a layout: strips, photos (per strip when
    every strip has the same number), length, time, sorties, data volume — uncompressed,
    and its JPEG estimate with the compression ratio assumed."""
    inp = plan.inputs
    per = {s.photos for s in layout.strips}
    photos = int(layout.notes.get("photos", len(layout.photos)))
    out: dict[str, Any] = {
        "strips": len(layout.strips),
        "photos_per_strip": per.pop() if len(per) == 1 else None,
        "photos": photos, "flight_length_m": layout.flight_length_m,
        "flight_time_s": layout.flight_time_s, "sorties": len(layout.sorties),
    }
    if out["photos_per_strip"] is None:
        del out["photos_per_strip"]
    if not layout.notes.get("max_flight_time_min"):  # no sortie time: not counted
        del out["sorties"]
    if inp.image_width_px and inp.image_height_px:
        out["data_volume_bytes"] = float(FL.data_volume_bytes(
            photos, inp.image_width_px, inp.image_height_px, inp.bands, inp.bits_per_band))
        out["data_volume_jpeg_bytes"] = float(FL.jpeg_volume_bytes(out["data_volume_bytes"]))
        out["jpeg_compression_ratio"] = FL.JPEG_COMPRESSION_RATIO
    return out


def with_layout(plan: UavPlan, layout: FlightLayout) -> UavPlan:
    """``plan`` with its flight figures taken from ``layout`` (and a warning when the layout
    cannot be flown)."""
    warnings = plan.warnings + layout_warnings(layout)
    return replace(plan, flight={**plan.flight, **uav_flight_figures(plan, layout)},
                   warnings=warnings)


def layout_warnings(layout: FlightLayout) -> tuple[PlanWarning, ...]:
    """A "not feasible" warning with the layout's reason, and a warning when the planning
    projection stretches the area by more than :data:`~scanplan.geo.area.MAX_SCALE_ERROR_PCT`
    (an area far out of its zone, often a mistyped coordinate)."""
    out: tuple[PlanWarning, ...] = ()
    area = layout.area
    if (area.scale_error_pct is not None and area.lon_range_deg is not None
            and area.scale_error_pct > MAX_SCALE_ERROR_PCT):
        west, east = area.lon_range_deg
        out += (PlanWarning("area_scale_distortion", Message(
            "area_scale_distortion", crs=area.plan_crs, pct=area.scale_error_pct,
            west=west, east=east)),)
    if layout.crosshatch and layout.feasible:
        n = layout.first_pass_strips or 0
        out += (PlanWarning("crosshatch", Message(
            "crosshatch", first=n, second=len(layout.strips) - n,
            direction=layout.direction_deg, cross=layout.cross_direction_deg,
            transit=float(layout.notes.get("pass_transit_m", 0.0))), severity="info"),)
    if not layout.feasible:
        out += (PlanWarning("flight_not_feasible", Message("flight_not_feasible",
                                                           why=layout.reason or "")),)
    return out


def film_layout(scenario: ScanScenario, frame_width_mm: float, frame_along_mm: float,
                focal_mm: float, forward_overlap_pct: float, side_overlap_pct: float,
                area: Area,
                opts: LayoutOptions | None = None,
                values: Mapping[str, float] | None = None) -> FlightLayout:
    """The aerial survey's flight scheme at a film scenario's photo scale over ``area``.

    Footprint = frame side × Mc; spacing and base from the overlaps (formulas.md §3), the
    same layout as a UAV's. No flight time (the aircraft's speed is not an input).
    """
    opts = opts or LayoutOptions()
    check_options(replace(opts, bank_deg=None, max_flight_time_min=None), area, None)
    across = float(frame_side_on_ground_m(frame_width_mm, scenario.photo_scale))
    along = float(frame_side_on_ground_m(frame_along_mm, scenario.photo_scale))
    spacing = float(FL.line_spacing_m(across, side_overlap_pct))
    base = float(FL.photo_base_m(along, forward_overlap_pct))
    pixel = scenario.scanner_pixel_um or scenario.scan_pixel_um
    vals = {"gsd_cm": float(scanned_ground_pixel_cm(pixel, scenario.photo_scale)),
            "recognition_p": (scenario.recognition_probability
                              if scenario.recognition_probability is not None else np.nan)}
    vals.update(values or {})
    return plan_lines(
        area, spacing_m=spacing, base_m=base, footprint_across_m=across,
        footprint_along_m=along,
        height_m=float(height_at_photo_scale_m(scenario.photo_scale, focal_mm)),
        direction_deg=_direction(opts, area),
        extension_bases=opts.extension_bases, turn=_turn(replace(opts, bank_deg=None), None),
        speed_ms=None, max_flight_time_min=None, ground_m=opts.ground_m, photo_values=vals,
        kind="film")

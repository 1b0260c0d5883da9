"""A crosshatch (double grid): the area flown twice, the second pass's lines at the first
direction + 90° (docs/flight-lines.md).

QGroundControl's Survey calls it "Refly at 90 deg offset", Pix4Dcapture "Double grid",
UgCS "crosshatch": every point of the area is then photographed along two line
directions, which a 3D model of buildings (their walls seen from four sides) and the
block's geometry gain from. Both passes are laid out by the same code as one pass
(:mod:`.lines`: the bands, the photographed parts, the exposures), the second with the
direction turned by 90°; nothing here makes geometry of its own.

- **Flight order.** The first pass's serpentine, then the second's. Of the second pass's
  two serpentines (begun from either side: the area turned by +90° or by +270°), the one
  whose first run-in is nearer the first pass's last run-out; the aircraft flies straight
  from that run-out to that run-in (the pass transit, ``notes["pass_transit_m"]``: from
  the last photo of the first pass to the first photo of the second — the run-out, the
  straight, the run-in — the path the missions fly, :mod:`.mission`).
- **Numbers.** The strips and the photos are numbered on from the first pass; each strip
  keeps its own direction (:meth:`~scanplan.geo.layout.FlightLayout.strip_direction_deg`).
- **Sorties.** The two passes are one serpentine for the battery: the sorties are packed
  along it (:func:`scanplan.geo.sorties.pack_sorties`), so a sortie may end in the first
  pass and the next resume there, or fly the pass transit. The packing works in the
  planning CRS (the two passes have no common rotated frame); the transit to a take-off
  point is a distance, the same in either frame.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import replace
from typing import Any

import numpy as np

from ..i18n.messages import Message
from .layout import Area, FlightLayout, Photos, Strip
from .lines import (
    MAX_PHOTO_CENTRES,
    MAX_STRIPS,
    _Airborne,
    _bands,
    _Extension,
    _flight_order,
    _not_flown,
    _packed,
    _Parts,
    _photos,
    _rotated,
    _Serpentine,
    _single_strip_reason,
    _strip_records,
    _time_s,
    _to_plan_xy,
    _TooMany,
    _turns_flown,
    plan_lines,
)
from .sorties import FlightModel, SortiePlan, path_time_s, turn_penalties_m
from .strips import Turn

__all__ = ["crosshatch_layout", "plan_crosshatch"]


class _Pass:
    """One pass: its parts in its rotated frame, its exposures in flight order and the
    way back to the planning CRS."""

    def __init__(self, parts: _Parts, direction: float, origin: tuple[float, float],
                 turn: Turn) -> None:
        self.parts = parts
        self.direction = direction
        self.to_xy = _to_plan_xy(direction, origin)
        self.ex_strip, self.ex_v, self.path = _flight_order(parts)
        sign = np.where(self.ex_strip % 2 == 0, 1.0, -1.0)
        u = parts.u_m[self.ex_strip]
        lead_out = max(turn.lead_m, parts.base_m / 2.0)
        self.sign = sign
        self.xy = np.column_stack(self.to_xy(u, self.ex_v))
        self.start_xy = np.column_stack(self.to_xy(u, self.ex_v - sign * turn.lead_m))
        self.end_xy = np.column_stack(self.to_xy(u, self.ex_v + sign * lead_out))

    def heading(self, k: int) -> np.ndarray:
        """The unit heading of exposure ``k`` (flight order) in the planning CRS."""
        u = self.parts.u_m[self.ex_strip[k]]
        a = np.array(self.to_xy(np.array([u]), np.array([0.0])))[:, 0]
        b = np.array(self.to_xy(np.array([u]), np.array([float(self.sign[k])])))[:, 0]
        return b - a

    def penalty(self, turn: Turn, speed_ms: float, model: FlightModel) -> np.ndarray:
        return turn_penalties_m(self.ex_strip, self.ex_v, self.parts.u_m, turn.kind,
                                turn.lead_m, speed_ms, model, self.parts.base_m / 2.0)


def _pass_parts(geom: object, direction: float, origin: tuple[float, float],
                spacing_m: float, base_m: float, ext: _Extension, turn: Turn) -> _Parts:
    """The photographed parts of the lines at ``direction`` [°] (raises ``_TooMany``)."""
    return _Parts.of(_bands(_rotated(geom, direction, origin), spacing_m), base_m, ext, turn)


def _junction(first: _Pass, second: _Pass, turn: Turn) -> tuple[float, np.ndarray]:
    """The pass transit: its length from the first pass's last photo to the second's
    first [m], and its polyline (that photo, the run-out, the run-in, this photo)."""
    pe, q = first.xy[-1], second.xy[0]
    ro, ri = first.end_xy[-1], second.start_xy[0]
    poly = np.vstack([pe, ro, ri, q])
    return float(np.sum(np.hypot(*np.diff(poly, axis=0).T))), poly


def _junction_penalty_m(poly: np.ndarray, h1: np.ndarray, h2: np.ndarray, speed_ms: float,
                        model: FlightModel) -> float:
    """The pass transit's corners as metres at the cruise speed beyond its length, entered
    and left at the cruise speed on straights as long as a braking run (as
    :func:`~scanplan.geo.sorties.turn_penalties_m` costs a turn)."""
    run_up = speed_ms ** 2 / (2.0 * model.accel_ms2) + 1.0
    full = np.vstack([poly[0] - run_up * h1, poly, poly[-1] + run_up * h2])
    keep = np.r_[True, np.hypot(*np.diff(full, axis=0).T) > 1e-9]
    full = full[keep]
    length = float(np.sum(np.hypot(*np.diff(full, axis=0).T)))
    t = path_time_s(full, speed_ms, model, start_ms=speed_ms, end_ms=speed_ms)
    return max(0.0, t * speed_ms - length)


def plan_crosshatch(area: Area, *, spacing_m: float, base_m: float,
                    footprint_across_m: float, footprint_along_m: float, height_m: float,
                    direction_deg: float | str = "auto", extension_bases: int = 1,
                    turn: Turn = Turn(),  # noqa: B008 - a frozen dataclass
                    speed_ms: float | None = None, max_flight_time_min: float | None = None,
                    ground_m: float = 0.0, photo_values: Mapping[str, float] | None = None,
                    kind: str = "uav", takeoff_xy_m: tuple[float, float] | None = None,
                    flight_model: FlightModel | None = None, manned: bool = False,
                    climb_m: float | None = None) -> FlightLayout:
    """Both passes of a crosshatch over ``area`` (module notes): the parameters and the
    result of :func:`scanplan.geo.lines.plan_lines`, the result with
    ``cross_direction_deg`` and ``first_pass_strips`` set.

    The first pass's direction (``"auto"``: the least flight length of one pass) and the
    grid's scale come from :func:`~scanplan.geo.lines.plan_lines` itself, laid out as one
    sortie without times; a block that cannot be laid out (too many strips) is returned
    as it says.
    """
    one = plan_lines(area, spacing_m=spacing_m, base_m=base_m,
                     footprint_across_m=footprint_across_m,
                     footprint_along_m=footprint_along_m, height_m=height_m,
                     direction_deg=direction_deg, extension_bases=extension_bases, turn=turn,
                     ground_m=ground_m, photo_values=photo_values, kind=kind, manned=True)
    if not one.strips:
        return one
    geom = area.geometry
    origin = (float(geom.centroid.x), float(geom.centroid.y))
    k = float(one.notes.get("grid_scale", 1.0))
    notes: dict[str, object] = {"max_flight_time_min": max_flight_time_min,
                                "turn_kind": turn.kind, "turn_m": turn.value_m,
                                "takeoff_xy_m": takeoff_xy_m}
    if "grid_scale" in one.notes:
        notes["grid_scale"] = k
    if "auto_directions_tried" in one.notes:
        notes["auto_directions_tried"] = one.notes["auto_directions_tried"]
    common = dict(area=area, direction_deg=one.direction_deg, spacing_m=spacing_m,
                  base_m=base_m, extension_bases=float(int(extension_bases)), kind=kind,
                  footprint_across_m=footprint_across_m, footprint_along_m=footprint_along_m,
                  speed_ms=speed_ms, turn=turn.describe())
    ext = _Extension(int(extension_bases), footprint_along_m * k / 2.0)
    parts = _pass_parts(geom, one.direction_deg, origin, spacing_m * k, base_m * k, ext, turn)
    air = None if manned or kind != "uav" else _Airborne(
        geom.boundary, height_m if climb_m is None else climb_m,
        flight_model or FlightModel.bundled())
    return crosshatch_layout(
        area, parts, direction=one.direction_deg, origin=origin, spacing_m=spacing_m * k,
        base_m=base_m * k, ext=ext, turn=turn, takeoff_xy_m=takeoff_xy_m, speed_ms=speed_ms,
        max_flight_time_min=max_flight_time_min, air=air, height_m=height_m,
        ground_m=ground_m, photo_values=photo_values or {}, notes=notes, common=common)


def crosshatch_layout(area: Area, first_parts: _Parts, *, direction: float,
                      origin: tuple[float, float], spacing_m: float, base_m: float,
                      ext: _Extension, turn: Turn, takeoff_xy_m: tuple[float, float] | None,
                      speed_ms: float | None, max_flight_time_min: float | None,
                      air: _Airborne | None, height_m: float, ground_m: float,
                      photo_values: Mapping[str, float], notes: dict[str, object],
                      common: dict[str, object]) -> FlightLayout:
    """Both passes of a crosshatch over ``area`` as one :class:`FlightLayout` (module notes).

    Parameters
    ----------
    area : Area
        The area in its planning CRS.
    first_parts : _Parts
        The first pass's photographed parts, at ``direction`` (:func:`plan_lines`).
    direction : float
        The first pass's line direction, clockwise from grid north [°].
    origin : (float, float)
        The rotation's origin, the area's centroid [m].
    spacing_m, base_m : float
        Line spacing and photo base in the grid [m].
    ext : _Extension
        The extension exposures past each end.
    turn : Turn
        The turn between strips.
    takeoff_xy_m : (float, float) or None
        The take-off point in the planning CRS [m].
    speed_ms, max_flight_time_min : float or None
        Ground speed [m/s] and the longest sortie [min].
    air : _Airborne or None
        The climb and the flight model (its ``boundary`` in the planning CRS), None for film
        or a manned aircraft.
    height_m, ground_m : float
        Height above ground and the flat ground's elevation [m].
    photo_values : mapping
        The per-photo figures of flat ground.
    notes, common : dict
        :func:`plan_lines`'s notes (added to) and the fields every layout has.

    Returns
    -------
    FlightLayout
        ``cross_direction_deg`` and ``first_pass_strips`` set.
    """
    geom = area.geometry
    a = _Pass(first_parts, direction, origin, turn)
    try:
        b = _second_pass(geom, a, direction, origin, spacing_m, base_m, ext, turn)
    except _TooMany as exc:
        return _not_flown(Message("layout.too_many_strips", n=exc.n, spacing=spacing_m,
                                  most=MAX_STRIPS), notes, common)
    n_a = a.parts.n_strips
    notes["bridged_m"] = a.parts.bridged_m() + b.parts.bridged_m()
    serp, notes["pass_transit_m"] = _joined(a, b, turn, base_m)
    if air is not None:
        air = _Airborne(geom.boundary if air.boundary is not None else None, air.height_m,
                        air.model)
    plan, ex_strip, reason = _packed(serp, turn, takeoff_xy_m, speed_ms, max_flight_time_min,
                                     notes, air)
    conn = np.r_[a.parts.conn, 0.0, b.parts.conn]  # the pass transit is no turn
    length = float(np.sum(plan.length_m))
    turns = _turns_flown(plan, ex_strip, conn)
    notes["transit_m"] = float(np.sum(plan.transit_m))
    if reason is None:
        reason = (_single_strip_reason(a.parts, spacing_m, _rotated(geom, direction, origin))
                  or _single_strip_reason(b.parts, spacing_m, _rotated(geom, b.direction,
                                                                         origin)))
    strips, photos = _records(a, b, plan, ex_strip, area, height_m, ground_m, photo_values,
                              notes)
    sorties = plan.records(speed_ms)
    flown = [s.time_s for s in sorties]
    return FlightLayout(strips=strips, sorties=sorties, photos=photos,
                        flight_length_m=length, turn_length_m=turns,
                        flight_time_s=(float(sum(flown)) if flown and None not in flown
                                       else _time_s(length, speed_ms)),
                        feasible=reason is None, reason=reason, notes=notes,
                        cross_direction_deg=(direction + 90.0) % 180.0,
                        first_pass_strips=n_a, **common)  # type: ignore[arg-type]


def _second_pass(geom: Any, a: _Pass, direction: float, origin: tuple[float, float],
                 spacing_m: float, base_m: float, ext: _Extension, turn: Turn) -> _Pass:
    """The second pass at ``direction`` + 90°, begun from the side nearer the first pass's
    end (raises :class:`_TooMany` past the strip limit)."""
    best: tuple[float, _Pass] | None = None
    for turned in (direction + 90.0, direction + 270.0):  # begun from either side
        parts = _pass_parts(geom, turned, origin, spacing_m, base_m, ext, turn)
        b = _Pass(parts, turned, origin, turn)
        gap = float(np.hypot(*(b.start_xy[0] - a.end_xy[-1]))) if len(b.path) else math.inf
        if best is None or gap < best[0]:
            best = (gap, b)
    assert best is not None
    return best[1]


def _joined(a: _Pass, b: _Pass, turn: Turn, base_m: float) -> tuple[_Serpentine, float]:
    """Both passes as one serpentine to pack into sorties, and the transit between the
    passes [m] (no turn of the strips' own: flown straight from pass to pass)."""
    junction, poly = _junction(a, b, turn) if len(a.path) and len(b.path) else (0.0, None)
    path = np.r_[a.path, (a.path[-1] if len(a.path) else 0.0) + junction + b.path]

    def penalty(speed: float, model: FlightModel) -> np.ndarray:
        pa, pb = a.penalty(turn, speed, model), b.penalty(turn, speed, model)
        jp = (_junction_penalty_m(poly, a.heading(len(a.path) - 1), b.heading(0), speed,
                                  model) if poly is not None else 0.0)
        return np.r_[pa, (pa[-1] if len(pa) else 0.0) + jp + pb]

    serp = _Serpentine(np.r_[a.ex_strip, b.ex_strip + a.parts.n_strips], path,
                       np.vstack([a.start_xy, b.start_xy]), np.vstack([a.end_xy, b.end_xy]),
                       penalty, base_m)
    return serp, junction


def _records(a: _Pass, b: _Pass, plan: SortiePlan, ex_strip: np.ndarray, area: Area,
             height_m: float, ground_m: float, values: Mapping[str, float],
             notes: dict[str, object]) -> tuple[tuple[Strip, ...], Photos]:
    """Both passes' strip records and photo centres, the second numbered on from the
    first (the table left empty beyond :data:`~scanplan.geo.lines.MAX_PHOTO_CENTRES`)."""
    n_a = a.parts.n_strips
    n_ex_a = len(a.ex_strip)
    sortie_of = plan.start(n_a + b.parts.n_strips, ex_strip)
    continued = plan.continued(ex_strip)
    photos_a = int(a.parts.photos_per_strip.sum())
    n_photos = photos_a + int(b.parts.photos_per_strip.sum())
    out_strips: list[Strip] = []
    tables: list[dict[str, np.ndarray]] = []
    for k, (p, sorties, cont) in enumerate((
            (a, sortie_of[:n_a], {s: c for s, c in continued.items() if s < n_a}),
            (b, sortie_of[n_a:], {s - n_a: c for s, c in continued.items() if s >= n_a}))):
        parts = p.parts
        strips, (p_strip, p_start, pf, n_per), first_photo = _strip_records(
            parts.u_m, parts.p_strip, parts.first, parts.last, parts.n_per, parts.s_lo,
            parts.s_hi, parts.photos_per_strip, sorties, p.to_xy, cont)
        if k:
            strips = tuple(replace(s, number=s.number + n_a,
                                   first_photo=s.first_photo + photos_a) for s in strips)
        out_strips += strips
        if n_photos <= MAX_PHOTO_CENTRES:
            ex_sortie = (plan.exposure_sortie[:n_ex_a] if not k
                         else plan.exposure_sortie[n_ex_a:])
            cols = _photos(n_per, p_strip, p_start, pf, parts.u_m, first_photo, ex_sortie,
                           parts.base_m, p.to_xy, area, height_m, ground_m, values).columns
            if k:
                cols = {**cols, "photo": cols["photo"] + photos_a,
                        "strip": cols["strip"] + n_a}
            tables.append(cols)
    notes["photos"] = n_photos
    if n_photos > MAX_PHOTO_CENTRES:
        notes["photo_centres_omitted"] = n_photos
        return tuple(out_strips), Photos({})
    return tuple(out_strips), Photos({c: np.concatenate([t[c] for t in tables])
                                      for c in tables[0]})

"""Flight lines over an area: strips, photo centres, turns, sorties (docs/flight-lines.md).

One model for every area — a georeferenced polygon with holes and bays, or the abstract
``width_m × length_m`` rectangle — vectorised with shapely 2 (one call intersects every
strip's band with the area) and numpy (photo centres are built as arrays, never point by
point).

The layout, in a frame rotated so that the flight direction is +v:

- **Strips.** n = ceil(W/s) lines (:func:`scanplan.core.flight.strip_count`), W the area's
  extent across the lines and s the line spacing, centred on the area: the outer lines
  overhang both sides equally. Strip i is responsible for the band of width s around its
  line; a band that misses the area (between two islands) is dropped.
- **Photographed parts.** The band ∩ area gives the stretch(es) of the strip over the
  area. Parts closer than (2e + 1)·B (e = extension in bases, B = photo base) are photographed
  through; across a longer gap (a bay of a concave polygon, a hole, water between islands)
  the strip is *bridged*: flown straight on with the camera off, the parts photographed
  separately, each with its own extension. Bridging, not splitting the block, keeps one
  serpentine with one turn per strip; the gap is flown and counted in length and time
  (``notes["bridged_m"]``); split a strongly branched area into separate areas when the
  bridges cost more than the extra turns and transits would.
- **Photo centres.** A part of length L gets ceil(L/B) + 1 exposures
  (:func:`scanplan.core.flight.photos_per_strip`) at the base B, centred on the part: with
  a forward overlap ≥ 50 % every point of the area is then in ≥ 2 photos along the strip
  (stereo). Up to e extension exposures are added past each end, each only while its
  footprint still reaches into the part. B and the line spacing are laid out in the grid
  as the ground distances times the least scale factor of the projection over the area
  (:func:`grid_scale`).
- **Turns.** Between strips the aircraft flies the difference of the strip ends along the
  lines plus a turn across the distance d between the lines: a semicircle π·d/2 (default,
  as :func:`scanplan.core.flight.flight_length_m`); a multirotor's turnaround t past the
  end, 2t + d; or a fixed-wing turn of radius r (given, or r = v²/(g·tan φ) from the speed
  and the bank angle): πr + (d − 2r) when d ≥ 2r, else the three-arc "omega" turn
  r·(π + 4β), β = arccos((d/2 + r)/(2r)) — Dubins' shortest path for a heading reversal
  (Dubins 1957, Amer. J. Math. 79(3), 497–516).
- **Direction.** A given ``direction_deg`` (clockwise from grid north), or ``"auto"``: the
  direction of the least flight length among every edge direction of the convex hull and a
  sweep every 2°, refined around the best to 0.1° (the exact length of each, on a slightly
  simplified outline: :mod:`.direction`). The turns and the exposures of a strip:
  :mod:`.strips`.
- **Sorties.** With ``max_flight_time_min`` the serpentine is cut into sorties, each
  flying the longest stretch its battery allows — whole strips and a part of a strip,
  the run-in and run-out, and the transit from and to the take-off point when one is
  given (:mod:`scanplan.geo.sorties`); the next sortie resumes at the next exposure.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping
from dataclasses import dataclass

import numpy as np
import shapely
from shapely import affinity

from ..core import flight as FL
from ..i18n.messages import Message
from ..io.kept import Kept
from . import crs as geocrs
from .direction import _auto_direction, band_extents
from .layout import PHOTO_COLUMNS, Area, FlightLayout, LonLatColumns, Photos, Strip
from .sorties import (
    MAX_SORTIES,
    FlightModel,
    SortiePlan,
    boundary_transit,
    pack_sorties,
    packing_bound,
    sortie_overhead_m,
    turn_penalties_m,
)
from .strips import (
    G_MS2,
    MAX_STRIPS,
    Turn,
    _connections,
    _Extension,
    _strip_spans,
    turn_length_m,
    turn_radius_m,
)

__all__ = ["G_MS2", "MAX_PHOTO_CENTRES", "MAX_SORTIES", "MAX_STRIPS", "Turn", "band_extents",
           "grid_scale", "plan_lines", "turn_length_m", "turn_radius_m"]

MAX_PHOTO_CENTRES = 2_000_000
"""Most photo centres kept as a table (beyond: counted, not listed)."""


# -------------------------------------------------------------------------------------------
# Bands: the part of the area each strip covers
# -------------------------------------------------------------------------------------------
@dataclass(frozen=True)
class _Bands:
    u_m: np.ndarray  # line position across, per strip kept
    parts_strip: np.ndarray  # strip (index into u_m) of each part, sorted by strip, v
    parts_lo: np.ndarray  # part start along v
    parts_hi: np.ndarray  # part end along v
    n_lines: int  # lines before dropping empty bands


def _rotated(geom: object, direction_deg: float, origin: tuple[float, float]) -> object:
    """The area in the frame where the flight direction is +v (rotated counter-clockwise by
    the direction, which is clockwise from north)."""
    if direction_deg % 360.0 == 0.0:
        return geom
    return affinity.rotate(geom, direction_deg, origin=origin)


def _line_positions(geom: object, spacing_m: float) -> tuple[np.ndarray, float, float]:
    umin, vmin, umax, vmax = shapely.bounds(geom)
    width = umax - umin
    n = max(1, int(FL.strip_count(max(width, 1e-300), spacing_m)))
    if n > MAX_STRIPS:
        raise _TooMany(n)
    u = umin + (width - n * spacing_m) / 2.0 + (np.arange(n) + 0.5) * spacing_m
    return u, vmin, vmax


class _TooMany(Exception):
    def __init__(self, n: int) -> None:
        self.n = n


def _bands(geom: object, spacing_m: float) -> _Bands:
    u, vmin, vmax = _line_positions(geom, spacing_m)
    half = spacing_m / 2.0
    boxes = shapely.box(u - half, vmin - 1.0, u + half, vmax + 1.0)
    inter = shapely.intersection(boxes, geom)
    parts, idx = shapely.get_parts(inter, return_index=True)
    keep = shapely.area(parts) > 0.0
    parts, idx = parts[keep], idx[keep]
    b = shapely.bounds(parts)
    order = np.lexsort((b[:, 1], idx))
    idx, lo, hi = idx[order], b[order, 1], b[order, 3]
    used, strip = np.unique(idx, return_inverse=True)
    return _Bands(u_m=u[used], parts_strip=strip, parts_lo=lo, parts_hi=hi, n_lines=len(u))


def _merge(b: _Bands, gap_m: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Parts of a strip closer than ``gap_m`` merged (photographed through)."""
    if len(b.parts_lo) == 0:
        return b.parts_strip, b.parts_lo, b.parts_hi
    span = max(float(np.max(b.parts_hi) - np.min(b.parts_lo)), 1.0)
    shift = (b.parts_strip * (4.0 * span + 4.0 * gap_m)) - np.min(b.parts_lo)
    lo, hi = b.parts_lo + shift, b.parts_hi + shift
    run = np.maximum.accumulate(hi)
    new = np.ones(len(lo), dtype=bool)
    new[1:] = (lo[1:] > run[:-1] + gap_m) | (b.parts_strip[1:] != b.parts_strip[:-1])
    group = np.cumsum(new) - 1
    first = np.flatnonzero(new)
    last = np.concatenate((first[1:], [len(lo)])) - 1
    strip = b.parts_strip[first]
    out_lo = b.parts_lo[first]
    out_hi = run[last] - shift[last]
    del group
    return strip, out_lo, out_hi


# -------------------------------------------------------------------------------------------
# The layout
# -------------------------------------------------------------------------------------------
def plan_lines(
    area: Area,
    *,
    spacing_m: float,
    base_m: float,
    footprint_across_m: float,
    footprint_along_m: float,
    height_m: float,
    direction_deg: float | str = "auto",
    extension_bases: int = 1,
    turn: Turn = Turn(),  # noqa: B008 - a frozen dataclass: one immutable default
    speed_ms: float | None = None,
    max_flight_time_min: float | None = None,
    ground_m: float = 0.0,
    photo_values: Mapping[str, float] | None = None,
    kind: str = "uav",
    takeoff_xy_m: tuple[float, float] | None = None,
    flight_model: FlightModel | None = None,
    manned: bool = False,
    climb_m: float | None = None,
) -> FlightLayout:
    """Strips, photo centres, turns and sorties over ``area``.

    Parameters
    ----------
    area : Area
        The area in its planning CRS (:mod:`scanplan.geo.area`).
    spacing_m, base_m : float
        Line spacing and photo base [m] (:func:`scanplan.core.flight.line_spacing_m`,
        :func:`scanplan.core.flight.photo_base_m`).
    footprint_across_m, footprint_along_m : float
        One photo's ground footprint [m] (for reports and coverage checks).
    height_m : float
        Planned height above ground [m] (flat ground: every photo's AGL).
    direction_deg : float or "auto"
        Flight-line direction clockwise from grid north [°], or the least flight length.
    extension_bases : int
        Exposures past each end of every photographed part (default 1).
    turn : Turn
        Turn pattern between strips.
    speed_ms : float, optional
        Ground speed [m/s] for times (None: no times, as for film).
    max_flight_time_min : float, optional
        Longest sortie [min] (None: one sortie).
    ground_m : float
        Ground elevation of the flat area [m] (photo ``ground_m``; altitude = ground + H).
    photo_values : mapping, optional
        Per-photo figures that are the same at every centre on flat ground: ``gsd_cm``,
        ``resolution_cm``, ``recognition_p`` (NaN when absent).
    kind : str
        ``"uav"`` or ``"film"``.
    takeoff_xy_m : (float, float), optional
        The take-off (and landing) point in the planning CRS [m]: each sortie's transit
        from it to the block and back is flown, counted and packed into the battery.
        Not given, a UAV's sortie takes off from the area's boundary point nearest its
        run-in and returns there.
    flight_model : FlightModel, optional
        The numbers of the time as flown (default: ``norms/catalogue/flight-model.csv``).
    manned : bool
        A camera on a manned survey aircraft: its sorties are its length at the speed (a
        multirotor's flight model and a take-off from the area's boundary do not apply).
    climb_m : float, optional
        The height each sortie climbs after take-off and descends to land [m] (default
        ``height_m``; over relief, more).

    Returns
    -------
    FlightLayout
        ``feasible`` False with a ``reason`` when the block cannot be flown as planned.

    Long because: sixteen inputs, each documented above; the body is the layout's steps
    in order (grid scale, direction, bands, parts, sorties, records), each one call.
    """
    geom = area.geometry
    origin = (float(geom.centroid.x), float(geom.centroid.y))
    ext = int(extension_bases)
    notes: dict[str, object] = {"max_flight_time_min": max_flight_time_min,
                                "turn_kind": turn.kind, "turn_m": turn.value_m,
                                "takeoff_xy_m": takeoff_xy_m}
    common_sb = dict(spacing_m=spacing_m, base_m=base_m)  # on the ground, as reported
    k = grid_scale(area)
    if k != 1.0:  # laid out in the grid: a ground distance is k times longer there
        notes["grid_scale"] = k
        spacing_m, base_m = spacing_m * k, base_m * k
    direction = _direction(direction_deg, geom, origin, spacing_m, base_m,
                           _Extension(ext, footprint_along_m * k / 2.0), turn, notes)
    common = dict(area=area, direction_deg=direction, **common_sb,
                  extension_bases=float(ext), kind=kind, footprint_across_m=footprint_across_m,
                  footprint_along_m=footprint_along_m, speed_ms=speed_ms, turn=turn.describe())
    rot = _rotated(geom, direction, origin)
    try:
        bands = _bands(rot, spacing_m)
    except _TooMany as exc:
        return _not_flown(Message("layout.too_many_strips", n=exc.n, spacing=spacing_m,
                                  most=MAX_STRIPS), notes, common)
    parts = _Parts.of(bands, base_m, _Extension(ext, footprint_along_m * k / 2.0), turn)
    notes["bridged_m"] = parts.bridged_m()
    takeoff_uv = (None if takeoff_xy_m is None
                  else _to_rotated_uv(direction, origin)(*takeoff_xy_m))
    plan, ex_strip, reason = _sortie_plan(
        parts, turn, takeoff_uv, speed_ms, max_flight_time_min, notes,
        None if manned or kind != "uav" else _Airborne(
            rot.boundary, height_m if climb_m is None else climb_m,
            flight_model or FlightModel.bundled()))
    length = float(np.sum(plan.length_m))
    turns = _turns_flown(plan, ex_strip, parts.conn)
    notes["transit_m"] = float(np.sum(plan.transit_m))
    if reason is None:
        reason = _single_strip_reason(parts, spacing_m, rot)
    strips, photos = _records(parts, plan, ex_strip, _to_plan_xy(direction, origin), area,
                              height_m, ground_m, photo_values or {}, notes)
    sorties = plan.records(speed_ms, _to_plan_xy(direction, origin))
    flown = [s.time_s for s in sorties]
    return FlightLayout(strips=strips, sorties=sorties, photos=photos,
                        flight_length_m=length, turn_length_m=turns,
                        flight_time_s=(float(sum(flown)) if flown and None not in flown
                                       else _time_s(length, speed_ms)),
                        feasible=reason is None,
                        reason=reason, notes=notes, **common)


def grid_scale(area: Area) -> float:
    """The least point scale factor k of the planning projection over ``area`` (1 for the
    abstract block).

    A ground distance D is D·k in the grid (k: the projection's point scale factor,
    pyproj ``Proj.get_factors``; the least of the meridional and parallel scales for a
    projection that is not conformal). Laying the base and the line spacing out as D·k with
    the least k of the area's vertices and centre keeps the ground spacing of the photo
    centres at most the planned one everywhere (UTM k = 0.9996 on the central meridian
    would otherwise leave 0.04 % wider bases on the ground: slivers without stereo at
    exactly 50 % forward overlap).
    """
    if not area.georeferenced:
        return 1.0
    key = (area.plan_crs, shapely.to_wkb(area.geometry))
    return _GRID_SCALES.made(key, lambda: _grid_scale(area))  # type: ignore[return-value]


_GRID_SCALES: Kept[tuple[str, bytes], float] = Kept(32)
""":func:`grid_scale` of the last areas, by planning CRS and geometry (each plan lays the
same area out along several directions, and the page re-plans it on every edit)."""


def _grid_scale(area: Area) -> float:
    """:func:`grid_scale` of a georeferenced area, computed."""
    geom = area.geometry
    xy = np.vstack([shapely.get_coordinates(geom),
                    [[geom.centroid.x, geom.centroid.y]]])
    lon, lat = geocrs.transformer(area.plan_crs, 4326).transform(xy[:, 0], xy[:, 1])
    try:
        f = geocrs.proj(area.plan_crs).get_factors(lon, lat)
        k = np.minimum(np.asarray(f.meridional_scale), np.asarray(f.parallel_scale))
    except Exception:  # a CRS without factors (not a projection): no correction
        return 1.0
    k = k[np.isfinite(k) & (k > 0)]
    return float(k.min()) if len(k) else 1.0


def _not_flown(reason: Message, notes: dict[str, object],
               common: dict[str, object]) -> FlightLayout:
    """A layout with no strips that says why it cannot be planned."""
    return FlightLayout(strips=(), sorties=(), photos=Photos({}), flight_length_m=math.nan,
                        turn_length_m=math.nan, flight_time_s=None, feasible=False,
                        reason=reason, notes=notes, **common)  # type: ignore[arg-type]


def _direction(direction_deg: float | str, geom: object, origin: tuple[float, float],
               spacing_m: float, base_m: float, extension: int, turn: Turn,
               notes: dict[str, object]) -> float:
    """The flight direction [°, 0–180): the one given, or ``"auto"``'s least flight length
    (noting how many directions were tried)."""
    if direction_deg == "auto":
        direction, tried = _auto_direction(geom, origin, spacing_m, base_m, extension, turn)
        notes["auto_directions_tried"] = tried
        return direction
    return float(direction_deg) % 180.0


@dataclass(frozen=True, eq=False)
class _Parts:
    """The photographed parts of every strip in the rotated frame: part → strip
    (``p_strip``), exposures (``n_per``), first and last exposure along v; each strip's
    flown span [``s_lo``, ``s_hi``], the connections (turns) between strips and where each
    strip starts in flight order (serpentine: even strips flown +v)."""

    u_m: np.ndarray
    p_strip: np.ndarray
    n_per: np.ndarray
    first: np.ndarray
    last: np.ndarray
    s_lo: np.ndarray
    s_hi: np.ndarray
    conn: np.ndarray
    forward_v: np.ndarray
    base_m: float

    @classmethod
    def of(cls, bands: _Bands, base_m: float, ext: int, turn: Turn) -> _Parts:
        gap = (2 * ext + 1) * base_m
        p_strip, p_lo, p_hi = _merge(bands, gap)
        n_strips = len(bands.u_m)
        n_per, first, last, s_lo, s_hi = _strip_spans(p_strip, p_lo, p_hi, base_m, ext,
                                                      n_strips)
        conn = _connections(bands.u_m, s_lo, s_hi, turn)
        forward_v = np.where((np.arange(n_strips) % 2) == 0, s_lo, s_hi)
        return cls(bands.u_m, p_strip, n_per, first, last, s_lo, s_hi, conn, forward_v,
                   base_m)

    @property
    def n_strips(self) -> int:
        return len(self.u_m)

    @property
    def strip_len(self) -> np.ndarray:
        """Each strip's flown length [m], bridges included."""
        return self.s_hi - self.s_lo

    @property
    def photos_per_strip(self) -> np.ndarray:
        out = np.zeros(self.n_strips, dtype=np.int64)
        np.add.at(out, self.p_strip, self.n_per)
        return out

    def bridged_m(self) -> float:
        """Length flown with the camera off across gaps between parts [m]."""
        photographed = np.zeros(self.n_strips)
        np.add.at(photographed, self.p_strip, self.last - self.first)
        return float(np.sum(self.strip_len - photographed))


def _records(parts: _Parts, plan: SortiePlan, ex_strip: np.ndarray,
             to_xy: Callable[[np.ndarray, np.ndarray], tuple[np.ndarray, np.ndarray]],
             area: Area, height_m: float, ground_m: float, photo_values: Mapping[str, float],
             notes: dict[str, object]) -> tuple[tuple[Strip, ...], Photos]:
    """The strip records and the photo-centre table in the planning CRS (the table left
    empty, and the count noted, beyond :data:`MAX_PHOTO_CENTRES`)."""
    strips, (p_strip, p_start, pf, n_per), first_photo = _strip_records(
        parts.u_m, parts.p_strip, parts.first, parts.last, parts.n_per, parts.s_lo,
        parts.s_hi, parts.photos_per_strip, plan.start(parts.n_strips, ex_strip), to_xy,
        plan.continued(ex_strip))
    n_photos = int(parts.photos_per_strip.sum())
    if n_photos <= MAX_PHOTO_CENTRES:
        photos = _photos(n_per, p_strip, p_start, pf, parts.u_m, first_photo,
                         plan.exposure_sortie, parts.base_m, to_xy,
                         area, height_m, ground_m, photo_values)
    else:
        photos = Photos({})
        notes["photo_centres_omitted"] = n_photos
    notes["photos"] = n_photos
    return strips, photos


def _single_strip_reason(parts: _Parts, spacing_m: float, rot: object) -> Message | None:
    """Why one strip cannot cover an area narrower than the line spacing (None if it can)."""
    width = float(np.ptp(shapely.bounds(rot)[[0, 2]]))
    if parts.n_strips == 1 and spacing_m > width:
        return Message("layout.single_strip", spacing=spacing_m, width=width)
    return None


def _to_plan_xy(direction: float, origin: tuple[float, float]) -> Callable[
        [np.ndarray, np.ndarray], tuple[np.ndarray, np.ndarray]]:
    """(u, v) of the rotated frame → (x, y) of the planning CRS (rotation by −direction
    about ``origin``)."""
    theta = math.radians(direction)
    cos_t, sin_t = math.cos(theta), math.sin(theta)

    def to_xy(u: np.ndarray, v: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        if direction == 0.0:
            return np.asarray(u, dtype=float), np.asarray(v, dtype=float)
        du, dv = u - origin[0], v - origin[1]
        return origin[0] + du * cos_t + dv * sin_t, origin[1] - du * sin_t + dv * cos_t

    return to_xy


def _strip_records(u: np.ndarray, p_strip: np.ndarray, first: np.ndarray, last: np.ndarray,
                   n_per: np.ndarray, s_lo: np.ndarray, s_hi: np.ndarray,
                   photos_per_strip: np.ndarray, sortie_of: np.ndarray,
                   to_xy: Callable[[np.ndarray, np.ndarray], tuple[np.ndarray, np.ndarray]],
                   continued: Mapping[int, tuple[tuple[int, int], ...]],
                   ) -> tuple[tuple[Strip, ...], tuple[np.ndarray, ...], np.ndarray]:
    """The :class:`Strip` records (serpentine: strip 1 flown +v; ``continued``: strip →
    the later sorties that continue it, :meth:`SortiePlan.continued`), the photographed
    parts in flight order (strip, first exposure along v, forward?, photos) and each
    strip's first photo number."""
    n_strips = len(u)
    forward = (np.arange(n_strips) % 2) == 0
    sx, sy = to_xy(u, np.where(forward, s_lo, s_hi))
    ex, ey = to_xy(u, np.where(forward, s_hi, s_lo))
    pf = forward[p_strip]
    order = np.lexsort((np.where(pf, first, -first), p_strip))
    p_strip, first, last, n_per, pf = (a[order] for a in (p_strip, first, last, n_per, pf))
    p_start = np.where(pf, first, last)
    psx, psy = to_xy(u[p_strip], p_start)
    pex, pey = to_xy(u[p_strip], np.where(pf, last, first))
    first_photo = np.concatenate(([0], np.cumsum(photos_per_strip)[:-1])) + 1
    segs = np.bincount(p_strip, minlength=n_strips)
    parts_of: list[list[tuple[tuple[float, float], tuple[float, float]]]] = [
        [] for _ in range(n_strips)]
    for k, a, b, c, d in zip(p_strip.tolist(), *(np.asarray(z, dtype=float).tolist()
                                                  for z in (psx, psy, pex, pey)), strict=True):
        parts_of[k].append(((a, b), (c, d)))
    # Python numbers, column by column (as float()/int() of each element gives them)
    sx_, sy_, ex_, ey_, len_ = (np.asarray(z, dtype=float).tolist()
                                for z in (sx, sy, ex, ey, s_hi - s_lo))
    photos_, first_, sortie_, segs_ = (np.asarray(z).astype(np.int64).tolist() for z in (
        photos_per_strip, first_photo, sortie_of, segs))
    strips = tuple(
        Strip(number=i + 1, start_xy_m=(sx_[i], sy_[i]), end_xy_m=(ex_[i], ey_[i]),
              length_m=len_[i], photos=photos_[i], first_photo=first_[i],
              sortie=sortie_[i] + 1, segments=segs_[i], parts=tuple(parts_of[i]),
              continued=continued.get(i, ()))
        for i in range(n_strips))
    return strips, (p_strip, p_start, pf, n_per), first_photo


def _time_s(length_m: float, speed_ms: float | None) -> float | None:
    """Time at the ground speed [s]; None without a speed, or where a subnormal speed makes
    it infinite (never ``inf`` in a result)."""
    if not speed_ms or speed_ms <= 0:
        return None
    with np.errstate(over="ignore", divide="ignore"):
        t = float(length_m) / float(speed_ms)
    return t if math.isfinite(t) else None


def _to_rotated_uv(direction: float, origin: tuple[float, float]) -> Callable[
        [float, float], tuple[float, float]]:
    """(x, y) of the planning CRS → (u, v) of the rotated frame (the inverse of
    :func:`_to_plan_xy`)."""
    theta = math.radians(direction)
    cos_t, sin_t = math.cos(theta), math.sin(theta)

    def to_uv(x: float, y: float) -> tuple[float, float]:
        dx, dy = x - origin[0], y - origin[1]
        return origin[0] + dx * cos_t - dy * sin_t, origin[1] + dx * sin_t + dy * cos_t

    return to_uv


def _flight_order(parts: _Parts, most: int = MAX_PHOTO_CENTRES
                  ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Every exposure in flight order: its strip, its place along the line (v) and its
    path distance from the block's first exposure [m] (strips and turns). Beyond ``most``
    exposures every k-th is kept (with each part's ends): the places a sortie may end."""
    n_per = parts.n_per.astype(np.int64)
    total = int(n_per.sum())
    # Every k-th exposure of each part and its last one, counted before anything per
    # exposure is made (an extreme block has far more exposures than memory).
    k = max(1, math.ceil(total / most))
    kept = np.where(n_per > 0, (n_per - 1) // k + 1 + ((n_per - 1) % k != 0), 0)
    part = np.repeat(np.arange(len(n_per)), kept)
    nth = np.arange(int(kept.sum())) - np.concatenate(([0], np.cumsum(kept)[:-1]))[part]
    local = np.minimum(nth * k, n_per[part] - 1)
    v = parts.first[part] + parts.base_m * local
    strip = parts.p_strip[part]
    order = np.lexsort((np.where(strip % 2 == 0, v, -v), strip))
    strip, v = strip[order], v[order]
    start = np.concatenate(([0.0], np.cumsum(parts.strip_len[:-1] + parts.conn)))
    return strip, v, start[strip] + np.abs(v - parts.forward_v[strip])


@dataclass(frozen=True)
class _Airborne:
    """What the sorties' time as flown needs beyond the strips: the area's outline in the
    packing frame (the default take-off points; None: no transit without a take-off
    point, as for film), the climb height and the flight model."""

    boundary: object | None
    height_m: float
    model: FlightModel


def _sortie_plan(parts: _Parts, turn: Turn, takeoff_uv: tuple[float, float] | None,
                 speed_ms: float | None, max_min: float | None, notes: dict[str, object],
                 air: _Airborne | None = None
                 ) -> tuple[SortiePlan, np.ndarray, Message | None]:
    """The sorties (:func:`scanplan.geo.sorties.pack_sorties`), the strip of every
    exposure in flight order, and why the block cannot be flown (None if it can).

    Each sortie flies its run-in (:attr:`Turn.lead_m`) before its first exposure and a
    run-out of at least half a base past its last (where the camera trigger stops,
    :mod:`scanplan.geo.mission`), and the transit from the take-off point and back: the
    given one, else the area's boundary point nearest the sortie's run-in. With a speed,
    the battery holds the time as flown: the turns' corners, the climb, the descent, the
    start and the stop (:mod:`scanplan.geo.sorties`).
    """
    ex_strip, ex_v, path = _flight_order(parts)
    lead_in = turn.lead_m
    lead_out = max(turn.lead_m, parts.base_m / 2.0)
    sign = np.where(ex_strip % 2 == 0, 1.0, -1.0)
    u = parts.u_m[ex_strip]
    start_xy = np.column_stack([u, ex_v - sign * lead_in])
    end_xy = np.column_stack([u, ex_v + sign * lead_out])

    def penalty(speed_ms: float, model: FlightModel) -> np.ndarray:
        return turn_penalties_m(ex_strip, ex_v, parts.u_m, turn.kind, turn.lead_m,
                                speed_ms, model, parts.base_m / 2.0)

    return _packed(_Serpentine(ex_strip, path, start_xy, end_xy, penalty, parts.base_m),
                   turn, takeoff_uv, speed_ms, max_min, notes, air)


@dataclass(frozen=True)
class _Serpentine:
    """Every exposure in flight order as the packing sees it, in one metric frame: its
    strip (from 0), its path distance from the first exposure [m], the run-in point before
    it and the run-out point past it (n × 2) [m], and the turns' time beyond their length
    (``penalty(speed_ms, model)``, :func:`~scanplan.geo.sorties.turn_penalties_m`)."""

    ex_strip: np.ndarray
    path: np.ndarray
    start_xy: np.ndarray
    end_xy: np.ndarray
    penalty: Callable[[float, FlightModel], np.ndarray]
    base_m: float


def _packed(serp: _Serpentine, turn: Turn, takeoff_uv: tuple[float, float] | None,
            speed_ms: float | None, max_min: float | None, notes: dict[str, object],
            air: _Airborne | None = None
            ) -> tuple[SortiePlan, np.ndarray, Message | None]:
    """:func:`_sortie_plan` over a serpentine already laid out (one pass, or both passes
    of a crosshatch, :mod:`.crosshatch`); ``takeoff_uv`` and ``air.boundary`` in the
    serpentine's frame."""
    ex_strip, path, start_xy, end_xy = serp.ex_strip, serp.path, serp.start_xy, serp.end_xy
    lead_in = turn.lead_m
    lead_out = max(turn.lead_m, serp.base_m / 2.0)
    transit = None
    zeros = np.zeros(len(path))
    t_in = t_out = zeros
    if takeoff_uv is not None or (air is not None and air.boundary is not None):
        transit = boundary_transit(air.boundary if air is not None else None, start_xy,
                                   end_xy, takeoff_uv)
        if takeoff_uv is not None:  # the transits of a fixed take-off point, as before
            t_in = np.hypot(*(start_xy - np.asarray(takeoff_uv)).T)
            t_out = np.hypot(*(end_xy - np.asarray(takeoff_uv)).T)
    timed = bool(speed_ms and speed_ms > 0 and air is not None and math.isfinite(speed_ms))
    penalty = overhead = None
    if timed and air is not None and speed_ms is not None and len(path):
        penalty = serp.penalty(speed_ms, air.model)
        overhead = sortie_overhead_m(speed_ms, air.height_m, air.model)
        notes["sortie_overhead_s"] = overhead / speed_ms
    limit = None
    if max_min and speed_ms:
        with np.errstate(over="ignore"):
            limit = max_min * 60.0 * speed_ms
        if not math.isfinite(limit) or not np.isfinite(path).all():
            limit = None
        elif limit < serp.base_m:
            plan, _ = pack_sorties(path, ex_strip, t_in, t_out, lead_in_m=lead_in,
                                   lead_out_m=lead_out, limit_m=None, transit=transit)
            return plan, ex_strip, Message("layout.sortie_too_short", limit=max_min,
                                           base=serp.base_m, speed=speed_ms)
    if limit is not None and len(path):
        notes["packing_bound"] = packing_bound(float(path[-1] - path[0]) + lead_in
                                               + lead_out, limit)
    plan, reason = pack_sorties(path, ex_strip, t_in, t_out, lead_in_m=lead_in,
                                lead_out_m=lead_out, limit_m=limit, max_minutes=max_min,
                                transit=transit, penalty_m=penalty,
                                overhead_m=overhead or 0.0)
    return plan, ex_strip, reason


def _turns_flown(plan: SortiePlan, ex_strip: np.ndarray, conn: np.ndarray) -> float:
    """The turns flown within sorties (between a strip's last exposure and the next
    strip's first, in one sortie) [m]."""
    if len(ex_strip) < 2 or len(plan.exposure_sortie) != len(ex_strip):
        return float(np.sum(conn))
    change = np.flatnonzero(np.diff(ex_strip))
    same = plan.exposure_sortie[change] == plan.exposure_sortie[change + 1]
    return float(np.sum(conn[ex_strip[change][same]]))


def _photos(n_per: np.ndarray, p_strip: np.ndarray, p_start: np.ndarray, pf: np.ndarray,
            u: np.ndarray, first_photo: np.ndarray, sortie: np.ndarray, base_m: float,
            to_xy: object, area: Area, height_m: float, ground_m: float,
            values: Mapping[str, float]) -> Photos:
    total = int(n_per.sum())
    part = np.repeat(np.arange(len(n_per)), n_per)
    starts = np.concatenate(([0], np.cumsum(n_per)[:-1]))
    local = np.arange(total) - starts[part]
    sign = np.where(pf, 1.0, -1.0)[part]
    v = p_start[part] + sign * base_m * local
    strip0 = p_strip[part]
    x, y = to_xy(u[strip0], v)  # type: ignore[operator]
    running = np.arange(1, total + 1)  # flight order: the order of ``sortie``
    lon = lat = None if area.georeferenced else np.full(total, np.nan)  # None: when read
    full = np.full(total, 1.0)
    cols = {
        "photo": running, "strip": strip0 + 1, "index": running - first_photo[strip0] + 1,
        "sortie": sortie + 1, "x_m": np.asarray(x, dtype=float),
        "y_m": np.asarray(y, dtype=float), "lon_deg": lon, "lat_deg": lat,
        "ground_m": full * ground_m, "altitude_m": full * (ground_m + height_m),
        "agl_m": full * height_m,
        "gsd_cm": full * values.get("gsd_cm", np.nan),
        "resolution_cm": full * values.get("resolution_cm", np.nan),
        "recognition_p": full * values.get("recognition_p", np.nan),
    }
    assert list(cols) == list(PHOTO_COLUMNS)
    return Photos(LonLatColumns(cols, area.plan_crs) if area.georeferenced else cols)

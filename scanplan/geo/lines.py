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
  simplified outline).
- **Sorties.** With ``max_flight_time_min`` the serpentine is cut into sorties, each
  flying the longest stretch its battery allows — whole strips and a part of a strip,
  the run-in and run-out, and the transit from and to the take-off point when one is
  given (:mod:`scanplan.geo.sorties`); the next sortie resumes at the next exposure.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass

import numpy as np
import shapely
from shapely import affinity

from ..core import flight as FL
from ..i18n.messages import Message
from . import crs as geocrs
from .layout import PHOTO_COLUMNS, Area, FlightLayout, Photos, Strip
from .sorties import MAX_SORTIES, SortiePlan, pack_sorties, packing_bound

__all__ = ["MAX_PHOTO_CENTRES", "MAX_SORTIES", "MAX_STRIPS", "Turn", "band_extents",
           "grid_scale", "plan_lines",
           "turn_length_m", "turn_radius_m"]

G_MS2 = 9.80665
"""Standard gravity [m/s²] (CGPM 1901)."""
MAX_STRIPS = 100_000
"""Most strips a layout computes (beyond: not feasible)."""
MAX_PHOTO_CENTRES = 2_000_000
"""Most photo centres kept as a table (beyond: counted, not listed)."""
_AUTO_SWEEP_DEG = 2.0
_COST_CHUNK_BANDS = 500_000
"""Bands (plus edges) per chunk of directions in the "auto" search's costing (memory bound)."""


@dataclass(frozen=True)
class Turn:
    """How the aircraft turns between strips.

    ``kind``: ``"semicircle"`` (a half circle across the line spacing), ``"turnaround"``
    (multirotor: ``value_m`` flown past the strip end, across, and back in) or ``"radius"``
    (fixed-wing: turn radius ``value_m``).
    """

    kind: str = "semicircle"
    value_m: float = 0.0

    def describe(self) -> str:
        """``semicircle``, ``turnaround 20 m``, ``radius 150 m`` (for reports)."""
        return self.kind if self.kind == "semicircle" else f"{self.kind} {self.value_m:g} m"

    @property
    def lead_m(self) -> float:
        """The straight flown on the line before its first exposure and past its last
        (run-in and run-out) [m]: a multirotor's turnaround, a fixed wing's turn radius (it
        is on the line, wings level, before the camera fires); none for the semicircle."""
        return 0.0 if self.kind == "semicircle" else float(self.value_m)


def turn_radius_m(speed_ms: float, bank_deg: float) -> float:
    """Radius of a level coordinated turn, r = v²/(g·tan φ) [m].

    Parameters
    ----------
    speed_ms : float
        True airspeed ≈ ground speed in still air [m/s].
    bank_deg : float
        Bank angle φ [°], 0 < φ < 90.

    Notes
    -----
    FAA, *Pilot's Handbook of Aeronautical Knowledge* (FAA-H-8083-25C, 2023), ch. 5
    "Aerodynamics of Flight", forces in turns: the horizontal lift component L·sin φ is the
    centripetal force m·v²/r while L·cos φ = m·g.
    """
    return speed_ms ** 2 / (G_MS2 * math.tan(math.radians(bank_deg)))


def turn_length_m(across_m: np.ndarray, offset_m: np.ndarray, turn: Turn) -> np.ndarray:
    """Path flown from the end of one strip to the start of the next [m].

    Parameters
    ----------
    across_m : array_like
        Distance between the two lines [m].
    offset_m : array_like
        Difference of the two strip ends along the lines [m] (flown straight).
    turn : Turn
        The turn pattern; a fixed wing's includes the run-out and the run-in of one turn
        radius each (:attr:`Turn.lead_m`), a multirotor's the turnaround out and back.
    """
    d = np.asarray(across_m, dtype=float)
    off = np.abs(np.asarray(offset_m, dtype=float))
    if turn.kind == "semicircle":
        return np.pi * d / 2.0 + off
    if turn.kind == "turnaround":
        return 2.0 * turn.value_m + d + off
    if turn.kind == "radius":
        r = turn.value_m
        wide = np.pi * r + (d - 2.0 * r)
        beta = np.arccos(np.clip((d / 2.0 + r) / (2.0 * r), -1.0, 1.0))
        omega = r * (np.pi + 4.0 * beta)
        return np.where(d >= 2.0 * r, wide, omega) + off + 2.0 * r  # run-out, run-in
    raise ValueError(f"turn kind must be semicircle, turnaround or radius (got {turn.kind!r})")


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
    last = np.r_[first[1:], len(lo)] - 1
    strip = b.parts_strip[first]
    out_lo = b.parts_lo[first]
    out_hi = run[last] - shift[last]
    del group
    return strip, out_lo, out_hi


class _Extension(int):
    """Exposures past each end of a part (the int), and how far along the line a photo's
    footprint reaches from its centre [m] (``reach_m``): an extension exposure is kept only
    while its footprint reaches into the part — one that misses the area adds no coverage."""

    reach_m: float

    def __new__(cls, bases: int, reach_m: float) -> _Extension:
        obj = int.__new__(cls, bases)
        obj.reach_m = reach_m if math.isfinite(reach_m) and reach_m > 0 else math.inf
        return obj


def _photos_per_part(length_m: np.ndarray, base_m: float, extension: int) -> np.ndarray:
    """ceil(L/B) + 1 + 2e' exposures: e' ≤ e extension exposures past each end, those whose
    footprint still reaches into the part (j·B < reach − δ, δ the core's overhang past the
    part's end, ((n₀ − 1)·B − L)/2)."""
    length = np.maximum(length_m, 1e-300)
    core = FL.photos_per_strip(length, base_m, 0)
    reach = getattr(extension, "reach_m", math.inf)
    if not int(extension) or not math.isfinite(reach):
        return core + 2 * int(extension)
    delta = ((core - 1) * base_m - length) / 2.0
    kept = np.clip(np.ceil((reach - delta) / base_m) - 1, 0, int(extension)).astype(np.int64)
    return core + 2 * kept


def _strip_spans(strip: np.ndarray, lo: np.ndarray, hi: np.ndarray, base_m: float,
                 extension: int, n_strips: int) -> tuple[np.ndarray, ...]:
    """Per part: photos, first and last exposure along v; per strip: first/last exposure."""
    n = _photos_per_part(hi - lo, base_m, extension)
    half = (n - 1) * base_m / 2.0
    mid = (lo + hi) / 2.0
    first, last = mid - half, mid + half
    s_lo = np.full(n_strips, np.inf)
    s_hi = np.full(n_strips, -np.inf)
    np.minimum.at(s_lo, strip, first)
    np.maximum.at(s_hi, strip, last)
    return n, first, last, s_lo, s_hi


def _connections(u: np.ndarray, s_lo: np.ndarray, s_hi: np.ndarray, turn: Turn
                 ) -> np.ndarray:
    """Path between strip i and i + 1 (serpentine: strip 0 flown +v) [m]."""
    if len(u) < 2:
        return np.zeros(0)
    forward = (np.arange(len(u) - 1) % 2) == 0  # strip i flown +v ends at its top
    end_i = np.where(forward, s_hi[:-1], s_lo[:-1])
    start_next = np.where(forward, s_hi[1:], s_lo[1:])
    return turn_length_m(np.diff(u), start_next - end_i, turn)


def _edges(geom: object) -> np.ndarray:
    """Every boundary edge of the area as rows (x0, y0, x1, y1) [m]."""
    rings = shapely.get_rings(shapely.get_parts(geom))
    out = []
    for ring in rings:
        c = shapely.get_coordinates(ring)
        out.append(np.hstack([c[:-1], c[1:]]))
    return np.vstack(out) if out else np.zeros((0, 4))


def band_extents(edges: np.ndarray, u_start_m: float, spacing_m: float, n: int
                 ) -> tuple[np.ndarray, np.ndarray]:
    """Along-line extent (v_min, v_max) of the area in each of ``n`` bands of width
    ``spacing_m`` from ``u_start_m`` (±inf for a band that misses it).

    The extent of a polygon within a band is that of its boundary within the band (the
    band's own edges inside the polygon end on the boundary), so each edge is cut to the
    bands it crosses — numpy over every (edge, band) pair at once. This is the cost of the
    "auto" direction search, evaluated ~150 times per plan; it agrees with shapely's
    intersection bounds (tests/test_geo_lines.py) and runs a hundred times faster.
    """
    u0, v0, u1, v1 = edges.T
    lo_u, hi_u = np.minimum(u0, u1), np.maximum(u0, u1)
    k0 = np.clip(np.floor((lo_u - u_start_m) / spacing_m), 0, n - 1).astype(np.int64)
    k1 = np.clip(np.floor((hi_u - u_start_m) / spacing_m), 0, n - 1).astype(np.int64)
    counts = k1 - k0 + 1
    e = np.repeat(np.arange(len(edges)), counts)
    k = k0[e] + (np.arange(int(counts.sum())) - np.repeat(np.cumsum(counts) - counts, counts))
    a = u_start_m + k * spacing_m
    du, dv = (u1 - u0)[e], (v1 - v0)[e]
    with np.errstate(divide="ignore", invalid="ignore"):
        ta, tb = (a - u0[e]) / du, (a + spacing_m - u0[e]) / du
    flat = du == 0
    t_lo = np.where(flat, 0.0, np.clip(np.minimum(ta, tb), 0.0, 1.0))
    t_hi = np.where(flat, 1.0, np.clip(np.maximum(ta, tb), 0.0, 1.0))
    va, vb = v0[e] + t_lo * dv, v0[e] + t_hi * dv
    lo = np.full(n, np.inf)
    hi = np.full(n, -np.inf)
    np.minimum.at(lo, k, np.minimum(va, vb))
    np.maximum.at(hi, k, np.maximum(va, vb))
    return lo, hi


def _cost(edges: np.ndarray, direction_deg: float, origin: tuple[float, float],
          spacing_m: float, base_m: float, extension: int, turn: Turn) -> float:
    """Flight length of the serpentine at a direction (strips + connections) [m]."""
    t = math.radians(direction_deg)
    c, s = math.cos(t), math.sin(t)
    x0, y0 = edges[:, 0] - origin[0], edges[:, 1] - origin[1]
    x1, y1 = edges[:, 2] - origin[0], edges[:, 3] - origin[1]
    uv = np.column_stack([x0 * c - y0 * s, x0 * s + y0 * c, x1 * c - y1 * s, x1 * s + y1 * c])
    umin = float(min(uv[:, 0].min(), uv[:, 2].min()))
    width = float(max(uv[:, 0].max(), uv[:, 2].max())) - umin
    n = max(1, int(FL.strip_count(max(width, 1e-300), spacing_m)))
    if n > MAX_STRIPS:
        return math.inf
    u_start = umin + (width - n * spacing_m) / 2.0
    lo, hi = band_extents(uv, u_start, spacing_m, n)
    keep = np.isfinite(lo)
    u = u_start + (np.arange(n) + 0.5) * spacing_m
    lo, hi, u = lo[keep], hi[keep], u[keep]
    m = len(u)
    _, _, _, s_lo, s_hi = _strip_spans(np.arange(m), lo, hi, base_m, extension, m)
    return float(np.sum(s_hi - s_lo) + np.sum(_connections(u, s_lo, s_hi, turn)))


def _costs(edges: np.ndarray, directions_deg: Sequence[float], origin: tuple[float, float],
           spacing_m: float, base_m: float, extension: int, turn: Turn) -> np.ndarray:
    """Flight length of the serpentine at each direction (strips + connections) [m], for
    many directions at once: :func:`_cost` of every direction, bit for bit (the same
    operations on the same numbers, each direction's sums taken over its own part), in a
    few vectorised passes over every (direction, edge, band) instead of one layout each.

    Directions whose strip count exceeds :data:`MAX_STRIPS` cost ``inf``; the directions
    are taken in chunks of at most :data:`_COST_CHUNK_BANDS` bands in all (memory)."""
    dirs = [float(d) for d in directions_deg]
    out = np.full(len(dirs), math.inf)
    if not dirs:
        return out
    rad = [math.radians(d) for d in dirs]
    c = np.array([math.cos(t) for t in rad])[:, None]
    s = np.array([math.sin(t) for t in rad])[:, None]
    x0, y0 = edges[:, 0] - origin[0], edges[:, 1] - origin[1]
    x1, y1 = edges[:, 2] - origin[0], edges[:, 3] - origin[1]
    u0, v0 = x0 * c - y0 * s, x0 * s + y0 * c  # (directions, edges)
    u1, v1 = x1 * c - y1 * s, x1 * s + y1 * c
    umin = np.minimum(u0.min(axis=1), u1.min(axis=1))
    width = np.maximum(u0.max(axis=1), u1.max(axis=1)) - umin
    n = np.maximum(1, FL.strip_count(np.maximum(width, 1e-300), spacing_m))
    u_start = umin + (width - n * spacing_m) / 2.0
    todo = np.flatnonzero(n <= MAX_STRIPS)
    budget = np.cumsum(n[todo] + len(edges)) // _COST_CHUNK_BANDS
    for chunk in np.split(todo, np.flatnonzero(np.diff(budget)) + 1):
        if len(chunk):
            out[chunk] = _costs_chunk(u0[chunk], v0[chunk], u1[chunk], v1[chunk], n[chunk],
                                      u_start[chunk], spacing_m, base_m, extension, turn)
    return out


def _costs_chunk(u0: np.ndarray, v0: np.ndarray, u1: np.ndarray, v1: np.ndarray,
                 n: np.ndarray, u_start: np.ndarray, spacing_m: float, base_m: float,
                 extension: int, turn: Turn) -> list[float]:
    """:func:`_costs` of the directions whose edges (rows of ``u0`` … ``v1``), strip counts
    ``n`` and first band edges ``u_start`` are given: :func:`band_extents` over every
    (direction, edge) pair, then each direction's strips and connections."""
    n_dir, n_edges = u0.shape
    lo_u, hi_u = np.minimum(u0, u1), np.maximum(u0, u1)
    top = (n - 1)[:, None]
    k0 = np.clip(np.floor((lo_u - u_start[:, None]) / spacing_m), 0, top).astype(np.int64)
    k1 = np.clip(np.floor((hi_u - u_start[:, None]) / spacing_m), 0, top).astype(np.int64)
    counts = (k1 - k0 + 1).ravel()
    pair = np.repeat(np.arange(n_dir * n_edges), counts)  # (direction, edge) of each band cut
    d = pair // n_edges
    k = k0.ravel()[pair] + (np.arange(int(counts.sum()))
                            - np.repeat(np.cumsum(counts) - counts, counts))
    a = u_start[d] + k * spacing_m
    u0f, v0f = u0.ravel()[pair], v0.ravel()[pair]
    du, dv = u1.ravel()[pair] - u0f, v1.ravel()[pair] - v0f
    with np.errstate(divide="ignore", invalid="ignore"):
        ta, tb = (a - u0f) / du, (a + spacing_m - u0f) / du
    flat = du == 0
    t_lo = np.where(flat, 0.0, np.clip(np.minimum(ta, tb), 0.0, 1.0))
    t_hi = np.where(flat, 1.0, np.clip(np.maximum(ta, tb), 0.0, 1.0))
    va, vb = v0f + t_lo * dv, v0f + t_hi * dv
    band0 = np.r_[0, np.cumsum(n)[:-1]]  # each direction's first band
    lo = np.full(int(n.sum()), np.inf)
    hi = np.full(int(n.sum()), -np.inf)
    np.minimum.at(lo, band0[d] + k, np.minimum(va, vb))
    np.maximum.at(hi, band0[d] + k, np.maximum(va, vb))
    band_dir = np.repeat(np.arange(n_dir), n)
    band_k = np.arange(len(lo)) - band0[band_dir]
    keep = np.isfinite(lo)
    lo, hi, band_dir = lo[keep], hi[keep], band_dir[keep]
    u = u_start[band_dir] + (band_k[keep] + 0.5) * spacing_m
    n_photos = _photos_per_part(hi - lo, base_m, extension)
    half = (n_photos - 1) * base_m / 2.0
    mid = (lo + hi) / 2.0
    first, last = mid - half, mid + half
    m = np.bincount(band_dir, minlength=n_dir)  # strips kept per direction
    start = np.r_[0, np.cumsum(m)[:-1]]
    # connection i → i + 1 within a direction; strip j of a direction is flown +v when even
    j = np.arange(len(u)) - start[band_dir]
    same = band_dir[1:] == band_dir[:-1]
    forward = (j[:-1] % 2) == 0
    end_i = np.where(forward, last[:-1], first[:-1])
    start_next = np.where(forward, last[1:], first[1:])
    conn = turn_length_m((u[1:] - u[:-1])[same], (start_next - end_i)[same], turn)
    conn_start = np.r_[0, np.cumsum(np.maximum(m - 1, 0))[:-1]]  # direction i's first
    span = last - first
    costs = []
    for a_, m_, c_ in zip(start.tolist(), m.tolist(), conn_start.tolist(), strict=True):
        strips = np.add.reduce(span[a_:a_ + m_])  # np.sum's pairwise sum, as in _cost
        turns = np.add.reduce(conn[c_:c_ + max(m_ - 1, 0)])
        costs.append(float(strips + turns))
    return costs


def _auto_direction(geom: object, origin: tuple[float, float], spacing_m: float,
                    base_m: float, extension: int, turn: Turn) -> tuple[float, int]:
    """The direction of least flight length, and how many directions were tried.

    The candidates: every edge direction of the convex hull (the least width across the
    lines, which sets the number of strips, lies along one of them: rotating calipers) and
    a sweep every 2°, then twice around the best three (0.5° steps within ±2°, 0.1° steps
    within ±0.5°); each stage's new directions are costed in one call of :func:`_costs`.
    """
    simple = shapely.simplify(geom, min(spacing_m, base_m) / 4.0, preserve_topology=True)
    edges = _edges(simple)
    hull = shapely.get_coordinates(shapely.convex_hull(simple))
    d = np.diff(hull, axis=0)
    d = d[np.hypot(d[:, 0], d[:, 1]) > 0]
    hull_dirs = np.round(np.degrees(np.arctan2(d[:, 0], d[:, 1])) % 180.0, 6)
    tried: dict[float, float] = {}

    def run(cands: np.ndarray) -> None:
        new = [float(c) for c in np.unique(np.round(np.asarray(cands) % 180.0, 6))
               if float(c) not in tried]
        tried.update(zip(new, _costs(edges, new, origin, spacing_m, base_m, extension,
                                     turn).tolist(), strict=True))

    run(np.r_[hull_dirs, np.arange(0.0, 180.0, _AUTO_SWEEP_DEG)])
    for step, reach in ((0.5, 2.0), (0.1, 0.5)):
        best = sorted(tried, key=tried.__getitem__)[:3]
        run(np.concatenate([b + np.arange(-reach, reach + 1e-9, step) for b in best]))
    best = min(tried, key=lambda k: (tried[k], k))
    return float(best % 180.0), len(tried)


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
    turn: Turn = Turn(),
    speed_ms: float | None = None,
    max_flight_time_min: float | None = None,
    ground_m: float = 0.0,
    photo_values: Mapping[str, float] | None = None,
    kind: str = "uav",
    takeoff_xy_m: tuple[float, float] | None = None,
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
    plan, ex_strip, reason = _sortie_plan(parts, turn, takeoff_uv, speed_ms,
                                          max_flight_time_min, notes)
    length = float(np.sum(plan.length_m))
    turns = _turns_flown(plan, ex_strip, parts.conn)
    notes["transit_m"] = float(np.sum(plan.transit_m))
    if reason is None:
        reason = _single_strip_reason(parts, spacing_m, rot)
    strips, photos = _records(parts, plan, ex_strip, _to_plan_xy(direction, origin), area,
                              height_m, ground_m, photo_values or {}, notes)
    return FlightLayout(strips=strips, sorties=plan.records(speed_ms), photos=photos,
                        flight_length_m=length, turn_length_m=turns,
                        flight_time_s=_time_s(length, speed_ms), feasible=reason is None,
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
    first_photo = np.r_[0, np.cumsum(photos_per_strip)[:-1]] + 1
    segs = np.bincount(p_strip, minlength=n_strips)
    parts_of: list[list[tuple[tuple[float, float], tuple[float, float]]]] = [
        [] for _ in range(n_strips)]
    for k in range(len(p_strip)):
        parts_of[int(p_strip[k])].append(((float(psx[k]), float(psy[k])),
                                          (float(pex[k]), float(pey[k]))))
    strips = tuple(
        Strip(number=i + 1, start_xy_m=(float(sx[i]), float(sy[i])),
              end_xy_m=(float(ex[i]), float(ey[i])), length_m=float(s_hi[i] - s_lo[i]),
              photos=int(photos_per_strip[i]), first_photo=int(first_photo[i]),
              sortie=int(sortie_of[i]) + 1, segments=int(segs[i]),
              parts=tuple(parts_of[i]), continued=continued.get(i, ()))
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
    nth = np.arange(int(kept.sum())) - np.r_[0, np.cumsum(kept)[:-1]][part]
    local = np.minimum(nth * k, n_per[part] - 1)
    v = parts.first[part] + parts.base_m * local
    strip = parts.p_strip[part]
    order = np.lexsort((np.where(strip % 2 == 0, v, -v), strip))
    strip, v = strip[order], v[order]
    start = np.r_[0.0, np.cumsum(parts.strip_len[:-1] + parts.conn)]
    return strip, v, start[strip] + np.abs(v - parts.forward_v[strip])


def _sortie_plan(parts: _Parts, turn: Turn, takeoff_uv: tuple[float, float] | None,
                 speed_ms: float | None, max_min: float | None, notes: dict[str, object]
                 ) -> tuple[SortiePlan, np.ndarray, Message | None]:
    """The sorties (:func:`scanplan.geo.sorties.pack_sorties`), the strip of every
    exposure in flight order, and why the block cannot be flown (None if it can).

    Each sortie flies its run-in (:attr:`Turn.lead_m`) before its first exposure and a
    run-out of at least half a base past its last (where the camera trigger stops,
    :mod:`scanplan.geo.mission`); with a take-off point, the transit there and back.
    """
    ex_strip, ex_v, path = _flight_order(parts)
    lead_in = turn.lead_m
    lead_out = max(turn.lead_m, parts.base_m / 2.0)
    zeros = np.zeros(len(ex_v))
    if takeoff_uv is None:
        t_in = t_out = zeros
    else:
        sign = np.where(ex_strip % 2 == 0, 1.0, -1.0)
        du = parts.u_m[ex_strip] - takeoff_uv[0]
        t_in = np.hypot(du, ex_v - sign * lead_in - takeoff_uv[1])
        t_out = np.hypot(du, ex_v + sign * lead_out - takeoff_uv[1])
    limit = None
    if max_min and speed_ms:
        with np.errstate(over="ignore"):
            limit = max_min * 60.0 * speed_ms
        if not math.isfinite(limit) or not np.isfinite(path).all():
            limit = None
        elif limit < parts.base_m:
            plan, _ = pack_sorties(path, ex_strip, t_in, t_out, lead_in_m=lead_in,
                                   lead_out_m=lead_out, limit_m=None)
            return plan, ex_strip, Message("layout.sortie_too_short", limit=max_min,
                                           base=parts.base_m, speed=speed_ms)
    if limit is not None and len(path):
        notes["packing_bound"] = packing_bound(float(path[-1] - path[0]) + lead_in
                                               + lead_out, limit)
    plan, reason = pack_sorties(path, ex_strip, t_in, t_out, lead_in_m=lead_in,
                                lead_out_m=lead_out, limit_m=limit, max_minutes=max_min)
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
    starts = np.r_[0, np.cumsum(n_per)[:-1]]
    local = np.arange(total) - starts[part]
    sign = np.where(pf, 1.0, -1.0)[part]
    v = p_start[part] + sign * base_m * local
    strip0 = p_strip[part]
    x, y = to_xy(u[strip0], v)  # type: ignore[operator]
    running = np.arange(1, total + 1)  # flight order: the order of ``sortie``
    if area.georeferenced:
        lon, lat = geocrs.transformer(area.plan_crs, 4326).transform(x, y)
        lon, lat = np.asarray(lon, dtype=float), np.asarray(lat, dtype=float)
    else:
        lon = lat = np.full(total, np.nan)
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
    return Photos(cols)

"""The "auto" flight direction: the direction of least flight length (docs/flight-lines.md).

The candidates are every edge direction of the area's convex hull — the least width across
the lines, which sets the number of strips, lies along one of them (rotating calipers) —
and a sweep every 2°, then twice the neighbourhood of the best three (0.5° steps within
±2°, 0.1° steps within ±0.5°). Each candidate's cost is the serpentine's exact flight
length on a slightly simplified outline (strips with their extensions, rounded to the
base, and the connections with the chosen turn), found by cutting every boundary edge to
every band with numpy (:func:`band_extents`); each stage's new candidates are costed in one
pass over every (direction, edge, band) (:func:`_costs`), equal to the last bit to costing
each on its own (:func:`_cost`, tests/test_geo_lines.py).

Beside it, a crew lays the lines along the area's long axis — fewer, longer strips, fewer
turns — (:func:`long_axis_deg`: the long side of the area's minimum-area enclosing
rectangle, shapely's ``oriented_envelope``, the rotating-calipers rectangle of the convex
hull: H. Freeman and R. Shapira, "Determining the minimum-area encasing rectangle for an
arbitrary closed curve", *Comm. ACM* 18(7), 409–413, 1975) and, over relief flown one
altitude per strip, along the direction whose strips span the least relief
(:mod:`scanplan.geo.terrain_choice`); the plans compared are in docs/plan-choice.md.
"""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np
import shapely

from ..core import flight as FL
from .strips import (
    MAX_STRIPS,
    Turn,
    _connections,
    _photos_per_part,
    _strip_spans,
    run_sums,
    turn_length_m,
)

__all__ = ["band_extents", "long_axis_deg", "same_direction"]

_AUTO_SWEEP_DEG = 2.0
_COST_CHUNK_BANDS = 500_000
"""Bands (plus edges) per chunk of directions in the "auto" search's costing (memory bound)."""


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
    band0 = np.concatenate(([0], np.cumsum(n)[:-1]))  # each direction's first band
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
    start = np.concatenate(([0], np.cumsum(m)[:-1]))
    # connection i → i + 1 within a direction; strip j of a direction is flown +v when even
    j = np.arange(len(u)) - start[band_dir]
    same = band_dir[1:] == band_dir[:-1]
    forward = (j[:-1] % 2) == 0
    end_i = np.where(forward, last[:-1], first[:-1])
    start_next = np.where(forward, last[1:], first[1:])
    conn = turn_length_m((u[1:] - u[:-1])[same], (start_next - end_i)[same], turn)
    conn_start = np.concatenate(([0], np.cumsum(np.maximum(m - 1, 0))[:-1]))  # direction i's first
    # each direction's sums over its own strips and turns: np.sum's, as in _cost
    strips = run_sums(last - first, start, m)
    turns = run_sums(conn, conn_start, np.maximum(m - 1, 0))
    return (strips + turns).tolist()


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
        # the distinct directions, ascending (sorted(set()), not np.unique: that imports
        # numpy.ma to check for a mask, 15-20 ms of a fresh process's first plan)
        new = [c for c in sorted(set(np.round(np.asarray(cands, dtype=float) % 180.0,
                                              6).tolist())) if c not in tried]
        tried.update(zip(new, _costs(edges, new, origin, spacing_m, base_m, extension,
                                     turn).tolist(), strict=True))

    run(np.r_[hull_dirs, np.arange(0.0, 180.0, _AUTO_SWEEP_DEG)])
    for step, reach in ((0.5, 2.0), (0.1, 0.5)):
        best = sorted(tried, key=tried.__getitem__)[:3]
        run(np.concatenate([b + np.arange(-reach, reach + 1e-9, step) for b in best]))
    best = min(tried, key=lambda k: (tried[k], k))
    return float(best % 180.0), len(tried)


# -------------------------------------------------------------------------------------------
# The directions a crew would consider beside "auto"
# -------------------------------------------------------------------------------------------
SAME_DIRECTION_DEG = 1.0
"""Two directions closer than this are one candidate [°]."""


def long_axis_deg(geometry: object) -> float | None:
    """The direction of the long side of the area's minimum-area enclosing rectangle,
    clockwise from grid north [°, 0–180), as ``[area] direction_deg`` takes it.

    Parameters
    ----------
    geometry : shapely geometry
        The area in its planning CRS.

    Returns
    -------
    float or None
        None for an area without extent (a point, a line of zero length).

    Examples
    --------
    >>> from shapely.geometry import box
    >>> long_axis_deg(box(0, 0, 1000, 200)), long_axis_deg(box(0, 0, 200, 1000))
    (90.0, 0.0)
    """
    rect = shapely.oriented_envelope(geometry)
    if rect.geom_type != "Polygon" or rect.is_empty:
        return None
    xy = np.asarray(rect.exterior.coords, dtype=float)[:3]
    sides = np.diff(xy, axis=0)  # two adjacent sides
    lengths = np.hypot(sides[:, 0], sides[:, 1])
    if not lengths.max() > 0:
        return None
    dx, dy = sides[int(np.argmax(lengths))]
    bearing = math.degrees(math.atan2(dx, dy)) % 180.0  # clockwise from grid north
    return round(bearing, 6) % 180.0


def same_direction(a_deg: float, b_deg: float) -> bool:
    """Whether two line directions are one candidate (within :data:`SAME_DIRECTION_DEG`,
    modulo 180°).

    >>> same_direction(0.4, 179.8), same_direction(10.0, 12.0)
    (True, False)
    """
    d = abs((a_deg - b_deg + 90.0) % 180.0 - 90.0)
    return d < SAME_DIRECTION_DEG

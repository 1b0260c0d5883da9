"""Overlaps over the relief: every photo with its neighbours along and across the strips.

Forward: two consecutive photos of a strip (not across a gap of a split strip, more than
1.5 bases); side: a photo and the nearest photo, along the line, of the neighbouring strip.
For a pair at distance d, with the ground g_mid at the midpoint and the mean altitude A of
the two: overlap = 1 − d / (sensor side / f · (A − g_mid)). Flown low by the tolerance
down, the footprint shrinks by (1 − tolerance). Whether they are short of the plan:
:func:`scanplan.rules.terrain.overlap_warnings`.
"""

from __future__ import annotations

import itertools
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import NDArray

from ..core.photoscale import footprint_side_m
from .layout import FlightLayout, line_axes

if TYPE_CHECKING:
    from .terrain import Ground

# --- overlaps ------------------------------------------------------------------------------

@dataclass(frozen=True)
class Pairs:
    """Pairs of neighbouring photos: indices ``a``, ``b`` in strip order, their distance
    along (forward) or across (side) the strips [m]."""

    a: NDArray[np.int64]
    b: NDArray[np.int64]
    distance_m: NDArray[np.float64]


def _forward_pairs(x: NDArray[np.float64], y: NDArray[np.float64], strip: NDArray[np.int64],
                   along: NDArray[np.float64], base_m: float) -> Pairs:
    """Consecutive photos of a strip (in strip order), not across a split (> 1.5 bases)."""
    same = strip[1:] == strip[:-1]
    d = np.abs(np.diff(x * along[0] + y * along[1]))
    ok = same & (d <= 1.5 * base_m + 1e-9)
    a = np.flatnonzero(ok)
    return Pairs(a, a + 1, d[ok])


def _side_pairs(x: NDArray[np.float64], y: NDArray[np.float64], strip: NDArray[np.int64],
                along: NDArray[np.float64], across: NDArray[np.float64]) -> Pairs:
    """Each photo and the nearest photo (along the line) of the next strip across."""
    u = x * along[0] + y * along[1]
    v = x * across[0] + y * across[1]
    by_strip = np.argsort(strip, kind="stable")  # each strip's photos, in their order
    numbers, starts = np.unique(strip[by_strip], return_index=True)
    ends = np.append(starts[1:], strip.size)[:starts.size]
    members = {int(k): by_strip[s:e] for k, s, e in zip(numbers.tolist(), starts.tolist(),
                                                         ends.tolist(), strict=True)}
    mean_v = np.array([v[members[k]].mean() for k in numbers.tolist()])
    by_v = numbers[np.argsort(mean_v)]
    pairs = list(itertools.pairwise(by_v))
    if np.ndim(along) > 1:  # a crosshatch: neighbours within each pass (one direction)
        first = {k: int(members[k][0]) for k in numbers.tolist()}
        heading = {k: (round(float(along[0][i]), 9), round(float(along[1][i]), 9))
                   for k, i in first.items()}
        pairs = [(k0, k1) for k0, k1 in (
            pair for d in dict.fromkeys(heading.values())
            for pair in itertools.pairwise([k for k in by_v if heading[int(k)] == d]))]
    a_all, b_all, d_all = [], [], []
    for k0, k1 in pairs:
        i0 = members[int(k0)]
        i1 = members[int(k1)]
        order = np.argsort(u[i1])
        us = u[i1][order]
        u0 = u[i0]
        if us.size == 1:  # the one photo of the next strip
            pick = np.zeros(u0.size, dtype=np.int64)
        else:  # the nearer of the two photos on either side along the line
            right = np.minimum(np.maximum(np.searchsorted(us, u0), 1), us.size - 1)
            left = right - 1
            pick = np.where(np.abs(us[left] - u0) <= np.abs(us[right] - u0), left, right)
        j = i1[order][pick]
        a_all.append(i0)
        b_all.append(j)
        d_all.append(np.abs(v[j] - v[i0]))
    if not a_all:
        e = np.zeros(0, dtype=np.int64)
        return Pairs(e, e, np.zeros(0))
    return Pairs(np.concatenate(a_all), np.concatenate(b_all), np.concatenate(d_all))


def _pair_overlap_pct(p: Pairs, x: NDArray[np.float64], y: NDArray[np.float64],
                      alt: NDArray[np.float64], ground: Ground, plan_crs: str,
                      side_mm: float, focal_mm: float, down: float) -> NDArray[np.float64]:
    """Overlap of each pair [%]: 1 − d / footprint(A − g_mid), flown low by ``down``."""
    if p.a.size == 0:
        return np.zeros(0)
    mx, my = (x[p.a] + x[p.b]) / 2, (y[p.a] + y[p.b]) / 2
    g = ground.sample(mx, my, plan_crs)
    g = np.where(np.isfinite(g), g, ground.high_m)
    agl = (alt[p.a] + alt[p.b]) / 2 - g
    fp = footprint_side_m(side_mm, agl, focal_mm) * (1.0 - down)
    with np.errstate(divide="ignore", invalid="ignore"):
        return np.where(fp > 0, (1.0 - p.distance_m / fp) * 100.0, -np.inf)


def _per_photo_min(n: int, p: Pairs, values: NDArray[np.float64]) -> NDArray[np.float64]:
    out = np.full(n, np.inf)
    np.minimum.at(out, p.a, values)
    np.minimum.at(out, p.b, values)
    return np.where(np.isfinite(out), out, np.nan)


@dataclass(frozen=True)
class Overlaps:
    """Forward and side pairs, the overlap of each [%], and per photo the smaller [%]."""

    forward: Pairs
    side: Pairs
    forward_pct: NDArray[np.float64]
    side_pct: NDArray[np.float64]
    forward_photo: NDArray[np.float64]  # per photo, the smaller with its neighbours
    side_photo: NDArray[np.float64]


def photo_overlaps(layout: FlightLayout, cols: dict[str, NDArray[Any]], alt: NDArray[np.float64],
                   ground: Ground, sensor_width_mm: float, sensor_height_mm: float,
                   focal_mm: float, down: float) -> Overlaps:
    """Forward and side overlaps of every pair and of every photo (strip order) [%].

    ``sensor_width_mm`` lies across the strips, ``sensor_height_mm`` along them; ``down``
    is the height tolerance downwards (a fraction): the photos are flown that much low.
    """
    x, y = cols["x_m"].astype(float), cols["y_m"].astype(float)
    strip = cols["strip"].astype(np.int64)
    plan_crs = layout.area.plan_crs
    along, across = line_axes(layout.directions_deg(strip))
    fw = _forward_pairs(x, y, strip, along, layout.base_m)
    sd = _side_pairs(x, y, strip, along, across)
    fw_pct = _pair_overlap_pct(fw, x, y, alt, ground, plan_crs, sensor_height_mm, focal_mm,
                               down)
    sd_pct = _pair_overlap_pct(sd, x, y, alt, ground, plan_crs, sensor_width_mm, focal_mm, down)
    n = x.size
    return Overlaps(fw, sd, fw_pct, sd_pct, _per_photo_min(n, fw, fw_pct),
                     _per_photo_min(n, sd, sd_pct))

"""Overlaps over the relief: every photo with its neighbours along and across the strips.

Forward: two consecutive photos of a strip (not across a gap of a split strip, more than
1.5 bases); side: a photo and the nearest photo, along the line, of the neighbouring strip.
For a pair at distance d, with the ground g_mid at the midpoint and the mean altitude A of
the two: overlap = 1 − d / (sensor side / f · (A − g_mid)). Flown low by the tolerance
down, the footprint shrinks by (1 − tolerance). Split from :mod:`.terrain`.
"""

from __future__ import annotations

import itertools
import math
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import NDArray

from ..messages import Message
from ..rules.results import PlanWarning, UavInputs
from .layout import FlightLayout

if TYPE_CHECKING:
    from .terrain import Ground

MAX_LISTED = 6
"""Photos or strips named in one warning; the rest are counted."""


def _listing(numbers: NDArray[np.int64]) -> str:
    """``3, 4, 7`` or ``3, 4, 7, 9, 12, 15 and 40 more``."""
    shown = ", ".join(str(int(v)) for v in numbers[:MAX_LISTED])
    more = numbers.size - MAX_LISTED
    return shown + (f" (+{more})" if more > 0 else "")


# --- overlaps ------------------------------------------------------------------------------

def _axes(direction_deg: float) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    t = math.radians(direction_deg)
    return np.array([math.sin(t), math.cos(t)]), np.array([math.cos(t), -math.sin(t)])


@dataclass(frozen=True)
class _Pairs:
    a: NDArray[np.int64]
    b: NDArray[np.int64]
    distance_m: NDArray[np.float64]


def _forward_pairs(x: NDArray[np.float64], y: NDArray[np.float64], strip: NDArray[np.int64],
                   along: NDArray[np.float64], base_m: float) -> _Pairs:
    """Consecutive photos of a strip (in strip order), not across a split (> 1.5 bases)."""
    same = strip[1:] == strip[:-1]
    d = np.abs(np.diff(x * along[0] + y * along[1]))
    ok = same & (d <= 1.5 * base_m + 1e-9)
    a = np.flatnonzero(ok)
    return _Pairs(a, a + 1, d[ok])


def _side_pairs(x: NDArray[np.float64], y: NDArray[np.float64], strip: NDArray[np.int64],
                along: NDArray[np.float64], across: NDArray[np.float64]) -> _Pairs:
    """Each photo and the nearest photo (along the line) of the next strip across."""
    u = x * along[0] + y * along[1]
    v = x * across[0] + y * across[1]
    numbers = np.unique(strip)
    mean_v = np.array([v[strip == k].mean() for k in numbers])
    by_v = numbers[np.argsort(mean_v)]
    a_all, b_all, d_all = [], [], []
    for k0, k1 in itertools.pairwise(by_v):
        i0 = np.flatnonzero(strip == k0)
        i1 = np.flatnonzero(strip == k1)
        order = np.argsort(u[i1])
        us = u[i1][order]
        pos = np.clip(np.searchsorted(us, u[i0]), 1, max(us.size - 1, 1))
        left = np.clip(pos - 1, 0, us.size - 1)
        right = np.clip(pos, 0, us.size - 1)
        pick = np.where(np.abs(us[left] - u[i0]) <= np.abs(us[right] - u[i0]), left, right)
        j = i1[order][pick]
        a_all.append(i0)
        b_all.append(j)
        d_all.append(np.abs(v[j] - v[i0]))
    if not a_all:
        e = np.zeros(0, dtype=np.int64)
        return _Pairs(e, e, np.zeros(0))
    return _Pairs(np.concatenate(a_all), np.concatenate(b_all), np.concatenate(d_all))


def _pair_overlap_pct(p: _Pairs, x: NDArray[np.float64], y: NDArray[np.float64],
                      alt: NDArray[np.float64], ground: Ground, plan_crs: str,
                      side_mm: float, focal_mm: float, down: float) -> NDArray[np.float64]:
    """Overlap of each pair [%]: 1 − d / footprint(A − g_mid), flown low by ``down``."""
    if p.a.size == 0:
        return np.zeros(0)
    mx, my = (x[p.a] + x[p.b]) / 2, (y[p.a] + y[p.b]) / 2
    g = ground.sample(mx, my, plan_crs)
    g = np.where(np.isfinite(g), g, ground.high_m)
    agl = (alt[p.a] + alt[p.b]) / 2 - g
    fp = side_mm / focal_mm * agl * (1.0 - down)
    with np.errstate(divide="ignore", invalid="ignore"):
        return np.where(fp > 0, (1.0 - p.distance_m / fp) * 100.0, -np.inf)


def _per_photo_min(n: int, p: _Pairs, values: NDArray[np.float64]) -> NDArray[np.float64]:
    out = np.full(n, np.inf)
    np.minimum.at(out, p.a, values)
    np.minimum.at(out, p.b, values)
    return np.where(np.isfinite(out), out, np.nan)


@dataclass(frozen=True)
class _Overlaps:
    forward: _Pairs
    side: _Pairs
    forward_pct: NDArray[np.float64]
    side_pct: NDArray[np.float64]
    forward_photo: NDArray[np.float64]  # per photo, the smaller with its neighbours
    side_photo: NDArray[np.float64]


def _overlaps(layout: FlightLayout, cols: dict[str, NDArray[Any]], alt: NDArray[np.float64],
              ground: Ground, inp: UavInputs) -> _Overlaps:
    """Forward and side overlaps of every pair and of every photo (strip order)."""
    x, y = cols["x_m"].astype(float), cols["y_m"].astype(float)
    strip = cols["strip"].astype(np.int64)
    down = inp.height_tolerance_down_pct / 100.0
    plan_crs = layout.area.plan_crs
    along, across = _axes(layout.direction_deg)
    fw = _forward_pairs(x, y, strip, along, layout.base_m)
    sd = _side_pairs(x, y, strip, along, across)
    fw_pct = _pair_overlap_pct(fw, x, y, alt, ground, plan_crs, inp.sensor_height_mm,
                               inp.focal_mm, down)
    sd_pct = _pair_overlap_pct(sd, x, y, alt, ground, plan_crs, inp.sensor_width_mm,
                               inp.focal_mm, down)
    n = x.size
    return _Overlaps(fw, sd, fw_pct, sd_pct, _per_photo_min(n, fw, fw_pct),
                     _per_photo_min(n, sd, sd_pct))


def _overlap_warnings(inp: UavInputs, fw: _Pairs, fw_pct: NDArray[np.float64], sd: _Pairs,
                      sd_pct: NDArray[np.float64], cols: dict[str, NDArray[Any]]
                      ) -> list[PlanWarning]:
    out = []
    for kind, pairs, pct, planned in (("forward", fw, fw_pct, inp.forward_overlap_pct),
                                      ("side", sd, sd_pct, inp.side_overlap_pct)):
        if pct.size == 0:
            continue
        short = pct < planned - 0.05
        if not short.any():
            continue
        i = int(np.argmin(pct))
        photos = np.unique(np.concatenate([cols["photo"][pairs.a[short]],
                                           cols["photo"][pairs.b[short]]])).astype(np.int64)
        floor = 50.0 if kind == "forward" else 0.0
        out.append(PlanWarning(f"terrain_{kind}_overlap", Message(
            f"terrain_{kind}_overlap", value=float(pct[i]), planned=planned,
            a=int(cols["photo"][pairs.a[i]]), b=int(cols["photo"][pairs.b[i]]),
            count=int(photos.size), photos=_listing(photos),
            floor=Message(f"terrain_overlap_floor.{kind}") if pct[i] <= floor else None),
            severity="warning"))
    return out

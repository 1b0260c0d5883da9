"""The worst ground of every photo: over its footprint and under its stretch of the path.

Between two photo centres lies a base of ground no centre sees, and a footprint is much
wider than a base: a pit or a ridge between centres changes the finest scale and the
clearance the plan promises. So every photo gets, at the DEM's resolution
(:class:`~scanplan.geo.dem_grid.GroundGrid`):

* its **stretch of the path**: the flight line from the midpoint towards the previous
  photo to the midpoint towards the next; the first and the last photo of a strip reach
  further, by the run-in and run-out the layout flies (``notes["run_in_m"]`` when the
  layout states it, else its turnaround distance, its turn radius, or half the line
  spacing for a semicircle turn). The highest ground there sets the altitude (the
  clearance), the lowest bounds the height above ground the altitude ceiling limits;
* its **footprint** at the altitude it is flown: the lowest ground there gives its
  largest height above ground, so its coarsest GSD, ground resolution and recognition
  probability; the highest is reported beside it. The footprint is taken at the height
  above the lowest ground found (one refinement: a pit makes the footprint larger).

Where the ground is unknown (outside the DEM, no-data beyond the fill radius, or only a
``[min, max]`` range given) the block's lowest and highest ground stand in.
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from .dem_grid import GroundGrid
from .layout import FlightLayout, line_axes

__all__ = ["PathGround", "footprint_ground", "path_ground", "run_in_m"]


def run_in_m(layout: FlightLayout) -> float:
    """How far the aircraft flies the line before its first and after its last photo [m].

    ``notes["run_in_m"]`` when the layout states it; else the turn it was counted with:
    a turnaround distance, a turn radius, or half the line spacing (a semicircle).
    """
    stated = layout.notes.get("run_in_m")
    if stated is not None and math.isfinite(float(stated)):
        return float(stated)
    m = re.match(r"(turnaround|radius)\s+([0-9.eE+-]+)", layout.turn or "")
    if m:
        return float(m.group(2))
    return layout.spacing_m / 2.0 if math.isfinite(layout.spacing_m) else 0.0


@dataclass(frozen=True)
class PathGround:
    """Lowest and highest ground under each photo's stretch of the path [m] (strip order;
    the block's extremes where unknown); ``known`` where the DEM gave it."""

    low_m: NDArray[np.float64]
    high_m: NDArray[np.float64]
    known: NDArray[np.bool_]


def path_ground(grid: GroundGrid | None, x_m: NDArray[np.float64], y_m: NDArray[np.float64],
                strip: NDArray[np.int64], direction_deg: float | NDArray[np.float64],
                extend_m: float,
                low_m: float, high_m: float) -> PathGround:
    """The ground under each photo's stretch of its flight line (module notes).

    Parameters
    ----------
    grid : GroundGrid or None
        None without a DEM: every stretch lies between ``low_m`` and ``high_m``.
    x_m, y_m, strip : ndarray
        Photo centres in strip order, each strip in flight order.
    direction_deg : float or ndarray
        The lines' direction [°] (one per photo for a crosshatch).
    extend_m : float
        Run-in and run-out past the first and last photo of a strip [m].
    low_m, high_m : float
        The block's lowest and highest ground, for unknown ground [m].
    """
    n = x_m.size
    if grid is None or n == 0:
        return PathGround(np.full(n, low_m), np.full(n, high_m), np.zeros(n, dtype=bool))
    along, _ = line_axes(direction_deg)
    u = x_m * along[0] + y_m * along[1]
    first = np.ones(n, dtype=bool)
    first[1:] = strip[1:] != strip[:-1]
    last = np.ones(n, dtype=bool)
    last[:-1] = strip[1:] != strip[:-1]
    # the flight sense of each strip: from its first photo towards its last
    starts = np.flatnonzero(first)
    ends = np.flatnonzero(last)
    sense = np.sign(u[ends] - u[starts])
    sense[sense == 0] = 1.0
    sense = np.repeat(sense, ends - starts + 1)
    prev = np.empty(n)
    prev[1:] = (u[1:] + u[:-1]) / 2.0
    nxt = np.empty(n)
    nxt[:-1] = (u[1:] + u[:-1]) / 2.0
    s = np.where(first, u - sense * extend_m, prev)
    e = np.where(last, u + sense * extend_m, nxt)
    mid = (s + e) / 2.0 - u
    cx, cy = x_m + mid * along[0], y_m + mid * along[1]
    half = (e - s) / 2.0
    a = np.column_stack([half * along[0], half * along[1]])
    lo, hi = grid.box_range(cx, cy, a, np.zeros_like(a))
    known = np.isfinite(lo) & np.isfinite(hi)
    return PathGround(np.where(known, lo, low_m), np.where(known, hi, high_m), known)


def footprint_ground(grid: GroundGrid | None, x_m: NDArray[np.float64],
                     y_m: NDArray[np.float64], altitude_m: NDArray[np.float64],
                     ground_m: NDArray[np.float64],
                     direction_deg: float | NDArray[np.float64],
                     across_per_m: float, along_per_m: float, low_m: float, high_m: float
                     ) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Lowest and highest ground over each footprint [m] (the block's extremes where
    unknown).

    The footprint is ``across_per_m`` × ``along_per_m`` times the height above ground,
    first at the height over ``ground_m`` (the centre, or the path's lowest ground), then
    once more at the height over the lowest ground found.
    """
    n = x_m.size
    if grid is None or n == 0:
        return np.full(n, low_m), np.full(n, high_m)
    along, across = line_axes(direction_deg)
    g = np.asarray(ground_m, dtype=float)
    for _ in range(2):
        agl = np.maximum(altitude_m - g, 0.0)
        ha = along_per_m * agl / 2.0
        hc = across_per_m * agl / 2.0
        lo, hi = grid.box_range(x_m, y_m, np.column_stack([ha * along[0], ha * along[1]]),
                                np.column_stack([hc * across[0], hc * across[1]]))
        g = np.where(np.isfinite(lo), np.fmin(lo, g), g)
    return np.where(np.isfinite(lo), lo, low_m), np.where(np.isfinite(hi), hi, high_m)

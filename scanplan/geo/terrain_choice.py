"""How high each altitude mode and direction lets a block be flown: an estimate from the DEM.

Over relief the largest planned height depends on the ground each altitude spans
(:mod:`scanplan.geo.terrain`): the whole block in ``constant`` mode, one strip's band in
``strip`` mode — so in ``strip`` mode the direction of the lines decides it (strips along
a valley span little relief, strips across it all of it) — and a footprint plus the
tolerance in ``follow`` mode. Photos scale with 1/H² (the line spacing and the base both
grow with H), so the height each choice allows says how many photos it needs.

The estimate reads the min-max pyramid of the DEM under the block
(:class:`~scanplan.geo.dem_grid.GroundGrid`) at a level whose blocks are at most a quarter
of the line spacing (at most :data:`MAX_BLOCKS` blocks), keeps the blocks within half a
footprint of the area, and for each direction bins them across the lines (bins of half a
spacing); a strip's relief is the range of the bins within half a footprint of its line,
for every position of the line. Vectorised over blocks; a loop over the few directions and
bin offsets only. Used to choose the direction in ``strip`` mode and to say when another
choice needs far fewer photos; the plan itself is always checked photo by photo.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from .dem_grid import GroundGrid

__all__ = ["DIRECTIONS_DEG", "MAX_BLOCKS", "ModeHeights", "mode_heights"]

DIRECTIONS_DEG = tuple(float(d) for d in range(0, 180, 5))
"""The directions tried first [°]: every 5°; then every degree around the best."""
MAX_BLOCKS = 200_000
"""Most pyramid blocks the estimate reads (a coarser level beyond)."""


@dataclass(frozen=True)
class ModeHeights:
    """The largest planned height above the reference ground each choice allows [m]
    (estimates; :func:`mode_heights`).

    ``strip_m[i]`` is for ``directions_deg[i]``."""

    constant_m: float
    follow_m: float
    directions_deg: tuple[float, ...]
    strip_m: tuple[float, ...]

    def best_strip(self) -> tuple[float, float]:
        """(direction [°], height [m]) of the highest strip-mode plan."""
        i = int(np.argmax(self.strip_m))
        return self.directions_deg[i], self.strip_m[i]


def _blocks(grid: GroundGrid, spacing_m: float, cell_m: float
            ) -> tuple[int, NDArray[np.float64], NDArray[np.float64]]:
    """The pyramid level whose blocks are at most a quarter spacing (and at most
    :data:`MAX_BLOCKS` of them), with its block centres' window pixel coordinates."""
    levels = len(grid.lo)
    k = max(0, min(levels - 1, math.floor(math.log2(max(spacing_m / 4.0 / cell_m, 1.0)))))
    while k < levels - 1 and grid.lo[k].size > MAX_BLOCKS:
        k += 1
    h, w = grid.lo[k].shape
    size = 2 ** k
    cc, rr = np.meshgrid((np.arange(w) + 0.5) * size, (np.arange(h) + 0.5) * size)
    return k, cc.ravel(), rr.ravel()


def mode_heights(grid: GroundGrid, area_geometry: object, limit_m: float, spacing_m: float,
                 footprint_across_m: float, follow_tolerance_m: float,
                 directions_deg: tuple[float, ...] = DIRECTIONS_DEG) -> ModeHeights:
    """The largest planned height each altitude mode (and, in ``strip`` mode, each
    direction) allows, from the DEM (module notes).

    Parameters
    ----------
    grid : GroundGrid
        The DEM under the block.
    area_geometry : shapely geometry
        The area (planning CRS).
    limit_m : float
        The flat-ground maximum planned height [m].
    spacing_m, footprint_across_m : float
        Line spacing and footprint across the lines at the height planned [m].
    follow_tolerance_m : float
        ``follow`` mode's tolerance [m].
    """
    import shapely
    from pyproj import CRS, Transformer

    from . import dem as D

    info = grid.info
    cell = info.cell_size[0] * (111_320.0 if info.geographic else 1.0)
    k, cc, rr = _blocks(grid, spacing_m, cell)
    lo = grid.lo[k].ravel().astype(float)
    hi = grid.hi[k].ravel().astype(float)
    left, _b, _r, top = info.bounds
    dx = left + (cc + grid.col0) * info.cell_size[0]
    dy = top - (rr + grid.row0) * info.cell_size[1]
    if grid.plan_crs.upper() != "LOCAL":
        tr = Transformer.from_crs(CRS.from_wkt(info.crs_wkt), CRS.from_user_input(grid.plan_crs),
                                  always_xy=True)
        x, y = (np.asarray(v, dtype=float) for v in tr.transform(dx, dy))
    else:
        x, y = dx, dy
    near = shapely.buffer(area_geometry, footprint_across_m / 2.0)
    keep = (shapely.contains_xy(near, x, y) & np.isfinite(lo) & np.isfinite(hi)
            & (lo < D.HIGHEST_GROUND_M + 1) & (hi > D.LOWEST_GROUND_M - 1))
    x, y, lo, hi = x[keep], y[keep], lo[keep], hi[keep]
    if x.size == 0:
        return ModeHeights(limit_m, limit_m, directions_deg, (limit_m,) * len(directions_deg))
    constant = limit_m - (hi.max() - lo.min())
    follow = limit_m - follow_tolerance_m - _footprint_relief(grid, footprint_across_m, cell)
    tried = {d: limit_m - _strip_relief(x, y, lo, hi, d, spacing_m, footprint_across_m)
             for d in directions_deg}
    best = max(tried, key=lambda d: tried[d])
    for d in (best + k for k in (-4, -3, -2, -1, 1, 2, 3, 4)):  # every degree around it
        d = float(d % 180.0)
        if d not in tried:
            tried[d] = limit_m - _strip_relief(x, y, lo, hi, d, spacing_m, footprint_across_m)
    dirs = tuple(sorted(tried))
    return ModeHeights(float(constant), float(min(follow, limit_m)), dirs,
                       tuple(float(tried[d]) for d in dirs))


def _strip_relief(x: NDArray[np.float64], y: NDArray[np.float64], lo: NDArray[np.float64],
                  hi: NDArray[np.float64], direction_deg: float, spacing_m: float,
                  footprint_m: float) -> float:
    """The largest relief a strip's band (a footprint wide) spans, lines along
    ``direction_deg``, over every position of the lines [m]."""
    t = math.radians(direction_deg)
    v = x * math.cos(t) - y * math.sin(t)  # across the lines
    step = spacing_m / 2.0
    b = np.floor((v - v.min()) / step).astype(np.int64)
    nb = int(b.max()) + 1
    blo = np.full(nb, np.inf)
    bhi = np.full(nb, -np.inf)
    np.minimum.at(blo, b, lo)
    np.maximum.at(bhi, b, hi)
    half = max(1, math.ceil(footprint_m / 2.0 / step))
    wlo = blo.copy()
    whi = bhi.copy()
    for m in range(1, half + 1):  # the band: the bins within half a footprint
        wlo[m:] = np.minimum(wlo[m:], blo[:-m])
        wlo[:-m] = np.minimum(wlo[:-m], blo[m:])
        whi[m:] = np.maximum(whi[m:], bhi[:-m])
        whi[:-m] = np.maximum(whi[:-m], bhi[m:])
    relief = whi - wlo
    relief = relief[np.isfinite(relief)]
    return float(relief.max()) if relief.size else 0.0


def _footprint_relief(grid: GroundGrid, footprint_m: float, cell_m: float) -> float:
    """The largest relief within a footprint: the range of the pyramid's blocks of about
    a footprint's side [m]."""
    k = max(0, min(len(grid.lo) - 1, math.ceil(math.log2(max(footprint_m / cell_m, 1.0)))))
    r = grid.hi[k].astype(float) - grid.lo[k].astype(float)
    r = r[np.isfinite(r)]
    return float(r.max()) if r.size else 0.0

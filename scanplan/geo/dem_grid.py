"""The ground over footprints and flight paths at the DEM's own resolution.

The photo centres alone miss a pit or a ridge between them; this module reads the DEM
under the block once, fills its small voids conservatively, and answers "lowest and
highest ground over this rectangle" for every footprint and every stretch of a flight
line at once, in bounded time and memory.

The grid
--------
The DEM pixels under the layout (the photo centres' extent, widened by a margin that holds
every footprint and run-in) are read with rasterio in windows of at most
:data:`~scanplan.geo.dem.TILE_PX` square into one float32 array in the DEM's own grid (no
warping). From it a **min-max pyramid** is built: level k holds the minimum and the
maximum of every aligned 2^k × 2^k block (level 0 is the DEM itself). A query rectangle of
w × h pixels is answered at the level where it spans at most :data:`BLOCKS_PER_SIDE`
blocks a side. A level of up to 65,536 blocks has range tables, made the first time it is
asked (the min and max over every window of 2^a × 2^b blocks): a rectangle is four
look-ups, the windows anchored at its corners. A larger level groups the rectangles by
their extent in blocks (few distinct ones) and answers each group by one separable running
minimum and maximum of that extent over the level (``scipy.ndimage``) and one gather. No
Python loop runs over photos or pixels. The answer is conservative: the
blocks cover the rectangle and at most one block (< 1/BLOCKS_PER_SIDE of its side) beyond
each edge, so the lowest ground is never higher and the highest never lower than the
ground under the rectangle.

Which pixels count: every pixel whose value enters the bilinear surface over the
rectangle (the pixels touching it and their neighbours towards it), so the range bounds
the same interpolated ground the photo centres are sampled on.

Voids (no-data inside the DEM)
------------------------------
A no-data pixel within ``radius_m`` of known ground is **filled**, separately for the two
uses: for the highest ground with the highest known ground within ``radius_m`` (a square
of half-side ``radius_m`` around it) plus ``margin_m``, for the lowest with the lowest
minus ``margin_m`` — so a void never makes the aircraft lower or the photo scale
finer than the ground around it allows. Defaults (:data:`DEFAULT_VOID_RADIUS_M`,
:data:`DEFAULT_VOID_MARGIN_M`): 50 m and 10 m, i.e. ground hidden in the void may rise
or fall 20 % (11°) from the edge of the known ground; ``[terrain] void_fill_radius_m`` and
``void_fill_margin_m`` change them. A void pixel farther from known ground stays unknown:
it is counted (inside the area) with the area the DEM's extent misses, under one rule
(:func:`scanplan.geo.terrain.ground_under`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from numpy.typing import NDArray

from ..errors import InputError
from ..io.kept import MISSING, Kept
from . import dem as D

__all__ = ["BLOCKS_PER_SIDE", "DEFAULT_VOID_MARGIN_M", "DEFAULT_VOID_RADIUS_M", "GroundGrid",
           "VoidFill", "read_ground_grid"]

DEFAULT_VOID_RADIUS_M = 50.0
"""A no-data pixel is filled when known ground lies within this distance [m]."""
DEFAULT_VOID_MARGIN_M = 10.0
"""Added to (subtracted from) the highest (lowest) known ground of a fill [m]: 20 % of
:data:`DEFAULT_VOID_RADIUS_M`, the rise of an 11° slope over the radius."""
BLOCKS_PER_SIDE = 16
"""Pyramid blocks a query rectangle spans at most per side (the over-reach is < 1/8)."""
_TABLE_EXPONENTS = (BLOCKS_PER_SIDE + 1).bit_length()
"""Range tables hold windows of 2^0 … 2^4 blocks a side: a box spans at most
:data:`BLOCKS_PER_SIDE` + 1 blocks of its level."""
_TABLE_MAX_SPAN = (2 << (_TABLE_EXPONENTS - 1)) - 1
"""The widest box the tables answer [blocks]: two windows of the largest size, 2^4, cover
up to 31 blocks."""
_KEPT_PER_GRID = 8
"""Values kept with each grid (:attr:`GroundGrid.kept`)."""
_TABLE_MAX_BLOCKS = 1 << 16
"""Levels of at most this many blocks answer from range tables (25 windows a block, 2 ×
6.6 MB at most); a larger level by running extremes and gathers."""
_GATHER_VALUES = 1 << 20
"""Block values a direct look-up gathers at once (bounds its memory, 4 MB a side)."""
_M_PER_DEG_LAT = 110_574.0  # WGS 84, metres per degree of latitude (mean, at 0°…)
_M_PER_DEG_LON_EQ = 111_320.0  # … and of longitude at the equator


@dataclass(frozen=True)
class VoidFill:
    """What the void fill did inside the area (pixels and plan-CRS m²).

    ``filled_*``: no-data pixels filled; ``unknown_*``: no-data pixels beyond the radius,
    left unknown; ``rise_m``: the most a fill stands above the lowest known ground beside
    it (the price of the margin and radius) [m].
    """

    radius_m: float
    margin_m: float
    filled_px: int = 0
    filled_m2: float = 0.0
    unknown_px: int = 0
    unknown_m2: float = 0.0
    area_px: int = 0


@dataclass(frozen=True)
class GroundGrid:
    """The DEM under a layout as a min-max pyramid (values in metres, NaN = unknown).

    Attributes
    ----------
    info : DemInfo
    col0, row0 : int
        The window's upper-left pixel in the raster.
    lo, hi : tuple of ndarray
        Level k: the lowest and highest ground of every aligned 2^k-pixel block [m].
    plan_crs : str
    voids : VoidFill
    """

    info: D.DemInfo
    col0: int
    row0: int
    lo: tuple[NDArray[np.float32], ...]
    hi: tuple[NDArray[np.float32], ...]
    plan_crs: str
    voids: VoidFill
    _tables: dict[int, tuple[NDArray[np.float32], NDArray[np.float32]]] = field(
        default_factory=dict, init=False, repr=False, compare=False)
    """Each level's range tables, made when the level is first asked (:func:`_tables`)."""
    kept: Kept[tuple[Any, ...], Any] = field(
        default_factory=lambda: Kept(_KEPT_PER_GRID), init=False, repr=False, compare=False)
    """What is computed over this grid and asked again (the ground under a layout's flight
    path: the altitude modes of one layout fly the same path), kept with the grid and gone
    with it."""

    # --- coordinates -------------------------------------------------------------------
    def to_pixels(self, x_m: NDArray[np.float64], y_m: NDArray[np.float64]
                  ) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        """Planning-CRS points as fractional (col, row) of the window (pixel edges)."""
        dx, dy = D._to_dem_crs(np.asarray(x_m, float), np.asarray(y_m, float),
                               self.plan_crs, self.info)
        left, _b, _r, top = self.info.bounds
        cw, ch = self.info.cell_size
        return (dx - left) / cw - self.col0, (top - dy) / ch - self.row0

    def box_range(self, cx_m: NDArray[np.float64], cy_m: NDArray[np.float64],
                  a_m: NDArray[np.float64], b_m: NDArray[np.float64]
                  ) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        """Lowest and highest ground over rectangles given in the planning CRS [m].

        Each rectangle is its centre (cx, cy) ± a ± b, with ``a_m`` and ``b_m`` (n × 2) its
        two half-side vectors (a segment: b = 0). The rectangle is mapped into the DEM's
        pixel grid with the local Jacobian of the CRS transformation (pyproj at the centre
        and 10 m east and north of it), its bounding box taken there. NaN where the
        rectangle lies wholly outside the DEM or touches unknown ground.
        """
        cx = np.asarray(cx_m, float)
        cy = np.asarray(cy_m, float)
        n = cx.size
        if n == 0:
            return np.zeros(0), np.zeros(0)
        step = 10.0
        c, r = self.to_pixels(np.concatenate([cx, cx + step, cx]),
                              np.concatenate([cy, cy, cy + step]))
        c0, r0 = c[:n], r[:n]
        jxx, jyx = (c[n:2 * n] - c0) / step, (r[n:2 * n] - r0) / step  # per metre east
        jxy, jyy = (c[2 * n:] - c0) / step, (r[2 * n:] - r0) / step  # per metre north
        a = np.asarray(a_m, float).reshape(n, 2)
        b = np.asarray(b_m, float).reshape(n, 2)
        half_c = (np.abs(jxx * a[:, 0] + jxy * a[:, 1]) + np.abs(jxx * b[:, 0] + jxy * b[:, 1]))
        half_r = (np.abs(jyx * a[:, 0] + jyy * a[:, 1]) + np.abs(jyx * b[:, 0] + jyy * b[:, 1]))
        return self._pixel_range(c0 - half_c, c0 + half_c, r0 - half_r, r0 + half_r)

    # --- the pyramid query -----------------------------------------------------------
    def _pixel_range(self, cmin: NDArray[np.float64], cmax: NDArray[np.float64],
                     rmin: NDArray[np.float64], rmax: NDArray[np.float64]
                     ) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        """Lowest and highest ground of the pixels entering the bilinear surface over the
        boxes [cmin, cmax] × [rmin, rmax] (window pixel-edge coordinates)."""
        h, w = self.lo[0].shape
        n = cmin.size
        lo_out = np.full(n, np.nan)
        hi_out = np.full(n, np.nan)
        ok = np.isfinite(cmin) & np.isfinite(cmax) & np.isfinite(rmin) & np.isfinite(rmax)
        # the bilinear support: pixel centres at i + 0.5 within one pixel of the box
        i0 = np.floor(np.where(ok, cmin, 0.0) - 0.5)
        i1 = np.floor(np.where(ok, cmax, 0.0) - 0.5) + 1
        j0 = np.floor(np.where(ok, rmin, 0.0) - 0.5)
        j1 = np.floor(np.where(ok, rmax, 0.0) - 0.5) + 1
        ok &= (i1 >= 0) & (i0 <= w - 1) & (j1 >= 0) & (j0 <= h - 1)
        i0 = np.clip(i0, 0, w - 1).astype(np.int64)
        i1 = np.clip(i1, 0, w - 1).astype(np.int64)
        j0 = np.clip(j0, 0, h - 1).astype(np.int64)
        j1 = np.clip(j1, 0, h - 1).astype(np.int64)
        span = np.maximum(i1 - i0, j1 - j0) + 1
        level = np.ceil(np.log2(np.maximum(span / BLOCKS_PER_SIDE, 1.0))).astype(np.int64)
        level = np.minimum(level, len(self.lo) - 1)
        for k in np.unique(level[ok]).tolist():
            sel = np.flatnonzero(ok & (level == k))
            box = (i0[sel] >> k, i1[sel] >> k, j0[sel] >> k, j1[sel] >> k)
            widest = int(max((box[1] - box[0]).max(), (box[3] - box[2]).max())) + 1
            if self.lo[k].size <= _TABLE_MAX_BLOCKS and widest <= _TABLE_MAX_SPAN:
                if k not in self._tables:
                    self._tables[k] = _tables(self.lo[k], self.hi[k])
                lo_out[sel], hi_out[sel] = _tables_range(*self._tables[k], *box)
            else:
                lo_out[sel], hi_out[sel] = _blocks_range(self.lo[k], self.hi[k], *box)
        return lo_out, hi_out


def _tables(lo: NDArray[np.float32], hi: NDArray[np.float32]
            ) -> tuple[NDArray[np.float32], NDArray[np.float32]]:
    """Range tables of one level: ``t[a, b, j, i]`` the min (max) over the 2^a × 2^b
    blocks from (j, i) (a along the rows, b down the columns), for 2^a, 2^b up to the
    widest box a level is asked (:data:`BLOCKS_PER_SIDE` + 1 blocks). Unknown ground
    (NaN) is the extreme that wins (−inf, +inf); a window reaching past the level's edge
    holds what lies inside it (it is never asked)."""
    n = _TABLE_EXPONENTS
    out = []
    for z, fill, reduce in ((lo, -np.inf, np.minimum), (hi, np.inf, np.maximum)):
        z = np.where(np.isnan(z), np.float32(fill), z)
        h, w = z.shape
        t = np.empty((n, n, h, w), dtype=np.float32)
        t[0, 0] = z
        for a in range(1, n):  # along the rows: windows 2^a blocks wide
            s = 1 << (a - 1)
            m = max(w - s, 0)
            t[a, 0] = t[a - 1, 0]
            reduce(t[a - 1, 0, :, :m], t[a - 1, 0, :, s:s + m], out=t[a, 0, :, :m])
        for b in range(1, n):  # down the columns: 2^b blocks high
            s = 1 << (b - 1)
            m = max(h - s, 0)
            t[:, b] = t[:, b - 1]
            reduce(t[:, b - 1, :m], t[:, b - 1, s:s + m], out=t[:, b, :m])
        out.append(t)
    return out[0], out[1]


def _tables_range(tlo: NDArray[np.float32], thi: NDArray[np.float32], bi0: NDArray[np.int64],
                  bi1: NDArray[np.int64], bj0: NDArray[np.int64], bj1: NDArray[np.int64]
                  ) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """min/max over the blocks [bi0, bi1] × [bj0, bj1] (inclusive) from the range tables:
    the four windows of 2^a × 2^b blocks (the largest powers of two within the box's
    sides) anchored at its corners cover it exactly; an unknown block makes the range
    unknown (NaN). The same values as :func:`_blocks_range`."""
    n, _n, h, w = tlo.shape
    a = np.log2(bi1 - bi0 + 1).astype(np.int64)  # exact: the widths are small integers
    b = np.log2(bj1 - bj0 + 1).astype(np.int64)
    ie = bi1 - (1 << a) + 1
    je = bj1 - (1 << b) + 1
    table = (a * n + b) * (h * w)  # flat indices of the four windows: one gather each
    first, last = table + bj0 * w, table + je * w
    corners = (first + bi0, first + ie, last + bi0, last + ie)
    out = []
    for t, reduce in ((tlo.reshape(-1), np.minimum), (thi.reshape(-1), np.maximum)):
        v = reduce(reduce(t.take(corners[0]), t.take(corners[1])),
                   reduce(t.take(corners[2]), t.take(corners[3])))
        out.append(v.astype(np.float64))
    bad = ~np.isfinite(out[0]) | ~np.isfinite(out[1])
    return np.where(bad, np.nan, out[0]), np.where(bad, np.nan, out[1])


def _blocks_range(lo: NDArray[np.float32], hi: NDArray[np.float32], bi0: NDArray[np.int64],
                  bi1: NDArray[np.int64], bj0: NDArray[np.int64], bj1: NDArray[np.int64]
                  ) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """min/max over the blocks [bi0, bi1] × [bj0, bj1] of one level (inclusive), an
    unknown block making the range unknown (NaN).

    The boxes are grouped by their extent in blocks (few distinct ones): for each, one
    separable running minimum and maximum of that extent over the level
    (``scipy.ndimage``, each axis once) and one gather of every box's value at its
    corner; a group needing fewer look-ups than the level has blocks gathers its blocks
    directly instead.
    """
    from scipy.ndimage import maximum_filter1d, minimum_filter1d

    # unknown ground (NaN) as the extreme that wins: −inf for the minimum, +inf for the max
    lo_k = np.where(np.isnan(lo), -np.inf, lo) if np.isnan(lo).any() else lo
    hi_k = np.where(np.isnan(hi), np.inf, hi) if np.isnan(hi).any() else hi
    wi = bi1 - bi0 + 1
    wj = bj1 - bj0 + 1
    out_lo = np.empty(bi0.size)
    out_hi = np.empty(bi0.size)
    key = wi * (int(wj.max()) + 1) + wj  # sorted by width first: one row pass kept
    rows: dict[int, tuple[NDArray[np.float32], NDArray[np.float32]]] = {}
    for kk in np.unique(key).tolist():
        sel = np.flatnonzero(key == kk)
        w, h = int(wi[sel[0]]), int(wj[sel[0]])
        if w * h * sel.size < lo.size:  # few look-ups: gather them directly
            out_lo[sel], out_hi[sel] = _gather(lo_k, hi_k, bi0[sel], bj0[sel], w, h)
            continue
        if w not in rows:  # the running extremes along the rows, w blocks wide
            rows.clear()
            rows[w] = (minimum_filter1d(lo_k, w, axis=1, mode="constant", cval=np.inf),
                       maximum_filter1d(hi_k, w, axis=1, mode="constant", cval=-np.inf))
        rlo, rhi = rows[w]
        flo = minimum_filter1d(rlo, h, axis=0, mode="constant", cval=np.inf)
        fhi = maximum_filter1d(rhi, h, axis=0, mode="constant", cval=-np.inf)
        # a window of size s holds [c − s//2, c − s//2 + s − 1]: its first block at c − s//2
        jj = bj0[sel] + h // 2
        ii = bi0[sel] + w // 2
        out_lo[sel] = flo[jj, ii]
        out_hi[sel] = fhi[jj, ii]
    bad = ~np.isfinite(out_lo) | ~np.isfinite(out_hi)
    return np.where(bad, np.nan, out_lo), np.where(bad, np.nan, out_hi)


def _gather(lo: NDArray[np.float32], hi: NDArray[np.float32], bi0: NDArray[np.int64],
            bj0: NDArray[np.int64], w: int, h: int
            ) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """min/max over the w × h blocks from (bj0, bi0): each box's blocks gathered at once
    (n × h × w values, in chunks of about a million) and reduced per box."""
    out_lo = np.empty(bi0.size)
    out_hi = np.empty(bi0.size)
    dj = np.arange(h)[None, :, None]
    di = np.arange(w)[None, None, :]
    chunk = max(1, _GATHER_VALUES // (w * h))
    for s in range(0, bi0.size, chunk):
        jj = bj0[s:s + chunk, None, None] + dj
        ii = bi0[s:s + chunk, None, None] + di
        out_lo[s:s + chunk] = lo[jj, ii].min(axis=(1, 2))
        out_hi[s:s + chunk] = hi[jj, ii].max(axis=(1, 2))
    return out_lo, out_hi


def _pyramid(z: NDArray[np.float32], fill: float, levels: int) -> tuple[NDArray[np.float32], ...]:
    """Level 0 = ``z``; level k+1 the 2 × 2 reduction (min when ``fill`` is +inf, max when
    −inf) of level k, odd edges padded with ``fill`` (no ground beyond the window)."""
    reduce = np.minimum if fill > 0 else np.maximum
    out = [z]
    for _ in range(levels):
        a = out[-1]
        h, w = a.shape
        if h == 1 and w == 1:
            break
        if h % 2 or w % 2:
            a = np.pad(a, ((0, h % 2), (0, w % 2)), constant_values=fill)
        out.append(reduce(reduce(a[0::2, 0::2], a[1::2, 0::2]),
                          reduce(a[0::2, 1::2], a[1::2, 1::2])))
    return tuple(out)


def _cell_m(info: D.DemInfo, lat_deg: float) -> tuple[float, float]:
    """The pixel's size on the ground (x, y) [m] (a geographic DEM: at ``lat_deg``)."""
    cw, ch = info.cell_size
    if info.geographic:
        return (cw * _M_PER_DEG_LON_EQ * math.cos(math.radians(lat_deg)),
                ch * _M_PER_DEG_LAT)
    return cw, ch


def _fill_voids(z: NDArray[np.float32], inside: NDArray[np.bool_], cell_m: tuple[float, float],
                radius_m: float, margin_m: float, pixel_m2: float
                ) -> tuple[NDArray[np.float32], NDArray[np.float32], VoidFill]:
    """(lowest, highest) ground with the voids filled, and what was filled (see the module
    notes). ``inside`` marks the window's pixels inside the area (for the counts)."""
    void = np.isnan(z)
    if not void.any():
        return z, z, VoidFill(radius_m, margin_m, area_px=int(inside.sum()))
    from scipy import ndimage

    if void.all():
        reach = np.zeros_like(void)
    else:
        dist = ndimage.distance_transform_edt(void, sampling=(cell_m[1], cell_m[0]))
        reach = void & (dist <= radius_m)
    size = (2 * math.ceil(radius_m / cell_m[1]) + 1, 2 * math.ceil(radius_m / cell_m[0]) + 1)
    hi = z.copy()
    lo = z.copy()
    if reach.any():
        top = ndimage.maximum_filter(np.where(void, -np.inf, z).astype(np.float32), size=size,
                                     mode="constant", cval=-np.inf)
        bottom = ndimage.minimum_filter(np.where(void, np.inf, z).astype(np.float32),
                                        size=size, mode="constant", cval=np.inf)
        hi[reach] = top[reach] + margin_m
        lo[reach] = bottom[reach] - margin_m
    filled = int((reach & inside).sum())
    unknown = int((void & ~reach & inside).sum())
    return lo, hi, VoidFill(radius_m, margin_m, filled, filled * pixel_m2, unknown,
                            unknown * pixel_m2, int(inside.sum()))


def _window(info: D.DemInfo, plan_crs: str, bounds_m: tuple[float, float, float, float]
            ) -> tuple[int, int, int, int] | None:
    """The raster window (col0, row0, width, height) holding a planning-CRS rectangle
    (its edges densified and projected), clipped to the raster; None when disjoint."""
    x0, y0, x1, y1 = bounds_m
    t = np.linspace(0.0, 1.0, 33)
    xs = np.concatenate([x0 + (x1 - x0) * t, np.full(33, x1), x1 - (x1 - x0) * t,
                         np.full(33, x0)])
    ys = np.concatenate([np.full(33, y0), y0 + (y1 - y0) * t, np.full(33, y1),
                         y1 - (y1 - y0) * t])
    dx, dy = D._to_dem_crs(xs, ys, plan_crs, info)
    left, _b, _r, top = info.bounds
    cw, ch = info.cell_size
    c = (dx - left) / cw
    r = (top - dy) / ch
    if not (np.isfinite(c).all() and np.isfinite(r).all()):
        return None
    c0 = max(math.floor(c.min()) - 2, 0)
    r0 = max(math.floor(r.min()) - 2, 0)
    c1 = min(math.ceil(c.max()) + 2, info.width_px)
    r1 = min(math.ceil(r.max()) + 2, info.height_px)
    if c1 <= c0 or r1 <= r0:
        return None
    return c0, r0, c1 - c0, r1 - r0


def _read(info: D.DemInfo, win: tuple[int, int, int, int], factor_m: float, key: str
          ) -> NDArray[np.float32]:
    """The window's pixels [m] (float32, NaN on no-data), read in tiles."""
    import rasterio
    from rasterio.errors import RasterioError
    from rasterio.windows import Window

    c0, r0, w, h = win
    if w * h > D.MAX_READ_PX:
        raise D._refuse(key, info.path, f"the area covers more than {D.MAX_READ_PX:,} of its "
                        "pixels: resample the DEM to a coarser grid under the area first")
    whole = D._whole(info)
    if whole is not None:  # a small DEM, read once: the same pixels
        z = whole[r0:r0 + h, c0:c0 + w].astype(np.float32)
        return _metres(z, factor_m)
    z = np.empty((h, w), dtype=np.float32)
    try:
        # the file open_dem checked, opened as it was: GeoTIFF only, GDAL's messages kept
        with D.gdal_messages(), rasterio.open(info.path, driver=D.GTIFF) as src:
            for rr in range(0, h, D.TILE_PX):
                for cc in range(0, w, D.TILE_PX):
                    tw, th = min(D.TILE_PX, w - cc), min(D.TILE_PX, h - rr)
                    block = src.read(1, window=Window(c0 + cc, r0 + rr, tw, th), masked=True)
                    z[rr:rr + th, cc:cc + tw] = np.ma.filled(block.astype(np.float32), np.nan)
    except (RasterioError, OSError, ValueError, MemoryError) as exc:
        raise D._refuse(key, info.path, f"could not be read ({D._short(exc)})") from None
    return _metres(z, factor_m)


def _metres(z: NDArray[np.float32], factor_m: float) -> NDArray[np.float32]:
    """``z`` (changed in place) in metres, NaN where it is not finite."""
    z[~np.isfinite(z)] = np.nan
    if factor_m != 1.0:
        z *= np.float32(factor_m)
    return z


def _inside_mask(info: D.DemInfo, area_geometry: object, plan_crs: str,
                 win: tuple[int, int, int, int]) -> NDArray[np.bool_]:
    """The window's pixels whose centre lies inside the area (rasterio.features)."""
    import shapely
    from rasterio.features import geometry_mask
    from rasterio.transform import from_origin

    c0, r0, w, h = win
    left, _b, _r, top = info.bounds
    cw, ch = info.cell_size
    geom = area_geometry
    if plan_crs.upper() != "LOCAL":
        dense = shapely.segmentize(geom, max(math.sqrt(float(geom.area)) / 64.0, 1.0))
        geom = shapely.transform(dense, lambda xy: np.column_stack(
            D._to_dem_crs(xy[:, 0], xy[:, 1], plan_crs, info)))
    tr = from_origin(left + c0 * cw, top - r0 * ch, cw, ch)
    return geometry_mask([shapely.geometry.mapping(geom)], out_shape=(h, w), transform=tr,
                         invert=True)


def read_ground_grid(info: D.DemInfo, bounds_m: tuple[float, float, float, float],
                     area_geometry: object, plan_crs: str, factor_m: float = 1.0,
                     radius_m: float = DEFAULT_VOID_RADIUS_M,
                     margin_m: float = DEFAULT_VOID_MARGIN_M,
                     key: str = "terrain.dem") -> GroundGrid | None:
    """Read the DEM under ``bounds_m`` (planning CRS) and build the min-max pyramid.

    Parameters
    ----------
    info : DemInfo
    bounds_m : tuple of float
        (xmin, ymin, xmax, ymax) in the planning CRS: every footprint and path queried
        later lies inside it [m].
    area_geometry : shapely geometry
        The area (planning CRS), for the void counts.
    plan_crs : str
    factor_m : float
        Metres per DEM value.
    radius_m, margin_m : float
        The void fill (module notes) [m].

    Returns
    -------
    GroundGrid or None
        None when the rectangle misses the raster.

    Raises
    ------
    InputError
        When the window exceeds :data:`~scanplan.geo.dem.MAX_READ_PX` or the file fails.
    """
    memo = _memo_key(info, bounds_m, area_geometry, plan_crs, factor_m, radius_m, margin_m,
                     key)
    found = _GRIDS.get(memo) if memo is not None else MISSING
    if found is not MISSING:
        return found  # type: ignore[return-value]
    grid = _read_ground_grid(info, bounds_m, area_geometry, plan_crs, factor_m, radius_m,
                             margin_m, key)
    if memo is not None:
        if grid is not None:
            for a in (*grid.lo, *grid.hi):
                a.setflags(write=False)  # shared by later plans: never changed
        _GRIDS.put(memo, grid)
    return grid


_KEPT_GRIDS = 4
_GRIDS: Kept[tuple[Any, ...], GroundGrid | None] = Kept(_KEPT_GRIDS)
"""Pyramids kept (an edit that leaves the photos' extent alone — a relief interval, an
object, the norm set — re-plans over the same one)."""


def _memo_key(info: D.DemInfo, bounds_m: tuple[float, float, float, float],
              area_geometry: object, plan_crs: str, *rest: Any) -> tuple[Any, ...] | None:
    """What a pyramid depends on: the DEM file's version (:func:`~scanplan.geo.dem.
    file_stamp`), the rectangle, the area (its WKB's SHA-256), the CRS and the fill's
    settings (None when the file cannot be looked at: read as before)."""
    import hashlib

    import shapely

    stamp = D.file_stamp(info.path)
    if stamp is None:
        return None
    area = hashlib.sha256(shapely.to_wkb(area_geometry)).hexdigest()
    return (stamp, info, tuple(map(float, bounds_m)), area, plan_crs, *rest)


def _read_ground_grid(info: D.DemInfo, bounds_m: tuple[float, float, float, float],
                      area_geometry: object, plan_crs: str, factor_m: float, radius_m: float,
                      margin_m: float, key: str) -> GroundGrid | None:
    """:func:`read_ground_grid`, read and built."""
    win = _window(info, plan_crs, bounds_m)
    if win is None:
        return None
    z = _read(info, win, factor_m, key)
    cx, cy = (bounds_m[0] + bounds_m[2]) / 2, (bounds_m[1] + bounds_m[3]) / 2
    lat = 0.0
    if info.geographic:
        lat = float(D._to_dem_crs(np.array([cx]), np.array([cy]), plan_crs, info)[1][0])
    cell = _cell_m(info, lat)
    try:
        inside = _inside_mask(info, area_geometry, plan_crs, win)
    except (ValueError, TypeError) as exc:  # a geometry rasterio cannot burn
        raise InputError(key, f"{info.path.name}: the area could not be laid on the DEM "
                         f"({D._short(exc)})") from None
    lo0, hi0, voids = _fill_voids(z, inside, cell, radius_m, margin_m, cell[0] * cell[1])
    del inside
    levels = max(math.ceil(math.log2(max(z.shape))), 0)
    lo = _pyramid(lo0, math.inf, levels)  # without voids level 0 is one array for both
    hi = _pyramid(hi0, -math.inf, levels)
    return GroundGrid(info, win[0], win[1], lo, hi, plan_crs, voids)

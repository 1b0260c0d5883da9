"""Terrain: every photo at its own height above the ground — the ground and the geometry.

The Instruction's constraints and the recognition model depend on the photo scale, i.e.
on the height above the ground (AGL); the ground under a block is not flat. This module
gives every photo centre of a :class:`~scanplan.geo.layout.FlightLayout` its ground
elevation (from a DEM, :mod:`scanplan.geo.dem`, or only a ``[min, max]`` range), a flight
altitude (by the altitude mode), its AGL, the lowest and highest ground under its footprint
and its stretch of path, and (:mod:`.terrain_overlaps`) its forward and side overlaps with
its neighbours. The constraints are evaluated at every photo's own height by
:mod:`scanplan.rules.terrain`; :mod:`scanplan.project.terraincheck` joins the two.

Altitude modes (``[terrain] altitude_mode``)
---------------------------------------------
``constant`` (default)
    One altitude for the block: the planned height above the **highest** ground under the
    photo centres, A = max(g) + H. Why the highest and not the lowest: (1) the aircraft is
    never closer to the ground than planned — terrain and obstacle clearance hold
    everywhere; (2) the line spacing and photo base were designed at H, so every photo over
    lower ground overlaps *more* than planned: no gaps, no reflight; (3) the price — coarser
    GSD and L over low ground — is exactly what the check at the largest AGL finds and
    states, with its remedy. Holding H over the lowest ground instead would leave holes in
    the stereo coverage over every hill, which no check after the flight can repair.
``strip``
    One altitude per strip, the planned height above the highest ground of that strip.
``follow``
    Terrain following: the altitude steps with the ground so that the AGL at every photo
    centre lies within [H, H + tolerance] (``[terrain] follow_tolerance_m``); the
    waypoints are where the altitude steps.

Where the constraints are checked
---------------------------------
The UAV engine turns every constraint into a largest planned height H_max whose highest
flown height H_max·(1 + tolerance) still meets it (:mod:`scanplan.rules.uav`). Every
limit grows with the height above ground, so under terrain the worst photo for resolution
and interpretation is the one with the **largest** AGL (the lowest ground under an
altitude), for overlap the one with the **smallest**. A set of photos flown at one altitude
A therefore meets every constraint if and only if A ≤ min(g) + H_max: the maximum
altitude of a strip is closed form (no search), and so is the largest planned height
above the reference ground (constant: H_max − (max g − min g); strip: the same per strip,
the smallest over strips; follow: H_max − tolerance).

The photo's AGL is taken at its centre: at 60–80 % forward overlap every ground point
lies near the centre of some photo. The elevation range under each footprint (5 × 5
points) is reported beside it. Where the ground under a centre is unknown (outside the
DEM, nodata, or only a ``[min, max]`` range given), the photo is checked at the lowest
ground for resolution and at the highest for overlap: its ``ground_m`` is NaN and its
``agl_m`` is the largest AGL it may have.

Overlaps: between two consecutive photos of a strip (forward) and a photo and the nearest
photo of the neighbouring strip (side), with the ground at the midpoint of the pair and
the mean altitude of the two: overlap = 1 − distance / footprint(A − g_mid). The photo
carries the smaller of its two. Flown low by the tolerance down, the footprint shrinks by
(1 − tolerance).

Film: the photo scale changes with the ground, Mc = (A − g)/f (seed 001 uses Mc = H/f);
the scan pixel must meet the constraints at the smallest local photo scale (the largest
Mc), see :mod:`scanplan.geo.terrain_film`.
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import NDArray

from ..errors import InputError
from ..i18n.messages import Message, Names, PlanWarning, listing
from ..io.kept import Kept, arrays_key
from . import dem as D
from .dem_grid import DEFAULT_VOID_MARGIN_M, DEFAULT_VOID_RADIUS_M, GroundGrid, read_ground_grid
from .layout import FlightLayout, Photos
from .terrain_worst import PathGround, footprint_ground, path_ground, run_in_m

__all__ = [
    "ALTITUDE_MODES",
    "TERRAIN_PHOTO_COLUMNS",
    "Ground",
    "StripTerrain",
    "TerrainConfig",
    "TerrainResult",
    "WorstGround",
    "altitude_waypoints",
    "altitudes_m",
    "ground_under",
    "max_height_above_reference_m",
    "path_summary",
    "strip_order",
    "strip_rows",
    "terrain_layout",
    "worst_ground",
]

ALTITUDE_MODES = ("constant", "strip", "follow")
MAX_COVERAGE_GAP = 0.005
"""Largest share of the area a DEM may miss (0.5 %) before it is refused."""
DEFAULT_FOLLOW_TOLERANCE_M = 5.0

#: Columns this module adds to :data:`scanplan.geo.layout.PHOTO_COLUMNS`.
TERRAIN_PHOTO_COLUMNS: dict[str, str] = {
    "ground_min_m": "lowest ground under the photo's footprint [m]",
    "ground_max_m": "highest ground under the photo's footprint [m]",
    "forward_overlap_pct": "forward overlap with its strip neighbours, the smaller [%]",
    "side_overlap_pct": "side overlap with the neighbouring strips, the smaller [%]",
}

ALTITUDE_FRAME = "AMSL"
"""Altitudes are in the height system of the DEM (above mean sea level for the usual
DEMs); the mission export writes such a layout in MAV_FRAME_GLOBAL (0)."""


@dataclass(frozen=True)
class TerrainConfig:
    """What ``[terrain]`` says.

    Attributes
    ----------
    dem : Path or None
        The DEM (GeoTIFF in any CRS).
    ground_range_m : tuple of float or None
        ``[min, max]`` ground elevation without a DEM [m].
    altitude_mode : str
        ``constant``, ``strip`` or ``follow``.
    follow_tolerance_m : float
        How far the AGL may exceed the planned height in ``follow`` mode [m].
    vertical_unit : str or None
        The DEM's height unit (``m``, ``ft``, ``us-ft``, ``cm``, ``dm``) when stated.
    void_fill_radius_m, void_fill_margin_m : float
        No-data within the radius of known ground is filled with the highest (lowest)
        known ground within it plus (minus) the margin [m] (:mod:`.dem_grid`).
    """

    dem: Path | None = None
    ground_range_m: tuple[float, float] | None = None
    altitude_mode: str = "constant"
    follow_tolerance_m: float = DEFAULT_FOLLOW_TOLERANCE_M
    vertical_unit: str | None = None
    void_fill_radius_m: float = DEFAULT_VOID_RADIUS_M
    void_fill_margin_m: float = DEFAULT_VOID_MARGIN_M

    def __post_init__(self) -> None:
        # each key's own value first (the error names it), then whether the keys agree
        if self.altitude_mode not in ALTITUDE_MODES:
            raise InputError("terrain.altitude_mode", f"must be one of {', '.join(ALTITUDE_MODES)}"
                             f" (got {self.altitude_mode!r})")
        if self.ground_range_m is not None:
            lo, hi = self.ground_range_m
            if not (math.isfinite(lo) and math.isfinite(hi) and lo <= hi
                    and D.LOWEST_GROUND_M <= lo and hi <= D.HIGHEST_GROUND_M):
                raise InputError("terrain.ground_elevation_m", "must be [min, max] with "
                                 f"{D.LOWEST_GROUND_M:g} ≤ min ≤ max ≤ {D.HIGHEST_GROUND_M:g} m"
                                 f" (got {list(self.ground_range_m)})")
        if not (math.isfinite(self.follow_tolerance_m) and 0 <= self.follow_tolerance_m <= 500):
            raise InputError("terrain.follow_tolerance_m", "must be 0 … 500 m "
                             f"(got {self.follow_tolerance_m!r})")
        for name, hi in (("void_fill_radius_m", 1000.0), ("void_fill_margin_m", 500.0)):
            v = getattr(self, name)
            if not (isinstance(v, int | float) and math.isfinite(v) and 0 <= v <= hi):
                raise InputError(f"terrain.{name}", f"must be 0 … {hi:g} m (got {v!r})")
        if self.vertical_unit is not None and self.vertical_unit not in D.UNIT_FACTORS:
            raise InputError("terrain.vertical_unit", "must be one of "
                             f"{', '.join(D.UNIT_FACTORS)} (got {self.vertical_unit!r})")
        if self.dem is not None and self.ground_range_m is not None:
            raise InputError("terrain.ground_elevation_m", "give either dem or "
                             "ground_elevation_m, not both")
        if self.dem is None and self.ground_range_m is None:
            raise InputError("terrain", "needs dem (a GeoTIFF) or ground_elevation_m = "
                             "[min, max]")
        if self.dem is not None and str(self.dem).strip() in ("", "."):
            raise InputError("terrain.dem", "is empty: give the DEM's file name")


@dataclass(frozen=True)
class Ground:
    """The ground under the photo centres.

    ``centre_m`` is NaN where unknown; ``low_m``/``high_m`` bound the block's ground (the
    DEM's values under the photos, or the given range).
    """

    centre_m: NDArray[np.float64]
    low_m: float
    high_m: float
    source: str  # "dem" | "range"
    dem: D.DemInfo | None = None
    factor_m: float = 1.0
    warnings: tuple[PlanWarning, ...] = ()
    details: dict[str, Any] = field(default_factory=dict)
    grid: GroundGrid | None = None

    def sample(self, x_m: NDArray[np.float64], y_m: NDArray[np.float64],
               plan_crs: str) -> NDArray[np.float64]:
        """Ground at more points [m] (NaN where unknown; all NaN without a DEM)."""
        if self.dem is None:
            return np.full(np.shape(x_m), np.nan)
        return D.sample_dem(self.dem, x_m, y_m, plan_crs, self.factor_m).elevation_m


@dataclass(frozen=True)
class StripTerrain:
    """One strip under the terrain (altitudes in the DEM's height system) [m]."""

    number: int
    ground_min_m: float
    ground_max_m: float
    altitude_min_m: float
    altitude_max_m: float
    agl_min_m: float
    agl_max_m: float
    max_altitude_m: float | None  # highest altitude meeting every constraint, lowest ground
    excess_m: float  # how far its worst photo is above the limit (0 if it meets it)
    worst_photo: int


@dataclass(frozen=True)
class TerrainResult:
    """The layout with its terrain columns filled, and the checks.

    Attributes
    ----------
    layout : FlightLayout
        Photos with ground_m, altitude_m, agl_m, gsd_cm, resolution_cm, recognition_p and
        :data:`TERRAIN_PHOTO_COLUMNS`; strips with their altitude (strip/constant modes).
    mode : str
    height_m : float
        The planned AGL above the reference ground [m].
    strips : tuple of StripTerrain
    max_height_m : float or None
        The largest planned height above the reference ground at which the worst photo
        still meets its binding constraint [m] (None without limits).
    binding : str or None
        The constraint that binds at the worst photo.
    worst_resolution_photo, worst_overlap_photo : int
        Running numbers of the photo with the largest AGL and the smallest overlap.
    waypoints : list of dict
        Where the altitude steps (strip, photo, x_m, y_m, altitude_m), in flight order.
    warnings : tuple of PlanWarning
    """

    layout: FlightLayout
    mode: str
    height_m: float
    strips: tuple[StripTerrain, ...]
    max_height_m: float | None
    binding: str | None
    worst_resolution_photo: int
    worst_overlap_photo: int
    min_forward_overlap_pct: float
    min_side_overlap_pct: float
    waypoints: list[dict[str, Any]]
    warnings: tuple[PlanWarning, ...]
    ground: Ground
    altitude_frame: str = ALTITUDE_FRAME
    path: dict[str, float | None] = field(default_factory=dict)

    def summary(self) -> dict[str, Any]:
        """The JSON ``terrain`` section: plain numbers."""
        ph = self.layout.photos
        agl = ph["agl_m"]
        g_top = np.where(np.isfinite(ph["ground_m"]), ph["ground_m"], ph["ground_max_m"])
        return {
            "source": self.ground.source, "altitude_mode": self.mode,
            "altitude_frame": self.altitude_frame, "height_m": self.height_m,
            "ground_min_m": self.ground.low_m, "ground_max_m": self.ground.high_m,
            "agl_min_m": float(np.nanmin(ph["altitude_m"] - g_top)) if len(ph) else None,
            "agl_max_m": float(np.nanmax(agl)) if len(ph) else None,
            "max_height_m": self.max_height_m, "binding": self.binding,
            "worst_resolution_photo": self.worst_resolution_photo,
            "worst_overlap_photo": self.worst_overlap_photo,
            "min_forward_overlap_pct": self.min_forward_overlap_pct,
            "min_side_overlap_pct": self.min_side_overlap_pct,
            "strips": [s.__dict__.copy() for s in self.strips],
            **self.path,
            **self.ground.details,
        }


# --- the ground under the photos ----------------------------------------------------------

def ground_under(layout: FlightLayout, cfg: TerrainConfig, key: str = "terrain.dem",
                 base_folder: Path | None = None) -> Ground:
    """The ground elevation under every photo centre.

    Raises
    ------
    InputError
        Naming ``key``: an unreadable DEM, a DEM that misses more than
        :data:`MAX_COVERAGE_GAP` of the area (saying how much), no photo with ground under
        it, elevations that look like centimetres.
    """
    ph = layout.photos
    n = len(ph)
    if cfg.dem is None:
        lo, hi = cfg.ground_range_m  # type: ignore[misc]
        return Ground(np.full(n, np.nan), float(lo), float(hi), "range",
                      details={"ground_range_m": [float(lo), float(hi)]})
    path = cfg.dem if base_folder is None or cfg.dem.is_absolute() else base_folder / cfg.dem
    info = D.open_dem(path, key)
    if n == 0:  # a plan that cannot be flown has no photos: nothing to sample
        return Ground(np.zeros(0), math.nan, math.nan, "dem", info)
    factor, unit_source = D.vertical_factor(info, cfg.vertical_unit)
    plan_crs = layout.area.plan_crs
    missing_km2, share = 0.0, 0.0
    if plan_crs.upper() != "LOCAL":
        missing_km2, share = D.coverage_gap(info, layout.area.geometry, plan_crs, key)
        if share > MAX_COVERAGE_GAP:
            raise InputError(key, f"{info.path.name} does not cover the area: "
                             f"{missing_km2:.3g} km² ({share * 100:.1f} %) of it lies outside "
                             "the DEM; give a DEM that covers the whole area")
    s = D.sample_dem(info, ph["x_m"], ph["y_m"], plan_crs, factor, key)
    known = np.isfinite(s.elevation_m)
    if not known.any():
        raise InputError(key, f"{info.path.name}: none of the {n} photo centres has ground "
                         "under it (outside the DEM or nodata)")
    problem = D.unit_problem(s.elevation_m, info, unit_source)
    if problem == "cm":
        raise InputError(key, f"{info.path.name}: elevations from "
                         f"{np.nanmin(s.elevation_m):.0f} to {np.nanmax(s.elevation_m):.0f} "
                         "read as metres lie beyond any ground on Earth: they look like "
                         "centimetres or decimetres; state the unit ([terrain] vertical_unit "
                         '= "cm" or "dm")')
    grid = _grid(layout, info, cfg, factor, key, missing_km2, share)
    warnings: list[PlanWarning] = []
    if problem == "ft":
        warnings.append(PlanWarning("terrain_units_feet", Message(
            "terrain_units_feet", file=info.path.name, unit=(
                Names("US survey feet", "американских геодезических футах")
                if "us" in info.horizontal_unit.lower()
                else Names("feet", "футах")))))
    lo = float(np.nanmin(s.elevation_m))
    hi = float(np.nanmax(s.elevation_m))
    filled = _on_filled_voids(layout, grid, known)
    if grid is not None and grid.voids.filled_px:
        v = grid.voids
        warnings.append(PlanWarning("terrain_voids_filled", Message(
            "terrain_voids_filled", file=info.path.name, pixels=v.filled_px,
            area_m2=v.filled_m2, share=v.filled_px / max(v.area_px, 1) * 100.0,
            radius=v.radius_m, margin=v.margin_m, photos=int(filled.sum()))))
    if not (known | filled).all():
        bad = ph["photo"][~(known | filled)].astype(np.int64)
        warnings.append(PlanWarning("terrain_no_ground", Message(
            "terrain_no_ground", count=int(bad.size), total=n, photos=listing(bad),
            outside=int(s.outside.sum()), nodata=int((s.nodata & ~filled).sum()), low=lo,
            high=hi)))
    if info.geographic:
        warnings.append(PlanWarning("terrain_geographic", Message(
            "terrain_geographic", file=info.path.name, cell=info.cell_size[0] * 3600.0),
            severity="info"))
    details = {"dem": info.path.name, "dem_crs": _crs_name(info.crs_wkt),
               "dem_geographic": info.geographic, "dem_cell_size": list(info.cell_size),
               "vertical_unit_m": factor,
               "photos_without_ground": int((~(known | filled)).sum())}
    if grid is not None:
        v = grid.voids
        details.update(void_fill_radius_m=v.radius_m, void_fill_margin_m=v.margin_m,
                       voids_filled_px=v.filled_px, voids_filled_m2=v.filled_m2,
                       voids_unknown_m2=v.unknown_m2, photos_on_filled_voids=int(filled.sum()),
                       missing_extent_km2=missing_km2)
    return Ground(s.elevation_m, lo, hi, "dem", info, factor, tuple(warnings), details, grid)


def _on_filled_voids(layout: FlightLayout, grid: GroundGrid | None,
                     known: NDArray[np.bool_]) -> NDArray[np.bool_]:
    """The photos whose centre has no DEM value but stands on a filled void."""
    filled = np.zeros(known.size, dtype=bool)
    if grid is None or known.all():
        return filled
    ph = layout.photos
    idx = np.flatnonzero(~known)
    zero = np.zeros((idx.size, 2))
    lo, hi = grid.box_range(ph["x_m"][idx], ph["y_m"][idx], zero, zero)
    filled[idx] = np.isfinite(lo) & np.isfinite(hi)
    return filled


def _grid(layout: FlightLayout, info: D.DemInfo, cfg: TerrainConfig, factor: float, key: str,
          missing_km2: float, missing_share: float) -> GroundGrid | None:
    """The DEM under the layout as a min-max pyramid (:mod:`.dem_grid`), over the photo
    centres' extent widened by three footprint diagonals, the run-in and the fill radius.

    Raises
    ------
    InputError
        When the area's no-data beyond the fill radius and the part outside the DEM
        together exceed :data:`MAX_COVERAGE_GAP` of the area (both named).
    """
    ph = layout.photos
    x, y = np.asarray(ph["x_m"], float), np.asarray(ph["y_m"], float)
    diag = math.hypot(layout.footprint_across_m, layout.footprint_along_m)
    if not math.isfinite(diag):
        diag = 10.0 * max(layout.spacing_m, layout.base_m)
    pad = 3.0 * diag + run_in_m(layout) + cfg.void_fill_radius_m
    bounds = (float(x.min()) - pad, float(y.min()) - pad, float(x.max()) + pad,
              float(y.max()) + pad)
    grid = read_ground_grid(info, bounds, layout.area.geometry, layout.area.plan_crs, factor,
                            cfg.void_fill_radius_m, cfg.void_fill_margin_m, key)
    if grid is None:
        return None
    area_km2 = float(layout.area.geometry.area) / 1e6
    void_km2 = grid.voids.unknown_m2 / 1e6
    share = missing_share + (void_km2 / area_km2 if area_km2 > 0 else 0.0)
    if share > MAX_COVERAGE_GAP:
        raise InputError(key, f"{info.path.name} has no ground under {missing_km2 + void_km2:.3g}"
                         f" km² ({share * 100:.1f} %) of the area: {void_km2:.3g} km² of "
                         f"no-data farther than {cfg.void_fill_radius_m:g} m from known ground "
                         f"and {missing_km2:.3g} km² outside the DEM; at most "
                         f"{MAX_COVERAGE_GAP * 100:g} % may be missing: give a DEM without "
                         "these voids (or a larger [terrain] void_fill_radius_m)")
    return grid


@functools.lru_cache(maxsize=32)
def _crs_name(wkt: str) -> str:
    """``EPSG:n`` of a DEM's CRS, else its name (looked up once per CRS)."""
    from pyproj import CRS

    crs = CRS.from_wkt(wkt)
    epsg = crs.to_epsg()
    return f"EPSG:{epsg}" if epsg else crs.name


# --- altitudes -----------------------------------------------------------------------------

def strip_order(ph: Photos) -> NDArray[np.int64]:
    """Photos sorted by strip, then by number within the strip."""
    return np.lexsort((ph["index"], ph["strip"]))


def _follow_runs(g: NDArray[np.float64], strip: NDArray[np.int64], tol: float
                 ) -> NDArray[np.int64]:
    """Run id of every photo (in strip order): a run is consecutive photos of one strip
    whose ground spans at most ``tol`` (greedy, in flight order). Read-only: the last
    few are kept (a check asks the runs of its altitudes and of its height limit)."""
    g = np.asarray(g, dtype=float)
    strip = np.asarray(strip, dtype=np.int64)
    key = (arrays_key(g, strip), float(tol))
    return _RUNS.made(key, lambda: _read_only(_greedy_runs(g, strip, tol)))


_RUNS: Kept[tuple[bytes, float], NDArray[np.int64]] = Kept(4)


def _read_only(a: NDArray[Any]) -> NDArray[Any]:
    a.setflags(write=False)
    return a


def _greedy_runs(g: NDArray[np.float64], strip: NDArray[np.int64], tol: float
                 ) -> NDArray[np.int64]:
    """:func:`_follow_runs`, computed."""
    run = [0] * g.size
    rid, lo, hi, prev = -1, math.inf, -math.inf, None
    limit = tol + 1e-9
    for i, (v, k) in enumerate(zip(g.tolist(), strip.tolist(), strict=True)):  # floats
        if k == prev:  # max(hi, v) and min(lo, v), spelt out (the loop's hot path)
            top = v if v > hi else hi
            low = v if v < lo else lo
            if not top - low > limit:  # (NaN continues the run, as before)
                lo, hi = low, top
                run[i] = rid
                continue
        rid += 1
        lo = hi = v
        run[i] = rid
        prev = k
    return np.array(run, dtype=np.int64)


def _group_max(values: NDArray[np.float64], groups: NDArray[np.int64]) -> NDArray[np.float64]:
    """Per element, the max of ``values`` over its group (groups are 0 … k−1)."""
    out = np.full(int(groups.max()) + 1 if groups.size else 0, -np.inf)
    np.maximum.at(out, groups, values)
    return out[groups]


def _group_min(values: NDArray[np.float64], groups: NDArray[np.int64]) -> NDArray[np.float64]:
    out = np.full(int(groups.max()) + 1 if groups.size else 0, np.inf)
    np.minimum.at(out, groups, values)
    return out[groups]


def altitudes_m(ground_high_m: NDArray[np.float64], strip: NDArray[np.int64], mode: str,
                height_m: float, follow_tolerance_m: float = DEFAULT_FOLLOW_TOLERANCE_M
                ) -> NDArray[np.float64]:
    """Flight altitude of every photo (photos in strip order) [m].

    ``ground_high_m`` is the ground under each centre, the highest possible where unknown.
    constant: max(g) + H; strip: max over the strip + H; follow: max over the run + H.
    """
    g = np.asarray(ground_high_m, dtype=float)
    if g.size == 0:
        return g.copy()
    if mode == "constant":
        return np.full(g.size, float(g.max()) + height_m)
    if mode == "strip":
        _, groups = np.unique(strip, return_inverse=True)
        return _group_max(g, groups.astype(np.int64)) + height_m
    runs = _follow_runs(g, strip, follow_tolerance_m)
    return _group_max(g, runs) + height_m


# --- the UAV block -------------------------------------------------------------------------

def max_height_above_reference_m(limit_height_m: float, ground_low_m: NDArray[np.float64],
                                 ground_high_m: NDArray[np.float64], strip: NDArray[np.int64],
                                 mode: str, follow_tolerance_m: float) -> float:
    """The largest planned height above the reference ground that keeps the worst photo
    within ``limit_height_m`` (closed form, see the module notes) [m].

    ``ground_low_m``/``ground_high_m`` are each photo's ground for resolution (lowest
    possible) and for the altitude (highest possible).
    """
    if ground_low_m.size == 0:
        return limit_height_m
    if mode == "constant":
        return limit_height_m - (float(ground_high_m.max()) - float(ground_low_m.min()))
    if mode == "strip":
        _, groups = np.unique(strip, return_inverse=True)
        groups = groups.astype(np.int64)
        relief = _group_max(ground_high_m, groups) - _group_min(ground_low_m, groups)
        return limit_height_m - float(relief.max())
    runs = _follow_runs(ground_high_m, strip, follow_tolerance_m)
    relief = _group_max(ground_high_m, runs) - ground_low_m
    return limit_height_m - float(relief.max())


@dataclass(frozen=True)
class WorstGround:
    """Each photo's ground (strip order) [m]: at its centre (NaN where unknown), under its
    stretch of the path, over its footprint at the altitude flown; and that altitude."""

    centre_m: NDArray[np.float64]
    path_low_m: NDArray[np.float64]
    path_high_m: NDArray[np.float64]
    footprint_low_m: NDArray[np.float64]
    footprint_high_m: NDArray[np.float64]
    altitude_m: NDArray[np.float64]


def worst_ground(layout: FlightLayout, ground: Ground, cols: dict[str, NDArray[Any]],
                 centre_m: NDArray[np.float64], mode: str, height_m: float,
                 follow_tolerance_m: float, across_per_m: float, along_per_m: float
                 ) -> WorstGround:
    """The altitudes of the mode over the highest ground under the path, and the lowest and
    highest ground over every footprint at that altitude (:mod:`.terrain_worst`).

    ``cols`` are the photos in strip order, ``centre_m`` the ground at their centres (NaN
    where unknown); ``across_per_m``/``along_per_m`` the footprint sides per metre of
    height above ground.
    """
    g = np.asarray(centre_m, dtype=float)
    x, y = cols["x_m"].astype(float), cols["y_m"].astype(float)
    strip = cols["strip"].astype(np.int64)
    directions = layout.directions_deg(strip)  # each strip's own (a crosshatch's passes)
    path = _kept_path_ground(ground.grid, x, y, strip, directions, run_in_m(layout),
                             ground.low_m, ground.high_m)
    # a centre with ground known on a path without (outside the DEM's grid) keeps its own
    p_hi = np.where(path.known | ~np.isfinite(g), path.high_m, np.fmax(g, path.high_m))
    p_lo = np.where(path.known | ~np.isfinite(g), path.low_m, np.fmin(g, path.low_m))
    if ground.grid is None:  # no DEM grid: the centres as sampled, the range where unknown
        p_hi = np.where(np.isfinite(g), g, ground.high_m)
        p_lo = np.where(np.isfinite(g), g, ground.low_m)
    alt = altitudes_m(p_hi, strip, mode, height_m, follow_tolerance_m)
    f_lo, f_hi = footprint_ground(ground.grid, x, y, alt, np.where(np.isfinite(g), g, p_lo),
                                  directions, across_per_m, along_per_m,
                                  ground.low_m, ground.high_m)
    return WorstGround(g, p_lo, p_hi, f_lo, f_hi, alt)


def _kept_path_ground(grid: GroundGrid | None, x: NDArray[np.float64],
                      y: NDArray[np.float64], strip: NDArray[np.int64],
                      directions: float | NDArray[np.float64], extend_m: float,
                      low_m: float, high_m: float) -> PathGround:
    """:func:`~scanplan.geo.terrain_worst.path_ground`, kept with the grid
    (:attr:`~scanplan.geo.dem_grid.GroundGrid.kept`) by the photos and the run-in, its
    arrays read-only; without a grid (no DEM) computed, as it costs nothing."""
    if grid is None:
        return path_ground(grid, x, y, strip, directions, extend_m, low_m, high_m)
    key = ("path", arrays_key(x, y, strip, np.asarray(directions, dtype=float)),
           float(extend_m), float(low_m), float(high_m))

    def made() -> PathGround:
        path = path_ground(grid, x, y, strip, directions, extend_m, low_m, high_m)
        for arr in (path.low_m, path.high_m, path.known):
            _read_only(arr)
        return path

    return grid.kept.made(key, made)  # type: ignore[return-value]


def path_summary(alt: NDArray[np.float64], wg: WorstGround) -> dict[str, float | None]:
    """The clearance and the greatest height above ground under the flight path [m]."""
    if alt.size == 0:
        return {"clearance_min_m": None, "path_agl_max_m": None, "footprint_agl_max_m": None}
    return {"clearance_min_m": float(np.min(alt - wg.path_high_m)),
            "path_agl_max_m": float(np.max(alt - wg.path_low_m)),
            "footprint_agl_max_m": float(np.max(alt - wg.footprint_low_m))}


def terrain_layout(layout: FlightLayout, cols: dict[str, NDArray[Any]],
                   order: NDArray[np.int64], strips: tuple[StripTerrain, ...], mode: str
                   ) -> FlightLayout:
    """The layout with the terrain columns (back in its own photo order), each strip's
    altitude (constant and strip modes) and the altitude mode and frame in its notes."""
    n = order.size
    inverse = np.empty(n, dtype=np.int64)
    inverse[order] = np.arange(n)
    photos = Photos({k: np.asarray(v)[inverse] for k, v in cols.items()})
    altitude: dict[int, float | None] = {}
    if mode != "follow":
        for r in strips:
            altitude.setdefault(r.number, r.altitude_max_m)  # the first of its number
    new_strips = tuple(
        s if s.altitude_m is None and altitude.get(s.number) is None
        else replace(s, altitude_m=altitude.get(s.number))
        for s in layout.strips)
    notes = dict(layout.notes)
    notes.update(altitude_mode=mode, altitude_frame=ALTITUDE_FRAME)
    return replace(layout, photos=photos, strips=new_strips, notes=notes)


def strip_rows(cols: dict[str, NDArray[Any]], g_res: NDArray[np.float64],
               g_alt: NDArray[np.float64], limit_m: float | None
               ) -> tuple[StripTerrain, ...]:
    """Per strip: its ground, altitudes, the height above ground from the clearance (over
    the highest ground under its path) to the checked worst (over ``g_res``), and how far
    that exceeds the limit.

    Parameters
    ----------
    cols : dict of ndarray
        The photos in strip order with ``strip``, ``photo``, ``altitude_m``,
        ``ground_min_m`` and ``ground_max_m`` [m].
    g_res, g_alt : ndarray
        Every photo's ground for the limit (checked at) and for the altitude (highest under
        its path) [m].
    limit_m : float or None
        The largest height above ``g_res`` any photo may have [m] (None: no limit).

    Returns
    -------
    tuple of StripTerrain
    """
    strip = np.asarray(cols["strip"])
    if strip.size == 0:
        return ()
    order = np.argsort(strip, kind="stable")  # one pass over the photos, strip by strip
    numbers, first = np.unique(strip[order], return_index=True)
    group = np.repeat(np.arange(first.size), np.diff(np.append(first, strip.size)))

    def per(values: NDArray[Any], how: Any) -> NDArray[np.float64]:
        return how.reduceat(np.asarray(values, dtype=float)[order], first)

    alt = np.asarray(cols["altitude_m"], dtype=float)[order]
    agl = alt - np.asarray(g_res, dtype=float)[order]
    agl_max = np.maximum.reduceat(agl, first)
    # the first photo of each strip with its largest AGL (NaN first where the max is NaN)
    hit = (agl == agl_max[group]) | (np.isnan(agl) & np.isnan(agl_max[group]))
    at = np.flatnonzero(hit)
    worst = at[np.unique(group[at], return_index=True)[1]]
    g_min = per(g_res, np.minimum)
    lo, hi = per(cols["ground_min_m"], np.fmin), per(cols["ground_max_m"], np.fmax)
    a_lo, a_hi = np.minimum.reduceat(alt, first), np.maximum.reduceat(alt, first)
    clear = np.minimum.reduceat(alt - np.asarray(g_alt, dtype=float)[order], first)
    photo = np.asarray(cols["photo"])[order]
    rows = []
    for i, k in enumerate(numbers):
        excess = agl_max[i] - limit_m if limit_m is not None else 0.0
        rows.append(StripTerrain(
            number=int(k), ground_min_m=float(lo[i]), ground_max_m=float(hi[i]),
            altitude_min_m=float(a_lo[i]), altitude_max_m=float(a_hi[i]),
            agl_min_m=float(clear[i]), agl_max_m=float(agl_max[i]),
            max_altitude_m=float(g_min[i]) + limit_m if limit_m is not None else None,
            excess_m=float(excess) if excess > 0 else 0.0, worst_photo=int(photo[worst[i]])))
    return tuple(rows)


def altitude_waypoints(cols: dict[str, NDArray[Any]], mode: str) -> list[dict[str, Any]]:
    """Where the altitude steps: the first photo of every strip and of every altitude run."""
    alt = cols["altitude_m"]
    strip = cols["strip"]
    if alt.size == 0:
        return []
    step = np.ones(alt.size, dtype=bool)
    step[1:] = (strip[1:] != strip[:-1]) | (np.abs(np.diff(alt)) > 1e-6)
    idx = np.flatnonzero(step)
    return [{"strip": int(strip[i]), "photo": int(cols["photo"][i]),
             "x_m": float(cols["x_m"][i]), "y_m": float(cols["y_m"][i]),
             "altitude_m": float(alt[i])} for i in idx]

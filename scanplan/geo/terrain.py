"""Terrain: every photo at its own height above the ground, the worst photo binding.

The Instruction's constraints and the recognition model depend on the photo scale, i.e.
on the height above the ground (AGL); the ground under a block is not flat. This module
gives every photo centre of a :class:`~scanplan.geo.layout.FlightLayout` its ground
elevation (from a DEM, :mod:`scanplan.geo.dem`, or only a ``[min, max]`` range), a flight
altitude (by the altitude mode), its AGL, GSD, MTF ground resolution L, recognition
probability and its forward and side overlaps with its neighbours; then checks the
constraints where they are worst.

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

import itertools
import math
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import NDArray

from ..core import formulas as F
from ..errors import InputError
from ..messages import Message
from ..rules.results import PlanWarning, UavInputs, UavPlan
from . import dem as D
from .layout import FlightLayout, Photos

__all__ = [
    "ALTITUDE_MODES",
    "TERRAIN_PHOTO_COLUMNS",
    "Ground",
    "StripTerrain",
    "TerrainConfig",
    "TerrainResult",
    "ground_under",
    "uav_terrain",
]

ALTITUDE_MODES = ("constant", "strip", "follow")
FOOTPRINT_GRID = 5
"""Points per footprint side sampled for the elevation range under a photo."""
MAX_COVERAGE_GAP = 0.005
"""Largest share of the area a DEM may miss (0.5 %) before it is refused."""
DEFAULT_FOLLOW_TOLERANCE_M = 5.0
MAX_LISTED = 6
"""Photos or strips named in one warning; the rest are counted."""

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
    """

    dem: Path | None = None
    ground_range_m: tuple[float, float] | None = None
    altitude_mode: str = "constant"
    follow_tolerance_m: float = DEFAULT_FOLLOW_TOLERANCE_M
    vertical_unit: str | None = None

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
            **self.ground.details,
        }


# --- the ground under the photos ----------------------------------------------------------

def _listing(numbers: NDArray[np.int64]) -> str:
    """``3, 4, 7`` or ``3, 4, 7, 9, 12, 15 and 40 more``."""
    shown = ", ".join(str(int(v)) for v in numbers[:MAX_LISTED])
    more = numbers.size - MAX_LISTED
    return shown + (f" (+{more})" if more > 0 else "")


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
    warnings: list[PlanWarning] = []
    if problem == "ft":
        warnings.append(PlanWarning("terrain_units_feet", Message(
            "terrain_units_feet", file=info.path.name, unit=(
                {"en": "US survey feet", "ru": "американских геодезических футах"}
                if "us" in info.horizontal_unit.lower()
                else {"en": "feet", "ru": "футах"}))))
    lo = float(np.nanmin(s.elevation_m))
    hi = float(np.nanmax(s.elevation_m))
    if not known.all():
        bad = ph["photo"][~known].astype(np.int64)
        warnings.append(PlanWarning("terrain_no_ground", Message(
            "terrain_no_ground", count=int(bad.size), total=n, photos=_listing(bad),
            outside=int(s.outside.sum()), nodata=int(s.nodata.sum()), low=lo, high=hi)))
    if info.geographic:
        warnings.append(PlanWarning("terrain_geographic", Message(
            "terrain_geographic", file=info.path.name, cell=info.cell_size[0] * 3600.0),
            severity="info"))
    details = {"dem": info.path.name, "dem_crs": _crs_name(info.crs_wkt),
               "dem_geographic": info.geographic, "dem_cell_size": list(info.cell_size),
               "vertical_unit_m": factor, "photos_without_ground": int((~known).sum())}
    return Ground(s.elevation_m, lo, hi, "dem", info, factor, tuple(warnings), details)


def _crs_name(wkt: str) -> str:
    from pyproj import CRS

    crs = CRS.from_wkt(wkt)
    epsg = crs.to_epsg()
    return f"EPSG:{epsg}" if epsg else crs.name


# --- altitudes -----------------------------------------------------------------------------

def _order(ph: Photos) -> NDArray[np.int64]:
    """Photos sorted by strip, then by number within the strip."""
    return np.lexsort((ph["index"], ph["strip"]))


def _follow_runs(g: NDArray[np.float64], strip: NDArray[np.int64], tol: float
                 ) -> NDArray[np.int64]:
    """Run id of every photo (in strip order): a run is consecutive photos of one strip
    whose ground spans at most ``tol`` (greedy, in flight order)."""
    run = np.empty(g.size, dtype=np.int64)
    rid, lo, hi, prev = -1, math.inf, -math.inf, None
    for i in range(g.size):
        v = g[i]
        if prev is None or strip[i] != prev or max(hi, v) - min(lo, v) > tol + 1e-9:
            rid += 1
            lo = hi = v
        else:
            lo, hi = min(lo, v), max(hi, v)
        run[i] = rid
        prev = strip[i]
    return run


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


# --- the footprint range ------------------------------------------------------------------

def _footprint_range(x: NDArray[np.float64], y: NDArray[np.float64], agl: NDArray[np.float64],
                     ground: Ground, plan_crs: str, direction_deg: float, across_mm: float,
                     along_mm: float, focal_mm: float
                     ) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Lowest and highest ground under each footprint (5 × 5 points) [m]."""
    n = x.size
    if ground.dem is None or n == 0:
        return np.full(n, ground.low_m), np.full(n, ground.high_m)
    along, across = _axes(direction_deg)
    t = np.linspace(-0.5, 0.5, FOOTPRINT_GRID)
    sa, sc = np.meshgrid(t, t)
    sa, sc = sa.ravel(), sc.ravel()
    fa = (along_mm / focal_mm * np.maximum(agl, 0.0))[:, None] * sa[None, :]
    fc = (across_mm / focal_mm * np.maximum(agl, 0.0))[:, None] * sc[None, :]
    px = x[:, None] + fa * along[0] + fc * across[0]
    py = y[:, None] + fa * along[1] + fc * across[1]
    g = ground.sample(px.ravel(), py.ravel(), plan_crs).reshape(n, -1)
    with np.errstate(all="ignore"):
        import warnings as _w
        with _w.catch_warnings():
            _w.simplefilter("ignore", RuntimeWarning)
            lo, hi = np.nanmin(g, axis=1), np.nanmax(g, axis=1)
    return (np.where(np.isfinite(lo), lo, ground.low_m),
            np.where(np.isfinite(hi), hi, ground.high_m))


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


def uav_terrain(layout: FlightLayout, ground: Ground, inp: UavInputs, plan: UavPlan,
                mode: str = "constant",
                follow_tolerance_m: float = DEFAULT_FOLLOW_TOLERANCE_M) -> TerrainResult:
    """Every photo at its own AGL; the constraints at the worst photo.

    Steps: the photos in strip order with their ground (:func:`_ground_for_checks`); the
    altitudes of the mode and the AGL; the per-photo figures at that AGL
    (:func:`_photo_figures`); the overlaps with the neighbours (:func:`_overlaps`); the
    layout with the terrain columns (:func:`_terrain_layout`); the closed-form maximum
    height and the warnings.

    Parameters
    ----------
    layout : FlightLayout
        Flight lines and photo centres (from the planned height ``inp.height_m``).
    ground : Ground
        From :func:`ground_under`.
    inp : UavInputs
        The camera and flight; ``height_m`` is the planned AGL over the reference ground.
    plan : UavPlan
        The flat-ground plan: its limits as planned heights (``max_height_m``, ``binding``).
    mode : str
        ``constant``, ``strip`` or ``follow``.

    Returns
    -------
    TerrainResult
    """
    ph = layout.photos
    n = len(ph)
    order = _order(ph)
    cols = {k: np.asarray(v)[order] for k, v in ph.columns.items()}
    strip = cols["strip"].astype(np.int64)
    g, g_res, g_alt = _ground_for_checks(ground, order, n)
    h = float(inp.height_m)
    alt = altitudes_m(g_alt, strip, mode, h, follow_tolerance_m)
    agl = alt - g_res
    up = inp.height_tolerance_up_pct / 100.0
    cols.update(ground_m=g, altitude_m=alt, agl_m=agl, **_photo_figures(inp, agl))
    g_lo, g_hi = _footprint_range(cols["x_m"].astype(float), cols["y_m"].astype(float), agl,
                                  ground, layout.area.plan_crs, layout.direction_deg,
                                  inp.sensor_width_mm, inp.sensor_height_mm, inp.focal_mm)
    ov = _overlaps(layout, cols, alt, ground, inp)
    cols.update(ground_min_m=g_lo, ground_max_m=g_hi, forward_overlap_pct=ov.forward_photo,
                side_overlap_pct=ov.side_photo)
    limit = plan.max_height_m
    strips = _strip_rows(cols, g_res, limit)
    new_layout = _terrain_layout(layout, cols, order, strips, mode)
    worst_res = int(cols["photo"][int(np.argmax(agl))]) if n else 0
    both = np.fmin(ov.forward_photo, ov.side_photo)
    worst_ov = int(cols["photo"][int(np.nanargmin(both))]) if np.isfinite(both).any() else 0
    max_h = None
    if limit is not None:
        max_h = max_height_above_reference_m(limit, g_res, g_alt, strip, mode,
                                             follow_tolerance_m)
    warnings = list(ground.warnings)
    warnings += _resolution_warnings(strips, plan, mode, h, max_h, up, agl, cols)
    warnings += _overlap_warnings(inp, ov.forward, ov.forward_pct, ov.side, ov.side_pct, cols)
    return TerrainResult(
        layout=new_layout, mode=mode, height_m=h, strips=strips, max_height_m=max_h,
        binding=plan.binding, worst_resolution_photo=worst_res, worst_overlap_photo=worst_ov,
        min_forward_overlap_pct=(float(np.nanmin(ov.forward_pct)) if ov.forward_pct.size
                                 else math.nan),
        min_side_overlap_pct=float(np.nanmin(ov.side_pct)) if ov.side_pct.size else math.nan,
        waypoints=_waypoints(cols, mode), warnings=tuple(warnings), ground=ground)


def _ground_for_checks(ground: Ground, order: NDArray[np.int64], n: int
                       ) -> tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.float64]]:
    """The ground under each photo (strip order; NaN where unknown), and the ground it is
    checked at: the lowest possible for resolution, the highest for the altitude."""
    g = ground.centre_m[order] if ground.centre_m.size == n else np.full(n, np.nan)
    g_res = np.where(np.isfinite(g), g, ground.low_m)
    g_alt = np.where(np.isfinite(g), g, ground.high_m)
    return g, g_res, g_alt


def _photo_figures(inp: UavInputs, agl: NDArray[np.float64]) -> dict[str, NDArray[np.float64]]:
    """GSD = p·H/f, the MTF ground resolution L and the recognition probability
    P = exp(−(B·L/L_obj)²) of every photo at its AGL (``gsd_cm``, ``resolution_cm``,
    ``recognition_p``)."""
    from ..rules.uav import ground_resolution_m

    n = agl.size
    gsd = inp.pixel_um / 1000.0 * agl / inp.focal_mm
    lr = ground_resolution_m(inp, np.maximum(agl, 1e-3)) if n else np.zeros(0)
    obj = inp.map_object
    with np.errstate(all="ignore"):
        p_rec = (F.recognition_probability(obj.size_m, lr, obj.shape_coefficient)
                 if obj is not None else np.full(n, np.nan))
    return {"gsd_cm": gsd * 100.0, "resolution_cm": lr * 100.0,
            "recognition_p": np.asarray(p_rec, dtype=float)}


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


def _terrain_layout(layout: FlightLayout, cols: dict[str, NDArray[Any]],
                    order: NDArray[np.int64], strips: tuple[StripTerrain, ...], mode: str
                    ) -> FlightLayout:
    """The layout with the terrain columns (back in its own photo order), each strip's
    altitude (constant and strip modes) and the altitude mode and frame in its notes."""
    n = order.size
    inverse = np.empty(n, dtype=np.int64)
    inverse[order] = np.arange(n)
    photos = Photos({k: np.asarray(v)[inverse] for k, v in cols.items()})
    new_strips = tuple(
        replace(s, altitude_m=(next((r.altitude_max_m for r in strips if r.number == s.number),
                                    None) if mode != "follow" else None))
        for s in layout.strips)
    notes = dict(layout.notes)
    notes.update(altitude_mode=mode, altitude_frame=ALTITUDE_FRAME)
    return replace(layout, photos=photos, strips=new_strips, notes=notes)


def _strip_rows(cols: dict[str, NDArray[Any]], g_res: NDArray[np.float64],
                limit_m: float | None) -> tuple[StripTerrain, ...]:
    rows = []
    strip = cols["strip"]
    for k in np.unique(strip):
        sel = strip == k
        agl = cols["agl_m"][sel]
        alt = cols["altitude_m"][sel]
        gmin = float(g_res[sel].min())
        max_alt = gmin + limit_m if limit_m is not None else None
        excess = max(0.0, float(agl.max()) - limit_m) if limit_m is not None else 0.0
        rows.append(StripTerrain(
            number=int(k), ground_min_m=float(np.nanmin(cols["ground_min_m"][sel])),
            ground_max_m=float(np.nanmax(cols["ground_max_m"][sel])),
            altitude_min_m=float(alt.min()), altitude_max_m=float(alt.max()),
            agl_min_m=float(agl.min()), agl_max_m=float(agl.max()), max_altitude_m=max_alt,
            excess_m=excess, worst_photo=int(cols["photo"][sel][int(np.argmax(agl))])))
    return tuple(rows)


def _resolution_warnings(strips: tuple[StripTerrain, ...], plan: UavPlan, mode: str,
                         height_m: float, max_h: float | None, up: float,
                         agl: NDArray[np.float64], cols: dict[str, NDArray[Any]]
                         ) -> list[PlanWarning]:
    if plan.max_height_m is None or not strips:
        return []
    failing = [s for s in strips if s.excess_m > 1e-6]
    if not failing:
        return []
    worst = max(failing, key=lambda s: s.excess_m)
    nums = np.array([s.number for s in failing], dtype=np.int64)
    by = ", ".join(f"{s.number}: {s.excess_m:.0f}" for s in failing[:MAX_LISTED])
    remedy = {"constant": "terrain_remedy.constant", "strip": "terrain_remedy.strip",
              "follow": "terrain_remedy.follow"}[mode]
    return [PlanWarning("terrain_resolution", Message(
        "terrain_resolution", height=height_m, photo=worst.worst_photo, strip=worst.number,
        agl=worst.agl_max_m, flown=worst.agl_max_m * (1 + up), limit=plan.max_height_m,
        cid=plan.binding, excess=worst.excess_m, count=len(failing), strips=_listing(nums),
        by=by + (" …" if len(failing) > MAX_LISTED else ""),
        remedy=Message(remedy, max=max_h if max_h is not None else 0.0, height=height_m)))]


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


def _waypoints(cols: dict[str, NDArray[Any]], mode: str) -> list[dict[str, Any]]:
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

"""Synthetic DEMs (written with rasterio) and flight layouts for the terrain tests."""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path

import numpy as np
import rasterio
import shapely
from rasterio.transform import from_origin

from scanplan.geo.layout import Area, FlightLayout, Photos, Sortie, Strip
from scanplan.rules.results import UavInputs

PLAN_CRS = "EPSG:32637"
X0, Y0 = 500_000.0, 6_000_000.0
SENSOR_W_MM, SENSOR_H_MM, FOCAL_MM, PIXEL_UM = 24.0, 16.0, 35.0, 4.0


def uav_inputs(height_m: float = 100.0, up_pct: float = 0.0, down_pct: float = 0.0,
               gsd_target_cm: float | None = None, **kw) -> UavInputs:
    return UavInputs(pixel_um=PIXEL_UM, focal_mm=FOCAL_MM, f_number=8,
                     sensor_width_mm=SENSOR_W_MM, sensor_height_mm=SENSOR_H_MM,
                     height_m=height_m, speed_ms=10, exposure_s=1 / 2000,
                     forward_overlap_pct=80, side_overlap_pct=60,
                     height_tolerance_up_pct=up_pct, height_tolerance_down_pct=down_pct,
                     gsd_target_m=None if gsd_target_cm is None else gsd_target_cm / 100, **kw)


def layout(height_m: float = 100.0, strips: int = 5, per_strip: int = 12,
           forward_pct: float = 80.0, side_pct: float = 60.0, x0: float = X0, y0: float = Y0,
           plan_crs: str = PLAN_CRS) -> FlightLayout:
    """Strips along grid north (direction 0°) at x0 + k·spacing, photos at y0 + j·base."""
    across = SENSOR_W_MM / FOCAL_MM * height_m
    along = SENSOR_H_MM / FOCAL_MM * height_m
    spacing = across * (1 - side_pct / 100)
    base = along * (1 - forward_pct / 100)
    xs, ys, strip, index = [], [], [], []
    recs = []
    for k in range(strips):
        js = range(per_strip) if k % 2 == 0 else range(per_strip - 1, -1, -1)
        for i, j in enumerate(js):
            xs.append(x0 + k * spacing)
            ys.append(y0 + j * base)
            strip.append(k + 1)
            index.append(i + 1)
        start = (x0 + k * spacing, y0 + (0 if k % 2 == 0 else (per_strip - 1) * base))
        end = (x0 + k * spacing, y0 + ((per_strip - 1) * base if k % 2 == 0 else 0))
        recs.append(Strip(k + 1, start, end, (per_strip - 1) * base, per_strip,
                          k * per_strip + 1, 1))
    n = len(xs)
    cols = {"photo": np.arange(1, n + 1), "strip": np.array(strip), "index": np.array(index),
            "sortie": np.ones(n, dtype=int), "x_m": np.array(xs), "y_m": np.array(ys),
            "lon_deg": np.full(n, np.nan), "lat_deg": np.full(n, np.nan),
            "ground_m": np.zeros(n), "altitude_m": np.full(n, height_m),
            "agl_m": np.full(n, height_m), "gsd_cm": np.full(n, np.nan),
            "resolution_cm": np.full(n, np.nan), "recognition_p": np.full(n, np.nan)}
    geom = shapely.box(x0, y0, x0 + (strips - 1) * spacing, y0 + (per_strip - 1) * base)
    area = Area(geom, plan_crs, "test rectangle", plan_crs != "LOCAL", geom.area / 1e6,
                geom.length / 1e3)
    return FlightLayout(area=area, direction_deg=0.0, spacing_m=spacing, base_m=base,
                        strips=tuple(recs), sorties=(Sortie(1, tuple(range(1, strips + 1)),
                                                            0.0, None),),
                        photos=Photos(cols), flight_length_m=0.0, turn_length_m=0.0,
                        flight_time_s=None)


def write_dem(path: Path, func: Callable[[np.ndarray, np.ndarray], np.ndarray], *,
              left: float, top: float, cell: float, width: int, height: int,
              crs: str = PLAN_CRS, nodata: float | None = None, dtype: str = "float32",
              units: str | None = None) -> Path:
    """A GeoTIFF whose pixel (r, c) holds func(x, y) at the pixel centre."""
    cols = left + (np.arange(width) + 0.5) * cell
    rows = top - (np.arange(height) + 0.5) * cell
    xx, yy = np.meshgrid(cols, rows)
    data = np.asarray(func(xx, yy), dtype=dtype)
    with rasterio.open(path, "w", driver="GTiff", width=width, height=height, count=1,
                       dtype=dtype, crs=crs, transform=from_origin(left, top, cell, cell),
                       nodata=nodata, tiled=True, blockxsize=256, blockysize=256) as dst:
        dst.write(data, 1)
        if units:
            dst.set_band_unit(1, units)
    return path


def dem_around(path: Path, func, lay: FlightLayout, cell: float = 2.0, margin: float = 400.0,
               **kw) -> Path:
    """A DEM in the plan CRS covering the layout's area with a margin."""
    x0, y0, x1, y1 = lay.area.geometry.bounds
    width = int((x1 - x0 + 2 * margin) / cell)
    height = int((y1 - y0 + 2 * margin) / cell)
    return write_dem(path, func, left=x0 - margin, top=y1 + margin, cell=cell, width=width,
                     height=height, **kw)


def terrain_cases(tmp: Path) -> dict[str, list]:
    """Cases that raise every terrain warning: {case: [warning messages and reasons]}."""
    from pyproj import Transformer

    from scanplan.geo import terrain as T
    from scanplan.norms import load_norm_set
    from scanplan.project import terraincheck as TC
    from scanplan.rules.uav import plan_uav

    out: dict[str, list] = {}
    lay = layout(100.0)

    def slope(x, y):
        return 100 + 0.3 * (x - X0)

    tilt = dem_around(tmp / "tilt-cases.tif", slope, lay, dtype="float64")
    for mode in T.ALTITUDE_MODES:
        inp = uav_inputs(100.0, gsd_target_cm=1.0)
        res = TC.uav_terrain(lay, T.ground_under(lay, T.TerrainConfig(dem=tilt)), inp,
                            plan_uav(inp), mode, 40.0)
        out[f"terrain {mode}"] = [w.message for w in res.warnings]
    inp = uav_inputs(100.0, down_pct=70.0)
    res = TC.uav_terrain(lay, T.ground_under(lay, T.TerrainConfig(dem=tilt)), inp,
                        plan_uav(inp))
    out["terrain overlaps"] = [w.message for w in res.warnings]
    from scanplan.project.alternatives import overlap_findings
    short, within = overlap_findings(inp, res)  # a plan compared: rejected for it
    out["plans compared, overlaps short"] = short + within
    inp = uav_inputs(100.0, down_pct=30.0)
    res = TC.uav_terrain(lay, T.ground_under(lay, T.TerrainConfig(dem=tilt)), inp,
                        plan_uav(inp))
    out["terrain overlaps above the floor"] = [w.message for w in res.warnings]
    ph = lay.photos
    hx, hy = ph["x_m"][0], ph["y_m"][0]
    holes = dem_around(tmp / "holes-cases.tif", lambda x, y: np.where(
        np.hypot(x - hx, y - hy) < 5, -9999.0, 150.0), lay, nodata=-9999.0)
    out["terrain nodata"] = [w.message for w in T.ground_under(
        lay, T.TerrainConfig(dem=holes)).warnings]
    # no fill: a void the fill does not reach, within the share a DEM may miss
    pin = dem_around(tmp / "pin-cases.tif", lambda x, y: np.where(
        np.hypot(x - ph["x_m"][29], y - ph["y_m"][29]) < 1.5, -9999.0, 150.0), lay,
        nodata=-9999.0)
    out["terrain nodata unfilled"] = [w.message for w in T.ground_under(
        lay, T.TerrainConfig(dem=pin, void_fill_radius_m=0.0)).warnings]
    to = Transformer.from_crs(PLAN_CRS, "EPSG:4326", always_xy=True)
    lon, lat = to.transform(ph["x_m"], ph["y_m"])
    geo = write_dem(tmp / "geo-cases.tif", lambda x, y: np.full_like(x, 150.0),
                    left=float(np.min(lon)) - 0.01, top=float(np.max(lat)) + 0.01,
                    cell=1 / 3600, width=int((np.ptp(lon) + 0.02) * 3600),
                    height=int((np.ptp(lat) + 0.02) * 3600), crs="EPSG:4326")
    out["terrain geographic"] = [w.message for w in T.ground_under(
        lay, T.TerrainConfig(dem=geo)).warnings]
    # New York: a UTM block, a DEM in the state plane (US survey feet)
    ny = layout(100.0, x0=585_000.0, y0=4_510_000.0, plan_crs="EPSG:32618")
    to_ft = Transformer.from_crs("EPSG:32618", "EPSG:2263", always_xy=True)
    fx, fy = to_ft.transform(ny.photos["x_m"], ny.photos["y_m"])
    feet = write_dem(tmp / "feet-cases.tif", lambda x, y: np.full_like(x, 300.0),
                     left=float(np.min(fx)) - 3000, top=float(np.max(fy)) + 3000, cell=10.0,
                     width=int((np.ptp(fx) + 6000) / 10), height=int((np.ptp(fy) + 6000) / 10),
                     crs="EPSG:2263")
    out["terrain feet"] = [w.message for w in T.ground_under(
        ny, T.TerrainConfig(dem=feet)).warnings]
    rules = load_norm_set("gkinp-02-036-02").rules()
    film = layout(1530.0, strips=3, per_strip=5, forward_pct=60, side_pct=30)
    fdem = dem_around(tmp / "film-cases.tif", lambda x, y: 100 + 0.1 * (x - X0), film,
                      cell=20.0)
    ft = TC.film_terrain(film, T.ground_under(film, T.TerrainConfig(dem=fdem)), rules,
                        map_scale=2000, photo_scale=10000, relief_interval_m=1.0,
                        focal_mm=153, frame_along_mm=230, forward_overlap_pct=60,
                        resolving_power_lpmm=40, object_size_m=0.2, shape_coefficient=0.97)
    out["terrain film"] = [w.message for w in ft.warnings]
    return out


def valley_pinned(tmp: Path, mode: str = "constant") -> Path:
    """The valley example (with its KML and DEM) in ``tmp``, its altitude mode pinned: the
    example leaves the mode to scanplan, which follows the terrain there."""
    import shutil

    examples = Path(__file__).resolve().parent.parent / "examples"
    for folder in ("areas", "dem"):
        if not (tmp / folder).exists():
            shutil.copytree(examples / folder, tmp / folder)
    text = (examples / "uav-town-valley-2000.toml").read_text(encoding="utf-8")
    assert 'altitude_mode = "auto"' in text
    p = tmp / f"uav-town-valley-2000-{mode}.toml"
    p.write_text(text.replace('altitude_mode = "auto"', f'altitude_mode = "{mode}"'),
                 encoding="utf-8")
    return p

"""Benchmark: 10⁵ photo centres sampled on a 5,000 × 5,000 DEM (issue 12).

A synthetic DEM (float32, tiled 256 × 256, 5,000 × 5,000 cells of 4 m, in Web Mercator)
is written to a temporary folder; 100,000 photo centres spread over it, given in UTM zone
37N, are sampled with :func:`scanplan.geo.dem.sample_dem` — reprojection of the points
with pyproj, windowed reads of at most 2,048² pixels, bilinear interpolation — after one
untimed warm-up call. Target: ≤ 2 s (the issue's).

The in-process baseline is the simplest correct alternative with the same libraries: one
``read()`` of the whole raster into memory, the same pyproj transform and a numpy
bilinear; the ratio (scanplan / baseline) is the second row, target ≤ 1.5 (ours: bounded
memory may cost at most half again the time of reading everything at once). The values
of both must agree (checked, 1e-6 m).

Run: ``python benchmarks/bench_terrain.py``
"""

from __future__ import annotations

import math
import tempfile
import time
from pathlib import Path

import numpy as np
from _common import Result

TARGET_S = 2.0
TARGET_RATIO = 1.5
SIDE_PX = 5_000
CELL_M = 4.0
N_POINTS = 100_000
PLAN_CRS = "EPSG:32637"
DEM_CRS = "EPSG:3857"


def _write_dem(path: Path, side: int) -> tuple[float, float]:
    import rasterio
    from pyproj import Transformer
    from rasterio.transform import from_origin

    cx, cy = Transformer.from_crs(PLAN_CRS, DEM_CRS, always_xy=True).transform(500_000,
                                                                              6_000_000)
    left, top = cx - side * CELL_M / 2, cy + side * CELL_M / 2
    with rasterio.open(path, "w", driver="GTiff", width=side, height=side, count=1,
                       dtype="float32", crs=DEM_CRS, tiled=True, blockxsize=256,
                       blockysize=256,
                       transform=from_origin(left, top, CELL_M, CELL_M)) as dst:
        rows = np.arange(side, dtype=np.float32)
        for r0 in range(0, side, 1000):
            r = rows[r0:r0 + 1000, None]
            c = np.arange(side, dtype=np.float32)[None, :]
            block = 200 + 30 * np.sin(r / 300) + 20 * np.cos(c / 450)
            dst.write(block.astype(np.float32), 1,
                      window=rasterio.windows.Window(0, r0, side, block.shape[0]))
    return left, top


def _points(n: int, side: int, seed: int = 0) -> tuple[np.ndarray, np.ndarray]:
    """Photo centres (UTM) over the middle 90 % of the DEM."""
    rng = np.random.default_rng(seed)
    half = side * CELL_M / 2 * 0.9 * 0.5  # Mercator scale ≈ 1.9 at 54°N: stay inside
    return (500_000 + rng.uniform(-half, half, n), 6_000_000 + rng.uniform(-half, half, n))


def _baseline(path: Path, x: np.ndarray, y: np.ndarray) -> np.ndarray:
    import rasterio
    from pyproj import Transformer

    with rasterio.open(path) as src:
        data = src.read(1).astype(np.float64)
        t = src.transform
    mx, my = Transformer.from_crs(PLAN_CRS, DEM_CRS, always_xy=True).transform(x, y)
    col = (np.asarray(mx) - t.c) / t.a - 0.5
    row = (np.asarray(my) - t.f) / t.e - 0.5
    c0 = np.floor(col).astype(int)
    r0 = np.floor(row).astype(int)
    tx, ty = col - c0, row - r0
    return (data[r0, c0] * (1 - tx) * (1 - ty) + data[r0, c0 + 1] * tx * (1 - ty)
            + data[r0 + 1, c0] * (1 - tx) * ty + data[r0 + 1, c0 + 1] * tx * ty)


def run(n: int = N_POINTS, side: int = SIDE_PX, repeat: int = 3) -> dict[str, float]:
    """Time scanplan's sampling and the whole-raster baseline (best of ``repeat``)."""
    from scanplan.geo.dem import open_dem, sample_dem

    with tempfile.TemporaryDirectory() as tmp:
        path = Path(tmp) / "dem.tif"
        _write_dem(path, side)
        x, y = _points(n, side)
        info = open_dem(path)
        sample_dem(info, x[:10], y[:10], PLAN_CRS)  # warm-up: imports, pyproj database
        best, base = math.inf, math.inf
        for _ in range(repeat):
            t0 = time.perf_counter()
            s = sample_dem(open_dem(path), x, y, PLAN_CRS)
            best = min(best, time.perf_counter() - t0)
            t0 = time.perf_counter()
            ref = _baseline(path, x, y)
            base = min(base, time.perf_counter() - t0)
        diff = float(np.nanmax(np.abs(s.elevation_m - ref)))
        missing = int(np.isnan(s.elevation_m).sum())
    return {"n": n, "side": side, "scanplan_s": best, "baseline_s": base,
            "ratio": best / base, "max_diff_m": diff, "missing": missing}


def measure(quick: bool = False) -> list[Result]:
    """The runner's entry: the time (≤ 2 s) and the ratio to the baseline (≤ 1.5)."""
    r = run(repeat=1 if quick else 3)
    ok = r["max_diff_m"] <= 1e-6 and r["missing"] == 0
    note = (f"{r['n']:,} photo centres (UTM) on a {r['side']:,} × {r['side']:,} float32 DEM "
            f"(Web Mercator, tiled): scanplan {r['scanplan_s']:.3f} s (pyproj + windowed "
            f"reads + bilinear); whole-raster read + the same bilinear "
            f"{r['baseline_s']:.3f} s; values agree to {r['max_diff_m']:.1e} m, "
            f"{r['missing']} missing")
    return [
        Result("terrain", r["scanplan_s"] if ok else math.nan, "s", TARGET_S, "<=", note=note),
        Result("terrain.ratio", r["ratio"] if ok else math.nan, "x", TARGET_RATIO, "<=",
               note="scanplan's bounded-memory sampling / the whole-raster baseline, same "
                    "process"),
    ]


if __name__ == "__main__":
    res = run()
    print(f"{res['n']:,} points on {res['side']:,}²: scanplan {res['scanplan_s']:.3f} s, "
          f"baseline {res['baseline_s']:.3f} s, ratio {res['ratio']:.2f}, "
          f"max diff {res['max_diff_m']:.1e} m, missing {res['missing']}")

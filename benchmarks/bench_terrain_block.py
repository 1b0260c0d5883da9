"""Benchmark: a 10 × 10 km block with a DEM — 330,912 photos checked over the relief.

The block is a 10 km square (UTM zone 37N) planned at 1:2000 with the town example's UAV
(DJI Zenmuse P1 35 mm, 85 m, 80/70 % overlaps, a 20 m turnaround, 25-minute batteries,
lines along grid north), over a synthetic DEM of 5 m cells (2,240 × 2,240 float32, 20 m
of rolling relief, tiled GeoTIFF) written to a temporary folder. Measured, after one
untimed warm-up plan of a small block (first-call imports):

* **plan CPU** — ``time.process_time`` of ``load_project`` + ``plan_project``: the layout,
  the DEM read once into its min-max pyramid, every photo's footprint and stretch of path,
  the overlaps, the checks. Target ≤ 10 s.
* **memory per photo** — the ``tracemalloc`` peak of the same plan (a second run) divided
  by the photos: every array the plan holds at its busiest, the DEM's pyramid included.
  Target ≤ 1 kB (1,000 B). The same block without ``[terrain]`` is measured beside it (the
  note), and so is the process's peak RSS (``resource.getrusage``, Linux: kB).
* **all files** — the wall time of ``scanplan plan --out`` (in process, click's runner):
  the plan and every file it writes (the workbook, the PDF, photos.csv, the missions, the
  GIS files). Target ≤ 30 s.

Run: ``python benchmarks/bench_terrain_block.py`` (about a minute on the 2-core machine).
"""

from __future__ import annotations

import math
import resource
import tempfile
import time
import tracemalloc
from pathlib import Path

import numpy as np
from _common import Result

TARGET_CPU_S = 10.0
TARGET_BYTES_PER_PHOTO = 1000.0
TARGET_FILES_S = 30.0
X0, Y0 = 420_000.0, 6_100_000.0
SIDE_M = 10_000.0
CELL_M = 5.0
MARGIN_M = 600.0


def write_dem(folder: Path) -> Path:
    """The block's DEM: rolling relief of 20 m, 5 m cells, 600 m beyond the block."""
    import rasterio
    from rasterio.transform import from_origin

    n = int((SIDE_M + 2 * MARGIN_M) / CELL_M)
    left, top = X0 - MARGIN_M, Y0 + SIDE_M + MARGIN_M
    path = folder / "dem.tif"
    with rasterio.open(path, "w", driver="GTiff", width=n, height=n, count=1,
                       dtype="float32", crs="EPSG:32637",
                       transform=from_origin(left, top, CELL_M, CELL_M), nodata=-9999.0,
                       tiled=True, blockxsize=256, blockysize=256) as dst:
        xs = left + (np.arange(n) + 0.5) * CELL_M
        for r0 in range(0, n, 512):
            ys = top - (np.arange(r0, min(r0 + 512, n)) + 0.5) * CELL_M
            xx, yy = np.meshgrid(xs, ys)
            z = 150 + 6 * np.sin((xx - X0) / 900) + 4 * np.cos((yy - Y0) / 1300)
            dst.write(z.astype(np.float32), 1,
                      window=rasterio.windows.Window(0, r0, n, ys.size))
    return path


def project_text(side_m: float = SIDE_M, terrain: bool = True) -> str:
    """The block's project file (the DEM beside it as ``dem.tif``)."""
    ring = ", ".join(f"[{a:.1f}, {b:.1f}]" for a, b in (
        (X0, Y0), (X0 + side_m, Y0), (X0 + side_m, Y0 + side_m), (X0, Y0 + side_m)))
    text = f"""[project]
name = "Benchmark: 10 x 10 km block over a DEM"
[map]
scale = 2000
relief_interval_m = 0.5
[uav]
camera = "dji-zenmuse-p1-35"
height_m = 85
height_tolerance_pct = 10
speed_ms = 12
exposure_s = 0.0005
forward_overlap_pct = 80
side_overlap_pct = 70
turnaround_m = 20
max_flight_time_min = 25
[area]
polygon = [{ring}]
crs = "EPSG:32637"
direction_deg = 0
"""
    return text + ('[terrain]\ndem = "dem.tif"\n' if terrain else "")


def _plan(path: Path):
    from scanplan.project.file import load_project
    from scanplan.project.spec import plan_project

    return plan_project(load_project(path))


def run(files: bool = True) -> dict[str, float]:
    """Plan the block (CPU, then memory), without the DEM (memory), and write its files."""
    from click.testing import CliRunner

    from scanplan.cli.main import main

    with tempfile.TemporaryDirectory() as tmp:
        folder = Path(tmp)
        write_dem(folder)
        small = folder / "small.toml"
        small.write_text(project_text(1000.0), encoding="utf-8")
        _plan(small)  # warm-up: imports, the pyproj database, the norm set
        block = folder / "block.toml"
        block.write_text(project_text(), encoding="utf-8")
        flat = folder / "flat.toml"
        flat.write_text(project_text(terrain=False), encoding="utf-8")
        t0 = time.process_time()
        spec = _plan(block)
        cpu = time.process_time() - t0
        photos = spec.uav.job.layout.n_photos
        del spec
        tracemalloc.start()
        spec = _plan(block)
        peak = tracemalloc.get_traced_memory()[1]
        tracemalloc.stop()
        del spec
        tracemalloc.start()
        _plan(flat)
        peak_flat = tracemalloc.get_traced_memory()[1]
        tracemalloc.stop()
        files_s = math.nan
        if files:
            t0 = time.perf_counter()
            res = CliRunner().invoke(main, ["plan", str(block), "--out", str(folder / "out")])
            files_s = time.perf_counter() - t0
            if res.exit_code != 0:
                raise RuntimeError(res.output[-2000:])
        rss_mb = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0
    return {"photos": photos, "cpu_s": cpu, "peak_mb": peak / 1e6,
            "bytes_per_photo": peak / photos, "flat_bytes_per_photo": peak_flat / photos,
            "files_s": files_s, "rss_mb": rss_mb}


def measure(quick: bool = False) -> list[Result]:
    """The runner's rows: plan CPU (≤ 10 s), memory per photo (≤ 1 kB), all files
    (≤ 30 s; not in the quick profile)."""
    r = run(files=not quick)
    note = (f"{r['photos']:,} photos over a 2,240² DEM (5 m): plan {r['cpu_s']:.2f} s CPU; "
            f"tracemalloc peak {r['peak_mb']:.0f} MB = {r['bytes_per_photo']:.0f} B per photo "
            f"(the same block without a DEM: {r['flat_bytes_per_photo']:.0f} B); peak RSS of "
            f"the process {r['rss_mb']:.0f} MB")
    rows = [
        Result("terrain_block.plan_cpu", r["cpu_s"], "s", TARGET_CPU_S, "<=", note=note),
        Result("terrain_block.bytes_per_photo", r["bytes_per_photo"], "B",
               TARGET_BYTES_PER_PHOTO, "<=", timing=False,
               note="tracemalloc peak of the plan with the DEM / photos"),
    ]
    if not quick:
        rows.append(Result("terrain_block.files", r["files_s"], "s", TARGET_FILES_S, "<=",
                           note="scanplan plan --out: the plan and every file it writes "
                                "(wall time)"))
    return rows


if __name__ == "__main__":
    res = run()
    print(f"{res['photos']:,} photos: plan {res['cpu_s']:.2f} s CPU, "
          f"{res['bytes_per_photo']:.0f} B/photo with the DEM "
          f"({res['flat_bytes_per_photo']:.0f} without; peak {res['peak_mb']:.0f} MB), "
          f"all files {res['files_s']:.1f} s, peak RSS {res['rss_mb']:.0f} MB")

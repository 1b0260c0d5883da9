"""Write examples/dem/town-valley.tif: a SYNTHETIC digital elevation model (not survey data).

The town of the UAV example (examples/areas/town-uav.kml) stands on a plateau at about
160 m; this DEM cuts a river valley 60 m deep across it, from the south-west to the
north-east, with a flat floor 120 m wide at 100 m and slopes about 300 m wide on each side,
and lets the plateau rise gently (0.4 m per 100 m) to the north-west. Grid: 20 m cells in
WGS 84 / UTM zone 37N (EPSG:32637), float32, heights in metres above sea level, deflate
compressed. Regenerate with ``python examples/dem/make_town_valley.py``.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import rasterio
from pyproj import Transformer
from rasterio.transform import from_origin

HERE = Path(__file__).resolve().parent
CELL_M = 20.0
PLATEAU_M = 160.0
DEPTH_M = 60.0
FLOOR_HALF_WIDTH_M = 60.0
SLOPE_WIDTH_M = 300.0


def elevation_m(x: np.ndarray, y: np.ndarray, cx: float, cy: float) -> np.ndarray:
    """Plateau with a valley along the line through (cx, cy) at 45° (SW → NE)."""
    d = np.abs((x - cx) - (y - cy)) / np.sqrt(2.0)  # distance from the valley axis [m]
    t = np.clip((d - FLOOR_HALF_WIDTH_M) / SLOPE_WIDTH_M, 0.0, 1.0)
    valley = DEPTH_M * (1.0 - (3 * t**2 - 2 * t**3))  # smooth slopes (smoothstep)
    rise = 0.004 * ((y - cy) - (x - cx)) / np.sqrt(2.0)  # gently up to the north-west
    return PLATEAU_M - valley + np.maximum(rise, 0.0)


def main() -> Path:
    to_utm = Transformer.from_crs("EPSG:4326", "EPSG:32637", always_xy=True)
    cx, cy = to_utm.transform(38.7915, 55.0803)  # the town's middle
    half_w, half_h = 2600.0, 1800.0
    left, top = round(cx - half_w, -1), round(cy + half_h, -1)
    width, height = int(2 * half_w / CELL_M), int(2 * half_h / CELL_M)
    xs = left + (np.arange(width) + 0.5) * CELL_M
    ys = top - (np.arange(height) + 0.5) * CELL_M
    xx, yy = np.meshgrid(xs, ys)
    z = elevation_m(xx, yy, cx, cy).astype(np.float32)
    path = HERE / "town-valley.tif"
    with rasterio.open(path, "w", driver="GTiff", width=width, height=height, count=1,
                       dtype="float32", crs="EPSG:32637",
                       transform=from_origin(left, top, CELL_M, CELL_M), nodata=-9999.0,
                       compress="deflate", predictor=3, tiled=True, blockxsize=128,
                       blockysize=128) as dst:
        dst.write(z, 1)
        dst.set_band_unit(1, "metre")
        dst.update_tags(SOURCE="SYNTHETIC: scanplan example, examples/dem/make_town_valley.py")
    return path


if __name__ == "__main__":
    print(main())

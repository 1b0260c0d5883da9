"""The worst ground between the photo centres: a pit or a ridge 10 m wide, 40 m deep/high,
where no centre is, changes the worst GSD, the clearance and the altitude ceiling's check.

Flat ground at 150 m (2 m cells) with a 10 m × 10 m square pit or ridge; the layout of
``terrain_helpers`` (strips along grid north, 27.4 m apart, photos 18.3 m apart at
100 m). The centres nearest the feature are more than two cells away, so the bilinear
ground at every centre is 150 m: a check at the centres alone would see flat ground.
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np
import pytest

sys.path.insert(0, str(Path(__file__).parent))

from terrain_helpers import FOCAL_MM, PIXEL_UM, X0, Y0, dem_around, layout, uav_inputs

from scanplan.geo import terrain as T
from scanplan.project import terraincheck as TC
from scanplan.rules.uav import plan_uav

H = 100.0
FLAT_M = 150.0
DEPTH_M = 40.0


def _square(cx: float, cy: float, dz: float):
    def z(x, y):
        inside = (np.abs(x - cx) < 5.0) & (np.abs(y - cy) < 5.0)
        return np.where(inside, FLAT_M + dz, FLAT_M)
    return z


def _run(tmp: Path, z, **kw):
    lay = layout(H, forward_pct=60.0)
    p = dem_around(tmp / "dem.tif", z, lay)
    inp = uav_inputs(H, **kw)
    plan = plan_uav(inp)
    ground = T.ground_under(lay, T.TerrainConfig(dem=p))
    return lay, TC.uav_terrain(lay, ground, inp, plan), plan


def test_a_pit_between_the_centres_sets_the_worst_gsd(tmp_path):
    lay0 = layout(H, forward_pct=60.0)
    # between strips 2 and 3, between two photos: 13.7 m and 9.1 m from the nearest lines
    # and photos
    cx, cy = X0 + 1.5 * lay0.spacing_m, Y0 + 5.5 * lay0.base_m
    _, r, _ = _run(tmp_path, _square(cx, cy, -DEPTH_M), gsd_target_cm=2.0)
    ph = r.layout.photos
    np.testing.assert_allclose(ph["ground_m"], FLAT_M, atol=1e-6)  # the centres: flat
    gsd_flat = PIXEL_UM / 1000 * H / FOCAL_MM * 100
    gsd_pit = PIXEL_UM / 1000 * (H + DEPTH_M) / FOCAL_MM * 100
    assert ph["gsd_cm"].max() == pytest.approx(gsd_pit, rel=1e-6)  # +40 %
    assert ph["gsd_cm"].max() > 1.3 * gsd_flat
    # the photos whose footprint holds the pit, and only those near it, are worst
    worst = ph["gsd_cm"] > gsd_flat * 1.01
    d_across = np.abs(ph["x_m"][worst] - cx)
    d_along = np.abs(ph["y_m"][worst] - cy)
    assert worst.sum() >= 2
    fp_across = 24.0 / FOCAL_MM * (H + DEPTH_M)
    fp_along = 16.0 / FOCAL_MM * (H + DEPTH_M)
    assert np.all(d_across <= fp_across / 2 + 5 + 25) and np.all(d_along <= fp_along / 2 + 30)
    assert r.summary()["footprint_agl_max_m"] == pytest.approx(H + DEPTH_M, abs=1e-6)
    assert r.summary()["path_agl_max_m"] == pytest.approx(H, abs=1e-6)  # not under a line
    # and the maximum height over the block knows it: the GSD limit at the pit
    assert r.max_height_m == pytest.approx(plan_uav(uav_inputs(H, gsd_target_cm=2.0))
                                           .max_height_m - DEPTH_M, abs=1e-6)


def test_a_pit_under_a_line_breaks_the_altitude_ceiling(tmp_path):
    """A 120 m ceiling and a plan at 100 m over flat ground: over the pit under strip 2,
    between two photos, the aircraft is 140 m above the ground."""
    lay0 = layout(H, forward_pct=60.0)
    cx, cy = X0 + lay0.spacing_m, Y0 + 5.5 * lay0.base_m
    _, flat, plan = _run(tmp_path, lambda x, y: np.full_like(x, FLAT_M), ceiling_m=120.0)
    assert plan.binding == "HC" and plan.max_height_m == pytest.approx(120.0)
    assert not [w for w in flat.warnings if w.code == "terrain_resolution"]
    (tmp_path / "pit").mkdir()
    _, r, _ = _run(tmp_path / "pit", _square(cx, cy, -DEPTH_M), ceiling_m=120.0)
    np.testing.assert_allclose(r.layout.photos["ground_m"], FLAT_M, atol=1e-6)
    s = r.summary()
    assert s["path_agl_max_m"] == pytest.approx(H + DEPTH_M, abs=1e-6)
    assert s["clearance_min_m"] == pytest.approx(H, abs=1e-6)
    w = next(w for w in r.warnings if w.code == "terrain_resolution")
    assert "HC" in w.message
    assert r.max_height_m == pytest.approx(120.0 - DEPTH_M, abs=1e-6)
    bad = [st for st in r.strips if st.excess_m > 0]
    assert [st.number for st in bad] == [2] and bad[0].excess_m == pytest.approx(20.0)


def test_a_ridge_under_a_line_between_the_centres_lifts_the_altitude(tmp_path):
    lay0 = layout(H, forward_pct=60.0)
    cx, cy = X0 + lay0.spacing_m, Y0 + 5.5 * lay0.base_m
    _, r, _ = _run(tmp_path, _square(cx, cy, DEPTH_M))
    ph = r.layout.photos
    np.testing.assert_allclose(ph["ground_m"], FLAT_M, atol=1e-6)
    np.testing.assert_allclose(ph["altitude_m"], FLAT_M + DEPTH_M + H, atol=1e-6)
    assert r.summary()["clearance_min_m"] == pytest.approx(H, abs=1e-6)
    # strip mode: only the strip over the ridge is lifted
    lay = layout(H, forward_pct=60.0)
    p = dem_around(tmp_path / "ridge.tif", _square(cx, cy, DEPTH_M), lay)
    inp = uav_inputs(H)
    rs = TC.uav_terrain(lay, T.ground_under(lay, T.TerrainConfig(dem=p)), inp, plan_uav(inp),
                       "strip")
    alts = {s.number: s.altitude_m for s in rs.layout.strips}
    assert alts[2] == pytest.approx(FLAT_M + DEPTH_M + H)
    assert {k: v for k, v in alts.items() if k != 2} == pytest.approx(
        {k: FLAT_M + H for k in alts if k != 2})


def test_the_pyramid_is_read_once_until_the_dem_changes(tmp_path, monkeypatch):
    """A re-plan that leaves the photos' extent alone reuses the DEM's min-max pyramid; a
    rewritten DEM file is read again."""
    import time

    from scanplan.geo import dem as D
    from scanplan.geo import dem_grid as G

    lay = layout()
    path = dem_around(tmp_path / "dem.tif", lambda x, y: 100.0 + 0 * x, lay)
    reads: list[int] = []
    real = G._read_ground_grid
    monkeypatch.setattr(G, "_read_ground_grid", lambda *a: reads.append(1) or real(*a))
    x0, y0, x1, y1 = lay.area.geometry.bounds
    args = ((x0, y0, x1, y1), lay.area.geometry, lay.area.plan_crs)
    first = G.read_ground_grid(D.open_dem(path), *args)
    assert G.read_ground_grid(D.open_dem(path), *args) is first and len(reads) == 1
    assert not first.lo[0].flags.writeable  # shared: never changed in place
    time.sleep(0.01)
    dem_around(path, lambda x, y: 50.0 + 0 * x, lay)  # the same file name, new heights
    again = G.read_ground_grid(D.open_dem(path), *args)
    assert len(reads) == 2 and float(np.nanmax(again.hi[0])) == pytest.approx(50.0)

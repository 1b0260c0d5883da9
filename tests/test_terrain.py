"""Terrain (issue 12): every photo at its own height above ground, on synthetic DEMs.

The DEMs are written with rasterio in each test (flat plane, tilted plane, cone hill, a
cliff, nodata holes, a DEM in another CRS and a geographic one); AGL, GSD and overlaps at
every photo are compared with their analytic values.

Tolerances: a plane is reproduced exactly by bilinear sampling, so plane DEMs agree to
1e-6 m (float32 storage of the DEM: its values are chosen exactly representable or the
analytic value is computed from the stored float32); the cone hill is curved inside a cell,
so its ground agrees within the bilinear error bound slope·cell/2 (here 0.1 m × 2 = 0.2 m
is generous; the measured error is below it); overlaps follow to 1e-9 %.
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

sys.path.insert(0, str(Path(__file__).parent))

from terrain_helpers import (
    FOCAL_MM,
    PIXEL_UM,
    PLAN_CRS,
    SENSOR_H_MM,
    SENSOR_W_MM,
    X0,
    Y0,
    dem_around,
    layout,
    uav_inputs,
    write_dem,
)

from scanplan.errors import InputError
from scanplan.geo import dem as D
from scanplan.geo import terrain as T
from scanplan.project import terraincheck as TC
from scanplan.rules.uav import ground_resolution_m, plan_uav

H = 100.0
MID = 2 * 12 + 5  # a photo of the middle strip of layout(), inside the area
GRID_REACH_M = 25.0
"""How far beyond a footprint or path (of these layouts, 2 m cells) the grid may reach:
the bilinear support (one cell) and one pyramid block (< 1/8 of the footprint's side)."""


def run(lay, dem_path=None, *, mode="constant", h=H, tol_m=5.0, rng=None, **kw):
    inp = uav_inputs(h, **kw)
    plan = plan_uav(inp)
    cfg = T.TerrainConfig(dem=dem_path, ground_range_m=rng, altitude_mode=mode,
                          follow_tolerance_m=tol_m)
    ground = T.ground_under(lay, cfg)
    return TC.uav_terrain(lay, ground, inp, plan, mode, tol_m), inp, plan


def analytic_overlaps(lay, alt, ground_fn):
    """Forward and side overlap of every photo from the exact ground function [%]."""
    ph = lay.photos
    x, y, strip, idx = ph["x_m"], ph["y_m"], ph["strip"], ph["index"]
    n = len(ph)
    fw = np.full(n, np.inf)
    sd = np.full(n, np.inf)
    key = {(int(s), round(float(xx), 6), round(float(yy), 6)): i
           for i, (s, xx, yy) in enumerate(zip(strip, x, y, strict=True))}
    for i in range(n):
        for j in range(n):
            if i == j:
                continue
            same = strip[i] == strip[j]
            dx, dy = abs(x[i] - x[j]), abs(y[i] - y[j])
            if same and dx < 1e-6 and abs(dy - lay.base_m) < 1e-6:
                g = ground_fn((x[i] + x[j]) / 2, (y[i] + y[j]) / 2)
                fp = SENSOR_H_MM / FOCAL_MM * ((alt[i] + alt[j]) / 2 - g)
                fw[i] = min(fw[i], (1 - lay.base_m / fp) * 100)
            if abs(strip[i] - strip[j]) == 1 and dy < 1e-6:
                g = ground_fn((x[i] + x[j]) / 2, (y[i] + y[j]) / 2)
                fp = SENSOR_W_MM / FOCAL_MM * ((alt[i] + alt[j]) / 2 - g)
                sd[i] = min(sd[i], (1 - dx / fp) * 100)
    del key, idx
    return fw, sd


# --- flat and tilted planes: exact -----------------------------------------------------------

def test_flat_dem_gives_the_planned_height_everywhere(tmp_path):
    lay = layout(H)
    p = dem_around(tmp_path / "flat.tif", lambda x, y: np.full_like(x, 212.5), lay)
    r, _inp, plan = run(lay, p, gsd_target_cm=1.5)
    ph = r.layout.photos
    np.testing.assert_allclose(ph["ground_m"], 212.5, atol=1e-9)
    np.testing.assert_allclose(ph["altitude_m"], 312.5, atol=1e-9)
    np.testing.assert_allclose(ph["agl_m"], H, atol=1e-9)
    np.testing.assert_allclose(ph["gsd_cm"], PIXEL_UM / 1000 * H / FOCAL_MM * 100, rtol=1e-12)
    np.testing.assert_allclose(ph["forward_overlap_pct"], 80.0, atol=1e-9)
    np.testing.assert_allclose(ph["side_overlap_pct"], 60.0, atol=1e-9)
    assert r.max_height_m == pytest.approx(plan.max_height_m, abs=1e-9)
    assert r.warnings == ()


@pytest.mark.parametrize("mode", ["constant", "strip", "follow"])
def test_tilted_plane_agl_gsd_overlaps_are_analytic(tmp_path, mode):
    """z = 150 + 0.08·(x − x0) − 0.03·(y − y0): exact under bilinear sampling."""
    lay = layout(H, strips=4, per_strip=9)

    def z(x, y):
        return 150.0 + 0.08 * (x - X0) - 0.03 * (y - Y0)

    p = dem_around(tmp_path / "tilt.tif", lambda x, y: z(x, y), lay, dtype="float64")
    r, inp, _plan = run(lay, p, mode=mode, tol_m=1.0)
    ph = r.layout.photos
    g = z(ph["x_m"], ph["y_m"])
    np.testing.assert_allclose(ph["ground_m"], g, atol=1e-6)
    # the path of each strip: its photos and the run-in (half the spacing, a semicircle
    # turn) before and after; on a plane its highest ground is at one of its ends
    run_in = lay.spacing_m / 2
    ends = {k: max(z(ph["x_m"][ph["strip"] == k][0], ph["y_m"][ph["strip"] == k].min()
                     - run_in),
                   z(ph["x_m"][ph["strip"] == k][0], ph["y_m"][ph["strip"] == k].max()
                     + run_in)) for k in np.unique(ph["strip"])}
    top = np.array([ends[k] for k in ph["strip"]])
    alt = ph["altitude_m"]
    reach = GRID_REACH_M * 0.085  # the conservative reach of the grid × the plane's slope
    if mode == "constant":
        assert np.all(alt == alt[0])
        assert max(ends.values()) + H - 1e-3 <= alt[0] <= max(ends.values()) + H + reach
    elif mode == "strip":
        assert np.all((alt >= top + H - 1e-3) & (alt <= top + H + reach))
    else:
        assert np.all(alt - g >= H - 1e-3) and np.all(alt - g <= H + 1.0 + reach + 2.0)
    assert r.path["clearance_min_m"] >= H - 1e-3
    # GSD, L at the largest height above the ground seen in the footprint
    np.testing.assert_allclose(ph["agl_m"], alt - ph["ground_min_m"], atol=1e-9)
    np.testing.assert_allclose(ph["gsd_cm"], PIXEL_UM / 1000 * ph["agl_m"] / FOCAL_MM * 100,
                               rtol=1e-12)
    np.testing.assert_allclose(ph["resolution_cm"],
                               ground_resolution_m(inp, ph["agl_m"]) * 100, rtol=1e-6)
    fw, sd = analytic_overlaps(lay, alt, z)
    np.testing.assert_allclose(ph["forward_overlap_pct"], fw, atol=1e-6)
    np.testing.assert_allclose(ph["side_overlap_pct"], sd, atol=1e-6)
    # the footprint range on a plane: the plane at the footprint's corners; the grid's
    # answer holds it (never higher / lower) and reaches at most GRID_REACH_M beyond it
    fa = SENSOR_H_MM / FOCAL_MM * (alt - g) / 2
    fc = SENSOR_W_MM / FOCAL_MM * (alt - g) / 2
    lo = z(ph["x_m"] - fc, ph["y_m"] + fa)
    hi = z(ph["x_m"] + fc, ph["y_m"] - fa)
    assert np.all(ph["ground_min_m"] <= lo + 1e-3)
    assert np.all(ph["ground_max_m"] >= hi - 1e-3)
    fa2 = SENSOR_H_MM / FOCAL_MM * ph["agl_m"] / 2
    fc2 = SENSOR_W_MM / FOCAL_MM * ph["agl_m"] / 2
    assert np.all(ph["ground_min_m"] >= z(ph["x_m"] - fc2, ph["y_m"] + fa2) - reach)
    assert np.all(ph["ground_max_m"] <= z(ph["x_m"] + fc2, ph["y_m"] - fa2) + reach)


def test_constant_mode_holds_the_planned_height_over_the_highest_ground(tmp_path):
    lay = layout(H)
    p = dem_around(tmp_path / "tilt.tif", lambda x, y: 100 + 0.1 * (x - X0), lay,
                   dtype="float64")
    r, *_ = run(lay, p)
    ph = r.layout.photos
    # over the highest ground under the path: never closer than planned, and no higher
    # than the grid's reach above it
    assert H - 1e-3 <= r.path["clearance_min_m"] <= H + 1e-3
    assert np.all(ph["altitude_m"] - ph["ground_m"] >= H - 1e-3)
    assert np.all(ph["forward_overlap_pct"] >= 80 - 1e-6)  # nowhere less than planned
    assert r.min_side_overlap_pct >= 60 - 1e-6


# --- cone hill, cliff ------------------------------------------------------------------------

def cone(x, y, cx=X0 + 60.0, cy=Y0 + 60.0, top=80.0, slope=0.1):
    return np.maximum(0.0, top - slope * np.hypot(x - cx, y - cy)) + 100.0


def test_cone_hill_within_the_bilinear_bound(tmp_path):
    lay = layout(H)
    p = dem_around(tmp_path / "cone.tif", cone, lay, cell=2.0, dtype="float64")
    r, _inp, _ = run(lay, p)
    ph = r.layout.photos
    g = cone(ph["x_m"], ph["y_m"])
    err = np.abs(ph["ground_m"] - g)
    assert err.max() <= 0.1 * 2.0  # slope × cell: the bilinear bound on a cone
    alt = ph["altitude_m"][0]
    np.testing.assert_allclose(ph["agl_m"], alt - ph["ground_min_m"], atol=1e-9)
    assert np.all(ph["ground_min_m"] <= ph["ground_m"] + 1e-3)
    assert np.all(ph["altitude_m"] == alt)
    # the highest ground under a path: the cone beside its top, on the nearest line
    under = max(cone(x, Y0 + 60.0) for x in np.unique(ph["x_m"]))
    assert alt >= under + H - 0.2 - 1e-3


def test_cliff_strips_on_either_side_and_the_footprint_range(tmp_path):
    lay = layout(H, strips=4)
    cliff_x = X0 + 1.5 * lay.spacing_m  # between strips 2 and 3

    def z(x, y):
        return np.where(x < cliff_x, 100.0, 160.0)

    p = dem_around(tmp_path / "cliff.tif", z, lay, cell=1.0)
    r, _inp, _ = run(lay, p, mode="strip")
    ph = r.layout.photos
    low, high = ph["strip"] <= 2, ph["strip"] >= 3
    np.testing.assert_allclose(ph["ground_m"][low], 100.0)
    np.testing.assert_allclose(ph["ground_m"][high], 160.0)
    np.testing.assert_allclose(ph["altitude_m"][low], 200.0)
    np.testing.assert_allclose(ph["altitude_m"][high], 260.0)
    # footprints of strips 2 and 3 reach across the cliff: both levels under them; strip
    # 3 sees the foot of the cliff, 160 m below its altitude
    s2 = ph["strip"] == 2
    np.testing.assert_allclose(ph["agl_m"][s2], H)
    np.testing.assert_allclose(ph["agl_m"][ph["strip"] == 3], H + 60.0)
    np.testing.assert_allclose(ph["ground_min_m"][s2], 100.0)
    np.testing.assert_allclose(ph["ground_max_m"][s2], 160.0)
    assert [s.altitude_m for s in r.layout.strips] == [200.0, 200.0, 260.0, 260.0]
    # constant mode over the same cliff: strips 1–2 are 60 m higher above their ground
    rc, *_ = run(lay, p, mode="constant")
    np.testing.assert_allclose(rc.layout.photos["agl_m"][low], H + 60.0)


# --- the worst photo binds; the maximum height in closed form -----------------------------

@pytest.mark.parametrize("mode", ["constant", "strip", "follow"])
def test_maximum_height_is_where_the_worst_photo_meets_its_constraint(tmp_path, mode):
    lay = layout(H)
    p = dem_around(tmp_path / "cone.tif", cone, lay, dtype="float64")
    r, _inp, plan = run(lay, p, mode=mode, gsd_target_cm=1.5, up_pct=10)
    assert plan.binding == "GSD"
    h_max = r.max_height_m
    assert h_max is not None and 0 < h_max < plan.max_height_m
    # the closed form holds for the footprints at the height it was computed at: there
    # the worst photo meets the limit exactly; footprints grow with the height, so the
    # height is found by a few fixed-point steps (the plan's own re-check does the same)
    worst_then = r.layout.photos["agl_m"] - (r.height_m - h_max)
    assert worst_then.max() == pytest.approx(plan.max_height_m, abs=1e-6)
    for _ in range(4):
        at, *_ = run(lay, p, mode=mode, h=h_max, gsd_target_cm=1.5, up_pct=10)
        if at.max_height_m >= h_max - 1e-9:
            break
        h_max = at.max_height_m
    worst = at.layout.photos["agl_m"].max()
    assert plan.max_height_m - 0.05 <= worst <= plan.max_height_m + 1e-6
    flown_gsd = PIXEL_UM / 1000 * worst * 1.10 / FOCAL_MM
    assert flown_gsd <= 0.015 * (1 + 1e-9)  # the binding GSD limit
    assert not [w for w in at.warnings if w.code == "terrain_resolution"]
    above, *_ = run(lay, p, mode=mode, h=h_max + 0.5, gsd_target_cm=1.5, up_pct=10)
    codes = [w.code for w in above.warnings]
    assert "terrain_resolution" in codes
    w = next(w for w in above.warnings if w.code == "terrain_resolution")
    assert f"photo {above.worst_resolution_photo}" in w.message
    excess = max(s.excess_m for s in above.strips)
    assert 0.45 <= excess <= 0.6


def test_strip_maximum_altitude_is_its_lowest_ground_plus_the_limit(tmp_path):
    lay = layout(H)
    p = dem_around(tmp_path / "tilt.tif", lambda x, y: 100 + 0.2 * (x - X0), lay,
                   dtype="float64")
    r, _inp, plan = run(lay, p, mode="constant", gsd_target_cm=1.2)
    ph = r.layout.photos
    for s in r.strips:
        sel = ph["strip"] == s.number
        assert s.max_altitude_m == pytest.approx(ph["ground_min_m"][sel].min()
                                                 + plan.max_height_m)
        assert s.excess_m == pytest.approx(max(0.0, ph["agl_m"][sel].max()
                                               - plan.max_height_m), abs=1e-9)
    w = next(w for w in r.warnings if w.code == "terrain_resolution")
    assert "strip" in w.message and "altitude_mode" in w.message
    assert "маршрут" in w.text("ru")


# --- flat DEM ≡ no DEM --------------------------------------------------------------------

@settings(max_examples=25, deadline=None,
          suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(level=st.floats(-400, 4000), h=st.floats(40, 300), up=st.floats(0, 50),
       down=st.floats(0, 30), mode=st.sampled_from(T.ALTITUDE_MODES))
def test_flat_dem_is_the_same_as_no_dem(tmp_path, level, h, up, down, mode):
    lay = layout(h, strips=3, per_strip=5)
    level = float(np.float32(level))
    p = dem_around(tmp_path / f"flat{abs(hash((level, h)))}.tif",
                   lambda x, y: np.full_like(x, level), lay, cell=10.0)
    a, _, pa = run(lay, p, mode=mode, h=h, up_pct=up, down_pct=down, gsd_target_cm=2.0)
    b, _, _pb = run(lay, None, mode=mode, h=h, up_pct=up, down_pct=down, gsd_target_cm=2.0,
                   rng=(0.0, 0.0))
    pa_, pb_ = a.layout.photos, b.layout.photos
    for col in ("agl_m", "gsd_cm", "resolution_cm", "forward_overlap_pct", "side_overlap_pct"):
        np.testing.assert_allclose(pa_[col], pb_[col], rtol=1e-9, atol=1e-9, err_msg=col)
    np.testing.assert_allclose(pa_["altitude_m"] - level, pb_["altitude_m"], atol=1e-6)
    assert a.max_height_m == pytest.approx(b.max_height_m, abs=1e-9)
    assert a.max_height_m == pytest.approx(pa.max_height_m, abs=1e-9)
    assert [w.code for w in a.warnings] == [w.code for w in b.warnings]


def test_ground_range_without_a_dem_checks_both_ends():
    lay = layout(H)
    r, _inp, plan = run(lay, None, rng=(120.0, 180.0), gsd_target_cm=1.2)
    ph = r.layout.photos
    assert np.all(np.isnan(ph["ground_m"]))
    np.testing.assert_allclose(ph["altitude_m"], 280.0)  # over the highest ground
    np.testing.assert_allclose(ph["agl_m"], 160.0)  # the largest AGL it may have
    assert r.max_height_m == pytest.approx(plan.max_height_m - 60.0)
    assert "terrain_resolution" in [w.code for w in r.warnings]


# --- bad input -------------------------------------------------------------------------------

def test_a_three_pixel_void_is_filled_conservatively_and_reported(tmp_path):
    """Three no-data pixels under a photo of the middle strip: filled with the highest
    known ground within the radius plus the margin (for the altitude) and the lowest minus
    it (for the scale)."""
    lay = layout(H)
    ph = lay.photos
    hx, hy = ph["x_m"][MID], ph["y_m"][MID]
    cell = 2.0

    def z(x, y):
        base = 100 + 0.05 * (x - X0)
        # three pixels in a row, the photo centre on the middle one
        void = (np.abs(y - hy) < cell / 2) & (np.abs(x - hx) < 1.5 * cell)
        return np.where(void, -9999.0, base)

    x0, y0, x1, y1 = lay.area.geometry.bounds
    # pixel centres on the photo centre: the DEM's origin half a cell off it
    left = hx - cell / 2 - cell * round((hx - x0 + 400) / cell)
    top = hy + cell / 2 + cell * round((y1 + 400 - hy) / cell)
    p = write_dem(tmp_path / "void.tif", z, left=left, top=top, cell=cell,
                  width=int((x1 - x0 + 800) / cell), height=int((y1 - y0 + 800) / cell),
                  nodata=-9999.0)
    cfg = T.TerrainConfig(dem=p)
    ground = T.ground_under(lay, cfg)
    assert ground.grid.voids.filled_px == 3 and ground.grid.voids.unknown_px == 0
    assert ground.details["voids_filled_m2"] == pytest.approx(3 * cell * cell)
    w = next(w for w in ground.warnings if w.code == "terrain_voids_filled")
    assert "3 pixels (12 m²" in w.message and "50 m" in w.message
    assert "3~пикселей" in w.text("ru") or "3 пикселей" in w.text("ru")
    assert "terrain_no_ground" not in [w.code for w in ground.warnings]
    inp = uav_inputs(H)
    r = TC.uav_terrain(lay, ground, inp, plan_uav(inp))
    out = r.layout.photos
    i = int(np.flatnonzero(out["photo"] == ph["photo"][MID])[0])
    assert np.isnan(out["ground_m"][i])  # the centre itself has no DEM value
    # the fill: the highest known ground within 50 m of the void (its east end) + 10 m
    fill_hi = 100 + 0.05 * (hx + cell + 50.0 - X0) + 10.0  # pixel centres
    fill_lo = 100 + 0.05 * (hx - cell - 50.0 - X0) - 10.0
    assert out["altitude_m"][i] >= fill_hi + H - 0.5
    assert out["ground_min_m"][i] <= fill_lo + 1e-3
    assert r.summary()["voids_filled_px"] == 3


def test_a_half_no_data_dem_is_refused_naming_the_share(tmp_path):
    lay = layout(H, strips=20)
    x0, _y0, x1, _y1 = lay.area.geometry.bounds
    mid = (x0 + x1) / 2

    def z(x, y):
        return np.where(x > mid, -9999.0, 100.0 + 0.0 * y)

    p = dem_around(tmp_path / "half.tif", z, lay, nodata=-9999.0)
    with pytest.raises(InputError) as e:
        T.ground_under(lay, T.TerrainConfig(dem=p))
    msg = e.value.message
    assert e.value.field == "terrain.dem" and "no-data" in msg and "km²" in msg
    share = float(msg.split("(")[1].split("%")[0])
    assert 30.0 < share < 50.0  # the half, but its 50 m beside known ground


def test_no_data_beyond_the_radius_counts_with_the_missing_extent(tmp_path):
    """A 12 m hole (1 % of the block) is filled at the default radius, refused without it;
    four pixels (0.15 %) without a fill is named and checked at the block's extremes."""
    lay = layout(H)
    ph = lay.photos
    hx, hy = ph["x_m"][MID], ph["y_m"][MID]

    def z(x, y, r):
        return np.where(np.hypot(x - hx, y - hy) < r, -9999.0, 100 + 0.05 * (x - X0))

    hole = dem_around(tmp_path / "hole.tif", lambda x, y: z(x, y, 6.0), lay, nodata=-9999.0)
    assert T.ground_under(lay, T.TerrainConfig(dem=hole)).grid.voids.unknown_px == 0
    with pytest.raises(InputError, match=r"no-data farther than 0 m"):
        T.ground_under(lay, T.TerrainConfig(dem=hole, void_fill_radius_m=0.0))
    pin = dem_around(tmp_path / "pin.tif", lambda x, y: z(x, y, 1.5), lay, nodata=-9999.0)
    g = T.ground_under(lay, T.TerrainConfig(dem=pin, void_fill_radius_m=0.0))
    assert g.grid.voids.unknown_px >= 1
    w = next(w for w in g.warnings if w.code == "terrain_no_ground")
    assert f"photos {ph['photo'][MID]}" in w.message and "1 on nodata" in w.message
    inp = uav_inputs(H)
    r = TC.uav_terrain(lay, g, inp, plan_uav(inp))
    out = r.layout.photos
    bad = np.isnan(out["ground_m"])
    assert out["agl_m"][bad][0] == pytest.approx(out["altitude_m"][bad][0] - g.low_m)


def test_a_dem_that_misses_part_of_the_area_is_refused_saying_how_much(tmp_path):
    lay = layout(H)
    x0, y0, x1, y1 = lay.area.geometry.bounds
    half = (x1 - x0) / 2
    p = write_dem(tmp_path / "half.tif", lambda x, y: np.full_like(x, 100.0), left=x0 - 50,
                  top=y1 + 50, cell=2.0, width=int((half + 50) / 2),
                  height=int((y1 - y0 + 100) / 2))
    with pytest.raises(InputError) as e:
        T.ground_under(lay, T.TerrainConfig(dem=p))
    assert e.value.field == "terrain.dem"
    assert "does not cover the area" in e.value.message and "km²" in e.value.message
    assert "50" in e.value.message.split("(")[1]  # about half of it, in %


def test_centimetre_elevations_are_refused_unless_stated(tmp_path):
    lay = layout(H)
    p = dem_around(tmp_path / "cm.tif", lambda x, y: np.full_like(x, 21250.0), lay)
    with pytest.raises(InputError, match="centimetres"):
        T.ground_under(lay, T.TerrainConfig(dem=p))
    g = T.ground_under(lay, T.TerrainConfig(dem=p, vertical_unit="cm"))
    np.testing.assert_allclose(g.centre_m, 212.5, rtol=1e-6)


def test_feet_from_the_band_unit_and_a_feet_crs_warning(tmp_path):
    lay = layout(H)
    p = dem_around(tmp_path / "ft.tif", lambda x, y: np.full_like(x, 1000.0), lay, units="ft")
    g = T.ground_under(lay, T.TerrainConfig(dem=p))
    np.testing.assert_allclose(g.centre_m, 304.8, rtol=1e-6)
    # a DEM in a US state-plane CRS (feet): its heights are probably feet too
    p2 = dem_around(tmp_path / "m.tif", lambda x, y: np.full_like(x, 1000.0), lay)
    ny = D.DemInfo(p2, "", False, 1, 1, (1, 1), (0, 0, 1, 1), None, "", "US survey foot")
    assert D.unit_problem(np.array([10.0]), ny, "default") == "ft"
    assert D.unit_problem(np.array([10.0]), ny, "project") is None  # the unit was stated


def test_a_corrupt_tiff_is_an_input_error(tmp_path):
    p = tmp_path / "bad.tif"
    p.write_bytes(b"II*\x00" + b"\x00garbage" * 100)
    with pytest.raises(InputError) as e:
        T.ground_under(layout(H), T.TerrainConfig(dem=p))
    assert "not a readable GeoTIFF" in e.value.message and e.value.field == "terrain.dem"
    with pytest.raises(InputError, match="no such file"):
        T.ground_under(layout(H), T.TerrainConfig(dem=tmp_path / "none.tif"))


def test_a_huge_header_is_refused_without_reading(tmp_path):
    import rasterio
    from rasterio.transform import from_origin
    p = tmp_path / "huge.tif"
    with rasterio.open(p, "w", driver="GTiff", width=D.MAX_DIMENSION_PX + 1, height=1,
                       count=1, dtype="uint8", crs=PLAN_CRS,
                       transform=from_origin(X0, Y0, 1, 1), tiled=True, sparse_ok=True):
        pass
    with pytest.raises(InputError, match="more than"):
        D.open_dem(p)


def test_a_dem_without_crs_is_refused(tmp_path):
    p = write_dem(tmp_path / "nocrs.tif", lambda x, y: x * 0, left=0, top=10, cell=1,
                  width=10, height=10, crs=None)
    with pytest.raises(InputError, match="coordinate reference system"):
        D.open_dem(p)


def test_reads_stay_within_the_tile_bound(tmp_path, monkeypatch):
    """A tile smaller than the DEM: the same values read in several windows."""
    lay = layout(H)
    p = dem_around(tmp_path / "tilt.tif", lambda x, y: 100 + 0.05 * (x - X0), lay,
                   dtype="float64")
    whole = T.ground_under(lay, T.TerrainConfig(dem=p)).centre_m
    monkeypatch.setattr(D, "TILE_PX", 64)
    tiled = T.ground_under(lay, T.TerrainConfig(dem=p)).centre_m
    np.testing.assert_allclose(tiled, whole, atol=1e-9)
    monkeypatch.setattr(D, "MAX_READ_PX", 1000)
    with pytest.raises(InputError, match="coarser grid"):
        T.ground_under(lay, T.TerrainConfig(dem=p))


# --- another CRS, a geographic DEM -----------------------------------------------------------

def test_a_dem_in_web_mercator_is_sampled_at_the_reprojected_centres(tmp_path):
    from pyproj import Transformer
    lay = layout(H)
    to = Transformer.from_crs(PLAN_CRS, "EPSG:3857", always_xy=True)
    mx, my = to.transform(lay.photos["x_m"], lay.photos["y_m"])
    mx0, my0 = float(np.min(mx)), float(np.min(my))

    def z(x, y):
        return 100.0 + 0.02 * (x - mx0) + 0.01 * (y - my0)

    p = write_dem(tmp_path / "merc.tif", z, left=mx0 - 2000, top=float(np.max(my)) + 2000,
                  cell=4.0, width=int((np.ptp(mx) + 4000) / 4), height=int((np.ptp(my) + 4000) / 4),
                  crs="EPSG:3857", dtype="float64")
    r, *_ = run(lay, p)
    np.testing.assert_allclose(r.layout.photos["ground_m"], z(mx, my), atol=1e-6)


def test_a_geographic_dem_is_handled_by_projecting_the_points(tmp_path):
    from pyproj import Transformer
    lay = layout(H)
    to = Transformer.from_crs(PLAN_CRS, "EPSG:4326", always_xy=True)
    lon, lat = to.transform(lay.photos["x_m"], lay.photos["y_m"])
    lon0, lat0 = float(np.min(lon)), float(np.min(lat))

    def z(x, y):  # 1 m per 0.0001° of longitude, 2 m per 0.0001° of latitude
        return 150.0 + 10_000 * (x - lon0) + 20_000 * (y - lat0)

    cell = 1 / 3600  # 1″
    p = write_dem(tmp_path / "geo.tif", z, left=lon0 - 0.02, top=float(np.max(lat)) + 0.02,
                  cell=cell, width=int((np.ptp(lon) + 0.04) / cell),
                  height=int((np.ptp(lat) + 0.04) / cell), crs="EPSG:4326", dtype="float64")
    r, *_ = run(lay, p)
    np.testing.assert_allclose(r.layout.photos["ground_m"], z(np.asarray(lon), np.asarray(lat)),
                               atol=1e-5)
    w = next(w for w in r.warnings if w.code == "terrain_geographic")
    assert w.severity == "info" and "1.00″" in w.message


# --- film: the local photo scale ---------------------------------------------------------------

def test_film_local_scale_and_the_binding_frame(tmp_path):
    from scanplan.norms import load_norm_set
    rules = load_norm_set("gkinp-02-036-02").rules()
    f_mm, mc = 153.0, 10000.0
    h = mc * f_mm / 1000.0  # 1530 m
    lay = layout(h, strips=3, per_strip=5, forward_pct=60, side_pct=30)
    p = dem_around(tmp_path / "tilt.tif", lambda x, y: 100 + 0.1 * (x - X0), lay,
                   cell=20.0, dtype="float64")
    g = T.ground_under(lay, T.TerrainConfig(dem=p))
    ft = TC.film_terrain(lay, g, rules, map_scale=2000, photo_scale=mc, relief_interval_m=1.0,
                        focal_mm=f_mm, frame_along_mm=230, forward_overlap_pct=60,
                        resolving_power_lpmm=40, object_size_m=0.2, shape_coefficient=0.97)
    gx = 100 + 0.1 * (lay.photos["x_m"] - X0)
    expect = (gx.max() + h - gx) / (f_mm / 1000)
    # the layout states no footprint: the centre's bilinear support (one 20 m cell each
    # way) and the path; conservative by at most two cells of the 0.1 slope each way
    assert np.all(ft.mc >= expect - 1e-6)
    assert np.all(ft.mc <= expect + 2 * 0.1 * 2 * 20.0 / (f_mm / 1000))
    assert ft.mc_min == pytest.approx(mc)
    assert ft.binding_frame == int(lay.photos["photo"][np.argmin(gx)])
    from scanplan.rules.film import evaluate
    ev = evaluate(rules, map_scale=2000, photo_scale=ft.mc_max, relief_interval_m=1.0,
                  focal_mm=f_mm, frame_along_mm=230, forward_overlap_pct=60,
                  resolving_power_lpmm=40, object_size_m=0.2, shape_coefficient=0.97)
    assert ft.scan_pixel_um == pytest.approx(float(ev.scan_pixel_um))
    assert ft.scan_pixel_um < ft.scan_pixel_planned_um
    w = next(w for w in ft.warnings if w.code == "terrain_film_scale")
    assert f"frame {ft.binding_frame}" in w.message and w.severity == "info"


def test_config_checks_name_the_key():
    with pytest.raises(InputError) as e:
        T.TerrainConfig(ground_range_m=(10.0, 5.0))
    assert e.value.field == "terrain.ground_elevation_m"
    with pytest.raises(InputError, match="altitude_mode"):
        T.TerrainConfig(ground_range_m=(0.0, 1.0), altitude_mode="agl")
    with pytest.raises(InputError, match="vertical_unit"):
        T.TerrainConfig(ground_range_m=(0.0, 1.0), vertical_unit="yards")


def test_follow_mode_waypoints_step_with_the_ground(tmp_path):
    lay = layout(H, strips=2, per_strip=12)
    p = dem_around(tmp_path / "tilt.tif", lambda x, y: 100 + 0.5 * (y - Y0), lay,
                   dtype="float64")
    r, *_ = run(lay, p, mode="follow", tol_m=4.0)
    ph = r.layout.photos
    assert r.path["clearance_min_m"] >= H - 1e-3
    reach = 0.5 * (GRID_REACH_M + lay.base_m)  # a step reaches half a base further
    assert np.all((ph["altitude_m"] - ph["ground_m"] >= H - 1e-3)
                  & (ph["altitude_m"] - ph["ground_m"] <= H + 4.0 + reach))
    steps = {(w["strip"], w["altitude_m"]) for w in r.waypoints}
    assert len(steps) > 2  # the altitude steps along the slope
    assert r.layout.notes["altitude_frame"] == "AMSL"
    assert all(s.altitude_m is None for s in r.layout.strips)



def test_a_layout_without_photos_gives_an_empty_result(tmp_path):
    from dataclasses import replace

    from scanplan.geo.layout import Photos
    lay = layout(H)
    p = dem_around(tmp_path / "flat.tif", lambda x, y: np.full_like(x, 100.0), lay)
    empty = replace(lay, photos=Photos({k: v[:0] for k, v in lay.photos.columns.items()}),
                    strips=())
    r, *_ = run(empty, p)
    assert len(r.layout.photos) == 0 and r.strips == () and r.warnings == ()
    assert r.summary()["agl_max_m"] is None

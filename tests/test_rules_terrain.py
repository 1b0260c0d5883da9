"""rules/terrain.py: the constraint records evaluated at every photo's own height.

The ground each photo is checked at follows each limit record's ``compares``; a constraint
registered once binds the worst photo of a UAV block over a DEM and the worst frame of a
film block, with no terrain code naming it.
"""

from __future__ import annotations

import sys
from pathlib import Path
from types import SimpleNamespace

import numpy as np
import pytest

sys.path.insert(0, str(Path(__file__).parent))

from terrain_helpers import FOCAL_MM, PIXEL_UM, X0, dem_around, layout, uav_inputs
from test_rules_registry import DUMMY_GROUND_M, dummy  # noqa: F401  (the fixture)

from scanplan.core.photoscale import ground_pixel_m, height_for_ground_pixel_m
from scanplan.geo import terrain as T
from scanplan.norms import load_norm_set
from scanplan.project import terraincheck as TC
from scanplan.rules import terrain as RT
from scanplan.rules.uav import plan_uav

H = 100.0


def _plan(**limits: float) -> SimpleNamespace:
    """A plan whose limits are ``compares=max planned height`` pairs."""
    recs = tuple(SimpleNamespace(compares=k, max_height_m=v) for k, v in limits.items())
    return SimpleNamespace(limits=recs, max_height_m=min(limits.values()) if limits else None)


def test_without_a_ceiling_every_photo_is_checked_over_its_footprint():
    f_lo, p_lo = np.array([10.0, 20.0]), np.array([0.0, 5.0])
    np.testing.assert_array_equal(RT.checked_ground_m(_plan(GSD=200.0), f_lo, p_lo), f_lo)


def test_a_ceiling_is_checked_over_the_path():
    """L_r = 200 (GSD) and L_c = 150 (ceiling): L = 150, g_eff = min(g_f + 50, g_p + 0)."""
    f_lo, p_lo = np.array([10.0, 20.0, 100.0]), np.array([0.0, 90.0, 100.0])
    got = RT.checked_ground_m(_plan(GSD=200.0, H=150.0), f_lo, p_lo)
    np.testing.assert_array_equal(got, [0.0, 70.0, 100.0])
    # the altitude A = g_eff + L meets both: A − g_f ≤ 200 and A − g_p ≤ 150
    alt = got + 150.0
    assert np.all(alt - f_lo <= 200.0) and np.all(alt - p_lo <= 150.0)


def test_photo_figures_are_the_core_formula_at_each_height():
    agl = np.array([80.0, 100.0, 140.0])
    fig = RT.photo_figures(uav_inputs(H), agl)
    np.testing.assert_array_equal(fig["gsd_cm"], ground_pixel_m(PIXEL_UM, agl, FOCAL_MM) * 100)
    assert fig["gsd_cm"][2] == pytest.approx(PIXEL_UM / 1000 * 140.0 / FOCAL_MM * 100)
    assert np.all(np.diff(fig["resolution_cm"]) > 0)  # L grows with the height


def test_a_registered_constraint_binds_the_worst_uav_photo(tmp_path, dummy):  # noqa: F811
    """A plane rising 5 m per 100 m: the dummy's 1 cm GSD limit binds, and the worst photo
    (over the lowest ground) keeps the block below it by the relief under the block."""
    lay = layout(H)
    inp = uav_inputs(H)
    plan = plan_uav(inp)
    assert plan.binding == "QX"
    limit_m = float(height_for_ground_pixel_m(DUMMY_GROUND_M, PIXEL_UM, FOCAL_MM))
    assert plan.max_height_m == pytest.approx(limit_m)
    dem = dem_around(tmp_path / "plane.tif", lambda x, y: 150.0 + 0.05 * (x - X0), lay)
    res = TC.uav_terrain(lay, T.ground_under(lay, T.TerrainConfig(dem=dem)), inp, plan)
    assert res.binding == "QX"
    ph = res.layout.photos
    relief = float(ph["altitude_m"].max() - ph["ground_min_m"].min())
    assert res.max_height_m == pytest.approx(limit_m - (relief - H), abs=1e-6)
    assert res.max_height_m < limit_m - 0.05 * (lay.photos["x_m"].max() - X0) + 1e-6


def test_a_registered_constraint_binds_the_worst_film_frame(dummy):  # noqa: F811
    rules = load_norm_set().rules()
    wf = RT.film_at_worst_frame(rules, photo_scale=10000.0, worst_scale=12500.0,
                                map_scale=2000, relief_interval_m=0.5, focal_mm=153.0,
                                frame_along_mm=230.0, forward_overlap_pct=60.0,
                                resolving_power_lpmm=40.0, object_size_m=0.2,
                                shape_coefficient=0.97)
    assert wf.binding == wf.binding_planned == "QX"
    assert wf.scan_pixel_um == pytest.approx(DUMMY_GROUND_M * 1e6 / 12500.0)
    assert wf.scan_pixel_planned_um == pytest.approx(DUMMY_GROUND_M * 1e6 / 10000.0)
    note = RT.film_scale_warning(wf.scan_pixel_um, wf.scan_pixel_planned_um, wf.binding,
                                 10000.0, 12500.0, "frame 1")
    assert note is not None and note.code == "terrain_film_scale"
    assert RT.film_scale_warning(1.0, 1.0, "QX", 10000.0, 10000.0, "frame 1") is None

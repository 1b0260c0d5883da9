"""The terrain check's fast paths give what the plain computation gives, value for value.

A plan over a DEM asks the ground under thousands of footprints and path stretches, and
samples the DEM many times, for every layout it compares. The fast paths checked here
against the straightforward loops they replaced (which are written out in the tests):
the range tables of a pyramid level, the direct gather of a few boxes, the follow mode's
runs, the side neighbours of each photo, and a small DEM read once and kept.
"""

from __future__ import annotations

import math
import sys
import time
from pathlib import Path

import numpy as np
import pytest

sys.path.insert(0, str(Path(__file__).parent))

from terrain_helpers import dem_around, layout

from scanplan.errors import InputError
from scanplan.geo import dem as D
from scanplan.geo import dem_grid as G
from scanplan.geo import terrain as T
from scanplan.geo import terrain_overlaps as TO


def _brute_range(z, bi0, bi1, bj0, bj1):
    """min/max over each box, NaN when it holds an unknown block (the plain loop)."""
    lo, hi = [], []
    for i0, i1, j0, j1 in zip(bi0, bi1, bj0, bj1, strict=True):
        block = z[j0:j1 + 1, i0:i1 + 1]
        if np.isnan(block).any():
            lo.append(np.nan)
            hi.append(np.nan)
        else:
            lo.append(float(block.min()))
            hi.append(float(block.max()))
    return np.array(lo), np.array(hi)


@pytest.mark.parametrize("seed", range(6))
def test_range_tables_and_gathers_give_each_box_its_extremes(seed):
    rng = np.random.default_rng(seed)
    h, w = int(rng.integers(1, 90)), int(rng.integers(1, 90))
    z = rng.normal(100.0, 20.0, (h, w)).astype(np.float32)
    if seed % 2:
        z[rng.random((h, w)) < 0.02] = np.nan
    n = 400
    bi0, bj0 = rng.integers(0, w, n), rng.integers(0, h, n)
    bi1 = np.minimum(bi0 + rng.integers(0, 2 * G.BLOCKS_PER_SIDE - 1, n), w - 1)
    bj1 = np.minimum(bj0 + rng.integers(0, 2 * G.BLOCKS_PER_SIDE - 1, n), h - 1)
    want = _brute_range(z, bi0, bi1, bj0, bj1)
    tables = G._tables_range(*G._tables(z, z), bi0, bi1, bj0, bj1)
    blocks = G._blocks_range(z, z, bi0, bi1, bj0, bj1)
    for got in (tables, blocks):
        np.testing.assert_array_equal(got[0], want[0])
        np.testing.assert_array_equal(got[1], want[1])


def _runs_loop(g, strip, tol):
    """The follow mode's runs as first written: numpy scalars, max/min."""
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


@pytest.mark.parametrize("seed", range(5))
def test_follow_runs_split_where_the_ground_spans_more_than_the_tolerance(seed):
    rng = np.random.default_rng(seed)
    n = 500
    g = np.round(rng.normal(150.0, 4.0, n), 1)
    if seed % 2:
        g[rng.random(n) < 0.05] = np.nan  # unknown ground: the run goes on, as before
    strip = np.sort(rng.integers(0, 7, n))
    tol = float(rng.uniform(0.5, 8.0))
    np.testing.assert_array_equal(T._follow_runs(g, strip, tol), _runs_loop(g, strip, tol))
    again = T._follow_runs(g.copy(), strip.copy(), tol)  # asked again: kept, read-only
    assert again is T._follow_runs(g, strip, tol) and not again.flags.writeable
    np.testing.assert_array_equal(T._greedy_runs(g, strip, tol), again)


def test_each_photo_pairs_with_the_nearest_photo_of_the_next_strip():
    rng = np.random.default_rng(3)
    x = np.concatenate([np.full(9, 0.0), np.full(1, 40.0), np.full(12, 80.0)])
    y = np.concatenate([np.sort(rng.uniform(0, 300, 9)), [150.0],
                        np.sort(rng.uniform(0, 300, 12))])
    strip = np.repeat([0, 1, 2], [9, 1, 12])
    pairs = TO._side_pairs(x, y, strip, np.array([0.0, 1.0]), np.array([1.0, 0.0]))
    want_a, want_b = [], []
    for k0, k1 in ((0, 1), (1, 2)):
        i1 = np.flatnonzero(strip == k1)
        for i in np.flatnonzero(strip == k0):
            d = np.abs(y[i1] - y[i])
            want_a.append(i)
            want_b.append(i1[np.flatnonzero(d == d.min())[0]])
    np.testing.assert_array_equal(pairs.a, want_a)
    np.testing.assert_array_equal(pairs.b, want_b)
    np.testing.assert_allclose(pairs.distance_m, 40.0)


def test_a_small_dem_is_read_once_and_again_when_rewritten(tmp_path, monkeypatch):
    lay = layout()
    path = dem_around(tmp_path / "dem.tif", lambda x, y: 100.0 + 0.01 * x, lay)
    info = D.open_dem(path)
    assert info.width_px * info.height_px <= D.WHOLE_MAX_PX
    xs, ys = lay.photos["x_m"][:50], lay.photos["y_m"][:50]
    first = D.sample_dem(info, xs, ys, lay.area.plan_crs).elevation_m
    reads: list[int] = []
    real = D._whole

    def counted(i):
        reads.append(1)
        return real(i)

    monkeypatch.setattr(D, "_whole", counted)
    again = D.sample_dem(info, xs, ys, lay.area.plan_crs).elevation_m
    np.testing.assert_array_equal(again, first)
    assert len(D._WHOLE) >= 1 and reads == [1]
    monkeypatch.setattr(D, "WHOLE_MAX_PX", 0)  # read in windows: the same values
    windowed = D.sample_dem(info, xs, ys, lay.area.plan_crs).elevation_m
    np.testing.assert_array_equal(windowed, first)
    monkeypatch.undo()
    time.sleep(0.01)
    dem_around(path, lambda x, y: 50.0 + 0 * x, lay)  # the same name, new heights
    info = D.open_dem(path)
    rewritten = D.sample_dem(info, xs, ys, lay.area.plan_crs).elevation_m
    np.testing.assert_allclose(rewritten, 50.0)


def test_an_accepted_dem_header_is_kept_until_the_file_or_a_companion_changes(tmp_path):
    lay = layout()
    path = dem_around(tmp_path / "dem.tif", lambda x, y: 100.0 + 0 * x, lay)
    first = D.open_dem(path)
    assert D.open_dem(path) is first  # each layout of a plan opens it: read once
    time.sleep(0.01)
    dem_around(path, lambda x, y: 100.0 + 0 * x, lay, cell=4.0)  # rewritten: 4 m cells
    again = D.open_dem(path)
    assert again is not first and again.cell_size == (4.0, 4.0)
    (tmp_path / "dem.tif.ovr").write_text("not a TIFF")  # a companion GDAL would open
    with pytest.raises(InputError, match="ovr"):
        D.open_dem(path)


def test_the_path_ground_kept_is_the_one_computed_over_its_own_grid(tmp_path):
    """The ground under the path is kept with its grid, by photos and run-in: the same
    inputs give the very result (read-only) equal to a fresh computation; another grid over
    other ground, or other photos, their own; a grid copied or pickled keeps nothing."""
    import copy
    import pickle

    from scanplan.geo.terrain_worst import path_ground

    lay = layout()
    ph = lay.photos
    x, y = ph["x_m"].astype(float), ph["y_m"].astype(float)
    strip = ph["strip"].astype(np.int64)
    grids = []
    for name, base in (("a.tif", 100.0), ("b.tif", 300.0)):
        info = D.open_dem(dem_around(tmp_path / name, lambda x, y, b=base: b + 0.01 * x, lay))
        grids.append(G.read_ground_grid(info, lay.area.geometry.bounds, lay.area.geometry,
                                        lay.area.plan_crs))
    grids[0].kept.clear()
    grids[1].kept.clear()
    args = (x, y, strip, 0.0, 20.0, 50.0, 400.0)
    kept = T._kept_path_ground(grids[0], *args)
    assert T._kept_path_ground(grids[0], *args) is kept and len(grids[0].kept) == 1
    fresh = path_ground(grids[0], *args)
    for a, b in ((kept.low_m, fresh.low_m), (kept.high_m, fresh.high_m),
                 (kept.known, fresh.known)):
        np.testing.assert_array_equal(a, b)
        assert not a.flags.writeable
    other = T._kept_path_ground(grids[1], *args)
    np.testing.assert_array_equal(other.low_m, path_ground(grids[1], *args).low_m)
    assert np.all(other.low_m > kept.low_m + 150.0) and len(grids[1].kept) == 1
    moved = T._kept_path_ground(grids[0], x + 10.0, *args[1:])
    assert moved is not kept and len(grids[0].kept) == 2
    for twin in (copy.deepcopy(grids[0]), pickle.loads(pickle.dumps(grids[0]))):
        assert len(twin.kept) == 0 and twin.kept.size == grids[0].kept.size
        again = T._kept_path_ground(twin, *args)
        np.testing.assert_array_equal(again.high_m, kept.high_m)
    no_dem = T._kept_path_ground(None, *args)
    assert not no_dem.known.any() and np.all(no_dem.low_m == 50.0)

"""The MTF ground resolution solved once per camera chain (scanplan.rules.resolution): the
values looked up are the values a new solve gives, bit for bit; the maximum height for a
limit on L is the one the pass-by-pass search gave, with one or two solves; a change of the
chain (an input, a registered component) is another chain."""

from __future__ import annotations

import numpy as np
import pytest

import scanplan.core.mtf as M
from scanplan.project.jobs import uav_job
from scanplan.rules import resolution as R

CASES = [  # (camera, f-number, speed, exposure): the catalogue's UAV and aircraft cameras
    ("canon-eos-5d-mark-ii-50", 8.0, 25.0, 1e-3),
    ("dji-zenmuse-p1-35", 5.6, 12.0, 1 / 1000),
    ("dji-mavic-3e", 2.8, 10.0, 1 / 2000),
]


def _inputs(camera: str, f_number: float, speed: float, exposure: float):
    return uav_job(camera=camera, f_number=f_number, speed_ms=speed, exposure_s=exposure,
                   height_m=100.0).plan.inputs


def _direct(inp, heights, field="centre"):
    return M.ground_resolution(*R.chain(inp, np.asarray(heights, dtype=float)), field=field)


def _search_as_it_was(inp, limit_m):
    """The search before: every pass solved on its own, centre and corner together."""
    def ok(h):
        lr = np.asarray(M.uav_resolution(*R.chain(inp, h)).centre.ground_resolution_m)
        return np.isfinite(lr) & (lr <= limit_m)

    grid = np.geomspace(1.0, 20_000.0, 257)
    fails = np.flatnonzero(~ok(grid))
    if fails.size == 0:
        return 20_000.0
    if fails[0] == 0:
        return 0.0
    lo, hi = float(grid[fails[0] - 1]), float(grid[fails[0]])
    while hi - lo >= 1e-3:
        inner = np.linspace(lo, hi, 64)[1:-1]
        fails = np.flatnonzero(~ok(inner))
        if fails.size == 0:
            lo = float(inner[-1])
        else:
            hi = float(inner[fails[0]])
            if fails[0] > 0:
                lo = float(inner[fails[0] - 1])
    return lo


@pytest.fixture
def solves(monkeypatch):
    """Counts the vectorised solves (and the heights in each)."""
    calls: list[int] = []
    real = R._solve

    def counted(inp, heights, field):
        calls.append(len(heights))
        return real(inp, heights, field)

    monkeypatch.setattr(R, "_solve", counted)
    R._MEMO.clear()
    R._MAX_HEIGHTS.clear()
    return calls


@pytest.mark.parametrize("case", CASES)
def test_looked_up_values_are_the_solved_values(case, solves):
    inp = _inputs(*case)
    rng = np.random.default_rng(4)
    heights = rng.uniform(5.0, 3000.0, 300)
    for field in ("centre", "corner"):
        ref = _direct(inp, heights, field)
        for _ in range(6):  # asked in pieces of every size, in any order, with repeats
            pick = rng.choice(heights, int(rng.integers(1, 80)))
            got = R.resolution_at(inp, pick, field)
            idx = np.searchsorted(np.sort(heights), pick)
            order = np.argsort(heights)[idx]
            assert np.array_equal(got["ground_resolution_m"],
                                  ref.ground_resolution_m[order], equal_nan=True)
            assert np.array_equal(got["r_lpmm"], ref.r_lpmm[order], equal_nan=True)
            assert np.array_equal(got["l_over_gsd"], ref.l_over_gsd[order], equal_nan=True)
            assert np.array_equal(got["resolvable"], ref.resolvable[order])
            assert np.array_equal(got["sensor_limited"],
                                  ref.resolving_power.sensor_limited[order])
    assert sum(solves) <= 2 * len(heights)  # each height solved at most once per field


@pytest.mark.parametrize("case", CASES)
def test_the_maximum_height_is_the_pass_by_pass_search(case, solves):
    inp = _inputs(*case)
    l_1m = float(_direct(inp, [1.0]).ground_resolution_m[0])
    for limit in (0.5 * l_1m, 0.01, 0.03, 0.05, 0.1, 0.27, 5.0):
        before = len(solves)
        got = R.max_height_for_ground_resolution(inp, limit)
        assert got == _search_as_it_was(inp, limit), limit
        assert len(solves) - before <= 3  # the grid (once per chain) and one or two more
        again = len(solves)
        assert R.max_height_for_ground_resolution(inp, limit) == got
        assert len(solves) == again  # kept: no solve
    assert R.max_height_for_ground_resolution(inp, 0.5 * l_1m) == 0.0


def test_another_chain_is_solved_again(solves):
    inp, fast = _inputs(*CASES[0]), _inputs(CASES[0][0], 8.0, 40.0, 1e-3)
    solves.clear()
    R._MEMO.clear()
    a = R.centre_resolution_m(inp, [150.0])
    slower = R.centre_resolution_m(fast, [150.0])
    assert len(solves) == 2 and slower[0] > a[0]  # more motion blur: a coarser L
    assert R.centre_resolution_m(inp, [150.0]) == a and len(solves) == 2


def test_a_registered_component_is_another_chain(solves):
    inp = _inputs(*CASES[0])
    before = R.centre_resolution_m(inp, [150.0])[0]
    M.register(M.Component("dummy", "atmosphere",
                           lambda s: M.Term(lambda n, c: c, {"c": np.full(np.shape(
                               s.pixel_um), 0.8)}),
                           {"en": "Test factor", "ru": "Тестовый множитель"}, "a test"))
    try:
        with_dummy = R.centre_resolution_m(inp, [150.0])[0]
    finally:
        M.unregister("dummy")
    assert with_dummy > before  # less contrast: a coarser L
    assert R.centre_resolution_m(inp, [150.0])[0] == before

"""What a re-plan asks again is answered from memory, with the very values computed.

The page re-plans a project on every edit; an edit that moves neither the dates nor the
site asks the same sun windows, and one that leaves the layout over the ground alone asks
the resolving power at the same photos' heights. Both are kept per process; these tests
check the second answer is the first one and that nothing was computed again. The plans
solved only to choose one leave out the curves for plots, which the plan chosen gets later:
the same curves.
"""

from __future__ import annotations

import datetime as dt
import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).parent))

from terrain_helpers import uav_inputs

from scanplan.geo import sun as S
from scanplan.rules import resolution as R


def test_sun_windows_are_computed_once_per_site_and_dates(monkeypatch):
    dates = [dt.date(2025, 5, 1) + dt.timedelta(days=i) for i in range(5)]
    calls: list[int] = []
    real = S.sun_elevation_deg
    monkeypatch.setattr(S, "sun_elevation_deg", lambda *a: calls.append(1) or real(*a))
    S._sun_windows.cache_clear()
    first = S.sun_windows(dates, 56.34, 37.52, 20.0, time_zone="Europe/Moscow")
    again = S.sun_windows(list(dates), 56.34, 37.52, 20.0, time_zone="Europe/Moscow")
    assert again == first and len(calls) == 1
    other = S.sun_windows(dates, 56.34, 37.52, 25.0, time_zone="Europe/Moscow")
    assert len(calls) == 2 and other[0].hours < first[0].hours  # a higher sun: a new answer


def test_every_photos_heights_are_solved_once_and_given_back_unchanged(monkeypatch):
    inp = uav_inputs()
    heights = np.linspace(80.0, 130.0, R._MEMO_BATCH + 500)  # a terrain plan's photos
    solves: list[int] = []
    real = R._solve
    monkeypatch.setattr(R, "_solve", lambda *a: solves.append(1) or real(*a))
    first = R.resolution_at(inp, heights)
    first["ground_resolution_m"][:] = -1.0  # a caller's own array: the memory is not touched
    again = R.resolution_at(inp, heights.copy())
    assert len(solves) == 1
    direct = R.resolution_at(inp, heights[:10])  # the plain path, height by height
    np.testing.assert_array_equal(again["ground_resolution_m"][:10],
                                  direct["ground_resolution_m"])
    R.resolution_at(inp, heights + 0.5)  # other heights: solved
    assert len(solves) == 3


def test_a_plan_solved_without_its_curves_gets_the_very_curves_later():
    """The plans solved to choose a UAV plan leave out the curves for plots; the plan chosen
    gets them afterwards (``with_curves``): equal to the plan solved with them, over relief
    too, and a plan that has them is given back as it is."""
    from scanplan.project.jobs import uav_job
    from scanplan.rules.uav import with_curves

    for kw in ({"map_scale": 2000, "relief_interval_m": 0.5},
               {"map_scale": 2000, "relief_interval_m": 0.5, "flown_band_m": (80.0, 140.0)},
               {"height_m": 120.0}):
        args = dict(camera="dji-phantom-4-rtk", **{"height_m": None, **kw})
        whole = uav_job(**args).plan
        bare = uav_job(**args, curves=False).plan
        assert not bare.height_curve and not bare.mtf_centre
        assert whole.height_curve and whole.mtf_centre
        assert with_curves(bare) == whole
        assert with_curves(whole) is whole


def test_the_curves_kept_are_each_plan_s_own_lists():
    """The curves are kept by the plan's inputs and heights: a re-plan gets equal curves in
    lists of its own (a caller changing one plan's curve changes no other), and another
    camera or height its own curves."""
    from scanplan.project.jobs import uav_job
    from scanplan.rules import uav as U

    U._CURVES.clear()
    a = uav_job(camera="dji-phantom-4-rtk", height_m=120.0).plan
    b = uav_job(camera="dji-phantom-4-rtk", height_m=120.0).plan
    assert a.height_curve == b.height_curve and a.mtf_centre == b.mtf_centre
    assert len(U._CURVES) == 1
    a.height_curve["gsd_m"][0] = -1.0
    a.mtf_centre["system"].clear()
    c = uav_job(camera="dji-phantom-4-rtk", height_m=120.0).plan
    assert c.height_curve == b.height_curve and c.mtf_centre == b.mtf_centre
    assert c.height_curve["gsd_m"][0] > 0 and c.mtf_centre["system"]
    U._CURVES.clear()
    assert uav_job(camera="dji-phantom-4-rtk", height_m=120.0).plan.mtf_centre == \
        b.mtf_centre  # made again: the same curves
    higher = uav_job(camera="dji-phantom-4-rtk", height_m=150.0).plan
    other = uav_job(camera="dji-zenmuse-p1-35", height_m=120.0).plan
    assert higher.height_curve != b.height_curve and other.mtf_centre != b.mtf_centre

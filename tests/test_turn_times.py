"""The turns of a layout timed together (scanplan.geo.sorties.paths_time_s, used by
turn_penalties_m) give each turn the time the one-path function gives it, bit for bit; and
the limits of a job at one height, solved once, serve every direction's job at it."""

from __future__ import annotations

import numpy as np
import pytest

from scanplan.geo.mission import _with_trigger_off, turn_path
from scanplan.geo.sorties import FlightModel, path_time_s, paths_time_s, turn_penalties_m

MODEL = FlightModel(2.5, 5.0, 2.0, 2.5, 1.5)


def _paths(rng: np.random.Generator) -> list[np.ndarray]:
    out = [rng.uniform(-400, 400, (int(rng.integers(2, 25)), 2)) for _ in range(30)]
    out.append(np.array([[0.0, 0.0], [0.0, 0.0], [10.0, 0.0]]))  # a repeated point
    out.append(np.array([[0.0, 0.0], [50.0, 0.0], [100.0, 0.0]]))  # straight on
    out.append(np.array([[0.0, 0.0], [50.0, 0.0], [0.0, 0.0]]))  # turned back
    return out


@pytest.mark.parametrize("seed", range(5))
def test_paths_together_equal_each_alone(seed):
    rng = np.random.default_rng(seed)
    paths = _paths(rng)
    speed, start, end = float(rng.uniform(3, 25)), float(rng.uniform(0, 9)), 4.0
    times, lengths = paths_time_s(paths, speed, MODEL, start_ms=start, end_ms=end)
    for p, t, length in zip(paths, times, lengths, strict=True):
        assert t == path_time_s(p, speed, MODEL, start_ms=start, end_ms=end)
        assert length == float(np.sum(np.hypot(*np.diff(p, axis=0).T)))


def test_paths_time_refuses_a_path_of_one_point():
    with pytest.raises(ValueError, match="two points"):
        paths_time_s([np.zeros((1, 2))], 10.0, MODEL)


def _penalties_turn_by_turn(ex, along, across, kind, lead, speed, off):
    """The turns' extra time as metres, each turn timed alone (the reference)."""
    run_up = speed ** 2 / (2.0 * MODEL.accel_ms2) + 1.0
    steps = np.zeros(len(ex))
    for k in np.flatnonzero(np.diff(ex)):
        s0, s1 = int(ex[k]), int(ex[k + 1])
        p = np.array([across[s0], along[k]])
        q = np.array([across[s1], along[k + 1]])
        h = np.array([0.0, 1.0 if s0 % 2 == 0 else -1.0])
        path = turn_path(p, h, q, lead, kind)
        mid = [(m.x_m, m.y_m) for m in _with_trigger_off(p, path, off, 0, 0)]  # as written
        poly = np.vstack([p - run_up * h, p, np.array(mid), np.array(path[-1:]),
                          q - run_up * h])
        length = float(np.sum(np.hypot(*np.diff(poly, axis=0).T)))
        t = path_time_s(poly, speed, MODEL, start_ms=speed, end_ms=speed)
        steps[k + 1] = max(0.0, t * speed - length)
    return np.cumsum(steps)


@pytest.mark.parametrize("kind", ["turnaround", "semicircle", "dubins"])
def test_turn_penalties_equal_each_turn_timed_alone(kind):
    rng = np.random.default_rng(11)
    costly = 0
    for _ in range(20):
        per = rng.integers(1, 6, int(rng.integers(2, 12)))
        ex = np.repeat(np.arange(len(per)), per)
        along = np.concatenate([np.sort(rng.uniform(-300, 300, c))[::1 if s % 2 == 0 else -1]
                                for s, c in enumerate(per)])
        across = np.cumsum(rng.uniform(5, 80, len(per)))
        lead, speed, off = (float(x) for x in rng.uniform([0, 3, 0], [60, 25, 40]))
        got = turn_penalties_m(ex, along, across, kind, lead, speed, MODEL, off)
        want = _penalties_turn_by_turn(ex, along, across, kind, lead, speed, off)
        assert np.array_equal(got, want)
        assert np.all(np.diff(got) >= 0)  # a turn never saves time
        costly += got[-1] > 0
    assert costly > 10  # most layouts' turns cost time beyond their length


def test_one_direction_s_limits_serve_another():
    from scanplan.geo.area import AreaSpec, load_area
    from scanplan.project.flightplan import LayoutOptions
    from scanplan.project.jobs import uav_job

    area = load_area(AreaSpec(polygon=((37.60, 55.70), (37.62, 55.70), (37.62, 55.71),
                                       (37.60, 55.71))))
    kw = dict(height_m=120.0, camera="dji-phantom-4-rtk", map_scale="1:2000",
              relief_interval_m=1.0, area=area)
    along = uav_job(**kw, layout_options=LayoutOptions(direction_deg=0.0))
    across = uav_job(**kw, layout_options=LayoutOptions(direction_deg=90.0),
                     limits=along.limits)
    alone = uav_job(**kw, layout_options=LayoutOptions(direction_deg=90.0))
    assert across.limits is along.limits
    assert across.plan == alone.plan and across.layout.n_photos == alone.layout.n_photos
    with pytest.raises(ValueError, match="other inputs"):
        uav_job(**{**kw, "height_m": 150.0}, limits=along.limits)

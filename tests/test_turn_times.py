"""The turns of a layout timed together (scanplan.geo.sorties.paths_time_s, used by
turn_penalties_m) give each turn the time the one-path function gives it, bit for bit; and
the limits of a job at one height, solved once, serve every direction's job at it."""

from __future__ import annotations

import math

import numpy as np
import pytest

from scanplan.geo.mission import _with_trigger_off, turn_path, turn_path_xy
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


def _turn_path_arrays(p, h, q, lead_m, kind):
    """The turn's waypoints written out with numpy 2-vectors and an arc's angles from
    np.linspace at each call: the plain form of ``turn_path``."""
    w = q - p
    off = float(w @ h)
    nv = w - off * h
    d = float(np.hypot(*nv))
    n = nv / d if d > 0 else np.array([h[1], -h[0]])
    apex_out = p + (max(0.0, off) + lead_m) * h
    apex_in = apex_out + d * n
    ox, oy, nx, ny, hx, hy = (float(v) for v in (*apex_out, *n, *h))

    def at(a, b):
        return ox + a * nx + b * hx, oy + a * ny + b * hy

    def arc(ca, cb, r, a0, a1):
        k = max(1, math.ceil(abs(math.degrees(a1 - a0)) / 20.0))
        return [at(ca + r * math.cos(t), cb + r * math.sin(t))
                for t in np.linspace(a0, a1, k + 1)[1:]]

    out = []
    if float(np.hypot(*(apex_out - p))) > 1e-6:
        out.append(at(0.0, 0.0))
    if kind == "turnaround" or d == 0:
        out.append(at(d, 0.0))
    elif kind == "semicircle":
        out += arc(d / 2.0, 0.0, d / 2.0, math.pi, 0.0)
    else:
        r = lead_m
        if d >= 2.0 * r:
            out += arc(r, 0.0, r, math.pi, math.pi / 2.0) + arc(d - r, 0.0, r, math.pi / 2.0, 0.0)
        else:
            beta = math.acos((d / 2.0 + r) / (2.0 * r))
            y = 2.0 * r * math.sin(beta)
            out += arc(-r, 0.0, r, 0.0, beta) + arc(d / 2.0, y, r, math.pi + beta, -beta) \
                + arc(d + r, 0.0, r, math.pi - beta, math.pi)
    if float(np.hypot(*(q - apex_in))) > 1e-6:
        out.append((float(q[0]), float(q[1])))
    else:
        out[-1] = (float(q[0]), float(q[1]))
    return out


@pytest.mark.parametrize("kind", ["semicircle", "turnaround", "dubins"])
def test_turn_path_is_its_plain_form_to_the_last_bit(kind):
    """The turn's waypoints, computed on Python floats with each arc's steps kept, are the
    plain numpy form's bit for bit: any heading, the packing frame's ±north, a next strip
    straight ahead, no lead, a Dubins turn tighter than its radius."""
    rng = np.random.default_rng(7)
    for i in range(3000):
        p = rng.uniform(-5e5, 5e5, 2) if i % 3 else np.round(rng.uniform(-1e3, 1e3, 2), 1)
        a = rng.uniform(0, 2 * np.pi)
        h = np.array([math.sin(a), math.cos(a)]) if i % 2 else np.array([0.0, (-1.0) ** i])
        q = p + rng.normal(0, 80, 2) * (i % 11 != 0)
        lead = float(rng.choice([0.0, 5.0, 12.0, 150.0, rng.uniform(0, 200)]))
        got, want = turn_path(p, h, q, lead, kind), _turn_path_arrays(p, h, q, lead, kind)
        assert [(x.hex(), y.hex()) for x, y in got] == \
            [(float(x).hex(), float(y).hex()) for x, y in want]


@pytest.mark.parametrize("kind", ["semicircle", "turnaround", "dubins"])
def test_the_penalties_offset_along_the_grid_is_turn_path_s(kind):
    """The turn penalties give the turn its offset along the heading (0, ±1) as the along
    part times ±1 plus the across part times 0 (no numpy dot per turn): the waypoints are
    :func:`turn_path`'s bit for bit — q straight across from p (an offset of ±0), q = p,
    q behind p, no lead."""
    rng = np.random.default_rng(5)
    for i in range(3000):
        p = rng.uniform(-5e5, 5e5, 2) if i % 3 else np.round(rng.uniform(-1e3, 1e3, 2), 1)
        hy = (-1.0) ** i
        q = p + rng.normal(0, 80, 2) * (i % 11 != 0)
        if i % 5 == 0:
            q[1] = p[1]  # straight across: an offset of zero, of either sign
        lead = float(rng.choice([0.0, 5.0, 12.0, rng.uniform(0, 200)]))
        px, py, qx, qy = (float(v) for v in (*p, *q))
        off = (qx - px) * 0.0 + (qy - py) * hy
        got = turn_path_xy(px, py, 0.0, hy, qx, qy, off, lead, kind)
        want = turn_path(p, np.array([0.0, hy]), q, lead, kind)
        assert [(x.hex(), y.hex()) for x, y in got] == [(x.hex(), y.hex()) for x, y in want]


def test_turnaround_rows_are_the_turn_by_turn_rows_to_the_last_bit():
    """The turnaround turns' waypoints made for every turn at once (the penalties' fast
    path) are those of each turn made alone through ``turn_path`` and its trigger-off point:
    q ahead of p and behind it, straight across (no apex of the run-out), q at p, no lead,
    no trigger-off distance and one longer than the turn, next strips either side."""
    from scanplan.geo.sorties import _turn_rows, turnaround_rows

    rng = np.random.default_rng(23)
    for i in range(400):
        n = int(rng.integers(1, 30))
        p = np.where(i % 4 == 0, np.round(rng.uniform(-500, 500, (n, 2)), 1),
                     rng.uniform(-5e5, 5e5, (n, 2)))
        q = p + rng.normal(0, 60, (n, 2)) * (rng.random((n, 1)) > 0.1)
        across = rng.random(n) < 0.2
        q[across, 1] = p[across, 1]  # straight across: the apex is q's own line
        hy = np.where(rng.random(n) < 0.5, 1.0, -1.0)
        lead = float(rng.choice([0.0, 5.0, rng.uniform(0, 120)]))
        run_up = float(rng.uniform(1, 40))
        off = float(rng.choice([0.0, 3.0, 1e4, rng.uniform(0, 80)]))
        args = (p[:, 0], p[:, 1], q[:, 0], q[:, 1], hy)
        got, got_sizes = turnaround_rows(*args, lead, run_up, off)
        want, want_sizes = _turn_rows(*args, "turnaround", lead, run_up, off)
        assert got_sizes == want_sizes
        assert got.shape == want.shape and np.array_equal(got.view(np.int64),
                                                          want.view(np.int64))


def test_run_sums_are_each_runs_own_sum_to_the_last_bit():
    """The sums of many runs in one call per length equal ``np.sum`` of each run alone
    (the turns' times and lengths, the "auto" direction's strips and turns): runs of length
    0 to 3,000, overlapping, at any start, over values of mixed magnitude."""
    from scanplan.geo.strips import run_sums

    rng = np.random.default_rng(5)
    values = rng.normal(0, 1, 40_000) * 10.0 ** rng.integers(-6, 7, 40_000)
    lengths = np.r_[np.arange(0, 260), rng.integers(0, 3001, 300), [8, 8, 8, 128, 129, 1024]]
    starts = rng.integers(0, len(values) - 3001, len(lengths))
    got = run_sums(values, starts, lengths)
    want = [np.sum(values[a:a + n]) for a, n in zip(starts, lengths, strict=True)]
    assert [float(x).hex() for x in got] == [float(x).hex() for x in want]
    assert run_sums(values, np.array([], dtype=np.int64), np.array([], dtype=np.int64)).size == 0

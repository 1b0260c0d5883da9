"""Sorties: the serpentine cut into flights of one battery each, and their time as flown
(docs/flight-lines.md).

The block is flown as one serpentine — strips, and the turns between them, in flight
order. Every exposure has a place on it: the path distance ``c`` from the first exposure
of the block. A sortie flies one stretch of it, from an exposure *a* to an exposure *b*
(whole strips, or a part of a strip at either end), and flies

    (c_b − c_a) + run-in + run-out + transit(take-off → run-in of a)
                + transit(run-out of b → take-off)

metres. The take-off point is the given one, else the area's boundary point nearest the
sortie's run-in (the crew drives along the boundary to the launch site nearest each
sortie): the return leg is always flown and counted.

**The time as flown** (:class:`FlightModel`, its numbers and their sources in
``norms/catalogue/flight-model.csv``): the climb from the take-off point to the mission
height and the descent back at the autopilot's climb and descent speeds; the path at the
ground speed ``v`` with a trapezoidal speed profile — acceleration and braking at ``a``
between the nodes' speed limits (:func:`profile_time_s`); a node where the path turns by
θ is passed at most at ``sqrt(a_c · r)``, r = t / tan(θ/2) the radius of the arc that cuts
the corner a tangent length ``t`` before it (:func:`corner_speeds_ms`); a waypoint where
the aircraft stops (a DJI ``toPointAndStop…`` turn mode, the take-off and landing) at 0.
In the packing each turn between strips costs its own time as flown (its waypoints,
:func:`scanplan.geo.mission.turn_path`), and each sortie the climb, the descent, the start
and the stop and two corners onto and off the block counted as stops (an upper bound).

The sorties are packed greedily: each one runs as far along the serpentine as the battery
allows and the next resumes at the next exposure. For a cost that grows with the stretch
this gives the fewest sorties for the flight order (the greedy cover of a line by
intervals); the packing bound — the serpentine's length divided by one battery — is what
no packing can beat, and the greedy one stays within a run-in, a run-out and the transit
of it per sortie.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, field

import numpy as np

from ..i18n.messages import Message
from .layout import Sortie
from .strips import run_sums

Point = tuple[float, float]

__all__ = ["MAX_SORTIES", "FlightModel", "SortiePlan", "boundary_transit", "corner_speeds_ms",
           "pack_sorties", "path_time_s", "paths_time_s", "profile_time_s", "sortie_overhead_m",
           "turn_penalties_m", "vertical_time_s"]

MAX_SORTIES = 1_000
"""Most sorties (beyond: not feasible)."""


@dataclass(frozen=True)
class FlightModel:
    """The numbers of the time as flown (``norms/catalogue/flight-model.csv``).

    Attributes
    ----------
    accel_ms2 : float
        Acceleration and braking along the path [m/s²].
    corner_accel_ms2 : float
        Lateral acceleration through a corner [m/s²].
    corner_radius_m : float
        How far before a corner the aircraft starts to turn (the tangent length) [m].
    climb_speed_ms, descent_speed_ms : float
        Vertical speeds of the climb after take-off and the descent to land [m/s].
    """

    accel_ms2: float
    corner_accel_ms2: float
    corner_radius_m: float
    climb_speed_ms: float
    descent_speed_ms: float

    @classmethod
    def bundled(cls) -> FlightModel:
        """The model of the bundled ``flight-model.csv``."""
        from ..norms.aircraft import flight_model_params

        p = flight_model_params()
        return cls(p["horizontal_accel_ms2"].value, p["corner_accel_ms2"].value,
                   p["corner_radius_m"].value, p["climb_speed_ms"].value,
                   p["descent_speed_ms"].value)


def profile_time_s(leg_m: np.ndarray, node_ms: np.ndarray, speed_ms: float,
                   accel_ms2: float) -> float:
    """Time over a chain of legs with a speed limit at every node [s].

    Parameters
    ----------
    leg_m : ndarray
        The legs' lengths [m], n of them.
    node_ms : ndarray
        The speed limit at each of the n + 1 nodes [m/s] (0: a stop).
    speed_ms : float
        The cruise speed [m/s] (> 0).
    accel_ms2 : float
        Acceleration and braking [m/s²] (> 0).

    Notes
    -----
    The trapezoidal speed profile: a forward pass caps each node at the speed reachable
    from the one before, u_{i+1} ≤ sqrt(u_i² + 2aL_i), a backward pass at the speed it can
    still brake from, u_i ≤ sqrt(u_{i+1}² + 2aL_i); each leg is then flown accelerating
    from u_0 to its peak v_p = min(v, sqrt((2aL + u_0² + u_1²)/2)), cruising, and braking
    to u_1: t = (v_p − u_0)/a + (v_p − u_1)/a + (L − (2v_p² − u_0² − u_1²)/(2a))/v_p.

    >>> round(profile_time_s(np.array([100.0]), np.array([0.0, 0.0]), 10.0, 2.5), 3)
    14.0
    >>> round(profile_time_s(np.array([100.0]), np.array([10.0, 10.0]), 10.0, 2.5), 3)
    10.0
    """
    leg = np.asarray(leg_m, dtype=float)
    u = _capped_speeds(leg, np.asarray(node_ms, dtype=float), speed_ms, accel_ms2,
                       [(0, len(leg))])
    return float(np.sum(_leg_times_s(leg, u, speed_ms, accel_ms2)))


def _capped_speeds(leg_m: np.ndarray, node_ms: np.ndarray, speed_ms: float, accel_ms2: float,
                   chains: list[tuple[int, int]]) -> np.ndarray:
    """:func:`profile_time_s`'s two passes: each node's speed limit capped at what can be
    reached from the node before and braked from to the node after [m/s]. ``chains``: the
    (first, last) node of each chain of legs (its legs ``first … last − 1``); a leg between
    chains is not flown."""
    u = np.minimum(node_ms, speed_ms).tolist()  # Python floats: the passes go node by node
    two_a_l = (2.0 * accel_ms2 * leg_m).tolist()
    sqrt = math.sqrt
    for first, last in chains:
        for i in range(first, last):  # forward: what can be reached
            u[i + 1] = min(u[i + 1], sqrt(u[i] ** 2 + two_a_l[i]))
        for i in range(last - 1, first - 1, -1):  # backward: what can still brake
            u[i] = min(u[i], sqrt(u[i + 1] ** 2 + two_a_l[i]))
    return np.array(u)


def _leg_times_s(leg_m: np.ndarray, u_ms: np.ndarray, speed_ms: float, accel_ms2: float
                 ) -> np.ndarray:
    """The time of each leg between node speeds ``u_ms`` (:func:`profile_time_s`'s
    trapezoid) [s]; 0 for a leg of no length."""
    a, leg = accel_ms2, leg_m
    two_a_l = 2.0 * a * leg
    u0, u1 = u_ms[:-1], u_ms[1:]
    vp = np.minimum(speed_ms, np.sqrt((two_a_l + u0 ** 2 + u1 ** 2) / 2.0))
    with np.errstate(divide="ignore", invalid="ignore"):
        cruise = (leg - (2.0 * vp ** 2 - u0 ** 2 - u1 ** 2) / (2.0 * a)) / vp
        t = (vp - u0) / a + (vp - u1) / a + np.where(vp > 0, np.maximum(cruise, 0.0), 0.0)
    return np.where(leg > 0, t, 0.0)


def corner_speeds_ms(xy: np.ndarray, speed_ms: float, model: FlightModel,
                     tangent_m: np.ndarray | float | None = None) -> np.ndarray:
    """The speed limit at each node of a path [m/s]: the cruise speed where the path goes
    straight on, ``sqrt(a_c · r)`` where it turns by θ — r = t / tan(θ/2), the arc that
    cuts the corner a tangent length t before the node, t at most half of either leg — and
    the cruise speed at the two ends (the caller sets where the aircraft stops).

    >>> m = FlightModel(2.5, 5.0, 2.0, 2.5, 1.5)
    >>> corner_speeds_ms(np.array([[0.0, 0], [100, 0], [100, 100]]), 12.0, m).round(2)
    array([12.  ,  3.16, 12.  ])
    """
    xy = np.asarray(xy, dtype=float)
    n = len(xy)
    out = np.full(n, float(speed_ms))
    if n < 3:
        return out
    d = np.diff(xy, axis=0)
    seg = np.hypot(d[:, 0], d[:, 1])
    a, b = d[:-1], d[1:]
    la, lb = seg[:-1], seg[1:]
    with np.errstate(divide="ignore", invalid="ignore"):
        cos = np.clip(np.sum(a * b, axis=1) / (la * lb), -1.0, 1.0)
    theta = np.arccos(np.where((la > 0) & (lb > 0), cos, 1.0))
    t = model.corner_radius_m if tangent_m is None else np.asarray(tangent_m, float)[1:-1] \
        if np.ndim(tangent_m) else float(tangent_m)
    t = np.minimum(np.minimum(t, la / 2.0), lb / 2.0)
    with np.errstate(divide="ignore", invalid="ignore"):
        r = t / np.tan(theta / 2.0)
        v = np.sqrt(model.corner_accel_ms2 * np.maximum(r, 0.0))
    out[1:-1] = np.where(theta > 1e-6, np.minimum(v, speed_ms), speed_ms)
    return out


def path_time_s(xy: np.ndarray, speed_ms: float, model: FlightModel, *,
                start_ms: float = 0.0, end_ms: float = 0.0, stops: np.ndarray | None = None,
                tangent_m: np.ndarray | float | None = None) -> float:
    """Time to fly the polyline ``xy`` [s]: its corners (:func:`corner_speeds_ms`), the
    nodes in ``stops`` (a boolean per node) at rest, entered at ``start_ms`` and left at
    ``end_ms`` (:func:`profile_time_s`).

    >>> m = FlightModel(2.5, 5.0, 2.0, 2.5, 1.5)
    >>> round(path_time_s(np.array([[0.0, 0], [100, 0]]), 10.0, m), 3)
    14.0
    """
    xy = np.asarray(xy, dtype=float)
    if len(xy) < 2:
        return 0.0
    d = np.diff(xy, axis=0)
    leg = np.hypot(d[:, 0], d[:, 1])
    node = corner_speeds_ms(xy, speed_ms, model, tangent_m)
    node[0], node[-1] = min(start_ms, speed_ms), min(end_ms, speed_ms)
    if stops is not None:
        node = np.where(np.asarray(stops, bool), 0.0, node)
    return profile_time_s(leg, node, speed_ms, model.accel_ms2)


def paths_time_s(paths: list[np.ndarray], speed_ms: float, model: FlightModel, *,
                 start_ms: float = 0.0, end_ms: float = 0.0
                 ) -> tuple[np.ndarray, np.ndarray]:
    """Time to fly each polyline of ``paths`` [s], as :func:`path_time_s` gives it, and its
    length [m] — the paths' corners and legs computed together (the turns of a layout).

    >>> m = FlightModel(2.5, 5.0, 2.0, 2.5, 1.5)
    >>> t, length = paths_time_s([np.array([[0.0, 0], [100, 0]])] * 2, 10.0, m)
    >>> t.round(3).tolist(), length.tolist()
    ([14.0, 14.0], [100.0, 100.0])
    """
    sizes = [len(p) for p in paths]
    if not paths or min(sizes) < 2:
        raise ValueError("paths_time_s: every path needs two points or more")
    return _chains_time_s(np.concatenate([np.asarray(p, dtype=float) for p in paths]),
                          sizes, speed_ms, model, start_ms, end_ms)


def _chains_time_s(xy: np.ndarray, sizes: list[int], speed_ms: float, model: FlightModel,
                   start_ms: float, end_ms: float) -> tuple[np.ndarray, np.ndarray]:
    """:func:`paths_time_s` of the paths one after the other in ``xy``, ``sizes[i]``
    points each."""
    d = np.diff(xy, axis=0)
    leg = np.hypot(d[:, 0], d[:, 1])  # the leg from one path's end to the next: not flown
    node = corner_speeds_ms(xy, speed_ms, model)  # each path's interior nodes as alone
    ends = np.cumsum(sizes)
    starts = ends - np.asarray(sizes)
    node[starts], node[ends - 1] = min(start_ms, speed_ms), min(end_ms, speed_ms)
    chains = [(int(a), int(b) - 1) for a, b in zip(starts, ends, strict=True)]
    t = _leg_times_s(leg, _capped_speeds(leg, node, speed_ms, model.accel_ms2, chains),
                     speed_ms, model.accel_ms2)
    return run_sums(t, starts, ends - 1 - starts), run_sums(leg, starts, ends - 1 - starts)


def vertical_time_s(climb_m: float, descent_m: float, model: FlightModel) -> float:
    """The climb after take-off and the descent to land [s]."""
    return max(climb_m, 0.0) / model.climb_speed_ms + max(descent_m, 0.0) / \
        model.descent_speed_ms


def sortie_overhead_m(speed_ms: float, height_m: float, model: FlightModel) -> float:
    """What a sortie costs beyond its path, as metres at the cruise speed: the climb and
    the descent, the start from rest and the stop (v/(2a) each), and the two corners onto
    the block and off it counted as stops (v/a each) — an upper bound of the time as
    flown, as a stop costs at most v/a over cruising its leg."""
    t = vertical_time_s(height_m, height_m, model) + 3.0 * speed_ms / model.accel_ms2
    return t * speed_ms


@dataclass
class SortiePlan:
    """Sorties in flight order.

    Attributes
    ----------
    exposure_sortie : ndarray of int
        The sortie (from 0) of every exposure, in flight order.
    strips : list of list of int
        The strips (from 0) each sortie flies, whole or in part.
    length_m, transit_m : list of float
        Each sortie's flight length, transit included, and the transit's share [m].
    cost_m : list of float
        Each sortie's time as flown, as metres at the cruise speed [m] (empty: the length).
    first : list of int
        Each sortie's first exposure (flight order).
    takeoff_uv : list of (float, float)
        Each sortie's take-off point in the packing's frame (empty: none).
    """

    exposure_sortie: np.ndarray
    strips: list[list[int]]
    length_m: list[float]
    transit_m: list[float]
    cost_m: list[float] = field(default_factory=list)
    first: list[int] = field(default_factory=list)
    takeoff_uv: list[tuple[float, float]] = field(default_factory=list)

    def start(self, n_strips: int, exposure_strip: np.ndarray) -> np.ndarray:
        """The sortie each strip starts in (that of its first exposure)."""
        out = np.zeros(n_strips, dtype=np.int64)
        first = np.r_[True, exposure_strip[1:] != exposure_strip[:-1]] if len(
            exposure_strip) else np.zeros(0, dtype=bool)
        out[exposure_strip[first]] = self.exposure_sortie[first]
        return out

    def continued(self, exposure_strip: np.ndarray) -> dict[int, tuple[tuple[int, int], ...]]:
        """The strips a later sortie continues (a battery change mid-strip): strip (from 0)
        → (sortie, photo) for each sortie after the one it starts in — the sortie (from 1)
        and the running number of its first photo on that strip (from 1: exposures are
        numbered in flight order)."""
        s = self.exposure_sortie
        if len(s) < 2:
            return {}
        at = np.flatnonzero((s[1:] != s[:-1])
                            & (exposure_strip[1:] == exposure_strip[:-1])) + 1
        out: dict[int, list[tuple[int, int]]] = {}
        for k in at:
            out.setdefault(int(exposure_strip[k]), []).append((int(s[k]) + 1, int(k) + 1))
        return {strip: tuple(v) for strip, v in out.items()}

    def records(self, speed_ms: float | None,
                to_xy: Callable[[float, float], tuple[float, float]] | None = None
                ) -> tuple[Sortie, ...]:
        """The :class:`Sortie` records: times as flown at ``speed_ms`` (the cost, else the
        length), take-off points through ``to_xy`` (packing frame → planning CRS)."""
        def time(m: float) -> float | None:
            if not speed_ms or speed_ms <= 0:
                return None
            t = m / speed_ms
            return t if math.isfinite(t) else None
        costs = self.cost_m if len(self.cost_m) == len(self.length_m) else self.length_m
        homes: list[tuple[float, float] | None] = (
            [to_xy(*t) if to_xy else t for t in self.takeoff_uv]
            if len(self.takeoff_uv) == len(self.length_m) else [None] * len(self.length_m))
        return tuple(Sortie(number=k + 1, strips=tuple(i + 1 for i in st), length_m=ln,
                            time_s=time(c), transit_m=tr,
                            takeoff_xy_m=(None if h is None else (float(h[0]), float(h[1]))))
                     for k, (st, ln, tr, c, h) in enumerate(zip(
                         self.strips, self.length_m, self.transit_m, costs, homes,
                         strict=True)))


def pack_sorties(path_m: np.ndarray, exposure_strip: np.ndarray, run_in_m: np.ndarray,
                 run_out_m: np.ndarray, *, lead_in_m: float, lead_out_m: float,
                 limit_m: float | None, max_minutes: float | None = None,
                 transit: Callable[[int, np.ndarray], tuple[float, np.ndarray,
                                                            tuple[float, float] | None]]
                 | None = None,
                 penalty_m: np.ndarray | None = None, overhead_m: float = 0.0
                 ) -> tuple[SortiePlan, Message | None]:
    """Sorties over the serpentine, and why it cannot be flown (None if it can).

    Parameters
    ----------
    path_m : ndarray
        Path distance of every exposure from the block's first one, in flight order [m]
        (ascending).
    exposure_strip : ndarray of int
        The strip (from 0) of every exposure.
    run_in_m, run_out_m : ndarray
        Transit from the take-off point to the run-in before each exposure, and from the
        run-out after it back [m] (used when ``transit`` is not given).
    lead_in_m, lead_out_m : float
        Run-in before a sortie's first exposure and run-out after its last one [m].
    limit_m : float or None
        What one battery flies, as metres at the cruise speed [m] (None: one sortie).
    max_minutes : float, optional
        The battery's flight time [min] (for the message).
    transit : callable, optional
        ``transit(a, b)`` → the transit to the run-in of exposure ``a`` [m], the transits
        back from the run-out of each exposure of the array ``b`` [m], and the take-off
        point: a take-off point that depends on where the sortie starts.
    penalty_m : ndarray, optional
        The time the path up to each exposure costs beyond its length at the cruise speed
        (its corners), as metres [m] (ascending; default none).
    overhead_m : float
        What every sortie costs beyond its path (climb, descent, start, stop), as metres.

    Returns
    -------
    SortiePlan, Message or None
        ``cost_m`` is each sortie's time as flown in metres at the cruise speed (what the
        battery limit is checked against), ``length_m`` its geometric length.
    """
    n = len(path_m)
    fixed = lead_in_m + lead_out_m
    pen = np.zeros(n) if penalty_m is None else np.asarray(penalty_m, dtype=float)
    eq = path_m + pen  # the path as time, in metres at the cruise speed

    def legs(a: int, b: np.ndarray) -> tuple[float, np.ndarray, tuple[float, float] | None]:
        if transit is not None:
            return transit(a, b)
        return float(run_in_m[a]), np.asarray(run_out_m[b], dtype=float), None

    if n == 0:
        return SortiePlan(np.zeros(0, dtype=np.int64), [], [], []), None
    if limit_m is None or not math.isfinite(limit_m):
        t_in, t_out, home = legs(0, np.array([n - 1]))
        length = float(path_m[-1] - path_m[0]) + fixed + t_in + float(t_out[0])
        cost = float(eq[-1] - eq[0]) + fixed + t_in + float(t_out[0]) + overhead_m
        return SortiePlan(np.zeros(n, dtype=np.int64),
                          [sorted(set(exposure_strip.tolist()))],
                          [length], [t_in + float(t_out[0])], [cost], [0],
                          [home] if home is not None else []), None
    return _pack_greedy(path_m, eq, exposure_strip, legs, fixed, overhead_m, float(limit_m),
                        max_minutes)


def _pack_greedy(path_m: np.ndarray, eq: np.ndarray, exposure_strip: np.ndarray,
                 legs: Callable[[int, np.ndarray], tuple[float, np.ndarray,
                                                         tuple[float, float] | None]],
                 fixed: float, overhead_m: float, limit_m: float,
                 max_minutes: float | None) -> tuple[SortiePlan, Message | None]:
    """Each sortie as long as the battery allows, in flight order: the sorties of
    :func:`pack_sorties` when a battery limit is given (``fixed``: the run-in and the
    run-out, ``overhead_m``: what every sortie costs beyond its path) [m]."""
    n = len(path_m)
    sortie = np.zeros(n, dtype=np.int64)
    plan = SortiePlan(sortie, [], [], [])
    a = 0
    while a < n:
        # Only exposures within one battery of path from ``a`` can end its sortie (the
        # cost never falls below the path flown): the work stays linear in exposures.
        end = a + int(np.searchsorted(eq[a:], eq[a] + limit_m - fixed - overhead_m,
                                      "right"))
        end = max(end, a + 1)
        window = np.arange(a, end)
        t_in, t_out, home = legs(a, window)
        cost = eq[a:end] - eq[a] + fixed + overhead_m + t_in + t_out
        fits = np.flatnonzero(cost <= limit_m)
        if not len(fits) or fits[0] != 0:
            return _failed(n, plan), Message(
                "layout.sortie_cannot_reach", limit=max_minutes or 0.0,
                have=float(limit_m), need=float(cost[0]))
        k = int(fits[-1])
        b = a + k
        sortie[a:b + 1] = len(plan.strips)
        flown = exposure_strip[a:b + 1]
        heads = np.flatnonzero(flown[1:] != flown[:-1]) + 1  # each run's first exposure
        plan.strips.append(sorted({int(flown[0]), *flown[heads].tolist()}))
        plan.length_m.append(float(path_m[b] - path_m[a]) + fixed + t_in + float(t_out[k]))
        plan.transit_m.append(t_in + float(t_out[k]))
        plan.cost_m.append(float(cost[k]))
        plan.first.append(a)
        if home is not None:
            plan.takeoff_uv.append(home)
        if len(plan.strips) > MAX_SORTIES:
            return _failed(n, plan), Message(
                "layout.too_many_sorties", most=MAX_SORTIES, limit=max_minutes or 0.0)
        a = b + 1
    return plan, None


def _failed(n: int, plan: SortiePlan) -> SortiePlan:
    return SortiePlan(np.zeros(n, dtype=np.int64), plan.strips or [[]],
                      plan.length_m or [0.0], plan.transit_m or [0.0])


def turn_penalties_m(exposure_strip: np.ndarray, along_m: np.ndarray, across_m: np.ndarray,
                     turn_kind: str, lead_m: float, speed_ms: float, model: FlightModel,
                     trigger_off_m: float = 0.0) -> np.ndarray:
    """The time the turns cost beyond their length at the cruise speed, as metres,
    summed along the serpentine up to each exposure [m] (:func:`pack_sorties`'s
    ``penalty_m``).

    The exposures are in the packing's frame: ``across_m`` the line's position of each
    strip (by strip index), ``along_m`` each exposure's place along its line; an
    even-numbered strip is flown towards +along, the next back. Each turn is flown through
    the waypoints the mission writes for it (:func:`scanplan.geo.mission.turn_path`, with
    the camera's trigger-off point ``trigger_off_m`` along it), entered and left at the
    cruise speed.
    """
    ex = np.asarray(exposure_strip)
    out = np.zeros(len(ex))
    if len(ex) < 2 or not speed_ms or speed_ms <= 0:
        return out
    change = np.flatnonzero(np.diff(ex))
    if not len(change):
        return out
    run_up = speed_ms ** 2 / (2.0 * model.accel_ms2) + 1.0  # [m]
    across, along = np.asarray(across_m, dtype=float), np.asarray(along_m, dtype=float)
    s0 = ex[change]
    px, py = across[s0], along[change]
    qx, qy = across[ex[change + 1]], along[change + 1]
    hy = np.where(s0 % 2 == 0, 1.0, -1.0)
    # a turn's time depends on its shape only: each shape timed once, at its first turn
    seen: dict[tuple[float, float], int] = {}
    turn_of: list[int] = []
    first: list[int] = []  # each shape's first turn
    for i, (a, b) in enumerate(zip((hy * (qy - py)).tolist(), np.abs(qx - px).tolist(),
                                   strict=True)):
        key = (round(a, 3), round(b, 3))
        if key not in seen:
            seen[key] = len(first)
            first.append(i)
        turn_of.append(seen[key])
    ends = (px[first], py[first], qx[first], qy[first], hy[first])
    # each turn with the straights before and after at full length: the braking for the
    # turn begins on the strip, before its last photo (an upper bound where the strip is
    # shorter)
    if turn_kind == "turnaround":
        rows, sizes = turnaround_rows(*ends, lead_m, run_up, trigger_off_m)
    else:
        rows, sizes = _turn_rows(*ends, turn_kind, lead_m, run_up, trigger_off_m)
    times, lengths = _chains_time_s(rows, sizes, speed_ms, model, speed_ms, speed_ms)
    extra = [max(0.0, float(t) * speed_ms - float(length))
             for t, length in zip(times, lengths, strict=True)]
    steps = np.zeros(len(ex))
    steps[change + 1] = np.array(extra)[turn_of]
    return np.cumsum(steps)


def _turn_rows(px: np.ndarray, py: np.ndarray, qx: np.ndarray, qy: np.ndarray,
               hy: np.ndarray, turn_kind: str, lead_m: float, run_up_m: float,
               trigger_off_m: float) -> tuple[np.ndarray, list[int]]:
    """The waypoints each turn is timed through (:func:`turn_penalties_m`), one turn after
    the other (n × 2), and how many each turn has: the run-up before the strip's last photo
    ``p``, ``p``, the turn's waypoints (:func:`scanplan.geo.mission.turn_path`) with the
    trigger-off point, the next strip's first photo ``q`` and the run-up past it [m]."""
    from .mission import turn_path_xy, turns_trigger_off

    starts: list[Point] = []
    paths: list[list[Point]] = []
    for p0, p1, q0, q1, h in zip(px.tolist(), py.tolist(), qx.tolist(), qy.tolist(),
                                 hy.tolist(), strict=True):
        # (q − p) · (0, h): exactly the along part times h (the across part times 0 adds
        # a zero, whose sign no waypoint keeps)
        off = (q0 - p0) * 0.0 + (q1 - p1) * h
        starts.append((p0, p1))
        paths.append(turn_path_xy(p0, p1, 0.0, h, q0, q1, off, lead_m, turn_kind))
    rows: list[Point] = []
    sizes = []
    for (p0, p1), h, path, (before, off_pt, after) in zip(
            starts, hy.tolist(), paths, turns_trigger_off(starts, paths, trigger_off_m),
            strict=True):
        q0, q1 = path[-1]
        turn = [(p0, p1 - run_up_m * h), (p0, p1), *before, off_pt, *after, path[-1],
                (q0, q1 - run_up_m * h)]
        rows += turn
        sizes.append(len(turn))
    return np.array(rows, dtype=float).reshape(-1, 2), sizes


def turnaround_rows(px: np.ndarray, py: np.ndarray, qx: np.ndarray, qy: np.ndarray,
                    hy: np.ndarray, lead_m: float, run_up_m: float, trigger_off_m: float
                    ) -> tuple[np.ndarray, list[int]]:
    """:func:`_turn_rows` of turnaround turns, for every turn at once: the same waypoints
    to the last bit (the same operations on the same numbers, tests/test_turn_times.py).

    A turnaround (:func:`scanplan.geo.mission.turn_path`) from ``p`` heading (0, hy) to
    ``q``: the run-out apex A (``lead_m`` past the farther of ``p`` and ``q`` along the
    heading; left out where it is ``p`` itself), the run-in apex B across from it (left
    out where it is ``q``), and ``q``; the camera is disarmed ``trigger_off_m`` along that
    ring from ``p``, at most half way (:func:`scanplan.geo.mission.turns_trigger_off`).
    """
    n = len(px)
    zero = np.zeros(n)
    off = (qx - px) * 0.0 + (qy - py) * hy  # (q − p) · (0, hy), as _turn_rows
    nvx, nvy = (qx - px) - off * zero, (qy - py) - off * hy  # the across part of q − p
    d = np.hypot(nvx, nvy)
    with np.errstate(divide="ignore", invalid="ignore"):
        nx = np.where(d > 0, nvx / d, hy)
        ny = np.where(d > 0, nvy / d, -zero)
    ahead = np.where(off > 0.0, off, 0.0) + lead_m  # max(0, off) + lead
    ox, oy = px + ahead * zero, py + ahead * hy
    ix, iy = ox + d * nx, oy + d * ny
    ax, ay = ox + 0.0 * nx + 0.0 * zero, oy + 0.0 * ny + 0.0 * hy  # A: at(0, 0)
    bx, by = ox + d * nx + 0.0 * zero, oy + d * ny + 0.0 * hy  # B: at(d, 0)
    has_a = np.hypot(ox - px, oy - py) > 1e-6
    has_b = np.hypot(qx - ix, qy - iy) > 1e-6  # else q takes B's place
    # the ring p, [A], [B], q, its points moved to the front of four places
    cand = np.stack([np.column_stack([px, py]), np.column_stack([ax, ay]),
                     np.column_stack([bx, by]), np.column_stack([qx, qy])], axis=1)
    keep = np.column_stack([np.ones(n, bool), has_a, has_b, np.ones(n, bool)])
    size = keep.sum(axis=1)  # 2 … 4 points
    ring = np.full((n, 4, 2), np.nan)
    ring[np.nonzero(keep)[0], (np.cumsum(keep, axis=1) - 1)[keep]] = cand[keep]
    # the trigger-off point: at = min(after, half the ring), in the segment ending at k
    seg = np.hypot(*np.moveaxis(np.diff(ring, axis=1), 2, 0))  # NaN past the ring's end
    cum = np.concatenate([zero[:, None], np.cumsum(seg, axis=1)], axis=1)
    total = cum[np.arange(n), size - 1]
    half = total / 2.0
    at = np.where(half < trigger_off_m, half, trigger_off_m)
    k = np.clip((cum <= at[:, None]).sum(axis=1), 1, size - 1)
    rows_i = np.arange(n)
    seg_k, cum_k = seg[rows_i, k - 1], cum[rows_i, k - 1]
    with np.errstate(divide="ignore", invalid="ignore"):
        t = np.where(seg_k > 0, (at - cum_k) / seg_k, 0.0)
    (x0, y0), (x1, y1) = ring[rows_i, k - 1].T, ring[rows_i, k].T
    cut = np.column_stack([x0 + t * (x1 - x0), y0 + t * (y1 - y0)])
    # each turn's rows: the run-up, p, the ring's points before k, the trigger-off point,
    # those from k on (not the last) apart from it, q, the run-up past q
    j = np.arange(1, 3)  # the ring's inner points
    inner = ring[:, 1:3]
    apart = np.hypot(inner[..., 0] - cut[:, None, 0], inner[..., 1] - cut[:, None, 1]) > 1e-6
    before = j[None, :] < k[:, None]
    after = (j[None, :] >= k[:, None]) & (j[None, :] <= (size - 2)[:, None]) & apart
    last = ring[rows_i, size - 1]
    slots = np.stack([np.column_stack([px, py - run_up_m * hy]), np.column_stack([px, py]),
                      inner[:, 0], inner[:, 1], cut, inner[:, 0], inner[:, 1], last,
                      np.column_stack([last[:, 0], last[:, 1] - run_up_m * hy])], axis=1)
    use = np.column_stack([np.ones((n, 2), bool), before, np.ones(n, bool), after,
                           np.ones((n, 2), bool)])
    return slots[use], use.sum(axis=1).tolist()


def boundary_transit(boundary: object, start_xy: np.ndarray, end_xy: np.ndarray,
                     takeoff_xy: tuple[float, float] | None
                     ) -> Callable[[int, np.ndarray], tuple[float, np.ndarray,
                                                            tuple[float, float] | None]]:
    """:func:`pack_sorties`'s ``transit``: from the take-off point to a sortie's run-in and
    back from its run-out. The take-off point is ``takeoff_xy`` when given, else the point
    of ``boundary`` (the area's outline, a shapely geometry in the same frame) nearest the
    run-in of the sortie's first exposure.

    ``start_xy``/``end_xy`` are each exposure's run-in and run-out points (n × 2) [m].
    """
    import shapely

    def transit(a: int, b: np.ndarray) -> tuple[float, np.ndarray, tuple[float, float]]:
        if takeoff_xy is not None:
            home = (float(takeoff_xy[0]), float(takeoff_xy[1]))
        else:
            pt = shapely.points(start_xy[a])
            near = shapely.line_interpolate_point(boundary, shapely.line_locate_point(
                boundary, pt))
            home = (float(shapely.get_x(near)), float(shapely.get_y(near)))
        t_in = float(math.hypot(start_xy[a][0] - home[0], start_xy[a][1] - home[1]))
        t_out = np.hypot(end_xy[b, 0] - home[0], end_xy[b, 1] - home[1])
        return t_in, t_out, home

    return transit


def packing_bound(serpentine_m: float, limit_m: float) -> int:
    """The fewest sorties any packing can fly: the serpentine over one battery."""
    return max(1, math.ceil(serpentine_m / limit_m))

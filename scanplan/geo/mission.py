"""The mission a crew flies, independent of any file format (docs/exports.md).

:func:`sortie_missions` turns a :class:`~scanplan.geo.layout.FlightLayout` into one
:class:`SortieMission` per sortie: the path as waypoints in the planning CRS — run-in,
the trigger-on and trigger-off points of every photographed run, the turns between strips,
the run-out — each point saying at which photo's altitude it is flown. The exporters
(QGroundControl Plan, the Mission Planner waypoint file, any other autopilot format) render
these records; they compute no geometry of their own, so every format flies the same path,
and its length is the layout's reported flight length (:mod:`scanplan.geo.lines`).

**The camera trigger.** Each run is armed at its first photo centre with a trigger
distance and "one image now", and disarmed half a base past its last photo centre. This
is MAVLink's MAV_CMD_DO_SET_CAM_TRIGG_DIST (param1 distance [m], param3 = 1: one image at
once) as ArduPilot implements it (``AP_Camera_Backend::update``): while the distance is
positive, an image is taken whenever the aircraft's distance from where the last image was
taken reaches it, checked in the 50 Hz camera update, so each image is up to one loop step
late and the lateness adds up along a run. The trigger distance of a run is the ground
(ellipsoidal) distance between its planned centres — the grid's base divided by the
projection's scale factor k — so the exposures fall on the planned centres, not on a grid
that k stretches. A run holds at most as many photos as keep its added lateness within a
quarter of a base at the planned speed (:data:`CAMERA_LOOP_HZ`); a longer part is split
into runs, each re-armed at its first centre (which resets the lateness). The disarm half
a base past the last centre then comes after the run's last image and before the next
would be due, so every run fires exactly its photos — also where a waypoint is reached a
few metres early (ArduCopter's WPNAV_RADIUS, 2 m) — and in ``follow`` altitude mode the
altitude steps are run boundaries like any other.
"""

from __future__ import annotations

import bisect
import functools
import itertools
import math
from collections.abc import Collection
from dataclasses import dataclass
from typing import Any

import numpy as np

from .layout import FlightLayout

__all__ = ["CAMERA_LOOP_HZ", "MissionPoint", "SortieMission", "sortie_missions",
           "turn_path", "turns_trigger_off"]

CAMERA_LOOP_HZ = 50.0
"""How often the autopilot checks the trigger distance [Hz]: ArduPilot runs
``AP_Camera::update`` in its 50 Hz scheduler (ArduCopter/ArduPlane ``scheduler_tasks``)."""
RUN_LATENESS_SHARE = 0.25
"""The most lateness a run may add up, as a share of its trigger distance."""
ARC_STEP_DEG = 20.0
"""Largest turn between two waypoints of an arc [°] (chord 0.5 % short of the arc)."""
_STEP_M = 1e-6  # an altitude change smaller than this is no step [m]


@dataclass(frozen=True)
class MissionPoint:
    """One waypoint of a mission (planning CRS).

    Attributes
    ----------
    x_m, y_m : float
        Position in the layout's planning CRS [m].
    role : str
        ``"run_in"`` (the start of a strip's straight before its first photo),
        ``"trigger_on"`` (a run's first photo centre: arm the trigger, one image now),
        ``"photo"`` (a run's last photo centre), ``"trigger_off"`` (half a base past a
        run: disarm), ``"run_out"`` (the end of the straight past the last photo) or
        ``"turn"`` (a point of the turn to the next strip).
    strip : int
        The strip (from 1) the point belongs to.
    photo : int
        Position in the layout's photo table of the photo whose altitude the point is flown
        at (the higher of the two neighbours between runs and in turns).
    trigger_m : float or None
        ``"trigger_on"``: the trigger distance on the ground [m]; ``"trigger_off"``: 0.
    """

    x_m: float
    y_m: float
    role: str
    strip: int
    photo: int
    trigger_m: float | None = None


@dataclass(frozen=True)
class SortieMission:
    """One sortie's mission: take-off, the waypoints in order, return.

    Attributes
    ----------
    number : int
        The sortie (from 1).
    points : tuple of MissionPoint
        The waypoints in flight order.
    takeoff_xy_m : (float, float) or None
        The take-off point in the planning CRS [m]: the given one, else the area's boundary
        point nearest the sortie's run-in (None: an area with no place on the map; the
        mission's home is then its first waypoint).
    photos : int
        The photos the sortie takes.
    """

    number: int
    points: tuple[MissionPoint, ...]
    takeoff_xy_m: tuple[float, float] | None
    photos: int

    @property
    def home_xy_m(self) -> tuple[float, float]:
        """Where the sortie takes off and returns to [m]."""
        if self.takeoff_xy_m is not None:
            return self.takeoff_xy_m
        return (self.points[0].x_m, self.points[0].y_m)

    def path_length_m(self) -> float:
        """The length of the path in the planning CRS [m]: take-off point, every waypoint,
        back to the take-off point (no transit without one)."""
        xy = np.array([[p.x_m, p.y_m] for p in self.points])
        if self.takeoff_xy_m is not None:
            xy = np.vstack([self.takeoff_xy_m, xy, self.takeoff_xy_m])
        return float(np.sum(np.hypot(*np.diff(xy, axis=0).T)))


def sortie_missions(layout: FlightLayout, speed_ms: float, *,
                    loop_hz: float = CAMERA_LOOP_HZ,
                    numbers: Collection[int] | None = None) -> tuple[SortieMission, ...]:
    """Every sortie of ``layout`` as a :class:`SortieMission` (see the module's rules).

    Parameters
    ----------
    layout : FlightLayout
        A feasible layout with its photo table.
    speed_ms : float
        Ground speed along the strips [m/s] (the lateness of the trigger per loop step).
    loop_hz : float
        How often the autopilot checks the trigger distance [Hz].
    numbers : collection of int, optional
        Only these sorties (from 1); all when not given.

    Returns
    -------
    tuple of SortieMission
        In flight order; empty without photos.
    """
    ph = layout.photos
    if len(ph) == 0:
        return ()
    ctx = _Context.of(layout, speed_ms, loop_hz)
    sortie = np.asarray(ph["sortie"]).astype(np.int64)
    order = np.argsort(np.asarray(ph["photo"]), kind="stable")
    out = []
    for s in layout.sorties:
        if numbers is not None and s.number not in numbers:
            continue
        mine = order[sortie[order] == s.number]
        if not len(mine):
            continue
        # the sortie's own take-off point (the given one, else the area's boundary point
        # nearest its run-in: geo/sorties.py), else the layout's
        home = s.takeoff_xy_m if s.takeoff_xy_m is not None else ctx.takeoff
        out.append(SortieMission(s.number, tuple(ctx.sortie_points(mine)), home, len(mine)))
    return tuple(out)


@dataclass
class _Context:
    layout: FlightLayout
    x: np.ndarray
    y: np.ndarray
    alt: np.ndarray
    strip: np.ndarray
    lead_m: float
    turn_kind: str
    max_lateness_m: float  # one loop step at the speed [m]
    takeoff: tuple[float, float] | None
    geo: tuple[Any, Any] | None = None

    @classmethod
    def of(cls, layout: FlightLayout, speed_ms: float, loop_hz: float) -> _Context:
        ph = layout.photos
        kind = str(layout.notes.get("turn_kind", "semicircle"))
        takeoff = layout.notes.get("takeoff_xy_m")
        return cls(layout, np.asarray(ph["x_m"], float), np.asarray(ph["y_m"], float),
                   np.asarray(ph["altitude_m"], float),
                   np.asarray(ph["strip"]).astype(np.int64),
                   0.0 if kind == "semicircle" else float(layout.notes.get("turn_m", 0.0)),
                   kind, speed_ms / loop_hz,
                   tuple(map(float, takeoff)) if takeoff is not None else None)

    def _higher(self, i: int, j: int) -> int:
        return i if self.alt[i] >= self.alt[j] else j

    def _heading(self, number: int, idx: np.ndarray) -> np.ndarray:
        st = self.layout.strips[number - 1]
        h = np.subtract(st.end_xy_m, st.start_xy_m, dtype=float)
        if not np.hypot(*h) and len(idx) > 1:
            h = np.array([self.x[idx[-1]] - self.x[idx[0]], self.y[idx[-1]] - self.y[idx[0]]])
        norm = float(np.hypot(*h))
        return h / norm if norm else np.array([0.0, 1.0])

    def sortie_points(self, idx: np.ndarray) -> list[MissionPoint]:
        """The waypoints of the photos ``idx`` (one sortie, flight order)."""
        cuts = np.flatnonzero(np.diff(self.strip[idx])) + 1
        groups = np.split(idx, cuts)
        base = self.layout.base_m
        pts: list[MissionPoint] = []
        for g, mine in enumerate(groups):
            number = int(self.strip[mine[0]])
            h = self._heading(number, mine)
            p0 = np.array([self.x[mine[0]], self.y[mine[0]]])
            if g == 0 and self.lead_m > 0:
                pts.append(MissionPoint(*(p0 - self.lead_m * h), "run_in", number,
                                        int(mine[0])))
            runs = self._runs(mine)
            triggers = self._ground_bases(runs, h)
            for r, run in enumerate(runs):
                pts += self._run(run, number, float(triggers[r]))
                last = np.array([self.x[run[-1]], self.y[run[-1]]])
                if r + 1 < len(runs):  # the next run of the strip: disarm before it
                    nxt = runs[r + 1][0]
                    gap = float(np.hypot(self.x[nxt] - last[0], self.y[nxt] - last[1]))
                    pts.append(MissionPoint(*(last + min(base, gap) / 2.0 * h),
                                            "trigger_off", number,
                                            self._higher(int(run[-1]), int(nxt)), 0.0))
            end = int(mine[-1])
            pe = np.array([self.x[end], self.y[end]])
            if g + 1 == len(groups):  # the sortie's last strip: run-out, then return
                out = max(self.lead_m, base / 2.0)
                pts.append(MissionPoint(*(pe + base / 2.0 * h), "trigger_off", number,
                                        end, 0.0))
                if out > base / 2.0:
                    pts.append(MissionPoint(*(pe + out * h), "run_out", number, end))
                continue
            nxt = groups[g + 1]
            q = np.array([self.x[nxt[0]], self.y[nxt[0]]])
            alt_ref = self._higher(end, int(nxt[0]))
            following = int(self.strip[nxt[0]])
            if self.layout.strip_pass(following) != self.layout.strip_pass(number):
                pts += self._pass_transit(pe, h, q, self._heading(following, nxt), number,
                                          alt_ref)
                continue
            path = turn_path(pe, h, q, self.lead_m, self.turn_kind)
            pts += _with_trigger_off(pe, path, base / 2.0, number, alt_ref)
        return pts

    def _pass_transit(self, pe: np.ndarray, h: np.ndarray, q: np.ndarray, h2: np.ndarray,
                      number: int, photo: int) -> list[MissionPoint]:
        """From a crosshatch's first pass to its second (:mod:`.crosshatch`): disarmed
        half a base past the last photo, the run-out, straight to the run-in before the
        next strip's first photo ``q`` (heading ``h2``; its run puts ``q``)."""
        base = self.layout.base_m
        out = max(self.lead_m, base / 2.0)
        pts = [MissionPoint(*(pe + base / 2.0 * h), "trigger_off", number, photo, 0.0)]
        if out > base / 2.0:
            pts.append(MissionPoint(*(pe + out * h), "run_out", number, photo))
        if self.lead_m > 0:
            pts.append(MissionPoint(*(q - self.lead_m * h2), "run_in", number + 1, photo))
        return pts

    def _runs(self, mine: np.ndarray) -> list[np.ndarray]:
        """The strip's photos cut into runs: at a gap (bridged, > 1.5 bases), wherever two
        centres are not one grid step apart (where two parts of a strip meet closer than a
        base: a distance trigger cannot fire both), at an altitude step, and into pieces
        short enough for the trigger's lateness."""
        base = self.layout.base_m
        grid_step = base * float(self.layout.notes.get("grid_scale", 1.0))
        step = np.hypot(np.diff(self.x[mine]), np.diff(self.y[mine]))
        cut = ((step > 1.5 * base) | (np.abs(step - grid_step) > 0.01 * grid_step)
               | (np.abs(np.diff(self.alt[mine])) > _STEP_M))
        pieces = np.split(mine, np.flatnonzero(cut) + 1)
        most = int(RUN_LATENESS_SHARE * base / self.max_lateness_m) + 1 \
            if self.max_lateness_m > 0 else len(mine)
        out = []
        for p in pieces:
            k = math.ceil(len(p) / max(1, most))
            out += [a for a in np.array_split(p, k) if len(a)]
        return out

    def _run(self, run: np.ndarray, number: int, trigger: float) -> list[MissionPoint]:
        """A run: armed at its first centre (``trigger``: the ground base), its last
        centre."""
        a, b = int(run[0]), int(run[-1])
        pts = [MissionPoint(float(self.x[a]), float(self.y[a]), "trigger_on", number, a,
                            trigger)]
        if b != a:
            pts.append(MissionPoint(float(self.x[b]), float(self.y[b]), "photo", number, b))
        return pts

    def _ground_bases(self, runs: list[np.ndarray], h: np.ndarray) -> np.ndarray:
        """The distance between two exposures of each run on the ground (ellipsoid) [m]:
        the grid's step between its centres over the projection's scale factor along
        the run (a run of one photo: along one step of the heading ``h``)."""
        step = self.layout.base_m * float(self.layout.notes.get("grid_scale", 1.0))
        if not self.layout.area.georeferenced or not runs:
            return np.full(len(runs), step)
        tr, geod = self._geo()
        a = np.array([int(r[0]) for r in runs])
        b = np.array([int(r[-1]) for r in runs])
        one = a == b
        px, py = self.x[a], self.y[a]
        qx = np.where(one, px + step * h[0], self.x[b])
        qy = np.where(one, py + step * h[1], self.y[b])
        grid = np.hypot(qx - px, qy - py)
        lon, lat = tr.transform(np.r_[px, qx], np.r_[py, qy])
        lon, lat = np.asarray(lon, dtype=float), np.asarray(lat, dtype=float)
        n = len(runs)
        ground = np.asarray(geod.inv(lon[:n], lat[:n], lon[n:], lat[n:])[2], dtype=float)
        with np.errstate(divide="ignore", invalid="ignore"):
            return np.where(grid > 0, step * ground / grid, step)

    def _geo(self) -> tuple[Any, Any]:
        if self.geo is None:
            from pyproj import Geod, Transformer

            self.geo = (Transformer.from_crs(self.layout.area.plan_crs, 4326, always_xy=True),
                        Geod(ellps="WGS84"))
        return self.geo


def turn_path(p: np.ndarray, h: np.ndarray, q: np.ndarray, lead_m: float,
              kind: str) -> list[tuple[float, float]]:
    """The waypoints from a strip's last photo ``p`` (heading ``h``) to the next strip's
    first photo ``q`` (heading −h), ``q`` included, ``p`` not: the run-out, the turn, the
    run-in (:func:`scanplan.geo.lines.turn_length_m`)."""
    off = float((q - p) @ h)
    px, py, qx, qy, hx, hy = (float(v) for v in (p[0], p[1], q[0], q[1], h[0], h[1]))
    return turn_path_xy(px, py, hx, hy, qx, qy, off, lead_m, kind)


def turn_path_xy(px: float, py: float, hx: float, hy: float, qx: float, qy: float,
                 off: float, lead_m: float, kind: str) -> list[tuple[float, float]]:
    """:func:`turn_path` of Python floats: ``p`` (``px``, ``py``), the heading (``hx``,
    ``hy``), ``q`` (``qx``, ``qy``) and ``off``, how far ``q`` lies ahead of ``p`` along
    the heading ((q − p) · h) [m]."""
    nvx, nvy = (qx - px) - off * hx, (qy - py) - off * hy  # the across part of q − p
    d = float(np.hypot(nvx, nvy))
    nx, ny = (nvx / d, nvy / d) if d > 0 else (hy, -hx)
    ox, oy = px + (max(0.0, off) + lead_m) * hx, py + (max(0.0, off) + lead_m) * hy
    ix, iy = ox + d * nx, oy + d * ny  # the apex of the run-in

    def at(a: float, b: float) -> tuple[float, float]:  # local (across, along) → plan
        return ox + a * nx + b * hx, oy + a * ny + b * hy  # as apex_out + a·n + b·h

    def arc(ca: float, cb: float, r: float, a0: float, a1: float) -> list[tuple[float, float]]:
        return [at(ca + r * c, cb + r * s) for c, s in _arc_steps(a0, a1)]

    out: list[tuple[float, float]] = []
    if float(np.hypot(ox - px, oy - py)) > 1e-6:
        out.append(at(0.0, 0.0))
    if kind == "turnaround" or d == 0:
        out.append(at(d, 0.0))
    elif kind == "semicircle":
        out += arc(d / 2.0, 0.0, d / 2.0, math.pi, 0.0)
    else:  # a fixed wing's turn of radius r (Dubins)
        r = lead_m
        if d >= 2.0 * r:
            out += arc(r, 0.0, r, math.pi, math.pi / 2.0)
            out += arc(d - r, 0.0, r, math.pi / 2.0, 0.0)
        else:
            beta = math.acos((d / 2.0 + r) / (2.0 * r))
            y = 2.0 * r * math.sin(beta)
            out += arc(-r, 0.0, r, 0.0, beta)
            out += arc(d / 2.0, y, r, math.pi + beta, -beta)
            out += arc(d + r, 0.0, r, math.pi - beta, math.pi)
    if float(np.hypot(qx - ix, qy - iy)) > 1e-6:
        out.append((qx, qy))
    else:
        out[-1] = (qx, qy)
    return out


@functools.lru_cache(maxsize=1024)
def _arc_steps(a0: float, a1: float) -> tuple[tuple[float, float], ...]:
    """(cos t, sin t) of an arc's waypoints from angle ``a0`` to ``a1`` [rad], ``a0`` left
    out: equal steps of at most :data:`ARC_STEP_DEG` (a turn's arcs recur turn after turn)."""
    k = max(1, math.ceil(abs(math.degrees(a1 - a0)) / ARC_STEP_DEG))
    return tuple((math.cos(t), math.sin(t)) for t in np.linspace(a0, a1, k + 1)[1:].tolist())


Point = tuple[float, float]


def turns_trigger_off(starts: list[Point], paths: list[list[Point]], after_m: float
                      ) -> list[tuple[list[Point], Point, list[Point]]]:
    """Where each turn disarms the camera: for the turn from ``starts[i]`` (a strip's last
    photo) through the waypoints ``paths[i]`` (:func:`turn_path`), its waypoints before the
    trigger-off point, that point — ``after_m`` along the turn, at most half the way — and
    the waypoints after it, the last one (the next strip's first photo, which its run puts)
    and any on the trigger-off point itself left out [m]. The turns' legs are measured
    together (the turns of a layout, :func:`scanplan.geo.sorties.turn_penalties_m`).

    >>> turns_trigger_off([(0.0, 0.0)], [[(0.0, 10.0), (20.0, 10.0), (20.0, 0.0)]], 15.0)
    [([(0.0, 10.0)], (5.0, 10.0), [(20.0, 10.0)])]
    """
    rings = [[start, *path] for start, path in zip(starts, paths, strict=True)]
    xy = np.array([pt for ring in rings for pt in ring], dtype=float)
    legs = np.hypot(*np.diff(xy, axis=0).T).tolist()  # a ring's last to the next: unused
    cut: list[tuple[int, Point]] = []
    first = 0
    for ring in rings:
        seg = legs[first:first + len(ring) - 1]
        cum = [0.0, *itertools.accumulate(seg)]
        at = min(after_m, cum[-1] / 2.0)
        k = bisect.bisect_right(cum, at)  # the segment ending at point k
        k = min(max(k, 1), len(ring) - 1)
        t = (at - cum[k - 1]) / seg[k - 1] if seg[k - 1] > 0 else 0.0
        (x0, y0), (x1, y1) = ring[k - 1], ring[k]
        cut.append((k, (x0 + t * (x1 - x0), y0 + t * (y1 - y0))))
        first += len(ring)
    rest = [ring[k:-1] for ring, (k, _) in zip(rings, cut, strict=True)]
    pts = np.array([pt for r in rest for pt in r], dtype=float).reshape(-1, 2)
    offs = np.array([off for r, (_, off) in zip(rest, cut, strict=True) for _ in r],
                    dtype=float).reshape(-1, 2)
    apart = (np.hypot(pts[:, 0] - offs[:, 0], pts[:, 1] - offs[:, 1]) > 1e-6).tolist()
    out = []
    first = 0
    for ring, r, (k, off) in zip(rings, rest, cut, strict=True):
        after = [pt for pt, keep in zip(r, apart[first:first + len(r)], strict=True) if keep]
        out.append((ring[1:k], off, after))
        first += len(r)
    return out


def _with_trigger_off(p: np.ndarray, path: list[Point], after_m: float,
                      number: int, photo: int) -> list[MissionPoint]:
    """The turn's waypoints with the trigger-off point ``after_m`` along it from ``p`` (at
    most half the way; the last point, the next strip's first photo, is left out: its run
    puts it; :func:`turns_trigger_off`)."""
    [(before, off, after)] = turns_trigger_off([(float(p[0]), float(p[1]))], [path], after_m)
    pts = [MissionPoint(x, y, "turn", number, photo) for x, y in before]
    pts.append(MissionPoint(off[0], off[1], "trigger_off", number, photo, 0.0))
    pts += [MissionPoint(x, y, "turn", number, photo) for x, y in after]
    return pts

"""Sorties: the serpentine cut into flights of one battery each (docs/flight-lines.md).

The block is flown as one serpentine — strips, and the turns between them, in flight
order. Every exposure has a place on it: the path distance ``c`` from the first exposure
of the block. A sortie flies one stretch of it, from an exposure *a* to an exposure *b*
(whole strips, or a part of a strip at either end), and costs

    (c_b − c_a) + run-in + run-out + transit(take-off → run-in of a)
                + transit(run-out of b → take-off)

metres of flight, which must fit the battery: speed × the sortie's flight time. The
sorties are packed greedily: each one runs as far along the serpentine as the battery
allows and the next resumes at the next exposure. For a cost that grows with the stretch
this gives the fewest sorties for the flight order (the greedy cover of a line by
intervals); the packing bound — the serpentine's length divided by one battery — is what
no packing can beat, and the greedy one stays within a run-in, a run-out and the transit
of it per sortie. Without a take-off point the transit is not known and not counted (the
crew launches beside each sortie's run-in).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..i18n.messages import Message
from .layout import Sortie

__all__ = ["MAX_SORTIES", "SortiePlan", "pack_sorties"]

MAX_SORTIES = 1_000
"""Most sorties (beyond: not feasible)."""


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
    """

    exposure_sortie: np.ndarray
    strips: list[list[int]]
    length_m: list[float]
    transit_m: list[float]

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

    def records(self, speed_ms: float | None) -> tuple[Sortie, ...]:
        """The :class:`Sortie` records (times at ``speed_ms``)."""
        def time(m: float) -> float | None:
            if not speed_ms or speed_ms <= 0:
                return None
            t = m / speed_ms
            return t if math.isfinite(t) else None
        return tuple(Sortie(number=k + 1, strips=tuple(i + 1 for i in st), length_m=ln,
                            time_s=time(ln), transit_m=tr)
                     for k, (st, ln, tr) in enumerate(zip(self.strips, self.length_m,
                                                          self.transit_m, strict=True)))


def pack_sorties(path_m: np.ndarray, exposure_strip: np.ndarray, run_in_m: np.ndarray,
                 run_out_m: np.ndarray, *, lead_in_m: float, lead_out_m: float,
                 limit_m: float | None, max_minutes: float | None = None
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
        run-out after it back [m] (zeros without a take-off point).
    lead_in_m, lead_out_m : float
        Run-in before a sortie's first exposure and run-out after its last one [m].
    limit_m : float or None
        The flight length of one battery [m] (None: one sortie).
    max_minutes : float, optional
        The battery's flight time [min] (for the message).
    """
    n = len(path_m)
    fixed = lead_in_m + lead_out_m
    if n == 0:
        return SortiePlan(np.zeros(0, dtype=np.int64), [], [], []), None
    if limit_m is None or not math.isfinite(limit_m):
        length = float(path_m[-1] - path_m[0]) + fixed + float(run_in_m[0] + run_out_m[-1])
        return SortiePlan(np.zeros(n, dtype=np.int64),
                          [sorted(set(exposure_strip.tolist()))],
                          [length], [float(run_in_m[0] + run_out_m[-1])]), None
    sortie = np.zeros(n, dtype=np.int64)
    strips: list[list[int]] = []
    lengths: list[float] = []
    transits: list[float] = []
    a = 0
    while a < n:
        # Only exposures within one battery of path from ``a`` can end its sortie (the
        # cost never falls below the path flown): the work stays linear in exposures.
        end = a + int(np.searchsorted(path_m[a:], path_m[a] + limit_m - fixed, "right"))
        end = max(end, a + 1)
        cost = path_m[a:end] - path_m[a] + fixed + run_in_m[a] + run_out_m[a:end]
        fits = np.flatnonzero(cost <= limit_m)
        if not len(fits) or fits[0] != 0:
            return _failed(n, strips, lengths, transits), Message(
                "layout.sortie_cannot_reach", limit=max_minutes or 0.0,
                have=float(limit_m), need=float(cost[0]))
        b = a + int(fits[-1])
        sortie[a:b + 1] = len(strips)
        strips.append(sorted(set(exposure_strip[a:b + 1].tolist())))
        lengths.append(float(cost[b - a]))
        transits.append(float(run_in_m[a] + run_out_m[b]))
        if len(strips) > MAX_SORTIES:
            return _failed(n, strips, lengths, transits), Message(
                "layout.too_many_sorties", most=MAX_SORTIES, limit=max_minutes or 0.0)
        a = b + 1
    return SortiePlan(sortie, strips, lengths, transits), None


def _failed(n: int, strips: list[list[int]], lengths: list[float],
            transits: list[float]) -> SortiePlan:
    return SortiePlan(np.zeros(n, dtype=np.int64), strips or [[]], lengths or [0.0],
                      transits or [0.0])


def packing_bound(serpentine_m: float, limit_m: float) -> int:
    """The fewest sorties any packing can fly: the serpentine over one battery."""
    return max(1, math.ceil(serpentine_m / limit_m))

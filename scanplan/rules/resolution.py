"""The MTF ground resolution L of a UAV camera at many heights, solved once per camera chain.

A plan asks for L at the frame centre many times over: the maximum height for each limit
on L (a log grid of 257 heights, then three or four passes of 62 heights each), the
planned and highest flown heights, the 30 heights of the report's curve — and the page
re-plans on every edit with the same camera. Every value depends only on the camera chain
(camera, flight speed and exposure, atmosphere, motion, scene, threshold, the MTF
components registered) and the height: the solver treats every height on its own
(:func:`scanplan.core.mtf.solve_resolving_power`, no value depends on another element of
the array), so a value solved once is the value a new solve would give, bit for bit
(tests/test_uav_resolution.py). This module keeps them:

- :func:`centre_resolution_m` — L at the centre for some heights: those not yet solved for
  this chain are solved in one vectorised call, the rest are looked up;
- :func:`max_height_for_ground_resolution` — the search of :mod:`.uav` for the height
  where L reaches a limit, unchanged, over those remembered values; before each pass it
  solves, in the same call, the passes it expects next (from the values it has), so a
  search costs one or two solves instead of four or five. Its answer for a chain and a
  limit is kept too.

Nothing here changes a result; it only avoids solving the same equation twice.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from ..core import mtf as M
from ..errors import FieldValueError, InputError
from ..io.kept import MISSING, Kept, arrays_key
from .results import UavInputs

__all__ = ["FIGURES", "centre_resolution_m", "chain", "chain_key",
           "max_height_for_ground_resolution", "resolution_at"]

HEIGHT_GRID_POINTS = 257  # 1 m … 20 km in steps of 4 %
HEIGHT_PASS_POINTS = 62  # each refinement pass cuts the bracket 63-fold
HEIGHT_TOLERANCE_M = 1e-3
MAX_SEARCH_HEIGHT_M = 20_000.0
_MEMO_CHAINS = 16
"""Camera chains whose values are kept (the least recently used dropped beyond)."""
_MEMO_HEIGHTS = 8_192
"""Heights kept per chain (the chain's values are dropped beyond: a bound, not a policy)."""
_MEMO_BATCH = 1_024
"""Larger requests (every photo of a terrain plan) are solved in one call and kept whole
(:data:`_BATCHES`), not looked up height by height."""

_CHAIN_FIELDS = ("pixel_um", "focal_mm", "f_number", "sensor_width_mm", "sensor_height_mm",
                 "lens_table_centre", "lens_table_corner", "speed_ms", "exposure_s",
                 "shift_factor", "haze_contrast", "random_speed_ms", "roll_rate_rad_s",
                 "pitch_rate_rad_s", "yaw_rate_rad_s", "r_max", "r_min", "threshold_k0")
"""The inputs of :func:`scanplan.rules.uav._chain` besides the height."""


def chain(inp: UavInputs, height_m: Any) -> tuple[M.Camera, M.Flight, M.Atmosphere,
                                                  M.Motion, M.Scene, M.Threshold]:
    """The MTF chain's descriptions of ``inp`` at ``height_m`` [m]."""
    cam = M.Camera(inp.pixel_um, inp.focal_mm, inp.f_number, inp.sensor_width_mm,
                   inp.sensor_height_mm, lens_table_centre=inp.lens_table_centre,
                   lens_table_corner=inp.lens_table_corner)
    fl = M.Flight(height_m, inp.speed_ms, inp.exposure_s, inp.shift_factor)
    atm = M.Atmosphere(contrast_coefficient=inp.haze_contrast)
    mot = M.Motion(inp.random_speed_ms, inp.roll_rate_rad_s, inp.pitch_rate_rad_s,
                   inp.yaw_rate_rad_s)
    return cam, fl, atm, mot, M.Scene(inp.r_max, inp.r_min), M.Threshold(
        params={"k0": inp.threshold_k0})


_SEEN: dict[int, Any] = {}
"""Every MTF component a key named, kept alive so that its ``id`` is never another's."""


def chain_key(inp: UavInputs) -> tuple[Any, ...]:
    """What L depends on besides the height: the chain's inputs and the MTF components
    registered (a component registered or removed is another chain)."""
    for c in M.REGISTRY:
        _SEEN.setdefault(id(c), c)
    return (tuple(getattr(inp, f) for f in _CHAIN_FIELDS),
            tuple((c.name, id(c)) for c in M.REGISTRY))


_MEMO: Kept[tuple[Any, ...], dict[float, tuple[float, ...]]] = Kept(_MEMO_CHAINS)
_MAX_HEIGHTS: Kept[tuple[Any, ...], float] = Kept(4 * _MEMO_CHAINS)
_BATCHES: Kept[tuple[Any, ...], list[tuple[float, ...]]] = Kept(_MEMO_CHAINS)
"""Batches of more than :data:`_MEMO_BATCH` heights solved, by chain, image point and the
heights' bytes (a re-plan over the same ground asks the same photos' heights again)."""


def _memo(key: tuple[Any, ...]) -> dict[float, tuple[float, ...]]:
    return _MEMO.made(key, dict)


FIGURES = ("r_lpmm", "resolvable", "sensor_limited", "ground_resolution_m", "l_over_gsd")
"""What :func:`resolution_at` gives for each height (the figures of
:class:`scanplan.core.mtf.GroundResolution`)."""


def _solve(inp: UavInputs, heights_m: np.ndarray, field: str) -> list[tuple[float, ...]]:
    """:data:`FIGURES` at each of ``heights_m`` [m] (1-D) at one image point, one call."""
    try:
        g = M.ground_resolution(*chain(inp, heights_m), field=field)
    except FieldValueError as exc:  # the models name their field: a typed error
        raise InputError(exc.field, exc.message) from None
    n = heights_m.shape
    cols = [np.broadcast_to(np.asarray(a, dtype=float), n).tolist()
            for a in (g.r_lpmm, g.resolvable, g.resolving_power.sensor_limited,
                      g.ground_resolution_m, g.l_over_gsd)]
    return list(zip(*cols, strict=True))


def resolution_at(inp: UavInputs, heights_m: Any, field: str = "centre"
                  ) -> dict[str, np.ndarray]:
    """R, L and L/GSD at one image point for an array of heights, each solved once per
    camera chain.

    Heights solved before for the same chain and image point are looked up; the others
    are solved together in one vectorised call (seed 000: L = H/(2·R·f)).

    Parameters
    ----------
    inp : UavInputs
        Camera, flight and target (``height_m`` is ignored).
    heights_m : array_like
        Heights above ground [m], > 0.
    field : {"centre", "corner"}
        The image point (:func:`scanplan.core.mtf.ground_resolution`).

    Returns
    -------
    dict of ndarray
        :data:`FIGURES` → one value per height, the shape of ``heights_m``: R [lines/mm]
        and L [m] (NaN where nothing is resolved), ``resolvable`` and ``sensor_limited``
        (bool), L/GSD.

    Raises
    ------
    InputError
        Naming the field of an input the MTF models refuse.
    """
    h = np.asarray(heights_m, dtype=float)
    flat = h.ravel().tolist()
    if len(flat) > _MEMO_BATCH:  # every photo's own height: the batch is kept whole
        batch = (chain_key(inp), field, arrays_key(h))
        rows = _BATCHES.made(batch, lambda: _solve(inp, h.ravel(), field))
    else:
        values = _memo((chain_key(inp), field))
        missing = sorted({x for x in flat if x not in values})
        solved = (dict(zip(missing, _solve(inp, np.array(missing), field), strict=True))
                  if missing else {})
        rows = [values[x] if x in values else solved[x] for x in flat]
        if len(values) + len(solved) > _MEMO_HEIGHTS:
            values.clear()
        values.update(solved)
    cols = np.array(rows, dtype=float).reshape(len(flat), len(FIGURES)).T
    out = {name: col.reshape(h.shape) for name, col in zip(FIGURES, cols, strict=True)}
    for name in ("resolvable", "sensor_limited"):
        out[name] = out[name].astype(bool)
    return out


def centre_resolution_m(inp: UavInputs, heights_m: Any) -> np.ndarray:
    """The MTF ground resolution L at the frame centre for an array of heights [m]
    (:func:`resolution_at`): NaN where nothing is resolved, the shape of ``heights_m``."""
    return resolution_at(inp, heights_m)["ground_resolution_m"]


def _inner(lo: float, hi: float) -> np.ndarray:
    """The heights one pass of the search tries inside the bracket (lo, hi)."""
    return np.linspace(lo, hi, HEIGHT_PASS_POINTS + 2)[1:-1]


def _expected_passes(values: dict[float, tuple[float, ...]], limit_m: float, lo: float,
                     hi: float) -> list[float]:
    """The heights of the pass in the bracket (lo, hi) and of the passes after it, as the
    search will choose them if L crosses the limit where the values known so far say
    (linearly between the nearest heights known on either side of the crossing; the
    middle of the bracket where they say nothing)."""
    known = sorted((h, v[3]) for h, v in values.items()
                   if lo <= h <= hi and math.isfinite(v[3]))
    below = [(h, v) for h, v in known if v <= limit_m]
    above = [(h, v) for h, v in known if v > limit_m]
    guess = 0.5 * (lo + hi)
    if below and above:
        (h0, v0), (h1, v1) = below[-1], above[0]
        if h1 > h0 and v1 > v0:
            guess = h0 + (limit_m - v0) * (h1 - h0) / (v1 - v0)
    out: list[float] = []
    while hi - lo >= HEIGHT_TOLERANCE_M:
        inner = _inner(lo, hi)
        out.extend(inner.tolist())
        j = int(np.searchsorted(inner, guess, side="right"))  # the first to fail, expected
        if j >= len(inner):
            lo = float(inner[-1])
        else:
            hi = float(inner[j])
            if j > 0:
                lo = float(inner[j - 1])
    return out


def max_height_for_ground_resolution(inp: UavInputs, limit_m: float) -> float:
    """Highest height at which the centre L does not exceed ``limit_m``.

    Vectorised search: L on a log grid of heights from 1 m to the search ceiling in one
    call, then passes that cut the bracket of the *first* crossing 63-fold each, until
    it is narrower than 1 mm. L grows with height (tests/test_mtf.py); should it not,
    the first crossing is the safe answer. Where L is not resolvable it is taken as
    exceeding every limit. Returns 0 if even 1 m fails, the ceiling if nothing fails below
    it. Every height a pass tries is judged by its own solved L, as before; the values
    come from :func:`centre_resolution_m`, and each solve also takes the passes the search
    is expected to try next, so a search costs one or two solves (none when the chain's
    values are known), and the answer for a chain and a limit is kept.

    Parameters
    ----------
    inp : UavInputs
        Camera, flight and target.
    limit_m : float
        The largest ground resolution L allowed [m].

    Returns
    -------
    float
        The maximum height [m], within 1 mm below the crossing.
    """
    key = (chain_key(inp), float(limit_m))
    found = _MAX_HEIGHTS.get(key)
    if found is not MISSING:
        return found  # type: ignore[return-value]
    values = _memo((key[0], "centre"))

    def ok(heights_m: np.ndarray) -> np.ndarray:
        lr = centre_resolution_m(inp, heights_m)
        return np.isfinite(lr) & (lr <= limit_m)

    grid = np.geomspace(1.0, MAX_SEARCH_HEIGHT_M, HEIGHT_GRID_POINTS)
    fails = np.flatnonzero(~ok(grid))
    if fails.size == 0:
        result = MAX_SEARCH_HEIGHT_M
    elif fails[0] == 0:
        result = 0.0
    else:
        lo, hi = float(grid[fails[0] - 1]), float(grid[fails[0]])
        while hi - lo >= HEIGHT_TOLERANCE_M:
            inner = _inner(lo, hi)
            if any(x not in values for x in inner.tolist()):  # this pass and the next ones
                centre_resolution_m(inp, np.array(_expected_passes(values, limit_m, lo, hi)))
            fails = np.flatnonzero(~ok(inner))
            if fails.size == 0:
                lo = float(inner[-1])
            else:
                hi = float(inner[fails[0]])
                if fails[0] > 0:
                    lo = float(inner[fails[0] - 1])
        result = lo
    return _MAX_HEIGHTS.put(key, result)

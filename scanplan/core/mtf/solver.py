"""Resolving-power solver and ground resolution (seed 000)."""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
import numpy.typing as npt

from scanplan.core.checks import positive
from scanplan.core.mtf._base import (
    DEFAULT_GRID_POINTS,
    DEFAULT_ITERATIONS,
    NDArrayBool,
    NDArrayFloat,
)


@dataclass(frozen=True, eq=False)
class ResolvingPower:
    """Result of :func:`solve_resolving_power`.

    Attributes
    ----------
    r_lpmm : numpy.ndarray
        System resolving power R [lines/mm]; **NaN where not resolvable**.
    resolvable : numpy.ndarray of bool
        False where K_obj·T(0) ≤ K_thr(0): the object contrast is below the
        threshold even at the lowest frequencies; no resolving power exists.
    sensor_limited : numpy.ndarray of bool
        True where the curves do not cross below R_m, so R = R_m (Nyquist): the
        sensor's sampling, not the optics or motion, limits the resolution.
    nyquist_lpmm : numpy.ndarray
        R_m [lines/mm].
    """

    r_lpmm: NDArrayFloat
    resolvable: NDArrayBool
    sensor_limited: NDArrayBool
    nyquist_lpmm: NDArrayFloat


def solve_resolving_power(
    margin: Callable[[NDArrayFloat], NDArrayFloat],
    nyquist_lpmm: npt.ArrayLike,
    *,
    upper_lpmm: npt.ArrayLike | None = None,
    grid_points: int = DEFAULT_GRID_POINTS,
    iterations: int = DEFAULT_ITERATIONS,
    coarse_margin: Callable[[NDArrayFloat], NDArrayFloat] | None = None,
    polish: bool = True,
) -> ResolvingPower:
    """Vectorised first crossing of image contrast and threshold contrast.

    R = the smallest N in (0, R_m] with margin(N) = K(N) − K_thr(N) ≤ 0.

    Parameters
    ----------
    margin : callable
        ``margin(freq_lpmm) -> K − K_thr``. Called with an array whose last axis
        holds frequencies and whose leading axes broadcast against the configuration
        shape; must return the broadcast shape (configurations …, frequencies).
    nyquist_lpmm : array_like
        R_m per configuration [lines/mm].
    upper_lpmm : array_like, optional
        Search ceiling per configuration [lines/mm], capped at R_m. Pass the first
        zero of an oscillating component (motion sinc) so that the margin is
        monotone on the searched interval; a crossing is always found below it.
    grid_points : int, optional
        Points of the uniform bracketing grid on [0, ceiling], 0 included.
        Default 5.
    iterations : int, optional
        Refinement steps inside the bracket (Illinois regula falsi, every fourth
        step a bisection). Default 12.
    coarse_margin : callable, optional
        A cheaper version of ``margin`` (e.g. float32) used for the grid and the
        refinement steps. The decision "resolvable" is always taken with ``margin``
        at N = 0, and the root is always polished with ``margin``.
    polish : bool, optional
        Finish with one secant step of ``margin`` from the refined root (two
        evaluations; default True): exact to float64 round-off for a smooth margin.

    Returns
    -------
    ResolvingPower
        ``r_lpmm`` is NaN where not resolvable; ``sensor_limited`` flags R = R_m.

    Notes
    -----
    Spec formulas.md §3 (R = abscissa of the intersection of K(N) and K_thr(N),
    seed 000). No Python loop over configurations: the margin is evaluated once on
    the grid for all configurations, the first grid point with margin ≤ 0 brackets
    the first crossing, and a fixed number of vectorised steps refine it, keeping a
    sign-changing bracket (Illinois modification of regula falsi, with an
    interleaved bisection so the bracket also shrinks geometrically). For the
    built-in chain every component is non-increasing and K_thr increasing below the
    ceiling, so the crossing is unique; user tables that oscillate need a finer grid.

    Examples
    --------
    >>> solve_resolving_power(lambda n: 0.5 - n / 100.0, [80.0, 40.0]).r_lpmm.tolist()
    [50.0, 40.0]
    """
    if grid_points < 2:
        raise ValueError(f"grid_points must be >= 2 (got {grid_points})")
    rm = positive("nyquist_lpmm", nyquist_lpmm)
    ceiling = rm if upper_lpmm is None else np.minimum(rm, positive("upper_lpmm", upper_lpmm))
    fun = margin if coarse_margin is None else coarse_margin
    b = _bracket(margin, fun, ceiling, grid_points, coarse=coarse_margin is not None)
    lo, hi, f_lo, f_hi = _refine(fun, b, iterations)
    est = _regula_falsi_point(lo, hi, f_lo, f_hi)
    if polish:
        est = _polish(margin, est, lo, hi, b.ceiling, b.shape)
    shape = b.shape
    r = np.where(b.crossed, est, b.ceiling)
    resolvable = b.resolvable & (r > 0.0)  # a crossing at N = 0 resolves nothing
    sensor_limited = resolvable & (~b.crossed | (r >= np.broadcast_to(rm, shape) * (1 - 1e-12)))
    r = np.where(resolvable, r, np.nan)
    return ResolvingPower(r_lpmm=r, resolvable=resolvable, sensor_limited=sensor_limited,
                          nyquist_lpmm=np.array(np.broadcast_to(rm, shape), dtype=float))


@dataclass(frozen=True, eq=False)
class _Bracket:
    """The first grid interval [lo, hi] where the margin changes sign, per configuration."""

    shape: tuple[int, ...]
    ceiling: NDArrayFloat
    resolvable: NDArrayBool  # margin(0) > 0, decided with the exact margin
    crossed: NDArrayBool  # some grid point above 0 has margin <= 0
    lo: np.ndarray
    hi: np.ndarray
    f_lo: np.ndarray  # > 0 where a crossing exists
    f_hi: np.ndarray  # <= 0 where a crossing exists


def _bracket(margin: Callable[[NDArrayFloat], NDArrayFloat],
             fun: Callable[[NDArrayFloat], NDArrayFloat], ceiling: NDArrayFloat,
             grid_points: int, *, coarse: bool) -> _Bracket:
    """Evaluate ``fun`` once on a uniform grid [0, ceiling] for every configuration and
    bracket the first crossing (the first grid point with margin ≤ 0)."""
    x = np.linspace(0.0, 1.0, grid_points)
    grid = ceiling[..., None] * x
    m = np.asarray(fun(grid))
    shape = m.shape[:-1]
    grid = np.broadcast_to(grid.astype(m.dtype), m.shape)
    ceiling = np.broadcast_to(ceiling, shape)
    if not coarse:
        resolvable = m[..., 0] > 0.0
    else:
        m0 = np.asarray(margin(np.zeros((*shape, 1))), dtype=float)[..., 0]
        resolvable = np.broadcast_to(m0, shape) > 0.0
    below = m[..., 1:] <= 0.0
    idx = np.argmax(below, axis=-1)[..., None] + 1

    def at(a: np.ndarray, i: np.ndarray) -> np.ndarray:
        return np.take_along_axis(a, i, axis=-1)[..., 0]

    return _Bracket(shape=shape, ceiling=ceiling, resolvable=resolvable,
                    crossed=below.any(axis=-1), lo=at(grid, idx - 1), hi=at(grid, idx),
                    f_lo=at(m, idx - 1), f_hi=at(m, idx))


def _refine(fun: Callable[[NDArrayFloat], NDArrayFloat], b: _Bracket,
            iterations: int) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """Shrink every bracket by a fixed number of vectorised steps: Illinois regula falsi,
    every fourth step a bisection; returns (lo, hi, f_lo, f_hi) in float64."""
    shape = b.shape
    lo, hi, f_lo, f_hi = b.lo, b.hi, b.f_lo, b.f_hi
    s_lo = np.ones(shape, dtype=f_lo.dtype)  # Illinois weights of the end values
    s_hi = np.ones(shape, dtype=f_lo.dtype)
    kept = np.zeros(shape, dtype=np.int8)  # +1: hi kept last step, -1: lo kept
    for step in range(iterations):  # fixed count, vectorised over configurations
        if step % 4 == 3:
            mid = 0.5 * (lo + hi)
        else:
            g_lo, g_hi = s_lo * f_lo, s_hi * f_hi
            denom = g_lo - g_hi
            ok = denom > 0
            mid = np.where(ok, lo + g_lo * (hi - lo) / np.where(ok, denom, 1.0), 0.5 * (lo + hi))
            mid = np.clip(mid, lo, hi)
        f_mid = np.broadcast_to(np.asarray(fun(mid[..., None]))[..., 0], shape)
        pos = f_mid > 0.0
        s_hi = np.where(pos, np.where(kept == 1, 0.5 * s_hi, s_hi), 1.0)
        s_lo = np.where(pos, 1.0, np.where(kept == -1, 0.5 * s_lo, s_lo))
        lo, f_lo = np.where(pos, mid, lo), np.where(pos, f_mid, f_lo)
        hi, f_hi = np.where(pos, hi, mid), np.where(pos, f_hi, f_mid)
        kept = np.where(pos, 1, -1).astype(np.int8)
    return lo.astype(float), hi.astype(float), f_lo.astype(float), f_hi.astype(float)


def _regula_falsi_point(lo: np.ndarray, hi: np.ndarray, f_lo: np.ndarray,
                        f_hi: np.ndarray) -> np.ndarray:
    """The regula falsi point of each bracket (``lo`` where the end values do not
    straddle zero)."""
    denom = f_lo - f_hi
    ok = denom > 0
    return np.clip(np.where(ok, lo + f_lo * (hi - lo) / np.where(ok, denom, 1.0), lo), lo, hi)


def _polish(margin: Callable[[NDArrayFloat], NDArrayFloat], est: np.ndarray,
            lo: np.ndarray, hi: np.ndarray, ceiling: NDArrayFloat,
            shape: tuple[int, ...]) -> np.ndarray:
    """One float64 secant step of the exact ``margin`` from the refined root (two
    evaluations), kept within the bracket's width of ``est`` and within [0, ceiling]."""
    step_ = 1e-6 * ceiling
    pts = np.stack([est, est + step_], axis=-1)
    fp = np.broadcast_to(np.asarray(margin(pts), dtype=float), (*shape, 2))
    slope = (fp[..., 1] - fp[..., 0]) / step_
    ok = slope < 0
    polished = est - fp[..., 0] / np.where(ok, slope, -1.0)
    width = np.maximum(hi - lo, 4.0 * step_)
    est = np.where(ok, np.clip(polished, est - width, est + width), est)
    return np.clip(est, 0.0, ceiling)


def ground_resolution_m(
    height_m: npt.ArrayLike, r_lpmm: npt.ArrayLike, focal_mm: npt.ArrayLike
) -> NDArrayFloat:
    """Ground resolution (linear resolution on the ground, LRM) L = H / (2·R·f).

    Parameters
    ----------
    height_m : array_like
        Flight height H [m].
    r_lpmm : array_like
        System resolving power R [lines/mm]; NaN (not resolvable) propagates.
    focal_mm : array_like
        Focal length f [mm].

    Returns
    -------
    numpy.ndarray
        L [m]: the smallest ground detail imaged separately. NaN where R is NaN.

    Notes
    -----
    Seed 000, the formula before eq. 1 (L = H/(2Rf)). Same quantity as seed 001's
    A = Mc/(2R) with Mc = H/f.

    Examples
    --------
    >>> round(float(ground_resolution_m(300.0, 40.0, 50.0)), 4)
    0.075
    """
    h = positive("height_m", height_m)
    f = positive("focal_mm", focal_mm)
    r = np.asarray(r_lpmm, dtype=float)
    if np.any(r <= 0):
        raise ValueError("r_lpmm must be > 0 (got a value <= 0)")
    return h / (2.0 * r * f)

"""One photographing height per block: the ground height range rule.

ГОСТ Р 59328-2021 «Аэрофотосъемка топографическая. Технические требования», §6.2.1 (read
in its second draft, «Проект, 2-ая редакция»): a survey object may be divided into blocks
(съемочные участки); within a block flown at one height the ground height range ΔH
(buildings included in built-up areas) must not exceed 7 % of the photographing height H_ф
on flat terrain, 15 % on hilly and 25 % in mountains, unless the flight follows the terrain.
The percentages are norm parameters (``block_relief_flat_pct``, ``block_relief_hilly_pct``,
``block_relief_mountain_pct``); the bundled sets carry the draft's numbers, marked so.

The check takes any array of ground elevations — the two ends of ``[terrain]
ground_elevation_m``, or samples of a DEM — so the terrain layer can call it unchanged.
Pure numpy, no I/O.

>>> c = block_height_check([100.0, 108.0], 100.0, "flat", 7.0)
>>> c.range_pct, c.split_needed, c.blocks
(8.0, True, 2)
>>> block_height_check([100.0, 106.0], 100.0, "flat", 7.0).split_needed
False
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike

__all__ = ["RELIEF_CLASSES", "BlockHeightCheck", "block_bands", "block_height_check"]

RELIEF_CLASSES = ("flat", "hilly", "mountainous")
"""Relief classes of §6.2.1: равнинная, всхолмлённая, горная местность."""


@dataclass(frozen=True)
class BlockHeightCheck:
    """The ground height range of a block against the one-height rule.

    Attributes
    ----------
    relief_class : str
        ``flat``, ``hilly`` or ``mountainous``.
    limit_pct : float
        Largest range for one photographing height [% of H].
    flight_height_m : float
        Photographing height above the ground the plan is designed for [m].
    ground_min_m, ground_max_m : float
        Lowest and highest ground (buildings included) [m].
    range_m, range_pct : float
        ΔH [m] and ΔH / H [%].
    allowed_range_m : float
        limit_pct × H [m].
    split_needed : bool
        ΔH exceeds the limit: split the block or fly it at several heights.
    blocks : int
        Fewest height bands of at most ``allowed_range_m`` each that cover the range
        (1 when no split is needed).
    bands_m : tuple of (float, float)
        The ground height bands of those blocks, lowest first [m]: each can be flown at one
        height (its photographing height measured from its own ground).
    samples : int
        How many ground elevations were checked.
    """

    relief_class: str
    limit_pct: float
    flight_height_m: float
    ground_min_m: float
    ground_max_m: float
    range_m: float
    range_pct: float
    allowed_range_m: float
    split_needed: bool
    blocks: int
    bands_m: tuple[tuple[float, float], ...]
    samples: int


def block_height_check(ground_elevations_m: ArrayLike, flight_height_m: float,
                       relief_class: str, limit_pct: float) -> BlockHeightCheck:
    """Check the ground height range of a block flown at one height (ГОСТ Р 59328-2021
    §6.2.1, second draft).

    Parameters
    ----------
    ground_elevations_m : array_like
        Ground elevations in the block [m]: the lowest and highest ground, or DEM samples
        (NaN = no data, ignored).
    flight_height_m : float
        Photographing height above the ground [m], > 0.
    relief_class : {"flat", "hilly", "mountainous"}
        The relief class of the block (a project parameter).
    limit_pct : float
        The norm's largest range for the class [% of the flight height], > 0.

    Returns
    -------
    BlockHeightCheck

    Raises
    ------
    ValueError
        For an unknown relief class, a height or limit ≤ 0, or no finite elevation.

    Notes
    -----
    ΔH = max(z) − min(z) must satisfy ΔH ≤ (limit / 100)·H. When it does not, the block is
    cut into n = ⌈ΔH / ((limit / 100)·H)⌉ bands of ground height, each flown at its own
    height; the bands are equal, starting at the lowest ground.
    """
    if relief_class not in RELIEF_CLASSES:
        raise ValueError(f"relief class must be one of {', '.join(RELIEF_CLASSES)} "
                         f"(got {relief_class!r})")
    h = float(flight_height_m)
    lim = float(limit_pct)
    if not (h > 0 and math.isfinite(h)):
        raise ValueError(f"flight height must be a finite number > 0 m (got {h!r})")
    if not (lim > 0 and math.isfinite(lim)):
        raise ValueError(f"limit must be a finite number > 0 % (got {lim!r})")
    z = np.asarray(ground_elevations_m, dtype=np.float64).ravel()
    z = z[np.isfinite(z)]
    if z.size == 0:
        raise ValueError("no finite ground elevation to check")
    lo, hi = float(z.min()), float(z.max())
    rng = hi - lo
    allowed = lim / 100.0 * h
    # a relative tolerance keeps a range exactly at the limit within it
    over = rng > allowed * (1.0 + 1e-12)
    n = max(1, math.ceil(rng / allowed - 1e-12)) if over else 1
    step = rng / n
    bands = tuple((lo + i * step, lo + (i + 1) * step if i < n - 1 else hi) for i in range(n))
    return BlockHeightCheck(relief_class, lim, h, lo, hi, rng, 100.0 * rng / h, allowed,
                            bool(over), n, bands, int(z.size))


def block_bands(ground_elevations_m: ArrayLike, check: BlockHeightCheck) -> np.ndarray:
    """Which sub-block each ground elevation belongs to: where the block is split.

    Parameters
    ----------
    ground_elevations_m : array_like
        Ground elevations [m], any shape (a DEM's cells: the result maps them to
        sub-blocks).
    check : BlockHeightCheck
        The result of :func:`block_height_check` on the block.

    Returns
    -------
    ndarray of int
        The band index (0 = lowest ground) per elevation, same shape; −1 for NaN.

    >>> c = block_height_check([100.0, 116.0], 100.0, "flat", 7.0)
    >>> block_bands([100.0, 105.0, 109.0, 116.0, float("nan")], c).tolist()
    [0, 0, 1, 2, -1]
    """
    z = np.asarray(ground_elevations_m, dtype=np.float64)
    inner = np.array([hi for _, hi in check.bands_m[:-1]], dtype=np.float64)
    out = np.digitize(z, inner, right=True).astype(np.int64)
    return np.where(np.isfinite(z), out, -1)

"""One strip and the turns between strips: the arithmetic the layout (:mod:`.lines`) and
the "auto" direction's search (:mod:`.direction`) share.

- :class:`Turn` and :func:`turn_length_m` — the path between two strips (a semicircle, a
  multirotor's turnaround, a fixed wing's turn of a radius, :func:`turn_radius_m`);
- the exposures of a photographed part of a strip (ceil(L/B) + 1, and the extension
  exposures past each end whose footprint still reaches into the part), each strip's first
  and last exposure, and the connections of a serpentine.

docs/flight-lines.md describes the model.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..core import flight as FL

__all__ = ["G_MS2", "MAX_STRIPS", "Turn", "run_sums", "turn_length_m", "turn_radius_m"]

G_MS2 = 9.80665
"""Standard gravity [m/s²] (CGPM 1901)."""
MAX_STRIPS = 100_000
"""Most strips a layout computes (beyond: not feasible)."""


@dataclass(frozen=True)
class Turn:
    """How the aircraft turns between strips.

    ``kind``: ``"semicircle"`` (a half circle across the line spacing), ``"turnaround"``
    (multirotor: ``value_m`` flown past the strip end, across, and back in) or ``"radius"``
    (fixed-wing: turn radius ``value_m``).
    """

    kind: str = "semicircle"
    value_m: float = 0.0

    def describe(self) -> str:
        """``semicircle``, ``turnaround 20 m``, ``radius 150 m`` (for reports)."""
        return self.kind if self.kind == "semicircle" else f"{self.kind} {self.value_m:g} m"

    @property
    def lead_m(self) -> float:
        """The straight flown on the line before its first exposure and past its last
        (run-in and run-out) [m]: a multirotor's turnaround, a fixed wing's turn radius (it
        is on the line, wings level, before the camera fires); none for the semicircle."""
        return 0.0 if self.kind == "semicircle" else float(self.value_m)


def turn_radius_m(speed_ms: float, bank_deg: float) -> float:
    """Radius of a level coordinated turn, r = v²/(g·tan φ) [m].

    Parameters
    ----------
    speed_ms : float
        True airspeed ≈ ground speed in still air [m/s].
    bank_deg : float
        Bank angle φ [°], 0 < φ < 90.

    Notes
    -----
    FAA, *Pilot's Handbook of Aeronautical Knowledge* (FAA-H-8083-25C, 2023), ch. 5
    "Aerodynamics of Flight", forces in turns: the horizontal lift component L·sin φ is the
    centripetal force m·v²/r while L·cos φ = m·g.
    """
    return speed_ms ** 2 / (G_MS2 * math.tan(math.radians(bank_deg)))


def turn_length_m(across_m: np.ndarray, offset_m: np.ndarray, turn: Turn) -> np.ndarray:
    """Path flown from the end of one strip to the start of the next [m].

    Parameters
    ----------
    across_m : array_like
        Distance between the two lines [m].
    offset_m : array_like
        Difference of the two strip ends along the lines [m] (flown straight).
    turn : Turn
        The turn pattern; a fixed wing's includes the run-out and the run-in of one turn
        radius each (:attr:`Turn.lead_m`), a multirotor's the turnaround out and back.
    """
    d = np.asarray(across_m, dtype=float)
    off = np.abs(np.asarray(offset_m, dtype=float))
    if turn.kind == "semicircle":
        return np.pi * d / 2.0 + off
    if turn.kind == "turnaround":
        return 2.0 * turn.value_m + d + off
    if turn.kind == "radius":
        r = turn.value_m
        wide = np.pi * r + (d - 2.0 * r)
        beta = np.arccos(np.clip((d / 2.0 + r) / (2.0 * r), -1.0, 1.0))
        omega = r * (np.pi + 4.0 * beta)
        return np.where(d >= 2.0 * r, wide, omega) + off + 2.0 * r  # run-out, run-in
    raise ValueError(f"turn kind must be semicircle, turnaround or radius (got {turn.kind!r})")


class _Extension(int):
    """Exposures past each end of a part (the int), and how far along the line a photo's
    footprint reaches from its centre [m] (``reach_m``): an extension exposure is kept only
    while its footprint reaches into the part — one that misses the area adds no coverage."""

    reach_m: float

    def __new__(cls, bases: int, reach_m: float) -> _Extension:
        obj = int.__new__(cls, bases)
        obj.reach_m = reach_m if math.isfinite(reach_m) and reach_m > 0 else math.inf
        return obj


def run_sums(values: np.ndarray, starts: np.ndarray, lengths: np.ndarray) -> np.ndarray:
    """``np.sum(values[a:a + n])`` of each run (a, n), to the last bit, in one call per
    distinct length: the runs of one length are summed as the rows of one array, which
    numpy sums as it sums each row alone (its pairwise sum along the row; tested over
    lengths up to 3,000 in tests/test_turn_times.py). A run of length 0 sums to 0.

    Parameters
    ----------
    values : ndarray
        1-D, float.
    starts, lengths : ndarray of int
        Each run's first index and its length.

    Returns
    -------
    ndarray
        One sum per run.
    """
    values = np.asarray(values, dtype=float)
    starts = np.asarray(starts, dtype=np.int64)
    lengths = np.asarray(lengths, dtype=np.int64)
    out = np.zeros(len(starts))
    for n in sorted(set(lengths.tolist()) - {0}):  # (np.unique would import numpy.ma)
        sel = np.flatnonzero(lengths == n)
        out[sel] = np.add.reduce(values[starts[sel, None] + np.arange(n)], axis=1)
    return out


def _photos_per_part(length_m: np.ndarray, base_m: float, extension: int) -> np.ndarray:
    """ceil(L/B) + 1 + 2e' exposures: e' ≤ e extension exposures past each end, those whose
    footprint still reaches into the part (j·B < reach − δ, δ the core's overhang past the
    part's end, ((n₀ − 1)·B − L)/2)."""
    length = np.maximum(length_m, 1e-300)
    core = FL.photos_per_strip(length, base_m, 0)
    reach = getattr(extension, "reach_m", math.inf)
    if not int(extension) or not math.isfinite(reach):
        return core + 2 * int(extension)
    delta = ((core - 1) * base_m - length) / 2.0
    kept = np.clip(np.ceil((reach - delta) / base_m) - 1, 0, int(extension)).astype(np.int64)
    return core + 2 * kept


def _strip_spans(strip: np.ndarray, lo: np.ndarray, hi: np.ndarray, base_m: float,
                 extension: int, n_strips: int) -> tuple[np.ndarray, ...]:
    """Per part: photos, first and last exposure along v; per strip: first/last exposure."""
    n = _photos_per_part(hi - lo, base_m, extension)
    half = (n - 1) * base_m / 2.0
    mid = (lo + hi) / 2.0
    first, last = mid - half, mid + half
    s_lo = np.full(n_strips, np.inf)
    s_hi = np.full(n_strips, -np.inf)
    np.minimum.at(s_lo, strip, first)
    np.maximum.at(s_hi, strip, last)
    return n, first, last, s_lo, s_hi


def _connections(u: np.ndarray, s_lo: np.ndarray, s_hi: np.ndarray, turn: Turn
                 ) -> np.ndarray:
    """Path between strip i and i + 1 (serpentine: strip 0 flown +v) [m]."""
    if len(u) < 2:
        return np.zeros(0)
    forward = (np.arange(len(u) - 1) % 2) == 0  # strip i flown +v ends at its top
    end_i = np.where(forward, s_hi[:-1], s_lo[:-1])
    start_next = np.where(forward, s_hi[1:], s_lo[1:])
    return turn_length_m(np.diff(u), start_next - end_i, turn)

"""The turns between strips: the path flown from the end of one strip to the start of the
next (a semicircle, a multirotor's turnaround, a fixed wing's turn of a radius,
:func:`turn_radius_m`), shared by the layout (:mod:`.lines`) and its sorties.

docs/flight-lines.md describes the model.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

__all__ = ["G_MS2", "Turn", "turn_length_m", "turn_radius_m"]

G_MS2 = 9.80665
"""Standard gravity [m/s²] (CGPM 1901)."""

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

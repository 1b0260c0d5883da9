"""The domain of every numeric input: the range in which scanplan's models are meant to run.

These are not norms (the Instruction's numbers live in ``norms/``); they are the honest
limits of the inputs a mapping contract can have, wide enough for every real job
(1:500 … 1:25000 maps, 1:100000 photos, 1 µm pixels, 2 km flying heights and more) and
narrow enough that no formula overflows or divides by nothing. An input outside its
domain is refused with the input named and the range stated, never carried into a NaN,
an infinity or a numpy warning. ``docs/input-ranges.md`` lists them (a test keeps it in
step).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from ..errors import InputError

__all__ = ["DOMAINS", "HINTS", "MAX_LIST_ITEMS", "Domain", "check_domain", "check_range"]

MAX_LIST_ITEMS = 100
"""Most values of a repeated input (photo scales of a sweep, scan pixels to check)."""


@dataclass(frozen=True)
class Domain:
    """An interval of allowed values (``lo < x`` or ``lo ≤ x``; ``x ≤ hi`` or ``x < hi``)."""

    lo: float
    hi: float
    unit: str = ""
    lo_open: bool = False
    hi_open: bool = False
    meaning: str = ""


DOMAINS: dict[str, Domain] = {
    # map and photos
    "map_scale": Domain(100, 1_000_000, meaning="map scale denominator Mk"),
    "photo_scale": Domain(100, 1_000_000, meaning="photo scale denominator Mc"),
    "relief_interval_m": Domain(0.01, 1000, "m", meaning="relief (contour) interval h_c"),
    # film camera, scanning
    "focal_mm": Domain(1, 2000, "mm", meaning="focal length"),
    "frame_width_mm": Domain(1, 1000, "mm", meaning="frame side across track"),
    "frame_along_mm": Domain(1, 1000, "mm", meaning="frame side along track"),
    "resolving_power_lpmm": Domain(1, 2000, "lines/mm", meaning="resolving power of the photos R"),
    "forward_overlap_pct": Domain(50, 100, "%", hi_open=True, meaning="forward overlap"),
    "side_overlap_pct": Domain(10, 100, "%", hi_open=True, meaning="side overlap"),
    "scanner": Domain(0.1, 1000, "µm", meaning="scanner step"),
    "pixel_um": Domain(0.1, 1000, "µm", meaning="pixel size (scan pixel or sensor pitch)"),
    "bands": Domain(1, 16, meaning="bands per scanned frame"),
    "bits_per_band": Domain(1, 32, meaning="bits per band"),
    # the object to interpret and the rules
    "object_size_m": Domain(0.001, 1000, "m", meaning="size of the object to interpret"),
    "shape": Domain(0, 100, lo_open=True, meaning="shape coefficient B"),
    "probability": Domain(0.01, 0.999, meaning="required recognition probability"),
    "pr_coefficient": Domain(0.05, 2, meaning="k_R in P_R = k_R/R"),
    # digital camera and flight
    "f_number": Domain(0.5, 128, meaning="working f-number"),
    "sensor_width_mm": Domain(0.1, 1000, "mm", meaning="sensor side across track"),
    "sensor_height_mm": Domain(0.1, 1000, "mm", meaning="sensor side along track"),
    "height_m": Domain(1, 20_000, "m", meaning="flight height above ground"),
    "max_height_m": Domain(1, 20_000, "m",
                           meaning="altitude ceiling: highest height flown above ground"),
    "gsd_cm": Domain(0.01, 1000, "cm", meaning="target ground sample distance"),
    "parallax_error_px": Domain(0.01, 10, "px", lo_open=False,
                                meaning="RMS error of a measured x-parallax (σ_px)"),
    "height_tolerance_up_pct": Domain(0, 100, "%", hi_open=True,
                                      meaning="how much higher the UAV may fly"),
    "height_tolerance_down_pct": Domain(0, 100, "%", hi_open=True,
                                        meaning="how much lower the UAV may fly"),
    "exposure_s": Domain(1e-6, 10, "s", meaning="exposure time"),
    "speed_ms": Domain(0, 500, "m/s", meaning="ground speed"),
    "random_speed_ms": Domain(0, 100, "m/s", meaning="RMS random linear speed"),
    "roll_rate_rad_s": Domain(0, 10, "rad/s", meaning="RMS roll rate"),
    "pitch_rate_rad_s": Domain(0, 10, "rad/s", meaning="RMS pitch rate"),
    "yaw_rate_rad_s": Domain(0, 10, "rad/s", meaning="RMS yaw rate"),
    "roll_deg": Domain(-45, 45, "°", meaning="roll for the tilted-frame corner GSD"),
    "pitch_deg": Domain(-45, 45, "°", meaning="pitch for the tilted-frame corner GSD"),
    "haze_contrast": Domain(0, 1, lo_open=True,
                            meaning="contrast transmission of the air column (haze)"),
    "threshold_k0": Domain(0, 1, lo_open=True, hi_open=True,
                           meaning="sensor threshold contrast at low frequency"),
    "shift_factor": Domain(0, 1, lo_open=True,
                           meaning="photographic/geometric image shift factor"),
    "r_max": Domain(0, 1, lo_open=True, meaning="brightness coefficient of the lightest detail"),
    "r_min": Domain(0, 1, meaning="brightness coefficient of the darkest detail"),
    "area_width_m": Domain(0, 1_000_000, "m", lo_open=True, meaning="block width"),
    "area_length_m": Domain(0, 1_000_000, "m", lo_open=True, meaning="block length"),
}
"""Input name → its domain. The names are the Python names of the inputs; the command line
and the project file map them to their options and keys."""

HINTS: dict[str, str] = {
    "forward_overlap_pct": "a percentage, e.g. 60 (film) or 80 (UAV), not a fraction like "
                           "0.8; under 50 % a point is on one photo only: no stereo model",
    "side_overlap_pct": "a percentage, e.g. 30 (film) or 60 (UAV), not a fraction like "
                        "0.6; under 10 % any drift leaves gaps between the strips",
}
"""Why a domain is what it is, added to the message when a value falls outside it."""


def _bound(x: float) -> str:
    """``1000000`` rather than ``1e+06``; ``0.01`` as is."""
    if float(x).is_integer() and abs(x) < 1e15:
        return str(int(x))
    return f"{x:g}"


def check_range(name: str, value: float | None, *, lo: float | None = None,
                hi: float | None = None, lo_open: bool = True, hi_open: bool = False,
                unit: str = "") -> None:
    """Raise :class:`InputError` naming ``name`` unless ``value`` is finite and in range.

    ``lo``/``hi`` are exclusive when ``lo_open``/``hi_open`` (default: > lo, ≤ hi).

    Parameters
    ----------
    name : str
        The input's name (the error's ``field``).
    value : float or None
        The value to check; None, bools, NaN and infinities are refused.
    lo, hi : float, optional
        The bounds.
    lo_open, hi_open : bool
        Whether the bounds are exclusive.
    unit : str
        Unit named in the message.
    """
    ok = isinstance(value, int | float) and not isinstance(value, bool)
    try:
        ok = ok and math.isfinite(value)  # type: ignore[arg-type]
    except OverflowError:  # an integer too large for a float
        ok = False
    if ok and lo is not None:
        ok = value > lo if lo_open else value >= lo
    if ok and hi is not None:
        ok = value < hi if hi_open else value <= hi
    if not ok:
        parts = []
        if lo is not None:
            parts.append(f"{'>' if lo_open else '≥'} {_bound(lo)}")
        if hi is not None:
            parts.append(f"{'<' if hi_open else '≤'} {_bound(hi)}")
        rng = " and ".join(parts)
        try:
            shown = repr(value)
        except ValueError:  # over Python's 4,300-digit limit
            shown = "a number of more than 4,300 digits"
        raise InputError(name, f"must be a finite number {rng}{' ' + unit if unit else ''} "
                               f"(got {shown[:200]})")


def check_domain(name: str, value: float | None, domain: str | None = None) -> None:
    """Raise :class:`InputError` naming ``name`` unless ``value`` lies in its domain.

    Parameters
    ----------
    name : str
        The input's name (the error's ``field``).
    value : float or None
        The value to check.
    domain : str, optional
        The key of :data:`DOMAINS` when it differs from ``name``.
    """
    d = DOMAINS[domain or name]
    try:
        check_range(name, value, lo=d.lo, hi=d.hi, lo_open=d.lo_open, hi_open=d.hi_open,
                    unit=d.unit)
    except InputError as exc:
        hint = HINTS.get(domain or name)
        if hint is None:
            raise
        raise InputError(exc.field, f"{exc.message}: {hint}") from None

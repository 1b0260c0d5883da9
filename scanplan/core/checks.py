"""Input checks of the numeric core: a value as a float array, or a typed error.

Every formula of :mod:`scanplan.core` checks its physical inputs through these functions,
so a bad input raises :class:`~scanplan.errors.FieldValueError` (a ValueError) carrying
the input's name as its ``field`` and the first bad element: ``"pixel_um must be > 0
(got -1)"``. They broadcast over arrays like the formulas and do no I/O.
"""

from __future__ import annotations

import math

import numpy as np
import numpy.typing as npt

from ..errors import FieldValueError

__all__ = ["finite", "in_range", "nonnegative", "positive"]

NDArrayFloat = npt.NDArray[np.float64]


def _first_bad(arr: np.ndarray, bad: np.ndarray) -> str:
    value = np.broadcast_to(arr, bad.shape)[bad].flat[0]
    return f"{float(value):g}"


def _number(name: str, value: object) -> float | None:
    """A plain Python ``float`` or ``int`` as a finite float (None for anything else): the
    formulas' scalar inputs, checked without numpy's array passes (the same value, the same
    error)."""
    if type(value) is not float and type(value) is not int:
        return None
    x = float(value)  # type: ignore[arg-type]
    if not math.isfinite(x):
        raise FieldValueError(name, f"must be finite (got {x:g})")
    return x


def finite(name: str, value: npt.ArrayLike) -> NDArrayFloat:
    """``value`` as a float array, every element finite.

    Parameters
    ----------
    name : str
        The input's name (the error's ``field``).
    value : array_like
        The input.

    Returns
    -------
    ndarray
        ``value`` as float64.

    Raises
    ------
    FieldValueError
        An element is NaN or infinite.

    Examples
    --------
    >>> finite("height_m", [100, 120]).tolist()
    [100.0, 120.0]
    """
    x = _number(name, value)
    if x is not None:
        return np.asarray(x)
    arr = np.asarray(value, dtype=float)
    bad = ~np.isfinite(arr)
    if bad.any():
        raise FieldValueError(name, f"must be finite (got {_first_bad(arr, bad)})")
    return arr


def positive(name: str, value: npt.ArrayLike) -> NDArrayFloat:
    """``value`` as a float array, every element finite and > 0.

    Parameters
    ----------
    name : str
        The input's name (the error's ``field``).
    value : array_like
        The input.

    Returns
    -------
    ndarray
        ``value`` as float64.

    Raises
    ------
    FieldValueError
        An element is not finite or not above zero.

    Examples
    --------
    >>> positive("pixel_um", -1)
    Traceback (most recent call last):
    ...
    scanplan.errors.FieldValueError: pixel_um must be > 0 (got -1)
    """
    x = _number(name, value)
    if x is not None and x > 0:
        return np.asarray(x)
    arr = finite(name, value)
    bad = ~(arr > 0)
    if bad.any():
        raise FieldValueError(name, f"must be > 0 (got {_first_bad(arr, bad)})")
    return arr


def nonnegative(name: str, value: npt.ArrayLike) -> NDArrayFloat:
    """``value`` as a float array, every element finite and >= 0.

    Parameters
    ----------
    name : str
        The input's name (the error's ``field``).
    value : array_like
        The input.

    Returns
    -------
    ndarray
        ``value`` as float64.

    Raises
    ------
    FieldValueError
        An element is not finite or below zero.

    Examples
    --------
    >>> float(nonnegative("wind_ms", 0))
    0.0
    """
    x = _number(name, value)
    if x is not None and x >= 0:
        return np.asarray(x)
    arr = finite(name, value)
    bad = ~(arr >= 0)
    if bad.any():
        raise FieldValueError(name, f"must be >= 0 (got {_first_bad(arr, bad)})")
    return arr


def in_range(
    name: str,
    value: npt.ArrayLike,
    low: float,
    high: float,
    *,
    low_inclusive: bool = True,
    high_inclusive: bool = True,
) -> NDArrayFloat:
    """``value`` as a float array, every element finite and within [low, high].

    Parameters
    ----------
    name : str
        The input's name (the error's ``field``).
    value : array_like
        The input.
    low, high : float
        The bounds.
    low_inclusive, high_inclusive : bool
        Whether each bound itself is allowed (default: both).

    Returns
    -------
    ndarray
        ``value`` as float64.

    Raises
    ------
    FieldValueError
        An element is not finite or outside the bounds.

    Examples
    --------
    >>> in_range("forward_overlap_pct", 100, 0, 100, high_inclusive=False)
    Traceback (most recent call last):
    ...
    scanplan.errors.FieldValueError: forward_overlap_pct must be in [0, 100) (got 100)
    """
    x = _number(name, value)
    if x is not None and (x >= low if low_inclusive else x > low) and \
            (x <= high if high_inclusive else x < high):
        return np.asarray(x)
    arr = finite(name, value)
    ok_low = arr >= low if low_inclusive else arr > low
    ok_high = arr <= high if high_inclusive else arr < high
    bad = ~(ok_low & ok_high)
    if bad.any():
        lo = "[" if low_inclusive else "("
        hi = "]" if high_inclusive else ")"
        raise FieldValueError(
            name, f"must be in {lo}{low:g}, {high:g}{hi} (got {_first_bad(arr, bad)})"
        )
    return arr

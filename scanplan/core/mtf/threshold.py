"""Object contrast and the threshold-contrast models (pluggable)."""

from __future__ import annotations

from collections.abc import Callable
from typing import Any, Literal

import numpy as np
import numpy.typing as npt

from scanplan.core.checks import in_range, nonnegative, positive
from scanplan.core.mtf._base import DEFAULT_K0, NDArrayFloat
from scanplan.errors import FieldValueError, pick_method


def object_contrast(r_max: npt.ArrayLike, r_min: npt.ArrayLike) -> NDArrayFloat:
    """Object contrast K_obj = (r_max − r_min) / (r_max + r_min).

    Parameters
    ----------
    r_max : array_like
        Spectral brightness coefficient of the lightest detail [–], > 0.
    r_min : array_like
        Spectral brightness coefficient of the darkest detail [–], 0 ≤ r_min ≤ r_max.

    Returns
    -------
    numpy.ndarray
        Michelson contrast in [0, 1].

    Notes
    -----
    Seed 000, the unnumbered formula after the definition of R ("Контраст объекта
    съемки … определяется по формуле"); its printed form is lost in extraction and
    restated in spec formulas.md §3.

    Examples
    --------
    >>> round(float(object_contrast(0.3, 0.1)), 4)
    0.5
    """
    rmax = positive("r_max", r_max)
    rmin = nonnegative("r_min", r_min)
    if np.any(rmin > rmax):
        bad = np.broadcast_to(rmin, np.broadcast(rmin, rmax).shape)[
            np.broadcast_to(rmin > rmax, np.broadcast(rmin, rmax).shape)
        ]
        raise FieldValueError("r_min", f"must be <= r_max (got {float(bad.flat[0]):g})")
    return (rmax - rmin) / (rmax + rmin)


def weber_to_michelson(k_weber: npt.ArrayLike) -> NDArrayFloat:
    """Convert a Weber contrast (B_max − B_min)/B_max to Michelson: K = K_W / (2 − K_W).

    Parameters
    ----------
    k_weber : array_like
        Weber contrast [–], 0 ≤ K_W ≤ 1.

    Returns
    -------
    numpy.ndarray
        Michelson contrast [–].

    Notes
    -----
    Spec formulas.md §3 (Russian texts often use the Weber form).

    Examples
    --------
    >>> round(float(weber_to_michelson(0.02)), 4)
    0.0101
    """
    kw = in_range("k_weber", k_weber, 0.0, 1.0)
    return kw / (2.0 - kw)


def threshold_sandvik_exponential(
    freq_lpmm: npt.ArrayLike, nyquist_lpmm: npt.ArrayLike, k0: npt.ArrayLike = DEFAULT_K0
) -> NDArrayFloat:
    """Threshold contrast function K_thr(N) = K0^(1 − N/R_m).

    Parameters
    ----------
    freq_lpmm : array_like
        Spatial frequency N [lines/mm].
    nyquist_lpmm : array_like
        Sensor limiting resolution R_m [lines/mm] (:func:`nyquist_lpmm`).
    k0 : array_like, optional
        Threshold contrast at low frequency K0 [–], 0 < K0 < 1. Default 0.03.

    Returns
    -------
    numpy.ndarray
        K_thr, rising from K0 at N = 0 to 1 at N = R_m.

    Notes
    -----
    Seed 000, the "Sandvik formula" for the threshold contrast function.
    **Reconstruction**: the printed form is lost. Sandvik's law makes resolving power
    grow with the logarithm of contrast; its exponential threshold form with
    K_thr(R_m) = 1 (R_m is "the resolving power at image contrast 1") is
    K0^(1 − N/R_m) (spec formulas.md §3).

    Default K0 = 0.03: for a digital sensor the low-frequency threshold is the
    contrast a bar pattern needs to stand out of the noise, K0 ≈ k/SNR. With a
    mid-grey SNR of 100–150 (full-frame and medium-format CMOS at base ISO) and a
    detection factor k ≈ 3–5 (Rose criterion) this gives 0.02–0.05; 0.03 is the
    middle of that range. It is a parameter: set it from the camera's noise or a
    measured threshold curve (:func:`threshold_table`).

    Examples
    --------
    >>> np.round(threshold_sandvik_exponential([0.0, 78.125], 78.125), 4).tolist()
    [0.03, 1.0]
    """
    n = nonnegative("freq_lpmm", freq_lpmm)
    rm = positive("nyquist_lpmm", nyquist_lpmm)
    k = in_range("k0", k0, 0.0, 1.0, low_inclusive=False, high_inclusive=False)
    return k ** (1.0 - n / rm)


def threshold_table(
    freq_lpmm: npt.ArrayLike,
    nyquist_lpmm: npt.ArrayLike,
    table_freq_lpmm: npt.ArrayLike,
    table_k: npt.ArrayLike,
    relative: bool = False,
) -> NDArrayFloat:
    """Measured threshold-contrast curve, linearly interpolated.

    Parameters
    ----------
    freq_lpmm : array_like
        Spatial frequency N [lines/mm].
    nyquist_lpmm : array_like
        R_m [lines/mm]; used only when ``relative`` is True.
    table_freq_lpmm : array_like, 1-D
        Tabulated frequencies, strictly increasing [lines/mm], or N/R_m [–] when
        ``relative``.
    table_k : array_like, 1-D
        Threshold contrast at those frequencies [–], in (0, 1].
    relative : bool, optional
        Interpret the table's frequencies as fractions of R_m.

    Returns
    -------
    numpy.ndarray
        Held constant outside the table.

    Notes
    -----
    The replacement the spec asks for ("keep the threshold model pluggable, so a
    measured curve can replace it"); not a seed formula.

    Examples
    --------
    >>> round(float(threshold_table(20.0, 78.125, [0.0, 40.0], [0.02, 0.1])), 4)
    0.06
    """
    n = nonnegative("freq_lpmm", freq_lpmm)
    tf = nonnegative("table_freq_lpmm", np.ravel(table_freq_lpmm))
    tk = in_range("table_k", np.ravel(table_k), 0.0, 1.0, low_inclusive=False)
    if tf.shape != tk.shape or tf.size == 0:
        raise ValueError("table_k must have the same non-zero length as table_freq_lpmm")
    if np.any(np.diff(tf) <= 0):
        raise ValueError("table_freq_lpmm must be strictly increasing")
    x = n / positive("nyquist_lpmm", nyquist_lpmm) if relative else n
    return np.interp(x, tf, tk)


#: Threshold-contrast models by name (front function :func:`threshold_contrast`).
THRESHOLD_METHODS: dict[str, Callable[..., NDArrayFloat]] = {
    "sandvik-exponential": threshold_sandvik_exponential,
    "table": threshold_table,
}


def threshold_contrast(
    freq_lpmm: npt.ArrayLike,
    nyquist_lpmm: npt.ArrayLike,
    method: Literal["sandvik-exponential", "table"] = "sandvik-exponential",
    **kwargs: Any,
) -> NDArrayFloat:
    """Threshold contrast K_thr(N) by the named model (see :data:`THRESHOLD_METHODS`).

    Parameters
    ----------
    freq_lpmm : array_like
        Spatial frequency N [lines/mm].
    nyquist_lpmm : array_like
        R_m [lines/mm].
    method : str, optional
        ``"sandvik-exponential"`` (default) or ``"table"``.
    **kwargs
        Parameters of the chosen model (``k0``; ``table_freq_lpmm``, ``table_k``,
        ``relative``).

    Returns
    -------
    numpy.ndarray

    Raises
    ------
    ValueError
        For an unknown method name.

    Examples
    --------
    >>> round(float(threshold_contrast(39.0625, 78.125, k0=0.03)), 4)
    0.1732
    """
    return pick_method(THRESHOLD_METHODS, method)(freq_lpmm, nyquist_lpmm, **kwargs)

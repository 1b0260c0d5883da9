"""Atmosphere MTF: haze (two models) and turbulence (seed 000, eqs. 1–2)."""

from __future__ import annotations

from collections.abc import Callable
from typing import Any, Literal

import numpy as np
import numpy.typing as npt

from scanplan.core.checks import finite, in_range, nonnegative, positive
from scanplan.core.mtf._base import (
    DEFAULT_HAZE_CONTRAST,
    NDArrayFloat,
    _k_gauss,
    _k_haze_indicatrix,
)
from scanplan.errors import pick_method


def haze_contrast_coefficient(
    freq_lpmm: npt.ArrayLike, contrast_coefficient: npt.ArrayLike = DEFAULT_HAZE_CONTRAST
) -> NDArrayFloat:
    """Haze as a frequency-independent contrast transmission coefficient, T_h(N) = c.

    Parameters
    ----------
    freq_lpmm : array_like
        Spatial frequency N on the image [lines/mm] (only its shape is used).
    contrast_coefficient : array_like, optional
        Contrast transmission of the air column c [–], 0 < c ≤ 1. Default 0.9.

    Returns
    -------
    numpy.ndarray
        c broadcast to the shape of ``freq_lpmm`` (and of c).

    Notes
    -----
    Seed 000 (text after eq. 2): instead of a haze MTF one may use the contrast
    reduction coefficient of the air layer, independent of frequency. This is the
    default haze model for UAV heights. Default c = 0.9: a 300–500 m vertical path
    in clear air (visibility ≳ 20 km, extinction ≈ 0.2 km⁻¹, optical depth ≈ 0.06–0.1)
    adds path radiance of roughly a tenth of the radiance of a dark (r ≈ 0.1)
    vegetated scene; the value is an estimate, set it from a measurement when known.

    Examples
    --------
    >>> round(float(haze_contrast_coefficient(50.0)), 4)
    0.9
    """
    n = finite("freq_lpmm", freq_lpmm)
    c = in_range("contrast_coefficient", contrast_coefficient, 0.0, 1.0, low_inclusive=False)
    return np.broadcast_to(c, np.broadcast(n, c).shape).astype(float)


def haze_exponential_indicatrix(
    freq_lpmm: npt.ArrayLike,
    focal_mm: npt.ArrayLike,
    height_m: npt.ArrayLike,
    scattering_per_km: npt.ArrayLike = 0.15,
    indicatrix_per_rad: npt.ArrayLike = 10.0,
) -> NDArrayFloat:
    """Haze MTF for an exponential scattering indicatrix with layer thickness d = H.

    T_h(N) = exp{−μH·[1 − 1/sqrt(1 + (2π·f·N/α)²)]}

    Parameters
    ----------
    freq_lpmm : array_like
        Spatial frequency N on the image [lines/mm].
    focal_mm : array_like
        Focal length f [mm] (f·N is the angular frequency in cycles/rad).
    height_m : array_like
        Flight height H [m] = thickness of the scattering layer d.
    scattering_per_km : array_like, optional
        Scattering coefficient of the air μ [1/km]. Default 0.15 (clear air,
        visibility ≈ 25 km).
    indicatrix_per_rad : array_like, optional
        Parameter α of the exponential indicatrix p(θ) ∝ exp(−α·θ) [1/rad]. Default
        10 (forward peak of aerosol scattering ≈ 6° wide).

    Returns
    -------
    numpy.ndarray
        T_h in (exp(−μH), 1].

    Notes
    -----
    Seed 000, eq. 1 (haze MTF with μ, d, α). **Reconstruction**: the printed form
    is lost in the extracted text; this is the form restated in spec formulas.md §3.
    For any practical f·N the bracket is ≈ 1, so T_h ≈ exp(−μH): the haze acts as
    a frequency-independent coefficient, which is why the seed allows
    :func:`haze_contrast_coefficient` instead.

    Examples
    --------
    >>> np.round(haze_exponential_indicatrix([0.0, 50.0], 50.0, 300.0), 4).tolist()
    [1.0, 0.956]
    """
    n = nonnegative("freq_lpmm", freq_lpmm)
    f = positive("focal_mm", focal_mm)
    h = positive("height_m", height_m)
    mu = nonnegative("scattering_per_km", scattering_per_km)
    alpha = positive("indicatrix_per_rad", indicatrix_per_rad)
    return _k_haze_indicatrix(n, f, mu * h * 1e-3, alpha)


#: Haze models by name (front function :func:`haze_mtf`).
HAZE_METHODS: dict[str, Callable[..., NDArrayFloat]] = {
    "contrast-coefficient": haze_contrast_coefficient,
    "exponential-indicatrix": haze_exponential_indicatrix,
}


def haze_mtf(
    freq_lpmm: npt.ArrayLike,
    method: Literal["contrast-coefficient", "exponential-indicatrix"] = "contrast-coefficient",
    **kwargs: Any,
) -> NDArrayFloat:
    """Haze transfer T_h(N) by the named model (see :data:`HAZE_METHODS`).

    Parameters
    ----------
    freq_lpmm : array_like
        Spatial frequency N [lines/mm].
    method : str, optional
        ``"contrast-coefficient"`` (default; frequency independent) or
        ``"exponential-indicatrix"`` (reconstructed seed 000, eq. 1).
    **kwargs
        Parameters of the chosen model.

    Returns
    -------
    numpy.ndarray

    Raises
    ------
    ValueError
        For an unknown method name.

    Examples
    --------
    >>> round(float(haze_mtf(50.0, contrast_coefficient=0.8)), 4)
    0.8
    """
    return pick_method(HAZE_METHODS, method)(freq_lpmm, **kwargs)


def turbulence_mtf(
    freq_lpmm: npt.ArrayLike, focal_mm: npt.ArrayLike, turbulence_urad: npt.ArrayLike
) -> NDArrayFloat:
    """Turbulence MTF T_v(N) = exp(−2π²·f²·γ²·N²).

    Parameters
    ----------
    freq_lpmm : array_like
        Spatial frequency N [lines/mm].
    focal_mm : array_like
        Focal length f [mm].
    turbulence_urad : array_like
        Angular size γ of the turbulence blur [µrad] (0 switches it off).

    Returns
    -------
    numpy.ndarray

    Notes
    -----
    Seed 000, eq. 2. f·γ is the RMS blur on the image in mm.

    Examples
    --------
    >>> round(float(turbulence_mtf(50.0, 50.0, 5.0)), 6)
    0.996921
    """
    n = finite("freq_lpmm", freq_lpmm)
    f = positive("focal_mm", focal_mm)
    g = nonnegative("turbulence_urad", turbulence_urad) * 1e-6
    return _k_gauss(n, f * g)

"""Sensor MTF: pixel aperture, charge transfer, diffusion (seed 000, eq. 4)."""

from __future__ import annotations

import numpy as np
import numpy.typing as npt

from scanplan.core.checks import finite, in_range, nonnegative, positive
from scanplan.core.mtf._base import NDArrayFloat, _k_charge_transfer, _k_diffusion, _k_sinc


def nyquist_lpmm(pixel_um: npt.ArrayLike) -> NDArrayFloat:
    """Sensor limiting resolution (Nyquist) R_m = 1 / (2p).

    Parameters
    ----------
    pixel_um : array_like
        Pixel pitch p [µm].

    Returns
    -------
    numpy.ndarray
        R_m [lines/mm] = 500 / pixel_um.

    Notes
    -----
    Seed 000, the formula for R_m after the Sandvik threshold function.

    Examples
    --------
    >>> round(float(nyquist_lpmm(6.4)), 3)
    78.125
    """
    return 1.0 / (2.0 * positive("pixel_um", pixel_um) * 1e-3)


def pixel_aperture_mtf(
    freq_lpmm: npt.ArrayLike, pixel_um: npt.ArrayLike, fill_factor: npt.ArrayLike = 1.0
) -> NDArrayFloat:
    """Geometric pixel-aperture MTF T_g(N) = |sinc(π·a·N)|, a = p·sqrt(fill factor).

    Parameters
    ----------
    freq_lpmm : array_like
        Spatial frequency N [lines/mm].
    pixel_um : array_like
        Pixel pitch p [µm].
    fill_factor : array_like, optional
        Linear-area fill factor of the pixel [–], 0 < ff ≤ 1 (1 with micro-lenses).

    Returns
    -------
    numpy.ndarray
        First zero at N = 1/a.

    Notes
    -----
    Seed 000, eq. 4 (component T_g; the seed gives no formula, "described in many
    specialised works"); form from spec formulas.md §3. sinc(x) = sin x / x.

    Examples
    --------
    >>> round(float(pixel_aperture_mtf(78.125, 6.4)), 4)
    0.6366
    """
    n = finite("freq_lpmm", freq_lpmm)
    p = positive("pixel_um", pixel_um) * 1e-3
    ff = in_range("fill_factor", fill_factor, 0.0, 1.0, low_inclusive=False)
    return _k_sinc(p * np.sqrt(ff) * n)


def charge_transfer_mtf(
    freq_lpmm: npt.ArrayLike,
    pixel_um: npt.ArrayLike,
    transfers: npt.ArrayLike = 0,
    inefficiency: npt.ArrayLike = 0.0,
) -> NDArrayFloat:
    """CCD charge-transfer MTF T_t(N) = exp{−n·ε·[1 − cos(2π·N·p)]}.

    Parameters
    ----------
    freq_lpmm : array_like
        Spatial frequency N [lines/mm].
    pixel_um : array_like
        Pixel pitch p [µm].
    transfers : array_like, optional
        Number of charge transfers n [–] (0 for CMOS: T_t = 1).
    inefficiency : array_like, optional
        Charge-transfer inefficiency per transfer ε [–], 0 ≤ ε < 1.

    Returns
    -------
    numpy.ndarray

    Notes
    -----
    Seed 000, eq. 4 (component T_t; no printed formula in the seed); form from
    spec formulas.md §3 (Holst).

    Examples
    --------
    >>> round(float(charge_transfer_mtf(78.125, 6.4, 2000, 1e-5)), 4)
    0.9608
    """
    n = finite("freq_lpmm", freq_lpmm)
    p = positive("pixel_um", pixel_um) * 1e-3
    nt = nonnegative("transfers", transfers)
    eps = in_range("inefficiency", inefficiency, 0.0, 1.0, high_inclusive=False)
    return _k_charge_transfer(n, p, nt * eps)


def diffusion_mtf(
    freq_lpmm: npt.ArrayLike,
    diffusion_length_um: npt.ArrayLike = 0.0,
    depletion_um: npt.ArrayLike = 2.0,
    absorption_per_um: npt.ArrayLike = 0.7,
) -> NDArrayFloat:
    """Lateral charge-diffusion MTF (Seib's form as given by Holst).

    T_d(N) = [1 − e^{−α·W}/(1 + α·L(N))] / [1 − e^{−α·W}/(1 + α·L0)],
    L(N) = L0 / sqrt(1 + (2π·L0·N)²).

    Parameters
    ----------
    freq_lpmm : array_like
        Spatial frequency N [lines/mm].
    diffusion_length_um : array_like, optional
        Minority-carrier diffusion length L0 [µm]. Default 0: T_d = 1 (switched off;
        the seed treats diffusion as optional).
    depletion_um : array_like, optional
        Depletion width W [µm]. Default 2.
    absorption_per_um : array_like, optional
        Absorption coefficient of silicon α at the wavelength [1/µm]. Default 0.7
        (≈ 550 nm).

    Returns
    -------
    numpy.ndarray

    Notes
    -----
    Seed 000, eq. 4 (component T_d; no printed formula). Form: D. H. Seib, IEEE
    Trans. Electron Devices 21 (1974) 210–217, as given by G. C. Holst, *CCD
    Arrays, Cameras, and Displays*. Not a seed formula: an optional extra.

    Examples
    --------
    >>> round(float(diffusion_mtf(78.125, 10.0)), 4)
    0.9257
    """
    n = nonnegative("freq_lpmm", freq_lpmm) * 1e-3  # cycles per µm
    l0 = nonnegative("diffusion_length_um", diffusion_length_um)
    w = positive("depletion_um", depletion_um)
    alpha = positive("absorption_per_um", absorption_per_um)
    return _k_diffusion(n, l0, w, alpha)

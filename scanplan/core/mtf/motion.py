"""Image-motion MTF: linear, random and angular shifts (seed 000, eqs. 5–8)."""

from __future__ import annotations

import numpy as np
import numpy.typing as npt

from scanplan.core.checks import finite, in_range, nonnegative, positive
from scanplan.core.mtf._base import NDArrayFloat, _k_gauss, _k_linear_motion


def geometric_image_shift_mm(
    speed_ms: npt.ArrayLike,
    exposure_s: npt.ArrayLike,
    focal_mm: npt.ArrayLike,
    height_m: npt.ArrayLike,
) -> NDArrayFloat:
    """Geometric image shift during the exposure, δ_w = w·t/Mc = w·t·f/H.

    Parameters
    ----------
    speed_ms : array_like
        Speed w [m/s] (ground speed, or a random-motion speed).
    exposure_s : array_like
        Exposure time t [s].
    focal_mm : array_like
        Focal length f [mm].
    height_m : array_like
        Flight height H [m].

    Returns
    -------
    numpy.ndarray
        δ_w on the image [mm].

    Notes
    -----
    Seed 000, eq. 6.

    Examples
    --------
    >>> round(float(geometric_image_shift_mm(25.0, 1e-3, 50.0, 300.0)), 6)
    0.004167
    """
    w = nonnegative("speed_ms", speed_ms)
    t = positive("exposure_s", exposure_s)
    f = positive("focal_mm", focal_mm)
    h = positive("height_m", height_m)
    return w * t * f / h


def photographic_image_shift_mm(
    geometric_shift_mm: npt.ArrayLike, shift_factor: npt.ArrayLike = 1.0
) -> NDArrayFloat:
    """Photographic image shift δ = k·δ_w.

    Parameters
    ----------
    geometric_shift_mm : array_like
        δ_w [mm] (:func:`geometric_image_shift_mm`).
    shift_factor : array_like, optional
        k [–]: ≈ 1 for bright objects (autumn canopy), 0.6–0.7 for summer landscapes.

    Returns
    -------
    numpy.ndarray
        δ [mm].

    Notes
    -----
    Seed 000, text after eq. 6 (δ ≈ δ_w; δ ≈ (0.6–0.7)·δ_w). The factor is a norm
    parameter.

    Examples
    --------
    >>> round(float(photographic_image_shift_mm(0.004167, 0.65)), 6)
    0.002709
    """
    d = nonnegative("geometric_shift_mm", geometric_shift_mm)
    k = in_range("shift_factor", shift_factor, 0.0, 1.0, low_inclusive=False)
    return k * d


def linear_motion_mtf(
    freq_lpmm: npt.ArrayLike, shift_mm: npt.ArrayLike, shutter_efficiency: npt.ArrayLike = 1.0
) -> NDArrayFloat:
    """Regular linear motion MTF with a trapezoidal shutter opening.

    T_w(N) = |sinc(π·N·η·δ) · sinc(π·N·(1 − η)·δ)|,  sinc(x) = sin x / x.

    Parameters
    ----------
    freq_lpmm : array_like
        Spatial frequency N [lines/mm] (along the motion).
    shift_mm : array_like
        Photographic shift δ [mm] (:func:`photographic_image_shift_mm`).
    shutter_efficiency : array_like, optional
        Optical efficiency of the shutter η [–], 0.5 ≤ η ≤ 1 (1: rectangular opening,
        plain sinc). Below 0.5 the two boxes swap roles (η and 1 − η give the same
        trapezoid), so 0.3 would silently act as 0.7: it is refused.

    Returns
    -------
    numpy.ndarray

    Notes
    -----
    Seed 000, eq. 5. **Reconstruction**: the printed form is lost; this is the form
    of spec formulas.md §3 — the exposure profile is a trapezoid, the convolution of
    two boxes of widths η·δ and (1 − η)·δ, whose transform is the product of sincs.
    First zero at N = 1 / (max(η, 1 − η)·δ).

    Examples
    --------
    >>> round(float(linear_motion_mtf(78.125, 0.0027)), 4)
    0.9284
    """
    n = finite("freq_lpmm", freq_lpmm)
    d = nonnegative("shift_mm", shift_mm)
    eta = in_range("shutter_efficiency", shutter_efficiency, 0.5, 1.0)
    return _k_linear_motion(n, eta * d, (1.0 - eta) * d)


def angular_shift_tilt_mm(
    rate_rad_s: npt.ArrayLike,
    exposure_s: npt.ArrayLike,
    focal_mm: npt.ArrayLike,
    q_mm: npt.ArrayLike = 0.0,
) -> NDArrayFloat:
    """Image shift from rotation about the longitudinal or transverse axis.

    δ = ω·t·(f² + q²) / f

    Parameters
    ----------
    rate_rad_s : array_like
        Angular rate ω_x (roll) or ω_y (pitch) [rad/s].
    exposure_s : array_like
        Exposure time t [s].
    focal_mm : array_like
        Focal length f [mm].
    q_mm : array_like, optional
        Distance of the image point from the image centre q [mm] (0: centre).

    Returns
    -------
    numpy.ndarray
        δ [mm].

    Notes
    -----
    Seed 000, eq. 8 (first two forms; printed forms lost, restated in spec §3). The
    exact shift at a point at distance q in the direction of the motion; it is the
    worst case over directions.

    Examples
    --------
    >>> round(float(angular_shift_tilt_mm(0.02, 1e-3, 50.0, 21.6)), 6)
    0.001187
    """
    w = nonnegative("rate_rad_s", rate_rad_s)
    t = positive("exposure_s", exposure_s)
    f = positive("focal_mm", focal_mm)
    q = nonnegative("q_mm", q_mm)
    return w * t * (f * f + q * q) / f


def angular_shift_yaw_mm(
    rate_rad_s: npt.ArrayLike, exposure_s: npt.ArrayLike, q_mm: npt.ArrayLike
) -> NDArrayFloat:
    """Image shift from rotation about the vertical axis, δ = ω_z·t·q.

    Parameters
    ----------
    rate_rad_s : array_like
        Angular rate ω_z [rad/s].
    exposure_s : array_like
        Exposure time t [s].
    q_mm : array_like
        Distance of the image point from the centre q [mm].

    Returns
    -------
    numpy.ndarray
        δ [mm].

    Notes
    -----
    Seed 000, eq. 8 (third form).

    Examples
    --------
    >>> round(float(angular_shift_yaw_mm(0.02, 1e-3, 21.6)), 6)
    0.000432
    """
    w = nonnegative("rate_rad_s", rate_rad_s)
    t = positive("exposure_s", exposure_s)
    q = nonnegative("q_mm", q_mm)
    return w * t * q


def random_shift_rms_mm(*shifts_mm: npt.ArrayLike) -> NDArrayFloat:
    """Combine independent random image shifts as a root-sum-square, σ = sqrt(Σ δ_i²).

    Parameters
    ----------
    *shifts_mm : array_like
        Shifts of the independent random components [mm]: random linear motion
        (:func:`geometric_image_shift_mm` with the random speed) and the angular
        components (:func:`angular_shift_tilt_mm`, :func:`angular_shift_yaw_mm`)
        evaluated with RMS rates.

    Returns
    -------
    numpy.ndarray
        σ [mm].

    Notes
    -----
    Seed 000, text after eq. 7 and eq. 8; spec §3 ("combine independent components
    as a root-sum-square"). Each component's shift over the exposure is taken as its
    contribution to σ (the seed's usage; conservative compared with the RMS of a
    uniform smear, δ/√12).

    Examples
    --------
    >>> round(float(random_shift_rms_mm(0.003, 0.004)), 6)
    0.005
    """
    if not shifts_mm:
        return np.zeros(())
    arrs = [nonnegative("shifts_mm", s) for s in shifts_mm]
    total = np.zeros(np.broadcast_shapes(*(a.shape for a in arrs)))
    for a in arrs:  # fixed count of components, not of configurations
        total = total + a * a
    return np.sqrt(total)


def random_motion_mtf(freq_lpmm: npt.ArrayLike, sigma_mm: npt.ArrayLike) -> NDArrayFloat:
    """Random image-motion MTF T_σ(N) = exp(−2π²·σ²·N²).

    Parameters
    ----------
    freq_lpmm : array_like
        Spatial frequency N [lines/mm].
    sigma_mm : array_like
        RMS random image shift σ [mm].

    Returns
    -------
    numpy.ndarray

    Notes
    -----
    Seed 000, eq. 7.

    Examples
    --------
    >>> round(float(random_motion_mtf(78.125, 0.002)), 4)
    0.6176
    """
    n = finite("freq_lpmm", freq_lpmm)
    return _k_gauss(n, nonnegative("sigma_mm", sigma_mm))

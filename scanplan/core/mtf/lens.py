"""Lens MTF: diffraction (seed 000, eq. 3) and manufacturer tables."""

from __future__ import annotations

from typing import Literal

import numpy as np
import numpy.typing as npt

from scanplan.core.checks import finite, in_range, nonnegative, positive
from scanplan.core.mtf._base import DEFAULT_WAVELENGTH_UM, NDArrayFloat, _k_diffraction


def half_field_angle_rad(
    sensor_width_mm: npt.ArrayLike, sensor_height_mm: npt.ArrayLike, focal_mm: npt.ArrayLike
) -> NDArrayFloat:
    """Half field angle at the frame corner, β = atan(sqrt(a² + b²) / (2f)).

    Parameters
    ----------
    sensor_width_mm, sensor_height_mm : array_like
        Sensor sides a, b [mm].
    focal_mm : array_like
        Focal length f [mm].

    Returns
    -------
    numpy.ndarray
        β [rad].

    Notes
    -----
    Seed 000, the formula for β after eq. 3 (printed form lost; restated in spec §3).

    Examples
    --------
    >>> round(float(half_field_angle_rad(36.0, 24.0, 50.0)), 4)
    0.4083
    """
    a = positive("sensor_width_mm", sensor_width_mm)
    b = positive("sensor_height_mm", sensor_height_mm)
    f = positive("focal_mm", focal_mm)
    return np.arctan(np.hypot(a, b) / (2.0 * f))


def diffraction_cutoff_lpmm(
    f_number: npt.ArrayLike,
    wavelength_um: npt.ArrayLike = DEFAULT_WAVELENGTH_UM,
    field_angle_rad: npt.ArrayLike = 0.0,
    direction: Literal["sagittal", "tangential"] = "sagittal",
) -> NDArrayFloat:
    """Diffraction cut-off frequency N_c = cos β / (λ·n0) (tangential: cos³β).

    Parameters
    ----------
    f_number : array_like
        f-number n0 [–].
    wavelength_um : array_like, optional
        Reference wavelength λ [µm]. Default 0.55.
    field_angle_rad : array_like, optional
        Field angle β of the analysed image point [rad] (0 at the centre).
    direction : {"sagittal", "tangential"}
        Orientation of the bars relative to the radius of the image point.

    Returns
    -------
    numpy.ndarray
        N_c [lines/mm].

    Notes
    -----
    Seed 000, eq. 3 (definition of ν = N/N_c). The exponent of cos β by direction
    follows spec formulas.md §3.

    Examples
    --------
    >>> round(float(diffraction_cutoff_lpmm(8.0)), 1)
    227.3
    """
    n0 = positive("f_number", f_number)
    lam_mm = positive("wavelength_um", wavelength_um) * 1e-3
    beta = in_range("field_angle_rad", field_angle_rad, 0.0, np.pi / 2, high_inclusive=False)
    if direction == "sagittal":
        c = np.cos(beta)
    elif direction == "tangential":
        c = np.cos(beta) ** 3
    else:
        raise ValueError(f"direction must be 'sagittal' or 'tangential' (got {direction!r})")
    return c / (lam_mm * n0)


def diffraction_mtf(nu: npt.ArrayLike) -> NDArrayFloat:
    """Diffraction-limited MTF of a circular pupil at normalised frequency ν.

    T_o(ν) = (2/π)·[acos ν − ν·sqrt(1 − ν²)] for 0 ≤ ν < 1, else 0.

    Parameters
    ----------
    nu : array_like
        ν = N / N_c [–], ≥ 0.

    Returns
    -------
    numpy.ndarray
        T_o; T_o(0.5) = 0.3910.

    Notes
    -----
    Seed 000, eq. 3.

    Examples
    --------
    >>> np.round(diffraction_mtf([0.0, 0.5, 1.0]), 4).tolist()
    [1.0, 0.391, 0.0]
    """
    return _k_diffraction(nonnegative("nu", nu))


def lens_diffraction_mtf(
    freq_lpmm: npt.ArrayLike,
    f_number: npt.ArrayLike,
    wavelength_um: npt.ArrayLike = DEFAULT_WAVELENGTH_UM,
    field_angle_rad: npt.ArrayLike = 0.0,
    direction: Literal["sagittal", "tangential"] = "sagittal",
) -> NDArrayFloat:
    """Diffraction-limited lens MTF T_o(N) at the given image point.

    Parameters
    ----------
    freq_lpmm : array_like
        Spatial frequency N [lines/mm].
    f_number : array_like
        f-number n0 [–].
    wavelength_um : array_like, optional
        λ [µm]. Default 0.55.
    field_angle_rad : array_like, optional
        β [rad]; 0 at the centre, :func:`half_field_angle_rad` at the corner.
    direction : {"sagittal", "tangential"}

    Returns
    -------
    numpy.ndarray

    Notes
    -----
    Seed 000, eq. 3 with N_c from :func:`diffraction_cutoff_lpmm`. Real lenses are
    not diffraction limited at wide apertures (seed 000: computed MTFs deviate by
    ±0.04–0.07); use :func:`lens_table_mtf` with the manufacturer's curve when known.

    Examples
    --------
    >>> round(float(lens_diffraction_mtf(100.0, 8.0)), 4)
    0.4584
    """
    n = nonnegative("freq_lpmm", freq_lpmm)
    nc = diffraction_cutoff_lpmm(f_number, wavelength_um, field_angle_rad, direction)
    return diffraction_mtf(n / nc)


def lens_table_mtf(
    freq_lpmm: npt.ArrayLike,
    table_freq_lpmm: npt.ArrayLike,
    table_mtf: npt.ArrayLike,
    beyond: float = 0.0,
) -> NDArrayFloat:
    """Manufacturer lens MTF table (N → T), linearly interpolated.

    Parameters
    ----------
    freq_lpmm : array_like
        Spatial frequency N [lines/mm].
    table_freq_lpmm : array_like, 1-D
        Tabulated frequencies [lines/mm], strictly increasing, ≥ 0. If the table does
        not start at 0, the point (0, 1) is prepended.
    table_mtf : array_like, 1-D
        Tabulated MTF values [–] in [0, 1].
    beyond : float, optional
        Value beyond the last tabulated frequency. Default 0 (conservative: the
        table must cover the frequencies that matter, up to the sensor's Nyquist).

    Returns
    -------
    numpy.ndarray

    Notes
    -----
    Seed 000 (after eq. 3): manufacturers publish MTF charts for some lenses; the
    chart replaces the diffraction formula. One table describes one image point and
    one direction.

    Examples
    --------
    >>> np.round(lens_table_mtf([10.0, 25.0], [0.0, 20.0, 40.0], [1.0, 0.8, 0.6]), 4).tolist()
    [0.9, 0.75]
    """
    n = finite("freq_lpmm", freq_lpmm)
    tf = nonnegative("table_freq_lpmm", np.ravel(table_freq_lpmm))
    tm = in_range("table_mtf", np.ravel(table_mtf), 0.0, 1.0)
    if tf.shape != tm.shape or tf.size == 0:
        raise ValueError("table_mtf must have the same non-zero length as table_freq_lpmm")
    if np.any(np.diff(tf) <= 0):
        raise ValueError("table_freq_lpmm must be strictly increasing")
    if tf[0] > 0:
        tf = np.concatenate(([0.0], tf))
        tm = np.concatenate(([1.0], tm))
    return np.interp(n, tf, tm, right=beyond)

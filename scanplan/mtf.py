"""MTF chain, threshold contrast and resolving power of a UAV camera (seed 000).

Real ground resolution of a digital aerial camera (spec formulas.md §3):

* image contrast K(N) = K_obj · T(N), T = T_a · T_o · T_m · T_s (seed 000, eqs. 1–7);
* threshold contrast K_thr(N) of the sensor (a named, replaceable model);
* resolving power R = the smallest N in (0, R_m] with K(N) ≤ K_thr(N), R_m = 1/(2p);
* ground resolution L = H / (2·R·f) (seed 000, the unnumbered formula before eq. 1),
  compared with GSD = p·H/f: L/GSD = R_m/R ≥ 1.

N (``freq_lpmm``) is a spatial frequency on the image in line pairs per mm. Every
component is its own vectorised function of frequency; the chain functions
(:func:`component_mtfs`, :func:`contrast_curves`, :func:`ground_resolution`) take a
camera + flight + atmosphere + motion + scene description (frozen dataclasses whose
fields may be arrays) and broadcast over every configuration at once. The frequency
grid is always the **last** axis of a chain result.

Not resolvable is a result, not a number: where K_obj·T(0) ≤ K_thr(0) the resolving
power and the ground resolution are NaN and ``resolvable`` is False.
"""

from __future__ import annotations

from collections.abc import Callable, Iterable, Mapping
from dataclasses import dataclass
from typing import Any, Literal

import numpy as np
import numpy.typing as npt

from scanplan.errors import pick_method
from scanplan.flight import (
    _finite,
    _in_range,
    _nonnegative,
    _positive,
    ground_sample_distance_m,
)

__all__ = [
    "COMPONENTS",
    "HAZE_METHODS",
    "THRESHOLD_METHODS",
    "Atmosphere",
    "Camera",
    "Flight",
    "GroundResolution",
    "Motion",
    "ResolvingPower",
    "Scene",
    "Threshold",
    "UAVResolution",
    "angular_shift_tilt_mm",
    "angular_shift_yaw_mm",
    "charge_transfer_mtf",
    "component_mtfs",
    "contrast_curves",
    "diffraction_cutoff_lpmm",
    "diffraction_mtf",
    "diffusion_mtf",
    "geometric_image_shift_mm",
    "ground_resolution",
    "ground_resolution_m",
    "half_field_angle_rad",
    "haze_contrast_coefficient",
    "haze_exponential_indicatrix",
    "haze_mtf",
    "lens_diffraction_mtf",
    "lens_table_mtf",
    "linear_motion_mtf",
    "nyquist_lpmm",
    "object_contrast",
    "photographic_image_shift_mm",
    "pixel_aperture_mtf",
    "random_motion_mtf",
    "random_shift_rms_mm",
    "resolving_power",
    "solve_resolving_power",
    "system_mtf",
    "threshold_contrast",
    "threshold_sandvik_exponential",
    "threshold_table",
    "turbulence_mtf",
    "uav_resolution",
    "weber_to_michelson",
]

NDArrayFloat = npt.NDArray[np.float64]
NDArrayBool = npt.NDArray[np.bool_]

#: Reference wavelength λ for the diffraction MTF [µm] (green, middle of the visible band).
DEFAULT_WAVELENGTH_UM = 0.55
#: Threshold contrast at low frequency K0 of the Sandvik exponential model [–].
DEFAULT_K0 = 0.03
#: Frequency-independent contrast transmission of the air below a UAV [–].
DEFAULT_HAZE_CONTRAST = 0.9
DEFAULT_HAZE_MAX_HEIGHT_M = 500.0
"""Height up to which :data:`DEFAULT_HAZE_CONTRAST` is argued (clear air, docs/uav-models.md
"Defaults and why"); above it a plan says the default is used out of its range."""
#: Bracketing grid and refinement steps of the resolving-power solver.
DEFAULT_GRID_POINTS = 5
DEFAULT_ITERATIONS = 12


# =================================================================================
# Kernels: the formulas without validation. Public functions validate and call them;
# the chain validates its inputs once and then calls only the kernels.
# =================================================================================
def _k_sinc(x: NDArrayFloat) -> NDArrayFloat:
    """|sin(πx)/(πx)| with the value 1 at x = 0 (keeps the float dtype of x)."""
    y = np.pi * np.asarray(x)
    with np.errstate(divide="ignore", invalid="ignore"):
        return np.where(y == 0.0, 1.0, np.abs(np.sin(y) / y))


def _k_gauss(n: NDArrayFloat, sigma_mm: NDArrayFloat) -> NDArrayFloat:
    """exp(−2π²σ²N²) (seed 000, eqs. 2 and 7)."""
    s = sigma_mm * n
    return np.exp(-2.0 * np.pi**2 * s * s)


def _k_haze_indicatrix(
    n: NDArrayFloat, f: NDArrayFloat, tau: NDArrayFloat, alpha: NDArrayFloat
) -> NDArrayFloat:
    x = 2.0 * np.pi * f * n / alpha
    return np.exp(-tau * (1.0 - 1.0 / np.sqrt(1.0 + x * x)))


def _k_diffraction(nu: NDArrayFloat) -> NDArrayFloat:
    vc = np.minimum(nu, 1.0)
    return (2.0 / np.pi) * (np.arccos(vc) - vc * np.sqrt(1.0 - vc * vc))


def _k_charge_transfer(n: NDArrayFloat, p_mm: NDArrayFloat, ne: NDArrayFloat) -> NDArrayFloat:
    return np.exp(-ne * (1.0 - np.cos(2.0 * np.pi * n * p_mm)))


def _k_diffusion(
    n_per_um: NDArrayFloat, l0: NDArrayFloat, w: NDArrayFloat, alpha: NDArrayFloat
) -> NDArrayFloat:
    ln = l0 / np.sqrt(1.0 + (2.0 * np.pi * l0 * n_per_um) ** 2)
    e = np.exp(-alpha * w)
    return (1.0 - e / (1.0 + alpha * ln)) / (1.0 - e / (1.0 + alpha * l0))


def _k_linear_motion(n: NDArrayFloat, d1: NDArrayFloat, d2: NDArrayFloat) -> NDArrayFloat:
    return _k_sinc(n * d1) * _k_sinc(n * d2)


# =================================================================================
# Object contrast
# =================================================================================
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
    """
    rmax = _positive("r_max", r_max)
    rmin = _nonnegative("r_min", r_min)
    if np.any(rmin > rmax):
        bad = np.broadcast_to(rmin, np.broadcast(rmin, rmax).shape)[
            np.broadcast_to(rmin > rmax, np.broadcast(rmin, rmax).shape)
        ]
        raise ValueError(f"r_min must be <= r_max (got {float(bad.flat[0]):g})")
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
    """
    kw = _in_range("k_weber", k_weber, 0.0, 1.0)
    return kw / (2.0 - kw)


# =================================================================================
# Atmosphere: haze (two models) and turbulence
# =================================================================================
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
    """
    n = _finite("freq_lpmm", freq_lpmm)
    c = _in_range("contrast_coefficient", contrast_coefficient, 0.0, 1.0, low_inclusive=False)
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
    """
    n = _nonnegative("freq_lpmm", freq_lpmm)
    f = _positive("focal_mm", focal_mm)
    h = _positive("height_m", height_m)
    mu = _nonnegative("scattering_per_km", scattering_per_km)
    alpha = _positive("indicatrix_per_rad", indicatrix_per_rad)
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
        ``"exponential-indicatrix"`` (reconstructed seed 000 eq. 1).
    **kwargs
        Parameters of the chosen model.

    Returns
    -------
    numpy.ndarray

    Raises
    ------
    ValueError
        For an unknown method name.
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
    """
    n = _finite("freq_lpmm", freq_lpmm)
    f = _positive("focal_mm", focal_mm)
    g = _nonnegative("turbulence_urad", turbulence_urad) * 1e-6
    return _k_gauss(n, f * g)


# =================================================================================
# Lens
# =================================================================================
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
    """
    a = _positive("sensor_width_mm", sensor_width_mm)
    b = _positive("sensor_height_mm", sensor_height_mm)
    f = _positive("focal_mm", focal_mm)
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
    """
    n0 = _positive("f_number", f_number)
    lam_mm = _positive("wavelength_um", wavelength_um) * 1e-3
    beta = _in_range("field_angle_rad", field_angle_rad, 0.0, np.pi / 2, high_inclusive=False)
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
    """
    return _k_diffraction(_nonnegative("nu", nu))


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
    """
    n = _nonnegative("freq_lpmm", freq_lpmm)
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
    """
    n = _finite("freq_lpmm", freq_lpmm)
    tf = _nonnegative("table_freq_lpmm", np.ravel(table_freq_lpmm))
    tm = _in_range("table_mtf", np.ravel(table_mtf), 0.0, 1.0)
    if tf.shape != tm.shape or tf.size == 0:
        raise ValueError("table_mtf must have the same non-zero length as table_freq_lpmm")
    if np.any(np.diff(tf) <= 0):
        raise ValueError("table_freq_lpmm must be strictly increasing")
    if tf[0] > 0:
        tf = np.concatenate(([0.0], tf))
        tm = np.concatenate(([1.0], tm))
    return np.interp(n, tf, tm, right=beyond)


# =================================================================================
# Sensor
# =================================================================================
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
    """
    return 1.0 / (2.0 * _positive("pixel_um", pixel_um) * 1e-3)


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
    """
    n = _finite("freq_lpmm", freq_lpmm)
    p = _positive("pixel_um", pixel_um) * 1e-3
    ff = _in_range("fill_factor", fill_factor, 0.0, 1.0, low_inclusive=False)
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
    """
    n = _finite("freq_lpmm", freq_lpmm)
    p = _positive("pixel_um", pixel_um) * 1e-3
    nt = _nonnegative("transfers", transfers)
    eps = _in_range("inefficiency", inefficiency, 0.0, 1.0, high_inclusive=False)
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
    """
    n = _nonnegative("freq_lpmm", freq_lpmm) * 1e-3  # cycles per µm
    l0 = _nonnegative("diffusion_length_um", diffusion_length_um)
    w = _positive("depletion_um", depletion_um)
    alpha = _positive("absorption_per_um", absorption_per_um)
    return _k_diffusion(n, l0, w, alpha)


# =================================================================================
# Image motion
# =================================================================================
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
    """
    w = _nonnegative("speed_ms", speed_ms)
    t = _positive("exposure_s", exposure_s)
    f = _positive("focal_mm", focal_mm)
    h = _positive("height_m", height_m)
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
    """
    d = _nonnegative("geometric_shift_mm", geometric_shift_mm)
    k = _in_range("shift_factor", shift_factor, 0.0, 1.0, low_inclusive=False)
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
    """
    n = _finite("freq_lpmm", freq_lpmm)
    d = _nonnegative("shift_mm", shift_mm)
    eta = _in_range("shutter_efficiency", shutter_efficiency, 0.5, 1.0)
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
    """
    w = _nonnegative("rate_rad_s", rate_rad_s)
    t = _positive("exposure_s", exposure_s)
    f = _positive("focal_mm", focal_mm)
    q = _nonnegative("q_mm", q_mm)
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
    """
    w = _nonnegative("rate_rad_s", rate_rad_s)
    t = _positive("exposure_s", exposure_s)
    q = _nonnegative("q_mm", q_mm)
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
    """
    if not shifts_mm:
        return np.zeros(())
    arrs = [_nonnegative("shifts_mm", s) for s in shifts_mm]
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
    """
    n = _finite("freq_lpmm", freq_lpmm)
    return _k_gauss(n, _nonnegative("sigma_mm", sigma_mm))


# =================================================================================
# Threshold contrast (pluggable)
# =================================================================================
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
    """
    n = _nonnegative("freq_lpmm", freq_lpmm)
    rm = _positive("nyquist_lpmm", nyquist_lpmm)
    k = _in_range("k0", k0, 0.0, 1.0, low_inclusive=False, high_inclusive=False)
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
    """
    n = _nonnegative("freq_lpmm", freq_lpmm)
    tf = _nonnegative("table_freq_lpmm", np.ravel(table_freq_lpmm))
    tk = _in_range("table_k", np.ravel(table_k), 0.0, 1.0, low_inclusive=False)
    if tf.shape != tk.shape or tf.size == 0:
        raise ValueError("table_k must have the same non-zero length as table_freq_lpmm")
    if np.any(np.diff(tf) <= 0):
        raise ValueError("table_freq_lpmm must be strictly increasing")
    x = n / _positive("nyquist_lpmm", nyquist_lpmm) if relative else n
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
    """
    return pick_method(THRESHOLD_METHODS, method)(freq_lpmm, nyquist_lpmm, **kwargs)


# =================================================================================
# Resolving power solver and ground resolution
# =================================================================================
@dataclass(frozen=True, eq=False)
class ResolvingPower:
    """Result of :func:`solve_resolving_power`.

    Attributes
    ----------
    r_lpmm : numpy.ndarray
        System resolving power R [lines/mm]; **NaN where not resolvable**.
    resolvable : numpy.ndarray of bool
        False where K_obj·T(0) ≤ K_thr(0): the object contrast is below the
        threshold even at the lowest frequencies; no resolving power exists.
    sensor_limited : numpy.ndarray of bool
        True where the curves do not cross below R_m, so R = R_m (Nyquist): the
        sensor's sampling, not the optics or motion, limits the resolution.
    nyquist_lpmm : numpy.ndarray
        R_m [lines/mm].
    """

    r_lpmm: NDArrayFloat
    resolvable: NDArrayBool
    sensor_limited: NDArrayBool
    nyquist_lpmm: NDArrayFloat


def solve_resolving_power(
    margin: Callable[[NDArrayFloat], NDArrayFloat],
    nyquist_lpmm: npt.ArrayLike,
    *,
    upper_lpmm: npt.ArrayLike | None = None,
    grid_points: int = DEFAULT_GRID_POINTS,
    iterations: int = DEFAULT_ITERATIONS,
    coarse_margin: Callable[[NDArrayFloat], NDArrayFloat] | None = None,
    polish: bool = True,
) -> ResolvingPower:
    """Vectorised first crossing of image contrast and threshold contrast.

    R = the smallest N in (0, R_m] with margin(N) = K(N) − K_thr(N) ≤ 0.

    Parameters
    ----------
    margin : callable
        ``margin(freq_lpmm) -> K − K_thr``. Called with an array whose last axis
        holds frequencies and whose leading axes broadcast against the configuration
        shape; must return the broadcast shape (configurations …, frequencies).
    nyquist_lpmm : array_like
        R_m per configuration [lines/mm].
    upper_lpmm : array_like, optional
        Search ceiling per configuration [lines/mm], capped at R_m. Pass the first
        zero of an oscillating component (motion sinc) so that the margin is
        monotone on the searched interval; a crossing is always found below it.
    grid_points : int, optional
        Points of the uniform bracketing grid on [0, ceiling], 0 included.
        Default 5.
    iterations : int, optional
        Refinement steps inside the bracket (Illinois regula falsi, every fourth
        step a bisection). Default 12.
    coarse_margin : callable, optional
        A cheaper version of ``margin`` (e.g. float32) used for the grid and the
        refinement steps. The decision "resolvable" is always taken with ``margin``
        at N = 0, and the root is always polished with ``margin``.
    polish : bool, optional
        Finish with one secant step of ``margin`` from the refined root (two
        evaluations; default True): exact to float64 round-off for a smooth margin.

    Returns
    -------
    ResolvingPower
        ``r_lpmm`` is NaN where not resolvable; ``sensor_limited`` flags R = R_m.

    Notes
    -----
    Spec formulas.md §3 (R = abscissa of the intersection of K(N) and K_thr(N),
    seed 000). No Python loop over configurations: the margin is evaluated once on
    the grid for all configurations, the first grid point with margin ≤ 0 brackets
    the first crossing, and a fixed number of vectorised steps refine it, keeping a
    sign-changing bracket (Illinois modification of regula falsi, with an
    interleaved bisection so the bracket also shrinks geometrically). For the
    built-in chain every component is non-increasing and K_thr increasing below the
    ceiling, so the crossing is unique; user tables that oscillate need a finer grid.
    """
    if grid_points < 2:
        raise ValueError(f"grid_points must be >= 2 (got {grid_points})")
    rm = _positive("nyquist_lpmm", nyquist_lpmm)
    ceiling = rm if upper_lpmm is None else np.minimum(rm, _positive("upper_lpmm", upper_lpmm))
    fun = margin if coarse_margin is None else coarse_margin
    x = np.linspace(0.0, 1.0, grid_points)
    grid = ceiling[..., None] * x
    m = np.asarray(fun(grid))
    shape = m.shape[:-1]
    grid = np.broadcast_to(grid.astype(m.dtype), m.shape)
    ceiling = np.broadcast_to(ceiling, shape)

    if coarse_margin is None:
        resolvable = m[..., 0] > 0.0
    else:
        m0 = np.asarray(margin(np.zeros((*shape, 1))), dtype=float)[..., 0]
        resolvable = np.broadcast_to(m0, shape) > 0.0
    below = m[..., 1:] <= 0.0
    crossed = below.any(axis=-1)
    idx = np.argmax(below, axis=-1)[..., None] + 1
    lo = np.take_along_axis(grid, idx - 1, axis=-1)[..., 0]
    hi = np.take_along_axis(grid, idx, axis=-1)[..., 0]
    f_lo = np.take_along_axis(m, idx - 1, axis=-1)[..., 0]  # > 0 where a crossing exists
    f_hi = np.take_along_axis(m, idx, axis=-1)[..., 0]  # <= 0 where a crossing exists
    s_lo = np.ones(shape, dtype=m.dtype)  # Illinois weights of the end values
    s_hi = np.ones(shape, dtype=m.dtype)
    kept = np.zeros(shape, dtype=np.int8)  # +1: hi kept last step, -1: lo kept
    for step in range(iterations):  # fixed count, vectorised over configurations
        if step % 4 == 3:
            mid = 0.5 * (lo + hi)
        else:
            g_lo, g_hi = s_lo * f_lo, s_hi * f_hi
            denom = g_lo - g_hi
            ok = denom > 0
            mid = np.where(ok, lo + g_lo * (hi - lo) / np.where(ok, denom, 1.0), 0.5 * (lo + hi))
            mid = np.clip(mid, lo, hi)
        f_mid = np.broadcast_to(np.asarray(fun(mid[..., None]))[..., 0], shape)
        pos = f_mid > 0.0
        s_hi = np.where(pos, np.where(kept == 1, 0.5 * s_hi, s_hi), 1.0)
        s_lo = np.where(pos, 1.0, np.where(kept == -1, 0.5 * s_lo, s_lo))
        lo, f_lo = np.where(pos, mid, lo), np.where(pos, f_mid, f_lo)
        hi, f_hi = np.where(pos, hi, mid), np.where(pos, f_hi, f_mid)
        kept = np.where(pos, 1, -1).astype(np.int8)
    lo, hi = lo.astype(float), hi.astype(float)
    f_lo, f_hi = f_lo.astype(float), f_hi.astype(float)
    denom = f_lo - f_hi
    ok = denom > 0
    est = np.clip(np.where(ok, lo + f_lo * (hi - lo) / np.where(ok, denom, 1.0), lo), lo, hi)
    if polish:
        # float64 secant step from the refined root: two evaluations of ``margin``
        step_ = 1e-6 * ceiling
        pts = np.stack([est, est + step_], axis=-1)
        fp = np.broadcast_to(np.asarray(margin(pts), dtype=float), (*shape, 2))
        slope = (fp[..., 1] - fp[..., 0]) / step_
        ok = slope < 0
        polished = est - fp[..., 0] / np.where(ok, slope, -1.0)
        width = np.maximum(hi - lo, 4.0 * step_)
        est = np.where(ok, np.clip(polished, est - width, est + width), est)
        est = np.clip(est, 0.0, ceiling)
    r = np.where(crossed, est, ceiling)
    resolvable = resolvable & (r > 0.0)  # a crossing at N = 0 resolves nothing
    sensor_limited = resolvable & (~crossed | (r >= np.broadcast_to(rm, shape) * (1 - 1e-12)))
    r = np.where(resolvable, r, np.nan)
    return ResolvingPower(
        r_lpmm=r,
        resolvable=resolvable,
        sensor_limited=sensor_limited,
        nyquist_lpmm=np.array(np.broadcast_to(rm, shape), dtype=float),
    )


def ground_resolution_m(
    height_m: npt.ArrayLike, r_lpmm: npt.ArrayLike, focal_mm: npt.ArrayLike
) -> NDArrayFloat:
    """Ground resolution (linear resolution on the ground, LRM) L = H / (2·R·f).

    Parameters
    ----------
    height_m : array_like
        Flight height H [m].
    r_lpmm : array_like
        System resolving power R [lines/mm]; NaN (not resolvable) propagates.
    focal_mm : array_like
        Focal length f [mm].

    Returns
    -------
    numpy.ndarray
        L [m]: the smallest ground detail imaged separately. NaN where R is NaN.

    Notes
    -----
    Seed 000, the formula before eq. 1 (L = H/(2Rf)). Same quantity as seed 001's
    A = Mc/(2R) with Mc = H/f.
    """
    h = _positive("height_m", height_m)
    f = _positive("focal_mm", focal_mm)
    r = np.asarray(r_lpmm, dtype=float)
    if np.any(r <= 0):
        raise ValueError("r_lpmm must be > 0 (got a value <= 0)")
    return h / (2.0 * r * f)


# =================================================================================
# The chain: descriptions of camera, flight, atmosphere, motion, scene, threshold
# =================================================================================
@dataclass(frozen=True, eq=False)
class Camera:
    """Digital camera + lens. Fields may be arrays (one value per configuration).

    Attributes
    ----------
    pixel_um : array_like
        Pixel pitch p [µm].
    focal_mm : array_like
        Focal length f [mm].
    f_number : array_like
        Working f-number n0 [–].
    sensor_width_mm : array_like
        Sensor side across track a [mm] (long side, camera mounted landscape).
    sensor_height_mm : array_like
        Sensor side along track b [mm].
    fill_factor : array_like
        Pixel fill factor [–] (1 with micro-lenses).
    wavelength_um : array_like
        Reference wavelength λ [µm].
    shutter_efficiency : array_like
        Optical efficiency of the shutter η [–] (1: instantaneous opening).
    ccd_transfers, ccd_inefficiency : array_like
        CCD transfer count n and inefficiency ε (0 for CMOS).
    diffusion_length_um, depletion_um, absorption_per_um : array_like
        Parameters of :func:`diffusion_mtf` (diffusion off by default).
    lens_table_centre, lens_table_corner : tuple of (freq_lpmm, mtf), optional
        Manufacturer MTF tables replacing the diffraction formula at the centre / at
        the corner (shared by all configurations).
    """

    pixel_um: npt.ArrayLike
    focal_mm: npt.ArrayLike
    f_number: npt.ArrayLike
    sensor_width_mm: npt.ArrayLike
    sensor_height_mm: npt.ArrayLike
    fill_factor: npt.ArrayLike = 1.0
    wavelength_um: npt.ArrayLike = DEFAULT_WAVELENGTH_UM
    shutter_efficiency: npt.ArrayLike = 1.0
    ccd_transfers: npt.ArrayLike = 0
    ccd_inefficiency: npt.ArrayLike = 0.0
    diffusion_length_um: npt.ArrayLike = 0.0
    depletion_um: npt.ArrayLike = 2.0
    absorption_per_um: npt.ArrayLike = 0.7
    lens_table_centre: tuple[npt.ArrayLike, npt.ArrayLike] | None = None
    lens_table_corner: tuple[npt.ArrayLike, npt.ArrayLike] | None = None


@dataclass(frozen=True, eq=False)
class Flight:
    """Flight conditions of one exposure.

    Attributes
    ----------
    height_m : array_like
        Height above ground H [m].
    speed_ms : array_like
        Ground speed w [m/s].
    exposure_s : array_like
        Exposure time t [s].
    shift_factor : array_like
        Photographic / geometric shift k [–]: 1 for bright objects (autumn canopy;
        default, conservative), 0.6–0.7 for summer landscapes (seed 000).
    """

    height_m: npt.ArrayLike
    speed_ms: npt.ArrayLike
    exposure_s: npt.ArrayLike
    shift_factor: npt.ArrayLike = 1.0


@dataclass(frozen=True, eq=False)
class Motion:
    """Random motion of a light UAV (RMS values).

    Attributes
    ----------
    random_speed_ms : array_like
        RMS random linear speed of the camera [m/s] (across track, vertical, gusts).
    roll_rate_rad_s : array_like
        RMS angular rate about the longitudinal axis ω_x [rad/s].
    pitch_rate_rad_s : array_like
        RMS angular rate about the transverse axis ω_y [rad/s].
    yaw_rate_rad_s : array_like
        RMS angular rate about the vertical axis ω_z [rad/s].
    """

    random_speed_ms: npt.ArrayLike = 0.0
    roll_rate_rad_s: npt.ArrayLike = 0.0
    pitch_rate_rad_s: npt.ArrayLike = 0.0
    yaw_rate_rad_s: npt.ArrayLike = 0.0


@dataclass(frozen=True, eq=False)
class Atmosphere:
    """Atmosphere between the camera and the ground.

    Attributes
    ----------
    haze_method : str
        Key of :data:`HAZE_METHODS`; default ``"contrast-coefficient"``.
    contrast_coefficient : array_like
        For ``"contrast-coefficient"`` [–]; default 0.9.
    scattering_per_km, indicatrix_per_rad : array_like
        For ``"exponential-indicatrix"`` [1/km], [1/rad].
    turbulence_urad : array_like
        Turbulence blur angle γ [µrad]; default 5 (≈ 1″: f·γ is a fraction of a
        micrometre at UAV focal lengths, i.e. nearly negligible, as expected below
        the clouds, seed 002).
    """

    haze_method: str = "contrast-coefficient"
    contrast_coefficient: npt.ArrayLike = DEFAULT_HAZE_CONTRAST
    scattering_per_km: npt.ArrayLike = 0.15
    indicatrix_per_rad: npt.ArrayLike = 10.0
    turbulence_urad: npt.ArrayLike = 5.0


@dataclass(frozen=True, eq=False)
class Scene:
    """Object and background brightness.

    Attributes
    ----------
    r_max, r_min : array_like
        Spectral brightness coefficients of the lightest and darkest details [–].
        Default 0.3 / 0.1 (K_obj = 0.5): a light man-made or bare-soil detail on
        vegetation in the visible band.
    """

    r_max: npt.ArrayLike = 0.3
    r_min: npt.ArrayLike = 0.1

    @property
    def contrast(self) -> NDArrayFloat:
        """K_obj [–] (:func:`object_contrast`)."""
        return object_contrast(self.r_max, self.r_min)


@dataclass(frozen=True, eq=False)
class Threshold:
    """Threshold-contrast model: a key of :data:`THRESHOLD_METHODS` and its parameters.

    Attributes
    ----------
    method : str
        Default ``"sandvik-exponential"``.
    params : mapping
        Keyword arguments of the model; default ``{"k0": 0.03}``.
    """

    method: str = "sandvik-exponential"
    params: Mapping[str, Any] | None = None

    def _params(self) -> dict[str, Any]:
        if self.method not in THRESHOLD_METHODS:
            raise ValueError(
                f"method must be one of {sorted(THRESHOLD_METHODS)} (got {self.method!r})"
            )
        if self.params is None:
            return {"k0": DEFAULT_K0} if self.method == "sandvik-exponential" else {}
        return dict(self.params)

    def __call__(self, freq_lpmm: npt.ArrayLike, nyquist_lpmm: npt.ArrayLike) -> NDArrayFloat:
        """K_thr(N) [–] for frequencies N [lines/mm] and Nyquist R_m [lines/mm]."""
        return threshold_contrast(freq_lpmm, nyquist_lpmm, self.method, **self._params())

    def prepare(
        self, nyquist_lpmm: npt.ArrayLike, dtype: type = np.float64
    ) -> Callable[[NDArrayFloat], NDArrayFloat]:
        """Validate once and return a fast ``K_thr(freq_lpmm)`` for the solver."""
        params = self._params()
        if self.method == "sandvik-exponential":
            k0 = np.asarray(params.get("k0", DEFAULT_K0), dtype=float)
            threshold_sandvik_exponential(0.0, nyquist_lpmm, k0)  # validates
            k0 = k0[..., None] if k0.ndim else k0
            inv_rm = (1.0 / np.asarray(nyquist_lpmm, dtype=float)).astype(dtype)
            if np.dtype(dtype) == np.float64:
                return lambda n: np.power(k0, 1.0 - n * inv_rm)  # exact K0 at N = 0
            ln_k0 = np.log(k0).astype(dtype)
            return lambda n: np.exp(ln_k0 * (1.0 - n * inv_rm))  # fast coarse phase
        return lambda n: threshold_contrast(n, nyquist_lpmm, self.method, **params)


#: Names of the chain components, in chain order (keys of :func:`component_mtfs`).
COMPONENTS: tuple[str, ...] = (
    "haze",
    "turbulence",
    "lens",
    "pixel",
    "charge_transfer",
    "diffusion",
    "linear_motion",
    "random_motion",
)

Field = Literal["centre", "corner"]
Direction = Literal["sagittal", "tangential"]


def _check_disable(disable: Iterable[str]) -> frozenset[str]:
    names = frozenset([disable] if isinstance(disable, str) else disable)
    unknown = names - set(COMPONENTS)
    if unknown:
        raise ValueError(
            f"disable must name components of {list(COMPONENTS)} (got {sorted(unknown)})"
        )
    return names


def _col(value: npt.ArrayLike) -> NDArrayFloat:
    """Configuration parameter with a trailing axis for the frequency grid."""
    return np.asarray(value, dtype=float)[..., None]


def _all_zero(value: npt.ArrayLike) -> bool:
    return bool(np.all(np.asarray(value) == 0))


class _Chain:
    """Validated, precomputed chain for a set of configurations (private).

    Every per-configuration quantity (δ, σ, N_c, pixel aperture, …) is validated
    and computed once, stored with a trailing axis of length 1 for the frequency
    grid; :meth:`components` and :meth:`product` then evaluate only the kernels.
    :meth:`astype` gives a float32 copy for the solver's coarse phase.
    """

    def __init__(
        self,
        camera: Camera,
        flight: Flight,
        atmosphere: Atmosphere,
        motion: Motion,
        field: Field,
        direction: Direction | None,
        disable: Iterable[str],
    ) -> None:
        off = _check_disable(disable)
        if field not in ("centre", "corner"):
            raise ValueError(f"field must be 'centre' or 'corner' (got {field!r})")
        if direction is None:
            direction = "sagittal" if field == "centre" else "tangential"
        p_um = _positive("pixel_um", camera.pixel_um)
        f = _positive("focal_mm", camera.focal_mm)
        n0 = _positive("f_number", camera.f_number)
        h = _positive("height_m", flight.height_m)
        t = _positive("exposure_s", flight.exposure_s)
        w = _nonnegative("speed_ms", flight.speed_ms)
        self.nyquist = nyquist_lpmm(p_um)
        self.active: list[str] = []
        self.lens_table: tuple[npt.ArrayLike, npt.ArrayLike] | None = None
        self.haze_kind = ""
        prm: dict[str, NDArrayFloat] = {}

        # atmosphere
        if "haze" not in off:
            if atmosphere.haze_method == "contrast-coefficient":
                c = haze_contrast_coefficient(0.0, atmosphere.contrast_coefficient)
                if not np.all(c == 1.0):
                    self.haze_kind, prm["haze_c"] = "coefficient", c
            elif atmosphere.haze_method == "exponential-indicatrix":
                mu = _nonnegative("scattering_per_km", atmosphere.scattering_per_km)
                prm["haze_alpha"] = _positive("indicatrix_per_rad", atmosphere.indicatrix_per_rad)
                prm["haze_tau"], prm["f"] = mu * h * 1e-3, f
                self.haze_kind = "indicatrix"
            else:
                haze_mtf(0.0, atmosphere.haze_method)  # raises ValueError naming the choices
            if self.haze_kind:
                self.active.append("haze")
        gam = _nonnegative("turbulence_urad", atmosphere.turbulence_urad)
        if "turbulence" not in off and not _all_zero(gam):
            prm["fg"] = f * gam * 1e-6
            self.active.append("turbulence")

        # lens
        if field == "corner":
            beta = half_field_angle_rad(camera.sensor_width_mm, camera.sensor_height_mm, f)
            q = 0.5 * np.hypot(
                np.asarray(camera.sensor_width_mm, float),
                np.asarray(camera.sensor_height_mm, float),
            )
        else:
            beta, q = np.zeros(()), np.zeros(())
        table = camera.lens_table_centre if field == "centre" else camera.lens_table_corner
        if "lens" not in off:
            if table is not None:
                lens_table_mtf(0.0, table[0], table[1])  # validate the table once
                self.lens_table = table
            else:
                nc = diffraction_cutoff_lpmm(n0, camera.wavelength_um, beta, direction)
                prm["inv_nc"] = 1.0 / nc
            self.active.append("lens")

        # sensor
        p_mm = p_um * 1e-3
        ff = _in_range("fill_factor", camera.fill_factor, 0.0, 1.0, low_inclusive=False)
        if "pixel" not in off:
            prm["aperture_mm"] = p_mm * np.sqrt(ff)
            self.active.append("pixel")
        nt = _nonnegative("ccd_transfers", camera.ccd_transfers)
        eps = _in_range("ccd_inefficiency", camera.ccd_inefficiency, 0.0, 1.0, high_inclusive=False)
        if "charge_transfer" not in off and not _all_zero(nt * eps):
            prm["n_eps"], prm["p_mm"] = nt * eps, p_mm
            self.active.append("charge_transfer")
        l0 = _nonnegative("diffusion_length_um", camera.diffusion_length_um)
        dw = _positive("depletion_um", camera.depletion_um)
        da = _positive("absorption_per_um", camera.absorption_per_um)
        if "diffusion" not in off and not _all_zero(l0):
            prm["l0"], prm["depletion"], prm["absorption"] = l0, dw, da
            self.active.append("diffusion")

        # motion
        delta = photographic_image_shift_mm(
            geometric_image_shift_mm(w, t, f, h), flight.shift_factor
        )
        eta = _in_range("shutter_efficiency", camera.shutter_efficiency, 0.5, 1.0)
        sigma = random_shift_rms_mm(
            geometric_image_shift_mm(motion.random_speed_ms, t, f, h),
            angular_shift_tilt_mm(motion.roll_rate_rad_s, t, f, q),
            angular_shift_tilt_mm(motion.pitch_rate_rad_s, t, f, q),
            angular_shift_yaw_mm(motion.yaw_rate_rad_s, t, q),
        )
        self.motion_width_mm = np.zeros(())
        if "linear_motion" not in off and not _all_zero(delta):
            prm["d1"], prm["d2"] = eta * delta, (1.0 - eta) * delta
            self.motion_two_boxes = not _all_zero(prm["d2"])
            self.motion_width_mm = np.maximum(eta, 1.0 - eta) * delta
            self.active.append("linear_motion")
        if "random_motion" not in off and not _all_zero(sigma):
            prm["sigma"] = sigma
            self.active.append("random_motion")
        # product of the Gaussian components = one Gaussian with the summed variance
        prm["gauss_var"] = prm.get("fg", np.zeros(())) ** 2 + prm.get("sigma", np.zeros(())) ** 2
        self.prm = {k: np.asarray(v, dtype=float)[..., None] for k, v in prm.items()}

    def astype(self, dtype: type) -> _Chain:
        """Shallow copy whose parameters have the given float dtype."""
        other = object.__new__(_Chain)
        other.__dict__.update(self.__dict__)
        other.prm = {k: v.astype(dtype) for k, v in self.prm.items()}
        return other

    def _component(self, name: str, n: NDArrayFloat) -> NDArrayFloat:
        p = self.prm
        if name == "haze":
            if self.haze_kind == "coefficient":
                return p["haze_c"]
            return _k_haze_indicatrix(n, p["f"], p["haze_tau"], p["haze_alpha"])
        if name == "turbulence":
            return _k_gauss(n, p["fg"])
        if name == "lens":
            if self.lens_table is not None:
                return lens_table_mtf(n, self.lens_table[0], self.lens_table[1])
            return _k_diffraction(n * p["inv_nc"])
        if name == "pixel":
            return _k_sinc(n * p["aperture_mm"])
        if name == "charge_transfer":
            return _k_charge_transfer(n, p["p_mm"], p["n_eps"])
        if name == "diffusion":
            return _k_diffusion(n * 1e-3, p["l0"], p["depletion"], p["absorption"])
        if name == "linear_motion":
            if self.motion_two_boxes:
                return _k_linear_motion(n, p["d1"], p["d2"])
            return _k_sinc(n * p["d1"])
        return _k_gauss(n, p["sigma"])  # random_motion

    def components(self, n: NDArrayFloat) -> dict[str, NDArrayFloat]:
        out = {
            name: self._component(name, n) if name in self.active else np.ones(np.shape(n))
            for name in COMPONENTS  # fixed number of components
        }
        common = np.broadcast_shapes(*(v.shape for v in out.values()))
        return {k: np.broadcast_to(v, common) for k, v in out.items()}

    def product(self, n: NDArrayFloat) -> NDArrayFloat:
        total: NDArrayFloat | None = None
        for name in self.active:  # fixed number of components
            if name in ("turbulence", "random_motion"):
                continue
            v = self._component(name, n)
            total = v if total is None else total * v
        if "turbulence" in self.active or "random_motion" in self.active:
            g = np.exp((-2.0 * np.pi**2) * self.prm["gauss_var"] * (n * n))
            total = g if total is None else total * g
        if total is None:
            return np.ones(np.shape(n), dtype=np.result_type(n, np.float32))
        return np.broadcast_to(total, np.broadcast_shapes(np.shape(n), total.shape))


def component_mtfs(
    freq_lpmm: npt.ArrayLike,
    camera: Camera,
    flight: Flight,
    atmosphere: Atmosphere | None = None,
    motion: Motion | None = None,
    *,
    field: Field = "centre",
    direction: Direction | None = None,
    disable: Iterable[str] = (),
) -> dict[str, NDArrayFloat]:
    """Every MTF component of the chain on a frequency grid.

    Parameters
    ----------
    freq_lpmm : array_like
        Frequencies N [lines/mm]; the **last** axis of every result. A 1-D grid
        broadcasts against array-valued configuration fields (result shape
        configurations + (len(grid),)).
    camera, flight : Camera, Flight
    atmosphere : Atmosphere, optional
        Default :class:`Atmosphere` ().
    motion : Motion, optional
        Default: no random motion.
    field : {"centre", "corner"}
        Image point analysed: the centre (β = 0, q = 0) or the frame corner
        (β = atan(sqrt(a² + b²)/(2f)), q = half diagonal).
    direction : {"sagittal", "tangential"}, optional
        Lens direction; default sagittal at the centre (where both coincide) and
        tangential (cos³β, the worse one) at the corner.
    disable : iterable of str
        Components switched off (T = 1); names from :data:`COMPONENTS`.

    Returns
    -------
    dict
        name → T(N) for every name of :data:`COMPONENTS`, in chain order.

    Notes
    -----
    Seed 000, eqs. 1–8: T = T_a·T_o·T_m·T_s with T_a = T_h·T_v (haze, turbulence),
    T_m = T_g·T_t·T_d (pixel, charge transfer, diffusion), T_s = T_w·T_σ (linear and
    random motion). Motion is evaluated along track, where forward motion acts.
    """
    chain = _Chain(
        camera,
        flight,
        Atmosphere() if atmosphere is None else atmosphere,
        Motion() if motion is None else motion,
        field,
        direction,
        disable,
    )
    return chain.components(_nonnegative("freq_lpmm", freq_lpmm))


def system_mtf(
    freq_lpmm: npt.ArrayLike,
    camera: Camera,
    flight: Flight,
    atmosphere: Atmosphere | None = None,
    motion: Motion | None = None,
    **kwargs: Any,
) -> NDArrayFloat:
    """System MTF T(N), the product of :func:`component_mtfs` (seed 000, eq. 1).

    Parameters and keywords as :func:`component_mtfs`.

    Returns
    -------
    numpy.ndarray
        Shape configurations + frequencies.
    """
    comps = component_mtfs(freq_lpmm, camera, flight, atmosphere, motion, **kwargs)
    total = np.ones(np.broadcast_shapes(*(v.shape for v in comps.values())))
    for v in comps.values():  # fixed number of components
        total = total * v
    return total


def contrast_curves(
    freq_lpmm: npt.ArrayLike,
    camera: Camera,
    flight: Flight,
    atmosphere: Atmosphere | None = None,
    motion: Motion | None = None,
    scene: Scene | None = None,
    threshold: Threshold | None = None,
    **kwargs: Any,
) -> dict[str, NDArrayFloat]:
    """Everything a report plots: components, T(N), K(N) and K_thr(N) on a grid.

    Parameters
    ----------
    freq_lpmm : array_like
        Frequencies N [lines/mm] (last axis of every result).
    camera, flight, atmosphere, motion : see :func:`component_mtfs`
    scene : Scene, optional
        Default :class:`Scene` () (K_obj = 0.5).
    threshold : Threshold, optional
        Default Sandvik exponential with K0 = 0.03.
    **kwargs
        ``field``, ``direction``, ``disable`` as :func:`component_mtfs`.

    Returns
    -------
    dict
        The component names of :data:`COMPONENTS`, plus ``"system"`` (T),
        ``"image_contrast"`` (K = K_obj·T) and ``"threshold"`` (K_thr).
    """
    scene = Scene() if scene is None else scene
    threshold = Threshold() if threshold is None else threshold
    comps = component_mtfs(freq_lpmm, camera, flight, atmosphere, motion, **kwargs)
    t = np.ones(np.broadcast_shapes(*(v.shape for v in comps.values())))
    for v in comps.values():  # fixed number of components
        t = t * v
    k = _col(scene.contrast) * t
    kthr = threshold(np.asarray(freq_lpmm, float), _col(nyquist_lpmm(camera.pixel_um)))
    out = dict(comps)
    out["system"] = t
    out["image_contrast"] = k
    out["threshold"] = np.broadcast_to(kthr, np.broadcast_shapes(kthr.shape, k.shape))
    return out


def resolving_power(
    camera: Camera,
    flight: Flight,
    atmosphere: Atmosphere | None = None,
    motion: Motion | None = None,
    scene: Scene | None = None,
    threshold: Threshold | None = None,
    *,
    field: Field = "centre",
    direction: Direction | None = None,
    disable: Iterable[str] = (),
    grid_points: int = DEFAULT_GRID_POINTS,
    iterations: int = DEFAULT_ITERATIONS,
    precision: Literal["mixed", "double"] = "mixed",
) -> ResolvingPower:
    """System resolving power R for every configuration at once.

    Parameters
    ----------
    camera, flight, atmosphere, motion, scene, threshold
        Descriptions (fields may be arrays; they broadcast together).
    field, direction, disable
        As :func:`component_mtfs`.
    grid_points, iterations
        As :func:`solve_resolving_power`.
    precision : {"mixed", "double"}
        ``"mixed"`` (default): bracket and refine in float32 (SIMD-fast), then the
        float64 decision at N = 0 and a float64 secant polish — the result agrees
        with ``"double"`` to ~1e-9 lines/mm. ``"double"``: float64 throughout.

    Returns
    -------
    ResolvingPower

    Notes
    -----
    Spec formulas.md §3, seed 000: R is the abscissa of the first intersection of
    K(N) = K_obj·T(N) and K_thr(N) in (0, R_m]. The search ceiling is the first zero
    of the linear-motion sinc, 1/(max(η, 1 − η)·δ), below which every built-in
    component is monotone (:func:`solve_resolving_power`).
    """
    scene = Scene() if scene is None else scene
    threshold = Threshold() if threshold is None else threshold
    chain = _Chain(
        camera,
        flight,
        Atmosphere() if atmosphere is None else atmosphere,
        Motion() if motion is None else motion,
        field,
        direction,
        disable,
    )
    # every configuration gets its own R, even where nothing depends on it (zero motion:
    # no component varies with the flying height)
    shape = np.broadcast_shapes(np.shape(chain.nyquist), np.shape(chain.motion_width_mm),
                                *(v.shape[:-1] for v in chain.prm.values()),
                                *(np.shape(x) for x in (flight.height_m, flight.speed_ms,
                                                        flight.exposure_s)))
    rm = np.broadcast_to(chain.nyquist, shape)
    width = np.broadcast_to(chain.motion_width_mm, shape)
    upper = None
    below = width * rm > 1.0  # the sinc's first zero lies below R_m (no 1/width overflow)
    if np.any(below):
        upper = np.where(below, 1.0 / np.where(below, width, 1.0), rm)
    kobj = _col(scene.contrast)
    kthr = threshold.prepare(_col(rm))

    def margin(freq: NDArrayFloat) -> NDArrayFloat:
        return kobj * chain.product(freq) - kthr(freq)

    coarse = None
    if precision == "mixed":
        chain32 = chain.astype(np.float32)
        kobj32 = kobj.astype(np.float32)
        kthr32 = threshold.prepare(_col(rm), np.float32)

        def coarse(freq: NDArrayFloat) -> NDArrayFloat:
            return kobj32 * chain32.product(freq.astype(np.float32)) - kthr32(freq)

    elif precision != "double":
        raise ValueError(f"precision must be 'mixed' or 'double' (got {precision!r})")
    return solve_resolving_power(
        margin,
        rm,
        upper_lpmm=upper,
        grid_points=grid_points,
        iterations=iterations,
        coarse_margin=coarse,
    )


@dataclass(frozen=True, eq=False)
class GroundResolution:
    """Ground resolution of one image point (centre or corner).

    Attributes
    ----------
    field : str
        ``"centre"`` or ``"corner"``.
    resolving_power : ResolvingPower
        R, ``resolvable``, ``sensor_limited``, R_m.
    gsd_m : numpy.ndarray
        GSD = p·H/f [m].
    ground_resolution_m : numpy.ndarray
        L = H/(2·R·f) [m]; **NaN where not resolvable** (never a fake number).
    l_over_gsd : numpy.ndarray
        L/GSD = R_m/R ≥ 1 [–]; NaN where not resolvable.
    """

    field: str
    resolving_power: ResolvingPower
    gsd_m: NDArrayFloat
    ground_resolution_m: NDArrayFloat
    l_over_gsd: NDArrayFloat

    @property
    def r_lpmm(self) -> NDArrayFloat:
        """R [lines/mm] (NaN where not resolvable)."""
        return self.resolving_power.r_lpmm

    @property
    def resolvable(self) -> NDArrayBool:
        """False where the object is not resolvable at all."""
        return self.resolving_power.resolvable


def ground_resolution(
    camera: Camera,
    flight: Flight,
    atmosphere: Atmosphere | None = None,
    motion: Motion | None = None,
    scene: Scene | None = None,
    threshold: Threshold | None = None,
    *,
    field: Field = "centre",
    **kwargs: Any,
) -> GroundResolution:
    """R, L, GSD and L/GSD at one image point for every configuration.

    Parameters
    ----------
    camera, flight, atmosphere, motion, scene, threshold
        As :func:`resolving_power`.
    field : {"centre", "corner"}
    **kwargs
        ``direction``, ``disable``, ``grid_points``, ``iterations``.

    Returns
    -------
    GroundResolution

    Notes
    -----
    Seed 000: L = H/(2Rf); GSD = pH/f; L/GSD = R_m/R, the seed's point that GSD
    overstates the real resolution (about 2× for UAV cameras).
    """
    rp = resolving_power(
        camera, flight, atmosphere, motion, scene, threshold, field=field, **kwargs
    )
    gsd = ground_sample_distance_m(camera.pixel_um, flight.height_m, camera.focal_mm)
    h = np.asarray(flight.height_m, dtype=float)
    f = np.asarray(camera.focal_mm, dtype=float)
    big = np.broadcast_shapes(rp.r_lpmm.shape, gsd.shape)
    r = np.broadcast_to(rp.r_lpmm, big)
    ell = ground_resolution_m(h, r, f) * np.ones(big)
    gsd = np.broadcast_to(gsd, big).astype(float)
    return GroundResolution(
        field=field, resolving_power=rp, gsd_m=gsd, ground_resolution_m=ell, l_over_gsd=ell / gsd
    )


@dataclass(frozen=True, eq=False)
class UAVResolution:
    """Ground resolution at the frame centre and at the frame corner.

    Attributes
    ----------
    centre : GroundResolution
        Sagittal lens MTF, no angular-motion lever arm (q = 0).
    corner : GroundResolution
        Lens at β = atan(sqrt(a² + b²)/(2f)) (tangential by default), angular motion
        with q = half diagonal.
    """

    centre: GroundResolution
    corner: GroundResolution


def uav_resolution(
    camera: Camera,
    flight: Flight,
    atmosphere: Atmosphere | None = None,
    motion: Motion | None = None,
    scene: Scene | None = None,
    threshold: Threshold | None = None,
    **kwargs: Any,
) -> UAVResolution:
    """Centre and corner ground resolution (spec §3: "Report centre and corner").

    Parameters
    ----------
    camera, flight, atmosphere, motion, scene, threshold
        As :func:`resolving_power`.
    **kwargs
        ``disable``, ``grid_points``, ``iterations``; ``direction`` applies to the
        corner.

    Returns
    -------
    UAVResolution
    """
    direction = kwargs.pop("direction", None)
    centre = ground_resolution(
        camera, flight, atmosphere, motion, scene, threshold, field="centre", **kwargs
    )
    corner = ground_resolution(
        camera,
        flight,
        atmosphere,
        motion,
        scene,
        threshold,
        field="corner",
        direction=direction,
        **kwargs,
    )
    return UAVResolution(centre=centre, corner=corner)

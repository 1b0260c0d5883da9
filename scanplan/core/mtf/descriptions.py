"""Descriptions of camera, flight, motion, atmosphere, scene and threshold."""

from __future__ import annotations

from collections.abc import Callable, Mapping
from dataclasses import dataclass
from typing import Any

import numpy as np
import numpy.typing as npt

from scanplan.core.mtf._base import (
    DEFAULT_HAZE_CONTRAST,
    DEFAULT_K0,
    DEFAULT_WAVELENGTH_UM,
    NDArrayFloat,
)
from scanplan.core.mtf.threshold import (
    THRESHOLD_METHODS,
    object_contrast,
    threshold_contrast,
    threshold_sandvik_exponential,
)


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

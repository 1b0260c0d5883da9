"""Shared types, defaults and kernels of the MTF package (no validation).

Public functions validate and call the kernels; the chain validates its inputs once and then
calls only the kernels.
"""

from __future__ import annotations

import numpy as np
import numpy.typing as npt

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


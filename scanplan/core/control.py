"""The checkpoint error budget and the control's precision against the target.

Pure numpy. What checkpoints measure is the block's error plus the error of the ground
control that oriented it and of the checkpoints' own survey. With independent errors the
best the checkpoints can show is their root-sum-square (docs/control.md, "Error budget"):

    RMSE at best = sqrt(σ_model² + σ_control² + σ_checkpoint²)

vertically with σ_model = σ_Z, the idealised stereo precision (Kraus 2007), in plan with
σ_model = σ_px·GSD per axis (the normal case's planimetric precision at the nadir). It is a
lower bound: calibration, image blur, the GCPs' identification and their number add to it.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray

from .checks import finite, nonnegative, positive

__all__ = ["control_ratio", "rmse_at_best_m"]


def rmse_at_best_m(sigma_model_m: ArrayLike, sigma_control_m: ArrayLike,
                   sigma_check_m: ArrayLike) -> NDArray[np.float64]:
    """The smallest checkpoint RMSE a block can show [m].

    Parameters
    ----------
    sigma_model_m : array_like
        The block's own precision [m] (σ_Z vertically; σ_px·GSD per axis in plan).
    sigma_control_m : array_like
        The ground control's survey precision (RMSE) [m]; 0 without GCPs.
    sigma_check_m : array_like
        The checkpoints' survey precision (RMSE) [m].

    Returns
    -------
    ndarray
        sqrt(σ_model² + σ_control² + σ_checkpoint²) [m], never below any of the three.

    Examples
    --------
    σ_Z 3 cm, GCPs and checkpoints surveyed to 4 cm: 3·√(1 + 2·(4/3)²) ≈ 6.4 cm.

    >>> round(float(rmse_at_best_m(0.03, 0.04, 0.04)), 4)
    0.064
    """
    parts = [np.asarray(v, dtype=float) for v in (sigma_model_m, sigma_control_m, sigma_check_m)]
    for name, v in zip(("sigma_model_m", "sigma_control_m", "sigma_check_m"), parts,
                       strict=True):
        finite(name, v)
        nonnegative(name, v)
    return np.sqrt(parts[0] ** 2 + parts[1] ** 2 + parts[2] ** 2)


def control_ratio(target_m: ArrayLike, sigma_control_m: ArrayLike) -> NDArray[np.float64]:
    """How many times more precise the control is than the target (target / σ_control).

    Parameters
    ----------
    target_m : array_like
        The product's required accuracy (RMSE) [m].
    sigma_control_m : array_like
        The ground control's survey precision (RMSE) [m].

    Returns
    -------
    ndarray
        target / σ_control [–]; a recommendation of "k times more precise" holds when ≥ k.

    Examples
    --------
    The EEA's own example (requirement 321): a 2.5 m RMSE target and GCPs of 0.8 m RMSE are
    3.1 times more precise — "at least 3 times" holds.

    >>> round(float(control_ratio(2.5, 0.8)), 3)
    3.125
    """
    t, s = np.asarray(target_m, dtype=float), np.asarray(sigma_control_m, dtype=float)
    finite("target_m", t)
    positive("target_m", t)
    finite("sigma_control_m", s)
    positive("sigma_control_m", s)
    return t / s

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

The package has one module per component family — :mod:`~scanplan.core.mtf.atmosphere`,
:mod:`~scanplan.core.mtf.lens`, :mod:`~scanplan.core.mtf.sensor`,
:mod:`~scanplan.core.mtf.motion` — plus
the threshold models (:mod:`~scanplan.core.mtf.threshold`), the solver
(:mod:`~scanplan.core.mtf.solver`), the input descriptions (:mod:`~scanplan.core.mtf.descriptions`),
the component registry (:mod:`~scanplan.core.mtf.components`) and the chain that multiplies the
registered components (:mod:`~scanplan.core.mtf.chain`). Every public name is re-exported here.

Not resolvable is a result, not a number: where K_obj·T(0) ≤ K_thr(0) the resolving
power and the ground resolution are NaN and ``resolvable`` is False.
"""

from __future__ import annotations

from scanplan.core.mtf._base import (
    DEFAULT_GRID_POINTS,
    DEFAULT_HAZE_CONTRAST,
    DEFAULT_HAZE_MAX_HEIGHT_M,
    DEFAULT_ITERATIONS,
    DEFAULT_K0,
    DEFAULT_WAVELENGTH_UM,
    NDArrayBool,
    NDArrayFloat,
)
from scanplan.core.mtf.atmosphere import (
    HAZE_METHODS,
    haze_contrast_coefficient,
    haze_exponential_indicatrix,
    haze_mtf,
    turbulence_mtf,
)
from scanplan.core.mtf.chain import (
    GroundResolution,
    UAVResolution,
    component_mtfs,
    contrast_curves,
    ground_resolution,
    resolving_power,
    system_mtf,
    uav_resolution,
)
from scanplan.core.mtf.components import (
    COMPONENTS,
    REGISTRY,
    Component,
    Direction,
    Field,
    Setup,
    Term,
    component_label,
    component_names,
    register,
    unregister,
)
from scanplan.core.mtf.descriptions import Atmosphere, Camera, Flight, Motion, Scene, Threshold
from scanplan.core.mtf.lens import (
    diffraction_cutoff_lpmm,
    diffraction_mtf,
    half_field_angle_rad,
    lens_diffraction_mtf,
    lens_table_mtf,
)
from scanplan.core.mtf.motion import (
    angular_shift_tilt_mm,
    angular_shift_yaw_mm,
    geometric_image_shift_mm,
    linear_motion_mtf,
    photographic_image_shift_mm,
    random_motion_mtf,
    random_shift_rms_mm,
)
from scanplan.core.mtf.sensor import (
    charge_transfer_mtf,
    diffusion_mtf,
    nyquist_lpmm,
    pixel_aperture_mtf,
)
from scanplan.core.mtf.solver import ResolvingPower, ground_resolution_m, solve_resolving_power
from scanplan.core.mtf.threshold import (
    THRESHOLD_METHODS,
    object_contrast,
    threshold_contrast,
    threshold_sandvik_exponential,
    threshold_table,
    weber_to_michelson,
)

__all__ = [
    "COMPONENTS",
    "DEFAULT_GRID_POINTS",
    "DEFAULT_HAZE_CONTRAST",
    "DEFAULT_HAZE_MAX_HEIGHT_M",
    "DEFAULT_ITERATIONS",
    "DEFAULT_K0",
    "DEFAULT_WAVELENGTH_UM",
    "HAZE_METHODS",
    "REGISTRY",
    "THRESHOLD_METHODS",
    "Atmosphere",
    "Camera",
    "Component",
    "Direction",
    "Field",
    "Flight",
    "GroundResolution",
    "Motion",
    "NDArrayBool",
    "NDArrayFloat",
    "ResolvingPower",
    "Scene",
    "Setup",
    "Term",
    "Threshold",
    "UAVResolution",
    "angular_shift_tilt_mm",
    "angular_shift_yaw_mm",
    "charge_transfer_mtf",
    "component_label",
    "component_mtfs",
    "component_names",
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
    "register",
    "resolving_power",
    "solve_resolving_power",
    "system_mtf",
    "threshold_contrast",
    "threshold_sandvik_exponential",
    "threshold_table",
    "turbulence_mtf",
    "uav_resolution",
    "unregister",
    "weber_to_michelson",
]

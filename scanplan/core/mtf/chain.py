"""The chain: multiplies the registered components; resolving and ground resolution."""

from __future__ import annotations

from collections.abc import Callable, Iterable, Mapping
from dataclasses import dataclass
from typing import Any, Literal

import numpy as np
import numpy.typing as npt

from scanplan.core.checks import nonnegative, positive
from scanplan.core.flight import ground_sample_distance_m
from scanplan.core.mtf._base import (
    DEFAULT_GRID_POINTS,
    DEFAULT_ITERATIONS,
    NDArrayBool,
    NDArrayFloat,
)
from scanplan.core.mtf.components import (
    REGISTRY,
    Direction,
    Field,
    Setup,
    Term,
    check_disable,
    component_names,
)
from scanplan.core.mtf.descriptions import Atmosphere, Camera, Flight, Motion, Scene, Threshold
from scanplan.core.mtf.lens import half_field_angle_rad
from scanplan.core.mtf.sensor import nyquist_lpmm
from scanplan.core.mtf.solver import ResolvingPower, ground_resolution_m, solve_resolving_power


def _col(value: npt.ArrayLike) -> NDArrayFloat:
    """Configuration parameter with a trailing axis for the frequency grid."""
    return np.asarray(value, dtype=float)[..., None]


class _Chain:
    """Validated, prepared chain of the registered components (private).

    Every component of :data:`~scanplan.core.mtf.components.REGISTRY` prepares its term once
    (validation, δ, σ, N_c, pixel aperture, …); parameters get a trailing axis of length 1
    for the frequency grid; :meth:`components` and :meth:`product` then evaluate only the
    kernels. :meth:`astype` gives a float32 copy for the solver's coarse phase.
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
        off = check_disable(disable)
        if field not in ("centre", "corner"):
            raise ValueError(f"field must be 'centre' or 'corner' (got {field!r})")
        if direction is None:
            direction = "sagittal" if field == "centre" else "tangential"
        p_um = positive("pixel_um", camera.pixel_um)
        f = positive("focal_mm", camera.focal_mm)
        if field == "corner":
            beta = half_field_angle_rad(camera.sensor_width_mm, camera.sensor_height_mm, f)
            q = 0.5 * np.hypot(np.asarray(camera.sensor_width_mm, float),
                               np.asarray(camera.sensor_height_mm, float))
        else:
            beta, q = np.zeros(()), np.zeros(())
        setup = Setup(
            camera, flight, atmosphere, motion, field, direction,
            pixel_um=p_um, pixel_mm=p_um * 1e-3, focal_mm=f,
            f_number=positive("f_number", camera.f_number),
            height_m=positive("height_m", flight.height_m),
            exposure_s=positive("exposure_s", flight.exposure_s),
            speed_ms=nonnegative("speed_ms", flight.speed_ms),
            beta_rad=beta, lever_mm=q,
        )
        self.nyquist = nyquist_lpmm(p_um)
        self.names = component_names()
        # every component validates its inputs, even when switched off
        prepared = [(c.name, c.prepare(setup)) for c in REGISTRY]
        self.terms: dict[str, Term] = {
            name: term for name, term in prepared if term is not None and name not in off
        }
        widths = [t.box_width_mm for t in self.terms.values() if t.box_width_mm is not None]
        self.motion_width_mm = np.zeros(()) if not widths else np.maximum.reduce(widths)
        sigmas = [t.gauss_sigma_mm for t in self.terms.values() if t.gauss_sigma_mm is not None]
        # product of the Gaussian terms = one Gaussian with the summed variance
        gauss_var = sum((np.asarray(s, float) ** 2 for s in sigmas[1:]),
                        np.asarray(sigmas[0], float) ** 2) if sigmas else None
        self.gauss_var = None if gauss_var is None else _col(gauss_var)
        self.prm = {name: {k: _col(v) for k, v in t.params.items()}
                    for name, t in self.terms.items()}

    def astype(self, dtype: type) -> _Chain:
        """Shallow copy whose parameters have the given float dtype."""
        other = object.__new__(_Chain)
        other.__dict__.update(self.__dict__)
        other.prm = {name: {k: v.astype(dtype) for k, v in p.items()}
                     for name, p in self.prm.items()}
        if self.gauss_var is not None:
            other.gauss_var = self.gauss_var.astype(dtype)
        return other

    def param_shapes(self) -> list[tuple[int, ...]]:
        """Configuration shapes of every parameter (without the frequency axis)."""
        return [v.shape[:-1] for p in self.prm.values() for v in p.values()]

    def _component(self, name: str, n: NDArrayFloat) -> NDArrayFloat:
        return self.terms[name].kernel(n, **self.prm[name])

    def components(self, n: NDArrayFloat) -> dict[str, NDArrayFloat]:
        out = {
            name: self._component(name, n) if name in self.terms else np.ones(np.shape(n))
            for name in self.names  # one entry per registered component
        }
        common = np.broadcast_shapes(*(v.shape for v in out.values()))
        return {k: np.broadcast_to(v, common) for k, v in out.items()}

    def product(self, n: NDArrayFloat) -> NDArrayFloat:
        total: NDArrayFloat | None = None
        for name, term in self.terms.items():  # one factor per registered component
            if term.gauss_sigma_mm is not None:
                continue
            v = self._component(name, n)
            total = v if total is None else total * v
        if self.gauss_var is not None:
            g = np.exp((-2.0 * np.pi**2) * self.gauss_var * (n * n))
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

    Examples
    --------
    Canon EOS 5D Mark II with a 50 mm lens at f/8, 300 m, 25 m/s, 1/1000 s (seed 002):

    >>> cam = Camera(pixel_um=6.4, focal_mm=50.0, f_number=8.0, sensor_width_mm=36.0,
    ...              sensor_height_mm=24.0)
    >>> fl = Flight(height_m=300.0, speed_ms=25.0, exposure_s=1e-3, shift_factor=0.65)
    >>> t = component_mtfs([40.0], cam, fl)
    >>> {k: round(float(v[0]), 4) for k, v in t.items()}  # doctest: +NORMALIZE_WHITESPACE
    {'haze': 0.9, 'turbulence': 0.998, 'lens': 0.7771, 'pixel': 0.8956,
     'charge_transfer': 1.0, 'diffusion': 1.0, 'linear_motion': 0.9808, 'random_motion': 1.0}
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
    return chain.components(nonnegative("freq_lpmm", freq_lpmm))


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

    Examples
    --------
    >>> cam = Camera(6.4, 50.0, 8.0, 36.0, 24.0)
    >>> fl = Flight(300.0, 25.0, 1e-3, 0.65)
    >>> np.round(system_mtf([0.0, 40.0], cam, fl), 4).tolist()
    [0.9, 0.6131]
    """
    return _multiply(component_mtfs(freq_lpmm, camera, flight, atmosphere, motion, **kwargs))


def _multiply(comps: Mapping[str, NDArrayFloat]) -> NDArrayFloat:
    """T(N): the product of the component MTFs, in registry order, broadcast together."""
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

    Examples
    --------
    >>> cam = Camera(6.4, 50.0, 8.0, 36.0, 24.0)
    >>> c = contrast_curves([0.0, 40.0], cam, Flight(300.0, 25.0, 1e-3, 0.65))
    >>> np.round(c["image_contrast"], 4).tolist(), np.round(c["threshold"], 4).tolist()
    ([0.45, 0.3066], [0.03, 0.1806])
    """
    scene = Scene() if scene is None else scene
    threshold = Threshold() if threshold is None else threshold
    comps = component_mtfs(freq_lpmm, camera, flight, atmosphere, motion, **kwargs)
    t = _multiply(comps)
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

    Examples
    --------
    >>> cam = Camera(6.4, 50.0, 8.0, 36.0, 24.0)
    >>> fl = Flight([150.0, 300.0], 25.0, 1e-3, 0.65)
    >>> np.round(resolving_power(cam, fl).r_lpmm, 2).tolist()
    [47.47, 48.86]
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
    rm, upper = _search_ceiling(chain, flight)
    margin, coarse = _margins(chain, scene, threshold, rm, precision)
    return solve_resolving_power(
        margin,
        rm,
        upper_lpmm=upper,
        grid_points=grid_points,
        iterations=iterations,
        coarse_margin=coarse,
    )


def _search_ceiling(chain: _Chain, flight: Flight) -> tuple[NDArrayFloat, NDArrayFloat | None]:
    """R_m per configuration and the search ceiling below it: the first zero of the
    linear-motion sinc, 1/δ, where it lies below R_m (None where it never does)."""
    # every configuration gets its own R, even where nothing depends on it (zero motion:
    # no component varies with the flying height)
    shape = np.broadcast_shapes(np.shape(chain.nyquist), np.shape(chain.motion_width_mm),
                                *chain.param_shapes(),
                                *(np.shape(x) for x in (flight.height_m, flight.speed_ms,
                                                        flight.exposure_s)))
    rm = np.broadcast_to(chain.nyquist, shape)
    width = np.broadcast_to(chain.motion_width_mm, shape)
    upper = None
    below = width * rm > 1.0  # the sinc's first zero lies below R_m (no 1/width overflow)
    if np.any(below):
        upper = np.where(below, 1.0 / np.where(below, width, 1.0), rm)
    return rm, upper


_Margin = Callable[[NDArrayFloat], NDArrayFloat]


def _margins(chain: _Chain, scene: Scene, threshold: Threshold, rm: NDArrayFloat,
             precision: str) -> tuple[_Margin, _Margin | None]:
    """The margin K_obj·T(N) − K_thr(N) in float64, and its float32 version for the
    bracketing steps (``precision="mixed"``; None for ``"double"``)."""
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
    return margin, coarse


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

    Examples
    --------
    >>> cam = Camera(6.4, 50.0, 8.0, 36.0, 24.0)
    >>> g = ground_resolution(cam, Flight(300.0, 25.0, 1e-3, 0.65))
    >>> round(float(g.gsd_m), 4), round(float(g.ground_resolution_m), 4)
    (0.0384, 0.0614)
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

    Examples
    --------
    >>> cam = Camera(6.4, 50.0, 8.0, 36.0, 24.0)
    >>> u = uav_resolution(cam, Flight(300.0, 25.0, 1e-3, 0.65))
    >>> round(float(u.centre.r_lpmm), 2), round(float(u.corner.r_lpmm), 2)
    (48.86, 47.08)
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

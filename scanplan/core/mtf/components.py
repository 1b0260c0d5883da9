"""The registry of MTF components: one record per component, in chain order.

A component is data plus one small function: a :class:`Component` record (name, family,
labels for reports, the seed equation) and its ``prepare`` function, which takes the
validated inputs of a chain (:class:`Setup`) and returns a :class:`Term` — the kernel
``T(N, **params)`` and its per-configuration parameters — or ``None`` where the component
is identically 1. The chain (:mod:`scanplan.core.mtf.chain`) multiplies the terms of
:data:`REGISTRY`; the plan's MTF table (``UavPlan.mtf_centre``: JSON, the workbook's MTF
sheet) lists the same components with :func:`component_label`. Adding a component is
one ``prepare`` function and one :func:`register` call here (the formula itself lives in
its family module: atmosphere, lens, sensor or motion).

Examples
--------
>>> [c.name for c in REGISTRY][:3]
['haze', 'turbulence', 'lens']
>>> component_label("pixel", "ru")
'Апертура пикселя'
"""

from __future__ import annotations

from collections.abc import Callable, Iterable, Mapping
from dataclasses import dataclass, field
from typing import Literal

import numpy as np
import numpy.typing as npt

from scanplan.core.checks import in_range, nonnegative, positive
from scanplan.core.mtf._base import (
    NDArrayFloat,
    _k_charge_transfer,
    _k_diffraction,
    _k_diffusion,
    _k_gauss,
    _k_haze_indicatrix,
    _k_linear_motion,
    _k_sinc,
)
from scanplan.core.mtf.atmosphere import haze_contrast_coefficient, haze_mtf
from scanplan.core.mtf.descriptions import Atmosphere, Camera, Flight, Motion
from scanplan.core.mtf.lens import diffraction_cutoff_lpmm, lens_table_mtf
from scanplan.core.mtf.motion import (
    angular_shift_tilt_mm,
    angular_shift_yaw_mm,
    geometric_image_shift_mm,
    photographic_image_shift_mm,
    random_shift_rms_mm,
)
from scanplan.i18n.messages import Names

__all__ = [
    "COMPONENTS",
    "REGISTRY",
    "Component",
    "Direction",
    "Field",
    "Setup",
    "Term",
    "component_label",
    "component_names",
    "register",
    "unregister",
]

Field = Literal["centre", "corner"]
Direction = Literal["sagittal", "tangential"]


@dataclass(frozen=True, eq=False)
class Setup:
    """Validated inputs of a chain, shared by every component's ``prepare``.

    Attributes
    ----------
    camera, flight, atmosphere, motion : Camera, Flight, Atmosphere, Motion
        The descriptions as given (component-specific fields are validated by the
        component's own ``prepare``).
    field : {"centre", "corner"}
    direction : {"sagittal", "tangential"}
        Lens direction (resolved: sagittal at the centre, tangential at the corner).
    pixel_um, pixel_mm, focal_mm, f_number, height_m, exposure_s, speed_ms : ndarray
        Validated common quantities.
    beta_rad : ndarray
        Field angle β of the analysed point (0 at the centre).
    lever_mm : ndarray
        Lever arm q of angular motion (0 at the centre, the half diagonal at the corner).
    """

    camera: Camera
    flight: Flight
    atmosphere: Atmosphere
    motion: Motion
    field: Field
    direction: Direction
    pixel_um: NDArrayFloat
    pixel_mm: NDArrayFloat
    focal_mm: NDArrayFloat
    f_number: NDArrayFloat
    height_m: NDArrayFloat
    exposure_s: NDArrayFloat
    speed_ms: NDArrayFloat
    beta_rad: NDArrayFloat
    lever_mm: NDArrayFloat


@dataclass(frozen=True, eq=False)
class Term:
    """One prepared component: ``kernel(freq_lpmm, **params)`` is its T(N).

    Attributes
    ----------
    kernel : callable
        ``kernel(n, **params)`` with ``n`` the frequency grid [lines/mm] (last axis) and
        every parameter carrying a trailing axis of length 1; returns T(N) [–].
    params : dict of str to ndarray
        Per-configuration parameters (the chain appends the frequency axis and casts
        them to float32 for the solver's coarse phase).
    gauss_sigma_mm : ndarray, optional
        Set for a Gaussian term exp(−2π²σ²N²): the chain multiplies all Gaussian terms
        as one Gaussian with the summed variance (one ``exp`` per evaluation).
    box_width_mm : ndarray, optional
        Width of a box blur whose MTF has its first zero at 1/width; the solver
        searches below the smallest such zero, where every built-in term is monotone.
    """

    kernel: Callable[..., NDArrayFloat]
    params: dict[str, NDArrayFloat] = field(default_factory=dict)
    gauss_sigma_mm: NDArrayFloat | None = None
    box_width_mm: NDArrayFloat | None = None


@dataclass(frozen=True, eq=False)
class Component:
    """A registered MTF component.

    Attributes
    ----------
    name : str
        Key in :func:`~scanplan.core.mtf.component_mtfs`, the JSON ``mtf_centre`` table and
        ``disable``.
    family : {"atmosphere", "lens", "sensor", "motion"} or str
        Seed 000, eq. 1: T = T_a·T_o·T_m·T_s.
    prepare : callable
        ``prepare(setup) -> Term | None``; validates its inputs (raising ``ValueError``
        naming the field) and returns ``None`` where T ≡ 1 for every configuration.
    label : mapping
        Report label per locale (``{"en": ..., "ru": ...}``).
    source : str
        Where the formula comes from (seed and equation, or a full reference).
    """

    name: str
    family: str
    prepare: Callable[[Setup], Term | None]
    label: Mapping[str, str]
    source: str


REGISTRY: list[Component] = []


def register(component: Component, *, before: str | None = None) -> Component:
    """Add a component to the chain (at the end, or before the named one).

    Parameters
    ----------
    component : Component
    before : str, optional
        Name of a registered component to insert in front of (chain order).

    Returns
    -------
    Component
        The record, for use as a decorator-free one-liner.
    """
    if component.name in component_names():
        raise ValueError(f"component {component.name!r} is already registered")
    if set(component.label) < {"en", "ru"}:
        raise ValueError(f"component {component.name!r} needs an 'en' and a 'ru' label")
    at = len(REGISTRY) if before is None else component_names().index(before)
    REGISTRY.insert(at, component)
    return component


def unregister(name: str) -> None:
    """Remove a registered component by name (tests, plug-ins)."""
    REGISTRY[:] = [c for c in REGISTRY if c.name != name]


def component_names() -> tuple[str, ...]:
    """Names of the registered components, in chain order."""
    return tuple(c.name for c in REGISTRY)


def component_label(name: str, locale: str = "en") -> str:
    """Report label of a registered component in ``locale`` ("en" or "ru").

    Raises
    ------
    KeyError
        If no component of that name is registered.
    """
    for c in REGISTRY:
        if c.name == name:
            return c.label.get(locale, c.label["en"])
    raise KeyError(name)


def _all_zero(value: npt.ArrayLike) -> bool:
    return bool(np.all(np.asarray(value) == 0))


# =================================================================================
# Built-in components (seed 000, eqs. 1–8), in chain order
# =================================================================================
def _k_constant(n: NDArrayFloat, c: NDArrayFloat) -> NDArrayFloat:
    """A frequency-independent factor c (broadcast by the chain)."""
    return c


def _k_lens_diffraction(n: NDArrayFloat, inv_nc: NDArrayFloat) -> NDArrayFloat:
    return _k_diffraction(n * inv_nc)


def _k_pixel(n: NDArrayFloat, aperture_mm: NDArrayFloat) -> NDArrayFloat:
    return _k_sinc(n * aperture_mm)


def _k_diffusion_lpmm(
    n: NDArrayFloat, l0: NDArrayFloat, depletion: NDArrayFloat, absorption: NDArrayFloat
) -> NDArrayFloat:
    return _k_diffusion(n * 1e-3, l0, depletion, absorption)


def _k_one_box(n: NDArrayFloat, d1: NDArrayFloat, d2: NDArrayFloat) -> NDArrayFloat:
    return _k_sinc(n * d1)


def _prepare_haze(s: Setup) -> Term | None:
    atm = s.atmosphere
    if atm.haze_method == "contrast-coefficient":
        c = haze_contrast_coefficient(0.0, atm.contrast_coefficient)
        return None if np.all(c == 1.0) else Term(_k_constant, {"c": c})
    if atm.haze_method == "exponential-indicatrix":
        mu = nonnegative("scattering_per_km", atm.scattering_per_km)
        alpha = positive("indicatrix_per_rad", atm.indicatrix_per_rad)
        return Term(_k_haze_indicatrix,
                    {"f": s.focal_mm, "tau": mu * s.height_m * 1e-3, "alpha": alpha})
    haze_mtf(0.0, atm.haze_method)  # raises ValueError naming the choices
    return None


def _prepare_turbulence(s: Setup) -> Term | None:
    gam = nonnegative("turbulence_urad", s.atmosphere.turbulence_urad)
    if _all_zero(gam):
        return None
    fg = s.focal_mm * gam * 1e-6
    return Term(_k_gauss, {"sigma_mm": fg}, gauss_sigma_mm=fg)


def _prepare_lens(s: Setup) -> Term:
    cam = s.camera
    table = cam.lens_table_centre if s.field == "centre" else cam.lens_table_corner
    if table is not None:
        lens_table_mtf(0.0, table[0], table[1])  # validate the table once
        freq, mtf = table
        return Term(lambda n: lens_table_mtf(n, freq, mtf))
    nc = diffraction_cutoff_lpmm(s.f_number, cam.wavelength_um, s.beta_rad, s.direction)
    return Term(_k_lens_diffraction, {"inv_nc": 1.0 / nc})


def _prepare_pixel(s: Setup) -> Term:
    ff = in_range("fill_factor", s.camera.fill_factor, 0.0, 1.0, low_inclusive=False)
    return Term(_k_pixel, {"aperture_mm": s.pixel_mm * np.sqrt(ff)})


def _prepare_charge_transfer(s: Setup) -> Term | None:
    nt = nonnegative("ccd_transfers", s.camera.ccd_transfers)
    eps = in_range("ccd_inefficiency", s.camera.ccd_inefficiency, 0.0, 1.0,
                    high_inclusive=False)
    if _all_zero(nt * eps):
        return None
    return Term(_k_charge_transfer, {"p_mm": s.pixel_mm, "ne": nt * eps})


def _prepare_diffusion(s: Setup) -> Term | None:
    l0 = nonnegative("diffusion_length_um", s.camera.diffusion_length_um)
    dw = positive("depletion_um", s.camera.depletion_um)
    da = positive("absorption_per_um", s.camera.absorption_per_um)
    if _all_zero(l0):
        return None
    return Term(_k_diffusion_lpmm, {"l0": l0, "depletion": dw, "absorption": da})


def _prepare_linear_motion(s: Setup) -> Term | None:
    delta = photographic_image_shift_mm(
        geometric_image_shift_mm(s.speed_ms, s.exposure_s, s.focal_mm, s.height_m),
        s.flight.shift_factor,
    )
    eta = in_range("shutter_efficiency", s.camera.shutter_efficiency, 0.5, 1.0)
    if _all_zero(delta):
        return None
    d1, d2 = eta * delta, (1.0 - eta) * delta
    kernel = _k_one_box if _all_zero(d2) else _k_linear_motion
    return Term(kernel, {"d1": d1, "d2": d2}, box_width_mm=np.maximum(eta, 1.0 - eta) * delta)


def _prepare_random_motion(s: Setup) -> Term | None:
    m, t, f, q = s.motion, s.exposure_s, s.focal_mm, s.lever_mm
    sigma = random_shift_rms_mm(
        geometric_image_shift_mm(m.random_speed_ms, t, f, s.height_m),
        angular_shift_tilt_mm(m.roll_rate_rad_s, t, f, q),
        angular_shift_tilt_mm(m.pitch_rate_rad_s, t, f, q),
        angular_shift_yaw_mm(m.yaw_rate_rad_s, t, q),
    )
    if _all_zero(sigma):
        return None
    return Term(_k_gauss, {"sigma_mm": sigma}, gauss_sigma_mm=sigma)


for _c in (
    Component("haze", "atmosphere", _prepare_haze, Names("Haze", "Дымка"),
              "seed 000, eq. 1 (or the contrast coefficient of the text after eq. 2)"),
    Component("turbulence", "atmosphere", _prepare_turbulence,
              Names("Turbulence", "Турбулентность"), "seed 000, eq. 2"),
    Component("lens", "lens", _prepare_lens, Names("Lens", "Объектив"),
              "seed 000, eq. 3 (or the manufacturer's table)"),
    Component("pixel", "sensor", _prepare_pixel,
              Names("Pixel aperture", "Апертура пикселя"), "seed 000, eq. 4"),
    Component("charge_transfer", "sensor", _prepare_charge_transfer,
              Names("Charge transfer", "Перенос заряда"), "seed 000, eq. 4"),
    Component("diffusion", "sensor", _prepare_diffusion,
              Names("Diffusion", "Диффузия"),
              "seed 000, eq. 4; form: D. H. Seib, IEEE Trans. Electron Devices 21 (1974) 210–217"),
    Component("linear_motion", "motion", _prepare_linear_motion,
              Names("Linear motion", "Линейный сдвиг"), "seed 000, eqs. 5–6"),
    Component("random_motion", "motion", _prepare_random_motion,
              Names("Random motion", "Случайные колебания"), "seed 000, eqs. 7–8"),
):
    register(_c)

#: Names of the built-in components, in chain order (the registry may hold more).
COMPONENTS: tuple[str, ...] = component_names()


def check_disable(disable: Iterable[str]) -> frozenset[str]:
    """Validate the names of components to switch off (T = 1)."""
    names = frozenset([disable] if isinstance(disable, str) else disable)
    known = component_names()
    unknown = names - set(known)
    if unknown:
        raise ValueError(f"disable must name components of {list(known)} (got {sorted(unknown)})")
    return names

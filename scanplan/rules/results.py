"""Result and input records of the rules engine (film and UAV), in one place.

The engines (:mod:`scanplan.rules.film`, :mod:`scanplan.rules.uav`) build them; the
terminal, ``--json``, the workbook and the PDF render them and never recompute a number.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field
from functools import cached_property
from typing import Any

import numpy as np
from numpy.typing import NDArray

from ..core import mtf as M
from ..i18n.messages import (
    Names,
    PlanWarning,  # a record of the base layer, named here for importers
)

__all__ = [
    "ConstraintResult",
    "Evaluation",
    "HeightLimit",
    "ObjectSpec",
    "PixelReach",
    "PlanWarning",
    "Recognition",
    "ScanInputs",
    "ScanPlan",
    "ScanRules",
    "ScanScenario",
    "UavInputs",
    "UavPlan",
]

@dataclass(frozen=True)
class ScanRules:
    """Normative parameters of the film rules engine (from a norm set).

    Attributes mirror :data:`scanplan.norms.schema.PARAMETERS`.
    """

    planimetric_accuracy_mm: float
    height_accuracy_fraction: float
    processing_loss_k: float
    photoplan_resolution_mm: float
    pr_coefficient: float
    probability: float
    height_formula: str
    constraints: tuple[str, ...]
    standard_forward_overlap_pct: float
    recognition_rounding: str
    interpretation_min_lpmm: float
    interpretation_max_lpmm: float
    # digital (UAV) blocks — scanplan.rules.uav
    digital_height_formula: str
    image_measurement_px: float
    multi_ray: str
    uav_max_height_m: float


@dataclass(frozen=True, eq=False)
class Evaluation:
    """Vectorised engine output.

    Attributes
    ----------
    ids : tuple of str
        Enabled constraints, in the order of the first axis of ``pixel_um``.
    pixels : tuple of ndarray
        Each constraint's largest allowed scan pixel [µm], in the order of ``ids``, each
        broadcast to the scenarios' shape.
    binding_index : ndarray of int
        Index into ``ids`` of the binding constraint.
    scan_pixel_um : ndarray
        The scan pixel, min over constraints [µm].
    """

    ids: tuple[str, ...]
    pixels: tuple[NDArray[np.float64], ...]
    binding_index: NDArray[np.intp]
    scan_pixel_um: NDArray[np.float64]

    @cached_property
    def pixel_um(self) -> NDArray[np.float64]:
        """Each constraint's pixel as one array, shape (n_constraints, ...) [µm] (stacked
        when first asked for: the binding constraint and the scan pixel do not need it)."""
        return np.stack(self.pixels)

    @property
    def binding(self) -> NDArray[np.str_]:
        """Id of the binding constraint per scenario."""
        return np.asarray(self.ids)[self.binding_index]

    @property
    def margin_pct(self) -> NDArray[np.float64]:
        """How much larger each constraint is than the binding one [%]."""
        return (self.pixel_um / self.scan_pixel_um - 1.0) * 100.0


@dataclass(frozen=True)
class ObjectSpec:
    """The object the interpretation constraint protects."""

    name: str
    size_m: float
    shape: str
    shape_coefficient: float
    source: str  # where it comes from (a Message: object_source.norm / object_source.user)
    map_scale: int | None = None  # the norm table row's map scale, if it came from one
    name_ru: str = ""   # the norm table's Russian name (reports in Russian)
    shape_ru: str = ""  # the shape's Russian name
    status: str = ""  # the norm row's status (norm, estimate …); "" for the user's object

    def names(self) -> dict[str, Any]:
        """Message parameters naming the object: ``object``, ``size``, ``shape``."""
        return {"object": Names(self.name, self.name_ru or self.name),
                "size": self.size_m,
                "shape": Names(self.shape, self.shape_ru or self.shape)}


@dataclass(frozen=True)
class ScanInputs:
    """Inputs of a film scan plan (validated by :func:`plan_scan`)."""

    map_scale: float
    relief_interval_m: float
    photo_scales: tuple[float, ...]
    focal_mm: float
    frame_width_mm: float
    frame_along_mm: float
    resolving_power_lpmm: float
    forward_overlap_pct: float
    object: ObjectSpec | None
    camera: str = ""
    scanner: str = ""
    camera_name: str = ""
    scanner_steps_um: tuple[float, ...] = ()
    bands: int = 1
    bits_per_band: int = 8
    candidate_pixels_um: tuple[float, ...] = ()


@dataclass(frozen=True)
class ConstraintResult:
    """One constraint at one photo scale.

    ``protects``, ``equation`` and ``reason`` are :class:`~scanplan.i18n.messages.Message` s:
    English text that renders in another locale with ``.text(locale)``.
    """

    id: str
    name: str
    pixel_um: float
    margin_um: float
    margin_pct: float
    binding: bool
    protects: str
    equation: str
    reason: str
    details: dict[str, Any] = field(default_factory=dict)


@dataclass(frozen=True)
class ScanScenario:
    """The engine's answer at one photo scale (``explanation``: a
    :class:`~scanplan.i18n.messages.Message`)."""

    photo_scale: float
    photo_to_map_ratio: float
    constraints: tuple[ConstraintResult, ...]
    binding: str
    scan_pixel_um: float
    explanation: str
    scanner_pixel_um: float | None
    frame_megabytes: float
    resolution_on_ground_mm: float
    required_resolving_power_lpmm: float | None
    recognition_probability: float | None
    height_pixel_other_um: float | None
    local_photo_scale: float | None = None
    """Over relief (``[terrain]``): the smallest local photo scale of the block (Mc of the
    frame over the lowest ground), at which the constraints, the scan pixel and the binding
    constraint of this scenario were evaluated while ``photo_scale`` stays the scale flown
    over the reference ground; None on flat ground (evaluated at ``photo_scale``)."""

    @property
    def checked_photo_scale(self) -> float:
        """The photo scale the constraints were evaluated at (Mc)."""
        return self.local_photo_scale if self.local_photo_scale is not None else self.photo_scale

    def constraint(self, cid: str) -> ConstraintResult:
        """The result of constraint ``cid``."""
        for c in self.constraints:
            if c.id == cid:
                return c
        raise KeyError(cid)


@dataclass(frozen=True)
class PixelReach:
    """The inverse answer for one available scan pixel: the smallest photo scale (the
    largest Mc) it supports.

    ``max_photo_scale`` is 0 when the pixel is coarser than P_R (no photo scale keeps the
    photo's resolving power); ``limit`` names the constraint that sets it.
    ``max_photo_scale_interpretable`` also respects the interpretation limit: a finer pixel
    lets P_D allow smaller photo scales, but past the limit the photo itself does not carry
    the object (P_D < P_R), so both are reported.
    """

    pixel_um: float
    max_photo_scale: float
    limit: str
    max_photo_scale_interpretable: float | None = None
    """The same, no larger than the interpretation limit (the photo scale beyond which the
    map's object cannot be interpreted even on the original photos, whatever the pixel);
    None without an object."""


@dataclass(frozen=True)
class ScanPlan:
    """A complete film scan plan: inputs, rules, one scenario per photo scale, warnings."""

    inputs: ScanInputs
    rules: ScanRules
    scenarios: tuple[ScanScenario, ...]
    warnings: tuple[PlanWarning, ...]
    interpretation_limit_photo_scale: float | None
    max_photo_scales: tuple[PixelReach, ...] = ()
    sweep: dict[str, Any] = field(default_factory=dict)

    @property
    def constraint_ids(self) -> tuple[str, ...]:
        """The constraints the engine evaluated, in its order (the norm set's enabled ids,
        then the registered constraints that need no norm switch)."""
        return tuple(c.id for c in self.scenarios[0].constraints) if self.scenarios else ()


@dataclass(frozen=True)
class UavInputs:
    """Camera, flight and (optionally) the map a UAV flight must serve.

    Lengths on the sensor in mm/µm, on the ground in m; angles in degrees; overlaps in %.
    """

    pixel_um: float
    focal_mm: float
    f_number: float
    sensor_width_mm: float
    sensor_height_mm: float
    height_m: float
    speed_ms: float
    exposure_s: float
    forward_overlap_pct: float = 80.0
    side_overlap_pct: float = 60.0
    height_tolerance_up_pct: float = 0.0
    height_tolerance_down_pct: float = 0.0
    camera: str = ""
    camera_name: str = ""
    image_width_px: int | None = None
    image_height_px: int | None = None
    min_trigger_interval_s: float | None = None
    r_max: float = 0.3
    r_min: float = 0.1
    threshold_k0: float = M.DEFAULT_K0
    haze_contrast: float = M.DEFAULT_HAZE_CONTRAST
    shift_factor: float = 1.0
    random_speed_ms: float = 0.0
    roll_rate_rad_s: float = 0.0
    pitch_rate_rad_s: float = 0.0
    yaw_rate_rad_s: float = 0.0
    roll_deg: float = 0.0
    pitch_deg: float = 0.0
    map_scale: float | None = None
    relief_interval_m: float | None = None
    map_object: ObjectSpec | None = None
    objects: tuple[ObjectSpec, ...] = ()
    area_width_m: float | None = None
    area_length_m: float | None = None
    bands: int = 3
    bits_per_band: int = 8
    orientation: str = "landscape"
    platform: str = "uav"
    lens_table_centre: tuple[tuple[float, ...], tuple[float, ...]] | None = None
    lens_table_corner: tuple[tuple[float, ...], tuple[float, ...]] | None = None
    ceiling_m: float | None = None
    ceiling_from_project: bool = False
    aerodrome_distance_km: float | None = None
    """The norm set's distance from the reference points of uncontrolled aerodromes for
    flights without an airspace-use permission in the 2020 wording [km]."""
    airspace_conditions: Mapping[str, str] | None = None
    """The conditions of flights without an airspace-use permission in both languages (a
    :class:`~scanplan.i18n.messages.Names`)
    (``norms/catalogue/airspace-conditions.csv``, :mod:`scanplan.norms.airspace`)."""
    airspace_wording: str = ""
    """The date of the conditions' wording (ISO)."""
    gsd_target_m: float | None = None
    gsd_limit_m: float | None = None
    """The norm set's largest GSD for the map scale (table ``gsd_limits``) [m]."""
    gsd_limit_area: str = "general"
    """Its row: ``general`` or ``dense_urban``."""
    gsd_limit_source: str = ""


@dataclass(frozen=True)
class Recognition:
    """Recognition probability of one norm object, P = exp(−(B·L/L_obj)²) (seed 001, eq. 7)."""

    object: str
    object_size_m: float
    shape: str
    map_scale: int | None
    probability: float | None
    probability_at_max_height: float | None
    probability_corner_at_max_height: float | None


@dataclass(frozen=True)
class HeightLimit:
    """One constraint as a maximum planned flight height.

    ``reason`` and ``equation`` are :class:`~scanplan.i18n.messages.Message` s: English text that
    renders in another locale with ``.text(locale)``.
    """

    id: str
    name: str
    limit_m: float          # limit the GSD, L (on the ground) or H (flown) must not exceed [m]
    compares: str           # "GSD", "L" or "H" (the altitude ceiling)
    max_height_m: float     # largest PLANNED height whose highest flown height meets it [m]
    binding: bool
    margin_pct: float
    reason: str
    equation: str
    max_flown_height_m: float | None = None  # max_height_m × (1 + tolerance) [m]
    details: dict[str, Any] = field(default_factory=dict)


@dataclass(frozen=True)
class UavPlan:
    """Everything ``scanplan uav`` reports (one result object for text, JSON and reports)."""

    inputs: UavInputs
    heights_m: dict[str, float]
    gsd_m: float
    gsd_at_max_height_m: float
    nyquist_lpmm: float
    resolving_power_lpmm: float | None
    resolving_power_corner_lpmm: float | None
    ground_resolution_m: float | None
    ground_resolution_corner_m: float | None
    ground_resolution_at_max_height_m: float | None
    ground_resolution_to_gsd: float | None
    resolvable: bool
    sensor_limited: bool
    motion_blur_px: float
    max_exposure_s: float
    max_speed_ms: float
    tilted_corner_gsd_m: float | None
    flight: dict[str, Any]
    recognition: tuple[Recognition, ...]
    limits: tuple[HeightLimit, ...]
    max_height_m: float | None
    binding: str | None
    warnings: tuple[PlanWarning, ...]
    mtf_centre: dict[str, Any] = field(default_factory=dict)
    height_curve: dict[str, Any] = field(default_factory=dict)
    max_flown_height_m: float | None = None
    ceiling_m: float | None = None
    constraints_max_height_m: float | None = None
    height_accuracy: dict[str, Any] = field(default_factory=dict)
    over_relief: bool = False
    """``heights_m["min"]``/``["max"]`` are the lowest and highest heights above the ground
    really flown over relief (not the planned height ± its tolerance)."""

    @property
    def max_planned_height_m(self) -> float | None:
        """The largest planned height whose highest flown height meets every limit [m]."""
        return self.max_height_m

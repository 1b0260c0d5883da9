"""The rules engine: which scan pixel a contract needs, and why.

Every enabled constraint gives the largest scan pixel that still protects one property of
the map (planimetric accuracy, heights, the graphic photo-plan, the photo's resolving
power, interpretation of the smallest map objects). The scan pixel is their minimum; the
constraint that attains it is *binding*. The engine reports every constraint with its
margin to the binding one, the reason it exists, and warnings drawn from seed 001's
conclusions.

Two layers:

- :func:`evaluate` — one vectorised call over any number of scenarios (pure numpy).
- :func:`plan_scan` — a film/scan plan for a handful of photo scales, with explanations,
  inverse answers (largest photo scale for a scanner pixel, interpretation limit),
  scanner steps and data volume. Its result objects feed the terminal, ``--json`` and the
  reports alike.

The engine takes its normative numbers in a :class:`ScanRules` (built from a norm set by
:meth:`scanplan.norms.NormSet.rules`); it reads no files.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from . import formulas as F
from .domains import check_domain, check_range
from .errors import InputError
from .messages import Message, localize

__all__ = [
    "CONSTRAINTS",
    "ConstraintInfo",
    "ConstraintResult",
    "Evaluation",
    "ObjectSpec",
    "PixelReach",
    "PlanWarning",
    "ScanInputs",
    "ScanPlan",
    "ScanRules",
    "ScanScenario",
    "check_range",
    "evaluate",
    "height_formula_name",
    "interpretation_limit_photo_scale",
    "max_photo_scale",
    "plan_scan",
    "round_to_scanner",
]


@dataclass(frozen=True)
class ScanRules:
    """Normative parameters of the film rules engine (from a norm set).

    Attributes mirror :data:`scanplan.normschema.PARAMETERS`.
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
    # digital (UAV) blocks — scanplan.uav
    digital_height_formula: str
    image_measurement_px: float
    multi_ray: str
    uav_max_height_m: float


@dataclass(frozen=True)
class ConstraintInfo:
    """What a constraint protects and where its formula comes from."""

    id: str
    name: str
    name_ru: str
    protects: str
    equation: str
    depends_on_photo_scale: bool


CONSTRAINTS: dict[str, ConstraintInfo] = {
    "PS": ConstraintInfo("PS", "planimetric accuracy", "точность в плане",
                         Message("protects.PS"), Message("equation.PS"), True),
    "PZ": ConstraintInfo("PZ", "height accuracy", "точность по высоте",
                         Message("protects.PZ"), Message("equation.PZ"), True),
    "PP": ConstraintInfo("PP", "graphic photo-plan", "графический фотоплан",
                         Message("protects.PP"), Message("equation.PP"), True),
    "PR": ConstraintInfo("PR", "resolving power of the photo", "разрешающая способность снимка",
                         Message("protects.PR"), Message("equation.PR"), False),
    "PD": ConstraintInfo("PD", "interpretation", "дешифрирование",
                         Message("protects.PD"), Message("equation.PD"), True),
    # limits of a UAV flight only (scanplan.uav); the film engine never enables them
    "GSD": ConstraintInfo("GSD", "target GSD", "заданный размер пикселя на местности",
                          Message("protects.GSD"), Message("equation.GSD"), False),
    "HC": ConstraintInfo("HC", "altitude ceiling", "предельная высота полёта",
                         Message("protects.HC"), Message("equation.HC"), False),
}
"""The film constraints, in the Instruction's order, then the UAV-only limits."""


# ---------------------------------------------------------------------------------------
# Vectorised core
# ---------------------------------------------------------------------------------------


@dataclass(frozen=True)
class Evaluation:
    """Vectorised engine output.

    Attributes
    ----------
    ids : tuple of str
        Enabled constraints, in the order of the first axis of ``pixel_um``.
    pixel_um : ndarray, shape (n_constraints, ...)
        Each constraint's largest allowed scan pixel [µm].
    binding_index : ndarray of int
        Index into ``ids`` of the binding constraint.
    scan_pixel_um : ndarray
        The scan pixel, min over constraints [µm].
    """

    ids: tuple[str, ...]
    pixel_um: NDArray[np.float64]
    binding_index: NDArray[np.intp]
    scan_pixel_um: NDArray[np.float64]

    @property
    def binding(self) -> NDArray[np.str_]:
        """Id of the binding constraint per scenario."""
        return np.asarray(self.ids)[self.binding_index]

    @property
    def margin_pct(self) -> NDArray[np.float64]:
        """How much larger each constraint is than the binding one [%]."""
        return (self.pixel_um / self.scan_pixel_um - 1.0) * 100.0


def constraint_pixels_um(
    rules: ScanRules,
    *,
    map_scale: ArrayLike,
    photo_scale: ArrayLike,
    relief_interval_m: ArrayLike,
    focal_mm: ArrayLike,
    frame_along_mm: ArrayLike,
    forward_overlap_pct: ArrayLike,
    resolving_power_lpmm: ArrayLike,
    object_size_m: ArrayLike,
    shape_coefficient: ArrayLike,
    height_formula: str | None = None,
) -> dict[str, NDArray[np.float64]]:
    """Each enabled constraint's pixel [µm], vectorised (see :data:`CONSTRAINTS`)."""
    out: dict[str, NDArray[np.float64]] = {}
    for cid in rules.constraints:
        if cid == "PS":
            out[cid] = F.planimetric_pixel_um(
                map_scale, photo_scale,
                planimetric_accuracy_mm=rules.planimetric_accuracy_mm,
                processing_loss_k=rules.processing_loss_k)
        elif cid == "PZ":
            out[cid] = F.height_pixel_um(
                relief_interval_m, photo_scale, focal_mm,
                F.photo_base_mm(frame_along_mm, forward_overlap_pct),
                height_accuracy_fraction=rules.height_accuracy_fraction,
                processing_loss_k=rules.processing_loss_k,
                method=height_formula or rules.height_formula)  # type: ignore[arg-type]
        elif cid == "PP":
            out[cid] = F.photoplan_pixel_um(
                map_scale, photo_scale, photoplan_resolution_mm=rules.photoplan_resolution_mm)
        elif cid == "PR":
            out[cid] = F.resolving_power_pixel_um(
                resolving_power_lpmm, pr_coefficient=rules.pr_coefficient)
        elif cid == "PD":
            out[cid] = F.interpretation_pixel_um(
                np.asarray(object_size_m, dtype=np.float64) * 1000.0, photo_scale,
                shape_coefficient, rules.probability,
                pr_coefficient=rules.pr_coefficient,
                rounding=rules.recognition_rounding)  # type: ignore[arg-type]
        else:  # the norm schema only lets known ids through
            raise ValueError(f"unknown constraint {cid!r}")
    return out


def evaluate(
    rules: ScanRules,
    *,
    map_scale: ArrayLike,
    photo_scale: ArrayLike,
    relief_interval_m: ArrayLike,
    focal_mm: ArrayLike,
    frame_along_mm: ArrayLike,
    forward_overlap_pct: ArrayLike,
    resolving_power_lpmm: ArrayLike,
    object_size_m: ArrayLike = np.nan,
    shape_coefficient: ArrayLike = np.nan,
) -> Evaluation:
    """Evaluate the enabled constraints and pick the binding one, for any array of scenarios.

    Parameters
    ----------
    rules : ScanRules
        Normative parameters and the list of enabled constraints.
    map_scale : array_like
        Mk [-].
    photo_scale : array_like
        Mc [-].
    relief_interval_m : array_like
        h_c [m].
    focal_mm : array_like
        f [mm].
    frame_along_mm : array_like
        Frame side along track l_y [mm].
    forward_overlap_pct : array_like
        p [%].
    resolving_power_lpmm : array_like
        R of the photo [lines/mm].
    object_size_m : array_like
        L of the object to interpret [m] (needed when P_D is enabled).
    shape_coefficient : array_like
        B of that object [-].

    Returns
    -------
    Evaluation
        All inputs broadcast together; inputs are not validated here (see
        :func:`plan_scan`), NaN in gives NaN out.
    """
    values = constraint_pixels_um(
        rules, map_scale=map_scale, photo_scale=photo_scale,
        relief_interval_m=relief_interval_m, focal_mm=focal_mm,
        frame_along_mm=frame_along_mm, forward_overlap_pct=forward_overlap_pct,
        resolving_power_lpmm=resolving_power_lpmm, object_size_m=object_size_m,
        shape_coefficient=shape_coefficient)
    ids = tuple(values)
    shape = np.broadcast_shapes(*(np.shape(x) for x in (
        map_scale, photo_scale, relief_interval_m, focal_mm, frame_along_mm,
        forward_overlap_pct, resolving_power_lpmm, object_size_m, shape_coefficient)))
    stacked = np.stack([np.broadcast_to(v, shape) for v in values.values()])
    idx = np.argmin(stacked, axis=0)
    scan = np.take_along_axis(stacked, idx[np.newaxis], axis=0)[0]
    return Evaluation(ids=ids, pixel_um=stacked, binding_index=idx, scan_pixel_um=scan)


def max_photo_scale(
    rules: ScanRules,
    pixel_um: ArrayLike,
    *,
    map_scale: ArrayLike,
    relief_interval_m: ArrayLike,
    focal_mm: ArrayLike,
    frame_along_mm: ArrayLike,
    forward_overlap_pct: ArrayLike,
    resolving_power_lpmm: ArrayLike,
    object_size_m: ArrayLike = np.nan,
    shape_coefficient: ArrayLike = np.nan,
) -> tuple[NDArray[np.float64], NDArray[np.str_]]:
    """The largest photo scale denominator Mc a given scan pixel supports.

    Every constraint except P_R is a limit on the ground divided by Mc, so
    Mc_max = min_i(P_i(Mc = 1) / pixel). P_R does not depend on Mc: a pixel coarser than P_R
    supports no photo scale (Mc_max = 0, limited by ``"PR"``).

    Parameters
    ----------
    rules : ScanRules
        As :func:`evaluate`.
    pixel_um : array_like
        The scan pixel available [µm].
    map_scale, relief_interval_m, focal_mm, frame_along_mm : array_like
        As :func:`evaluate`.
    forward_overlap_pct, resolving_power_lpmm, object_size_m, shape_coefficient : array_like
        As :func:`evaluate`.

    Returns
    -------
    mc_max : ndarray
        Largest Mc [-] (0 where no scale works).
    limiting : ndarray of str
        The constraint that sets it.
    """
    at_unit_scale = constraint_pixels_um(
        rules, map_scale=map_scale, photo_scale=1.0, relief_interval_m=relief_interval_m,
        focal_mm=focal_mm, frame_along_mm=frame_along_mm,
        forward_overlap_pct=forward_overlap_pct, resolving_power_lpmm=resolving_power_lpmm,
        object_size_m=object_size_m, shape_coefficient=shape_coefficient)
    pixel = np.asarray(pixel_um, dtype=np.float64)
    scaled = {k: v for k, v in at_unit_scale.items() if CONSTRAINTS[k].depends_on_photo_scale}
    if scaled:
        ids = np.asarray(tuple(scaled))
        stacked = np.stack(np.broadcast_arrays(*scaled.values(), pixel))[:-1]
        ratios = stacked / pixel
        idx = np.argmin(ratios, axis=0)
        mc = np.take_along_axis(ratios, idx[np.newaxis], axis=0)[0]
        limiting = ids[idx]
    else:
        mc = np.full(np.shape(pixel), np.inf)
        limiting = np.full(np.shape(pixel), "", dtype="<U2")
    if "PR" in at_unit_scale:
        pr = at_unit_scale["PR"]
        too_coarse = pixel > pr * (1.0 + 1e-12)
        mc, limiting, too_coarse = np.broadcast_arrays(mc, limiting, too_coarse)
        mc = np.where(too_coarse, 0.0, mc)
        limiting = np.where(too_coarse, "PR", limiting)
    return np.asarray(mc, dtype=np.float64), np.asarray(limiting)


def interpretation_limit_photo_scale(
    object_size_m: ArrayLike,
    shape_coefficient: ArrayLike,
    probability: ArrayLike,
    resolving_power_lpmm: ArrayLike,
    *,
    rounding: str = "exact",
) -> NDArray[np.float64]:
    """Mc_interp: the smallest photo scale at which the object is still recognisable.

    Mc_interp = 2·L·sqrt(−ln P)·R / B, i.e. the Mc where P_D = P_R (equivalently
    A = L·sqrt(−ln P)/B). At larger Mc the object cannot be interpreted even on the
    original photos.

    Parameters
    ----------
    object_size_m : array_like
        L [m].
    shape_coefficient : array_like
        B [-].
    probability : array_like
        P in (0, 1).
    resolving_power_lpmm : array_like
        R of the photo [lines/mm].
    rounding : {"exact", "paper"}
        See :func:`scanplan.formulas.probability_root`.

    Returns
    -------
    ndarray
        Mc_interp [-]: ≈ 8850 for 20 cm poles (1:2000 map), circle, P = 0.75, R = 40.

    Notes
    -----
    Seed 001 conclusion 1 ("keep Mc/Mk < 5" for 1:2000) follows from it.
    """
    root = F.probability_root(probability, rounding)  # type: ignore[arg-type]
    return (
        2.0 * np.asarray(object_size_m, dtype=np.float64) * 1000.0 * root
        * np.asarray(resolving_power_lpmm, dtype=np.float64)
        / np.asarray(shape_coefficient, dtype=np.float64)
    )


def round_to_scanner(pixel_um: ArrayLike, steps_um: Sequence[float]) -> NDArray[np.float64]:
    """Largest scanner step not coarser than ``pixel_um`` (NaN if all steps are coarser).

    Parameters
    ----------
    pixel_um : array_like
        Required scan pixel [µm].
    steps_um : sequence of float
        Pixels the scanner offers [µm].

    Returns
    -------
    ndarray
        Scanner pixel to use [µm].
    """
    steps = np.sort(np.asarray(steps_um, dtype=np.float64))
    pixel = np.asarray(pixel_um, dtype=np.float64)
    idx = np.searchsorted(steps, pixel * (1.0 + 1e-9), side="right") - 1
    return np.where(idx >= 0, steps[np.clip(idx, 0, None)], np.nan)


# ---------------------------------------------------------------------------------------
# A plan for a handful of photo scales, with explanations
# ---------------------------------------------------------------------------------------


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

    def names(self) -> dict[str, Any]:
        """Message parameters naming the object: ``object``, ``size``, ``shape``."""
        return {"object": {"en": self.name, "ru": self.name_ru or self.name},
                "size": self.size_m,
                "shape": {"en": self.shape, "ru": self.shape_ru or self.shape}}


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
    scanner_steps_um: tuple[float, ...] = ()
    bands: int = 1
    bits_per_band: int = 8
    candidate_pixels_um: tuple[float, ...] = ()


@dataclass(frozen=True)
class ConstraintResult:
    """One constraint at one photo scale.

    ``protects``, ``equation`` and ``reason`` are :class:`~scanplan.messages.Message` s:
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
class PlanWarning:
    """A warning or note from the rules (``severity`` is ``"warning"`` or ``"info"``).

    ``message`` is a :class:`~scanplan.messages.Message` (its English text) whose code is
    ``code``; :meth:`text` renders it in another locale.
    """

    code: str
    message: str
    photo_scales: tuple[float, ...] = ()
    severity: str = "warning"

    def text(self, locale: str = "en") -> str:
        """The message in ``locale`` (``"en"`` or ``"ru"``)."""
        return localize(self.message, locale)


@dataclass(frozen=True)
class ScanScenario:
    """The engine's answer at one photo scale (``explanation``: a
    :class:`~scanplan.messages.Message`)."""

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

    def constraint(self, cid: str) -> ConstraintResult:
        """The result of constraint ``cid``."""
        for c in self.constraints:
            if c.id == cid:
                return c
        raise KeyError(cid)


@dataclass(frozen=True)
class PixelReach:
    """The inverse answer for one available scan pixel: the largest photo scale it supports.

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


def validate_inputs(inp: ScanInputs, rules: ScanRules) -> None:
    """Raise :class:`InputError` (field = the input's name) for any value outside its domain
    (:data:`scanplan.domains.DOMAINS`)."""
    check_domain("map_scale", inp.map_scale)
    if not inp.photo_scales:
        raise InputError("photo_scale", "give at least one photo scale")
    for mc in inp.photo_scales:
        check_domain("photo_scale", mc)
    for name in ("relief_interval_m", "focal_mm", "frame_width_mm", "frame_along_mm",
                 "resolving_power_lpmm", "forward_overlap_pct", "bands", "bits_per_band"):
        check_domain(name, getattr(inp, name))
    for s in inp.scanner_steps_um:
        check_domain("scanner", s)
    for s in inp.candidate_pixels_um:
        check_domain("pixel_um", s)
    if inp.object is not None:
        check_domain("object_size_m", inp.object.size_m)
        check_domain("shape", inp.object.shape_coefficient)
    elif "PD" in rules.constraints:
        raise InputError(
            "object_size_m",
            f"the norm set has no smallest object for map scale 1:{inp.map_scale:g}; "
            "give the object size in m (> 0)")
    check_domain("probability", rules.probability)
    check_domain("pr_coefficient", rules.pr_coefficient)


def height_formula_name(formula: str) -> Message | str:
    """The height formula's name as a message parameter (``instruction``/``parallax``)."""
    try:
        return Message(f"height_formula.{formula}")
    except KeyError:
        return formula


def _reason(cid: str, inp: ScanInputs, rules: ScanRules) -> Message:
    """Why constraint ``cid`` is there, with this contract's numbers."""
    k = rules.processing_loss_k
    if cid == "PS":
        ground = rules.planimetric_accuracy_mm * inp.map_scale / 1000.0
        return Message("reason.PS", vs=rules.planimetric_accuracy_mm, map=inp.map_scale,
                       ground=ground, k=k)
    if cid == "PZ":
        vz = rules.height_accuracy_fraction * inp.relief_interval_m
        return Message("reason.PZ", fraction=rules.height_accuracy_fraction, vz=vz,
                       hc=inp.relief_interval_m, k=k,
                       formula=height_formula_name(rules.height_formula))
    if cid == "PP":
        return Message("reason.PP", resolution=rules.photoplan_resolution_mm * 1000,
                       map=inp.map_scale)
    if cid == "PR":
        return Message("reason.PR", r=inp.resolving_power_lpmm, kr=rules.pr_coefficient)
    obj = inp.object
    assert obj is not None
    return Message("reason.PD", obj.names(), b=obj.shape_coefficient, p=rules.probability)


def _constraint_name(cid: str) -> dict[str, str]:
    info = CONSTRAINTS[cid]
    return {"en": info.name, "ru": info.name_ru}


def plan_scan(inp: ScanInputs, rules: ScanRules) -> ScanPlan:
    """Evaluate a film scan plan at each photo scale, with explanations and warnings.

    Parameters
    ----------
    inp : ScanInputs
        Map, camera, photo scales, object to interpret, scanner.
    rules : ScanRules
        Normative parameters.

    Returns
    -------
    ScanPlan

    Raises
    ------
    InputError
        For out-of-range input (``field`` is the input's name, e.g. ``"photo_scale"``).
    """
    validate_inputs(inp, rules)
    mc = np.asarray(inp.photo_scales, dtype=np.float64)
    obj = inp.object
    size_m = obj.size_m if obj else np.nan
    coef = obj.shape_coefficient if obj else np.nan
    common: dict[str, Any] = dict(
        map_scale=inp.map_scale, relief_interval_m=inp.relief_interval_m,
        focal_mm=inp.focal_mm, frame_along_mm=inp.frame_along_mm,
        forward_overlap_pct=inp.forward_overlap_pct,
        resolving_power_lpmm=inp.resolving_power_lpmm, object_size_m=size_m,
        shape_coefficient=coef)
    ev = evaluate(rules, photo_scale=mc, **common)
    other_formula = "parallax" if rules.height_formula == "instruction" else "instruction"
    pz_other = F.height_pixel_um(
        inp.relief_interval_m, mc, inp.focal_mm,
        F.photo_base_mm(inp.frame_along_mm, inp.forward_overlap_pct),
        height_accuracy_fraction=rules.height_accuracy_fraction,
        processing_loss_k=rules.processing_loss_k, method=other_formula)  # type: ignore[arg-type]
    a_mm = F.resolution_on_ground_mm(mc, inp.resolving_power_lpmm)
    rounding = rules.recognition_rounding
    if obj:
        r_needed = F.required_resolving_power_lpmm(
            obj.size_m * 1000.0, mc, obj.shape_coefficient, rules.probability,
            rounding=rounding)  # type: ignore[arg-type]
        mc_interp = float(interpretation_limit_photo_scale(
            obj.size_m, obj.shape_coefficient, rules.probability, inp.resolving_power_lpmm,
            rounding=rounding))
    else:
        r_needed = np.full_like(mc, np.nan)
        mc_interp = None
    scanner_px = (round_to_scanner(ev.scan_pixel_um, inp.scanner_steps_um)
                  if inp.scanner_steps_um else None)
    delivered = scanner_px if scanner_px is not None else ev.scan_pixel_um
    volume_px = np.where(np.isfinite(delivered), delivered, ev.scan_pixel_um)
    mbytes = F.scanned_frame_bytes(inp.frame_width_mm, inp.frame_along_mm, volume_px,
                                   bands=inp.bands, bits_per_band=inp.bits_per_band) / 1e6
    # image resolving power after scanning: the photo's R, or what the pixel keeps
    r_eff = np.minimum(inp.resolving_power_lpmm, rules.pr_coefficient / (volume_px / 1000.0))
    p_rec = (F.recognition_probability(obj.size_m * 1000.0,
                                       F.resolution_on_ground_mm(mc, r_eff),
                                       obj.shape_coefficient) if obj else None)

    warnings: list[PlanWarning] = []
    scenarios = []
    margins = ev.margin_pct
    for j, scale in enumerate(mc):
        bind_i = int(ev.binding_index[j])
        scan = float(ev.scan_pixel_um[j])
        results = []
        for i, cid in enumerate(ev.ids):
            info = CONSTRAINTS[cid]
            val = float(ev.pixel_um[i, j])
            details: dict[str, Any] = {}
            if cid == "PZ":
                details = {"formula": rules.height_formula,
                           f"{other_formula}_pixel_um": float(pz_other[j]),
                           "base_mm": float(F.photo_base_mm(inp.frame_along_mm,
                                                            inp.forward_overlap_pct))}
            elif cid == "PD" and obj:
                details = {"object": obj.name, "object_size_m": obj.size_m,
                           "shape": obj.shape, "shape_coefficient": obj.shape_coefficient,
                           "probability": rules.probability,
                           "required_resolving_power_lpmm": float(r_needed[j])}
            elif cid == "PR":
                details = {"pr_coefficient": rules.pr_coefficient,
                           "resolving_power_lpmm": inp.resolving_power_lpmm}
            results.append(ConstraintResult(
                id=cid, name=info.name, pixel_um=val, margin_um=val - scan,
                margin_pct=float(margins[i, j]), binding=(i == bind_i),
                protects=info.protects, equation=info.equation,
                reason=_reason(cid, inp, rules), details=details))
        bind = ev.ids[bind_i]
        runner = sorted((r for r in results if not r.binding), key=lambda r: r.pixel_um)
        explanation = Message(
            "explanation", cid=bind, name=_constraint_name(bind), scale=float(scale),
            pixel=scan, reason=results[bind_i].reason,
            next=Message("explanation.next", cid=runner[0].id, pixel=runner[0].pixel_um,
                         margin=runner[0].margin_pct) if runner else None)
        sp = float(scanner_px[j]) if scanner_px is not None else None
        scenarios.append(ScanScenario(
            photo_scale=float(scale), photo_to_map_ratio=float(scale / inp.map_scale),
            constraints=tuple(results), binding=bind, scan_pixel_um=scan,
            explanation=explanation,
            scanner_pixel_um=sp if sp is None or math.isfinite(sp) else None,
            frame_megabytes=float(mbytes[j]), resolution_on_ground_mm=float(a_mm[j]),
            required_resolving_power_lpmm=float(r_needed[j]) if obj else None,
            recognition_probability=float(p_rec[j]) if p_rec is not None else None,
            height_pixel_other_um=float(pz_other[j])))

    warnings.extend(_scenario_warnings(inp, rules, scenarios, mc_interp))
    overlap = overlap_warning(
        rules, inp.forward_overlap_pct,
        Message("overlap_not_standard.detail", pairs=[
            Message("overlap_not_standard.pair", pixel=s.height_pixel_other_um or 0,
                    scale=s.photo_scale) for s in scenarios]))
    if overlap:
        warnings.append(overlap)

    pixels = sorted(set(inp.scanner_steps_um) | set(inp.candidate_pixels_um))
    reach: tuple[PixelReach, ...] = ()
    if pixels:
        m, lim = max_photo_scale(rules, np.asarray(pixels), **common)
        reach = tuple(PixelReach(float(p), float(mm), str(ll),
                                 None if mc_interp is None else min(float(mm), mc_interp))
                      for p, mm, ll in zip(pixels, m, lim, strict=True))
    # a dense sweep of photo scales for plots and the Sweep sheet (one vectorised call)
    lo, hi = float(mc.min()) * 0.5, float(mc.max()) * 2.0
    grid = np.geomspace(lo, hi, 61)
    dense = evaluate(rules, photo_scale=grid, **common)
    sweep: dict[str, Any] = {"photo_scale": grid.tolist()}
    for i, cid in enumerate(dense.ids):
        sweep[cid] = dense.pixel_um[i].tolist()
    sweep["scan_pixel_um"] = dense.scan_pixel_um.tolist()
    sweep["binding"] = dense.binding.tolist()
    return ScanPlan(inputs=inp, rules=rules, scenarios=tuple(scenarios), sweep=sweep,
                    warnings=tuple(warnings), interpretation_limit_photo_scale=mc_interp,
                    max_photo_scales=reach)


def overlap_warning(rules: ScanRules, forward_overlap_pct: float,
                    detail: Message | None = None) -> PlanWarning | None:
    """``overlap_not_standard`` when the printed height formula meets a non-standard overlap.

    Parameters
    ----------
    rules : ScanRules
        Enabled constraints, height formula and the Instruction's standard overlap.
    forward_overlap_pct : float
        The overlap flown [%].
    detail : Message, optional
        ``overlap_not_standard.detail``: the parallax form's numbers, if the caller has them.
    """
    if ("PZ" not in rules.constraints or rules.height_formula != "instruction"
            or math.isclose(forward_overlap_pct, rules.standard_forward_overlap_pct)):
        return None
    return PlanWarning("overlap_not_standard", Message(
        "overlap_not_standard", overlap=forward_overlap_pct,
        standard=rules.standard_forward_overlap_pct, detail=detail))


def _at_scales(xs: Sequence[ScanScenario]) -> Message:
    """``at 1:10000, 1:15000`` (the Russian form agrees in number)."""
    return Message("at_scale" if len(xs) == 1 else "at_scales",
                   scales=[x.photo_scale for x in xs])


def _scenario_warnings(inp: ScanInputs, rules: ScanRules, scen: Sequence[ScanScenario],
                       mc_interp: float | None) -> list[PlanWarning]:
    """Warnings from seed 001's conclusions, one per code, naming the photo scales."""
    out = []
    obj = inp.object
    if obj and mc_interp is not None:
        bad = [s for s in scen if s.photo_scale > mc_interp * (1 + 1e-12)]
        if bad:
            pr = float(F.resolving_power_pixel_um(inp.resolving_power_lpmm,
                                                  pr_coefficient=rules.pr_coefficient))
            common: dict[str, Any] = {
                **obj.names(), "need": [s.required_resolving_power_lpmm for s in bad],
                "r": inp.resolving_power_lpmm, "limit": math.floor(mc_interp),
                "ratio": mc_interp / inp.map_scale}
            if "PD" in rules.constraints:
                msg = Message("not_interpretable", common, at=_at_scales(bad),
                              pd=[s.constraint("PD").pixel_um for s in bad], pr=pr)
            else:
                msg = Message("above_interpretation_limit", common,
                              scales=[s.photo_scale for s in bad])
            out.append(PlanWarning(msg.code, msg,
                                   photo_scales=tuple(s.photo_scale for s in bad)))
    for s in scen:
        if s.binding != "PR":
            continue
        others = [c for c in s.constraints if c.id != "PR"]
        if not others:
            continue
        coarsest = min(others, key=lambda c: c.pixel_um)
        ratio = (coarsest.pixel_um / s.scan_pixel_um) ** 2
        if ratio > 1.0 + 1e-9:
            out.append(PlanWarning(
                "pr_drives_volume",
                Message("pr_drives_volume", scale=s.photo_scale, pr=s.scan_pixel_um,
                        coarsest=coarsest.pixel_um, cid=coarsest.id, ratio=ratio),
                photo_scales=(s.photo_scale,), severity="info"))
    if inp.scanner_steps_um:
        fine = [s for s in scen if s.scanner_pixel_um is None]
        if fine:
            out.append(PlanWarning(
                "scanner_too_coarse",
                Message("scanner_too_coarse", at=_at_scales(fine),
                        pixels=[s.scan_pixel_um for s in fine], scanner=inp.scanner,
                        step=min(inp.scanner_steps_um)),
                photo_scales=tuple(s.photo_scale for s in fine)))
    return out

"""UAV digital-camera planning: real ground resolution combined with the Instruction.

A digital camera delivers two things on the ground (docs/architecture.md):
GSD = p·H/f (geometry) and the MTF ground resolution L = H/(2·R·f) (seed 000). The
Instruction's geometric constraints are limits on the ground that the GSD must not exceed
(P_S, P_Z, P_P multiplied by Mc); the interpretation constraint is a limit that L must not
exceed (seed 001's A ≤ L_obj·sqrt(−ln P)/B with A ≡ L). Each limit gives a maximum flight
height; the smallest is binding.

Light UAVs do not hold the planned height (seed 002: 300 m planned, 300–420 m flown): the
constraints are checked at the highest height flown, blur and overlaps at the lowest. The
*maximum planned height* is the largest planned height whose highest flown height,
planned × (1 + tolerance), still meets every limit; an altitude ceiling limits that highest
flown height (docs/uav-models.md §10).

The height constraint of a digital block is by default the stereo normal case with the
widest base of standard overlap, σ_Z = (H/B)·(H/c)·σ_px ≤ V_z (docs/uav-models.md §9); the
Instruction's P_Z and its parallax form are computed beside it for comparison.

Pure numpy on top of :mod:`scanplan.mtf` and :mod:`scanplan.flight`; no I/O.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, replace
from typing import Any

import numpy as np

from . import flight as FL
from . import formulas as F
from . import mtf as M
from .domains import check_domain
from .errors import InputError
from .messages import Message
from .orientation import attitude_matrix, corner_gsd
from .planner import (
    CONSTRAINTS,
    ObjectSpec,
    PlanWarning,
    ScanRules,
    height_formula_name,
    overlap_warning,
)

__all__ = ["HeightLimit", "Recognition", "UavInputs", "UavPlan", "plan_uav"]

_HEIGHT_GRID_POINTS = 257  # 1 m … 20 km in steps of 4 %
_HEIGHT_PASS_POINTS = 62  # each refinement pass cuts the bracket 63-fold
_HEIGHT_TOLERANCE_M = 1e-3
_MAX_SEARCH_HEIGHT_M = 20_000.0


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
    gsd_target_m: float | None = None


@dataclass(frozen=True)
class Recognition:
    """Recognition probability of one norm object, P = exp(−(B·L/L_obj)²) (seed 001 eq. 7)."""

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

    ``reason`` and ``equation`` are :class:`~scanplan.messages.Message` s: English text that
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

    @property
    def max_planned_height_m(self) -> float | None:
        """The largest planned height whose highest flown height meets every limit [m]."""
        return self.max_height_m


def _chain(inp: UavInputs, height_m: Any) -> tuple[M.Camera, M.Flight, M.Atmosphere,
                                                   M.Motion, M.Scene, M.Threshold]:
    cam = M.Camera(inp.pixel_um, inp.focal_mm, inp.f_number, inp.sensor_width_mm,
                   inp.sensor_height_mm, lens_table_centre=inp.lens_table_centre,
                   lens_table_corner=inp.lens_table_corner)
    fl = M.Flight(height_m, inp.speed_ms, inp.exposure_s, inp.shift_factor)
    atm = M.Atmosphere(contrast_coefficient=inp.haze_contrast)
    mot = M.Motion(inp.random_speed_ms, inp.roll_rate_rad_s, inp.pitch_rate_rad_s,
                   inp.yaw_rate_rad_s)
    return cam, fl, atm, mot, M.Scene(inp.r_max, inp.r_min), M.Threshold(
        params={"k0": inp.threshold_k0})


def _resolution(inp: UavInputs, height_m: Any) -> M.UAVResolution:
    try:
        return M.uav_resolution(*_chain(inp, height_m))
    except ValueError as exc:  # the models name their field first: "pixel_um must be > 0"
        name = str(exc).split(" ", 1)[0]
        raise InputError(name, str(exc).split(" ", 1)[1] if " " in str(exc) else str(exc)
                         ) from None


def _f(x: Any) -> float | None:
    v = float(np.asarray(x))
    return v if math.isfinite(v) else None


def max_height_for_ground_resolution(inp: UavInputs, limit_m: float) -> float:
    """Highest height at which the centre L does not exceed ``limit_m``.

    Vectorised search: L on a log grid of heights from 1 m to the search ceiling in one
    call, then passes that cut the bracket of the *first* crossing 63-fold each, again one
    call per pass, until it is narrower than 1 mm (about four MTF solves in all, instead of
    a scalar bisection's 25). L grows with height (tests/test_mtf.py); should it not, the
    first crossing is the safe answer. Where L is not resolvable it is taken as exceeding
    every limit. Returns 0 if even 1 m fails, the ceiling if nothing fails below it.

    Parameters
    ----------
    inp : UavInputs
        Camera, flight and target.
    limit_m : float
        The largest ground resolution L allowed [m].

    Returns
    -------
    float
        The maximum height [m], within 1 mm below the crossing.
    """
    def ok(heights_m: np.ndarray) -> np.ndarray:
        lr = np.asarray(_resolution(inp, heights_m).centre.ground_resolution_m, dtype=float)
        return np.isfinite(lr) & (lr <= limit_m)

    grid = np.geomspace(1.0, _MAX_SEARCH_HEIGHT_M, _HEIGHT_GRID_POINTS)
    fails = np.flatnonzero(~ok(grid))
    if fails.size == 0:
        return _MAX_SEARCH_HEIGHT_M
    if fails[0] == 0:
        return 0.0
    lo, hi = float(grid[fails[0] - 1]), float(grid[fails[0]])
    while hi - lo >= _HEIGHT_TOLERANCE_M:
        inner = np.linspace(lo, hi, _HEIGHT_PASS_POINTS + 2)[1:-1]
        fails = np.flatnonzero(~ok(inner))
        if fails.size == 0:
            lo = float(inner[-1])
        else:
            hi = float(inner[fails[0]])
            if fails[0] > 0:
                lo = float(inner[fails[0] - 1])
    return lo


def _check_inputs(inp: UavInputs) -> None:
    """Every input in its domain (:data:`scanplan.domains.DOMAINS`), field = its name."""
    for name in ("pixel_um", "focal_mm", "f_number", "sensor_width_mm", "sensor_height_mm",
                 "height_m", "exposure_s", "speed_ms", "random_speed_ms", "roll_rate_rad_s",
                 "pitch_rate_rad_s", "yaw_rate_rad_s", "forward_overlap_pct",
                 "side_overlap_pct", "height_tolerance_up_pct", "height_tolerance_down_pct",
                 "roll_deg", "pitch_deg", "threshold_k0", "haze_contrast", "shift_factor",
                 "r_max", "r_min"):
        check_domain(name, getattr(inp, name))
    if inp.r_min > inp.r_max:
        raise InputError("r_min", f"must be ≤ r_max: the darkest detail is not lighter than the "
                         f"lightest (got r_min {inp.r_min!r}, r_max {inp.r_max!r})")
    if inp.map_scale is not None:
        check_domain("map_scale", inp.map_scale)
        check_domain("relief_interval_m", inp.relief_interval_m)
    if inp.map_object is not None:
        check_domain("object_size_m", inp.map_object.size_m)
        check_domain("shape", inp.map_object.shape_coefficient)
    for name in ("area_width_m", "area_length_m"):
        if getattr(inp, name) is not None:
            check_domain(name, getattr(inp, name))
    if inp.ceiling_m is not None:
        check_domain("max_height_m", inp.ceiling_m)
    if inp.gsd_target_m is not None:
        check_domain("gsd_cm", inp.gsd_target_m * 100.0)


def _height_accuracy(inp: UavInputs, rules: ScanRules
                     ) -> tuple[float, Message, dict[str, Any]]:
    """The height constraint of a digital block: (GSD limit [m], reason, details).

    Three forms, each as the largest GSD on the ground (evaluated at Mc = 1):

    - ``normal_case`` (default for digital cameras): σ_Z = (H/B)·(H/c)·σ_px·f ≤ V_z with
      the widest base of standard stereo overlap (:func:`scanplan.formulas.
      stereo_height_ground_limit_m`), V_z read as an RMS error;
    - ``instruction`` and ``parallax``: the Instruction's P_Z and its parallax form with the
      single-step base b = l_y·(1 − p) and the processing loss k (seed 001 eq. 2).

    All three are in ``details["forms"]`` for comparison; ``rules.digital_height_formula``
    picks the one that constrains the flight.
    """
    assert inp.relief_interval_m is not None
    k = rules.processing_loss_k
    vz = rules.height_accuracy_fraction * inp.relief_interval_m
    pixel_m = inp.pixel_um / 1e6
    up = 1.0 + inp.height_tolerance_up_pct / 100.0
    base_mm = F.photo_base_mm(inp.sensor_height_mm, inp.forward_overlap_pct)
    forms: dict[str, dict[str, float]] = {}
    for form in ("instruction", "parallax"):
        g = float(F.height_pixel_um(inp.relief_interval_m, 1.0, inp.focal_mm, base_mm,
                                    height_accuracy_fraction=rules.height_accuracy_fraction,
                                    processing_loss_k=k, method=form)) / 1e6  # type: ignore[arg-type]
        forms[form] = {"ground_limit_m": g}
    fraction = float(F.stereo_base_fraction(inp.forward_overlap_pct,
                                            rules.standard_forward_overlap_pct))
    steps = round(fraction / (1.0 - inp.forward_overlap_pct / 100.0))
    bh = fraction * inp.sensor_height_mm / inp.focal_mm
    multi = (float(F.strip_multi_ray_factor(inp.forward_overlap_pct,
                                            rules.standard_forward_overlap_pct))
             if rules.multi_ray == "strip" else 1.0)
    sigma = rules.image_measurement_px
    forms["normal_case"] = {"ground_limit_m": float(F.stereo_height_ground_limit_m(
        vz, bh, sigma, multi))}
    for v in forms.values():
        v["max_flown_height_m"] = v["ground_limit_m"] * inp.focal_mm / 1000.0 / pixel_m
        v["max_planned_height_m"] = v["max_flown_height_m"] / up
    formula = rules.digital_height_formula
    h_plan = inp.height_m
    h_hi = h_plan * up
    sz = F.normal_case_height_error_m(np.array([h_plan, h_hi]),
                                      bh * np.array([h_plan, h_hi]), inp.focal_mm,
                                      inp.pixel_um, sigma, multi)
    details: dict[str, Any] = {
        "formula": formula, "height_accuracy_m": vz,
        "height_accuracy_meaning": "RMS (one standard deviation) of the model heights",
        "stereo_base_steps": steps, "stereo_base_to_height": bh,
        "stereo_overlap_pct": 100.0 * (1.0 - fraction),
        "single_step_base_to_height": float(base_mm) / inp.focal_mm,
        "image_measurement_px": sigma, "multi_ray": rules.multi_ray,
        "multi_ray_factor": multi, "processing_loss_k": k,
        "sigma_z_at_planned_height_m": float(sz[0]),
        "sigma_z_at_highest_flown_height_m": float(sz[1]),
        "sigma_z_in_gsd": sigma * multi / bh,
        "forms": forms,
    }
    if formula == "normal_case":
        reason = Message("limit.PZ.normal_case", vz=vz, hc=inp.relief_interval_m, bh=bh,
                         steps=steps, overlap=100.0 * (1.0 - fraction), sigma=sigma,
                         multi=Message("limit.PZ.multi", f=multi) if multi < 1.0 else None)
    else:
        reason = Message("limit.PZ", vz=vz, hc=inp.relief_interval_m, k=k,
                         formula=height_formula_name(formula))
    return forms[formula]["ground_limit_m"], reason, details


def _ground_limits(inp: UavInputs, rules: ScanRules) -> dict[str, tuple[float, str, Message]]:
    """id → (ground limit [m], compares-with, reason) for the enabled constraints.

    P_S, P_Z, P_P of seed 001 eqs. 1–3 times Mc are limits on the ground; P_R has no digital
    counterpart (the sensor is the "scan"); P_D becomes a limit on L.
    """
    assert inp.map_scale is not None and inp.relief_interval_m is not None
    out: dict[str, tuple[float, str, Message]] = {}
    k = rules.processing_loss_k
    mk = inp.map_scale
    # the evaluation at Mc = 1 gives each pixel limit times Mc, i.e. on the ground [µm → m]
    if "PS" in rules.constraints:
        g = float(F.planimetric_pixel_um(mk, 1.0, planimetric_accuracy_mm=rules.
                                         planimetric_accuracy_mm, processing_loss_k=k)) / 1e6
        out["PS"] = (g, "GSD", Message("limit.PS", vs=rules.planimetric_accuracy_mm, map=mk,
                                       k=k))
    if "PZ" in rules.constraints:
        g, reason, _ = _height_accuracy(inp, rules)
        out["PZ"] = (g, "GSD", reason)
    if "PP" in rules.constraints:
        g = float(F.photoplan_pixel_um(mk, 1.0, photoplan_resolution_mm=rules.
                                       photoplan_resolution_mm)) / 1e6
        out["PP"] = (g, "GSD", Message("limit.PP",
                                       resolution=rules.photoplan_resolution_mm * 1000, map=mk))
    obj = inp.map_object
    if "PD" in rules.constraints and obj is not None:
        root = float(F.probability_root(rules.probability, rules.recognition_rounding))  # type: ignore[arg-type]
        g = obj.size_m * root / obj.shape_coefficient
        out["PD"] = (g, "L", Message("limit.PD", obj.names(), p=rules.probability))
    return out


def _height_limits(inp: UavInputs, rules: ScanRules | None) -> tuple[
        tuple[HeightLimit, ...], float | None, str | None, float | None, dict[str, Any],
        list[PlanWarning]]:
    """Every limit as a maximum PLANNED height, the binding one, and the ceiling's effect.

    A limit on the GSD or on L holds at the highest flown height H·(1 + tolerance); the
    altitude ceiling limits the highest flown height itself. So every limit gives the
    largest planned height whose highest flown height still meets it, and the smallest is
    the maximum planned height.

    Returns
    -------
    limits, max planned height [m], binding id, what the constraints other than the
    ceiling allow [m] (None unless the ceiling binds), height-accuracy details, warnings.
    """
    up = 1.0 + inp.height_tolerance_up_pct / 100.0
    h_plan = inp.height_m
    raw: list[tuple[str, float, str, Message, float, dict[str, Any]]] = []
    accuracy: dict[str, Any] = {}
    warnings: list[PlanWarning] = []
    if inp.map_scale is not None:
        if rules is None:
            raise ValueError("rules are needed with a map scale")
        if "PZ" in rules.constraints:
            accuracy = _height_accuracy(inp, rules)[2]
        for cid, (g, compares, reason) in _ground_limits(inp, rules).items():
            h_at_limit = (g * inp.focal_mm / (inp.pixel_um / 1000.0) if compares == "GSD"
                          else max_height_for_ground_resolution(inp, g))
            raw.append((cid, g, compares, reason, h_at_limit / up,
                        accuracy if cid == "PZ" else {}))
        digital = replace(rules, height_formula=rules.digital_height_formula)
        overlap = overlap_warning(digital, inp.forward_overlap_pct)
        if overlap:
            warnings.append(overlap)
    if inp.gsd_target_m is not None:
        g = inp.gsd_target_m
        raw.append(("GSD", g, "GSD", Message("limit.GSD", gsd=g * 100.0),
                    g * inp.focal_mm / (inp.pixel_um / 1000.0) / up, {}))
    if inp.ceiling_m is not None:
        source = Message("ceiling.project" if inp.ceiling_from_project else "ceiling.norms")
        raw.append(("HC", inp.ceiling_m, "H", Message("limit.HC", ceiling=inp.ceiling_m,
                                                      source=source),
                    inp.ceiling_m / up, {"from_project": inp.ceiling_from_project}))
    if not raw:
        return (), None, None, None, accuracy, warnings
    best = min(raw, key=lambda r: r[4])
    max_h, binding = best[4], best[0]
    limits = tuple(HeightLimit(
        id=cid, name=CONSTRAINTS[cid].name, limit_m=g, compares=compares,
        max_height_m=h, binding=(cid == binding),
        margin_pct=(h / max_h - 1) * 100 if max_h > 0 else math.inf, reason=reason,
        equation=Message("equation.PZ.normal_case")
        if cid == "PZ" and details.get("formula") == "normal_case"
        else CONSTRAINTS[cid].equation, max_flown_height_m=h * up, details=details)
        for cid, g, compares, reason, h, details in raw)
    allow = None
    others = [r for r in raw if r[0] != "HC"]
    if binding == "HC" and others:
        nxt = min(others, key=lambda r: r[4])
        if nxt[4] > max_h * (1 + 1e-9):
            allow = nxt[4]
            warnings.append(PlanWarning("ceiling_binds", Message(
                "ceiling_binds", ceiling=inp.ceiling_m, max=max_h, allow=allow, cid=nxt[0],
                tolerance=Message("ceiling_binds.tolerance",
                                  tolerance=inp.height_tolerance_up_pct)
                if inp.height_tolerance_up_pct else None), severity="info"))
    if h_plan > max_h * (1 + 1e-9):
        info = CONSTRAINTS[binding]
        warnings.append(PlanWarning("height_above_max", Message(
            "height_above_max", height=h_plan, max=max_h, cid=binding,
            name={"en": info.name, "ru": info.name_ru},
            tolerance=Message("height_above_max.tolerance",
                              tolerance=inp.height_tolerance_up_pct)
            if inp.height_tolerance_up_pct else None)))
    return limits, max_h, binding, allow, accuracy, warnings


def _flight_time_s(length_m: float, speed_ms: float) -> float | None:
    """Time on the strips [s]; None at ground speed 0, or where a subnormal speed makes it
    infinite (never ``inf`` in a result)."""
    if speed_ms <= 0:
        return None
    with np.errstate(over="ignore", divide="ignore"):
        t = float(FL.flight_time_s(length_m, speed_ms))
    return t if math.isfinite(t) else None


def plan_uav(inp: UavInputs, rules: ScanRules | None = None) -> UavPlan:
    """Plan a UAV flight: GSD, MTF ground resolution, blur, flight geometry, and — with a map
    scale — the maximum flight height under the norm set's constraints.

    Parameters
    ----------
    inp : UavInputs
        Camera, flight, scene and map.
    rules : ScanRules, optional
        Needed when ``inp.map_scale`` is given.

    Returns
    -------
    UavPlan

    Raises
    ------
    InputError
        Naming the field for out-of-range input.
    """
    _check_inputs(inp)
    if rules is not None:
        check_domain("probability", rules.probability)
    band = FL.height_band(inp.height_m, inp.height_tolerance_up_pct / 100.0,
                          inp.height_tolerance_down_pct / 100.0)
    h_plan, h_lo, h_hi = inp.height_m, float(band.min_m), float(band.max_m)
    res = _resolution(inp, np.array([h_plan, h_hi]))
    c, k = res.centre, res.corner
    gsd = FL.ground_sample_distance_m(inp.pixel_um, np.array([h_plan, h_lo, h_hi]),
                                      inp.focal_mm)
    gsd_plan, gsd_lo, gsd_hi = (float(x) for x in gsd)
    resolvable = bool(np.asarray(c.resolvable)[0])
    warnings: list[PlanWarning] = []

    if inp.haze_contrast == M.DEFAULT_HAZE_CONTRAST and h_hi > M.DEFAULT_HAZE_MAX_HEIGHT_M:
        warnings.append(PlanWarning("haze_default_height", Message(
            "haze_default_height", c=inp.haze_contrast, valid=M.DEFAULT_HAZE_MAX_HEIGHT_M,
            height=h_hi, key="[uav.atmosphere] haze_contrast"), severity="info"))
    blur = float(FL.motion_blur_px(inp.speed_ms, inp.exposure_s, gsd_lo))
    max_exp = float(FL.max_exposure_for_blur_s(max(inp.speed_ms, 1e-12), gsd_lo))
    max_speed = float(FL.max_speed_for_blur_ms(inp.exposure_s, gsd_lo))
    if blur > FL.MAX_BLUR_PX:
        warnings.append(PlanWarning("motion_blur", Message(
            "motion_blur", blur=blur, height=h_lo, limit=FL.MAX_BLUR_PX,
            denominator=math.ceil(1 / max_exp), speed=max_speed)))

    fp_across = float(FL.footprint_m(inp.sensor_width_mm, h_plan, inp.focal_mm))
    fp_along = float(FL.footprint_m(inp.sensor_height_mm, h_plan, inp.focal_mm))
    base = float(FL.photo_base_m(fp_along, inp.forward_overlap_pct))
    spacing = float(FL.line_spacing_m(fp_across, inp.side_overlap_pct))
    with np.errstate(over="ignore"):  # a subnormal speed: inf, shown as "—"
        interval = (float(FL.photo_interval_s(base, inp.speed_ms)) if inp.speed_ms > 0
                    else math.inf)
    fl: dict[str, Any] = {
        "footprint_across_m": fp_across, "footprint_along_m": fp_along, "base_m": base,
        "line_spacing_m": spacing, "photo_interval_s": interval,
        "forward_overlap_at_min_height_pct": float(FL.actual_overlap_pct(
            inp.forward_overlap_pct, h_plan, h_lo)),
        "side_overlap_at_min_height_pct": float(FL.actual_overlap_pct(
            inp.side_overlap_pct, h_plan, h_lo)),
        "forward_overlap_at_max_height_pct": float(FL.actual_overlap_pct(
            inp.forward_overlap_pct, h_plan, h_hi)),
    }
    if inp.min_trigger_interval_s:
        fl["min_trigger_interval_s"] = inp.min_trigger_interval_s
        fl["max_speed_for_trigger_ms"] = float(FL.max_speed_for_trigger_ms(
            base, inp.min_trigger_interval_s))
        if interval < inp.min_trigger_interval_s:
            warnings.append(PlanWarning("trigger_interval", Message(
                "trigger_interval", interval=interval, minimum=inp.min_trigger_interval_s,
                speed=fl["max_speed_for_trigger_ms"])))
    if inp.area_width_m and inp.area_length_m:
        strips = max(1, int(FL.strip_count(inp.area_width_m, spacing)))  # 1e-300 m: one
        per_strip = int(FL.photos_per_strip(inp.area_length_m, base))
        # each strip is flown over its photographed span, first to last exposure (the
        # photos past the block ends included), not the block length
        length = float(FL.flight_length_m(strips, (per_strip - 1) * base, spacing))
        fl.update({"strips": strips, "photos_per_strip": per_strip,
                   "photos": strips * per_strip, "flight_length_m": length,
                   "flight_time_s": _flight_time_s(length, inp.speed_ms)})
        if inp.image_width_px and inp.image_height_px:
            fl["data_volume_bytes"] = float(FL.data_volume_bytes(
                strips * per_strip, inp.image_width_px, inp.image_height_px,
                inp.bands, inp.bits_per_band))

    tilt = None
    if inp.roll_deg or inp.pitch_deg:
        rot = attitude_matrix(math.radians(inp.roll_deg), math.radians(inp.pitch_deg))
        tilt = _f(corner_gsd(h_hi, inp.focal_mm, inp.pixel_um, inp.sensor_width_mm,
                             inp.sensor_height_mm, rotation=rot).worst_m)
        if tilt is None or not tilt > 0:
            raise InputError("roll_deg" if abs(inp.roll_deg) >= abs(inp.pitch_deg)
                             else "pitch_deg", "at this roll and pitch a corner of the frame "
                             "looks at or above the horizon; give a smaller tilt")

    l_plan = _f(np.asarray(c.ground_resolution_m)[0])
    l_hi = _f(np.asarray(c.ground_resolution_m)[1])
    l_corner_hi = _f(np.asarray(k.ground_resolution_m)[1])
    if not resolvable:
        warnings.append(PlanWarning("not_resolvable", Message(
            "not_resolvable", contrast=float(M.object_contrast(inp.r_max, inp.r_min)),
            threshold=inp.threshold_k0)))

    def p_rec(obj: ObjectSpec, l_m: float | None) -> float | None:
        if l_m is None:
            return None
        return float(F.recognition_probability(obj.size_m, l_m, obj.shape_coefficient))

    recognition = tuple(
        Recognition(o.name, o.size_m, o.shape, o.map_scale, p_rec(o, l_plan),
                    p_rec(o, l_hi), p_rec(o, l_corner_hi))
        for o in inp.objects)

    limits, max_h, binding, allow, accuracy, lim_warnings = _height_limits(inp, rules)
    warnings.extend(lim_warnings)
    up = 1.0 + inp.height_tolerance_up_pct / 100.0
    max_flown = max_h * up if max_h is not None else None

    # GSD and L against height, for plots (one vectorised call)
    top = max(h_hi, max_flown or 0.0) * 1.3
    hs = np.linspace(top / 30.0, top, 30)
    curve = _resolution(inp, hs).centre
    height_curve = {"height_m": hs.tolist(),
                    "gsd_m": np.asarray(curve.gsd_m).ravel().tolist(),
                    "ground_resolution_m": [
                        None if not math.isfinite(v) else v
                        for v in np.asarray(curve.ground_resolution_m).ravel().tolist()]}
    freq = np.linspace(0, float(M.nyquist_lpmm(inp.pixel_um)), 41)
    curves = M.contrast_curves(freq, *_chain(inp, h_plan))
    return UavPlan(
        inputs=inp, heights_m={"planned": h_plan, "min": h_lo, "max": h_hi},
        gsd_m=gsd_plan, gsd_at_max_height_m=gsd_hi,
        nyquist_lpmm=float(M.nyquist_lpmm(inp.pixel_um)),
        resolving_power_lpmm=_f(np.asarray(c.r_lpmm)[0]),
        resolving_power_corner_lpmm=_f(np.asarray(k.r_lpmm)[0]),
        ground_resolution_m=l_plan, ground_resolution_corner_m=_f(
            np.asarray(k.ground_resolution_m)[0]),
        ground_resolution_at_max_height_m=l_hi,
        ground_resolution_to_gsd=_f(np.asarray(c.l_over_gsd)[0]),
        resolvable=resolvable,
        sensor_limited=bool(np.asarray(c.resolving_power.sensor_limited)[0]),
        motion_blur_px=blur, max_exposure_s=max_exp, max_speed_ms=max_speed,
        tilted_corner_gsd_m=tilt, flight=fl, height_curve=height_curve,
        recognition=recognition, limits=limits,
        max_height_m=max_h, binding=binding, warnings=tuple(warnings),
        max_flown_height_m=max_flown, ceiling_m=inp.ceiling_m,
        constraints_max_height_m=allow, height_accuracy=accuracy,
        mtf_centre={"freq_lpmm": freq.tolist(),
                    **{name: np.asarray(v).ravel().tolist() for name, v in curves.items()}})


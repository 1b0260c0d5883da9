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

Pure numpy on top of :mod:`scanplan.core.mtf` and :mod:`scanplan.core.flight`; no I/O.
"""

from __future__ import annotations

import math
from dataclasses import replace
from typing import Any

import numpy as np

from ..core import flight as FL
from ..core import formulas as F
from ..core import mtf as M
from ..core import photoscale as PS
from ..core.domains import DOMAINS, check_domain
from ..core.orientation import attitude_matrix, corner_gsd
from ..core.shown import shown_above
from ..errors import FieldValueError, InputError
from ..i18n.messages import Message, Names
from ..i18n.messages_uav import date_words
from ..io.kept import Kept
from .constraints import height_accuracy as _height_accuracy  # noqa: F401  (tests, importers)
from .film import check_probability, overlap_warning
from .registry import CONSTRAINTS, DigitalLimit, digital_ids
from .resolution import (
    centre_resolution_m,
    chain,
    chain_key,
    max_height_for_ground_resolution,
    resolution_at,
)
from .results import (
    HeightLimit,
    ObjectSpec,
    PlanWarning,
    Recognition,
    ScanRules,
    UavInputs,
    UavPlan,
)

__all__ = ["SWEEP_COLUMNS", "HeightLimit", "Recognition", "UavInputs", "UavPlan",
           "ground_resolution_m", "height_sweep", "max_height_for_ground_resolution",
           "plan_uav", "with_curves"]

_chain = chain  # the MTF chain's descriptions at a height (.resolution)


def _resolution(inp: UavInputs, height_m: Any) -> M.UAVResolution:
    try:
        return M.uav_resolution(*_chain(inp, height_m))
    except FieldValueError as exc:  # the models name their field: a typed error, not a text
        raise InputError(exc.field, exc.message) from None


def ground_resolution_m(inp: UavInputs, heights_m: Any) -> np.ndarray:
    """The MTF ground resolution L at the frame centre for an array of heights [m].

    One vectorised solve of the heights not solved before for this camera chain
    (seed 000: L = H/(2·R·f), :func:`.resolution.centre_resolution_m`); NaN where nothing
    is resolved. Used by the terrain layer for every photo's own height above ground.

    Parameters
    ----------
    inp : UavInputs
        Camera, flight and target (``height_m`` is ignored).
    heights_m : array_like
        Heights above ground [m], > 0.

    Returns
    -------
    ndarray
        L [m], the shape of ``heights_m``.
    """
    h = np.asarray(heights_m, dtype=float)
    if h.size == 0:
        return np.zeros(h.shape)
    return centre_resolution_m(inp, h)


def _f(x: Any) -> float | None:
    v = float(np.asarray(x))
    return v if math.isfinite(v) else None


def _check_inputs(inp: UavInputs) -> None:
    """Every input in its domain (:data:`scanplan.core.domains.DOMAINS`), field = its name."""
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


def _limit_rows(inp: UavInputs, rules: ScanRules | None
                ) -> list[tuple[str, DigitalLimit, float]]:
    """(id, limit, largest planned height [m]) of every applicable registry constraint.

    A limit on the GSD gives H = g·f/p, one on L the height where L reaches it
    (:func:`max_height_for_ground_resolution`), one on H itself is that height; each at the
    highest flown height, so the planned height is that divided by 1 + tolerance.
    """
    up = 1.0 + inp.height_tolerance_up_pct / 100.0
    with_map = inp.map_scale is not None
    if with_map and rules is None:
        raise ValueError("rules are needed with a map scale")
    rows = []
    for cid in digital_ids(rules.constraints if rules is not None else (), with_map=with_map):
        rec = CONSTRAINTS[cid]
        lim = rec.ground_limit(inp, rules)  # type: ignore[misc]
        if lim is None:
            continue
        g = lim.limit_m
        if rec.compares == "GSD":
            h_at_limit = float(PS.height_for_ground_pixel_m(g, inp.pixel_um, inp.focal_mm))
        elif rec.compares == "L":
            h_at_limit = max_height_for_ground_resolution(inp, g)
        elif cid == "HC" and _strict_ceiling(inp):
            h_at_limit = g * (1.0 - _BELOW)  # "below 150 m": the ceiling itself is not allowed
        else:
            h_at_limit = g
        rows.append((cid, lim, h_at_limit / up))
    return rows


_BELOW = 1e-9
"""A strict ceiling ("below 150 m") as a relative margin: the largest height allowed is the
ceiling × (1 − _BELOW), so the recommended height (rounded down to 5 m) stays below it."""


def _strict_ceiling(inp: UavInputs) -> bool:
    """The norm set's ceiling for flights without an airspace-use permission is a strict
    bound (the Federal Rules say "below 150 m"); a project's own ceiling is inclusive."""
    return inp.ceiling_m is not None and not inp.ceiling_from_project


def _airspace_warnings(inp: UavInputs) -> list[PlanWarning]:
    """The conditions of flying without an airspace-use permission (printed with every plan
    under the norm set's ceiling), and a warning when the highest flown height is not below
    that ceiling."""
    if not _strict_ceiling(inp):
        return []
    assert inp.ceiling_m is not None
    out = [PlanWarning("airspace_conditions", Message(
        "airspace_conditions", conditions=inp.airspace_conditions or Names("", ""),
        date=date_words(inp.airspace_wording) if inp.airspace_wording else ""),
        severity="warning")]  # conditions the crew must check: what to act on
    up = 1.0 + inp.height_tolerance_up_pct / 100.0
    flown = inp.height_m * up
    if flown >= inp.ceiling_m * (1.0 - _BELOW):
        out.append(PlanWarning("airspace_not_below", Message(
            "airspace_not_below", flown=flown, ceiling=inp.ceiling_m, planned=inp.height_m,
            key="[uav] max_height_m")))
    return out


def _ceiling_and_height_warnings(inp: UavInputs, rows: list[tuple[str, DigitalLimit, float]],
                                 max_h: float, binding: str
                                 ) -> tuple[float | None, list[PlanWarning]]:
    """``ceiling_binds`` (with what the other constraints allow) and ``height_above_max``."""
    warnings: list[PlanWarning] = []
    allow = None
    others = [r for r in rows if r[0] != "HC"]
    if binding == "HC" and others:
        nxt = min(others, key=lambda r: r[2])
        if nxt[2] > max_h * (1 + 1e-9):
            allow = nxt[2]
            warnings.append(PlanWarning("ceiling_binds", Message(
                "ceiling_binds", ceiling=inp.ceiling_m, max=max_h, allow=allow, cid=nxt[0],
                tolerance=Message("ceiling_binds.tolerance",
                                  tolerance=inp.height_tolerance_up_pct)
                if inp.height_tolerance_up_pct else None), severity="info"))
    if inp.height_m > max_h * (1 + 1e-9):
        info = CONSTRAINTS[binding]
        lowest = DOMAINS["height_m"].lo  # below it no height is flown (not "0 m")
        code = ("height_above_max" if max_h >= lowest else "height_not_feasible"
                if max_h > 0 else "height_never_feasible")
        extra = {"lowest": lowest} if code == "height_not_feasible" else {}
        warnings.append(PlanWarning("height_above_max", Message(
            code, height=inp.height_m, max=max_h, cid=binding, **extra,
            name=Names(info.name, info.name_ru),
            tolerance=Message("height_above_max.tolerance",
                              tolerance=inp.height_tolerance_up_pct)
            if inp.height_tolerance_up_pct else None)))
    return allow, warnings


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
    rows = _limit_rows(inp, rules)
    accuracy: dict[str, Any] = next((lim.details for cid, lim, _ in rows if cid == "PZ"), {})
    warnings: list[PlanWarning] = []
    if inp.map_scale is not None and rules is not None:
        digital = replace(rules, height_formula=rules.digital_height_formula)
        overlap = overlap_warning(digital, inp.forward_overlap_pct)
        if overlap:
            warnings.append(overlap)
    if not rows:
        return (), None, None, None, accuracy, warnings + _airspace_warnings(inp)
    best = min(rows, key=lambda r: r[2])
    max_h, binding = best[2], best[0]
    limits = tuple(HeightLimit(
        id=cid, name=CONSTRAINTS[cid].name, limit_m=lim.limit_m,
        compares=CONSTRAINTS[cid].compares, max_height_m=h, binding=(cid == binding),
        margin_pct=(h / max_h - 1) * 100 if max_h > 0 else math.inf, reason=lim.reason,
        equation=lim.equation or CONSTRAINTS[cid].equation, max_flown_height_m=h * up,
        details=lim.details)
        for cid, lim, h in rows)
    allow, more = _ceiling_and_height_warnings(inp, rows, max_h, binding)
    return limits, max_h, binding, allow, accuracy, warnings + more + _airspace_warnings(inp)


def _flight_time_s(length_m: float, speed_ms: float) -> float | None:
    """Time on the strips [s]; None at ground speed 0, or where a subnormal speed makes it
    infinite (never ``inf`` in a result)."""
    if speed_ms <= 0:
        return None
    with np.errstate(over="ignore", divide="ignore"):
        t = float(FL.flight_time_s(length_m, speed_ms))
    return t if math.isfinite(t) else None


def _blur(inp: UavInputs, gsd_lo: float, h_lo: float, h_hi: float,
          warnings: list[PlanWarning]) -> tuple[float, float, float]:
    """Motion blur at the lowest height [px], the longest exposure and the highest speed
    that keep it under :data:`scanplan.core.flight.MAX_BLUR_PX`; appends the haze and blur
    warnings."""
    if inp.haze_contrast == M.DEFAULT_HAZE_CONTRAST and h_hi > M.DEFAULT_HAZE_MAX_HEIGHT_M:
        warnings.append(PlanWarning("haze_default_height", Message(
            "haze_default_height", c=inp.haze_contrast, valid=M.DEFAULT_HAZE_MAX_HEIGHT_M,
            height=h_hi, key="[uav.atmosphere] haze_contrast")))  # give the value
    blur = float(FL.motion_blur_px(inp.speed_ms, inp.exposure_s, gsd_lo))
    max_exp = float(FL.max_exposure_for_blur_s(max(inp.speed_ms, 1e-12), gsd_lo))
    max_speed = float(FL.max_speed_for_blur_ms(inp.exposure_s, gsd_lo))
    if blur > FL.MAX_BLUR_PX:
        warnings.append(PlanWarning("motion_blur", Message(
            "motion_blur", blur=shown_above(blur, FL.MAX_BLUR_PX), height=h_lo,
            limit=FL.MAX_BLUR_PX,
            denominator=math.ceil(1 / max_exp), speed=max_speed)))
    return blur, max_exp, max_speed



def _flight_geometry(inp: UavInputs, h_plan: float, h_lo: float, h_hi: float,
                     warnings: list[PlanWarning]) -> dict[str, Any]:
    """Footprints, base, line spacing, interval and overlaps flown; appends the trigger
    warning. Strips, photos, length, time and data volume over an area come from the
    flight layout (:mod:`scanplan.project.flightplan`, one model for a rectangle and a
    polygon)."""
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
    return fl


def _tilted_corner_gsd(inp: UavInputs, h_hi: float) -> float | None:
    """The worst corner GSD of a tilted frame at the highest height [m] (None untilted)."""
    if not (inp.roll_deg or inp.pitch_deg):
        return None
    rot = attitude_matrix(math.radians(inp.roll_deg), math.radians(inp.pitch_deg))
    tilt = _f(corner_gsd(h_hi, inp.focal_mm, inp.pixel_um, inp.sensor_width_mm,
                         inp.sensor_height_mm, rotation=rot).worst_m)
    if tilt is None or not tilt > 0:
        raise InputError("roll_deg" if abs(inp.roll_deg) >= abs(inp.pitch_deg)
                         else "pitch_deg", "at this roll and pitch a corner of the frame "
                         "looks at or above the horizon; give a smaller tilt")
    return tilt


def _recognition(inp: UavInputs, l_plan: float | None, l_hi: float | None,
                 l_corner_hi: float | None) -> tuple[Recognition, ...]:
    """Recognition probability of every norm object at the planned and highest heights."""
    def p_rec(obj: ObjectSpec, l_m: float | None) -> float | None:
        if l_m is None:
            return None
        return float(F.recognition_probability(obj.size_m, l_m, obj.shape_coefficient))

    return tuple(
        Recognition(o.name, o.size_m, o.shape, o.map_scale, p_rec(o, l_plan),
                    p_rec(o, l_hi), p_rec(o, l_corner_hi))
        for o in inp.objects)


_CURVES_KEPT = 8
_CURVES: Kept[tuple[Any, ...], tuple[dict[str, Any], dict[str, Any]]] = Kept(_CURVES_KEPT)
"""The curves for plots of the last plans, by their inputs, heights and the MTF components
registered (the page re-plans with the same camera chain on every edit)."""


def _curves(inp: UavInputs, h_plan: float, h_hi: float, max_flown: float | None
            ) -> tuple[dict[str, Any], dict[str, Any]]:
    """GSD and L against height, and the MTF at the planned height, for plots: as made by
    :func:`_made_curves`, kept for the same inputs and heights (each plan is given lists
    of its own)."""
    key = (inp, chain_key(inp)[1], float(h_plan), float(h_hi), max_flown)
    try:
        hash(key)
    except TypeError:  # inputs given as lists (the API's own types are hashable)
        return _made_curves(inp, h_plan, h_hi, max_flown)
    kept = _CURVES.made(key, lambda: _made_curves(inp, h_plan, h_hi, max_flown))
    return tuple({k: list(v) for k, v in d.items()} for d in kept)  # type: ignore[return-value]


def _made_curves(inp: UavInputs, h_plan: float, h_hi: float, max_flown: float | None
                 ) -> tuple[dict[str, Any], dict[str, Any]]:
    """GSD and L against height, and the MTF at the planned height, for plots (one
    vectorised call each)."""
    top = max(h_hi, max_flown or 0.0) * 1.3
    hs = np.linspace(top / 30.0, top, 30)
    curve = centre_resolution_m(inp, hs)
    gsd = FL.ground_sample_distance_m(inp.pixel_um, hs, inp.focal_mm)
    height_curve = {"height_m": hs.tolist(),
                    "gsd_m": np.asarray(gsd, dtype=float).ravel().tolist(),
                    "ground_resolution_m": [
                        None if not math.isfinite(v) else v
                        for v in np.asarray(curve).ravel().tolist()]}
    freq = np.linspace(0, float(M.nyquist_lpmm(inp.pixel_um)), 41)
    curves = M.contrast_curves(freq, *_chain(inp, h_plan))
    mtf_centre = {"freq_lpmm": freq.tolist(),
                  **{name: np.asarray(v).ravel().tolist() for name, v in curves.items()}}
    return height_curve, mtf_centre


def _resolvable_warning(inp: UavInputs, resolvable: bool) -> list[PlanWarning]:
    """``not_resolvable`` when the object's contrast stays below the threshold."""
    if resolvable:
        return []
    return [PlanWarning("not_resolvable", Message(
        "not_resolvable", contrast=float(M.object_contrast(inp.r_max, inp.r_min)),
        threshold=inp.threshold_k0))]


def _heights(inp: UavInputs, flown_band_m: tuple[float, float] | None
             ) -> tuple[float, float, float]:
    """The planned, lowest and highest flown heights above the ground [m]: the planned
    height ± its tolerances, or over relief the heights really flown."""
    if flown_band_m is not None:
        lo, hi = (float(x) for x in flown_band_m)
        return float(inp.height_m), lo, hi
    band = FL.height_band(inp.height_m, inp.height_tolerance_up_pct / 100.0,
                          inp.height_tolerance_down_pct / 100.0)
    return float(inp.height_m), float(band.min_m), float(band.max_m)


def plan_uav(inp: UavInputs, rules: ScanRules | None = None,
             flown_band_m: tuple[float, float] | None = None, *, curves: bool = True) -> UavPlan:
    """Plan a UAV flight: GSD, MTF ground resolution, blur, flight geometry, and — with a map
    scale — the maximum flight height under the norm set's constraints.

    Steps: the inputs checked; the height band and the MTF resolution at the planned and
    highest heights; blur; geometry; tilt; recognition; the limits as heights; the curves.

    Parameters
    ----------
    inp : UavInputs
        Camera, flight, scene and map.
    rules : ScanRules, optional
        Needed when ``inp.map_scale`` is given.
    flown_band_m : (float, float), optional
        Over relief, the lowest and highest heights above ground really flown [m], in
        place of H ± the tolerance (the limits do not change; ``over_relief``).
    curves : bool, optional
        False: no curves for plots (``height_curve``, ``mtf_centre``; :func:`with_curves`).

    Returns
    -------
    UavPlan

    Raises
    ------
    InputError
        Naming the field for out-of-range input.

    Examples
    --------
    >>> p = plan_uav(UavInputs(pixel_um=4.0, focal_mm=35, f_number=8, sensor_width_mm=24,
    ...     sensor_height_mm=16, height_m=100, speed_ms=10, exposure_s=1/1000,
    ...     ceiling_m=120))
    >>> round(p.gsd_m * 100, 2), p.binding, round(p.max_height_m)
    (1.14, 'HC', 120)
    """
    _check_inputs(inp)
    if rules is not None:
        check_probability(rules)
    h_plan, h_lo, h_hi = _heights(inp, flown_band_m)
    c = resolution_at(inp, [h_plan, h_hi], "centre")
    k = resolution_at(inp, [h_plan, h_hi], "corner")
    gsd = FL.ground_sample_distance_m(inp.pixel_um, np.array([h_plan, h_lo, h_hi]),
                                      inp.focal_mm)
    gsd_plan, gsd_lo, gsd_hi = (float(x) for x in gsd)
    resolvable = bool(c["resolvable"][0])
    warnings: list[PlanWarning] = []
    blur, max_exp, max_speed = _blur(inp, gsd_lo, h_lo, h_hi, warnings)
    fl = _flight_geometry(inp, h_plan, h_lo, h_hi, warnings)
    tilt = _tilted_corner_gsd(inp, h_hi)
    l_plan = _f(c["ground_resolution_m"][0])
    l_hi = _f(c["ground_resolution_m"][1])
    warnings += _resolvable_warning(inp, resolvable)
    recognition = _recognition(inp, l_plan, l_hi, _f(k["ground_resolution_m"][1]))
    limits, max_h, binding, allow, accuracy, lim_warnings = _height_limits(inp, rules)
    warnings.extend(lim_warnings)
    up = 1.0 + inp.height_tolerance_up_pct / 100.0
    max_flown = max_h * up if max_h is not None else None
    height_curve, mtf_centre = _curves(inp, h_plan, h_hi, max_flown) if curves else ({}, {})
    if flown_band_m is not None and accuracy and rules is not None:  # σ_Z as flown
        accuracy = _accuracy_at(inp, rules, accuracy, h_lo, h_hi)
    return UavPlan(
        inputs=inp, heights_m={"planned": h_plan, "min": h_lo, "max": h_hi},
        over_relief=flown_band_m is not None,
        gsd_m=gsd_plan, gsd_at_max_height_m=gsd_hi,
        nyquist_lpmm=float(M.nyquist_lpmm(inp.pixel_um)),
        resolving_power_lpmm=_f(c["r_lpmm"][0]),
        resolving_power_corner_lpmm=_f(k["r_lpmm"][0]),
        ground_resolution_m=l_plan, ground_resolution_corner_m=_f(k["ground_resolution_m"][0]),
        ground_resolution_at_max_height_m=l_hi,
        ground_resolution_to_gsd=_f(c["l_over_gsd"][0]),
        resolvable=resolvable,
        sensor_limited=bool(c["sensor_limited"][0]),
        motion_blur_px=blur, max_exposure_s=max_exp, max_speed_ms=max_speed,
        tilted_corner_gsd_m=tilt, flight=fl, height_curve=height_curve,
        recognition=recognition, limits=limits,
        max_height_m=max_h, binding=binding, warnings=tuple(warnings),
        max_flown_height_m=max_flown, ceiling_m=inp.ceiling_m,
        constraints_max_height_m=allow, height_accuracy=accuracy, mtf_centre=mtf_centre)



def with_curves(plan: UavPlan) -> UavPlan:
    """``plan`` with its curves for plots, when it was planned without them
    (``plan_uav(..., curves=False)``): the very curves :func:`plan_uav` gives, from the
    plan's inputs, planned and highest flown heights and highest flown height allowed.

    Parameters
    ----------
    plan : UavPlan

    Returns
    -------
    UavPlan
        ``plan`` itself when it has its curves.
    """
    if plan.height_curve and plan.mtf_centre:
        return plan
    height_curve, mtf_centre = _curves(plan.inputs, plan.heights_m["planned"],
                                       plan.heights_m["max"], plan.max_flown_height_m)
    return replace(plan, height_curve=height_curve, mtf_centre=mtf_centre)


def _accuracy_at(inp: UavInputs, rules: ScanRules, accuracy: dict[str, Any], h_lo: float,
                 h_hi: float) -> dict[str, Any]:
    """The height accuracy's σ_Z at the lowest and highest heights really flown over relief
    (the mission's trigger distance, fixed at the planned height: :func:`~scanplan.rules.
    constraints.sigma_z_m`) [m], with those heights."""
    from .constraints import sigma_z_m

    used = replace(rules, image_measurement_px=accuracy["image_measurement_px"],
                   multi_ray=accuracy["multi_ray"])
    lo, hi = (float(x) for x in sigma_z_m(inp, used, np.array([h_lo, h_hi])))
    return {**accuracy, "sigma_z_at_highest_flown_height_m": hi,
            "sigma_z_at_lowest_flown_height_m": lo, "highest_flown_height_m": h_hi,
            "lowest_flown_height_m": h_lo}


SWEEP_COLUMNS: dict[str, str] = {
    "gsd_cm": "GSD at the planned height [cm]",
    "gsd_at_max_height_cm": "GSD at the highest flown height [cm]",
    "resolution_cm": "MTF ground resolution L at the planned height [cm] (NaN: not resolved)",
    "resolution_at_max_height_cm": "L at the highest flown height [cm]",
    "motion_blur_px": "motion blur at the lowest flown height [px]",
    "footprint_across_m": "footprint of one photo across the strip [m]",
    "footprint_along_m": "footprint of one photo along the strip [m]",
    "base_m": "photo base (trigger distance) [m]",
    "line_spacing_m": "distance between strips [m]",
    "photo_interval_s": "time between photos at the ground speed [s] (inf at speed 0)",
}
"""The per-height figures of :func:`height_sweep`, with their units."""


def height_sweep(inp: UavInputs, heights_m: Any) -> dict[str, np.ndarray]:
    """The figures of :func:`plan_uav` that change with the planned height, for many heights
    in one vectorised pass (the MTF chain solved once over every height).

    Parameters
    ----------
    inp : UavInputs
        Camera, flight and target (``height_m`` is ignored; the inputs are checked as
        :func:`plan_uav` checks them).
    heights_m : array_like
        Planned heights above ground [m], each in the domain of ``height_m``.

    Returns
    -------
    dict of ndarray
        :data:`SWEEP_COLUMNS` → one value per height, equal to what :func:`plan_uav` gives
        at that height (the same formulas on arrays).
    """
    h = np.atleast_1d(np.asarray(heights_m, dtype=float))
    for value in h:
        check_domain("height_m", float(value))
    _check_inputs(replace(inp, height_m=float(h[0])))
    band = FL.height_band(h, inp.height_tolerance_up_pct / 100.0,
                          inp.height_tolerance_down_pct / 100.0)
    h_lo, h_hi = np.asarray(band.min_m, dtype=float), np.asarray(band.max_m, dtype=float)
    lr = np.asarray(centre_resolution_m(inp, np.concatenate([h, h_hi])), dtype=float).ravel()
    pitch = inp.pixel_um
    gsd_lo = FL.ground_sample_distance_m(pitch, h_lo, inp.focal_mm)
    fp_across = FL.footprint_m(inp.sensor_width_mm, h, inp.focal_mm)
    fp_along = FL.footprint_m(inp.sensor_height_mm, h, inp.focal_mm)
    base = FL.photo_base_m(fp_along, inp.forward_overlap_pct)
    with np.errstate(over="ignore"):
        interval = (FL.photo_interval_s(base, inp.speed_ms) if inp.speed_ms > 0
                    else np.full(h.shape, np.inf))
    return {
        "gsd_cm": FL.ground_sample_distance_m(pitch, h, inp.focal_mm) * 100.0,
        "gsd_at_max_height_cm": FL.ground_sample_distance_m(pitch, h_hi, inp.focal_mm) * 100,
        "resolution_cm": lr[:h.size] * 100.0,
        "resolution_at_max_height_cm": lr[h.size:] * 100.0,
        "motion_blur_px": np.asarray(FL.motion_blur_px(inp.speed_ms, inp.exposure_s, gsd_lo),
                                     dtype=float),
        "footprint_across_m": np.asarray(fp_across, dtype=float),
        "footprint_along_m": np.asarray(fp_along, dtype=float),
        "base_m": np.asarray(base, dtype=float),
        "line_spacing_m": np.asarray(FL.line_spacing_m(fp_across, inp.side_overlap_pct),
                                     dtype=float),
        "photo_interval_s": np.asarray(interval, dtype=float),
    }

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
  inverse answers (smallest photo scale, the largest Mc, for a scanner pixel, interpretation limit),
  scanner steps and data volume. Its result objects feed the terminal, ``--json`` and the
  reports alike.

The engine takes its normative numbers in a :class:`ScanRules` (built from a norm set by
:meth:`scanplan.norms.NormSet.rules`); it reads no files.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ..core import formulas as F
from ..core import photoscale as PS
from ..core.domains import check_domain, check_range
from ..errors import InputError
from ..i18n.messages import Message, Names
from .constraints import height_formula_name
from .registry import CONSTRAINTS, ConstraintInfo, FilmArgs, film_ids
from .results import (
    ConstraintResult,
    Evaluation,
    ObjectSpec,
    PixelReach,
    PlanWarning,
    ScanInputs,
    ScanPlan,
    ScanRules,
    ScanScenario,
)

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


# ---------------------------------------------------------------------------------------
# Vectorised core
# ---------------------------------------------------------------------------------------


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
    """Each enabled constraint's pixel [µm], vectorised (the registry's film records).

    The constraints are the norm set's enabled ids, then the registered film constraints
    that need no norm switch (:func:`scanplan.rules.registry.film_ids`).

    Examples
    --------
    >>> from scanplan.norms import load_norm_set
    >>> rules = load_norm_set().rules()
    >>> px = constraint_pixels_um(rules, map_scale=2000, photo_scale=8000,
    ...     relief_interval_m=0.5, focal_mm=152, frame_along_mm=230, forward_overlap_pct=60,
    ...     resolving_power_lpmm=40, object_size_m=0.2, shape_coefficient=0.97)
    >>> list(px), round(float(px["PS"]), 2)
    (['PS', 'PZ', 'PP', 'PR', 'PD'], 25.0)
    """
    args = FilmArgs(map_scale, photo_scale, relief_interval_m, focal_mm, frame_along_mm,
                    forward_overlap_pct, resolving_power_lpmm, object_size_m,
                    shape_coefficient, height_formula or rules.height_formula)
    return {cid: CONSTRAINTS[cid].film_pixel_um(rules, args)  # type: ignore[misc]
            for cid in film_ids(rules.constraints)}


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
    pixels = tuple(np.broadcast_to(np.asarray(v, dtype=np.float64), shape)
                   for v in values.values())
    idx, scan = _binding(pixels, shape)
    return Evaluation(ids=ids, pixels=pixels, binding_index=idx, scan_pixel_um=scan)


def _binding(pixels: tuple[NDArray[np.float64], ...], shape: tuple[int, ...]
             ) -> tuple[NDArray[np.intp], NDArray[np.float64]]:
    """The index of the smallest pixel and its value, per scenario: ``np.argmin`` over the
    constraints and the value there (the first of equal ones; the first NaN where there is
    one, whose value is NaN), taken one constraint after the other over contiguous arrays
    instead of across a stacked copy."""
    if not pixels:
        np.stack(pixels)  # ValueError: no constraint is enabled (as ever)
    idx = np.zeros(shape, dtype=np.intp)
    scan = np.array(pixels[0], dtype=np.float64)
    for i, v in enumerate(pixels[1:], start=1):
        with np.errstate(invalid="ignore"):
            better = (v < scan) | (np.isnan(v) & ~np.isnan(scan))
        idx[better] = i
        scan = np.minimum(scan, v)  # a NaN stays: nothing is less than it
    return idx, scan


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
    for cid, fixed in at_unit_scale.items():  # P_R: a pixel coarser supports no scale
        if CONSTRAINTS[cid].depends_on_photo_scale:
            continue
        too_coarse = pixel > fixed * (1.0 + 1e-12)
        mc, limiting, too_coarse = np.broadcast_arrays(mc, limiting, too_coarse)
        mc = np.where(too_coarse, 0.0, mc)
        limiting = np.where(too_coarse, cid, limiting)
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
        See :func:`scanplan.core.formulas.probability_root`.

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


def validate_inputs(inp: ScanInputs, rules: ScanRules) -> None:
    """Raise :class:`InputError` (field = the input's name) for any value outside its domain
    (:data:`scanplan.core.domains.DOMAINS`)."""
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
    check_probability(rules)
    check_domain("pr_coefficient", rules.pr_coefficient)


def check_probability(rules: Any) -> None:
    """P within its domain, and one the rounding can carry.

    The paper's rounding (seed 001, eqs. 9–10; :func:`scanplan.core.formulas.probability_root`)
    truncates −ln P to two decimals: for P above exp(−0.01) ≈ 0.99005 that is 0, and
    sqrt(−ln P) = 0 makes the object infinitely large to the model (P_D = 0 µm, a photo
    scale of 1:0, an infinite resolving power). No result follows from it, so such a P is
    refused with the paper's rounding; the exact root carries any P of the domain.

    Raises
    ------
    InputError
        ``probability``, naming the range and the remedy.
    """
    check_domain("probability", rules.probability)
    if getattr(rules, "recognition_rounding", "exact") == "paper" and float(
            F.probability_root(rules.probability, "paper")) <= 0.0:
        limit = math.floor(math.exp(-0.01) * 1e5) / 1e5
        raise InputError("probability", f"{rules.probability:g} cannot be used with the "
                         "paper's rounding (--rounding paper): it truncates −ln P to two "
                         f"decimals, which is 0 for P > {limit:g}, and the recognition model "
                         f"then has no answer; give P ≤ {limit:g}, or --rounding exact")


def _constraint_name(cid: str) -> dict[str, str]:
    info = CONSTRAINTS[cid]
    return Names(info.name, info.name_ru)


def _common_args(inp: ScanInputs) -> dict[str, Any]:
    """The engine's keyword arguments other than the photo scale."""
    obj = inp.object
    return dict(
        map_scale=inp.map_scale, relief_interval_m=inp.relief_interval_m,
        focal_mm=inp.focal_mm, frame_along_mm=inp.frame_along_mm,
        forward_overlap_pct=inp.forward_overlap_pct,
        resolving_power_lpmm=inp.resolving_power_lpmm,
        object_size_m=obj.size_m if obj else np.nan,
        shape_coefficient=obj.shape_coefficient if obj else np.nan)


def _per_scale_numbers(inp: ScanInputs, rules: ScanRules, mc: NDArray[np.float64],
                       ev: Evaluation) -> dict[str, Any]:
    """Everything the scenarios report besides the constraints, one array per quantity:
    the other height formula's P_Z, A, the R needed, the interpretation limit, the scanner
    step, the frame volume and the recognition probability after scanning."""
    obj = inp.object
    other_formula = "parallax" if rules.height_formula == "instruction" else "instruction"
    pz_other = F.height_pixel_um(
        inp.relief_interval_m, mc, inp.focal_mm,
        F.photo_base_mm(inp.frame_along_mm, inp.forward_overlap_pct),
        height_accuracy_fraction=rules.height_accuracy_fraction,
        processing_loss_k=rules.processing_loss_k, method=other_formula)  # type: ignore[arg-type]
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
    r_eff = PS.effective_resolving_power_lpmm(inp.resolving_power_lpmm, volume_px,
                                              rules.pr_coefficient)
    p_rec = (F.recognition_probability(obj.size_m * 1000.0,
                                       F.resolution_on_ground_mm(mc, r_eff),
                                       obj.shape_coefficient) if obj else None)
    return {"other_formula": other_formula, "pz_other": pz_other,
            "a_mm": F.resolution_on_ground_mm(mc, inp.resolving_power_lpmm),
            "r_needed": r_needed, "mc_interp": mc_interp, "scanner_px": scanner_px,
            "mbytes": mbytes, "p_rec": p_rec}


def _constraint_results(inp: ScanInputs, rules: ScanRules, ev: Evaluation,
                        ctx: dict[str, Any], j: int) -> list[ConstraintResult]:
    """Every evaluated constraint at scenario ``j``, from its registry record."""
    bind_i = int(ev.binding_index[j])
    scan = float(ev.scan_pixel_um[j])
    margins = ev.margin_pct
    results = []
    for i, cid in enumerate(ev.ids):
        info = CONSTRAINTS[cid]
        val = float(ev.pixel_um[i, j])
        details = info.film_details(inp, rules, ctx, j) if info.film_details else {}
        reason = info.film_reason(inp, rules) if info.film_reason else ""
        results.append(ConstraintResult(
            id=cid, name=info.name, pixel_um=val, margin_um=val - scan,
            margin_pct=float(margins[i, j]), binding=(i == bind_i),
            protects=info.protects, equation=info.equation, reason=reason,
            details=details))
    return results


def _scenario(inp: ScanInputs, rules: ScanRules, ev: Evaluation, ctx: dict[str, Any],
              j: int, scale: float) -> ScanScenario:
    """The engine's answer at photo scale ``scale`` (scenario ``j``)."""
    results = _constraint_results(inp, rules, ev, ctx, j)
    bind_i = int(ev.binding_index[j])
    scan = float(ev.scan_pixel_um[j])
    bind = ev.ids[bind_i]
    runner = sorted((r for r in results if not r.binding), key=lambda r: r.pixel_um)
    explanation = Message(
        "explanation", cid=bind, name=_constraint_name(bind), scale=scale,
        pixel=scan, reason=results[bind_i].reason,
        next=Message("explanation.next", cid=runner[0].id, pixel=runner[0].pixel_um,
                     margin=runner[0].margin_pct) if runner else None)
    scanner_px, p_rec, obj = ctx["scanner_px"], ctx["p_rec"], inp.object
    sp = float(scanner_px[j]) if scanner_px is not None else None
    return ScanScenario(
        photo_scale=scale, photo_to_map_ratio=float(scale / inp.map_scale),
        constraints=tuple(results), binding=bind, scan_pixel_um=scan,
        explanation=explanation,
        scanner_pixel_um=sp if sp is None or math.isfinite(sp) else None,
        frame_megabytes=float(ctx["mbytes"][j]),
        resolution_on_ground_mm=float(ctx["a_mm"][j]),
        required_resolving_power_lpmm=float(ctx["r_needed"][j]) if obj else None,
        recognition_probability=float(p_rec[j]) if p_rec is not None else None,
        height_pixel_other_um=float(ctx["pz_other"][j]))


def _pixel_reach(inp: ScanInputs, rules: ScanRules, common: dict[str, Any],
                 mc_interp: float | None) -> tuple[PixelReach, ...]:
    """The inverse answers: the smallest photo scale (largest Mc) each scanner step or
    candidate supports."""
    pixels = sorted(set(inp.scanner_steps_um) | set(inp.candidate_pixels_um))
    if not pixels:
        return ()
    m, lim = max_photo_scale(rules, np.asarray(pixels), **common)
    return tuple(PixelReach(float(p), float(mm), str(ll),
                            None if mc_interp is None else min(float(mm), mc_interp))
                 for p, mm, ll in zip(pixels, m, lim, strict=True))


def _sweep(rules: ScanRules, mc: NDArray[np.float64], common: dict[str, Any]
           ) -> dict[str, Any]:
    """A dense sweep of photo scales for plots and the Sweep sheet (one vectorised call)."""
    lo, hi = float(mc.min()) * 0.5, float(mc.max()) * 2.0
    grid = np.geomspace(lo, hi, 61)
    dense = evaluate(rules, photo_scale=grid, **common)
    sweep: dict[str, Any] = {"photo_scale": grid.tolist()}
    for i, cid in enumerate(dense.ids):
        sweep[cid] = dense.pixel_um[i].tolist()
    sweep["scan_pixel_um"] = dense.scan_pixel_um.tolist()
    sweep["binding"] = dense.binding.tolist()
    return sweep


def plan_scan(inp: ScanInputs, rules: ScanRules) -> ScanPlan:
    """Evaluate a film scan plan at each photo scale, with explanations and warnings.

    Steps: validate; evaluate the registry's constraints at every photo scale; the other
    numbers per scale; one scenario per scale; warnings; inverse answers; the sweep.

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

    Examples
    --------
    >>> from scanplan.norms import load_norm_set
    >>> ns = load_norm_set()
    >>> inp = ScanInputs(map_scale=2000, relief_interval_m=0.5, photo_scales=(8000.0,),
    ...     focal_mm=152, frame_width_mm=230, frame_along_mm=230, resolving_power_lpmm=40,
    ...     forward_overlap_pct=60, object=ObjectSpec("pole", 0.2, "circle", 0.97, "user"))
    >>> s = plan_scan(inp, ns.rules()).scenarios[0]
    >>> s.binding, round(s.scan_pixel_um, 1)
    ('PZ', 10.3)
    """
    validate_inputs(inp, rules)
    mc = np.asarray(inp.photo_scales, dtype=np.float64)
    common = _common_args(inp)
    ev = evaluate(rules, photo_scale=mc, **common)
    ctx = _per_scale_numbers(inp, rules, mc, ev)
    scenarios = [_scenario(inp, rules, ev, ctx, j, float(scale)) for j, scale in enumerate(mc)]
    mc_interp = ctx["mc_interp"]
    warnings = _scenario_warnings(inp, rules, scenarios, mc_interp)
    overlap = overlap_warning(
        rules, inp.forward_overlap_pct,
        Message("overlap_not_standard.detail", pairs=[
            Message("overlap_not_standard.pair", pixel=s.height_pixel_other_um or 0,
                    scale=s.photo_scale) for s in scenarios]))
    if overlap:
        warnings.append(overlap)
    return ScanPlan(inputs=inp, rules=rules, scenarios=tuple(scenarios),
                    sweep=_sweep(rules, mc, common), warnings=tuple(warnings),
                    interpretation_limit_photo_scale=mc_interp,
                    max_photo_scales=_pixel_reach(inp, rules, common, mc_interp))


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

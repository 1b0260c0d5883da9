"""Archive photos: film photos that already exist at a given scale, to be scanned.

The commonest scan job: the photo scale is given (``[film] photo_scale``), not chosen. The
specification then answers the scan pixel for *those* photos and says which of the map's
objects cannot be interpreted on them and what follows (field interpretation, other
sources) — never "fly a larger scale", the photos exist.

When the map's object cannot be interpreted (the photo scale is above the interpretation
limit, i.e. P_D < P_R), the interpretation pixel P_D is not used for the scan pixel:
scanning finer than P_R adds no detail the photos do not carry (seed 001 conclusion 2), so
the scan pixel is the smallest of the other constraints. Nothing here recomputes a
formula; it re-reads the engine's answer at the one photo scale.
"""

from __future__ import annotations

import dataclasses
import math
from typing import Any

import numpy as np

from ..core import formulas as F
from ..i18n.messages import Message, Names
from ..rules.film import CONSTRAINTS, PlanWarning, ScanPlan, ScanScenario, round_to_scanner
from .jobs import ScanJob

__all__ = ["ARCHIVE_REPLACED_CODES", "archive_film"]

ARCHIVE_REPLACED_CODES = ("not_interpretable", "above_interpretation_limit",
                          "scanner_too_coarse")
"""Film warnings whose remedy is a different photo scale: for archive photos they are
replaced by ``archive_not_interpretable`` / ``archive_scanner_too_coarse``."""


def _name(cid: str) -> dict[str, str]:
    info = CONSTRAINTS[cid]
    return Names(info.name, info.name_ru)


def _without_pd(plan: ScanPlan, s: ScanScenario) -> ScanScenario:
    """The scenario with P_D set aside: the smallest other constraint binds."""
    others = [c for c in s.constraints if c.id != "PD"]
    bind = min(others, key=lambda c: c.pixel_um)
    pixel = bind.pixel_um
    constraints = tuple(dataclasses.replace(
        c, binding=(c.id == bind.id), margin_um=c.pixel_um - pixel,
        margin_pct=(c.pixel_um / pixel - 1.0) * 100.0) for c in s.constraints)
    inp = plan.inputs
    scanner_px = None
    if inp.scanner_steps_um:
        x = float(round_to_scanner(pixel, inp.scanner_steps_um))
        scanner_px = x if math.isfinite(x) else None
    delivered = scanner_px or pixel
    mbytes = float(F.scanned_frame_bytes(inp.frame_width_mm, inp.frame_along_mm, delivered,
                                         bands=inp.bands,
                                         bits_per_band=inp.bits_per_band)) / 1e6
    runner = sorted((c for c in constraints if not c.binding and c.id != "PD"),
                    key=lambda c: c.pixel_um)
    explanation = Message(
        "explanation", cid=bind.id, name=_name(bind.id), scale=s.photo_scale, pixel=pixel,
        reason=bind.reason,
        next=Message("explanation.next", cid=runner[0].id, pixel=runner[0].pixel_um,
                     margin=runner[0].margin_pct) if runner else None)
    return dataclasses.replace(s, constraints=constraints, binding=bind.id,
                               scan_pixel_um=pixel, scanner_pixel_um=scanner_px,
                               frame_megabytes=mbytes, explanation=explanation)


def _sweep_without_pd(plan: ScanPlan, limit: float) -> dict[str, Any]:
    """The dense sweep restated as :func:`_without_pd` restates the scenario: at photo
    scales smaller than the interpretation limit ``limit`` P_D is set aside, so the scan
    pixel curve passes through the archive photos' scan pixel (the plot and the Sweep sheet
    drew the minimum with P_D, below the pixel the specification gives)."""
    sweep = dict(plan.sweep)
    ids = [c for c in plan.constraint_ids if c in sweep and c != "PD"]
    if not ids or "scan_pixel_um" not in sweep:
        return sweep
    pixel, binding = list(sweep["scan_pixel_um"]), list(sweep.get("binding", []))
    for i, mc in enumerate(sweep["photo_scale"]):
        if mc > limit * (1 + 1e-12):
            cid = min(ids, key=lambda c: sweep[c][i])
            pixel[i] = sweep[cid][i]
            if i < len(binding):
                binding[i] = cid
    sweep["scan_pixel_um"] = pixel
    if binding:
        sweep["binding"] = binding
    return sweep


def archive_film(job: ScanJob) -> tuple[ScanJob, ScanScenario, Message]:
    """The specification for existing photos at one given scale.

    Parameters
    ----------
    job : ScanJob
        The engine's plan at exactly one photo scale (the archive photos').

    Returns
    -------
    job : ScanJob
        The same job, its scenario and warnings restated for archive photos (P_D set
        aside when the object cannot be interpreted; remedies that change the photo scale
        replaced by field interpretation and other sources).
    scenario : ScanScenario
        The recommendation: the scan pixel for these photos (never None).
    reason : Message
        ``spec.film_archive`` or ``spec.film_archive_uninterpretable``.
    """
    plan = job.plan
    (s,) = plan.scenarios
    inp, rules = plan.inputs, plan.rules
    obj = inp.object
    limit = plan.interpretation_limit_photo_scale
    readable = obj is None or limit is None or s.photo_scale <= limit * (1 + 1e-12)
    warnings = [w for w in plan.warnings if w.code not in ARCHIVE_REPLACED_CODES]
    new: list[PlanWarning] = []
    if readable:
        rec = s
        reason = Message("spec.film_archive", scale=s.photo_scale, pixel=s.scan_pixel_um,
                         explanation=s.explanation)
    else:
        assert obj is not None and limit is not None
        rec = _without_pd(plan, s) if "PD" in rules.constraints else s
        need = F.required_resolving_power_lpmm(
            obj.size_m * 1000.0, np.asarray(s.photo_scale), obj.shape_coefficient,
            rules.probability, rounding=rules.recognition_rounding)  # type: ignore[arg-type]
        msg = Message("archive_not_interpretable", obj.names(), scale=s.photo_scale,
                      limit=math.floor(limit), ratio=limit / inp.map_scale,
                      need=float(need), r=inp.resolving_power_lpmm)
        new.append(PlanWarning(msg.code, msg, photo_scales=(s.photo_scale,)))
        pd = s.constraint("PD").pixel_um if "PD" in rules.constraints else float("nan")
        reason = Message("spec.film_archive_uninterpretable", scale=s.photo_scale,
                         pixel=rec.scan_pixel_um, cid=rec.binding, name=_name(rec.binding),
                         pd=pd, objects=obj.names()["object"])
    if inp.scanner_steps_um and rec.scanner_pixel_um is None:
        msg = Message("archive_scanner_too_coarse", scale=s.photo_scale,
                      pixel=rec.scan_pixel_um, scanner=inp.scanner,
                      step=min(inp.scanner_steps_um))
        new.append(PlanWarning(msg.code, msg, photo_scales=(s.photo_scale,)))
    sweep = (_sweep_without_pd(plan, limit) if rec is not s and limit is not None
             else plan.sweep)
    plan = dataclasses.replace(plan, scenarios=(rec,), warnings=tuple(new + warnings),
                               sweep=sweep)
    return ScanJob(plan, job.norm_set), rec, reason

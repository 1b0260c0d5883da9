"""It must hold at the worst photo: the constraints evaluated at every photo's own height.

Over relief every photo has its own height above the ground and so its own photo scale
(:mod:`scanplan.core.photoscale`). The ground and the geometry — the DEM, the altitudes of
the altitude mode, the lowest and highest ground under every footprint and stretch of path,
the overlaps — come from :mod:`scanplan.geo.terrain`; this module is where the constraint
records of :mod:`scanplan.rules.registry` meet them, for both carriers:

- UAV: the plan's limits (one :class:`~scanplan.rules.results.HeightLimit` per enabled
  record, by its ``compares``: the GSD and the MTF ground resolution L hold over a
  footprint's lowest ground, the altitude ceiling over the path's lowest) give every photo
  the ground it is checked at (:func:`checked_ground_m`); its figures at its own height
  (:func:`photo_figures`) and what fails (:func:`resolution_warnings`,
  :func:`overlap_warnings`), and the height accuracy at the photo highest above its
  ground (:func:`height_accuracy_warnings`).
- Film: the engine (:func:`scanplan.rules.film.evaluate`, every enabled record) at the
  frame with the largest local Mc and at the planned Mc (:func:`film_at_worst_frame`),
  with the parallax form's local base (:func:`local_forward_overlap_pct`); every frame's
  recognition probability at its local scale (:func:`frame_recognition_p`).

Nothing here reads a file or a layout: arrays in, arrays and warnings out.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass, replace
from typing import Any, Protocol

import numpy as np
from numpy.typing import NDArray

from ..core import formulas as F
from ..core.flight import actual_overlap_pct
from ..core.photoscale import effective_resolving_power_lpmm, ground_pixel_m
from ..i18n.messages import MAX_LISTED, Message, PlanWarning, listing
from .constraints import sigma_z_m
from .film import evaluate
from .results import ScanInputs, ScanRules, UavInputs, UavPlan
from .uav import ground_resolution_m

__all__ = ["WorstFrame", "checked_ground_m", "film_at_worst_frame", "film_scale_warning",
           "frame_recognition_p", "height_accuracy_warnings",
           "local_forward_overlap_pct", "overlap_warnings", "photo_figures",
           "resolution_warnings"]

_REMEDIES = {"constant": "terrain_remedy.constant", "strip": "terrain_remedy.strip",
             "follow": "terrain_remedy.follow"}


class _Strip(Protocol):
    """A strip's worst photo (:class:`scanplan.geo.terrain.StripTerrain`)."""

    number: int
    agl_max_m: float
    excess_m: float
    worst_photo: int


class _Pairs(Protocol):
    """Pairs of neighbouring photos, by index in strip order
    (:class:`scanplan.geo.terrain_overlaps.Pairs`)."""

    a: NDArray[np.int64]
    b: NDArray[np.int64]


# --- UAV: every photo at its own height above ground ---------------------------------------

def photo_figures(inp: UavInputs, agl_m: NDArray[np.float64]) -> dict[str, NDArray[np.float64]]:
    """GSD, MTF ground resolution L and recognition probability of every photo at its AGL.

    Parameters
    ----------
    inp : UavInputs
        The camera, the flight and the map's object (``height_m`` is not used).
    agl_m : ndarray
        Every photo's height above its ground [m].

    Returns
    -------
    dict
        ``gsd_cm`` (GSD = p·H/f, :func:`scanplan.core.photoscale.ground_pixel_m`) [cm],
        ``resolution_cm`` (L = H/(2·R·f), :func:`scanplan.rules.uav.ground_resolution_m`)
        [cm], ``recognition_p`` (P = exp(−(B·L/L_obj)²), formulas.md §2; NaN without an
        object) [-].
    """
    n = agl_m.size
    gsd = ground_pixel_m(inp.pixel_um, agl_m, inp.focal_mm)
    lr = ground_resolution_m(inp, np.maximum(agl_m, 1e-3)) if n else np.zeros(0)
    obj = inp.map_object
    with np.errstate(all="ignore"):
        p_rec = (F.recognition_probability(obj.size_m, lr, obj.shape_coefficient)
                 if obj is not None else np.full(n, np.nan))
    return {"gsd_cm": gsd * 100.0, "resolution_cm": lr * 100.0,
            "recognition_p": np.asarray(p_rec, dtype=float)}


def checked_ground_m(plan: UavPlan, footprint_low_m: NDArray[np.float64],
                     path_low_m: NDArray[np.float64]) -> NDArray[np.float64]:
    """The ground each photo is checked at against the plan's maximum height L [m].

    The limits on GSD and L (records that compare ``"GSD"`` or ``"L"``) hold over the
    footprint's lowest ground g_f, the altitude ceiling (``"H"``) over the path's lowest
    g_p: photo i meets them all iff A − g_f ≤ L_r and A − g_p ≤ L_c, i.e.
    A ≤ min(g_f + L_r, g_p + L_c) = g_eff + L with L = min(L_r, L_c). So
    g_eff = min(g_f + L_r, g_p + L_c) − L stands for both in the closed-form checks.

    Parameters
    ----------
    plan : UavPlan
        The flat-ground plan: ``limits`` (one per enabled constraint record, with its
        ``compares`` and ``max_height_m``) and ``max_height_m`` L [m].
    footprint_low_m, path_low_m : ndarray
        Every photo's lowest ground under its footprint and under its stretch of path [m].

    Returns
    -------
    ndarray
        g_eff [m]: ``footprint_low_m`` itself without a ceiling among the limits.
    """
    limits = getattr(plan, "limits", ()) or ()
    ceiling = [lim.max_height_m for lim in limits if lim.compares == "H"]
    rest = [lim.max_height_m for lim in limits if lim.compares != "H"]
    if not ceiling or plan.max_height_m is None:
        return footprint_low_m
    l_c = min(ceiling)
    l_r = min(rest) if rest else math.inf
    big = min(l_c, l_r)
    return np.minimum(footprint_low_m + (l_r - big), path_low_m + (l_c - big))


def resolution_warnings(strips: Sequence[_Strip], plan: UavPlan, mode: str, height_m: float,
                        max_height_m: float | None, up: float) -> list[PlanWarning]:
    """The ``terrain_resolution`` warning: the strips whose worst photo is higher above its
    ground than the plan's maximum height, the worst of them named, and the remedy of the
    altitude mode.

    Parameters
    ----------
    strips : sequence of StripTerrain
        Every strip's worst photo, its AGL and excess over the limit [m].
    plan : UavPlan
        The flat-ground plan (``max_height_m`` [m], ``binding``).
    mode : str
        The altitude mode (``constant``, ``strip``, ``follow``): which remedy.
    height_m : float
        The planned height above the reference ground [m].
    max_height_m : float or None
        The largest planned height the worst photo allows [m].
    up : float
        The height tolerance upwards (a fraction).

    Returns
    -------
    list of PlanWarning
        Empty when every strip holds.
    """
    if plan.max_height_m is None or not strips:
        return []
    failing = [s for s in strips if s.excess_m > 1e-6]
    if not failing:
        return []
    worst = max(failing, key=lambda s: s.excess_m)
    nums = np.array([s.number for s in failing], dtype=np.int64)
    by = ", ".join(f"{s.number}: {s.excess_m:.0f}" for s in failing[:MAX_LISTED])
    return [PlanWarning("terrain_resolution", Message(
        "terrain_resolution", height=height_m, photo=worst.worst_photo, strip=worst.number,
        agl=worst.agl_max_m, flown=worst.agl_max_m * (1 + up), limit=plan.max_height_m,
        cid=plan.binding, excess=worst.excess_m, count=len(failing), strips=listing(nums),
        by=by + (" …" if len(failing) > MAX_LISTED else ""),
        remedy=Message(_REMEDIES[mode], max=max_height_m if max_height_m is not None else 0.0,
                       height=height_m)))]


def overlap_warnings(inp: UavInputs, fw: _Pairs, fw_pct: NDArray[np.float64], sd: _Pairs,
                     sd_pct: NDArray[np.float64], photo: NDArray[Any]) -> list[PlanWarning]:
    """``terrain_forward_overlap``/``terrain_side_overlap``: the pairs short of the planned
    overlap, the worst pair named.

    Parameters
    ----------
    inp : UavInputs
        The planned forward and side overlaps [%].
    fw, sd : Pairs
        Forward and side pairs of photos (indices in strip order).
    fw_pct, sd_pct : ndarray
        The overlap of each pair [%].
    photo : ndarray
        The running numbers of the photos in strip order.

    Returns
    -------
    list of PlanWarning
        One per kind of overlap that falls short (by more than 0.05 %).
    """
    out = []
    for kind, pairs, pct, planned in (("forward", fw, fw_pct, inp.forward_overlap_pct),
                                      ("side", sd, sd_pct, inp.side_overlap_pct)):
        if pct.size == 0:
            continue
        short = pct < planned - 0.05
        if not short.any():
            continue
        i = int(np.argmin(pct))
        photos = np.unique(np.concatenate([photo[pairs.a[short]],
                                           photo[pairs.b[short]]])).astype(np.int64)
        floor = 50.0 if kind == "forward" else 0.0
        out.append(PlanWarning(f"terrain_{kind}_overlap", Message(
            f"terrain_{kind}_overlap", value=float(pct[i]), planned=planned,
            a=int(photo[pairs.a[i]]), b=int(photo[pairs.b[i]]),
            count=int(photos.size), photos=listing(photos),
            floor=Message(f"terrain_overlap_floor.{kind}") if pct[i] <= floor else None),
            severity="warning"))
    return out


def height_accuracy_warnings(inp: UavInputs, rules: ScanRules, accuracy: dict[str, Any],
                             agl_m: Any) -> tuple[PlanWarning, ...]:
    """``terrain_height_accuracy``: σ_Z of the stereo normal case at the photo highest above
    its ground, at its highest flown height, with the mission's trigger distance (fixed in
    metres at the planned height), when it exceeds V_z.

    Parameters
    ----------
    inp : UavInputs
        The camera and flight (``height_m`` the planned height) [m].
    rules : ScanRules
        The norm set's rules.
    accuracy : dict
        The flat plan's ``height_accuracy`` details (``image_measurement_px``,
        ``multi_ray``, ``height_accuracy_m`` = V_z [m]).
    agl_m : array_like
        Every photo's height above its ground [m] (NaN where unknown).

    Returns
    -------
    tuple of PlanWarning
        Empty when σ_Z ≤ V_z or no photo has a height above ground.
    """
    agl = np.asarray(agl_m, dtype=float)
    agl = agl[np.isfinite(agl)]
    if not agl.size:
        return ()
    rules = replace(rules, image_measurement_px=accuracy["image_measurement_px"],
                    multi_ray=accuracy["multi_ray"])
    flown = float(agl.max()) * (1.0 + inp.height_tolerance_up_pct / 100.0)
    sz = float(sigma_z_m(inp, rules, flown))
    if sz <= accuracy["height_accuracy_m"] * (1 + 1e-9):
        return ()
    return (PlanWarning("terrain_height_accuracy", Message(
        "terrain_height_accuracy", sz=sz, vz=accuracy["height_accuracy_m"], agl=flown,
        planned=inp.height_m, overlap=inp.forward_overlap_pct)),)


# --- film: every frame at its own photo scale ----------------------------------------------

def local_forward_overlap_pct(rules: ScanRules, forward_overlap_pct: float,
                              photo_scale: float, local_scale: float) -> float:
    """The forward overlap the height constraint sees at a frame of local scale Mc_l [%].

    The exposures are spaced for the planned Mc, so the base on the ground is fixed,
    B = b·Mc, and the image base of a frame at Mc_l is b_l = b·Mc/Mc_l — the overlap
    1 − (1 − p)·Mc/Mc_l (:func:`scanplan.core.flight.actual_overlap_pct` with heights ∝ Mc).
    The parallax form P_Z = V_z·b/(k·Mc·f) takes that local base. The Instruction's form
    P_Z = V_z·f/(k·Mc·b) keeps the planned base, as it is checked as printed: with the
    local one its value would not depend on the local scale at all (Mc_l·b_l = Mc·b).

    Parameters
    ----------
    rules : ScanRules
        ``height_formula`` picks the form.
    forward_overlap_pct : float
        Planned forward overlap p [%].
    photo_scale, local_scale : float
        Planned and local photo scale denominators Mc, Mc_l.

    Returns
    -------
    float
        The overlap for the height constraint at that frame [%].

    Examples
    --------
    >>> from scanplan.norms import load_norm_set
    >>> from dataclasses import replace
    >>> r = replace(load_norm_set().rules(), height_formula="parallax")
    >>> round(local_forward_overlap_pct(r, 60.0, 10000.0, 12000.0), 3)
    66.667
    """
    if rules.height_formula != "parallax":
        return float(forward_overlap_pct)
    return float(actual_overlap_pct(forward_overlap_pct, photo_scale, local_scale))


@dataclass(frozen=True)
class WorstFrame:
    """The film engine at the planned photo scale (flat ground) and at the frame with the
    largest local Mc: the scan pixel [µm] and the binding constraint of each."""

    scan_pixel_um: float
    binding: str
    scan_pixel_planned_um: float
    binding_planned: str


def film_at_worst_frame(rules: ScanRules, *, photo_scale: float, worst_scale: float,
                        map_scale: float, relief_interval_m: float, focal_mm: float,
                        frame_along_mm: float, forward_overlap_pct: float,
                        resolving_power_lpmm: float, object_size_m: float = math.nan,
                        shape_coefficient: float = math.nan) -> WorstFrame:
    """The engine (:func:`scanplan.rules.film.evaluate`, every enabled constraint record)
    at the planned Mc and at the worst frame's ``worst_scale``, the latter with the
    parallax form's local base (:func:`local_forward_overlap_pct`).

    Parameters
    ----------
    rules : ScanRules
        The norm set's rules (enabled constraints, height formula).
    photo_scale, worst_scale : float
        The planned Mc and the largest local Mc of the block.
    map_scale, relief_interval_m, focal_mm, frame_along_mm : float
        Mk; h_c [m]; f [mm]; l_y [mm] (as :func:`scanplan.rules.film.evaluate`).
    forward_overlap_pct, resolving_power_lpmm, object_size_m, shape_coefficient : float
        p [%]; R [lp/mm]; the object's size L [m] and shape coefficient B (NaN: none).

    Returns
    -------
    WorstFrame
        Scan pixel [µm] and binding constraint at each of the two scales.
    """
    overlap = np.array([forward_overlap_pct, local_forward_overlap_pct(
        rules, forward_overlap_pct, photo_scale, worst_scale)])
    ev = evaluate(rules, map_scale=map_scale, photo_scale=np.array([photo_scale, worst_scale]),
                  relief_interval_m=relief_interval_m, focal_mm=focal_mm,
                  frame_along_mm=frame_along_mm, forward_overlap_pct=overlap,
                  resolving_power_lpmm=resolving_power_lpmm, object_size_m=object_size_m,
                  shape_coefficient=shape_coefficient)
    pix = np.asarray(ev.scan_pixel_um, dtype=float)
    binds = np.asarray(ev.binding)
    return WorstFrame(float(pix[1]), str(binds[1]), float(pix[0]), str(binds[0]))


def film_scale_warning(scan_pixel_um: float, planned_pixel_um: float, binding: str,
                       mc_min: float, mc_max: float, where: Message) -> PlanWarning | None:
    """``terrain_film_scale`` (a note): the relief spreads the local photo scale from
    1:``mc_min`` to 1:``mc_max`` and the frame ``where`` needs a finer scan pixel than flat
    ground.

    Parameters
    ----------
    scan_pixel_um, planned_pixel_um : float
        The scan pixel at the worst frame and on flat ground [µm].
    binding : str
        The constraint binding at the worst frame.
    mc_min, mc_max : float
        The block's largest and smallest local photo scale (denominators).
    where : Message
        Which frame (or the lowest ground of a range).

    Returns
    -------
    PlanWarning or None
        None when the worst frame needs no finer pixel.
    """
    if not scan_pixel_um < planned_pixel_um * (1 - 1e-9):
        return None
    return PlanWarning("terrain_film_scale", Message(
        "terrain_film_scale", lo=float(round(mc_min)), hi=float(round(mc_max)), where=where,
        pixel=scan_pixel_um, planned=planned_pixel_um, cid=binding), severity="info")


def frame_recognition_p(inp: ScanInputs, rules: ScanRules, mc: Any,
                        pixel_um: float) -> NDArray[np.float64]:
    """Recognition probability of the map's object on every frame at its local scale.

    P = exp(−(B·a/L)²) with a = Mc/(2·R_eff) the photo's resolution on the ground and
    R_eff = min(R, k_R/pixel) what the scan keeps (formulas.md §1–2, the engine's own
    computation in :func:`scanplan.rules.film.plan_scan`).

    Parameters
    ----------
    inp : ScanInputs
        The map's object (size [m], shape coefficient) and the photo's R [lp/mm].
    rules : ScanRules
        ``pr_coefficient`` k_R.
    mc : array_like
        Every frame's local photo scale denominator.
    pixel_um : float
        The scan pixel specified [µm].

    Returns
    -------
    ndarray
        P per frame [-]; NaN without an object.
    """
    obj = inp.object
    mc = np.asarray(mc, dtype=float)
    if obj is None:
        return np.full(mc.size, np.nan)
    r_eff = effective_resolving_power_lpmm(inp.resolving_power_lpmm, pixel_um,
                                           rules.pr_coefficient)
    return np.asarray(F.recognition_probability(
        obj.size_m * 1000.0, F.resolution_on_ground_mm(mc, r_eff), obj.shape_coefficient),
        dtype=float)

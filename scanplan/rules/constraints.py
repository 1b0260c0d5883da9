"""The built-in constraints: seed 001's P_S, P_Z, P_P, P_R, P_D and the UAV-only limits.

Each constraint is one :class:`~scanplan.rules.record.Constraint` record plus the small
functions it names: the film pixel (seed 001, eqs. 1–6), the reason with the contract's
numbers, and the digital ground limit (the same limit on the ground, Mc = 1, compared with
the GSD or the MTF ground resolution L; docs/uav-models.md §9–10). The texts are keys of
the message catalogue (:mod:`scanplan.i18n.messages`).

>>> from scanplan.rules.registry import CONSTRAINTS
>>> [c.id for c in CONSTRAINTS.values() if "film" in c.workflows][:5]
['PS', 'PZ', 'PP', 'PR', 'PD']
>>> CONSTRAINTS["PD"].compares, CONSTRAINTS["HC"].compares
('L', 'H')
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import NDArray

from ..core import flight as FL
from ..core import formulas as F
from ..core import photoscale as PS
from ..core import stereo as S
from ..i18n.messages import Message
from .record import Constraint, DigitalLimit, FilmArgs

if TYPE_CHECKING:
    from .results import ScanInputs, ScanRules, UavInputs

__all__ = ["BUILTIN", "height_accuracy", "height_formula_name", "sigma_z_m", "stereo_geometry"]


def height_formula_name(formula: str) -> Message | str:
    """The height formula's name as a message parameter (``instruction``/``parallax``).

    >>> str(height_formula_name("no-such-form"))
    'no-such-form'
    """
    try:
        return Message(f"height_formula.{formula}")
    except KeyError:
        return formula


def _at_unit_scale_m(pixel_um: Any) -> float:
    """A pixel limit evaluated at Mc = 1, i.e. the limit on the ground [µm → m]."""
    return float(pixel_um) / 1e6


# --- P_S: planimetric accuracy (seed 001, eq. 1) ------------------------------------------

def _ps_pixel(rules: ScanRules, a: FilmArgs) -> NDArray[np.float64]:
    return F.planimetric_pixel_um(a.map_scale, a.photo_scale,
                                  planimetric_accuracy_mm=rules.planimetric_accuracy_mm,
                                  processing_loss_k=rules.processing_loss_k)


def _ps_reason(inp: ScanInputs, rules: ScanRules) -> Message:
    ground = rules.planimetric_accuracy_mm * inp.map_scale / 1000.0
    return Message("reason.PS", vs=rules.planimetric_accuracy_mm, map=inp.map_scale,
                   ground=ground, k=rules.processing_loss_k)


def _ps_ground(inp: UavInputs, rules: ScanRules | None) -> DigitalLimit:
    assert rules is not None and inp.map_scale is not None
    k, mk = rules.processing_loss_k, inp.map_scale
    g = _at_unit_scale_m(F.planimetric_pixel_um(
        mk, 1.0, planimetric_accuracy_mm=rules.planimetric_accuracy_mm, processing_loss_k=k))
    return DigitalLimit(g, Message("limit.PS", vs=rules.planimetric_accuracy_mm, map=mk, k=k),
                        {})


# --- P_Z: height accuracy (seed 001, eq. 2; digital: the stereo normal case) ---------------

def _pz_pixel(rules: ScanRules, a: FilmArgs) -> NDArray[np.float64]:
    return F.height_pixel_um(
        a.relief_interval_m, a.photo_scale, a.focal_mm,
        F.photo_base_mm(a.frame_along_mm, a.forward_overlap_pct),
        height_accuracy_fraction=rules.height_accuracy_fraction,
        processing_loss_k=rules.processing_loss_k,
        method=a.height_formula)  # type: ignore[arg-type]


def _pz_reason(inp: ScanInputs, rules: ScanRules) -> Message:
    vz = rules.height_accuracy_fraction * inp.relief_interval_m
    return Message("reason.PZ", fraction=rules.height_accuracy_fraction, vz=vz,
                   hc=inp.relief_interval_m, k=rules.processing_loss_k,
                   formula=height_formula_name(rules.height_formula))


def _pz_details(inp: ScanInputs, rules: ScanRules, ctx: dict[str, Any], j: int
                ) -> dict[str, Any]:
    return {"formula": rules.height_formula,
            f"{ctx['other_formula']}_pixel_um": float(ctx["pz_other"][j]),
            "base_mm": float(F.photo_base_mm(inp.frame_along_mm, inp.forward_overlap_pct))}


def _pz_ground(inp: UavInputs, rules: ScanRules | None) -> DigitalLimit:
    assert rules is not None
    g, reason, details = height_accuracy(inp, rules)
    return DigitalLimit(g, reason, details,
                        equation=Message("equation.PZ.normal_case")
                        if details.get("formula") == "normal_case" else None)


def stereo_geometry(inp: UavInputs, rules: ScanRules, height_ratio: Any
                    ) -> dict[str, NDArray[np.float64]]:
    """The stereo geometry of a digital block at heights ``height_ratio`` × planned.

    The trigger distance is fixed in metres at the planned height, s = (1 − p)·footprint(H);
    at a height h = ratio·H the overlap flown is 1 − (1 − p)/ratio
    (:func:`scanplan.core.flight.actual_overlap_pct`), and the base of the standard pair
    and the multi-ray factor follow from that overlap (docs/uav-models.md §9).

    Parameters
    ----------
    inp : UavInputs
        Camera and overlap.
    rules : ScanRules
        Standard stereo overlap, multi-ray switch.
    height_ratio : array_like
        Height checked over the planned height [-] (1 + tolerance at the highest flown
        height; (H + relief)/H over the lowest ground).

    Returns
    -------
    dict
        ``overlap_pct`` flown [%], ``base_to_height`` B/h [-], ``base_in_steps`` B/s [-],
        ``pair_overlap_pct`` (overlap of the standard pair) [%], ``multi_ray_factor`` [-].
    """
    ratio = np.asarray(height_ratio, dtype=np.float64)
    flown = np.asarray(FL.actual_overlap_pct(inp.forward_overlap_pct, 1.0, ratio),
                       dtype=np.float64)
    fraction = S.stereo_base_fraction(flown, rules.standard_forward_overlap_pct)
    multi = (S.strip_multi_ray_factor(flown, rules.standard_forward_overlap_pct)
             if rules.multi_ray == "strip" else np.ones_like(fraction))
    step = 1.0 - flown / 100.0
    return {"overlap_pct": flown, "base_to_height": fraction * inp.sensor_height_mm
            / inp.focal_mm, "base_in_steps": fraction / step,
            "pair_overlap_pct": 100.0 * (1.0 - fraction), "multi_ray_factor": multi}


def sigma_z_m(inp: UavInputs, rules: ScanRules, height_m: Any) -> NDArray[np.float64]:
    """Idealised stereo precision σ_Z at flown heights above ground ``height_m`` [m] with the
    mission's trigger distance (fixed in metres at the planned height ``inp.height_m``).

    σ_Z = (h/B)·(h/c)·σ_px·f with B and f from :func:`stereo_geometry` at the ratio
    h/H (docs/uav-models.md §9): at the highest flown height (H·(1 + tolerance)), over the
    lowest ground (H + relief) or both.

    Parameters
    ----------
    inp : UavInputs
        Camera, overlap and planned height.
    rules : ScanRules
        σ_px, standard overlap, multi-ray switch.
    height_m : array_like
        Heights above ground flown [m], > 0.

    Returns
    -------
    ndarray
        σ_Z [m], one standard deviation.
    """
    h = np.asarray(height_m, dtype=np.float64)
    geo = stereo_geometry(inp, rules, h / inp.height_m)
    return np.asarray(S.normal_case_height_error_m(
        h, geo["base_to_height"] * h, inp.focal_mm, inp.pixel_um,
        rules.image_measurement_px, geo["multi_ray_factor"]), dtype=np.float64)


def height_accuracy(inp: UavInputs, rules: ScanRules
                     ) -> tuple[float, Message, dict[str, Any]]:
    """The height constraint of a digital block: (GSD limit [m], reason, details).

    Three forms, each as the largest GSD on the ground (evaluated at Mc = 1):

    - ``normal_case`` (default for digital cameras): σ_Z = (H/B)·(H/c)·σ_px·f ≤ V_z (an
      RMS) at the highest flown height, B the standard pair's base at the overlap flown
      there with the mission's trigger distance (:func:`stereo_geometry`);
    - ``instruction`` and ``parallax``: the Instruction's P_Z and its parallax form with the
      single-step base b = l_y·(1 − p) and the processing loss k (seed 001, eq. 2).

    All three are in ``details["forms"]``; ``rules.digital_height_formula`` picks one.

    Parameters
    ----------
    inp : UavInputs
        Camera, flight and map (``relief_interval_m`` given).
    rules : ScanRules
        Normative parameters (V_z fraction, σ_px, standard overlap, multi-ray, the form).

    Returns
    -------
    ground limit [m], reason (a Message), details (dict)
    """
    assert inp.relief_interval_m is not None
    k = rules.processing_loss_k
    vz = rules.height_accuracy_fraction * inp.relief_interval_m
    up = 1.0 + inp.height_tolerance_up_pct / 100.0
    base_mm = F.photo_base_mm(inp.sensor_height_mm, inp.forward_overlap_pct)
    forms: dict[str, dict[str, float]] = {}
    for form in ("instruction", "parallax"):
        g = float(F.height_pixel_um(inp.relief_interval_m, 1.0, inp.focal_mm, base_mm,
                                    height_accuracy_fraction=rules.height_accuracy_fraction,
                                    processing_loss_k=k, method=form)) / 1e6  # type: ignore[arg-type]
        forms[form] = {"ground_limit_m": g}
    geo = stereo_geometry(inp, rules, np.array([1.0, up]))
    bh, multi = float(geo["base_to_height"][1]), float(geo["multi_ray_factor"][1])
    sigma = rules.image_measurement_px
    forms["normal_case"] = {"ground_limit_m": float(S.stereo_height_ground_limit_m(
        vz, bh, sigma, multi))}
    for v in forms.values():
        v["max_flown_height_m"] = float(PS.height_for_ground_pixel_m(v["ground_limit_m"],
                                                                     inp.pixel_um, inp.focal_mm))
        v["max_planned_height_m"] = v["max_flown_height_m"] / up
    formula = rules.digital_height_formula
    heights = inp.height_m * np.array([1.0, up])
    sz = S.normal_case_height_error_m(heights, geo["base_to_height"] * heights,
                                      inp.focal_mm, inp.pixel_um, sigma,
                                      geo["multi_ray_factor"])
    steps = float(geo["base_in_steps"][1])
    overlap = float(geo["pair_overlap_pct"][1])
    details: dict[str, Any] = {
        "formula": formula, "height_accuracy_m": vz,
        "height_accuracy_meaning": "RMS (one standard deviation) of the model heights",
        "model": "idealised stereo precision (image measurement only: no ground control, "
                 "calibration or surface errors)",
        "trigger_spacing_m": (1.0 - inp.forward_overlap_pct / 100.0)
        * float(PS.footprint_side_m(inp.sensor_height_mm, inp.height_m, inp.focal_mm)),
        "forward_overlap_at_highest_flown_height_pct": float(geo["overlap_pct"][1]),
        "stereo_base_steps": steps, "stereo_base_to_height": bh,
        "stereo_base_to_height_at_planned_height": float(geo["base_to_height"][0]),
        "stereo_overlap_pct": overlap,
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
                         steps=steps, overlap=overlap, sigma=sigma,
                         multi=Message("limit.PZ.multi", f=multi) if multi < 1.0 else None)
    else:
        reason = Message("limit.PZ", vz=vz, hc=inp.relief_interval_m, k=k,
                         formula=height_formula_name(formula))
    return forms[formula]["ground_limit_m"], reason, details



# --- P_P: graphic photo-plan (seed 001, eq. 3) ------------------------------------------

def _pp_pixel(rules: ScanRules, a: FilmArgs) -> NDArray[np.float64]:
    return F.photoplan_pixel_um(a.map_scale, a.photo_scale,
                                photoplan_resolution_mm=rules.photoplan_resolution_mm)


def _pp_reason(inp: ScanInputs, rules: ScanRules) -> Message:
    return Message("reason.PP", resolution=rules.photoplan_resolution_mm * 1000,
                   map=inp.map_scale)


def _pp_ground(inp: UavInputs, rules: ScanRules | None) -> DigitalLimit:
    assert rules is not None and inp.map_scale is not None
    g = _at_unit_scale_m(F.photoplan_pixel_um(
        inp.map_scale, 1.0, photoplan_resolution_mm=rules.photoplan_resolution_mm))
    return DigitalLimit(g, Message("limit.PP", resolution=rules.photoplan_resolution_mm * 1000,
                                   map=inp.map_scale), {})


# --- P_R: resolving power of the photo (seed 001, eq. 4); no digital counterpart ---------

def _pr_pixel(rules: ScanRules, a: FilmArgs) -> NDArray[np.float64]:
    return F.resolving_power_pixel_um(a.resolving_power_lpmm,
                                      pr_coefficient=rules.pr_coefficient)


def _pr_reason(inp: ScanInputs, rules: ScanRules) -> Message:
    return Message("reason.PR", r=inp.resolving_power_lpmm, kr=rules.pr_coefficient)


def _pr_details(inp: ScanInputs, rules: ScanRules, ctx: dict[str, Any], j: int
                ) -> dict[str, Any]:
    return {"pr_coefficient": rules.pr_coefficient,
            "resolving_power_lpmm": inp.resolving_power_lpmm}


# --- P_D: interpretation (seed 001, eqs. 5–7); digital: a limit on L ---------------------

def _pd_pixel(rules: ScanRules, a: FilmArgs) -> NDArray[np.float64]:
    return F.interpretation_pixel_um(
        np.asarray(a.object_size_m, dtype=np.float64) * 1000.0, a.photo_scale,
        a.shape_coefficient, rules.probability, pr_coefficient=rules.pr_coefficient,
        rounding=rules.recognition_rounding)  # type: ignore[arg-type]


def _pd_reason(inp: ScanInputs, rules: ScanRules) -> Message:
    obj = inp.object
    assert obj is not None
    return Message("reason.PD", obj.names(), b=obj.shape_coefficient, p=rules.probability)


def _pd_details(inp: ScanInputs, rules: ScanRules, ctx: dict[str, Any], j: int
                ) -> dict[str, Any]:
    obj = inp.object
    if obj is None:
        return {}
    return {"object": obj.name, "object_size_m": obj.size_m, "shape": obj.shape,
            "shape_coefficient": obj.shape_coefficient, "probability": rules.probability,
            "required_resolving_power_lpmm": float(ctx["r_needed"][j])}


def _pd_ground(inp: UavInputs, rules: ScanRules | None) -> DigitalLimit | None:
    assert rules is not None
    obj = inp.map_object
    if obj is None:
        return None
    root = float(F.probability_root(rules.probability, rules.recognition_rounding))  # type: ignore[arg-type]
    return DigitalLimit(obj.size_m * root / obj.shape_coefficient,
                        Message("limit.PD", obj.names(), p=rules.probability), {})


# --- UAV-only limits: a target GSD, the altitude ceiling (docs/uav-models.md §10) --------

def _gsd_ground(inp: UavInputs, rules: ScanRules | None) -> DigitalLimit | None:
    if inp.gsd_target_m is None:
        return None
    g = inp.gsd_target_m
    return DigitalLimit(g, Message("limit.GSD", gsd=g * 100.0), {})


def _hc_ground(inp: UavInputs, rules: ScanRules | None) -> DigitalLimit | None:
    if inp.ceiling_m is None:
        return None
    source = Message("ceiling.project" if inp.ceiling_from_project else "ceiling.norms")
    key = "limit.HC" if inp.ceiling_from_project else "limit.HC.below"
    return DigitalLimit(inp.ceiling_m, Message(key, ceiling=inp.ceiling_m, source=source),
                        {"from_project": inp.ceiling_from_project,
                         "strict": not inp.ceiling_from_project})


# --- GL: the largest GSD per plan scale of today's standard (ГОСТ Р 59562-2021, Table Б.1) --

def _gl_ground(inp: UavInputs, rules: ScanRules | None) -> DigitalLimit | None:
    if inp.gsd_limit_m is None or inp.map_scale is None:
        return None
    area = Message(f"gsd_area.{inp.gsd_limit_area}")
    return DigitalLimit(inp.gsd_limit_m,
                        Message("limit.GL", gsd=inp.gsd_limit_m * 100.0, map=inp.map_scale,
                                area=area),
                        {"area": inp.gsd_limit_area, "source": inp.gsd_limit_source})


BUILTIN: tuple[Constraint, ...] = (
    Constraint("PS", "planimetric accuracy", "точность в плане", Message("protects.PS"),
               Message("equation.PS"), True, "GSD", _ps_pixel, _ps_reason, None, _ps_ground),
    Constraint("PZ", "height accuracy", "точность по высоте", Message("protects.PZ"),
               Message("equation.PZ"), True, "GSD", _pz_pixel, _pz_reason, _pz_details,
               _pz_ground),
    Constraint("PP", "graphic photo-plan", "графический фотоплан", Message("protects.PP"),
               Message("equation.PP"), True, "GSD", _pp_pixel, _pp_reason, None, _pp_ground),
    Constraint("PR", "resolving power of the photo", "разрешающая способность снимка",
               Message("protects.PR"), Message("equation.PR"), False, "L", _pr_pixel,
               _pr_reason, _pr_details, None),
    Constraint("PD", "interpretation", "дешифрирование", Message("protects.PD"),
               Message("equation.PD"), True, "L", _pd_pixel, _pd_reason, _pd_details,
               _pd_ground),
    Constraint("GL", "GSD limit of the plan scale",
               "предельный размер пикселя на местности для масштаба плана",
               Message("protects.GL"), Message("equation.GL"), False, "GSD",
               ground_limit=_gl_ground),
    Constraint("GSD", "target GSD", "заданный размер пикселя на местности",
               Message("protects.GSD"), Message("equation.GSD"), False, "GSD",
               ground_limit=_gsd_ground, norm_switch=False, needs_map=False),
    Constraint("HC", "altitude ceiling", "предельная высота полёта", Message("protects.HC"),
               Message("equation.HC"), False, "H", ground_limit=_hc_ground,
               norm_switch=False, needs_map=False),
)
"""The built-in records, in the Instruction's order, then the UAV-only limits (the
registry, :mod:`scanplan.rules.registry`, holds them when it is imported)."""

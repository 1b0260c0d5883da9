"""The Python API: plan a film scan from names and numbers a surveyor knows.

>>> from scanplan import scan
>>> plan = scan(map_scale=2000, relief_interval_m=1.0, photo_scales=[10000],
...             camera="afa-te-100")
>>> plan.scenarios[0].binding, round(plan.scenarios[0].scan_pixel_um, 1)
('PR', 12.5)

Errors are :class:`scanplan.errors.InputError` whose ``field`` is the argument name.
"""

from __future__ import annotations

import os
from collections.abc import Iterable
from dataclasses import dataclass

from .errors import InputError
from .norms import DEFAULT_NORM_SET, NormSet, load_norm_set, parse_scale
from .normschema import PARAMETERS
from .planner import ObjectSpec, ScanInputs, ScanPlan, plan_scan

__all__ = ["ScanJob", "parse_frame_mm", "resolve_object", "scan"]


@dataclass(frozen=True)
class ScanJob:
    """A computed scan plan together with the norm set it used."""

    plan: ScanPlan
    norm_set: NormSet


def parse_frame_mm(text: object, field: str = "frame_mm") -> tuple[float, float]:
    """``"230x230"`` (across × along track, mm) → (230.0, 230.0)."""
    if isinstance(text, tuple | list) and len(text) == 2:
        parts = [str(x) for x in text]
    else:
        parts = str(text).lower().replace("×", "x").replace("*", "x").split("x")
    try:
        w, h = (float(p.strip().replace(",", ".")) for p in parts)
    except ValueError:
        raise InputError(
            field, f"must be WIDTHxHEIGHT in mm, e.g. 230x230 (got {text!r})") from None
    if not (w > 0 and h > 0 and w < float("inf") and h < float("inf")):
        raise InputError(field, f"sides must be finite numbers > 0 mm (got {text!r})")
    return w, h


def resolve_object(
    ns: NormSet,
    map_scale: float,
    *,
    object_size_m: float | None = None,
    shape: str | None = None,
) -> ObjectSpec | None:
    """The object the interpretation constraint protects.

    The user's size wins; otherwise the norm set's smallest object for exactly this map
    scale (seed 001 Table 3). With neither, None (the engine then asks for a size if P_D is
    enabled — never a guess).
    """
    norm_obj = ns.object_for(map_scale)
    if object_size_m is not None:
        shape_id = shape or (norm_obj.shape if norm_obj else ns.parameters["shape"])
        coef = ns.shape_coefficient(shape_id, "shape")
        return ObjectSpec("object", float(object_size_m), shape_id, coef, "object_size_m")
    if norm_obj is None:
        return None
    shape_id = shape or norm_obj.shape
    coef = ns.shape_coefficient(shape_id, "shape")
    return ObjectSpec(norm_obj.name, norm_obj.size_m, shape_id, coef,
                      f"norm set {ns.name}, table objects, 1:{norm_obj.map_scale} "
                      f"({norm_obj.source})")


def scan_job(
    *,
    map_scale: object,
    relief_interval_m: float,
    photo_scales: Iterable[object],
    camera: str | None = None,
    focal_mm: float | None = None,
    frame_mm: object | None = None,
    resolving_power_lpmm: float | None = None,
    forward_overlap_pct: float | None = None,
    norms: str | os.PathLike[str] = DEFAULT_NORM_SET,
    object_size_m: float | None = None,
    shape: str | None = None,
    probability: float | None = None,
    height_formula: str | None = None,
    pr_coefficient: float | None = None,
    recognition_rounding: str | None = None,
    scanner: str | None = None,
    bands: int = 1,
    bits_per_band: int = 8,
    pixel_um: Iterable[float] = (),
) -> ScanJob:
    """Like :func:`scan`, returning the norm set too (for reports)."""
    ns = load_norm_set(norms)
    mk = parse_scale(map_scale, "map_scale")
    scales = tuple(parse_scale(s, "photo_scale") for s in photo_scales)
    if camera:
        cam = ns.camera(camera, "camera")
        f = focal_mm if focal_mm is not None else cam.focal_mm
        w, h = (parse_frame_mm(frame_mm) if frame_mm is not None
                else (cam.sensor_width_mm, cam.sensor_height_mm))
        r = resolving_power_lpmm if resolving_power_lpmm is not None else cam.resolving_power_lpmm
    else:
        if focal_mm is None or frame_mm is None:
            raise InputError("camera", "give a catalogue camera id, or both the focal length "
                             "and the frame size (scanplan cameras list)")
        f = focal_mm
        w, h = parse_frame_mm(frame_mm)
        r = resolving_power_lpmm
    if r is None:
        raise InputError("resolving_power_lpmm", "the photo's resolving power R is needed "
                         "(lines/mm > 0, typically 25–60 for aerial film)")
    overrides = {"probability": probability, "height_formula": height_formula,
                 "pr_coefficient": pr_coefficient, "recognition_rounding": recognition_rounding}
    for key, value in overrides.items():
        if value is not None:
            problem = None
            try:
                problem = PARAMETERS[key].value.check(value)
            except (TypeError, ValueError):
                problem = f"must be {PARAMETERS[key].value.describe()}"
            if problem:
                raise InputError(key, f"{problem} (got {value!r})")
    rules = ns.rules(**overrides)
    obj = resolve_object(ns, mk, object_size_m=object_size_m, shape=shape)
    steps = ns.scanner_steps(scanner, "scanner") if scanner else ()
    overlap = (forward_overlap_pct if forward_overlap_pct is not None
               else rules.standard_forward_overlap_pct)
    inputs = ScanInputs(
        map_scale=mk, relief_interval_m=relief_interval_m, photo_scales=scales, focal_mm=f,
        frame_width_mm=w, frame_along_mm=h, resolving_power_lpmm=r,
        forward_overlap_pct=overlap, object=obj, camera=camera or "", scanner=scanner or "",
        scanner_steps_um=steps, bands=bands, bits_per_band=bits_per_band,
        candidate_pixels_um=tuple(pixel_um))
    return ScanJob(plan_scan(inputs, rules), ns)


def scan(**kwargs: object) -> ScanPlan:
    """Plan the scanning of film photos for a map: every constraint at each photo scale.

    Parameters
    ----------
    map_scale : int, float or str
        Map scale denominator Mk (``2000`` or ``"1:2000"``).
    relief_interval_m : float
        Relief (contour) interval h_c [m].
    photo_scales : iterable
        Photo scale denominators Mc to evaluate.
    camera : str, optional
        Catalogue camera id (``scanplan cameras list``); or give ``focal_mm`` and
        ``frame_mm`` (``"230x230"``, across × along track).
    resolving_power_lpmm : float, optional
        R of the photos [lines/mm] (default: the camera's catalogue value).
    forward_overlap_pct : float, optional
        Forward overlap [%] (default: the norm set's standard, 60 %).
    norms : str or path
        Norm set name or folder (default ``gkinp-02-036-02``).
    object_size_m, shape, probability : optional
        The object to interpret (default: the norm set's smallest object for the map scale).
    height_formula, pr_coefficient, recognition_rounding : optional
        Norm parameter overrides.
    scanner : str, optional
        Scanner id: round the scan pixel down to its steps.
    bands, bits_per_band : int
        For the data volume of a scanned frame.
    pixel_um : iterable of float
        Scan pixels [µm] to answer "what is the largest photo scale this pixel supports"
        (the scanner's steps are always answered).

    Returns
    -------
    ScanPlan
    """
    return scan_job(**kwargs).plan  # type: ignore[arg-type]
